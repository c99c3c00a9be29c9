/* MMRT trace pass host side: batches of rays through the built A-buffer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/program.h"
#include "mmrt_internal.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */

/* Default thickness: this fraction of the scene's bounding-box diagonal. */
#define MMRT_DEFAULT_THICKNESS 0.002f
/* Linear marching: the demo's default samples per view. */
#define MMRT_DEFAULT_SAMPLES 30

float dirt_mmrt_thickness(const dirt_mmrt *m, const dirt_mmrt_trace_opts *o)
{
    if (o->thickness > 0)
        return o->thickness;
    if (o->thickness < 0)
        return 0.0f;
    return MMRT_DEFAULT_THICKNESS * m->scene_diagonal;
}

bool dirt_mmrt_trace(dirt_mmrt *m, GLuint rays, GLuint hits, uint32_t count,
                     const dirt_mmrt_trace_opts *opts_in, dirt_mmrt_trace_stats *stats)
{
    dirt_mmrt_trace_opts o = opts_in ? *opts_in : (dirt_mmrt_trace_opts){0};
    float thickness = dirt_mmrt_thickness(m, &o);
    if (stats)
        *stats = (dirt_mmrt_trace_stats){.rays = count, .thickness = thickness,
                                         .ms = -1, .clock = DIRT_CLOCK_NONE};
    if (!m->built) {
        DIRT_ERROR("mmrt trace before a successful build");
        return false;
    }
    if (o.march != DIRT_MMRT_MARCH_HIZ && o.march != DIRT_MMRT_MARCH_LINEAR) {
        DIRT_ERROR("unknown march mode %d", (int)o.march);
        return false;
    }
    if (!count)
        return true;
    int samples = o.samples == 0 ? MMRT_DEFAULT_SAMPLES : o.samples;
    int top = o.hiz_levels > 0 ? o.hiz_levels - 1 : DIRT_MAX_MIP_LEVELS;

    /* Alpha-tested traversal: its own build of the shader. */
    if (o.alpha.materials) {
        glsl_define def = {"DIRT_TRACE_ALPHA", "1"};
        const char *paths[] = {"mmrt/trace.comp", NULL};
        if (!mmrt_program_extra(m, &m->prog_trace_alpha, "mmrt/trace.comp (alpha)", paths,
                                &def, 1, MMRT_ARR(MMRT_VERTICES) | MMRT_ABUFFER,
                                o.alpha.texels))
            return false;
    }
    gl_group_push("mmrt trace");
    /* The clear follows the last trace's atomics; the trace reads the
     * A-buffer the build's shaders wrote (image loads once split:
     * mmrt_split_barriers), and rays a shader may have made. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    mmrt_split_barriers(m));
    static const uint32_t zero = 0;
    glClearNamedBufferSubData(m->counters, GL_R32UI, 16, 32, GL_RED_INTEGER, GL_UNSIGNED_INT,
                              &zero);
    dirt_mmrt_bind(m);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    glUseProgram(o.alpha.materials ? m->prog_trace_alpha.id : m->prog_trace.id);
    glUniform1ui(DIRT_LOC_MMRT_TRACE_COUNT, count);
    glUniform1i(DIRT_LOC_MMRT_TRACE_MARCH, o.march == DIRT_MMRT_MARCH_HIZ ? 0 : 1);
    glUniform1i(DIRT_LOC_MMRT_TRACE_SAMPLES, samples);
    glUniform1i(DIRT_LOC_MMRT_TRACE_TOP_LEVEL, top);
    glUniform1f(DIRT_LOC_MMRT_TRACE_THICKNESS, thickness);
    glUniform1ui(DIRT_LOC_MMRT_TRACE_SEED, o.seed);
    glUniform1ui(DIRT_LOC_MMRT_TRACE_FIRST_RAY, o.first_ray);
    glUniform1i(DIRT_LOC_MMRT_TRACE_STATS, o.count ? 1 : 0);
    glUniform1i(DIRT_LOC_MMRT_TRACE_ALL_VIEWS, o.all_views ? 1 : 0);
    /* Alpha test: the integrator's tables (the data nodes hold the rest). */
    if (o.alpha.materials) {
        glUniform1i(DIRT_LOC_ALPHA_ENABLED, 1);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_MATERIALS, o.alpha.materials);
        gl_split_bind(o.alpha.texels);
        glUniform4ui(DIRT_LOC_ALPHA_KEY, o.alpha.seed, o.alpha.sample, o.alpha.bounce,
                     o.alpha.dim);
        glUniform1ui(DIRT_LOC_ALPHA_FIRST_PIXEL, o.alpha.first_pixel);
    }
    /* Timed only when stats are asked for: a caller timing its own pass (a
     * frame graph) may have a time query active, and they do not nest. */
    if (stats)
        gl_timer_begin(&m->trace_timer);
    gl_dispatch_rays(o.batch, count, 0);
    if (stats)
        gl_timer_end(&m->trace_timer);
    glUseProgram(0);
    bool ok = true;
    if (stats) {
        struct dirt_mmrt_gpu_counters c;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the trace's counters */
        ok = gl_buffer_read(m->counters, 0, sizeof(c), &c);
        if (ok) {
            stats->hits = o.count ? c.trace.x : 0;
            stats->steps = c.trace.y;
            stats->nodes_visited = c.trace.z;
            stats->pixels_tested = c.trace2.x;
            stats->aborted = c.trace.w;
            stats->ms = m->trace_timer.ms;
            stats->clock = m->trace_timer.clock;
            if (c.trace.w)
                DIRT_WARN("mmrt trace: %u of %u rays ran out of march steps", c.trace.w, count);
        }
    }
    gl_group_pop();
    return ok && gl_check("mmrt trace");
}

bool dirt_mmrt_trace_cpu(dirt_mmrt *m, const dirt_ray *rays, size_t count, dirt_hit *hits,
                         const dirt_mmrt_trace_opts *opts, dirt_mmrt_trace_stats *stats)
{
    dirt_mmrt_trace_stats local;
    dirt_mmrt_trace_stats *st = stats ? stats : &local;
    if (count > UINT32_MAX / 2) {
        DIRT_ERROR("too many rays in one batch (%zu)", count);
        return false;
    }
    if (!count) {
        *st = (dirt_mmrt_trace_stats){.ms = -1, .clock = DIRT_CLOCK_NONE};
        return true;
    }
    size_t bytes = count * sizeof(dirt_ray);
    if (!gl_buffer_ensure(m->gpu, &m->rays, &m->rays_size, bytes, false, "mmrt rays") ||
        !gl_buffer_ensure(m->gpu, &m->hits, &m->hits_size, bytes, true, "mmrt hits"))
        return false;
    glNamedBufferSubData(m->rays, 0, (GLsizeiptr)bytes, rays);
    /* With stats (always here) dirt_mmrt_trace fenced its writes for readback. */
    if (!dirt_mmrt_trace(m, m->rays, m->hits, (uint32_t)count, opts, st))
        return false;
    if (!gl_buffer_read(m->hits, 0, bytes, hits))
        return false;
    if (!(opts && opts->count)) {
        st->hits = 0;
        for (size_t i = 0; i < count; i++)
            st->hits += hits[i].prim != DIRT_HIT_NONE;
    }
    return true;
}
