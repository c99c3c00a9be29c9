/* bench-build: DIRT's build against MMRT's at equal settings, in one
 * process, interleaved, minimum of repeats (the build comparison of the
 * DIRT paper's Table 2: 1x1 tiles, same B; and DIRT with larger tiles).
 *   bench-build [SCENE ...] [-W 256 -H 256] [--views single|cube|cube+camera]
 *               [-F face] [-S 1,2] [-B 4] [--repeat N] [--reference-clip]
 *               [--build raster|compute|both]
 * SCENE "default" is the embedded scene. Every structure is created and
 * built once first (that first build's total is reported: "first ms", with
 * the DIRT passes it ran), then the N rounds build each structure once in
 * turn (MMRT, DIRT at each S; with --reference-clip also DIRT with the plain
 * Sutherland-Hodgman clip of every candidate; with --build compute the
 * compute build instead of the raster one, with --build both each DIRT
 * structure in both builds, side by side), so machine load hits all of
 * them alike; the minimum total of each over the rounds is reported, with
 * its passes. Times: the GPU's one clock (dirt_gpu_clock): timer queries
 * where the driver times rasterization, else CPU wall time around glFinish
 * (llvmpipe). Built with -DDIRT_BENCH_OLD it uses only what the build had
 * before the candidate passes (to measure an older tree the same way). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "dirt/ads.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "mmrt/mmrt.h"
#include "dirt/scene.h"

#define MAX_S 4
#define MAX_T (1 + 4 * MAX_S)
#define MAX_PASSES 8

typedef struct tech {
    char name[48];
    dirt_ads *ads;            /* or */
    dirt_mmrt *mmrt;
    double first, best;       /* ms */
    double best_ms[MAX_PASSES];
    char first_runs[32];
    uint64_t records;         /* n_p or fragments */
    double mb;                /* used */
} tech;

static double sum(const double *ms, int n)
{
    double t = 0;
    for (int i = 0; i < n; i++)
        t += ms[i] > 0 ? ms[i] : 0;
    return t;
}

/* Builds t once; its total ms, or -1. */
static double build(tech *t, const dirt_frame *f, const dirt_camera *cam)
{
    if (t->ads) {
        if (!dirt_ads_build(t->ads, f, cam))
            return -1;
        const dirt_ads_stats *st = dirt_ads_get_stats(t->ads);
        t->records = st->samples;
        t->mb = st->bytes_total_used / 1e6;
        return sum(st->ms, DIRT_ADS_NUM_PASSES);
    }
    if (!dirt_mmrt_build(t->mmrt, f, cam))
        return -1;
    const dirt_mmrt_stats *st = dirt_mmrt_get_stats(t->mmrt);
    t->records = st->fragments;
    t->mb = st->bytes_total_used / 1e6;
    return sum(st->ms, DIRT_MMRT_NUM_PASSES);
}

static void keep_passes(tech *t)
{
    if (t->ads)
        memcpy(t->best_ms, dirt_ads_get_stats(t->ads)->ms, sizeof(double) * DIRT_ADS_NUM_PASSES);
    else
        memcpy(t->best_ms, dirt_mmrt_get_stats(t->mmrt)->ms,
               sizeof(double) * DIRT_MMRT_NUM_PASSES);
}

_Static_assert(DIRT_ADS_NUM_PASSES <= MAX_PASSES && DIRT_MMRT_NUM_PASSES <= MAX_PASSES,
               "pass counts");

int main(int argc, char **argv)
{
    const char *scenes[16];
    int nscenes = 0, W = 256, H = 256, F = 0, repeat = 5, B = 4;
    int S[MAX_S] = {1, 2}, nS = 2;
    bool reference = false;
    bool build_raster = true, build_compute = false; /* --build */
    enum dirt_view_mode mode = DIRT_VIEWS_SINGLE;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-F")) F = atoi(v), i++;
        else if (!strcmp(a, "-S")) nS = bench_parse_list(v, S, MAX_S), i++;
        else if (!strcmp(a, "-B")) B = atoi(v), i++;
        else if (!strcmp(a, "--repeat")) repeat = atoi(v), i++;
        else if (!strcmp(a, "--reference-clip")) reference = true;
        else if (!strcmp(a, "--build")) {
            build_raster = !strcmp(v, "raster") || !strcmp(v, "both");
            build_compute = !strcmp(v, "compute") || !strcmp(v, "both");
            if (!build_raster && !build_compute) {
                fprintf(stderr, "bench-build: --build raster|compute|both, got '%s'\n", v);
                return 2;
            }
            i++;
        }
        else if (!strcmp(a, "--views")) {
            if (!bench_views("bench-build", v, &mode))
                return 2;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-build [SCENE|default ...] [-W N -H N] [--views MODE] [-F face] "
                   "[-S 1,2] [-B 4] [--repeat N] [--reference-clip] "
                   "[--build raster|compute|both]\n");
            return 0;
        } else if (nscenes < 16) scenes[nscenes++] = a;
    }
    if (W <= 0 || H <= 0 || repeat <= 0 || nS <= 0 || B <= 0) {
        fprintf(stderr, "bench-build: bad arguments (see --help)\n");
        return 2;
    }
