/* Internal state of a DIRT structure, shared by the build (build.c) and the
 * trace (trace.c). */
#ifndef DIRT_DIRT_ADS_INTERNAL_H
#define DIRT_DIRT_ADS_INTERNAL_H

#include "common/layout.h"
#include "dirt/ads.h"
#include "gl/gl.h"
#include "gl/graph_gl.h"
#include "gl/split.h"

/* The structure's arrays that may pass one storage block (gl/split.h). */
enum ads_array {
    ADS_VERTICES,       /* dirt_gpu_vertex[3] per primitive */
    ADS_PRIM_MATERIAL,  /* uint per primitive */
    ADS_CANDIDATES,     /* uvec4 per candidate, then the compute build's work records */
    ADS_NODES,          /* uvec2 id node */
    ADS_HEADS,          /* uint per bucket and tile */
    ADS_DEPTH,          /* uvec2 depth bounds per tile, then their pyramid */
    ADS_NUM_ARRAYS
};
extern const gl_split_desc *const ads_array_desc[ADS_NUM_ARRAYS];

struct dirt_ads {
    dirt_gpu *gpu;
    dirt_ads_opts opts;
    int num_views;
    bool use_nv;
    /* programs, each built for the layouts of the split arrays it reads
     * (ads_programs) */
    gl_split_program prog_depth, prog_bound, prog_count, prog_fill;
    gl_split_program prog_hist, prog_edges; /* adaptive depth buckets */
    gl_split_program prog_tiles, prog_range; /* the compute build's (unmade for the raster build) */
    gl_split_program prog_mip;
    /* the defines of the raster build's passes (DIRT_NUM_VIEWS, pass, ...) */
    char nviews[8];
    /* frame graphs: build (clear, depth bounds, mip, count nodes, read
     * counters), fill (fill primitives) once the node pool is sized, and
     * bound (clear counters, candidate bound, read counters) when the
     * candidate buffer's size is unknown; the compute build has candidate
     * tiles before depth bounds in build, and candidate tiles as bound */
    fg_graph *graph, *fill, *bound;
    fg_res r_vertices[DIRT_SPLIT_MAX_PARTS], r_heads[DIRT_SPLIT_MAX_PARTS],
        r_nodes[DIRT_SPLIT_MAX_PARTS], r_cands[DIRT_SPLIT_MAX_PARTS];
    fg_res r_depth[DIRT_SPLIT_MAX_PARTS];
    fg_res r_views, r_params, r_counters;
    int graph_atlas_w, graph_atlas_h;
    int graph_parts[ADS_NUM_ARRAYS]; /* the split arrays' parts the graphs import */
    struct dirt_gpu_ads_counters counters_cpu; /* read back by the graph */
    /* buffers and their capacities in bytes */
    gl_split vertices;        /* ADS_VERTICES: per primitive */
    gl_split heads, nodes, cands; /* ADS_HEADS, ADS_NODES, ADS_CANDIDATES */
    gl_split depth;           /* ADS_DEPTH */
    GLuint views, params, counters;
    size_t node_capacity;     /* nodes */
    /* Node depth ranges (opts.node_depths): whether the last build stored
     * them (its node count at most node_depth_max_nodes:
     * DIRT_NODE_DEPTH_MAX_NODES, lowered by tests to reach the plain
     * fallback). */
    bool node_depths_stored;
    size_t node_depth_max_nodes;
    size_t cand_capacity;     /* candidates (0: unknown, the bound pass sizes it) */
    int cand_tiles;           /* tiles and primitives the capacity was bounded for */
    size_t cand_prims;
    dirt_view_set set;
    size_t num_primitives;
    struct dirt_gpu_vertex *staging;
    size_t staging_cap;
    dirt_ads_stats stats;
    /* the large primitives' grid (common/layout.h, DIRT_BIND_LARGE_CELLS;
     * only with opts.large_grid, else all zero, no entries, no buffer):
     * per view (level, first entry, cells x, cells y), the entries' staging
     * copy and the GL buffer */
    struct dirt_i4 large_grid[DIRT_GPU_MAX_VIEWS];
    uint32_t (*large_staging)[2];
    size_t large_entries, large_staging_cap;
    GLuint large_cells;
    size_t large_cells_size;
    /* trace */
    /* The trace's builds, [alpha | large << 1 | count << 2 | grid << 3 |
     * sub-tiles << 4 | masks << 5 | node depths << 6]:
     * DIRT_TRACE_ALPHA (alpha tests), DIRT_TRACE_LARGE (large primitives;
     * llvmpipe runs a loop's body once even when no invocation enters it, so
     * the build without them is kept for structures that have none),
     * DIRT_TRACE_COUNT (work counters), DIRT_TRACE_LARGE_GRID (with large:
     * through their grid, opts.large_grid), DIRT_SUB_TILES (the nodes'
     * rectangles, opts.sub_tiles), DIRT_BUCKET_MASKS (the tiles' bucket
     * occupancy masks, ads_has_masks), DIRT_NODE_DEPTHS (the nodes' depth
     * ranges, for a build that stored them: node_depths_stored).
     * [0] made at creation (and for each build's layouts), the others on
     * first use. */
    gl_split_program prog_trace[128];
    GLuint rays, hits, work;
    size_t rays_size, hits_size, work_size;
    gl_timer trace_timer;
    /* fetch */
    gl_split prim_material;   /* ADS_PRIM_MATERIAL: uint per primitive */
    GLuint hit_heads;         /* uint per tile */
    size_t hit_heads_size;
    GLuint fetch_params;
    gl_split_program prog_fetch, prog_fetch_miss, prog_fetch_raster;
    GLuint fetch_vao, fetch_fbo;
    int fetch_fbo_w, fetch_fbo_h;
    uint32_t *material_staging;
    /* direct visibility */
    gl_split_program prog_vis, prog_vis_resolve;
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

/* Binds every buffer of the structure at its DIRT_BIND_* point, and the
 * parts of its split arrays at their units. */
void ads_bind_all(dirt_ads *a);

/* The barrier bits of shaders' accesses of the structure's arrays after
 * the build's shaders wrote them (gl_split_barrier of each): what a
 * hand-written barrier before a trace, Fetch or visibility draw issues. */
GLbitfield ads_split_barriers(dirt_ads *a);

/* Binds the parts of the split arrays that are split (a pass body's part
 * of the binding: the frame graph binds the storage blocks). */
void ads_bind_split(dirt_ads *a);

/* Makes every program of the structure the one for the split arrays'
 * current layouts (the trace's: ads_trace_program). False after logging. */
bool ads_programs(dirt_ads *a);

/* Whether the structure keeps bucket occupancy masks: opts.bucket_masks
 * and buckets <= DIRT_BUCKET_MASK_MAX_BUCKETS (then the count pass sets
 * them and the trace reads them: DIRT_BUCKET_MASKS). */
bool ads_has_masks(const dirt_ads *a);

/* Makes `p` the program of `label` / `paths` / `defs` for the layouts of
 * the arrays in `arrays` (ADS_ARR(enum ads_array) bits). */
bool ads_program(dirt_ads *a, gl_split_program *p, const char *label, const char *const *paths,
                 const glsl_define *defs, size_t n, unsigned arrays);
/* The same with one more split array the shaders read (NULL: none; the
 * traces' alpha test reads the texels, dirt_trace_alpha.texels). */
bool ads_program_extra(dirt_ads *a, gl_split_program *p, const char *label,
                       const char *const *paths, const glsl_define *defs, size_t n,
                       unsigned arrays, const gl_split *extra);
#define ADS_ARR(x) (1u << (x))
/* The trace's arrays. */
#define ADS_TRACE_ARRAYS (ADS_ARR(ADS_VERTICES) | ADS_ARR(ADS_PRIM_MATERIAL) | \
                          ADS_ARR(ADS_NODES) | ADS_ARR(ADS_HEADS) | ADS_ARR(ADS_DEPTH))

#endif
