/* The embree engine: the CPU ground truth (Embree 3), a mean of means over
 * the calls (engine.h). dirt_session_advance renders a sample in pieces of
 * tiles (dirt_ref_opts.first_tile) into an image of its own, sized by the
 * pace measured so far, and adds it to the mean when its last tile is
 * done, exactly as add_samples adds one sample. */
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
    /* The sample in progress (advance): its tiles [0, part_tiles) are done
     * in `part` (0: none in progress). */
    dirt_image *part;
    size_t part_tiles;
    double ms_per_tile;         /* the pace of the last piece (0: none yet) */
} embree_engine;

static void destroy(engine *e)
{
    embree_engine *m = (embree_engine *)e;
    if (!m)
        return;
    dirt_ref_accel_destroy(m->accel);
    dirt_image_destroy(m->img);
    dirt_image_destroy(m->part);
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
    dirt_image_destroy(m->part);
    m->part = NULL;
    m->part_tiles = 0;
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
    embree_engine *m = (embree_engine *)e;
    m->display.current = false;
    m->part_tiles = 0; /* the sample in progress is dropped */
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

/* The render options of `count` samples from env->samples + `skip`. */
static dirt_ref_opts ref_opts(const embree_engine *m, const engine_env *env, int count, int skip)
{
    const dirt_session_opts *o = env->opts;
    return (dirt_ref_opts){
        .width = env->width, .height = env->height, .spp = count,
        .first_sample = (uint32_t)(env->samples + skip), .bounces = o->bounces ? o->bounces : 4,
        .mode = o->mode == DIRT_PT_AO ? DIRT_REF_MODE_AO : DIRT_REF_MODE_PT,
        .ao_distance = o->ao_distance, .seed = o->seed,
        .background = {o->background[0], o->background[1], o->background[2]},
        .env = o->env, .threads = o->threads, .accel = m->accel,
    };
}

/* Adds a render's figures to `st`. */
static void add_figures(const dirt_ref_stats *rs, const dirt_ref_opts *ro, dirt_session_stats *st)
{
    st->trace_ms += rs->seconds * 1e3;
    st->rays += rs->rays;
    st->invalid_samples += rs->invalid;
    engine_add_paths_at_event(st, rs->paths_at_event,
                              ro->mode == DIRT_REF_MODE_AO ? 1 : ro->bounces + 1);
    engine_add_pass(st, "render", rs->seconds * 1e3, DIRT_CLOCK_CPU);
}

/* Adds `r`, the mean of `count` samples, to the mean of `have` (takes r). */
static void merge(embree_engine *m, const engine_env *env, int have, dirt_image *r, int count)
{
    if (have == 0 || !m->img) {
        dirt_image_destroy(m->img);
        m->img = r;
    } else {
        /* Mean of means, weighted by their samples ("Z" and "ID" are per
         * pixel centre: the same every time). */
        double a = have, b = count, inv = 1.0 / (a + b);
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
}

/* Renders tiles [part_tiles, part_tiles + count) of the sample in progress
 * (sample env->samples) into m->part; adds the figures to `st`. */
static bool render_piece(embree_engine *m, const engine_env *env, size_t count,
                         dirt_session_stats *st)
{
    dirt_ref_opts ro = ref_opts(m, env, 1, 0);
    ro.first_tile = m->part_tiles;
    ro.num_tiles = count;
    ro.into = m->part_tiles > 0 ? m->part : NULL;
    dirt_ref_stats rs;
    double t0 = dirt_clock_ms();
    dirt_image *r = dirt_ref_render(env->scene, env->frame, env->cam, &ro, &rs);
    if (!r)
        return false;
    if (r != m->part) {
        dirt_image_destroy(m->part);
        m->part = r;
    }
    m->ms_per_tile = (dirt_clock_ms() - t0) / (double)count;
    m->part_tiles += count;
    add_figures(&rs, &ro, st);
    return true;
}

/* Completes the sample in progress if there is one: its remaining tiles,
 * then the mean. *added is 1 when it did. */
static bool complete_part(embree_engine *m, const engine_env *env, dirt_session_stats *st,
                          int *added)
{
    *added = 0;
    size_t all = dirt_ref_num_tiles(env->width, env->height);
    if (m->part_tiles == 0)
        return true;
    if (m->part_tiles < all && !render_piece(m, env, all - m->part_tiles, st))
        return false;
    merge(m, env, env->samples, m->part, 1);
    m->part = NULL;
    m->part_tiles = 0;
    *added = 1;
    return true;
}

/* Adds the samples [env->samples, env->samples + count) to the mean; a
 * sample in progress is completed first, as the first of them. */
static bool add_samples(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                        void *user, dirt_session_stats *st, int *samples)
{
    embree_engine *m = (embree_engine *)e;
    int added = 0;
    if (!complete_part(m, env, st, &added))
        return false;
    if (count - added > 0) {
        ref_progress prog = {progress, user};
        dirt_ref_opts ro = ref_opts(m, env, count - added, added);
        ro.progress = progress ? on_ref_progress : NULL;
        ro.progress_user = &prog;
        dirt_ref_stats rs;
        dirt_image *r = dirt_ref_render(env->scene, env->frame, env->cam, &ro, &rs);
        if (!r)
            return false;
        merge(m, env, env->samples + added, r, count - added);
        add_figures(&rs, &ro, st);
    }
    *samples = env->samples + count;
    return true;
}

/* The next sample in pieces of tiles for about `budget_ms`: each piece
 * sized from the last one's pace to fill what is left of the budget (one
 * tile while none is measured, or for a budget of 0); the call returns
 * after the piece that completes the sample or reaches three quarters of
 * the budget. */
static bool advance(engine *e, const engine_env *env, double budget_ms, dirt_session_stats *st,
                    int *samples, bool *completed)
{
    embree_engine *m = (embree_engine *)e;
    size_t all = dirt_ref_num_tiles(env->width, env->height);
    double t0 = dirt_clock_ms();
    *completed = false;
    *samples = env->samples;
    for (;;) {
        double left = budget_ms - (dirt_clock_ms() - t0);
        size_t n = 1;
        if (m->ms_per_tile > 0 && left > 0) {
            double fit = left / m->ms_per_tile;
            n = fit >= (double)all ? all : fit >= 1 ? (size_t)fit : 1;
        }
        if (n > all - m->part_tiles)
            n = all - m->part_tiles;
        if (!render_piece(m, env, n, st))
            return false;
        if (m->part_tiles == all) {
            int added;
            if (!complete_part(m, env, st, &added))
                return false;
            *completed = true;
            *samples = env->samples + 1;
            return true;
        }
        if (dirt_clock_ms() - t0 >= 0.75 * budget_ms)
            return true;
    }
}

static double part(const engine *e, const engine_env *env)
{
    const embree_engine *m = (const embree_engine *)e;
    size_t all = dirt_ref_num_tiles(env->width, env->height);
    return all ? (double)m->part_tiles / (double)all : 0.0;
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
    .advance = advance,
    .part = part,
    .image = image,
    .display_texture = display_texture,
};
