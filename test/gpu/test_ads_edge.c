/* DIRT build edge cases:
 *  - slivers, zero-area (collinear, repeated-point) and edge-on triangles,
 *    triangles lying on tile boundaries and crossing the near plane are all
 *    recorded wherever their exact clip is non-empty;
 *  - pools: a first build runs every pass once (from a node pool of 1 too)
 *    and gives exactly the lists of a run with ample capacity; a candidate
 *    buffer that is too small reruns the depth pass, same lists;
 *  - odd view sizes (97x61): the Hi-Z pyramid equals a CPU min/max pyramid. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "common/layout.h"
#include "dirt/log.h"
#include "dirt/scene.h"
#include "gpu.h"


static void test_slivers(dirt_gpu *gpu)
{
    enum { FIXED = 6, RANDOM = 400 };
    dirt_frame *f = frame_new(FIXED + RANDOM);
    /* Camera at z = 3 looking at the origin; the view plane z = 0 spans
     * about [-1.7, 1.7] vertically. */
    dirt_camera cam = {.type = DIRT_CAMERA_PERSPECTIVE, .yfov = 1.0471976f, .znear = 0.1f};
    dirt_camera_look_at(&cam, (const float[3]){0, 0, 3}, (const float[3]){0, 0, 0},
                        (const float[3]){0, 1, 0});
    /* zero area: collinear, across many tiles */
    set_tri(f, 0, (float[3]){-1, -0.5f, 0}, (float[3]){0, 0, 0}, (float[3]){1, 0.5f, 0});
    /* zero area: one point three times */
    set_tri(f, 1, (float[3]){0.3f, 0.2f, 0}, (float[3]){0.3f, 0.2f, 0}, (float[3]){0.3f, 0.2f, 0});
    /* sliver 1e-4 wide */
    set_tri(f, 2, (float[3]){-1, 0.1f, 0}, (float[3]){1, 0.1001f, 0}, (float[3]){1, 0.1f, 0});
    /* degenerate segment on the vertical centre line (a tile boundary) */
    set_tri(f, 3, (float[3]){0, -1, 0}, (float[3]){0, 1, 0}, (float[3]){0, 1, 0});
    /* edge-on: its plane y = 0 contains the eye */
    set_tri(f, 4, (float[3]){-0.5f, 0, 1}, (float[3]){0.5f, 0, 1}, (float[3]){0, 0, -1});
    /* crosses the near plane and passes behind the eye */
    set_tri(f, 5, (float[3]){0, 0.1f, 3.5f}, (float[3]){0.5f, 0.5f, 2.0f}, (float[3]){-0.5f, 0.2f, 2.5f});
    unsigned seed = 12345;
    for (size_t t = FIXED; t < FIXED + RANDOM; t++) {
        float c[3] = {ads_rand(&seed) * 3 - 1.5f, ads_rand(&seed) * 3 - 1.5f, ads_rand(&seed) * 2 - 1};
        float d[3] = {ads_rand(&seed) - 0.5f, ads_rand(&seed) - 0.5f, ads_rand(&seed) - 0.5f};
        float w = t % 2 ? 1e-5f : 0.0f; /* half slivers, half exactly degenerate */
        float e[3] = {c[0] + d[0], c[1] + d[1], c[2] + d[2]};
        float g[3] = {c[0] + d[0] * 0.5f + w, c[1] + d[1] * 0.5f - w, c[2] + d[2] * 0.5f};
        if (t % 5 == 0)
            memcpy(e, c, 12), memcpy(g, c, 12); /* a point */
        set_tri(f, t, c, e, g);
    }
    frame_bounds(f);
    static const int sizes[] = {1, 2, 4};
    for (int m = 0; m < 2; m++) {
        for (int s = 0; s < 3; s++) {
            dirt_ads_opts o = {
                .views = {.mode = m ? DIRT_VIEWS_CUBE_CAMERA : DIRT_VIEWS_SINGLE,
                          .width = 64, .height = 48, .face_size = 32, .tile_size = sizes[s]},
                .buckets = 8,
                .force_emulation = true,
                .large = -1, /* every triangle in the lists */
                .bucket_masks = true,
            };
            build_and_check(gpu, "slivers", f, &cam, &o);
            /* Every fixed degenerate triangle is in some list. */
            dirt_ads *ads = dirt_ads_create(gpu, &o);
            dirt_ads_data d;
            if (ads && dirt_ads_build(ads, f, &cam) && dirt_ads_read(ads, &d)) {
                bool seen[FIXED] = {false};
                for (uint32_t i = 0; i < d.num_nodes; i++) {
                    if (d.nodes[i][0] < FIXED)
                        seen[d.nodes[i][0]] = true;
                }
                for (int t = 0; t < FIXED; t++)
                    CHECK_MSG(seen[t], "degenerate triangle %d not recorded (S=%d)", t, sizes[s]);
                dirt_ads_data_free(&d);
            } else {
                CHECK(false);
            }
            dirt_ads_destroy(ads);
        }
    }
    frame_free(f);
}

