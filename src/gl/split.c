/* Split arrays (split.h): one storage block while it fits, else texel-buffer
 * parts. */
#include "gl/split.h"

#include "gl/program.h"
#include "common/layout.h"

#include <stdio.h>
#include <string.h>

const gl_split_desc gl_split_vertices = {
    .label = "scene's vertices", .define = "DIRT_SPLIT_VERTICES",
    .record_bytes = 3 * sizeof(struct dirt_gpu_vertex),
    .format = GL_RGBA32F, .binding = DIRT_BIND_VERTICES, .unit = DIRT_UNIT_SPLIT_VERTICES,
    .advice = "render a scene of fewer triangles",
};
const gl_split_desc gl_split_prim_material = {
    .label = "scene's per-primitive materials", .define = "DIRT_SPLIT_PRIM_MATERIAL",
    .record_bytes = 4, .format = GL_R32UI, .binding = DIRT_BIND_PRIM_MATERIAL,
    .unit = DIRT_UNIT_SPLIT_PRIM_MATERIAL, .advice = "render a scene of fewer triangles",
};

const gl_split_desc gl_split_depth = {
    .label = "depth bounds and their pyramid", .define = "DIRT_SPLIT_DEPTH",
    .record_bytes = DIRT_DEPTH_ENTRY_BYTES, .format = GL_R32UI, .image = true,
    .binding = DIRT_BIND_DEPTH, .unit = DIRT_IMAGE_SPLIT_DEPTH, .readback = true,
    .advice = "use smaller views (-W/-H, --face-size), fewer views (--views) or, for dirt, "
              "larger tiles (-S)",
};

size_t gl_split_texel_bytes(GLenum format)
{
    switch (format) {
    case GL_RGBA32F:
    case GL_RGBA32UI:
        return 16;
    case GL_RG32UI:
        return 8;
    case GL_R32UI:
        return 4;
    default:
        return 0;
    }
}

bool gl_split_plan(const dirt_gpu *gpu, const gl_split_desc *d, size_t records,
                   gl_split_layout *out)
{
    *out = (gl_split_layout){0, 0};
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    size_t texel = gl_split_texel_bytes(d->format);
    if (!texel || d->record_bytes % texel) {
        DIRT_ERROR("the %s: records of %zu bytes are not whole texels of format 0x%x", d->label,
                   d->record_bytes, (unsigned)d->format);
        return false;
    }
    if (records == 0)
        records = 1;
    if (records > SIZE_MAX / d->record_bytes) {
        DIRT_ERROR("the %s: %zu records overflow", d->label, records);
        return false;
    }
    double mb = (double)records * (double)d->record_bytes / 1e6;
    if (c->max_ssbo_size <= 0 || (uint64_t)records * d->record_bytes <= (uint64_t)c->max_ssbo_size)
        return true; /* one storage block */
    /* Parts: the texel-buffer limit, and DIRT_MAX_BLOCK_BYTES when set. */
    uint64_t part_bytes = c->max_texel_buffer > 0 ? (uint64_t)c->max_texel_buffer * texel : 0;
    if (c->block_override > 0 && (part_bytes == 0 || (uint64_t)c->block_override < part_bytes))
        part_bytes = (uint64_t)c->block_override;
    /* A buffer's size is a 32-bit number in Mesa's drivers. */
    if (part_bytes == 0 || part_bytes > ((uint64_t)1 << 31))
        part_bytes = (uint64_t)1 << 31;
    uint64_t per = part_bytes / d->record_bytes;
    if (per == 0) {
        DIRT_ERROR("the %s: a texel buffer (%llu bytes) holds no %zu-byte record", d->label,
                   (unsigned long long)part_bytes, d->record_bytes);
        return false;
    }
    int shift = 0;
    while (((uint64_t)2 << shift) <= per && shift < 40)
        shift++;
    uint64_t parts = ((uint64_t)records + ((uint64_t)1 << shift) - 1) >> shift;
    const char *advice = d->advice ? d->advice : "make the scene or the image smaller";
    if (parts > DIRT_SPLIT_MAX_PARTS) {
        DIRT_ERROR("the %s need %.1f MB, more than this GPU holds in one array (%d parts of "
                   "%.1f MB, its largest texel buffer%s): %s", d->label, mb,
                   DIRT_SPLIT_MAX_PARTS, ((uint64_t)1 << shift) * (double)d->record_bytes / 1e6,
                   c->block_override > 0 ? " or DIRT_MAX_BLOCK_BYTES" : "", advice);
        return false;
    }
    int units = d->image ? c->max_image_units : c->max_texture_units;
    if (units > 0 && d->unit + parts > (uint64_t)units) {
        DIRT_ERROR("the %s need %.1f MB, more than this GPU holds in one array (one storage "
                   "block of %.1f MB, or texel buffers at %s units %u..%llu, and it has %d): "
                   "%s", d->label, mb, c->max_ssbo_size / 1e6, d->image ? "image" : "texture",
                   d->unit, (unsigned long long)(d->unit + parts - 1), units, advice);
        return false;
    }
    *out = (gl_split_layout){(int)parts, shift};
    return true;
}

