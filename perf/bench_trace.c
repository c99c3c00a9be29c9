/* bench-trace: Mrays/s per ray type (the DIRT paper's Table 1 layout) for
 * DIRT (GPU) and Embree (CPU) on the same rays, with their hit agreement.
 *   bench-trace [SCENE|default ...] [-W 1024 -H 512] [--views MODE] [-S 2]
 *               [-B 16] [--face N] [--large N] [--max-scene-memory MIB]
 * (--large: DIRT's large primitives, 0 = none; default 16; the build is
 * the raster one unless DIRT_BUILD=compute)
 * Rays: camera G-buffer at W x H (Embree primary hits), then one event of
 * each type from those points (ref/raytypes.h). DIRT times: the GPU's one
 * clock (dirt_gpu_clock): GPU timer queries, or CPU wall time around
 * glFinish on a software renderer. Embree:
 * wall time of a multithreaded batch. Agreement: the same primitive, or the
 * same t within 1e-4 (a shared edge or vertex: either triangle is right),
 * or both missing (visibility: the same verdict); "same primitive": the
 * same primitive or both missing. --max-scene-memory: the load budget in
 * MiB (dirt_load_opts.max_bytes; default 512). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "dirt/ads.h"
#include "dirt/clock.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

int main(int argc, char **argv)
{
    const char *scenes[16];
    int n = 0, W = 1024, H = 512, S = 2, B = 16, face = 0, large = DIRT_ADS_MAX_LARGE;
    dirt_load_opts load = {0};
    enum dirt_view_mode mode = DIRT_VIEWS_CUBE_CAMERA;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-S")) S = atoi(v), i++;
        else if (!strcmp(a, "-B")) B = atoi(v), i++;
        else if (!strcmp(a, "--face")) face = atoi(v), i++;
        else if (!strcmp(a, "--large")) large = atoi(v), i++;
        else if (!strcmp(a, "--max-scene-memory")) load.max_bytes = (size_t)atoll(v) << 20, i++;
        else if (!strcmp(a, "--views")) {
            if (!bench_views("bench-trace", v, &mode))
                return 2;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-trace [SCENE|default ...] [-W N -H N] [--views MODE] [-S N] "
                   "[-B N] [--face N] [--large N] [--max-scene-memory MIB]\n");
            return 0;
        } else if (n < 16) scenes[n++] = a;
    }
    if (!n)
        scenes[n++] = "default";
    dirt_log_set_level(DIRT_LOG_WARN);
    char desc[512];
    dirt_gpu *gpu = bench_gpu(desc, sizeof(desc));
    if (!gpu)
        return 3;
    printf("GPU: %s\n\n| scene | tris | rays/type | DIRT build ms | type | DIRT Mrays/s | "
           "Embree Mrays/s | agreement %% | same primitive %% |\n"
           "|---|---|---|---|---|---|---|---|---|\n", desc);
    for (int si = 0; si < n; si++) {
        dirt_scene *scene = bench_scene(scenes[si], &load);
        if (!scene)
            return 2;
        dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
        dirt_gbuffer g;
        if (!accel || !dirt_gbuffer_build(accel, scene, f, &cam, W, H, &g))
            return 1;
        dirt_ads_opts o = {.views = {.mode = mode, .width = W, .height = H, .face_size = face,
                                     .tile_size = S},
                           .buckets = B, .large = large > 0 ? large : -1};
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        if (!ads || !dirt_ads_build(ads, f, &cam) || !dirt_ads_build(ads, f, &cam))
            return 1;
        const dirt_ads_stats *as = dirt_ads_get_stats(ads);
        double build = 0;
        for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
            build += as->ms[p];
        size_t cap = (size_t)W * H;
        dirt_ray *rays = malloc(cap * sizeof(*rays));
        dirt_hit *hits = malloc(cap * sizeof(*hits));
        dirt_ref_hit *ref = malloc(cap * sizeof(*ref));
        unsigned char *occ = malloc(cap);
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
            size_t cnt = dirt_rays_generate(&g, &cam, t, 1, rays);
            bool vis = t == DIRT_RAY_VISIBILITY;
            dirt_trace_opts to = {.any_hit = vis};
            dirt_trace_stats ts;
            if (!dirt_ads_trace(ads, rays, cnt, hits, &to, &ts))
                return 1;
            double dms = ts.ms;
            double e0 = dirt_clock_ms();
            if (vis)
                dirt_ref_occluded(accel, (const dirt_ref_ray *)rays, occ, cnt, 0);
            else
                dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, cnt, 0);
            double ems = dirt_clock_ms() - e0;
            size_t same = 0, exact = 0;
            for (size_t i = 0; i < cnt; i++) {
                bool dh = hits[i].prim != DIRT_HIT_NONE;
                if (vis) {
                    same += dh == (occ[i] != 0);
                    exact += dh == (occ[i] != 0);
                } else {
                    bool eh = ref[i].prim != DIRT_REF_MISS;
                    same += (!dh && !eh) ||
                            (dh && eh && (hits[i].prim == ref[i].prim ||
                                          fabsf(hits[i].t - ref[i].t) <= 1e-4f * ref[i].t));
                    exact += (!dh && !eh) || (dh && eh && hits[i].prim == ref[i].prim);
                }
            }
            printf("| %s | %zu | %zu | %.1f | %s | %.3f | %.3f | %.3f%s | %.3f |\n", name,
                   f->num_triangles, cnt, build, dirt_ray_type_names[t], cnt / (dms * 1e3),
                   cnt / (ems * 1e3), 100.0 * same / (cnt ? cnt : 1),
                   ts.aborted ? " (aborted rays!)" : "", 100.0 * exact / (cnt ? cnt : 1));
            fflush(stdout);
        }
        printf("| %s: %d large primitives |\n", name, as->num_large);
        free(rays);
        free(hits);
        free(ref);
        free(occ);
        dirt_ads_destroy(ads);
        dirt_gbuffer_free(&g);
        dirt_ref_accel_destroy(accel);
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    printf("\nDIRT times: %s; Embree: wall time, all CPU threads.\n",
           dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU ? "CPU wall time around glFinish (cpu clock)"
                                                 : "GPU timer queries (gpu clock)");
    dirt_gpu_destroy(gpu);
    return 0;
}
