/* bench-mmrt: MMRT build stage per pass (ms), fragments and memory (MB) over
 * a list of bucket counts, as a markdown table on stdout; optionally the
 * trace of a batch of rays per march mode.
 *   bench-mmrt [SCENE ...] [-W 1024 -H 512] [--views single|cube|cube+camera]
 *              [-F face] [-B 4,8,16] [--repeat N] [--trace N]
 * SCENE "default" is the embedded scene. Times: GPU timer queries where the
 * driver times rasterization, else CPU wall time around glFinish (the only
 * meaningful figure on llvmpipe). Each configuration is built once to warm
 * up (pools grow), then N times; the mean of those N is reported. --trace N
 * traces N primary rays (from the camera's eye through uniformly random
 * points of its image, seeded, the same for every configuration) with the
 * Hi-Z walk and the linear march (30 samples per view), default thickness;
 * times without the upload and read-back. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/gpu.h"
#include "dirt/log.h"
#include "dirt/mmrt.h"
#include "dirt/scene.h"

static int parse_list(const char *s, int *out, int max)
{
    int n = 0;
    while (*s && n < max) {
        out[n++] = atoi(s);
        const char *c = strchr(s, ',');
        if (!c)
            break;
        s = c + 1;
    }
    return n;
}

static float frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

static const char *mode_name(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? "single" : m == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    int nscenes = 0, W = 1024, H = 512, F = 0, repeat = 3, trace = 0;
    int B[8] = {4, 8, 16}, nB = 3;
    enum dirt_view_mode mode = DIRT_VIEWS_SINGLE;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "-F")) F = atoi(v), i++;
        else if (!strcmp(a, "-B")) nB = parse_list(v, B, 8), i++;
        else if (!strcmp(a, "--repeat")) repeat = atoi(v), i++;
        else if (!strcmp(a, "--trace")) trace = atoi(v), i++;
        else if (!strcmp(a, "--views")) {
            mode = !strcmp(v, "cube") ? DIRT_VIEWS_CUBE
                 : !strcmp(v, "cube+camera") ? DIRT_VIEWS_CUBE_CAMERA : DIRT_VIEWS_SINGLE;
            i++;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-mmrt [SCENE|default ...] [-W N -H N] [--views MODE] [-F N] "
                   "[-B 4,8,16] [--repeat N] [--trace N]\n");
            return 0;
        } else if (nscenes < 16) scenes[nscenes++] = a;
    }
    if (W <= 0 || H <= 0 || repeat <= 0 || nB <= 0 || trace < 0) {
        fprintf(stderr, "bench-mmrt: bad arguments (see --help)\n");
        return 2;
    }
    if (!nscenes)
        scenes[nscenes++] = "default";
    dirt_log_set_level(DIRT_LOG_WARN);
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.no_debug = true});
    if (!gpu)
        return 3;
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    printf("GPU: %s\n\n", desc);
    printf("| scene | tris | views | B | fragments | layers avg/max | clear ms | depth ms | mip ms "
           "| store ms | reorder ms | total ms | MB used | MB alloc | paper MB |%s\n",
           trace ? " trace Hi-Z ms | trace linear ms | Mrays/s Hi-Z / linear | hits % |" : "");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|%s\n",
           trace ? "---|---|---|---|" : "");
    dirt_ray *rays = NULL;
    dirt_hit *hits = NULL;
    if (trace) {
        rays = calloc((size_t)trace, sizeof(*rays));
        hits = calloc((size_t)trace, sizeof(*hits));
        if (!rays || !hits)
            return 1;
    }
    for (int si = 0; si < nscenes; si++) {
        dirt_scene *scene = strcmp(scenes[si], "default") ? dirt_scene_load(scenes[si], NULL)
                                                          : dirt_scene_create_default();
        if (!scene)
            return 2;
        dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
        if (!f)
            return 1;
        dirt_camera cam;
        if (f->num_cameras && f->cameras[0].type == DIRT_CAMERA_PERSPECTIVE)
            cam = f->cameras[0];
        else
            dirt_camera_auto(f, &cam);
        unsigned seed = 2016;
        float ty = tanf(0.5f * (cam.yfov > 0 ? cam.yfov : 0.785398163f));
        float tx = ty * (float)W / (float)H;
        for (int i = 0; i < trace; i++) {
            float sx = (2 * frand(&seed) - 1) * tx, sy = (2 * frand(&seed) - 1) * ty;
            float d[3];
            for (int k = 0; k < 3; k++)
                d[k] = cam.forward[k] + sx * cam.right[k] + sy * cam.up[k];
            rays[i] = (dirt_ray){{cam.eye[0], cam.eye[1], cam.eye[2]}, 0, {d[0], d[1], d[2]},
                                 INFINITY};
        }
        const char *name = strrchr(scenes[si], '/') ? strrchr(scenes[si], '/') + 1 : scenes[si];
        for (int b = 0; b < nB; b++) {
            dirt_mmrt_opts o = {.views = {.mode = mode, .width = W, .height = H, .face_size = F},
                                .buckets = B[b], .cpu_timing = true};
            dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
            if (!m || !dirt_mmrt_build(m, f, &cam))
                return 1;
            double ms[DIRT_MMRT_NUM_PASSES] = {0};
            bool gpu_times = true;
            for (int r = 0; r < repeat; r++) {
                if (!dirt_mmrt_build(m, f, &cam))
                    return 1;
                const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
                for (int p = 0; p < DIRT_MMRT_NUM_PASSES; p++) {
                    gpu_times &= st->gpu_ms[p] >= 0;
                    ms[p] += (gpu_times ? st->gpu_ms[p] : st->cpu_ms[p]) / repeat;
                }
            }
            const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
            double total = 0;
            for (int p = 0; p < DIRT_MMRT_NUM_PASSES; p++)
                total += ms[p];
            printf("| %s | %llu | %s | %d | %llu | %.2f / %u | %.2f | %.2f | %.2f | %.2f | %.2f | "
                   "%.2f | %.2f | %.2f | %.2f |", name, (unsigned long long)st->primitives,
                   mode_name(mode), B[b], (unsigned long long)st->fragments, st->avg_layers,
                   st->max_layers, ms[0], ms[1], ms[2], ms[3], ms[4], total,
                   st->bytes_total_used / 1e6, st->bytes_total_allocated / 1e6,
                   st->bytes_paper / 1e6);
            if (trace) {
                double tms[2];
                uint64_t nhits = 0;
                for (int k = 0; k < 2; k++) {
                    dirt_mmrt_trace_opts to = {.march = k ? DIRT_MMRT_MARCH_LINEAR
                                                          : DIRT_MMRT_MARCH_HIZ};
                    dirt_mmrt_trace_stats ts;
                    if (!dirt_mmrt_trace_cpu(m, rays, (size_t)trace, hits, &to, &ts))
                        return 1;
                    tms[k] = ts.gpu_ms >= 0 ? ts.gpu_ms : ts.cpu_ms;
                    if (!k)
                        nhits = ts.hits;
                }
                printf(" %.2f | %.2f | %.3f / %.3f | %.1f |", tms[0], tms[1],
                       trace / (tms[0] * 1e3), trace / (tms[1] * 1e3), 100.0 * nhits / trace);
            }
            printf("\n");
            fflush(stdout);
            dirt_mmrt_destroy(m);
        }
        dirt_frame_destroy(f);
        dirt_scene_destroy(scene);
    }
    printf("\nTimes: %s.\n", dirt_gpu_get_caps(gpu)->software
                                 ? "CPU wall time around glFinish (software renderer)"
                                 : "GPU timer queries (GL_TIME_ELAPSED)");
    free(rays);
    free(hits);
    dirt_gpu_destroy(gpu);
    return 0;
}
