#version 450 core
// Hi-Z pyramid of the depth bounds: level DIRT_LEVEL from level DIRT_LEVEL-1
// of every view (z = view). Sizes are ceil(size / 2^level), so a parent
// covers its 2x2 children that exist and odd sizes stay conservative.
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE_2D, local_size_y = DIRT_GROUP_SIZE_2D) in;

layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
#include "common/depth.glsl"

layout(location = DIRT_LOC_MIP_LEVEL) uniform int u_level;

int level_base(dirt_gpu_view v, int d)
{
    return v.level_base[d >> 2][d & 3];
}

ivec2 level_size(dirt_gpu_view v, int d)
{
    return (v.size.zw + (1 << d) - 1) >> d;
}

void main()
{
    dirt_gpu_view v = views[gl_GlobalInvocationID.z];
    int d = u_level;
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = level_size(v, d);
    if (d >= v.placement.z || any(greaterThanEqual(p, size)))
        return;
    ivec2 child = level_size(v, d - 1);
    int cb = level_base(v, d - 1);
    uint lo = DIRT_DEPTH_CLEAR_MIN, hi = DIRT_DEPTH_CLEAR_MAX;
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < 2; i++) {
            ivec2 c = 2 * p + ivec2(i, j);
            if (c.x < child.x && c.y < child.y) {
                uvec2 e = dirt_depth(cb + c.y * child.x + c.x);
                lo = min(lo, e.x);
                hi = max(hi, e.y);
            }
        }
    }
    dirt_depth_store(uint(level_base(v, d) + p.y * size.x + p.x), uvec2(lo, hi));
}
