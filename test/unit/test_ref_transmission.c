/* The transmission lobe of the BSDF (KHR_materials_transmission + _ior +
 * _specular; src/integrator/bsdf.c, doc/light-transport.md section 3):
 *  - energy, importance form (a transmitted weight times eta^2, undoing the
 *    radiance compression, so a lossless interface scores exactly 1): the
 *    directional albedo of white dielectrics with transmission is <= 1 for
 *    every roughness, angle, side (eta = ior on the front, 1 / ior on the
 *    back, total internal reflection included) and specular colour; 1 for
 *    smooth clear glass on either side;
 *  - generalized reciprocity of the rough transmission, f(wi, wo; 1 / eta) =
 *    eta^2 f(wo, wi; eta), and the plain reciprocity of the reflection;
 *  - the pdf integrates over the whole sphere to the sampler's success rate
 *    (~1: only refractions that come out on the wrong side fail), and a
 *    histogram of the sampled directions over the sphere matches it;
 *  - the smooth (delta) transmission: Snell's direction, weight
 *    (1 - F_t) / (eta^2 p_trans), none on total internal reflection;
 *  - rough transmission against an independent double transcription of the
 *    documented formula (Walter et al. 2007);
 *  - the F0 of KHR_materials_ior / _specular: 0.04 at ior 1.5, the spec's
 *    clamp of f0(ior) x specular colour, F90 = the specular factor.
 * Sample counts and tolerances are stated where they are checked. */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "integrator/integrator.h"
#include "integrator/rng.h"
#include "core/vec3.h"

#define PI 3.14159265358979323846

static dirt_vec3 dir_from_mu(float mu, float phi)
{
    float s = sqrtf(fmaxf(0.0f, 1.0f - mu * mu));
    return v3(s * cosf(phi), s * sinf(phi), mu);
}

/* A white (or `c`) dielectric with transmission t, seen with relative
 * index eta. */
static dirt_bsdf glass(float c, float roughness, float t, float eta, float spec)
{
    float f0 = dirt_ior_f0(eta >= 1.0f ? eta : 1.0f / eta);
    dirt_bsdf b = {{c, c, c}, 0.0f, roughness * roughness, spec, {f0, f0, f0}, t, eta};
    return b;
}

/* Albedo (red channel), importance form, from the sampler: mean weight over
 * an n x n stratified grid of (u1, u2), each lobe taken with its
 * probability (the lobe choice integrated exactly); transmitted weights
 * times eta^2. */
static double albedo(const dirt_bsdf *b, dirt_vec3 wo, int n)
{
    const float u_last = 1.0f - 1.0f / 16777216.0f;
    float ps, pt;
    dirt_bsdf_lobe_probabilities(b, wo, &ps, &pt);
    float pd = fmaxf(0.0f, 1.0f - ps - pt);
    float lobe_u[3] = {0.0f, ps + 0.5f * pd, u_last};
    float lobe_p[3] = {ps, pd, pt};
    double s = 0.0;
    for (int l = 0; l < 3; l++) {
        if (!(lobe_p[l] > 0.0f))
            continue;
        double sl = 0.0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                dirt_bsdf_sample smp;
                if (!dirt_bsdf_sample_dir(b, wo, lobe_u[l], (i + 0.5f) / n, (j + 0.5f) / n, &smp))
                    continue;
                double w = smp.weight.x;
                if (smp.wi.z < 0.0f)
                    w *= (double)b->eta * b->eta;
                sl += w;
            }
        s += lobe_p[l] * sl / ((double)n * n);
    }
    return s;
}

