/* Raster preview: draws the evaluated frame with simple direct lighting into
 * a float colour target and reads it back, as a two-pass frame graph
 * (doc/frame-graph.md section 7):
 *
 *   "preview draw" (raster)    FG_VERTEX "preview vertices" (import),
 *                              FG_SSBO_READ "preview materials", "preview lights"
 *                              (imports, bound by the graph),
 *                              FG_SAMPLED scene textures + "white" (imports,
 *                              bound per material by the body),
 *                              FG_COLOR "preview color" (transient rgba32f),
 *                              FG_DEPTH "preview depth" (transient depth32f)
 *   "preview readback"         FG_TRANSFER_READ "preview color" into the
 *                              caller's buffer (fg_keep)
 *
 * The CPU uploads of vertices and lights (glNamedBufferSubData) happen before
 * fg_execute, outside the graph: GL orders API updates before later draws, so
 * they need no barrier. The graph is declared once at create, recompiled when
 * the image size changes, and its imports are repointed (fg_set_import) when
 * the vertex or light buffer grows. The vertices are a split array (gl/split.h:
 * one buffer while they fit one storage block, else parts of whole
 * triangles, each drawn on its own) and the graph is declared again when
 * their parts change. */
#include "raster/raster.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/graph_gl.h"
#include "gl/split.h"
#include "core/vec3.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */

#define PASS_DRAW "preview draw"
#define PASS_READBACK "preview readback"

/* Vertex of the preview's vertex buffer. */
typedef struct preview_vertex {
    float position[3];
    float normal[3];
    float uv[2];
} preview_vertex;

/* The vertex buffer, a split array of triangles (read as vertex attributes,
 * never as a storage block or texels: only its parts' sizes matter). */
static const gl_split_desc vbo_desc = {
    .label = "raster preview's vertices", .define = "DIRT_SPLIT_PREVIEW",
    .record_bytes = 3 * sizeof(preview_vertex), .format = GL_RGBA32F,
    .unit = DIRT_UNIT_SPLIT_VERTICES, .advice = "render a scene of fewer triangles",
};

/* Triangles of one material, contiguous in the vertex buffer. */
typedef struct material_range {
    uint32_t material;
    uint32_t first_vertex, num_vertices;
} material_range;

struct dirt_raster {
    dirt_gpu *gpu;
    const dirt_scene *scene;
    GLuint program;
    GLuint vao;
    gl_split vbo;         /* preview_vertex[3] per triangle */
    GLuint materials;
    size_t materials_bytes;
    GLuint lights;
    size_t lights_capacity;
    GLuint *textures;     /* one per scene texture (0 when it failed) */
    size_t num_textures;
    GLuint white;         /* 1x1 white texture for materials without one */
    /* frame graph: declared at create, compiled for graph_width x graph_height
     * (0 x 0 = not compiled yet, or the last compile failed) */
    fg_graph *graph;
    fg_res res_vertices[DIRT_SPLIT_MAX_PARTS];
    fg_res res_materials, res_lights, res_color, res_aov, res_depth;
    int graph_width, graph_height;
    int graph_parts;      /* the vertex buffer's parts the graph imports */
    /* what the pass bodies of the current render need */
    struct {
        float view_proj[16];
        const float *eye;
        float forward[3]; /* unit camera axis (the Z AOV) */
        int num_lights;
        float ambient;
        float *rgba;      /* caller's width*height*4 floats */
        float *aov;       /* caller's width*height*4 floats (N.xyz, Z) or NULL */
        int width, height;
    } frame;
    /* CPU staging, reused between frames */
    preview_vertex *staging;
    uint32_t *order;
    material_range *ranges;
    size_t num_ranges;
};

