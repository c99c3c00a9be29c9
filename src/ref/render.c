/* DIRT engine, src/ref: CPU path tracer and ambient occlusion on Embree,
 * the ground truth for the GPU integrators. The estimator is specified in
 * doc/light-transport.md (section "Path tracing") and the random numbers in
 * doc/rng.md; the GPU implementation must make the same decisions with the
 * same dimensions of the same RNG. */
#include "ref/ref.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/clock.h"
#include "integrator/integrator.h"
#include "dirt/log.h"
#include "integrator/rng.h"
#include "core/vec3.h"
#include "ref/parallel.h"

#define TILE DIRT_REF_TILE
#define DEFAULT_WIDTH 640
#define DEFAULT_HEIGHT 480
#define DEFAULT_SPP 16
#define DEFAULT_BOUNCES 4
/* Shadow rays stop this fraction short of the light sample. */
#define SHADOW_SHORTEN 1e-4f

typedef struct render_ctx {
    const dirt_ref_materials *mats;
    const dirt_frame *frame;
    const dirt_camera *cam;
    const dirt_ref_accel *accel;
    dirt_area_lights area;
    unsigned num_sources; /* NEE light sources: area set (if any) + punctual */
    int width, height, spp, bounces;
    uint32_t first_sample, seed;
    enum dirt_ref_mode mode;
    float ao_distance;
    const dirt_env *env;  /* NULL: nothing beyond the scene */
    dirt_env *own_env;    /* the background's constant map */
    int tiles_x, tiles_y;
    size_t first_tile;    /* the part rendered: tiles first_tile + [0, count) */

    float *rgba, *albedo[3], *normal[3], *depth, *ids;

    atomic_uint_fast64_t rays, invalid;
    atomic_uint_fast64_t events[DIRT_PT_MAX_EVENTS]; /* paths that reached event k */
    pthread_mutex_t progress_lock;
    uint64_t done, total;
    dirt_ref_progress_fn progress;
    void *progress_user;
} render_ctx;

/* Everything the estimator needs about a hit point. */
typedef struct vertex {
    uint32_t prim;
    dirt_vec3 p;       /* position (from barycentrics) */
    dirt_vec3 ng;      /* unit geometric normal, facing the incoming ray */
    dirt_vec3 t, b, n; /* shading frame, n facing the incoming ray */
    dirt_vec3 wo;      /* local direction towards the previous vertex */
    bool front;        /* the ray hit the winding-front side */
    dirt_surface surf;
    dirt_vec3 le;      /* emitted radiance towards the previous vertex */
    dirt_vec3 origin;  /* p offset along ng: origin of rays leaving the vertex
                          on the side of the incoming ray */
    dirt_vec3 origin_below; /* p offset along -ng: origin of rays transmitted
                          through the surface */
} vertex;

/* Offset of spawned ray origins along the geometric normal (doc: "Rays"). */
static float ray_epsilon(dirt_vec3 p)
{
    float m = fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z)));
    return 1e-4f * fmaxf(1.0f, m);
}

static float mat_specular(const render_ctx *c, uint32_t m)
{
    return c->mats->specular ? c->mats->specular[m] : 1.0f;
}

static dirt_vec3 tri_point(const dirt_frame *f, uint32_t prim, float b1, float b2)
{
    dirt_vec3 p0 = v3_load(f->position[3 * (size_t)prim]);
    dirt_vec3 p1 = v3_load(f->position[3 * (size_t)prim + 1]);
    dirt_vec3 p2 = v3_load(f->position[3 * (size_t)prim + 2]);
    dirt_vec3 r = v3_scale(p0, 1.0f - b1 - b2);
    r = v3_mad(r, p1, b1);
    return v3_mad(r, p2, b2);
}

static void tri_uv(const dirt_frame *f, uint32_t prim, float b1, float b2, float uv[2])
{
    if (!f->uv) {
        uv[0] = uv[1] = 0.0f;
        return;
    }
    const float *t0 = f->uv[3 * (size_t)prim], *t1 = f->uv[3 * (size_t)prim + 1],
                *t2 = f->uv[3 * (size_t)prim + 2];
    float b0 = 1.0f - b1 - b2;
    uv[0] = b0 * t0[0] + b1 * t1[0] + b2 * t2[0];
    uv[1] = b0 * t0[1] + b1 * t1[1] + b2 * t2[1];
}

static dirt_vec3 tri_normal_ng(const dirt_frame *f, uint32_t prim)
{
    dirt_vec3 p0 = v3_load(f->position[3 * (size_t)prim]);
    dirt_vec3 e1 = v3_sub(v3_load(f->position[3 * (size_t)prim + 1]), p0);
    dirt_vec3 e2 = v3_sub(v3_load(f->position[3 * (size_t)prim + 2]), p0);
    return v3_normalize(v3_cross(e1, e2));
}

