/* DIRT engine: packing and upload of the GPU light-transport model's scene
 * tables (integrator/gpu_tables.h, glsl/common/integrator_layout.h). */
#include "integrator/gpu_tables.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "gl/gl.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */
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
    out->params = (dirt_f4){m->metallic, m->roughness, clamp01f(specular * m->specular), 0.0f};
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
    out->params.w = m->normal_scale;
    out->textures2 = (dirt_i4){texture_index(m->normal_tex, num_textures),
                               texture_index(m->transmission_tex, num_textures),
                               texture_index(m->specular_tex, num_textures),
                               texture_index(m->specular_color_tex, num_textures)};
    out->params2 = (dirt_f4){m->transmission, dirt_ior_eta(m->ior), m->alpha_cutoff,
                             (float)m->alpha_mode};
    out->specular_color = (dirt_f4){m->specular_color[0], m->specular_color[1],
                                    m->specular_color[2], dirt_ior_f0(m->ior)};
    /* Texture transforms: the matrix the C model forms per lookup, made
     * by the same function (the same cosf / sinf bits). */
    for (int k = 0; k < DIRT_MODEL_TEX_SLOTS; k++) {
        float x[6];
        dirt_tex_transform_matrix(&m->xf[k], x);
        out->xf[2 * k] = (dirt_f4){x[0], x[1], x[2], 0.0f};
        out->xf[2 * k + 1] = (dirt_f4){x[3], x[4], x[5], 0.0f};
    }
}

_Static_assert(DIRT_MODEL_TEX_SLOTS == DIRT_NUM_TEX_SLOTS,
               "common/integrator_layout.h and dirt/scene.h: texture slots");

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
        dirt_material white;
        dirt_material_default(&white);
        white.metallic = 0.0f;
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
        floats = n + h + 1 + 3 * n + 2 * ((size_t)env->width + 1);
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
        size_t w1 = (size_t)env->width + 1;
        memcpy(d + 4 * n + h + 1, env->col_cos, w1 * sizeof(float));
        memcpy(d + 4 * n + h + 1 + w1, env->col_sin, w1 * sizeof(float));
    }
    return out;
}

/* ---- textures ----------------------------------------------------------- */

_Static_assert(sizeof(struct dirt_gpu_model_texels) ==
                   DIRT_MODEL_TEXELS_HEADER_WORDS * sizeof(uint32_t) &&
               sizeof(struct dirt_gpu_model_texture) == 4 * sizeof(uint32_t),
               "texel buffer records are 4 words");

static bool has_pixels(const dirt_texture *t)
{
    return t->rgba && t->width > 0 && t->height > 0;
}

bool dirt_gpu_textures_pack(const dirt_texture *textures, size_t count,
                            dirt_gpu_texel_buffer *out)
{
    memset(out, 0, sizeof(*out));
    /* Words after the header: the records, then the texels; the shader
     * indexes them with 32-bit uints. */
    const uint64_t max_words = UINT32_MAX;
    uint64_t words = (uint64_t)count * 4;
    for (size_t i = 0; i < count && words <= max_words; i++)
        if (has_pixels(&textures[i]))
            words += (uint64_t)textures[i].width * (uint64_t)textures[i].height;
    if (words > max_words || words > SIZE_MAX / sizeof(uint32_t) - 4) {
        DIRT_ERROR("gpu tables: the %zu textures need more than %llu texels and records, the "
                   "most the shader can index", count, (unsigned long long)max_words);
        return false;
    }
    size_t header = sizeof(struct dirt_gpu_model_texels) / sizeof(uint32_t);
    out->size = (header + (size_t)words) * sizeof(uint32_t);
    out->words = malloc(out->size);
    if (!out->words) {
        DIRT_ERROR("gpu tables: out of memory for %zu bytes of texels", out->size);
        out->size = 0;
        return false;
    }
    struct dirt_gpu_model_texels hdr;
    memset(&hdr, 0, sizeof(hdr));
    hdr.counts = (dirt_u4){(uint32_t)count, (uint32_t)words, 0u, 0u};
    memcpy(out->words, &hdr, sizeof(hdr));
    uint32_t *body = out->words + header; /* word k of the shader */
    uint32_t next = (uint32_t)count * 4;  /* first free texel word */
    for (size_t i = 0; i < count; i++) {
        const dirt_texture *t = &textures[i];
        struct dirt_gpu_model_texture rec;
        memset(&rec, 0, sizeof(rec));
        if (has_pixels(t)) {
            rec.extent = (dirt_u4){next, (uint32_t)t->width, (uint32_t)t->height, 0u};
            size_t n = (size_t)t->width * (size_t)t->height;
            /* The word's value, not its bytes: R low, whatever the host's
             * byte order (GL reads buffer words in the host's order). */
            for (size_t k = 0; k < n; k++) {
                const uint8_t *c = t->rgba + 4 * k;
                body[next + k] = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 |
                                 (uint32_t)c[3] << 24;
            }
            next += (uint32_t)n;
            out->num_texels += n;
        }
        memcpy(body + 4 * i, &rec, sizeof(rec));
    }
    out->num_textures = count;
    return true;
}

