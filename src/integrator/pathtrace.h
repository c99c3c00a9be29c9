/* DIRT engine: the GPU path tracer (Trace -> Fetch -> Shade loop).
 *
 * Every sample is one execution of a frame graph: ray generation, then per
 * path event k = 1..K+1: trace (closest hit), fetch (G_{k} from the hit,
 * three-point ring of shading points), shade (emission with MIS, one
 * next-event sample, one BSDF sample), shadow trace (any hit) and resolve;
 * finally accumulation. The light-transport model, the random numbers and
 * the order in which they are drawn are those of the Embree reference
 * (doc/light-transport.md), so both converge to the same image.
 * The rays are traced through a technique's tracer (views/tracer.h: the DIRT
 * structure, the MMRT A-buffer); this header knows no technique.
 *
 * Progressive: the accumulation persists between calls. dirt_pt_reset
 * starts it for an image size, dirt_pt_add_samples adds samples (sample
 * indices continue, so 1 + 1 + 2 samples give the image of one 4-sample
 * render), dirt_pt_read gives the mean, dirt_pt_display_texture the same
 * mean in a GL texture that never leaves the GPU. */
#ifndef DIRT_PATHTRACE_H
#define DIRT_PATHTRACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "common/constants.h"
#include "dirt/gpu.h"
#include "dirt/image.h"
#include "dirt/scene.h"
#include "dirt/stats.h"
#include "dirt/types.h"
#include "views/tracer.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_pt dirt_pt;

/* Zero-initialised = path tracing, 1 spp, 4 bounces (as the reference), seed 0, black
 * background. */
typedef struct dirt_pt_opts {
    enum dirt_pt_mode mode;
    int spp;                  /* samples per pixel (default 1) */
    int bounces;              /* K scattering events (default 4; 0 = direct emission only
                                 when bounces_set) */
    bool bounces_set;         /* take `bounces` as given even when 0 */
    uint32_t seed;
    float background[3];      /* radiance of rays that leave the scene (the
                                 constant environment, sampled as a map);
                                 ignored when `env` is given */
    const struct dirt_env *env; /* environment light (borrowed until the call
                                 returns; NULL = the background) */
    float ao_distance;        /* AO ray length; 0 = infinite */
    /* G_1 from a visibility buffer of the camera view instead of traced
     * camera rays (pixel centres: no pixel jitter, no depth of field). */
    bool direct_visibility;   /* needs a tracer with a visibility function */
    /* Sort each event's live rays (k >= 2) by a key of origin and direction
     * before its trace (glsl/integrator/sort.comp): neighbouring
     * invocations trace neighbouring rays. The image does not change. */
    bool sort_rays;
    /* Called after every sample of a call (done/total of that call; may be NULL). */
    void (*progress)(void *user, int done, int total);
    void *progress_user;
} dirt_pt_opts;

/* The path tracer's passes, in the order of a sample. */
enum dirt_pt_pass {
    DIRT_PT_PASS_RAYGEN,
    DIRT_PT_PASS_VISIBILITY,  /* direct visibility (replaces trace 1) */
    DIRT_PT_PASS_TRACE,       /* closest-hit traces */
    DIRT_PT_PASS_FETCH,
    DIRT_PT_PASS_SHADE,
    DIRT_PT_PASS_SHADOW,      /* any-hit shadow traces */
    DIRT_PT_PASS_RESOLVE,
    DIRT_PT_PASS_ACCUMULATE,
    DIRT_PT_PASS_COMPACT,     /* the live paths of the next event, gathered */
    DIRT_PT_PASS_SORT,        /* and sorted (dirt_pt_opts.sort_rays) */
    DIRT_PT_NUM_PASSES
};

extern const char *const dirt_pt_pass_names[DIRT_PT_NUM_PASSES];

/* Figures of one dirt_pt_add_samples call (or one dirt_pt_render).
 *
 * Pass times never stall the GPU: the frame graph times its passes
 * asynchronously. With the CPU clock (llvmpipe, dirt_gpu_opts.cpu_timing)
 * that changes nothing: glFinish around every pass, each call's times are
 * its own. With the GPU clock (time queries) a pass's result is read only
 * once the GPU has it, one or more samples later, so a call's pass_ms hold
 * the times that arrived during it: typically the earlier calls' last
 * samples and all but its own last ones. The rest arrive at the readback:
 * dirt_pt_read waits for them (it waits for the GPU anyway) and keeps them
 * for dirt_pt_take_late_times; dirt_pt_render adds them itself. Summed over
 * the calls of an accumulation plus the late times, every sample's every
 * pass is counted once. dirt_pt_reset forgets the times still in flight. */
