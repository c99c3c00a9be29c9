/* Data layouts shared by C and GLSL: the single definition of every record
 * that crosses the CPU/GPU boundary. Included from C (src/) and from GLSL
 * (glsl/). Every member is a 16-byte vector so std430 and C agree without
 * padding rules; test/common/layout_check.c checks every size and member offset
 * with _Static_assert. Binding points and other shared numbers are in
 * common/constants.h (the registry).
 *
 * This file must stay valid as both C11 and GLSL 4.50: only structs of
 * DIRT_V4/DIRT_IV4/DIRT_UV4 members and #defines. */
#ifndef DIRT_COMMON_LAYOUT_H
#define DIRT_COMMON_LAYOUT_H

/* Binding points, node sizes, workgroup sizes, uniform locations. */
#include "common/constants.h"

#ifdef GL_core_profile
#define DIRT_V4 vec4
#define DIRT_IV4 ivec4
#define DIRT_UV4 uvec4
#else
typedef struct dirt_f4 { float x, y, z, w; } dirt_f4;
typedef struct dirt_i4 { int x, y, z, w; } dirt_i4;
typedef struct dirt_u4 { unsigned int x, y, z, w; } dirt_u4;
#define DIRT_V4 dirt_f4
#define DIRT_IV4 dirt_i4
#define DIRT_UV4 dirt_u4
#endif

/* The raster preview binds dirt_gpu_material[] at DIRT_BIND_PREVIEW_MATERIALS
 * and dirt_gpu_light[] at DIRT_BIND_PREVIEW_LIGHTS. */

/* Light kinds of the raster preview (punctual kinds match dirt_light_type). */
#define DIRT_PREVIEW_LIGHT_DIRECTIONAL 0
#define DIRT_PREVIEW_LIGHT_POINT 1
#define DIRT_PREVIEW_LIGHT_SPOT 2
#define DIRT_PREVIEW_LIGHT_EMITTER 3 /* an emissive surface lumped into one point */

/* One material (64 bytes). */
struct dirt_gpu_material {
    DIRT_V4 base_color;  /* linear RGBA factor */
    DIRT_V4 emissive;    /* rgb = emissive factor * strength, w unused */
    DIRT_V4 pbr;         /* x metallic, y roughness, zw unused */
    DIRT_IV4 textures;   /* x base colour, y metallic-roughness, z emissive (-1 none), w flags */
};

/* One preview light (64 bytes). */
struct dirt_gpu_light {
    DIRT_V4 position;    /* xyz world position, w kind (DIRT_PREVIEW_LIGHT_*) */
    DIRT_V4 direction;   /* xyz unit direction the light shines along (emitter: its normal) */
    DIRT_V4 color;       /* rgb intensity (emitter: radiance * area), w range (0 = inf) */
    DIRT_V4 cone;        /* x cos inner, y cos outer (spot) */
};

/* ---- DIRT acceleration structure (src/dirt/build.c, glsl/dirt/) ---- */

/* Bindings: DIRT_BIND_VERTICES, _VIEWS, _DEPTH (shared with MMRT) and
 * DIRT_BIND_PARAMS, _HEADS, _NODES, _COUNTERS (common/constants.h). */

#define DIRT_LIST_END 0xFFFFFFFFu
#define DIRT_GPU_MAX_VIEWS 7   /* = DIRT_MAX_VIEWS of views/views.h */
/* Cleared depth bounds: zmin = +inf, zmax = 0 (empty: zmin > zmax). Depths
 * are positive, so their float bits order like the floats. */
#define DIRT_DEPTH_CLEAR_MIN 0x7F800000u
#define DIRT_DEPTH_CLEAR_MAX 0u
/* How far the GPU moves every tile-frustum plane outwards before clipping:
 * side planes by DIRT_CLIP_EPS tile widths, near/far by DIRT_CLIP_EPS / 100
 * in NDC depth. Float rounding is far below this, so the GPU never misses a
 * (primitive, tile) pair the exact clip has; the CPU reference uses 0 for
 * the pairs that must be present and 2 * DIRT_CLIP_EPS for those that may. */
#define DIRT_CLIP_EPS 1e-3

