/* DIRT engine: alpha coverage and the traversal's alpha test of the
 * light-transport model (doc/light-transport.md section 1, "Alpha"; the
 * random source in doc/rng.md, "Alpha"). The GLSL twin is
 * glsl/integrator/alpha.glsl. */
#include "integrator/integrator.h"

#include "integrator/rng.h"

float dirt_material_coverage(const dirt_material *m, const dirt_texture *textures,
                             size_t num_textures, float u, float v)
{
    int t = m->base_color_tex;
    if (!textures || t < 0 || (size_t)t >= num_textures)
        return m->base_color[3];
    float c[4], x[6], uv[2];
    /* At the base colour slot's uv (its KHR_texture_transform); the linear
     * lookup: alpha is never decoded, so it equals the sRGB slot's alpha,
     * and the RGB decode is not paid for. */
    dirt_tex_transform_matrix(&m->xf[DIRT_SLOT_BASE_COLOR], x);
    dirt_tex_transform_apply(x, u, v, uv);
    dirt_texture_sample(&textures[t], false, uv[0], uv[1], c);
    return m->base_color[3] * c[3];
}

bool dirt_material_alpha_tested(const dirt_material *m)
{
    return m->alpha_mode == DIRT_ALPHA_MASK || m->alpha_mode == DIRT_ALPHA_BLEND;
}

bool dirt_alpha_accept(const dirt_material *m, const dirt_texture *textures,
                       size_t num_textures, float u, float v, uint32_t ray_key, uint32_t prim)
{
    if (m->alpha_mode == DIRT_ALPHA_MASK)
        return dirt_material_coverage(m, textures, num_textures, u, v) >= m->alpha_cutoff;
    if (m->alpha_mode == DIRT_ALPHA_BLEND)
        return dirt_rng_alpha(ray_key, prim) <
               dirt_material_coverage(m, textures, num_textures, u, v);
    return true;
}

bool dirt_materials_alpha_tested(const dirt_material *materials, size_t count)
{
    for (size_t i = 0; materials && i < count; i++) {
        if (dirt_material_alpha_tested(&materials[i]))
            return true;
    }
    return false;
}
