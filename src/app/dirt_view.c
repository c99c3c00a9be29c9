/* dirt-view: the interactive viewer on the render session (doc/viewer.md).
 *
 * A GLFW window with panels (gl/ui.h) over the progressive render of one
 * session, and optionally a second session on the same camera for a split
 * or difference view. Every displayed frame adds a bounded number of
 * samples (--samples-per-frame, default 1), never a whole render. This
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

/* A bounded amount of work: at most samples_per_frame samples, or the
 * raster preview while input moves the camera; none in a frame whose image
 * a script output took. False when rendering fails. */
static bool sample(viewer *v, bool *preview)
{
    int have = dirt_session_samples(v->s);
    *preview = v->moving && v->pre;
    if (*preview && !dirt_session_add_samples(v->pre, 1, NULL, NULL)) {
        view_status(v, "the raster preview failed (see the log); off");
        v->o.no_preview = true;
        *preview = false;
    }
    int target = view_target(v, v->s);
    if (!*preview && !v->hold && (target == 0 || have < target)) {
        int n = v->o.samples_per_frame;
        if (target && have + n > target)
            n = target - have;
        dirt_session_stats before = *dirt_session_get_stats(v->s);
        if (!dirt_session_add_samples(v->s, n, NULL, NULL)) {
            cli_error(PROG, "rendering failed (see the log)");
            return false;
        }
        record_passes(v, &before, have == 0);
        v->generation++;
    }
    if (!*preview && !v->hold)
        view_sample_compare(v);
    return true;
}

/* One displayed frame: input, the script, the sessions, samples, drawing,
 * panels, screenshots. False when rendering fails. */
static bool frame(viewer *v, double dt)
{
    double t0 = dirt_clock_ms();
    dirt_gpu_window_poll(v->gpu);
    dirt_window_input in;
    dirt_gpu_window_input(v->gpu, &in);
    if (in.close_requested || dirt_gpu_window_should_close(v->gpu))
        v->quit = true;
    v->win_w = in.width;
    v->win_h = in.height;
    v->cursor_x = in.mouse_x;
    v->cursor_y = in.mouse_y;
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
    for (int k = 0; k < DIRT_NUM_KEYS; k++) {
        if (v->held[k] > 0)
            v->held[k]--;
        v->pressed[k] = false;
    }
    if (v->o.play)
        play(v, dt);
    view_render_size(v, in.width, in.height);
    view_sync_sessions(v);
    if (v->click_pending)
        view_focus_at(v);
    double s0 = dirt_clock_ms();
    bool preview;
    if (!sample(v, &preview))
        return false;
    double s1 = dirt_clock_ms();
    v->hold = false;
    view_draw(v, preview);
    view_panels(v);
    dirt_ui_end_frame(v->ui);
    if (!view_take_screenshots(v)) {
        cli_error(PROG, "could not write a screenshot (see the error above)");
        v->exit_code = DIRT_EXIT_FAILURE;
    }
    dirt_gpu_window_swap(v->gpu);
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
    enum { SCRIPT_OUTS = CLI_IO_MAX - 4 };
    const char *souts[SCRIPT_OUTS] = {0};
    static char spng[SCRIPT_OUTS][4200];
    vs_outputs(&v->script, souts, spng, SCRIPT_OUTS);
    char save_png[4200] = "";
    if (v->o.save_image && cli_has_ext(v->o.save_image, ".exr"))
        cli_png_beside(v->o.save_image, save_png, sizeof(save_png));
    bool env_file = v->o.env_path && strcmp(v->o.env_path, "sky");
    cli_io io = {.scene_path = scene_path && strcmp(scene_path, "default") ? scene_path : NULL,
                 .scene = *scene,
                 .in = {{env_file ? v->o.env_path : NULL, "--env"}, {v->o.script, "--script"},
                        {v->o.compare_image, "--compare-image"}},
                 .out = {{v->o.screenshot, "--screenshot"}, {v->o.save_image, "--save-image"},
                         {save_png[0] ? save_png : NULL, "--save-image"},
                         {v->o.report, "--report"}}};
    for (size_t i = 0; i < SCRIPT_OUTS; i++)
        io.out[4 + i][0] = souts[i], io.out[4 + i][1] = "the script";
    if (cli_check_io(PROG, &io) != DIRT_EXIT_OK)
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
