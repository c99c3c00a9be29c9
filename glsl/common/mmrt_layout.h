/* MMRT (the fragment-based multiview, multilayer A-buffer baseline of
 * Vardis, Vasilakis, Papaioannou, I3D 2016): data layouts shared by C
 * (src/mmrt/) and GLSL (glsl/mmrt/). Same rules as common/layout.h: valid
 * C11 and GLSL 4.50, structs of DIRT_V4/DIRT_IV4/DIRT_UV4 members and
 * #defines only; test/common/layout_check.c checks sizes and offsets.
 *
 * MMRT reuses from common/layout.h: dirt_gpu_vertex (DIRT_BIND_VERTICES),
 * dirt_gpu_view (DIRT_BIND_VIEWS), the depth bounds + Hi-Z pyramid layout
 * (DIRT_BIND_DEPTH, uvec2 float bits of (zmin, zmax) per pixel, cleared to
 * DIRT_DEPTH_CLEAR_MIN/MAX), dirt_gpu_ray (DIRT_BIND_RAYS) and dirt_gpu_hit
 * (DIRT_BIND_HITS). Its views are DIRT's with tile size 1: a "tile" is a
 * pixel, and global pixel g of view v is v.tile_base + y * width + x. */
#ifndef DIRT_COMMON_MMRT_LAYOUT_H
#define DIRT_COMMON_MMRT_LAYOUT_H

#include "common/layout.h"

/* The MMRT passes bind their buffers at DIRT_BIND_MMRT_* (the MMRT range of
 * common/constants.h) and the per-primitive materials at the shared
 * DIRT_BIND_PRIM_MATERIAL. */

/* An id node is DIRT_MMRT_ID_UINTS consecutive uints
 * (DIRT_MMRT_ID_NODE_BYTES, the MMRT paper's 12 bytes; common/constants.h): [0] float bits of the fragment's eye-space depth z (> 0),
 * [1] next node (farther; DIRT_LIST_END ends the list), [2] prev node
 * (nearer; set by the reorder pass). Node i's shading data is data node i. */
#define DIRT_MMRT_ID_Z 0
#define DIRT_MMRT_ID_NEXT 1
#define DIRT_MMRT_ID_PREV 2

/* Lists of up to this many nodes are sorted in registers in one go; longer
 * ones are sorted in chunks of this size merged into the sorted list (all
 * nodes kept). 8 keeps the arrays in registers (llvmpipe lowers indexed
 * local arrays to select chains: 32 was 7x slower there). */
#define DIRT_MMRT_SORT_CHUNK 8

/* Build parameters (32 bytes). */
struct dirt_mmrt_gpu_params {
    DIRT_IV4 config;     /* views, buckets B, pixels (all views), atlas width */
    DIRT_UV4 pool;       /* node capacity, pyramid entries, atlas height, 0 */
};

/* One data node (32 bytes): the shading attributes of a fragment, sampled
 * at its pixel centre. The position is (1 - u - v) p0 + u p1 + v p2 of the
 * primitive's vertices (vertex buffer). */
struct dirt_mmrt_gpu_data {
    DIRT_UV4 ids;        /* x primitive id, y material index, z shading normal
                            (octahedral, packSnorm2x16), w global pixel */
    DIRT_V4 attr;        /* x u, y v (perspective-correct barycentrics of
                            vertices 1 and 2), zw texture uv */
};

/* Counters (48 bytes). `build` is cleared by every build; `trace` and
 * `trace2` by every trace. */
struct dirt_mmrt_gpu_counters {
    DIRT_UV4 build;      /* x fragments requested (node counter), y most
                            fragments in one pixel, z bucket lists longer than
                            DIRT_MMRT_SORT_CHUNK, w pixels with a fragment */
    DIRT_UV4 trace;      /* x rays that hit, y march steps (Hi-Z cells at any
                            level, linear samples), z id nodes visited, w rays
                            that ran out of march steps */
    DIRT_UV4 trace2;     /* x pixel tests (incl. early skips), yzw 0 */
};

#endif
