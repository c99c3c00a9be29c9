/* DIRT build stage: depth bounds (the exact range of every candidate,
 * stored), Hi-Z mip, count nodes (the node pool's size) and fill
 * primitives passes; a candidate bound pass sizes the candidate buffer when
 * its size is unknown. The depth bounds come from a raster pass (default)
 * or, in the compute build, from a candidate tiles pass and a compute range
 * pass; the later passes are the same. doc/dirt-build.md. */
#include "views/hiz.h"
#include "dirt/ads.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/clock.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "dirt/ads_internal.h"
#include "gl/graph_gl.h"
#include "views/views_gpu.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */

const char *const dirt_ads_pass_names[DIRT_ADS_NUM_PASSES] = {
    "clear", "depth bounds", "mip", "fill primitives", "count nodes", "candidate bound",
    "candidate tiles",
};


_Static_assert(DIRT_WORK_RECORD_NODES * DIRT_NODE_BYTES == DIRT_CANDIDATE_BYTES,
               "a work record (uvec4, as a candidate) fills DIRT_WORK_RECORD_NODES id nodes");
_Static_assert(DIRT_ADS_MAX_LARGE == DIRT_GPU_MAX_LARGE && DIRT_GPU_MAX_LARGE % 4 == 0,
               "one count of large primitives");

int dirt_ads_select_large(const dirt_frame *f, int max, double area_fraction,
                          uint32_t ids[DIRT_ADS_MAX_LARGE])
{
    if (max > DIRT_ADS_MAX_LARGE)
        max = DIRT_ADS_MAX_LARGE;
    double dx = (double)f->bounds_max[0] - f->bounds_min[0];
    double dy = (double)f->bounds_max[1] - f->bounds_min[1];
    double dz = (double)f->bounds_max[2] - f->bounds_min[2];
    double min_area = (area_fraction > 0 ? area_fraction : DIRT_ADS_LARGE_AREA) *
                      (dx * dx + dy * dy + dz * dz);
    /* The largest so far, by area descending (ties: id ascending). */
    double area[DIRT_ADS_MAX_LARGE];
    int n = 0;
    for (size_t p = 0; max > 0 && p < f->num_triangles; p++) {
        const float *a = f->position[3 * p], *b = f->position[3 * p + 1], *c = f->position[3 * p + 2];
        double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
        double e2[3] = {(double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2]};
        double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2],
               z = e1[0] * e2[1] - e1[1] * e2[0];
        double s = 0.5 * sqrt(x * x + y * y + z * z);
        if (!(s >= min_area && s > 0) || (n == max && s <= area[n - 1]))
            continue;
        int k = n < max ? n++ : n - 1;
        while (k > 0 && area[k - 1] < s) {
            area[k] = area[k - 1];
            ids[k] = ids[k - 1];
            k--;
        }
        area[k] = s;
        ids[k] = (uint32_t)p;
    }
    /* ascending ids */
    for (int i = 1; i < n; i++) {
        uint32_t v = ids[i];
        int k = i;
        for (; k > 0 && ids[k - 1] > v; k--)
            ids[k] = ids[k - 1];
        ids[k] = v;
    }
    return n;
}

const gl_split_desc *const ads_array_desc[ADS_NUM_ARRAYS] = {
    [ADS_VERTICES] = &gl_split_vertices,
    [ADS_PRIM_MATERIAL] = &gl_split_prim_material,
    [ADS_CANDIDATES] = &(const gl_split_desc){
        .label = "DIRT build's candidates", .define = "DIRT_SPLIT_CANDIDATES",
        .record_bytes = DIRT_CANDIDATE_BYTES, .format = GL_RGBA32UI, .image = true,
        .binding = DIRT_BIND_CANDIDATES, .unit = DIRT_IMAGE_SPLIT_CANDIDATES,
        .advice = "use larger tiles (-S), smaller views or a scene of fewer triangles"},
    [ADS_NODES] = &(const gl_split_desc){
        .label = "DIRT id nodes", .define = "DIRT_SPLIT_NODES", .record_bytes = DIRT_NODE_BYTES,
        .format = GL_RG32UI, .image = true, .binding = DIRT_BIND_NODES,
        .unit = DIRT_IMAGE_SPLIT_NODES, .readback = true,
        .advice = "use larger tiles (-S), fewer buckets (-B), smaller views or a scene of "
                  "fewer triangles"},
    [ADS_HEADS] = &(const gl_split_desc){
        .label = "DIRT list heads", .define = "DIRT_SPLIT_HEADS", .record_bytes = DIRT_HEAD_BYTES,
        .format = GL_R32UI, .image = true, .binding = DIRT_BIND_HEADS,
        .unit = DIRT_IMAGE_SPLIT_HEADS, .readback = true,
        .advice = "use larger tiles (-S), fewer buckets (-B) or smaller views"},
    [ADS_DEPTH] = &gl_split_depth,
};

/* The structure's split arrays, by enum ads_array. */
static void ads_arrays(dirt_ads *a, gl_split *arr[ADS_NUM_ARRAYS])
{
    arr[ADS_VERTICES] = &a->vertices;
    arr[ADS_PRIM_MATERIAL] = &a->prim_material;
    arr[ADS_CANDIDATES] = &a->cands;
    arr[ADS_NODES] = &a->nodes;
    arr[ADS_HEADS] = &a->heads;
    arr[ADS_DEPTH] = &a->depth;
}

bool ads_program_extra(dirt_ads *a, gl_split_program *p, const char *label,
                       const char *const *paths, const glsl_define *defs, size_t n,
                       unsigned arrays, const gl_split *extra)
{
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    return gl_split_program_select(p, label, paths, defs, n, ads_array_desc, arr, ADS_NUM_ARRAYS, arrays,
                                   extra);
}

bool ads_program(dirt_ads *a, gl_split_program *p, const char *label, const char *const *paths,
                 const glsl_define *defs, size_t n, unsigned arrays)
{
    return ads_program_extra(a, p, label, paths, defs, n, arrays, NULL);
}

