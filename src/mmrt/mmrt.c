/* MMRT build: depth bounds, Hi-Z mip, store and reorder passes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "views/hiz.h"
#include "views/views_gpu.h"
#include "gl/program.h"
#include "mmrt_internal.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */
_Static_assert(DIRT_MMRT_END == DIRT_LIST_END, "list end");

const char *const dirt_mmrt_pass_names[DIRT_MMRT_NUM_PASSES] = {
    "mmrt clear", "mmrt depth bounds", "mmrt mip", "mmrt store", "mmrt reorder",
};

#define MMRT_ADVICE "use smaller views (-W/-H, --face-size), fewer views (--views) or fewer " \
                    "buckets (-B)"

const gl_split_desc *const mmrt_array_desc[MMRT_NUM_ARRAYS] = {
    [MMRT_VERTICES] = &gl_split_vertices,
    [MMRT_PRIM_MATERIAL] = &gl_split_prim_material,
    [MMRT_HEADS] = &(const gl_split_desc){
        .label = "MMRT bucket heads", .define = "DIRT_SPLIT_MMRT_HEADS",
        .record_bytes = DIRT_HEAD_BYTES, .format = GL_R32UI, .image = true,
        .binding = DIRT_BIND_MMRT_HEADS, .unit = DIRT_IMAGE_SPLIT_MMRT_HEADS, .readback = true,
        .advice = MMRT_ADVICE},
    [MMRT_TAILS] = &(const gl_split_desc){
        .label = "MMRT bucket tails", .define = "DIRT_SPLIT_MMRT_TAILS",
        .record_bytes = DIRT_HEAD_BYTES, .format = GL_R32UI, .image = true,
        .binding = DIRT_BIND_MMRT_TAILS, .unit = DIRT_IMAGE_SPLIT_MMRT_TAILS, .readback = true,
        .advice = MMRT_ADVICE},
    [MMRT_IDS] = &(const gl_split_desc){
        .label = "MMRT id nodes", .define = "DIRT_SPLIT_MMRT_IDS",
        .record_bytes = DIRT_MMRT_ID_NODE_BYTES, .format = GL_R32UI, .image = true,
        .binding = DIRT_BIND_MMRT_IDS, .unit = DIRT_IMAGE_SPLIT_MMRT_IDS, .readback = true,
        .advice = MMRT_ADVICE},
    [MMRT_DATA] = &(const gl_split_desc){
        .label = "MMRT data nodes", .define = "DIRT_SPLIT_MMRT_DATA",
        .record_bytes = DIRT_MMRT_DATA_NODE_BYTES, .format = GL_RGBA32UI, .image = true,
        .binding = DIRT_BIND_MMRT_DATA, .unit = DIRT_IMAGE_SPLIT_MMRT_DATA, .readback = true,
        .advice = MMRT_ADVICE},
    [MMRT_DEPTH] = &gl_split_depth,
};

void mmrt_arrays(dirt_mmrt *m, gl_split *arr[MMRT_NUM_ARRAYS])
{
    arr[MMRT_VERTICES] = &m->vertices;
    arr[MMRT_PRIM_MATERIAL] = &m->materials;
    arr[MMRT_HEADS] = &m->heads;
    arr[MMRT_TAILS] = &m->tails;
    arr[MMRT_IDS] = &m->ids;
    arr[MMRT_DATA] = &m->data;
    arr[MMRT_DEPTH] = &m->depth;
}

GLbitfield mmrt_split_barriers(dirt_mmrt *m)
{
    gl_split *arr[MMRT_NUM_ARRAYS];
    mmrt_arrays(m, arr);
    GLbitfield bits = 0;
    for (int i = 0; i < MMRT_NUM_ARRAYS; i++)
        bits |= gl_split_barrier(arr[i]);
    return bits;
}

bool mmrt_program_extra(dirt_mmrt *m, gl_split_program *p, const char *label,
                        const char *const *paths, const glsl_define *defs, size_t n,
                        unsigned arrays, const gl_split *extra)
{
    gl_split *arr[MMRT_NUM_ARRAYS];
    mmrt_arrays(m, arr);
    return gl_split_program_select(p, label, paths, defs, n, mmrt_array_desc, arr, MMRT_NUM_ARRAYS, arrays,
                                   extra);
}

bool mmrt_program(dirt_mmrt *m, gl_split_program *p, const char *label, const char *const *paths,
                  const glsl_define *defs, size_t n, unsigned arrays)
{
    return mmrt_program_extra(m, p, label, paths, defs, n, arrays, NULL);
}

