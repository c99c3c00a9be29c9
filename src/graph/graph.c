/* Frame graph: creation, declarations, access/format/barrier tables. */
#include "graph/graph_internal.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ---- tables -------------------------------------------------------------- */

enum { RD = 1, WR = 2, SW = 4, TEX = 8, BUF = 16, RASTER = 32 };

static const struct {
    const char *name;
    unsigned flags;
    uint32_t bit;       /* consumer bit; transfers pick texture/buffer at run time */
} access_table[FG_ACCESS_COUNT] = {
    [FG_ACCESS_NONE]    = {"none", 0, 0},
    [FG_SAMPLED]        = {"sampled", RD | TEX, FG_BARRIER_TEXTURE_FETCH},
    [FG_IMAGE_LOAD]     = {"image load", RD | TEX, FG_BARRIER_SHADER_IMAGE_ACCESS},
    [FG_IMAGE_STORE]    = {"image store", WR | SW | TEX, FG_BARRIER_SHADER_IMAGE_ACCESS},
    [FG_IMAGE_ATOMIC]   = {"image atomic", RD | WR | SW | TEX, FG_BARRIER_SHADER_IMAGE_ACCESS},
    [FG_SSBO_READ]      = {"ssbo read", RD | BUF, FG_BARRIER_SHADER_STORAGE},
    [FG_SSBO_WRITE]     = {"ssbo write", WR | SW | BUF, FG_BARRIER_SHADER_STORAGE},
    [FG_ATOMIC_COUNTER] = {"atomic counter", RD | WR | SW | BUF, FG_BARRIER_ATOMIC_COUNTER},
    [FG_UNIFORM]        = {"uniform", RD | BUF, FG_BARRIER_UNIFORM},
    [FG_VERTEX]         = {"vertex", RD | BUF, FG_BARRIER_VERTEX_ATTRIB_ARRAY},
    [FG_INDEX]          = {"index", RD | BUF, FG_BARRIER_ELEMENT_ARRAY},
    [FG_INDIRECT]       = {"indirect", RD | BUF, FG_BARRIER_COMMAND},
    [FG_COLOR]          = {"color", WR | TEX | RASTER, FG_BARRIER_FRAMEBUFFER},
    [FG_DEPTH]          = {"depth", WR | TEX | RASTER, FG_BARRIER_FRAMEBUFFER},
    [FG_TRANSFER_READ]  = {"transfer read", RD | TEX | BUF, 0},
    [FG_TRANSFER_WRITE] = {"transfer write", WR | TEX | BUF, 0},
};

static unsigned access_flags(fg_access a)
{
    return (a > FG_ACCESS_NONE && a < FG_ACCESS_COUNT) ? access_table[a].flags : 0;
}

const char *fg_access_name(fg_access a)
{
    return (a >= FG_ACCESS_NONE && a < FG_ACCESS_COUNT) ? access_table[a].name : "?";
}

bool fg_access_reads(fg_access a) { return access_flags(a) & RD; }
bool fg_access_writes(fg_access a) { return access_flags(a) & WR; }
bool fg_access_shader_write(fg_access a) { return access_flags(a) & SW; }

uint32_t fg_barrier_bit(fg_access later, bool texture)
{
    if (later == FG_TRANSFER_READ || later == FG_TRANSFER_WRITE)
        return texture ? FG_BARRIER_TEXTURE_UPDATE : FG_BARRIER_BUFFER_UPDATE;
    return (later > FG_ACCESS_NONE && later < FG_ACCESS_COUNT) ? access_table[later].bit : 0;
}

uint32_t fg_barrier_bits(fg_access earlier, fg_access later, bool texture)
{
    if (!access_flags(earlier) || !access_flags(later))
        return 0;
    if (fg_access_shader_write(earlier) || fg_access_shader_write(later))
        return fg_barrier_bit(later, texture);
    return 0;
}

