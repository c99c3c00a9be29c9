/* OpenGL backend of the frame graph (src/graph/ is GL-free) and the GL
 * helpers pass bodies use for readback and clears. */
#include "gl/gl.h"

#include <stdlib.h>
#include <string.h>

#include "gl/graph_gl.h"

_Static_assert(FG_BARRIER_VERTEX_ATTRIB_ARRAY == GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_ELEMENT_ARRAY == GL_ELEMENT_ARRAY_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_UNIFORM == GL_UNIFORM_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_TEXTURE_FETCH == GL_TEXTURE_FETCH_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_SHADER_IMAGE_ACCESS == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_COMMAND == GL_COMMAND_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_PIXEL_BUFFER == GL_PIXEL_BUFFER_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_TEXTURE_UPDATE == GL_TEXTURE_UPDATE_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_BUFFER_UPDATE == GL_BUFFER_UPDATE_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_FRAMEBUFFER == GL_FRAMEBUFFER_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_TRANSFORM_FEEDBACK == GL_TRANSFORM_FEEDBACK_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_ATOMIC_COUNTER == GL_ATOMIC_COUNTER_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_SHADER_STORAGE == GL_SHADER_STORAGE_BARRIER_BIT, "bits");
_Static_assert(FG_BARRIER_ALL == (GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
    GL_ELEMENT_ARRAY_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT |
    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
    GL_TRANSFORM_FEEDBACK_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
    GL_SHADER_STORAGE_BARRIER_BIT), "bits");

/* Internal format, and the client format/type of a tight readback. */
static const struct {
    GLenum internal, format, type;
} gl_formats[FG_FORMAT_COUNT] = {
    [FG_R8] = {GL_R8, GL_RED, GL_UNSIGNED_BYTE},
    [FG_RGBA8] = {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE},
    [FG_R16F] = {GL_R16F, GL_RED, GL_HALF_FLOAT},
    [FG_RG16F] = {GL_RG16F, GL_RG, GL_HALF_FLOAT},
    [FG_RGBA16F] = {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT},
    [FG_R32F] = {GL_R32F, GL_RED, GL_FLOAT},
    [FG_RG32F] = {GL_RG32F, GL_RG, GL_FLOAT},
    [FG_RGBA32F] = {GL_RGBA32F, GL_RGBA, GL_FLOAT},
    [FG_R32UI] = {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT},
    [FG_RG32UI] = {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT},
    [FG_RGBA32UI] = {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT},
    [FG_R32I] = {GL_R32I, GL_RED_INTEGER, GL_INT},
    [FG_DEPTH32F] = {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT},
};

#define MAX_ATTACH 9 /* 8 colour + depth */

/* Framebuffer and timer of one pass (by declaration index). */
typedef struct pass_state {
    GLuint fbo;
    uint32_t key[MAX_ATTACH * 3 + 3];
    int key_len;
    gl_timer timer;           /* with the gpu's one clock (dirt_gpu_clock) */
    bool timer_ok;
} pass_state;

typedef struct graph_gl {
    dirt_gpu *gpu;
    GLuint vao;
    pass_state *passes;
    int num_passes;
} graph_gl;

static pass_state *state_of(graph_gl *b, int index)
{
    if (index >= b->num_passes) {
        int n = index + 1;
        pass_state *p = realloc(b->passes, (size_t)n * sizeof(*p));
        if (!p) {
            DIRT_ERROR("frame graph: out of memory");
            return NULL;
        }
        memset(p + b->num_passes, 0, (size_t)(n - b->num_passes) * sizeof(*p));
        b->passes = p;
        b->num_passes = n;
    }
    return &b->passes[index];
}

