/* dirt-view: the interactive viewer on the render session (doc/viewer.md).
 *
 * A GLFW window with panels (gl/ui.h) over the progressive render of one
 * session, and optionally a second session on the same camera for a split
 * or difference view. Every displayed frame does a bounded slice of work:
 * about --slice-ms of path tracing (a sample spans as many frames as it
 * needs: dirt_session_advance), at most --samples-per-frame samples. This
 * file holds the options, the start, the frame loop and the exit; the
 * viewer's parts are listed in view.h. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app/cli.h"
#include "app/setup.h"
#include "app/view.h"
#include "dirt/clock.h"

void view_status(viewer *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->status, sizeof(v->status), fmt, ap);
    va_end(ap);
    if (!v->o.quiet)
        fprintf(stderr, "%s: %s\n", PROG, v->status);
}

/* The passes of this frame's samples: the path tracer's as the difference
 * to before (they add up over the accumulation), the build's as the last
 * build's times (they are not summed: a build runs once per restart). */
static void record_passes(viewer *v, const dirt_session_stats *before, bool restarted)
{
    const dirt_session_stats *st = dirt_session_get_stats(v->s);
    v->num_frame_passes = st->num_passes < 32 ? st->num_passes : 32;
    v->num_build_passes = st->num_build_passes < v->num_frame_passes ? st->num_build_passes
                                                                     : v->num_frame_passes;
    for (int i = 0; i < v->num_frame_passes; i++) {
        v->frame_passes[i] = st->passes[i];
        if (i >= v->num_build_passes && !restarted && i < before->num_passes &&
            before->passes[i].name == st->passes[i].name)
            v->frame_passes[i].ms -= before->passes[i].ms;
    }
    v->last = *st;
}

/* Plays the animation for `dt` seconds (--speed; wrapped or back to 0). */
static void play(viewer *v, double dt)
{
    v->o.time += dt * v->o.speed;
    int clip = v->o.clip < 0 ? 0 : v->o.clip;
    if (dirt_scene_num_clips(v->scene) > (size_t)clip) {
        double dur = dirt_scene_clip_duration(v->scene, (size_t)clip);
        if (dur > 0 && v->o.time > dur)
            v->o.time = v->o.loop ? fmod(v->o.time, dur) : 0;
    }
}

/* A sample of the window's every pixel on a software renderer takes
 * about this long at the automatic scale. */
#define AUTO_SAMPLE_MS 1000.0
/* The pace assumed before one is measured, in ms per pixel per sample: the
 * default scene on llvmpipe, 35.6 s for 1024 x 768 (issue 26's figure). */
#define ASSUMED_PACE_MS (35600.0 / (1024.0 * 768.0))

/* A software renderer (llvmpipe, softpipe, or lavapipe under zink), from
 * the GL renderer string. */
static bool software_renderer(const dirt_gpu *gpu)
{
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    return c->software || strstr(c->renderer, "llvmpipe") || strstr(c->renderer, "lavapipe") ||
           strstr(c->renderer, "softpipe");
}

/* Chooses the automatic scale for a win_w x win_h window at v->pace_ms:
 * the integer N (1 .. 16) whose render of window / N takes closest to
 * AUTO_SAMPLE_MS a sample; says so when it changes (`why`: where the pace
 * comes from). */
static void choose_scale(viewer *v, int win_w, int win_h, const char *why)
{
    double best = -1;
    int n = 1;
    for (int k = 1; k <= 16; k++) {
        double w = win_w / k >= 16 ? win_w / k : 16, h = win_h / k >= 16 ? win_h / k : 16;
        double err = fabs(log(w * h * v->pace_ms / AUTO_SAMPLE_MS));
        if (best < 0 || err < best) {
            best = err;
            n = k;
        }
    }
    v->auto_w = win_w;
    v->auto_h = win_h;
    int rw = win_w / n >= 16 ? win_w / n : 16, rh = win_h / n >= 16 ? win_h / n : 16;
    double est = rw * (double)rh * v->pace_ms / 1000.0;
    snprintf(v->scale_note, sizeof(v->scale_note),
             "software renderer: window / %d, about %.1f s a sample (%s); --scale sets it", n,
             est, why);
    if (n != v->o.scale && !v->o.quiet)
        fprintf(stderr, "%s: software renderer (%s): rendering at the window's size / %d "
                "(%d x %d) so that a sample takes about %.1f s (%s: %.3g ms per pixel); "
                "--scale N sets it\n", PROG, dirt_gpu_get_caps(v->gpu)->renderer, n, rw, rh,
                est, why, v->pace_ms);
    v->o.scale = n;
    v->auto_n = n;
}

