/* The barrier checker (dirt_gpu_opts.check_barriers, DIRT_CHECK_BARRIERS=1).
 *
 * Every GL call of the engine that reads or writes memory goes through the
 * gl_chk_* forms (gl.h's macros). For a draw or dispatch the checker asks
 * GL what the current program can touch: the buffers bound at its storage
 * blocks, uniform blocks and atomic counter buffers, the textures at its
 * images and samplers (buffer textures: their buffers), the indirect
 * buffer, the vertex array's enabled attributes and the framebuffer's
 * attachments; whether a block or image is read, written or both comes
 * from the program's source (gl_check_program). Transfers (uploads,
 * clears, readbacks, mipmap generation, framebuffer clears and reads) name
 * their object. Per GL buffer and texture it keeps the time of the last
 * incoherent shader write (storage block write, image store or atomic,
 * atomic counter) and of the last access by the pipeline, and per barrier
 * bit the time it was last issued. An access L to an object O is a hazard
 * when O was written by a shader after the last glMemoryBarrier with L's
 * bit (read or write after write), or when L is itself an incoherent write
 * and O was accessed by the pipeline after it (write after read): the rule
 * of doc/frame-graph.md, section 4, except that transfers (API uploads,
 * clears, readbacks) leave nothing pending, GL orders them itself. L's bit
 * is the one the frame graph derives (fg_barrier_bit).
 *
 * This file calls GL directly (DIRT_GL_RAW). */
#define DIRT_GL_RAW 1
#include "gl/gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/glsl_iface.h"

const char *const dirt_gpu_hazard_messages[DIRT_GPU_HAZARD_COUNT] = {
#define DIRT_GPU_HAZARD_MSG_(id, msg) msg,
    DIRT_GPU_HAZARDS(DIRT_GPU_HAZARD_MSG_)
#undef DIRT_GPU_HAZARD_MSG_
};

/* Kinds of access. */
enum acc {
    A_SSBO_READ, A_SSBO_WRITE, A_IMAGE_LOAD, A_IMAGE_STORE, A_ATOMIC, A_UNIFORM, A_SAMPLED,
    A_VERTEX, A_INDIRECT, A_FB_READ, A_FB_WRITE, A_UPDATE_READ, A_UPDATE_WRITE, A_COUNT
};

static const char *const acc_names[A_COUNT] = {
    "storage block read", "storage block write", "image load", "image store or atomic",
    "atomic counter", "uniform block read", "texture fetch", "vertex fetch",
    "indirect command read", "framebuffer read", "framebuffer write", "transfer read",
    "transfer write",
};

static bool incoherent(enum acc a)
{
    return a == A_SSBO_WRITE || a == A_IMAGE_STORE || a == A_ATOMIC;
}

static bool writes(enum acc a)
{
    return incoherent(a) || a == A_FB_WRITE || a == A_UPDATE_WRITE;
}

static bool pipeline(enum acc a)
{
    return a != A_UPDATE_READ && a != A_UPDATE_WRITE;
}

/* The consumer bit of access a (doc/frame-graph.md, section 4). */
static GLbitfield bit_of(enum acc a, bool texture)
{
    switch (a) {
    case A_SSBO_READ:
    case A_SSBO_WRITE: return GL_SHADER_STORAGE_BARRIER_BIT;
    case A_IMAGE_LOAD:
    case A_IMAGE_STORE: return GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    case A_ATOMIC: return GL_ATOMIC_COUNTER_BARRIER_BIT;
    case A_UNIFORM: return GL_UNIFORM_BARRIER_BIT;
    case A_SAMPLED: return GL_TEXTURE_FETCH_BARRIER_BIT;
    case A_VERTEX: return GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT;
    case A_INDIRECT: return GL_COMMAND_BARRIER_BIT;
    case A_FB_READ:
    case A_FB_WRITE: return GL_FRAMEBUFFER_BARRIER_BIT;
    default: return texture ? GL_TEXTURE_UPDATE_BARRIER_BIT : GL_BUFFER_UPDATE_BARRIER_BIT;
    }
}