/* Every program (but the alpha trace's) for the arrays' current layouts. */
static bool mmrt_programs(dirt_mmrt *m)
{
    const unsigned V = MMRT_ARR(MMRT_VERTICES), M = MMRT_ARR(MMRT_PRIM_MATERIAL);
    const unsigned D = MMRT_ARR(MMRT_DEPTH);
    if (!views_hiz_program(&m->prog_mip, m->depth.layout))
        return false;
    glsl_define defs[2] = {{"MMRT_NUM_VIEWS", m->nviews}, {"MMRT_PASS_DEPTH", "1"}};
    const char *paths[] = {"mmrt/raster.vert", "mmrt/raster.geom", "mmrt/raster.frag", NULL};
    if (!mmrt_program(m, &m->prog_depth, "mmrt depth bounds", paths, defs, 2, V | D))
        return false;
    defs[1].name = "MMRT_PASS_STORE";
    const char *trace[] = {"mmrt/trace.comp", NULL};
    const char *reorder[] = {"mmrt/reorder.comp", NULL};
    glsl_define sort_def = {"MMRT_SORT_LIST", "1"};
    return mmrt_program(m, &m->prog_store, "mmrt store", paths, defs, 2,
                        V | M | D | MMRT_ABUFFER) &&
           mmrt_program(m, &m->prog_reorder, "mmrt/reorder.comp", reorder, &sort_def,
                        m->opts.sort == DIRT_MMRT_SORT_LIST ? 1 : 0, MMRT_ABUFFER) &&
           mmrt_program(m, &m->prog_trace, "mmrt/trace.comp", trace, NULL, 0,
                        V | D | MMRT_ABUFFER);
}

void mmrt_bind_geometry(dirt_mmrt *m)
{
    gl_split_bind(&m->vertices);
    gl_split_bind(&m->materials);
}

static int views_in_mode(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? 1 : m == DIRT_VIEWS_CUBE ? 6 : 7;
}

dirt_mmrt *dirt_mmrt_create(dirt_gpu *gpu, const dirt_mmrt_opts *opts)
{
    dirt_mmrt *m = calloc(1, sizeof(*m));
    if (!m) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    m->gpu = gpu;
    if (opts)
        m->opts = *opts;
    m->opts.views.tile_size = 1;
    if (m->opts.buckets <= 0)
        m->opts.buckets = 4;
    if (m->opts.views.mode < DIRT_VIEWS_SINGLE || m->opts.views.mode > DIRT_VIEWS_CUBE_CAMERA) {
        DIRT_ERROR("unknown view mode %d", (int)m->opts.views.mode);
        goto error;
    }
    m->num_views = views_in_mode(m->opts.views.mode);
    GLint max_viewports = 0;
    glGetIntegerv(GL_MAX_VIEWPORTS, &max_viewports);
    if (max_viewports < m->num_views) {
        DIRT_ERROR("MMRT draws all %d views at once with viewport arrays; this GPU has %d "
                   "viewports", m->num_views, max_viewports);
        goto error;
    }
    snprintf(m->nviews, sizeof(m->nviews), "%d", m->num_views);
    /* The min/max pyramid is DIRT's, on a tile size of 1. */
    if (m->opts.sort == DIRT_MMRT_SORT_AUTO)
        m->opts.sort = dirt_gpu_get_caps(gpu)->software ? DIRT_MMRT_SORT_LIST
                                                        : DIRT_MMRT_SORT_REGISTERS;
    if (m->opts.sort != DIRT_MMRT_SORT_REGISTERS && m->opts.sort != DIRT_MMRT_SORT_LIST) {
        DIRT_ERROR("unknown sort %d", (int)m->opts.sort);
        goto error;
    }
    if (!mmrt_programs(m))
        goto error;
    glCreateVertexArrays(1, &m->vao);
    gl_label(GL_VERTEX_ARRAY, m->vao, "mmrt vao");
    glCreateFramebuffers(1, &m->fbo);
    gl_label(GL_FRAMEBUFFER, m->fbo, "mmrt raster atlas");
    m->views = gl_buffer_create(gpu, DIRT_MAX_VIEWS * sizeof(struct dirt_gpu_view), NULL,
                                false, "mmrt views");
    m->params = gl_buffer_create(gpu, sizeof(struct dirt_mmrt_gpu_params), NULL, false,
                                 "mmrt params");
    m->counters = gl_buffer_create(gpu, sizeof(struct dirt_mmrt_gpu_counters), NULL, true,
                                   "mmrt counters");
    if (!m->views || !m->params || !m->counters)
        goto error;
    if (!gl_timer_init(&m->trace_timer, gpu, "mmrt trace"))
        goto error;
    m->node_capacity = m->opts.initial_nodes;
    if (!gl_check("mmrt create"))
        goto error;
    return m;
error:
    dirt_mmrt_destroy(m);
    return NULL;
}

