// Alpha-tested traversal, the GLSL twin of src/integrator/alpha.c
// (doc/light-transport.md section 1, "Alpha"; doc/rng.md, "Alpha"). Include
// file (no #version) for the trace passes: it declares the model's material
// and texel tables (integrator/model.glsl with DIRT_MODEL_BUFFERS and
// DIRT_MODEL_SURFACE_ONLY, unless the shader included the full model) and the trace's alpha uniforms, which the host sets from
// a dirt_trace_alpha (core/ray.h).
#ifndef DIRT_ALPHA_GLSL
#define DIRT_ALPHA_GLSL

#ifndef DIRT_MODEL_BUFFERS
#define DIRT_MODEL_BUFFERS 1
#define DIRT_MODEL_SURFACE_ONLY 1 // two storage blocks, not seven
#endif
#include "common/rng.glsl"
#include "integrator/model.glsl"

// enum dirt_alpha_mode (dirt_gpu_model_material.params2.w, exact)
#define DIRT_ALPHA_OPAQUE_G 0.0
#define DIRT_ALPHA_MASK_G 1.0
#define DIRT_ALPHA_BLEND_G 2.0

// 0: every surface is opaque (nothing below is read; the scene has no
// alpha-tested material, or the caller gave no tables).
layout(location = DIRT_LOC_ALPHA_ENABLED) uniform int u_alpha;
// Ray i of the batch has the key dirt_rng_u32(key.x seed, u_alpha_first_pixel
// + i, key.y sample, key.z bounce, key.w dim).
layout(location = DIRT_LOC_ALPHA_KEY) uniform uvec4 u_alpha_key;
layout(location = DIRT_LOC_ALPHA_FIRST_PIXEL) uniform uint u_alpha_first_pixel;

// The BLEND key of ray i of this batch.
uint dirt_alpha_ray_key_g(uint i)
{
    return dirt_rng_u32(u_alpha_key.x, u_alpha_first_pixel + i, u_alpha_key.y, u_alpha_key.z,
                        u_alpha_key.w);
}

// UV at barycentrics (b1, b2) from the vertices' UVs (= tri_uv of
// src/ref/accel.c and src/ref/render.c, operation for operation).
vec2 dirt_alpha_uv_g(vec2 t0, vec2 t1, vec2 t2, float b1, float b2)
{
    precise float b0 = 1.0 - b1 - b2;
    precise float u = b0 * t0.x + b1 * t1.x + b2 * t2.x;
    precise float v = b0 * t0.y + b1 * t1.y + b2 * t2.y;
    return vec2(u, v);
}

// = dirt_material_coverage: base_color.a * T(base colour texture).a, the
// linear lookup (alpha is never decoded).
float dirt_material_coverage_g(uint material, vec2 uv)
{
    // Two members, not the 336-byte record (the trace's inner loop).
    float factor = dirt_model_materials[material].base_color.w;
    vec2 t = dirt_slot_uv_rows_g(dirt_model_materials[material].xf[0],
                                 dirt_model_materials[material].xf[1], uv);
    return factor * dirt_texture_sample_g(dirt_model_materials[material].textures.x, false, t).w;
}

// = dirt_material_alpha_tested.
bool dirt_material_alpha_tested_g(uint material)
{
    float mode = dirt_model_materials[material].params2.w;
    return mode == DIRT_ALPHA_MASK_G || mode == DIRT_ALPHA_BLEND_G;
}

// = dirt_alpha_accept: whether the ray of `ray_key` sees primitive `prim` of
// `material` at uv. OPAQUE: always; MASK: coverage >= cutoff; BLEND:
// dirt_rng_alpha(ray_key, prim) < coverage.
bool dirt_alpha_accept_g(uint material, vec2 uv, uint ray_key, uint prim)
{
    vec4 p2 = dirt_model_materials[material].params2;
    if (p2.w == DIRT_ALPHA_MASK_G)
        return dirt_material_coverage_g(material, uv) >= p2.z;
    if (p2.w == DIRT_ALPHA_BLEND_G)
        return dirt_rng_alpha(ray_key, prim) < dirt_material_coverage_g(material, uv);
    return true;
}

#endif