void gl_split_release(gl_split *s)
{
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS; k++) {
        gl_texture_destroy(&s->tex[k]);
        gl_buffer_destroy(&s->buf[k]);
        s->part_bytes[k] = 0;
    }
    s->capacity = 0;
    s->layout = (gl_split_layout){0, 0};
}

size_t gl_split_part_records(const gl_split *s)
{
    return s->layout.parts ? (size_t)1 << s->layout.shift : s->capacity;
}

bool gl_split_ensure(dirt_gpu *gpu, gl_split *s, const gl_split_desc *d, size_t records)
{
    if (records == 0)
        records = 1;
    if (s->desc == d && s->buf[0] && s->capacity >= records)
        return true;
    gl_split_release(s);
    s->desc = d;
    gl_split_layout l;
    if (!gl_split_plan(gpu, d, records, &l))
        return false;
    if (l.parts == 0) {
        s->buf[0] = gl_buffer_create(gpu, records * d->record_bytes, NULL, d->readback, d->label);
        if (!s->buf[0])
            return false;
        s->part_bytes[0] = records * d->record_bytes;
        s->capacity = records;
        return true;
    }
    size_t per = (size_t)1 << l.shift;
    for (int k = 0; k < l.parts; k++) {
        size_t n = records - (size_t)k * per < per ? records - (size_t)k * per : per;
        char label[160];
        snprintf(label, sizeof(label), "%s part %d", d->label, k);
        /* No gpu: a texel buffer is not a storage block, its limit is the
         * plan's. */
        s->buf[k] = gl_buffer_create(NULL, n * d->record_bytes, NULL, d->readback, label);
        if (!s->buf[k]) {
            DIRT_ERROR("the %s: could not allocate part %d of %d (%.1f MB)", d->label, k, l.parts,
                       n * (double)d->record_bytes / 1e6);
            gl_split_release(s);
            return false;
        }
        s->part_bytes[k] = n * d->record_bytes;
        glCreateTextures(GL_TEXTURE_BUFFER, 1, &s->tex[k]);
        glTextureBuffer(s->tex[k], d->format, s->buf[k]);
        gl_label(GL_TEXTURE, s->tex[k], "%s", label);
        if (!gl_check("glTextureBuffer")) {
            DIRT_ERROR("the %s: part %d (%.1f MB) cannot be a texel buffer", d->label, k,
                       n * (double)d->record_bytes / 1e6);
            gl_split_release(s);
            return false;
        }
    }
    s->layout = l;
    s->capacity = records;
    DIRT_INFO("the %s: %.1f MB in %d part%s of up to %zu records (texel buffers; storage "
              "blocks of %.1f MB)", d->label, records * (double)d->record_bytes / 1e6, l.parts,
              l.parts == 1 ? "" : "s", per, dirt_gpu_get_caps(gpu)->max_ssbo_size / 1e6);
    return true;
}

