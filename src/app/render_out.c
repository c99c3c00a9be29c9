/* What a dirt-render run writes (render_out.h). */
#include "app/render_out.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/cli.h"
#include "dirt/clock.h"
#include "dirt/input.h"

bool render_out_open(render_out *w, const char *prog, const app_opts *o, const render_seq *q,
                     int argc, char **argv)
{
    memset(w, 0, sizeof(*w));
    w->log = -1;
    w->prog = prog;
    w->o = o;
    w->one_frame = !q->sequence;
    app_provenance_init(&w->prov, argc, argv, o->num_scenes ? o->scenes[0] : NULL);
    char files[2][RENDER_PATH_MAX];
    int n = render_seq_files(q, q->frames.count ? q->frames.frames[0] : 0, files);
    for (int i = 0; i < n; i++) {
        if (!cli_creatable(prog, files[i]))
            return false;
    }
    const char *more[] = {o->stats, o->graph_dot, o->log};
    for (int i = 0; i < 3; i++) {
        if (more[i] && !cli_creatable(prog, more[i]))
            return false;
    }
    if (o->debug_ads) {
        char probe[RENDER_PATH_MAX];
        snprintf(probe, sizeof(probe), "%s/ads.png", o->debug_ads);
        if (!cli_creatable(prog, probe))
            return false;
    }
    w->frames = calloc(q->frames.count ? q->frames.count : 1, sizeof(*w->frames));
    if (!w->frames) {
        cli_error(prog, "out of memory");
        return false;
    }
    return true;
}

int render_out_start(render_out *w, const dirt_scene *scene)
{
    const app_opts *o = w->o;
    const char *prog = w->prog;
    /* The files of every frame of the range (not only this worker's
     * share), or of the one frame. */
    long one = 0;
    const long *frames = o->frames.count ? o->frames.frames : &one;
    size_t num_frames = o->frames.count ? o->frames.count : 1;
    bool env_file = o->env_path && strcmp(o->env_path, "sky");
    cli_io io = {.scene_path = o->num_scenes ? o->scenes[0] : NULL,
                 .scene = scene,
                 .in = {{env_file ? o->env_path : NULL, "--env"}},
                 .in_frames = {o->mse_reference, "--mse-reference"},
                 .out_frames = o->output,
                 .out_png = o->png,
                 .frames = frames,
                 .num_frames = num_frames,
                 .out = {{o->stats, "--stats"}, {o->graph_dot, "--graph-dot"}, {o->log, "--log"}},
                 .out_dirs = {{o->debug_ads, "ads_", "--debug-ads"}}};
    if (io.scene_path && !strcmp(io.scene_path, "default"))
        io.scene_path = NULL;
    const dirt_session_opts *s = &o->s;
    int rc = cli_check_io(prog, &io);
    if (rc == DIRT_EXIT_OK)
        rc = cli_check_camera(prog, scene, o->auto_camera ? -2 : o->camera,
                              app_camera_choice(o) == DIRT_CAMERA_EXPLICIT, &o->look, s->width,
                              s->height,
                              s->engine == DIRT_ENGINE_RASTER || s->engine == DIRT_ENGINE_EMBREE,
                              s->views != DIRT_SESSION_VIEWS_CUBE);
    if (rc != DIRT_EXIT_OK || !o->log)
        return rc;
    w->log = open(o->log, O_WRONLY | O_APPEND | O_CLOEXEC);
    if (w->log < 0 && errno == ENOENT)
        w->log_made = (w->log = open(o->log, O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC,
                                     0644)) >= 0;
    if (w->log < 0) {
        cli_error(prog, "cannot append to '%s': %s", o->log, strerror(errno));
        return DIRT_EXIT_USAGE;
    }
    return DIRT_EXIT_OK;
}

/* Appends one line to the JSON Lines log, whole or not at all
 * (cli_log_append: one write(2), so lines of workers sharing a log do not
 * interleave). */
static bool log_line(render_out *w, cJSON *rec)
{
    char *text = rec ? cJSON_PrintUnformatted(rec) : NULL;
    size_t n = text ? strlen(text) : 0;
    char *line = text ? realloc(text, n + 2) : NULL;
    if (line) {
        line[n] = '\n';
        line[n + 1] = 0;
    }
    bool ok = line && cli_log_append(w->log, line, n + 1);
    free(line ? line : text);
    cJSON_Delete(rec);
    if (!ok)
        cli_error(w->prog, "cannot append to '%s'", w->o->log);
    return ok;
}

/* MSE and relative MSE of the beauty against the reference of `frame`. */
static bool compare_reference(render_out *w, long frame, const dirt_image *img,
                              dirt_image_error *e)
{
    char path[RENDER_PATH_MAX];
    seq_frame_path(w->o->mse_reference, frame, path, sizeof(path));
    enum dirt_input_error err = DIRT_INPUT_ERR_OK;
    dirt_image *ref = dirt_image_read(path, NULL, &err);
    bool ok = ref && dirt_image_compare(img, ref, e);
    if (!ok)
        cli_error(w->prog, "%s: cannot compare with the reference '%s' (see above)",
                  dirt_input_error_name(ref ? DIRT_INPUT_ERR_INVALID : err), path);
    dirt_image_destroy(ref);
    return ok;
}

