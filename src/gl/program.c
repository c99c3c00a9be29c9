#include "gl/program.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/constants.h"

static GLenum stage_enum(const char *stage)
{
    static const struct { const char *name; GLenum e; } map[] = {
        {"vert", GL_VERTEX_SHADER}, {"tesc", GL_TESS_CONTROL_SHADER},
        {"tese", GL_TESS_EVALUATION_SHADER}, {"geom", GL_GEOMETRY_SHADER},
        {"frag", GL_FRAGMENT_SHADER}, {"comp", GL_COMPUTE_SHADER},
    };
    for (size_t i = 0; i < sizeof(map) / sizeof(map[0]); i++) {
        if (stage && strcmp(stage, map[i].name) == 0)
            return map[i].e;
    }
    return 0;
}

static void log_file_table(const glsl_files *files)
{
    for (int i = 0; i < files->count; i++)
        DIRT_ERROR("  source %d = glsl/%s", i, files->path[i]);
}

/* Compiles one stage; *source_out (when not NULL) gets its assembled
 * source, which the caller frees. */
static GLuint compile_stage(const char *path, const glsl_define *defines, size_t num_defines,
                            char **source_out)
{
    GLenum type = stage_enum(glsl_stage_of(path));
    if (!type) {
        DIRT_ERROR("shader %s: unknown stage (extension must be .vert/.tesc/.tese/.geom/"
                   ".frag/.comp)", path);
        return 0;
    }
    glsl_files files;
    char *src = glsl_assemble(glsl_root(), path, defines, num_defines, &files);
    if (!src)
        return 0;
    GLuint sh = glCreateShader(type);
    const GLchar *text = src;
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    if (source_out)
        *source_out = src;
    else
        free(src);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[8192];
        glGetShaderInfoLog(sh, sizeof(log), NULL, log);
        DIRT_ERROR("shader glsl/%s failed to compile:\n%s", path, log);
        log_file_table(&files);
        glDeleteShader(sh);
        return 0;
    }
    gl_label(GL_SHADER, sh, "%s", path);
    return sh;
}

GLuint gl_program_create(const char *label, const char *const *paths,
                         const glsl_define *defines, size_t num_defines)
{
    GLuint shaders[6] = {0};
    char *sources[6] = {0};
    size_t n = 0;
    GLuint prog = glCreateProgram();
    for (; paths[n]; n++) {
        if (n >= 6) {
            DIRT_ERROR("program %s: too many stages", label);
            goto error;
        }
        shaders[n] = compile_stage(paths[n], defines, num_defines, &sources[n]);
        if (!shaders[n])
            goto error;
        glAttachShader(prog, shaders[n]);
    }
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[8192];
        glGetProgramInfoLog(prog, sizeof(log), NULL, log);
        DIRT_ERROR("program %s failed to link:\n%s", label, log);
        goto error;
    }
    for (size_t i = 0; i < n; i++) {
        glDetachShader(prog, shaders[i]);
        glDeleteShader(shaders[i]);
    }
    gl_label(GL_PROGRAM, prog, "%s", label);
    gl_check_program(prog, label, sources, (int)n);
    for (size_t i = 0; i < 6; i++)
        free(sources[i]);
    return prog;
error:
    for (size_t i = 0; i < 6; i++) {
        if (shaders[i])
            glDeleteShader(shaders[i]);
        free(sources[i]);
    }
    glDeleteProgram(prog);
    return 0;
}

GLuint gl_program_compute(const char *path, const glsl_define *defines, size_t num_defines)
{
    const char *paths[] = {path, NULL};
    return gl_program_create(path, paths, defines, num_defines);
}

void gl_dispatch_rays(GLuint batch, uint32_t count, uint32_t min_groups)
{
    if (batch) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAY_BATCH, batch);
        glUniform1i(DIRT_LOC_RAY_BATCH, 1);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, batch);
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        return;
    }
    glUniform1i(DIRT_LOC_RAY_BATCH, 0);
    uint32_t groups = DIRT_GROUPS(count);
    glDispatchCompute(groups > min_groups ? groups : min_groups, 1, 1);
}

void gl_dispatch_rows(size_t invocations)
{
    size_t groups = DIRT_GROUPS(invocations);
    if (!groups)
        return;
    size_t rows = (groups + DIRT_GROUPS_ROW - 1) / DIRT_GROUPS_ROW;
    glDispatchCompute((GLuint)(groups < DIRT_GROUPS_ROW ? groups : DIRT_GROUPS_ROW),
                      (GLuint)rows, 1);
}

void gl_program_destroy(GLuint *program)
{
    if (*program)
        glDeleteProgram(*program);
    *program = 0;
}