/* Keeps the automatic scale (if still in charge): again for a new window
 * size; off once the panel or the script set another. */
static void update_scale(viewer *v, int win_w, int win_h)
{
    if (!v->auto_scale)
        return;
    if (v->o.scale != v->auto_n) {
        v->auto_scale = false;
        snprintf(v->scale_note, sizeof(v->scale_note), "window / %d (set)", v->o.scale);
        return;
    }
    if (win_w != v->auto_w || win_h != v->auto_h)
        choose_scale(v, win_w, win_h, "window resized");
}

/* A sample completed after `ms` of work, the `nth` of its accumulation:
 * the automatic scale looks at the pace once per accumulation (at the
 * second sample: the first also traces the depth AOV) and chooses again
 * when a sample took less than half or more than twice its aim. */
static void sample_done(viewer *v, double ms, int nth)
{
    v->last_sample_ms = ms;
    if (!v->auto_scale || v->paced || nth < 2 || v->o.scale != v->auto_n)
        return;
    v->paced = true;
    v->pace_ms = ms / ((double)v->rw * (double)v->rh);
    if (ms < 0.5 * AUTO_SAMPLE_MS || ms > 2 * AUTO_SAMPLE_MS)
        choose_scale(v, v->win_w, v->win_h, "measured");
}

/* About o.slice_ms of the main session's next samples (a new accumulation
 * builds its structure first, then goes on in the next frame when that
 * took the slice), at most o.samples_per_frame completed and up to
 * `target`. False when rendering fails. */
static bool advance(viewer *v, int have, int target)
{
    double t0 = dirt_clock_ms();
    if (have == 0 && dirt_session_sample_part(v->s) == 0) {
        v->sample_work_ms = 0;
        v->paced = false;
        if (!dirt_session_build(v->s))
            return false;
        if (dirt_clock_ms() - t0 >= v->o.slice_ms && v->o.slice_ms > 0)
            return true;
    }
    for (int added = 0;;) {
        double a0 = dirt_clock_ms(), left = v->o.slice_ms - (a0 - t0);
        bool done = false;
        if (!dirt_session_advance(v->s, left > 0 ? left : 0, &done))
            return false;
        v->sample_work_ms += dirt_clock_ms() - a0;
        if (!done)
            return true; /* the slice is over within the sample */
        added++;
        v->generation++;
        sample_done(v, v->sample_work_ms, have + added);
        v->sample_work_ms = 0;
        if (added >= v->o.samples_per_frame || (target && have + added >= target) ||
            dirt_clock_ms() - t0 >= v->o.slice_ms)
            return true;
    }
}

/* A bounded amount of work: a slice of the path tracer (advance), or the
 * raster preview while input moves the camera (and once beside the slice
 * until the accumulation's first sample completes); no tracing in a frame whose
 * image a script output took, nor in one where input arrived (`input`: it
 * is answered at once). *traced says whether a slice ran. False when
 * rendering fails. */
static bool sample(viewer *v, bool input, bool *preview, bool *traced)
{
    int have = dirt_session_samples(v->s);
    *traced = false;
    *preview = v->moving && v->pre;
    /* Until the accumulation's first sample completes, the raster preview
     * of the camera (rendered once; a camera or setting change restarts
     * it) fills the image while the sample is traced (view_draw). */
    bool fill = !*preview && v->pre && !v->o.no_preview && have == 0 &&
                dirt_session_samples(v->pre) == 0;
    if ((*preview || fill) && !dirt_session_add_samples(v->pre, 1, NULL, NULL)) {
        view_status(v, "the raster preview failed (see the log); off");
        v->o.no_preview = true;
        *preview = false;
    }
    int target = view_target(v, v->s);
    if (input)
        return true;
    if (!*preview && !v->hold && (target == 0 || have < target)) {
        dirt_session_stats before = *dirt_session_get_stats(v->s);
        if (!advance(v, have, target)) {
            cli_error(PROG, "rendering failed (see the log)");
            return false;
        }
        record_passes(v, &before, have == 0);
        *traced = true;
    }
    if (!*preview && !v->hold) {
        view_sample_compare(v);
        *traced = true;
    }
    return true;
}

/* Whether `in` holds events to answer at once: a mouse button went down
 * or up, a key went down, the wheel turned, a double click, a drop. */
