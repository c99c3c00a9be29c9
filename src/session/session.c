/* The render session: scene + time + camera + image size + an engine (its
 * table of operations, engine.h) + progressive accumulation + stats. What
 * differs between the engines lives behind that table; here are the rules
 * every engine follows: what restarts the accumulation, what remakes or
 * rebuilds the engine, and the common figures. */
#include "dirt/session.h"
#include "common/constants.h"
#include "common/layout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/clock.h"
#include "dirt/log.h"
#include "integrator/integrator.h"
#include "session/engine.h"
#include "session/session_internal.h"

const char *const dirt_engine_names[DIRT_NUM_ENGINES] = {"dirt", "mmrt", "embree", "raster"};

struct dirt_session {
    dirt_gpu *gpu;
    char gpu_desc[256];       /* dirt_gpu_describe, made once */
    const dirt_scene *scene;
    dirt_session_opts opts;
    /* frame and camera */
    dirt_frame *frame;
    double time;
    dirt_eval_opts eval;
    enum dirt_camera_choice cam_choice;
    int cam_index;
    dirt_camera cam_explicit;
    bool have_clip_cam;       /* clip_cam frames the clip of `eval` */
    dirt_camera clip_cam;
    dirt_camera cam;          /* in use: choice at this time, lens applied */
    int width, height;
    /* the engine */
    const engine_ops *ops;    /* session_engines[opts.engine] */
    engine *engine;
    bool built;               /* the structure matches frame, camera and options */
    /* the accumulation */
    int samples;
    dirt_session_stats stats;
};

bool dirt_session_check_opts(const dirt_session_opts *o, char *why, size_t size)
{
    session_begin();
    char local[8];
    if (!why) {
        why = local;
        size = sizeof(local);
    }
    if ((unsigned)o->engine >= DIRT_NUM_ENGINES)
        snprintf(why, size, "engine %d unknown", (int)o->engine);
    else if (o->width < 0 || o->height < 0 || o->width > 16384 || o->height > 16384)
        snprintf(why, size, "image size %dx%d out of range", o->width, o->height);
    else if (o->tile_size && o->tile_size != 1 && o->tile_size != 2 && o->tile_size != 4 &&
             o->tile_size != 8)
        snprintf(why, size, "tile size %d: must be 1, 2, 4 or 8", o->tile_size);
    else if (o->buckets < 0 || o->bounces < 0 || o->bounces > 64 || o->face_size < 0 ||
             o->hiz_levels < 0 || o->march_samples < 0 || o->thickness < 0 ||
             o->aperture < 0 || o->focus < 0 || o->ao_distance < 0 || o->threads < 0)
        snprintf(why, size, "a negative or out-of-range option");
    else if (o->large > DIRT_ADS_MAX_LARGE)
        snprintf(why, size, "large primitives %d: at most %d", o->large, DIRT_ADS_MAX_LARGE);
    else if (o->build != DIRT_SESSION_BUILD_AUTO && o->build != DIRT_SESSION_BUILD_RASTER &&
             o->build != DIRT_SESSION_BUILD_COMPUTE)
        snprintf(why, size, "build mode %d unknown", (int)o->build);
    else if (o->depth_buckets != DIRT_DEPTH_BUCKETS_UNIFORM &&
             o->depth_buckets != DIRT_DEPTH_BUCKETS_ADAPTIVE)
        snprintf(why, size, "depth bucket mode %d unknown", (int)o->depth_buckets);
    else if (o->depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE && o->buckets > DIRT_ADAPT_MAX_BUCKETS)
        snprintf(why, size, "%d buckets: adaptive depth buckets take at most %d", o->buckets,
                 DIRT_ADAPT_MAX_BUCKETS);
    else if (o->node_depths && o->buckets > DIRT_NODE_DEPTH_MAX_BUCKETS)
        snprintf(why, size, "%d buckets: node depth ranges take at most %d", o->buckets,
                 DIRT_NODE_DEPTH_MAX_BUCKETS);
    else if (!session_engines[o->engine]->check_opts ||
             session_engines[o->engine]->check_opts(o, why, size))
        return true;
    return session_fail(DIRT_SESSION_ERR_OPTION);
}

static bool check_opts(const dirt_session_opts *o, bool have_gpu)
{
    char why[256];
    if (!dirt_session_check_opts(o, why, sizeof(why))) {
        DIRT_ERROR("%s", why);
        return false;
    }
    if (session_engines[o->engine]->needs_gpu && !have_gpu) {
        DIRT_ERROR("engine %s needs a GPU", dirt_engine_names[o->engine]);
        return session_fail(DIRT_SESSION_ERR_NO_GPU);
    }
    return true;
}

