/* Path tracer furnace tests (src/ref/render.c) with closed-form answers.
 *
 * 1. White furnace: inside a closed box whose walls all have Lambert albedo
 *    0.5 (metallic 0, dielectric specular weight 0: exactly Lambert, see
 *    doc/light-transport.md) and emit radiance 1, every path vertex sees
 *    L = 1 + 0.5 L, so L = 2; with K bounces the estimator must return the
 *    truncated series sum_{i=0}^{K} 0.5^i. Tolerance: 5 standard errors of
 *    the image mean, the standard error estimated from the spread of the
 *    pixel values (pixels are independent: the RNG keys differ), reported in
 *    the log. The area lights are sampled (NEE) and hit (BSDF) at every
 *    vertex, so a wrong MIS weight, light pdf, BSDF weight or Russian
 *    roulette compensation shifts the mean by far more than that.
 *    Variants: a zero-power punctual light added (NEE chooses among two
 *    sources, L stays 2); walls facing outwards with one-sided emission (the
 *    inside sees only back sides: L < 1e-6) and double-sided (L = 2).
 * 2. Mirror furnace: walls of white smooth metal (F = 1, a delta lobe)
 *    emitting 1: every path sees exactly K + 1 (no noise at all).
 * 3. Punctual lights: a Lambert floor lit by a point, a spot and a
 *    directional light; the centre pixel of a narrow camera looking straight
 *    down must equal rho / pi * E within 1e-3 relative.
 * 4. Background: rays that leave an open scene return the background.
 *    Environment: a white convex box in a uniform environment (the
 *    background, or a map) reflects exactly 1; a floor under a non-uniform
 *    map reflects its cosine-weighted integral (env_furnace, env_floor).
 * 5. An area light close above a floor: a square emitter (half size a,
 *    facing down) at height h over a Lambert floor, direct light only; the
 *    floor point under its centre, seen from the side under the light, must
 *    be rho / pi * E with E = Le pi F (F: the point-to-square form factor,
 *    four corner rectangles) within 5 standard errors, at the origin and
 *    moved 20 units away. The shadow ray must end before the light sample
 *    it aims at: aimed from the shading point but started from the origin
 *    offset along the normal (ray_epsilon, 1e-4 of the coordinates), it ran
 *    past the light (through it: occluded) whenever the offset exceeded its
 *    shortening, 1e-4 of the distance times the cosine -- every light closer
 *    than the coordinates' magnitude, e.g. the Cornell box's tall box top.
 * 6. Glass furnace: a closed sphere of white glass (transmission 1, ior
 *    1.5), smooth and rough, in a uniform environment looks like the
 *    environment: mean 1 over its pixels (glass_furnace). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "integrator/integrator.h"
#include "ref/ref.h"

#define PI 3.14159265358979323846

typedef struct mesh {
    dirt_frame f;
    float (*pos)[3];
    float (*nrm)[3];
    float (*uv)[2];
    uint32_t *mat;
    size_t cap, n;
} mesh;

static bool mesh_init(mesh *m, size_t cap)
{
    memset(m, 0, sizeof(*m));
    m->pos = calloc(3 * cap, sizeof(float[3]));
    m->nrm = calloc(3 * cap, sizeof(float[3]));
    m->uv = calloc(3 * cap, sizeof(float[2]));
    m->mat = calloc(cap, sizeof(uint32_t));
    m->cap = cap;
    return m->pos && m->nrm && m->uv && m->mat;
}

static void mesh_free(mesh *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->uv);
    free(m->mat);
}

/* Triangle a, b, c (front = counter-clockwise), flat normal. */
static void tri(mesh *m, const float a[3], const float b[3], const float c[3], uint32_t mat)
{
    if (m->n >= m->cap)
        return;
    const float *v[3] = {a, b, c};
    float e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) {
            m->pos[3 * m->n + j][k] = v[j][k];
            m->nrm[3 * m->n + j][k] = n[k] / l;
        }
    m->mat[m->n] = mat;
    m->n++;
    m->f.num_triangles = m->n;
    m->f.position = m->pos;
    m->f.normal = m->nrm;
    m->f.uv = m->uv;
    m->f.material = m->mat;
}

