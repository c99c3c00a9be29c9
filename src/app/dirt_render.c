/* dirt-render: renders one frame or a frame range of a glTF scene headless. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "dirt/ads.h"
#include "dirt/file.h"
#include "dirt/pathtrace.h"
#include "dirt/ref.h"
#include "dirt/clock.h"
#include "dirt/gpu.h"
#include "dirt/image.h"
#include "dirt/log.h"
#include "dirt/mmrt.h"
#include "dirt/raster.h"
#include "dirt/scene.h"

#define PROG "dirt-render"

enum engine { ENGINE_DIRT, ENGINE_RASTER, ENGINE_EMBREE, ENGINE_MMRT };

typedef struct options {
    const char *scene_path;   /* NULL = embedded default scene */
    const char *output;
    long width, height;
    bool width_set, height_set;
    double time;
    long camera;              /* -1 = scene camera 0, or automatic without cameras */
    long clip;
    bool loop;
    long frame_first, frame_last;
    bool frames_set;
    double fps;
    enum engine engine;
    bool png_preview;
    double exposure;
    bool quiet;
    bool cpu_timing;
    /* DIRT structure */
    const char *debug_ads;    /* directory for pictures, or NULL */
    enum dirt_view_mode views;
    long tile_size, buckets, face_size;
    bool buckets_set;
    bool force_emulation;
    /* path tracing */
    long spp, bounces, hiz_levels;
    unsigned long seed;
    bool ao;
    double ao_distance;
    float background[3];
    enum dirt_fetch_mode fetch;
    const char *stats_path;
    long threads;
    double aperture, focus;
    bool direct_visibility;
    const char *graph_dot;    /* --graph-dot FILE, or NULL */
    /* MMRT */
    double thickness;         /* 0 = MMRT's default */
    enum dirt_mmrt_march march;
    long march_samples;       /* 0 = MMRT's default */
} options;

