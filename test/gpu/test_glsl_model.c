/* The GLSL light-transport model (glsl/integrator/model.glsl) computes what
 * the C model (src/integrator/) computes.
 *
 * glsl/integrator/test_model.comp runs one group of GLSL functions on N
 * random input records and writes the results; the test runs the C
 * functions on the same inputs (same float bits) and compares:
 *
 *  - values: |gpu - c| <= REL * scale + ABS + cond * scale + 2 * spread
 *    (+ the texture term below). scale is the largest |c| of the field (a
 *    vector is compared as a whole: directions near a zero component have no
 *    useful component-wise relative error).
 *    REL = 1e-4: GLSL's +, -, * are correctly rounded, /, sqrt and
 *    inversesqrt are within 2.5-3 ulp, pow within a few ulp, and sin/cos
 *    have an absolute error around 1e-6 on GPUs; the model's longest chain
 *    (bsdf_sample_dir: warp, reflection, eval, pdf) has ~100 such
 *    operations, i.e. <= ~3e-5 relative when nothing cancels.
 *    Where something cancels, the rounding is amplified by the function's
 *    condition number, which two terms account for:
 *    spread = the largest change of the C result when the geometric inputs
 *    (directions, positions, u's, pixel coordinates) are moved by up to 4 ulp
 *    (4 tries; material factors are not moved: they enter through exact
 *    operations the GPU reproduces bit for bit), and
 *    cond = the relative error of GGX D from a few-ulp rounding of h.z,
 *    2 * 16 * 2^-24 / d with d = h.z^2 (a^2 - 1) + 1 (D near its peak for
 *    small alpha: the input perturbation cannot show it, h.z is pinned by
 *    the normalisation); for the sample weight scaled by how much D cancels
 *    between f and the pdf.
 *    Cases whose tolerance is more than 10 REL from these terms are counted
 *    ("ill-conditioned") and must stay below 2% per field (25% for the pdf
 *    of bsdf samples: a sample of the specular lobe lies near D's peak, and
 *    for alpha below ~0.05 its float pdf is ill-conditioned in any
 *    implementation, C included).
 *    bsdf_sample's pdf and weight are compared with the C model's at the
 *    GPU's sampled direction; the direction with the C sample's.
 *  - booleans (and the area-light index) must be equal, except where the C
 *    decision is within 1e-5 of its threshold (|u_lobe - p_spec|, |wi.z|,
 *    spot cone edge, range window, cdf boundary); those are counted and
 *    must stay below 0.1%. Values are compared only where the booleans agree
 *    (and the function succeeded).
 *  - textures and textured materials: the GLSL reads the same texels at
 *    their own sizes and performs the C lookup's operations in the same
 *    order (floor, wrap, the products and differences of the bilinear
 *    filter: correctly rounded in GLSL, and `precise`, so no fused
 *    multiply-add), so the only difference is the decode of each texel:
 *    c / 255 (GLSL's division: 2.5 ulp) and, for sRGB slots, the curve's
 *    division and pow (GPUs compute pow as exp2(y log2 x): on NVIDIA the
 *    PTX bounds of lg2/ex2.approx plus the rounding of y log2 x give up to
 *    ~1e-6 relative for the darkest decoded values; 5.6e-7 measured on
 *    llvmpipe by the misc mode). The filter is a convex combination of the
 *    four texels, so a lookup differs by at most the largest texel error:
 *    |gpu - c| <= TEXEL_REL * M, M = the largest decoded value of that
 *    texture (<= 1; a dark texture keeps the bound tight), TEXEL_REL = 2e-6
 *    (2x that worst case). Measured on llvmpipe: linear lookups bit-exact,
 *    sRGB lookups within 2.4e-7 M (0.12 of the tolerance), ~69% of all
 *    lookups bit-exact. The hardware-filtered, resized lookup this replaced
 *    was off by up to 0.0049 on same-size textures (8-bit filter weights)
 *    and 0.32 on resized ones; emulating 8-bit weights, a 1e-4 texel offset
 *    or pow(x, 2.4001) fails this comparison.
 *    Material values scale it by the factor that multiplies the texture
 *    (2 r for alpha = r^2); everything else of a material is the same
 *    float operations on both sides and must be exact (ABS). No REL and no
 *    perturbation spread: GPU and C compute the same operations on the
 *    same bits, so a UV's conditioning does not enter.
 *
 * Last, the same comparison runs on a build of the shader with TEST_FAULT
 * (every result times 1.001 plus 0.01): it must fail nearly every case of
 * every mode, proving the comparison catches a broken function. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "integrator/gpu_tables.h"
#include "integrator/integrator.h"
#include "dirt/log.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gpu.h"
#include "model_shader.h"
#include "core/vec3.h"

#define N 10000
#define STRIDE 32 /* floats per record (8 vec4) */
#define REL 1e-4
#define ABS 1e-12
#define TEXEL_REL 2e-6
#define NEAR_THRESHOLD 1e-5
#define PERTURB_TRIES 4
/* Tolerances below this (absolute) do not count as loose. */
#define ILL_FLOOR 1e-6
/* Fields a mode compares, at most. */
#define MAX_FIELDS 12

enum {
    MODE_WARPS = 0,
    MODE_VNDF = 1,
    MODE_ONB = 2,
    MODE_EVAL = 3,
    MODE_SAMPLE = 4,
    MODE_MISC = 5,
    MODE_LIGHT = 6,
    MODE_AREA = 7,
    MODE_MATERIAL = 8,
    MODE_CAMERA = 9,
    MODE_TEXTURE = 10,
    MODE_TRANS = 11,
};

/* ---- random numbers ----------------------------------------------------- */

static uint64_t rng_state = 0x243f6a8885a308d3ull;

static uint32_t rnd32(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    uint64_t x = rng_state;
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    return (uint32_t)x;
}

/* [0, 1) with 24 bits, like the RNG of the integrator. */
static float urand(void) { return (float)(rnd32() >> 8) * (1.0f / 16777216.0f); }
static float urange(float a, float b) { return a + (b - a) * urand(); }
static int irange(int n) { return (int)(rnd32() % (uint32_t)n); }

/* A second stream for the inputs added with transmission, ior and the
 * specular colour, so the cases drawn before them stay what they were. */
static uint64_t rng2_state = 0x13198a2e03707344ull;
static uint32_t rnd32b(void)
{
    rng2_state = rng2_state * 6364136223846793005ull + 1442695040888963407ull;
    uint64_t x = rng2_state;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return (uint32_t)x;
}
static float urand2(void) { return (float)(rnd32b() >> 8) * (1.0f / 16777216.0f); }
static float urange2(float a, float b) { return a + (b - a) * urand2(); }
static int irange2(int n) { return (int)(rnd32b() % (uint32_t)n); }

/* x moved by up to 4 ulp (relative 2^-23 steps). */
static float perturb(float x)
{
    int k = irange(9) - 4;
    return x * (1.0f + (float)k * FLT_EPSILON);
}
static dirt_vec3 perturb3(dirt_vec3 v) { return v3(perturb(v.x), perturb(v.y), perturb(v.z)); }
/* Perturbed but kept in the input's domain: [0,1] for factors, [0,1) for
 * uniform numbers (leaving it measures a different function). */
static float perturb01(float x) { return fminf(fmaxf(perturb(x), 0.0f), 1.0f); }
static float perturb_u(float x) { return fminf(fmaxf(perturb(x), 0.0f), 1.0f - 1.0f / 16777216.0f); }
/* The same, but 0 is moved along the RNG's grid (a relative step leaves it
 * 0): for the VNDF's u2, whose cap top z = 1 at u2 = 0 is where
 * sqrt(1 - z^2) amplifies an ulp of z to ~3e-4 on either side. */
static float perturb_u0(float x)
{
    return x == 0.0f ? (float)irange2(5) / 16777216.0f : perturb_u(x);
}

/* Unit direction in the upper hemisphere: mostly uniform in z, some grazing,
 * some exactly the normal. */
static dirt_vec3 random_upper(void)
{
    int k = irange(20);
    double z = k == 0 ? 1.0 : (k == 1 ? (double)urange(1e-4f, 1e-2f) : 1.0 - (double)urand());
    double phi = 6.283185307179586 * (double)urand();
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    return v3((float)(r * cos(phi)), (float)(r * sin(phi)), (float)z);
}

