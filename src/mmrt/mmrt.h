/* DIRT engine: MMRT, the fragment-based baseline DIRT is measured against
 * (Vardis, Vasilakis, Papaioannou, "A Multiview and Multilayer Approach for
 * Interactive Ray Tracing", I3D 2016). Rebuilt every frame on the GPU:
 *   1 depth bounds: every pixel of every view gets the min/max eye-space
 *     depth of the fragments (pixel-centre samples of normally rasterized
 *     triangles) that land on it;
 *   2 mip: a min/max (Hi-Z) pyramid of those bounds (DIRT's, any size);
 *   3 store: every fragment becomes an id node {z, next, prev} plus a data
 *     node (shading attributes), pushed on the list of its bucket: B uniform
 *     slices of the pixel's linear depth range (a decoupled, bucketed,
 *     double-linked-list A-buffer, one atomic counter);
 *   4 reorder: each bucket list sorted by depth, prev pointers and tails set.
 * Complete by construction: every fragment is stored exactly once; the node
 * pools grow and the store pass reruns in the same frame when they overflow.
 *
 * The trace marches rays in image space through the views (linear sampling
 * or Hi-Z on the depth pyramid) and accepts a fragment whose depth is within
 * a thickness of the ray's depth span at that pixel: an approximation whose
 * quality depends on the thickness and the views' resolution (the weakness
 * DIRT removes). See doc/mmrt.md. */
#ifndef DIRT_MMRT_H
#define DIRT_MMRT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "common/constants.h" /* DIRT_MMRT_*_NODE_BYTES */

#include "views/tracer.h"
#include "dirt/gpu.h"
#include "dirt/scene.h"
#include "dirt/stats.h"
#include "dirt/types.h"
#include "views/views.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_mmrt dirt_mmrt;

/* Zero-initialised = single camera view 640x480, B = 4 (the MMRT paper's
 * setting), automatic initial node capacity and sort. views.tile_size is
 * ignored: MMRT is per pixel (tile size 1). */
typedef struct dirt_mmrt_opts {
    dirt_view_opts views;
    int buckets;              /* B >= 1 (default 4) */
    size_t initial_nodes;     /* first node capacity (0 = automatic: 2 per pixel) */
    enum dirt_mmrt_sort sort;
} dirt_mmrt_opts;

extern const char *const dirt_mmrt_pass_names[DIRT_MMRT_NUM_PASSES];

/* Node sizes in bytes: DIRT_MMRT_ID_NODE_BYTES (12, {z, next, prev}) and
 * DIRT_MMRT_DATA_NODE_BYTES (32, dirt_mmrt_data_node), defined once in the
 * shared registry. */

/* Compiles the programs. NULL on failure (logged). */
dirt_mmrt *dirt_mmrt_create(dirt_gpu *gpu, const dirt_mmrt_opts *opts);
/* Accepts NULL. */
void dirt_mmrt_destroy(dirt_mmrt *mmrt);

/* Builds the A-buffer of `frame` seen from `cam`. Returns false (logged)
 * when a buffer would exceed the GPU's limits or GL fails. */
bool dirt_mmrt_build(dirt_mmrt *mmrt, const dirt_frame *frame, const dirt_camera *cam);

const dirt_mmrt_stats *dirt_mmrt_get_stats(const dirt_mmrt *mmrt);
const dirt_view_set *dirt_mmrt_views(const dirt_mmrt *mmrt);
int dirt_mmrt_buckets(const dirt_mmrt *mmrt);

/* Prints a summary of the last build's stats to `out` (a FILE *). */
void dirt_mmrt_print_stats(const dirt_mmrt *mmrt, void *out);

/* ---- CPU copy of the structure (checks, pictures) ---- */

typedef struct dirt_mmrt_id_node {
    float z;                  /* eye-space depth in its view */
    uint32_t next, prev;      /* farther / nearer node, DIRT_MMRT_END ends */
} dirt_mmrt_id_node;

/* Shading attributes of a fragment, at its pixel centre (the GPU layout
 * dirt_mmrt_gpu_data of glsl/common/mmrt_layout.h). */
typedef struct dirt_mmrt_data_node {
    uint32_t prim;            /* primitive id */
    uint32_t material;        /* material index */
    uint32_t normal_oct;      /* shading normal, octahedral snorm16 x 2 */
    uint32_t pixel;           /* global pixel (view tile_base + y * width + x) */
    float u, v;               /* barycentrics of vertices 1 and 2 */
    float uv[2];              /* texture coordinates */
} dirt_mmrt_data_node;

#define DIRT_MMRT_END 0xFFFFFFFFu

typedef struct dirt_mmrt_data {
    int num_pixels, buckets, pyramid_size;
    float (*depth)[2];        /* pyramid: (zmin, zmax); +inf/0 for empty pixels */
    uint32_t *heads, *tails;  /* buckets * pixels, bucket-major: [b * pixels + g] */
    dirt_mmrt_id_node *ids;
    dirt_mmrt_data_node *data;
    uint32_t num_nodes;
} dirt_mmrt_data;

