/* dirt-view: the interactive viewer on the render session (doc/viewer.md).
 *
 * A GLFW window with panels (dirt/ui.h) over the progressive render of one
 * session, and optionally a second session on the same camera for a split
 * or difference view. Every displayed frame adds a bounded number of
 * samples (--samples-per-frame, default 1), never a whole render. The
 * program calls no GL: the session renders, dirt/window.h presents. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "app/cli.h"
#include "app/sequence.h"
#include "app/view_camera.h"
#include "app/view_script.h"
#include "dirt/clock.h"
#include "dirt/file.h"
#include "dirt/integrator.h"
#include "dirt/log.h"
#include "dirt/session.h"
#include "dirt/ui.h"
#include "dirt/window.h"

#define PROG "dirt-view"

enum buffer {
    BUF_BEAUTY, BUF_ALBEDO, BUF_NORMAL, BUF_DEPTH, BUF_ID,
    BUF_LISTS, BUF_BUCKETS, BUF_ZMIN, BUF_ZMAX, NUM_BUFFERS
};
static const char *const buffer_names[NUM_BUFFERS + 1] = {
    "beauty", "albedo", "normal", "depth", "id", "lists", "buckets", "zmin", "zmax", NULL};
static const char *const buffer_labels[NUM_BUFFERS] = {
    "beauty", "albedo", "normal", "depth (Z)", "primitive id (first hit)",
    "list length per tile / fragments per pixel", "bucket occupancy",
    "depth bounds: min", "depth bounds: max"};

static const char *const modes[] = {"pt", "ao", NULL};
static const char *const views[] = {"", "single", "cube", "cube+camera", NULL};
static const char *const fetches[] = {"compute", "raster", NULL};
static const char *const marches[] = {"hiz", "linear", NULL};
static const char *const tonemaps[] = {"clamp", "reinhard", "aces", NULL};
static const char *const compares[] = {"none", "dirt", "mmrt", "embree", "raster", NULL};

/* What the command line, the panels and the script set. */
typedef struct vopts {
    const char *scene_path;     /* NULL = the embedded default scene */
    dirt_session_opts s;        /* width 0: the render follows the window */
    int spp;                    /* target samples (0 = no limit) */
    int samples_per_frame;
    int camera;                 /* -1 default, -2 automatic, else the scene's camera */
    dirt_camera_look look;
    bool eye_set, target_set, look_set;
    double time, speed;
    int clip;
    bool loop, play;
    int win_w, win_h;
    int compare;                /* index in compares: 0 none, else engine + 1 */
    float split;                /* 0..1: where the split is (0 = difference view) */
    bool diff;
    float diff_range;
    int buffer;
    float exposure;
    int tonemap;
    long hiz_top;               /* -1 = the pyramid's top */
    long large;                 /* --large: -1 = the default, 0 = none */
    bool no_ui, cpu_timing, quiet, conservative_off, direct_visibility;
    bool no_preview;            /* path trace while moving too (no raster preview) */
    int scale;                  /* render at the window's size / scale */
    const char *script, *screenshot, *save_image, *report;
    long test_frames;
    const char *env_path;       /* --env: a map file or "sky" */
    float env_intensity, env_rotation;
    dirt_load_opts load;        /* --max-scene-memory, --strict, --allow-outside-paths */
} vopts;

/* Options with a value, by name (the command line's long names; the
 * script's `set` names drop the dashes). Kinds as cli_value, plus 'B'
 * (bool on/off) and 'n' (a buffer name). */
typedef struct vopt_spec {
    const char *s, *l;
    char kind;
    size_t off;
    double lo, hi;
    const char *const *names;
    bool runtime;               /* may change while the window is open */
} vopt_spec;

#define OFF(f) offsetof(vopts, f)
static const vopt_spec specs[] = {
    {"-W", "--width", 'i', OFF(s.width), 16, 16384, NULL, true},
    {"-H", "--height", 'i', OFF(s.height), 16, 16384, NULL, true},
    {NULL, "--window", 's', 0, 0, 0, NULL, false},
    {NULL, "--engine", 'c', OFF(s.engine), 0, 0, NULL, true},
    {NULL, "--compare", 'c', OFF(compare), 0, 0, compares, true},
    {NULL, "--split", 'f', OFF(split), 0, 1, NULL, true},
    {NULL, "--diff", 'B', OFF(diff), 0, 0, NULL, true},
    {NULL, "--diff-range", 'f', OFF(diff_range), 1e-6, 1e6, NULL, true},
    {NULL, "--mode", 'c', OFF(s.mode), 0, 0, modes, true},
    {NULL, "--spp", 'i', OFF(spp), 0, 1 << 20, NULL, true},
    {NULL, "--samples-per-frame", 'i', OFF(samples_per_frame), 1, 1024, NULL, true},
    {NULL, "--bounces", 'i', OFF(s.bounces), 1, 64, NULL, true},
    {NULL, "--seed", 'u', OFF(s.seed), 0, 4294967295.0, NULL, true},
    {NULL, "--ao-distance", 'f', OFF(s.ao_distance), 0, 1e30, NULL, true},
    {NULL, "--background", 'b', OFF(s.background), 0, 0, NULL, true},
    {NULL, "--env", 's', OFF(env_path), 0, 0, NULL, false},
    {NULL, "--env-intensity", 'f', OFF(env_intensity), 1e-6, 1e6, NULL, true},
    {NULL, "--env-rotation", 'f', OFF(env_rotation), -1e6, 1e6, NULL, true},
    {NULL, "--threads", 'i', OFF(s.threads), 1, 4096, NULL, true},
    {NULL, "--camera", 'i', OFF(camera), 0, 1000000, NULL, true},
    {NULL, "--eye", 'v', OFF(look.eye), 0, 0, NULL, true},
    {NULL, "--look-at", 'v', OFF(look.target), 0, 0, NULL, true},
    {NULL, "--up", 'v', OFF(look.up), 0, 0, NULL, true},
    {NULL, "--fov", 'f', OFF(look.fov_deg), 1e-3, 179.9, NULL, true},
    {NULL, "--znear", 'f', OFF(look.znear), 1e-12, 1e30, NULL, true},
    {NULL, "--zfar", 'f', OFF(look.zfar), 1e-12, 1e30, NULL, true},
    {NULL, "--aperture", 'f', OFF(s.aperture), 0, 1e6, NULL, true},
    {NULL, "--focus", 'f', OFF(s.focus), 0, 1e9, NULL, true},
    {"-t", "--time", 'd', OFF(time), -1e6, 1e6, NULL, true},
    {NULL, "--speed", 'd', OFF(speed), -100, 100, NULL, true},
    {NULL, "--clip", 'i', OFF(clip), -1, 1000000, NULL, true},
    {NULL, "--loop", 'B', OFF(loop), 0, 0, NULL, true},
    {NULL, "--play", 'B', OFF(play), 0, 0, NULL, true},
    {NULL, "--views", 'c', OFF(s.views), 0, 0, views, true},
    {"-S", "--tile", 'i', OFF(s.tile_size), 1, 8, NULL, true},
    {"-B", "--buckets", 'i', OFF(s.buckets), 1, 1024, NULL, true},
    {NULL, "--face-size", 'i', OFF(s.face_size), 1, 16384, NULL, true},
    {NULL, "--hiz-top", 'l', OFF(hiz_top), -1, 15, NULL, true},
    {NULL, "--large", 'l', OFF(large), 0, DIRT_ADS_MAX_LARGE, NULL, true},
    {NULL, "--fetch", 'c', OFF(s.fetch), 0, 0, fetches, true},
    {NULL, "--direct-visibility", 'B', OFF(direct_visibility), 0, 0, NULL, true},
    {NULL, "--no-conservative-raster", 'B', OFF(conservative_off), 0, 0, NULL, true},
    {NULL, "--march", 'c', OFF(s.march), 0, 0, marches, true},
    {NULL, "--samples", 'i', OFF(s.march_samples), 1, 65536, NULL, true},
    {NULL, "--thickness", 'f', OFF(s.thickness), 0, 1e12, NULL, true},
    {NULL, "--buffer", 'c', OFF(buffer), 0, 0, buffer_names, true},
    {NULL, "--exposure", 'f', OFF(exposure), -64, 64, NULL, true},
    {NULL, "--tonemap", 'c', OFF(tonemap), 0, 0, tonemaps, true},
    {NULL, "--no-ui", 'B', OFF(no_ui), 0, 0, NULL, true},
    {NULL, "--no-preview", 'B', OFF(no_preview), 0, 0, NULL, true},
    {NULL, "--scale", 'i', OFF(scale), 1, 16, NULL, true},
    {NULL, "--cpu-timing", 'B', OFF(cpu_timing), 0, 0, NULL, false},
    {"-q", "--quiet", 'B', OFF(quiet), 0, 0, NULL, false},
    {NULL, "--script", 's', OFF(script), 0, 0, NULL, false},
    {NULL, "--test-frames", 'l', OFF(test_frames), 1, 1e9, NULL, false},
    {NULL, "--screenshot", 's', OFF(screenshot), 0, 0, NULL, false},
    {NULL, "--save-image", 's', OFF(save_image), 0, 0, NULL, false},
    {NULL, "--report", 'j', OFF(report), 0, 0, NULL, false},
    {NULL, "--max-scene-memory", 'z', OFF(load.max_bytes), 1 << 20, 1e13, NULL, false},
    {NULL, "--strict", 'B', OFF(load.strict), 0, 0, NULL, false},
    {NULL, "--allow-outside-paths", 'B', OFF(load.allow_outside), 0, 0, NULL, false},
};
#undef OFF
#define NUM_SPECS (sizeof(specs) / sizeof(specs[0]))

