/* Drawing images into the window (gl/window.h): the presentation program
 * (glsl/present/), window clears and read-back, RGBA32F textures of CPU
 * images. Every function leaves the GL state it found: the session renders
 * with its own state between presents. */
#include "gl/window.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/constants.h"
#include "common/display.h"
#include "gl/gl.h"
#include "gl/program.h"

/* The window of `gpu`, false after logging `what` on a headless GPU. */
static bool has_window(dirt_gpu *gpu, const char *what)
{
    if (!gpu || !gpu->window) {
        DIRT_ERROR("%s: the GPU has no window (create it with dirt_gpu_opts.window)", what);
        return false;
    }
    return true;
}

/* ---- saved GL state ---- */

#define SAVED_CAPS 6
static const GLenum saved_caps[SAVED_CAPS] = {GL_BLEND, GL_DEPTH_TEST, GL_STENCIL_TEST,
                                              GL_SCISSOR_TEST, GL_CULL_FACE,
                                              GL_FRAMEBUFFER_SRGB};

/* What a draw into the default framebuffer changes. */
typedef struct saved_state {
    GLint draw_fb, viewport[4], program, vao, active_unit;
    GLint texture[2], sampler[2];
    GLboolean caps[SAVED_CAPS];
    GLboolean color_mask[4];
    GLint polygon_mode[2];
} saved_state;

static const GLuint present_units[2] = {DIRT_UNIT_PRESENT_A, DIRT_UNIT_PRESENT_B};

static void save_state(saved_state *s)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fb);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_unit);
    for (int i = 0; i < 2; i++) {
        glActiveTexture(GL_TEXTURE0 + present_units[i]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->texture[i]);
        glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler[i]);
    }
    glActiveTexture((GLenum)s->active_unit);
    for (int i = 0; i < SAVED_CAPS; i++)
        s->caps[i] = glIsEnabled(saved_caps[i]);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    glGetIntegerv(GL_POLYGON_MODE, s->polygon_mode);
}

/* Plain drawing into the default framebuffer's back buffer. */
static void draw_state(void)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    for (int i = 0; i < SAVED_CAPS; i++)
        glDisable(saved_caps[i]);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

static void restore_state(const saved_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fb);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vao);
    for (int i = 0; i < 2; i++) {
        glBindTextureUnit(present_units[i], (GLuint)s->texture[i]);
        glBindSampler(present_units[i], (GLuint)s->sampler[i]);
    }
    glActiveTexture((GLenum)s->active_unit);
    for (int i = 0; i < SAVED_CAPS; i++)
        (s->caps[i] ? glEnable : glDisable)(saved_caps[i]);
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    glPolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
}

/* ---- presentation ---- */

static bool ensure_program(dirt_gpu *gpu)
{
    if (gpu->present_program)
        return true;
    static const char *const paths[] = {"present/present.vert", "present/present.frag", NULL};
    gpu->present_program = gl_program_create("present", paths, NULL, 0);
    if (!gpu->present_program)
        return false;
    glCreateVertexArrays(1, &gpu->present_vao);
    gl_label(GL_VERTEX_ARRAY, gpu->present_vao, "present (no attributes)");
    return true;
}

const char *dirt_gpu_glsl_dir(void)
{
    return glsl_root();
}

void dirt_gpu_set_glsl_dir(const char *dir)
{
    glsl_set_root(dir);
}

bool dirt_gpu_present_reload(dirt_gpu *gpu)
{
    if (!has_window(gpu, "dirt_gpu_present_reload"))
        return false;
    if (!gpu->present_program)
        return ensure_program(gpu);
    static const char *const paths[] = {"present/present.vert", "present/present.frag", NULL};
    GLuint fresh = gl_program_create("present", paths, NULL, 0);
    if (!fresh)
        return false;
    gl_program_destroy(&gpu->present_program);
    gpu->present_program = fresh;
    return true;
}

void gl_present_release(dirt_gpu *gpu)
{
    gl_program_destroy(&gpu->present_program);
    if (gpu->present_vao)
        glDeleteVertexArrays(1, &gpu->present_vao);
    gpu->present_vao = 0;
}

static bool is_texture_2d(GLuint tex)
{
    if (!tex || !glIsTexture(tex))
        return false;
    GLint target = 0;
    glGetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    return target == GL_TEXTURE_2D;
}

static int shader_mode(enum dirt_present_mode m)
{
    switch (m) {
    case DIRT_PRESENT_COLOR: return DIRT_PRESENT_ID_COLOR;
    case DIRT_PRESENT_HEAT: return DIRT_PRESENT_ID_HEAT;
    case DIRT_PRESENT_SIGNED: return DIRT_PRESENT_ID_SIGNED;
    case DIRT_PRESENT_DIFF: return DIRT_PRESENT_ID_DIFF;
    }
    return -1;
}