/* Fills v from a hit of a ray with unit direction `dir`. */
static void make_vertex(const render_ctx *c, dirt_vec3 dir, const dirt_ref_hit *h, vertex *v)
{
    const dirt_frame *f = c->frame;
    uint32_t prim = h->prim;
    v->prim = prim;
    v->p = tri_point(f, prim, h->u, h->v);
    dirt_vec3 ng = v3_load(h->ng);
    v->front = v3_dot(ng, dir) < 0.0f;
    if (!v->front)
        ng = v3_neg(ng);
    v->ng = ng;

    float uv[2];
    tri_uv(f, prim, h->u, h->v, uv);
    uint32_t m = f->material[prim];
    dirt_vec3 ns = ng;
    if (f->normal) {
        float b0 = 1.0f - h->u - h->v;
        dirt_vec3 n0 = v3_load(f->normal[3 * (size_t)prim]);
        dirt_vec3 n1 = v3_load(f->normal[3 * (size_t)prim + 1]);
        dirt_vec3 n2 = v3_load(f->normal[3 * (size_t)prim + 2]);
        dirt_vec3 n = v3_normalize(v3_mad(v3_mad(v3_scale(n0, b0), n1, h->u), n2, h->v));
        dirt_vec3 n_ts;
        if (f->tangent && dirt_material_normal_ts(&c->mats->materials[m], c->mats->textures,
                                                  c->mats->num_textures, uv[0], uv[1], &n_ts)) {
            /* Normal map (doc/light-transport.md, section 1): the front
             * side's normal, flipped below like the interpolated one. */
            const float *t0 = f->tangent[3 * (size_t)prim], *t1 = f->tangent[3 * (size_t)prim + 1],
                        *t2 = f->tangent[3 * (size_t)prim + 2];
            dirt_vec3 t = v3_mad(v3_mad(v3_scale(v3_load(t0), b0), v3_load(t1), h->u),
                                 v3_load(t2), h->v);
            float w = b0 * t0[3] + h->u * t1[3] + h->v * t2[3];
            n = dirt_normal_map_apply(n, t, w, n_ts);
        }
        if (!v->front)
            n = v3_neg(n);
        if (v3_is_finite(n) && v3_dot(n, ng) > 0.0f)
            ns = n;
    }
    dirt_vec3 wo_world = v3_neg(dir);
    dirt_onb(ns, &v->t, &v->b);
    v->n = ns;
    v->wo = v3_to_local(wo_world, v->t, v->b, v->n);
    if (v->wo.z <= 0.0f) { /* viewer below the shading normal: shade with ng */
        v->n = ng;
        dirt_onb(ng, &v->t, &v->b);
        v->wo = v3_to_local(wo_world, v->t, v->b, v->n);
    }

    dirt_material_surface(&c->mats->materials[m], mat_specular(c, m), c->mats->textures,
                          c->mats->num_textures, uv[0], uv[1], &v->surf);
    if (!v->front) /* leaving the material: the relative index inverts */
        v->surf.bsdf.eta = 1.0f / v->surf.bsdf.eta;
    v->le = (v->front || v->surf.double_sided) ? v->surf.emission : v3(0.0f, 0.0f, 0.0f);
    v->origin = v3_mad(v->p, ng, ray_epsilon(v->p));
    v->origin_below = v3_mad(v->p, ng, -ray_epsilon(v->p));
}

/* Whether light from world direction wi can reach v's BSDF, and on which
 * side: above the geometric surface (dot(wi, ng) > 0), or below it when the
 * BSDF transmits (*below); the local direction *wl must lie on the same
 * side of the shading frame (wl.z of the same sign). */
static bool light_side(const vertex *v, dirt_vec3 wi, dirt_vec3 *wl, bool *below)
{
    float d = v3_dot(wi, v->ng);
    *wl = v3_to_local(wi, v->t, v->b, v->n);
    *below = d < 0.0f;
    if (d > 0.0f)
        return wl->z > 0.0f;
    return *below && dirt_bsdf_transmits(&v->surf.bsdf) && wl->z < 0.0f;
}

/* `akey`: the ray's alpha key (doc/rng.md, "Alpha"). */
static bool trace(render_ctx *c, uint64_t *rays, dirt_vec3 org, dirt_vec3 dir, float tmax,
                  uint32_t akey, dirt_ref_hit *hit)
{
    dirt_ref_ray r = {{org.x, org.y, org.z}, 0.0f, {dir.x, dir.y, dir.z}, tmax};
    (*rays)++;
    return dirt_ref_intersect1_key(c->accel, &r, akey, hit);
}

