/* bench-ref: the Embree ground truth's BVH build time and ray throughput per
 * ray type (the DIRT paper's Table 1 types), as markdown tables on stdout.
 *   bench-ref [SCENE|default ...] [-W 1024 -H 512] [--threads N] [--repeat N]
 *             [--high-quality] [--pt-spp N]
 * Without SCENE: the default scene and, when present,
 * $DIRT_SHARED_DIR/scenes/gltf/FlightHelmet/FlightHelmet.gltf (else the
 * ../shared of the source tree).
 *
 * Method: the frame at t = 0 and the scene's first perspective camera (else
 * dirt_camera_auto). Build: the BVH is rebuilt `repeat` times after one
 * warm-up (dirt_ref_accel_update, as every animated frame does); the median
 * rtcCommitScene time is reported. Rays: primary rays through the pixel
 * centres of a W x H image, then from their hits one ray of each type
 * (dirt_rays_generate: visibility towards a light point, mirror, GGX glossy,
 * cosine diffuse); each batch is traced closest-hit (dirt_ref_intersect on
 * all threads) once to warm up and then `repeat` times; the median time
 * gives Mrays/s. Visibility rays are also timed as occlusion queries (what
 * a shadow ray needs). Last, the path tracer's own rate (all rays it casts,
 * W/4 x H/4 pixels, --pt-spp samples, K = 4). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dirt/clock.h"
#include "dirt/log.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "dirt/scene.h"

#ifndef DIRT_SHARED_DIR_DEFAULT
#define DIRT_SHARED_DIR_DEFAULT "../shared"
#endif

#define MAX_REPEAT 101

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct result {
    const char *name;
    size_t tris;
    double build_ms, mprims;
    size_t rays[DIRT_RAY_TYPES];
    double hit_pct[DIRT_RAY_TYPES];
    double mrays[DIRT_RAY_TYPES];
    double occluded_mrays;
    double pt_mrays;
} result;

static bool bench_scene(const char *path, int W, int H, int threads, int repeat, bool hq,
                        int pt_spp, result *r)
{
    bool ok = false;
    dirt_scene *scene = NULL;
    dirt_frame *f = NULL;
    dirt_ref_accel *accel = NULL;
    dirt_gbuffer g;
    dirt_ray *rays = NULL;
    dirt_ref_hit *hits = NULL;
    uint8_t *occ = NULL;
    double times[MAX_REPEAT];

    memset(&g, 0, sizeof(g));
    memset(r, 0, sizeof(*r));
    r->name = path;
    scene = strcmp(path, "default") ? dirt_scene_load(path, NULL) : dirt_scene_create_default();
    if (!scene)
        goto done;
    f = dirt_scene_evaluate(scene, 0.0f, NULL);
    if (!f)
        goto done;
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    r->tris = f->num_triangles;

    dirt_ref_accel_opts ao = {0};
    ao.threads = threads;
    ao.high_quality = hq;
    accel = dirt_ref_accel_create(f, &ao);
    if (!accel)
        goto done;
    for (int i = 0; i < repeat; i++) {
        if (!dirt_ref_accel_update(accel, f))
            goto done;
        dirt_ref_build_stats bs;
        dirt_ref_accel_stats(accel, &bs);
        times[i] = bs.build_ms;
    }
    r->build_ms = median(times, repeat);
    r->mprims = r->build_ms > 0 ? (double)r->tris / (r->build_ms * 1e3) : 0.0;

    if (!dirt_gbuffer_build(accel, scene, f, &cam, W, H, &g))
        goto done;
    size_t n = (size_t)W * (size_t)H;
    rays = malloc(n * sizeof(*rays));
    hits = malloc(n * sizeof(*hits));
    occ = malloc(n);
    if (!rays || !hits || !occ) {
        fprintf(stderr, "bench-ref: out of memory\n");
        goto done;
    }
    for (int t = 0; t < DIRT_RAY_TYPES; t++) {
        size_t count = dirt_rays_generate(&g, &cam, (enum dirt_ray_type)t, 1u, rays);
        const dirt_ref_ray *rr = (const dirt_ref_ray *)rays;
        r->rays[t] = count;
        if (count == 0)
            continue;
        dirt_ref_intersect(accel, rr, hits, count, threads); /* warm-up */
        size_t nhit = 0;
        for (size_t i = 0; i < count; i++)
            nhit += hits[i].prim != DIRT_REF_MISS;
        r->hit_pct[t] = 100.0 * (double)nhit / (double)count;
        for (int i = 0; i < repeat; i++) {
            double t0 = dirt_clock_ms();
            dirt_ref_intersect(accel, rr, hits, count, threads);
            times[i] = dirt_clock_ms() - t0;
        }
        double ms = median(times, repeat);
        r->mrays[t] = ms > 0 ? (double)count / (ms * 1e3) : 0.0;
        if (t == DIRT_RAY_VISIBILITY) {
            dirt_ref_occluded(accel, rr, occ, count, threads);
            for (int i = 0; i < repeat; i++) {
                double t0 = dirt_clock_ms();
                dirt_ref_occluded(accel, rr, occ, count, threads);
                times[i] = dirt_clock_ms() - t0;
            }
            ms = median(times, repeat);
            r->occluded_mrays = ms > 0 ? (double)count / (ms * 1e3) : 0.0;
        }
    }

    if (pt_spp > 0) {
        dirt_ref_opts o = {0};
        o.width = W / 4 > 0 ? W / 4 : 1;
        o.height = H / 4 > 0 ? H / 4 : 1;
        o.spp = pt_spp;
        o.bounces = 4;
        o.threads = threads;
        o.accel = accel;
        dirt_ref_stats st;
        dirt_image *img = dirt_ref_render(scene, f, &cam, &o, &st);
        if (!img)
            goto done;
        dirt_image_destroy(img);
        r->pt_mrays = st.mrays_per_s;
    }
    ok = true;