static bool upload_textures(dirt_raster *r)
{
    const dirt_texture *tex = dirt_scene_textures(r->scene);
    r->num_textures = dirt_scene_num_textures(r->scene);
    r->textures = calloc(r->num_textures ? r->num_textures : 1, sizeof(GLuint));
    if (!r->textures) {
        DIRT_ERROR("out of memory");
        return false;
    }
    int max = dirt_gpu_get_caps(r->gpu)->max_texture_size;
    for (size_t i = 0; i < r->num_textures; i++) {
        if (!tex[i].rgba || tex[i].width <= 0 || tex[i].height <= 0)
            continue;
        /* Each texture is a 2D texture of its own: its limit is a side, not
         * a storage block (the path tracer reads the texel table, a split
         * array). */
        if (max > 0 && (tex[i].width > max || tex[i].height > max)) {
            DIRT_ERROR("the raster preview: texture %zu '%s' is %dx%d, more than this GPU's "
                       "GL_MAX_TEXTURE_SIZE (%d) a side: scale it down to at most %dx%d", i,
                       tex[i].name, tex[i].width, tex[i].height, max, max, max);
            return false;
        }
        int levels = 1;
        for (int s = tex[i].width > tex[i].height ? tex[i].width : tex[i].height; s > 1; s >>= 1)
            levels++;
        GLuint t = gl_texture_2d(GL_RGBA8, tex[i].width, tex[i].height, levels, tex[i].name);
        if (!t)
            return false;
        glTextureSubImage2D(t, 0, 0, 0, tex[i].width, tex[i].height, GL_RGBA,
                            GL_UNSIGNED_BYTE, tex[i].rgba);
        glGenerateTextureMipmap(t);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
        r->textures[i] = t;
    }
    static const uint8_t white[4] = {255, 255, 255, 255};
    r->white = gl_texture_2d(GL_RGBA8, 1, 1, 1, "white");
    if (!r->white)
        return false;
    glTextureSubImage2D(r->white, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white);
    return true;
}

static bool upload_materials(dirt_raster *r)
{
    size_t n = dirt_scene_num_materials(r->scene);
    const dirt_material *mat = dirt_scene_materials(r->scene);
    struct dirt_gpu_material *gm = calloc(n ? n : 1, sizeof(*gm));
    if (!gm) {
        DIRT_ERROR("out of memory");
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        const dirt_material *m = &mat[i];
        float s = m->emissive_strength;
        gm[i].base_color = (dirt_f4){m->base_color[0], m->base_color[1], m->base_color[2],
                                     m->base_color[3]};
        gm[i].emissive = (dirt_f4){m->emissive[0] * s, m->emissive[1] * s,
                                   m->emissive[2] * s, 0};
        gm[i].pbr = (dirt_f4){m->metallic, m->roughness, 0, 0};
        gm[i].textures = (dirt_i4){m->base_color_tex, m->metallic_roughness_tex,
                                   m->emissive_tex, m->double_sided ? 1 : 0};
    }
    r->materials_bytes = (n ? n : 1) * sizeof(*gm);
    r->materials = gl_buffer_create(r->gpu, r->materials_bytes, gm, false,
                                    "preview materials");
    free(gm);
    return r->materials != 0;
}

/* Draws the vertices [lo, hi) of every material range with its textures;
 * vertex lo is the bound vertex buffer's first. */
static void draw_ranges(const dirt_raster *r, size_t lo, size_t hi)
{
    const dirt_material *mat = dirt_scene_materials(r->scene);
    for (size_t i = 0; i < r->num_ranges; i++) {
        const material_range *mr = &r->ranges[i];
        size_t first = mr->first_vertex > lo ? mr->first_vertex : lo;
        size_t last = mr->first_vertex + mr->num_vertices < hi
                          ? mr->first_vertex + mr->num_vertices : hi;
        if (first >= last)
            continue;
        const dirt_material *m = &mat[mr->material];
        GLuint base = m->base_color_tex >= 0 && (size_t)m->base_color_tex < r->num_textures
                          ? r->textures[m->base_color_tex] : 0;
        GLuint emis = m->emissive_tex >= 0 && (size_t)m->emissive_tex < r->num_textures
                          ? r->textures[m->emissive_tex] : 0;
        glBindTextureUnit(DIRT_UNIT_PREVIEW_BASE_COLOR, base ? base : r->white);
        glBindTextureUnit(DIRT_UNIT_PREVIEW_EMISSIVE, emis ? emis : r->white);
        glUniform1i(DIRT_LOC_PREVIEW_MATERIAL, (GLint)mr->material);
        glDrawArrays(GL_TRIANGLES, (GLint)(first - lo), (GLsizei)(last - first));
    }
}

