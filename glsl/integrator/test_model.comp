#version 450 core
// Test shader of test/gpu/test_glsl_model.c: runs one function group of
// integrator/model.glsl on every input record and writes its results, so the
// test can compare them with the C model (src/integrator/).
//
// Record i reads in_data[8i .. 8i+7] and writes out_data[8i .. 8i+7]; the
// meaning of the slots per mode is listed below (booleans as 0/1, indices as
// exact floats) and mirrored in the test. With TEST_FAULT defined every
// result r becomes 1.001 r + 0.01 (the test proves its comparison catches
// that).
#define DIRT_MODEL_BUFFERS 1
#include "integrator/model.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer TestIn { vec4 in_data[]; };
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer TestOut { vec4 out_data[]; };

layout(location = DIRT_LOC_TEST_MODEL_MODE) uniform int u_mode;
layout(location = DIRT_LOC_TEST_MODEL_COUNT) uniform uint u_count;

#define TEST_STRIDE 8u

#define MODE_WARPS 0    // in0 (u1, u2)            -> o0 cosine dir, o1 (tri b1, b2, disk x, y)
#define MODE_VNDF 1     // in0 (alpha, u1, u2), in1 wo -> o0 h
#define MODE_ONB 2      // in0 n                  -> o0 t, o1 b
#define MODE_EVAL 3     // in0 (base, metallic), in1 (alpha, specular), in2 wo, in3 wi
                        // -> o0 f, o1 (pdf, p_spec, D(h), G2), o2 (F(wo.z), F_d(wo.z)),
                        //    o3 (lambda(wo), lambda(wi), delta)
#define MODE_SAMPLE 4   // in0, in1 as EVAL, in2 wo, in3 (u_lobe, u1, u2)
                        // -> o0 (ok, delta, lobe, pdf), o1 wi, o2 weight
#define MODE_MISC 5     // in0 (a, b, c), in1 beta -> o0 (mis(a, b), rr(beta), srgb(c))
#define MODE_LIGHT 6    // in0..3 light record, in4 p -> o0 (ok, dist), o1 wi, o2 li
#define MODE_AREA 7     // in0 (u) -> o0 (index)
#define MODE_MATERIAL 8 // in0 (material, u, v) -> o0 (base, metallic),
                        //    o1 (alpha, specular, double_sided, emissive), o2 emission
#define MODE_CAMERA 9   // in0..4 camera record, in5 (width, height, px, py),
                        // in6 (lens_u, lens_v) -> o0 org, o1 dir
#define MODE_TEXTURE 10 // in0 (texture, srgb, u, v) -> o0 rgba
#define MODE_TRANS 11   // in0, in1 as EVAL (in1 (alpha, specular, transmission, eta),
                        // in4 f0), in2 wo, in3 (c) -> o0 (p_trans, F_t(c), transmits,
                        //    transmission delta), o1 (p_spec)

dirt_bsdf_g read_bsdf(uint b)
{
    dirt_bsdf_g r;
    r.base_color = in_data[b].xyz;
    r.metallic = in_data[b].w;
    r.alpha = in_data[b + 1u].x;
    r.specular = in_data[b + 1u].y;
    r.transmission = in_data[b + 1u].z;
    r.eta = in_data[b + 1u].w;
    r.f0 = in_data[b + 4u].xyz;
    return r;
}

