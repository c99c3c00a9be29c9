/* DIRT engine: the counter-based random number generator shared by the CPU
 * reference (src/ref) and the GPU integrator (glsl/common/rng.glsl).
 *
 * There is no state: the random number used for a decision is a pure function
 * of (seed, pixel, sample, bounce, dimension), so the CPU and the GPU draw the
 * same numbers for the same path and per-pixel comparisons are meaningful.
 * The specification (and the allocation of dimensions below) is in
 * doc/rng.md; glsl/common/rng.glsl must compute the same bits. Change both
 * together and update the regression values in test/unit/test_ref_rng.c.
 *
 *   key   = dirt_rng_key(seed, pixel, sample, bounce)
 *   u32   = dirt_rng_next(key, dim)            (== dirt_rng_u32(...))
 *   float = (u32 >> 8) * 2^-24                 in [0, 1 - 2^-24], exact
 *
 * pixel = y * width + x with y = 0 the top row; sample = index of the sample
 * in the pixel (counting across progressive passes); bounce = 0 for the
 * camera ray, k for the decisions taken at the k-th path vertex. */
#ifndef DIRT_INTEGRATOR_RNG_H
#define DIRT_INTEGRATOR_RNG_H

#include <stdint.h>

/* ---- dimensions (identical #defines in glsl/common/rng.glsl) ----------- */

/* bounce 0: camera ray */
#define DIRT_RNG_DIM_PIXEL_X 0u   /* jitter inside the pixel */
#define DIRT_RNG_DIM_PIXEL_Y 1u
#define DIRT_RNG_DIM_LENS_U 2u    /* thin-lens aperture sample */
#define DIRT_RNG_DIM_LENS_V 3u
/* bounce k >= 1: decisions at path vertex k */
#define DIRT_RNG_DIM_LIGHT_SELECT 0u /* which light source (area set or punctual) */
#define DIRT_RNG_DIM_LIGHT_TRI 1u    /* which emissive triangle */
#define DIRT_RNG_DIM_LIGHT_U 2u      /* point on that triangle */
#define DIRT_RNG_DIM_LIGHT_V 3u
#define DIRT_RNG_DIM_LOBE 4u         /* BSDF lobe choice */
#define DIRT_RNG_DIM_BSDF_U 5u       /* BSDF direction (also the AO direction) */
#define DIRT_RNG_DIM_BSDF_V 6u
#define DIRT_RNG_DIM_RR 7u           /* Russian roulette */
/* every bounce k >= 0: keys of the stochastic-transparency (alpha BLEND)
 * decisions of the rays leaving vertex k (k = 0: the camera), one key per
 * ray (dirt_rng_u32 with these dims), one decision per primitive under it
 * (dirt_rng_alpha); doc/rng.md, "Alpha" */
#define DIRT_RNG_DIM_ALPHA_PATH 8u   /* the path ray (camera ray, BSDF sample) */
#define DIRT_RNG_DIM_ALPHA_SHADOW 9u /* the shadow ray (next-event estimation, AO) */
/* The sample index that keys the pinhole ray through the pixel centre of
 * the Z and ID AOVs (its alpha decisions; it is no sample of the image). */
#define DIRT_RNG_SAMPLE_AOV 0xFFFFFFFFu

/* One 32-bit mixing round: bijective on uint32 (xor-shifts and odd
 * multipliers), full avalanche. Constants from Chris Wellons' hash-prospector
 * ("lowbias32"); see doc/rng.md. */
static inline uint32_t dirt_rng_mix(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* Hash of the path prefix (seed, pixel, sample, bounce). Compute it once per
 * path vertex and draw its dimensions with dirt_rng_next. */
static inline uint32_t dirt_rng_key(uint32_t seed, uint32_t pixel,
                                    uint32_t sample, uint32_t bounce)
{
    uint32_t h = dirt_rng_mix(seed + 0x9e3779b9u);
    h = dirt_rng_mix(h ^ pixel);
    h = dirt_rng_mix(h ^ sample);
    h = dirt_rng_mix(h ^ bounce);
    return h;
}

/* The 32-bit random number of dimension `dim` under `key`. Dimensions are
 * spread by the golden-ratio constant before mixing: consecutive dimensions
 * then differ in many input bits (a plain xor of dim leaves a measurable
 * correlation between dims 2i and 2i+1 after one round; doc/rng.md). */
static inline uint32_t dirt_rng_next(uint32_t key, uint32_t dim)
{
    return dirt_rng_mix(key + dim * 0x9e3779b9u);
}

/* Top 24 bits of x scaled by 2^-24: a float in [0, 1), every value exactly
 * representable, so the CPU and the GPU agree bit for bit. */
static inline float dirt_rng_to_float(uint32_t x)
{
    return (float)(x >> 8) * (1.0f / 16777216.0f);
}

/* The whole function in one call: uint32 of (seed, pixel, sample, bounce, dim). */
static inline uint32_t dirt_rng_u32(uint32_t seed, uint32_t pixel, uint32_t sample,
                                    uint32_t bounce, uint32_t dim)
{
    return dirt_rng_next(dirt_rng_key(seed, pixel, sample, bounce), dim);
}

/* The same as a float in [0, 1). */
static inline float dirt_rng_float(uint32_t seed, uint32_t pixel, uint32_t sample,
                                   uint32_t bounce, uint32_t dim)
{
    return dirt_rng_to_float(dirt_rng_u32(seed, pixel, sample, bounce, dim));
}

/* Float of dimension `dim` under a precomputed key. */
static inline float dirt_rng_next_float(uint32_t key, uint32_t dim)
{
    return dirt_rng_to_float(dirt_rng_next(key, dim));
}

/* The uniform number in [0, 1) that decides whether primitive `prim` is
 * seen by the ray of `ray_key` (= dirt_rng_u32(seed, pixel, sample, bounce,
 * DIRT_RNG_DIM_ALPHA_*)): a pure function of the ray's key and the
 * primitive, so it does not matter how often or in which order a traversal
 * tests the primitive. */
static inline float dirt_rng_alpha(uint32_t ray_key, uint32_t prim)
{
    return dirt_rng_to_float(dirt_rng_next(ray_key, prim));
}

#endif
