/* Drawing images into the window (dirt/window.h), read back with
 * dirt_gpu_window_read (run under xvfb-run by test_gl_window.sh):
 *  (a) COLOR mode, 1:1, every tone map with exposure -1, 0 and +1: each pixel
 *      is the byte dirt_image_write_png stores (the expected bytes come from
 *      the PNG writer itself, decoded again, and from the curve computed
 *      here with dirt_linear_to_srgb8); a difference of 1 is allowed only
 *      where 255 * srgb(v) lies within 1e-3 of a rounding boundary;
 *  (b) placement: a sub-rectangle shows texel (i, j) at window pixel
 *      (x + i, y + j) from the top left, scaled rectangles show texel
 *      floor(i * tex_w / w), and every pixel outside keeps the clear colour;
 *  (c) HEAT (non-finite values black), SIGNED, DIFF, and a split at a known
 *      column with and without its line;
 * plus: the GL state a present changes is restored, textures work on a
 * headless GPU, where the window functions refuse. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "check.h"
#include "common/display.h"
#include "dirt/image.h"
#include "gl/window.h"
#include "gl/gl.h"
#include "gpu.h"

#define WIN_W 64
#define WIN_H 32

/* ---- the CPU side: png.c's and debug.c's math, from the shared constants ---- */

static float cpu_tonemap(float x, enum dirt_tonemap op)
{
    switch (op) {
    case DIRT_TONEMAP_REINHARD:
        return x > 0.0f ? x / (1.0f + x) : 0.0f;
    case DIRT_TONEMAP_ACES:
        if (!(x > 0.0f))
            return 0.0f;
        return (x * (DIRT_ACES_A * x + DIRT_ACES_B)) /
               (x * (DIRT_ACES_C * x + DIRT_ACES_D) + DIRT_ACES_E);
    default:
        return x;
    }
}

static void cpu_heat(float x, float rgb[3])
{
    static const float keys[DIRT_HEAT_KEYS][3] = {{DIRT_HEAT_KEY_0}, {DIRT_HEAT_KEY_1},
                                                  {DIRT_HEAT_KEY_2}, {DIRT_HEAT_KEY_3},
                                                  {DIRT_HEAT_KEY_4}};
    x = fminf(fmaxf(x, 0), 1) * (DIRT_HEAT_KEYS - 1);
    int i = (int)x < DIRT_HEAT_KEYS - 1 ? (int)x : DIRT_HEAT_KEYS - 2;
    float t = x - (float)i;
    for (int k = 0; k < 3; k++)
        rgb[k] = keys[i][k] + t * (keys[i + 1][k] - keys[i][k]);
}

/* Whether 255 * srgb(v) is within 1e-3 of a rounding boundary (k + 0.5):
 * there the GPU's pow may round the other way. */
static bool near_boundary(float v)
{
    if (!(v > 0.0f) || v >= 1.0f)
        return false;
    float s = v <= DIRT_SRGB_LINEAR_MAX
                  ? DIRT_SRGB_LINEAR_SCALE * v
                  : DIRT_SRGB_SCALE * powf(v, DIRT_SRGB_EXPONENT) - DIRT_SRGB_OFFSET;
    double f = (double)s * 255.0;
    return fabs(f - floor(f) - 0.5) < 1e-3;
}

/* ---- comparing ---- */

typedef struct tally {
    int pixels, exact, off_by_one, wrong;
} tally;

/* One window pixel against the linear values `lin` (already exposed and
 * tone mapped: what dirt_linear_to_srgb8 takes). */
