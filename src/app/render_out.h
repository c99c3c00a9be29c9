/* What a dirt-render run writes: every output location proven creatable
 * before any work, and kept apart from every input (the scene and the
 * files it read, --env, every frame's --mse-reference); each frame's image
 * (and PNG preview) with its provenance in the EXR header, its stats
 * record, its line of the --log and its error against --mse-reference; at
 * the end the --log summary, --graph-dot and --stats (with the run's
 * provenance). All or nothing: a one-frame run's files go when the run
 * fails later; a failed run leaves no directory it made and no log it
 * made empty; a log line is written whole or not at all. */
#ifndef DIRT_APP_RENDER_OUT_H
#define DIRT_APP_RENDER_OUT_H

#include <stdbool.h>
#include <stdio.h>

#include "app/options.h"
#include "app/provenance.h"
#include "app/render_seq.h"
#include "dirt/session.h"

typedef struct render_out {
    const char *prog;
    const app_opts *o;
    app_provenance prov;
    int log;                     /* --log open O_APPEND, or -1 */
    bool log_made;               /* this run made the log file */
    dirt_session_stats *frames;  /* one record per frame rendered */
    size_t count;
    char written[2][RENDER_PATH_MAX]; /* a one-frame run's files */
    int num_written;
    bool one_frame;
} render_out;

/* Checks that every output of the run can be made (the first frame's
 * files, --stats, --graph-dot, --log, --debug-ads). False after printing
 * why. */
bool render_out_open(render_out *w, const char *prog, const app_opts *o, const render_seq *q,
                     int argc, char **argv);

/* Before anything is written, with the scene loaded: every input exists
 * as a regular file (each frame's --mse-reference: MISSING,
 * NOT_REGULAR), no output (the files of every frame of --frames, their
 * PNG previews, --stats, --graph-dot, --log, the --debug-ads pictures) is
 * an input or another output (COLLISION), and the camera is one the
 * engine can render (cli_check_camera); then opens the log. The exit
 * status: DIRT_EXIT_OK, or DIRT_EXIT_USAGE after printing "PROG: ID: why". */
int render_out_start(render_out *w, const dirt_scene *scene);

/* Writes a rendered frame: `files` from the session's image, the log
 * line, the frame's record. DIRT_EXIT_OK, or the exit status after
 * printing why (DIRT_EXIT_FAILURE: no image; DIRT_EXIT_USAGE: a reference
 * that cannot be read or compared with, an output that cannot be
 * written). */
int render_out_frame(render_out *w, dirt_session *s, long frame, char files[2][RENDER_PATH_MAX],
                     int nfiles);

/* The end of a run that rendered `q`'s frames: the log's summary,
 * --graph-dot and --stats. False after printing why. */
bool render_out_finish(render_out *w, const dirt_session *s, const render_seq *q);

/* Closes the log; with !ok a one-frame run's files, a log this run made
 * that is still empty and the directories it made are removed. */
void render_out_close(render_out *w, bool ok);

#endif
