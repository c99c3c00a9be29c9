/* dirt-view's panels (view.h): Settings (every knob of both techniques,
 * the camera, the display, the animation, files), Numbers (frame times,
 * passes, buffers) and the key bindings. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/view.h"
#include "app/view_camera.h"

static const char *const buffer_labels[NUM_BUFFERS] = {
    "beauty", "albedo", "normal", "depth (Z)", "primitive id (first hit)",
    "list length per tile / fragments per pixel", "bucket occupancy",
    "depth bounds: min", "depth bounds: max"};

static void note_panel(viewer *v)
{
    if (v->num_panels < 5)
        dirt_ui_panel_rect(v->panels[v->num_panels++]);
}

/* Below this window size the panels start collapsed to their title bars,
 * so the image stays visible (they open with a click). */
#define SMALL_W 800
#define SMALL_H 600

static bool small_window(const viewer *v)
{
    return v->win_w < SMALL_W || v->win_h < SMALL_H;
}

static void collapse_if_small(const viewer *v)
{
    if (small_window(v))
        dirt_ui_next_collapsed();
}

/* A panel's width: `w`, or in a small window at most 3/5 of it (so the
 * panels, each whole inside the window, leave the image visible). */
static float panel_width(const viewer *v, float w)
{
    float cap = small_window(v) ? floorf(0.6f * (float)v->win_w) : (float)v->win_w - 16;
    return w < cap ? w : cap > 120 ? cap : 120;
}

/* Right-hand panels: against the window's right edge, not left of Settings
 * in a large window. */
static float right_x(const viewer *v, float w)
{
    float x = (float)v->win_w - w - 8;
    if (!small_window(v) && x < 346)
        x = 346;
    return x > 8 ? x : 8;
}

/* Test hook DIRT_VIEW_OPEN_HEADERS=1: every section starts open (for a
 * look at every label). */
static bool header(const char *label, bool default_open)
{
    static int all = -1;
    if (all < 0) {
        const char *e = getenv("DIRT_VIEW_OPEN_HEADERS");
        all = e && *e == '1';
    }
    return dirt_ui_header(label, default_open || all);
}

