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

/* Dispatches the current compute program over a ray batch
 * (glsl/common/ray_batch.glsl): with `batch` (a buffer holding a
 * dirt_gpu_ray_batch header then the owners), binds it at
 * DIRT_BIND_RAY_BATCH, sets u_ray_batch and dispatches indirectly from its
 * header; with 0, clears u_ray_batch and dispatches over `count`
 * invocations, at least `min_groups` groups. */
void gl_dispatch_rays(GLuint batch, uint32_t count, uint32_t min_groups);

/* Dispatches the current compute program over `invocations` invocations of
 * DIRT_GROUP_SIZE-wide groups in rows of DIRT_GROUPS_ROW groups (GL promises
 * only 65535 groups per dimension); the shader numbers its invocations with
 * dirt_row_invocation() (glsl/common/rows.glsl) and bound-checks. Nothing
 * for 0. */
void gl_dispatch_rows(size_t invocations);

#endif
