/* GPU test helper: a headless GL 4.5 context, or skip. */
#ifndef DIRT_TEST_GPU_H
#define DIRT_TEST_GPU_H

#include "check.h"
#include "dirt/gpu.h"

#include <stdlib.h>

/* dirt_gpu_create(o), or NULL after printing why; the test then returns
 * TEST_SKIP (77). In CI (CI=true), and when DIRT_EXPECT_RENDERER names the
 * driver the run is for (dirt.sh test), a missing context is a failure:
 * the test ends with exit 1 here. */
static inline dirt_gpu *test_gpu_opts(const dirt_gpu_opts *o)
{
    dirt_gpu *gpu = dirt_gpu_create(o);
    const char *want = getenv("DIRT_EXPECT_RENDERER");
    if (!gpu && (test_in_ci() || (want && *want))) {
        fprintf(stderr, "%s: no OpenGL 4.5 context%s%s: failing instead of skipping\n",
                test_in_ci() ? "CI=true" : "DIRT_EXPECT_RENDERER", want && *want ? " of " : "",
                want && *want ? want : "");
        exit(1);
    }
    if (!gpu)
        fprintf(stderr, "no OpenGL 4.5 context: skipping\n");
    return gpu;
}

/* A headless context with synchronous debug output (test_gpu_opts). */
static inline dirt_gpu *test_gpu(void)
{
    return test_gpu_opts(&(dirt_gpu_opts){.sync_debug = true});
}

#endif