static const char *bit_name(GLbitfield b)
{
    switch (b) {
    case GL_SHADER_STORAGE_BARRIER_BIT: return "GL_SHADER_STORAGE_BARRIER_BIT";
    case GL_SHADER_IMAGE_ACCESS_BARRIER_BIT: return "GL_SHADER_IMAGE_ACCESS_BARRIER_BIT";
    case GL_ATOMIC_COUNTER_BARRIER_BIT: return "GL_ATOMIC_COUNTER_BARRIER_BIT";
    case GL_UNIFORM_BARRIER_BIT: return "GL_UNIFORM_BARRIER_BIT";
    case GL_TEXTURE_FETCH_BARRIER_BIT: return "GL_TEXTURE_FETCH_BARRIER_BIT";
    case GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT: return "GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT";
    case GL_COMMAND_BARRIER_BIT: return "GL_COMMAND_BARRIER_BIT";
    case GL_FRAMEBUFFER_BARRIER_BIT: return "GL_FRAMEBUFFER_BARRIER_BIT";
    case GL_TEXTURE_UPDATE_BARRIER_BIT: return "GL_TEXTURE_UPDATE_BARRIER_BIT";
    case GL_BUFFER_UPDATE_BARRIER_BIT: return "GL_BUFFER_UPDATE_BARRIER_BIT";
    default: return "barrier";
    }
}

static int bit_index(GLbitfield b)
{
    for (int i = 0; i < 32; i++) {
        if (b == (1u << i))
            return i;
    }
    return 0;
}

/* One GL buffer or texture. */
typedef struct obj {
    uint64_t w_time, a_time;     /* last incoherent shader write, last pipeline access */
    uint8_t w_acc, a_acc;
    char w_where[200], a_where[200];
} obj;

/* What a program touches. */
enum res_kind { R_SSBO, R_UBO, R_ATOMIC, R_IMAGE, R_SAMPLER };

typedef struct pres {
    enum res_kind kind;
    int access;                  /* GLSL_READ / GLSL_WRITE / GLSL_READ_WRITE */
    GLint index;                 /* blocks: binding; images, samplers: location */
    GLint count;                 /* images, samplers: array size */
    GLenum query;                /* samplers: the texture binding to ask for */
    bool buffer_texture;         /* samplerBuffer, imageBuffer: the buffer behind */
} pres;

typedef struct prog {
    bool known;
    char label[64];
    pres *res;
    int n;
} prog;

#define MAX_SITES 256
#define MAX_GROUPS 8

typedef struct gl_checker {
    dirt_gpu *gpu;
    bool fatal;
    uint64_t now;
    uint64_t issued[32];
    obj *bufs, *texs;
    size_t nbufs, ntexs;
    prog *progs;
    size_t nprogs;
    char groups[MAX_GROUPS][64];
    int depth;
    dirt_gpu_barrier_check counts;
    gl_barrier_site sites[MAX_SITES];
    int nsites;
    char drop[128];
    uint64_t dropped;
} gl_checker;


/* The checker of the current GPU, NULL when it does not check. */
static gl_checker *current(void)
{
    dirt_gpu *gpu = gl_current();
    return gpu ? gpu->check : NULL;
}

/* ---- objects --------------------------------------------------------------- */

static obj *object(gl_checker *c, bool texture, GLuint name)
{
    obj **a = texture ? &c->texs : &c->bufs;
    size_t *n = texture ? &c->ntexs : &c->nbufs;
    if (name >= *n) {
        size_t m = *n ? *n : 64;
        while (m <= name)
            m *= 2;
        obj *g = realloc(*a, m * sizeof(*g));
        if (!g)
            return NULL;
        memset(g + *n, 0, (m - *n) * sizeof(*g));
        *a = g;
        *n = m;
    }
    return &(*a)[name];
}

/* A new or deleted name starts clean (GL reuses names). */
static void forget(gl_checker *c, bool texture, GLsizei n, const GLuint *names)
{
    for (GLsizei i = 0; i < n; i++) {
        obj *o = names[i] ? object(c, texture, names[i]) : NULL;
        if (o)
            memset(o, 0, sizeof(*o));
    }
}

/* File name from the last folder src/ or test/ on (neither has a folder of
 * that name inside, and the source tree itself may sit in one: the install
 * test builds a copy at .../src/). */
static const char *short_file(const char *file)
{
    const char *best = NULL;
    for (const char *p = file; *p; p++) {
        if ((!strncmp(p, "src/", 4) || !strncmp(p, "test/", 5)) && (p == file || p[-1] == '/'))
            best = p;
    }
    return best ? best : file;
}

/* "dispatch of 'mmrt/trace.comp' (src/mmrt/trace.c:79) in 'a / b'" */
static void describe(gl_checker *c, const char *what, GLuint program, const char *file,
                     int line, char *out, size_t size)
{
    char groups[160] = "";
    size_t len = 0;
    for (int i = 0; i < c->depth && i < MAX_GROUPS && len + 4 < sizeof(groups); i++)
        len += (size_t)snprintf(groups + len, sizeof(groups) - len, "%s%s", i ? " / " : "",
                                c->groups[i]);
    char prog_part[96] = "";
    if (program) {
        const char *label = program < c->nprogs && c->progs[program].known
                                ? c->progs[program].label : "?";
        snprintf(prog_part, sizeof(prog_part), " of '%s'", label);
    }
    snprintf(out, size, "%s%s (%s:%d)%s%s%s", what, prog_part, short_file(file), line,
             c->depth ? " in '" : "", groups, c->depth ? "'" : "");
}

