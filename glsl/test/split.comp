#version 450 core
// Test shader (test/gpu/test_split.c): every accessor of every split array
// (src/gl/split.h), in whatever layout the defines give. in_data[0] = (op,
// records per invocation range: n), in_data[1] = (vertices, prim materials,
// DIRT candidates, DIRT nodes), in_data[2] = (DIRT heads, MMRT heads and
// tails, MMRT nodes, depth entries): the record counts. op 0 writes record i
// of the arrays shaders write with the values below (through every store,
// store_zw, exchange, min and max); op 1 reads record i of every array into
// out_data[9 i .. 9 i + 8] (zero past an array's count).
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "common/vertices.glsl"
#include "common/depth.glsl"
#include "dirt/structure.glsl"
#include "mmrt/arrays.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer TestIn { uvec4 in_data[]; };
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer TestOut { uvec4 out_data[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    uint op = in_data[0].x;
    uvec4 n0 = in_data[1], n1 = in_data[2];
    if (op == 0u) {
        if (i < n0.z) {
            dirt_candidate_store(i, uvec4(i, 3u * i, 5u * i, 7u * i));
            dirt_candidate_store_zw(i, uvec2(i + 11u, i + 13u));
        }
        if (i < n0.w)
            dirt_node_store(i, uvec2(i, ~i));
        if (i < n1.x)
            out_data[i] = uvec4(dirt_head_exchange(i, i ^ 0x55u));
        if (i < n1.y) {
            mmrt_head_store(i, i + 1u);
            uint old = mmrt_head_exchange(i, i + 2u);
            mmrt_tail_store(i, old + 100u);
        }
        if (i < n1.z) {
            mmrt_id_store(i, uint(DIRT_MMRT_ID_Z), i * 2u);
            mmrt_id_store(i, uint(DIRT_MMRT_ID_NEXT), i * 2u + 1u);
            mmrt_id_store(i, uint(DIRT_MMRT_ID_PREV), ~i);
            dirt_mmrt_gpu_data d;
            d.ids = uvec4(i, i + 1u, i + 2u, i + 3u);
            d.attr = vec4(float(i) * 0.5, -float(i), 1.0 / float(i + 1u), 3.0);
            mmrt_data_store(i, d);
        }
        if (i < n1.w) {
            dirt_depth_store(i, uvec2(1000u + i, 2000u + i));
            dirt_depth_min(i, 1000u + i / 2u);
            dirt_depth_max(i, 1000u + i * 2u);
        }
        return;
    }
    uvec4 z = uvec4(0u);
    uint o = 9u * i;
    out_data[o] = i < n0.x ? floatBitsToUint(dirt_vertex_at(3u * i + 2u).position) : z;
    out_data[o + 1u] = i < n0.x ? floatBitsToUint(dirt_vertex_at(3u * i).normal) : z;
    out_data[o + 2u] = uvec4(i < n0.x ? floatBitsToUint(dirt_vertex_pos_at(3u * i + 1u))
                                      : uvec3(0u),
                             i < n0.y ? dirt_prim_material(i) : 0u);
    out_data[o + 3u] = i < n0.z ? dirt_candidate(i) : z;
    out_data[o + 4u] = uvec4(i < n0.w ? dirt_node(i) : uvec2(0u), i < n1.x ? dirt_head(i) : 0u,
                             i < n1.w ? dirt_depth(i).x : 0u);
    out_data[o + 5u] = i < n1.y ? uvec4(mmrt_head(i), mmrt_tail(i),
                                        i < n1.w ? dirt_depth(i).y : 0u, 0u) : z;
    out_data[o + 6u] = i < n1.z ? uvec4(mmrt_id(i, uint(DIRT_MMRT_ID_Z)),
                                        mmrt_id(i, uint(DIRT_MMRT_ID_NEXT)),
                                        mmrt_id(i, uint(DIRT_MMRT_ID_PREV)), mmrt_data_prim(i))
                                  : z;
    out_data[o + 7u] = i < n1.z ? mmrt_data(i).ids : z;
    out_data[o + 8u] = i < n1.z ? floatBitsToUint(mmrt_data(i).attr) : z;
}
