/* Atomic writes: failures leave nothing behind, replacements are complete,
 * aborts keep the original, temp files never survive. */
#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "dirt/file.h"
#include "dirt/image.h"

static char g_dir[] = "/tmp/dirt_test_io_atomic.XXXXXX";

static bool exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

/* Number of entries in `dir` (excluding . and ..), and how many of them
 * contain ".tmp." (leftover temp files). -1 when it cannot be opened. */
static int count_entries(const char *dir, int *temps)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    *temps = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        n++;
        if (strstr(e->d_name, ".tmp."))
            (*temps)++;
    }
    closedir(d);
    return n;
}

/* Removes `path` and, when it is a directory, everything below it. */
static void remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        chmod(path, 0755);
        DIR *d = opendir(path);
        if (d) {
            struct dirent *e;
            char sub[1024];
            while ((e = readdir(d))) {
                if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                    continue;
                snprintf(sub, sizeof(sub), "%s/%s", path, e->d_name);
                remove_tree(sub);
            }
            closedir(d);
        }
        rmdir(path);
    } else {
        unlink(path);
    }
}

static bool write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    bool ok = fputs(text, f) >= 0;
    return fclose(f) == 0 && ok;
}

/* True when the file at `path` holds exactly `text`. */
static bool has_text(const char *path, const char *text)
{
    char buf[256] = {0};
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    return n == strlen(text) && memcmp(buf, text, n) == 0;
}

static dirt_image *small_image(float v)
{
    dirt_image *img = dirt_image_create(4, 3);
    if (img)
        for (int i = 0; i < 4 * 3 * 4; i++)
            img->rgba[i] = v;
    return img;
}

static void test_missing_directory(dirt_image *img)
{
    char dir[512], path[600];
    snprintf(dir, sizeof(dir), "%s/does_not_exist", g_dir);
    snprintf(path, sizeof(path), "%s/out.exr", dir);
    CHECK(!dirt_image_write_exr(img, path, NULL));
    snprintf(path, sizeof(path), "%s/out.png", dir);
    CHECK(!dirt_image_write_png(img, path, NULL));
    CHECK(!dirt_image_write(img, path, NULL));
    CHECK(!dirt_write_file_atomic(path, "x", 1));
    CHECK(dirt_atomic_open(path) == NULL);
    CHECK(!exists(dir) && !exists(path));

    /* a parent that is a regular file fails even for root */
    char file[512];
    snprintf(file, sizeof(file), "%s/plain_file", g_dir);
    CHECK(write_text(file, "plain"));
    snprintf(path, sizeof(path), "%s/out.exr", file);
    CHECK(!dirt_image_write_exr(img, path, NULL));
    CHECK(has_text(file, "plain"));
    unlink(file);

    int temps = 0;
    CHECK(count_entries(g_dir, &temps) == 0);
}

static void test_readonly_directory(dirt_image *img)
{
    char dir[512], path[600];
    snprintf(dir, sizeof(dir), "%s/readonly", g_dir);
    CHECK(mkdir(dir, 0755) == 0);
    CHECK(chmod(dir, 0555) == 0);
    if (access(dir, W_OK) == 0) {
        fprintf(stderr, "note: permissions not enforced (root?), skipping "
                        "the read-only directory check\n");
    } else {
        snprintf(path, sizeof(path), "%s/out.exr", dir);
        CHECK(!dirt_image_write_exr(img, path, NULL));
        snprintf(path, sizeof(path), "%s/out.png", dir);
        CHECK(!dirt_image_write_png(img, path, NULL));
        CHECK(!dirt_write_file_atomic(path, "x", 1));
        int temps = 0;
        CHECK(count_entries(dir, &temps) == 0);
    }
    chmod(dir, 0755);
    remove_tree(dir);
}

static void test_overwrite(dirt_image *img)
{
    char path[512];
    int temps = 0;
    snprintf(path, sizeof(path), "%s/over.exr", g_dir);
    CHECK(write_text(path, "old content"));
    CHECK(chmod(path, 0600) == 0);
    CHECK(dirt_image_write(img, path, NULL));
    dirt_image *back = dirt_image_read_exr(path);
    CHECK(back != NULL);
    if (back) {
        CHECK(back->width == 4 && back->height == 3);
        CHECK(back->rgba[0] == img->rgba[0]);
        dirt_image_destroy(back);
    }
    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0600);
    CHECK(count_entries(g_dir, &temps) == 1 && temps == 0);

    /* overwrite once more with a PNG over a PNG */
    snprintf(path, sizeof(path), "%s/over.png", g_dir);
    CHECK(dirt_image_write_png(img, path, NULL));
    CHECK(dirt_image_write_png(img, path, NULL));
    CHECK(count_entries(g_dir, &temps) == 2 && temps == 0);
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644);
    remove_tree(path);
    snprintf(path, sizeof(path), "%s/over.exr", g_dir);
    remove_tree(path);
}

