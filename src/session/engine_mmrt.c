/* The mmrt engine: the path tracer through the MMRT A-buffer (engine.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "session/engine_pt.h"

typedef struct mmrt_engine {
    engine_pt pt;               /* first: the path tracer's operations use it */
    dirt_mmrt *mmrt;
} mmrt_engine;

/* gpu/mmrt_hits and the path tracer: MMRT rays start this many thicknesses
 * off the surface. */
#define MMRT_OFFSET_THICKNESSES 3

static bool check_opts(const dirt_session_opts *o, char *why, size_t size)
{
    if (o->fetch == DIRT_FETCH_RASTER || o->direct_visibility) {
        snprintf(why, size, "the mmrt engine has no Fetch pass and no visibility buffer: the "
                            "raster Fetch and direct visibility are DIRT's");
        return false;
    }
    return true;
}

static dirt_mmrt_trace_opts trace_opts(const dirt_session_opts *o)
{
    return (dirt_mmrt_trace_opts){.march = o->march, .samples = o->march_samples,
                                  .hiz_levels = o->hiz_levels, .thickness = o->thickness,
                                  .seed = o->seed};
}

static bool reshape(engine *e, const engine_env *env)
{
    mmrt_engine *m = (mmrt_engine *)e;
    engine_pt_drop(&m->pt);
    dirt_mmrt_destroy(m->mmrt);
    dirt_view_opts vo = engine_view_opts(env);
    vo.tile_size = 1; /* MMRT is per pixel */
    m->mmrt = dirt_mmrt_create(env->gpu, &(dirt_mmrt_opts){
                                              .views = vo,
                                              .buckets = env->opts->buckets ? env->opts->buckets : 4,
                                          });
    return m->mmrt != NULL;
}

static void destroy(engine *e)
{
    mmrt_engine *m = (mmrt_engine *)e;
    if (!m)
        return;
    dirt_mmrt_destroy(m->mmrt);
    engine_pt_finish(&m->pt);
    free(m);
}

static engine *create(const engine_env *env)
{
    mmrt_engine *m = calloc(1, sizeof(*m));
    if (!m) {
        DIRT_ERROR("out of memory");
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        return NULL;
    }
    if (!reshape((engine *)m, env) || !engine_pt_init(&m->pt, env)) {
        destroy((engine *)m);
        return NULL;
    }
    return (engine *)m;
}

static bool build(engine *e, const engine_env *env)
{
    mmrt_engine *m = (mmrt_engine *)e;
    m->pt.tracer = NULL;
    /* The path tracer's tables first: a scene it cannot hold fails before
     * the build. */
    if (!dirt_pt_check_frame(m->pt.pt, env->frame))
        return false;
    if (!dirt_mmrt_build(m->mmrt, env->frame, env->cam))
        return false;
    dirt_mmrt_trace_opts to = trace_opts(env->opts);
    m->pt.tracer = dirt_mmrt_tracer(m->mmrt, &to);
    return m->pt.tracer != NULL;
}

static void build_stats(engine *e, dirt_session_stats *st)
{
    const dirt_mmrt_stats *m = dirt_mmrt_get_stats(((mmrt_engine *)e)->mmrt);
    st->has_mmrt = true;
    st->mmrt = *m;
    for (int i = 0; i < DIRT_MMRT_NUM_PASSES; i++) {
        double ms = engine_measured_ms(m->ms[i], m->clock);
        st->build_ms += ms;
        engine_add_pass(st, dirt_mmrt_pass_names[i], ms, m->clock);
    }
    engine_add_buffer(st, "vertices", m->bytes_vertices, m->bytes_vertices);
    engine_add_buffer(st, "depth bounds", m->bytes_depth, m->bytes_depth);
    engine_add_buffer(st, "list heads", m->bytes_heads, m->bytes_heads);
    engine_add_buffer(st, "id nodes", m->bytes_id_nodes_used, m->bytes_id_nodes_allocated);
    engine_add_buffer(st, "data nodes", m->bytes_data_nodes_used, m->bytes_data_nodes_allocated);
}

