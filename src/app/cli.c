#include "app/cli.h"

#include "app/sequence.h"
#include "dirt/clock.h"
#include "dirt/file.h"

#include <errno.h>
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
    if (!quiet)
        printf("wrote %s\n", path);
    if (png_preview) {
        char png[4200];
        cli_png_beside(path, png, sizeof(png));
        if (!dirt_image_write_png(img, png, &wo->png)) {
            cli_error(prog, "could not write '%s'", png);
            return false;
        }
        if (!quiet)
            printf("wrote %s\n", png);
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
