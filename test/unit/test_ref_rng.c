/* The shared counter-based RNG (src/integrator/rng.h, doc/rng.md).
 *
 * - regression values: computed once from the reference implementation and
 *   frozen here; glsl/common/rng.glsl must produce the same bits (the GPU test
 *   compares them). A change to any of these values is a change of the
 *   specification: update doc/rng.md, the GLSL twin and this table together.
 * - the float conversion is exactly (u32 >> 8) * 2^-24, in [0, 1).
 * - uniformity: mean and a 16-bin chi-square over 1e6 draws along every key
 *   component (pixel, sample, bounce, dimension, seed), and a 16x16 chi-square
 *   of dimension pairs (pixel jitter, light point, BSDF direction). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "check.h"
#include "integrator/rng.h"

struct known {
    uint32_t seed, pixel, sample, bounce, dim, u32;
    float f;
};

static const struct known known_values[] = {
    {0u, 0u, 0u, 0u, 0u, 0x0eaa7511u, 0.0572884679f},
    {0u, 0u, 0u, 0u, 1u, 0x2c3e0b30u, 0.172821701f},
    {1u, 2u, 3u, 4u, 5u, 0xa662d80bu, 0.649945736f},
    {0u, 123456u, 7u, 2u, 6u, 0x8ecdbc81u, 0.557826757f},
    {4294967295u, 4294967295u, 4294967295u, 4294967295u, 4294967295u, 0x5ce88307u, 0.362922847f},
    {42u, 307199u, 1023u, 9u, 3u, 0xfd8b9e39u, 0.990411639f},
};

#define N_DRAWS 1000000
#define BINS 16
/* chi-square critical values at p = 1e-4: 15 degrees of freedom -> 42.6,
 * 255 degrees of freedom -> 339 (Wilson-Hilferty approximation). A correct
 * generator fails one of the checks below with probability ~1e-3 in all, and
 * the inputs are fixed, so the outcome is deterministic. */
#define CHI2_15 42.6
#define CHI2_255 339.0

/* Key component varied along the stream. */
enum axis { AXIS_PIXEL, AXIS_SAMPLE, AXIS_BOUNCE, AXIS_DIM, AXIS_SEED };

static float draw(enum axis a, uint32_t i)
{
    switch (a) {
    case AXIS_PIXEL: return dirt_rng_float(7u, i, 3u, 1u, 5u);
    case AXIS_SAMPLE: return dirt_rng_float(7u, 1234u, i, 1u, 5u);
    case AXIS_BOUNCE: return dirt_rng_float(7u, 1234u, 3u, i, 5u);
    case AXIS_DIM: return dirt_rng_float(7u, 1234u, 3u, 1u, i);
    case AXIS_SEED: return dirt_rng_float(i, 1234u, 3u, 1u, 5u);
    }
    return -1.0f;
}

static void check_axis(enum axis a, const char *name)
{
    long counts[BINS] = {0};
    double sum = 0.0;
    int out_of_range = 0;
    for (uint32_t i = 0; i < N_DRAWS; i++) {
        float u = draw(a, i);
        if (!(u >= 0.0f && u < 1.0f)) {
            out_of_range++;
            continue;
        }
        sum += u;
        counts[(int)(u * BINS)]++;
    }
    double mean = sum / N_DRAWS;
    double expect = (double)N_DRAWS / BINS, chi2 = 0.0;
    for (int b = 0; b < BINS; b++)
        chi2 += (counts[b] - expect) * (counts[b] - expect) / expect;
    fprintf(stderr, "%-7s mean %.5f chi2(15) %.2f\n", name, mean, chi2);
    CHECK(out_of_range == 0);
    /* standard error of the mean: sqrt(1/12 / 1e6) = 2.9e-4; 5 sigma */
    CHECK_NEAR(mean, 0.5, 5 * 2.9e-4);
    CHECK_MSG(chi2 < CHI2_15, "%s: chi2 %.2f", name, chi2);
}

