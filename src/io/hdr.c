/* Radiance RGBE (.hdr) reading: the header and the scanlines' lengths are
 * checked here, the pixels decoded by stb_image (Debian's libstb), which
 * reads a missing byte as 0: a truncated file would decode as black (or,
 * in a run-length scanline, loop on the zeros), so nothing reaches it that
 * is not complete. */
#include "dirt/image.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "dirt/log.h"
#include "io/read.h"

/* The header of an RGBE file in b[0, n): its size and where its pixels
 * start. False with the reason in `why` when it is not one stb_image
 * reads: "#?RADIANCE" or "#?RGBE", lines up to an empty one of which one is
 * FORMAT=32-bit_rle_rgbe, then "-Y H +X W" (the only orientation). */
static bool parse_header(const uint8_t *b, size_t n, int *w, int *h, size_t *data,
                         const char **why)
{
    size_t p = 0;
    bool valid = false;
    char line[1024];
    for (int k = 0;; k++) {
        size_t len = 0;
        while (p < n && b[p] != '\n') {
            if (len + 1 < sizeof(line))
                line[len++] = (char)b[p];
            p++;
        }
        if (p >= n) {
            *why = "the header ends before the image size";
            return false;
        }
        p++;
        line[len] = 0;
        if (k == 0) {
            if (strcmp(line, "#?RADIANCE") != 0 && strcmp(line, "#?RGBE") != 0) {
                *why = "not a Radiance RGBE file (no #?RADIANCE)";
                return false;
            }
            continue;
        }
        if (len == 0)
            break;
        if (!strcmp(line, "FORMAT=32-bit_rle_rgbe"))
            valid = true;
    }
    if (!valid) {
        *why = "no FORMAT=32-bit_rle_rgbe line (another pixel format)";
        return false;
    }
    size_t len = 0;
    while (p < n && b[p] != '\n' && len + 1 < sizeof(line))
        line[len++] = (char)b[p++];
    line[len] = 0;
    if (p >= n) {
        *why = "the file ends in its size line";
        return false;
    }
    p++;
    long hh = 0, ww = 0;
    char extra;
    if (sscanf(line, "-Y %ld +X %ld%c", &hh, &ww, &extra) != 2) {
        *why = "its size line is not '-Y H +X W' (the only layout read)";
        return false;
    }
    if (hh < 1 || ww < 1 || hh > DIRT_IMAGE_MAX_DIM || ww > DIRT_IMAGE_MAX_DIM) {
        *why = "its size is out of range";
        *w = (int)(ww > INT32_MAX ? INT32_MAX : ww);
        *h = (int)(hh > INT32_MAX ? INT32_MAX : hh);
        return false;
    }
    *w = (int)ww;
    *h = (int)hh;
    *data = p;
    return true;
}

/* Walks the pixel data b[p, n) of a w x h image as stb_image will read it:
 * flat RGBE when the width is under 8 or at least 32768, or from the first
 * scanline that is not run-length encoded on (stb_image reads the rest
 * flat, from the image's start); otherwise each scanline's header (2, 2,
 * width) and its four run-length components. INVALID with the reason when
 * a scanline is malformed, TRUNCATED (naming the row) when the data ends
 * early; OK when every byte the decoder will read is there. */
static enum dirt_input_error walk_pixels(const uint8_t *b, size_t n, size_t p, int w, int h,
                                         char *why, size_t size)
{
    size_t flat = (size_t)w * (size_t)h * 4;
    if (w < 8 || w >= 32768) {
        if (n - p < flat) {
            snprintf(why, size, "%zu bytes of flat pixels, %zu in the file", flat, n - p);
            return DIRT_INPUT_ERR_TRUNCATED;
        }
        return DIRT_INPUT_ERR_OK;
    }
    for (int j = 0; j < h; j++) {
        if (n - p < 4) {
            snprintf(why, size, "row %d of %d is missing", j, h);
            return DIRT_INPUT_ERR_TRUNCATED;
        }
        if (b[p] != 2 || b[p + 1] != 2 || (b[p + 2] & 0x80)) {
            /* Not run-length encoded: stb_image reads every pixel flat from
             * here (writing from the image's start). */
            if (n - p < flat) {
                snprintf(why, size, "%zu bytes of flat pixels from row %d, %zu in the file",
                         flat, j, n - p);
                return DIRT_INPUT_ERR_TRUNCATED;
            }
            return DIRT_INPUT_ERR_OK;
        }
        int len = (b[p + 2] << 8) | b[p + 3];
        if (len != w) {
            snprintf(why, size, "row %d declares a width of %d, not %d", j, len, w);
            return DIRT_INPUT_ERR_INVALID;
        }
        p += 4;
        for (int k = 0; k < 4; k++) {
            int i = 0;
            while (i < w) {
                if (p >= n) {
                    snprintf(why, size, "row %d of %d ends early", j, h);
                    return DIRT_INPUT_ERR_TRUNCATED;
                }
                int count = b[p++];
                if (count > 128) {
                    count -= 128;
                    if (p >= n) {
                        snprintf(why, size, "row %d of %d ends early", j, h);
                        return DIRT_INPUT_ERR_TRUNCATED;
                    }
                    p++;
                } else if (n - p < (size_t)count) {
                    snprintf(why, size, "row %d of %d ends early", j, h);
                    return DIRT_INPUT_ERR_TRUNCATED;
                } else {
                    p += (size_t)count;
                }
                if (count > w - i) {
                    snprintf(why, size, "row %d: a run past the row's end", j);
                    return DIRT_INPUT_ERR_INVALID;
                }
                i += count;
            }
        }
    }
    return DIRT_INPUT_ERR_OK;
}