static void expect(tally *t, const uint8_t *got, const float lin[3], const char *what, int x,
                   int y)
{
    t->pixels++;
    bool bad = false, lsb = false;
    for (int c = 0; c < 3; c++) {
        int want = dirt_linear_to_srgb8(lin[c]);
        int d = abs((int)got[c] - want);
        if (d == 0)
            continue;
        if (d == 1 && near_boundary(lin[c]))
            lsb = true;
        else
            bad = true;
    }
    if (bad) {
        if (t->wrong++ < 8)
            fprintf(stderr, "%s: pixel (%d, %d) = %d %d %d, want %d %d %d (linear %g %g %g)\n",
                    what, x, y, got[0], got[1], got[2], dirt_linear_to_srgb8(lin[0]),
                    dirt_linear_to_srgb8(lin[1]), dirt_linear_to_srgb8(lin[2]),
                    (double)lin[0], (double)lin[1], (double)lin[2]);
    } else if (lsb) {
        t->off_by_one++;
    } else {
        t->exact++;
    }
}

static bool same_rgb(const uint8_t *a, const uint8_t *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static const uint8_t *px(const uint8_t *fb, int x, int y)
{
    return fb + ((size_t)y * WIN_W + (size_t)x) * 4;
}

/* Clear colour k / 255 exactly, so its bytes are known. */
static const float k_clear[3] = {32.0f / 255.0f, 64.0f / 255.0f, 96.0f / 255.0f};
static const uint8_t k_clear8[3] = {32, 64, 96};

static bool present_and_read(dirt_gpu *gpu, const dirt_present_opts *o, uint8_t *fb)
{
    bool ok = dirt_gpu_window_clear(gpu, k_clear);
    ok = dirt_gpu_present(gpu, o) && ok;
    ok = dirt_gpu_window_read(gpu, fb, WIN_W, WIN_H) && ok;
    CHECK(ok);
    return ok;
}

/* ---- test images ---- */

static uint32_t g_seed = 12345u;
static float rnd(void)
{
    g_seed = g_seed * 1664525u + 1013904223u;
    return (float)(g_seed >> 8) / 16777216.0f;
}

/* WIN_W x WIN_H pixels: special values first, then a spread over [0, 8). */
static float *color_image(void)
{
    static const float special[] = {
        0.0f, -0.0f, 1e-6f, 1e-4f, 0.001f, 0.002f, 0.0031308f, 0.0032f, 0.01f, 0.05f,
        0.1f, 0.18f, 0.2f, 0.214f, 0.5f, 0.75f, 0.9f, 0.99f, 0.999f, 1.0f, 1.001f, 1.5f,
        2.0f, 3.7f, 4.0f, 10.0f, 100.0f, 1000.0f, -0.5f, -1.0f, -100.0f, NAN, -NAN, INFINITY,
        -INFINITY,
    };
    const size_t n_special = sizeof(special) / sizeof(special[0]);
    float *img = malloc(sizeof(float) * 4 * WIN_W * WIN_H);
    for (size_t i = 0; i < (size_t)WIN_W * WIN_H; i++) {
        for (int c = 0; c < 3; c++) {
            size_t k = i * 3 + (size_t)c;
            img[i * 4 + (size_t)c] = k < 3 * n_special ? special[(k / 3 + (size_t)c * 7) % n_special]
                                                       : 8.0f * rnd() * rnd();
        }
        img[i * 4 + 3] = 1.0f;
    }
    return img;
}

/* ---- (a) COLOR against the PNG writer ---- */

static void test_color(dirt_gpu *gpu, uint8_t *fb)
{
    float *img = color_image();
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, WIN_W, WIN_H, img);
    CHECK(tex != 0);
    dirt_image *im = dirt_image_create(WIN_W, WIN_H);
    memcpy(im->rgba, img, sizeof(float) * 4 * WIN_W * WIN_H);
    char dir[] = "/tmp/dirt_test_present.XXXXXX", path[64];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof(path), "%s/color.png", dir);
    static const enum dirt_tonemap ops[] = {DIRT_TONEMAP_CLAMP, DIRT_TONEMAP_REINHARD,
                                            DIRT_TONEMAP_ACES};
    static const float exposures[] = {-1.0f, 0.0f, 1.0f};
    tally all = {0};
    for (int o = 0; o < 3; o++) {
        for (int e = 0; e < 3; e++) {
            dirt_present_opts po = {.texture = tex, .w = WIN_W, .h = WIN_H,
                                    .mode = DIRT_PRESENT_COLOR, .exposure = exposures[e],
                                    .tonemap = ops[o]};
            if (!present_and_read(gpu, &po, fb))
                continue;
            /* The PNG writer's own bytes, decoded again. */
            dirt_png_options pngo = {.exposure = exposures[e], .tonemap = ops[o]};
            CHECK(dirt_image_write_png(im, path, &pngo));
            int lw = 0, lh = 0, lc = 0;
            unsigned char *png = stbi_load(path, &lw, &lh, &lc, 3);
            CHECK(png && lw == WIN_W && lh == WIN_H);
            char what[64];
            snprintf(what, sizeof(what), "COLOR tonemap %d exposure %g", (int)ops[o],
                     (double)exposures[e]);
            const float scale = exp2f(exposures[e]);
            tally t = {0};
            int png_mismatch = 0;
            for (int y = 0; y < WIN_H; y++) {
                for (int x = 0; x < WIN_W; x++) {
                    const float *src = img + ((size_t)y * WIN_W + (size_t)x) * 4;
                    float lin[3];
                    for (int c = 0; c < 3; c++)
                        lin[c] = cpu_tonemap(src[c] * scale, ops[o]);
                    expect(&t, px(fb, x, y), lin, what, x, y);
                    for (int c = 0; png && c < 3; c++)
                        if (png[((size_t)y * WIN_W + (size_t)x) * 3 + (size_t)c] !=
                            dirt_linear_to_srgb8(lin[c]))
                            png_mismatch++;
                }
            }
            CHECK_MSG(t.wrong == 0, "%s: %d of %d pixels wrong", what, t.wrong, t.pixels);
            CHECK_MSG(png_mismatch == 0, "%s: this test's curve differs from png.c's in %d "
                      "values", what, png_mismatch);
            all.pixels += t.pixels, all.exact += t.exact, all.off_by_one += t.off_by_one;
            stbi_image_free(png);
        }
    }
    fprintf(stderr, "COLOR: %d pixels, %d exact, %d off by one at a rounding boundary\n",
            all.pixels, all.exact, all.off_by_one);
    /* The boundary allowance is rare: most pixels are exact. */
    CHECK(all.exact >= all.pixels * 9 / 10);
    remove(path);
    rmdir(dir);
    dirt_image_destroy(im);
    dirt_gpu_texture_destroy(gpu, tex);
    free(img);
}

