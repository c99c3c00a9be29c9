/* The shader sources embedded into the library at build time (glsl/embed.py
 * writes the table from every file glsl/meson.build lists). Pure C, no GL. */
#ifndef DIRT_GL_GLSL_EMBEDDED_H
#define DIRT_GL_GLSL_EMBEDDED_H

#include <stddef.h>

/* One file of glsl/: `path` relative to glsl/ ("common/constants.h"),
 * `text` its bytes followed by a 0 byte, `size` without that 0. */
typedef struct glsl_embedded_file {
    const char *path;
    const char *text;
    size_t size;
} glsl_embedded_file;

/* Sorted by path (strcmp). */
extern const glsl_embedded_file glsl_embedded_files[];
extern const size_t glsl_embedded_count;

#endif
