/* DIRT engine: frame graph (internal API for the techniques).
 *
 * Passes declare which resources they read and write and how (the access
 * kind: image store, SSBO read, vertex fetch, ...). fg_compile() turns the
 * declarations into an executable schedule: it validates them, culls passes
 * whose results reach no output, orders the rest topologically (declaration
 * order where the dependencies leave a choice), computes resource lifetimes,
 * lets transient resources with disjoint lifetimes share one allocation, and
 * derives the glMemoryBarrier bits every pass needs. fg_execute() allocates,
 * binds, issues the barriers, runs the pass callbacks inside debug groups and
 * times them (with the backend's one clock, see fg_backend_ops.end_pass and
 * doc/frame-graph.md, Timing); its validation mode re-checks every hazard against the
 * barriers that were really issued.
 *
 * Layering: everything in src/graph/ is plain C without GL. GL work goes
 * through a small backend interface (fg_backend) handed in by the code that
 * creates the graph; the OpenGL backend and the GL helpers for pass bodies
 * (fg_gl_*) live in src/gl/graph_gl.h, a layer above this one. Unit tests
 * compile graphs with no backend, or execute them with a fake one.
 *
 * Resource semantics ("call order"): every fg_use() of a resource sees the
 * content left by the latest write *declared* before that call (in program
 * order of the fg_use calls, not in pass creation order). A write creates a
 * new version of the resource; readers of a version run after its writer and
 * before the next writer. So declaring passes one after another gives that
 * order, and adding a use to an earlier-created pass can move it later.
 * All accesses of one pass to one resource form one use: reads in it see the
 * version before the pass's own write.
 *
 * Threading: a graph is used from the thread that owns the GL context.
 * See doc/frame-graph.md for the design, the barrier table and examples. */
#ifndef DIRT_GRAPH_GRAPH_H
#define DIRT_GRAPH_GRAPH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "dirt/stats.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fg_graph fg_graph;
typedef struct fg_pass fg_pass;
typedef struct fg_ctx fg_ctx;

/* Resource handle. id 0 is "no resource" (what a failed declaration returns). */
typedef struct fg_res {
    uint32_t id;
} fg_res;

/* ---- accesses ------------------------------------------------------------ */

/* How a pass touches a resource. Reads see earlier writes; writes create a
 * new version. "Read-write" accesses do both (they need an earlier writer
 * when the resource is transient). */
typedef enum fg_access {
    FG_ACCESS_NONE = 0,
    FG_SAMPLED,        /* read: texture()/texelFetch() through a sampler (texture) */
    FG_IMAGE_LOAD,     /* read: imageLoad (texture) */
    FG_IMAGE_STORE,    /* write: imageStore (texture) */
    FG_IMAGE_ATOMIC,   /* read-write: imageAtomic* (texture) */
    FG_SSBO_READ,      /* read: shader storage block (buffer) */
    FG_SSBO_WRITE,     /* write: shader storage block stores/atomics; declare
                          FG_SSBO_READ as well when the shader reads old content */
    FG_ATOMIC_COUNTER, /* read-write: atomic_uint counters (buffer) */
    FG_UNIFORM,        /* read: uniform block (buffer) */
    FG_VERTEX,         /* read: vertex attribute fetch (buffer) */
    FG_INDEX,          /* read: element array (buffer) */
    FG_INDIRECT,       /* read: Draw*Indirect / DispatchComputeIndirect args (buffer) */
    FG_COLOR,          /* write: framebuffer colour attachment (texture, raster pass) */
    FG_DEPTH,          /* write: framebuffer depth attachment, depth test + write
                          (depth texture, raster pass) */
    FG_TRANSFER_READ,  /* read: glGet*SubData, glGetTextureImage, copy source, map */
    FG_TRANSFER_WRITE, /* write: glClear*Data/Image, glBufferSubData, glTexSubImage,
                          copy destination */
    FG_ACCESS_COUNT
} fg_access;

/* Short lowercase name ("image store"), "?" when out of range. */
const char *fg_access_name(fg_access a);
bool fg_access_reads(fg_access a);
bool fg_access_writes(fg_access a);
/* Incoherent shader writes: image store/atomic, SSBO write, atomic counter.
 * Only these make glMemoryBarrier necessary (see fg_barrier_bits). */