/* Pass body of "preview draw": the graph has bound the framebuffer of the
 * colour/depth targets (viewport = image size), the material and light SSBOs
 * and an empty VAO; this clears the targets and draws each material range
 * with its textures. Leaves depth testing off and no program bound. */
static bool exec_draw(fg_ctx *ctx, void *user)
{
    dirt_raster *r = user;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    static const float clear_color[4] = {0, 0, 0, 1};
    static const float clear_depth = 1.0f;
    const float clear_aov[4] = {0, 0, 0, INFINITY}; /* misses: no normal, Z infinite */
    glClearBufferfv(GL_COLOR, 0, clear_color);
    glClearBufferfv(GL_COLOR, 1, clear_aov);
    glClearBufferfv(GL_DEPTH, 0, &clear_depth);
    glUseProgram(r->program);
    glUniformMatrix4fv(DIRT_LOC_PREVIEW_VIEW_PROJ, 1, GL_FALSE, r->frame.view_proj);
    glUniform3fv(DIRT_LOC_PREVIEW_EYE, 1, r->frame.eye);
    glUniform3fv(DIRT_LOC_PREVIEW_FORWARD, 1, r->frame.forward);
    glUniform1i(DIRT_LOC_PREVIEW_NUM_LIGHTS, r->frame.num_lights);
    glUniform1f(DIRT_LOC_PREVIEW_AMBIENT, r->frame.ambient);
    glBindVertexArray(r->vao);
    /* Each part of the vertex buffer on its own (one while it is one
     * storage block). */
    size_t per = 3 * gl_split_part_records(&r->vbo);
    for (int k = 0; k < (r->vbo.layout.parts ? r->vbo.layout.parts : 1); k++) {
        GLuint vbo = fg_name(ctx, r->res_vertices[k]);
        if (!vbo)
            return false;
        glVertexArrayVertexBuffer(r->vao, 0, vbo, 0, sizeof(preview_vertex));
        draw_ranges(r, (size_t)k * per, (size_t)(k + 1) * per);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    return true;
}

/* Reads RGBA32F target `res` (bottom-up) into `out` and flips the rows so
 * row 0 is the top. */
static bool read_flipped(fg_ctx *ctx, const dirt_raster *r, fg_res res, float *out)
{
    int w = 0, h = 0;
    fg_texture_size(ctx, res, &w, &h, NULL, NULL);
    if (w != r->frame.width || h != r->frame.height) {
        DIRT_ERROR("raster preview: target is %dx%d, the image %dx%d", w, h, r->frame.width,
                   r->frame.height);
        return false;
    }
    size_t row = (size_t)w * 4;
    if (!fg_gl_read_texture(ctx, res, 0, out, row * (size_t)h * sizeof(float)))
        return false;
    for (int y = 0; y < h / 2; y++) {
        float *a = out + (size_t)y * row, *b = out + (size_t)(h - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            float tmp = a[i];
            a[i] = b[i];
            b[i] = tmp;
        }
    }
    return true;
}

/* Pass body of "preview readback": the colour target, and the AOV target
 * when the caller wants it, into the caller's buffers (row 0 = top). */
static bool exec_readback(fg_ctx *ctx, void *user)
{
    dirt_raster *r = user;
    return read_flipped(ctx, r, r->res_color, r->frame.rgba) &&
           (!r->frame.aov || read_flipped(ctx, r, r->res_aov, r->frame.aov));
}

/* Scene textures a material samples (base colour or emissive), imported so
 * that the graph's DOT and stats show them; the draw body binds them. */
static bool declare_textures(dirt_raster *r, fg_pass *draw)
{
    const dirt_texture *tex = dirt_scene_textures(r->scene);
    const dirt_material *mat = dirt_scene_materials(r->scene);
    size_t nmat = dirt_scene_num_materials(r->scene);
    bool *sampled = calloc(r->num_textures ? r->num_textures : 1, sizeof(bool));
    if (!sampled) {
        DIRT_ERROR("out of memory");
        return false;
    }
    for (size_t m = 0; m < nmat; m++) {
        int ids[2] = {mat[m].base_color_tex, mat[m].emissive_tex};
        for (int k = 0; k < 2; k++) {
            if (ids[k] >= 0 && (size_t)ids[k] < r->num_textures)
                sampled[ids[k]] = true;
        }
    }
    bool ok = true;
    for (size_t i = 0; i < r->num_textures && ok; i++) {
        if (!sampled[i] || !r->textures[i])
            continue;
        char name[96];
        snprintf(name, sizeof(name), "texture %zu%s%.40s", i, tex[i].name[0] ? " " : "",
                 tex[i].name);
        fg_res t = fg_import_texture(r->graph, name, r->textures[i],
                                     &(fg_tex_desc){.format = FG_RGBA8, .width = tex[i].width,
                                                    .height = tex[i].height,
                                                    .levels = FG_MIPS_FULL});
        ok = t.id != 0;
        if (ok)
            fg_read(draw, t, FG_SAMPLED);
    }
    free(sampled);
    if (!ok)
        return false;
    fg_res white = fg_import_texture(r->graph, "white", r->white,
                                     &(fg_tex_desc){.format = FG_RGBA8, .width = 1,
                                                    .height = 1});
    if (!white.id)
        return false;
    fg_read(draw, white, FG_SAMPLED);
    return true;
}

/* Declares the preview's graph (see the top of the file). The vertex and light
 * buffers must exist (their imports are repointed when they grow). Compiled
 * later, by ensure_graph, once the image size is known. */
static bool build_graph(dirt_raster *r)
{
    r->graph = gl_graph_create(r->gpu);
    if (!r->graph)
        return false;
    fg_graph *g = r->graph;
    gl_split_import(g, "preview vertices", &r->vbo, r->res_vertices);
    r->graph_parts = r->vbo.layout.parts;
    r->res_materials = fg_import_buffer(g, "preview materials", r->materials,
                                        r->materials_bytes);
    r->res_lights = fg_import_buffer(g, "preview lights", r->lights,
                                     r->lights_capacity * sizeof(struct dirt_gpu_light));
    r->res_color = fg_texture(g, "preview color", &(fg_tex_desc){.format = FG_RGBA32F});
    r->res_aov = fg_texture(g, "preview normal and depth", &(fg_tex_desc){.format = FG_RGBA32F});
    r->res_depth = fg_texture(g, "preview depth", &(fg_tex_desc){.format = FG_DEPTH32F});

    fg_pass *draw = fg_add_pass(g, PASS_DRAW, FG_RASTER, exec_draw, r);
    fg_pass *rb = fg_add_pass(g, PASS_READBACK, FG_COMPUTE, exec_readback, r);
    if (!r->res_vertices[0].id || !r->res_materials.id || !r->res_lights.id ||
        !r->res_color.id || !r->res_aov.id || !r->res_depth.id || !draw || !rb)
        return false;
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && r->res_vertices[k].id; k++)
        fg_read(draw, r->res_vertices[k], FG_VERTEX);
    fg_use(draw, r->res_materials, FG_SSBO_READ,
           &(fg_use_opts){.bind = true, .binding = DIRT_BIND_PREVIEW_MATERIALS});
    fg_use(draw, r->res_lights, FG_SSBO_READ,
           &(fg_use_opts){.bind = true, .binding = DIRT_BIND_PREVIEW_LIGHTS});
    if (!declare_textures(r, draw))
        return false;
    fg_use(draw, r->res_color, FG_COLOR, &(fg_use_opts){.binding = 0});
    fg_use(draw, r->res_aov, FG_COLOR, &(fg_use_opts){.binding = 1});
    fg_write(draw, r->res_depth, FG_DEPTH);

    fg_read(rb, r->res_color, FG_TRANSFER_READ);
    fg_read(rb, r->res_aov, FG_TRANSFER_READ);
    fg_keep(rb);
    return true;
}

