/* Poisoned memory (dirt_gpu_opts.poison): new buffers and textures, and
 * frame-graph transients at their first use in an execute, are filled with
 * a pattern no pass writes, so that a read of memory nobody wrote changes
 * the result on every driver (llvmpipe zero-fills new memory; lavapipe and
 * GPU drivers do not). Built without the barrier checker's wrappers
 * (check.c): the clears and their barriers are the test harness's, not the
 * engine's, and must not hide a barrier the engine is missing. */
#define DIRT_GL_RAW 1
#include "gl/gl.h"

void gl_poison_buffer(GLuint buf, size_t size, bool after_shaders)
{
    dirt_gpu *gpu = gl_current();
    if (!gpu || !gpu->poison || !buf || !size)
        return;
    if (after_shaders)
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    static const uint32_t word = DIRT_GPU_POISON_WORD;
    static const uint8_t byte = DIRT_GPU_POISON_UNORM;
    size_t words = size / 4 * 4;
    if (words)
        glClearNamedBufferSubData(buf, GL_R32UI, 0, (GLsizeiptr)words, GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &word);
    if (size > words)
        glClearNamedBufferSubData(buf, GL_R8UI, (GLintptr)words, (GLsizeiptr)(size - words),
                                  GL_RED_INTEGER, GL_UNSIGNED_BYTE, &byte);
}

void gl_poison_texture(GLuint tex, bool after_shaders)
{
    dirt_gpu *gpu = gl_current();
    if (!gpu || !gpu->poison || !tex)
        return;
    if (after_shaders)
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    GLint levels = 0, depth = GL_NONE, red = GL_NONE;
    glGetTextureParameteriv(tex, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_DEPTH_TYPE, &depth);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_RED_TYPE, &red);
    union {
        float f[4];
        uint32_t u[4];
        uint8_t b[4];
    } v;
    GLenum format = GL_RGBA, type = GL_FLOAT;
    for (int i = 0; i < 4; i++)
        v.u[i] = DIRT_GPU_POISON_WORD; /* a quiet NaN as a float */
    if (depth != GL_NONE) {
        format = GL_DEPTH_COMPONENT; /* 0: the near plane, nothing passes GL_LESS */
        v.f[0] = 0.0f;
    } else if (red == GL_UNSIGNED_INT || red == GL_INT) {
        format = GL_RGBA_INTEGER;
        type = red == GL_INT ? GL_INT : GL_UNSIGNED_INT;
    } else if (red == GL_UNSIGNED_NORMALIZED || red == GL_SIGNED_NORMALIZED) {
        type = GL_UNSIGNED_BYTE;
        for (int i = 0; i < 4; i++)
            v.b[i] = DIRT_GPU_POISON_UNORM;
    }
    for (GLint l = 0; l < (levels > 0 ? levels : 1); l++)
        glClearTexImage(tex, l, format, type, &v);
}
