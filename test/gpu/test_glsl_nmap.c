/* GLSL texture transforms and normal maps == C (glsl/integrator/model.glsl
 * against src/integrator/texture.c), through the records
 * dirt_gpu_materials_pack and dirt_gpu_textures_pack upload:
 * - the slot uv (dirt_slot_uv_g vs dirt_tex_transform_apply of the slot's
 *   dirt_tex_transform_matrix): bit for bit, for 64 materials with random
 *   transforms per slot (set or not; offsets, rotations up to +-7 rad, scales
 *   incl. 0 and negative) at uniform uvs and special ones (+-0, +-inf, NaN,
 *   1e30, denormals): the packer computes the matrix with the C function,
 *   the shader applies it with `precise` products and sums;
 * - the tangent-space normal (dirt_material_normal_ts_g): the same verdict,
 *   the normal within 1e-6 (linear lookups are bit-exact on both sides; the
 *   normalisation's sqrt and division are GLSL's);
 * - the normal-map frame (dirt_normal_map_apply_g) on random unit normals,
 *   tangents at least 0.01 |t| off the normal (away from the 1e-3
 *   threshold, where the two sides may decide differently), both
 *   handednesses, within 1e-5; and on degenerate tangents (0, along n,
 *   NaN, inf): n itself, bit for bit;
 * - textured surfaces with transforms (dirt_material_surface_g): within
 *   2e-6 times the value's scale (the sRGB decode's division and pow; the
 *   untransformed case is test_glsl_model's).
 * The shader built with TEST_FAULT (every result r -> 1.001 r + 0.01) must
 * fail nearly every record. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/vec3.h"
#include "integrator/gpu_tables.h"
#include "integrator/integrator.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gpu.h"
#include "model_shader.h"

#define N 20000
#define NUM_MATERIALS 64
#define NUM_TEXTURES 5
#define MODE_SLOT_UV 0
#define MODE_NORMAL_TS 1
#define MODE_APPLY 2
#define MODE_SURFACE 3

static uint32_t rng = 88172645u;
static float urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return (float)(rng >> 8) * (1.0f / 16777216.0f);
}
static float urange(float a, float b) { return a + (b - a) * urand(); }
static int irange(int n) { return (int)(urand() * (float)n) % n; }

static dirt_material g_mats[NUM_MATERIALS];
static dirt_texture g_tex[NUM_TEXTURES];

static void make_tables(void)
{
    const int sizes[NUM_TEXTURES][2] = {{8, 4}, {3, 5}, {1, 1}, {17, 4}, {16, 16}};
    for (int t = 0; t < NUM_TEXTURES; t++) {
        int w = sizes[t][0], h = sizes[t][1];
        uint8_t *px = malloc((size_t)w * h * 4);
        for (int k = 0; k < w * h * 4; k++)
            px[k] = (uint8_t)(urand() * 256.0f);
        g_tex[t] = (dirt_texture){.width = w, .height = h, .rgba = px};
    }
    for (int i = 0; i < NUM_MATERIALS; i++) {
        dirt_material *m = &g_mats[i];
        dirt_material_default(m);
        int pick[4];
        for (int k = 0; k < 4; k++) /* -1 none, 0..4, 5 out of range */
            pick[k] = irange(NUM_TEXTURES + 2) - 1;
        m->base_color_tex = pick[0];
        m->metallic_roughness_tex = pick[1];
        m->emissive_tex = pick[2];
        m->normal_tex = i < 4 ? -1 : pick[3] < 0 ? i % NUM_TEXTURES : pick[3];
        float scales[] = {1.0f, 0.0f, -1.0f, 0.5f};
        m->normal_scale = i < 8 ? scales[i % 4] : urange(-2.0f, 2.0f);
        for (int k = 0; k < 3; k++) {
            m->base_color[k] = urand();
            m->emissive[k] = i % 3 == 0 ? urange(0.0f, 3.0f) : 0.0f;
        }
        m->metallic = urand();
        m->roughness = urand();
        for (int s = 0; s < DIRT_NUM_TEX_SLOTS; s++) {
            dirt_tex_transform *x = &m->xf[s];
            x->set = i >= 2 && urand() < 0.8f;
            x->offset[0] = urange(-2.0f, 2.0f);
            x->offset[1] = urange(-2.0f, 2.0f);
            x->rotation = i % 5 == 0 ? 0.0f : urange(-7.0f, 7.0f);
            x->scale[0] = i % 7 == 0 ? 0.0f : urange(-3.0f, 3.0f);
            x->scale[1] = i % 11 == 0 ? 1.0f : urange(-3.0f, 3.0f);
        }
    }
}

