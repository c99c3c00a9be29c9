/* DIRT engine: monotonic wall clock. */
#ifndef DIRT_CLOCK_H
#define DIRT_CLOCK_H

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Milliseconds from an arbitrary fixed point (CLOCK_MONOTONIC). */
DIRT_API double dirt_clock_ms(void);

#ifdef __cplusplus
}
#endif
#endif