static bool occluded(render_ctx *c, uint64_t *rays, dirt_vec3 org, dirt_vec3 dir, float tmax,
                     uint32_t akey)
{
    dirt_ref_ray r = {{org.x, org.y, org.z}, 0.0f, {dir.x, dir.y, dir.z}, tmax};
    (*rays)++;
    return dirt_ref_occluded1_key(c->accel, &r, akey);
}

/* Whether anything blocks the segment from a vertex's ray origin `org`
 * (origin, or origin_below for light through the surface) to the light
 * point y (the shadow ray stops SHADOW_SHORTEN short of y). Aimed from the
 * origin itself: a ray from the origin along the direction from v->p would
 * end ray_epsilon off y and could pass through the light (shadowing it by
 * itself) when the light is closer than the magnitude of the coordinates. */
static bool occluded_to(render_ctx *c, uint64_t *rays, dirt_vec3 org, dirt_vec3 y,
                        uint32_t akey)
{
    dirt_vec3 d = v3_sub(y, org);
    float len = v3_length(d);
    if (!(len > 0.0f))
        return false;
    return occluded(c, rays, org, v3_scale(d, 1.0f / len), len * (1.0f - SHADOW_SHORTEN),
                    akey);
}

/* Solid-angle pdf with which NEE picks direction `dir` towards a point of
 * emissive triangle `prim` at distance `dist` (including the 1 / n source
 * choice). 0 when the point cannot be sampled. */
static float light_pdf(const render_ctx *c, uint32_t prim, dirt_vec3 dir, float dist)
{
    if (c->area.count == 0)
        return 0.0f;
    float cos_l = fabsf(v3_dot(tri_normal_ng(c->frame, prim), dir));
    if (!(cos_l > 0.0f))
        return 0.0f;
    return dist * dist / (cos_l * c->area.total_area * (float)c->num_sources);
}

/* Solid-angle pdf with which NEE picks direction `dir` of the environment
 * (including the 1 / n source choice). */
static float env_light_pdf(const render_ctx *c, dirt_vec3 dir)
{
    return dirt_env_pdf(c->env, dir) / (float)c->num_sources;
}

/* Next-event estimation at vertex v: one light source, one shadow ray.
 * Light geometry (direction, distance, pdf) is taken from the surface point
 * p; only the shadow ray starts at the offset origin (along the same
 * direction). Returns the contribution before multiplying by the path
 * throughput. */