/* ---- (b) placement ---- */

/* A tw x th image whose texel (i, j) has a distinct value in (0, 1). */
static float *ramp_image(int tw, int th)
{
    float *img = malloc(sizeof(float) * 4 * (size_t)tw * (size_t)th);
    for (int j = 0; j < th; j++)
        for (int i = 0; i < tw; i++) {
            float *p = img + ((size_t)j * (size_t)tw + (size_t)i) * 4;
            p[0] = (float)(i + 1) / (float)(tw + 1);
            p[1] = (float)(j + 1) / (float)(th + 1);
            p[2] = 0.5f;
            p[3] = 1.0f;
        }
    return img;
}

static void check_rect(dirt_gpu *gpu, uint8_t *fb, int tw, int th, int rx, int ry, int rw,
                       int rh)
{
    float *img = ramp_image(tw, th);
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, tw, th, img);
    CHECK(tex != 0);
    dirt_present_opts po = {.texture = tex, .x = rx, .y = ry, .w = rw, .h = rh};
    if (present_and_read(gpu, &po, fb)) {
        char what[96];
        snprintf(what, sizeof(what), "%dx%d image in %dx%d at (%d, %d)", tw, th, rw, rh, rx, ry);
        tally t = {0};
        int outside_wrong = 0;
        for (int y = 0; y < WIN_H; y++) {
            for (int x = 0; x < WIN_W; x++) {
                bool in = x >= rx && x < rx + rw && y >= ry && y < ry + rh;
                if (!in) {
                    if (!same_rgb(px(fb, x, y), k_clear8) && outside_wrong++ < 4)
                        fprintf(stderr, "%s: pixel (%d, %d) outside = %d %d %d\n", what, x, y,
                                px(fb, x, y)[0], px(fb, x, y)[1], px(fb, x, y)[2]);
                    continue;
                }
                int i = (x - rx) * tw / rw, j = (y - ry) * th / rh;
                const float *p = img + ((size_t)j * (size_t)tw + (size_t)i) * 4;
                expect(&t, px(fb, x, y), p, what, x, y);
            }
        }
        CHECK_MSG(t.wrong == 0, "%s: %d pixels inside wrong", what, t.wrong);
        CHECK_MSG(outside_wrong == 0, "%s: %d pixels outside not the clear colour", what,
                  outside_wrong);
    }
    dirt_gpu_texture_destroy(gpu, tex);
    free(img);
}

