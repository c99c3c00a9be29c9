/* Uniform values reach every dispatch (the MMRT chunked difference on zink):
 * two compute programs alternate on the compute stage, each first
 * dispatched with u_batch = 0 (and its count), then with u_batch = 1 and
 * the same values in both; every dispatch must read what was set last.
 * Mesa 22.3's zink specializes shaders on the values of uniforms that
 * steer branches ("inlined uniforms") and, when the program changes and
 * the new one's values equal the previous program's, keeps the new one's
 * variant made for its old values: here 10 of the 12 batched dispatches
 * read u_batch = 0. In the path tracer that was MMRT's trace after the
 * Z pass's plain traces: it took the compacted rays as rays 0..n-1 of the
 * chunk (owner = index), so events 2 and later shaded the wrong pixels
 * whenever the image was chunked. dirt_gpu_create turns the inlining off
 * (ZINK_INLINE_UNIFORMS=0 unless the environment sets it); other drivers
 * pass either way. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "gl/program.h"
#include "gpu.h"

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    fprintf(stderr, "%s\n", desc);
    const char *inl = getenv("ZINK_INLINE_UNIFORMS");
    CHECK_MSG(inl != NULL, "dirt_gpu_create left ZINK_INLINE_UNIFORMS unset");
    GLuint prog[2] = {gl_program_compute("test/uniform_switch.comp", NULL, 0),
                      gl_program_compute("test/uniform_switch.comp", NULL, 0)};
    CHECK(prog[0] && prog[1] && prog[0] != prog[1]);
    enum { OWNERS = 900, BATCHED = 6 };
    static uint32_t batch[4 + OWNERS];
    batch[0] = DIRT_GROUPS(799);
    batch[1] = batch[2] = 1;
    batch[3] = 799;
    for (int i = 0; i < OWNERS; i++)
        batch[4 + i] = 5000u + (uint32_t)i;
    GLuint in = gl_buffer_create(gpu, sizeof(batch), batch, false, "uniform switch batch");
    GLuint out = gl_buffer_create(gpu, 64 * sizeof(uint32_t), NULL, true, "uniform switch out");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_IN, in);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, out);
    /* Plain: three rounds of both programs (counts as MMRT's Z pass in
     * chunks of 832 of a 48x36 image). */
    const uint32_t plain[3] = {832, 832, 64};
    for (int k = 0; k < 3; k++) {
        for (int j = 0; j < 2; j++) {
            glUseProgram(prog[j]);
            glUniform1i(DIRT_LOC_TEST_SWITCH_BATCH, 0);
            glUniform1ui(DIRT_LOC_TEST_SWITCH_COUNT, plain[k]);
            glUniform1ui(DIRT_LOC_TEST_SWITCH_SLOT, 63);
            glDispatchCompute(DIRT_GROUPS(plain[k]), 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
    }
    /* Batched, dispatched from the batch as the path tracer does. */
    for (int k = 0; k < BATCHED; k++) {
        for (int j = 0; j < 2; j++) {
            glUseProgram(prog[j]);
            glUniform1i(DIRT_LOC_TEST_SWITCH_BATCH, 1);
            glUniform1ui(DIRT_LOC_TEST_SWITCH_COUNT, 832);
            glUniform1ui(DIRT_LOC_TEST_SWITCH_SLOT, (GLuint)(2 * k + j));
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in);
            glDispatchComputeIndirect(0);
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
    }
    glUseProgram(0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t got[64];
    CHECK(gl_buffer_read(out, 0, sizeof(got), got));
    int stale = 0;
    for (int i = 0; i < 2 * BATCHED; i++)
        stale += got[i] != 5000u;
    CHECK_MSG(stale == 0, "%d of %d batched dispatches read u_batch = 0 (a stale uniform)",
              stale, 2 * BATCHED);
    gl_buffer_destroy(&in);
    gl_buffer_destroy(&out);
    gl_program_destroy(&prog[0]);
    gl_program_destroy(&prog[1]);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    fprintf(stderr, "uniforms: %d dispatches of two alternating programs read the values "
                    "set last\n", 6 + 2 * BATCHED);
    return check_finish();
}
