/* What dirt-view's window shows (view.h): the render fitted into the
 * window, the raster preview while the camera moves, and the buffers:
 * AOVs and the structure's pictures as heat maps. */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "app/view.h"

/* A colour per primitive id (a hash), black for misses. */
static void id_colour(float id, float rgb[3])
{
    if (!(id >= 0)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    uint32_t h = (uint32_t)id * 2654435761u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    for (int k = 0; k < 3; k++)
        rgb[k] = 0.15f + 0.85f * (float)((h >> (8 * k)) & 255) / 255.0f;
}

/* Makes the texture of a non-beauty buffer (AOVs: from the image; the
 * structure's pictures: from the last build). False when there is none. */
static bool aux_texture(viewer *v)
{
    long key = v->generation * NUM_BUFFERS + v->o.buffer;
    if (key == v->aux_key)
        return v->aux_tex != 0;
    v->aux_key = key;
    dirt_image *pic = NULL;
    const dirt_image *img = NULL;
    float top = 1;
    int b = v->o.buffer;
    if (b >= BUF_LISTS) {
        pic = dirt_session_picture(v->s, (enum dirt_session_picture)(b - BUF_LISTS), &top);
        img = pic;
    } else {
        img = dirt_session_samples(v->s) > 0 ? dirt_session_image(v->s) : NULL;
    }
    if (!img)
        return false;
    size_t n = (size_t)img->width * img->height;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) {
        dirt_image_destroy(pic);
        return false;
    }
    const char *names[3] = {NULL, NULL, NULL};
    if (b == BUF_ALBEDO)
        names[0] = "albedo.R", names[1] = "albedo.G", names[2] = "albedo.B";
    else if (b == BUF_NORMAL)
        names[0] = "N.X", names[1] = "N.Y", names[2] = "N.Z";
    else if (b == BUF_DEPTH)
        names[0] = "Z";
    else if (b == BUF_ID)
        names[0] = "ID";
    const float *ch[3] = {0};
    for (int k = 0; k < 3; k++)
        ch[k] = names[k] ? dirt_image_find_channel(img, names[k]) : NULL;
    bool ok = b >= BUF_LISTS || ch[0];
    v->aux_lo = 0;
    v->aux_hi = top;
    if (b == BUF_DEPTH && ok) {
        float lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            if (isfinite(ch[0][i])) {
                lo = fminf(lo, ch[0][i]);
                hi = fmaxf(hi, ch[0][i]);
            }
        }
        v->aux_lo = isfinite(lo) ? lo : 0;
        v->aux_hi = hi > lo ? hi : v->aux_lo + 1;
    }
    for (size_t i = 0; ok && i < n; i++) {
        float *px = rgba + 4 * i;
        if (b >= BUF_LISTS) {
            memcpy(px, img->rgba + 4 * i, 4 * sizeof(float));
            if (!isfinite(px[0]))
                px[0] = -1; /* empty: below the ramp (black) */
        } else if (b == BUF_ID) {
            id_colour(ch[0][i], px);
            px[3] = 1;
        } else {
            for (int k = 0; k < 3; k++)
                px[k] = ch[k] ? ch[k][i] : (b == BUF_DEPTH && !isfinite(ch[0][i]) ? -1 : 0);
            if (b == BUF_DEPTH)
                px[0] = isfinite(ch[0][i]) ? ch[0][i] : v->aux_lo - 1;
            px[3] = 1;
        }
    }
    if (ok) {
        v->aux_tex = dirt_gpu_texture_upload(v->gpu, v->aux_tex, img->width, img->height, rgba);
        v->aux_w = img->width;
        v->aux_h = img->height;
    }
    free(rgba);
    dirt_image_destroy(pic);
    return ok && v->aux_tex;
}

/* The rectangle an image of w x h takes in the window: fitted (1:1 at the
 * top left when it follows the window, else fitted and centred), or with a
 * zoom, zoom window pixels per image pixel with the image point
 * (zoom_u, zoom_v) (fractions of the image) at the window's centre. */
