/* dirt-view's window input (view.h): the mouse and keys as the user gives
 * them (and the script's held keys), scenes dropped on the window, and a
 * double click's focus. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "app/cli.h"
#include "app/view.h"
#include "app/setup.h"
#include "app/view_camera.h"

static bool key_held(const viewer *v, const dirt_window_input *in, enum dirt_key k)
{
    return in->key[k] || v->held[k] > 0;
}


/* The mouse (off the panels) moves the free camera and double clicks
 * focus; keys (when no panel has the keyboard) fly and toggle. */
void view_handle_input(viewer *v, const dirt_window_input *in, double dt, bool ui_mouse,
                       bool ui_keys)
{
    if (!ui_mouse) {
        /* Drags: the cursor's motion while the button was down since the
         * last poll, however short the drag or slow the frame. */
        double ldx = in->drag_dx[DIRT_MOUSE_LEFT], ldy = in->drag_dy[DIRT_MOUSE_LEFT];
        if (ldx != 0 || ldy != 0) {
            view_to_look(v);
            vcam_orbit(&v->look, (float)ldx * 0.3f, (float)ldy * 0.3f);
            v->cam_dirty = v->moving = true;
        }
        double pdx = in->drag_dx[DIRT_MOUSE_RIGHT] + in->drag_dx[DIRT_MOUSE_MIDDLE];
        double pdy = in->drag_dy[DIRT_MOUSE_RIGHT] + in->drag_dy[DIRT_MOUSE_MIDDLE];
        if ((pdx != 0 || pdy != 0) && in->height > 0) {
            view_to_look(v);
            vcam_pan(&v->look, (float)(pdx / in->height), (float)(-pdy / in->height));
            v->cam_dirty = v->moving = true;
        }
        if (in->scroll != 0) {
            view_to_look(v);
            vcam_dolly(&v->look, powf(0.85f, (float)in->scroll));
            v->cam_dirty = v->moving = true;
        }
        /* Ctrl + wheel zooms the image about the cursor, Ctrl + left drag
         * pans it (the camera stays). */
        if (in->ctrl_scroll != 0)
            view_zoom_steps(v, in->ctrl_scroll, in->ctrl_scroll_x, in->ctrl_scroll_y);
        if (in->ctrl_drag_dx != 0 || in->ctrl_drag_dy != 0)
            view_pan_image(v, in->ctrl_drag_dx, in->ctrl_drag_dy);
        if (in->double_clicks > 0) {
            v->click_pending = true;
            v->click_x = in->mouse_x;
            v->click_y = in->mouse_y;
        }
    }
    if (ui_keys)
        return;
    float speed = 0.25f * v->diag * (float)dt * (key_held(v, in, DIRT_KEY_SHIFT) ? 5.0f : 1.0f);
    float fw = 0, rt = 0, up = 0;
    fw += key_held(v, in, DIRT_KEY_W) ? speed : 0;
    fw -= key_held(v, in, DIRT_KEY_S) ? speed : 0;
    rt += key_held(v, in, DIRT_KEY_D) ? speed : 0;
    rt -= key_held(v, in, DIRT_KEY_A) ? speed : 0;
    up += key_held(v, in, DIRT_KEY_E) ? speed : 0;
    up -= key_held(v, in, DIRT_KEY_Q) ? speed : 0;
    if (fw != 0 || rt != 0 || up != 0) {
        view_to_look(v);
        vcam_fly(&v->look, fw, rt, up);
        v->cam_dirty = v->moving = true;
    }
    bool p[DIRT_NUM_KEYS];
    unsigned char mods[DIRT_NUM_KEYS];
    for (int k = 0; k < DIRT_NUM_KEYS; k++) {
        p[k] = in->key_pressed[k] || v->pressed[k];
        mods[k] = (unsigned char)((in->key_pressed[k] ? in->key_mods[k] : 0) |
                                  (v->pressed[k] ? v->pressed_mods[k] : 0));
    }
    if (p[DIRT_KEY_ESCAPE])
        v->quit = true;
    if (p[DIRT_KEY_F1])
        v->show_help = !v->show_help;
    if (p[DIRT_KEY_H])
        v->o.no_ui = !v->o.no_ui;
    if (p[DIRT_KEY_F5])
        view_reload_shaders(v);
    if (p[DIRT_KEY_R]) {
        view_reset_camera(v);
        view_status(v, "camera reset");
    }
    if (p[DIRT_KEY_C])
        view_cycle_camera(v);
    /* 1 .. 9: the buffer; Ctrl + N saves bookmark N, Shift + N goes to it. */
    for (int k = 0; k < 9; k++) {
        if (!p[DIRT_KEY_1 + k])
            continue;
        unsigned char m = mods[DIRT_KEY_1 + k];
        if (m & DIRT_MOD_CTRL)
            view_bookmark_save(v, k + 1);
        else if (m & DIRT_MOD_SHIFT)
            view_bookmark_go(v, k + 1);
        else if (!m)
            v->o.buffer = k;
    }
    if (p[DIRT_KEY_TAB])
        v->o.s.engine = (enum dirt_engine)((v->o.s.engine + 1) % DIRT_NUM_ENGINES);
    if (p[DIRT_KEY_V] && v->ref)
        v->ref_on = !v->ref_on;
    else if (p[DIRT_KEY_V])
        v->o.compare = v->o.compare ? 0 : (v->o.s.engine == DIRT_ENGINE_MMRT ? 1 : 2);
    if (p[DIRT_KEY_X])
        v->o.diff = !v->o.diff;
    if (p[DIRT_KEY_Z]) {
        /* 1:1 about the cursor (the window's centre when it is outside), or
         * back to fitted. */
        bool inside = in->mouse_x >= 0 && in->mouse_y >= 0 && in->mouse_x < in->width &&
                      in->mouse_y < in->height;
        view_zoom_at(v, v->zoom > 0 ? 0 : 1, inside ? in->mouse_x : in->width / 2.0,
                     inside ? in->mouse_y : in->height / 2.0);
    }
    if (p[DIRT_KEY_SPACE])
        v->o.play = !v->o.play;
    if (p[DIRT_KEY_RIGHT] || p[DIRT_KEY_LEFT]) {
        v->o.play = false;
        v->o.time += p[DIRT_KEY_RIGHT] ? 1.0 / 24 : -1.0 / 24;
    }
    if (p[DIRT_KEY_MINUS])
        v->o.exposure -= 1;
    if (p[DIRT_KEY_EQUAL])
        v->o.exposure += 1;
    if (p[DIRT_KEY_P] || p[DIRT_KEY_O]) {
        char path[64];
        view_shot_name(v, p[DIRT_KEY_P] ? "png" : "exr", path, sizeof(path));
        if (p[DIRT_KEY_O])
            view_save_render(v, path);
        else
            view_screenshot(v, path); /* taken after the frame is drawn: see the loop */
    }
}

