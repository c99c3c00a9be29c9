#version 450 core
#include "common/constants.h"
// Test shader (test/gpu/test_barriers.c): reads a texture the way the
// window's draw reads the display texture (a texture fetch) and stores one
// texel, so the read is not dropped.
layout(local_size_x = 1) in;
layout(binding = DIRT_UNIT_TEST) uniform sampler2D u_texture;
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer Out {
    vec4 texel;
};

void main()
{
    texel = texelFetch(u_texture, ivec2(0), 0);
}