static void panel_settings(viewer *v)
{
    app_opts *o = &v->o;
    collapse_if_small(v);
    if (dirt_ui_begin("Settings", NULL, 8, 8, panel_width(v, 330),
                      (float)(v->win_h - 16 > 200 ? v->win_h - 16 : 200))) {
        int samples = dirt_session_samples(v->s);
        dirt_ui_text("%s", v->scene_name);
        dirt_ui_text("%zu triangles, %d x %d", dirt_scene_num_triangles(v->scene), v->rw, v->rh);
        dirt_ui_text("%d / %d samples in %.1f s%s", samples, o->spp,
                     dirt_session_get_stats(v->s)->total_ms / 1000.0,
                     o->spp && samples >= o->spp ? " (done)" : "");
        double part = dirt_session_sample_part(v->s);
        if (part > 0)
            dirt_ui_text("sample %d: %.0f %% (%d ms a frame; the last took %.2f s)", samples + 1,
                         100.0 * part, o->slice_ms, v->last_sample_ms / 1000.0);
        if (v->scale_note[0])
            dirt_ui_text_disabled("%s", v->scale_note);
        if (v->status[0])
            dirt_ui_text_disabled("%s", v->status);
        if (header("Render", true)) {
            int eng = (int)o->s.engine;
            if (dirt_ui_combo("engine", &eng, app_engine_names, DIRT_NUM_ENGINES))
                o->s.engine = (enum dirt_engine)eng;
            if (v->ref)
                dirt_ui_checkbox("compare with the reference image (V)", &v->ref_on);
            if (!v->ref || !v->ref_on)
                dirt_ui_combo("compare with", &o->compare, app_compare_names, 5);
            if (o->compare || (v->ref && v->ref_on)) {
                dirt_ui_slider_float("split", &o->split, 0.0f, 1.0f, "%.2f", false);
                dirt_ui_checkbox("difference heat map", &o->diff);
                if (o->diff)
                    dirt_ui_slider_float("difference range", &o->diff_range, 1e-4f, 10.0f, "%.4f",
                                         true);
            }
            dirt_ui_slider_int("target spp (0 = no limit)", &o->spp, 0, 4096);
            dirt_ui_slider_int("samples per frame", &o->samples_per_frame, 1, 64);
            dirt_ui_slider_int("ms of tracing per frame", &o->slice_ms, 0, 1000);
            if (o->s.width <= 0)
                dirt_ui_slider_int("render scale (window / N)", &o->scale, 1, 16);
            int mode = (int)o->s.mode;
            if (dirt_ui_combo("mode", &mode, app_mode_names, 2))
                o->s.mode = (enum dirt_pt_mode)mode;
            int bounces = o->s.bounces ? o->s.bounces : 4;
            if (dirt_ui_slider_int("bounces", &bounces, 1, 16))
                o->s.bounces = bounces;
            if (o->s.mode == DIRT_PT_AO)
                dirt_ui_slider_float("AO distance (0 = inf)", &o->s.ao_distance, 0.0f, v->diag,
                                     "%.3f", false);
            if (o->env_path) {
                dirt_ui_text("environment: %s", o->env_path);
                float intensity = o->env_intensity > 0 ? o->env_intensity : 1.0f;
                if (dirt_ui_slider_float("env intensity", &intensity, 0.01f, 100.0f, "%.3f", true))
                    o->env_intensity = intensity;
                dirt_ui_slider_float("env rotation", &o->env_rotation, -180.0f, 180.0f,
                                     "%.1f deg", false);
            } else {
                dirt_ui_color3("background", o->s.background);
            }
            int seed = (int)o->s.seed;
            if (dirt_ui_input_int("seed", &seed, 1) && seed >= 0)
                o->s.seed = (uint32_t)seed;
            bool follow = o->s.width == 0;
            if (dirt_ui_checkbox("resolution follows the window", &follow)) {
                o->s.width = follow ? 0 : v->rw;
                o->s.height = follow ? 0 : v->rh;
            }
            if (!follow) {
                int w = o->s.width, h = o->s.height;
                if (dirt_ui_input_int("width", &w, 16) && w >= 16 && w <= 16384)
                    o->s.width = w;
                if (dirt_ui_input_int("height (0 = aspect)", &h, 16) && h >= 0 && h <= 16384)
                    o->s.height = h;
            }
        }
        if (header("Structure", false)) {
            int vm = (int)o->s.views;
            const char *vnames[] = {"cube+camera (default)", "single", "cube", "cube+camera"};
            if (dirt_ui_combo("views", &vm, vnames, 4))
                o->s.views = (enum dirt_session_views)vm;
            const char *tiles[] = {"1", "2", "4", "8"};
            int ti = o->s.tile_size == 1 ? 0 : o->s.tile_size == 4 ? 2 : o->s.tile_size == 8 ? 3 : 1;
            if (dirt_ui_combo("tile size S", &ti, tiles, 4))
                o->s.tile_size = 1 << ti;
            int b = o->s.buckets ? o->s.buckets
                    : o->s.engine == DIRT_ENGINE_MMRT ? 4 : dirt_session_auto_buckets(v->gpu);
            if (dirt_ui_slider_int("buckets", &b, 1, 64))
                o->s.buckets = b;
            int lg = o->large < 0 ? DIRT_ADS_MAX_LARGE : (int)o->large;
            if (dirt_ui_slider_int("large primitives", &lg, 0, DIRT_ADS_MAX_LARGE))
                o->large = lg;
            dirt_ui_checkbox("large primitives' grid", &o->s.large_grid);
            dirt_ui_checkbox("sub-tile rectangles", &o->s.sub_tiles);
            dirt_ui_checkbox("bucket occupancy masks", &o->s.bucket_masks);
            dirt_ui_checkbox("node depth ranges", &o->s.node_depths);
            int top = (int)o->hiz_top;
            if (dirt_ui_slider_int("Hi-Z top (-1 = all)", &top, -1, 15))
                o->hiz_top = top;
            int fetch = (int)o->s.fetch;
            if (dirt_ui_combo("Fetch", &fetch, app_fetch_names, 2))
                o->s.fetch = (enum dirt_fetch_mode)fetch;
            dirt_ui_checkbox("direct visibility", &o->s.direct_visibility);
            dirt_ui_checkbox("emulate conservative raster", &o->s.force_emulation);
            int march = (int)o->s.march;
            if (dirt_ui_combo("MMRT march", &march, app_march_names, 2))
                o->s.march = (enum dirt_mmrt_march)march;
            int ms = o->s.march_samples ? o->s.march_samples : 30;
            if (dirt_ui_slider_int("MMRT samples", &ms, 1, 256))
                o->s.march_samples = ms;
            dirt_ui_slider_float("MMRT thickness (0 = auto)", &o->s.thickness, 0.0f,
                                 0.05f * v->diag, "%.4f", false);
        }
        if (header("Camera", false)) {
            char cam[1024];
            view_camera_args(v, cam, sizeof(cam));
            dirt_ui_text("%s", cam[0] ? cam : "(the scene's default camera)");
            if (dirt_ui_button("reset"))
                view_reset_camera(v);
            dirt_ui_same_line();
            if (dirt_ui_button("next scene camera"))
                view_cycle_camera(v);
            dirt_ui_same_line();
            if (dirt_ui_button("print")) {
                char args[4096];
                view_render_args(v, args, sizeof(args));
                printf("camera: %s\ndirt-render %s --spp %d\n", cam, args,
                       dirt_session_samples(v->s));
            }
            if (v->cam_mode == CAM_LOOK) {
                if (dirt_ui_slider_float("field of view", &v->look.fov_deg, 5.0f, 120.0f, "%.1f",
                                         false))
                    v->cam_dirty = true;
            }
            dirt_ui_slider_float("aperture", &o->s.aperture, 0.0f, 0.05f * v->diag, "%.4f", false);
            dirt_ui_slider_float("focus distance", &o->s.focus, 0.0f, 2.0f * v->diag, "%.3f",
                                 false);
        }
        if (header("Display", true)) {
            dirt_ui_combo("buffer", &o->buffer, buffer_labels, NUM_BUFFERS);
            dirt_ui_slider_float("exposure", &o->exposure, -10.0f, 10.0f, "%.1f", false);
            dirt_ui_combo("tone map", &o->tonemap, app_tonemap_names, 3);
        }
        size_t clips = dirt_scene_num_clips(v->scene);
        if (header("Animation", clips > 0)) {
            if (!clips) {
                dirt_ui_text_disabled("the scene has no animation");
            } else {
                int clip = o->clip < 0 ? 0 : o->clip;
                float dur = dirt_scene_clip_duration(v->scene, (size_t)clip);
                float t = (float)o->time;
                if (dirt_ui_button(o->play ? "pause" : "play"))
                    o->play = !o->play;
                dirt_ui_same_line();
                if (dirt_ui_button("step")) {
                    o->play = false;
                    o->time += 1.0 / 24;
                }
                if (dirt_ui_slider_float("time", &t, 0.0f, dur > 0 ? dur : 1.0f, "%.3f s", false))
                    o->time = t;
                const char *names[64];
                int n = clips < 64 ? (int)clips : 64;
                for (int i = 0; i < n; i++)
                    names[i] = dirt_scene_clip_name(v->scene, (size_t)i);
                dirt_ui_combo("clip", &o->clip, names, n);
                dirt_ui_checkbox("loop", &o->loop);
                float sp = (float)o->speed;
                if (dirt_ui_slider_float("speed", &sp, -4.0f, 4.0f, "%.2f x", false))
                    o->speed = sp;
            }
        }
        if (header("Files", false)) {
            if (dirt_ui_button("screenshot (P)")) {
                char path[64];
                view_shot_name(v, "png", path, sizeof(path));
                view_screenshot(v, path);
            }
            dirt_ui_same_line();
            if (dirt_ui_button("save render (O)")) {
                char path[64];
                view_shot_name(v, "exr", path, sizeof(path));
                view_save_render(v, path);
            }
            dirt_ui_text_disabled("drop a .gltf / .glb on the window to open it");
        }
    }
    note_panel(v);
    dirt_ui_end();
}

