/* Region timers with the GPU's one clock (dirt_gpu_clock); with the GPU
 * clock, a ring of time queries per timer so that ending a region need not
 * wait for its result (gl.h). */
#include "gl/gl.h"

#include "dirt/clock.h"

bool gl_timer_init(gl_timer *t, dirt_gpu *gpu, const char *label)
{
    *t = (gl_timer){.gpu = gpu, .clock = dirt_gpu_clock(gpu), .ms = -1};
    if (t->clock != DIRT_CLOCK_GPU)
        return true;
    glCreateQueries(GL_TIME_ELAPSED, GL_TIMER_RING, t->queries);
    for (int i = 0; i < GL_TIMER_RING; i++) {
        if (!t->queries[i]) {
            gl_check("glCreateQueries");
            DIRT_ERROR("could not create GL_TIME_ELAPSED queries%s%s", label ? " for " : "",
                       label ? label : "");
            glDeleteQueries(GL_TIMER_RING, t->queries);
            for (int k = 0; k < GL_TIMER_RING; k++)
                t->queries[k] = 0;
            return false;
        }
        if (label)
            gl_label(GL_QUERY, t->queries[i], "%s [%d]", label, i);
    }
    return true;
}

/* What harvest_oldest did. */
enum harvest { NOT_READ, DISCARDED, REPORTED };

/* Reads the oldest result in flight. `check`: ask GL_QUERY_RESULT_AVAILABLE
 * first, and when it is false and !wait, read nothing. A read made while
 * the result was not available, or without asking, waits for the GPU and
 * is counted. The result is added to *ms unless it is to be discarded. */
static enum harvest harvest_oldest(gl_timer *t, bool check, bool wait, double *ms)
{
    GLuint q = t->queries[t->oldest];
    bool waits = true;
    if (check) {
        GLint available = GL_FALSE;
        glGetQueryObjectiv(q, GL_QUERY_RESULT_AVAILABLE, &available);
        waits = available == GL_FALSE;
        if (waits && !wait)
            return NOT_READ;
    }
    GLuint64 ns = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
    dirt_gpu_query_counts *c = &t->gpu->queries;
    c->harvested++;
    if (waits)
        c->waits++;
    t->oldest = (t->oldest + 1) % GL_TIMER_RING;
    t->pending--;
    if (t->discard > 0) {
        t->discard--;
        return DISCARDED;
    }
    *ms += (double)ns * 1e-6;
    return REPORTED;
}

void gl_timer_begin(gl_timer *t)
{
    if (t->running)
        return;
    if (t->clock == DIRT_CLOCK_GPU) {
        if (t->pending == GL_TIMER_RING) {
            t->gpu->queries.ring_waits++;
            if (harvest_oldest(t, true, true, &t->held_ms) == REPORTED)
                t->held = true;
        }
        glBeginQuery(GL_TIME_ELAPSED, t->queries[(t->oldest + t->pending) % GL_TIMER_RING]);
    } else {
        glFinish();
        t->cpu_start = dirt_clock_ms();
    }
    t->running = true;
}

/* Ends the running query (GPU clock): it joins the ones in flight. */
static void end_query(gl_timer *t)
{
    glEndQuery(GL_TIME_ELAPSED);
    t->pending++;
    t->gpu->queries.issued++;
    t->running = false;
}

static void end_cpu(gl_timer *t)
{
    glFinish();
    t->ms = dirt_clock_ms() - t->cpu_start;
    t->running = false;
}

void gl_timer_end(gl_timer *t)
{
    if (!t->running)
        return;
    if (t->clock != DIRT_CLOCK_GPU) {
        end_cpu(t);
        return;
    }
    end_query(t);
    double ms = t->held_ms;
    t->held_ms = 0;
    t->held = false;
    while (t->pending > 1) /* earlier asynchronous ends' results, in order */
        harvest_oldest(t, true, true, &ms);
    harvest_oldest(t, false, true, &ms); /* this region's: waits */
    t->ms = ms;
}

void gl_timer_end_async(gl_timer *t)
{
    if (!t->running)
        return;
    if (t->clock != DIRT_CLOCK_GPU) {
        end_cpu(t);
        return;
    }
    end_query(t);
    double ms = t->held_ms;
    t->held_ms = 0;
    t->held = false;
    while (t->pending > 0 && harvest_oldest(t, true, false, &ms) != NOT_READ) {
    }
    t->ms = ms;
}

int gl_timer_drain(gl_timer *t, double *ms)
{
    *ms = 0;
    if (t->clock != DIRT_CLOCK_GPU)
        return 0;
    int reported = t->held ? 1 : 0;
    *ms = t->held_ms;
    t->held_ms = 0;
    t->held = false;
    while (t->pending > 0)
        reported += harvest_oldest(t, true, true, ms) == REPORTED;
    return reported;
}

int gl_timer_pending(const gl_timer *t)
{
    return t->pending;
}

void gl_timer_discard(gl_timer *t)
{
    if (t->clock != DIRT_CLOCK_GPU)
        return;
    t->discard = t->pending;
    t->held_ms = 0;
    t->held = false;
}

void gl_timer_release(gl_timer *t)
{
    if (t->running && t->clock == DIRT_CLOCK_GPU)
        end_query(t);
    if (t->gpu)
        t->gpu->queries.dropped += (uint64_t)t->pending;
    t->pending = 0;
    t->discard = 0;
    t->running = false;
    if (t->queries[0])
        glDeleteQueries(GL_TIMER_RING, t->queries);
    for (int i = 0; i < GL_TIMER_RING; i++)
        t->queries[i] = 0;
}

dirt_gpu_query_counts dirt_gpu_queries(const dirt_gpu *gpu)
{
    return gpu->queries;
}

uint64_t dirt_gpu_query_waits(const dirt_gpu *gpu)
{
    return gpu->queries.waits;
}
