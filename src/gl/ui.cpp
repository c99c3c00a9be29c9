/* DIRT engine: the panels of gl/ui.h over Dear ImGui 1.86 (Debian's
 * libimgui-dev: the library, its GLFW and OpenGL 3 backends). A C++
 * translation unit behind a C API, as src/scene/gltf.cpp: nothing of ImGui
 * shows in the header, and no C++ exception leaves it (ImGui allocates
 * with malloc and does not throw).
 *
 * The GLFW backend installs its callbacks over the GPU's own (window.c,
 * installed when the window was made) and calls them first, so the
 * program's dirt_gpu_window_input keeps seeing every event; the program
 * asks dirt_ui_wants_mouse / _keyboard whether to act on them. */
extern "C" {
#include "gl/gl.h"
}
#include "gl/ui.h"
#include "common/display.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdarg>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace {

/* Panel rectangles kept per frame for dirt_ui_covers (more are ignored). */
constexpr int kMaxRects = 64;
/* Nesting of dirt_ui_begin (ImGui's windows nest; ours rarely do). */
constexpr int kMaxDepth = 16;

struct Rect {
    float x, y, w, h;
};

} // namespace

struct dirt_ui {
    dirt_gpu *gpu;
    ImGuiContext *ctx;
    bool in_frame;
    /* Whether each open dirt_ui_begin called ImGui::Begin (an `open` that
     * was already false does not). */
    bool began[kMaxDepth];
    int depth;
    int tables;                 /* open dirt_ui_table_begin */
    Rect frame[kMaxRects];      /* the panels of the open frame */
    int num_frame;
    Rect last[kMaxRects];       /* the panels of the last completed frame */
    int num_last;
    /* The wheel steps the open frame's NewFrame applied: steps beyond them
     * came from a poll within the frame and are kept for the next one
     * (ImGui's EndFrame clears the wheel). */
    float wheel, wheel_h;
    int clipped, clipped_last;  /* labels cut off in the open / last frame */
};

namespace {

/* The UI whose frame is open: the widget functions act on it. */
dirt_ui *g_ui = nullptr;

/* True when a frame is open; else logs that `fn` was called outside one. */
bool in_frame(const char *fn)
{
    if (g_ui && g_ui->in_frame)
        return true;
    DIRT_ERROR("%s: no UI frame is open (dirt_ui_begin_frame)", fn);
    return false;
}

bool in_table(const char *fn)
{
    if (!in_frame(fn))
        return false;
    if (g_ui->tables > 0)
        return true;
    DIRT_ERROR("%s: no table is open (dirt_ui_table_begin)", fn);
    return false;
}

/* ImGui's io of `ui`, whichever context is current. */
const ImGuiIO &io_of(const dirt_ui *ui)
{
    ImGuiContext *prev = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(ui->ctx);
    const ImGuiIO &io = ImGui::GetIO();
    ImGui::SetCurrentContext(prev);
    return io;
}

/* Draws the frame's panels into the default framebuffer's back buffer. */
void draw(void)
{
    gl_group_push("ui");
    GLint draw_fb = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb);
    GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_FRAMEBUFFER_SRGB);
    /* The backend sets (and restores) everything else it uses: program,
     * textures, vertex arrays, blending, scissor, viewport. */
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (srgb)
        glEnable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fb);
    gl_group_pop();
}

/* Counts the last item (a widget with its label) when it reaches past the
 * panel's right edge: cut off. */
void check_fits()
{
    float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x > right + 0.5f)
        g_ui->clipped++;
}

/* Draws a widget (`draw` returns ImGui's answer) and checks that it fits. */
template <typename F> bool fitted(F draw)
{
    bool r = draw();
    check_fits();
    return r;
}

/* A labelled widget whose label does not fit beside it at the panel's
 * item width gets the label on its own line above and the whole width
 * (so no label is cut off, whatever the panel's width). Returns the label
 * to give ImGui ("##" + label then, the same id every frame); `buf` holds
 * it. A label wider than the panel itself is still cut off (check_fits). */
