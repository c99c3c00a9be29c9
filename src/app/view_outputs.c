/* dirt-view's outputs (view.h): window screenshots, saved renders (with
 * provenance), reports, and the dirt-render command line of what it shows;
 * the key bindings it lists. */
#include <cjson/cJSON.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/cli.h"
#include "app/view.h"
#include "dirt/clock.h"
#include "dirt/file.h"

/* The key and mouse bindings (F1, --bindings, doc/viewer.md). */
const char *const view_bindings[][2] = {
    {"Left drag", "orbit around the target"},
    {"Right drag, Middle drag", "pan"},
    {"Wheel", "dolly toward / away from the target"},
    {"W A S D", "fly forward, left, back, right"},
    {"Q E", "fly down, up"},
    {"Shift", "with W A S D Q E: 5x faster"},
    {"Double click", "focus the thin lens on the surface under the cursor"},
    {"R", "reset the camera (the scene's, or the automatic one)"},
    {"C", "next scene camera"},
    {"1 .. 9", "buffer: beauty, albedo, normal, depth, id, lists, buckets, zmin, zmax"},
    {"Ctrl + 1 .. 9", "save the camera (and lens) as bookmark N (SCENE.bookmarks.json)"},
    {"Shift + 1 .. 9", "go to camera bookmark N"},
    {"Tab", "next engine (dirt, mmrt, embree, raster)"},
    {"V", "split view against the comparison engine (or --compare-image) on / off"},
    {"X", "difference heat map of the split on / off"},
    {"Space", "play / pause the animation"},
    {"Left Right", "step the animation one frame (1/24 s) back / forward"},
    {"Minus Equal", "exposure down / up one stop"},
    {"P", "screenshot of the window (dirt-view-N.png)"},
    {"O", "save the render (dirt-view-N.exr and .png)"},
    {"Ctrl + Wheel", "zoom the image in / out (powers of 2) about the cursor"},
    {"Ctrl + Left drag", "pan the image (zoomed or not)"},
    {"Z", "zoom 1:1 about the cursor / back to fitted"},
    {"H", "hide / show the panels"},
    {"F5", "reload the shaders from DIRT_GLSL_DIR or, run from its build tree, the source "
           "tree's glsl/ (a broken one keeps the old programs)"},
    {"F1", "this help"},
    {"Escape", "quit"},
};
const size_t view_num_bindings = sizeof(view_bindings) / sizeof(view_bindings[0]);


/* The render alone, with the provenance of dirt-render's EXRs and the
 * dirt-render options of the image (dirt.render_args). */
bool view_save_render(viewer *v, const char *path)
{
    if (dirt_session_samples(v->s) == 0 && !dirt_session_add_samples(v->s, 1, NULL, NULL))
        return false;
    const dirt_image *img = dirt_session_image(v->s);
    char args[4096];
    view_render_args(v, args, sizeof(args));
    app_provenance_extra(&v->prov, "render_args", args);
    size_t na;
    const dirt_image_attr *attrs =
        app_provenance_attrs(&v->prov, dirt_session_get_stats(v->s), true, &na);
    dirt_image_write_options wo = {.exr = {.attrs = attrs, .num_attrs = na},
                                   .png = {.exposure = v->o.exposure,
                                           .tonemap = (enum dirt_tonemap)v->o.tonemap}};
    bool ok = img && cli_write_image(PROG, img, path, &wo, cli_has_ext(path, ".exr"), v->o.quiet);
    if (ok)
        view_status(v, "saved %s (%d samples)", path, dirt_session_samples(v->s));
    return ok;
}