static const struct {
    uint32_t bit;
    const char *name;
} barrier_names[] = {
    {FG_BARRIER_VERTEX_ATTRIB_ARRAY, "VERTEX_ATTRIB_ARRAY"},
    {FG_BARRIER_ELEMENT_ARRAY, "ELEMENT_ARRAY"},
    {FG_BARRIER_UNIFORM, "UNIFORM"},
    {FG_BARRIER_TEXTURE_FETCH, "TEXTURE_FETCH"},
    {FG_BARRIER_SHADER_IMAGE_ACCESS, "SHADER_IMAGE_ACCESS"},
    {FG_BARRIER_COMMAND, "COMMAND"},
    {FG_BARRIER_PIXEL_BUFFER, "PIXEL_BUFFER"},
    {FG_BARRIER_TEXTURE_UPDATE, "TEXTURE_UPDATE"},
    {FG_BARRIER_BUFFER_UPDATE, "BUFFER_UPDATE"},
    {FG_BARRIER_FRAMEBUFFER, "FRAMEBUFFER"},
    {FG_BARRIER_TRANSFORM_FEEDBACK, "TRANSFORM_FEEDBACK"},
    {FG_BARRIER_ATOMIC_COUNTER, "ATOMIC_COUNTER"},
    {FG_BARRIER_SHADER_STORAGE, "SHADER_STORAGE"},
};

const char *fg_barrier_name(uint32_t bit)
{
    static const char *const full[] = {
        "GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT", "GL_ELEMENT_ARRAY_BARRIER_BIT",
        "GL_UNIFORM_BARRIER_BIT", "GL_TEXTURE_FETCH_BARRIER_BIT",
        "GL_SHADER_IMAGE_ACCESS_BARRIER_BIT", "GL_COMMAND_BARRIER_BIT",
        "GL_PIXEL_BUFFER_BARRIER_BIT", "GL_TEXTURE_UPDATE_BARRIER_BIT",
        "GL_BUFFER_UPDATE_BARRIER_BIT", "GL_FRAMEBUFFER_BARRIER_BIT",
        "GL_TRANSFORM_FEEDBACK_BARRIER_BIT", "GL_ATOMIC_COUNTER_BARRIER_BIT",
        "GL_SHADER_STORAGE_BARRIER_BIT",
    };
    for (size_t i = 0; i < sizeof(barrier_names) / sizeof(barrier_names[0]); i++) {
        if (barrier_names[i].bit == bit)
            return full[i];
    }
    return NULL;
}

char *fg_barrier_string(uint32_t bits, char *buf, size_t size)
{
    if (!buf || size == 0)
        return buf;
    buf[0] = '\0';
    if (!bits) {
        snprintf(buf, size, "-");
        return buf;
    }
    size_t len = 0;
    for (size_t i = 0; i < sizeof(barrier_names) / sizeof(barrier_names[0]); i++) {
        if (!(bits & barrier_names[i].bit))
            continue;
        int n = snprintf(buf + len, size - len, "%s%s", len ? "|" : "", barrier_names[i].name);
        if (n < 0 || (size_t)n >= size - len) {
            buf[len] = '\0'; /* no partial names */
            break;
        }
        len += (size_t)n;
    }
    return buf;
}

int fg_barrier_index(uint32_t bit)
{
    if (!bit || (bit & (bit - 1)) || bit >= (1u << FG_NUM_BARRIER_BITS))
        return -1;
    int i = 0;
    while (!(bit & 1u)) {
        bit >>= 1;
        i++;
    }
    return i;
}

static const struct {
    const char *name;
    size_t bytes;
    bool depth;
} format_table[FG_FORMAT_COUNT] = {
    [FG_FORMAT_NONE] = {"none", 0, false},
    [FG_R8] = {"r8", 1, false},
    [FG_RGBA8] = {"rgba8", 4, false},
    [FG_R16F] = {"r16f", 2, false},
    [FG_RG16F] = {"rg16f", 4, false},
    [FG_RGBA16F] = {"rgba16f", 8, false},
    [FG_R32F] = {"r32f", 4, false},
    [FG_RG32F] = {"rg32f", 8, false},
    [FG_RGBA32F] = {"rgba32f", 16, false},
    [FG_R32UI] = {"r32ui", 4, false},
    [FG_RG32UI] = {"rg32ui", 8, false},
    [FG_RGBA32UI] = {"rgba32ui", 16, false},
    [FG_R32I] = {"r32i", 4, false},
    [FG_DEPTH32F] = {"depth32f", 4, true},
};