const char *fit_label(const char *label, char *buf, size_t size)
{
    if (!label)
        return label;
    float lw = ImGui::CalcTextSize(label, nullptr, true).x;
    float avail = ImGui::GetContentRegionAvail().x;
    if (lw <= 0 ||
        ImGui::CalcItemWidth() + ImGui::GetStyle().ItemInnerSpacing.x + lw <= avail)
        return label;
    ImGui::TextUnformatted(label, strstr(label, "##"));
    check_fits();
    ImGui::SetNextItemWidth(-FLT_MIN);
    snprintf(buf, size, "##%s", label);
    return buf;
}

} // namespace

extern "C" {

dirt_ui *dirt_ui_create(dirt_gpu *gpu)
{
    if (!gpu || !gpu->window) {
        DIRT_ERROR("dirt_ui_create: the GPU has no window (create it with dirt_gpu_opts.window)");
        return nullptr;
    }
    if (gpu->ui) {
        DIRT_ERROR("dirt_ui_create: the GPU has a UI already (one per window)");
        return nullptr;
    }
    dirt_ui *ui = static_cast<dirt_ui *>(calloc(1, sizeof(dirt_ui)));
    if (!ui) {
        DIRT_ERROR("dirt_ui_create: out of memory");
        return nullptr;
    }
    ui->gpu = gpu;
    ImGuiContext *prev = ImGui::GetCurrentContext();
    IMGUI_CHECKVERSION();
    ui->ctx = ImGui::CreateContext();
    ImGui::SetCurrentContext(ui->ctx);
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr; /* the layout is the program's, the same on every run */
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    GLFWwindow *win = static_cast<GLFWwindow *>(gpu->window);
    if (!ImGui_ImplGlfw_InitForOpenGL(win, true)) {
        DIRT_ERROR("dirt_ui_create: ImGui's GLFW backend did not start");
        ImGui::DestroyContext(ui->ctx);
        ImGui::SetCurrentContext(prev);
        free(ui);
        return nullptr;
    }
    if (!ImGui_ImplOpenGL3_Init("#version 450")) {
        DIRT_ERROR("dirt_ui_create: ImGui's OpenGL 3 backend did not start");
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext(ui->ctx);
        ImGui::SetCurrentContext(prev);
        free(ui);
        return nullptr;
    }
    ImGui::SetCurrentContext(prev);
    gpu->ui = ui;
    return ui;
}

void dirt_ui_destroy(dirt_ui *ui)
{
    if (!ui)
        return;
    if (g_ui == ui)
        g_ui = nullptr;
    ImGuiContext *prev = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(ui->ctx);
    if (ui->in_frame)
        ImGui::EndFrame();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown(); /* puts the GPU's own callbacks back */
    ImGui::DestroyContext(ui->ctx);
    ImGui::SetCurrentContext(prev == ui->ctx ? nullptr : prev);
    ui->gpu->ui = nullptr;
    free(ui);
}

void gl_ui_release(dirt_gpu *gpu)
{
    dirt_ui_destroy(static_cast<dirt_ui *>(gpu->ui));
}

void gl_ui_make_current(dirt_gpu *gpu)
{
    if (gpu->ui)
        ImGui::SetCurrentContext(static_cast<dirt_ui *>(gpu->ui)->ctx);
}

void dirt_ui_begin_frame(dirt_ui *ui)
{
    if (!ui) {
        DIRT_ERROR("dirt_ui_begin_frame: NULL UI");
        return;
    }
    if (ui->in_frame) {
        DIRT_ERROR("dirt_ui_begin_frame: the frame is open already");
        return;
    }
    if (g_ui && g_ui != ui && g_ui->in_frame) {
        DIRT_ERROR("dirt_ui_begin_frame: another UI's frame is open");
        return;
    }
    ImGui::SetCurrentContext(ui->ctx);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGuiIO &io = ImGui::GetIO();
    /* Passes run back to back (dirt_ui_end_pass) may read the same clock;
     * ImGui needs time to move forward. */
    if (!(io.DeltaTime > 0.0f))
        io.DeltaTime = 1e-6f;
    ImGui::NewFrame();
    ui->wheel = io.MouseWheel;
    ui->wheel_h = io.MouseWheelH;
    ui->in_frame = true;
    ui->depth = 0;
    ui->tables = 0;
    ui->num_frame = 0;
    ui->clipped = 0;
    g_ui = ui;
}

/* Closes the open frame of `ui` (`fn` for the log); draws its panels when
 * `shown`. */
static void end_frame(dirt_ui *ui, bool shown, const char *fn)
{
    if (!ui || !ui->in_frame || g_ui != ui) {
        DIRT_ERROR("%s: no frame of this UI is open", fn);
        return;
    }
    while (ui->tables > 0) {
        DIRT_ERROR("%s: a table was left open", fn);
        dirt_ui_table_end();
    }
    while (ui->depth > 0) {
        DIRT_ERROR("%s: a panel was left open (dirt_ui_end)", fn);
        dirt_ui_end();
    }
    ImGuiIO &io = ImGui::GetIO();
    float wheel = io.MouseWheel - ui->wheel, wheel_h = io.MouseWheelH - ui->wheel_h;
    /* A poll within the frame (dirt-view's after its trace slice) may have
     * changed the modifier keys since NewFrame merged them; EndFrame checks
     * that they agree. */
    io.KeyMods = (io.KeyCtrl ? ImGuiKeyModFlags_Ctrl : 0) | (io.KeyShift ? ImGuiKeyModFlags_Shift : 0) |
                 (io.KeyAlt ? ImGuiKeyModFlags_Alt : 0) | (io.KeySuper ? ImGuiKeyModFlags_Super : 0);
    if (shown) {
        ImGui::Render();
        draw();
    } else {
        ImGui::EndFrame();
    }
    io.MouseWheel += wheel;
    io.MouseWheelH += wheel_h;
    ui->in_frame = false;
    memcpy(ui->last, ui->frame, sizeof(ui->frame));
    ui->num_last = ui->num_frame;
    ui->clipped_last = ui->clipped;
    g_ui = nullptr;
}

void dirt_ui_end_frame(dirt_ui *ui)
{
    end_frame(ui, true, "dirt_ui_end_frame");
}

void dirt_ui_end_pass(dirt_ui *ui)
{
    end_frame(ui, false, "dirt_ui_end_pass");
}

bool dirt_ui_buttons_changed(const dirt_ui *ui)
{
    if (!ui || !ui->in_frame)
        return false;
    const ImGuiIO &io = io_of(ui);
    for (int i = 0; i < IM_ARRAYSIZE(io.MouseDown); i++)
        if (io.MouseClicked[i] || io.MouseReleased[i])
            return true;
    return false;
}

int dirt_ui_clipped_labels(const dirt_ui *ui)
{
    return ui ? ui->clipped_last : 0;
}

bool dirt_ui_wants_mouse(const dirt_ui *ui)
{
    return ui && io_of(ui).WantCaptureMouse;
}

bool dirt_ui_wants_keyboard(const dirt_ui *ui)
{
    return ui && io_of(ui).WantCaptureKeyboard;
}

/* ---- panels ---- */

bool dirt_ui_begin(const char *title, bool *open, float x, float y, float w, float h)
{
    if (!in_frame("dirt_ui_begin"))
        return false;
    dirt_ui *ui = g_ui;
    if (ui->depth >= kMaxDepth) {
        DIRT_ERROR("dirt_ui_begin: panels nested deeper than %d", kMaxDepth);
        return false;
    }
    if (!title || (open && !*open)) {
        if (!title)
            DIRT_ERROR("dirt_ui_begin: NULL title");
        ui->began[ui->depth++] = false;
        return false;
    }
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(w, h), ImGuiCond_Once);
    bool visible = ImGui::Begin(title, open);
    ui->began[ui->depth++] = true;
    ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize(); /* collapsed: the title bar */
    if (ui->num_frame < kMaxRects)
        ui->frame[ui->num_frame++] = Rect{p.x, p.y, s.x, s.y};
    return visible;
}

