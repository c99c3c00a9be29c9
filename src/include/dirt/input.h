/* DIRT engine: what users bring and what they keep.
 *
 * Input files are read with bounds: only regular files (a FIFO, a device or
 * a directory is refused at once, without blocking), their size checked
 * against a limit before a byte is read. Paths a scene references stay in
 * the scene's folder unless the caller allows otherwise. And a run's
 * outputs are kept apart from its inputs: an output that is an input (the
 * same file, a hard or symbolic link to it) or another output is refused
 * before anything is written.
 *
 * Errors a caller tells apart are ids of one list (DIRT_INPUT_ERRORS): the
 * programs print the id's name with the message, the tests expect it. */
#ifndef DIRT_INPUT_H
#define DIRT_INPUT_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DIRT_INPUT_ERRORS(X)                                                          \
    X(OK, "ok")                                                                       \
    X(MISSING, "the file does not exist")                                             \
    X(IO, "the file cannot be opened or read")                                        \
    X(NOT_REGULAR, "not a regular file (a directory, FIFO, socket or device)")        \
    X(TOO_LARGE, "the file, or what it declares, is larger than the limit")           \
    X(TRUNCATED, "the file ends before the data it declares")                         \
    X(INVALID, "malformed content")                                                   \
    X(NO_COLOUR, "an image without colour channels (R, G, B or Y)")                   \
    X(OUTSIDE, "a path that leads outside the folder it must stay in")                \
    X(COLLISION, "an output that is one of the run's inputs or another output")

enum dirt_input_error {
#define DIRT_INPUT_ERR_ENUM_(id, msg) DIRT_INPUT_ERR_##id,
    DIRT_INPUT_ERRORS(DIRT_INPUT_ERR_ENUM_)
#undef DIRT_INPUT_ERR_ENUM_
    DIRT_INPUT_NUM_ERRORS
};

/* "NOT_REGULAR", ...: the id's name; "?" out of range. */
DIRT_API const char *dirt_input_error_name(enum dirt_input_error e);
/* "not a regular file (...)", ...; "?" out of range. */
DIRT_API const char *dirt_input_error_str(enum dirt_input_error e);

/* ---- bounded reading ------------------------------------------------------ */

/* Opens `path` for reading as a regular file of at most `max_bytes` bytes
 * (0: no limit). The open does not block (O_NONBLOCK: a FIFO without a
 * writer, a device) and never makes a terminal the controlling one; the
 * descriptor is then fstat'd, so what is checked is what was opened:
 * anything but a regular file fails with NOT_REGULAR, a larger file with
 * TOO_LARGE, before any byte is read. Returns the descriptor (blocking
 * again, close-on-exec; the caller closes it) and the file's size in *size;
 * -1 on failure with the id in *err (MISSING, IO, NOT_REGULAR, TOO_LARGE)
 * and errno kept. Nothing is logged: the caller names the file's role. */
DIRT_API int dirt_input_open(const char *path, size_t max_bytes, size_t *size,
                             enum dirt_input_error *err);

/* Reads a whole file opened as dirt_input_open does: the size fstat gave,
 * into malloc'd memory followed by one NUL byte (for text parsers; not
 * counted in *size). A file that shrinks while it is read fails (TRUNCATED);
 * bytes appended meanwhile are not read. NULL on failure with *err set,
 * nothing logged. */
DIRT_API void *dirt_input_read(const char *path, size_t max_bytes, size_t *size,
                               enum dirt_input_error *err);

/* ---- confinement ---------------------------------------------------------- */

/* Whether the file `path` (absolute, or relative to the working directory,
 * as a reference resolved against `dir` reads) stays inside the folder
 * `dir`: its path, with "." and ".." taken as written, lies under `dir`,
 * and once symbolic links are resolved (realpath) it, or the deepest part
 * of it that exists, still lies under the folder's real path. A path that
 * does not exist can be inside (a missing file is the reader's to report).
 * False when it leads outside, or when `dir` cannot be resolved. */
DIRT_API bool dirt_input_inside(const char *dir, const char *path);

/* ---- a run's inputs and outputs ------------------------------------------- */

/* The files one run reads and writes, to keep them apart. */
typedef struct dirt_run_files dirt_run_files;

DIRT_API dirt_run_files *dirt_run_files_create(void);
/* Accepts NULL. */
DIRT_API void dirt_run_files_destroy(dirt_run_files *f);

/* Records an input: the file `path` (its device and inode, and its real
 * path). `what` names its role in messages ("the scene", "--env"); both
 * strings are copied. A path that does not exist is not recorded (true):
 * reading it fails on its own. False only when out of memory (logged). */
DIRT_API bool dirt_run_files_input(dirt_run_files *f, const char *path, const char *what);

/* Records an output and checks it against the inputs recorded so far: when
 * it is one of them (the same device and inode: the file itself, a hard
 * link, a symbolic link to it) returns COLLISION with the reason in `why`.
 * Outputs are compared with each other by dirt_run_files_check. OK, or
 * COLLISION; IO when out of memory. Nothing is logged. */
DIRT_API enum dirt_input_error dirt_run_files_output(dirt_run_files *f, const char *path,
                                                     const char *what, char *why,
                                                     size_t size);

/* Records a folder the run writes files named `prefix`* into: an input in
 * it whose name starts with `prefix` collides (COLLISION, reason in
 * `why`). */
DIRT_API enum dirt_input_error dirt_run_files_output_dir(dirt_run_files *f, const char *dir,
                                                         const char *prefix, const char *what,
                                                         char *why, size_t size);

/* Checks everything recorded: every output against every input (again:
 * inputs recorded after an output count too) and the outputs against each
 * other (two that name the same file: the same real folder and name).
 * OK, or COLLISION with the first reason in `why`. */
DIRT_API enum dirt_input_error dirt_run_files_check(dirt_run_files *f, char *why,
                                                    size_t size);

#ifdef __cplusplus
}
#endif
#endif
