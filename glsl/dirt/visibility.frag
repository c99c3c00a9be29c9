#version 450 core
// Direct visibility: the visibility buffer texel = (primitive id, the
// barycentric weights of vertices 1 and 2 as float bits, 1 = covered).
layout(location = 0) in vec2 v_bary;
layout(location = 0) out uvec4 out_vis;

void main()
{
    out_vis = uvec4(uint(gl_PrimitiveID), floatBitsToUint(v_bary.x), floatBitsToUint(v_bary.y), 1u);
}
