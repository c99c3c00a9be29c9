/* The MMRT A-buffer as the integrator's tracer (views/tracer.h): the
 * Trace -> Fetch -> Shade frame graph of the path tracer traced through the
 * A-buffer. MMRT has no Fetch: the "fetch" turns a hit's data node into the
 * shading point (glsl/mmrt/to_gpoint.comp). MMRT accepts any fragment
 * within the thickness of the ray's depth, so rays must start clear of the
 * surface they leave, and shadow rays stop clear of the light, by more than
 * the thickness in depth in every view: the tracer's surface_offset
 * (PT_MMRT_OFFSET_THICKNESSES thicknesses) makes Shade start them that far
 * off the surface along its normal and end shadow rays that far off the
 * emitter along its normal (views/tracer.h). Before every trace
 * glsl/mmrt/pt_rays.comp counts the batch's active rays. */
#include <stddef.h>
#include <stdlib.h>

#include "common/mmrt_pt_layout.h"
#include "gl/program.h"
#include "mmrt_internal.h"

/* Surface offset, in thicknesses. Along the normal, 3 thicknesses are at
 * least 3 x 0.577 = 1.7 thicknesses in depth in a 90-degree cube face (the
 * view axis is within 54.7 degrees of any view ray) and more in the
 * camera's narrower view; a planar surface is never within the thickness of
 * a ray leaving it, at any angle. (Moved 3 thicknesses along the ray
 * instead, as before, a ray leaving at under 19.5 degrees was still within
 * one thickness of its surface in depth in a view along the normal: the
 * Cornell box's shadow rays below 10 degrees of elevation were 30 %
 * falsely occluded, by their own wall or by the light.) */
#define PT_MMRT_OFFSET_THICKNESSES 3.0f

struct mmrt_tracer {
    dirt_gpu *gpu;
    GLuint prog_rays;
    gl_split_program prog_gpoint;  /* for the layout of the vertices */
    GLuint counts;            /* dirt_mmrt_pt_counts */
    dirt_mmrt *mmrt;
    dirt_mmrt_trace_opts opts;
    uint32_t calls;           /* traces since the last restart (jitter seed) */
    uint32_t sample_calls;    /* `calls` when the sample's first chunk began */
    uint32_t first_ray;       /* begin_chunk: pixel of the chunk's ray 0 */
    float offset;             /* world distance */
    dirt_tracer tracer;
};
typedef struct mmrt_tracer pt_mmrt;

void mmrt_tracer_release(dirt_mmrt *mmrt)
{
    pt_mmrt *s = mmrt->tracer;
    if (!s)
        return;
    gl_program_destroy(&s->prog_rays);
    gl_split_program_destroy(&s->prog_gpoint);
    gl_buffer_destroy(&s->counts);
    free(s);
    mmrt->tracer = NULL;
}

/* The tracer's state kept in the dirt_mmrt (created on first use). */
static pt_mmrt *get_state(dirt_mmrt *mmrt)
{
    if (mmrt->tracer)
        return mmrt->tracer;
    pt_mmrt *s = calloc(1, sizeof(*s));
    if (!s) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    mmrt->tracer = s;
    s->gpu = mmrt->gpu;
    s->mmrt = mmrt;
    s->prog_rays = gl_program_compute("mmrt/pt_rays.comp", NULL, 0);
    s->counts = gl_buffer_create(s->gpu, sizeof(struct dirt_mmrt_pt_counts), NULL, true,
                                 "mmrt pt counts");
    if (!s->prog_rays || !s->counts) {
        mmrt_tracer_release(mmrt);
        return NULL;
    }
    return s;
}

static bool mmrt_tech_trace(void *self, uint32_t rays, uint32_t hits, uint32_t count,
                            unsigned flags)
{
    pt_mmrt *s = self;
    (void)flags;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    gl_group_push("mmrt pt ray count");
    /* The count reads the counters the build or the last trace wrote, and
     * its atomics follow the last count's. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(s->prog_rays);
    glUniform1ui(DIRT_LOC_MMRT_PT_RAYS_COUNT, count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_PT_COUNTS, s->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_COUNTERS, g.counters);
    gl_dispatch_rays(s->opts.batch, count, 1); /* invocation 0 always runs */
    glUseProgram(0);
    gl_group_pop();
    /* Any hit: MMRT's closest hit answers "something in [tmin, tmax]" too. */
    dirt_mmrt_trace_opts o = s->opts;
    o.seed = s->opts.seed + s->calls++ * 0x9E3779B9u;
    o.first_ray = s->first_ray;
    return dirt_mmrt_trace(s->mmrt, rays, hits, count, &o, NULL);
}

static void mmrt_tech_set_batch(void *self, uint32_t batch)
{
    pt_mmrt *s = self;
    s->opts.batch = batch;
}

static void mmrt_tech_set_alpha(void *self, const dirt_trace_alpha *alpha)
{
    pt_mmrt *s = self;
    s->opts.alpha = alpha ? *alpha : (dirt_trace_alpha){0};
}

