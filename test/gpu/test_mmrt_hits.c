/* The hit-agreement harness of the DIRT test, run on MMRT: the same rays
 * (camera G-buffer; visibility, specular, glossy 0.1, diffuse) traced by MMRT
 * (Hi-Z march, cube+camera views, B = 4) and by Embree on the default scene,
 * for two thicknesses (secondary rays start 3 thicknesses off the surface,
 * as in the path tracer). It prints MMRT's agreement per ray type and thickness
 * (expected below DIRT's 100 %: MMRT's hits are approximate) and asserts:
 *  - every hit lies within the thickness (in the eye depth of the view it was
 *    found in) of the stored fragment it reports;
 *  - camera rays through pixel centres find the visible surface (>= 99 %);
 *  - each secondary ray type agrees with Embree at least as often as
 *    measured when the floors were set (llvmpipe, Mesa 22.3.6; the test is
 *    deterministic): thickness 0.2 %: visibility 61.2, specular 76.4,
 *    glossy 65.1, diffuse 42.1 %; thickness 1 %: 75.0, 78.0, 72.6, 60.9 %.
 *    Each floor sits about one point below (MIN_AGREE), so a regression in
 *    the march or the views shows while rounding on another GPU does not;
 *  - no march aborted. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "mmrt/mmrt.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "gpu.h"

/* Agreement floors in percent, per thickness and ray type (see above). */
static const double MIN_AGREE[2][DIRT_RAY_TYPES] = {
    [0] = {[DIRT_RAY_PRIMARY] = 99.0, [DIRT_RAY_VISIBILITY] = 60.0, [DIRT_RAY_SPECULAR] = 75.0,
           [DIRT_RAY_GLOSSY] = 64.0, [DIRT_RAY_DIFFUSE] = 41.0},
    [1] = {[DIRT_RAY_PRIMARY] = 99.0, [DIRT_RAY_VISIBILITY] = 74.0, [DIRT_RAY_SPECULAR] = 77.0,
           [DIRT_RAY_GLOSSY] = 71.5, [DIRT_RAY_DIFFUSE] = 60.0},
};

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam = f->cameras[0];
    cam.aspect = 0;
    const int W = 64, H = 48;
    dirt_mmrt_opts mo = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = W, .height = H,
                                   .face_size = 48}};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &mo);
    CHECK(m && dirt_mmrt_build(m, f, &cam));
    const dirt_view_set *set = dirt_mmrt_views(m);
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    CHECK(dirt_gbuffer_build(accel, scene, f, &cam, W, H, &g));
    size_t cap = (size_t)W * H;
    dirt_ray *rays = malloc(cap * sizeof(*rays));
    dirt_hit *hits = malloc(cap * sizeof(*hits));
    dirt_ref_hit *ref = malloc(cap * sizeof(*ref));
    unsigned char *occ = malloc(cap);
    float diag = sqrtf(12.0f); /* the default room spans 2 x 2 x 2 */
    static const float rel_thickness[] = {0.002f, 0.01f};
    for (int k = 0; k < 2; k++) {
        dirt_mmrt_trace_opts to = {.march = DIRT_MMRT_MARCH_HIZ,
                                   .thickness = rel_thickness[k] * diag};
        fprintf(stderr, "MMRT thickness %.3f (%.1f%% of the diagonal):", to.thickness,
                100 * rel_thickness[k]);
        for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
            size_t n = dirt_rays_generate(&g, &cam, t, 7, rays);
            /* Secondary rays start (and visibility rays end) 3 thicknesses
             * away from the surfaces, as the path tracer does for MMRT:
             * closer, MMRT hits the surface the ray leaves. Embree gets the
             * same rays. */
            for (size_t i = 0; t != DIRT_RAY_PRIMARY && i < n; i++) {
                float len = sqrtf(rays[i].dir[0] * rays[i].dir[0] + rays[i].dir[1] * rays[i].dir[1] +
                                  rays[i].dir[2] * rays[i].dir[2]);
                rays[i].tmin = 3 * to.thickness / len;
                if (t == DIRT_RAY_VISIBILITY)
                    rays[i].tmax = 1 - 3 * to.thickness / len;
            }
            dirt_mmrt_trace_stats ts;
            CHECK(dirt_mmrt_trace_cpu(m, rays, n, hits, &to, &ts));
            CHECK(ts.aborted == 0);
            bool vis = t == DIRT_RAY_VISIBILITY;
            if (vis)
                dirt_ref_occluded(accel, (const dirt_ref_ray *)rays, occ, n, 0);
            else
                dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, n, 0);
            size_t same = 0, beyond = 0;
            for (size_t i = 0; i < n; i++) {
                bool mh = hits[i].prim != DIRT_HIT_NONE;
                if (mh) {
                    float p[3];
                    for (int c = 0; c < 3; c++)
                        p[c] = rays[i].org[c] + hits[i].t * rays[i].dir[c];
                    double z = dirt_view_depth(&set->views[hits[i].view], p);
                    if (fabs(z - hits[i].reserved) > to.thickness * 1.001 + 1e-5 * z)
                        beyond++;
                }
                if (vis) {
                    same += mh == (occ[i] != 0);
                } else {
                    bool eh = ref[i].prim != DIRT_REF_MISS;
                    same += (!mh && !eh) || (mh && eh && hits[i].prim == ref[i].prim);
                }
            }
            fprintf(stderr, " %s %.1f%%", dirt_ray_type_names[t], 100.0 * same / n);
            CHECK_MSG(beyond == 0, "%zu %s hits farther than the thickness from their fragment",
                      beyond, dirt_ray_type_names[t]);
            CHECK_MSG(100.0 * same >= MIN_AGREE[k][t] * n,
                      "thickness %d: %s rays agree %.1f%%, floor %.1f%%", k,
                      dirt_ray_type_names[t], 100.0 * same / n, MIN_AGREE[k][t]);
        }
        fputc('\n', stderr);
    }
    free(rays);
    free(hits);
    free(ref);
    free(occ);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    dirt_mmrt_destroy(m);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
