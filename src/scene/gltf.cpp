/* DIRT engine: glTF 2.0 (.gltf / .glb) loader. A C++ translation unit behind
 * a C API (as src/gl/ui.cpp): tinygltf parses the file, this code validates every
 * reference and byte range and converts the model into the plain C structs of
 * scene_internal.h. Nothing here trusts the file: an accessor outside its
 * buffer, an index past the vertex count, a non-finite position or a bad
 * object reference ends the load with an error, never with a crash. */
#include "scene/scene_internal.h"
#include "scene/cpp_alloc.hpp"

#include "dirt/log.h"

#include "dirt/input.h"

#include <tiny_gltf.h>
#include <stb_image.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <exception>
#include <string>
#include <vector>

namespace {

/* The glTF extensions this loader honours: the one list behind both checks
 * of a parsed file (extension_check): one in extensionsRequired that is not
 * here fails the load (DIRT_SCENE_ERR_UNSUPPORTED, naming it), one in
 * extensionsUsed that is not here is ignored with a warning. An extension
 * joins the list when the loader reads it (and doc/scenes.md names it). */
const char *const supported_extensions[] = {
    "KHR_lights_punctual",             /* lights of nodes (convert_cameras_lights) */
    "KHR_materials_emissive_strength", /* emissiveStrength (convert_materials) */
    "KHR_materials_ior",               /* ior (convert_materials) */
    "KHR_materials_specular",          /* specularFactor/ColorFactor and their
                                          textures (convert_materials) */
    "KHR_materials_transmission",      /* transmissionFactor/Texture
                                          (convert_materials) */
    "KHR_mesh_quantization",           /* integer attributes (read_floats takes every
                                          component type, normalized or not) */
    "KHR_texture_transform",           /* uv transforms of the texture slots read
                                          (read_tex_transform) */
    nullptr,
};

bool extension_supported(const std::string &name)
{
    for (const char *const *e = supported_extensions; *e; e++) {
        if (name == *e)
            return true;
    }
    return false;
}

/* The distinct names of `names` the loader does not support, in order,
 * leaving out those of `skip`. */
std::vector<std::string> unsupported(const std::vector<std::string> &names,
                                     const std::vector<std::string> *skip)
{
    std::vector<std::string> out;
    for (const std::string &n : names) {
        bool dup = extension_supported(n);
        for (const std::string &o : out)
            dup |= o == n;
        for (size_t k = 0; skip && k < skip->size(); k++)
            dup |= (*skip)[k] == n;
        if (!dup)
            out.push_back(n);
    }
    return out;
}

std::string join(const std::vector<std::string> &names)
{
    std::string list;
    for (const std::string &n : names)
        list += (list.empty() ? "" : ", ") + n;
    return list;
}

/* Fails (UNSUPPORTED, logged, naming them) when extensionsRequired names
 * extensions the loader does not support; otherwise, with `warn_used`,
 * warns once about each extension of extensionsUsed that it ignores. */
bool extension_check(const tinygltf::Model &m, const char *path, bool warn_used)
{
    std::vector<std::string> req = unsupported(m.extensionsRequired, nullptr);
    if (!req.empty()) {
        std::vector<std::string> ok(supported_extensions,
                                    supported_extensions +
                                        sizeof(supported_extensions) / sizeof(char *) - 1);
        SCENE_FAIL(UNSUPPORTED,
                   "'%s' requires the glTF extension%s %s, which this loader does not "
                   "support (it supports %s)",
                   path, req.size() > 1 ? "s" : "", join(req).c_str(), join(ok).c_str());
        return false;
    }
    if (warn_used) {
        for (const std::string &e : unsupported(m.extensionsUsed, &m.extensionsRequired))
            SCENE_WARN("'%s' uses the glTF extension %s, which this loader ignores: the "
                      "scene may look different from what its author intended",
                      path, e.c_str());
    }
    return true;
}

/* Unpacked accessor: where its elements are and how to read them. */
struct AccessorView {
    const unsigned char *data = nullptr; /* first element; nullptr = all zeros */
    size_t stride = 0;
    size_t count = 0;
    int ncomp = 0;        /* components per element */
    int rows = 0;         /* components per column (matrices), else ncomp */
    size_t comp_size = 0;
    size_t column_stride = 0;
    size_t elem_size = 0;
    int comp_type = 0;
    bool normalized = false;
};

struct Loader {
    const tinygltf::Model *m = nullptr;
    dirt_scene *s = nullptr;
    std::string path;
    /* Decoded texture per (image, sRGB) pair: -2 = not tried yet. */
    std::vector<int> texture_of;
    uint32_t default_material = 0;
    bool failed = false; /* a texture failed the load (logged, id set) */
};

/* The budget of the load in progress on this thread (scene_charge). */
bool charge(size_t count, size_t each, const char *what)
{
    return scene_charge(count, each, what);
}

/* Deepest nesting of JSON objects and arrays in `n` bytes, counting brackets
 * outside strings (escaped quotes inside strings skipped); stops scanning
 * once the depth passes `limit`. Only bounds the nesting: whether the bytes
 * are valid JSON is the parser's business. */
int json_depth(const unsigned char *p, size_t n, int limit)
{
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = p[i];
        if (in_string) {
            if (c == '\\')
                i++;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > deepest) {
                deepest = depth;
                if (deepest > limit)
                    break;
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            depth--;
        }
    }
    return deepest;
}

int num_components(int type, int *rows)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: *rows = 1; return 1;
    case TINYGLTF_TYPE_VEC2: *rows = 2; return 2;
    case TINYGLTF_TYPE_VEC3: *rows = 3; return 3;
    case TINYGLTF_TYPE_VEC4: *rows = 4; return 4;
    case TINYGLTF_TYPE_MAT2: *rows = 2; return 4;
    case TINYGLTF_TYPE_MAT3: *rows = 3; return 9;
    case TINYGLTF_TYPE_MAT4: *rows = 4; return 16;
    default: *rows = 0; return 0;
    }
}

size_t component_size(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

/* Checks that [offset, offset + length) lies inside a block of `size` bytes
 * without overflowing. */
bool range_ok(size_t offset, size_t length, size_t size)
{
    return offset <= size && length <= size - offset;
}

/* Byte range of buffer view `index`, validated against its buffer. Returns
 * nullptr on success, else why it is invalid (nothing logged). */
const char *buffer_view_problem(const tinygltf::Model &m, int index,
                                const unsigned char **data, size_t *length, size_t *stride)
{
    if (index < 0 || (size_t)index >= m.bufferViews.size())
        return "buffer view out of range";
    const tinygltf::BufferView &bv = m.bufferViews[(size_t)index];
    if (bv.buffer < 0 || (size_t)bv.buffer >= m.buffers.size())
        return "buffer of the buffer view out of range";
    const tinygltf::Buffer &b = m.buffers[(size_t)bv.buffer];
    if (!range_ok(bv.byteOffset, bv.byteLength, b.data.size()))
        return "buffer view exceeds its buffer (truncated file?)";
    *data = b.data.empty() ? nullptr : b.data.data() + bv.byteOffset;
    *length = bv.byteLength;
    if (stride)
        *stride = bv.byteStride;
    return nullptr;
}

/* buffer_view_problem that logs the problem as an error. */
bool buffer_view_bytes(const tinygltf::Model &m, int index, const char *what,
                       const unsigned char **data, size_t *length, size_t *stride)
{
    const char *why = buffer_view_problem(m, index, data, length, stride);
    if (!why)
        return true;
    scene_set_error(strstr(why, "exceeds") ? DIRT_SCENE_ERR_TRUNCATED : DIRT_SCENE_ERR_REFERENCE);
    const tinygltf::BufferView *bv =
        index >= 0 && (size_t)index < m.bufferViews.size() ? &m.bufferViews[(size_t)index]
                                                           : nullptr;
    const tinygltf::Buffer *b = bv && bv->buffer >= 0 && (size_t)bv->buffer < m.buffers.size()
                                    ? &m.buffers[(size_t)bv->buffer]
                                    : nullptr;
    DIRT_ERROR("%s: bufferView %d: %s (%zu buffer views; offset %zu, length %zu, buffer "
               "%d of %zu bytes)",
               what, index, why, m.bufferViews.size(), bv ? bv->byteOffset : 0,
               bv ? bv->byteLength : 0, bv ? bv->buffer : -1, b ? b->data.size() : 0);
    return false;
}

/* Resolves accessor `index` and checks that every element lies inside its
 * buffer view. */
bool view_accessor(const tinygltf::Model &m, int index, const char *what,
                   AccessorView *v)
{
    if (index < 0 || (size_t)index >= m.accessors.size()) {
        SCENE_FAIL(REFERENCE, "%s: accessor %d out of range (%zu accessors)", what, index,
                   m.accessors.size());
        return false;
    }
    const tinygltf::Accessor &a = m.accessors[(size_t)index];
    v->ncomp = num_components(a.type, &v->rows);
    v->comp_size = component_size(a.componentType);
    if (v->ncomp == 0 || v->comp_size == 0) {
        SCENE_FAIL(TYPE, "%s: accessor %d has an invalid type %d / component type %d", what,
                   index, a.type, a.componentType);
        return false;
    }
    v->comp_type = a.componentType;
    v->normalized = a.normalized;
    v->count = a.count;
    if (v->count > SCENE_MAX_COUNT) {
        SCENE_FAIL(TOO_LARGE, "%s: accessor %d has too many elements (%zu)", what, index, v->count);
        return false;
    }
    /* Matrix columns start on 4-byte boundaries. */
    int cols = v->ncomp / v->rows;
    v->column_stride = (v->rows * v->comp_size + 3) & ~(size_t)3;
    if (cols == 1)
        v->column_stride = v->rows * v->comp_size;
    v->elem_size = v->column_stride * (size_t)cols;
    if (a.bufferView < 0) {
        v->data = nullptr; /* zeros, possibly replaced by sparse values */
        v->stride = v->elem_size;
        return true;
    }
    const unsigned char *bytes = nullptr;
    size_t length = 0, stride = 0;
    char ctx[160];
    snprintf(ctx, sizeof(ctx), "%s: accessor %d", what, index);
    if (!buffer_view_bytes(m, a.bufferView, ctx, &bytes, &length, &stride))
        return false;
    if (stride == 0)
        stride = v->elem_size;
    if (stride < v->elem_size) {
        SCENE_FAIL(RANGE, "%s: byteStride %zu is smaller than the element size %zu", ctx, stride,
                   v->elem_size);
        return false;
    }
    v->stride = stride;
    if (v->count > 0) {
        bool ok = a.byteOffset <= length && v->elem_size <= length - a.byteOffset &&
                  (v->count - 1) <= (length - a.byteOffset - v->elem_size) / stride;
        if (!ok) {
            SCENE_FAIL(RANGE, "%s: %zu elements of %zu bytes (stride %zu) from offset %zu exceed "
                       "buffer view %d of %zu bytes",
                       ctx, v->count, v->elem_size, stride, a.byteOffset, a.bufferView,
                       length);
            return false;
        }
        v->data = bytes + a.byteOffset;
    }
    return true;
}

float read_component(const unsigned char *p, int ct, bool normalized)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        memcpy(&f, p, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        uint8_t x = p[0];
        return normalized ? x / 255.0f : (float)x;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t x;
        memcpy(&x, p, 1);
        return normalized ? std::fmax(x / 127.0f, -1.0f) : (float)x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t x;
        memcpy(&x, p, 2);
        return normalized ? x / 65535.0f : (float)x;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t x;
        memcpy(&x, p, 2);
        return normalized ? std::fmax(x / 32767.0f, -1.0f) : (float)x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t x;
        memcpy(&x, p, 4);
        return normalized ? (float)(x / 4294967295.0) : (float)x;
    }
    default: return 0.0f;
    }
}

