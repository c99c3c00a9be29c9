/* The one option table of the programs (dirt-render, dirt-view,
 * dirt-compare). Every option has one entry: its spellings, one meaning
 * (where its value goes: a field of app_opts, most often the render
 * session's option of the same meaning), one kind and one range, its help
 * text and its default. A program lists the options it accepts (app_use,
 * in sections with titles); from that list the same table parses its
 * command line, applies its defaults and prints its --help, so help,
 * parsing and ranges cannot disagree. dirt-compare takes some options as
 * comma-separated lists (sweeps): each item is parsed as the single value
 * would be. */
#ifndef DIRT_APP_OPTIONS_H
#define DIRT_APP_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "app/sequence.h"
#include "dirt/session.h"

enum app_opt {
    APP_OPT_NONE = 0, /* ends a program's list */
    /* outputs */
    APP_OPT_OUTPUT, APP_OPT_OUTPUT_DIR, APP_OPT_WIDTH, APP_OPT_HEIGHT, APP_OPT_PNG,
    APP_OPT_EXPOSURE, APP_OPT_TONEMAP, APP_OPT_MSE_REFERENCE, APP_OPT_INFO, APP_OPT_STATS,
    APP_OPT_GRAPH_DOT, APP_OPT_DEBUG_ADS,
    /* scene, time and camera */
    APP_OPT_TIME, APP_OPT_FRAMES, APP_OPT_FPS, APP_OPT_CLIP, APP_OPT_LOOP, APP_OPT_PLAY,
    APP_OPT_SPEED, APP_OPT_CAMERA, APP_OPT_AUTO_CAMERA, APP_OPT_EYE, APP_OPT_LOOK_AT, APP_OPT_UP,
    APP_OPT_FOV, APP_OPT_ZNEAR, APP_OPT_ZFAR, APP_OPT_APERTURE, APP_OPT_FOCUS,
    APP_OPT_MAX_SCENE_MEMORY, APP_OPT_STRICT, APP_OPT_ALLOW_OUTSIDE_PATHS,
    /* light transport and the device */
    APP_OPT_ENGINE, APP_OPT_MODE, APP_OPT_SPP, APP_OPT_BOUNCES, APP_OPT_SEED, APP_OPT_AO_DISTANCE,
    APP_OPT_BACKGROUND, APP_OPT_ENV, APP_OPT_ENV_INTENSITY, APP_OPT_ENV_ROTATION, APP_OPT_THREADS,
    APP_OPT_GPU, APP_OPT_CPU_TIMING, APP_OPT_COUNT_WORK, APP_OPT_SORT_RAYS,
    /* the structure: DIRT and MMRT */
    APP_OPT_VIEWS, APP_OPT_TILE, APP_OPT_BUCKETS, APP_OPT_FACE_SIZE, APP_OPT_NO_CONSERVATIVE,
    APP_OPT_BUILD, APP_OPT_DEPTH_BUCKETS, APP_OPT_LARGE, APP_OPT_LARGE_GRID, APP_OPT_SUB_TILES,
    APP_OPT_BUCKET_MASKS, APP_OPT_NODE_DEPTHS, APP_OPT_HIZ_TOP,
    APP_OPT_FETCH, APP_OPT_DIRECT_VISIBILITY,
    APP_OPT_MARCH, APP_OPT_SAMPLES, APP_OPT_THICKNESS,
    /* sequences and farms (dirt-render) */
    APP_OPT_SKIP_EXISTING, APP_OPT_PLACEHOLDERS, APP_OPT_CLAIM_TIMEOUT, APP_OPT_CHUNK,
    APP_OPT_ANIMATED_SEED, APP_OPT_LOG,
    /* the window (dirt-view) */
    APP_OPT_WINDOW, APP_OPT_SAMPLES_PER_FRAME, APP_OPT_SLICE_MS, APP_OPT_BUFFER, APP_OPT_COMPARE,
    APP_OPT_COMPARE_IMAGE, APP_OPT_SPLIT,
    APP_OPT_DIFF, APP_OPT_DIFF_RANGE, APP_OPT_SCALE, APP_OPT_NO_PREVIEW, APP_OPT_NO_UI,
    APP_OPT_SCRIPT, APP_OPT_TEST_FRAMES, APP_OPT_SCREENSHOT, APP_OPT_SAVE_IMAGE, APP_OPT_REPORT,
    APP_OPT_BINDINGS,
    /* measurement (dirt-compare) */
    APP_OPT_RES, APP_OPT_DIRT_BUCKETS, APP_OPT_MMRT_BUCKETS, APP_OPT_THICKNESS_REL,
    APP_OPT_WARMUP, APP_OPT_REPEAT, APP_OPT_AGREE_RES, APP_OPT_NO_QUALITY, APP_OPT_IMAGES,
    APP_OPT_PRESET,
    /* every program */
    APP_OPT_QUIET, APP_OPT_VERBOSE, APP_OPT_HELP, APP_OPT_VERSION,
    APP_NUM_OPTS
};