void dirt_ui_next_collapsed(void)
{
    if (in_frame("dirt_ui_next_collapsed"))
        ImGui::SetNextWindowCollapsed(true, ImGuiCond_Once);
}

void dirt_ui_overlay_text(float x, float y, const char *text, float size[2])
{
    if (!in_frame("dirt_ui_overlay_text") || !text)
        return;
    ImVec2 t = ImGui::CalcTextSize(text);
    ImDrawList *dl = ImGui::GetForegroundDrawList();
    dl->AddRectFilled(ImVec2(x, y), ImVec2(x + t.x + 6, y + t.y + 4), IM_COL32(0, 0, 0, 200));
    dl->AddText(ImVec2(x + 3, y + 2), IM_COL32(255, 255, 255, 255), text);
    if (size)
        size[0] = t.x + 6, size[1] = t.y + 4;
}

/* The present shader's heat ramp at t in [0, 1] as the 8-bit sRGB colour it
 * displays (glsl/present/present.frag: heat, then srgb8). */
static ImU32 heat_colour(float t)
{
    static const float keys[DIRT_HEAT_KEYS][3] = {{DIRT_HEAT_KEY_0}, {DIRT_HEAT_KEY_1},
                                                  {DIRT_HEAT_KEY_2}, {DIRT_HEAT_KEY_3},
                                                  {DIRT_HEAT_KEY_4}};
    float x = (t < 0 ? 0 : t > 1 ? 1 : t) * (DIRT_HEAT_KEYS - 1);
    int k = (int)x < DIRT_HEAT_KEYS - 1 ? (int)x : DIRT_HEAT_KEYS - 2;
    float f = x - (float)k;
    int c[3];
    for (int j = 0; j < 3; j++) {
        float l = keys[k][j] + f * (keys[k + 1][j] - keys[k][j]);
        float e = l <= 0.0f  ? 0.0f
                  : l >= 1.0f ? 1.0f
                  : l <= DIRT_SRGB_LINEAR_MAX
                      ? DIRT_SRGB_LINEAR_SCALE * l
                      : DIRT_SRGB_SCALE * std::pow(l, DIRT_SRGB_EXPONENT) - DIRT_SRGB_OFFSET;
        c[j] = (int)std::lround(255.0f * (e < 0 ? 0 : e > 1 ? 1 : e));
    }
    return IM_COL32(c[0], c[1], c[2], 255);
}

