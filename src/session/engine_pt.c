/* The path tracer's half of the dirt and mmrt engines (engine_pt.h):
 * progressive accumulation through the tracer of the engine's last build. */
#include "session/engine_pt.h"

#include <string.h>

#include "dirt/log.h"

bool engine_pt_init(engine_pt *p, const engine_env *env)
{
    *p = (engine_pt){0};
    p->pt = dirt_pt_create(env->gpu, env->scene);
    return p->pt != NULL;
}

void engine_pt_finish(engine_pt *p)
{
    dirt_image_destroy(p->img);
    dirt_pt_destroy(p->pt);
    *p = (engine_pt){0};
}

void engine_pt_drop(engine_pt *p)
{
    p->tracer = NULL;
    /* The image's size is the structure's. */
    dirt_image_destroy(p->img);
    p->img = NULL;
    p->img_current = false;
    p->fresh = true;
}

void engine_pt_restart(engine *e)
{
    ((engine_pt *)e)->img_current = false;
    ((engine_pt *)e)->fresh = true;
}

static dirt_pt_opts pt_opts(const dirt_session_opts *o)
{
    return (dirt_pt_opts){
        .mode = o->mode,
        .bounces = o->bounces ? o->bounces : 4,
        .seed = o->seed,
        .background = {o->background[0], o->background[1], o->background[2]},
        .env = o->env,
        .ao_distance = o->ao_distance,
        .direct_visibility = o->direct_visibility,
        .sort_rays = o->sort_rays,
    };
}

/* The path tracer's passes of `ps` (direct visibility only when used). */
static void add_passes(dirt_session_stats *st, const dirt_pt_stats *ps, bool visibility)
{
    for (int i = 0; i < DIRT_PT_NUM_PASSES; i++) {
        if (i == DIRT_PT_PASS_VISIBILITY && !visibility)
            continue;
        engine_add_pass(st, dirt_pt_pass_names[i], ps->pass_ms[i], ps->clock);
    }
}

/* Adds one call's figures `ps` to `st`; the integrator's buffers once. */
static void add_figures(engine_pt *p, const dirt_pt_stats *ps, bool visibility,
                        dirt_session_stats *st)
{
    st->trace_ms += ps->trace_ms;
    st->fetch_ms += ps->fetch_ms;
    st->visibility_ms += ps->visibility_ms;
    st->shade_ms += ps->shade_ms;
    st->rays += ps->rays;
    st->aborted += ps->aborted;
    engine_add_paths_at_event(st, ps->paths_at_event, ps->events);
    add_passes(st, ps, visibility);
    /* The integrator's buffers once, after the structure's (the copy of the
     * completed samples may come later, with the first partial sample). */
    bool listed = false, shown = false;
    for (int i = 0; i < st->num_buffers; i++) {
        listed |= !strcmp(st->buffers[i].name, "pt accumulation");
        shown |= !strcmp(st->buffers[i].name, "pt shown accumulation");
    }
    dirt_buffer_bytes b[16];
    int nb = !listed || !shown ? dirt_pt_buffers(p->pt, p->tracer, b, 16) : 0;
    for (int i = 0; i < nb; i++)
        if (!listed || !strcmp(b[i].name, "pt shown accumulation"))
            engine_add_buffer(st, b[i].name, b[i].used, b[i].allocated);
}

/* A new accumulation (env->samples 0, and a restart or nothing in
 * progress) starts with a reset to the image size. */
static bool begin(engine_pt *p, const engine_env *env)
{
    if (env->samples == 0 && (p->fresh || dirt_pt_part_pixels(p->pt) == 0)) {
        if (!dirt_pt_reset(p->pt, env->width, env->height))
            return false;
        p->fresh = false;
    }
    return true;
}

bool engine_pt_add_samples(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                           void *user, dirt_session_stats *st, int *samples)
{
    engine_pt *p = (engine_pt *)e;
    if (!begin(p, env))
        return false;
    dirt_pt_opts po = pt_opts(env->opts);
    po.progress = progress;
    po.progress_user = user;
    dirt_pt_stats ps;
    if (!dirt_pt_add_samples(p->pt, p->tracer, env->frame, env->cam, &po, count, &ps))
        return false;
    *samples = dirt_pt_samples(p->pt);
    p->img_current = false;
    add_figures(p, &ps, po.direct_visibility, st);
    return true;
}

bool engine_pt_advance(engine *e, const engine_env *env, double budget_ms,
                       dirt_session_stats *st, int *samples, bool *completed)
{
    engine_pt *p = (engine_pt *)e;
    if (!begin(p, env))
        return false;
    dirt_pt_opts po = pt_opts(env->opts);
    dirt_pt_stats ps;
    if (!dirt_pt_advance(p->pt, p->tracer, env->frame, env->cam, &po, budget_ms, completed, &ps))
        return false;
    *samples = dirt_pt_samples(p->pt);
    if (*completed)
        p->img_current = false;
    add_figures(p, &ps, po.direct_visibility, st);
    return true;
}

double engine_pt_part(const engine *e, const engine_env *env)
{
    const engine_pt *p = (const engine_pt *)e;
    size_t px = (size_t)env->width * (size_t)env->height;
    size_t done = p->fresh ? 0 : dirt_pt_part_pixels(p->pt); /* a restart dropped it */
    return px ? (double)done / (double)px : 0.0;
}

void engine_pt_late_times(engine *e, const engine_env *env, bool wait, dirt_session_stats *st)
{
    engine_pt *p = (engine_pt *)e;
    if (!p->pt || !env->samples)
        return;
    dirt_pt_stats late;
    dirt_pt_take_late_times(p->pt, wait, &late);
    if (late.clock == DIRT_CLOCK_NONE)
        return;
    st->trace_ms += late.trace_ms;
    st->fetch_ms += late.fetch_ms;
    st->visibility_ms += late.visibility_ms;
    st->shade_ms += late.shade_ms;
    add_passes(st, &late, env->opts->direct_visibility);
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
}

const dirt_image *engine_pt_image(engine *e, const engine_env *env, dirt_session_stats *st)
{
    engine_pt *p = (engine_pt *)e;
    if (p->img_current)
        return p->img;
    if (!p->img || p->img->width != env->width || p->img->height != env->height) {
        dirt_image_destroy(p->img);
        p->img = engine_new_image(env->width, env->height, engine_pt_aovs, 8);
        if (!p->img)
            return NULL;
    }
    if (!dirt_pt_read(p->pt, p->img, &st->invalid_samples))
        return NULL;
    engine_pt_late_times(e, env, false, st); /* the readback drained them */
    p->img_current = true;
    return p->img;
}

uint32_t engine_pt_display_texture(engine *e, const engine_env *env)
{
    (void)env;
    return dirt_pt_display_texture(((engine_pt *)e)->pt);
}

bool engine_pt_write_graph_dot(const engine *e, const char *path)
{
    return dirt_pt_write_dot(((const engine_pt *)e)->pt, path);
}
