/* The render session: scene + time + camera + technique + integrator +
 * progressive accumulation + stats. */
#include "dirt/session.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/ads.h"
#include "dirt/clock.h"
#include "integrator/integrator.h"
#include "integrator/pathtrace.h"
#include "dirt/log.h"
#include "mmrt/mmrt.h"
#include "raster/raster.h"
#include "ref/ref.h"
#include "gl/gl.h"
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
    dirt_ads *ads;
    dirt_mmrt *mmrt;
    dirt_raster *raster;
    dirt_pt *pt;
    dirt_ref_accel *accel;
    dirt_ref_materials accel_alpha; /* the scene's materials, for the accel's alpha test */
    const dirt_tracer *tracer; /* of the current build */
    bool built;               /* the structure matches frame, camera and options */
    double build_ms;
    /* the result */
    int samples;
    dirt_image *img;          /* accumulated (embree, raster) or read back (dirt, mmrt) */
    bool img_current;         /* img holds the current accumulation */
    GLuint display;           /* embree, raster: uploaded beauty */
    int display_w, display_h;
    bool display_current;
    dirt_session_stats stats;
};

static bool gpu_engine(enum dirt_engine e)
{
    return e != DIRT_ENGINE_EMBREE;
}

static bool traced(enum dirt_engine e)
{
    return e == DIRT_ENGINE_DIRT || e == DIRT_ENGINE_MMRT;
}

static enum dirt_view_mode view_mode(enum dirt_session_views v)
{
    return v == DIRT_SESSION_VIEWS_SINGLE ? DIRT_VIEWS_SINGLE
           : v == DIRT_SESSION_VIEWS_CUBE ? DIRT_VIEWS_CUBE
                                          : DIRT_VIEWS_CUBE_CAMERA;
}

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
    else if (o->engine == DIRT_ENGINE_MMRT &&
             (o->fetch == DIRT_FETCH_RASTER || o->direct_visibility))
        snprintf(why, size, "the mmrt engine has no Fetch pass and no visibility buffer: the "
                            "raster Fetch and direct visibility are DIRT's");
    else if (o->engine == DIRT_ENGINE_DIRT && o->direct_visibility &&
             o->views == DIRT_SESSION_VIEWS_CUBE)
        snprintf(why, size, "direct visibility needs a camera view: single or cube+camera views");
    else
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
    if (gpu_engine(o->engine) && !have_gpu) {
        DIRT_ERROR("engine %s needs a GPU", dirt_engine_names[o->engine]);
        return session_fail(DIRT_SESSION_ERR_NO_GPU);
    }
    return true;
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

static void release_engine(dirt_session *s)
{
    dirt_ads_destroy(s->ads);
    dirt_mmrt_destroy(s->mmrt);
    dirt_raster_destroy(s->raster);
    dirt_ref_accel_destroy(s->accel);
    s->ads = NULL;
    s->mmrt = NULL;
    s->raster = NULL;
    s->accel = NULL;
    s->tracer = NULL;
    s->built = false;
    /* The image's channels and size are the engine's. */
    dirt_image_destroy(s->img);
    s->img = NULL;
    s->img_current = false;
}

/* DIRT's tile size when the options leave it open (tile_size 0): S = 2, or
 * the smallest of 4 and 8 whose list heads (buckets x tiles of every view)
 * take at most a quarter of one storage block, so that large images work
 * out of the box: the primitive-list nodes, a few per head and known only
 * after the first fill, must fit one block too (the default scene at
 * 3840x2160 needs 17.5 M nodes, 140 MB, at S = 4 and about a quarter of
 * that at S = 8). The tile count does not depend on the camera, so a unit
 * box's views tell it. An explicit S is kept (its error, if any, advises
 * larger tiles). */
static int auto_tile_size(dirt_session *s, dirt_view_opts vo, int buckets)
{
    int64_t max = dirt_gpu_get_caps(s->gpu)->max_ssbo_size;
    static const float bmin[3] = {-1, -1, -1}, bmax[3] = {1, 1, 1};
    dirt_camera cam;
    dirt_camera_auto_bounds(bmin, bmax, &cam);
    static const int sizes[] = {2, 4, 8};
    uint64_t heads2 = 0;
    for (size_t i = 0; i < sizeof(sizes) / sizeof(sizes[0]); i++) {
        vo.tile_size = sizes[i];
        dirt_view_set set;
        if (!dirt_views_setup(&set, &cam, bmin, bmax, &vo, 0))
            return 2; /* the build reports the bad size */
        uint64_t heads = (uint64_t)buckets * (uint64_t)set.num_tiles * DIRT_HEAD_BYTES;
        if (i == 0)
            heads2 = heads;
        if (max <= 0 || heads <= (uint64_t)max / 4) {
            if (sizes[i] != 2)
                DIRT_INFO("tile size %d (the list heads of tile size 2 would need %.1f MB, "
                          "more than a quarter of this GPU's largest storage buffer, %.1f MB)",
                          sizes[i], heads2 / 1e6, max / 1e6);
            return sizes[i];
        }
    }
    return 8;
}

