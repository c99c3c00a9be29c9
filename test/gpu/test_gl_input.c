/* The window's input (dirt/window.h) and panels (dirt/ui.h) under real X
 * events: test_gl_input.sh runs this program under xvfb-run and answers
 * each "STEP <name> [x y]" line it prints with xdotool (mouse, buttons,
 * wheel, keys, window size). For each step the program polls for up to 5 s
 * until the input it expects arrived, then prints "OK <name>" or
 * "FAIL <name>: <what it saw>".
 *
 *   test_gl_input input TITLE   dirt_window_input: cursor and its motion,
 *                               buttons, double clicks, wheel, keys (W,
 *                               Shift left and right, F1), resizes, title;
 *                               drops and the close button through the
 *                               window's callbacks; a GPU destroyed with
 *                               its UI attached
 *   test_gl_input ui TITLE      one panel at 10,10 200x100: drawn inside,
 *                               not outside, dirt_ui_covers agrees; hover
 *                               takes the mouse; a click on its button
 *                               returns true (and still reaches the GPU's
 *                               input); text typed into its field arrives */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "gl/ui.h"
#include "gl/window.h"
#include "gl/gl.h"

#include <GLFW/glfw3.h>

#define WAIT_SECONDS 5.0

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void nap(void)
{
    struct timespec ts = {0, 5 * 1000 * 1000};
    nanosleep(&ts, NULL);
}

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void say(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
    fflush(stdout);
}

/* What a step saw, summed over its polls. */
typedef struct seen {
    dirt_window_input last;
    int polls;
    double dx, dy, scroll;
    int pressed[DIRT_MOUSE_BUTTONS], released[DIRT_MOUSE_BUTTONS];
    int double_clicks, resized;
    int key_pressed[DIRT_NUM_KEYS];
} seen;

static void add(seen *s, const dirt_window_input *in)
{
    s->last = *in;
    s->polls++;
    s->dx += in->mouse_dx;
    s->dy += in->mouse_dy;
    s->scroll += in->scroll;
    for (int b = 0; b < DIRT_MOUSE_BUTTONS; b++) {
        s->pressed[b] += in->button_pressed[b];
        s->released[b] += in->button_released[b];
    }
    s->double_clicks += in->double_clicks;
    s->resized += in->resized;
    for (int k = 0; k < DIRT_NUM_KEYS; k++)
        s->key_pressed[k] += in->key_pressed[k];
}

static void describe(const seen *s, char *buf, size_t size)
{
    const dirt_window_input *in = &s->last;
    int n = snprintf(buf, size,
                     "polls %d, size %dx%d (resized %d), mouse %.1f %.1f (motion %.1f %.1f), "
                     "buttons held %d%d%d pressed %d/%d/%d released %d/%d/%d, double %d, "
                     "scroll %.1f, keys held:",
                     s->polls, in->width, in->height, s->resized, in->mouse_x, in->mouse_y, s->dx,
                     s->dy, in->button[0], in->button[1], in->button[2], s->pressed[0],
                     s->pressed[1], s->pressed[2], s->released[0], s->released[1], s->released[2],
                     s->double_clicks, s->scroll);
    for (int k = 1; k < DIRT_NUM_KEYS && n > 0 && (size_t)n < size; k++)
        if (in->key[k])
            n += snprintf(buf + n, size - (size_t)n, " %s", dirt_key_names[k]);
    if (n > 0 && (size_t)n < size)
        n += snprintf(buf + n, size - (size_t)n, "; pressed:");
    for (int k = 1; k < DIRT_NUM_KEYS && n > 0 && (size_t)n < size; k++)
        if (s->key_pressed[k])
            n += snprintf(buf + n, size - (size_t)n, " %s(%d)", dirt_key_names[k],
                          s->key_pressed[k]);
}

/* ---- the input program ---- */

typedef bool (*done_fn)(const seen *s, const seen *before);

static dirt_gpu *g_gpu;

