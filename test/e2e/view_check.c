/* dirt-view's image checks for test_view.sh.
 *   view_check same A.exr B.exr
 *       the RGBA and every channel of A equal B's, bit for bit
 *   view_check window SHOT.png RENDER.png REPORT.json
 *       SHOT (the window, panels included) equals RENDER (the render alone,
 *       written by the same tone map) at every pixel no panel of REPORT
 *       covers, within the one 8-bit step a GPU's and the CPU's float
 *       pow/rounding may differ by (and exactly at 99% of them or more);
 *       inside the panels, most pixels differ from the render.
 *   view_check window SHOT.png RENDER.png REPORT.json collapsed
 *       the same, but the panels may be collapsed title bars, which are
 *       translucent and may equal the render (a dark background) inside.
 *   view_check heat SHOT.png IMAGE.exr
 *       SHOT (the depth buffer shown without panels) is the heat ramp of
 *       IMAGE's "Z" over its finite range (misses black), sRGB-encoded,
 *       within one 8-bit step (exactly at 99% of the pixels or more).
 *   view_check split SHOT.png A.exr B.exr
 *       SHOT (a split view without panels, split at 0.5) shows A left of
 *       the middle column, a white line in it, and B right of it, each as
 *       its PNG (exposure 0, clamp), within one 8-bit step (exactly at 99%
 *       of the pixels or more on each side)
 *   view_check diff SHOT.png A.exr B.exr RANGE
 *       SHOT is the heat ramp of |luminance(A) - luminance(B)| over
 *       0..RANGE, sRGB-encoded, within one 8-bit step (exactly at 99%)
 *   view_check zoom SHOT.png RENDER.png X0 Y0 Z
 *       SHOT (a zoomed window without panels) shows RENDER (a PNG of the
 *       render) at Z window pixels per render pixel with its top left at
 *       window pixel (X0, Y0): every window pixel equals the render pixel
 *       floor((p - X0) / Z) within one 8-bit step (exactly at 99% or more),
 *       each Z x Z block of the window is one colour exactly, and the
 *       window lies inside the image
 *   view_check ramp SHOT.png X Y W H
 *       SHOT's rectangle X, Y, W, H (a colour bar) has in column i the heat
 *       ramp at (i + 0.5) / W, sRGB-encoded as the present shader shows it
 *       (glsl/common/display.h's keys), exactly, in every row
 *   view_check pngs A.png B.png same|negative
 *       B equals A at every pixel (RGB), or is its negative (255 - A)
 *   view_check pixel IMAGE.exr CHANNEL X Y
 *       prints the value of CHANNEL (R, G, B, A: the beauty's) at pixel (X, Y)
 *       (row 0 = top), %.9g
 * Prints what it found; exit 0 when the condition holds, 1 when it does
 * not, 2 on unreadable input. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>
#include <stb_image.h>

#include "common/display.h"
#include "dirt/image.h"

static int same(const char *a_path, const char *b_path)
{
    dirt_image *a = dirt_image_read_exr(a_path), *b = dirt_image_read_exr(b_path);
    int rc = 2;
    if (!a || !b)
        goto done;
    rc = 1;
    if (a->width != b->width || a->height != b->height) {
        printf("sizes differ: %dx%d vs %dx%d\n", a->width, a->height, b->width, b->height);
        goto done;
    }
    size_t n = (size_t)a->width * a->height;
    size_t diff = 0;
    for (size_t i = 0; i < 4 * n; i++)
        diff += memcmp(&a->rgba[i], &b->rgba[i], sizeof(float)) != 0;
    int channels = 0;
    for (int c = 0; c < b->channel_count; c++) {
        const float *pa = dirt_image_find_channel(a, b->channels[c].name);
        if (!pa) {
            printf("%s lacks channel %s\n", a_path, b->channels[c].name);
            diff++;
            continue;
        }
        channels++;
        for (size_t i = 0; i < n; i++)
            diff += memcmp(&pa[i], &b->channels[c].data[i], sizeof(float)) != 0;
    }
    printf("%dx%d, RGBA + %d channels: %zu values differ\n", a->width, a->height, channels, diff);
    rc = diff == 0 && a->channel_count == b->channel_count ? 0 : 1;
done:
    dirt_image_destroy(a);
    dirt_image_destroy(b);
    return rc;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (t && fread(t, 1, (size_t)n, f) != (size_t)n) {
        free(t);
        t = NULL;
    }
    if (t)
        t[n] = '\0';
    fclose(f);
    return t;
}

static int window(const char *shot_path, const char *render_path, const char *report_path,
                  bool collapsed)
{
    int sw, sh, sc, rw, rh, rc_;
    unsigned char *shot = stbi_load(shot_path, &sw, &sh, &sc, 4);
    unsigned char *ren = stbi_load(render_path, &rw, &rh, &rc_, 4);
    char *text = slurp(report_path);
    cJSON *rep = text ? cJSON_Parse(text) : NULL;
    int rc = 2;
    const cJSON *panels = rep ? cJSON_GetObjectItem(rep, "panels") : NULL;
    if (!shot || !ren || !cJSON_IsArray(panels)) {
        printf("unreadable input\n");
        goto done;
    }
    rc = 1;
    if (sw != rw || sh != rh) {
        printf("window %dx%d, render %dx%d: the render should fill the window\n", sw, sh, rw, rh);
        goto done;
    }
    float rect[8][4];
    int np = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, panels) {
        if (np < 8 && cJSON_GetArraySize(p) == 4)
            for (int k = 0; k < 4; k++)
                rect[np][k] = (float)cJSON_GetArrayItem(p, k)->valuedouble;
        np++;
    }
    size_t out = 0, out_exact = 0, out_off = 0, in = 0, in_diff = 0;
    int worst = 0;
    for (int y = 0; y < sh; y++) {
        for (int x = 0; x < sw; x++) {
            bool covered = false;
            for (int i = 0; i < np && i < 8; i++)
                covered |= x + 1 > rect[i][0] - 2 && x < rect[i][0] + rect[i][2] + 2 &&
                           y + 1 > rect[i][1] - 2 && y < rect[i][1] + rect[i][3] + 2;
            const unsigned char *a = shot + ((size_t)y * sw + x) * 4;
            const unsigned char *b = ren + ((size_t)y * sw + x) * 4;
            int d = 0;
            for (int k = 0; k < 3; k++)
                d = abs(a[k] - b[k]) > d ? abs(a[k] - b[k]) : d;
            if (covered) {
                in++;
                in_diff += d > 0;
            } else {
                out++;
                out_exact += d == 0;
                out_off += d > 1;
                worst = d > worst ? d : worst;
            }
        }
    }
    printf("%d panel(s); uncovered pixels: %zu, %zu exact, %zu off by more than 1 (worst %d); "
           "covered: %zu, %zu differ\n", np, out, out_exact, out_off, worst, in, in_diff);
    bool ok = np > 0 && out > 0 && out_off == 0 && out_exact * 100 >= out * 99 &&
              in > 0 && (collapsed || in_diff * 2 > in);
    rc = ok ? 0 : 1;
done:
    stbi_image_free(shot);
    stbi_image_free(ren);
    cJSON_Delete(rep);
    free(text);
    return rc;
}


static const float heat_keys[DIRT_HEAT_KEYS][3] = {{DIRT_HEAT_KEY_0}, {DIRT_HEAT_KEY_1},
                                                   {DIRT_HEAT_KEY_2}, {DIRT_HEAT_KEY_3},
                                                   {DIRT_HEAT_KEY_4}};

/* The heat ramp at x in 0..1 (clamped). */
static void ramp(float x, float rgb[3])
{
    x = fminf(fmaxf(x, 0), 1) * (DIRT_HEAT_KEYS - 1);
    int k = (int)x < DIRT_HEAT_KEYS - 1 ? (int)x : DIRT_HEAT_KEYS - 2;
    float t = x - (float)k;
    for (int j = 0; j < 3; j++)
        rgb[j] = heat_keys[k][j] + t * (heat_keys[k + 1][j] - heat_keys[k][j]);
}

