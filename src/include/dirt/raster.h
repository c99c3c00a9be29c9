/* DIRT engine: raster preview — the scene rasterized with simple direct
 * lighting (no shadows, no bounces). The quick look of dirt-render and the
 * viewer's fallback; not a ground truth. */
#ifndef DIRT_RASTER_H
#define DIRT_RASTER_H

#include <stdbool.h>

#include "dirt/gpu.h"
#include "dirt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_raster dirt_raster;

/* Zero-initialised = defaults. */
typedef struct dirt_raster_opts {
    float ambient;        /* ambient factor times albedo; 0 = default 0.02, <0 = none */
    bool cpu_timing;      /* time with glFinish + CPU clock as well */
} dirt_raster_opts;

typedef struct dirt_raster_stats {
    double gpu_ms;        /* GL_TIME_ELAPSED of the draw (-1 unavailable) */
    double cpu_ms;        /* glFinish wall time (-1 unless cpu_timing) */
    int num_lights;       /* punctual + lumped emitters */
} dirt_raster_stats;

/* Compiles the preview shaders and uploads the scene's materials and
 * textures. The scene must outlive the renderer. NULL on failure (logged). */
dirt_raster *dirt_raster_create(dirt_gpu *gpu, const dirt_scene *scene);
void dirt_raster_destroy(dirt_raster *r);

/* Renders `frame` (of the scene given at create) from `cam` into `rgba`,
 * width*height*4 linear floats, row 0 = top. `opts`/`stats` may be NULL. */
bool dirt_raster_render(dirt_raster *r, const dirt_frame *frame, const dirt_camera *cam,
                        int width, int height, const dirt_raster_opts *opts,
                        float *rgba, dirt_raster_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
