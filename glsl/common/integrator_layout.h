/* Data layouts of the GPU light-transport model (glsl/integrator/model.glsl),
 * shared by C (src/integrator/gpu_tables.c packs them) and GLSL. Same rules
 * as common/layout.h, which this file includes: only structs of
 * DIRT_V4/DIRT_IV4/DIRT_UV4 members and #defines, valid C11 and GLSL 4.50;
 * test/common/layout_check.c checks sizes and offsets with _Static_assert.
 *
 * These records are the integrator's, not the raster preview's
 * (dirt_gpu_material / dirt_gpu_light of layout.h). Every value a record
 * holds is either copied from the scene or computed on the CPU with the same
 * float operation the C model uses (e.g. cos of the spot cone angles, tan of
 * half the field of view), so the GLSL and the C model start from the same
 * bits. Specification: doc/light-transport-gpu.md. */
#ifndef DIRT_COMMON_INTEGRATOR_LAYOUT_H
#define DIRT_COMMON_INTEGRATOR_LAYOUT_H

#include "common/layout.h"

/* The model's tables are bound at DIRT_BIND_MODEL_* (declared by
 * model.glsl when DIRT_MODEL_BUFFERS is defined; common/constants.h). */

/* Punctual light kinds (= enum dirt_light_type). */
#define DIRT_MODEL_LIGHT_DIRECTIONAL 0
#define DIRT_MODEL_LIGHT_POINT 1
#define DIRT_MODEL_LIGHT_SPOT 2

/* Camera kinds (= enum dirt_camera_type). */
#define DIRT_MODEL_CAMERA_PERSPECTIVE 0
#define DIRT_MODEL_CAMERA_ORTHOGRAPHIC 1

/* dirt_gpu_model_material.textures.w bits. */
#define DIRT_MODEL_MAT_DOUBLE_SIDED 1
#define DIRT_MODEL_MAT_EMISSIVE 2      /* dirt_material_is_emissive */

/* Texture slots of a material (= DIRT_NUM_TEX_SLOTS of dirt/scene.h, enum
 * dirt_tex_slot order: base colour, metallic-roughness, emissive, normal,
 * transmission, specular, specular colour). */
#define DIRT_MODEL_TEX_SLOTS 7

/* One material of the integrator (336 bytes). */
struct dirt_gpu_model_material {
    DIRT_V4 base_color;  /* rgb linear base colour factor, w alpha factor */
    DIRT_V4 emission;    /* rgb emissive * emissive_strength (float product as
                            in C), (0,0,0) when not emissive; w unused */
    DIRT_V4 params;      /* x metallic, y roughness (factors, unclamped),
                            z dielectric specular weight (the packer's extra
                            factor times specularFactor) clamped to [0,1],
                            w normal scale */
    DIRT_IV4 textures;   /* x base colour, y metallic-roughness, z emissive
                            texture (index of dirt_gpu_model_texture; -1:
                            none / out of range), w DIRT_MODEL_MAT_* flags */
    DIRT_IV4 textures2;  /* x normal, y transmission, z specular, w specular
                            colour texture (as `textures`) */
    DIRT_V4 params2;     /* x transmission factor, y the ior refraction uses
                            (dirt_ior_eta), z alpha cutoff, w alpha mode
                            (enum dirt_alpha_mode, exact) */
    DIRT_V4 specular_color; /* rgb specularColorFactor, w dirt_ior_f0(ior) */
    DIRT_V4 xf[2 * DIRT_MODEL_TEX_SLOTS]; /* per slot s: xf[2s] = (m00, m01,
                            m02, 0), xf[2s + 1] = (m10, m11, m12, 0): the
                            slot's KHR_texture_transform as uv' = M (u, v, 1)
                            (the identity when the slot has none) */
};

/* One punctual light (64 bytes), from a dirt_light. */
struct dirt_gpu_model_light {
    DIRT_V4 position;    /* xyz world position, w kind (DIRT_MODEL_LIGHT_*, exact) */
    DIRT_V4 direction;   /* xyz direction the light shines, as in dirt_light
                            (not normalised: the model normalises), w range
                            (0 = none) */
    DIRT_V4 color;       /* rgb color * intensity, w unused */
    DIRT_V4 cone;        /* x cosf(outer_cone), y cosf(inner_cone) (spot), zw 0 */
};