/* Closed box [-1,1]^3 with its front faces inside (two triangles a face). */
static void box_inward(mesh *m, uint32_t mat)
{
    float p[8][3];
    for (int i = 0; i < 8; i++) {
        p[i][0] = (i & 1) ? 1.0f : -1.0f;
        p[i][1] = (i & 2) ? 1.0f : -1.0f;
        p[i][2] = (i & 4) ? 1.0f : -1.0f;
    }
    /* Each quad counter-clockwise seen from inside. */
    static const int q[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (int f = 0; f < 6; f++) {
        tri(m, p[q[f][0]], p[q[f][1]], p[q[f][2]], mat);
        tri(m, p[q[f][0]], p[q[f][2]], p[q[f][3]], mat);
    }
}

static dirt_material mat_make(float albedo, float metallic, float roughness, float emission)
{
    dirt_material m;
    dirt_material_default(&m);
    m.base_color[0] = m.base_color[1] = m.base_color[2] = albedo;
    m.base_color[3] = 1.0f;
    m.base_color_tex = m.metallic_roughness_tex = m.emissive_tex = DIRT_NO_TEXTURE;
    m.metallic = metallic;
    m.roughness = roughness;
    m.emissive[0] = m.emissive[1] = m.emissive[2] = emission;
    m.emissive_strength = 1.0f;
    return m;
}

static void look(dirt_camera *c, float ex, float ey, float ez, float tx, float ty, float tz,
                 float yfov)
{
    float eye[3] = {ex, ey, ez}, target[3] = {tx, ty, tz}, up[3] = {0, 1, 0};
    if (fabsf(tx - ex) < 1e-6f && fabsf(tz - ez) < 1e-6f)
        up[1] = 0.0f, up[2] = -1.0f; /* looking straight down */
    memset(c, 0, sizeof(*c));
    dirt_camera_look_at(c, eye, target, up);
    c->type = DIRT_CAMERA_PERSPECTIVE;
    c->yfov = yfov;
}

/* Image mean of the red channel and its standard error. */
static void image_mean(const dirt_image *img, double *mean, double *se)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    double s = 0.0, s2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        double v = img->rgba[4 * i];
        s += v;
        s2 += v * v;
    }
    *mean = s / (double)n;
    double var = (s2 / (double)n - *mean * *mean) * (double)n / (double)(n - 1);
    *se = sqrt(fmax(var, 0.0) / (double)n);
}

/* Variants of the white furnace. */
enum variant {
    PLAIN,
    BLACK_LIGHT,  /* plus a punctual light of zero power: NEE picks it half of
                     the time, so the area light's 1/2 selection probability
                     must enter its weight and its MIS pdf; still L = 2 */
    OUTWARD,      /* walls facing outwards, one-sided emission: the inside
                     sees only their back sides, which do not emit: L = 0
                     (up to float noise) */
    OUTWARD_TWO_SIDED, /* the same walls double-sided: L = 2 again */
};

