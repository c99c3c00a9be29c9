/* The compute build (dirt_ads_opts.build = DIRT_BUILD_COMPUTE) against the
 * raster build and the CPU reference: on the default scene and one shared
 * scene (CesiumMilkTruck; in CI a missing ../shared fails), for S in
 * {1, 2, 4, 8} and views single, cube and cube+camera,
 *  - the same primitives in every (tile, bucket) list as the raster build
 *    (as sets: list order comes from atomics), entry for entry, no
 *    duplicates;
 *  - the same depth bounds and Hi-Z pyramid, bit for bit, and the same n_p
 *    and node count;
 *  - the CPU reference check (ads_check: nothing missing, nothing beyond
 *    the allowed set, buckets exactly those the range overlaps, bounds in
 *    the sandwich; the pyramid equal to the CPU min/max pyramid);
 * also with the reference clip (DIRT_CLIP_SH) in both builds; pools: a
 * first build runs every pass once, a second needs no bound pass, a
 * candidate buffer of 1 reruns the depth pass (same lists); one structure
 * frame after frame of an animation (reruns when a frame outgrows the
 * buffers) equals a fresh raster build per frame; and the trace
 * through either structure gives the same hits, bit for bit, and a render
 * session (dirt_session_opts.build) the same image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "common/layout.h"
#include "dirt/scene.h"
#include "dirt/session.h"
#include "gpu.h"

/* Compares the compute build with the raster build and the CPU reference;
 * returns true when everything agrees. */