uint32_t read_uint(const unsigned char *p, int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t x;
        memcpy(&x, p, 2);
        return x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t x;
        memcpy(&x, p, 4);
        return x;
    }
    default: return 0;
    }
}

/* Element `i` of an accessor as floats (matrix padding skipped). */
void read_element(const AccessorView &v, const unsigned char *elem, float *out)
{
    int cols = v.ncomp / v.rows;
    for (int c = 0; c < cols; c++) {
        const unsigned char *col = elem + (size_t)c * v.column_stride;
        for (int r = 0; r < v.rows; r++)
            out[c * v.rows + r] = read_component(col + (size_t)r * v.comp_size, v.comp_type,
                                                 v.normalized);
    }
}

/* Applies the sparse substitution of accessor `index` (if any) to `out`,
 * which holds count * ncomp floats (as_float) or uint32s. */
bool apply_sparse(const tinygltf::Model &m, int index, const AccessorView &v,
                  const char *what, float *out_f, uint32_t *out_u)
{
    const tinygltf::Accessor &a = m.accessors[(size_t)index];
    if (!a.sparse.isSparse)
        return true;
    char ctx[160];
    snprintf(ctx, sizeof(ctx), "%s: sparse accessor %d", what, index);
    if (a.sparse.count < 0 || (size_t)a.sparse.count > v.count) {
        SCENE_FAIL(RANGE, "%s: sparse count %d out of range (accessor count %zu)", ctx,
                   a.sparse.count, v.count);
        return false;
    }
    size_t n = (size_t)a.sparse.count;
    if (n == 0)
        return true;
    size_t isz = component_size(a.sparse.indices.componentType);
    if (isz == 0 || a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
        a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) {
        SCENE_FAIL(TYPE, "%s: invalid sparse indices", ctx);
        return false;
    }
    const unsigned char *ib = nullptr, *vb = nullptr;
    size_t ilen = 0, vlen = 0;
    if (!buffer_view_bytes(m, a.sparse.indices.bufferView, ctx, &ib, &ilen, nullptr) ||
        !buffer_view_bytes(m, a.sparse.values.bufferView, ctx, &vb, &vlen, nullptr))
        return false;
    if (!range_ok((size_t)a.sparse.indices.byteOffset, n * isz, ilen) ||
        !range_ok((size_t)a.sparse.values.byteOffset, n * v.elem_size, vlen)) {
        SCENE_FAIL(RANGE, "%s: sparse indices/values exceed their buffer views", ctx);
        return false;
    }
    ib += a.sparse.indices.byteOffset;
    vb += a.sparse.values.byteOffset;
    for (size_t k = 0; k < n; k++) {
        uint32_t dst = read_uint(ib + k * isz, a.sparse.indices.componentType);
        if (dst >= v.count) {
            SCENE_FAIL(RANGE, "%s: sparse index %u >= count %zu", ctx, dst, v.count);
            return false;
        }
        const unsigned char *elem = vb + k * v.elem_size;
        if (out_f) {
            read_element(v, elem, out_f + (size_t)dst * v.ncomp);
        } else {
            for (int c = 0; c < v.ncomp; c++)
                out_u[(size_t)dst * v.ncomp + c] =
                    read_uint(elem + (size_t)c * v.comp_size, v.comp_type);
        }
    }
    return true;
}

/* Reads accessor `index` as floats (normalized integers mapped to [0,1] or
 * [-1,1]). `want_ncomp` > 0 requires that many components per element. */
bool read_floats(const tinygltf::Model &m, int index, const char *what, int want_ncomp,
                 std::vector<float> *out, AccessorView *view_out = nullptr)
{
    AccessorView v;
    if (!view_accessor(m, index, what, &v))
        return false;
    if (want_ncomp > 0 && v.ncomp != want_ncomp) {
        SCENE_FAIL(TYPE, "%s: accessor %d has %d components per element, expected %d", what,
                   index, v.ncomp, want_ncomp);
        return false;
    }
    if (!charge(v.count, (size_t)v.ncomp * sizeof(float), what))
        return false;
    out->assign(v.count * (size_t)v.ncomp, 0.0f);
    if (v.data) {
        if (v.comp_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            /* Fast path: float elements have no column padding. */
            for (size_t i = 0; i < v.count; i++)
                memcpy(out->data() + i * (size_t)v.ncomp, v.data + i * v.stride,
                       (size_t)v.ncomp * 4u);
        } else {
            for (size_t i = 0; i < v.count; i++)
                read_element(v, v.data + i * v.stride, out->data() + i * (size_t)v.ncomp);
        }
    }
    if (!apply_sparse(m, index, v, what, out->data(), nullptr))
        return false;
    if (view_out)
        *view_out = v;
    return true;
}

/* Reads an unsigned integer accessor (UNSIGNED_BYTE/SHORT/INT). */
bool read_uints(const tinygltf::Model &m, int index, const char *what, int want_ncomp,
                std::vector<uint32_t> *out)
{
    AccessorView v;
    if (!view_accessor(m, index, what, &v))
        return false;
    if (v.ncomp != want_ncomp || v.ncomp != v.rows) {
        SCENE_FAIL(TYPE, "%s: accessor %d has %d components per element, expected %d", what,
                   index, v.ncomp, want_ncomp);
        return false;
    }
    if (v.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        v.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        v.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        SCENE_FAIL(TYPE, "%s: accessor %d must hold unsigned integers (component type %d)", what,
                   index, v.comp_type);
        return false;
    }
    if (!charge(v.count, (size_t)v.ncomp * sizeof(uint32_t), what))
        return false;
    out->assign(v.count * (size_t)v.ncomp, 0u);
    if (v.data) {
        for (size_t i = 0; i < v.count; i++) {
            const unsigned char *e = v.data + i * v.stride;
            for (int c = 0; c < v.ncomp; c++)
                (*out)[i * (size_t)v.ncomp + c] = read_uint(e + (size_t)c * v.comp_size,
                                                            v.comp_type);
        }
    }
    return apply_sparse(m, index, v, what, nullptr, out->data());
}

bool all_finite(const std::vector<float> &v)
{
    for (float x : v) {
        if (!std::isfinite(x))
            return false;
    }
    return true;
}

using dirt_scene_cpp::alloc_zeroed;
using dirt_scene_cpp::decode_rgba8;
using dirt_scene_cpp::dup_array;

/* ---- textures and materials -------------------------------------------- */

/* Scene texture index for glTF texture `tex` used in colour space `srgb`,
 * decoding its image on first use; DIRT_NO_TEXTURE (warned) when missing or
 * undecodable. */
int get_texture(Loader &L, int tex, bool srgb, const char *what)
{
    const tinygltf::Model &m = *L.m;
    if (tex < 0)
        return DIRT_NO_TEXTURE;
    if ((size_t)tex >= m.textures.size()) {
        SCENE_WARN("%s: %s: texture %d out of range (%zu textures); using the factor",
                  L.path.c_str(), what, tex, m.textures.size());
        L.s->stats.textures_failed++;
        return DIRT_NO_TEXTURE;
    }
    int img = m.textures[(size_t)tex].source;
    if (img < 0 || (size_t)img >= m.images.size()) {
        SCENE_WARN("%s: %s: texture %d has no usable image (source %d); using the factor",
                  L.path.c_str(), what, tex, img);
        L.s->stats.textures_failed++;
        return DIRT_NO_TEXTURE;
    }
    int &slot = L.texture_of[(size_t)img * 2 + (srgb ? 1 : 0)];
    if (slot != -2)
        return slot;
    slot = DIRT_NO_TEXTURE;

    const tinygltf::Image &image = m.images[(size_t)img];
    const unsigned char *bytes = nullptr;
    size_t size = 0;
    std::string label = !image.name.empty() ? image.name
                        : !image.uri.empty() && image.uri.compare(0, 5, "data:") != 0
                            ? image.uri
                            : "image " + std::to_string(img);
    if (image.bufferView >= 0) {
        const char *why = buffer_view_problem(m, image.bufferView, &bytes, &size, nullptr);
        if (why) {
            SCENE_WARN("%s: image '%s': bufferView %d: %s", L.path.c_str(), label.c_str(),
                      image.bufferView, why);
            bytes = nullptr;
        }
    } else if (!image.image.empty()) {
        bytes = image.image.data();
        size = image.image.size();
    }
    if (!bytes || size == 0) {
        SCENE_WARN("%s: %s: image '%s' is missing; using the factor", L.path.c_str(), what,
                  label.c_str());
        L.s->stats.textures_failed++;
        return slot;
    }
    if (size > (size_t)INT32_MAX) {
        SCENE_WARN("%s: image '%s' is too large; using the factor", L.path.c_str(),
                  label.c_str());
        L.s->stats.textures_failed++;
        return slot;
    }
    int w = 0, h = 0;
    const char *why = "";
    /* The size the image declares, checked against the budget before a
     * pixel is decoded (dirt_scene_cpp::texture_fits). */
    int fits = dirt_scene_cpp::texture_fits(bytes, size, (L.path + ": image '" + label + "'").c_str(),
                                            &why);
    if (fits < 0) {
        L.failed = true;
        return slot;
    }
    uint8_t *rgba = fits ? decode_rgba8(bytes, size, &w, &h, &why) : nullptr;
    if (fits)
        dirt_scene_cpp::texture_decoded(bytes, size, rgba ? w : 0, rgba ? h : 0);
    if (!rgba) {
        SCENE_WARN("%s: %s: cannot decode image '%s' (%s); using the factor",
                  L.path.c_str(), what, label.c_str(), why);
        L.s->stats.textures_failed++;
        return slot;
    }

    dirt_texture *t = &L.s->textures[L.s->num_textures];
    t->width = w;
    t->height = h;
    t->rgba = rgba;
    t->srgb = srgb;
    scene_copy_name(t->name, sizeof(t->name), label.c_str());
    slot = (int)L.s->num_textures++;
    return slot;
}

