/* bench-compare: MMRT vs DIRT at equal settings, in the layout of the DIRT
 * paper's Table 2, as a markdown table on stdout.
 *   bench-compare [SCENE ...] [-W 512 -H 256] [-B 4] [--bounces 4] [--repeat 2]
 *                 [--views single,cube+camera]
 * SCENE "default" is the embedded scene; a path that does not exist is
 * skipped with a note (so the FlightHelmet of ../shared can be listed
 * always). Default: default scene and
 * ../shared/scenes/gltf/FlightHelmet/FlightHelmet.gltf.
 * Both techniques: tile size 1 (MMRT is per pixel), the same B, the same
 * views (camera W x H, cube faces max(W, H) / 2). Per row: the structure's
 * records (DIRT: clipped samples n_p and id nodes; MMRT: fragments), the
 * bytes it uses (MB), the build (ms, mean of --repeat builds after a warm-up
 * one, passes summed), and the traversal of a fixed ray batch: one sample
 * per pixel of path tracing (camera, continuation and shadow rays of
 * --bounces events, the same seed, so the same camera rays) through the
 * same frame graph: trace ms (trace + shadow trace passes), rays traced,
 * Mrays/s, and relMSE of that 1-spp image against Embree's with the same
 * seed (DIRT agrees to float rounding; MMRT's paths diverge where its hits
 * are approximate). Everything runs through the render session
 * (dirt/session.h), so the figures are the ones dirt-render --stats reports;
 * times follow the engine's one timing rule (GPU timers on a GPU, the CPU
 * clock around glFinish on a software renderer such as llvmpipe). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dirt/gpu.h"
#include "dirt/log.h"
#include "dirt/session.h"

typedef struct config {
    int width, height, buckets, bounces, repeat;
    enum dirt_session_views views[3];
    int num_views;
} config;

static const char *view_name(enum dirt_session_views m)
{
    return m == DIRT_SESSION_VIEWS_SINGLE ? "single"
           : m == DIRT_SESSION_VIEWS_CUBE ? "cube"
                                          : "cube+camera";
}

static dirt_session_opts session_opts(const config *c, enum dirt_engine e,
                                      enum dirt_session_views vm)
{
    return (dirt_session_opts){.engine = e, .width = c->width, .height = c->height,
                               .views = vm, .tile_size = 1, .buckets = c->buckets,
                               .bounces = c->bounces, .seed = 7, .background = {1, 1, 1}};
}

/* One row: the build (mean of --repeat after a warm-up) and one sample per
 * pixel through technique `e`. */
static bool bench_row(dirt_gpu *gpu, const dirt_scene *scene, const config *c,
                      enum dirt_engine e, enum dirt_session_views vm, const char *scene_name,
                      const dirt_image *ref)
{
    dirt_session_opts o = session_opts(c, e, vm);
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    bool ok = s && dirt_session_build(s);
    double build = 0;
    for (int r = 0; ok && r < c->repeat; r++) {
        ok = dirt_session_set_time(s, 0, NULL) && dirt_session_build(s);
        build += ok ? dirt_session_get_stats(s)->build_ms / c->repeat : 0;
    }
    ok = ok && dirt_session_add_samples(s, 1, NULL, NULL);
    const dirt_image *img = ok ? dirt_session_image(s) : NULL;
    if (img) {
        const dirt_session_stats *st = dirt_session_get_stats(s);
        char records[96];
        if (st->has_ads)
            snprintf(records, sizeof(records), "n_p %llu, nodes %llu",
                     (unsigned long long)st->ads.samples, (unsigned long long)st->ads.nodes);
        else
            snprintf(records, sizeof(records), "fragments %llu",
                     (unsigned long long)st->mmrt.fragments);
        uint64_t bytes = st->has_ads ? st->ads.bytes_total_used : st->mmrt.bytes_total_used;
        printf("| %s | %s | %s | %s | %.2f | %.1f | %.1f | %llu | %.3f | %.3g |\n", scene_name,
               view_name(vm), e == DIRT_ENGINE_DIRT ? "DIRT" : "MMRT", records,
               bytes / 1048576.0, build, st->trace_ms, (unsigned long long)st->rays,
               st->mrays_per_s, dirt_image_rel_mse(img, ref));
        fflush(stdout);
    } else {
        fprintf(stderr, "bench-compare: %s, %s views, %s failed (see above)\n", scene_name,
                view_name(vm), dirt_engine_names[e]);
    }
    dirt_session_destroy(s);
    return img != NULL;
}

