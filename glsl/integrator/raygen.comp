#version 450 core
// Path tracer, event 0: a camera ray per pixel (jittered in the pixel, thin
// lens when the camera has an aperture), a fresh path state, and the batch
// of event 1: every pixel, ray p owned by pixel p.
#include "common/layout.h"
#define DIRT_MODEL_BUFFERS 1
#include "common/rng.glsl"
#include "integrator/model.glsl"
#include "integrator/pt_common.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_RAYS) writeonly buffer Rays {
    dirt_gpu_ray rays[];
};
#define DIRT_RAY_BATCH_ALWAYS 1
#define DIRT_RAY_BATCH_ACCESS // read-write (the functions read it)
#include "common/ray_batch.glsl"

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p == 0u)
        dirt_ray_batch.dispatch = uvec4(max(uint(DIRT_GROUPS(u_pixels)), 1u), 1u, 1u, u_pixels);
    if (p >= u_pixels)
        return;
    dirt_ray_batch_owner[p] = p;
    uint pixel = u_pixel_offset + p;
    uint x = pixel % uint(u_width), y = pixel / uint(u_width);
    uint key = dirt_rng_key(u_seed, pixel, u_sample, 0u);
    float px = float(x) + dirt_rng_next_float(key, DIRT_RNG_DIM_PIXEL_X);
    float py = float(y) + dirt_rng_next_float(key, DIRT_RNG_DIM_PIXEL_Y);
    vec3 org, dir;
    dirt_camera_ray_g(dirt_model_camera, u_width, u_height, px, py,
                      dirt_rng_next_float(key, DIRT_RNG_DIM_LENS_U),
                      dirt_rng_next_float(key, DIRT_RNG_DIM_LENS_V), org, dir);
    rays[p].origin_tmin = vec4(org, 0.0);
    rays[p].dir_tmax = vec4(dir, DIRT_INFINITY_G);
    dirt_gpu_path s;
    s.beta_pdf = vec4(1.0, 1.0, 1.0, 0.0);
    s.radiance = vec4(0.0, 0.0, 0.0, uintBitsToFloat(DIRT_PATH_ALIVE | DIRT_PATH_PREV_DELTA));
    s.pending = vec4(0.0);
    s.first_albedo = vec4(0.0);
    s.first_normal = vec4(0.0);
    paths[p] = s;
}
