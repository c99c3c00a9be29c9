// DIRT engine: the light-transport model in GLSL, the twin of
// src/integrator/integrator.h (src/integrator/bsdf.c, lights.c,
// texture.c). Function for function and formula for formula: every
// dirt_X_g here computes what dirt_X computes in C, with the same operations
// in the same order, so the two differ only by float rounding (GLSL's
// division, sqrt, pow and sin/cos are not correctly rounded). Textures are
// read from the same texels at their own sizes with the C filter's
// operations (doc/light-transport-gpu.md). test/gpu/test_glsl_model.c
// checks GLSL == C. Change both together.
//
// Conventions as in C: BSDF directions are in the local shading frame
// (normal +z, wo and wi point away from the surface, unit length); f is the
// BSDF without the cosine, "weight" is f cos / pdf, pdfs are per solid angle;
// colours linear RGB.
//
// Include file (no #version). Define DIRT_MODEL_BUFFERS before including it
// to get the scene tables (materials, textures, area and punctual lights,
// camera; bindings in common/integrator_layout.h) and the functions that read
// them: dirt_material_surface_g, dirt_texture_sample_g,
// dirt_material_normal_ts_g, dirt_area_lights_select_g (and the tangents,
// dirt_model_tangent_g).
#ifndef DIRT_MODEL_GLSL
#define DIRT_MODEL_GLSL

#include "common/integrator_layout.h"

#define DIRT_PI_G 3.14159265358979323846
#define DIRT_INV_PI_G 0.31830988618379067154
#define DIRT_ALPHA_DELTA_G 1e-3
#define DIRT_DIELECTRIC_F0_G 0.04
#define DIRT_ETA_MATCHED_G 1e-3
#define DIRT_RR_START_VERTEX_G 3
#define DIRT_INFINITY_G uintBitsToFloat(0x7F800000u)

// BSDF parameters at one surface point (= dirt_bsdf).
struct dirt_bsdf_g {
    vec3 base_color; // linear, each in [0,1]
    float metallic;  // [0,1]
    float alpha;     // GGX alpha = roughness^2; < DIRT_ALPHA_DELTA_G: mirror
    float specular;  // dielectric specular weight in [0,1]
    vec3 f0;         // dielectric F0 colour before the weight, each in [0,1]
    float transmission; // [0,1]
    float eta;       // relative ior n(far side) / n(wo's side), > 0
};

// Surface description at a hit (= dirt_surface).
struct dirt_surface_g {
    dirt_bsdf_g bsdf;
    vec3 emission;     // emitted radiance (front side, or both when double_sided)
    bool double_sided;
};

// ---- vector helpers (the operations of src/integrator/vec3.h) ----------

