#version 450 core
// The path tracer's MMRT ray setup, run before every MMRT trace of a batch:
// copies the batch with tmin raised to u_offset (world distance along the
// ray) so a ray does not hit the surface it leaves within MMRT's thickness,
// and for shadow rays (u_shadow) tmax lowered by the same distance so the
// light's own surface is not hit; a shadow ray shorter than that becomes
// inactive (no hit = unoccluded). Counts the active rays (tmax >= tmin as
// given) and, in invocation 0, adds the aborted count of the previous MMRT
// trace (the trace clears it) to the render's counters.
#include "common/layout.h"
#include "common/mmrt_pt_layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_MMRT_PT_RAYS_OUT) writeonly buffer RaysOut {
    dirt_gpu_ray rays_out[];
};
layout(std430, binding = DIRT_BIND_MMRT_PT_COUNTS) buffer Counts {
    dirt_mmrt_pt_counts counts;
};
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) readonly buffer Counters {
    dirt_mmrt_gpu_counters counters;
};

layout(location = DIRT_LOC_MMRT_PT_RAYS_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_MMRT_PT_RAYS_OFFSET) uniform float u_offset;
layout(location = DIRT_LOC_MMRT_PT_RAYS_SHADOW) uniform int u_shadow;

shared uint s_active;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (gl_LocalInvocationIndex == 0u)
        s_active = 0u;
    barrier();
    if (i == 0u)
        atomicAdd(counts.counts.y, counters.trace.w);
    if (i < u_count) {
        dirt_gpu_ray r = rays[i];
        float tmin = r.origin_tmin.w, tmax = r.dir_tmax.w;
        if (tmax >= tmin) {
            atomicAdd(s_active, 1u);
            float len = length(r.dir_tmax.xyz);
            float off = len > 0.0 ? u_offset / len : 0.0;
            tmin = max(tmin, off);
            if (u_shadow != 0 && !isinf(tmax))
                tmax -= off;
            if (tmax < tmin) {
                tmin = 0.0;
                tmax = -1.0;
            }
        }
        rays_out[i] = dirt_gpu_ray(vec4(r.origin_tmin.xyz, tmin), vec4(r.dir_tmax.xyz, tmax));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && s_active > 0u)
        atomicAdd(counts.counts.x, s_active);
}
