/* The registry of constants shared by C and GLSL: compute workgroup sizes,
 * node sizes, storage-buffer binding points (grouped into one named range
 * per subsystem), texture units and uniform locations. Every number that
 * both sides must agree on is defined here once and used by name on both
 * sides; the record layouts that use them live in common/layout.h,
 * integrator_layout.h, mmrt_layout.h and mmrt_pt_layout.h, which include
 * this file.
 *
 * This file must stay valid as both C11 and GLSL 4.50: #define, #if and
 * #error only. The #error checks below run in every C file and every shader
 * that includes it (shaders are validated at build time), so a binding
 * outside its subsystem's range or two overlapping ranges fail the build.
 * test/common/layout_check.c adds what the preprocessor cannot check
 * (uniqueness of every binding and of each program's uniform locations,
 * record sizes and member offsets). */
#ifndef DIRT_COMMON_CONSTANTS_H
#define DIRT_COMMON_CONSTANTS_H

/* ---- Compute workgroups ---- */

/* local_size_x of every one-dimensional compute shader; the host launches
 * DIRT_GROUPS(n) groups for n invocations (the shaders bound-check). */
#define DIRT_GROUP_SIZE 64
#define DIRT_GROUPS(n) (((n) + DIRT_GROUP_SIZE - 1) / DIRT_GROUP_SIZE)
/* local_size_x = local_size_y of two-dimensional compute shaders (the Hi-Z
 * mip pass, the frame-graph test's image pass): DIRT_GROUPS_2D(w) x
 * DIRT_GROUPS_2D(h) groups cover a w x h image. */
#define DIRT_GROUP_SIZE_2D 8
#define DIRT_GROUPS_2D(n) (((n) + DIRT_GROUP_SIZE_2D - 1) / DIRT_GROUP_SIZE_2D)
/* Groups per row of a long one-dimensional launch: GL promises 65535 groups
 * per dimension, so more groups go in rows (y); group (x, y) is number
 * y * DIRT_GROUPS_ROW + x (the DIRT compute build's passes). */
#define DIRT_GROUPS_ROW 65535
/* The DIRT compute build (glsl/dirt/tiles.comp, range.comp): a work record
 * covers q chunks of DIRT_BUILD_CHUNK candidate tiles of one (primitive,
 * view), one lane per tile of a chunk (so a lane takes q tiles),
 * DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK records per group. q is up to
 * DIRT_BUILD_LANE_TILES (all the footprint's chunks up to that), more when
 * a footprint would make more than DIRT_BUILD_MAX_RECORDS records, which
 * bounds the loops of both passes (llvmpipe caps an invocation's loop
 * iterations); glsl/dirt/footprint.glsl, dirt_build_chunks. */
#define DIRT_BUILD_CHUNK 8
#define DIRT_BUILD_LANE_TILES 4
#define DIRT_BUILD_MAX_RECORDS 4096
#if DIRT_GROUP_SIZE % DIRT_BUILD_CHUNK != 0
#error "common/constants.h: DIRT_BUILD_CHUNK must divide DIRT_GROUP_SIZE"
#endif

/* ---- Node and entry sizes (bytes) ---- */

#define DIRT_NODE_BYTES 8              /* DIRT id node: uvec2 (primitive id, next) */
#define DIRT_DEPTH_ENTRY_BYTES 8       /* depth-bounds pyramid entry: uvec2 (zmin, zmax) bits */
#define DIRT_HEAD_BYTES 4              /* list head: one uint */
#define DIRT_CANDIDATE_BYTES 16        /* DIRT build candidate: uvec4 (see common/layout.h) */
#define DIRT_WORK_RECORD_NODES 2       /* id nodes a compute build's work record (uvec4) takes */
#define DIRT_HIT_NODE_BYTES 32         /* dirt_gpu_hit (the DIRT paper's hit node) */
#define DIRT_MMRT_ID_UINTS 3           /* MMRT id node: {z, next, prev} uints */
#define DIRT_MMRT_ID_NODE_BYTES 12     /* = 4 * DIRT_MMRT_ID_UINTS (the MMRT paper's size) */
#define DIRT_MMRT_DATA_NODE_BYTES 32   /* dirt_mmrt_gpu_data */

/* Adaptive depth buckets (dirt_ads_opts.depth_buckets = DIRT_DEPTH_BUCKETS_ADAPTIVE;
 * doc/dirt-build.md, "Adaptive depth buckets"). A tile of B buckets has
 * H = DIRT_ADAPT_FINE * B fine bins, uniform over its depth bounds (eq.
 * 1a/1b with H for B); its bucket edges are fine-bin indices 0 = e0 <= e1
 * <= ... <= e(B-1) <= eB = H, and depth of fine bin f lies in bucket b when
 * e(b) <= f < e(b+1). The list-heads array (DIRT_BIND_HEADS) then holds,
 * after the B * tiles heads, DIRT_ADAPT_EDGE_WORDS(B) uints per tile of
 * edges (e(b), b in 1..B-1, 16 bits each: the low half of word (b - 1) / 2
 * for odd b, the high half for even b), then the build's histogram
 * of its candidates' range ends, H uints per tile (tile-major; counting up from the heads'
 * clear value DIRT_LIST_END, so a bin holds its count - 1). B is at most
 * DIRT_ADAPT_MAX_BUCKETS (an edge fits 16 bits). */