/* (Re)compiles the graph for a width x height image; a no-op when it already
 * is. The transient targets are reallocated at the next execute. */
static bool ensure_graph(dirt_raster *r, int width, int height)
{
    if (r->graph_width == width && r->graph_height == height)
        return true;
    r->graph_width = r->graph_height = 0;
    fg_set_resolution(r->graph, width, height);
    if (!fg_compile(r->graph)) {
        DIRT_ERROR("raster preview: frame graph does not compile at %dx%d: %s", width,
                   height, fg_last_error(r->graph));
        return false;
    }
    r->graph_width = width;
    r->graph_height = height;
    return true;
}

dirt_raster *dirt_raster_create(dirt_gpu *gpu, const dirt_scene *scene)
{
    dirt_raster *r = calloc(1, sizeof(*r));
    if (!r) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    r->gpu = gpu;
    r->scene = scene;
    const char *paths[] = {"raster/preview.vert", "raster/preview.frag", NULL};
    r->program = gl_program_create("raster preview", paths, NULL, 0);
    if (!r->program)
        goto error;
    glCreateVertexArrays(1, &r->vao);
    gl_label(GL_VERTEX_ARRAY, r->vao, "preview vao");
    static const struct { GLuint loc, size, offset; } attr[] = {
        {0, 3, offsetof(preview_vertex, position)},
        {1, 3, offsetof(preview_vertex, normal)},
        {2, 2, offsetof(preview_vertex, uv)},
    };
    for (size_t i = 0; i < 3; i++) {
        glEnableVertexArrayAttrib(r->vao, attr[i].loc);
        glVertexArrayAttribFormat(r->vao, attr[i].loc, (GLint)attr[i].size, GL_FLOAT,
                                  GL_FALSE, attr[i].offset);
        glVertexArrayAttribBinding(r->vao, attr[i].loc, 0);
    }
    if (!upload_textures(r) || !upload_materials(r))
        goto error;
    /* Minimal vertex and light buffers, so the graph has something to import;
     * dirt_raster_render grows them. */
    r->lights_capacity = 1;
    r->lights = gl_buffer_create(r->gpu, r->lights_capacity * sizeof(struct dirt_gpu_light),
                                 NULL, false, "preview lights");
    if (!gl_split_ensure(r->gpu, &r->vbo, &vbo_desc, 1) || !r->lights)
        goto error;
    if (!build_graph(r)) {
        DIRT_ERROR("raster preview: could not declare the frame graph");
        goto error;
    }
    return r;
error:
    dirt_raster_destroy(r);
    return NULL;
}