static dirt_vec3 random_sphere(void)
{
    int k = irange(40);
    if (k == 0)
        return v3(0.0f, 0.0f, 1.0f);
    if (k == 1)
        return v3(0.0f, 0.0f, -1.0f);
    if (k == 2)
        return v3(1.0f, 0.0f, 0.0f);
    double z = 2.0 * (double)urand() - 1.0;
    double phi = 6.283185307179586 * (double)urand();
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    return v3((float)(r * cos(phi)), (float)(r * sin(phi)), (float)z);
}

static float random_u(void)
{
    int k = irange(50);
    return k == 0 ? 0.0f : (k == 1 ? 1.0f - 1.0f / 16777216.0f : urand());
}

static void random_bsdf(dirt_bsdf *b)
{
    for (int c = 0; c < 3; c++) {
        int k = irange(10);
        (&b->base_color.x)[c] = k == 0 ? 0.0f : (k == 1 ? 1.0f : urand());
    }
    int k = irange(3);
    b->metallic = k == 0 ? 0.0f : (k == 1 ? 1.0f : urand());
    k = irange(20);
    if (k < 3)
        b->alpha = 0.0f; /* mirror */
    else if (k < 5)
        b->alpha = urange(0.0f, DIRT_ALPHA_DELTA);
    else if (k < 7)
        b->alpha = urange(DIRT_ALPHA_DELTA, 2.0f * DIRT_ALPHA_DELTA);
    else if (k < 10)
        b->alpha = expf(urange(logf(DIRT_ALPHA_DELTA), 0.0f));
    else {
        float r = urand();
        b->alpha = r * r;
    }
    k = irange(10);
    b->specular = k < 2 ? 1.0f : (k == 2 ? 0.0f : urand());
    /* KHR_materials_specular colour, transmission, ior: glTF's defaults,
     * clear glass and random; eta on the front (ior) and the back (1 / ior),
     * index-matched (1, 1 + 5e-4: a delta) and the specular-glossiness
     * ior 0 (eta 1, F0 1). */
    k = irange2(4);
    float f0 = dirt_ior_f0(1.5f);
    b->f0 = k < 2 ? v3(f0, f0, f0) : (k == 2 ? v3(1.0f, 1.0f, 1.0f) : v3(urand2(), urand2(), urand2()));
    k = irange2(4);
    b->transmission = k < 2 ? 0.0f : (k == 2 ? 1.0f : urand2());
    k = irange2(8);
    float ior = k < 2 ? 1.5f : (k == 2 ? 1.0f : (k == 3 ? 1.0005f : urange2(1.0f, 2.5f)));
    b->eta = irange2(2) ? ior : 1.0f / ior;
}

/* ---- the scene data the C side evaluates --------------------------------- */

static const dirt_material *g_mats;
static const float *g_spec;
static const dirt_texture *g_tex;
static size_t g_ntex;
static const dirt_area_lights *g_area;
static dirt_light g_lights[N];
static dirt_camera g_cams[N];
static double g_tex_max[2][64]; /* [srgb] largest decoded value of texture i (<= 1) */

static void put3(float *o, dirt_vec3 v)
{
    o[0] = v.x;
    o[1] = v.y;
    o[2] = v.z;
}
static dirt_vec3 get3(const float *p) { return v3(p[0], p[1], p[2]); }
static void put4(float *o, dirt_f4 v)
{
    o[0] = v.x;
    o[1] = v.y;
    o[2] = v.z;
    o[3] = v.w;
}

/* Material parameters are never perturbed: they enter the model through
 * exact or correctly rounded operations (a2 = alpha * alpha, 1 - metallic),
 * which the GPU computes to the same bits, and moving them would report
 * conditioning the GPU cannot see (e.g. a diffuse term appearing for
 * metallic 1 - 4 ulp). */
static dirt_bsdf read_bsdf(const float *in)
{
    dirt_bsdf b;
    b.base_color = get3(in);
    b.metallic = in[3];
    b.alpha = in[4];
    b.specular = in[5];
    b.transmission = in[6];
    b.eta = in[7];
    b.f0 = get3(in + 16);
    return b;
}

/* The C results of record `idx` in the GPU's output layout; `p`: with
 * perturbed float inputs. `gpu` (may be NULL) is the GPU's result of the
 * record: bsdf_sample's pdf and weight are the C model's at the GPU's
 * direction (the direction itself is compared with the C sample's), so a
 * rounding difference in the sampled direction is not amplified by a sharp
 * lobe into the pdf comparison. */