#define APP_MAX_SCENES 16
#define APP_MAX_LIST 16

/* The values of a swept option, in the order given (a size: w, h). */
typedef struct app_list {
    int n;
    double v[APP_MAX_LIST][2];
} app_list;

/* Every value an option can set. Zero plus the defaults app_opts_init
 * applies is a program's starting point. */
typedef struct app_opts {
    const char *scenes[APP_MAX_SCENES]; /* the SCENE arguments */
    int num_scenes;
    /* the render session's options: every technique setting lands here */
    dirt_session_opts s;
    long hiz_top;               /* --hiz-top: -1 = the pyramid's top */
    long large;                 /* --large: 0 = none */
    /* scene, time and camera */
    double time, fps, speed;
    int clip;
    bool loop, play;
    int camera;                 /* --camera: -1 = none given */
    bool auto_camera;
    dirt_camera_look look;      /* --eye, --look-at, --up, --fov, --znear, --zfar */
    size_t max_scene_bytes;     /* --max-scene-memory (dirt_load_opts.max_bytes, and
                                   dirt_env_opts.max_bytes of --env) */
    bool strict;                /* --strict (dirt_load_opts.strict) */
    bool allow_outside_paths;   /* --allow-outside-paths (dirt_load_opts.allow_outside) */
    int spp;
    const char *env_path;       /* --env: a map or "sky" */
    float env_intensity, env_rotation;
    int gpu_platform;           /* enum dirt_gpu_platform */
    bool cpu_timing;
    /* outputs */
    const char *output, *stats, *graph_dot, *debug_ads, *mse_reference, *log;
    bool png, info;
    float exposure;
    int tonemap;                /* enum dirt_tonemap */
    /* sequences */
    seq_frames frames;          /* --frames (owned: app_opts_free) */
    bool skip_existing, placeholders, animated_seed;
    double claim_timeout;
    const char *chunk;
    /* the window */
    int window[2];
    int samples_per_frame, slice_ms, buffer, compare, scale; /* scale 0: automatic */
    float split, diff_range;
    bool diff, no_preview, no_ui, bindings;
    const char *script, *screenshot, *save_image, *report;
    const char *compare_image;  /* --compare-image: a reference EXR to compare with */
    long test_frames;
    /* measurement */
    int res[2], agree_res[2], warmup, repeat, dirt_buckets, mmrt_buckets;
    double thickness_rel;
    bool no_quality, images;
    const char *preset;
    const char *presets[8];     /* every --preset file read (inputs of the run) */
    int num_presets;
    /* every program */
    bool quiet, verbose, help, version;
    /* which options the command line (or a preset) gave */
    bool given[APP_NUM_OPTS];
    /* the swept values of the options a program takes as lists */
    app_list lists[APP_NUM_OPTS];
} app_opts;