#define DIRT_ADAPT_FINE 4
#define DIRT_ADAPT_MAX_BUCKETS 1024
#define DIRT_ADAPT_EDGE_WORDS(B) ((B) / 2)
#define DIRT_ADAPT_TILE_UINTS(B) ((B) + DIRT_ADAPT_EDGE_WORDS(B) + DIRT_ADAPT_FINE * (B))
#if DIRT_ADAPT_FINE * DIRT_ADAPT_MAX_BUCKETS > 65535
#error "common/constants.h: an adaptive bucket edge must fit 16 bits"
#endif

/* Bucket occupancy masks (doc/dirt-build.md, "Pass 3: count nodes"):
 * with B <= DIRT_BUCKET_MASK_MAX_BUCKETS, the list-heads array ends with
 * one uint per tile (tile-major, after the heads and, with adaptive depth
 * buckets, the edges and histogram: DIRT_BUCKET_MASK_INDEX(per_tile, T, t),
 * per_tile = B or DIRT_ADAPT_TILE_UINTS(B)). It starts at the heads' clear
 * value DIRT_LIST_END (every bit set) and the count pass clears the bits of
 * each candidate's depth range; the tile's occupancy is its complement.
 * Uniform depth buckets: bit s stands for the tile's depth slab s of
 * DIRT_BUCKET_MASK_SLABS equal slabs of its bounds (whatever B; slab of a
 * depth: dirt_mask_slab, dirt/structure.glsl), clear when some candidate's
 * range meets it. Adaptive depth buckets: bit b is clear when bucket b holds
 * at least one node (bits at and above B: 0). With more buckets than
 * DIRT_BUCKET_MASK_MAX_BUCKETS there are no masks. */
#define DIRT_BUCKET_MASK_MAX_BUCKETS 32
#define DIRT_BUCKET_MASK_SLABS 32
#define DIRT_BUCKET_MASK_INDEX(per_tile, T, t) ((per_tile) * (T) + (t))

/* Path events of one sample the GPU path tracer can run: K = 64
 * scattering events (dirt_pt_opts.bounces) and the emission-only event
 * after them. */
#define DIRT_PT_MAX_EVENTS 65

/* The path tracer's ray sort (dirt_pt_opts.sort_rays; glsl/integrator/
 * sort.comp): a ray's key is its direction's cell on a
 * DIRT_SORT_DIR_CELLS x DIRT_SORT_DIR_CELLS octahedral map (high bits)
 * above the Morton code of its origin's cell on a DIRT_SORT_GRID^3 grid
 * over the scene's bounds (low bits); one bucket per key. */
#define DIRT_SORT_DIR_BITS 2                         /* per axis of the map */
#define DIRT_SORT_GRID_BITS 3                        /* per axis of the grid */
#define DIRT_SORT_DIR_CELLS (1 << DIRT_SORT_DIR_BITS)
#define DIRT_SORT_GRID (1 << DIRT_SORT_GRID_BITS)
#define DIRT_SORT_BUCKETS (1 << (2 * DIRT_SORT_DIR_BITS + 3 * DIRT_SORT_GRID_BITS))
#define DIRT_SORT_SCAN_GROUP 256                     /* invocations of the scan */
#if DIRT_SORT_BUCKETS % DIRT_SORT_SCAN_GROUP != 0
#error "common/constants.h: DIRT_SORT_SCAN_GROUP must divide DIRT_SORT_BUCKETS"
#endif

/* ---- Storage-buffer binding points ----
 *
 * Each subsystem owns the range [DIRT_BIND_<S>_FIRST, DIRT_BIND_<S>_LAST];
 * the ranges are disjoint and ascending, so no two names share a binding
 * point and a pass may bind buffers of several subsystems at once (the path
 * tracer's Shade reads the shared range, the integrator's and the model
 * tables together). Buffers read or written by more than one subsystem
 * (DIRT, MMRT and the integrator exchange vertices, rays, hits and shading
 * points through them) are in the SHARED range. */

#define DIRT_BIND_SHARED_FIRST 0
#define DIRT_BIND_VERTICES 0         /* dirt_gpu_vertex[3 * primitives] */
#define DIRT_BIND_VIEWS 1            /* dirt_gpu_view[views] (DIRT and MMRT) */
#define DIRT_BIND_DEPTH 2            /* uvec2[pyramid entries]: float bits of (zmin, zmax) */
#define DIRT_BIND_RAYS 3             /* dirt_gpu_ray[rays] */
#define DIRT_BIND_HITS 4             /* dirt_gpu_hit[rays] (closest hit per ray) */
#define DIRT_BIND_PRIM_MATERIAL 5    /* uint[primitives]: material of each primitive */
#define DIRT_BIND_GPOINTS 6          /* dirt_gpu_gpoint[3 * pixels]: the shading ring */
#define DIRT_BIND_RAY_BATCH 7        /* dirt_gpu_ray_batch, uint owner[rays]: a batch the GPU sized */
#define DIRT_BIND_SHARED_LAST 7