static void test_placement(dirt_gpu *gpu, uint8_t *fb)
{
    check_rect(gpu, fb, 8, 4, 5, 3, 8, 4);     /* 1:1 in a corner of the window */
    check_rect(gpu, fb, 8, 4, 40, 20, 16, 8);  /* magnified 2x */
    check_rect(gpu, fb, 7, 5, 1, 2, 20, 13);   /* magnified, not a whole ratio */
    check_rect(gpu, fb, 64, 32, 10, 6, 16, 9); /* minified */
    check_rect(gpu, fb, 8, 4, 60, 30, 8, 4);   /* cut by the window's corner */
    /* Bad rectangles and textures are refused. */
    float one[4] = {1, 1, 1, 1};
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, 1, 1, one);
    CHECK(!dirt_gpu_present(gpu, &(dirt_present_opts){.texture = tex, .w = 0, .h = 4}));
    CHECK(!dirt_gpu_present(gpu, &(dirt_present_opts){.texture = 0, .w = 4, .h = 4}));
    CHECK(!dirt_gpu_present(gpu, &(dirt_present_opts){.texture = tex, .w = 4, .h = 4,
                                                      .split = 0.5f}));
    CHECK(!dirt_gpu_present(gpu, &(dirt_present_opts){.texture = tex, .w = 4, .h = 4,
                                                      .mode = DIRT_PRESENT_HEAT, .lo = 1,
                                                      .hi = 1}));
    /* Updates in place keep the name; a new size replaces the texture. */
    uint32_t same = dirt_gpu_texture_upload(gpu, tex, 1, 1, one);
    CHECK(same == tex);
    float four[16] = {0};
    uint32_t other = dirt_gpu_texture_upload(gpu, same, 2, 2, four);
    CHECK(other != 0);
    dirt_gpu_texture_destroy(gpu, other);
}

/* ---- (c) the other modes and the split ---- */

