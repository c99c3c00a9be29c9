/* DIRT engine: the per-primitive image-space acceleration structure (ADS)
 * of DIRT (HPG 2016, section 4.1), rebuilt every frame on the GPU:
 *   1 depth bounds: every view's tiles get the min/max eye-space depth of the
 *     triangles clipped exactly to the tile frustum;
 *   2 mip: a min/max (Hi-Z) pyramid of those bounds, any size;
 *   3 fill primitives: per (view, bucket, tile) a linked list of the ids of
 *     the triangles whose clipped depth range overlaps the bucket (eq. 1a/1b;
 *     or, with adaptive depth buckets, between the tile's own edges).
 * Complete by construction: a (primitive, tile) pair whose exact clip is
 * non-empty is always stored, in every bucket its range overlaps. Node pools
 * grow and the fill pass reruns in the same frame when they overflow. */
#ifndef DIRT_ADS_H
#define DIRT_ADS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/gpu.h"
#include "dirt/scene.h"
#include "dirt/stats.h"
#include "dirt/types.h"
#include "views/tracer.h"
#include "views/views.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_ads dirt_ads;

/* The mode DIRT_BUILD_DEFAULT stands for: DIRT_BUILD=compute gives
 * COMPUTE, DIRT_BUILD=raster RASTER, anything else `fallback`. */
enum dirt_build_mode dirt_build_from_env(enum dirt_build_mode fallback);

/* Zero-initialised = single camera view 640x480, S = 2, B = 16, automatic
 * initial node capacity, raster build. */
typedef struct dirt_ads_opts {
    dirt_view_opts views;
    int buckets;              /* B >= 1 (default 16) */
    size_t initial_nodes;     /* first node capacity (0 = automatic; the pool is sized
                                 from the count pass before the fill pass runs) */
    size_t initial_candidates; /* first candidate capacity (0 = from the bound
                                  pass); the compute build's work records
                                  live in the node pool (initial_nodes) */
    bool force_emulation;     /* ignore GL_NV_conservative_raster */
    bool reference_clip;      /* Sutherland-Hodgman clip of every candidate tile (the
                                 slow reference of the exact range, for checks and
                                 benchmarks; doc/dirt-build.md) */
    enum dirt_build_mode build; /* default (raster), raster or compute passes */
    int large;                /* large primitives (doc/dirt-trace.md): at most this many
                                 of the frame's largest triangles (dirt_ads_select_large)
                                 are left out of the lists and tested by every ray
                                 (or through their grid: large_grid);
                                 0 = DIRT_ADS_MAX_LARGE, < 0 = none */
    double large_area;        /* the smallest large triangle's area, as a fraction of the
                                 squared diagonal of the frame's bounds (0 =
                                 DIRT_ADS_LARGE_AREA) */
    bool large_grid;          /* each build also makes the large primitives' grid
                                 (common/layout.h) and the trace tests a large
                                 primitive only in the grid's cells whose depth
                                 range the ray meets (fewer triangle tests, more
                                 march steps; the same hits); false: every ray
                                 tests every large primitive */
    enum dirt_depth_buckets depth_buckets; /* uniform (default) or adaptive
                                 (doc/dirt-build.md; B at most DIRT_ADAPT_MAX_BUCKETS) */
    bool sub_tiles;           /* every id node also carries the cells of a 4 x 4 grid
                                 over its tile that the primitive's clipped
                                 footprint may cover, and the trace skips a node
                                 whose cells the ray's segment in the tile misses
                                 (common/layout.h, DIRT_SUBTILE_*; fewer triangle
                                 tests, the same hits); the build then fails
                                 (logged) for frames of DIRT_SUBTILE_MAX_PRIMS or
                                 more triangles. false: plain ids, the trace
                                 without the test */
    bool bucket_masks;        /* each build also keeps one occupancy word per tile
                                 (uniform buckets: bit s: a candidate's range meets
                                 depth slab s of DIRT_BUCKET_MASK_SLABS; adaptive:
                                 bit b: bucket b holds a node; common/constants.h,
                                 DIRT_BUCKET_MASK_*), when buckets <=
                                 DIRT_BUCKET_MASK_MAX_BUCKETS, and the trace skips a
                                 tile that holds nothing in the ray's depth span by
                                 its mask (fewer tiles walked, the same hits); false
                                 or more buckets: no masks, the trace without the
                                 test */
    bool node_depths;         /* every id node's next word also carries its primitive's
                                 depth range in its bucket, in DIRT_NODE_DEPTH_SLABS
                                 sub-slabs (common/layout.h, DIRT_NODE_DEPTH_*), and
                                 the trace skips a node whose range the ray's depth
                                 span misses (fewer triangle tests, the same hits; no
                                 memory); B at most DIRT_NODE_DEPTH_MAX_BUCKETS. A
                                 build of more than DIRT_NODE_DEPTH_MAX_NODES nodes
                                 stores plain next words instead
                                 (dirt_ads_stats.node_depths). false: plain, the trace
                                 without the test */
} dirt_ads_opts;

