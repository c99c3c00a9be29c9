/* DIRT engine: raster preview — the scene rasterized with simple direct
 * lighting (no shadows, no bounces). The quick look of dirt-render and the
 * viewer's fallback; not a ground truth. */
#ifndef DIRT_RASTER_H
#define DIRT_RASTER_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/gpu.h"
#include "dirt/scene.h"
#include "dirt/stats.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_raster dirt_raster;

/* Zero-initialised = defaults. */
typedef struct dirt_raster_opts {
    float ambient;        /* ambient factor times albedo; 0 = default 0.02, <0 = none */
} dirt_raster_opts;

/* Most passes the preview's frame graph runs (dirt_raster_stats.passes). */
#define DIRT_RASTER_MAX_PASSES 4

/* One pass of the preview's frame graph, from the graph's own stats. */
typedef struct dirt_raster_pass_stats {
    char name[32];        /* "preview draw", "preview readback" */
    double ms;            /* the pass's time; -1 when not measured */
    enum dirt_clock clock; /* what measured ms (the GPU's one clock, dirt_gpu_clock) */
    unsigned barrier;     /* glMemoryBarrier bits issued before it (GL values; 0 = none) */
} dirt_raster_pass_stats;

typedef struct dirt_raster_stats {
    double ms;            /* sum of the passes' times (draw + readback); -1 when
                             any was not measured */
    enum dirt_clock clock; /* what measured them; DIRT_CLOCK_NONE when ms is -1 */
    int num_lights;       /* punctual + lumped emitters */
    /* Frame graph (src/graph/), filled by a successful render: */
    int num_passes;       /* passes executed, at most DIRT_RASTER_MAX_PASSES */
    dirt_raster_pass_stats passes[DIRT_RASTER_MAX_PASSES]; /* in execution order */
    size_t transient_bytes;   /* graph-owned targets: colour and AOV RGBA32F + depth32f */
    size_t imported_bytes;    /* vertex/material/light buffers and sampled textures */
    unsigned long long validation_errors; /* missing barriers found by the graph's
                                             validation since create (always 0 in a
                                             render that succeeded) */
} dirt_raster_stats;

/* Compiles the preview shaders and uploads the scene's materials and
 * textures. The scene must outlive the renderer. NULL on failure (logged). */
dirt_raster *dirt_raster_create(dirt_gpu *gpu, const dirt_scene *scene);
void dirt_raster_destroy(dirt_raster *r);

/* Renders `frame` (of the scene given at create) from `cam` into `rgba`,
 * width*height*4 linear floats, row 0 = top, and, when `aov` is not NULL,
 * into `aov` (width*height*4 floats): the world-space shading normal facing
 * the camera (xyz; 0 where nothing is hit) and Z (w), the depth along the
 * camera's forward axis (INFINITY where nothing is hit), the engine's "N"
 * and "Z" AOVs at pixel centres. `opts`/`stats` may be NULL.
 * Runs on a frame graph (doc/frame-graph.md section 7) executed with barrier
 * validation on; a change of size recompiles it. */
bool dirt_raster_render(dirt_raster *r, const dirt_frame *frame, const dirt_camera *cam,
                        int width, int height, const dirt_raster_opts *opts,
                        float *rgba, float *aov, dirt_raster_stats *stats);

/* Writes the GraphViz DOT of the preview's frame graph, as compiled for the
 * latest render's size, to `path` (render with `dot -Tsvg`). False after
 * logging when nothing was rendered yet or the file cannot be written. */
bool dirt_raster_write_dot(const dirt_raster *r, const char *path);

#ifdef __cplusplus
}
#endif
#endif