static void check_energy(void)
{
    static const float rough[] = {0.0f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f};
    static const float mus[] = {1.0f, 0.9f, 0.7f, 0.5f, 0.3f, 0.15f, 0.05f};
    static const float etas[] = {1.5f, 1.0f / 1.5f, 1.33f, 1.0f / 1.33f, 2.4f, 1.0f / 2.4f};
    static const float trans[] = {1.0f, 0.5f};
    double worst = 0.0, worst_smooth = 0.0;
    for (size_t e = 0; e < sizeof(etas) / sizeof(etas[0]); e++)
        for (size_t t = 0; t < 2; t++)
            for (size_t r = 0; r < sizeof(rough) / sizeof(rough[0]); r++)
                for (size_t a = 0; a < sizeof(mus) / sizeof(mus[0]); a++) {
                    dirt_bsdf b = glass(1.0f, rough[r], trans[t], etas[e], 1.0f);
                    dirt_vec3 wo = dir_from_mu(mus[a], 0.4f);
                    double es = albedo(&b, wo, 128);
                    CHECK_MSG(es <= 1.0 + 2e-3, "eta %.3f t %.1f r %.2f mu %.2f: albedo %.5f > 1",
                              etas[e], trans[t], rough[r], mus[a], es);
                    worst = fmax(worst, es);
                    if (rough[r] == 0.0f && trans[t] == 1.0f) {
                        /* smooth clear glass: reflection F + transmission
                         * 1 - F, exactly (TIR: all reflected) */
                        worst_smooth = fmax(worst_smooth, fabs(es - 1.0));
                        CHECK_MSG(fabs(es - 1.0) < 1e-5, "smooth glass eta %.3f mu %.2f: %.6f",
                                  etas[e], mus[a], es);
                    }
                }
    /* Specular colour (clamped F0 up to 1) and factor: still <= 1. */
    for (int k = 0; k < 200; k++) {
        uint32_t key = dirt_rng_key(31u, (uint32_t)k, 0u, 0u);
        float u[8];
        for (uint32_t d = 0; d < 8; d++)
            u[d] = dirt_rng_next_float(key, d);
        dirt_bsdf b = glass(1.0f, u[0], u[1], u[2] < 0.5f ? 1.0f + 2.0f * u[3] : 1.0f / (1.0f + 2.0f * u[3]),
                            u[4]);
        b.f0 = v3(u[5], u[6], u[7] * 0.2f);
        dirt_vec3 wo = dir_from_mu(0.05f + 0.95f * dirt_rng_next_float(key, 8), 1.0f);
        double es = albedo(&b, wo, 64);
        worst = fmax(worst, es);
        CHECK_MSG(es <= 1.0 + 2e-3, "random %d: albedo %.5f > 1", k, es);
    }
    fprintf(stderr, "energy: max albedo %.5f (importance form), smooth clear glass |1 - E| <= %.2g\n",
            worst, worst_smooth);
    /* Rough clear glass loses only what single scattering misses. */
    dirt_bsdf b = glass(1.0f, 0.3f, 1.0f, 1.5f, 1.0f);
    double e = albedo(&b, dir_from_mu(0.8f, 0.0f), 256);
    fprintf(stderr, "rough (0.3) clear glass at mu 0.8: %.5f\n", e);
    CHECK(e > 0.97 && e <= 1.0 + 1e-3);
}