static dirt_vec3 sample_light(render_ctx *c, uint64_t *rays, const vertex *v, uint32_t key)
{
    dirt_vec3 zero = v3(0.0f, 0.0f, 0.0f);
    unsigned n = c->num_sources;
    if (n == 0)
        return zero;
    uint32_t akey = dirt_rng_next(key, DIRT_RNG_DIM_ALPHA_SHADOW); /* the shadow ray's */
    float us = dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_SELECT);
    unsigned s = (unsigned)(us * (float)n);
    if (s >= n)
        s = n - 1;

    if (c->area.count > 0 && s == 0) {
        size_t idx = dirt_area_lights_select(&c->area, dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_TRI));
        uint32_t prim = c->area.prim[idx];
        float b1, b2;
        dirt_sample_triangle(dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_U),
                             dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_V), &b1, &b2);
        dirt_vec3 y = tri_point(c->frame, prim, b1, b2);
        dirt_vec3 to = v3_sub(y, v->p);
        float dist = v3_length(to);
        if (!(dist > 0.0f))
            return zero;
        dirt_vec3 wi = v3_scale(to, 1.0f / dist), wl;
        bool below;
        if (!light_side(v, wi, &wl, &below))
            return zero;
        dirt_vec3 nl = tri_normal_ng(c->frame, prim);
        float cos_l = -v3_dot(nl, wi);
        uint32_t m = c->frame->material[prim];
        const dirt_material *mat = &c->mats->materials[m];
        if (cos_l < 0.0f && !mat->double_sided)
            return zero; /* back of a one-sided emitter */
        dirt_vec3 f = dirt_bsdf_eval(&v->surf.bsdf, v->wo, wl);
        if (v3_is_zero(f))
            return zero;
        float pdf_l = light_pdf(c, prim, wi, dist);
        if (!(pdf_l > 0.0f) || !isfinite(pdf_l))
            return zero;
        float uv[2];
        dirt_surface ls;
        tri_uv(c->frame, prim, b1, b2, uv);
        dirt_material_surface(mat, mat_specular(c, m), c->mats->textures, c->mats->num_textures,
                              uv[0], uv[1], &ls);
        if (v3_is_zero(ls.emission))
            return zero;
        if (occluded_to(c, rays, below ? v->origin_below : v->origin, y, akey))
            return zero;
        float w = dirt_mis_power(pdf_l, dirt_bsdf_pdf(&v->surf.bsdf, v->wo, wl));
        return v3_scale(v3_mul(f, ls.emission), fabsf(wl.z) * w / pdf_l);
    }

    if (dirt_env_samples(c->env) && s == n - 1) {
        dirt_vec3 wi, le;
        float pdf_e;
        if (!dirt_env_sample(c->env, dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_TRI),
                             dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_U),
                             dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_V), &wi, &pdf_e, &le))
            return zero;
        dirt_vec3 wl;
        bool below;
        if (!light_side(v, wi, &wl, &below))
            return zero;
        dirt_vec3 f = dirt_bsdf_eval(&v->surf.bsdf, v->wo, wl);
        if (v3_is_zero(f))
            return zero;
        float pdf_l = pdf_e / (float)n;
        if (occluded(c, rays, below ? v->origin_below : v->origin, wi, INFINITY, akey))
            return zero;
        float w = dirt_mis_power(pdf_l, dirt_bsdf_pdf(&v->surf.bsdf, v->wo, wl));
        return v3_scale(v3_mul(f, le), fabsf(wl.z) * w / pdf_l);
    }

    const dirt_light *light = &c->frame->lights[s - (c->area.count > 0 ? 1u : 0u)];
    dirt_vec3 wi, li;
    float dist;
    if (!dirt_punctual_light(light, v->p, &wi, &dist, &li))
        return zero;
    dirt_vec3 wl;
    bool below;
    if (!light_side(v, wi, &wl, &below))
        return zero;
    dirt_vec3 f = dirt_bsdf_eval(&v->surf.bsdf, v->wo, wl);
    if (v3_is_zero(f))
        return zero;
    dirt_vec3 org = below ? v->origin_below : v->origin;
    if (isinf(dist) ? occluded(c, rays, org, wi, INFINITY, akey)
                    : occluded_to(c, rays, org, v3_mad(v->p, wi, dist), akey))
        return zero;
    return v3_scale(v3_mul(f, li), fabsf(wl.z) * (float)n);
}

/* First-hit data of one sample (AOVs). */
typedef struct first_hit {
    bool hit;
    dirt_vec3 albedo, normal;
} first_hit;

/* One path-traced sample of pixel `pixel` through (org, dir). */
/* One path; events[k] counts it when it reaches event k (its k-th ray). */
static dirt_vec3 path_sample(render_ctx *c, uint64_t *rays, uint64_t *events, uint32_t pixel,
                             uint32_t sample, dirt_vec3 org, dirt_vec3 dir, first_hit *fh)
{
    dirt_vec3 l = v3(0.0f, 0.0f, 0.0f), beta = v3(1.0f, 1.0f, 1.0f);
    float prev_pdf = 0.0f;
    bool prev_delta = true; /* the camera ray counts emission fully */
    /* The alpha key of the ray leaving the previous vertex (0: the camera). */
    uint32_t akey = dirt_rng_u32(c->seed, pixel, sample, 0u, DIRT_RNG_DIM_ALPHA_PATH);
    for (int k = 1;; k++) {
        if (k < DIRT_PT_MAX_EVENTS)
            events[k]++;
        dirt_ref_hit h;
        if (!trace(c, rays, org, dir, INFINITY, akey, &h)) {
            dirt_vec3 le = dirt_env_eval(c->env, dir);
            float w = 1.0f;
            if (!prev_delta && !v3_is_zero(le))
                w = dirt_mis_power(prev_pdf, env_light_pdf(c, dir));
            l = v3_add(l, v3_scale(v3_mul(beta, le), w));
            break;
        }
        vertex v;
        make_vertex(c, dir, &h, &v);
        if (k == 1) {
            fh->hit = true;
            fh->albedo = v.surf.bsdf.base_color;
            fh->normal = v.n;
        }
        if (!v3_is_zero(v.le)) {
            float w = 1.0f;
            if (!prev_delta) {
                float pl = light_pdf(c, v.prim, dir, h.t);
                w = dirt_mis_power(prev_pdf, pl);
            }
            l = v3_add(l, v3_scale(v3_mul(beta, v.le), w));
        }
        if (k > c->bounces)
            break;

        uint32_t key = dirt_rng_key(c->seed, pixel, sample, (uint32_t)k);
        l = v3_add(l, v3_mul(beta, sample_light(c, rays, &v, key)));

        dirt_bsdf_sample s;
        if (!dirt_bsdf_sample_dir(&v.surf.bsdf, v.wo, dirt_rng_next_float(key, DIRT_RNG_DIM_LOBE),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_U),
                                  dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_V), &s))
            break;
        dirt_vec3 wi = v3_from_local(s.wi, v.t, v.b, v.n);
        bool below = s.wi.z < 0.0f; /* transmitted through the surface */
        float side = v3_dot(wi, v.ng);
        if (below ? !(side < 0.0f) : side <= 0.0f)
            break; /* the shading and geometric sides disagree */
        beta = v3_mul(beta, s.weight);
        prev_pdf = s.pdf;
        prev_delta = s.delta;
        if (k >= DIRT_RR_START_VERTEX) {
            float q = dirt_rr_survival(beta);
            if (q < 1.0f) {
                if (!(dirt_rng_next_float(key, DIRT_RNG_DIM_RR) < q))
                    break;
                beta = v3_scale(beta, 1.0f / q);
            }
        }
        org = below ? v.origin_below : v.origin;
        dir = v3_normalize(wi);
        akey = dirt_rng_next(key, DIRT_RNG_DIM_ALPHA_PATH);
    }
    return l;
}

