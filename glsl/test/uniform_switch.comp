#version 450 core
#include "common/constants.h"
// Test shader (test/gpu/test_gl_uniforms.c): a uniform that chooses
// between two readings of a buffer, as common/ray_batch.glsl's u_ray_batch
// does. Invocation 0 writes, at slot u_slot, the owner of entry 0 of the
// batch in DIRT_BIND_TEST_IN when u_batch is set (the batch's count bounds
// the invocations then), else its own index.
layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(location = DIRT_LOC_TEST_SWITCH_BATCH) uniform int u_batch;
layout(location = DIRT_LOC_TEST_SWITCH_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_TEST_SWITCH_SLOT) uniform uint u_slot;
layout(std430, binding = DIRT_BIND_TEST_IN) readonly buffer Batch {
    uvec4 dispatch; // w: count
    uint owner[];
};
layout(std430, binding = DIRT_BIND_TEST_OUT) writeonly buffer Out {
    uint values[];
};

void main()
{
    uint i = gl_GlobalInvocationID.x;
    uint n = u_batch != 0 ? min(u_count, dispatch.w) : u_count;
    if (i >= n)
        return;
    if (i == 0u)
        values[u_slot] = u_batch != 0 ? owner[i] : i;
}
