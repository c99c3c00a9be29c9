#version 450 core
// Frame graph GPU test, pass 2: image(x, y) = values[y * width + x] / 1000 + 0.25.

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Values { uint values[]; };
layout(r32f, binding = 0) writeonly uniform image2D u_image;

layout(location = 0) uniform ivec2 u_size;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, u_size)))
        return;
    uint v = values[p.y * u_size.x + p.x];
    imageStore(u_image, p, vec4(float(v) / 1000.0 + 0.25));
}
