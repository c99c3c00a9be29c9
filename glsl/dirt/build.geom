#version 450 core
// DIRT build passes (depth bounds, candidate bound, fetch), geometry stage:
// one invocation per view. Emits, in the raster atlas (one pixel per tile,
// views side by side), a quad covering every tile the triangle's
// near-clipped projection touches (conservative rasterization by bounding
// box; the fragment stage computes the exact range and discards empty
// tiles). With DIRT_CONSERVATIVE_NV the hardware rasterizes the triangle
// conservatively instead, except for triangles that cross the near plane or
// are (near-)degenerate, which keep the quad. The fragment stage gets the
// triangle clipped against the near and far planes (dirt/clip.glsl; with
// DIRT_CLIP_SH the triangle itself). DIRT_PASS_BOUND emits nothing: it adds
// the tiles of the quad to counters.build.x, an upper bound of the
// candidates the depth pass will find (it sizes their buffer). The large
// primitives (dirt/large.glsl) are in no list: the build passes skip them,
// the Fetch does not.
#include "common/layout.h"
#include "dirt/clip.glsl"
#include "dirt/footprint.glsl"

#ifndef DIRT_NUM_VIEWS
#define DIRT_NUM_VIEWS 1
#endif

layout(triangles, invocations = DIRT_NUM_VIEWS) in;
layout(triangle_strip, max_vertices = 4) out;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#include "dirt/large.glsl"

#ifdef DIRT_PASS_BOUND
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
#endif

// The polygon the fragment stage clips (g_n vertices), the primitive, the view.
layout(location = 0) flat out vec4 g_p0;
layout(location = 1) flat out vec4 g_p1;
layout(location = 2) flat out vec4 g_p2;
layout(location = 3) flat out vec4 g_p3;
layout(location = 4) flat out vec4 g_p4;
layout(location = 5) flat out uint g_prim;
layout(location = 6) flat out int g_view;
layout(location = 7) flat out int g_n;

void set_outputs(vec4 poly[5], int poly_n, uint prim, int view)
{
    g_p0 = poly[0];
    g_p1 = poly[1];
    g_p2 = poly[2];
    g_p3 = poly[3];
    g_p4 = poly[4];
    g_prim = prim;
    g_view = view;
    g_n = poly_n;
}

void emit(vec2 atlas_px, vec4 poly[5], int poly_n, uint prim, int view)
{
    vec2 atlas = vec2(params.pool.zw);
    gl_Position = vec4(atlas_px / atlas * 2.0 - 1.0, 0.0, 1.0);
    set_outputs(poly, poly_n, prim, view);
    EmitVertex();
}

void main()
{
    int view = gl_InvocationID;
    dirt_gpu_view v = views[view];
    uint prim = uint(gl_PrimitiveIDIn);
#ifndef DIRT_PASS_FETCH
    if (dirt_is_large(prim))
        return;
#endif
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 c[3];
    for (int i = 0; i < 3; i++)
        c[i] = vp * vec4(dirt_vertex_pos_at(3u * prim + uint(i)), 1.0);

    // The conservative footprint (dirt/footprint.glsl: shared with the
    // compute build, so both examine the same tiles).
    vec2 lo, hi;
    bool crosses_near;
    if (!dirt_footprint(v, params.config.y, c, lo, hi, crosses_near))
        return;
    vec2 tiles = vec2(v.size.xy) / float(params.config.y);

#ifdef DIRT_PASS_BOUND
    // The candidate tiles of the footprint: at least the fragments the quad
    // makes (dirt_footprint_tiles).
    ivec4 r = dirt_footprint_tiles(lo, hi);
    atomicAdd(counters.build.x, uint(r.z) * uint(r.w));
    return;
#endif
    vec4 poly[5];
    int poly_n;
#if defined(DIRT_CLIP_SH) || defined(DIRT_PASS_FETCH)
    poly = vec4[5](c[0], c[1], c[2], c[2], c[2]);
    poly_n = 3;
#else
    dirt_clip_near_far(c, float(DIRT_CLIP_EPS), poly, poly_n);
    if (poly_n < 3)
        return;
#endif

    vec2 base = vec2(float(v.placement.y), 0.0);
#ifdef DIRT_CONSERVATIVE_NV
    vec2 e1 = (c[1].xy / c[1].w - c[0].xy / c[0].w) * tiles;
    vec2 e2 = (c[2].xy / c[2].w - c[0].xy / c[0].w) * tiles;
    float area = abs(e1.x * e2.y - e1.y * e2.x);
    if (!crosses_near && area > 1e-3) {
        // The triangle itself, mapped from the view's NDC to the atlas.
        vec2 atlas = vec2(params.pool.zw);
        for (int i = 0; i < 3; i++) {
            vec2 px = base + (c[i].xy / c[i].w * 0.5 + 0.5) * tiles;
            vec2 ndc = px / atlas * 2.0 - 1.0;
            gl_Position = vec4(ndc * c[i].w, 0.0, c[i].w);
            set_outputs(poly, poly_n, prim, view);
            EmitVertex();
        }
        EndPrimitive();
        return;
    }
#endif
    emit(base + vec2(lo.x, lo.y), poly, poly_n, prim, view);
    emit(base + vec2(hi.x, lo.y), poly, poly_n, prim, view);
    emit(base + vec2(lo.x, hi.y), poly, poly_n, prim, view);
    emit(base + vec2(hi.x, hi.y), poly, poly_n, prim, view);
    EndPrimitive();
}
