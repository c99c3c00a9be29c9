/* dirt-render: renders one frame or a frame range of a glTF scene headless. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "dirt/ads.h"
#include "dirt/clock.h"
#include "dirt/gpu.h"
#include "dirt/image.h"
#include "dirt/log.h"
#include "dirt/raster.h"
#include "dirt/scene.h"

#define PROG "dirt-render"

enum engine { ENGINE_RASTER };

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
    bool force_emulation;
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
"\n"
"Technique:\n"
"      --engine NAME     raster: rasterized preview with direct lighting (default)\n"
"      --cpu-timing      time passes with glFinish and the CPU clock too\n"
"\n"
"DIRT acceleration structure:\n"
"      --debug-ads DIR   build the structure for the frame, print its stats and\n"
"                        write heat maps of list lengths and depth bounds per\n"
"                        view into DIR (single frame only)\n"
"      --views MODE      single | cube | cube+camera (default single)\n"
"  -S, --tile-size S     tile size 1, 2, 4 or 8 (default 2)\n"
"  -B, --buckets B       depth buckets per tile, >= 1 (default 16)\n"
"      --face-size N     cube face size in pixels (default max(W,H)/2)\n"
"      --no-conservative-raster  emulate conservative rasterization even when\n"
"                        GL_NV_conservative_raster is present\n"
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
                   .buckets = 16};
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
            } else {
                cli_error(PROG, "unknown engine '%s' (available: raster)", val);
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
        } else if (!strcmp(a, "-S") || !strcmp(a, "--tile-size")) {
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
        } else if (!strcmp(a, "--face-size")) {
            NEED_VALUE();
            if (!cli_int(PROG, a, val, 1, 16384, &o->face_size))
                return DIRT_EXIT_USAGE;
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
    if (o->debug_ads && many) {
        cli_error(PROG, "--debug-ads works on a single frame, not with --frames");
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
    dirt_image *img = NULL;
    rc = DIRT_EXIT_USAGE;

    /* Check every output location before any expensive work. */
    long first = o.frames_set ? o.frame_first : 0;
    long last = o.frames_set ? o.frame_last : 0;
    char path[4096];
    output_path(&o, first, path, sizeof(path));
    if (!cli_output_dir_ok(PROG, path))
        goto done;
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

    rc = DIRT_EXIT_NO_GPU;
    gpu = dirt_gpu_create(&(dirt_gpu_opts){0});
    if (!gpu) {
        cli_error(PROG, "no OpenGL 4.5 context could be made (see the error above)");
        goto done;
    }
    rc = DIRT_EXIT_FAILURE;
    raster = dirt_raster_create(gpu, scene);
    img = dirt_image_create((int)o.width, (int)o.height);
    if (!raster || !img)
        goto done;
    if (o.debug_ads) {
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
    if (!o.quiet) {
        char desc[512];
        dirt_gpu_describe(gpu, desc, sizeof(desc));
        fprintf(stderr, "%s: %s, %zu triangles; %s\n", PROG,
                o.scene_path ? o.scene_path : "default scene", dirt_scene_num_triangles(scene),
                desc);
    }

    dirt_eval_opts eo = {.clip = (int)o.clip, .loop = o.loop};
    double t0 = dirt_clock_ms();
    for (long f = first; f <= last; f++) {
        float t = o.frames_set ? (float)(f / o.fps) : (float)o.time;
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
        dirt_raster_stats st;
        dirt_raster_opts ro = {.cpu_timing = o.cpu_timing};
        if (!dirt_raster_render(raster, frame, &cam, (int)o.width, (int)o.height, &ro,
                                img->rgba, &st))
            goto done;
        if (ads) {
            if (!dirt_ads_build(ads, frame, &cam))
                goto done;
            if (!o.quiet)
                dirt_ads_print_stats(ads, stderr);
            if (!dirt_ads_write_debug(ads, o.debug_ads, o.quiet)) {
                rc = DIRT_EXIT_USAGE;
                goto done;
            }
        }
        output_path(&o, f, path, sizeof(path));
        if (!write_outputs(&o, img, path)) {
            rc = DIRT_EXIT_USAGE; /* unwritable output */
            goto done;
        }
        if (!o.quiet && last > first) {
            double el = (dirt_clock_ms() - t0) / 1000.0;
            long done_n = f - first + 1, total = last - first + 1;
            fprintf(stderr, "%s: frame %ld/%ld (t=%.3fs) elapsed %.1fs, ETA %.1fs\n", PROG,
                    done_n, total, t, el, el / done_n * (total - done_n));
        }
    }
    rc = DIRT_EXIT_OK;
done:
    dirt_image_destroy(img);
    dirt_raster_destroy(raster);
    dirt_ads_destroy(ads);
    dirt_frame_destroy(frame);
    dirt_gpu_destroy(gpu);
    dirt_scene_destroy(scene);
    return rc;
}