static void panel_numbers(viewer *v)
{
    float w = panel_width(v, 360), x = right_x(v, w), y = small_window(v) ? 34 : 8;
    float h = (float)v->win_h - y - 8;
    collapse_if_small(v);
    if (dirt_ui_begin("Numbers", NULL, x, y, w, h < 420 ? (h > 100 ? h : 100) : 420)) {
        const dirt_session_stats *st = &v->last;
        /* Memory first, where it is always in view. */
        dirt_ui_text("memory: %.2f MB used / %.2f MB allocated",
                     st->bytes_total_used / 1048576.0, st->bytes_total_allocated / 1048576.0);
        dirt_ui_item_rect(v->memory_rect);
        if (header("Inspector (under the cursor)", true)) {
            view_inspect(v);
            const struct view_probe *a = &v->probe[0], *b = &v->probe[1];
            if (!a->valid) {
                dirt_ui_text_disabled("move the cursor over the image");
            } else {
                if (v->zoom > 0)
                    dirt_ui_text("pixel %d, %d (zoom %g:1)", a->x, a->y, (double)v->zoom);
                else
                    dirt_ui_text("pixel %d, %d (fitted)", a->x, a->y);
                const char *heads[3] = {"channel", dirt_engine_names[v->applied.engine],
                                        b->valid ? view_compare_name(v) : ""};
                if (dirt_ui_table_begin("inspect", b->valid ? 3 : 2, heads)) {
                    for (int c = 0; c < a->count; c++) {
                        dirt_ui_table_row();
                        dirt_ui_table_cell("%s", a->names[c]);
                        dirt_ui_table_cell("%.6g", a->values[c]);
                        float vb = NAN;
                        for (int j = 0; b->valid && j < b->count; j++)
                            if (!strcmp(b->names[j], a->names[c]))
                                vb = b->values[j];
                        if (b->valid)
                            dirt_ui_table_cell("%.6g", vb);
                    }
                    dirt_ui_table_end();
                }
            }
        }
        float fmax = 1;
        for (int i = 0; i < v->ring_count; i++)
            fmax = fmaxf(fmax, v->frame_ms[i]);
        char cap[96];
        float last = v->ring_count ? v->frame_ms[(v->ring_pos + RING - 1) % RING] : 0;
        snprintf(cap, sizeof(cap), "frame %.1f ms", last);
        if (v->ring_count > 0)
            dirt_ui_plot_lines("##frame", v->frame_ms, v->ring_count, v->ring_count < RING ? 0 : v->ring_pos,
                           cap, 0, fmax, 50);
        float smax = 1;
        for (int i = 0; i < v->ring_count; i++)
            smax = fmaxf(smax, v->sample_ms[i]);
        float lasts = v->ring_count ? v->sample_ms[(v->ring_pos + RING - 1) % RING] : 0;
        snprintf(cap, sizeof(cap), "samples of the frame %.1f ms", lasts);
        if (v->ring_count > 0)
            dirt_ui_plot_lines("##samples", v->sample_ms, v->ring_count,
                           v->ring_count < RING ? 0 : v->ring_pos, cap, 0, smax, 50);
        dirt_ui_text("%s", st->device);
        dirt_ui_text("%.2f Mrays/s, %llu rays, %llu aborted", st->mrays_per_s,
                     (unsigned long long)st->rays, (unsigned long long)st->aborted);
        static const char *const ph[] = {"pass", "ms", "clock", "of"};
        if (dirt_ui_table_begin("passes", 4, ph)) {
            for (int i = 0; i < v->num_frame_passes; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", v->frame_passes[i].name);
                dirt_ui_table_cell("%.3f", v->frame_passes[i].ms);
                dirt_ui_table_cell("%s", dirt_clock_names[v->frame_passes[i].clock]);
                dirt_ui_table_cell("%s", i < v->num_build_passes ? "last build" : "last frame");
            }
            dirt_ui_table_end();
        }
        static const char *const bh[] = {"buffer", "used MB", "allocated MB"};
        if (dirt_ui_table_begin("buffers", 3, bh)) {
            for (int i = 0; i < st->num_buffers; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", st->buffers[i].name);
                dirt_ui_table_cell("%.3f", st->buffers[i].used / 1048576.0);
                dirt_ui_table_cell("%.3f", st->buffers[i].allocated / 1048576.0);
            }
            dirt_ui_table_row();
            dirt_ui_table_cell("total");
            dirt_ui_table_cell("%.3f", st->bytes_total_used / 1048576.0);
            dirt_ui_table_cell("%.3f", st->bytes_total_allocated / 1048576.0);
            dirt_ui_table_end();
        }
    }
    note_panel(v);
    dirt_ui_end();
}

