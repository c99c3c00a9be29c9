#version 450 core
// Compute Fetch: one invocation per hit record (DIRT_BIND_HITS), reading the
// primitive's vertices from the vertex buffer and interpolating with the
// stored barycentrics into G_{k+1} of the owner pixel.
#include "common/layout.h"
#include "common/ray_batch.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

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

#include "dirt/fetch_common.glsl"

void main()
{
    uint r = gl_GlobalInvocationID.x;
    if (r < dirt_batch_count(fetch.config.x))
        dirt_fetch_record(r);
}
