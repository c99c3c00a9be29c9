/* dirt-view's state and its parts, one job per file:
 *   dirt_view.c        options, start, the frame loop, exit
 *   view_sessions.c    the render sessions kept in step with the settings
 *                      (the main one and the raster preview), the scene
 *   view_split.c       the split view: the comparison session
 *   view_look.c        which camera is shown, the free camera's moves
 *   view_input.c       the window's input: mouse, keys, drops, focus
 *   view_display.c     what the window shows: the image, the buffers
 *   view_panels.c      the panels
 *   view_script_run.c  the script's actions as the frames pass
 *   view_bookmarks.c   camera bookmarks, kept beside the scene
 *   view_outputs.c     screenshots, saved renders, reports, dirt-render
 *                      command lines
 * (view_camera.c: the free camera's maths; view_script.c: the script's
 * parser.) The program calls no GL: the sessions render, gl/window.h
 * presents, gl/ui.h draws the panels. */
#ifndef DIRT_APP_VIEW_H
#define DIRT_APP_VIEW_H

#include <stdbool.h>
#include <stddef.h>

#include "app/options.h"
#include "app/provenance.h"
#include "app/view_script.h"
#include "dirt/env.h"
#include "dirt/session.h"
#include "gl/ui.h"
#include "gl/window.h"

#define PROG "dirt-view"

/* The buffers the window can show (--buffer, keys 1 to 9). */
enum buffer {
    BUF_BEAUTY, BUF_ALBEDO, BUF_NORMAL, BUF_DEPTH, BUF_ID,
    BUF_LISTS, BUF_BUCKETS, BUF_ZMIN, BUF_ZMAX, NUM_BUFFERS
};

/* What the camera is: the scene's default, the automatic one, a scene
 * camera, or the free camera (a dirt_camera_look). */
enum cam_mode { CAM_DEFAULT, CAM_AUTO, CAM_SCENE, CAM_LOOK };

#define RING 240
#define NUM_BOOKMARKS 9
#define INSPECT_CHANNELS 20

