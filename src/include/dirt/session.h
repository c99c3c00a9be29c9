/* DIRT engine: the render session every program uses.
 *
 * A session renders one scene through one engine: it owns the evaluated
 * frame (time, clip, loop), the camera, the technique (the DIRT structure,
 * the MMRT A-buffer, the Embree reference or the raster preview), the path
 * tracer and its accumulation, and the result image; it borrows the GPU and
 * the scene, which must outlive it. Rendering is progressive: samples are
 * added to the accumulation until something that changes the image (time,
 * camera, options) restarts it. The structure is rebuilt only when the
 * frame, the camera or its own options change.
 *
 * Typical use (examples/render.c is a whole program):
 *   dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){0});  // headless EGL
 *   dirt_scene *scene = dirt_scene_create_default();
 *   dirt_session *s = dirt_session_create(gpu, scene, &(dirt_session_opts){.seed = 3});
 *   dirt_session_set_time(s, 0.5, NULL);                // restarts the accumulation
 *   dirt_session_add_samples(s, 16, NULL, NULL);        // progressive: add more later
 *   const dirt_image *img = dirt_session_image(s);      // beauty + AOVs
 *   const dirt_session_stats *st = dirt_session_get_stats(s);
 *   dirt_session_destroy(s);
 *   dirt_scene_destroy(scene);
 *   dirt_gpu_destroy(gpu);
 * A call that fails logs why and returns false, NULL or 0;
 * dirt_session_last_error() tells the reason as an id.
 */
#ifndef DIRT_SESSION_H
#define DIRT_SESSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/api.h"
#include "dirt/env.h"
#include "dirt/gpu.h"
#include "dirt/image.h"
#include "dirt/scene.h"
#include "dirt/stats.h"
#include "dirt/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_session dirt_session;

/* Why a session call failed: one X-macro list gives the enum
 * (DIRT_SESSION_ERR_<id>), the messages (dirt_session_error_str) and the
 * names (dirt_session_error_name) the tests and the Python module use. */
#define DIRT_SESSION_ERRORS(X)                                                          \
    X(OK, "ok")                                                                         \
    X(ARGUMENT, "a missing argument (no scene, no camera, no path) or a bad count")     \
    X(OPTION, "an option out of range or contradicting another (dirt_session_check_opts)") \
    X(NO_GPU, "a GPU engine (dirt, mmrt, raster) or a display without a GPU")           \
    X(CAMERA, "no such camera in the scene")                                            \
    X(CLIP, "no such animation clip in the scene")                                      \
    X(NOT_READY, "nothing to give yet: no samples, or no structure built")              \
    X(UNSUPPORTED, "the engine has no such thing (a structure, pictures, a frame graph)") \
    X(IO, "a file cannot be written")                                                   \
    X(OUT_OF_MEMORY, "out of memory")                                                   \
    X(RENDER, "the engine failed: a GPU limit, a GL error, a shader (the log says which)")

enum dirt_session_error {
#define DIRT_SESSION_ERR_ENUM_(id, msg) DIRT_SESSION_ERR_##id,
    DIRT_SESSION_ERRORS(DIRT_SESSION_ERR_ENUM_)
#undef DIRT_SESSION_ERR_ENUM_
    DIRT_SESSION_NUM_ERRORS
};

/* The outcome of this thread's last call of a session function that can
 * fail (those returning bool, a pointer or a texture name, and
 * dirt_session_check_opts): DIRT_SESSION_ERR_OK after a success, else the
 * reason (the log says more). */
DIRT_API enum dirt_session_error dirt_session_last_error(void);
/* "ok", "no such camera in the scene", ...; "?" out of range. */
DIRT_API const char *dirt_session_error_str(enum dirt_session_error e);
/* "OK", "CAMERA", ...: the id's name. */
DIRT_API const char *dirt_session_error_name(enum dirt_session_error e);

enum dirt_engine {
    DIRT_ENGINE_DIRT = 0,  /* path tracing through the DIRT structure (GPU) */
    DIRT_ENGINE_MMRT,      /* the same path tracer through the MMRT A-buffer (GPU) */
    DIRT_ENGINE_EMBREE,    /* the CPU ground truth (Embree 3) */
    DIRT_ENGINE_RASTER,    /* rasterized preview with direct lighting (GPU) */
    DIRT_NUM_ENGINES
};

