/* DIRT engine: the figures every engine reports in the same shape: pass
 * times tagged with the clock that measured them, and bytes per buffer. */
#ifndef DIRT_STATS_H
#define DIRT_STATS_H

#include <stdint.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What measured a time. */
enum dirt_clock {
    DIRT_CLOCK_NONE = 0, /* not measured */
    DIRT_CLOCK_GPU,      /* GL_TIME_ELAPSED timer queries */
    DIRT_CLOCK_CPU,      /* CPU wall clock (around glFinish for GPU work) */
};

DIRT_API extern const char *const dirt_clock_names[3]; /* "none", "gpu", "cpu" */

/* The time of one pass (summed over its runs), ms. */
typedef struct dirt_pass_time {
    const char *name;    /* static string */
    double ms;
    enum dirt_clock clock;
} dirt_pass_time;

/* One buffer's bytes: what the last frame used of what is allocated. */
typedef struct dirt_buffer_bytes {
    const char *name;    /* static string */
    uint64_t used, allocated;
} dirt_buffer_bytes;

#ifdef __cplusplus
}
#endif
#endif
