/* Shared by the DIRT build tests: build, read back, check against the CPU
 * reference, print the counts compared. */
#ifndef DIRT_TEST_ADS_COMMON_H
#define DIRT_TEST_ADS_COMMON_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/layout.h"
#include "dirt/ads.h"
#include "dirt/ads_ref.h"
#include "dirt/scene.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

/* Relative tolerance of depth-bound and bucket-edge comparisons: float
 * rounding of clip-space coordinates (24-bit mantissa, a few operations). */
#define ADS_DEPTH_TOL 1e-5

/* qsort order of uint64_t. */
static inline int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Sorted (tile, bucket, primitive) triples of a read-back structure (with
 * sub-tile rectangles, the primitive word is prim | rect << 24, as the GPU
 * stores it, so the rectangles are compared too); NULL
 * (and a failed check) when a list is longer than the node count (a cycle)
 * or links outside the nodes. */
static inline uint64_t *list_triples(const dirt_ads_data *d, size_t *count)
{
    uint64_t *out = malloc(((size_t)d->num_nodes + 1) * sizeof(*out));
    size_t n = 0;
    bool bad = false;
    for (int b = 0; b < d->buckets && !bad; b++) {
        for (int t = 0; t < d->num_tiles && !bad; t++) {
            for (uint32_t node = d->heads[(size_t)b * d->num_tiles + t];
                 node != DIRT_LIST_END && !bad; node = d->nodes[node][1]) {
                bad = node >= d->num_nodes || n >= d->num_nodes;
                if (!bad)
                    out[n++] = ((uint64_t)t << 40) | ((uint64_t)b << 32) | d->nodes[node][0] |
                               (d->rects ? (uint64_t)d->rects[node] << DIRT_SUBTILE_SHIFT : 0);
            }
        }
    }
    CHECK_MSG(!bad, "a list links outside the %u nodes or loops", d->num_nodes);
    if (bad) {
        free(out);
        *count = 0;
        return NULL;
    }
    qsort(out, n, sizeof(*out), cmp_u64);
    *count = n;
    return out;
}

/* A structure of `o` built for f and cam and read back into d; NULL (a
 * failed check) when any step fails. */
static inline dirt_ads *ads_build_read(dirt_gpu *gpu, const dirt_ads_opts *o,
                                       const dirt_frame *f, const dirt_camera *cam,
                                       dirt_ads_data *d)
{
    dirt_ads *ads = dirt_ads_create(gpu, o);
    CHECK(ads != NULL);
    if (!ads)
        return NULL;
    bool ok = dirt_ads_build(ads, f, cam) && dirt_ads_read(ads, d);
    CHECK(ok);
    if (!ok) {
        dirt_ads_destroy(ads);
        return NULL;
    }
    return ads;
}

static const char *mode_name(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? "single" : m == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
}

/* A frame of n hand-made triangles (only positions matter to the build). */
static inline dirt_frame *frame_new(size_t n)
{
    dirt_frame *f = calloc(1, sizeof(*f));
    f->num_triangles = n;
    f->position = calloc(3 * n, sizeof(*f->position));
    f->normal = calloc(3 * n, sizeof(*f->normal));
    f->uv = calloc(3 * n, sizeof(*f->uv));
    f->material = calloc(n, sizeof(*f->material));
    f->instance = calloc(n, sizeof(*f->instance));
    return f;
}

static inline void frame_free(dirt_frame *f)
{
    free(f->position);
    free(f->normal);
    free(f->uv);
    free(f->material);
    free(f->instance);
    free(f);
}

static inline void frame_bounds(dirt_frame *f)
{
    for (int k = 0; k < 3; k++) {
        f->bounds_min[k] = INFINITY;
        f->bounds_max[k] = -INFINITY;
    }
    for (size_t i = 0; i < 3 * f->num_triangles; i++) {
        for (int k = 0; k < 3; k++) {
            f->bounds_min[k] = fminf(f->bounds_min[k], f->position[i][k]);
            f->bounds_max[k] = fmaxf(f->bounds_max[k], f->position[i][k]);
        }
    }
}

static inline void set_tri(dirt_frame *f, size_t t, const float a[3], const float b[3], const float c[3])
{
    memcpy(f->position[3 * t], a, 12);
    memcpy(f->position[3 * t + 1], b, 12);
    memcpy(f->position[3 * t + 2], c, 12);
}

/* The tests' random numbers: a linear congruential step of *state, then
 * its top 24 bits as a float in [0, 1). */
static inline float ads_rand(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (float)(*state >> 8) / 16777216.0f;
}

/* A soup of n random triangles, each within a cube of side `size` around a
 * random point of the unit box (many primitives per tile); bounds set. */