DIRT_API extern const char *const dirt_engine_names[DIRT_NUM_ENGINES]; /* "dirt", "mmrt", ... */

/* How DIRT's structure is built (doc/dirt-build.md; both give the same
 * lists). AUTO: by measurement per device (dirt_session_auto_build). */
enum dirt_session_build {
    DIRT_SESSION_BUILD_AUTO = 0,
    DIRT_SESSION_BUILD_RASTER,  /* DIRT_BUILD_RASTER */
    DIRT_SESSION_BUILD_COMPUTE, /* DIRT_BUILD_COMPUTE */
};

/* The build AUTO picks on `gpu` (NULL: raster): the compute build on a
 * software renderer (llvmpipe: measured 1.0-2.2x faster for the whole
 * build, perf/results/build-compute-llvmpipe.md; the faster build in 71 of
 * 72 cells of perf/results/defaults-llvmpipe.md), the raster build
 * (the paper's pipeline, hardware conservative raster) on a hardware GPU
 * until a measurement there says otherwise (perf/gpu-check.sh measures
 * both). The environment variable DIRT_BUILD=raster|compute overrides it
 * (dirt_build_from_env). */
DIRT_API enum dirt_build_mode dirt_session_auto_build(const dirt_gpu *gpu);

/* DIRT's bucket count when dirt_session_opts.buckets is 0, on `gpu` (NULL:
 * 16): 8 on a software renderer (llvmpipe: the best whole frame at S = 2
 * in the geometric mean over the shared and default scenes, in three
 * interleaved runs of perf/bench-defaults.py, perf/results/
 * defaults-llvmpipe.md), 16 (the authors' demo's) on a hardware GPU until
 * a measurement there says otherwise. */
DIRT_API int dirt_session_auto_buckets(const dirt_gpu *gpu);

/* Views of the structure; DEFAULT = camera view and cube faces. */
enum dirt_session_views {
    DIRT_SESSION_VIEWS_DEFAULT = 0,
    DIRT_SESSION_VIEWS_SINGLE,
    DIRT_SESSION_VIEWS_CUBE,
    DIRT_SESSION_VIEWS_CUBE_CAMERA,
};