/* Sub-tile rectangles (dirt_ads_opts.sub_tiles; doc/dirt-build.md): a
 * candidate's and an id node's primitive word is prim | rect << 24, rect
 * the cells of a DIRT_SUBTILE_GRID x DIRT_SUBTILE_GRID grid over the tile
 * that the primitive's clipped footprint may cover, as x0 | (3 - x1) << 2 |
 * y0 << 4 | (3 - y1) << 6 (cells x0..x1, y0..y1; 0 = the whole tile).
 * Primitive ids must then be below DIRT_SUBTILE_MAX_PRIMS (the build fails
 * otherwise). DIRT_SUBTILE_MARGIN: how far (in cells) the build widens a
 * footprint's box and the trace a ray segment's before taking cells, far
 * above the eps band (DIRT_CLIP_EPS tile widths = 0.004 cells) and float
 * rounding. */
#define DIRT_SUBTILE_GRID 4
#define DIRT_SUBTILE_SHIFT 24
#define DIRT_SUBTILE_PRIM_MASK 0x00FFFFFFu
#define DIRT_SUBTILE_MAX_PRIMS 0x01000000u
#define DIRT_SUBTILE_MARGIN 0.05

/* Node depth ranges (dirt_ads_opts.node_depths; doc/dirt-build.md, "Node
 * depth ranges"): an id node's next word is next | d << 24, next the next
 * node's index (DIRT_NODE_NEXT_END: none) and d = lo | hi << 4 the
 * primitive's depth range in its bucket, in DIRT_NODE_DEPTH_SLABS sub-slabs
 * of the bucket (dirt_node_depth_q and dirt_node_depth_sub,
 * dirt/structure.glsl; d =
 * DIRT_NODE_DEPTH_FULL: the whole bucket). A build stores them only when
 * its node count is at most DIRT_NODE_DEPTH_MAX_NODES (an index must fit 24
 * bits); otherwise its next words are plain (dirt_ads_stats.node_depths
 * says which). The count pass hands the fill pass the range's two ends in
 * the candidate's w: first bucket | lo << 12 | last bucket << 16 | hi << 28
 * (B at most DIRT_NODE_DEPTH_MAX_BUCKETS; a middle bucket's range is the
 * whole bucket). */
#define DIRT_NODE_DEPTH_SLABS 16
#define DIRT_NODE_DEPTH_SHIFT 24
#define DIRT_NODE_NEXT_MASK 0x00FFFFFFu
#define DIRT_NODE_NEXT_END 0x00FFFFFFu
#define DIRT_NODE_DEPTH_MAX_NODES 0x00FFFFFFu
#define DIRT_NODE_DEPTH_FULL 0xF0u
#define DIRT_CAND_BUCKET_MASK 0xFFFu
#define DIRT_NODE_DEPTH_MAX_BUCKETS 4095

/* One vertex of the per-frame vertex buffer (32 bytes); vertex v of
 * primitive p is entry 3p + v. */
struct dirt_gpu_vertex {
    DIRT_V4 position;    /* xyz world position, w texture u */
    DIRT_V4 normal;      /* xyz world normal, w texture v */
};

/* One view (192 bytes); see views/views.h. */
struct dirt_gpu_view {
    DIRT_V4 view_proj[4]; /* columns of proj * view */
    DIRT_V4 eye_near;     /* xyz centre of projection, w znear */
    DIRT_V4 forward_far;  /* xyz view axis, w zfar */
    DIRT_IV4 size;        /* width, height, tiles_x, tiles_y */
    DIRT_IV4 placement;   /* tile_base, atlas_x, num_levels, face (-1 camera) */
    DIRT_IV4 level_base[4]; /* first pyramid entry of levels 0..15 */
};

/* Large primitives (doc/dirt-trace.md, "Large primitives"): at most this
 * many primitives are kept out of the tiles' lists and tested by every ray
 * instead, or through the large primitives' grid (below) where the
 * structure has one (dirt_ads_opts.large_grid). */
#define DIRT_GPU_MAX_LARGE 16