static void usage(FILE *out)
{
    fprintf(out,
"Usage: " PROG " [SCENE] -o OUTPUT [options]\n"
"\n"
"Renders a glTF 2.0 scene (.gltf or .glb) headless through OpenGL 4.5 (EGL).\n"
"Without SCENE, renders the embedded default scene (a Cornell-style room).\n"
"\n"
"Output:\n"
"  -o, --output PATH     image to write: .exr (float RGBA) or .png (8-bit sRGB).\n"
"                        With --frames, PATH holds one printf integer pattern\n"
"                        such as out/frame_%%04d.exr.\n"
"  -W, --width N         image width in pixels (default 640)\n"
"  -H, --height N        image height (default: width / camera aspect, or 480)\n"
"      --png             with an .exr output, also write a .png preview beside it\n"
"      --exposure STOPS  exposure of PNG output (default 0)\n"
"\n"
"Scene and camera:\n"
"  -t, --time T          animation time in seconds (default 0)\n"
"      --frames A:B      render frames A..B (inclusive) at time frame/fps\n"
"      --fps F           frames per second for --frames (default 24)\n"
"      --clip I          animation clip index (default 0; -1 = rest pose)\n"
"      --loop            wrap time into the clip instead of clamping\n"
"      --camera I        use the scene's camera I (default: camera 0, or an\n"
"                        automatic camera framing the scene when it has none)\n"
"      --auto-camera     ignore the scene's cameras; frame the scene bounds\n"
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
"      --stats FILE.json write timings, ray counts and memory as JSON (dirt and\n"
"                        mmrt: also bytes per buffer; mmrt: also fragments)\n"
"      --threads N       embree: CPU threads (default: all)\n"
"      --cpu-timing      time passes with glFinish and the CPU clock too (always\n"
"                        on with a software renderer such as llvmpipe)\n"
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

/* Checks that `pattern` has exactly one integer conversion (%d, %04d, ...)
 * and no other '%' except "%%". */
static bool valid_frame_pattern(const char *pattern)
{
    int conversions = 0;
    for (const char *p = pattern; *p; p++) {
        if (*p != '%')
            continue;
        if (p[1] == '%') {
            p++;
            continue;
        }
        p++;
        if (*p == '0')
            p++;
        while (*p >= '0' && *p <= '9')
            p++;
        if (*p != 'd')
            return false;
        conversions++;
    }
    return conversions == 1;
}

static bool parse_frames(const char *text, options *o)
{
    const char *colon = text ? strchr(text, ':') : NULL;
    if (!colon) {
        cli_error(PROG, "--frames expects A:B, got '%s'", text ? text : "");
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

/* Returns DIRT_EXIT_OK, or DIRT_EXIT_USAGE after printing why; -1 for --help. */
static int parse_args(int argc, char **argv, options *o)
{
    *o = (options){.width = 640, .height = 480, .camera = -1, .fps = 24, .tile_size = 2,
                   .buckets = 16, .spp = 16, .bounces = 4, .views = DIRT_VIEWS_CUBE_CAMERA};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED_VALUE()                                                   \
    do {                                                               \
        if (!val) {                                                    \
            cli_error(PROG, "option %s needs a value", a);             \
            return DIRT_EXIT_USAGE;                                    \
        }                                                              \
        i++;                                                           \
    } while (0)
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            return -1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            NEED_VALUE();
            o->output = val;
        } else if (!strcmp(a, "-W") || !strcmp(a, "--width")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 16384, &o->width))
                return DIRT_EXIT_USAGE;
            o->width_set = true;
        } else if (!strcmp(a, "-H") || !strcmp(a, "--height")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 16384, &o->height))
                return DIRT_EXIT_USAGE;
            o->height_set = true;
        } else if (!strcmp(a, "-t") || !strcmp(a, "--time")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, -1e6, 1e6, &o->time))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--frames")) {
            NEED_VALUE();
            if (!parse_frames(val, o))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--fps")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, 1e-3, 1e4, &o->fps))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--clip")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, -1, 1000000, &o->clip))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--loop")) {
            o->loop = true;
        } else if (!strcmp(a, "--camera")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 0, 1000000, &o->camera))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--auto-camera")) {
            o->camera = -2;
        } else if (!strcmp(a, "--engine")) {
            NEED_VALUE();
            if (!strcmp(val, "raster")) {
                o->engine = ENGINE_RASTER;
            } else if (!strcmp(val, "dirt")) {
                o->engine = ENGINE_DIRT;
            } else if (!strcmp(val, "embree")) {
                o->engine = ENGINE_EMBREE;
            } else if (!strcmp(val, "mmrt")) {
                o->engine = ENGINE_MMRT;
            } else {
                cli_error(PROG, "unknown engine '%s' (available: dirt, mmrt, embree, raster)",
                          val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--mode")) {
            NEED_VALUE();
            if (strcmp(val, "pt") && strcmp(val, "ao")) {
                cli_error(PROG, "--mode expects pt or ao, got '%s'", val);
                return DIRT_EXIT_USAGE;
            }
            o->ao = !strcmp(val, "ao");
        } else if (!strcmp(a, "--spp")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 1 << 20, &o->spp))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--bounces")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 64, &o->bounces))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--seed")) {
            NEED_VALUE();
            long v;
            if (!cli_int(PROG, a, val, 0, 4294967295L, &v))
                return DIRT_EXIT_USAGE;
            o->seed = (unsigned long)v;
        } else if (!strcmp(a, "--ao-distance")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, 0, 1e30, &o->ao_distance))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--background")) {
            NEED_VALUE();
            char extra;
            if (sscanf(val, "%f,%f,%f%c", &o->background[0], &o->background[1],
                       &o->background[2], &extra) != 3 || !(o->background[0] >= 0) ||
                !(o->background[1] >= 0) || !(o->background[2] >= 0) ||
                o->background[0] > 1e30f || o->background[1] > 1e30f || o->background[2] > 1e30f) {
                cli_error(PROG, "--background expects R,G,B (non-negative), got '%s'", val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--stats")) {
            NEED_VALUE();
            if (!cli_has_ext(val, ".json")) {
                cli_error(PROG, "--stats file '%s' must end in .json", val);
                return DIRT_EXIT_USAGE;
            }
            o->stats_path = val;
        } else if (!strcmp(a, "--threads")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 4096, &o->threads))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--hiz-top")) {
            NEED_VALUE();
            long top;
            if (!cli_int(PROG, a, val, 0, 15, &top))
                return DIRT_EXIT_USAGE;
            o->hiz_levels = top + 1;
        } else if (!strcmp(a, "--aperture")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, 0, 1e6, &o->aperture))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--focus")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, 1e-6, 1e9, &o->focus))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--fetch")) {
            NEED_VALUE();
            if (!strcmp(val, "compute")) {
                o->fetch = DIRT_FETCH_COMPUTE;
            } else if (!strcmp(val, "raster")) {
                o->fetch = DIRT_FETCH_RASTER;
            } else {
                cli_error(PROG, "--fetch expects compute or raster, got '%s'", val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--png")) {
            o->png_preview = true;
        } else if (!strcmp(a, "--exposure")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, -64, 64, &o->exposure))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--debug-ads")) {
            NEED_VALUE();
            o->debug_ads = val;
        } else if (!strcmp(a, "--views")) {
            NEED_VALUE();
            if (!strcmp(val, "single")) {
                o->views = DIRT_VIEWS_SINGLE;
            } else if (!strcmp(val, "cube")) {
                o->views = DIRT_VIEWS_CUBE;
            } else if (!strcmp(val, "cube+camera")) {
                o->views = DIRT_VIEWS_CUBE_CAMERA;
            } else {
                cli_error(PROG, "--views expects single, cube or cube+camera, got '%s'", val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "-S") || !strcmp(a, "--tile-size") || !strcmp(a, "--tile")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 8, &o->tile_size))
                return DIRT_EXIT_USAGE;
            if (o->tile_size != 1 && o->tile_size != 2 && o->tile_size != 4 && o->tile_size != 8) {
                cli_error(PROG, "%s expects 1, 2, 4 or 8, got '%s'", a, val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "-B") || !strcmp(a, "--buckets")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 1024, &o->buckets))
                return DIRT_EXIT_USAGE;
            o->buckets_set = true;
        } else if (!strcmp(a, "--march")) {
            NEED_VALUE();
            if (!strcmp(val, "hiz")) {
                o->march = DIRT_MMRT_MARCH_HIZ;
            } else if (!strcmp(val, "linear")) {
                o->march = DIRT_MMRT_MARCH_LINEAR;
            } else {
                cli_error(PROG, "--march expects hiz or linear, got '%s'", val);
                return DIRT_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--samples")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 65536, &o->march_samples))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--thickness")) {
            NEED_VALUE();
            if (!cli_float(PROG, a, val, 1e-12, 1e12, &o->thickness))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--face-size")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 16384, &o->face_size))
                return DIRT_EXIT_USAGE;
        } else if (!strcmp(a, "--graph-dot")) {
            NEED_VALUE();
            if (!cli_has_ext(val, ".dot")) {
                cli_error(PROG, "--graph-dot file '%s' must end in .dot", val);
                return DIRT_EXIT_USAGE;
            }
            o->graph_dot = val;
        } else if (!strcmp(a, "--direct-visibility")) {
            o->direct_visibility = true;
        } else if (!strcmp(a, "--no-conservative-raster")) {
            o->force_emulation = true;
        } else if (!strcmp(a, "--cpu-timing")) {
            o->cpu_timing = true;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            o->quiet = true;
            dirt_log_set_level(DIRT_LOG_ERROR);
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
#undef NEED_VALUE
    }
    if (!o->output) {
        cli_error(PROG, "no output given: use -o OUT.exr or -o OUT.png (see --help)");
        return DIRT_EXIT_USAGE;
    }
    if (!cli_has_ext(o->output, ".exr") && !cli_has_ext(o->output, ".png")) {
        cli_error(PROG, "output '%s' must end in .exr or .png", o->output);
        return DIRT_EXIT_USAGE;
    }
    bool many = o->frames_set && o->frame_last > o->frame_first;
    if (many && !valid_frame_pattern(o->output)) {
        cli_error(PROG, "--frames renders several images: the output '%s' needs one "
                  "integer pattern such as frame_%%04d.exr", o->output);
        return DIRT_EXIT_USAGE;
    }
    if (!many && strchr(o->output, '%') && !valid_frame_pattern(o->output)) {
        cli_error(PROG, "output '%s' has a stray '%%'", o->output);
        return DIRT_EXIT_USAGE;
    }
    if (o->engine == ENGINE_MMRT && (o->fetch == DIRT_FETCH_RASTER || o->direct_visibility)) {
        cli_error(PROG, "--engine mmrt has no Fetch pass and no visibility buffer: "
                  "--fetch raster and --direct-visibility are DIRT's");
        return DIRT_EXIT_USAGE;
    }
    if (o->debug_ads && many) {
        cli_error(PROG, "--debug-ads works on a single frame, not with --frames");
        return DIRT_EXIT_USAGE;
    }
    if (o->direct_visibility && o->engine == ENGINE_DIRT && o->views == DIRT_VIEWS_CUBE) {
        cli_error(PROG, "--direct-visibility needs a camera view: --views single or cube+camera");
        return DIRT_EXIT_USAGE;
    }
    if (o->png_preview && !cli_has_ext(o->output, ".exr")) {
        cli_error(PROG, "--png needs an .exr output (the output is already a PNG)");
        return DIRT_EXIT_USAGE;
    }
    return DIRT_EXIT_OK;
}