void dirt_mmrt_destroy(dirt_mmrt *m)
{
    if (!m)
        return;
    mmrt_tracer_release(m);
    gl_split_program_destroy(&m->prog_depth);
    gl_split_program_destroy(&m->prog_reorder);
    gl_split_program_destroy(&m->prog_store);
    gl_split_program_destroy(&m->prog_trace);
    gl_split_program_destroy(&m->prog_trace_alpha);
    gl_split_program_destroy(&m->prog_mip);
    if (m->vao)
        glDeleteVertexArrays(1, &m->vao);
    if (m->fbo)
        glDeleteFramebuffers(1, &m->fbo);
    gl_split *arr[MMRT_NUM_ARRAYS];
    mmrt_arrays(m, arr);
    for (int i = 0; i < MMRT_NUM_ARRAYS; i++)
        gl_split_release(arr[i]);
    GLuint *bufs[] = {&m->views, &m->params, &m->counters,
                      &m->rays, &m->hits};
    for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
        gl_buffer_destroy(bufs[i]);
    fg_destroy(m->g_build);
    fg_destroy(m->g_restore);
    fg_destroy(m->g_finish);
    gl_timer_release(&m->trace_timer);
    free(m->staging);
    free(m);
}

static bool upload_frame(dirt_mmrt *m, const dirt_frame *f)
{
    size_t nv = f->num_triangles * 3;
    if (f->num_triangles > (size_t)INT32_MAX / 3) {
        DIRT_ERROR("%zu triangles: more than one draw can hold", f->num_triangles);
        return false;
    }
    if (nv > m->staging_cap) {
        struct dirt_gpu_vertex *s = realloc(m->staging, nv * sizeof(*s));
        if (!s) {
            DIRT_ERROR("out of memory for %zu vertices", nv);
            return false;
        }
        m->staging = s;
        m->staging_cap = nv;
    }
    for (size_t i = 0; i < nv; i++) {
        m->staging[i].position = (dirt_f4){f->position[i][0], f->position[i][1],
                                           f->position[i][2], f->uv[i][0]};
        m->staging[i].normal = (dirt_f4){f->normal[i][0], f->normal[i][1], f->normal[i][2],
                                         f->uv[i][1]};
    }
    size_t n = f->num_triangles;
    if (!gl_split_ensure(m->gpu, &m->vertices, mmrt_array_desc[MMRT_VERTICES], n) ||
        !gl_split_ensure(m->gpu, &m->materials, mmrt_array_desc[MMRT_PRIM_MATERIAL], n) ||
        (n && (!gl_split_write(&m->vertices, 0, n, m->staging) ||
               !gl_split_write(&m->materials, 0, n, f->material))))
        return false;
    m->num_primitives = f->num_triangles;
    return true;
}

static void upload_views(dirt_mmrt *m)
{
    struct dirt_gpu_view gv[DIRT_MAX_VIEWS];
    views_pack_gpu(&m->set, gv);
    glNamedBufferSubData(m->views, 0, (GLsizeiptr)sizeof(gv), gv);
}

static void upload_params(dirt_mmrt *m)
{
    struct dirt_mmrt_gpu_params p = {
        .config = {m->set.count, m->opts.buckets, m->set.num_tiles, m->set.atlas_width},
        .pool = {(unsigned)m->node_capacity, (unsigned)m->set.pyramid_size,
                 (unsigned)m->set.atlas_height, 0},
    };
    glNamedBufferSubData(m->params, 0, sizeof(p), &p);
}

/* Most nodes the pools hold in one storage block: the data pool (32 B per
 * node) is the larger array. Past it they split (gl/split.h). */
static size_t block_nodes(const dirt_mmrt *m)
{
    int64_t max = dirt_gpu_get_caps(m->gpu)->max_ssbo_size;
    size_t lim = max > 0 ? (size_t)(max / DIRT_MMRT_DATA_NODE_BYTES) : (size_t)UINT32_MAX;
    return lim < (size_t)UINT32_MAX - 1 ? lim : (size_t)UINT32_MAX - 1;
}

/* Most nodes at all: the shaders index id node words with 32-bit uints. */
#define MMRT_MAX_NODES ((size_t)(UINT32_MAX / DIRT_MMRT_ID_UINTS) - 1)

static bool ensure_nodes(dirt_mmrt *m, size_t nodes)
{
    if (nodes > MMRT_MAX_NODES) {
        DIRT_ERROR("the A-buffer needs %zu fragment nodes, more than the %zu a 32-bit index "
                   "reaches: use smaller views or fewer views", nodes, MMRT_MAX_NODES);
        return false;
    }
    if (m->ids.buf[0] && m->data.buf[0] && m->node_capacity >= nodes)
        return true;
    gl_split_release(&m->ids);
    gl_split_release(&m->data);
    m->node_capacity = 0;
    if (!gl_split_ensure(m->gpu, &m->ids, mmrt_array_desc[MMRT_IDS], nodes) ||
        !gl_split_ensure(m->gpu, &m->data, mmrt_array_desc[MMRT_DATA], nodes))
        return false;
    m->node_capacity = nodes;
    return true;
}

/* The size checks that need no pass: the scene's arrays and the views'
 * (before any upload or pass; the nodes are sized by the store pass's
 * count). False after logging what to change. */
