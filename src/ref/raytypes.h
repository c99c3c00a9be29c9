/* DIRT engine: the ray types of the DIRT paper's Table 1 (visibility,
 * specular, glossy GGX 0.1, diffuse) generated from a camera G-buffer, the
 * same set for every technique (Embree, DIRT, MMRT), so hit agreement and
 * Mrays/s compare like with like. */
#ifndef DIRT_RAYTYPES_H
#define DIRT_RAYTYPES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/ray.h"
#include "ref/ref.h"
#include "dirt/scene.h"
#include "dirt/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Primary hits of a width x height camera image (Embree). */
typedef struct dirt_gbuffer {
    int width, height;
    size_t count;            /* pixels with a hit */
    uint32_t *pixel;         /* pixel index of hit i */
    uint32_t *prim;
    float (*position)[3];
    float (*normal)[3];      /* unit geometric normal facing the camera ray */
    float (*view_dir)[3];    /* unit direction of the camera ray */
    float light[3];          /* target of visibility rays */
    float epsilon;           /* origin offset along the normal */
} dirt_gbuffer;

/* Casts the camera rays with `accel` (built over `frame`). The visibility
 * target is the area-weighted centre of the emissive triangles (moved by
 * 1e-3 of the scene size along their normal), else the first punctual light,
 * else the top of the bounds. False on out-of-memory (logged). */
bool dirt_gbuffer_build(const dirt_ref_accel *accel, const dirt_scene *scene,
                        const dirt_frame *frame, const dirt_camera *cam, int width,
                        int height, dirt_gbuffer *out);
void dirt_gbuffer_free(dirt_gbuffer *g);

/* Fills out[0 .. count) (count = g->count, or width*height for primary rays)
 * with rays of `type`, deterministic in `seed`. Returns the number written. */
size_t dirt_rays_generate(const dirt_gbuffer *g, const dirt_camera *cam, enum dirt_ray_type type,
                          uint32_t seed, dirt_ray *out);

#ifdef __cplusplus
}
#endif
#endif
