#version 450 core
// DIRT build passes, fragment stage: one invocation per (primitive, view,
// tile) candidate.
//  DIRT_PASS_DEPTH: computes the exact depth range of the triangle inside
//                   the tile frustum (dirt/clip.glsl; DIRT_CLIP_SH: the
//                   plain clip), drops tiles it misses, min/maxes the range
//                   into the tile's depth bounds (pyramid level 0) and
//                   appends the candidate (common/layout.h) for the count
//                   and fill passes (dirt/count.comp, dirt/fill.comp), which
//                   so never compute a range again. Candidates past the
//                   buffer's capacity are counted, not written: the host
//                   grows the buffer and runs the pass again.
//                   DIRT_SUB_TILES: the candidate's primitive word carries
//                   its sub-tile rectangle (dirt_subtile_rect,
//                   common/layout.h).
//  DIRT_PASS_BOUND: nothing (the geometry stage counts).
//  DIRT_PASS_FETCH: the paper's raster Fetch: tiles with no hit record are
//                   masked out; otherwise every record of the tile's hit list
//                   whose primitive is this one is fetched into G_{k+1} of
//                   its owner (no clip needed: the record's tile is one this
//                   primitive's conservative raster covers).
#include "common/layout.h"
#include "dirt/clip.glsl"

layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#ifdef DIRT_PASS_FETCH
#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_HITS) readonly buffer Hits {
    dirt_gpu_hit hits[];
};
layout(std430, binding = DIRT_BIND_GPOINTS) writeonly buffer GPoints {
    dirt_gpu_gpoint gpoints[];
};
layout(std430, binding = DIRT_BIND_FETCH_PARAMS) readonly buffer FetchParams {
    dirt_gpu_fetch_params fetch;
};
layout(std430, binding = DIRT_BIND_HIT_HEADS) readonly buffer HitHeads {
    uint hit_heads[];
};
#include "dirt/fetch_common.glsl"
#endif
#ifdef DIRT_PASS_DEPTH
#include "common/depth.glsl"
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
#define DIRT_CANDIDATES_WRITEONLY
#include "dirt/structure.glsl"
#endif

layout(location = 0) flat in vec4 g_p0;
layout(location = 1) flat in vec4 g_p1;
layout(location = 2) flat in vec4 g_p2;
layout(location = 3) flat in vec4 g_p3;
layout(location = 4) flat in vec4 g_p4;
layout(location = 5) flat in uint g_prim;
layout(location = 6) flat in int g_view;
layout(location = 7) flat in int g_n;

void main()
{
#ifndef DIRT_PASS_BOUND
    dirt_gpu_view v = views[g_view];
    ivec2 tile = ivec2(gl_FragCoord.xy) - ivec2(v.placement.y, 0);
    if (any(lessThan(tile, ivec2(0))) || any(greaterThanEqual(tile, v.size.zw)))
        return;
#ifdef DIRT_PASS_FETCH
    uint gt = uint(v.placement.x + tile.y * v.size.z + tile.x);
    for (uint r = hit_heads[gt]; r != DIRT_LIST_END; r = hits[r].ids.w) {
        if (hits[r].ids.x == g_prim && hits[r].ids.y == uint(g_view))
            dirt_fetch_record(r);
    }
#elif defined(DIRT_PASS_DEPTH)
    int S = params.config.y;
    float zmin, zmax;
#ifdef DIRT_CLIP_SH
    if (!dirt_clip_tile(v, S, tile, g_p0, g_p1, g_p2, float(DIRT_CLIP_EPS), zmin, zmax))
        return;
#else
    if (!dirt_range_tile(v, S, tile, g_p0, g_p1, g_p2, g_p3, g_p4, g_n, float(DIRT_CLIP_EPS),
                         zmin, zmax))
        return;
#endif
    uint t = uint(v.placement.x + tile.y * v.size.z + tile.x);
    uint word = g_prim;
#ifdef DIRT_SUB_TILES
    word |= dirt_subtile_rect(v, S, tile) << DIRT_SUBTILE_SHIFT;
#endif
    dirt_depth_min(t, floatBitsToUint(zmin));
    dirt_depth_max(t, floatBitsToUint(zmax));
    uint i = atomicAdd(counters.fill.y, 1u);
    if (i < params.cand.x)
        dirt_candidate_store(i, uvec4(word, t, floatBitsToUint(zmin), floatBitsToUint(zmax)));
#endif
#endif
}
