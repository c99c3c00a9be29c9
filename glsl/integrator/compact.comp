#version 450 core
// Path tracer, after event k: gathers the paths that go on. Ray i of the
// event's batch (DIRT_BIND_RAY_BATCH) is, after Shade, the ray of event
// k + 1 of its path, inactive (tmax < tmin) when the path ended. The active
// ones are appended to the next batch (DIRT_BIND_NEXT_BATCH, its count
// cleared by the host before): the ray into DIRT_BIND_SHADOW_RAYS (the
// event's shadow rays are spent by now; the host swaps the two ray
// buffers' roles every event) and its owner beside it. One global atomic
// per work group; the order of the entries varies between runs, which
// changes nothing (every decision is keyed by the owner pixel).
//
// With DIRT_COMPACT_FINISH, one invocation instead makes the next batch's
// dispatch from its count and adds the count to the paths of event k + 1
// (DIRT_BIND_PT_EVENTS).
#include "common/layout.h"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_NEXT_BATCH) buffer NextBatch {
    dirt_gpu_ray_batch next_batch;
    uint next_owner[];
};
layout(location = DIRT_LOC_COMPACT_PIXELS) uniform uint u_pixels;
layout(location = DIRT_LOC_COMPACT_EVENT) uniform uint u_event;

#ifdef DIRT_COMPACT_FINISH
layout(std430, binding = DIRT_BIND_PT_EVENTS) buffer Events {
    uint event_paths[];
};

void main()
{
    if (gl_GlobalInvocationID.x != 0u)
        return;
    uint n = next_batch.dispatch.w;
    next_batch.dispatch.xyz = uvec3(max(uint(DIRT_GROUPS(n)), 1u), 1u, 1u);
    if (u_event + 1u < uint(DIRT_PT_MAX_EVENTS))
        event_paths[u_event + 1u] += n;
}
#else
#define DIRT_RAY_BATCH_ALWAYS 1
#include "common/ray_batch.glsl"

layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_SHADOW_RAYS) writeonly buffer NextRays {
    dirt_gpu_ray next_rays[];
};

shared uint s_count, s_base;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (gl_LocalInvocationIndex == 0u)
        s_count = 0u;
    barrier();
    bool live = false;
    dirt_gpu_ray r;
    if (i < dirt_batch_count(u_pixels)) {
        r = rays[i];
        live = r.dir_tmax.w >= r.origin_tmin.w;
    }
    uint slot = live ? atomicAdd(s_count, 1u) : 0u;
    barrier();
    if (gl_LocalInvocationIndex == 0u && s_count > 0u)
        s_base = atomicAdd(next_batch.dispatch.w, s_count);
    barrier();
    if (live) {
        next_rays[s_base + slot] = r;
        next_owner[s_base + slot] = dirt_batch_owner(i);
    }
}
#endif
