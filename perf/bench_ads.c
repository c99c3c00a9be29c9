/* bench-ads: DIRT build stage per pass (ms) and memory (MB) over a grid of
 * tile sizes and bucket counts, as a markdown table on stdout.
 *   bench-ads [SCENE ...] [-W 1024 -H 512] [--views single|cube|cube+camera]
 *             [-S 1,2,4] [-B 8,16,32] [--repeat N] [--min] [--reference-clip]
 * SCENE "default" is the embedded scene. Times: the GPU's one clock
 * (dirt_gpu_clock): GPU timer queries where the driver times rasterization,
 * else CPU wall time around glFinish (the only meaningful figure on
 * llvmpipe). Each configuration is built once first (its total is "first
 * ms"; "runs" counts its depth, fill and bound passes), then N times; the
 * mean of those N is reported (--min: the one build of least total time).
 * --reference-clip: the plain Sutherland-Hodgman clip of every candidate
 * (dirt_ads_opts.reference_clip), to see what the fast range saves. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "dirt/ads.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "dirt/scene.h"

static double total_ms(const dirt_ads_stats *st)
{
    double t = 0;
    for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
        t += st->ms[p] > 0 ? st->ms[p] : 0;
    return t;
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    int nscenes = 0, W = 1024, H = 512, repeat = 3;
    int S[8] = {1, 2, 4}, nS = 3, B[8] = {8, 16, 32}, nB = 3;
    bool use_min = false, reference = false;
    enum dirt_view_mode mode = DIRT_VIEWS_SINGLE;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-S")) nS = bench_parse_list(v, S, 8), i++;
        else if (!strcmp(a, "-B")) nB = bench_parse_list(v, B, 8), i++;
        else if (!strcmp(a, "--repeat")) repeat = atoi(v), i++;
        else if (!strcmp(a, "--min")) use_min = true;
        else if (!strcmp(a, "--reference-clip")) reference = true;
        else if (!strcmp(a, "--views")) {
            if (!bench_views("bench-ads", v, &mode))
                return 2;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-ads [SCENE|default ...] [-W N -H N] [--views MODE] "
                   "[-S 1,2,4] [-B 8,16,32] [--repeat N] [--min] [--reference-clip]\n");
            return 0;
        } else if (nscenes < 16) scenes[nscenes++] = a;
    }
    if (W <= 0 || H <= 0 || repeat <= 0 || nS <= 0 || nB <= 0) {
        fprintf(stderr, "bench-ads: bad arguments (see --help)\n");
        return 2;
    }
    if (!nscenes)
        scenes[nscenes++] = "default";
    dirt_log_set_level(DIRT_LOG_WARN);
    char desc[512];
    dirt_gpu *gpu = bench_gpu(desc, sizeof(desc));
    if (!gpu)
        return 3;
    printf("GPU: %s\n\n", desc);
    printf("| scene | tris | views | S | B | n_p | c |");
    for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
        printf(" %s ms |", dirt_ads_pass_names[p]);
    printf(" total ms | first ms | runs | MB used | MB alloc | Table 3 MB |\n|");
    for (int p = 0; p < DIRT_ADS_NUM_PASSES + 13; p++)
        printf("---|");
    printf("\n");
    for (int si = 0; si < nscenes; si++) {
        dirt_scene *scene = bench_scene(scenes[si], NULL);
        if (!scene)
            return 2;
        dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        for (int s = 0; s < nS; s++) {
            for (int b = 0; b < nB; b++) {
                dirt_ads_opts o = {.views = {.mode = mode, .width = W, .height = H,
                                             .tile_size = S[s]},
                                   .buckets = B[b], .reference_clip = reference};
                dirt_ads *ads = dirt_ads_create(gpu, &o);
                if (!ads || !dirt_ads_build(ads, f, &cam))
                    return 1;
                const dirt_ads_stats *st = dirt_ads_get_stats(ads);
                double first = total_ms(st);
                int runs[3] = {st->depth_runs, st->fill_runs, st->bound_pass};
                double ms[DIRT_ADS_NUM_PASSES] = {0}, best = -1;
                for (int r = 0; r < repeat; r++) {
                    if (!dirt_ads_build(ads, f, &cam))
                        return 1;
                    double t = total_ms(st);
                    if (use_min ? best < 0 || t < best : true) {
                        for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
                            ms[p] = use_min ? st->ms[p] : ms[p] + st->ms[p] / repeat;
                        best = t;
                    }
                }
                double total = 0;
                for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
                    total += ms[p] > 0 ? ms[p] : 0;
                printf("| %s | %llu | %s | %d | %d | %llu | %.2f |", name,
                       (unsigned long long)st->primitives,
                       mode == DIRT_VIEWS_SINGLE ? "single" : mode == DIRT_VIEWS_CUBE ? "cube" : "cube+camera",
                       S[s], B[b], (unsigned long long)st->samples, st->buckets_per_sample);
                for (int p = 0; p < DIRT_ADS_NUM_PASSES; p++)
                    printf(" %.2f |", ms[p] > 0 ? ms[p] : 0.0);
                printf(" %.2f | %.2f | %d/%d/%d | %.2f | %.2f | %.2f |\n", total, first, runs[0],
                       runs[1], runs[2], st->bytes_total_used / 1e6,
                       st->bytes_total_allocated / 1e6, st->bytes_table3 / 1e6);
                fflush(stdout);
                dirt_ads_destroy(ads);
            }
        }
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    printf("\nTimes: %s.\n", dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU
                                 ? "CPU wall time around glFinish (cpu clock)"
                                 : "GPU timer queries (GL_TIME_ELAPSED, gpu clock)");
    dirt_gpu_destroy(gpu);
    return 0;
}