/* Prints the step, polls until `done` holds (then `settle` more seconds, so
 * that events which should not arrive have the time to) or the time is up;
 * checks `done` once more at the end. */
static bool step(const char *name, done_fn done, double settle, seen *s)
{
    seen before = *s;
    memset(s, 0, sizeof(*s));
    s->last = before.last;
    say("STEP %s", name);
    double start = now(), reached = -1;
    while (now() - start < WAIT_SECONDS) {
        dirt_gpu_window_poll(g_gpu);
        dirt_window_input in;
        CHECK(dirt_gpu_window_input(g_gpu, &in));
        add(s, &in);
        if (reached < 0 && done(s, &before))
            reached = now();
        if (reached >= 0 && now() - reached >= settle)
            break;
        nap();
    }
    bool ok = done(s, &before);
    char what[1024];
    describe(s, what, sizeof(what));
    if (ok)
        say("OK %s: %s", name, what);
    else
        say("FAIL %s: saw %s", name, what);
    CHECK_MSG(ok, "step %s", name);
    return ok;
}

static bool at_40_30(const seen *s, const seen *b)
{
    (void)b;
    return s->last.mouse_x == 40 && s->last.mouse_y == 30;
}
static bool at_50_35(const seen *s, const seen *b)
{
    /* The motion of the polls adds up to the move (and is not counted twice). */
    return s->last.mouse_x == 50 && s->last.mouse_y == 35 && s->dx == 10 && s->dy == 5 &&
           b->last.mouse_x == 40;
}
static bool left_down(const seen *s, const seen *b)
{
    (void)b;
    return s->pressed[DIRT_MOUSE_LEFT] == 1 && s->last.button[DIRT_MOUSE_LEFT] &&
           s->released[DIRT_MOUSE_LEFT] == 0;
}
static bool left_up(const seen *s, const seen *b)
{
    (void)b;
    /* The press of the step before is not reported again. */
    return s->released[DIRT_MOUSE_LEFT] == 1 && !s->last.button[DIRT_MOUSE_LEFT] &&
           s->pressed[DIRT_MOUSE_LEFT] == 0;
}
static bool right_click(const seen *s, const seen *b)
{
    (void)b;
    return s->pressed[DIRT_MOUSE_RIGHT] == 1 && s->released[DIRT_MOUSE_RIGHT] == 1 &&
           !s->last.button[DIRT_MOUSE_RIGHT] && s->pressed[DIRT_MOUSE_LEFT] == 0;
}
static bool double_click(const seen *s, const seen *b)
{
    (void)b;
    return s->pressed[DIRT_MOUSE_LEFT] == 2 && s->released[DIRT_MOUSE_LEFT] == 2 &&
           s->double_clicks == 1;
}
/* Two presses a second apart (the script waits 1 s): no double click. */
static bool slow_clicks(const seen *s, const seen *b)
{
    (void)b;
    return s->pressed[DIRT_MOUSE_LEFT] == 2 && s->released[DIRT_MOUSE_LEFT] == 2 &&
           s->double_clicks == 0;
}
static bool scrolled_up(const seen *s, const seen *b)
{
    (void)b;
    return s->scroll == 2.0;
}
static bool scrolled_down(const seen *s, const seen *b)
{
    (void)b;
    return s->scroll == -1.0;
}
static bool w_down(const seen *s, const seen *b)
{
    (void)b;
    return s->last.key[DIRT_KEY_W] && s->key_pressed[DIRT_KEY_W] >= 1 &&
           !s->last.key[DIRT_KEY_SHIFT];
}
static bool w_up(const seen *s, const seen *b)
{
    (void)b;
    return !s->last.key[DIRT_KEY_W] && s->key_pressed[DIRT_KEY_W] == 0;
}
static bool shift_l_down(const seen *s, const seen *b)
{
    (void)b;
    return s->last.key[DIRT_KEY_SHIFT] && s->key_pressed[DIRT_KEY_SHIFT] == 1;
}
static bool shift_r_down(const seen *s, const seen *b)
{
    (void)b;
    return s->last.key[DIRT_KEY_SHIFT] && s->key_pressed[DIRT_KEY_SHIFT] == 1;
}
static bool shift_l_up(const seen *s, const seen *b)
{
    (void)b;
    /* Right Shift still holds it. */
    return s->last.key[DIRT_KEY_SHIFT] && s->polls >= 20;
}
static bool shift_r_up(const seen *s, const seen *b)
{
    (void)b;
    return !s->last.key[DIRT_KEY_SHIFT];
}
static bool f1_tapped(const seen *s, const seen *b)
{
    (void)b;
    return s->key_pressed[DIRT_KEY_F1] == 1 && !s->last.key[DIRT_KEY_F1];
}
static bool resized_200x150(const seen *s, const seen *b)
{
    (void)b;
    return s->last.width == 200 && s->last.height == 150 && s->resized == 1 &&
           !s->last.resized;
}
static bool resized_180x140(const seen *s, const seen *b)
{
    (void)b;
    return s->last.width == 180 && s->last.height == 140 && s->resized == 1;
}
static bool f2_tapped(const seen *s, const seen *b)
{
    (void)b;
    return s->key_pressed[DIRT_KEY_F2] == 1;
}
static bool nothing(const seen *s, const seen *b)
{
    (void)b;
    return s->polls >= 10;
}

