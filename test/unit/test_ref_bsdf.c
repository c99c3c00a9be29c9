/* The BSDF of the light-transport model (src/integrator/bsdf.c,
 * doc/light-transport.md):
 *  - energy: white furnace of the BSDF alone, the directional albedo
 *    int f cos dwi (+ the mirror's F) is <= 1 for every material and angle,
 *    and the specular-free Lambert case returns exactly its base colour;
 *  - the sampler is consistent with eval and pdf: the mean sample weight
 *    equals the albedo integrated from eval by quadrature, and the histogram
 *    of sampled directions matches the pdf integrated over each bin;
 *  - reciprocity f(wo, wi) = f(wi, wo);
 *  - eval and pdf equal an independent double-precision transcription of
 *    the formulas of doc/light-transport.md (1e-3 relative: float rounding
 *    of the half vector moves D of sharp lobes by up to ~5e-4);
 *  - the delta lobe below DIRT_ALPHA_DELTA (mirror direction, weight F/p).
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

static dirt_bsdf material(float r, float g, float b, float metallic, float roughness, float spec)
{
    dirt_bsdf m = {{r, g, b}, metallic, roughness * roughness, spec,
                   {DIRT_DIELECTRIC_F0, DIRT_DIELECTRIC_F0, DIRT_DIELECTRIC_F0}, 0.0f, 1.5f};
    return m;
}

/* Albedo (red channel) from the sampler: mean weight over an n x n
 * stratified grid of (u1, u2), the lobe choice integrated exactly: both
 * branches are taken, weighted by their probabilities p and 1 - p. */
static double albedo_sampled(const dirt_bsdf *b, dirt_vec3 wo, int n)
{
    const float u_last = 1.0f - 1.0f / 16777216.0f; /* largest RNG float */
    float p = dirt_bsdf_spec_probability(b, wo);
    double s = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            dirt_bsdf_sample smp;
            float u1 = (i + 0.5f) / n, u2 = (j + 0.5f) / n;
            if (p > 0.0f && dirt_bsdf_sample_dir(b, wo, 0.0f, u1, u2, &smp))
                s += p * smp.weight.x;
            if (p < 1.0f && dirt_bsdf_sample_dir(b, wo, u_last, u1, u2, &smp))
                s += (1.0 - p) * smp.weight.x;
        }
    return s / ((double)n * n);
}

/* Albedo (red channel) from eval alone: cosine-weighted midpoint quadrature
 * over an n x n grid, plus the mirror's F(wo.z) when the lobe is a delta. */
static double albedo_quadrature(const dirt_bsdf *b, dirt_vec3 wo, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            dirt_vec3 wi = dirt_sample_cosine((i + 0.5f) / n, (j + 0.5f) / n);
            s += dirt_bsdf_eval(b, wo, wi).x * PI; /* f cos / (cos / pi) */
        }
    s /= (double)n * n;
    if (dirt_bsdf_is_delta(b))
        s += dirt_bsdf_fresnel(b, wo.z).x;
    return s;
}

