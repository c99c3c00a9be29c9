/* GPU path tracer: the Trace -> Fetch -> Shade loop on a frame graph. */
#include "dirt/pathtrace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/ads_internal.h"
#include "dirt/clock.h"
#include "dirt/file.h"
#include "dirt/gpu_tables.h"
#include "dirt/integrator.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "graph/graph.h"
#include "integrator/pt_technique.h"

_Static_assert(sizeof(struct dirt_gpu_gpoint) == 64, "gpoint layout");
_Static_assert(sizeof(struct dirt_gpu_path) == 80, "path layout");
_Static_assert(sizeof(struct dirt_gpu_accum) == 48, "accum layout");

enum pass_kind { P_RAYGEN, P_TRACE, P_FETCH, P_SHADE, P_SHADOW, P_RESOLVE, P_ACCUM };

typedef struct pass_ctx {
    struct dirt_pt *pt;
    enum pass_kind kind;
    int k; /* path event */
} pass_ctx;

#define MAX_PASSES 512

struct dirt_pt {
    dirt_gpu *gpu;
    const dirt_scene *scene;
    GLuint prog_raygen, prog_shade, prog_ao, prog_resolve, prog_accum;
    /* per-pixel buffers */
    GLuint rays, hits, shadow_rays, shadow_hits, gpoints, paths, accum;
    size_t pixels;
    /* graph (rebuilt when the configuration changes) */
    fg_graph *graph;
    size_t g_pixels;
    int g_events;
    enum dirt_pt_mode g_mode;
    enum dirt_fetch_mode g_fetch;
    bool g_direct;
    pass_ctx ctx[MAX_PASSES];
    int num_ctx;
    /* render state read by the pass bodies */
    pt_technique *tech;
    dirt_gpu_model_tables tables;
    const dirt_pt_opts *opts;
    int width, height, bounces;
    uint32_t sample;
    float ao_distance;
    pt_tech_state tech_state; /* a technique's persistent state (MMRT's) */
};

pt_tech_state *dirt_pt_tech_state(dirt_pt *pt)
{
    return &pt->tech_state;
}

dirt_gpu *dirt_pt_gpu(const dirt_pt *pt)
{
    return pt->gpu;
}

dirt_pt *dirt_pt_create(dirt_gpu *gpu, const dirt_scene *scene)
{
    dirt_pt *pt = calloc(1, sizeof(*pt));
    if (!pt) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    pt->gpu = gpu;
    pt->scene = scene;
    glsl_define ao = {"DIRT_AO", "1"};
    pt->prog_raygen = gl_program_compute("integrator/raygen.comp", NULL, 0);
    pt->prog_shade = gl_program_compute("integrator/shade.comp", NULL, 0);
    pt->prog_ao = gl_program_compute("integrator/shade.comp", &ao, 1);
    pt->prog_resolve = gl_program_compute("integrator/resolve.comp", NULL, 0);
    pt->prog_accum = gl_program_compute("integrator/accumulate.comp", NULL, 0);
    if (!pt->prog_raygen || !pt->prog_shade || !pt->prog_ao || !pt->prog_resolve ||
        !pt->prog_accum) {
        dirt_pt_destroy(pt);
        return NULL;
    }
    return pt;
}

static void release_buffers(dirt_pt *pt)
{
    GLuint *b[] = {&pt->rays, &pt->hits, &pt->shadow_rays, &pt->shadow_hits,
                   &pt->gpoints, &pt->paths, &pt->accum};
    for (size_t i = 0; i < sizeof(b) / sizeof(b[0]); i++)
        gl_buffer_destroy(b[i]);
    pt->pixels = 0;
}

void dirt_pt_destroy(dirt_pt *pt)
{
    if (!pt)
        return;
    GLuint *p[] = {&pt->prog_raygen, &pt->prog_shade, &pt->prog_ao, &pt->prog_resolve,
                   &pt->prog_accum};
    for (size_t i = 0; i < sizeof(p) / sizeof(p[0]); i++)
        gl_program_destroy(p[i]);
    release_buffers(pt);
    dirt_gpu_model_tables_destroy(&pt->tables);
    fg_destroy(pt->graph);
    if (pt->tech_state.release)
        pt->tech_state.release(pt->tech_state.state);
    free(pt);
}