/* Loads SHOT and two EXRs of its size. False (printed) otherwise. */
static bool load_three(const char *shot_path, const char *a_path, const char *b_path,
                       unsigned char **shot, dirt_image **a, dirt_image **b, int *w, int *h)
{
    int c;
    *shot = stbi_load(shot_path, w, h, &c, 4);
    *a = dirt_image_read_exr(a_path);
    *b = dirt_image_read_exr(b_path);
    if (!*shot || !*a || !*b) {
        printf("unreadable input\n");
        return false;
    }
    if ((*a)->width != *w || (*a)->height != *h || (*b)->width != *w || (*b)->height != *h) {
        printf("window %dx%d, images %dx%d and %dx%d\n", *w, *h, (*a)->width, (*a)->height,
               (*b)->width, (*b)->height);
        return false;
    }
    return true;
}

/* The largest difference of a shot pixel's RGB from `want` (8-bit codes). */
static int off_by(const unsigned char *px, const int want[3])
{
    int d = 0;
    for (int j = 0; j < 3; j++)
        d = abs(px[j] - want[j]) > d ? abs(px[j] - want[j]) : d;
    return d;
}

static int split(const char *shot_path, const char *a_path, const char *b_path)
{
    unsigned char *shot = NULL;
    dirt_image *a = NULL, *b = NULL;
    int w, h, rc = 2;
    if (!load_three(shot_path, a_path, b_path, &shot, &a, &b, &w, &h))
        goto done;
    /* Pixel centres left of w / 2 show A, the column holding w / 2 is the
     * line, the rest B. */
    int line = w / 2;
    size_t n[2] = {0, 0}, exact[2] = {0, 0}, off[2] = {0, 0}, line_white = 0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const unsigned char *px = shot + ((size_t)y * w + x) * 4;
            if (x == line) {
                line_white += px[0] == 255 && px[1] == 255 && px[2] == 255;
                continue;
            }
            int side = x > line;
            const float *c = (side ? b : a)->rgba + ((size_t)y * w + x) * 4;
            int want[3];
            for (int j = 0; j < 3; j++)
                want[j] = dirt_linear_to_srgb8(c[j]);
            int d = off_by(px, want);
            n[side]++;
            exact[side] += d == 0;
            off[side] += d > 1;
        }
    }
    printf("left (A): %zu of %zu exact, %zu off by more than 1; right (B): %zu of %zu exact, "
           "%zu off by more than 1; line %zu of %d white\n", exact[0], n[0], off[0], exact[1],
           n[1], off[1], line_white, h);
    rc = 1;
    if (off[0] == 0 && off[1] == 0 && exact[0] * 100 >= n[0] * 99 &&
        exact[1] * 100 >= n[1] * 99 && line_white == (size_t)h)
        rc = 0;