static bool check_sizes(dirt_mmrt *m, const dirt_frame *f)
{
    gl_split_layout l;
    size_t heads = (size_t)m->opts.buckets * (size_t)m->set.num_tiles;
    return gl_split_plan(m->gpu, mmrt_array_desc[MMRT_VERTICES], f->num_triangles, &l) &&
           gl_split_plan(m->gpu, mmrt_array_desc[MMRT_PRIM_MATERIAL], f->num_triangles, &l) &&
           gl_split_plan(m->gpu, mmrt_array_desc[MMRT_DEPTH], (size_t)m->set.pyramid_size, &l) &&
           gl_split_plan(m->gpu, mmrt_array_desc[MMRT_HEADS], heads, &l) &&
           gl_split_plan(m->gpu, mmrt_array_desc[MMRT_TAILS], heads, &l);
}

static bool ensure_targets(dirt_mmrt *m)
{
    const dirt_view_set *s = &m->set;
    size_t heads = (size_t)m->opts.buckets * (size_t)s->num_tiles;
    if (!gl_split_ensure(m->gpu, &m->depth, mmrt_array_desc[MMRT_DEPTH], s->pyramid_size))
        return false;
    if (!gl_split_ensure(m->gpu, &m->heads, mmrt_array_desc[MMRT_HEADS], heads) ||
        !gl_split_ensure(m->gpu, &m->tails, mmrt_array_desc[MMRT_TAILS], heads))
        return false;
    if (!m->node_capacity) {
        size_t automatic = (size_t)s->num_tiles * 2 + 1024;
        m->node_capacity = automatic < block_nodes(m) ? automatic : block_nodes(m);
    }
    if (!ensure_nodes(m, m->node_capacity))
        return false;
    if (m->fbo_width != s->atlas_width || m->fbo_height != s->atlas_height) {
        glNamedFramebufferParameteri(m->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, s->atlas_width);
        glNamedFramebufferParameteri(m->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, s->atlas_height);
        m->fbo_width = s->atlas_width;
        m->fbo_height = s->atlas_height;
    }
    return true;
}

void dirt_mmrt_bind(dirt_mmrt *m)
{
    mmrt_bind_geometry(m);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_VIEWS, m->views);
    gl_split_bind(&m->depth);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_PARAMS, m->params);
    gl_split_bind(&m->heads);
    gl_split_bind(&m->tails);
    gl_split_bind(&m->ids);
    gl_split_bind(&m->data);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MMRT_COUNTERS, m->counters);
}

void dirt_mmrt_gl_buffers(const dirt_mmrt *m, dirt_mmrt_gl *out)
{
    *out = (dirt_mmrt_gl){m->views, m->params, m->counters};
}

static void clear_lists(dirt_mmrt *m)
{
    static const uint32_t end = DIRT_LIST_END, zero = 0;
    gl_split_clear(&m->heads, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    glClearNamedBufferSubData(m->counters, GL_R32UI, 0, 16, GL_RED_INTEGER, GL_UNSIGNED_INT,
                              &zero);
}

/* Draws every triangle into every view with `program`: viewport and scissor
 * i are view i's rectangle in the raster atlas; the geometry shader picks
 * the viewport. */
static void raster_views(dirt_mmrt *m, GLuint program)
{
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    for (int i = 0; i < m->set.count; i++) {
        const dirt_view *v = &m->set.views[i];
        glViewportIndexedf((GLuint)i, (float)v->atlas_x, 0.0f, (float)v->width,
                           (float)v->height);
        glScissorIndexed((GLuint)i, v->atlas_x, 0, v->width, v->height);
    }
    glEnable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program);
    glBindVertexArray(m->vao);
    if (m->num_primitives)
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(m->num_primitives * 3));
    glBindVertexArray(0);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void fill_stats(dirt_mmrt *m, const struct dirt_mmrt_gpu_counters *c, int runs,
                       const double *ms, enum dirt_clock clock)
{
    dirt_mmrt_stats *st = &m->stats;
    const uint64_t B = (uint64_t)m->opts.buckets, P = (uint64_t)m->set.num_tiles;
    st->primitives = m->num_primitives;
    st->pixels = P;
    st->fragments = c->build.x;
    st->max_layers = c->build.y;
    st->long_lists = c->build.z;
    st->covered_pixels = c->build.w;
    st->avg_layers = st->covered_pixels ? (double)st->fragments / (double)st->covered_pixels : 0;
    st->store_runs = runs;
    st->sort = m->opts.sort;
    st->bytes_vertices = m->num_primitives * (3 * sizeof(struct dirt_gpu_vertex) + 4);
    st->bytes_depth = (uint64_t)m->set.pyramid_size * DIRT_DEPTH_ENTRY_BYTES;
    st->bytes_heads = 2 * DIRT_HEAD_BYTES * B * P;
    st->bytes_id_nodes_allocated = (uint64_t)m->node_capacity * DIRT_MMRT_ID_NODE_BYTES;
    st->bytes_id_nodes_used = st->fragments * DIRT_MMRT_ID_NODE_BYTES;
    st->bytes_data_nodes_allocated = (uint64_t)m->node_capacity * DIRT_MMRT_DATA_NODE_BYTES;
    st->bytes_data_nodes_used = st->fragments * DIRT_MMRT_DATA_NODE_BYTES;
    uint64_t fixed = st->bytes_vertices + st->bytes_depth + st->bytes_heads;
    st->bytes_total_allocated = fixed + st->bytes_id_nodes_allocated +
                                st->bytes_data_nodes_allocated;
    st->bytes_total_used = fixed + st->bytes_id_nodes_used + st->bytes_data_nodes_used;
    st->bytes_paper = (double)P * (8.0 + 8.0 * (double)B) +
                      (double)st->fragments * (DIRT_MMRT_ID_NODE_BYTES + DIRT_MMRT_DATA_NODE_BYTES);
    st->clock = clock;
    for (int i = 0; i < DIRT_MMRT_NUM_PASSES; i++)
        st->ms[i] = clock == DIRT_CLOCK_NONE ? -1 : ms[i];
}

