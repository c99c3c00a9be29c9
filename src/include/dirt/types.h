/* DIRT engine: the vocabulary of the consumer API that several layers share:
 * how DIRT builds and fetches, how MMRT sorts and marches, the path
 * tracer's modes and limits, the structures' figures (the DIRT and MMRT
 * papers' tables), the ray types of the hit-agreement checks and the
 * tone-map operators. Plain enums, records and name tables: the session's
 * options and stats (dirt/session.h) and the image writers (dirt/image.h)
 * use them, and the layers that implement them (src/dirt, src/mmrt,
 * src/integrator, src/ref, src/io, src/gl) take them from here, so each is
 * defined once. Values the shaders share are defined for GLSL in glsl/common/
 * and checked equal to these at compile time where both are seen
 * (src/io/png.c, src/integrator/gpu_pt.c). */
#ifndef DIRT_TYPES_H
#define DIRT_TYPES_H

#include <stdbool.h>
#include <stdint.h>

#include "dirt/api.h"
#include "dirt/stats.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Display ---- */

/* The tone-map operator applied after exposure (PNG output: dirt/image.h;
 * the window's presentation). */
enum dirt_tonemap {
    DIRT_TONEMAP_CLAMP = 0, /* clamp to [0,1] */
    DIRT_TONEMAP_REINHARD = 1, /* x / (1 + x) per channel */
    DIRT_TONEMAP_ACES = 2, /* Narkowicz's rational fit of the ACES curve */
};

/* ---- DIRT: the structure (doc/dirt-build.md, doc/dirt-trace.md) ---- */

/* How the structure is built (doc/dirt-build.md). Both give the same
 * structure: the same primitives in every (tile, bucket) list (the order
 * within a list comes from atomics), the same depth bounds and pyramid. */
enum dirt_build_mode {
    DIRT_BUILD_DEFAULT = 0, /* raster, unless the environment variable
                               DIRT_BUILD=compute|raster says otherwise (how
                               the test suites run every DIRT test with
                               either build; explicit modes are never
                               overridden) */
    DIRT_BUILD_RASTER,      /* a geometry-shader quad per (primitive, view), the range
                               per fragment */
    DIRT_BUILD_COMPUTE,     /* compute passes only: candidate tiles per (primitive,
                               view), the range per candidate tile */
};

/* Where a tile's depth buckets lie (doc/dirt-build.md, "Adaptive depth
 * buckets"). */
enum dirt_depth_buckets {
    DIRT_DEPTH_BUCKETS_UNIFORM = 0, /* B equal slabs of the tile's depth bounds (the
                                       DIRT paper's eq. 1a/1b) */
    DIRT_DEPTH_BUCKETS_ADAPTIVE,    /* per tile, edges at equal-coverage quantiles of
                                       its candidates' depth ranges (B <= 1024) */
};

/* Most large primitives a structure keeps (= DIRT_GPU_MAX_LARGE). */
#define DIRT_ADS_MAX_LARGE 16
/* A triangle is large when its area is at least this fraction of the squared
 * diagonal of the frame's bounds. */
#define DIRT_ADS_LARGE_AREA 0.05

enum dirt_fetch_mode {
    DIRT_FETCH_COMPUTE = 0, /* reads the primitive's vertices (compute pass) */
    DIRT_FETCH_RASTER = 1,  /* the paper's geometry pass over the hit lists */
};

/* The build's passes (doc/dirt-build.md): clear; depth bounds (exact range
 * per candidate, stored); mip; fill primitives (from the stored candidates);
 * count nodes (bucket ranges, node offsets: the node pool's size); candidate
 * bound (only when the candidate buffer's size is unknown: an upper bound of
 * the candidates, from the geometry stage, or in the compute build from the
 * candidate tiles pass); candidate tiles (compute build only: the work
 * records of every (primitive, view) footprint, before depth bounds). */