/* The large primitives of `frame`: of the triangles whose area is at least
 * `area` (0: DIRT_ADS_LARGE_AREA) times the squared diagonal of the frame's
 * bounds (and not 0), the `max` largest (ties: the lower id first; max is
 * clamped to [0, DIRT_ADS_MAX_LARGE]). Writes their ids to ids, ascending,
 * and returns how many. Deterministic; what dirt_ads_build uses with max =
 * opts.large, area = opts.large_area. */
int dirt_ads_select_large(const dirt_frame *frame, int max, double area,
                          uint32_t ids[DIRT_ADS_MAX_LARGE]);

extern const char *const dirt_ads_pass_names[DIRT_ADS_NUM_PASSES];

/* Compiles the build programs. NULL on failure (logged). */
dirt_ads *dirt_ads_create(dirt_gpu *gpu, const dirt_ads_opts *opts);
void dirt_ads_destroy(dirt_ads *ads);

/* Builds the structure for `frame` seen from `cam`. Returns false (logged)
 * when a buffer would exceed the GPU's limits or GL fails. */
bool dirt_ads_build(dirt_ads *ads, const dirt_frame *frame, const dirt_camera *cam);

const dirt_ads_stats *dirt_ads_get_stats(const dirt_ads *ads);
const dirt_view_set *dirt_ads_views(const dirt_ads *ads);
int dirt_ads_buckets(const dirt_ads *ads);

/* CPU copy of the built structure, for checks and pictures. */
typedef struct dirt_ads_data {
    int num_tiles, buckets;
    int pyramid_size;
    float (*depth)[2];        /* pyramid: (zmin, zmax); +inf/0 for empty tiles */
    uint32_t *heads;          /* buckets * tiles, bucket-major */
    int fine_bins;            /* adaptive buckets: H fine bins per tile; 0 = uniform */
    uint16_t *edges;          /* adaptive buckets: (buckets + 1) per tile, e(0) = 0 ..
                                 e(B) = H (common/constants.h, DIRT_ADAPT_*); NULL
                                 when uniform */
    uint32_t *masks;          /* occupancy per tile (uniform buckets: bit s: a
                                 candidate's range meets depth slab s; adaptive:
                                 bit b: bucket b holds a node; common/constants.h,
                                 DIRT_BUCKET_MASK_*); NULL
                                 without them (bucket_masks off, or buckets >
                                 DIRT_BUCKET_MASK_MAX_BUCKETS) */
    uint32_t (*nodes)[2];     /* (primitive, next); the primitive without its
                                 rectangle (sub_tiles) */
    uint8_t *rects;           /* sub_tiles: each node's rectangle byte
                                 (common/layout.h); NULL without them */
    uint8_t *node_depths;     /* node_depths stored by the build: each node's range
                                 byte lo | hi << 4 (common/layout.h), its next word
                                 then plain in nodes; NULL without them */
    uint32_t num_nodes;
    int num_large;            /* the large primitives, left out of the lists */
    uint32_t large[DIRT_ADS_MAX_LARGE];
} dirt_ads_data;

/* Reads the structure back (blocking). Free with dirt_ads_data_free. */
bool dirt_ads_read(dirt_ads *ads, dirt_ads_data *out);
void dirt_ads_data_free(dirt_ads_data *data);

/* ---- Trace ---- */

/* Zero-initialised = full Hi-Z, closest hit. */
typedef struct dirt_trace_opts {
    int hiz_levels;   /* the highest level a march climbs to: 0 = the pyramid's top;
                         n > 0: level n - 1 */
    bool any_hit;     /* visibility rays: stop at the first hit found */
    bool from_surfaces; /* every ray leaves a surface point: the march of its first
                           piece starts at level 0 (a hint: the same hits either
                           way; doc/dirt-trace.md, "Hi-Z march") */
    dirt_trace_alpha alpha; /* alpha-tested traversal (views/tracer.h); zero = none */
    uint32_t batch;   /* GL buffer of a ray batch the GPU sized (dirt_tracer's
                         set_batch); 0 = the call's rays 0 .. count - 1 */
    uint32_t work;    /* GL buffer of one dirt_trace_work per ray: the counting
                         build of the trace fills it; 0 = the plain build */
} dirt_trace_opts;

