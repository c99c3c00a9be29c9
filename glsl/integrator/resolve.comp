#version 450 core
// Path tracer: adds each pending next-event (or AO) contribution whose
// shadow ray reached its target unblocked (DIRT_BIND_HITS holds the shadow
// rays' any-hit results; shadow ray i of the event's batch belongs to the
// path of pixel owner[i]).
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_PATHS) buffer Paths {
    dirt_gpu_path paths[];
};
layout(std430, binding = DIRT_BIND_HITS) readonly buffer Hits {
    dirt_gpu_hit hits[];
};
#define DIRT_RAY_BATCH_ALWAYS 1
#include "common/ray_batch.glsl"

layout(location = DIRT_LOC_RESOLVE_PIXELS) uniform uint u_pixels;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_pixels))
        return;
    uint p = dirt_batch_owner(i);
    if (paths[p].pending.w == 0.0)
        return;
    if (hits[i].ids.x == DIRT_NO_HIT)
        paths[p].radiance.xyz += paths[p].pending.xyz;
    paths[p].pending = vec4(0.0);
}