static void c_eval(int mode, const float *in, int idx, bool p, const float *gpu, float *out)
{
    memset(out, 0, STRIDE * sizeof(float));
    switch (mode) {
    case MODE_WARPS: {
        float u1 = p ? perturb_u(in[0]) : in[0], u2 = p ? perturb_u(in[1]) : in[1];
        put3(out, dirt_sample_cosine(u1, u2));
        dirt_sample_triangle(u1, u2, &out[4], &out[5]);
        dirt_sample_disk(u1, u2, &out[6], &out[7]);
        break;
    }
    case MODE_VNDF: {
        float a = in[0], u1 = in[1], u2 = in[2];
        dirt_vec3 wo = get3(in + 4);
        if (p) {
            u1 = perturb_u(u1), u2 = perturb_u(u2);
            wo = perturb3(wo);
        }
        put3(out, dirt_sample_ggx_vndf(a, wo, u1, u2));
        break;
    }
    case MODE_ONB: {
        dirt_vec3 n = get3(in), t, b;
        if (p)
            n = perturb3(n);
        dirt_onb(n, &t, &b);
        put3(out, t);
        put3(out + 4, b);
        break;
    }
    case MODE_EVAL: {
        dirt_bsdf b = read_bsdf(in);
        dirt_vec3 wo = get3(in + 8), wi = get3(in + 12);
        if (p) {
            wo = perturb3(wo);
            wi = perturb3(wi);
        }
        put3(out, dirt_bsdf_eval(&b, wo, wi));
        out[4] = dirt_bsdf_pdf(&b, wo, wi);
        out[5] = dirt_bsdf_spec_probability(&b, wo);
        out[6] = dirt_ggx_d(b.alpha, v3_normalize(v3_add(wo, wi)));
        out[7] = dirt_ggx_g2(b.alpha, wo, wi);
        put3(out + 8, dirt_bsdf_fresnel(&b, wo.z));
        out[11] = dirt_bsdf_fresnel_dielectric(&b, wo.z);
        out[12] = dirt_ggx_lambda(b.alpha, wo);
        out[13] = dirt_ggx_lambda(b.alpha, wi);
        out[14] = dirt_bsdf_is_delta(&b) ? 1.0f : 0.0f;
        break;
    }
    case MODE_SAMPLE: {
        dirt_bsdf b = read_bsdf(in);
        dirt_vec3 wo = get3(in + 8);
        float ul = in[12], u1 = in[13], u2 = in[14];
        if (p) {
            wo = perturb3(wo);
            ul = perturb_u(ul), u1 = perturb_u(u1), u2 = perturb_u0(u2);
        }
        dirt_bsdf_sample s;
        memset(&s, 0, sizeof(s));
        bool ok = dirt_bsdf_sample_dir(&b, wo, ul, u1, u2, &s);
        out[0] = ok ? 1.0f : 0.0f;
        out[1] = ok && s.delta ? 1.0f : 0.0f;
        out[2] = ul < dirt_bsdf_spec_probability(&b, wo) ? 1.0f : 0.0f;
        if (ok) {
            out[3] = s.pdf;
            put3(out + 4, s.wi);
            put3(out + 8, s.weight);
            if (gpu && !s.delta && gpu[0] > 0.5f && gpu[1] < 0.5f) {
                dirt_vec3 wg = get3(gpu + 4);
                float pdf = dirt_bsdf_pdf(&b, wo, wg);
                out[3] = pdf;
                put3(out + 8, v3_scale(dirt_bsdf_eval(&b, wo, wg), fabsf(wg.z) / pdf));
            }
        }
        break;
    }
    case MODE_TRANS: {
        dirt_bsdf b = read_bsdf(in);
        dirt_vec3 wo = get3(in + 8);
        float c = in[12];
        if (p) {
            wo = perturb3(wo);
            c = perturb01(c);
        }
        float ps, pt;
        dirt_bsdf_lobe_probabilities(&b, wo, &ps, &pt);
        out[0] = pt;
        out[1] = dirt_bsdf_fresnel_interface(&b, c);
        out[2] = dirt_bsdf_transmits(&b) ? 1.0f : 0.0f;
        out[3] = dirt_bsdf_transmission_is_delta(&b) ? 1.0f : 0.0f;
        out[4] = ps;
        break;
    }
    case MODE_MISC: {
        float a = in[0], b = in[1], c = in[2];
        dirt_vec3 beta = get3(in + 4);
        if (p) {
            a = perturb(a), b = perturb(b), c = perturb01(c);
            beta = perturb3(beta);
        }
        out[0] = dirt_mis_power(a, b);
        out[1] = dirt_rr_survival(beta);
        out[2] = dirt_srgb_to_linear(c);
        break;
    }
    case MODE_LIGHT: {
        dirt_light l = g_lights[idx];
        dirt_vec3 pt = get3(in + 16);
        if (p) {
            for (int c = 0; c < 3; c++) {
                l.position[c] = perturb(l.position[c]);
                l.direction[c] = perturb(l.direction[c]);
            }
            l.range = perturb(l.range);
            pt = perturb3(pt);
        }
        dirt_vec3 wi = v3(0, 0, 0), li = v3(0, 0, 0);
        float dist = 0.0f;
        bool ok = dirt_punctual_light(&l, pt, &wi, &dist, &li);
        out[0] = ok ? 1.0f : 0.0f;
        if (ok) {
            out[1] = dist;
            put3(out + 4, wi);
            put3(out + 8, li);
        }
        break;
    }
    case MODE_AREA:
        out[0] = (float)dirt_area_lights_select(g_area, in[0]);
        break;
    case MODE_MATERIAL: {
        int m = (int)in[0];
        float u = in[1], v = in[2];
        if (p)
            u = perturb(u), v = perturb(v);
        dirt_surface s;
        dirt_material_surface(&g_mats[m], g_spec ? g_spec[m] : 1.0f, g_tex, g_ntex, u, v, &s);
        put3(out, s.bsdf.base_color);
        out[3] = s.bsdf.metallic;
        out[4] = s.bsdf.alpha;
        out[5] = s.bsdf.specular;
        out[6] = s.double_sided ? 1.0f : 0.0f;
        out[7] = dirt_material_is_emissive(&g_mats[m]) ? 1.0f : 0.0f;
        put3(out + 8, s.emission);
        out[11] = s.bsdf.eta;
        put3(out + 12, s.bsdf.f0);
        out[15] = s.bsdf.transmission;
        break;
    }
    case MODE_CAMERA: {
        dirt_camera c = g_cams[idx];
        float px = in[22], py = in[23], lu = in[24], lv = in[25];
        if (p) {
            for (int k = 0; k < 3; k++) {
                c.eye[k] = perturb(c.eye[k]);
                c.forward[k] = perturb(c.forward[k]);
                c.right[k] = perturb(c.right[k]);
                c.up[k] = perturb(c.up[k]);
            }
            c.yfov = perturb(c.yfov);
            px = perturb(px), py = perturb(py), lu = perturb_u(lu), lv = perturb_u(lv);
        }
        dirt_vec3 org, dir;
        dirt_camera_ray(&c, (int)in[20], (int)in[21], px, py, lu, lv, &org, &dir);
        put3(out, org);
        put3(out + 4, dir);
        break;
    }
    case MODE_TEXTURE: {
        int t = (int)in[0];
        float u = in[2], v = in[3];
        if (p)
            u = perturb(u), v = perturb(v);
        /* out of range: NULL, white (as dirt_material_surface reads it) */
        bool ok = t >= 0 && (size_t)t < g_ntex;
        dirt_texture_sample(ok ? &g_tex[t] : NULL, in[1] != 0.0f, u, v, out);
        break;
    }
    }
}

/* Distance of the C decisions of record `idx` to their thresholds (large
 * when there is no decision near). */
static float c_margin(int mode, const float *in, int idx)
{
    float m = 1.0f;
    if (mode == MODE_SAMPLE) {
        dirt_bsdf b = read_bsdf(in);
        dirt_vec3 wo = get3(in + 8);
        float ul = in[12], u1 = in[13], u2 = in[14];
        float ps, pt;
        dirt_bsdf_lobe_probabilities(&b, wo, &ps, &pt);
        float pd = fmaxf(0.0f, 1.0f - ps - pt);
        m = fabsf(ul - ps);
        if (pt > 0.0f)
            m = fminf(m, fabsf(ul - (ps + pd)));
        dirt_vec3 wi = v3(0, 0, 1);
        if (pt > 0.0f && ul >= ps + pd) {
            /* the interface: reflect or refract by the rescaled u against
             * F_t, refraction impossible at sin2 = 1 */
            float ut = (ul - (ps + pd)) / pt;
            bool dt = dirt_bsdf_transmission_is_delta(&b);
            dirt_vec3 h = dt && dirt_bsdf_is_delta(&b) ? v3(0, 0, 1)
                                                      : dirt_sample_ggx_vndf(b.alpha, wo, u1, u2);
            float c = v3_dot(wo, h), fr = dirt_bsdf_fresnel_interface(&b, dt ? wo.z : c);
            m = fminf(m, fabsf(ut - fr) * pt);
            if (ut < fr) {
                wi = v3_sub(v3_scale(h, 2.0f * c), wo);
            } else {
                if (dt)
                    h = v3(0, 0, 1), c = wo.z;
                float sin2 = (1.0f - c * c) / (b.eta * b.eta);
                m = fminf(m, fminf(fabsf(1.0f - sin2), fabsf(c)));
                if (sin2 < 1.0f)
                    wi = v3_sub(v3_scale(h, c / b.eta - sqrtf(1.0f - sin2)), v3_scale(wo, 1.0f / b.eta));
            }
        } else if (ul >= ps) {
            wi = dirt_sample_cosine(u1, u2);
        } else if (!dirt_bsdf_is_delta(&b)) {
            dirt_vec3 h = dirt_sample_ggx_vndf(b.alpha, wo, u1, u2);
            wi = v3_sub(v3_scale(h, 2.0f * v3_dot(wo, h)), wo);
        }
        m = fminf(m, fabsf(wi.z));
    } else if (mode == MODE_TRANS) {
        dirt_bsdf b = read_bsdf(in);
        float c = in[12], sin2 = (1.0f - c * c) / (b.eta * b.eta);
        m = fabsf(1.0f - sin2); /* total internal reflection */
        m = fminf(m, fminf(fabsf(b.alpha - DIRT_ALPHA_DELTA), fabsf(fabsf(b.eta - 1.0f) - DIRT_ETA_MATCHED)));
    } else if (mode == MODE_LIGHT) {
        const dirt_light *l = &g_lights[idx];
        if (l->type == DIRT_LIGHT_DIRECTIONAL)
            return m;
        dirt_vec3 to = v3_sub(v3_load(l->position), get3(in + 16));
        float d = v3_length(to);
        if (l->range > 0.0f) {
            float r = d / l->range;
            m = fminf(m, fabsf(1.0f - r * r * r * r));
        }
        if (l->type == DIRT_LIGHT_SPOT && d > 0.0f) {
            float cd = -v3_dot(v3_normalize(v3_load(l->direction)), v3_scale(to, 1.0f / d));
            m = fminf(m, fabsf(cd - cosf(l->outer_cone)));
        }
    } else if (mode == MODE_AREA) {
        float x = in[0] * g_area->total_area;
        size_t i = dirt_area_lights_select(g_area, in[0]);
        m = fabsf(g_area->cdf[i] - x);
        if (i > 0)
            m = fminf(m, fabsf(x - g_area->cdf[i - 1]));
        m /= g_area->total_area;
    }
    return m;
}

/* TEXEL_REL * the largest decoded value of texture t read with `srgb`
 * (0 for none / out of range / no pixels: those read exactly 1). */
static double texel_tol(int t, bool srgb)
{
    if (t < 0 || (size_t)t >= g_ntex)
        return 0.0;
    return TEXEL_REL * (t < 64 ? g_tex_max[srgb][t] : 1.0); /* values <= 1 */
}