static bool compare(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                    const dirt_camera *cam, dirt_ads_opts o)
{
    dirt_ads_data d[2];
    dirt_ads *ads[2];
    o.build = DIRT_BUILD_RASTER;
    ads[0] = ads_build_read(gpu, &o, f, cam, &d[0]);
    o.build = DIRT_BUILD_COMPUTE;
    ads[1] = ads_build_read(gpu, &o, f, cam, &d[1]);
    bool ok = ads[0] && ads[1];
    if (!ok)
        goto done;
    const dirt_ads_stats *rs = dirt_ads_get_stats(ads[0]), *cs = dirt_ads_get_stats(ads[1]);
    CHECK(rs->build == DIRT_BUILD_RASTER && cs->build == DIRT_BUILD_COMPUTE);
    size_t n[2] = {0, 0};
    uint64_t *tri[2] = {list_triples(&d[0], &n[0]), list_triples(&d[1], &n[1])};
    size_t differ = 0, dup = 0;
    if (tri[0] && tri[1]) {
        /* sorted-set difference, both ways */
        size_t i = 0, j = 0;
        while (i < n[0] || j < n[1]) {
            if (j == n[1] || (i < n[0] && tri[0][i] < tri[1][j]))
                differ++, i++;
            else if (i == n[0] || tri[1][j] < tri[0][i])
                differ++, j++;
            else
                i++, j++;
        }
        for (size_t k = 1; k < n[1]; k++)
            dup += tri[1][k] == tri[1][k - 1];
    } else {
        ok = false;
    }
    bool same_depth = d[0].pyramid_size == d[1].pyramid_size &&
                      memcmp(d[0].depth, d[1].depth, (size_t)d[0].pyramid_size * 8) == 0;
    const dirt_view_set *set = dirt_ads_views(ads[1]);
    ads_check_report r = {0};
    CHECK(ads_check(set, f, &d[1], ADS_DEPTH_TOL, &r));
    uint64_t pyr = ads_check_pyramid(set, &d[1]);
    fprintf(stderr,
            "%-16s %-11s S=%d B=%-2d%s: %6d tiles | raster %7zu entries, compute %7zu, "
            "differ %zu, dup %zu, depth %s | n_p %llu / %llu, records %llu | reference: "
            "missing %llu, beyond %llu, buckets %llu, bounds %llu, masks %llu, pyramid %llu | "
            "runs %d/%d%s\n",
            label, mode_name(o.views.mode), set->tile_size, o.buckets,
            o.reference_clip ? " SH" : "", set->num_tiles, n[0], n[1], differ, dup,
            same_depth ? "equal" : "DIFFER", (unsigned long long)rs->samples,
            (unsigned long long)cs->samples, (unsigned long long)cs->work_records,
            (unsigned long long)r.missing, (unsigned long long)r.beyond_tolerance,
            (unsigned long long)r.bad_buckets, (unsigned long long)r.bad_bounds,
            (unsigned long long)r.bad_masks, (unsigned long long)pyr, cs->depth_runs, cs->fill_runs,
            cs->bound_pass ? ", bound" : "");
    CHECK(n[0] > 0);
    CHECK_MSG(differ == 0 && n[0] == n[1], "%s S=%d %s: %zu list entries differ",
              label, set->tile_size, mode_name(o.views.mode), differ);
    CHECK(dup == 0);
    CHECK_MSG(same_depth, "%s S=%d %s: depth bounds / pyramid differ", label, set->tile_size,
              mode_name(o.views.mode));
    CHECK(rs->samples == cs->samples && rs->nodes == cs->nodes);
    CHECK(r.missing == 0 && r.beyond_tolerance == 0 && r.duplicates == 0 &&
          r.bad_buckets == 0 && r.bad_bounds == 0 && r.bad_list_links == 0 &&
          r.bad_masks == 0 && pyr == 0);
    /* with the option the raster build's masks are the compute build's (the
     * same lists; ads_check held them to the lists); without, neither build
     * has masks or bytes for them */
    if (o.bucket_masks)
        CHECK(d[1].masks != NULL && d[0].masks != NULL &&
              memcmp(d[0].masks, d[1].masks, (size_t)set->num_tiles * 4) == 0);
    else
        CHECK(!d[0].masks && !d[1].masks && !rs->bytes_bucket_masks && !cs->bytes_bucket_masks);
    CHECK(r.required_pairs > 0 && cs->samples == r.gpu_pairs);
    /* First build: the bound (candidate tiles) pass, then every pass once. */
    CHECK(cs->bound_pass && cs->depth_runs == 1 && cs->fill_runs == 1);
    CHECK(cs->ms[DIRT_ADS_PASS_TILES] != 0 && rs->ms[DIRT_ADS_PASS_TILES] <= 0);
    ok = ok && differ == 0 && n[0] == n[1] && dup == 0 && same_depth && r.missing == 0 &&
         r.beyond_tolerance == 0 && r.bad_buckets == 0 && r.bad_bounds == 0 &&
         r.bad_masks == 0 && pyr == 0;
    free(tri[0]);
    free(tri[1]);
done:
    for (int i = 0; i < 2; i++) {
        if (ads[i])
            dirt_ads_data_free(&d[i]);
        dirt_ads_destroy(ads[i]);
    }
    return ok;
}

static void run_scene(dirt_gpu *gpu, const char *label, dirt_scene *scene, float t)
{
    CHECK_MSG(scene != NULL, "%s: scene did not load", label);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, t, NULL);
    CHECK(f != NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    static const int sizes[] = {1, 2, 4, 8};
    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE,
                                                DIRT_VIEWS_CUBE_CAMERA};
    for (int m = 0; m < 3; m++) {
        for (int s = 0; s < 4; s++) {
            dirt_ads_opts o = {
                .views = {.mode = modes[m], .width = 48, .height = 36, .face_size = 24,
                          .tile_size = sizes[s]},
                .buckets = 8,
                .force_emulation = true,
                .bucket_masks = s != 1, /* (S = 2: without) */
            };
            compare(gpu, label, f, &cam, o);
        }
    }
    /* the reference clip in both builds */
    dirt_ads_opts o = {
        .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 48, .height = 36, .face_size = 24,
                  .tile_size = 2},
        .buckets = 8, .force_emulation = true, .reference_clip = true,
    };
    compare(gpu, label, f, &cam, o);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

