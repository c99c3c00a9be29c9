/* Node depth ranges (dirt_ads_opts.node_depths; doc/dirt-build.md, "Node
 * depth ranges"; doc/dirt-trace.md):
 *  - lists: with the option, every node's range byte passes the CPU
 *    reference check (ads_check: its sub-slabs hold those of the pair's
 *    exact range in its bucket and lie within those of the widened range),
 *    with uniform and adaptive depth buckets, raster and compute builds; the
 *    two builds' lists are the same entry for entry, ranges included; the
 *    lists without their ranges are the lists built without the option,
 *    entry for entry; the ranges say something (fewer than all 16 sub-slabs
 *    per node on average). Default scene, Cornell box when the shared scenes
 *    are there, a soup of small triangles; views single and cube+camera,
 *    S = 1, 2.
 *  - hits: the trace with the option finds the same hits as without it, bit
 *    for bit (primitive, view, t, u, v; any-hit rays: the same occlusion),
 *    every ray type, plain, with adaptive buckets and with every other trace
 *    option on (large primitives' grid, sub-tile rectangles, bucket masks);
 *    it reads the same list nodes and makes no more triangle tests, and
 *    agrees with Embree as gpu/dirt_hits asks; the soup's rays make fewer.
 *  - the fallback: a build with more nodes than its limit (lowered here from
 *    DIRT_NODE_DEPTH_MAX_NODES) stores plain next words, says so in its
 *    stats, reads back without ranges and traces the same hits;
 *  - more than DIRT_NODE_DEPTH_MAX_BUCKETS buckets: creation fails. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "check.h"
#include "dirt/ads.h"
#include "dirt/ads_internal.h"
#include "dirt/scene.h"
#include "gpu.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

#define MIN_AGREEMENT 0.999

static uint32_t g_rng = 4242u; /* ads_rand's state: the soup, then the rays */

/* The lists of one build, each entry with its range byte in bits 24..31 of
 * the primitive (the tests' primitives are below 2^24), or without
 * (list_triples, which also checks the links; the caller reads a build's
 * lists without their bytes first, so the walk with them only stays in
 * bounds). */