bool fg_access_shader_write(fg_access a);

/* ---- barrier bits -------------------------------------------------------- */

/* glMemoryBarrier bits. The values are the GL ones (src/gl/graph_gl.c
 * static-asserts that), so they can be passed to GL unchanged. */
enum {
    FG_BARRIER_VERTEX_ATTRIB_ARRAY = 0x0001,
    FG_BARRIER_ELEMENT_ARRAY       = 0x0002,
    FG_BARRIER_UNIFORM             = 0x0004,
    FG_BARRIER_TEXTURE_FETCH       = 0x0008,
    FG_BARRIER_SHADER_IMAGE_ACCESS = 0x0020,
    FG_BARRIER_COMMAND             = 0x0040,
    FG_BARRIER_PIXEL_BUFFER        = 0x0080,
    FG_BARRIER_TEXTURE_UPDATE      = 0x0100,
    FG_BARRIER_BUFFER_UPDATE       = 0x0200,
    FG_BARRIER_FRAMEBUFFER         = 0x0400,
    FG_BARRIER_TRANSFORM_FEEDBACK  = 0x0800,
    FG_BARRIER_ATOMIC_COUNTER      = 0x1000,
    FG_BARRIER_SHADER_STORAGE      = 0x2000,
    /* every bit above: issued once at the first execute after a compile */
    FG_BARRIER_ALL                 = 0x3fef,
};

/* The bit that makes earlier shader writes visible to `later` (and orders
 * `later` after earlier accesses when it is itself a shader write).
 * `texture` selects TEXTURE_UPDATE vs BUFFER_UPDATE for transfers. */
uint32_t fg_barrier_bit(fg_access later, bool texture);
/* Bits needed between an `earlier` and a `later` access of the same memory:
 * fg_barrier_bit(later) when either access is an incoherent shader write,
 * else 0 (GL orders everything else itself). The table is in
 * doc/frame-graph.md. */
uint32_t fg_barrier_bits(fg_access earlier, fg_access later, bool texture);
/* "GL_SHADER_STORAGE_BARRIER_BIT" for one bit; NULL for unknown bits. */
const char *fg_barrier_name(uint32_t bit);
/* "TEXTURE_FETCH|SHADER_STORAGE" (short names, low bit first), "-" for 0;
 * names that do not fit are left out (256 bytes always suffice). Returns
 * `buf`. */
char *fg_barrier_string(uint32_t bits, char *buf, size_t size);

/* ---- resources ----------------------------------------------------------- */

typedef enum fg_format {
    FG_FORMAT_NONE = 0,
    FG_R8, FG_RGBA8,
    FG_R16F, FG_RG16F, FG_RGBA16F,
    FG_R32F, FG_RG32F, FG_RGBA32F,
    FG_R32UI, FG_RG32UI, FG_RGBA32UI,
    FG_R32I,
    FG_DEPTH32F,
    FG_FORMAT_COUNT
} fg_format;

/* GLSL layout name ("r32ui", "depth32f"), bytes per texel, depth or not. */
const char *fg_format_name(fg_format f);
size_t fg_format_bytes(fg_format f);
bool fg_format_is_depth(fg_format f);

/* Full mip chain down to 1x1 (fg_tex_desc.levels). */
#define FG_MIPS_FULL (-1)

/* Texture descriptor. Zero-initialised fields take the defaults noted. */
typedef struct fg_tex_desc {
    fg_format format;   /* required */
    int width, height;  /* > 0: absolute size; 0: relative to the output resolution */
    int div;            /* relative size = ceil(output / div); 0 means 1 */
    bool array;         /* 2D array texture (also with one layer) */
    int layers;         /* array layers; 0 means 1 */
    int levels;         /* mip levels; 0 means 1; FG_MIPS_FULL = full chain */
} fg_tex_desc;

/* Buffer descriptor: size = bytes + per_pixel * pixels, where pixels =
 * ceil(out_w / div) * ceil(out_h / div) * (layers or 1). */
