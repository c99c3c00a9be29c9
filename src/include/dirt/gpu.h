/* DIRT engine: GPU device (an OpenGL 4.5 core context).
 *
 * Applications create one dirt_gpu and hand it to the techniques; they never
 * call GL themselves. Headless contexts use EGL (Mesa's surfaceless platform,
 * then the EGL device platform, so both llvmpipe and a headless NVIDIA GPU
 * work); windowed contexts use GLFW. The context is current on the creating
 * thread. */
#ifndef DIRT_GPU_H
#define DIRT_GPU_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/api.h"

#include "dirt/stats.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_gpu dirt_gpu;

/* The headless EGL platform. AUTO prefers a hardware GPU: the EGL devices
 * that are not Mesa's software device first, then Mesa's surfaceless
 * platform (llvmpipe, or the GPU Mesa drives), then any EGL device.
 * DEVICE: EGL devices only (hardware first); SURFACELESS: Mesa's only.
 * The environment variable DIRT_GPU (auto, device, surfaceless) chooses
 * when the options leave it AUTO. The platform in use is in caps.platform
 * and dirt_gpu_describe. */
enum dirt_gpu_platform {
    DIRT_GPU_PLATFORM_AUTO = 0,
    DIRT_GPU_PLATFORM_DEVICE,
    DIRT_GPU_PLATFORM_SURFACELESS,
};

/* "auto", "device", "surfaceless"; NULL-terminated (for option parsers). */
DIRT_API extern const char *const dirt_gpu_platform_names[4];

/* Options for dirt_gpu_create. Zero-initialised = headless, debug output on
 * at warning level and above. */
typedef struct dirt_gpu_opts {
    bool window;             /* GLFW window instead of headless EGL */
    int width, height;       /* window size (default 1280x720) */
    const char *title;       /* window title (default "DIRT") */
    bool vsync;              /* window: swap interval 1 */
    bool no_debug;           /* no debug context / debug output */
    bool force_device_platform; /* headless: skip Mesa surfaceless, use EGL devices
                                   (as platform = DIRT_GPU_PLATFORM_DEVICE) */
    enum dirt_gpu_platform platform; /* headless: which EGL platform (default: the
                                   environment's DIRT_GPU, else auto) */
    bool sync_debug;         /* synchronous GL debug output (messages at the call that
                                caused them; slower). Default: only at log level
                                debug (-v, DIRT_LOG=debug); the tests turn it on */
    bool disable_conservative;  /* report GL_NV_conservative_raster as absent */
    bool cpu_timing;         /* time every pass with glFinish + the CPU clock, even
                                where GL timer queries work (dirt_gpu_clock) */
    bool gpu_timing;         /* for tests: time with GL timer queries even on a
                                software renderer (llvmpipe's GL_TIME_ELAPSED works
                                but does not time rasterization, so its figures are
                                not the work's); cpu_timing wins (dirt_gpu_clock) */
    bool poison;             /* test builds: fill every buffer and texture the engine
                                allocates with DIRT_GPU_POISON_WORD when it is made,
                                and every frame-graph transient at its first use in
                                each execute, so a read of memory nobody wrote shows
                                on any driver. Also on when the environment has
                                DIRT_POISON=1 (the test suite sets it) */
    bool check_barriers;     /* test builds: the barrier checker (src/gl/check.c) follows
                                every draw, dispatch and transfer the engine issues and
                                the buffers and textures each reads and writes, and
                                reports an access that follows an incoherent shader
                                write (or a shader write that follows any access) of
                                the same object with no glMemoryBarrier of the bit
                                that access needs in between: logged with both
                                commands, counted (dirt_gpu_barrier_counts) and in
                                dirt_gpu_error_count. DIRT_CHECK_BARRIERS=1 in the
                                environment turns it on too and makes the first
                                hazard abort the process (the test suite sets it);
                                with this option the process goes on */
} dirt_gpu_opts;

/* What poisoned memory holds (dirt_gpu_opts.poison): every 32-bit word of a
 * buffer, and every texel channel of a float or integer texture (read as a
 * float: a quiet NaN; as an index: far past any array). 16-bit float
 * channels hold a NaN, normalized ones DIRT_GPU_POISON_UNORM (as do the
 * last bytes of a buffer whose size is no multiple of 4), depth textures
 * 0 (the near plane: nothing passes a GL_LESS test). */
#define DIRT_GPU_POISON_WORD 0x7FF7DEADu
#define DIRT_GPU_POISON_UNORM 0xADu

typedef struct dirt_gpu_caps {
    int gl_major, gl_minor;
    char version[160];
    char renderer[160];
    char vendor[160];
    const char *platform;        /* "egl-surfaceless", "egl-device", "glfw" */
    bool nv_conservative_raster; /* GL_NV_conservative_raster usable */
    bool software;               /* llvmpipe/softpipe: timestamps don't time raster work */
    bool timer_query;
    int timer_bits;              /* GL_QUERY_COUNTER_BITS of GL_TIME_ELAPSED (0: none) */
    int timestamp_bits;          /* GL_QUERY_COUNTER_BITS of GL_TIMESTAMP */
    /* The storage block size every size check and split uses:
     * GL_MAX_SHADER_STORAGE_BLOCK_SIZE (driver_ssbo_size), or the value of
     * the environment variable DIRT_MAX_BLOCK_BYTES when that is set and
     * smaller (a test hook: arrays then split, and the path tracer chunks,
     * as they would past the driver's own limit; see block_override). */
    int64_t max_ssbo_size;
    int64_t driver_ssbo_size;    /* GL_MAX_SHADER_STORAGE_BLOCK_SIZE as the driver says */
    int64_t block_override;      /* DIRT_MAX_BLOCK_BYTES in effect (0: none) */
    int64_t max_texel_buffer;    /* GL_MAX_TEXTURE_BUFFER_SIZE (texels) */
    int max_texture_size;
    int max_array_layers;
    int max_compute_group_invocations;
    int max_image_units;
    int max_texture_units;       /* GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS */
    int max_ssbo_bindings;
} dirt_gpu_caps;

