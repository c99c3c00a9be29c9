/* dirt-render: renders one frame or a frame range of a scene headless, on
 * the render session (dirt/session.h). Its options are the shared table's
 * (options.h; what it accepts: programs.c), its frames come from
 * render_seq.h, its outputs go through render_out.h. */
#include <stdio.h>
#include <string.h>

#include "app/cli.h"
#include "app/options.h"
#include "app/render_out.h"
#include "app/render_seq.h"
#include "app/setup.h"
#include "dirt/file.h"
#include "dirt/env.h"
#include "dirt/log.h"
#include "dirt/session.h"

#define PROG "dirt-render"

/* dirt-render's own checks across options; warns about options that do
 * nothing here. False after printing why. */
static bool check_options(const app_opts *o)
{
    const dirt_session_opts *s = &o->s;
    bool many = o->frames.count > 1;
    if (o->info)
        return true;
    int fields = o->output ? seq_pattern_fields(o->output) : 0;
    bool png_out = o->output && (cli_has_ext(o->output, ".png") || o->png);
    if (!o->output) {
        cli_error(PROG, "no output given: use -o OUT.exr or -o OUT.png (see --help)");
    } else if (!cli_has_ext(o->output, ".exr") && !cli_has_ext(o->output, ".png")) {
        cli_error(PROG, "output '%s' must end in .exr or .png", o->output);
    } else if (fields < 0) {
        cli_error(PROG, "output '%s' has more than one frame field, a stray '%%' or a field "
                  "wider than %d", o->output, SEQ_MAX_FIELD_WIDTH);
    } else if (many && fields != 1) {
        cli_error(PROG, "--frames renders several images: the output '%s' needs one frame "
                  "field such as frame_####.exr or frame_%%04d.exr", o->output);
    } else if (!app_check(&app_render_program, o)) {
        return false;
    } else if (o->debug_ads && many) {
        cli_error(PROG, "--debug-ads works on a single frame, not with --frames");
    } else if (o->png && !cli_has_ext(o->output, ".exr")) {
        cli_error(PROG, "--png needs an .exr output (the output is already a PNG)");
    } else if (o->graph_dot && s->engine != DIRT_ENGINE_DIRT && s->engine != DIRT_ENGINE_MMRT) {
        cli_error(PROG, "--graph-dot needs a path-tracing engine (dirt or mmrt)");
    } else if ((o->chunk || o->placeholders) && !o->frames.count) {
        cli_error(PROG, "--chunk and --placeholders share out --frames: give a frame list");
    } else {
        const struct { bool idle; const char *what; } warn[] = {
            {(o->given[APP_OPT_EXPOSURE] || o->given[APP_OPT_TONEMAP]) && !png_out,
             "--exposure and --tonemap only change PNG output"},
            {o->given[APP_OPT_TIME] && o->frames.count,
             "-t is ignored with --frames (time = frame / fps)"},
            {s->threads && s->engine != DIRT_ENGINE_EMBREE, "--threads is for --engine embree"},
            {(s->march || s->march_samples || s->thickness > 0) && s->engine != DIRT_ENGINE_MMRT,
             "--march, --samples and --thickness are MMRT's"},
            {s->ao_distance > 0 && s->mode != DIRT_PT_AO, "--ao-distance needs --mode ao"},
            {s->focus > 0 && !(s->aperture > 0), "--focus needs --aperture"},
            {o->animated_seed && !o->frames.count, "--animated-seed needs --frames"},
        };
        for (size_t i = 0; i < sizeof(warn) / sizeof(warn[0]); i++) {
            if (warn[i].idle && !o->quiet)
                fprintf(stderr, "%s: warning: %s\n", PROG, warn[i].what);
        }
        return true;
    }
    return false;
}

/* The structure's pictures of the frame just rendered (a DIRT session). */
static bool write_debug_ads(const app_opts *o, dirt_session *s)
{
    return dirt_session_write_debug_ads(s, o->debug_ads, o->quiet);
}

/* A session of `engine` on the command line's camera; NULL after logging. */
static dirt_session *make_session(dirt_gpu *gpu, const dirt_scene *scene, const app_opts *o,
                                  enum dirt_engine engine)
{
    dirt_session_opts so = app_session_opts(o);
    so.engine = engine;
    dirt_session *s = dirt_session_create(gpu, scene, &so);
    dirt_camera look = app_look_camera(o);
    if (s && !dirt_session_set_camera(s, app_camera_choice(o), o->camera, &look)) {
        dirt_session_destroy(s);
        s = NULL;
    }
    return s;
}

