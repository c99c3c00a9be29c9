#version 450 core
#include "common/constants.h"
// Frame graph GPU test, pass 3: colour = (r, 2r, 1 - r, 1), r fetched from
// the image pass 2 wrote, at this fragment's pixel.

layout(binding = DIRT_UNIT_TEST) uniform sampler2D u_image;

layout(location = 0) out vec4 o_color;

void main()
{
    float r = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0).r;
    o_color = vec4(r, r * 2.0, 1.0 - r, 1.0);
}
