/* Internal state of an MMRT A-buffer, shared by the build (mmrt.c) and the
 * trace (trace.c), and the GL-level entry points other GPU passes use (an
 * integrator's Fetch reads the data nodes directly). */
#ifndef DIRT_MMRT_INTERNAL_H
#define DIRT_MMRT_INTERNAL_H

#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "mmrt/mmrt.h"
#include "gl/gl.h"
#include "gl/graph_gl.h"
#include "gl/split.h"

/* The A-buffer's arrays that may pass one storage block (gl/split.h). */
enum mmrt_array {
    MMRT_VERTICES,       /* dirt_gpu_vertex[3] per primitive */
    MMRT_PRIM_MATERIAL,  /* uint per primitive */
    MMRT_HEADS,          /* uint per bucket and pixel */
    MMRT_TAILS,          /* uint per bucket and pixel */
    MMRT_IDS,            /* DIRT_MMRT_ID_UINTS uints per node */
    MMRT_DATA,           /* dirt_mmrt_gpu_data per node */
    MMRT_DEPTH,          /* uvec2 depth bounds per pixel, then their pyramid */
    MMRT_NUM_ARRAYS
};
#define MMRT_ARR(x) (1u << (x))
/* The A-buffer's own arrays (heads, tails, id and data nodes). */
#define MMRT_ABUFFER (MMRT_ARR(MMRT_HEADS) | MMRT_ARR(MMRT_TAILS) | MMRT_ARR(MMRT_IDS) | \
                      MMRT_ARR(MMRT_DATA))

struct dirt_mmrt {
    dirt_gpu *gpu;
    dirt_mmrt_opts opts;
    int num_views;
    /* programs built for the layouts of the split arrays they read
     * (mmrt_programs; the alpha trace on first use) */
    gl_split_program prog_depth, prog_store, prog_reorder, prog_trace, prog_trace_alpha;
    gl_split_program prog_mip;
    char nviews[8];
    GLuint vao, fbo;
    int fbo_width, fbo_height;
    /* buffers and their capacities in bytes */
    gl_split vertices, materials;  /* MMRT_VERTICES, MMRT_PRIM_MATERIAL */
    gl_split heads, tails, ids, data; /* MMRT_HEADS, _TAILS, _IDS, _DATA */
    gl_split depth;                  /* MMRT_DEPTH */
    GLuint views, params, counters;
    size_t node_capacity;     /* nodes (id and data pools alike) */
    GLuint rays, hits;        /* trace_cpu staging */
    size_t rays_size, hits_size;
    gl_timer trace_timer;
    /* frame graphs: build (clear, depth bounds, mip, store, read counters),
     * restore (clear lists, store, read counters) after pool growth, and
     * finish (reorder, read counters) */
    fg_graph *g_build, *g_restore, *g_finish;
    fg_res r_vertices[DIRT_SPLIT_MAX_PARTS], r_materials[DIRT_SPLIT_MAX_PARTS];
    fg_res r_heads[DIRT_SPLIT_MAX_PARTS], r_tails[DIRT_SPLIT_MAX_PARTS];
    fg_res r_ids[DIRT_SPLIT_MAX_PARTS], r_data[DIRT_SPLIT_MAX_PARTS];
    fg_res r_depth[DIRT_SPLIT_MAX_PARTS];
    fg_res r_views, r_params, r_counters;
    int graph_atlas_w, graph_atlas_h;
    int graph_parts[MMRT_NUM_ARRAYS]; /* the split arrays' parts the graphs import */
    struct dirt_mmrt_gpu_counters counters_cpu; /* read back by the graphs */
    dirt_view_set set;
    size_t num_primitives;
    float scene_diagonal;
    bool built;
    struct dirt_gpu_vertex *staging;
    size_t staging_cap;
    dirt_mmrt_stats stats;
    struct mmrt_tracer *tracer; /* the integrator's view of it (tracer.c) */
};

/* Frees the tracer state (tracer.c); called by dirt_mmrt_destroy. */
void mmrt_tracer_release(dirt_mmrt *mmrt);

/* GL names of the structure's buffers (valid until the next build or
 * destroy); the split arrays: mmrt_arrays. */
typedef struct dirt_mmrt_gl {
    GLuint views, params, counters;
} dirt_mmrt_gl;

/* The split arrays, by enum mmrt_array. */
void mmrt_arrays(dirt_mmrt *m, gl_split *arr[MMRT_NUM_ARRAYS]);
extern const gl_split_desc *const mmrt_array_desc[MMRT_NUM_ARRAYS];
/* The barrier bits of shaders' accesses of the arrays after the build's
 * shaders wrote them (gl_split_barrier of each): what a hand-written
 * barrier before the trace or Fetch issues. */
GLbitfield mmrt_split_barriers(dirt_mmrt *m);

/* Makes `p` the program of `label` / `paths` / `defs` for the layouts of
 * the arrays in `arrays` (MMRT_ARR(enum mmrt_array) bits). False after
 * logging. */
bool mmrt_program(dirt_mmrt *m, gl_split_program *p, const char *label, const char *const *paths,
                  const glsl_define *defs, size_t n, unsigned arrays);
/* The same with one more split array the shaders read (NULL: none; the
 * traces' alpha test reads the texels, dirt_trace_alpha.texels). */
bool mmrt_program_extra(dirt_mmrt *m, gl_split_program *p, const char *label,
                        const char *const *paths, const glsl_define *defs, size_t n,
                        unsigned arrays, const gl_split *extra);

/* Binds the vertices and the per-primitive materials (storage blocks or
 * texel buffers) for the shaders that read them. */
void mmrt_bind_geometry(dirt_mmrt *m);

void dirt_mmrt_gl_buffers(const dirt_mmrt *mmrt, dirt_mmrt_gl *out);

/* Binds every buffer of the structure at its DIRT_BIND_* / DIRT_BIND_MMRT_*
 * point. */
void dirt_mmrt_bind(dirt_mmrt *mmrt);

/* The thickness a trace with `opts` uses (resolves the default from the
 * scene of the last build). */
float dirt_mmrt_thickness(const dirt_mmrt *mmrt, const dirt_mmrt_trace_opts *opts);

/* Traces `count` rays of the dirt_gpu_ray buffer `rays` into the
 * dirt_gpu_hit buffer `hits` (same contract as dirt_mmrt_trace_cpu, without
 * transfers; the caller orders its own barriers around it: this issues a
 * GL_SHADER_STORAGE_BARRIER_BIT before and after the dispatch). `stats` may
 * be NULL; when given, the dispatch is timed (a GL time query: none may be
 * active) and the counters are read back (blocking). */
bool dirt_mmrt_trace(dirt_mmrt *mmrt, GLuint rays, GLuint hits, uint32_t count,
                     const dirt_mmrt_trace_opts *opts, dirt_mmrt_trace_stats *stats);

#endif
