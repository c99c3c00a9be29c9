#version 450 core
// Direct visibility resolve: turns each pixel's visibility texel into the
// pixel's ray (from the view's centre of projection through the visible
// point) and hit record, as the Trace would have written them, so the same
// Fetch builds G_1. Image row 0 is the top; GL's row 0 the bottom. Hits are
// also linked into their tile's hit list (for the raster Fetch).
#include "common/layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
layout(std430, binding = DIRT_BIND_RAYS) writeonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_HITS) writeonly buffer Hits {
    dirt_gpu_hit hits[];
};
layout(std430, binding = DIRT_BIND_HIT_HEADS) buffer HitHeads {
    uint hit_heads[];
};

layout(binding = DIRT_UNIT_VISIBILITY) uniform usampler2D u_vis;
layout(location = DIRT_LOC_VIS_RESOLVE_VIEW) uniform int u_view;

void main()
{
    dirt_gpu_view v = views[u_view];
    uint p = dirt_row_invocation();
    ivec2 size = v.size.xy;
    if (p >= uint(size.x * size.y))
        return;
    ivec2 img = ivec2(int(p) % size.x, int(p) / size.x);
    ivec2 gl = ivec2(img.x, size.y - 1 - img.y);
    uvec4 t = texelFetch(u_vis, gl, 0);
    vec3 eye = v.eye_near.xyz;
    dirt_gpu_hit h;
    if (t.w == 0u) {
        // Nothing visible: the pixel centre's ray, no hit.
        mat4 inv = inverse(mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]));
        vec2 ndc = (vec2(gl) + 0.5) / vec2(size) * 2.0 - 1.0;
        vec4 far_pt = inv * vec4(ndc, 1.0, 1.0);
        vec3 dir = normalize(far_pt.xyz / far_pt.w - eye);
        rays[p].origin_tmin = vec4(eye, 0.0);
        rays[p].dir_tmax = vec4(dir, uintBitsToFloat(0x7F800000u));
        h.ids = uvec4(DIRT_NO_HIT, uint(u_view), p, DIRT_LIST_END);
        h.bary_t = vec4(0.0, 0.0, -1.0, 0.0);
        hits[p] = h;
        return;
    }
    uint prim = t.x;
    float u = uintBitsToFloat(t.y), w = uintBitsToFloat(t.z);
    vec3 pos = (1.0 - u - w) * dirt_vertex_pos_at(3u * prim) +
               u * dirt_vertex_pos_at(3u * prim + 1u) + w * dirt_vertex_pos_at(3u * prim + 2u);
    vec3 d = pos - eye;
    float dist = length(d);
    rays[p].origin_tmin = vec4(eye, 0.0);
    rays[p].dir_tmax = vec4(d / dist, uintBitsToFloat(0x7F800000u));
    ivec2 tile = clamp(gl / params.config.y, ivec2(0), v.size.zw - 1);
    uint next = atomicExchange(hit_heads[uint(v.placement.x + tile.y * v.size.z + tile.x)], p);
    h.ids = uvec4(prim, uint(u_view), p, next);
    h.bary_t = vec4(u, w, dist, 0.0);
    hits[p] = h;
}
