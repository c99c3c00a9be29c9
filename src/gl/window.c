/* The input of a windowed dirt_gpu (gl/window.h): GLFW callbacks fill a
 * gl_window_state between the two halves of dirt_gpu_window_poll; the key
 * names of the API. */
#include "gl/window.h"

#include <GLFW/glfw3.h>
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl.h"

/* Two left presses at most this far apart in time and space are a double click. */
#define DOUBLE_CLICK_SECONDS 0.35
#define DOUBLE_CLICK_PIXELS 4.0
#define MAX_DROPS ((int)(sizeof(((dirt_window_input *)0)->drops) / sizeof(const char *)))

/* The modifier keys, each of which has a left and a right GLFW key. */
enum { MOD_LSHIFT, MOD_RSHIFT, MOD_LCTRL, MOD_RCTRL, MOD_LALT, MOD_RALT, MOD_KEYS };

struct gl_window_state {
    dirt_window_input in;       /* what dirt_gpu_window_input returns */
    char *drops[8];             /* owned copies behind in.drops */
    bool mod_held[MOD_KEYS];
    double last_x, last_y;      /* cursor at the previous poll */
    double scale_x, scale_y;    /* framebuffer pixels per window coordinate */
    double click_time;          /* the last left press that may start a double click */
    double click_x, click_y;
    bool click_armed;
};

const char *const dirt_key_names[DIRT_NUM_KEYS] = {
    [DIRT_KEY_NONE] = "",
    [DIRT_KEY_W] = "W", [DIRT_KEY_A] = "A", [DIRT_KEY_S] = "S", [DIRT_KEY_D] = "D",
    [DIRT_KEY_Q] = "Q", [DIRT_KEY_E] = "E", [DIRT_KEY_R] = "R", [DIRT_KEY_F] = "F",
    [DIRT_KEY_P] = "P", [DIRT_KEY_C] = "C", [DIRT_KEY_H] = "H", [DIRT_KEY_M] = "M",
    [DIRT_KEY_N] = "N", [DIRT_KEY_O] = "O", [DIRT_KEY_V] = "V", [DIRT_KEY_X] = "X",
    [DIRT_KEY_Z] = "Z",
    [DIRT_KEY_0] = "0", [DIRT_KEY_1] = "1", [DIRT_KEY_2] = "2", [DIRT_KEY_3] = "3",
    [DIRT_KEY_4] = "4", [DIRT_KEY_5] = "5", [DIRT_KEY_6] = "6", [DIRT_KEY_7] = "7",
    [DIRT_KEY_8] = "8", [DIRT_KEY_9] = "9",
    [DIRT_KEY_SPACE] = "Space", [DIRT_KEY_ESCAPE] = "Escape", [DIRT_KEY_ENTER] = "Enter",
    [DIRT_KEY_TAB] = "Tab",
    [DIRT_KEY_LEFT] = "Left", [DIRT_KEY_RIGHT] = "Right", [DIRT_KEY_UP] = "Up",
    [DIRT_KEY_DOWN] = "Down",
    [DIRT_KEY_PAGE_UP] = "PageUp", [DIRT_KEY_PAGE_DOWN] = "PageDown", [DIRT_KEY_HOME] = "Home",
    [DIRT_KEY_MINUS] = "Minus", [DIRT_KEY_EQUAL] = "Equal", [DIRT_KEY_COMMA] = "Comma",
    [DIRT_KEY_PERIOD] = "Period",
    [DIRT_KEY_F1] = "F1", [DIRT_KEY_F2] = "F2", [DIRT_KEY_F3] = "F3", [DIRT_KEY_F5] = "F5",
    [DIRT_KEY_F12] = "F12",
    [DIRT_KEY_SHIFT] = "Shift", [DIRT_KEY_CTRL] = "Ctrl", [DIRT_KEY_ALT] = "Alt",
};

/* The GLFW key of each dirt_key (Shift, Ctrl and Alt come from two keys each:
 * mod_key below). */
