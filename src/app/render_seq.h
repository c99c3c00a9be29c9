/* dirt-render's frames: which frames this worker renders (--frames, one
 * frame at --time, the share of --chunk), the files of each, the ones
 * skipped (complete, or claimed by another worker with --placeholders),
 * claims kept fresh while a frame renders, and progress with an ETA. */
#ifndef DIRT_APP_RENDER_SEQ_H
#define DIRT_APP_RENDER_SEQ_H

#include <stdbool.h>
#include <stddef.h>

#include "app/cli.h"
#include "app/options.h"
#include "app/sequence.h"

#define RENDER_PATH_MAX 4200

typedef struct render_seq {
    const char *prog;
    const app_opts *o;
    seq_frames frames;          /* to render, in order (owned) */
    bool sequence;              /* --frames: else one frame, numbered 0 */
    size_t next;                /* index of the next frame to consider */
    size_t rendered, skipped;
    seq_claim claim;
    double start;               /* dirt_clock_ms */
    cli_progress progress;      /* of the frame being rendered */
} render_seq;

/* The frames of `o` (its share with --chunk). False after printing why. */
bool render_seq_init(render_seq *q, const char *prog, const app_opts *o);
void render_seq_free(render_seq *q);

/* The files of `frame`: the image, and its PNG preview with --png. */
int render_seq_files(const render_seq *q, long frame, char files[2][RENDER_PATH_MAX]);

/* Removes the temporary files dead writers left, once per output
 * directory of the frames. */
void render_seq_clean(render_seq *q);

/* The next frame to render (claimed with --placeholders): 1 with *frame,
 * its files and their count (its directory made), 0 when none is left,
 * -1 after printing why (a claim or a directory that cannot be made). */
int render_seq_next(render_seq *q, long *frame, char files[2][RENDER_PATH_MAX], int *nfiles);

/* A dirt_session_add_samples progress callback (user: the render_seq):
 * prints the frame's progress and keeps its claim fresh. */
void render_seq_progress(void *user, int done, int total);

/* The frame is written: its claim goes, the progress of the sequence is
 * printed. */
void render_seq_done(render_seq *q, long frame, const char *file);

/* The time and seed of `frame` (--animated-seed mixes the seed with it). */
double render_seq_time(const render_seq *q, long frame);
uint32_t render_seq_seed(const render_seq *q, long frame);

#endif