/* Reads the structure back (blocking). Free with dirt_mmrt_data_free. */
bool dirt_mmrt_read(dirt_mmrt *mmrt, dirt_mmrt_data *out);
void dirt_mmrt_data_free(dirt_mmrt_data *data);

/* Decodes a data node's normal. */
void dirt_mmrt_unpack_normal(uint32_t packed, float out[3]);

/* ---- Trace ---- */

/* Zero-initialised = Hi-Z over the whole pyramid, thickness 0.2 % of the
 * scene's bounding-box diagonal. */
typedef struct dirt_mmrt_trace_opts {
    enum dirt_mmrt_march march;
    int samples;      /* linear: samples per view; 0 = 30 (the demo's
                         default); < 0 = conservative: every pixel the ray
                         crosses (the Hi-Z walk without its upper levels) */
    int hiz_levels;   /* Hi-Z: 0 = every level; n > 0: levels 0 .. n-1 */
    float thickness;  /* eye-space depth units; 0 = default; < 0 = exactly 0 */
    uint32_t seed;    /* jitter of linear marching */
    uint32_t first_ray; /* ray i of this batch is ray first_ray + i of the
                           wavefront it was cut from (keys the jitter, so
                           that cutting a batch into chunks changes nothing) */
    bool all_views;   /* march every view over the whole ray, keep the closest
                         hit (default: each part of the ray in one view, the
                         first of camera, faces whose frustum holds it) */
    bool count;       /* count pixels tested / nodes visited (atomics) */
    dirt_trace_alpha alpha; /* alpha-tested traversal (views/tracer.h): the fragments
                           of hits it rejects are passed over; zero = none */
    uint32_t batch;   /* GL buffer of a ray batch the GPU sized (dirt_tracer's
                         set_batch): count is its capacity; 0 = none */
} dirt_mmrt_trace_opts;

typedef struct dirt_mmrt_trace_stats {
    uint64_t rays, hits;
    /* When opts.count (32-bit GPU counters: keep batches modest): */
    uint64_t steps;           /* march steps: Hi-Z cells at any level, linear samples */
    uint64_t pixels_tested;   /* per-pixel tests (bounds, then buckets and lists) */
    uint64_t nodes_visited;   /* id nodes read */
    uint64_t aborted;         /* rays whose Hi-Z walk ran out of steps */
    float thickness;          /* the thickness used */
    double ms;                /* the trace dispatch; -1 when not measured */
    enum dirt_clock clock;    /* what measured ms (dirt_gpu_clock; NONE when not measured) */
} dirt_mmrt_trace_stats;

/* Traces `count` rays through the structure of the last dirt_mmrt_build
 * (blocking: uploads, dispatches, reads back), closest hit per ray:
 * hits[i].prim = DIRT_HIT_NONE when nothing was hit; else prim and view of
 * the fragment hit, owner = i, next = its data node index (the shading
 * record), u/v = the fragment's barycentrics (at its pixel centre, not at
 * the ray), t = along the ray where its depth in that view equals the
 * fragment's (clamped to the ray's span on that pixel), reserved = the
 * fragment's depth. `opts` and `stats` may be NULL. */
bool dirt_mmrt_trace_cpu(dirt_mmrt *mmrt, const dirt_ray *rays, size_t count, dirt_hit *hits,
                         const dirt_mmrt_trace_opts *opts, dirt_mmrt_trace_stats *stats);

/* ---- The A-buffer as the integrator's tracer (views/tracer.h) ---- */

/* The tracer over the A-buffer of the last dirt_mmrt_build with trace
 * options `opts` (NULL = defaults; the seed jitters the linear march, mixed
 * with the index of the trace since the tracer's counts were last reset).
 * MMRT's way (the MMRT paper: no Fetch): a hit's data node becomes the
 * shading point directly (shading normal, uv and material from the data
 * node; geometric normal of the primitive; position where the ray meets the
 * hit primitive's plane when it meets it inside the hit fragment's pixel,
 * else the MMRT hit point, ray origin + t direction; the hit's t is set to
 * the distance used). Its surface_offset is 3 thicknesses: rays leave
 * surfaces 3 thicknesses off along the normal and shadow rays stop 3
 * thicknesses off the light's plane (views/tracer.h), so that a ray is never
 * within the thickness of a planar surface it leaves or aims at. No visibility
 * function. Owned by `mmrt`; valid until the next call or destroy. NULL
 * (logged) before a successful build. */
const dirt_tracer *dirt_mmrt_tracer(dirt_mmrt *mmrt, const dirt_mmrt_trace_opts *opts);

#ifdef __cplusplus
}
#endif
#endif