/* The large primitives' grid (doc/dirt-trace.md, "The large primitives'
 * grid"; only with dirt_ads_opts.large_grid, else large_grid[] is zero and
 * nothing is bound), at DIRT_BIND_LARGE_CELLS: per view v, the cells of pyramid level
 * L = params.large_grid[v].x & 0xFFFF (the first level with at most
 * DIRT_LARGE_GRID cells per side; cell (cx, cy) is the level-0 tiles
 * [cx 2^L, (cx + 1) 2^L) x [cy 2^L, (cy + 1) 2^L)), zw cells per side
 * (ceil(tiles / 2^L)); entry large_grid[v].y + (cy zx + cx) nl + k (nl =
 * params.cand.w) holds the float bits of (zmin, zmax): a conservative
 * eye-depth range of large primitive k in the cell's frustum (the clipped
 * triangle's, its planes moved out by DIRT_LARGE_CELL_EPS cell widths and
 * the range widened by DIRT_LARGE_DEPTH_EPS times the view's far depth),
 * (DIRT_DEPTH_CLEAR_MIN, _MAX) where it misses the cell; bit 16 + k of
 * large_grid[v].x is set when primitive k meets some cell of the view. The
 * trace tests a
 * large primitive only in cells whose range the ray's depth span meets. */
#define DIRT_LARGE_GRID 8
#define DIRT_LARGE_CELL_EPS 1e-2
#define DIRT_LARGE_DEPTH_EPS 1e-5

/* Build parameters (224 bytes). */
struct dirt_gpu_ads_params {
    DIRT_IV4 config;     /* views, tile size S, buckets B, tiles */
    DIRT_UV4 pool;       /* node capacity, pyramid entries, atlas width, atlas height */
    DIRT_UV4 cand;       /* x candidate capacity (records), y work-record capacity
                            (compute build: the records the node pool holds), z
                            primitives, w large primitives */
    DIRT_UV4 large[DIRT_GPU_MAX_LARGE / 4]; /* the large primitives' ids, ascending,
                            cand.w of them; DIRT_LIST_END in the unused slots */
    DIRT_IV4 large_grid[DIRT_GPU_MAX_VIEWS]; /* per view: x grid level | primitives
                            met << 16, y first entry at DIRT_BIND_LARGE_CELLS,
                            zw cells per side */
};

/* Counters of the build and the trace (48 bytes). */
struct dirt_gpu_ads_counters {
    DIRT_UV4 fill;       /* x id nodes needed (count pass), y (primitive, tile) pairs
                            n_p (depth pass, also past the candidate capacity);
                            z rays aborted by the last trace, w active rays traced
                            since the host last reset it */
    DIRT_UV4 build;      /* x candidate bound (bound pass; the compute build's
                            candidate tiles pass: the tiles it examines), y work
                            records (candidate tiles pass, also past their
                            capacity), zw 0 */
    DIRT_UV4 dispatch;   /* xyz the groups of the compute build's depth bounds
                            pass (read by glDispatchComputeIndirect at
                            DIRT_ADS_DISPATCH_OFFSET), w 0 */
};
#define DIRT_ADS_DISPATCH_OFFSET 32

/* A work record of the compute build (a uvec4 in DIRT_WORK_RECORD_NODES id
 * nodes of the node pool, which holds no node before the fill pass: record
 * r is nodes 2r and 2r + 1, dirt_work_record in dirt/structure.glsl),
 * written by the candidate tiles pass as uvec4(primitive, view | k << 3,
 * x0 | y0 << 16, nx | ny << 16): record k of the footprint of nx x ny tiles
 * from tile (x0, y0) of the view (row-major tile e = k q C .. (k+1) q C - 1,
 * C = DIRT_BUILD_CHUNK, q chunks per record, glsl/dirt/footprint.glsl).
 *
 * A candidate of the build (DIRT_CANDIDATE_BYTES, at DIRT_BIND_CANDIDATES):
 * one (primitive, tile) pair with a non-empty range, written by the depth
 * pass as uvec4(primitive, global tile, float bits of zmin, of zmax); the
 * count pass replaces zw by (first id node, first bucket | last bucket << 16)
 * for the fill pass. */

/* ---- Rays and hits shared by every technique's trace ---- */

/* Bound at DIRT_BIND_RAYS and DIRT_BIND_HITS (shared range). */
#define DIRT_NO_HIT 0xFFFFFFFFu