/* DIRT acceleration structure (src/dirt/build.c, glsl/dirt/build.*). */
#define DIRT_BIND_ADS_FIRST 8
#define DIRT_BIND_PARAMS 8           /* dirt_gpu_ads_params */
#define DIRT_BIND_HEADS 9            /* uint[buckets * tiles]: first node or DIRT_LIST_END */
#define DIRT_BIND_NODES 10            /* uvec2[capacity]: (primitive id, next node) */
#define DIRT_BIND_COUNTERS 11        /* dirt_gpu_ads_counters */
#define DIRT_BIND_CANDIDATES 12      /* uvec4[candidate capacity]: the build's (primitive, tile) pairs */
#define DIRT_BIND_ADS_LAST 12

/* DIRT trace and fetch (src/dirt/trace.c, glsl/dirt/trace.comp, fetch*). */
#define DIRT_BIND_TRACE_FIRST 13
#define DIRT_BIND_HIT_HEADS 13       /* uint[tiles]: first hit record of each ADS tile */
#define DIRT_BIND_FETCH_PARAMS 14    /* dirt_gpu_fetch_params */
#define DIRT_BIND_TRACE_LAST 14

/* GPU path tracer (src/integrator/gpu_pt.c, glsl/integrator/). */
#define DIRT_BIND_INTEGRATOR_FIRST 15
#define DIRT_BIND_PATHS 15           /* dirt_gpu_path[pixels] */
#define DIRT_BIND_ACCUM 16           /* dirt_gpu_accum[pixels] */
#define DIRT_BIND_SHADOW_RAYS 17     /* dirt_gpu_ray[pixels]: next-event shadow rays */
#define DIRT_BIND_NEXT_BATCH 18      /* the ray batch compaction fills (layout of DIRT_BIND_RAY_BATCH) */
#define DIRT_BIND_PT_EVENTS 19       /* uint[DIRT_PT_MAX_EVENTS]: paths that reached each event */
#define DIRT_BIND_INTEGRATOR_LAST 19

/* MMRT A-buffer (src/mmrt/, glsl/mmrt/); its per-primitive materials are
 * DIRT_BIND_PRIM_MATERIAL. */
#define DIRT_BIND_MMRT_FIRST 20
#define DIRT_BIND_MMRT_PARAMS 20     /* dirt_mmrt_gpu_params */
#define DIRT_BIND_MMRT_HEADS 21      /* uint[B * pixels], bucket-major: nearest node or DIRT_LIST_END */
#define DIRT_BIND_MMRT_TAILS 22      /* uint[B * pixels], bucket-major: farthest node or DIRT_LIST_END */
#define DIRT_BIND_MMRT_IDS 23        /* uint[DIRT_MMRT_ID_UINTS * capacity]: id nodes */
#define DIRT_BIND_MMRT_DATA 24       /* dirt_mmrt_gpu_data[capacity] */
#define DIRT_BIND_MMRT_COUNTERS 25   /* dirt_mmrt_gpu_counters */
#define DIRT_BIND_MMRT_LAST 25

/* The path tracer's MMRT technique (src/mmrt/pt_mmrt.c, glsl/mmrt/pt_rays.comp). */
#define DIRT_BIND_MMRT_PT_FIRST 26
#define DIRT_BIND_MMRT_PT_COUNTS 26   /* dirt_mmrt_pt_counts */
#define DIRT_BIND_MMRT_PT_LAST 26

/* Tables of the light-transport model (src/integrator/gpu_tables.c,
 * glsl/integrator/model.glsl with DIRT_MODEL_BUFFERS). */
#define DIRT_BIND_MODEL_FIRST 27
#define DIRT_BIND_MODEL_MATERIALS 27   /* dirt_gpu_model_material[materials] */
#define DIRT_BIND_MODEL_AREA_CDF 28    /* dirt_gpu_model_lights header, float cdf[count] */
#define DIRT_BIND_MODEL_AREA_PRIMS 29  /* uint prim[count] (at least one entry) */
#define DIRT_BIND_MODEL_PUNCTUAL 30    /* dirt_gpu_model_light[punctual] (at least one) */
#define DIRT_BIND_MODEL_CAMERA 31      /* one dirt_gpu_model_camera */
#define DIRT_BIND_MODEL_TEXELS 32      /* dirt_gpu_model_texels header, texture records, RGBA8 texels */
#define DIRT_BIND_MODEL_ENV 33         /* the environment light: header, cdfs, texels */
#define DIRT_BIND_MODEL_TANGENTS 34    /* per-vertex tangents (normal maps) */
#define DIRT_BIND_MODEL_LAST 34

