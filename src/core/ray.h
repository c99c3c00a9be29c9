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

/* What a GPU trace needs for alpha-tested traversal (doc/light-transport.md
 * section 1, "Alpha"): a hit of a MASK or BLEND material that the alpha test
 * rejects is no hit, and the trace goes on to the next one. Zero-initialised
 * = no test (every surface opaque, the trace as fast as without alpha).
 * The tables are the integrator's (dirt_gpu_model_tables, dirt/gpu_tables.h):
 * the trace binds them at DIRT_BIND_MODEL_MATERIALS and _TEXELS and reads
 * the per-primitive materials, UVs and texels. BLEND decisions use the key
 * dirt_rng_u32(seed, first_pixel + owner(i), sample, bounce, dim) for ray i
 * of the batch, owner(i) = i or its ray batch's owner (dirt/tracer.h,
 * set_batch; doc/rng.md, "Alpha"). */
typedef struct dirt_trace_alpha {
    uint32_t materials;   /* GL buffer of dirt_gpu_model_material; 0 = no test */
    uint32_t texels;      /* GL buffer of the texel table */
    uint32_t seed;        /* the render's seed */
    uint32_t sample;      /* sample index */
    uint32_t bounce;      /* the vertex the rays leave (0: camera rays) */
    uint32_t dim;         /* DIRT_RNG_DIM_ALPHA_PATH or _SHADOW */
    uint32_t first_pixel; /* pixel of ray 0 of the batch */
} dirt_trace_alpha;

#ifdef __cplusplus
}
#endif
#endif
