/* GPU path tracer: the Trace -> Fetch -> Shade loop on a frame graph. */
#include "integrator/pathtrace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/clock.h"
#include "dirt/file.h"
#include "integrator/gpu_tables.h"
#include "integrator/integrator.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/graph_gl.h"
#include "gl/split.h"
#include "integrator/depth.h"
#include "integrator/ray_sort.h"
#include "integrator/rng.h"

/* The session's per-event figures (dirt/types.h) hold every event the
 * shaders count (common/constants.h). */
_Static_assert(DIRT_MAX_EVENTS == DIRT_PT_MAX_EVENTS, "DIRT_MAX_EVENTS differs from common/constants.h");

const char *const dirt_pt_pass_names[DIRT_PT_NUM_PASSES] = {
    [DIRT_PT_PASS_RAYGEN] = "raygen",
    [DIRT_PT_PASS_VISIBILITY] = "direct visibility",
    [DIRT_PT_PASS_TRACE] = "trace",
    [DIRT_PT_PASS_FETCH] = "fetch",
    [DIRT_PT_PASS_SHADE] = "shade",
    [DIRT_PT_PASS_SHADOW] = "shadow trace",
    [DIRT_PT_PASS_RESOLVE] = "resolve",
    [DIRT_PT_PASS_ACCUMULATE] = "accumulate",
    [DIRT_PT_PASS_COMPACT] = "compact",
    [DIRT_PT_PASS_SORT] = "ray sort",
};

typedef struct pass_ctx {
    struct dirt_pt *pt;
    enum dirt_pt_pass kind;
    int k;       /* path event */
    bool finish; /* compaction's second pass (the next batch's dispatch) */
    enum dirt_ray_sort_pass sort; /* DIRT_PT_PASS_SORT: which pass */
} pass_ctx;

#define MAX_PASSES 512

/* The image is worked through in chunks (wavefronts) of at most `chunk`
 * pixels: every per-pixel buffer but the accumulation holds one chunk, and
 * one sample runs the whole frame graph once per chunk, in pixel order.
 * Record p of a chunk is image pixel offset + p, which keys the random
 * numbers (glsl/integrator/pt_common.glsl), so the image does not depend on
 * the chunk size. The accumulation (and the display pass) is split into one
 * buffer per chunk, since the whole image's sums can outgrow one storage
 * block too. */

struct dirt_pt {
    dirt_gpu *gpu;
    const dirt_scene *scene;
    GLuint prog_raygen, prog_resolve, prog_accum, prog_display;
    /* Shade (and its AO build), built for the layouts of the tracer's
     * geometry (dirt_tracer.vertices_split, .prim_material_split) */
    gl_split_program prog_shade, prog_ao;
    GLuint prog_compact, prog_finish;
    /* per-pixel buffers of one chunk. Event k's rays are ray_buf[(k - 1) & 1]
     * (shade writes the rays of k + 1 over them), its shadow rays the other
     * one, which compaction then fills with the live rays of k + 1; its
     * batch (dirt_gpu_ray_batch + owners) is batch[(k - 1) & 1]. */
    GLuint rays, hits, shadow_rays, shadow_hits, gpoints, paths;
    GLuint batch[2];
    GLuint events;     /* uint[DIRT_PT_MAX_EVENTS]: paths per event (compact.comp) */
    /* the ray sort (dirt_pt_opts.sort_rays; made on first use): compaction
     * gathers the live rays into sort_rays and sort_batch, which the sort
     * permutes into the event's rays and batch */
    dirt_ray_sort *sort;
    GLuint sort_rays, sort_batch, sort_scratch;
    float sort_min[3], sort_max[3]; /* the box of its origin grid (the frame's bounds) */
    /* accumulation: one buffer per chunk (accum[c] = pixels c*chunk ...) */
    GLuint *accum;
    /* dirt_pt_advance: the sample in progress is done for pixels
     * 0 .. part_done - 1 (0: none in progress); while one is, `shown` (one
     * buffer per chunk, made at the first partial sample) holds the
     * accumulation of the completed samples, which the readback and the
     * display give. Pieces start at multiples of `granule` pixels within
     * their chunk (whole work groups whose accumulation records start at
     * the GL's storage-buffer offset alignment); `px_per_ms` is the
     * measured pace that sizes them. */
    size_t part_done;
    GLuint *shown;
    bool shown_current;       /* `shown` holds this sample's completed ones */
    size_t granule;
    double px_per_ms;
    size_t pixels;     /* of the image */
    size_t chunk;      /* pixels per chunk (the last may hold fewer) */
    size_t num_chunks;
    size_t chunk_limit; /* dirt_pt_set_chunk_limit; 0 = the GPU's limits only */
    /* the chunk the graph's passes work on during dirt_pt_add_samples */
    size_t cur_chunk, cur_offset, cur_count;
    /* graph (rebuilt when the configuration changes) */
    fg_graph *graph;
    size_t g_pixels;
    int g_events;
    enum dirt_pt_mode g_mode;
    bool g_direct;
    bool g_sort;
    pass_ctx ctx[MAX_PASSES];
    int num_ctx;
    /* pass times that came after the dirt_pt_add_samples call that issued
     * them (drained at a readback), until dirt_pt_take_late_times */
    double late_ms[DIRT_PT_NUM_PASSES];
    enum dirt_clock late_clock;
    /* accumulation: image size and samples so far */
    int width, height;
    uint32_t samples;
    bool accum_valid;         /* reset since the buffers were (re)made */
    /* display texture (dirt_pt_display_texture) */
    GLuint display;
    int display_w, display_h;
    uint32_t display_samples; /* samples it shows; ~0 = stale */
    /* the Z AOV of the accumulation (depth.c), made with its first samples */
    float *depth, *ids;   /* and the "ID" AOV */
    size_t depth_pixels;
    /* state read by the pass bodies during dirt_pt_add_samples */
    const dirt_tracer *tech;
    dirt_gpu_model_tables tables;
    /* the environment table (DIRT_BIND_MODEL_ENV) and what it holds: the
     * map `env_src` (borrowed from the options; NULL with env_bg set: the
     * constant `env_bg`, made into `env_own`) */
    GLuint env_buf;
    size_t env_bytes;
    const dirt_env *env_src;
    dirt_env *env_own;
    float env_bg[3];
    bool env_valid;
    const dirt_pt_opts *opts;
    int bounces;
    uint32_t sample;
    float ao_distance;
    bool alpha;               /* the scene has alpha-tested materials */
};

/* Makes Shade and its AO build the ones for the geometry of `tech` (NULL:
 * one storage block each) and the tables' texels and tangents. False after
 * logging. */
static bool shade_programs(dirt_pt *pt, const dirt_tracer *tech)
{
    const gl_split_desc *d[4] = {&gl_split_vertices, &gl_split_prim_material};
    gl_split_layout l[4] = {{0, 0}, {0, 0}};
    if (tech) {
        l[0] = tech->vertices_split;
        l[1] = tech->prim_material_split;
    }
    dirt_gpu_model_tables_arrays(&pt->tables, d + 2, l + 2);
    const char *paths[] = {"integrator/shade.comp", NULL};
    glsl_define ao = {"DIRT_AO", "1"};
    return gl_split_program_ensure(&pt->prog_shade, "integrator/shade.comp", paths, NULL, 0, d,
                                   l, 4) &&
           gl_split_program_ensure(&pt->prog_ao, "integrator/shade.comp (AO)", paths, &ao, 1, d,
                                   l, 4);
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
    GLint align = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    pt->granule = DIRT_GROUP_SIZE;
    while (align > 0 && (pt->granule * sizeof(struct dirt_gpu_accum)) % (size_t)align != 0 &&
           pt->granule < 64 * DIRT_GROUP_SIZE)
        pt->granule += DIRT_GROUP_SIZE;
    /* Test hook: DIRT_PT_CHUNK_PIXELS=n forces chunks of at most n pixels. */
    const char *hook = getenv("DIRT_PT_CHUNK_PIXELS");
    if (hook && *hook)
        dirt_pt_set_chunk_limit(pt, (size_t)strtoull(hook, NULL, 10));
    pt->prog_raygen = gl_program_compute("integrator/raygen.comp", NULL, 0);
    pt->prog_resolve = gl_program_compute("integrator/resolve.comp", NULL, 0);
    pt->prog_accum = gl_program_compute("integrator/accumulate.comp", NULL, 0);
    pt->prog_display = gl_program_compute("integrator/display.comp", NULL, 0);
    glsl_define finish = {"DIRT_COMPACT_FINISH", "1"};
    pt->prog_compact = gl_program_compute("integrator/compact.comp", NULL, 0);
    pt->prog_finish = gl_program_compute("integrator/compact.comp", &finish, 1);
    if (!pt->prog_raygen || !pt->prog_resolve || !pt->prog_accum || !pt->prog_display ||
        !pt->prog_compact || !pt->prog_finish || !shade_programs(pt, NULL)) {
        dirt_pt_destroy(pt);
        return NULL;
    }
    return pt;
}

