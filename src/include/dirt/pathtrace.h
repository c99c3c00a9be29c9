/* DIRT engine: the GPU path tracer (Trace -> Fetch -> Shade loop).
 *
 * Every sample is one execution of a frame graph: ray generation, then per
 * path event k = 1..K+1: trace (closest hit), fetch (G_{k} from the hit,
 * three-point ring of shading points), shade (emission with MIS, one
 * next-event sample, one BSDF sample), shadow trace (any hit) and resolve;
 * finally accumulation. The light-transport model, the random numbers and
 * the order in which they are drawn are those of the Embree reference
 * (doc/light-transport.md), so both converge to the same image.
 * The rays are traced through a technique: the DIRT structure
 * (dirt_pt_render) or the MMRT A-buffer (dirt_pt_render_mmrt), the same frame
 * graph either way (only the trace, fetch and geometry bindings differ). */
#ifndef DIRT_PATHTRACE_H
#define DIRT_PATHTRACE_H

#include <stdbool.h>
#include <stdint.h>

#include "dirt/ads.h"
#include "dirt/gpu.h"
#include "dirt/image.h"
#include "dirt/mmrt.h"
#include "dirt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_pt dirt_pt;

enum dirt_pt_mode { DIRT_PT_PATH = 0, DIRT_PT_AO = 1 };

/* Zero-initialised = path tracing, 1 spp, 4 bounces (as the reference), seed 0, black
 * background, compute Fetch. */
typedef struct dirt_pt_opts {
    enum dirt_pt_mode mode;
    int spp;                  /* samples per pixel (default 1) */
    int bounces;              /* K scattering events (default 4; 0 = direct emission only
                                 when bounces_set) */
    bool bounces_set;         /* take `bounces` as given even when 0 */
    uint32_t seed;
    float background[3];      /* radiance of rays that leave the scene */
    float ao_distance;        /* AO ray length; 0 = infinite */
    enum dirt_fetch_mode fetch;
    /* G_1 from a visibility buffer of the camera view instead of traced
     * camera rays (pixel centres: no pixel jitter, no depth of field). */
    bool direct_visibility;
    dirt_trace_opts trace;    /* DIRT's trace options (dirt_pt_render) */
    dirt_mmrt_trace_opts mmrt; /* MMRT's (dirt_pt_render_mmrt); its seed is mixed with
                                  the trace call's index for the linear march jitter */
    bool cpu_timing;          /* glFinish + CPU clock per pass */
    /* Called after every sample (may be NULL). */
    void (*progress)(void *user, int done, int total);
    void *progress_user;
} dirt_pt_opts;

typedef struct dirt_pt_stats {
    double build_ms;          /* the structure's build (from its stats) */
    double trace_ms, fetch_ms, shade_ms; /* summed over samples and events */
    double total_ms;          /* wall time of the render */
    uint64_t rays;            /* rays traced (camera, continuation, shadow) */
    uint64_t aborted;         /* rays whose march gave up (see dirt_trace_stats) */
    double mrays_per_s;       /* rays / trace time */
    uint64_t invalid_samples; /* non-finite samples dropped */
    uint64_t bytes_integrator; /* rays, hits, shading ring, paths, sums */
} dirt_pt_stats;

/* Uploads the scene's materials and textures. The scene must outlive it.
 * NULL on failure (logged). */
dirt_pt *dirt_pt_create(dirt_gpu *gpu, const dirt_scene *scene);
void dirt_pt_destroy(dirt_pt *pt);

/* Renders `frame` from `cam` through the DIRT structure `ads` (built for
 * this frame and camera) into `out` (its size is the image size): beauty in
 * RGBA (alpha 1) and, when `out` has them, the channels "albedo.R/G/B" and
 * "N.X/Y/Z" (first-hit means). `stats` may be NULL. */
bool dirt_pt_render(dirt_pt *pt, dirt_ads *ads, const dirt_frame *frame,
                    const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                    dirt_pt_stats *stats);

/* The same through the MMRT A-buffer `mmrt` (built for this frame and
 * camera), MMRT's way (the MMRT paper: no Fetch): a hit's data node becomes
 * the shading point directly (the "fetch" pass only converts it: position =
 * ray origin + t direction, the MMRT hit point; shading normal, uv and
 * material from the data node; geometric normal of the primitive), and the
 * shadow rays of next-event estimation are MMRT traces too. Every ray is
 * traced from 3 thicknesses along it (shadow rays also stop 3 thicknesses
 * short of their end) so that a ray does not hit the surface it leaves
 * within the thickness. opts->mmrt gives the march and thickness; fetch
 * must be compute and direct_visibility false (false, logged, otherwise).
 * Stats: rays counts the active rays traced; bytes_integrator includes the
 * technique's offset ray copy. */
bool dirt_pt_render_mmrt(dirt_pt *pt, dirt_mmrt *mmrt, const dirt_frame *frame,
                         const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                         dirt_pt_stats *stats);

/* DOT of the last render's frame graph; false before the first render. */
bool dirt_pt_write_dot(const dirt_pt *pt, const char *path);

#ifdef __cplusplus
}
#endif
#endif