/* Makes a GL 4.5 core context. Returns NULL after logging why (no EGL display,
 * no GL 4.5, no window system, or a renderer string without the text the
 * environment variable DIRT_EXPECT_RENDERER names, case-insensitively: the
 * test runs set it so that a driver falling back to another fails). Before
 * the driver is loaded it sets ZINK_INLINE_UNIFORMS=0 in the environment
 * unless that is set (Mesa 22.3's zink keeps stale shader variants with
 * it: src/gl/context.c). */
DIRT_API dirt_gpu *dirt_gpu_create(const dirt_gpu_opts *opts);
DIRT_API void dirt_gpu_destroy(dirt_gpu *gpu);

DIRT_API const dirt_gpu_caps *dirt_gpu_get_caps(const dirt_gpu *gpu);
/* One line: "OpenGL 4.5 (Core Profile) Mesa ... | llvmpipe ... | conservative raster: no". */
DIRT_API void dirt_gpu_describe(const dirt_gpu *gpu, char *buf, size_t size);

/* The one timing rule: the clock every pass on this GPU is measured with.
 * DIRT_CLOCK_CPU (glFinish before and after, CPU wall clock) when the GPU
 * was created with opts.cpu_timing, when it has no timer queries, or when
 * the renderer is software (caps.software: llvmpipe's GL_TIME_ELAPSED does
 * not time rasterization) unless opts.gpu_timing (tests) asks for the
 * queries; else DIRT_CLOCK_GPU (GL_TIME_ELAPSED queries, no glFinish).
 * Fixed for the GPU's lifetime. Every timer (the gl layer's gl_timer, the
 * frame graph's GL backend) asks this function; nothing else decides, and
 * every reported time carries this clock. With the GPU clock the frame
 * graph's asynchronous timers (the path tracer's) read their results one or
 * more samples late, from a ring of queries, and never wait for them
 * (doc/frame-graph.md, Timing). */
DIRT_API enum dirt_clock dirt_gpu_clock(const dirt_gpu *gpu);

/* The GPU clock's time queries since creation (tests and diagnostics).
 * issued = harvested + dropped + those still in flight. */
typedef struct dirt_gpu_query_counts {
    uint64_t issued;      /* GL_TIME_ELAPSED queries ended */
    uint64_t harvested;   /* their results read (discarded ones included) */
    uint64_t dropped;     /* freed in flight, never read (a timer released) */
    uint64_t waits;       /* result reads that waited for the GPU: AVAILABLE was
                             false at the time, or not asked (a blocking end) */
    uint64_t ring_waits;  /* begins that found their timer's ring full and read
                             its oldest result first */
} dirt_gpu_query_counts;

DIRT_API dirt_gpu_query_counts dirt_gpu_queries(const dirt_gpu *gpu);
/* dirt_gpu_queries(gpu).waits: 0 over a stretch of work means no query
 * result stalled the CPU there. */
DIRT_API uint64_t dirt_gpu_query_waits(const dirt_gpu *gpu);

/* What the barrier checker reports (dirt_gpu_opts.check_barriers), one id
 * per kind of hazard with its message. */
#define DIRT_GPU_HAZARDS(X)                                                         \
    X(READ_AFTER_WRITE, "read after an incoherent shader write without its barrier") \
    X(WRITE_AFTER_WRITE, "write after an incoherent shader write without its barrier") \
    X(WRITE_AFTER_READ, "shader write after an access without its barrier")

enum dirt_gpu_hazard {
#define DIRT_GPU_HAZARD_ENUM_(id, msg) DIRT_GPU_HAZARD_##id,
    DIRT_GPU_HAZARDS(DIRT_GPU_HAZARD_ENUM_)
#undef DIRT_GPU_HAZARD_ENUM_
    DIRT_GPU_HAZARD_COUNT
};

DIRT_API extern const char *const dirt_gpu_hazard_messages[DIRT_GPU_HAZARD_COUNT];

typedef struct dirt_gpu_barrier_check {
    bool on;                 /* the checker runs on this GPU */
    uint64_t commands;       /* draws, dispatches and transfers checked */
    uint64_t barriers;       /* glMemoryBarrier calls seen */
    uint64_t hazards[DIRT_GPU_HAZARD_COUNT]; /* found, by kind */
    uint64_t total;          /* their sum */
} dirt_gpu_barrier_check;

/* The barrier checker's counts since the GPU was made (all zero when off). */
DIRT_API dirt_gpu_barrier_check dirt_gpu_barrier_counts(const dirt_gpu *gpu);

/* Whether the GPU poisons new memory (dirt_gpu_opts.poison or DIRT_POISON=1). */
DIRT_API bool dirt_gpu_poisons(const dirt_gpu *gpu);

/* Waits for all GPU work (glFinish). */
DIRT_API void dirt_gpu_finish(dirt_gpu *gpu);

/* Number of GL debug messages of severity medium/high or type error logged
 * since creation (tests use it to prove a run was clean). */
DIRT_API uint64_t dirt_gpu_error_count(const dirt_gpu *gpu);

#ifdef __cplusplus
}
#endif
#endif