/* A KHR_texture_transform of a textureInfo (its extensions `ext`) into *xf
 * (left the identity, set false, without one): offset, rotation, scale as
 * given; a member that is not a finite number (pair) is warned about and
 * keeps its default. Returns the texCoord the transform overrides with,
 * -1 when it has none. */
int read_tex_transform(Loader &L, const tinygltf::ExtensionMap &ext, const std::string &what,
                       dirt_tex_transform *xf)
{
    auto it = ext.find("KHR_texture_transform");
    if (it == ext.end() || !it->second.IsObject())
        return -1;
    const tinygltf::Value &v = it->second;
    xf->set = true;
    auto pair = [&](const char *key, float out[2]) {
        if (!v.Has(key))
            return;
        const tinygltf::Value &a = v.Get(key);
        if (a.IsArray() && a.ArrayLen() == 2 && a.Get(0).IsNumber() && a.Get(1).IsNumber() &&
            std::isfinite(a.Get(0).GetNumberAsDouble()) &&
            std::isfinite(a.Get(1).GetNumberAsDouble())) {
            out[0] = (float)a.Get(0).GetNumberAsDouble();
            out[1] = (float)a.Get(1).GetNumberAsDouble();
        } else {
            SCENE_WARN("%s: %s: invalid KHR_texture_transform %s ignored", L.path.c_str(),
                      what.c_str(), key);
        }
    };
    pair("offset", xf->offset);
    pair("scale", xf->scale);
    if (v.Has("rotation")) {
        const tinygltf::Value &r = v.Get("rotation");
        if (r.IsNumber() && std::isfinite(r.GetNumberAsDouble()))
            xf->rotation = (float)r.GetNumberAsDouble();
        else
            SCENE_WARN("%s: %s: invalid KHR_texture_transform rotation ignored",
                      L.path.c_str(), what.c_str());
    }
    if (v.Has("texCoord") && v.Get("texCoord").IsNumber())
        return (int)v.Get("texCoord").GetNumberAsDouble();
    return -1;
}

/* The scene texture of a textureInfo (index, texCoord, extensions) and, when
 * `xf` is given, its KHR_texture_transform. Only TEXCOORD_0 exists: another
 * set (the textureInfo's, or the transform's override) is warned about and
 * read as set 0. */
int texture_slot(Loader &L, int index, int tex_coord, const tinygltf::ExtensionMap &ext,
                 bool srgb, const char *slot, const std::string &mat, dirt_tex_transform *xf)
{
    if (index < 0)
        return DIRT_NO_TEXTURE;
    std::string what = "material '" + mat + "' " + slot;
    if (xf) {
        int over = read_tex_transform(L, ext, what, xf);
        if (over >= 0)
            tex_coord = over;
    }
    if (tex_coord != 0)
        SCENE_WARN("%s: %s uses TEXCOORD_%d; only TEXCOORD_0 is supported", L.path.c_str(),
                  what.c_str(), tex_coord);
    return get_texture(L, index, srgb, what.c_str());
}

int texture_slot(Loader &L, const tinygltf::TextureInfo &ti, bool srgb, const char *slot,
                 const std::string &mat, dirt_tex_transform *xf = nullptr)
{
    return texture_slot(L, ti.index, ti.texCoord, ti.extensions, srgb, slot, mat, xf);
}

float finite_or(double x, float fallback)
{
    return std::isfinite(x) ? (float)x : fallback;
}

/* A number member `key` of extension object `ext` into *out when it is
 * finite and within [lo, hi]; otherwise a warning and *out unchanged.
 * Absent: unchanged, quietly. */
void ext_number(Loader &L, const tinygltf::Value &ext, const char *key, double lo, double hi,
                const std::string &mat, float *out)
{
    if (!ext.Has(key))
        return;
    const tinygltf::Value &v = ext.Get(key);
    double x = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
    if (std::isfinite(x) && x >= lo && x <= hi)
        *out = (float)x;
    else
        SCENE_WARN("%s: material '%s': invalid %s ignored", L.path.c_str(), mat.c_str(), key);
}

/* A textureInfo member `key` of an extension object: its texture (or
 * DIRT_NO_TEXTURE), with the checks of texture_slot / get_texture (an index
 * out of range warns and keeps the factor). */
int ext_texture(Loader &L, const tinygltf::Value &ext, const char *key, bool srgb,
                const std::string &mat, dirt_tex_transform *xf)
{
    if (!ext.Has(key))
        return DIRT_NO_TEXTURE;
    const tinygltf::Value &v = ext.Get(key);
    if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsInt()) {
        SCENE_WARN("%s: material '%s': invalid %s ignored", L.path.c_str(), mat.c_str(), key);
        return DIRT_NO_TEXTURE;
    }
    tinygltf::TextureInfo ti;
    ti.index = v.Get("index").GetNumberAsInt();
    if (v.Has("texCoord") && v.Get("texCoord").IsInt())
        ti.texCoord = v.Get("texCoord").GetNumberAsInt();
    /* its own extensions (KHR_texture_transform) */
    if (v.Has("extensions") && v.Get("extensions").IsObject()) {
        const tinygltf::Value &e = v.Get("extensions");
        for (const std::string &k : e.Keys())
            ti.extensions[k] = e.Get(k);
    }
    return texture_slot(L, ti, srgb, key, mat, xf); /* range checked there */
}

/* KHR_materials_transmission, _ior, _specular of material `src` into d. */
void convert_material_exts(Loader &L, const tinygltf::Material &src, const std::string &name,
                           dirt_material *d)
{
    auto ext = src.extensions.find("KHR_materials_transmission");
    if (ext != src.extensions.end() && ext->second.IsObject()) {
        ext_number(L, ext->second, "transmissionFactor", 0.0, 1.0, name, &d->transmission);
        d->transmission_tex = ext_texture(L, ext->second, "transmissionTexture", false, name,
                                          &d->xf[DIRT_SLOT_TRANSMISSION]);
    }
    ext = src.extensions.find("KHR_materials_ior");
    if (ext != src.extensions.end() && ext->second.IsObject()) {
        float ior = d->ior;
        ext_number(L, ext->second, "ior", 0.0, INFINITY, name, &ior);
        /* glTF allows ior >= 1, or 0 (F0 = 1, the specular-glossiness
         * conversion) */
        if (ior == 0.0f || ior >= 1.0f)
            d->ior = ior;
        else
            SCENE_WARN("%s: material '%s': ior %g below 1 ignored", L.path.c_str(), name.c_str(),
                      (double)ior);
    }
    ext = src.extensions.find("KHR_materials_specular");
    if (ext != src.extensions.end() && ext->second.IsObject()) {
        const tinygltf::Value &e = ext->second;
        ext_number(L, e, "specularFactor", 0.0, 1.0, name, &d->specular);
        d->specular_tex = ext_texture(L, e, "specularTexture", false, name,
                                      &d->xf[DIRT_SLOT_SPECULAR]);
        if (e.Has("specularColorFactor")) {
            const tinygltf::Value &c = e.Get("specularColorFactor");
            bool ok = c.IsArray() && c.ArrayLen() == 3;
            float col[3];
            for (int k = 0; ok && k < 3; k++) {
                double x = c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : NAN;
                ok = std::isfinite(x) && x >= 0.0;
                col[k] = (float)x;
            }
            if (ok)
                std::memcpy(d->specular_color, col, sizeof(col));
            else
                SCENE_WARN("%s: material '%s': invalid specularColorFactor ignored",
                          L.path.c_str(), name.c_str());
        }
        d->specular_color_tex = ext_texture(L, e, "specularColorTexture", true, name,
                                            &d->xf[DIRT_SLOT_SPECULAR_COLOR]);
    }
}

void default_material(dirt_material *d, const char *name)
{
    dirt_material_default(d); /* the glTF defaults */
    scene_copy_name(d->name, sizeof(d->name), name);
}

void convert_materials(Loader &L, bool need_default)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    size_t n = m.materials.size();
    s->materials = alloc_zeroed<dirt_material>(n + 1);
    s->textures = alloc_zeroed<dirt_texture>(m.images.size() * 2);
    L.texture_of.assign(m.images.size() * 2, -2);
    for (size_t i = 0; i < n; i++) {
        const tinygltf::Material &src = m.materials[i];
        dirt_material *d = &s->materials[i];
        std::string name = src.name.empty() ? "material " + std::to_string(i) : src.name;
        default_material(d, name.c_str());
        const tinygltf::PbrMetallicRoughness &pbr = src.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4) {
            for (int k = 0; k < 4; k++)
                d->base_color[k] = finite_or(pbr.baseColorFactor[k], 1.0f);
        }
        d->metallic = finite_or(pbr.metallicFactor, 1.0f);
        d->roughness = finite_or(pbr.roughnessFactor, 1.0f);
        if (src.emissiveFactor.size() == 3) {
            for (int k = 0; k < 3; k++)
                d->emissive[k] = finite_or(src.emissiveFactor[k], 0.0f);
        }
        auto ext = src.extensions.find("KHR_materials_emissive_strength");
        if (ext != src.extensions.end() && ext->second.IsObject() &&
            ext->second.Has("emissiveStrength")) {
            const tinygltf::Value &v = ext->second.Get("emissiveStrength");
            if (v.IsNumber() && std::isfinite(v.GetNumberAsDouble()) &&
                v.GetNumberAsDouble() >= 0.0)
                d->emissive_strength = (float)v.GetNumberAsDouble();
            else
                SCENE_WARN("%s: material '%s': invalid emissiveStrength ignored",
                          L.path.c_str(), name.c_str());
        }
        d->double_sided = src.doubleSided;
        /* alphaMode / alphaCutoff (doc/light-transport.md section 1, Alpha). */
        if (src.alphaMode == "MASK") {
            d->alpha_mode = DIRT_ALPHA_MASK;
        } else if (src.alphaMode == "BLEND") {
            d->alpha_mode = DIRT_ALPHA_BLEND;
        } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
            SCENE_WARN("%s: material '%s': unknown alphaMode '%s' read as OPAQUE", L.path.c_str(),
                      name.c_str(), src.alphaMode.c_str());
        }
        if (std::isfinite(src.alphaCutoff) && src.alphaCutoff >= 0.0)
            d->alpha_cutoff = (float)src.alphaCutoff;
        else
            SCENE_WARN("%s: material '%s': invalid alphaCutoff ignored (0.5)", L.path.c_str(),
                      name.c_str());
        d->base_color_tex = texture_slot(L, pbr.baseColorTexture, true, "baseColorTexture",
                                         name, &d->xf[DIRT_SLOT_BASE_COLOR]);
        d->metallic_roughness_tex = texture_slot(L, pbr.metallicRoughnessTexture, false,
                                                 "metallicRoughnessTexture", name,
                                                 &d->xf[DIRT_SLOT_METALLIC_ROUGHNESS]);
        d->emissive_tex = texture_slot(L, src.emissiveTexture, true, "emissiveTexture", name,
                                       &d->xf[DIRT_SLOT_EMISSIVE]);
        const tinygltf::NormalTextureInfo &nt = src.normalTexture;
        d->normal_tex = texture_slot(L, nt.index, nt.texCoord, nt.extensions, false,
                                     "normalTexture", name, &d->xf[DIRT_SLOT_NORMAL]);
        if (d->normal_tex != DIRT_NO_TEXTURE) {
            d->normal_scale = finite_or(nt.scale, 1.0f);
            if (!std::isfinite(nt.scale))
                SCENE_WARN("%s: material '%s': invalid normalTexture scale read as 1",
                          L.path.c_str(), name.c_str());
        }
        convert_material_exts(L, src, name, d);
    }
    s->num_materials = n;
    L.default_material = (uint32_t)n;
    if (need_default) {
        default_material(&s->materials[n], "default");
        s->num_materials = n + 1;
    }
}