static int shader_tonemap(enum dirt_tonemap t)
{
    switch (t) {
    case DIRT_TONEMAP_CLAMP: return DIRT_TONEMAP_ID_CLAMP;
    case DIRT_TONEMAP_REINHARD: return DIRT_TONEMAP_ID_REINHARD;
    case DIRT_TONEMAP_ACES: return DIRT_TONEMAP_ID_ACES;
    }
    return -1;
}

bool dirt_gpu_present(dirt_gpu *gpu, const dirt_present_opts *opts)
{
    if (!has_window(gpu, "dirt_gpu_present"))
        return false;
    if (!opts) {
        DIRT_ERROR("dirt_gpu_present: NULL options");
        return false;
    }
    const dirt_present_opts *o = opts;
    int mode = shader_mode(o->mode);
    int tonemap = shader_tonemap(o->tonemap);
    bool split = o->split != 0.0f && o->mode != DIRT_PRESENT_DIFF;
    if (mode < 0 || tonemap < 0) {
        DIRT_ERROR("dirt_gpu_present: unknown mode %d or tone map %d", (int)o->mode,
                   (int)o->tonemap);
        return false;
    }
    if (o->w <= 0 || o->h <= 0) {
        DIRT_ERROR("dirt_gpu_present: rectangle %dx%d at (%d, %d) is empty", o->w, o->h, o->x,
                   o->y);
        return false;
    }
    if (!is_texture_2d(o->texture)) {
        DIRT_ERROR("dirt_gpu_present: texture %u is not a 2D texture", o->texture);
        return false;
    }
    if ((split || o->mode == DIRT_PRESENT_DIFF) && !is_texture_2d(o->texture_b)) {
        DIRT_ERROR("dirt_gpu_present: the %s needs texture_b (%u is not a 2D texture)",
                   split ? "split" : "difference", o->texture_b);
        return false;
    }
    if (split && !(o->split > 0.0f && o->split < 1.0f)) {
        DIRT_ERROR("dirt_gpu_present: split %g outside (0, 1)", (double)o->split);
        return false;
    }
    if ((o->mode == DIRT_PRESENT_HEAT || o->mode == DIRT_PRESENT_DIFF) &&
        !(isfinite(o->lo) && isfinite(o->hi) && o->hi > o->lo)) {
        DIRT_ERROR("dirt_gpu_present: range %g..%g (need finite lo < hi)", (double)o->lo,
                   (double)o->hi);
        return false;
    }
    if (o->mode == DIRT_PRESENT_HEAT && (o->channel < 0 || o->channel > 3)) {
        DIRT_ERROR("dirt_gpu_present: channel %d outside 0..3", o->channel);
        return false;
    }
    if (o->mode == DIRT_PRESENT_COLOR && !isfinite(o->exposure)) {
        DIRT_ERROR("dirt_gpu_present: exposure must be finite");
        return false;
    }

    gl_group_push("present");
    saved_state saved;
    save_state(&saved);
    bool ok = ensure_program(gpu);
    if (ok) {
        int win_w = 0, win_h = 0;
        dirt_gpu_window_size(gpu, &win_w, &win_h);
        int y_gl = win_h - o->y - o->h; /* the rectangle's bottom row, GL's way up */
        draw_state();
        glViewport(o->x, y_gl, o->w, o->h);
        glUseProgram(gpu->present_program);
        glBindVertexArray(gpu->present_vao);
        glBindTextureUnit(DIRT_UNIT_PRESENT_A, o->texture);
        glBindTextureUnit(DIRT_UNIT_PRESENT_B, o->texture_b ? o->texture_b : o->texture);
        glBindSampler(DIRT_UNIT_PRESENT_A, 0);
        glBindSampler(DIRT_UNIT_PRESENT_B, 0);
        glUniform4i(DIRT_LOC_PRESENT_RECT, o->x, y_gl, o->w, o->h);
        glUniform1i(DIRT_LOC_PRESENT_MODE, mode);
        /* The scale png.c multiplies by, computed the same way. */
        glUniform1f(DIRT_LOC_PRESENT_SCALE, exp2f(o->exposure));
        glUniform1i(DIRT_LOC_PRESENT_TONEMAP, tonemap);
        glUniform1i(DIRT_LOC_PRESENT_CHANNEL, o->channel);
        glUniform2f(DIRT_LOC_PRESENT_RANGE, o->lo, o->hi);
        glUniform1f(DIRT_LOC_PRESENT_SPLIT, split ? (float)o->x + o->split * (float)o->w : -1.0f);
        glUniform1i(DIRT_LOC_PRESENT_SPLIT_LINE, split && o->split_line ? 1 : 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        ok = gl_check("present");
    }
    restore_state(&saved);
    gl_group_pop();
    return ok;
}

bool dirt_gpu_window_clear(dirt_gpu *gpu, const float rgb[3])
{
    if (!has_window(gpu, "dirt_gpu_window_clear"))
        return false;
    if (!rgb) {
        DIRT_ERROR("dirt_gpu_window_clear: NULL colour");
        return false;
    }
    GLint draw_fb = 0;
    GLfloat clear[4];
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    GLboolean mask[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(rgb[0], rgb[1], rgb[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(clear[0], clear[1], clear[2], clear[3]);
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    (scissor ? glEnable : glDisable)(GL_SCISSOR_TEST);
    (srgb ? glEnable : glDisable)(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fb);
    return gl_check("window clear");
}

bool dirt_gpu_window_read(dirt_gpu *gpu, uint8_t *rgba, int width, int height)
{
    if (!has_window(gpu, "dirt_gpu_window_read"))
        return false;
    int w = 0, h = 0;
    dirt_gpu_window_size(gpu, &w, &h);
    if (!rgba || width != w || height != h || w <= 0 || h <= 0) {
        DIRT_ERROR("dirt_gpu_window_read: asked for %dx%d%s, the framebuffer is %dx%d", width,
                   height, rgba ? "" : " into NULL", w, h);
        return false;
    }
    GLint read_fb = 0, read_buffer = 0, pack_buffer = 0, alignment = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glGetIntegerv(GL_READ_BUFFER, &read_buffer);
    glReadBuffer(GL_BACK);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    bool ok = gl_check("window read");
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
    glReadBuffer((GLenum)read_buffer);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fb);
    if (!ok)
        return false;
    /* GL's rows run from the bottom: flip so that row 0 is the top. */
    size_t row = (size_t)w * 4;
    uint8_t *tmp = malloc(row);
    if (!tmp) {
        DIRT_ERROR("dirt_gpu_window_read: out of memory");
        return false;
    }
    for (int y = 0; y < h / 2; y++) {
        uint8_t *a = rgba + (size_t)y * row, *b = rgba + (size_t)(h - 1 - y) * row;
        memcpy(tmp, a, row);
        memcpy(a, b, row);
        memcpy(b, tmp, row);
    }
    free(tmp);
    return true;
}

/* ---- textures of CPU images ---- */

uint32_t dirt_gpu_texture_upload(dirt_gpu *gpu, uint32_t tex, int width, int height,
                                 const float *rgba)
{
    if (!gpu || !rgba) {
        DIRT_ERROR("dirt_gpu_texture_upload: NULL %s", gpu ? "pixels" : "GPU");
        return 0;
    }
    int max = gpu->caps.max_texture_size;
    if (width <= 0 || height <= 0 || (max > 0 && (width > max || height > max))) {
        DIRT_ERROR("dirt_gpu_texture_upload: %dx%d (the GPU allows 1..%d per side)", width,
                   height, max);
        return 0;
    }
    if (tex) {
        GLint w = 0, h = 0, format = 0;
        if (is_texture_2d(tex)) {
            glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
            glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
            glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
        } else {
            DIRT_ERROR("dirt_gpu_texture_upload: %u is not a 2D texture", tex);
            return 0;
        }
        if ((w != width || h != height || format != GL_RGBA32F)) {
            GLuint old = tex;
            gl_texture_destroy(&old);
            tex = 0;
        }
    }
    bool made = false;
    if (!tex) {
        tex = gl_texture_2d(GL_RGBA32F, width, height, 1, "image (dirt_gpu_texture_upload)");
        if (!tex)
            return 0;
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        made = true;
    }
    GLint unpack_buffer = 0, alignment = 0;
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    bool ok = gl_texture_upload_rgba32f(tex, width, height, rgba);
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)unpack_buffer);
    if (!ok) {
        DIRT_ERROR("dirt_gpu_texture_upload: upload of %dx%d failed", width, height);
        if (made) {
            GLuint t = tex;
            gl_texture_destroy(&t);
        }
        return 0;
    }
    return tex;
}

void dirt_gpu_texture_destroy(dirt_gpu *gpu, uint32_t tex)
{
    (void)gpu;
    if (tex) {
        GLuint t = tex;
        gl_texture_destroy(&t);
    }
}