typedef struct dirt_pt_stats {
    double pass_ms[DIRT_PT_NUM_PASSES]; /* summed over samples and events (the
                                           times that arrived, see above) */
    enum dirt_clock clock;    /* what measured them: the clock of the frame graph's
                                 stats (the GPU's one clock, dirt_gpu_clock);
                                 DIRT_CLOCK_NONE when nothing was measured */
    double trace_ms;          /* trace + shadow trace */
    double fetch_ms;
    double visibility_ms;     /* direct visibility */
    double shade_ms;          /* raygen + shade + resolve + compact + accumulate */
    double total_ms;          /* wall time of the call */
    uint64_t rays;            /* rays traced (camera, continuation, shadow) */
    uint64_t aborted;         /* rays whose march gave up (see dirt_trace_stats) */
    double mrays_per_s;       /* rays / trace time */
    uint64_t invalid_samples; /* non-finite samples dropped (dirt_pt_render only) */
    uint64_t bytes_integrator; /* one chunk's rays, hits, shading ring, paths and
                                * ray batches, the image's sums, the tracer's own */
    /* Paths that reached event k (k = 1 .. DIRT_PT_MAX_EVENTS - 1; 0 unused),
     * summed over the samples: after event 1 (every pixel) only these are
     * traced, fetched and shaded (compaction, indirect dispatch). */
    uint64_t paths_at_event[DIRT_PT_MAX_EVENTS];
    int events;               /* events of a sample (K + 1; AO: 1) */
} dirt_pt_stats;

/* Compiles the programs. The scene must outlive it; its materials and
 * textures are uploaded on the first samples. NULL on failure (logged). */
dirt_pt *dirt_pt_create(dirt_gpu *gpu, const dirt_scene *scene);
/* Accepts NULL. */
void dirt_pt_destroy(dirt_pt *pt);

/* The size checks of the scene's tables at `frame` that need no pass (the
 * texels and the tangents in one storage block or a split array:
 * dirt_gpu_model_tables_plan): the engines call it before their build, so
 * a scene they cannot hold fails before any expensive work. False after
 * logging what to change. */
bool dirt_pt_check_frame(dirt_pt *pt, const dirt_frame *frame);

/* Starts a new accumulation of width x height pixels (0 samples). The image
 * is worked through in chunks (wavefronts) of dirt_pt_chunk_pixels pixels,
 * so any size fits the GPU's storage blocks; the pixels do not depend on the
 * chunk size (the random numbers are keyed by image pixel). False (logged)
 * when the buffers cannot be allocated. */
bool dirt_pt_reset(dirt_pt *pt, int width, int height);

/* Pixels per chunk for an image of `pixels` on `gpu`: as many as one storage
 * block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) holds of the largest per-pixel
 * record (the 3-slot shading ring), at most 65535 work groups (GL's least
 * count per dimension), at most `limit` when limit > 0, whole work groups,
 * at most `pixels`. */
size_t dirt_pt_chunk_pixels(const dirt_gpu *gpu, size_t pixels, size_t limit);

/* Test hook: chunks of at most `pixels` (0 = the GPU's limits only; the
 * environment variable DIRT_PT_CHUNK_PIXELS sets it at create). Takes effect
 * at the next dirt_pt_reset, which it requires. */
void dirt_pt_set_chunk_limit(dirt_pt *pt, size_t pixels);

/* Adds `count` samples of `frame` seen from `cam`, traced through `tracer`
 * (the technique's structure built for this frame and camera; borrowed for
 * the call). Sample indices continue from dirt_pt_samples, so the random
 * numbers, and the image, are those of one render of all samples. opts->spp
 * is ignored. `stats` (may be NULL) gets this call's figures. False
 * (logged) before dirt_pt_reset or on GL failure. */
bool dirt_pt_add_samples(dirt_pt *pt, const dirt_tracer *tracer, const dirt_frame *frame,
                         const dirt_camera *cam, const dirt_pt_opts *opts, int count,
                         dirt_pt_stats *stats);

