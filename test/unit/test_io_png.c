/* PNG previews: written through dirt_image_write_png / dirt_image_write,
 * decoded back with stb_image and compared with hand-computed sRGB bytes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "check.h"
#include "dirt/image.h"

static char g_dir[] = "/tmp/dirt_test_io_png.XXXXXX";

/* Linear inputs and the 8-bit sRGB value each must become with exposure 0
 * and the clamp tonemap: round(255 * (1.055 v^(1/2.4) - 0.055)), or
 * round(255 * 12.92 v) for v <= 0.0031308. */
static const struct { float linear; int srgb; } k_table[] = {
    {0.0f, 0}, {0.5f, 188}, {1.0f, 255}, {2.0f, 255}, {0.2f, 124},
    {0.05f, 63}, {0.001f, 3}, {0.0031308f, 10}, {0.18f, 118}, {0.75f, 225},
    {-1.0f, 0}, {1e30f, 255},
};
#define K_COUNT (int)(sizeof(k_table) / sizeof(k_table[0]))

/* Decodes `path`, checks size and channel count, returns the pixels. */
static unsigned char *load(const char *path, int w, int h, int comp)
{
    int lw = 0, lh = 0, lc = 0;
    unsigned char *px = stbi_load(path, &lw, &lh, &lc, 0);
    CHECK_MSG(px != NULL, "stbi_load(%s) failed", path);
    if (!px)
        return NULL;
    CHECK(lw == w && lh == h && lc == comp);
    if (lw != w || lh != h || lc != comp) {
        stbi_image_free(px);
        return NULL;
    }
    return px;
}

/* Pixel i of a 5-wide image takes table entry i for R, entry i+1 for G and
 * i+2 for B (wrapping), so channel order and row order both matter. */
static dirt_image *make_table_image(int w, int h)
{
    dirt_image *img = dirt_image_create(w, h);
    if (!img)
        return NULL;
    for (int i = 0; i < w * h; i++) {
        for (int c = 0; c < 3; c++)
            img->rgba[i * 4 + c] = k_table[(i + c) % K_COUNT].linear;
        img->rgba[i * 4 + 3] = (float)(i % 5) / 4.0f; /* 0, .25, .5, .75, 1 */
    }
    return img;
}

static void test_clamp_rgb(void)
{
    const int w = 5, h = 3; /* odd width: rows are not 4-byte aligned */
    char path[256];
    snprintf(path, sizeof(path), "%s/clamp.png", g_dir);
    dirt_image *img = make_table_image(w, h);
    CHECK(img != NULL);
    if (!img)
        return;
    CHECK(dirt_image_write_png(img, path, NULL));
    unsigned char *px = load(path, w, h, 3);
    if (px) {
        for (int i = 0; i < w * h; i++)
            for (int c = 0; c < 3; c++) {
                int want = k_table[(i + c) % K_COUNT].srgb;
                CHECK_MSG(px[i * 3 + c] == want,
                          "pixel %d channel %d: got %d want %d (linear %g)", i,
                          c, px[i * 3 + c], want,
                          (double)k_table[(i + c) % K_COUNT].linear);
            }
        stbi_image_free(px);
    }
    for (int i = 0; i < K_COUNT; i++)
        CHECK_MSG(dirt_linear_to_srgb8(k_table[i].linear) == k_table[i].srgb,
                  "srgb8(%g)", (double)k_table[i].linear);
    CHECK(dirt_linear_to_srgb8(NAN) == 0);
    CHECK(dirt_linear_to_srgb8(INFINITY) == 255);
    dirt_image_destroy(img);
    unlink(path);
}

static void test_alpha_and_dispatch(void)
{
    const int w = 5, h = 2;
    char path[256];
    snprintf(path, sizeof(path), "%s/alpha.PNG", g_dir); /* case-insensitive */
    dirt_image *img = make_table_image(w, h);
    CHECK(img != NULL);
    if (!img)
        return;
    dirt_image_write_options opts = {.png = {.alpha = true}};
    CHECK(dirt_image_write(img, path, &opts));
    unsigned char *px = load(path, w, h, 4);
    if (px) {
        static const int alpha[5] = {0, 64, 128, 191, 255}; /* round(255 a) */
        for (int i = 0; i < w * h; i++) {
            CHECK(px[i * 4 + 0] == k_table[i % K_COUNT].srgb);
            CHECK(px[i * 4 + 2] == k_table[(i + 2) % K_COUNT].srgb);
            CHECK_MSG(px[i * 4 + 3] == alpha[i % 5], "alpha %d: %d", i,
                      px[i * 4 + 3]);
        }
        stbi_image_free(px);
    }
    dirt_image_destroy(img);
    unlink(path);
}

/* One-pixel images through exposure and the tonemap curves. */
static int one_pixel(float v, const dirt_png_options *opts)
{
    char path[256];
    snprintf(path, sizeof(path), "%s/one.png", g_dir);
    dirt_image *img = dirt_image_create(1, 1);
    if (!img)
        return -1;
    img->rgba[0] = img->rgba[1] = img->rgba[2] = v;
    int got = -1;
    if (dirt_image_write_png(img, path, opts)) {
        unsigned char *px = load(path, 1, 1, 3);
        if (px) {
            got = px[0];
            CHECK(px[1] == px[0] && px[2] == px[0]);
            stbi_image_free(px);
        }
    }
    dirt_image_destroy(img);
    unlink(path);
    return got;
}

static void test_exposure_tonemap(void)
{
    dirt_png_options o = {0};
    CHECK(one_pixel(0.5f, &o) == 188);
    o.exposure = 1.0f; /* 0.25 * 2 = 0.5 */
    CHECK(one_pixel(0.25f, &o) == 188);
    o.exposure = -2.0f; /* 2.0 / 4 = 0.5 */
    CHECK(one_pixel(2.0f, &o) == 188);
    o.exposure = 0.0f;
    o.tonemap = DIRT_TONEMAP_REINHARD;
    CHECK(one_pixel(1.0f, &o) == 188); /* 1 / (1 + 1) = 0.5 */
    CHECK(one_pixel(3.0f, &o) == 225); /* 3 / 4 = 0.75 */
    o.tonemap = DIRT_TONEMAP_ACES;
    /* (x(2.51x+0.03)) / (x(2.43x+0.59)+0.14): x=1 -> 0.80380, x=4 -> 0.97342 */
    CHECK(one_pixel(1.0f, &o) == 232);
    CHECK(one_pixel(4.0f, &o) == 252);
    CHECK(one_pixel(0.0f, &o) == 0);
    o.tonemap = (enum dirt_tonemap)99;
    CHECK(one_pixel(0.5f, &o) == -1); /* rejected */
}

int main(void)
{
    if (!mkdtemp(g_dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_clamp_rgb();
    test_alpha_and_dispatch();
    test_exposure_tonemap();
    rmdir(g_dir);
    return check_finish();
}
