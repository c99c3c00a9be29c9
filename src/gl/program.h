/* GL programs from glsl/ files. */
#ifndef DIRT_GL_PROGRAM_H
#define DIRT_GL_PROGRAM_H

#include "gl/gl.h"
#include "gl/glsl_source.h"

/* Compiles and links the stages named by `paths` (relative to glsl_root(),
 * stage from the extension; NULL-terminated) with the given defines. Returns
 * the program (labelled `label`) or 0 after logging the compiler/linker output
 * with the file table. */
GLuint gl_program_create(const char *label, const char *const *paths,
                         const glsl_define *defines, size_t num_defines);

/* Convenience: a compute program from one .comp file. */
GLuint gl_program_compute(const char *path, const glsl_define *defines, size_t num_defines);

void gl_program_destroy(GLuint *program);

#endif
