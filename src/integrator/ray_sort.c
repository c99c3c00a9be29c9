/* The path tracer's ray sort (ray_sort.h). */
#include "integrator/ray_sort.h"

#include <stdlib.h>

#include "common/layout.h"
#include "dirt/log.h"
#include "gl/program.h"

struct dirt_ray_sort {
    GLuint prog[DIRT_RAY_SORT_PASSES];
};

dirt_ray_sort *dirt_ray_sort_create(void)
{
    dirt_ray_sort *rs = calloc(1, sizeof(*rs));
    if (!rs) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    static const char *const names[DIRT_RAY_SORT_PASSES] = {"DIRT_SORT_COUNT", "DIRT_SORT_SCAN",
                                                             "DIRT_SORT_SCATTER"};
    for (int p = 0; p < DIRT_RAY_SORT_PASSES; p++) {
        glsl_define d = {names[p], "1"};
        rs->prog[p] = gl_program_compute("integrator/sort.comp", &d, 1);
        if (!rs->prog[p]) {
            dirt_ray_sort_destroy(rs);
            return NULL;
        }
    }
    return rs;
}

void dirt_ray_sort_destroy(dirt_ray_sort *rs)
{
    if (!rs)
        return;
    for (int p = 0; p < DIRT_RAY_SORT_PASSES; p++)
        gl_program_destroy(&rs->prog[p]);
    free(rs);
}

size_t dirt_ray_sort_scratch_bytes(size_t capacity)
{
    return ((size_t)DIRT_SORT_BUCKETS + (capacity > 0 ? capacity : 1)) * sizeof(uint32_t);
}

void dirt_ray_sort_pass(const dirt_ray_sort *rs, enum dirt_ray_sort_pass pass,
                        const dirt_ray_sort_io *io)
{
    if (pass == DIRT_RAY_SORT_COUNT) {
        static const uint32_t zero = 0;
        glClearNamedBufferSubData(io->scratch, GL_R32UI, 0,
                                  (GLsizeiptr)DIRT_SORT_BUCKETS * sizeof(uint32_t), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &zero);
    }
    glUseProgram(rs->prog[pass]);
    glUniform1ui(DIRT_LOC_SORT_RAYS, io->capacity);
    glUniform3fv(DIRT_LOC_SORT_BOUNDS_MIN, 1, io->bounds_min);
    glUniform3fv(DIRT_LOC_SORT_BOUNDS_MAX, 1, io->bounds_max);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_SORT, io->scratch);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, io->in_rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAY_BATCH, io->in_batch);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_NEXT_BATCH, io->out_batch);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_SHADOW_RAYS, io->out_rays);
    if (pass == DIRT_RAY_SORT_SCAN) {
        glDispatchCompute(1, 1, 1);
    } else {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, io->in_batch);
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    glUseProgram(0);
}
