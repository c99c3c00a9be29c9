/* GLSL environment light == C (glsl/integrator/model.glsl against
 * src/integrator/env.c), through the table dirt_gpu_env_pack uploads, on
 * three maps: the built-in sky turned by 20 degrees (512 x 256, a sun of a
 * few texels), the constant map (1 x 1) and an odd 37 x 11 map with black
 * rows and columns (zero-weight texels: cells of the cdf of width 0) turned
 * by -100 degrees.
 * - Lookup (dirt_env_texel / _eval / _pdf) of 20,000 directions, uniform on
 *   the sphere, plus the poles, the axes and 360 directions on the
 *   map's column edges: the same texel, the same
 *   radiance bit for bit, the pdf within 1e-6 relative, for every one: the
 *   texel is decided by comparisons of the same floats on both sides (the
 *   column's atan2 guess corrected at its edges). Printed: how many
 *   directions lie within 1e-4 of a column edge (where the atan2 guess
 *   alone flipped texels: 1 in 12,288 camera rays of the odd map did).
 * - Sampling (dirt_env_sample) of 20,000 uniform triples: the same verdict
 *   and texel for every one (the texel choice compares the same floats),
 *   radiance bit for bit, the pdf within 1e-6 relative, the direction within
 *   1e-5 (GLSL's sin and cos).
 * - The shader built with TEST_FAULT (every result r -> 1.001 r + 0.01)
 *   fails these comparisons on nearly every record. */
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
#define MODE_LOOKUP 0
#define MODE_SAMPLE 1
#define PI 3.14159265358979323846

static uint32_t rng = 2463534242u;
static float urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return (float)(rng >> 8) * (1.0f / 16777216.0f);
}

/* Runs `prog` in `mode` over n records (2 vec4 in, 3 vec4 out each). */
static bool run(dirt_gpu *gpu, GLuint prog, int mode, const float *in, int n, float *out)
{
    return test_run_model_shader(gpu, prog, mode, in, 8, n, out, 12);
}

static bool rel_ok(float gpu, float c, double tol)
{
    return fabs((double)gpu - (double)c) <= tol * fabs((double)c) ||
           (c == 0.0f && gpu == 0.0f);
}

/* Distance of d's column coordinate to the nearest column edge, in
 * columns (the C formula in double). */
static double column_edge_distance(const dirt_env *env, dirt_vec3 d)
{
    double ex = env->rot_cos * d.x - env->rot_sin * d.z, ez = env->rot_sin * d.x + env->rot_cos * d.z;
    double x = (atan2(ex, -ez) + PI) / (2.0 * PI) * env->width;
    return fabs(x - floor(x + 0.5));
}

/* Compares one map; returns the number of failed records (fault runs
 * expect many). */