done:
    stbi_image_free(shot);
    dirt_image_destroy(a);
    dirt_image_destroy(b);
    return rc;
}

static int diff(const char *shot_path, const char *a_path, const char *b_path, float range)
{
    unsigned char *shot = NULL;
    dirt_image *a = NULL, *b = NULL;
    int w, h, rc = 2;
    if (!load_three(shot_path, a_path, b_path, &shot, &a, &b, &w, &h) || !(range > 0))
        goto done;
    size_t n = (size_t)w * h, exact = 0, off = 0, nonzero = 0;
    for (size_t i = 0; i < n; i++) {
        const float *ca = a->rgba + 4 * i, *cb = b->rgba + 4 * i;
        float la = DIRT_LUMA_R * ca[0] + DIRT_LUMA_G * ca[1] + DIRT_LUMA_B * ca[2];
        float lb = DIRT_LUMA_R * cb[0] + DIRT_LUMA_G * cb[1] + DIRT_LUMA_B * cb[2];
        float rgb[3];
        ramp(fabsf(la - lb) / range, rgb);
        int want[3];
        for (int j = 0; j < 3; j++)
            want[j] = dirt_linear_to_srgb8(rgb[j]);
        int d = off_by(shot + 4 * i, want);
        exact += d == 0;
        off += d > 1;
        nonzero += la != lb;
    }
    printf("%zu of %zu pixels exact, %zu off by more than 1; A and B differ at %zu\n", exact, n,
           off, nonzero);
    rc = off == 0 && exact * 100 >= n * 99 && nonzero > 0 ? 0 : 1;
done:
    stbi_image_free(shot);
    dirt_image_destroy(a);
    dirt_image_destroy(b);
    return rc;
}