static void usage(FILE *f)
{
    fputs(
"Usage: dirt-view [SCENE] [options]\n"
"\n"
"Interactive viewer: progressive path tracing of a glTF 2.0 (.gltf, .glb) or\n"
"  OBJ (.obj) scene (without SCENE, the embedded default scene) through DIRT,\n"
"  the MMRT A-buffer, Embree or the raster preview, with panels for every\n"
"  setting, the structure's heat maps, per-pass timings and memory. F1 in the\n"
"  window lists the key bindings (also doc/viewer.md, --bindings).\n"
"\n"
"Window and render:\n"
"      --window WxH      window size (default 1280x720)\n"
"  -W, --width N         render width (default: follow the window)\n"
"  -H, --height N        render height (default: follow the window, or\n"
"                        width / the camera's aspect with --width)\n"
"      --spp N           stop accumulating at N samples (default 1024; 0 = never)\n"
"      --samples-per-frame N  samples added per displayed frame (default 1)\n"
"      --buffer NAME     beauty (default), albedo, normal, depth, id, lists,\n"
"                        buckets, zmin, zmax\n"
"      --exposure STOPS, --tonemap clamp|reinhard|aces   display (and PNG output)\n"
"      --compare ENGINE  split view against a second engine on the same camera:\n"
"                        dirt, mmrt, embree or raster (default none)\n"
"      --split X         where the split is, 0..1 of the width (default 0.5)\n"
"      --diff            with --compare: a heat map of the difference instead of\n"
"                        the split (X toggles it)\n"
"      --diff-range R    the difference that shows white (default 0.1)\n"
"      --scale N         render at the window's size / N, shown enlarged (default 1)\n"
"      --no-preview      path trace while the camera moves (default: the raster\n"
"                        preview until it stops)\n"
"      --no-ui           hide the panels (H toggles them)\n"
"\n"
"Scene, camera and animation (as dirt-render):\n"
"  -t, --time T, --clip I, --loop, --play, --speed X (time scale, default 1)\n"
"      --camera I, --auto-camera, --eye X,Y,Z --look-at X,Y,Z [--up X,Y,Z]\n"
"      [--fov DEG] [--znear Z] [--zfar Z], --aperture R, --focus D\n"
"\n"
"Technique (as dirt-render): --engine dirt|mmrt|embree|raster, --mode pt|ao,\n"
"  --bounces K, --seed N, --ao-distance D, --background R,G,B, --threads N,\n"
"  --env FILE.exr|FILE.hdr|sky [--env-intensity X] [--env-rotation DEG],\n"
"  --views single|cube|cube+camera, -S/--tile S, -B/--buckets B, --face-size N,\n"
"  --hiz-top L, --large N, --fetch compute|raster, --direct-visibility,\n"
"  --no-conservative-raster, --march hiz|linear, --samples N, --thickness T,\n"
"  --cpu-timing\n"
"\n"
"Inputs (as dirt-render; doc/scenes.md): --max-scene-memory SIZE (the scene's\n"
"  and the --env map's load budget, default 512M), --strict (a warning about the\n"
"  scene exits 2), --allow-outside-paths (references may leave its folder)\n"
"\n"
"Scripted mode (tests, reproducible demos):\n"
"      --script FILE     timed actions (doc/viewer.md: wait-frames, wait-samples,\n"
"                        wait-file, orbit, pan, dolly, fly, camera, key, click, set, resize,\n"
"                        screenshot, save-image, report, print-camera, quit)\n"
"      --test-frames N   quit after N frames\n"
"      --screenshot FILE.png  at exit: the window, panels included\n"
"      --save-image FILE.exr  at exit: the render alone (.exr with a .png beside\n"
"                        it, or .png)\n"
"      --report FILE.json     at exit: camera (as dirt-render options), sizes,\n"
"                        samples, panel rectangles\n"
"      --bindings        print the key and mouse bindings and exit\n"
"  -q, --quiet, -v, --verbose, -h, --help\n"
"\n"
"Exit status: 0 done, 1 a write failed, 2 bad option, scene or script (or an\n"
"output that is an input), 3 no window or OpenGL 4.5 context.\n", f);
}

/* ---- bindings (F1, --bindings, doc/viewer.md) ---- */

static const char *const bindings[][2] = {
    {"Left drag", "orbit around the target"},
    {"Right drag, Middle drag", "pan"},
    {"Wheel", "dolly toward / away from the target"},
    {"W A S D", "fly forward, left, back, right"},
    {"Q E", "fly down, up"},
    {"Shift", "with W A S D Q E: 5x faster"},
    {"Double click", "focus the thin lens on the surface under the cursor"},
    {"R", "reset the camera (the scene's, or the automatic one)"},
    {"C", "next scene camera"},
    {"1 .. 9", "buffer: beauty, albedo, normal, depth, id, lists, buckets, zmin, zmax"},
    {"Tab", "next engine (dirt, mmrt, embree, raster)"},
    {"V", "split view against the comparison engine on / off"},
    {"X", "difference heat map of the split on / off"},
    {"Space", "play / pause the animation"},
    {"Left Right", "step the animation one frame (1/24 s) back / forward"},
    {"Minus Equal", "exposure down / up one stop"},
    {"P", "screenshot of the window (dirt-view-N.png)"},
    {"O", "save the render (dirt-view-N.exr and .png)"},
    {"H", "hide / show the panels"},
    {"F1", "this help"},
    {"Escape", "quit"},
};
#define NUM_BINDINGS (sizeof(bindings) / sizeof(bindings[0]))

/* ---- option parsing ---- */

static const vopt_spec *find_spec(const char *name, bool script)
{
    for (size_t k = 0; k < NUM_SPECS; k++) {
        const vopt_spec *sp = &specs[k];
        if (script ? !strcmp(sp->l + 2, name)
                   : (!strcmp(sp->l, name) || (sp->s && !strcmp(sp->s, name))))
            return sp;
    }
    return NULL;
}

static bool parse_window(const char *val, vopts *o)
{
    int w, h;
    char extra;
    if (sscanf(val, "%dx%d%c", &w, &h, &extra) != 2 || w < 64 || h < 64 || w > 16384 ||
        h > 16384) {
        cli_error(PROG, "--window expects WxH (64..16384), got '%s'", val);
        return false;
    }
    o->win_w = w;
    o->win_h = h;
    return true;
}

/* Sets one option from text; false after printing why. */
static bool apply_spec(const vopt_spec *sp, const char *name, const char *val, vopts *o)
{
    const char *engines[DIRT_NUM_ENGINES + 1] = {0};
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        engines[e] = dirt_engine_names[e];
    char *dst = (char *)o + sp->off;
    if (!strcmp(sp->l, "--window"))
        return parse_window(val, o);
    if (sp->kind == 'B') {
        bool on = !strcmp(val, "on") || !strcmp(val, "1") || !strcmp(val, "true");
        bool off = !strcmp(val, "off") || !strcmp(val, "0") || !strcmp(val, "false");
        if (!on && !off) {
            cli_error(PROG, "%s expects on or off, got '%s'", name, val);
            return false;
        }
        *(bool *)dst = on;
        return true;
    }
    if (sp->kind == 's') {
        *(const char **)dst = val;
        return true;
    }
    if (!cli_value(PROG, name, val, sp->kind, dst, sp->lo, sp->hi,
                   sp->names ? sp->names : engines))
        return false;
    o->eye_set |= sp->off == offsetof(vopts, look.eye);
    o->target_set |= sp->off == offsetof(vopts, look.target);
    o->look_set |= sp->kind == 'v' || sp->off == offsetof(vopts, look.fov_deg) ||
                   sp->off == offsetof(vopts, look.znear) || sp->off == offsetof(vopts, look.zfar);
    return true;
}

static bool check_paths(const vopts *o)
{
    if (o->screenshot && !cli_has_ext(o->screenshot, ".png")) {
        cli_error(PROG, "--screenshot '%s' must end in .png", o->screenshot);
        return false;
    }
    if (o->save_image && !cli_has_ext(o->save_image, ".exr") &&
        !cli_has_ext(o->save_image, ".png")) {
        cli_error(PROG, "--save-image '%s' must end in .exr or .png", o->save_image);
        return false;
    }
    if (o->look_set && !(o->eye_set && o->target_set)) {
        cli_error(PROG, "a camera of its own needs both --eye and --look-at");
        return false;
    }
    bool background = o->s.background[0] || o->s.background[1] || o->s.background[2];
    if (o->env_path && background) {
        cli_error(PROG, "--env and --background both set the environment: give one");
        return false;
    }
    if (!o->env_path && (o->env_intensity != 0 || o->env_rotation != 0)) {
        cli_error(PROG, "--env-intensity and --env-rotation need an --env map");
        return false;
    }
    char why[256];
    dirt_session_opts s = o->s;
    if (!s.width)
        s.width = 640;
    if (!dirt_session_check_opts(&s, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
        return false;
    }
    return true;
}

/* DIRT_EXIT_OK, DIRT_EXIT_USAGE after printing why, -1 for --help, -2 for
 * --bindings. */
static int parse_args(int argc, char **argv, vopts *o)
{
    *o = (vopts){.spp = 1024, .samples_per_frame = 1, .scale = 1, .camera = -1, .speed = 1,
                 .win_w = 1280, .win_h = 720, .split = 0.5f, .diff_range = 0.1f,
                 .hiz_top = -1, .large = -1, .look = {.up = {0, 1, 0}}};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const vopt_spec *sp = a[0] == '-' ? find_spec(a, false) : NULL;
        if (sp && sp->kind == 'B') {
            *(bool *)((char *)o + sp->off) = true;
            continue;
        }
        if (sp) {
            if (i + 1 >= argc) {
                cli_error(PROG, "option %s needs a value", a);
                return DIRT_EXIT_USAGE;
            }
            if (!apply_spec(sp, a, argv[++i], o))
                return DIRT_EXIT_USAGE;
            continue;
        }
        if (!strcmp(a, "-h") || !strcmp(a, "--help"))
            return -1;
        if (!strcmp(a, "--bindings"))
            return -2;
        if (!strcmp(a, "--auto-camera")) {
            o->camera = -2;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            dirt_log_set_level(DIRT_LOG_DEBUG);
        } else if (a[0] == '-' && a[1] != '\0') {
            cli_error(PROG, "unknown option '%s' (see --help)", a);
            return DIRT_EXIT_USAGE;
        } else if (!o->scene_path) {
            o->scene_path = a;
        } else {
            cli_error(PROG, "more than one scene given ('%s' and '%s')", o->scene_path, a);
            return DIRT_EXIT_USAGE;
        }
    }
    if (o->quiet)
        dirt_log_set_level(DIRT_LOG_ERROR);
    return check_paths(o) ? DIRT_EXIT_OK : DIRT_EXIT_USAGE;
}

/* ---- the viewer ---- */

enum cam_mode { CAM_DEFAULT, CAM_AUTO, CAM_SCENE, CAM_LOOK };

#define RING 240

typedef struct viewer {
    vopts o;
    dirt_gpu *gpu;
    dirt_ui *ui;
    dirt_scene *scene;
    char scene_name[4096];
    dirt_env *env, *env_old;    /* --env (v->o.s.env), and the one it replaced */
    float env_intensity, env_rotation; /* what env was made with */
    dirt_session *s, *cmp;
    int cmp_engine;             /* engine of cmp, -1 none */
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
    long generation;            /* bumps on every restart and sample */
    /* numbers */
    float frame_ms[RING], sample_ms[RING];
    int ring_pos, ring_count;
    dirt_session_stats last;    /* stats after the last frame's samples */
    dirt_pass_time frame_passes[32];
    int num_frame_passes;
    /* input and script */
    int held[DIRT_NUM_KEYS];    /* frames a script key stays held */
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
    float panels[4][4];
    int num_panels;
    int win_w, win_h;
} viewer;