bool dirt_pt_check_frame(dirt_pt *pt, const dirt_frame *frame)
{
    gl_split_layout texels, tangents;
    return dirt_gpu_model_tables_plan(pt->gpu, pt->scene, frame, &texels, &tangents);
}

static void release_buffers(dirt_pt *pt)
{
    GLuint *b[] = {&pt->rays, &pt->hits, &pt->shadow_rays, &pt->shadow_hits,
                   &pt->gpoints, &pt->paths, &pt->batch[0], &pt->batch[1], &pt->events,
                   &pt->sort_rays, &pt->sort_batch, &pt->sort_scratch};
    for (size_t i = 0; i < sizeof(b) / sizeof(b[0]); i++)
        gl_buffer_destroy(b[i]);
    for (size_t c = 0; c < pt->num_chunks && pt->accum; c++)
        gl_buffer_destroy(&pt->accum[c]);
    for (size_t c = 0; c < pt->num_chunks && pt->shown; c++)
        gl_buffer_destroy(&pt->shown[c]);
    free(pt->accum);
    free(pt->shown);
    pt->accum = pt->shown = NULL;
    pt->part_done = 0;
    pt->num_chunks = 0;
    pt->chunk = 0;
    gl_texture_destroy(&pt->display);
    free(pt->depth);
    free(pt->ids);
    pt->depth = pt->ids = NULL;
    pt->depth_pixels = 0;
    pt->pixels = 0;
    pt->accum_valid = false;
    pt->g_pixels = 0; /* the graph imports these buffers: remake it */
}

/* Bytes of a ray batch of `n` rays: its header, then the owners. */
static size_t batch_bytes(size_t n)
{
    return sizeof(struct dirt_gpu_ray_batch) + n * sizeof(uint32_t);
}

/* Pixels of chunk c. */
static size_t chunk_pixels(const dirt_pt *pt, size_t c)
{
    size_t first = c * pt->chunk;
    return pt->pixels - first < pt->chunk ? pt->pixels - first : pt->chunk;
}

/* The largest record per pixel of one chunk's buffers (the shading ring's
 * three shading points): every buffer must fit one storage block. */
static size_t largest_per_pixel(void)
{
    size_t m = 3 * sizeof(struct dirt_gpu_gpoint);
    size_t others[] = {sizeof(struct dirt_gpu_ray), sizeof(struct dirt_gpu_hit),
                       sizeof(struct dirt_gpu_path), sizeof(struct dirt_gpu_accum)};
    for (size_t i = 0; i < sizeof(others) / sizeof(others[0]); i++)
        m = others[i] > m ? others[i] : m;
    return m;
}

void dirt_pt_set_chunk_limit(dirt_pt *pt, size_t pixels)
{
    if (pt->chunk_limit == pixels)
        return;
    pt->chunk_limit = pixels;
    release_buffers(pt); /* the next reset remakes them (and restarts) */
}

size_t dirt_pt_chunk_pixels(const dirt_gpu *gpu, size_t pixels, size_t limit)
{
    int64_t max = dirt_gpu_get_caps(gpu)->max_ssbo_size;
    size_t c = max > 0 ? (size_t)max / largest_per_pixel() : pixels;
    if (limit > 0 && limit < c)
        c = limit;
    /* The passes over a chunk launch one group per DIRT_GROUP_SIZE pixels
     * in one dimension, of which GL promises 65535. */
    if (c > (size_t)65535 * DIRT_GROUP_SIZE)
        c = (size_t)65535 * DIRT_GROUP_SIZE;
    /* Whole work groups per chunk (except the image's last). */
    if (c > DIRT_GROUP_SIZE)
        c -= c % DIRT_GROUP_SIZE;
    if (c < 1)
        c = 1;
    return c < pixels ? c : pixels;
}

void dirt_pt_destroy(dirt_pt *pt)
{
    if (!pt)
        return;
    GLuint *p[] = {&pt->prog_raygen, &pt->prog_resolve, &pt->prog_accum, &pt->prog_display,
                   &pt->prog_compact, &pt->prog_finish};
    for (size_t i = 0; i < sizeof(p) / sizeof(p[0]); i++)
        gl_program_destroy(p[i]);
    gl_split_program_destroy(&pt->prog_shade);
    gl_split_program_destroy(&pt->prog_ao);
    dirt_ray_sort_destroy(pt->sort);
    release_buffers(pt);
    dirt_gpu_model_tables_destroy(&pt->tables);
    gl_buffer_destroy(&pt->env_buf);
    dirt_env_destroy(pt->env_own);
    fg_destroy(pt->graph);
    free(pt);
}

static bool ensure_buffers(dirt_pt *pt, size_t pixels)
{
    if (pt->pixels == pixels && pt->accum)
        return true;
    release_buffers(pt);
    size_t chunk = dirt_pt_chunk_pixels(pt->gpu, pixels, pt->chunk_limit);
    size_t n = (pixels + chunk - 1) / chunk;
    pt->accum = calloc(n, sizeof(*pt->accum));
    if (!pt->accum) {
        DIRT_ERROR("out of memory");
        return false;
    }
    pt->num_chunks = n;
    pt->chunk = chunk;
    pt->pixels = pixels;
    if (n > 1)
        DIRT_INFO("path tracer: %zu pixels in %zu chunks of %zu (storage blocks of %.1f MB)",
                  pixels, n, chunk, dirt_gpu_get_caps(pt->gpu)->max_ssbo_size / 1e6);
    pt->rays = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_ray), NULL, false,
                                "pt rays");
    pt->hits = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_hit), NULL, false,
                                "pt hits");
    pt->shadow_rays = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_ray), NULL,
                                       false, "pt shadow rays");
    pt->shadow_hits = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_hit), NULL,
                                       false, "pt shadow hits");
    pt->gpoints = gl_buffer_create(pt->gpu, 3 * chunk * sizeof(struct dirt_gpu_gpoint), NULL,
                                   false, "pt shading ring");
    pt->paths = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_path), NULL, false,
                                 "pt paths");
    for (int b = 0; b < 2; b++)
        pt->batch[b] = gl_buffer_create(pt->gpu, batch_bytes(chunk), NULL, false,
                                        b ? "pt batch B" : "pt batch A");
    pt->events = gl_buffer_create(pt->gpu, DIRT_PT_MAX_EVENTS * sizeof(uint32_t), NULL, true,
                                  "pt paths per event");
    bool ok = pt->rays && pt->hits && pt->shadow_rays && pt->shadow_hits && pt->gpoints &&
              pt->paths && pt->batch[0] && pt->batch[1] && pt->events;
    for (size_t c = 0; ok && c < n; c++) {
        pt->accum[c] = gl_buffer_create(pt->gpu, chunk_pixels(pt, c) * sizeof(struct dirt_gpu_accum),
                                        NULL, true, "pt accumulation");
        ok = pt->accum[c] != 0;
    }
    if (!ok) {
        release_buffers(pt);
        return false;
    }
    return true;
}

/* The sort's programs and buffers (after ensure_buffers). False after
 * logging. */