/* Raster preview (src/raster/preview.c, glsl/raster/). */
#define DIRT_BIND_PREVIEW_FIRST 35
#define DIRT_BIND_PREVIEW_MATERIALS 35 /* dirt_gpu_material[materials] */
#define DIRT_BIND_PREVIEW_LIGHTS 36    /* dirt_gpu_light[lights] */
#define DIRT_BIND_PREVIEW_LAST 36

/* Test shaders (glsl/test/, glsl/graph_test/, integrator/test_model.comp). */
#define DIRT_BIND_TEST_FIRST 37
#define DIRT_BIND_TEST_IN 37           /* a test's input buffer */
#define DIRT_BIND_TEST_OUT 38          /* a test's output buffer */
#define DIRT_BIND_TEST_LAST 38

/* Work counters (the counting builds of the traces, DIRT_TRACE_COUNT). */
#define DIRT_BIND_WORK_FIRST 39
#define DIRT_BIND_WORK 39              /* uvec4[rays]: one ray's work (dirt/trace.comp: tiles,
                                          Hi-Z steps, list nodes, triangle tests) */
#define DIRT_BIND_WORK_LAST 39

/* The path tracer's ray sort (src/integrator/ray_sort.c,
 * glsl/integrator/sort.comp). */
#define DIRT_BIND_SORT_FIRST 40
#define DIRT_BIND_SORT 40              /* uint offset[DIRT_SORT_BUCKETS], uint key[rays] */
#define DIRT_BIND_SORT_LAST 40

/* The DIRT structure's grid of large primitives (common/layout.h; only with
 * dirt_ads_opts.large_grid; the ADS range is full). */
#define DIRT_BIND_LARGE_FIRST 41
#define DIRT_BIND_LARGE_CELLS 41       /* uvec2[entries]: float bits of (zmin, zmax) per large
                                          primitive and grid cell */
#define DIRT_BIND_LARGE_LAST 41

/* Every binding point lies in [0, DIRT_BIND_LAST]; the GPU test checks it
 * against GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS of the context. */
#define DIRT_BIND_LAST DIRT_BIND_LARGE_LAST

/* The ranges are non-empty, ascending and disjoint. */
#if DIRT_BIND_SHARED_FIRST != 0 || DIRT_BIND_SHARED_LAST < DIRT_BIND_SHARED_FIRST || \
    DIRT_BIND_ADS_FIRST <= DIRT_BIND_SHARED_LAST || DIRT_BIND_ADS_LAST < DIRT_BIND_ADS_FIRST || \
    DIRT_BIND_TRACE_FIRST <= DIRT_BIND_ADS_LAST || DIRT_BIND_TRACE_LAST < DIRT_BIND_TRACE_FIRST || \
    DIRT_BIND_INTEGRATOR_FIRST <= DIRT_BIND_TRACE_LAST || \
    DIRT_BIND_INTEGRATOR_LAST < DIRT_BIND_INTEGRATOR_FIRST || \
    DIRT_BIND_MMRT_FIRST <= DIRT_BIND_INTEGRATOR_LAST || DIRT_BIND_MMRT_LAST < DIRT_BIND_MMRT_FIRST || \
    DIRT_BIND_MMRT_PT_FIRST <= DIRT_BIND_MMRT_LAST || \
    DIRT_BIND_MMRT_PT_LAST < DIRT_BIND_MMRT_PT_FIRST || \
    DIRT_BIND_MODEL_FIRST <= DIRT_BIND_MMRT_PT_LAST || DIRT_BIND_MODEL_LAST < DIRT_BIND_MODEL_FIRST || \
    DIRT_BIND_PREVIEW_FIRST <= DIRT_BIND_MODEL_LAST || \
    DIRT_BIND_PREVIEW_LAST < DIRT_BIND_PREVIEW_FIRST || \
    DIRT_BIND_TEST_FIRST <= DIRT_BIND_PREVIEW_LAST || DIRT_BIND_TEST_LAST < DIRT_BIND_TEST_FIRST || \
    DIRT_BIND_WORK_FIRST <= DIRT_BIND_TEST_LAST || DIRT_BIND_WORK_LAST < DIRT_BIND_WORK_FIRST || \
    DIRT_BIND_SORT_FIRST <= DIRT_BIND_WORK_LAST || DIRT_BIND_SORT_LAST < DIRT_BIND_SORT_FIRST || \
    DIRT_BIND_LARGE_FIRST <= DIRT_BIND_SORT_LAST || DIRT_BIND_LARGE_LAST < DIRT_BIND_LARGE_FIRST
#error "common/constants.h: storage-buffer binding ranges overlap or are out of order"
#endif

