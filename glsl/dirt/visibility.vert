#version 450 core
// Direct visibility: the camera view rasterized with depth test; vertices
// pulled from the vertex buffer, barycentrics interpolated (perspective
// correct) so the fragment knows where on its triangle the pixel centre is.
#include "common/layout.h"

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};

layout(location = DIRT_LOC_VISIBILITY_VIEW) uniform int u_view;

layout(location = 0) out vec2 v_bary;

void main()
{
    dirt_gpu_view v = views[u_view];
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    int k = gl_VertexID % 3;
    v_bary = vec2(k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
    gl_Position = vp * vec4(dirt_vertex_pos_at(uint(gl_VertexID)), 1.0);
}