static void object_label(bool texture, GLuint name, char *out, size_t size)
{
    GLsizei len = 0;
    out[0] = '\0';
    glGetObjectLabel(texture ? GL_TEXTURE : GL_BUFFER, name, (GLsizei)size, &len, out);
    if (!len)
        snprintf(out, size, "%s %u", texture ? "texture" : "buffer", name);
}

/* ---- one command ------------------------------------------------------------ */

typedef struct chk_access {
    bool texture;
    GLuint name;
    enum acc acc;
} chk_access;

#define MAX_ACCESSES 160

typedef struct command {
    chk_access a[MAX_ACCESSES];
    int n;
} command;

static void add(command *cmd, bool texture, GLuint name, enum acc a)
{
    if (!name || cmd->n >= MAX_ACCESSES)
        return;
    for (int i = 0; i < cmd->n; i++) {
        if (cmd->a[i].texture == texture && cmd->a[i].name == name && cmd->a[i].acc == a)
            return;
    }
    cmd->a[cmd->n++] = (chk_access){texture, name, a};
}

static void hazard(gl_checker *c, enum dirt_gpu_hazard kind, const char *where,
                   const chk_access *a, const obj *o, bool after_write, GLbitfield bit)
{
    char label[128];
    object_label(a->texture, a->name, label, sizeof(label));
    const char *verb = writes(a->acc) ? "writes" : "reads";
    dirt_log(DIRT_LOG_ERROR, NULL, 0,
             "barrier check: %s %s %s '%s' (%s) after %s %s it (%s) with no %s in between: %s",
             where, verb, a->texture ? "texture" : "buffer", label, acc_names[a->acc],
             after_write ? o->w_where : o->a_where, after_write ? "wrote" : "accessed",
             acc_names[after_write ? o->w_acc : o->a_acc], bit_name(bit),
             dirt_gpu_hazard_messages[kind]);
    c->counts.hazards[kind]++;
    c->counts.total++;
    __atomic_fetch_add(&c->gpu->error_count, 1, __ATOMIC_RELAXED);
    if (c->fatal) {
        dirt_log(DIRT_LOG_ERROR, NULL, 0, "barrier check: DIRT_CHECK_BARRIERS=1: stopping at "
                                          "the first hazard");
        abort();
    }
}

/* Checks the command's accesses against what came before, then records
 * them. */
static void run_command(gl_checker *c, command *cmd, const char *where)
{
    c->counts.commands++;
    for (int i = 0; i < cmd->n; i++) {
        const chk_access *a = &cmd->a[i];
        obj *o = object(c, a->texture, a->name);
        if (!o)
            continue;
        GLbitfield bit = bit_of(a->acc, a->texture);
        uint64_t issued = c->issued[bit_index(bit)];
        if (o->w_time > issued) {
            hazard(c, writes(a->acc) ? DIRT_GPU_HAZARD_WRITE_AFTER_WRITE
                                     : DIRT_GPU_HAZARD_READ_AFTER_WRITE, where, a, o, true, bit);
            o->w_time = 0; /* once per write */
        } else if (incoherent(a->acc) && o->a_time > issued) {
            hazard(c, DIRT_GPU_HAZARD_WRITE_AFTER_READ, where, a, o, false, bit);
            o->a_time = 0;
        }
    }
    c->now++;
    for (int i = 0; i < cmd->n; i++) {
        const chk_access *a = &cmd->a[i];
        obj *o = object(c, a->texture, a->name);
        if (!o)
            continue;
        if (pipeline(a->acc)) {
            o->a_time = c->now;
            o->a_acc = (uint8_t)a->acc;
            snprintf(o->a_where, sizeof(o->a_where), "%s", where);
        }
        if (incoherent(a->acc)) {
            o->w_time = c->now;
            o->w_acc = (uint8_t)a->acc;
            snprintf(o->w_where, sizeof(o->w_where), "%s", where);
        }
    }
}

/* One transfer on one object. */
static void transfer(gl_checker *c, bool texture, GLuint name, enum acc a, const char *what,
                     const char *file, int line)
{
    command cmd = {.n = 0};
    add(&cmd, texture, name, a);
    char where[200];
    describe(c, what, 0, file, line, where, sizeof(where));
    run_command(c, &cmd, where);
}

/* ---- programs ----------------------------------------------------------------- */