bool ads_programs(dirt_ads *a)
{
    const unsigned V = ADS_ARR(ADS_VERTICES), M = ADS_ARR(ADS_PRIM_MATERIAL);
    const unsigned C = ADS_ARR(ADS_CANDIDATES), N = ADS_ARR(ADS_NODES), H = ADS_ARR(ADS_HEADS);
    const unsigned D = ADS_ARR(ADS_DEPTH);
    if (!views_hiz_program(&a->prog_mip, a->depth.layout))
        return false;
    glsl_define defs[5] = {{"DIRT_NUM_VIEWS", a->nviews}, {"DIRT_PASS_DEPTH", "1"}};
    size_t ndefs = 2;
    if (a->use_nv)
        defs[ndefs++] = (glsl_define){"DIRT_CONSERVATIVE_NV", "1"};
    if (a->opts.reference_clip)
        defs[ndefs++] = (glsl_define){"DIRT_CLIP_SH", "1"};
    /* sub-tile rectangles: the depth pass (raster) or the range pass
     * (compute) only */
    glsl_define sub = {"DIRT_SUB_TILES", "1"};
    const char *paths[] = {"dirt/build.vert", "dirt/build.geom", "dirt/build.frag", NULL};
#define COMP(name) (const char *const[]){name, NULL}
    if (a->opts.build == DIRT_BUILD_COMPUTE) {
        /* the compute build's passes take DIRT_CLIP_SH (and the range pass
         * DIRT_SUB_TILES) only */
        glsl_define sh[2] = {{"DIRT_CLIP_SH", "1"}, sub};
        size_t nsh = a->opts.reference_clip ? 1 : 0;
        glsl_define *rd = a->opts.reference_clip ? sh : sh + 1;
        size_t nrd = nsh + (a->opts.sub_tiles ? 1 : 0);
        /* (the work records in the node pool) */
        if (!ads_program(a, &a->prog_tiles, "dirt/tiles.comp", COMP("dirt/tiles.comp"), sh,
                         nsh, V | N) ||
            !ads_program(a, &a->prog_range, "dirt/range.comp", COMP("dirt/range.comp"), rd,
                         nrd, V | C | D | N))
            return false;
    } else {
        if (a->opts.sub_tiles)
            defs[ndefs] = sub;
        if (!ads_program(a, &a->prog_depth, "dirt depth bounds", paths, defs,
                         ndefs + (a->opts.sub_tiles ? 1 : 0), V | C | D))
            return false;
        defs[1].name = "DIRT_PASS_BOUND";
        if (!ads_program(a, &a->prog_bound, "dirt candidate bound", paths, defs, ndefs, V))
            return false;
    }
    defs[1].name = "DIRT_PASS_FETCH";
    const char *vis[] = {"dirt/visibility.vert", "dirt/visibility.frag", NULL};
    /* adaptive depth buckets: their passes, and the count pass and the trace
     * through the edges */
    bool adapt = a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE;
    glsl_define ad = {"DIRT_ADAPTIVE", "1"};
    if (adapt &&
        (!ads_program(a, &a->prog_hist, "dirt/bucket_hist.comp", COMP("dirt/bucket_hist.comp"),
                      NULL, 0, C | D | H) ||
         !ads_program(a, &a->prog_edges, "dirt/bucket_edges.comp",
                      COMP("dirt/bucket_edges.comp"), NULL, 0, H)))
        return false;
    /* the count pass: through the edges (adaptive), setting the bucket
     * masks (ads_has_masks); the heads' array only for those */
    bool masks = ads_has_masks(a);
    /* node depth ranges: the count pass hands them to the fill pass */
    bool nd = a->opts.node_depths;
    glsl_define ndd = {"DIRT_NODE_DEPTHS", "1"};
    glsl_define cd[3] = {ad};
    size_t ncd = adapt ? 1 : 0;
    if (masks)
        cd[ncd++] = (glsl_define){"DIRT_BUCKET_MASKS", "1"};
    if (nd)
        cd[ncd++] = ndd;
    return ads_program(a, &a->prog_count, "dirt/count.comp", COMP("dirt/count.comp"), cd, ncd,
                       adapt || masks || nd ? C | D | H : C | D) &&
           ads_program(a, &a->prog_fill, "dirt/fill.comp", COMP("dirt/fill.comp"), &ndd,
                       nd ? 1 : 0, C | N | H) &&
           ads_program(a, &a->prog_trace[0], "dirt/trace.comp", COMP("dirt/trace.comp"), &ad,
                       adapt ? 1 : 0, ADS_TRACE_ARRAYS) &&
           ads_program(a, &a->prog_fetch, "dirt/fetch.comp", COMP("dirt/fetch.comp"), NULL, 0,
                       V | M) &&
           ads_program(a, &a->prog_fetch_miss, "dirt/fetch_miss.comp",
                       COMP("dirt/fetch_miss.comp"), NULL, 0, V | M) &&
           ads_program(a, &a->prog_fetch_raster, "dirt fetch (raster)", paths, defs, ndefs,
                       V | M) &&
           ads_program(a, &a->prog_vis, "dirt direct visibility", vis, NULL, 0, V) &&
           ads_program(a, &a->prog_vis_resolve, "dirt/visibility_resolve.comp",
                       COMP("dirt/visibility_resolve.comp"), NULL, 0, V);
#undef COMP
}

static int views_in_mode(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? 1 : m == DIRT_VIEWS_CUBE ? 6 : 7;
}

enum dirt_build_mode dirt_build_from_env(enum dirt_build_mode fallback)
{
    const char *e = getenv("DIRT_BUILD");
    if (e && !strcmp(e, "compute"))
        return DIRT_BUILD_COMPUTE;
    if (e && !strcmp(e, "raster"))
        return DIRT_BUILD_RASTER;
    return fallback;
}

dirt_ads *dirt_ads_create(dirt_gpu *gpu, const dirt_ads_opts *opts)
{
    dirt_ads *a = calloc(1, sizeof(*a));
    if (!a) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    a->gpu = gpu;
    if (opts)
        a->opts = *opts;
    if (a->opts.buckets <= 0)
        a->opts.buckets = 16;
    if (a->opts.buckets > 65535) { /* a candidate packs two bucket indices in 32 bits */
        DIRT_ERROR("%d buckets: at most 65535", a->opts.buckets);
        goto error;
    }
    if (a->opts.depth_buckets != DIRT_DEPTH_BUCKETS_UNIFORM &&
        a->opts.depth_buckets != DIRT_DEPTH_BUCKETS_ADAPTIVE) {
        DIRT_ERROR("unknown depth bucket mode %d", (int)a->opts.depth_buckets);
        goto error;
    }
    if (a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE &&
        a->opts.buckets > DIRT_ADAPT_MAX_BUCKETS) {
        DIRT_ERROR("%d buckets: adaptive depth buckets take at most %d", a->opts.buckets,
                   DIRT_ADAPT_MAX_BUCKETS);
        goto error;
    }
    if (a->opts.node_depths && a->opts.buckets > DIRT_NODE_DEPTH_MAX_BUCKETS) {
        DIRT_ERROR("%d buckets: node depth ranges take at most %d", a->opts.buckets,
                   DIRT_NODE_DEPTH_MAX_BUCKETS);
        goto error;
    }
    a->node_depth_max_nodes = DIRT_NODE_DEPTH_MAX_NODES;
    if (a->opts.views.mode < DIRT_VIEWS_SINGLE || a->opts.views.mode > DIRT_VIEWS_CUBE_CAMERA) {
        DIRT_ERROR("unknown view mode %d", (int)a->opts.views.mode);
        goto error;
    }
    if (a->opts.build == DIRT_BUILD_DEFAULT)
        a->opts.build = dirt_build_from_env(DIRT_BUILD_RASTER);
    if (a->opts.build != DIRT_BUILD_RASTER && a->opts.build != DIRT_BUILD_COMPUTE) {
        DIRT_ERROR("unknown build mode %d", (int)a->opts.build);
        goto error;
    }
    bool compute = a->opts.build == DIRT_BUILD_COMPUTE;
    (void)compute;
    a->num_views = views_in_mode(a->opts.views.mode);
    /* (also the raster Fetch's, whichever build) */
    a->use_nv = dirt_gpu_get_caps(gpu)->nv_conservative_raster && !a->opts.force_emulation;

    snprintf(a->nviews, sizeof(a->nviews), "%d", a->num_views);
    /* every program, for arrays in one storage block until a build says
     * otherwise */
    if (!ads_programs(a))
        goto error;
    glCreateVertexArrays(1, &a->vis_vao);
    glCreateVertexArrays(1, &a->fetch_vao);
    gl_label(GL_VERTEX_ARRAY, a->fetch_vao, "dirt fetch vao");
    glCreateFramebuffers(1, &a->fetch_fbo);
    gl_label(GL_FRAMEBUFFER, a->fetch_fbo, "dirt fetch atlas");
    a->fetch_params = gl_buffer_create(gpu, sizeof(struct dirt_gpu_fetch_params), NULL, false,
                                       "dirt fetch params");
    if (!a->fetch_params)
        goto error;
    if (!gl_timer_init(&a->trace_timer, gpu, "dirt trace"))
        goto error;
    a->views = gl_buffer_create(gpu, DIRT_MAX_VIEWS * sizeof(struct dirt_gpu_view), NULL,
                                false, "dirt views");
    a->params = gl_buffer_create(gpu, sizeof(struct dirt_gpu_ads_params), NULL, false,
                                 "dirt params");
    a->counters = gl_buffer_create(gpu, sizeof(struct dirt_gpu_ads_counters), NULL, true,
                                   "dirt counters");
    if (!a->views || !a->params || !a->counters)
        goto error;
    a->node_capacity = a->opts.initial_nodes;
    a->cand_capacity = a->opts.initial_candidates;
    return a;
error:
    dirt_ads_destroy(a);
    return NULL;
}