/* What a call lends the engine. */
static engine_env env_of(const dirt_session *s)
{
    return (engine_env){.gpu = s->gpu, .scene = s->scene, .opts = &s->opts, .frame = s->frame,
                        .cam = &s->cam, .width = s->width, .height = s->height,
                        .samples = s->samples};
}

/* ---- camera ---- */

/* The camera definition whose aspect sizes the image, or NULL (automatic or
 * explicit camera). */
static const dirt_camera_def *camera_def(const dirt_session *s)
{
    size_t n = dirt_scene_num_cameras(s->scene);
    if (s->cam_choice == DIRT_CAMERA_SCENE && (size_t)s->cam_index < n)
        return &dirt_scene_cameras(s->scene)[s->cam_index];
    if (s->cam_choice == DIRT_CAMERA_DEFAULT && n > 0)
        return &dirt_scene_cameras(s->scene)[0];
    return NULL;
}

static void resolve_size(dirt_session *s)
{
    int w = s->opts.width > 0 ? s->opts.width : 640;
    int h = s->opts.height;
    if (h <= 0) {
        const dirt_camera_def *d = camera_def(s);
        float aspect = 0;
        if (d)
            aspect = d->aspect;
        else if (s->cam_choice == DIRT_CAMERA_EXPLICIT)
            aspect = s->cam_explicit.aspect;
        if (!(aspect > 0) || !isfinite(aspect))
            aspect = 4.0f / 3.0f;
        h = (int)((float)w / aspect + 0.5f);
        if (h < 1)
            h = 1;
        if (h > 16384)
            h = 16384;
    }
    s->width = w;
    s->height = h;
}

static bool resolve_camera(dirt_session *s)
{
    const dirt_frame *f = s->frame;
    dirt_camera cam;
    size_t scene_cam = s->cam_choice == DIRT_CAMERA_SCENE ? (size_t)s->cam_index : 0;
    bool from_scene = (s->cam_choice == DIRT_CAMERA_SCENE || s->cam_choice == DIRT_CAMERA_DEFAULT) &&
                      scene_cam < f->num_cameras;
    if (s->cam_choice == DIRT_CAMERA_SCENE && !from_scene) {
        DIRT_ERROR("camera %d: the scene has %zu camera(s)", s->cam_index, f->num_cameras);
        return session_fail(DIRT_SESSION_ERR_CAMERA);
    }
    if (from_scene) {
        cam = f->cameras[scene_cam];
    } else if (s->cam_choice == DIRT_CAMERA_EXPLICIT) {
        cam = s->cam_explicit;
    } else {
        /* Automatic (also the default without cameras): one camera for
         * the whole clip. */
        if (!s->have_clip_cam) {
            float bmin[3], bmax[3];
            if (!dirt_scene_clip_bounds(s->scene, &s->eval, bmin, bmax))
                return false;
            dirt_camera_auto_bounds(bmin, bmax, &s->clip_cam);
            s->have_clip_cam = true;
        }
        cam = s->clip_cam;
    }
    if (s->opts.aperture > 0) {
        cam.aperture_radius = s->opts.aperture;
        float d = 0;
        for (int k = 0; k < 3; k++)
            d += (0.5f * (f->bounds_min[k] + f->bounds_max[k]) - cam.eye[k]) * cam.forward[k];
        cam.focus_distance = s->opts.focus > 0 ? s->opts.focus : (d > 0 ? d : 1.0f);
    }
    s->cam = cam;
    return true;
}

/* ---- the engine ---- */

/* Makes the engine of s->opts for the current size, or remakes its
 * structure when it is already that engine (reshape keeps the rest). */
static bool make_engine(dirt_session *s)
{
    engine_env env = env_of(s);
    const engine_ops *want = session_engines[s->opts.engine];
    s->built = false;
    if (s->engine && s->ops == want)
        return s->ops->reshape(s->engine, &env);
    if (s->engine)
        s->ops->destroy(s->engine);
    s->ops = want;
    s->engine = want->create(&env);
    return s->engine != NULL;
}

static void restart(dirt_session *s)
{
    s->samples = 0;
    memset(&s->stats, 0, sizeof(s->stats));
    if (s->engine)
        s->ops->restart(s->engine);
}

/* Warns when nothing can light the image: no punctual light, no emissive
 * material and a black background (path tracing and the preview). */