static int compare(dirt_gpu *gpu, GLuint prog, const dirt_env *env, const char *name, bool report)
{
    size_t size = 0;
    void *table = dirt_gpu_env_pack(env, 0, &size);
    GLuint buf = table ? gl_buffer_create(gpu, size, table, false, "env test table") : 0;
    free(table);
    CHECK(buf != 0);
    if (!buf)
        return N;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_ENV, buf);
    float *in = calloc((size_t)N * 8, sizeof(float)), *out = calloc((size_t)N * 12, sizeof(float));
    int bad = 0, edge = 0;
    /* Lookup. */
    for (int i = 0; i < N; i++) {
        dirt_vec3 d;
        if (i < 6) {
            float axes[6][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
            d = v3(axes[i][0], axes[i][1], axes[i][2]);
        } else if (i < 6 + 40 * 9) {
            /* On the column edges of the map (up to the rounding of the
             * float direction), at 9 heights. */
            int k = (i - 6) / 9, m = (i - 6) % 9;
            double phi = 2.0 * PI * (k % (env->width + 1)) / env->width - PI,
                   z = -0.8 + 0.2 * m;
            double rot = atan2(env->rot_sin, env->rot_cos), s = sqrt(1.0 - z * z);
            double ex = s * sin(phi), ez = -s * cos(phi);
            d = v3((float)(cos(rot) * ex + sin(rot) * ez), (float)z,
                   (float)(-sin(rot) * ex + cos(rot) * ez));
        } else {
            float z = 1.0f - 2.0f * urand(), phi = 2.0f * (float)PI * urand();
            float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
            d = v3_normalize(v3(s * cosf(phi), z, s * sinf(phi)));
        }
        in[8 * i] = d.x, in[8 * i + 1] = d.y, in[8 * i + 2] = d.z;
    }
    CHECK(run(gpu, prog, MODE_LOOKUP, in, N, out));
    for (int i = 0; i < N; i++) {
        dirt_vec3 d = v3(in[8 * i], in[8 * i + 1], in[8 * i + 2]);
        const float *o = &out[12 * i];
        int col, row;
        dirt_env_texel(env, d, &col, &row);
        dirt_vec3 e = dirt_env_eval(env, d);
        float pdf = dirt_env_pdf(env, d);
        bool same = o[0] == (float)col && o[1] == (float)row && rel_ok(o[2], pdf, 1e-6) &&
                    o[4] == e.x && o[5] == e.y && o[6] == e.z;
        edge += column_edge_distance(env, d) < 1e-4;
        if (same)
            continue;
        if (report && bad < 5)
            fprintf(stderr, "  %s lookup %d: gpu (%g %g) pdf %g, C (%d %d) pdf %g\n", name, i,
                    o[0], o[1], o[2], col, row, pdf);
        bad++;
    }
    /* Sampling. */
    for (int i = 0; i < N; i++) {
        in[8 * i] = urand(), in[8 * i + 1] = urand(), in[8 * i + 2] = urand();
    }
    CHECK(run(gpu, prog, MODE_SAMPLE, in, N, out));
    int sampled = 0;
    for (int i = 0; i < N; i++) {
        const float *o = &out[12 * i];
        dirt_vec3 d = {0}, rad = {0};
        float pdf = 0.0f;
        bool ok = dirt_env_sample(env, in[8 * i], in[8 * i + 1], in[8 * i + 2], &d, &pdf, &rad);
        sampled += ok;
        bool same = o[0] == (ok ? 1.0f : 0.0f);
        if (same && ok)
            same = rel_ok(o[1], pdf, 1e-6) && fabsf(o[4] - d.x) <= 1e-5f &&
                   fabsf(o[5] - d.y) <= 1e-5f && fabsf(o[6] - d.z) <= 1e-5f && o[8] == rad.x &&
                   o[9] == rad.y && o[10] == rad.z;
        if (!same) {
            if (report && bad < 5)
                fprintf(stderr, "  %s sample %d: gpu ok %g pdf %g dir %g %g %g, C ok %d pdf %g "
                        "dir %g %g %g\n", name, i, o[0], o[1], o[4], o[5], o[6], ok, pdf, d.x,
                        d.y, d.z);
            bad++;
        }
    }
    if (report) {
        fprintf(stderr, "%-10s %dx%d: %d of %d lookups and %d samples (%d drawn) differ, "
                "%d lookups within 1e-4 of a column edge\n", name, env->width, env->height, bad,
                N, N, sampled, edge);
        CHECK_MSG(bad == 0, "%s: %d records differ", name, bad);
        CHECK(sampled > N / 2);
    }
    free(in);
    free(out);
    gl_buffer_destroy(&buf);
    return bad;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    GLuint prog = gl_program_compute("integrator/test_env.comp", NULL, 0);
    glsl_define fault_def[] = {{"TEST_FAULT", "1"}};
    GLuint fault = gl_program_compute("integrator/test_env.comp", fault_def, 1);
    CHECK(prog && fault);
    dirt_env *sky = dirt_env_sky(&(dirt_env_opts){.rotation = 20.0f});
    float c[3] = {0.3f, 0.6f, 0.9f};
    dirt_env *one = dirt_env_constant(c);
    enum { W = 37, H = 11 };
    float *rgb = malloc(W * H * 3 * sizeof(float));
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            for (int k = 0; k < 3; k++)
                rgb[3 * (j * W + i) + k] = (j == 4 || i % 9 == 0) ? 0.0f
                                           : urand() * (i == 30 && j == 2 ? 500.0f : 2.0f);
    dirt_env *odd = dirt_env_create(rgb, W, H, &(dirt_env_opts){.rotation = -100.0f});
    CHECK(sky && one && odd);
    if (prog && fault && sky && one && odd) {
        compare(gpu, prog, sky, "sky", true);
        compare(gpu, prog, one, "constant", true);
        compare(gpu, prog, odd, "odd", true);
        int f = compare(gpu, fault, odd, "fault", false);
        fprintf(stderr, "fault shader: %d of %d records differ\n", f, 2 * N);
        CHECK_MSG(f > 2 * N * 9 / 10, "the comparison does not catch a faulty shader (%d)", f);
    }
    dirt_env_destroy(sky);
    dirt_env_destroy(one);
    dirt_env_destroy(odd);
    free(rgb);
    gl_program_destroy(&prog);
    gl_program_destroy(&fault);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