void dirt_ads_destroy(dirt_ads *a)
{
    if (!a)
        return;
    gl_split_program *progs[] = {&a->prog_depth, &a->prog_bound, &a->prog_tiles, &a->prog_range,
                                 &a->prog_count, &a->prog_fill, &a->prog_fetch,
                                 &a->prog_fetch_miss, &a->prog_fetch_raster, &a->prog_vis,
                                 &a->prog_vis_resolve, &a->prog_hist, &a->prog_edges};
    for (size_t i = 0; i < sizeof(progs) / sizeof(progs[0]); i++)
        gl_split_program_destroy(progs[i]);
    for (size_t k = 0; k < sizeof(a->prog_trace) / sizeof(a->prog_trace[0]); k++)
        gl_split_program_destroy(&a->prog_trace[k]);
    gl_split_program_destroy(&a->prog_mip);
    if (a->vis_vao)
        glDeleteVertexArrays(1, &a->vis_vao);
    if (a->vis_fbo)
        glDeleteFramebuffers(1, &a->vis_fbo);
    gl_texture_destroy(&a->vis_color);
    gl_texture_destroy(&a->vis_depth);
    if (a->fetch_vao)
        glDeleteVertexArrays(1, &a->fetch_vao);
    if (a->fetch_fbo)
        glDeleteFramebuffers(1, &a->fetch_fbo);
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    for (int i = 0; i < ADS_NUM_ARRAYS; i++)
        gl_split_release(arr[i]);
    gl_buffer_destroy(&a->hit_heads);
    gl_buffer_destroy(&a->fetch_params);
    free(a->material_staging);
    gl_buffer_destroy(&a->rays);
    gl_buffer_destroy(&a->hits);
    gl_buffer_destroy(&a->work);
    gl_buffer_destroy(&a->large_cells);
    free(a->large_staging);
    gl_timer_release(&a->trace_timer);
    fg_destroy(a->graph);
    fg_destroy(a->fill);
    fg_destroy(a->bound);
    GLuint *bufs[] = {&a->views, &a->params, &a->counters};
    for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
        gl_buffer_destroy(bufs[i]);
    free(a->staging);
    free(a);
}

static bool upload_frame(dirt_ads *a, const dirt_frame *f)
{
    size_t nv = f->num_triangles * 3;
    if (nv > a->staging_cap) {
        struct dirt_gpu_vertex *s = realloc(a->staging, nv * sizeof(*s));
        if (!s) {
            DIRT_ERROR("out of memory for %zu vertices", nv);
            return false;
        }
        a->staging = s;
        a->staging_cap = nv;
    }
    for (size_t i = 0; i < nv; i++) {
        a->staging[i].position = (dirt_f4){f->position[i][0], f->position[i][1],
                                           f->position[i][2], f->uv[i][0]};
        a->staging[i].normal = (dirt_f4){f->normal[i][0], f->normal[i][1], f->normal[i][2],
                                         f->uv[i][1]};
    }
    uint32_t *ms = realloc(a->material_staging, (f->num_triangles + 1) * sizeof(uint32_t));
    if (!ms) {
        DIRT_ERROR("out of memory");
        return false;
    }
    a->material_staging = ms;
    memcpy(ms, f->material, f->num_triangles * sizeof(uint32_t));
    /* (one record more than the primitives: never an empty buffer) */
    size_t n = f->num_triangles;
    if (!gl_split_ensure(a->gpu, &a->prim_material, ads_array_desc[ADS_PRIM_MATERIAL], n + 1) ||
        !gl_split_ensure(a->gpu, &a->vertices, ads_array_desc[ADS_VERTICES], n) ||
        (n && (!gl_split_write(&a->prim_material, 0, n, ms) ||
               !gl_split_write(&a->vertices, 0, n, a->staging))))
        return false;
    a->num_primitives = n;
    return true;
}

static void upload_views(dirt_ads *a)
{
    struct dirt_gpu_view gv[DIRT_MAX_VIEWS];
    views_pack_gpu(&a->set, gv);
    glNamedBufferSubData(a->views, 0, (GLsizeiptr)sizeof(gv), gv);
}

/* The compute build's work records the node pool holds (they live there
 * until the fill pass); 0 for the raster build, which has none. */
static size_t rec_capacity(const dirt_ads *a)
{
    return a->opts.build == DIRT_BUILD_COMPUTE ? a->node_capacity / DIRT_WORK_RECORD_NODES : 0;
}

static void upload_params(dirt_ads *a)
{
    struct dirt_gpu_ads_params p = {
        .config = {a->set.count, a->set.tile_size, a->opts.buckets, a->set.num_tiles},
        .pool = {(unsigned)a->node_capacity, (unsigned)a->set.pyramid_size,
                 (unsigned)a->set.atlas_width, (unsigned)a->set.atlas_height},
        .cand = {(unsigned)a->cand_capacity, (unsigned)rec_capacity(a),
                 (unsigned)a->num_primitives, (unsigned)a->stats.num_large},
    };
    for (int v = 0; v < DIRT_GPU_MAX_VIEWS; v++)
        p.large_grid[v] = a->large_grid[v];
    uint32_t large[DIRT_GPU_MAX_LARGE];
    for (int k = 0; k < DIRT_GPU_MAX_LARGE; k++)
        large[k] = k < a->stats.num_large ? a->stats.large[k] : DIRT_LIST_END;
    for (int q = 0; q < DIRT_GPU_MAX_LARGE / 4; q++)
        p.large[q] = (dirt_u4){large[4 * q], large[4 * q + 1], large[4 * q + 2], large[4 * q + 3]};
    glNamedBufferSubData(a->params, 0, sizeof(p), &p);
}

/* The float nearest below / above the double x (a range rounded outwards). */
static float float_below(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_above(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* The large primitives' grid (common/layout.h, "large primitives' grid"):
 * per view the first pyramid level of at most DIRT_LARGE_GRID cells per
 * side, and per cell and large primitive the depth range of the triangle
 * clipped to the cell's frustum (double precision, planes moved out by
 * DIRT_LARGE_CELL_EPS cell widths), widened by DIRT_LARGE_DEPTH_EPS times
 * the view's far depth and rounded outwards, so that any hit of the
 * primitive the trace can accept lies in the range of the cell its march is
 * in. Computed on the CPU from the frame's positions (at most 16
 * primitives) and uploaded; false (logged) on failure. */