enum dirt_build_mode dirt_session_auto_build(const dirt_gpu *gpu)
{
    const dirt_gpu_caps *caps = gpu ? dirt_gpu_get_caps(gpu) : NULL;
    return dirt_build_from_env(caps && caps->software ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER);
}

int dirt_session_auto_buckets(const dirt_gpu *gpu)
{
    const dirt_gpu_caps *caps = gpu ? dirt_gpu_get_caps(gpu) : NULL;
    return caps && caps->software ? 8 : 16;
}

static bool make_engine(dirt_session *s)
{
    const dirt_session_opts *o = &s->opts;
    dirt_view_opts vo = {.mode = view_mode(o->views), .width = s->width, .height = s->height,
                         .face_size = o->face_size, .tile_size = o->tile_size ? o->tile_size : 2};
    int buckets = o->buckets ? o->buckets : dirt_session_auto_buckets(s->gpu);
    switch (o->engine) {
    case DIRT_ENGINE_DIRT:
        if (!o->tile_size)
            vo.tile_size = auto_tile_size(s, vo, buckets);
        s->ads = dirt_ads_create(s->gpu, &(dirt_ads_opts){
                                             .views = vo,
                                             .buckets = buckets,
                                             .force_emulation = o->force_emulation,
                                             .large = o->large,
                                             .build = o->build == DIRT_SESSION_BUILD_RASTER
                                                          ? DIRT_BUILD_RASTER
                                                      : o->build == DIRT_SESSION_BUILD_COMPUTE
                                                          ? DIRT_BUILD_COMPUTE
                                                          : dirt_session_auto_build(s->gpu),
                                         });
        if (!s->ads)
            return false;
        break;
    case DIRT_ENGINE_MMRT:
        vo.tile_size = 1;
        s->mmrt = dirt_mmrt_create(s->gpu, &(dirt_mmrt_opts){
                                               .views = vo,
                                               .buckets = o->buckets ? o->buckets : 4,
                                           });
        if (!s->mmrt)
            return false;
        break;
    case DIRT_ENGINE_RASTER:
        s->raster = dirt_raster_create(s->gpu, s->scene);
        if (!s->raster)
            return false;
        break;
    case DIRT_ENGINE_EMBREE:
    case DIRT_NUM_ENGINES:
        break;
    }
    if (traced(o->engine) && !s->pt) {
        s->pt = dirt_pt_create(s->gpu, s->scene);
        if (!s->pt)
            return false;
    }
    return true;
}