static int heat(const char *shot_path, const char *exr_path)
{
    static const float keys[DIRT_HEAT_KEYS][3] = {{DIRT_HEAT_KEY_0}, {DIRT_HEAT_KEY_1},
                                                   {DIRT_HEAT_KEY_2}, {DIRT_HEAT_KEY_3},
                                                   {DIRT_HEAT_KEY_4}};
    int w, h, c;
    unsigned char *shot = stbi_load(shot_path, &w, &h, &c, 4);
    dirt_image *img = dirt_image_read_exr(exr_path);
    const float *z = img ? dirt_image_find_channel(img, "Z") : NULL;
    int rc = 2;
    if (!shot || !z) {
        printf("unreadable input\n");
        goto done;
    }
    rc = 1;
    if (w != img->width || h != img->height) {
        printf("window %dx%d, image %dx%d\n", w, h, img->width, img->height);
        goto done;
    }
    size_t n = (size_t)w * h, exact = 0, off = 0, misses = 0;
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(z[i]))
            lo = fminf(lo, z[i]), hi = fmaxf(hi, z[i]);
    for (size_t i = 0; i < n; i++) {
        float rgb[3] = {0, 0, 0};
        if (isfinite(z[i])) {
            float x = fminf(fmaxf((z[i] - lo) / (hi - lo), 0), 1) * (DIRT_HEAT_KEYS - 1);
            int k = (int)x < DIRT_HEAT_KEYS - 1 ? (int)x : DIRT_HEAT_KEYS - 2;
            float t = x - (float)k;
            for (int j = 0; j < 3; j++)
                rgb[j] = keys[k][j] + t * (keys[k + 1][j] - keys[k][j]);
        } else {
            misses++;
        }
        int d = 0;
        for (int j = 0; j < 3; j++) {
            int e = abs(shot[4 * i + j] - dirt_linear_to_srgb8(rgb[j]));
            d = e > d ? e : d;
        }
        exact += d == 0;
        off += d > 1;
    }
    printf("depth %g..%g, %zu misses: %zu of %zu pixels exact, %zu off by more than 1\n", lo, hi,
           misses, exact, n, off);
    rc = off == 0 && exact * 100 >= n * 99 && hi > lo ? 0 : 1;
done:
    stbi_image_free(shot);
    dirt_image_destroy(img);
    return rc;
}

static int zoom(const char *shot_path, const char *render_path, int x0, int y0, int z)
{
    int sw, sh, rw, rh, c;
    unsigned char *shot = stbi_load(shot_path, &sw, &sh, &c, 4);
    unsigned char *ren = stbi_load(render_path, &rw, &rh, &c, 4);
    int rc = 2;
    if (!shot || !ren || z < 1) {
        printf("unreadable input\n");
        goto done;
    }
    rc = 1;
    size_t n = 0, exact = 0, off = 0, outside = 0, blocks_split = 0;
    for (int y = 0; y < sh; y++) {
        for (int x = 0; x < sw; x++) {
            int tx = (int)floor((double)(x - x0) / z), ty = (int)floor((double)(y - y0) / z);
            if (tx < 0 || ty < 0 || tx >= rw || ty >= rh) {
                outside++;
                continue;
            }
            const unsigned char *a = shot + ((size_t)y * sw + x) * 4;
            int want[3];
            for (int j = 0; j < 3; j++)
                want[j] = ren[((size_t)ty * rw + tx) * 4 + j];
            int d = off_by(a, want);
            n++;
            exact += d == 0;
            off += d > 1;
            /* the block's top-left window pixel (when in the window) */
            int bx = x0 + tx * z, by = y0 + ty * z;
            if (bx >= 0 && by >= 0 && memcmp(a, shot + ((size_t)by * sw + bx) * 4, 3) != 0)
                blocks_split++;
        }
    }
    printf("zoom %d, image at (%d, %d): %zu window pixels, %zu exact, %zu off by more than 1; "
           "%zu differ from their block; %zu outside the image\n", z, x0, y0, n, exact, off,
           blocks_split, outside);
    rc = n > 0 && off == 0 && exact * 100 >= n * 99 && blocks_split == 0 && outside == 0 ? 0 : 1;
done:
    stbi_image_free(shot);
    stbi_image_free(ren);
    return rc;
}

static int ramp_bar(const char *shot_path, int x0, int y0, int w, int h)
{
    int sw, sh, c;
    unsigned char *shot = stbi_load(shot_path, &sw, &sh, &c, 4);
    int rc = 2;
    if (!shot || w < 2 || h < 1 || x0 < 0 || y0 < 0 || x0 + w > sw || y0 + h > sh) {
        printf("unreadable input or the bar %d,%d %dx%d is outside the window\n", x0, y0, w, h);
        goto done;
    }
    size_t n = 0, exact = 0;
    int worst = 0;
    for (int i = 0; i < w; i++) {
        float rgb[3];
        ramp(((float)i + 0.5f) / (float)w, rgb);
        int want[3];
        for (int j = 0; j < 3; j++)
            want[j] = dirt_linear_to_srgb8(rgb[j]);
        for (int y = y0; y < y0 + h; y++) {
            int d = off_by(shot + ((size_t)y * sw + x0 + i) * 4, want);
            n++;
            exact += d == 0;
            worst = d > worst ? d : worst;
        }
    }
    printf("colour bar %d,%d %dx%d: %zu of %zu pixels exact (worst off by %d)\n", x0, y0, w, h,
           exact, n, worst);
    rc = exact == n ? 0 : 1;
done:
    stbi_image_free(shot);
    return rc;
}