/* Works on the next sample (as dirt_pt_add_samples with count 1) for about
 * `budget_ms` of wall time, in pieces of pixels in pixel order (whole work
 * groups, within a chunk; sized by the pace measured so far; each piece
 * ends with glFinish so that its time is the work's), and returns after
 * the piece that completes the sample or reaches three quarters of the
 * budget (a piece sized for the rest fills it): at least one
 * piece per call; budget 0 (or below) does one smallest piece. The sample
 * spans as many calls as it needs; *completed (may be NULL) says whether
 * this call completed it (dirt_pt_samples grew by one). With direct
 * visibility a piece is a whole chunk. The pixels are those of
 * dirt_pt_add_samples (keyed by pixel, not by piece). While a sample is in
 * progress, dirt_pt_read and dirt_pt_display_texture give the completed
 * samples (a copy of the sums made when it began, 48 B per pixel, kept
 * from the first such sample on); dirt_pt_add_samples completes it first,
 * counted as one of its `count`. `stats` as dirt_pt_add_samples's, for
 * this call's pieces. False (logged) as dirt_pt_add_samples. */
bool dirt_pt_advance(dirt_pt *pt, const dirt_tracer *tracer, const dirt_frame *frame,
                     const dirt_camera *cam, const dirt_pt_opts *opts, double budget_ms,
                     bool *completed, dirt_pt_stats *stats);

/* Pixels of the sample in progress done so far (0: none in progress). */
size_t dirt_pt_part_pixels(const dirt_pt *pt);

/* Samples accumulated since the last reset (completed ones). */
int dirt_pt_samples(const dirt_pt *pt);

/* The mean of the accumulation into `out` (of the accumulation's size):
 * beauty in RGBA (alpha 1) and, when `out` has them, the channels
 * "albedo.R/G/B" and "N.X/Y/Z" (first-hit means) and "Z" (the depth along
 * the camera's forward axis of the first hit of the pinhole ray through the
 * pixel centre, INFINITY where it misses: the Embree reference's Z, traced
 * once per accumulation through the tracer) and "ID" (that hit's primitive
 * as a float, -1 where it misses). `invalid_samples` (may be
 * NULL) gets the non-finite samples dropped. Blocking readback; then the
 * pass times still in flight are drained (dirt_pt_take_late_times). False
 * (logged) with no samples or a size mismatch. */
bool dirt_pt_read(dirt_pt *pt, dirt_image *out, uint64_t *invalid_samples);

/* The pass times that came after the dirt_pt_add_samples call that issued
 * them (see dirt_pt_stats): with `wait`, first waits for every one still in
 * flight (dirt_pt_read did that for the samples it read). Fills late's
 * pass_ms, clock (DIRT_CLOCK_NONE when none came late) and the per-kind
 * sums (trace_ms, fetch_ms, visibility_ms, shade_ms); the rest is 0. Each
 * time is given once: they are forgotten here. */
void dirt_pt_take_late_times(dirt_pt *pt, bool wait, dirt_pt_stats *late);
/* Adds late times (dirt_pt_take_late_times) to the figures `st`: pass_ms,
 * the per-kind sums, clock, mrays_per_s. */
void dirt_pt_add_late_times(dirt_pt_stats *st, const dirt_pt_stats *late);

/* The same mean beauty in an RGBA32F texture (GL name; texel (x, y) = image
 * pixel (x, y), row 0 = top; alpha 1), updated on the GPU when samples were
 * added: the pixels equal dirt_pt_read's. Owned by `pt`, valid until the
 * next reset to another size or destroy. 0 (logged) with no samples. No
 * readback and no wait: the pass times keep arriving with later calls. */
uint32_t dirt_pt_display_texture(dirt_pt *pt);

/* One render: reset to out's size, opts->spp samples (default 1), read;
 * `stats` include the late pass times (complete). */
bool dirt_pt_render(dirt_pt *pt, const dirt_tracer *tracer, const dirt_frame *frame,
                    const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                    dirt_pt_stats *stats);

/* The integrator's buffers (and the tracer's own, when `tracer` is given)
 * for the current accumulation size, and the scene's texel buffer ("model
 * texels", once samples were added): at most `max` records into `out`;
 * returns how many. */
int dirt_pt_buffers(const dirt_pt *pt, const dirt_tracer *tracer, dirt_buffer_bytes *out,
                    int max);

/* DOT of the last frame graph; false before the first samples. */
bool dirt_pt_write_dot(const dirt_pt *pt, const char *path);

#ifdef __cplusplus
}
#endif
#endif