/* Drops and the close button have no xdotool command: the window's own
 * callbacks (asked back from GLFW) are called as glfwPollEvents would. */
static void test_drops_and_close(void)
{
    GLFWwindow *win = g_gpu->window;
    GLFWdropfun drop = glfwSetDropCallback(win, NULL);
    glfwSetDropCallback(win, drop);
    GLFWwindowclosefun close = glfwSetWindowCloseCallback(win, NULL);
    glfwSetWindowCloseCallback(win, close);
    CHECK(drop && close);
    if (!drop || !close)
        return;
    char names[10][32];
    const char *paths[10];
    for (int i = 0; i < 10; i++) {
        snprintf(names[i], sizeof(names[i]), "/tmp/dropped %d.gltf", i);
        paths[i] = names[i];
    }
    dirt_gpu_window_poll(g_gpu);
    drop(win, 3, paths);
    drop(win, 7, paths + 3); /* one poll: 10 paths, the first 8 kept */
    dirt_window_input in;
    CHECK(dirt_gpu_window_input(g_gpu, &in));
    CHECK(in.num_drops == 8);
    for (int i = 0; i < in.num_drops && i < 8; i++)
        CHECK(in.drops[i] && in.drops[i] != paths[i] && strcmp(in.drops[i], paths[i]) == 0);
    memset(names, 0, sizeof(names)); /* the GPU holds copies */
    CHECK(in.drops[7] && strcmp(in.drops[7], "/tmp/dropped 7.gltf") == 0);
    CHECK(!in.close_requested && !dirt_gpu_window_should_close(g_gpu));
    close(win);
    dirt_gpu_window_poll(g_gpu);
    CHECK(dirt_gpu_window_input(g_gpu, &in));
    CHECK(in.num_drops == 0 && in.drops[0] == NULL); /* the next poll drops them */
    CHECK(in.close_requested);
    dirt_gpu_window_poll(g_gpu);
    drop(win, 1, paths); /* freed by dirt_gpu_destroy */
}

