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
    dirt_gpu_query_counts queries; /* timer.c: the time queries' counts */
};

/* ---- capabilities (context.c) ---- */

/* Test hook (the in-process form of DIRT_MAX_BLOCK_BYTES): storage blocks of
 * `bytes` from now on (caps.max_ssbo_size and block_override), or the
 * driver's again for 0 or anything not below it. Objects made before keep
 * what they were made with until they grow or are remade. */
void gl_gpu_set_block_bytes(dirt_gpu *gpu, int64_t bytes);

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
 * (a frame graph pass).
 *
 * GPU clock: every timer owns a ring of GL_TIMER_RING queries, so a region
 * can be ended without waiting for its result:
 *  - gl_timer_end (blocking) ends the query and reads its result at once
 *    (a wait: the CPU stops until the GPU has run the region);
 *  - gl_timer_end_async ends the query and harvests, without waiting and in
 *    order, every earlier query of the ring whose GL_QUERY_RESULT_AVAILABLE
 *    is true; t->ms is their sum (0 when none had arrived): results come one
 *    or more regions late, the region just ended is counted by a later end
 *    or by gl_timer_drain;
 *  - gl_timer_begin with all GL_TIMER_RING queries still in flight waits for
 *    the oldest (counted in dirt_gpu_query_counts.ring_waits), whose time the
 *    next end reports;
 *  - gl_timer_drain waits for the rest and gives their sum.
 * Every GL_QUERY_RESULT read that waits (AVAILABLE false at the time, or a
 * blocking end's read, which does not ask) counts in dirt_gpu_query_waits.
 * The CPU clock has no queries: both ends are the blocking one. */
#define GL_TIMER_RING 8

typedef struct gl_timer {
    dirt_gpu *gpu;
    GLuint queries[GL_TIMER_RING]; /* GPU clock only */
    int oldest;            /* ring slot of the oldest query in flight */
    int pending;           /* ended, result not read yet (the running one aside) */
    int discard;           /* the oldest `discard` of them are read but not reported */
    double held_ms;        /* read by a begin (ring full), reported at the next end */
    bool held;             /* held_ms holds a result */
    enum dirt_clock clock; /* the clock `ms` is measured with (fixed at init) */
    bool running;
    double cpu_start;
    double ms;             /* what the last end reported; -1 until one did */
} gl_timer;

/* False after logging when the queries cannot be created. */
bool gl_timer_init(gl_timer *t, dirt_gpu *gpu, const char *label);
void gl_timer_begin(gl_timer *t);
/* Ends the region and sets t->ms to its time (blocking: waits for the query
 * result or for glFinish; results of earlier asynchronous ends still in
 * flight are waited for too and added). */
void gl_timer_end(gl_timer *t);
/* Ends the region without waiting (GPU clock): t->ms = the sum of the
 * earlier regions' results that have arrived (see above). CPU clock: as
 * gl_timer_end. */
void gl_timer_end_async(gl_timer *t);
/* Waits for every result still in flight; *ms = their sum plus what a full
 * ring's begin read (0 when none). Returns how many results that is (the
 * discarded ones aside). A running region is not touched: its end reports
 * it. */
int gl_timer_drain(gl_timer *t, double *ms);
/* Results still in flight (ended, not read). */
int gl_timer_pending(const gl_timer *t);
/* Forgets the results in flight without waiting: they are read as they
 * arrive but not reported (a caller restarting what it measures; a running
 * region is not touched). */
void gl_timer_discard(gl_timer *t);
/* Frees the queries; results still in flight are dropped (counted). */
void gl_timer_release(gl_timer *t);

#endif
