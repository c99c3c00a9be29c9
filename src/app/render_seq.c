/* dirt-render's frames (render_seq.h). */
#include "app/render_seq.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/clock.h"

bool render_seq_init(render_seq *q, const char *prog, const app_opts *o)
{
    memset(q, 0, sizeof(*q));
    q->prog = prog;
    q->o = o;
    q->sequence = o->frames.count > 0;
    size_t n = q->sequence ? o->frames.count : 1;
    q->frames.frames = malloc(n * sizeof(long));
    if (!q->frames.frames) {
        cli_error(prog, "out of memory");
        return false;
    }
    if (q->sequence)
        memcpy(q->frames.frames, o->frames.frames, n * sizeof(long));
    else
        q->frames.frames[0] = 0;
    q->frames.count = n;
    if (o->chunk) {
        long k = 0, m = 0;
        char why[512];
        bool ok = !strcmp(o->chunk, "slurm") ? seq_slurm_share(&k, &m, why, sizeof(why))
                                             : sscanf(o->chunk, "%ld/%ld", &k, &m) == 2;
        if (!ok || !seq_frames_chunk(&q->frames, k, m, why, sizeof(why))) {
            cli_error(prog, "--chunk %s: %s", o->chunk, ok ? why : "expects K/N or slurm");
            return false;
        }
        if (!o->quiet)
            fprintf(stderr, "%s: share %ld of %ld: %zu frame(s)\n", prog, k, m, q->frames.count);
    }
    q->start = dirt_clock_ms();
    return true;
}

void render_seq_free(render_seq *q)
{
    if (q->claim.held)
        seq_claim_release(&q->claim, "", false);
    seq_frames_free(&q->frames);
}

int render_seq_files(const render_seq *q, long frame, char files[2][RENDER_PATH_MAX])
{
    seq_frame_path(q->o->output, frame, files[0], RENDER_PATH_MAX);
    if (!q->o->png)
        return 1;
    cli_png_beside(files[0], files[1], RENDER_PATH_MAX);
    return 2;
}

void render_seq_clean(render_seq *q)
{
    char png_pattern[RENDER_PATH_MAX], last_dir[RENDER_PATH_MAX] = "";
    cli_png_beside(q->o->output, png_pattern, sizeof(png_pattern));
    for (size_t i = 0; i < q->frames.count; i++) {
        char f[RENDER_PATH_MAX];
        seq_frame_path(q->o->output, q->frames.frames[i], f, sizeof(f));
        char *slash = strrchr(f, '/');
        if (slash)
            *slash = '\0';
        if (!strcmp(f, last_dir) && i)
            continue;
        snprintf(last_dir, sizeof(last_dir), "%s", f);
        seq_clean_stale_temps(q->o->output, q->frames.frames[i], q->o->claim_timeout);
        if (q->o->png)
            seq_clean_stale_temps(png_pattern, q->frames.frames[i], q->o->claim_timeout);
    }
}

int render_seq_next(render_seq *q, long *frame, char files[2][RENDER_PATH_MAX], int *nfiles)
{
    const app_opts *o = q->o;
    bool shared = o->skip_existing || o->placeholders;
    char why[512];
    while (q->next < q->frames.count) {
        long f = q->frames.frames[q->next++];
        *nfiles = render_seq_files(q, f, files);
        const char *paths[2] = {files[0], files[1]};
        if (shared && seq_complete(paths, *nfiles)) {
            q->skipped++;
            continue;
        }
        if (o->placeholders) {
            if (!seq_claim_take(files[0], o->claim_timeout, &q->claim, why, sizeof(why))) {
                if (why[0]) {
                    cli_error(q->prog, "%s", why);
                    return -1;
                }
                q->skipped++; /* another worker's */
                continue;
            }
            if (seq_complete(paths, *nfiles)) { /* finished while we looked */
                seq_claim_release(&q->claim, files[0], true);
                q->skipped++;
                continue;
            }
        }
        if (!seq_make_parent_dirs(files[0], why, sizeof(why))) {
            cli_error(q->prog, "%s", why);
            return -1;
        }
        double now = dirt_clock_ms();
        q->progress = (cli_progress){.prog = q->prog, .start = now, .last = now, .frame = f,
                                     .quiet = o->quiet};
        *frame = f;
        return 1;
    }
    return 0;
}

void render_seq_progress(void *user, int done, int total)
{
    render_seq *q = user;
    cli_progress_sample(&q->progress, done, total);
    seq_claim_touch(&q->claim);
}

void render_seq_done(render_seq *q, long frame, const char *file)
{
    seq_claim_release(&q->claim, file, true);
    q->rendered++;
    size_t total = q->frames.count;
    if (q->o->quiet || total <= 1)
        return;
    double el = (dirt_clock_ms() - q->start) / 1000.0;
    size_t left = total - q->next;
    fprintf(stderr, "%s: frame %ld done (%zu of %zu; %zu rendered, %zu skipped), elapsed %.1fs, "
            "ETA %.1fs\n", q->prog, frame, q->next, total, q->rendered, q->skipped, el,
            el / (double)q->rendered * (double)left);
}

double render_seq_time(const render_seq *q, long frame)
{
    return q->sequence ? (double)frame / q->o->fps : q->o->time;
}

uint32_t render_seq_seed(const render_seq *q, long frame)
{
    uint32_t seed = q->o->s.seed;
    if (!q->o->animated_seed)
        return seed;
    /* The seed and the frame number mixed (a fixed integer hash), so every
     * frame's noise differs and reruns agree. */
    uint32_t h = seed ^ (uint32_t)frame * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    return h ^ (h >> 16);
}
