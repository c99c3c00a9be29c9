/* DIRT engine: the scene tables of the GPU light-transport model.
 *
 * Packs what glsl/integrator/model.glsl reads (materials, the scene's
 * textures, area and punctual lights, the camera) into the records of
 * glsl/common/integrator_layout.h, and uploads them. The packing is pure C;
 * dirt_gpu_model_tables_* create and bind the GL objects (a current GL 4.5
 * context is needed). Specification: doc/light-transport-gpu.md. */
#ifndef DIRT_GPU_TABLES_H
#define DIRT_GPU_TABLES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/gpu.h"
#include "integrator/integrator.h"
#include "dirt/scene.h"
#include "gl/split.h"

#include "common/integrator_layout.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- records (pure C) --------------------------------------------------- */

/* One material: factors as in the scene; texture indices outside
 * [0, num_textures) become -1 (the white default, as dirt_material_surface
 * reads them); emission = emissive * emissive_strength (the float product
 * dirt_material_surface computes) and the EMISSIVE flag when
 * dirt_material_is_emissive, else (0,0,0); specular = clamp01(specular *
 * m->specular) (the extra factor times the material's specularFactor, as
 * dirt_material_surface forms it); params2.y = dirt_ior_eta(ior),
 * specular_color.w = dirt_ior_f0(ior). */
void dirt_gpu_material_pack(const dirt_material *m, float specular, size_t num_textures,
                            struct dirt_gpu_model_material *out);

/* Every material of an array: out[i] from materials[i] with specular[i]
 * (specular NULL: 1 for every material, as plain glTF). */
void dirt_gpu_materials_pack(const dirt_material *materials, size_t count,
                             const float *specular, size_t num_textures,
                             struct dirt_gpu_model_material *out);

/* The scene's materials in a new array (caller frees; *count receives the
 * number, which is at least 1: a scene without materials gets one default
 * white material so the buffer is never empty). NULL after logging on
 * out-of-memory. */
struct dirt_gpu_model_material *dirt_gpu_scene_materials(const dirt_scene *scene,
                                                         const float *specular,
                                                         size_t *count);

/* One punctual light; the cone cosines are cosf() of the angles, as
 * dirt_punctual_light computes them. */
void dirt_gpu_light_pack(const dirt_light *light, struct dirt_gpu_model_light *out);

/* A camera; forward.w = tanf(0.5 yfov) with the default yfov of
 * dirt_camera_ray when yfov <= 0. */
void dirt_gpu_camera_pack(const dirt_camera *cam, struct dirt_gpu_model_camera *out);

/* The area-light table as the two buffers model.glsl reads:
 *   cdf:   struct dirt_gpu_model_lights header, then float cdf[count]
 *   prims: uint32_t prim[max(count, 1)]
 * `area` may be NULL or empty (count 0). num_punctual is recorded in the
 * header with the NEE source count (dirt_light_source_count). */
typedef struct dirt_gpu_area_table {
    void *cdf;          /* malloc'd, cdf_size bytes */
    size_t cdf_size;
    uint32_t *prims;    /* malloc'd, prims_size bytes */
    size_t prims_size;
} dirt_gpu_area_table;

/* False after logging on out-of-memory (out is then empty). */
bool dirt_gpu_area_lights_pack(const dirt_area_lights *area, size_t num_punctual,
                               dirt_gpu_area_table *out);
void dirt_gpu_area_table_free(dirt_gpu_area_table *t);

/* The environment table model.glsl reads at DIRT_BIND_MODEL_ENV: a struct
 * dirt_gpu_model_env header, then the map's cdf, row_cos and rgb (layout
 * in common/integrator_layout.h), copied bit for bit. `env` NULL: the
 * header of no environment and one zero float. Returns malloc'd memory of
 * *size bytes (caller frees); NULL after logging on out-of-memory or when
 * the table would not fit `max_bytes` (> 0: the GPU's storage-block
 * limit). */
void *dirt_gpu_env_pack(const dirt_env *env, size_t max_bytes, size_t *size);

/* ---- textures (pure C) -------------------------------------------------- */

/* The scene's textures at their own sizes, as the texel buffer model.glsl
 * reads (glsl/common/integrator_layout.h): header, one
 * dirt_gpu_model_texture per texture (scene order), then every texture's
 * RGBA8 texels, unchanged (row 0 first, R in the low byte of a word). A
 * texture without pixels (rgba NULL or a size <= 0) gets a 0 x 0 record and
 * no texels (it reads white, as in dirt_texture_sample). With count 0 the
 * buffer is the header alone. */