static bool ensure_buffers(dirt_pt *pt, size_t pixels)
{
    if (pt->pixels == pixels)
        return true;
    release_buffers(pt);
    pt->rays = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_ray), NULL, false,
                                "pt rays");
    pt->hits = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_hit), NULL, false,
                                "pt hits");
    pt->shadow_rays = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_ray), NULL,
                                       false, "pt shadow rays");
    pt->shadow_hits = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_hit), NULL,
                                       false, "pt shadow hits");
    pt->gpoints = gl_buffer_create(pt->gpu, 3 * pixels * sizeof(struct dirt_gpu_gpoint), NULL,
                                   false, "pt shading ring");
    pt->paths = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_path), NULL, false,
                                 "pt paths");
    pt->accum = gl_buffer_create(pt->gpu, pixels * sizeof(struct dirt_gpu_accum), NULL, true,
                                 "pt accumulation");
    if (!pt->rays || !pt->hits || !pt->shadow_rays || !pt->shadow_hits || !pt->gpoints ||
        !pt->paths || !pt->accum) {
        release_buffers(pt);
        return false;
    }
    pt->pixels = pixels;
    return true;
}

/* Uniforms of pt_common.glsl for event k; binds the model tables and the
 * technique's geometry. */
static void set_common(dirt_pt *pt, GLuint prog, int k)
{
    glUseProgram(prog);
    glUniform1ui(0, (GLuint)pt->pixels);
    glUniform1i(1, pt->width);
    glUniform1i(2, pt->height);
    glUniform1ui(3, pt->opts->seed);
    glUniform1ui(4, pt->sample);
    glUniform1ui(5, (GLuint)k);
    glUniform1ui(6, (GLuint)pt->bounces);
    glUniform1ui(7, (GLuint)(k % 3));
    glUniform3fv(8, 1, pt->opts->background);
    glUniform1f(9, pt->ao_distance);
    dirt_gpu_model_tables_bind(&pt->tables);
    pt->tech->bind_geometry(pt->tech->self);
}

static void bind(GLuint binding, GLuint buf)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buf);
}

static GLuint groups(size_t n)
{
    return (GLuint)((n + 63) / 64);
}

static bool exec_pass(fg_ctx *ctx, void *user)
{
    (void)ctx;
    pass_ctx *c = user;
    dirt_pt *pt = c->pt;
    switch (c->kind) {
    case P_RAYGEN:
        set_common(pt, pt->prog_raygen, 0);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_RAYS, pt->rays);
        glDispatchCompute(groups(pt->pixels), 1, 1);
        break;
    case P_TRACE:
        if (c->k == 1 && pt->g_direct)
            return pt->tech->visibility(pt->tech->self, pt->rays, pt->hits);
        return pt->tech->trace(pt->tech->self, pt->opts, pt->rays, pt->hits,
                               (uint32_t)pt->pixels, false, pt->g_fetch == DIRT_FETCH_RASTER);
    case P_FETCH:
        return pt->tech->fetch(pt->tech->self, pt->g_fetch == DIRT_FETCH_RASTER, pt->rays,
                               pt->hits, (uint32_t)pt->pixels, pt->gpoints, (uint32_t)(c->k % 3));
    case P_SHADE:
        set_common(pt, pt->g_mode == DIRT_PT_AO ? pt->prog_ao : pt->prog_shade, c->k);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_GPOINTS, pt->gpoints);
        bind(DIRT_BIND_HITS, pt->hits);
        bind(DIRT_BIND_RAYS, pt->rays);
        bind(DIRT_BIND_SHADOW_RAYS, pt->shadow_rays);
        glDispatchCompute(groups(pt->pixels), 1, 1);
        break;
    case P_SHADOW:
        return pt->tech->trace(pt->tech->self, pt->opts, pt->shadow_rays, pt->shadow_hits,
                               (uint32_t)pt->pixels, true, false);
    case P_RESOLVE:
        glUseProgram(pt->prog_resolve);
        glUniform1ui(0, (GLuint)pt->pixels);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_HITS, pt->shadow_hits);
        glDispatchCompute(groups(pt->pixels), 1, 1);
        break;
    case P_ACCUM:
        glUseProgram(pt->prog_accum);
        glUniform1ui(0, (GLuint)pt->pixels);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_ACCUM, pt->accum);
        glDispatchCompute(groups(pt->pixels), 1, 1);
        break;
    }
    glUseProgram(0);
    return true;
}

/* One graph of a sample: raygen, then per event k = 1..events trace, fetch,
 * shade, shadow trace, resolve; then accumulate. All buffers are imported
 * (they persist across samples); the structure's buffers are the
 * technique's and not declared. */