static void set_status(viewer *v, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void set_status(viewer *v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->status, sizeof(v->status), fmt, ap);
    va_end(ap);
    if (!v->o.quiet)
        fprintf(stderr, "%s: %s\n", PROG, v->status);
}

/* The session options the viewer's settings ask for. */
static dirt_session_opts wanted_opts(const viewer *v, int engine)
{
    dirt_session_opts s = v->o.s;
    s.engine = (enum dirt_engine)engine;
    s.width = v->rw;
    s.height = v->rh;
    s.hiz_levels = (int)(v->o.hiz_top + 1);
    if (v->o.large >= 0)
        s.large = v->o.large ? (int)v->o.large : -1;
    s.force_emulation = v->o.conservative_off;
    s.direct_visibility = v->o.direct_visibility;
    if (s.engine != DIRT_ENGINE_MMRT) {
        s.march = 0;
        s.march_samples = 0;
        s.thickness = 0;
    }
    if (!(s.aperture > 0))
        s.focus = 0;
    return s;
}

static float scene_diagonal(const dirt_frame *f)
{
    float d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += (f->bounds_max[k] - f->bounds_min[k]) * (f->bounds_max[k] - f->bounds_min[k]);
    return d2 > 0 ? sqrtf(d2) : 1.0f;
}

/* The camera the session shows, applied to a session. */
static bool apply_camera(viewer *v, dirt_session *s)
{
    if (v->cam_mode == CAM_LOOK) {
        dirt_camera c;
        dirt_camera_from_look(&v->look, &c);
        return dirt_session_set_camera(s, DIRT_CAMERA_EXPLICIT, 0, &c);
    }
    enum dirt_camera_choice ch = v->cam_mode == CAM_SCENE ? DIRT_CAMERA_SCENE
                                 : v->cam_mode == CAM_AUTO ? DIRT_CAMERA_AUTO
                                                           : DIRT_CAMERA_DEFAULT;
    return dirt_session_set_camera(s, ch, v->cam_index, NULL);
}

/* Switches to the free camera, starting from what is shown now. */
static void to_look(viewer *v)
{
    if (v->cam_mode == CAM_LOOK)
        return;
    const dirt_camera *c = dirt_session_camera(v->s);
    const dirt_frame *f = dirt_session_frame(v->s);
    float d = 0;
    for (int k = 0; k < 3; k++)
        d += (0.5f * (f->bounds_min[k] + f->bounds_max[k]) - c->eye[k]) * c->forward[k];
    vcam_from_camera(&v->look, c, d > 0 ? d : 0.5f * v->diag);
    v->cam_mode = CAM_LOOK;
}

static void reset_camera(viewer *v)
{
    v->cam_mode = v->o.camera >= 0 ? CAM_SCENE : v->o.camera == -2 ? CAM_AUTO : CAM_DEFAULT;
    v->cam_index = v->o.camera >= 0 ? v->o.camera : 0;
    if (v->o.look_set) {
        v->look = v->o.look;
        v->cam_mode = CAM_LOOK;
    }
    v->cam_dirty = true;
}

/* Makes the main (and comparison) sessions for the scene; false after
 * logging. */
static bool make_sessions(viewer *v)
{
    dirt_session_destroy(v->s);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->pre);
    v->s = v->cmp = v->pre = NULL;
    v->cmp_engine = -1;
    v->applied = wanted_opts(v, v->o.s.engine);
    v->s = dirt_session_create(v->gpu, v->scene, &v->applied);
    if (!v->s)
        return false;
    v->cam_dirty = v->time_dirty = true;
    v->aux_key = -1;
    v->generation++;
    return true;
}

static bool load_scene(viewer *v, const char *path)
{
    dirt_scene *sc = path ? dirt_scene_load(path, &v->o.load) : dirt_scene_create_default();
    if (!sc)
        return false;
    dirt_session_destroy(v->s);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->pre);
    v->s = v->cmp = v->pre = NULL;
    dirt_scene_destroy(v->scene);
    v->scene = sc;
    snprintf(v->scene_name, sizeof(v->scene_name), "%s", path ? path : "default scene");
    if (!make_sessions(v))
        return false;
    v->diag = scene_diagonal(dirt_session_frame(v->s));
    reset_camera(v);
    char title[4200];
    snprintf(title, sizeof(title), "dirt-view: %s", v->scene_name);
    dirt_gpu_window_set_title(v->gpu, title);
    return true;
}

/* Render size: the window's, or the fixed one (height from the camera's
 * aspect when only the width is fixed). */
static void render_size(viewer *v, int win_w, int win_h)
{
    if (v->o.s.width > 0) {
        v->rw = v->o.s.width;
        v->rh = v->o.s.height;
    } else {
        int sc = v->o.scale > 0 ? v->o.scale : 1;
        v->rw = win_w / sc >= 16 ? win_w / sc : 16;
        v->rh = win_h / sc >= 16 ? win_h / sc : 16;
    }
}

/* Remakes the environment map when its intensity or rotation changed (the
 * map bakes both in); the old one is kept until the sessions have the new
 * one (v->env_old, freed at the end of sync_sessions). False when the map
 * could not be remade (the old settings come back). */
static bool sync_env(viewer *v)
{
    if (!v->o.env_path ||
        (v->o.env_intensity == v->env_intensity && v->o.env_rotation == v->env_rotation))
        return true;
    char why[512];
    dirt_env_opts eo = {.intensity = v->o.env_intensity, .rotation = v->o.env_rotation,
                        .max_bytes = v->o.load.max_bytes};
    dirt_env *e = dirt_env_load(v->o.env_path, &eo, why, sizeof(why));
    if (!e) {
        set_status(v, "environment: %s", why);
        v->o.env_intensity = v->env_intensity;
        v->o.env_rotation = v->env_rotation;
        return false;
    }
    dirt_env_destroy(v->env_old);
    v->env_old = v->env;
    v->env = e;
    v->o.s.env = e;
    v->env_intensity = v->o.env_intensity;
    v->env_rotation = v->o.env_rotation;
    return true;
}

static bool sync_all(viewer *v);

/* Brings the sessions to the settings; restarts what changed. */
static bool sync_sessions(viewer *v)
{
    sync_env(v);
    bool ok = sync_all(v);
    /* The replaced map goes once no session holds it. */
    dirt_session *all[] = {v->s, v->cmp, v->pre};
    bool held = false;
    for (int i = 0; i < 3; i++)
        held |= all[i] && dirt_session_get_opts(all[i])->env == v->env_old;
    if (v->env_old && !held) {
        dirt_env_destroy(v->env_old);
        v->env_old = NULL;
    }
    return ok;
}

static bool sync_all(viewer *v)
{
    dirt_session_opts want = wanted_opts(v, v->o.s.engine);
    if (memcmp(&want, &v->applied, sizeof(want)) != 0) {
        bool restarted = false;
        if (!dirt_session_set_opts(v->s, &want, &restarted)) {
            set_status(v, "the session refused the settings (see the log); kept the old ones");
            int w = v->o.s.width, h = v->o.s.height;
            v->o.s = v->applied;
            v->o.s.width = w;
            v->o.s.height = h;
            return false;
        }
        v->applied = want;
        v->generation++;
    }
    if (v->time_dirty || v->o.time != v->applied_time || v->o.clip != v->applied_clip ||
        v->o.loop != v->applied_loop) {
        dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
        if (!dirt_session_set_time(v->s, v->o.time, &eval)) {
            set_status(v, "clip %d does not exist; back to clip %d", v->o.clip, v->applied_clip);
            v->o.clip = v->applied_clip;
            return false;
        }
        v->applied_time = v->o.time;
        v->applied_clip = v->o.clip;
        v->applied_loop = v->o.loop;
        v->time_dirty = false;
        v->cam_dirty = true; /* an animated scene camera follows the time */
        if (v->cmp)
            dirt_session_set_time(v->cmp, v->o.time, &eval);
        if (v->pre)
            dirt_session_set_time(v->pre, v->o.time, &eval);
        v->generation++;
    }
    if (v->cam_dirty) {
        if (!apply_camera(v, v->s)) {
            set_status(v, "no such camera; back to the default one");
            v->cam_mode = CAM_DEFAULT;
            apply_camera(v, v->s);
        }
        if (v->cmp)
            apply_camera(v, v->cmp);
        if (v->pre)
            apply_camera(v, v->pre);
        v->cam_dirty = false;
        v->generation++;
    }
    /* The comparison session: the same camera, time and settings. */
    int want_cmp = v->o.compare - 1;
    if (want_cmp != v->cmp_engine) {
        dirt_session_destroy(v->cmp);
        v->cmp = NULL;
        v->cmp_engine = -1;
        if (want_cmp >= 0) {
            dirt_session_opts co = wanted_opts(v, want_cmp);
            v->cmp = dirt_session_create(want_cmp == DIRT_ENGINE_EMBREE ? NULL : v->gpu,
                                         v->scene, &co);
            dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
            if (!v->cmp || !dirt_session_set_time(v->cmp, v->o.time, &eval) ||
                !apply_camera(v, v->cmp)) {
                dirt_session_destroy(v->cmp);
                v->cmp = NULL;
                v->o.compare = 0;
                set_status(v, "the comparison engine could not be made (see the log)");
                return false;
            }
            v->cmp_engine = want_cmp;
        }
        v->generation++;
    } else if (v->cmp) {
        dirt_session_opts co = wanted_opts(v, want_cmp);
        if (memcmp(&co, dirt_session_get_opts(v->cmp), sizeof(co)) != 0)
            dirt_session_set_opts(v->cmp, &co, NULL);
    }
    /* The raster preview, made the first time the camera moves. */
    if (v->moving && !v->o.no_preview && v->applied.engine != DIRT_ENGINE_RASTER) {
        dirt_session_opts po = wanted_opts(v, DIRT_ENGINE_RASTER);
        dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
        if (!v->pre) {
            v->pre = dirt_session_create(v->gpu, v->scene, &po);
            if (!v->pre || !dirt_session_set_time(v->pre, v->o.time, &eval) ||
                !apply_camera(v, v->pre)) {
                dirt_session_destroy(v->pre);
                v->pre = NULL;
                v->o.no_preview = true;
                set_status(v, "the raster preview could not be made (see the log); off");
            }
        } else if (memcmp(&po, dirt_session_get_opts(v->pre), sizeof(po)) != 0) {
            dirt_session_set_opts(v->pre, &po, NULL);
        }
    }
    return true;
}

