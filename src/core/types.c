/* The name tables of dirt/types.h. */
#include "dirt/types.h"

const char *const dirt_ray_type_names[DIRT_RAY_TYPES] = {
    "primary", "visibility", "specular", "glossy", "diffuse",
};