/* Every binding lies in its subsystem's range. */
#define DIRT_BIND_IN(b, first, last) ((b) >= (first) && (b) <= (last))
#if !DIRT_BIND_IN(DIRT_BIND_VERTICES, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_VIEWS, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_DEPTH, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_RAYS, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_HITS, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_PRIM_MATERIAL, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_GPOINTS, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_RAY_BATCH, DIRT_BIND_SHARED_FIRST, DIRT_BIND_SHARED_LAST)
#error "common/constants.h: a shared binding lies outside DIRT_BIND_SHARED_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_PARAMS, DIRT_BIND_ADS_FIRST, DIRT_BIND_ADS_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_HEADS, DIRT_BIND_ADS_FIRST, DIRT_BIND_ADS_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_NODES, DIRT_BIND_ADS_FIRST, DIRT_BIND_ADS_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_COUNTERS, DIRT_BIND_ADS_FIRST, DIRT_BIND_ADS_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_CANDIDATES, DIRT_BIND_ADS_FIRST, DIRT_BIND_ADS_LAST)
#error "common/constants.h: a DIRT structure binding lies outside DIRT_BIND_ADS_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_HIT_HEADS, DIRT_BIND_TRACE_FIRST, DIRT_BIND_TRACE_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_FETCH_PARAMS, DIRT_BIND_TRACE_FIRST, DIRT_BIND_TRACE_LAST)
#error "common/constants.h: a trace/fetch binding lies outside DIRT_BIND_TRACE_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_PATHS, DIRT_BIND_INTEGRATOR_FIRST, DIRT_BIND_INTEGRATOR_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_NEXT_BATCH, DIRT_BIND_INTEGRATOR_FIRST, DIRT_BIND_INTEGRATOR_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_PT_EVENTS, DIRT_BIND_INTEGRATOR_FIRST, DIRT_BIND_INTEGRATOR_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_ACCUM, DIRT_BIND_INTEGRATOR_FIRST, DIRT_BIND_INTEGRATOR_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_SHADOW_RAYS, DIRT_BIND_INTEGRATOR_FIRST, DIRT_BIND_INTEGRATOR_LAST)
#error "common/constants.h: an integrator binding lies outside DIRT_BIND_INTEGRATOR_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_MMRT_PARAMS, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MMRT_HEADS, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MMRT_TAILS, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MMRT_IDS, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MMRT_DATA, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MMRT_COUNTERS, DIRT_BIND_MMRT_FIRST, DIRT_BIND_MMRT_LAST)
#error "common/constants.h: an MMRT binding lies outside DIRT_BIND_MMRT_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_MMRT_PT_COUNTS, DIRT_BIND_MMRT_PT_FIRST, DIRT_BIND_MMRT_PT_LAST)
#error "common/constants.h: an MMRT technique binding lies outside DIRT_BIND_MMRT_PT_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_MODEL_MATERIALS, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_AREA_CDF, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_AREA_PRIMS, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_PUNCTUAL, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_CAMERA, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_TEXELS, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_ENV, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_MODEL_TANGENTS, DIRT_BIND_MODEL_FIRST, DIRT_BIND_MODEL_LAST)
#error "common/constants.h: a model-table binding lies outside DIRT_BIND_MODEL_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_PREVIEW_MATERIALS, DIRT_BIND_PREVIEW_FIRST, DIRT_BIND_PREVIEW_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_PREVIEW_LIGHTS, DIRT_BIND_PREVIEW_FIRST, DIRT_BIND_PREVIEW_LAST)
#error "common/constants.h: a preview binding lies outside DIRT_BIND_PREVIEW_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_TEST_IN, DIRT_BIND_TEST_FIRST, DIRT_BIND_TEST_LAST) || \
    !DIRT_BIND_IN(DIRT_BIND_TEST_OUT, DIRT_BIND_TEST_FIRST, DIRT_BIND_TEST_LAST)
#error "common/constants.h: a test binding lies outside DIRT_BIND_TEST_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_WORK, DIRT_BIND_WORK_FIRST, DIRT_BIND_WORK_LAST)
#error "common/constants.h: the work binding lies outside DIRT_BIND_WORK_*"
#endif
#if !DIRT_BIND_IN(DIRT_BIND_SORT, DIRT_BIND_SORT_FIRST, DIRT_BIND_SORT_LAST)
#error "common/constants.h: the sort binding lies outside DIRT_BIND_SORT_*"
#endif

/* ---- Texture and image units ---- */

/* Raster preview: a material's base colour and emissive textures. */
#define DIRT_UNIT_PREVIEW_BASE_COLOR 0
#define DIRT_UNIT_PREVIEW_EMISSIVE 1
/* Direct visibility: the RGBA32UI visibility buffer read by the resolve. */
#define DIRT_UNIT_VISIBILITY 0
/* Frame-graph tests: the one sampled texture / storage image of a pass. */
#define DIRT_UNIT_TEST 0
/* image unit of the path tracer's display texture (glsl/integrator/display.comp) */
#define DIRT_UNIT_DISPLAY 0
/* The window's presentation (glsl/present/present.frag): the image, and the
 * second image of a split or a difference. */
