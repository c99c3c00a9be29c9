/* dirt-render: renders one frame or a frame range of a glTF scene headless,
 * on the render session (dirt/session.h). */
#include <cjson/cJSON.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/sequence.h"
#include "dirt/clock.h"
#include "dirt/file.h"
#include "dirt/integrator.h"
#include "dirt/log.h"
#include "dirt/session.h"

#define PROG "dirt-render"

typedef struct options {
    dirt_session_opts s;
    const char *scene_path;   /* NULL = embedded default scene */
    const char *output, *stats_path, *graph_dot, *debug_ads, *log_path, *mse_ref, *chunk;
    const char *env_path;     /* --env */
    dirt_env_opts env;        /* --env-intensity, --env-rotation */
    bool background_set;
    double time, fps, exposure, claim_timeout;
    int camera;               /* -1 default, -2 automatic, else scene camera */
    int gpu_platform;         /* enum dirt_gpu_platform */
    dirt_camera_look look;    /* --eye, --look-at, ... */
    bool eye_set, target_set, look_set; /* --eye, --look-at, any look option */
    int clip, tonemap;
    bool loop, png_preview, quiet, info, time_set, exposure_set, tonemap_set;
    bool skip_existing, placeholders, animated_seed;
    bool cpu_timing;          /* dirt_gpu_opts.cpu_timing */
    seq_frames frames;        /* empty: one frame at --time */
    dirt_load_opts load;      /* --max-scene-memory */
    int spp;
} options;