#ifdef DIRT_BENCH_OLD
    if (build_compute) {
        fprintf(stderr, "bench-build: --build compute needs the compute build\n");
        return 2;
    }
    if (reference) {
        fprintf(stderr, "bench-build: --reference-clip needs the candidate build\n");
        return 2;
    }
#endif
    if (!nscenes)
        scenes[nscenes++] = "default";
    dirt_log_set_level(DIRT_LOG_WARN);
    char desc[512];
    dirt_gpu *gpu = bench_gpu(desc, sizeof(desc));
    if (!gpu)
        return 3;
    const char *views = mode == DIRT_VIEWS_SINGLE ? "single"
                        : mode == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
    printf("GPU: %s\n\n", desc);
    printf("%dx%d %s views%s, B = %d, minimum of %d interleaved rounds after one first build"
           "\n\n", W, H, views, mode == DIRT_VIEWS_SINGLE ? "" : " (faces max(W,H)/2 or -F)", B,
           repeat);
    printf("| scene | tris | technique | records | MB | first ms | first runs | build ms "
           "(min) | passes (min round) | / MMRT |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int si = 0; si < nscenes; si++) {
        dirt_scene *scene = bench_scene(scenes[si], NULL);
        if (!scene)
            return 2;
        dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        dirt_view_opts vo = {.mode = mode, .width = W, .height = H, .face_size = F};
        tech t[MAX_T];
        int nt = 0;
        memset(t, 0, sizeof(t));
        t[nt].mmrt = dirt_mmrt_create(gpu, &(dirt_mmrt_opts){.views = vo, .buckets = B});
        snprintf(t[nt++].name, sizeof(t[0].name), "MMRT");
        for (int r = 0; r < (reference ? 2 : 1); r++) {
            for (int s = 0; s < nS; s++) {
                for (int c = 0; c < 2; c++) {
                    if (!(c ? build_compute : build_raster))
                        continue;
                    dirt_ads_opts o = {.views = vo, .buckets = B};
                    o.views.tile_size = S[s];
#ifndef DIRT_BENCH_OLD
                    o.reference_clip = r == 1;
                    o.build = c ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER;
#endif
                    t[nt].ads = dirt_ads_create(gpu, &o);
                    snprintf(t[nt++].name, sizeof(t[0].name), "DIRT S=%d%s%s", S[s],
                             c ? " compute" : "", r ? " (reference clip)" : "");
                }
            }
        }
        for (int i = 0; i < nt; i++) {
            if (!t[i].ads && !t[i].mmrt)
                return 1;
            t[i].first = build(&t[i], f, &cam);
            if (t[i].first < 0)
                return 1;
            if (t[i].ads) {
                const dirt_ads_stats *st = dirt_ads_get_stats(t[i].ads);
#ifdef DIRT_BENCH_OLD
                snprintf(t[i].first_runs, sizeof(t[i].first_runs), "fill %d", st->fill_runs);
#else
                snprintf(t[i].first_runs, sizeof(t[i].first_runs), "depth %d, fill %d%s",
                         st->depth_runs, st->fill_runs, st->bound_pass ? ", bound" : "");
#endif
            } else {
                snprintf(t[i].first_runs, sizeof(t[i].first_runs), "store %d",
                         dirt_mmrt_get_stats(t[i].mmrt)->store_runs);
            }
            t[i].best = -1;
        }
        for (int r = 0; r < repeat; r++) {
            for (int i = 0; i < nt; i++) {
                double ms = build(&t[i], f, &cam);
                if (ms < 0)
                    return 1;
                if (t[i].best < 0 || ms < t[i].best) {
                    t[i].best = ms;
                    keep_passes(&t[i]);
                }
            }
        }
        for (int i = 0; i < nt; i++) {
            char passes[512];
            size_t k = 0;
            int np = t[i].ads ? DIRT_ADS_NUM_PASSES : DIRT_MMRT_NUM_PASSES;
            for (int p = 0; p < np && k < sizeof(passes); p++) {
                const char *pn = t[i].ads ? dirt_ads_pass_names[p] : dirt_mmrt_pass_names[p];
                if (t[i].best_ms[p] > 0)
                    k += (size_t)snprintf(passes + k, sizeof(passes) - k, "%s%s %.1f",
                                          k ? ", " : "", pn, t[i].best_ms[p]);
            }
            printf("| %s | %llu | %s | %llu | %.2f | %.1f | %s | %.1f | %s | %.2f |\n", name,
                   (unsigned long long)f->num_triangles, t[i].name,
                   (unsigned long long)t[i].records, t[i].mb, t[i].first, t[i].first_runs,
                   t[i].best, passes, t[i].best / t[0].best);
        }
        fflush(stdout);
        for (int i = 0; i < nt; i++) {
            dirt_ads_destroy(t[i].ads);
            dirt_mmrt_destroy(t[i].mmrt);
        }
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    printf("\nTimes: %s. records: DIRT n_p (clipped primitive samples), MMRT fragments.\n",
           dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU ? "CPU wall time around glFinish (cpu clock)"
                                                 : "GPU timer queries (gpu clock)");
    dirt_gpu_destroy(gpu);
    return 0;
}