/* ---- meshes ------------------------------------------------------------- */

/* Triangle list of TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN indices. */
void convert_triangles(const std::vector<uint32_t> &idx, int mode, const char *what,
                       std::vector<uint32_t> *tris)
{
    size_t n = idx.size();
    tris->clear();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0)
            SCENE_WARN("%s: %zu indices is not a multiple of 3; the last %zu are ignored",
                      what, n, n % 3);
        tris->assign(idx.begin(), idx.begin() + (ptrdiff_t)(n - n % 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < n; i++) {
            /* Odd triangles swap their first two vertices to keep the winding. */
            if (i % 2 == 0)
                tris->insert(tris->end(), {idx[i], idx[i + 1], idx[i + 2]});
            else
                tris->insert(tris->end(), {idx[i + 1], idx[i], idx[i + 2]});
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 0; i + 2 < n; i++)
            tris->insert(tris->end(), {idx[i + 1], idx[i + 2], idx[0]});
    }
}

/* Converts one glTF primitive. Returns false on a fatal error; sets *skip
 * when the primitive holds no triangles to keep (points, lines). */
bool convert_prim(Loader &L, const tinygltf::Primitive &src, const char *what,
                  scene_prim *dst, bool *skip)
{
    const tinygltf::Model &m = *L.m;
    *skip = false;
    int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        SCENE_WARN("%s: mode %d (points/lines) is not supported; primitive skipped", what,
                  mode);
        *skip = true;
        return true;
    }
    auto attr = [&](const char *name) {
        auto it = src.attributes.find(name);
        return it == src.attributes.end() ? -1 : it->second;
    };
    int a_pos = attr("POSITION");
    if (a_pos < 0) {
        SCENE_WARN("%s: no POSITION attribute; primitive skipped", what);
        *skip = true;
        return true;
    }
    if (src.material < -1 ||
        (src.material >= 0 && (size_t)src.material >= m.materials.size())) {
        SCENE_FAIL(REFERENCE, "%s: material %d out of range (%zu materials)", what, src.material,
                   m.materials.size());
        return false;
    }
    dst->material = src.material >= 0 ? (uint32_t)src.material : L.default_material;

    std::string ctx = std::string(what) + " POSITION";
    std::vector<float> pos;
    if (!read_floats(m, a_pos, ctx.c_str(), 3, &pos))
        return false;
    if (!all_finite(pos)) {
        SCENE_FAIL(NOT_FINITE, "%s: non-finite (NaN/Inf) vertex position", what);
        return false;
    }
    size_t nv = pos.size() / 3;
    dst->num_vertices = nv;
    dst->position = (float(*)[3])dup_array(pos);

    int a_nrm = attr("NORMAL");
    if (a_nrm >= 0) {
        std::vector<float> nrm;
        ctx = std::string(what) + " NORMAL";
        if (!read_floats(m, a_nrm, ctx.c_str(), 3, &nrm))
            return false;
        if (nrm.size() != pos.size()) {
            SCENE_FAIL(RANGE, "%s: NORMAL has %zu elements, POSITION %zu", what, nrm.size() / 3, nv);
            return false;
        }
        if (!all_finite(nrm))
            SCENE_WARN("%s: non-finite normals; using flat normals", what);
        else
            dst->normal = (float(*)[3])dup_array(nrm);
    }

    int a_tan = attr("TANGENT");
    if (a_tan >= 0) {
        std::vector<float> tan;
        ctx = std::string(what) + " TANGENT";
        if (!read_floats(m, a_tan, ctx.c_str(), 4, &tan))
            return false;
        if (tan.size() / 4 != nv) {
            SCENE_FAIL(RANGE, "%s: TANGENT has %zu elements, POSITION %zu", what,
                       tan.size() / 4, nv);
            return false;
        }
        if (!all_finite(tan)) {
            SCENE_WARN("%s: non-finite tangents ignored", what);
        } else {
            for (size_t v = 0; v < nv; v++) /* w: handedness, +1 or -1 */
                tan[4 * v + 3] = tan[4 * v + 3] < 0.0f ? -1.0f : 1.0f;
            dst->tangent = (float(*)[4])dup_array(tan);
        }
    }

    int a_uv = attr("TEXCOORD_0");
    if (a_uv >= 0) {
        std::vector<float> uv;
        ctx = std::string(what) + " TEXCOORD_0";
        if (!read_floats(m, a_uv, ctx.c_str(), 2, &uv))
            return false;
        if (uv.size() / 2 != nv) {
            SCENE_FAIL(RANGE, "%s: TEXCOORD_0 has %zu elements, POSITION %zu", what, uv.size() / 2,
                       nv);
            return false;
        }
        for (float &x : uv) {
            if (!std::isfinite(x))
                x = 0.0f;
        }
        dst->uv = (float(*)[2])dup_array(uv);
    }

    int a_j = attr("JOINTS_0"), a_w = attr("WEIGHTS_0");
    if ((a_j >= 0) != (a_w >= 0)) {
        SCENE_WARN("%s: JOINTS_0 without WEIGHTS_0 (or the reverse); not skinned", what);
    } else if (a_j >= 0) {
        if (attr("JOINTS_1") >= 0)
            SCENE_WARN("%s: JOINTS_1/WEIGHTS_1 ignored (4 influences per vertex)", what);
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        ctx = std::string(what) + " JOINTS_0";
        if (!read_uints(m, a_j, ctx.c_str(), 4, &joints))
            return false;
        ctx = std::string(what) + " WEIGHTS_0";
        if (!read_floats(m, a_w, ctx.c_str(), 4, &weights))
            return false;
        if (joints.size() / 4 != nv || weights.size() / 4 != nv) {
            SCENE_FAIL(RANGE, "%s: JOINTS_0/WEIGHTS_0 counts (%zu/%zu) differ from POSITION (%zu)",
                       what, joints.size() / 4, weights.size() / 4, nv);
            return false;
        }
        dst->joints = alloc_zeroed<uint16_t[4]>(nv);
        dst->weights = alloc_zeroed<float[4]>(nv);
        size_t zero_sum = 0;
        for (size_t v = 0; v < nv; v++) {
            double sum = 0.0;
            for (int k = 0; k < 4; k++) {
                float w = weights[4 * v + k];
                uint32_t j = joints[4 * v + k];
                if (!std::isfinite(w) || w < 0.0f) {
                    SCENE_FAIL(INVALID, "%s: vertex %zu has an invalid skin weight %g", what, v,
                               (double)w);
                    return false;
                }
                if (j > UINT16_MAX) {
                    SCENE_FAIL(INDEX, "%s: vertex %zu joint %u out of range", what, v, j);
                    return false;
                }
                dst->joints[v][k] = (uint16_t)j;
                dst->weights[v][k] = w;
                sum += w;
            }
            if (sum <= 0.0) {
                /* No influence at all: bind rigidly to the first joint. */
                zero_sum++;
                dst->weights[v][0] = 1.0f;
                dst->weights[v][1] = dst->weights[v][2] = dst->weights[v][3] = 0.0f;
                L.s->stats.weights_normalized++;
            } else if (std::fabs(sum - 1.0) > 1e-6) {
                for (int k = 0; k < 4; k++)
                    dst->weights[v][k] = (float)(dst->weights[v][k] / sum);
                L.s->stats.weights_normalized++;
            }
        }
        if (zero_sum)
            SCENE_WARN("%s: %zu vertices have all skin weights zero; bound to their first "
                      "joint", what, zero_sum);
    }

    /* Morph targets. */
    size_t nt = src.targets.size();
    if (nt > 0) {
        dst->num_targets = nt;
        bool any_pos = false, any_nrm = false, any_tan = false;
        for (const auto &t : src.targets) {
            any_pos |= t.count("POSITION") > 0;
            any_nrm |= t.count("NORMAL") > 0;
            any_tan |= t.count("TANGENT") > 0 && dst->tangent;
        }
        if (nv > SCENE_MAX_COUNT / (nt ? nt : 1)) {
            SCENE_FAIL(TOO_LARGE, "%s: too many morph target vertices", what);
            return false;
        }
        if (!charge(nt * nv, (any_pos + any_nrm + any_tan) * sizeof(float[3]), what))
            return false;
        if (any_pos)
            dst->target_position = alloc_zeroed<float[3]>(nt * nv);
        if (any_nrm)
            dst->target_normal = alloc_zeroed<float[3]>(nt * nv);
        if (any_tan) /* TANGENT deltas (xyz) of a primitive that has tangents */
            dst->target_tangent = alloc_zeroed<float[3]>(nt * nv);
        for (size_t k = 0; k < nt; k++) {
            for (int which = 0; which < 3; which++) {
                const char *name = which == 0 ? "POSITION" : which == 1 ? "NORMAL" : "TANGENT";
                auto it = src.targets[k].find(name);
                if (it == src.targets[k].end() || (which == 2 && !any_tan))
                    continue;
                std::vector<float> d;
                ctx = std::string(what) + " target " + std::to_string(k) + " " + name;
                if (!read_floats(m, it->second, ctx.c_str(), 3, &d))
                    return false;
                if (d.size() != pos.size()) {
                    SCENE_FAIL(RANGE, "%s: %zu elements, POSITION has %zu", ctx.c_str(),
                               d.size() / 3, nv);
                    return false;
                }
                if (!all_finite(d)) {
                    SCENE_FAIL(NOT_FINITE, "%s: non-finite (NaN/Inf) morph target delta", ctx.c_str());
                    return false;
                }
                float(*out)[3] = which == 0 ? dst->target_position
                                 : which == 1 ? dst->target_normal : dst->target_tangent;
                memcpy(out + k * nv, d.data(), d.size() * sizeof(float));
            }
        }
    }

    /* Indices -> triangle list. */
    std::vector<uint32_t> idx;
    if (src.indices >= 0) {
        ctx = std::string(what) + " indices";
        if (!read_uints(m, src.indices, ctx.c_str(), 1, &idx))
            return false;
        for (size_t i = 0; i < idx.size(); i++) {
            if (idx[i] >= nv) {
                SCENE_FAIL(INDEX, "%s: index %zu is %u but there are only %zu vertices", what, i,
                           idx[i], nv);
                return false;
            }
        }
    } else {
        if (!charge(nv, sizeof(uint32_t), what))
            return false;
        idx.resize(nv);
        for (size_t i = 0; i < nv; i++)
            idx[i] = (uint32_t)i;
    }
    /* A strip or fan of n indices makes up to 3n triangle indices. */
    if (!charge(idx.size(), 3 * sizeof(uint32_t), what))
        return false;
    std::vector<uint32_t> tris;
    convert_triangles(idx, mode, what, &tris);
    dst->num_triangles = tris.size() / 3;
    dst->indices = dup_array(tris);

    /* A normal map needs tangents: made when the file has none. */
    if (!dst->tangent && dst->uv && L.s->materials[dst->material].normal_tex != DIRT_NO_TEXTURE) {
        if (!charge(nv, sizeof(float[4]), what))
            return false;
        if (!scene_prim_generate_tangents(dst))
            throw std::bad_alloc();
    }
    return true;
}