static bool input_arrived(const dirt_window_input *in)
{
    for (int b = 0; b < DIRT_MOUSE_BUTTONS; b++)
        if (in->button_pressed[b] || in->button_released[b])
            return true;
    for (int k = 0; k < DIRT_NUM_KEYS; k++)
        if (in->key_pressed[k])
            return true;
    return in->scroll != 0 || in->ctrl_scroll != 0 || in->double_clicks > 0 || in->num_drops > 0;
}

/* The window's input of the last poll into the viewer's cursor and size. */
static void take_input(viewer *v, dirt_window_input *in)
{
    dirt_gpu_window_input(v->gpu, in);
    if (in->close_requested || dirt_gpu_window_should_close(v->gpu))
        v->quit = true;
    v->win_w = in->width;
    v->win_h = in->height;
    v->cursor_x = in->mouse_x;
    v->cursor_y = in->mouse_y;
    for (int b = 0; b < DIRT_MOUSE_BUTTONS; b++)
        v->releases += in->button_released[b];
}

/* At most this many passes of the panels' logic before the drawn one (a
 * click needs two: its press and its release; what it defers applies in
 * the drawn pass). */
#define MAX_LOGIC_PASSES 4

/* Test hook DIRT_VIEW_FRAME_LOG: after each frame is shown, its wall-clock
 * time, number, the main session's samples and part of the one in
 * progress, the buffer, whether the panels are shown, the Settings
 * panel's height (collapsed or open), the mouse button releases seen so
 * far and the panels' logic-only passes so far (dirt_ui_end_pass). */
static void log_frame(viewer *v)
{
    if (!v->frame_log)
        return;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    fprintf(v->frame_log, "%lld.%06ld %ld %d %.4f %s %d %.0f %ld %ld\n", (long long)ts.tv_sec,
            ts.tv_nsec / 1000, v->frame, dirt_session_samples(v->s),
            dirt_session_sample_part(v->s), app_buffer_names[v->o.buffer], !v->o.no_ui,
            v->num_panels > 0 ? v->panels[0][3] : 0.0f, v->releases, v->ui_passes);
    fflush(v->frame_log);
}

/* One displayed frame: input, the script, the sessions, samples, drawing,
 * panels, screenshots. Input is answered in the frame that sees it: a
 * frame where it arrived traces nothing; the events that arrive during the
 * trace slice are polled after it; and the panels' logic runs again
 * (dirt_ui_end_pass) while a mouse button went down or up in the last
 * pass, so that a click and what it defers show in this frame's drawing.
 * False when rendering fails. */
static bool frame(viewer *v, double dt)
{
    double t0 = dirt_clock_ms();
    dirt_gpu_window_poll(v->gpu);
    dirt_window_input in;
    take_input(v, &in);
    if (!view_open_drops(v, &in))
        return false;
    dirt_ui_begin_frame(v->ui);
    v->moving = false;
    bool ui_mouse = !v->o.no_ui && dirt_ui_wants_mouse(v->ui);
    bool ui_keys = !v->o.no_ui && dirt_ui_wants_keyboard(v->ui);
    if (!view_run_script(v)) {
        v->exit_code = DIRT_EXIT_FAILURE;
        v->quit = true;
    }
    view_handle_input(v, &in, dt, ui_mouse, ui_keys);
    bool input = input_arrived(&in);
    for (int k = 0; k < DIRT_NUM_KEYS; k++) {
        if (v->held[k] > 0)
            v->held[k]--;
        v->pressed[k] = false;
    }
    if (v->o.play)
        play(v, dt);
    update_scale(v, in.width, in.height);
    view_render_size(v, in.width, in.height);
    view_sync_sessions(v);
    if (v->click_pending)
        view_focus_at(v);
    double s0 = dirt_clock_ms();
    bool preview, traced;
    if (!sample(v, input, &preview, &traced))
        return false;
    double s1 = dirt_clock_ms();
    bool late = false;
    if (traced) {
        /* What arrived during the slice: answered in this frame (the
         * motion too, so that a drag keeps its whole length; held keys
         * fly in the next frame's time step). */
        dirt_gpu_window_poll(v->gpu);
        take_input(v, &in);
        if (!view_open_drops(v, &in))
            return false;
        view_handle_input(v, &in, 0, ui_mouse, ui_keys);
        late = input_arrived(&in);
    }
    v->hold = false;
    /* The panels' logic until a pass sees no button change (the first
     * pass opened before the late poll: its events need one more). */
    for (int pass = 0; !v->o.no_ui && pass < MAX_LOGIC_PASSES &&
                       (late || dirt_ui_buttons_changed(v->ui));
         pass++) {
        late = false;
        view_panels(v);
        dirt_ui_end_pass(v->ui);
        dirt_ui_begin_frame(v->ui);
        v->ui_passes++;
    }
    view_draw(v, preview);
    view_panels(v);
    dirt_ui_end_frame(v->ui);
    if (!view_take_screenshots(v)) {
        cli_error(PROG, "could not write a screenshot (see the error above)");
        v->exit_code = DIRT_EXIT_FAILURE;
    }
    dirt_gpu_window_swap(v->gpu);
    log_frame(v);
    if (v->slow_frame_ms > 0)
        nanosleep(&(struct timespec){.tv_sec = v->slow_frame_ms / 1000,
                                     .tv_nsec = (v->slow_frame_ms % 1000) * 1000000L},
                  NULL);
    v->frame_ms[v->ring_pos] = (float)(dirt_clock_ms() - t0);
    v->sample_ms[v->ring_pos] = (float)(s1 - s0);
    v->ring_pos = (v->ring_pos + 1) % RING;
    if (v->ring_count < RING)
        v->ring_count++;
    v->frame++;
    if (v->o.test_frames && v->frame >= v->o.test_frames)
        v->quit = true;
    return true;
}

