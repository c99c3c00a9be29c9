/* Convergence of the reference path tracer on the default scene
 * (dirt_scene_create_default, its own camera, 32 x 24 pixels, K = 4).
 *
 * The reference is a 4096-spp render with its own seed, independent of every
 * test render. For spp = 4, 16, 64 the MSE against it is averaged over 16
 * renders with distinct seeds (the scene has caustic paths - a mirror sphere
 * seen by diffuse walls - whose rare large samples make the MSE of a single
 * 768-pixel render scatter by a factor ~2; averaging 16 brings the scatter of
 * the ratios below ~20 %). For an unbiased estimator with independent
 * samples, E[MSE(n)] = s^2 / n + s^2 / 4096, so each 4x step in spp divides
 * the MSE by ~3.95. Accepted range per step: [2.5, 6.4] = 4 x [0.625, 1.6],
 * measured ratios over 8 disjoint seed groups were 3.1 .. 4.8. A biased
 * estimator flattens the curve (a squared bias of 0.01 alone gives a 16 -> 64
 * ratio of 2.1), correlated samples give ~1.
 * Also checks the first-hit channels (closed room: every pixel hits) and
 * that the render is deterministic. Runtime ~7 s on 2 cores. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "ref/ref.h"

#define SEEDS 16

int main(void)
{
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    if (!scene)
        return check_finish();
    dirt_frame *frame = dirt_scene_evaluate(scene, 0.0f, NULL);
    CHECK(frame != NULL && frame->num_cameras > 0);
    if (!frame || frame->num_cameras == 0) {
        dirt_frame_destroy(frame);
        dirt_scene_destroy(scene);
        return check_finish();
    }
    dirt_camera cam = frame->cameras[0];

    dirt_ref_accel *accel = dirt_ref_accel_create(frame, NULL);
    CHECK(accel != NULL);
    dirt_ref_opts o = {0};
    o.width = 32;
    o.height = 24;
    o.bounces = 4;
    o.accel = accel;
    o.spp = 4096;
    o.seed = 0x5eed0000u;
    dirt_ref_stats st;
    dirt_image *ref = dirt_ref_render(scene, frame, &cam, &o, &st);
    CHECK(ref != NULL);
    if (!ref || !accel)
        goto done;
    fprintf(stderr, "reference: %d spp, %.2f s, %.2f Mrays/s, %d threads\n", o.spp, st.seconds,
            st.mrays_per_s, st.threads);
    CHECK(st.invalid == 0);

    /* First-hit channels: the room is closed, so every pixel has a hit. */
    const float *nx = dirt_image_find_channel(ref, "N.X"), *ny = dirt_image_find_channel(ref, "N.Y"),
                *nz = dirt_image_find_channel(ref, "N.Z"), *z = dirt_image_find_channel(ref, "Z"),
                *ar = dirt_image_find_channel(ref, "albedo.R");
    CHECK(nx && ny && nz && z && ar);
    if (nx && ny && nz && z && ar) {
        int bad = 0;
        for (int i = 0; i < o.width * o.height; i++) {
            float l = sqrtf(nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i]);
            /* a mean of unit normals: length 1 except at silhouettes */
            bad += !(l > 0.3f && l <= 1.0001f) || !(isfinite(z[i]) && z[i] > 0.0f) ||
                   !(ar[i] >= 0.0f && ar[i] <= 1.0f);
        }
        CHECK_MSG(bad == 0, "%d pixels with invalid first-hit channels", bad);
    }

    static const int spps[3] = {4, 16, 64};
    double mse[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < SEEDS; k++) {
            o.spp = spps[i];
            o.seed = (uint32_t)(100 * i + k); /* distinct from each other and the reference */
            dirt_image *img = dirt_ref_render(scene, frame, &cam, &o, NULL);
            CHECK(img != NULL);
            if (!img)
                goto done;
            mse[i] += dirt_image_mse(img, ref) / SEEDS;
            if (i == 0 && k == 0) { /* deterministic: the same render twice */
                dirt_image *again = dirt_ref_render(scene, frame, &cam, &o, NULL);
                CHECK(again && memcmp(again->rgba, img->rgba,
                                      (size_t)o.width * o.height * 4 * sizeof(float)) == 0);
                dirt_image_destroy(again);
            }
            dirt_image_destroy(img);
        }
    for (int i = 0; i < 3; i++)
        fprintf(stderr, "spp %2d: MSE %.6f\n", spps[i], mse[i]);
    for (int i = 0; i < 2; i++) {
        double r = mse[i] / mse[i + 1];
        fprintf(stderr, "MSE(%d) / MSE(%d) = %.2f (accepted 2.5 .. 6.4)\n", spps[i], spps[i + 1], r);
        CHECK_MSG(r >= 2.5 && r <= 6.4, "spp %d -> %d: MSE ratio %.2f", spps[i], spps[i + 1], r);
    }

done:
    dirt_image_destroy(ref);
    dirt_ref_accel_destroy(accel);
    dirt_frame_destroy(frame);
    dirt_scene_destroy(scene);
    return check_finish();
}