static void restart(dirt_session *s)
{
    s->samples = 0;
    s->img_current = false;
    s->display_current = false;
    memset(&s->stats, 0, sizeof(s->stats));
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
    if (!check_opts(&o, gpu != NULL))
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
    release_engine(s);
    dirt_pt_destroy(s->pt);
    gl_texture_destroy(&s->display);
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
                  old.large != n.large;
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
        release_engine(s);
        resolve_size(s);
        if (!make_engine(s)) {
            /* Back to the old options (their objects were made before). */
            release_engine(s);
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
    if (w != s->width || h != s->height) {
        /* The views follow the image size. */
        release_engine(s);
        if (!make_engine(s))
            return session_fail(DIRT_SESSION_ERR_RENDER);
    }
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
    return s->built ? s->ads : NULL;
}

dirt_mmrt *dirt_session_mmrt(dirt_session *s)
{
    return s->built ? s->mmrt : NULL;
}

/* ---- stats ---- */

/* A figure as the session adds it up: 0 when it was not measured. Which
 * clock measured it is the figure's own (dirt_gpu_clock decided). */
static double measured_ms(double ms, enum dirt_clock clock)
{
    return clock != DIRT_CLOCK_NONE && ms > 0 ? ms : 0;
}

static void add_pass(dirt_session_stats *st, const char *name, double ms, enum dirt_clock clock)
{
    for (int i = 0; i < st->num_passes; i++) {
        if (!strcmp(st->passes[i].name, name)) {
            st->passes[i].ms += ms;
            return;
        }
    }
    if (st->num_passes < (int)(sizeof(st->passes) / sizeof(st->passes[0])))
        st->passes[st->num_passes++] = (dirt_pass_time){name, ms, clock};
}

/* Adds a render's paths per event (k = 1 .. events) to the stats. */
static void add_paths_at_event(dirt_session_stats *st, const uint64_t *paths, int events)
{
    if (events > DIRT_PT_MAX_EVENTS - 1)
        events = DIRT_PT_MAX_EVENTS - 1;
    if (events > st->events)
        st->events = events;
    for (int k = 1; k <= events; k++)
        st->paths_at_event[k] += paths[k];
}

static void add_buffer(dirt_session_stats *st, const char *name, uint64_t used,
                       uint64_t allocated)
{
    if (st->num_buffers < (int)(sizeof(st->buffers) / sizeof(st->buffers[0])))
        st->buffers[st->num_buffers++] = (dirt_buffer_bytes){name, used, allocated};
    st->bytes_total_used += used;
    st->bytes_total_allocated += allocated;
}

/* The build's passes and buffers (from the technique's own stats). */
static void build_stats(dirt_session *s, dirt_session_stats *st)
{
    st->num_passes = 0;
    st->num_buffers = 0;
    st->bytes_total_used = st->bytes_total_allocated = 0;
    st->build_ms = 0;
    if (s->ads) {
        const dirt_ads_stats *a = dirt_ads_get_stats(s->ads);
        st->has_ads = true;
        st->ads = *a;
        for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++) {
            double ms = measured_ms(a->ms[i], a->clock);
            st->build_ms += ms;
            add_pass(st, dirt_ads_pass_names[i], ms, a->clock);
        }
        add_buffer(st, "vertices", a->bytes_vertices, a->bytes_vertices);
        add_buffer(st, "depth bounds", a->bytes_depth, a->bytes_depth);
        add_buffer(st, "list heads", a->bytes_heads, a->bytes_heads);
        add_buffer(st, "id nodes", a->bytes_nodes_used, a->bytes_nodes_allocated);
        add_buffer(st, "candidates", a->bytes_candidates_used, a->bytes_candidates_allocated);
    } else if (s->mmrt) {
        const dirt_mmrt_stats *m = dirt_mmrt_get_stats(s->mmrt);
        st->has_mmrt = true;
        st->mmrt = *m;
        for (int i = 0; i < DIRT_MMRT_NUM_PASSES; i++) {
            double ms = measured_ms(m->ms[i], m->clock);
            st->build_ms += ms;
            add_pass(st, dirt_mmrt_pass_names[i], ms, m->clock);
        }
        add_buffer(st, "vertices", m->bytes_vertices, m->bytes_vertices);
        add_buffer(st, "depth bounds", m->bytes_depth, m->bytes_depth);
        add_buffer(st, "list heads", m->bytes_heads, m->bytes_heads);
        add_buffer(st, "id nodes", m->bytes_id_nodes_used, m->bytes_id_nodes_allocated);
        add_buffer(st, "data nodes", m->bytes_data_nodes_used, m->bytes_data_nodes_allocated);
    } else if (s->accel) {
        st->build_ms = s->build_ms;
        add_pass(st, "bvh build", s->build_ms, DIRT_CLOCK_CPU);
    }
}

static void fill_common(dirt_session *s, dirt_session_stats *st)
{
    st->engine = s->opts.engine;
    snprintf(st->device, sizeof(st->device), "%s",
             s->gpu && gpu_engine(s->opts.engine) ? s->gpu_desc : "CPU");
    st->width = s->width;
    st->height = s->height;
    st->samples = s->samples;
    st->bounces = s->opts.bounces ? s->opts.bounces : 4;
    st->mode = s->opts.mode;
    st->time = s->time;
}

/* ---- rendering ---- */