static void test_heat_signed(dirt_gpu *gpu, uint8_t *fb)
{
    float *img = malloc(sizeof(float) * 4 * WIN_W * WIN_H);
    const float lo = -2.0f, hi = 6.0f;
    for (int i = 0; i < WIN_W * WIN_H; i++) {
        float *p = img + (size_t)i * 4;
        /* channel 1 sweeps beyond both ends of lo..hi */
        p[0] = 2.0f * rnd() - 1.0f;
        p[1] = lo - 1.0f + (hi - lo + 2.0f) * (float)i / (float)(WIN_W * WIN_H - 1);
        p[2] = 2.0f * rnd() - 1.0f;
        p[3] = rnd();
    }
    img[4 * 5 + 1] = INFINITY;
    img[4 * 6 + 1] = -INFINITY;
    img[4 * 7 + 1] = NAN;
    img[4 * 8 + 0] = NAN;
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, WIN_W, WIN_H, img);
    CHECK(tex != 0);

    dirt_present_opts po = {.texture = tex, .w = WIN_W, .h = WIN_H, .mode = DIRT_PRESENT_HEAT,
                            .channel = 1, .lo = lo, .hi = hi};
    if (present_and_read(gpu, &po, fb)) {
        tally t = {0};
        for (int y = 0; y < WIN_H; y++)
            for (int x = 0; x < WIN_W; x++) {
                float v = img[((size_t)y * WIN_W + (size_t)x) * 4 + 1], rgb[3] = {0, 0, 0};
                if (isfinite(v))
                    cpu_heat((v - lo) / (hi - lo), rgb);
                expect(&t, px(fb, x, y), rgb, "HEAT", x, y);
            }
        CHECK_MSG(t.wrong == 0, "HEAT: %d pixels wrong", t.wrong);
        const uint8_t black[3] = {0, 0, 0};
        CHECK(same_rgb(px(fb, 5, 0), black) && same_rgb(px(fb, 6, 0), black) &&
              same_rgb(px(fb, 7, 0), black));
        /* The hottest pixel (past hi) is white. */
        const uint8_t white[3] = {255, 255, 255};
        CHECK(same_rgb(px(fb, WIN_W - 1, WIN_H - 1), white));
    }
    po.mode = DIRT_PRESENT_SIGNED;
    if (present_and_read(gpu, &po, fb)) {
        tally t = {0};
        for (int y = 0; y < WIN_H; y++)
            for (int x = 0; x < WIN_W; x++) {
                const float *p = img + ((size_t)y * WIN_W + (size_t)x) * 4;
                float lin[3] = {p[0] * 0.5f + 0.5f, p[1] * 0.5f + 0.5f, p[2] * 0.5f + 0.5f};
                expect(&t, px(fb, x, y), lin, "SIGNED", x, y);
            }
        CHECK_MSG(t.wrong == 0, "SIGNED: %d pixels wrong", t.wrong);
    }
    dirt_gpu_texture_destroy(gpu, tex);
    free(img);
}

static float lum(const float *p)
{
    return DIRT_LUMA_R * p[0] + DIRT_LUMA_G * p[1] + DIRT_LUMA_B * p[2];
}

