/* GPU test helper: a headless GL 4.5 context, or skip. */
#ifndef DIRT_TEST_GPU_H
#define DIRT_TEST_GPU_H

#include "check.h"
#include "dirt/gpu.h"

/* Returns a headless context, or NULL after printing why; the test then
 * returns TEST_SKIP (77). In CI (CI=true) a missing context is a failure:
 * the test ends with exit 1 here. */
static inline dirt_gpu *test_gpu(void)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.sync_debug = true});
    if (!gpu && test_in_ci()) {
        fprintf(stderr, "CI=true: no OpenGL 4.5 context: failing instead of skipping\n");
        exit(1);
    }
    if (!gpu)
        fprintf(stderr, "no OpenGL 4.5 context: skipping\n");
    return gpu;
}

#endif
