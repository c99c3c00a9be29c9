/* DIRT engine: the glTF metallic-roughness BSDF, its sampling, and the small
 * warps shared by the integrators. Specification: doc/light-transport.md.
 * Every function here has a GLSL twin; keep them formula for formula. */
#include "integrator/integrator.h"

#include <math.h>

#include "core/vec3.h"

#define PI_F 3.14159265358979323846f
#define INV_PI_F 0.31830988618379067154f

bool dirt_bsdf_is_delta(const dirt_bsdf *b)
{
    return b->alpha < DIRT_ALPHA_DELTA;
}

bool dirt_bsdf_transmission_is_delta(const dirt_bsdf *b)
{
    return b->alpha < DIRT_ALPHA_DELTA || fabsf(b->eta - 1.0f) < DIRT_ETA_MATCHED;
}

bool dirt_bsdf_transmits(const dirt_bsdf *b)
{
    return b->transmission > 0.0f && b->metallic < 1.0f;
}

float dirt_ior_f0(float ior)
{
    if (!(ior >= 0.0f))
        return DIRT_DIELECTRIC_F0; /* NaN or negative: the glTF default */
    if (isinf(ior))
        return 1.0f;
    double r = ((double)ior - 1.0) / ((double)ior + 1.0);
    return (float)(r * r);
}

float dirt_ior_eta(float ior)
{
    return ior >= 1.0f && !isinf(ior) ? ior : 1.0f;
}

/* (1 - c)^5 with c clamped to [0,1]. */
static float schlick_weight(float c)
{
    float m = 1.0f - clamp01(c);
    float m2 = m * m;
    return m2 * m2 * m;
}

/* The dielectric Schlick Fresnel at cos theta = c, per channel:
 * s (f0 + (1 - f0) x(c)). */
static dirt_vec3 fresnel_d_rgb(const dirt_bsdf *b, float c)
{
    float x = schlick_weight(c);
    dirt_vec3 f0 = b->f0;
    return v3(b->specular * (f0.x + (1.0f - f0.x) * x), b->specular * (f0.y + (1.0f - f0.y) * x),
              b->specular * (f0.z + (1.0f - f0.z) * x));
}

/* The cosine Schlick's approximation takes at an interface of relative
 * index eta met at cos theta = c from the wo side: c itself when that side
 * is the optically thinner one (eta >= 1), else the cosine of the refracted
 * direction (the angle on the thinner side). False on total internal
 * reflection (or eta 0). */
static bool interface_cos(float eta, float c, float *cf)
{
    if (eta >= 1.0f) {
        *cf = c;
        return true;
    }
    float sin2 = (1.0f - c * c) / (eta * eta);
    if (!(sin2 < 1.0f))
        return false;
    *cf = sqrtf(1.0f - sin2);
    return true;
}

/* The interface's Fresnel F_t(c) (RGB): the dielectric Schlick at
 * interface_cos, 1 on total internal reflection. */
static dirt_vec3 fresnel_t_rgb(const dirt_bsdf *b, float c)
{
    float cf;
    if (!interface_cos(b->eta, c, &cf))
        return v3(1.0f, 1.0f, 1.0f);
    return fresnel_d_rgb(b, cf);
}

float dirt_bsdf_fresnel_dielectric(const dirt_bsdf *b, float c)
{
    return v3_max_comp(fresnel_d_rgb(b, c));
}

float dirt_bsdf_fresnel_interface(const dirt_bsdf *b, float c)
{
    return v3_max_comp(fresnel_t_rgb(b, c));
}