static const int glfw_keys[DIRT_NUM_KEYS] = {
    [DIRT_KEY_NONE] = GLFW_KEY_UNKNOWN,
    [DIRT_KEY_W] = GLFW_KEY_W, [DIRT_KEY_A] = GLFW_KEY_A, [DIRT_KEY_S] = GLFW_KEY_S,
    [DIRT_KEY_D] = GLFW_KEY_D, [DIRT_KEY_Q] = GLFW_KEY_Q, [DIRT_KEY_E] = GLFW_KEY_E,
    [DIRT_KEY_R] = GLFW_KEY_R, [DIRT_KEY_F] = GLFW_KEY_F, [DIRT_KEY_P] = GLFW_KEY_P,
    [DIRT_KEY_C] = GLFW_KEY_C, [DIRT_KEY_H] = GLFW_KEY_H, [DIRT_KEY_M] = GLFW_KEY_M,
    [DIRT_KEY_N] = GLFW_KEY_N, [DIRT_KEY_O] = GLFW_KEY_O, [DIRT_KEY_V] = GLFW_KEY_V,
    [DIRT_KEY_X] = GLFW_KEY_X, [DIRT_KEY_Z] = GLFW_KEY_Z,
    [DIRT_KEY_0] = GLFW_KEY_0, [DIRT_KEY_1] = GLFW_KEY_1, [DIRT_KEY_2] = GLFW_KEY_2,
    [DIRT_KEY_3] = GLFW_KEY_3, [DIRT_KEY_4] = GLFW_KEY_4, [DIRT_KEY_5] = GLFW_KEY_5,
    [DIRT_KEY_6] = GLFW_KEY_6, [DIRT_KEY_7] = GLFW_KEY_7, [DIRT_KEY_8] = GLFW_KEY_8,
    [DIRT_KEY_9] = GLFW_KEY_9,
    [DIRT_KEY_SPACE] = GLFW_KEY_SPACE, [DIRT_KEY_ESCAPE] = GLFW_KEY_ESCAPE,
    [DIRT_KEY_ENTER] = GLFW_KEY_ENTER, [DIRT_KEY_TAB] = GLFW_KEY_TAB,
    [DIRT_KEY_LEFT] = GLFW_KEY_LEFT, [DIRT_KEY_RIGHT] = GLFW_KEY_RIGHT,
    [DIRT_KEY_UP] = GLFW_KEY_UP, [DIRT_KEY_DOWN] = GLFW_KEY_DOWN,
    [DIRT_KEY_PAGE_UP] = GLFW_KEY_PAGE_UP, [DIRT_KEY_PAGE_DOWN] = GLFW_KEY_PAGE_DOWN,
    [DIRT_KEY_HOME] = GLFW_KEY_HOME,
    [DIRT_KEY_MINUS] = GLFW_KEY_MINUS, [DIRT_KEY_EQUAL] = GLFW_KEY_EQUAL,
    [DIRT_KEY_COMMA] = GLFW_KEY_COMMA, [DIRT_KEY_PERIOD] = GLFW_KEY_PERIOD,
    [DIRT_KEY_F1] = GLFW_KEY_F1, [DIRT_KEY_F2] = GLFW_KEY_F2, [DIRT_KEY_F3] = GLFW_KEY_F3,
    [DIRT_KEY_F5] = GLFW_KEY_F5, [DIRT_KEY_F12] = GLFW_KEY_F12,
    [DIRT_KEY_SHIFT] = GLFW_KEY_UNKNOWN, [DIRT_KEY_CTRL] = GLFW_KEY_UNKNOWN,
    [DIRT_KEY_ALT] = GLFW_KEY_UNKNOWN,
};

