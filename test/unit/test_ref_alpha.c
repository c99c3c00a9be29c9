/* Alpha coverage in the model and in the Embree reference
 * (doc/light-transport.md section 1, "Alpha"; doc/rng.md, "Alpha").
 *  - coverage = base_color[3] * T(base colour).a, alpha never decoded;
 *    MASK accepts coverage >= cutoff; BLEND accepts with probability a;
 *  - the decision hash: frozen values, a pure function of (ray key, prim)
 *    (any order, any number of calls), decisions of neighbouring primitives
 *    and rays uncorrelated;
 *  - Embree: a ray through a masked-out texel hits the wall behind, one
 *    through a covered texel the plane; shadow rays likewise; through a
 *    BLEND plane of coverage 0.3, 0.7 of the rays pass (within 5 standard
 *    errors), closest-hit and occlusion queries alike; through two stacked
 *    BLEND planes every ray hits exactly the first plane that accepts it;
 *  - the renderer: a black BLEND plane (a = 0.3) in front of a white
 *    background shows 0.7 (opaque: 0); a masked plane shows the background
 *    where the texture is transparent and the plane elsewhere (within the
 *    black metal's Fresnel reflection, 2e-4). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "integrator/integrator.h"
#include "ref/ref.h"
#include "integrator/rng.h"

/* Up to 8 quads, 2 triangles each. */
typedef struct mesh {
    dirt_frame f;
    float pos[48][3];
    float uv[48][2];
    uint32_t mat[16];
} mesh;

/* Quad a b c d (counter-clockwise seen from its front) of material m with
 * UVs (0,0) at a, (1,0) at b, (1,1) at c, (0,1) at d. */
