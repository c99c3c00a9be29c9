/* DIRT Trace pass host side: batches of rays through the built structure. */
#include <stdlib.h>
#include <string.h>

#include "dirt/ads_internal.h"

_Static_assert(sizeof(dirt_ray) == sizeof(struct dirt_gpu_ray), "ray layout");
_Static_assert(sizeof(dirt_hit) == sizeof(struct dirt_gpu_hit), "hit layout");

static bool ensure(dirt_ads *a, GLuint *buf, size_t *cap, size_t size, bool readback,
                   const char *label)
{
    if (*buf && *cap >= size)
        return true;
    gl_buffer_destroy(buf);
    *buf = gl_buffer_create(a->gpu, size, NULL, readback, label);
    *cap = *buf ? size : 0;
    return *buf != 0;
}

bool dirt_ads_trace(dirt_ads *a, const dirt_ray *rays, size_t count, dirt_hit *hits,
                    const dirt_trace_opts *opts_in, dirt_trace_stats *stats)
{
    dirt_trace_opts opts = opts_in ? *opts_in : (dirt_trace_opts){0};
    if (stats)
        *stats = (dirt_trace_stats){.rays = count, .gpu_ms = -1, .cpu_ms = -1};
    if (!count)
        return true;
    if (count > UINT32_MAX / 2) {
        DIRT_ERROR("too many rays in one batch (%zu)", count);
        return false;
    }
    size_t bytes = count * sizeof(dirt_ray);
    if (!ensure(a, &a->rays, &a->rays_size, bytes, false, "dirt rays") ||
        !ensure(a, &a->hits, &a->hits_size, bytes, true, "dirt hits"))
        return false;
    gl_group_push("dirt trace");
    glNamedBufferSubData(a->rays, 0, (GLsizeiptr)bytes, rays);
    static const uint32_t zero = 0;
    glClearNamedBufferSubData(a->counters, GL_R32UI, 8, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                              &zero);
    ads_bind_all(a);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, a->rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, a->hits);
    glUseProgram(a->prog_trace);
    glUniform1ui(0, (GLuint)count);
    glUniform1i(1, opts.hiz_levels > 0 ? opts.hiz_levels - 1 : -1);
    glUniform1i(2, opts.any_hit ? 1 : 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    a->trace_timer.cpu_finish = a->opts.cpu_timing;
    gl_timer_begin(&a->trace_timer);
    glDispatchCompute((GLuint)((count + 63) / 64), 1, 1);
    gl_timer_end(&a->trace_timer);
    glUseProgram(0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    struct dirt_gpu_ads_counters c;
    bool ok = gl_buffer_read(a->hits, 0, bytes, hits) &&
              gl_buffer_read(a->counters, 0, sizeof(c), &c);
    gl_group_pop();
    if (ok && stats) {
        stats->aborted = c.fill.z;
        stats->gpu_ms = a->trace_timer.gpu_ms;
        stats->cpu_ms = a->trace_timer.cpu_ms;
    }
    if (ok && c.fill.z)
        DIRT_WARN("%u of %zu rays ran out of march steps", c.fill.z, count);
    return ok && gl_check("dirt trace");
}