/* A program's use of an option. */
enum {
    APP_USE_LIST = 1u << 0,     /* a comma-separated list (a sweep) */
    APP_USE_RUNTIME = 1u << 1,  /* a script may set it while the program runs */
};
typedef struct app_use {
    enum app_opt id;
    unsigned flags;
    const char *dflt;           /* this program's default value, NULL: the table's */
    const char *note;           /* replaces the table's default text, NULL: the table's */
} app_use;

typedef struct app_section {
    const char *title;          /* "Output:" */
    const app_use *uses;        /* ends with APP_OPT_NONE */
} app_section;

typedef struct app_program {
    const char *name;           /* "dirt-render": the prefix of every message */
    const char *usage;          /* the help text before the options */
    const app_section *sections; /* ends with a NULL title */
    const char *epilogue;       /* the help text after them */
    int max_scenes;             /* SCENE arguments accepted */
} app_program;

/* The programs (programs.c). */
extern const app_program app_render_program, app_view_program, app_compare_program;

/* The program's defaults in `o` (zeroed first). */
void app_opts_init(const app_program *p, app_opts *o);
void app_opts_free(app_opts *o);

/* Parses the command line into `o` (app_opts_init first). APP_PARSE_OK, or
 * APP_PARSE_USAGE after printing "PROG: why" (an unknown option, a missing
 * or bad value, too many scenes). --help and --version only set o->help
 * and o->version. Applies -v and -q to the log. */
enum { APP_PARSE_OK = 0, APP_PARSE_USAGE = 2 };
int app_parse(const app_program *p, int argc, char **argv, app_opts *o);

/* Sets one option that `p` accepts with `flags` from text, by its long
 * name without the dashes ("hiz-top"; a flag takes on/off): a script's
 * `set`. False after printing why (not such an option, bad value). */
bool app_set(const app_program *p, const char *name, const char *value, unsigned flags,
             app_opts *o);
/* The option of that name `p` accepts with `flags`, or APP_OPT_NONE. */
enum app_opt app_find(const app_program *p, const char *name, unsigned flags);

/* The checks across options that every program shares (a camera of its
 * own needs --eye and --look-at, one environment, the session's own
 * checks, ...), for the options `p` accepts. False after printing why. */
bool app_check(const app_program *p, const app_opts *o);

/* Prints `p`'s --help: its usage text, every option it accepts with its
 * help text and default, its epilogue. */
void app_print_help(const app_program *p, FILE *out);

/* The session options the command line asks for (--hiz-top and --large
 * mapped onto the session's hiz_levels and large). */
dirt_session_opts app_session_opts(const app_opts *o);
/* The camera the command line chooses, and the camera of --eye etc. */
enum dirt_camera_choice app_camera_choice(const app_opts *o);
dirt_camera app_look_camera(const app_opts *o);

/* Choice names of the table (NULL-terminated), for programs that print
 * options back (the viewer's dirt-render command line). */
extern const char *const app_mode_names[];
extern const char *const app_views_names[];
extern const char *const app_fetch_names[];
extern const char *const app_build_names[];
extern const char *const app_depth_buckets_names[];
extern const char *const app_march_names[];
extern const char *const app_tonemap_names[];
extern const char *const app_engine_names[];
extern const char *const app_compare_names[];
extern const char *const app_buffer_names[];

/* The table itself, for tests: the entry of `id`. */
typedef struct app_opt_def {
    enum app_opt id;
    const char *s, *l, *alias; /* "-W", "--width"; another long spelling or NULL */
    const char *meta;          /* the value's name in the help ("N"); NULL: a flag */
    char kind;
    size_t off;                /* where in app_opts */
    double lo, hi;
    const char *const *names;  /* a choice's names */
    const char *help;
    const char *dflt;          /* a value, applied by app_opts_init; NULL: none */
    const char *note;          /* the default in words, when it is not a value */
} app_opt_def;
const app_opt_def *app_opt_table(enum app_opt id);

#endif