bool convert_meshes(Loader &L)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    s->meshes = alloc_zeroed<scene_mesh>(m.meshes.size());
    s->num_meshes = m.meshes.size();
    for (size_t i = 0; i < m.meshes.size(); i++) {
        const tinygltf::Mesh &src = m.meshes[i];
        scene_mesh *dst = &s->meshes[i];
        scene_copy_name(dst->name, sizeof(dst->name), src.name.c_str());
        dst->prims = alloc_zeroed<scene_prim>(src.primitives.size());
        size_t max_targets = 0;
        for (size_t p = 0; p < src.primitives.size(); p++) {
            char what[256];
            snprintf(what, sizeof(what), "%s: mesh %zu ('%s') primitive %zu", L.path.c_str(),
                     i, src.name.c_str(), p);
            scene_prim *pr = &dst->prims[dst->num_prims];
            bool skip = false;
            /* Count the primitive before converting so that a failure frees
             * whatever it allocated. */
            dst->num_prims++;
            if (!convert_prim(L, src.primitives[p], what, pr, &skip))
                return false;
            if (skip) {
                dst->num_prims--;
                memset(pr, 0, sizeof(*pr));
                s->stats.prims_skipped++;
                continue;
            }
            dst->num_triangles += pr->num_triangles;
            if (pr->num_targets > max_targets)
                max_targets = pr->num_targets;
        }
        dst->num_weights = max_targets;
        dst->weights = alloc_zeroed<float>(max_targets);
        if (!src.weights.empty() && src.weights.size() != max_targets)
            SCENE_WARN("%s: mesh %zu has %zu default weights for %zu morph targets",
                      L.path.c_str(), i, src.weights.size(), max_targets);
        for (size_t k = 0; k < max_targets && k < src.weights.size(); k++)
            dst->weights[k] = finite_or(src.weights[k], 0.0f);
    }
    return true;
}

/* ---- nodes, skins, cameras, lights -------------------------------------- */

bool convert_nodes(Loader &L)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    s->nodes = alloc_zeroed<scene_node>(m.nodes.size());
    s->num_nodes = m.nodes.size();
    for (size_t i = 0; i < m.nodes.size(); i++) {
        const tinygltf::Node &src = m.nodes[i];
        scene_node *d = &s->nodes[i];
        scene_copy_name(d->name, sizeof(d->name), src.name.c_str());
        d->parent = -1;
        d->mesh = src.mesh;
        d->skin = src.skin;
        d->camera = src.camera;
        d->light = -1;
        d->rotation[3] = 1.0f;
        d->scale[0] = d->scale[1] = d->scale[2] = 1.0f;
        d->children = dup_array(src.children);
        d->num_children = src.children.size();

        bool finite = true;
        auto take = [&](const std::vector<double> &v, size_t n, float *out, const char *what) {
            if (v.empty())
                return;
            if (v.size() != n) {
                SCENE_WARN("%s: node %zu: %s has %zu values, expected %zu; ignored",
                          L.path.c_str(), i, what, v.size(), n);
                return;
            }
            for (size_t k = 0; k < n; k++) {
                out[k] = (float)v[k];
                finite &= std::isfinite(out[k]);
            }
        };
        take(src.translation, 3, d->translation, "translation");
        take(src.rotation, 4, d->rotation, "rotation");
        take(src.scale, 3, d->scale, "scale");
        if (!src.matrix.empty()) {
            if (src.matrix.size() == 16) {
                d->has_matrix = true;
                take(src.matrix, 16, d->matrix, "matrix");
            } else {
                SCENE_WARN("%s: node %zu: matrix has %zu values; ignored", L.path.c_str(), i,
                          src.matrix.size());
            }
        }
        if (!finite) {
            SCENE_FAIL(NOT_FINITE, "%s: node %zu has a non-finite transform", L.path.c_str(), i);
            return false;
        }
        float q2 = d->rotation[0] * d->rotation[0] + d->rotation[1] * d->rotation[1] +
                   d->rotation[2] * d->rotation[2] + d->rotation[3] * d->rotation[3];
        if (q2 < 1e-12f) {
            SCENE_WARN("%s: node %zu has a zero rotation quaternion; identity used",
                      L.path.c_str(), i);
            d->rotation[0] = d->rotation[1] = d->rotation[2] = 0.0f;
            d->rotation[3] = 1.0f;
        } else {
            float inv = 1.0f / std::sqrt(q2);
            for (int k = 0; k < 4; k++)
                d->rotation[k] *= inv;
        }
        if (!src.weights.empty()) {
            std::vector<float> w(src.weights.size());
            for (size_t k = 0; k < w.size(); k++)
                w[k] = finite_or(src.weights[k], 0.0f);
            d->weights = dup_array(w);
            d->num_weights = w.size();
        }
        auto ext = src.extensions.find("KHR_lights_punctual");
        if (ext != src.extensions.end() && ext->second.IsObject() &&
            ext->second.Has("light")) {
            const tinygltf::Value &v = ext->second.Get("light");
            if (v.IsNumber())
                d->light = v.GetNumberAsInt();
            if (d->light < 0) {
                SCENE_FAIL(REFERENCE, "%s: node %zu: invalid KHR_lights_punctual light", L.path.c_str(), i);
                return false;
            }
        }
    }
    return true;
}

bool convert_skins(Loader &L)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    s->skins = alloc_zeroed<scene_skin>(m.skins.size());
    s->num_skins = m.skins.size();
    for (size_t i = 0; i < m.skins.size(); i++) {
        const tinygltf::Skin &src = m.skins[i];
        scene_skin *d = &s->skins[i];
        size_t nj = src.joints.size();
        d->joints = dup_array(src.joints);
        d->num_joints = nj;
        d->inverse_bind = alloc_zeroed<float[16]>(nj);
        for (size_t j = 0; j < nj; j++)
            scene_mat4_identity(d->inverse_bind[j]);
        if (src.inverseBindMatrices >= 0) {
            char what[200];
            snprintf(what, sizeof(what), "%s: skin %zu inverseBindMatrices", L.path.c_str(),
                     i);
            std::vector<float> ibm;
            if (!read_floats(m, src.inverseBindMatrices, what, 16, &ibm))
                return false;
            if (ibm.size() / 16 < nj) {
                SCENE_FAIL(RANGE, "%s: %zu matrices for %zu joints", what, ibm.size() / 16, nj);
                return false;
            }
            if (!all_finite(ibm)) {
                SCENE_FAIL(NOT_FINITE, "%s: non-finite values", what);
                return false;
            }
            memcpy(d->inverse_bind, ibm.data(), nj * 16 * sizeof(float));
        }
    }
    return true;
}

void convert_cameras_lights(Loader &L)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    s->camera_protos = alloc_zeroed<dirt_camera_def>(m.cameras.size());
    s->num_camera_protos = m.cameras.size();
    for (size_t i = 0; i < m.cameras.size(); i++) {
        const tinygltf::Camera &src = m.cameras[i];
        dirt_camera_def *d = &s->camera_protos[i];
        scene_copy_name(d->name, sizeof(d->name), src.name.c_str());
        d->node = -1;
        if (src.type == "orthographic") {
            d->type = DIRT_CAMERA_ORTHOGRAPHIC;
            d->xmag = finite_or(src.orthographic.xmag, 1.0f);
            d->ymag = finite_or(src.orthographic.ymag, 1.0f);
            d->znear = finite_or(src.orthographic.znear, 0.0f);
            d->zfar = finite_or(src.orthographic.zfar, 0.0f);
        } else {
            if (src.type != "perspective")
                SCENE_WARN("%s: camera %zu: unknown type '%s'; perspective assumed",
                          L.path.c_str(), i, src.type.c_str());
            d->type = DIRT_CAMERA_PERSPECTIVE;
            d->yfov = finite_or(src.perspective.yfov, 0.0f);
            if (!(d->yfov > 0.0f && d->yfov < 3.14159f)) {
                SCENE_WARN("%s: camera %zu: invalid yfov %g; 45 degrees used", L.path.c_str(),
                          i, (double)d->yfov);
                d->yfov = 0.785398163f;
            }
            d->aspect = finite_or(src.perspective.aspectRatio, 0.0f);
            d->znear = finite_or(src.perspective.znear, 0.0f);
            d->zfar = finite_or(src.perspective.zfar, 0.0f);
        }
    }
    s->light_protos = alloc_zeroed<dirt_light_def>(m.lights.size());
    s->num_light_protos = m.lights.size();
    for (size_t i = 0; i < m.lights.size(); i++) {
        const tinygltf::Light &src = m.lights[i];
        dirt_light_def *d = &s->light_protos[i];
        scene_copy_name(d->name, sizeof(d->name), src.name.c_str());
        d->node = -1;
        if (src.type == "directional") {
            d->type = DIRT_LIGHT_DIRECTIONAL;
        } else if (src.type == "spot") {
            d->type = DIRT_LIGHT_SPOT;
        } else {
            if (src.type != "point")
                SCENE_WARN("%s: light %zu: unknown type '%s'; point assumed", L.path.c_str(),
                          i, src.type.c_str());
            d->type = DIRT_LIGHT_POINT;
        }
        for (int k = 0; k < 3; k++)
            d->color[k] = src.color.size() == 3 ? finite_or(src.color[k], 1.0f) : 1.0f;
        d->intensity = finite_or(src.intensity, 1.0f);
        d->range = finite_or(src.range, 0.0f);
        d->inner_cone = finite_or(src.spot.innerConeAngle, 0.0f);
        d->outer_cone = finite_or(src.spot.outerConeAngle, 0.785398163f);
    }
}

