/* The environment light's model (src/integrator/env.c; doc/light-transport.md,
 * "Environment"):
 * 1. orientation: +Y is row 0, -Z the image centre, rotation turns the map
 *    about +Y (a bright texel follows it);
 * 2. the pdf integrates to 1 over the sphere (a 1024 x 512 quadrature in
 *    (phi, cos theta), equal solid angles; only cells straddling a texel
 *    edge are off, which bounds the error by 2e-3 for a 16 x 8 map), and
 *    the 1 x 1 map's pdf is exactly uniform, 1 / (4 pi);
 * 3. every sample's pdf and radiance equal dirt_env_pdf and dirt_env_eval
 *    of the direction it returns (the sampler and the lookup agree), and the
 *    share of samples in each texel is its weight's share within 5 binomial
 *    standard deviations (200,000 samples);
 * 4. files: an EXR and an HDR map load texel for texel; a missing file, a
 *    wrong extension and a negative texel fail with a reason; "sky" is the
 *    built-in 512 x 256 sky. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "check.h"
#include "dirt/image.h"
#include "integrator/integrator.h"

#define PI 3.14159265358979323846

/* A 16 x 8 map of uneven radiance with one bright texel at (11, 2). */
static float *test_map(int w, int h)
{
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float *t = &rgb[3 * ((size_t)j * (size_t)w + (size_t)i)];
            t[0] = 0.1f + 0.05f * (float)((i * 7 + j * 3) % 5);
            t[1] = 0.2f + 0.03f * (float)((i + 2 * j) % 4);
            t[2] = (i + j) % 6 == 0 ? 0.0f : 0.3f;
            if (i == 11 && j == 2)
                t[0] = t[1] = t[2] = 40.0f;
        }
    return rgb;
}

static dirt_vec3 dir_of(double phi, double z)
{
    double s = sqrt(fmax(0.0, 1.0 - z * z));
    return (dirt_vec3){(float)(s * sin(phi)), (float)z, (float)(-s * cos(phi))};
}

static void orientation(void)
{
    float *rgb = test_map(16, 8);
    dirt_env *env = dirt_env_create(rgb, 16, 8, NULL);
    CHECK(env != NULL);
    int i, j;
    dirt_env_texel(env, (dirt_vec3){0, 0, -1}, &i, &j);
    CHECK(i == 8 && j == 4); /* the image centre looks along -Z */
    dirt_env_texel(env, (dirt_vec3){0, 1, 0}, &i, &j);
    CHECK(j == 0);
    dirt_env_texel(env, (dirt_vec3){0, -1, 0}, &i, &j);
    CHECK(j == 7);
    dirt_env_texel(env, (dirt_vec3){1, 0, 0}, &i, &j);
    CHECK(i == 12); /* +X a quarter turn right of -Z */
    /* The bright texel's centre, then the map turned by 90 degrees: it moves
     * to the direction turned by 90 degrees about +Y. */
    double phi = 2.0 * PI * (11.5 / 16.0) - PI, z = cos(PI * 2.5 / 8.0);
    dirt_vec3 d = dir_of(phi, z);
    CHECK(dirt_env_eval(env, d).x == 40.0f);
    dirt_env *rot = dirt_env_create(rgb, 16, 8, &(dirt_env_opts){.rotation = 90.0f});
    CHECK(rot != NULL);
    dirt_vec3 turned = {d.z, d.y, -d.x}; /* R_y(90 degrees) d */
    CHECK(dirt_env_eval(rot, turned).x == 40.0f);
    CHECK(dirt_env_eval(rot, d).x != 40.0f);
    CHECK_NEAR(dirt_env_pdf(rot, turned), dirt_env_pdf(env, d), 1e-6 * dirt_env_pdf(env, d));
    /* Intensity scales the radiance. */
    dirt_env *bright = dirt_env_create(rgb, 16, 8, &(dirt_env_opts){.intensity = 2.5f});
    CHECK(bright && dirt_env_eval(bright, d).x == 100.0f);
    dirt_env_destroy(bright);
    dirt_env_destroy(rot);
    dirt_env_destroy(env);
    free(rgb);
}

