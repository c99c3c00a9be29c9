/* Internal state of a DIRT structure, shared by the build (build.c) and the
 * trace (trace.c). */
#ifndef DIRT_DIRT_ADS_INTERNAL_H
#define DIRT_DIRT_ADS_INTERNAL_H

#include "common/layout.h"
#include "dirt/ads.h"
#include "gl/gl.h"
#include "gl/graph_gl.h"

struct dirt_ads {
    dirt_gpu *gpu;
    dirt_ads_opts opts;
    int num_views;
    bool use_nv;
    GLuint prog_depth, prog_bound, prog_mip, prog_count, prog_fill;
    GLuint prog_tiles, prog_range; /* the compute build's (0 for the raster build) */
    /* frame graphs: build (clear, depth bounds, mip, count nodes, read
     * counters), fill (fill primitives) once the node pool is sized, and
     * bound (clear counters, candidate bound, read counters) when the
     * candidate buffer's size is unknown; the compute build has candidate
     * tiles before depth bounds in build, and candidate tiles as bound */
    fg_graph *graph, *fill, *bound;
    fg_res r_vertices, r_views, r_params, r_depth, r_heads, r_nodes, r_counters, r_cands;
    int graph_atlas_w, graph_atlas_h;
    struct dirt_gpu_ads_counters counters_cpu; /* read back by the graph */
    /* buffers and their capacities in bytes */
    GLuint vertices, views, params, depth, heads, nodes, counters, cands;
    size_t vertices_size, depth_size, heads_size;
    size_t node_capacity;     /* nodes */
    size_t cand_capacity;     /* candidates (0: unknown, the bound pass sizes it) */
    size_t rec_capacity;      /* compute build: work records, after the candidates in
                                 the same buffer (0 for the raster build) */
    int cand_tiles;           /* tiles and primitives the capacity was bounded for */
    size_t cand_prims;
    dirt_view_set set;
    size_t num_primitives;
    struct dirt_gpu_vertex *staging;
    size_t staging_cap;
    dirt_ads_stats stats;
    /* trace */
    /* The trace's builds, [alpha | large << 1 | count << 2]: DIRT_TRACE_ALPHA
     * (alpha tests), DIRT_TRACE_LARGE (large primitives; llvmpipe runs a
     * loop's body once even when no invocation enters it, so the build
     * without them is kept for structures that have none), DIRT_TRACE_COUNT
     * (work counters). [0] made at creation, the others on first use. */
    GLuint prog_trace[8];
    GLuint rays, hits, work;
    size_t rays_size, hits_size, work_size;
    gl_timer trace_timer;
    /* fetch */
    GLuint prim_material;     /* uint per primitive */
    size_t prim_material_size;
    GLuint hit_heads;         /* uint per tile */
    size_t hit_heads_size;
    GLuint fetch_params;
    GLuint prog_fetch, prog_fetch_miss, prog_fetch_raster;
    GLuint fetch_vao, fetch_fbo;
    int fetch_fbo_w, fetch_fbo_h;
    uint32_t *material_staging;
    /* direct visibility */
    GLuint prog_vis, prog_vis_resolve;
    GLuint vis_fbo, vis_color, vis_depth, vis_vao;
    int vis_w, vis_h;
    /* the integrator's view of it (tracer.c) */
    dirt_tracer tracer;
    dirt_ads_tracer_opts tracer_opts;
    bool built;               /* the last build succeeded */
};

/* Direct visibility of the camera view: rasterizes a visibility buffer and
 * resolves it into one ray and hit record per image pixel (row 0 = top),
 * hits linked per tile like a linked trace. False (logged) when there is no
 * camera view. */
bool ads_visibility_gl(dirt_ads *a, GLuint rays, GLuint hits);

/* Traces `count` rays from buffer `rays` into `hits` (GL names, each at
 * least count records). With `link`, hits are also linked into per-tile
 * hit lists (hit_heads is cleared first) for the raster Fetch. Issues the
 * barriers it needs before and after. */
bool ads_trace_gl(dirt_ads *a, GLuint rays, GLuint hits, uint32_t count,
                  const dirt_trace_opts *opts, bool link, dirt_trace_stats *stats);

/* Resets / reads the count of active rays traced (counters.fill.w). */
void ads_reset_ray_count(dirt_ads *a);
bool ads_read_counts(dirt_ads *a, uint64_t *rays, uint64_t *aborted);

/* Binds the vertex buffer and the per-primitive materials (for shading). */
void ads_bind_geometry(dirt_ads *a);

/* Fetches the hit records into ring slot `slot` of `gpoints` (owner pixel =
 * record's ids.z). raster: the paper's geometry-pass Fetch over the hit
 * lists of the last linked trace (plus a compute pass for the misses);
 * else the compute Fetch. `batch`: the ray batch of that trace (0: count
 * records). */
bool ads_fetch_gl(dirt_ads *a, bool raster, GLuint rays, GLuint hits, uint32_t count,
                  GLuint gpoints, uint32_t slot, GLuint batch);

/* Binds every buffer of the structure at its DIRT_BIND_* point. */
void ads_bind_all(dirt_ads *a);

#endif
