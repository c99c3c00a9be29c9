#version 450 core
#include "common/constants.h"
// Test shader: busy work for the timing test (test/gpu/test_timing.c).
// Every invocation runs SPIN_STEPS rounds of an integer hash (well under
// llvmpipe's 65,535 loop iterations per invocation) and stores the result,
// so the loop cannot be dropped.
#ifndef SPIN_STEPS
#define SPIN_STEPS 2048
#endif
layout(local_size_x = DIRT_GROUP_SIZE) in;
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer Out { uint values[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    uint h = i;
    for (int k = 0; k < SPIN_STEPS; k++) {
        h ^= h >> 16;
        h *= 0x7feb352du;
        h ^= h >> 15;
        h *= 0x846ca68bu;
        h ^= h >> 16;
        h += uint(k);
    }
    values[i] = h;
}