static void pdf_integral(void)
{
    float *rgb = test_map(16, 8);
    dirt_env *env = dirt_env_create(rgb, 16, 8, &(dirt_env_opts){.rotation = 33.0f});
    const int nu = 1024, nv = 512;
    double sum = 0.0;
    for (int b = 0; b < nv; b++)
        for (int a = 0; a < nu; a++) {
            dirt_vec3 d = dir_of(2.0 * PI * (a + 0.5) / nu - PI, 1.0 - 2.0 * (b + 0.5) / nv);
            sum += dirt_env_pdf(env, d);
        }
    double integral = sum * 4.0 * PI / ((double)nu * nv);
    fprintf(stderr, "pdf integral over the sphere: %.6f\n", integral);
    CHECK_NEAR(integral, 1.0, 2e-3);
    float c[3] = {0.5f, 1.0f, 2.0f};
    dirt_env *one = dirt_env_constant(c);
    CHECK(one && dirt_env_samples(one));
    for (int k = 0; k < 100; k++) {
        dirt_vec3 d = dir_of(0.37 * k, cos(0.61 * k));
        CHECK_NEAR(dirt_env_pdf(one, d), 1.0 / (4.0 * PI), 1e-6 / (4.0 * PI));
        CHECK(dirt_env_eval(one, d).z == 2.0f);
    }
    float black[3] = {0, 0, 0};
    dirt_env *none = dirt_env_constant(black);
    dirt_vec3 d, rad;
    float pdf;
    CHECK(none && !dirt_env_samples(none) && dirt_env_pdf(none, d = (dirt_vec3){0, 1, 0}) == 0.0f);
    CHECK(!dirt_env_sample(none, 0.5f, 0.5f, 0.5f, &d, &pdf, &rad));
    dirt_env_destroy(none);
    dirt_env_destroy(one);
    dirt_env_destroy(env);
    free(rgb);
}

/* A small deterministic generator (xorshift32) for the sampler's inputs. */
static float next_u(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (float)(*s >> 8) * (1.0f / 16777216.0f);
}

static void sampling(void)
{
    enum { W = 16, H = 8, N = 200000 };
    float *rgb = test_map(W, H);
    dirt_env *env = dirt_env_create(rgb, W, H, &(dirt_env_opts){.rotation = -71.0f});
    static int counts[W * H];
    memset(counts, 0, sizeof(counts));
    uint32_t s = 12345u;
    int mismatched = 0, failed = 0;
    for (int n = 0; n < N; n++) {
        float us = next_u(&s), u1 = next_u(&s), u2 = next_u(&s);
        /* Keep off the texel edges, where float rounding may put the
         * direction into the neighbour. */
        u1 = 0.001f + 0.998f * u1;
        u2 = 0.001f + 0.998f * u2;
        dirt_vec3 d, rad;
        float pdf;
        if (!dirt_env_sample(env, us, u1, u2, &d, &pdf, &rad)) {
            failed++;
            continue;
        }
        int i, j;
        dirt_env_texel(env, d, &i, &j);
        counts[j * W + i]++;
        dirt_vec3 e = dirt_env_eval(env, d);
        float p = dirt_env_pdf(env, d);
        if (fabsf(p - pdf) > 1e-5f * pdf || e.x != rad.x || e.y != rad.y || e.z != rad.z ||
            fabsf(d.x * d.x + d.y * d.y + d.z * d.z - 1.0f) > 1e-5f)
            mismatched++;
    }
    CHECK_MSG(failed == 0, "%d samples failed", failed);
    CHECK_MSG(mismatched == 0, "%d samples disagree with the lookup", mismatched);
    double total = 0.0, worst = 0.0;
    double wts[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const float *t = &rgb[3 * (j * W + i)];
            double band = cos(PI * j / H) - cos(PI * (j + 1) / H);
            wts[j * W + i] = (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) * band;
            total += wts[j * W + i];
        }
    for (int k = 0; k < W * H; k++) {
        double p = wts[k] / total, mean = N * p, sd = sqrt(N * p * (1.0 - p));
        double z = sd > 0 ? fabs(counts[k] - mean) / sd : fabs(counts[k] - mean);
        worst = fmax(worst, z);
        CHECK_MSG(z <= 5.0, "texel %d: %d samples, expected %.1f (sd %.1f)", k, counts[k], mean,
                  sd);
    }
    fprintf(stderr, "texel shares: worst deviation %.2f standard deviations\n", worst);
    dirt_env_destroy(env);
    free(rgb);
}

