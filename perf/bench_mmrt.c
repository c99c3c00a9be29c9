/* bench-mmrt: MMRT build stage per pass (ms), fragments and memory (MB) over
 * a list of bucket counts, as a markdown table on stdout; optionally the
 * trace of a batch of rays per march mode.
 *   bench-mmrt [SCENE ...] [-W 1024 -H 512] [--views single|cube|cube+camera]
 *              [-F face] [-B 4,8,16] [--repeat N] [--trace] [--thickness F]
 * SCENE "default" is the embedded scene. Times: the GPU's one clock
 * (dirt_gpu_clock): GPU timer queries where the driver times rasterization,
 * else CPU wall time around glFinish (the only meaningful figure on
 * llvmpipe). Each configuration is built once to warm
 * up (pools grow), then N times; the mean of those N is reported.
 * --trace adds a second table: the ray types of the DIRT paper's Table 1
 * (ref/raytypes.h: primary, visibility, specular, glossy, diffuse, from an
 * Embree G-buffer of the camera image) traced with the Hi-Z walk and the
 * linear march (30 samples per view), thickness F x the scene diagonal
 * (--thickness, default 0.002 = the library's default): ms (without
 * upload and read-back), Mrays/s, and the agreement with Embree on the same
 * rays: the same primitive (or both miss), and "agree": visibility rays the
 * same occluded/free answer, other rays the same primitive or both hit within
 * 2 thicknesses along the ray (MMRT returns the fragment at a pixel centre,
 * often a neighbour of the primitive the ray meets). MMRT needs its bounce rays to
 * start beyond the thickness, so their origins are moved 2 thicknesses along
 * the normal (visibility rays keep their end point and stop 2 thicknesses
 * short of the light); Embree traces those same rays. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "mmrt/mmrt.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "dirt/scene.h"

/* The rays of every type for one scene, made MMRT-ready, with Embree's
 * closest hits. */
typedef struct ray_sets {
    dirt_ray *rays[DIRT_RAY_TYPES];
    uint32_t *ref_prim[DIRT_RAY_TYPES];
    float *ref_t[DIRT_RAY_TYPES];
    size_t count[DIRT_RAY_TYPES];
    float thickness;          /* the trace's default: 0.2 % of the diagonal */
} ray_sets;

static bool make_rays(const dirt_scene *scene, const dirt_frame *f, const dirt_camera *cam,
                      int W, int H, float thick_rel, ray_sets *rs)
{
    memset(rs, 0, sizeof(*rs));
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    if (!accel || !dirt_gbuffer_build(accel, scene, f, cam, W, H, &g)) {
        dirt_ref_accel_destroy(accel);
        return false;
    }
    float d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += (f->bounds_max[k] - f->bounds_min[k]) * (f->bounds_max[k] - f->bounds_min[k]);
    rs->thickness = thick_rel * sqrtf(d2);
    float off = 2 * rs->thickness;
    size_t cap = (size_t)W * H;
    bool ok = true;
    for (int t = 0; t < DIRT_RAY_TYPES && ok; t++) {
        rs->rays[t] = malloc(cap * sizeof(dirt_ray));
        rs->ref_prim[t] = malloc(cap * sizeof(uint32_t));
        rs->ref_t[t] = malloc(cap * sizeof(float));
        dirt_ref_ray *rr = malloc(cap * sizeof(dirt_ref_ray));
        dirt_ref_hit *rh = malloc(cap * sizeof(dirt_ref_hit));
        ok = rs->rays[t] && rs->ref_prim[t] && rs->ref_t[t] && rr && rh;
        size_t n = ok ? dirt_rays_generate(&g, cam, (enum dirt_ray_type)t, 7, rs->rays[t]) : 0;
        rs->count[t] = n;
        for (size_t i = 0; ok && i < n; i++) {
            dirt_ray *r = &rs->rays[t][i];
            if (t != DIRT_RAY_PRIMARY) {
                for (int k = 0; k < 3; k++) {
                    r->org[k] += off * g.normal[i][k];
                    if (t == DIRT_RAY_VISIBILITY)
                        r->dir[k] -= off * g.normal[i][k];
                }
                if (t == DIRT_RAY_VISIBILITY) {
                    float len = sqrtf(r->dir[0] * r->dir[0] + r->dir[1] * r->dir[1] +
                                      r->dir[2] * r->dir[2]);
                    r->tmax = len > 2 * off ? 1 - off / len : 0;
                }
            }
            rr[i] = (dirt_ref_ray){{r->org[0], r->org[1], r->org[2]}, r->tmin,
                                   {r->dir[0], r->dir[1], r->dir[2]}, r->tmax};
        }
        if (ok && n) {
            dirt_ref_intersect(accel, rr, rh, n, 0);
            for (size_t i = 0; i < n; i++) {
                rs->ref_prim[t][i] = rh[i].prim == DIRT_REF_MISS ? DIRT_HIT_NONE : rh[i].prim;
                rs->ref_t[t][i] = rh[i].t;
            }
        }
        free(rr);
        free(rh);
    }
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    return ok;
}