static prog *program(gl_checker *c, GLuint p)
{
    if (p >= c->nprogs) {
        size_t m = c->nprogs ? c->nprogs : 64;
        while (m <= p)
            m *= 2;
        prog *g = realloc(c->progs, m * sizeof(*g));
        if (!g)
            return NULL;
        memset(g + c->nprogs, 0, (m - c->nprogs) * sizeof(*g));
        c->progs = g;
        c->nprogs = m;
    }
    return &c->progs[p];
}

static void drop_program(gl_checker *c, GLuint p)
{
    if (p < c->nprogs) {
        free(c->progs[p].res);
        memset(&c->progs[p], 0, sizeof(c->progs[p]));
    }
}

/* The texture binding a sampler type is read from (0: not followed). */
static GLenum sampler_query(GLenum type, bool *buffer)
{
    *buffer = false;
    switch (type) {
    case GL_SAMPLER_2D: case GL_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_2D:
    case GL_SAMPLER_2D_SHADOW:
        return GL_TEXTURE_BINDING_2D;
    case GL_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_SAMPLER_2D_ARRAY_SHADOW:
        return GL_TEXTURE_BINDING_2D_ARRAY;
    case GL_SAMPLER_3D: case GL_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_3D:
        return GL_TEXTURE_BINDING_3D;
    case GL_SAMPLER_CUBE: case GL_INT_SAMPLER_CUBE: case GL_UNSIGNED_INT_SAMPLER_CUBE:
        return GL_TEXTURE_BINDING_CUBE_MAP;
    case GL_SAMPLER_1D: case GL_INT_SAMPLER_1D: case GL_UNSIGNED_INT_SAMPLER_1D:
        return GL_TEXTURE_BINDING_1D;
    case GL_SAMPLER_BUFFER: case GL_INT_SAMPLER_BUFFER: case GL_UNSIGNED_INT_SAMPLER_BUFFER:
        *buffer = true;
        return GL_TEXTURE_BINDING_BUFFER;
    default:
        return 0;
    }
}

static bool image_type(GLenum type, bool *buffer)
{
    *buffer = type == GL_IMAGE_BUFFER || type == GL_INT_IMAGE_BUFFER ||
              type == GL_UNSIGNED_INT_IMAGE_BUFFER;
    switch (type) {
    case GL_IMAGE_1D: case GL_IMAGE_2D: case GL_IMAGE_3D: case GL_IMAGE_CUBE:
    case GL_IMAGE_BUFFER: case GL_IMAGE_1D_ARRAY: case GL_IMAGE_2D_ARRAY:
    case GL_INT_IMAGE_1D: case GL_INT_IMAGE_2D: case GL_INT_IMAGE_3D: case GL_INT_IMAGE_CUBE:
    case GL_INT_IMAGE_BUFFER: case GL_INT_IMAGE_1D_ARRAY: case GL_INT_IMAGE_2D_ARRAY:
    case GL_UNSIGNED_INT_IMAGE_1D: case GL_UNSIGNED_INT_IMAGE_2D:
    case GL_UNSIGNED_INT_IMAGE_3D: case GL_UNSIGNED_INT_IMAGE_CUBE:
    case GL_UNSIGNED_INT_IMAGE_BUFFER: case GL_UNSIGNED_INT_IMAGE_1D_ARRAY:
    case GL_UNSIGNED_INT_IMAGE_2D_ARRAY:
        return true;
    default:
        return false;
    }
}

static void push_res(prog *pr, pres r)
{
    pres *g = realloc(pr->res, (size_t)(pr->n + 1) * sizeof(*g));
    if (!g)
        return;
    pr->res = g;
    pr->res[pr->n++] = r;
}

/* Access of declaration `name` (an array's "[0]" dropped), READ_WRITE when
 * the sources do not declare it. */
static int decl_access(const glsl_decl *d, int n, const char *name, bool image, bool *found)
{
    char base[64];
    snprintf(base, sizeof(base), "%s", name);
    char *br = strchr(base, '[');
    if (br)
        *br = '\0';
    for (int i = 0; i < n; i++) {
        if (d[i].image == image && !strcmp(d[i].name, base)) {
            *found = true;
            return d[i].access;
        }
    }
    *found = false;
    return GLSL_READ_WRITE;
}