/* The camera bookmarks: a row per slot with go / save / delete, and where
 * they are kept. */
static void panel_bookmarks(viewer *v)
{
    /* Starts collapsed to its title bar under Numbers (a click opens it). */
    float w = panel_width(v, 360), x = right_x(v, w), y = small_window(v) ? 60 : 436;
    float h = (float)v->win_h - y - 8;
    dirt_ui_next_collapsed();
    if (dirt_ui_begin("Bookmarks", NULL, x, y, w, h < 120 ? 120 : h > 300 ? 300 : h)) {
        dirt_ui_text_disabled("Ctrl + N saves, Shift + N goes to N");
        dirt_ui_text_disabled("%s", v->bm_note);
        for (int i = 0; i < NUM_BOOKMARKS; i++) {
            const struct view_bookmark *m = &v->bookmarks[i];
            char id[32];
            if (m->set)
                dirt_ui_text("%d: eye %.3g, %.3g, %.3g; fov %.3g", i + 1, (double)m->look.eye[0],
                             (double)m->look.eye[1], (double)m->look.eye[2],
                             (double)(m->look.fov_deg > 0 ? m->look.fov_deg : 45.0f));
            else
                dirt_ui_text_disabled("%d: empty", i + 1);
            if (m->set) {
                char args[1024];
                vcam_format(&m->look, args, sizeof(args));
                dirt_ui_tooltip(args);
                dirt_ui_same_line();
                snprintf(id, sizeof(id), "go##bm%d", i + 1);
                if (dirt_ui_button(id))
                    view_bookmark_go(v, i + 1);
            }
            dirt_ui_same_line();
            snprintf(id, sizeof(id), "save##bm%d", i + 1);
            if (dirt_ui_button(id))
                view_bookmark_save(v, i + 1);
            if (m->set) {
                dirt_ui_same_line();
                snprintf(id, sizeof(id), "delete##bm%d", i + 1);
                if (dirt_ui_button(id))
                    view_bookmark_delete(v, i + 1);
            }
        }
    }
    note_panel(v);
    dirt_ui_end();
}