static void check_energy(void)
{
    static const float metal[] = {0.0f, 0.5f, 1.0f};
    static const float rough[] = {0.0f, 0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f};
    static const float mus[] = {1.0f, 0.9f, 0.7f, 0.5f, 0.3f, 0.15f, 0.05f, 0.01f};
    double worst = 0.0, worst_diff = 0.0;
    for (size_t m = 0; m < 3; m++)
        for (size_t r = 0; r < sizeof(rough) / sizeof(rough[0]); r++)
            for (size_t a = 0; a < sizeof(mus) / sizeof(mus[0]); a++) {
                dirt_bsdf b = material(1.0f, 1.0f, 1.0f, metal[m], rough[r], 1.0f);
                dirt_vec3 wo = dir_from_mu(mus[a], 0.3f);
                double es = albedo_sampled(&b, wo, 256);
                /* Stratified estimate; its error is far below the 1e-3 margin
                 * for these smooth integrands (checked against n = 512). */
                CHECK_MSG(es <= 1.0 + 1e-3, "m %.1f r %.2f mu %.2f: albedo %.5f > 1",
                          metal[m], rough[r], mus[a], es);
                if (es > worst)
                    worst = es;
                /* Quadrature of eval converges only for lobes wider than the
                 * grid: compare for roughness >= 0.3 (alpha >= 0.09) and
                 * wo.z >= 0.15. Tolerance 0.01 absolute (quadrature error of
                 * a 256^2 grid on these lobes is < 2e-3). */
                if (rough[r] >= 0.3f && mus[a] >= 0.15f) {
                    double eq = albedo_quadrature(&b, wo, 256);
                    double d = fabs(es - eq);
                    if (d > worst_diff)
                        worst_diff = d;
                    CHECK_MSG(d < 0.01, "m %.1f r %.2f mu %.2f: sampler %.5f vs eval %.5f",
                              metal[m], rough[r], mus[a], es, eq);
                }
            }
    fprintf(stderr, "energy: max albedo %.5f, max |sampler - quadrature| %.5f\n", worst, worst_diff);

    /* Without the dielectric lobe the BSDF is exactly Lambert: albedo =
     * base colour at every angle (the furnace test relies on it). */
    for (size_t a = 0; a < sizeof(mus) / sizeof(mus[0]); a++) {
        dirt_bsdf b = material(0.5f, 0.5f, 0.5f, 0.0f, 0.5f, 0.0f);
        dirt_vec3 wo = dir_from_mu(mus[a], 1.0f);
        CHECK_NEAR(albedo_sampled(&b, wo, 64), 0.5, 1e-5);
        CHECK_NEAR(albedo_quadrature(&b, wo, 256), 0.5, 1e-4);
        CHECK_NEAR(dirt_bsdf_eval(&b, wo, dir_from_mu(0.4f, 2.0f)).x, 0.5 / PI, 1e-6);
    }
    /* A white smooth metal is a perfect mirror: albedo 1. */
    dirt_bsdf mirror = material(1.0f, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f);
    CHECK_NEAR(albedo_sampled(&mirror, dir_from_mu(0.3f, 0.0f), 16), 1.0, 1e-6);
}

/* Histogram of sampled directions against the pdf. Bins: 16 in cos theta x
 * 32 in phi. Expected counts are N * int_bin pdf, integrated with a 12 x 12
 * midpoint rule per bin (in (cos theta, phi), where dw = dmu dphi).
 * Per-bin bound for bins expecting >= 100 samples: |obs - exp| <=
 * 5 sqrt(exp) + 0.03 exp (5 binomial standard deviations plus 3 % for the
 * quadrature of the pdf). The fraction of successful samples must equal the
 * integral of the pdf over the hemisphere within 5e-3. */
static void check_histogram(const char *name, const dirt_bsdf *b, dirt_vec3 wo)
{
    enum { NMU = 16, NPHI = 32, SUB = 12, N = 1000000 };
    static double obs[NMU][NPHI];
    for (int i = 0; i < NMU; i++)
        for (int j = 0; j < NPHI; j++)
            obs[i][j] = 0.0;
    long ok = 0, delta = 0;
    for (uint32_t s = 0; s < N; s++) {
        uint32_t key = dirt_rng_key(99u, s, 0u, 1u);
        dirt_bsdf_sample smp;
        if (!dirt_bsdf_sample_dir(b, wo, dirt_rng_next_float(key, DIRT_RNG_DIM_LOBE),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_U),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_V), &smp))
            continue;
        if (smp.delta) { /* the mirror lobe is not part of the pdf */
            delta++;
            continue;
        }
        ok++;
        /* The reported pdf is the pdf of the returned direction. */
        float p = dirt_bsdf_pdf(b, wo, smp.wi);
        if (fabsf(p - smp.pdf) > 1e-5f * p)
            CHECK_MSG(0, "%s: sample pdf %g != dirt_bsdf_pdf %g", name, smp.pdf, p);
        int i = (int)(smp.wi.z * NMU);
        double phi = atan2(smp.wi.y, smp.wi.x);
        if (phi < 0.0)
            phi += 2.0 * PI;
        int j = (int)(phi / (2.0 * PI) * NPHI);
        if (i >= NMU)
            i = NMU - 1;
        if (j >= NPHI)
            j = NPHI - 1;
        obs[i][j] += 1.0;
    }
    double total_pdf = 0.0;
    int bad = 0, tested = 0;
    double worst = 0.0;
    for (int i = 0; i < NMU; i++)
        for (int j = 0; j < NPHI; j++) {
            double integral = 0.0;
            for (int a = 0; a < SUB; a++)
                for (int c = 0; c < SUB; c++) {
                    float mu = (float)((i + (a + 0.5) / SUB) / NMU);
                    float phi = (float)((j + (c + 0.5) / SUB) / NPHI * 2.0 * PI);
                    integral += dirt_bsdf_pdf(b, wo, dir_from_mu(mu, phi));
                }
            integral *= (1.0 / NMU) * (2.0 * PI / NPHI) / (SUB * SUB);
            total_pdf += integral;
            double exp = integral * N;
            if (exp < 100.0)
                continue;
            tested++;
            double dev = fabs(obs[i][j] - exp);
            double bound = 5.0 * sqrt(exp) + 0.03 * exp;
            if (dev / bound > worst)
                worst = dev / bound;
            if (dev > bound) {
                bad++;
                fprintf(stderr, "%s: bin (%d,%d) observed %.0f expected %.1f\n", name, i, j,
                        obs[i][j], exp);
            }
        }
    fprintf(stderr, "histogram %-16s %d bins tested, worst deviation %.2f of bound, "
            "success %.4f, pdf integral %.4f\n", name, tested, worst, (double)ok / N, total_pdf);
    CHECK_MSG(bad == 0, "%s: %d bins outside the bound", name, bad);
    CHECK(tested >= 50);
    CHECK_NEAR((double)ok / N, total_pdf, 5e-3);
    /* Mirror samples come with probability p_spec (binomial s.e. <= 5e-4). */
    if (dirt_bsdf_is_delta(b))
        CHECK_NEAR((double)delta / N, dirt_bsdf_spec_probability(b, wo), 3e-3);
    else
        CHECK(delta == 0);
}

