#version 450 core
// Layout test (test/gpu/test_layout_gpu.c): one of every C/GLSL twin record
// in one std430 block, in the order of the C mirror struct of the test.
// The host asks GL where every member is and reads back the tags written
// here at the offsets the C compiler gives.
#include "common/integrator_layout.h"
#include "common/mmrt_pt_layout.h"

layout(local_size_x = 1) in;

layout(std430, binding = DIRT_BIND_TEST_OUT) buffer Records {
    dirt_gpu_material r_material;
    dirt_gpu_light r_light;
    dirt_gpu_vertex r_vertex;
    dirt_gpu_view r_view;
    dirt_gpu_ads_params r_ads_params;
    dirt_gpu_ads_counters r_ads_counters;
    dirt_gpu_ray r_ray;
    dirt_gpu_hit r_hit;
    dirt_gpu_gpoint r_gpoint;
    dirt_gpu_fetch_params r_fetch_params;
    dirt_gpu_path r_path;
    dirt_gpu_accum r_accum;
    dirt_gpu_model_material r_model_material;
    dirt_gpu_model_light r_model_light;
    dirt_gpu_model_lights r_model_lights;
    dirt_gpu_model_camera r_model_camera;
    dirt_gpu_model_texels r_model_texels;
    dirt_gpu_model_texture r_model_texture;
    dirt_gpu_model_tangent r_model_tangent;
    dirt_mmrt_gpu_params r_mmrt_params;
    dirt_mmrt_gpu_data r_mmrt_data;
    dirt_mmrt_gpu_counters r_mmrt_counters;
    dirt_mmrt_pt_counts r_mmrt_pt_counts;
};

// The tags: one member of each record kind, checked by the host.
void main()
{
    r_material.textures = ivec4(-1, 2, -3, 4);
    r_view.level_base[3] = ivec4(11, 12, 13, 14);
    r_view.forward_far.w = 0.25;
    r_hit.bary_t.z = 0.5;
    r_gpoint.n_mat.y = -1.5;
    r_path.first_normal.y = 2.0;
    r_accum.normal.z = 3.0;
    r_model_camera.lens.w = 2.5;
    r_model_texture.extent.z = 17u;
    r_model_tangent.tangent.w = -1.0;
    r_mmrt_counters.trace2.x = 77u;
    r_mmrt_pt_counts.counts.y = 99u;
}