static bool make_graph(dirt_pt *pt, int events)
{
    fg_destroy(pt->graph);
    pt->graph = fg_create(pt->gpu);
    if (!pt->graph)
        return false;
    fg_graph *g = pt->graph;
    size_t px = pt->pixels;
    fg_res rays = fg_import_buffer(g, "rays", pt->rays, px * sizeof(struct dirt_gpu_ray));
    fg_res hits = fg_import_buffer(g, "hits", pt->hits, px * sizeof(struct dirt_gpu_hit));
    fg_res srays = fg_import_buffer(g, "shadow rays", pt->shadow_rays, px * sizeof(struct dirt_gpu_ray));
    fg_res shits = fg_import_buffer(g, "shadow hits", pt->shadow_hits, px * sizeof(struct dirt_gpu_hit));
    fg_res gpts = fg_import_buffer(g, "shading ring", pt->gpoints, 3 * px * sizeof(struct dirt_gpu_gpoint));
    fg_res paths = fg_import_buffer(g, "paths", pt->paths, px * sizeof(struct dirt_gpu_path));
    fg_res accum = fg_import_buffer(g, "accumulation", pt->accum, px * sizeof(struct dirt_gpu_accum));
    pt->num_ctx = 0;
#define ADD(kind_, k_)                                                                   \
    (pt->ctx[pt->num_ctx] = (pass_ctx){pt, (kind_), (k_)},                                \
     fg_add_pass(g, name, FG_COMPUTE, exec_pass, &pt->ctx[pt->num_ctx++]))
    char name[64];
    snprintf(name, sizeof(name), "raygen");
    fg_pass *p = ADD(P_RAYGEN, 0);
    fg_write(p, rays, FG_SSBO_WRITE);
    fg_write(p, paths, FG_SSBO_WRITE);
    for (int k = 1; k <= events; k++) {
        if (pt->num_ctx + 6 >= MAX_PASSES) {
            DIRT_ERROR("too many path events (%d)", events);
            return false;
        }
        if (k == 1 && pt->g_direct)
            snprintf(name, sizeof(name), "direct visibility");
        else
            snprintf(name, sizeof(name), "trace %d", k);
        p = ADD(P_TRACE, k);
        fg_read(p, rays, FG_SSBO_READ);
        fg_write(p, hits, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "fetch %d", k);
        p = ADD(P_FETCH, k);
        fg_read(p, rays, FG_SSBO_READ);
        fg_read(p, hits, FG_SSBO_READ);
        fg_use(p, gpts, FG_SSBO_READ, NULL);
        fg_write(p, gpts, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "shade %d", k);
        p = ADD(P_SHADE, k);
        fg_read(p, gpts, FG_SSBO_READ);
        fg_read(p, hits, FG_SSBO_READ);
        fg_use(p, paths, FG_SSBO_READ, NULL);
        fg_write(p, paths, FG_SSBO_WRITE);
        fg_write(p, rays, FG_SSBO_WRITE);
        fg_write(p, srays, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "shadow trace %d", k);
        p = ADD(P_SHADOW, k);
        fg_read(p, srays, FG_SSBO_READ);
        fg_write(p, shits, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "resolve %d", k);
        p = ADD(P_RESOLVE, k);
        fg_read(p, shits, FG_SSBO_READ);
        fg_use(p, paths, FG_SSBO_READ, NULL);
        fg_write(p, paths, FG_SSBO_WRITE);
    }
    snprintf(name, sizeof(name), "accumulate");
    p = ADD(P_ACCUM, 0);
    fg_read(p, paths, FG_SSBO_READ);
    fg_use(p, accum, FG_SSBO_READ, NULL);
    fg_write(p, accum, FG_SSBO_WRITE);
#undef ADD
    if (!fg_compile(g))
        return false;
    pt->g_pixels = px;
    pt->g_events = events;
    return true;
}

/* Sums the last execute's pass times into trace / fetch / shade. */
static void add_times(dirt_pt *pt, dirt_pt_stats *st)
{
    fg_stats s;
    if (!fg_get_stats(pt->graph, &s))
        return;
    for (int i = 0; i < s.num_passes; i++) {
        const fg_pass_stats *p = &s.passes[i];
        double ms = p->gpu_ms >= 0 ? p->gpu_ms : p->cpu_ms;
        if (ms < 0)
            continue;
        if (!strncmp(p->name, "trace", 5) || !strncmp(p->name, "shadow", 6))
            st->trace_ms += ms;
        else if (!strncmp(p->name, "fetch", 5))
            st->fetch_ms += ms;
        else
            st->shade_ms += ms;
    }
}

