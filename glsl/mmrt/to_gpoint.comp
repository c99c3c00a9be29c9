#version 450 core
// The path tracer's MMRT "fetch": no Fetch in the MMRT sense -- the hit's
// data node is the shading point. Converts hit r (dirt_mmrt trace record:
// ids.x primitive, ids.z owner pixel, ids.w data node, bary_t.z t) into
// G_k of its owner in ring slot u_slot: position = ray origin + t direction
// (the MMRT hit point, within the thickness of the surface), shading normal,
// material and uv from the data node (the fragment's, at its pixel centre),
// geometric normal of the primitive (winding order) from the vertex buffer,
// wo = -ray direction. Misses are written as DIRT's Fetch writes them.
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "mmrt/abuffer.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_VERTICES) readonly buffer Vertices {
    dirt_gpu_vertex vertices[];
};
layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_HITS) readonly buffer Hits {
    dirt_gpu_hit hits[];
};
layout(std430, binding = DIRT_BIND_GPOINTS) writeonly buffer Gpoints {
    dirt_gpu_gpoint gpoints[];
};
layout(std430, binding = DIRT_BIND_MMRT_DATA) readonly buffer Data {
    dirt_mmrt_gpu_data data[];
};

layout(location = DIRT_LOC_MMRT_TO_GPOINT_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_MMRT_TO_GPOINT_SLOT) uniform uint u_slot;

void main()
{
    uint r = gl_GlobalInvocationID.x;
    if (r >= u_count)
        return;
    dirt_gpu_hit h = hits[r];
    uint slot = 3u * h.ids.z + u_slot;
    dirt_gpu_ray ray = rays[r];
    vec3 dir = normalize(ray.dir_tmax.xyz);
    dirt_gpu_gpoint g;
    uint p = h.ids.x;
    if (p == DIRT_NO_HIT) {
        g.pos_prim = vec4(0.0, 0.0, 0.0, uintBitsToFloat(DIRT_NO_HIT));
        g.n_mat = vec4(0.0);
        g.ng_u = vec4(0.0);
        g.wo_v = vec4(-dir, 0.0);
        gpoints[slot] = g;
        return;
    }
    dirt_mmrt_gpu_data d = data[h.ids.w];
    vec3 a = vertices[3u * p].position.xyz, b = vertices[3u * p + 1u].position.xyz,
         c = vertices[3u * p + 2u].position.xyz;
    vec3 ng = cross(b - a, c - a);
    float lg = length(ng);
    ng = lg > 0.0 ? ng / lg : vec3(0.0, 0.0, 1.0);
    vec3 ns = mmrt_unpack_normal(d.ids.z);
    if (any(isnan(ns)))
        ns = ng;
    vec3 pos = ray.origin_tmin.xyz + h.bary_t.z * ray.dir_tmax.xyz;
    g.pos_prim = vec4(pos, uintBitsToFloat(p));
    g.n_mat = vec4(ns, uintBitsToFloat(d.ids.y));
    g.ng_u = vec4(ng, d.attr.z);
    g.wo_v = vec4(-dir, d.attr.w);
    gpoints[slot] = g;
}