static float special_uv(int k)
{
    const float s[] = {0.0f, -0.0f, INFINITY, -INFINITY, NAN, 1e30f, -1e30f, 1e-40f, 1.0f,
                       -1.0f, 0.5f, 1.0f - 1.0f / 16777216.0f};
    return s[k % (int)(sizeof(s) / sizeof(s[0]))];
}

/* Runs the shader over n records (3 vec4 in, 2 vec4 out). */
static bool run(dirt_gpu *gpu, GLuint prog, int mode, const float *in, int n, float *out)
{
    return test_run_model_shader(gpu, prog, mode, in, 12, n, out, 8);
}

static bool same_bits(float a, float b) { return memcmp(&a, &b, sizeof(a)) == 0; }

static dirt_vec3 random_unit(void)
{
    float z = urange(-1.0f, 1.0f), phi = 6.2831853f * urand();
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3_normalize(v3(s * cosf(phi), s * sinf(phi), z));
}

/* Compares every mode; returns the number of failed records (the fault
 * shader expects many). `report`: print and check. */
static int compare(dirt_gpu *gpu, GLuint prog, bool report)
{
    float *in = calloc((size_t)N * 12, sizeof(float)), *out = calloc((size_t)N * 8, sizeof(float));
    int bad_total = 0;
    for (int mode = 0; mode < 4; mode++) {
        for (int i = 0; i < N; i++) {
            float *a = &in[12 * i];
            memset(a, 0, 12 * sizeof(float));
            if (mode == MODE_APPLY) {
                dirt_vec3 n = random_unit(), t;
                if (i % 50 == 0) {
                    const dirt_vec3 deg[] = {v3(0, 0, 0), v3_scale(n, 2.0f), v3(NAN, 0, 0),
                                             v3(INFINITY, 1, 0), v3_scale(n, -0.5f)};
                    t = deg[(i / 50) % 5];
                } else {
                    do {
                        t = v3_scale(random_unit(), urange(0.1f, 3.0f));
                    } while (v3_length(v3_sub(t, v3_scale(n, v3_dot(n, t)))) <
                             0.01f * v3_length(t));
                }
                dirt_vec3 nts = random_unit();
                nts.z = fabsf(nts.z);
                a[0] = n.x, a[1] = n.y, a[2] = n.z;
                a[4] = t.x, a[5] = t.y, a[6] = t.z, a[7] = i % 2 ? 1.0f : -1.0f;
                a[8] = nts.x, a[9] = nts.y, a[10] = nts.z;
            } else {
                a[0] = (float)(i % NUM_MATERIALS);
                a[1] = (float)((i / NUM_MATERIALS) % DIRT_NUM_TEX_SLOTS);
                bool sp = i % 9 == 0;
                a[2] = sp ? special_uv(i / 9) : urange(-3.0f, 3.0f);
                a[3] = sp ? special_uv(i / 9 + 5) : urange(-3.0f, 3.0f);
            }
        }
        if (!run(gpu, prog, mode, in, N, out)) {
            CHECK(false);
            break;
        }
        int bad = 0, ok_count = 0;
        double worst = 0.0;
        for (int i = 0; i < N; i++) {
            const float *a = &in[12 * i], *o = &out[8 * i];
            const dirt_material *m = &g_mats[(int)a[0]];
            bool same = true;
            double err = 0.0;
            if (mode == MODE_SLOT_UV) {
                float x[6], c[2];
                dirt_tex_transform_matrix(&m->xf[(int)a[1]], x);
                dirt_tex_transform_apply(x, a[2], a[3], c);
                same = same_bits(o[0], c[0]) && same_bits(o[1], c[1]);
            } else if (mode == MODE_NORMAL_TS) {
                dirt_vec3 n = v3(0, 0, 0);
                bool ok = dirt_material_normal_ts(m, g_tex, NUM_TEXTURES, a[2], a[3], &n);
                ok_count += ok;
                same = o[0] == (ok ? 1.0f : 0.0f);
                if (same && ok) {
                    err = fmax(fabs(o[1] - n.x), fmax(fabs(o[2] - n.y), fabs(o[3] - n.z)));
                    same = err <= 1e-6;
                }
            } else if (mode == MODE_APPLY) {
                dirt_vec3 n = v3(a[0], a[1], a[2]);
                dirt_vec3 r = dirt_normal_map_apply(n, v3(a[4], a[5], a[6]), a[7],
                                                    v3(a[8], a[9], a[10]));
                if (i % 50 == 0) {
                    same = same_bits(o[0], n.x) && same_bits(o[1], n.y) && same_bits(o[2], n.z) &&
                           r.x == n.x && r.y == n.y && r.z == n.z;
                } else {
                    err = fmax(fabs(o[0] - r.x), fmax(fabs(o[1] - r.y), fabs(o[2] - r.z)));
                    same = err <= 1e-5;
                }
            } else {
                dirt_surface s;
                dirt_material_surface(m, 1.0f, g_tex, NUM_TEXTURES, a[2], a[3], &s);
                const float c[8] = {s.bsdf.base_color.x, s.bsdf.base_color.y,
                                    s.bsdf.base_color.z, s.bsdf.metallic, s.bsdf.alpha,
                                    s.emission.x, s.emission.y, s.emission.z};
                for (int k = 0; k < 8; k++) {
                    double e = fabs(o[k] - c[k]) / fmax(1.0, fabs(c[k]));
                    err = fmax(err, e);
                }
                same = err <= 2e-6;
            }
            worst = fmax(worst, err);
            if (!same) {
                if (report && bad < 5)
                    fprintf(stderr, "  mode %d record %d: gpu (%g %g %g %g), in (%g %g %g %g)\n",
                            mode, i, o[0], o[1], o[2], o[3], a[0], a[1], a[2], a[3]);
                bad++;
            }
        }
        if (report) {
            static const char *const names[] = {"slot uv", "normal_ts", "normal map apply",
                                                "surface"};
            fprintf(stderr, "%-16s %d of %d records differ, largest difference %.3g%s\n",
                    names[mode], bad, N, worst,
                    mode == MODE_NORMAL_TS ? "" : "");
            if (mode == MODE_NORMAL_TS)
                fprintf(stderr, "                 (%d records with a normal map)\n", ok_count);
            CHECK_MSG(bad == 0, "%s: %d records differ", names[mode], bad);
            if (mode == MODE_NORMAL_TS)
                CHECK(ok_count > N / 2);
        }
        bad_total += bad;
    }
    free(in);
    free(out);
    return bad_total;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    GLuint prog = gl_program_compute("integrator/test_nmap.comp", NULL, 0);
    glsl_define fault_def[] = {{"TEST_FAULT", "1"}};
    GLuint fault = gl_program_compute("integrator/test_nmap.comp", fault_def, 1);
    CHECK(prog && fault);
    make_tables();
    struct dirt_gpu_model_material recs[NUM_MATERIALS];
    dirt_gpu_materials_pack(g_mats, NUM_MATERIALS, NULL, NUM_TEXTURES, recs);
    dirt_gpu_texel_buffer tb = {0};
    CHECK(dirt_gpu_textures_pack(g_tex, NUM_TEXTURES, &tb));
    GLuint mats = gl_buffer_create(gpu, sizeof(recs), recs, false, "nmap test materials");
    gl_split texels = {0};
    CHECK(mats && dirt_gpu_textures_upload(gpu, &tb, &texels));
    if (prog && fault && mats && texels.buf[0]) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_MATERIALS, mats);
        gl_split_bind(&texels);
        compare(gpu, prog, true);
        int f = compare(gpu, fault, false);
        fprintf(stderr, "fault shader: %d of %d records differ\n", f, 4 * N);
        CHECK_MSG(f > 4 * N * 9 / 10, "the comparison does not catch a faulty shader (%d)", f);
    }
    gl_buffer_destroy(&mats);
    gl_split_release(&texels);
    dirt_gpu_texel_buffer_free(&tb);
    for (int t = 0; t < NUM_TEXTURES; t++)
        free(g_tex[t].rgba);
    gl_program_destroy(&prog);
    gl_program_destroy(&fault);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
