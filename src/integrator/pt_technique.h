/* The ray-tracing technique as the GPU path tracer (gpu_pt.c) sees it: a
 * small vtable over GL buffers, so the same frame graph runs on the DIRT
 * structure (ads_* of src/dirt/ads_internal.h) or on the MMRT A-buffer
 * (src/mmrt/pt_mmrt.c). Internal to the engine. */
#ifndef DIRT_PT_TECHNIQUE_H
#define DIRT_PT_TECHNIQUE_H

#include <stdbool.h>
#include <stdint.h>

#include "dirt/pathtrace.h"
#include "dirt/views.h"
#include "gl/gl.h"

typedef struct pt_technique {
    void *self;
    const char *name;         /* "dirt", "mmrt" */
    /* Traces `count` dirt_gpu_ray records of `rays` into the dirt_gpu_hit
     * records of `hits` (hit i's owner = i). any_hit: shadow rays (only
     * "something in [tmin, tmax]" matters). link: also link the hits for a
     * raster Fetch (DIRT only). Issues the barriers it needs before and
     * after. `opts` is the render's. */
    bool (*trace)(void *self, const dirt_pt_opts *opts, GLuint rays, GLuint hits,
                  uint32_t count, bool any_hit, bool link);
    /* First hits of the camera view from a visibility buffer; NULL when the
     * technique has none. */
    bool (*visibility)(void *self, GLuint rays, GLuint hits);
    /* Writes G_{k} of every hit's owner pixel into ring slot `slot` of
     * `gpoints` (misses: prim = DIRT_NO_HIT, wo = -ray direction). raster:
     * the geometry-pass Fetch (DIRT only). */
    bool (*fetch)(void *self, bool raster, GLuint rays, GLuint hits, uint32_t count,
                  GLuint gpoints, uint32_t slot);
    /* Binds the dirt_gpu_vertex buffer at DIRT_BIND_VERTICES and the
     * per-primitive materials at DIRT_BIND_PRIM_MATERIAL (Shade reads them). */
    void (*bind_geometry)(void *self);
    /* Resets / reads the active rays traced (tmax >= tmin) and the rays
     * whose march gave up, since the reset. */
    void (*reset_counts)(void *self);
    bool (*read_counts)(void *self, uint64_t *rays, uint64_t *aborted);
    const dirt_view_set *views; /* the technique's views (direct visibility) */
    double build_ms;          /* the structure's last build, summed over passes */
    uint64_t bytes_extra;     /* integrator-side buffers the technique owns */
} pt_technique;

/* One slot per dirt_pt for a technique's persistent state (programs,
 * buffers), released with `release(state)` when the dirt_pt is destroyed.
 * MMRT's lives here (src/mmrt/pt_mmrt.c). */
typedef struct pt_tech_state {
    void *state;
    void (*release)(void *state);
} pt_tech_state;

pt_tech_state *dirt_pt_tech_state(dirt_pt *pt);
dirt_gpu *dirt_pt_gpu(const dirt_pt *pt);

/* Renders through any technique (gpu_pt.c): the body of dirt_pt_render. */
bool dirt_pt_render_technique(dirt_pt *pt, pt_technique *tech, const dirt_frame *frame,
                              const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                              dirt_pt_stats *stats);

#endif
