/* The automatic camera for a whole clip: dirt_scene_clip_bounds unions the
 * bounds over the clip and dirt_camera_auto_bounds frames them, so every
 * frame of a sequence gets the same camera, while dirt_camera_auto (one
 * frame's bounds) follows the objects. Uses the animated shared scenes
 * (BoxAnimated, Fox): when ../shared is missing the test skips, except with
 * CI=true, where a missing scene fails it. */
#include "check.h"

#include "dirt/scene.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool in_ci(void)
{
    const char *ci = getenv("CI");
    return ci && strcmp(ci, "true") == 0;
}

/* Largest distance by which the frame's bounds stick out of [mn, mx]. */
static double overshoot(const dirt_frame *f, const float mn[3], const float mx[3])
{
    double worst = 0.0;
    for (int k = 0; k < 3; k++) {
        worst = fmax(worst, (double)mn[k] - f->bounds_min[k]);
        worst = fmax(worst, (double)f->bounds_max[k] - mx[k]);
    }
    return worst;
}

/* A scene without animation: the clip bounds are the rest pose's bounds and
 * the clip camera is dirt_camera_auto of the rest pose, bit for bit. */
static void check_static(const dirt_scene *s, const char *name)
{
    float mn[3], mx[3];
    dirt_eval_opts rest = {.clip = -1};
    CHECK(dirt_scene_clip_bounds(s, &rest, mn, mx));
    if (dirt_scene_num_clips(s) == 0) { /* clip 0 (NULL options) does not exist */
        float mn0[3], mx0[3];
        CHECK(dirt_scene_clip_bounds(s, NULL, mn0, mx0));
        CHECK(memcmp(mn, mn0, sizeof(mn)) == 0 && memcmp(mx, mx0, sizeof(mx)) == 0);
    }
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, &rest);
    CHECK(f != NULL);
    if (!f)
        return;
    CHECK_MSG(memcmp(mn, f->bounds_min, sizeof(mn)) == 0 &&
                  memcmp(mx, f->bounds_max, sizeof(mx)) == 0,
              "%s: clip bounds differ from the rest pose's", name);
    dirt_camera a, b;
    memset(&a, 0xAB, sizeof(a));
    memset(&b, 0xCD, sizeof(b));
    dirt_camera_auto(f, &a);
    dirt_camera_auto_bounds(mn, mx, &b);
    CHECK_MSG(memcmp(&a, &b, sizeof(a)) == 0, "%s: dirt_camera_auto != auto_bounds", name);
    CHECK(b.type == DIRT_CAMERA_PERSPECTIVE && b.aspect == 0.0f);
    dirt_frame_destroy(f);
}

/* One animated clip: the clip camera is the same for every frame, the union
 * contains every frame, the per-frame camera moves. Returns the number of
 * distinct per-frame cameras seen. */
static int check_clip(const dirt_scene *s, const char *name, dirt_eval_opts o)
{
    float mn[3], mx[3];
    CHECK(dirt_scene_clip_bounds(s, &o, mn, mx));
    double diag = sqrt((double)(mx[0] - mn[0]) * (mx[0] - mn[0]) +
                       (double)(mx[1] - mn[1]) * (mx[1] - mn[1]) +
                       (double)(mx[2] - mn[2]) * (mx[2] - mn[2]));
    CHECK(diag > 0.0);
    float d = 0.0f;
    if (o.all_clips) {
        for (size_t c = 0; c < dirt_scene_num_clips(s); c++)
            d = fmaxf(d, dirt_scene_clip_duration(s, (size_t)c));
    } else {
        d = dirt_scene_clip_duration(s, (size_t)o.clip);
    }
    CHECK(d > 0.0f);

    dirt_camera clip_cam;
    dirt_camera_auto_bounds(mn, mx, &clip_cam);
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, &o);
    CHECK(f != NULL);
    if (!f)
        return 0;
    dirt_camera first_auto;
    dirt_camera_auto(f, &first_auto);
    int distinct = 1;
    double worst = 0.0;
    enum { FRAMES = 10 };
    for (int k = 0; k < FRAMES; k++) {
        /* 10 frame times over the clip (first and last included, the rest
         * off the uniform sampling grid), the way a sequence renders it. */
        float t = d * (float)k / (float)(FRAMES - 1);
        if (k > 0 && k < FRAMES - 1)
            t += 0.37f * d / 1000.0f;
        CHECK(dirt_scene_evaluate_into(s, t, &o, f));

        /* What a renderer does for this frame: the clip camera again. */
        float fmn[3], fmx[3];
        CHECK(dirt_scene_clip_bounds(s, &o, fmn, fmx));
        dirt_camera c;
        memset(&c, k, sizeof(c));
        dirt_camera_auto_bounds(fmn, fmx, &c);
        CHECK_MSG(memcmp(&c, &clip_cam, sizeof(c)) == 0,
                  "%s: clip camera differs at t = %g", name, (double)t);

        /* The union holds the frame (exactly at the ends, which are sample
         * times; within a tiny fraction of the size between samples). */
        double over = overshoot(f, mn, mx);
        worst = fmax(worst, over);
        if (k == 0 || k == FRAMES - 1)
            CHECK_MSG(over <= 0.0, "%s: t = %g sticks out by %g", name, (double)t, over);
        else
            CHECK_MSG(over <= 1e-3 * diag, "%s: t = %g sticks out by %g (size %g)", name,
                      (double)t, over, diag);

        dirt_camera per_frame;
        dirt_camera_auto(f, &per_frame);
        if (memcmp(&per_frame, &first_auto, sizeof(per_frame)) != 0)
            distinct++;
    }
    fprintf(stderr, "%s clip %d%s: duration %g s, size %g, worst overshoot %g, %d/%d "
                    "per-frame cameras differ from the first\n",
            name, o.clip, o.all_clips ? " (all)" : "", (double)d, diag, worst, distinct - 1,
            FRAMES - 1);
    dirt_frame_destroy(f);
    return distinct;
}