static bool ensure_sort(dirt_pt *pt)
{
    if (!pt->sort && !(pt->sort = dirt_ray_sort_create()))
        return false;
    if (pt->sort_rays)
        return true;
    size_t chunk = pt->chunk;
    pt->sort_rays = gl_buffer_create(pt->gpu, chunk * sizeof(struct dirt_gpu_ray), NULL, false,
                                     "pt unsorted rays");
    pt->sort_batch = gl_buffer_create(pt->gpu, batch_bytes(chunk), NULL, false,
                                      "pt unsorted batch");
    pt->sort_scratch = gl_buffer_create(pt->gpu, dirt_ray_sort_scratch_bytes(chunk), NULL, false,
                                        "pt ray sort");
    if (!pt->sort_rays || !pt->sort_batch || !pt->sort_scratch) {
        gl_buffer_destroy(&pt->sort_rays);
        gl_buffer_destroy(&pt->sort_batch);
        gl_buffer_destroy(&pt->sort_scratch);
        return false;
    }
    pt->g_pixels = 0; /* the graph imports these buffers: remake it */
    return true;
}

static void bind(GLuint binding, GLuint buf)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buf);
}

/* Makes env_buf hold the environment of `opts` (uploaded again only when
 * the map or the background changed). False after logging. */
static bool ensure_env(dirt_pt *pt, const dirt_pt_opts *opts)
{
    const float *bg = opts->background;
    bool constant = !opts->env && (bg[0] > 0.0f || bg[1] > 0.0f || bg[2] > 0.0f);
    if (pt->env_valid && pt->env_src == opts->env &&
        (opts->env || !memcmp(pt->env_bg, bg, sizeof(pt->env_bg))))
        return true;
    pt->env_valid = false;
    dirt_env_destroy(pt->env_own);
    pt->env_own = NULL;
    gl_buffer_destroy(&pt->env_buf);
    pt->env_bytes = 0;
    if (constant && !(pt->env_own = dirt_env_constant(bg)))
        return false;
    const dirt_env *env = opts->env ? opts->env : pt->env_own;
    size_t size = 0;
    const dirt_gpu_caps *caps = dirt_gpu_get_caps(pt->gpu);
    void *data = dirt_gpu_env_pack(env, caps && caps->max_ssbo_size > 0 ?
                                   (size_t)caps->max_ssbo_size : 0, &size);
    if (!data)
        return false;
    pt->env_buf = gl_buffer_create(pt->gpu, size, data, false, "pt environment");
    free(data);
    if (!pt->env_buf)
        return false;
    pt->env_bytes = size;
    pt->env_src = opts->env;
    memcpy(pt->env_bg, bg, sizeof(pt->env_bg));
    pt->env_valid = true;
    return true;
}

/* Uniforms of pt_common.glsl for event k; binds the model tables and the
 * technique's geometry. */
static void set_common(dirt_pt *pt, GLuint prog, int k)
{
    glUseProgram(prog);
    glUniform1ui(DIRT_LOC_PT_PIXELS, (GLuint)pt->cur_count);
    glUniform1ui(DIRT_LOC_PT_PIXEL_OFFSET, (GLuint)pt->cur_offset);
    glUniform1i(DIRT_LOC_PT_WIDTH, pt->width);
    glUniform1i(DIRT_LOC_PT_HEIGHT, pt->height);
    glUniform1ui(DIRT_LOC_PT_SEED, pt->opts->seed);
    glUniform1ui(DIRT_LOC_PT_SAMPLE, pt->sample);
    glUniform1ui(DIRT_LOC_PT_BOUNCE, (GLuint)k);
    glUniform1ui(DIRT_LOC_PT_BOUNCES, (GLuint)pt->bounces);
    glUniform1ui(DIRT_LOC_PT_SLOT, (GLuint)(k % 3));
    glUniform1f(DIRT_LOC_PT_AO_DISTANCE, pt->ao_distance);
    glUniform1f(DIRT_LOC_PT_SURFACE_OFFSET, pt->tech->surface_offset);
    dirt_gpu_model_tables_bind(&pt->tables);
    bind(DIRT_BIND_MODEL_ENV, pt->env_buf);
    pt->tech->bind_geometry(pt->tech->self);
}


/* The alpha test of the next trace (dirt_trace_alpha): rays leaving vertex
 * `bounce` of this chunk, keyed with `dim` (doc/rng.md, "Alpha"); off when
 * the scene has no alpha-tested material. */
static void set_alpha(dirt_pt *pt, uint32_t bounce, uint32_t dim)
{
    if (!pt->tech->set_alpha)
        return;
    dirt_trace_alpha a = {0};
    if (pt->alpha) {
        a = (dirt_trace_alpha){.materials = pt->tables.materials, .texels = &pt->tables.texels,
                               .seed = pt->opts->seed, .sample = pt->sample, .bounce = bounce,
                               .dim = dim, .first_pixel = (uint32_t)pt->cur_offset};
    }
    pt->tech->set_alpha(pt->tech->self, &a);
}

static GLuint groups(size_t n)
{
    return (GLuint)DIRT_GROUPS(n);
}

/* Event k's rays, shadow rays and batch (see struct dirt_pt). */
static GLuint event_rays(const dirt_pt *pt, int k)
{
    return (k - 1) & 1 ? pt->shadow_rays : pt->rays;
}

static GLuint event_shadow_rays(const dirt_pt *pt, int k)
{
    return (k - 1) & 1 ? pt->rays : pt->shadow_rays;
}

static GLuint event_batch(const dirt_pt *pt, int k)
{
    return pt->batch[(k - 1) & 1];
}

/* Dispatches the current program over event k's batch (indirect). */
static void dispatch_batch(const dirt_pt *pt, int k)
{
    GLuint b = event_batch(pt, k);
    bind(DIRT_BIND_RAY_BATCH, b);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, b);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

/* The tracer's next calls work on event k's batch (0: plain, all pixels). */
static void set_batch(dirt_pt *pt, int k)
{
    pt->tech->set_batch(pt->tech->self, k > 0 ? event_batch(pt, k) : 0);
}