static uint32_t gl_create(void *self, const fg_phys_desc *d)
{
    graph_gl *b = self;
    const char *label = d->label ? d->label : "frame graph";
    if (!d->texture)
        return gl_buffer_create(b->gpu, d->bytes, NULL, d->readback, label);
    GLenum fmt = gl_formats[d->format].internal;
    GLuint tex = d->array ? gl_texture_2d_array(fmt, d->width, d->height, d->layers, d->levels,
                                                label)
                          : gl_texture_2d(fmt, d->width, d->height, d->levels, label);
    if (!tex)
        return 0;
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        d->levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

static void gl_destroy(void *self, const fg_phys_desc *d, uint32_t name)
{
    (void)self;
    GLuint n = name;
    if (d->texture)
        gl_texture_destroy(&n);
    else
        gl_buffer_destroy(&n);
}

static void gl_barrier(void *self, uint32_t bits)
{
    (void)self;
    glMemoryBarrier(bits);
}

/* Attachment set of a raster pass as a key, to reuse its framebuffer. */
static int fb_key(const fg_pass_info *p, uint32_t *key)
{
    int n = 0;
    for (int i = 0; i < p->num_bindings && n + 3 <= MAX_ATTACH * 3; i++) {
        const fg_binding *bd = &p->bindings[i];
        if (bd->access != FG_COLOR && bd->access != FG_DEPTH)
            continue;
        key[n++] = bd->name;
        key[n++] = (uint32_t)bd->opts.level;
        key[n++] = bd->access == FG_DEPTH ? 0xffffffffu : bd->opts.binding;
    }
    key[n++] = (uint32_t)p->raster_width;
    key[n++] = (uint32_t)p->raster_height;
    key[n++] = (uint32_t)p->raster_layers;
    return n;
}

static bool make_framebuffer(pass_state *s, const fg_pass_info *p)
{
    if (s->fbo)
        glDeleteFramebuffers(1, &s->fbo);
    s->fbo = 0;
    glCreateFramebuffers(1, &s->fbo);
    GLenum bufs[8];
    int nbufs = 0;
    for (int i = 0; i < 8; i++)
        bufs[i] = GL_NONE;
    for (int i = 0; i < p->num_bindings; i++) {
        const fg_binding *bd = &p->bindings[i];
        if (bd->access == FG_DEPTH) {
            glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, bd->name, bd->opts.level);
        } else if (bd->access == FG_COLOR) {
            GLenum att = GL_COLOR_ATTACHMENT0 + bd->opts.binding;
            glNamedFramebufferTexture(s->fbo, att, bd->name, bd->opts.level);
            bufs[bd->opts.binding] = att;
            if ((int)bd->opts.binding + 1 > nbufs)
                nbufs = (int)bd->opts.binding + 1;
        }
    }
    if (nbufs)
        glNamedFramebufferDrawBuffers(s->fbo, nbufs, bufs);
    else
        glNamedFramebufferDrawBuffer(s->fbo, GL_NONE);
    bool attachments = false;
    for (int i = 0; i < p->num_bindings; i++)
        attachments |= p->bindings[i].access == FG_COLOR || p->bindings[i].access == FG_DEPTH;
    if (!attachments) {
        glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, p->raster_width);
        glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, p->raster_height);
        if (p->raster_layers > 1)
            glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_LAYERS,
                                         p->raster_layers);
    }
    GLenum status = glCheckNamedFramebufferStatus(s->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        DIRT_ERROR("frame graph: framebuffer of raster pass '%s' is incomplete (0x%x)",
                   p->name, status);
        glDeleteFramebuffers(1, &s->fbo);
        s->fbo = 0;
        return false;
    }
    gl_label(GL_FRAMEBUFFER, s->fbo, "fg %s", p->name);
    return true;
}

static GLenum image_mode(const fg_binding *bd)
{
    if (bd->access == FG_IMAGE_ATOMIC || (bd->pass_reads && bd->pass_writes))
        return GL_READ_WRITE;
    return bd->access == FG_IMAGE_LOAD ? GL_READ_ONLY : GL_WRITE_ONLY;
}