void view_fit(const viewer *v, int w, int h, int r[4])
{
    if (v->zoom > 0) {
        r[2] = (int)lround(w * (double)v->zoom);
        r[3] = (int)lround(h * (double)v->zoom);
        r[2] = r[2] < 1 ? 1 : r[2];
        r[3] = r[3] < 1 ? 1 : r[3];
        r[0] = (int)lround(v->win_w / 2.0 - v->zoom_u * r[2]);
        r[1] = (int)lround(v->win_h / 2.0 - v->zoom_v * r[3]);
        return;
    }
    if (w == v->win_w && h == v->win_h) {
        r[0] = r[1] = 0, r[2] = w, r[3] = h;
        return;
    }
    double s = fmin((double)v->win_w / w, (double)v->win_h / h);
    r[2] = (int)(w * s);
    r[3] = (int)(h * s);
    if (r[2] < 1)
        r[2] = 1;
    if (r[3] < 1)
        r[3] = 1;
    r[0] = (v->win_w - r[2]) / 2;
    r[1] = (v->win_h - r[3]) / 2;
}

/* The size of the image shown: the render, or the buffer's picture. */
static void shown_size(const viewer *v, int *w, int *h)
{
    *w = v->rw, *h = v->rh;
    if (v->o.buffer != BUF_BEAUTY && v->aux_tex && v->aux_w > 0)
        *w = v->aux_w, *h = v->aux_h;
}

/* Zoom limits: 1/16 .. 64 window pixels per image pixel, and no wider than
 * a viewport may be. */
#define ZOOM_MIN 0.0625
#define ZOOM_MAX 64.0
#define ZOOM_MAX_PIXELS 16384.0

void view_zoom_at(viewer *v, double zoom, double wx, double wy)
{
    int w, h, r[4];
    shown_size(v, &w, &h);
    if (w <= 0 || h <= 0 || v->win_w <= 0 || v->win_h <= 0)
        return;
    if (!(zoom > 0)) {
        v->zoom = 0;
        view_status(v, "zoom: fitted");
        return;
    }
    double zmax = fmin(ZOOM_MAX, ZOOM_MAX_PIXELS / (w > h ? w : h));
    zoom = fmin(fmax(zoom, ZOOM_MIN), zmax);
    view_fit(v, w, h, r);
    /* The image point under (wx, wy) stays there. */
    double pu = (wx - r[0]) / r[2], pv = (wy - r[1]) / r[3];
    double left = wx - pu * w * zoom, top = wy - pv * h * zoom;
    v->zoom = (float)zoom;
    v->zoom_u = (v->win_w / 2.0 - left) / (w * zoom);
    v->zoom_v = (v->win_h / 2.0 - top) / (h * zoom);
    v->zoom_u = fmin(fmax(v->zoom_u, 0), 1);
    v->zoom_v = fmin(fmax(v->zoom_v, 0), 1);
    view_status(v, "zoom %g:1", zoom);
}

void view_zoom_steps(viewer *v, double steps, double wx, double wy)
{
    int w, h, r[4];
    shown_size(v, &w, &h);
    if (w <= 0 || steps == 0)
        return;
    view_fit(v, w, h, r);
    /* Powers of two; from a fit between two, the next one that way. */
    double l = log2((double)r[2] / w);
    double to = steps > 0 ? floor(l + 1e-9) + steps : ceil(l - 1e-9) + steps;
    view_zoom_at(v, exp2(to), wx, wy);
}

void view_pan_image(viewer *v, double dx, double dy)
{
    int w, h, r[4];
    shown_size(v, &w, &h);
    if (w <= 0 || (dx == 0 && dy == 0))
        return;
    if (!(v->zoom > 0)) {
        /* Panning a fitted image: the same scale, now movable. */
        view_fit(v, w, h, r);
        v->zoom = (float)r[2] / (float)w;
        v->zoom_u = (v->win_w / 2.0 - r[0]) / r[2];
        v->zoom_v = (v->win_h / 2.0 - r[1]) / r[3];
    }
    view_fit(v, w, h, r);
    v->zoom_u = fmin(fmax(v->zoom_u - dx / r[2], 0), 1);
    v->zoom_v = fmin(fmax(v->zoom_v - dy / r[3], 0), 1);
}

/* Draws the frame's image: the raster preview while the camera moves (or
 * before the first sample), the beauty with the split view, or a buffer
 * (AOV or structure picture) through the present shader's modes. */
