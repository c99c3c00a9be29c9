#version 450 core
// Raster Fetch companion: the raster pass only sees hits; this pass writes
// the misses (records without a primitive) into G_{k+1}.
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
    if (r < dirt_batch_count(fetch.config.x) && hits[r].ids.x == DIRT_NO_HIT)
        dirt_fetch_record(r);
}