dirt_image *io_read_hdr(const char *path, const dirt_image_read_opts *o, enum dirt_input_error *err)
{
    if (!path) {
        DIRT_ERROR("hdr: NULL path");
        *err = DIRT_INPUT_ERR_INVALID;
        return NULL;
    }
    size_t n = 0;
    uint8_t *b = dirt_input_read(path, o->max_bytes, &n, err);
    if (!b) {
        DIRT_ERROR("hdr: '%s': %s%s%s", path, dirt_input_error_str(*err),
                   *err == DIRT_INPUT_ERR_IO ? ": " : "",
                   *err == DIRT_INPUT_ERR_IO ? strerror(errno) : "");
        return NULL;
    }
    dirt_image *img = NULL;
    float *px = NULL;
    int w = 0, h = 0;
    size_t data = 0;
    const char *bad = NULL;
    char why[160];
    if (!parse_header(b, n, &w, &h, &data, &bad)) {
        *err = w > DIRT_IMAGE_MAX_DIM || h > DIRT_IMAGE_MAX_DIM ? DIRT_INPUT_ERR_TOO_LARGE
                                                                : DIRT_INPUT_ERR_INVALID;
        DIRT_ERROR("hdr: '%s': %s", path, bad);
        goto done;
    }
    /* The pixels the header declares must be in the file (a walk, no
     * memory), then fit the limit: the file, stb_image's float RGB and the
     * image's RGBA planes, then the caller's share, held at once. */
    *err = walk_pixels(b, n, data, w, h, why, sizeof(why));
    if (*err != DIRT_INPUT_ERR_OK) {
        DIRT_ERROR("hdr: '%s' (%d x %d): %s: %s", path, w, h,
                   *err == DIRT_INPUT_ERR_TRUNCATED ? "the file ends before its pixels do"
                                                    : "malformed pixel data",
                   why);
        goto done;
    }
    size_t px_count = (size_t)w * (size_t)h;
    size_t per_pixel = 12 + 16 + o->extra_per_pixel;
    if (px_count > (o->max_bytes - (n < o->max_bytes ? n : o->max_bytes)) / per_pixel) {
        *err = DIRT_INPUT_ERR_TOO_LARGE;
        DIRT_ERROR("hdr: '%s': %d x %d pixels need %zu MiB to read, more than the limit of "
                   "%zu MiB", path, w, h, (px_count * per_pixel + n) >> 20, o->max_bytes >> 20);
        goto done;
    }
    *err = DIRT_INPUT_ERR_INVALID;
    int sw = 0, sh = 0, comp = 0;
    px = n <= (size_t)INT32_MAX ? stbi_loadf_from_memory(b, (int)n, &sw, &sh, &comp, 3) : NULL;
    if (!px || sw != w || sh != h) {
        DIRT_ERROR("hdr: cannot read '%s': %s", path,
                   !px && stbi_failure_reason() ? stbi_failure_reason() : "unknown error");
        goto done;
    }
    free(b);
    b = NULL;
    img = dirt_image_create(w, h);
    if (!img)
        goto done;
    for (size_t k = 0; k < px_count; k++) {
        for (int c = 0; c < 3; c++)
            img->rgba[4 * k + (size_t)c] = px[3 * k + (size_t)c];
        img->rgba[4 * k + 3] = 1.0f;
    }
    *err = DIRT_INPUT_ERR_OK;
done:
    stbi_image_free(px);
    free(b);
    return img;
}

dirt_image *dirt_image_read_hdr(const char *path)
{
    dirt_image_read_opts o = io_read_defaults(NULL);
    enum dirt_input_error err;
    return io_read_hdr(path, &o, &err);
}