/* Renders the frames of `q` into `w`'s outputs: the exit status. */
static int render_frames(const app_opts *o, dirt_session *s, dirt_session *debug, render_seq *q,
                         render_out *w)
{
    dirt_eval_opts eval = {.clip = o->clip, .loop = o->loop};
    long frame;
    char files[2][RENDER_PATH_MAX];
    int nfiles, next;
    while ((next = render_seq_next(q, &frame, files, &nfiles)) > 0) {
        dirt_session_opts so = *dirt_session_get_opts(s);
        so.seed = render_seq_seed(q, frame);
        double t = render_seq_time(q, frame);
        if (!dirt_session_set_opts(s, &so, NULL) || !dirt_session_set_time(s, t, &eval) ||
            (debug && !dirt_session_set_time(debug, t, &eval)) ||
            !dirt_session_add_samples(s, o->spp, render_seq_progress, q))
            return DIRT_EXIT_FAILURE;
        if (o->debug_ads && !write_debug_ads(o, debug ? debug : s))
            return DIRT_EXIT_USAGE;
        int rc = render_out_frame(w, s, frame, files, nfiles);
        if (rc != DIRT_EXIT_OK)
            return rc;
        render_seq_done(q, frame, files[0]);
    }
    if (next < 0)
        return DIRT_EXIT_USAGE;
    /* From here on, only writes can fail. */
    return render_out_finish(w, s, q) ? DIRT_EXIT_OK : DIRT_EXIT_USAGE;
}

/* The whole run after the options: the exit status. */
static int run(app_opts *o, int argc, char **argv)
{
    const char *scene_path = o->num_scenes ? o->scenes[0] : NULL;
    render_seq q;
    render_out w = {.log = -1};
    dirt_scene *scene = NULL;
    dirt_env *env = NULL;
    dirt_gpu *gpu = NULL;
    dirt_session *s = NULL, *debug = NULL;
    int rc = DIRT_EXIT_USAGE;
    bool ok = render_seq_init(&q, PROG, o) && (o->info || dirt_cleanup_on_signals()) &&
              (o->info || render_out_open(&w, PROG, o, &q, argc, argv)) &&
              (scene = app_load_scene(PROG, scene_path, o));
    if (ok && o->info) {
        rc = dirt_scene_print_info(scene, stdout) ? DIRT_EXIT_OK : DIRT_EXIT_FAILURE;
        goto done;
    }
    /* Every input and output, and the camera, before anything is written. */
    if (!ok || !app_load_env(PROG, o, &env) || !app_check_scene(PROG, o, scene) ||
        render_out_start(&w, scene) != DIRT_EXIT_OK)
        goto done;
    bool debug_session = o->debug_ads && o->s.engine != DIRT_ENGINE_DIRT;
    rc = DIRT_EXIT_NO_GPU;
    if ((o->s.engine != DIRT_ENGINE_EMBREE || o->debug_ads) && !(gpu = app_gpu(PROG, o)))
        goto done;
    rc = DIRT_EXIT_FAILURE;
    if (!(s = make_session(gpu, scene, o, o->s.engine)) ||
        (debug_session && !(debug = make_session(gpu, scene, o, DIRT_ENGINE_DIRT))))
        goto done;
    char desc[256] = "CPU";
    if (gpu && o->s.engine != DIRT_ENGINE_EMBREE)
        dirt_gpu_describe(gpu, desc, sizeof(desc));
    if (!o->quiet)
        fprintf(stderr, "%s: %s, %zu triangles, engine %s; %s\n", PROG,
                scene_path ? scene_path : "default scene", dirt_scene_num_triangles(scene),
                dirt_engine_names[o->s.engine], desc);
    render_seq_clean(&q);
    rc = render_frames(o, s, debug, &q, &w);
done:
    render_out_close(&w, rc == DIRT_EXIT_OK);
    render_seq_free(&q);
    dirt_session_destroy(debug);
    dirt_session_destroy(s);
    dirt_gpu_destroy(gpu);
    dirt_env_destroy(env);
    dirt_scene_destroy(scene);
    return rc;
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    setvbuf(stderr, NULL, _IOLBF, 0);
    app_opts o;
    app_opts_init(&app_render_program, &o);
    int rc = app_parse(&app_render_program, argc, argv, &o);
    if (rc == APP_PARSE_OK && o.help)
        app_print_help(&app_render_program, stdout);
    else if (rc == APP_PARSE_OK && o.version)
        rc = app_version(PROG, &o);
    else if (rc == APP_PARSE_OK)
        rc = check_options(&o) ? run(&o, argc, argv) : DIRT_EXIT_USAGE;
    app_opts_free(&o);
    return rc;
}
