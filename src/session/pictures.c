/* Pictures of the session's structure (dirt_session_picture): the DIRT
 * structure's tiles or the MMRT A-buffer's pixels, every view laid out in
 * one image; the DIRT structure's per-view pictures and figures
 * (dirt_session_write_debug_ads). Contracts in dirt/session.h. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "dirt/log.h"
#include "dirt/ads.h"
#include "dirt/session.h"
#include "session/engine.h"
#include "session/session_internal.h"

/* Where each view goes: the cube faces unfolded as a cross (+Y above,
 * -X +Z +X -Z across, -Y below, in face-size cells), the camera view to
 * the right of the cross. */
static void place(const dirt_view_set *set, int *x, int *y, int *w, int *h)
{
    static const int cell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
    int face = 0;
    for (int i = 0; i < set->count; i++)
        if (set->views[i].face >= 0 && set->views[i].tiles_x > face)
            face = set->views[i].tiles_x;
    int cross_w = face ? 4 * face : 0, cross_h = face ? 3 * face : 0;
    *w = cross_w;
    *h = cross_h;
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        if (v->face >= 0) {
            x[i] = cell[v->face][0] * face;
            y[i] = cell[v->face][1] * face;
        } else {
            x[i] = cross_w + (cross_w ? face / 4 : 0);
            y[i] = 0;
            *w = x[i] + v->tiles_x;
            if (v->tiles_y > *h)
                *h = v->tiles_y;
        }
    }
}

dirt_image *dirt_session_picture(dirt_session *s, enum dirt_session_picture what, float *max)
{
    session_begin();
    const engine_ops *ops = NULL;
    engine_env env;
    engine *e = session_built_engine(s, &ops, &env);
    if (max)
        *max = 0;
    if (!e || !ops->cells) {
        /* An engine with pictures that is not built yet is not ready; one
         * without has none. */
        enum dirt_engine id = dirt_session_get_opts(s)->engine;
        DIRT_ERROR("structure picture: the session has no DIRT structure or MMRT A-buffer "
                   "(engine %s, or not built)", dirt_engine_names[id]);
        session_fail(session_engines[id]->cells ? DIRT_SESSION_ERR_NOT_READY
                                                : DIRT_SESSION_ERR_UNSUPPORTED);
        return NULL;
    }
    engine_cells c = {0};
    dirt_image *img = NULL;
    if (!ops->cells(e, &c))
        goto error;
    const dirt_view_set *set = c.set;
    int x[DIRT_MAX_VIEWS], y[DIRT_MAX_VIEWS], w, h;
    place(set, x, y, &w, &h);
    img = dirt_image_create(w, h);
    if (!img)
        goto error;
    memset(img->rgba, 0, (size_t)w * h * 4 * sizeof(float));
    float top = 0;
    for (int vi = 0; vi < set->count; vi++) {
        const dirt_view *v = &set->views[vi];
        for (int ty = 0; ty < v->tiles_y; ty++) {
            for (int tx = 0; tx < v->tiles_x; tx++) {
                int t = v->tile_base + ty * v->tiles_x + tx;
                if (t < 0 || t >= c.count)
                    continue;
                /* Cell rows are bottom-up; image rows top-down. */
                float *px = img->rgba + ((size_t)(y[vi] + v->tiles_y - 1 - ty) * w + x[vi] + tx) * 4;
                float val;
                if (what == DIRT_PICTURE_LISTS) {
                    val = (float)c.len[t];
                } else if (what == DIRT_PICTURE_BUCKETS) {
                    val = (float)c.used[t];
                } else if (c.depth[t][0] > c.depth[t][1]) {
                    val = NAN; /* empty */
                } else {
                    float z = c.depth[t][what == DIRT_PICTURE_ZMIN ? 0 : 1];
                    val = (z - v->znear) / (v->zfar - v->znear);
                }
                px[0] = val;
                px[3] = 1;
                if (val > top)
                    top = val;
            }
        }
    }
    if (max)
        *max = what == DIRT_PICTURE_BUCKETS ? (float)c.buckets
               : what == DIRT_PICTURE_LISTS ? top : 1.0f;
    engine_cells_free(&c);
    return img;
error:
    engine_cells_free(&c);
    dirt_image_destroy(img);
    session_fail(DIRT_SESSION_ERR_RENDER);
    return NULL;
}

bool dirt_session_write_debug_ads(dirt_session *s, const char *dir, bool quiet)
{
    session_begin();
    if (!dir) {
        DIRT_ERROR("debug pictures: no directory");
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    if (!session_engines[dirt_session_get_opts(s)->engine]->ads) {
        DIRT_ERROR("debug pictures of the DIRT structure: the session's engine is %s",
                   dirt_engine_names[dirt_session_get_opts(s)->engine]);
        return session_fail(DIRT_SESSION_ERR_UNSUPPORTED);
    }
    dirt_ads *ads = dirt_session_ads(s);
    if (!ads && !dirt_session_build(s))
        return session_fail(DIRT_SESSION_ERR_RENDER);
    ads = dirt_session_ads(s);
    if (!quiet)
        dirt_ads_print_stats(ads, stderr);
    return dirt_ads_write_debug(ads, dir, quiet) || session_fail(DIRT_SESSION_ERR_IO);
}