/* One ambient-occlusion sample: 1 unblocked (or camera miss), 0 blocked. */
static float ao_sample(render_ctx *c, uint64_t *rays, uint32_t pixel, uint32_t sample,
                       dirt_vec3 org, dirt_vec3 dir, first_hit *fh)
{
    dirt_ref_hit h;
    if (!trace(c, rays, org, dir, INFINITY,
               dirt_rng_u32(c->seed, pixel, sample, 0u, DIRT_RNG_DIM_ALPHA_PATH), &h))
        return 1.0f;
    vertex v;
    make_vertex(c, dir, &h, &v);
    fh->hit = true;
    fh->albedo = v.surf.bsdf.base_color;
    fh->normal = v.n;
    uint32_t key = dirt_rng_key(c->seed, pixel, sample, 1u);
    dirt_vec3 wl = dirt_sample_cosine(dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_U),
                                      dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_V));
    dirt_vec3 wi = v3_normalize(v3_from_local(wl, v.t, v.b, v.n));
    if (v3_dot(wi, v.ng) <= 0.0f)
        return 0.0f; /* enters the surface itself */
    return occluded(c, rays, v.origin, wi, c->ao_distance,
                    dirt_rng_next(key, DIRT_RNG_DIM_ALPHA_SHADOW)) ? 0.0f : 1.0f;
}