static bool format_valid(fg_format f) { return f > FG_FORMAT_NONE && f < FG_FORMAT_COUNT; }

const char *fg_format_name(fg_format f) { return format_valid(f) ? format_table[f].name : "?"; }
size_t fg_format_bytes(fg_format f) { return format_valid(f) ? format_table[f].bytes : 0; }
bool fg_format_is_depth(fg_format f) { return format_valid(f) && format_table[f].depth; }

size_t fg_texture_bytes(fg_format f, int width, int height, int layers, int levels)
{
    size_t total = 0;
    for (int l = 0; l < levels; l++) {
        size_t w = (size_t)(width >> l > 0 ? width >> l : 1);
        size_t h = (size_t)(height >> l > 0 ? height >> l : 1);
        total += w * h;
    }
    return total * (size_t)(layers > 0 ? layers : 1) * fg_format_bytes(f);
}

/* ---- helpers ------------------------------------------------------------- */

void fg_fail_(fg_graph *g, const char *file, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    dirt_log(DIRT_LOG_ERROR, file, line, "frame graph: %s", msg);
    if (g) {
        if (g->num_errors++ == 0)
            snprintf(g->error, sizeof(g->error), "%s", msg);
    }
}

/* Declaration-time error: logged now, kept (and counted) so that every
 * later fg_compile fails with it. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void decl_fail_(fg_graph *g, const char *file, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    dirt_log(DIRT_LOG_ERROR, file, line, "frame graph: %s", msg);
    if (g->decl_errors++ == 0)
        snprintf(g->decl_error, sizeof(g->decl_error), "%s", msg);
}
#define DECL_FAIL(g, ...) decl_fail_((g), __FILE__, __LINE__, __VA_ARGS__)

bool fg_grow(void **ptr, int *cap, int need, size_t size)
{
    if (need <= *cap)
        return true;
    int n = *cap ? *cap : 8;
    while (n < need)
        n *= 2;
    void *p = realloc(*ptr, (size_t)n * size);
    if (!p) {
        DIRT_ERROR("frame graph: out of memory");
        return false;
    }
    *ptr = p;
    *cap = n;
    return true;
}

static char *copy_name(const char *s)
{
    size_t n = strlen(s);
    char *c = malloc(n + 1);
    if (c)
        memcpy(c, s, n + 1);
    return c;
}

fg_resource *fg_res_get(const fg_graph *g, fg_res r)
{
    if (!g || r.id == 0 || r.id > (uint32_t)g->num_res)
        return NULL;
    return &g->res[r.id - 1];
}

fg_pass *fg_pass_find(const fg_graph *g, const char *name)
{
    if (!g || !name)
        return NULL;
    for (int i = 0; i < g->num_passes; i++) {
        if (strcmp(g->passes[i]->name, name) == 0)
            return g->passes[i];
    }
    return NULL;
}

/* ---- lifetime ------------------------------------------------------------ */

fg_graph *fg_create(const fg_backend *backend)
{
    fg_graph *g = calloc(1, sizeof(*g));
    if (!g) {
        DIRT_ERROR("frame graph: out of memory");
        if (backend && backend->ops && backend->ops->release)
            backend->ops->release(backend->self);
        return NULL;
    }
    if (backend && backend->ops) {
        g->backend = *backend;
        g->has_backend = true;
    }
    return g;
}

void fg_destroy(fg_graph *g)
{
    if (!g)
        return;
    fg_invalidate(g);
    fg_release_allocations(g);
    if (g->has_backend && g->backend.ops->release)
        g->backend.ops->release(g->backend.self);
    for (int i = 0; i < g->num_res; i++)
        free(g->res[i].name);
    for (int i = 0; i < g->num_passes; i++) {
        free(g->passes[i]->name);
        free(g->passes[i]);
    }
    free(g->res);
    free(g->passes);
    free(g->uses);
    free(g->held);
    free(g->scratch);
    free(g->objs);
    free(g);
}

