/* DIRT engine: immediate-mode panels for the programs' windows, over Dear
 * ImGui (Debian's libimgui-dev, its GLFW and OpenGL 3 backends) behind a C
 * API. One dirt_ui per windowed GPU; the widget functions act on the UI
 * whose frame is open (between dirt_ui_begin_frame and dirt_ui_end_frame),
 * as ImGui's do, and follow ImGui's meaning (a widget returns true when the
 * user changed its value in this frame). No settings file is read or
 * written (the layout is the program's, the same on every run). */
#ifndef DIRT_UI_H
#define DIRT_UI_H

#include <stdbool.h>
#include <stdint.h>

#include "dirt/gpu.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_ui dirt_ui;

/* Attaches the UI to the window of `gpu` (made with opts.window): its
 * input callbacks chain to the GPU's, so dirt_gpu_window_input keeps
 * working. NULL after logging (headless GPU, second UI). */
dirt_ui *dirt_ui_create(dirt_gpu *gpu);
/* Accepts NULL. Call it before dirt_gpu_destroy (which destroys a UI
 * still attached, with a warning). */
void dirt_ui_destroy(dirt_ui *ui);

/* Opens a frame (after dirt_gpu_window_poll). */
void dirt_ui_begin_frame(dirt_ui *ui);
/* Closes the frame and draws its panels over the window's back buffer. */
void dirt_ui_end_frame(dirt_ui *ui);
/* Closes the frame without drawing: a pass of the panels' logic only.
 * The program runs such passes (begin, its panels, end_pass) before the
 * drawn one so that input takes effect in the frame it is shown in: the
 * panels see a mouse button go down in one pass and up in the next (a
 * click acts on the release), and what a click defers (a panel's collapse,
 * a popup opening) applies in the pass after it. Wheel steps that arrive
 * while a frame is open (a poll within it) go to the next pass. */
void dirt_ui_end_pass(dirt_ui *ui);
/* Whether the open frame saw a mouse button go down or up: its widgets act
 * on that (or defer an effect to the next frame), so another pass of the
 * panels is needed before they are shown as they now are. */
bool dirt_ui_buttons_changed(const dirt_ui *ui);
/* Whether the panels take the mouse / keyboard (the cursor is over a panel,
 * a widget is active or a text field has focus): the program then leaves
 * those events alone. Valid after dirt_ui_begin_frame. */
bool dirt_ui_wants_mouse(const dirt_ui *ui);
bool dirt_ui_wants_keyboard(const dirt_ui *ui);

/* ---- panels ---- */

/* A panel placed at x, y with size w, h the first time it appears (later
 * the user may move it). `open` (may be NULL) gets a close button. Returns
 * whether its content is visible; call dirt_ui_end either way. */
bool dirt_ui_begin(const char *title, bool *open, float x, float y, float w, float h);
void dirt_ui_end(void);
/* The next dirt_ui_begin's panel starts collapsed to its title bar (the
 * first time it appears; the user may open it). */
void dirt_ui_next_collapsed(void);
/* The current panel's rectangle in window pixels (x, y, w, h). */
void dirt_ui_panel_rect(float rect[4]);
/* The last widget's rectangle in window pixels (x, y, w, h); zeros outside
 * a shown panel. */
void dirt_ui_item_rect(float rect[4]);
/* Labels (and checkboxes, buttons) of the last frame that did not fit in
 * their panel's width. A label that does not fit beside its widget goes
 * on its own line above it, and text wraps at the panel's edge, so only
 * one wider than the whole panel counts. */
int dirt_ui_clipped_labels(const dirt_ui *ui);
/* Whether any panel is shown at window pixel (x, y) in the last frame. */
bool dirt_ui_covers(const dirt_ui *ui, float x, float y);

/* ---- over the image (outside any panel; drawn over the panels) ---- */

/* `text` in white on a dark box whose top left is window pixel (x, y);
 * its size goes to size[2] (may be NULL). */
void dirt_ui_overlay_text(float x, float y, const char *text, float size[2]);
/* The heat ramp of the present shader (glsl/common/display.h), low at the
 * left, in the rectangle x, y, w, h (rounded to whole pixels): column i
 * has the colour the present shader shows for (i + 0.5) / w of the range. */
void dirt_ui_overlay_ramp(float x, float y, float w, float h);

/* ---- widgets ---- */

#if defined(__GNUC__)
#define DIRT_UI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define DIRT_UI_PRINTF(a, b)
#endif

void dirt_ui_text(const char *fmt, ...) DIRT_UI_PRINTF(1, 2);
void dirt_ui_text_disabled(const char *fmt, ...) DIRT_UI_PRINTF(1, 2);
/* Shows `text` in a tooltip when the previous widget is hovered. */
void dirt_ui_tooltip(const char *text);
bool dirt_ui_header(const char *label, bool default_open); /* collapsing header */
void dirt_ui_separator(void);
void dirt_ui_same_line(void);
bool dirt_ui_button(const char *label);
bool dirt_ui_checkbox(const char *label, bool *value);
bool dirt_ui_radio(const char *label, int *value, int button_value);
/* `items`: `count` labels; *current is an index. */
bool dirt_ui_combo(const char *label, int *current, const char *const *items, int count);
bool dirt_ui_slider_int(const char *label, int *value, int lo, int hi);
/* `format` as printf ("%.3f"); `logarithmic` for ranges over decades. */
bool dirt_ui_slider_float(const char *label, float *value, float lo, float hi,
                          const char *format, bool logarithmic);
bool dirt_ui_input_int(const char *label, int *value, int step);
bool dirt_ui_input_float(const char *label, float *value, const char *format);
/* Edits 3 floats (a colour without the picker, a position). */
bool dirt_ui_input_float3(const char *label, float value[3], const char *format);
bool dirt_ui_color3(const char *label, float rgb[3]);
/* A text field editing `buf` (NUL-terminated, `size` bytes). */
bool dirt_ui_input_text(const char *label, char *buf, int size);

/* A line plot of `count` values (ring: the first is values[offset]) with
 * the y range lo..hi and a caption over it; height in pixels. */
void dirt_ui_plot_lines(const char *label, const float *values, int count, int offset,
                        const char *overlay, float lo, float hi, float height);
/* An RGBA32F or RGBA8 GL texture drawn w x h (row 0 at the top). */
void dirt_ui_image(uint32_t texture, float w, float h);

/* A table with `columns` columns and a header row of `headers`; fill it
 * with dirt_ui_table_row + dirt_ui_table_cell, close with _end when
 * _begin returned true. */
bool dirt_ui_table_begin(const char *id, int columns, const char *const *headers);
void dirt_ui_table_row(void);
void dirt_ui_table_cell(const char *fmt, ...) DIRT_UI_PRINTF(1, 2);
void dirt_ui_table_end(void);

#ifdef __cplusplus
}
#endif
#endif