int view_check_io(const viewer *v, const char *scene_path, const dirt_scene *scene)
{
    enum { SCRIPT_OUTS = CLI_IO_MAX - 5 };
    const char *souts[SCRIPT_OUTS] = {0};
    static char spng[SCRIPT_OUTS][4200];
    vs_outputs(&v->script, souts, spng, SCRIPT_OUTS);
    char save_png[4200] = "";
    if (v->o.save_image && cli_has_ext(v->o.save_image, ".exr"))
        cli_png_beside(v->o.save_image, save_png, sizeof(save_png));
    bool env_file = v->o.env_path && strcmp(v->o.env_path, "sky");
    /* The scene's bookmarks file is written whenever a bookmark changes. */
    char bm[4200];
    view_bookmarks_path(scene_path, bm, sizeof(bm));
    cli_io io = {.scene_path = scene_path,
                 .scene = scene,
                 .in = {{env_file ? v->o.env_path : NULL, "--env"}, {v->o.script, "--script"},
                        {v->o.compare_image, "--compare-image"}},
                 .out = {{v->o.screenshot, "--screenshot"}, {v->o.save_image, "--save-image"},
                         {save_png[0] ? save_png : NULL, "--save-image"},
                         {v->o.report, "--report"},
                         {bm[0] ? bm : NULL, "the scene's camera bookmarks"}}};
    for (size_t i = 0; i < SCRIPT_OUTS; i++)
        io.out[5 + i][0] = souts[i], io.out[5 + i][1] = "the script";
    return cli_check_io(PROG, &io);
}

void view_shot_name(viewer *v, const char *ext, char *path, size_t size)
{
    struct stat st;
    do
        snprintf(path, size, "dirt-view-%d.%s", ++v->shots, ext);
    while (lstat(path, &st) == 0 && v->shots < INT_MAX);
}

/* Requested window screenshots are taken at the end of the frame, after
 * the panels are drawn (take_screenshots). */
bool view_screenshot(viewer *v, const char *path)
{
    if (v->num_shots >= 4)
        return false;
    snprintf(v->shot_path[v->num_shots++], sizeof(v->shot_path[0]), "%s", path);
    return true;
}

/* Takes the screenshots asked for in this frame (the window as drawn). */
bool view_take_screenshots(viewer *v)
{
    bool ok = true;
    uint8_t *px = NULL;
    if (v->num_shots) {
        px = malloc((size_t)v->win_w * v->win_h * 4);
        ok = px && dirt_gpu_window_read(v->gpu, px, v->win_w, v->win_h);
    }
    for (int i = 0; ok && i < v->num_shots; i++) {
        ok = dirt_write_png_rgba8(v->shot_path[i], v->win_w, v->win_h, px);
        if (ok)
            view_status(v, "screenshot %s (%dx%d)", v->shot_path[i], v->win_w, v->win_h);
    }
    v->num_shots = 0;
    free(px);
    return ok;
}

/* The dirt-render options that render what the main session shows now
 * (size, engine, every technique setting that differs from dirt-render's
 * default, time, camera, lens), samples excepted. */