/* Absolute tolerance of a field of a texture lookup or a textured
 * material (the texel term, scaled by the factor that multiplies it). */
static double tex_tol(int mode, const float *in, int off)
{
    if (mode == MODE_TEXTURE)
        return texel_tol((int)in[0], in[1] != 0.0f);
    if (mode != MODE_MATERIAL)
        return 0.0;
    const dirt_material *m = &g_mats[(int)in[0]];
    switch (off) {
    case 0: /* base colour */
        return texel_tol(m->base_color_tex, true) *
               fmax(m->base_color[0], fmax(m->base_color[1], m->base_color[2]));
    case 3: /* metallic */
        return texel_tol(m->metallic_roughness_tex, false) * fabs(m->metallic);
    case 4: /* alpha = (roughness * g)^2 */
        return 2.0 * texel_tol(m->metallic_roughness_tex, false) * fabs(m->roughness) *
               fmin(1.0, fabs(m->roughness));
    case 8: /* emission */
        return texel_tol(m->emissive_tex, true) *
               fmax(m->emissive[0], fmax(m->emissive[1], m->emissive[2])) * m->emissive_strength;
    case 5: /* specular = clamp(s) * specular_tex.a */
        return texel_tol(m->specular_tex, false);
    case 12: /* f0 = f0(ior) specular_color sRGB(tex) */
        return texel_tol(m->specular_color_tex, true) * dirt_ior_f0(m->ior) *
               fmax(m->specular_color[0], fmax(m->specular_color[1], m->specular_color[2]));
    case 15: /* transmission */
        return texel_tol(m->transmission_tex, false) * fabs(m->transmission);
    }
    return 0.0;
}

/* The largest decoded value of each texture (g_tex_max), for texel_tol. */
static void texture_maxima(void)
{
    memset(g_tex_max, 0, sizeof(g_tex_max));
    for (size_t t = 0; t < g_ntex && t < 64; t++) {
        const dirt_texture *x = &g_tex[t];
        if (!x->rgba || x->width <= 0 || x->height <= 0)
            continue;
        size_t n = (size_t)x->width * (size_t)x->height * 4;
        for (size_t k = 0; k < n; k++) {
            float lin = (float)x->rgba[k] / 255.0f;
            float srgb = k % 4 == 3 ? lin : dirt_srgb_to_linear(lin);
            g_tex_max[0][t] = fmax(g_tex_max[0][t], lin);
            g_tex_max[1][t] = fmax(g_tex_max[1][t], srgb);
        }
    }
}

/* Texture lookups and materials: the same float operations on both sides,
 * compared with the texel term alone (header comment). */
static bool texel_only(int mode) { return mode == MODE_TEXTURE || mode == MODE_MATERIAL; }

/* Relative error the float evaluation of GGX D has near its peak, where the
 * input perturbation does not show it: D = a2 / (pi d^2) with
 * d = h.z^2 (a2 - 1) + 1 summed from O(1) terms, so a rounding of a few ulp
 * in h.z (the GPU normalises with inversesqrt) moves d by ~16 * 2^-24
 * absolute and D by twice that relative to d. Applies to the fields made
 * from D: eval's f, pdf and D, sample's pdf and weight (at the GPU's wi). */
static double ggx_cond(int mode, const float *in, const float *gpu, int off)
{
    bool eval = mode == MODE_EVAL && (off == 0 || off == 4 || off == 6);
    bool sample = mode == MODE_SAMPLE && (off == 3 || off == 8);
    if (!eval && !sample)
        return 0.0;
    dirt_bsdf b = read_bsdf(in);
    if (dirt_bsdf_is_delta(&b))
        return 0.0;
    dirt_vec3 wo = get3(in + 8), wi = eval ? get3(in + 12) : get3(gpu + 4);
    dirt_vec3 h = v3_normalize(v3_add(wo, wi));
    if (wi.z < 0.0f) { /* transmission: the generalized half vector */
        h = v3_normalize(v3_mad(wo, wi, b.eta));
        if (h.z < 0.0f)
            h = v3_neg(h);
    }
    double a2 = (double)b.alpha * b.alpha, hz = h.z;
    double d = (1.0 - hz * hz) + hz * hz * a2;
    double cond = d > 0.0 ? 2.0 * 16.0 / 16777216.0 / d : INFINITY;
    if (sample && off == 8) {
        /* weight = f wi.z / pdf: D cancels as far as it makes up the same
         * share of f and of the pdf. The diffuse-only parts are the model's
         * with the lobe made a mirror (alpha 0). */
        dirt_bsdf diffuse = b;
        diffuse.alpha = 0.0f;
        dirt_vec3 f = dirt_bsdf_eval(&b, wo, wi), fd = dirt_bsdf_eval(&diffuse, wo, wi);
        double pdf = dirt_bsdf_pdf(&b, wo, wi), pdfd = dirt_bsdf_pdf(&diffuse, wo, wi);
        double sf = v3_max_comp(f) > 0.0f ? 1.0 - (double)v3_max_comp(fd) / v3_max_comp(f) : 0.0;
        double sp = pdf > 0.0 ? 1.0 - pdfd / pdf : 0.0;
        cond *= fabs(sf - sp) + 1e-3;
    }
    return cond;
}

/* False for fields that mean nothing for a record (D of a mirror: the model
 * never evaluates it; in float it overflows). */
static bool field_applies(int mode, const float *c, int off)
{
    return !(mode == MODE_EVAL && off == 6 && c[14] > 0.5f);
}

/* ---- comparison --------------------------------------------------------- */

typedef struct field {
    const char *name;
    int off, n;
    char kind;      /* 'v' value, 'b' boolean, 'i' index */
    double max_ill; /* allowed fraction of ill-conditioned cases (0: 2%) */
} field;

typedef struct mode_desc {
    const char *name;
    int mode;
    int valid_off; /* offset of the C success flag gating the values, or -1 */
    field fields[MAX_FIELDS];
} mode_desc;

static const mode_desc modes[] = {
    {"warps", MODE_WARPS, -1,
     {{"cosine dir", 0, 3, 'v'}, {"triangle b1,b2", 4, 2, 'v'}, {"disk x,y", 6, 2, 'v'}}},
    {"ggx vndf", MODE_VNDF, -1, {{"h", 0, 3, 'v'}}},
    {"onb", MODE_ONB, -1, {{"t", 0, 3, 'v'}, {"b", 4, 3, 'v'}}},
    {"bsdf eval", MODE_EVAL, -1,
     {{"f", 0, 3, 'v'}, {"pdf", 4, 1, 'v'}, {"p_spec", 5, 1, 'v'}, {"ggx D", 6, 1, 'v'},
      {"ggx G2", 7, 1, 'v'}, {"fresnel rgb", 8, 3, 'v'}, {"fresnel dielectric", 11, 1, 'v'},
      {"delta", 14, 1, 'b'}}},
    {"bsdf sample", MODE_SAMPLE, 0,
     {{"ok", 0, 1, 'b'}, {"delta", 1, 1, 'b'}, {"lobe", 2, 1, 'b'}, {"pdf", 3, 1, 'v', 0.25},
      {"wi", 4, 3, 'v'}, {"weight", 8, 3, 'v'}}},
    {"misc", MODE_MISC, -1,
     {{"mis power", 0, 1, 'v'}, {"rr survival", 1, 1, 'v'}, {"srgb decode", 2, 1, 'v'}}},
    {"punctual light", MODE_LIGHT, 0,
     {{"ok", 0, 1, 'b'}, {"dist", 1, 1, 'v'}, {"wi", 4, 3, 'v'}, {"li", 8, 3, 'v'}}},
    {"area select", MODE_AREA, -1, {{"index", 0, 1, 'i'}}},
    {"material", MODE_MATERIAL, -1,
     {{"base colour", 0, 3, 'v'}, {"metallic", 3, 1, 'v'}, {"alpha", 4, 1, 'v'},
      {"specular", 5, 1, 'v'}, {"double sided", 6, 1, 'b'}, {"emissive", 7, 1, 'b'},
      {"emission", 8, 3, 'v'}, {"eta", 11, 1, 'v'}, {"f0", 12, 3, 'v'},
      {"transmission", 15, 1, 'v'}}},
    {"transmission", MODE_TRANS, -1,
     /* c at the critical angle in 1 of 10 cases on purpose, where
      * sqrt(1 - (1 - c^2) / eta^2) is ill-conditioned: up to 10% */
     {{"p_trans", 0, 1, 'v'}, {"fresnel interface", 1, 1, 'v', 0.1}, {"transmits", 2, 1, 'b'},
      {"delta", 3, 1, 'b'}, {"p_spec", 4, 1, 'v'}}},
    {"camera", MODE_CAMERA, -1, {{"org", 0, 3, 'v'}, {"dir", 4, 3, 'v'}}},
    {"texture", MODE_TEXTURE, -1, {{"rgba", 0, 4, 'v'}}},
};