#define DIRT_UNIT_PRESENT_A 0
#define DIRT_UNIT_PRESENT_B 1

/* ---- Split arrays (src/gl/split.h; doc/architecture.md, "Arrays past one
 * storage block") ----
 *
 * An array of records that may pass one storage block is stored as one
 * buffer read as a shader storage block while it fits (the shaders see the
 * DIRT_BIND_* block), else as up to DIRT_SPLIT_MAX_PARTS parts, each a
 * texel buffer: bound from DIRT_UNIT_SPLIT_<ARRAY> + part on (texture units,
 * arrays the CPU writes, read with texelFetch) or DIRT_IMAGE_SPLIT_<ARRAY> +
 * part (image units, arrays shaders write). Each array owns
 * DIRT_SPLIT_MAX_PARTS consecutive units; the ranges start above the fixed
 * units of this section and do not overlap. */
#define DIRT_SPLIT_MAX_PARTS 8
#define DIRT_UNIT_SPLIT_FIRST 4
#define DIRT_UNIT_SPLIT_VERTICES 4       /* dirt_gpu_vertex[3] per primitive: RGBA32F */
#define DIRT_UNIT_SPLIT_PRIM_MATERIAL 12 /* uint per primitive: R32UI */
#define DIRT_UNIT_SPLIT_TANGENTS 20      /* dirt_gpu_model_tangent per frame vertex: RGBA32F */
#define DIRT_UNIT_SPLIT_TEXELS 28        /* the model's texel table, a word each: R32UI */
#define DIRT_UNIT_SPLIT_LAST 35
#define DIRT_IMAGE_SPLIT_FIRST 1
#define DIRT_IMAGE_SPLIT_CANDIDATES 1    /* DIRT build candidates: RGBA32UI */
#define DIRT_IMAGE_SPLIT_NODES 9         /* DIRT id nodes: RG32UI */
#define DIRT_IMAGE_SPLIT_HEADS 17        /* DIRT list heads: R32UI */
#define DIRT_IMAGE_SPLIT_MMRT_HEADS 25   /* MMRT bucket heads: R32UI */
#define DIRT_IMAGE_SPLIT_MMRT_TAILS 33   /* MMRT bucket tails: R32UI */
#define DIRT_IMAGE_SPLIT_MMRT_IDS 41     /* MMRT id nodes (3 uints each): R32UI */
#define DIRT_IMAGE_SPLIT_MMRT_DATA 49    /* MMRT data nodes (2 texels each): RGBA32UI */
#define DIRT_IMAGE_SPLIT_DEPTH 57        /* depth bounds + pyramid (2 texels each): R32UI */
#define DIRT_IMAGE_SPLIT_LAST 64
/* The shaders' declarations and accessors of an array's parts are built
 * from glsl/common/split.glsl (DIRT_SPLIT_EACH and its helpers), included
 * here for the shaders only (GL_core_profile: every shader is #version 450
 * core) so that every shader has it whatever #if its arrays' includes sit
 * in (the shader assembler includes a file once). */
#ifdef GL_core_profile
#include "common/split.glsl"
#endif
#if DIRT_UNIT_SPLIT_FIRST <= DIRT_UNIT_PRESENT_B || \
    DIRT_UNIT_SPLIT_FIRST <= DIRT_UNIT_PREVIEW_EMISSIVE || \
    DIRT_UNIT_SPLIT_PRIM_MATERIAL != DIRT_UNIT_SPLIT_VERTICES + DIRT_SPLIT_MAX_PARTS || \
    DIRT_UNIT_SPLIT_TANGENTS != DIRT_UNIT_SPLIT_PRIM_MATERIAL + DIRT_SPLIT_MAX_PARTS || \
    DIRT_UNIT_SPLIT_TEXELS != DIRT_UNIT_SPLIT_TANGENTS + DIRT_SPLIT_MAX_PARTS || \
    DIRT_UNIT_SPLIT_LAST != DIRT_UNIT_SPLIT_TEXELS + DIRT_SPLIT_MAX_PARTS - 1 || \
    DIRT_UNIT_SPLIT_VERTICES != DIRT_UNIT_SPLIT_FIRST
#error "common/constants.h: the split arrays' texture unit ranges overlap"
#endif
#if DIRT_IMAGE_SPLIT_FIRST <= DIRT_UNIT_DISPLAY || \
    DIRT_IMAGE_SPLIT_CANDIDATES != DIRT_IMAGE_SPLIT_FIRST || \
    DIRT_IMAGE_SPLIT_NODES != DIRT_IMAGE_SPLIT_CANDIDATES + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_HEADS != DIRT_IMAGE_SPLIT_NODES + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_MMRT_HEADS != DIRT_IMAGE_SPLIT_HEADS + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_MMRT_TAILS != DIRT_IMAGE_SPLIT_MMRT_HEADS + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_MMRT_IDS != DIRT_IMAGE_SPLIT_MMRT_TAILS + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_MMRT_DATA != DIRT_IMAGE_SPLIT_MMRT_IDS + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_DEPTH != DIRT_IMAGE_SPLIT_MMRT_DATA + DIRT_SPLIT_MAX_PARTS || \
    DIRT_IMAGE_SPLIT_LAST != DIRT_IMAGE_SPLIT_DEPTH + DIRT_SPLIT_MAX_PARTS - 1
