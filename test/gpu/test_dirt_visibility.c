/* Direct visibility: the visibility buffer of the camera view, resolved into
 * rays and hit records, finds the same first hits as Embree's pixel-centre
 * camera rays (same primitive, or the same t within 1e-4 on shared edges,
 * for >= 99.9 % of the pixels; every Embree miss is a miss), at odd image
 * sizes too; and a path-traced image with --direct-visibility renders
 * without aborted rays or GL errors. Default scene and CesiumMilkTruck. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "dirt/ads.h"
#include "integrator/pathtrace.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "gpu.h"

static void run(dirt_gpu *gpu, const char *label, dirt_scene *scene, int w, int h)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    cam.aspect = 0; /* the image's aspect, as the views use */
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = w, .height = h,
                                 .face_size = 32, .tile_size = 2},
                       .buckets = 8, .force_emulation = true};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads && dirt_ads_build(ads, f, &cam));
    size_t n = (size_t)w * h;
    dirt_ray *rays = malloc(n * sizeof(*rays));
    dirt_hit *hits = malloc(n * sizeof(*hits));
    CHECK(dirt_ads_direct_visibility(ads, rays, hits));
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    CHECK(dirt_gbuffer_build(accel, scene, f, &cam, w, h, &g));
    dirt_ray *prim = malloc(n * sizeof(*prim));
    dirt_rays_generate(&g, &cam, DIRT_RAY_PRIMARY, 0, prim);
    dirt_ref_hit *ref = malloc(n * sizeof(*ref));
    dirt_ref_intersect(accel, (const dirt_ref_ray *)prim, ref, n, 0);
    size_t same = 0, ref_hits = 0, false_hits = 0;
    for (size_t i = 0; i < n; i++) {
        bool eh = ref[i].prim != DIRT_REF_MISS, dh = hits[i].prim != DIRT_HIT_NONE;
        ref_hits += eh;
        false_hits += dh && !eh;
        CHECK(hits[i].owner == i);
        if (eh && dh && (hits[i].prim == ref[i].prim ||
                         fabsf(hits[i].t - ref[i].t) <= 1e-4f * ref[i].t))
            same++;
        else if (!eh && !dh)
            same++;
    }
    fprintf(stderr, "%-16s %dx%d: %zu pixels, %zu Embree hits, visibility agrees on %zu "
            "(%.3f%%), %zu hits where Embree misses\n", label, w, h, n, ref_hits, same,
            100.0 * same / n, false_hits);
    CHECK(same >= 0.999 * n);
    CHECK(false_hits <= n / 1000);
    /* Path tracing from the visibility buffer. */
    dirt_pt *pt = dirt_pt_create(gpu, scene);
    dirt_image *img = dirt_image_create(w, h);
    dirt_pt_opts po = {.spp = 2, .bounces = 2, .direct_visibility = true,
                       .background = {1, 1, 1}}; /* the truck has no lights */
    dirt_pt_stats st;
    CHECK(pt && img && dirt_pt_render(pt, dirt_ads_tracer(ads, NULL), f, &cam, &po, img, &st));
    CHECK(st.aborted == 0 && st.invalid_samples == 0);
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += img->rgba[4 * i] + img->rgba[4 * i + 1] + img->rgba[4 * i + 2];
    CHECK(sum > 0 && isfinite(sum));
    dirt_image_destroy(img);
    dirt_pt_destroy(pt);
    free(ref);
    free(prim);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    free(rays);
    free(hits);
    dirt_ads_destroy(ads);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    run(gpu, "default", dirt_scene_create_default(), 64, 48);
    run(gpu, "default", dirt_scene_create_default(), 97, 61);
    const char *shared = test_shared_dir();
    if (shared) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf", shared);
        run(gpu, "CesiumMilkTruck", dirt_scene_load(path, NULL), 80, 60);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
