/* Runs a model test shader (glsl/integrator/test_*.comp: uniforms
 * DIRT_LOC_TEST_MODEL_MODE / _COUNT, records in at DIRT_BIND_TEST_IN, out
 * at DIRT_BIND_TEST_OUT) over n records of in_floats and out_floats floats
 * each; the results go to `out`. Header-only, for GPU test executables
 * (include after gl/gl.h). False (GL error, out of memory) after logging. */
#ifndef DIRT_TEST_MODEL_SHADER_H
#define DIRT_TEST_MODEL_SHADER_H

#include "common/layout.h"
#include "gl/gl.h"

static inline bool test_run_model_shader(dirt_gpu *gpu, GLuint prog, int mode, const float *in,
                                         size_t in_floats, int n, float *out,
                                         size_t out_floats)
{
    GLuint bin = gl_buffer_create(gpu, (size_t)n * in_floats * sizeof(float), in, false,
                                  "model test in");
    GLuint bout = gl_buffer_create(gpu, (size_t)n * out_floats * sizeof(float), NULL, true,
                                   "model test out");
    bool ok = bin && bout;
    if (ok) {
        glUseProgram(prog);
        glProgramUniform1i(prog, DIRT_LOC_TEST_MODEL_MODE, mode);
        glProgramUniform1ui(prog, DIRT_LOC_TEST_MODEL_COUNT, (GLuint)n);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_IN, bin);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, bout);
        glDispatchCompute((GLuint)DIRT_GROUPS(n), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        ok = gl_buffer_read(bout, 0, (size_t)n * out_floats * sizeof(float), out) &&
             gl_check("model test dispatch");
    }
    gl_buffer_destroy(&bin);
    gl_buffer_destroy(&bout);
    return ok;
}

#endif