/* ---- resources ----------------------------------------------------------- */

static fg_res add_resource(fg_graph *g, const char *name, bool texture, bool imported)
{
    if (!name || !*name) {
        DECL_FAIL(g, "a resource needs a name");
        return (fg_res){0};
    }
    for (int i = 0; i < g->num_res; i++) {
        if (strcmp(g->res[i].name, name) == 0) {
            DECL_FAIL(g, "resource '%s' is declared twice", name);
            return (fg_res){0};
        }
    }
    if (!fg_grow((void **)&g->res, &g->cap_res, g->num_res + 1, sizeof(*g->res)))
        goto oom;
    fg_resource *r = &g->res[g->num_res];
    *r = (fg_resource){.texture = texture, .imported = imported, .first = -1, .last = -1,
                       .physical = -1};
    r->name = copy_name(name);
    if (!r->name)
        goto oom;
    g->num_res++;
    fg_invalidate(g);
    return (fg_res){(uint32_t)g->num_res};
oom:
    DECL_FAIL(g, "out of memory declaring resource '%s'", name);
    return (fg_res){0};
}

static bool check_tex_desc(fg_graph *g, const char *name, const fg_tex_desc *d)
{
    if (!d) {
        DECL_FAIL(g, "texture '%s': no descriptor", name ? name : "?");
        return false;
    }
    if (!format_valid(d->format)) {
        DECL_FAIL(g, "texture '%s': no valid format", name ? name : "?");
        return false;
    }
    return true;
}

fg_res fg_texture(fg_graph *g, const char *name, const fg_tex_desc *desc)
{
    if (!g)
        return (fg_res){0};
    if (!check_tex_desc(g, name, desc))
        return (fg_res){0};
    fg_res h = add_resource(g, name, true, false);
    if (h.id)
        g->res[h.id - 1].tex = *desc;
    return h;
}

fg_res fg_buffer(fg_graph *g, const char *name, const fg_buf_desc *desc)
{
    if (!g)
        return (fg_res){0};
    if (!desc) {
        DECL_FAIL(g, "buffer '%s': no descriptor", name ? name : "?");
        return (fg_res){0};
    }
    fg_res h = add_resource(g, name, false, false);
    if (h.id)
        g->res[h.id - 1].buf = *desc;
    return h;
}

fg_res fg_import_buffer(fg_graph *g, const char *name, uint32_t gl_name, size_t size)
{
    if (!g)
        return (fg_res){0};
    if (!gl_name) {
        DECL_FAIL(g, "imported buffer '%s': GL name 0", name ? name : "?");
        return (fg_res){0};
    }
    fg_res h = add_resource(g, name, false, true);
    if (h.id) {
        g->res[h.id - 1].import_name = gl_name;
        g->res[h.id - 1].import_size = size;
        g->res[h.id - 1].buf.bytes = size;
    }
    return h;
}

fg_res fg_import_texture(fg_graph *g, const char *name, uint32_t gl_name,
                         const fg_tex_desc *desc)
{
    if (!g)
        return (fg_res){0};
    if (!check_tex_desc(g, name, desc))
        return (fg_res){0};
    if (!gl_name) {
        DECL_FAIL(g, "imported texture '%s': GL name 0", name ? name : "?");
        return (fg_res){0};
    }
    fg_res h = add_resource(g, name, true, true);
    if (h.id) {
        g->res[h.id - 1].tex = *desc;
        g->res[h.id - 1].import_name = gl_name;
    }
    return h;
}

bool fg_set_import(fg_graph *g, fg_res r, uint32_t gl_name, size_t size)
{
    fg_resource *res = fg_res_get(g, r);
    if (!res || !res->imported || !gl_name) {
        DIRT_ERROR("frame graph: fg_set_import needs an imported resource and a GL name");
        return false;
    }
    res->import_name = gl_name;
    if (!res->texture) {
        res->import_size = size;
        res->buf.bytes = size;
        res->bytes = size;
        if (g->rstats && g->compiled)
            g->rstats[r.id - 1].bytes = size;
    }
    return true;
}

