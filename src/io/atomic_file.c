/* Atomic file output: temp file in the target directory + fsync + rename.
 * Contracts are documented in dirt/file.h. */
#include "io/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dirt/log.h"

#define DEFAULT_MODE 0644

struct dirt_atomic_file {
    char *path; /* target */
    char *temp; /* mkstemp result */
    FILE *fp;   /* stream on the temp file, NULL once closed */
    int cleanup; /* slot in the signal cleanup list, -1 none */
};

/* ---- files removed when a signal ends the process ---- */

#define CLEANUP_SLOTS 32
#define CLEANUP_PATH 4352
static char cleanup_path[CLEANUP_SLOTS][CLEANUP_PATH];
static volatile sig_atomic_t cleanup_used[CLEANUP_SLOTS];

int dirt_cleanup_add(const char *path)
{
    size_t len = path ? strlen(path) : 0;
    if (!len || len >= CLEANUP_PATH)
        return -1;
    for (int i = 0; i < CLEANUP_SLOTS; i++) {
        if (cleanup_used[i])
            continue;
        memcpy(cleanup_path[i], path, len + 1);
        cleanup_used[i] = 1; /* after the copy: the handler reads only used slots */
        return i;
    }
    DIRT_WARN("more than %d files to remove on a signal: '%s' is not covered", CLEANUP_SLOTS,
              path);
    return -1;
}

void dirt_cleanup_remove(int slot)
{
    if (slot >= 0 && slot < CLEANUP_SLOTS)
        cleanup_used[slot] = 0;
}

/* The handshake between the thread making a file (dirt_cleanup_hold ...
 * release) and a handler running on another thread (the main thread's
 * signals are blocked meanwhile): the handler says it is ending the
 * process (`dying`), then waits while a file is being made (`holding`);
 * a thread that would make a file after that waits for the end instead.
 * Both flags are lock-free atomics (sequentially consistent: each side
 * writes its flag before it reads the other's), safe in a handler. */
static atomic_int cleanup_holding, cleanup_dying;
static sigset_t cleanup_saved_mask;

void dirt_cleanup_hold(void)
{
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &cleanup_saved_mask);
    atomic_store(&cleanup_holding, 1);
    if (atomic_load(&cleanup_dying)) {
        /* A handler is removing the listed files: make nothing more. */
        atomic_store(&cleanup_holding, 0);
        for (;;)
            pause();
    }
}

void dirt_cleanup_release(void)
{
    atomic_store(&cleanup_holding, 0);
    pthread_sigmask(SIG_SETMASK, &cleanup_saved_mask, NULL);
}

static void on_signal(int sig)
{
    /* Never on a holding thread (its signals are blocked): wait for it to
     * list the file it is making. */
    atomic_store(&cleanup_dying, 1);
    while (atomic_load(&cleanup_holding))
        ;
    /* unlink, signal and raise are async-signal-safe. */
    for (int i = 0; i < CLEANUP_SLOTS; i++) {
        if (cleanup_used[i])
            unlink(cleanup_path[i]);
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

bool dirt_cleanup_on_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
    for (size_t i = 0; i < sizeof(sigs) / sizeof(sigs[0]); i++) {
        if (sigaction(sigs[i], &sa, NULL) != 0) {
            DIRT_ERROR("cannot install the handler of signal %d: %s", sigs[i], strerror(errno));
            return false;
        }
    }
    return true;
}

/* The longest file name (NAME_MAX of Linux file systems). */
#define NAME_LIMIT 255

/* "<path>.tmp.<host>.<pid>.XXXXXX": the writer's host and process, so a
 * later run can tell a dead writer's leftovers from a live one's. When the
 * name would pass NAME_LIMIT bytes, the target's name is cut (its start
 * kept) so that it fits: a legal 255-byte output name still gets its
 * temporary file. */
static char *temp_name(const char *path)
{
    char host[65] = "host";
    if (gethostname(host, sizeof(host)) != 0)
        snprintf(host, sizeof(host), "host");
    host[sizeof(host) - 1] = '\0';
    for (char *c = host; *c; c++) {
        if (*c == '/' || *c == '.')
            *c = '-';
    }
    char suffix[128];
    snprintf(suffix, sizeof(suffix), ".tmp.%s.%ld.XXXXXX", host, (long)getpid());
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    size_t base = strlen(path) - dir;
    if (base + strlen(suffix) > NAME_LIMIT)
        base = NAME_LIMIT - strlen(suffix);
    size_t size = dir + base + strlen(suffix) + 1;
    char *t = malloc(size);
    if (t)
        snprintf(t, size, "%.*s%s", (int)(dir + base), path, suffix);
    return t;
}

/* Directory part of `path` as a new string ("." when there is none);
 * NULL when out of memory. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return strdup(".");
    size_t len = (size_t)(slash - path);
    if (len == 0)
        len = 1; /* "/name" -> "/" */
    char *dir = malloc(len + 1);
    if (!dir)
        return NULL;
    memcpy(dir, path, len);
    dir[len] = '\0';
    return dir;
}

/* Frees `f` after closing and removing the temp file if still present
 * (removed before it leaves the signal cleanup list: a signal in between
 * finds it listed). */