void dirt_gpu_texel_buffer_free(dirt_gpu_texel_buffer *b)
{
    if (!b)
        return;
    free(b->words);
    memset(b, 0, sizeof(*b));
}

/* ---- GL objects --------------------------------------------------------- */

const gl_split_desc dirt_gpu_split_texels = {
    .label = "scene's texels", .define = "DIRT_SPLIT_TEXELS", .record_bytes = sizeof(uint32_t),
    .format = GL_R32UI, .binding = DIRT_BIND_MODEL_TEXELS, .unit = DIRT_UNIT_SPLIT_TEXELS,
    .advice = "make the scene's textures smaller or fewer",
};
const gl_split_desc dirt_gpu_split_tangents = {
    .label = "frame's tangents", .define = "DIRT_SPLIT_TANGENTS",
    .record_bytes = sizeof(struct dirt_gpu_model_tangent), .format = GL_RGBA32F,
    .binding = DIRT_BIND_MODEL_TANGENTS, .unit = DIRT_UNIT_SPLIT_TANGENTS,
    .advice = "render a scene of fewer triangles, or one without normal maps",
};

bool dirt_gpu_textures_upload(dirt_gpu *gpu, const dirt_gpu_texel_buffer *b, gl_split *out)
{
    gl_split_release(out);
    size_t words = b->size / sizeof(uint32_t);
    if (!gl_split_ensure(gpu, out, &dirt_gpu_split_texels, words) ||
        !gl_split_write(out, 0, words, b->words)) {
        gl_split_release(out);
        return false;
    }
    return true;
}

/* Frame vertices with a tangent record: 3 per triangle when a material has
 * a normal map and the frame has tangents, else 0 (one zero record is
 * uploaded). */
static size_t tangent_records(bool normal_maps, const dirt_frame *frame)
{
    return normal_maps && frame && frame->tangent ? 3 * frame->num_triangles : 0;
}

/* (Re)uploads the frame's tangents (dirt_gpu_model_tangent per frame
 * vertex) when a material has a normal map and the frame has tangents, else
 * one zero record. False after logging. */
static bool upload_tangents(dirt_gpu *gpu, dirt_gpu_model_tables *t, const dirt_frame *frame)
{
    gl_split_release(&t->tangents);
    t->tangent_bytes = 0;
    size_t n = tangent_records(t->normal_maps, frame);
    /* dirt_frame.tangent is float[4] per vertex: the record's layout. */
    _Static_assert(sizeof(struct dirt_gpu_model_tangent) == 4 * sizeof(float), "tangent record");
    static const struct dirt_gpu_model_tangent zero;
    if (!gl_split_ensure(gpu, &t->tangents, &dirt_gpu_split_tangents, n > 0 ? n : 1) ||
        !gl_split_write(&t->tangents, 0, n > 0 ? n : 1,
                        n > 0 ? (const void *)frame->tangent : &zero)) {
        gl_split_release(&t->tangents);
        return false;
    }
    t->tangent_bytes = gl_split_bytes(&t->tangents);
    return true;
}