void dirt_ui_overlay_ramp(float x, float y, float w, float h)
{
    if (!in_frame("dirt_ui_overlay_ramp"))
        return;
    ImDrawList *dl = ImGui::GetForegroundDrawList();
    /* One flat column per pixel: column i shows the ramp at (i + 0.5) / w,
     * as the present shader would show that value (no interpolation of
     * encoded colours between keys). */
    float x0 = std::floor(x + 0.5f), y0 = std::floor(y + 0.5f);
    int n = (int)std::lround(w), rows = (int)std::lround(h);
    for (int i = 0; i < n; i++)
        dl->AddRectFilled(ImVec2(x0 + (float)i, y0), ImVec2(x0 + (float)i + 1.0f, y0 + (float)rows),
                          heat_colour(((float)i + 0.5f) / (float)n));
}

void dirt_ui_end(void)
{
    if (!in_frame("dirt_ui_end"))
        return;
    if (g_ui->depth <= 0) {
        DIRT_ERROR("dirt_ui_end: no panel is open (dirt_ui_begin)");
        return;
    }
    if (g_ui->began[--g_ui->depth])
        ImGui::End();
}

void dirt_ui_panel_rect(float rect[4])
{
    rect[0] = rect[1] = rect[2] = rect[3] = 0.0f;
    if (!in_frame("dirt_ui_panel_rect"))
        return;
    if (g_ui->depth <= 0 || !g_ui->began[g_ui->depth - 1]) {
        DIRT_ERROR("dirt_ui_panel_rect: no panel is shown");
        return;
    }
    ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
    rect[0] = p.x, rect[1] = p.y, rect[2] = s.x, rect[3] = s.y;
}

