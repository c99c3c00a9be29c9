/* EXR round trips: FLOAT bit-exact with extra channels, HALF rounding and
 * channel order, odd sizes, file layout (sorted channels, ZIP, pixel types)
 * and read failures. */
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "dirt/image.h"

static char g_dir[] = "/tmp/dirt_test_io_exr.XXXXXX";

/* Deterministic float with arbitrary mantissa bits in [-1000, 1000]. */
static uint32_t g_seed = 12345u;
static float next_float(void)
{
    g_seed = g_seed * 1664525u + 1013904223u;
    uint32_t r = g_seed >> 8; /* 24 bits */
    return ((float)r / (float)(1u << 24) - 0.5f) * 2000.0f;
}

/* float -> nearest binary16 (ties to even) -> float, computed independently
 * of the library: scale so one half ulp is 1 and round in double. Valid for
 * |x| < 65504 (no overflow handling needed by these tests). */
static float half_round(float x)
{
    if (x == 0.0f)
        return x;
    int e;
    frexp((double)x, &e); /* |x| = m * 2^e, m in [0.5, 1) */
    int ulp_exp = (e - 1) - 10;
    if (ulp_exp < -24)
        ulp_exp = -24; /* subnormal halves share ulp 2^-24 */
    double ulp = ldexp(1.0, ulp_exp);
    return (float)(nearbyint((double)x / ulp) * ulp);
}

static bool same_bits(const float *a, const float *b, size_t n, size_t stride)
{
    for (size_t i = 0; i < n; i++)
        if (memcmp(&a[i * stride], &b[i * stride], sizeof(float)) != 0)
            return false;
    return true;
}

static const char *const extra_names[3] = {"albedo.R", "N.X", "Z"};

/* FLOAT RGBA plus `nextra` (0..3) extra channels, compared bit for bit. */
static void test_float_roundtrip(int w, int h, int nextra)
{
    char path[256];
    snprintf(path, sizeof(path), "%s/float_%dx%d_%d.exr", g_dir, w, h,
             nextra);
    dirt_image *img = dirt_image_create(w, h);
    CHECK(img != NULL);
    if (!img)
        return;
    float *planes[3];
    for (int k = 0; k < nextra; k++) {
        planes[k] = dirt_image_add_channel(img, extra_names[k]);
        CHECK(planes[k] != NULL);
        if (!planes[k])
            goto out;
    }
    const size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n * 4; i++)
        img->rgba[i] = next_float();
    for (int k = 0; k < nextra; k++)
        for (size_t i = 0; i < n; i++)
            planes[k][i] = next_float();
    img->rgba[0] = 1e-40f;  /* subnormal float survives FLOAT storage */
    img->rgba[1] = -0.0f;

    CHECK(dirt_image_write_exr(img, path, NULL));
    dirt_image *back = dirt_image_read_exr(path);
    CHECK(back != NULL);
    if (back) {
        CHECK(back->width == w && back->height == h);
        CHECK(back->channel_count == nextra);
        if (back->width == w && back->height == h) {
            CHECK_MSG(same_bits(back->rgba, img->rgba, n * 4, 1),
                      "RGBA not bit-exact for %dx%d", w, h);
            for (int k = 0; k < nextra; k++) {
                const float *p = dirt_image_find_channel(back, extra_names[k]);
                CHECK_MSG(p != NULL, "channel %s missing", extra_names[k]);
                if (p)
                    CHECK_MSG(same_bits(p, planes[k], n, 1),
                              "channel %s not bit-exact", extra_names[k]);
            }
        }
    }
    dirt_image_destroy(back);
out:
    dirt_image_destroy(img);
    unlink(path);
}

/* HALF RGBA; values per channel are in disjoint ranges so any channel
 * permutation is caught. extra: 0 = RGBA only (the 4-channel HALF file is
 * where OpenEXRCore 3.1.5's interleaved float decode reverses the channel
 * order), 1 = plus a FLOAT "Z", 2 = plus a HALF "Z". */