typedef struct fg_buf_desc {
    size_t bytes;       /* fixed part */
    size_t per_pixel;   /* bytes per pixel of the (divided) output resolution */
    int div;            /* 0 means 1 */
    int layers;         /* multiplies the pixel count (views, buckets); 0 means 1 */
    bool readback;      /* CPU reads it back (GL_MAP_READ_BIT) */
} fg_buf_desc;

/* Transient resources: owned by the graph, allocated at execute, content
 * undefined at the start of every execute (a pass must write before anyone
 * reads), memory possibly shared with other transients. The name is copied.
 * Return {0} after logging on bad arguments; fg_compile then fails too. */
fg_res fg_texture(fg_graph *g, const char *name, const fg_tex_desc *desc);
fg_res fg_buffer(fg_graph *g, const char *name, const fg_buf_desc *desc);

/* Imported (persistent) resources: an existing GL object the caller owns and
 * keeps alive. Never aliased; content persists across executes; writes to
 * them count as outputs (their passes are never culled). Code outside the
 * graph that writes them with a shader must issue its own barrier. */
fg_res fg_import_buffer(fg_graph *g, const char *name, uint32_t gl_name, size_t size);
fg_res fg_import_texture(fg_graph *g, const char *name, uint32_t gl_name,
                         const fg_tex_desc *desc);
/* Points an imported resource at another GL object (same kind; e.g. after the
 * caller grew it). Takes effect at the next execute, no recompile needed.
 * `size` is for buffers' stats (ignored for textures). */
bool fg_set_import(fg_graph *g, fg_res r, uint32_t gl_name, size_t size);

/* Changes a transient buffer's descriptor (pool growth). Needs fg_compile. */
bool fg_set_buffer(fg_graph *g, fg_res r, const fg_buf_desc *desc);

/* Marks a resource as a graph output: the passes producing its final content
 * are kept (and, transitively, what they need). */
void fg_output(fg_graph *g, fg_res r);

/* Output resolution that relative sizes refer to. Needs fg_compile. */
void fg_set_resolution(fg_graph *g, int width, int height);
/* Aliasing of transients is on by default. Needs fg_compile. */
void fg_set_aliasing(fg_graph *g, bool enabled);
/* Shared imports (default off): the imports are also read and written by
 * shaders outside this graph between its executes (another graph, a
 * technique's own passes). The barrier derivation then takes every import
 * as written and accessed before each execute, so the first access of each
 * import in the execute gets its barrier bit, instead of a hand-written
 * glMemoryBarrier before the execute. Needs fg_compile. */
void fg_set_shared_imports(fg_graph *g, bool shared);

/* ---- passes -------------------------------------------------------------- */

typedef enum fg_pass_kind {
    FG_COMPUTE = 0,
    FG_RASTER,
} fg_pass_kind;

/* Runs the pass's GL work. The graph has issued the barriers, opened a debug
 * group, bound the requested bindings and, for raster passes, bound a
 * framebuffer of its attachments (or an attachment-less one of the pass's
 * raster size), set the viewport and bound an empty vertex array. Return
 * false (after logging) to abort the execute. */
typedef bool (*fg_execute_fn)(fg_ctx *ctx, void *user);

/* Adds a pass; the name is copied. NULL after logging (bad arguments). */
fg_pass *fg_add_pass(fg_graph *g, const char *name, fg_pass_kind kind, fg_execute_fn fn,
                     void *user);

/* Optional binding performed by the graph before the pass runs. */
typedef struct fg_use_opts {
    bool bind;          /* bind at `binding` (else the pass body binds itself) */
    unsigned binding;   /* image unit, texture unit, SSBO / UBO / atomic-counter
                           binding; colour attachments: draw buffer index (also
                           when bind is false) */
    int level;          /* mip level of image bindings and attachments */
} fg_use_opts;

/* Declares an access. `opts` may be NULL. fg_read/fg_write also check the
 * direction (fg_write takes writes and read-write accesses). Problems are
 * logged and make fg_compile fail. */
void fg_use(fg_pass *p, fg_res r, fg_access a, const fg_use_opts *opts);
void fg_read(fg_pass *p, fg_res r, fg_access a);
void fg_write(fg_pass *p, fg_res r, fg_access a);

