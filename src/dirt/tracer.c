/* The DIRT structure as the integrator's tracer (views/tracer.h): the trace,
 * visibility and Fetch passes of trace.c behind the technique interface. */
#include "dirt/ads_internal.h"

static bool tr_trace(void *self, uint32_t rays, uint32_t hits, uint32_t count, unsigned flags)
{
    dirt_ads *a = self;
    dirt_trace_opts o = a->tracer_opts.trace;
    bool any_hit = (flags & DIRT_TRACER_ANY_HIT) != 0;
    o.any_hit = any_hit;
    o.from_surfaces = (flags & DIRT_TRACER_FROM_SURFACES) != 0;
    /* The raster Fetch reads the closest hits through per-tile hit lists. */
    bool link = !any_hit && a->tracer_opts.fetch == DIRT_FETCH_RASTER;
    return ads_trace_gl(a, rays, hits, count, &o, link, NULL);
}

static void tr_set_batch(void *self, uint32_t batch)
{
    dirt_ads *a = self;
    a->tracer_opts.trace.batch = batch;
}

static void tr_set_alpha(void *self, const dirt_trace_alpha *alpha)
{
    dirt_ads *a = self;
    a->tracer_opts.trace.alpha = alpha ? *alpha : (dirt_trace_alpha){0};
}

static bool tr_visibility(void *self, uint32_t rays, uint32_t hits)
{
    return ads_visibility_gl(self, rays, hits);
}

static bool tr_fetch(void *self, uint32_t rays, uint32_t hits, uint32_t count, uint32_t gpoints,
                     uint32_t slot)
{
    dirt_ads *a = self;
    return ads_fetch_gl(a, a->tracer_opts.fetch == DIRT_FETCH_RASTER, rays, hits, count, gpoints,
                        slot, a->tracer_opts.trace.batch);
}

static void tr_bind_geometry(void *self)
{
    ads_bind_geometry(self);
}

static void tr_reset_counts(void *self)
{
    ads_reset_ray_count(self);
}

static bool tr_read_counts(void *self, uint64_t *rays, uint64_t *aborted)
{
    return ads_read_counts(self, rays, aborted);
}

const dirt_tracer *dirt_ads_tracer(dirt_ads *a, const dirt_ads_tracer_opts *opts)
{
    if (!a->built) {
        DIRT_ERROR("DIRT tracer requested before a successful dirt_ads_build");
        return NULL;
    }
    a->tracer_opts = opts ? *opts : (dirt_ads_tracer_opts){0};
    a->tracer = (dirt_tracer){
        .name = "dirt",
        .self = a,
        .trace = tr_trace,
        .visibility = tr_visibility,
        .fetch = tr_fetch,
        .bind_geometry = tr_bind_geometry,
        .reset_counts = tr_reset_counts,
        .read_counts = tr_read_counts,
        .set_alpha = tr_set_alpha,
        .set_batch = tr_set_batch,
        .views = &a->set,
        .vertices_split = a->vertices.layout,
        .prim_material_split = a->prim_material.layout,
    };
    return &a->tracer;
}