static bool build(dirt_session *s)
{
    if (s->built)
        return true;
    const dirt_session_opts *o = &s->opts;
    double t0 = dirt_clock_ms();
    s->tracer = NULL;
    switch (o->engine) {
    case DIRT_ENGINE_DIRT: {
        if (!dirt_ads_build(s->ads, s->frame, &s->cam))
            return false;
        dirt_ads_tracer_opts to = {.trace = {.hiz_levels = o->hiz_levels}, .fetch = o->fetch};
        s->tracer = dirt_ads_tracer(s->ads, &to);
        if (!s->tracer)
            return false;
        break;
    }
    case DIRT_ENGINE_MMRT: {
        if (!dirt_mmrt_build(s->mmrt, s->frame, &s->cam))
            return false;
        dirt_mmrt_trace_opts to = {.march = o->march, .samples = o->march_samples,
                                   .hiz_levels = o->hiz_levels, .thickness = o->thickness,
                                   .seed = o->seed};
        s->tracer = dirt_mmrt_tracer(s->mmrt, &to);
        if (!s->tracer)
            return false;
        break;
    }
    case DIRT_ENGINE_EMBREE:
        s->accel_alpha = (dirt_ref_materials){
            .materials = dirt_scene_materials(s->scene),
            .num_materials = dirt_scene_num_materials(s->scene),
            .textures = dirt_scene_textures(s->scene),
            .num_textures = dirt_scene_num_textures(s->scene)};
        if (s->accel ? !dirt_ref_accel_update(s->accel, s->frame)
                     : !(s->accel = dirt_ref_accel_create(
                             s->frame, &(dirt_ref_accel_opts){.threads = o->threads,
                                                              .alpha = &s->accel_alpha})))
            return false;
        break;
    case DIRT_ENGINE_RASTER:
    case DIRT_NUM_ENGINES:
        break;
    }
    s->build_ms = dirt_clock_ms() - t0;
    s->built = true;
    return true;
}

static dirt_image *new_image(const dirt_session *s, bool aovs)
{
    dirt_image *img = dirt_image_create(s->width, s->height);
    static const char *extra[] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z",
                                  "Z", "ID"};
    for (int i = 0; img && aovs && i < 8; i++) {
        if (!dirt_image_add_channel(img, extra[i])) {
            dirt_image_destroy(img);
            return NULL;
        }
    }
    return img;
}

static dirt_pt_opts pt_opts(const dirt_session *s)
{
    const dirt_session_opts *o = &s->opts;
    return (dirt_pt_opts){
        .mode = o->mode,
        .bounces = o->bounces ? o->bounces : 4,
        .seed = o->seed,
        .background = {o->background[0], o->background[1], o->background[2]},
        .env = o->env,
        .ao_distance = o->ao_distance,
        .direct_visibility = o->direct_visibility,
    };
}

typedef struct ref_progress {
    void (*fn)(void *user, int done, int total);
    void *user;
} ref_progress;

static void on_ref_progress(void *user, uint64_t done, uint64_t total)
{
    ref_progress *p = user;
    p->fn(p->user, (int)done, (int)total);
}

/* Adds the embree samples [samples, samples + count) to the mean in s->img. */
static bool add_embree(dirt_session *s, int count, ref_progress *prog, dirt_session_stats *st)
{
    const dirt_session_opts *o = &s->opts;
    dirt_ref_opts ro = {
        .width = s->width, .height = s->height, .spp = count, .first_sample = (uint32_t)s->samples,
        .bounces = o->bounces ? o->bounces : 4,
        .mode = o->mode == DIRT_PT_AO ? DIRT_REF_MODE_AO : DIRT_REF_MODE_PT,
        .ao_distance = o->ao_distance, .seed = o->seed,
        .background = {o->background[0], o->background[1], o->background[2]},
        .env = o->env, .threads = o->threads, .accel = s->accel,
        .progress = prog->fn ? on_ref_progress : NULL, .progress_user = prog,
    };
    dirt_ref_stats rs;
    dirt_image *r = dirt_ref_render(s->scene, s->frame, &s->cam, &ro, &rs);
    if (!r)
        return false;
    if (s->samples == 0 || !s->img) {
        dirt_image_destroy(s->img);
        s->img = r;
    } else {
        /* Mean of means, weighted by their samples ("Z" and "ID" are per
         * pixel centre: the same every time). */
        double a = s->samples, b = count, inv = 1.0 / (a + b);
        size_t n = (size_t)s->width * s->height;
        for (size_t i = 0; i < 4 * n; i++)
            s->img->rgba[i] = (float)((s->img->rgba[i] * a + r->rgba[i] * b) * inv);
        for (int c = 0; c < s->img->channel_count; c++) {
            float *dst = s->img->channels[c].data;
            const float *src = dirt_image_find_channel(r, s->img->channels[c].name);
            if (!src || !strcmp(s->img->channels[c].name, "Z") ||
                !strcmp(s->img->channels[c].name, "ID"))
                continue;
            for (size_t i = 0; i < n; i++)
                dst[i] = (float)((dst[i] * a + src[i] * b) * inv);
        }
        dirt_image_destroy(r);
    }
    st->trace_ms += rs.seconds * 1e3;
    st->rays += rs.rays;
    st->invalid_samples += rs.invalid;
    add_paths_at_event(st, rs.paths_at_event, ro.mode == DIRT_REF_MODE_AO ? 1 : ro.bounces + 1);
    add_pass(st, "render", rs.seconds * 1e3, DIRT_CLOCK_CPU);
    return true;
}

