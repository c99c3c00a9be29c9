/* DIRT build completeness (issue acceptance): against the exact CPU clip of
 * every triangle to every tile frustum, on the default scene and two shared
 * scenes, for S in {1,2,4}, B in {1,8,32}, views single and cube: zero
 * missing (primitive, tile) pairs, each in exactly the buckets its range
 * overlaps, depth bounds between the exact and the widened references,
 * nothing stored beyond the boundary tolerance, Hi-Z pyramid exact. */
#include <stdio.h>

#include "ads_common.h"
#include "dirt/scene.h"
#include "gpu.h"

static void run_scene(dirt_gpu *gpu, const char *label, dirt_scene *scene, float t)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, t, NULL);
    CHECK(f != NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    static const int sizes[] = {1, 2, 4};
    static const int buckets[] = {1, 8, 32};
    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE};
    for (int m = 0; m < 2; m++) {
        for (int s = 0; s < 3; s++) {
            for (int b = 0; b < 3; b++) {
                dirt_ads_opts o = {
                    .views = {.mode = modes[m], .width = 48, .height = 36, .face_size = 24,
                              .tile_size = sizes[s]},
                    .buckets = buckets[b],
                    .force_emulation = true,
                    .bucket_masks = s != 1, /* (S = 2: without; build_and_check) */
                };
                build_and_check(gpu, label, f, &cam, &o);
            }
        }
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    run_scene(gpu, "default", dirt_scene_create_default(), 0.0f);
    const char *shared = test_shared_dir();
    if (shared) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf", shared);
        run_scene(gpu, "CesiumMilkTruck", dirt_scene_load(path, NULL), 0.5f);
        snprintf(path, sizeof(path), "%s/scenes/gltf/Fox/Fox.glb", shared);
        run_scene(gpu, "Fox", dirt_scene_load(path, NULL), 0.7f);
    } else {
        fprintf(stderr, "../shared absent: default scene only\n");
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