void gl_check_program(GLuint p, const char *label, char *const *sources, int nsrc)
{
    gl_checker *c = current();
    if (!c || !p)
        return;
    prog *pr = program(c, p);
    if (!pr)
        return;
    drop_program(c, p);
    pr->known = true;
    snprintf(pr->label, sizeof(pr->label), "%s", label ? label : "?");
    enum { MAX_DECLS = 96 };
    glsl_decl decls[MAX_DECLS];
    int nd = 0;
    for (int s = 0; s < nsrc; s++) {
        glsl_decl one[MAX_DECLS];
        int k = glsl_memory_decls(sources[s], one, MAX_DECLS);
        for (int i = 0; i < k && i < MAX_DECLS; i++) {
            bool merged = false;
            for (int j = 0; j < nd && !merged; j++) {
                if (decls[j].image == one[i].image && !strcmp(decls[j].name, one[i].name)) {
                    decls[j].access |= one[i].access;
                    merged = true;
                }
            }
            if (!merged && nd < MAX_DECLS)
                decls[nd++] = one[i];
        }
    }
    static const struct { GLenum iface; enum res_kind kind; } blocks[] = {
        {GL_SHADER_STORAGE_BLOCK, R_SSBO}, {GL_UNIFORM_BLOCK, R_UBO},
        {GL_ATOMIC_COUNTER_BUFFER, R_ATOMIC}};
    for (size_t b = 0; b < sizeof(blocks) / sizeof(blocks[0]); b++) {
        GLint count = 0;
        glGetProgramInterfaceiv(p, blocks[b].iface, GL_ACTIVE_RESOURCES, &count);
        for (GLint i = 0; i < count; i++) {
            GLenum prop = GL_BUFFER_BINDING;
            GLint binding = 0;
            glGetProgramResourceiv(p, blocks[b].iface, (GLuint)i, 1, &prop, 1, NULL, &binding);
            int access = blocks[b].kind == R_UBO ? GLSL_READ : GLSL_READ_WRITE;
            if (blocks[b].kind == R_SSBO) {
                char name[64] = "";
                glGetProgramResourceName(p, GL_SHADER_STORAGE_BLOCK, (GLuint)i, sizeof(name),
                                         NULL, name);
                bool found;
                access = decl_access(decls, nd, name, false, &found);
                if (!found && nsrc > 0)
                    DIRT_ERROR("barrier check: program '%s': storage block %s is not in its "
                               "source as read: taken as read and written", pr->label, name);
            }
            push_res(pr, (pres){.kind = blocks[b].kind, .access = access, .index = binding});
        }
    }
    GLint uniforms = 0;
    glGetProgramInterfaceiv(p, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
    for (GLint i = 0; i < uniforms; i++) {
        GLenum props[3] = {GL_TYPE, GL_LOCATION, GL_ARRAY_SIZE};
        GLint v[3] = {0, -1, 1};
        glGetProgramResourceiv(p, GL_UNIFORM, (GLuint)i, 3, props, 3, NULL, v);
        if (v[1] < 0)
            continue; /* in a block */
        bool buffer = false;
        GLenum query = sampler_query((GLenum)v[0], &buffer);
        if (query) {
            push_res(pr, (pres){.kind = R_SAMPLER, .access = GLSL_READ, .index = v[1],
                                .count = v[2], .query = query, .buffer_texture = buffer});
        } else if (image_type((GLenum)v[0], &buffer)) {
            char name[64] = "";
            glGetProgramResourceName(p, GL_UNIFORM, (GLuint)i, sizeof(name), NULL, name);
            bool found;
            int access = decl_access(decls, nd, name, true, &found);
            push_res(pr, (pres){.kind = R_IMAGE, .access = access, .index = v[1],
                                .count = v[2], .buffer_texture = buffer});
        }
    }
}

/* The buffer behind buffer texture `tex`. */
static GLuint buffer_of(GLuint tex)
{
    GLint buf = 0;
    if (tex)
        glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_BUFFER_DATA_STORE_BINDING, &buf);
    return (GLuint)buf;
}

