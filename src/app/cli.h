/* Small command-line helpers shared by the programs. Errors are reported as
 * one line on stderr, "PROG: message", and the programs exit with
 * DIRT_EXIT_USAGE (2) for bad input. */
#ifndef DIRT_APP_CLI_H
#define DIRT_APP_CLI_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/image.h"

enum {
    DIRT_EXIT_OK = 0,
    DIRT_EXIT_FAILURE = 1, /* a render or write failed at run time */
    DIRT_EXIT_USAGE = 2,   /* bad option, unreadable/malformed input, unwritable output */
    DIRT_EXIT_NO_GPU = 3,  /* no OpenGL 4.5 context could be made */
};

/* Prints "prog: <message>\n" to stderr. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void cli_error(const char *prog, const char *fmt, ...);

/* Strict number parsing: the whole string must be a number in [lo, hi].
 * On failure prints "prog: OPTION expects ..." and returns false. */
bool cli_int(const char *prog, const char *option, const char *text, long lo, long hi,
             long *out);
bool cli_float(const char *prog, const char *option, const char *text, double lo, double hi,
               double *out);

/* Parses the value `val` of `option` by `kind` into `dst`: 's' a string
 * (const char *), 'i' int, 'l' long, 'u' uint32_t (integers in [lo, hi]),
 * 'd' double, 'f' float (in [lo, hi]), 'c' the index (int) of `val` in the
 * NULL-terminated `names` ("" entries are skipped), 'j' / 'g' a path that
 * must end in .json / .dot, 'b' three non-negative floats "R,G,B" (float[3]),
 * 'v' three finite floats "X,Y,Z" (float[3]).
 * Other kinds are left to the caller (true). On
 * failure prints "prog: ..." and returns false. */
bool cli_value(const char *prog, const char *option, const char *val, char kind, void *dst,
               double lo, double hi, const char *const *names);

/* True when `path` ends with `ext` (case-insensitive, ext includes the dot). */
bool cli_has_ext(const char *path, const char *ext);


/* The PNG preview's name beside `path`: its 4-letter extension (".exr")
 * replaced by ".png". */
void cli_png_beside(const char *path, char *buf, size_t size);

/* Writes `img` to `path` (.exr or .png, atomically) and, with `png_preview`,
 * a PNG beside it (path with .png for its 4-letter extension); prints each
 * file written unless `quiet`. False after printing why. */
bool cli_write_image(const char *prog, const dirt_image *img, const char *path,
                     const dirt_image_write_options *wo, bool png_preview, bool quiet);

/* Progress of a frame's samples on stderr, at most once a second (and at
 * the end): a callback for dirt_session_add_samples with a cli_progress. */
typedef struct cli_progress {
    const char *prog;
    double start, last;       /* dirt_clock_ms */
    long frame;
    bool quiet;
} cli_progress;
void cli_progress_sample(void *user, int done, int total);

/* Makes `path` creatable now: its directories are created and its
 * temporary file is made and removed (proof that the write will not fail
 * for permissions or a missing directory, unlike access(2) as root). False
 * after printing why. */
bool cli_creatable(const char *prog, const char *path);

#endif