/* ---- passes (bodies run by the frame graphs) ---- */

static bool exec_clear(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_mmrt *m = user;
    static const uint32_t depth_clear[2] = {DIRT_DEPTH_CLEAR_MIN, DIRT_DEPTH_CLEAR_MAX};
    static const uint32_t end = DIRT_LIST_END;
    gl_split_clear(&m->depth, GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, depth_clear);
    gl_split_clear(&m->tails, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    clear_lists(m);
    return true;
}

static bool exec_clear_lists(fg_ctx *ctx, void *user)
{
    (void)ctx;
    clear_lists(user);
    return true;
}

static bool exec_depth(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_mmrt *m = user;
    dirt_mmrt_bind(m);
    raster_views(m, m->prog_depth.id);
    return true;
}

static bool exec_mip(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_mmrt *m = user;
    dirt_mmrt_bind(m);
    views_hiz_dispatch(m->prog_mip.id, &m->set);
    return true;
}

static bool exec_store(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_mmrt *m = user;
    dirt_mmrt_bind(m);
    raster_views(m, m->prog_store.id);
    return true;
}

static bool exec_reorder(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_mmrt *m = user;
    dirt_mmrt_bind(m);
    glUseProgram(m->prog_reorder.id);
    gl_dispatch_rows((size_t)m->set.num_tiles);
    glUseProgram(0);
    return true;
}

static bool exec_read_counters(fg_ctx *ctx, void *user)
{
    dirt_mmrt *m = user;
    return fg_gl_read_buffer(ctx, m->r_counters, 0, sizeof(m->counters_cpu), &m->counters_cpu);
}

static void import_all(dirt_mmrt *m, fg_graph *g)
{
    gl_split_import(g, "vertices", &m->vertices, m->r_vertices);
    gl_split_import(g, "materials", &m->materials, m->r_materials);
    m->r_views = fg_import_buffer(g, "views", m->views, DIRT_MAX_VIEWS * sizeof(struct dirt_gpu_view));
    m->r_params = fg_import_buffer(g, "params", m->params, sizeof(struct dirt_mmrt_gpu_params));
    gl_split_import(g, "depth bounds", &m->depth, m->r_depth);
    gl_split_import(g, "heads", &m->heads, m->r_heads);
    gl_split_import(g, "tails", &m->tails, m->r_tails);
    gl_split_import(g, "id nodes", &m->ids, m->r_ids);
    gl_split_import(g, "data nodes", &m->data, m->r_data);
    m->r_counters = fg_import_buffer(g, "counters", m->counters,
                                     sizeof(struct dirt_mmrt_gpu_counters));
}

static fg_pass *raster_pass(dirt_mmrt *m, fg_graph *g, int which, fg_execute_fn fn)
{
    fg_pass *p = fg_add_pass(g, dirt_mmrt_pass_names[which], FG_RASTER, fn, m);
    fg_set_raster_size(p, &(fg_tex_desc){.width = m->set.atlas_width,
                                         .height = m->set.atlas_height});
    return p;
}

/* The store pass and the counter readback (build and restore graphs). */
static void add_store(dirt_mmrt *m, fg_graph *g)
{
    fg_pass *p = raster_pass(m, g, DIRT_MMRT_PASS_STORE, exec_store);
    gl_split_use(p, &m->vertices, m->r_vertices, FG_SSBO_READ);
    gl_split_use(p, &m->materials, m->r_materials, FG_SSBO_READ);
    fg_read(p, m->r_views, FG_SSBO_READ);
    fg_read(p, m->r_params, FG_SSBO_READ);
    gl_split_use(p, &m->depth, m->r_depth, FG_SSBO_READ);
    gl_split_use(p, &m->heads, m->r_heads, FG_SSBO_READ);
    gl_split_use(p, &m->heads, m->r_heads, FG_SSBO_WRITE);
    gl_split_use(p, &m->ids, m->r_ids, FG_SSBO_WRITE);
    gl_split_use(p, &m->data, m->r_data, FG_SSBO_WRITE);
    fg_use(p, m->r_counters, FG_SSBO_READ, NULL);
    fg_write(p, m->r_counters, FG_SSBO_WRITE);
    p = fg_add_pass(g, "read counters", FG_COMPUTE, exec_read_counters, m);
    fg_read(p, m->r_counters, FG_TRANSFER_READ);
    fg_keep(p);
}

/* The parts of the split arrays (what the graphs import). */
static void graph_parts(dirt_mmrt *m, int parts[MMRT_NUM_ARRAYS])
{
    gl_split *arr[MMRT_NUM_ARRAYS];
    mmrt_arrays(m, arr);
    for (int i = 0; i < MMRT_NUM_ARRAYS; i++)
        parts[i] = arr[i]->layout.parts;
}

/* Whether the graphs import what the arrays now hold. */
static bool graphs_current(dirt_mmrt *m)
{
    int parts[MMRT_NUM_ARRAYS];
    graph_parts(m, parts);
    return m->g_build && m->graph_atlas_w == m->set.atlas_width &&
           m->graph_atlas_h == m->set.atlas_height &&
           !memcmp(parts, m->graph_parts, sizeof(parts));
}

static bool make_graphs(dirt_mmrt *m)
{
    fg_destroy(m->g_build);
    fg_destroy(m->g_restore);
    fg_destroy(m->g_finish);
    m->g_build = gl_graph_create(m->gpu);
    m->g_restore = gl_graph_create(m->gpu);
    m->g_finish = gl_graph_create(m->gpu);
    if (!m->g_build || !m->g_restore || !m->g_finish)
        return false;
    fg_graph *g = m->g_build;
    import_all(m, g);
    fg_pass *p = fg_add_pass(g, dirt_mmrt_pass_names[DIRT_MMRT_PASS_CLEAR], FG_COMPUTE,
                             exec_clear, m);
    gl_split_use(p, &m->depth, m->r_depth, FG_TRANSFER_WRITE);
    gl_split_use(p, &m->tails, m->r_tails, FG_TRANSFER_WRITE);
    gl_split_use(p, &m->heads, m->r_heads, FG_TRANSFER_WRITE);
    fg_write(p, m->r_counters, FG_TRANSFER_WRITE);
    p = raster_pass(m, g, DIRT_MMRT_PASS_DEPTH, exec_depth);
    gl_split_use(p, &m->vertices, m->r_vertices, FG_SSBO_READ);
    fg_read(p, m->r_views, FG_SSBO_READ);
    fg_read(p, m->r_params, FG_SSBO_READ);
    gl_split_use(p, &m->depth, m->r_depth, FG_SSBO_READ);
    gl_split_use(p, &m->depth, m->r_depth, FG_SSBO_WRITE);
    p = fg_add_pass(g, dirt_mmrt_pass_names[DIRT_MMRT_PASS_MIP], FG_COMPUTE, exec_mip, m);
    fg_read(p, m->r_views, FG_SSBO_READ);
    gl_split_use(p, &m->depth, m->r_depth, FG_SSBO_READ);
    gl_split_use(p, &m->depth, m->r_depth, FG_SSBO_WRITE);
    add_store(m, g);

    g = m->g_restore;
    import_all(m, g);
    p = fg_add_pass(g, dirt_mmrt_pass_names[DIRT_MMRT_PASS_CLEAR], FG_COMPUTE, exec_clear_lists, m);
    gl_split_use(p, &m->heads, m->r_heads, FG_TRANSFER_WRITE);
    fg_write(p, m->r_counters, FG_TRANSFER_WRITE);
    add_store(m, g);

    g = m->g_finish;
    import_all(m, g);
    p = fg_add_pass(g, dirt_mmrt_pass_names[DIRT_MMRT_PASS_REORDER], FG_COMPUTE, exec_reorder, m);
    fg_read(p, m->r_params, FG_SSBO_READ);
    gl_split_use(p, &m->heads, m->r_heads, FG_SSBO_READ);
    gl_split_use(p, &m->heads, m->r_heads, FG_SSBO_WRITE);
    gl_split_use(p, &m->ids, m->r_ids, FG_SSBO_READ);
    gl_split_use(p, &m->ids, m->r_ids, FG_SSBO_WRITE);
    gl_split_use(p, &m->data, m->r_data, FG_SSBO_READ);
    gl_split_use(p, &m->tails, m->r_tails, FG_SSBO_WRITE);
    fg_use(p, m->r_counters, FG_SSBO_READ, NULL);
    fg_write(p, m->r_counters, FG_SSBO_WRITE);
    p = fg_add_pass(g, "read counters", FG_COMPUTE, exec_read_counters, m);
    fg_read(p, m->r_counters, FG_TRANSFER_READ);
    fg_keep(p);
    /* The three graphs share the A-buffer: each one's first access of a
     * buffer gets the barrier the others' writes need (fg_set_shared_imports). */
    fg_set_shared_imports(m->g_build, true);
    fg_set_shared_imports(m->g_restore, true);
    fg_set_shared_imports(m->g_finish, true);
    if (!fg_compile(m->g_build) || !fg_compile(m->g_restore) || !fg_compile(m->g_finish))
        return false;
    m->graph_atlas_w = m->set.atlas_width;
    m->graph_atlas_h = m->set.atlas_height;
    graph_parts(m, m->graph_parts);
    return true;
}

/* Points every graph at the current buffers (after growth). */
static void update_imports(dirt_mmrt *m)
{
    fg_graph *gs[3] = {m->g_build, m->g_restore, m->g_finish};
    for (int i = 0; i < 3; i++) {
        gl_split_set_imports(gs[i], &m->vertices, m->r_vertices);
        gl_split_set_imports(gs[i], &m->materials, m->r_materials);
        gl_split_set_imports(gs[i], &m->depth, m->r_depth);
        gl_split_set_imports(gs[i], &m->heads, m->r_heads);
        gl_split_set_imports(gs[i], &m->tails, m->r_tails);
        gl_split_set_imports(gs[i], &m->ids, m->r_ids);
        gl_split_set_imports(gs[i], &m->data, m->r_data);
    }
}

bool dirt_mmrt_build(dirt_mmrt *m, const dirt_frame *f, const dirt_camera *cam)
{
    double ms[DIRT_MMRT_NUM_PASSES] = {0};
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    m->built = false;
    int max_fb_w = 0, max_fb_h = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_fb_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_fb_h);
    dirt_view_opts vo = m->opts.views;
    vo.tile_size = 1;
    /* The raster limits are checked here rather than by dirt_views_setup,
     * whose advice names tiles: MMRT is per pixel, its advice is the views. */
    if (!dirt_views_setup(&m->set, cam, f->bounds_min, f->bounds_max, &vo, 0))
        return false;
    if (m->set.atlas_width > max_fb_w || m->set.atlas_height > max_fb_h) {
        DIRT_ERROR("the views need a raster of %dx%d pixels, more than this GPU's %dx%d: "
                   "use smaller views (-W/-H, --face-size) or fewer views (--views)",
                   m->set.atlas_width, m->set.atlas_height, max_fb_w, max_fb_h);
        return false;
    }
    float d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += (f->bounds_max[k] - f->bounds_min[k]) * (f->bounds_max[k] - f->bounds_min[k]);
    m->scene_diagonal = d2 > 0 && isfinite(d2) ? sqrtf(d2) : 1.0f;

    gl_group_push("mmrt build");
    bool ok = false;
    if (!check_sizes(m, f) || !upload_frame(m, f) || !ensure_targets(m))
        goto done;
    upload_views(m);
    upload_params(m);
    if (!mmrt_programs(m) || (!graphs_current(m) && !make_graphs(m)))
        goto done;
    update_imports(m);
    fg_exec_opts eo = {.validate = true};
    if (!fg_execute(m->g_build, &eo))
        goto done;
    fg_add_pass_times(m->g_build, dirt_mmrt_pass_names, DIRT_MMRT_NUM_PASSES, ms, &clock);
    int runs = 1;
    while (m->counters_cpu.build.x > m->node_capacity) {
        /* Plus a quarter; within one storage block while the need fits one. */
        size_t need = m->counters_cpu.build.x;
        size_t grown = need + need / 4;
        if (need <= block_nodes(m) && grown > block_nodes(m))
            grown = block_nodes(m);
        size_t before = m->node_capacity;
        if (!ensure_nodes(m, grown))
            goto done;
        DIRT_INFO("mmrt node pools grew from %zu to %zu nodes (%.1f MB); store pass rerun",
                  before, grown,
                  grown * (double)(DIRT_MMRT_ID_NODE_BYTES + DIRT_MMRT_DATA_NODE_BYTES) / 1e6);
        upload_params(m);
        if (!mmrt_programs(m) || (!graphs_current(m) && !make_graphs(m)))
            goto done;
        update_imports(m);
        if (!fg_execute(m->g_restore, &eo))
            goto done;
        fg_add_pass_times(m->g_restore, dirt_mmrt_pass_names, DIRT_MMRT_NUM_PASSES, ms, &clock);
        runs++;
    }
    if (!fg_execute(m->g_finish, &eo))
        goto done;
    fg_add_pass_times(m->g_finish, dirt_mmrt_pass_names, DIRT_MMRT_NUM_PASSES, ms, &clock);
    fill_stats(m, &m->counters_cpu, runs, ms, clock);
    ok = gl_check("mmrt build");
    m->built = ok;
done:
    glUseProgram(0);
    gl_group_pop();
    return ok;
}