static void panel_help(viewer *v)
{
    bool open = true;
    if (dirt_ui_begin("Key bindings (F1)", &open, (float)v->win_w / 2 - 220, 60, 440, 480)) {
        static const char *const hh[] = {"input", "does"};
        if (dirt_ui_table_begin("bindings", 2, hh)) {
            for (size_t i = 0; i < view_num_bindings; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", view_bindings[i][0]);
                dirt_ui_table_cell("%s", view_bindings[i][1]);
            }
            dirt_ui_table_end();
        }
    }
    note_panel(v);
    dirt_ui_end();
    if (!open)
        v->show_help = false;
}

static void label(viewer *v, float x, float y, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void label(viewer *v, float x, float y, const char *fmt, ...)
{
    if (v->num_labels >= 4)
        return;
    int i = v->num_labels++;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->label[i], sizeof(v->label[i]), fmt, ap);
    va_end(ap);
    float size[2] = {0, 0};
    dirt_ui_overlay_text(x, y, v->label[i], size);
    float r[4] = {x, y, size[0], size[1]};
    memcpy(v->label_rect[i], r, sizeof(r));
}

/* The part of the image's rectangle inside the window (zoomed, it may be
 * larger). */
static void visible_fit(const viewer *v, int w, int h, int r[4])
{
    view_fit(v, w, h, r);
    int x0 = r[0] > 0 ? r[0] : 0, y0 = r[1] > 0 ? r[1] : 0;
    int x1 = r[0] + r[2] < v->win_w ? r[0] + r[2] : v->win_w;
    int y1 = r[1] + r[3] < v->win_h ? r[1] + r[3] : v->win_h;
    r[0] = x0, r[1] = y0, r[2] = x1 > x0 ? x1 - x0 : 0, r[3] = y1 > y0 ? y1 - y0 : 0;
}

