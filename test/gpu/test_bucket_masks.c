/* Bucket occupancy masks as an option (dirt_ads_opts.bucket_masks;
 * doc/dirt-build.md, "Bucket occupancy masks"; doc/dirt-trace.md):
 *  - hits: the trace of a structure built with the masks finds the same hits
 *    as the one built without, bit for bit (primitive, view, t, u, v;
 *    any-hit rays: the same occlusion), every ray type of the default scene's
 *    G-buffer and random rays in a soup of small triangles, views single and
 *    cube+camera, alone and with sub-tile rectangles, the large primitives'
 *    grid, adaptive depth buckets (compute build), and all three;
 *  - work (counting builds): never more tiles walked per ray with the masks,
 *    and fewer in all with uniform depth buckets (the rays meet empty
 *    tiles; adaptive buckets split each tile's covered depths evenly and
 *    leave none empty here). (Hi-Z steps, nodes and tests are not compared
 *    per ray: two builds' list order differs, and with it the rejection
 *    cache's and the march's work on some rays, masks or not.)
 *  - without the option there are no masks (dirt_ads_read gives none) and
 *    no bytes for them; with it and B <= 32, 4 B per tile; with it and
 *    B = 64 none, and the hits the same as without.
 * The masks' contents are checked against the lists by ads_check (the
 * gpu/ads_* tests), the skip's counts against a CPU count in
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

static uint32_t g_rng = 4242u; /* ads_rand's state: the soup, then the rays */

enum { V_PLAIN, V_SUB_TILES, V_GRID, V_ADAPTIVE, V_ALL, V_WIDE, VARIANTS };
static const char *const variant_names[] = {
    "plain", "sub-tiles", "large grid", "adaptive, compute", "sub-tiles+grid+adaptive",
    "B=64 (no masks)"};

static dirt_ads_opts variant_opts(int k, bool single, bool masks)
{
    bool adapt = k == V_ADAPTIVE || k == V_ALL;
    return (dirt_ads_opts){
        .views = {.mode = single ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA, .width = 64,
                  .height = 48, .face_size = 32, .tile_size = 2},
        .buckets = k == V_WIDE ? 64 : 8, .force_emulation = true,
        .large_grid = k == V_GRID || k == V_ALL, .sub_tiles = k == V_SUB_TILES || k == V_ALL,
        .depth_buckets = adapt ? DIRT_DEPTH_BUCKETS_ADAPTIVE : DIRT_DEPTH_BUCKETS_UNIFORM,
        .build = adapt ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER, .bucket_masks = masks};
}