static bool build_large_grid(dirt_ads *a, const dirt_frame *f)
{
    int nl = a->stats.num_large;
    size_t entries = 0;
    memset(a->large_grid, 0, sizeof(a->large_grid));
    a->large_entries = 0;
    if (!a->opts.large_grid || nl == 0)
        return true; /* (no grid: no entries, no buffer; the trace has none) */
    for (int v = 0; nl > 0 && v < a->set.count; v++) {
        const dirt_view *vw = &a->set.views[v];
        int L = 0;
        while (((vw->tiles_x + (1 << L) - 1) >> L) > DIRT_LARGE_GRID ||
               ((vw->tiles_y + (1 << L) - 1) >> L) > DIRT_LARGE_GRID)
            L++;
        int nx = (vw->tiles_x + (1 << L) - 1) >> L, ny = (vw->tiles_y + (1 << L) - 1) >> L;
        a->large_grid[v] = (struct dirt_i4){L, (int)entries, nx, ny};
        entries += (size_t)nx * (size_t)ny * (size_t)nl;
    }
    a->large_entries = entries;
    if (entries + 1 > a->large_staging_cap) {
        uint32_t(*s)[2] = realloc(a->large_staging, (entries + 1) * sizeof(*s));
        if (!s) {
            DIRT_ERROR("out of memory for the large primitives' grid");
            return false;
        }
        a->large_staging = s;
        a->large_staging_cap = entries + 1;
    }
    for (size_t i = 0; i <= entries; i++) {
        a->large_staging[i][0] = DIRT_DEPTH_CLEAR_MIN;
        a->large_staging[i][1] = DIRT_DEPTH_CLEAR_MAX;
    }
    for (int v = 0; nl > 0 && v < a->set.count; v++) {
        const dirt_view *vw = &a->set.views[v];
        struct dirt_i4 g = a->large_grid[v];
        int cs = a->set.tile_size << (g.x & 0xFFFF); /* a cell's pixels per side */
        double margin = DIRT_LARGE_DEPTH_EPS * vw->zfar;
        for (int k = 0; k < nl; k++) {
            float p[3][3];
            for (int c = 0; c < 3; c++)
                memcpy(p[c], f->position[3 * (size_t)a->stats.large[k] + c], sizeof(p[c]));
            int r[4];
            if (!dirt_triangle_tile_rect(vw, cs, p, 1.0, r))
                continue;
            for (int cy = r[2]; cy <= r[3] && cy < g.w; cy++) {
                for (int cx = r[0]; cx <= r[1] && cx < g.z; cx++) {
                    double lo, hi;
                    if (!dirt_clip_triangle_tile(vw, cs, cx, cy, p, DIRT_LARGE_CELL_EPS, &lo, &hi))
                        continue;
                    float flo = float_below(lo - margin), fhi = float_above(hi + margin);
                    uint32_t *e = a->large_staging[(size_t)g.y + ((size_t)cy * (size_t)g.z +
                                                                  (size_t)cx) * (size_t)nl + (size_t)k];
                    memcpy(&e[0], &flo, 4);
                    memcpy(&e[1], &fhi, 4);
                    a->large_grid[v].x = (int)((unsigned)a->large_grid[v].x | 1u << (16 + k));
                }
            }
        }
    }
    /* (one entry more: never an empty buffer) */
    size_t bytes = (entries + 1) * sizeof(*a->large_staging);
    if (!gl_buffer_ensure(a->gpu, &a->large_cells, &a->large_cells_size, bytes, false,
                          "dirt large primitives' grid"))
        return false;
    glNamedBufferSubData(a->large_cells, 0, (GLsizeiptr)bytes, a->large_staging);
    return true;
}

static bool ensure_nodes(dirt_ads *a, size_t nodes)
{
    if (!gl_split_ensure(a->gpu, &a->nodes, ads_array_desc[ADS_NODES], nodes)) {
        a->node_capacity = 0;
        return false;
    }
    a->node_capacity = a->nodes.capacity;
    return true;
}

/* Candidate buffer of at least `cands` candidates (at least one, so the
 * buffer always exists, and never fewer than before); false (logged) past
 * what the GPU can hold. */
static bool ensure_cands(dirt_ads *a, size_t cands)
{
    if (cands < 1)
        cands = 1;
    if (a->cands.buf[0] && cands < a->cand_capacity)
        cands = a->cand_capacity;
    if (a->cands.buf[0] && a->cand_capacity == cands)
        return true;
    gl_split_release(&a->cands);
    a->cand_capacity = 0;
    if (!gl_split_ensure(a->gpu, &a->cands, ads_array_desc[ADS_CANDIDATES], cands))
        return false;
    a->cand_capacity = cands;
    return true;
}

static size_t cands_bytes(const dirt_ads *a)
{
    return a->cand_capacity * DIRT_CANDIDATE_BYTES;
}

/* Grows a pool to `need` plus a quarter; not past one storage block when
 * `need` fits one (an array stays one block while it can). */
static size_t grown(const dirt_ads *a, size_t need, size_t bytes_each)
{
    size_t g = need + need / 4;
    int64_t max = dirt_gpu_get_caps(a->gpu)->max_ssbo_size;
    if (max > 0 && (int64_t)(need * bytes_each) <= max && (int64_t)(g * bytes_each) > max)
        g = (size_t)max / bytes_each;
    return g;
}

/* Records per tile before the bucket masks in the list-heads array: the
 * heads, and with adaptive depth buckets each tile's edges and histogram
 * (common/constants.h). */
static size_t heads_per_tile(const dirt_ads *a)
{
    return a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE
               ? (size_t)DIRT_ADAPT_TILE_UINTS(a->opts.buckets)
               : (size_t)a->opts.buckets;
}

bool ads_has_masks(const dirt_ads *a)
{
    return a->opts.bucket_masks && a->opts.buckets <= DIRT_BUCKET_MASK_MAX_BUCKETS;
}

/* Records of the list-heads array: heads_per_tile per tile, then one
 * bucket occupancy mask per tile when the structure has them
 * (ads_has_masks; common/constants.h, DIRT_BUCKET_MASK_*). */
static size_t heads_records(const dirt_ads *a, size_t tiles)
{
    return (heads_per_tile(a) + (ads_has_masks(a) ? 1 : 0)) * tiles;
}

/* The size checks that need no pass: the scene's arrays and the views'
 * (before any upload or pass; the candidates and the nodes are sized by
 * the passes that count them). False after logging what to change. */
static bool check_sizes(dirt_ads *a, const dirt_frame *f)
{
    gl_split_layout l;
    size_t heads = heads_records(a, (size_t)a->set.num_tiles);
    return gl_split_plan(a->gpu, ads_array_desc[ADS_VERTICES], f->num_triangles, &l) &&
           gl_split_plan(a->gpu, ads_array_desc[ADS_PRIM_MATERIAL], f->num_triangles + 1, &l) &&
           gl_split_plan(a->gpu, ads_array_desc[ADS_DEPTH], (size_t)a->set.pyramid_size, &l) &&
           gl_split_plan(a->gpu, ads_array_desc[ADS_HEADS], heads, &l);
}

static bool ensure_targets(dirt_ads *a)
{
    const dirt_view_set *s = &a->set;
    size_t heads = heads_records(a, (size_t)s->num_tiles);
    if (!gl_split_ensure(a->gpu, &a->depth, ads_array_desc[ADS_DEPTH], s->pyramid_size) ||
        !gl_split_ensure(a->gpu, &a->heads, ads_array_desc[ADS_HEADS], heads))
        return false;
    if (!a->node_capacity)
        a->node_capacity = (size_t)s->num_tiles * 4 + 1024;
    if (!ensure_nodes(a, a->node_capacity) || !ensure_cands(a, a->cand_capacity))
        return false;
    return true;
}

void ads_bind_split(dirt_ads *a)
{
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    for (int i = 0; i < ADS_NUM_ARRAYS; i++) {
        if (arr[i]->layout.parts)
            gl_split_bind(arr[i]);
    }
}

GLbitfield ads_split_barriers(dirt_ads *a)
{
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    GLbitfield bits = 0;
    for (int i = 0; i < ADS_NUM_ARRAYS; i++)
        bits |= gl_split_barrier(arr[i]);
    return bits;
}

void ads_bind_all(dirt_ads *a)
{
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    for (int i = 0; i < ADS_NUM_ARRAYS; i++)
        gl_split_bind(arr[i]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_VIEWS, a->views);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_PARAMS, a->params);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_COUNTERS, a->counters);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_LARGE_CELLS, a->large_cells);
}

