/* The shared-constants registry (glsl/common/constants.h) seen from C at
 * run time, for tests and messages. layout_check.c also holds every
 * compile-time check of the registry and of the C/GLSL twin records. */
#ifndef DIRT_GL_LAYOUT_CHECK_H
#define DIRT_GL_LAYOUT_CHECK_H

#include <stddef.h>

/* A named storage-buffer binding point and the range that owns it. */
typedef struct dirt_layout_binding {
    const char *name;  /* "DIRT_BIND_RAYS" */
    int binding;
    const char *range; /* "SHARED", "ADS", "TRACE", ... */
} dirt_layout_binding;

/* A subsystem's binding range [first, last]. */
typedef struct dirt_layout_range {
    const char *name;
    int first, last;
} dirt_layout_range;

/* A uniform of a program: its GLSL name and its DIRT_LOC_* location. */
typedef struct dirt_layout_uniform {
    const char *name;  /* "u_count" */
    int location;
} dirt_layout_uniform;

/* A program of glsl/ and the uniforms the registry names for it. A
 * compiler drops unused uniforms, so a uniform need only be active in one
 * of the programs sharing its table (e.g. u_ao_distance in the AO Shade). */
typedef struct dirt_layout_program {
    const char *paths[3];                  /* stage sources, NULL-terminated */
    const char *define;                    /* one define (value 1) or NULL */
    const dirt_layout_uniform *uniforms;
    size_t num_uniforms;
} dirt_layout_program;

/* Every DIRT_BIND_* of the registry, ascending. */
extern const dirt_layout_binding dirt_layout_bindings[];
extern const size_t dirt_layout_num_bindings;
/* Every DIRT_BIND_<range>_FIRST/_LAST pair, ascending. */
extern const dirt_layout_range dirt_layout_ranges[];
extern const size_t dirt_layout_num_ranges;
/* Every program with named uniform locations. */
extern const dirt_layout_program dirt_layout_programs[];
extern const size_t dirt_layout_num_programs;

/* Name of the DIRT_BIND_* at `binding`, NULL when none is. A switch with
 * one case per name: two names with one value do not compile. */
const char *dirt_layout_binding_name(int binding);

#endif