static void furnace_variant(int bounces, int spp, enum variant var)
{
    mesh m;
    CHECK(mesh_init(&m, 12));
    box_inward(&m, 0);
    if (var == OUTWARD || var == OUTWARD_TWO_SIDED) { /* swap two vertices */
        for (size_t t = 0; t < m.n; t++)
            for (int k = 0; k < 3; k++) {
                float tmp = m.pos[3 * t + 1][k];
                m.pos[3 * t + 1][k] = m.pos[3 * t + 2][k];
                m.pos[3 * t + 2][k] = tmp;
                m.nrm[3 * t][k] = m.nrm[3 * t + 1][k] = m.nrm[3 * t + 2][k] = -m.nrm[3 * t][k];
            }
    }
    dirt_light black;
    memset(&black, 0, sizeof(black));
    black.type = DIRT_LIGHT_POINT;
    if (var == BLACK_LIGHT) {
        m.f.num_lights = 1;
        m.f.lights = &black;
    }
    dirt_material mat = mat_make(0.5f, 0.0f, 1.0f, 1.0f);
    mat.double_sided = var == OUTWARD_TWO_SIDED;
    float spec = 0.0f;
    dirt_ref_materials mats = {&mat, 1, NULL, 0, &spec};
    dirt_camera cam;
    look(&cam, 0.2f, -0.1f, 0.3f, -0.4f, 0.5f, -1.0f, 1.6f);
    dirt_ref_opts o = {0};
    o.width = 32;
    o.height = 32;
    o.spp = spp;
    o.bounces = bounces;
    o.seed = 17u + (uint32_t)bounces; /* independent runs */
    dirt_ref_stats st;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, &st);
    CHECK(img != NULL);
    if (img) {
        static const char *const names[] = {"", " +black light", " outward", " two-sided"};
        double expect = 0.0, mean, se;
        for (int i = 0; i <= bounces; i++)
            expect += pow(0.5, i);
        image_mean(img, &mean, &se);
        fprintf(stderr, "furnace K=%2d%s: mean %.5f expected %.5f, s.e. %.5f (%.1f s.e.), "
                "%.2f Mrays/s, %llu rays\n", bounces, names[var], mean,
                var == OUTWARD ? 0.0 : expect, se, var != OUTWARD && se > 0 ? (mean - expect) / se : 0.0,
                st.mrays_per_s, (unsigned long long)st.rays);
        CHECK(st.invalid == 0);
        if (var == OUTWARD) {
            /* 0 up to float noise: a light sample coplanar with the shading
             * point (same wall) has cosines of +-1e-8 instead of 0. */
            CHECK_MSG(mean < 1e-6, "back sides emit: mean %g", mean);
            goto out;
        }
        CHECK(se > 0.0 && se < 0.01);
        CHECK_MSG(fabs(mean - expect) < 5.0 * se, "K=%d: mean %.5f, expected %.5f, s.e. %.5f",
                  bounces, mean, expect, se);
        /* Every pixel sees the walls: albedo AOV = 0.5, Z finite. */
        float *alb = dirt_image_find_channel(img, "albedo.G");
        float *z = dirt_image_find_channel(img, "Z");
        CHECK(alb && z);
        if (alb && z) {
            CHECK_NEAR(alb[100], 0.5, 1e-6);
            CHECK(isfinite(z[100]) && z[100] > 0.0f);
        }
    }
out:
    dirt_image_destroy(img);
    mesh_free(&m);
}

static void furnace(int bounces, int spp)
{
    furnace_variant(bounces, spp, PLAIN);
}

static void mirror_furnace(int bounces)
{
    mesh m;
    CHECK(mesh_init(&m, 12));
    box_inward(&m, 0);
    dirt_material mat = mat_make(1.0f, 1.0f, 0.0f, 1.0f);
    dirt_ref_materials mats = {&mat, 1, NULL, 0, NULL};
    dirt_camera cam;
    look(&cam, 0.1f, 0.2f, -0.3f, 0.7f, -0.2f, 1.0f, 1.2f);
    dirt_ref_opts o = {0};
    o.width = 16;
    o.height = 16;
    o.spp = 4;
    o.bounces = bounces;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    if (img) {
        double worst = 0.0;
        for (int i = 0; i < 16 * 16; i++)
            worst = fmax(worst, fabs(img->rgba[4 * i] - (bounces + 1.0)));
        fprintf(stderr, "mirror furnace K=%d: max |L - %d| = %.2e\n", bounces, bounces + 1, worst);
        /* Float accumulation only; a path that ends early loses >= 1. */
        CHECK_MSG(worst < 1e-4, "K=%d: max deviation %g", bounces, worst);
    }
    dirt_image_destroy(img);
    mesh_free(&m);
}

/* Lambert floor y = 0 (albedo rho, no specular) lit by one punctual light;
 * camera 1 unit above the origin looking down with a tiny field of view. */
static void punctual_ex(const char *name, const dirt_light *light, double irradiance,
                        bool dark_area_light)
{
    mesh m;
    CHECK(mesh_init(&m, 3));
    float a[3] = {-50, 0, -50}, b[3] = {-50, 0, 50}, c[3] = {50, 0, 50}, d[3] = {50, 0, -50};
    tri(&m, a, b, c, 0);
    tri(&m, a, c, d, 0);
    if (dark_area_light) {
        /* An emitter under the floor facing down: NEE picks it half of the
         * time and gets nothing, so the punctual light's sample must count
         * twice. */
        float e0[3] = {0, -1, 0}, e1[3] = {1, -1, 0}, e2[3] = {0, -1, 1};
        tri(&m, e0, e1, e2, 1);
    }
    m.f.num_lights = 1;
    m.f.lights = (dirt_light *)light;
    const float rho = 0.6f;
    dirt_material mat[2] = {mat_make(rho, 0.0f, 1.0f, 0.0f), mat_make(rho, 0.0f, 1.0f, 5.0f)};
    float spec[2] = {0.0f, 0.0f};
    dirt_ref_materials mats = {mat, 2, NULL, 0, spec};
    dirt_camera cam;
    look(&cam, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1e-4f);
    dirt_ref_opts o = {0};
    o.width = 1;
    o.height = 1;
    o.spp = dark_area_light ? 4096 : 4;
    o.bounces = 3;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    if (img) {
        double expect = rho / PI * irradiance;
        /* Without the dark emitter every sample is the same (the pixel is
         * tiny): 1e-3 relative. With it a sample is 0 or 2x with equal
         * probability: s.e. = expect / sqrt(spp); 5 s.e. */
        double tol = dark_area_light ? 5.0 * expect / sqrt((double)o.spp) : 1e-3 * expect;
        fprintf(stderr, "%-12s L %.6f expected %.6f (tolerance %.2g)\n", name, img->rgba[0],
                expect, tol);
        CHECK_NEAR(img->rgba[0], expect, tol);
    }
    dirt_image_destroy(img);
    mesh_free(&m);
}