static void check_reciprocity(void)
{
    int bad = 0;
    for (uint32_t s = 0; s < 20000; s++) {
        uint32_t key = dirt_rng_key(5u, s, 0u, 0u);
        float u[8];
        for (uint32_t d = 0; d < 8; d++)
            u[d] = dirt_rng_next_float(key, d);
        dirt_bsdf b = material(u[0], u[1], u[2], u[3] < 0.3f ? 0.0f : u[3], 0.05f + u[4],
                               u[5] < 0.2f ? 0.0f : 1.0f);
        dirt_vec3 wo = dirt_sample_cosine(u[6], u[7]);
        dirt_vec3 wi = dirt_sample_cosine(dirt_rng_next_float(key, 8), dirt_rng_next_float(key, 9));
        dirt_vec3 a = dirt_bsdf_eval(&b, wo, wi), c = dirt_bsdf_eval(&b, wi, wo);
        float tol = 1e-5f * fmaxf(1.0f, fmaxf(a.x, fmaxf(a.y, a.z)));
        if (fabsf(a.x - c.x) > tol || fabsf(a.y - c.y) > tol || fabsf(a.z - c.z) > tol)
            bad++;
        if (!(a.x >= 0.0f && a.y >= 0.0f && a.z >= 0.0f) || !isfinite(a.x + a.y + a.z))
            bad++;
    }
    CHECK_MSG(bad == 0, "%d non-reciprocal or invalid evaluations", bad);
    /* Below the surface the BSDF and the pdf are zero. */
    dirt_bsdf b = material(0.8f, 0.8f, 0.8f, 0.0f, 0.5f, 1.0f);
    CHECK(dirt_bsdf_eval(&b, v3(0, 0, 1), v3(0, 0.6f, -0.8f)).x == 0.0f);
    CHECK(dirt_bsdf_pdf(&b, v3(0, 0.6f, -0.8f), v3(0, 0, 1)) == 0.0f);
}

static void check_delta(void)
{
    dirt_bsdf b = material(0.9f, 0.6f, 0.3f, 1.0f, 0.01f, 1.0f); /* alpha 1e-4 */
    CHECK(dirt_bsdf_is_delta(&b));
    dirt_bsdf rough = material(0.9f, 0.6f, 0.3f, 1.0f, 0.04f, 1.0f); /* alpha 1.6e-3 */
    CHECK(!dirt_bsdf_is_delta(&rough));
    dirt_vec3 wo = dir_from_mu(0.6f, 0.7f);
    float p = dirt_bsdf_spec_probability(&b, wo);
    CHECK_NEAR(p, 1.0, 1e-6); /* a metal has no diffuse lobe */
    dirt_bsdf_sample s;
    CHECK(dirt_bsdf_sample_dir(&b, wo, 0.5f, 0.3f, 0.3f, &s));
    CHECK(s.delta);
    CHECK_NEAR(s.wi.x, -wo.x, 1e-7);
    CHECK_NEAR(s.wi.y, -wo.y, 1e-7);
    CHECK_NEAR(s.wi.z, wo.z, 1e-7);
    dirt_vec3 f = dirt_bsdf_fresnel(&b, wo.z);
    CHECK_NEAR(s.weight.x, f.x, 1e-6);
    CHECK_NEAR(s.weight.z, f.z, 1e-6);
    /* The non-delta part of a smooth metal is zero. */
    CHECK(dirt_bsdf_eval(&b, wo, dir_from_mu(0.6f, 0.7f + 3.14159f)).x == 0.0f);
    /* Smooth dielectric: mirror chosen with probability p, weight F / p;
     * otherwise the diffuse lobe with its own pdf. */
    dirt_bsdf d = material(0.5f, 0.5f, 0.5f, 0.0f, 0.0f, 1.0f);
    p = dirt_bsdf_spec_probability(&d, wo);
    CHECK(p > 0.0f && p < 1.0f);
    CHECK(dirt_bsdf_sample_dir(&d, wo, 0.5f * p, 0.3f, 0.3f, &s));
    CHECK(s.delta);
    CHECK_NEAR(s.weight.x, dirt_bsdf_fresnel(&d, wo.z).x / p, 1e-6);
    CHECK(dirt_bsdf_sample_dir(&d, wo, 0.5f + 0.5f * p, 0.3f, 0.3f, &s));
    CHECK(!s.delta);
    CHECK_NEAR(s.pdf, (1.0f - p) * s.wi.z / PI, 1e-6);
}

