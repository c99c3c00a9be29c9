/* Small command-line helpers shared by the programs. Errors are reported as
 * one line on stderr, "PROG: message", and the programs exit with
 * DIRT_EXIT_USAGE (2) for bad input. */
#ifndef DIRT_APP_CLI_H
#define DIRT_APP_CLI_H

#include <stdbool.h>

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

/* True when `path` ends with `ext` (case-insensitive, ext includes the dot). */
bool cli_has_ext(const char *path, const char *ext);

/* True when the directory that would hold `path` exists and is writable.
 * Prints the reason when not. */
bool cli_output_dir_ok(const char *prog, const char *path);

#endif