enum { DIRT_ADS_PASS_CLEAR, DIRT_ADS_PASS_DEPTH, DIRT_ADS_PASS_MIP, DIRT_ADS_PASS_FILL,
       DIRT_ADS_PASS_COUNT, DIRT_ADS_PASS_BOUND, DIRT_ADS_PASS_TILES, DIRT_ADS_NUM_PASSES };

typedef struct dirt_ads_stats {
    /* Counts of the last build. */
    uint64_t primitives;
    uint64_t tiles;           /* tiles of every view (level 0 of the pyramids) */
    uint64_t samples;         /* n_p: (primitive, tile) pairs with a non-empty clip */
    uint64_t nodes;           /* id nodes = sum over samples of buckets overlapped */
    double buckets_per_sample; /* c = nodes / samples */
    int fill_runs;            /* fill passes run: 1 (the pool is sized from the count) */
    int depth_runs;           /* depth passes run: 1, or 2 when the candidates
                                 outgrew their buffer (never on a first build) */
    bool bound_pass;          /* the candidate bound pass ran (first build, or the
                                 view set or the primitive count changed) */
    bool conservative_nv;     /* the hardware conservative path was used (raster build) */
    enum dirt_build_mode build; /* how it was built (RASTER or COMPUTE) */
    uint64_t work_records;    /* compute build: work records of the candidate tiles
                                 (0 for the raster build) */
    int num_large;            /* large primitives (not in the lists, not in `samples`) */
    uint32_t large[DIRT_ADS_MAX_LARGE]; /* their ids, ascending */
    /* Bytes. */
    uint64_t bytes_vertices;  /* vertex buffer */
    uint64_t bytes_depth;     /* depth bounds incl. pyramid: 8 B per entry */
    uint64_t bytes_heads;     /* 4 B * B * tiles */
    uint64_t bytes_nodes_allocated, bytes_nodes_used; /* the node pool: 8 B per node;
                                 the compute build's work records (16 B each) use it
                                 before the nodes, so used = the larger of the two */
    uint64_t bytes_candidates_allocated, bytes_candidates_used; /* 16 B per candidate
                                 (build scratch: n_p records, not in Table 3) */
    uint64_t bytes_total_allocated, bytes_total_used;
    /* DIRT paper Table 3 per tile: 8 B * 1.33 (depth + mips) + 4 B * B
     * (heads) + 8 B * c * n_p / tiles (nodes), times the tiles. */
    double bytes_table3;
    /* Pass times of the last build, ms, summed over the runs of each pass
     * (0 for a pass that did not run), measured by `clock` (the GPU's one
     * clock, dirt_gpu_clock); all -1 and DIRT_CLOCK_NONE when not measured. */
    double ms[DIRT_ADS_NUM_PASSES];
    enum dirt_clock clock;
    uint64_t bytes_large_grid; /* the large primitives' grid: 8 B per large primitive
                                 and grid cell (in the totals; not in Table 3) */
    uint64_t bytes_large_grid_allocated; /* its GL buffer */
    /* Adaptive depth buckets (0 with uniform ones; in both totals): the
     * bucket edges the trace reads (2 B per edge, B / 2 uints per tile)
     * and the build's coverage histogram (4 B per fine bin, 4 B uints per
     * tile; build scratch). Their passes' time is in ms[DIRT_ADS_PASS_COUNT]. */
    enum dirt_depth_buckets depth_buckets;
    uint64_t bytes_bucket_edges, bytes_bucket_histogram;
    /* Occupancy masks (B <= 32, else 0; in both totals, not in Table 3):
     * 4 B per tile, after the heads in the list-heads buffer; the trace
     * skips the tiles they show holding nothing in a ray's depth span. */
    uint64_t bytes_bucket_masks;
    /* Node depth ranges (dirt_ads_opts.node_depths, session option
     * node_depths): whether the last build stored them in its nodes' next
     * words (no bytes of their own); false when off, or when the build had
     * more than 2^24 - 1 nodes and stored plain next words. */
    bool node_depths;
} dirt_ads_stats;

/* ---- MMRT: the A-buffer (doc/mmrt.md) ---- */

/* How the reorder pass sorts bucket lists of three or more nodes (same
 * result either way). */
