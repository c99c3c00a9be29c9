/* DIRT engine: the built-in default scene. Its content is
 * data/default_scene.gltf, compiled into the library by embed.c (see
 * src/scene/meson.build), so the programs need no file beside them. */
#include "scene/scene_internal.h"

#include "dirt/log.h"

dirt_scene *dirt_scene_create_default(void)
{
    dirt_scene *s = dirt_scene_load_memory(scene_default_gltf, scene_default_gltf_size,
                                           "default", NULL);
    if (!s)
        DIRT_ERROR("cannot build the embedded default scene");
    return s;
}