/* Zero-initialised = the defaults named per field. */
typedef struct dirt_session_opts {
    enum dirt_engine engine;    /* default dirt */
    int width;                  /* image width (default 640) */
    int height;                 /* 0 = width / the camera's aspect (4:3 when it has none) */
    /* the structure (dirt and mmrt) */
    enum dirt_session_views views;
    int face_size;              /* cube face pixels (0 = max(width, height) / 2) */
    int tile_size;              /* DIRT's S in {1, 2, 4, 8} (0 = 2; MMRT is per pixel) */
    int buckets;                /* 0 = dirt_session_auto_buckets for dirt (8 on a software
                                   renderer, 16 on a GPU), 4 for mmrt (the MMRT paper's) */
    bool force_emulation;       /* dirt: ignore GL_NV_conservative_raster */
    enum dirt_session_build build; /* dirt: how the structure is built (same structure) */
    enum dirt_depth_buckets depth_buckets; /* dirt: uniform (default) or adaptive bucket
                                   edges per tile (doc/dirt-build.md; B <= 1024) */
    int large;                  /* dirt: large primitives tested by every ray instead of
                                   listed (doc/dirt-trace.md): 0 = up to 16, < 0 = none,
                                   n = up to n (at most 16) */
    bool large_grid;            /* dirt: the large primitives are tested through a grid
                                   of their own (doc/dirt-trace.md, "The large
                                   primitives' grid"): far fewer triangle tests per ray,
                                   more march steps; the same hits and image. false
                                   (default): every ray tests every large primitive */
    bool sub_tiles;             /* dirt: every list node carries the 4 x 4 sub-tile cells
                                   its primitive may cover, and rays skip the nodes whose
                                   cells their segment in the tile misses
                                   (doc/dirt-build.md, "Sub-tile rectangles"): fewer
                                   triangle tests per ray; the same hits and image; scenes
                                   below 2^24 triangles. false (default): plain lists */
    bool bucket_masks;          /* dirt: one word per tile marks which of 32 depth slabs
                                   of the tile hold a primitive (with adaptive buckets:
                                   which buckets hold nodes; B <= 32), and rays skip the
                                   tiles with nothing in their depth span
                                   (doc/dirt-build.md, "Pass 3"): fewer tiles walked; the
                                   same hits and image. false (default): no masks (on
                                   llvmpipe they cost 3-6 % of the frame) */
    bool node_depths;           /* dirt: every list node carries its primitive's depth
                                   range in its bucket (16 sub-slabs, in the node's next
                                   word), and rays skip the nodes whose range their depth
                                   span in the tile misses (doc/dirt-build.md, "Node
                                   depth ranges"): fewer triangle tests per ray, no
                                   memory; the same hits and image; B <= 4095. false
                                   (default): plain lists */
    int hiz_levels;             /* 0 = the whole pyramid; n: levels 0 .. n-1 */
    enum dirt_fetch_mode fetch; /* dirt: compute (default) or raster Fetch */
    bool direct_visibility;     /* dirt: first hits from a visibility buffer */
    enum dirt_mmrt_march march; /* mmrt: Hi-Z (default) or linear */
    int march_samples;          /* mmrt linear: samples per view (0 = 30) */
    float thickness;            /* mmrt: 0 = 0.2 % of the scene's diagonal */
    /* light transport (every engine but raster) */
    enum dirt_pt_mode mode;     /* path tracing (default) or AO */
    int bounces;                /* 0 = 4 */
    uint32_t seed;
    float background[3];        /* the constant environment (unless `env`) */
    const dirt_env *env;        /* environment light (dirt/env.h; borrowed:
                                   it must outlive its use in the session;
                                   NULL = the background) */
    float ao_distance;          /* 0 = infinite */
    float aperture;             /* thin-lens radius (0 = pinhole) */
    float focus;                /* focus distance (0 = distance to the scene centre) */
    int threads;                /* embree: CPU threads (0 = all) */
    /* Work counters (doc/dirt-trace.md, "Work counters"): after each build,
     * the hit-agreement rays of every ray type (the camera G-buffer at the
     * image size, this seed) are traced by the counting build of the
     * engine's trace and by a counting walk of Embree's BVH, into
     * dirt_session_stats.work. The image does not change. dirt, mmrt and
     * embree (its BVH's counts only). */
    bool count_work;
    /* dirt and mmrt path tracing: sort each event's live rays (after the
     * first) by a key of origin and direction before tracing them, so that
     * neighbouring GPU invocations trace neighbouring rays (doc/light-
     * transport-gpu.md, "Ray sort"). The image does not change. */
    bool sort_rays;
    /* Times: the GPU engines' come with the GPU's one clock (dirt_gpu_clock;
     * the CPU clock on a GPU needs dirt_gpu_opts.cpu_timing); Embree's are
     * CPU times. */
} dirt_session_opts;

/* True when `opts` are valid (the checks dirt_session_create and
 * dirt_session_set_opts make, except that a GPU engine needs a GPU); else
 * false with the reason in `why` (may be NULL; one line, no prefix). */
DIRT_API bool dirt_session_check_opts(const dirt_session_opts *opts, char *why, size_t size);

/* Which camera the session looks through. */
enum dirt_camera_choice {
    DIRT_CAMERA_DEFAULT = 0,    /* the scene's camera 0, or automatic without cameras */
    DIRT_CAMERA_SCENE,          /* the scene's camera `index` */
    DIRT_CAMERA_AUTO,           /* frames the whole animation clip, the same at every time */
    DIRT_CAMERA_EXPLICIT,       /* a camera given by the application */
};

/* The work of one ray type's rays, summed over the rays (counted, not
 * timed: what carries over to any GPU). Each engine fills its own. */
typedef struct dirt_session_work {
    uint64_t rays;
    uint64_t triangle_tests;  /* exact ray-triangle tests (dirt, embree; 0 for mmrt,
                                 which tests fragments' depths instead) */
    uint64_t tiles;           /* dirt: tiles whose bucket lists were walked */
    uint64_t hiz_steps;       /* dirt, mmrt: march steps (cells of any level looked at) */
    uint64_t list_nodes;      /* dirt: list nodes read */
    uint64_t fragments;       /* mmrt: fragments visited (each one depth test) */
    uint64_t pixels;          /* mmrt: pixel lists tested */
    uint64_t bvh_nodes;       /* embree: BVH nodes visited */
} dirt_session_work;

