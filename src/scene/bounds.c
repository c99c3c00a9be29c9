/* DIRT engine: bounds of a scene over a whole animation clip, for a camera
 * that frames every frame of a sequence the same way. */
#include "scene/scene_internal.h"

#include "dirt/log.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Uniform samples per second of clip, and the bounds on their number. */
#define CLIP_SAMPLES_PER_SECOND 120.0f
#define CLIP_MIN_SAMPLES 64
#define CLIP_MAX_SAMPLES 2048

static void grow(float mn[3], float mx[3], const dirt_frame *f)
{
    if (f->num_triangles == 0)
        return;
    for (int k = 0; k < 3; k++) {
        if (f->bounds_min[k] < mn[k])
            mn[k] = f->bounds_min[k];
        if (f->bounds_max[k] > mx[k])
            mx[k] = f->bounds_max[k];
    }
}

static bool eval_grow(const dirt_scene *s, float t, const dirt_eval_opts *o, dirt_frame *f,
                      float mn[3], float mx[3])
{
    if (!dirt_scene_evaluate_into(s, t, o, f))
        return false;
    grow(mn, mx, f);
    return true;
}

/* Every key time of `clip` (in [0, its duration]) is evaluated. */
static bool eval_keys(const dirt_scene *s, const scene_clip *clip, const dirt_eval_opts *o,
                      dirt_frame *f, float mn[3], float mx[3])
{
    for (size_t c = 0; c < clip->num_samplers; c++) {
        const scene_sampler *smp = &clip->samplers[c];
        for (size_t k = 0; k < smp->num_keys; k++) {
            if (!eval_grow(s, smp->times[k], o, f, mn, mx))
                return false;
        }
    }
    return true;
}

bool dirt_scene_clip_bounds(const dirt_scene *s, const dirt_eval_opts *opts, float min[3],
                            float max[3])
{
    static const dirt_eval_opts defaults = {0};
    if (!s || !min || !max) {
        DIRT_ERROR("dirt_scene_clip_bounds: no scene or no output");
        return false;
    }
    if (!opts)
        opts = &defaults;
    bool all = opts->all_clips && s->num_clips > 0;
    bool one = !all && opts->clip >= 0 && (size_t)opts->clip < s->num_clips;
    float duration = 0.0f;
    if (all) {
        for (size_t c = 0; c < s->num_clips; c++)
            duration = fmaxf(duration, s->clips[c].duration);
    } else if (one) {
        duration = s->clips[opts->clip].duration;
    }

    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, opts);
    if (!f)
        return false; /* logged */
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    grow(mn, mx, f);
    bool ok = true;
    if (all || one) {
        /* Key times first: the poses the animation passes through exactly. */
        for (size_t c = 0; c < s->num_clips && ok; c++) {
            if (all || (size_t)opts->clip == c)
                ok = eval_keys(s, &s->clips[c], opts, f, mn, mx);
        }
        /* Then the motion between keys, uniformly, ending on the duration. */
        float want = ceilf(duration * CLIP_SAMPLES_PER_SECOND);
        size_t n = want < (float)CLIP_MIN_SAMPLES   ? CLIP_MIN_SAMPLES
                   : want > (float)CLIP_MAX_SAMPLES ? CLIP_MAX_SAMPLES
                                                    : (size_t)want;
        for (size_t i = 1; i <= n && ok && duration > 0.0f; i++)
            ok = eval_grow(s, duration * ((float)i / (float)n), opts, f, mn, mx);
    }
    dirt_frame_destroy(f);
    if (!ok)
        return false;
    if (!(mn[0] <= mx[0])) { /* no triangles at any time */
        memset(mn, 0, sizeof(mn));
        memset(mx, 0, sizeof(mx));
    }
    memcpy(min, mn, sizeof(mn));
    memcpy(max, mx, sizeof(mx));
    return true;
}
