/* dirt-render: renders one frame or a frame range of a glTF scene headless,
 * on the render session (dirt/session.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "dirt/clock.h"
#include "dirt/log.h"
#include "dirt/session.h"

#define PROG "dirt-render"

typedef struct options {
    dirt_session_opts s;
    const char *scene_path;   /* NULL = embedded default scene */
    const char *output, *stats_path, *graph_dot, *debug_ads;
    double time, fps, exposure;
    int camera;               /* -1 default, -2 automatic, else scene camera */
    int clip;
    bool loop, png_preview, quiet, info, frames_set;
    bool cpu_timing;          /* dirt_gpu_opts.cpu_timing */
    long frame_first, frame_last;
    int spp;
} options;

static void usage(FILE *out)
{
    fprintf(out,
"Usage: " PROG " [SCENE] -o OUTPUT [options]\n"
"       " PROG " --info [SCENE]\n"
"\n"
"Renders a glTF 2.0 scene (.gltf or .glb) headless through OpenGL 4.5 (EGL).\n"
"Without SCENE, renders the embedded default scene (a Cornell-style room).\n"
"\n"
"Output:\n"
"  -o, --output PATH     image to write: .exr (float RGBA) or .png (8-bit sRGB).\n"
"                        With --frames, PATH holds one printf integer pattern\n"
"                        such as out/frame_%%04d.exr.\n"
"  -W, --width N         image width in pixels (default 640)\n"
"  -H, --height N        image height (default: width / the camera's aspect,\n"
"                        4:3 for the automatic camera)\n"
"      --png             with an .exr output, also write a .png preview beside it\n"
"      --exposure STOPS  exposure of PNG output (default 0)\n"
"      --info            print the scene's cameras, clips, lights, emitters and\n"
"                        counts, and exit\n"
"\n"
"Scene and camera:\n"
"  -t, --time T          animation time in seconds (default 0)\n"
"      --frames A:B      render frames A..B (inclusive) at time frame/fps\n"
"      --fps F           frames per second for --frames (default 24)\n"
"      --clip I          animation clip index (default 0; -1 = rest pose)\n"
"      --loop            wrap time into the clip instead of clamping\n"
"      --camera I        use the scene's camera I (default: camera 0, or an\n"
"                        automatic camera framing the scene when it has none)\n"
"      --auto-camera     ignore the scene's cameras: frame the whole animation\n"
"                        clip (the same camera at every frame)\n"
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
"      --background R,G,B  radiance of rays that leave the scene (default 0,0,0)\n"
"      --stats FILE.json write timings (per pass, with the clock that measured\n"
"                        them), ray counts and bytes per buffer as JSON\n"
"      --threads N       embree: CPU threads (default: all)\n"
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
"  -B, --buckets B       depth buckets per tile, >= 1 (default 16 for dirt, 4 for\n"
"                        mmrt, the MMRT paper's setting)\n"
"      --face-size N     cube face size in pixels (default max(W,H)/2)\n"
"      --no-conservative-raster  emulate conservative rasterization even when\n"
"                        GL_NV_conservative_raster is present\n"
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
static const char *const marches[] = {"hiz", "linear", NULL};

static bool parse_frames(const char *text, options *o)
{
    const char *colon = strchr(text, ':');
    if (!colon) {
        cli_error(PROG, "--frames expects A:B, got '%s'", text);
        return false;
    }
    char first[32];
    snprintf(first, sizeof(first), "%.*s", (int)(colon - text), text);
    if (!cli_int(PROG, "--frames (first)", first, 0, 10000000, &o->frame_first) ||
        !cli_int(PROG, "--frames (last)", colon + 1, 0, 10000000, &o->frame_last))
        return false;
    if (o->frame_last < o->frame_first) {
        cli_error(PROG, "--frames %s: last frame before first", text);
        return false;
    }
    o->frames_set = true;
    return true;
}

/* The checks across options; false after printing why. */
static bool check_options(const options *o)
{
    const dirt_session_opts *s = &o->s;
    bool many = o->frames_set && o->frame_last > o->frame_first;
    char why[256];
    if (o->info)
        return true;
    if (!o->output) {
        cli_error(PROG, "no output given: use -o OUT.exr or -o OUT.png (see --help)");
    } else if (!cli_has_ext(o->output, ".exr") && !cli_has_ext(o->output, ".png")) {
        cli_error(PROG, "output '%s' must end in .exr or .png", o->output);
    } else if (many && !cli_frame_pattern_ok(o->output)) {
        cli_error(PROG, "--frames renders several images: the output '%s' needs one "
                  "integer pattern such as frame_%%04d.exr", o->output);
    } else if (!many && strchr(o->output, '%') && !cli_frame_pattern_ok(o->output)) {
        cli_error(PROG, "output '%s' has a stray '%%'", o->output);
    } else if (!dirt_session_check_opts(s, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
    } else if (o->debug_ads && many) {
        cli_error(PROG, "--debug-ads works on a single frame, not with --frames");
    } else if (o->png_preview && !cli_has_ext(o->output, ".exr")) {
        cli_error(PROG, "--png needs an .exr output (the output is already a PNG)");
    } else if (o->graph_dot && s->engine != DIRT_ENGINE_DIRT && s->engine != DIRT_ENGINE_MMRT) {
        cli_error(PROG, "--graph-dot needs a path-tracing engine (dirt or mmrt)");
    } else {
        return true;
    }
    return false;
}

/* Returns DIRT_EXIT_OK, or DIRT_EXIT_USAGE after printing why; -1 for --help. */
static int parse_args(int argc, char **argv, options *o)
{
    *o = (options){.s = {.width = 640}, .fps = 24, .camera = -1, .spp = 16};
    long hiz_top = -1;
    const char *engines[DIRT_NUM_ENGINES + 1] = {0};
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        engines[e] = dirt_engine_names[e];
    /* Options with a value (argv[i + 1]), by kind: s string, i int, l long,
     * u uint32, d double, f float, c choice of `names`, F frames, b colour,
     * j .json path, g .dot path. */
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
        {NULL, "--engine", NULL, 'c', &o->s.engine, 0, 0, engines},
        {NULL, "--mode", NULL, 'c', &o->s.mode, 0, 0, modes},
        {NULL, "--views", NULL, 'c', &o->s.views, 0, 0, views},
        {NULL, "--fetch", NULL, 'c', &o->s.fetch, 0, 0, fetches},
        {NULL, "--march", NULL, 'c', &o->s.march, 0, 0, marches},
        {NULL, "--frames", NULL, 'F', o, 0, 0, NULL},
        {NULL, "--background", NULL, 'b', o->s.background, 0, 0, NULL},
        {NULL, "--stats", NULL, 'j', &o->stats_path, 0, 0, NULL},
        {NULL, "--graph-dot", NULL, 'g', &o->graph_dot, 0, 0, NULL},
    };
    const struct { const char *s, *l; bool *dst; } flags[] = {
        {NULL, "--loop", &o->loop}, {NULL, "--png", &o->png_preview},
        {NULL, "--info", &o->info}, {NULL, "--direct-visibility", &o->s.direct_visibility},
        {NULL, "--no-conservative-raster", &o->s.force_emulation},
        {NULL, "--cpu-timing", &o->cpu_timing}, {"-q", "--quiet", &o->quiet},
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
    return check_options(o) ? DIRT_EXIT_OK : DIRT_EXIT_USAGE;
}

/* Checks every output location before any expensive work. */
static bool outputs_ok(const options *o)
{
    char path[4200];
    cli_frame_path(o->output, o->frames_set ? o->frame_first : 0, path, sizeof(path));
    if (!cli_output_dir_ok(PROG, path) ||
        (o->stats_path && !cli_output_dir_ok(PROG, o->stats_path)) ||
        (o->graph_dot && !cli_output_dir_ok(PROG, o->graph_dot)))
        return false;
    snprintf(path, sizeof(path), "%s/ads.png", o->debug_ads ? o->debug_ads : ".");
    return !o->debug_ads || cli_output_dir_ok(PROG, path);
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

int main(int argc, char **argv)
{
    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc < 0) {
        usage(stdout);
        return DIRT_EXIT_OK;
    }
    if (rc != DIRT_EXIT_OK)
        return rc;
    dirt_scene *scene = NULL;
    dirt_gpu *gpu = NULL;
    dirt_session *session = NULL, *debug = NULL;
    dirt_session_stats *fstats = NULL;
    rc = DIRT_EXIT_USAGE;
    if (!o.info && !outputs_ok(&o))
        goto done;
    scene = o.scene_path ? dirt_scene_load(o.scene_path, NULL) : dirt_scene_create_default();
    if (!scene) {
        cli_error(PROG, "cannot load scene '%s' (see the error above)",
                  o.scene_path ? o.scene_path : "default");
        goto done;
    }
    if (o.info) {
        rc = dirt_scene_print_info(scene, stdout) ? DIRT_EXIT_OK : DIRT_EXIT_FAILURE;
        goto done;
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
        gpu = dirt_gpu_create(&(dirt_gpu_opts){.cpu_timing = o.cpu_timing});
        if (!gpu) {
            cli_error(PROG, "no OpenGL 4.5 context could be made (see the error above)");
            goto done;
        }
    }
    rc = DIRT_EXIT_FAILURE;
    dirt_session_opts dbg_opts = o.s;
    dbg_opts.engine = DIRT_ENGINE_DIRT;
    enum dirt_camera_choice choice = o.camera >= 0    ? DIRT_CAMERA_SCENE
                                     : o.camera == -2 ? DIRT_CAMERA_AUTO
                                                      : DIRT_CAMERA_DEFAULT;
    dirt_eval_opts eval = {.clip = o.clip, .loop = o.loop};
    session = dirt_session_create(gpu, scene, &o.s);
    if (!session || !dirt_session_set_camera(session, choice, o.camera, NULL))
        goto done;
    debug = o.debug_ads && o.s.engine != DIRT_ENGINE_DIRT
                ? dirt_session_create(gpu, scene, &dbg_opts) : NULL;
    if (o.debug_ads && o.s.engine != DIRT_ENGINE_DIRT &&
        (!debug || !dirt_session_set_camera(debug, choice, o.camera, NULL)))
        goto done;
    long first = o.frames_set ? o.frame_first : 0, last = o.frames_set ? o.frame_last : 0;
    fstats = calloc((size_t)(last - first + 1), sizeof(*fstats));
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
    double t0 = dirt_clock_ms();
    for (long fi = first; fi <= last; fi++) {
        double t = o.frames_set ? fi / o.fps : o.time;
        if (!dirt_session_set_time(session, t, &eval) ||
            (debug && !dirt_session_set_time(debug, t, &eval)))
            goto done;
        double f0 = dirt_clock_ms();
        cli_progress prog = {.prog = PROG, .start = f0, .last = f0, .frame = fi, .quiet = o.quiet};
        if (!dirt_session_add_samples(session, o.spp, cli_progress_sample, &prog))
            goto done;
        if (o.debug_ads && !write_debug_ads(&o, debug ? debug : session)) {
            rc = DIRT_EXIT_USAGE;
            goto done;
        }
        const dirt_image *img = dirt_session_image(session);
        if (!img)
            goto done;
        dirt_session_stats *fs = &fstats[fi - first];
        *fs = *dirt_session_get_stats(session);
        char path[4200];
        cli_frame_path(o.output, fi, path, sizeof(path));
        if (!cli_write_image(PROG, img, path, o.exposure, o.png_preview, o.quiet)) {
            rc = DIRT_EXIT_USAGE; /* unwritable output */
            goto done;
        }
        if (!o.quiet && o.s.engine != DIRT_ENGINE_RASTER)
            fprintf(stderr, "%s: frame %ld: build %.1f ms, trace %.1f ms, fetch %.1f ms, shade "
                    "%.1f ms, %llu rays (%.2f Mrays/s)%s\n", PROG, fi, fs->build_ms, fs->trace_ms,
                    fs->fetch_ms, fs->shade_ms, (unsigned long long)fs->rays, fs->mrays_per_s,
                    fs->aborted ? ", SOME RAYS ABORTED" : "");
        if (!o.quiet && last > first) {
            double el = (dirt_clock_ms() - t0) / 1000.0;
            long n = fi - first + 1, total = last - first + 1;
            fprintf(stderr, "%s: frame %ld/%ld (t=%.3fs) elapsed %.1fs, ETA %.1fs\n", PROG, n,
                    total, t, el, el / n * (total - n));
        }
    }
    rc = DIRT_EXIT_USAGE; /* from here on, only writes can fail */
    if (o.graph_dot) {
        if (!dirt_session_write_graph_dot(session, o.graph_dot)) {
            cli_error(PROG, "could not write '%s'", o.graph_dot);
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.graph_dot);
    }
    if (o.stats_path) {
        if (!dirt_session_write_stats(o.stats_path, fstats, (size_t)(last - first + 1))) {
            cli_error(PROG, "could not write '%s'", o.stats_path);
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.stats_path);
    }
    rc = DIRT_EXIT_OK;
done:
    free(fstats);
    dirt_session_destroy(debug);
    dirt_session_destroy(session);
    dirt_gpu_destroy(gpu);
    dirt_scene_destroy(scene);
    return rc;
}
