/* dirt-view's split view (view.h): a second session of another engine on
 * the same camera, time and settings (--compare, V), a slice per frame,
 * or a reference image from disk (--compare-image), shown beside the main
 * one (--split) or as a heat map of the difference (--diff, X). */
#include <string.h>

#include "app/cli.h"
#include "dirt/input.h"
#include "app/view.h"

bool view_load_reference(viewer *v)
{
    app_opts *o = &v->o;
    if (!o->compare_image)
        return true;
    enum dirt_input_error err = DIRT_INPUT_ERR_OK;
    v->ref = dirt_image_read(o->compare_image, NULL, &err);
    if (!v->ref) {
        cli_error(PROG, "--compare-image: %s: cannot read '%s': %s (see the error above)",
                  dirt_input_error_name(err), o->compare_image, dirt_input_error_str(err));
        return false;
    }
    int w = v->ref->width, h = v->ref->height;
    if ((o->s.width && o->s.width != w) || (o->s.height && o->s.height != h)) {
        cli_error(PROG, "--compare-image: '%s' is %dx%d, the render -W %d -H %d: they must be "
                  "the same size (leave out -W/-H and the render takes the image's)",
                  o->compare_image, w, h, o->s.width, o->s.height);
        return false;
    }
    o->s.width = w;
    o->s.height = h;
    v->ref_on = true;
    return true;
}

bool view_ref_shown(const viewer *v)
{
    return v->ref && v->ref_on && v->ref_tex && v->ref->width == v->rw &&
           v->ref->height == v->rh;
}

bool view_comparing(const viewer *v)
{
    if (dirt_session_samples(v->s) == 0)
        return false;
    return view_ref_shown(v) || (v->cmp && dirt_session_samples(v->cmp) > 0);
}

const char *view_compare_name(const viewer *v)
{
    if (view_ref_shown(v))
        return "reference";
    return v->cmp ? dirt_engine_names[v->cmp_engine] : "none";
}

/* Makes, remakes or drops the comparison session as o.compare asks, and
 * keeps its options those of the main session. False after setting the
 * status (the split view is then off). */
bool view_sync_compare(viewer *v)
{
    if (v->ref && !v->ref_tex) {
        v->ref_tex = dirt_gpu_texture_upload(v->gpu, 0, v->ref->width, v->ref->height,
                                             v->ref->rgba);
        if (!v->ref_tex) {
            view_status(v, "the reference image could not be uploaded (see the log); off");
            dirt_image_destroy(v->ref);
            v->ref = NULL;
        }
    }
    bool mismatch = v->ref && (v->ref->width != v->rw || v->ref->height != v->rh);
    if (mismatch && !v->ref_mismatch)
        view_status(v, "the reference is %dx%d, the render %dx%d: not compared",
                    v->ref->width, v->ref->height, v->rw, v->rh);
    v->ref_mismatch = mismatch;
    /* The reference takes the comparison engine's place while it is on. */
    int want_cmp = v->ref && v->ref_on ? -1 : v->o.compare - 1;
    if (want_cmp != v->cmp_engine) {
        dirt_session_destroy(v->cmp);
        v->cmp = NULL;
        v->cmp_engine = -1;
        if (want_cmp >= 0) {
            dirt_session_opts co = view_wanted_opts(v, want_cmp);
            /* Every engine gets the GPU: Embree's image is uploaded for display. */
            v->cmp = dirt_session_create(v->gpu, v->scene, &co);
            dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
            if (!v->cmp || !dirt_session_set_time(v->cmp, v->o.time, &eval) ||
                !view_apply_camera(v, v->cmp)) {
                dirt_session_destroy(v->cmp);
                v->cmp = NULL;
                v->o.compare = 0;
                view_status(v, "the comparison engine could not be made (see the log)");
                return false;
            }
            v->cmp_engine = want_cmp;
        }
        v->generation++;
    } else if (v->cmp) {
        dirt_session_opts co = view_wanted_opts(v, want_cmp);
        if (memcmp(&co, dirt_session_get_opts(v->cmp), sizeof(co)) != 0)
            dirt_session_set_opts(v->cmp, &co, NULL);
    }
    return true;
}

/* A slice of the comparison's next sample (--slice-ms, as the main
 * session's) up to the target (--spp); a failure turns the split view
 * off. */
void view_sample_compare(viewer *v)
{
    if (!v->cmp)
        return;
    int hc = dirt_session_samples(v->cmp), target = view_target(v, v->cmp);
    bool done = false;
    if (target != 0 && hc >= target)
        return;
    if (!dirt_session_advance(v->cmp, v->o.slice_ms, &done)) {
        view_status(v, "the comparison engine failed (see the log); split view off");
        v->o.compare = 0;
    } else if (done) {
        v->generation++;
    }
}

/* The comparison's half of a beauty presentation: the split or the
 * difference heat map, once the comparison has samples. */
void view_present_split(const viewer *v, dirt_present_opts *p)
{
    if (!view_comparing(v))
        return;
    p->texture_b = view_ref_shown(v) ? v->ref_tex : dirt_session_display_texture(v->cmp);
    if (v->o.diff) {
        p->mode = DIRT_PRESENT_DIFF;
        p->lo = 0;
        p->hi = v->o.diff_range;
    } else {
        p->split = v->o.split > 0 && v->o.split < 1 ? v->o.split : 0.5f;
        p->split_line = true;
    }
}
