#include "app/cli.h"

#include "app/sequence.h"
#include "dirt/clock.h"
#include "dirt/file.h"
#include "dirt/input.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

void cli_error(const char *prog, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", prog);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

bool cli_int(const char *prog, const char *option, const char *text, long lo, long hi,
             long *out)
{
    char *end = NULL;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : 0;
    if (!text || !*text || *end || errno || v < lo || v > hi) {
        cli_error(prog, "%s expects an integer in [%ld, %ld], got '%s'", option, lo, hi,
                  text ? text : "");
        return false;
    }
    *out = v;
    return true;
}

bool cli_float(const char *prog, const char *option, const char *text, double lo, double hi,
               double *out)
{
    char *end = NULL;
    errno = 0;
    double v = text ? strtod(text, &end) : 0;
    if (!text || !*text || *end || errno || !isfinite(v) || v < lo || v > hi) {
        cli_error(prog, "%s expects a number in [%g, %g], got '%s'", option, lo, hi,
                  text ? text : "");
        return false;
    }
    *out = v;
    return true;
}

bool cli_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

bool cli_value(const char *prog, const char *option, const char *val, char kind, void *dst,
               double lo, double hi, const char *const *names)
{
    long n = 0;
    double d = 0;
    switch (kind) {
    case 's':
        *(const char **)dst = val;
        return true;
    case 'i':
    case 'l':
    case 'u':
        if (!cli_int(prog, option, val, (long)lo, (long)hi, &n))
            return false;
        if (kind == 'i')
            *(int *)dst = (int)n;
        else if (kind == 'l')
            *(long *)dst = n;
        else
            *(uint32_t *)dst = (uint32_t)n;
        return true;
    case 'd':
    case 'f':
        if (!cli_float(prog, option, val, lo, hi, &d))
            return false;
        if (kind == 'd')
            *(double *)dst = d;
        else
            *(float *)dst = (float)d;
        return true;
    case 'c': {
        char list[256] = "";
        for (int c = 0; names[c]; c++) {
            if (!names[c][0])
                continue; /* a placeholder for a default value */
            if (!strcmp(val, names[c])) {
                *(int *)dst = c;
                return true;
            }
            size_t len = strlen(list);
            snprintf(list + len, sizeof(list) - len, "%s%s", len ? ", " : "", names[c]);
        }
        if (!strcmp(option, "--engine"))
            cli_error(prog, "unknown engine '%s' (available: %s)", val, list);
        else
            cli_error(prog, "%s expects one of %s, got '%s'", option, list, val);
        return false;
    }
    case 'j':
    case 'g': {
        const char *ext = kind == 'j' ? ".json" : ".dot";
        if (!cli_has_ext(val, ext)) {
            cli_error(prog, "%s file '%s' must end in %s", option, val, ext);
            return false;
        }
        *(const char **)dst = val;
        return true;
    }
    case 'b': {
        float *rgb = dst;
        char extra;
        bool ok = sscanf(val, "%f,%f,%f%c", &rgb[0], &rgb[1], &rgb[2], &extra) == 3;
        for (int k = 0; ok && k < 3; k++)
            ok = rgb[k] >= 0 && rgb[k] <= 1e30f;
        if (!ok)
            cli_error(prog, "%s expects R,G,B (non-negative), got '%s'", option, val);
        return ok;
    }
    case 'v': {
        float *xyz = dst;
        char extra;
        bool ok = sscanf(val, "%f,%f,%f%c", &xyz[0], &xyz[1], &xyz[2], &extra) == 3;
        for (int k = 0; ok && k < 3; k++)
            ok = isfinite(xyz[k]);
        if (!ok)
            cli_error(prog, "%s expects X,Y,Z (finite numbers), got '%s'", option, val);
        return ok;
    }
    default:
        return true; /* the caller parses the rest */
    }
}

void cli_png_beside(const char *path, char *buf, size_t size)
{
    size_t len = strlen(path);
    snprintf(buf, size, "%.*s.png", (int)(len >= 4 ? len - 4 : len), path);
}

bool cli_write_image(const char *prog, const dirt_image *img, const char *path,
                     const dirt_image_write_options *wo, bool png_preview, bool quiet)
{
    if (!dirt_image_write(img, path, wo)) {
        cli_error(prog, "could not write '%s'", path);
        return false;
    }
    if (png_preview) {
        char png[4200];
        cli_png_beside(path, png, sizeof(png));
        if (!dirt_image_write_png(img, png, &wo->png)) {
            /* The image and its preview are one output: neither stays. */
            unlink(path);
            cli_error(prog, "could not write '%s' (so '%s' is removed too)", png, path);
            return false;
        }
        if (!quiet)
            printf("wrote %s\nwrote %s\n", path, png);
    } else if (!quiet) {
        printf("wrote %s\n", path);
    }
    return true;
}

void cli_progress_sample(void *user, int done, int total)
{
    cli_progress *p = user;
    double now = dirt_clock_ms();
    if (p->quiet || (now - p->last < 1000.0 && done < total))
        return;
    p->last = now;
    double el = (now - p->start) / 1000.0;
    fprintf(stderr, "%s: frame %ld: sample %d/%d, %.1fs elapsed, ETA %.1fs\n", p->prog, p->frame,
            done, total, el, done ? el / done * (total - done) : 0.0);
}

bool cli_creatable(const char *prog, const char *path)
{
    char why[512];
    if (!seq_make_parent_dirs(path, why, sizeof(why))) {
        cli_error(prog, "%s", why);
        return false;
    }
    dirt_atomic_file *f = dirt_atomic_open(path);
    if (!f) {
        cli_error(prog, "cannot write '%s' (see the error above)", path);
        return false;
    }
    dirt_atomic_abort(f);
    return true;
}

/* ---- what a run reads and writes ---- */

static int io_fail(const char *prog, enum dirt_input_error e, const char *why)
{
    cli_error(prog, "%s: %s", dirt_input_error_name(e), why);
    return DIRT_EXIT_USAGE;
}

int cli_check_io(const char *prog, const cli_io *io)
{
    char why[8700];
    dirt_run_files *f = dirt_run_files_create();
    if (!f)
        return DIRT_EXIT_FAILURE;
    int rc = DIRT_EXIT_USAGE;
    enum dirt_input_error e = DIRT_INPUT_ERR_OK;
    bool ok = true;
    if (io->scene_path)
        ok = dirt_run_files_input(f, io->scene_path, "the scene");
    for (size_t i = 0; ok && io->scene && i < dirt_scene_num_files(io->scene); i++)
        ok = dirt_run_files_input(f, dirt_scene_file(io->scene, i), "a file of the scene");
    for (size_t i = 0; ok && i < CLI_IO_MAX; i++) {
        if (io->in[i][0])
            ok = dirt_run_files_input(f, io->in[i][0], io->in[i][1]);
    }
    char path[4200], png[4200];
    for (size_t k = 0; ok && io->in_frames[0] && k < io->num_frames; k++) {
        seq_frame_path(io->in_frames[0], io->frames[k], path, sizeof(path));
        size_t size = 0;
        int fd = dirt_input_open(path, 0, &size, &e);
        if (fd < 0) {
            snprintf(why, sizeof(why), "%s '%s' of frame %ld: %s", io->in_frames[1], path,
                     io->frames[k], dirt_input_error_str(e));
            rc = io_fail(prog, e, why);
            goto done;
        }
        close(fd);
        ok = dirt_run_files_input(f, path, io->in_frames[1]);
    }
    if (!ok) {
        rc = DIRT_EXIT_FAILURE;
        goto done;
    }
    for (size_t k = 0; io->out_frames && k < io->num_frames && !e; k++) {
        seq_frame_path(io->out_frames, io->frames[k], path, sizeof(path));
        e = dirt_run_files_output(f, path, "-o", why, sizeof(why));
        if (!e && io->out_png) {
            cli_png_beside(path, png, sizeof(png));
            e = dirt_run_files_output(f, png, "--png", why, sizeof(why));
        }
    }
    for (size_t i = 0; i < CLI_IO_MAX && !e; i++) {
        if (io->out[i][0])
            e = dirt_run_files_output(f, io->out[i][0], io->out[i][1], why, sizeof(why));
    }
    for (size_t i = 0; i < 4 && !e; i++) {
        if (io->out_dirs[i][0])
            e = dirt_run_files_output_dir(f, io->out_dirs[i][0], io->out_dirs[i][1],
                                          io->out_dirs[i][2], why, sizeof(why));
    }
    if (!e)
        e = dirt_run_files_check(f, why, sizeof(why));
    if (e) {
        rc = io_fail(prog, e, why);
        goto done;
    }
    rc = DIRT_EXIT_OK;
done:
    dirt_run_files_destroy(f);
    return rc;
}

void cli_scene_error(const char *prog, const char *path)
{
    enum dirt_scene_error e = dirt_scene_last_error();
    cli_error(prog, "cannot load scene '%s': %s (%s; see the error above)",
              path ? path : "default", dirt_scene_error_name(e), dirt_scene_error_str(e));
}

int cli_check_camera(const char *prog, const dirt_scene *scene, int camera, bool look_set,
                     const dirt_camera_look *look, int width, int height, bool raster_engine,
                     bool camera_view)
{
    if (look_set) {
        double d[3], up2 = 0, d2 = 0, c2 = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)look->target[k] - look->eye[k];
            d2 += d[k] * d[k];
            up2 += (double)look->up[k] * look->up[k];
        }
        double c[3] = {d[1] * look->up[2] - d[2] * look->up[1],
                       d[2] * look->up[0] - d[0] * look->up[2],
                       d[0] * look->up[1] - d[1] * look->up[0]};
        for (int k = 0; k < 3; k++)
            c2 += c[k] * c[k];
        if (!(d2 > 0) || !isfinite(d2)) {
            cli_error(prog, "--eye and --look-at are the same point: no view direction");
            return DIRT_EXIT_USAGE;
        }
        /* sin^2 of the angle between up and the view below 1e-8 (0.006
         * degrees): the camera's roll is undefined (the engines' fallbacks
         * would differ). */
        if (!(c2 > 1e-8 * d2 * up2)) {
            cli_error(prog, "--up %g,%g,%g is %s the view direction (--look-at - --eye): the "
                      "camera's roll is undefined; give another --up",
                      (double)look->up[0], (double)look->up[1], (double)look->up[2],
                      up2 > 0 ? "parallel to" : "zero, not");
            return DIRT_EXIT_USAGE;
        }
        return DIRT_EXIT_OK;
    }
    size_t n = scene ? dirt_scene_num_cameras(scene) : 0;
    if (camera == -1 && n > 0)
        camera = 0;
    if (camera < 0 || (size_t)camera >= n)
        return DIRT_EXIT_OK; /* automatic (or out of range: said elsewhere) */
    const dirt_camera_def *d = &dirt_scene_cameras(scene)[camera];
    if (d->type == DIRT_CAMERA_ORTHOGRAPHIC && !raster_engine && camera_view) {
        cli_error(prog, "camera %d ('%s') is orthographic: the dirt and mmrt engines' camera "
                  "view is a perspective one; use --views cube (their cube faces take any "
                  "camera), another camera, or --engine embree or raster", camera, d->name);
        return DIRT_EXIT_USAGE;
    }
    if (height <= 0 && d->type == DIRT_CAMERA_PERSPECTIVE && d->aspect > 0 && isfinite(d->aspect)) {
        double h = (double)(width > 0 ? width : 640) / d->aspect;
        if (!(h + 0.5 >= 1.0) || h + 0.5 > 16384.0) {
            cli_error(prog, "camera %d ('%s') has the aspect ratio %g: an image %d wide would "
                      "be %.0f tall (1 to 16384): give -H", camera, d->name, (double)d->aspect,
                      width > 0 ? width : 640, h);
            return DIRT_EXIT_USAGE;
        }
    }
    return DIRT_EXIT_OK;
}

bool cli_log_append(int fd, const char *line, size_t n)
{
    off_t before = lseek(fd, 0, SEEK_END);
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(fd, line + done, n - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            break;
        done += (size_t)w;
    }
    if (done == n)
        return true;
    /* Undo the part written, when nobody appended after it. */
    struct stat st;
    if (done > 0 && before >= 0 && fstat(fd, &st) == 0 &&
        st.st_size == before + (off_t)done && ftruncate(fd, before) != 0)
        fprintf(stderr, "cannot cut the log back after a failed write: %s\n", strerror(errno));
    return false;
}
