/* Allocation helpers of the scene layer's C++ loaders (gltf.cpp, obj.cpp):
 * C heap arrays (freed by the C side with free()) that throw
 * std::bad_alloc on failure, for the loaders' one catch; and their one
 * image decoder, within the load's budget. */
#ifndef DIRT_SCENE_CPP_ALLOC_HPP
#define DIRT_SCENE_CPP_ALLOC_HPP

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include <stb_image.h>

#include "dirt/log.h"
#include "scene/scene_internal.h"

namespace dirt_scene_cpp {

/* A malloc'd copy of `v` (at least one element's room). */
template <typename T> T *dup_array(const std::vector<T> &v)
{
    T *p = (T *)malloc((v.empty() ? 1 : v.size()) * sizeof(T));
    if (!p)
        throw std::bad_alloc();
    if (!v.empty())
        memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

/* n zeroed elements (at least one's room). */
template <typename T> T *alloc_zeroed(size_t n)
{
    T *p = (T *)calloc(n ? n : 1, sizeof(T));
    if (!p)
        throw std::bad_alloc();
    return p;
}

/* How many times its decoded pixels (4 bytes each) decoding an image may
 * hold at once: stb_image's own output, its working buffers (a PNG's
 * inflated rows, a JPEG's components) and the copy decode_rgba8 returns;
 * measured (test scene_memory, doc/scenes.md "Memory"). */
const size_t texture_decode_factor = 3;

/* Whether the image file in bytes[0, size) (size <= INT32_MAX) may be
 * decoded: a PNG, JPEG, BMP or TGA, from the size its header declares (stbi_info_from_memory,
 * before any pixel is decoded): 1 when the decode fits the load's budget
 * (texture_decode_factor times its pixels, 4 bytes each, are charged: call
 * texture_decoded after the decode to give back what the decoder freed);
 * 0 when stb cannot read the header (stb's reason in *why: the caller warns
 * and uses the factor); -1 when the decode does not fit (logged with
 * `label`, TOO_LARGE: the load fails). */
inline int texture_fits(const unsigned char *bytes, size_t size, const char *label,
                        const char **why)
{
    /* A texture is PNG or JPEG (glTF), BMP or TGA (OBJ's usual maps):
     * stb_image's other formats are not read (its Radiance decoder loops
     * forever on a truncated run-length scanline: a fuzz finding). */
    static const struct { const char *magic; size_t n; } refused[] = {
        {"#?RADIANCE", 10}, {"#?RGBE", 6}, {"8BPS", 4}, {"GIF8", 4},
        {"\x53\x80\xf6\x34", 4}, {"P5", 2}, {"P6", 2}};
    for (const auto &r : refused) {
        if (size >= r.n && memcmp(bytes, r.magic, r.n) == 0) {
            *why = "not a PNG, JPEG, BMP or TGA image";
            return 0;
        }
    }
    /* A PNG's chunks must lie in the file: stb_image allocates what a
     * chunk's length field says before it reads it (a fuzz finding: 1.8 GB
     * for a 200-byte file). */
    if (size >= 8 && memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0) {
        size_t p = 8;
        while (p + 12 <= size) {
            size_t len = (size_t)bytes[p] << 24 | (size_t)bytes[p + 1] << 16 |
                         (size_t)bytes[p + 2] << 8 | bytes[p + 3];
            if (len > size - p - 12) {
                *why = "a PNG chunk runs past the end of the file";
                return 0;
            }
            if (memcmp(bytes + p + 4, "IEND", 4) == 0)
                break;
            p += 12 + len;
        }
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, (int)size, &w, &h, &comp) || w <= 0 || h <= 0) {
        *why = stbi_failure_reason() ? stbi_failure_reason() : "unknown format";
        return 0;
    }
    size_t pixels = (size_t)w * (size_t)h;
    if (!scene_budget_fits(pixels, 4 * texture_decode_factor)) {
        SCENE_FAIL(TOO_LARGE,
                   "%s declares %d x %d pixels: decoding it needs %zu MiB, more than is left of "
                   "the load budget (%zu MiB of %zu; dirt_load_opts.max_bytes, "
                   "--max-scene-memory)",
                   label, w, h, (pixels * 4 * texture_decode_factor) >> 20,
                   scene_budget_left() >> 20, scene_load_opts()->max_bytes >> 20);
        return -1;
    }
    return scene_charge(pixels, 4 * texture_decode_factor, label) ? 1 : -1;
}

/* After the decode texture_fits allowed: gives back the decoder's working
 * memory, keeping the charge of the w x h pixels kept (none when the
 * decode failed: pass 0 x 0); `declared` the pixels texture_fits saw. */
inline void texture_decoded(const unsigned char *bytes, size_t size, int w, int h)
{
    int dw = 0, dh = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, (int)size, &dw, &dh, &comp))
        return;
    size_t charged = (size_t)dw * (size_t)dh * 4 * texture_decode_factor;
    size_t kept = (size_t)w * (size_t)h * 4;
    scene_refund(charged > kept ? charged - kept : 0, 1);
}

/* The image file in bytes[0, size) (size <= INT32_MAX) decoded by
 * stb_image to 8-bit RGBA, rows top to bottom, in a malloc'd buffer (the C
 * side frees it), its size in *w, *h; nullptr when it cannot be decoded,
 * with stb's reason in *why. Throws std::bad_alloc. */
inline uint8_t *decode_rgba8(const unsigned char *bytes, size_t size, int *w, int *h,
                             const char **why)
{
    int comp = 0;
    unsigned char *pixels = stbi_load_from_memory(bytes, (int)size, w, h, &comp, 4);
    if (!pixels || *w <= 0 || *h <= 0) {
        *why = stbi_failure_reason() ? stbi_failure_reason() : "unknown format";
        if (pixels)
            stbi_image_free(pixels);
        return nullptr;
    }
    size_t n = (size_t)*w * (size_t)*h * 4u;
    uint8_t *rgba = (uint8_t *)malloc(n);
    if (!rgba) {
        stbi_image_free(pixels);
        throw std::bad_alloc();
    }
    memcpy(rgba, pixels, n);
    stbi_image_free(pixels);
    return rgba;
}

} // namespace dirt_scene_cpp

#endif