static void quad(mesh *m, const float a[3], const float b[3], const float c[3], const float d[3],
                 uint32_t mat)
{
    size_t n = m->f.num_triangles;
    const float *v[6] = {a, b, c, a, c, d};
    static const float t[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const int ti[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) {
        memcpy(m->pos[3 * n + (size_t)i], v[i], sizeof(float[3]));
        memcpy(m->uv[3 * n + (size_t)i], t[ti[i]], sizeof(float[2]));
    }
    m->mat[n] = m->mat[n + 1] = mat;
    m->f.num_triangles = n + 2;
    m->f.position = m->pos;
    m->f.uv = m->uv;
    m->f.material = m->mat;
    m->f.normal = NULL;
}

/* A square in the plane z = const, facing +z, x and y in [-h, h]. */
static void plane_z(mesh *m, float z, float h, uint32_t mat)
{
    float a[3] = {-h, -h, z}, b[3] = {h, -h, z}, c[3] = {h, h, z}, d[3] = {-h, h, z};
    quad(m, a, b, c, d, mat);
}

static dirt_material make(enum dirt_alpha_mode mode, float alpha, int tex)
{
    dirt_material m;
    dirt_material_default(&m);
    m.alpha_mode = mode;
    m.base_color[3] = alpha;
    m.base_color_tex = tex;
    return m;
}

/* 2 x 1 texture: texel 0 opaque, texel 1 transparent (RGB white). Along u
 * the linear-filtered alpha is 1 at u = 0.25, 0 at u = 0.75, 0.5 at u = 0
 * and 0.5. */
static uint8_t mask_px[8] = {255, 255, 255, 255, 255, 255, 255, 0};

static dirt_texture mask_texture(void)
{
    dirt_texture t;
    memset(&t, 0, sizeof(t));
    t.width = 2;
    t.height = 1;
    t.rgba = mask_px;
    t.srgb = true;
    return t;
}

static void test_coverage(void)
{
    static uint8_t px[4] = {10, 20, 30, 128};
    dirt_texture t;
    memset(&t, 0, sizeof(t));
    t.width = t.height = 1;
    t.rgba = px;
    t.srgb = true;
    dirt_material m = make(DIRT_ALPHA_BLEND, 0.5f, 0);
    /* Alpha is linear: 128 / 255, not its sRGB decode (0.216). */
    CHECK_NEAR(dirt_material_coverage(&m, &t, 1, 0.3f, 0.7f), 0.5 * 128.0 / 255.0, 1e-7);
    m.base_color_tex = DIRT_NO_TEXTURE;
    CHECK(dirt_material_coverage(&m, &t, 1, 0.3f, 0.7f) == 0.5f);
    m.base_color_tex = 3; /* out of range: white */
    CHECK(dirt_material_coverage(&m, &t, 1, 0.3f, 0.7f) == 0.5f);
    dirt_texture mt = mask_texture();
    m = make(DIRT_ALPHA_MASK, 1.0f, 0);
    CHECK_NEAR(dirt_material_coverage(&m, &mt, 1, 0.25f, 0.5f), 1.0, 1e-7);
    CHECK_NEAR(dirt_material_coverage(&m, &mt, 1, 0.75f, 0.5f), 0.0, 1e-7);
    CHECK_NEAR(dirt_material_coverage(&m, &mt, 1, 0.5f, 0.5f), 0.5, 1e-7);
    /* At the base colour slot's transformed uv (KHR_texture_transform):
     * offset u by 0.5 and the opaque half reads the clear one. */
    m.xf[DIRT_SLOT_BASE_COLOR].set = true;
    m.xf[DIRT_SLOT_BASE_COLOR].offset[0] = 0.5f;
    CHECK_NEAR(dirt_material_coverage(&m, &mt, 1, 0.25f, 0.5f), 0.0, 1e-7);
    CHECK_NEAR(dirt_material_coverage(&m, &mt, 1, 0.75f, 0.5f), 1.0, 1e-7);
    m.xf[DIRT_SLOT_BASE_COLOR].set = false;

    /* MASK: coverage >= cutoff is seen. */
    m.alpha_cutoff = 0.5f;
    CHECK(dirt_alpha_accept(&m, &mt, 1, 0.5f, 0.5f, 0, 0));   /* exactly the cutoff */
    CHECK(dirt_alpha_accept(&m, &mt, 1, 0.25f, 0.5f, 0, 0));
    CHECK(!dirt_alpha_accept(&m, &mt, 1, 0.75f, 0.5f, 0, 0));
    CHECK(!dirt_alpha_accept(&m, &mt, 1, 0.51f, 0.5f, 0, 0)); /* 0.48 */
    m.alpha_cutoff = 0.0f;
    CHECK(dirt_alpha_accept(&m, &mt, 1, 0.75f, 0.5f, 0, 0)); /* cutoff 0: everything */
    /* OPAQUE ignores coverage; BLEND with a = 0 is never seen, a = 1 always. */
    dirt_material o = make(DIRT_ALPHA_OPAQUE, 0.0f, DIRT_NO_TEXTURE);
    dirt_material b0 = make(DIRT_ALPHA_BLEND, 0.0f, DIRT_NO_TEXTURE);
    dirt_material b1 = make(DIRT_ALPHA_BLEND, 1.0f, DIRT_NO_TEXTURE);
    dirt_material b3 = make(DIRT_ALPHA_BLEND, 0.3f, DIRT_NO_TEXTURE);
    int n0 = 0, n1 = 0, no = 0, n3 = 0;
    const int N = 100000;
    for (int k = 0; k < N; k++) {
        uint32_t key = dirt_rng_u32(7, (uint32_t)k, 3, 1, DIRT_RNG_DIM_ALPHA_PATH);
        no += dirt_alpha_accept(&o, NULL, 0, 0, 0, key, 5);
        n0 += dirt_alpha_accept(&b0, NULL, 0, 0, 0, key, 5);
        n1 += dirt_alpha_accept(&b1, NULL, 0, 0, 0, key, 5);
        n3 += dirt_alpha_accept(&b3, NULL, 0, 0, 0, key, (uint32_t)k % 17);
    }
    CHECK(no == N && n0 == 0 && n1 == N);
    double sd = sqrt(0.3 * 0.7 / N);
    fprintf(stderr, "BLEND a = 0.3: %.4f of %d keys accept (5 sd = %.4f)\n", (double)n3 / N, N,
            5 * sd);
    CHECK(fabs((double)n3 / N - 0.3) < 5 * sd);
    CHECK(dirt_material_alpha_tested(&m) && dirt_material_alpha_tested(&b3) &&
          !dirt_material_alpha_tested(&o));
    dirt_material list[2] = {o, b3};
    CHECK(!dirt_materials_alpha_tested(list, 1) && dirt_materials_alpha_tested(list, 2));
}

static void test_hash(void)
{
    /* Frozen (doc/rng.md, "Alpha"): changing them changes the specification. */
    uint32_t k = dirt_rng_u32(0, 0, 0, 0, DIRT_RNG_DIM_ALPHA_PATH);
    fprintf(stderr, "alpha keys: path(0,0,0,0) = 0x%08x, shadow(1,2,3,4) = 0x%08x, "
            "decision(prim 0) = %.9g, (prim 12345 of key 0xdeadbeef) = %.9g\n", k,
            dirt_rng_u32(1, 2, 3, 4, DIRT_RNG_DIM_ALPHA_SHADOW), (double)dirt_rng_alpha(k, 0),
            (double)dirt_rng_alpha(0xdeadbeefu, 12345));
    CHECK(k == 0x3e98135bu);
    CHECK(dirt_rng_alpha(k, 0) == 0.871368051f);
    CHECK(dirt_rng_u32(1, 2, 3, 4, DIRT_RNG_DIM_ALPHA_SHADOW) == 0xee86cc67u);
    CHECK(dirt_rng_alpha(0xdeadbeefu, 12345) == dirt_rng_to_float(dirt_rng_mix(0xdeadbeefu + 12345u * 0x9e3779b9u)));
    /* Order and repetition do not matter: a traversal may test a primitive
     * several times, in any order. */
    enum { P = 64 };
    float fwd[P], rev[P];
    for (uint32_t p = 0; p < P; p++)
        fwd[p] = dirt_rng_alpha(k, p);
    for (int r = 0; r < 3; r++)
        for (int p = P - 1; p >= 0; p--)
            rev[p] = dirt_rng_alpha(k, (uint32_t)p);
    CHECK(memcmp(fwd, rev, sizeof(fwd)) == 0);
    /* Neighbouring primitives under one key, one primitive under
     * neighbouring pixels' keys, and a ray's path and shadow keys: the
     * decisions' correlation within 5 / sqrt(N). */
    const int N = 200000;
    double sxy[3] = {0, 0, 0}, sx[3] = {0, 0, 0}, sy[3] = {0, 0, 0}, sxx[3] = {0, 0, 0},
           syy[3] = {0, 0, 0};
    for (int i = 0; i < N; i++) {
        uint32_t a = dirt_rng_u32(3, (uint32_t)i, 0, 1, DIRT_RNG_DIM_ALPHA_PATH);
        uint32_t b = dirt_rng_u32(3, (uint32_t)i + 1, 0, 1, DIRT_RNG_DIM_ALPHA_PATH);
        uint32_t s = dirt_rng_u32(3, (uint32_t)i, 0, 1, DIRT_RNG_DIM_ALPHA_SHADOW);
        double x[3] = {dirt_rng_alpha(a, 7), dirt_rng_alpha(a, 7), dirt_rng_alpha(a, 7)};
        double y[3] = {dirt_rng_alpha(a, 8), dirt_rng_alpha(b, 7), dirt_rng_alpha(s, 7)};
        for (int c = 0; c < 3; c++) {
            sx[c] += x[c];
            sy[c] += y[c];
            sxy[c] += x[c] * y[c];
            sxx[c] += x[c] * x[c];
            syy[c] += y[c] * y[c];
        }
    }
    static const char *const what[3] = {"prim p vs p+1", "pixel i vs i+1", "path vs shadow"};
    for (int c = 0; c < 3; c++) {
        double cov = sxy[c] / N - sx[c] / N * sy[c] / N;
        double corr = cov / sqrt((sxx[c] / N - sx[c] * sx[c] / N / N) *
                                 (syy[c] / N - sy[c] * sy[c] / N / N));
        fprintf(stderr, "decision correlation, %s: %.5f\n", what[c], corr);
        CHECK(fabs(corr) < 5.0 / sqrt((double)N));
    }
}

/* A ray along -z through (x, y) from z = 5. */
static dirt_ref_ray ray_at(float x, float y)
{
    dirt_ref_ray r = {{x, y, 5.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, INFINITY};
    return r;
}

static void test_embree(void)
{
    dirt_texture mt = mask_texture();
    dirt_material mats[4] = {make(DIRT_ALPHA_OPAQUE, 1.0f, DIRT_NO_TEXTURE),
                             make(DIRT_ALPHA_MASK, 1.0f, 0),
                             make(DIRT_ALPHA_BLEND, 0.3f, DIRT_NO_TEXTURE),
                             make(DIRT_ALPHA_BLEND, 0.5f, DIRT_NO_TEXTURE)};
    dirt_ref_materials rm = {mats, 4, &mt, 1, NULL};
    dirt_ref_accel_opts ao = {.alpha = &rm};

    /* MASK: plane at z = 0 (u = (x + 1) / 2), opaque wall at z = -1. */
    mesh m;
    memset(&m, 0, sizeof(m));
    plane_z(&m, 0.0f, 1.0f, 1);
    plane_z(&m, -1.0f, 4.0f, 0);
    dirt_ref_accel *a = dirt_ref_accel_create(&m.f, &ao);
    dirt_ref_accel *plain = dirt_ref_accel_create(&m.f, NULL);
    CHECK(a && plain && dirt_ref_accel_alpha_tested(a) && !dirt_ref_accel_alpha_tested(plain));
    if (a && plain) {
        /* x = -0.5: u = 0.25 covered; x = 0.5: u = 0.75 masked out. */
        dirt_ref_hit h;
        dirt_ref_ray r = ray_at(-0.5f, 0.1f);
        CHECK(dirt_ref_intersect1(a, &r, &h) && h.prim < 2 && fabsf(h.t - 5.0f) < 1e-5f);
        r = ray_at(0.5f, 0.1f);
        CHECK(dirt_ref_intersect1(a, &r, &h) && h.prim >= 2 && fabsf(h.t - 6.0f) < 1e-5f);
        CHECK(dirt_ref_intersect1(plain, &r, &h) && h.prim < 2); /* no alpha: opaque */
        /* Shadow rays from the wall towards z = 5 through the plane. */
        dirt_ref_ray s = {{0.5f, 0.1f, -0.9f}, 0.0f, {0.0f, 0.0f, 1.0f}, 5.0f};
        CHECK(!dirt_ref_occluded1(a, &s));
        CHECK(dirt_ref_occluded1(plain, &s));
        s.org[0] = -0.5f;
        CHECK(dirt_ref_occluded1(a, &s));
        /* A row of rays across the plane: hits the plane iff coverage >=
         * cutoff at the hit's UV (the model's own decision). */
        int bad = 0;
        for (int i = 0; i < 1000; i++) {
            float x = -0.999f + 1.998f * (float)i / 999.0f;
            r = ray_at(x, 0.3f);
            bool hit = dirt_ref_intersect1(a, &r, &h) && h.prim < 2;
            float u = (x + 1.0f) * 0.5f;
            float cov = dirt_material_coverage(&mats[1], &mt, 1, u, 0.65f);
            if (fabsf(cov - 0.5f) > 1e-4f && hit != (cov >= 0.5f))
                bad++;
        }
        CHECK_MSG(bad == 0, "%d rays disagree with the coverage", bad);
    }
    dirt_ref_accel_destroy(a);
    dirt_ref_accel_destroy(plain);

    /* BLEND a = 0.3: 0.7 of the rays pass (closest hit and occlusion). */
    memset(&m, 0, sizeof(m));
    plane_z(&m, 0.0f, 1.0f, 2);
    a = dirt_ref_accel_create(&m.f, &ao);
    CHECK(a != NULL);
    if (a) {
        const int N = 20000;
        int pass = 0, pass_occ = 0, same = 0;
        for (int i = 0; i < N; i++) {
            uint32_t key = dirt_rng_u32(1, (uint32_t)i, 0, 0, DIRT_RNG_DIM_ALPHA_PATH);
            dirt_ref_ray r = ray_at(0.9f * sinf((float)i), 0.9f * cosf(1.3f * (float)i));
            dirt_ref_hit h, h2;
            bool hit = dirt_ref_intersect1_key(a, &r, key, &h);
            pass += !hit;
            pass_occ += !dirt_ref_occluded1_key(a, &r, key);
            /* The same key answers the same (the decision is the key's). */
            same += dirt_ref_intersect1_key(a, &r, key, &h2) == hit &&
                    hit == dirt_ref_occluded1_key(a, &r, key);
        }
        double sd = sqrt(0.3 * 0.7 / N);
        fprintf(stderr, "BLEND plane a = 0.3: %.4f of %d rays pass (occlusion: %.4f; 5 sd = "
                "%.4f)\n", (double)pass / N, N, (double)pass_occ / N, 5 * sd);
        CHECK(fabs((double)pass / N - 0.7) < 5 * sd);
        CHECK(pass == pass_occ);
        CHECK(same == N);
    }
    dirt_ref_accel_destroy(a);

    /* Two stacked BLEND planes (a = 0.5 at z = 0, 0.3 at z = -1) and an
     * opaque wall: every ray hits the first plane that accepts it. */
    memset(&m, 0, sizeof(m));
    plane_z(&m, 0.0f, 1.0f, 3);
    plane_z(&m, -1.0f, 1.0f, 2);
    plane_z(&m, -2.0f, 4.0f, 0);
    a = dirt_ref_accel_create(&m.f, &ao);
    CHECK(a != NULL);
    if (a) {
        const int N = 20000;
        int bad = 0, counts[3] = {0, 0, 0};
        for (int i = 0; i < N; i++) {
            uint32_t key = dirt_rng_u32(2, (uint32_t)i, 5, 2, DIRT_RNG_DIM_ALPHA_SHADOW);
            float x = 0.9f * sinf((float)i), y = 0.9f * cosf(1.7f * (float)i);
            dirt_ref_ray r = ray_at(x, y);
            dirt_ref_hit h;
            if (!dirt_ref_intersect1_key(a, &r, key, &h)) {
                bad++;
                continue;
            }
            /* The triangle of each quad at (x, y): the first of the two
             * (a b c) holds the points with u >= v (x >= y here). */
            uint32_t tri = x >= y ? 0u : 1u;
            int expect = dirt_alpha_accept(&mats[3], NULL, 0, 0, 0, key, tri) ? 0
                         : dirt_alpha_accept(&mats[2], NULL, 0, 0, 0, key, 2 + tri) ? 1 : 2;
            int got = (int)(h.prim / 2);
            if (got > 2 || got != expect)
                bad++;
            else
                counts[got]++;
        }
        fprintf(stderr, "stacked BLEND planes: first %.4f, second %.4f, wall %.4f (expected "
                "0.5, 0.15, 0.35), %d mismatches\n", (double)counts[0] / N,
                (double)counts[1] / N, (double)counts[2] / N, bad);
        CHECK(bad == 0);
        CHECK(fabs((double)counts[2] / N - 0.35) < 5 * sqrt(0.35 * 0.65 / N));
    }
    dirt_ref_accel_destroy(a);
}

/* The renderer: a plane of material `mat` (black metal, reflects nothing)
 * filling the view of a camera at z = 3 in front of a white background. */
static double render_mean(dirt_material mat, const dirt_texture *tex, size_t num_tex,
                          float *transparent_err)
{
    mesh m;
    memset(&m, 0, sizeof(m));
    plane_z(&m, 0.0f, 2.0f, 0);
    mat.base_color[0] = mat.base_color[1] = mat.base_color[2] = 0.0f;
    mat.metallic = 1.0f;
    dirt_ref_materials rm = {&mat, 1, tex, num_tex, NULL};
    dirt_camera cam;
    memset(&cam, 0, sizeof(cam));
    float eye[3] = {0, 0, 3}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    dirt_camera_look_at(&cam, eye, target, up);
    cam.yfov = 0.5f;
    dirt_ref_opts o = {.width = 32, .height = 32, .spp = 16, .bounces = 2, .seed = 3,
                       .background = {1.0f, 1.0f, 1.0f}, .threads = 2};
    dirt_image *img = dirt_ref_render_materials(&rm, &m.f, &cam, &o, NULL);
    CHECK(img != NULL);
    if (!img)
        return -1.0;
    double s = 0;
    float err = 0;
    for (int y = 0; y < 32; y++) {
        for (int x = 0; x < 32; x++) {
            float v = img->rgba[4 * (y * 32 + x)];
            s += v;
            if (tex) {
                /* The pixel's UV range along u: fully transparent or fully
                 * covered pixels must read 1 or 0 exactly. */
                dirt_vec3 org, dir;
                float u[2];
                for (int k = 0; k < 2; k++) {
                    dirt_camera_ray(&cam, 32, 32, (float)x + (float)k, (float)y + 0.5f, 0, 0,
                                    &org, &dir);
                    float t = -org.z / dir.z;
                    u[k] = (org.x + t * dir.x + 2.0f) / 4.0f;
                }
                float u0 = fminf(u[0], u[1]), u1 = fmaxf(u[0], u[1]);
                /* covered for frac(u) in [0, 0.5] (cutoff 0.5), transparent
                 * in (0.5, 1) */
                float f0 = u0 - floorf(u0), f1 = f0 + (u1 - u0);
                if (f0 > 0.52f && f1 < 0.98f)
                    err = fmaxf(err, fabsf(v - 1.0f));
                else if (f0 > 0.02f && f1 < 0.48f)
                    err = fmaxf(err, fabsf(v));
            }
        }
    }
    if (transparent_err)
        *transparent_err = err;
    dirt_image_destroy(img);
    return s / (32.0 * 32.0);
}

static void test_render(void)
{
    double mb = render_mean(make(DIRT_ALPHA_BLEND, 0.3f, DIRT_NO_TEXTURE), NULL, 0, NULL);
    double sd = sqrt(0.21 / (32.0 * 32.0 * 16.0));
    fprintf(stderr, "render: black BLEND plane a = 0.3 over white: %.4f (expected 0.7, 5 sd "
            "%.4f)\n", mb, 5 * sd);
    CHECK(fabs(mb - 0.7) < 5 * sd);
    double mo = render_mean(make(DIRT_ALPHA_OPAQUE, 0.3f, DIRT_NO_TEXTURE), NULL, 0, NULL);
    CHECK(mo < 0.01); /* only the metal's Schlick Fresnel at the edges */
    dirt_texture mt = mask_texture();
    float err = 1.0f;
    dirt_material mm = make(DIRT_ALPHA_MASK, 1.0f, 0);
    double mk = render_mean(mm, &mt, 1, &err);
    fprintf(stderr, "render: masked plane: mean %.4f (half transparent), pixels off their "
            "texels' answer by %.3g\n", mk, err);
    CHECK(fabs(mk - 0.5) < 0.05);
    CHECK(err < 0.01f); /* the black metal's Fresnel: 2e-4 */
}

int main(void)
{
    test_coverage();
    test_hash();
    test_embree();
    test_render();
    return check_finish();
}
