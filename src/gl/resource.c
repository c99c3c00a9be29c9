/* Buffers and textures with immutable storage, labelled. */
#include "gl/gl.h"

GLuint gl_buffer_create(dirt_gpu *gpu, size_t size, const void *data, bool readback,
                        const char *label)
{
    if (size == 0)
        size = 16; /* GL forbids zero-sized storage; keep a tiny valid buffer */
    if (gpu && gpu->caps.max_ssbo_size > 0 && (int64_t)size > gpu->caps.max_ssbo_size) {
        DIRT_ERROR("buffer '%s' needs %zu bytes, more than this GPU's maximum storage "
                   "block size (%lld bytes)", label ? label : "?", size,
                   (long long)gpu->caps.max_ssbo_size);
        return 0;
    }
    while (glGetError() != GL_NO_ERROR) {
    }
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    GLbitfield flags = GL_DYNAMIC_STORAGE_BIT | (readback ? GL_MAP_READ_BIT : 0);
    glNamedBufferStorage(buf, (GLsizeiptr)size, data, flags);
    if (!gl_check("glNamedBufferStorage")) {
        DIRT_ERROR("could not allocate %zu bytes for buffer '%s'", size, label ? label : "?");
        glDeleteBuffers(1, &buf);
        return 0;
    }
    if (label)
        gl_label(GL_BUFFER, buf, "%s", label);
    if (!data)
        gl_poison_buffer(buf, size, false);
    return buf;
}

void gl_buffer_destroy(GLuint *buf)
{
    if (*buf)
        glDeleteBuffers(1, buf);
    *buf = 0;
}

bool gl_buffer_ensure(dirt_gpu *gpu, GLuint *buf, size_t *cap, size_t size, bool readback,
                      const char *label)
{
    if (*buf && *cap >= size)
        return true;
    gl_buffer_destroy(buf);
    *buf = gl_buffer_create(gpu, size, NULL, readback, label);
    *cap = *buf ? size : 0;
    return *buf != 0;
}

bool gl_buffer_read(GLuint buf, size_t offset, size_t size, void *out)
{
    glGetNamedBufferSubData(buf, (GLintptr)offset, (GLsizeiptr)size, out);
    return gl_check("glGetNamedBufferSubData");
}

GLuint gl_texture_2d(GLenum internal_format, int width, int height, int levels,
                     const char *label)
{
    while (glGetError() != GL_NO_ERROR) {
    }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, levels, internal_format, width, height);
    if (!gl_check("glTextureStorage2D")) {
        DIRT_ERROR("could not allocate %dx%d texture '%s'", width, height, label ? label : "?");
        glDeleteTextures(1, &tex);
        return 0;
    }
    if (label)
        gl_label(GL_TEXTURE, tex, "%s", label);
    gl_poison_texture(tex, false);
    return tex;
}

GLuint gl_texture_2d_array(GLenum internal_format, int width, int height, int layers,
                           int levels, const char *label)
{
    while (glGetError() != GL_NO_ERROR) {
    }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
    glTextureStorage3D(tex, levels, internal_format, width, height, layers);
    if (!gl_check("glTextureStorage3D")) {
        DIRT_ERROR("could not allocate %dx%dx%d texture array '%s'", width, height, layers,
                   label ? label : "?");
        glDeleteTextures(1, &tex);
        return 0;
    }
    if (label)
        gl_label(GL_TEXTURE, tex, "%s", label);
    gl_poison_texture(tex, false);
    return tex;
}

void gl_texture_destroy(GLuint *tex)
{
    if (*tex)
        glDeleteTextures(1, tex);
    *tex = 0;
}

bool gl_texture_upload_rgba32f(GLuint tex, int width, int height, const float *rgba)
{
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(tex, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    return gl_check("texture upload");
}

bool gl_texture_read_rgba32f(GLuint tex, int width, int height, float *rgba)
{
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT,
                      (GLsizei)((size_t)width * (size_t)height * 4 * sizeof(float)), rgba);
    return gl_check("texture read");
}

bool gl_buffer_write(GLuint buf, size_t offset, size_t size, const void *data)
{
    glNamedBufferSubData(buf, (GLintptr)offset, (GLsizeiptr)size, data);
    return gl_check("buffer write");
}
