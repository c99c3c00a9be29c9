/* bench-coherence: how alike the work of neighbouring rays is, in the order
 * the path tracer traces them with and without its ray sort
 * (dirt_pt_opts.sort_rays; glsl/integrator/sort.comp). Counts, not times:
 * the same on any machine for the same build, scene and size.
 *   bench-coherence [SCENE|default ...] [-W 256 -H 192] [--views MODE] [-S 2]
 *                   [-B 8] [--large N] [--group 32] [--max-scene-memory MIB]
 * Rays: camera G-buffer at W x H (Embree primary hits), then one event of
 * each type from those points (ref/raytypes.h), in pixel order (what
 * compaction hands the trace of a bounce: the live paths in about pixel
 * order), and the same rays after the GPU sort over the scene's bounds.
 * Both orders go through DIRT's counting trace (dirt_ads_trace_work); the
 * hits must agree ray for ray. For each counter (tiles, Hi-Z steps, list
 * nodes, triangle tests) it prints the mean per ray (the same in both
 * orders) and the lockstep efficiency of groups of G consecutive rays
 * (--group, 32 by default: a GPU's SIMD width): sum of the work / sum over
 * groups of G x the group's largest work. A SIMD GPU runs each group for
 * as long as its longest ray, so 1 means no divergence and 1/G that one ray
 * does all of its group's work. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "bench_common.h"
#include "dirt/ads.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "gl/gl.h"
#include "integrator/ray_sort.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

enum { C_TILES, C_HIZ, C_NODES, C_TESTS, C_NUM };
static const char *const counter_names[C_NUM] = {"tiles", "Hi-Z steps", "list nodes",
                                                 "triangle tests"};

static uint32_t counter(const dirt_trace_work *w, int c)
{
    return c == C_TILES ? w->tiles : c == C_HIZ ? w->hiz_steps
                       : c == C_NODES ? w->list_nodes : w->triangle_tests;
}

/* Sum of work / sum over groups of `group` consecutive rays of group x max. */
static double lockstep(const dirt_trace_work *w, size_t n, int c, int group)
{
    double sum = 0, cost = 0;
    for (size_t g = 0; g < n; g += (size_t)group) {
        uint32_t mx = 0;
        for (size_t i = g; i < n && i < g + (size_t)group; i++) {
            uint32_t v = counter(&w[i], c);
            sum += v;
            mx = v > mx ? v : mx;
        }
        cost += (double)group * mx;
    }
    return cost > 0 ? sum / cost : 1.0;
}

/* The permutation the GPU sort gives `rays` (order[j] = the ray traced
 * j-th). False after logging. */
