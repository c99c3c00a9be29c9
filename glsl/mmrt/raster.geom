#version 450 core
// MMRT depth bounds and store passes, geometry stage: one invocation per
// view (invocations = views). Emits the triangle in the view's clip space
// with gl_ViewportIndex = view; viewport and scissor `view` are the view's
// rectangle in the no-attachment raster atlas (views side by side), so the
// hardware clips to the view frustum and rasterizes normally: a fragment is
// a pixel-centre sample of the triangle (MMRT rasterizes non-conservatively).
// MMRT_PASS_STORE adds the shading attributes to the varyings.
#include "common/layout.h"
#include "common/mmrt_layout.h"

#ifndef MMRT_NUM_VIEWS
#define MMRT_NUM_VIEWS 1
#endif

layout(triangles, invocations = MMRT_NUM_VIEWS) in;
layout(triangle_strip, max_vertices = 3) out;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};

layout(location = 0) out float g_depth;     // eye-space depth (clip w)
layout(location = 1) flat out int g_view;
#ifdef MMRT_PASS_STORE
layout(location = 2) out vec2 g_bary;       // barycentrics of vertices 1, 2
layout(location = 3) out vec3 g_normal;
layout(location = 4) out vec2 g_uv;
layout(location = 5) flat out uint g_prim;
layout(location = 6) flat out uint g_material;
#endif

void main()
{
    int view = gl_InvocationID;
    dirt_gpu_view v = views[view];
    uint prim = uint(gl_PrimitiveIDIn);
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 c[3];
    for (int i = 0; i < 3; i++)
        c[i] = vp * vec4(dirt_vertex_pos_at(3u * prim + uint(i)), 1.0);
    // Trivial reject: all three vertices outside one frustum plane.
    for (int k = 0; k < 3; k++) {
        if ((c[0][k] > c[0].w && c[1][k] > c[1].w && c[2][k] > c[2].w) ||
            (c[0][k] < -c[0].w && c[1][k] < -c[1].w && c[2][k] < -c[2].w))
            return;
    }
#ifdef MMRT_PASS_STORE
    uint material = dirt_prim_material(prim);
#endif
    for (int i = 0; i < 3; i++) {
        gl_Position = c[i];
        gl_ViewportIndex = view;
        g_depth = c[i].w;
        g_view = view;
#ifdef MMRT_PASS_STORE
        dirt_gpu_vertex vx = dirt_vertex_at(3u * prim + uint(i));
        g_bary = vec2(i == 1 ? 1.0 : 0.0, i == 2 ? 1.0 : 0.0);
        g_normal = vx.normal.xyz;
        g_uv = vec2(vx.position.w, vx.normal.w);
        g_prim = prim;
        g_material = material;
#endif
        EmitVertex();
    }
    EndPrimitive();
}