bool fg_set_buffer(fg_graph *g, fg_res r, const fg_buf_desc *desc)
{
    fg_resource *res = fg_res_get(g, r);
    if (!res || res->imported || res->texture || !desc) {
        DIRT_ERROR("frame graph: fg_set_buffer needs a transient buffer and a descriptor");
        return false;
    }
    res->buf = *desc;
    fg_invalidate(g);
    return true;
}

void fg_output(fg_graph *g, fg_res r)
{
    fg_resource *res = fg_res_get(g, r);
    if (!res) {
        if (g)
            DECL_FAIL(g, "fg_output: unknown resource #%u", r.id);
        return;
    }
    res->output = true;
    fg_invalidate(g);
}

void fg_set_resolution(fg_graph *g, int width, int height)
{
    if (!g)
        return;
    g->out_width = width;
    g->out_height = height;
    fg_invalidate(g);
}

void fg_set_aliasing(fg_graph *g, bool enabled)
{
    if (!g)
        return;
    g->no_alias = !enabled;
    fg_invalidate(g);
}

void fg_set_shared_imports(fg_graph *g, bool shared)
{
    if (!g)
        return;
    g->shared_imports = shared;
    fg_invalidate(g);
}

/* ---- passes -------------------------------------------------------------- */

fg_pass *fg_add_pass(fg_graph *g, const char *name, fg_pass_kind kind, fg_execute_fn fn,
                     void *user)
{
    if (!g)
        return NULL;
    if (!name || !*name) {
        DECL_FAIL(g, "a pass needs a name");
        return NULL;
    }
    if (fg_pass_find(g, name)) {
        DECL_FAIL(g, "pass '%s' is declared twice", name);
        return NULL;
    }
    if (kind != FG_COMPUTE && kind != FG_RASTER) {
        DECL_FAIL(g, "pass '%s': unknown kind %d", name, (int)kind);
        return NULL;
    }
    if (!fg_grow((void **)&g->passes, &g->cap_passes, g->num_passes + 1, sizeof(*g->passes)))
        goto oom;
    fg_pass *p = calloc(1, sizeof(*p));
    if (!p)
        goto oom;
    p->name = copy_name(name);
    if (!p->name) {
        free(p);
        goto oom;
    }
    p->g = g;
    p->index = g->num_passes;
    p->kind = kind;
    p->fn = fn;
    p->user = user;
    p->position = -1;
    p->ms = -1;
    p->clock = DIRT_CLOCK_NONE;
    g->passes[g->num_passes++] = p;
    fg_invalidate(g);
    return p;
oom:
    DECL_FAIL(g, "out of memory declaring pass '%s'", name);
    return NULL;
}

static void add_use(fg_pass *p, fg_res r, fg_access a, const fg_use_opts *opts, int direction)
{
    if (!p)
        return;
    fg_graph *g = p->g;
    if (!fg_grow((void **)&g->uses, &g->cap_uses, g->num_uses + 1, sizeof(*g->uses))) {
        DECL_FAIL(g, "out of memory declaring a use in pass '%s'", p->name);
        return;
    }
    g->uses[g->num_uses++] = (fg_use_rec){
        .pass = p->index, .res = r.id, .access = a,
        .opts = opts ? *opts : (fg_use_opts){0}, .direction = direction,
    };
    fg_invalidate(g);
}

void fg_use(fg_pass *p, fg_res r, fg_access a, const fg_use_opts *opts)
{
    add_use(p, r, a, opts, 0);
}

void fg_read(fg_pass *p, fg_res r, fg_access a)
{
    add_use(p, r, a, NULL, 1);
}

void fg_write(fg_pass *p, fg_res r, fg_access a)
{
    add_use(p, r, a, NULL, 2);
}

void fg_keep(fg_pass *p)
{
    if (!p)
        return;
    p->keep = true;
    fg_invalidate(p->g);
}

void fg_set_raster_size(fg_pass *p, const fg_tex_desc *size)
{
    if (!p || !size)
        return;
    p->raster = *size;
    p->has_raster_size = true;
    fg_invalidate(p->g);
}

const char *fg_last_error(const fg_graph *g)
{
    return g && g->error[0] ? g->error : "";
}
