/* Frame sequences: lists, names, shares, claims and stale temp files. */
#include "app/sequence.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "dirt/file.h"

#define MAX_FRAME 10000000L
/* The longest file name (NAME_MAX of Linux file systems). */
#define SEQ_NAME_MAX 255
#define MAX_FRAMES 1000000L

/* A whole non-negative integer at *p, advancing it. */
static bool number(const char **p, long *out)
{
    const char *s = *p;
    if (*s < '0' || *s > '9')
        return false;
    long v = 0;
    while (*s >= '0' && *s <= '9') {
        v = v * 10 + (*s - '0');
        if (v > MAX_FRAME)
            return false;
        s++;
    }
    *p = s;
    *out = v;
    return true;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return x < y ? -1 : x > y;
}

static bool add_range(seq_frames *f, size_t *cap, long a, long b, long step)
{
    for (long v = a; v <= b; v += step) {
        if (f->count >= (size_t)MAX_FRAMES)
            return false;
        if (f->count == *cap) {
            size_t n = *cap ? 2 * *cap : 64;
            long *grown = realloc(f->frames, n * sizeof(*grown));
            if (!grown)
                return false;
            f->frames = grown;
            *cap = n;
        }
        f->frames[f->count++] = v;
    }
    return true;
}

bool seq_frames_parse(const char *text, seq_frames *out, char *why, size_t size)
{
    *out = (seq_frames){0};
    size_t cap = 0;
    const char *p = text ? text : "";
    long a, b, step = 1;
    if (strchr(p, ':')) {
        /* A:B[:step] */
        if (!number(&p, &a) || *p++ != ':' || !number(&p, &b) ||
            (*p == ':' && (p++, !number(&p, &step) || step < 1)) || *p) {
            snprintf(why, size, "expects A:B[:step] or a list such as 1,5,10-20, got '%s'",
                     text);
            return false;
        }
        if (b < a) {
            snprintf(why, size, "'%s': last frame before first", text);
            return false;
        }
        if (!add_range(out, &cap, a, b, step))
            goto too_many;
        return true;
    }
    while (*p) {
        if (!number(&p, &a)) {
            snprintf(why, size, "expects A:B[:step] or a list such as 1,5,10-20, got '%s'", text);
            goto error;
        }
        b = a;
        if (*p == '-') {
            p++;
            if (!number(&p, &b) || b < a) {
                snprintf(why, size, "'%s': a range must read A-B with A <= B", text);
                goto error;
            }
        }
        if (!add_range(out, &cap, a, b, 1))
            goto too_many;
        if (*p == ',' && p[1])
            p++;
        else if (*p) {
            snprintf(why, size, "expects A:B[:step] or a list such as 1,5,10-20, got '%s'", text);
            goto error;
        }
    }
    if (!out->count) {
        snprintf(why, size, "no frames in '%s'", text);
        goto error;
    }
    qsort(out->frames, out->count, sizeof(long), cmp_long);
    size_t n = 1;
    for (size_t i = 1; i < out->count; i++) {
        if (out->frames[i] != out->frames[n - 1])
            out->frames[n++] = out->frames[i];
    }
    out->count = n;
    return true;
too_many:
    snprintf(why, size, "'%s': more than %ld frames (or out of memory)", text, MAX_FRAMES);
error:
    seq_frames_free(out);
    return false;
}

void seq_frames_free(seq_frames *f)
{
    free(f->frames);
    *f = (seq_frames){0};
}

bool seq_frames_chunk(seq_frames *f, long k, long n, char *why, size_t size)
{
    if (n < 1 || k < 1 || k > n) {
        snprintf(why, size, "share %ld of %ld: expects K/N with 1 <= K <= N", k, n);
        return false;
    }
    /* Share k covers [floor((k-1) c / n), floor(k c / n)). */
    size_t c = f->count;
    size_t first = (size_t)((unsigned long long)(k - 1) * c / (unsigned long long)n);
    size_t last = (size_t)((unsigned long long)k * c / (unsigned long long)n);
    memmove(f->frames, f->frames + first, (last - first) * sizeof(long));
    f->count = last - first;
    return true;
}