static void warn_unlit(const dirt_scene *scene, const dirt_session_opts *o)
{
    if (o->mode == DIRT_PT_AO || o->background[0] > 0 || o->background[1] > 0 ||
        o->background[2] > 0 || dirt_env_samples(o->env) || dirt_scene_num_lights(scene) > 0)
        return;
    const dirt_material *m = dirt_scene_materials(scene);
    for (size_t i = 0; i < dirt_scene_num_materials(scene); i++) {
        if (dirt_material_is_emissive(&m[i]))
            return;
    }
    DIRT_WARN("the scene has no light, no emissive material and no environment: the image "
              "will be black (give --env FILE.exr|.hdr, --env sky or a --background, or "
              "render AO)");
}

dirt_session *dirt_session_create(dirt_gpu *gpu, const dirt_scene *scene,
                                  const dirt_session_opts *opts)
{
    dirt_session_opts o = opts ? *opts : (dirt_session_opts){0};
    if (!scene) {
        session_begin();
        DIRT_ERROR("a session without a scene");
        session_fail(DIRT_SESSION_ERR_ARGUMENT);
        return NULL;
    }
    if (!check_opts(&o, gpu != NULL)) /* begins the call's error record */
        return NULL;
    dirt_session *s = calloc(1, sizeof(*s));
    if (!s) {
        DIRT_ERROR("out of memory");
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        return NULL;
    }
    s->gpu = gpu;
    if (gpu)
        dirt_gpu_describe(gpu, s->gpu_desc, sizeof(s->gpu_desc));
    s->scene = scene;
    s->opts = o;
    warn_unlit(scene, &o);
    s->frame = dirt_scene_evaluate(scene, 0, &s->eval);
    if (!s->frame) {
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        goto error;
    }
    resolve_size(s);
    if (!resolve_camera(s) || !make_engine(s))
        goto error;
    return s;
error:
    session_fail(DIRT_SESSION_ERR_RENDER);
    dirt_session_destroy(s);
    return NULL;
}

void dirt_session_destroy(dirt_session *s)
{
    if (!s)
        return;
    if (s->engine)
        s->ops->destroy(s->engine);
    dirt_frame_destroy(s->frame);
    free(s);
}

bool dirt_session_set_opts(dirt_session *s, const dirt_session_opts *opts, bool *restarted)
{
    dirt_session_opts n = opts ? *opts : (dirt_session_opts){0};
    if (restarted)
        *restarted = false;
    if (!check_opts(&n, s->gpu != NULL)) /* begins the call's error record */
        return false;
    dirt_session_opts old = s->opts;
    /* What the structure is made of and what only its tracer reads; threads
     * only change how the work is spread. */
    bool structure = old.engine != n.engine || old.width != n.width || old.height != n.height ||
                  old.views != n.views || old.face_size != n.face_size ||
                  old.tile_size != n.tile_size || old.buckets != n.buckets ||
                  old.force_emulation != n.force_emulation || old.build != n.build ||
                  old.large != n.large || old.large_grid != n.large_grid ||
                  old.depth_buckets != n.depth_buckets || old.sub_tiles != n.sub_tiles ||
                  old.bucket_masks != n.bucket_masks || old.node_depths != n.node_depths;
    bool tracer = old.hiz_levels != n.hiz_levels || old.fetch != n.fetch ||
                  old.direct_visibility != n.direct_visibility || old.march != n.march ||
                  old.march_samples != n.march_samples || old.thickness != n.thickness ||
                  old.aperture != n.aperture || old.focus != n.focus;
    bool image_changes = structure || tracer || old.mode != n.mode ||
                         old.bounces != n.bounces || old.seed != n.seed ||
                         old.ao_distance != n.ao_distance ||
                         old.env != n.env ||
                         memcmp(old.background, n.background, sizeof(n.background)) != 0;
    s->opts = n;
    if (structure) {
        resolve_size(s);
        if (!make_engine(s)) {
            /* Back to the old options, with an engine made afresh for them. */
            if (s->engine)
                s->ops->destroy(s->engine);
            s->engine = NULL;
            s->opts = old;
            resolve_size(s);
            if (!make_engine(s))
                DIRT_ERROR("the session's old engine could not be remade either");
            restart(s);
            if (restarted)
                *restarted = true;
            return session_fail(DIRT_SESSION_ERR_RENDER);
        }
    }
    if (old.aperture != n.aperture || old.focus != n.focus)
        resolve_camera(s);
    if (tracer)
        s->built = false; /* the tracer (and, for the lens, the views) change */
    if (image_changes) {
        restart(s);
        if (restarted)
            *restarted = true;
    }
    return true;
}

const dirt_session_opts *dirt_session_get_opts(const dirt_session *s)
{
    return &s->opts;
}