static int pngs(const char *a_path, const char *b_path, bool negative)
{
    int aw, ah, bw, bh, c;
    unsigned char *a = stbi_load(a_path, &aw, &ah, &c, 4);
    unsigned char *b = stbi_load(b_path, &bw, &bh, &c, 4);
    int rc = 2;
    if (!a || !b || aw != bw || ah != bh) {
        printf("unreadable input or sizes differ\n");
        goto done;
    }
    size_t n = (size_t)aw * ah, match = 0;
    for (size_t i = 0; i < n; i++) {
        bool m = true;
        for (int j = 0; j < 3; j++)
            m = m && b[4 * i + j] == (negative ? 255 - a[4 * i + j] : a[4 * i + j]);
        match += m;
    }
    printf("%zu of %zu pixels %s\n", match, n, negative ? "the negative" : "the same");
    rc = match == n ? 0 : 1;
done:
    stbi_image_free(a);
    stbi_image_free(b);
    return rc;
}

static int pixel(const char *path, const char *channel, int x, int y)
{
    dirt_image *img = dirt_image_read_exr(path);
    const float *c = img ? dirt_image_find_channel(img, channel) : NULL;
    const char *rgba = strchr("RGBA", channel[0]);
    int rc = 2;
    if (img && x >= 0 && y >= 0 && x < img->width && y < img->height) {
        size_t i = (size_t)y * img->width + x;
        if (c) {
            printf("%.9g\n", c[i]);
            rc = 0;
        } else if (rgba && channel[0] && !channel[1]) { /* the beauty's R, G, B, A */
            printf("%.9g\n", img->rgba[4 * i + (rgba - "RGBA")]);
            rc = 0;
        }
    }
    dirt_image_destroy(img);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc == 6 && !strcmp(argv[1], "pixel"))
        return pixel(argv[2], argv[3], atoi(argv[4]), atoi(argv[5]));
    if (argc == 5 && !strcmp(argv[1], "split"))
        return split(argv[2], argv[3], argv[4]);
    if (argc == 6 && !strcmp(argv[1], "diff"))
        return diff(argv[2], argv[3], argv[4], strtof(argv[5], NULL));
    if (argc == 4 && !strcmp(argv[1], "heat"))
        return heat(argv[2], argv[3]);
    if (argc == 7 && !strcmp(argv[1], "zoom"))
        return zoom(argv[2], argv[3], atoi(argv[4]), atoi(argv[5]), atoi(argv[6]));
    if (argc == 7 && !strcmp(argv[1], "ramp"))
        return ramp_bar(argv[2], atoi(argv[3]), atoi(argv[4]), atoi(argv[5]), atoi(argv[6]));
    if (argc == 5 && !strcmp(argv[1], "pngs") &&
        (!strcmp(argv[4], "same") || !strcmp(argv[4], "negative")))
        return pngs(argv[2], argv[3], !strcmp(argv[4], "negative"));
    if (argc == 4 && !strcmp(argv[1], "same"))
        return same(argv[2], argv[3]);
    if (argc == 5 && !strcmp(argv[1], "window"))
        return window(argv[2], argv[3], argv[4], false);
    if (argc == 6 && !strcmp(argv[1], "window") && !strcmp(argv[5], "collapsed"))
        return window(argv[2], argv[3], argv[4], true);
    fprintf(stderr, "usage: view_check same A.exr B.exr | window SHOT.png RENDER.png REPORT.json [collapsed] | "
            "heat SHOT.png IMAGE.exr | split SHOT.png A.exr B.exr | diff SHOT.png A.exr B.exr RANGE | "
            "zoom SHOT.png RENDER.png X0 Y0 Z | ramp SHOT.png X Y W H | pngs A.png B.png same|negative | pixel IMAGE.exr CHANNEL X Y\n");
    return 2;
}