done:
    free(rays);
    free(hits);
    free(occ);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    return ok;
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    char helmet[4096];
    int nscenes = 0, W = 1024, H = 512, threads = 0, repeat = 5, pt_spp = 4;
    bool hq = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
        if (!strcmp(a, "-W")) W = atoi(v), i++;
        else if (!strcmp(a, "-H")) H = atoi(v), i++;
        else if (!strcmp(a, "--threads")) threads = atoi(v), i++;
        else if (!strcmp(a, "--repeat")) repeat = atoi(v), i++;
        else if (!strcmp(a, "--pt-spp")) pt_spp = atoi(v), i++;
        else if (!strcmp(a, "--high-quality")) hq = true;
        else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: bench-ref [SCENE|default ...] [-W 1024 -H 512] [--threads N] "
                   "[--repeat N] [--high-quality] [--pt-spp N]\n");
            return 0;
        } else if (a[0] == '-') {
            fprintf(stderr, "bench-ref: unknown option %s (see --help)\n", a);
            return 2;
        } else if (nscenes < 16) {
            scenes[nscenes++] = a;
        }
    }
    if (W <= 0 || H <= 0 || threads < 0 || repeat <= 0 || repeat > MAX_REPEAT || pt_spp < 0) {
        fprintf(stderr, "bench-ref: bad arguments (see --help)\n");
        return 2;
    }
    if (!nscenes) {
        scenes[nscenes++] = "default";
        const char *sd = getenv("DIRT_SHARED_DIR");
        snprintf(helmet, sizeof(helmet), "%s/scenes/gltf/FlightHelmet/FlightHelmet.gltf",
                 sd && *sd ? sd : DIRT_SHARED_DIR_DEFAULT);
        FILE *fp = fopen(helmet, "rb");
        if (fp) {
            fclose(fp);
            scenes[nscenes++] = helmet;
        } else {
            fprintf(stderr, "bench-ref: %s not found, skipped\n", helmet);
        }
    }
    dirt_log_set_level(DIRT_LOG_WARN);

    result res[16];
    int nres = 0;
    for (int i = 0; i < nscenes; i++) {
        if (!bench_scene(scenes[i], W, H, threads, repeat, hq, pt_spp, &res[nres])) {
            fprintf(stderr, "bench-ref: %s failed\n", scenes[i]);
            return 1;
        }
        nres++;
    }

    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    printf("Embree %s BVH (robust), %dx%d primary rays, %d threads, median of %d runs\n\n",
           hq ? "HIGH" : "MEDIUM", W, H, threads > 0 ? threads : (int)cpus, repeat);
    printf("| scene | triangles | build ms | build Mprims/s | primary | visibility | specular "
           "| glossy | diffuse | visibility (occluded) | path tracer |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nres; i++) {
        const result *r = &res[i];
        const char *base = strrchr(r->name, '/');
        printf("| %s | %zu | %.2f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
               base ? base + 1 : r->name, r->tris, r->build_ms, r->mprims,
               r->mrays[DIRT_RAY_PRIMARY], r->mrays[DIRT_RAY_VISIBILITY],
               r->mrays[DIRT_RAY_SPECULAR], r->mrays[DIRT_RAY_GLOSSY], r->mrays[DIRT_RAY_DIFFUSE],
               r->occluded_mrays, r->pt_mrays);
    }
    printf("\nRay throughput in Mrays/s (closest hit unless stated).\n\n");
    printf("| scene | ray type | rays | hit %% |\n|---|---|---|---|\n");
    for (int i = 0; i < nres; i++) {
        const char *base = strrchr(res[i].name, '/');
        for (int t = 0; t < DIRT_RAY_TYPES; t++)
            printf("| %s | %s | %zu | %.1f |\n", base ? base + 1 : res[i].name,
                   dirt_ray_type_names[t], res[i].rays[t], res[i].hit_pct[t]);
    }
    return 0;
}
