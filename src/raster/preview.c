/* Raster preview pass: draws the evaluated frame with simple direct lighting
 * into a float colour target and reads it back. */
#include "dirt/raster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "gl/gl.h"
#include "gl/program.h"

_Static_assert(sizeof(struct dirt_gpu_material) == 64, "material layout");
_Static_assert(sizeof(struct dirt_gpu_light) == 64, "light layout");

/* Vertex of the preview's vertex buffer. */
typedef struct preview_vertex {
    float position[3];
    float normal[3];
    float uv[2];
} preview_vertex;

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
    GLuint vbo;
    size_t vbo_capacity;  /* vertices */
    GLuint materials;
    GLuint lights;
    size_t lights_capacity;
    GLuint *textures;     /* one per scene texture (0 when it failed) */
    size_t num_textures;
    GLuint white;         /* 1x1 white texture for materials without one */
    GLuint fbo, color, depth;
    int fb_width, fb_height;
    gl_timer timer;
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
    for (size_t i = 0; i < r->num_textures; i++) {
        if (!tex[i].rgba || tex[i].width <= 0 || tex[i].height <= 0)
            continue;
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
    r->materials = gl_buffer_create(r->gpu, (n ? n : 1) * sizeof(*gm), gm, false,
                                    "preview materials");
    free(gm);
    return r->materials != 0;
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
    if (!gl_timer_init(&r->timer, false, "preview timer"))
        goto error;
    return r;
error:
    dirt_raster_destroy(r);
    return NULL;
}

static void release_framebuffer(dirt_raster *r)
{
    if (r->fbo)
        glDeleteFramebuffers(1, &r->fbo);
    r->fbo = 0;
    gl_texture_destroy(&r->color);
    gl_texture_destroy(&r->depth);
    r->fb_width = r->fb_height = 0;
}

void dirt_raster_destroy(dirt_raster *r)
{
    if (!r)
        return;
    release_framebuffer(r);
    gl_program_destroy(&r->program);
    if (r->vao)
        glDeleteVertexArrays(1, &r->vao);
    gl_buffer_destroy(&r->vbo);
    gl_buffer_destroy(&r->materials);
    gl_buffer_destroy(&r->lights);
    for (size_t i = 0; r->textures && i < r->num_textures; i++)
        gl_texture_destroy(&r->textures[i]);
    gl_texture_destroy(&r->white);
    gl_timer_release(&r->timer);
    free(r->textures);
    free(r->staging);
    free(r->order);
    free(r->ranges);
    free(r);
}

static bool ensure_framebuffer(dirt_raster *r, int w, int h)
{
    if (r->fbo && r->fb_width == w && r->fb_height == h)
        return true;
    release_framebuffer(r);
    r->color = gl_texture_2d(GL_RGBA32F, w, h, 1, "preview color");
    r->depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, w, h, 1, "preview depth");
    if (!r->color || !r->depth)
        return false;
    glCreateFramebuffers(1, &r->fbo);
    glNamedFramebufferTexture(r->fbo, GL_COLOR_ATTACHMENT0, r->color, 0);
    glNamedFramebufferTexture(r->fbo, GL_DEPTH_ATTACHMENT, r->depth, 0);
    gl_label(GL_FRAMEBUFFER, r->fbo, "preview fbo");
    GLenum status = glCheckNamedFramebufferStatus(r->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        DIRT_ERROR("preview framebuffer incomplete (0x%x) at %dx%d", status, w, h);
        return false;
    }
    r->fb_width = w;
    r->fb_height = h;
    return true;
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

