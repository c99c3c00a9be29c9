#version 450 core
// DIRT build, adaptive depth buckets (common/constants.h, DIRT_ADAPT_*;
// doc/dirt-build.md, "Adaptive depth buckets"), first half, before the
// count pass: one invocation per stored candidate adds 1 to the fine bin
// of each end of its depth range in its tile (twice to one bin when both
// ends lie in it): the tile's histogram of range ends, after the heads and
// edges in the list-heads array, counted up from the clear value.
// Order-independent: the sums are the same whatever the atomics' order.
#include "common/layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#define DIRT_DEPTH_READONLY
#include "common/depth.glsl"
layout(std430, binding = DIRT_BIND_COUNTERS) readonly buffer Counters {
    dirt_gpu_ads_counters counters;
};
#define DIRT_CANDIDATES_READONLY
#include "dirt/structure.glsl"

void main()
{
    uint i = dirt_row_invocation();
    if (i >= min(counters.fill.y, params.cand.x))
        return;
    uvec4 c = dirt_candidate(i);
    float zlo = uintBitsToFloat(dirt_depth(c.y).x);
    float range = uintBitsToFloat(dirt_depth(c.y).y) - zlo;
    int B = params.config.z, H = DIRT_ADAPT_FINE * B;
    uint T = uint(params.config.w);
    int f0 = dirt_fine_bin(uintBitsToFloat(c.z), zlo, range, H);
    int f1 = dirt_fine_bin(uintBitsToFloat(c.w), zlo, range, H);
    uint base = uint(B + DIRT_ADAPT_EDGE_WORDS(B)) * T + c.y * uint(H);
    dirt_head_add(base + uint(f0), 1u);
    dirt_head_add(base + uint(f1), 1u);
}