/* Never culled (the pass has effects outside the graph, e.g. a readback). */
void fg_keep(fg_pass *p);

/* Size of the attachment-less framebuffer of a raster pass that has no
 * FG_COLOR/FG_DEPTH use (default: the output resolution, 1 layer). Uses the
 * size fields of fg_tex_desc (width/height/div/layers). */
void fg_set_raster_size(fg_pass *p, const fg_tex_desc *size);

/* ---- compile ------------------------------------------------------------- */

/* Validates and schedules (pure CPU). False after logging every problem
 * found; fg_last_error() then holds the first message. Errors: unknown
 * resource, access not valid for the resource (kind, depth format, raster-only
 * access in a compute pass), two different writes of one resource in one
 * pass, reading a transient no earlier pass wrote, dependency cycles, bad or
 * unresolvable sizes, raster attachments of different sizes. */
bool fg_compile(fg_graph *g);
const char *fg_last_error(const fg_graph *g);

/* Compiled schedule queries (valid after a successful fg_compile). */
int fg_num_passes(const fg_graph *g);          /* declared */
int fg_num_ordered(const fg_graph *g);         /* not culled */
/* Declaration index of the pass at execution position `pos`, -1 if none. */
int fg_order(const fg_graph *g, int pos);
/* Execution position of pass `name`, -1 when culled or unknown. */
int fg_position(const fg_graph *g, const char *name);
bool fg_culled(const fg_graph *g, const char *name);
/* glMemoryBarrier bits issued right before pass `name` (steady state, i.e.
 * including hazards carried over from the previous execute). */
uint32_t fg_pass_barrier(const fg_graph *g, const char *name);
/* First/last execution position using `r` (-1 when unused or culled). */
bool fg_lifetime(const fg_graph *g, fg_res r, int *first, int *last);
/* Physical allocation of a transient (-1 for imported or unused). Resources
 * with the same index share memory. */
int fg_physical(const fg_graph *g, fg_res r);
int fg_num_physical(const fg_graph *g);
/* Bytes of a resource at the compiled resolution (mip chains and layers
 * included). */
size_t fg_bytes(const fg_graph *g, fg_res r);

/* ---- execute ------------------------------------------------------------- */

typedef struct fg_exec_opts {
    bool no_timers;       /* do not time the passes (their ms stay -1): no time
                             queries, no glFinish around them */
    bool async_timers;    /* never wait for a pass's time: with the GPU clock a
                             pass's timer ends without reading its result, and
                             the pass's ms (and the stats') is the sum of its
                             earlier executes' times that have arrived by this
                             one (0 when none): times come one or more executes
                             late and fg_drain_timers gives the rest. Totals
                             summed over executes and the drain are complete.
                             The CPU clock is unchanged (glFinish around each
                             pass: ms is the pass's own) */
    bool validate;        /* check every hazard against the barriers really
                             issued; violations are errors */
    /* Test hook: do not issue the derived barrier of the pass with this name
     * (validation must then report it). */
    const char *debug_drop_barrier;
} fg_exec_opts;

/* Runs the compiled graph once. `opts` may be NULL. False after logging when
 * the graph is not compiled, has no backend, an allocation or a pass fails,
 * or (validate) a barrier is missing. */
bool fg_execute(fg_graph *g, const fg_exec_opts *opts);

/* The times of asynchronously timed passes (fg_exec_opts.async_timers) still
 * in flight: waits for them and writes each pass's late ms to late_ms[i] by
 * declaration index (i < count, normally fg_num_passes; 0 where nothing was
 * late). *clock (may be NULL) gets their clock, DIRT_CLOCK_NONE when none was
 * late. Each time is given once: by an execute's stats or by one drain. Call
 * it where the CPU waits for the GPU anyway (a readback). False when the
 * graph cannot execute (no backend). */
bool fg_drain_timers(fg_graph *g, double *late_ms, int count, enum dirt_clock *clock);
/* Forgets the times in flight without waiting (the caller restarts what it
 * measures): no later execute or drain reports them. */