/* A ray of a batch (32 bytes): points p = origin + t * dir, t in (tmin, tmax). */
struct dirt_gpu_ray {
    DIRT_V4 origin_tmin;  /* xyz origin, w tmin */
    DIRT_V4 dir_tmax;     /* xyz direction (need not be unit), w tmax */
};

/* The closest hit of a ray (32 bytes, the DIRT paper's hit node size). */
struct dirt_gpu_hit {
    DIRT_UV4 ids;         /* x primitive id (DIRT_NO_HIT), y view, z owner pixel, w next hit */
    DIRT_V4 bary_t;       /* x, y barycentrics of vertices 1 and 2, z t, w unused */
};

/* A batch of rays whose size the GPU decided (the path tracer's live paths
 * after compaction): the header (16 bytes) of the DIRT_BIND_RAY_BATCH
 * buffer, followed by uint owner[capacity], the owner of ray i (the pixel
 * of the chunk whose path it continues). A pass over the batch dispatches
 * indirectly from `dispatch` (glDispatchComputeIndirect reads x, y, z) and
 * bounds-checks against its w. */
struct dirt_gpu_ray_batch {
    DIRT_UV4 dispatch;    /* x max(DIRT_GROUPS(count), 1) (a pass may have work
                             in invocation 0 alone), y 1, z 1, w count */
};

/* ---- Fetch and the three-point shading buffer ---- */

/* Bindings: DIRT_BIND_PRIM_MATERIAL, DIRT_BIND_GPOINTS (shared range),
 * DIRT_BIND_HIT_HEADS, DIRT_BIND_FETCH_PARAMS (trace range). */

/* A shading point G_k of a pixel (32 bytes, the DIRT paper's shading node
 * size). The ring holds three per pixel: slot (k mod 3) of pixel p is entry
 * 3 p + (k mod 3). prim = DIRT_NO_HIT marks a miss (the ray left the scene).
 * What a record does not hold, Shade derives exactly as Fetch would have:
 * the arriving direction from the ray it traced (normalize(dir)), the
 * geometric normal from the primitive's vertices (winding order,
 * normalised cross product), the texture uv from the hit record's
 * barycentrics (vertices 1 and 2), which the tracer's fetch leaves as those
 * of this point (pt_common.glsl, make_vertex). */
struct dirt_gpu_gpoint {
    DIRT_V4 pos_prim;     /* xyz position, w primitive id (uint bits) */
    DIRT_V4 n_mat;        /* xyz unit shading normal, w material (uint bits) */
};

/* Parameters of a Fetch (32 bytes). */
struct dirt_gpu_fetch_params {
    DIRT_UV4 config;      /* x hit count, y ring slot written (k+1 mod 3), z pixels, w 0 */
    DIRT_UV4 reserved;
};

/* ---- GPU path tracer (glsl/integrator/) ---- */

/* Bindings: DIRT_BIND_PATHS, DIRT_BIND_ACCUM, DIRT_BIND_SHADOW_RAYS
 * (integrator range of common/constants.h). */

#define DIRT_PATH_ALIVE 1u        /* dirt_gpu_path.radiance.w flag bits */
#define DIRT_PATH_PREV_DELTA 2u
#define DIRT_PATH_FIRST_HIT 4u

/* State of one pixel's path between passes (80 bytes). */
struct dirt_gpu_path {
    DIRT_V4 beta_pdf;     /* xyz throughput, w solid-angle pdf of the last BSDF sample */
    DIRT_V4 radiance;     /* xyz radiance gathered, w DIRT_PATH_* flags (uint bits) */
    DIRT_V4 pending;      /* xyz next-event contribution awaiting its shadow ray,
                             w 1 when a shadow ray is out */
    DIRT_V4 first_albedo; /* xyz albedo of the first hit, w unused */
    DIRT_V4 first_normal; /* xyz shading normal of the first hit, w unused */
};

/* Running sums of one pixel over the samples (48 bytes). */
struct dirt_gpu_accum {
    DIRT_V4 color;        /* xyz radiance sum, w samples */
    DIRT_V4 albedo;       /* xyz first-hit albedo sum, w non-finite samples dropped */
    DIRT_V4 normal;       /* xyz first-hit normal sum */
};

#endif