/* What the current program touches. */
static GLuint program_accesses(gl_checker *c, command *cmd)
{
    GLint p = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &p);
    if (p <= 0)
        return 0;
    prog *pr = program(c, (GLuint)p);
    if (pr && !pr->known) {
        /* Not made by gl_program_create: every block read and written. */
        gl_check_program((GLuint)p, "(a program made elsewhere)", NULL, 0);
        pr = program(c, (GLuint)p);
    }
    if (!pr || !pr->known)
        return (GLuint)p;
    GLint active = 0;
    bool active_saved = false;
    for (int i = 0; i < pr->n; i++) {
        const pres *r = &pr->res[i];
        GLint name = 0;
        switch (r->kind) {
        case R_SSBO:
            glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, (GLuint)r->index, &name);
            if (r->access & GLSL_READ)
                add(cmd, false, (GLuint)name, A_SSBO_READ);
            if (r->access & GLSL_WRITE)
                add(cmd, false, (GLuint)name, A_SSBO_WRITE);
            break;
        case R_UBO:
            glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, (GLuint)r->index, &name);
            add(cmd, false, (GLuint)name, A_UNIFORM);
            break;
        case R_ATOMIC:
            glGetIntegeri_v(GL_ATOMIC_COUNTER_BUFFER_BINDING, (GLuint)r->index, &name);
            add(cmd, false, (GLuint)name, A_ATOMIC);
            break;
        case R_IMAGE:
            for (GLint e = 0; e < r->count; e++) {
                GLint unit = 0, mode = GL_READ_WRITE;
                glGetUniformiv((GLuint)p, r->index + e, &unit);
                glGetIntegeri_v(GL_IMAGE_BINDING_NAME, (GLuint)unit, &name);
                glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, (GLuint)unit, &mode);
                int access = r->access & (mode == GL_READ_ONLY ? GLSL_READ
                                          : mode == GL_WRITE_ONLY ? GLSL_WRITE
                                                                  : GLSL_READ_WRITE);
                bool tex = !r->buffer_texture;
                GLuint obj_name = tex ? (GLuint)name : buffer_of((GLuint)name);
                if (access & GLSL_READ)
                    add(cmd, tex, obj_name, A_IMAGE_LOAD);
                if (access & GLSL_WRITE)
                    add(cmd, tex, obj_name, A_IMAGE_STORE);
            }
            break;
        case R_SAMPLER:
            if (!active_saved) {
                glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
                active_saved = true;
            }
            for (GLint e = 0; e < r->count; e++) {
                GLint unit = 0;
                glGetUniformiv((GLuint)p, r->index + e, &unit);
                glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
                glGetIntegerv(r->query, &name);
                if (r->buffer_texture)
                    add(cmd, false, buffer_of((GLuint)name), A_SAMPLED);
                else
                    add(cmd, true, (GLuint)name, A_SAMPLED);
            }
            break;
        }
    }
    if (active_saved)
        glActiveTexture((GLenum)active);
    return (GLuint)p;
}