float dirt_clamp01_g(float x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

// Unit vector along a; (0,0,0) stays (0,0,0) (v3_normalize: scale by 1/l).
vec3 dirt_normalize_g(vec3 a)
{
    float l = sqrt(dot(a, a));
    return l > 0.0 ? a * (1.0 / l) : a;
}

float dirt_luminance_g(vec3 a) { return 0.2126 * a.x + 0.7152 * a.y + 0.0722 * a.z; }
bool dirt_is_zero_g(vec3 a) { return a.x == 0.0 && a.y == 0.0 && a.z == 0.0; }
bool dirt_is_finite_g(vec3 a) { return !any(isnan(a)) && !any(isinf(a)); }

// ---- BSDF (bsdf.c) ------------------------------------------------------

bool dirt_bsdf_is_delta_g(dirt_bsdf_g b) { return b.alpha < DIRT_ALPHA_DELTA_G; }

bool dirt_bsdf_transmission_is_delta_g(dirt_bsdf_g b)
{
    return b.alpha < DIRT_ALPHA_DELTA_G || abs(b.eta - 1.0) < DIRT_ETA_MATCHED_G;
}

bool dirt_bsdf_transmits_g(dirt_bsdf_g b) { return b.transmission > 0.0 && b.metallic < 1.0; }

float dirt_max_comp_g(vec3 a) { return max(a.x, max(a.y, a.z)); }

// (1 - c)^5 with c clamped to [0,1].
float dirt_schlick_weight_g(float c)
{
    float m = 1.0 - dirt_clamp01_g(c);
    float m2 = m * m;
    return m2 * m2 * m;
}

// Dielectric Schlick Fresnel per channel: s (f0 + (1 - f0) x(c)).
vec3 dirt_bsdf_fresnel_d_rgb_g(dirt_bsdf_g b, float c)
{
    float x = dirt_schlick_weight_g(c);
    vec3 f0 = b.f0;
    return vec3(b.specular * (f0.x + (1.0 - f0.x) * x), b.specular * (f0.y + (1.0 - f0.y) * x),
                b.specular * (f0.z + (1.0 - f0.z) * x));
}

// The cosine Schlick takes at an interface of relative index eta met at
// cos c from the wo side: c when eta >= 1, else the refracted direction's;
// false on total internal reflection.
bool dirt_interface_cos_g(float eta, float c, out float cf)
{
    cf = c;
    if (eta >= 1.0)
        return true;
    float sin2 = (1.0 - c * c) / (eta * eta);
    if (!(sin2 < 1.0))
        return false;
    cf = sqrt(1.0 - sin2);
    return true;
}

// The interface's Fresnel F_t(c) (RGB), 1 on total internal reflection.
vec3 dirt_bsdf_fresnel_t_rgb_g(dirt_bsdf_g b, float c)
{
    float cf;
    if (!dirt_interface_cos_g(b.eta, c, cf))
        return vec3(1.0);
    return dirt_bsdf_fresnel_d_rgb_g(b, cf);
}

// Dielectric Fresnel F_d(c), scalar (largest channel).
float dirt_bsdf_fresnel_dielectric_g(dirt_bsdf_g b, float c)
{
    return dirt_max_comp_g(dirt_bsdf_fresnel_d_rgb_g(b, c));
}

// The interface's F_t(c), scalar (largest channel).
float dirt_bsdf_fresnel_interface_g(dirt_bsdf_g b, float c)
{
    return dirt_max_comp_g(dirt_bsdf_fresnel_t_rgb_g(b, c));
}

// Fresnel of the whole specular lobe (RGB):
// (1 - m) ((1 - t) F_d(c) + t F_t(c)) + m (base + (1 - base)(1 - c)^5).
vec3 dirt_bsdf_fresnel_g(dirt_bsdf_g b, float c)
{
    float x = dirt_schlick_weight_g(c);
    vec3 fd = dirt_bsdf_fresnel_d_rgb_g(b, c), ft = dirt_bsdf_fresnel_t_rgb_g(b, c);
    float m = b.metallic, t = b.transmission;
    vec3 base = b.base_color;
    return vec3((1.0 - m) * ((1.0 - t) * fd.x + t * ft.x) + m * (base.x + (1.0 - base.x) * x),
                (1.0 - m) * ((1.0 - t) * fd.y + t * ft.y) + m * (base.y + (1.0 - base.y) * x),
                (1.0 - m) * ((1.0 - t) * fd.z + t * ft.z) + m * (base.z + (1.0 - base.z) * x));
}

// GGX normal distribution D(h), h a unit local half vector.
float dirt_ggx_d_g(float alpha, vec3 h)
{
    if (h.z <= 0.0)
        return 0.0;
    float a2 = alpha * alpha;
    float d = h.z * h.z * (a2 - 1.0) + 1.0;
    return a2 / (DIRT_PI_G * d * d);
}

// Smith Lambda of w (G1 = 1 / (1 + Lambda)); +inf when w.z == 0.
float dirt_ggx_lambda_g(float alpha, vec3 w)
{
    float z2 = w.z * w.z;
    if (z2 <= 0.0)
        return DIRT_INFINITY_G;
    float a2t2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
    return 0.5 * (sqrt(1.0 + a2t2) - 1.0);
}

// Height-correlated Smith G2 = 1 / (1 + L(wo) + L(wi)).
float dirt_ggx_g2_g(float alpha, vec3 wo, vec3 wi)
{
    return 1.0 / (1.0 + dirt_ggx_lambda_g(alpha, wo) + dirt_ggx_lambda_g(alpha, wi));
}

// Fresnel of the reflection lobe sampled on its own (= fresnel_opaque):
// (1 - m)(1 - t) F_d(c) + m (base + (1 - base) x(c)).
vec3 dirt_bsdf_fresnel_opaque_g(dirt_bsdf_g b, float c)
{
    float x = dirt_schlick_weight_g(c);
    vec3 fd = dirt_bsdf_fresnel_d_rgb_g(b, c);
    float m = b.metallic, t = b.transmission;
    vec3 base = b.base_color;
    return vec3((1.0 - m) * ((1.0 - t) * fd.x) + m * (base.x + (1.0 - base.x) * x),
                (1.0 - m) * ((1.0 - t) * fd.y) + m * (base.y + (1.0 - base.y) * x),
                (1.0 - m) * ((1.0 - t) * fd.z) + m * (base.z + (1.0 - base.z) * x));
}

// Lobe probabilities from wo (= dirt_bsdf_lobe_probabilities): p_spec,
// p_trans (the interface); diffuse takes max(0, 1 - p_spec - p_trans).
void dirt_bsdf_lobe_probabilities_g(dirt_bsdf_g b, vec3 wo, out float p_spec, out float p_trans)
{
    float m = b.metallic, t = b.transmission;
    float ws = dirt_luminance_g(dirt_bsdf_fresnel_opaque_g(b, wo.z));
    float fd = dirt_bsdf_fresnel_dielectric_g(b, wo.z);
    float wd = (1.0 - m) * (1.0 - t) * dirt_luminance_g(b.base_color) * (1.0 - fd);
    float ft = dirt_bsdf_fresnel_interface_g(b, wo.z);
    float wt = (1.0 - m) * t * (ft + (1.0 - ft) * dirt_luminance_g(b.base_color));
    float sum = ws + wd + wt;
    p_spec = sum > 0.0 ? ws / sum : 0.5;
    p_trans = sum > 0.0 ? wt / sum : 0.0;
}

// Probability of choosing the specular lobe when sampling from wo.
float dirt_bsdf_spec_probability_g(dirt_bsdf_g b, vec3 wo)
{
    float ps, pt;
    dirt_bsdf_lobe_probabilities_g(b, wo, ps, pt);
    return ps;
}

// (1 - m) (1 - t) (1 - F_d(wi.z)) (1 - F_d(wo.z)) / pi.
float dirt_bsdf_diffuse_factor_g(dirt_bsdf_g b, vec3 wo, vec3 wi)
{
    return (1.0 - b.metallic) * (1.0 - b.transmission) *
           (1.0 - dirt_bsdf_fresnel_dielectric_g(b, wi.z)) *
           (1.0 - dirt_bsdf_fresnel_dielectric_g(b, wo.z)) * DIRT_INV_PI_G;
}

// Generalized half vector of a refraction pair: h = normalize(wo + eta wi)
// turned to +z, co = wo.h, ci = wi.h; false unless co > 0 > ci.
bool dirt_refraction_half_g(dirt_bsdf_g b, vec3 wo, vec3 wi, out vec3 h, out float co,
                            out float ci)
{
    h = dirt_normalize_g(wo + wi * b.eta);
    if (h.z < 0.0)
        h = -h;
    co = dot(wo, h);
    ci = dot(wi, h);
    return co > 0.0 && ci < 0.0;
}

// Rough transmission (scalar, without base colour), radiance form:
// (1 - m) t (1 - F_t(wo.h)) D G2 |wo.h| |wi.h| / (wo.z |wi.z| (wo.h + eta wi.h)^2).
float dirt_bsdf_transmission_factor_g(dirt_bsdf_g b, vec3 wo, vec3 wi)
{
    vec3 h;
    float co, ci;
    if (!dirt_refraction_half_g(b, wo, wi, h, co, ci))
        return 0.0;
    float d = dirt_ggx_d_g(b.alpha, h);
    float g = dirt_ggx_g2_g(b.alpha, wo, wi);
    float ft = dirt_bsdf_fresnel_interface_g(b, co);
    float den = co + b.eta * ci;
    return (1.0 - b.metallic) * b.transmission * (1.0 - ft) * d * g * co * -ci /
           (wo.z * -wi.z * den * den);
}

bool dirt_bsdf_has_rough_transmission_g(dirt_bsdf_g b)
{
    return dirt_bsdf_transmits_g(b) && !dirt_bsdf_transmission_is_delta_g(b);
}

// f(wo, wi) of the non-delta part: wi.z > 0 diffuse + GGX reflection
// (diffuse only for a mirror), wi.z < 0 the rough transmission. Zero when
// wo.z <= 0 or wi.z == 0.
vec3 dirt_bsdf_eval_g(dirt_bsdf_g b, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z == 0.0 || isnan(wi.z))
        return vec3(0.0);
    if (wi.z < 0.0) {
        if (!dirt_bsdf_has_rough_transmission_g(b))
            return vec3(0.0);
        return b.base_color * dirt_bsdf_transmission_factor_g(b, wo, wi);
    }
    vec3 f = b.base_color * dirt_bsdf_diffuse_factor_g(b, wo, wi);
    if (!dirt_bsdf_is_delta_g(b)) {
        vec3 h = dirt_normalize_g(wo + wi);
        float d = dirt_ggx_d_g(b.alpha, h);
        float g = dirt_ggx_g2_g(b.alpha, wo, wi);
        vec3 fr = dirt_bsdf_fresnel_g(b, dot(wo, h));
        f = f + fr * (d * g / (4.0 * wo.z * wi.z));
    }
    return f;
}

