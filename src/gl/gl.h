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
    struct gl_window_state *input; /* windowed only: gl/window.h's input */
    GLuint present_program;        /* present.c, made by the first dirt_gpu_present */
    GLuint present_vao;            /* the empty vertex array its draw binds */
    void *ui;                      /* the dirt_ui attached (ui.cpp), NULL when none */
    uint64_t error_count;
    bool in_finish_timer;
    dirt_gpu_query_counts queries; /* timer.c: the time queries' counts */
    bool poison;                   /* poison.c: fill new memory (dirt_gpu_poisons) */
    struct gl_checker *check;      /* check.c: the barrier checker, NULL when off */
};

/* ---- capabilities (context.c) ---- */

/* Test hook (the in-process form of DIRT_MAX_BLOCK_BYTES): storage blocks of
 * `bytes` from now on (caps.max_ssbo_size and block_override), or the
 * driver's again for 0 or anything not below it. Objects made before keep
 * what they were made with until they grow or are remade. */
void gl_gpu_set_block_bytes(dirt_gpu *gpu, int64_t bytes);

/* The GPU whose context is current on this thread: the one made last by
 * dirt_gpu_create here (NULL after it was destroyed). The helpers that take
 * no dirt_gpu (textures, the poisoning) act for it. */
dirt_gpu *gl_current(void);

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

/* ---- poisoned memory (poison.c) ---- */

/* When the current GPU poisons (dirt_gpu_opts.poison), fill buffer `buf`
 * (`size` bytes) with DIRT_GPU_POISON_WORD, or every level of texture `tex`
 * with the poison of its format (see DIRT_GPU_POISON_WORD). `after_shaders`:
 * earlier shader writes may still be in flight (a reused frame-graph
 * allocation): the GL_BUFFER_UPDATE / GL_TEXTURE_UPDATE barrier the clear
 * needs comes first. Nothing when the GPU does not poison. */
void gl_poison_buffer(GLuint buf, size_t size, bool after_shaders);
void gl_poison_texture(GLuint tex, bool after_shaders);

/* ---- the barrier checker (check.c) ---- */

/* Starts the checker on `gpu` (its context current) when the options or
 * DIRT_CHECK_BARRIERS ask; DIRT_DROP_BARRIER=FILE:LINE makes that
 * glMemoryBarrier call issue nothing (gl_check_drop_barrier). False after
 * logging when it could not start. */
bool gl_check_init(dirt_gpu *gpu);
void gl_check_release(dirt_gpu *gpu);
/* Records what program `prog` (linked) reads and writes: its storage
 * blocks, uniform blocks, atomic counter buffers, images and samplers from
 * GL's introspection, whether each block and image is read, written or
 * both from the `n` stage sources (gl/glsl_iface.h). Nothing when the
 * checker is off. */
void gl_check_program(GLuint prog, const char *label, char *const *sources, int n);
/* The debug group stack (gl_group_push/pop), for the checker's messages. */
void gl_check_group(const char *push_name);
/* Test hooks. A glMemoryBarrier call site ("src/dirt/trace.c:62", the
 * file from src/ or test/ on) whose call issues nothing from now on (NULL:
 * none); how often it was skipped. */
void gl_check_drop_barrier(dirt_gpu *gpu, const char *site);
uint64_t gl_check_dropped(const dirt_gpu *gpu);
/* The glMemoryBarrier call sites seen since the GPU was made (file:line as
 * above, calls). Returns how many; fills at most `max`. */
typedef struct gl_barrier_site {
    char site[128];
    uint64_t calls;
} gl_barrier_site;
int gl_check_barrier_sites(const dirt_gpu *gpu, gl_barrier_site *out, int max);

/* The checked forms of the GL calls that access memory (check.c); every
 * file that includes this header calls them through the macros below, so
 * the checker sees the engine's GL work (ImGui's own calls and poison.c's,
 * which define DIRT_GL_RAW, it does not). Each calls GL and, when the
 * current GPU checks, checks and records the call. */
void gl_chk_MemoryBarrier(GLbitfield bits, const char *file, int line);
void gl_chk_DispatchCompute(GLuint x, GLuint y, GLuint z, const char *file, int line);
void gl_chk_DispatchComputeIndirect(GLintptr offset, const char *file, int line);
void gl_chk_DrawArrays(GLenum mode, GLint first, GLsizei count, const char *file, int line);
void gl_chk_ClearNamedBufferData(GLuint buf, GLenum ifmt, GLenum fmt, GLenum type,
                                 const void *data, const char *file, int line);
void gl_chk_ClearNamedBufferSubData(GLuint buf, GLenum ifmt, GLintptr off, GLsizeiptr size,
                                    GLenum fmt, GLenum type, const void *data, const char *file,
                                    int line);
void gl_chk_NamedBufferSubData(GLuint buf, GLintptr off, GLsizeiptr size, const void *data,
                               const char *file, int line);
