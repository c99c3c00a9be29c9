/* An outside program on the DIRT engine's consumer API: renders a scene (the
 * default scene, or a glTF/OBJ file) through one engine and writes an EXR
 * (beauty and AOVs). Builds with nothing but pkg-config:
 *
 *     cc -std=c11 render.c $(pkg-config --cflags --libs dirt) -o render
 *     ./render -o out.exr                         # default scene, DIRT, 4 spp
 *     ./render --engine embree --spp 16 scene.glb -o ref.exr
 *
 * Exit status: 0 written, 1 render failure, 2 bad arguments or scene,
 * 3 no OpenGL 4.5 context for a GPU engine. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dirt/gpu.h>
#include <dirt/scene.h>
#include <dirt/session.h>
#include <dirt/version.h>

static int usage(void)
{
    fprintf(stderr, "usage: render [--engine dirt|mmrt|embree|raster] [--spp N] [--seed N]\n"
                    "              [-W WIDTH] [-H HEIGHT] [--bounces N] [SCENE] -o OUT.exr|.png\n");
    return 2;
}

/* Parses a whole non-negative int, or returns -1. */
static int count(const char *s)
{
    char *end;
    long v = strtol(s, &end, 10);
    return *s && !*end && v >= 0 && v <= 1 << 20 ? (int)v : -1;
}

int main(int argc, char **argv)
{
    dirt_session_opts opts = {.width = 160, .seed = 1};
    const char *scene_path = NULL, *out = NULL;
    int spp = 4;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int n = v ? count(v) : -1;
        if (!strcmp(a, "-o") && v) {
            out = v;
        } else if (!strcmp(a, "--engine") && v) {
            int e = 0;
            while (e < DIRT_NUM_ENGINES && strcmp(dirt_engine_names[e], v))
                e++;
            if (e == DIRT_NUM_ENGINES)
                return usage();
            opts.engine = (enum dirt_engine)e;
        } else if (!strcmp(a, "--spp") && n > 0) {
            spp = n;
        } else if (!strcmp(a, "--seed") && n >= 0) {
            opts.seed = (uint32_t)n;
        } else if (!strcmp(a, "-W") && n > 0) {
            opts.width = n;
        } else if (!strcmp(a, "-H") && n > 0) {
            opts.height = n;
        } else if (!strcmp(a, "--bounces") && n > 0) {
            opts.bounces = n;
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
            continue;
        } else {
            return usage();
        }
        i++;
    }
    char why[256];
    if (!out || !dirt_session_check_opts(&opts, why, sizeof(why)))
        return out ? (fprintf(stderr, "render: %s\n", why), 2) : usage();

    dirt_scene *scene = scene_path ? dirt_scene_load(scene_path, NULL)
                                   : dirt_scene_create_default();
    if (!scene) {
        fprintf(stderr, "render: %s: %s\n", scene_path ? scene_path : "default scene",
                dirt_scene_error_str(dirt_scene_last_error()));
        return 2;
    }
    /* The CPU engine needs no GPU. */
    dirt_gpu *gpu = NULL;
    if (opts.engine != DIRT_ENGINE_EMBREE && !(gpu = dirt_gpu_create(&(dirt_gpu_opts){0}))) {
        dirt_scene_destroy(scene);
        return 3;
    }
    char device[512] = "CPU";
    if (gpu)
        dirt_gpu_describe(gpu, device, sizeof(device));
    printf("libdirt %s (built against %d.%d.%d), %s\n", dirt_version(), DIRT_VERSION_MAJOR,
           DIRT_VERSION_MINOR, DIRT_VERSION_PATCH, device);

    int status = 1;
    dirt_session *s = dirt_session_create(gpu, scene, &opts);
    if (s && dirt_session_add_samples(s, spp, NULL, NULL) &&
        dirt_session_write_image(s, out, NULL)) {
        const dirt_session_stats *st = dirt_session_get_stats(s);
        printf("%s: %dx%d, %d spp, %s engine, %.1f Mrays/s\n", out, st->width, st->height,
               st->samples, dirt_engine_names[st->engine], st->mrays_per_s);
        status = 0;
    } else {
        fprintf(stderr, "render: %s\n", dirt_session_error_str(dirt_session_last_error()));
        if (dirt_session_last_error() == DIRT_SESSION_ERR_IO)
            status = 2;
    }
    dirt_session_destroy(s);
    dirt_gpu_destroy(gpu);
    dirt_scene_destroy(scene);
    return status;
}
