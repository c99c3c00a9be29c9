// The scene's vertices (dirt_gpu_vertex, vertex k of primitive p is vertex
// 3 p + k) and the material of each primitive, as DIRT, MMRT and Shade read
// them: one storage block each while it fits (DIRT_BIND_VERTICES,
// DIRT_BIND_PRIM_MATERIAL), else split arrays (src/gl/split.h) built
// with DIRT_SPLIT_VERTICES / DIRT_SPLIT_PRIM_MATERIAL parts of
// 2^..._SHIFT primitives: RGBA32F texel buffers of six texels per
// primitive (position, normal of each vertex) at DIRT_UNIT_SPLIT_VERTICES
// + part, R32UI ones at DIRT_UNIT_SPLIT_PRIM_MATERIAL + part. Needs
// common/layout.h.

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
#define DIRT_VERTICES_PART(k, a) \
    layout(binding = DIRT_UNIT_SPLIT_VERTICES + k) uniform samplerBuffer dirt_vertices_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_VERTICES, DIRT_VERTICES_PART, 0)
#define DIRT_VERTICES_FETCH(k, a) \
    if (part == uint(k)) r = texelFetch(dirt_vertices_part##k, t);

// Texel j (0: position, 1: normal) of vertex v.
vec4 dirt_vertex_texel(uint v, uint j)
{
    uint part = (v / 3u) >> uint(DIRT_SPLIT_VERTICES_SHIFT);
    int t = int(2u * (v - 3u * (part << uint(DIRT_SPLIT_VERTICES_SHIFT))) + j);
    vec4 r = vec4(0.0);
#if DIRT_SPLIT_VERTICES == 1
    r = texelFetch(dirt_vertices_part0, t);
#else
    DIRT_SPLIT_EACH(DIRT_SPLIT_VERTICES, DIRT_VERTICES_FETCH, 0)
#endif
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
#define DIRT_PRIM_MATERIAL_PART(k, a) \
    layout(binding = DIRT_UNIT_SPLIT_PRIM_MATERIAL + k) uniform usamplerBuffer \
        dirt_prim_material_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_PRIM_MATERIAL, DIRT_PRIM_MATERIAL_PART, 0)
#define DIRT_PRIM_MATERIAL_FETCH(k, a) \
    if (part == uint(k)) r = texelFetch(dirt_prim_material_part##k, t).x;

uint dirt_prim_material(uint p)
{
    uint part = p >> uint(DIRT_SPLIT_PRIM_MATERIAL_SHIFT);
    int t = int(p - (part << uint(DIRT_SPLIT_PRIM_MATERIAL_SHIFT)));
    uint r = 0u;
#if DIRT_SPLIT_PRIM_MATERIAL == 1
    r = texelFetch(dirt_prim_material_part0, t).x;
#else
    DIRT_SPLIT_EACH(DIRT_SPLIT_PRIM_MATERIAL, DIRT_PRIM_MATERIAL_FETCH, 0)
#endif
    return r;
}
#endif