/* ---- passes (bodies run by the frame graph) ---- */

static bool exec_clear(fg_ctx *ctx, void *user)
{
    dirt_ads *a = user;
    static const uint32_t depth_clear[2] = {DIRT_DEPTH_CLEAR_MIN, DIRT_DEPTH_CLEAR_MAX};
    static const uint32_t end = DIRT_LIST_END, zero = 0;
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && a->r_depth[k].id; k++)
        glClearNamedBufferData(fg_name(ctx, a->r_depth[k]), GL_RG32UI, GL_RG_INTEGER,
                               GL_UNSIGNED_INT, depth_clear);
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && a->r_heads[k].id; k++)
        glClearNamedBufferData(fg_name(ctx, a->r_heads[k]), GL_R32UI, GL_RED_INTEGER,
                               GL_UNSIGNED_INT, &end);
    glClearNamedBufferData(fg_name(ctx, a->r_counters), GL_R32UI, GL_RED_INTEGER,
                           GL_UNSIGNED_INT, &zero);
    return true;
}

static bool exec_clear_counters(fg_ctx *ctx, void *user)
{
    dirt_ads *a = user;
    static const uint32_t zero = 0;
    glClearNamedBufferData(fg_name(ctx, a->r_counters), GL_R32UI, GL_RED_INTEGER,
                           GL_UNSIGNED_INT, &zero);
    return true;
}

/* Draws every triangle into every view (the graph bound the attachment-less
 * atlas framebuffer, its viewport and an empty vertex array). */
static void draw_views(dirt_ads *a, GLuint program)
{
    ads_bind_split(a);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    if (a->use_nv)
        glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
    glUseProgram(program);
    if (a->num_primitives)
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(a->num_primitives * 3));
    glUseProgram(0);
    if (a->use_nv)
        glDisable(GL_CONSERVATIVE_RASTERIZATION_NV);
}

static bool exec_depth(fg_ctx *ctx, void *user)
{
    (void)ctx;
    draw_views(user, ((dirt_ads *)user)->prog_depth.id);
    return true;
}

/* Compute build: the candidate tiles of every (primitive, view). */
static bool exec_tiles(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_ads *a = user;
    ads_bind_split(a);
    glUseProgram(a->prog_tiles.id);
    gl_dispatch_rows(a->num_primitives * (size_t)a->num_views);
    glUseProgram(0);
    return true;
}

/* Compute build: the range of every candidate tile, groups from the
 * candidate tiles pass (counters.dispatch, bound as the indirect buffer). */
static bool exec_range(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_ads *a = user;
    ads_bind_split(a);
    glUseProgram(a->prog_range.id);
    glDispatchComputeIndirect((GLintptr)DIRT_ADS_DISPATCH_OFFSET);
    glUseProgram(0);
    return true;
}

static bool exec_bound(fg_ctx *ctx, void *user)
{
    (void)ctx;
    glEnable(GL_RASTERIZER_DISCARD);
    draw_views(user, ((dirt_ads *)user)->prog_bound.id);
    glDisable(GL_RASTERIZER_DISCARD);
    return true;
}

/* Count and fill dispatch over the candidate records: all the capacity
 * (count: the depth pass's count is on the GPU) or the count read back
 * (fill); the shaders bound-check against both. */
static bool exec_count(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_ads *a = user;
    ads_bind_split(a);
    if (a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE) {
        /* adaptive depth buckets: each tile's coverage histogram, then its
         * edges, which the count pass reads (timed with it) */
        GLbitfield bar = GL_SHADER_STORAGE_BARRIER_BIT | ads_split_barriers(a);
        glUseProgram(a->prog_hist.id);
        gl_dispatch_rows(a->cand_capacity);
        glMemoryBarrier(bar);
        glUseProgram(a->prog_edges.id);
        gl_dispatch_rows((size_t)a->set.num_tiles);
        glMemoryBarrier(bar);
    }
    glUseProgram(a->prog_count.id);
    gl_dispatch_rows(a->cand_capacity);
    glUseProgram(0);
    return true;
}

static bool exec_fill(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_ads *a = user;
    size_t n = a->counters_cpu.fill.y < a->cand_capacity ? a->counters_cpu.fill.y
                                                          : a->cand_capacity;
    if (n) {
        ads_bind_split(a);
        glUseProgram(a->prog_fill.id);
        if (a->opts.node_depths)
            glUniform1i(DIRT_LOC_FILL_NODE_DEPTHS, a->node_depths_stored ? 1 : 0);
        gl_dispatch_rows(n);
        glUseProgram(0);
    }
    return true;
}

static bool exec_mip(fg_ctx *ctx, void *user)
{
    (void)ctx;
    dirt_ads *a = user;
    ads_bind_split(a);
    views_hiz_dispatch(a->prog_mip.id, &a->set);
    return true;
}

static bool exec_read_counters(fg_ctx *ctx, void *user)
{
    dirt_ads *a = user;
    return fg_gl_read_buffer(ctx, a->r_counters, 0, sizeof(a->counters_cpu), &a->counters_cpu);
}

static void use(fg_pass *p, fg_res r, fg_access acc, unsigned binding)
{
    fg_use(p, r, acc, &(fg_use_opts){.bind = true, .binding = binding});
}

static void add_read_counters(dirt_ads *a, fg_graph *g)
{
    fg_pass *p = fg_add_pass(g, "read counters", FG_COMPUTE, exec_read_counters, a);
    fg_read(p, a->r_counters, FG_TRANSFER_READ);
    fg_keep(p);
}

static void raster_size(dirt_ads *a, fg_pass *p)
{
    fg_set_raster_size(p, &(fg_tex_desc){.width = a->set.atlas_width,
                                         .height = a->set.atlas_height});
}

/* The compute build's candidate tiles pass, named `pass` (candidate tiles
 * in the build graph; candidate bound in the bound graph, where its counts
 * size the buffer and the records it writes, within the capacity, are
 * written again by the build). */
static void add_tiles(dirt_ads *a, fg_graph *g, int pass)
{
    fg_pass *p = fg_add_pass(g, dirt_ads_pass_names[pass], FG_COMPUTE, exec_tiles, a);
    gl_split_use(p, &a->vertices, a->r_vertices, FG_SSBO_READ);
    use(p, a->r_views, FG_SSBO_READ, DIRT_BIND_VIEWS);
    use(p, a->r_params, FG_SSBO_READ, DIRT_BIND_PARAMS);
    use(p, a->r_counters, FG_SSBO_READ, DIRT_BIND_COUNTERS);
    use(p, a->r_counters, FG_SSBO_WRITE, DIRT_BIND_COUNTERS);
    gl_split_use(p, &a->nodes, a->r_nodes, FG_SSBO_WRITE); /* (the work records) */
}

/* The parts of the split arrays (what the graphs import). */
static void graph_parts(dirt_ads *a, int parts[ADS_NUM_ARRAYS])
{
    gl_split *arr[ADS_NUM_ARRAYS];
    ads_arrays(a, arr);
    for (int i = 0; i < ADS_NUM_ARRAYS; i++)
        parts[i] = arr[i]->layout.parts;
}

/* Whether the graphs import what the arrays now hold. */
static bool graphs_current(dirt_ads *a)
{
    int parts[ADS_NUM_ARRAYS];
    graph_parts(a, parts);
    return a->graph && a->graph_atlas_w == a->set.atlas_width &&
           a->graph_atlas_h == a->set.atlas_height &&
           !memcmp(parts, a->graph_parts, sizeof(parts));
}

