/* DIRT engine: rays, hits and the tracer interface every ray-tracing
 * technique offers the integrator.
 *
 * A technique (the DIRT structure, the MMRT A-buffer) builds its structure
 * for a frame, then hands out a dirt_tracer: a small table of functions over
 * GPU buffers (OpenGL buffer names) that traces batches of dirt_gpu_ray
 * records into dirt_gpu_hit records and turns hits into shading points
 * (dirt_gpu_gpoint, glsl/common/layout.h). The integrator (pathtrace.h)
 * knows only this interface, never a technique's internals; each technique's
 * own options (march, Hi-Z levels, Fetch kind, thickness) are given to it
 * when the tracer is made (dirt_ads_tracer, dirt_mmrt_tracer). */
#ifndef DIRT_TRACER_H
#define DIRT_TRACER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/ray.h"
#include "dirt/gpu.h"
#include "gl/split.h"
#include "views/views.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a GPU trace needs for alpha-tested traversal (doc/light-transport.md
 * section 1, "Alpha"): a hit of a MASK or BLEND material that the alpha test
 * rejects is no hit, and the trace goes on to the next one. Zero-initialised
 * = no test (every surface opaque, the trace as fast as without alpha).
 * The tables are the integrator's (dirt_gpu_model_tables, integrator/gpu_tables.h):
 * the trace binds them at DIRT_BIND_MODEL_MATERIALS and _TEXELS (or the
 * texels' parts, gl_split_bind) and reads
 * the per-primitive materials, UVs and texels. BLEND decisions use the key
 * dirt_rng_u32(seed, first_pixel + owner(i), sample, bounce, dim) for ray i
 * of the batch, owner(i) = i or its ray batch's owner (views/tracer.h,
 * set_batch; doc/rng.md, "Alpha"). */
typedef struct dirt_trace_alpha {
    uint32_t materials;   /* GL buffer of dirt_gpu_model_material; 0 = no test */
    const gl_split *texels; /* the texel table (dirt_gpu_model_tables.texels:
                               one storage block, or texel-buffer parts the
                               trace's program is built for) */
    uint32_t seed;        /* the render's seed */
    uint32_t sample;      /* sample index */
    uint32_t bounce;      /* the vertex the rays leave (0: camera rays) */
    uint32_t dim;         /* DIRT_RNG_DIM_ALPHA_PATH or _SHADOW */
    uint32_t first_pixel; /* pixel of ray 0 of the batch */
} dirt_trace_alpha;

/* What a batch of rays handed to dirt_tracer.trace is (bits; 0 = camera
 * rays or rays from anywhere, closest hits). */
enum dirt_tracer_flags {
    DIRT_TRACER_ANY_HIT = 1u << 0,       /* shadow rays: only "something in (tmin, tmax)"
                                            matters */
    DIRT_TRACER_FROM_SURFACES = 1u << 1, /* every ray leaves a surface point (a path's
                                            vertex): a hint for where a march starts;
                                            the hits are the same without it */
};

/* A technique's tracer for the structure of its last build. Owned by the
 * technique; valid until its next build, option change or destruction.
 * Buffers are OpenGL buffer names; every function issues, before its own
 * work, the memory barriers its reads and writes need (of the technique's
 * buffers and of those handed in); whoever reads what a function wrote
 * fences that read (the path tracer's frame graph declares the buffers it
 * hands in; doc/frame-graph.md, section 11). */
