/* GPU test helper: a headless GL 4.5 context, or skip. */
#ifndef DIRT_TEST_GPU_H
#define DIRT_TEST_GPU_H

#include "check.h"
#include "dirt/gpu.h"

/* Returns a headless context, or NULL after printing why; the test then
 * returns TEST_SKIP (77). */
static inline dirt_gpu *test_gpu(void)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){0});
    if (!gpu)
        fprintf(stderr, "no OpenGL 4.5 context: skipping\n");
    return gpu;
}

#endif