static void free_rays(ray_sets *rs)
{
    for (int t = 0; t < DIRT_RAY_TYPES; t++) {
        free(rs->rays[t]);
        free(rs->ref_prim[t]);
        free(rs->ref_t[t]);
    }
}

static const char *mode_name(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? "single" : m == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    int nscenes = 0, W = 1024, H = 512, F = 0, repeat = 3;
    bool trace = false;
    float thick_rel = 0.002f; /* thickness / scene diagonal (the library default) */
    int B[8] = {4, 8, 16}, nB = 3;
    enum dirt_view_mode mode = DIRT_VIEWS_SINGLE;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-F")) F = atoi(v), i++;
        else if (!strcmp(a, "-B")) nB = bench_parse_list(v, B, 8), i++;
        else if (!strcmp(a, "--repeat")) repeat = atoi(v), i++;
        else if (!strcmp(a, "--trace")) trace = true;
        else if (!strcmp(a, "--thickness")) thick_rel = (float)atof(v), i++;
        else if (!strcmp(a, "--views")) {
            if (!bench_views("bench-mmrt", v, &mode))
                return 2;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-mmrt [SCENE|default ...] [-W N -H N] [--views MODE] [-F N] "
                   "[-B 4,8,16] [--repeat N] [--trace] [--thickness F (x diagonal)]\n");
            return 0;
        } else if (nscenes < 16) scenes[nscenes++] = a;
    }
    if (W <= 0 || H <= 0 || repeat <= 0 || nB <= 0 || !(thick_rel > 0)) {
        fprintf(stderr, "bench-mmrt: bad arguments (see --help)\n");
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
    printf("| scene | tris | views | B | fragments | layers avg/max | clear ms | depth ms | mip ms "
           "| store ms | reorder ms | total ms | MB used | MB alloc | paper MB |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    /* Trace rows are collected and printed as a second table at the end. */
    char *trace_rows = NULL;
    size_t trace_len = 0;
    FILE *tf = trace ? open_memstream(&trace_rows, &trace_len) : NULL;
    dirt_hit *hits = trace ? malloc((size_t)W * H * sizeof(dirt_hit)) : NULL;
    if (trace && (!tf || !hits))
        return 1;
    for (int si = 0; si < nscenes; si++) {
        dirt_scene *scene = bench_scene(scenes[si], NULL);
        if (!scene)
            return 2;
        dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
        if (!f)
            return 1;
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        ray_sets rs;
        if (trace && !make_rays(scene, f, &cam, W, H, thick_rel, &rs))
            return 1;
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        for (int b = 0; b < nB; b++) {
            dirt_mmrt_opts o = {.views = {.mode = mode, .width = W, .height = H, .face_size = F},
                                .buckets = B[b]};
            dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
            if (!m || !dirt_mmrt_build(m, f, &cam))
                return 1;
            double ms[DIRT_MMRT_NUM_PASSES] = {0};
            for (int r = 0; r < repeat; r++) {
                if (!dirt_mmrt_build(m, f, &cam))
                    return 1;
                const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
                for (int p = 0; p < DIRT_MMRT_NUM_PASSES; p++)
                    ms[p] += st->ms[p] / repeat;
            }
            const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
            double total = 0;
            for (int p = 0; p < DIRT_MMRT_NUM_PASSES; p++)
                total += ms[p];
            printf("| %s | %llu | %s | %d | %llu | %.2f / %u | %.2f | %.2f | %.2f | %.2f | %.2f | "
                   "%.2f | %.2f | %.2f | %.2f |\n", name, (unsigned long long)st->primitives,
                   mode_name(mode), B[b], (unsigned long long)st->fragments, st->avg_layers,
                   st->max_layers, ms[0], ms[1], ms[2], ms[3], ms[4], total,
                   st->bytes_total_used / 1e6, st->bytes_total_allocated / 1e6,
                   st->bytes_paper / 1e6);
            for (int t = 0; trace && t < DIRT_RAY_TYPES; t++) {
                size_t n = rs.count[t];
                if (!n)
                    continue;
                fprintf(tf, "| %s | %d | %s | %zu |", name, B[b], dirt_ray_type_names[t], n);
                for (int k = 0; k < 2; k++) {
                    dirt_mmrt_trace_opts to = {.march = k ? DIRT_MMRT_MARCH_LINEAR
                                                          : DIRT_MMRT_MARCH_HIZ,
                                               .thickness = rs.thickness};
                    dirt_mmrt_trace_stats ts;
                    if (!dirt_mmrt_trace_cpu(m, rs.rays[t], n, hits, &to, &ts))
                        return 1;
                    double tms = ts.ms;
                    size_t same = 0, agree = 0;
                    for (size_t i = 0; i < n; i++) {
                        const dirt_ray *r = &rs.rays[t][i];
                        uint32_t ref = rs.ref_prim[t][i], got = hits[i].prim;
                        same += got == ref;
                        if (t == DIRT_RAY_VISIBILITY) {
                            agree += (got == DIRT_HIT_NONE) == (ref == DIRT_HIT_NONE);
                        } else if (got == ref) {
                            agree++;
                        } else if (got != DIRT_HIT_NONE && ref != DIRT_HIT_NONE) {
                            float len = sqrtf(r->dir[0] * r->dir[0] + r->dir[1] * r->dir[1] +
                                              r->dir[2] * r->dir[2]);
                            agree += fabsf(hits[i].t - rs.ref_t[t][i]) * len <= 2 * rs.thickness;
                        }
                    }
                    fprintf(tf, " %.1f | %.3f | %.2f | %.2f |", tms, n / (tms * 1e3),
                            100.0 * same / n, 100.0 * agree / n);
                }
                fprintf(tf, "\n");
            }
            fflush(stdout);
            dirt_mmrt_destroy(m);
        }
        if (trace)
            free_rays(&rs);
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    if (trace) {
        fclose(tf);
        printf("\n| scene | B | rays | count | Hi-Z ms | Hi-Z Mrays/s | Hi-Z same prim %% | "
               "Hi-Z agree %% | linear ms | linear Mrays/s | linear same prim %% | "
               "linear agree %% |\n");
        printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n%s",
               trace_rows ? trace_rows : "");
        printf("\nagree: visibility rays, the same occluded/free answer as Embree; other "
               "rays, the same primitive, or both hit within 2 thicknesses along the "
               "ray, or both miss. Thickness %.4g x the scene diagonal.\n", thick_rel);
        free(trace_rows);
    }
    printf("\nTimes: %s.\n", dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU
                                 ? "CPU wall time around glFinish (cpu clock)"
                                 : "GPU timer queries (GL_TIME_ELAPSED, gpu clock)");
    free(hits);
    dirt_gpu_destroy(gpu);
    return 0;
}
