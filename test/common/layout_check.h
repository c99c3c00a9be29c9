/* The shared-constants registry (glsl/common/constants.h) seen from C at
 * run time, for tests and messages. layout_check.c also holds every
 * compile-time check of the registry and of the C/GLSL twin records. */
#ifndef DIRT_TEST_LAYOUT_CHECK_H
#define DIRT_TEST_LAYOUT_CHECK_H

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
    unsigned ranges;                       /* bit i: may bind in dirt_layout_ranges[i] */
    const dirt_layout_uniform *uniforms;
    size_t num_uniforms;
} dirt_layout_program;

/* Every DIRT_BIND_* of the registry, ascending. */
extern const dirt_layout_binding dirt_layout_bindings[];
extern const size_t dirt_layout_num_bindings;
/* Every DIRT_BIND_<range>_FIRST/_LAST pair, ascending; bit i of a
 * program's `ranges` is dirt_layout_ranges[i]. */
enum {
    DIRT_RANGE_SHARED = 1u << 0, DIRT_RANGE_ADS = 1u << 1, DIRT_RANGE_TRACE = 1u << 2,
    DIRT_RANGE_INTEGRATOR = 1u << 3, DIRT_RANGE_MMRT = 1u << 4, DIRT_RANGE_MMRT_PT = 1u << 5,
    DIRT_RANGE_MODEL = 1u << 6, DIRT_RANGE_PREVIEW = 1u << 7, DIRT_RANGE_TEST = 1u << 8,
    DIRT_RANGE_WORK = 1u << 9, DIRT_RANGE_SORT = 1u << 10, DIRT_RANGE_LARGE = 1u << 11,
};
extern const dirt_layout_range dirt_layout_ranges[];
extern const size_t dirt_layout_num_ranges;
/* Every program with named uniform locations. */
extern const dirt_layout_program dirt_layout_programs[];
extern const size_t dirt_layout_num_programs;

/* Name of the DIRT_BIND_* at `binding`, NULL when none is. A switch with
 * one case per name: two names with one value do not compile. */
const char *dirt_layout_binding_name(int binding);

#endif