size_t gl_split_bytes(const gl_split *s)
{
    size_t b = 0;
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS; k++)
        b += s->part_bytes[k];
    return b;
}

/* Calls fn for the pieces of records [first, first + count) in each part. */
typedef bool (*piece_fn)(GLuint buf, size_t offset, size_t bytes, void *data);

static bool each_piece(const gl_split *s, size_t first, size_t count, void *data, piece_fn fn)
{
    if (first + count > s->capacity || first + count < first) {
        DIRT_ERROR("the %s: records %zu..%zu past its capacity of %zu",
                   s->desc ? s->desc->label : "split array", first, first + count, s->capacity);
        return false;
    }
    size_t per = gl_split_part_records(s), rb = s->desc->record_bytes;
    char *p = data;
    while (count > 0) {
        size_t k = first / per, off = first % per;
        size_t n = per - off < count ? per - off : count;
        if (!fn(s->buf[k], off * rb, n * rb, p))
            return false;
        p += n * rb;
        first += n;
        count -= n;
    }
    return true;
}

static bool write_piece(GLuint buf, size_t offset, size_t bytes, void *data)
{
    glNamedBufferSubData(buf, (GLintptr)offset, (GLsizeiptr)bytes, data);
    return true;
}

static bool read_piece(GLuint buf, size_t offset, size_t bytes, void *data)
{
    return gl_buffer_read(buf, offset, bytes, data);
}

bool gl_split_write(gl_split *s, size_t first, size_t count, const void *records)
{
    return each_piece(s, first, count, (void *)records, write_piece) &&
           gl_check("split array upload");
}

bool gl_split_read(const gl_split *s, size_t first, size_t count, void *out)
{
    return each_piece(s, first, count, out, read_piece);
}

void gl_split_clear(gl_split *s, GLenum internal, GLenum format, GLenum type, const void *value)
{
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && s->buf[k]; k++)
        glClearNamedBufferData(s->buf[k], internal, format, type, value);
}

void gl_split_bind(const gl_split *s)
{
    if (!s->desc || !s->buf[0])
        return;
    const gl_split_desc *d = s->desc;
    if (s->layout.parts == 0) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, d->binding, s->buf[0]);
        return;
    }
    /* Nothing at the block's binding: a shader built for one block must not
     * read a stale buffer there. */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, d->binding, 0);
    for (int k = 0; k < s->layout.parts; k++) {
        if (d->image)
            glBindImageTexture(d->unit + (GLuint)k, s->tex[k], 0, GL_FALSE, 0, GL_READ_WRITE,
                               d->format);
        else
            glBindTextureUnit(d->unit + (GLuint)k, s->tex[k]);
    }
}

void gl_split_defines(const gl_split_desc *d, gl_split_layout layout, gl_split_defs *out)
{
    snprintf(out->name[0], sizeof(out->name[0]), "%s", d->define);
    snprintf(out->name[1], sizeof(out->name[1]), "%s_SHIFT", d->define);
    snprintf(out->value[0], sizeof(out->value[0]), "%d", layout.parts);
    snprintf(out->value[1], sizeof(out->value[1]), "%d", layout.shift);
    for (int i = 0; i < 2; i++)
        out->def[i] = (glsl_define){out->name[i], out->value[i]};
}

uint32_t gl_split_key(gl_split_layout layout)
{
    return (uint32_t)layout.parts | (uint32_t)layout.shift << 8;
}

void gl_split_import(fg_graph *g, const char *name, const gl_split *s, fg_res *r)
{
    int n = s->layout.parts ? s->layout.parts : 1;
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS; k++) {
        r[k] = (fg_res){0};
        if (k >= n)
            continue;
        char label[160];
        if (s->layout.parts)
            snprintf(label, sizeof(label), "%s part %d", name, k);
        else
            snprintf(label, sizeof(label), "%s", name);
        r[k] = fg_import_buffer(g, label, s->buf[k], s->part_bytes[k]);
    }
}

void gl_split_set_imports(fg_graph *g, const gl_split *s, const fg_res *r)
{
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && r[k].id; k++)
        fg_set_import(g, r[k], s->buf[k], s->part_bytes[k]);
}

