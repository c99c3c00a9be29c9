#version 450 core
// DIRT build, fill pass: one invocation per candidate, after the count pass
// (common/layout.h; launched in rows, common/rows.glsl): one {primitive id,
// next} node per bucket of its range, at the nodes the count pass gave it,
// pushed on the list of (bucket, tile).
// The host sized the pool from the count; nodes past it (none) would be
// skipped.
#include "common/layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
layout(std430, binding = DIRT_BIND_COUNTERS) readonly buffer Counters {
    dirt_gpu_ads_counters counters;
};
#define DIRT_CANDIDATES_READONLY
#define DIRT_NODES_WRITEONLY
#include "dirt/structure.glsl"

void main()
{
    uint i = dirt_row_invocation();
    if (i >= min(counters.fill.y, params.cand.x))
        return;
    uvec4 c = dirt_candidate(i);
    uint b0 = c.w & 0xFFFFu, b1 = c.w >> 16;
    uint tiles = uint(params.config.w), capacity = params.pool.x;
    for (uint b = b0; b <= b1; b++) {
        uint node = c.z + (b - b0);
        if (node < capacity) {
            uint prev = dirt_head_exchange(b * tiles + c.y, node);
            dirt_node_store(node, uvec2(c.x, prev));
        }
    }
}