typedef struct viewer {
    app_opts o;                 /* the command line, then the panels and the script */
    app_provenance prov;        /* of saved renders */
    dirt_gpu *gpu;
    dirt_ui *ui;
    dirt_scene *scene;
    char scene_name[4096];
    dirt_env *env, *env_old;    /* --env (o.s.env), and the one it replaced */
    float env_intensity, env_rotation; /* what env was made with */
    dirt_session *s, *cmp;
    int cmp_engine;             /* engine of cmp, -1 none */
    dirt_image *ref;            /* --compare-image: the reference, shown instead of cmp */
    uint32_t ref_tex;           /*   its display texture (0 until uploaded) */
    bool ref_on;                /*   shown (V toggles it) */
    bool ref_mismatch;          /*   its size is not the render's (said once) */
    dirt_session *pre;          /* the raster preview shown while the camera moves */
    bool moving;                /* input moved the camera in this frame */
    bool hold;                  /* an output was taken in this frame: no new samples */
    dirt_session_opts applied;  /* the options s has */
    int rw, rh;                 /* render size in use */
    /* camera */
    enum cam_mode cam_mode;
    int cam_index;
    dirt_camera_look look;
    bool cam_dirty;
    float diag;                 /* the scene's bounding-box diagonal */
    /* time */
    double applied_time;
    int applied_clip;
    bool applied_loop, time_dirty;
    /* display */
    uint32_t aux_tex;
    int aux_w, aux_h;
    long aux_key;               /* generation the aux texture shows, -1 none */
    float aux_lo, aux_hi;
    float zoom;                 /* 0: fitted; else window pixels per image pixel */
    double zoom_u, zoom_v;      /* with a zoom: the image point at the window's centre
                                   (fractions of the image) */
    long generation;            /* bumps on every restart and sample */
    /* numbers */
    float frame_ms[RING], sample_ms[RING];
    int ring_pos, ring_count;
    dirt_session_stats last;    /* stats after the last frame's samples */
    dirt_pass_time frame_passes[32]; /* the last build's, then this frame's samples' */
    int num_frame_passes;
    int num_build_passes;       /* frame_passes[0 .. num_build_passes): the build's */
    /* input and script */
    int held[DIRT_NUM_KEYS];    /* frames a script key stays held */
    bool pressed[DIRT_NUM_KEYS]; /* a script key went down in this frame */
    unsigned char pressed_mods[DIRT_NUM_KEYS]; /* with these DIRT_MOD_* ("key Ctrl+1") */
    /* camera bookmarks (view_bookmarks.c), slot i is key i + 1 */
    struct view_bookmark {
        bool set;
        dirt_camera_look look;  /* the free camera */
        float aperture, focus;  /* the thin lens */
    } bookmarks[NUM_BOOKMARKS];
    char bm_path[4200];         /* <scene>.bookmarks.json; "" for the default scene (memory) */
    bool bm_keep_file;          /* the file could not be read: it is never written */
    char bm_note[4800];         /* what the Bookmarks panel says of the file */
    view_script script;
    size_t next_action;
    long wait_frames;
    int wait_samples;
    char wait_file[4096];
    bool click_pending;
    double click_x, click_y;
    long frame;
    bool show_help, quit;
    int exit_code;
    int shots;                  /* numbers the P / O files */
    char shot_path[4][4096];    /* window screenshots asked for in this frame */
    int num_shots;
    char status[512];
    float memory_rect[4];       /* the Numbers panel's memory line (window pixels) */
    int shader_reloads;         /* F5 reloads that took */
    int shader_reload_failures; /* F5 reloads refused (the old programs kept) */
    char reload_status[512];    /* what the last F5 did */
    float panels[5][4];
    int num_panels;
    int win_w, win_h;
    /* drawn over the image with the panels: the split's labels, the colour
     * bar of a heat map or difference (for the report) */
    char label[4][64];
    float label_rect[4][4];
    int num_labels;
    bool bar;
    float bar_lo, bar_hi, bar_rect[4];
    int slow_frame_ms;          /* test hook DIRT_VIEW_SLOW_FRAME_MS: added to every frame */
    FILE *frame_log;            /* test hook DIRT_VIEW_FRAME_LOG: a line per frame shown */
    /* a sample in pieces over frames (--slice-ms) */
    double sample_work_ms;      /* time in the sample in progress so far */
    double last_sample_ms;      /* the last completed sample's (0: none yet) */
    long ui_passes;             /* passes of the panels' logic only, all frames (frame log) */
    long releases;              /* mouse button releases seen, all frames (frame log) */
    /* the automatic --scale on a software renderer (o.scale 0 at start) */
    bool auto_scale;            /* o.scale is the automatic choice */
    double pace_ms;             /* a sample's milliseconds per pixel (measured, or assumed) */
    bool paced;                 /* this accumulation's pace was looked at */
    int auto_w, auto_h;         /* the window size the scale was chosen for */
    int auto_n;                 /* the scale it chose */
    char scale_note[192];       /* what the panel says of it */
    /* the inspector: every channel of both images under the cursor */
    double cursor_x, cursor_y;  /* window pixels */
    struct view_probe {
        bool valid;             /* the cursor is over the image, which has samples */
        int x, y;               /* render pixel */
        int count;
        char names[INSPECT_CHANNELS][32];
        float values[INSPECT_CHANNELS];
    } probe[2];                 /* the main session, the comparison */
} viewer;

