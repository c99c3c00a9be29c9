/* Tonemapped 8-bit sRGB PNG previews through stb_image_write.
 * Contracts are documented in dirt/image.h. */
#include "dirt/image.h"

#include "common/display.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "dirt/log.h"
#include "io/atomic_file.h"

/* The consumer API's tone-map ids (dirt/types.h) are the shaders'
 * (common/display.h). */
_Static_assert(DIRT_TONEMAP_CLAMP == DIRT_TONEMAP_ID_CLAMP &&
                   DIRT_TONEMAP_REINHARD == DIRT_TONEMAP_ID_REINHARD &&
                   DIRT_TONEMAP_ACES == DIRT_TONEMAP_ID_ACES,
               "enum dirt_tonemap differs from common/display.h");

unsigned char dirt_linear_to_srgb8(float v)
{
    if (!(v > 0.0f)) /* negative, zero and NaN */
        return 0;
    if (v >= 1.0f)
        return 255;
    float s = v <= DIRT_SRGB_LINEAR_MAX
                  ? DIRT_SRGB_LINEAR_SCALE * v
                  : DIRT_SRGB_SCALE * powf(v, DIRT_SRGB_EXPONENT) - DIRT_SRGB_OFFSET;
    long q = lroundf(s * 255.0f);
    return (unsigned char)(q < 0 ? 0 : q > 255 ? 255 : q);
}

/* Tonemap curve applied to one exposed linear value; the result is clamped
 * by the sRGB step. The constants are common/display.h's, shared with the
 * window's presentation shader (glsl/present/present.frag). */
static float tonemap(float x, enum dirt_tonemap op)
{
    switch (op) {
    case DIRT_TONEMAP_REINHARD:
        return x > 0.0f ? x / (1.0f + x) : 0.0f;
    case DIRT_TONEMAP_ACES:
        /* Narkowicz 2015 fit of the ACES filmic curve (sRGB primaries). */
        if (!(x > 0.0f))
            return 0.0f;
        return (x * (DIRT_ACES_A * x + DIRT_ACES_B)) /
               (x * (DIRT_ACES_C * x + DIRT_ACES_D) + DIRT_ACES_E);
    case DIRT_TONEMAP_CLAMP:
    default:
        return x;
    }
}

/* stb writer sink: appends to the atomic file's stream, remembers failure. */
typedef struct png_sink {
    FILE *fp;
    bool failed;
    int err;
} png_sink;

static void png_write(void *context, void *data, int size)
{
    png_sink *s = context;
    if (s->failed || size <= 0)
        return;
    if (fwrite(data, 1, (size_t)size, s->fp) != (size_t)size) {
        s->failed = true;
        s->err = errno;
    }
}

bool dirt_image_write_png(const dirt_image *img, const char *path,
                          const dirt_png_options *opts)
{
    dirt_atomic_file *af = NULL;
    unsigned char *pixels = NULL;
    png_sink sink = {NULL, false, 0};

    if (!img || !img->rgba || !path) {
        DIRT_ERROR("PNG write: NULL image or path");
        return false;
    }
    dirt_png_options o = {0};
    if (opts)
        o = *opts;
    if (o.tonemap != DIRT_TONEMAP_CLAMP && o.tonemap != DIRT_TONEMAP_REINHARD &&
        o.tonemap != DIRT_TONEMAP_ACES) {
        DIRT_ERROR("PNG write '%s': unknown tonemap %d", path, (int)o.tonemap);
        return false;
    }
    if (!isfinite(o.exposure)) {
        DIRT_ERROR("PNG write '%s': exposure must be finite", path);
        return false;
    }

    const int comp = o.alpha ? 4 : 3;
    const size_t count = (size_t)img->width * (size_t)img->height;
    /* stb_image_write sizes its buffers with int arithmetic. */
    if (count * (size_t)(comp + 1) > (size_t)INT32_MAX / 2) {
        DIRT_ERROR("PNG write '%s': %dx%d is too large for the PNG writer",
                   path, img->width, img->height);
        return false;
    }
    const float scale = exp2f(o.exposure);
    pixels = malloc(count * (size_t)comp);
    if (!pixels) {
        DIRT_ERROR("PNG write '%s': out of memory", path);
        return false;
    }
    for (size_t i = 0; i < count; i++) {
        const float *src = img->rgba + i * 4;
        unsigned char *dst = pixels + i * (size_t)comp;
        for (int c = 0; c < 3; c++)
            dst[c] = dirt_linear_to_srgb8(tonemap(src[c] * scale, o.tonemap));
        if (o.alpha) {
            float a = src[3];
            a = a > 0.0f ? (a < 1.0f ? a : 1.0f) : 0.0f; /* NaN -> 0 */
            dst[3] = (unsigned char)lroundf(a * 255.0f);
        }
    }

    af = dirt_atomic_open(path);
    if (!af)
        goto error;
    sink.fp = dirt_atomic_stream(af);
    if (!stbi_write_png_to_func(png_write, &sink, img->width, img->height,
                                comp, pixels, img->width * comp)) {
        DIRT_ERROR("PNG write '%s': encoding failed", path);
        goto error;
    }
    if (sink.failed) {
        DIRT_ERROR("PNG write '%s': writing '%s' failed: %s", path,
                   dirt_atomic_temp_path(af), strerror(sink.err));
        goto error;
    }
    free(pixels);
    return dirt_atomic_commit(af);

error:
    dirt_atomic_abort(af);
    free(pixels);
    return false;
}

bool dirt_write_png_rgba8(const char *path, int width, int height, const uint8_t *rgba)
{
    if (!path || !rgba || width <= 0 || height <= 0 ||
        (size_t)width * (size_t)height * 4 > (size_t)INT32_MAX / 2) {
        DIRT_ERROR("PNG write: bad arguments (%dx%d)", width, height);
        return false;
    }
    dirt_atomic_file *af = dirt_atomic_open(path);
    if (!af)
        return false;
    png_sink sink = {dirt_atomic_stream(af), false, 0};
    if (!stbi_write_png_to_func(png_write, &sink, width, height, 4, rgba, width * 4)) {
        DIRT_ERROR("PNG write '%s': encoding failed", path);
        dirt_atomic_abort(af);
        return false;
    }
    if (sink.failed) {
        DIRT_ERROR("PNG write '%s': writing '%s' failed: %s", path, dirt_atomic_temp_path(af),
                   strerror(sink.err));
        dirt_atomic_abort(af);
        return false;
    }
    return dirt_atomic_commit(af);
}
