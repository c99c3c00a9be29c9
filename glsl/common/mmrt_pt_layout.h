/* The path tracer's MMRT technique (src/mmrt/pt_mmrt.c, glsl/mmrt/pt_rays.comp,
 * glsl/mmrt/to_gpoint.comp): bindings and counters. Same rules as
 * common/layout.h. */
#ifndef DIRT_COMMON_MMRT_PT_LAYOUT_H
#define DIRT_COMMON_MMRT_PT_LAYOUT_H

#include "common/mmrt_layout.h"

/* pt_rays.comp: the offset copy of a ray batch and the technique's counters.
 * These reuse DIRT's Fetch binding points (unused by every MMRT pass). */
#define DIRT_BIND_MMRT_PT_RAYS_OUT 11  /* dirt_gpu_ray[count] */
#define DIRT_BIND_MMRT_PT_COUNTS 12    /* dirt_mmrt_pt_counts */

/* Counters of a render (16 bytes), cleared by the host at its start. */
struct dirt_mmrt_pt_counts {
    DIRT_UV4 counts;     /* x active rays traced (tmax >= tmin as given), y rays
                            whose march gave up (the previous traces'), zw 0 */
};

#endif