static const mode_desc *mode_of(int mode)
{
    for (size_t i = 0; i < sizeof(modes) / sizeof(modes[0]); i++)
        if (modes[i].mode == mode)
            return &modes[i];
    return NULL;
}

typedef struct field_stats {
    double max_err, max_rel, max_rel_tight;
    int worst, fails, ill, compared;
} field_stats;

typedef struct compare_result {
    int cases, bool_fail, near, value_fail, ill, ill_excess;
    double texel_ratio; /* texture modes: largest |gpu - c| / (TEXEL_REL M) */
    int exact;          /* texture modes: records equal bit for bit */
} compare_result;

static bool any_nonfinite(const float *c, int n)
{
    for (int k = 0; k < n; k++)
        if (!isfinite(c[k]))
            return true;
    return false;
}

/* Compares the GPU results `gpu` of n records with the C model; prints
 * per-field statistics unless quiet. */
static compare_result compare(int mode, const float *in, const float *gpu, int n, bool quiet)
{
    const mode_desc *d = mode_of(mode);
    compare_result r = {n, 0, 0, 0, 0, 0, 0.0, 0};
    field_stats st[MAX_FIELDS];
    memset(st, 0, sizeof(st));
    int printed = 0;
    for (int i = 0; i < n; i++) {
        const float *ci = in + (size_t)i * STRIDE, *g = gpu + (size_t)i * STRIDE;
        float c[STRIDE], cp[STRIDE];
        c_eval(mode, ci, i, false, g, c);
        bool agree = true;
        float margin = -1.0f;
        for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++) {
            const field *fd = &d->fields[f];
            bool mismatch;
            if (fd->kind == 'b')
                mismatch = (c[fd->off] > 0.5f) != (g[fd->off] > 0.5f);
            else if (fd->kind == 'i')
                mismatch = c[fd->off] != g[fd->off];
            else
                continue;
            if (!mismatch)
                continue;
            agree = false;
            if (margin < 0.0f)
                margin = c_margin(mode, ci, i);
            if (margin < NEAR_THRESHOLD) {
                r.near++;
            } else {
                r.bool_fail++;
                st[f].fails++;
                if (!quiet && printed++ < 10)
                    fprintf(stderr, "  %s #%d: %s gpu %g c %g (margin %g)\n", d->name, i,
                            fd->name, g[fd->off], c[fd->off], margin);
            }
        }
        if (!agree || (d->valid_off >= 0 && !(c[d->valid_off] > 0.5f)))
            continue;
        /* Spread of the C results under input perturbation (only tries that
         * make the same decisions; not for the texel-only modes). */
        double spread[MAX_FIELDS] = {0};
        for (int t = 0; t < (texel_only(mode) ? 0 : PERTURB_TRIES); t++) {
            c_eval(mode, ci, i, true, g, cp);
            bool same = true;
            for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++)
                if (d->fields[f].kind == 'b' &&
                    (cp[d->fields[f].off] > 0.5f) != (c[d->fields[f].off] > 0.5f))
                    same = false;
            if (!same)
                continue;
            for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++) {
                const field *fd = &d->fields[f];
                if (fd->kind != 'v' || any_nonfinite(c + fd->off, fd->n) ||
                    any_nonfinite(cp + fd->off, fd->n))
                    continue;
                for (int k = 0; k < fd->n; k++)
                    spread[f] = fmax(spread[f], fabs((double)cp[fd->off + k] - c[fd->off + k]));
            }
        }

        bool ill_case = false;
        for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++) {
            const field *fd = &d->fields[f];
            if (fd->kind != 'v' || !field_applies(mode, c, fd->off))
                continue;
            double err = 0.0, scale = 0.0, cond = 0.0;
            bool bad = false, ill_field = false;
            if (any_nonfinite(c + fd->off, fd->n)) {
                /* inf (directional distance, Lambda at z = 0): exact */
                for (int k = 0; k < fd->n; k++) {
                    float a = c[fd->off + k], b = g[fd->off + k];
                    if (!(a == b || (isnan(a) && isnan(b))))
                        bad = true;
                }
                err = bad ? INFINITY : 0.0;
            } else {
                for (int k = 0; k < fd->n; k++) {
                    double a = c[fd->off + k], b = g[fd->off + k];
                    err = isfinite(b) ? fmax(err, fabs(a - b)) : INFINITY;
                    scale = fmax(scale, fabs(a));
                }
                cond = ggx_cond(mode, ci, g, fd->off) * scale;
                double tt = tex_tol(mode, ci, fd->off);
                double tol = texel_only(mode)
                                 ? ABS + tt
                                 : REL * scale + ABS + tt + cond + 2.0 * spread[f];
                ill_field = cond + 2.0 * spread[f] > 10.0 * REL * scale + ILL_FLOOR;
                if (ill_field) {
                    st[f].ill++;
                    ill_case = true;
                }
                bad = !(err <= tol);
                if (texel_only(mode) && tt > 0.0)
                    r.texel_ratio = fmax(r.texel_ratio, err / tt);
            }
            st[f].compared++;
            double rel = err / fmax(scale, 1e-30);
            if (err > st[f].max_err)
                st[f].max_err = err;
            if (rel > st[f].max_rel && isfinite(err)) {
                st[f].max_rel = rel;
                st[f].worst = i;
            }
            if (cond + 2.0 * spread[f] <= REL * scale && tex_tol(mode, ci, fd->off) == 0.0 &&
                rel > st[f].max_rel_tight)
                st[f].max_rel_tight = rel; /* checked at <= 2 REL */
            if (bad) {
                st[f].fails++;
                r.value_fail++;
                if (!quiet && printed++ < 10) {
                    fprintf(stderr, "  %s #%d: %s differs by %.3g (scale %.3g, spread %.3g):", d->name,
                            i, fd->name, err, scale, spread[f]);
                    for (int k = 0; k < fd->n; k++)
                        fprintf(stderr, " %.9g/%.9g", g[fd->off + k], c[fd->off + k]);
                    fprintf(stderr, "  (gpu/c)\n");
                }
            }
        }
        r.ill += ill_case;
        if (texel_only(mode)) {
            bool same = true;
            for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++)
                same &= memcmp(c + d->fields[f].off, g + d->fields[f].off,
                               (size_t)d->fields[f].n * sizeof(float)) == 0;
            r.exact += same;
        }
    }
    for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++) {
        double allowed = d->fields[f].max_ill > 0.0 ? d->fields[f].max_ill : 0.02;
        if (st[f].ill > allowed * n)
            r.ill_excess++;
    }
    if (!quiet) {
        for (int f = 0; f < MAX_FIELDS && d->fields[f].name; f++) {
            const field *fd = &d->fields[f];
            if (fd->kind == 'v')
                fprintf(stderr,
                        "  %-14s %-18s compared %5d  max abs err %.3g  max rel err %.3g (#%d), "
                        "%.3g where tol <= 2 REL  ill-conditioned %d  failed %d\n",
                        d->name, fd->name, st[f].compared, st[f].max_err, st[f].max_rel,
                        st[f].worst, st[f].max_rel_tight, st[f].ill, st[f].fails);
            else
                fprintf(stderr, "  %-14s %-18s mismatches away from a threshold: %d\n", d->name,
                        fd->name, st[f].fails);
        }
        fprintf(stderr, "  %-14s %d cases: %d near-threshold decision mismatches, %d "
                "ill-conditioned cases\n", d->name, n, r.near, r.ill);
    }
    return r;
}

/* ---- running the shader ------------------------------------------------- */

/* Runs `prog` in `mode` over n records of `in`; the results go to `out`. */
static bool run_mode(dirt_gpu *gpu, GLuint prog, int mode, const float *in, int n, float *out)
{
    return test_run_model_shader(gpu, prog, mode, in, STRIDE, n, out, STRIDE);
}