#error "common/constants.h: the split arrays' image unit ranges overlap"
#endif

/* ---- Uniform locations ----
 *
 * layout(location = DIRT_LOC_*) in the shader, glUniform*(DIRT_LOC_*, ...)
 * on the host. Locations are per program: the names of one program (one
 * block below) are distinct, names of different programs may share values. */

/* glsl/integrator/pt_common.glsl: raygen.comp, shade.comp (and its AO variant). */
#define DIRT_LOC_PT_PIXELS 0         /* uint: pixels of this chunk (wavefront) */
#define DIRT_LOC_PT_WIDTH 1          /* int */
#define DIRT_LOC_PT_HEIGHT 2         /* int */
#define DIRT_LOC_PT_SEED 3           /* uint */
#define DIRT_LOC_PT_SAMPLE 4         /* uint: sample index */
#define DIRT_LOC_PT_BOUNCE 5         /* uint k: the path event being shaded */
#define DIRT_LOC_PT_BOUNCES 6        /* uint K: scattering events allowed */
#define DIRT_LOC_PT_SLOT 7           /* uint: ring slot of G_k (k mod 3) */
/* location 8: free (was the background radiance; now the environment table) */
#define DIRT_LOC_PT_AO_DISTANCE 9    /* float */
#define DIRT_LOC_PT_PIXEL_OFFSET 10  /* uint: image pixel of the chunk's record 0 */
#define DIRT_LOC_PT_SURFACE_OFFSET 11 /* float: the tracer's surface_offset (views/tracer.h) */
/* glsl/integrator/resolve.comp */
#define DIRT_LOC_RESOLVE_PIXELS 0    /* uint: pixels of this chunk */
/* glsl/integrator/compact.comp, batch.comp */
#define DIRT_LOC_COMPACT_PIXELS 0    /* uint: pixels of this chunk (a batch's capacity) */
#define DIRT_LOC_COMPACT_EVENT 1     /* uint k: the path event whose survivors are gathered */
/* glsl/integrator/sort.comp (every pass) */
#define DIRT_LOC_SORT_RAYS 0         /* uint: the capacity of the batch being sorted */
#define DIRT_LOC_SORT_BOUNDS_MIN 1   /* vec3: the box the origin grid spans */
#define DIRT_LOC_SORT_BOUNDS_MAX 2   /* vec3 */
/* glsl/integrator/accumulate.comp */
#define DIRT_LOC_ACCUM_PIXELS 0      /* uint: pixels of this chunk */
/* glsl/integrator/display.comp */
#define DIRT_LOC_DISPLAY_PIXELS 0    /* uint: pixels of this chunk */
#define DIRT_LOC_DISPLAY_WIDTH 1     /* int: image width */
#define DIRT_LOC_DISPLAY_INV_SAMPLES 2 /* float: 1 / samples accumulated */
#define DIRT_LOC_DISPLAY_PIXEL_OFFSET 3 /* uint: image pixel of the chunk's record 0 */
/* glsl/integrator/test_model.comp */
#define DIRT_LOC_TEST_MODEL_MODE 0   /* int */
#define DIRT_LOC_TEST_MODEL_COUNT 1  /* uint */

/* glsl/dirt/trace.comp */
#define DIRT_LOC_TRACE_COUNT 0       /* uint: rays */
#define DIRT_LOC_TRACE_HIZ_TOP 1     /* int: highest level a march climbs to; < 0 = top */
#define DIRT_LOC_TRACE_ANY_HIT 2     /* int: 1 stops at the first accepted hit */
#define DIRT_LOC_TRACE_LINK 3        /* int: 1 links hits per ADS tile (raster Fetch) */
#define DIRT_LOC_TRACE_FROM_SURFACES 4 /* int: 1 the rays leave surfaces (march start: level 0) */
/* glsl/dirt/fill.comp (built with DIRT_NODE_DEPTHS) */
#define DIRT_LOC_FILL_NODE_DEPTHS 0  /* int: 1 stores the nodes' depth ranges */
/* glsl/views/hiz.comp */
#define DIRT_LOC_MIP_LEVEL 0         /* int: the level written */
/* glsl/dirt/visibility.vert */
#define DIRT_LOC_VISIBILITY_VIEW 0   /* int: the camera view */
/* glsl/dirt/visibility_resolve.comp */
#define DIRT_LOC_VIS_RESOLVE_VIEW 0  /* int: the camera view */