/* The documented formulas, written again independently in double: pins
 * every choice of the model (height-correlated Smith, coupled diffuse,
 * Fresnel mix, lobe probability) so that a change shows up here and the GLSL
 * twin can be checked against the same numbers. */
static double lum(const double c[3])
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

static void model_eval(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi, double f[3], double *pdf)
{
    double base[3] = {b->base_color.x, b->base_color.y, b->base_color.z};
    double m = b->metallic, a = b->alpha, s = b->specular;
    double h[3] = {wo.x + wi.x, wo.y + wi.y, wo.z + wi.z};
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int k = 0; k < 3; k++)
        h[k] /= hl;
    double voh = wo.x * h[0] + wo.y * h[1] + wo.z * h[2];
#define FD(c) (s * (0.04 + 0.96 * pow(1.0 - (c), 5.0)))
    double d = a * a / (PI * pow(h[2] * h[2] * (a * a - 1.0) + 1.0, 2.0));
    double to2 = (1.0 - (double)wo.z * wo.z) / ((double)wo.z * wo.z);
    double ti2 = (1.0 - (double)wi.z * wi.z) / ((double)wi.z * wi.z);
    double lo = 0.5 * (sqrt(1.0 + a * a * to2) - 1.0), li = 0.5 * (sqrt(1.0 + a * a * ti2) - 1.0);
    double g2 = 1.0 / (1.0 + lo + li), g1 = 1.0 / (1.0 + lo);
    double fo[3];
    for (int k = 0; k < 3; k++) {
        double fr = (1 - m) * FD(voh) + m * (base[k] + (1 - base[k]) * pow(1 - voh, 5.0));
        f[k] = (1 - m) * base[k] * (1 - FD(wi.z)) * (1 - FD(wo.z)) / PI +
               fr * d * g2 / (4.0 * wo.z * wi.z);
        fo[k] = (1 - m) * FD(wo.z) + m * (base[k] + (1 - base[k]) * pow(1 - wo.z, 5.0));
    }
    double ws = lum(fo), wd = (1 - m) * lum(base) * (1 - FD(wo.z));
    double p = ws + wd > 0 ? ws / (ws + wd) : 0.5;
    *pdf = p * d * g1 / (4.0 * wo.z) + (1 - p) * wi.z / PI;
#undef FD
}

static void check_formulas(void)
{
    int bad = 0;
    for (uint32_t i = 0; i < 2000; i++) {
        uint32_t key = dirt_rng_key(77u, i, 0u, 0u);
        float u[9];
        for (uint32_t d = 0; d < 9; d++)
            u[d] = dirt_rng_next_float(key, d);
        dirt_bsdf b = material(u[0], u[1], u[2], u[3], 0.05f + 0.95f * u[4], u[5]);
        dirt_vec3 wo = dirt_sample_cosine(u[6], u[7]);
        dirt_vec3 wi = dirt_sample_cosine(u[8], dirt_rng_next_float(key, 9));
        if (wo.z < 0.05f || wi.z < 0.05f)
            continue;
        double f[3], pdf;
        model_eval(&b, wo, wi, f, &pdf);
        dirt_vec3 g = dirt_bsdf_eval(&b, wo, wi);
        double gf[3] = {g.x, g.y, g.z};
        for (int k = 0; k < 3; k++)
            if (fabs(gf[k] - f[k]) > 1e-3 * fmax(f[k], 1e-3))
                bad++;
        if (fabs(dirt_bsdf_pdf(&b, wo, wi) - pdf) > 1e-3 * fmax(pdf, 1e-3))
            bad++;
    }
    CHECK_MSG(bad == 0, "%d values differ from the documented formulas", bad);
}

