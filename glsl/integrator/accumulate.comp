#version 450 core
// Path tracer: adds the finished sample of every pixel to the running sums
// (non-finite samples are dropped and counted, like the reference).
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PATHS) readonly buffer Paths {
    dirt_gpu_path paths[];
};
layout(std430, binding = DIRT_BIND_ACCUM) buffer Accum {
    dirt_gpu_accum accum[];
};

layout(location = DIRT_LOC_ACCUM_PIXELS) uniform uint u_pixels;

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p >= u_pixels)
        return;
    dirt_gpu_path s = paths[p];
    vec3 l = s.radiance.xyz;
    bool finite = !any(isnan(l)) && !any(isinf(l));
    dirt_gpu_accum a = accum[p];
    a.color += vec4(finite ? l : vec3(0.0), 1.0);
    if (!finite)
        a.albedo.w += 1.0;
    if ((floatBitsToUint(s.radiance.w) & DIRT_PATH_FIRST_HIT) != 0u) {
        a.albedo.xyz += s.first_albedo.xyz;
        a.normal.xyz += s.first_normal.xyz;
    }
    accum[p] = a;
}
