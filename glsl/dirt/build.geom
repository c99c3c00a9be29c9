#version 450 core
// DIRT build passes (depth bounds and fill primitives), geometry stage: one
// invocation per view. Emits, in the raster atlas (one pixel per tile, views
// side by side), a quad covering every tile the triangle's near-clipped
// projection touches (conservative rasterization by bounding box; the
// fragment stage clips exactly and discards empty tiles). With
// DIRT_CONSERVATIVE_NV the hardware rasterizes the triangle conservatively
// instead, except for triangles that cross the near plane or are
// (near-)degenerate, which keep the quad.
#include "common/layout.h"

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

layout(location = 0) flat out vec4 g_c0;
layout(location = 1) flat out vec4 g_c1;
layout(location = 2) flat out vec4 g_c2;
layout(location = 3) flat out uint g_prim;
layout(location = 4) flat out int g_view;

void emit(vec2 atlas_px, vec4 c0, vec4 c1, vec4 c2, uint prim, int view)
{
    vec2 atlas = vec2(params.pool.zw);
    gl_Position = vec4(atlas_px / atlas * 2.0 - 1.0, 0.0, 1.0);
    g_c0 = c0;
    g_c1 = c1;
    g_c2 = c2;
    g_prim = prim;
    g_view = view;
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
            g_c0 = c[0];
            g_c1 = c[1];
            g_c2 = c[2];
            g_prim = prim;
            g_view = view;
            EmitVertex();
        }
        EndPrimitive();
        return;
    }
#endif
    emit(base + vec2(lo.x, lo.y), c[0], c[1], c[2], prim, view);
    emit(base + vec2(hi.x, lo.y), c[0], c[1], c[2], prim, view);
    emit(base + vec2(lo.x, hi.y), c[0], c[1], c[2], prim, view);
    emit(base + vec2(hi.x, hi.y), c[0], c[1], c[2], prim, view);
    EndPrimitive();
}
