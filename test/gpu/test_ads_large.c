/* DIRT's large primitives (doc/dirt-trace.md, "Large primitives"):
 *  - selection: dirt_ads_select_large equals a brute-force choice (every
 *    triangle of area >= DIRT_ADS_LARGE_AREA x diagonal^2, sorted by area
 *    descending then id, the first `max`, ids ascending) on the default
 *    scene, the Cornell box and a frame of 24 equal large triangles (the tie
 *    rule), for max = 16, 5, 1 and 0;
 *  - the build keeps them out of the lists: its stats name the selection for
 *    opts.large = 0 (16), 3 and -1 (none), no list node holds one, and the
 *    lists pass the CPU reference check (ads_check, which leaves them out);
 *  - the trace finds the same hits with and without them: every ray type
 *    (camera G-buffer rays) on the default scene and the Cornell box, views
 *    single and cube+camera, S = 1 and 2, raster and compute build: the same
 *    primitive, t, u and v bits for every ray (a large primitive's hit counts
 *    only where the ray is inside a view, as a listed one's); and the same
 *    with the large primitives' grid (opts.large_grid: the trace tests one
 *    only in cells of the grid whose depth range for it the ray's span
 *    meets, so a range or a cell march that misses a hit shows here:
 *    testing only the span's entry depth made 200-687 rays of a type
 *    differ); the grid's bytes only with it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "check.h"
#include "dirt/ads.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "dirt/scene.h"
#include "gpu.h"

typedef struct ranked {
    double area;
    uint32_t id;
} ranked;

static int by_area(const void *a, const void *b)
{
    const ranked *x = a, *y = b;
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    return x->id < y->id ? -1 : x->id > y->id;
}

static int by_id(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* The brute-force selection. */
static int expected_large(const dirt_frame *f, int max, uint32_t *ids)
{
    double d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += ((double)f->bounds_max[k] - f->bounds_min[k]) *
              ((double)f->bounds_max[k] - f->bounds_min[k]);
    ranked *r = malloc((f->num_triangles + 1) * sizeof(*r));
    size_t n = 0;
    for (size_t p = 0; p < f->num_triangles; p++) {
        const float *a = f->position[3 * p], *b = f->position[3 * p + 1], *c = f->position[3 * p + 2];
        double u[3], v[3];
        for (int k = 0; k < 3; k++) {
            u[k] = (double)b[k] - a[k];
            v[k] = (double)c[k] - a[k];
        }
        double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
               z = u[0] * v[1] - u[1] * v[0];
        double area = 0.5 * sqrt(x * x + y * y + z * z);
        if (area >= DIRT_ADS_LARGE_AREA * d2 && area > 0)
            r[n++] = (ranked){area, (uint32_t)p};
    }
    qsort(r, n, sizeof(*r), by_area);
    int m = (int)n < max ? (int)n : max;
    for (int i = 0; i < m; i++)
        ids[i] = r[i].id;
    qsort(ids, (size_t)m, sizeof(*ids), by_id);
    free(r);
    return m;
}

static void check_selection(const char *label, const dirt_frame *f, int expect_min)
{
    static const int maxes[] = {16, 5, 1, 0};
    for (int i = 0; i < 4; i++) {
        uint32_t got[DIRT_ADS_MAX_LARGE], want[DIRT_ADS_MAX_LARGE];
        int ng = dirt_ads_select_large(f, maxes[i], 0, got);
        int nw = expected_large(f, maxes[i], want);
        CHECK_MSG(ng == nw && !memcmp(got, want, (size_t)nw * sizeof(*got)),
                  "%s max %d: %d selected, %d expected", label, maxes[i], ng, nw);
        if (i == 0) {
            fprintf(stderr, "%-10s %zu triangles: %d large\n", label, f->num_triangles, ng);
            CHECK(ng >= expect_min);
        }
    }
}

/* 24 equal right triangles of area 2 in a 4 x 4 x 0.1 box (so each is
 * large) and two small ones: the 16 lowest ids win the ties. */