static inline dirt_frame *ads_soup(size_t n, float size, uint32_t *state)
{
    dirt_frame *f = frame_new(n);
    for (size_t t = 0; t < n; t++) {
        float c[3] = {ads_rand(state), ads_rand(state), ads_rand(state)}, p[3][3];
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                p[v][k] = c[k] + size * (ads_rand(state) - 0.5f);
        set_tri(f, t, p[0], p[1], p[2]);
    }
    frame_bounds(f);
    return f;
}

/* A random ray from a point inside f's bounds in a random direction
 * (unit), over (1e-4, infinity). */
static inline void ads_random_ray(const dirt_frame *f, uint32_t *state, dirt_ray *r)
{
    float d[3], l = 0;
    for (int k = 0; k < 3; k++) {
        r->org[k] = f->bounds_min[k] + ads_rand(state) * (f->bounds_max[k] - f->bounds_min[k]);
        d[k] = ads_rand(state) - 0.5f;
        l += d[k] * d[k];
    }
    for (int k = 0; k < 3; k++)
        r->dir[k] = d[k] / sqrtf(l);
    r->tmin = 1e-4f;
    r->tmax = INFINITY;
}

/* Rays of every type (enum dirt_ray_type order): rays[t], counts[t] of
 * them. Free with ads_type_rays_free (also after a failed fill). */
typedef struct ads_type_rays {
    dirt_ray *rays[DIRT_RAY_TYPES];
    size_t counts[DIRT_RAY_TYPES];
} ads_type_rays;

static inline void ads_type_rays_free(ads_type_rays *r)
{
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        free(r->rays[t]);
    memset(r, 0, sizeof(*r));
}

/* The rays of every type from the camera G-buffer of `scene` (w x h pixels,
 * random numbers from `seed`; dirt_rays_generate). False (a failed check)
 * when Embree or the G-buffer fails: no rays then. */
static inline bool ads_gbuffer_rays(dirt_scene *scene, const dirt_frame *f,
                                    const dirt_camera *cam, int w, int h, uint32_t seed,
                                    ads_type_rays *out)
{
    memset(out, 0, sizeof(*out));
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    bool ok = accel && dirt_gbuffer_build(accel, scene, f, cam, w, h, &g);
    CHECK(ok);
    for (int t = 0; ok && t < DIRT_RAY_TYPES; t++) {
        out->rays[t] = malloc((size_t)w * (size_t)h * sizeof(dirt_ray));
        CHECK(out->rays[t] != NULL);
        out->counts[t] = out->rays[t] ? dirt_rays_generate(&g, cam, (enum dirt_ray_type)t,
                                                           seed, out->rays[t])
                                      : 0;
    }
    if (ok)
        dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    return ok;
}

/* n random rays from inside f's bounds (ads_random_ray), the same for every
 * type, the visibility rays' tmax set to vis_tmax. */
static inline void ads_random_type_rays(const dirt_frame *f, uint32_t *state, size_t n,
                                        float vis_tmax, ads_type_rays *out)
{
    memset(out, 0, sizeof(*out));
    for (int t = 0; t < DIRT_RAY_TYPES; t++) {
        out->rays[t] = malloc(n * sizeof(dirt_ray));
        CHECK(out->rays[t] != NULL);
        out->counts[t] = out->rays[t] ? n : 0;
    }
    for (size_t i = 0; i < n; i++) {
        dirt_ray r;
        ads_random_ray(f, state, &r);
        for (int t = 0; t < DIRT_RAY_TYPES; t++)
            if (out->rays[t])
                out->rays[t][i] = r;
        if (out->rays[DIRT_RAY_VISIBILITY])
            out->rays[DIRT_RAY_VISIBILITY][i].tmax = vis_tmax;
    }
}

/* Two traces' hits of one ray the same: primitive, view, t, u and v bit for
 * bit; any-hit (visibility) rays: the same occlusion. */
static inline bool ads_same_hit_bits(const dirt_hit *a, const dirt_hit *b, bool visibility)
{
    if (visibility)
        return (a->prim == DIRT_HIT_NONE) == (b->prim == DIRT_HIT_NONE);
    return a->prim == b->prim && a->view == b->view && !memcmp(&a->t, &b->t, 4) &&
           !memcmp(&a->u, &b->u, 4) && !memcmp(&a->v, &b->v, 4);
}

/* A DIRT hit agrees with Embree's as gpu/dirt_hits asks: both miss, or
 * both hit the same primitive or at the same t within ADS_AGREE_T_TOL
 * (shared edges); any-hit rays: the same occlusion. */