static void punctual(const char *name, const dirt_light *light, double irradiance)
{
    punctual_ex(name, light, irradiance, false);
}

static void lights(void)
{
    dirt_light l;
    memset(&l, 0, sizeof(l));
    l.type = DIRT_LIGHT_POINT;
    l.position[0] = 0.6f;
    l.position[1] = 0.8f; /* distance 1, cos 0.8 */
    l.color[0] = l.color[1] = l.color[2] = 5.0f;
    punctual("point", &l, 5.0 * 0.8);
    punctual_ex("point+area", &l, 5.0 * 0.8, true);
    l.type = DIRT_LIGHT_SPOT; /* aimed at the origin: full intensity */
    l.direction[0] = -0.6f;
    l.direction[1] = -0.8f;
    l.inner_cone = 0.1f;
    l.outer_cone = 0.3f;
    punctual("spot", &l, 5.0 * 0.8);
    l.direction[0] = 0.0f; /* axis straight down: angle to the origin 36.9 deg */
    l.direction[1] = -1.0f;
    l.outer_cone = 0.5f;
    l.inner_cone = 0.0f;
    double s = (0.8 - cos(0.5)) / (1.0 - cos(0.5));
    punctual("spot cone", &l, s > 0 ? 5.0 * 0.8 * s * s : 0.0);
    l.outer_cone = 0.7f;
    s = (0.8 - cos(0.7)) / (1.0 - cos(0.7));
    punctual("spot cone 2", &l, 5.0 * 0.8 * s * s);
    l.type = DIRT_LIGHT_DIRECTIONAL;
    l.direction[0] = 0.0f;
    l.direction[1] = -0.5f;
    l.direction[2] = -0.866025f; /* cos 0.5 */
    punctual("directional", &l, 5.0 * 0.5);
}

static void background(void)
{
    mesh m;
    CHECK(mesh_init(&m, 1));
    float a[3] = {0, 0, -5}, b[3] = {1, 0, -5}, c[3] = {0, 1, -5};
    tri(&m, a, b, c, 0);
    dirt_material mat = mat_make(0.5f, 0.0f, 1.0f, 0.0f);
    dirt_ref_materials mats = {&mat, 1, NULL, 0, NULL};
    dirt_camera cam;
    look(&cam, 0, 0, 0, 0, 0, 1, 0.5f); /* looking away from the triangle */
    dirt_ref_opts o = {0};
    o.width = 8;
    o.height = 8;
    o.spp = 2;
    o.background[0] = 0.25f;
    o.background[1] = 0.5f;
    o.background[2] = 2.0f;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    if (img) {
        CHECK(img->rgba[0] == 0.25f && img->rgba[1] == 0.5f && img->rgba[2] == 2.0f &&
              img->rgba[3] == 1.0f);
        float *z = dirt_image_find_channel(img, "Z");
        CHECK(z && isinf(z[0]));
    }
    dirt_image_destroy(img);
    mesh_free(&m);
}

/* Environment furnace: a convex box of white Lambert walls (albedo 1,
 * dielectric specular weight 0) facing outwards, in a uniform environment
 * of radiance 1, reflects radiance 1 wherever it is seen (every direction
 * over a face sees the environment). The environment is the constant
 * background (the 1 x 1 map) or a 64 x 32 map of ones turned by 37 degrees
 * (importance sampling over many texels, rotation). Tolerance: 5 standard
 * errors of the mean over the box's pixels; the background pixels must be
 * exactly 1. */