/* Figures of the accumulation since the last restart (times and rays add
 * up over dirt_session_add_samples calls; the build's are the last build's).
 * The path tracer's pass times may lag:
 * with the GPU clock (time queries) no sample waits for its times, so after
 * dirt_session_add_samples they hold the times the GPU had delivered by
 * then, and the last samples' come later: with the next calls (a viewer
 * showing the display texture sees them late, never stalling for them), or
 * at dirt_session_image, whose readback waits for the GPU and completes them,
 * or at dirt_session_drain_times. After either, the totals are complete.
 * The CPU clock (llvmpipe, cpu_timing) and the build's passes never lag. */
typedef struct dirt_session_stats {
    enum dirt_engine engine;
    char device[256];           /* the GL renderer, or "CPU" */
    int width, height;
    int samples;                /* accumulated */
    int bounces;
    enum dirt_pt_mode mode;
    uint32_t seed;              /* dirt_session_opts.seed */
    double time;                /* scene time of the frame */
    double build_ms;            /* the structure's last build (embree: BVH) */
    double trace_ms, fetch_ms, visibility_ms, shade_ms;
    double total_ms;            /* wall time of the calls, build included */
    uint64_t rays, aborted, invalid_samples;
    double mrays_per_s;
    /* Paths that reached event k = 1 .. events (the path tracers: dirt,
     * mmrt, embree; summed over the samples): what the GPU engines trace
     * after event 1 (compaction). 0 events for the raster preview. */
    int events;
    uint64_t paths_at_event[DIRT_MAX_EVENTS];
    int num_passes;
    dirt_pass_time passes[32];  /* build passes, then the path tracer's */
    int num_build_passes;       /* passes[0 .. num_build_passes) are the last build's (its
                                   times, not summed over the samples); the rest add up
                                   over the accumulation */
    int num_buffers;
    dirt_buffer_bytes buffers[24];
    uint64_t bytes_total_used, bytes_total_allocated;
    /* The technique's own figures (the DIRT and MMRT papers' tables). */
    bool has_ads;
    dirt_ads_stats ads;
    bool has_mmrt;
    dirt_mmrt_stats mmrt;
    /* With dirt_session_opts.count_work: the work of the last build's
     * structure per ray type (enum dirt_ray_type), and Embree's BVH over
     * the same rays (for the embree engine the two are the same). */
    bool has_work;
    dirt_session_work work[DIRT_RAY_TYPES];
    dirt_session_work embree_work[DIRT_RAY_TYPES];
} dirt_session_stats;

/* A session on `scene` (and `gpu`, which may be NULL for the embree engine
 * only). Evaluates time 0 of clip 0 and takes the default camera. NULL after
 * logging on bad options or when the engine cannot be made. */
DIRT_API dirt_session *dirt_session_create(dirt_gpu *gpu, const dirt_scene *scene,
                                           const dirt_session_opts *opts);
/* Accepts NULL. */
DIRT_API void dirt_session_destroy(dirt_session *s);

/* Sets the options. Rebuilds only what they touch (engine objects, the
 * structure, the integrator state). *restarted (may be NULL) says whether the
 * accumulation restarts (it does for any change that alters the image).
 * False after logging on bad options; the session keeps the old ones. */
DIRT_API bool dirt_session_set_opts(dirt_session *s, const dirt_session_opts *opts, bool *restarted);
DIRT_API const dirt_session_opts *dirt_session_get_opts(const dirt_session *s);

/* Evaluates the scene at `time` seconds of `eval` (clip, loop; NULL = clip 0,
 * clamped). Restarts the accumulation. False after logging (bad clip). */
DIRT_API bool dirt_session_set_time(dirt_session *s, double time, const dirt_eval_opts *eval);
DIRT_API const dirt_frame *dirt_session_frame(const dirt_session *s);

/* Chooses the camera: `index` is the scene camera for DIRT_CAMERA_SCENE,
 * `cam` the camera for DIRT_CAMERA_EXPLICIT (else ignored, may be NULL).
 * Restarts the accumulation. False after logging (no such camera). */
DIRT_API bool dirt_session_set_camera(dirt_session *s, enum dirt_camera_choice choice, int index,
                                      const dirt_camera *cam);