void gl_chk_GetNamedBufferSubData(GLuint buf, GLintptr off, GLsizeiptr size, void *data,
                                  const char *file, int line);
void gl_chk_ClearTexImage(GLuint tex, GLint level, GLenum fmt, GLenum type, const void *data,
                          const char *file, int line);
void gl_chk_TextureSubImage2D(GLuint tex, GLint level, GLint x, GLint y, GLsizei w, GLsizei h,
                              GLenum fmt, GLenum type, const void *data, const char *file,
                              int line);
void gl_chk_GetTextureImage(GLuint tex, GLint level, GLenum fmt, GLenum type, GLsizei size,
                            void *data, const char *file, int line);
void gl_chk_GenerateTextureMipmap(GLuint tex, const char *file, int line);
void gl_chk_Clear(GLbitfield mask, const char *file, int line);
void gl_chk_ClearBufferfv(GLenum buffer, GLint drawbuffer, const GLfloat *value,
                          const char *file, int line);
void gl_chk_ClearNamedFramebufferfv(GLuint fb, GLenum buffer, GLint drawbuffer,
                                    const GLfloat *value, const char *file, int line);
void gl_chk_ClearNamedFramebufferuiv(GLuint fb, GLenum buffer, GLint drawbuffer,
                                     const GLuint *value, const char *file, int line);
void gl_chk_ReadPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum fmt, GLenum type,
                       void *data, const char *file, int line);
void gl_chk_CreateBuffers(GLsizei n, GLuint *names);
void gl_chk_DeleteBuffers(GLsizei n, const GLuint *names);
void gl_chk_CreateTextures(GLenum target, GLsizei n, GLuint *names);
void gl_chk_DeleteTextures(GLsizei n, const GLuint *names);
void gl_chk_DeleteProgram(GLuint prog);

#ifndef DIRT_GL_RAW
#define glMemoryBarrier(b) gl_chk_MemoryBarrier((b), __FILE__, __LINE__)
#define glDispatchCompute(x, y, z) gl_chk_DispatchCompute((x), (y), (z), __FILE__, __LINE__)
#define glDispatchComputeIndirect(o) gl_chk_DispatchComputeIndirect((o), __FILE__, __LINE__)
#define glDrawArrays(m, f, c) gl_chk_DrawArrays((m), (f), (c), __FILE__, __LINE__)
#define glClearNamedBufferData(b, i, f, t, d) \
    gl_chk_ClearNamedBufferData((b), (i), (f), (t), (d), __FILE__, __LINE__)
#define glClearNamedBufferSubData(b, i, o, s, f, t, d) \
    gl_chk_ClearNamedBufferSubData((b), (i), (o), (s), (f), (t), (d), __FILE__, __LINE__)
#define glNamedBufferSubData(b, o, s, d) \
    gl_chk_NamedBufferSubData((b), (o), (s), (d), __FILE__, __LINE__)
#define glGetNamedBufferSubData(b, o, s, d) \
    gl_chk_GetNamedBufferSubData((b), (o), (s), (d), __FILE__, __LINE__)
#define glClearTexImage(t, l, f, ty, d) \
    gl_chk_ClearTexImage((t), (l), (f), (ty), (d), __FILE__, __LINE__)
#define glTextureSubImage2D(t, l, x, y, w, h, f, ty, d) \
    gl_chk_TextureSubImage2D((t), (l), (x), (y), (w), (h), (f), (ty), (d), __FILE__, __LINE__)
#define glGetTextureImage(t, l, f, ty, s, d) \
    gl_chk_GetTextureImage((t), (l), (f), (ty), (s), (d), __FILE__, __LINE__)
#define glGenerateTextureMipmap(t) gl_chk_GenerateTextureMipmap((t), __FILE__, __LINE__)
#define glClear(m) gl_chk_Clear((m), __FILE__, __LINE__)
#define glClearBufferfv(b, d, v) gl_chk_ClearBufferfv((b), (d), (v), __FILE__, __LINE__)
#define glClearNamedFramebufferfv(fb, b, d, v) \
    gl_chk_ClearNamedFramebufferfv((fb), (b), (d), (v), __FILE__, __LINE__)
#define glClearNamedFramebufferuiv(fb, b, d, v) \
    gl_chk_ClearNamedFramebufferuiv((fb), (b), (d), (v), __FILE__, __LINE__)
#define glReadPixels(x, y, w, h, f, t, d) \
    gl_chk_ReadPixels((x), (y), (w), (h), (f), (t), (d), __FILE__, __LINE__)
#define glCreateBuffers(n, b) gl_chk_CreateBuffers((n), (b))
#define glDeleteBuffers(n, b) gl_chk_DeleteBuffers((n), (b))
#define glCreateTextures(t, n, b) gl_chk_CreateTextures((t), (n), (b))
#define glDeleteTextures(n, b) gl_chk_DeleteTextures((n), (b))
#define glDeleteProgram(p) gl_chk_DeleteProgram((p))
#endif

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
