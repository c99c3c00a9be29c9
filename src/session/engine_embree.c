/* The embree engine: the CPU ground truth (Embree 3), a mean of means over
 * the calls (engine.h). */
#include <stdlib.h>
#include <string.h>

#include "dirt/clock.h"
#include "dirt/log.h"
#include "session/engine.h"

typedef struct embree_engine {
    dirt_ref_accel *accel;
    dirt_ref_materials alpha;   /* the scene's materials, for the accel's alpha test */
    double build_ms;            /* the last build's wall time */
    dirt_image *img;            /* the accumulated mean */
    engine_display display;
} embree_engine;

static void destroy(engine *e)
{
    embree_engine *m = (embree_engine *)e;
    if (!m)
        return;
    dirt_ref_accel_destroy(m->accel);
    dirt_image_destroy(m->img);
    engine_display_release(&m->display);
    free(m);
}

static engine *create(const engine_env *env)
{
    (void)env;
    embree_engine *m = calloc(1, sizeof(*m));
    if (!m) {
        DIRT_ERROR("out of memory");
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
    }
    return (engine *)m;
}

/* The BVH is made again at the next build, as for a new engine. */
static bool reshape(engine *e, const engine_env *env)
{
    (void)env;
    embree_engine *m = (embree_engine *)e;
    dirt_ref_accel_destroy(m->accel);
    m->accel = NULL;
    dirt_image_destroy(m->img);
    m->img = NULL;
    m->display.current = false;
    return true;
}

static bool build(engine *e, const engine_env *env)
{
    embree_engine *m = (embree_engine *)e;
    double t0 = dirt_clock_ms();
    m->alpha = (dirt_ref_materials){.materials = dirt_scene_materials(env->scene),
                                    .num_materials = dirt_scene_num_materials(env->scene),
                                    .textures = dirt_scene_textures(env->scene),
                                    .num_textures = dirt_scene_num_textures(env->scene)};
    if (m->accel ? !dirt_ref_accel_update(m->accel, env->frame)
                 : !(m->accel = dirt_ref_accel_create(
                         env->frame, &(dirt_ref_accel_opts){.threads = env->opts->threads,
                                                            .alpha = &m->alpha})))
        return false;
    m->build_ms = dirt_clock_ms() - t0;
    return true;
}

static void build_stats(engine *e, dirt_session_stats *st)
{
    embree_engine *m = (embree_engine *)e;
    st->build_ms = m->build_ms;
    engine_add_pass(st, "bvh build", m->build_ms, DIRT_CLOCK_CPU);
}

static void restart(engine *e)
{
    ((embree_engine *)e)->display.current = false;
}

typedef struct ref_progress {
    engine_progress_fn fn;
    void *user;
} ref_progress;

static void on_ref_progress(void *user, uint64_t done, uint64_t total)
{
    ref_progress *p = user;
    p->fn(p->user, (int)done, (int)total);
}

/* Adds the samples [env->samples, env->samples + count) to the mean. */
static bool add_samples(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                        void *user, dirt_session_stats *st, int *samples)
{
    embree_engine *m = (embree_engine *)e;
    const dirt_session_opts *o = env->opts;
    ref_progress prog = {progress, user};
    dirt_ref_opts ro = {
        .width = env->width, .height = env->height, .spp = count,
        .first_sample = (uint32_t)env->samples, .bounces = o->bounces ? o->bounces : 4,
        .mode = o->mode == DIRT_PT_AO ? DIRT_REF_MODE_AO : DIRT_REF_MODE_PT,
        .ao_distance = o->ao_distance, .seed = o->seed,
        .background = {o->background[0], o->background[1], o->background[2]},
        .env = o->env, .threads = o->threads, .accel = m->accel,
        .progress = progress ? on_ref_progress : NULL, .progress_user = &prog,
    };
    dirt_ref_stats rs;
    dirt_image *r = dirt_ref_render(env->scene, env->frame, env->cam, &ro, &rs);
    if (!r)
        return false;
    if (env->samples == 0 || !m->img) {
        dirt_image_destroy(m->img);
        m->img = r;
    } else {
        /* Mean of means, weighted by their samples ("Z" and "ID" are per
         * pixel centre: the same every time). */
        double a = env->samples, b = count, inv = 1.0 / (a + b);
        size_t n = (size_t)env->width * env->height;
        for (size_t i = 0; i < 4 * n; i++)
            m->img->rgba[i] = (float)((m->img->rgba[i] * a + r->rgba[i] * b) * inv);
        for (int c = 0; c < m->img->channel_count; c++) {
            float *dst = m->img->channels[c].data;
            const float *src = dirt_image_find_channel(r, m->img->channels[c].name);
            if (!src || !strcmp(m->img->channels[c].name, "Z") ||
                !strcmp(m->img->channels[c].name, "ID"))
                continue;
            for (size_t i = 0; i < n; i++)
                dst[i] = (float)((dst[i] * a + src[i] * b) * inv);
        }
        dirt_image_destroy(r);
    }
    m->display.current = false;
    st->trace_ms += rs.seconds * 1e3;
    st->rays += rs.rays;
    st->invalid_samples += rs.invalid;
    engine_add_paths_at_event(st, rs.paths_at_event, ro.mode == DIRT_REF_MODE_AO ? 1 : ro.bounces + 1);
    engine_add_pass(st, "render", rs.seconds * 1e3, DIRT_CLOCK_CPU);
    *samples = env->samples + count;
    return true;
}

static const dirt_image *image(engine *e, const engine_env *env, dirt_session_stats *st)
{
    (void)env;
    (void)st;
    return ((embree_engine *)e)->img;
}

static uint32_t display_texture(engine *e, const engine_env *env)
{
    embree_engine *m = (embree_engine *)e;
    return engine_display_upload(&m->display, env->gpu, m->img);
}

const engine_ops engine_embree_ops = {
    .needs_gpu = false,
    .create = create,
    .destroy = destroy,
    .reshape = reshape,
    .build = build,
    .build_stats = build_stats,
    .restart = restart,
    .add_samples = add_samples,
    .image = image,
    .display_texture = display_texture,
};