/* Header of the area-light table (32 bytes), first in the
 * DIRT_BIND_MODEL_AREA_CDF buffer, followed by float cdf[count] (the
 * dirt_area_lights cdf). The primitive of entry i is prim[i] of
 * DIRT_BIND_MODEL_AREA_PRIMS. */
struct dirt_gpu_model_lights {
    DIRT_UV4 counts;     /* x emissive triangles (area count), y punctual
                            lights, z light sources for NEE
                            (dirt_light_source_count), w 0 */
    DIRT_V4 area;        /* x total area, yzw 0 */
};

/* Header of the environment light (32 bytes), first in the
 * DIRT_BIND_MODEL_ENV buffer, followed by float data[]: the dirt_env's
 * cdf[w h] at 0, row_cos[h + 1] at w h, rgb[3 w h] at w h + h + 1,
 * col_cos[w + 1] at 4 w h + h + 1 and col_sin[w + 1] after it. Without an
 * environment: size 0 x 0 and one float of data. */
struct dirt_gpu_model_env {
    DIRT_IV4 dims;       /* x width, y height (0: no environment), z 1 when
                            NEE samples it (dirt_env_samples), w 0 */
    DIRT_V4 params;      /* x rot_cos, y rot_sin, z total, w 0 */
};

/* A camera (80 bytes), from a dirt_camera. */
struct dirt_gpu_model_camera {
    DIRT_V4 eye;         /* xyz eye, w kind (DIRT_MODEL_CAMERA_*, exact) */
    DIRT_V4 forward;     /* xyz forward, w tanf(0.5 yfov) (yfov <= 0: of the
                            default 0.785398163 as in dirt_camera_ray) */
    DIRT_V4 right;       /* xyz right, w aspect (0: width / height of the image) */
    DIRT_V4 up;          /* xyz up, w 0 */
    DIRT_V4 lens;        /* x aperture radius, y focus distance (thin lens when
                            both > 0), z xmag, w ymag (orthographic, raw) */
};

/* The scene's textures at their own sizes, one buffer at
 * DIRT_BIND_MODEL_TEXELS of 32-bit words:
 *
 *   struct dirt_gpu_model_texels         header (16 bytes)
 *   struct dirt_gpu_model_texture[count]  one record per scene texture, in
 *                                         scene order (16 bytes each)
 *   uint texels[]                         every texture's RGBA8 texels
 *
 * Word k after the header is dirt_model_texel_words[k] in GLSL; a texture's
 * texel (i, j) (row j = 0 = the first image row, as in dirt_texture) is word
 * extent.x + j * width + i, holding R in bits 0-7, G 8-15, B 16-23, A 24-31
 * (the bytes of dirt_texture.rgba, unchanged). */
/* Words of the header before the records (= sizeof(struct
 * dirt_gpu_model_texels) / 4). */
#define DIRT_MODEL_TEXELS_HEADER_WORDS 4
struct dirt_gpu_model_texels {
    DIRT_UV4 counts;     /* x textures (records that follow), y words after
                            the header (records and texels), zw 0 */
};

/* One texture of the texel buffer (16 bytes). */
struct dirt_gpu_model_texture {
    DIRT_UV4 extent;     /* x word of texel (0, 0) (counted from the first
                            word after the header), y width, z height
                            (0 x 0: the texture has no pixels and reads
                            (1,1,1,1), as dirt_texture_sample), w 0 */
};

/* The frame's tangents for normal maps, at DIRT_BIND_MODEL_TANGENTS: one
 * record per frame vertex, entry 3 p + k = vertex k of primitive p (the
 * order of dirt_frame.tangent and of the vertex buffer). A frame without
 * tangents, or a scene whose materials have no normal map, uploads one
 * zero record instead; the shader reads entries only for a normal-mapped
 * material and only below the array's length (16 bytes each). */
struct dirt_gpu_model_tangent {
    DIRT_V4 tangent;     /* xyz unit world tangent (0 where the mesh has
                            none), w handedness +1 / -1 (= dirt_frame) */
};

#endif