static bool sort_order(dirt_gpu *gpu, const dirt_ray_sort *rs, const dirt_ray *rays, size_t n,
                       const float bmin[3], const float bmax[3], uint32_t *order)
{
    size_t bbytes = sizeof(struct dirt_gpu_ray_batch) + n * sizeof(uint32_t);
    uint32_t *batch = malloc(bbytes);
    if (!batch)
        return false;
    batch[0] = (uint32_t)(n ? DIRT_GROUPS(n) : 1);
    batch[1] = batch[2] = 1;
    batch[3] = (uint32_t)n;
    for (size_t i = 0; i < n; i++)
        batch[4 + i] = (uint32_t)i;
    dirt_ray_sort_io io = {
        .in_rays = gl_buffer_create(gpu, n * sizeof(*rays), rays, false, "rays"),
        .in_batch = gl_buffer_create(gpu, bbytes, batch, false, "batch"),
        .out_rays = gl_buffer_create(gpu, n * sizeof(*rays), NULL, false, "sorted rays"),
        .out_batch = gl_buffer_create(gpu, bbytes, NULL, true, "sorted batch"),
        .scratch = gl_buffer_create(gpu, dirt_ray_sort_scratch_bytes(n), NULL, false, "scratch"),
        .capacity = (uint32_t)n};
    memcpy(io.bounds_min, bmin, sizeof(io.bounds_min));
    memcpy(io.bounds_max, bmax, sizeof(io.bounds_max));
    bool ok = io.in_rays && io.in_batch && io.out_rays && io.out_batch && io.scratch;
    for (int p = 0; ok && p < DIRT_RAY_SORT_PASSES; p++) {
        dirt_ray_sort_pass(rs, (enum dirt_ray_sort_pass)p, &io);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    ok = ok && gl_buffer_read(io.out_batch, 0, bbytes, batch);
    if (ok)
        memcpy(order, batch + 4, n * sizeof(uint32_t));
    gl_buffer_destroy(&io.in_rays);
    gl_buffer_destroy(&io.in_batch);
    gl_buffer_destroy(&io.out_rays);
    gl_buffer_destroy(&io.out_batch);
    gl_buffer_destroy(&io.scratch);
    free(batch);
    return ok;
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    int n = 0, W = 256, H = 192, S = 2, B = 8, large = DIRT_ADS_MAX_LARGE, group = 32;
    dirt_load_opts load = {0};
    enum dirt_view_mode mode = DIRT_VIEWS_CUBE_CAMERA;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-S")) S = atoi(v), i++;
        else if (!strcmp(a, "-B")) B = atoi(v), i++;
        else if (!strcmp(a, "--large")) large = atoi(v), i++;
        else if (!strcmp(a, "--group")) group = atoi(v), i++;
        else if (!strcmp(a, "--max-scene-memory")) load.max_bytes = (size_t)atoll(v) << 20, i++;
        else if (!strcmp(a, "--views")) {
            if (!bench_views("bench-coherence", v, &mode))
                return 2;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-coherence [SCENE|default ...] [-W N -H N] [--views MODE] "
                   "[-S N] [-B N] [--large N] [--group G] [--max-scene-memory MIB]\n");
            return 0;
        } else if (a[0] == '-') {
            fprintf(stderr, "bench-coherence: unknown option %s (see --help)\n", a);
            return 2;
        } else if (n < 16) scenes[n++] = a;
    }
    if (W < 1 || H < 1 || group < 1) {
        fprintf(stderr, "bench-coherence: -W, -H and --group must be positive\n");
        return 2;
    }
    if (!n)
        scenes[n++] = "default";
    dirt_log_set_level(DIRT_LOG_WARN);
    char desc[512];
    dirt_gpu *gpu = bench_gpu(desc, sizeof(desc));
    if (!gpu)
        return 3;
    dirt_ray_sort *rs = dirt_ray_sort_create();
    if (!rs)
        return 1;
    printf("| scene | ray type | rays | counter | per ray | lockstep efficiency, pixel order | "
           "sorted | sorted / pixel order |\n|---|---|---|---|---|---|---|---|\n");
    int status = 0;
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
        dirt_ads_opts o = {.views = {.mode = mode, .width = W, .height = H, .tile_size = S},
                           .buckets = B, .large = large > 0 ? large : -1};
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        if (!ads || !dirt_ads_build(ads, f, &cam))
            return 1;
        size_t cap = (size_t)W * H;
        dirt_ray *rays = malloc(cap * sizeof(*rays)), *sorted = malloc(cap * sizeof(*rays));
        dirt_hit *hits = malloc(cap * sizeof(*hits)), *shits = malloc(cap * sizeof(*hits));
        dirt_trace_work *work = malloc(cap * sizeof(*work)), *swork = malloc(cap * sizeof(*work));
        uint32_t *order = malloc(cap * sizeof(*order));
        if (!rays || !sorted || !hits || !shits || !work || !swork || !order)
            return 1;
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
            size_t cnt = dirt_rays_generate(&g, &cam, t, 1, rays);
            dirt_trace_opts to = {.any_hit = t == DIRT_RAY_VISIBILITY};
            if (!sort_order(gpu, rs, rays, cnt, f->bounds_min, f->bounds_max, order))
                return 1;
            for (size_t j = 0; j < cnt; j++)
                sorted[j] = rays[order[j]];
            if (!dirt_ads_trace_work(ads, rays, cnt, hits, &to, NULL, work) ||
                !dirt_ads_trace_work(ads, sorted, cnt, shits, &to, NULL, swork))
                return 1;
            size_t differ = 0;
            for (size_t j = 0; j < cnt; j++) {
                const dirt_hit *a = &hits[order[j]], *b = &shits[j];
                differ += a->prim != b->prim || memcmp(&a->u, &b->u, 3 * sizeof(float));
            }
            if (differ) {
                fprintf(stderr, "bench-coherence: %s %s: %zu hits differ between the orders\n",
                        name, dirt_ray_type_names[t], differ);
                status = 1;
            }
            for (int c = 0; c < C_NUM; c++) {
                double sum = 0;
                for (size_t j = 0; j < cnt; j++)
                    sum += counter(&work[j], c);
                double eu = lockstep(work, cnt, c, group), es = lockstep(swork, cnt, c, group);
                printf("| %s | %s | %zu | %s | %.2f | %.3f | %.3f | %.2f |\n", name,
                       dirt_ray_type_names[t], cnt, counter_names[c], cnt ? sum / cnt : 0.0, eu,
                       es, eu > 0 ? es / eu : 0.0);
            }
            fflush(stdout);
        }
        free(rays);
        free(sorted);
        free(hits);
        free(shits);
        free(work);
        free(swork);
        free(order);
        dirt_ads_destroy(ads);
        dirt_gbuffer_free(&g);
        dirt_ref_accel_destroy(accel);
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    printf("\nGroups of %d consecutive rays; %dx%d, S = %d, B = %d.\n", group, W, H, S, B);
    dirt_ray_sort_destroy(rs);
    dirt_gpu_destroy(gpu);
    return status;
}
