/* Bounded reading of input files, confinement of paths, and a run's inputs
 * kept apart from its outputs. Contracts in dirt/input.h. */
#define _XOPEN_SOURCE 700 /* realpath(3) */
#include "dirt/input.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dirt/log.h"

static const char *const error_names[] = {
#define DIRT_INPUT_ERR_NAME_(id, msg) #id,
    DIRT_INPUT_ERRORS(DIRT_INPUT_ERR_NAME_)
#undef DIRT_INPUT_ERR_NAME_
};
static const char *const error_strs[] = {
#define DIRT_INPUT_ERR_STR_(id, msg) msg,
    DIRT_INPUT_ERRORS(DIRT_INPUT_ERR_STR_)
#undef DIRT_INPUT_ERR_STR_
};

const char *dirt_input_error_name(enum dirt_input_error e)
{
    return (unsigned)e < DIRT_INPUT_NUM_ERRORS ? error_names[e] : "?";
}

const char *dirt_input_error_str(enum dirt_input_error e)
{
    return (unsigned)e < DIRT_INPUT_NUM_ERRORS ? error_strs[e] : "?";
}

/* ---- bounded reading ---- */

int dirt_input_open(const char *path, size_t max_bytes, size_t *size, enum dirt_input_error *err)
{
    enum dirt_input_error dummy;
    if (!err)
        err = &dummy;
    *err = DIRT_INPUT_ERR_IO;
    if (!path || !*path) {
        errno = EINVAL;
        return -1;
    }
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT || errno == ENOTDIR)
            *err = DIRT_INPUT_ERR_MISSING;
        return -1;
    }
    struct stat st;
    int saved;
    if (fstat(fd, &st) != 0)
        goto fail;
    if (!S_ISREG(st.st_mode)) {
        *err = DIRT_INPUT_ERR_NOT_REGULAR;
        errno = S_ISDIR(st.st_mode) ? EISDIR : EINVAL;
        goto fail;
    }
    if (st.st_size < 0 || (uint64_t)st.st_size > (uint64_t)SIZE_MAX - 1 ||
        (max_bytes && (uint64_t)st.st_size > (uint64_t)max_bytes)) {
        *err = DIRT_INPUT_ERR_TOO_LARGE;
        errno = EFBIG;
        goto fail;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0)
        goto fail;
    if (size)
        *size = (size_t)st.st_size;
    *err = DIRT_INPUT_ERR_OK;
    return fd;
fail:
    saved = errno;
    close(fd);
    errno = saved;
    return -1;
}

void *dirt_input_read(const char *path, size_t max_bytes, size_t *size,
                      enum dirt_input_error *err)
{
    enum dirt_input_error dummy;
    if (!err)
        err = &dummy;
    size_t n = 0;
    int fd = dirt_input_open(path, max_bytes, &n, err);
    if (fd < 0)
        return NULL;
    unsigned char *data = malloc(n + 1);
    if (!data) {
        *err = DIRT_INPUT_ERR_TOO_LARGE;
        close(fd);
        errno = ENOMEM;
        return NULL;
    }
    size_t got = 0;
    while (got < n) {
        ssize_t r = read(fd, data + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0) {
            int saved = r < 0 ? errno : EIO;
            *err = r < 0 ? DIRT_INPUT_ERR_IO : DIRT_INPUT_ERR_TRUNCATED;
            free(data);
            close(fd);
            errno = saved;
            return NULL;
        }
        got += (size_t)r;
    }
    close(fd);
    data[n] = 0;
    if (size)
        *size = n;
    *err = DIRT_INPUT_ERR_OK;
    return data;
}

/* ---- paths ---- */

/* `path` made absolute (the working directory in front of a relative one),
 * malloc'd; NULL when out of memory or the working directory is unknown. */
static char *absolute(const char *path)
{
    if (path[0] == '/')
        return strdup(path);
    char cwd[PATH_MAX];
    if (!getcwd(cwd, sizeof(cwd)))
        return NULL;
    size_t n = strlen(cwd) + strlen(path) + 2;
    char *a = malloc(n);
    if (a)
        snprintf(a, n, "%s/%s", cwd, path);
    return a;
}

/* Appends the components of `rest` to the absolute path in `out` (of
 * `cap` bytes), "." skipped and ".." taking one off (never above "/").
 * False when it does not fit. */
static bool append_lexical(char *out, size_t cap, const char *rest)
{
    size_t len = strlen(out);
    const char *p = rest;
    while (*p) {
        while (*p == '/')
            p++;
        if (!*p)
            break;
        const char *e = strchr(p, '/');
        size_t k = e ? (size_t)(e - p) : strlen(p);
        if (k == 1 && p[0] == '.') {
            /* nothing */
        } else if (k == 2 && p[0] == '.' && p[1] == '.') {
            while (len > 1 && out[len - 1] != '/')
                len--;
            if (len > 1)
                len--; /* the slash, unless it is the root */
            out[len] = 0;
        } else {
            if (len + 1 + k + 1 > cap)
                return false;
            if (len > 1 || out[0] != '/')
                out[len++] = '/';
            memcpy(out + len, p, k);
            len += k;
            out[len] = 0;
        }
        p += k;
    }
    return true;
}