const dirt_mmrt_stats *dirt_mmrt_get_stats(const dirt_mmrt *m)
{
    return &m->stats;
}

const dirt_view_set *dirt_mmrt_views(const dirt_mmrt *m)
{
    return &m->set;
}

int dirt_mmrt_buckets(const dirt_mmrt *m)
{
    return m->opts.buckets;
}

bool dirt_mmrt_read(dirt_mmrt *m, dirt_mmrt_data *out)
{
    memset(out, 0, sizeof(*out));
    if (!m->built) {
        DIRT_ERROR("no MMRT build to read");
        return false;
    }
    out->num_pixels = m->set.num_tiles;
    out->buckets = m->opts.buckets;
    out->pyramid_size = m->set.pyramid_size;
    out->num_nodes = (uint32_t)(m->stats.fragments < m->node_capacity ? m->stats.fragments
                                                                       : m->node_capacity);
    size_t heads = (size_t)out->buckets * (size_t)out->num_pixels;
    out->depth = malloc((size_t)out->pyramid_size * sizeof(*out->depth) + 8);
    out->heads = malloc(heads * DIRT_HEAD_BYTES + DIRT_HEAD_BYTES);
    out->tails = malloc(heads * DIRT_HEAD_BYTES + DIRT_HEAD_BYTES);
    out->ids = malloc((size_t)out->num_nodes * sizeof(*out->ids) + 16);
    out->data = malloc((size_t)out->num_nodes * sizeof(*out->data) + 32);
    if (!out->depth || !out->heads || !out->tails || !out->ids || !out->data) {
        DIRT_ERROR("out of memory reading the A-buffer back");
        dirt_mmrt_data_free(out);
        return false;
    }
    /* (The build's last pass, the counter readback, was fenced with
     * GL_BUFFER_UPDATE_BARRIER_BIT after every shader write of the build.) */
    size_t n = out->num_nodes;
    if (!gl_split_read(&m->depth, 0, (size_t)out->pyramid_size, out->depth) ||
        !gl_split_read(&m->heads, 0, heads, out->heads) ||
        !gl_split_read(&m->tails, 0, heads, out->tails) ||
        (n && !gl_split_read(&m->ids, 0, n, out->ids)) ||
        (n && !gl_split_read(&m->data, 0, n, out->data))) {
        dirt_mmrt_data_free(out);
        return false;
    }
    return true;
}

