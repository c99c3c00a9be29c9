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
#include "dirt/integrator.h"
#include "dirt/scene.h"

#include "common/integrator_layout.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- records (pure C) --------------------------------------------------- */

/* One material: factors as in the scene; texture indices outside
 * [0, num_textures) become -1 (the white default, as dirt_material_surface
 * reads them); emission = emissive * emissive_strength (the float product
 * dirt_material_surface computes) and the EMISSIVE flag when
 * dirt_material_is_emissive, else (0,0,0); specular = clamp01(specular). */
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

/* The scene's textures as one RGBA8 2D array: layer i = texture i, every
 * layer width x height with `levels` mip levels. Level l is
 * max(1, width >> l) x max(1, height >> l); pixels holds level 0 of every
 * layer (layer-major, rows top to bottom as in dirt_texture), then level 1 of
 * every layer, ... (level_offset[l] = byte offset of level l).
 *
 * width x height = the largest width and the largest height of the textures,
 * each clamped to max_size. A texture of exactly that size is copied
 * unchanged into level 0 (sampling it matches dirt_texture_sample up to the
 * hardware's filter precision); any other is resampled (documented
 * difference): each destination texel is the mean of k x k bilinear
 * samples (dirt_texture_sample, repeat) of the original, taken at the
 * centres of a k x k grid over the texel's footprint in uv (k = ceil(source /
 * destination size) per axis, 1 when enlarging), computed in linear space
 * (sRGB textures decoded, averaged, re-encoded) and rounded to 8 bits. Mip
 * levels are made the same way from the original. A texture with no pixels
 * becomes a white layer. With count 0 there is one white 1x1 layer (GL needs
 * one). */
#define DIRT_GPU_MAX_MIP_LEVELS 16
typedef struct dirt_gpu_texture_array {
    int width, height, layers, levels;
    uint8_t *pixels;
    size_t size;                                 /* bytes of pixels */
    size_t level_offset[DIRT_GPU_MAX_MIP_LEVELS];
} dirt_gpu_texture_array;

/* max_size <= 0: 4096. False after logging on out-of-memory. */
bool dirt_gpu_textures_pack(const dirt_texture *textures, size_t count, int max_size,
                            dirt_gpu_texture_array *out);
void dirt_gpu_texture_array_free(dirt_gpu_texture_array *a);

/* ---- GL objects --------------------------------------------------------- */

/* Every table of model.glsl on the GPU. GL names (GLuint), 0 = none. */
typedef struct dirt_gpu_model_tables {
    unsigned materials, area_cdf, area_prims, punctual, camera;
    unsigned tex_linear; /* GL_TEXTURE_2D_ARRAY, GL_RGBA8, mipmapped */
    unsigned tex_srgb;   /* GL_SRGB8_ALPHA8 view of tex_linear's storage */
    size_t num_materials, num_area, num_punctual;
} dirt_gpu_model_tables;

/* Uploads the texture array: tex_linear with immutable storage, tex_srgb a
 * texture view of it; both sample bilinear (GL_LINEAR mag,
 * GL_LINEAR_MIPMAP_LINEAR min) with GL_REPEAT. False after logging (too many
 * layers, too large, GL error); then both are 0. */
bool dirt_gpu_textures_upload(dirt_gpu *gpu, const dirt_gpu_texture_array *a,
                              unsigned *tex_linear, unsigned *tex_srgb);

/* Creates every buffer and the texture array for one frame of a scene:
 * materials (dirt_gpu_scene_materials with `specular`, NULL = 1), textures
 * (dirt_gpu_textures_pack, max_texture_size <= 0: 4096), the area-light
 * table of `area` (may be NULL), the frame's punctual lights and `camera`
 * (may be NULL: a zero record). False after logging; `out` is then all 0. */
bool dirt_gpu_model_tables_create(dirt_gpu *gpu, const dirt_scene *scene,
                                  const dirt_frame *frame, const dirt_area_lights *area,
                                  const dirt_camera *camera, const float *specular,
                                  int max_texture_size, dirt_gpu_model_tables *out);

/* Replaces the per-frame tables (area-light table of `area`, may be NULL;
 * the frame's punctual lights; the camera, NULL: a zero record) of tables
 * made by dirt_gpu_model_tables_create, keeping the per-scene ones
 * (materials, textures). False after logging (the tables must then be
 * destroyed). */
bool dirt_gpu_model_tables_set_frame(dirt_gpu *gpu, dirt_gpu_model_tables *t,
                                     const dirt_frame *frame, const dirt_area_lights *area,
                                     const dirt_camera *camera);

/* Replaces the camera record (glNamedBufferSubData). */
bool dirt_gpu_model_tables_set_camera(dirt_gpu_model_tables *t, const dirt_camera *camera);

/* Binds the buffers to DIRT_BIND_MODEL_* and the textures to
 * DIRT_UNIT_MODEL_TEX_*. */
void dirt_gpu_model_tables_bind(const dirt_gpu_model_tables *t);

void dirt_gpu_model_tables_destroy(dirt_gpu_model_tables *t);

#ifdef __cplusplus
}
#endif
#endif