/* Pools of the compute build: a second build of the same frame runs no
 * bound pass and one depth pass; its work records use the node pool (the
 * pool's used bytes are the larger of the nodes' and the records', the
 * candidate buffer's the candidates' alone); a candidate buffer of 1 (no
 * bound pass) with a node pool of 1 (no room for a record), and ample
 * candidates with a node pool of 1, rerun the depth pass once; the lists
 * are the same in every case. */
static void test_pools(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_ads_opts o = {
        .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 48, .height = 32, .face_size = 24,
                  .tile_size = 2},
        .buckets = 8, .force_emulation = true, .build = DIRT_BUILD_COMPUTE,
    };
    enum { CASES = 3 };
    dirt_ads_data d[CASES];
    size_t n[CASES] = {0};
    uint64_t *tri[CASES] = {NULL};
    for (int i = 0; i < CASES; i++) {
        o.initial_candidates = i == 1 ? 1 : i == 2 ? (size_t)1 << 16 : 0;
        o.initial_nodes = 1;
        dirt_ads *ads = ads_build_read(gpu, &o, f, &f->cameras[0], &d[i]);
        if (!ads)
            continue;
        const dirt_ads_stats *st = dirt_ads_get_stats(ads);
        fprintf(stderr, "compute pools case %d: %llu candidates, %llu records, %llu nodes, "
                "bound %d, depth runs %d, fill runs %d\n", i, (unsigned long long)st->samples,
                (unsigned long long)st->work_records, (unsigned long long)st->nodes,
                st->bound_pass, st->depth_runs, st->fill_runs);
        CHECK(st->bound_pass == (i == 0) && st->depth_runs == (i == 0 ? 1 : 2) &&
              st->fill_runs == 1);
        uint64_t pool = st->work_records * DIRT_WORK_RECORD_NODES > st->nodes
                            ? st->work_records * DIRT_WORK_RECORD_NODES : st->nodes;
        CHECK(st->work_records > 0 && st->bytes_nodes_used == pool * DIRT_NODE_BYTES &&
              st->bytes_nodes_used <= st->bytes_nodes_allocated);
        CHECK(st->bytes_candidates_used == st->samples * DIRT_CANDIDATE_BYTES &&
              st->bytes_candidates_used <= st->bytes_candidates_allocated);
        tri[i] = list_triples(&d[i], &n[i]);
        CHECK(dirt_ads_build(ads, f, &f->cameras[0]));
        CHECK(!st->bound_pass && st->depth_runs == 1 && st->fill_runs == 1);
        dirt_ads_destroy(ads);
    }
    for (int i = 1; i < CASES; i++)
        CHECK(tri[0] && tri[i] && n[0] == n[i] && n[0] > 0 &&
              memcmp(tri[0], tri[i], n[0] * sizeof(uint64_t)) == 0 &&
              memcmp(d[0].depth, d[i].depth, (size_t)d[0].pyramid_size * 8) == 0);
    for (int i = 0; i < CASES; i++) {
        free(tri[i]);
        dirt_ads_data_free(&d[i]);
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

static void test_animation(dirt_gpu *gpu, const char *shared)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/gltf/BoxAnimated/BoxAnimated.gltf", shared);
    dirt_scene *scene = dirt_scene_load(path, NULL);
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 96, .height = 72},
                       .buckets = 16, .force_emulation = true, .build = DIRT_BUILD_COMPUTE};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads != NULL);
    int reruns = 0;
    static const float times[] = {0.75f, 0.8f, 0.85f, 0.9f, 0.93f, 0.98f, 1.2f, 1.5f, 2.0f};
    /* Sized first from afar (small footprints), so the first frame's
     * candidates and work records outgrow their buffer. */
    if (ads) {
        dirt_frame *f = dirt_scene_evaluate(scene, times[0], NULL);
        dirt_camera cam, far;
        dirt_camera_default(f, &cam);
        float c[3], eye[3];
        for (int k = 0; k < 3; k++) {
            c[k] = 0.5f * (f->bounds_min[k] + f->bounds_max[k]);
            eye[k] = c[k] + 8.0f * (cam.eye[k] - c[k]);
        }
        far = cam;
        dirt_camera_look_at(&far, eye, c, cam.up);
        CHECK(dirt_ads_build(ads, f, &far));
        dirt_frame_destroy(f);
    }
    o.build = DIRT_BUILD_RASTER;
    for (size_t i = 0; ads && i < sizeof(times) / sizeof(times[0]); i++) {
        dirt_frame *f = dirt_scene_evaluate(scene, times[i], NULL);
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        dirt_ads *fresh = dirt_ads_create(gpu, &o);
        dirt_ads_data d[2];
        bool ok = fresh && dirt_ads_build(ads, f, &cam) && dirt_ads_build(fresh, f, &cam) &&
                  dirt_ads_read(ads, &d[0]) && dirt_ads_read(fresh, &d[1]);
        CHECK(ok);
        if (ok) {
            reruns += dirt_ads_get_stats(ads)->depth_runs - 1;
            size_t n[2] = {0, 0};
            uint64_t *tri[2] = {list_triples(&d[0], &n[0]), list_triples(&d[1], &n[1])};
            CHECK_MSG(tri[0] && tri[1] && n[0] == n[1] && n[0] > 0 &&
                          memcmp(tri[0], tri[1], n[0] * sizeof(uint64_t)) == 0,
                      "t = %g: the compute lists differ from a fresh raster build's (%zu vs "
                      "%zu entries)", times[i], n[0], n[1]);
            CHECK_MSG(memcmp(d[0].depth, d[1].depth, (size_t)d[0].pyramid_size * 8) == 0,
                      "t = %g: the depth bounds differ", times[i]);
            for (int k = 0; k < 2; k++) {
                free(tri[k]);
                dirt_ads_data_free(&d[k]);
            }
        }
        dirt_ads_destroy(fresh);
        dirt_frame_destroy(f);
    }
    fprintf(stderr, "compute animation: %d depth pass reruns over %zu frames\n", reruns,
            sizeof(times) / sizeof(times[0]));
    CHECK(reruns > 0); /* the growth path ran */
    dirt_ads_destroy(ads);
    dirt_scene_destroy(scene);
}