/* The real path of `path` as far as it exists: realpath of its longest
 * existing leading part, the rest of its components appended as written
 * ("." and ".." taken lexically). malloc'd; NULL when out of memory. */
static char *resolve(const char *path)
{
    char *abs = absolute(path);
    if (!abs)
        return NULL;
    size_t n = strlen(abs);
    char *out = NULL;
    /* Cut components off the end until realpath succeeds ("/" always does). */
    for (size_t cut = n;;) {
        char saved = abs[cut];
        abs[cut] = 0;
        char *real = realpath(cut ? abs : "/", NULL);
        abs[cut] = saved;
        if (real) {
            size_t cap = strlen(real) + (n - cut) + 2;
            out = malloc(cap);
            if (out) {
                snprintf(out, cap, "%s", real);
                if (!append_lexical(out, cap, abs + cut)) {
                    free(out);
                    out = NULL;
                }
            }
            free(real);
            break;
        }
        if (cut == 0)
            break;
        /* the previous slash */
        size_t c = cut;
        while (c > 0 && abs[c - 1] == '/')
            c--;
        while (c > 0 && abs[c - 1] != '/')
            c--;
        while (c > 1 && abs[c - 1] == '/')
            c--;
        cut = c;
    }
    free(abs);
    return out;
}

/* True when `path` is `dir` or lies under it (both resolved). */
static bool under(const char *dir, const char *path)
{
    size_t n = strlen(dir);
    if (n == 1 && dir[0] == '/')
        return true;
    return strncmp(path, dir, n) == 0 && (path[n] == '/' || path[n] == 0);
}

bool dirt_input_inside(const char *dir, const char *path)
{
    if (!dir || !path)
        return false;
    char *real_dir = realpath(*dir ? dir : ".", NULL);
    char *real = real_dir ? resolve(path) : NULL;
    bool in = real && under(real_dir, real);
    free(real);
    free(real_dir);
    return in;
}

/* ---- a run's inputs and outputs ---- */

typedef struct run_file {
    char *path;    /* as given */
    char *real;    /* resolve()d */
    char *what;
    bool have_id;  /* dev/ino valid (the file exists) */
    dev_t dev;
    ino_t ino;
    bool dir;      /* an output folder: files `prefix`* in it */
    char *prefix;
} run_file;

struct dirt_run_files {
    run_file *in, *out;
    size_t num_in, num_out, cap_in, cap_out;
};

dirt_run_files *dirt_run_files_create(void)
{
    dirt_run_files *f = calloc(1, sizeof(*f));
    if (!f)
        DIRT_ERROR("out of memory");
    return f;
}

static void free_file(run_file *r)
{
    free(r->path);
    free(r->real);
    free(r->what);
    free(r->prefix);
}

void dirt_run_files_destroy(dirt_run_files *f)
{
    if (!f)
        return;
    for (size_t i = 0; i < f->num_in; i++)
        free_file(&f->in[i]);
    for (size_t i = 0; i < f->num_out; i++)
        free_file(&f->out[i]);
    free(f->in);
    free(f->out);
    free(f);
}

/* A new zeroed entry at the end of *list, NULL when out of memory. */
static run_file *push(run_file **list, size_t *num, size_t *cap)
{
    if (*num == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        run_file *grown = realloc(*list, c * sizeof(run_file));
        if (!grown)
            return NULL;
        *list = grown;
        *cap = c;
    }
    run_file *r = &(*list)[(*num)++];
    memset(r, 0, sizeof(*r));
    return r;
}

static bool fill(run_file *r, const char *path, const char *what)
{
    r->path = strdup(path);
    r->what = strdup(what ? what : "");
    r->real = resolve(path);
    struct stat st;
    if (stat(path, &st) == 0) {
        r->have_id = true;
        r->dev = st.st_dev;
        r->ino = st.st_ino;
    }
    return r->path && r->what && r->real;
}

bool dirt_run_files_input(dirt_run_files *f, const char *path, const char *what)
{
    struct stat st;
    if (!f || !path || !*path || stat(path, &st) != 0)
        return true;
    for (size_t i = 0; i < f->num_in; i++) {
        if (f->in[i].dev == st.st_dev && f->in[i].ino == st.st_ino)
            return true; /* already known (the first role is kept) */
    }
    run_file *r = push(&f->in, &f->num_in, &f->cap_in);
    if (!r || !fill(r, path, what)) {
        DIRT_ERROR("out of memory");
        return false;
    }
    return true;
}

/* The base name of a resolved path. */
static const char *base_name(const char *real)
{
    const char *s = strrchr(real, '/');
    return s ? s + 1 : real;
}

