/* The path tracer's ray sort (dirt_pt_opts.sort_rays; glsl/integrator/
 * sort.comp): a counting sort of a ray batch by a key of origin and
 * direction, in three passes the caller issues in order (the frame graph's
 * barriers, or glMemoryBarrier, between them). */
#ifndef DIRT_INTEGRATOR_RAY_SORT_H
#define DIRT_INTEGRATOR_RAY_SORT_H

#include <stddef.h>
#include <stdint.h>

#include "gl/gl.h"

typedef struct dirt_ray_sort dirt_ray_sort;

enum dirt_ray_sort_pass {
    DIRT_RAY_SORT_COUNT,   /* clears the counters; each ray's key; rays per key */
    DIRT_RAY_SORT_SCAN,    /* counts into first slots; the output batch's header */
    DIRT_RAY_SORT_SCATTER, /* rays and owners to their slots */
    DIRT_RAY_SORT_PASSES
};

/* The sort's programs; NULL after logging. */
dirt_ray_sort *dirt_ray_sort_create(void);
void dirt_ray_sort_destroy(dirt_ray_sort *rs);

/* Bytes of the scratch buffer for batches of up to `capacity` rays. */
size_t dirt_ray_sort_scratch_bytes(size_t capacity);

/* The buffers of one sort: the input batch (dirt_gpu_ray_batch + owners;
 * at most `capacity` rays) and its rays, the output batch and rays (of the
 * same capacity; other buffers than the input's), the scratch buffer
 * (dirt_ray_sort_scratch_bytes), and the box the origin grid spans (the
 * scene's bounds; any box gives a valid sort). */
typedef struct dirt_ray_sort_io {
    GLuint in_rays, in_batch, out_rays, out_batch, scratch;
    uint32_t capacity;
    float bounds_min[3], bounds_max[3];
} dirt_ray_sort_io;

/* Issues pass `pass` of the sort (count and scatter dispatch indirectly
 * from the input batch). Afterwards the output holds the input's rays and
 * owners, permuted so that equal keys are contiguous and keys ascend, and
 * the input's header. Leaves no program in use. */
void dirt_ray_sort_pass(const dirt_ray_sort *rs, enum dirt_ray_sort_pass pass,
                        const dirt_ray_sort_io *io);

#endif
