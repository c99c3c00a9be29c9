/* The raster engine: the rasterized preview with direct lighting, one
 * render per accumulation (engine.h). */
#include <stdio.h>
#include <stdlib.h>

#include "dirt/log.h"
#include "raster/raster.h"
#include "session/engine.h"

typedef struct raster_engine {
    dirt_raster *raster;
    dirt_image *img;            /* beauty + N.X/Y/Z, Z */
    engine_display display;
} raster_engine;

static const char *const aovs[4] = {"N.X", "N.Y", "N.Z", "Z"};

static bool reshape(engine *e, const engine_env *env)
{
    raster_engine *r = (raster_engine *)e;
    dirt_raster_destroy(r->raster);
    dirt_image_destroy(r->img);
    r->img = NULL;
    r->display.current = false;
    r->raster = dirt_raster_create(env->gpu, env->scene);
    return r->raster != NULL;
}

static void destroy(engine *e)
{
    raster_engine *r = (raster_engine *)e;
    if (!r)
        return;
    dirt_raster_destroy(r->raster);
    dirt_image_destroy(r->img);
    engine_display_release(&r->display);
    free(r);
}

static engine *create(const engine_env *env)
{
    raster_engine *r = calloc(1, sizeof(*r));
    if (!r) {
        DIRT_ERROR("out of memory");
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        return NULL;
    }
    if (!reshape((engine *)r, env)) {
        destroy((engine *)r);
        return NULL;
    }
    return (engine *)r;
}

/* Nothing to build: the preview draws the frame directly. */
static bool build(engine *e, const engine_env *env)
{
    (void)e;
    (void)env;
    return true;
}

static void build_stats(engine *e, dirt_session_stats *st)
{
    (void)e;
    (void)st;
}

static void restart(engine *e)
{
    ((raster_engine *)e)->display.current = false;
}

static bool add_samples(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                        void *user, dirt_session_stats *st, int *samples)
{
    (void)count;
    raster_engine *r = (raster_engine *)e;
    if (!r->img && !(r->img = engine_new_image(env->width, env->height, aovs, 4)))
        return false;
    size_t n = (size_t)env->width * (size_t)env->height;
    float *aov = malloc(4 * n * sizeof(float));
    dirt_raster_stats rs;
    bool ok = aov && dirt_raster_render(r->raster, env->frame, env->cam, env->width, env->height,
                                        NULL, r->img->rgba, aov, &rs);
    /* N.X, N.Y, N.Z, Z: the channels in the order added. */
    for (size_t i = 0; ok && i < n; i++) {
        for (int c = 0; c < 4; c++)
            r->img->channels[c].data[i] = aov[4 * i + (size_t)c];
    }
    free(aov);
    if (!ok)
        return false;
    r->display.current = false;
    st->num_passes = 0;
    st->num_build_passes = 0; /* nothing built: the draw is the whole image */
    for (int i = 0; i < rs.num_passes; i++) {
        const dirt_raster_pass_stats *p = &rs.passes[i];
        engine_add_pass(st, i == 0 ? "preview draw" : "preview readback",
                        engine_measured_ms(p->ms, p->clock), p->clock);
    }
    st->shade_ms = engine_measured_ms(rs.ms, rs.clock);
    *samples = 1;
    if (progress)
        progress(user, 1, 1);
    return true;
}

static const dirt_image *image(engine *e, const engine_env *env, dirt_session_stats *st)
{
    (void)env;
    (void)st;
    return ((raster_engine *)e)->img;
}

static uint32_t display_texture(engine *e, const engine_env *env)
{
    raster_engine *r = (raster_engine *)e;
    return engine_display_upload(&r->display, env->gpu, r->img);
}

/* The preview traces no rays: it has no work to count. */
static bool check_opts(const dirt_session_opts *o, char *why, size_t size)
{
    if (o->count_work) {
        snprintf(why, size, "work counters need an engine that traces rays (dirt, mmrt, embree)");
        return false;
    }
    return true;
}

const engine_ops engine_raster_ops = {
    .needs_gpu = true,
    .check_opts = check_opts,
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
