/* Sub-tile rectangles (dirt_ads_opts.sub_tiles; doc/dirt-build.md, "Sub-tile
 * rectangles"; doc/dirt-trace.md):
 *  - lists: with the option, the raster and the compute build pass the CPU
 *    reference check (ads_check), rectangles included: every (primitive,
 *    tile) pair's rectangle holds the cells of the exact clip's NDC box
 *    (eps 0) and lies within those of the widened clip's box (2 eps) widened
 *    by DIRT_SUBTILE_MARGIN cells, the same in all its buckets; the two
 *    builds' lists are the same entry for entry, rectangles included; and
 *    the lists without their rectangles are the lists built without the
 *    option, entry for entry (default scene, Cornell box when the shared
 *    scenes are there, a soup of small triangles; views single and
 *    cube+camera, S = 1, 2, 4; uniform and adaptive depth buckets);
 *  - hits: the trace with the option finds the same hits as without it,
 *    bit for bit (primitive, view, t, u, v; any-hit rays: the same
 *    occlusion), every ray type, with and without the large primitives'
 *    grid and adaptive depth buckets, and agrees with Embree as
 *    gpu/dirt_hits asks (99.9 % of the rays in cube+camera mode); the rays
 *    of the soup test fewer triangles with it (work counters);
 *  - the primitive limit: a frame of DIRT_SUBTILE_MAX_PRIMS triangles fails
 *    the build (logged) before anything is read from it.
 * The CPU count of the trace's work with the rectangle skip is in
 * gpu/trace_work. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "check.h"
#include "dirt/ads.h"
#include "dirt/scene.h"
#include "gpu.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

#define MIN_AGREEMENT 0.999

static uint32_t g_rng = 777u; /* ads_rand's state: the soup, then the rays */

/* The lists of one build without their rectangles. */
static uint64_t *plain_triples(dirt_ads_data *d, size_t *n)
{
    uint8_t *r = d->rects;
    d->rects = NULL;
    uint64_t *t = list_triples(d, n);
    d->rects = r;
    return t;
}

static bool same_triples(const uint64_t *a, size_t na, const uint64_t *b, size_t nb)
{
    return a && b && na == nb && !memcmp(a, b, na * sizeof(*a));
}

static void test_lists(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                       const dirt_camera *cam)
{
    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE_CAMERA};
    static const int sizes[] = {1, 2, 4};
    for (int m = 0; m < 2; m++) {
        for (int si = 0; si < 3; si++) {
            for (int ad = 0; ad < 2; ad++) {
                /* [build][option] */
                dirt_ads_data d[2][2];
                bool have[2][2] = {{false}};
                for (int b = 0; b < 2; b++) {
                    for (int on = 0; on < 2; on++) {
                        dirt_ads_opts o = {
                            .views = {.mode = modes[m], .width = 64, .height = 48,
                                      .face_size = 32, .tile_size = sizes[si]},
                            .buckets = 8, .force_emulation = true,
                            .build = b ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER,
                            .depth_buckets = ad ? DIRT_DEPTH_BUCKETS_ADAPTIVE
                                                : DIRT_DEPTH_BUCKETS_UNIFORM,
                            .sub_tiles = on, .bucket_masks = on};
                        if (on && !ad) {
                            char l[64];
                            snprintf(l, sizeof(l), "%s %s", label, b ? "compute" : "raster");
                            CHECK(build_and_check(gpu, l, f, cam, &o));
                        }
                        dirt_ads *ads = ads_build_read(gpu, &o, f, cam, &d[b][on]);
                        have[b][on] = ads != NULL;
                        if (ads && on && ad) {
                            /* (ads_check's buckets are uniform ones: gpu/ads_adaptive
                             * checks the adaptive lists, which are the same as
                             * without the rectangles, below) */
                            ads_check_report r = {0};
                            CHECK(ads_check(dirt_ads_views(ads), f, &d[b][on], ADS_DEPTH_TOL,
                                            &r));
                            CHECK_MSG(r.bad_rects == 0 && r.missing == 0 &&
                                          r.beyond_tolerance == 0,
                                      "%s adaptive: %llu bad rectangles", label,
                                      (unsigned long long)r.bad_rects);
                        }
                        dirt_ads_destroy(ads);
                    }
                }
                if (!have[0][0] || !have[0][1] || !have[1][0] || !have[1][1])
                    continue;
                size_t n[2][2], nr[2];
                uint64_t *pt[2][2], *rt[2];
                size_t cells = 0, nodes = d[0][1].num_nodes;
                for (uint32_t k = 0; k < d[0][1].num_nodes; k++) {
                    int c[4];
                    ads_ref_rect_cells(d[0][1].rects[k], c);
                    cells += (size_t)(c[1] - c[0] + 1) * (size_t)(c[3] - c[2] + 1);
                }
                for (int b = 0; b < 2; b++) {
                    for (int on = 0; on < 2; on++)
                        pt[b][on] = plain_triples(&d[b][on], &n[b][on]);
                    rt[b] = list_triples(&d[b][1], &nr[b]);
                }
                bool same_off = same_triples(pt[0][0], n[0][0], pt[0][1], n[0][1]) &&
                                same_triples(pt[1][0], n[1][0], pt[1][1], n[1][1]);
                bool same_builds = same_triples(rt[0], nr[0], rt[1], nr[1]);
                fprintf(stderr, "%-10s %-11s S=%d %s: %zu nodes, %.2f of 16 cells per node; "
                        "lists as without: %s; raster = compute (rectangles too): %s\n", label,
                        mode_name(modes[m]), sizes[si], ad ? "adaptive" : "uniform", nodes,
                        nodes ? (double)cells / (double)nodes : 0.0, same_off ? "yes" : "NO",
                        same_builds ? "yes" : "NO");
                CHECK_MSG(same_off, "%s: the lists differ from those built without rectangles",
                          label);
                CHECK_MSG(same_builds, "%s: raster and compute lists or rectangles differ",
                          label);
                /* the rectangles say something: fewer than all 16 cells */
                CHECK(nodes > 0 && cells < 16 * nodes);
                for (int b = 0; b < 2; b++) {
                    for (int on = 0; on < 2; on++) {
                        free(pt[b][on]);
                        dirt_ads_data_free(&d[b][on]);
                    }
                    free(rt[b]);
                }
            }
        }
    }
}

