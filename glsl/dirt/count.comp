#version 450 core
// DIRT build, count pass: one invocation per candidate the depth pass
// stored (common/layout.h), launched in rows (common/rows.glsl). Its bucket
// range in its tile (DIRT paper eq. 1a/1b, clamped to [0, B-1]; a tile of
// zero depth range puts everything in bucket 0) and its first id node,
// taken from counters.fill.x, which ends as the number of id nodes the fill
// pass needs: the host sizes the node pool from it before the fill pass
// runs. The depth range is the one the depth
// pass min/maxed into the tile's bounds, so it lies inside them.
// DIRT_ADAPTIVE (adaptive depth buckets): the buckets of the fine bins of
// the range's ends through the tile's edges (dirt/structure.glsl), which
// bucket_edges.comp wrote before this pass.
// DIRT_BUCKET_MASKS (dirt_ads_opts.bucket_masks, B <=
// DIRT_BUCKET_MASK_MAX_BUCKETS; common/constants.h): the range's bits
// cleared in the tile's occupancy mask: with uniform buckets those of the
// depth slabs it meets (dirt_mask_slab), with adaptive ones those of its
// buckets (the fill pass gives each of them a node).
// DIRT_NODE_DEPTHS (dirt_ads_opts.node_depths): the range's sub-slabs in its
// first and last buckets in the candidate's w for the fill pass
// (common/layout.h, DIRT_NODE_DEPTH_*).
#include "common/layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#define DIRT_DEPTH_READONLY
#include "common/depth.glsl"
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
#include "dirt/structure.glsl"

void main()
{
    uint i = dirt_row_invocation();
    if (i >= min(counters.fill.y, params.cand.x))
        return;
    uvec4 c = dirt_candidate(i);
    float zmin = uintBitsToFloat(c.z), zmax = uintBitsToFloat(c.w);
    float tmin = uintBitsToFloat(dirt_depth(c.y).x);
    float trange = uintBitsToFloat(dirt_depth(c.y).y) - tmin;
    int B = params.config.z;
    int b0 = 0, b1 = 0;
#ifdef DIRT_ADAPTIVE
    int H = DIRT_ADAPT_FINE * B;
    uint T = uint(params.config.w);
    b0 = dirt_adapt_bucket(c.y, dirt_fine_bin(zmin, tmin, trange, H), B, T);
    b1 = dirt_adapt_bucket(c.y, dirt_fine_bin(zmax, tmin, trange, H), B, T);
#else
    if (trange > 0.0) {
        b0 = clamp(int(floor(float(B) * (zmin - tmin) / trange)), 0, B - 1);
        b1 = clamp(int(floor(float(B) * (zmax - tmin) / trange)), 0, B - 1);
    }
#endif
#ifdef DIRT_BUCKET_MASKS
#ifdef DIRT_ADAPTIVE
    uint bits = dirt_bucket_bits(b0, b1);
#else
    uint bits = dirt_bucket_bits(dirt_mask_slab(zmin, tmin, trange),
                                 dirt_mask_slab(zmax, tmin, trange));
#endif
    dirt_head_and(dirt_bucket_mask_index(c.y, B, uint(params.config.w)), ~bits);
#endif
    uint w = uint(b0) | (uint(b1) << 16);
#ifdef DIRT_NODE_DEPTHS
    // The range's sub-slab in its first bucket and in its last.
#ifdef DIRT_ADAPTIVE
    float qa = dirt_node_depth_q(zmin, tmin, trange, H), qb = dirt_node_depth_q(zmax, tmin, trange, H);
    uint lo = dirt_node_depth_sub(qa, float(dirt_adapt_edge(c.y, b0, B, T)),
                                  float(dirt_adapt_edge(c.y, b0 + 1, B, T)));
    uint hi = dirt_node_depth_sub(qb, float(dirt_adapt_edge(c.y, b1, B, T)),
                                  float(dirt_adapt_edge(c.y, b1 + 1, B, T)));
#else
    float qa = dirt_node_depth_q(zmin, tmin, trange, B), qb = dirt_node_depth_q(zmax, tmin, trange, B);
    uint lo = dirt_node_depth_sub(qa, float(b0), float(b0 + 1));
    uint hi = dirt_node_depth_sub(qb, float(b1), float(b1 + 1));
#endif
    w |= (lo << 12) | (hi << 28);
#endif
    uint first = atomicAdd(counters.fill.x, uint(b1 - b0 + 1));
    dirt_candidate_store_zw(i, uvec2(first, w));
}