static bool env_long(const char *name, long *out)
{
    const char *v = getenv(name);
    if (!v || !*v)
        return false;
    char *end;
    errno = 0;
    long x = strtol(v, &end, 10);
    if (errno || *end)
        return false;
    *out = x;
    return true;
}

bool seq_slurm_share(long *k, long *n, char *why, size_t size)
{
    long id, count, min = 0;
    if (!env_long("SLURM_ARRAY_TASK_ID", &id) || !env_long("SLURM_ARRAY_TASK_COUNT", &count)) {
        snprintf(why, size, "SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are not set "
                            "(not inside a Slurm job array?)");
        return false;
    }
    env_long("SLURM_ARRAY_TASK_MIN", &min);
    long step = 1;
    env_long("SLURM_ARRAY_TASK_STEP", &step);
    if (step < 1)
        step = 1;
    *k = (id - min) / step + 1;
    *n = count;
    if (*k < 1 || *k > *n) {
        snprintf(why, size, "Slurm task %ld (min %ld, step %ld) is not one of %ld tasks", id, min,
                 step, count);
        return false;
    }
    return true;
}

/* ---- names ---- */

int seq_pattern_fields(const char *pattern)
{
    int fields = 0;
    for (const char *p = pattern; *p; p++) {
        if (*p == '#') {
            int width = 1;
            while (p[1] == '#')
                p++, width++;
            if (width > SEQ_MAX_FIELD_WIDTH)
                return -1;
            fields++;
        } else if (*p == '%') {
            if (p[1] == '%') {
                p++;
                continue;
            }
            p++;
            if (*p == '0')
                p++;
            int digits = 0, width = 0;
            while (*p >= '0' && *p <= '9') {
                if (++digits > 2)
                    return -1; /* (also keeps the width from overflowing) */
                width = width * 10 + (*p - '0');
                p++;
            }
            if (*p != 'd' || width > SEQ_MAX_FIELD_WIDTH)
                return -1;
            fields++;
        }
    }
    return fields > 1 ? -1 : fields;
}

void seq_frame_path(const char *pattern, long frame, char *buf, size_t size)
{
    size_t o = 0;
    for (const char *p = pattern; *p && o + 1 < size; p++) {
        if (*p == '#') {
            int width = 0;
            while (p[width] == '#')
                width++;
            int n = snprintf(buf + o, size - o, "%0*ld", width < SEQ_MAX_FIELD_WIDTH ? width
                                                                            : SEQ_MAX_FIELD_WIDTH,
                             frame);
            o += n > 0 ? (size_t)n : 0;
            p += width - 1;
        } else if (*p == '%' && p[1] == '%') {
            buf[o++] = '%';
            p++;
        } else if (*p == '%') {
            /* %[0][width]d */
            const char *q = p + 1;
            bool zero = *q == '0';
            if (zero)
                q++;
            int width = 0;
            while (*q >= '0' && *q <= '9') {
                if (width < SEQ_MAX_FIELD_WIDTH)
                    width = width * 10 + (*q - '0');
                q++;
            }
            if (width > SEQ_MAX_FIELD_WIDTH)
                width = SEQ_MAX_FIELD_WIDTH;
            int n = snprintf(buf + o, size - o, zero ? "%0*ld" : "%*ld", width, frame);
            o += n > 0 ? (size_t)n : 0;
            p = q; /* at the 'd' */
        } else {
            buf[o++] = *p;
        }
        if (o >= size)
            o = size - 1;
    }
    buf[o < size ? o : size - 1] = '\0';
}

/* The directories this process made (seq_remove_made_dirs), in order. */
static char **made_dirs;
static size_t num_made_dirs;

static void remember_dir(const char *dir)
{
    char **grown = realloc(made_dirs, (num_made_dirs + 1) * sizeof(char *));
    if (!grown)
        return;
    made_dirs = grown;
    if ((made_dirs[num_made_dirs] = strdup(dir)) != NULL)
        num_made_dirs++;
}

void seq_remove_made_dirs(void)
{
    while (num_made_dirs > 0) {
        char *d = made_dirs[--num_made_dirs];
        rmdir(d); /* only when empty: what was completed in it stays */
        free(d);
    }
    free(made_dirs);
    made_dirs = NULL;
}