enum dirt_mmrt_sort {
    DIRT_MMRT_SORT_AUTO = 0,      /* list on software renderers, else registers */
    DIRT_MMRT_SORT_REGISTERS = 1, /* chunks of 8 in registers, merged */
    DIRT_MMRT_SORT_LIST = 2,      /* insertion sort in the linked list itself */
};

enum dirt_mmrt_march {
    DIRT_MMRT_MARCH_HIZ = 0,    /* min/max pyramid walk (exact pixel traversal) */
    DIRT_MMRT_MARCH_LINEAR = 1, /* N jittered samples per view */
};

enum { DIRT_MMRT_PASS_CLEAR, DIRT_MMRT_PASS_DEPTH, DIRT_MMRT_PASS_MIP, DIRT_MMRT_PASS_STORE,
       DIRT_MMRT_PASS_REORDER, DIRT_MMRT_NUM_PASSES };

typedef struct dirt_mmrt_stats {
    /* Counts of the last build. */
    uint64_t primitives;
    uint64_t pixels;          /* sum of the views' pixels */
    uint64_t covered_pixels;  /* pixels with at least one fragment */
    uint64_t fragments;       /* stored fragments = id nodes = data nodes */
    uint32_t max_layers;      /* most fragments in one pixel */
    double avg_layers;        /* fragments / covered pixels */
    uint64_t long_lists;      /* bucket lists longer than the register sort
                                 (sorted in merged chunks) */
    int store_runs;           /* 1, or more when the node pools grew */
    enum dirt_mmrt_sort sort; /* the reorder's sort (never AUTO) */
    /* Bytes. */
    uint64_t bytes_vertices;  /* vertex buffer + per-primitive materials */
    uint64_t bytes_depth;     /* depth bounds incl. Hi-Z pyramid: 8 B per entry */
    uint64_t bytes_heads;     /* head + tail pointers: 8 B * B * pixels */
    uint64_t bytes_id_nodes_allocated, bytes_id_nodes_used;     /* 12 B per node */
    uint64_t bytes_data_nodes_allocated, bytes_data_nodes_used; /* 32 B per node */
    uint64_t bytes_total_allocated, bytes_total_used;
    /* MMRT paper Table 2 (DLLB): pixels * (8 + 8 B) + fragments * (12 +
     * data), data = 32 B here; without the Hi-Z pyramid levels above 0. */
    double bytes_paper;
    /* Pass times of the last build, ms, measured by `clock` (the GPU's one
     * clock, dirt_gpu_clock); all -1 and DIRT_CLOCK_NONE when not measured.
     * The store entry adds up every run of the store pass. */
    double ms[DIRT_MMRT_NUM_PASSES];
    enum dirt_clock clock;
} dirt_mmrt_stats;

/* ---- The path tracer ---- */

enum dirt_pt_mode { DIRT_PT_PATH = 0, DIRT_PT_AO = 1 };

/* Path events of one sample (K = 64 scattering events and the emission-only
 * event after them): the length of the per-event figures. Equals the GPU
 * path tracer's DIRT_PT_MAX_EVENTS (glsl/common/constants.h; checked in
 * src/integrator/gpu_pt.c). */
#define DIRT_MAX_EVENTS 65

/* ---- Ray types of the hit-agreement checks (DIRT paper, Table 1) ---- */

enum dirt_ray_type {
    DIRT_RAY_PRIMARY,    /* camera rays through pixel centres */
    DIRT_RAY_VISIBILITY, /* towards a point of the light (tmax = 1: dir spans the segment) */
    DIRT_RAY_SPECULAR,   /* mirror reflection */
    DIRT_RAY_GLOSSY,     /* GGX (alpha = 0.1) visible-normal sample around the mirror */
    DIRT_RAY_DIFFUSE,    /* cosine-weighted */
    DIRT_RAY_TYPES
};

DIRT_API extern const char *const dirt_ray_type_names[DIRT_RAY_TYPES];

#ifdef __cplusplus
}
#endif
#endif
