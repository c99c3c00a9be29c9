#version 450 core
// Path tracer: the ray sort (dirt_pt_opts.sort_rays; src/integrator/
// ray_sort.c). A counting sort of a ray batch by a key of its origin and
// direction, so that neighbouring invocations of the trace start near each
// other and head the same way. In: the batch at DIRT_BIND_RAY_BATCH (count,
// owners) and its rays at DIRT_BIND_RAYS. Out: the same rays and owners,
// permuted, at DIRT_BIND_SHADOW_RAYS and DIRT_BIND_NEXT_BATCH. Scratch:
// DIRT_BIND_SORT (one counter per bucket, cleared by the host before the
// count pass, then each ray's key). Three passes, chosen by
// DIRT_SORT_PASS:
//   0 count: each ray's key, and the rays per bucket;
//   1 scan: the counts into first slots (one work group); the output
//     batch's header (count, dispatch) copied from the input's;
//   2 scatter: each ray and its owner to the next slot of its bucket.
// The order within a bucket is the order of the scatter's atomics (it
// varies between runs); the image does not depend on it: every decision of
// a path is keyed by its owner pixel, as after compaction.
#include "common/layout.h"

#define DIRT_RAY_BATCH_ALWAYS 1
#include "common/ray_batch.glsl"

#ifdef DIRT_SORT_SCAN
layout(local_size_x = DIRT_SORT_SCAN_GROUP) in;
#else
layout(local_size_x = DIRT_GROUP_SIZE) in;
#endif

layout(std430, binding = DIRT_BIND_SORT) buffer Sort {
    uint sort_offset[DIRT_SORT_BUCKETS];
    uint sort_key[];
};
layout(location = DIRT_LOC_SORT_RAYS) uniform uint u_rays;
layout(location = DIRT_LOC_SORT_BOUNDS_MIN) uniform vec3 u_bmin;
layout(location = DIRT_LOC_SORT_BOUNDS_MAX) uniform vec3 u_bmax;

#ifndef DIRT_SORT_SCAN
layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
#endif
#ifndef DIRT_SORT_COUNT
layout(std430, binding = DIRT_BIND_NEXT_BATCH) buffer NextBatch {
    dirt_gpu_ray_batch next_batch;
    uint next_owner[];
};
#endif
#ifdef DIRT_SORT_SCATTER
layout(std430, binding = DIRT_BIND_SHADOW_RAYS) writeonly buffer NextRays {
    dirt_gpu_ray next_rays[];
};
#endif

// Spreads the low DIRT_SORT_GRID_BITS bits of v to every third bit.
uint spread3(uint v)
{
    uint r = 0u;
    for (int b = 0; b < DIRT_SORT_GRID_BITS; b++)
        r |= ((v >> uint(b)) & 1u) << uint(3 * b);
    return r;
}

#if defined(DIRT_SORT_COUNT)
// The bucket of a ray: its direction's cell on the octahedral map, then the
// Morton code of its origin's cell (origins outside the box clamp to its
// border cells; a non-finite ray lands in some bucket).
uint ray_key(dirt_gpu_ray r)
{
    vec3 d = r.dir_tmax.xyz;
    float l1 = abs(d.x) + abs(d.y) + abs(d.z);
    vec2 o = l1 > 0.0 ? d.xy / l1 : vec2(0.0);
    if (d.z < 0.0)
        o = (1.0 - abs(o.yx)) * vec2(o.x >= 0.0 ? 1.0 : -1.0, o.y >= 0.0 ? 1.0 : -1.0);
    uvec2 dc = uvec2(clamp((o * 0.5 + 0.5) * float(DIRT_SORT_DIR_CELLS), vec2(0.0),
                           vec2(float(DIRT_SORT_DIR_CELLS - 1))));
    vec3 ext = max(u_bmax - u_bmin, vec3(1e-30));
    uvec3 g = uvec3(clamp((r.origin_tmin.xyz - u_bmin) / ext * float(DIRT_SORT_GRID), vec3(0.0),
                          vec3(float(DIRT_SORT_GRID - 1))));
    uint morton = spread3(g.x) | (spread3(g.y) << 1u) | (spread3(g.z) << 2u);
    uint key = ((dc.y * uint(DIRT_SORT_DIR_CELLS) + dc.x) << uint(3 * DIRT_SORT_GRID_BITS)) |
               morton;
    return min(key, uint(DIRT_SORT_BUCKETS - 1));
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_rays))
        return;
    uint k = ray_key(rays[i]);
    sort_key[i] = k;
    atomicAdd(sort_offset[k], 1u);
}
#elif defined(DIRT_SORT_SCAN)
#define PER (DIRT_SORT_BUCKETS / DIRT_SORT_SCAN_GROUP)
shared uint s_sum[DIRT_SORT_SCAN_GROUP];

void main()
{
    uint t = gl_LocalInvocationIndex;
    uint first = t * uint(PER), sum = 0u;
    for (uint b = 0u; b < uint(PER); b++)
        sum += sort_offset[first + b];
    s_sum[t] = sum;
    barrier();
    if (t == 0u) {
        uint run = 0u;
        for (uint j = 0u; j < uint(DIRT_SORT_SCAN_GROUP); j++) {
            uint c = s_sum[j];
            s_sum[j] = run;
            run += c;
        }
        next_batch.dispatch = dirt_ray_batch.dispatch;
    }
    barrier();
    uint run = s_sum[t];
    for (uint b = 0u; b < uint(PER); b++) {
        uint c = sort_offset[first + b];
        sort_offset[first + b] = run;
        run += c;
    }
}
#elif defined(DIRT_SORT_SCATTER)
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_rays))
        return;
    uint slot = atomicAdd(sort_offset[sort_key[i]], 1u);
    next_rays[slot] = rays[i];
    next_owner[slot] = dirt_batch_owner(i);
}
#else
#error "sort.comp: define DIRT_SORT_COUNT, DIRT_SORT_SCAN or DIRT_SORT_SCATTER"
#endif