/* Over the image: each half of the split labelled with its engine; under
 * a heat map or the difference, a colour bar with its range. */
static void overlay(viewer *v)
{
    v->num_labels = 0;
    v->bar = false;
    int r[4];
    bool cmp = view_comparing(v);
    if (v->o.buffer == BUF_BEAUTY && cmp && !v->o.diff) {
        view_fit(v, v->rw, v->rh, r);
        float split = v->o.split > 0 && v->o.split < 1 ? v->o.split : 0.5f;
        float sx = (float)r[0] + split * (float)r[2];
        visible_fit(v, v->rw, v->rh, r);
        float y = (float)(r[1] + r[3]) - 24;
        if (sx > (float)r[0])
            label(v, (float)r[0] + 4, y, "%s", dirt_engine_names[v->applied.engine]);
        if (sx < (float)(r[0] + r[2]))
            label(v, fmaxf(sx, (float)r[0]) + 4, y, "%s", view_compare_name(v));
        return;
    }
    float lo, hi;
    char what[64];
    if (v->o.buffer == BUF_BEAUTY && cmp && v->o.diff) {
        visible_fit(v, v->rw, v->rh, r);
        lo = 0, hi = v->o.diff_range;
        snprintf(what, sizeof(what), "|lum(%s) - lum(%s)|", dirt_engine_names[v->applied.engine],
                 view_compare_name(v));
    } else if ((v->o.buffer == BUF_DEPTH || v->o.buffer >= BUF_LISTS) && v->aux_tex) {
        visible_fit(v, v->aux_w, v->aux_h, r);
        lo = v->aux_lo, hi = v->aux_hi > v->aux_lo ? v->aux_hi : v->aux_lo + 1;
        snprintf(what, sizeof(what), "%s", buffer_labels[v->o.buffer]);
    } else {
        return;
    }
    /* Whole pixels: column i of the bar is the ramp at (i + 0.5) / w. */
    float w = floorf(fminf(256.0f, (float)r[2] - 16)), x = floorf((float)r[0] + ((float)r[2] - w) / 2);
    float y = (float)(r[1] + r[3]) - 40;
    if (w < 32)
        return;
    dirt_ui_overlay_ramp(x, y, w, 12);
    v->bar = true;
    v->bar_lo = lo, v->bar_hi = hi;
    v->bar_rect[0] = x, v->bar_rect[1] = y, v->bar_rect[2] = w, v->bar_rect[3] = 12;
    label(v, x, y + 13, "%.4g", lo);
    label(v, x + w - 48, y + 13, "%.4g", hi);
    label(v, x, y - 19, "%s", what);
}

/* The panels of this frame: Settings, Numbers and, with F1, the key
 * bindings; their rectangles go to the report. Over the image: the split's
 * labels and the colour bar. */
void view_panels(viewer *v)
{
    v->num_panels = 0;
    v->num_labels = 0;
    v->bar = false;
    memset(v->memory_rect, 0, sizeof(v->memory_rect));
    if (v->o.no_ui)
        return;
    overlay(v);
    panel_settings(v);
    panel_numbers(v);
    panel_bookmarks(v);
    if (v->show_help)
        panel_help(v);
}
