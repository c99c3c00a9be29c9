#version 450 core
// DIRT compute build, candidate tiles pass: one invocation per (primitive,
// view), view-major (invocation i is primitive i mod P of view i / P; P =
// params.cand.z primitives), launched as rows of DIRT_GROUPS_ROW groups.
// The footprint of the raster build's geometry stage (dirt/footprint.glsl:
// the same reject, near/far clip and candidate tiles), cut into work records
// of DIRT_BUILD_CHUNK tiles each (common/layout.h), appended at
// counters.build.y, in the node pool (dirt_work_record_store); records past
// the capacity (params.cand.y) are counted, not written (the host grows the
// pool and runs the build again). Also
// adds the tiles to counters.build.x (an upper bound of the candidates: it
// sizes their buffer) and raises counters.dispatch to the groups of the
// range pass (dirt/range.comp) that cover every record written. The large
// primitives (dirt/large.glsl) get no records: they are in no list.
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
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
#include "dirt/large.glsl"
#define DIRT_CANDIDATES_NONE
#define DIRT_NODES_WRITEONLY
#include "dirt/structure.glsl"

void main()
{
    uint i = (gl_WorkGroupID.y * uint(DIRT_GROUPS_ROW) + gl_WorkGroupID.x) * uint(DIRT_GROUP_SIZE) +
             gl_LocalInvocationID.x;
    uint P = params.cand.z;
    if (i >= P * uint(params.config.x))
        return;
    int view = int(i / P);
    uint prim = i - uint(view) * P;
    if (dirt_is_large(prim))
        return;
    dirt_gpu_view v = views[view];
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 c[3];
    for (int k = 0; k < 3; k++)
        c[k] = vp * vec4(dirt_vertex_pos_at(3u * prim + uint(k)), 1.0);
    vec2 lo, hi;
    bool crosses_near;
    if (!dirt_footprint(v, params.config.y, c, lo, hi, crosses_near))
        return;
#ifndef DIRT_CLIP_SH
    // Nothing between the near and far planes: no candidate (as the
    // geometry stage drops it).
    vec4 poly[5];
    int poly_n;
    dirt_clip_near_far(c, float(DIRT_CLIP_EPS), poly, poly_n);
    if (poly_n < 3)
        return;
#endif
    ivec4 r = dirt_footprint_tiles(lo, hi);
    uint n = uint(r.z) * uint(r.w);
    if (n == 0u)
        return;
    // Records of q chunks each (q = 1 unless the footprint needs more than
    // DIRT_BUILD_MAX_RECORDS records of one chunk): dirt_build_chunks.
    uint q = dirt_build_chunks(n);
    uint R = (n + q * uint(DIRT_BUILD_CHUNK) - 1u) / (q * uint(DIRT_BUILD_CHUNK));
    atomicAdd(counters.build.x, n);
    uint r0 = atomicAdd(counters.build.y, R);
    uint cap = params.cand.y;
    for (uint k = 0u; k < R && r0 + k < cap; k++)
        dirt_work_record_store(r0 + k, uvec4(prim, uint(view) | (k << 3),
                                             uint(r.x) | (uint(r.y) << 16),
                                             uint(r.z) | (uint(r.w) << 16)));
    // The range pass's groups: DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK records
    // each, in rows of DIRT_GROUPS_ROW; enough for the last record written.
    uint last = min(r0 + R, cap);
    if (last > r0) {
        uint groups = (last + uint(DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK) - 1u) /
                      uint(DIRT_GROUP_SIZE / DIRT_BUILD_CHUNK);
        atomicMax(counters.dispatch.x, min(groups, uint(DIRT_GROUPS_ROW)));
        atomicMax(counters.dispatch.y, (groups + uint(DIRT_GROUPS_ROW) - 1u) /
                                           uint(DIRT_GROUPS_ROW));
        atomicMax(counters.dispatch.z, 1u);
    }
}
