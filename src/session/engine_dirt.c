/* The dirt engine: path tracing through the DIRT structure (engine.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/log.h"
#include "session/engine_pt.h"

typedef struct dirt_state {
    engine_pt pt;               /* first: the path tracer's operations use it */
    dirt_ads *ads;
} dirt_state;

/* gpu/dirt_hits: relative t tolerance for "the same hit" on a shared edge. */
#define AGREE_T_TOL 1e-4

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

static bool check_opts(const dirt_session_opts *o, char *why, size_t size)
{
    if (o->direct_visibility && o->views == DIRT_SESSION_VIEWS_CUBE) {
        snprintf(why, size, "direct visibility needs a camera view: single or cube+camera views");
        return false;
    }
    return true;
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
static int auto_tile_size(dirt_gpu *gpu, dirt_view_opts vo, int buckets)
{
    int64_t max = dirt_gpu_get_caps(gpu)->max_ssbo_size;
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

static bool reshape(engine *e, const engine_env *env)
{
    dirt_state *d = (dirt_state *)e;
    const dirt_session_opts *o = env->opts;
    engine_pt_drop(&d->pt);
    dirt_ads_destroy(d->ads);
    d->ads = NULL;
    dirt_view_opts vo = engine_view_opts(env);
    int buckets = o->buckets ? o->buckets : dirt_session_auto_buckets(env->gpu);
    if (!o->tile_size)
        vo.tile_size = auto_tile_size(env->gpu, vo, buckets);
    enum dirt_build_mode build = o->build == DIRT_SESSION_BUILD_RASTER    ? DIRT_BUILD_RASTER
                                 : o->build == DIRT_SESSION_BUILD_COMPUTE ? DIRT_BUILD_COMPUTE
                                                                          : dirt_session_auto_build(env->gpu);
    d->ads = dirt_ads_create(env->gpu, &(dirt_ads_opts){.views = vo, .buckets = buckets,
                                                        .force_emulation = o->force_emulation,
                                                        .large = o->large, .build = build,
                                                        .large_grid = o->large_grid,
                                                        .sub_tiles = o->sub_tiles,
                                                        .bucket_masks = o->bucket_masks,
                                                        .node_depths = o->node_depths,
                                                        .depth_buckets = o->depth_buckets});
    return d->ads != NULL;
}

static void destroy(engine *e)
{
    dirt_state *d = (dirt_state *)e;
    if (!d)
        return;
    dirt_ads_destroy(d->ads);
    engine_pt_finish(&d->pt);
    free(d);
}

static engine *create(const engine_env *env)
{
    dirt_state *d = calloc(1, sizeof(*d));
    if (!d) {
        DIRT_ERROR("out of memory");
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
        return NULL;
    }
    /* The structure first, as the session always made it. */
    if (!reshape((engine *)d, env) || !engine_pt_init(&d->pt, env)) {
        destroy((engine *)d);
        return NULL;
    }
    return (engine *)d;
}

static bool build(engine *e, const engine_env *env)
{
    dirt_state *d = (dirt_state *)e;
    d->pt.tracer = NULL;
    /* The path tracer's tables first: a scene it cannot hold fails before
     * the build. */
    if (!dirt_pt_check_frame(d->pt.pt, env->frame))
        return false;
    if (!dirt_ads_build(d->ads, env->frame, env->cam))
        return false;
    dirt_ads_tracer_opts to = {.trace = {.hiz_levels = env->opts->hiz_levels},
                               .fetch = env->opts->fetch};
    d->pt.tracer = dirt_ads_tracer(d->ads, &to);
    return d->pt.tracer != NULL;
}

static void build_stats(engine *e, dirt_session_stats *st)
{
    const dirt_ads_stats *a = dirt_ads_get_stats(((dirt_state *)e)->ads);
    st->has_ads = true;
    st->ads = *a;
    for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++) {
        double ms = engine_measured_ms(a->ms[i], a->clock);
        st->build_ms += ms;
        engine_add_pass(st, dirt_ads_pass_names[i], ms, a->clock);
    }
    engine_add_buffer(st, "vertices", a->bytes_vertices, a->bytes_vertices);
    engine_add_buffer(st, "depth bounds", a->bytes_depth, a->bytes_depth);
    engine_add_buffer(st, "list heads", a->bytes_heads, a->bytes_heads);
    engine_add_buffer(st, "id nodes", a->bytes_nodes_used, a->bytes_nodes_allocated);
    engine_add_buffer(st, "candidates", a->bytes_candidates_used, a->bytes_candidates_allocated);
    engine_add_buffer(st, "large primitives' grid", a->bytes_large_grid,
                      a->bytes_large_grid_allocated);
    engine_add_buffer(st, "bucket masks", a->bytes_bucket_masks, a->bytes_bucket_masks);
    if (a->depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE) {
        engine_add_buffer(st, "bucket edges", a->bytes_bucket_edges, a->bytes_bucket_edges);
        engine_add_buffer(st, "bucket histogram", a->bytes_bucket_histogram,
                          a->bytes_bucket_histogram);
    }
}

static dirt_ads *ads_of(engine *e)
{
    return ((dirt_state *)e)->ads;
}

static bool cells(engine *e, engine_cells *c)
{
    dirt_ads *ads = ((dirt_state *)e)->ads;
    dirt_ads_data d;
    if (!dirt_ads_read(ads, &d))
        return false;
    c->set = dirt_ads_views(ads);
    bool ok = engine_cells_from_lists(c, d.num_tiles, d.buckets, d.heads,
                                      d.nodes ? &d.nodes[0][1] : NULL, 2,
                                      d.num_nodes, DIRT_LIST_END, (const float (*)[2])d.depth);
    dirt_ads_data_free(&d);
    return ok;
}

/* gpu/dirt_hits' criterion: the same primitive, or the same t within
 * AGREE_T_TOL relative, or both missing (visibility: both hit or both miss). */
static bool same_hit(const dirt_hit *d, const dirt_ref_hit *e, bool visibility)
{
    bool dh = d->prim != DIRT_HIT_NONE, eh = e->prim != DIRT_REF_MISS;
    if (visibility || !dh || !eh)
        return dh == eh;
    return d->prim == e->prim || fabs(d->t - e->t) <= AGREE_T_TOL * fmax(e->t, 1e-3);
}

static bool agree(engine *e, const engine_env *env, engine_agree *b)
{
    bool vis = b->type == DIRT_RAY_VISIBILITY;
    dirt_trace_stats ts;
    /* (every ray type but the camera's leaves a surface point, as in the
     * path tracer's batches) */
    dirt_trace_opts to = {.hiz_levels = env->opts->hiz_levels, .any_hit = vis,
                          .from_surfaces = b->type != DIRT_RAY_PRIMARY};
    dirt_ref_intersect(b->accel, (const dirt_ref_ray *)b->rays, b->ref, b->count, 0);
    dirt_ads *ads = ((dirt_state *)e)->ads;
    dirt_trace_work *w = b->count_work ? malloc((b->count + 1) * sizeof(*w)) : NULL;
    if (b->count_work && !w) {
        DIRT_ERROR("out of memory");
        return false;
    }
    bool ok = w ? dirt_ads_trace_work(ads, b->rays, b->count, b->hits, &to, &ts, w)
                : dirt_ads_trace(ads, b->rays, b->count, b->hits, &to, &ts);
    b->work = (dirt_session_work){.rays = b->count};
    for (size_t i = 0; ok && w && i < b->count; i++) {
        b->work.tiles += w[i].tiles;
        b->work.hiz_steps += w[i].hiz_steps;
        b->work.list_nodes += w[i].list_nodes;
        b->work.triangle_tests += w[i].triangle_tests;
    }
    free(w);
    if (!ok)
        return false;
    b->same = 0;
    for (size_t i = 0; i < b->count; i++)
        b->same += same_hit(&b->hits[i], &b->ref[i], vis);
    b->ms = ts.ms;
    b->clock = ts.clock;
    b->aborted = ts.aborted;
    b->thickness = 0;
    return true;
}

const engine_ops engine_dirt_ops = {
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
    .ads = ads_of,
    .cells = cells,
    .agree = agree,
};