void seq_forget_made_dirs(void)
{
    for (size_t i = 0; i < num_made_dirs; i++)
        free(made_dirs[i]);
    free(made_dirs);
    made_dirs = NULL;
    num_made_dirs = 0;
}

bool seq_make_parent_dirs(const char *path, char *why, size_t size)
{
    char dir[4200];
    snprintf(dir, sizeof(dir), "%s", path);
    char *slash = strrchr(dir, '/');
    if (!slash || slash == dir)
        return true;
    *slash = '\0';
    for (char *p = dir + 1;; p++) {
        bool end = *p == '\0';
        if (*p == '/' || end) {
            *p = '\0';
            if (mkdir(dir, 0777) == 0) {
                remember_dir(dir);
            } else if (errno != EEXIST) {
                snprintf(why, size, "cannot create directory '%s': %s", dir, strerror(errno));
                return false;
            }
            struct stat st;
            if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
                snprintf(why, size, "'%s' is not a directory", dir);
                return false;
            }
            if (end)
                break;
            *p = '/';
        }
    }
    return true;
}

bool seq_complete(const char *const *paths, int count)
{
    for (int i = 0; i < count; i++) {
        struct stat st;
        if (stat(paths[i], &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0)
            return false;
    }
    return count > 0;
}

/* ---- claims ---- */

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_REALTIME, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* The newest claim generation of `frame_file` (-1 when none) and its age. */
static long newest_claim(const char *frame_file, double *age)
{
    long g = -1;
    char path[4300];
    for (long i = 0; i < 1000000; i++) {
        snprintf(path, sizeof(path), "%s.claim.%ld", frame_file, i);
        struct stat st;
        if (stat(path, &st) != 0)
            break;
        g = i;
        *age = now_s() - ((double)st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9);
    }
    return g;
}

/* This host's name, as claims and temporary files write it. */
static void host_name(char *host, size_t size)
{
    snprintf(host, size, "?");
    if (gethostname(host, size - 1) != 0)
        snprintf(host, size, "?");
    host[size - 1] = '\0';
}

/* True when claim generation `g` of `frame_file` names this host and a
 * process that no longer exists: its worker died (a claim of another host
 * is judged by its age alone, doc/farm.md). */
static bool claim_of_dead_local_worker(const char *frame_file, long g)
{
    char path[4300], line[256], host[128];
    snprintf(path, sizeof(path), "%s.claim.%ld", frame_file, g);
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    bool got = fgets(line, sizeof(line), f) != NULL;
    fclose(f);
    char claim_host[130];
    long pid = 0;
    if (!got || sscanf(line, "%129s %ld", claim_host, &pid) != 2 || pid <= 0)
        return false;
    host_name(host, sizeof(host));
    return strcmp(claim_host, host) == 0 && pid != (long)getpid() &&
           kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

static int claim_slot = -1;

bool seq_claim_take(const char *frame_file, double timeout_s, seq_claim *c, char *why,
                    size_t size)
{
    *c = (seq_claim){0};
    why[0] = '\0';
    for (int attempt = 0; attempt < 16; attempt++) {
        double age = 0;
        long g = newest_claim(frame_file, &age);
        if (g >= 0 && age < timeout_s && !claim_of_dead_local_worker(frame_file, g))
            return false; /* another worker holds it */
        /* No claim, or the newest is stale: make the next generation. */
        snprintf(c->path, sizeof(c->path), "%s.claim.%ld", frame_file, g + 1);
        /* No signal between making the claim and registering it for
         * removal (dirt_cleanup_add): a SIGTERM there would leave it. */
        dirt_cleanup_hold();
        int fd = open(c->path, O_WRONLY | O_CREAT | O_EXCL, 0644);
        if (fd >= 0)
            claim_slot = dirt_cleanup_add(c->path);
        dirt_cleanup_release();
        if (fd < 0) {
            if (errno == EEXIST)
                continue; /* another worker made it first: look again */
            snprintf(why, size, "cannot claim '%s': %s", frame_file, strerror(errno));
            return false;
        }
        char host[128];
        host_name(host, sizeof(host));
        char line[256];
        int n = snprintf(line, sizeof(line), "%s %ld\n", host, (long)getpid());
        bool ok = write(fd, line, (size_t)n) == n;
        close(fd);
        if (!ok) {
            unlink(c->path);
            dirt_cleanup_remove(claim_slot);
            claim_slot = -1;
            snprintf(why, size, "cannot write the claim '%s'", c->path);
            return false;
        }
        c->held = true;
        return true;
    }
    snprintf(why, size, "cannot claim '%s': too many workers racing", frame_file);
    return false;
}

void seq_claim_touch(seq_claim *c)
{
    static double last;
    double t = now_s();
    if (!c || !c->held || t - last < 1.0)
        return;
    last = t;
    utimensat(AT_FDCWD, c->path, NULL, 0);
}

void seq_claim_release(seq_claim *c, const char *frame_file, bool frame_done)
{
    if (!c->held)
        return;
    /* Removed before it leaves the signal cleanup list. */
    if (frame_done) {
        double age;
        long g = newest_claim(frame_file, &age);
        char path[4300];
        for (long i = 0; i <= g; i++) {
            snprintf(path, sizeof(path), "%s.claim.%ld", frame_file, i);
            unlink(path);
        }
    } else {
        unlink(c->path);
    }
    dirt_cleanup_remove(claim_slot);
    claim_slot = -1;
    c->held = false;
}

/* ---- stale temporary files ---- */

/* Length of the constant text of `base` (a file name) before and after its
 * frame field. */
static void field_bounds(const char *base, size_t *before, size_t *after)
{
    size_t n = strlen(base), i = 0;
    while (i < n && base[i] != '#' && !(base[i] == '%' && base[i + 1] != '%'))
        i++;
    *before = i;
    *after = 0;
    if (i == n)
        return;
    size_t j = i + 1;
    if (base[i] == '#') {
        while (base[j] == '#')
            j++;
    } else {
        while (base[j] && base[j] != 'd')
            j++;
        j += base[j] == 'd';
    }
    *after = n - j;
}

int seq_clean_stale_temps(const char *pattern, long frame, double timeout_s)
{
    char file[4200], dir[4200];
    seq_frame_path(pattern, frame, file, sizeof(file));
    snprintf(dir, sizeof(dir), "%s", file);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof(dir), ".");
    const char *pbase = strrchr(pattern, '/') ? strrchr(pattern, '/') + 1 : pattern;
    size_t before, after;
    field_bounds(pbase, &before, &after);
    size_t plen = strlen(pbase);
    char host[65] = "host";
    gethostname(host, sizeof(host) - 1);
    for (char *h = host; *h; h++) {
        if (*h == '/' || *h == '.')
            *h = '-';
    }
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int removed = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        /* NAME.tmp.HOST.PID.XXXXXX where NAME is a file the pattern makes:
         * its constant text before and after the frame field (or, for a
         * pattern without one, the name itself). */
        const char *tmp = strstr(e->d_name, ".tmp.");
        if (!tmp)
            continue;
        size_t name = (size_t)(tmp - e->d_name);
        /* A temporary name at the longest a name may be had its target's
         * name cut (dirt/file.h): only the start of the name can match. */
        bool cut = strlen(e->d_name) >= SEQ_NAME_MAX;
        size_t lead = name < before ? name : before;
        if (cut ? strncmp(e->d_name, pbase, lead) != 0
                : name < before + after || strncmp(e->d_name, pbase, before) != 0 ||
                      strncmp(e->d_name + name - after, pbase + plen - after, after) != 0 ||
                      (before == plen && name != plen))
            continue;
        char path[8600];
        snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
        /* HOST.PID.XXXXXX after ".tmp." */
        const char *rest = tmp + 5;
        const char *dot = strchr(rest, '.');
        bool dead = false;
        if (dot && (size_t)(dot - rest) == strlen(host) && !strncmp(rest, host, strlen(host))) {
            long pid = strtol(dot + 1, NULL, 10);
            dead = pid > 0 && kill((pid_t)pid, 0) != 0 && errno == ESRCH;
        } else {
            struct stat st;
            dead = stat(path, &st) == 0 &&
                   now_s() - ((double)st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9) > timeout_s;
        }
        if (dead && unlink(path) == 0)
            removed++;
    }
    closedir(d);
    return removed;
}