static void check_reciprocity(void)
{
    int bad = 0, tested = 0;
    for (uint32_t s = 0; s < 20000; s++) {
        uint32_t key = dirt_rng_key(6u, s, 0u, 0u);
        float u[8];
        for (uint32_t d = 0; d < 8; d++)
            u[d] = dirt_rng_next_float(key, d);
        float eta = 1.1f + 1.5f * u[0];
        if (u[1] < 0.5f)
            eta = 1.0f / eta;
        dirt_bsdf b = glass(u[2], 0.1f + 0.9f * u[3], 0.2f + 0.8f * u[4], eta, 1.0f);
        dirt_bsdf r = b;
        r.eta = 1.0f / eta;
        dirt_vec3 wo = dirt_sample_cosine(u[5], u[6]);
        dirt_vec3 wi = dirt_sample_cosine(u[7], dirt_rng_next_float(key, 8));
        wi.z = -wi.z;
        if (wo.z < 0.02f || wi.z > -0.02f)
            continue;
        dirt_vec3 a = dirt_bsdf_eval(&b, wo, wi);
        dirt_vec3 c = dirt_bsdf_eval(&r, v3_neg(wi), v3_neg(wo));
        /* seen from wi's side the pair is (-wi, -wo) in a frame whose +z
         * faces wi: the same geometry mirrored through the surface */
        double expect = (double)eta * eta * a.x;
        if (!(a.x >= 0.0f) || !isfinite(a.x))
            bad++;
        if (fabs(c.x - expect) > 2e-3 * fmax(expect, 1e-3))
            bad++;
        tested++;
    }
    fprintf(stderr, "reciprocity: %d transmitted pairs\n", tested);
    CHECK(tested > 15000);
    CHECK_MSG(bad == 0, "%d pairs break f(wi, wo; 1/eta) = eta^2 f(wo, wi; eta)", bad);
    /* Reflection with transmission stays symmetric. */
    bad = 0;
    for (uint32_t s = 0; s < 5000; s++) {
        uint32_t key = dirt_rng_key(7u, s, 0u, 0u);
        dirt_bsdf b = glass(0.9f, 0.05f + dirt_rng_next_float(key, 0), dirt_rng_next_float(key, 1),
                            dirt_rng_next_float(key, 2) < 0.5f ? 1.5f : 1.0f / 1.5f, 1.0f);
        dirt_vec3 wo = dirt_sample_cosine(dirt_rng_next_float(key, 3), dirt_rng_next_float(key, 4));
        dirt_vec3 wi = dirt_sample_cosine(dirt_rng_next_float(key, 5), dirt_rng_next_float(key, 6));
        dirt_vec3 a = dirt_bsdf_eval(&b, wo, wi), c = dirt_bsdf_eval(&b, wi, wo);
        if (fabsf(a.x - c.x) > 1e-5f * fmaxf(1.0f, a.x))
            bad++;
    }
    CHECK_MSG(bad == 0, "%d non-reciprocal reflections", bad);
}

/* Histogram of the sampled directions over the whole sphere against the
 * pdf: 32 bins in cos theta (in [-1, 1]) x 16 in phi, expected counts
 * N int_bin pdf by a 48 x 48 midpoint rule per bin (the refraction pdf
 * peaks sharply inside some bins: 12 x 12 missed 17 % of one). Bins expecting >= 100:
 * |obs - exp| <= 5 sqrt(exp) + 0.03 exp. The success rate must equal the
 * pdf's integral over the sphere within 5e-3. */
static void check_histogram(const char *name, const dirt_bsdf *b, dirt_vec3 wo)
{
    enum { NMU = 32, NPHI = 16, SUB = 48, N = 1000000 };
    static double obs[NMU][NPHI];
    for (int i = 0; i < NMU; i++)
        for (int j = 0; j < NPHI; j++)
            obs[i][j] = 0.0;
    long ok = 0, below = 0, pdf_bad = 0;
    for (uint32_t s = 0; s < N; s++) {
        uint32_t key = dirt_rng_key(98u, s, 0u, 1u);
        dirt_bsdf_sample smp;
        if (!dirt_bsdf_sample_dir(b, wo, dirt_rng_next_float(key, DIRT_RNG_DIM_LOBE),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_U),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_V), &smp))
            continue;
        CHECK(!smp.delta);
        ok++;
        below += smp.wi.z < 0.0f;
        float p = dirt_bsdf_pdf(b, wo, smp.wi);
        pdf_bad += fabsf(p - smp.pdf) > 1e-5f * p;
        int i = (int)((smp.wi.z + 1.0f) * 0.5f * NMU);
        double phi = atan2(smp.wi.y, smp.wi.x);
        if (phi < 0.0)
            phi += 2.0 * PI;
        int j = (int)(phi / (2.0 * PI) * NPHI);
        i = i < 0 ? 0 : (i >= NMU ? NMU - 1 : i);
        j = j >= NPHI ? NPHI - 1 : j;
        obs[i][j] += 1.0;
    }
    CHECK_MSG(pdf_bad == 0, "%s: %ld samples report a pdf other than dirt_bsdf_pdf", name, pdf_bad);
    double total = 0.0, total_below = 0.0, worst = 0.0;
    int bad = 0, tested = 0;
    for (int i = 0; i < NMU; i++)
        for (int j = 0; j < NPHI; j++) {
            double integral = 0.0;
            for (int a = 0; a < SUB; a++)
                for (int c = 0; c < SUB; c++) {
                    float mu = (float)(-1.0 + 2.0 * (i + (a + 0.5) / SUB) / NMU);
                    float phi = (float)((j + (c + 0.5) / SUB) / NPHI * 2.0 * PI);
                    integral += dirt_bsdf_pdf(b, wo, dir_from_mu(mu, phi));
                }
            integral *= (2.0 / NMU) * (2.0 * PI / NPHI) / (SUB * SUB);
            total += integral;
            if (i < NMU / 2)
                total_below += integral;
            double exp = integral * N;
            if (exp < 100.0)
                continue;
            tested++;
            double dev = fabs(obs[i][j] - exp), bound = 5.0 * sqrt(exp) + 0.03 * exp;
            worst = fmax(worst, dev / bound);
            if (dev > bound) {
                bad++;
                fprintf(stderr, "%s: bin (%d,%d) observed %.0f expected %.1f\n", name, i, j,
                        obs[i][j], exp);
            }
        }
    fprintf(stderr, "histogram %-22s %d bins, worst %.2f of bound, success %.4f (below %.4f), "
            "pdf integral %.4f (below %.4f)\n", name, tested, worst, (double)ok / N,
            (double)below / N, total, total_below);
    CHECK_MSG(bad == 0, "%s: %d bins outside the bound", name, bad);
    CHECK(tested >= 40);
    CHECK_NEAR((double)ok / N, total, 5e-3);
    CHECK_NEAR((double)below / N, total_below, 5e-3);
    CHECK(total > 0.9 && total < 1.0 + 5e-3);
}

