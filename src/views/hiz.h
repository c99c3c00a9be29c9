/* The Hi-Z min/max pyramid of a view set's tile (or pixel) depth bounds
 * (glsl/views/hiz.comp), shared by the DIRT and MMRT builds. */
#ifndef DIRT_VIEWS_HIZ_H
#define DIRT_VIEWS_HIZ_H

#include "views/views.h"
#include "gl/gl.h"

/* Compiles the pyramid program. 0 after logging. The caller owns it
 * (gl_program_destroy). */
GLuint views_hiz_program(void);

/* Builds levels 1.. of the pyramid of every view of `set` with `program`;
 * the views and the pyramid must be bound at DIRT_BIND_VIEWS /
 * DIRT_BIND_DEPTH and level 0 visible to shaders. Issues the barriers
 * between levels itself (not after the last one). */
void views_hiz_dispatch(GLuint program, const dirt_view_set *set);

#endif