static int run_input(const char *title)
{
    g_gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = 160, .height = 120,
                                             .title = title});
    if (!g_gpu) {
        say("FAIL window: no window");
        return 1;
    }
    dirt_window_input in;
    CHECK(dirt_gpu_window_input(g_gpu, &in));
    CHECK(in.width == 160 && in.height == 120 && in.num_drops == 0 && !in.close_requested);
    /* The key names. */
    CHECK(dirt_key_from_name("W") == DIRT_KEY_W && dirt_key_from_name("w") == DIRT_KEY_W);
    CHECK(dirt_key_from_name("space") == DIRT_KEY_SPACE);
    CHECK(dirt_key_from_name("PAGEUP") == DIRT_KEY_PAGE_UP);
    CHECK(dirt_key_from_name("F12") == DIRT_KEY_F12 && dirt_key_from_name("7") == DIRT_KEY_7);
    CHECK(dirt_key_from_name("ctrl") == DIRT_KEY_CTRL);
    CHECK(dirt_key_from_name("") == DIRT_KEY_NONE && dirt_key_from_name("F4") == DIRT_KEY_NONE);
    CHECK(dirt_key_from_name(NULL) == DIRT_KEY_NONE && dirt_key_from_name("Wx") == DIRT_KEY_NONE);
    for (int k = 1; k < DIRT_NUM_KEYS; k++)
        CHECK_MSG(dirt_key_names[k] && (int)dirt_key_from_name(dirt_key_names[k]) == k, "key %d", k);
    CHECK(strcmp(dirt_key_names[DIRT_KEY_NONE], "") == 0);

    dirt_gpu_window_swap(g_gpu);
    say("READY");
    seen s;
    memset(&s, 0, sizeof(s));
    s.last = in;
    step("focus", nothing, 0, &s);
    step("move", at_40_30, 0.2, &s);
    step("move2", at_50_35, 0.2, &s);
    step("press", left_down, 0.2, &s);
    step("release", left_up, 0.2, &s);
    step("right", right_click, 0.2, &s);
    step("double", double_click, 0.3, &s);
    step("slow", slow_clicks, 0.3, &s);
    step("scroll_up", scrolled_up, 0.3, &s);
    step("scroll_down", scrolled_down, 0.3, &s);
    step("w_down", w_down, 0.2, &s);
    step("w_up", w_up, 0.2, &s);
    step("shift_l_down", shift_l_down, 0.2, &s);
    step("shift_r_down", shift_r_down, 0.2, &s);
    step("shift_l_up", shift_l_up, 0, &s);
    step("shift_r_up", shift_r_up, 0.2, &s);
    step("f1", f1_tapped, 0.2, &s);
    step("resize", resized_200x150, 0.3, &s);
    CHECK(dirt_gpu_window_set_size(g_gpu, 180, 140));
    step("set_size", resized_180x140, 0.3, &s);
    char renamed[256];
    snprintf(renamed, sizeof(renamed), "%s renamed", title);
    CHECK(dirt_gpu_window_set_title(g_gpu, renamed));
    dirt_gpu_window_poll(g_gpu);
    step("title", f2_tapped, 0, &s); /* the script reads the name back, then taps F2 */
    CHECK(!dirt_gpu_window_set_size(g_gpu, 0, 10));
    test_drops_and_close();
    CHECK(dirt_gpu_error_count(g_gpu) == 0);
    /* A GPU destroyed with its UI still attached takes the UI with it (here,
     * as a second window GPU in one process upsets LeakSanitizer's thread
     * walk in the sanitizer build: Mesa's GLX state of the first). */
    dirt_ui *ui = dirt_ui_create(g_gpu);
    CHECK(ui != NULL);
    for (int i = 0; ui && i < 2; i++) {
        dirt_gpu_window_poll(g_gpu);
        dirt_ui_begin_frame(ui);
        dirt_ui_begin("Left attached", NULL, 0, 0, 32, 32);
        dirt_ui_text("%d", i);
        dirt_ui_end();
        dirt_ui_end_frame(ui);
        dirt_gpu_window_swap(g_gpu);
    }
    CHECK(dirt_gpu_error_count(g_gpu) == 0);
    dirt_gpu_destroy(g_gpu);
    int rc = check_finish();
    say("DONE %d", rc);
    return rc;
}

/* ---- the UI program ---- */