static void env_furnace(bool map)
{
    mesh m;
    CHECK(mesh_init(&m, 12));
    box_inward(&m, 0);
    for (size_t t = 0; t < m.n; t++) /* outwards: swap two vertices */
        for (int k = 0; k < 3; k++) {
            float tmp = m.pos[3 * t + 1][k];
            m.pos[3 * t + 1][k] = m.pos[3 * t + 2][k];
            m.pos[3 * t + 2][k] = tmp;
            m.nrm[3 * t][k] = m.nrm[3 * t + 1][k] = m.nrm[3 * t + 2][k] = -m.nrm[3 * t][k];
        }
    dirt_material mat = mat_make(1.0f, 0.0f, 1.0f, 0.0f);
    float spec = 0.0f;
    dirt_ref_materials mats = {&mat, 1, NULL, 0, &spec};
    dirt_camera cam;
    look(&cam, 2.5f, 1.8f, 3.0f, 0.0f, 0.0f, 0.0f, 0.9f);
    dirt_ref_opts o = {0};
    o.width = 32;
    o.height = 32;
    o.spp = 64;
    o.bounces = 4;
    o.seed = 3u;
    float *ones = NULL;
    dirt_env *env = NULL;
    if (map) {
        ones = malloc(64 * 32 * 3 * sizeof(float));
        for (int k = 0; k < 64 * 32 * 3; k++)
            ones[k] = 1.0f;
        env = dirt_env_create(ones, 64, 32, &(dirt_env_opts){.rotation = 37.0f});
        CHECK(env != NULL);
        o.env = env;
    } else {
        o.background[0] = o.background[1] = o.background[2] = 1.0f;
    }
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    float *ids = img ? dirt_image_find_channel(img, "ID") : NULL;
    CHECK(ids != NULL);
    if (img && ids) {
        double s = 0.0, s2 = 0.0;
        size_t n = 0, bg_bad = 0;
        for (size_t i = 0; i < (size_t)o.width * (size_t)o.height; i++) {
            double v = img->rgba[4 * i];
            if (ids[i] < 0) {
                /* Away from the box (no neighbour's centre on it, so no
                 * jittered sample of this pixel hits it): exactly 1. */
                int x = (int)(i % (size_t)o.width), y = (int)(i / (size_t)o.width);
                bool clear = true;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        int xx = x + dx, yy = y + dy;
                        if (xx >= 0 && yy >= 0 && xx < o.width && yy < o.height &&
                            ids[yy * o.width + xx] >= 0)
                            clear = false;
                    }
                if (clear)
                    bg_bad += img->rgba[4 * i] != 1.0f || img->rgba[4 * i + 2] != 1.0f;
                continue;
            }
            s += v;
            s2 += v * v;
            n++;
        }
        double mean = s / (double)n, se = sqrt(fmax(s2 / n - mean * mean, 0.0) / (n - 1));
        fprintf(stderr, "environment furnace (%s): %zu box pixels, mean %.5f, s.e. %.5f\n",
                map ? "64x32 map" : "background", n, mean, se);
        CHECK(n > 200 && n < 1000);
        CHECK(se > 0.0 && se < 0.01);
        CHECK_MSG(fabs(mean - 1.0) < 5.0 * se, "mean %.5f, expected 1, s.e. %.5f", mean, se);
        CHECK_MSG(bg_bad == 0, "%zu background pixels are not 1", bg_bad);
    }
    dirt_image_destroy(img);
    dirt_env_destroy(env);
    free(ones);
    mesh_free(&m);
}

/* An upward floor (albedo rho) under a non-uniform map (a gradient with a
 * bright texel above the horizon and light below it, turned by 50 degrees)
 * reflects L = rho / pi * sum over the texels above the horizon of
 * rgb (2 pi / w) (c_top^2 - c_bottom^2) / 2 (the cosine-weighted solid
 * angle of each band), direct light only; the centre of a narrow camera
 * looking straight down, within 5 standard errors. */