/* ---- inputs ------------------------------------------------------------- */

/* A texture coordinate: mostly uniform over [-3, 3] (repeat), else a case
 * where wrapping and flooring decide: texel centres and edges of a w-texel
 * axis (in float, as a scene would give them), multiples of 1/8, -0 and
 * tiny negatives (u - floor(u) rounds to exactly 1), 1 - 2^-24, 1, large
 * magnitudes (floor(u) = u), denormals, +-inf and NaN (read as 0). */
static float random_uv(int w)
{
    int k = irange(40);
    if (k >= 16)
        return urange(-3.0f, 3.0f);
    int i = irange(w + 1) - irange(2) * w;
    switch (k) {
    case 0: return ((float)i + 0.5f) / (float)w;        /* a texel centre */
    case 1: return (float)i / (float)w;                 /* a texel edge */
    case 2: return (float)irange(25) / 8.0f - 1.0f;
    case 3: return -0.0f;
    case 4: return -urange(1e-12f, 1e-7f);
    case 5: return -FLT_MIN;
    case 6: return 1.0f - 1.0f / 16777216.0f;
    case 7: return 1.0f;
    case 8: return urange(-1e5f, 1e5f);
    case 9: return irange(2) ? 1e30f : -3e38f;
    case 10: return FLT_MIN / 8.0f;                     /* denormal */
    case 11: return INFINITY;
    case 12: return -INFINITY;
    case 13: return NAN;
    case 14: return (float)i + 0.5f / (float)w;         /* the centre of texel 0 of a repeat */
    default: return 1.0f + 1e-7f * urand();
    }
}

/* The tangential part of wo's smooth refraction (-wo.xy / eta) of record r. */
static float wo_refr_x(const float *r) { return r[8] / r[7]; }
static float wo_refr_y(const float *r) { return r[9] / r[7]; }

static void fill_inputs(int mode, float *in, int n, size_t num_materials, int num_textures)
{
    memset(in, 0, (size_t)n * STRIDE * sizeof(float));
    for (int i = 0; i < n; i++) {
        float *r = in + (size_t)i * STRIDE;
        switch (mode) {
        case MODE_WARPS:
            r[0] = random_u();
            r[1] = random_u();
            break;
        case MODE_VNDF: {
            int k = irange(10);
            r[0] = k == 0 ? 0.0f : (k == 1 ? 1.0f : urand());
            r[1] = random_u();
            r[2] = random_u();
            put3(r + 4, random_upper());
            break;
        }
        case MODE_ONB:
            put3(r, random_sphere());
            break;
        case MODE_EVAL:
        case MODE_SAMPLE:
        case MODE_TRANS: {
            dirt_bsdf b;
            random_bsdf(&b);
            put3(r, b.base_color);
            r[3] = b.metallic;
            r[4] = b.alpha;
            r[5] = b.specular;
            r[6] = b.transmission;
            r[7] = b.eta;
            put3(r + 16, b.f0);
            put3(r + 8, random_upper());
            if (mode == MODE_EVAL) {
                dirt_vec3 wi = random_upper();
                if (b.transmission > 0.0f && irange2(2)) /* through the surface */
                    wi.z = -wi.z;
                if (b.transmission > 0.0f && irange2(20) == 0) /* near the refraction of wo */
                    wi = v3_normalize(v3(-wo_refr_x(r), -wo_refr_y(r), -sqrtf(fmaxf(0.0f,
                        1.0f - (r[8] * r[8] + r[9] * r[9]) / (b.eta * b.eta))) - 1e-3f * urand2()));
                put3(r + 12, wi);
            } else if (mode == MODE_TRANS) {
                r[12] = irange2(10) == 0 ? sqrtf(fmaxf(0.0f, 1.0f - b.eta * b.eta)) : random_u();
            } else {
                r[12] = random_u();
                r[13] = random_u();
                r[14] = random_u();
            }
            break;
        }
        case MODE_MISC: {
            int k = irange(8);
            r[0] = k == 0 ? 0.0f : urange(0.0f, 100.0f);
            r[1] = k == 1 || k == 0 ? 0.0f : urange(0.0f, 100.0f);
            r[2] = urand();
            put3(r + 4, v3(urange(0.0f, 3.0f), urange(0.0f, 1.5f), urange(0.0f, 1.0f)));
            break;
        }
        case MODE_LIGHT: {
            dirt_light *l = &g_lights[i];
            memset(l, 0, sizeof(*l));
            l->type = (enum dirt_light_type)irange(3);
            for (int c = 0; c < 3; c++) {
                l->position[c] = urange(-10.0f, 10.0f);
                l->direction[c] = urange(-2.0f, 2.0f);
                l->color[c] = urange(0.0f, 100.0f);
            }
            int k = irange(40);
            if (k == 0)
                l->color[0] = l->color[1] = l->color[2] = 0.0f;
            if (k == 1)
                l->direction[0] = l->direction[1] = l->direction[2] = 0.0f;
            l->range = irange(2) ? 0.0f : urange(1.0f, 30.0f);
            l->outer_cone = urange(0.05f, 1.5f);
            l->inner_cone = irange(8) == 0 ? l->outer_cone : urange(0.0f, l->outer_cone);
            dirt_vec3 pt = v3(urange(-10.0f, 10.0f), urange(-10.0f, 10.0f), urange(-10.0f, 10.0f));
            if (k == 2)
                pt = v3_load(l->position); /* at the light: no contribution */
            struct dirt_gpu_model_light rec;
            dirt_gpu_light_pack(l, &rec);
            put4(r, rec.position);
            put4(r + 4, rec.direction);
            put4(r + 8, rec.color);
            put4(r + 12, rec.cone);
            put3(r + 16, pt);
            break;
        }
        case MODE_AREA: {
            int k = irange(10);
            if (k == 0 && g_area->count > 0) /* exactly at a cdf boundary */
                r[0] = g_area->cdf[irange((int)g_area->count)] / g_area->total_area;
            else
                r[0] = random_u();
            break;
        }
        case MODE_MATERIAL:
            r[0] = (float)irange((int)num_materials);
            r[1] = random_uv(1 + irange(17));
            r[2] = random_uv(1 + irange(17));
            break;
        case MODE_CAMERA: {
            dirt_camera *c = &g_cams[i];
            memset(c, 0, sizeof(*c));
            float eye[3] = {urange(-5, 5), urange(-5, 5), urange(-5, 5)};
            float target[3] = {eye[0] + urange(-1, 1), eye[1] + urange(-0.5f, 0.5f),
                               eye[2] + (irange(2) ? 1.0f : -1.0f)};
            float up[3] = {0.0f, 1.0f, 0.0f};
            dirt_camera_look_at(c, eye, target, up);
            int k = irange(10);
            c->type = k < 2 ? DIRT_CAMERA_ORTHOGRAPHIC : DIRT_CAMERA_PERSPECTIVE;
            c->yfov = irange(5) == 0 ? 0.0f : urange(0.2f, 2.0f);
            c->aspect = irange(2) ? 0.0f : urange(0.5f, 2.0f);
            c->xmag = irange(3) == 0 ? 0.0f : urange(0.5f, 5.0f);
            c->ymag = irange(3) == 0 ? 0.0f : urange(0.5f, 5.0f);
            if (k >= 6) { /* thin lens */
                c->aperture_radius = urange(0.01f, 0.5f);
                c->focus_distance = urange(0.5f, 20.0f);
            }
            struct dirt_gpu_model_camera rec;
            dirt_gpu_camera_pack(c, &rec);
            put4(r, rec.eye);
            put4(r + 4, rec.forward);
            put4(r + 8, rec.right);
            put4(r + 12, rec.up);
            put4(r + 16, rec.lens);
            int w = 1 + irange(2000), h = 1 + irange(2000);
            r[20] = (float)w;
            r[21] = (float)h;
            r[22] = urand() * (float)w;
            r[23] = urand() * (float)h;
            r[24] = random_u();
            r[25] = random_u();
            break;
        }
        case MODE_TEXTURE: {
            /* -1 and num_textures: out of range (white) */
            int t = irange(num_textures + 2) - 1;
            bool in_range = t >= 0 && (size_t)t < g_ntex;
            int w = in_range && g_tex[t].width > 0 ? g_tex[t].width : 4;
            int h = in_range && g_tex[t].height > 0 ? g_tex[t].height : 4;
            r[0] = (float)t;
            r[1] = (float)irange(2);
            r[2] = random_uv(w);
            r[3] = random_uv(h);
            break;
        }
        }
    }
}