static bool exec_pass(fg_ctx *ctx, void *user)
{
    (void)ctx;
    pass_ctx *c = user;
    dirt_pt *pt = c->pt;
    bool ok = true;
    switch (c->kind) {
    case DIRT_PT_PASS_RAYGEN:
        set_common(pt, pt->prog_raygen, 0);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_RAYS, event_rays(pt, 1));
        bind(DIRT_BIND_RAY_BATCH, event_batch(pt, 1));
        glDispatchCompute(groups(pt->cur_count), 1, 1);
        break;
    case DIRT_PT_PASS_VISIBILITY:
        return pt->tech->visibility(pt->tech->self, event_rays(pt, 1), pt->hits);
    case DIRT_PT_PASS_TRACE:
        set_alpha(pt, (uint32_t)(c->k - 1), DIRT_RNG_DIM_ALPHA_PATH);
        set_batch(pt, c->k);
        /* (event 1's rays are the camera's; later ones leave path vertices) */
        ok = pt->tech->trace(pt->tech->self, event_rays(pt, c->k), pt->hits,
                             (uint32_t)pt->cur_count, c->k > 1 ? DIRT_TRACER_FROM_SURFACES : 0);
        set_batch(pt, 0);
        return ok;
    case DIRT_PT_PASS_FETCH:
        set_batch(pt, c->k);
        ok = pt->tech->fetch(pt->tech->self, event_rays(pt, c->k), pt->hits,
                             (uint32_t)pt->cur_count, pt->gpoints, (uint32_t)(c->k % 3));
        set_batch(pt, 0);
        return ok;
    case DIRT_PT_PASS_SHADE:
        set_common(pt, pt->g_mode == DIRT_PT_AO ? pt->prog_ao.id : pt->prog_shade.id, c->k);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_GPOINTS, pt->gpoints);
        bind(DIRT_BIND_HITS, pt->hits);
        bind(DIRT_BIND_RAYS, event_rays(pt, c->k));
        bind(DIRT_BIND_SHADOW_RAYS, event_shadow_rays(pt, c->k));
        dispatch_batch(pt, c->k);
        break;
    case DIRT_PT_PASS_SHADOW:
        set_alpha(pt, (uint32_t)c->k, DIRT_RNG_DIM_ALPHA_SHADOW);
        set_batch(pt, c->k);
        ok = pt->tech->trace(pt->tech->self, event_shadow_rays(pt, c->k), pt->shadow_hits,
                             (uint32_t)pt->cur_count,
                             DIRT_TRACER_ANY_HIT | DIRT_TRACER_FROM_SURFACES);
        set_batch(pt, 0);
        return ok;
    case DIRT_PT_PASS_RESOLVE:
        glUseProgram(pt->prog_resolve);
        glUniform1ui(DIRT_LOC_RESOLVE_PIXELS, (GLuint)pt->cur_count);
        bind(DIRT_BIND_PATHS, pt->paths);
        bind(DIRT_BIND_HITS, pt->shadow_hits);
        dispatch_batch(pt, c->k);
        break;
    case DIRT_PT_PASS_SORT: {
        dirt_ray_sort_io io = {
            .in_rays = pt->sort_rays, .in_batch = pt->sort_batch,
            .out_rays = event_rays(pt, c->k + 1), .out_batch = event_batch(pt, c->k + 1),
            .scratch = pt->sort_scratch, .capacity = (uint32_t)pt->cur_count};
        memcpy(io.bounds_min, pt->sort_min, sizeof(io.bounds_min));
        memcpy(io.bounds_max, pt->sort_max, sizeof(io.bounds_max));
        dirt_ray_sort_pass(pt->sort, c->sort, &io);
        return true;
    }
    case DIRT_PT_PASS_COMPACT: {
        /* With the sort, into its input; else into event k + 1's batch. */
        GLuint next = pt->g_sort ? pt->sort_batch : event_batch(pt, c->k + 1);
        bind(DIRT_BIND_NEXT_BATCH, next);
        if (c->finish) {
            /* The next batch's dispatch from its count; the paths of k + 1. */
            glUseProgram(pt->prog_finish);
            glUniform1ui(DIRT_LOC_COMPACT_EVENT, (GLuint)c->k);
            bind(DIRT_BIND_PT_EVENTS, pt->events);
            glDispatchCompute(1, 1, 1);
            break;
        }
        /* The rays of event k + 1 (written over event k's by Shade) whose
         * paths go on, into the next batch. */
        static const uint32_t zero[4] = {0, 0, 0, 0};
        glClearNamedBufferSubData(next, GL_RGBA32UI, 0, sizeof(struct dirt_gpu_ray_batch),
                                  GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero);
        glUseProgram(pt->prog_compact);
        glUniform1ui(DIRT_LOC_COMPACT_PIXELS, (GLuint)pt->cur_count);
        bind(DIRT_BIND_RAYS, event_rays(pt, c->k));
        bind(DIRT_BIND_SHADOW_RAYS, pt->g_sort ? pt->sort_rays : event_shadow_rays(pt, c->k));
        dispatch_batch(pt, c->k);
        break;
    }
    case DIRT_PT_PASS_ACCUMULATE:
    case DIRT_PT_NUM_PASSES:
        glUseProgram(pt->prog_accum);
        glUniform1ui(DIRT_LOC_ACCUM_PIXELS, (GLuint)pt->cur_count);
        bind(DIRT_BIND_PATHS, pt->paths);
        /* This piece's records of the chunk's sums (a whole chunk, or a
         * part starting at a multiple of pt->granule: aligned). */
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_ACCUM, pt->accum[pt->cur_chunk],
                          (GLintptr)((pt->cur_offset - pt->cur_chunk * pt->chunk) *
                                     sizeof(struct dirt_gpu_accum)),
                          (GLsizeiptr)(pt->cur_count * sizeof(struct dirt_gpu_accum)));
        glDispatchCompute(groups(pt->cur_count), 1, 1);
        break;
    }
    glUseProgram(0);
    return true;
}

static void drain_times(dirt_pt *pt);

/* A pass over ray batch `b`: reads its owners and dispatches from it. */
static void read_batch(fg_pass *p, fg_res b)
{
    fg_read(p, b, FG_SSBO_READ);
    fg_read(p, b, FG_INDIRECT);
}

/* One graph of a sample's chunk: raygen, then per event k = 1..events trace,
 * fetch, shade, shadow trace, resolve and (but after the last) compact;
 * then accumulate. Every pass after raygen works on event k's batch (the
 * live paths; dispatched indirectly from it). All buffers are imported
 * (they persist across samples); the structure's buffers are the
 * technique's and not declared. The accumulation resource stands for the
 * current chunk's buffer (the pass binds pt->accum[cur_chunk]; GL barriers
 * are not per buffer). */