static void env_floor(void)
{
    enum { W = 32, H = 16 };
    const float rho = 0.8f;
    mesh m;
    CHECK(mesh_init(&m, 2));
    float f0[3] = {-5, 0, -5}, f1[3] = {-5, 0, 5}, f2[3] = {5, 0, 5}, f3[3] = {5, 0, -5};
    tri(&m, f0, f1, f2, 0);
    tri(&m, f0, f2, f3, 0);
    dirt_material mat = mat_make(rho, 0.0f, 1.0f, 0.0f);
    float spec = 0.0f;
    dirt_ref_materials mats = {&mat, 1, NULL, 0, &spec};
    float *rgb = malloc(W * H * 3 * sizeof(float));
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            for (int c = 0; c < 3; c++)
                rgb[3 * (j * W + i) + c] = (j == 3 && i == 20) ? 60.0f
                                           : 0.2f + 0.05f * (float)j + 0.01f * (float)(i % 7);
    dirt_env *env = dirt_env_create(rgb, W, H, &(dirt_env_opts){.rotation = 50.0f});
    CHECK(env != NULL);
    if (!env) {
        free(rgb);
        mesh_free(&m);
        return;
    }
    double expect = 0.0;
    for (int j = 0; j < H / 2; j++) {
        double ct = env->row_cos[j], cb = env->row_cos[j + 1];
        for (int i = 0; i < W; i++)
            expect += env->rgb[3 * (j * W + i)] * (2.0 * PI / W) * (ct * ct - cb * cb) / 2.0;
    }
    expect *= rho / PI;
    dirt_camera cam;
    look(&cam, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1e-3f);
    dirt_ref_opts o = {0};
    o.width = 16;
    o.height = 16;
    o.spp = 64;
    o.bounces = 1;
    o.seed = 9u;
    o.env = env;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    if (img) {
        double mean, se;
        image_mean(img, &mean, &se);
        fprintf(stderr, "environment floor: L %.5f expected %.5f, s.e. %.5f\n", mean, expect, se);
        CHECK(se > 0.0 && se < 0.02 * expect);
        CHECK_MSG(fabs(mean - expect) < 5.0 * se, "L %.5f, expected %.5f, s.e. %.5f", mean,
                  expect, se);
    }
    dirt_image_destroy(img);
    dirt_env_destroy(env);
    free(rgb);
    mesh_free(&m);
}

/* Triangle a, b, c of a closed body around the origin, turned to face
 * outwards; degenerate ones (at the poles) skipped. */
static void tri_out(mesh *m, const float a[3], const float b[3], const float c[3], uint32_t mat)
{
    float e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 1e-9f))
        return;
    float out = n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]);
    if (out > 0.0f)
        tri(m, a, b, c, mat);
    else
        tri(m, a, c, b, mat);
}

/* Glass furnace (KHR_materials_transmission): a closed faceted sphere
 * (radius 1, 48 x 24 segments, flat normals) of white glass (base 1,
 * metallic 0, transmission 1, ior 1.5, specular 1) in a uniform
 * environment of radiance 1 (the background) must look like its
 * surroundings: every path that enters leaves again (the 1 / eta^2 of
 * entering undone by the eta^2 of leaving) and reflection F plus
 * transmission 1 - F is 1 at every smooth interface, so the pixels over
 * the sphere have mean 1 (smooth: within 5 standard errors).
 * Bounces: the facets (7.5 degrees apart) let rays near the rim meet the
 * next facet beyond the critical angle, and such chains of total internal
 * reflection run long; measured smooth means with K = 48, 100, 200, 500,
 * 1000: 0.99367 (seed 11, 64 spp), 0.99719, 0.99909, 0.99993, 0.99993, so
 * K = 500 leaves no truncation visible (Russian roulette from the 4th ray on
 * keeps the rest unbiased).
 * Rough (NEE of the environment through the surface, MIS, shadow rays from
 * the far side): the single-scattering GGX lobes lose energy (the directional
 * albedo of test_ref_transmission: roughness 0.1 >= 0.998 except within a
 * few degrees of grazing; 0.3 from 0.999 down to 0.88), so the mean must lie
 * in [1 - loss, 1 + 5 s.e.] with loss 0.01 for roughness 0.1 and 0.08 for
 * 0.3; and the same image without next-event estimation (a copy of the map
 * with total 0: pure BSDF sampling, MIS weight 1) must have the same mean
 * within 5 combined standard errors: NEE and MIS through the surface add
 * nothing and lose nothing. */