static float tri_area(const float a[3], const float b[3], const float c[3], float n[3])
{
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return 0.5f * len;
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

bool dirt_raster_render(dirt_raster *r, const dirt_frame *f, const dirt_camera *cam,
                        int width, int height, const dirt_raster_opts *opts_in,
                        float *rgba, dirt_raster_stats *stats)
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
    if (!ensure_framebuffer(r, width, height) || !stage_vertices(r, f))
        goto done;
    size_t nv = f->num_triangles * 3;
    if (nv > r->vbo_capacity || !r->vbo) {
        gl_buffer_destroy(&r->vbo);
        r->vbo_capacity = nv ? nv : 3;
        r->vbo = gl_buffer_create(r->gpu, r->vbo_capacity * sizeof(preview_vertex), NULL,
                                  false, "preview vertices");
        if (!r->vbo)
            goto done;
        glVertexArrayVertexBuffer(r->vao, 0, r->vbo, 0, sizeof(preview_vertex));
    }
    if (nv)
        glNamedBufferSubData(r->vbo, 0, (GLsizeiptr)(nv * sizeof(preview_vertex)), r->staging);

    int num_lights = gather_lights(r, f, &lights);
    if (num_lights < 0) {
        DIRT_ERROR("out of memory gathering lights");
        goto done;
    }
    if ((size_t)num_lights > r->lights_capacity || !r->lights) {
        gl_buffer_destroy(&r->lights);
        r->lights_capacity = num_lights > 0 ? (size_t)num_lights : 1;
        r->lights = gl_buffer_create(r->gpu, r->lights_capacity * sizeof(*lights), NULL,
                                     false, "preview lights");
        if (!r->lights)
            goto done;
    }
    if (num_lights)
        glNamedBufferSubData(r->lights, 0, num_lights * (GLsizeiptr)sizeof(*lights), lights);

    float proj[16], view_proj[16];
    dirt_camera_projection(cam, (float)width / (float)height, proj);
    for (int c = 0; c < 4; c++) {
        for (int rr = 0; rr < 4; rr++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += proj[k * 4 + rr] * cam->view[c * 4 + k];
            view_proj[c * 4 + rr] = s;
        }
    }

    if (opts.cpu_timing != r->timer.cpu_finish)
        r->timer.cpu_finish = opts.cpu_timing;
    gl_timer_begin(&r->timer);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    static const float clear_color[4] = {0, 0, 0, 1};
    static const float clear_depth = 1.0f;
    glClearNamedFramebufferfv(r->fbo, GL_COLOR, 0, clear_color);
    glClearNamedFramebufferfv(r->fbo, GL_DEPTH, 0, &clear_depth);
    glUseProgram(r->program);
    glUniformMatrix4fv(0, 1, GL_FALSE, view_proj);
    glUniform3fv(1, 1, cam->eye);
    glUniform1i(3, num_lights);
    glUniform1f(4, ambient);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_PREVIEW_MATERIALS, r->materials);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_PREVIEW_LIGHTS, r->lights);
    glBindVertexArray(r->vao);
    const dirt_material *mat = dirt_scene_materials(r->scene);
    for (size_t i = 0; i < r->num_ranges; i++) {
        const material_range *mr = &r->ranges[i];
        const dirt_material *m = &mat[mr->material];
        GLuint base = m->base_color_tex >= 0 && (size_t)m->base_color_tex < r->num_textures
                          ? r->textures[m->base_color_tex] : 0;
        GLuint emis = m->emissive_tex >= 0 && (size_t)m->emissive_tex < r->num_textures
                          ? r->textures[m->emissive_tex] : 0;
        glBindTextureUnit(0, base ? base : r->white);
        glBindTextureUnit(1, emis ? emis : r->white);
        glUniform1i(2, (GLint)mr->material);
        glDrawArrays(GL_TRIANGLES, (GLint)mr->first_vertex, (GLsizei)mr->num_vertices);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl_timer_end(&r->timer);

    /* Read back bottom-up, then flip rows so row 0 is the top. */
    size_t row = (size_t)width * 4;
    glGetTextureImage(r->color, 0, GL_RGBA, GL_FLOAT,
                      (GLsizei)(row * (size_t)height * sizeof(float)), rgba);
    for (int y = 0; y < height / 2; y++) {
        float *a = rgba + (size_t)y * row, *b = rgba + (size_t)(height - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            float tmp = a[i];
            a[i] = b[i];
            b[i] = tmp;
        }
    }
    ok = gl_check("raster preview");
    if (stats) {
        stats->gpu_ms = r->timer.gpu_ms;
        stats->cpu_ms = r->timer.cpu_ms;
        stats->num_lights = num_lights;
    }
done:
    gl_group_pop();
    free(lights);
    return ok;
}