/* The status line of the Settings panel, also printed unless --quiet. */
void view_status(viewer *v, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* view_sessions.c */
/* The samples session `s` accumulates to: --spp (0: no limit), 1 for the
 * raster preview (its one image is the whole result). */
int view_target(const viewer *v, const dirt_session *s);
dirt_session_opts view_wanted_opts(const viewer *v, int engine);
bool view_load_scene(viewer *v, dirt_scene *sc, const char *path);
void view_render_size(viewer *v, int win_w, int win_h);
bool view_sync_sessions(viewer *v);
/* Shader reload (F5): with the shaders read from a source tree
 * (view_shader_source), remakes the sessions and the presentation program from
 * them; a shader that does not compile keeps the old programs (the status
 * line and the log say why). False when nothing was reloaded. */
bool view_reload_shaders(viewer *v);
/* Where F5 reads the shaders from, into `dir`: "DIRT_GLSL_DIR" (that
 * folder); "build tree" when this dirt-view runs from a meson build tree
 * (a parent folder of /proc/self/exe holds meson-info/meson-info.json
 * naming that folder as the build) and its source tree's glsl/ is there;
 * NULL when there is none (why in `why`: an installed program uses the
 * library's embedded shaders). */
const char *view_shader_source(char *dir, size_t size, char *why, size_t why_size);

/* view_split.c */
/* Reads --compare-image (before the window): exit 2's reasons printed,
 * false when it cannot be read or its size is not the render's (-W/-H);
 * without -W/-H the render takes its size. */
bool view_load_reference(viewer *v);
/* The comparison shown now: the reference (when its size is the render's)
 * or the comparison session, with samples; its name ("reference" or the
 * engine's). */
bool view_ref_shown(const viewer *v);
bool view_comparing(const viewer *v);
const char *view_compare_name(const viewer *v);
bool view_sync_compare(viewer *v);
void view_sample_compare(viewer *v);
void view_present_split(const viewer *v, dirt_present_opts *p);

/* view_look.c */
bool view_apply_camera(viewer *v, dirt_session *s);
void view_to_look(viewer *v);
/* The free camera of what is shown now (the current look, or one made from
 * the scene's / automatic camera), without switching to it. */
void view_current_look(const viewer *v, dirt_camera_look *look);
void view_reset_camera(viewer *v);
void view_cycle_camera(viewer *v);
void view_camera_args(const viewer *v, char *buf, size_t size);

/* view_input.c */
void view_handle_input(viewer *v, const dirt_window_input *in, double dt, bool ui_mouse,
                       bool ui_keys);
bool view_open_drops(viewer *v, const dirt_window_input *in);
void view_focus_at(viewer *v);
/* A key name with modifiers ("Ctrl+1", "Shift+F5", "W"): the key, its
 * DIRT_MOD_* bits in *mods; DIRT_KEY_NONE when unknown. */
enum dirt_key view_key_parse(const char *name, unsigned char *mods);

/* view_display.c */
void view_fit(const viewer *v, int w, int h, int r[4]);
/* Zoom: `zoom` window pixels per image pixel (clamped to 1/16 .. 64; 0 or
 * less: fitted), keeping the image point under window pixel (wx, wy) there;
 * `steps` powers of two in (+) or out (-) from the scale shown; panning the
 * image by window pixels (a fitted image keeps its scale). */
void view_zoom_at(viewer *v, double zoom, double wx, double wy);
void view_zoom_steps(viewer *v, double steps, double wx, double wy);
void view_pan_image(viewer *v, double dx, double dy);
void view_draw(viewer *v, bool preview);

/* The values of every channel (R, G, B, A, then the AOVs) of both images
 * at the render pixel under the cursor (reads the images back). */
void view_inspect(viewer *v);

/* view_bookmarks.c */
/* The bookmarks file of a scene: "<scene path>.bookmarks.json" into `buf`;
 * "" for the default scene (NULL or "default": its bookmarks live in
 * memory only). */
void view_bookmarks_path(const char *scene_path, char *buf, size_t size);
/* Forgets the bookmarks and reads those of the scene at `scene_path`
 * (view_bookmarks_path). A missing file: no bookmarks. An unreadable or
 * malformed one: a log line, no bookmarks, and the file is never written
 * in this scene's session (bm_keep_file). */
void view_bookmarks_open(viewer *v, const char *scene_path);
/* Slot 1 .. 9: stores the camera shown now (and the lens) / shows the
 * stored one (the free camera, the lens) / forgets it. A change is
 * written to the file at once, atomically; when it cannot be (the default
 * scene, an unreadable file, a folder not writable) the bookmark is kept
 * in memory and the status line says so. False for an empty slot (go,
 * delete) or a slot out of range. */
bool view_bookmark_save(viewer *v, int slot);
bool view_bookmark_go(viewer *v, int slot);
bool view_bookmark_delete(viewer *v, int slot);

/* view_panels.c */
void view_panels(viewer *v);

/* view_script_run.c */
bool view_run_script(viewer *v);
bool view_check_script(const view_script *sc, const app_opts *o);

/* view_outputs.c */
bool view_save_render(viewer *v, const char *path);
bool view_screenshot(viewer *v, const char *path);
bool view_take_screenshots(viewer *v);
void view_render_args(const viewer *v, char *buf, size_t size);
/* Checks the files of this run with `scene` (loaded from `scene_path`,
 * NULL for the default scene) as its scene: no output asked for (at exit
 * or by the script) may be the scene, a file it read, the environment or
 * the script (cli_check_io). DIRT_EXIT_OK, or DIRT_EXIT_USAGE after
 * printing why. */
int view_check_io(const viewer *v, const char *scene_path, const dirt_scene *scene);
/* Names the next file of the P / O keys and buttons, "dirt-view-N.EXT" in
 * the current folder with N the first number after the last one used
 * whose file does not exist, so that no file is replaced. */
void view_shot_name(viewer *v, const char *ext, char *path, size_t size);
bool view_write_report(viewer *v, const char *path);
extern const char *const view_bindings[][2];
extern const size_t view_num_bindings;

#endif