dirt_vec3 dirt_bsdf_fresnel(const dirt_bsdf *b, float c)
{
    float x = schlick_weight(c);
    dirt_vec3 fd = fresnel_d_rgb(b, c), ft = fresnel_t_rgb(b, c);
    float m = b->metallic, t = b->transmission;
    dirt_vec3 base = b->base_color;
    return v3((1.0f - m) * ((1.0f - t) * fd.x + t * ft.x) + m * (base.x + (1.0f - base.x) * x),
              (1.0f - m) * ((1.0f - t) * fd.y + t * ft.y) + m * (base.y + (1.0f - base.y) * x),
              (1.0f - m) * ((1.0f - t) * fd.z + t * ft.z) + m * (base.z + (1.0f - base.z) * x));
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

/* Fresnel of the reflection lobe sampled on its own: the opaque share and
 * the metal, (1 - m)(1 - t) F_d(c) + m (base + (1 - base) x(c)); the
 * transmissive share's reflection is sampled with its refraction. */
static dirt_vec3 fresnel_opaque(const dirt_bsdf *b, float c)
{
    float x = schlick_weight(c);
    dirt_vec3 fd = fresnel_d_rgb(b, c);
    float m = b->metallic, t = b->transmission;
    dirt_vec3 base = b->base_color;
    return v3((1.0f - m) * ((1.0f - t) * fd.x) + m * (base.x + (1.0f - base.x) * x),
              (1.0f - m) * ((1.0f - t) * fd.y) + m * (base.y + (1.0f - base.y) * x),
              (1.0f - m) * ((1.0f - t) * fd.z) + m * (base.z + (1.0f - base.z) * x));
}

void dirt_bsdf_lobe_probabilities(const dirt_bsdf *b, dirt_vec3 wo, float *p_spec,
                                  float *p_trans)
{
    float m = b->metallic, t = b->transmission;
    float ws = v3_luminance(fresnel_opaque(b, wo.z));
    float fd = dirt_bsdf_fresnel_dielectric(b, wo.z);
    float wd = (1.0f - m) * (1.0f - t) * v3_luminance(b->base_color) * (1.0f - fd);
    float ft = dirt_bsdf_fresnel_interface(b, wo.z);
    float wt = (1.0f - m) * t * (ft + (1.0f - ft) * v3_luminance(b->base_color));
    float sum = ws + wd + wt;
    *p_spec = sum > 0.0f ? ws / sum : 0.5f;
    *p_trans = sum > 0.0f ? wt / sum : 0.0f;
}

float dirt_bsdf_spec_probability(const dirt_bsdf *b, dirt_vec3 wo)
{
    float ps, pt;
    dirt_bsdf_lobe_probabilities(b, wo, &ps, &pt);
    return ps;
}

/* Diffuse factor (without base colour): Lambert behind the dielectric
 * interface, entered and left once, on the opaque share 1 - t:
 * (1 - m) (1 - t) (1 - F_d(wi.z)) (1 - F_d(wo.z)) / pi, F_d the scalar
 * (largest channel) dielectric Fresnel. Symmetric in wo and wi; its albedo
 * (1 - m)(1 - t)(1 - F_d(wo.z))(1 - avg F_d) never exceeds what the
 * specular lobe leaves over (doc/light-transport.md). */
static float diffuse_factor(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    return (1.0f - b->metallic) * (1.0f - b->transmission) *
           (1.0f - dirt_bsdf_fresnel_dielectric(b, wi.z)) *
           (1.0f - dirt_bsdf_fresnel_dielectric(b, wo.z)) * INV_PI_F;
}

/* The generalized half vector of a refraction pair (wo.z > 0 > wi.z,
 * Walter et al. 2007): h = normalize(wo + eta wi) turned to +z, with
 * *co = wo . h and *ci = wi . h. False when wo or wi lies on the wrong
 * side of that microfacet (co <= 0 or ci >= 0): no refraction links them. */
static bool refraction_half(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi, dirt_vec3 *h,
                            float *co, float *ci)
{
    dirt_vec3 hh = v3_normalize(v3_mad(wo, wi, b->eta));
    if (hh.z < 0.0f)
        hh = v3_neg(hh);
    *h = hh;
    *co = v3_dot(wo, hh);
    *ci = v3_dot(wi, hh);
    return *co > 0.0f && *ci < 0.0f;
}

/* Rough transmission f_t (scalar, without base colour) for wi.z < 0, in
 * radiance form (the 1 / eta^2 of the compressed solid angle included):
 * (1 - m) t (1 - F_t(wo.h)) D(h) G2 |wo.h| |wi.h| /
 * (wo.z |wi.z| (wo.h + eta wi.h)^2). */
static float transmission_factor(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    dirt_vec3 h;
    float co, ci;
    if (!refraction_half(b, wo, wi, &h, &co, &ci))
        return 0.0f;
    float d = dirt_ggx_d(b->alpha, h);
    float g = dirt_ggx_g2(b->alpha, wo, wi);
    float ft = dirt_bsdf_fresnel_interface(b, co);
    float den = co + b->eta * ci;
    return (1.0f - b->metallic) * b->transmission * (1.0f - ft) * d * g * co * -ci /
           (wo.z * -wi.z * den * den);
}

static bool has_rough_transmission(const dirt_bsdf *b)
{
    return dirt_bsdf_transmits(b) && !dirt_bsdf_transmission_is_delta(b);
}

dirt_vec3 dirt_bsdf_eval(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    if (wo.z <= 0.0f || wi.z == 0.0f || !(wi.z == wi.z))
        return v3(0.0f, 0.0f, 0.0f);
    if (wi.z < 0.0f) {
        if (!has_rough_transmission(b))
            return v3(0.0f, 0.0f, 0.0f);
        return v3_scale(b->base_color, transmission_factor(b, wo, wi));
    }
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

/* Solid-angle pdf of the refracted wi (wi.z < 0) for a visible normal
 * sampled from wo: G1(wo) (wo.h) D(h) / wo.z times the Jacobian
 * eta^2 |wi.h| / (wo.h + eta wi.h)^2. */
static float pdf_vndf_refract(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    dirt_vec3 h;
    float co, ci;
    if (!refraction_half(b, wo, wi, &h, &co, &ci))
        return 0.0f;
    float g1 = 1.0f / (1.0f + dirt_ggx_lambda(b->alpha, wo));
    float den = co + b->eta * ci;
    return g1 * co * dirt_ggx_d(b->alpha, h) / wo.z * (b->eta * b->eta * -ci / (den * den));
}

/* The share of the interface lobe that reflects, at the microfacet of
 * cosine c = wo . h: F_t(c), or F_t(wo.z) when the transmission is a delta
 * (the choice is made before any microfacet is drawn). */
static float interface_reflect(const dirt_bsdf *b, dirt_vec3 wo, float c)
{
    return dirt_bsdf_fresnel_interface(b, dirt_bsdf_transmission_is_delta(b) ? wo.z : c);
}

float dirt_bsdf_pdf(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    if (wo.z <= 0.0f || wi.z == 0.0f || !(wi.z == wi.z))
        return 0.0f;
    float p, pt;
    dirt_bsdf_lobe_probabilities(b, wo, &p, &pt);
    if (wi.z < 0.0f) {
        if (!(pt > 0.0f) || !has_rough_transmission(b))
            return 0.0f;
        dirt_vec3 h;
        float co, ci;
        if (!refraction_half(b, wo, wi, &h, &co, &ci))
            return 0.0f;
        return pt * (1.0f - dirt_bsdf_fresnel_interface(b, co)) * pdf_vndf_refract(b, wo, wi);
    }
    float pdf = fmaxf(0.0f, 1.0f - p - pt) * wi.z * INV_PI_F;
    if (!dirt_bsdf_is_delta(b)) {
        float ps = p;
        if (pt > 0.0f)
            ps += pt * interface_reflect(b, wo, v3_dot(wo, v3_normalize(v3_add(wo, wi))));
        pdf += ps * pdf_vndf(b->alpha, wo, wi);
    }
    return pdf;
}

/* wo refracted through the microfacet of unit normal h (wo . h = c > 0)
 * into the side of relative index eta: -wo / eta + (c / eta - cos_t) h.
 * False on total internal reflection. */
static bool refract_dir(dirt_vec3 wo, dirt_vec3 h, float c, float eta, dirt_vec3 *wi)
{
    float sin2 = (1.0f - c * c) / (eta * eta);
    if (!(sin2 < 1.0f))
        return false;
    float ct = sqrtf(1.0f - sin2);
    *wi = v3_sub(v3_scale(h, c / eta - ct), v3_scale(wo, 1.0f / eta));
    return true;
}

bool dirt_bsdf_sample_dir(const dirt_bsdf *b, dirt_vec3 wo, float u_lobe,
                          float u1, float u2, dirt_bsdf_sample *out)
{
    if (wo.z <= 0.0f)
        return false;
    float p, pt;
    dirt_bsdf_lobe_probabilities(b, wo, &p, &pt);
    float pd = fmaxf(0.0f, 1.0f - p - pt);
    dirt_vec3 wi;
    bool trans = false;
    if (u_lobe < p) {
        if (dirt_bsdf_is_delta(b)) {
            out->wi = v3(-wo.x, -wo.y, wo.z);
            out->weight = v3_scale(fresnel_opaque(b, wo.z), 1.0f / p);
            out->pdf = 0.0f;
            out->delta = true;
            return !v3_is_zero(out->weight);
        }
        dirt_vec3 h = dirt_sample_ggx_vndf(b->alpha, wo, u1, u2);
        wi = v3_sub(v3_scale(h, 2.0f * v3_dot(wo, h)), wo);
    } else if (pt > 0.0f && u_lobe >= p + pd) {
        /* The interface: reflect with probability F_t at the microfacet
         * (the lobe's u reused, rescaled to [0,1)), else refract. */
        float ut = (u_lobe - (p + pd)) / pt;
        float m = b->metallic, t = b->transmission;
        if (dirt_bsdf_transmission_is_delta(b)) {
            float fr = dirt_bsdf_fresnel_interface(b, wo.z);
            if (ut < fr) {
                if (dirt_bsdf_is_delta(b)) {
                    out->wi = v3(-wo.x, -wo.y, wo.z);
                    out->weight = v3_scale(fresnel_t_rgb(b, wo.z), (1.0f - m) * t / (pt * fr));
                    out->pdf = 0.0f;
                    out->delta = true;
                    return !v3_is_zero(out->weight) && v3_is_finite(out->weight);
                }
                dirt_vec3 h = dirt_sample_ggx_vndf(b->alpha, wo, u1, u2);
                wi = v3_sub(v3_scale(h, 2.0f * v3_dot(wo, h)), wo);
            } else {
                if (!refract_dir(wo, v3(0.0f, 0.0f, 1.0f), wo.z, b->eta, &out->wi))
                    return false;
                out->weight = v3_scale(b->base_color, (1.0f - m) * t / (b->eta * b->eta * pt));
                out->pdf = 0.0f;
                out->delta = true;
                return out->wi.z < 0.0f && !v3_is_zero(out->weight) && v3_is_finite(out->weight);
            }
        } else {
            dirt_vec3 h = dirt_sample_ggx_vndf(b->alpha, wo, u1, u2);
            float c = v3_dot(wo, h);
            if (!(c > 0.0f))
                return false;
            if (ut < dirt_bsdf_fresnel_interface(b, c)) {
                wi = v3_sub(v3_scale(h, 2.0f * c), wo);
            } else {
                trans = true;
                if (!refract_dir(wo, h, c, b->eta, &wi))
                    return false;
            }
        }
    } else {
        wi = dirt_sample_cosine(u1, u2);
    }
    if (trans ? !(wi.z < 0.0f) : !(wi.z > 0.0f))
        return false;
    float pdf = dirt_bsdf_pdf(b, wo, wi);
    if (!(pdf > 0.0f))
        return false;
    dirt_vec3 f = dirt_bsdf_eval(b, wo, wi);
    out->wi = wi;
    out->weight = v3_scale(f, fabsf(wi.z) / pdf);
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