void view_render_args(const viewer *v, char *buf, size_t size)
{
    const dirt_session_opts *o = &v->applied;
    size_t n = 0;
#define ADD(...) (n < size ? (void)(n += (size_t)snprintf(buf + n, size - n, __VA_ARGS__)) : (void)0)
    ADD("-W %d -H %d --engine %s --seed %u", o->width, o->height, dirt_engine_names[o->engine],
        o->seed);
    if (o->bounces && o->bounces != 4)
        ADD(" --bounces %d", o->bounces);
    if (o->mode)
        ADD(" --mode %s", app_mode_names[o->mode]);
    if (o->ao_distance > 0)
        ADD(" --ao-distance %.9g", o->ao_distance);
    if (v->o.env_path) {
        char env[4200] = "--env";
        app_shell_quote(env, sizeof(env), strlen(env), v->o.env_path);
        ADD(" %s", env);
        if (v->env_intensity != 0 && v->env_intensity != 1)
            ADD(" --env-intensity %.9g", v->env_intensity);
        if (v->env_rotation != 0)
            ADD(" --env-rotation %.9g", v->env_rotation);
    } else if (o->background[0] || o->background[1] || o->background[2]) {
        ADD(" --background %.9g,%.9g,%.9g", o->background[0], o->background[1], o->background[2]);
    }
    if (o->views)
        ADD(" --views %s", app_views_names[o->views]);
    if (o->tile_size)
        ADD(" --tile %d", o->tile_size);
    if (o->buckets)
        ADD(" --buckets %d", o->buckets);
    if (o->face_size)
        ADD(" --face-size %d", o->face_size);
    if (o->engine == DIRT_ENGINE_DIRT && o->build)
        ADD(" --build %s", app_build_names[o->build]);
    if (o->engine == DIRT_ENGINE_DIRT && o->depth_buckets)
        ADD(" --depth-buckets %s", app_depth_buckets_names[o->depth_buckets]);
    if (o->engine == DIRT_ENGINE_DIRT && o->large && o->large != DIRT_ADS_MAX_LARGE)
        ADD(" --large %d", o->large < 0 ? 0 : o->large);
    if (o->engine == DIRT_ENGINE_DIRT && o->large_grid)
        ADD(" --large-grid");
    if (o->engine == DIRT_ENGINE_DIRT && o->sub_tiles)
        ADD(" --sub-tiles");
    if (o->engine == DIRT_ENGINE_DIRT && o->bucket_masks)
        ADD(" --bucket-masks");
    if (o->engine == DIRT_ENGINE_DIRT && o->node_depths)
        ADD(" --node-depths");
    if (o->hiz_levels)
        ADD(" --hiz-top %d", o->hiz_levels - 1);
    if (o->fetch)
        ADD(" --fetch %s", app_fetch_names[o->fetch]);
    if (o->direct_visibility)
        ADD(" --direct-visibility");
    if (o->force_emulation)
        ADD(" --no-conservative-raster");
    if (o->engine == DIRT_ENGINE_MMRT && o->march)
        ADD(" --march %s", app_march_names[o->march]);
    if (o->engine == DIRT_ENGINE_MMRT && o->march_samples)
        ADD(" --samples %d", o->march_samples);
    if (o->engine == DIRT_ENGINE_MMRT && o->thickness > 0)
        ADD(" --thickness %.9g", o->thickness);
    if (o->aperture > 0)
        ADD(" --aperture %.9g", o->aperture);
    if (o->aperture > 0 && o->focus > 0)
        ADD(" --focus %.9g", o->focus);
    if (v->applied_time != 0)
        ADD(" -t %.17g", v->applied_time);
    if (v->applied_clip)
        ADD(" --clip %d", v->applied_clip);
    if (v->applied_loop)
        ADD(" --loop");
    char cam[1024];
    view_camera_args(v, cam, sizeof(cam));
    if (cam[0])
        ADD(" %s", cam);
#undef ADD
}

/* The report: camera (as dirt-render options), sizes, samples, frame
 * times, device, panel rectangles and provenance, as JSON. */