static void output_path(const options *o, long frame, char *buf, size_t size)
{
    if (strchr(o->output, '%'))
        snprintf(buf, size, o->output, (int)frame);
    else
        snprintf(buf, size, "%s", o->output);
}

static bool write_outputs(const options *o, const dirt_image *img, const char *path)
{
    dirt_image_write_options wo = {.png = {.exposure = (float)o->exposure}};
    if (!dirt_image_write(img, path, &wo)) {
        cli_error(PROG, "could not write '%s'", path);
        return false;
    }
    if (!o->quiet)
        printf("wrote %s\n", path);
    if (o->png_preview) {
        char png[4200];
        snprintf(png, sizeof(png), "%.*s.png", (int)(strlen(path) - 4), path);
        if (!dirt_image_write_png(img, png, &wo.png)) {
            cli_error(PROG, "could not write '%s'", png);
            return false;
        }
        if (!o->quiet)
            printf("wrote %s\n", png);
    }
    return true;
}

/* Statistics of one frame, for --stats and the summary line. */
typedef struct frame_stats {
    double build_ms, trace_ms, fetch_ms, shade_ms, total_ms, mrays_per_s;
    uint64_t rays, aborted, bytes_total;
    dirt_ads_stats ads;
    bool has_ads;
    dirt_mmrt_stats mmrt;
    bool has_mmrt;
} frame_stats;