/* Option off against on, variant k: 0 plain, 1 large primitives' grid,
 * 2 adaptive depth buckets; views single and cube+camera. */
static void test_hits(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                      const dirt_camera *cam, const dirt_ray *const rays[DIRT_RAY_TYPES],
                      const size_t counts[DIRT_RAY_TYPES])
{
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    CHECK(accel != NULL);
    size_t most = 0;
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        most = counts[t] > most ? counts[t] : most;
    dirt_hit *h[2] = {malloc((most + 1) * sizeof(dirt_hit)), malloc((most + 1) * sizeof(dirt_hit))};
    dirt_ref_hit *ref = malloc((most + 1) * sizeof(*ref));
    dirt_trace_work *w[2] = {malloc((most + 1) * sizeof(dirt_trace_work)),
                             malloc((most + 1) * sizeof(dirt_trace_work))};
    for (int mode = 0; mode < 2; mode++) {
        for (int k = 0; k < 3; k++) {
            dirt_ads *ads[2];
            for (int on = 0; on < 2; on++) {
                dirt_ads_opts o = {
                    .views = {.mode = mode ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA,
                              .width = 64, .height = 48, .face_size = 32, .tile_size = 2},
                    .buckets = 8, .force_emulation = true, .large_grid = k == 1,
                    .depth_buckets = k == 2 ? DIRT_DEPTH_BUCKETS_ADAPTIVE
                                            : DIRT_DEPTH_BUCKETS_UNIFORM,
                    .build = k == 2 ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER, .sub_tiles = on, .bucket_masks = on};
                ads[on] = dirt_ads_create(gpu, &o);
                CHECK(ads[on] && dirt_ads_build(ads[on], f, cam));
            }
            if (!ads[0] || !ads[1] || !accel) {
                dirt_ads_destroy(ads[0]);
                dirt_ads_destroy(ads[1]);
                continue;
            }
            fprintf(stderr, "%-10s %-11s %s:", label, mode ? "single" : "cube+camera",
                    k == 1 ? "large grid" : k == 2 ? "adaptive, compute" : "plain");
            for (int t = 0; t < DIRT_RAY_TYPES; t++) {
                size_t n = counts[t];
                bool vis = t == DIRT_RAY_VISIBILITY;
                dirt_trace_opts to = {.any_hit = vis};
                dirt_trace_stats ts[2];
                for (int on = 0; on < 2; on++) {
                    CHECK(dirt_ads_trace_work(ads[on], rays[t], n, h[on], &to, &ts[on], w[on]));
                    CHECK(ts[on].aborted == 0);
                }
                dirt_ref_intersect(accel, (const dirt_ref_ray *)rays[t], ref, n, 0);
                size_t differ = 0, agreed = 0;
                uint64_t tests[2] = {0, 0}, nodes[2] = {0, 0};
                for (size_t i = 0; i < n; i++) {
                    bool same = ads_same_hit_bits(&h[0][i], &h[1][i], vis);
                    differ += !same;
                    agreed += ads_agree_embree(&h[1][i], &ref[i], vis);
                    for (int on = 0; on < 2; on++) {
                        tests[on] += w[on][i].triangle_tests;
                        nodes[on] += w[on][i].list_nodes;
                    }
                    if (!same && differ <= 3)
                        fprintf(stderr, "\n  ray %zu: off prim %u t %.9g, on prim %u t %.9g", i,
                                h[0][i].prim, h[0][i].t, h[1][i].prim, h[1][i].t);
                }
                fprintf(stderr, " | %s %zu differ, Embree %.4f, tests %.2f -> %.2f",
                        dirt_ray_type_names[t], differ, n ? (double)agreed / (double)n : 1.0,
                        n ? (double)tests[0] / (double)n : 0.0,
                        n ? (double)tests[1] / (double)n : 0.0);
                CHECK_MSG(differ == 0, "%s %s variant %d %s: %zu of %zu rays differ", label,
                          mode ? "single" : "cube+camera", k, dirt_ray_type_names[t], differ, n);
                /* the rectangles only skip tests; the masks (on with them) skip
                 * tiles: with adaptive buckets only those whose lists in the
                 * span are empty (the same lists read), with uniform ones also
                 * those whose ranges miss the span's depth slabs (fewer) */
                CHECK((k == 2 ? nodes[0] == nodes[1] : nodes[1] <= nodes[0]) || vis);
                CHECK(tests[1] <= tests[0] || vis);
                if (!mode)
                    CHECK_MSG(agreed >= MIN_AGREEMENT * (double)n, "%s %s: %zu of %zu agree "
                              "with Embree", label, dirt_ray_type_names[t], agreed, n);
                if (!vis && n > 0 && !strcmp(label, "soup"))
                    CHECK_MSG(tests[1] < tests[0], "%s %s: no test skipped", label,
                              dirt_ray_type_names[t]);
            }
            fprintf(stderr, "\n");
            dirt_ads_destroy(ads[0]);
            dirt_ads_destroy(ads[1]);
        }
    }
    free(h[0]);
    free(h[1]);
    free(w[0]);
    free(w[1]);
    free(ref);
    dirt_ref_accel_destroy(accel);
}