static uint64_t *depth_triples(dirt_ads_data *d, bool with, size_t *n)
{
    if (!with || !d->node_depths)
        return list_triples(d, n);
    uint64_t *t = malloc(((size_t)d->num_nodes + 1) * sizeof(*t));
    CHECK(t != NULL);
    *n = 0;
    if (!t)
        return NULL;
    size_t k = 0;
    for (int b = 0; b < d->buckets; b++)
        for (int tile = 0; tile < d->num_tiles; tile++)
            for (uint32_t node = d->heads[(size_t)b * d->num_tiles + tile];
                 node != DIRT_LIST_END && node < d->num_nodes && k < d->num_nodes;
                 node = d->nodes[node][1])
                t[k++] = ((uint64_t)tile << 40) | ((uint64_t)b << 32) | d->nodes[node][0] |
                         (uint64_t)d->node_depths[node] << 24;
    qsort(t, k, sizeof(*t), cmp_u64);
    *n = k;
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
    for (int m = 0; m < 2; m++) {
        for (int S = 1; S <= 2; S++) {
            for (int ad = 0; ad < 2; ad++) {
                dirt_ads_data d[2][2]; /* [build][option] */
                bool have[2][2] = {{false}};
                for (int b = 0; b < 2; b++) {
                    for (int on = 0; on < 2; on++) {
                        dirt_ads_opts o = {
                            .views = {.mode = modes[m], .width = 64, .height = 48,
                                      .face_size = 32, .tile_size = S},
                            .buckets = 8, .force_emulation = true,
                            .build = b ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER,
                            .depth_buckets = ad ? DIRT_DEPTH_BUCKETS_ADAPTIVE
                                                : DIRT_DEPTH_BUCKETS_UNIFORM,
                            .node_depths = on};
                        if (on && !ad) {
                            char l[64];
                            snprintf(l, sizeof(l), "%s %s", label, b ? "compute" : "raster");
                            CHECK(build_and_check(gpu, l, f, cam, &o));
                        }
                        dirt_ads *ads = ads_build_read(gpu, &o, f, cam, &d[b][on]);
                        have[b][on] = ads != NULL;
                        if (ads && on) {
                            /* (with adaptive buckets ads_check's bucket check is a
                             * uniform one, gpu/ads_adaptive checks those lists; the
                             * ranges it checks in the structure's own buckets) */
                            ads_check_report r = {0};
                            CHECK(ads_check(dirt_ads_views(ads), f, &d[b][on], ADS_DEPTH_TOL,
                                            &r));
                            CHECK_MSG(r.bad_node_depths == 0 && r.missing == 0 &&
                                          r.beyond_tolerance == 0 && d[b][on].node_depths,
                                      "%s %s S=%d %s: %llu bad node depth ranges", label,
                                      mode_name(modes[m]), S, ad ? "adaptive" : "uniform",
                                      (unsigned long long)r.bad_node_depths);
                        }
                        dirt_ads_destroy(ads);
                    }
                }
                if (!have[0][0] || !have[0][1] || !have[1][0] || !have[1][1])
                    continue;
                size_t n[2][2], nr[2];
                uint64_t *pt[2][2], *rt[2];
                size_t slabs = 0, nodes = d[1][1].num_nodes;
                for (uint32_t k = 0; k < nodes; k++)
                    slabs += (size_t)((d[1][1].node_depths[k] >> 4) -
                                      (d[1][1].node_depths[k] & 15) + 1);
                for (int b = 0; b < 2; b++) {
                    for (int on = 0; on < 2; on++)
                        pt[b][on] = depth_triples(&d[b][on], false, &n[b][on]);
                    rt[b] = depth_triples(&d[b][1], true, &nr[b]);
                }
                bool same_off = same_triples(pt[0][0], n[0][0], pt[0][1], n[0][1]) &&
                                same_triples(pt[1][0], n[1][0], pt[1][1], n[1][1]);
                bool same_builds = same_triples(rt[0], nr[0], rt[1], nr[1]);
                fprintf(stderr, "%-10s %-11s S=%d %-8s: %zu nodes, %.2f of 16 sub-slabs per "
                        "node; lists as without: %s; raster = compute (ranges too): %s\n",
                        label, mode_name(modes[m]), S, ad ? "adaptive" : "uniform", nodes,
                        nodes ? (double)slabs / (double)nodes : 0.0, same_off ? "yes" : "NO",
                        same_builds ? "yes" : "NO");
                CHECK_MSG(same_off, "%s: the lists differ from those built without ranges",
                          label);
                CHECK_MSG(same_builds, "%s: raster and compute lists or ranges differ", label);
                CHECK(nodes > 0 && slabs < 16 * nodes);
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

/* The structure of variant k, node depth ranges on or off: 0 plain (raster
 * build), 1 adaptive depth buckets (compute), 2 every other trace option
 * on (grid, rectangles, masks), 3 the fallback: on, with a node limit below
 * the build's count (so plain next words). */
static dirt_ads *variant(dirt_gpu *gpu, int mode, int k, bool on, const dirt_frame *f,
                         const dirt_camera *cam)
{
    dirt_ads_opts o = {
        .views = {.mode = mode ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA, .width = 64,
                  .height = 48, .face_size = 32, .tile_size = 2},
        .buckets = 8, .force_emulation = true, .large_grid = k == 2, .sub_tiles = k == 2,
        .bucket_masks = k == 2,
        .depth_buckets = k == 1 ? DIRT_DEPTH_BUCKETS_ADAPTIVE : DIRT_DEPTH_BUCKETS_UNIFORM,
        .build = k == 1 ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER, .node_depths = on};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads != NULL);
    if (!ads)
        return NULL;
    if (k == 3 && on)
        ads->node_depth_max_nodes = 16;
    bool ok = dirt_ads_build(ads, f, cam);
    CHECK(ok);
    if (ok && on) {
        const dirt_ads_stats *st = dirt_ads_get_stats(ads);
        CHECK_MSG(st->node_depths == (k != 3), "variant %d: node depths stored %d", k,
                  st->node_depths);
        if (k == 3) {
            /* read back without ranges, the lists of a plain build */
            dirt_ads_data d;
            CHECK(st->nodes > 16);
            if (dirt_ads_read(ads, &d)) {
                CHECK(d.node_depths == NULL);
                ads_check_report r = {0};
                CHECK(ads_check(dirt_ads_views(ads), f, &d, ADS_DEPTH_TOL, &r));
                CHECK(r.missing == 0 && r.beyond_tolerance == 0 && r.bad_list_links == 0);
                dirt_ads_data_free(&d);
            }
        }
    }
    if (!ok) {
        dirt_ads_destroy(ads);
        return NULL;
    }
    return ads;
}

static void test_hits(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                      const dirt_camera *cam, const dirt_ray *const rays[DIRT_RAY_TYPES],
                      const size_t counts[DIRT_RAY_TYPES])
{
    static const char *const names[] = {"plain", "adaptive, compute", "all options",
                                        "fallback"};
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
        for (int k = 0; k < 4; k++) {
            dirt_ads *ads[2] = {variant(gpu, mode, k, false, f, cam),
                                variant(gpu, mode, k, true, f, cam)};
            if (!ads[0] || !ads[1] || !accel) {
                dirt_ads_destroy(ads[0]);
                dirt_ads_destroy(ads[1]);
                continue;
            }
            fprintf(stderr, "%-10s %-11s %s:", label, mode ? "single" : "cube+camera",
                    names[k]);
            for (int t = 0; t < DIRT_RAY_TYPES; t++) {
                size_t n = counts[t];
                bool vis = t == DIRT_RAY_VISIBILITY;
                dirt_trace_opts to = {.any_hit = vis, .from_surfaces = t != DIRT_RAY_PRIMARY};
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
                CHECK_MSG(differ == 0, "%s %s %s %s: %zu of %zu rays differ", label,
                          mode ? "single" : "cube+camera", names[k], dirt_ray_type_names[t],
                          differ, n);
                /* a skipped node is still read (any-hit rays stop at
                 * whichever hit comes first: not compared). The tests of
                 * one bucket depend on its list's order, which comes from
                 * the build's atomics: the fallback's are not compared. */
                if (!vis) {
                    CHECK_MSG(nodes[1] == nodes[0], "%s %s %s: list nodes %llu -> %llu", label,
                              names[k], dirt_ray_type_names[t], (unsigned long long)nodes[0],
                              (unsigned long long)nodes[1]);
                    CHECK(k == 3 || tests[1] <= tests[0]);
                }
                if (!mode)
                    CHECK_MSG(agreed >= MIN_AGREEMENT * (double)n, "%s %s: %zu of %zu agree "
                              "with Embree", label, dirt_ray_type_names[t], agreed, n);
                if (!vis && n > 0 && k != 3 && !strcmp(label, "soup"))
                    CHECK_MSG(tests[1] < tests[0], "%s %s %s: no test skipped", label,
                              names[k], dirt_ray_type_names[t]);
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
    g_rng = 1234u;
    ads_random_type_rays(f, &g_rng, 2000, 0.7f, &r);
    test_hits(gpu, "soup", f, cam, (const dirt_ray *const *)r.rays, r.counts);
    ads_type_rays_free(&r);
}

static void test_limit(dirt_gpu *gpu)
{
    dirt_ads_opts o = {.views = {.width = 32, .height = 24},
                       .buckets = DIRT_NODE_DEPTH_MAX_BUCKETS + 1, .force_emulation = true,
                       .node_depths = true};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK_MSG(ads == NULL, "%d buckets were taken with node depth ranges", o.buckets);
    dirt_ads_destroy(ads);
    o.buckets = DIRT_NODE_DEPTH_MAX_BUCKETS;
    ads = dirt_ads_create(gpu, &o);
    CHECK(ads != NULL);
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