void gl_split_use(fg_pass *p, const gl_split *s, const fg_res *r, fg_access access)
{
    if (access == FG_TRANSFER_READ || access == FG_TRANSFER_WRITE) {
        for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && r[k].id; k++)
            fg_use(p, r[k], access, NULL);
        return;
    }
    if (s->layout.parts == 0) {
        fg_use(p, r[0], access, &(fg_use_opts){.bind = true, .binding = s->desc->binding});
        return;
    }
    bool write = access == FG_SSBO_WRITE;
    fg_access a = !s->desc->image ? FG_SAMPLED : write ? FG_IMAGE_STORE : FG_IMAGE_LOAD;
    for (int k = 0; k < s->layout.parts; k++)
        fg_use(p, r[k], a, NULL);
}

GLbitfield gl_split_barrier(const gl_split *s)
{
    if (!s->desc || s->layout.parts == 0)
        return GL_SHADER_STORAGE_BARRIER_BIT;
    return s->desc->image ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT : GL_TEXTURE_FETCH_BARRIER_BIT;
}

bool gl_split_program_ensure(gl_split_program *p, const char *label, const char *const *paths,
                      const glsl_define *defines, size_t num_defines,
                      const gl_split_desc *const *descs, const gl_split_layout *layouts,
                      size_t n)
{
    if (n > GL_SPLIT_PROGRAM_MAX_ARRAYS || num_defines > 16) {
        DIRT_ERROR("%s: %zu split arrays and %zu defines, at most %d and 16", label, n,
                   num_defines, GL_SPLIT_PROGRAM_MAX_ARRAYS);
        return false;
    }
    if (p->id && p->num_built == n && (n == 0 || !memcmp(p->built, layouts, n * sizeof(*layouts))))
        return true;
    gl_program_destroy(&p->id);
    p->num_built = 0;
    glsl_define all[16 + 2 * GL_SPLIT_PROGRAM_MAX_ARRAYS];
    gl_split_defs defs[GL_SPLIT_PROGRAM_MAX_ARRAYS];
    size_t k = 0;
    for (size_t i = 0; i < num_defines; i++)
        all[k++] = defines[i];
    for (size_t i = 0; i < n; i++) {
        gl_split_defines(descs[i], layouts[i], &defs[i]);
        all[k++] = defs[i].def[0];
        all[k++] = defs[i].def[1];
    }
    p->id = gl_program_create(label, paths, all, k);
    if (!p->id)
        return false;
    if (n)
        memcpy(p->built, layouts, n * sizeof(*layouts));
    p->num_built = n;
    return true;
}

void gl_split_program_destroy(gl_split_program *p)
{
    gl_program_destroy(&p->id);
    p->num_built = 0;
}

bool gl_split_program_select(gl_split_program *p, const char *label, const char *const *paths,
                             const glsl_define *defines, size_t num_defines,
                             const gl_split_desc *const *descs, gl_split *const *arr, size_t n,
                             unsigned mask, const gl_split *extra)
{
    const gl_split_desc *d[GL_SPLIT_PROGRAM_MAX_ARRAYS];
    gl_split_layout l[GL_SPLIT_PROGRAM_MAX_ARRAYS];
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (mask & (1u << i)) {
            if (k == GL_SPLIT_PROGRAM_MAX_ARRAYS) {
                DIRT_ERROR("%s: more than %d split arrays", label, GL_SPLIT_PROGRAM_MAX_ARRAYS);
                return false;
            }
            d[k] = descs[i];
            l[k] = arr[i]->layout;
            k++;
        }
    }
    if (extra) {
        if (k == GL_SPLIT_PROGRAM_MAX_ARRAYS) {
            DIRT_ERROR("%s: more than %d split arrays", label, GL_SPLIT_PROGRAM_MAX_ARRAYS);
            return false;
        }
        d[k] = extra->desc;
        l[k] = extra->layout;
        k++;
    }
    return gl_split_program_ensure(p, label, paths, defines, num_defines, d, l, k);
}
