/* The path tracer's MMRT technique (src/mmrt/pt_mmrt.c, glsl/mmrt/pt_rays.comp,
 * glsl/mmrt/to_gpoint.comp): bindings and counters. Same rules as
 * common/layout.h. */
#ifndef DIRT_COMMON_MMRT_PT_LAYOUT_H
#define DIRT_COMMON_MMRT_PT_LAYOUT_H

#include "common/mmrt_layout.h"

/* pt_rays.comp writes its counts at DIRT_BIND_MMRT_PT_COUNTS (the MMRT
 * technique's own range of common/constants.h). */

/* Counters of a render (16 bytes), cleared by the host at its start. */
struct dirt_mmrt_pt_counts {
    DIRT_UV4 counts;     /* x active rays traced (tmax >= tmin as given), y rays
                            whose march gave up (the previous traces'), zw 0 */
};

#endif