/* Pool sizing. A first build runs every pass once (the candidate buffer
 * from the bound pass, the node pool from the count pass), from a node
 * capacity of 1 too, and gives exactly the lists of a build with ample
 * pools; a second build of the same frame needs no bound pass; a candidate
 * buffer of 1 (initial_candidates) reruns the depth pass once, same lists;
 * other primitives bring the bound pass back, still one depth pass. */
static void test_overflow(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_ads_opts o = {
        .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 48, .height = 32, .face_size = 24,
                  .tile_size = 2},
        .buckets = 8,
        .force_emulation = true,
    };
    enum { CASES = 3 };
    dirt_ads_data d[CASES];
    size_t n[CASES] = {0};
    uint64_t *tri[CASES] = {NULL};
    for (int i = 0; i < CASES; i++) {
        o.initial_nodes = i == 1 ? (size_t)1 << 20 : 1;
        o.initial_candidates = i == 2 ? 1 : i == 1 ? (size_t)1 << 20 : 0;
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        CHECK(ads && dirt_ads_build(ads, f, &f->cameras[0]) && dirt_ads_read(ads, &d[i]));
        if (!ads)
            continue;
        const dirt_ads_stats *st = dirt_ads_get_stats(ads);
        fprintf(stderr, "pools case %d: %llu nodes, %llu candidates, bound pass %d, depth runs "
                "%d, fill runs %d\n", i, (unsigned long long)st->nodes,
                (unsigned long long)st->samples, st->bound_pass, st->depth_runs, st->fill_runs);
        CHECK(st->fill_runs == 1);
        CHECK(st->bound_pass == (i == 0));
        CHECK(st->depth_runs == (i == 2 ? 2 : 1));
        /* (the compute build keeps its work records in the node pool) */
        CHECK(st->bytes_candidates_allocated >= st->bytes_candidates_used &&
              st->bytes_candidates_used == st->samples * DIRT_CANDIDATE_BYTES);
        CHECK(st->build == DIRT_BUILD_COMPUTE || st->work_records == 0);
        tri[i] = list_triples(&d[i], &n[i]);
        /* A second build of the same frame: every pass once, no bound pass. */
        CHECK(dirt_ads_build(ads, f, &f->cameras[0]));
        CHECK(st->fill_runs == 1 && st->depth_runs == 1 && !st->bound_pass);
        if (i == 0) {
            /* Other primitives: the bound pass again, still one depth pass. */
            dirt_frame *g = dirt_scene_evaluate(scene, 0, NULL);
            g->num_triangles -= 1;
            CHECK(dirt_ads_build(ads, g, &g->cameras[0]));
            CHECK(st->bound_pass && st->depth_runs == 1 && st->fill_runs == 1);
            g->num_triangles += 1;
            dirt_frame_destroy(g);
        }
        dirt_ads_destroy(ads);
    }
    for (int i = 1; i < CASES; i++) {
        CHECK(n[i] == n[0] && n[0] > 0);
        CHECK(n[i] == n[0] && tri[i] && tri[0] && memcmp(tri[i], tri[0], n[0] * sizeof(uint64_t)) == 0);
        /* Depth bounds are independent of the pools. */
        CHECK(d[i].pyramid_size == d[0].pyramid_size &&
              memcmp(d[i].depth, d[0].depth, (size_t)d[0].pyramid_size * 8) == 0);
    }
    for (int i = 0; i < CASES; i++) {
        free(tri[i]);
        dirt_ads_data_free(&d[i]);
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

/* Frame after frame (an animation, one structure): each build equals a
 * fresh structure's build of that frame, lists and bounds, also when the
 * candidates outgrow the buffer the first frame sized and the depth pass
 * reruns. */
static void test_animation(dirt_gpu *gpu)
{
    const char *shared = test_shared_dir();
    if (!shared) {
        fprintf(stderr, "../shared absent: animation part skipped\n");
        return;
    }
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/gltf/BoxAnimated/BoxAnimated.gltf", shared);
    dirt_scene *scene = dirt_scene_load(path, NULL);
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 96, .height = 72},
                       .buckets = 16, .force_emulation = true};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads != NULL);
    int reruns = 0;
    static const float times[] = {0.75f, 0.8f, 0.85f, 0.9f, 0.93f, 0.98f, 1.2f, 1.5f, 2.0f};
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
            const dirt_ads_stats *st = dirt_ads_get_stats(ads);
            reruns += st->depth_runs - 1;
            size_t n[2];
            uint64_t *tri[2] = {list_triples(&d[0], &n[0]), list_triples(&d[1], &n[1])};
            CHECK_MSG(n[0] == n[1] && memcmp(tri[0], tri[1], n[0] * sizeof(uint64_t)) == 0,
                      "t = %g: the lists differ from a fresh build's (%zu vs %zu nodes, %d "
                      "depth passes)", times[i], n[0], n[1], st->depth_runs);
            CHECK_MSG(memcmp(d[0].depth, d[1].depth, (size_t)d[0].pyramid_size * 8) == 0,
                      "t = %g: the depth bounds differ from a fresh build's", times[i]);
            for (int k = 0; k < 2; k++) {
                free(tri[k]);
                dirt_ads_data_free(&d[k]);
            }
        }
        dirt_ads_destroy(fresh);
        dirt_frame_destroy(f);
    }
    fprintf(stderr, "animation: %d depth pass reruns over %zu frames\n", reruns,
            sizeof(times) / sizeof(times[0]));
    dirt_ads_destroy(ads);
    dirt_scene_destroy(scene);
}

