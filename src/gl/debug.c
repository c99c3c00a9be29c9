/* GL debug output into the engine log; object labels and debug groups. */
#include "gl/gl.h"

#include <stdarg.h>
#include <stdio.h>

static const char *source_name(GLenum s)
{
    switch (s) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
    case GL_DEBUG_SOURCE_APPLICATION: return "app";
    default: return "other";
    }
}

static const char *type_name(GLenum t)
{
    switch (t) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    default: return "other";
    }
}

static void APIENTRY on_debug(GLenum source, GLenum type, GLuint id, GLenum severity,
                                GLsizei length, const GLchar *message, const void *user)
{
    (void)length;
    dirt_gpu *gpu = (dirt_gpu *)user;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP)
        return;
    enum dirt_log_level level = DIRT_LOG_DEBUG;
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH)
        level = DIRT_LOG_ERROR;
    else if (severity == GL_DEBUG_SEVERITY_MEDIUM || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR)
        level = DIRT_LOG_WARN;
    if (level <= DIRT_LOG_WARN)
        __atomic_fetch_add(&gpu->error_count, 1, __ATOMIC_RELAXED); /* async output: any thread */
    dirt_log(level, NULL, 0, "GL %s %s #%u: %s", source_name(source), type_name(type),
             id, message);
}

void gl_debug_install(dirt_gpu *gpu)
{
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT))
        DIRT_DEBUG("context has no debug flag; debug output may be limited");
    glEnable(GL_DEBUG_OUTPUT);
    /* Synchronous output stalls a GPU's pipeline at every call: only when
     * asked, or when debug messages are printed anyway. */
    if (gpu->opts.sync_debug || dirt_log_get_level() >= DIRT_LOG_DEBUG)
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    else
        glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug, gpu);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_TRUE);
    /* Notifications (buffer placement hints etc.) are noise. */
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0,
                          NULL, GL_FALSE);
}

void gl_label(GLenum type, GLuint id, const char *fmt, ...)
{
    char name[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(name, sizeof(name), fmt, ap);
    va_end(ap);
    glObjectLabel(type, id, -1, name);
}

void gl_group_push(const char *name)
{
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
    gl_check_group(name);
}

void gl_group_pop(void)
{
    glPopDebugGroup();
    gl_check_group(NULL);
}

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "GL error";
    }
}

bool gl_check_(const char *file, int line, const char *what)
{
    bool ok = true;
    for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
        dirt_log(DIRT_LOG_ERROR, file, line, "%s: %s (0x%x)", what, gl_error_name(e), e);
        ok = false;
    }
    return ok;
}