static void test_stream_api(void)
{
    char path[512];
    int temps = 0;
    snprintf(path, sizeof(path), "%s/stats.json", g_dir);
    CHECK(write_text(path, "original"));

    /* abort: original intact, temp file gone */
    dirt_atomic_file *f = dirt_atomic_open(path);
    CHECK(f != NULL);
    if (f) {
        const char *tmp = dirt_atomic_temp_path(f);
        CHECK(tmp && strncmp(tmp, path, strlen(path)) == 0 &&
              strstr(tmp, ".tmp.") != NULL);
        CHECK(exists(tmp));
        CHECK(strcmp(dirt_atomic_target_path(f), path) == 0);
        fputs("garbage that must never appear", dirt_atomic_stream(f));
        fflush(dirt_atomic_stream(f));
        CHECK(has_text(path, "original"));
        char tmp_copy[600];
        snprintf(tmp_copy, sizeof(tmp_copy), "%s", tmp);
        dirt_atomic_abort(f);
        CHECK(!exists(tmp_copy));
    }
    CHECK(has_text(path, "original"));
    CHECK(count_entries(g_dir, &temps) == 1 && temps == 0);
    dirt_atomic_abort(NULL);

    /* commit replaces the content */
    f = dirt_atomic_open(path);
    CHECK(f != NULL);
    if (f) {
        fprintf(dirt_atomic_stream(f), "{\"frames\": %d}\n", 3);
        CHECK(dirt_atomic_commit(f));
    }
    CHECK(has_text(path, "{\"frames\": 3}\n"));
    CHECK(dirt_write_file_atomic(path, "replaced", 8));
    CHECK(has_text(path, "replaced"));
    CHECK(count_entries(g_dir, &temps) == 1 && temps == 0);

    /* commit that cannot rename (a directory appeared at the target):
     * fails, removes its temp file, leaves the directory alone */
    char target[512];
    snprintf(target, sizeof(target), "%s/becomes_dir", g_dir);
    f = dirt_atomic_open(target);
    CHECK(f != NULL);
    if (f) {
        fputs("data", dirt_atomic_stream(f));
        CHECK(mkdir(target, 0755) == 0);
        char keep[600];
        snprintf(keep, sizeof(keep), "%s/keep", target);
        CHECK(write_text(keep, "k")); /* non-empty: rename must fail */
        CHECK(!dirt_atomic_commit(f));
        CHECK(has_text(keep, "k"));
    }
    CHECK(count_entries(g_dir, &temps) == 2 && temps == 0);
    remove_tree(target);
    CHECK(dirt_atomic_open(g_dir) == NULL); /* a directory is not a file */
    remove_tree(path);
}

static void test_bad_extension(dirt_image *img)
{
    char path[512];
    int temps = 0;
    snprintf(path, sizeof(path), "%s/out.bmp", g_dir);
    CHECK(!dirt_image_write(img, path, NULL));
    CHECK(!exists(path));
    snprintf(path, sizeof(path), "%s/noext", g_dir);
    CHECK(!dirt_image_write(img, path, NULL));
    snprintf(path, sizeof(path), "%s/.exr", g_dir); /* extension only */
    CHECK(!dirt_image_write(img, path, NULL));
    CHECK(count_entries(g_dir, &temps) == 0);
}

/* A writer killed by SIGTERM (or SIGINT) mid-write leaves neither its
 * temporary file nor the target, nor a claim it registered; the temporary
 * file names its host and process. */