static void render_pixel(render_ctx *c, uint64_t *rays, uint64_t *events, int x, int y)
{
    uint32_t pixel = (uint32_t)y * (uint32_t)c->width + (uint32_t)x;
    size_t i = (size_t)pixel;
    double sum[3] = {0.0, 0.0, 0.0}, alb[3] = {0.0, 0.0, 0.0}, nrm[3] = {0.0, 0.0, 0.0};
    uint64_t bad = 0;
    for (int s = 0; s < c->spp; s++) {
        uint32_t sample = c->first_sample + (uint32_t)s;
        uint32_t key = dirt_rng_key(c->seed, pixel, sample, 0u);
        float px = (float)x + dirt_rng_next_float(key, DIRT_RNG_DIM_PIXEL_X);
        float py = (float)y + dirt_rng_next_float(key, DIRT_RNG_DIM_PIXEL_Y);
        dirt_vec3 org, dir;
        dirt_camera_ray(c->cam, c->width, c->height, px, py,
                        dirt_rng_next_float(key, DIRT_RNG_DIM_LENS_U),
                        dirt_rng_next_float(key, DIRT_RNG_DIM_LENS_V), &org, &dir);
        first_hit fh = {false, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
        dirt_vec3 l;
        if (c->mode == DIRT_REF_MODE_AO) {
            float a = ao_sample(c, rays, pixel, sample, org, dir, &fh);
            l = v3(a, a, a);
            events[1]++;
        } else {
            l = path_sample(c, rays, events, pixel, sample, org, dir, &fh);
        }
        if (!v3_is_finite(l)) {
            bad++;
            l = v3(0.0f, 0.0f, 0.0f);
        }
        sum[0] += l.x;
        sum[1] += l.y;
        sum[2] += l.z;
        if (fh.hit) {
            alb[0] += fh.albedo.x;
            alb[1] += fh.albedo.y;
            alb[2] += fh.albedo.z;
            nrm[0] += fh.normal.x;
            nrm[1] += fh.normal.y;
            nrm[2] += fh.normal.z;
        }
    }
    double inv = 1.0 / (double)c->spp;
    for (int k = 0; k < 3; k++) {
        c->rgba[4 * i + (size_t)k] = (float)(sum[k] * inv);
        c->albedo[k][i] = (float)(alb[k] * inv);
        c->normal[k][i] = (float)(nrm[k] * inv);
    }
    c->rgba[4 * i + 3] = 1.0f;

    /* Z: pinhole ray through the pixel centre. */
    dirt_vec3 org, dir;
    dirt_camera_ray(c->cam, c->width, c->height, (float)x + 0.5f, (float)y + 0.5f, 0.0f, 0.0f,
                    &org, &dir);
    dirt_ref_hit h;
    if (trace(c, rays, org, dir, INFINITY,
              dirt_rng_u32(c->seed, pixel, DIRT_RNG_SAMPLE_AOV, 0u, DIRT_RNG_DIM_ALPHA_PATH), &h)) {
        dirt_vec3 p = v3_mad(org, dir, h.t);
        c->depth[i] = v3_dot(v3_sub(p, v3_load(c->cam->eye)), v3_normalize(v3_load(c->cam->forward)));
        c->ids[i] = (float)h.prim;
    } else {
        c->depth[i] = INFINITY;
        c->ids[i] = -1.0f;
    }
    if (bad)
        atomic_fetch_add(&c->invalid, bad);
}

static void render_tiles(void *ctx, size_t begin, size_t end, int worker)
{
    render_ctx *c = ctx;
    (void)worker;
    for (size_t i = begin; i < end; i++) {
        size_t t = c->first_tile + i;
        int tx = (int)(t % (size_t)c->tiles_x), ty = (int)(t / (size_t)c->tiles_x);
        int x0 = tx * TILE, y0 = ty * TILE;
        int x1 = x0 + TILE < c->width ? x0 + TILE : c->width;
        int y1 = y0 + TILE < c->height ? y0 + TILE : c->height;
        uint64_t rays = 0, events[DIRT_PT_MAX_EVENTS] = {0};
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++)
                render_pixel(c, &rays, events, x, y);
        atomic_fetch_add(&c->rays, rays);
        for (int k = 1; k < DIRT_PT_MAX_EVENTS; k++) {
            if (events[k])
                atomic_fetch_add(&c->events[k], events[k]);
        }
        if (c->progress) {
            pthread_mutex_lock(&c->progress_lock);
            c->done += (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0) * (uint64_t)c->spp;
            c->progress(c->progress_user, c->done, c->total);
            pthread_mutex_unlock(&c->progress_lock);
        }
    }
}

static bool check_opts(const dirt_ref_opts *o)
{
    if (o->width < 1 || o->height < 1 || o->width > DIRT_IMAGE_MAX_DIM ||
        o->height > DIRT_IMAGE_MAX_DIM) {
        DIRT_ERROR("reference render: image size %dx%d out of range", o->width, o->height);
        return false;
    }
    if (o->spp < 1) {
        DIRT_ERROR("reference render: spp %d must be >= 1", o->spp);
        return false;
    }
    if (o->bounces < 1 || o->bounces > 1000) {
        DIRT_ERROR("reference render: bounces %d out of [1, 1000]", o->bounces);
        return false;
    }
    if (o->mode != DIRT_REF_MODE_PT && o->mode != DIRT_REF_MODE_AO) {
        DIRT_ERROR("reference render: unknown mode %d", (int)o->mode);
        return false;
    }
    if (!(o->ao_distance >= 0.0f)) {
        DIRT_ERROR("reference render: AO distance %g must be >= 0", (double)o->ao_distance);
        return false;
    }
    for (int k = 0; k < 3; k++) {
        if (!(o->background[k] >= 0.0f) || !isfinite(o->background[k])) {
            DIRT_ERROR("reference render: background radiance must be finite and >= 0");
            return false;
        }
    }
    return true;
}

size_t dirt_ref_num_tiles(int width, int height)
{
    if (width < 1 || height < 1)
        return 0;
    return (size_t)((width + TILE - 1) / TILE) * (size_t)((height + TILE - 1) / TILE);
}

/* Pixels of the tiles [first, first + count) of a c->width x c->height image. */
static uint64_t part_pixels(const render_ctx *c, size_t first, size_t count)
{
    uint64_t n = 0;
    for (size_t t = first; t < first + count; t++) {
        int tx = (int)(t % (size_t)c->tiles_x), ty = (int)(t / (size_t)c->tiles_x);
        int w = c->width - tx * TILE < TILE ? c->width - tx * TILE : TILE;
        int h = c->height - ty * TILE < TILE ? c->height - ty * TILE : TILE;
        n += (uint64_t)w * (uint64_t)h;
    }
    return n;
}