static int mod_key(int key)
{
    switch (key) {
    case GLFW_KEY_LEFT_SHIFT: return MOD_LSHIFT;
    case GLFW_KEY_RIGHT_SHIFT: return MOD_RSHIFT;
    case GLFW_KEY_LEFT_CONTROL: return MOD_LCTRL;
    case GLFW_KEY_RIGHT_CONTROL: return MOD_RCTRL;
    case GLFW_KEY_LEFT_ALT: return MOD_LALT;
    case GLFW_KEY_RIGHT_ALT: return MOD_RALT;
    default: return -1;
    }
}

static enum dirt_key from_glfw(int key)
{
    if (key == GLFW_KEY_UNKNOWN)
        return DIRT_KEY_NONE;
    for (int k = 1; k < DIRT_NUM_KEYS; k++)
        if (glfw_keys[k] == key)
            return (enum dirt_key)k;
    return DIRT_KEY_NONE;
}

enum dirt_key dirt_key_from_name(const char *name)
{
    if (!name || !*name)
        return DIRT_KEY_NONE;
    for (int k = 1; k < DIRT_NUM_KEYS; k++) {
        const char *a = dirt_key_names[k], *b = name;
        while (*a && *b && tolower((unsigned char)*a) == tolower((unsigned char)*b))
            a++, b++;
        if (!*a && !*b)
            return (enum dirt_key)k;
    }
    return DIRT_KEY_NONE;
}

static struct gl_window_state *state_of(GLFWwindow *win)
{
    dirt_gpu *gpu = glfwGetWindowUserPointer(win);
    return gpu ? gpu->input : NULL;
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    (void)scancode;
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    bool down = action == GLFW_PRESS || action == GLFW_REPEAT;
    int m = mod_key(key);
    if (m >= 0) {
        st->mod_held[m] = down;
        enum dirt_key k = m <= MOD_RSHIFT ? DIRT_KEY_SHIFT : m <= MOD_RCTRL ? DIRT_KEY_CTRL
                                                                            : DIRT_KEY_ALT;
        int pair = m & ~1;
        st->in.key[k] = st->mod_held[pair] || st->mod_held[pair + 1];
        if (down)
            st->in.key_pressed[k] = true;
        return;
    }
    enum dirt_key k = from_glfw(key);
    if (k == DIRT_KEY_NONE)
        return;
    st->in.key[k] = down;
    if (down) {
        st->in.key_pressed[k] = true;
        st->in.key_mods[k] = (unsigned char)(((mods & GLFW_MOD_SHIFT) ? DIRT_MOD_SHIFT : 0) |
                                             ((mods & GLFW_MOD_CONTROL) ? DIRT_MOD_CTRL : 0) |
                                             ((mods & GLFW_MOD_ALT) ? DIRT_MOD_ALT : 0));
    }
}

static void on_cursor(GLFWwindow *win, double x, double y)
{
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    double nx = x * st->scale_x, ny = y * st->scale_y;
    for (int b = 0; b < DIRT_MOUSE_BUTTONS; b++) {
        if (!st->in.button[b])
            continue;
        if (b == DIRT_MOUSE_LEFT && st->in.key[DIRT_KEY_CTRL]) {
            st->in.ctrl_drag_dx += nx - st->in.mouse_x;
            st->in.ctrl_drag_dy += ny - st->in.mouse_y;
        } else {
            st->in.drag_dx[b] += nx - st->in.mouse_x;
            st->in.drag_dy[b] += ny - st->in.mouse_y;
        }
    }
    st->in.mouse_x = nx;
    st->in.mouse_y = ny;
}