/* Whether output `o` is input `in`; the reason in `why`. */
static bool collides(const run_file *o, const run_file *in, char *why, size_t size)
{
    if (o->dir) {
        size_t n = strlen(o->real);
        const char *name = base_name(in->real);
        bool inside = strncmp(in->real, o->real, n) == 0 && in->real[n] == '/' &&
                      strchr(in->real + n + 1, '/') == NULL;
        if (!inside || strncmp(name, o->prefix, strlen(o->prefix)) != 0)
            return false;
        snprintf(why, size, "%s '%s' would write '%s*' files over the input '%s' (%s)", o->what,
                 o->path, o->prefix, in->path, in->what);
        return true;
    }
    bool same = (o->have_id && in->have_id && o->dev == in->dev && o->ino == in->ino) ||
                strcmp(o->real, in->real) == 0;
    if (!same)
        return false;
    if (strcmp(o->path, in->path) == 0)
        snprintf(why, size, "the output '%s' (%s) is the input %s", o->path, o->what, in->what);
    else
        snprintf(why, size, "the output '%s' (%s) is the input '%s' (%s)%s", o->path, o->what,
                 in->path, in->what,
                 strcmp(o->real, in->real) == 0 ? "" : ": the same file by another name (a link)");
    return true;
}

static enum dirt_input_error add_output(dirt_run_files *f, const char *path, const char *what,
                                        const char *prefix, char *why, size_t size)
{
    char dummy[8];
    if (!why) {
        why = dummy;
        size = sizeof(dummy);
    }
    why[0] = 0;
    if (!f || !path || !*path)
        return DIRT_INPUT_ERR_OK;
    run_file *r = push(&f->out, &f->num_out, &f->cap_out);
    if (!r || !fill(r, path, what) || (prefix && !(r->prefix = strdup(prefix)))) {
        snprintf(why, size, "out of memory");
        return DIRT_INPUT_ERR_IO;
    }
    r->dir = prefix != NULL;
    for (size_t i = 0; i < f->num_in; i++) {
        if (collides(r, &f->in[i], why, size))
            return DIRT_INPUT_ERR_COLLISION;
    }
    return DIRT_INPUT_ERR_OK;
}

enum dirt_input_error dirt_run_files_output(dirt_run_files *f, const char *path, const char *what,
                                            char *why, size_t size)
{
    return add_output(f, path, what, NULL, why, size);
}

enum dirt_input_error dirt_run_files_output_dir(dirt_run_files *f, const char *dir,
                                                const char *prefix, const char *what, char *why,
                                                size_t size)
{
    return add_output(f, dir, what, prefix ? prefix : "", why, size);
}

static int cmp_real(const void *a, const void *b)
{
    const run_file *x = *(const run_file *const *)a, *y = *(const run_file *const *)b;
    return strcmp(x->real, y->real);
}

enum dirt_input_error dirt_run_files_check(dirt_run_files *f, char *why, size_t size)
{
    char dummy[8];
    if (!why) {
        why = dummy;
        size = sizeof(dummy);
    }
    why[0] = 0;
    if (!f)
        return DIRT_INPUT_ERR_OK;
    for (size_t o = 0; o < f->num_out; o++) {
        for (size_t i = 0; i < f->num_in; i++) {
            if (collides(&f->out[o], &f->in[i], why, size))
                return DIRT_INPUT_ERR_COLLISION;
        }
    }
    /* Files against files by name (sorted: O(n log n) for a long range),
     * then files against the output folders. */
    run_file **sorted = malloc((f->num_out ? f->num_out : 1) * sizeof(*sorted));
    if (!sorted) {
        snprintf(why, size, "out of memory");
        return DIRT_INPUT_ERR_IO;
    }
    size_t n = 0;
    for (size_t o = 0; o < f->num_out; o++) {
        if (!f->out[o].dir)
            sorted[n++] = &f->out[o];
    }
    qsort(sorted, n, sizeof(*sorted), cmp_real);
    enum dirt_input_error e = DIRT_INPUT_ERR_OK;
    for (size_t k = 1; k < n && !e; k++) {
        if (strcmp(sorted[k - 1]->real, sorted[k]->real) == 0) {
            snprintf(why, size, "the outputs '%s' (%s) and '%s' (%s) are the same file",
                     sorted[k - 1]->path, sorted[k - 1]->what, sorted[k]->path, sorted[k]->what);
            e = DIRT_INPUT_ERR_COLLISION;
        }
    }
    for (size_t d = 0; d < f->num_out && !e; d++) {
        if (!f->out[d].dir)
            continue;
        for (size_t k = 0; k < n && !e; k++) {
            if (collides(&f->out[d], sorted[k], why, size)) {
                snprintf(why, size, "%s '%s' would write '%s*' files over the output '%s' (%s)",
                         f->out[d].what, f->out[d].path, f->out[d].prefix, sorted[k]->path,
                         sorted[k]->what);
                e = DIRT_INPUT_ERR_COLLISION;
            }
        }
    }
    free(sorted);
    return e;
}