static void test_half_roundtrip(int w, int h, int extra)
{
    const bool half_extra = extra == 2;
    char path[256];
    snprintf(path, sizeof(path), "%s/half_%dx%d_%d.exr", g_dir, w, h, extra);
    dirt_image *img = dirt_image_create(w, h);
    CHECK(img != NULL);
    if (!img)
        return;
    float *z = NULL;
    if (extra) {
        z = dirt_image_add_channel(img, "Z");
        CHECK(z != NULL);
        if (!z)
            goto out;
    }
    const size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        float u = (float)((i * 7919u) % 1000u) / 1000.0f; /* [0,1) */
        img->rgba[i * 4 + 0] = 0.1f + 0.8f * u;           /* (0.1, 0.9) */
        img->rgba[i * 4 + 1] = 1.0f + 6.9f * u + 0.013f;  /* [1, 8) */
        img->rgba[i * 4 + 2] = -3.3f * u - 0.0371f;       /* negative */
        img->rgba[i * 4 + 3] = 1e-4f * u + 1e-7f;         /* subnormal halves */
        if (z)
            z[i] = 100.0f + 0.1234567f * (float)i;
    }
    dirt_exr_options opts = {.half_rgba = true, .half_extra = half_extra};
    CHECK(dirt_image_write_exr(img, path, &opts));
    dirt_image *back = dirt_image_read_exr(path);
    CHECK(back != NULL);
    if (back && back->width == w && back->height == h) {
        static const char names[4] = {'R', 'G', 'B', 'A'};
        for (int c = 0; c < 4; c++) {
            size_t bad = 0, first = 0;
            for (size_t i = 0; i < n; i++) {
                float want = half_round(img->rgba[i * 4 + c]);
                if (back->rgba[i * 4 + c] != want && bad++ == 0)
                    first = i;
            }
            CHECK_MSG(bad == 0, "HALF channel %c: %zu wrong, first at %zu: "
                      "got %.9g want %.9g (written %.9g)", names[c], bad,
                      first, back->rgba[first * 4 + c],
                      half_round(img->rgba[first * 4 + c]),
                      img->rgba[first * 4 + c]);
        }
        /* spot check with hand-known values: pixel 0 has u = 0 */
        CHECK(back->rgba[0] == half_round(0.1f));
        CHECK_NEAR(back->rgba[0], 0.1, 0.0001);
        CHECK_NEAR(back->rgba[1], 1.013, 0.001);
        CHECK_NEAR(back->rgba[2], -0.0371, 0.0001);
        CHECK_NEAR(back->rgba[3], 1e-7, 3e-8);
        CHECK(back->channel_count == (extra ? 1 : 0));
        const float *bz = dirt_image_find_channel(back, "Z");
        CHECK((bz != NULL) == (extra != 0));
        if (bz && z) {
            bool ok = true;
            for (size_t i = 0; i < n && ok; i++)
                ok = half_extra ? bz[i] == half_round(z[i]) : bz[i] == z[i];
            CHECK_MSG(ok, "Z channel wrong (half_extra=%d)", (int)half_extra);
        }
    } else {
        CHECK(!"HALF read back failed or wrong size");
    }
    dirt_image_destroy(back);
out:
    dirt_image_destroy(img);
    unlink(path);
}

/* The file itself: channels sorted by name, ZIP, requested pixel types. */
static void test_file_layout(void)
{
    char path[256];
    snprintf(path, sizeof(path), "%s/layout.exr", g_dir);
    dirt_image *img = dirt_image_create(5, 3);
    CHECK(img != NULL);
    if (!img)
        return;
    CHECK(dirt_image_add_channel(img, "Z") != NULL);
    CHECK(dirt_image_add_channel(img, "N.X") != NULL);
    CHECK(dirt_image_add_channel(img, "albedo.R") != NULL);
    dirt_exr_options opts = {.half_rgba = true};
    CHECK(dirt_image_write_exr(img, path, &opts));

    exr_context_t ctx = NULL;
    CHECK(exr_start_read(&ctx, path, NULL) == EXR_ERR_SUCCESS);
    if (ctx) {
        exr_compression_t comp = EXR_COMPRESSION_NONE;
        CHECK(exr_get_compression(ctx, 0, &comp) == EXR_ERR_SUCCESS);
        CHECK(comp == EXR_COMPRESSION_ZIP);
        exr_storage_t st = EXR_STORAGE_LAST_TYPE;
        CHECK(exr_get_storage(ctx, 0, &st) == EXR_ERR_SUCCESS);
        CHECK(st == EXR_STORAGE_SCANLINE);
        const exr_attr_chlist_t *cl = NULL;
        CHECK(exr_get_channels(ctx, 0, &cl) == EXR_ERR_SUCCESS);
        CHECK(cl && cl->num_channels == 7);
        if (cl && cl->num_channels == 7) {
            static const char *const sorted[7] = {"A", "B", "G", "N.X", "R",
                                                  "Z", "albedo.R"};
            for (int i = 0; i < 7; i++) {
                const char *nm = cl->entries[i].name.str;
                CHECK_MSG(strcmp(nm, sorted[i]) == 0, "channel %d is %s", i,
                          nm);
                bool rgba = strlen(nm) == 1 && strchr("RGBA", nm[0]);
                CHECK_MSG(cl->entries[i].pixel_type ==
                              (rgba ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT),
                          "channel %s type %d", nm,
                          (int)cl->entries[i].pixel_type);
            }
        }
        exr_finish(&ctx);
    }
    dirt_image_destroy(img);
    unlink(path);
}

