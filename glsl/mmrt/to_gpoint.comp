#version 450 core
// The path tracer's MMRT "fetch": no Fetch in the MMRT sense -- the hit's
// data node is the shading point. Converts hit r (dirt_mmrt trace record:
// ids.x primitive, ids.y view, ids.z owner pixel, ids.w data node, bary_t.z
// t) into G_k of its owner in ring slot u_slot: shading normal and material
// from the data node (the fragment's, at its pixel centre). Position: where
// the ray meets the plane of the hit primitive, when it meets it inside the
// pixel of the hit fragment in the hit view (the ray crosses the surface
// there); else (a ray passing within the thickness of the surface without
// crossing it in that pixel) the MMRT hit point, ray origin + t direction.
// The hit's t becomes the distance used (Shade's MIS weight of an emitter
// hit reads it), and its barycentrics those of the shading point (projected
// on the primitive's plane), from which Shade interpolates the texture uv
// and the tangents. Not the MMRT point alone: it lies at the fragment's depth, and where a surface is seen at a grazing angle its
// depth changes across the pixel by far more than the thickness, so the
// point is off the surface by up to half of that change along the ray (in
// the Cornell box seen from above the ceiling, up to 5 units, through the
// light 0.9 under it: lit from below, a bright line on the ceiling's top,
// relMSE 46 against Embree at 96x72). Misses are written as DIRT's Fetch
// writes them.
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "mmrt/abuffer.glsl"
#include "common/geometry.glsl"
#include "common/ray_batch.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_HITS) buffer Hits {
    dirt_gpu_hit hits[];
};
layout(std430, binding = DIRT_BIND_GPOINTS) writeonly buffer Gpoints {
    dirt_gpu_gpoint gpoints[];
};
#define MMRT_HEADS_READONLY
#define MMRT_TAILS_READONLY
#define MMRT_IDS_READONLY
#define MMRT_DATA_READONLY
#include "mmrt/arrays.glsl"

layout(location = DIRT_LOC_MMRT_TO_GPOINT_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_MMRT_TO_GPOINT_SLOT) uniform uint u_slot;

// Pixels by which the plane point may lie outside the fragment's pixel
// (float rounding of the projection; the march cuts rays exactly at pixel
// borders).
#define PIXEL_MARGIN 0.01

// t where the ray o + t d meets the plane of triangle (a, b, c) inside
// global pixel `gpix` of view `vi`; -1 when it does not.
float plane_t_in_pixel(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c, uint vi, uint gpix)
{
    vec3 n = cross(b - a, c - a);
    float den = dot(n, d);
    if (den == 0.0)
        return -1.0;
    float t = dot(n, a - o) / den;
    if (!(t > 0.0) || isinf(t))
        return -1.0;
    dirt_gpu_view v = views[vi];
    vec4 cp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]) *
              vec4(o + t * d, 1.0);
    if (!(cp.w > 0.0))
        return -1.0;
    vec2 s = (cp.xy / cp.w * 0.5 + 0.5) * vec2(v.size.xy);
    int l = int(gpix) - v.placement.x;
    vec2 px = vec2(float(l % v.size.x), float(l / v.size.x));
    bool inside = all(greaterThanEqual(s, px - PIXEL_MARGIN)) &&
                  all(lessThanEqual(s, px + 1.0 + PIXEL_MARGIN));
    return inside ? t : -1.0;
}

// Barycentrics (of vertices 1 and 2) of the projection of point q on the
// plane of triangle (a, b, c); (0, 0) for a degenerate triangle.
vec2 plane_barycentrics(vec3 q, vec3 a, vec3 b, vec3 c)
{
    vec3 e1 = b - a, e2 = c - a, e = q - a;
    float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    float d1 = dot(e, e1), d2 = dot(e, e2);
    float den = d11 * d22 - d12 * d12;
    if (!(den > 0.0))
        return vec2(0.0);
    return vec2(d22 * d1 - d12 * d2, d11 * d2 - d12 * d1) / den;
}

void main()
{
    uint r = gl_GlobalInvocationID.x;
    if (r >= dirt_batch_count(u_count))
        return;
    dirt_gpu_hit h = hits[r];
    uint slot = 3u * h.ids.z + u_slot;
    dirt_gpu_ray ray = rays[r];
    dirt_gpu_gpoint g;
    uint p = h.ids.x;
    if (p == DIRT_NO_HIT) {
        g.pos_prim = vec4(0.0, 0.0, 0.0, uintBitsToFloat(DIRT_NO_HIT));
        g.n_mat = vec4(0.0);
        gpoints[slot] = g;
        return;
    }
    dirt_mmrt_gpu_data d = mmrt_data(h.ids.w);
    vec3 a = dirt_vertex_pos_at(3u * p), b = dirt_vertex_pos_at(3u * p + 1u),
         c = dirt_vertex_pos_at(3u * p + 2u);
    vec3 ns = mmrt_unpack_normal(d.ids.z);
    if (any(isnan(ns)))
        ns = dirt_geometric_normal(a, b, c);
    float t = plane_t_in_pixel(ray.origin_tmin.xyz, ray.dir_tmax.xyz, a, b, c, h.ids.y, d.ids.w);
    if (t < 0.0)
        t = h.bary_t.z;
    vec3 pos = ray.origin_tmin.xyz + t * ray.dir_tmax.xyz;
    hits[r].bary_t = vec4(plane_barycentrics(pos, a, b, c), t, h.bary_t.w);
    g.pos_prim = vec4(pos, uintBitsToFloat(p));
    g.n_mat = vec4(ns, uintBitsToFloat(d.ids.y));
    gpoints[slot] = g;
}
