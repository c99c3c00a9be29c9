#version 450 core
// The path tracer's MMRT ray count, run before every MMRT trace of a batch:
// counts the active rays (tmax >= tmin) and, in invocation 0, adds the
// aborted count of the previous MMRT trace (the trace clears it) to the
// render's counters. (Rays leaving a surface already start off it: Shade
// offsets their origins by the tracer's surface_offset along the normal.)
#include "common/layout.h"
#include "common/mmrt_pt_layout.h"
#include "common/ray_batch.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_MMRT_PT_COUNTS) buffer Counts {
    dirt_mmrt_pt_counts counts;
};
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) readonly buffer Counters {
    dirt_mmrt_gpu_counters counters;
};

layout(location = DIRT_LOC_MMRT_PT_RAYS_COUNT) uniform uint u_count;

shared uint s_active;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (gl_LocalInvocationIndex == 0u)
        s_active = 0u;
    barrier();
    if (i == 0u)
        atomicAdd(counts.counts.y, counters.trace.w);
    if (i < dirt_batch_count(u_count) && rays[i].dir_tmax.w >= rays[i].origin_tmin.w)
        atomicAdd(s_active, 1u);
    barrier();
    if (gl_LocalInvocationIndex == 0u && s_active > 0u)
        atomicAdd(counts.counts.x, s_active);
}