static void test_diff_split(dirt_gpu *gpu, uint8_t *fb)
{
    size_t n = (size_t)WIN_W * WIN_H;
    float *a = malloc(sizeof(float) * 4 * n), *b = malloc(sizeof(float) * 4 * n);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 4; c++) {
            a[i * 4 + (size_t)c] = rnd();
            b[i * 4 + (size_t)c] = c < 3 ? 2.0f * rnd() : 1.0f;
        }
    a[0] = INFINITY; /* inf - finite: not finite, black */
    uint32_t ta = dirt_gpu_texture_upload(gpu, 0, WIN_W, WIN_H, a);
    uint32_t tb = dirt_gpu_texture_upload(gpu, 0, WIN_W, WIN_H, b);
    CHECK(ta && tb);

    const float lo = 0.0f, hi = 1.5f;
    dirt_present_opts po = {.texture = ta, .texture_b = tb, .w = WIN_W, .h = WIN_H,
                            .mode = DIRT_PRESENT_DIFF, .lo = lo, .hi = hi};
    if (present_and_read(gpu, &po, fb)) {
        tally t = {0};
        int boundary = 0;
        for (int y = 0; y < WIN_H; y++)
            for (int x = 0; x < WIN_W; x++) {
                size_t i = ((size_t)y * WIN_W + (size_t)x) * 4;
                float d = fabsf(lum(a + i) - lum(b + i)), rgb[3] = {0, 0, 0};
                if (isfinite(d))
                    cpu_heat((d - lo) / (hi - lo), rgb);
                /* The luminance's sum may be evaluated in another order on the
                 * GPU: skip pixels whose heat sits on a rounding edge of it. */
                float eps = 1e-6f * (hi - lo), r1[3], r2[3];
                cpu_heat((d - eps - lo) / (hi - lo), r1);
                cpu_heat((d + eps - lo) / (hi - lo), r2);
                bool edge = false;
                for (int c = 0; c < 3 && isfinite(d); c++)
                    edge = edge || dirt_linear_to_srgb8(r1[c]) != dirt_linear_to_srgb8(r2[c]);
                if (edge) {
                    boundary++;
                    continue;
                }
                expect(&t, px(fb, x, y), rgb, "DIFF", x, y);
            }
        CHECK_MSG(t.wrong == 0, "DIFF: %d pixels wrong", t.wrong);
        CHECK(boundary < WIN_W * WIN_H / 20);
        const uint8_t black[3] = {0, 0, 0};
        CHECK(same_rgb(px(fb, 0, 0), black));
    }

    /* Splits: at 0.25 of 64 (x = 16) and at 0.3 (x = 19.2, inside column 19),
     * in a rectangle starting at x = 0 and in one starting at x = 8. */
    static const struct { float split; int x0, w, first_b; bool line; } splits[] = {
        {0.25f, 0, 64, 16, false}, {0.25f, 0, 64, 16, true},
        {0.3f, 0, 64, 19, true},   {0.3f, 0, 64, 19, false}, {0.5f, 8, 48, 32, true},
    };
    for (size_t s = 0; s < sizeof(splits) / sizeof(splits[0]); s++) {
        dirt_present_opts sp = {.texture = ta, .texture_b = tb, .x = splits[s].x0,
                                .w = splits[s].w, .h = WIN_H, .mode = DIRT_PRESENT_COLOR,
                                .split = splits[s].split, .split_line = splits[s].line};
        if (!present_and_read(gpu, &sp, fb))
            continue;
        int line_x = (int)floorf((float)splits[s].x0 + splits[s].split * (float)splits[s].w);
        char what[64];
        snprintf(what, sizeof(what), "split %g line %d", (double)splits[s].split,
                 (int)splits[s].line);
        tally t = {0};
        int line_wrong = 0, outside_wrong = 0;
        const uint8_t white[3] = {255, 255, 255};
        for (int y = 0; y < WIN_H; y++)
            for (int x = 0; x < WIN_W; x++) {
                int lx = x - splits[s].x0;
                if (lx < 0 || lx >= splits[s].w) {
                    outside_wrong += !same_rgb(px(fb, x, y), k_clear8);
                    continue;
                }
                if (splits[s].line && x == line_x) {
                    line_wrong += !same_rgb(px(fb, x, y), white);
                    continue;
                }
                int tx = lx * WIN_W / splits[s].w;
                const float *src = (x >= splits[s].first_b ? b : a) +
                                   ((size_t)y * WIN_W + (size_t)tx) * 4;
                float lin[3] = {src[0], src[1], src[2]};
                expect(&t, px(fb, x, y), lin, what, x, y);
            }
        CHECK_MSG(t.wrong == 0, "%s: %d pixels wrong", what, t.wrong);
        CHECK_MSG(line_wrong == 0, "%s: %d line pixels not white", what, line_wrong);
        CHECK_MSG(outside_wrong == 0, "%s: %d pixels outside changed", what, outside_wrong);
    }
    dirt_gpu_texture_destroy(gpu, ta);
    dirt_gpu_texture_destroy(gpu, tb);
    free(a);
    free(b);
}

/* ---- GL state and the headless GPU ---- */