static double sphere_mean(const dirt_material *mat, const float *spec, int bounces, bool nee,
                          const char *what, double *se_out, uint64_t *invalid)
{
    enum { NU = 48, NV = 24 };
    mesh m;
    CHECK(mesh_init(&m, 2 * NU * NV));
    float p[NV + 1][NU + 1][3];
    for (int j = 0; j <= NV; j++)
        for (int i = 0; i <= NU; i++) {
            double th = PI * j / NV, ph = 2.0 * PI * i / NU;
            p[j][i][0] = (float)(sin(th) * cos(ph));
            p[j][i][1] = (float)cos(th);
            p[j][i][2] = (float)(sin(th) * sin(ph));
        }
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            tri_out(&m, p[j][i], p[j][i + 1], p[j + 1][i + 1], 0);
            tri_out(&m, p[j][i], p[j + 1][i + 1], p[j + 1][i], 0);
        }
    dirt_ref_materials mats = {mat, 1, NULL, 0, spec};
    dirt_camera cam;
    look(&cam, 0.4f, 0.9f, 3.2f, 0.0f, 0.0f, 0.0f, 0.75f);
    dirt_ref_opts o = {0};
    o.width = 32;
    o.height = 32;
    o.spp = 64;
    o.bounces = bounces;
    o.seed = 11u;
    const float one[3] = {1.0f, 1.0f, 1.0f};
    dirt_env *env = dirt_env_constant(one);
    CHECK(env != NULL);
    /* Without NEE: the map is seen by rays but never sampled (total 0), and
     * a punctual light of zero power keeps one NEE source (so the
     * environment's MIS pdf is 0 / 1, weight 1). */
    dirt_light black;
    memset(&black, 0, sizeof(black));
    black.type = DIRT_LIGHT_DIRECTIONAL;
    black.direction[1] = -1.0f;
    if (env && !nee) {
        env->total = 0.0f;
        m.f.num_lights = 1;
        m.f.lights = &black;
    }
    o.env = env;
    dirt_ref_stats st;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &o, &st);
    CHECK(img != NULL);
    float *ids = img ? dirt_image_find_channel(img, "ID") : NULL;
    CHECK(ids != NULL);
    double mean = 0.0, se = 1.0;
    if (img && ids) {
        double s = 0.0, s2 = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < (size_t)o.width * (size_t)o.height; i++) {
            if (ids[i] < 0)
                continue;
            double v = img->rgba[4 * i];
            s += v;
            s2 += v * v;
            n++;
        }
        mean = s / (double)n;
        se = sqrt(fmax(s2 / n - mean * mean, 0.0) / (n - 1));
        fprintf(stderr, "%s furnace (roughness %.2f, %s): %zu sphere pixels, mean %.5f, "
                "s.e. %.5f\n", what, mat->roughness, nee ? "NEE" : "no NEE", n, mean, se);
        CHECK(n > 200);
        *invalid = st.invalid;
    }
    dirt_image_destroy(img);
    dirt_env_destroy(env);
    mesh_free(&m);
    *se_out = se;
    return mean;
}

static double glass_mean(float roughness, bool nee, double *se_out, uint64_t *invalid)
{
    dirt_material mat = mat_make(1.0f, 0.0f, roughness, 0.0f);
    mat.transmission = 1.0f;
    mat.ior = 1.5f;
    return sphere_mean(&mat, NULL, 500, nee, "glass", se_out, invalid);
}

/* The furnace: the same sphere white and diffuse (Lambert: albedo
 * 1, metallic 0, dielectric specular weight 0) in the uniform environment
 * of radiance 1 reflects 1 (a convex body: every reflected direction sees
 * the environment): with NEE (MIS of light and BSDF samples) within 5
 * standard errors; without it every path is exactly 1 (zero variance). */
static void diffuse_sphere_furnace(void)
{
    dirt_material mat = mat_make(1.0f, 0.0f, 1.0f, 0.0f);
    float spec = 0.0f;
    for (int nee = 1; nee >= 0; nee--) {
        double se = 1.0;
        uint64_t bad = 1;
        double mean = sphere_mean(&mat, &spec, 4, nee, "white diffuse sphere", &se, &bad);
        CHECK(bad == 0 && se < 0.01);
        /* Without NEE every path is the cosine-sampled Lambert weight 1
         * times the environment's 1: exactly 1 up to float rounding. */
        double tol = nee ? 5.0 * se : 1e-5;
        CHECK_MSG(fabs(mean - 1.0) < tol, "white diffuse sphere (%s): mean %.5f, s.e. %.5f",
                  nee ? "NEE" : "no NEE", mean, se);
    }
}

