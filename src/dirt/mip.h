/* The Hi-Z min/max pyramid pass (glsl/dirt/mip.comp), shared by the DIRT
 * and MMRT builds. */
#ifndef DIRT_DIRT_MIP_H
#define DIRT_DIRT_MIP_H

#include "dirt/views.h"
#include "gl/gl.h"

/* Builds levels 1.. of the pyramid of every view of `set` with the compiled
 * mip.comp `program`; the views and the pyramid must be bound at
 * DIRT_BIND_VIEWS / DIRT_BIND_DEPTH and level 0 visible to shaders. Issues
 * the barriers between levels itself (not after the last one). */
void dirt_mip_dispatch(GLuint program, const dirt_view_set *set);

#endif
