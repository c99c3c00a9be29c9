// The scene's vertices (dirt_gpu_vertex, vertex k of primitive p is vertex
// 3 p + k) and the material of each primitive, as DIRT, MMRT and Shade read
// them: one storage block each while it fits (DIRT_BIND_VERTICES,
// DIRT_BIND_PRIM_MATERIAL), else split arrays (src/gl/split.h) built
// with DIRT_SPLIT_VERTICES / DIRT_SPLIT_PRIM_MATERIAL parts of
// 2^..._SHIFT primitives: RGBA32F texel buffers of six texels per
// primitive (position, normal of each vertex) at DIRT_UNIT_SPLIT_VERTICES
// + part, R32UI ones at DIRT_UNIT_SPLIT_PRIM_MATERIAL + part
// (common/split.glsl). Needs common/layout.h.


#ifndef DIRT_SPLIT_VERTICES
#define DIRT_SPLIT_VERTICES 0
#define DIRT_SPLIT_VERTICES_SHIFT 0
#endif
#ifndef DIRT_SPLIT_PRIM_MATERIAL
#define DIRT_SPLIT_PRIM_MATERIAL 0
#define DIRT_SPLIT_PRIM_MATERIAL_SHIFT 0
#endif

#if DIRT_SPLIT_VERTICES == 0
layout(std430, binding = DIRT_BIND_VERTICES) readonly buffer Vertices {
    dirt_gpu_vertex vertices[];
};

// Vertex v (= 3 p + k).
dirt_gpu_vertex dirt_vertex_at(uint v)
{
    return vertices[v];
}

vec3 dirt_vertex_pos_at(uint v)
{
    return vertices[v].position.xyz;
}
#else
DIRT_SPLIT_SAMPLERS(DIRT_SPLIT_VERTICES, DIRT_UNIT_SPLIT_VERTICES, samplerBuffer, dirt_vertices)

// Texel j (0: position, 1: normal) of vertex v.
vec4 dirt_vertex_texel(uint v, uint j)
{
    DIRT_SPLIT_AT(v / 3u, DIRT_SPLIT_VERTICES_SHIFT, 6u)
    t += int(2u * (v % 3u) + j);
    vec4 r = vec4(0.0);
    DIRT_SPLIT_LOAD(DIRT_SPLIT_VERTICES, r, texelFetch, dirt_vertices, .xyzw)
    return r;
}

dirt_gpu_vertex dirt_vertex_at(uint v)
{
    dirt_gpu_vertex r;
    r.position = dirt_vertex_texel(v, 0u);
    r.normal = dirt_vertex_texel(v, 1u);
    return r;
}

vec3 dirt_vertex_pos_at(uint v)
{
    return dirt_vertex_texel(v, 0u).xyz;
}
#endif

#if DIRT_SPLIT_PRIM_MATERIAL == 0
layout(std430, binding = DIRT_BIND_PRIM_MATERIAL) readonly buffer PrimMaterial {
    uint prim_material[];
};

uint dirt_prim_material(uint p)
{
    return prim_material[p];
}
#else
DIRT_SPLIT_SAMPLERS(DIRT_SPLIT_PRIM_MATERIAL, DIRT_UNIT_SPLIT_PRIM_MATERIAL, usamplerBuffer,
                    dirt_prim_material)

uint dirt_prim_material(uint p)
{
    DIRT_SPLIT_AT(p, DIRT_SPLIT_PRIM_MATERIAL_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_PRIM_MATERIAL, r, texelFetch, dirt_prim_material, .x)
    return r;
}
#endif
