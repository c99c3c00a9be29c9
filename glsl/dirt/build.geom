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
// candidates the depth pass will find (it sizes their buffer).
#include "common/layout.h"
#include "dirt/clip.glsl"

#ifndef DIRT_NUM_VIEWS
#define DIRT_NUM_VIEWS 1
#endif

layout(triangles, invocations = DIRT_NUM_VIEWS) in;
layout(triangle_strip, max_vertices = 4) out;

layout(std430, binding = DIRT_BIND_VERTICES) readonly buffer Vertices {
    dirt_gpu_vertex vertices[];
};
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};

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
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 c[3];
    for (int i = 0; i < 3; i++)
        c[i] = vp * vec4(vertices[3u * prim + uint(i)].position.xyz, 1.0);

    // Trivial reject: all three vertices beyond one plane of the view
    // frustum (moved out a little, so this never rejects a touching one).
    float m = 1.0 + 1e-3;
    if ((c[0].x > m * c[0].w && c[1].x > m * c[1].w && c[2].x > m * c[2].w) ||
        (c[0].x < -m * c[0].w && c[1].x < -m * c[1].w && c[2].x < -m * c[2].w) ||
        (c[0].y > m * c[0].w && c[1].y > m * c[1].w && c[2].y > m * c[2].w) ||
        (c[0].y < -m * c[0].w && c[1].y < -m * c[1].w && c[2].y < -m * c[2].w) ||
        (c[0].z > m * c[0].w && c[1].z > m * c[1].w && c[2].z > m * c[2].w) ||
        (c[0].w < 0.5 * v.eye_near.w && c[1].w < 0.5 * v.eye_near.w &&
         c[2].w < 0.5 * v.eye_near.w))
        return;

    // Clip against w >= near / 2 (nothing nearer can be in a tile frustum)
    // and project what is left to tile coordinates.
    float wmin = 0.5 * v.eye_near.w;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    vec2 tiles = vec2(v.size.xy) / float(params.config.y);
    bool crosses_near = false;
    for (int i = 0; i < 3; i++) {
        vec4 p = c[i], q = c[(i + 1) % 3];
        if (p.w >= wmin) {
            vec2 t = (p.xy / p.w * 0.5 + 0.5) * tiles;
            lo = min(lo, t);
            hi = max(hi, t);
        } else {
            crosses_near = true;
        }
        if ((p.w >= wmin) != (q.w >= wmin)) {
            vec4 s = p + ((wmin - p.w) / (q.w - p.w)) * (q - p);
            vec2 t = (s.xy / wmin * 0.5 + 0.5) * tiles;
            lo = min(lo, t);
            hi = max(hi, t);
        }
    }
    vec2 tmax = vec2(v.size.zw);
    lo = clamp(lo - 0.51, vec2(0.0), tmax);
    hi = clamp(hi + 0.51, vec2(0.0), tmax);
    if (lo.x >= hi.x || lo.y >= hi.y)
        return;

#ifdef DIRT_PASS_BOUND
    // Tile centres in the quad widened by 0.01 (vertex snapping): at least
    // the fragments it makes (and those of the hardware conservative path,
    // whose tiles meet the triangle, so their centres lie within 0.5 of it).
    vec2 n = max(floor(hi + 0.01 - 0.5) - ceil(lo - 0.01 - 0.5) + 1.0, vec2(0.0));
    atomicAdd(counters.build.x, uint(n.x) * uint(n.y));
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