typedef struct dirt_tracer {
    const char *name;          /* "dirt", "mmrt" */
    void *self;
    /* Traces `count` dirt_gpu_ray records of `rays` into the dirt_gpu_hit
     * records of `hits` (hit i's owner = i; see set_batch). flags: what the
     * rays are (dirt_tracer_flags). */
    bool (*trace)(void *self, uint32_t rays, uint32_t hits, uint32_t count, unsigned flags);
    /* First hits of the camera view from a visibility buffer (one ray and
     * hit per pixel of the camera view); NULL when the technique has none. */
    bool (*visibility)(void *self, uint32_t rays, uint32_t hits);
    /* Writes G of every hit's owner pixel into ring slot `slot` of
     * `gpoints` (misses: prim = DIRT_NO_HIT, wo = -ray direction), for the
     * hits of the last closest-hit trace (or visibility) of these buffers.
     * It may rewrite a hit's t to the distance of the shading point it
     * chose (MMRT: where the ray meets the hit primitive). */
    bool (*fetch)(void *self, uint32_t rays, uint32_t hits, uint32_t count, uint32_t gpoints,
                  uint32_t slot);
    /* Binds the vertices (dirt_gpu_vertex) and the per-primitive materials
     * for Shade: at DIRT_BIND_VERTICES and DIRT_BIND_PRIM_MATERIAL while
     * each fits one storage block, else their texel buffers
     * (vertices_split, prim_material_split below). */
    void (*bind_geometry)(void *self);
    /* Resets / reads the active rays traced (tmax >= tmin) and the rays
     * whose march gave up, since the reset (blocking read; the integrator
     * issues the GL_BUFFER_UPDATE_BARRIER_BIT before it). */
    void (*reset_counts)(void *self);
    bool (*read_counts)(void *self, uint64_t *rays, uint64_t *aborted);
    /* A new accumulation begins (sample 0): a technique whose traces are
     * randomised per call restarts its sequence. NULL when there is none. */
    void (*restart)(void *self);
    /* The integrator works through the image in chunks (wavefronts): before
     * the traces of each chunk of one sample it calls begin_chunk with the
     * chunk's first pixel (0 starts a sample); the chunk's ray i is pixel
     * first + i (in a ray batch: first + owner[i], see set_batch). A technique whose traces are randomised per call and per
     * ray keys them by (call of the sample, pixel), so that the chunking
     * changes no result. NULL when there is nothing to key. */
    void (*begin_chunk)(void *self, uint32_t first);
    /* Alpha-tested traversal for the traces that follow (dirt_trace_alpha above; the
     * integrator sets it before each trace: its keys differ per ray kind
     * and path event). A zeroed `alpha` (or NULL) turns the test off.
     * NULL when the technique cannot test alpha. */
    void (*set_alpha)(void *self, const dirt_trace_alpha *alpha);
    /* A ray batch the GPU sized (compaction of the integrator's live paths)
     * for the traces and fetches that follow: `batch` is a buffer holding a
     * dirt_gpu_ray_batch header, then uint owner[] (glsl/common/layout.h).
     * Their `count` is then its capacity and the header's count the rays;
     * ray i's hit has owner owner[i], which also keys the ray's randomised
     * decisions (alpha, MMRT's jitter) in place of i; passes dispatch
     * indirectly from the header, so the host never reads the count. 0
     * returns to plain batches. Required: the path tracer traces its live
     * paths only after event 1, and refuses a tracer without it. */
    void (*set_batch)(void *self, uint32_t batch);
    const dirt_view_set *views; /* the technique's views (direct visibility) */
    /* How the arrays bind_geometry binds are stored (gl/split.h; their
     * texel buffers' units: common/constants.h): Shade is built for them
     * (common/vertices.glsl). */
    gl_split_layout vertices_split, prim_material_split;
    uint64_t bytes_extra;      /* integrator-side buffers the technique owns */
    /* World distance by which rays leaving a surface start off it along its
     * geometric normal (on the side they leave, beyond the integrator's own
     * epsilon), and by which shadow rays towards an emitting triangle stop
     * off its plane (on the receiver's side); a shadow ray whose receiver
     * and light point are within twice this distance of each other's plane
     * is not traced (unoccluded: the technique cannot resolve anything
     * between them). 0 for exact tracers (DIRT: the reference's rays). */
    float surface_offset;
} dirt_tracer;

#ifdef __cplusplus
}
#endif
#endif
