/* Shared by the benchmark programs of perf/: comma lists, the --views
 * names, the GPU and the scenes. Header only (each benchmark is one file). */
#ifndef DIRT_PERF_BENCH_COMMON_H
#define DIRT_PERF_BENCH_COMMON_H

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/gpu.h"
#include "dirt/scene.h"
#include "views/views.h"

/* The integers of a comma list "1,2,4" into out (at most max); how many. */
static inline int bench_parse_list(const char *s, int *out, int max)
{
    int n = 0;
    while (*s && n < max) {
        out[n++] = atoi(s);
        const char *c = strchr(s, ',');
        if (!c)
            break;
        s = c + 1;
    }
    return n;
}

/* --views NAME (single, cube, cube+camera) into *mode; false after
 * printing the error for any other name. */
static inline bool bench_views(const char *prog, const char *name, enum dirt_view_mode *mode)
{
    if (!strcmp(name, "single"))
        *mode = DIRT_VIEWS_SINGLE;
    else if (!strcmp(name, "cube"))
        *mode = DIRT_VIEWS_CUBE;
    else if (!strcmp(name, "cube+camera"))
        *mode = DIRT_VIEWS_CUBE_CAMERA;
    else {
        fprintf(stderr, "%s: --views is single, cube or cube+camera, not '%s'\n", prog, name);
        return false;
    }
    return true;
}

/* The GPU of a benchmark (no debug output) and its description in desc;
 * NULL after logging. */
static inline dirt_gpu *bench_gpu(char *desc, size_t size)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.no_debug = true});
    if (gpu)
        dirt_gpu_describe(gpu, desc, size);
    return gpu;
}

/* The scene at `path` ("default": the built-in one) with `load` (NULL:
 * defaults); NULL after logging. */
static inline dirt_scene *bench_scene(const char *path, const dirt_load_opts *load)
{
    return strcmp(path, "default") ? dirt_scene_load(path, load) : dirt_scene_create_default();
}

#endif