bool dirt_session_set_time(dirt_session *s, double time, const dirt_eval_opts *eval)
{
    session_begin();
    dirt_eval_opts e = eval ? *eval : (dirt_eval_opts){0};
    size_t clips = dirt_scene_num_clips(s->scene);
    if (e.clip >= 0 && clips > 0 && (size_t)e.clip >= clips) {
        DIRT_ERROR("clip %d: the scene has %zu animation clip(s)", e.clip, clips);
        return session_fail(DIRT_SESSION_ERR_CLIP);
    }
    if (e.clip != s->eval.clip || e.loop != s->eval.loop || e.all_clips != s->eval.all_clips)
        s->have_clip_cam = false;
    if (!dirt_scene_evaluate_into(s->scene, (float)time, &e, s->frame))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    s->eval = e;
    s->time = time;
    s->built = false;
    restart(s);
    return resolve_camera(s) || session_fail(DIRT_SESSION_ERR_RENDER);
}

const dirt_frame *dirt_session_frame(const dirt_session *s)
{
    return s->frame;
}

bool dirt_session_set_camera(dirt_session *s, enum dirt_camera_choice choice, int index,
                             const dirt_camera *cam)
{
    session_begin();
    if (choice == DIRT_CAMERA_SCENE &&
        (index < 0 || (size_t)index >= dirt_scene_num_cameras(s->scene))) {
        DIRT_ERROR("camera %d: the scene has %zu camera(s)", index,
                   dirt_scene_num_cameras(s->scene));
        return session_fail(DIRT_SESSION_ERR_CAMERA);
    }
    if (choice == DIRT_CAMERA_EXPLICIT && !cam) {
        DIRT_ERROR("explicit camera without a camera");
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    s->cam_choice = choice;
    s->cam_index = index;
    if (cam)
        s->cam_explicit = *cam;
    int w = s->width, h = s->height;
    resolve_size(s);
    if ((w != s->width || h != s->height) && !make_engine(s))
        return session_fail(DIRT_SESSION_ERR_RENDER); /* the views follow the image size */
    s->built = false;
    restart(s);
    return resolve_camera(s) || session_fail(DIRT_SESSION_ERR_RENDER);
}

const dirt_camera *dirt_session_camera(const dirt_session *s)
{
    return &s->cam;
}

void dirt_session_size(const dirt_session *s, int *width, int *height)
{
    if (width)
        *width = s->width;
    if (height)
        *height = s->height;
}

void dirt_session_reset(dirt_session *s)
{
    restart(s);
}

int dirt_session_samples(const dirt_session *s)
{
    return s->samples;
}

dirt_ads *dirt_session_ads(dirt_session *s)
{
    return s->built && s->ops->ads ? s->ops->ads(s->engine) : NULL;
}

dirt_mmrt *dirt_session_mmrt(dirt_session *s)
{
    return s->built && s->ops->mmrt ? s->ops->mmrt(s->engine) : NULL;
}

engine *session_built_engine(dirt_session *s, const engine_ops **ops, engine_env *env)
{
    if (!s->built)
        return NULL;
    *ops = s->ops;
    *env = env_of(s);
    return s->engine;
}

/* ---- stats ---- */

/* The build's passes and buffers (the engine's own figures). */
static void build_stats(dirt_session *s, dirt_session_stats *st)
{
    st->num_passes = 0;
    st->num_buffers = 0;
    st->bytes_total_used = st->bytes_total_allocated = 0;
    st->build_ms = 0;
    s->ops->build_stats(s->engine, st);
    st->num_build_passes = st->num_passes;
}

static void fill_common(dirt_session *s, dirt_session_stats *st)
{
    st->engine = s->opts.engine;
    snprintf(st->device, sizeof(st->device), "%s",
             s->gpu && s->ops->needs_gpu ? s->gpu_desc : "CPU");
    st->width = s->width;
    st->height = s->height;
    st->samples = s->samples;
    st->bounces = s->opts.bounces ? s->opts.bounces : 4;
    st->mode = s->opts.mode;
    st->seed = s->opts.seed;
    st->time = s->time;
}

/* ---- rendering ---- */

static bool build(dirt_session *s)
{
    if (s->built)
        return true;
    if (!s->engine) {
        DIRT_ERROR("the session has no engine (it could not be remade: see the errors above)");
        return false;
    }
    engine_env env = env_of(s);
    if (!s->ops->build(s->engine, &env))
        return false;
    s->built = true;
    return true;
}

bool dirt_session_build(dirt_session *s)
{
    session_begin();
    if (!build(s))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    build_stats(s, &s->stats);
    fill_common(s, &s->stats);
    s->stats.has_work = false;
    if (s->opts.count_work && !session_count_work(s, &s->stats))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    return true;
}

/* What dirt_session_add_samples and dirt_session_advance do first: the
 * structure built, the stats' common part, the work counted. *t0 moves
 * past the counting. False after recording the error. */
static bool prepare_samples(dirt_session *s, double *t0)
{
    bool was_built = s->built;
    if (!build(s))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    dirt_session_stats *st = &s->stats;
    if (!was_built || st->num_passes == 0)
        build_stats(s, st);
    fill_common(s, st);
    if (!was_built || !s->opts.count_work)
        st->has_work = false;
    if (s->opts.count_work && !st->has_work) {
        /* Counting is not rendering: its time stays out of total_ms. */
        double c0 = dirt_clock_ms();
        if (!session_count_work(s, st))
            return session_fail(DIRT_SESSION_ERR_RENDER);
        *t0 += dirt_clock_ms() - c0;
    }
    return true;
}

bool dirt_session_add_samples(dirt_session *s, int count,
                              void (*progress)(void *user, int done, int total), void *user)
{
    session_begin();
    if (count < 1) {
        DIRT_ERROR("sample count %d", count);
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    double t0 = dirt_clock_ms();
    if (!prepare_samples(s, &t0))
        return false;
    dirt_session_stats *st = &s->stats;
    engine_env env = env_of(s);
    if (!s->ops->add_samples(s->engine, &env, count, progress, user, st, &s->samples))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    st->samples = s->samples;
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
    st->total_ms += dirt_clock_ms() - t0;
    return true;
}

bool dirt_session_advance(dirt_session *s, double budget_ms, bool *completed)
{
    session_begin();
    bool done = false;
    if (completed)
        *completed = false;
    if (!(budget_ms >= 0)) {
        DIRT_ERROR("time budget %g ms", budget_ms);
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    if (!s->ops->advance) {
        /* An engine that does not split a sample adds a whole one. */
        if (!dirt_session_add_samples(s, 1, NULL, NULL))
            return false;
        if (completed)
            *completed = true;
        return true;
    }
    double t0 = dirt_clock_ms();
    if (!prepare_samples(s, &t0))
        return false;
    dirt_session_stats *st = &s->stats;
    engine_env env = env_of(s);
    if (!s->ops->advance(s->engine, &env, budget_ms, st, &s->samples, &done))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    st->samples = s->samples;
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
    st->total_ms += dirt_clock_ms() - t0;
    if (completed)
        *completed = done;
    return true;
}

double dirt_session_sample_part(const dirt_session *s)
{
    if (!s->engine || !s->ops->part)
        return 0.0;
    engine_env env = env_of(s);
    return s->ops->part(s->engine, &env);
}

const dirt_image *dirt_session_image(dirt_session *s)
{
    session_begin();
    if (!s->samples) {
        DIRT_ERROR("no samples yet");
        session_fail(DIRT_SESSION_ERR_NOT_READY);
        return NULL;
    }
    engine_env env = env_of(s);
    const dirt_image *img = s->ops->image(s->engine, &env, &s->stats);
    if (!img)
        session_fail(DIRT_SESSION_ERR_RENDER);
    return img;
}

void dirt_session_drain_times(dirt_session *s)
{
    engine_env env = env_of(s);
    if (s->engine && s->ops->late_times)
        s->ops->late_times(s->engine, &env, true, &s->stats);
}

uint32_t dirt_session_display_texture(dirt_session *s)
{
    session_begin();
    if (!s->samples) {
        DIRT_ERROR("no samples to display");
        session_fail(DIRT_SESSION_ERR_NOT_READY);
        return 0;
    }
    engine_env env = env_of(s);
    uint32_t tex = s->ops->display_texture(s->engine, &env);
    if (!tex)
        session_fail(DIRT_SESSION_ERR_RENDER);
    return tex;
}

const dirt_session_stats *dirt_session_get_stats(const dirt_session *s)
{
    return &s->stats;
}

bool dirt_session_write_graph_dot(const dirt_session *s, const char *path)
{
    session_begin();
    if (!s->engine || !s->ops->write_graph_dot) {
        DIRT_ERROR("the %s engine has no path tracer frame graph",
                   dirt_engine_names[s->opts.engine]);
        return session_fail(DIRT_SESSION_ERR_UNSUPPORTED);
    }
    return s->ops->write_graph_dot(s->engine, path) ||
           session_fail(s->samples ? DIRT_SESSION_ERR_IO : DIRT_SESSION_ERR_NOT_READY);
}

const dirt_scene *dirt_session_scene(const dirt_session *s)
{
    return s->scene;
}