enum dirt_key view_key_parse(const char *name, unsigned char *mods)
{
    static const struct { const char *prefix; unsigned char bit; } pre[] = {
        {"ctrl+", DIRT_MOD_CTRL}, {"shift+", DIRT_MOD_SHIFT}, {"alt+", DIRT_MOD_ALT}};
    *mods = 0;
    for (bool more = true; more;) {
        more = false;
        for (size_t i = 0; i < sizeof(pre) / sizeof(pre[0]); i++) {
            size_t n = strlen(pre[i].prefix);
            if (!strncasecmp(name, pre[i].prefix, n) && name[n]) {
                *mods |= pre[i].bit;
                name += n;
                more = true;
            }
        }
    }
    return dirt_key_from_name(name);
}

/* Focus on the surface under the cursor: the Z AOV at that pixel. */
void view_focus_at(viewer *v)
{
    v->click_pending = false;
    if (dirt_session_samples(v->s) == 0 || v->win_w <= 0)
        return;
    int r[4];
    view_fit(v, v->rw, v->rh, r);
    int x = (int)floor((v->click_x - r[0]) * v->rw / r[2]);
    int y = (int)floor((v->click_y - r[1]) * v->rh / r[3]);
    const dirt_image *img = dirt_session_image(v->s);
    const float *z = img ? dirt_image_find_channel(img, "Z") : NULL;
    if (!z || x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    float d = z[(size_t)y * img->width + x];
    if (!isfinite(d) || !(d > 0)) {
        view_status(v, "nothing under the cursor to focus on");
        return;
    }
    v->o.s.focus = d;
    if (!(v->o.s.aperture > 0))
        v->o.s.aperture = 0.01f * v->diag;
    view_status(v, "focus %.4g (aperture %.4g)", d, v->o.s.aperture);
}

/* Opens the scene last dropped on the window (with --max-scene-memory,
 * --strict and --allow-outside-paths);
 * a scene that does not load, or one that this run's outputs would
 * overwrite a file of (view_check_io), leaves the shown one. False when the sessions
 * for the new one cannot be made. */
bool view_open_drops(viewer *v, const dirt_window_input *in)
{
    if (in->num_drops <= 0)
        return true;
    char keep[4096];
    snprintf(keep, sizeof(keep), "%s", in->drops[in->num_drops - 1]);
    dirt_load_opts lo = app_load_opts(&v->o);
    dirt_scene *sc = dirt_scene_load(keep, &lo);
    if (!sc) {
        view_status(v, "could not open '%s' (see the log); kept the scene", keep);
        return true;
    }
    if (view_check_io(v, keep, sc) != DIRT_EXIT_OK) {
        dirt_scene_destroy(sc);
        view_status(v, "did not open '%s': this run writes one of its files (see the log); "
                       "kept the scene", keep);
        return true;
    }
    if (!view_load_scene(v, sc, keep))
        return false;
    view_status(v, "opened %s", keep);
    return true;
}
