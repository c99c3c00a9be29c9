#version 450 core
#include "common/constants.h"
// Test shader: the GLSL RNG over a grid of keys, for comparison with C.
#include "common/rng.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer Out { uvec2 values[]; };
layout(location = DIRT_LOC_TEST_RNG_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_TEST_RNG_SEED) uniform uint u_seed;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count)
        return;
    // (pixel, sample, bounce, dimension) from the index, spanning wide ranges.
    uint pixel = i * 2654435761u;
    uint sample_index = i / 7u;
    uint bounce = i % 13u;
    uint dim = i % 11u;
    uint key = dirt_rng_key(u_seed, pixel, sample_index, bounce);
    values[i] = uvec2(dirt_rng_next(key, dim),
                      floatBitsToUint(dirt_rng_float(u_seed, pixel, sample_index, bounce, dim)));
}