static void usage(FILE *out)
{
    fprintf(out,
"Usage: " PROG " [SCENE] -o OUTPUT [options]\n"
"       " PROG " --info [SCENE]\n"
"\n"
"Renders a glTF 2.0 (.gltf, .glb) or OBJ + MTL (.obj) scene headless through OpenGL 4.5 (EGL).\n"
"Without SCENE, renders the embedded default scene (a Cornell-style room).\n"
"\n"
"Output:\n"
"  -o, --output PATH     image to write: .exr (float RGBA + albedo, N, Z) or .png\n"
"                        (8-bit sRGB). With --frames, PATH holds one frame field:\n"
"                        a run of # (f_####.exr: the frame zero-padded to 4) or a\n"
"                        printf integer (f_%%04d.exr). Missing directories are\n"
"                        made.\n"
"  -W, --width N         image width in pixels (default 640)\n"
"  -H, --height N        image height (default: width / the camera's aspect,\n"
"                        4:3 for the automatic camera)\n"
"      --png             with an .exr output, also write a .png preview beside it\n"
"      --exposure STOPS  exposure of PNG output (default 0)\n"
"      --tonemap OP      PNG tone map: clamp (default), reinhard or aces\n"
"      --mse-reference FILE.exr  print and record each frame's MSE and relative\n"
"                        MSE against this image (it may hold a frame field)\n"
"      --info            print the scene's cameras, clips, lights, emitters and\n"
"                        counts, and exit\n"
"\n"
"Scene and camera:\n"
"      --max-scene-memory SIZE  the most memory the expanded scene may take\n"
"                        (default 512M; K, M, G: powers of 1024): a scene that\n"
"                        needs more is refused before it is allocated\n"
"  -t, --time T          animation time in seconds (default 0)\n"
"      --frames LIST     frames A:B[:step] (A..B inclusive) or a list such as\n"
"                        1,5,10-20, each at time frame/fps\n"
"      --fps F           frames per second for --frames (default 24)\n"
"      --clip I          animation clip index (default 0; -1 = rest pose)\n"
"      --loop            wrap time into the clip instead of clamping\n"
"      --camera I        use the scene's camera I (default: camera 0, or an\n"
"                        automatic camera framing the scene when it has none)\n"
"      --auto-camera     ignore the scene's cameras: frame the whole animation\n"
"                        clip (the same camera at every frame)\n"
"      --eye X,Y,Z       a camera of its own: its position (with --look-at; the\n"
"                        numbers dirt-view prints for its camera)\n"
"      --look-at X,Y,Z   the point that camera looks at\n"
"      --up X,Y,Z        its up direction (default 0,1,0)\n"
"      --fov DEG         its vertical field of view (default 45)\n"
"      --znear Z, --zfar Z  its depth range (default: 1/1000 of the distance to\n"
"                        the --look-at point; infinite)\n"
"      --aperture R      thin-lens aperture radius (default 0: pinhole)\n"
"      --focus D         focus distance with --aperture (default: distance to the\n"
"                        scene centre)\n"
"\n"
"Technique:\n"
"      --engine NAME     dirt: path tracing through the DIRT structure on the GPU\n"
"                        (default); mmrt: the same path tracer through the MMRT\n"
"                        A-buffer (the fragment-based baseline, doc/mmrt.md);\n"
"                        embree: the CPU ground truth (Embree 3); raster:\n"
"                        rasterized preview with direct lighting\n"
"      --mode MODE       pt (path tracing, default) or ao (ambient occlusion)\n"
"      --spp N           samples per pixel (default 16)\n"
"      --bounces K       scattering events per path, 1 = direct light (default 4)\n"
"      --seed N          random seed (default 0); the same seed gives the same\n"
"                        paths in every engine\n"
"      --ao-distance D   AO ray length (default: infinite)\n"
"      --background R,G,B  radiance of rays that leave the scene (default 0,0,0):\n"
"                        a constant environment light\n"
"      --env FILE        environment light: an equirectangular map (.exr or\n"
"                        .hdr, linear radiance; its centre looks along -Z),\n"
"                        or 'sky' for the built-in sky; importance-sampled\n"
"      --env-intensity X scale of the map's radiance (default 1)\n"
"      --env-rotation DEG  turn the map about +Y (default 0)\n"
"      --stats FILE.json write timings (per pass, with the clock that measured\n"
"                        them), ray counts, paths per path event and bytes per\n"
"                        buffer as JSON\n"
"      --threads N       embree: CPU threads (default: all)\n"
"      --gpu PLATFORM    auto (default: a hardware GPU's EGL device, else Mesa's\n"
"                        surfaceless platform), device or surfaceless; also the\n"
"                        environment variable DIRT_GPU\n"
"      --cpu-timing      time passes with glFinish and the CPU clock (always on\n"
"                        with a software renderer such as llvmpipe)\n"
"\n"
"DIRT acceleration structure (--engine dirt, --debug-ads; --views, --face-size\n"
"and -B also set MMRT's):\n"
"      --debug-ads DIR   build the structure for the frame, print its stats and\n"
"                        write heat maps of list lengths and depth bounds per\n"
"                        view into DIR (single frame only)\n"
"      --views MODE      single | cube | cube+camera (default cube+camera)\n"
"  -S, --tile S          tile size 1, 2, 4 or 8 (default 2; also --tile-size)\n"
"  -B, --buckets B       depth buckets per tile, >= 1 (default for dirt: 8 on a\n"
"                        software renderer, 16 on a GPU, as measured; 4 for\n"
"                        mmrt, the MMRT paper's setting)\n"
"      --face-size N     cube face size in pixels (default max(W,H)/2)\n"
"      --no-conservative-raster  emulate conservative rasterization even when\n"
"                        GL_NV_conservative_raster is present\n"
"      --build KIND      how the structure is built (the same structure either\n"
"                        way; doc/dirt-build.md): raster, compute, or auto\n"
"                        (default: compute on a software renderer, raster on\n"
"                        a GPU, as measured)\n"
"      --large N         at most N (0..16) of the largest triangles are tested by\n"
"                        every ray instead of listed in tiles (doc/dirt-trace.md;\n"
"                        default 16, 0 = none)\n"
"      --hiz-top L       highest Hi-Z level the march starts from; 0 = tiles\n"
"                        only, no Hi-Z (default: the pyramid's top)\n"
"      --fetch KIND      compute (default) or raster (the paper's geometry pass)\n"
"      --direct-visibility  first hits from a visibility buffer of the camera view\n"
"                        (pixel centres: no anti-aliasing or depth of field)\n"
"      --graph-dot FILE.dot  write the path tracer's frame graph (dirt, mmrt)\n"
"\n"
"MMRT (--engine mmrt; tile size 1: MMRT is per pixel):\n"
"      --march KIND      hiz (default: walk of the min/max depth pyramid) or linear\n"
"                        (jittered samples along the ray in each view)\n"
"      --samples N       linear march: samples per view (default 30)\n"
"      --thickness T     a fragment is hit when its depth is within T (eye-space\n"
"                        depth units) of the ray's (default 0.2%% of the scene's\n"
"                        bounding-box diagonal); rays start 3 T off surfaces\n"
"      --hiz-top L       as for dirt: highest Hi-Z level of the walk\n"
"\n"
"Sequences and farms:\n"
"      --skip-existing   leave frames whose files are complete alone\n"
"      --placeholders    claim each frame (FILE.claim.N) before rendering it, so\n"
"                        any number of workers can share one output directory;\n"
"                        implies --skip-existing\n"
"      --claim-timeout S a claim not refreshed for S seconds belongs to a dead\n"
"                        worker and is taken over (default 600)\n"
"      --chunk K/N       render the K-th of N contiguous shares of the frames;\n"
"                        --chunk slurm takes K and N from the Slurm job array\n"
"      --animated-seed   a different seed per frame (seed mixed with the frame\n"
"                        number; default: the same noise on every frame)\n"
"      --log FILE.jsonl  append one JSON record per frame as it finishes, then a\n"
"                        summary record\n"
"\n"
"Other:\n"
"  -q, --quiet           print only errors\n"
"  -v, --verbose         print debug messages\n"
"  -h, --help            show this help and exit\n"
"\n"
"Exit status: 0 success, 1 render failure, 2 bad option or input (unreadable\n"
"or malformed scene, unwritable output), 3 no OpenGL 4.5 context.\n"
"Images are written atomically: a failed run leaves no partial file.\n");
}