static void test_odd_sizes(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    static const int sizes[] = {1, 2, 8};
    for (int s = 0; s < 3; s++) {
        dirt_ads_opts o = {
            .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 97, .height = 61,
                      .face_size = 37, .tile_size = sizes[s]},
            .buckets = 4,
            .force_emulation = true,
        };
        build_and_check(gpu, "odd 97x61", f, &f->cameras[0], &o);
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

static int limit_errors;

static void on_log(void *user, enum dirt_log_level level, const char *file, int line,
                   const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level == DIRT_LOG_ERROR && strstr(msg, "more than this GPU holds in one array") &&
        strstr(msg, "larger tiles (-S)"))
        limit_errors++;
}

/* A structure beyond what the GPU holds in one array (here 275 GB of list
 * heads: past DIRT_SPLIT_MAX_PARTS texel buffers) fails up front with one
 * clear error naming the knobs, and a normal one still builds afterwards. */
static void test_limits(dirt_gpu *gpu)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_ads_opts huge = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = 8192, .height = 8192,
                                    .tile_size = 1},
                          .buckets = 1024, .force_emulation = true};
    dirt_ads *ads = dirt_ads_create(gpu, &huge);
    CHECK(ads != NULL);
    dirt_log_set_callback(on_log, NULL);
    CHECK(!dirt_ads_build(ads, f, &f->cameras[0]));
    dirt_log_set_callback(NULL, NULL);
    CHECK(limit_errors == 1);
    dirt_ads_destroy(ads);
    dirt_ads_opts ok = {.views = {.width = 32, .height = 24}, .buckets = 4,
                        .force_emulation = true};
    ads = dirt_ads_create(gpu, &ok);
    CHECK(ads && dirt_ads_build(ads, f, &f->cameras[0]));
    dirt_ads_destroy(ads);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    test_slivers(gpu);
    test_overflow(gpu);
    test_animation(gpu);
    test_odd_sizes(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    test_limits(gpu);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