void fg_discard_timers(fg_graph *g);

/* Inside a pass callback. fg_name() returns the GL name of a resource the
 * pass declared (0 and an error, counted as a validation error, when it did
 * not declare it). */
uint32_t fg_name(const fg_ctx *ctx, fg_res r);
bool fg_declares(const fg_ctx *ctx, fg_res r, fg_access a);
const char *fg_pass_name(const fg_ctx *ctx);
void fg_resolution(const fg_ctx *ctx, int *width, int *height);
size_t fg_buffer_size(const fg_ctx *ctx, fg_res r);
/* Level-0 size; any pointer may be NULL. False when r is not a texture. */
bool fg_texture_size(const fg_ctx *ctx, fg_res r, int *width, int *height, int *layers,
                     int *levels);
fg_format fg_texture_format(const fg_ctx *ctx, fg_res r);
/* Bytes of `r` actually filled this execute (e.g. node count * node size
 * read back from a counter); shows up in the stats. */
void fg_report_used(fg_ctx *ctx, fg_res r, size_t bytes);

/* ---- stats and export ---------------------------------------------------- */

typedef struct fg_pass_stats {
    const char *name;
    fg_pass_kind kind;
    bool culled;
    int position;         /* execution position, -1 when culled */
    uint32_t barrier;     /* bits issued before it */
    double ms;            /* last execute; -1 when not measured (culled, no_timers);
                             async_timers: the pass's times that arrived during it */
    enum dirt_clock clock; /* what measured ms (the backend's one clock);
                              DIRT_CLOCK_NONE when not measured */
} fg_pass_stats;

typedef struct fg_res_stats {
    const char *name;
    bool texture, imported, output, culled;
    int physical;         /* shared allocation index, -1 imported/culled */
    int first, last;      /* lifetime in execution positions */
    size_t bytes;         /* allocated for this resource */
    size_t used_bytes;    /* last fg_report_used value (0 when none) */
    bool used_reported;
} fg_res_stats;

typedef struct fg_stats {
    int num_passes;                 /* declaration order */
    const fg_pass_stats *passes;
    int num_resources;              /* declaration order */
    const fg_res_stats *resources;
    int num_physical;
    size_t transient_bytes;         /* sum of the live transients (no aliasing) */
    size_t allocated_bytes;         /* sum of the physical allocations (aliasing) */
    size_t live_peak_bytes;         /* max over passes of the transients alive then */
    size_t imported_bytes;
    size_t peak_bytes;              /* allocated_bytes + imported_bytes */
    size_t peak_bytes_no_alias;     /* transient_bytes + imported_bytes */
    size_t used_bytes;              /* sum of the reported used bytes */
    double ms;                      /* sum over the passes measured in the last
                                       execute; -1 when none was measured */
    enum dirt_clock clock;          /* their clock; DIRT_CLOCK_NONE when none was
                                       measured or (a contract violation of the
                                       backend) they disagree, then ms = -1 */
    uint64_t executions;
    uint64_t validation_errors;     /* since creation */
} fg_stats;

/* Fills `s`; its arrays stay valid until the graph changes (declarations,
 * fg_compile, fg_destroy). False when the graph is not compiled. */
bool fg_get_stats(const fg_graph *g, fg_stats *s);
/* Human-readable table of the stats. */
void fg_print_stats(const fg_graph *g, FILE *f);
/* Adds the last execute's time of every measured pass named names[k]
 * (k < count) to ms[k]; passes not measured (culled, no_timers) add
 * nothing. *clock takes the clock of the measured passes: the caller starts
 * it at DIRT_CLOCK_NONE (and ms[] at 0) and may add several graphs' times;
 * *clock still DIRT_CLOCK_NONE afterwards means nothing was measured. A
 * pass measured by another clock than *clock already holds is left out
 * (logged; one backend has one clock). For techniques that run several
 * graphs (e.g. a rerun after pool growth) and report one time per pass
 * name. */
void fg_add_pass_times(const fg_graph *g, const char *const *names, int count, double *ms,
                       enum dirt_clock *clock);

