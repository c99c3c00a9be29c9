/* Region timers with the GPU's one clock (dirt_gpu_clock). */
#include "gl/gl.h"

#include "dirt/clock.h"

bool gl_timer_init(gl_timer *t, dirt_gpu *gpu, const char *label)
{
    *t = (gl_timer){.clock = dirt_gpu_clock(gpu), .ms = -1};
    if (t->clock != DIRT_CLOCK_GPU)
        return true;
    glCreateQueries(GL_TIME_ELAPSED, 1, &t->query);
    if (!t->query) {
        gl_check("glCreateQueries");
        DIRT_ERROR("could not create a GL_TIME_ELAPSED query%s%s", label ? " for " : "",
                   label ? label : "");
        return false;
    }
    if (label)
        gl_label(GL_QUERY, t->query, "%s", label);
    return true;
}

void gl_timer_begin(gl_timer *t)
{
    if (t->clock == DIRT_CLOCK_GPU) {
        glBeginQuery(GL_TIME_ELAPSED, t->query);
    } else {
        glFinish();
        t->cpu_start = dirt_clock_ms();
    }
    t->running = true;
}

void gl_timer_end(gl_timer *t)
{
    if (!t->running)
        return;
    t->running = false;
    if (t->clock == DIRT_CLOCK_GPU) {
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(t->query, GL_QUERY_RESULT, &ns);
        t->ms = (double)ns * 1e-6;
    } else {
        glFinish();
        t->ms = dirt_clock_ms() - t->cpu_start;
    }
}

void gl_timer_release(gl_timer *t)
{
    if (t->query)
        glDeleteQueries(1, &t->query);
    t->query = 0;
}
