// A pass over a ray batch (views/tracer.h, set_batch): the number of rays
// and the owner of each come from the DIRT_BIND_RAY_BATCH buffer
// (dirt_gpu_ray_batch, then uint owner[]), which the host also dispatches
// from. A tracer's passes do so when u_ray_batch is set (else the batch is
// rays 0 .. n - 1 of the call, ray i owned by i); the path tracer's own
// passes always (DIRT_RAY_BATCH_ALWAYS). DIRT_RAY_BATCH_ACCESS qualifies
// the block (default readonly). Needs common/layout.h.

#ifdef DIRT_RAY_BATCH_ALWAYS
#define DIRT_RAY_BATCH_ON true
#else
layout(location = DIRT_LOC_RAY_BATCH) uniform int u_ray_batch;
#define DIRT_RAY_BATCH_ON (u_ray_batch != 0)
#endif
#ifndef DIRT_RAY_BATCH_ACCESS
#define DIRT_RAY_BATCH_ACCESS readonly
#endif
layout(std430, binding = DIRT_BIND_RAY_BATCH) DIRT_RAY_BATCH_ACCESS buffer RayBatch {
    dirt_gpu_ray_batch dirt_ray_batch;
    uint dirt_ray_batch_owner[];
};

// Rays in the batch; n is the call's count (the batch's capacity).
uint dirt_batch_count(uint n)
{
    return DIRT_RAY_BATCH_ON ? min(n, dirt_ray_batch.dispatch.w) : n;
}

// Owner of ray i of the batch: what its hit record's ids.z says, and the
// index that keys its random decisions (pixel = first pixel + owner).
uint dirt_batch_owner(uint i)
{
    return DIRT_RAY_BATCH_ON ? dirt_ray_batch_owner[i] : i;
}