static dirt_mmrt *mmrt_of(engine *e)
{
    return ((mmrt_engine *)e)->mmrt;
}

static bool cells(engine *e, engine_cells *c)
{
    dirt_mmrt *mm = ((mmrt_engine *)e)->mmrt;
    dirt_mmrt_data d;
    if (!dirt_mmrt_read(mm, &d))
        return false;
    c->set = dirt_mmrt_views(mm);
    bool ok = engine_cells_from_lists(c, d.num_pixels, d.buckets, d.heads,
                                      d.ids ? &d.ids[0].next : NULL,
                                      sizeof(*d.ids) / sizeof(uint32_t), d.num_nodes,
                                      DIRT_MMRT_END, (const float (*)[2])d.depth);
    dirt_mmrt_data_free(&d);
    return ok;
}

/* gpu/mmrt_hits' criterion: secondary rays start, and visibility rays end,
 * MMRT_OFFSET_THICKNESSES thicknesses (the primary batch's) off the
 * surface; the same primitive or both missing; visibility against Embree's
 * occlusion. */
static bool agree(engine *e, const engine_env *env, engine_agree *b)
{
    bool vis = b->type == DIRT_RAY_VISIBILITY;
    for (size_t i = 0; b->type != DIRT_RAY_PRIMARY && i < b->count; i++) {
        dirt_ray *r = &b->rays[i];
        float len = sqrtf(r->dir[0] * r->dir[0] + r->dir[1] * r->dir[1] + r->dir[2] * r->dir[2]);
        r->tmin = MMRT_OFFSET_THICKNESSES * b->thickness / len;
        if (vis)
            r->tmax = 1 - MMRT_OFFSET_THICKNESSES * b->thickness / len;
    }
    dirt_mmrt_trace_opts mo = trace_opts(env->opts);
    mo.count = mo.count || b->count_work;
    dirt_mmrt_trace_stats ts;
    if (!dirt_mmrt_trace_cpu(((mmrt_engine *)e)->mmrt, b->rays, b->count, b->hits, &mo, &ts))
        return false;
    if (b->type == DIRT_RAY_PRIMARY)
        b->thickness = ts.thickness;
    if (vis)
        dirt_ref_occluded(b->accel, (const dirt_ref_ray *)b->rays, b->occluded, b->count, 0);
    else
        dirt_ref_intersect(b->accel, (const dirt_ref_ray *)b->rays, b->ref, b->count, 0);
    b->same = 0;
    for (size_t i = 0; i < b->count; i++) {
        bool mh = b->hits[i].prim != DIRT_HIT_NONE;
        if (vis) {
            b->same += mh == (b->occluded[i] != 0);
        } else {
            bool eh = b->ref[i].prim != DIRT_REF_MISS;
            b->same += (!mh && !eh) || (mh && eh && b->hits[i].prim == b->ref[i].prim);
        }
    }
    b->ms = ts.ms;
    b->clock = ts.clock;
    b->aborted = ts.aborted;
    b->work = (dirt_session_work){.rays = b->count};
    if (b->count_work) {
        b->work.fragments = ts.nodes_visited;
        b->work.pixels = ts.pixels_tested;
        b->work.hiz_steps = ts.steps;
    }
    return true;
}

const engine_ops engine_mmrt_ops = {
    .needs_gpu = true,
    .check_opts = check_opts,
    .create = create,
    .destroy = destroy,
    .reshape = reshape,
    .build = build,
    .build_stats = build_stats,
    .restart = engine_pt_restart,
    .add_samples = engine_pt_add_samples,
    .advance = engine_pt_advance,
    .part = engine_pt_part,
    .image = engine_pt_image,
    .display_texture = engine_pt_display_texture,
    .late_times = engine_pt_late_times,
    .write_graph_dot = engine_pt_write_graph_dot,
    .mmrt = mmrt_of,
    .cells = cells,
    .agree = agree,
};