/* The camera in use at the current time (aperture and focus applied). */
DIRT_API const dirt_camera *dirt_session_camera(const dirt_session *s);

/* Image size in use (height resolved from the camera's aspect). */
DIRT_API void dirt_session_size(const dirt_session *s, int *width, int *height);

/* Builds the technique's structure for the current frame, camera and
 * options now (dirt_session_add_samples does it when needed). */
DIRT_API bool dirt_session_build(dirt_session *s);

/* Restarts the accumulation (0 samples). */
DIRT_API void dirt_session_reset(dirt_session *s);
/* Adds `count` samples (raster: renders the preview; count is ignored),
 * building the structure first when the frame, camera or options changed.
 * `progress` (may be NULL) is called after every sample. False after
 * logging on failure. */
DIRT_API bool dirt_session_add_samples(dirt_session *s, int count,
                                       void (*progress)(void *user, int done, int total), void *user);
/* Works on the next sample for about `budget_ms` milliseconds of wall time
 * and returns (a bounded slice of work, for a program that must answer
 * its user between slices): the path tracers (dirt, mmrt) trace a sample
 * in pieces of pixels, sized by the pace measured so far, and stop after
 * the piece that reaches the budget or completes the sample, so one sample
 * may span many calls; budget 0 does one smallest piece (whole work
 * groups). The structure is built first when needed (dirt_session_build,
 * not split). The other engines (embree, raster) add one whole sample per
 * call. *completed (may be NULL) says whether this call completed a sample
 * (dirt_session_samples grew by one). The pixels are those of
 * dirt_session_add_samples, bit for bit: N samples made by any mix of
 * calls equal one render of N. While a sample is in progress,
 * dirt_session_samples, dirt_session_image and dirt_session_display_texture
 * give the completed samples only (the path tracers keep a copy of their
 * sums when a sample begins: 48 bytes per pixel more, from the first split
 * sample on), and dirt_session_add_samples completes it first (as one of
 * its `count`). A restart drops it. False after logging on failure
 * (ARGUMENT for a negative or NaN budget). */
DIRT_API bool dirt_session_advance(dirt_session *s, double budget_ms, bool *completed);
/* The part of the sample in progress done, in [0, 1): 0 when none is in
 * progress (and for the engines that do not split a sample). */
DIRT_API double dirt_session_sample_part(const dirt_session *s);
/* Completed samples in the accumulation. */
DIRT_API int dirt_session_samples(const dirt_session *s);

/* The accumulated image: RGBA beauty (the mean) and the engine's AOVs
 * (dirt, mmrt, embree: "albedo.R/G/B", "N.X/Y/Z", "Z" and "ID": the depth
 * and primitive of the pinhole ray through the pixel centre, -1 on a miss;
 * raster: "N.X/Y/Z", "Z"). Owned by
 * the session, valid until the next call that changes it. NULL (logged)
 * before any sample or on a readback failure. */
DIRT_API const dirt_image *dirt_session_image(dirt_session *s);

/* Writes the accumulated image (dirt_session_image: beauty and AOVs) to
 * `path` by its extension, .exr or .png (dirt_image_write; `opts` may be
 * NULL), atomically. False (logged) with no samples (NOT_READY) or when the
 * file cannot be written (IO). */
DIRT_API bool dirt_session_write_image(dirt_session *s, const char *path,
                                       const dirt_image_write_options *opts);

/* The beauty as an RGBA32F GL texture (texel (x, y) = pixel (x, y), row 0 =
 * top) for display: on the GPU engines it never leaves the GPU; embree's
 * image is uploaded. Owned by the session. 0 (logged) before any sample. */
DIRT_API uint32_t dirt_session_display_texture(dirt_session *s);

DIRT_API const dirt_session_stats *dirt_session_get_stats(const dirt_session *s);
/* Waits for the path tracer's pass times still in flight and adds them to
 * the stats (dirt_session_image does it with its readback): for a caller
 * that reads the figures of every call without reading the image back. */
DIRT_API void dirt_session_drain_times(dirt_session *s);

/* Writes a stats document as JSON (through cJSON), atomically: the
 * figures of `frames[count - 1]`'s run (engine, device, size, samples),
 * their means, and every frame's record in "frames". False after logging
 * when the file cannot be written. */