/* The rough transmission written again in double from the document. */
static double model_transmission(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi)
{
    double eta = b->eta, a = b->alpha;
    double h[3] = {wo.x + eta * wi.x, wo.y + eta * wi.y, wo.z + eta * wi.z};
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    double sg = h[2] < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++)
        h[k] *= sg / hl;
    double co = wo.x * h[0] + wo.y * h[1] + wo.z * h[2];
    double ci = wi.x * h[0] + wi.y * h[1] + wi.z * h[2];
    if (co <= 0 || ci >= 0)
        return 0.0;
    double d = a * a / (PI * pow(h[2] * h[2] * (a * a - 1.0) + 1.0, 2.0));
    double to2 = (1.0 - (double)wo.z * wo.z) / ((double)wo.z * wo.z);
    double ti2 = (1.0 - (double)wi.z * wi.z) / ((double)wi.z * wi.z);
    double g2 = 1.0 / (1.0 + 0.5 * (sqrt(1.0 + a * a * to2) - 1.0) + 0.5 * (sqrt(1.0 + a * a * ti2) - 1.0));
    double c = co;
    double ft = 1.0;
    if (eta < 1.0) {
        double s2 = (1.0 - co * co) / (eta * eta);
        c = s2 < 1.0 ? sqrt(1.0 - s2) : -1.0;
    }
    if (c >= 0.0)
        ft = b->specular * (b->f0.x + (1.0 - b->f0.x) * pow(1.0 - c, 5.0));
    double den = co + eta * ci;
    return (1 - b->metallic) * b->transmission * b->base_color.x * (1.0 - ft) * d * g2 * co * -ci /
           (wo.z * -wi.z * den * den);
}

static void check_formula(void)
{
    int bad = 0, tested = 0;
    for (uint32_t s = 0; s < 5000; s++) {
        uint32_t key = dirt_rng_key(8u, s, 0u, 0u);
        float u[9];
        for (uint32_t d = 0; d < 9; d++)
            u[d] = dirt_rng_next_float(key, d);
        float eta = 1.05f + 1.5f * u[0];
        dirt_bsdf b = glass(u[1], 0.1f + 0.9f * u[2], u[3], u[4] < 0.5f ? eta : 1.0f / eta, u[5]);
        dirt_vec3 wo = dirt_sample_cosine(u[6], u[7]);
        dirt_vec3 wi = dirt_sample_cosine(u[8], dirt_rng_next_float(key, 9));
        wi.z = -wi.z;
        if (wo.z < 0.05f || wi.z > -0.05f)
            continue;
        double f = model_transmission(&b, wo, wi), g = dirt_bsdf_eval(&b, wo, wi).x;
        tested++;
        if (fabs(f - g) > 1e-3 * fmax(f, 1e-3))
            bad++;
    }
    CHECK(tested > 3000);
    CHECK_MSG(bad == 0, "%d transmissions differ from the documented formula", bad);
}

