/* What every program does before it renders: the scene (within
 * --max-scene-memory), the environment map, the checks of --camera and
 * --clip against the scene, the GPU, and --version. Each prints
 * "PROG: why" on failure. */
#ifndef DIRT_APP_SETUP_H
#define DIRT_APP_SETUP_H

#include <stdbool.h>

#include "app/options.h"
#include "dirt/gpu.h"
#include "dirt/env.h"
#include "dirt/scene.h"

/* The loader's options of the command line: --max-scene-memory,
 * --strict, --allow-outside-paths. */
dirt_load_opts app_load_opts(const app_opts *o);
/* The environment's: --env-intensity, --env-rotation, and
 * --max-scene-memory as the bound of loading the map. */
dirt_env_opts app_env_opts(const app_opts *o);

/* Loads `path` (NULL or "default": the embedded default scene) with
 * app_load_opts. NULL after printing why: one line that names the
 * reason's id (dirt_scene_last_error; TOO_LARGE names --max-scene-memory
 * too). */
dirt_scene *app_load_scene(const char *prog, const char *path, const app_opts *o);

/* The environment of --env (app_env_opts), set as o->s.env; true without
 * --env. False after printing why (led by the reason's id, dirt/input.h).
 * The map is the caller's (dirt_env_destroy). */
bool app_load_env(const char *prog, app_opts *o, dirt_env **env);

/* --camera and --clip exist in `scene`. False after printing why. */
bool app_check_scene(const char *prog, const app_opts *o, const dirt_scene *scene);

/* A headless GPU for --gpu and --cpu-timing. NULL after printing why. */
dirt_gpu *app_gpu(const char *prog, const app_opts *o);

/* --version: the program, the library's version and commit, and the
 * OpenGL renderer of a headless context (made for the purpose). The exit
 * status: 0, or 3 (DIRT_EXIT_NO_GPU) when no OpenGL 4.5 context could be
 * made (the version and commit are printed all the same). */
int app_version(const char *prog, const app_opts *o);

#endif