static void check_warps(void)
{
    /* Orthonormal basis for normals in every octant, including the poles. */
    int bad = 0;
    for (uint32_t s = 0; s < 10000; s++) {
        dirt_vec3 n = dirt_sample_cosine(dirt_rng_float(1, s, 0, 0, 0), dirt_rng_float(1, s, 0, 0, 1));
        if (s % 2)
            n.z = -n.z;
        if (s == 2)
            n = v3(0, 0, 1);
        if (s == 3)
            n = v3(0, 0, -1);
        dirt_vec3 t, b;
        dirt_onb(n, &t, &b);
        float d[6] = {t.x * t.x + t.y * t.y + t.z * t.z - 1, b.x * b.x + b.y * b.y + b.z * b.z - 1,
                      t.x * b.x + t.y * b.y + t.z * b.z, t.x * n.x + t.y * n.y + t.z * n.z,
                      b.x * n.x + b.y * n.y + b.z * n.z,
                      /* right-handed: t x b = n */
                      (t.y * b.z - t.z * b.y) - n.x};
        for (int k = 0; k < 6; k++)
            if (fabsf(d[k]) > 1e-5f)
                bad++;
    }
    CHECK_MSG(bad == 0, "%d basis errors", bad);
    /* Triangle warp stays inside and is uniform: mean barycentrics 1/3. */
    double m1 = 0.0, m2 = 0.0;
    int outside = 0;
    for (uint32_t s = 0; s < 100000; s++) {
        float b1, b2;
        dirt_sample_triangle(dirt_rng_float(2, s, 0, 0, 0), dirt_rng_float(2, s, 0, 0, 1), &b1, &b2);
        if (b1 < 0 || b2 < 0 || b1 + b2 > 1.0f + 1e-6f)
            outside++;
        m1 += b1;
        m2 += b2;
    }
    CHECK(outside == 0);
    /* std of a barycentric is sqrt(1/18); s.e. over 1e5 = 7.5e-4; 5 sigma */
    CHECK_NEAR(m1 / 100000, 1.0 / 3.0, 4e-3);
    CHECK_NEAR(m2 / 100000, 1.0 / 3.0, 4e-3);
    CHECK_NEAR(dirt_mis_power(1.0f, 1.0f), 0.5, 1e-7);
    CHECK_NEAR(dirt_mis_power(3.0f, 1.0f), 0.9, 1e-7);
    CHECK(dirt_mis_power(0.0f, 0.0f) == 0.0f);
    CHECK_NEAR(dirt_rr_survival(v3(0.2f, 0.7f, 0.1f)), 0.7, 1e-7);
    CHECK(dirt_rr_survival(v3(2.0f, 0.0f, 0.0f)) == 1.0f);
}

int main(void)
{
    check_energy();
    dirt_bsdf lambert = material(0.7f, 0.7f, 0.7f, 0.0f, 0.5f, 1.0f);
    dirt_bsdf plastic = material(0.2f, 0.5f, 0.9f, 0.0f, 0.3f, 1.0f);
    dirt_bsdf metal = material(0.9f, 0.8f, 0.5f, 1.0f, 0.4f, 1.0f);
    dirt_bsdf glossy = material(0.9f, 0.9f, 0.9f, 0.7f, 0.6f, 1.0f);
    dirt_bsdf smooth = material(0.5f, 0.5f, 0.5f, 0.0f, 0.0f, 1.0f);
    check_histogram("lambert normal", &lambert, dir_from_mu(1.0f, 0.0f));
    check_histogram("plastic 0.5", &plastic, dir_from_mu(0.5f, 0.2f));
    check_histogram("metal 0.8", &metal, dir_from_mu(0.8f, 1.0f));
    check_histogram("metal grazing", &metal, dir_from_mu(0.2f, 1.0f));
    check_histogram("glossy 0.4", &glossy, dir_from_mu(0.4f, 2.0f));
    check_histogram("smooth diffuse", &smooth, dir_from_mu(0.7f, 0.0f));
    check_reciprocity();
    check_formulas();
    check_delta();
    check_warps();
    return check_finish();
}