/* Builds the three graphs over the structure's (imported) buffers. */
static bool make_graphs(dirt_ads *a)
{
    fg_destroy(a->graph);
    fg_destroy(a->fill);
    fg_destroy(a->bound);
    a->graph = gl_graph_create(a->gpu);
    a->fill = gl_graph_create(a->gpu);
    a->bound = gl_graph_create(a->gpu);
    if (!a->graph || !a->fill || !a->bound)
        return false;
    fg_graph *graphs[3] = {a->graph, a->fill, a->bound};
    for (int i = 0; i < 3; i++) {
        fg_graph *g = graphs[i];
        gl_split_import(g, "vertices", &a->vertices, a->r_vertices);
        a->r_views = fg_import_buffer(g, "views", a->views, DIRT_MAX_VIEWS * sizeof(struct dirt_gpu_view));
        a->r_params = fg_import_buffer(g, "params", a->params, sizeof(struct dirt_gpu_ads_params));
        gl_split_import(g, "depth bounds", &a->depth, a->r_depth);
        gl_split_import(g, "list heads", &a->heads, a->r_heads);
        gl_split_import(g, "id nodes", &a->nodes, a->r_nodes);
        a->r_counters = fg_import_buffer(g, "counters", a->counters,
                                         sizeof(struct dirt_gpu_ads_counters));
        gl_split_import(g, "candidates", &a->cands, a->r_cands);
    }
    /* build: clear, depth bounds, mip, count nodes, read counters */
    fg_graph *g = a->graph;
    fg_pass *p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_CLEAR], FG_COMPUTE, exec_clear, a);
    gl_split_use(p, &a->depth, a->r_depth, FG_TRANSFER_WRITE);
    gl_split_use(p, &a->heads, a->r_heads, FG_TRANSFER_WRITE);
    fg_write(p, a->r_counters, FG_TRANSFER_WRITE);
    bool compute = a->opts.build == DIRT_BUILD_COMPUTE;
    if (compute) {
        add_tiles(a, g, DIRT_ADS_PASS_TILES);
        p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_DEPTH], FG_COMPUTE, exec_range, a);
        use(p, a->r_counters, FG_INDIRECT, 0);
        gl_split_use(p, &a->nodes, a->r_nodes, FG_SSBO_READ); /* (the work records) */
    } else {
        p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_DEPTH], FG_RASTER, exec_depth, a);
        raster_size(a, p);
    }
    gl_split_use(p, &a->vertices, a->r_vertices, FG_SSBO_READ);
    use(p, a->r_views, FG_SSBO_READ, DIRT_BIND_VIEWS);
    use(p, a->r_params, FG_SSBO_READ, DIRT_BIND_PARAMS);
    gl_split_use(p, &a->depth, a->r_depth, FG_SSBO_READ);
    gl_split_use(p, &a->depth, a->r_depth, FG_SSBO_WRITE);
    use(p, a->r_counters, FG_SSBO_READ, DIRT_BIND_COUNTERS);
    use(p, a->r_counters, FG_SSBO_WRITE, DIRT_BIND_COUNTERS);
    gl_split_use(p, &a->cands, a->r_cands, FG_SSBO_WRITE);
    p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_MIP], FG_COMPUTE, exec_mip, a);
    use(p, a->r_views, FG_SSBO_READ, DIRT_BIND_VIEWS);
    gl_split_use(p, &a->depth, a->r_depth, FG_SSBO_READ);
    gl_split_use(p, &a->depth, a->r_depth, FG_SSBO_WRITE);
    p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_COUNT], FG_COMPUTE, exec_count, a);
    use(p, a->r_params, FG_SSBO_READ, DIRT_BIND_PARAMS);
    gl_split_use(p, &a->depth, a->r_depth, FG_SSBO_READ);
    use(p, a->r_counters, FG_SSBO_READ, DIRT_BIND_COUNTERS);
    use(p, a->r_counters, FG_SSBO_WRITE, DIRT_BIND_COUNTERS);
    gl_split_use(p, &a->cands, a->r_cands, FG_SSBO_READ);
    gl_split_use(p, &a->cands, a->r_cands, FG_SSBO_WRITE);
    if (a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE || ads_has_masks(a)) {
        /* (the histogram and edges after the heads, the bucket masks after
         * those) */
        gl_split_use(p, &a->heads, a->r_heads, FG_SSBO_READ);
        gl_split_use(p, &a->heads, a->r_heads, FG_SSBO_WRITE);
    }
    add_read_counters(a, g);
    /* fill: the lists, from the counted candidates */
    g = a->fill;
    p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_FILL], FG_COMPUTE, exec_fill, a);
    use(p, a->r_params, FG_SSBO_READ, DIRT_BIND_PARAMS);
    use(p, a->r_counters, FG_SSBO_READ, DIRT_BIND_COUNTERS);
    gl_split_use(p, &a->cands, a->r_cands, FG_SSBO_READ);
    gl_split_use(p, &a->heads, a->r_heads, FG_SSBO_READ);
    gl_split_use(p, &a->heads, a->r_heads, FG_SSBO_WRITE);
    gl_split_use(p, &a->nodes, a->r_nodes, FG_SSBO_WRITE);
    /* bound: an upper bound of the candidates */
    g = a->bound;
    p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_CLEAR], FG_COMPUTE, exec_clear_counters, a);
    fg_write(p, a->r_counters, FG_TRANSFER_WRITE);
    if (compute) {
        add_tiles(a, g, DIRT_ADS_PASS_BOUND);
    } else {
        p = fg_add_pass(g, dirt_ads_pass_names[DIRT_ADS_PASS_BOUND], FG_RASTER, exec_bound, a);
        raster_size(a, p);
        gl_split_use(p, &a->vertices, a->r_vertices, FG_SSBO_READ);
        use(p, a->r_views, FG_SSBO_READ, DIRT_BIND_VIEWS);
        use(p, a->r_params, FG_SSBO_READ, DIRT_BIND_PARAMS);
        use(p, a->r_counters, FG_SSBO_READ, DIRT_BIND_COUNTERS);
        use(p, a->r_counters, FG_SSBO_WRITE, DIRT_BIND_COUNTERS);
    }
    add_read_counters(a, g);
    /* The three graphs share the structure's buffers: each one's first
     * access of a buffer gets the barrier the others' writes need. */
    fg_set_shared_imports(a->graph, true);
    fg_set_shared_imports(a->fill, true);
    fg_set_shared_imports(a->bound, true);
    if (!fg_compile(a->graph) || !fg_compile(a->fill) || !fg_compile(a->bound))
        return false;
    a->graph_atlas_w = a->set.atlas_width;
    a->graph_atlas_h = a->set.atlas_height;
    graph_parts(a, a->graph_parts);
    return true;
}

/* Points the graphs at the current buffers (after growth). */
static void update_imports(dirt_ads *a)
{
    fg_graph *graphs[3] = {a->graph, a->fill, a->bound};
    for (int i = 0; i < 3; i++) {
        gl_split_set_imports(graphs[i], &a->vertices, a->r_vertices);
        gl_split_set_imports(graphs[i], &a->depth, a->r_depth);
        gl_split_set_imports(graphs[i], &a->heads, a->r_heads);
        gl_split_set_imports(graphs[i], &a->nodes, a->r_nodes);
        gl_split_set_imports(graphs[i], &a->cands, a->r_cands);
    }
}

/* Runs one graph, adds its pass times (the graphs share the structure's
 * buffers: fg_set_shared_imports fences what the others wrote). */
static bool run_graph(fg_graph *g, double *ms, enum dirt_clock *clock)
{
    fg_exec_opts eo = {.validate = true};
    if (!fg_execute(g, &eo))
        return false;
    fg_add_pass_times(g, dirt_ads_pass_names, DIRT_ADS_NUM_PASSES, ms, clock);
    return true;
}