/* ---- input ---- */

static bool key_held(const viewer *v, const dirt_window_input *in, enum dirt_key k)
{
    return in->key[k] || v->held[k] > 0;
}

static void cycle_camera(viewer *v)
{
    size_t n = dirt_scene_num_cameras(v->scene);
    if (!n) {
        set_status(v, "the scene has no cameras");
        return;
    }
    v->cam_index = v->cam_mode == CAM_SCENE ? (int)((v->cam_index + 1) % n) : 0;
    v->cam_mode = CAM_SCENE;
    v->cam_dirty = true;
    set_status(v, "scene camera %d", v->cam_index);
}

static bool save_render(viewer *v, const char *path);
static bool screenshot(viewer *v, const char *path);

static void handle_input(viewer *v, const dirt_window_input *in, double dt, bool ui_mouse,
                         bool ui_keys)
{
    if (!ui_mouse) {
        if (in->button[DIRT_MOUSE_LEFT] && !in->button_pressed[DIRT_MOUSE_LEFT] &&
            (in->mouse_dx != 0 || in->mouse_dy != 0)) {
            to_look(v);
            vcam_orbit(&v->look, (float)in->mouse_dx * 0.3f, (float)in->mouse_dy * 0.3f);
            v->cam_dirty = v->moving = true;
        }
        if ((in->button[DIRT_MOUSE_RIGHT] || in->button[DIRT_MOUSE_MIDDLE]) &&
            (in->mouse_dx != 0 || in->mouse_dy != 0) && in->height > 0) {
            to_look(v);
            vcam_pan(&v->look, (float)(in->mouse_dx / in->height),
                     (float)(-in->mouse_dy / in->height));
            v->cam_dirty = v->moving = true;
        }
        if (in->scroll != 0) {
            to_look(v);
            vcam_dolly(&v->look, powf(0.85f, (float)in->scroll));
            v->cam_dirty = v->moving = true;
        }
        if (in->double_clicks > 0) {
            v->click_pending = true;
            v->click_x = in->mouse_x;
            v->click_y = in->mouse_y;
        }
    }
    if (ui_keys)
        return;
    float speed = 0.25f * v->diag * (float)dt * (key_held(v, in, DIRT_KEY_SHIFT) ? 5.0f : 1.0f);
    float fw = 0, rt = 0, up = 0;
    fw += key_held(v, in, DIRT_KEY_W) ? speed : 0;
    fw -= key_held(v, in, DIRT_KEY_S) ? speed : 0;
    rt += key_held(v, in, DIRT_KEY_D) ? speed : 0;
    rt -= key_held(v, in, DIRT_KEY_A) ? speed : 0;
    up += key_held(v, in, DIRT_KEY_E) ? speed : 0;
    up -= key_held(v, in, DIRT_KEY_Q) ? speed : 0;
    if (fw != 0 || rt != 0 || up != 0) {
        to_look(v);
        vcam_fly(&v->look, fw, rt, up);
        v->cam_dirty = v->moving = true;
    }
    const bool *p = in->key_pressed;
    if (p[DIRT_KEY_ESCAPE])
        v->quit = true;
    if (p[DIRT_KEY_F1])
        v->show_help = !v->show_help;
    if (p[DIRT_KEY_H])
        v->o.no_ui = !v->o.no_ui;
    if (p[DIRT_KEY_R]) {
        reset_camera(v);
        set_status(v, "camera reset");
    }
    if (p[DIRT_KEY_C])
        cycle_camera(v);
    for (int k = 0; k < 9; k++)
        if (p[DIRT_KEY_1 + k])
            v->o.buffer = k;
    if (p[DIRT_KEY_TAB])
        v->o.s.engine = (enum dirt_engine)((v->o.s.engine + 1) % DIRT_NUM_ENGINES);
    if (p[DIRT_KEY_V])
        v->o.compare = v->o.compare ? 0 : (v->o.s.engine == DIRT_ENGINE_MMRT ? 1 : 2);
    if (p[DIRT_KEY_X])
        v->o.diff = !v->o.diff;
    if (p[DIRT_KEY_SPACE])
        v->o.play = !v->o.play;
    if (p[DIRT_KEY_RIGHT] || p[DIRT_KEY_LEFT]) {
        v->o.play = false;
        v->o.time += p[DIRT_KEY_RIGHT] ? 1.0 / 24 : -1.0 / 24;
    }
    if (p[DIRT_KEY_MINUS])
        v->o.exposure -= 1;
    if (p[DIRT_KEY_EQUAL])
        v->o.exposure += 1;
    if (p[DIRT_KEY_P] || p[DIRT_KEY_O]) {
        char path[64];
        snprintf(path, sizeof(path), "dirt-view-%d.%s", ++v->shots, p[DIRT_KEY_P] ? "png" : "exr");
        if (p[DIRT_KEY_O])
            save_render(v, path);
        else
            screenshot(v, path); /* taken after the frame is drawn: see the loop */
    }
}

/* Focus on the surface under the cursor: the Z AOV at that pixel. */
static void fit(const viewer *v, int w, int h, int r[4]);

