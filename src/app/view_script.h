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
 *   key NAME [FRAMES]               hold a key (dirt/window.h names) N frames (1)
 *   click X Y                       left click at window pixel X, Y
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
    VS_PRINT_CAMERA, VS_QUIT,
};

typedef struct vs_action {
    enum vs_kind kind;
    int line;            /* 1-based line in the file */
    double num[3];       /* numbers of the action */
    char name[64];       /* set: option; key: key name; camera: "auto"/"default"/"" */
    char text[4096];     /* set: value; wait-file, screenshot, save-image, report: path */
} vs_action;

typedef struct view_script {
    vs_action *actions;
    size_t count;
} view_script;

/* Parses `text`. False with "line N: why" in `why` on the first bad line. */
bool vs_parse(const char *text, view_script *out, char *why, size_t size);
/* Reads and parses a file. False with the reason in `why`. */
bool vs_load(const char *path, view_script *out, char *why, size_t size);
/* Accepts an empty script. */
void vs_free(view_script *s);

#endif