#define UI_W 320
#define UI_H 240
static const float k_clear[3] = {32.0f / 255.0f, 64.0f / 255.0f, 96.0f / 255.0f};

typedef struct ui_state {
    dirt_ui *ui;
    GLuint fbo, fbo_tex;
    int clicks;
    char text[64];
    seen input;
    bool wants_mouse, wants_keyboard;
} ui_state;

/* One frame: poll, clear, the panel, draw; `fb` (when not NULL) gets the
 * frame before the swap. */
static void ui_frame(ui_state *st, uint8_t *fb)
{
    dirt_gpu_window_poll(g_gpu);
    dirt_window_input in;
    CHECK(dirt_gpu_window_input(g_gpu, &in));
    add(&st->input, &in);
    CHECK(dirt_gpu_window_clear(g_gpu, k_clear));
    dirt_ui_begin_frame(st->ui);
    st->wants_mouse = dirt_ui_wants_mouse(st->ui);
    st->wants_keyboard = dirt_ui_wants_keyboard(st->ui);
    if (dirt_ui_begin("Panel", NULL, 10, 10, 200, 100)) {
        if (dirt_ui_button("Press me"))
            st->clicks++;
        dirt_ui_input_text("Name", st->text, (int)sizeof(st->text));
        float r[4];
        dirt_ui_panel_rect(r);
        CHECK(r[0] == 10 && r[1] == 10 && r[2] == 200 && r[3] == 100);
    }
    dirt_ui_end();
    /* The program's own framebuffer is bound: the panels still go to the
     * window, and the binding stays. */
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st->fbo);
    dirt_ui_end_frame(st->ui);
    GLint bound = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    CHECK(bound == (GLint)st->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    if (fb)
        CHECK(dirt_gpu_window_read(g_gpu, fb, UI_W, UI_H));
    dirt_gpu_window_swap(g_gpu);
    nap();
}

typedef bool (*ui_done_fn)(const ui_state *st);

static bool ui_step(ui_state *st, const char *name, int x, int y, ui_done_fn done)
{
    memset(&st->input, 0, sizeof(st->input));
    if (x >= 0)
        say("STEP %s %d %d", name, x, y);
    else
        say("STEP %s", name);
    double start = now();
    while (now() - start < WAIT_SECONDS && !done(st))
        ui_frame(st, NULL);
    bool ok = done(st);
    say("%s %s: clicks %d, text \"%s\", wants mouse %d keyboard %d, left pressed %d", ok ? "OK" : "FAIL",
        name, st->clicks, st->text, st->wants_mouse, st->wants_keyboard,
        st->input.pressed[DIRT_MOUSE_LEFT]);
    CHECK_MSG(ok, "step %s", name);
    return ok;
}

static bool over_panel(const ui_state *st) { return st->wants_mouse; }
static bool clicked(const ui_state *st)
{
    return st->clicks == 1 && st->input.pressed[DIRT_MOUSE_LEFT] == 1 &&
           st->input.released[DIRT_MOUSE_LEFT] == 1;
}
static bool away(const ui_state *st) { return !st->wants_mouse && st->clicks == 1; }
static bool typed(const ui_state *st)
{
    return strcmp(st->text, "dirt") == 0 && st->wants_keyboard;
}

