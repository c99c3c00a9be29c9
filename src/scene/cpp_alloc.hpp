/* Allocation helpers of the scene layer's C++ loaders (gltf.cpp, obj.cpp):
 * C heap arrays (freed by the C side with free()) that throw
 * std::bad_alloc on failure, for the loaders' one catch; their load
 * budget; and their one image decoder. */
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

/* The expanded-size budget of one load (dirt_load_opts.max_bytes): every
 * array a loader makes from the file is charged before it is allocated.
 * Each loader keeps one per thread (thread_local), set by its entry
 * points. */
struct load_budget {
    size_t left;

    /* Charges `count` x `each` bytes (overflow-safe); false (logged,
     * TOO_LARGE) when they do not fit. */
    bool charge(size_t count, size_t each, const char *what)
    {
        if (each != 0 && count > left / each) {
            SCENE_FAIL(TOO_LARGE,
                       "%s: %zu elements of %zu bytes exceed what is left of the load budget "
                       "(%zu bytes; dirt_load_opts.max_bytes)",
                       what, count, each, left);
            return false;
        }
        left -= count * each;
        return true;
    }
};

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
