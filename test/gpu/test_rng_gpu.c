/* One RNG for CPU and GPU: the GLSL twin (glsl/common/rng.glsl) gives
 * exactly the bits of the C one (src/integrator/rng.h) for 2^18 keys over
 * wide ranges of (seed, pixel, sample, bounce, dimension), both the integer
 * stream and the floats in [0, 1). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gpu.h"
#include "integrator/rng.h"

#define N (1u << 18)

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    GLuint prog = gl_program_compute("test/rng.comp", NULL, 0);
    GLuint buf = gl_buffer_create(gpu, N * 8, NULL, true, "rng values");
    CHECK(prog && buf);
    uint32_t *out = malloc(N * 8);
    static const uint32_t seeds[] = {0u, 1u, 0xDEADBEEFu};
    for (int s = 0; s < 3; s++) {
        glUseProgram(prog);
        glUniform1ui(DIRT_LOC_TEST_RNG_COUNT, N);
        glUniform1ui(DIRT_LOC_TEST_RNG_SEED, seeds[s]);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, buf);
        glDispatchCompute(DIRT_GROUPS(N), 1, 1);
        /* the readback, and the next seed's dispatch writing the same words */
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        CHECK(gl_buffer_read(buf, 0, N * 8, out));
        uint32_t bad_u = 0, bad_f = 0;
        for (uint32_t i = 0; i < N; i++) {
            uint32_t pixel = i * 2654435761u, sample = i / 7u, bounce = i % 13u, dim = i % 11u;
            uint32_t key = dirt_rng_key(seeds[s], pixel, sample, bounce);
            float f = dirt_rng_float(seeds[s], pixel, sample, bounce, dim);
            uint32_t fb;
            memcpy(&fb, &f, 4);
            bad_u += out[2 * i] != dirt_rng_next(key, dim);
            bad_f += out[2 * i + 1] != fb;
        }
        fprintf(stderr, "seed %#x: %u keys, %u integer and %u float mismatches\n", seeds[s], N,
                bad_u, bad_f);
        CHECK(bad_u == 0 && bad_f == 0);
    }
    free(out);
    gl_buffer_destroy(&buf);
    gl_program_destroy(&prog);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