static bool same_rgb(const uint8_t *a, const uint8_t *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static int run_ui(const char *title)
{
    g_gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = UI_W, .height = UI_H,
                                             .title = title});
    if (!g_gpu) {
        say("FAIL window: no window");
        return 1;
    }
    ui_state st;
    memset(&st, 0, sizeof(st));
    st.ui = dirt_ui_create(g_gpu);
    CHECK(st.ui != NULL);
    if (!st.ui) {
        dirt_gpu_destroy(g_gpu);
        return check_finish();
    }
    CHECK(dirt_ui_create(g_gpu) == NULL); /* one per window */
    glCreateTextures(GL_TEXTURE_2D, 1, &st.fbo_tex);
    glTextureStorage2D(st.fbo_tex, 1, GL_RGBA8, UI_W, UI_H);
    glCreateFramebuffers(1, &st.fbo);
    glNamedFramebufferTexture(st.fbo, GL_COLOR_ATTACHMENT0, st.fbo_tex, 0);
    CHECK(!dirt_ui_button("outside a frame"));
    /* Nothing covered before a frame was drawn. */
    CHECK(!dirt_ui_covers(st.ui, 50, 50));
    uint8_t *fb = malloc((size_t)UI_W * UI_H * 4);
    for (int i = 0; i < 3; i++)
        ui_frame(&st, NULL);
    ui_frame(&st, fb);
    const uint8_t clear8[3] = {32, 64, 96};
    int inside_same = 0, outside_changed = 0;
    for (int y = 0; y < UI_H; y++)
        for (int x = 0; x < UI_W; x++) {
            bool in = x >= 10 && x < 210 && y >= 10 && y < 110;
            bool same = same_rgb(fb + ((size_t)y * UI_W + (size_t)x) * 4, clear8);
            if (in && same)
                inside_same++;
            if (!in && !same && outside_changed++ < 4)
                fprintf(stderr, "pixel (%d, %d) outside the panel changed\n", x, y);
            bool covered = dirt_ui_covers(st.ui, (float)x + 0.5f, (float)y + 0.5f);
            if (covered != in && (x % 7 == 0 || x == 9 || x == 10 || x == 209 || x == 210))
                CHECK_MSG(covered == in, "covers(%d, %d) = %d", x, y, covered);
        }
    CHECK_MSG(inside_same == 0, "%d pixels inside the panel kept the clear colour", inside_same);
    CHECK_MSG(outside_changed == 0, "%d pixels outside the panel changed", outside_changed);
    CHECK(dirt_ui_covers(st.ui, 10, 10) && !dirt_ui_covers(st.ui, 210, 60) &&
          !dirt_ui_covers(st.ui, 100, 110) && dirt_ui_covers(st.ui, 209.5f, 109.5f));
    free(fb);

    say("READY");
    /* Default style and font: the title bar is 19 pixels (13 + 2 * 3), the
     * content starts 8 pixels in; the button is 19 high, the text field
     * 4 below it. */
    ui_step(&st, "hover", 40, 46, over_panel);
    ui_step(&st, "click", 40, 46, clicked);
    ui_step(&st, "away", 300, 200, away);
    ui_step(&st, "type", 100, 69, typed);
    CHECK(dirt_gpu_error_count(g_gpu) == 0);
    glDeleteFramebuffers(1, &st.fbo);
    glDeleteTextures(1, &st.fbo_tex);
    dirt_ui_destroy(st.ui);
    dirt_ui_destroy(NULL);
    /* The GPU's own callbacks are back. */
    say("STEP after 60 80");
    dirt_window_input in;
    memset(&in, 0, sizeof(in));
    for (double start = now(); now() - start < WAIT_SECONDS; nap()) {
        dirt_gpu_window_poll(g_gpu);
        CHECK(dirt_gpu_window_input(g_gpu, &in));
        if (in.mouse_x == 60 && in.mouse_y == 80)
            break;
    }
    bool back = in.mouse_x == 60 && in.mouse_y == 80;
    say("%s after: mouse %.1f %.1f", back ? "OK" : "FAIL", in.mouse_x, in.mouse_y);
    CHECK(back);
    dirt_gpu_destroy(g_gpu);
    int rc = check_finish();
    say("DONE %d", rc);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 3 || (strcmp(argv[1], "input") != 0 && strcmp(argv[1], "ui") != 0)) {
        fprintf(stderr, "usage: %s input|ui TITLE\n", argv[0]);
        return 2;
    }
    return strcmp(argv[1], "input") == 0 ? run_input(argv[2]) : run_ui(argv[2]);
}
