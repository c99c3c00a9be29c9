/* Small command-line helpers shared by the programs. Errors are reported as
 * one line on stderr, "PROG: message", and the programs exit with
 * DIRT_EXIT_USAGE (2) for bad input. */
#ifndef DIRT_APP_CLI_H
#define DIRT_APP_CLI_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/image.h"
#include "dirt/scene.h"

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

/* ---- what a run reads and writes (dirt/input.h) ----------------------- */

#define CLI_IO_MAX 16

/* The files of one run, for cli_check_io. Unused entries are NULL. */
typedef struct cli_io {
    const char *scene_path;          /* as given; NULL for the default scene */
    const dirt_scene *scene;         /* loaded: the files it read are inputs */
    const char *in[CLI_IO_MAX][2];   /* {path, role ("--env")}: other inputs */
    const char *in_frames[2];        /* {pattern, role}: an input per frame
                                        (--mse-reference), each must exist */
    const char *out_frames;          /* the output pattern: a file per frame */
    bool out_png;                    /* and a PNG preview beside each */
    const long *frames;              /* the frames of the in/out patterns */
    size_t num_frames;
    const char *out[CLI_IO_MAX][2];  /* {path, role}: other outputs */
    const char *out_dirs[4][3];      /* {folder, name prefix, role}: folders the
                                        run writes `prefix`* files into */
} cli_io;

/* Checks a run's files before anything is written: every input of an
 * input pattern exists as a regular file (MISSING, NOT_REGULAR), and no
 * output is an input (the same file: its name, a hard or symbolic link;
 * COLLISION) or another output. Returns DIRT_EXIT_OK, or DIRT_EXIT_USAGE
 * after printing "prog: ID: reason". */
int cli_check_io(const char *prog, const cli_io *io);

/* The one line a failed scene load prints: "prog: cannot load scene 'x':
 * ID (what it means; see the error above)", the id of
 * dirt_scene_last_error(). */
void cli_scene_error(const char *prog, const char *path);

/* Checks the camera a run will use before anything is made, exit status
 * DIRT_EXIT_USAGE after printing why (else DIRT_EXIT_OK): an explicit
 * camera (`look`, when look_set) whose eye is its target or whose up is
 * parallel to its view; a scene camera (`camera` >= 0, or camera 0 when it
 * is -1 and the scene has one) whose aspect makes the image, `width` wide,
 * taller than 16384 or under 1 pixel when `height` is 0 (not given); an
 * orthographic scene camera with the dirt or mmrt engine and a camera view
 * (`camera_view`: views that include it). */
int cli_check_camera(const char *prog, const dirt_scene *scene, int camera, bool look_set,
                     const dirt_camera_look *look, int width, int height, bool raster_engine,
                     bool camera_view);

/* Appends one line (`n` bytes, ending in '\n') to the log open on `fd`
 * (O_APPEND) with one write(2), so that lines of workers sharing a log do
 * not interleave; a write that fails part way (a full disk) is undone
 * (the file is cut back to its size before it, unless another writer
 * appended meanwhile), so the log never ends in a partial line. False
 * when the line is not in the log. */
bool cli_log_append(int fd, const char *line, size_t n);

#endif
