#version 450 core
// Path tracer: the mean of the accumulation into the display texture
// (texel (x, y) = image pixel (x, y), row 0 = top; rgb mean radiance,
// alpha 1). The same float product as dirt_pt_read on the CPU, so both
// give the same pixels.
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_ACCUM) readonly buffer Accum {
    dirt_gpu_accum accum[];
};
layout(rgba32f, binding = DIRT_UNIT_DISPLAY) uniform writeonly image2D u_display;

layout(location = DIRT_LOC_DISPLAY_PIXELS) uniform uint u_pixels;
layout(location = DIRT_LOC_DISPLAY_WIDTH) uniform int u_width;
layout(location = DIRT_LOC_DISPLAY_INV_SAMPLES) uniform float u_inv_samples;
// Record p of this chunk's accumulation is image pixel u_pixel_offset + p.
layout(location = DIRT_LOC_DISPLAY_PIXEL_OFFSET) uniform uint u_pixel_offset;

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p >= u_pixels)
        return;
    uint pixel = u_pixel_offset + p;
    ivec2 xy = ivec2(int(pixel % uint(u_width)), int(pixel / uint(u_width)));
    imageStore(u_display, xy, vec4(accum[p].color.xyz * u_inv_samples, 1.0));
}
