#version 450 core
// DIRT build, adaptive depth buckets (common/constants.h, DIRT_ADAPT_*;
// doc/dirt-build.md, "Adaptive depth buckets"), second half: one
// invocation per tile turns its histogram of range ends (bucket_hist.comp;
// C = 2 x its candidates in all) into its bucket edges at equal-count
// quantiles: e(b), b in 1..B-1, is the smallest fine-bin index k whose bins
// below it hold at least ceil(b C / B) of the ends (0 for an empty tile),
// so about C / B range ends lie in each bucket. Writes the packed
// edges; the histogram is left as it is (the next build's clear resets it).
#include "common/layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#include "dirt/structure.glsl"

void main()
{
    uint t = dirt_row_invocation();
    uint T = uint(params.config.w);
    if (t >= T)
        return;
    int B = params.config.z, H = DIRT_ADAPT_FINE * B;
    uint hist = uint(B + DIRT_ADAPT_EDGE_WORDS(B)) * T + t * uint(H);
    uint edges = uint(B) * T + t * uint(DIRT_ADAPT_EDGE_WORDS(B));
    // (counts: the stored value + 1, from the clear value DIRT_LIST_END)
    double C = 0.0;
    for (int k = 0; k < H; k++)
        C += double(dirt_head(hist + uint(k)) + 1u);
    // Walk the cumulative coverage once; edge b is placed at the first k
    // where cum(k) >= q(b) = ceil(b C / B).
    double cum = 0.0;
    int b = 1;
    uint word = 0u;
    for (int k = 0; k <= H && b < B; k++) {
        while (b < B && cum >= ceil(double(b) * C / double(B))) {
            if ((b & 1) != 0) {
                word = uint(k);
            } else {
                word |= uint(k) << 16;
                dirt_head_exchange(edges + uint(b - 1) / 2u, word);
            }
            b++;
        }
        if (k < H)
            cum += double(dirt_head(hist + uint(k)) + 1u);
    }
    if ((B & 1) == 0 && B > 1)
        dirt_head_exchange(edges + uint(B - 2) / 2u, word);
}