int render_out_frame(render_out *w, dirt_session *s, long frame, char files[2][RENDER_PATH_MAX],
                     int nfiles)
{
    const app_opts *o = w->o;
    const dirt_image *img = dirt_session_image(s);
    dirt_image_error err = {0};
    if (!img)
        return DIRT_EXIT_FAILURE;
    if (o->mse_reference && !compare_reference(w, frame, img, &err))
        return DIRT_EXIT_USAGE; /* a reference that is not one: bad input */
    dirt_session_stats *fs = &w->frames[w->count++];
    *fs = *dirt_session_get_stats(s);
    size_t na;
    const dirt_image_attr *attrs = app_provenance_attrs(&w->prov, fs, true, &na);
    dirt_image_write_options wo = {
        .exr = {.attrs = attrs, .num_attrs = na},
        .png = {.exposure = o->exposure, .tonemap = (enum dirt_tonemap)o->tonemap}};
    if (!cli_write_image(w->prog, img, files[0], &wo, o->png, o->quiet))
        return DIRT_EXIT_USAGE;
    for (int k = 0; w->one_frame && k < nfiles; k++)
        memcpy(w->written[w->num_written++], files[k], RENDER_PATH_MAX);
    if (!o->quiet && fs->engine != DIRT_ENGINE_RASTER)
        fprintf(stderr, "%s: frame %ld: build %.1f ms, trace %.1f ms, fetch %.1f ms, shade "
                "%.1f ms, %llu rays (%.2f Mrays/s)%s\n", w->prog, frame, fs->build_ms,
                fs->trace_ms, fs->fetch_ms, fs->shade_ms, (unsigned long long)fs->rays,
                fs->mrays_per_s, fs->aborted ? ", SOME RAYS ABORTED" : "");
    if (o->mse_reference && !o->quiet)
        fprintf(stderr, "%s: frame %ld: MSE %.6g, relative MSE %.6g against the reference\n",
                w->prog, frame, err.mse, err.rel_mse);
    if (w->log < 0)
        return DIRT_EXIT_OK;
    cJSON *rec = dirt_session_stats_json(fs);
    const dirt_camera *cam = dirt_session_camera(s);
    cJSON_AddNumberToObject(rec, "frame", (double)frame);
    cJSON_AddStringToObject(rec, "file", files[0]);
    cJSON *c = cJSON_AddObjectToObject(rec, "camera");
    cJSON_AddItemToObject(c, "eye", cJSON_CreateFloatArray(cam->eye, 3));
    cJSON_AddItemToObject(c, "forward", cJSON_CreateFloatArray(cam->forward, 3));
    cJSON_AddNumberToObject(c, "yfov", cam->yfov);
    if (o->mse_reference) {
        cJSON_AddNumberToObject(rec, "mse", err.mse);
        cJSON_AddNumberToObject(rec, "rel_mse", err.rel_mse);
    }
    return log_line(w, rec) ? DIRT_EXIT_OK : DIRT_EXIT_USAGE;
}

bool render_out_finish(render_out *w, const dirt_session *s, const render_seq *q)
{
    const app_opts *o = w->o;
    if (w->log >= 0) {
        cJSON *sum = cJSON_CreateObject();
        cJSON *in = cJSON_AddObjectToObject(sum, "summary");
        cJSON_AddNumberToObject(in, "frames", (double)q->frames.count);
        cJSON_AddNumberToObject(in, "rendered", (double)q->rendered);
        cJSON_AddNumberToObject(in, "skipped", (double)q->skipped);
        cJSON_AddNumberToObject(in, "wall_ms", dirt_clock_ms() - q->start);
        if (!log_line(w, sum))
            return false;
    }
    if (!o->quiet && q->skipped)
        fprintf(stderr, "%s: %zu frame(s) rendered, %zu skipped (complete or claimed)\n", w->prog,
                q->rendered, q->skipped);
    if (!w->count)
        return true;
    if (o->graph_dot) {
        if (!dirt_session_write_graph_dot(s, o->graph_dot)) {
            cli_error(w->prog, "could not write '%s'", o->graph_dot);
            return false;
        }
        if (!o->quiet)
            printf("wrote %s\n", o->graph_dot);
    }
    if (o->stats) {
        /* The run's provenance: its seed is --seed's (each frame's own is
         * in its record). */
        dirt_session_stats run = w->frames[w->count - 1];
        run.seed = o->s.seed;
        size_t na;
        const dirt_image_attr *attrs = app_provenance_attrs(&w->prov, &run, false, &na);
        if (!dirt_session_write_stats_attrs(o->stats, w->frames, w->count, attrs, na)) {
            cli_error(w->prog, "could not write '%s'", o->stats);
            return false;
        }
        if (!o->quiet)
            printf("wrote %s\n", o->stats);
    }
    return true;
}

void render_out_close(render_out *w, bool ok)
{
    for (int k = 0; !ok && k < w->num_written; k++)
        unlink(w->written[k]);
    /* A failed run leaves no empty log and no directory it made. */
    struct stat st;
    if (w->log >= 0 && !ok && w->log_made && fstat(w->log, &st) == 0 && st.st_size == 0)
        unlink(w->o->log);
    if (w->log >= 0)
        close(w->log);
    if (!ok)
        seq_remove_made_dirs();
    seq_forget_made_dirs();
    free(w->frames);
    w->log = -1;
    w->frames = NULL;
}