static void focus_at(viewer *v)
{
    v->click_pending = false;
    if (dirt_session_samples(v->s) == 0 || v->win_w <= 0)
        return;
    int r[4];
    fit(v, v->rw, v->rh, r);
    int x = (int)floor((v->click_x - r[0]) * v->rw / r[2]);
    int y = (int)floor((v->click_y - r[1]) * v->rh / r[3]);
    const dirt_image *img = dirt_session_image(v->s);
    const float *z = img ? dirt_image_find_channel(img, "Z") : NULL;
    if (!z || x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    float d = z[(size_t)y * img->width + x];
    if (!isfinite(d) || !(d > 0)) {
        set_status(v, "nothing under the cursor to focus on");
        return;
    }
    v->o.s.focus = d;
    if (!(v->o.s.aperture > 0))
        v->o.s.aperture = 0.01f * v->diag;
    set_status(v, "focus %.4g (aperture %.4g)", d, v->o.s.aperture);
}

/* ---- outputs ---- */

static bool save_render(viewer *v, const char *path)
{
    if (dirt_session_samples(v->s) == 0 && !dirt_session_add_samples(v->s, 1, NULL, NULL))
        return false;
    const dirt_image *img = dirt_session_image(v->s);
    dirt_image_write_options wo = {.png = {.exposure = v->o.exposure,
                                           .tonemap = (enum dirt_tonemap)v->o.tonemap}};
    bool ok = img && cli_write_image(PROG, img, path, &wo, cli_has_ext(path, ".exr"), v->o.quiet);
    if (ok)
        set_status(v, "saved %s (%d samples)", path, dirt_session_samples(v->s));
    return ok;
}

/* Requested window screenshots are taken at the end of the frame, after
 * the panels are drawn (take_screenshots). */
static bool screenshot(viewer *v, const char *path)
{
    if (v->num_shots >= 4)
        return false;
    snprintf(v->shot_path[v->num_shots++], sizeof(v->shot_path[0]), "%s", path);
    return true;
}

static bool take_screenshots(viewer *v)
{
    bool ok = true;
    uint8_t *px = NULL;
    if (v->num_shots) {
        px = malloc((size_t)v->win_w * v->win_h * 4);
        ok = px && dirt_gpu_window_read(v->gpu, px, v->win_w, v->win_h);
    }
    for (int i = 0; ok && i < v->num_shots; i++) {
        ok = dirt_write_png_rgba8(v->shot_path[i], v->win_w, v->win_h, px);
        if (ok)
            set_status(v, "screenshot %s (%dx%d)", v->shot_path[i], v->win_w, v->win_h);
    }
    v->num_shots = 0;
    free(px);
    return ok;
}

static void camera_args(const viewer *v, char *buf, size_t size)
{
    switch (v->cam_mode) {
    case CAM_LOOK:
        vcam_format(&v->look, buf, size);
        break;
    case CAM_SCENE:
        snprintf(buf, size, "--camera %d", v->cam_index);
        break;
    case CAM_AUTO:
        snprintf(buf, size, "--auto-camera");
        break;
    default:
        buf[0] = '\0';
    }
}

/* The dirt-render options that render what the main session shows now
 * (size, engine, every technique setting that differs from dirt-render's
 * default, time, camera, lens), samples excepted. */
static void render_args(const viewer *v, char *buf, size_t size)
{
    const dirt_session_opts *o = &v->applied;
    size_t n = 0;
#define ADD(...) (n < size ? (void)(n += (size_t)snprintf(buf + n, size - n, __VA_ARGS__)) : (void)0)
    ADD("-W %d -H %d --engine %s --seed %u", o->width, o->height, dirt_engine_names[o->engine],
        o->seed);
    if (o->bounces)
        ADD(" --bounces %d", o->bounces);
    if (o->mode)
        ADD(" --mode %s", modes[o->mode]);
    if (o->ao_distance > 0)
        ADD(" --ao-distance %.9g", o->ao_distance);
    if (v->o.env_path) {
        /* Quoted for a shell only when it needs it. */
        bool plain = true;
        for (const char *c = v->o.env_path; *c; c++)
            plain &= (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                     (*c >= '0' && *c <= '9') || strchr("_./+-", *c) != NULL;
        ADD(plain ? " --env %s" : " --env '%s'", v->o.env_path);
        if (v->env_intensity != 0 && v->env_intensity != 1)
            ADD(" --env-intensity %.9g", v->env_intensity);
        if (v->env_rotation != 0)
            ADD(" --env-rotation %.9g", v->env_rotation);
    } else if (o->background[0] || o->background[1] || o->background[2]) {
        ADD(" --background %.9g,%.9g,%.9g", o->background[0], o->background[1], o->background[2]);
    }
    if (o->views)
        ADD(" --views %s", views[o->views]);
    if (o->tile_size)
        ADD(" --tile %d", o->tile_size);
    if (o->buckets)
        ADD(" --buckets %d", o->buckets);
    if (o->face_size)
        ADD(" --face-size %d", o->face_size);
    if (o->engine == DIRT_ENGINE_DIRT && o->large)
        ADD(" --large %d", o->large < 0 ? 0 : o->large);
    if (o->hiz_levels)
        ADD(" --hiz-top %d", o->hiz_levels - 1);
    if (o->fetch)
        ADD(" --fetch %s", fetches[o->fetch]);
    if (o->direct_visibility)
        ADD(" --direct-visibility");
    if (o->force_emulation)
        ADD(" --no-conservative-raster");
    if (o->engine == DIRT_ENGINE_MMRT && o->march)
        ADD(" --march %s", marches[o->march]);
    if (o->engine == DIRT_ENGINE_MMRT && o->march_samples)
        ADD(" --samples %d", o->march_samples);
    if (o->engine == DIRT_ENGINE_MMRT && o->thickness > 0)
        ADD(" --thickness %.9g", o->thickness);
    if (o->aperture > 0)
        ADD(" --aperture %.9g", o->aperture);
    if (o->aperture > 0 && o->focus > 0)
        ADD(" --focus %.9g", o->focus);
    if (v->applied_time != 0)
        ADD(" -t %.17g", v->applied_time);
    if (v->applied_clip)
        ADD(" --clip %d", v->applied_clip);
    if (v->applied_loop)
        ADD(" --loop");
    char cam[1024];
    camera_args(v, cam, sizeof(cam));
    if (cam[0])
        ADD(" %s", cam);
#undef ADD
}

static bool write_report(viewer *v, const char *path)
{
    cJSON *r = cJSON_CreateObject();
    char cam[1024];
    camera_args(v, cam, sizeof(cam));
    const char *modes_[] = {"default", "auto", "scene", "look"};
    cJSON_AddStringToObject(r, "scene", v->scene_name);
    cJSON_AddStringToObject(r, "engine", dirt_engine_names[v->applied.engine]);
    int win[2] = {v->win_w, v->win_h}, ren[2] = {v->rw, v->rh};
    cJSON_AddItemToObject(r, "window", cJSON_CreateIntArray(win, 2));
    cJSON_AddItemToObject(r, "render", cJSON_CreateIntArray(ren, 2));
    cJSON_AddNumberToObject(r, "samples", dirt_session_samples(v->s));
    cJSON_AddNumberToObject(r, "frames", (double)v->frame);
    cJSON_AddNumberToObject(r, "time", v->applied_time);
    cJSON_AddStringToObject(r, "camera_mode", modes_[v->cam_mode]);
    cJSON_AddStringToObject(r, "camera_args", cam);
    char args[4096];
    render_args(v, args, sizeof(args));
    cJSON_AddStringToObject(r, "render_args", args);
    cJSON_AddNumberToObject(r, "aperture", v->applied.aperture);
    cJSON_AddNumberToObject(r, "focus", v->applied.focus);
    const dirt_camera *c = dirt_session_camera(v->s);
    cJSON *cj = cJSON_AddObjectToObject(r, "camera");
    cJSON_AddItemToObject(cj, "eye", cJSON_CreateFloatArray(c->eye, 3));
    cJSON_AddItemToObject(cj, "forward", cJSON_CreateFloatArray(c->forward, 3));
    cJSON_AddNumberToObject(cj, "yfov", c->yfov);
    /* Displayed frames' times (the last RING frames, skipping the first
     * one: it builds the GPU programs), ms. */
    const float *rings[2] = {v->frame_ms, v->sample_ms};
    const char *ring_names[2] = {"frame_ms", "samples_ms"};
    for (int k = 0; k < 2; k++) {
        float sorted[RING];
        int n = 0;
        for (int i = 0; i < v->ring_count; i++) {
            int idx = (v->ring_count < RING ? i : (v->ring_pos + i) % RING);
            if (v->ring_count < RING && v->frame > 1 && i == 0)
                continue;
            sorted[n++] = rings[k][idx];
        }
        for (int i = 1; i < n; i++)
            for (int j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
                float t = sorted[j];
                sorted[j] = sorted[j - 1];
                sorted[j - 1] = t;
            }
        cJSON *t = cJSON_AddObjectToObject(r, ring_names[k]);
        cJSON_AddNumberToObject(t, "count", n);
        cJSON_AddNumberToObject(t, "min", n ? sorted[0] : 0);
        cJSON_AddNumberToObject(t, "median", n ? sorted[n / 2] : 0);
        cJSON_AddNumberToObject(t, "max", n ? sorted[n - 1] : 0);
    }
    cJSON_AddStringToObject(r, "clock", dirt_clock_names[dirt_gpu_clock(v->gpu)]);
    char desc[256];
    dirt_gpu_describe(v->gpu, desc, sizeof(desc));
    cJSON_AddStringToObject(r, "device", desc);
    cJSON *panels = cJSON_AddArrayToObject(r, "panels");
    for (int i = 0; !v->o.no_ui && i < v->num_panels; i++)
        cJSON_AddItemToArray(panels, cJSON_CreateFloatArray(v->panels[i], 4));
    char *text = cJSON_Print(r);
    cJSON_Delete(r);
    bool ok = text && dirt_write_file_atomic(path, text, strlen(text));
    free(text);
    if (!ok)
        cli_error(PROG, "could not write the report '%s'", path);
    return ok;
}

/* ---- script ---- */

/* Runs script actions until one waits; false on a failed action (the
 * viewer then quits with exit status 1). */
static bool run_script(viewer *v)
{
    if (v->wait_frames > 0) {
        v->wait_frames--;
        return true;
    }
    if (v->wait_file[0]) {
        if (access(v->wait_file, F_OK) != 0)
            return true;
        v->wait_file[0] = '\0';
    }
    if (v->wait_samples > 0) {
        int target = v->wait_samples;
        if (dirt_session_samples(v->s) < target &&
            (v->o.spp == 0 || dirt_session_samples(v->s) < v->o.spp))
            return true;
        v->wait_samples = 0;
    }
    while (v->next_action < v->script.count) {
        const vs_action *a = &v->script.actions[v->next_action++];
        switch (a->kind) {
        case VS_WAIT_FRAMES:
            v->wait_frames = (long)a->num[0];
            if (v->wait_frames > 0) {
                v->wait_frames--;
                return true;
            }
            break;
        case VS_WAIT_SAMPLES:
            v->wait_samples = (int)a->num[0];
            return true;
        case VS_WAIT_FILE:
            snprintf(v->wait_file, sizeof(v->wait_file), "%s", a->text);
            return true;
        case VS_ORBIT:
            to_look(v);
            vcam_orbit(&v->look, (float)a->num[0], (float)a->num[1]);
            v->cam_dirty = true;
            break;
        case VS_PAN:
            to_look(v);
            vcam_pan(&v->look, (float)a->num[0], (float)a->num[1]);
            v->cam_dirty = true;
            break;
        case VS_DOLLY:
            to_look(v);
            vcam_dolly(&v->look, (float)a->num[0]);
            v->cam_dirty = true;
            break;
        case VS_FLY:
            to_look(v);
            vcam_fly(&v->look, (float)a->num[0], (float)a->num[1], (float)a->num[2]);
            v->cam_dirty = true;
            break;
        case VS_CAMERA:
            v->cam_mode = !strcmp(a->name, "auto")      ? CAM_AUTO
                          : !strcmp(a->name, "default") ? CAM_DEFAULT
                                                        : CAM_SCENE;
            v->cam_index = (int)a->num[0];
            if (v->cam_mode == CAM_SCENE &&
                (size_t)v->cam_index >= dirt_scene_num_cameras(v->scene)) {
                cli_error(PROG, "script line %d: the scene has %zu camera(s)", a->line,
                          dirt_scene_num_cameras(v->scene));
                return false;
            }
            v->cam_dirty = true;
            break;
        case VS_KEY:
            v->held[dirt_key_from_name(a->name)] = (int)a->num[0];
            break;
        case VS_CLICK:
            v->click_pending = true;
            v->click_x = a->num[0];
            v->click_y = a->num[1];
            break;
        case VS_SET: {
            const vopt_spec *sp = find_spec(a->name, true);
            char opt[80];
            snprintf(opt, sizeof(opt), "--%s", a->name);
            if (sp && !strcmp(a->name, "camera"))
                v->cam_dirty = true;
            if (!sp || !apply_spec(sp, opt, a->text, &v->o))
                return false;
            if (!strcmp(a->name, "camera")) {
                v->cam_mode = CAM_SCENE;
                v->cam_index = v->o.camera;
            }
            if (sp->kind == 'v' || sp->off == offsetof(vopts, look.fov_deg) ||
                sp->off == offsetof(vopts, look.znear) || sp->off == offsetof(vopts, look.zfar)) {
                to_look(v);
                v->look.fov_deg = v->o.look.fov_deg > 0 ? v->o.look.fov_deg : v->look.fov_deg;
                if (v->o.eye_set)
                    memcpy(v->look.eye, v->o.look.eye, sizeof(v->look.eye));
                if (v->o.target_set)
                    memcpy(v->look.target, v->o.look.target, sizeof(v->look.target));
                memcpy(v->look.up, v->o.look.up, sizeof(v->look.up));
                if (v->o.look.znear > 0)
                    v->look.znear = v->o.look.znear;
                if (v->o.look.zfar > 0)
                    v->look.zfar = v->o.look.zfar;
                v->cam_dirty = true;
            }
            break;
        }
        case VS_RESIZE:
            dirt_gpu_window_set_size(v->gpu, (int)a->num[0], (int)a->num[1]);
            break;
        case VS_SCREENSHOT:
            v->hold = true;
            if (!cli_creatable(PROG, a->text))
                return false;
            screenshot(v, a->text);
            return true; /* taken at the end of this frame: the next actions wait */
        case VS_SAVE_IMAGE:
            v->hold = true;
            if (!save_render(v, a->text))
                return false;
            break;
        case VS_REPORT:
            v->hold = true;
            if (!write_report(v, a->text))
                return false;
            break;
        case VS_PRINT_CAMERA: {
            char cam[1024];
            camera_args(v, cam, sizeof(cam));
            printf("camera: %s\n", cam);
            break;
        }
        case VS_QUIT:
            v->quit = v->hold = true; /* --save-image at exit gets this image */
            return true;
        }
    }
    return true;
}

/* The script's `set` and `key` actions, tried on a copy of the options and
 * names before the window opens. */
static bool check_script(const view_script *sc, const vopts *o)
{
    vopts scratch = *o;
    for (size_t i = 0; i < sc->count; i++) {
        const vs_action *a = &sc->actions[i];
        if (a->kind == VS_KEY && dirt_key_from_name(a->name) == DIRT_KEY_NONE) {
            cli_error(PROG, "script line %d: unknown key '%s'", a->line, a->name);
            return false;
        }
        if (a->kind != VS_SET)
            continue;
        const vopt_spec *sp = find_spec(a->name, true);
        char opt[80];
        snprintf(opt, sizeof(opt), "--%s", a->name);
        if (!sp || !sp->runtime) {
            cli_error(PROG, "script line %d: '%s' is not an option `set` can change", a->line,
                      a->name);
            return false;
        }
        if (!apply_spec(sp, opt, a->text, &scratch)) {
            cli_error(PROG, "script line %d: bad value", a->line);
            return false;
        }
    }
    return true;
}

/* ---- panels ---- */

static void note_panel(viewer *v)
{
    if (v->num_panels < 4)
        dirt_ui_panel_rect(v->panels[v->num_panels++]);
}

static void panel_settings(viewer *v)
{
    vopts *o = &v->o;
    const char *engines[DIRT_NUM_ENGINES];
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        engines[e] = dirt_engine_names[e];
    if (dirt_ui_begin("Settings", NULL, 8, 8, 330, (float)(v->win_h - 16 > 200 ? v->win_h - 16 : 200))) {
        int samples = dirt_session_samples(v->s);
        dirt_ui_text("%s", v->scene_name);
        dirt_ui_text("%zu triangles, %d x %d", dirt_scene_num_triangles(v->scene), v->rw, v->rh);
        dirt_ui_text("%d / %d samples in %.1f s%s", samples, o->spp,
                     dirt_session_get_stats(v->s)->total_ms / 1000.0,
                     o->spp && samples >= o->spp ? " (done)" : "");
        if (v->status[0])
            dirt_ui_text_disabled("%s", v->status);
        if (dirt_ui_header("Render", true)) {
            int eng = (int)o->s.engine;
            if (dirt_ui_combo("engine", &eng, engines, DIRT_NUM_ENGINES))
                o->s.engine = (enum dirt_engine)eng;
            dirt_ui_combo("compare with", &o->compare, compares, 5);
            if (o->compare) {
                dirt_ui_slider_float("split", &o->split, 0.0f, 1.0f, "%.2f", false);
                dirt_ui_checkbox("difference heat map", &o->diff);
                if (o->diff)
                    dirt_ui_slider_float("difference range", &o->diff_range, 1e-4f, 10.0f, "%.4f",
                                         true);
            }
            dirt_ui_slider_int("target spp (0 = no limit)", &o->spp, 0, 4096);
            dirt_ui_slider_int("samples per frame", &o->samples_per_frame, 1, 64);
            int mode = (int)o->s.mode;
            if (dirt_ui_combo("mode", &mode, modes, 2))
                o->s.mode = (enum dirt_pt_mode)mode;
            int bounces = o->s.bounces ? o->s.bounces : 4;
            if (dirt_ui_slider_int("bounces", &bounces, 1, 16))
                o->s.bounces = bounces;
            if (o->s.mode == DIRT_PT_AO)
                dirt_ui_slider_float("AO distance (0 = inf)", &o->s.ao_distance, 0.0f, v->diag,
                                     "%.3f", false);
            if (o->env_path) {
                dirt_ui_text("environment: %s", o->env_path);
                float intensity = o->env_intensity > 0 ? o->env_intensity : 1.0f;
                if (dirt_ui_slider_float("env intensity", &intensity, 0.01f, 100.0f, "%.3f", true))
                    o->env_intensity = intensity;
                dirt_ui_slider_float("env rotation", &o->env_rotation, -180.0f, 180.0f,
                                     "%.1f deg", false);
            } else {
                dirt_ui_color3("background", o->s.background);
            }
            int seed = (int)o->s.seed;
            if (dirt_ui_input_int("seed", &seed, 1) && seed >= 0)
                o->s.seed = (uint32_t)seed;
            bool follow = o->s.width == 0;
            if (dirt_ui_checkbox("resolution follows the window", &follow)) {
                o->s.width = follow ? 0 : v->rw;
                o->s.height = follow ? 0 : v->rh;
            }
            if (!follow) {
                int w = o->s.width, h = o->s.height;
                if (dirt_ui_input_int("width", &w, 16) && w >= 16 && w <= 16384)
                    o->s.width = w;
                if (dirt_ui_input_int("height (0 = aspect)", &h, 16) && h >= 0 && h <= 16384)
                    o->s.height = h;
            }
        }
        if (dirt_ui_header("Structure", false)) {
            int vm = (int)o->s.views;
            const char *vnames[] = {"cube+camera (default)", "single", "cube", "cube+camera"};
            if (dirt_ui_combo("views", &vm, vnames, 4))
                o->s.views = (enum dirt_session_views)vm;
            const char *tiles[] = {"1", "2", "4", "8"};
            int ti = o->s.tile_size == 1 ? 0 : o->s.tile_size == 4 ? 2 : o->s.tile_size == 8 ? 3 : 1;
            if (dirt_ui_combo("tile size S", &ti, tiles, 4))
                o->s.tile_size = 1 << ti;
            int b = o->s.buckets ? o->s.buckets
                    : o->s.engine == DIRT_ENGINE_MMRT ? 4 : dirt_session_auto_buckets(v->gpu);
            if (dirt_ui_slider_int("buckets", &b, 1, 64))
                o->s.buckets = b;
            int lg = o->large < 0 ? DIRT_ADS_MAX_LARGE : (int)o->large;
            if (dirt_ui_slider_int("large primitives", &lg, 0, DIRT_ADS_MAX_LARGE))
                o->large = lg;
            int top = (int)o->hiz_top;
            if (dirt_ui_slider_int("Hi-Z top (-1 = all)", &top, -1, 15))
                o->hiz_top = top;
            int fetch = (int)o->s.fetch;
            if (dirt_ui_combo("Fetch", &fetch, fetches, 2))
                o->s.fetch = (enum dirt_fetch_mode)fetch;
            dirt_ui_checkbox("direct visibility", &o->direct_visibility);
            dirt_ui_checkbox("emulate conservative raster", &o->conservative_off);
            int march = (int)o->s.march;
            if (dirt_ui_combo("MMRT march", &march, marches, 2))
                o->s.march = (enum dirt_mmrt_march)march;
            int ms = o->s.march_samples ? o->s.march_samples : 30;
            if (dirt_ui_slider_int("MMRT samples", &ms, 1, 256))
                o->s.march_samples = ms;
            dirt_ui_slider_float("MMRT thickness (0 = auto)", &o->s.thickness, 0.0f,
                                 0.05f * v->diag, "%.4f", false);
        }
        if (dirt_ui_header("Camera", false)) {
            char cam[1024];
            camera_args(v, cam, sizeof(cam));
            dirt_ui_text("%s", cam[0] ? cam : "(the scene's default camera)");
            if (dirt_ui_button("reset"))
                reset_camera(v);
            dirt_ui_same_line();
            if (dirt_ui_button("next scene camera"))
                cycle_camera(v);
            dirt_ui_same_line();
            if (dirt_ui_button("print")) {
                char args[4096];
                render_args(v, args, sizeof(args));
                printf("camera: %s\ndirt-render %s --spp %d\n", cam, args,
                       dirt_session_samples(v->s));
            }
            if (v->cam_mode == CAM_LOOK) {
                if (dirt_ui_slider_float("field of view", &v->look.fov_deg, 5.0f, 120.0f, "%.1f",
                                         false))
                    v->cam_dirty = true;
            }
            dirt_ui_slider_float("aperture", &o->s.aperture, 0.0f, 0.05f * v->diag, "%.4f", false);
            dirt_ui_slider_float("focus distance", &o->s.focus, 0.0f, 2.0f * v->diag, "%.3f",
                                 false);
        }
        if (dirt_ui_header("Display", true)) {
            dirt_ui_combo("buffer", &o->buffer, buffer_labels, NUM_BUFFERS);
            dirt_ui_slider_float("exposure", &o->exposure, -10.0f, 10.0f, "%.1f", false);
            dirt_ui_combo("tone map", &o->tonemap, tonemaps, 3);
        }
        size_t clips = dirt_scene_num_clips(v->scene);
        if (dirt_ui_header("Animation", clips > 0)) {
            if (!clips) {
                dirt_ui_text_disabled("the scene has no animation");
            } else {
                int clip = o->clip < 0 ? 0 : o->clip;
                float dur = dirt_scene_clip_duration(v->scene, (size_t)clip);
                float t = (float)o->time;
                if (dirt_ui_button(o->play ? "pause" : "play"))
                    o->play = !o->play;
                dirt_ui_same_line();
                if (dirt_ui_button("step")) {
                    o->play = false;
                    o->time += 1.0 / 24;
                }
                if (dirt_ui_slider_float("time", &t, 0.0f, dur > 0 ? dur : 1.0f, "%.3f s", false))
                    o->time = t;
                const char *names[64];
                int n = clips < 64 ? (int)clips : 64;
                for (int i = 0; i < n; i++)
                    names[i] = dirt_scene_clip_name(v->scene, (size_t)i);
                dirt_ui_combo("clip", &o->clip, names, n);
                dirt_ui_checkbox("loop", &o->loop);
                float sp = (float)o->speed;
                if (dirt_ui_slider_float("speed", &sp, -4.0f, 4.0f, "%.2f x", false))
                    o->speed = sp;
            }
        }
        if (dirt_ui_header("Files", false)) {
            if (dirt_ui_button("screenshot (P)")) {
                char path[64];
                snprintf(path, sizeof(path), "dirt-view-%d.png", ++v->shots);
                screenshot(v, path);
            }
            dirt_ui_same_line();
            if (dirt_ui_button("save render (O)")) {
                char path[64];
                snprintf(path, sizeof(path), "dirt-view-%d.exr", ++v->shots);
                save_render(v, path);
            }
            dirt_ui_text_disabled("drop a .gltf / .glb on the window to open it");
        }
    }
    note_panel(v);
    dirt_ui_end();
}

static void panel_numbers(viewer *v)
{
    float w = 360, x = (float)v->win_w - w - 8;
    if (x < 346)
        x = 346;
    if (dirt_ui_begin("Numbers", NULL, x, 8, w, 420)) {
        const dirt_session_stats *st = &v->last;
        float fmax = 1;
        for (int i = 0; i < v->ring_count; i++)
            fmax = fmaxf(fmax, v->frame_ms[i]);
        char cap[96];
        float last = v->ring_count ? v->frame_ms[(v->ring_pos + RING - 1) % RING] : 0;
        snprintf(cap, sizeof(cap), "frame %.1f ms", last);
        if (v->ring_count > 0)
            dirt_ui_plot_lines("##frame", v->frame_ms, v->ring_count, v->ring_count < RING ? 0 : v->ring_pos,
                           cap, 0, fmax, 50);
        float smax = 1;
        for (int i = 0; i < v->ring_count; i++)
            smax = fmaxf(smax, v->sample_ms[i]);
        float lasts = v->ring_count ? v->sample_ms[(v->ring_pos + RING - 1) % RING] : 0;
        snprintf(cap, sizeof(cap), "samples of the frame %.1f ms", lasts);
        if (v->ring_count > 0)
            dirt_ui_plot_lines("##samples", v->sample_ms, v->ring_count,
                           v->ring_count < RING ? 0 : v->ring_pos, cap, 0, smax, 50);
        dirt_ui_text("%s", st->device);
        dirt_ui_text("%.2f Mrays/s, %llu rays, %llu aborted", st->mrays_per_s,
                     (unsigned long long)st->rays, (unsigned long long)st->aborted);
        static const char *const ph[] = {"pass (last frame)", "ms", "clock"};
        if (dirt_ui_table_begin("passes", 3, ph)) {
            for (int i = 0; i < v->num_frame_passes; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", v->frame_passes[i].name);
                dirt_ui_table_cell("%.3f", v->frame_passes[i].ms);
                dirt_ui_table_cell("%s", dirt_clock_names[v->frame_passes[i].clock]);
            }
            dirt_ui_table_end();
        }
        static const char *const bh[] = {"buffer", "used MB", "allocated MB"};
        if (dirt_ui_table_begin("buffers", 3, bh)) {
            for (int i = 0; i < st->num_buffers; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", st->buffers[i].name);
                dirt_ui_table_cell("%.3f", st->buffers[i].used / 1048576.0);
                dirt_ui_table_cell("%.3f", st->buffers[i].allocated / 1048576.0);
            }
            dirt_ui_table_row();
            dirt_ui_table_cell("total");
            dirt_ui_table_cell("%.3f", st->bytes_total_used / 1048576.0);
            dirt_ui_table_cell("%.3f", st->bytes_total_allocated / 1048576.0);
            dirt_ui_table_end();
        }
    }
    note_panel(v);
    dirt_ui_end();
}

static void panel_help(viewer *v)
{
    bool open = true;
    if (dirt_ui_begin("Key bindings (F1)", &open, (float)v->win_w / 2 - 220, 60, 440, 480)) {
        static const char *const hh[] = {"input", "does"};
        if (dirt_ui_table_begin("bindings", 2, hh)) {
            for (size_t i = 0; i < NUM_BINDINGS; i++) {
                dirt_ui_table_row();
                dirt_ui_table_cell("%s", bindings[i][0]);
                dirt_ui_table_cell("%s", bindings[i][1]);
            }
            dirt_ui_table_end();
        }
    }
    note_panel(v);
    dirt_ui_end();
    if (!open)
        v->show_help = false;
}

/* ---- display ---- */

/* A colour per primitive id (a hash), black for misses. */
static void id_colour(float id, float rgb[3])
{
    if (!(id >= 0)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    uint32_t h = (uint32_t)id * 2654435761u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    for (int k = 0; k < 3; k++)
        rgb[k] = 0.15f + 0.85f * (float)((h >> (8 * k)) & 255) / 255.0f;
}

/* Makes the texture of a non-beauty buffer (AOVs: from the image; the
 * structure's pictures: from the last build). False when there is none. */
static bool aux_texture(viewer *v)
{
    long key = v->generation * NUM_BUFFERS + v->o.buffer;
    if (key == v->aux_key)
        return v->aux_tex != 0;
    v->aux_key = key;
    dirt_image *pic = NULL;
    const dirt_image *img = NULL;
    float top = 1;
    int b = v->o.buffer;
    if (b >= BUF_LISTS) {
        pic = dirt_session_picture(v->s, (enum dirt_session_picture)(b - BUF_LISTS), &top);
        img = pic;
    } else {
        img = dirt_session_samples(v->s) > 0 ? dirt_session_image(v->s) : NULL;
    }
    if (!img)
        return false;
    size_t n = (size_t)img->width * img->height;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) {
        dirt_image_destroy(pic);
        return false;
    }
    const char *names[3] = {NULL, NULL, NULL};
    if (b == BUF_ALBEDO)
        names[0] = "albedo.R", names[1] = "albedo.G", names[2] = "albedo.B";
    else if (b == BUF_NORMAL)
        names[0] = "N.X", names[1] = "N.Y", names[2] = "N.Z";
    else if (b == BUF_DEPTH)
        names[0] = "Z";
    else if (b == BUF_ID)
        names[0] = "ID";
    const float *ch[3] = {0};
    for (int k = 0; k < 3; k++)
        ch[k] = names[k] ? dirt_image_find_channel(img, names[k]) : NULL;
    bool ok = b >= BUF_LISTS || ch[0];
    v->aux_lo = 0;
    v->aux_hi = top;
    if (b == BUF_DEPTH && ok) {
        float lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            if (isfinite(ch[0][i])) {
                lo = fminf(lo, ch[0][i]);
                hi = fmaxf(hi, ch[0][i]);
            }
        }
        v->aux_lo = isfinite(lo) ? lo : 0;
        v->aux_hi = hi > lo ? hi : v->aux_lo + 1;
    }
    for (size_t i = 0; ok && i < n; i++) {
        float *px = rgba + 4 * i;
        if (b >= BUF_LISTS) {
            memcpy(px, img->rgba + 4 * i, 4 * sizeof(float));
            if (!isfinite(px[0]))
                px[0] = -1; /* empty: below the ramp (black) */
        } else if (b == BUF_ID) {
            id_colour(ch[0][i], px);
            px[3] = 1;
        } else {
            for (int k = 0; k < 3; k++)
                px[k] = ch[k] ? ch[k][i] : (b == BUF_DEPTH && !isfinite(ch[0][i]) ? -1 : 0);
            if (b == BUF_DEPTH)
                px[0] = isfinite(ch[0][i]) ? ch[0][i] : v->aux_lo - 1;
            px[3] = 1;
        }
    }
    if (ok) {
        v->aux_tex = dirt_gpu_texture_upload(v->gpu, v->aux_tex, img->width, img->height, rgba);
        v->aux_w = img->width;
        v->aux_h = img->height;
    }
    free(rgba);
    dirt_image_destroy(pic);
    return ok && v->aux_tex;
}

/* The rectangle an image of w x h takes in the window: 1:1 at the top
 * left when it follows the window, else fitted and centred. */
static void fit(const viewer *v, int w, int h, int r[4])
{
    if (w == v->win_w && h == v->win_h) {
        r[0] = r[1] = 0, r[2] = w, r[3] = h;
        return;
    }
    double s = fmin((double)v->win_w / w, (double)v->win_h / h);
    r[2] = (int)(w * s);
    r[3] = (int)(h * s);
    if (r[2] < 1)
        r[2] = 1;
    if (r[3] < 1)
        r[3] = 1;
    r[0] = (v->win_w - r[2]) / 2;
    r[1] = (v->win_h - r[3]) / 2;
}

static void draw(viewer *v, bool preview)
{
    static const float grey[3] = {0.08f, 0.08f, 0.09f};
    dirt_gpu_window_clear(v->gpu, grey);
    bool have_pre = v->pre && dirt_session_samples(v->pre) > 0;
    if (v->o.buffer == BUF_BEAUTY && have_pre &&
        (preview || dirt_session_samples(v->s) == 0)) {
        int r[4];
        fit(v, v->rw, v->rh, r);
        dirt_present_opts p = {.texture = dirt_session_display_texture(v->pre), .x = r[0],
                               .y = r[1], .w = r[2], .h = r[3], .exposure = v->o.exposure,
                               .tonemap = (enum dirt_tonemap)v->o.tonemap};
        if (p.texture)
            dirt_gpu_present(v->gpu, &p);
        return;
    }
    if (dirt_session_samples(v->s) == 0)
        return;
    int r[4];
    dirt_present_opts p = {.exposure = v->o.exposure, .tonemap = v->o.tonemap};
    if (v->o.buffer == BUF_BEAUTY) {
        p.texture = dirt_session_display_texture(v->s);
        fit(v, v->rw, v->rh, r);
        if (v->cmp && dirt_session_samples(v->cmp) > 0) {
            p.texture_b = dirt_session_display_texture(v->cmp);
            if (v->o.diff) {
                p.mode = DIRT_PRESENT_DIFF;
                p.lo = 0;
                p.hi = v->o.diff_range;
            } else {
                p.split = v->o.split > 0 && v->o.split < 1 ? v->o.split : 0.5f;
                p.split_line = true;
            }
        }
    } else {
        if (!aux_texture(v))
            return;
        p.texture = v->aux_tex;
        fit(v, v->aux_w, v->aux_h, r);
        if (v->o.buffer == BUF_NORMAL) {
            p.mode = DIRT_PRESENT_SIGNED;
        } else if (v->o.buffer == BUF_DEPTH || v->o.buffer >= BUF_LISTS) {
            p.mode = DIRT_PRESENT_HEAT;
            p.lo = v->aux_lo;
            p.hi = v->aux_hi > v->aux_lo ? v->aux_hi : v->aux_lo + 1;
        } else {
            p.exposure = 0;
            p.tonemap = 0;
        }
    }
    p.x = r[0], p.y = r[1], p.w = r[2], p.h = r[3];
    if (p.texture)
        dirt_gpu_present(v->gpu, &p);
}

/* ---- the frame ---- */

static void record_passes(viewer *v, const dirt_session_stats *before, bool restarted)
{
    const dirt_session_stats *st = dirt_session_get_stats(v->s);
    v->num_frame_passes = st->num_passes < 32 ? st->num_passes : 32;
    for (int i = 0; i < v->num_frame_passes; i++) {
        v->frame_passes[i] = st->passes[i];
        if (!restarted && i < before->num_passes && before->passes[i].name == st->passes[i].name)
            v->frame_passes[i].ms -= before->passes[i].ms;
    }
    v->last = *st;
}

static bool frame(viewer *v, double dt)
{
    double t0 = dirt_clock_ms();
    dirt_gpu_window_poll(v->gpu);
    dirt_window_input in;
    dirt_gpu_window_input(v->gpu, &in);
    if (in.close_requested || dirt_gpu_window_should_close(v->gpu))
        v->quit = true;
    v->win_w = in.width;
    v->win_h = in.height;
    if (in.num_drops > 0) {
        const char *path = in.drops[in.num_drops - 1];
        char keep[4096];
        snprintf(keep, sizeof(keep), "%s", path);
        dirt_scene *probe = dirt_scene_load(keep, &v->o.load);
        if (!probe) {
            set_status(v, "could not open '%s' (see the log); kept the scene", keep);
        } else {
            dirt_scene_destroy(probe);
            if (!load_scene(v, keep))
                return false;
            set_status(v, "opened %s", keep);
        }
    }
    dirt_ui_begin_frame(v->ui);
    v->moving = false;
    bool ui_mouse = !v->o.no_ui && dirt_ui_wants_mouse(v->ui);
    bool ui_keys = !v->o.no_ui && dirt_ui_wants_keyboard(v->ui);
    if (!run_script(v)) {
        v->exit_code = DIRT_EXIT_FAILURE;
        v->quit = true;
    }
    handle_input(v, &in, dt, ui_mouse, ui_keys);
    for (int k = 0; k < DIRT_NUM_KEYS; k++)
        if (v->held[k] > 0)
            v->held[k]--;
    if (v->o.play) {
        v->o.time += dt * v->o.speed;
        int clip = v->o.clip < 0 ? 0 : v->o.clip;
        if (dirt_scene_num_clips(v->scene) > (size_t)clip) {
            double dur = dirt_scene_clip_duration(v->scene, (size_t)clip);
            if (dur > 0 && v->o.time > dur)
                v->o.time = v->o.loop ? fmod(v->o.time, dur) : 0;
        }
    }
    render_size(v, in.width, in.height);
    sync_sessions(v);
    if (v->click_pending)
        focus_at(v);
    /* A bounded amount of work: at most samples_per_frame samples, or the
     * raster preview while input moves the camera; none in a frame whose
     * image a script output took. */
    double s0 = dirt_clock_ms();
    int have = dirt_session_samples(v->s);
    bool preview = v->moving && v->pre;
    if (preview && !dirt_session_add_samples(v->pre, 1, NULL, NULL)) {
        set_status(v, "the raster preview failed (see the log); off");
        v->o.no_preview = true;
        preview = false;
    }
    if (!preview && !v->hold && (v->o.spp == 0 || have < v->o.spp)) {
        int n = v->o.samples_per_frame;
        if (v->o.spp && have + n > v->o.spp)
            n = v->o.spp - have;
        dirt_session_stats before = *dirt_session_get_stats(v->s);
        if (!dirt_session_add_samples(v->s, n, NULL, NULL)) {
            cli_error(PROG, "rendering failed (see the log)");
            return false;
        }
        record_passes(v, &before, have == 0);
        v->generation++;
    }
    if (v->cmp && !preview && !v->hold) {
        int hc = dirt_session_samples(v->cmp);
        if ((v->o.spp == 0 || hc < v->o.spp) && !dirt_session_add_samples(v->cmp, 1, NULL, NULL)) {
            set_status(v, "the comparison engine failed (see the log); split view off");
            v->o.compare = 0;
        }
    }
    double s1 = dirt_clock_ms();
    v->hold = false;
    draw(v, preview);
    v->num_panels = 0;
    if (!v->o.no_ui) {
        panel_settings(v);
        panel_numbers(v);
        if (v->show_help)
            panel_help(v);
    }
    dirt_ui_end_frame(v->ui);
    if (!take_screenshots(v)) {
        cli_error(PROG, "could not write a screenshot (see the error above)");
        v->exit_code = DIRT_EXIT_FAILURE;
    }
    dirt_gpu_window_swap(v->gpu);
    v->frame_ms[v->ring_pos] = (float)(dirt_clock_ms() - t0);
    v->sample_ms[v->ring_pos] = (float)(s1 - s0);
    v->ring_pos = (v->ring_pos + 1) % RING;
    if (v->ring_count < RING)
        v->ring_count++;
    v->frame++;
    if (v->o.test_frames && v->frame >= v->o.test_frames)
        v->quit = true;
    return true;
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    setvbuf(stderr, NULL, _IOLBF, 0);
    viewer *v = calloc(1, sizeof(*v));
    if (!v)
        return DIRT_EXIT_FAILURE;
    int rc = parse_args(argc, argv, &v->o);
    if (rc == -1 || rc == -2) {
        if (rc == -1)
            usage(stdout);
        for (size_t i = 0; rc == -2 && i < NUM_BINDINGS; i++)
            printf("%-24s %s\n", bindings[i][0], bindings[i][1]);
        free(v);
        return DIRT_EXIT_OK;
    }
    if (rc != DIRT_EXIT_OK) {
        free(v);
        return rc;
    }
    rc = DIRT_EXIT_USAGE;
    char why[1024];
    if (v->o.script && !vs_load(v->o.script, &v->script, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
        goto done;
    }
    if (!check_script(&v->script, &v->o))
        goto done;
    const char *outs[] = {v->o.screenshot, v->o.save_image, v->o.report};
    for (int i = 0; i < 3; i++)
        if (outs[i] && !cli_creatable(PROG, outs[i]))
            goto done;
    v->scene = v->o.scene_path ? dirt_scene_load(v->o.scene_path, &v->o.load)
                               : dirt_scene_create_default();
    if (!v->scene) {
        cli_scene_error(PROG, v->o.scene_path);
        goto done;
    }
    if (v->o.env_path) {
        dirt_env_opts eo = {.intensity = v->o.env_intensity, .rotation = v->o.env_rotation,
                            .max_bytes = v->o.load.max_bytes};
        if (!(v->env = dirt_env_load(v->o.env_path, &eo, why, sizeof(why)))) {
            cli_error(PROG, "--env: %s", why);
            goto done;
        }
        v->o.s.env = v->env;
        v->env_intensity = v->o.env_intensity;
        v->env_rotation = v->o.env_rotation;
    }
    /* No output (at exit or from the script) may be an input. */
    const char *souts[CLI_IO_MAX - 4] = {0};
    char spng[CLI_IO_MAX - 4][4200];
    vs_outputs(&v->script, souts, spng, CLI_IO_MAX - 4);
    char save_png[4200] = "";
    if (v->o.save_image && cli_has_ext(v->o.save_image, ".exr"))
        cli_png_beside(v->o.save_image, save_png, sizeof(save_png));
    cli_io io = {.scene_path = v->o.scene_path, .scene = v->scene,
                 .in = {{strcmp(v->o.env_path ? v->o.env_path : "sky", "sky") ? v->o.env_path
                                                                             : NULL, "--env"},
                        {v->o.script, "--script"}},
                 .out = {{v->o.screenshot, "--screenshot"}, {v->o.save_image, "--save-image"},
                         {save_png[0] ? save_png : NULL, "--save-image"},
                         {v->o.report, "--report"}}};
    for (size_t i = 0; i < CLI_IO_MAX - 4; i++)
        io.out[4 + i][0] = souts[i], io.out[4 + i][1] = "the script";
    if (cli_check_io(PROG, &io) != DIRT_EXIT_OK)
        goto done;
    if (v->o.camera >= 0 && (size_t)v->o.camera >= dirt_scene_num_cameras(v->scene)) {
        cli_error(PROG, "--camera %d: the scene has %zu camera(s)", v->o.camera,
                  dirt_scene_num_cameras(v->scene));
        goto done;
    }
    size_t clips = dirt_scene_num_clips(v->scene);
    if (v->o.clip >= 0 && clips > 0 && (size_t)v->o.clip >= clips) {
        cli_error(PROG, "--clip %d: the scene has %zu animation clip(s)", v->o.clip, clips);
        goto done;
    }
    rc = DIRT_EXIT_NO_GPU;
    v->gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = v->o.win_w,
                                              .height = v->o.win_h, .title = "dirt-view",
                                              .cpu_timing = v->o.cpu_timing});
    if (!v->gpu) {
        cli_error(PROG, "no window with an OpenGL 4.5 context could be made (see the error "
                  "above; under no display, run it with xvfb-run)");
        goto done;
    }
    v->ui = dirt_ui_create(v->gpu);
    if (!v->ui)
        goto done;
    rc = DIRT_EXIT_FAILURE;
    dirt_scene *first = v->scene;
    v->scene = NULL;
    dirt_window_input in;
    dirt_gpu_window_poll(v->gpu);
    dirt_gpu_window_input(v->gpu, &in);
    v->win_w = in.width;
    v->win_h = in.height;
    render_size(v, in.width, in.height);
    /* Hand the loaded scene to the viewer (load_scene would load it again). */
    v->scene = first;
    snprintf(v->scene_name, sizeof(v->scene_name), "%s",
             v->o.scene_path ? v->o.scene_path : "default scene");
    if (!make_sessions(v))
        goto done;
    v->diag = scene_diagonal(dirt_session_frame(v->s));
    reset_camera(v);
    v->applied_clip = v->o.clip;
    if (!v->o.quiet) {
        char desc[256];
        dirt_gpu_describe(v->gpu, desc, sizeof(desc));
        fprintf(stderr, "%s: %s, %zu triangles; %s; F1 lists the key bindings\n", PROG,
                v->scene_name, dirt_scene_num_triangles(v->scene), desc);
    }
    double last = dirt_clock_ms();
    while (!v->quit) {
        double now = dirt_clock_ms();
        double dt = (now - last) / 1000.0;
        last = now;
        if (dt > 0.25)
            dt = 0.25; /* a slow frame does not throw the camera across the scene */
        if (!frame(v, dt))
            goto done;
    }
    rc = v->exit_code;
    if (v->o.save_image && !save_render(v, v->o.save_image))
        rc = DIRT_EXIT_FAILURE;
    if (v->o.screenshot) {
        /* The last frame again, for the window as it is now. */
        v->quit = false;
        screenshot(v, v->o.screenshot);
        v->hold = true; /* the image as saved: no more samples */
        if (!frame(v, 0))
            rc = DIRT_EXIT_FAILURE;
    }
    if (v->o.report && !write_report(v, v->o.report))
        rc = DIRT_EXIT_FAILURE;
    if (!v->o.quiet) {
        char cam[1024];
        camera_args(v, cam, sizeof(cam));
        char args[4096];
        render_args(v, args, sizeof(args));
        fprintf(stderr, "%s: %d samples; camera: %s\n%s: the same image offline: dirt-render %s%s"
                "%s --spp %d -o OUT.exr\n", PROG, dirt_session_samples(v->s),
                cam[0] ? cam : "(default)", PROG, v->o.scene_path ? v->o.scene_path : "",
                v->o.scene_path ? " " : "", args, dirt_session_samples(v->s));
    }
done:
    dirt_gpu_texture_destroy(v->gpu, v->aux_tex);
    dirt_session_destroy(v->pre);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->s);
    dirt_ui_destroy(v->ui);
    dirt_gpu_destroy(v->gpu);
    dirt_env_destroy(v->env);
    dirt_env_destroy(v->env_old);
    dirt_scene_destroy(v->scene);
    vs_free(&v->script);
    free(v);
    if (rc == DIRT_EXIT_USAGE)
        seq_remove_made_dirs(); /* a refused run leaves no directory it made */
    seq_forget_made_dirs();
    return rc;
}