typedef struct progress_state {
    double start, last;
    long frame;
    bool quiet;
} progress_state;

static void on_progress(void *user, int done, int total)
{
    progress_state *p = user;
    double now = dirt_clock_ms();
    if (p->quiet || (now - p->last < 1000.0 && done < total))
        return;
    p->last = now;
    double el = (now - p->start) / 1000.0;
    fprintf(stderr, "%s: frame %ld: sample %d/%d, %.1fs elapsed, ETA %.1fs\n", PROG, p->frame,
            done, total, el, done ? el / done * (total - done) : 0.0);
}

static void on_ref_progress(void *user, uint64_t done, uint64_t total)
{
    on_progress(user, (int)done, (int)total);
}

static void json_stats(FILE *f, const frame_stats *s, const char *indent)
{
    fprintf(f, "%s\"build_ms\": %.6f,\n%s\"trace_ms\": %.6f,\n%s\"fetch_ms\": %.6f,\n"
               "%s\"shade_ms\": %.6f,\n%s\"total_ms\": %.6f,\n%s\"rays\": %llu,\n"
               "%s\"mrays_per_s\": %.6f,\n%s\"aborted_rays\": %llu,\n%s\"bytes_total\": %llu",
            indent, s->build_ms, indent, s->trace_ms, indent, s->fetch_ms, indent, s->shade_ms,
            indent, s->total_ms, indent, (unsigned long long)s->rays, indent, s->mrays_per_s,
            indent, (unsigned long long)s->aborted, indent, (unsigned long long)s->bytes_total);
    if (s->has_ads && !s->has_mmrt) {
        const dirt_ads_stats *a = &s->ads;
        fprintf(f, ",\n%s\"bytes\": {\"vertices\": %llu, \"depth bounds\": %llu, "
                   "\"list heads\": %llu, \"id nodes\": %llu, \"id nodes allocated\": %llu},\n"
                   "%s\"samples_np\": %llu,\n%s\"buckets_per_sample\": %.6f",
                indent, (unsigned long long)a->bytes_vertices, (unsigned long long)a->bytes_depth,
                (unsigned long long)a->bytes_heads, (unsigned long long)a->bytes_nodes_used,
                (unsigned long long)a->bytes_nodes_allocated, indent,
                (unsigned long long)a->samples, indent, a->buckets_per_sample);
    } else if (s->has_mmrt) {
        /* The same keys as DIRT's where they mean the same; "list heads"
         * holds heads and tails. */
        const dirt_mmrt_stats *m = &s->mmrt;
        fprintf(f, ",\n%s\"bytes\": {\"vertices\": %llu, \"depth bounds\": %llu, "
                   "\"list heads\": %llu, \"id nodes\": %llu, \"id nodes allocated\": %llu, "
                   "\"data nodes\": %llu, \"data nodes allocated\": %llu},\n"
                   "%s\"fragments\": %llu,\n%s\"max_layers\": %u,\n%s\"bytes_paper\": %.0f",
                indent, (unsigned long long)m->bytes_vertices, (unsigned long long)m->bytes_depth,
                (unsigned long long)m->bytes_heads, (unsigned long long)m->bytes_id_nodes_used,
                (unsigned long long)m->bytes_id_nodes_allocated,
                (unsigned long long)m->bytes_data_nodes_used,
                (unsigned long long)m->bytes_data_nodes_allocated, indent,
                (unsigned long long)m->fragments, indent, m->max_layers, indent, m->bytes_paper);
    }
}

