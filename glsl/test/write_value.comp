#version 450 core
#include "common/constants.h"
// Test shader: writes TEST_VALUE and TEST_VALUE + 1 (TEST_VALUE is injected
// by the loader; the build-time check gives it a value).
layout(local_size_x = 1) in;
layout(std430, binding = DIRT_BIND_TEST_OUT) buffer Out { uint values[]; };

void main()
{
    values[0] = TEST_VALUE;
    values[1] = TEST_VALUE + 1u;
}