// Solid-angle pdf of wi for visible-normal sampling: D(h) G1(wo) / (4 wo.z).
float dirt_bsdf_pdf_vndf_g(float alpha, vec3 wo, vec3 wi)
{
    vec3 h = dirt_normalize_g(wo + wi);
    float g1 = 1.0 / (1.0 + dirt_ggx_lambda_g(alpha, wo));
    return dirt_ggx_d_g(alpha, h) * g1 / (4.0 * wo.z);
}

// Solid-angle pdf of a refracted wi (wi.z < 0): G1(wo) (wo.h) D(h) / wo.z
// times eta^2 |wi.h| / (wo.h + eta wi.h)^2.
float dirt_bsdf_pdf_vndf_refract_g(dirt_bsdf_g b, vec3 wo, vec3 wi)
{
    vec3 h;
    float co, ci;
    if (!dirt_refraction_half_g(b, wo, wi, h, co, ci))
        return 0.0;
    float g1 = 1.0 / (1.0 + dirt_ggx_lambda_g(b.alpha, wo));
    float den = co + b.eta * ci;
    return g1 * co * dirt_ggx_d_g(b.alpha, h) / wo.z * (b.eta * b.eta * -ci / (den * den));
}

// The share of the interface lobe that reflects at the microfacet of
// cosine c (= interface_reflect): F_t(c), F_t(wo.z) for a delta transmission.
float dirt_bsdf_interface_reflect_g(dirt_bsdf_g b, vec3 wo, float c)
{
    return dirt_bsdf_fresnel_interface_g(b, dirt_bsdf_transmission_is_delta_g(b) ? wo.z : c);
}

// Solid-angle pdf of dirt_bsdf_sample_dir_g for the non-delta part:
// wi.z > 0 (p_spec + p_trans F_t) pdf_vndf + p_diff wi.z / pi, wi.z < 0
// p_trans (1 - F_t) pdf of the refracted visible normal. Zero when wo.z <= 0
// or wi.z == 0.
float dirt_bsdf_pdf_g(dirt_bsdf_g b, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z == 0.0 || isnan(wi.z))
        return 0.0;
    float p, pt;
    dirt_bsdf_lobe_probabilities_g(b, wo, p, pt);
    if (wi.z < 0.0) {
        if (!(pt > 0.0) || !dirt_bsdf_has_rough_transmission_g(b))
            return 0.0;
        vec3 h;
        float co, ci;
        if (!dirt_refraction_half_g(b, wo, wi, h, co, ci))
            return 0.0;
        return pt * (1.0 - dirt_bsdf_fresnel_interface_g(b, co)) *
               dirt_bsdf_pdf_vndf_refract_g(b, wo, wi);
    }
    float pdf = max(0.0, 1.0 - p - pt) * wi.z * DIRT_INV_PI_G;
    if (!dirt_bsdf_is_delta_g(b)) {
        float ps = p;
        if (pt > 0.0)
            ps += pt * dirt_bsdf_interface_reflect_g(b, wo, dot(wo, dirt_normalize_g(wo + wi)));
        pdf += ps * dirt_bsdf_pdf_vndf_g(b.alpha, wo, wi);
    }
    return pdf;
}

// wo refracted through the microfacet h (wo.h = c > 0) into the side of
// relative index eta: -wo / eta + (c / eta - cos_t) h; false on total
// internal reflection.
bool dirt_refract_dir_g(vec3 wo, vec3 h, float c, float eta, out vec3 wi)
{
    wi = vec3(0.0);
    float sin2 = (1.0 - c * c) / (eta * eta);
    if (!(sin2 < 1.0))
        return false;
    float ct = sqrt(1.0 - sin2);
    wi = h * (c / eta - ct) - wo * (1.0 / eta);
    return true;
}

// ---- warps and frames (bsdf.c) -----------------------------------------

// Cosine-weighted hemisphere about +z; pdf = z / pi.
vec3 dirt_sample_cosine_g(float u1, float u2)
{
    float r = sqrt(u1);
    float phi = 2.0 * DIRT_PI_G * u2;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u1)));
}

// GGX visible normal from wo (wo.z > 0), spherical-cap method.
vec3 dirt_sample_ggx_vndf_g(float alpha, vec3 wo, float u1, float u2)
{
    vec3 ws = dirt_normalize_g(vec3(alpha * wo.x, alpha * wo.y, wo.z));
    float phi = 2.0 * DIRT_PI_G * u1;
    float z = (1.0 - u2) * (1.0 + ws.z) - ws.z;
    float sin_t = sqrt(dirt_clamp01_g(1.0 - z * z));
    vec3 c = vec3(sin_t * cos(phi), sin_t * sin(phi), z);
    vec3 hs = c + ws;
    return dirt_normalize_g(vec3(alpha * hs.x, alpha * hs.y, max(hs.z, 0.0)));
}

// Uniform point on the unit disk.
void dirt_sample_disk_g(float u1, float u2, out float x, out float y)
{
    float r = sqrt(u1);
    float phi = 2.0 * DIRT_PI_G * u2;
    x = r * cos(phi);
    y = r * sin(phi);
}

// Uniform barycentrics on a triangle: point = (1-b1-b2) p0 + b1 p1 + b2 p2.
void dirt_sample_triangle_g(float u1, float u2, out float b1, out float b2)
{
    float s = sqrt(u1);
    b1 = 1.0 - s;
    b2 = u2 * s;
}