static void bind(graph_gl *b, const fg_pass_info *p, const fg_binding *bd)
{
    GLuint unit = bd->opts.binding;
    switch (bd->access) {
    case FG_SAMPLED:
        glBindTextureUnit(unit, bd->name);
        break;
    case FG_IMAGE_LOAD:
    case FG_IMAGE_STORE:
    case FG_IMAGE_ATOMIC:
        glBindImageTexture(unit, bd->name, bd->opts.level, bd->array ? GL_TRUE : GL_FALSE, 0,
                           image_mode(bd), gl_formats[bd->format].internal);
        break;
    case FG_SSBO_READ:
    case FG_SSBO_WRITE:
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, unit, bd->name);
        break;
    case FG_ATOMIC_COUNTER:
        glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, unit, bd->name);
        break;
    case FG_UNIFORM:
        glBindBufferBase(GL_UNIFORM_BUFFER, unit, bd->name);
        break;
    case FG_INDIRECT:
        glBindBuffer(p->kind == FG_RASTER ? GL_DRAW_INDIRECT_BUFFER
                                          : GL_DISPATCH_INDIRECT_BUFFER, bd->name);
        break;
    case FG_INDEX:
        glVertexArrayElementBuffer(b->vao, bd->name);
        break;
    default: /* vertex buffers need a stride: the pass body binds them;
                attachments go through the framebuffer; transfers bind nothing */
        break;
    }
}

static bool gl_begin_pass(void *self, const fg_pass_info *p)
{
    graph_gl *b = self;
    pass_state *s = state_of(b, p->index);
    if (!s)
        return false;
    while (glGetError() != GL_NO_ERROR) {
    } /* errors of earlier code were logged by the debug output already */
    gl_group_push(p->name);
    if (p->kind == FG_RASTER) {
        uint32_t key[MAX_ATTACH * 3 + 3];
        int n = fb_key(p, key);
        if (!s->fbo || n != s->key_len || memcmp(key, s->key, (size_t)n * sizeof(*key)) != 0) {
            s->key_len = 0;
            if (!make_framebuffer(s, p)) {
                gl_group_pop();
                return false;
            }
            memcpy(s->key, key, (size_t)n * sizeof(*key));
            s->key_len = n;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
        glViewport(0, 0, p->raster_width, p->raster_height);
        glBindVertexArray(b->vao);
    }
    for (int i = 0; i < p->num_bindings; i++) {
        if (p->bindings[i].opts.bind)
            bind(b, p, &p->bindings[i]);
    }
    if (!gl_check("frame graph pass setup")) {
        DIRT_ERROR("frame graph: binding the resources of pass '%s' failed", p->name);
        if (p->kind == FG_RASTER)
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl_group_pop();
        return false;
    }
    if (p->timed) {
        if (!s->timer_ok)
            s->timer_ok = gl_timer_init(&s->timer, b->gpu, p->name);
        if (s->timer_ok)
            gl_timer_begin(&s->timer);
    }
    return true;
}

static bool gl_end_pass(void *self, const fg_pass_info *p, double *ms, enum dirt_clock *clock)
{
    graph_gl *b = self;
    pass_state *s = state_of(b, p->index);
    *ms = -1;
    *clock = DIRT_CLOCK_NONE;
    if (s && p->timed && s->timer_ok && s->timer.running) {
        if (p->async)
            gl_timer_end_async(&s->timer);
        else
            gl_timer_end(&s->timer);
        *ms = s->timer.ms;
        *clock = s->timer.clock;
    }
    if (p->kind == FG_RASTER) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
    }
    gl_group_pop();
    if (!gl_check("frame graph pass")) {
        DIRT_ERROR("frame graph: pass '%s' left a GL error", p->name);
        return false;
    }
    return true;
}

static void gl_drain(void *self, int index, bool discard, double *ms, enum dirt_clock *clock)
{
    graph_gl *b = self;
    if (index < 0 || index >= b->num_passes || !b->passes[index].timer_ok)
        return;
    gl_timer *t = &b->passes[index].timer;
    if (discard) {
        gl_timer_discard(t);
        return;
    }
    double late_ms = 0;
    if (gl_timer_drain(t, &late_ms) > 0) {
        *ms = late_ms;
        *clock = t->clock;
    }
}

static void gl_release(void *self)
{
    graph_gl *b = self;
    if (!b)
        return;
    for (int i = 0; i < b->num_passes; i++) {
        if (b->passes[i].fbo)
            glDeleteFramebuffers(1, &b->passes[i].fbo);
        if (b->passes[i].timer_ok)
            gl_timer_release(&b->passes[i].timer);
    }
    if (b->vao)
        glDeleteVertexArrays(1, &b->vao);
    free(b->passes);
    free(b);
}

