#version 450 core
// DIRT build, count pass: one invocation per candidate the depth pass
// stored (common/layout.h). Its bucket range in its tile (DIRT paper eq.
// 1a/1b, clamped to [0, B-1]; a tile of zero depth range puts everything in
// bucket 0) and its first id node, taken from counters.fill.x, which ends as
// the number of id nodes the fill pass needs: the host sizes the node pool
// from it before the fill pass runs. The depth range is the one the depth
// pass min/maxed into the tile's bounds, so it lies inside them.
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
layout(std430, binding = DIRT_BIND_DEPTH) readonly buffer Depth {
    uvec2 depth[];
};
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
layout(std430, binding = DIRT_BIND_CANDIDATES) buffer Candidates {
    uvec4 candidates[];
};

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= min(counters.fill.y, params.cand.x))
        return;
    uvec4 c = candidates[i];
    float zmin = uintBitsToFloat(c.z), zmax = uintBitsToFloat(c.w);
    float tmin = uintBitsToFloat(depth[c.y].x);
    float trange = uintBitsToFloat(depth[c.y].y) - tmin;
    int B = params.config.z;
    int b0 = 0, b1 = 0;
    if (trange > 0.0) {
        b0 = clamp(int(floor(float(B) * (zmin - tmin) / trange)), 0, B - 1);
        b1 = clamp(int(floor(float(B) * (zmax - tmin) / trange)), 0, B - 1);
    }
    uint first = atomicAdd(counters.fill.x, uint(b1 - b0 + 1));
    candidates[i].zw = uvec2(first, uint(b0) | (uint(b1) << 16));
}