static void discard(dirt_atomic_file *f, bool remove_temp)
{
    if (f->fp)
        fclose(f->fp);
    if (remove_temp && unlink(f->temp) != 0 && errno != ENOENT)
        DIRT_WARN("cannot remove temporary file '%s': %s", f->temp,
                  strerror(errno));
    dirt_cleanup_remove(f->cleanup);
    free(f->temp);
    free(f->path);
    free(f);
}

dirt_atomic_file *dirt_atomic_open(const char *path)
{
    dirt_atomic_file *f = NULL;
    char *dir = NULL;
    int fd = -1;

    if (!path || !*path) {
        DIRT_ERROR("atomic write: empty output path");
        return NULL;
    }
    if (path[strlen(path) - 1] == '/') {
        DIRT_ERROR("atomic write: output path '%s' names a directory", path);
        return NULL;
    }

    mode_t mode = DEFAULT_MODE;
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            DIRT_ERROR("cannot write '%s': it is a directory", path);
            return NULL;
        }
        if (S_ISREG(st.st_mode))
            mode = st.st_mode & 07777;
    }

    f = calloc(1, sizeof(*f));
    if (!f)
        goto oom;
    f->cleanup = -1;
    f->path = strdup(path);
    f->temp = temp_name(path);
    if (!f->path || !f->temp)
        goto oom;

    /* No signal between making the file and listing it for removal
     * (SIGTERM there used to leave an empty temporary file). */
    dirt_cleanup_hold();
    fd = mkstemp(f->temp);
    if (fd >= 0)
        f->cleanup = dirt_cleanup_add(f->temp);
    dirt_cleanup_release();
    if (fd < 0) {
        int err = errno;
        dir = dir_of(path);
        DIRT_ERROR("cannot write '%s': cannot create a temporary file in "
                   "directory '%s': %s", path, dir ? dir : "?", strerror(err));
        goto error;
    }
    if (fchmod(fd, mode) != 0)
        DIRT_WARN("cannot set mode %o on '%s': %s", (unsigned)mode, f->temp,
                  strerror(errno));
    f->fp = fdopen(fd, "wb");
    if (!f->fp) {
        DIRT_ERROR("cannot write '%s': fdopen failed: %s", path,
                   strerror(errno));
        close(fd);
        unlink(f->temp);
        dirt_cleanup_remove(f->cleanup);
        goto error;
    }
    return f;

oom:
    DIRT_ERROR("cannot write '%s': out of memory", path);
error:
    free(dir);
    if (f) {
        free(f->temp);
        free(f->path);
        free(f);
    }
    return NULL;
}

FILE *dirt_atomic_stream(dirt_atomic_file *f)
{
    return f ? f->fp : NULL;
}

const char *dirt_atomic_temp_path(const dirt_atomic_file *f)
{
    return f ? f->temp : NULL;
}

const char *dirt_atomic_target_path(const dirt_atomic_file *f)
{
    return f ? f->path : NULL;
}

/* fsync the directory holding `path` so the rename itself is durable.
 * Failure is only a warning: the data is already safely in place. */
static void sync_dir(const char *path)
{
    char *dir = dir_of(path);
    if (!dir)
        return;
    int fd = open(dir, O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
        if (fsync(fd) != 0 && errno != EINVAL)
            DIRT_WARN("fsync of directory '%s' failed: %s", dir,
                      strerror(errno));
        close(fd);
    }
    free(dir);
}

bool dirt_atomic_commit(dirt_atomic_file *f)
{
    if (!f) {
        DIRT_ERROR("atomic commit: NULL file");
        return false;
    }
    if (fflush(f->fp) != 0) {
        DIRT_ERROR("cannot write '%s': writing '%s' failed: %s", f->path,
                   f->temp, strerror(errno));
        goto error;
    }
    if (ferror(f->fp)) {
        DIRT_ERROR("cannot write '%s': an earlier write to '%s' failed",
                   f->path, f->temp);
        goto error;
    }
    if (fsync(fileno(f->fp)) != 0) {
        DIRT_ERROR("cannot write '%s': fsync of '%s' failed: %s", f->path,
                   f->temp, strerror(errno));
        goto error;
    }
    FILE *fp = f->fp;
    f->fp = NULL;
    if (fclose(fp) != 0) {
        DIRT_ERROR("cannot write '%s': closing '%s' failed: %s", f->path,
                   f->temp, strerror(errno));
        goto error;
    }
    if (rename(f->temp, f->path) != 0) {
        DIRT_ERROR("cannot write '%s': rename from '%s' failed: %s", f->path,
                   f->temp, strerror(errno));
        goto error;
    }
    sync_dir(f->path);
    discard(f, false);
    return true;

error:
    discard(f, true);
    return false;
}

void dirt_atomic_abort(dirt_atomic_file *f)
{
    if (f)
        discard(f, true);
}

bool dirt_write_file_atomic(const char *path, const void *data, size_t size)
{
    if (size && !data) {
        DIRT_ERROR("cannot write '%s': NULL data", path ? path : "(null)");
        return false;
    }
    dirt_atomic_file *f = dirt_atomic_open(path);
    if (!f)
        return false;
    if (size && fwrite(data, 1, size, f->fp) != size) {
        DIRT_ERROR("cannot write '%s': writing '%s' failed: %s", path,
                   f->temp, strerror(errno));
        dirt_atomic_abort(f);
        return false;
    }
    return dirt_atomic_commit(f);
}