bool view_write_report(viewer *v, const char *path)
{
    cJSON *r = cJSON_CreateObject();
    char cam[1024];
    view_camera_args(v, cam, sizeof(cam));
    const char *modes_[] = {"default", "auto", "scene", "look"};
    cJSON_AddStringToObject(r, "scene", v->scene_name);
    cJSON_AddStringToObject(r, "engine", dirt_engine_names[v->applied.engine]);
    int win[2] = {v->win_w, v->win_h}, ren[2] = {v->rw, v->rh};
    cJSON_AddItemToObject(r, "window", cJSON_CreateIntArray(win, 2));
    cJSON_AddItemToObject(r, "render", cJSON_CreateIntArray(ren, 2));
    cJSON_AddNumberToObject(r, "samples", dirt_session_samples(v->s));
    /* the slices (a sample over frames) and the render scale */
    cJSON_AddNumberToObject(r, "sample_part", dirt_session_sample_part(v->s));
    cJSON_AddNumberToObject(r, "slice_ms", v->o.slice_ms);
    cJSON_AddNumberToObject(r, "last_sample_ms", v->last_sample_ms);
    cJSON_AddNumberToObject(r, "scale", v->o.s.width > 0 ? 1 : v->o.scale);
    cJSON_AddBoolToObject(r, "scale_auto", v->auto_scale);
    cJSON_AddStringToObject(r, "compare", view_compare_name(v));
    if (v->o.compare_image)
        cJSON_AddStringToObject(r, "compare_image", v->o.compare_image);
    cJSON_AddNumberToObject(r, "compare_samples", v->cmp ? dirt_session_samples(v->cmp) : 0);
    cJSON_AddBoolToObject(r, "diff", v->o.diff);
    cJSON_AddStringToObject(r, "buffer", app_buffer_names[v->o.buffer]);
    cJSON_AddBoolToObject(r, "panels_shown", !v->o.no_ui);
    cJSON_AddBoolToObject(r, "help_shown", v->show_help);
    cJSON_AddNumberToObject(r, "exposure", v->o.exposure);
    cJSON_AddBoolToObject(r, "play", v->o.play);
    cJSON_AddNumberToObject(r, "frames", (double)v->frame);
    cJSON_AddNumberToObject(r, "shader_reloads", v->shader_reloads);
    cJSON_AddNumberToObject(r, "shader_reload_failures", v->shader_reload_failures);
    cJSON_AddStringToObject(r, "shader_reload_status", v->reload_status);
    {
        /* Where F5 would read the shaders from now ("" and "embedded": none). */
        char dir[4096], why[4400];
        const char *from = view_shader_source(dir, sizeof(dir), why, sizeof(why));
        cJSON_AddStringToObject(r, "shader_source", from ? from : "embedded");
        cJSON_AddStringToObject(r, "shader_source_dir", dir);
    }
    cJSON_AddNumberToObject(r, "time", v->applied_time);
    cJSON_AddStringToObject(r, "camera_mode", modes_[v->cam_mode]);
    cJSON_AddStringToObject(r, "camera_args", cam);
    char args[4096];
    view_render_args(v, args, sizeof(args));
    cJSON_AddStringToObject(r, "render_args", args);
    app_provenance_extra(&v->prov, "render_args", args);
    cJSON_AddNumberToObject(r, "aperture", v->applied.aperture);
    cJSON_AddNumberToObject(r, "focus", v->applied.focus);
    const dirt_camera *c = dirt_session_camera(v->s);
    cJSON *cj = cJSON_AddObjectToObject(r, "camera");
    cJSON_AddItemToObject(cj, "eye", cJSON_CreateFloatArray(c->eye, 3));
    cJSON_AddItemToObject(cj, "forward", cJSON_CreateFloatArray(c->forward, 3));
    cJSON_AddNumberToObject(cj, "yfov", c->yfov);
    /* Displayed frames' times (the last RING frames, skipping the first
     * one: it builds the GPU programs), ms. */
    const float *rings[2] = {v->frame_ms, v->sample_ms};
    const char *ring_names[2] = {"frame_ms", "samples_ms"};
    for (int k = 0; k < 2; k++) {
        float sorted[RING];
        int n = 0;
        for (int i = 0; i < v->ring_count; i++) {
            int idx = (v->ring_count < RING ? i : (v->ring_pos + i) % RING);
            if (v->ring_count < RING && v->frame > 1 && i == 0)
                continue;
            sorted[n++] = rings[k][idx];
        }
        for (int i = 1; i < n; i++)
            for (int j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
                float t = sorted[j];
                sorted[j] = sorted[j - 1];
                sorted[j - 1] = t;
            }
        cJSON *t = cJSON_AddObjectToObject(r, ring_names[k]);
        cJSON_AddNumberToObject(t, "count", n);
        cJSON_AddNumberToObject(t, "min", n ? sorted[0] : 0);
        cJSON_AddNumberToObject(t, "median", n ? sorted[n / 2] : 0);
        cJSON_AddNumberToObject(t, "max", n ? sorted[n - 1] : 0);
    }
    cJSON_AddStringToObject(r, "clock", dirt_clock_names[dirt_gpu_clock(v->gpu)]);
    char desc[256];
    dirt_gpu_describe(v->gpu, desc, sizeof(desc));
    cJSON_AddStringToObject(r, "device", desc);
    size_t na;
    const dirt_image_attr *attrs =
        app_provenance_attrs(&v->prov, dirt_session_get_stats(v->s), false, &na);
    cJSON *pj = cJSON_AddObjectToObject(r, "provenance");
    for (size_t i = 0; i < na; i++)
        cJSON_AddStringToObject(pj, attrs[i].name, attrs[i].value);
    view_inspect(v);
    cJSON *insp = cJSON_AddObjectToObject(r, "inspect");
    for (int k = 0; k < 2; k++) {
        const struct view_probe *pr = &v->probe[k];
        if (!pr->valid)
            continue;
        if (k == 0) {
            int px[2] = {pr->x, pr->y};
            cJSON_AddItemToObject(insp, "pixel", cJSON_CreateIntArray(px, 2));
        }
        cJSON *side = cJSON_AddObjectToObject(insp, k ? "b" : "a");
        for (int ch = 0; ch < pr->count; ch++)
            cJSON_AddNumberToObject(side, pr->names[ch], pr->values[ch]);
    }
    cJSON *labels = cJSON_AddArrayToObject(r, "labels");
    for (int i = 0; i < v->num_labels; i++) {
        cJSON *l = cJSON_CreateObject();
        cJSON_AddStringToObject(l, "text", v->label[i]);
        cJSON_AddItemToObject(l, "rect", cJSON_CreateFloatArray(v->label_rect[i], 4));
        cJSON_AddItemToArray(labels, l);
    }
    if (v->bar) {
        cJSON *b = cJSON_AddObjectToObject(r, "colour_bar");
        cJSON_AddNumberToObject(b, "lo", v->bar_lo);
        cJSON_AddNumberToObject(b, "hi", v->bar_hi);
        cJSON_AddItemToObject(b, "rect", cJSON_CreateFloatArray(v->bar_rect, 4));
    }
    /* The Numbers panel's passes: the last build's, then the last frame's
     * samples'; memory, and where its line is (0s: not shown). */
    cJSON *passes = cJSON_AddArrayToObject(r, "passes");
    for (int i = 0; i < v->num_frame_passes; i++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "name", v->frame_passes[i].name);
        cJSON_AddNumberToObject(p, "ms", v->frame_passes[i].ms);
        cJSON_AddStringToObject(p, "clock", dirt_clock_names[v->frame_passes[i].clock]);
        cJSON_AddBoolToObject(p, "build", i < v->num_build_passes);
        cJSON_AddItemToArray(passes, p);
    }
    cJSON *mem = cJSON_AddObjectToObject(r, "memory");
    cJSON_AddNumberToObject(mem, "used", (double)v->last.bytes_total_used);
    cJSON_AddNumberToObject(mem, "allocated", (double)v->last.bytes_total_allocated);
    cJSON_AddItemToObject(mem, "rect", cJSON_CreateFloatArray(v->memory_rect, 4));
    /* Where the image is: its rectangle in the window, and the zoom (0:
     * fitted). */
    {
        int iw = v->rw, ih = v->rh, ir[4];
        if (v->o.buffer != BUF_BEAUTY && v->aux_tex && v->aux_w > 0)
            iw = v->aux_w, ih = v->aux_h;
        view_fit(v, iw, ih, ir);
        cJSON_AddItemToObject(r, "image_rect", cJSON_CreateIntArray(ir, 4));
        cJSON_AddNumberToObject(r, "zoom", v->zoom);
    }
    /* The camera bookmarks: the slots set, and where they are kept ("" for
     * memory only). */
    cJSON *bms = cJSON_AddObjectToObject(r, "bookmarks");
    cJSON_AddStringToObject(bms, "file", v->bm_path);
    cJSON_AddBoolToObject(bms, "file_kept", v->bm_keep_file);
    cJSON *slots = cJSON_AddArrayToObject(bms, "slots");
    for (int i = 0; i < NUM_BOOKMARKS; i++)
        if (v->bookmarks[i].set)
            cJSON_AddItemToArray(slots, cJSON_CreateNumber(i + 1));
    /* Labels of the last frame's panels cut off by their panel's width. */
    cJSON_AddNumberToObject(r, "clipped_labels", v->o.no_ui ? 0 : dirt_ui_clipped_labels(v->ui));
    cJSON *panels = cJSON_AddArrayToObject(r, "panels");
    for (int i = 0; !v->o.no_ui && i < v->num_panels; i++)
        cJSON_AddItemToArray(panels, cJSON_CreateFloatArray(v->panels[i], 4));
    char *text = cJSON_Print(r);
    cJSON_Delete(r);
    bool ok = text && dirt_write_file_atomic(path, text, strlen(text));
    free(text);
    if (!ok)
        cli_error(PROG, "could not write the report '%s'", path);
    return ok;
}
