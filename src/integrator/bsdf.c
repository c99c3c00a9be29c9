/* DIRT engine: the glTF metallic-roughness BSDF, its sampling, and the small
 * warps shared by the integrators. Specification: doc/light-transport.md.
 * Every function here has a GLSL twin; keep them formula for formula. */
#include "dirt/integrator.h"

#include <math.h>

#include "core/vec3.h"

#define PI_F 3.14159265358979323846f
#define INV_PI_F 0.31830988618379067154f

bool dirt_bsdf_is_delta(const dirt_bsdf *b)
{
    return b->alpha < DIRT_ALPHA_DELTA;
}

/* (1 - c)^5 with c clamped to [0,1]. */
static float schlick_weight(float c)
{
    float m = 1.0f - clamp01(c);
    float m2 = m * m;
    return m2 * m2 * m;
}

float dirt_bsdf_fresnel_dielectric(const dirt_bsdf *b, float c)
{
    return b->specular * (DIRT_DIELECTRIC_F0 + (1.0f - DIRT_DIELECTRIC_F0) * schlick_weight(c));
}

dirt_vec3 dirt_bsdf_fresnel(const dirt_bsdf *b, float c)
{
    float x = schlick_weight(c);
    float fd = b->specular * (DIRT_DIELECTRIC_F0 + (1.0f - DIRT_DIELECTRIC_F0) * x);
    float m = b->metallic;
    dirt_vec3 base = b->base_color;
    return v3((1.0f - m) * fd + m * (base.x + (1.0f - base.x) * x),
              (1.0f - m) * fd + m * (base.y + (1.0f - base.y) * x),
              (1.0f - m) * fd + m * (base.z + (1.0f - base.z) * x));
}

float dirt_ggx_d(float alpha, dirt_vec3 h)
{
    if (h.z <= 0.0f)
        return 0.0f;
    float a2 = alpha * alpha;
    float d = h.z * h.z * (a2 - 1.0f) + 1.0f;
    return a2 / (PI_F * d * d);
}

float dirt_ggx_lambda(float alpha, dirt_vec3 w)
{
    float z2 = w.z * w.z;
    if (z2 <= 0.0f)
        return INFINITY;
    float a2t2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
    return 0.5f * (sqrtf(1.0f + a2t2) - 1.0f);
}

float dirt_ggx_g2(float alpha, dirt_vec3 wo, dirt_vec3 wi)
{
    return 1.0f / (1.0f + dirt_ggx_lambda(alpha, wo) + dirt_ggx_lambda(alpha, wi));
}

float dirt_bsdf_spec_probability(const dirt_bsdf *b, dirt_vec3 wo)
{
    float ws = v3_luminance(dirt_bsdf_fresnel(b, wo.z));
    float wd = (1.0f - b->metallic) * v3_luminance(b->base_color) *
               (1.0f - dirt_bsdf_fresnel_dielectric(b, wo.z));
    float sum = ws + wd;
    return sum > 0.0f ? ws / sum : 0.5f;
}

/* Diffuse factor (without base colour): Lambert behind the dielectric
 * interface, entered and left once: (1 - m) (1 - F_d(wi.z)) (1 - F_d(wo.z)) / pi.
 * Symmetric in wo and wi; its albedo (1 - m)(1 - F_d(wo.z))(1 - avg F_d) never
 * exceeds what the specular lobe leaves over (doc/light-transport.md). */
static float diffuse_factor(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    return (1.0f - b->metallic) * (1.0f - dirt_bsdf_fresnel_dielectric(b, wi.z)) *
           (1.0f - dirt_bsdf_fresnel_dielectric(b, wo.z)) * INV_PI_F;
}