/* The trace through either structure: the same hits, bit for bit (the
 * trace breaks ties by primitive id, so list order does not matter). Rays
 * from the camera through a grid of its view and from the scene's centre
 * in a spread of directions (those leave through the cube faces). */
static void test_trace(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    enum { GX = 48, GY = 36, NR = 2 * GX * GY };
    dirt_ray *rays = calloc(NR, sizeof(*rays));
    dirt_hit *hits[2] = {calloc(NR, sizeof(dirt_hit)), calloc(NR, sizeof(dirt_hit))};
    float centre[3];
    for (int k = 0; k < 3; k++)
        centre[k] = 0.5f * (f->bounds_min[k] + f->bounds_max[k]);
    float th = tanf(0.5f * cam.yfov), tw = th * (float)GX / (float)GY;
    for (int y = 0; y < GY; y++) {
        for (int x = 0; x < GX; x++) {
            float u = (2.0f * (x + 0.5f) / GX - 1.0f) * tw, v = (1.0f - 2.0f * (y + 0.5f) / GY) * th;
            dirt_ray *r = &rays[y * GX + x];
            for (int k = 0; k < 3; k++) {
                r->org[k] = cam.eye[k];
                r->dir[k] = cam.forward[k] + u * cam.right[k] + v * cam.up[k];
            }
            r->tmax = 1e30f;
            /* from the centre: a direction on the sphere */
            dirt_ray *s = &rays[GX * GY + y * GX + x];
            float phi = 6.2831853f * (x + 0.5f) / GX, ct = 1.0f - 2.0f * (y + 0.5f) / GY;
            float st = sqrtf(1.0f - ct * ct);
            memcpy(s->org, centre, sizeof(centre));
            s->dir[0] = st * cosf(phi), s->dir[1] = st * sinf(phi), s->dir[2] = ct;
            s->tmin = 1e-4f;
            s->tmax = 1e30f;
        }
    }
    for (int i = 0; i < 2; i++) {
        dirt_ads_opts o = {
            .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 96, .height = 72, .tile_size = 2},
            .buckets = 8, .build = i ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER,
        };
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        dirt_trace_stats ts = {0};
        CHECK(ads && dirt_ads_build(ads, f, &cam) &&
              dirt_ads_trace(ads, rays, NR, hits[i], NULL, &ts));
        CHECK(ts.aborted == 0);
        dirt_ads_destroy(ads);
    }
    size_t found = 0, differ = 0;
    for (size_t i = 0; i < NR; i++) {
        found += hits[0][i].prim != DIRT_HIT_NONE;
        differ += hits[0][i].prim != hits[1][i].prim || hits[0][i].view != hits[1][i].view ||
                  memcmp(&hits[0][i].u, &hits[1][i].u, 3 * sizeof(float)) != 0;
    }
    fprintf(stderr, "trace: %d rays, %zu hits, %zu differ between the builds\n", NR, found,
            differ);
    CHECK(found > NR / 4);
    CHECK(differ == 0);
    free(rays);
    free(hits[0]);
    free(hits[1]);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