static void gl_poison(void *self, const fg_binding *bd)
{
    (void)self;
    if (bd->texture)
        gl_poison_texture(bd->name, true);
    else
        gl_poison_buffer(bd->name, bd->bytes, true);
}

static const fg_backend_ops gl_ops = {
    .create = gl_create,
    .destroy = gl_destroy,
    .barrier = gl_barrier,
    .begin_pass = gl_begin_pass,
    .end_pass = gl_end_pass,
    .release = gl_release,
    .drain = gl_drain,
    .poison = gl_poison,
};

bool fg_gl_backend(dirt_gpu *gpu, fg_backend *out)
{
    graph_gl *b = calloc(1, sizeof(*b));
    if (!b) {
        DIRT_ERROR("frame graph: out of memory");
        return false;
    }
    b->gpu = gpu;
    glCreateVertexArrays(1, &b->vao);
    if (!b->vao) {
        gl_check("glCreateVertexArrays");
        DIRT_ERROR("frame graph: could not create a vertex array");
        free(b);
        return false;
    }
    gl_label(GL_VERTEX_ARRAY, b->vao, "frame graph empty vao");
    *out = (fg_backend){.ops = &gl_ops, .self = b};
    return true;
}

fg_graph *gl_graph_create(dirt_gpu *gpu)
{
    fg_backend b;
    if (!fg_gl_backend(gpu, &b))
        return NULL;
    return fg_create(&b);
}

/* ---- helpers for pass bodies ---------------------------------------------- */

static uint32_t declared(const fg_ctx *ctx, fg_res r, fg_access a, const char *what)
{
    if (!fg_declares(ctx, r, a)) {
        DIRT_ERROR("frame graph: pass '%s' calls %s without declaring %s on the resource",
                   fg_pass_name(ctx), what, fg_access_name(a));
        return 0;
    }
    return fg_name(ctx, r);
}

bool fg_gl_read_buffer(const fg_ctx *ctx, fg_res r, size_t offset, size_t size, void *out)
{
    GLuint name = declared(ctx, r, FG_TRANSFER_READ, "fg_gl_read_buffer");
    if (!name)
        return false;
    size_t have = fg_buffer_size(ctx, r);
    if (offset > have || size > have - offset) {
        DIRT_ERROR("frame graph: reading %zu bytes at %zu of a %zu-byte buffer", size, offset,
                   have);
        return false;
    }
    return gl_buffer_read(name, offset, size, out);
}

bool fg_gl_read_texture(const fg_ctx *ctx, fg_res r, int level, void *out, size_t size)
{
    GLuint name = declared(ctx, r, FG_TRANSFER_READ, "fg_gl_read_texture");
    if (!name)
        return false;
    fg_format f = fg_texture_format(ctx, r);
    int w = 0, h = 0, layers = 0, levels = 0;
    fg_texture_size(ctx, r, &w, &h, &layers, &levels);
    if (level < 0 || level >= levels) {
        DIRT_ERROR("frame graph: texture level %d of %d", level, levels);
        return false;
    }
    GLint align = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &align);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(name, level, gl_formats[f].format, gl_formats[f].type, (GLsizei)size,
                      out);
    glPixelStorei(GL_PACK_ALIGNMENT, align);
    return gl_check("glGetTextureImage");
}

bool fg_gl_clear(const fg_ctx *ctx, fg_res r)
{
    GLuint name = declared(ctx, r, FG_TRANSFER_WRITE, "fg_gl_clear");
    if (!name)
        return false;
    fg_format f = fg_texture_format(ctx, r);
    int levels = 0;
    if (f == FG_FORMAT_NONE) {
        glClearNamedBufferData(name, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, NULL);
    } else {
        fg_texture_size(ctx, r, NULL, NULL, NULL, &levels);
        for (int l = 0; l < levels; l++)
            glClearTexImage(name, l, gl_formats[f].format, gl_formats[f].type, NULL);
    }
    return gl_check("frame graph clear");
}