/* Everything before the window: the script, the outputs, the scene, the
 * environment. DIRT_EXIT_OK, or the exit status after printing why. */
static int prepare(viewer *v, dirt_scene **scene)
{
    char why[1024];
    if (!app_check(&app_view_program, &v->o))
        return DIRT_EXIT_USAGE;
    if (v->o.script && !vs_load(v->o.script, &v->script, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
        return DIRT_EXIT_USAGE;
    }
    if (!view_check_script(&v->script, &v->o))
        return DIRT_EXIT_USAGE;
    const char *outs[] = {v->o.screenshot, v->o.save_image, v->o.report};
    for (int i = 0; i < 3; i++)
        if (outs[i] && !cli_creatable(PROG, outs[i]))
            return DIRT_EXIT_USAGE;
    const char *scene_path = v->o.num_scenes ? v->o.scenes[0] : NULL;
    *scene = app_load_scene(PROG, scene_path, &v->o);
    if (!*scene || !app_load_env(PROG, &v->o, &v->env) || !app_check_scene(PROG, &v->o, *scene) ||
        !view_load_reference(v))
        return DIRT_EXIT_USAGE;
    /* No output (at exit or from the script) may be an input. */
    if (view_check_io(v, scene_path && strcmp(scene_path, "default") ? scene_path : NULL,
                      *scene) != DIRT_EXIT_OK)
        return DIRT_EXIT_USAGE;
    v->env_intensity = v->o.env_intensity;
    v->env_rotation = v->o.env_rotation;
    return DIRT_EXIT_OK;
}

/* The outputs asked for at exit, and the same image's dirt-render command
 * line. The exit status. */
static int finish(viewer *v)
{
    int rc = v->exit_code;
    if (v->o.save_image && !view_save_render(v, v->o.save_image))
        rc = DIRT_EXIT_FAILURE;
    if (v->o.screenshot) {
        /* The last frame again, for the window as it is now. */
        v->quit = false;
        view_screenshot(v, v->o.screenshot);
        v->hold = true; /* the image as saved: no more samples */
        if (!frame(v, 0))
            rc = DIRT_EXIT_FAILURE;
    }
    if (v->o.report && !view_write_report(v, v->o.report))
        rc = DIRT_EXIT_FAILURE;
    if (!v->o.quiet) {
        const char *path = v->o.num_scenes ? v->o.scenes[0] : "";
        char cam[1024], args[4096];
        view_camera_args(v, cam, sizeof(cam));
        view_render_args(v, args, sizeof(args));
        fprintf(stderr, "%s: %d samples; camera: %s\n%s: the same image offline: dirt-render %s%s"
                "%s --spp %d -o OUT.exr\n", PROG, dirt_session_samples(v->s),
                cam[0] ? cam : "(default)", PROG, path, path[0] ? " " : "", args,
                dirt_session_samples(v->s));
    }
    return rc;
}

/* The window, the scene's sessions and the frame loop. The exit status. */
static int run(viewer *v, dirt_scene *scene)
{
    v->gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = v->o.window[0],
                                              .height = v->o.window[1], .title = "dirt-view",
                                              .cpu_timing = v->o.cpu_timing});
    if (!v->gpu) {
        dirt_scene_destroy(scene);
        cli_error(PROG, "no window with an OpenGL 4.5 context could be made (see the error "
                  "above; under no display, run it with xvfb-run)");
        return DIRT_EXIT_NO_GPU;
    }
    if (!(v->ui = dirt_ui_create(v->gpu))) {
        dirt_scene_destroy(scene);
        return DIRT_EXIT_NO_GPU;
    }
    dirt_window_input in;
    dirt_gpu_window_poll(v->gpu);
    dirt_gpu_window_input(v->gpu, &in);
    v->win_w = in.width;
    v->win_h = in.height;
    if (v->o.scale == 0 && v->o.s.width <= 0 && software_renderer(v->gpu)) {
        v->auto_scale = true;
        v->pace_ms = ASSUMED_PACE_MS;
        choose_scale(v, in.width, in.height, "assumed");
    } else if (v->o.scale == 0) {
        v->o.scale = 1;
    }
    view_render_size(v, in.width, in.height);
    if (!view_load_scene(v, scene, v->o.num_scenes ? v->o.scenes[0] : NULL))
        return DIRT_EXIT_FAILURE;
    v->applied_clip = v->o.clip;
    if (!v->o.quiet) {
        char desc[256];
        dirt_gpu_describe(v->gpu, desc, sizeof(desc));
        fprintf(stderr, "%s: %s, %zu triangles; %s; F1 lists the key bindings\n", PROG,
                v->scene_name, dirt_scene_num_triangles(v->scene), desc);
    }
    /* Test hook: every frame takes this much longer (a deliberately slow
     * frame, for the input that arrives during one). */
    const char *slow = getenv("DIRT_VIEW_SLOW_FRAME_MS");
    v->slow_frame_ms = slow ? atoi(slow) : 0;
    /* Test hook: a line per frame shown (log_frame), for a latency probe. */
    const char *flog = getenv("DIRT_VIEW_FRAME_LOG");
    if (flog && *flog && !(v->frame_log = fopen(flog, "w"))) {
        cli_error(PROG, "DIRT_VIEW_FRAME_LOG: cannot write %s", flog);
        return DIRT_EXIT_USAGE;
    }
    double last = dirt_clock_ms();
    while (!v->quit) {
        double now = dirt_clock_ms();
        double dt = (now - last) / 1000.0;
        last = now;
        if (dt > 0.25)
            dt = 0.25; /* a slow frame does not throw the camera across the scene */
        if (!frame(v, dt))
            return DIRT_EXIT_FAILURE;
    }
    return finish(v);
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    setvbuf(stderr, NULL, _IOLBF, 0);
    viewer *v = calloc(1, sizeof(*v));
    if (!v)
        return DIRT_EXIT_FAILURE;
    app_opts_init(&app_view_program, &v->o);
    int rc = app_parse(&app_view_program, argc, argv, &v->o);
    dirt_scene *scene = NULL;
    if (rc == APP_PARSE_OK && v->o.help) {
        app_print_help(&app_view_program, stdout);
    } else if (rc == APP_PARSE_OK && v->o.bindings) {
        for (size_t i = 0; i < view_num_bindings; i++)
            printf("%-24s %s\n", view_bindings[i][0], view_bindings[i][1]);
    } else if (rc == APP_PARSE_OK && v->o.version) {
        rc = app_version(PROG, &v->o);
    } else if (rc == APP_PARSE_OK && (rc = prepare(v, &scene)) == DIRT_EXIT_OK) {
        app_provenance_init(&v->prov, argc, argv, v->o.num_scenes ? v->o.scenes[0] : NULL);
        rc = run(v, scene);
    } else {
        dirt_scene_destroy(scene);
    }
    if (v->frame_log)
        fclose(v->frame_log);
    dirt_gpu_texture_destroy(v->gpu, v->aux_tex);
    dirt_gpu_texture_destroy(v->gpu, v->ref_tex);
    dirt_image_destroy(v->ref);
    dirt_session_destroy(v->pre);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->s);
    dirt_ui_destroy(v->ui);
    dirt_gpu_destroy(v->gpu);
    dirt_env_destroy(v->env);
    dirt_env_destroy(v->env_old);
    dirt_scene_destroy(v->scene);
    vs_free(&v->script);
    app_opts_free(&v->o);
    free(v);
    if (rc == DIRT_EXIT_USAGE)
        seq_remove_made_dirs(); /* a refused run leaves no directory it made */
    seq_forget_made_dirs();
    return rc;
}