// Orthonormal basis (t, b, n) about the unit vector n (Duff et al. 2017).
void dirt_onb_g(vec3 n, out vec3 t, out vec3 b)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Samples wi from wo (= dirt_bsdf_sample_dir): u_lobe < p_spec picks the
// specular lobe, u_lobe >= p_spec + p_diff (p_trans > 0) the interface
// (reflect when the rescaled u_lobe < F_t, else refract), else diffuse;
// (u1, u2) the direction. False when wo.z <= 0, the sample is on the wrong
// side, refraction is impossible or its weight is zero; the outs are then
// unspecified. Delta lobes (pdf 0, delta true): the mirror (F_opaque(wo.z) /
// p_spec), the interface's mirror ((1 - m) t F_t(wo.z) / (p_trans F_t)) and
// the smooth refraction ((1 - m) t base / (eta^2 p_trans)).
bool dirt_bsdf_sample_dir_g(dirt_bsdf_g b, vec3 wo, float u_lobe, float u1, float u2,
                            out vec3 wi, out vec3 weight, out float pdf, out bool delta)
{
    wi = vec3(0.0);
    weight = vec3(0.0);
    pdf = 0.0;
    delta = false;
    if (wo.z <= 0.0)
        return false;
    float p, pt;
    dirt_bsdf_lobe_probabilities_g(b, wo, p, pt);
    float pd = max(0.0, 1.0 - p - pt);
    bool trans = false;
    if (u_lobe < p) {
        if (dirt_bsdf_is_delta_g(b)) {
            wi = vec3(-wo.x, -wo.y, wo.z);
            weight = dirt_bsdf_fresnel_opaque_g(b, wo.z) * (1.0 / p);
            delta = true;
            return !dirt_is_zero_g(weight);
        }
        vec3 h = dirt_sample_ggx_vndf_g(b.alpha, wo, u1, u2);
        wi = h * (2.0 * dot(wo, h)) - wo;
    } else if (pt > 0.0 && u_lobe >= p + pd) {
        float ut = (u_lobe - (p + pd)) / pt;
        float m = b.metallic, t = b.transmission;
        if (dirt_bsdf_transmission_is_delta_g(b)) {
            float fr = dirt_bsdf_fresnel_interface_g(b, wo.z);
            if (ut < fr) {
                if (dirt_bsdf_is_delta_g(b)) {
                    wi = vec3(-wo.x, -wo.y, wo.z);
                    weight = dirt_bsdf_fresnel_t_rgb_g(b, wo.z) * ((1.0 - m) * t / (pt * fr));
                    delta = true;
                    return !dirt_is_zero_g(weight) && dirt_is_finite_g(weight);
                }
                vec3 h = dirt_sample_ggx_vndf_g(b.alpha, wo, u1, u2);
                wi = h * (2.0 * dot(wo, h)) - wo;
            } else {
                if (!dirt_refract_dir_g(wo, vec3(0.0, 0.0, 1.0), wo.z, b.eta, wi))
                    return false;
                weight = b.base_color * ((1.0 - m) * t / (b.eta * b.eta * pt));
                delta = true;
                return wi.z < 0.0 && !dirt_is_zero_g(weight) && dirt_is_finite_g(weight);
            }
        } else {
            vec3 h = dirt_sample_ggx_vndf_g(b.alpha, wo, u1, u2);
            float c = dot(wo, h);
            if (!(c > 0.0))
                return false;
            if (ut < dirt_bsdf_fresnel_interface_g(b, c)) {
                wi = h * (2.0 * c) - wo;
            } else {
                trans = true;
                if (!dirt_refract_dir_g(wo, h, c, b.eta, wi))
                    return false;
            }
        }
    } else {
        wi = dirt_sample_cosine_g(u1, u2);
    }
    if (trans ? !(wi.z < 0.0) : !(wi.z > 0.0))
        return false;
    pdf = dirt_bsdf_pdf_g(b, wo, wi);
    if (!(pdf > 0.0))
        return false;
    vec3 f = dirt_bsdf_eval_g(b, wo, wi);
    weight = f * (abs(wi.z) / pdf);
    return !dirt_is_zero_g(weight) && dirt_is_finite_g(weight);
}