/* ---- synthetic scene data ------------------------------------------------ */

#define NUM_TEX 8
#define NUM_MATS 64
#define TEX_MAX_TEXELS (64 * 33)
static uint8_t tex_pixels[NUM_TEX][TEX_MAX_TEXELS * 4];
static dirt_texture textures[NUM_TEX];
static dirt_material materials[NUM_MATS];
static float speculars[NUM_MATS];

/* Random textures at their own sizes, none a power of two in both axes:
 * 8x4, 3x5, 17x4, 1x1, a dark 5x3 (bytes 0-15: the relative bound must hold
 * where the values are small), 1x7, 64x33, and one without pixels. The
 * sRGB flag alternates (the lookup's slot decides the decode, not it). */
static void make_textures(void)
{
    static const int size[NUM_TEX][2] = {{8, 4}, {3, 5}, {17, 4}, {1, 1},
                                         {5, 3}, {1, 7}, {64, 33}, {0, 0}};
    for (int t = 0; t < NUM_TEX; t++) {
        dirt_texture *x = &textures[t];
        memset(x, 0, sizeof(*x));
        snprintf(x->name, sizeof(x->name), "t%d", t);
        x->srgb = t % 2 == 0;
        if (size[t][0] == 0)
            continue; /* no pixels: reads white */
        x->width = size[t][0];
        x->height = size[t][1];
        for (int k = 0; k < x->width * x->height * 4; k++)
            tex_pixels[t][k] = (uint8_t)(rnd32() & (t == 4 ? 15u : 255u));
        x->rgba = tex_pixels[t];
    }
}

static int random_tex(void)
{
    int k = irange(10);
    return k < 3 ? DIRT_NO_TEXTURE : (k == 3 ? 17 /* out of range */ : irange(NUM_TEX));
}

static void make_materials(void)
{
    for (int i = 0; i < NUM_MATS; i++) {
        dirt_material *m = &materials[i];
        memset(m, 0, sizeof(*m));
        for (int c = 0; c < 4; c++)
            m->base_color[c] = urand();
        m->base_color_tex = random_tex();
        int k = irange(3);
        m->metallic = k == 0 ? 0.0f : (k == 1 ? 1.0f : urange(0.0f, 1.2f));
        m->roughness = urange(0.0f, 1.2f);
        m->metallic_roughness_tex = random_tex();
        if (irange(2)) {
            for (int c = 0; c < 3; c++)
                m->emissive[c] = urange(0.0f, 2.0f);
            m->emissive_strength = irange(4) == 0 ? 0.0f : urange(0.5f, 20.0f);
        } else {
            m->emissive_strength = 1.0f;
        }
        m->emissive_tex = random_tex();
        m->double_sided = irange(2);
        speculars[i] = urange(-0.2f, 1.2f);
        /* KHR_materials_specular, _transmission, _ior */
        m->specular = irange2(3) == 0 ? 1.0f : urange2(0.0f, 1.2f);
        m->specular_tex = random_tex();
        for (int c = 0; c < 3; c++)
            m->specular_color[c] = irange2(3) == 0 ? 1.0f : urange2(0.0f, 30.0f);
        m->specular_color_tex = random_tex();
        k = irange2(4);
        m->transmission = k == 0 ? 0.0f : (k == 1 ? 1.0f : urange2(0.0f, 1.2f));
        m->transmission_tex = random_tex();
        k = irange2(6);
        m->ior = k == 0 ? 1.5f : (k == 1 ? 0.0f : (k == 2 ? 1.0f : urange2(1.0f, 3.0f)));
    }
}

static dirt_area_lights make_area(float *cdf, uint32_t *prim, size_t n)
{
    dirt_area_lights a = {n, prim, cdf, 0.0f};
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        int k = irange(10);
        double area = k == 0 ? 1e-7 * (double)urand() + 1e-9 : -log(1.0 - (double)urand()) + 1e-6;
        sum += area;
        cdf[i] = (float)sum;
        prim[i] = (uint32_t)(3 * i + 1);
    }
    a.total_area = (float)sum;
    return a;
}

/* ---- checks --------------------------------------------------------------- */

static bool pass(const compare_result *r)
{
    return r->bool_fail == 0 && r->value_fail == 0 && (double)r->near <= 1e-3 * r->cases &&
           r->ill_excess == 0;
}

static void check_mode(dirt_gpu *gpu, GLuint prog, GLuint fault_prog, int mode, float *in,
                       float *out, int n, size_t num_materials, int num_textures)
{
    const mode_desc *d = mode_of(mode);
    fill_inputs(mode, in, n, num_materials, num_textures);
    CHECK(run_mode(gpu, prog, mode, in, n, out));
    compare_result r = compare(mode, in, out, n, false);
    if (mode == MODE_TEXTURE) { /* the decode's error, by slot */
        double e[2] = {0.0, 0.0}, q[2] = {0.0, 0.0};
        float c[STRIDE];
        for (int i = 0; i < n; i++) {
            const float *ci = in + (size_t)i * STRIDE, *g = out + (size_t)i * STRIDE;
            bool srgb = ci[1] != 0.0f;
            double tol = texel_tol((int)ci[0], srgb);
            c_eval(mode, ci, i, false, NULL, c);
            for (int k = 0; k < 4; k++) {
                double err = fabs((double)g[k] - c[k]);
                e[srgb] = fmax(e[srgb], err);
                if (tol > 0.0)
                    q[srgb] = fmax(q[srgb], err / (tol / TEXEL_REL));
            }
        }
        fprintf(stderr, "  %-14s max abs err: linear %.3g, sRGB %.3g; relative to the "
                "texture's largest texel: linear %.3g, sRGB %.3g (TEXEL_REL %.3g)\n", d->name,
                e[0], e[1], q[0], q[1], TEXEL_REL);
    }
    if (texel_only(mode))
        fprintf(stderr, "  %-14s %d of %d records bit-exact; largest error %.3g of its "
                "tolerance\n", d->name, r.exact, n, r.texel_ratio);
    CHECK_MSG(pass(&r), "%s: %d decision mismatches, %d value mismatches, %d near-threshold, "
              "%d ill-conditioned of %d (%d fields over their bound)", d->name, r.bool_fail,
              r.value_fail, r.near, r.ill, r.cases, r.ill_excess);
    if (fault_prog) {
        CHECK(run_mode(gpu, fault_prog, mode, in, n, out));
        compare_result f = compare(mode, in, out, n, true);
        int caught = f.bool_fail + f.value_fail;
        fprintf(stderr, "  %-14s faulty shader: %d mismatches (fields) over %d cases\n", d->name,
                caught, n);
        CHECK_MSG(caught >= n / 2, "%s: the comparison missed a faulty shader", d->name);
    }
}

/* The texel buffer: header counts, one record per texture (texels packed
 * in scene order after the records, 0 x 0 for no pixels), every texel word
 * the texture's four bytes (R low), nothing else. */