/* String attributes land in the header as given (read with OpenEXR's own
 * API); a name the header already holds with another type is refused and
 * nothing is written. */
static void test_attributes(void)
{
    char path[256];
    snprintf(path, sizeof(path), "%s/attrs.exr", g_dir);
    dirt_image *img = dirt_image_create(4, 2);
    CHECK(img != NULL);
    if (!img)
        return;
    const dirt_image_attr attrs[] = {{"dirt.scene", "room.glb"},
                                     {"dirt.commandLine", "dirt-render 'a b' -o x.exr"}};
    dirt_exr_options opts = {.attrs = attrs, .num_attrs = 2};
    CHECK(dirt_image_write_exr(img, path, &opts));
    exr_context_t ctx = NULL;
    CHECK(exr_start_read(&ctx, path, NULL) == EXR_ERR_SUCCESS);
    for (int i = 0; ctx && i < 2; i++) {
        const char *v = NULL;
        int32_t len = 0;
        CHECK(exr_attr_get_string(ctx, 0, attrs[i].name, &len, &v) == EXR_ERR_SUCCESS);
        CHECK_MSG(v && len == (int32_t)strlen(attrs[i].value) && !memcmp(v, attrs[i].value, len),
                  "attribute %s", attrs[i].name);
    }
    if (ctx)
        exr_finish(&ctx);
    unlink(path);
    const dirt_image_attr bad[] = {{"channels", "R"}};
    opts = (dirt_exr_options){.attrs = bad, .num_attrs = 1};
    CHECK(!dirt_image_write_exr(img, path, &opts));
    CHECK(access(path, F_OK) != 0);
    dirt_image_destroy(img);
}

static void test_image_api(void)
{
    CHECK(dirt_image_create(0, 4) == NULL);
    CHECK(dirt_image_create(4, -1) == NULL);
    dirt_image *img = dirt_image_create(3, 2);
    CHECK(img != NULL);
    if (!img)
        return;
    CHECK(img->rgba[0] == 0.0f && img->rgba[3 * 2 * 4 - 1] == 0.0f);
    float *a = dirt_image_add_channel(img, "albedo.R");
    CHECK(a != NULL);
    CHECK(dirt_image_add_channel(img, "albedo.R") == NULL); /* duplicate */
    CHECK(dirt_image_add_channel(img, "R") == NULL);        /* reserved */
    CHECK(dirt_image_add_channel(img, "") == NULL);
    float *b = dirt_image_add_channel(img, "albedo.G");
    CHECK(b != NULL && b != a);
    CHECK(dirt_image_find_channel(img, "albedo.R") == a);
    CHECK(dirt_image_find_channel(img, "albedo.G") == b);
    CHECK(dirt_image_find_channel(img, "albedo.B") == NULL);
    CHECK(img->channel_count == 2);
    dirt_image_destroy(img);
    dirt_image_destroy(NULL);
}

static void test_read_failures(void)
{
    char path[256];
    snprintf(path, sizeof(path), "%s/missing.exr", g_dir);
    CHECK(dirt_image_read_exr(path) == NULL);
    snprintf(path, sizeof(path), "%s/garbage.exr", g_dir);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs("this is not an OpenEXR file at all", f);
        fclose(f);
        CHECK(dirt_image_read_exr(path) == NULL);
        unlink(path);
    }
}

int main(void)
{
    if (!mkdtemp(g_dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_image_api();
    test_float_roundtrip(97, 61, 3);
    test_float_roundtrip(97, 61, 0);
    test_float_roundtrip(1, 1, 3);
    test_float_roundtrip(3, 17, 1);
    test_half_roundtrip(97, 61, 0);
    test_half_roundtrip(97, 61, 1);
    test_half_roundtrip(2, 33, 2);
    test_file_layout();
    test_attributes();
    test_read_failures();
    rmdir(g_dir);
    return check_finish();
}
