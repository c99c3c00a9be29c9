/* The GPU path tracer's MMRT technique (integrator/pt_technique.h): the
 * Trace -> Fetch -> Shade frame graph of gpu_pt.c traced through the MMRT
 * A-buffer. MMRT has no Fetch: the "fetch" pass turns a hit's data node into
 * the shading point (glsl/mmrt/to_gpoint.comp). Every trace first copies its
 * batch with the start (and, for shadow rays, the end) moved by
 * PT_MMRT_OFFSET_THICKNESSES thicknesses along the ray (glsl/mmrt/
 * pt_rays.comp), so that a ray does not hit the surface it leaves: MMRT
 * accepts any fragment within the thickness of the ray's depth. */
#include <stdlib.h>

#include "common/mmrt_pt_layout.h"
#include "gl/program.h"
#include "integrator/pt_technique.h"
#include "mmrt_internal.h"

_Static_assert(sizeof(struct dirt_mmrt_pt_counts) == 16, "mmrt pt counts layout");

/* Ray start offset, in thicknesses (the mmrt_trace test starts its bounce
 * rays 3 thicknesses off the surface). */
#define PT_MMRT_OFFSET_THICKNESSES 3.0f

typedef struct pt_mmrt {
    dirt_gpu *gpu;
    GLuint prog_rays, prog_gpoint;
    GLuint rays;              /* offset copy of the batch being traced */
    size_t rays_cap;          /* in rays */
    GLuint counts;            /* dirt_mmrt_pt_counts */
    /* set per render */
    dirt_mmrt *mmrt;
    uint32_t calls;           /* traces since the render began (jitter seed) */
    float offset;             /* world distance */
} pt_mmrt;

static void pt_mmrt_release(void *state)
{
    pt_mmrt *s = state;
    if (!s)
        return;
    gl_program_destroy(&s->prog_rays);
    gl_program_destroy(&s->prog_gpoint);
    gl_buffer_destroy(&s->rays);
    gl_buffer_destroy(&s->counts);
    free(s);
}

/* The technique's state kept in the dirt_pt (created on first use). */
static pt_mmrt *get_state(dirt_pt *pt)
{
    pt_tech_state *ts = dirt_pt_tech_state(pt);
    if (ts->state)
        return ts->state;
    pt_mmrt *s = calloc(1, sizeof(*s));
    if (!s) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    s->gpu = dirt_pt_gpu(pt);
    s->prog_rays = gl_program_compute("mmrt/pt_rays.comp", NULL, 0);
    s->prog_gpoint = gl_program_compute("mmrt/to_gpoint.comp", NULL, 0);
    s->counts = gl_buffer_create(s->gpu, sizeof(struct dirt_mmrt_pt_counts), NULL, true,
                                 "mmrt pt counts");
    if (!s->prog_rays || !s->prog_gpoint || !s->counts)
        goto error;
    ts->state = s;
    ts->release = pt_mmrt_release;
    return s;
error:
    pt_mmrt_release(s);
    return NULL;
}

static bool ensure_rays(pt_mmrt *s, size_t count)
{
    if (s->rays && s->rays_cap >= count)
        return true;
    gl_buffer_destroy(&s->rays);
    s->rays_cap = 0;
    s->rays = gl_buffer_create(s->gpu, (count ? count : 1) * sizeof(struct dirt_gpu_ray), NULL,
                               false, "mmrt pt offset rays");
    if (!s->rays)
        return false;
    s->rays_cap = count;
    return true;
}

static bool mmrt_tech_trace(void *self, const dirt_pt_opts *opts, GLuint rays, GLuint hits,
                            uint32_t count, bool any_hit, bool link)
{
    pt_mmrt *s = self;
    (void)link; /* no raster Fetch (refused before the render) */
    if (!ensure_rays(s, count))
        return false;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    gl_group_push("mmrt pt ray setup");
    glUseProgram(s->prog_rays);
    glUniform1ui(0, count);
    glUniform1f(1, s->offset);
    glUniform1i(2, any_hit ? 1 : 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_PT_RAYS_OUT, s->rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_PT_COUNTS, s->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_COUNTERS, g.counters);
    glDispatchCompute((count + 63) / 64 ? (count + 63) / 64 : 1, 1, 1);
    glUseProgram(0);
    gl_group_pop();
    /* Any hit: MMRT's closest hit answers "something in [tmin, tmax]" too. */
    dirt_mmrt_trace_opts o = opts->mmrt;
    o.seed = opts->mmrt.seed + s->calls++ * 0x9E3779B9u;
    return dirt_mmrt_trace(s->mmrt, s->rays, hits, count, &o, NULL);
}

