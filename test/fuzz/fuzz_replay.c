/* DIRT engine: replays the scene fuzz corpus through the fuzz entry
 * (dirt_fuzz_scene_one), built with the normal compiler, in every
 * `meson test`:
 *   fuzz_replay                 write the seed corpus to a temporary
 *                               directory and replay it (the test)
 *   fuzz_replay --write DIR     write the seed corpus into DIR (for libFuzzer)
 *   fuzz_replay FILE|DIR ...    replay files (e.g. a crash libFuzzer saved)
 * The test fails when an invariant breaks or the seeds stop exercising
 * both outcomes (some load, some fail). */
#include "fuzz_scene.h"

#include "dirt/log.h"
#include "dirt/scene.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int loaded, failed, broken;

static void quiet(void *user, enum dirt_log_level level, const char *file, int line,
                  const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

static bool replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return false;
    }
    size_t cap = 1 << 16, n = 0;
    uint8_t *data = malloc(cap);
    size_t got;
    while (data && (got = fread(data + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint8_t *bigger = realloc(data, cap *= 2);
            if (!bigger) {
                free(data);
                data = NULL;
            } else {
                data = bigger;
            }
        }
    }
    fclose(f);
    if (!data) {
        fprintf(stderr, "%s: out of memory\n", path);
        return false;
    }
    bool ok = dirt_fuzz_scene_one(data, n);
    /* Load once more to learn the outcome (the entry keeps it to itself). */
    dirt_scene *s = dirt_fuzz_load(data, n);
    if (s)
        loaded++;
    else
        failed++;
    fprintf(stderr, "%-40s %s%s\n", path, s ? "loads" : dirt_scene_error_name(dirt_scene_last_error()),
            ok ? "" : "  INVARIANT BROKEN");
    dirt_scene_destroy(s);
    free(data);
    broken += !ok;
    return ok;
}

static bool replay_path(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        perror(path);
        return false;
    }
    if (!S_ISDIR(st.st_mode))
        return replay_file(path);
    DIR *d = opendir(path);
    if (!d) {
        perror(path);
        return false;
    }
    bool ok = true;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char p[4096];
        snprintf(p, sizeof(p), "%s/%s", path, e->d_name);
        ok &= replay_file(p);
    }
    closedir(d);
    return ok;
}

int main(int argc, char **argv)
{
    dirt_log_set_callback(quiet, NULL);
    if (argc == 3 && !strcmp(argv[1], "--write")) {
        int n = dirt_fuzz_write_corpus(argv[2]);
        fprintf(stderr, "wrote %d seed files into %s\n", n, argv[2]);
        return n > 0 ? 0 : 1;
    }
    bool ok = true;
    if (argc > 1) {
        for (int i = 1; i < argc; i++)
            ok &= replay_path(argv[i]);
    } else {
        char dir[] = "/tmp/dirt_fuzz_corpus_XXXXXX";
        if (!mkdtemp(dir)) {
            perror("mkdtemp");
            return 1;
        }
        int n = dirt_fuzz_write_corpus(dir);
        ok = n > 0 && replay_path(dir);
        /* The seeds must keep both outcomes: valid files that load, invalid
         * ones that fail (a loader that refuses everything fails here). */
        if (loaded < 8 || failed < 5) {
            fprintf(stderr, "seed corpus: %d load, %d fail (want >= 8 and >= 5)\n", loaded,
                    failed);
            ok = false;
        }
        DIR *d = opendir(dir);
        struct dirent *e;
        while (d && (e = readdir(d)) != NULL) {
            char p[4096];
            snprintf(p, sizeof(p), "%s/%s", dir, e->d_name);
            if (e->d_name[0] != '.')
                remove(p);
        }
        if (d)
            closedir(d);
        rmdir(dir);
    }
    fprintf(stderr, "replayed: %d load, %d fail, %d invariants broken\n", loaded, failed, broken);
    return ok && broken == 0 ? 0 : 1;
}