static void test_state_restored(dirt_gpu *gpu, uint8_t *fb)
{
    float one[4] = {0.5f, 0.5f, 0.5f, 1};
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, 1, 1, one);
    GLuint vao = 0, fbo_tex = 0, fbo = 0;
    glCreateVertexArrays(1, &vao);
    glCreateTextures(GL_TEXTURE_2D, 1, &fbo_tex);
    glTextureStorage2D(fbo_tex, 1, GL_RGBA8, 4, 4);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, fbo_tex, 0);
    glBindVertexArray(vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(1, 2, 3, 4);
    glEnable(GL_BLEND);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    glBindTextureUnit(0, fbo_tex);
    CHECK(dirt_gpu_present(gpu, &(dirt_present_opts){.texture = tex, .w = 4, .h = 4}));
    GLint v[4] = {0}, prog = -1, bound_vao = 0, draw_fb = 0, unit0 = 0;
    glGetIntegerv(GL_VIEWPORT, v);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &bound_vao);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0);
    CHECK(v[0] == 1 && v[1] == 2 && v[2] == 3 && v[3] == 4);
    CHECK(prog == 0);
    CHECK(bound_vao == (GLint)vao);
    CHECK(draw_fb == (GLint)fbo);
    CHECK(unit0 == (GLint)fbo_tex);
    CHECK(glIsEnabled(GL_BLEND) && glIsEnabled(GL_SCISSOR_TEST));
    /* The present went to the window despite the bound framebuffer and the
     * scissor box; the clear too. */
    CHECK(dirt_gpu_window_read(gpu, fb, WIN_W, WIN_H));
    const uint8_t grey[3] = {188, 188, 188}; /* srgb8(0.5) */
    CHECK(same_rgb(px(fb, 2, 2), grey));
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glBindTextureUnit(0, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &fbo_tex);
    glDeleteVertexArrays(1, &vao);
    dirt_gpu_texture_destroy(gpu, tex);
    /* A read of the wrong size is refused. */
    CHECK(!dirt_gpu_window_read(gpu, fb, WIN_W - 1, WIN_H));
}

static void test_headless(void)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){0});
    if (!gpu) {
        CHECK_MSG(!test_in_ci(), "CI=true: no headless context");
        return;
    }
    float img[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    uint32_t tex = dirt_gpu_texture_upload(gpu, 0, 2, 1, img);
    CHECK(tex != 0);
    float back[8] = {0};
    CHECK(gl_texture_read_rgba32f(tex, 2, 1, back));
    CHECK(memcmp(back, img, sizeof(img)) == 0);
    uint8_t fb[4];
    dirt_window_input in;
    CHECK(!dirt_gpu_present(gpu, &(dirt_present_opts){.texture = tex, .w = 1, .h = 1}));
    CHECK(!dirt_gpu_window_clear(gpu, k_clear));
    CHECK(!dirt_gpu_window_read(gpu, fb, 1, 1));
    CHECK(!dirt_gpu_window_input(gpu, &in));
    CHECK(!dirt_gpu_window_set_title(gpu, "x"));
    CHECK(!dirt_gpu_window_set_size(gpu, 10, 10));
    dirt_gpu_texture_destroy(gpu, tex);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
}

int main(void)
{
    test_headless();
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = WIN_W,
                                                     .height = WIN_H, .title = "dirt present"});
    if (!gpu) {
        fprintf(stderr, "no window system: skipping\n");
        return TEST_SKIP;
    }
    int w = 0, h = 0;
    dirt_gpu_window_size(gpu, &w, &h);
    CHECK(w == WIN_W && h == WIN_H);
    if (w != WIN_W || h != WIN_H) {
        dirt_gpu_destroy(gpu);
        return check_finish();
    }
    uint8_t *fb = malloc((size_t)WIN_W * WIN_H * 4);
    test_color(gpu, fb);
    test_placement(gpu, fb);
    test_heat_signed(gpu, fb);
    test_diff_split(gpu, fb);
    test_state_restored(gpu, fb);
    dirt_gpu_window_swap(gpu);
    dirt_gpu_window_poll(gpu);
    free(fb);
    CHECK_MSG(dirt_gpu_error_count(gpu) == 0, "%llu GL errors",
              (unsigned long long)dirt_gpu_error_count(gpu));
    dirt_gpu_destroy(gpu);
    return check_finish();
}