DIRT_API bool dirt_session_write_stats(const char *path, const dirt_session_stats *frames, size_t count);
/* The same with an object "provenance" of the `num_attrs` text attributes
 * (what made the frames: the ones the programs write into their EXR
 * headers, dirt/image.h), each name a key. */
DIRT_API bool dirt_session_write_stats_attrs(const char *path, const dirt_session_stats *frames,
                                             size_t count, const dirt_image_attr *attrs,
                                             size_t num_attrs);

/* One stats record as a cJSON object (the "frames" entries of
 * dirt_session_write_stats), owned by the caller (cJSON_Delete). NULL when
 * out of memory. */
struct cJSON;
DIRT_API struct cJSON *dirt_session_stats_json(const dirt_session_stats *stats);

/* Frame graph DOT of the path tracer (dirt, mmrt). False (logged) before
 * the first samples or for the engines without a path tracer (embree,
 * raster). */
DIRT_API bool dirt_session_write_graph_dot(const dirt_session *s, const char *path);

/* Writes the DIRT structure of the current frame (built first when
 * needed) as pictures into the directory `dir`, which must exist: per view
 * <dir>/ads_v<i>_<name>_lists.png (heat map of the list length per tile),
 * _zmin.png and _zmax.png (depth bounds), and <dir>/ads_graph.dot (the
 * build's frame graph); unless `quiet`, prints the build's figures (counts,
 * bytes against the DIRT paper's Table 3, pass times) on stderr and the
 * file names on stdout. False (logged) for engines other than dirt, or when
 * the build or a file fails. */
DIRT_API bool dirt_session_write_debug_ads(dirt_session *s, const char *dir, bool quiet);

/* Pictures of the last build's structure, one value per DIRT tile or MMRT
 * pixel in R (A = 1 where a view covers the picture, else 0; G = B = 0),
 * every view in one image: the cube faces unfolded as a cross (+Y above;
 * -X, +Z, +X, -Z across; -Y below), the camera view right of it. */
enum dirt_session_picture {
    DIRT_PICTURE_LISTS = 0,   /* list length summed over the buckets (MMRT:
                                 fragments per pixel) */
    DIRT_PICTURE_BUCKETS,     /* buckets holding at least one entry */
    DIRT_PICTURE_ZMIN,        /* depth bounds, 0 at the view's near plane, 1 at */
    DIRT_PICTURE_ZMAX,        /*   its far plane; NaN for empty cells */
};
/* A new image (caller destroys it); *max (may be NULL) gets the range's
 * top: the longest list, the number of buckets, or 1 for depths. Blocking
 * readback. NULL (logged) before a build or for embree and raster. */
DIRT_API dirt_image *dirt_session_picture(dirt_session *s, enum dirt_session_picture what, float *max);

/* The scene the session renders (borrowed). */
DIRT_API const dirt_scene *dirt_session_scene(const dirt_session *s);

/* Hit agreement with Embree per ray type (enum dirt_ray_type) of the DIRT
 * structure or MMRT A-buffer of the session's last build, on the rays of a
 * width x height camera G-buffer of the session's frame and camera (seed).
 * The rays and the criteria are those of the tests gpu/dirt_hits (DIRT: the
 * same primitive, or the same t within 1e-4 relative, or both missing;
 * visibility: both hit or both miss) and gpu/mmrt_hits (MMRT: secondary rays
 * start, and visibility rays end, 3 thicknesses off the surface; the same
 * primitive or both missing; visibility against Embree's occlusion). Also
 * the trace time per ray type (one batch each, the GPU's clock). */
typedef struct dirt_session_agreement {
    uint64_t rays[DIRT_RAY_TYPES];
    uint64_t same[DIRT_RAY_TYPES];
    double fraction[DIRT_RAY_TYPES];  /* same / rays (NAN without rays) */
    double ms[DIRT_RAY_TYPES];        /* the trace of the batch (-1 unmeasured) */
    enum dirt_clock clock;
    uint64_t aborted;                 /* rays whose march ran out of steps */
    float thickness;                  /* mmrt: the thickness used (else 0) */
} dirt_session_agreement;

/* False after logging (not built, not dirt/mmrt, out of memory, GL). */
DIRT_API bool dirt_session_hit_agreement(dirt_session *s, int width, int height, uint32_t seed,
                                         dirt_session_agreement *out);

#ifdef __cplusplus
}
#endif
#endif
