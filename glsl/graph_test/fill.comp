#version 450 core
#include "common/constants.h"
// Frame graph GPU test, pass 1: values[i] = (i * 37 + seed) % 1000.

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer Values { uint values[]; };

layout(location = DIRT_LOC_TEST_FILL_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_TEST_FILL_SEED) uniform uint u_seed;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < u_count)
        values[i] = (i * 37u + u_seed) % 1000u;
}