typedef struct dirt_gpu_texel_buffer {
    uint32_t *words;       /* malloc'd, size bytes: header, records, texels */
    size_t size;           /* bytes */
    size_t num_textures;
    size_t num_texels;     /* texels of every texture */
} dirt_gpu_texel_buffer;

/* False after logging (out of memory; more than 2^32 - 1 words: the
 * shader's word index is 32-bit); out is then empty. */
bool dirt_gpu_textures_pack(const dirt_texture *textures, size_t count,
                            dirt_gpu_texel_buffer *out);
void dirt_gpu_texel_buffer_free(dirt_gpu_texel_buffer *b);

/* ---- GL objects --------------------------------------------------------- */

/* The texel table and the tangents as split arrays (gl/split.h; model.glsl
 * reads them through dirt_model_texel_word_g / dirt_model_tangent_g): the
 * texel table's words (header included, R32UI texels when split) and one
 * dirt_gpu_model_tangent per frame vertex (RGBA32F). */
extern const gl_split_desc dirt_gpu_split_texels, dirt_gpu_split_tangents;

/* Every table of model.glsl on the GPU. GL names (GLuint), 0 = none. */
typedef struct dirt_gpu_model_tables {
    unsigned materials, area_cdf, area_prims, punctual, camera;
    gl_split texels;     /* the texel buffer (dirt_gpu_texel_buffer) */
    size_t texel_bytes;  /* its size: allocated = used */
    size_t num_materials, num_area, num_punctual, num_textures;
    gl_split tangents;   /* the frame's tangents (dirt_gpu_model_tangent per
                            frame vertex; one zero record when no material
                            has a normal map or the frame has no tangents) */
    size_t tangent_bytes;
    bool normal_maps;    /* a material has a normal map */
} dirt_gpu_model_tables;

/* Uploads a texel buffer into `out` (one storage block while it fits this
 * GPU's GL_MAX_SHADER_STORAGE_BLOCK_SIZE, else texel-buffer parts). False
 * after logging, `out` then empty: more than one split array holds (the
 * error says to make the textures smaller or fewer), or a GL error. */
bool dirt_gpu_textures_upload(dirt_gpu *gpu, const dirt_gpu_texel_buffer *b, gl_split *out);

/* The layouts the texels and tangents of `scene` at `frame` (NULL: none)
 * take on this GPU, as dirt_gpu_model_tables_create makes them: pure
 * arithmetic, before any upload or pass. False after logging what to
 * change when one does not fit (the size checks of the path tracer,
 * dirt_pt_check_frame). */
bool dirt_gpu_model_tables_plan(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *frame,
                                gl_split_layout *texels, gl_split_layout *tangents);

/* The defines and layouts of a program that reads the tables (the
 * texels' and tangents' split arrays): `descs` and `layouts` get 2
 * entries. */
void dirt_gpu_model_tables_arrays(const dirt_gpu_model_tables *t, const gl_split_desc **descs,
                                  gl_split_layout *layouts);

/* Creates every buffer for one frame of a scene: materials
 * (dirt_gpu_scene_materials with `specular`, NULL = 1), the texel buffer of
 * the scene's textures (dirt_gpu_textures_pack), the frame's tangents, the area-light table of
 * `area` (may be NULL), the frame's punctual lights and `camera` (may be
 * NULL: a zero record). False after logging; `out` is then all 0. */
bool dirt_gpu_model_tables_create(dirt_gpu *gpu, const dirt_scene *scene,
                                  const dirt_frame *frame, const dirt_area_lights *area,
                                  const dirt_camera *camera, const float *specular,
                                  dirt_gpu_model_tables *out);

/* Replaces the per-frame tables (the tangents; area-light table of `area`, may be NULL;
 * the frame's punctual lights; the camera, NULL: a zero record) of tables
 * made by dirt_gpu_model_tables_create, keeping the per-scene ones
 * (materials, textures). False after logging (the tables must then be
 * destroyed). */
bool dirt_gpu_model_tables_set_frame(dirt_gpu *gpu, dirt_gpu_model_tables *t,
                                     const dirt_frame *frame, const dirt_area_lights *area,
                                     const dirt_camera *camera);

/* Replaces the camera record (glNamedBufferSubData). */
bool dirt_gpu_model_tables_set_camera(dirt_gpu_model_tables *t, const dirt_camera *camera);

/* Binds the buffers to DIRT_BIND_MODEL_*. */
void dirt_gpu_model_tables_bind(const dirt_gpu_model_tables *t);

void dirt_gpu_model_tables_destroy(dirt_gpu_model_tables *t);

#ifdef __cplusplus
}
#endif
#endif