void view_draw(viewer *v, bool preview)
{
    static const float grey[3] = {0.08f, 0.08f, 0.09f};
    dirt_gpu_window_clear(v->gpu, grey);
    bool have_pre = v->pre && dirt_session_samples(v->pre) > 0;
    if (v->o.buffer == BUF_BEAUTY && have_pre &&
        (preview || dirt_session_samples(v->s) == 0)) {
        int r[4];
        view_fit(v, v->rw, v->rh, r);
        dirt_present_opts p = {.texture = dirt_session_display_texture(v->pre), .x = r[0],
                               .y = r[1], .w = r[2], .h = r[3], .exposure = v->o.exposure,
                               .tonemap = (enum dirt_tonemap)v->o.tonemap};
        if (p.texture)
            dirt_gpu_present(v->gpu, &p);
        return;
    }
    if (dirt_session_samples(v->s) == 0)
        return;
    int r[4];
    dirt_present_opts p = {.exposure = v->o.exposure, .tonemap = v->o.tonemap};
    if (v->o.buffer == BUF_BEAUTY) {
        p.texture = dirt_session_display_texture(v->s);
        view_fit(v, v->rw, v->rh, r);
        view_present_split(v, &p);
    } else {
        if (!aux_texture(v))
            return;
        p.texture = v->aux_tex;
        view_fit(v, v->aux_w, v->aux_h, r);
        if (v->o.buffer == BUF_NORMAL) {
            p.mode = DIRT_PRESENT_SIGNED;
        } else if (v->o.buffer == BUF_DEPTH || v->o.buffer >= BUF_LISTS) {
            p.mode = DIRT_PRESENT_HEAT;
            p.lo = v->aux_lo;
            p.hi = v->aux_hi > v->aux_lo ? v->aux_hi : v->aux_lo + 1;
        } else {
            p.exposure = 0;
            p.tonemap = 0;
        }
    }
    p.x = r[0], p.y = r[1], p.w = r[2], p.h = r[3];
    if (p.texture)
        dirt_gpu_present(v->gpu, &p);
}

/* One image's channels at pixel (x, y); false off the image. */
static bool probe_image(const dirt_image *img, int x, int y, struct view_probe *pr)
{
    pr->valid = false;
    if (!img || x < 0 || y < 0 || x >= img->width || y >= img->height)
        return false;
    size_t i = (size_t)y * img->width + x;
    static const char *const rgba[4] = {"R", "G", "B", "A"};
    pr->count = 0;
    for (int k = 0; k < 4; k++) {
        snprintf(pr->names[pr->count], sizeof(pr->names[0]), "%s", rgba[k]);
        pr->values[pr->count++] = img->rgba[4 * i + k];
    }
    for (int c = 0; c < img->channel_count && pr->count < INSPECT_CHANNELS; c++) {
        snprintf(pr->names[pr->count], sizeof(pr->names[0]), "%s", img->channels[c].name);
        pr->values[pr->count++] = img->channels[c].data[i];
    }
    pr->x = x;
    pr->y = y;
    pr->valid = true;
    return true;
}

/* One session's channels at render pixel (x, y); false off the image or
 * before samples. */
static bool probe_session(dirt_session *s, int x, int y, struct view_probe *pr)
{
    pr->valid = false;
    if (!s || dirt_session_samples(s) == 0)
        return false;
    return probe_image(dirt_session_image(s), x, y, pr);
}

void view_inspect(viewer *v)
{
    v->probe[0].valid = v->probe[1].valid = false;
    if (v->win_w <= 0 || v->rw <= 0)
        return;
    int r[4];
    view_fit(v, v->rw, v->rh, r);
    int x = (int)floor((v->cursor_x - r[0]) * v->rw / r[2]);
    int y = (int)floor((v->cursor_y - r[1]) * v->rh / r[3]);
    if (x < 0 || y < 0 || x >= v->rw || y >= v->rh)
        return;
    probe_session(v->s, x, y, &v->probe[0]);
    if (view_ref_shown(v))
        probe_image(v->ref, x, y, &v->probe[1]);
    else
        probe_session(v->cmp, x, y, &v->probe[1]);
}
