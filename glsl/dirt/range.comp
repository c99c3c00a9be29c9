#version 450 core
// DIRT compute build, depth bounds pass (the raster build's depth pass as
// compute): DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK work records per group (the
// records dirt/tiles.comp wrote in the node pool; launched indirectly
// from counters.dispatch, rows of DIRT_GROUPS_ROW groups), DIRT_BUILD_CHUNK
// lanes per record. Lane l of record k of a footprint (dirt/footprint.glsl)
// takes its tiles k q C + l + j C, j < q (C = DIRT_BUILD_CHUNK, q =
// dirt_build_chunks), and does for each what the raster build's fragment
// stage does for its fragment, with the same functions and the same inputs
// (the near/far-clipped polygon of dirt_clip_near_far, dirt_range_tile; with
// DIRT_CLIP_SH the triangle and dirt_clip_tile), so the ranges are the same
// floats: drops tiles it misses, min/maxes the range into the tile's depth
// bounds and appends the candidate (common/layout.h) at counters.fill.y;
// past the capacity counted, not written. DIRT_SUB_TILES: the candidate's
// primitive word carries its sub-tile rectangle (dirt_subtile_rect).
#include "common/layout.h"
#include "dirt/clip.glsl"
#include "dirt/footprint.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#include "common/depth.glsl"
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
// Candidates [0, params.cand.x); the work records in the node pool.
#define DIRT_CANDIDATES_WRITEONLY
#define DIRT_NODES_READONLY
#include "dirt/structure.glsl"

void main()
{
    const uint per_group = uint(DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK);
    uint rec = (gl_WorkGroupID.y * uint(DIRT_GROUPS_ROW) + gl_WorkGroupID.x) * per_group +
               gl_LocalInvocationID.x / uint(DIRT_BUILD_CHUNK);
    uint lane = gl_LocalInvocationID.x % uint(DIRT_BUILD_CHUNK);
    if (rec >= min(counters.build.y, params.cand.y))
        return;
    uvec4 w = dirt_work_record(rec);
    uint prim = w.x;
    int view = int(w.y & 7u);
    uint k = w.y >> 3;
    ivec2 t0 = ivec2(int(w.z & 0xFFFFu), int(w.z >> 16));
    uint nx = w.w & 0xFFFFu, n = nx * (w.w >> 16);
    uint q = dirt_build_chunks(n);

    dirt_gpu_view v = views[view];
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 c[3];
    for (int i = 0; i < 3; i++)
        c[i] = vp * vec4(dirt_vertex_pos_at(3u * prim + uint(i)), 1.0);
    vec4 poly[5];
    int poly_n;
#ifdef DIRT_CLIP_SH
    poly = vec4[5](c[0], c[1], c[2], c[2], c[2]);
    poly_n = 3;
#else
    dirt_clip_near_far(c, float(DIRT_CLIP_EPS), poly, poly_n);
#endif
    int S = params.config.y;
    uint first = k * q * uint(DIRT_BUILD_CHUNK) + lane;
    uint end = min((k + 1u) * q * uint(DIRT_BUILD_CHUNK), n);
    for (uint e = first; e < end; e += uint(DIRT_BUILD_CHUNK)) {
        ivec2 tile = t0 + ivec2(int(e % nx), int(e / nx));
        float zmin, zmax;
#ifdef DIRT_CLIP_SH
        if (!dirt_clip_tile(v, S, tile, poly[0], poly[1], poly[2], float(DIRT_CLIP_EPS), zmin,
                            zmax))
            continue;
#else
        if (!dirt_range_tile(v, S, tile, poly[0], poly[1], poly[2], poly[3], poly[4], poly_n,
                             float(DIRT_CLIP_EPS), zmin, zmax))
            continue;
#endif
        uint t = uint(v.placement.x + tile.y * v.size.z + tile.x);
        uint word = prim;
#ifdef DIRT_SUB_TILES
        word |= dirt_subtile_rect(v, S, tile) << DIRT_SUBTILE_SHIFT;
#endif
        dirt_depth_min(t, floatBitsToUint(zmin));
        dirt_depth_max(t, floatBitsToUint(zmax));
        uint i = atomicAdd(counters.fill.y, 1u);
        if (i < params.cand.x)
            dirt_candidate_store(i, uvec4(word, t, floatBitsToUint(zmin), floatBitsToUint(zmax)));
    }
}