/* Off against on for every variant and ray type. */
static void test_hits(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                      const dirt_camera *cam, const dirt_ray *const rays[DIRT_RAY_TYPES],
                      const size_t counts[DIRT_RAY_TYPES])
{
    size_t most = 0;
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        most = counts[t] > most ? counts[t] : most;
    dirt_hit *h[2] = {malloc((most + 1) * sizeof(dirt_hit)), malloc((most + 1) * sizeof(dirt_hit))};
    dirt_trace_work *w[2] = {malloc((most + 1) * sizeof(dirt_trace_work)),
                             malloc((most + 1) * sizeof(dirt_trace_work))};
    for (int mode = 0; mode < 2; mode++) {
        for (int k = 0; k < VARIANTS; k++) {
            dirt_ads *ads[2];
            for (int on = 0; on < 2; on++) {
                dirt_ads_opts o = variant_opts(k, mode == 1, on == 1);
                ads[on] = dirt_ads_create(gpu, &o);
                CHECK(ads[on] && dirt_ads_build(ads[on], f, cam));
                if (!ads[on])
                    continue;
                /* masks and their bytes only with the option and B <= 32 */
                bool want = on && o.buckets <= DIRT_BUCKET_MASK_MAX_BUCKETS;
                const dirt_ads_stats *st = dirt_ads_get_stats(ads[on]);
                dirt_ads_data d;
                CHECK(dirt_ads_read(ads[on], &d));
                CHECK_MSG((d.masks != NULL) == want, "%s %s masks %s: masks %s", label,
                          variant_names[k], on ? "on" : "off", d.masks ? "present" : "missing");
                CHECK(st->bytes_bucket_masks ==
                      (want ? (uint64_t)dirt_ads_views(ads[on])->num_tiles * 4 : 0));
                dirt_ads_data_free(&d);
            }
            if (!ads[0] || !ads[1]) {
                dirt_ads_destroy(ads[0]);
                dirt_ads_destroy(ads[1]);
                continue;
            }
            fprintf(stderr, "%-8s %-11s %-24s:", label, mode ? "single" : "cube+camera",
                    variant_names[k]);
            uint64_t all_tiles[2] = {0, 0};
            for (int t = 0; t < DIRT_RAY_TYPES; t++) {
                size_t n = counts[t];
                bool vis = t == DIRT_RAY_VISIBILITY;
                dirt_trace_opts to = {.any_hit = vis};
                dirt_trace_stats ts[2];
                for (int on = 0; on < 2; on++) {
                    CHECK(dirt_ads_trace_work(ads[on], rays[t], n, h[on], &to, &ts[on], w[on]));
                    CHECK(ts[on].aborted == 0);
                }
                size_t differ = 0, more_tiles = 0;
                uint64_t tiles[2] = {0, 0};
                for (size_t i = 0; i < n; i++) {
                    bool same = ads_same_hit_bits(&h[0][i], &h[1][i], vis);
                    differ += !same;
                    if (!same && differ <= 3)
                        fprintf(stderr, "\n  ray %zu: off prim %u t %.9g, on prim %u t %.9g", i,
                                h[0][i].prim, h[0][i].t, h[1][i].prim, h[1][i].t);
                    for (int on = 0; on < 2; on++)
                        tiles[on] += w[on][i].tiles;
                    more_tiles += w[1][i].tiles > w[0][i].tiles;
                }
                all_tiles[0] += tiles[0];
                all_tiles[1] += tiles[1];
                fprintf(stderr, " | %s %zu differ, tiles %.3f -> %.3f", dirt_ray_type_names[t],
                        differ, n ? (double)tiles[0] / (double)n : 0.0,
                        n ? (double)tiles[1] / (double)n : 0.0);
                CHECK_MSG(differ == 0, "%s %s %s %s: %zu of %zu rays differ", label,
                          mode ? "single" : "cube+camera", variant_names[k],
                          dirt_ray_type_names[t], differ, n);
                CHECK_MSG(more_tiles == 0, "%s %s %s: %zu rays walk more tiles with the masks",
                          label, variant_names[k], dirt_ray_type_names[t], more_tiles);
                if (k == V_WIDE)
                    CHECK(tiles[0] == tiles[1]);
            }
            fprintf(stderr, "\n");
            /* (adaptive buckets split a tile's covered depths evenly: here no
             * bucket a ray's span meets is empty, and nothing is skipped) */
            if (k == V_PLAIN || k == V_SUB_TILES || k == V_GRID)
                CHECK_MSG(all_tiles[1] < all_tiles[0], "%s %s: no tile skipped (%llu tiles)",
                          label, variant_names[k], (unsigned long long)all_tiles[0]);
            dirt_ads_destroy(ads[0]);
            dirt_ads_destroy(ads[1]);
        }
    }
    free(h[0]);
    free(h[1]);
    free(w[0]);
    free(w[1]);
}

static void scene_hits(dirt_gpu *gpu, dirt_scene *scene)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    ads_type_rays r;
    if (ads_gbuffer_rays(scene, f, &cam, 48, 36, 5, &r))
        test_hits(gpu, "default", f, &cam, (const dirt_ray *const *)r.rays, r.counts);
    ads_type_rays_free(&r);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

/* Random rays from inside the soup's box, every type the same rays
 * (visibility: a short tmax). */
static void soup_hits(dirt_gpu *gpu)
{
    dirt_frame *f = ads_soup(3000, 0.06f, &g_rng);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    ads_type_rays r;
    ads_random_type_rays(f, &g_rng, 2000, 0.3f, &r);
    test_hits(gpu, "soup", f, &cam, (const dirt_ray *const *)r.rays, r.counts);
    ads_type_rays_free(&r);
    frame_free(f);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    scene_hits(gpu, dirt_scene_create_default());
    soup_hits(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