void dirt_raster_destroy(dirt_raster *r)
{
    if (!r)
        return;
    fg_destroy(r->graph);
    gl_program_destroy(&r->program);
    if (r->vao)
        glDeleteVertexArrays(1, &r->vao);
    gl_split_release(&r->vbo);
    gl_buffer_destroy(&r->materials);
    gl_buffer_destroy(&r->lights);
    for (size_t i = 0; r->textures && i < r->num_textures; i++)
        gl_texture_destroy(&r->textures[i]);
    gl_texture_destroy(&r->white);
    free(r->textures);
    free(r->staging);
    free(r->order);
    free(r->ranges);
    free(r);
}

bool dirt_raster_write_dot(const dirt_raster *r, const char *path)
{
    if (!r || !path) {
        DIRT_ERROR("raster preview: dirt_raster_write_dot needs a renderer and a path");
        return false;
    }
    if (!r->graph_width) {
        DIRT_ERROR("raster preview: no compiled frame graph yet (render a frame first)");
        return false;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        DIRT_ERROR("raster preview: cannot open '%s' for writing", path);
        return false;
    }
    bool ok = fg_write_dot(r->graph, f);
    if (fclose(f) != 0)
        ok = false;
    if (!ok)
        DIRT_ERROR("raster preview: writing the frame graph DOT to '%s' failed", path);
    return ok;
}

/* Counting sort of triangles by material (stable), filling the staging
 * vertices and the material ranges. */