static dirt_scene *load_shared(const char *shared, const char *rel, bool *missing)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/%s", shared, rel);
    FILE *probe = fopen(path, "rb");
    if (!probe) {
        fprintf(stderr, "%s: missing\n", path);
        *missing = true;
        return NULL;
    }
    fclose(probe);
    dirt_scene *s = dirt_scene_load(path, NULL);
    CHECK_MSG(s != NULL, "cannot load %s", path);
    return s;
}

int main(void)
{
    /* Arguments. */
    float mn[3], mx[3];
    CHECK(!dirt_scene_clip_bounds(NULL, NULL, mn, mx)); /* logs an error */

    /* The default scene has no animation. */
    dirt_scene *def = dirt_scene_create_default();
    CHECK(def != NULL);
    if (def) {
        check_static(def, "default");
        dirt_scene_destroy(def);
    }

    /* A box without extent frames a unit sphere around its centre. */
    static const float p[3] = {1.0f, 2.0f, 3.0f};
    dirt_camera c;
    dirt_camera_auto_bounds(p, p, &c);
    CHECK(c.forward[2] < 0.0f && c.eye[2] > p[2]);
    CHECK_NEAR(sqrt(pow(c.eye[0] - p[0], 2) + pow(c.eye[1] - p[1], 2) +
                    pow(c.eye[2] - p[2], 2)),
               1.0 / sin(0.5 * 0.785398163), 1e-5);

    const char *shared = test_shared_dir();
    if (!shared) {
        if (in_ci()) {
            CHECK_MSG(shared != NULL, "CI=true but no shared assets (DIRT_SHARED_DIR)");
            return check_finish();
        }
        fprintf(stderr, "no shared assets (DIRT_SHARED_DIR); animated part skipped\n");
        return check_failures_ ? check_finish() : TEST_SKIP;
    }
    bool missing = false;

    dirt_scene *box = load_shared(shared, "gltf/BoxAnimated/BoxAnimated.gltf", &missing);
    if (box) {
        CHECK(dirt_scene_num_clips(box) >= 1);
        CHECK(check_clip(box, "BoxAnimated", (dirt_eval_opts){.clip = 0}) > 1);
        CHECK(check_clip(box, "BoxAnimated", (dirt_eval_opts){.clip = 0, .loop = true}) > 1);
        dirt_scene_destroy(box);
    }

    dirt_scene *fox = load_shared(shared, "gltf/Fox/Fox.glb", &missing);
    if (fox) {
        CHECK(dirt_scene_num_clips(fox) == 3);
        for (size_t k = 0; k < dirt_scene_num_clips(fox); k++)
            CHECK(check_clip(fox, "Fox", (dirt_eval_opts){.clip = (int)k}) > 1);
        CHECK(check_clip(fox, "Fox", (dirt_eval_opts){.all_clips = true}) > 1);
        /* Clip -1 is the rest pose. */
        check_static(fox, "Fox");
        dirt_scene_destroy(fox);
    }

    if (missing) {
        if (in_ci()) {
            CHECK_MSG(!missing, "CI=true but a shared scene is missing");
            return check_finish();
        }
        fprintf(stderr, "a shared scene is missing; skipped\n");
        return check_failures_ ? check_finish() : TEST_SKIP;
    }
    return check_finish();
}
