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

struct dirt_mmrt {
    dirt_gpu *gpu;
    dirt_mmrt_opts opts;
    int num_views;
    GLuint prog_depth, prog_store, prog_mip, prog_reorder, prog_trace;
    GLuint prog_trace_alpha; /* DIRT_TRACE_ALPHA: made on first use */
    GLuint vao, fbo;
    int fbo_width, fbo_height;
    /* buffers and their capacities in bytes */
    GLuint vertices, materials, views, params, depth, heads, tails, ids, data, counters;
    size_t vertices_size, materials_size, depth_size, heads_size, tails_size;
    size_t node_capacity;     /* nodes (id and data pools alike) */
    GLuint rays, hits;        /* trace_cpu staging */
    size_t rays_size, hits_size;
    gl_timer trace_timer;
    /* frame graphs: build (clear, depth bounds, mip, store, read counters),
     * restore (clear lists, store, read counters) after pool growth, and
     * finish (reorder, read counters) */
    fg_graph *g_build, *g_restore, *g_finish;
    fg_res r_vertices, r_materials, r_views, r_params, r_depth, r_heads, r_tails, r_ids,
        r_data, r_counters;
    int graph_atlas_w, graph_atlas_h;
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
 * destroy). */
typedef struct dirt_mmrt_gl {
    GLuint vertices, materials, views, params, depth, heads, tails, ids, data, counters;
} dirt_mmrt_gl;

void dirt_mmrt_gl_buffers(const dirt_mmrt *mmrt, dirt_mmrt_gl *out);

/* Binds every buffer of the structure at its DIRT_BIND_* / DIRT_BIND_MMRT_*
 * point. */
void dirt_mmrt_bind(const dirt_mmrt *mmrt);

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