/* glsl/mmrt/trace.comp */
#define DIRT_LOC_MMRT_TRACE_COUNT 0      /* uint: rays */
#define DIRT_LOC_MMRT_TRACE_MARCH 1      /* int: 0 Hi-Z, 1 linear */
#define DIRT_LOC_MMRT_TRACE_SAMPLES 2    /* int: linear samples per view */
#define DIRT_LOC_MMRT_TRACE_TOP_LEVEL 3  /* int: Hi-Z highest level used */
#define DIRT_LOC_MMRT_TRACE_THICKNESS 4  /* float */
#define DIRT_LOC_MMRT_TRACE_SEED 5       /* uint */
#define DIRT_LOC_MMRT_TRACE_STATS 6      /* int: count pixels / nodes visited */
#define DIRT_LOC_MMRT_TRACE_ALL_VIEWS 7  /* int: every view over the whole segment */
#define DIRT_LOC_MMRT_TRACE_FIRST_RAY 8  /* uint: wavefront index of the batch's ray 0 */
/* glsl/mmrt/pt_rays.comp */
/* Both trace passes (glsl/dirt/trace.comp, glsl/mmrt/trace.comp) with the
 * alpha test of glsl/integrator/alpha.glsl (dirt_trace_alpha, core/ray.h). */
#define DIRT_LOC_ALPHA_ENABLED 16      /* int: 1 tests alpha-tested materials' hits */
#define DIRT_LOC_ALPHA_KEY 17          /* uvec4: seed, sample, bounce, dim of the rays' keys */
#define DIRT_LOC_ALPHA_FIRST_PIXEL 18  /* uint: pixel of the batch's ray 0 */
/* The tracers' passes over a ray batch (DIRT trace, compute Fetch and its
 * miss pass; MMRT trace, pt_rays, to_gpoint): glsl/common/ray_batch.glsl. */
#define DIRT_LOC_RAY_BATCH 19          /* int: 1 = count and owners from DIRT_BIND_RAY_BATCH */

#define DIRT_LOC_MMRT_PT_RAYS_COUNT 0    /* uint: rays */
/* glsl/mmrt/to_gpoint.comp */
#define DIRT_LOC_MMRT_TO_GPOINT_COUNT 0  /* uint: rays */
#define DIRT_LOC_MMRT_TO_GPOINT_SLOT 1   /* uint: ring slot written */

/* glsl/raster/preview.vert + preview.frag (one program) */
#define DIRT_LOC_PREVIEW_VIEW_PROJ 0   /* mat4 */
#define DIRT_LOC_PREVIEW_EYE 1         /* vec3 */
#define DIRT_LOC_PREVIEW_MATERIAL 2    /* int */
#define DIRT_LOC_PREVIEW_NUM_LIGHTS 3  /* int */
#define DIRT_LOC_PREVIEW_AMBIENT 4     /* float */
#define DIRT_LOC_PREVIEW_FORWARD 5     /* vec3: unit camera axis (the Z AOV) */

/* glsl/present/present.vert + present.frag (one program, src/gl/present.c) */
#define DIRT_LOC_PRESENT_RECT 0        /* ivec4: x, y (from the framebuffer's bottom), w, h */
#define DIRT_LOC_PRESENT_MODE 1        /* int: DIRT_PRESENT_ID_* (common/display.h) */
#define DIRT_LOC_PRESENT_SCALE 2       /* float: 2^exposure */
#define DIRT_LOC_PRESENT_TONEMAP 3     /* int: DIRT_TONEMAP_ID_* */
#define DIRT_LOC_PRESENT_CHANNEL 4     /* int: the heat's channel */
#define DIRT_LOC_PRESENT_RANGE 5       /* vec2: lo, hi */
#define DIRT_LOC_PRESENT_SPLIT 6       /* float: window x of the split, < 0 for none */
#define DIRT_LOC_PRESENT_SPLIT_LINE 7  /* int: 1 draws the split's white column */

/* glsl/test/rng.comp */
#define DIRT_LOC_TEST_RNG_COUNT 0      /* uint */
#define DIRT_LOC_TEST_RNG_SEED 1       /* uint */
/* glsl/graph_test/fill.comp */
#define DIRT_LOC_TEST_FILL_COUNT 0     /* uint */
#define DIRT_LOC_TEST_FILL_SEED 1      /* uint */
/* glsl/graph_test/to_image.comp */
#define DIRT_LOC_TEST_TO_IMAGE_SIZE 0  /* ivec2 */
/* glsl/graph_test/splat.frag */
#define DIRT_LOC_TEST_SPLAT_ADD 0      /* uint */
/* glsl/test/uniform_switch.comp */
#define DIRT_LOC_TEST_SWITCH_BATCH 0   /* int */
#define DIRT_LOC_TEST_SWITCH_COUNT 1   /* uint */
#define DIRT_LOC_TEST_SWITCH_SLOT 2    /* uint */

#endif