/* A session switched from the raster to the compute build remakes the
 * structure and renders the same image, bit for bit; the automatic build
 * (the default) is dirt_session_auto_build's: compute on llvmpipe. */
static void test_session(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    enum { W = 80, H = 60 };
    dirt_session_opts o = {.width = W, .height = H, .bounces = 2};
    dirt_session *a = dirt_session_create(gpu, scene, &o);
    CHECK(a && dirt_session_add_samples(a, 1, NULL, NULL));
    CHECK(a && dirt_session_get_stats(a)->ads.build == dirt_session_auto_build(gpu));
    CHECK(dirt_session_auto_build(gpu) ==
          dirt_build_from_env(dirt_gpu_get_caps(gpu)->software ? DIRT_BUILD_COMPUTE
                                                               : DIRT_BUILD_RASTER));
    dirt_session_destroy(a);
    o.build = DIRT_SESSION_BUILD_RASTER;
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    float *img[2] = {NULL, NULL};
    for (int i = 0; s && i < 2; i++) {
        if (i) {
            o.build = DIRT_SESSION_BUILD_COMPUTE;
            bool restarted = false;
            CHECK(dirt_session_set_opts(s, &o, &restarted) && restarted);
        }
        CHECK(dirt_session_add_samples(s, 2, NULL, NULL));
        const dirt_session_stats *st = dirt_session_get_stats(s);
        CHECK(st->has_ads && st->aborted == 0 &&
              st->ads.build == (i ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER));
        const dirt_image *im = dirt_session_image(s);
        CHECK(im && im->width == W && im->height == H);
        if (im) {
            img[i] = malloc(sizeof(float) * 4 * W * H);
            memcpy(img[i], im->rgba, sizeof(float) * 4 * W * H);
        }
    }
    CHECK_MSG(img[0] && img[1] && memcmp(img[0], img[1], sizeof(float) * 4 * W * H) == 0,
              "session: the compute build's image differs from the raster build's");
    free(img[0]);
    free(img[1]);
    dirt_session_destroy(s);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    run_scene(gpu, "default", dirt_scene_create_default(), 0.0f);
    const char *shared = test_shared_dir();
    if (shared) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf",
                 shared);
        run_scene(gpu, "CesiumMilkTruck", dirt_scene_load(path, NULL), 0.5f);
        test_animation(gpu, shared);
    } else {
        fprintf(stderr, "../shared absent: default scene only\n");
    }
    test_pools(gpu);
    test_trace(gpu);
    test_session(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
