#version 450 core
// DIRT build, fill pass: one invocation per candidate, after the count pass
// (common/layout.h; launched in rows, common/rows.glsl): one {primitive id,
// next} node per bucket of its range, at the nodes the count pass gave it,
// pushed on the list of (bucket, tile).
// DIRT_NODE_DEPTHS (dirt_ads_opts.node_depths), with u_node_depths set (the
// host's count is at most DIRT_NODE_DEPTH_MAX_NODES): each node's next word
// also carries the primitive's depth range in its bucket (common/layout.h).
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
#ifdef DIRT_NODE_DEPTHS
layout(location = DIRT_LOC_FILL_NODE_DEPTHS) uniform int u_node_depths;
#endif
#define DIRT_CANDIDATES_READONLY
#define DIRT_NODES_WRITEONLY
#include "dirt/structure.glsl"

void main()
{
    uint i = dirt_row_invocation();
    if (i >= min(counters.fill.y, params.cand.x))
        return;
    uvec4 c = dirt_candidate(i);
#ifdef DIRT_NODE_DEPTHS
    uint b0 = c.w & DIRT_CAND_BUCKET_MASK, b1 = (c.w >> 16) & DIRT_CAND_BUCKET_MASK;
#else
    uint b0 = c.w & 0xFFFFu, b1 = c.w >> 16;
#endif
    uint tiles = uint(params.config.w), capacity = params.pool.x;
    for (uint b = b0; b <= b1; b++) {
        uint node = c.z + (b - b0);
        if (node < capacity) {
            uint prev = dirt_head_exchange(b * tiles + c.y, node);
#ifdef DIRT_NODE_DEPTHS
            if (u_node_depths != 0) {
                uint lo = b == b0 ? (c.w >> 12) & 15u : 0u;
                uint hi = b == b1 ? c.w >> 28 : uint(DIRT_NODE_DEPTH_SLABS - 1);
                prev = (prev & DIRT_NODE_NEXT_MASK) | ((lo | hi << 4) << DIRT_NODE_DEPTH_SHIFT);
            }
#endif
            dirt_node_store(node, uvec2(c.x, prev));
        }
    }
}
