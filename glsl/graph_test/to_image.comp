#version 450 core
#include "common/constants.h"
// Frame graph GPU test, pass 2: image(x, y) = values[y * width + x] / 1000 + 0.25.

layout(local_size_x = DIRT_GROUP_SIZE_2D, local_size_y = DIRT_GROUP_SIZE_2D) in;

layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer Values { uint values[]; };
layout(r32f, binding = DIRT_UNIT_TEST) writeonly uniform image2D u_image;

layout(location = DIRT_LOC_TEST_TO_IMAGE_SIZE) uniform ivec2 u_size;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, u_size)))
        return;
    uint v = values[p.y * u_size.x + p.x];
    imageStore(u_image, p, vec4(float(v) / 1000.0 + 0.25));
}
