/* What every program does before it renders (setup.h). */
#include "app/setup.h"

#include <stdio.h>
#include <string.h>

#include "app/cli.h"
#include "dirt/log.h"
#include "dirt/version.h"

dirt_load_opts app_load_opts(const app_opts *o)
{
    return (dirt_load_opts){.max_bytes = o->max_scene_bytes, .strict = o->strict,
                            .allow_outside = o->allow_outside_paths};
}

dirt_env_opts app_env_opts(const app_opts *o)
{
    return (dirt_env_opts){.intensity = o->env_intensity, .rotation = o->env_rotation,
                           .max_bytes = o->max_scene_bytes};
}

dirt_scene *app_load_scene(const char *prog, const char *path, const app_opts *o)
{
    bool def = !path || !strcmp(path, "default");
    dirt_load_opts lo = app_load_opts(o);
    dirt_scene *scene = def ? dirt_scene_create_default() : dirt_scene_load(path, &lo);
    if (scene)
        return scene;
    if (!def && dirt_scene_last_error() == DIRT_SCENE_ERR_TOO_LARGE)
        cli_error(prog, "cannot load scene '%s': TOO_LARGE (it needs more memory than "
                  "--max-scene-memory allows, %zu bytes; see the error above): raise the "
                  "budget with --max-scene-memory (such as 4G; a mesh takes about 230 bytes "
                  "a triangle)", path,
                  o->max_scene_bytes);
    else
        cli_scene_error(prog, def ? NULL : path);
    return NULL;
}

bool app_load_env(const char *prog, app_opts *o, dirt_env **env)
{
    *env = NULL;
    if (!o->env_path)
        return true;
    char why[512];
    dirt_env_opts eo = app_env_opts(o);
    *env = dirt_env_load(o->env_path, &eo, why, sizeof(why));
    if (!*env) {
        cli_error(prog, "--env: %s", why);
        return false;
    }
    o->s.env = *env;
    return true;
}

bool app_check_scene(const char *prog, const app_opts *o, const dirt_scene *scene)
{
    size_t cameras = dirt_scene_num_cameras(scene), clips = dirt_scene_num_clips(scene);
    if (o->camera >= 0 && (size_t)o->camera >= cameras) {
        cli_error(prog, "--camera %d: the scene has %zu camera(s)", o->camera, cameras);
        return false;
    }
    if (o->clip >= 0 && clips > 0 && (size_t)o->clip >= clips) {
        cli_error(prog, "--clip %d: the scene has %zu animation clip(s)", o->clip, clips);
        return false;
    }
    return true;
}

dirt_gpu *app_gpu(const char *prog, const app_opts *o)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){
        .cpu_timing = o->cpu_timing, .platform = (enum dirt_gpu_platform)o->gpu_platform});
    if (!gpu)
        cli_error(prog, "no OpenGL 4.5 context could be made (see the error above)");
    return gpu;
}

int app_version(const char *prog, const app_opts *o)
{
    printf("%s %s (commit %s)\n", prog, dirt_version(), dirt_version_commit());
    fflush(stdout);
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){
        .no_debug = true, .platform = (enum dirt_gpu_platform)o->gpu_platform});
    if (!gpu) {
        printf("OpenGL renderer: none (no OpenGL 4.5 context could be made: see the error "
               "above; the embree engine needs none)\n");
        return DIRT_EXIT_NO_GPU;
    }
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    printf("OpenGL renderer: %s\n", desc);
    dirt_gpu_destroy(gpu);
    return DIRT_EXIT_OK;
}