static bool mmrt_tech_fetch(void *self, bool raster, GLuint rays, GLuint hits, uint32_t count,
                            GLuint gpoints, uint32_t slot)
{
    pt_mmrt *s = self;
    if (raster) {
        DIRT_ERROR("MMRT has no raster Fetch");
        return false;
    }
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    gl_group_push("mmrt pt data node to shading point");
    glUseProgram(s->prog_gpoint);
    glUniform1ui(0, count);
    glUniform1ui(1, slot);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_VERTICES, g.vertices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_GPOINTS, gpoints);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_DATA, g.data);
    if (count)
        glDispatchCompute((count + 63) / 64, 1, 1);
    glUseProgram(0);
    gl_group_pop();
    return true;
}

/* Only the two buffers Shade reads: dirt_mmrt_bind would also take binding
 * points of the model tables (20-22). */
static void mmrt_tech_bind_geometry(void *self)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_VERTICES, g.vertices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_PRIM_MATERIAL, g.materials);
}

static void mmrt_tech_reset_counts(void *self)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    static const uint32_t zero = 0;
    glClearNamedBufferData(s->counts, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    /* the trace counters (the build's stay) */
    glClearNamedBufferSubData(g.counters, GL_R32UI, 16, 32, GL_RED_INTEGER, GL_UNSIGNED_INT,
                              &zero);
}

static bool mmrt_tech_read_counts(void *self, uint64_t *rays, uint64_t *aborted)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    struct dirt_mmrt_pt_counts c;
    struct dirt_mmrt_gpu_counters mc;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!gl_buffer_read(s->counts, 0, sizeof(c), &c) ||
        !gl_buffer_read(g.counters, 0, sizeof(mc), &mc))
        return false;
    *rays = c.counts.x;
    *aborted = (uint64_t)c.counts.y + mc.trace.w; /* + the last trace's */
    return true;
}

bool dirt_pt_render_mmrt(dirt_pt *pt, dirt_mmrt *mmrt, const dirt_frame *frame,
                         const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                         dirt_pt_stats *stats)
{
    if (!mmrt->built) {
        DIRT_ERROR("MMRT path tracing before a successful dirt_mmrt_build");
        return false;
    }
    if (opts && opts->fetch == DIRT_FETCH_RASTER) {
        DIRT_ERROR("MMRT has no raster Fetch (its data nodes are the shading points)");
        return false;
    }
    pt_mmrt *s = get_state(pt);
    if (!s || !ensure_rays(s, (size_t)out->width * (size_t)out->height))
        return false;
    static const dirt_mmrt_trace_opts defaults = {0};
    s->mmrt = mmrt;
    s->calls = 0;
    s->offset = PT_MMRT_OFFSET_THICKNESSES *
                dirt_mmrt_thickness(mmrt, opts ? &opts->mmrt : &defaults);
    pt_technique tech = {
        .self = s,
        .name = "mmrt",
        .trace = mmrt_tech_trace,
        .visibility = NULL,
        .fetch = mmrt_tech_fetch,
        .bind_geometry = mmrt_tech_bind_geometry,
        .reset_counts = mmrt_tech_reset_counts,
        .read_counts = mmrt_tech_read_counts,
        .views = &mmrt->set,
        .bytes_extra = s->rays_cap * sizeof(struct dirt_gpu_ray) +
                       sizeof(struct dirt_mmrt_pt_counts),
    };
    const dirt_mmrt_stats *ms = &mmrt->stats;
    for (int i = 0; i < DIRT_MMRT_NUM_PASSES; i++) {
        double t = ms->gpu_ms[i] >= 0 ? ms->gpu_ms[i] : ms->cpu_ms[i];
        if (t > 0)
            tech.build_ms += t;
    }
    bool ok = dirt_pt_render_technique(pt, &tech, frame, cam, opts, out, stats);
    s->mmrt = NULL;
    return ok;
}