static bool parse_views(const char *s, config *c)
{
    c->num_views = 0;
    while (*s && c->num_views < 3) {
        size_t n = strcspn(s, ",");
        if (n == 6 && !strncmp(s, "single", 6))
            c->views[c->num_views++] = DIRT_SESSION_VIEWS_SINGLE;
        else if (n == 4 && !strncmp(s, "cube", 4))
            c->views[c->num_views++] = DIRT_SESSION_VIEWS_CUBE;
        else if (n == 11 && !strncmp(s, "cube+camera", 11))
            c->views[c->num_views++] = DIRT_SESSION_VIEWS_CUBE_CAMERA;
        else
            return false;
        s += n;
        if (*s == ',')
            s++;
    }
    return c->num_views > 0;
}

int main(int argc, char **argv)
{
    config c = {.width = 512, .height = 256, .buckets = 4, .bounces = 4, .repeat = 2,
                .views = {DIRT_SESSION_VIEWS_SINGLE, DIRT_SESSION_VIEWS_CUBE_CAMERA},
                .num_views = 2};
    const char *scenes[16];
    int num_scenes = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-W") && v) {
            c.width = atoi(v), i++;
        } else if (!strcmp(a, "-H") && v) {
            c.height = atoi(v), i++;
        } else if (!strcmp(a, "-B") && v) {
            c.buckets = atoi(v), i++;
        } else if (!strcmp(a, "--bounces") && v) {
            c.bounces = atoi(v), i++;
        } else if (!strcmp(a, "--repeat") && v) {
            c.repeat = atoi(v), i++;
        } else if (!strcmp(a, "--views") && v) {
            if (!parse_views(v, &c)) {
                fprintf(stderr, "bench-compare: --views expects single,cube,cube+camera\n");
                return 2;
            }
            i++;
        } else if (a[0] == '-') {
            fprintf(stderr, "usage: bench-compare [SCENE ...] [-W N -H N] [-B N] [--bounces K] "
                            "[--repeat N] [--views single,cube+camera]\n");
            return 2;
        } else if (num_scenes < 16) {
            scenes[num_scenes++] = a;
        }
    }
    if (c.width < 1 || c.height < 1 || c.buckets < 1 || c.bounces < 1 || c.repeat < 1) {
        fprintf(stderr, "bench-compare: sizes, B, bounces and repeat must be >= 1\n");
        return 2;
    }
    if (!num_scenes) {
        scenes[num_scenes++] = "default";
        scenes[num_scenes++] = "../shared/scenes/gltf/FlightHelmet/FlightHelmet.gltf";
    }
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){0});
    if (!gpu) {
        fprintf(stderr, "bench-compare: no OpenGL 4.5 context\n");
        return 3;
    }
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    printf("Device: %s\n\n%dx%d camera view, cube faces %d^2, tile size 1, B = %d, 1 spp path "
           "tracing with %d bounces (seed 7, background 1); build: mean of %d\n\n",
           desc, c.width, c.height, (c.width > c.height ? c.width : c.height) / 2, c.buckets,
           c.bounces, c.repeat);
    printf("| scene | views | technique | records | MB | build ms | trace ms | rays | Mrays/s | "
           "relMSE vs Embree |\n|---|---|---|---|---|---|---|---|---|---|\n");
    int failures = 0;
    for (int s = 0; s < num_scenes; s++) {
        bool def = !strcmp(scenes[s], "default");
        if (!def && access(scenes[s], R_OK) != 0) {
            printf("| %s | | | absent: skipped | | | | | | |\n", scenes[s]);
            continue;
        }
        dirt_scene *scene = def ? dirt_scene_create_default() : dirt_scene_load(scenes[s], NULL);
        /* The reference: Embree, the same seed, camera and settings. */
        dirt_session_opts ro = session_opts(&c, DIRT_ENGINE_EMBREE, DIRT_SESSION_VIEWS_DEFAULT);
        dirt_session *ref = scene ? dirt_session_create(gpu, scene, &ro) : NULL;
        const dirt_image *ref_img =
            ref && dirt_session_add_samples(ref, 1, NULL, NULL) ? dirt_session_image(ref) : NULL;
        const char *name = def ? "default" : strrchr(scenes[s], '/') ? strrchr(scenes[s], '/') + 1
                                                                    : scenes[s];
        for (int v = 0; ref_img && v < c.num_views; v++) {
            failures += !bench_row(gpu, scene, &c, DIRT_ENGINE_DIRT, c.views[v], name, ref_img);
            failures += !bench_row(gpu, scene, &c, DIRT_ENGINE_MMRT, c.views[v], name, ref_img);
        }
        if (!ref_img)
            failures++;
        dirt_session_destroy(ref);
        dirt_scene_destroy(scene);
    }
    dirt_gpu_destroy(gpu);
    return failures ? 1 : 0;
}