/* The textures attached to framebuffer `fb` (0: the window's: none). */
static void attachments(command *cmd, GLuint fb, enum acc a)
{
    if (!fb)
        return;
    static const GLenum att[] = {
        GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3,
        GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5, GL_COLOR_ATTACHMENT6, GL_COLOR_ATTACHMENT7,
        GL_DEPTH_ATTACHMENT, GL_STENCIL_ATTACHMENT};
    for (size_t i = 0; i < sizeof(att) / sizeof(att[0]); i++) {
        GLint type = GL_NONE, name = 0;
        glGetNamedFramebufferAttachmentParameteriv(fb, att[i],
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type != GL_TEXTURE)
            continue;
        glGetNamedFramebufferAttachmentParameteriv(fb, att[i],
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
        add(cmd, true, (GLuint)name, a);
    }
}

static GLuint bound(GLenum query)
{
    GLint v = 0;
    glGetIntegerv(query, &v);
    return (GLuint)v;
}

/* ---- lifetime and hooks ---------------------------------------------------------- */

bool gl_check_init(dirt_gpu *gpu)
{
    const char *env = getenv("DIRT_CHECK_BARRIERS");
    bool env_on = env && *env && strcmp(env, "0") != 0;
    if (!gpu->opts.check_barriers && !env_on)
        return true;
    gl_checker *c = calloc(1, sizeof(*c));
    if (!c) {
        DIRT_ERROR("out of memory");
        return false;
    }
    c->gpu = gpu;
    c->fatal = env_on && !gpu->opts.check_barriers && strcmp(env, "count") != 0;
    c->counts.on = true;
    const char *drop = getenv("DIRT_DROP_BARRIER");
    if (drop && *drop)
        snprintf(c->drop, sizeof(c->drop), "%s", drop);
    gpu->check = c;
    return true;
}

void gl_check_release(dirt_gpu *gpu)
{
    gl_checker *c = gpu->check;
    if (!c)
        return;
    if (c->drop[0] && !c->dropped)
        DIRT_WARN("barrier check: the dropped barrier %s was never called", c->drop);
    for (size_t i = 0; i < c->nprogs; i++)
        free(c->progs[i].res);
    free(c->progs);
    free(c->bufs);
    free(c->texs);
    free(c);
    gpu->check = NULL;
}

void gl_check_group(const char *push_name)
{
    gl_checker *c = current();
    if (!c)
        return;
    if (!push_name) {
        if (c->depth > 0)
            c->depth--;
        return;
    }
    if (c->depth < MAX_GROUPS)
        snprintf(c->groups[c->depth], sizeof(c->groups[0]), "%s", push_name);
    c->depth++;
}

void gl_check_drop_barrier(dirt_gpu *gpu, const char *site)
{
    if (!gpu->check)
        return;
    snprintf(gpu->check->drop, sizeof(gpu->check->drop), "%s", site ? site : "");
    gpu->check->dropped = 0;
}

uint64_t gl_check_dropped(const dirt_gpu *gpu)
{
    return gpu->check ? gpu->check->dropped : 0;
}

int gl_check_barrier_sites(const dirt_gpu *gpu, gl_barrier_site *out, int max)
{
    const gl_checker *c = gpu->check;
    if (!c)
        return 0;
    for (int i = 0; i < c->nsites && i < max; i++)
        out[i] = c->sites[i];
    return c->nsites;
}

dirt_gpu_barrier_check dirt_gpu_barrier_counts(const dirt_gpu *gpu)
{
    return gpu->check ? gpu->check->counts : (dirt_gpu_barrier_check){0};
}

/* ---- the checked calls -------------------------------------------------------------- */

void gl_chk_MemoryBarrier(GLbitfield bits, const char *file, int line)
{
    gl_checker *c = current();
    if (!c) {
        glMemoryBarrier(bits);
        return;
    }
    char site[128];
    snprintf(site, sizeof(site), "%s:%d", short_file(file), line);
    int s = 0;
    while (s < c->nsites && strcmp(c->sites[s].site, site) != 0)
        s++;
    if (s == c->nsites && s < MAX_SITES) {
        snprintf(c->sites[s].site, sizeof(c->sites[s].site), "%s", site);
        c->nsites++;
    }
    if (s < MAX_SITES)
        c->sites[s].calls++;
    if (c->drop[0] && !strcmp(c->drop, site)) {
        if (!c->dropped)
            DIRT_WARN("barrier check: test hook: the glMemoryBarrier at %s issues nothing", site);
        c->dropped++;
        return;
    }
    glMemoryBarrier(bits);
    c->counts.barriers++;
    c->now++;
    for (int i = 0; i < 32; i++) {
        if (bits & (1u << i))
            c->issued[i] = c->now;
    }
}

static void draw_or_dispatch(gl_checker *c, bool draw, bool indirect, const char *file,
                             int line)
{
    command cmd = {.n = 0};
    GLuint p = program_accesses(c, &cmd);
    if (indirect)
        add(&cmd, false, bound(draw ? GL_DRAW_INDIRECT_BUFFER_BINDING
                                    : GL_DISPATCH_INDIRECT_BUFFER_BINDING), A_INDIRECT);
    if (draw) {
        if (bound(GL_VERTEX_ARRAY_BINDING)) {
            GLint max_attribs = 16;
            glGetIntegerv(GL_MAX_VERTEX_ATTRIBS, &max_attribs);
            for (GLint i = 0; i < max_attribs; i++) {
                GLint on = 0, buf = 0;
                glGetVertexAttribiv((GLuint)i, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &on);
                if (!on)
                    continue;
                glGetVertexAttribiv((GLuint)i, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &buf);
                add(&cmd, false, (GLuint)buf, A_VERTEX);
            }
        }
        attachments(&cmd, bound(GL_DRAW_FRAMEBUFFER_BINDING), A_FB_WRITE);
    }
    char where[200];
    describe(c, draw ? "draw" : "dispatch", p, file, line, where, sizeof(where));
    run_command(c, &cmd, where);
}

void gl_chk_DispatchCompute(GLuint x, GLuint y, GLuint z, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        draw_or_dispatch(c, false, false, file, line);
    glDispatchCompute(x, y, z);
}

void gl_chk_DispatchComputeIndirect(GLintptr offset, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        draw_or_dispatch(c, false, true, file, line);
    glDispatchComputeIndirect(offset);
}

void gl_chk_DrawArrays(GLenum mode, GLint first, GLsizei count, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        draw_or_dispatch(c, true, false, file, line);
    glDrawArrays(mode, first, count);
}

void gl_chk_ClearNamedBufferData(GLuint buf, GLenum ifmt, GLenum fmt, GLenum type,
                                 const void *data, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, false, buf, A_UPDATE_WRITE, "buffer clear", file, line);
    glClearNamedBufferData(buf, ifmt, fmt, type, data);
}

void gl_chk_ClearNamedBufferSubData(GLuint buf, GLenum ifmt, GLintptr off, GLsizeiptr size,
                                    GLenum fmt, GLenum type, const void *data, const char *file,
                                    int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, false, buf, A_UPDATE_WRITE, "buffer clear", file, line);
    glClearNamedBufferSubData(buf, ifmt, off, size, fmt, type, data);
}