static void test_ties(void)
{
    dirt_frame *f = frame_new(26);
    for (int t = 0; t < 24; t++) {
        float z = 0.1f * (float)t / 23.0f;
        set_tri(f, (size_t)t, (float[3]){0, 0, z}, (float[3]){2, 0, z}, (float[3]){0, 2, z});
    }
    set_tri(f, 24, (float[3]){4, 4, 0}, (float[3]){3.9f, 4, 0}, (float[3]){4, 3.9f, 0});
    set_tri(f, 25, (float[3]){-0.0f, 0, 0}, (float[3]){0.1f, 0, 0}, (float[3]){4, 4, 0.05f});
    frame_bounds(f);
    uint32_t ids[DIRT_ADS_MAX_LARGE];
    int n = dirt_ads_select_large(f, 16, 0, ids);
    CHECK(n == 16);
    for (int i = 0; i < n; i++)
        CHECK_MSG(ids[i] == (uint32_t)i, "tie %d: id %u", i, ids[i]);
    check_selection("ties", f, 16);
    frame_free(f);
}

/* Builds with opts.large = 0, 3, -1: the stats name the selection, no node
 * holds a large primitive, the lists pass the reference check. */
static void test_build(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                       const dirt_camera *cam)
{
    static const int larges[] = {0, 3, -1};
    for (int i = 0; i < 3; i++) {
        dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64, .height = 48,
                                     .face_size = 32, .tile_size = 2},
                           .buckets = 8, .force_emulation = true, .large = larges[i],
                           .bucket_masks = true, .build = i == 1 ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER};
        CHECK(build_and_check(gpu, label, f, cam, &o));
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        CHECK(ads && dirt_ads_build(ads, f, cam));
        if (!ads)
            continue;
        const dirt_ads_stats *st = dirt_ads_get_stats(ads);
        uint32_t want[DIRT_ADS_MAX_LARGE];
        int nw = larges[i] < 0 ? 0 : expected_large(f, larges[i] ? larges[i] : 16, want);
        CHECK_MSG(st->num_large == nw && !memcmp(st->large, want, (size_t)nw * sizeof(*want)),
                  "%s large %d: %d in the stats, %d expected", label, larges[i], st->num_large, nw);
        dirt_ads_data d;
        if (dirt_ads_read(ads, &d)) {
            size_t held = 0;
            for (uint32_t k = 0; k < d.num_nodes; k++)
                for (int j = 0; j < d.num_large; j++)
                    held += d.nodes[k][0] == d.large[j];
            CHECK_MSG(held == 0, "%s: %zu list nodes hold a large primitive", label, held);
            CHECK(d.num_large == st->num_large);
            dirt_ads_data_free(&d);
        }
        dirt_ads_destroy(ads);
    }
}

