/* dirt-view's split view (view.h): a second session of another engine on
 * the same camera, time and settings (--compare, V), a slice per frame,
 * shown beside the main one (--split) or as a heat map of the difference
 * (--diff, X). */
#include <string.h>

#include "app/view.h"

/* Makes, remakes or drops the comparison session as o.compare asks, and
 * keeps its options those of the main session. False after setting the
 * status (the split view is then off). */
bool view_sync_compare(viewer *v)
{
    int want_cmp = v->o.compare - 1;
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
    if (!v->cmp || dirt_session_samples(v->cmp) == 0)
        return;
    p->texture_b = dirt_session_display_texture(v->cmp);
    if (v->o.diff) {
        p->mode = DIRT_PRESENT_DIFF;
        p->lo = 0;
        p->hi = v->o.diff_range;
    } else {
        p->split = v->o.split > 0 && v->o.split < 1 ? v->o.split : 0.5f;
        p->split_line = true;
    }
}