static void check_smooth(void)
{
    const float eta = 1.5f;
    dirt_bsdf b = glass(0.8f, 0.0f, 1.0f, eta, 1.0f);
    CHECK(dirt_bsdf_transmission_is_delta(&b) && dirt_bsdf_transmits(&b));
    dirt_vec3 wo = dir_from_mu(0.6f, 0.3f);
    float ps, pt;
    dirt_bsdf_lobe_probabilities(&b, wo, &ps, &pt);
    /* clear glass: one lobe, the interface (reflect with probability F_t,
     * else refract, by the rescaled u_lobe) */
    CHECK(ps == 0.0f && pt == 1.0f);
    double f = dirt_bsdf_fresnel_interface(&b, wo.z);
    dirt_bsdf_sample s;
    CHECK(dirt_bsdf_sample_dir(&b, wo, 0.5f * (float)f, 0.3f, 0.3f, &s));
    CHECK(s.delta && s.wi.z == wo.z && s.wi.x == -wo.x);
    CHECK_NEAR(s.weight.x, 1.0, 1e-6); /* F_t / F_t */
    CHECK(dirt_bsdf_sample_dir(&b, wo, 0.999f, 0.3f, 0.3f, &s));
    CHECK(s.delta && s.pdf == 0.0f && s.wi.z < 0.0f);
    /* Snell: sin_t = sin_i / eta, in the plane of incidence, unit length */
    double si = sqrt(1.0 - 0.36), st = sqrt((double)s.wi.x * s.wi.x + (double)s.wi.y * s.wi.y);
    CHECK_NEAR(st, si / eta, 1e-6);
    CHECK_NEAR(v3_length(s.wi), 1.0, 1e-6);
    CHECK_NEAR(s.wi.x * wo.y - s.wi.y * wo.x, 0.0, 1e-6);
    CHECK(s.wi.x * wo.x < 0.0f);
    CHECK_NEAR(s.weight.x, 0.8 / (eta * eta), 1e-6); /* (1 - F_t) base / (eta^2 (1 - F_t)) */
    /* nothing of it in eval or pdf; NEE sees none */
    CHECK(dirt_bsdf_eval(&b, wo, s.wi).x == 0.0f && dirt_bsdf_pdf(&b, wo, s.wi) == 0.0f);
    /* from inside beyond the critical angle: total reflection, no lobe */
    dirt_bsdf in = glass(1.0f, 0.0f, 1.0f, 1.0f / eta, 1.0f);
    dirt_vec3 graze = dir_from_mu(0.5f, 1.0f); /* sin 0.866 > 1 / 1.5 */
    CHECK(dirt_bsdf_fresnel_interface(&in, graze.z) == 1.0f);
    CHECK(dirt_bsdf_fresnel(&in, graze.z).x == 1.0f);
    dirt_bsdf_lobe_probabilities(&in, graze, &ps, &pt);
    CHECK(pt == 1.0f && ps == 0.0f);
    CHECK(dirt_bsdf_sample_dir(&in, graze, 0.999f, 0.3f, 0.3f, &s));
    CHECK(s.delta && s.wi.z > 0.0f && s.weight.x == 1.0f);
    /* index matched (eta within DIRT_ETA_MATCHED of 1): a delta however
     * rough, straight through */
    dirt_bsdf m = glass(1.0f, 0.5f, 1.0f, 1.0f, 1.0f);
    CHECK(dirt_bsdf_transmission_is_delta(&m) && !dirt_bsdf_is_delta(&m));
    CHECK(dirt_bsdf_sample_dir(&m, wo, 0.999999f, 0.3f, 0.3f, &s));
    CHECK(s.delta && fabsf(s.wi.x + wo.x) < 1e-6f && fabsf(s.wi.z + wo.z) < 1e-6f);
    /* opaque and metallic: no transmission at all */
    dirt_bsdf o = glass(1.0f, 0.5f, 0.0f, 1.5f, 1.0f);
    CHECK(!dirt_bsdf_transmits(&o) && dirt_bsdf_eval(&o, wo, v3(0, 0.6f, -0.8f)).x == 0.0f);
    o.transmission = 1.0f;
    o.metallic = 1.0f;
    CHECK(!dirt_bsdf_transmits(&o) && dirt_bsdf_eval(&o, wo, v3(0, 0.6f, -0.8f)).x == 0.0f);
}

