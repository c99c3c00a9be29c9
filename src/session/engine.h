/* The engines under the render session: one table of operations each
 * engine implements (engine_dirt.c, engine_mmrt.c, engine_embree.c,
 * engine_raster.c; the path tracer's half of dirt and mmrt in
 * engine_pt.c). The session (session.c) keeps the time, the camera, the
 * image size, the restart rules and the common stats, and reaches an
 * engine only through its table: it never asks which engine it has.
 *
 * An engine owns what it makes (its structure, its tracer, its image, its
 * display texture) and borrows what the session lends it in an engine_env
 * for the length of one call. */
#ifndef DIRT_SESSION_ENGINE_H
#define DIRT_SESSION_ENGINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/ads.h"
#include "dirt/image.h"
#include "mmrt/mmrt.h"
#include "core/ray.h"
#include "ref/ref.h"
#include "dirt/session.h"
#include "dirt/stats.h"
#include "session/session_internal.h"

/* An engine's state: each engine's file defines what it holds. */
typedef struct engine engine;

/* What the session lends an engine for one call. */
typedef struct engine_env {
    dirt_gpu *gpu;                 /* NULL only for an engine that needs none */
    const dirt_scene *scene;
    const dirt_session_opts *opts; /* checked (dirt_session_check_opts) */
    const dirt_frame *frame;       /* the evaluated frame */
    const dirt_camera *cam;        /* the camera in use, lens applied */
    int width, height;             /* the image size in use */
    int samples;                   /* samples accumulated before the call */
} engine_env;

/* Progress callback of dirt_session_add_samples. */
typedef void (*engine_progress_fn)(void *user, int done, int total);

/* Per-cell figures of a structure, for dirt_session_picture: list lengths
 * summed over the buckets, non-empty buckets and the level-0 depth bounds
 * of `count` cells (DIRT tiles, MMRT pixels) laid out by `set`. The arrays
 * are the caller's to free (engine_cells_free). */
typedef struct engine_cells {
    const dirt_view_set *set;
    int count, buckets;
    uint32_t *len, *used;
    float (*depth)[2];
} engine_cells;

/* One batch of dirt_session_hit_agreement: `count` rays of `type` from the
 * camera G-buffer, traced by the engine's structure and compared with
 * Embree (`accel`, the session's frame). `hits`, `ref` and `occluded` are
 * scratch of `count` records each. */
typedef struct engine_agree {
    const dirt_ref_accel *accel;
    enum dirt_ray_type type;
    dirt_ray *rays;                /* the engine may move their ends (MMRT's offsets) */
    size_t count;
    dirt_hit *hits;
    dirt_ref_hit *ref;
    unsigned char *occluded;
    float thickness;               /* in: the primary batch's (MMRT), out: this batch's */
    bool count_work;               /* in: trace with the counting build, into `work` */
    /* out */
    dirt_session_work work;        /* rays and the engine's counts (count_work) */
    size_t same;                   /* rays whose hits agree */
    double ms;                     /* the trace of the batch */
    enum dirt_clock clock;
    uint64_t aborted;
} engine_agree;

/* The operations. Those marked "may be NULL" are missing where the engine
 * has no such thing; the session then says so (logged) and fails.
 *
 * Error ids (dirt_session_last_error): the session begins each public
 * call's record and records RENDER when an operation fails. An operation
 * that knows a more precise reason records it first with session_fail
 * (session_internal.h): OUT_OF_MEMORY, NO_GPU, IO, ...; the first id of a
 * call stays. */