/* Pairs of dimensions used together must be jointly uniform. */
static void check_pair(uint32_t bounce, uint32_t d0, uint32_t d1, const char *name)
{
    static long counts[BINS][BINS];
    for (int i = 0; i < BINS; i++)
        for (int j = 0; j < BINS; j++)
            counts[i][j] = 0;
    for (uint32_t i = 0; i < N_DRAWS; i++) {
        uint32_t key = dirt_rng_key(11u, i % 4096u, i / 4096u, bounce);
        float a = dirt_rng_next_float(key, d0), b = dirt_rng_next_float(key, d1);
        counts[(int)(a * BINS)][(int)(b * BINS)]++;
    }
    double expect = (double)N_DRAWS / (BINS * BINS), chi2 = 0.0;
    for (int i = 0; i < BINS; i++)
        for (int j = 0; j < BINS; j++)
            chi2 += (counts[i][j] - expect) * (counts[i][j] - expect) / expect;
    fprintf(stderr, "pair %-12s chi2(255) %.1f\n", name, chi2);
    CHECK_MSG(chi2 < CHI2_255, "%s: chi2 %.1f", name, chi2);
}

int main(void)
{
    for (size_t i = 0; i < sizeof(known_values) / sizeof(known_values[0]); i++) {
        const struct known *k = &known_values[i];
        uint32_t u = dirt_rng_u32(k->seed, k->pixel, k->sample, k->bounce, k->dim);
        CHECK_MSG(u == k->u32, "key %zu: got 0x%08x, expected 0x%08x", i, u, k->u32);
        CHECK(dirt_rng_float(k->seed, k->pixel, k->sample, k->bounce, k->dim) == k->f);
        uint32_t key = dirt_rng_key(k->seed, k->pixel, k->sample, k->bounce);
        CHECK(dirt_rng_next(key, k->dim) == u);
        CHECK(dirt_rng_next_float(key, k->dim) == k->f);
    }
    /* The mixer is a bijection with mix(0) = 0: the seed constant keeps the
     * all-zero key away from the fixed point. */
    CHECK(dirt_rng_mix(0u) == 0u);
    CHECK(dirt_rng_u32(0, 0, 0, 0, 0) != 0u);

    /* Float conversion: exact 24-bit mantissa, never 1. */
    CHECK(dirt_rng_to_float(0u) == 0.0f);
    CHECK(dirt_rng_to_float(0xffffffffu) == 1.0f - 1.0f / 16777216.0f);
    CHECK(dirt_rng_to_float(0x000000ffu) == 0.0f);
    CHECK(dirt_rng_to_float(0x00000100u) == 1.0f / 16777216.0f);
    CHECK(dirt_rng_to_float(0x80000000u) == 0.5f);

    check_axis(AXIS_PIXEL, "pixel");
    check_axis(AXIS_SAMPLE, "sample");
    check_axis(AXIS_BOUNCE, "bounce");
    check_axis(AXIS_DIM, "dim");
    check_axis(AXIS_SEED, "seed");
    check_pair(0u, DIRT_RNG_DIM_PIXEL_X, DIRT_RNG_DIM_PIXEL_Y, "pixel xy");
    check_pair(2u, DIRT_RNG_DIM_LIGHT_U, DIRT_RNG_DIM_LIGHT_V, "light uv");
    check_pair(1u, DIRT_RNG_DIM_BSDF_U, DIRT_RNG_DIM_BSDF_V, "bsdf uv");
    check_pair(1u, DIRT_RNG_DIM_LOBE, DIRT_RNG_DIM_RR, "lobe rr");
    check_pair(1u, DIRT_RNG_DIM_LIGHT_SELECT, DIRT_RNG_DIM_LIGHT_TRI, "light sel");

    /* Neighbouring keys give unrelated streams: a sample's numbers are not
     * its neighbour's numbers shifted by one dimension. */
    int equal = 0;
    for (uint32_t p = 0; p < 10000; p++)
        for (uint32_t d = 0; d < 7; d++)
            equal += dirt_rng_u32(0, p, 0, 1, d + 1) == dirt_rng_u32(0, p + 1, 0, 1, d);
    CHECK(equal == 0);
    return check_finish();
}