/* ---- animations --------------------------------------------------------- */

bool convert_sampler(Loader &L, const tinygltf::AnimationSampler &src, size_t width,
                     bool quat, const char *what, scene_sampler *d)
{
    const tinygltf::Model &m = *L.m;
    if (src.interpolation == "STEP") {
        d->interp = SCENE_INTERP_STEP;
    } else if (src.interpolation == "CUBICSPLINE") {
        d->interp = SCENE_INTERP_CUBIC;
    } else {
        if (src.interpolation != "LINEAR")
            SCENE_WARN("%s: unknown interpolation '%s'; LINEAR used", what,
                      src.interpolation.c_str());
        d->interp = SCENE_INTERP_LINEAR;
    }
    std::vector<float> times, values;
    std::string ctx = std::string(what) + " input";
    if (!read_floats(m, src.input, ctx.c_str(), 1, &times))
        return false;
    ctx = std::string(what) + " output";
    if (!read_floats(m, src.output, ctx.c_str(), 0, &values))
        return false;
    if (times.empty()) {
        SCENE_FAIL(INVALID, "%s: no keyframes", what);
        return false;
    }
    for (size_t k = 0; k < times.size(); k++) {
        if (!std::isfinite(times[k]) || (k > 0 && times[k] < times[k - 1])) {
            SCENE_FAIL(INVALID, "%s: key times must be finite and increasing (key %zu)", what, k);
            return false;
        }
    }
    if (!all_finite(values)) {
        SCENE_FAIL(NOT_FINITE, "%s: non-finite output values", what);
        return false;
    }
    size_t per_key = width * (d->interp == SCENE_INTERP_CUBIC ? 3 : 1);
    if (values.size() / per_key < times.size()) {
        SCENE_FAIL(RANGE, "%s: %zu output values for %zu keys of %zu values", what, values.size(),
                   times.size(), per_key);
        return false;
    }
    values.resize(times.size() * per_key);
    if (quat && d->interp != SCENE_INTERP_CUBIC) {
        for (size_t k = 0; k < times.size(); k++) {
            float *q = &values[4 * k];
            float l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            if (l > 1e-12f) {
                for (int c = 0; c < 4; c++)
                    q[c] /= l;
            } else {
                q[0] = q[1] = q[2] = 0.0f;
                q[3] = 1.0f;
            }
        }
    }
    d->num_keys = times.size();
    d->width = width;
    d->times = dup_array(times);
    d->values = dup_array(values);
    return true;
}

bool convert_animations(Loader &L)
{
    const tinygltf::Model &m = *L.m;
    dirt_scene *s = L.s;
    s->clips = alloc_zeroed<scene_clip>(m.animations.size());
    s->num_clips = m.animations.size();
    for (size_t a = 0; a < m.animations.size(); a++) {
        const tinygltf::Animation &src = m.animations[a];
        scene_clip *clip = &s->clips[a];
        std::string name = src.name.empty() ? "animation " + std::to_string(a) : src.name;
        scene_copy_name(clip->name, sizeof(clip->name), name.c_str());
        /* One sampler per channel (a shared glTF sampler is duplicated). */
        clip->channels = alloc_zeroed<scene_channel>(src.channels.size());
        clip->samplers = alloc_zeroed<scene_sampler>(src.channels.size());
        for (size_t c = 0; c < src.channels.size(); c++) {
            const tinygltf::AnimationChannel &ch = src.channels[c];
            char what[300];
            snprintf(what, sizeof(what), "%s: animation %zu ('%s') channel %zu",
                     L.path.c_str(), a, name.c_str(), c);
            if (ch.target_node < 0) {
                SCENE_WARN("%s: no target node; ignored", what);
                continue;
            }
            if ((size_t)ch.target_node >= s->num_nodes) {
                SCENE_FAIL(REFERENCE, "%s: target node %d out of range (%zu nodes)", what,
                           ch.target_node, s->num_nodes);
                return false;
            }
            if (ch.sampler < 0 || (size_t)ch.sampler >= src.samplers.size()) {
                SCENE_FAIL(REFERENCE, "%s: sampler %d out of range (%zu samplers)", what, ch.sampler,
                           src.samplers.size());
                return false;
            }
            const scene_node *node = &s->nodes[ch.target_node];
            enum scene_path path;
            size_t width;
            if (ch.target_path == "translation") {
                path = SCENE_PATH_TRANSLATION;
                width = 3;
            } else if (ch.target_path == "rotation") {
                path = SCENE_PATH_ROTATION;
                width = 4;
            } else if (ch.target_path == "scale") {
                path = SCENE_PATH_SCALE;
                width = 3;
            } else if (ch.target_path == "weights") {
                path = SCENE_PATH_WEIGHTS;
                if (node->mesh < 0 || (size_t)node->mesh >= s->num_meshes ||
                    s->meshes[node->mesh].num_weights == 0) {
                    SCENE_WARN("%s: weights of node %d, which has no morph targets; ignored",
                              what, ch.target_node);
                    continue;
                }
                width = s->meshes[node->mesh].num_weights;
            } else {
                SCENE_WARN("%s: unsupported path '%s'; ignored", what, ch.target_path.c_str());
                continue;
            }
            if (node->has_matrix && path != SCENE_PATH_WEIGHTS) {
                SCENE_WARN("%s: node %d is defined by a matrix and cannot be animated; "
                          "ignored", what, ch.target_node);
                continue;
            }
            scene_sampler *smp = &clip->samplers[clip->num_samplers];
            clip->num_samplers++; /* counted first so that a failure frees it */
            if (!convert_sampler(L, src.samplers[(size_t)ch.sampler], width,
                                 path == SCENE_PATH_ROTATION, what, smp))
                return false;
            scene_channel *dc = &clip->channels[clip->num_channels++];
            dc->node = ch.target_node;
            dc->path = path;
            dc->sampler = (int)(clip->num_samplers - 1);
            float last = smp->times[smp->num_keys - 1];
            if (last > clip->duration)
                clip->duration = last;
        }
    }
    return true;
}

/* ---- file reading ------------------------------------------------------- */

/* Keeps encoded image bytes for decoding on first use (only the images that
 * materials reference get decoded, and a bad image only warns). Images in
 * buffer views are read later, with range checks. The copy is charged to
 * the budget (an external file's own bytes were charged when read). */
bool keep_encoded_image(tinygltf::Image *image, const int index, std::string *err, std::string *,
                        int, int, const unsigned char *bytes, int size, void *)
{
    if (image->bufferView >= 0)
        return true;
    if (bytes && size > 0) {
        if (!charge((size_t)size, 1, "an image's encoded bytes")) {
            if (err)
                *err += "image " + std::to_string(index) + ": load budget exceeded\n";
            return false;
        }
        image->image.assign(bytes, bytes + size);
    }
    image->as_is = true;
    return true;
}

/* A message of a parser, fit to print: the excerpt of the input some
 * messages end with ("; last read: '...'", nlohmann's) removed, a data URI
 * cut after its header, other bytes outside printable ASCII shown as '?',
 * at most 300 bytes. Messages never echo a file's contents beyond the names
 * and URIs a scene gives. */
std::string printable(const std::string &line)
{
    std::string t = line;
    size_t cut = t.find("; last read:");
    if (cut != std::string::npos)
        t.erase(cut);
    size_t data = t.find("data:");
    if (data != std::string::npos) {
        size_t comma = t.find(',', data);
        size_t end = comma == std::string::npos ? t.size() : comma + 1;
        size_t stop = t.find_first_of(" '\"", end);
        t.replace(end, (stop == std::string::npos ? t.size() : stop) - end, "...");
    }
    for (char &c : t) {
        if ((unsigned char)c < 32 || (unsigned char)c > 126)
            c = '?';
    }
    if (t.size() > 300)
        t = t.substr(0, 297) + "...";
    return t;
}

void log_lines(bool error, const char *path, const std::string &text)
{
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        if (end > start) {
            std::string line = printable(text.substr(start, end - start));
            if (error)
                DIRT_ERROR("%s: %s", path, line.c_str());
            else
                SCENE_WARN("%s: %s", path, line.c_str());
        }
        start = end + 1;
    }
}