static void on_button(GLFWwindow *win, int button, int action, int mods)
{
    (void)mods;
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    int b = button == GLFW_MOUSE_BUTTON_LEFT    ? DIRT_MOUSE_LEFT
            : button == GLFW_MOUSE_BUTTON_RIGHT ? DIRT_MOUSE_RIGHT
            : button == GLFW_MOUSE_BUTTON_MIDDLE ? DIRT_MOUSE_MIDDLE
                                                 : -1;
    if (b < 0)
        return;
    if (action == GLFW_PRESS) {
        st->in.button[b] = true;
        st->in.button_pressed[b] = true;
        if (b == DIRT_MOUSE_LEFT) {
            double now = glfwGetTime();
            double x = st->in.mouse_x, y = st->in.mouse_y;
            if (st->click_armed && now - st->click_time <= DOUBLE_CLICK_SECONDS &&
                fabs(x - st->click_x) <= DOUBLE_CLICK_PIXELS &&
                fabs(y - st->click_y) <= DOUBLE_CLICK_PIXELS) {
                st->in.double_clicks++;
                st->click_armed = false; /* a third press starts a new pair */
            } else {
                st->click_armed = true;
                st->click_time = now;
                st->click_x = x;
                st->click_y = y;
            }
        }
    } else if (action == GLFW_RELEASE) {
        st->in.button[b] = false;
        st->in.button_released[b] = true;
    }
}

static void on_scroll(GLFWwindow *win, double dx, double dy)
{
    (void)dx;
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    if (st->in.key[DIRT_KEY_CTRL]) {
        st->in.ctrl_scroll += dy;
        st->in.ctrl_scroll_x = st->in.mouse_x;
        st->in.ctrl_scroll_y = st->in.mouse_y;
    } else {
        st->in.scroll += dy;
    }
}

static void on_drop(GLFWwindow *win, int count, const char **paths)
{
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    for (int i = 0; i < count; i++) {
        if (st->in.num_drops >= MAX_DROPS) {
            DIRT_WARN("window: %d paths dropped, keeping the first %d", count, MAX_DROPS);
            break;
        }
        char *copy = malloc(strlen(paths[i]) + 1);
        if (!copy) {
            DIRT_ERROR("window: out of memory for a dropped path");
            break;
        }
        strcpy(copy, paths[i]);
        st->drops[st->in.num_drops] = copy;
        st->in.drops[st->in.num_drops] = copy;
        st->in.num_drops++;
    }
}

static void update_scale(GLFWwindow *win, struct gl_window_state *st)
{
    int ww = 0, wh = 0;
    glfwGetWindowSize(win, &ww, &wh);
    st->scale_x = ww > 0 && st->in.width > 0 ? (double)st->in.width / ww : 1.0;
    st->scale_y = wh > 0 && st->in.height > 0 ? (double)st->in.height / wh : 1.0;
}

static void on_framebuffer_size(GLFWwindow *win, int w, int h)
{
    struct gl_window_state *st = state_of(win);
    if (!st)
        return;
    if (w != st->in.width || h != st->in.height)
        st->in.resized = true;
    st->in.width = w;
    st->in.height = h;
    update_scale(win, st);
}

static void on_close(GLFWwindow *win)
{
    struct gl_window_state *st = state_of(win);
    if (st)
        st->in.close_requested = true;
}

bool gl_window_init(dirt_gpu *gpu)
{
    GLFWwindow *win = gpu->window;
    struct gl_window_state *st = calloc(1, sizeof(*st));
    if (!st) {
        DIRT_ERROR("window: out of memory");
        return false;
    }
    gpu->input = st;
    glfwSetWindowUserPointer(win, gpu);
    glfwGetFramebufferSize(win, &st->in.width, &st->in.height);
    update_scale(win, st);
    double x = 0, y = 0;
    glfwGetCursorPos(win, &x, &y);
    st->in.mouse_x = st->last_x = x * st->scale_x;
    st->in.mouse_y = st->last_y = y * st->scale_y;
    glfwSetKeyCallback(win, on_key);
    glfwSetCursorPosCallback(win, on_cursor);
    glfwSetMouseButtonCallback(win, on_button);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetDropCallback(win, on_drop);
    glfwSetFramebufferSizeCallback(win, on_framebuffer_size);
    glfwSetWindowCloseCallback(win, on_close);
    return true;
}

