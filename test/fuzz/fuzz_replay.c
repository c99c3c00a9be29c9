/* DIRT engine: replays the fuzz targets' seed corpora through their entries
 * (fuzz_scene.h, fuzz_inputs.h), built with the normal compiler, in every
 * `meson test`:
 *   fuzz_replay                 write every target's seed corpus to a
 *                               temporary directory and replay it (the test)
 *   fuzz_replay --write DIR     write the seeds into DIR/TARGET/ for each
 *                               target (scene, image, env, files: libFuzzer's
 *                               corpora)
 *   fuzz_replay [--target T] FILE|DIR ...
 *                               replay files through target T (default
 *                               scene), e.g. a crash libFuzzer saved
 * The test fails when an invariant breaks, a target's seeds stop
 * exercising both outcomes (some load, some are refused), or the replay's
 * peak memory passes the fuzzers' 1024 MB. */
#include "fuzz_inputs.h"
#include "fuzz_scene.h"

#include "dirt/log.h"
#include "dirt/scene.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

static bool scene_one(const uint8_t *data, size_t size)
{
    bool ok = dirt_fuzz_scene_one(data, size);
    /* Load once more to learn the outcome (the entry keeps it to itself). */
    dirt_scene *s = dirt_fuzz_load(data, size);
    dirt_fuzz_outcome = s != NULL;
    dirt_scene_destroy(s);
    return ok;
}

typedef struct target {
    const char *name;
    bool (*one)(const uint8_t *data, size_t size);
    int (*write_corpus)(const char *dir);
    int min_loaded, min_refused; /* what the seeds must keep */
} target;

static const target targets[] = {
    {"scene", scene_one, dirt_fuzz_write_corpus, 8, 5},
    {"image", dirt_fuzz_image_one, dirt_fuzz_write_image_corpus, 8, 6},
    {"env", dirt_fuzz_env_one, dirt_fuzz_write_env_corpus, 3, 4},
    {"files", dirt_fuzz_files_one, dirt_fuzz_write_files_corpus, 3, 4},
};
#define NUM_TARGETS (sizeof(targets) / sizeof(targets[0]))

static int loaded, refused, broken;

static void quiet(void *user, enum dirt_log_level level, const char *file, int line,
                  const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

static bool replay_file(const target *t, const char *path)
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
    bool ok = t->one(data, n);
    if (dirt_fuzz_outcome)
        loaded++;
    else
        refused++;
    /* (the id of a scene load: the scene and files targets') */
    enum dirt_scene_error e = t->one == scene_one || t->one == dirt_fuzz_files_one
                                  ? dirt_scene_last_error() : DIRT_SCENE_ERR_OK;
    fprintf(stderr, "%-6s %-44s %s%s\n", t->name, path,
            dirt_fuzz_outcome ? "loads" : e ? dirt_scene_error_name(e) : "refused",
            ok ? "" : "  INVARIANT BROKEN");
    free(data);
    broken += !ok;
    return ok;
}

static bool replay_path(const target *t, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        perror(path);
        return false;
    }
    if (!S_ISDIR(st.st_mode))
        return replay_file(t, path);
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
        ok &= replay_file(t, p);
    }
    closedir(d);
    return ok;
}

static void remove_dir(const char *dir)
{
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

/* Writes every target's seeds into DIR/NAME/; false on a write error. */
static bool write_all(const char *dir)
{
    mkdir(dir, 0755);
    for (size_t i = 0; i < NUM_TARGETS; i++) {
        char sub[4096];
        snprintf(sub, sizeof(sub), "%s/%s", dir, targets[i].name);
        mkdir(sub, 0755);
        int n = targets[i].write_corpus(sub);
        fprintf(stderr, "wrote %d %s seeds into %s\n", n, targets[i].name, sub);
        if (n <= 0)
            return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    dirt_log_set_callback(quiet, NULL);
    if (argc == 3 && !strcmp(argv[1], "--write"))
        return write_all(argv[2]) ? 0 : 1;
    bool ok = true;
    if (argc > 1) {
        const target *t = &targets[0];
        int first = 1;
        if (argc > 2 && !strcmp(argv[1], "--target")) {
            t = NULL;
            for (size_t i = 0; i < NUM_TARGETS; i++)
                if (!strcmp(argv[2], targets[i].name))
                    t = &targets[i];
            if (!t) {
                fprintf(stderr, "no fuzz target '%s' (scene, image, env, files)\n", argv[2]);
                return 2;
            }
            first = 3;
        }
        for (int i = first; i < argc; i++)
            ok &= replay_path(t, argv[i]);
    } else {
        for (size_t i = 0; i < NUM_TARGETS; i++) {
            char dir[] = "/tmp/dirt_fuzz_corpus_XXXXXX";
            if (!mkdtemp(dir)) {
                perror("mkdtemp");
                return 1;
            }
            loaded = refused = 0;
            int n = targets[i].write_corpus(dir);
            ok &= n > 0 && replay_path(&targets[i], dir);
            /* The seeds must keep both outcomes: inputs that load, inputs
             * that are refused (a loader that refuses everything fails). */
            fprintf(stderr, "%s: %d seeds, %d load, %d refused\n", targets[i].name, n, loaded,
                    refused);
            if (loaded < targets[i].min_loaded || refused < targets[i].min_refused) {
                fprintf(stderr, "%s seeds: %d load, %d refused (want >= %d and >= %d)\n",
                        targets[i].name, loaded, refused, targets[i].min_loaded,
                        targets[i].min_refused);
                ok = false;
            }
            remove_dir(dir);
        }
    }
    /* The fuzzers' -rss_limit_mb: a replay above it would be an oom
     * finding there (meson test fills every allocation, MALLOC_PERTURB_,
     * so an allocation counts whether touched or not). */
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    fprintf(stderr, "replayed: %d invariants broken, peak RSS %ld MB\n", broken,
            ru.ru_maxrss / 1024);
    if (ru.ru_maxrss > 1024L * 1024) {
        fprintf(stderr, "the replay's peak RSS passed 1024 MB (the fuzzers' limit)\n");
        ok = false;
    }
    return ok && broken == 0 ? 0 : 1;
}