void dirt_ui_item_rect(float rect[4])
{
    rect[0] = rect[1] = rect[2] = rect[3] = 0.0f;
    if (!in_frame("dirt_ui_item_rect") || g_ui->depth <= 0 || !g_ui->began[g_ui->depth - 1])
        return;
    ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    rect[0] = a.x, rect[1] = a.y, rect[2] = b.x - a.x, rect[3] = b.y - a.y;
}

bool dirt_ui_covers(const dirt_ui *ui, float x, float y)
{
    if (!ui)
        return false;
    for (int i = 0; i < ui->num_last; i++) {
        const Rect &r = ui->last[i];
        if (x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h)
            return true;
    }
    return false;
}

/* ---- widgets ---- */

void dirt_ui_text(const char *fmt, ...)
{
    if (!in_frame("dirt_ui_text"))
        return;
    va_list ap;
    va_start(ap, fmt);
    ImGui::PushTextWrapPos(0.0f); /* wrapped at the panel's edge, never cut off */
    ImGui::TextV(fmt, ap);
    ImGui::PopTextWrapPos();
    va_end(ap);
}

void dirt_ui_text_disabled(const char *fmt, ...)
{
    if (!in_frame("dirt_ui_text_disabled"))
        return;
    va_list ap;
    va_start(ap, fmt);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabledV(fmt, ap);
    ImGui::PopTextWrapPos();
    va_end(ap);
}