/* Camera G-buffer rays of every type. */
static void scene_hits(dirt_gpu *gpu, const char *label, dirt_scene *scene, const dirt_frame *f,
                       const dirt_camera *cam)
{
    ads_type_rays r;
    if (ads_gbuffer_rays(scene, f, cam, 48, 36, 5, &r))
        test_hits(gpu, label, f, cam, (const dirt_ray *const *)r.rays, r.counts);
    ads_type_rays_free(&r);
}

/* Random rays from inside the soup's box, every "type" the same rays
 * (visibility: tmax 0.7). */
static void soup_hits(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam)
{
    ads_type_rays r;
    g_rng = 99u;
    ads_random_type_rays(f, &g_rng, 2000, 0.7f, &r);
    test_hits(gpu, "soup", f, cam, (const dirt_ray *const *)r.rays, r.counts);
    ads_type_rays_free(&r);
}

/* Too many primitives for a 24-bit id: the build fails before reading the
 * frame (its arrays are NULL here). */
static void test_limit(dirt_gpu *gpu)
{
    dirt_frame f = {0};
    f.num_triangles = DIRT_SUBTILE_MAX_PRIMS;
    for (int k = 0; k < 3; k++) {
        f.bounds_min[k] = -1;
        f.bounds_max[k] = 1;
    }
    dirt_camera cam;
    dirt_camera_default(&f, &cam);
    dirt_ads_opts o = {.views = {.width = 32, .height = 24}, .buckets = 4,
                       .force_emulation = true, .sub_tiles = true};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads != NULL);
    if (ads)
        CHECK_MSG(!dirt_ads_build(ads, &f, &cam), "a frame of 2^24 triangles was built with "
                  "sub-tile rectangles");
    dirt_ads_destroy(ads);
}

static void run_scene(dirt_gpu *gpu, const char *label, dirt_scene *scene)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    test_lists(gpu, label, f, &cam);
    scene_hits(gpu, label, scene, f, &cam);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    test_limit(gpu);
    run_scene(gpu, "default", dirt_scene_create_default());
    const char *shared = test_shared_dir();
    if (shared) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox.glb", shared);
        run_scene(gpu, "CornellBox", dirt_scene_load(path, NULL));
    }
    dirt_frame *s = ads_soup(3000, 0.06f, &g_rng);
    dirt_camera cam;
    dirt_camera_default(s, &cam);
    test_lists(gpu, "soup", s, &cam);
    soup_hits(gpu, s, &cam);
    frame_free(s);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