bool dirt_session_build(dirt_session *s)
{
    session_begin();
    if (!build(s))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    build_stats(s, &s->stats);
    fill_common(s, &s->stats);
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
    bool was_built = s->built;
    if (!build(s))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    dirt_session_stats *st = &s->stats;
    if (!was_built || st->num_passes == 0)
        build_stats(s, st);
    fill_common(s, st);
    bool ok = false;
    switch (s->opts.engine) {
    case DIRT_ENGINE_DIRT:
    case DIRT_ENGINE_MMRT: {
        if (s->samples == 0 && !dirt_pt_reset(s->pt, s->width, s->height))
            return session_fail(DIRT_SESSION_ERR_RENDER);
        dirt_pt_opts po = pt_opts(s);
        po.progress = progress;
        po.progress_user = user;
        dirt_pt_stats ps;
        if (!dirt_pt_add_samples(s->pt, s->tracer, s->frame, &s->cam, &po, count, &ps))
            return session_fail(DIRT_SESSION_ERR_RENDER);
        s->samples = dirt_pt_samples(s->pt);
        st->trace_ms += ps.trace_ms;
        st->fetch_ms += ps.fetch_ms;
        st->visibility_ms += ps.visibility_ms;
        st->shade_ms += ps.shade_ms;
        st->rays += ps.rays;
        st->aborted += ps.aborted;
        add_paths_at_event(st, ps.paths_at_event, ps.events);
        for (int i = 0; i < DIRT_PT_NUM_PASSES; i++) {
            if (i == DIRT_PT_PASS_VISIBILITY && !po.direct_visibility)
                continue;
            add_pass(st, dirt_pt_pass_names[i], ps.pass_ms[i], ps.clock);
        }
        /* The integrator's buffers once, after the structure's. */
        bool listed = false;
        for (int i = 0; i < st->num_buffers; i++)
            listed |= !strcmp(st->buffers[i].name, "pt accumulation");
        if (!listed) {
            dirt_buffer_bytes b[16];
            int nb = dirt_pt_buffers(s->pt, s->tracer, b, 16);
            for (int i = 0; i < nb; i++)
                add_buffer(st, b[i].name, b[i].used, b[i].allocated);
        }
        ok = true;
        break;
    }
    case DIRT_ENGINE_EMBREE: {
        ref_progress rp = {progress, user};
        ok = add_embree(s, count, &rp, st);
        if (ok)
            s->samples += count;
        break;
    }
    case DIRT_ENGINE_RASTER: {
        if (!s->img) {
            s->img = new_image(s, false);
            static const char *aovs[] = {"N.X", "N.Y", "N.Z", "Z"};
            for (int c = 0; s->img && c < 4; c++) {
                if (!dirt_image_add_channel(s->img, aovs[c])) {
                    dirt_image_destroy(s->img);
                    s->img = NULL;
                }
            }
            if (!s->img)
                return session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        }
        size_t n = (size_t)s->width * (size_t)s->height;
        float *aov = malloc(4 * n * sizeof(float));
        dirt_raster_stats rs;
        ok = aov && dirt_raster_render(s->raster, s->frame, &s->cam, s->width, s->height, NULL,
                                       s->img->rgba, aov, &rs);
        /* N.X, N.Y, N.Z, Z: the channels in the order added above. */
        for (size_t i = 0; ok && i < n; i++) {
            for (int c = 0; c < 4; c++)
                s->img->channels[c].data[i] = aov[4 * i + (size_t)c];
        }
        free(aov);
        if (ok) {
            st->num_passes = 0;
            for (int i = 0; i < rs.num_passes; i++) {
                const dirt_raster_pass_stats *p = &rs.passes[i];
                add_pass(st, i == 0 ? "preview draw" : "preview readback",
                         measured_ms(p->ms, p->clock), p->clock);
            }
            st->shade_ms = measured_ms(rs.ms, rs.clock);
            s->samples = 1;
            if (progress)
                progress(user, 1, 1);
        }
        break;
    }
    case DIRT_NUM_ENGINES:
        break;
    }
    if (!ok)
        return session_fail(DIRT_SESSION_ERR_RENDER);
    s->img_current = s->opts.engine == DIRT_ENGINE_EMBREE || s->opts.engine == DIRT_ENGINE_RASTER;
    s->display_current = false;
    st->samples = s->samples;
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
    st->total_ms += dirt_clock_ms() - t0;
    return true;
}

