/* DIRT engine: the scene fuzz target's entry (see fuzz_scene.h). */
#include "fuzz_scene.h"

#include "dirt/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The frame agrees with the scene's counts; every corner is read (a short
 * array is then the sanitizer's to see). */
static bool check_frame(const dirt_scene *s, const dirt_frame *f)
{
    if (!f || f->num_triangles != dirt_scene_num_triangles(s) ||
        f->num_nodes != dirt_scene_num_nodes(s))
        return false;
    volatile float sink = 0.0f;
    for (size_t i = 0; i < 3 * f->num_triangles; i++)
        sink += f->position[i][0] + f->normal[i][1] + f->uv[i][0];
    for (size_t i = 0; i < f->num_triangles; i++)
        sink += (float)f->material[i];
    (void)sink;
    return true;
}

dirt_scene *dirt_fuzz_load(const uint8_t *data, size_t size)
{
    const dirt_load_opts lo = {.max_bytes = (size_t)64 << 20};
    if (size > 0 && data[0] == '#') {
        const uint8_t *nul = memchr(data, 0, size);
        size_t obj = nul ? (size_t)(nul - data) : size;
        return dirt_scene_load_obj_memory(data, obj, nul ? nul + 1 : NULL,
                                          nul ? size - obj - 1 : 0, "fuzz.obj", &lo);
    }
    return dirt_scene_load_memory(data, size, "fuzz.gltf", &lo);
}

bool dirt_fuzz_scene_one(const uint8_t *data, size_t size)
{
    dirt_scene *s = dirt_fuzz_load(data, size);
    if (!s) {
        if (dirt_scene_last_error() == DIRT_SCENE_ERR_OK) {
            fprintf(stderr, "fuzz: a failed load left no error id\n");
            return false;
        }
        return true;
    }
    bool ok = dirt_scene_last_error() == DIRT_SCENE_ERR_OK;
    static const float times[] = {0.0f, 0.37f, 1.0f, -2.5f, 1e6f};
    size_t clips = dirt_scene_num_clips(s);
    if (clips > 4)
        clips = 4;
    dirt_frame *f = NULL;
    for (int c = -1; ok && c <= (int)clips; c++) {
        for (size_t t = 0; ok && t < sizeof(times) / sizeof(times[0]); t++) {
            for (int loop = 0; ok && loop < 2; loop++) {
                dirt_eval_opts eo = {.clip = c < (int)clips ? c : 0, .loop = loop != 0,
                                     .all_clips = c == (int)clips};
                if (!f) {
                    f = dirt_scene_evaluate(s, times[t], &eo);
                    ok = check_frame(s, f);
                } else {
                    ok = dirt_scene_evaluate_into(s, times[t], &eo, f) && check_frame(s, f);
                }
            }
        }
        if (ok && c >= 0 && c < (int)clips) {
            float mn[3], mx[3];
            dirt_eval_opts eo = {.clip = c};
            ok = dirt_scene_clip_bounds(s, &eo, mn, mx);
        }
    }
    if (!ok)
        fprintf(stderr, "fuzz: a loaded scene failed to evaluate consistently\n");
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
    return ok;
}
