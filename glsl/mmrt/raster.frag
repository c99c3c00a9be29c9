#version 450 core
// MMRT depth bounds and store passes, fragment stage: one invocation per
// (view, pixel, triangle) whose pixel centre the triangle covers.
//  MMRT_PASS_DEPTH: atomic min/max of the fragment's eye-space depth into
//                   the pixel's depth bounds (pyramid level 0).
//  MMRT_PASS_STORE: one id node {z, next, prev} and one data node per
//                   fragment, from a single atomic counter, pushed on the
//                   list of its bucket (uniform in linear depth between the
//                   pixel's bounds). Nodes past the pool's capacity are
//                   counted, not written, and their heads are not touched, so
//                   the host can grow the pools and run the pass again.
// Both passes compute the depth with the same code from the same varyings,
// so a stored fragment's depth lies inside its pixel's bounds bit for bit.
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "mmrt/abuffer.glsl"

layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
// (one include: a second would be dropped, whichever branch it is in)
#ifndef MMRT_PASS_DEPTH
#define DIRT_DEPTH_READONLY
#endif
#include "common/depth.glsl"
#ifndef MMRT_PASS_DEPTH
layout(std430, binding = DIRT_BIND_MMRT_PARAMS) readonly buffer Params {
    dirt_mmrt_gpu_params params;
};
#define MMRT_IDS_WRITEONLY
#define MMRT_DATA_WRITEONLY
#define MMRT_TAILS_WRITEONLY
#include "mmrt/arrays.glsl"
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) buffer Counters {
    dirt_mmrt_gpu_counters counters;
};
#endif

layout(location = 0) in float g_depth;
layout(location = 1) flat in int g_view;
#ifdef MMRT_PASS_STORE
layout(location = 2) in vec2 g_bary;
layout(location = 3) in vec3 g_normal;
layout(location = 4) in vec2 g_uv;
layout(location = 5) flat in uint g_prim;
layout(location = 6) flat in uint g_material;
#endif

void main()
{
    dirt_gpu_view v = views[g_view];
    ivec2 px = ivec2(gl_FragCoord.xy) - ivec2(v.placement.y, 0);
    if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, v.size.xy)))
        return;
    uint g = uint(v.placement.x + px.y * v.size.x + px.x);
    float z = g_depth;
#ifdef MMRT_PASS_DEPTH
    dirt_depth_min(g, floatBitsToUint(z));
    dirt_depth_max(g, floatBitsToUint(z));
#else
    float zmin = uintBitsToFloat(dirt_depth(g).x);
    float zmax = uintBitsToFloat(dirt_depth(g).y);
    int B = params.config.y;
    int b = mmrt_bucket(z, zmin, zmax - zmin, B);
    uint node = atomicAdd(counters.build.x, 1u);
    if (node >= params.pool.x)
        return;
    uint pixels = uint(params.config.z);
    mmrt_id_store(node, uint(DIRT_MMRT_ID_Z), floatBitsToUint(z));
    mmrt_id_store(node, uint(DIRT_MMRT_ID_PREV), DIRT_LIST_END);
    mmrt_id_store(node, uint(DIRT_MMRT_ID_NEXT), mmrt_head_exchange(uint(b) * pixels + g, node));
    dirt_mmrt_gpu_data d;
    d.ids = uvec4(g_prim, g_material, mmrt_pack_normal(g_normal), g);
    d.attr = vec4(g_bary, g_uv);
    mmrt_data_store(node, d);
#endif
}