static void check_texel_pack(const dirt_gpu_texel_buffer *b)
{
    size_t texels = 0;
    for (int t = 0; t < NUM_TEX; t++)
        texels += (size_t)textures[t].width * (size_t)textures[t].height;
    CHECK(b->num_textures == NUM_TEX && b->num_texels == texels);
    CHECK(b->size == 16 + NUM_TEX * 16 + texels * 4);
    struct dirt_gpu_model_texels hdr;
    memcpy(&hdr, b->words, sizeof(hdr));
    CHECK(hdr.counts.x == NUM_TEX && hdr.counts.y == NUM_TEX * 4 + texels &&
          hdr.counts.z == 0 && hdr.counts.w == 0);
    const uint32_t *body = b->words + 4;
    uint32_t next = NUM_TEX * 4;
    int bad = 0;
    for (int t = 0; t < NUM_TEX; t++) {
        struct dirt_gpu_model_texture rec;
        memcpy(&rec, body + 4 * t, sizeof(rec));
        const dirt_texture *x = &textures[t];
        if (!x->rgba) {
            CHECK(rec.extent.x == 0 && rec.extent.y == 0 && rec.extent.z == 0);
            continue;
        }
        CHECK_MSG(rec.extent.x == next && rec.extent.y == (uint32_t)x->width &&
                  rec.extent.z == (uint32_t)x->height && rec.extent.w == 0,
                  "texture %d: record (%u, %u, %u, %u)", t, rec.extent.x, rec.extent.y,
                  rec.extent.z, rec.extent.w);
        for (int k = 0; k < x->width * x->height; k++) {
            uint32_t w = body[rec.extent.x + (uint32_t)k];
            for (int c = 0; c < 4; c++)
                bad += ((w >> (8 * c)) & 255u) != x->rgba[4 * k + c];
        }
        next += (uint32_t)(x->width * x->height);
    }
    CHECK_MSG(bad == 0, "%d texel bytes differ from the textures'", bad);
    /* No textures: the header alone. */
    dirt_gpu_texel_buffer none;
    CHECK(dirt_gpu_textures_pack(NULL, 0, &none));
    CHECK(none.size == 16 && none.words && none.words[0] == 0 && none.words[1] == 0);
    dirt_gpu_texel_buffer_free(&none);
}

static int limit_errors;
static void count_limit_errors(void *user, enum dirt_log_level level, const char *file, int line,
                               const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level == DIRT_LOG_ERROR && strstr(msg, "scene's texels") &&
        strstr(msg, "textures smaller or fewer"))
        limit_errors++;
    fprintf(stderr, "[log] %s\n", msg);
}

/* The texel table against the GPU's storage-block limit: at exactly the
 * limit one block; one byte under it, texel-buffer parts holding the same
 * words (read back); with parts of a sixteenth of it (DIRT_MAX_BLOCK_BYTES'
 * override), more parts than one split array has: refused with one error
 * saying what to change. */
static void check_texel_limit(dirt_gpu *gpu, const dirt_gpu_texel_buffer *b)
{
    dirt_gpu_caps saved = gpu->caps;
    size_t words = b->size / 4;
    gl_split s = {0};
    gpu->caps.max_ssbo_size = (int64_t)b->size; /* exactly the limit: one block */
    bool ok = dirt_gpu_textures_upload(gpu, b, &s);
    CHECK(ok && s.buf[0] && s.layout.parts == 0);
    gpu->caps.max_ssbo_size = (int64_t)b->size - 1;
    gpu->caps.block_override = (int64_t)b->size / 3;
    ok = dirt_gpu_textures_upload(gpu, b, &s);
    CHECK_MSG(ok && s.layout.parts >= 3 && s.layout.parts <= 6, "%d parts", s.layout.parts);
    uint32_t *back = calloc(words, 4);
    CHECK(back && gl_split_read(&s, 0, words, back) && !memcmp(back, b->words, b->size));
    free(back);
    gpu->caps.block_override = (int64_t)b->size / 16;
    limit_errors = 0;
    dirt_log_set_callback(count_limit_errors, NULL);
    ok = dirt_gpu_textures_upload(gpu, b, &s);
    dirt_log_set_callback(NULL, NULL);
    CHECK(!ok && !s.buf[0] && limit_errors == 1);
    gpu->caps = saved;
    gl_split_release(&s);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    fprintf(stderr, "device: %s\n", desc);

    GLuint prog = gl_program_compute("integrator/test_model.comp", NULL, 0);
    glsl_define fault_def[] = {{"TEST_FAULT", "1"}};
    GLuint fault = gl_program_compute("integrator/test_model.comp", fault_def, 1);
    CHECK(prog != 0 && fault != 0);
    if (!prog || !fault) {
        dirt_gpu_destroy(gpu);
        return check_finish();
    }
    float *in = malloc((size_t)N * STRIDE * sizeof(float));
    float *out = malloc((size_t)N * STRIDE * sizeof(float));
    CHECK(in && out);
    if (!in || !out)
        return check_finish();

    /* Part 1: synthetic materials, textures and area lights. */
    make_textures();
    make_materials();
    static float cdf[1000];
    static uint32_t prim[1000];
    dirt_area_lights area = make_area(cdf, prim, 1000);
    g_mats = materials;
    g_spec = speculars;
    g_tex = textures;
    g_ntex = NUM_TEX;
    g_area = &area;

    struct dirt_gpu_model_material gm[NUM_MATS];
    dirt_gpu_materials_pack(materials, NUM_MATS, speculars, NUM_TEX, gm);
    dirt_gpu_area_table at;
    CHECK(dirt_gpu_area_lights_pack(&area, 3, &at));
    texture_maxima();
    dirt_gpu_texel_buffer tb;
    CHECK(dirt_gpu_textures_pack(textures, NUM_TEX, &tb));
    check_texel_pack(&tb);
    check_texel_limit(gpu, &tb);
    dirt_gpu_model_tables tables = {0};
    tables.materials = gl_buffer_create(gpu, sizeof(gm), gm, false, "test materials");
    tables.area_cdf = gl_buffer_create(gpu, at.cdf_size, at.cdf, false, "test cdf");
    tables.area_prims = gl_buffer_create(gpu, at.prims_size, at.prims, false, "test prims");
    tables.punctual = gl_buffer_create(gpu, 64, NULL, false, "test lights");
    tables.camera = gl_buffer_create(gpu, 80, NULL, false, "test camera");
    CHECK(dirt_gpu_textures_upload(gpu, &tb, &tables.texels));
    dirt_gpu_model_tables_bind(&tables);

    static const int all[] = {MODE_WARPS,  MODE_VNDF,  MODE_ONB,      MODE_EVAL,
                              MODE_SAMPLE, MODE_MISC,  MODE_LIGHT,    MODE_AREA,
                              MODE_CAMERA, MODE_TEXTURE, MODE_MATERIAL, MODE_TRANS};
    for (size_t k = 0; k < sizeof(all) / sizeof(all[0]); k++)
        check_mode(gpu, prog, fault, all[k], in, out, N, NUM_MATS, NUM_TEX);
    dirt_gpu_model_tables_destroy(&tables);
    dirt_gpu_area_table_free(&at);
    dirt_gpu_texel_buffer_free(&tb);

    /* Part 2: the default scene through dirt_gpu_model_tables_create. */
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *frame = scene ? dirt_scene_evaluate(scene, 0.0f, NULL) : NULL;
    CHECK(scene && frame);
    if (frame) {
        dirt_area_lights sa;
        CHECK(dirt_area_lights_build(&sa, frame, dirt_scene_materials(scene),
                                     dirt_scene_num_materials(scene)));
        dirt_camera cam;
        if (frame->num_cameras > 0)
            cam = frame->cameras[0];
        else
            dirt_camera_auto(frame, &cam);
        dirt_gpu_model_tables st;
        CHECK(dirt_gpu_model_tables_create(gpu, scene, frame, &sa, &cam, NULL, &st));
        CHECK(st.num_materials == dirt_scene_num_materials(scene) && st.num_area == sa.count);
        dirt_gpu_model_tables_bind(&st);
        g_mats = dirt_scene_materials(scene);
        g_spec = NULL;
        g_tex = dirt_scene_textures(scene);
        g_ntex = dirt_scene_num_textures(scene);
        g_area = &sa;
        texture_maxima();
        fprintf(stderr, "default scene: %zu materials, %zu emissive triangles\n",
                st.num_materials, sa.count);
        check_mode(gpu, prog, 0, MODE_MATERIAL, in, out, 1000, st.num_materials, 1);
        if (sa.count > 0)
            check_mode(gpu, prog, 0, MODE_AREA, in, out, 1000, st.num_materials, 1);
        struct dirt_gpu_model_camera rc, pc;
        dirt_gpu_camera_pack(&cam, &pc);
        CHECK(gl_buffer_read(st.camera, 0, sizeof(rc), &rc));
        CHECK(memcmp(&rc, &pc, sizeof(rc)) == 0);
        dirt_gpu_model_tables_destroy(&st);
        dirt_area_lights_free(&sa);
    }
    dirt_frame_destroy(frame);
    dirt_scene_destroy(scene);

    free(in);
    free(out);
    gl_program_destroy(&prog);
    gl_program_destroy(&fault);
    CHECK(gl_check("end of test"));
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