/* The work of one ray (the trace's counting build; doc/dirt-trace.md,
 * "Work counters"): what it costs on any GPU, not a time. */
typedef struct dirt_trace_work {
    uint32_t tiles;          /* level-0 tiles whose buckets were walked */
    uint32_t hiz_steps;      /* march steps: cells of any level looked at, the large
                                primitives' grid's included */
    uint32_t list_nodes;     /* list nodes read */
    uint32_t triangle_tests; /* exact ray-triangle tests (large primitives' too) */
} dirt_trace_work;

typedef struct dirt_trace_stats {
    uint64_t rays;
    uint64_t aborted; /* rays whose march ran out of steps (their hit may be wrong) */
    double ms;        /* the trace dispatch; -1 when not measured */
    enum dirt_clock clock; /* what measured ms (dirt_gpu_clock; NONE when not measured) */
} dirt_trace_stats;

/* Traces `count` rays through the structure of the last dirt_ads_build
 * (blocking: uploads, dispatches, reads back). `opts`/`stats` may be NULL. */
bool dirt_ads_trace(dirt_ads *ads, const dirt_ray *rays, size_t count, dirt_hit *hits,
                    const dirt_trace_opts *opts, dirt_trace_stats *stats);
/* The same through the counting build, with each ray's work in work[i]
 * (opts->work is ignored). */
bool dirt_ads_trace_work(dirt_ads *ads, const dirt_ray *rays, size_t count, dirt_hit *hits,
                         const dirt_trace_opts *opts, dirt_trace_stats *stats,
                         dirt_trace_work *work);

/* ---- Fetch ---- */

/* A shading point G (layout of dirt_gpu_gpoint, glsl/common/layout.h):
 * prim = DIRT_HIT_NONE for a miss. */
typedef struct dirt_gpoint {
    float position[3];
    uint32_t prim;
    float normal[3];      /* unit shading normal */
    uint32_t material;
} dirt_gpoint;

/* ---- The structure as the integrator's tracer (views/tracer.h) ---- */

/* DIRT's options for path tracing through the structure. Zero-initialised
 * = full Hi-Z, compute Fetch. */
typedef struct dirt_ads_tracer_opts {
    dirt_trace_opts trace;    /* any_hit is ignored (the integrator asks per batch) */
    enum dirt_fetch_mode fetch;
} dirt_ads_tracer_opts;

/* The tracer over the structure of the last dirt_ads_build with `opts`
 * (NULL = defaults). Owned by `ads`; valid until the next call or
 * dirt_ads_destroy. It has a visibility function (direct visibility of the
 * camera view). NULL (logged) before a successful build. */
const dirt_tracer *dirt_ads_tracer(dirt_ads *ads, const dirt_ads_tracer_opts *opts);

/* Traces the rays and fetches every hit into out[i] (owner = ray i) with the
 * given Fetch. For tests and tools (blocking). */
bool dirt_ads_trace_fetch(dirt_ads *ads, const dirt_ray *rays, size_t count,
                          enum dirt_fetch_mode mode, dirt_gpoint *out);

/* Direct visibility (DIRT paper 4.1.3, without spin locks): a depth-tested
 * visibility buffer of the camera view, resolved into the ray (from the
 * view's centre of projection through the pixel's visible point) and hit
 * record of every pixel (width x height of the camera view, row 0 = top,
 * owner = pixel index). For tests and tools (blocking). */
bool dirt_ads_direct_visibility(dirt_ads *ads, dirt_ray *rays, dirt_hit *hits);

/* Writes per-view PNG pictures of the built structure into `dir` (which
 * must exist): <dir>/ads_v<i>_<name>_lists.png (heat map of list length per
 * tile: black 0, then blue, red, yellow, white at the longest list) and
 * _zmin.png / _zmax.png (depth bounds, near = white, far = black, empty
 * tiles dark red), and <dir>/ads_graph.dot (the build's frame graph).
 * Prints the file names on stdout unless `quiet`. */
bool dirt_ads_write_debug(dirt_ads *ads, const char *dir, bool quiet);

/* Prints a summary of the last build's stats (counts, bytes vs the DIRT
 * paper's Table 3, pass times) to `out` (a FILE *). */
void dirt_ads_print_stats(const dirt_ads *ads, void *out);

#ifdef __cplusplus
}
#endif
#endif