static bool make_graph(dirt_pt *pt, int events)
{
    /* Times still in flight belong to this accumulation's figures (after a
     * reset there are none: it discarded them). */
    if (pt->samples > 0)
        drain_times(pt);
    fg_destroy(pt->graph);
    pt->graph = gl_graph_create(pt->gpu);
    if (!pt->graph)
        return false;
    fg_graph *g = pt->graph;
    size_t px = pt->chunk;
    fg_res ray_buf[2] = {
        fg_import_buffer(g, "rays A", pt->rays, px * sizeof(struct dirt_gpu_ray)),
        fg_import_buffer(g, "rays B", pt->shadow_rays, px * sizeof(struct dirt_gpu_ray))};
    fg_res batch[2] = {fg_import_buffer(g, "batch A", pt->batch[0], batch_bytes(px)),
                       fg_import_buffer(g, "batch B", pt->batch[1], batch_bytes(px))};
    fg_res hits = fg_import_buffer(g, "hits", pt->hits, px * sizeof(struct dirt_gpu_hit));
    fg_res shits = fg_import_buffer(g, "shadow hits", pt->shadow_hits, px * sizeof(struct dirt_gpu_hit));
    fg_res gpts = fg_import_buffer(g, "shading ring", pt->gpoints, 3 * px * sizeof(struct dirt_gpu_gpoint));
    fg_res paths = fg_import_buffer(g, "paths", pt->paths, px * sizeof(struct dirt_gpu_path));
    fg_res evs = fg_import_buffer(g, "paths per event", pt->events,
                                  DIRT_PT_MAX_EVENTS * sizeof(uint32_t));
    fg_res accum = fg_import_buffer(g, "accumulation", pt->accum[0],
                                    chunk_pixels(pt, 0) * sizeof(struct dirt_gpu_accum));
    /* the sort's input and scratch (pt->g_sort) */
    fg_res urays = {0}, ubatch = {0}, scratch = {0};
    if (pt->g_sort) {
        urays = fg_import_buffer(g, "unsorted rays", pt->sort_rays,
                                 px * sizeof(struct dirt_gpu_ray));
        ubatch = fg_import_buffer(g, "unsorted batch", pt->sort_batch, batch_bytes(px));
        scratch = fg_import_buffer(g, "ray sort", pt->sort_scratch,
                                   dirt_ray_sort_scratch_bytes(px));
    }
    pt->num_ctx = 0;
#define ADD(kind_, k_)                                                                   \
    (pt->ctx[pt->num_ctx] = (pass_ctx){.pt = pt, .kind = (kind_), .k = (k_)},              \
     fg_add_pass(g, name, FG_COMPUTE, exec_pass, &pt->ctx[pt->num_ctx++]))
    char name[64];
    snprintf(name, sizeof(name), "raygen");
    fg_pass *p = ADD(DIRT_PT_PASS_RAYGEN, 0);
    fg_write(p, ray_buf[0], FG_SSBO_WRITE);
    fg_write(p, batch[0], FG_SSBO_WRITE);
    fg_write(p, paths, FG_SSBO_WRITE);
    for (int k = 1; k <= events; k++) {
        if (pt->num_ctx + 12 >= MAX_PASSES) {
            DIRT_ERROR("too many path events (%d)", events);
            return false;
        }
        fg_res rays = ray_buf[(k - 1) & 1], srays = ray_buf[k & 1];
        fg_res b = batch[(k - 1) & 1], bnext = batch[k & 1];
        bool vis = k == 1 && pt->g_direct;
        if (vis)
            snprintf(name, sizeof(name), "direct visibility");
        else
            snprintf(name, sizeof(name), "trace %d", k);
        p = ADD(vis ? DIRT_PT_PASS_VISIBILITY : DIRT_PT_PASS_TRACE, k);
        fg_read(p, rays, FG_SSBO_READ);
        if (!vis)
            read_batch(p, b);
        fg_write(p, hits, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "fetch %d", k);
        p = ADD(DIRT_PT_PASS_FETCH, k);
        fg_read(p, rays, FG_SSBO_READ);
        fg_read(p, hits, FG_SSBO_READ);
        read_batch(p, b);
        fg_write(p, hits, FG_SSBO_WRITE); /* MMRT: t and barycentrics of the shading point */
        fg_use(p, gpts, FG_SSBO_READ, NULL);
        fg_write(p, gpts, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "shade %d", k);
        p = ADD(DIRT_PT_PASS_SHADE, k);
        fg_read(p, gpts, FG_SSBO_READ);
        fg_read(p, hits, FG_SSBO_READ);
        read_batch(p, b);
        fg_use(p, paths, FG_SSBO_READ, NULL);
        fg_write(p, paths, FG_SSBO_WRITE);
        fg_use(p, rays, FG_SSBO_READ, NULL);
        fg_write(p, rays, FG_SSBO_WRITE);
        fg_write(p, srays, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "shadow trace %d", k);
        p = ADD(DIRT_PT_PASS_SHADOW, k);
        fg_read(p, srays, FG_SSBO_READ);
        read_batch(p, b);
        fg_write(p, shits, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "resolve %d", k);
        p = ADD(DIRT_PT_PASS_RESOLVE, k);
        fg_read(p, shits, FG_SSBO_READ);
        read_batch(p, b);
        fg_use(p, paths, FG_SSBO_READ, NULL);
        fg_write(p, paths, FG_SSBO_WRITE);
        if (k == events)
            break;
        /* Compaction in two passes (the graph orders the second after the
         * first's atomics): the live rays into the next batch, then its
         * dispatch and the paths per event. */
        /* With the sort, compaction gathers into the sort's input, which
         * the sort then permutes into the next event's rays and batch. */
        fg_res crays = pt->g_sort ? urays : srays, cbatch = pt->g_sort ? ubatch : bnext;
        snprintf(name, sizeof(name), "compact %d", k);
        p = ADD(DIRT_PT_PASS_COMPACT, k);
        fg_read(p, rays, FG_SSBO_READ);
        read_batch(p, b);
        fg_write(p, crays, FG_SSBO_WRITE);
        fg_use(p, cbatch, FG_SSBO_READ, NULL);
        fg_write(p, cbatch, FG_SSBO_WRITE);
        snprintf(name, sizeof(name), "compact finish %d", k);
        p = ADD(DIRT_PT_PASS_COMPACT, k);
        pt->ctx[pt->num_ctx - 1].finish = true;
        fg_use(p, cbatch, FG_SSBO_READ, NULL);
        fg_write(p, cbatch, FG_SSBO_WRITE);
        fg_use(p, evs, FG_SSBO_READ, NULL);
        fg_write(p, evs, FG_SSBO_WRITE);
        if (!pt->g_sort)
            continue;
        /* count: the keys and rays per bucket (the counters cleared first) */
        snprintf(name, sizeof(name), "sort count %d", k + 1);
        p = ADD(DIRT_PT_PASS_SORT, k);
        pt->ctx[pt->num_ctx - 1].sort = DIRT_RAY_SORT_COUNT;
        fg_read(p, urays, FG_SSBO_READ);
        read_batch(p, ubatch);
        fg_use(p, scratch, FG_SSBO_READ, NULL);
        fg_write(p, scratch, FG_SSBO_WRITE);
        /* scan: first slots; the next batch's header */
        snprintf(name, sizeof(name), "sort scan %d", k + 1);
        p = ADD(DIRT_PT_PASS_SORT, k);
        pt->ctx[pt->num_ctx - 1].sort = DIRT_RAY_SORT_SCAN;
        fg_read(p, ubatch, FG_SSBO_READ);
        fg_use(p, scratch, FG_SSBO_READ, NULL);
        fg_write(p, scratch, FG_SSBO_WRITE);
        fg_use(p, bnext, FG_SSBO_READ, NULL);
        fg_write(p, bnext, FG_SSBO_WRITE);
        /* scatter: the rays and owners of k + 1, in key order */
        snprintf(name, sizeof(name), "sort scatter %d", k + 1);
        p = ADD(DIRT_PT_PASS_SORT, k);
        pt->ctx[pt->num_ctx - 1].sort = DIRT_RAY_SORT_SCATTER;
        fg_read(p, urays, FG_SSBO_READ);
        read_batch(p, ubatch);
        fg_use(p, scratch, FG_SSBO_READ, NULL);
        fg_write(p, scratch, FG_SSBO_WRITE);
        fg_write(p, srays, FG_SSBO_WRITE);
        fg_use(p, bnext, FG_SSBO_READ, NULL);
        fg_write(p, bnext, FG_SSBO_WRITE);
    }
    snprintf(name, sizeof(name), "accumulate");
    p = ADD(DIRT_PT_PASS_ACCUMULATE, 0);
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

/* The per-kind sums of st->pass_ms. */
static void sum_kinds(dirt_pt_stats *st)
{
    st->trace_ms = st->pass_ms[DIRT_PT_PASS_TRACE] + st->pass_ms[DIRT_PT_PASS_SHADOW];
    st->fetch_ms = st->pass_ms[DIRT_PT_PASS_FETCH];
    st->visibility_ms = st->pass_ms[DIRT_PT_PASS_VISIBILITY];
    st->shade_ms = st->pass_ms[DIRT_PT_PASS_RAYGEN] + st->pass_ms[DIRT_PT_PASS_SHADE] +
                   st->pass_ms[DIRT_PT_PASS_RESOLVE] + st->pass_ms[DIRT_PT_PASS_COMPACT] +
                   st->pass_ms[DIRT_PT_PASS_SORT] +
                   st->pass_ms[DIRT_PT_PASS_ACCUMULATE];
}

/* Adds the last execute's pass times to `st`, keyed by each pass's kind
 * (the passes' declaration order is pt->ctx's); st->clock is the graph's.
 * The passes are timed asynchronously: with the GPU clock these are the
 * times of earlier executes that have arrived by now. */
static void add_times(dirt_pt *pt, dirt_pt_stats *st)
{
    fg_stats s;
    if (!fg_get_stats(pt->graph, &s) || s.clock == DIRT_CLOCK_NONE)
        return;
    st->clock = s.clock;
    for (int i = 0; i < s.num_passes && i < pt->num_ctx; i++) {
        const fg_pass_stats *p = &s.passes[i];
        if (p->clock == s.clock)
            st->pass_ms[pt->ctx[i].kind] += p->ms;
    }
    sum_kinds(st);
}

/* Waits for the pass times still in flight and holds them in pt->late_ms. */
static void drain_times(dirt_pt *pt)
{
    if (!pt->graph)
        return;
    double late[MAX_PASSES];
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    if (!fg_drain_timers(pt->graph, late, pt->num_ctx, &clock) || clock == DIRT_CLOCK_NONE)
        return;
    if (pt->late_clock != DIRT_CLOCK_NONE && pt->late_clock != clock)
        return; /* one GPU, one clock: cannot happen */
    pt->late_clock = clock;
    for (int i = 0; i < pt->num_ctx; i++)
        pt->late_ms[pt->ctx[i].kind] += late[i];
}

void dirt_pt_take_late_times(dirt_pt *pt, bool wait, dirt_pt_stats *late)
{
    if (wait)
        drain_times(pt);
    *late = (dirt_pt_stats){.clock = pt->late_clock};
    for (int i = 0; i < DIRT_PT_NUM_PASSES; i++)
        late->pass_ms[i] = pt->late_ms[i];
    sum_kinds(late);
    memset(pt->late_ms, 0, sizeof(pt->late_ms));
    pt->late_clock = DIRT_CLOCK_NONE;
}

/* Bytes per pixel of one chunk's buffers (the accumulation aside). */
static size_t chunk_bytes_per_pixel(void)
{
    return 2 * sizeof(struct dirt_gpu_ray) + 2 * sizeof(struct dirt_gpu_hit) +
           3 * sizeof(struct dirt_gpu_gpoint) + sizeof(struct dirt_gpu_path) +
           2 * sizeof(uint32_t);
}

/* Bytes of the ray sort's buffers for chunks of `px` pixels: the unsorted
 * rays and batch, and the scratch. */
static size_t sort_bytes(size_t px)
{
    return px * sizeof(struct dirt_gpu_ray) + batch_bytes(px) + dirt_ray_sort_scratch_bytes(px);
}

/* Bytes of the integrator's buffers: the chunk's, the batches' headers and
 * the paths per event, then the whole image's sums (360 B per pixel while
 * the image is one chunk, and 292 B), and the ray sort's once made. */
static uint64_t integrator_bytes(const dirt_pt *pt)
{
    return (uint64_t)pt->chunk * chunk_bytes_per_pixel() +
           2 * sizeof(struct dirt_gpu_ray_batch) + DIRT_PT_MAX_EVENTS * sizeof(uint32_t) +
           (uint64_t)pt->pixels * sizeof(struct dirt_gpu_accum) +
           (pt->sort_rays ? sort_bytes(pt->chunk) : 0);
}

int dirt_pt_buffers(const dirt_pt *pt, const dirt_tracer *tracer, dirt_buffer_bytes *out,
                    int max)
{
    size_t px = pt->chunk;
    const dirt_buffer_bytes all[] = {
        {"pt rays", px * sizeof(struct dirt_gpu_ray), 0},
        {"pt hits", px * sizeof(struct dirt_gpu_hit), 0},
        {"pt shadow rays", px * sizeof(struct dirt_gpu_ray), 0},
        {"pt shadow hits", px * sizeof(struct dirt_gpu_hit), 0},
        {"pt shading ring", 3 * px * sizeof(struct dirt_gpu_gpoint), 0},
        {"pt paths", px * sizeof(struct dirt_gpu_path), 0},
        {"pt ray batches", 2 * batch_bytes(px), 0},
        {"pt paths per event", DIRT_PT_MAX_EVENTS * sizeof(uint32_t), 0},
        {"pt accumulation", pt->pixels * sizeof(struct dirt_gpu_accum), 0},
        {"pt environment", pt->env_bytes, 0},
        /* the ray sort's input and scratch (made on first use) */
        {"pt ray sort", pt->sort_rays ? sort_bytes(px) : 0, 0},
        {"tracer", tracer ? tracer->bytes_extra : 0, 0},
        /* the scene's textures (made with the first samples) */
        {"model texels", pt->tables.texel_bytes, 0},
        /* the frame's tangents (normal maps; 16 B when none are used) */
        {"model tangents", pt->tables.tangent_bytes, 0},
    };
    int n = 0;
    for (size_t i = 0; i < sizeof(all) / sizeof(all[0]) && n < max; i++) {
        if (!all[i].used)
            continue;
        out[n] = all[i];
        out[n].allocated = out[n].used;
        n++;
    }
    return n;
}

bool dirt_pt_reset(dirt_pt *pt, int width, int height)
{
    if (width < 1 || height < 1) {
        DIRT_ERROR("image size %dx%d", width, height);
        return false;
    }
    size_t pixels = (size_t)width * (size_t)height;
    if (!ensure_buffers(pt, pixels))
        return false;
    static const float zero = 0.0f;
    for (size_t c = 0; c < pt->num_chunks; c++)
        glClearNamedBufferData(pt->accum[c], GL_R32F, GL_RED, GL_FLOAT, &zero);
    /* The times in flight and held are the last accumulation's. */
    fg_discard_timers(pt->graph);
    memset(pt->late_ms, 0, sizeof(pt->late_ms));
    pt->late_clock = DIRT_CLOCK_NONE;
    pt->width = width;
    pt->height = height;
    pt->samples = 0;
    pt->part_done = 0;
    pt->shown_current = false;
    pt->accum_valid = true;
    pt->display_samples = UINT32_MAX;
    return gl_check("dirt_pt_reset");
}

int dirt_pt_samples(const dirt_pt *pt)
{
    return pt->accum_valid ? (int)pt->samples : 0;
}

/* The accumulation of the completed samples into pt->shown (made when
 * missing), before a sample is worked on in pieces. False after logging. */
static bool keep_shown(dirt_pt *pt)
{
    if (!pt->shown) {
        pt->shown = calloc(pt->num_chunks, sizeof(*pt->shown));
        bool ok = pt->shown != NULL;
        for (size_t c = 0; ok && c < pt->num_chunks; c++) {
            pt->shown[c] = gl_buffer_create(pt->gpu, chunk_pixels(pt, c) *
                                                         sizeof(struct dirt_gpu_accum),
                                            NULL, true, "pt shown accumulation");
            ok = pt->shown[c] != 0;
        }
        if (!ok) {
            for (size_t c = 0; pt->shown && c < pt->num_chunks; c++)
                gl_buffer_destroy(&pt->shown[c]);
            free(pt->shown);
            pt->shown = NULL;
            DIRT_ERROR("out of memory for the completed samples' copy");
            return false;
        }
    }
    /* (The last call that wrote the sums ended with the
     * GL_BUFFER_UPDATE_BARRIER_BIT this copy needs.) */
    for (size_t c = 0; c < pt->num_chunks; c++)
        glCopyNamedBufferSubData(pt->accum[c], pt->shown[c], 0, 0,
                                 (GLsizeiptr)(chunk_pixels(pt, c) * sizeof(struct dirt_gpu_accum)));
    pt->shown_current = true;
    return true;
}

/* The accumulation buffers of the completed samples. */
static const GLuint *completed_sums(const dirt_pt *pt)
{
    return pt->part_done > 0 && pt->shown_current ? pt->shown : pt->accum;
}

/* Pixels of the next piece at pixel `off` of the sample in progress: the
 * rest of off's chunk for whole samples (budget_ms < 0) or direct
 * visibility (which resolves a whole camera view), else what the measured
 * pace does in the budget's rest (one granule with budget 0), in granules. */
static size_t piece_pixels(const dirt_pt *pt, size_t off, double budget_ms, double left_ms)
{
    size_t c = off / pt->chunk;
    size_t rest = c * pt->chunk + chunk_pixels(pt, c) - off;
    if (budget_ms < 0 || pt->g_direct)
        return rest;
    size_t n = pt->granule;
    if (budget_ms > 0 && pt->px_per_ms > 0 && left_ms > 0) {
        double want = pt->px_per_ms * left_ms;
        n = want >= (double)rest ? rest : (size_t)want;
    } else if (budget_ms > 0) {
        n = 4 * pt->granule; /* the pace is not known yet */
    }
    if (n < rest)
        n = n < pt->granule ? pt->granule : n - n % pt->granule;
    return n < rest ? n : rest;
}

/* dirt_pt_add_samples (budget_ms < 0: `count` whole samples, the one in
 * progress first) and dirt_pt_advance (count 1, pieces until budget_ms;
 * *completed says whether the sample completed). */
static bool run(dirt_pt *pt, const dirt_tracer *tech, const dirt_frame *frame,
                const dirt_camera *cam, const dirt_pt_opts *opts_in, int count, double budget_ms,
                bool *completed, dirt_pt_stats *stats)
{
    if (completed)
        *completed = false;
    if (!pt->accum_valid) {
        DIRT_ERROR("dirt_pt_add_samples before dirt_pt_reset");
        return false;
    }
    if (!tech) {
        DIRT_ERROR("no tracer (the technique's build failed?)");
        return false;
    }
    if (!tech->set_batch) {
        DIRT_ERROR("%s has no set_batch: the path tracer traces ray batches", tech->name);
        return false;
    }
    dirt_pt_opts opts = opts_in ? *opts_in : (dirt_pt_opts){0};
    if (!opts.bounces_set && opts.bounces <= 0)
        opts.bounces = 4;
    if (opts.bounces < 0 || opts.bounces > DIRT_PT_MAX_EVENTS - 1) {
        DIRT_ERROR("bounces %d: must be in [0, %d]", opts.bounces, DIRT_PT_MAX_EVENTS - 1);
        return false;
    }
    if (count < 0 || (uint64_t)pt->samples + (uint64_t)count > UINT32_MAX / 2) {
        DIRT_ERROR("sample count %d", count);
        return false;
    }
    dirt_pt_stats local;
    dirt_pt_stats *st = stats ? stats : &local;
    *st = (dirt_pt_stats){0};
    double t0 = dirt_clock_ms();
    pt->tech = tech;
    pt->opts = &opts;
    pt->bounces = opts.bounces;
    pt->ao_distance = opts.ao_distance > 0 ? opts.ao_distance : INFINITY;
    bool ok = false;
    dirt_area_lights area = {0};
    gl_group_push("dirt path tracer");
    if (!dirt_area_lights_build(&area, frame, dirt_scene_materials(pt->scene),
                                dirt_scene_num_materials(pt->scene)))
        goto done;
    if (!ensure_env(pt, &opts))
        goto done;
    /* Materials and textures are the scene's: uploaded once; lights, the
     * camera and the tangents change per frame. Shade is built for the
     * tables' layouts. */
    if (pt->tables.materials) {
        if (!dirt_gpu_model_tables_set_frame(pt->gpu, &pt->tables, frame, &area, cam)) {
            dirt_gpu_model_tables_destroy(&pt->tables);
            goto done;
        }
    } else if (!dirt_gpu_model_tables_create(pt->gpu, pt->scene, frame, &area, cam, NULL,
                                             &pt->tables)) {
        goto done;
    }
    if (!shade_programs(pt, tech))
        goto done;
    /* Alpha-tested traversal (doc/light-transport.md section 1, Alpha). */
    pt->alpha = dirt_materials_alpha_tested(dirt_scene_materials(pt->scene),
                                            dirt_scene_num_materials(pt->scene));
    if (pt->alpha && !tech->set_alpha) {
        DIRT_ERROR("%s cannot test alpha, and the scene has MASK or BLEND materials", tech->name);
        goto done;
    }
    if (pt->alpha && opts.direct_visibility) {
        DIRT_ERROR("direct visibility rasterizes the camera view without an alpha test; the "
                   "scene has MASK or BLEND materials: render without it");
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
        if (vs->camera_view < 0 || vs->views[vs->camera_view].width != pt->width ||
            vs->views[vs->camera_view].height != pt->height) {
            DIRT_ERROR("direct visibility needs a camera view of the image's size (%dx%d)",
                       pt->width, pt->height);
            goto done;
        }
        if (pt->num_chunks > 1) {
            DIRT_ERROR("direct visibility resolves the whole camera view at once: %dx%d is "
                       "%zu pixels, more than one chunk of this GPU's storage blocks holds "
                       "(%zu); render a smaller image or without direct visibility",
                       pt->width, pt->height, pt->pixels, pt->chunk);
            goto done;
        }
    }
    /* The sort's origin grid spans the frame's bounds. */
    bool sort = opts.sort_rays && events > 1;
    if (sort && !ensure_sort(pt))
        goto done;
    memcpy(pt->sort_min, frame->bounds_min, sizeof(pt->sort_min));
    memcpy(pt->sort_max, frame->bounds_max, sizeof(pt->sort_max));
    if (!pt->graph || pt->g_pixels != pt->chunk || pt->g_events != events ||
        pt->g_mode != opts.mode || pt->g_direct != opts.direct_visibility ||
        pt->g_sort != sort) {
        pt->g_mode = opts.mode;
        pt->g_direct = opts.direct_visibility;
        pt->g_sort = sort;
        if (!make_graph(pt, events))
            goto done;
    }
    if (pt->samples == 0 && pt->part_done == 0) {
        if (pt->depth_pixels != pt->pixels) {
            free(pt->depth);
            free(pt->ids);
            pt->depth = malloc(pt->pixels * sizeof(float));
            pt->ids = malloc(pt->pixels * sizeof(float));
            pt->depth_pixels = pt->depth && pt->ids ? pt->pixels : 0;
        }
        if (!pt->depth_pixels) {
            DIRT_ERROR("out of memory for the depth of %zu pixels", pt->pixels);
            goto done;
        }
    }
    dirt_trace_alpha za = {.materials = pt->alpha ? pt->tables.materials : 0,
                           .texels = &pt->tables.texels, .seed = opts.seed};
    tech->reset_counts(tech->self);
    static const uint32_t zero = 0;
    glClearNamedBufferData(pt->events, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    st->events = events;
    /* Asynchronous timers: no pass waits for its time query; late times are
     * drained at the readback (dirt_pt_read). */
    fg_exec_opts eo = {.validate = true, .async_timers = true};
    bool partial = budget_ms >= 0;
    for (int s = 0; s < count; s++) {
        pt->sample = pt->samples;
        if (partial && pt->part_done == 0 && pt->samples > 0 && !keep_shown(pt))
            goto done;
        /* Pieces in pixel order: whole chunks, or (partial) parts of one
         * chunk; the pixels are the same either way (keyed by pixel). */
        while (pt->part_done < pt->pixels) {
            double p0 = dirt_clock_ms();
            size_t off = pt->part_done;
            size_t n = piece_pixels(pt, off, budget_ms, budget_ms - (p0 - t0));
            pt->cur_chunk = off / pt->chunk;
            pt->cur_offset = off;
            pt->cur_count = n;
            if (pt->samples == 0) {
                /* The depth AOV of these pixels first (its traces restart
                 * a randomised tracer's sequence), then sample 0's. */
                if (!pt_depth_render(pt->gpu, tech, cam, pt->width, pt->height, off, n,
                                     pt->chunk, &za, pt->depth, pt->ids))
                    goto done;
                if (tech->restart)
                    tech->restart(tech->self);
            }
            if (tech->begin_chunk)
                tech->begin_chunk(tech->self, (uint32_t)off);
            if (!fg_execute(pt->graph, &eo))
                goto done;
            add_times(pt, st);
            st->paths_at_event[1] += n; /* event 1: every pixel */
            pt->part_done += n;
            if (partial) {
                glFinish(); /* the pace of work done, not of work issued */
                double ms = dirt_clock_ms() - p0;
                double pace = (double)n / (ms > 0.01 ? ms : 0.01);
                pt->px_per_ms = pt->px_per_ms > 0 ? 0.5 * (pt->px_per_ms + pace) : pace;
                /* A last piece of under a quarter of the budget would cost
                 * its fixed overhead for little: the call ends instead. */
                if (dirt_clock_ms() - t0 >= 0.75 * budget_ms)
                    break;
            }
        }
        if (pt->part_done < pt->pixels)
            break; /* the budget ran out within the sample */
        pt->part_done = 0;
        pt->shown_current = false;
        pt->samples++;
        if (completed)
            *completed = true;
        if (opts.progress)
            opts.progress(opts.progress_user, s + 1, count);
    }
    /* The tracer's counters, the paths per event and (dirt_pt_read) the
     * accumulation are read back next. */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!tech->read_counts(tech->self, &st->rays, &st->aborted))
        goto done;
    uint32_t per_event[DIRT_PT_MAX_EVENTS];
    if (!gl_buffer_read(pt->events, 0, sizeof(per_event), per_event))
        goto done;
    for (int k = 2; k <= events && k < DIRT_PT_MAX_EVENTS; k++)
        st->paths_at_event[k] = per_event[k];
    if (st->aborted)
        DIRT_WARN("%llu rays ran out of march steps", (unsigned long long)st->aborted);
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
    st->bytes_integrator = integrator_bytes(pt) + tech->bytes_extra;
    ok = gl_check("dirt path tracer");
done:
    st->total_ms = dirt_clock_ms() - t0;
    dirt_area_lights_free(&area);
    gl_group_pop();
    pt->opts = NULL;
    pt->tech = NULL;
    return ok;
}

bool dirt_pt_add_samples(dirt_pt *pt, const dirt_tracer *tech, const dirt_frame *frame,
                         const dirt_camera *cam, const dirt_pt_opts *opts, int count,
                         dirt_pt_stats *stats)
{
    return run(pt, tech, frame, cam, opts, count, -1.0, NULL, stats);
}

bool dirt_pt_advance(dirt_pt *pt, const dirt_tracer *tech, const dirt_frame *frame,
                     const dirt_camera *cam, const dirt_pt_opts *opts, double budget_ms,
                     bool *completed, dirt_pt_stats *stats)
{
    return run(pt, tech, frame, cam, opts, 1, budget_ms < 0 ? 0 : budget_ms, completed, stats);
}

size_t dirt_pt_part_pixels(const dirt_pt *pt)
{
    return pt->accum_valid ? pt->part_done : 0;
}

bool dirt_pt_read(dirt_pt *pt, dirt_image *out, uint64_t *invalid_samples)
{
    if (!pt->accum_valid || !pt->samples) {
        DIRT_ERROR("no samples to read");
        return false;
    }
    if (out->width != pt->width || out->height != pt->height) {
        DIRT_ERROR("image %dx%d, accumulation %dx%d", out->width, out->height, pt->width,
                   pt->height);
        return false;
    }
    size_t pixels = pt->pixels;
    /* (dirt_pt_add_samples, the accumulation's only writer, ended with the
     * GL_BUFFER_UPDATE_BARRIER_BIT this readback needs.) */
    struct dirt_gpu_accum *sums = malloc(pixels * sizeof(*sums));
    bool got = sums != NULL;
    const GLuint *src = completed_sums(pt);
    for (size_t c = 0; got && c < pt->num_chunks; c++)
        got = gl_buffer_read(src[c], 0, chunk_pixels(pt, c) * sizeof(*sums),
                             sums + c * pt->chunk);
    if (!got) {
        free(sums);
        DIRT_ERROR("could not read the image back");
        return false;
    }
    float *albedo[3] = {dirt_image_find_channel(out, "albedo.R"),
                        dirt_image_find_channel(out, "albedo.G"),
                        dirt_image_find_channel(out, "albedo.B")};
    float *normal[3] = {dirt_image_find_channel(out, "N.X"), dirt_image_find_channel(out, "N.Y"),
                        dirt_image_find_channel(out, "N.Z")};
    float *z = dirt_image_find_channel(out, "Z");
    if (z && pt->depth_pixels == pixels)
        memcpy(z, pt->depth, pixels * sizeof(float));
    float *ids = dirt_image_find_channel(out, "ID");
    if (ids && pt->depth_pixels == pixels)
        memcpy(ids, pt->ids, pixels * sizeof(float));
    /* The display pass multiplies by the same float (glsl/integrator/display.comp). */
    float inv = 1.0f / (float)pt->samples;
    uint64_t invalid = 0;
    for (size_t i = 0; i < pixels; i++) {
        out->rgba[4 * i + 0] = sums[i].color.x * inv;
        out->rgba[4 * i + 1] = sums[i].color.y * inv;
        out->rgba[4 * i + 2] = sums[i].color.z * inv;
        out->rgba[4 * i + 3] = 1.0f;
        invalid += (uint64_t)sums[i].albedo.w;
        float a[3] = {sums[i].albedo.x, sums[i].albedo.y, sums[i].albedo.z};
        float n[3] = {sums[i].normal.x, sums[i].normal.y, sums[i].normal.z};
        for (int k = 0; k < 3; k++) {
            if (albedo[k])
                albedo[k][i] = a[k] * inv;
            if (normal[k])
                normal[k][i] = n[k] * inv;
        }
    }
    free(sums);
    if (invalid_samples)
        *invalid_samples = invalid;
    /* The readback waited for the samples: their times have arrived. */
    drain_times(pt);
    return gl_check("dirt_pt_read");
}

uint32_t dirt_pt_display_texture(dirt_pt *pt)
{
    if (!pt->accum_valid || !pt->samples) {
        DIRT_ERROR("no samples to display");
        return 0;
    }
    if (!pt->display || pt->display_w != pt->width || pt->display_h != pt->height) {
        gl_texture_destroy(&pt->display);
        pt->display = gl_texture_2d(GL_RGBA32F, pt->width, pt->height, 1, "pt display");
        if (!pt->display)
            return 0;
        pt->display_w = pt->width;
        pt->display_h = pt->height;
        pt->display_samples = UINT32_MAX;
    }
    if (pt->display_samples == pt->samples)
        return pt->display;
    gl_group_push("dirt path tracer display");
    /* The accumulation was written by shader stores; the texture's readers
     * (the window's draw of the last frame) finish before the stores. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(pt->prog_display);
    glUniform1i(DIRT_LOC_DISPLAY_WIDTH, pt->width);
    glUniform1f(DIRT_LOC_DISPLAY_INV_SAMPLES, 1.0f / (float)pt->samples);
    glBindImageTexture(DIRT_UNIT_DISPLAY, pt->display, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    for (size_t c = 0; c < pt->num_chunks; c++) {
        /* Each chunk stores its own pixels; the barrier checker tracks the
         * whole texture, and two commands writing one need it. */
        if (c > 0)
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glUniform1ui(DIRT_LOC_DISPLAY_PIXELS, (GLuint)chunk_pixels(pt, c));
        glUniform1ui(DIRT_LOC_DISPLAY_PIXEL_OFFSET, (GLuint)(c * pt->chunk));
        bind(DIRT_BIND_ACCUM, completed_sums(pt)[c]);
        glDispatchCompute(groups(chunk_pixels(pt, c)), 1, 1);
    }
    glUseProgram(0);
    /* Readers sample it (the window's draw; a copy, gl_texture_read_rgba32f,
     * fences itself). */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    gl_group_pop();
    if (!gl_check("dirt_pt_display_texture"))
        return 0;
    pt->display_samples = pt->samples;
    return pt->display;
}

