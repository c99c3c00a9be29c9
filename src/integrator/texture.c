/* DIRT engine: texture lookups and material evaluation of the light-transport
 * model (doc/light-transport.md, "Textures" and "Materials"). */
#include "integrator/integrator.h"

#include <math.h>
#include <pthread.h>

#include "core/vec3.h"

static float srgb_table[256];
static pthread_once_t srgb_once = PTHREAD_ONCE_INIT;

float dirt_srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static void srgb_table_init(void)
{
    for (int i = 0; i < 256; i++)
        srgb_table[i] = dirt_srgb_to_linear((float)i / 255.0f);
}

/* Wraps integer texel coordinate i into [0, n). */
static int wrap(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

/* Texel (x, y) as linear floats. */
static void texel(const dirt_texture *tex, bool srgb, int x, int y, float out[4])
{
    const uint8_t *p = tex->rgba + ((size_t)y * (size_t)tex->width + (size_t)x) * 4;
    for (int c = 0; c < 3; c++)
        out[c] = srgb ? srgb_table[p[c]] : (float)p[c] / 255.0f;
    out[3] = (float)p[3] / 255.0f;
}

void dirt_texture_sample(const dirt_texture *tex, bool srgb, float u, float v,
                         float out[4])
{
    if (!tex || !tex->rgba || tex->width <= 0 || tex->height <= 0) {
        out[0] = out[1] = out[2] = out[3] = 1.0f;
        return;
    }
    if (srgb)
        pthread_once(&srgb_once, srgb_table_init);
    if (!isfinite(u))
        u = 0.0f;
    if (!isfinite(v))
        v = 0.0f;
    /* Repeat: bring u, v into [0, 1] first so the float -> int conversion
     * below cannot overflow; wrap() handles the -1 and n of the neighbours. */
    u -= floorf(u);
    v -= floorf(v);
    float x = u * (float)tex->width - 0.5f;
    float y = v * (float)tex->height - 0.5f;
    float x0f = floorf(x), y0f = floorf(y);
    float fx = x - x0f, fy = y - y0f;
    int x0 = (int)x0f, y0 = (int)y0f;
    int xa = wrap(x0, tex->width), xb = wrap(x0 + 1, tex->width);
    int ya = wrap(y0, tex->height), yb = wrap(y0 + 1, tex->height);
    float t00[4], t10[4], t01[4], t11[4];
    texel(tex, srgb, xa, ya, t00);
    texel(tex, srgb, xb, ya, t10);
    texel(tex, srgb, xa, yb, t01);
    texel(tex, srgb, xb, yb, t11);
    for (int c = 0; c < 4; c++) {
        float top = t00[c] + (t10[c] - t00[c]) * fx;
        float bottom = t01[c] + (t11[c] - t01[c]) * fx;
        out[c] = top + (bottom - top) * fy;
    }
}

static const dirt_texture *texture_at(const dirt_texture *textures, size_t n, int index)
{
    if (!textures || index < 0 || (size_t)index >= n)
        return NULL;
    return &textures[index];
}

void dirt_tex_transform_matrix(const dirt_tex_transform *xf, float m[6])
{
    if (!xf || !xf->set) {
        m[0] = 1.0f, m[1] = 0.0f, m[2] = 0.0f;
        m[3] = 0.0f, m[4] = 1.0f, m[5] = 0.0f;
        return;
    }
    float c = cosf(xf->rotation), s = sinf(xf->rotation);
    m[0] = xf->scale[0] * c;
    m[1] = xf->scale[1] * s;
    m[2] = xf->offset[0];
    m[3] = -(xf->scale[0] * s);
    m[4] = xf->scale[1] * c;
    m[5] = xf->offset[1];
}

void dirt_tex_transform_apply(const float m[6], float u, float v, float out[2])
{
    if (!isfinite(u))
        u = 0.0f;
    if (!isfinite(v))
        v = 0.0f;
    /* Separate statements: no contraction into fused multiply-adds (the
     * GLSL twin is `precise`). */
    float a = m[0] * u, b = m[1] * v;
    float c = m[3] * u, d = m[4] * v;
    out[0] = (a + b) + m[2];
    out[1] = (c + d) + m[5];
}

/* The uv of slot `slot`'s lookup (its transform applied). */
static void slot_uv(const dirt_material *m, enum dirt_tex_slot slot, float u, float v,
                      float out[2])
{
    float x[6];
    dirt_tex_transform_matrix(&m->xf[slot], x);
    dirt_tex_transform_apply(x, u, v, out);
}

void dirt_material_surface(const dirt_material *m, float specular,
                           const dirt_texture *textures, size_t num_textures,
                           float u, float v, dirt_surface *out)
{
    float bc[4], mr[4], em[4], uv[2];
    const dirt_texture *t;

    t = texture_at(textures, num_textures, m->base_color_tex);
    if (t) {
        slot_uv(m, DIRT_SLOT_BASE_COLOR, u, v, uv);
        dirt_texture_sample(t, true, uv[0], uv[1], bc);
    }
    else
        bc[0] = bc[1] = bc[2] = bc[3] = 1.0f;
    t = texture_at(textures, num_textures, m->metallic_roughness_tex);
    if (t) {
        slot_uv(m, DIRT_SLOT_METALLIC_ROUGHNESS, u, v, uv);
        dirt_texture_sample(t, false, uv[0], uv[1], mr);
    }
    else
        mr[0] = mr[1] = mr[2] = mr[3] = 1.0f;

    out->bsdf.base_color = v3(clamp01(m->base_color[0] * bc[0]), clamp01(m->base_color[1] * bc[1]),
                              clamp01(m->base_color[2] * bc[2]));
    float roughness = clamp01(m->roughness * mr[1]);
    out->bsdf.metallic = clamp01(m->metallic * mr[2]);
    out->bsdf.alpha = roughness * roughness;
    out->bsdf.specular = clamp01(specular * m->specular);
    out->double_sided = m->double_sided;

    /* KHR_materials_specular, _transmission, _ior. */
    float sa[4], sc[4], tr[4];
    t = texture_at(textures, num_textures, m->specular_tex);
    if (t) {
        slot_uv(m, DIRT_SLOT_SPECULAR, u, v, uv);
        dirt_texture_sample(t, false, uv[0], uv[1], sa);
    }
    else
        sa[0] = sa[1] = sa[2] = sa[3] = 1.0f;
    out->bsdf.specular = clamp01(out->bsdf.specular * sa[3]);
    t = texture_at(textures, num_textures, m->specular_color_tex);
    if (t) {
        slot_uv(m, DIRT_SLOT_SPECULAR_COLOR, u, v, uv);
        dirt_texture_sample(t, true, uv[0], uv[1], sc);
    }
    else
        sc[0] = sc[1] = sc[2] = sc[3] = 1.0f;
    float f0 = dirt_ior_f0(m->ior);
    out->bsdf.f0 = v3(clamp01(f0 * m->specular_color[0] * sc[0]),
                      clamp01(f0 * m->specular_color[1] * sc[1]),
                      clamp01(f0 * m->specular_color[2] * sc[2]));
    t = texture_at(textures, num_textures, m->transmission_tex);
    if (t) {
        slot_uv(m, DIRT_SLOT_TRANSMISSION, u, v, uv);
        dirt_texture_sample(t, false, uv[0], uv[1], tr);
    }
    else
        tr[0] = tr[1] = tr[2] = tr[3] = 1.0f;
    out->bsdf.transmission = clamp01(m->transmission * tr[0]);
    out->bsdf.eta = dirt_ior_eta(m->ior);

    float s = m->emissive_strength;
    if (dirt_material_is_emissive(m)) {
        t = texture_at(textures, num_textures, m->emissive_tex);
        if (t) {
            slot_uv(m, DIRT_SLOT_EMISSIVE, u, v, uv);
            dirt_texture_sample(t, true, uv[0], uv[1], em);
        }
        else
            em[0] = em[1] = em[2] = 1.0f;
        out->emission = v3(m->emissive[0] * s * em[0], m->emissive[1] * s * em[1],
                           m->emissive[2] * s * em[2]);
    } else {
        out->emission = v3(0.0f, 0.0f, 0.0f);
    }
}

bool dirt_material_normal_ts(const dirt_material *m, const dirt_texture *textures,
                             size_t num_textures, float u, float v, dirt_vec3 *n_ts)
{
    const dirt_texture *t = texture_at(textures, num_textures, m->normal_tex);
    if (!t)
        return false;
    float c[4], uv[2];
    slot_uv(m, DIRT_SLOT_NORMAL, u, v, uv);
    dirt_texture_sample(t, false, uv[0], uv[1], c);
    float s = m->normal_scale;
    float x = 2.0f * c[0] - 1.0f, y = 2.0f * c[1] - 1.0f;
    dirt_vec3 n = v3_normalize(v3(x * s, y * s, 2.0f * c[2] - 1.0f));
    if (v3_is_zero(n) || !v3_is_finite(n))
        return false;
    *n_ts = n;
    return true;
}

dirt_vec3 dirt_normal_map_apply(dirt_vec3 n, dirt_vec3 t, float w, dirt_vec3 n_ts)
{
    dirt_vec3 tp = v3_sub(t, v3_scale(n, v3_dot(n, t)));
    /* Not finite, zero, or (nearly) along n: what is left is rounding. */
    if (!(v3_length(tp) > 1e-3f * v3_length(t)))
        return n;
    dirt_vec3 to = v3_normalize(tp);
    dirt_vec3 b = v3_scale(v3_cross(n, to), w < 0.0f ? -1.0f : 1.0f);
    dirt_vec3 r = v3_scale(to, n_ts.x);
    r = v3_mad(r, b, n_ts.y);
    r = v3_normalize(v3_mad(r, n, n_ts.z));
    if (v3_is_zero(r) || !v3_is_finite(r))
        return n;
    return r;
}