static bool stage_vertices(dirt_raster *r, const dirt_frame *f)
{
    size_t nmat = dirt_scene_num_materials(r->scene);
    size_t nt = f->num_triangles;
    preview_vertex *v = realloc(r->staging, (nt ? nt : 1) * 3 * sizeof(*v));
    if (!v)
        goto oom;
    r->staging = v;
    uint32_t *count = calloc(nmat + 1, sizeof(uint32_t));
    material_range *ranges = realloc(r->ranges, (nmat ? nmat : 1) * sizeof(*ranges));
    if (!count || !ranges) {
        free(count);
        if (ranges)
            r->ranges = ranges;
        goto oom;
    }
    r->ranges = ranges;
    for (size_t t = 0; t < nt; t++)
        count[f->material[t] < nmat ? f->material[t] + 1 : nmat]++;
    /* count[m+1] = triangles of material m; prefix-sum into starts */
    uint32_t start = 0;
    r->num_ranges = 0;
    for (size_t m = 0; m < nmat; m++) {
        uint32_t c = count[m + 1];
        if (c) {
            ranges[r->num_ranges++] = (material_range){(uint32_t)m, start * 3, c * 3};
        }
        count[m + 1] = start;
        start += c;
    }
    for (size_t t = 0; t < nt; t++) {
        uint32_t m = f->material[t];
        if (m >= nmat)
            continue;
        uint32_t slot = count[m + 1]++;
        for (int k = 0; k < 3; k++) {
            preview_vertex *pv = &v[slot * 3 + k];
            memcpy(pv->position, f->position[3 * t + k], sizeof(pv->position));
            memcpy(pv->normal, f->normal[3 * t + k], sizeof(pv->normal));
            memcpy(pv->uv, f->uv[3 * t + k], sizeof(pv->uv));
        }
    }
    free(count);
    return true;
oom:
    DIRT_ERROR("out of memory staging %zu triangles", nt);
    return false;
}

/* Area of triangle (a, b, c); n = its unnormalised normal (b - a) x (c - a). */
static float tri_area(const float a[3], const float b[3], const float c[3], float n[3])
{
    dirt_vec3 a3 = v3_load(a);
    dirt_vec3 cr = v3_cross(v3_sub(v3_load(b), a3), v3_sub(v3_load(c), a3));
    n[0] = cr.x;
    n[1] = cr.y;
    n[2] = cr.z;
    return 0.5f * v3_length(cr);
}

/* Punctual lights plus one lumped point per (instance, emissive material):
 * radiance * area at the area-weighted centroid, facing the area-weighted
 * normal. Returns the number of lights written into *out (malloc'd). */