dirt_image *dirt_ref_render_materials(const dirt_ref_materials *materials,
                                      const dirt_frame *frame,
                                      const dirt_camera *camera,
                                      const dirt_ref_opts *opts,
                                      dirt_ref_stats *stats)
{
    dirt_ref_opts o = {0};
    render_ctx c;
    dirt_image *img = NULL;
    dirt_ref_accel *own = NULL;
    bool lock_ready = false;
    static const char *const albedo_names[3] = {"albedo.R", "albedo.G", "albedo.B"};
    static const char *const normal_names[3] = {"N.X", "N.Y", "N.Z"};

    memset(&c, 0, sizeof(c));
    if (stats)
        memset(stats, 0, sizeof(*stats));
    if (!materials || !frame || !camera) {
        DIRT_ERROR("reference render: NULL materials, frame or camera");
        return NULL;
    }
    if (opts)
        o = *opts;
    if (o.width == 0)
        o.width = DEFAULT_WIDTH;
    if (o.height == 0)
        o.height = DEFAULT_HEIGHT;
    if (o.spp == 0)
        o.spp = DEFAULT_SPP;
    if (o.bounces == 0)
        o.bounces = DEFAULT_BOUNCES;
    if (!check_opts(&o))
        return NULL;
    for (size_t p = 0; p < frame->num_triangles; p++) {
        if (frame->material[p] >= materials->num_materials) {
            DIRT_ERROR("reference render: triangle %zu has material %u, scene has %zu", p,
                       frame->material[p], materials->num_materials);
            return NULL;
        }
    }
    if (frame->num_lights > 0 && !frame->lights) {
        DIRT_ERROR("reference render: frame has %zu lights but no light array", frame->num_lights);
        return NULL;
    }

    c.mats = materials;
    c.frame = frame;
    c.cam = camera;
    c.width = o.width;
    c.height = o.height;
    c.spp = o.spp;
    c.bounces = o.bounces;
    c.first_sample = o.first_sample;
    c.seed = o.seed;
    c.mode = o.mode;
    c.ao_distance = o.ao_distance > 0.0f ? o.ao_distance : INFINITY;
    if (o.env) {
        c.env = o.env;
    } else if (o.background[0] > 0.0f || o.background[1] > 0.0f || o.background[2] > 0.0f) {
        c.own_env = dirt_env_constant(o.background);
        if (!c.own_env)
            return NULL;
        c.env = c.own_env;
    }
    c.tiles_x = (o.width + TILE - 1) / TILE;
    c.tiles_y = (o.height + TILE - 1) / TILE;
    size_t all_tiles = (size_t)c.tiles_x * (size_t)c.tiles_y;
    if (o.first_tile >= all_tiles || o.num_tiles > all_tiles - o.first_tile) {
        DIRT_ERROR("reference render: tiles %zu + %zu of %zu", o.first_tile, o.num_tiles,
                   all_tiles);
        dirt_env_destroy(c.own_env);
        return NULL;
    }
    size_t count = o.num_tiles ? o.num_tiles : all_tiles - o.first_tile;
    c.first_tile = o.first_tile;
    c.progress = o.progress;
    c.progress_user = o.progress_user;
    c.total = part_pixels(&c, o.first_tile, count) * (uint64_t)o.spp;
    atomic_init(&c.rays, 0);
    atomic_init(&c.invalid, 0);
    for (int k = 0; k < DIRT_PT_MAX_EVENTS; k++)
        atomic_init(&c.events[k], 0);

    bool alpha = false; /* a triangle has an alpha-tested material */
    for (size_t p = 0; p < frame->num_triangles && !alpha; p++)
        alpha = dirt_material_alpha_tested(&materials->materials[frame->material[p]]);
    if (o.accel) {
        if (dirt_ref_accel_num_prims(o.accel) != frame->num_triangles) {
            DIRT_ERROR("reference render: accel has %zu triangles, frame %zu",
                       dirt_ref_accel_num_prims(o.accel), frame->num_triangles);
            goto error;
        }
        if (alpha && !dirt_ref_accel_alpha_tested(o.accel)) {
            DIRT_ERROR("reference render: the frame has MASK or BLEND materials but the given "
                       "accel was built without them (dirt_ref_accel_opts.alpha)");
            goto error;
        }
        c.accel = o.accel;
    } else {
        dirt_ref_accel_opts ao = {0};
        ao.threads = o.threads;
        ao.alpha = materials;
        own = dirt_ref_accel_create(frame, &ao);
        if (!own)
            goto error;
        c.accel = own;
        if (stats) {
            dirt_ref_build_stats bs;
            dirt_ref_accel_stats(own, &bs);
            stats->build_ms = bs.build_ms;
            stats->mprims_per_s = bs.mprims_per_s;
        }
    }

    if (o.mode == DIRT_REF_MODE_PT) {
        if (!dirt_area_lights_build(&c.area, frame, materials->materials, materials->num_materials))
            goto error;
        c.num_sources = dirt_nee_source_count(c.area.count, frame->num_lights,
                                              dirt_env_samples(c.env));
    }

    if (o.into) {
        img = o.into;
        if (img->width != o.width || img->height != o.height) {
            DIRT_ERROR("reference render: the image to render into is %dx%d, not %dx%d",
                       img->width, img->height, o.width, o.height);
            img = NULL;
            goto error;
        }
        for (int k = 0; k < 3; k++) {
            c.albedo[k] = dirt_image_find_channel(img, albedo_names[k]);
            c.normal[k] = dirt_image_find_channel(img, normal_names[k]);
        }
        c.depth = dirt_image_find_channel(img, "Z");
        c.ids = dirt_image_find_channel(img, "ID");
        if (!c.albedo[0] || !c.albedo[1] || !c.albedo[2] || !c.normal[0] || !c.normal[1] ||
            !c.normal[2] || !c.depth || !c.ids) {
            DIRT_ERROR("reference render: the image to render into lacks a channel of a render");
            img = NULL;
            goto error;
        }
    } else {
        img = dirt_image_create(o.width, o.height);
        if (!img)
            goto error;
        for (int k = 0; k < 3; k++) {
            c.albedo[k] = dirt_image_add_channel(img, albedo_names[k]);
            c.normal[k] = dirt_image_add_channel(img, normal_names[k]);
            if (!c.albedo[k] || !c.normal[k])
                goto error;
        }
        c.depth = dirt_image_add_channel(img, "Z");
        c.ids = dirt_image_add_channel(img, "ID");
        if (!c.depth || !c.ids)
            goto error;
    }
    c.rgba = img->rgba;
    if (pthread_mutex_init(&c.progress_lock, NULL) != 0) {
        DIRT_ERROR("reference render: pthread_mutex_init failed");
        goto error;
    }
    lock_ready = true;

    double t0 = dirt_clock_ms();
    int used = ref_parallel_for(count, 1, o.threads, render_tiles, &c);
    double t1 = dirt_clock_ms();

    uint64_t invalid = atomic_load(&c.invalid);
    if (invalid)
        DIRT_WARN("reference render: %llu non-finite samples replaced by 0",
                  (unsigned long long)invalid);
    if (stats) {
        stats->seconds = (t1 - t0) * 1e-3;
        stats->rays = atomic_load(&c.rays);
        stats->mrays_per_s = stats->seconds > 0.0 ? (double)stats->rays / stats->seconds * 1e-6 : 0.0;
        stats->samples = c.total;
        stats->invalid = invalid;
        for (int k = 0; k < DIRT_PT_MAX_EVENTS; k++)
            stats->paths_at_event[k] = atomic_load(&c.events[k]);
        stats->threads = used;
    }
    pthread_mutex_destroy(&c.progress_lock);
    dirt_area_lights_free(&c.area);
    dirt_ref_accel_destroy(own);
    dirt_env_destroy(c.own_env);
    return img;

error:
    if (lock_ready)
        pthread_mutex_destroy(&c.progress_lock);
    if (img != o.into)
        dirt_image_destroy(img);
    dirt_area_lights_free(&c.area);
    dirt_ref_accel_destroy(own);
    dirt_env_destroy(c.own_env);
    return NULL;
}

dirt_image *dirt_ref_render(const dirt_scene *scene, const dirt_frame *frame,
                            const dirt_camera *camera, const dirt_ref_opts *opts,
                            dirt_ref_stats *stats)
{
    if (!scene) {
        DIRT_ERROR("reference render: scene is NULL");
        return NULL;
    }
    dirt_ref_materials m = {0};
    m.materials = dirt_scene_materials(scene);
    m.num_materials = dirt_scene_num_materials(scene);
    m.textures = dirt_scene_textures(scene);
    m.num_textures = dirt_scene_num_textures(scene);
    m.specular = NULL;
    return dirt_ref_render_materials(&m, frame, camera, opts, stats);
}
