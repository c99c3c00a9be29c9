#version 450 core
// Frame graph GPU test, pass 1: values[i] = (i * 37 + seed) % 1000.

layout(local_size_x = 64) in;

layout(std430, binding = 0) writeonly buffer Values { uint values[]; };

layout(location = 0) uniform uint u_count;
layout(location = 1) uniform uint u_seed;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < u_count)
        values[i] = (i * 37u + u_seed) % 1000u;
}