static int gather_lights(dirt_raster *r, const dirt_frame *f, struct dirt_gpu_light **out)
{
    const dirt_material *mat = dirt_scene_materials(r->scene);
    size_t cap = f->num_lights + 8, n = 0;
    struct dirt_gpu_light *l = calloc(cap, sizeof(*l));
    if (!l)
        return -1;
    for (size_t i = 0; i < f->num_lights; i++) {
        const dirt_light *s = &f->lights[i];
        l[n++] = (struct dirt_gpu_light){
            .position = {s->position[0], s->position[1], s->position[2], (float)s->type},
            .direction = {s->direction[0], s->direction[1], s->direction[2], 0},
            .color = {s->color[0], s->color[1], s->color[2], s->range},
            .cone = {cosf(s->inner_cone), cosf(s->outer_cone), 0, 0},
        };
    }
    /* Accumulate emitters; triangles of one instance+material are usually
     * contiguous, so a running group suffices. */
    double acc_p[3] = {0}, acc_n[3] = {0}, acc_a = 0, acc_e[3] = {0};
    uint32_t cur_inst = UINT32_MAX, cur_mat = UINT32_MAX;
    for (size_t t = 0; t <= f->num_triangles; t++) {
        bool flush = t == f->num_triangles || f->instance[t] != cur_inst ||
                     f->material[t] != cur_mat;
        if (flush && acc_a > 0) {
            double nl = sqrt(acc_n[0] * acc_n[0] + acc_n[1] * acc_n[1] + acc_n[2] * acc_n[2]);
            if (n == cap) {
                cap *= 2;
                struct dirt_gpu_light *g = realloc(l, cap * sizeof(*l));
                if (!g) {
                    free(l);
                    return -1;
                }
                l = g;
            }
            float dir[3] = {0, -1, 0};
            if (nl > 0) {
                for (int k = 0; k < 3; k++)
                    dir[k] = (float)(acc_n[k] / nl);
            }
            l[n++] = (struct dirt_gpu_light){
                .position = {(float)(acc_p[0] / acc_a), (float)(acc_p[1] / acc_a),
                             (float)(acc_p[2] / acc_a), DIRT_PREVIEW_LIGHT_EMITTER},
                .direction = {dir[0], dir[1], dir[2], 0},
                .color = {(float)acc_e[0], (float)acc_e[1], (float)acc_e[2], 0},
            };
        }
        if (t == f->num_triangles)
            break;
        if (flush) {
            memset(acc_p, 0, sizeof(acc_p));
            memset(acc_n, 0, sizeof(acc_n));
            memset(acc_e, 0, sizeof(acc_e));
            acc_a = 0;
            cur_inst = f->instance[t];
            cur_mat = f->material[t];
        }
        const dirt_material *m = &mat[f->material[t]];
        float e[3] = {m->emissive[0] * m->emissive_strength, m->emissive[1] * m->emissive_strength,
                      m->emissive[2] * m->emissive_strength};
        if (e[0] + e[1] + e[2] <= 0)
            continue;
        float nrm[3];
        const float *a = f->position[3 * t], *b = f->position[3 * t + 1], *c = f->position[3 * t + 2];
        float area = tri_area(a, b, c, nrm);
        if (!(area > 0))
            continue;
        /* Orient the face normal like the shading normals. */
        const float *sn = f->normal[3 * t];
        float flip = nrm[0] * sn[0] + nrm[1] * sn[1] + nrm[2] * sn[2] < 0 ? -1.0f : 1.0f;
        for (int k = 0; k < 3; k++) {
            acc_p[k] += area * (a[k] + b[k] + c[k]) / 3.0;
            acc_n[k] += flip * nrm[k] * 0.5f;
            acc_e[k] += area * e[k];
        }
        acc_a += area;
    }
    *out = l;
    return (int)n;
}

/* Grows the imported buffer `*buf` (capacity in elements of `elem` bytes) to
 * hold `need` elements and repoints its import; keeps it when large enough. */
static bool ensure_import(dirt_raster *r, GLuint *buf, size_t *capacity, size_t need,
                          size_t elem, fg_res res, const char *label)
{
    if (need <= *capacity && *buf)
        return true;
    gl_buffer_destroy(buf);
    *capacity = need ? need : 1;
    *buf = gl_buffer_create(r->gpu, *capacity * elem, NULL, false, label);
    if (!*buf) {
        *capacity = 0;
        return false;
    }
    return fg_set_import(r->graph, res, *buf, *capacity * elem);
}

/* Copies the graph's per-pass figures of the last execute into `stats`. */
static void fill_stats(const dirt_raster *r, int num_lights, dirt_raster_stats *stats)
{
    *stats = (dirt_raster_stats){.ms = -1, .clock = DIRT_CLOCK_NONE, .num_lights = num_lights};
    fg_stats gs;
    if (!fg_get_stats(r->graph, &gs))
        return;
    double sum = 0;
    bool measured = true;
    for (int pos = 0; pos < fg_num_ordered(r->graph); pos++) {
        int index = fg_order(r->graph, pos);
        if (index < 0 || index >= gs.num_passes)
            continue;
        const fg_pass_stats *p = &gs.passes[index];
        measured = measured && p->clock != DIRT_CLOCK_NONE && p->clock == gs.clock;
        sum += p->ms;
        if (stats->num_passes < DIRT_RASTER_MAX_PASSES) {
            dirt_raster_pass_stats *o = &stats->passes[stats->num_passes++];
            snprintf(o->name, sizeof(o->name), "%s", p->name);
            o->ms = p->ms;
            o->clock = p->clock;
            o->barrier = p->barrier;
        }
    }
    if (measured && stats->num_passes) {
        stats->ms = sum;
        stats->clock = gs.clock;
    }
    stats->transient_bytes = gs.allocated_bytes;
    stats->imported_bytes = gs.imported_bytes;
    stats->validation_errors = gs.validation_errors;
}