static void check_f0(void)
{
    CHECK(dirt_ior_f0(1.5f) == 0.04f);
    CHECK_NEAR(dirt_ior_f0(1.33f), pow(0.33 / 2.33, 2.0), 1e-8);
    CHECK(dirt_ior_f0(0.0f) == 1.0f && dirt_ior_f0(INFINITY) == 1.0f);
    CHECK(dirt_ior_f0(NAN) == 0.04f && dirt_ior_f0(-1.0f) == 0.04f);
    CHECK(dirt_ior_eta(1.5f) == 1.5f && dirt_ior_eta(0.0f) == 1.0f && dirt_ior_eta(0.5f) == 1.0f &&
          dirt_ior_eta(INFINITY) == 1.0f);
    /* KHR_materials_specular: F0 = min(f0(ior) colour, 1) s, F90 = s */
    dirt_material mat;
    dirt_material_default(&mat);
    mat.metallic = 0.0f;
    mat.ior = 1.33f;
    mat.specular = 0.5f;
    mat.specular_color[0] = 2.0f;
    mat.specular_color[1] = 100.0f; /* clamped to F0 1 */
    mat.specular_color[2] = 0.0f;
    mat.transmission = 0.7f;
    dirt_surface s;
    dirt_material_surface(&mat, 1.0f, NULL, 0, 0.0f, 0.0f, &s);
    double f0 = pow(0.33 / 2.33, 2.0);
    CHECK_NEAR(s.bsdf.f0.x, 2.0 * f0, 1e-7);
    CHECK(s.bsdf.f0.y == 1.0f && s.bsdf.f0.z == 0.0f);
    CHECK(s.bsdf.specular == 0.5f && s.bsdf.transmission == 0.7f && s.bsdf.eta == 1.33f);
    dirt_vec3 fn = dirt_bsdf_fresnel(&s.bsdf, 1.0f), fg = dirt_bsdf_fresnel(&s.bsdf, 0.0f);
    CHECK_NEAR(fn.x, 0.5 * 2.0 * f0, 1e-7);
    CHECK_NEAR(fn.y, 0.5, 1e-7);
    CHECK_NEAR(fn.z, 0.0, 1e-7);
    CHECK_NEAR(fg.x, 0.5, 1e-7);
    CHECK_NEAR(fg.z, 0.5, 1e-7);
    /* the extra factor of dirt_material_surface multiplies specularFactor */
    dirt_material_surface(&mat, 0.5f, NULL, 0, 0.0f, 0.0f, &s);
    CHECK(s.bsdf.specular == 0.25f);
    /* the scalar F_d is the largest channel (glTF's max_value) */
    CHECK_NEAR(dirt_bsdf_fresnel_dielectric(&s.bsdf, 1.0f), 0.25, 1e-7);
}

int main(void)
{
    check_f0();
    check_smooth();
    check_formula();
    check_reciprocity();
    check_energy();
    check_histogram("rough 0.5 front", &(dirt_bsdf){{1, 1, 1}, 0.0f, 0.25f, 1.0f, {0.04f, 0.04f, 0.04f}, 1.0f, 1.5f},
                    dir_from_mu(0.7f, 0.3f));
    check_histogram("rough 0.3 back", &(dirt_bsdf){{1, 1, 1}, 0.0f, 0.09f, 1.0f, {0.04f, 0.04f, 0.04f}, 1.0f, 1.0f / 1.5f},
                    dir_from_mu(0.9f, 1.3f));
    check_histogram("rough 0.7 half, t 0.5", &(dirt_bsdf){{0.7f, 0.5f, 0.2f}, 0.2f, 0.49f, 1.0f, {0.04f, 0.04f, 0.04f}, 0.5f, 1.33f},
                    dir_from_mu(0.4f, 2.0f));
    return check_finish();
}
