/* GPU timer queries plus a CPU glFinish timer. */
#include "gl/gl.h"

#include <string.h>

#include "dirt/clock.h"

/* Software renderers (llvmpipe, softpipe) answer GL_TIME_ELAPSED without
 * timing rasterization; their GPU times are reported as unavailable. */
static bool software_renderer(void)
{
    const char *r = (const char *)glGetString(GL_RENDERER);
    return r && (strstr(r, "llvmpipe") || strstr(r, "softpipe"));
}

bool gl_timer_init(gl_timer *t, bool cpu_finish, const char *label)
{
    *t = (gl_timer){.cpu_finish = cpu_finish, .gpu_ms = -1, .cpu_ms = -1,
                    .gpu_unreliable = software_renderer()};
    glCreateQueries(GL_TIME_ELAPSED, 1, &t->query);
    if (!t->query)
        return gl_check("glCreateQueries");
    if (label)
        gl_label(GL_QUERY, t->query, "%s", label);
    return true;
}

void gl_timer_begin(gl_timer *t)
{
    if (t->cpu_finish) {
        glFinish();
        t->cpu_start = dirt_clock_ms();
    }
    glBeginQuery(GL_TIME_ELAPSED, t->query);
    t->running = true;
}

void gl_timer_end(gl_timer *t)
{
    if (!t->running)
        return;
    glEndQuery(GL_TIME_ELAPSED);
    t->running = false;
    if (t->cpu_finish) {
        glFinish();
        t->cpu_ms = dirt_clock_ms() - t->cpu_start;
    }
    GLuint64 ns = 0;
    glGetQueryObjectui64v(t->query, GL_QUERY_RESULT, &ns);
    t->gpu_ms = t->gpu_unreliable ? -1 : (double)ns * 1e-6;
}

void gl_timer_release(gl_timer *t)
{
    if (t->query)
        glDeleteQueries(1, &t->query);
    t->query = 0;
}