static bool mmrt_tech_fetch(void *self, uint32_t rays, uint32_t hits, uint32_t count,
                            uint32_t gpoints, uint32_t slot)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    const char *paths[] = {"mmrt/to_gpoint.comp", NULL};
    if (!mmrt_program(s->mmrt, &s->prog_gpoint, "mmrt/to_gpoint.comp", paths, NULL, 0,
                      MMRT_ARR(MMRT_VERTICES) | MMRT_ARR(MMRT_DATA)))
        return false;
    gl_group_push("mmrt pt data node to shading point");
    /* The hits come from the trace; the ring's slot was read by Shade; the
     * data nodes come from the build's shaders (mmrt_split_barriers). */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | mmrt_split_barriers(s->mmrt));
    glUseProgram(s->prog_gpoint.id);
    glUniform1ui(DIRT_LOC_MMRT_TO_GPOINT_COUNT, count);
    glUniform1ui(DIRT_LOC_MMRT_TO_GPOINT_SLOT, slot);
    mmrt_bind_geometry(s->mmrt);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_VIEWS, g.views);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_GPOINTS, gpoints);
    gl_split_bind(&s->mmrt->data);
    gl_dispatch_rays(s->opts.batch, count, 0);
    glUseProgram(0);
    gl_group_pop();
    return true;
}

/* Only the two arrays Shade reads (dirt_mmrt_bind binds the whole
 * structure). */
static void mmrt_tech_bind_geometry(void *self)
{
    pt_mmrt *s = self;
    mmrt_bind_geometry(s->mmrt);
}

static void mmrt_tech_reset_counts(void *self)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    static const uint32_t zero = 0;
    glClearNamedBufferData(s->counts, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    /* the trace counters (the build's stay) */
    glClearNamedBufferSubData(g.counters, GL_R32UI, offsetof(struct dirt_mmrt_gpu_counters, trace),
                              sizeof(struct dirt_mmrt_gpu_counters) -
                                  offsetof(struct dirt_mmrt_gpu_counters, trace),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

/* A new accumulation: the linear march jitter sequence starts again. */
static void mmrt_tech_restart(void *self)
{
    pt_mmrt *s = self;
    s->calls = 0;
    s->sample_calls = 0;
    s->first_ray = 0;
}

/* Every chunk of a sample replays the sample's seed sequence (from the
 * `calls` of its first chunk), with its rays keyed by pixel. */
static void mmrt_tech_begin_chunk(void *self, uint32_t first)
{
    pt_mmrt *s = self;
    if (first == 0)
        s->sample_calls = s->calls;
    else
        s->calls = s->sample_calls;
    s->first_ray = first;
}

static bool mmrt_tech_read_counts(void *self, uint64_t *rays, uint64_t *aborted)
{
    pt_mmrt *s = self;
    dirt_mmrt_gl g;
    dirt_mmrt_gl_buffers(s->mmrt, &g);
    struct dirt_mmrt_pt_counts c;
    struct dirt_mmrt_gpu_counters mc;
    if (!gl_buffer_read(s->counts, 0, sizeof(c), &c) ||
        !gl_buffer_read(g.counters, 0, sizeof(mc), &mc))
        return false;
    *rays = c.counts.x;
    *aborted = (uint64_t)c.counts.y + mc.trace.w; /* + the last trace's */
    return true;
}

const dirt_tracer *dirt_mmrt_tracer(dirt_mmrt *mmrt, const dirt_mmrt_trace_opts *opts)
{
    if (!mmrt->built) {
        DIRT_ERROR("MMRT tracer requested before a successful dirt_mmrt_build");
        return NULL;
    }
    pt_mmrt *s = get_state(mmrt);
    if (!s)
        return NULL;
    static const dirt_mmrt_trace_opts defaults = {0};
    s->opts = opts ? *opts : defaults;
    s->offset = PT_MMRT_OFFSET_THICKNESSES * dirt_mmrt_thickness(mmrt, &s->opts);
    s->tracer = (dirt_tracer){
        .name = "mmrt",
        .self = s,
        .trace = mmrt_tech_trace,
        .visibility = NULL,
        .fetch = mmrt_tech_fetch,
        .bind_geometry = mmrt_tech_bind_geometry,
        .reset_counts = mmrt_tech_reset_counts,
        .read_counts = mmrt_tech_read_counts,
        .restart = mmrt_tech_restart,
        .begin_chunk = mmrt_tech_begin_chunk,
        .set_alpha = mmrt_tech_set_alpha,
        .set_batch = mmrt_tech_set_batch,
        .views = &mmrt->set,
        .vertices_split = mmrt->vertices.layout,
        .prim_material_split = mmrt->materials.layout,
        .bytes_extra = sizeof(struct dirt_mmrt_pt_counts),
        .surface_offset = s->offset,
    };
    return &s->tracer;
}