static void glass_furnace(float roughness, double loss)
{
    double se, se2;
    uint64_t bad = 1, bad2 = 1;
    double mean = glass_mean(roughness, true, &se, &bad);
    CHECK(bad == 0 && se < 0.01);
    CHECK_MSG(mean > 1.0 - loss - 5.0 * se && mean < 1.0 + 5.0 * se,
              "glass, roughness %.2f: mean %.5f, s.e. %.5f", roughness, mean, se);
    if (roughness > 0.0f) {
        double m2 = glass_mean(roughness, false, &se2, &bad2);
        CHECK(bad2 == 0);
        CHECK_MSG(fabs(mean - m2) < 5.0 * sqrt(se * se + se2 * se2),
                  "glass, roughness %.2f: with NEE %.5f, without %.5f", roughness, mean, m2);
    }
}

/* Form factor from a point to a rectangle X h by Y h parallel to it at
 * height h with one corner above the point. */
static double corner_ff(double X, double Y)
{
    double a = sqrt(1.0 + X * X), b = sqrt(1.0 + Y * Y);
    return (X / a * atan(Y / a) + Y / b * atan(X / b)) / (2.0 * PI);
}

static void near_light(float offset)
{
    const float a = 0.5f, h = 0.5f, le = 3.0f, rho = 0.6f, o = offset;
    mesh m;
    CHECK(mesh_init(&m, 4));
    float f0[3] = {o - 5, 0, o - 5}, f1[3] = {o - 5, 0, o + 5}, f2[3] = {o + 5, 0, o + 5},
          f3[3] = {o + 5, 0, o - 5};
    tri(&m, f0, f1, f2, 0);
    tri(&m, f0, f2, f3, 0);
    /* the emitter, counter-clockwise seen from below */
    float l0[3] = {o - a, h, o - a}, l1[3] = {o + a, h, o - a}, l2[3] = {o + a, h, o + a},
          l3[3] = {o - a, h, o + a};
    tri(&m, l0, l1, l2, 1);
    tri(&m, l0, l2, l3, 1);
    dirt_material mat[2] = {mat_make(rho, 0.0f, 1.0f, 0.0f), mat_make(0.0f, 0.0f, 1.0f, le)};
    float spec[2] = {0.0f, 0.0f};
    dirt_ref_materials mats = {mat, 2, NULL, 0, spec};
    dirt_camera cam;
    look(&cam, o + 2.0f, 0.1f, o, o, 0.0f, o, 1e-4f);
    dirt_ref_opts opt = {0};
    opt.width = 16;
    opt.height = 16;
    opt.spp = 64;
    opt.bounces = 1;
    opt.seed = 5u;
    dirt_image *img = dirt_ref_render_materials(&mats, &m.f, &cam, &opt, NULL);
    CHECK(img != NULL);
    if (img) {
        double expect = rho / PI * le * PI * 4.0 * corner_ff(a / h, a / h), mean, se;
        image_mean(img, &mean, &se);
        fprintf(stderr, "near light at %g: L %.5f expected %.5f, s.e. %.5f\n", offset, mean,
                expect, se);
        CHECK(se > 0.0 && se < 0.02 * expect);
        CHECK_MSG(fabs(mean - expect) < 5.0 * se, "near light at %g: L %.5f, expected %.5f",
                  offset, mean, expect);
    }
    dirt_image_destroy(img);
    mesh_free(&m);
}

int main(void)
{
    furnace(1, 128);
    furnace(2, 128);
    furnace(3, 128);
    furnace(6, 128);   /* Russian roulette active from the 4th ray on */
    furnace(40, 128);  /* ~ the infinite series: 2 - 2^-40 */
    furnace_variant(3, 128, BLACK_LIGHT);
    furnace_variant(3, 16, OUTWARD);
    furnace_variant(3, 128, OUTWARD_TWO_SIDED);
    mirror_furnace(1);
    mirror_furnace(5);
    lights();
    background();
    env_furnace(false);
    env_furnace(true);
    env_floor();
    near_light(0.0f);
    near_light(20.0f);
    diffuse_sphere_furnace();
    glass_furnace(0.0f, 0.0);
    glass_furnace(0.1f, 0.01);
    glass_furnace(0.3f, 0.08);
    return check_finish();
}