// Power heuristic (exponent 2): a^2 / (a^2 + b^2), 0 when both are 0.
float dirt_mis_power_g(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Russian-roulette survival probability min(1, max component of beta).
float dirt_rr_survival_g(vec3 beta)
{
    return min(1.0, max(beta.x, max(beta.y, beta.z)));
}

// ---- textures and materials (texture.c) -------------------------------

// sRGB decode, exact piecewise formula (= dirt_srgb_to_linear; the texture
// lookup decodes every texel with it).
float dirt_srgb_to_linear_g(float c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

// ---- lights (lights.c) --------------------------------------------------

// Incident light at p from a punctual light: wi unit towards the light, dist
// (+inf for directional), li = intensity x attenuation (glTF range window,
// smooth spot cone s^2). False when li is zero.
bool dirt_punctual_light_g(dirt_gpu_model_light light, vec3 p, out vec3 wi, out float dist,
                           out vec3 li)
{
    wi = vec3(0.0);
    dist = 0.0;
    li = vec3(0.0);
    vec3 color = light.color.xyz;
    int kind = int(light.position.w);
    if (kind == DIRT_MODEL_LIGHT_DIRECTIONAL) {
        vec3 d = dirt_normalize_g(light.direction.xyz);
        if (dirt_is_zero_g(d))
            return false;
        wi = -d;
        dist = DIRT_INFINITY_G;
        li = color;
        return !dirt_is_zero_g(color);
    }
    vec3 to = light.position.xyz - p;
    float d2 = dot(to, to);
    if (!(d2 > 0.0) || isinf(d2) || isnan(d2))
        return false;
    float d = sqrt(d2);
    wi = to * (1.0 / d);
    dist = d;
    float att = 1.0 / d2;
    float range = light.direction.w;
    if (range > 0.0) {
        float r = d / range;
        float r2 = r * r;
        att *= dirt_clamp01_g(1.0 - r2 * r2);
    }
    if (kind == DIRT_MODEL_LIGHT_SPOT) {
        vec3 sd = dirt_normalize_g(light.direction.xyz);
        float cd = -dot(sd, wi); // cosine between spot axis and light -> p
        float co = light.cone.x, ci = light.cone.y;
        float s = dirt_clamp01_g((cd - co) / max(1e-3, ci - co));
        att *= s * s;
    }
    li = color * att;
    return att > 0.0 && !dirt_is_zero_g(color);
}

// ---- camera (lights.c) --------------------------------------------------

// Primary ray through the continuous pixel position (px, py) of a width x
// height image (py = 0 the top edge): pinhole, thin lens (aperture and focus
// distance > 0; lens_u, lens_v mapped by dirt_sample_disk_g) or orthographic.
// dir is unit length.
void dirt_camera_ray_g(dirt_gpu_model_camera cam, int width, int height, float px, float py,
                       float lens_u, float lens_v, out vec3 org, out vec3 dir)
{
    float aspect = cam.right.w > 0.0 ? cam.right.w : float(width) / float(height);
    if (!(aspect > 0.0) || isinf(aspect) || isnan(aspect))
        aspect = 1.0;
    float nx = 2.0 * px / float(width) - 1.0;
    float ny = 1.0 - 2.0 * py / float(height);
    vec3 eye = cam.eye.xyz, fwd = cam.forward.xyz;
    vec3 right = cam.right.xyz, up = cam.up.xyz;
    if (int(cam.eye.w) == DIRT_MODEL_CAMERA_ORTHOGRAPHIC) {
        float ymag = cam.lens.w > 0.0 ? cam.lens.w : 1.0;
        float xmag = cam.lens.z > 0.0 ? cam.lens.z : ymag * aspect;
        org = (eye + right * (nx * xmag)) + up * (ny * ymag);
        dir = dirt_normalize_g(fwd);
        return;
    }
    float th = cam.forward.w; // tanf(0.5 yfov), computed on the CPU
    // d . forward = 1: the point at parameter f along d lies on the plane
    // perpendicular to forward at distance f.
    vec3 d = (fwd + right * (nx * th * aspect)) + up * (ny * th);
    float aperture = cam.lens.x, focus = cam.lens.y;
    if (aperture > 0.0 && focus > 0.0) {
        float lx, ly;
        dirt_sample_disk_g(lens_u, lens_v, lx, ly);
        vec3 focus_p = eye + d * focus;
        vec3 lens = (eye + right * (lx * aperture)) + up * (ly * aperture);
        org = lens;
        dir = dirt_normalize_g(focus_p - lens);
    } else {
        org = eye;
        dir = dirt_normalize_g(d);
    }
}

// ---- normal maps (texture.c) --------------------------------------------

// Shading normal a normal map gives (= dirt_normal_map_apply): n the unit
// interpolated normal (front side), t the interpolated tangent, w its
// handedness (sign): t' = normalize(t - n (n . t)), b = cross(n, t') sign(w),
// normalize(t' n_ts.x + b n_ts.y + n n_ts.z); n itself when |t - n (n . t)|
// is not above 1e-3 |t| (no tangent, or one along n) or the result is zero.
vec3 dirt_normal_map_apply_g(vec3 n, vec3 t, float w, vec3 n_ts)
{
    vec3 tp = t - n * dot(n, t);
    if (!(sqrt(dot(tp, tp)) > 1e-3 * sqrt(dot(t, t))))
        return n;
    vec3 to = dirt_normalize_g(tp);
    vec3 b = cross(n, to) * (w < 0.0 ? -1.0 : 1.0);
    vec3 r = dirt_normalize_g(to * n_ts.x + b * n_ts.y + n * n_ts.z);
    if (dirt_is_zero_g(r) || !dirt_is_finite_g(r))
        return n;
    return r;
}

#ifdef DIRT_MODEL_BUFFERS
// ---- scene tables -------------------------------------------------------

layout(std430, binding = DIRT_BIND_MODEL_MATERIALS) readonly buffer DirtModelMaterials {
    dirt_gpu_model_material dirt_model_materials[];
};
// DIRT_MODEL_SURFACE_ONLY: only the materials and the texels (and the
// functions reading them), for shaders short of storage blocks (the traces'
// alpha test, integrator/alpha.glsl).
#ifndef DIRT_MODEL_SURFACE_ONLY
layout(std430, binding = DIRT_BIND_MODEL_AREA_CDF) readonly buffer DirtModelAreaCdf {
    dirt_gpu_model_lights dirt_model_lights;
    float dirt_model_area_cdf[];
};
layout(std430, binding = DIRT_BIND_MODEL_AREA_PRIMS) readonly buffer DirtModelAreaPrims {
    uint dirt_model_area_prim[];
};
layout(std430, binding = DIRT_BIND_MODEL_PUNCTUAL) readonly buffer DirtModelPunctual {
    dirt_gpu_model_light dirt_model_punctual[];
};
layout(std430, binding = DIRT_BIND_MODEL_CAMERA) readonly buffer DirtModelCamera {
    dirt_gpu_model_camera dirt_model_camera;
};
#endif // DIRT_MODEL_SURFACE_ONLY
// The scene's textures at their own sizes (common/integrator_layout.h):
// the header, then dirt_gpu_model_texture records (4 words each), then the
// RGBA8 texels, one word each; and the frame's tangents
// (dirt_gpu_model_tangent, entry 3 prim + vertex). Each is one storage
// block while it fits (DIRT_BIND_MODEL_TEXELS, _TANGENTS), else a split
// array (src/gl/split.h, integrator/gpu_tables.h; common/split.glsl) of
// DIRT_SPLIT_TEXELS parts of 2^DIRT_SPLIT_TEXELS_SHIFT words (R32UI texel
// buffers at DIRT_UNIT_SPLIT_TEXELS + part) and DIRT_SPLIT_TANGENTS parts
// of 2^..._SHIFT tangents (RGBA32F at DIRT_UNIT_SPLIT_TANGENTS + part).
// Accessors: dirt_model_texel_word_g(k) (word k of the table, header
// included), dirt_model_tangent_g(v), dirt_model_tangent_count_g().
#ifndef DIRT_SPLIT_TEXELS
#define DIRT_SPLIT_TEXELS 0
#define DIRT_SPLIT_TEXELS_SHIFT 0
#endif
#ifndef DIRT_SPLIT_TANGENTS
#define DIRT_SPLIT_TANGENTS 0
#define DIRT_SPLIT_TANGENTS_SHIFT 0
#endif
#if DIRT_SPLIT_TEXELS == 0
layout(std430, binding = DIRT_BIND_MODEL_TEXELS) readonly buffer DirtModelTexels {
    uint dirt_model_texel_table[];
};

uint dirt_model_texel_word_g(uint k)
{
    return dirt_model_texel_table[k];
}
#else
DIRT_SPLIT_SAMPLERS(DIRT_SPLIT_TEXELS, DIRT_UNIT_SPLIT_TEXELS, usamplerBuffer, dirt_model_texels)

uint dirt_model_texel_word_g(uint k)
{
    DIRT_SPLIT_AT(k, DIRT_SPLIT_TEXELS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_TEXELS, r, texelFetch, dirt_model_texels, .x)
    return r;
}
#endif

#ifndef DIRT_MODEL_SURFACE_ONLY
#if DIRT_SPLIT_TANGENTS == 0
layout(std430, binding = DIRT_BIND_MODEL_TANGENTS) readonly buffer DirtModelTangents {
    dirt_gpu_model_tangent dirt_model_tangents[];
};

vec4 dirt_model_tangent_g(uint v)
{
    return dirt_model_tangents[v].tangent;
}

uint dirt_model_tangent_count_g()
{
    return uint(dirt_model_tangents.length());
}
#else
DIRT_SPLIT_SAMPLERS(DIRT_SPLIT_TANGENTS, DIRT_UNIT_SPLIT_TANGENTS, samplerBuffer,
                    dirt_model_tangents)

vec4 dirt_model_tangent_g(uint v)
{
    DIRT_SPLIT_AT(v, DIRT_SPLIT_TANGENTS_SHIFT, 1u)
    vec4 r = vec4(0.0);
    DIRT_SPLIT_LOAD(DIRT_SPLIT_TANGENTS, r, texelFetch, dirt_model_tangents, .xyzw)
    return r;
}

#define DIRT_MODEL_TANGENTS_SIZE_(k, a, b, c, d) n += uint(textureSize(dirt_model_tangents_part##k));
uint dirt_model_tangent_count_g()
{
    uint n = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_TANGENTS, DIRT_MODEL_TANGENTS_SIZE_, 0, 0, 0, 0)
    return n;
}
#endif
#endif // DIRT_MODEL_SURFACE_ONLY

// Record of texture `tex` (0 <= tex < counts.x).
dirt_gpu_model_texture dirt_model_texture_g(uint tex)
{
    uint k = uint(DIRT_MODEL_TEXELS_HEADER_WORDS) + 4u * tex;
    dirt_gpu_model_texture t;
    t.extent = uvec4(dirt_model_texel_word_g(k), dirt_model_texel_word_g(k + 1u),
                     dirt_model_texel_word_g(k + 2u), dirt_model_texel_word_g(k + 3u));
    return t;
}

// The number of textures (the header's counts.x).
uint dirt_model_texture_count_g()
{
    return dirt_model_texel_word_g(0u);
}

// Integer texel coordinate i wrapped into [0, n) (= wrap() of texture.c,
// i % n made non-negative; GLSL's % is undefined for a negative operand, so
// the magnitude is reduced and the sign applied by hand; i > INT_MIN).
int dirt_texel_wrap_g(int i, int n)
{
    int r = (i < 0 ? -i : i) % n;
    return i < 0 && r != 0 ? n - r : r;
}

// Texel (x, y) of a texture whose texel (0, 0) is word `first`, as linear
// floats (= texel() of texture.c): each byte c -> c / 255, RGB then
// sRGB-decoded when `srgb` (alpha never).
vec4 dirt_texel_g(uint first, int width, bool srgb, int x, int y)
{
    uint p = dirt_model_texel_word_g(uint(DIRT_MODEL_TEXELS_HEADER_WORDS) + first +
                                     uint(y) * uint(width) + uint(x));
    vec4 c = vec4(float(p & 255u), float((p >> 8u) & 255u), float((p >> 16u) & 255u),
                  float(p >> 24u)) / 255.0;
    if (srgb)
        c.xyz = vec3(dirt_srgb_to_linear_g(c.x), dirt_srgb_to_linear_g(c.y),
                     dirt_srgb_to_linear_g(c.z));
    return c;
}

// Bilinear, repeating lookup of texture `tex` at uv (= dirt_texture_sample,
// operation for operation): texel (i, j) has its centre at ((i + 0.5) / w,
// (j + 0.5) / h), row 0 = the first image row; the four texels are decoded
// (sRGB RGB when `srgb`, alpha never) before they are filtered. A texture
// index outside [0, count) or a texture without pixels reads (1,1,1,1);
// non-finite u or v read as 0. `precise` keeps every step the separately
// rounded operation C performs (no fused multiply-add), so GPU and C differ
// only by the decode's division and pow.
vec4 dirt_texture_sample_g(int tex, bool srgb, vec2 uv)
{
    if (tex < 0 || uint(tex) >= dirt_model_texture_count_g())
        return vec4(1.0);
    dirt_gpu_model_texture t = dirt_model_texture_g(uint(tex));
    int w = int(t.extent.y), h = int(t.extent.z);
    if (w <= 0 || h <= 0)
        return vec4(1.0);
    precise float u = uv.x, v = uv.y;
    if (isnan(u) || isinf(u))
        u = 0.0;
    if (isnan(v) || isinf(v))
        v = 0.0;
    // Repeat: u, v into [0, 1] first (u of -tiny becomes exactly 1; the
    // wrap of the neighbours handles it).
    u -= floor(u);
    v -= floor(v);
    precise float x = u * float(w) - 0.5;
    precise float y = v * float(h) - 0.5;
    float x0f = floor(x), y0f = floor(y);
    precise float fx = x - x0f, fy = y - y0f;
    int x0 = int(x0f), y0 = int(y0f);
    int xa = dirt_texel_wrap_g(x0, w), xb = dirt_texel_wrap_g(x0 + 1, w);
    int ya = dirt_texel_wrap_g(y0, h), yb = dirt_texel_wrap_g(y0 + 1, h);
    vec4 t00 = dirt_texel_g(t.extent.x, w, srgb, xa, ya);
    vec4 t10 = dirt_texel_g(t.extent.x, w, srgb, xb, ya);
    vec4 t01 = dirt_texel_g(t.extent.x, w, srgb, xa, yb);
    vec4 t11 = dirt_texel_g(t.extent.x, w, srgb, xb, yb);
    precise vec4 top = t00 + (t10 - t00) * fx;
    precise vec4 bottom = t01 + (t11 - t01) * fx;
    precise vec4 r = top + (bottom - top) * fy;
    return r;
}

// The uv of a texture slot whose transform has the rows r0, r1 (xf[2 slot],
// xf[2 slot + 1] of a material record): the rows applied (= dirt_tex_transform_apply of the
// packed dirt_tex_transform_matrix): non-finite u or v read as 0, then
// (m00 u + m01 v) + m02 and (m10 u + m11 v) + m12, each step separately
// rounded.
vec2 dirt_slot_uv_rows_g(vec4 r0, vec4 r1, vec2 uv)
{
    precise float u = uv.x, v = uv.y;
    if (isnan(u) || isinf(u))
        u = 0.0;
    if (isnan(v) || isinf(v))
        v = 0.0;
    precise float a = r0.x * u, b = r0.y * v, c = r1.x * u, d = r1.y * v;
    precise float x = (a + b) + r0.z, y = (c + d) + r1.z;
    return vec2(x, y);
}

// The same for the slot of a material record.
vec2 dirt_slot_uv_g(dirt_gpu_model_material m, int slot, vec2 uv)
{
    return dirt_slot_uv_rows_g(m.xf[2 * slot], m.xf[2 * slot + 1], uv);
}

// Textured surface of material `material` at uv (= dirt_material_surface),
// each slot's lookup at its transformed uv (dirt_slot_uv_g):
//   base = clamp(base_color * sRGB(base tex)), roughness = clamp(roughness *
//   mr.g), metallic = clamp(metallic * mr.b), alpha = roughness^2,
//   emission = (emissive * strength) * sRGB(emissive tex) when emissive,
//   specular = clamp(params.z * spec tex.a), f0 = clamp(f0(ior) *
//   specular_color * sRGB(spec colour tex).rgb), transmission =
//   clamp(transmission * trans tex.r), eta = the front side's.
dirt_surface_g dirt_material_surface_g(uint material, vec2 uv)
{
    dirt_gpu_model_material m = dirt_model_materials[material];
    vec4 bc = dirt_texture_sample_g(m.textures.x, true, dirt_slot_uv_g(m, 0, uv));
    vec4 mr = dirt_texture_sample_g(m.textures.y, false, dirt_slot_uv_g(m, 1, uv));
    dirt_surface_g s;
    s.bsdf.base_color = vec3(dirt_clamp01_g(m.base_color.x * bc.x),
                             dirt_clamp01_g(m.base_color.y * bc.y),
                             dirt_clamp01_g(m.base_color.z * bc.z));
    float roughness = dirt_clamp01_g(m.params.y * mr.y);
    s.bsdf.metallic = dirt_clamp01_g(m.params.x * mr.z);
    s.bsdf.alpha = roughness * roughness;
    s.bsdf.specular = m.params.z;
    s.double_sided = (m.textures.w & DIRT_MODEL_MAT_DOUBLE_SIDED) != 0;
    // KHR_materials_specular, _transmission, _ior (params2.y = dirt_ior_eta,
    // specular_color.w = dirt_ior_f0, computed by the packer).
    vec4 sa = dirt_texture_sample_g(m.textures2.z, false, dirt_slot_uv_g(m, 5, uv));
    s.bsdf.specular = dirt_clamp01_g(s.bsdf.specular * sa.w);
    vec4 sc = dirt_texture_sample_g(m.textures2.w, true, dirt_slot_uv_g(m, 6, uv));
    float f0 = m.specular_color.w;
    s.bsdf.f0 = vec3(dirt_clamp01_g(f0 * m.specular_color.x * sc.x),
                     dirt_clamp01_g(f0 * m.specular_color.y * sc.y),
                     dirt_clamp01_g(f0 * m.specular_color.z * sc.z));
    vec4 tr = dirt_texture_sample_g(m.textures2.y, false, dirt_slot_uv_g(m, 4, uv));
    s.bsdf.transmission = dirt_clamp01_g(m.params2.x * tr.x);
    s.bsdf.eta = m.params2.y;
    if ((m.textures.w & DIRT_MODEL_MAT_EMISSIVE) != 0) {
        vec4 em = dirt_texture_sample_g(m.textures.z, true, dirt_slot_uv_g(m, 2, uv));
        s.emission = m.emission.xyz * em.xyz;
    } else {
        s.emission = vec3(0.0);
    }
    return s;
}

// Tangent-space normal of the material's normal map at uv (=
// dirt_material_normal_ts): c = linear lookup at the normal slot's uv,
// n_ts = normalize(((2 c.r - 1) s, (2 c.g - 1) s, 2 c.b - 1)), s = the
// normal scale (params.w). False without a normal map (textures2.x < 0) or
// when n_ts is zero or not finite.
bool dirt_material_normal_ts_g(uint material, vec2 uv, out vec3 n_ts)
{
    dirt_gpu_model_material m = dirt_model_materials[material];
    n_ts = vec3(0.0, 0.0, 1.0);
    if (m.textures2.x < 0)
        return false;
    vec4 c = dirt_texture_sample_g(m.textures2.x, false, dirt_slot_uv_g(m, 3, uv));
    precise float x = 2.0 * c.x - 1.0, y = 2.0 * c.y - 1.0, z = 2.0 * c.z - 1.0;
    precise vec3 q = vec3(x * m.params.w, y * m.params.w, z);
    vec3 n = dirt_normalize_g(q);
    if (dirt_is_zero_g(n) || !dirt_is_finite_g(n))
        return false;
    n_ts = n;
    return true;
}

// True when the material emits (its triangles are area lights).
bool dirt_material_is_emissive_g(uint material)
{
    return (dirt_model_materials[material].textures.w & DIRT_MODEL_MAT_EMISSIVE) != 0;
}

#ifndef DIRT_MODEL_SURFACE_ONLY
// Index (into the cdf/prim tables) of the emissive triangle selected by u in
// [0,1): the first i with cdf[i] > u * total_area, the last one if none
// (binary search). The table must not be empty (counts.x > 0).
uint dirt_area_lights_select_g(float u)
{
    float x = u * dirt_model_lights.area.x;
    uint lo = 0u, hi = dirt_model_lights.counts.x - 1u;
    while (lo < hi) {
        uint mid = lo + (hi - lo) / 2u;
        if (dirt_model_area_cdf[mid] > x)
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}
// ---- environment light (env.c) -----------------------------------------

layout(std430, binding = DIRT_BIND_MODEL_ENV) readonly buffer DirtModelEnv {
    dirt_gpu_model_env dirt_model_env;
    float dirt_model_env_data[]; // cdf[w h], row_cos[h + 1], rgb[3 w h],
                                 // col_cos[w + 1], col_sin[w + 1]
};

// True when next-event estimation samples the map (= dirt_env_samples).
bool dirt_env_samples_g() { return dirt_model_env.dims.z != 0; }

// Number of NEE light sources (= dirt_nee_source_count): the area set, the
// punctual lights and, last, the environment.
uint dirt_nee_sources_g()
{
    return dirt_model_lights.counts.z + (dirt_env_samples_g() ? 1u : 0u);
}

float dirt_env_row_cos_g(int j)
{
    int w = dirt_model_env.dims.x, h = dirt_model_env.dims.y;
    return dirt_model_env_data[w * h + j];
}

// sin(phi - phi_k) of the map-frame direction e (= side of env.c); precise:
// the same rounding as C (no fused multiply-add).
float dirt_env_side_g(vec3 e, int k)
{
    int w = dirt_model_env.dims.x, h = dirt_model_env.dims.y;
    int base = 4 * w * h + h + 1;
    precise float a = e.x * dirt_model_env_data[base + k];
    precise float b = e.z * dirt_model_env_data[base + w + 1 + k];
    precise float r = a + b;
    return r;
}

// Texel (column, row) of unit world direction d (= dirt_env_texel): the
// column by an atan guess corrected at its edges, the row by comparisons.
ivec2 dirt_env_texel_g(vec3 d)
{
    int w = dirt_model_env.dims.x, h = dirt_model_env.dims.y;
    float rc = dirt_model_env.params.x, rs = dirt_model_env.params.y;
    precise float ex0 = rc * d.x, ex1 = rs * d.z, ez0 = rs * d.x, ez1 = rc * d.z;
    precise float ex = ex0 - ex1, ez = ez0 + ez1;
    vec3 e = vec3(ex, d.y, ez);
    float x = (atan(e.x, -e.z) + DIRT_PI_G) * (1.0 / (2.0 * DIRT_PI_G)) * float(w);
    int i = int(floor(x));
    if (!(x >= 0.0) || (e.x == 0.0 && e.z == 0.0))
        i = 0; // also NaN, and the poles (atan(0, 0) is undefined)
    if (i > w - 1)
        i = w - 1;
    if (w >= 4 && !(e.x == 0.0 && e.z == 0.0)) {
        for (int step = 0; step < 2; step++) {
            if (dirt_env_side_g(e, i) < 0.0)
                i = i > 0 ? i - 1 : w - 1;
            else if (dirt_env_side_g(e, i + 1) >= 0.0)
                i = i < w - 1 ? i + 1 : 0;
            else
                break;
        }
    }
    int lo = 0, hi = h - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (dirt_env_row_cos_g(mid + 1) <= e.y)
            hi = mid;
        else
            lo = mid + 1;
    }
    return ivec2(i, lo);
}

vec3 dirt_env_rgb_g(int k)
{
    int w = dirt_model_env.dims.x, h = dirt_model_env.dims.y;
    int base = w * h + h + 1 + 3 * k;
    return vec3(dirt_model_env_data[base], dirt_model_env_data[base + 1],
                dirt_model_env_data[base + 2]);
}

// Radiance seen looking along unit direction d (= dirt_env_eval); 0
// without an environment.
vec3 dirt_env_eval_g(vec3 d)
{
    if (dirt_model_env.dims.x == 0)
        return vec3(0.0);
    ivec2 t = dirt_env_texel_g(d);
    return dirt_env_rgb_g(t.y * dirt_model_env.dims.x + t.x);
}

// Solid-angle pdf of texel (i, j) (= texel_pdf of env.c).
float dirt_env_texel_pdf_g(int i, int j)
{
    int w = dirt_model_env.dims.x;
    int k = j * w + i;
    float wt = dirt_model_env_data[k] - (k > 0 ? dirt_model_env_data[k - 1] : 0.0);
    float band = dirt_env_row_cos_g(j) - dirt_env_row_cos_g(j + 1);
    float omega = (2.0 * DIRT_PI_G / float(w)) * band;
    return omega > 0.0 ? wt / (dirt_model_env.params.z * omega) : 0.0;
}

// = dirt_env_pdf.
float dirt_env_pdf_g(vec3 d)
{
    if (!dirt_env_samples_g())
        return 0.0;
    ivec2 t = dirt_env_texel_g(d);
    return dirt_env_texel_pdf_g(t.x, t.y);
}

// = dirt_env_sample.
bool dirt_env_sample_g(float u_sel, float u1, float u2, out vec3 d, out float pdf,
                       out vec3 radiance)
{
    d = vec3(0.0, 0.0, 1.0);
    pdf = 0.0;
    radiance = vec3(0.0);
    if (!dirt_env_samples_g())
        return false;
    int w = dirt_model_env.dims.x, h = dirt_model_env.dims.y;
    float x = u_sel * dirt_model_env.params.z;
    int lo = 0, hi = w * h - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (dirt_model_env_data[mid] > x)
            hi = mid;
        else
            lo = mid + 1;
    }
    int i = lo % w, j = lo / w;
    float p = dirt_env_texel_pdf_g(i, j);
    if (!(p > 0.0))
        return false;
    float phi = 2.0 * DIRT_PI_G * (float(i) + u1) / float(w) - DIRT_PI_G;
    float rj = dirt_env_row_cos_g(j);
    float z = rj - u2 * (rj - dirt_env_row_cos_g(j + 1));
    float s = sqrt(max(0.0, 1.0 - z * z));
    vec3 e = vec3(s * sin(phi), z, -s * cos(phi));
    float rc = dirt_model_env.params.x, rs = dirt_model_env.params.y;
    d = vec3(rc * e.x + rs * e.z, e.y, -rs * e.x + rc * e.z);
    pdf = p;
    radiance = dirt_env_rgb_g(lo);
    return true;
}
#endif // DIRT_MODEL_SURFACE_ONLY
#endif // DIRT_MODEL_BUFFERS

#endif