typedef struct engine_ops {
    bool needs_gpu;
    /* Checks of the options that only this engine makes (beyond the
     * common ones of dirt_session_check_opts): false with the reason in
     * `why` (one line). May be NULL. */
    bool (*check_opts)(const dirt_session_opts *o, char *why, size_t size);
    /* Makes the engine for env's options and size. NULL after logging. */
    engine *(*create)(const engine_env *env);
    /* Accepts NULL. */
    void (*destroy)(engine *e);
    /* The options that shape the structure (image size, views, face size,
     * tile size, buckets, build, large primitives, conservative raster)
     * changed: remakes what depends on them and keeps the rest (the path
     * tracer and its programs). The image starts over. False after
     * logging; the engine may then only be destroyed. */
    bool (*reshape)(engine *e, const engine_env *env);
    /* Builds the structure for env's frame, camera and options (the tracer
     * options included). False after logging. */
    bool (*build)(engine *e, const engine_env *env);
    /* Adds the last build's passes, buffers and the technique's figures
     * to `st` (the session cleared them). */
    void (*build_stats)(engine *e, dirt_session_stats *st);
    /* The accumulation restarts (0 samples): what the engine holds of the
     * old one is stale. */
    void (*restart)(engine *e);
    /* Adds `count` samples to the accumulation (env->samples so far; the
     * raster preview renders once, whatever the count), adds their figures
     * to `st` and sets *samples to the new total. `progress` (may be NULL)
     * after every sample. False after logging. */
    bool (*add_samples)(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                        void *user, dirt_session_stats *st, int *samples);
    /* Works on the next sample for about `budget_ms` (dirt_session_advance):
     * adds the call's figures to `st`, sets *samples to the completed
     * samples and *completed to whether this call completed one. The
     * image and display give the completed samples only. May be NULL: the
     * session adds one whole sample instead. */
    bool (*advance)(engine *e, const engine_env *env, double budget_ms, dirt_session_stats *st,
                    int *samples, bool *completed);
    /* The part of the sample in progress done, in [0, 1) (0: none). May be
     * NULL (never one in progress). */
    double (*part)(const engine *e, const engine_env *env);
    /* The accumulated image (beauty + the engine's AOVs), owned by the
     * engine; its late pass times go to `st`. NULL after logging. */
    const dirt_image *(*image)(engine *e, const engine_env *env, dirt_session_stats *st);
    /* The beauty as an RGBA32F GL texture, owned by the engine. 0 after
     * logging. */
    uint32_t (*display_texture)(engine *e, const engine_env *env);
    /* Adds pass times still to come (with `wait`, also those in flight) to
     * `st`. May be NULL (times never come late). */
    void (*late_times)(engine *e, const engine_env *env, bool wait, dirt_session_stats *st);
    /* The path tracer's frame graph as DOT. May be NULL. */
    bool (*write_graph_dot)(const engine *e, const char *path);
    /* The DIRT structure or MMRT A-buffer (built). May be NULL. */
    dirt_ads *(*ads)(engine *e);
    dirt_mmrt *(*mmrt)(engine *e);
    /* The per-cell figures of the built structure (blocking readback).
     * False after logging. May be NULL. */
    bool (*cells)(engine *e, engine_cells *out);
    /* Traces one hit-agreement batch. False after logging. May be NULL. */
    bool (*agree)(engine *e, const engine_env *env, engine_agree *batch);
} engine_ops;

extern const engine_ops engine_dirt_ops, engine_mmrt_ops, engine_embree_ops, engine_raster_ops;
/* The table of engine e is session_engines[e]. */
extern const engine_ops *const session_engines[DIRT_NUM_ENGINES];

/* ---- shared by the engines (engine.c) ---- */

/* A pass time as the session adds it up: 0 when it was not measured. */
double engine_measured_ms(double ms, enum dirt_clock clock);
/* Adds `ms` to the pass `name` (static string) or appends it. */
void engine_add_pass(dirt_session_stats *st, const char *name, double ms, enum dirt_clock clock);
/* Appends a buffer and adds it to the totals. */
void engine_add_buffer(dirt_session_stats *st, const char *name, uint64_t used,
                       uint64_t allocated);
/* Adds a render's paths per event (k = 1 .. events). */
void engine_add_paths_at_event(dirt_session_stats *st, const uint64_t *paths, int events);

/* A new width x height image with the extra channels `names` (n of them).
 * NULL after logging. */
dirt_image *engine_new_image(int width, int height, const char *const *names, int n);
/* The path tracers' AOVs, in the order their images hold them. */
extern const char *const engine_pt_aovs[8];

/* A CPU image shown through an uploaded RGBA32F texture. */
typedef struct engine_display {
    uint32_t texture;
    int width, height;
    bool current;                  /* holds the image's present pixels */
} engine_display;
/* Uploads `img`'s beauty when it is not current; the texture, or 0 after
 * logging (no GPU, GL failure). */
uint32_t engine_display_upload(engine_display *d, dirt_gpu *gpu, const dirt_image *img);
void engine_display_release(engine_display *d);

/* The structure's views for env's options and size (tile size 0 = 2). */
dirt_view_opts engine_view_opts(const engine_env *env);

/* The lists of a bucketed structure read back: `count` cells, `buckets`
 * lists each (heads bucket-major, `end` ends a list), node n's successor
 * at next[n * next_stride] (num_nodes nodes; a link past them ends the
 * list), depth bounds per cell. Fills c's len, used and depth (set stays
 * the caller's); false after logging (out of memory), c then freed. */
bool engine_cells_from_lists(engine_cells *c, int count, int buckets, const uint32_t *heads,
                             const uint32_t *next, size_t next_stride, uint32_t num_nodes,
                             uint32_t end, const float (*depth)[2]);
/* Frees the arrays of `c`. */
void engine_cells_free(engine_cells *c);

/* ---- for the session's other files (pictures.c, agreement.c) ---- */

/* The engine of the session's last build with its table and the env of a
 * call now; NULL when nothing is built. */
engine *session_built_engine(dirt_session *s, const engine_ops **ops, engine_env *env);

#endif