float flag(bool b) { return b ? 1.0 : 0.0; }

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count)
        return;
    uint b = i * TEST_STRIDE;
    vec4 o[8];
    for (int k = 0; k < 8; k++)
        o[k] = vec4(0.0);

    if (u_mode == MODE_WARPS) {
        vec4 a = in_data[b];
        o[0].xyz = dirt_sample_cosine_g(a.x, a.y);
        dirt_sample_triangle_g(a.x, a.y, o[1].x, o[1].y);
        dirt_sample_disk_g(a.x, a.y, o[1].z, o[1].w);
    } else if (u_mode == MODE_VNDF) {
        vec4 a = in_data[b];
        o[0].xyz = dirt_sample_ggx_vndf_g(a.x, in_data[b + 1u].xyz, a.y, a.z);
    } else if (u_mode == MODE_ONB) {
        vec3 t, bb;
        dirt_onb_g(in_data[b].xyz, t, bb);
        o[0].xyz = t;
        o[1].xyz = bb;
    } else if (u_mode == MODE_EVAL) {
        dirt_bsdf_g bs = read_bsdf(b);
        vec3 wo = in_data[b + 2u].xyz, wi = in_data[b + 3u].xyz;
        o[0].xyz = dirt_bsdf_eval_g(bs, wo, wi);
        o[1].x = dirt_bsdf_pdf_g(bs, wo, wi);
        o[1].y = dirt_bsdf_spec_probability_g(bs, wo);
        o[1].z = dirt_ggx_d_g(bs.alpha, dirt_normalize_g(wo + wi));
        o[1].w = dirt_ggx_g2_g(bs.alpha, wo, wi);
        o[2].xyz = dirt_bsdf_fresnel_g(bs, wo.z);
        o[2].w = dirt_bsdf_fresnel_dielectric_g(bs, wo.z);
        o[3].x = dirt_ggx_lambda_g(bs.alpha, wo);
        o[3].y = dirt_ggx_lambda_g(bs.alpha, wi);
        o[3].z = flag(dirt_bsdf_is_delta_g(bs));
    } else if (u_mode == MODE_SAMPLE) {
        dirt_bsdf_g bs = read_bsdf(b);
        vec3 wo = in_data[b + 2u].xyz;
        vec4 u = in_data[b + 3u];
        vec3 wi, weight;
        float pdf;
        bool delta;
        bool ok = dirt_bsdf_sample_dir_g(bs, wo, u.x, u.y, u.z, wi, weight, pdf, delta);
        o[0] = vec4(flag(ok), flag(delta), flag(u.x < dirt_bsdf_spec_probability_g(bs, wo)), pdf);
        o[1].xyz = wi;
        o[2].xyz = weight;
    } else if (u_mode == MODE_MISC) {
        vec4 a = in_data[b];
        o[0].x = dirt_mis_power_g(a.x, a.y);
        o[0].y = dirt_rr_survival_g(in_data[b + 1u].xyz);
        o[0].z = dirt_srgb_to_linear_g(a.z);
    } else if (u_mode == MODE_LIGHT) {
        dirt_gpu_model_light l;
        l.position = in_data[b];
        l.direction = in_data[b + 1u];
        l.color = in_data[b + 2u];
        l.cone = in_data[b + 3u];
        vec3 wi, li;
        float dist;
        bool ok = dirt_punctual_light_g(l, in_data[b + 4u].xyz, wi, dist, li);
        o[0].x = flag(ok);
        o[0].y = dist;
        o[1].xyz = wi;
        o[2].xyz = li;
    } else if (u_mode == MODE_AREA) {
        o[0].x = float(dirt_area_lights_select_g(in_data[b].x));
    } else if (u_mode == MODE_MATERIAL) {
        vec4 a = in_data[b];
        uint m = uint(a.x);
        dirt_surface_g s = dirt_material_surface_g(m, a.yz);
        o[0] = vec4(s.bsdf.base_color, s.bsdf.metallic);
        o[1] = vec4(s.bsdf.alpha, s.bsdf.specular, flag(s.double_sided),
                    flag(dirt_material_is_emissive_g(m)));
        o[2] = vec4(s.emission, s.bsdf.eta);
        o[3] = vec4(s.bsdf.f0, s.bsdf.transmission);
    } else if (u_mode == MODE_TRANS) {
        dirt_bsdf_g bs = read_bsdf(b);
        vec3 wo = in_data[b + 2u].xyz;
        float ps, pt;
        dirt_bsdf_lobe_probabilities_g(bs, wo, ps, pt);
        o[0] = vec4(pt, dirt_bsdf_fresnel_interface_g(bs, in_data[b + 3u].x),
                    flag(dirt_bsdf_transmits_g(bs)), flag(dirt_bsdf_transmission_is_delta_g(bs)));
        o[1].x = ps;
    } else if (u_mode == MODE_CAMERA) {
        dirt_gpu_model_camera c;
        c.eye = in_data[b];
        c.forward = in_data[b + 1u];
        c.right = in_data[b + 2u];
        c.up = in_data[b + 3u];
        c.lens = in_data[b + 4u];
        vec4 px = in_data[b + 5u];
        vec4 lens = in_data[b + 6u];
        vec3 org, dir;
        dirt_camera_ray_g(c, int(px.x), int(px.y), px.z, px.w, lens.x, lens.y, org, dir);
        o[0].xyz = org;
        o[1].xyz = dir;
    } else if (u_mode == MODE_TEXTURE) {
        vec4 a = in_data[b];
        o[0] = dirt_texture_sample_g(int(a.x), a.y != 0.0, a.zw);
    }

    for (uint k = 0u; k < TEST_STRIDE; k++) {
#ifdef TEST_FAULT
        o[k] = o[k] * 1.001 + 0.01;
#endif
        out_data[b + k] = o[k];
    }
}
