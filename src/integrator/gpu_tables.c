/* DIRT engine: packing and upload of the GPU light-transport model's scene
 * tables (dirt/gpu_tables.h, glsl/common/integrator_layout.h). */
#include "dirt/gpu_tables.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "gl/gl.h"

/* Record sizes and offsets are checked in src/gl/layout_check.c. */
_Static_assert(DIRT_MODEL_LIGHT_DIRECTIONAL == DIRT_LIGHT_DIRECTIONAL &&
               DIRT_MODEL_LIGHT_POINT == DIRT_LIGHT_POINT &&
               DIRT_MODEL_LIGHT_SPOT == DIRT_LIGHT_SPOT, "light kinds");
_Static_assert(DIRT_MODEL_CAMERA_PERSPECTIVE == DIRT_CAMERA_PERSPECTIVE &&
               DIRT_MODEL_CAMERA_ORTHOGRAPHIC == DIRT_CAMERA_ORTHOGRAPHIC, "camera kinds");

static float clamp01f(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

static int texture_index(int index, size_t num_textures)
{
    return index >= 0 && (size_t)index < num_textures ? index : -1;
}

/* ---- records ------------------------------------------------------------ */

void dirt_gpu_material_pack(const dirt_material *m, float specular, size_t num_textures,
                            struct dirt_gpu_model_material *out)
{
    memset(out, 0, sizeof(*out));
    out->base_color = (dirt_f4){m->base_color[0], m->base_color[1], m->base_color[2],
                                m->base_color[3]};
    out->params = (dirt_f4){m->metallic, m->roughness, clamp01f(specular), 0.0f};
    int flags = m->double_sided ? DIRT_MODEL_MAT_DOUBLE_SIDED : 0;
    if (dirt_material_is_emissive(m)) {
        float s = m->emissive_strength;
        /* dirt_material_surface computes emissive * s * tex left to right:
         * the first product here is the same float. */
        out->emission = (dirt_f4){m->emissive[0] * s, m->emissive[1] * s, m->emissive[2] * s,
                                  0.0f};
        flags |= DIRT_MODEL_MAT_EMISSIVE;
    }
    out->textures = (dirt_i4){texture_index(m->base_color_tex, num_textures),
                              texture_index(m->metallic_roughness_tex, num_textures),
                              texture_index(m->emissive_tex, num_textures), flags};
}

void dirt_gpu_materials_pack(const dirt_material *materials, size_t count,
                             const float *specular, size_t num_textures,
                             struct dirt_gpu_model_material *out)
{
    for (size_t i = 0; i < count; i++)
        dirt_gpu_material_pack(&materials[i], specular ? specular[i] : 1.0f, num_textures,
                               &out[i]);
}

struct dirt_gpu_model_material *dirt_gpu_scene_materials(const dirt_scene *scene,
                                                         const float *specular,
                                                         size_t *count)
{
    size_t n = dirt_scene_num_materials(scene);
    struct dirt_gpu_model_material *out = calloc(n > 0 ? n : 1, sizeof(*out));
    if (!out) {
        DIRT_ERROR("gpu tables: out of memory for %zu materials", n);
        return NULL;
    }
    if (n == 0) {
        dirt_material white = {.base_color = {1.0f, 1.0f, 1.0f, 1.0f},
                               .base_color_tex = DIRT_NO_TEXTURE,
                               .roughness = 1.0f,
                               .metallic_roughness_tex = DIRT_NO_TEXTURE,
                               .emissive_strength = 1.0f,
                               .emissive_tex = DIRT_NO_TEXTURE};
        dirt_gpu_material_pack(&white, 1.0f, 0, out);
        *count = 1;
        return out;
    }
    dirt_gpu_materials_pack(dirt_scene_materials(scene), n, specular,
                            dirt_scene_num_textures(scene), out);
    *count = n;
    return out;
}

void dirt_gpu_light_pack(const dirt_light *light, struct dirt_gpu_model_light *out)
{
    memset(out, 0, sizeof(*out));
    out->position = (dirt_f4){light->position[0], light->position[1], light->position[2],
                              (float)light->type};
    out->direction = (dirt_f4){light->direction[0], light->direction[1], light->direction[2],
                               light->range};
    out->color = (dirt_f4){light->color[0], light->color[1], light->color[2], 0.0f};
    out->cone = (dirt_f4){cosf(light->outer_cone), cosf(light->inner_cone), 0.0f, 0.0f};
}

void dirt_gpu_camera_pack(const dirt_camera *cam, struct dirt_gpu_model_camera *out)
{
    memset(out, 0, sizeof(*out));
    /* The default field of view and the half-angle tangent exactly as
     * dirt_camera_ray computes them. */
    float yfov = cam->yfov > 0.0f ? cam->yfov : 0.785398163f;
    out->eye = (dirt_f4){cam->eye[0], cam->eye[1], cam->eye[2], (float)cam->type};
    out->forward = (dirt_f4){cam->forward[0], cam->forward[1], cam->forward[2],
                             tanf(0.5f * yfov)};
    out->right = (dirt_f4){cam->right[0], cam->right[1], cam->right[2], cam->aspect};
    out->up = (dirt_f4){cam->up[0], cam->up[1], cam->up[2], 0.0f};
    out->lens = (dirt_f4){cam->aperture_radius, cam->focus_distance, cam->xmag, cam->ymag};
}

bool dirt_gpu_area_lights_pack(const dirt_area_lights *area, size_t num_punctual,
                               dirt_gpu_area_table *out)
{
    size_t n = area ? area->count : 0;
    struct dirt_gpu_model_lights hdr;
    memset(&hdr, 0, sizeof(hdr));
    hdr.counts = (dirt_u4){(unsigned)n, (unsigned)num_punctual,
                           dirt_light_source_count(n, num_punctual), 0u};
    hdr.area = (dirt_f4){n > 0 ? area->total_area : 0.0f, 0.0f, 0.0f, 0.0f};
    out->cdf_size = sizeof(hdr) + n * sizeof(float);
    out->prims_size = (n > 0 ? n : 1) * sizeof(uint32_t);
    out->cdf = malloc(out->cdf_size);
    out->prims = calloc(n > 0 ? n : 1, sizeof(uint32_t));
    if (!out->cdf || !out->prims) {
        DIRT_ERROR("gpu tables: out of memory for %zu area lights", n);
        dirt_gpu_area_table_free(out);
        return false;
    }
    memcpy(out->cdf, &hdr, sizeof(hdr));
    if (n > 0) {
        memcpy((char *)out->cdf + sizeof(hdr), area->cdf, n * sizeof(float));
        memcpy(out->prims, area->prim, n * sizeof(uint32_t));
    }
    return true;
}

void dirt_gpu_area_table_free(dirt_gpu_area_table *t)
{
    if (!t)
        return;
    free(t->cdf);
    free(t->prims);
    memset(t, 0, sizeof(*t));
}

void *dirt_gpu_env_pack(const dirt_env *env, size_t max_bytes, size_t *size)
{
    struct dirt_gpu_model_env hdr;
    memset(&hdr, 0, sizeof(hdr));
    size_t n = 0, h = 0, floats = 1;
    if (env) {
        n = (size_t)env->width * (size_t)env->height;
        h = (size_t)env->height;
        floats = n + h + 1 + 3 * n;
        hdr.dims = (dirt_i4){env->width, env->height, dirt_env_samples(env) ? 1 : 0, 0};
        hdr.params = (dirt_f4){env->rot_cos, env->rot_sin, env->total, 0.0f};
    }
    *size = sizeof(hdr) + floats * sizeof(float);
    if (max_bytes > 0 && *size > max_bytes) {
        DIRT_ERROR("gpu tables: the %dx%d environment map needs %zu bytes, more than the GPU's "
                   "storage-block limit of %zu", env->width, env->height, *size, max_bytes);
        return NULL;
    }
    char *out = calloc(1, *size);
    if (!out) {
        DIRT_ERROR("gpu tables: out of memory for the environment table (%zu bytes)", *size);
        return NULL;
    }
    memcpy(out, &hdr, sizeof(hdr));
    if (env) {
        float *d = (float *)(out + sizeof(hdr));
        memcpy(d, env->cdf, n * sizeof(float));
        memcpy(d + n, env->row_cos, (h + 1) * sizeof(float));
        memcpy(d + n + h + 1, env->rgb, 3 * n * sizeof(float));
    }
    return out;
}

/* ---- textures ----------------------------------------------------------- */

static float srgb_encode(float c)
{
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

static uint8_t to_byte(float c)
{
    float x = clamp01f(c) * 255.0f + 0.5f;
    return (uint8_t)(x >= 255.0f ? 255 : (int)x);
}

/* Bilinear, repeating lookup in a linear float RGBA image (texel centres at
 * (i + 0.5) / w as in dirt_texture_sample). */
static void float_sample(const float *img, int w, int h, float u, float v, float out[4])
{
    u -= floorf(u);
    v -= floorf(v);
    float x = u * (float)w - 0.5f, y = v * (float)h - 0.5f;
    float x0f = floorf(x), y0f = floorf(y);
    float fx = x - x0f, fy = y - y0f;
    int x0 = ((int)x0f % w + w) % w, y0 = ((int)y0f % h + h) % h;
    int x1 = (x0 + 1) % w, y1 = (y0 + 1) % h;
    const float *t00 = img + ((size_t)y0 * (size_t)w + (size_t)x0) * 4;
    const float *t10 = img + ((size_t)y0 * (size_t)w + (size_t)x1) * 4;
    const float *t01 = img + ((size_t)y1 * (size_t)w + (size_t)x0) * 4;
    const float *t11 = img + ((size_t)y1 * (size_t)w + (size_t)x1) * 4;
    for (int c = 0; c < 4; c++) {
        float top = t00[c] + (t10[c] - t00[c]) * fx;
        float bottom = t01[c] + (t11[c] - t01[c]) * fx;
        out[c] = top + (bottom - top) * fy;
    }
}

/* Rows [j0, j1) of a dw x dh linear float RGBA image into dst (row j0
 * first): each texel the mean of k x k bilinear samples of either the
 * original texture `tex` (decoded by dirt_texture_sample) or the float image
 * `src` (sw x sh), at the centres of a k x k grid over its footprint. */
static void resample(const dirt_texture *tex, const float *src, int sw, int sh, float *dst,
                     int dw, int dh, int j0, int j1)
{
    int kx = sw > dw ? (sw + dw - 1) / dw : 1;
    int ky = sh > dh ? (sh + dh - 1) / dh : 1;
    float inv = 1.0f / (float)(kx * ky);
    for (int j = j0; j < j1; j++) {
        for (int i = 0; i < dw; i++) {
            float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f}, s[4];
            for (int sy = 0; sy < ky; sy++) {
                float v = ((float)j + ((float)sy + 0.5f) / (float)ky) / (float)dh;
                for (int sx = 0; sx < kx; sx++) {
                    float u = ((float)i + ((float)sx + 0.5f) / (float)kx) / (float)dw;
                    if (tex)
                        dirt_texture_sample(tex, tex->srgb, u, v, s);
                    else
                        float_sample(src, sw, sh, u, v, s);
                    for (int c = 0; c < 4; c++)
                        sum[c] += s[c];
                }
            }
            float *o = dst + ((size_t)(j - j0) * (size_t)dw + (size_t)i) * 4;
            for (int c = 0; c < 4; c++)
                o[c] = sum[c] * inv;
        }
    }
}

static void encode(const float *img, size_t texels, bool srgb, uint8_t *out)
{
    for (size_t t = 0; t < texels; t++) {
        for (int c = 0; c < 3; c++)
            out[4 * t + (size_t)c] = to_byte(srgb ? srgb_encode(img[4 * t + (size_t)c])
                                                  : img[4 * t + (size_t)c]);
        out[4 * t + 3] = to_byte(img[4 * t + 3]);
    }
}

static int level_dim(int size, int level)
{
    int d = size >> level;
    return d > 0 ? d : 1;
}

static size_t level_bytes(const dirt_gpu_texture_array *a, int level)
{
    return (size_t)level_dim(a->width, level) * (size_t)level_dim(a->height, level) * 4;
}

/* Level `level` of layer `layer` of `a`. */
static uint8_t *layer_level(dirt_gpu_texture_array *a, int layer, int level)
{
    return a->pixels + a->level_offset[level] + (size_t)layer * level_bytes(a, level);
}

/* Fills every level of layer `layer` from texture t (NULL or empty: white).
 * Level 0 is t's bytes when t has the array's size, else resampled from t
 * row by row; level 1 is resampled from t, level l >= 2 from level l - 1
 * (in float). `work` holds float images of levels 1 and 2 (>= one row of
 * level 0). */
static void pack_layer(dirt_gpu_texture_array *a, int layer, const dirt_texture *t,
                       float *work)
{
    bool empty = !t || !t->rgba || t->width <= 0 || t->height <= 0;
    if (empty) {
        for (int l = 0; l < a->levels; l++)
            memset(layer_level(a, layer, l), 255, level_bytes(a, l));
        return;
    }
    if (t->width == a->width && t->height == a->height) {
        memcpy(layer_level(a, layer, 0), t->rgba, level_bytes(a, 0));
    } else {
        size_t row = (size_t)a->width * 4;
        for (int j = 0; j < a->height; j++) {
            resample(t, NULL, t->width, t->height, work, a->width, a->height, j, j + 1);
            encode(work, (size_t)a->width, t->srgb, layer_level(a, layer, 0) + (size_t)j * row);
        }
    }
    if (a->levels < 2)
        return;
    size_t n1 = (size_t)level_dim(a->width, 1) * (size_t)level_dim(a->height, 1) * 4;
    float *cur = work, *next = work + n1;
    int cw = level_dim(a->width, 1), ch = level_dim(a->height, 1);
    resample(t, NULL, t->width, t->height, cur, cw, ch, 0, ch);
    encode(cur, (size_t)cw * (size_t)ch, t->srgb, layer_level(a, layer, 1));
    for (int l = 2; l < a->levels; l++) {
        int nw = level_dim(a->width, l), nh = level_dim(a->height, l);
        resample(NULL, cur, cw, ch, next, nw, nh, 0, nh);
        encode(next, (size_t)nw * (size_t)nh, t->srgb, layer_level(a, layer, l));
        float *tmp = cur;
        cur = next;
        next = tmp;
        cw = nw;
        ch = nh;
    }
}

bool dirt_gpu_textures_pack(const dirt_texture *textures, size_t count, int max_size,
                            dirt_gpu_texture_array *out)
{
    memset(out, 0, sizeof(*out));
    if (max_size <= 0)
        max_size = 4096;
    int w = 1, h = 1;
    for (size_t i = 0; i < count; i++) {
        if (!textures[i].rgba)
            continue;
        w = textures[i].width > w ? textures[i].width : w;
        h = textures[i].height > h ? textures[i].height : h;
    }
    w = w < max_size ? w : max_size;
    h = h < max_size ? h : max_size;
    int levels = 1;
    while (levels < DIRT_GPU_MAX_MIP_LEVELS && ((w >> levels) > 0 || (h >> levels) > 0))
        levels++;
    out->width = w;
    out->height = h;
    out->layers = count > 0 ? (int)count : 1;
    out->levels = levels;
    size_t total = 0;
    for (int l = 0; l < levels; l++) {
        out->level_offset[l] = total;
        total += level_bytes(out, l) * (size_t)out->layers;
    }
    out->size = total;
    out->pixels = malloc(total);
    /* levels 1 and 2 (each the larger of the two alternates), and a row of 0 */
    size_t n1 = (size_t)level_dim(w, 1) * (size_t)level_dim(h, 1) * 4;
    size_t n2 = (size_t)level_dim(w, 2) * (size_t)level_dim(h, 2) * 4;
    size_t nw = n1 + n2 > (size_t)w * 4 ? n1 + n2 : (size_t)w * 4;
    float *work = malloc(nw * sizeof(float));
    if (!out->pixels || !work) {
        DIRT_ERROR("gpu tables: out of memory for a %dx%dx%d texture array", w, h, out->layers);
        free(work);
        dirt_gpu_texture_array_free(out);
        return false;
    }
    for (int i = 0; i < out->layers; i++)
        pack_layer(out, i, count > 0 ? &textures[i] : NULL, work);
    free(work);
    return true;
}

void dirt_gpu_texture_array_free(dirt_gpu_texture_array *a)
{
    if (!a)
        return;
    free(a->pixels);
    memset(a, 0, sizeof(*a));
}

/* ---- GL objects --------------------------------------------------------- */

static void sampler_state(GLuint tex)
{
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

bool dirt_gpu_textures_upload(dirt_gpu *gpu, const dirt_gpu_texture_array *a,
                              unsigned *tex_linear, unsigned *tex_srgb)
{
    *tex_linear = *tex_srgb = 0;
    const dirt_gpu_caps *caps = dirt_gpu_get_caps(gpu);
    if (caps && ((caps->max_array_layers > 0 && a->layers > caps->max_array_layers) ||
                 (caps->max_texture_size > 0 &&
                  (a->width > caps->max_texture_size || a->height > caps->max_texture_size)))) {
        DIRT_ERROR("gpu tables: a %dx%d texture array of %d layers exceeds this GPU's limits "
                   "(%d layers, %d texels)", a->width, a->height, a->layers,
                   caps->max_array_layers, caps->max_texture_size);
        return false;
    }
    GLuint tex = gl_texture_2d_array(GL_RGBA8, a->width, a->height, a->layers, a->levels,
                                     "model textures (linear)");
    if (!tex)
        return false;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    for (int l = 0; l < a->levels; l++) {
        int w = a->width >> l, h = a->height >> l;
        glTextureSubImage3D(tex, l, 0, 0, 0, w > 0 ? w : 1, h > 0 ? h : 1, a->layers, GL_RGBA,
                            GL_UNSIGNED_BYTE, a->pixels + a->level_offset[l]);
    }
    sampler_state(tex);
    GLuint view = 0;
    glGenTextures(1, &view);
    glTextureView(view, GL_TEXTURE_2D_ARRAY, tex, GL_SRGB8_ALPHA8, 0, (GLuint)a->levels, 0,
                  (GLuint)a->layers);
    if (!gl_check("model texture upload")) {
        DIRT_ERROR("gpu tables: could not upload the %dx%dx%d texture array", a->width,
                   a->height, a->layers);
        if (view)
            glDeleteTextures(1, &view);
        gl_texture_destroy(&tex);
        return false;
    }
    sampler_state(view);
    gl_label(GL_TEXTURE, view, "model textures (sRGB view)");
    *tex_linear = tex;
    *tex_srgb = view;
    return true;
}

bool dirt_gpu_model_tables_set_frame(dirt_gpu *gpu, dirt_gpu_model_tables *t,
                                     const dirt_frame *frame, const dirt_area_lights *area,
                                     const dirt_camera *camera)
{
    bool ok = false;
    dirt_gpu_area_table at = {0};
    size_t nl = frame ? frame->num_lights : 0;
    struct dirt_gpu_model_light *lights = calloc(nl > 0 ? nl : 1, sizeof(*lights));
    if (!lights) {
        DIRT_ERROR("gpu tables: out of memory");
        goto done;
    }
    for (size_t i = 0; i < nl; i++)
        dirt_gpu_light_pack(&frame->lights[i], &lights[i]);
    if (!dirt_gpu_area_lights_pack(area, nl, &at))
        goto done;
    struct dirt_gpu_model_camera cam;
    memset(&cam, 0, sizeof(cam));
    if (camera)
        dirt_gpu_camera_pack(camera, &cam);
    GLuint old[3] = {t->area_cdf, t->area_prims, t->punctual};
    for (int i = 0; i < 3; i++)
        gl_buffer_destroy(&old[i]);
    t->area_cdf = gl_buffer_create(gpu, at.cdf_size, at.cdf, false, "model area cdf");
    t->area_prims = gl_buffer_create(gpu, at.prims_size, at.prims, false, "model area prims");
    t->punctual = gl_buffer_create(gpu, (nl > 0 ? nl : 1) * sizeof(*lights), lights, false,
                                   "model punctual lights");
    if (!t->camera)
        t->camera = gl_buffer_create(gpu, sizeof(cam), &cam, false, "model camera");
    else
        glNamedBufferSubData(t->camera, 0, sizeof(cam), &cam);
    t->num_area = area ? area->count : 0;
    t->num_punctual = nl;
    ok = t->area_cdf && t->area_prims && t->punctual && t->camera;
done:
    free(lights);
    dirt_gpu_area_table_free(&at);
    return ok;
}

bool dirt_gpu_model_tables_create(dirt_gpu *gpu, const dirt_scene *scene,
                                  const dirt_frame *frame, const dirt_area_lights *area,
                                  const dirt_camera *camera, const float *specular,
                                  int max_texture_size, dirt_gpu_model_tables *out)
{
    memset(out, 0, sizeof(*out));
    bool ok = false;
    dirt_gpu_texture_array ta = {0};
    size_t nm = 0;
    struct dirt_gpu_model_material *mats = dirt_gpu_scene_materials(scene, specular, &nm);
    if (!mats) {
        DIRT_ERROR("gpu tables: out of memory");
        goto done;
    }
    if (!dirt_gpu_textures_pack(dirt_scene_textures(scene), dirt_scene_num_textures(scene),
                                max_texture_size, &ta))
        goto done;
    out->num_materials = nm;
    out->materials = gl_buffer_create(gpu, nm * sizeof(*mats), mats, false, "model materials");
    if (!out->materials || !dirt_gpu_textures_upload(gpu, &ta, &out->tex_linear, &out->tex_srgb))
        goto done;
    ok = dirt_gpu_model_tables_set_frame(gpu, out, frame, area, camera);
done:
    free(mats);
    dirt_gpu_texture_array_free(&ta);
    if (!ok)
        dirt_gpu_model_tables_destroy(out);
    return ok;
}

bool dirt_gpu_model_tables_set_camera(dirt_gpu_model_tables *t, const dirt_camera *camera)
{
    struct dirt_gpu_model_camera cam;
    dirt_gpu_camera_pack(camera, &cam);
    glNamedBufferSubData(t->camera, 0, sizeof(cam), &cam);
    return gl_check("model camera update");
}

void dirt_gpu_model_tables_bind(const dirt_gpu_model_tables *t)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_MATERIALS, t->materials);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_AREA_CDF, t->area_cdf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_AREA_PRIMS, t->area_prims);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_PUNCTUAL, t->punctual);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_CAMERA, t->camera);
    glBindTextureUnit(DIRT_UNIT_MODEL_TEX_LINEAR, t->tex_linear);
    glBindTextureUnit(DIRT_UNIT_MODEL_TEX_SRGB, t->tex_srgb);
}

void dirt_gpu_model_tables_destroy(dirt_gpu_model_tables *t)
{
    if (!t)
        return;
    GLuint b;
    b = t->materials; gl_buffer_destroy(&b);
    b = t->area_cdf; gl_buffer_destroy(&b);
    b = t->area_prims; gl_buffer_destroy(&b);
    b = t->punctual; gl_buffer_destroy(&b);
    b = t->camera; gl_buffer_destroy(&b);
    b = t->tex_srgb; gl_texture_destroy(&b);
    b = t->tex_linear; gl_texture_destroy(&b);
    memset(t, 0, sizeof(*t));
}