/* ---- The DIRT technique: the ads_* entry points of src/dirt ---- */

static bool dirt_tech_trace(void *self, const dirt_pt_opts *opts, GLuint rays, GLuint hits,
                            uint32_t count, bool any_hit, bool link)
{
    if (!any_hit)
        return ads_trace_gl(self, rays, hits, count, &opts->trace, link, NULL);
    dirt_trace_opts o = opts->trace;
    o.any_hit = true;
    return ads_trace_gl(self, rays, hits, count, &o, link, NULL);
}

static bool dirt_tech_visibility(void *self, GLuint rays, GLuint hits)
{
    return ads_visibility_gl(self, rays, hits);
}

static bool dirt_tech_fetch(void *self, bool raster, GLuint rays, GLuint hits, uint32_t count,
                            GLuint gpoints, uint32_t slot)
{
    return ads_fetch_gl(self, raster, rays, hits, count, gpoints, slot);
}

static void dirt_tech_bind_geometry(void *self)
{
    ads_bind_geometry(self);
}

static void dirt_tech_reset_counts(void *self)
{
    ads_reset_ray_count(self);
}

static bool dirt_tech_read_counts(void *self, uint64_t *rays, uint64_t *aborted)
{
    return ads_read_counts(self, rays, aborted);
}

bool dirt_pt_render(dirt_pt *pt, dirt_ads *ads, const dirt_frame *frame, const dirt_camera *cam,
                    const dirt_pt_opts *opts, dirt_image *out, dirt_pt_stats *stats)
{
    pt_technique tech = {
        .self = ads,
        .name = "dirt",
        .trace = dirt_tech_trace,
        .visibility = dirt_tech_visibility,
        .fetch = dirt_tech_fetch,
        .bind_geometry = dirt_tech_bind_geometry,
        .reset_counts = dirt_tech_reset_counts,
        .read_counts = dirt_tech_read_counts,
        .views = dirt_ads_views(ads),
    };
    const dirt_ads_stats *as = dirt_ads_get_stats(ads);
    for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++) {
        double ms = as->gpu_ms[i] >= 0 ? as->gpu_ms[i] : as->cpu_ms[i];
        if (ms > 0)
            tech.build_ms += ms;
    }
    return dirt_pt_render_technique(pt, &tech, frame, cam, opts, out, stats);
}