static const char *const modes[] = {"pt", "ao", NULL};
static const char *const views[] = {"", "single", "cube", "cube+camera", NULL};
static const char *const fetches[] = {"compute", "raster", NULL};
static const char *const builds[] = {"auto", "raster", "compute", NULL};
static const char *const marches[] = {"hiz", "linear", NULL};

static const char *const tonemaps[] = {"clamp", "reinhard", "aces", NULL};

static bool parse_frames(const char *text, options *o)
{
    char why[256];
    seq_frames_free(&o->frames);
    if (!seq_frames_parse(text, &o->frames, why, sizeof(why))) {
        cli_error(PROG, "--frames %s", why);
        return false;
    }
    return true;
}

/* The checks across options; false after printing why. Warns about
 * options that do nothing here. */
static bool check_options(const options *o)
{
    const dirt_session_opts *s = &o->s;
    bool many = o->frames.count > 1;
    char why[256];
    if (o->info)
        return true;
    int fields = o->output ? seq_pattern_fields(o->output) : 0;
    bool png_out = o->output && (cli_has_ext(o->output, ".png") || o->png_preview);
    if (!o->output) {
        cli_error(PROG, "no output given: use -o OUT.exr or -o OUT.png (see --help)");
    } else if (!cli_has_ext(o->output, ".exr") && !cli_has_ext(o->output, ".png")) {
        cli_error(PROG, "output '%s' must end in .exr or .png", o->output);
    } else if (fields < 0) {
        cli_error(PROG, "output '%s' has more than one frame field or a stray '%%'", o->output);
    } else if (many && fields != 1) {
        cli_error(PROG, "--frames renders several images: the output '%s' needs one frame "
                  "field such as frame_####.exr or frame_%%04d.exr", o->output);
    } else if (!dirt_session_check_opts(s, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
    } else if (o->look_set && !(o->eye_set && o->target_set)) {
        cli_error(PROG, "a camera of its own needs both --eye and --look-at");
    } else if (o->look_set && o->camera != -1) {
        cli_error(PROG, "--eye/--look-at and --camera/--auto-camera choose different cameras");
    } else if (o->look_set && o->look.zfar > 0 && o->look.znear > 0 &&
               !(o->look.zfar > o->look.znear)) {
        cli_error(PROG, "--zfar must be beyond --znear");
    } else if (o->env_path && o->background_set) {
        cli_error(PROG, "--env and --background both set the environment: give one");
    } else if (!o->env_path && (o->env.intensity != 0 || o->env.rotation != 0)) {
        cli_error(PROG, "--env-intensity and --env-rotation need an --env map");
    } else if (o->debug_ads && many) {
        cli_error(PROG, "--debug-ads works on a single frame, not with --frames");
    } else if (o->png_preview && !cli_has_ext(o->output, ".exr")) {
        cli_error(PROG, "--png needs an .exr output (the output is already a PNG)");
    } else if (o->graph_dot && s->engine != DIRT_ENGINE_DIRT && s->engine != DIRT_ENGINE_MMRT) {
        cli_error(PROG, "--graph-dot needs a path-tracing engine (dirt or mmrt)");
    } else if (o->log_path && !cli_has_ext(o->log_path, ".jsonl")) {
        cli_error(PROG, "--log file '%s' must end in .jsonl", o->log_path);
    } else if ((o->chunk || o->placeholders) && !o->frames.count) {
        cli_error(PROG, "--chunk and --placeholders share out --frames: give a frame list");
    } else {
        const struct { bool idle; const char *what; } warn[] = {
            {(o->exposure_set || o->tonemap_set) && !png_out,
             "--exposure and --tonemap only change PNG output"},
            {o->time_set && o->frames.count, "-t is ignored with --frames (time = frame / fps)"},
            {s->threads && s->engine != DIRT_ENGINE_EMBREE, "--threads is for --engine embree"},
            {(s->march || s->march_samples || s->thickness > 0) && s->engine != DIRT_ENGINE_MMRT,
             "--march, --samples and --thickness are MMRT's"},
            {s->ao_distance > 0 && s->mode != DIRT_PT_AO, "--ao-distance needs --mode ao"},
            {s->focus > 0 && !(s->aperture > 0), "--focus needs --aperture"},
            {o->animated_seed && !o->frames.count, "--animated-seed needs --frames"},
        };
        for (size_t i = 0; i < sizeof(warn) / sizeof(warn[0]); i++) {
            if (warn[i].idle && !o->quiet)
                fprintf(stderr, "%s: warning: %s\n", PROG, warn[i].what);
        }
        return true;
    }
    return false;
}

/* Returns DIRT_EXIT_OK, or DIRT_EXIT_USAGE after printing why; -1 for --help. */
static int parse_args(int argc, char **argv, options *o)
{
    *o = (options){.s = {.width = 640}, .fps = 24, .camera = -1, .spp = 16,
                   .claim_timeout = 600, .look = {.up = {0, 1, 0}}};
    long hiz_top = -1, large = -1;
    const char *engines[DIRT_NUM_ENGINES + 1] = {0};
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        engines[e] = dirt_engine_names[e];
    /* Options with a value (argv[i + 1]), by kind: s string, i int, l long,
     * u uint32, d double, f float, c choice of `names`, F frames, b colour,
     * j .json path, g .dot path, z size in bytes. */
    const struct { const char *s, *l, *alt; char kind; void *dst; double lo, hi;
                   const char *const *names; } opts[] = {
        {"-o", "--output", NULL, 's', &o->output, 0, 0, NULL},
        {"-W", "--width", NULL, 'i', &o->s.width, 1, 16384, NULL},
        {"-H", "--height", NULL, 'i', &o->s.height, 1, 16384, NULL},
        {"-t", "--time", NULL, 'd', &o->time, -1e6, 1e6, NULL},
        {NULL, "--fps", NULL, 'd', &o->fps, 1e-3, 1e4, NULL},
        {NULL, "--clip", NULL, 'i', &o->clip, -1, 1000000, NULL},
        {NULL, "--camera", NULL, 'i', &o->camera, 0, 1000000, NULL},
        {NULL, "--spp", NULL, 'i', &o->spp, 1, 1 << 20, NULL},
        {NULL, "--bounces", NULL, 'i', &o->s.bounces, 1, 64, NULL},
        {NULL, "--seed", NULL, 'u', &o->s.seed, 0, 4294967295.0, NULL},
        {NULL, "--ao-distance", NULL, 'f', &o->s.ao_distance, 0, 1e30, NULL},
        {NULL, "--threads", NULL, 'i', &o->s.threads, 1, 4096, NULL},
        {NULL, "--eye", NULL, 'v', o->look.eye, 0, 0, NULL},
        {NULL, "--look-at", NULL, 'v', o->look.target, 0, 0, NULL},
        {NULL, "--up", NULL, 'v', o->look.up, 0, 0, NULL},
        {NULL, "--fov", NULL, 'f', &o->look.fov_deg, 1e-3, 179.9, NULL},
        {NULL, "--znear", NULL, 'f', &o->look.znear, 1e-12, 1e30, NULL},
        {NULL, "--zfar", NULL, 'f', &o->look.zfar, 1e-12, 1e30, NULL},
        {NULL, "--aperture", NULL, 'f', &o->s.aperture, 0, 1e6, NULL},
        {NULL, "--focus", NULL, 'f', &o->s.focus, 1e-6, 1e9, NULL},
        {NULL, "--exposure", NULL, 'd', &o->exposure, -64, 64, NULL},
        {NULL, "--debug-ads", NULL, 's', &o->debug_ads, 0, 0, NULL},
        {"-S", "--tile", "--tile-size", 'i', &o->s.tile_size, 1, 8, NULL},
        {"-B", "--buckets", NULL, 'i', &o->s.buckets, 1, 1024, NULL},
        {NULL, "--samples", NULL, 'i', &o->s.march_samples, 1, 65536, NULL},
        {NULL, "--thickness", NULL, 'f', &o->s.thickness, 1e-12, 1e12, NULL},
        {NULL, "--face-size", NULL, 'i', &o->s.face_size, 1, 16384, NULL},
        {NULL, "--hiz-top", NULL, 'l', &hiz_top, 0, 15, NULL},
        {NULL, "--large", NULL, 'l', &large, 0, DIRT_ADS_MAX_LARGE, NULL},
        {NULL, "--engine", NULL, 'c', &o->s.engine, 0, 0, engines},
        {NULL, "--mode", NULL, 'c', &o->s.mode, 0, 0, modes},
        {NULL, "--views", NULL, 'c', &o->s.views, 0, 0, views},
        {NULL, "--fetch", NULL, 'c', &o->s.fetch, 0, 0, fetches},
        {NULL, "--build", NULL, 'c', &o->s.build, 0, 0, builds},
        {NULL, "--march", NULL, 'c', &o->s.march, 0, 0, marches},
        {NULL, "--frames", NULL, 'F', o, 0, 0, NULL},
        {NULL, "--background", NULL, 'b', o->s.background, 0, 0, NULL},
        {NULL, "--env", NULL, 's', &o->env_path, 0, 0, NULL},
        {NULL, "--env-intensity", NULL, 'f', &o->env.intensity, 1e-30, 1e30, NULL},
        {NULL, "--env-rotation", NULL, 'f', &o->env.rotation, -1e6, 1e6, NULL},
        {NULL, "--stats", NULL, 'j', &o->stats_path, 0, 0, NULL},
        {NULL, "--graph-dot", NULL, 'g', &o->graph_dot, 0, 0, NULL},
        {NULL, "--log", NULL, 's', &o->log_path, 0, 0, NULL},
        {NULL, "--mse-reference", NULL, 's', &o->mse_ref, 0, 0, NULL},
        {NULL, "--chunk", NULL, 's', &o->chunk, 0, 0, NULL},
        {NULL, "--claim-timeout", NULL, 'd', &o->claim_timeout, 1, 1e7, NULL},
        {NULL, "--tonemap", NULL, 'c', &o->tonemap, 0, 0, tonemaps},
        {NULL, "--gpu", NULL, 'c', &o->gpu_platform, 0, 0, dirt_gpu_platform_names},
        {NULL, "--max-scene-memory", NULL, 'z', &o->load.max_bytes, 1 << 20,
         (double)SIZE_MAX, NULL},
    };
    const struct { const char *s, *l; bool *dst; } flags[] = {
        {NULL, "--loop", &o->loop}, {NULL, "--png", &o->png_preview},
        {NULL, "--info", &o->info}, {NULL, "--direct-visibility", &o->s.direct_visibility},
        {NULL, "--no-conservative-raster", &o->s.force_emulation},
        {NULL, "--cpu-timing", &o->cpu_timing}, {"-q", "--quiet", &o->quiet},
        {NULL, "--skip-existing", &o->skip_existing}, {NULL, "--placeholders", &o->placeholders},
        {NULL, "--animated-seed", &o->animated_seed},
    };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
#define IS(s_, l_) (((s_) && !strcmp(a, (s_))) || !strcmp(a, (l_)))
        bool done = false;
        for (size_t k = 0; !done && k < sizeof(flags) / sizeof(flags[0]); k++)
            if (IS(flags[k].s, flags[k].l))
                *flags[k].dst = done = true;
        for (size_t k = 0; !done && k < sizeof(opts) / sizeof(opts[0]); k++) {
            if (!IS(opts[k].s, opts[k].l) && !(opts[k].alt && !strcmp(a, opts[k].alt)))
                continue;
            done = true;
            if (!val) {
                cli_error(PROG, "option %s needs a value", a);
                return DIRT_EXIT_USAGE;
            }
            i++;
            if (!cli_value(PROG, a, val, opts[k].kind, opts[k].dst, opts[k].lo, opts[k].hi,
                           opts[k].names))
                return DIRT_EXIT_USAGE;
            if (opts[k].kind == 'F' && !parse_frames(val, o))
                return DIRT_EXIT_USAGE;
            o->time_set |= opts[k].dst == &o->time;
            o->background_set |= opts[k].dst == o->s.background;
            o->exposure_set |= opts[k].dst == &o->exposure;
            o->tonemap_set |= opts[k].dst == &o->tonemap;
            o->eye_set |= opts[k].dst == o->look.eye;
            o->target_set |= opts[k].dst == o->look.target;
            o->look_set |= opts[k].kind == 'v' || opts[k].dst == &o->look.fov_deg ||
                           opts[k].dst == &o->look.znear || opts[k].dst == &o->look.zfar;
        }
        if (done)
            continue;
        if (IS("-h", "--help"))
            return -1;
        if (!strcmp(a, "--auto-camera")) {
            o->camera = -2;
        } else if (IS("-v", "--verbose")) {
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
#undef IS
    }
    if (o->quiet)
        dirt_log_set_level(DIRT_LOG_ERROR);
    o->s.hiz_levels = (int)(hiz_top + 1);
    if (large >= 0)
        o->s.large = large ? (int)large : -1;
    return check_options(o) ? DIRT_EXIT_OK : DIRT_EXIT_USAGE;
}

/* The files of `frame`: the image, and its PNG preview with --png. */
static int frame_files(const options *o, long frame, char files[2][4200])
{
    seq_frame_path(o->output, frame, files[0], sizeof(files[0]));
    if (!o->png_preview)
        return 1;
    cli_png_beside(files[0], files[1], sizeof(files[1]));
    return 2;
}

/* Checks every output location before any expensive work. */
static bool outputs_ok(const options *o, long first_frame)
{
    char files[2][4200];
    int n = frame_files(o, first_frame, files);
    for (int i = 0; i < n; i++) {
        if (!cli_creatable(PROG, files[i]))
            return false;
    }
    if ((o->stats_path && !cli_creatable(PROG, o->stats_path)) ||
        (o->graph_dot && !cli_creatable(PROG, o->graph_dot)) || (o->log_path && !cli_creatable(PROG, o->log_path)))
        return false;
    char probe[4200];
    snprintf(probe, sizeof(probe), "%s/ads.png", o->debug_ads ? o->debug_ads : ".");
    return !o->debug_ads || cli_creatable(PROG, probe);
}

/* The structure's pictures of the frame just rendered (a DIRT session). */
static bool write_debug_ads(const options *o, dirt_session *s)
{
    dirt_ads *ads = dirt_session_ads(s);
    if (!ads && !dirt_session_build(s))
        return false;
    ads = dirt_session_ads(s);
    if (!o->quiet)
        dirt_ads_print_stats(ads, stderr);
    return dirt_ads_write_debug(ads, o->debug_ads, o->quiet);
}

/* A frame's seed with --animated-seed: the seed and the frame number mixed
 * (a fixed integer hash), so every frame's noise differs and reruns agree. */
static uint32_t frame_seed(uint32_t seed, long frame)
{
    uint32_t h = seed ^ (uint32_t)frame * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    return h ^ (h >> 16);
}

typedef struct progress {
    cli_progress cli;
    seq_claim *claim;
} progress;

static void on_sample(void *user, int done, int total)
{
    progress *p = user;
    cli_progress_sample(&p->cli, done, total);
    seq_claim_touch(p->claim);
}

/* Appends one line to the JSON Lines log (one write(2): lines of workers
 * sharing a log do not interleave). */
static bool log_line(FILE *log, cJSON *rec)
{
    char *text = rec ? cJSON_PrintUnformatted(rec) : NULL;
    bool ok = text && fprintf(log, "%s\n", text) > 0 && fflush(log) == 0;
    free(text);
    return ok;
}

/* MSE and relative MSE of the beauty against the reference of `frame`. */
static bool compare_reference(const options *o, long frame, const dirt_image *img,
                              dirt_image_error *e)
{
    char path[4200];
    seq_frame_path(o->mse_ref, frame, path, sizeof(path));
    dirt_image *ref = dirt_image_read_exr(path);
    bool ok = ref && dirt_image_compare(img, ref, e);
    if (!ok)
        cli_error(PROG, "cannot compare with the reference '%s' (see above)", path);
    dirt_image_destroy(ref);
    return ok;
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    setvbuf(stderr, NULL, _IOLBF, 0);
    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc < 0) {
        usage(stdout);
        return DIRT_EXIT_OK;
    }
    if (rc != DIRT_EXIT_OK) {
        seq_frames_free(&o.frames);
        return rc;
    }
    dirt_scene *scene = NULL;
    dirt_env *env = NULL;
    dirt_gpu *gpu = NULL;
    dirt_session *session = NULL, *debug = NULL;
    dirt_session_stats *fstats = NULL;
    FILE *log = NULL;
    seq_claim claim = {0};
    char why[512];
    char written[2][4200]; /* a single frame's files, removed if the run fails later */
    int num_written = 0;
    rc = DIRT_EXIT_USAGE;
    /* The frames: the list, or one frame at --time (numbered 0). */
    bool sequence = o.frames.count > 0;
    if (!sequence && !(o.frames.frames = malloc(sizeof(long))))
        goto done;
    if (!sequence)
        o.frames.frames[o.frames.count++] = 0;
    if (o.chunk) {
        long k = 0, n = 0;
        bool ok = !strcmp(o.chunk, "slurm") ? seq_slurm_share(&k, &n, why, sizeof(why))
                                            : sscanf(o.chunk, "%ld/%ld", &k, &n) == 2;
        if (!ok || !seq_frames_chunk(&o.frames, k, n, why, sizeof(why))) {
            cli_error(PROG, "--chunk %s: %s", o.chunk, ok ? why : "expects K/N or slurm");
            goto done;
        }
        if (!o.quiet)
            fprintf(stderr, "%s: share %ld of %ld: %zu frame(s)\n", PROG, k, n, o.frames.count);
    }
    if (!o.info && !dirt_cleanup_on_signals())
        goto done;
    if (!o.info && !outputs_ok(&o, o.frames.count ? o.frames.frames[0] : 0))
        goto done;
    if (o.log_path && !(log = fopen(o.log_path, "a"))) {
        cli_error(PROG, "cannot append to '%s'", o.log_path);
        goto done;
    }
    scene = o.scene_path ? dirt_scene_load(o.scene_path, &o.load) : dirt_scene_create_default();
    if (!scene) {
        if (dirt_scene_last_error() == DIRT_SCENE_ERR_TOO_LARGE)
            cli_error(PROG, "scene '%s' needs more than %.0f MiB once expanded: raise the "
                      "budget with --max-scene-memory (such as 4G)", o.scene_path,
                      (o.load.max_bytes ? o.load.max_bytes : DIRT_LOAD_DEFAULT_MAX_BYTES) /
                          1048576.0);
        else
            cli_error(PROG, "cannot load scene '%s' (see the error above)",
                      o.scene_path ? o.scene_path : "default");
        goto done;
    }
    if (o.info) {
        rc = dirt_scene_print_info(scene, stdout) ? DIRT_EXIT_OK : DIRT_EXIT_FAILURE;
        goto done;
    }
    if (o.env_path) {
        if (!(env = dirt_env_load(o.env_path, &o.env, why, sizeof(why)))) {
            cli_error(PROG, "--env: %s", why);
            goto done;
        }
        o.s.env = env;
    }
    size_t cameras = dirt_scene_num_cameras(scene), clips = dirt_scene_num_clips(scene);
    if (o.camera >= 0 && (size_t)o.camera >= cameras) {
        cli_error(PROG, "--camera %d: the scene has %zu camera(s)", o.camera, cameras);
        goto done;
    }
    if (o.clip >= 0 && clips > 0 && (size_t)o.clip >= clips) {
        cli_error(PROG, "--clip %d: the scene has %zu animation clip(s)", o.clip, clips);
        goto done;
    }
    if (o.s.engine != DIRT_ENGINE_EMBREE || o.debug_ads) {
        rc = DIRT_EXIT_NO_GPU;
        gpu = dirt_gpu_create(&(dirt_gpu_opts){.cpu_timing = o.cpu_timing,
                                                .platform = (enum dirt_gpu_platform)o.gpu_platform});
        if (!gpu) {
            cli_error(PROG, "no OpenGL 4.5 context could be made (see the error above)");
            goto done;
        }
    }
    rc = DIRT_EXIT_FAILURE;
    dirt_session_opts dbg_opts = o.s;
    dbg_opts.engine = DIRT_ENGINE_DIRT;
    enum dirt_camera_choice choice = o.look_set       ? DIRT_CAMERA_EXPLICIT
                                     : o.camera >= 0  ? DIRT_CAMERA_SCENE
                                     : o.camera == -2 ? DIRT_CAMERA_AUTO
                                                      : DIRT_CAMERA_DEFAULT;
    dirt_camera look_cam;
    dirt_camera_from_look(&o.look, &look_cam);
    dirt_eval_opts eval = {.clip = o.clip, .loop = o.loop};
    session = dirt_session_create(gpu, scene, &o.s);
    if (!session || !dirt_session_set_camera(session, choice, o.camera, &look_cam))
        goto done;
    debug = o.debug_ads && o.s.engine != DIRT_ENGINE_DIRT
                ? dirt_session_create(gpu, scene, &dbg_opts) : NULL;
    if (o.debug_ads && o.s.engine != DIRT_ENGINE_DIRT &&
        (!debug || !dirt_session_set_camera(debug, choice, o.camera, &look_cam)))
        goto done;
    fstats = calloc(o.frames.count ? o.frames.count : 1, sizeof(*fstats));
    if (!fstats)
        goto done;
    if (!o.quiet) {
        char desc[256] = "CPU";
        if (gpu && o.s.engine != DIRT_ENGINE_EMBREE)
            dirt_gpu_describe(gpu, desc, sizeof(desc));
        fprintf(stderr, "%s: %s, %zu triangles, engine %s; %s\n", PROG,
                o.scene_path ? o.scene_path : "default scene", dirt_scene_num_triangles(scene),
                dirt_engine_names[o.s.engine], desc);
    }
    bool shared = o.skip_existing || o.placeholders;
    /* Dead writers' temporary files, once per output directory. */
    char png_pattern[4200], last_dir[4200] = "";
    cli_png_beside(o.output, png_pattern, sizeof(png_pattern));
    for (size_t i = 0; i < o.frames.count; i++) {
        char f[4200];
        seq_frame_path(o.output, o.frames.frames[i], f, sizeof(f));
        char *slash = strrchr(f, '/');
        if (slash)
            *slash = '\0';
        if (!strcmp(f, last_dir) && i)
            continue;
        snprintf(last_dir, sizeof(last_dir), "%s", f);
        seq_clean_stale_temps(o.output, o.frames.frames[i], o.claim_timeout);
        if (o.png_preview)
            seq_clean_stale_temps(png_pattern, o.frames.frames[i], o.claim_timeout);
    }
    size_t rendered = 0, skipped = 0, total = o.frames.count;
    double t0 = dirt_clock_ms();
    for (size_t i = 0; i < total; i++) {
        long fi = o.frames.frames[i];
        char files[2][4200];
        int nfiles = frame_files(&o, fi, files);
        const char *paths[2] = {files[0], files[1]};
        if (shared && seq_complete(paths, nfiles)) {
            skipped++;
            continue;
        }
        if (o.placeholders) {
            if (!seq_claim_take(files[0], o.claim_timeout, &claim, why, sizeof(why))) {
                if (why[0]) {
                    cli_error(PROG, "%s", why);
                    rc = DIRT_EXIT_USAGE;
                    goto done;
                }
                skipped++; /* another worker's */
                continue;
            }
            if (seq_complete(paths, nfiles)) { /* finished while we looked */
                seq_claim_release(&claim, files[0], true);
                skipped++;
                continue;
            }
        }
        double t = sequence ? fi / o.fps : o.time;
        uint32_t seed = o.animated_seed ? frame_seed(o.s.seed, fi) : o.s.seed;
        dirt_session_opts so = *dirt_session_get_opts(session);
        so.seed = seed;
        if (!seq_make_parent_dirs(files[0], why, sizeof(why))) {
            cli_error(PROG, "%s", why);
            rc = DIRT_EXIT_USAGE;
            goto done;
        }
        if (!dirt_session_set_opts(session, &so, NULL) ||
            !dirt_session_set_time(session, t, &eval) ||
            (debug && !dirt_session_set_time(debug, t, &eval)))
            goto done;
        double f0 = dirt_clock_ms();
        progress prog = {{.prog = PROG, .start = f0, .last = f0, .frame = fi, .quiet = o.quiet},
                         &claim};
        if (!dirt_session_add_samples(session, o.spp, on_sample, &prog))
            goto done;
        if (o.debug_ads && !write_debug_ads(&o, debug ? debug : session)) {
            rc = DIRT_EXIT_USAGE;
            goto done;
        }
        const dirt_image *img = dirt_session_image(session);
        dirt_image_error err = {0};
        if (!img || (o.mse_ref && !compare_reference(&o, fi, img, &err)))
            goto done;
        dirt_session_stats *fs = &fstats[rendered++];
        *fs = *dirt_session_get_stats(session);
        dirt_image_write_options wo = {.png = {.exposure = (float)o.exposure,
                                               .tonemap = (enum dirt_tonemap)o.tonemap}};
        if (!cli_write_image(PROG, img, files[0], &wo, o.png_preview, o.quiet)) {
            rc = DIRT_EXIT_USAGE; /* unwritable output */
            goto done;
        }
        seq_claim_release(&claim, files[0], true);
        for (int k = 0; !sequence && k < nfiles; k++)
            memcpy(written[num_written++], files[k], sizeof(files[k]));
        if (!o.quiet && o.s.engine != DIRT_ENGINE_RASTER)
            fprintf(stderr, "%s: frame %ld: build %.1f ms, trace %.1f ms, fetch %.1f ms, shade "
                    "%.1f ms, %llu rays (%.2f Mrays/s)%s\n", PROG, fi, fs->build_ms, fs->trace_ms,
                    fs->fetch_ms, fs->shade_ms, (unsigned long long)fs->rays, fs->mrays_per_s,
                    fs->aborted ? ", SOME RAYS ABORTED" : "");
        if (o.mse_ref && !o.quiet)
            fprintf(stderr, "%s: frame %ld: MSE %.6g, relative MSE %.6g against the reference\n",
                    PROG, fi, err.mse, err.rel_mse);
        if (log) {
            cJSON *rec = dirt_session_stats_json(fs);
            const dirt_camera *cam = dirt_session_camera(session);
            cJSON_AddNumberToObject(rec, "frame", (double)fi);
            cJSON_AddNumberToObject(rec, "seed", seed);
            cJSON_AddStringToObject(rec, "file", files[0]);
            cJSON *c = cJSON_AddObjectToObject(rec, "camera");
            cJSON_AddItemToObject(c, "eye", cJSON_CreateFloatArray(cam->eye, 3));
            cJSON_AddItemToObject(c, "forward", cJSON_CreateFloatArray(cam->forward, 3));
            cJSON_AddNumberToObject(c, "yfov", cam->yfov);
            if (o.mse_ref) {
                cJSON_AddNumberToObject(rec, "mse", err.mse);
                cJSON_AddNumberToObject(rec, "rel_mse", err.rel_mse);
            }
            bool ok = log_line(log, rec);
            cJSON_Delete(rec);
            if (!ok) {
                cli_error(PROG, "cannot append to '%s'", o.log_path);
                rc = DIRT_EXIT_USAGE;
                goto done;
            }
        }
        if (!o.quiet && total > 1) {
            double el = (dirt_clock_ms() - t0) / 1000.0;
            size_t left = total - i - 1;
            fprintf(stderr, "%s: frame %ld done (%zu of %zu; %zu rendered, %zu skipped), "
                    "elapsed %.1fs, ETA %.1fs\n", PROG, fi, i + 1, total, rendered, skipped, el,
                    el / rendered * (double)left);
        }
    }
    rc = DIRT_EXIT_USAGE; /* from here on, only writes can fail */
    if (log) {
        cJSON *sum = cJSON_CreateObject();
        cJSON *in = cJSON_AddObjectToObject(sum, "summary");
        cJSON_AddNumberToObject(in, "frames", (double)total);
        cJSON_AddNumberToObject(in, "rendered", (double)rendered);
        cJSON_AddNumberToObject(in, "skipped", (double)skipped);
        cJSON_AddNumberToObject(in, "wall_ms", dirt_clock_ms() - t0);
        bool ok = log_line(log, sum);
        cJSON_Delete(sum);
        if (!ok) {
            cli_error(PROG, "cannot append to '%s'", o.log_path);
            goto done;
        }
    }
    if (!o.quiet && skipped)
        fprintf(stderr, "%s: %zu frame(s) rendered, %zu skipped (complete or claimed)\n", PROG,
                rendered, skipped);
    if (o.graph_dot && rendered) {
        if (!dirt_session_write_graph_dot(session, o.graph_dot)) {
            cli_error(PROG, "could not write '%s'", o.graph_dot);
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.graph_dot);
    }
    if (o.stats_path && rendered) {
        if (!dirt_session_write_stats(o.stats_path, fstats, rendered)) {
            cli_error(PROG, "could not write '%s'", o.stats_path);
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.stats_path);
    }
    rc = DIRT_EXIT_OK;
done:
    /* A one-frame run is all or nothing (a sequence keeps its complete
     * frames: they are what --skip-existing resumes from). */
    for (int k = 0; rc != DIRT_EXIT_OK && k < num_written; k++)
        unlink(written[k]);
    if (claim.held)
        seq_claim_release(&claim, "", false);
    if (log)
        fclose(log);
    free(fstats);
    seq_frames_free(&o.frames);
    dirt_session_destroy(debug);
    dirt_session_destroy(session);
    dirt_gpu_destroy(gpu);
    dirt_env_destroy(env);
    dirt_scene_destroy(scene);
    return rc;
}