bool dirt_raster_render(dirt_raster *r, const dirt_frame *f, const dirt_camera *cam,
                        int width, int height, const dirt_raster_opts *opts_in,
                        float *rgba, float *aov, dirt_raster_stats *stats)
{
    dirt_raster_opts opts = opts_in ? *opts_in : (dirt_raster_opts){0};
    float ambient = opts.ambient == 0 ? 0.02f : (opts.ambient < 0 ? 0 : opts.ambient);
    struct dirt_gpu_light *lights = NULL;
    bool ok = false;
    if (width <= 0 || height <= 0) {
        DIRT_ERROR("invalid image size %dx%d", width, height);
        return false;
    }
    gl_group_push("raster preview");
    if (!ensure_graph(r, width, height) || !stage_vertices(r, f))
        goto done;

    /* Uploads, outside the graph (API updates: no barrier needed); the
     * graph again when the vertex buffer's parts change. */
    if (!gl_split_ensure(r->gpu, &r->vbo, &vbo_desc, f->num_triangles) ||
        (f->num_triangles && !gl_split_write(&r->vbo, 0, f->num_triangles, r->staging)))
        goto done;
    if (r->vbo.layout.parts != r->graph_parts) {
        fg_destroy(r->graph);
        r->graph = NULL;
        r->graph_width = r->graph_height = 0;
        if (!build_graph(r) || !ensure_graph(r, width, height)) {
            DIRT_ERROR("raster preview: could not declare the frame graph");
            goto done;
        }
    }
    gl_split_set_imports(r->graph, &r->vbo, r->res_vertices);

    int num_lights = gather_lights(r, f, &lights);
    if (num_lights < 0) {
        DIRT_ERROR("out of memory gathering lights");
        goto done;
    }
    if (!ensure_import(r, &r->lights, &r->lights_capacity, (size_t)num_lights, sizeof(*lights),
                       r->res_lights, "preview lights"))
        goto done;
    if (num_lights)
        glNamedBufferSubData(r->lights, 0, num_lights * (GLsizeiptr)sizeof(*lights), lights);
    if (!gl_check("raster preview uploads"))
        goto done;

    float proj[16];
    dirt_camera_projection(cam, (float)width / (float)height, proj);
    for (int c = 0; c < 4; c++) {
        for (int rr = 0; rr < 4; rr++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += proj[k * 4 + rr] * cam->view[c * 4 + k];
            r->frame.view_proj[c * 4 + rr] = s;
        }
    }
    r->frame.eye = cam->eye;
    float len = sqrtf(cam->forward[0] * cam->forward[0] + cam->forward[1] * cam->forward[1] +
                      cam->forward[2] * cam->forward[2]);
    for (int k = 0; k < 3; k++)
        r->frame.forward[k] = len > 0 ? cam->forward[k] / len : 0.0f;
    r->frame.num_lights = num_lights;
    r->frame.ambient = ambient;
    r->frame.rgba = rgba;
    r->frame.aov = aov;
    r->frame.width = width;
    r->frame.height = height;

    /* Validation is always on: it only compares bookkeeping (no GL queries). */
    ok = fg_execute(r->graph, &(fg_exec_opts){.validate = true});
    r->frame.rgba = NULL;
    r->frame.aov = NULL;
    r->frame.eye = NULL;
    if (!ok) {
        DIRT_ERROR("raster preview: executing the frame graph failed");
        goto done;
    }
    ok = gl_check("raster preview");
    if (ok && stats)
        fill_stats(r, num_lights, stats);
done:
    gl_group_pop();
    free(lights);
    return ok;
}