/* Adds the path tracer's late pass times (dirt_pt_take_late_times; with
 * `wait` the ones still in flight too) to the stats. */
static void add_late_times(dirt_session *s, bool wait)
{
    if (!traced(s->opts.engine) || !s->pt || !s->samples)
        return;
    dirt_pt_stats late;
    dirt_pt_take_late_times(s->pt, wait, &late);
    if (late.clock == DIRT_CLOCK_NONE)
        return;
    dirt_session_stats *st = &s->stats;
    st->trace_ms += late.trace_ms;
    st->fetch_ms += late.fetch_ms;
    st->visibility_ms += late.visibility_ms;
    st->shade_ms += late.shade_ms;
    for (int i = 0; i < DIRT_PT_NUM_PASSES; i++) {
        if (i == DIRT_PT_PASS_VISIBILITY && !s->opts.direct_visibility)
            continue;
        add_pass(st, dirt_pt_pass_names[i], late.pass_ms[i], late.clock);
    }
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
}

const dirt_image *dirt_session_image(dirt_session *s)
{
    session_begin();
    if (!s->samples) {
        DIRT_ERROR("no samples yet");
        session_fail(DIRT_SESSION_ERR_NOT_READY);
        return NULL;
    }
    if (s->img_current)
        return s->img;
    if (!s->img || s->img->width != s->width || s->img->height != s->height) {
        dirt_image_destroy(s->img);
        s->img = new_image(s, true);
        if (!s->img) {
            session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
            return NULL;
        }
    }
    if (!dirt_pt_read(s->pt, s->img, &s->stats.invalid_samples)) {
        session_fail(DIRT_SESSION_ERR_RENDER);
        return NULL;
    }
    add_late_times(s, false); /* the readback drained them */
    s->img_current = true;
    return s->img;
}

void dirt_session_drain_times(dirt_session *s)
{
    add_late_times(s, true);
}

uint32_t dirt_session_display_texture(dirt_session *s)
{
    session_begin();
    if (!s->samples) {
        DIRT_ERROR("no samples to display");
        session_fail(DIRT_SESSION_ERR_NOT_READY);
        return 0;
    }
    if (traced(s->opts.engine)) {
        uint32_t tex = dirt_pt_display_texture(s->pt);
        if (!tex)
            session_fail(DIRT_SESSION_ERR_RENDER);
        return tex;
    }
    if (!s->gpu) {
        DIRT_ERROR("no GPU to display on");
        session_fail(DIRT_SESSION_ERR_NO_GPU);
        return 0;
    }
    if (s->display_current && s->display_w == s->width && s->display_h == s->height)
        return s->display;
    if (!s->display || s->display_w != s->width || s->display_h != s->height) {
        gl_texture_destroy(&s->display);
        s->display = gl_texture_2d(GL_RGBA32F, s->width, s->height, 1, "session display");
        if (!s->display) {
            session_fail(DIRT_SESSION_ERR_RENDER);
            return 0;
        }
        s->display_w = s->width;
        s->display_h = s->height;
    }
    if (!gl_texture_upload_rgba32f(s->display, s->width, s->height, s->img->rgba)) {
        session_fail(DIRT_SESSION_ERR_RENDER);
        return 0;
    }
    s->display_current = true;
    return s->display;
}

const dirt_session_stats *dirt_session_get_stats(const dirt_session *s)
{
    return &s->stats;
}

bool dirt_session_write_graph_dot(const dirt_session *s, const char *path)
{
    session_begin();
    if (!traced(s->opts.engine)) {
        DIRT_ERROR("the %s engine has no path tracer frame graph",
                   dirt_engine_names[s->opts.engine]);
        return session_fail(DIRT_SESSION_ERR_UNSUPPORTED);
    }
    return dirt_pt_write_dot(s->pt, path) ||
           session_fail(s->samples ? DIRT_SESSION_ERR_IO : DIRT_SESSION_ERR_NOT_READY);
}

const dirt_scene *dirt_session_scene(const dirt_session *s)
{
    return s->scene;
}