void gl_chk_NamedBufferSubData(GLuint buf, GLintptr off, GLsizeiptr size, const void *data,
                               const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, false, buf, A_UPDATE_WRITE, "buffer upload", file, line);
    glNamedBufferSubData(buf, off, size, data);
}

void gl_chk_GetNamedBufferSubData(GLuint buf, GLintptr off, GLsizeiptr size, void *data,
                                  const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, false, buf, A_UPDATE_READ, "buffer readback", file, line);
    glGetNamedBufferSubData(buf, off, size, data);
}

void gl_chk_ClearTexImage(GLuint tex, GLint level, GLenum fmt, GLenum type, const void *data,
                          const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, true, tex, A_UPDATE_WRITE, "texture clear", file, line);
    glClearTexImage(tex, level, fmt, type, data);
}

void gl_chk_TextureSubImage2D(GLuint tex, GLint level, GLint x, GLint y, GLsizei w, GLsizei h,
                              GLenum fmt, GLenum type, const void *data, const char *file,
                              int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, true, tex, A_UPDATE_WRITE, "texture upload", file, line);
    glTextureSubImage2D(tex, level, x, y, w, h, fmt, type, data);
}

void gl_chk_GetTextureImage(GLuint tex, GLint level, GLenum fmt, GLenum type, GLsizei size,
                            void *data, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, true, tex, A_UPDATE_READ, "texture readback", file, line);
    glGetTextureImage(tex, level, fmt, type, size, data);
}

void gl_chk_GenerateTextureMipmap(GLuint tex, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        transfer(c, true, tex, A_UPDATE_WRITE, "mipmap generation", file, line);
    glGenerateTextureMipmap(tex);
}

/* A framebuffer clear or read: every texture attached. */
static void framebuffer_op(gl_checker *c, GLuint fb, enum acc a, const char *what,
                           const char *file, int line)
{
    command cmd = {.n = 0};
    attachments(&cmd, fb, a);
    char where[200];
    describe(c, what, 0, file, line, where, sizeof(where));
    run_command(c, &cmd, where);
}

void gl_chk_Clear(GLbitfield mask, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        framebuffer_op(c, bound(GL_DRAW_FRAMEBUFFER_BINDING), A_FB_WRITE, "framebuffer clear",
                       file, line);
    glClear(mask);
}

void gl_chk_ClearBufferfv(GLenum buffer, GLint drawbuffer, const GLfloat *value,
                          const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        framebuffer_op(c, bound(GL_DRAW_FRAMEBUFFER_BINDING), A_FB_WRITE, "framebuffer clear",
                       file, line);
    glClearBufferfv(buffer, drawbuffer, value);
}

void gl_chk_ClearNamedFramebufferfv(GLuint fb, GLenum buffer, GLint drawbuffer,
                                    const GLfloat *value, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        framebuffer_op(c, fb, A_FB_WRITE, "framebuffer clear", file, line);
    glClearNamedFramebufferfv(fb, buffer, drawbuffer, value);
}

void gl_chk_ClearNamedFramebufferuiv(GLuint fb, GLenum buffer, GLint drawbuffer,
                                     const GLuint *value, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        framebuffer_op(c, fb, A_FB_WRITE, "framebuffer clear", file, line);
    glClearNamedFramebufferuiv(fb, buffer, drawbuffer, value);
}

void gl_chk_ReadPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum fmt, GLenum type,
                       void *data, const char *file, int line)
{
    gl_checker *c = current();
    if (c)
        framebuffer_op(c, bound(GL_READ_FRAMEBUFFER_BINDING), A_FB_READ, "framebuffer read",
                       file, line);
    glReadPixels(x, y, w, h, fmt, type, data);
}

void gl_chk_CreateBuffers(GLsizei n, GLuint *names)
{
    glCreateBuffers(n, names);
    gl_checker *c = current();
    if (c)
        forget(c, false, n, names);
}

void gl_chk_DeleteBuffers(GLsizei n, const GLuint *names)
{
    gl_checker *c = current();
    if (c)
        forget(c, false, n, names);
    glDeleteBuffers(n, names);
}

void gl_chk_CreateTextures(GLenum target, GLsizei n, GLuint *names)
{
    glCreateTextures(target, n, names);
    gl_checker *c = current();
    if (c)
        forget(c, true, n, names);
}

void gl_chk_DeleteTextures(GLsizei n, const GLuint *names)
{
    gl_checker *c = current();
    if (c)
        forget(c, true, n, names);
    glDeleteTextures(n, names);
}

void gl_chk_DeleteProgram(GLuint p)
{
    gl_checker *c = current();
    if (c)
        drop_program(c, p);
    glDeleteProgram(p);
}