/* GraphViz DOT of the compiled graph: passes as boxes, resources as
 * ellipses, culled ones grey, edges labelled with the access. Deterministic.
 * fg_dot returns a malloc'd string (NULL after logging). */
char *fg_dot(const fg_graph *g);
bool fg_write_dot(const fg_graph *g, FILE *f);

/* ---- lifetime and backends ----------------------------------------------- */

/* Physical allocation requested from a backend. */
typedef struct fg_phys_desc {
    bool texture;
    size_t bytes;                   /* buffers: size; textures: computed total */
    bool readback;                  /* buffers */
    fg_format format;               /* textures */
    bool array;
    int width, height, layers, levels;
    const char *label;
} fg_phys_desc;

/* One declared access, resolved for the backend. */
typedef struct fg_binding {
    fg_res res;
    fg_access access;
    bool texture;
    uint32_t name;                  /* GL name */
    fg_use_opts opts;
    fg_format format;
    bool array;
    int width, height, layers, levels;
    size_t bytes;
    bool pass_reads, pass_writes;   /* the pass's whole use of this resource */
} fg_binding;

typedef struct fg_pass_info {
    const char *name;
    int index;                      /* declaration index */
    int position;                   /* execution position */
    fg_pass_kind kind;
    const fg_binding *bindings;
    int num_bindings;
    int raster_width, raster_height, raster_layers; /* attachment-less raster */
    bool timed;                     /* time the pass (fg_exec_opts.no_timers off) */
    bool async;                     /* without waiting (fg_exec_opts.async_timers) */
} fg_pass_info;

typedef struct fg_backend_ops {
    /* Returns the new object's name (non-zero) or 0 after logging. */
    uint32_t (*create)(void *self, const fg_phys_desc *d);
    void (*destroy)(void *self, const fg_phys_desc *d, uint32_t name);
    void (*barrier)(void *self, uint32_t bits);
    /* Debug group, framebuffer, bindings, timer start. False after logging. */
    bool (*begin_pass)(void *self, const fg_pass_info *p);
    /* Timer stop, state reset. When p->timed, writes the pass's time (ms)
     * and the clock that measured it; a backend has one clock for all its
     * passes (the GL one: dirt_gpu_clock). Else, or when it could not time,
     * *ms = -1 and *clock = DIRT_CLOCK_NONE (the graph presets these). False
     * (after logging) when the pass left a GL error. */
    bool (*end_pass)(void *self, const fg_pass_info *p, double *ms, enum dirt_clock *clock);
    /* Frees `self`. */
    void (*release)(void *self);
    /* Optional (NULL: the backend's times never come late). The late time of
     * pass `index` (declaration index): with `discard` forgets what is in
     * flight; else waits for it, writes its sum to *ms and its clock to
     * *clock (the graph presets 0 and DIRT_CLOCK_NONE: nothing late). An
     * asynchronous end_pass (p->async) reports in *ms the pass's earlier
     * times that have arrived (0 when none, with the clock). */
    void (*drain)(void *self, int index, bool discard, double *ms, enum dirt_clock *clock);
    /* Optional (NULL: nothing). Called before the barrier of the pass that
     * makes a transient's first access in an execute, once per transient:
     * the backend may overwrite the object with garbage (its content is
     * undefined there: a new allocation, the last execute's, or another
     * transient's sharing the memory), so that reading what no pass of
     * this execute wrote shows (the GL backend: dirt_gpu_opts.poison). */
    void (*poison)(void *self, const fg_binding *b);
} fg_backend_ops;

typedef struct fg_backend {
    const fg_backend_ops *ops;
    void *self;
} fg_backend;


/* A graph executing on `backend` (the graph takes ownership of
 * backend->self, released with ops->release, also on failure). backend may
 * be NULL: such a graph compiles, exports and reports, but cannot execute.
 * The code that owns the GPU hands the backend in: src/gl/graph_gl.h makes
 * an OpenGL one (gl_graph_create). NULL after logging. */
fg_graph *fg_create(const fg_backend *backend);
/* Frees the graph and every allocation it made. NULL is fine. */
void fg_destroy(fg_graph *g);


#ifdef __cplusplus
}
#endif
#endif