bool dirt_pt_render_technique(dirt_pt *pt, pt_technique *tech, const dirt_frame *frame,
                              const dirt_camera *cam, const dirt_pt_opts *opts_in, dirt_image *out,
                              dirt_pt_stats *stats)
{
    dirt_pt_opts opts = opts_in ? *opts_in : (dirt_pt_opts){0};
    if (opts.spp <= 0)
        opts.spp = 1;
    if (!opts.bounces_set && opts.bounces <= 0)
        opts.bounces = 4;
    if (opts.bounces < 0 || opts.bounces > 64) {
        DIRT_ERROR("bounces %d: must be in [0, 64]", opts.bounces);
        return false;
    }
    dirt_pt_stats local;
    dirt_pt_stats *st = stats ? stats : &local;
    *st = (dirt_pt_stats){0};
    double t0 = dirt_clock_ms();
    pt->tech = tech;
    pt->opts = &opts;
    pt->width = out->width;
    pt->height = out->height;
    pt->bounces = opts.bounces;
    pt->ao_distance = opts.ao_distance > 0 ? opts.ao_distance : INFINITY;
    size_t pixels = (size_t)out->width * (size_t)out->height;
    bool ok = false;
    dirt_area_lights area = {0};
    gl_group_push("dirt path tracer");
    if (!ensure_buffers(pt, pixels))
        goto done;
    if (!dirt_area_lights_build(&area, frame, dirt_scene_materials(pt->scene),
                                dirt_scene_num_materials(pt->scene)))
        goto done;
    /* Materials and textures are the scene's: uploaded once; lights and the
     * camera change per frame. */
    if (pt->tables.materials) {
        if (!dirt_gpu_model_tables_set_frame(pt->gpu, &pt->tables, frame, &area, cam)) {
            dirt_gpu_model_tables_destroy(&pt->tables);
            goto done;
        }
    } else if (!dirt_gpu_model_tables_create(pt->gpu, pt->scene, frame, &area, cam, NULL, 0,
                                             &pt->tables)) {
        goto done;
    }
    /* AO: one event (the first hit); path tracing: K + 1 (the last one only
     * gathers emission). */
    int events = opts.mode == DIRT_PT_AO ? 1 : opts.bounces + 1;
    if (opts.direct_visibility) {
        if (!tech->visibility) {
            DIRT_ERROR("direct visibility is not available with %s", tech->name);
            goto done;
        }
        const dirt_view_set *vs = tech->views;
        if (vs->camera_view < 0 || vs->views[vs->camera_view].width != out->width ||
            vs->views[vs->camera_view].height != out->height) {
            DIRT_ERROR("direct visibility needs a camera view of the image's size (%dx%d)",
                       out->width, out->height);
            goto done;
        }
    }
    if (!pt->graph || pt->g_pixels != pixels || pt->g_events != events ||
        pt->g_mode != opts.mode || pt->g_fetch != opts.fetch ||
        pt->g_direct != opts.direct_visibility) {
        pt->g_mode = opts.mode;
        pt->g_fetch = opts.fetch;
        pt->g_direct = opts.direct_visibility;
        if (!make_graph(pt, events))
            goto done;
    }
    static const float zero = 0.0f;
    glClearNamedBufferData(pt->accum, GL_R32F, GL_RED, GL_FLOAT, &zero);
    tech->reset_counts(tech->self);
    fg_exec_opts eo = {.cpu_timing = opts.cpu_timing, .validate = true};
    for (int s = 0; s < opts.spp; s++) {
        pt->sample = (uint32_t)s;
        if (!fg_execute(pt->graph, &eo))
            goto done;
        add_times(pt, st);
        if (opts.progress)
            opts.progress(opts.progress_user, s + 1, opts.spp);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    struct dirt_gpu_accum *sums = malloc(pixels * sizeof(*sums));
    if (!sums || !gl_buffer_read(pt->accum, 0, pixels * sizeof(*sums), sums)) {
        free(sums);
        DIRT_ERROR("could not read the image back");
        goto done;
    }
    float *albedo[3] = {dirt_image_find_channel(out, "albedo.R"),
                        dirt_image_find_channel(out, "albedo.G"),
                        dirt_image_find_channel(out, "albedo.B")};
    float *normal[3] = {dirt_image_find_channel(out, "N.X"), dirt_image_find_channel(out, "N.Y"),
                        dirt_image_find_channel(out, "N.Z")};
    double inv = 1.0 / opts.spp;
    for (size_t i = 0; i < pixels; i++) {
        out->rgba[4 * i + 0] = (float)(sums[i].color.x * inv);
        out->rgba[4 * i + 1] = (float)(sums[i].color.y * inv);
        out->rgba[4 * i + 2] = (float)(sums[i].color.z * inv);
        out->rgba[4 * i + 3] = 1.0f;
        st->invalid_samples += (uint64_t)sums[i].albedo.w;
        float a[3] = {sums[i].albedo.x, sums[i].albedo.y, sums[i].albedo.z};
        float n[3] = {sums[i].normal.x, sums[i].normal.y, sums[i].normal.z};
        for (int k = 0; k < 3; k++) {
            if (albedo[k])
                albedo[k][i] = (float)(a[k] * inv);
            if (normal[k])
                normal[k][i] = (float)(n[k] * inv);
        }
    }
    free(sums);
    if (!tech->read_counts(tech->self, &st->rays, &st->aborted))
        goto done;
    if (st->aborted)
        DIRT_WARN("%llu rays ran out of march steps", (unsigned long long)st->aborted);
    st->build_ms = tech->build_ms;
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
    st->bytes_integrator = pixels * (2 * sizeof(struct dirt_gpu_ray) + 2 * sizeof(struct dirt_gpu_hit) +
                                     3 * sizeof(struct dirt_gpu_gpoint) +
                                     sizeof(struct dirt_gpu_path) + sizeof(struct dirt_gpu_accum)) +
                          tech->bytes_extra;
    ok = gl_check("dirt path tracer");
done:
    st->total_ms = dirt_clock_ms() - t0;
    dirt_area_lights_free(&area);
    gl_group_pop();
    pt->opts = NULL;
    pt->tech = NULL;
    return ok;
}

bool dirt_pt_write_dot(const dirt_pt *pt, const char *path)
{
    if (!pt->graph) {
        DIRT_ERROR("no render yet: no frame graph to write");
        return false;
    }
    char *dot = fg_dot(pt->graph);
    bool ok = dot && dirt_write_file_atomic(path, dot, strlen(dot));
    free(dot);
    return ok;
}
