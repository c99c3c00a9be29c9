/* The Hi-Z min/max pyramid of a view set's tile (or pixel) depth bounds
 * (glsl/views/hiz.comp), shared by the DIRT and MMRT builds. */
#ifndef DIRT_VIEWS_HIZ_H
#define DIRT_VIEWS_HIZ_H

#include "views/views.h"
#include "gl/gl.h"
#include "gl/split.h"

/* Makes `p` the pyramid program for depth bounds stored in `layout`
 * (gl_split_depth). False after logging. The caller owns it
 * (gl_split_program_destroy). */
bool views_hiz_program(gl_split_program *p, gl_split_layout layout);

/* Builds levels 1.. of the pyramid of every view of `set` with `program`;
 * the views and the pyramid must be bound (DIRT_BIND_VIEWS; the pyramid
 * at DIRT_BIND_DEPTH, or its parts: gl_split_bind) and level 0 visible to
 * shaders. Issues the barriers
 * between levels itself (not after the last one). */
void views_hiz_dispatch(GLuint program, const dirt_view_set *set);

#endif