static void files(void)
{
    char dir[] = "/tmp/dirt_test_env_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char exr[256], hdr[256], neg[256], why[512];
    snprintf(exr, sizeof(exr), "%s/map.exr", dir);
    snprintf(hdr, sizeof(hdr), "%s/map.hdr", dir);
    snprintf(neg, sizeof(neg), "%s/neg.exr", dir);
    enum { W = 16, H = 8 };
    float *rgb = test_map(W, H);
    dirt_image *img = dirt_image_create(W, H);
    for (int k = 0; k < W * H; k++) {
        for (int c = 0; c < 3; c++)
            img->rgba[4 * k + c] = rgb[3 * k + c];
        img->rgba[4 * k + 3] = 1.0f;
    }
    CHECK(dirt_image_write_exr(img, exr, NULL));
    dirt_env *e = dirt_env_load(exr, NULL, why, sizeof(why));
    CHECK_MSG(e != NULL, "%s", why);
    if (e) {
        CHECK(e->width == W && e->height == H);
        CHECK(memcmp(e->rgb, rgb, sizeof(float) * 3 * W * H) == 0);
    }
    dirt_env_destroy(e);
    /* Radiance RGBE keeps 8 mantissa bits under one exponent per texel: each
     * component within 1/128 of the texel's largest. */
    CHECK(stbi_write_hdr(hdr, W, H, 3, rgb) != 0);
    e = dirt_env_load(hdr, NULL, why, sizeof(why));
    CHECK_MSG(e != NULL, "%s", why);
    if (e) {
        CHECK(e->width == W && e->height == H);
        double worst = 0.0;
        for (int k = 0; k < 3 * W * H; k++) { /* one exponent per texel: its quantum */
            const float *t = &rgb[3 * (k / 3)];
            worst = fmax(worst, fabs(e->rgb[k] - rgb[k]) / fmax(t[0], fmax(t[1], t[2])));
        }
        CHECK_MSG(worst < 1.0 / 128.0, "RGBE round trip off by %.4g relative", worst);
        CHECK(e->rgb[3 * (2 * W + 11)] == 40.0f);
    }
    dirt_env_destroy(e);
    img->rgba[4 * 5 + 1] = -1.0f;
    CHECK(dirt_image_write_exr(img, neg, NULL));
    CHECK(dirt_env_load(neg, NULL, why, sizeof(why)) == NULL && strstr(why, "neg.exr"));
    CHECK(dirt_env_load("/nonexistent/map.exr", NULL, why, sizeof(why)) == NULL &&
          strstr(why, "/nonexistent/map.exr"));
    CHECK(dirt_env_load("map.png", NULL, why, sizeof(why)) == NULL && strstr(why, ".exr or .hdr"));
    CHECK(dirt_env_load(hdr, &(dirt_env_opts){.intensity = -1.0f}, why, sizeof(why)) == NULL);
    e = dirt_env_load("sky", NULL, why, sizeof(why));
    CHECK(e && e->width == 512 && e->height == 256 && dirt_env_samples(e));
    if (e) /* the sun is the brightest thing, up in the sky */
        CHECK(dirt_env_eval(e, dir_of(0.6, sin(40.0 * PI / 180.0))).x == 400.0f);
    dirt_env_destroy(e);
    dirt_image_destroy(img);
    free(rgb);
    unlink(exr);
    unlink(hdr);
    unlink(neg);
    rmdir(dir);
}

int main(void)
{
    orientation();
    pdf_integral();
    sampling();
    files();
    return check_finish();
}
