/* Pictures of the session's structure (dirt_session_picture): the DIRT
 * structure's tiles or the MMRT A-buffer's pixels, every view laid out in
 * one image; the DIRT structure's per-view pictures and figures
 * (dirt_session_write_debug_ads). Contracts in dirt/session.h. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/ads.h"
#include "dirt/log.h"
#include "mmrt/mmrt.h"
#include "dirt/session.h"
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

/* Per-cell figures of a structure: list lengths summed over the buckets,
 * non-empty buckets, and the level-0 depth bounds. */
typedef struct cells {
    int count, buckets;
    uint32_t *len, *used;
    float (*depth)[2];
} cells;

static bool from_ads(dirt_ads *ads, cells *c)
{
    dirt_ads_data d;
    if (!dirt_ads_read(ads, &d))
        return false;
    c->count = d.num_tiles;
    c->buckets = d.buckets;
    c->len = calloc((size_t)d.num_tiles + 1, sizeof(uint32_t));
    c->used = calloc((size_t)d.num_tiles + 1, sizeof(uint32_t));
    c->depth = malloc(((size_t)d.num_tiles + 1) * sizeof(*c->depth));
    bool ok = c->len && c->used && c->depth;
    for (int b = 0; ok && b < d.buckets; b++) {
        for (int t = 0; t < d.num_tiles; t++) {
            uint32_t steps = 0;
            for (uint32_t n = d.heads[(size_t)b * d.num_tiles + t];
                 n != DIRT_LIST_END && n < d.num_nodes && steps <= d.num_nodes; n = d.nodes[n][1])
                steps++;
            c->len[t] += steps;
            c->used[t] += steps > 0;
        }
    }
    if (ok)
        memcpy(c->depth, d.depth, (size_t)d.num_tiles * sizeof(*c->depth));
    dirt_ads_data_free(&d);
    return ok;
}

static bool from_mmrt(dirt_mmrt *m, cells *c)
{
    dirt_mmrt_data d;
    if (!dirt_mmrt_read(m, &d))
        return false;
    c->count = d.num_pixels;
    c->buckets = d.buckets;
    c->len = calloc((size_t)d.num_pixels + 1, sizeof(uint32_t));
    c->used = calloc((size_t)d.num_pixels + 1, sizeof(uint32_t));
    c->depth = malloc(((size_t)d.num_pixels + 1) * sizeof(*c->depth));
    bool ok = c->len && c->used && c->depth;
    for (int b = 0; ok && b < d.buckets; b++) {
        for (int p = 0; p < d.num_pixels; p++) {
            uint32_t steps = 0;
            for (uint32_t n = d.heads[(size_t)b * d.num_pixels + p];
                 n != DIRT_MMRT_END && n < d.num_nodes && steps <= d.num_nodes; n = d.ids[n].next)
                steps++;
            c->len[p] += steps;
            c->used[p] += steps > 0;
        }
    }
    if (ok)
        memcpy(c->depth, d.depth, (size_t)d.num_pixels * sizeof(*c->depth));
    dirt_mmrt_data_free(&d);
    return ok;
}

dirt_image *dirt_session_picture(dirt_session *s, enum dirt_session_picture what, float *max)
{
    session_begin();
    dirt_ads *ads = dirt_session_ads(s);
    dirt_mmrt *mmrt = dirt_session_mmrt(s);
    if (max)
        *max = 0;
    if (!ads && !mmrt) {
        enum dirt_engine e = dirt_session_get_opts(s)->engine;
        DIRT_ERROR("structure picture: the session has no DIRT structure or MMRT A-buffer "
                   "(engine %s, or not built)", dirt_engine_names[e]);
        session_fail(e == DIRT_ENGINE_DIRT || e == DIRT_ENGINE_MMRT ? DIRT_SESSION_ERR_NOT_READY
                                                                    : DIRT_SESSION_ERR_UNSUPPORTED);
        return NULL;
    }
    const dirt_view_set *set = ads ? dirt_ads_views(ads) : dirt_mmrt_views(mmrt);
    cells c = {0};
    dirt_image *img = NULL;
    if (!(ads ? from_ads(ads, &c) : from_mmrt(mmrt, &c)))
        goto error;
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
    free(c.len);
    free(c.used);
    free(c.depth);
    return img;
error:
    free(c.len);
    free(c.used);
    free(c.depth);
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
    if (dirt_session_get_opts(s)->engine != DIRT_ENGINE_DIRT) {
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