void dirt_mmrt_data_free(dirt_mmrt_data *d)
{
    if (!d)
        return;
    free(d->depth);
    free(d->heads);
    free(d->tails);
    free(d->ids);
    free(d->data);
    memset(d, 0, sizeof(*d));
}

void dirt_mmrt_unpack_normal(uint32_t p, float out[3])
{
    /* unpackSnorm2x16: clamp(s / 32767, -1, 1), x in the low half. */
    float ex = fmaxf((float)(int16_t)(p & 0xFFFFu) / 32767.0f, -1.0f);
    float ey = fmaxf((float)(int16_t)(p >> 16) / 32767.0f, -1.0f);
    float n[3] = {ex, ey, 1.0f - fabsf(ex) - fabsf(ey)};
    if (n[2] < 0) {
        n[0] = (1.0f - fabsf(ey)) * (ex >= 0 ? 1.0f : -1.0f);
        n[1] = (1.0f - fabsf(ex)) * (ey >= 0 ? 1.0f : -1.0f);
    }
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        out[k] = l > 0 ? n[k] / l : 0.0f;
}

void dirt_mmrt_print_stats(const dirt_mmrt *m, void *out)
{
    FILE *f = out;
    const dirt_mmrt_stats *s = &m->stats;
    fprintf(f, "MMRT A-buffer: %d view(s), %llu pixels, B = %d, %llu primitives\n",
            m->set.count, (unsigned long long)s->pixels, m->opts.buckets,
            (unsigned long long)s->primitives);
    fprintf(f, "  fragments %llu (%.2f M), covered pixels %llu, layers avg %.2f max %u, "
            "long lists %llu, store runs %d, sort %s\n", (unsigned long long)s->fragments,
            s->fragments / 1e6, (unsigned long long)s->covered_pixels, s->avg_layers,
            s->max_layers, (unsigned long long)s->long_lists, s->store_runs,
            s->sort == DIRT_MMRT_SORT_LIST ? "list" : "registers");
    fprintf(f, "  MB: vertices %.2f, depth+pyramid %.2f, heads+tails %.2f, id nodes %.2f/%.2f, "
            "data nodes %.2f/%.2f (used/allocated), total %.2f/%.2f, paper formula %.2f\n",
            s->bytes_vertices / 1e6, s->bytes_depth / 1e6, s->bytes_heads / 1e6,
            s->bytes_id_nodes_used / 1e6, s->bytes_id_nodes_allocated / 1e6,
            s->bytes_data_nodes_used / 1e6, s->bytes_data_nodes_allocated / 1e6,
            s->bytes_total_used / 1e6, s->bytes_total_allocated / 1e6, s->bytes_paper / 1e6);
    fprintf(f, "  ms (%s clock):", dirt_clock_names[s->clock]);
    for (int i = 0; i < DIRT_MMRT_NUM_PASSES; i++)
        fprintf(f, " %s %.2f%s", dirt_mmrt_pass_names[i] + 5, s->ms[i],
                i + 1 < DIRT_MMRT_NUM_PASSES ? "," : "\n");
}