dirt_vec3 dirt_bsdf_eval(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    if (wo.z <= 0.0f || wi.z <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    dirt_vec3 f = v3_scale(b->base_color, diffuse_factor(b, wo, wi));
    if (!dirt_bsdf_is_delta(b)) {
        dirt_vec3 h = v3_normalize(v3_add(wo, wi));
        float d = dirt_ggx_d(b->alpha, h);
        float g = dirt_ggx_g2(b->alpha, wo, wi);
        dirt_vec3 fr = dirt_bsdf_fresnel(b, v3_dot(wo, h));
        f = v3_mad(f, fr, d * g / (4.0f * wo.z * wi.z));
    }
    return f;
}

/* Solid-angle pdf of wi for visible-normal sampling from wo:
 * D(h) G1(wo) / (4 wo.z), h = normalize(wo + wi). */
static float pdf_vndf(float alpha, dirt_vec3 wo, dirt_vec3 wi)
{
    dirt_vec3 h = v3_normalize(v3_add(wo, wi));
    float g1 = 1.0f / (1.0f + dirt_ggx_lambda(alpha, wo));
    return dirt_ggx_d(alpha, h) * g1 / (4.0f * wo.z);
}

float dirt_bsdf_pdf(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    if (wo.z <= 0.0f || wi.z <= 0.0f)
        return 0.0f;
    float p = dirt_bsdf_spec_probability(b, wo);
    float pdf = (1.0f - p) * wi.z * INV_PI_F;
    if (!dirt_bsdf_is_delta(b))
        pdf += p * pdf_vndf(b->alpha, wo, wi);
    return pdf;
}

bool dirt_bsdf_sample_dir(const dirt_bsdf *b, dirt_vec3 wo, float u_lobe,
                          float u1, float u2, dirt_bsdf_sample *out)
{
    if (wo.z <= 0.0f)
        return false;
    float p = dirt_bsdf_spec_probability(b, wo);
    dirt_vec3 wi;
    if (u_lobe < p) {
        if (dirt_bsdf_is_delta(b)) {
            out->wi = v3(-wo.x, -wo.y, wo.z);
            out->weight = v3_scale(dirt_bsdf_fresnel(b, wo.z), 1.0f / p);
            out->pdf = 0.0f;
            out->delta = true;
            return !v3_is_zero(out->weight);
        }
        dirt_vec3 h = dirt_sample_ggx_vndf(b->alpha, wo, u1, u2);
        wi = v3_sub(v3_scale(h, 2.0f * v3_dot(wo, h)), wo);
    } else {
        wi = dirt_sample_cosine(u1, u2);
    }
    if (wi.z <= 0.0f)
        return false;
    float pdf = dirt_bsdf_pdf(b, wo, wi);
    if (!(pdf > 0.0f))
        return false;
    dirt_vec3 f = dirt_bsdf_eval(b, wo, wi);
    out->wi = wi;
    out->weight = v3_scale(f, wi.z / pdf);
    out->pdf = pdf;
    out->delta = false;
    return !v3_is_zero(out->weight) && v3_is_finite(out->weight);
}

dirt_vec3 dirt_sample_cosine(float u1, float u2)
{
    float r = sqrtf(u1);
    float phi = 2.0f * PI_F * u2;
    return v3(r * cosf(phi), r * sinf(phi), sqrtf(fmaxf(0.0f, 1.0f - u1)));
}

dirt_vec3 dirt_sample_ggx_vndf(float alpha, dirt_vec3 wo, float u1, float u2)
{
    /* Stretch wo into the configuration where the microsurface is the unit
     * hemisphere; there the visible normals are uniform on the spherical cap
     * seen from wo: sample it, shift by the view direction, unstretch. */
    dirt_vec3 ws = v3_normalize(v3(alpha * wo.x, alpha * wo.y, wo.z));
    float phi = 2.0f * PI_F * u1;
    float z = (1.0f - u2) * (1.0f + ws.z) - ws.z;
    float sin_t = sqrtf(clamp01(1.0f - z * z));
    dirt_vec3 c = v3(sin_t * cosf(phi), sin_t * sinf(phi), z);
    dirt_vec3 hs = v3_add(c, ws);
    return v3_normalize(v3(alpha * hs.x, alpha * hs.y, fmaxf(hs.z, 0.0f)));
}

void dirt_sample_disk(float u1, float u2, float *x, float *y)
{
    float r = sqrtf(u1);
    float phi = 2.0f * PI_F * u2;
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}

void dirt_sample_triangle(float u1, float u2, float *b1, float *b2)
{
    float s = sqrtf(u1);
    *b1 = 1.0f - s;
    *b2 = u2 * s;
}

void dirt_onb(dirt_vec3 n, dirt_vec3 *t, dirt_vec3 *b)
{
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    *t = v3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    *b = v3(c, s + n.y * n.y * a, -n.y);
}

float dirt_mis_power(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

float dirt_rr_survival(dirt_vec3 beta)
{
    return fminf(1.0f, v3_max_comp(beta));
}