void dirt_ui_tooltip(const char *text)
{
    if (in_frame("dirt_ui_tooltip") && text && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", text);
}

bool dirt_ui_header(const char *label, bool default_open)
{
    return in_frame("dirt_ui_header") &&
           ImGui::CollapsingHeader(label, default_open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void dirt_ui_separator(void)
{
    if (in_frame("dirt_ui_separator"))
        ImGui::Separator();
}

void dirt_ui_same_line(void)
{
    if (in_frame("dirt_ui_same_line"))
        ImGui::SameLine();
}

bool dirt_ui_button(const char *label)
{
    if (!in_frame("dirt_ui_button"))
        return false;
    bool pressed = ImGui::Button(label);
    check_fits();
    return pressed;
}

bool dirt_ui_checkbox(const char *label, bool *value)
{
    if (!in_frame("dirt_ui_checkbox") || !value)
        return false;
    bool changed = ImGui::Checkbox(label, value);
    check_fits();
    return changed;
}

bool dirt_ui_radio(const char *label, int *value, int button_value)
{
    return in_frame("dirt_ui_radio") && value && ImGui::RadioButton(label, value, button_value);
}

bool dirt_ui_combo(const char *label, int *current, const char *const *items, int count)
{
    if (!in_frame("dirt_ui_combo") || !current)
        return false;
    if (!items || count <= 0) {
        DIRT_ERROR("dirt_ui_combo '%s': no items", label ? label : "");
        return false;
    }
    char buf[256];
    return fitted(
        [&] { return ImGui::Combo(fit_label(label, buf, sizeof(buf)), current, items, count); });
}

bool dirt_ui_slider_int(const char *label, int *value, int lo, int hi)
{
    char buf[256];
    return in_frame("dirt_ui_slider_int") && value &&
           fitted([&] {
               return ImGui::SliderInt(fit_label(label, buf, sizeof(buf)), value, lo, hi);
           });
}

bool dirt_ui_slider_float(const char *label, float *value, float lo, float hi,
                          const char *format, bool logarithmic)
{
    char buf[256];
    return in_frame("dirt_ui_slider_float") && value &&
           fitted([&] {
               return ImGui::SliderFloat(fit_label(label, buf, sizeof(buf)), value, lo, hi,
                                         format ? format : "%.3f",
                                         logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
           });
}

bool dirt_ui_input_int(const char *label, int *value, int step)
{
    char buf[256];
    return in_frame("dirt_ui_input_int") && value &&
           fitted([&] { return ImGui::InputInt(fit_label(label, buf, sizeof(buf)), value, step); });
}

bool dirt_ui_input_float(const char *label, float *value, const char *format)
{
    char buf[256];
    return in_frame("dirt_ui_input_float") && value &&
           fitted([&] {
               return ImGui::InputFloat(fit_label(label, buf, sizeof(buf)), value, 0.0f, 0.0f,
                                        format ? format : "%.3f");
           });
}

bool dirt_ui_input_float3(const char *label, float value[3], const char *format)
{
    char buf[256];
    return in_frame("dirt_ui_input_float3") && value &&
           fitted([&] {
               return ImGui::InputFloat3(fit_label(label, buf, sizeof(buf)), value,
                                         format ? format : "%.3f");
           });
}

bool dirt_ui_color3(const char *label, float rgb[3])
{
    char buf[256];
    return in_frame("dirt_ui_color3") && rgb &&
           fitted([&] { return ImGui::ColorEdit3(fit_label(label, buf, sizeof(buf)), rgb); });
}

bool dirt_ui_input_text(const char *label, char *buf, int size)
{
    if (!in_frame("dirt_ui_input_text"))
        return false;
    if (!buf || size <= 0) {
        DIRT_ERROR("dirt_ui_input_text '%s': no buffer", label ? label : "");
        return false;
    }
    char lb[256];
    return fitted(
        [&] { return ImGui::InputText(fit_label(label, lb, sizeof(lb)), buf, (size_t)size); });
}

void dirt_ui_plot_lines(const char *label, const float *values, int count, int offset,
                        const char *overlay, float lo, float hi, float height)
{
    if (!in_frame("dirt_ui_plot_lines"))
        return;
    if (!values || count <= 0) {
        DIRT_ERROR("dirt_ui_plot_lines '%s': no values", label ? label : "");
        return;
    }
    ImGui::PlotLines(label, values, count, offset, overlay, lo, hi, ImVec2(0.0f, height));
}

void dirt_ui_image(uint32_t texture, float w, float h)
{
    if (!in_frame("dirt_ui_image"))
        return;
    /* The backend binds the name as a GL_TEXTURE_2D; uv (0, 0) is the
     * texture's row 0, drawn at the top. */
    ImGui::Image((ImTextureID)(intptr_t)texture, ImVec2(w, h));
}

bool dirt_ui_table_begin(const char *id, int columns, const char *const *headers)
{
    if (!in_frame("dirt_ui_table_begin"))
        return false;
    if (columns < 1 || columns > 64) {
        DIRT_ERROR("dirt_ui_table_begin '%s': %d columns (1..64)", id ? id : "", columns);
        return false;
    }
    if (!ImGui::BeginTable(id, columns, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg))
        return false;
    g_ui->tables++;
    if (headers) {
        for (int i = 0; i < columns; i++)
            ImGui::TableSetupColumn(headers[i] ? headers[i] : "");
        ImGui::TableHeadersRow();
    }
    return true;
}

void dirt_ui_table_row(void)
{
    if (in_table("dirt_ui_table_row"))
        ImGui::TableNextRow();
}

void dirt_ui_table_cell(const char *fmt, ...)
{
    if (!in_table("dirt_ui_table_cell"))
        return;
    ImGui::TableNextColumn();
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}

void dirt_ui_table_end(void)
{
    if (!in_table("dirt_ui_table_end"))
        return;
    g_ui->tables--;
    ImGui::EndTable();
}

} // extern "C"