/* After the arrays changed: the programs for their layouts, the graphs over
 * their parts, the parameters of their capacities. */
static bool refresh(dirt_ads *a)
{
    if (!ads_programs(a) || (!graphs_current(a) && !make_graphs(a)))
        return false;
    upload_params(a);
    update_imports(a);
    return true;
}

bool dirt_ads_build(dirt_ads *a, const dirt_frame *f, const dirt_camera *cam)
{
    dirt_ads_stats *st = &a->stats;
    double ms[DIRT_ADS_NUM_PASSES] = {0};
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    int max_fb = 0, max_fb_h = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_fb);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_fb_h);
    if (!dirt_views_setup(&a->set, cam, f->bounds_min, f->bounds_max, &a->opts.views, max_fb))
        return false;
    if (a->set.atlas_height > max_fb_h) {
        DIRT_ERROR("views need a raster %d tiles high, more than this GPU's %d",
                   a->set.atlas_height, max_fb_h);
        return false;
    }
    a->built = false;
    gl_group_push("dirt build");
    bool ok = false;
    if (a->opts.sub_tiles && f->num_triangles >= DIRT_SUBTILE_MAX_PRIMS) {
        DIRT_ERROR("sub-tile rectangles need primitive ids below %u (they share a word with "
                   "the rectangle); this frame has %zu triangles: build without them "
                   "(--sub-tiles off)", DIRT_SUBTILE_MAX_PRIMS, f->num_triangles);
        goto done;
    }
    if (!check_sizes(a, f) || !upload_frame(a, f) || !ensure_targets(a))
        goto done;
    memset(st->large, 0, sizeof(st->large));
    st->num_large = a->opts.large < 0 ? 0
                  : dirt_ads_select_large(f, a->opts.large ? a->opts.large : DIRT_ADS_MAX_LARGE,
                                          a->opts.large_area, st->large);
    upload_views(a);
    if (!build_large_grid(a, f))
        goto done;
    if (!refresh(a))
        goto done;
    /* The candidate buffer: from the bound pass when its size is unknown
     * (first build, other views or primitives), so the depth pass of a
     * first build never overflows it. */
    st->bound_pass = false;
    bool compute = a->opts.build == DIRT_BUILD_COMPUTE;
    bool unknown = a->cand_tiles == 0 ? !a->opts.initial_candidates /* the caller's choice */
                                      : a->cand_tiles != a->set.num_tiles ||
                                            a->cand_prims != a->num_primitives;
    if (unknown) {
        if (!run_graph(a->bound, ms, &clock))
            goto done;
        st->bound_pass = true;
        /* A bound past one storage block may be far above the real count:
         * the candidates get one block, and the depth pass grows them
         * (split) when it counts more. The compute build's work records
         * go to the node pool. */
        size_t bound = a->counters_cpu.build.x;
        size_t recs = compute ? a->counters_cpu.build.y : 0;
        int64_t max = dirt_gpu_get_caps(a->gpu)->max_ssbo_size;
        if (max > 0 && (int64_t)(bound * DIRT_CANDIDATE_BYTES) > max)
            bound = (size_t)max / DIRT_CANDIDATE_BYTES;
        if (!ensure_cands(a, bound) ||
            (recs > rec_capacity(a) && !ensure_nodes(a, recs * DIRT_WORK_RECORD_NODES)) ||
            !refresh(a))
            goto done;
    }
    a->cand_tiles = a->set.num_tiles;
    a->cand_prims = a->num_primitives;
    /* clear, depth bounds, mip, count nodes; again if the candidates
     * outgrew their buffer */
    st->depth_runs = 0;
    for (;;) {
        if (!run_graph(a->graph, ms, &clock))
            goto done;
        st->depth_runs++;
        size_t n = a->counters_cpu.fill.y;
        size_t r = compute ? a->counters_cpu.build.y : 0;
        if (n <= a->cand_capacity && r <= rec_capacity(a))
            break;
        /* Work records past their capacity leave candidates out (the range
         * pass never saw them): the candidates and the node pool grow, the
         * graph reruns. */
        size_t g = n > a->cand_capacity ? grown(a, n, DIRT_CANDIDATE_BYTES) : a->cand_capacity;
        /* (then the candidates the missing records hold are not counted
         * either: the tiles the records cover bound them) */
        if (r > rec_capacity(a) && a->counters_cpu.build.x > g)
            g = a->counters_cpu.build.x;
        if (g > a->cand_capacity) {
            DIRT_INFO("candidate buffer grew from %zu to %zu records (%.1f MB); depth pass "
                      "rerun", a->cand_capacity, g, g * DIRT_CANDIDATE_BYTES / 1e6);
            if (!ensure_cands(a, g))
                goto done;
        }
        if (r > rec_capacity(a)) {
            size_t gn = grown(a, r * DIRT_WORK_RECORD_NODES, DIRT_NODE_BYTES);
            DIRT_INFO("node pool grew from %zu to %zu nodes (%.1f MB) for %zu work records; "
                      "depth pass rerun", a->node_capacity, gn, gn * DIRT_NODE_BYTES / 1e6, r);
            if (!ensure_nodes(a, gn))
                goto done;
        }
        if (!refresh(a))
            goto done;
    }
    /* The node pool from the count, then the one fill pass. */
    if (a->counters_cpu.fill.x > a->node_capacity) {
        size_t g = grown(a, a->counters_cpu.fill.x, DIRT_NODE_BYTES);
        DIRT_INFO("node pool grew from %zu to %zu nodes (%.1f MB)", a->node_capacity, g,
                  g * DIRT_NODE_BYTES / 1e6);
        if (!ensure_nodes(a, g) || !refresh(a))
            goto done;
    }
    /* Node depth ranges fit the next words while every index fits 24 bits. */
    a->node_depths_stored = a->opts.node_depths && a->counters_cpu.fill.x <= a->node_depth_max_nodes;
    if (a->opts.node_depths && !a->node_depths_stored)
        DIRT_INFO("%u id nodes: more than %zu, so no node depth ranges in this build",
                  a->counters_cpu.fill.x, a->node_depth_max_nodes);
    if (!run_graph(a->fill, ms, &clock))
        goto done;
    st->fill_runs = 1;
    st->node_depths = a->node_depths_stored;
    /* (Its readers fence: the trace, Fetch and visibility at their entry,
     * dirt_ads_read before its readback.) */
    struct dirt_gpu_ads_counters counters = a->counters_cpu;
    st->primitives = a->num_primitives;
    st->tiles = (uint64_t)a->set.num_tiles;
    st->samples = counters.fill.y;
    st->nodes = counters.fill.x;
    st->buckets_per_sample = st->samples ? (double)st->nodes / (double)st->samples : 0;
    st->conservative_nv = a->use_nv && !compute;
    st->build = a->opts.build;
    st->work_records = compute ? counters.build.y : 0;
    st->bytes_vertices = a->num_primitives * 3 * sizeof(struct dirt_gpu_vertex);
    st->bytes_depth = (uint64_t)a->set.pyramid_size * DIRT_DEPTH_ENTRY_BYTES;
    st->bytes_heads = (uint64_t)a->opts.buckets * (uint64_t)a->set.num_tiles * DIRT_HEAD_BYTES;
    st->depth_buckets = a->opts.depth_buckets;
    bool adapt = a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE;
    st->bytes_bucket_edges = adapt ? (uint64_t)DIRT_ADAPT_EDGE_WORDS(a->opts.buckets) *
                                         (uint64_t)a->set.num_tiles * DIRT_HEAD_BYTES
                                   : 0;
    st->bytes_bucket_histogram = adapt ? (uint64_t)DIRT_ADAPT_FINE * (uint64_t)a->opts.buckets *
                                             (uint64_t)a->set.num_tiles * DIRT_HEAD_BYTES
                                       : 0;
    st->bytes_bucket_masks = ads_has_masks(a) ? (uint64_t)a->set.num_tiles * DIRT_HEAD_BYTES : 0;
    uint64_t extra_bytes = st->bytes_bucket_edges + st->bytes_bucket_histogram +
                           st->bytes_bucket_masks;
    st->bytes_nodes_allocated = (uint64_t)a->node_capacity * DIRT_NODE_BYTES;
    /* (the pool held the work records before the nodes) */
    uint64_t pool_used = st->work_records * DIRT_WORK_RECORD_NODES;
    if (pool_used < st->nodes)
        pool_used = st->nodes;
    st->bytes_nodes_used = pool_used * DIRT_NODE_BYTES;
    st->bytes_candidates_allocated = cands_bytes(a);
    st->bytes_candidates_used = st->samples * DIRT_CANDIDATE_BYTES;
    st->bytes_large_grid = a->large_entries * sizeof(*a->large_staging);
    st->bytes_large_grid_allocated = a->large_cells_size;
    st->bytes_total_allocated = st->bytes_vertices + st->bytes_depth + st->bytes_heads +
                                st->bytes_nodes_allocated + st->bytes_candidates_allocated +
                                st->bytes_large_grid_allocated + extra_bytes;
    st->bytes_total_used = st->bytes_vertices + st->bytes_depth + st->bytes_heads +
                           st->bytes_nodes_used + st->bytes_candidates_used +
                           st->bytes_large_grid + extra_bytes;
    st->bytes_table3 = (double)a->set.num_tiles * (8.0 * 1.33 + 4.0 * a->opts.buckets) +
                       8.0 * st->buckets_per_sample * (double)st->samples;
    st->clock = clock;
    for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++)
        st->ms[i] = clock == DIRT_CLOCK_NONE ? -1 : ms[i];
    ok = gl_check("dirt build");