static bool write_stats(const options *o, const char *engine, const frame_stats *frames,
                        long count, const char *gpu_desc)
{
    dirt_atomic_file *af = dirt_atomic_open(o->stats_path);
    if (!af)
        return false;
    FILE *f = dirt_atomic_stream(af);
    frame_stats mean = {0};
    for (long i = 0; i < count; i++) {
        mean.build_ms += frames[i].build_ms / count;
        mean.trace_ms += frames[i].trace_ms / count;
        mean.fetch_ms += frames[i].fetch_ms / count;
        mean.shade_ms += frames[i].shade_ms / count;
        mean.total_ms += frames[i].total_ms / count;
        mean.rays += frames[i].rays;
        mean.aborted += frames[i].aborted;
        mean.bytes_total = frames[i].bytes_total > mean.bytes_total ? frames[i].bytes_total
                                                                    : mean.bytes_total;
    }
    mean.rays /= (uint64_t)count;
    mean.mrays_per_s = frames[count - 1].mrays_per_s;
    mean.ads = frames[count - 1].ads;
    mean.has_ads = frames[count - 1].has_ads;
    mean.mmrt = frames[count - 1].mmrt;
    mean.has_mmrt = frames[count - 1].has_mmrt;
    fprintf(f, "{\n  \"engine\": \"%s\",\n  \"device\": \"", engine);
    for (const char *c = gpu_desc; *c; c++)
        fputc(*c == '"' || *c == '\\' ? '\'' : *c, f);
    fprintf(f, "\",\n  \"width\": %ld,\n  \"height\": %ld,\n  \"spp\": %ld,\n  \"bounces\": %ld,\n"
               "  \"mode\": \"%s\",\n  \"frames_rendered\": %ld,\n",
            o->width, o->height, o->spp, o->bounces, o->ao ? "ao" : "pt", count);
    json_stats(f, &mean, "  ");
    fprintf(f, ",\n  \"frames\": [\n");
    for (long i = 0; i < count; i++) {
        fprintf(f, "    {\n");
        json_stats(f, &frames[i], "      ");
        fprintf(f, "\n    }%s\n", i + 1 < count ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    return dirt_atomic_commit(af);
}

static const char *engine_name(enum engine e)
{
    return e == ENGINE_DIRT     ? "dirt"
           : e == ENGINE_MMRT   ? "mmrt"
           : e == ENGINE_EMBREE ? "embree"
                                : "raster";
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
    dirt_frame *frame = NULL;
    dirt_gpu *gpu = NULL;
    dirt_raster *raster = NULL;
    dirt_ads *ads = NULL;
    dirt_mmrt *mmrt = NULL;
    dirt_pt *pt = NULL;
    dirt_image *img = NULL;
    frame_stats *fstats = NULL;
    char desc[512] = "CPU";
    rc = DIRT_EXIT_USAGE;

    /* Check every output location before any expensive work. */
    long first = o.frames_set ? o.frame_first : 0;
    long last = o.frames_set ? o.frame_last : 0;
    char path[4096];
    output_path(&o, first, path, sizeof(path));
    if (!cli_output_dir_ok(PROG, path))
        goto done;
    if (o.stats_path && !cli_output_dir_ok(PROG, o.stats_path))
        goto done;
    if (o.graph_dot && !cli_output_dir_ok(PROG, o.graph_dot))
        goto done;
    if (o.graph_dot && o.engine != ENGINE_DIRT && o.engine != ENGINE_MMRT) {
        cli_error(PROG, "--graph-dot needs a path-tracing engine (dirt or mmrt)");
        goto done;
    }
    if (o.debug_ads) {
        char probe[4200];
        snprintf(probe, sizeof(probe), "%s/ads.png", o.debug_ads);
        if (!cli_output_dir_ok(PROG, probe))
            goto done;
    }

    scene = o.scene_path ? dirt_scene_load(o.scene_path, NULL) : dirt_scene_create_default();
    if (!scene) {
        cli_error(PROG, "cannot load scene '%s' (see the error above)",
                  o.scene_path ? o.scene_path : "default");
        goto done;
    }
    size_t num_cameras = dirt_scene_num_cameras(scene);
    if (o.camera >= 0 && (size_t)o.camera >= num_cameras) {
        cli_error(PROG, "--camera %ld: the scene has %zu camera(s)", o.camera, num_cameras);
        goto done;
    }
    if (o.clip >= 0 && dirt_scene_num_clips(scene) > 0 &&
        (size_t)o.clip >= dirt_scene_num_clips(scene)) {
        cli_error(PROG, "--clip %ld: the scene has %zu animation clip(s)", o.clip,
                  dirt_scene_num_clips(scene));
        goto done;
    }
    int cam_index = o.camera >= 0 ? (int)o.camera : (o.camera == -1 && num_cameras ? 0 : -1);
    if (cam_index >= 0 && !o.height_set) {
        float aspect = dirt_scene_cameras(scene)[cam_index].aspect;
        if (aspect > 0)
            o.height = (long)(o.width / aspect + 0.5f);
        if (o.height < 1)
            o.height = 1;
    }
    fstats = calloc((size_t)(last - first + 1), sizeof(*fstats));
    img = dirt_image_create((int)o.width, (int)o.height);
    if (!fstats || !img)
        goto done;
    if (o.engine != ENGINE_RASTER) {
        static const char *extra[] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z"};
        for (int i = 0; i < 6; i++) {
            if (!dirt_image_add_channel(img, extra[i]))
                goto done;
        }
    }

    bool need_gpu = o.engine != ENGINE_EMBREE || o.debug_ads;
    if (need_gpu) {
        rc = DIRT_EXIT_NO_GPU;
        gpu = dirt_gpu_create(&(dirt_gpu_opts){0});
        if (!gpu) {
            cli_error(PROG, "no OpenGL 4.5 context could be made (see the error above)");
            goto done;
        }
        dirt_gpu_describe(gpu, desc, sizeof(desc));
        /* llvmpipe's timer queries don't time rasterization: clock it. */
        if (dirt_gpu_get_caps(gpu)->software)
            o.cpu_timing = true;
    }
    rc = DIRT_EXIT_FAILURE;
    if (o.engine == ENGINE_RASTER) {
        raster = dirt_raster_create(gpu, scene);
        if (!raster)
            goto done;
    }
    if (o.engine == ENGINE_DIRT || o.debug_ads) {
        dirt_ads_opts ao = {
            .views = {.mode = o.views, .width = (int)o.width, .height = (int)o.height,
                      .face_size = (int)o.face_size, .tile_size = (int)o.tile_size},
            .buckets = (int)o.buckets,
            .force_emulation = o.force_emulation,
            .cpu_timing = o.cpu_timing,
        };
        ads = dirt_ads_create(gpu, &ao);
        if (!ads)
            goto done;
    }
    if (o.engine == ENGINE_MMRT) {
        dirt_mmrt_opts mo = {
            .views = {.mode = o.views, .width = (int)o.width, .height = (int)o.height,
                      .face_size = (int)o.face_size, .tile_size = 1},
            .buckets = o.buckets_set ? (int)o.buckets : 4,
            .cpu_timing = o.cpu_timing,
        };
        mmrt = dirt_mmrt_create(gpu, &mo);
        if (!mmrt)
            goto done;
    }
    if (o.engine == ENGINE_DIRT || o.engine == ENGINE_MMRT) {
        pt = dirt_pt_create(gpu, scene);
        if (!pt)
            goto done;
    }
    if (!o.quiet)
        fprintf(stderr, "%s: %s, %zu triangles, engine %s; %s\n", PROG,
                o.scene_path ? o.scene_path : "default scene", dirt_scene_num_triangles(scene),
                engine_name(o.engine), desc);

    dirt_eval_opts eo = {.clip = (int)o.clip, .loop = o.loop};
    double t0 = dirt_clock_ms();
    for (long fi = first; fi <= last; fi++) {
        frame_stats *fs = &fstats[fi - first];
        float t = o.frames_set ? (float)(fi / o.fps) : (float)o.time;
        if (!frame)
            frame = dirt_scene_evaluate(scene, t, &eo);
        else if (!dirt_scene_evaluate_into(scene, t, &eo, frame))
            goto done;
        if (!frame)
            goto done;
        dirt_camera cam;
        if (cam_index >= 0 && (size_t)cam_index < frame->num_cameras)
            cam = frame->cameras[cam_index];
        else
            dirt_camera_auto(frame, &cam);
        if (o.aperture > 0) {
            cam.aperture_radius = (float)o.aperture;
            float c[3], d = 0;
            for (int k = 0; k < 3; k++) {
                c[k] = 0.5f * (frame->bounds_min[k] + frame->bounds_max[k]) - cam.eye[k];
                d += c[k] * cam.forward[k];
            }
            cam.focus_distance = o.focus > 0 ? (float)o.focus : (d > 0 ? d : 1.0f);
        }
        double f0 = dirt_clock_ms();
        progress_state prog = {.start = f0, .last = f0, .frame = fi, .quiet = o.quiet};
        if (ads) {
            if (!dirt_ads_build(ads, frame, &cam))
                goto done;
            fs->ads = *dirt_ads_get_stats(ads);
            fs->has_ads = true;
            if (o.debug_ads) {
                if (!o.quiet)
                    dirt_ads_print_stats(ads, stderr);
                if (!dirt_ads_write_debug(ads, o.debug_ads, o.quiet)) {
                    rc = DIRT_EXIT_USAGE;
                    goto done;
                }
            }
        }
        if (mmrt) {
            if (!dirt_mmrt_build(mmrt, frame, &cam))
                goto done;
            fs->mmrt = *dirt_mmrt_get_stats(mmrt);
            fs->has_mmrt = true;
        }
        if (o.engine == ENGINE_RASTER) {
            dirt_raster_stats st;
            dirt_raster_opts ro = {.cpu_timing = o.cpu_timing};
            if (!dirt_raster_render(raster, frame, &cam, (int)o.width, (int)o.height, &ro,
                                    img->rgba, &st))
                goto done;
            fs->shade_ms = st.gpu_ms >= 0 ? st.gpu_ms : st.cpu_ms;
        } else if (o.engine == ENGINE_DIRT || o.engine == ENGINE_MMRT) {
            dirt_pt_opts po = {
                .mode = o.ao ? DIRT_PT_AO : DIRT_PT_PATH,
                .spp = (int)o.spp,
                .bounces = (int)o.bounces,
                .seed = (uint32_t)o.seed,
                .background = {o.background[0], o.background[1], o.background[2]},
                .ao_distance = (float)o.ao_distance,
                .fetch = o.fetch,
                .direct_visibility = o.direct_visibility,
                .trace = {.hiz_levels = (int)o.hiz_levels},
                .mmrt = {.march = o.march, .samples = (int)o.march_samples,
                         .hiz_levels = (int)o.hiz_levels, .thickness = (float)o.thickness,
                         .seed = (uint32_t)o.seed},
                .cpu_timing = o.cpu_timing,
                .progress = on_progress,
                .progress_user = &prog,
            };
            dirt_pt_stats st;
            if (o.engine == ENGINE_MMRT ? !dirt_pt_render_mmrt(pt, mmrt, frame, &cam, &po, img, &st)
                                        : !dirt_pt_render(pt, ads, frame, &cam, &po, img, &st))
                goto done;
            fs->build_ms = st.build_ms;
            fs->trace_ms = st.trace_ms;
            fs->fetch_ms = st.fetch_ms;
            fs->shade_ms = st.shade_ms;
            fs->rays = st.rays;
            fs->aborted = st.aborted;
            fs->mrays_per_s = st.mrays_per_s;
            fs->bytes_total = (mmrt ? fs->mmrt.bytes_total_used : fs->ads.bytes_total_used) +
                              st.bytes_integrator;
        } else {
            dirt_ref_opts ro = {
                .width = (int)o.width, .height = (int)o.height, .spp = (int)o.spp,
                .bounces = (int)o.bounces, .mode = o.ao ? DIRT_REF_MODE_AO : DIRT_REF_MODE_PT,
                .ao_distance = (float)o.ao_distance, .seed = (uint32_t)o.seed,
                .background = {o.background[0], o.background[1], o.background[2]},
                .threads = (int)o.threads, .progress = on_ref_progress, .progress_user = &prog,
            };
            dirt_ref_stats st;
            dirt_image *ref = dirt_ref_render(scene, frame, &cam, &ro, &st);
            if (!ref)
                goto done;
            dirt_image_destroy(img);
            img = ref;
            fs->build_ms = st.build_ms;
            fs->trace_ms = st.seconds * 1e3;
            fs->rays = st.rays;
            fs->mrays_per_s = st.mrays_per_s;
        }
        fs->total_ms = dirt_clock_ms() - f0;
        output_path(&o, fi, path, sizeof(path));
        if (!write_outputs(&o, img, path)) {
            rc = DIRT_EXIT_USAGE; /* unwritable output */
            goto done;
        }
        if (!o.quiet && o.engine != ENGINE_RASTER)
            fprintf(stderr, "%s: frame %ld: build %.1f ms, trace %.1f ms, fetch %.1f ms, shade "
                    "%.1f ms, %llu rays (%.2f Mrays/s)%s\n", PROG, fi, fs->build_ms, fs->trace_ms,
                    fs->fetch_ms, fs->shade_ms, (unsigned long long)fs->rays, fs->mrays_per_s,
                    fs->aborted ? ", SOME RAYS ABORTED" : "");
        if (!o.quiet && last > first) {
            double el = (dirt_clock_ms() - t0) / 1000.0;
            long done_n = fi - first + 1, total = last - first + 1;
            fprintf(stderr, "%s: frame %ld/%ld (t=%.3fs) elapsed %.1fs, ETA %.1fs\n", PROG,
                    done_n, total, t, el, el / done_n * (total - done_n));
        }
    }
    if (o.graph_dot) {
        if (!dirt_pt_write_dot(pt, o.graph_dot)) {
            cli_error(PROG, "could not write '%s'", o.graph_dot);
            rc = DIRT_EXIT_USAGE;
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.graph_dot);
    }
    if (o.stats_path) {
        if (!write_stats(&o, engine_name(o.engine), fstats, last - first + 1, desc)) {
            cli_error(PROG, "could not write '%s'", o.stats_path);
            rc = DIRT_EXIT_USAGE;
            goto done;
        }
        if (!o.quiet)
            printf("wrote %s\n", o.stats_path);
    }
    rc = DIRT_EXIT_OK;
done:
    free(fstats);
    dirt_image_destroy(img);
    dirt_pt_destroy(pt);
    dirt_mmrt_destroy(mmrt);
    dirt_raster_destroy(raster);
    dirt_ads_destroy(ads);
    dirt_frame_destroy(frame);
    dirt_gpu_destroy(gpu);
    dirt_scene_destroy(scene);
    return rc;
}