#define ADS_AGREE_T_TOL 1e-4
static inline bool ads_agree_embree(const dirt_hit *d, const dirt_ref_hit *e, bool visibility)
{
    bool dh = d->prim != DIRT_HIT_NONE, eh = e->prim != DIRT_REF_MISS;
    if (visibility || !dh || !eh)
        return dh == eh;
    return d->prim == e->prim || fabs(d->t - e->t) <= ADS_AGREE_T_TOL * fmax(e->t, 1e-3);
}

/* Builds with `opts` and checks; returns false on any discrepancy. */
static inline bool build_and_check(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                            const dirt_camera *cam, const dirt_ads_opts *opts)
{
    dirt_ads *ads = dirt_ads_create(gpu, opts);
    CHECK(ads != NULL);
    if (!ads)
        return false;
    bool ok = dirt_ads_build(ads, f, cam);
    CHECK(ok);
    dirt_ads_data data;
    ads_check_report r = {0};
    if (ok && (ok = dirt_ads_read(ads, &data))) {
        const dirt_view_set *set = dirt_ads_views(ads);
        CHECK(ads_check(set, f, &data, ADS_DEPTH_TOL, &r));
        uint64_t pyr = ads_check_pyramid(set, &data);
        const dirt_ads_stats *st = dirt_ads_get_stats(ads);
        fprintf(stderr,
                "%-14s %-11s S=%d B=%-2d: %6llu tiles, %7llu required pairs, %7llu on GPU, "
                "%7llu allowed | missing %llu, beyond tol %llu, dup %llu, buckets %llu, "
                "bounds %llu, links %llu, masks %llu, rects %llu, node depths %llu, pyramid "
                "%llu | n_p %llu c "
                "%.2f runs "
                "%d/%d\n",
                label, mode_name(opts->views.mode), set->tile_size, opts->buckets,
                (unsigned long long)r.tiles, (unsigned long long)r.required_pairs,
                (unsigned long long)r.gpu_pairs, (unsigned long long)r.allowed_pairs,
                (unsigned long long)r.missing, (unsigned long long)r.beyond_tolerance,
                (unsigned long long)r.duplicates, (unsigned long long)r.bad_buckets,
                (unsigned long long)r.bad_bounds, (unsigned long long)r.bad_list_links,
                (unsigned long long)r.bad_masks, (unsigned long long)r.bad_rects,
                (unsigned long long)r.bad_node_depths, (unsigned long long)pyr, (unsigned long long)st->samples,
                st->buckets_per_sample, st->depth_runs, st->fill_runs);
        CHECK(r.missing == 0);
        CHECK(r.beyond_tolerance == 0);
        CHECK(r.duplicates == 0);
        CHECK(r.bad_buckets == 0);
        CHECK(r.bad_bounds == 0);
        CHECK(r.bad_list_links == 0);
        CHECK(r.bad_masks == 0);
        /* masks only with the option and B <= 32; none: no bytes for them */
        bool want_masks = opts->bucket_masks && opts->buckets <= DIRT_BUCKET_MASK_MAX_BUCKETS;
        CHECK(st->bytes_bucket_masks == (want_masks ? (uint64_t)set->num_tiles * 4 : 0));
        CHECK((data.masks != NULL) == want_masks);
        CHECK(r.bad_rects == 0);
        CHECK((data.rects != NULL) == opts->sub_tiles);
        CHECK(r.bad_node_depths == 0);
        CHECK((data.node_depths != NULL) == opts->node_depths);
        CHECK(st->node_depths == opts->node_depths);
        CHECK(pyr == 0);
        CHECK(st->samples == r.gpu_pairs);
        /* A first build runs each pass once (the bound pass sized the
         * candidates, the count pass the node pool). */
        CHECK_MSG(st->depth_runs == 1 && st->fill_runs == 1 && st->bound_pass,
                  "first build: %d depth, %d fill passes, bound pass %d", st->depth_runs,
                  st->fill_runs, st->bound_pass);
        CHECK(r.required_pairs > 0);
        ok = r.missing == 0 && r.beyond_tolerance == 0 && r.duplicates == 0 &&
             r.bad_buckets == 0 && r.bad_bounds == 0 && r.bad_list_links == 0 &&
             r.bad_masks == 0 &&
             (data.masks != NULL) == want_masks &&
             r.bad_rects == 0 && (data.rects != NULL) == opts->sub_tiles &&
             r.bad_node_depths == 0 && (data.node_depths != NULL) == opts->node_depths &&
             pyr == 0;
        dirt_ads_data_free(&data);
    }
    dirt_ads_destroy(ads);
    return ok;
}

#endif