done:
    a->built = ok;
    glUseProgram(0);
    gl_group_pop();
    return ok;
}

const dirt_ads_stats *dirt_ads_get_stats(const dirt_ads *a)
{
    return &a->stats;
}

const dirt_view_set *dirt_ads_views(const dirt_ads *a)
{
    return &a->set;
}

int dirt_ads_buckets(const dirt_ads *a)
{
    return a->opts.buckets;
}

bool dirt_ads_read(dirt_ads *a, dirt_ads_data *out)
{
    memset(out, 0, sizeof(*out));
    out->num_tiles = a->set.num_tiles;
    out->buckets = a->opts.buckets;
    out->pyramid_size = a->set.pyramid_size;
    out->num_nodes = (uint32_t)(a->stats.nodes < a->node_capacity ? a->stats.nodes
                                                                   : a->node_capacity);
    out->num_large = a->stats.num_large;
    memcpy(out->large, a->stats.large, sizeof(out->large));
    size_t heads = (size_t)out->buckets * (size_t)out->num_tiles;
    out->depth = malloc((size_t)out->pyramid_size * sizeof(*out->depth) + 8);
    out->heads = malloc(heads * DIRT_HEAD_BYTES + DIRT_HEAD_BYTES);
    out->nodes = malloc((size_t)out->num_nodes * DIRT_NODE_BYTES + DIRT_NODE_BYTES);
    if (!out->depth || !out->heads || !out->nodes) {
        DIRT_ERROR("out of memory reading the structure back");
        dirt_ads_data_free(out);
        return false;
    }
    /* The fill pass wrote the lists after the build's last counter readback. */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!gl_split_read(&a->depth, 0, (size_t)out->pyramid_size, out->depth) ||
        !gl_split_read(&a->heads, 0, heads, out->heads) ||
        (out->num_nodes && !gl_split_read(&a->nodes, 0, out->num_nodes, out->nodes))) {
        dirt_ads_data_free(out);
        return false;
    }
    if (a->opts.sub_tiles) {
        /* the rectangles apart, the ids plain */
        out->rects = malloc((size_t)out->num_nodes + 1);
        if (!out->rects) {
            DIRT_ERROR("out of memory reading the structure back");
            dirt_ads_data_free(out);
            return false;
        }
        for (uint32_t i = 0; i < out->num_nodes; i++) {
            out->rects[i] = (uint8_t)(out->nodes[i][0] >> DIRT_SUBTILE_SHIFT);
            out->nodes[i][0] &= DIRT_SUBTILE_PRIM_MASK;
        }
    }
    if (a->node_depths_stored) {
        /* the range bytes apart, the next words plain */
        out->node_depths = malloc((size_t)out->num_nodes + 1);
        if (!out->node_depths) {
            DIRT_ERROR("out of memory reading the structure back");
            dirt_ads_data_free(out);
            return false;
        }
        for (uint32_t i = 0; i < out->num_nodes; i++) {
            uint32_t next = out->nodes[i][1] & DIRT_NODE_NEXT_MASK;
            out->node_depths[i] = (uint8_t)(out->nodes[i][1] >> DIRT_NODE_DEPTH_SHIFT);
            out->nodes[i][1] = next == DIRT_NODE_NEXT_END ? DIRT_LIST_END : next;
        }
    }
    if (a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE) {
        int B = out->buckets, T = out->num_tiles;
        size_t words = (size_t)DIRT_ADAPT_EDGE_WORDS(B) * (size_t)T;
        uint32_t *w = malloc(words * DIRT_HEAD_BYTES + DIRT_HEAD_BYTES);
        out->fine_bins = DIRT_ADAPT_FINE * B;
        out->edges = malloc((size_t)(B + 1) * (size_t)T * sizeof(*out->edges));
        if (!w || !out->edges || (words && !gl_split_read(&a->heads, heads, words, w))) {
            if (!w || !out->edges)
                DIRT_ERROR("out of memory reading the structure back");
            free(w);
            dirt_ads_data_free(out);
            return false;
        }
        for (int t = 0; t < T; t++) {
            uint16_t *e = out->edges + (size_t)(B + 1) * (size_t)t;
            e[0] = 0;
            e[B] = (uint16_t)out->fine_bins;
            for (int b = 1; b < B; b++) {
                uint32_t x = w[(size_t)t * (size_t)DIRT_ADAPT_EDGE_WORDS(B) + (size_t)(b - 1) / 2];
                e[b] = (uint16_t)(b & 1 ? x & 0xFFFFu : x >> 16);
            }
        }
        free(w);
    }
    if (ads_has_masks(a)) {
        /* (stored as the empty buckets' bits: common/constants.h) */
        size_t T = (size_t)out->num_tiles;
        out->masks = malloc(T * DIRT_HEAD_BYTES + DIRT_HEAD_BYTES);
        if (!out->masks) {
            DIRT_ERROR("out of memory reading the structure back");
            dirt_ads_data_free(out);
            return false;
        }
        if (T && !gl_split_read(&a->heads, DIRT_BUCKET_MASK_INDEX(heads_per_tile(a), T, 0), T,
                                   out->masks)) {
            dirt_ads_data_free(out);
            return false;
        }
        for (size_t t = 0; t < T; t++)
            out->masks[t] = ~out->masks[t];
    }
    return true;
}

void dirt_ads_data_free(dirt_ads_data *d)
{
    if (!d)
        return;
    free(d->depth);
    free(d->heads);
    free(d->masks);
    free(d->nodes);
    free(d->rects);
    free(d->node_depths);
    free(d->edges);
    memset(d, 0, sizeof(*d));
}
