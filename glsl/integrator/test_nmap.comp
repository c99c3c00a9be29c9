#version 450 core
// Test shader of test/gpu/test_glsl_nmap.c: runs the texture-transform and
// normal-map functions of integrator/model.glsl on every input record, so
// the test can compare them with the C model (src/integrator/texture.c).
// Record i reads in_data[3i .. 3i+2] and writes out_data[2i .. 2i+1]. With
// TEST_FAULT defined every result r becomes 1.001 r + 0.01 (the test proves
// its comparison catches that).
#define DIRT_MODEL_BUFFERS 1
#include "integrator/model.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer TestIn { vec4 in_data[]; };
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer TestOut { vec4 out_data[]; };

layout(location = DIRT_LOC_TEST_MODEL_MODE) uniform int u_mode;
layout(location = DIRT_LOC_TEST_MODEL_COUNT) uniform uint u_count;

#define MODE_SLOT_UV 0   // in0 (material, slot, u, v) -> o0.xy the slot's uv
#define MODE_NORMAL_TS 1 // in0 (material, -, u, v) -> o0 (ok, n_ts)
#define MODE_APPLY 2     // in0 n, in1 (t, w), in2 n_ts -> o0 the shading normal
#define MODE_SURFACE 3   // in0 (material, -, u, v) -> o0 (base, metallic), o1 (alpha, emission)

vec4 fault(vec4 r)
{
#ifdef TEST_FAULT
    return r * 1.001 + 0.01;
#else
    return r;
#endif
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count)
        return;
    vec4 a = in_data[3u * i], b = in_data[3u * i + 1u], c = in_data[3u * i + 2u];
    vec4 o0 = vec4(0.0), o1 = vec4(0.0);
    uint mat = uint(a.x);
    if (u_mode == MODE_SLOT_UV) {
        o0 = vec4(dirt_slot_uv_g(dirt_model_materials[mat], int(a.y), a.zw), 0.0, 0.0);
    } else if (u_mode == MODE_NORMAL_TS) {
        vec3 n;
        bool ok = dirt_material_normal_ts_g(mat, a.zw, n);
        o0 = vec4(ok ? 1.0 : 0.0, ok ? n : vec3(0.0));
    } else if (u_mode == MODE_APPLY) {
        o0 = vec4(dirt_normal_map_apply_g(a.xyz, b.xyz, b.w, c.xyz), 0.0);
    } else {
        dirt_surface_g s = dirt_material_surface_g(mat, a.zw);
        o0 = vec4(s.bsdf.base_color, s.bsdf.metallic);
        o1 = vec4(s.bsdf.alpha, s.emission);
    }
    out_data[2u * i] = fault(o0);
    out_data[2u * i + 1u] = fault(o1);
}
