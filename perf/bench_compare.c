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
 * are approximate). Times: CPU wall clock around glFinish per pass
 * (cpu_timing), the meaningful figure on llvmpipe. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dirt/ads.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "dirt/mmrt.h"
#include "dirt/pathtrace.h"
#include "dirt/ref.h"
#include "dirt/scene.h"

typedef struct config {
    int width, height, buckets, bounces, repeat;
    enum dirt_view_mode views[3];
    int num_views;
} config;

static const char *view_name(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? "single" : m == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
}

static double sum_ms(const double *gpu, const double *cpu, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        double t = cpu[i] >= 0 ? cpu[i] : gpu[i];
        if (t > 0)
            s += t;
    }
    return s;
}

/* One row per technique for one scene and view mode. */
static bool bench_views(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *f,
                        const dirt_camera *cam, const config *c, enum dirt_view_mode vm,
                        const char *scene_name, const dirt_image *ref, dirt_pt *pt)
{
    dirt_view_opts vo = {.mode = vm, .width = c->width, .height = c->height, .tile_size = 1};
    dirt_pt_opts po = {.spp = 1, .bounces = c->bounces, .seed = 7,
                       .background = {1, 1, 1}};
    bool ok = false;
    dirt_ads *ads = NULL;
    dirt_mmrt *m = NULL;
    dirt_image *img = dirt_image_create(c->width, c->height);
    (void)scene;
    if (!img)
        goto done;

    /* DIRT */
    dirt_ads_opts ao = {.views = vo, .buckets = c->buckets};
    ads = dirt_ads_create(gpu, &ao);
    if (!ads || !dirt_ads_build(ads, f, cam))
        goto done;
    double build = 0;
    for (int r = 0; r < c->repeat; r++) {
        if (!dirt_ads_build(ads, f, cam))
            goto done;
        const dirt_ads_stats *as = dirt_ads_get_stats(ads);
        build += sum_ms(as->ms, as->ms, DIRT_ADS_NUM_PASSES) / c->repeat;
    }
    dirt_pt_stats st;
    if (!dirt_pt_render(pt, dirt_ads_tracer(ads, NULL), f, cam, &po, img, &st))
        goto done;
    const dirt_ads_stats *as = dirt_ads_get_stats(ads);
    printf("| %s | %s | DIRT | n_p %llu, nodes %llu | %.2f | %.1f | %.1f | %llu | %.3f | %.3g |\n",
           scene_name, view_name(vm), (unsigned long long)as->samples,
           (unsigned long long)as->nodes, as->bytes_total_used / 1048576.0, build, st.trace_ms,
           (unsigned long long)st.rays, st.mrays_per_s, dirt_image_rel_mse(img, ref));
    fflush(stdout);
    dirt_ads_destroy(ads);
    ads = NULL;

    /* MMRT */
    dirt_mmrt_opts mo = {.views = vo, .buckets = c->buckets};
    m = dirt_mmrt_create(gpu, &mo);
    if (!m || !dirt_mmrt_build(m, f, cam))
        goto done;
    build = 0;
    for (int r = 0; r < c->repeat; r++) {
        if (!dirt_mmrt_build(m, f, cam))
            goto done;
        const dirt_mmrt_stats *ms = dirt_mmrt_get_stats(m);
        build += sum_ms(ms->ms, ms->ms, DIRT_MMRT_NUM_PASSES) / c->repeat;
    }
    if (!dirt_pt_render(pt, dirt_mmrt_tracer(m, NULL), f, cam, &po, img, &st))
        goto done;
    const dirt_mmrt_stats *ms = dirt_mmrt_get_stats(m);
    printf("| %s | %s | MMRT | fragments %llu | %.2f | %.1f | %.1f | %llu | %.3f | %.3g |\n",
           scene_name, view_name(vm), (unsigned long long)ms->fragments,
           ms->bytes_total_used / 1048576.0, build, st.trace_ms, (unsigned long long)st.rays,
           st.mrays_per_s, dirt_image_rel_mse(img, ref));
    fflush(stdout);
    ok = true;
done:
    if (!ok)
        fprintf(stderr, "bench-compare: %s, %s views failed (see above)\n", scene_name,
                view_name(vm));
    dirt_ads_destroy(ads);
    dirt_mmrt_destroy(m);
    dirt_image_destroy(img);
    return ok;
}

static bool parse_views(const char *s, config *c)
{
    c->num_views = 0;
    while (*s && c->num_views < 3) {
        size_t n = strcspn(s, ",");
        if (n == 6 && !strncmp(s, "single", 6))
            c->views[c->num_views++] = DIRT_VIEWS_SINGLE;
        else if (n == 4 && !strncmp(s, "cube", 4))
            c->views[c->num_views++] = DIRT_VIEWS_CUBE;
        else if (n == 11 && !strncmp(s, "cube+camera", 11))
            c->views[c->num_views++] = DIRT_VIEWS_CUBE_CAMERA;
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
                .views = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE_CAMERA}, .num_views = 2};
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
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.cpu_timing = true});
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
        dirt_frame *f = scene ? dirt_scene_evaluate(scene, 0, NULL) : NULL;
        dirt_pt *pt = scene ? dirt_pt_create(gpu, scene) : NULL;
        dirt_image *ref = NULL;
        if (f && pt) {
            dirt_camera cam;
            if (f->num_cameras)
                cam = f->cameras[0];
            else
                dirt_camera_auto(f, &cam);
            dirt_ref_opts ro = {.width = c.width, .height = c.height, .spp = 1,
                                .bounces = c.bounces, .seed = 7, .background = {1, 1, 1}};
            ref = dirt_ref_render(scene, f, &cam, &ro, NULL);
            const char *name = def ? "default" : strrchr(scenes[s], '/') ? strrchr(scenes[s], '/') + 1
                                                                        : scenes[s];
            for (int v = 0; ref && v < c.num_views; v++)
                failures += !bench_views(gpu, scene, f, &cam, &c, c.views[v], name, ref, pt);
        }
        if (!f || !pt || !ref)
            failures++;
        dirt_image_destroy(ref);
        dirt_pt_destroy(pt);
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    dirt_gpu_destroy(gpu);
    return failures ? 1 : 0;
}