std::string file_stem(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    size_t dot = base.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* File-system callbacks for models parsed from memory: every external
 * reference (a buffer or image URI that is not a data URI) fails, so that a
 * model from memory never reads files. */
/* Claims that every file exists, so that tinygltf goes on to no_read_file
 * and its message says why the reference cannot be used. */
bool any_file_exists(const std::string &, void *)
{
    return true;
}

std::string no_expand(const std::string &path, void *)
{
    return path;
}

bool no_read_file(std::vector<unsigned char> *, std::string *err, const std::string &path,
                  void *)
{
    if (err)
        *err += "external file '" + path + "' cannot be read by a scene loaded from memory\n";
    return false;
}

bool no_write_file(std::string *err, const std::string &, const std::vector<unsigned char> &,
                   void *)
{
    if (err)
        *err += "writing is not supported\n";
    return false;
}

/* File-system callbacks for a model read from a file: a URI resolves in the
 * scene's folder only (tinygltf also tries the working directory: refused
 * here), must stay in it (scene_read_ref_file: OUTSIDE), be a regular file
 * within the budget (NOT_REGULAR, TOO_LARGE); what is read is charged and
 * listed (dirt_scene_file). `user` is the FileFs. */
struct FileFs {
    std::string label;   /* the scene file */
    std::string dir;     /* the scene's folder, as tinygltf joins it */
    std::string refused; /* the last path refused (said once) */
};

/* The URI as the file names it: `path` without the folder tinygltf joined. */
std::string uri_of(const FileFs &fs, const std::string &path)
{
    std::string pre = fs.dir.empty() || fs.dir.back() == '/' ? fs.dir : fs.dir + "/";
    return path.compare(0, pre.size(), pre) == 0 ? path.substr(pre.size()) : path;
}

bool in_folder_candidate(const FileFs &fs, const std::string &path)
{
    std::string pre = fs.dir.empty() || fs.dir.back() == '/' ? fs.dir : fs.dir + "/";
    return path.compare(0, pre.size(), pre) == 0;
}

bool file_exists(const std::string &path, void *user)
{
    FileFs &fs = *(FileFs *)user;
    if (!in_folder_candidate(fs, path))
        return false; /* tinygltf's second try, the working directory */
    if (!scene_load_opts()->allow_outside && !dirt_input_inside(fs.dir.c_str(), path.c_str())) {
        if (fs.refused != path) {
            fs.refused = path;
            SCENE_FAIL(OUTSIDE, "'%s': the URI '%s' leads outside the scene's folder '%s': "
                       "refused (--allow-outside-paths, dirt_load_opts.allow_outside, permits "
                       "it)", fs.label.c_str(), printable(uri_of(fs, path)).c_str(),
                       fs.dir.c_str());
        }
        return false;
    }
    return access(path.c_str(), F_OK) == 0;
}

bool read_file_cb(std::vector<unsigned char> *out, std::string *err, const std::string &path,
                  void *user)
{
    FileFs &fs = *(FileFs *)user;
    size_t n = 0;
    bool missing = false;
    std::string uri = printable(uri_of(fs, path));
    unsigned char *data = scene_read_ref_file(path.c_str(), uri.c_str(), "URI", 1, &n, &missing);
    if (!data) {
        if (err)
            *err += missing ? "not found\n" : "refused (see above)\n";
        return false;
    }
    try {
        out->assign(data, data + n);
    } catch (...) {
        free(data);
        throw;
    }
    free(data);
    return true;
}

/* What a .gltf's JSON costs the parsers, counted on its bytes before they
 * parse it (json_cost): nlohmann's document holds a node per value (an
 * value, and one more per object member (nlohmann's and tinygltf's map
 * nodes), and tinygltf a tinygltf::Value per value of extras and
 * extensions; tinygltf also makes one struct per element of
 * the arrays it reads (a material is about 2 KiB), in vectors that hold up
 * to three times their size while they grow (the old array and the new one
 * of twice the size). The strings' bytes are charged with
 * the file (json_string_copies). Measured against the peak of the parse
 * (doc/scenes.md, "Memory"). */
const size_t json_value_cost = 256;
const size_t json_member_cost = 256;
const size_t json_string_copies = 7;

struct ElementKind {
    const char *parent; /* nullptr: a top-level array */
    const char *key;
    size_t size;
};
const ElementKind element_kinds[] = {
    {nullptr, "accessors", sizeof(tinygltf::Accessor)},
    {nullptr, "animations", sizeof(tinygltf::Animation)},
    {nullptr, "buffers", sizeof(tinygltf::Buffer)},
    {nullptr, "bufferViews", sizeof(tinygltf::BufferView)},
    {nullptr, "cameras", sizeof(tinygltf::Camera)},
    {nullptr, "images", sizeof(tinygltf::Image)},
    {nullptr, "materials", sizeof(tinygltf::Material)},
    {nullptr, "meshes", sizeof(tinygltf::Mesh)},
    {nullptr, "nodes", sizeof(tinygltf::Node)},
    {nullptr, "samplers", sizeof(tinygltf::Sampler)},
    {nullptr, "scenes", sizeof(tinygltf::Scene)},
    {nullptr, "skins", sizeof(tinygltf::Skin)},
    {nullptr, "textures", sizeof(tinygltf::Texture)},
    {"meshes", "primitives", sizeof(tinygltf::Primitive)},
    {"animations", "channels", sizeof(tinygltf::AnimationChannel)},
    {"animations", "samplers", sizeof(tinygltf::AnimationSampler)},
    {"KHR_lights_punctual", "lights", sizeof(tinygltf::Light)},
};
const size_t num_element_kinds = sizeof(element_kinds) / sizeof(element_kinds[0]);

struct JsonFrame {
    bool object;
    int kind;        /* element_kinds index of this array's elements, -1 */
    std::string key; /* objects: the member being read */
};

/* The element kind of an array opening as the member stack.back().key:
 * a top-level member (the root object alone on the stack), a member of an
 * element of a top-level array (its kind the parent), or the lights of
 * the root's extensions.KHR_lights_punctual. -1 for any other array. */
int element_kind(const std::vector<JsonFrame> &stack)
{
    const std::string &key = stack.back().key;
    size_t d = stack.size();
    for (size_t e = 0; e < num_element_kinds; e++) {
        const ElementKind &ek = element_kinds[e];
        if (key != ek.key)
            continue;
        if (!ek.parent && d == 1)
            return (int)e;
        if (ek.parent && d == 3 && !stack[1].object && stack[1].kind >= 0 &&
            !strcmp(element_kinds[stack[1].kind].key, ek.parent) &&
            !element_kinds[stack[1].kind].parent)
            return (int)e;
        if (ek.parent && d == 3 && stack[1].object && stack[0].key == "extensions" &&
            stack[1].key == ek.parent)
            return (int)e;
    }
    return -1;
}

/* Bytes the parsers will hold for `n` bytes of JSON (beyond the bytes
 * themselves): json_value_cost per value, json_member_cost per object
 * member, and per element of the arrays of
 * element_kinds three times its struct's size. Scans like json_depth (strings
 * skipped, escapes honoured); nesting is already bounded. Saturates at
 * SIZE_MAX. */
size_t json_cost(const unsigned char *p, size_t n)
{
    std::vector<JsonFrame> stack;
    size_t cost = 0;
    auto add = [&cost](size_t c) { cost = c > SIZE_MAX - cost ? SIZE_MAX : cost + c; };
    for (size_t i = 0; i < n; i++) {
        unsigned char c = p[i];
        if (c == '"') {
            size_t j = i + 1;
            while (j < n && p[j] != '"')
                j += p[j] == '\\' ? 2 : 1;
            /* A member name (the next token a colon) is kept for kinds. */
            size_t k = j + 1;
            while (k < n && (p[k] == ' ' || p[k] == '\t' || p[k] == '\n' || p[k] == '\r'))
                k++;
            bool name = k < n && p[k] == ':';
            if (name && !stack.empty() && stack.back().object) {
                size_t len = j > i + 1 ? std::min(j, n) - i - 1 : 0;
                stack.back().key.assign((const char *)p + i + 1, std::min<size_t>(len, 32));
                add(json_member_cost);
            } else {
                add(json_value_cost);
            }
            i = j;
        } else if (c == '{' || c == '[') {
            add(json_value_cost);
            int kind = -1;
            if (c == '[' && !stack.empty() && stack.back().object)
                kind = element_kind(stack);
            if (c == '{' && !stack.empty() && !stack.back().object && stack.back().kind >= 0)
                add(3 * element_kinds[stack.back().kind].size);
            stack.push_back(JsonFrame{c == '{', kind, std::string()});
        } else if (c == '}' || c == ']') {
            if (!stack.empty())
                stack.pop_back();
        } else if ((c >= '0' && c <= '9') || c == '-' || c == 't' || c == 'f' || c == 'n') {
            /* a number or a literal: one value, its bytes skipped */
            add(json_value_cost);
            while (i + 1 < n && p[i + 1] != ',' && p[i + 1] != ']' && p[i + 1] != '}' &&
                   p[i + 1] != ' ' && p[i + 1] != '\n' && p[i + 1] != '\t' && p[i + 1] != '\r')
                i++;
        }
    }
    return cost;
}

/* Charges what parsing `n` bytes of JSON will hold (json_cost and the
 * strings' copies); false (logged, TOO_LARGE) when it does not fit. */
bool charge_json(const unsigned char *json, size_t n, const char *path)
{
    char what[4200];
    snprintf(what, sizeof(what), "'%s': the JSON's values and objects", path);
    if (!charge(json_cost(json, n), 1, what))
        return false;
    snprintf(what, sizeof(what), "'%s': the JSON's strings", path);
    return charge(n, json_string_copies, what);
}

/* Parses `size` bytes of .gltf JSON or .glb (told apart by the "glTF" magic)
 * into `model`. `label` names the data in messages. External URIs resolve
 * against `base_dir`, or always fail when `base_dir` is NULL. */
/* Fails (TOO_DEEP, logged) when `n` bytes of JSON nest deeper than
 * `limit`: tinygltf and nlohmann recurse once per level, so this runs
 * before either sees the bytes. */
bool depth_ok(const unsigned char *json, size_t n, int limit, const char *path)
{
    int d = json_depth(json, n, limit);
    if (d <= limit)
        return true;
    SCENE_FAIL(TOO_DEEP,
               "'%s': JSON nested deeper than %d levels (dirt_load_opts.max_depth)", path,
               limit);
    return false;
}

/* glTF 2.0 only: asset.version's major number must be 2 and minVersion, if
 * given, at most 2.0 (glTF 2.0, "Versioning"); VERSION, logged, otherwise. */
bool version_ok(const tinygltf::Model &m, const char *path)
{
    const std::string &v = m.asset.version, &mv = m.asset.minVersion;
    bool major2 = v.size() >= 2 && v[0] == '2' && v[1] == '.';
    bool min_ok = mv.empty() || mv == "2.0";
    if (major2 && min_ok)
        return true;
    SCENE_FAIL(VERSION,
               "'%s': asset.version '%s'%s%s%s: this loader reads glTF 2.0 only (a glTF 1.0 file "
               "needs converting)",
               path, printable(v).c_str(), mv.empty() ? "" : ", minVersion '",
               mv.empty() ? "" : printable(mv).c_str(), mv.empty() ? "" : "'");
    return false;
}

bool parse_bytes(const unsigned char *bytes, size_t size, const char *label,
                 const char *base_dir, const dirt_load_opts *opts, tinygltf::Model *model)
{
    const char *path = label;
    if (size == 0) {
        SCENE_FAIL(EMPTY, "'%s' is empty", path);
        return false;
    }
    if (size > UINT32_MAX) {
        SCENE_FAIL(TOO_LARGE, "'%s' is larger than 4 GiB", path);
        return false;
    }

    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(keep_encoded_image, nullptr);
    FileFs file_fs;
    tinygltf::FsCallbacks fs = {};
    if (!base_dir) {
        fs.FileExists = any_file_exists;
        fs.ExpandFilePath = no_expand;
        fs.ReadWholeFile = no_read_file;
        fs.WriteWholeFile = no_write_file;
        fs.user_data = nullptr;
    } else {
        file_fs.label = label;
        file_fs.dir = base_dir;
        fs.FileExists = file_exists;
        fs.ExpandFilePath = no_expand;
        fs.ReadWholeFile = read_file_cb;
        fs.WriteWholeFile = no_write_file;
        fs.user_data = &file_fs;
    }
    gltf.SetFsCallbacks(fs);
    std::string dir = base_dir ? base_dir : "";
    std::string err, warn;
    bool ok;
    bool binary = size >= 4 && memcmp(bytes, "glTF", 4) == 0;
    if (binary) {
        if (size < 20) {
            SCENE_FAIL(TRUNCATED, "'%s': truncated .glb (%zu bytes, header needs 20)", path, size);
            return false;
        }
        uint32_t version = le32(&bytes[4]);
        uint32_t length = le32(&bytes[8]);
        uint32_t json_len = le32(&bytes[12]);
        if (version != 2) {
            SCENE_FAIL(VERSION, "'%s': a .glb of version %u: this loader reads glTF 2.0 (.glb "
                       "version 2) only", path, version);
            return false;
        }
        if (length > size) {
            SCENE_FAIL(TRUNCATED, "'%s': truncated .glb: header says %u bytes, file has %zu", path,
                       length, size);
            return false;
        }
        if ((uint64_t)json_len + 20u > length) {
            SCENE_FAIL(TRUNCATED, "'%s': truncated .glb: JSON chunk of %u bytes exceeds the file", path,
                       json_len);
            return false;
        }
        uint32_t bin_len = 0;
        if (length >= (uint64_t)json_len + 28u) {
            bin_len = le32(&bytes[20 + json_len]);
            if ((uint64_t)json_len + 28u + bin_len > length) {
                SCENE_FAIL(TRUNCATED, "'%s': truncated .glb: BIN chunk of %u bytes exceeds the file",
                           path, bin_len);
                return false;
            }
        }
        /* tinygltf copies the BIN chunk into its buffer. */
        if (!depth_ok(bytes + 20, json_len, opts->max_depth, path) ||
            !charge_json(bytes + 20, json_len, path) || !charge(bin_len, 1, "the .glb's BIN chunk"))
            return false;
        ok = gltf.LoadBinaryFromMemory(model, &err, &warn, bytes, (unsigned int)size, dir);
    } else {
        if (!depth_ok(bytes, size, opts->max_depth, path) || !charge_json(bytes, size, path))
            return false;
        ok = gltf.LoadASCIIFromString(model, &err, &warn, (const char *)bytes,
                                      (unsigned int)size, dir);
    }
    log_lines(false, path, warn);
    /* A file refused by the callbacks (outside the folder, not a regular
     * file, over the budget) fails the load, also when tinygltf only warned
     * (an image). */
    if (scene_error_get() != DIRT_SCENE_ERR_OK) {
        if (!ok)
            log_lines(true, path, err);
        DIRT_ERROR("cannot load '%s'", path);
        return false;
    }
    /* tinygltf reads extensionsRequired before anything that may fail, so
     * an unsupported extension is the reason given even when what it
     * changes (an image format, compressed buffers) broke the parse. */
    if (!extension_check(*model, path, ok)) {
        if (!ok)
            log_lines(true, path, err);
        DIRT_ERROR("cannot load '%s'", path);
        return false;
    }
    if (!ok) {
        if (err.empty())
            err = "tinygltf could not parse the file";
        /* tinygltf's messages are all the id can come from here. */
        if (err.find("external file") != std::string::npos ||
            err.find("not found") != std::string::npos ||
            err.find("Failed to load external") != std::string::npos ||
            err.find("File read error") != std::string::npos)
            scene_set_error(DIRT_SCENE_ERR_EXTERNAL);
        else if (err.find("ize mismatch") != std::string::npos ||
                 err.find("binary size") != std::string::npos ||
                 err.find("Invalid binary data") != std::string::npos)
            scene_set_error(DIRT_SCENE_ERR_TRUNCATED);
        else if (err.find("invalid bufferView") != std::string::npos)
            scene_set_error(DIRT_SCENE_ERR_REFERENCE);
        else
            scene_set_error(DIRT_SCENE_ERR_SYNTAX);
        log_lines(true, path, err);
        DIRT_ERROR("cannot load '%s'", path);
        return false;
    }
    if (!version_ok(*model, path)) {
        DIRT_ERROR("cannot load '%s'", path);
        return false;
    }
    return true;
}

/* True when `name` ends in `ext` (".gltf"), in any case. */
bool has_ext(const std::string &name, const char *ext)
{
    size_t m = strlen(ext);
    if (name.size() < m)
        return false;
    for (size_t i = 0; i < m; i++) {
        char c = name[name.size() - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != ext[i])
            return false;
    }
    return true;
}

bool parse_model(const char *path, const dirt_load_opts *opts, tinygltf::Model *model)
{
    size_t size = 0;
    unsigned char *bytes = scene_read_scene_file(path, 1, &size);
    if (!bytes)
        return false;
    std::string p(path);
    /* A name that is not .gltf/.glb is read when its bytes are glTF: the
     * .glb magic, or a JSON object. */
    if (!has_ext(p, ".gltf") && !has_ext(p, ".glb")) {
        size_t k = 0;
        while (k < size && (bytes[k] == ' ' || bytes[k] == '\t' || bytes[k] == '\n' ||
                            bytes[k] == '\r'))
            k++;
        bool gltf = (size >= 4 && memcmp(bytes, "glTF", 4) == 0) || (k < size && bytes[k] == '{');
        if (!gltf) {
            size_t slash = p.find_last_of('/'), dot = p.find_last_of('.');
            std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                                  ? std::string("(none)")
                                  : printable(p.substr(dot));
            SCENE_FAIL(FORMAT, "'%s': unsupported format (extension %s; neither glTF nor OBJ): "
                       "the loader reads glTF 2.0 (.gltf, .glb) and Wavefront OBJ (.obj)",
                       path, ext.c_str());
            free(bytes);
            return false;
        }
    }
    size_t slash = p.find_last_of('/');
    std::string base_dir = slash == std::string::npos ? "." : p.substr(0, slash);
    if (base_dir.empty())
        base_dir = "/";
    bool ok;
    try {
        ok = parse_bytes(bytes, size, path, base_dir.c_str(), opts, model);
    } catch (...) {
        free(bytes);
        throw;
    }
    free(bytes);
    return ok;
}

/* Destroys the scene under construction unless released (also when a
 * conversion step throws). */
struct SceneGuard {
    dirt_scene *s;
    ~SceneGuard() { dirt_scene_destroy(s); }
    dirt_scene *release()
    {
        dirt_scene *r = s;
        s = nullptr;
        return r;
    }
};

bool convert(Loader &L, const tinygltf::Model &model, const char *path)
{
    bool need_default = false;
    for (const auto &mesh : model.meshes) {
        for (const auto &p : mesh.primitives)
            need_default |= p.material < 0;
    }

    /* The default scene, else scene 0, else (no scenes) every root node. */
    static const int no_roots = 0;
    std::vector<int> roots;
    const int *roots_ptr = nullptr;
    if (!model.scenes.empty()) {
        int sc = model.defaultScene;
        if (sc >= 0 && (size_t)sc >= model.scenes.size()) {
            SCENE_FAIL(REFERENCE, "%s: default scene %d out of range (%zu scenes)", path, sc,
                       model.scenes.size());
            return false;
        }
        if (sc < 0)
            sc = 0;
        roots = model.scenes[(size_t)sc].nodes;
        roots_ptr = roots.empty() ? &no_roots : roots.data();
    }

    convert_materials(L, need_default);
    if (L.failed || !convert_meshes(L) || !convert_nodes(L) || !convert_skins(L))
        return false;
    convert_cameras_lights(L);
    if (!convert_animations(L))
        return false;
    if (!scene_finalize(L.s, roots_ptr, roots.size()))
        return false;
    /* One evaluated frame: 3 corners x (position, normal, uv) + material and
     * instance per triangle (dirt_frame), for every instanced triangle. */
    const size_t frame_bytes = 3 * (sizeof(float[3]) * 2 + sizeof(float[2])) + 2 * sizeof(uint32_t);
    return charge(L.s->num_triangles, frame_bytes, "the evaluated frame's triangles");
}

/* Converts a parsed model into a finalized scene named `name`; `label`
 * names the source in messages. */
dirt_scene *convert_model(const tinygltf::Model &model, const char *label, const char *name)
{
    SceneGuard guard{scene_new(name)};
    if (!guard.s)
        return nullptr;
    Loader L;
    L.m = &model;
    L.s = guard.s;
    L.path = label;
    if (!convert(L, model, label)) {
        DIRT_ERROR("cannot load '%s'", label);
        return nullptr;
    }
    return guard.release();
}

dirt_scene *load(const char *path, const dirt_load_opts *opts)
{
    tinygltf::Model model;
    if (!parse_model(path, opts, &model))
        return nullptr;
    return convert_model(model, path, file_stem(path).c_str());
}

dirt_scene *load_memory(const void *data, size_t size, const char *label,
                        const dirt_load_opts *opts)
{
    tinygltf::Model model;
    if (!parse_bytes((const unsigned char *)data, size, label, nullptr, opts, &model))
        return nullptr;
    return convert_model(model, label, file_stem(label).c_str());
}

} // namespace

extern "C" const char *const *dirt_scene_gltf_extensions(void)
{
    return supported_extensions;
}

extern "C" dirt_scene *scene_load_gltf(const char *path, const dirt_load_opts *opts)
{
    try {
        return load(path, opts);
    } catch (const std::bad_alloc &) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory loading '%s'", path);
    } catch (const std::exception &e) {
        DIRT_ERROR("cannot load '%s': %s", path, e.what());
    } catch (...) {
        DIRT_ERROR("cannot load '%s': unknown error", path);
    }
    return nullptr;
}

extern "C" dirt_scene *scene_load_gltf_memory(const void *data, size_t size, const char *label,
                                              const dirt_load_opts *opts)
{
    try {
        return load_memory(data, size, label, opts);
    } catch (const std::bad_alloc &) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory loading '%s'", label);
    } catch (const std::exception &e) {
        DIRT_ERROR("cannot load '%s': %s", label, e.what());
    } catch (...) {
        DIRT_ERROR("cannot load '%s': unknown error", label);
    }
    return nullptr;
}
