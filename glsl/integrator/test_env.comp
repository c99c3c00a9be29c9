#version 450 core
// Test shader of test/gpu/test_glsl_env.c: runs the environment functions of
// integrator/model.glsl on every input record, so the test can compare them
// with the C model (src/integrator/env.c). Record i reads in_data[2i] and
// writes out_data[3i .. 3i+2]. With TEST_FAULT defined every result r
// becomes 1.001 r + 0.01 (the test proves its comparison catches that).
#define DIRT_MODEL_BUFFERS 1
#include "integrator/model.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer TestIn { vec4 in_data[]; };
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer TestOut { vec4 out_data[]; };

layout(location = DIRT_LOC_TEST_MODEL_MODE) uniform int u_mode;
layout(location = DIRT_LOC_TEST_MODEL_COUNT) uniform uint u_count;

#define MODE_LOOKUP 0 // in0 direction -> o0 (column, row, pdf), o1 radiance
#define MODE_SAMPLE 1 // in0 (u_sel, u1, u2) -> o0 (ok, pdf), o1 direction, o2 radiance

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
    vec4 a = in_data[2u * i];
    vec4 o0 = vec4(0.0), o1 = vec4(0.0), o2 = vec4(0.0);
    if (u_mode == MODE_LOOKUP) {
        ivec2 t = dirt_env_texel_g(a.xyz);
        o0 = vec4(float(t.x), float(t.y), dirt_env_pdf_g(a.xyz), 0.0);
        o1 = vec4(dirt_env_eval_g(a.xyz), 0.0);
    } else {
        vec3 d, rad;
        float pdf;
        bool ok = dirt_env_sample_g(a.x, a.y, a.z, d, pdf, rad);
        o0 = vec4(ok ? 1.0 : 0.0, pdf, 0.0, 0.0);
        o1 = vec4(d, 0.0);
        o2 = vec4(rad, 0.0);
    }
    out_data[3u * i] = fault(o0);
    out_data[3u * i + 1u] = fault(o1);
    out_data[3u * i + 2u] = fault(o2);
}
