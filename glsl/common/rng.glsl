// DIRT engine: counter-based RNG, the GLSL twin of src/integrator/rng.h.
//
// Stateless: every random number is a pure function of
// (seed, pixel, sample, bounce, dimension), computed with uint arithmetic
// only, so the GPU integrator and the CPU reference (src/ref) draw the same
// bits for the same path. Specification: doc/rng.md. Change this file and
// src/integrator/rng.h together.
//
//   key   = dirt_rng_key(seed, pixel, sample_index, bounce)
//   u32   = dirt_rng_next(key, dim)          (== dirt_rng_u32(...))
//   float = float(u32 >> 8) * 2^-24          in [0, 1 - 2^-24], exact
//
// pixel = y * width + x, y = 0 the top row; bounce 0 = camera ray, k = the
// decisions at path vertex k. Include file: no #version line.
#ifndef DIRT_RNG_GLSL
#define DIRT_RNG_GLSL

// bounce 0: camera ray
#define DIRT_RNG_DIM_PIXEL_X 0u
#define DIRT_RNG_DIM_PIXEL_Y 1u
#define DIRT_RNG_DIM_LENS_U 2u
#define DIRT_RNG_DIM_LENS_V 3u
// bounce k >= 1: decisions at path vertex k
#define DIRT_RNG_DIM_LIGHT_SELECT 0u
#define DIRT_RNG_DIM_LIGHT_TRI 1u
#define DIRT_RNG_DIM_LIGHT_U 2u
#define DIRT_RNG_DIM_LIGHT_V 3u
#define DIRT_RNG_DIM_LOBE 4u
#define DIRT_RNG_DIM_BSDF_U 5u
#define DIRT_RNG_DIM_BSDF_V 6u
#define DIRT_RNG_DIM_RR 7u
// every bounce k >= 0: keys of the alpha BLEND decisions of the rays leaving
// vertex k (0: the camera); doc/rng.md, "Alpha"
#define DIRT_RNG_DIM_ALPHA_PATH 8u
#define DIRT_RNG_DIM_ALPHA_SHADOW 9u

// One bijective 32-bit mixing round (xor-shifts, odd multipliers mod 2^32).
uint dirt_rng_mix(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Hash of the path prefix (seed, pixel, sample_index, bounce).
uint dirt_rng_key(uint seed, uint pixel, uint sample_index, uint bounce)
{
    uint h = dirt_rng_mix(seed + 0x9e3779b9u);
    h = dirt_rng_mix(h ^ pixel);
    h = dirt_rng_mix(h ^ sample_index);
    h = dirt_rng_mix(h ^ bounce);
    return h;
}

// The 32-bit random number of dimension `dim` under `key` (dimensions spread
// by the golden-ratio constant, wrapping mod 2^32).
uint dirt_rng_next(uint key, uint dim)
{
    return dirt_rng_mix(key + dim * 0x9e3779b9u);
}

// Top 24 bits scaled by 2^-24: exact, identical to the C conversion.
float dirt_rng_to_float(uint x)
{
    return float(x >> 8) * (1.0 / 16777216.0);
}

uint dirt_rng_u32(uint seed, uint pixel, uint sample_index, uint bounce, uint dim)
{
    return dirt_rng_next(dirt_rng_key(seed, pixel, sample_index, bounce), dim);
}

float dirt_rng_float(uint seed, uint pixel, uint sample_index, uint bounce, uint dim)
{
    return dirt_rng_to_float(dirt_rng_u32(seed, pixel, sample_index, bounce, dim));
}

float dirt_rng_next_float(uint key, uint dim)
{
    return dirt_rng_to_float(dirt_rng_next(key, dim));
}

// Decision number of primitive `prim` for the ray of `ray_key`
// (= dirt_rng_alpha of rng.h).
float dirt_rng_alpha(uint ray_key, uint prim)
{
    return dirt_rng_to_float(dirt_rng_next(ray_key, prim));
}

#endif
