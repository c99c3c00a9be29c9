/* Internal GL layer: the only headers that pull in OpenGL. Everything that
 * calls GL includes this file and lives in src/gl/ or in a technique file
 * that owns a pass body and uses these helpers. */
#ifndef DIRT_GL_GL_H
#define DIRT_GL_GL_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/gpu.h"
#include "dirt/log.h"

#ifndef GL_CONSERVATIVE_RASTERIZATION_NV
#define GL_CONSERVATIVE_RASTERIZATION_NV 0x9346
#endif

struct gl_window_state; /* window.c: the input callbacks' state */

struct dirt_gpu {
    dirt_gpu_caps caps;
    dirt_gpu_opts opts;
    /* EGL (headless) */
    void *egl_display;
    void *egl_context;
    /* GLFW (window) */
    void *window;
    struct gl_window_state *input; /* windowed only: dirt/window.h's input */
    GLuint present_program;        /* present.c, made by the first dirt_gpu_present */
    GLuint present_vao;            /* the empty vertex array its draw binds */
    void *ui;                      /* the dirt_ui attached (ui.cpp), NULL when none */
    uint64_t error_count;
    bool in_finish_timer;
};

/* ---- the window's input (window.c) ---- */

/* Makes the input state of a new window and installs its GLFW callbacks
 * (key, mouse button, cursor, scroll, drop, framebuffer size, close); the
 * UI's callbacks, installed later, chain to these. False after logging. */
bool gl_window_init(dirt_gpu *gpu);
/* dirt_gpu_window_poll around glfwPollEvents: _begin drops the last poll's
 * events (pressed, released, scroll, drops, double clicks), _end derives
 * what the callbacks do not report (cursor motion, Shift/Ctrl/Alt). */
void gl_window_poll_begin(dirt_gpu *gpu);
void gl_window_poll_end(dirt_gpu *gpu);
/* Frees the input state (before the window is destroyed). */
void gl_window_release(dirt_gpu *gpu);

/* ---- presentation (present.c) and panels (ui.cpp) ---- */

/* Frees the presentation program and vertex array (context current). */
void gl_present_release(dirt_gpu *gpu);
/* Destroys a UI still attached when its GPU is destroyed (ui.cpp, which
 * includes this header inside extern "C"). */
void gl_ui_release(dirt_gpu *gpu);
/* Makes the attached UI's ImGui context current: its GLFW callbacks, which
 * run inside glfwPollEvents, act on the current context. */
void gl_ui_make_current(dirt_gpu *gpu);

/* ---- debug output, labels, groups (debug.c) ---- */

/* Installs the debug callback that routes GL messages into the engine log. */
void gl_debug_install(dirt_gpu *gpu);
/* glObjectLabel with a printf-style name. `type` is GL_BUFFER, GL_TEXTURE,
 * GL_PROGRAM, GL_FRAMEBUFFER, GL_QUERY, ... */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void gl_label(GLenum type, GLuint id, const char *fmt, ...);
void gl_group_push(const char *name);
void gl_group_pop(void);
/* Drains glGetError; logs each error with the caller's location and returns
 * false when there was one. */
bool gl_check_(const char *file, int line, const char *what);
#define gl_check(what) gl_check_(__FILE__, __LINE__, (what))

/* ---- buffers and textures (resource.c) ---- */

/* Immutable-storage buffer (glNamedBufferStorage) with GL_DYNAMIC_STORAGE_BIT
 * and, when `readback`, GL_MAP_READ_BIT. `data` may be NULL. Returns 0 after
 * logging when the size exceeds what the GPU allows or allocation fails. */
GLuint gl_buffer_create(dirt_gpu *gpu, size_t size, const void *data,
                        bool readback, const char *label);
void gl_buffer_destroy(GLuint *buf);
/* Makes *buf (capacity *cap bytes) hold at least `size` bytes: keeps it when
 * large enough, else replaces it (content lost) with a new one of exactly
 * `size` bytes. False after logging; then *buf = 0 and *cap = 0. */
bool gl_buffer_ensure(dirt_gpu *gpu, GLuint *buf, size_t *cap, size_t size, bool readback,
                      const char *label);
/* Copies `size` bytes from offset 0 of `buf` into `out` (glGetNamedBufferSubData). */
bool gl_buffer_read(GLuint buf, size_t offset, size_t size, void *out);
/* Replaces `size` bytes at `offset` of `buf` (a GL_DYNAMIC_STORAGE_BIT
 * buffer) with `data` (glNamedBufferSubData; ordered by GL itself). */
bool gl_buffer_write(GLuint buf, size_t offset, size_t size, const void *data);

/* 2D texture with immutable storage. levels >= 1. */
GLuint gl_texture_2d(GLenum internal_format, int width, int height, int levels,
                     const char *label);
GLuint gl_texture_2d_array(GLenum internal_format, int width, int height,
                           int layers, int levels, const char *label);
void gl_texture_destroy(GLuint *tex);
/* Replaces level 0 of an RGBA32F 2D texture with width x height RGBA floats
 * (row 0 first). False after logging a GL error. */
bool gl_texture_upload_rgba32f(GLuint tex, int width, int height, const float *rgba);
/* Reads level 0 of an RGBA32F 2D texture (blocking; row 0 first). */
bool gl_texture_read_rgba32f(GLuint tex, int width, int height, float *rgba);

/* ---- timers (timer.c) ---- */

/* Times a region of GL work with the GPU's one clock (dirt_gpu_clock):
 * DIRT_CLOCK_GPU: a GL_TIME_ELAPSED query around the region (no glFinish);
 * DIRT_CLOCK_CPU: glFinish before and after, CPU wall clock in between.
 * Time queries do not nest: do not time a region inside another timed one
 * (a frame graph pass). Results are read after gl_timer_end. */
typedef struct gl_timer {
    GLuint query;          /* GPU clock only */
    enum dirt_clock clock; /* the clock `ms` is measured with (fixed at init) */
    bool running;
    double cpu_start;
    double ms;             /* the last region; -1 until one was measured */
} gl_timer;

/* False after logging when the query cannot be created. */
bool gl_timer_init(gl_timer *t, dirt_gpu *gpu, const char *label);
void gl_timer_begin(gl_timer *t);
/* Ends the region and sets t->ms (blocking: waits for the query result or
 * for glFinish). */
void gl_timer_end(gl_timer *t);
void gl_timer_release(gl_timer *t);

#endif