static void free_drops(struct gl_window_state *st)
{
    for (int i = 0; i < st->in.num_drops; i++) {
        free(st->drops[i]);
        st->drops[i] = NULL;
        st->in.drops[i] = NULL;
    }
    st->in.num_drops = 0;
}

void gl_window_poll_begin(dirt_gpu *gpu)
{
    struct gl_window_state *st = gpu->input;
    if (!st)
        return;
    free_drops(st);
    memset(st->in.button_pressed, 0, sizeof(st->in.button_pressed));
    memset(st->in.button_released, 0, sizeof(st->in.button_released));
    memset(st->in.key_pressed, 0, sizeof(st->in.key_pressed));
    memset(st->in.key_mods, 0, sizeof(st->in.key_mods));
    memset(st->in.drag_dx, 0, sizeof(st->in.drag_dx));
    memset(st->in.drag_dy, 0, sizeof(st->in.drag_dy));
    st->in.double_clicks = 0;
    st->in.scroll = 0;
    st->in.ctrl_scroll = 0;
    st->in.ctrl_drag_dx = st->in.ctrl_drag_dy = 0;
    st->in.resized = false;
    st->last_x = st->in.mouse_x;
    st->last_y = st->in.mouse_y;
}

void gl_window_poll_end(dirt_gpu *gpu)
{
    struct gl_window_state *st = gpu->input;
    if (!st)
        return;
    st->in.mouse_dx = st->in.mouse_x - st->last_x;
    st->in.mouse_dy = st->in.mouse_y - st->last_y;
    /* The close button stays requested until the program closes the window
     * (GLFW's should-close flag, which the close callback has set). */
    st->in.close_requested = st->in.close_requested || glfwWindowShouldClose(gpu->window);
}

void gl_window_release(dirt_gpu *gpu)
{
    if (!gpu->input)
        return;
    free_drops(gpu->input);
    if (gpu->window)
        glfwSetWindowUserPointer(gpu->window, NULL);
    free(gpu->input);
    gpu->input = NULL;
}

/* The GLFW window of `gpu`, NULL after logging `what` on a headless GPU. */
static GLFWwindow *window_of(dirt_gpu *gpu, const char *what)
{
    if (!gpu || !gpu->window || !gpu->input) {
        DIRT_ERROR("%s: the GPU has no window (create it with dirt_gpu_opts.window)", what);
        return NULL;
    }
    return gpu->window;
}

bool dirt_gpu_window_input(dirt_gpu *gpu, dirt_window_input *out)
{
    if (!out) {
        DIRT_ERROR("dirt_gpu_window_input: NULL output");
        return false;
    }
    if (!window_of(gpu, "dirt_gpu_window_input")) {
        memset(out, 0, sizeof(*out));
        return false;
    }
    *out = gpu->input->in;
    return true;
}

bool dirt_gpu_window_set_title(dirt_gpu *gpu, const char *title)
{
    GLFWwindow *win = window_of(gpu, "dirt_gpu_window_set_title");
    if (!win)
        return false;
    if (!title) {
        DIRT_ERROR("dirt_gpu_window_set_title: NULL title");
        return false;
    }
    glfwSetWindowTitle(win, title);
    return true;
}

bool dirt_gpu_window_set_size(dirt_gpu *gpu, int width, int height)
{
    GLFWwindow *win = window_of(gpu, "dirt_gpu_window_set_size");
    if (!win)
        return false;
    if (width <= 0 || height <= 0) {
        DIRT_ERROR("dirt_gpu_window_set_size: %dx%d is not a size", width, height);
        return false;
    }
    /* GLFW sizes windows in screen coordinates; ask for the framebuffer size. */
    struct gl_window_state *st = gpu->input;
    int ww = (int)lround(width / (st->scale_x > 0 ? st->scale_x : 1.0));
    int wh = (int)lround(height / (st->scale_y > 0 ? st->scale_y : 1.0));
    glfwSetWindowSize(win, ww > 0 ? ww : 1, wh > 0 ? wh : 1);
    return true;
}