/* Hits with and without the large primitives: bit for bit the same. */
static void test_hits(dirt_gpu *gpu, const char *label, dirt_scene *scene, const dirt_frame *f,
                      const dirt_camera *cam)
{
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    CHECK(accel && dirt_gbuffer_build(accel, scene, f, cam, 48, 36, &g));
    if (!accel)
        return;
    size_t n = 48 * 36; /* camera rays: one per pixel */
    dirt_ray *rays = malloc(n * sizeof(*rays));
    dirt_hit *hits[3] = {malloc(n * sizeof(dirt_hit)), malloc(n * sizeof(dirt_hit)),
                         malloc(n * sizeof(dirt_hit))};
    for (int mode = 0; mode < 2; mode++) {
        for (int s = 1; s <= 2; s++) {
            /* [0] none large, [1] large tested by every ray, [2] through their grid */
            dirt_ads *ads[3];
            int num_large = 0;
            for (int k = 0; k < 3; k++) {
                dirt_ads_opts o = {
                    .views = {.mode = mode ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA,
                              .width = 64, .height = 48, .face_size = 32, .tile_size = s},
                    .buckets = 8, .force_emulation = true, .large = k ? 0 : -1,
                    .large_grid = k == 2,
                    .build = s == 1 ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER};
                ads[k] = dirt_ads_create(gpu, &o);
                CHECK(ads[k] && dirt_ads_build(ads[k], f, cam));
                if (ads[k] && k)
                    num_large = dirt_ads_get_stats(ads[k])->num_large;
                if (ads[k]) /* the grid's bytes: with it only */
                    CHECK((dirt_ads_get_stats(ads[k])->bytes_large_grid > 0) == (k == 2));
            }
            CHECK(num_large > 0 && dirt_ads_get_stats(ads[2])->num_large == num_large);
            fprintf(stderr, "%-10s %-11s S=%d, %d large:", label, mode ? "single" : "cube+camera",
                    s, num_large);
            for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES && ads[0] && ads[1] && ads[2]; t++) {
                size_t cnt = dirt_rays_generate(&g, cam, t, 5, rays);
                dirt_trace_opts to = {.any_hit = t == DIRT_RAY_VISIBILITY};
                dirt_trace_stats ts[3];
                for (int k = 0; k < 3; k++) {
                    CHECK(dirt_ads_trace(ads[k], rays, cnt, hits[k], &to, &ts[k]));
                    CHECK(ts[k].aborted == 0);
                }
                for (int k = 1; k < 3; k++) {
                    size_t differ = 0, hit = 0, on_large = 0;
                    for (size_t i = 0; i < cnt; i++) {
                        const dirt_hit *a = &hits[0][i], *b = &hits[k][i];
                        bool same = a->prim == b->prim;
                        /* any-hit rays: the same answer (occluded or not) */
                        if (t != DIRT_RAY_VISIBILITY && a->prim != DIRT_HIT_NONE)
                            same = same && !memcmp(&a->t, &b->t, sizeof(float)) &&
                                   !memcmp(&a->u, &b->u, sizeof(float)) &&
                                   !memcmp(&a->v, &b->v, sizeof(float));
                        if (t == DIRT_RAY_VISIBILITY)
                            same = (a->prim == DIRT_HIT_NONE) == (b->prim == DIRT_HIT_NONE);
                        differ += !same;
                        hit += b->prim != DIRT_HIT_NONE;
                        const dirt_ads_stats *st = dirt_ads_get_stats(ads[1]);
                        for (int j = 0; j < st->num_large; j++)
                            on_large += b->prim == st->large[j];
                        if (!same && getenv("DIRT_TEST_VERBOSE"))
                            fprintf(stderr, "\n  ray %zu: listed prim %u t %.9g, large prim "
                                    "%u t %.9g", i, a->prim, a->t, b->prim, b->t);
                    }
                    fprintf(stderr, " | %s%s %zu/%zu hit (%zu on large), %zu differ",
                            dirt_ray_type_names[t], k == 2 ? " (grid)" : "", hit, cnt, on_large,
                            differ);
                    CHECK_MSG(differ == 0, "%s %s S=%d %s%s: %zu of %zu rays differ", label,
                              mode ? "single" : "cube+camera", s, dirt_ray_type_names[t],
                              k == 2 ? " through the large primitives' grid" : "", differ, cnt);
                    if (t != DIRT_RAY_VISIBILITY)
                        CHECK(on_large > 0);
                }
            }
            fprintf(stderr, "\n");
            for (int k = 0; k < 3; k++)
                dirt_ads_destroy(ads[k]);
        }
    }
    free(rays);
    for (int k = 0; k < 3; k++)
        free(hits[k]);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
}

static void run(dirt_gpu *gpu, const char *label, dirt_scene *scene, int expect_min)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    check_selection(label, f, expect_min);
    test_build(gpu, label, f, &cam);
    test_hits(gpu, label, scene, f, &cam);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    test_ties();
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    /* (the walls of both rooms are large) */
    run(gpu, "default", dirt_scene_create_default(), 8);
    const char *shared = test_shared_dir();
    if (shared) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox.glb", shared);
        run(gpu, "CornellBox", dirt_scene_load(path, NULL), 8);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