bool dirt_gpu_model_tables_plan(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *frame,
                                gl_split_layout *texels, gl_split_layout *tangents)
{
    const dirt_texture *tex = dirt_scene_textures(scene);
    size_t nt = dirt_scene_num_textures(scene);
    /* The words dirt_gpu_textures_pack writes: header, records, texels. */
    uint64_t words = DIRT_MODEL_TEXELS_HEADER_WORDS + (uint64_t)nt * 4;
    for (size_t i = 0; i < nt; i++)
        if (has_pixels(&tex[i]))
            words += (uint64_t)tex[i].width * (uint64_t)tex[i].height;
    if (words > SIZE_MAX / sizeof(uint32_t)) {
        DIRT_ERROR("gpu tables: the %zu textures need %llu texels and records, more than "
                   "this machine addresses", nt, (unsigned long long)words);
        return false;
    }
    const dirt_material *m = dirt_scene_materials(scene);
    bool normal_maps = false;
    for (size_t i = 0; i < dirt_scene_num_materials(scene); i++)
        normal_maps |= m[i].normal_tex >= 0 && (size_t)m[i].normal_tex < nt;
    return gl_split_plan(gpu, &dirt_gpu_split_texels, (size_t)words, texels) &&
           gl_split_plan(gpu, &dirt_gpu_split_tangents, tangent_records(normal_maps, frame),
                         tangents);
}

void dirt_gpu_model_tables_arrays(const dirt_gpu_model_tables *t, const gl_split_desc **descs,
                                  gl_split_layout *layouts)
{
    descs[0] = &dirt_gpu_split_texels;
    descs[1] = &dirt_gpu_split_tangents;
    layouts[0] = t->texels.layout;
    layouts[1] = t->tangents.layout;
}

bool dirt_gpu_model_tables_set_frame(dirt_gpu *gpu, dirt_gpu_model_tables *t,
                                     const dirt_frame *frame, const dirt_area_lights *area,
                                     const dirt_camera *camera)
{
    bool ok = false;
    if (!upload_tangents(gpu, t, frame))
        return false;
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
                                  dirt_gpu_model_tables *out)
{
    memset(out, 0, sizeof(*out));
    bool ok = false;
    dirt_gpu_texel_buffer tb = {0};
    size_t nm = 0;
    struct dirt_gpu_model_material *mats = dirt_gpu_scene_materials(scene, specular, &nm);
    if (!mats) {
        DIRT_ERROR("gpu tables: out of memory");
        goto done;
    }
    if (!dirt_gpu_textures_pack(dirt_scene_textures(scene), dirt_scene_num_textures(scene), &tb))
        goto done;
    out->num_materials = nm;
    out->num_textures = tb.num_textures;
    out->materials = gl_buffer_create(gpu, nm * sizeof(*mats), mats, false, "model materials");
    if (!out->materials || !dirt_gpu_textures_upload(gpu, &tb, &out->texels))
        goto done;
    out->texel_bytes = gl_split_bytes(&out->texels);
    for (size_t i = 0; i < nm; i++)
        out->normal_maps |= mats[i].textures2.x >= 0;
    ok = dirt_gpu_model_tables_set_frame(gpu, out, frame, area, camera);
done:
    free(mats);
    dirt_gpu_texel_buffer_free(&tb);
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
    gl_split_bind(&t->texels);
    gl_split_bind(&t->tangents);
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
    gl_split_release(&t->texels);
    gl_split_release(&t->tangents);
    memset(t, 0, sizeof(*t));
}
