/* DIRT engine: rays and hits as every ray tracer of the engine exchanges
 * them (the GPU techniques, the Embree reference, the checks). */
#ifndef DIRT_RAY_H
#define DIRT_RAY_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A ray: points org + t dir for t in (tmin, tmax). Same layout as the GPU's
 * dirt_gpu_ray (glsl/common/layout.h). */
typedef struct dirt_ray {
    float org[3];
    float tmin;
    float dir[3];
    float tmax;
} dirt_ray;

#define DIRT_HIT_NONE 0xFFFFFFFFu

/* The closest hit of a ray (layout of dirt_gpu_hit): prim = DIRT_HIT_NONE
 * when nothing was hit; the hit point is org + t dir
 * = (1 - u - v) p0 + u p1 + v p2; view = the view it was found in. */
typedef struct dirt_hit {
    uint32_t prim, view, owner, next;
    float u, v, t, reserved;
} dirt_hit;

#ifdef __cplusplus
}
#endif
#endif