bool dirt_pt_render(dirt_pt *pt, const dirt_tracer *tech, const dirt_frame *frame,
                    const dirt_camera *cam, const dirt_pt_opts *opts, dirt_image *out,
                    dirt_pt_stats *stats)
{
    int spp = opts && opts->spp > 0 ? opts->spp : 1;
    dirt_pt_stats local;
    dirt_pt_stats *st = stats ? stats : &local;
    if (!dirt_pt_reset(pt, out->width, out->height) ||
        !dirt_pt_add_samples(pt, tech, frame, cam, opts, spp, st) ||
        !dirt_pt_read(pt, out, &st->invalid_samples))
        return false;
    dirt_pt_stats late;
    dirt_pt_take_late_times(pt, false, &late);
    dirt_pt_add_late_times(st, &late);
    return true;
}

void dirt_pt_add_late_times(dirt_pt_stats *st, const dirt_pt_stats *late)
{
    if (late->clock == DIRT_CLOCK_NONE)
        return;
    if (st->clock != DIRT_CLOCK_NONE && st->clock != late->clock) {
        DIRT_ERROR("late pass times of the %s clock, the others of the %s clock: left out",
                   dirt_clock_names[late->clock], dirt_clock_names[st->clock]);
        return;
    }
    st->clock = late->clock;
    for (int i = 0; i < DIRT_PT_NUM_PASSES; i++)
        st->pass_ms[i] += late->pass_ms[i];
    sum_kinds(st);
    st->mrays_per_s = st->trace_ms > 0 ? st->rays / (st->trace_ms * 1e3) : 0;
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
