/* dirt-view's scripted mode: a text file of timed actions, one per line,
 * parsed whole before the window opens (a bad script exits 2 up front).
 *
 *   # comment                       blank lines and comments are skipped
 *   wait-frames N                   let N frames pass
 *   wait-samples N                  until the image holds N samples
 *   wait-file PATH                  until PATH exists (another program's cue)
 *   orbit YAW PITCH                 degrees about the target
 *   pan DX DY                       view heights
 *   dolly FACTOR                    distance to the target times FACTOR
 *   fly FORWARD RIGHT UP            scene units
 *   camera I | auto | default       the scene's camera I, the automatic one
 *   key NAME [FRAMES]               hold a key (gl/window.h names, with Ctrl+,
 *                                   Shift+ or Alt+ before it) N frames (1)
 *   click X Y                       left click at window pixel X, Y
 *   zoom Z [X Y] | zoom fit         Z window pixels per image pixel, keeping the
 *                                   image point at window pixel X, Y (the centre)
 *   pan-image DX DY                 move the image by window pixels
 *   bookmark save|go|delete N       camera bookmark N (1 .. 9)
 *   set OPTION VALUE                a command-line option without "--"
 *                                   (flags take on/off)
 *   resize W H                      the window's size
 *   screenshot FILE.png             the window, panels included, as this frame
 *                                   shows it (the next actions run next frame)
 *   save-image FILE.exr|.png        the render alone (an .exr gets a .png beside it)
 *   report FILE.json                camera, sizes, samples, panels
 *   print-camera                    the camera as dirt-render options, on stdout
 *   quit                            exit 0
 */
#ifndef DIRT_APP_VIEW_SCRIPT_H
#define DIRT_APP_VIEW_SCRIPT_H

#include <stdbool.h>
#include <stddef.h>

enum vs_kind {
    VS_WAIT_FRAMES, VS_WAIT_SAMPLES, VS_WAIT_FILE, VS_ORBIT, VS_PAN, VS_DOLLY, VS_FLY, VS_CAMERA,
    VS_KEY, VS_CLICK, VS_SET, VS_RESIZE, VS_SCREENSHOT, VS_SAVE_IMAGE, VS_REPORT,
    VS_PRINT_CAMERA, VS_QUIT, VS_ZOOM, VS_PAN_IMAGE, VS_BOOKMARK,
};

typedef struct vs_action {
    enum vs_kind kind;
    int line;            /* 1-based line in the file */
    double num[3];       /* numbers of the action */
    char name[64];       /* set: option; key: key name; camera: "auto"/"default"/"";
                            zoom: "fit" or ""; bookmark: save, go, delete */
    char text[4096];     /* set: value; wait-file, screenshot, save-image, report: path */
} vs_action;

typedef struct view_script {
    vs_action *actions;
    size_t count;
} view_script;

/* Parses `text`. False with "line N: why" in `why` on the first bad line. */
bool vs_parse(const char *text, view_script *out, char *why, size_t size);
/* Reads and parses a file: a regular file (a FIFO, device or directory
 * fails at once, "NOT_REGULAR: ..."), at most 64 MiB ("TOO_LARGE: ..."), of
 * text. False with the reason in `why`, led by its id (dirt/input.h) when
 * the file cannot be read. */
bool vs_load(const char *path, view_script *out, char *why, size_t size);
/* The files the script's actions write (screenshot, save-image and the PNG
 * beside an .exr, report), at most `max` into `out` (pointers into `s`'s
 * actions, or into `png`, `max` buffers of 4200 bytes for the PNGs);
 * returns how many. */
size_t vs_outputs(const view_script *s, const char **out, char (*png)[4200], size_t max);
/* Accepts an empty script. */
void vs_free(view_script *s);

#endif
