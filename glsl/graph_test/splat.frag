#version 450 core
// Frame graph GPU test: an attachment-less raster pass that adds u_add to
// its pixel of an r32ui image with an image atomic (the pattern of DIRT's
// build passes).

layout(r32ui, binding = 0) uniform uimage2D u_counts;

layout(location = 0) uniform uint u_add;

void main()
{
    imageAtomicAdd(u_counts, ivec2(gl_FragCoord.xy), u_add);
}