static void test_signal_cleanup(int sig)
{
    char target[256], claim[256];
    snprintf(target, sizeof(target), "%s/killed_%d.exr", g_dir, sig);
    snprintf(claim, sizeof(claim), "%s/killed_%d.exr.claim.0", g_dir, sig);
    int fds[2];
    CHECK(pipe(fds) == 0);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        if (!dirt_cleanup_on_signals())
            _exit(2);
        dirt_atomic_file *f = dirt_atomic_open(target);
        if (!f || !write_text(claim, "claim") || dirt_cleanup_add(claim) < 0)
            _exit(3);
        fputs("partial", dirt_atomic_stream(f));
        fflush(dirt_atomic_stream(f));
        char msg[4096];
        snprintf(msg, sizeof(msg), "%s", dirt_atomic_temp_path(f));
        if (write(fds[1], msg, strlen(msg) + 1) < 0)
            _exit(4);
        for (;;)
            pause();
    }
    close(fds[1]);
    char temp[4096] = "";
    ssize_t n = read(fds[0], temp, sizeof(temp) - 1);
    close(fds[0]);
    CHECK(n > 0);
    temp[n > 0 ? n : 0] = '\0';
    CHECK_MSG(exists(temp) && exists(claim), "the writer's files exist before the signal");
    char host[65] = "";
    gethostname(host, sizeof(host) - 1);
    char expect[512];
    snprintf(expect, sizeof(expect), ".tmp.%.*s", 20, host);
    for (char *c = expect + 5; *c; c++)
        if (*c == '.' || *c == '/')
            *c = '-';
    CHECK_MSG(strstr(temp, expect) != NULL, "temp name '%s' lacks '%s'", temp, expect);
    char pidpart[32];
    snprintf(pidpart, sizeof(pidpart), ".%ld.", (long)pid);
    CHECK_MSG(strstr(temp, pidpart) != NULL, "temp name '%s' lacks the pid", temp);
    kill(pid, sig);
    int status = 0;
    CHECK(waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig);
    CHECK_MSG(!exists(temp), "signal %d left '%s'", sig, temp);
    CHECK_MSG(!exists(claim), "signal %d left the claim", sig);
    CHECK(!exists(target));
}

static void *idle_thread(void *arg)
{
    (void)arg;
    for (;;)
        pause();
    return NULL;
}

/* No instant leaves a temporary file behind (issue 23: SIGTERM left an
 * empty one in 3 of 32 tries, between its making and its listing for
 * removal): a child opens and aborts atomic files without pause while a
 * second thread idles (a signal to the process may be handled there,
 * while the main thread is inside the window); it is killed after a
 * random delay, 60 times, and its directory must hold no temporary file
 * each time. */
static void test_signal_window(void)
{
    char dir[300], target[400];
    snprintf(dir, sizeof(dir), "%s/window", g_dir);
    CHECK(mkdir(dir, 0700) == 0);
    snprintf(target, sizeof(target), "%s/loop.exr", dir);
    srand(12345);
    int left = 0, killed = 0;
    for (int round = 0; round < 60; round++) {
        pid_t pid = fork();
        if (pid == 0) {
            if (!dirt_cleanup_on_signals())
                _exit(2);
            pthread_t t;
            if (pthread_create(&t, NULL, idle_thread, NULL) != 0)
                _exit(3);
            for (;;)
                dirt_atomic_abort(dirt_atomic_open(target));
        }
        struct timespec ts = {0, 2000000L + (long)(rand() % 8000) * 1000L};
        nanosleep(&ts, NULL);
        kill(pid, SIGTERM);
        int status = 0;
        waitpid(pid, &status, 0);
        killed += WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM;
        int temps = 0;
        count_entries(dir, &temps);
        left += temps > 0;
        if (temps)
            remove_tree(dir), mkdir(dir, 0700);
    }
    CHECK_MSG(killed == 60, "%d of 60 writers ended by SIGTERM", killed);
    CHECK_MSG(left == 0, "SIGTERM left a temporary file in %d of 60 tries", left);
}

/* A legal 240-byte name gets a temporary file (its name cut to fit). */
static void test_long_name(void)
{
    char name[241], path[600];
    memset(name, 'n', 236);
    memcpy(name + 236, ".png", 5);
    snprintf(path, sizeof(path), "%s/%s", g_dir, name);
    dirt_atomic_file *f = dirt_atomic_open(path);
    CHECK_MSG(f != NULL, "a 240-byte name was refused");
    if (f) {
        const char *t = strrchr(dirt_atomic_temp_path(f), '/');
        CHECK(t && strlen(t + 1) <= 255 && strncmp(t + 1, name, 100) == 0);
        fputs("x", dirt_atomic_stream(f));
        CHECK(dirt_atomic_commit(f));
    }
    CHECK(exists(path));
    int temps = 0;
    count_entries(g_dir, &temps);
    CHECK(temps == 0);
    remove(path);
}

int main(void)
{
    if (!mkdtemp(g_dir)) {
        perror("mkdtemp");
        return 1;
    }
    dirt_image *img = small_image(0.25f);
    CHECK(img != NULL);
    if (img) {
        test_missing_directory(img);
        test_readonly_directory(img);
        test_overwrite(img);
        test_stream_api();
        test_bad_extension(img);
        test_signal_cleanup(SIGTERM);
        test_signal_cleanup(SIGINT);
        test_signal_window();
        test_long_name();
    }
    dirt_image_destroy(img);
    remove_tree(g_dir);
    return check_finish();
}
