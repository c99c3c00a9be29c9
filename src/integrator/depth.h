/* The Z AOV of the GPU path tracer (depth.c). */
#ifndef DIRT_INTEGRATOR_DEPTH_H
#define DIRT_INTEGRATOR_DEPTH_H

#include <stdbool.h>

#include "dirt/gpu.h"
#include "dirt/scene.h"
#include "views/tracer.h"

/* Writes the depths of pixels start .. start + count - 1 of a width x
 * height image (pixel y * width + x, row 0 = top) into `depth`: the
 * distance along the camera's forward axis to the first hit of the pinhole ray
 * through each pixel centre, INFINITY where it misses; the reference's
 * "Z" (src/ref/render.c), and into `ids` (may be NULL) the primitive of
 * that hit as a float (exact below 2^24 triangles), -1 where it misses: the
 * reference's "ID". Traces through `tracer` in batches of at most
 * `batch` rays (the path tracer's chunk: they fit one storage block and one
 * dispatch; before each, a tracer randomised per call restarts its sequence
 * and keys the rays by pixel, restart and begin_chunk, so a pixel's depth
 * does not depend on the pixels traced with it). `alpha` (may be NULL: no test) gives the tables and seed of
 * the alpha test; its rays are keyed (bounce 0, DIRT_RNG_DIM_ALPHA_PATH,
 * sample DIRT_RNG_SAMPLE_AOV, pixel) as the reference's. Blocking. False
 * after logging. */
bool pt_depth_render(dirt_gpu *gpu, const dirt_tracer *tracer, const dirt_camera *cam, int width,
                     int height, size_t start, size_t count, size_t batch,
                     const dirt_trace_alpha *alpha, float *depth, float *ids);

#endif
