/* DIRT engine: the window of a windowed dirt_gpu (dirt_gpu_opts.window):
 * its input, drawing images into it, textures of CPU images, reading it back.
 *
 * Everything here needs a GPU made with opts.window; on a headless GPU the
 * functions return false / 0 after logging. Window coordinates are
 * framebuffer pixels with the origin at the top left. */
#ifndef DIRT_WINDOW_H
#define DIRT_WINDOW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/gpu.h"
#include "dirt/types.h" /* enum dirt_tonemap */

#ifdef __cplusplus
extern "C" {
#endif

/* The keys programs bind (GLFW's key codes are not part of the API). */
enum dirt_key {
    DIRT_KEY_NONE = 0,
    DIRT_KEY_W, DIRT_KEY_A, DIRT_KEY_S, DIRT_KEY_D, DIRT_KEY_Q, DIRT_KEY_E,
    DIRT_KEY_R, DIRT_KEY_F, DIRT_KEY_P, DIRT_KEY_C, DIRT_KEY_H, DIRT_KEY_M,
    DIRT_KEY_N, DIRT_KEY_O, DIRT_KEY_V, DIRT_KEY_X, DIRT_KEY_Z,
    DIRT_KEY_0, DIRT_KEY_1, DIRT_KEY_2, DIRT_KEY_3, DIRT_KEY_4,
    DIRT_KEY_5, DIRT_KEY_6, DIRT_KEY_7, DIRT_KEY_8, DIRT_KEY_9,
    DIRT_KEY_SPACE, DIRT_KEY_ESCAPE, DIRT_KEY_ENTER, DIRT_KEY_TAB,
    DIRT_KEY_LEFT, DIRT_KEY_RIGHT, DIRT_KEY_UP, DIRT_KEY_DOWN,
    DIRT_KEY_PAGE_UP, DIRT_KEY_PAGE_DOWN, DIRT_KEY_HOME,
    DIRT_KEY_MINUS, DIRT_KEY_EQUAL, DIRT_KEY_COMMA, DIRT_KEY_PERIOD,
    DIRT_KEY_F1, DIRT_KEY_F2, DIRT_KEY_F3, DIRT_KEY_F5, DIRT_KEY_F12,
    DIRT_KEY_SHIFT, DIRT_KEY_CTRL, DIRT_KEY_ALT,
    DIRT_NUM_KEYS
};

/* Names of the keys as the viewer's script and key-binding help spell
 * them ("W", "Space", "F1", "Shift", ...); "" for DIRT_KEY_NONE. */
extern const char *const dirt_key_names[DIRT_NUM_KEYS];
/* The key of a name (case-insensitive), DIRT_KEY_NONE when unknown. */
enum dirt_key dirt_key_from_name(const char *name);

/* Modifier bits of dirt_window_input.key_mods. */
enum { DIRT_MOD_SHIFT = 1, DIRT_MOD_CTRL = 2, DIRT_MOD_ALT = 4 };

enum dirt_mouse_button { DIRT_MOUSE_LEFT = 0, DIRT_MOUSE_RIGHT, DIRT_MOUSE_MIDDLE, DIRT_MOUSE_BUTTONS };

/* What happened in the window up to the last dirt_gpu_window_poll. "Held"
 * state is the state at that poll; "pressed", "released", scroll and drops
 * are the events of that poll only (they never pile up across polls). */
typedef struct dirt_window_input {
    int width, height;                 /* framebuffer size */
    bool resized;                      /* the size changed in this poll */
    double mouse_x, mouse_y;           /* cursor in window pixels */
    double mouse_dx, mouse_dy;         /* cursor motion in this poll */
    double drag_dx[DIRT_MOUSE_BUTTONS]; /* cursor motion in this poll while that button was */
    double drag_dy[DIRT_MOUSE_BUTTONS]; /*   down: a whole drag, however short, between polls */
    bool button[DIRT_MOUSE_BUTTONS];   /* held */
    bool button_pressed[DIRT_MOUSE_BUTTONS];
    bool button_released[DIRT_MOUSE_BUTTONS];
    int double_clicks;                 /* left-button double clicks in this poll */
    double scroll;                     /* wheel steps in this poll (+ = away from the user),
                                          those with Ctrl held excepted: */
    double ctrl_scroll;                /* wheel steps with Ctrl held, in this poll */
    double ctrl_scroll_x, ctrl_scroll_y; /* the cursor at the last of them */
    double ctrl_drag_dx, ctrl_drag_dy; /* cursor motion with the left button and Ctrl held,
                                          in this poll (not in drag_dx/dy[DIRT_MOUSE_LEFT]) */
    bool key[DIRT_NUM_KEYS];           /* held */
    bool key_pressed[DIRT_NUM_KEYS];   /* went down (or repeated) in this poll */
    unsigned char key_mods[DIRT_NUM_KEYS]; /* DIRT_MOD_* held when it last went down in
                                          this poll (so Ctrl + 1 pressed and released
                                          within one slow frame still reads as such) */
    int num_drops;                     /* paths dropped on the window in this poll */
    const char *drops[8];              /* owned by the GPU, valid until the next poll */
    bool close_requested;              /* the window's close button (stays true once
                                          pressed: dirt_gpu_window_should_close) */
} dirt_window_input;

/* Windowed contexts only (false/no-op otherwise). */
bool dirt_gpu_window_should_close(dirt_gpu *gpu);
void dirt_gpu_window_swap(dirt_gpu *gpu);
void dirt_gpu_window_poll(dirt_gpu *gpu);
void dirt_gpu_window_size(dirt_gpu *gpu, int *width, int *height);

/* The input gathered by the last dirt_gpu_window_poll. */
bool dirt_gpu_window_input(dirt_gpu *gpu, dirt_window_input *out);

/* Sets the title / asks the window system for a framebuffer size (the size
 * the window reports may differ; read it back from the next input). */
bool dirt_gpu_window_set_title(dirt_gpu *gpu, const char *title);
bool dirt_gpu_window_set_size(dirt_gpu *gpu, int width, int height);

/* ---- drawing images into the window ---- */

/* Every mode ends as dirt_image_write_png does: clamp to [0, 1] (NaN -> 0),
 * sRGB transfer, round to 8 bits. The heat ramp and the luminance weights
 * are those of common/display.h. */
enum dirt_present_mode {
    DIRT_PRESENT_COLOR = 0, /* RGB * 2^exposure, tone map, sRGB (as dirt_image_write_png) */
    DIRT_PRESENT_HEAT,      /* channel `channel` mapped lo..hi to the heat ramp
                               (non-finite values black) */
    DIRT_PRESENT_SIGNED,    /* RGB * 0.5 + 0.5 (normals), no tone map, sRGB */
    DIRT_PRESENT_DIFF,      /* heat of |luminance(a) - luminance(b)| over lo..hi
                               (a = texture, b = texture_b; no split) */
};

/* One draw of an RGBA32F texture (texel (x, y) = pixel (x, y), row 0 = top)
 * into the rectangle x, y, w, h of the window (pixel centres map to texel
 * centres; nearest texel). Zero-initialised fields: colour, exposure 0,
 * clamp, no split. */
typedef struct dirt_present_opts {
    uint32_t texture;            /* GL name of the image (required) */
    uint32_t texture_b;          /* second image: the right side of a split, or diff's b */
    int x, y, w, h;              /* destination in window pixels (w, h > 0) */
    enum dirt_present_mode mode;
    float exposure;              /* stops (COLOR) */
    enum dirt_tonemap tonemap;   /* COLOR */
    int channel;                 /* HEAT: 0..3 */
    float lo, hi;                /* HEAT and DIFF range (hi > lo) */
    float split;                 /* 0 = off; else the split's x in (0, 1) of w: pixels
                                    whose centre lies left of x + split * w show
                                    texture, the others texture_b, in `mode`
                                    (ignored by DIFF) */
    bool split_line;             /* draw a 1-pixel white line at the split (the
                                    column holding x + split * w) */
} dirt_present_opts;

/* Draws into the window's back buffer (whatever framebuffer is bound; the
 * GL state it changes is restored). False after logging (no window, no
 * texture, bad rectangle, split or range). */
bool dirt_gpu_present(dirt_gpu *gpu, const dirt_present_opts *opts);

/* The folder the shaders are read from at each compile: $DIRT_GLSL_DIR (a
 * source tree's glsl/), or dirt_gpu_set_glsl_dir's, or NULL when they are
 * the library's embedded ones (nothing to reload). */
const char *dirt_gpu_glsl_dir(void);
/* Reads the shaders from `dir` (a source tree's glsl/) from the next
 * compile on when $DIRT_GLSL_DIR is not set; NULL: the embedded ones
 * again. Programs already made stay as they are. */
void dirt_gpu_set_glsl_dir(const char *dir);
/* Compiles the presentation program again from the shader sources; when
 * that fails (logged), the old one stays in use. False then. */
bool dirt_gpu_present_reload(dirt_gpu *gpu);

/* Clears the window's back buffer to an RGB colour. */
bool dirt_gpu_window_clear(dirt_gpu *gpu, const float rgb[3]);

/* Makes or updates an RGBA32F texture holding `rgba` (width * height * 4
 * floats, row 0 = top): `tex` 0 makes a new one, else `tex` is replaced
 * when its size differs or updated in place. Returns the name (owned by
 * the caller: dirt_gpu_texture_destroy), 0 after logging. Works on any GPU. */
uint32_t dirt_gpu_texture_upload(dirt_gpu *gpu, uint32_t tex, int width, int height,
                                 const float *rgba);
/* Accepts 0. */
void dirt_gpu_texture_destroy(dirt_gpu *gpu, uint32_t tex);

/* Reads what was drawn into the back buffer since the last swap as 8-bit
 * RGBA, row 0 = top, into `rgba` (width * height * 4 bytes of the current
 * framebuffer size, as dirt_gpu_window_size reports). Blocking. */
bool dirt_gpu_window_read(dirt_gpu *gpu, uint8_t *rgba, int width, int height);

#ifdef __cplusplus
}
#endif
#endif
