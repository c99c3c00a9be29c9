/* DIRT engine: scene model.
 *
 * A scene is loaded once (glTF 2.0 .gltf/.glb, Wavefront OBJ + MTL, or the
 * embedded default scene) and evaluated at a time t into a world-space triangle soup, `dirt_frame`,
 * which is what every technique (raster preview, DIRT, MMRT, Embree) consumes.
 *
 * Primitive ids: triangle p of the frame is the p-th triangle in the order
 * (mesh instance in depth-first node order, glTF primitive, index triple);
 * for an OBJ file, the file's faces in order, each polygon of n corners
 * making n - 2 consecutive triangles.
 * The node hierarchy and meshes never change with t, so ids are stable over
 * time: the same id names the same triangle in every frame. */
#ifndef DIRT_SCENE_H
#define DIRT_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_scene dirt_scene;

#define DIRT_NO_TEXTURE (-1)

/* Decoded texture, always 8-bit RGBA, rows top to bottom as stored in the
 * image file (glTF UV (0,0) is the first texel of the first row). */
typedef struct dirt_texture {
    int width, height;
    uint8_t *rgba; /* width*height*4 bytes, owned by the scene */
    bool srgb;     /* true when used as base colour or emissive */
    char name[64];
} dirt_texture;

/* glTF alphaMode. */
enum dirt_alpha_mode { DIRT_ALPHA_OPAQUE = 0, DIRT_ALPHA_MASK = 1, DIRT_ALPHA_BLEND = 2 };

/* A material's texture slots (the order of dirt_material.xf). */
enum dirt_tex_slot {
    DIRT_SLOT_BASE_COLOR = 0,
    DIRT_SLOT_METALLIC_ROUGHNESS,
    DIRT_SLOT_EMISSIVE,
    DIRT_SLOT_NORMAL,
    DIRT_SLOT_TRANSMISSION,
    DIRT_SLOT_SPECULAR,
    DIRT_SLOT_SPECULAR_COLOR,
    DIRT_NUM_TEX_SLOTS
};

/* KHR_texture_transform of one texture slot (glTF: uv' = T(offset)
 * R(rotation) S(scale) uv). `set` false: the identity. */
typedef struct dirt_tex_transform {
    bool set;
    float offset[2];
    float rotation;             /* radians */
    float scale[2];
} dirt_tex_transform;

/* glTF metallic-roughness material. Texture fields are indices into the
 * scene's textures or DIRT_NO_TEXTURE. Make one with dirt_material_default
 * (the glTF defaults) and change what the file gives: a zeroed struct has
 * texture 0 in every slot. */
typedef struct dirt_material {
    char name[64];
    float base_color[4];        /* linear RGBA factor */
    int base_color_tex;         /* sRGB */
    float metallic, roughness;  /* factors */
    int metallic_roughness_tex; /* G = roughness, B = metallic (linear) */
    float emissive[3];          /* linear factor */
    float emissive_strength;    /* KHR_materials_emissive_strength, 1 if absent */
    int emissive_tex;           /* sRGB */
    bool double_sided;
    int normal_tex;             /* tangent-space normal map (linear RGB) */
    float normal_scale;         /* normalTexture.scale, 1 if absent */
    enum dirt_alpha_mode alpha_mode;
    float alpha_cutoff;         /* MASK: alphaCutoff, 0.5 if absent */
    float transmission;         /* KHR_materials_transmission factor, 0 if absent */
    int transmission_tex;       /* its R channel (linear) */
    float ior;                  /* KHR_materials_ior, 1.5 if absent */
    float specular;             /* KHR_materials_specular specularFactor, 1 if absent */
    int specular_tex;           /* its A channel (linear) */
    float specular_color[3];    /* specularColorFactor, 1 if absent */
    int specular_color_tex;     /* its RGB (sRGB) */
    dirt_tex_transform xf[DIRT_NUM_TEX_SLOTS]; /* per slot (enum dirt_tex_slot) */
} dirt_material;

/* The glTF defaults: white base, metallic 1, roughness 1, no emission
 * (strength 1), no texture in any slot, normal scale 1, opaque (cutoff
 * 0.5), no transmission, ior 1.5, specular 1 of colour 1, identity
 * transforms; the name empty. */
DIRT_API void dirt_material_default(dirt_material *m);

enum dirt_camera_type { DIRT_CAMERA_PERSPECTIVE = 0, DIRT_CAMERA_ORTHOGRAPHIC = 1 };

/* A camera as defined in the file; its pose comes from its node. */
typedef struct dirt_camera_def {
    char name[64];
    enum dirt_camera_type type;
    float yfov;         /* radians, perspective */
    float aspect;       /* 0 when the file gives none */
    float znear, zfar;  /* zfar 0 = infinite */
    float xmag, ymag;   /* orthographic */
    int node;           /* node carrying the camera */
} dirt_camera_def;

enum dirt_light_type {
    DIRT_LIGHT_DIRECTIONAL = 0,
    DIRT_LIGHT_POINT = 1,
    DIRT_LIGHT_SPOT = 2,
};

/* KHR_lights_punctual light; pose from its node. */
typedef struct dirt_light_def {
    char name[64];
    enum dirt_light_type type;
    float color[3];
    float intensity;    /* candela (point/spot) or lux (directional) */
    float range;        /* 0 = infinite */
    float inner_cone, outer_cone; /* radians, spot */
    int node;
} dirt_light_def;

/* Why a load failed: one X-macro list gives the enum (DIRT_SCENE_ERR_<id>),
 * the message table (dirt_scene_error_str) and the tests' expectations. */
#define DIRT_SCENE_ERRORS(X)                                                          \
    X(OK, "ok")                                                                       \
    X(ARGUMENT, "no path or data given")                                              \
    X(IO, "the file cannot be opened or read")                                        \
    X(EMPTY, "the file is empty")                                                     \
    X(TRUNCATED, "the data ends early (a .glb chunk, a buffer or a buffer view)")     \
    X(TOO_DEEP, "JSON nested deeper than the limit")                                  \
    X(SYNTAX, "not a glTF 2.0 or OBJ file (syntax or required members)")              \
    X(EXTERNAL, "an external file cannot be used (missing, or loading from memory)")  \
    X(RANGE, "an accessor's elements lie outside its buffer view")                    \
    X(TYPE, "an accessor of the wrong type or component type")                        \
    X(REFERENCE, "a reference to an object that does not exist")                      \
    X(INDEX, "a vertex index or joint past its range")                                \
    X(NOT_FINITE, "a non-finite position")                                            \
    X(HIERARCHY, "a node cycle or a node with two parents")                           \
    X(TOO_LARGE, "the scene needs more memory than the load budget")                  \
    X(OUT_OF_MEMORY, "out of memory")                                                 \
    X(UNSUPPORTED, "the file requires a glTF extension the loader does not support")  \
    X(VERSION, "not glTF 2.0 (a glTF 1.0 file, or a version this loader does not read)") \
    X(FORMAT, "not a scene format the loader reads (glTF 2.0 .gltf/.glb, OBJ .obj)")  \
    X(NOT_REGULAR, "not a regular file (a directory, FIFO, socket or device)")        \
    X(OUTSIDE, "a referenced file lies outside the scene's folder")                   \
    X(STRICT, "a warning about the scene, and the load is strict")                    \
    X(INVALID, "other invalid content")

enum dirt_scene_error {
#define DIRT_SCENE_ERR_ENUM_(id, msg) DIRT_SCENE_ERR_##id,
    DIRT_SCENE_ERRORS(DIRT_SCENE_ERR_ENUM_)
#undef DIRT_SCENE_ERR_ENUM_
    DIRT_SCENE_NUM_ERRORS
};

/* "ok", "JSON nested deeper than the limit", ...; "?" out of range. */
DIRT_API const char *dirt_scene_error_str(enum dirt_scene_error e);
/* "OK", "TOO_DEEP", ...: the id's name (for messages and tests). */
DIRT_API const char *dirt_scene_error_name(enum dirt_scene_error e);

/* The outcome of this thread's last dirt_scene_load / dirt_scene_load_memory /
 * dirt_scene_load_obj_memory:
 * DIRT_SCENE_ERR_OK after a success, else the first reason the load met
 * (the log says more). */
DIRT_API enum dirt_scene_error dirt_scene_last_error(void);

/* Default of dirt_load_opts.max_bytes: 512 MiB for everything a load
 * holds (about 2.4 million glTF triangles with their vertex arrays; an
 * accessor of 2^27 floats with no bufferView is already past it). */
#define DIRT_LOAD_DEFAULT_MAX_BYTES ((size_t)512 << 20)
/* Default of dirt_load_opts.max_depth: JSON nesting of objects and arrays. */
#define DIRT_LOAD_DEFAULT_MAX_DEPTH 128

/* Options for dirt_scene_load. Zero-initialised = defaults. */
typedef struct dirt_load_opts {
    /* The load's memory budget, one for everything it reads and decodes:
     * the files (the scene file, its buffers, images and MTL libraries,
     * each checked against what is left before it is read), the parsers'
     * structures (the glTF JSON's values and objects, counted on the bytes
     * before the parser sees them; tinyobjloader's arrays, from a count of
     * the OBJ's statements), every texture (its declared size checked
     * before decoding) and the scene's own arrays. Each is charged before
     * it is allocated, at the measured cost per byte or element
     * (doc/scenes.md, "Memory"); a load that needs more fails with
     * DIRT_SCENE_ERR_TOO_LARGE. 0 = DIRT_LOAD_DEFAULT_MAX_BYTES. */
    size_t max_bytes;
    /* Deepest nesting of JSON objects/arrays accepted (checked on the bytes
     * before any parser sees them): deeper fails with
     * DIRT_SCENE_ERR_TOO_DEEP. 0 = DIRT_LOAD_DEFAULT_MAX_DEPTH. (glTF only.) */
    int max_depth;
    /* Every warning about the scene (a missing or undecodable texture, an
     * ignored extension or MTL statement, ...) fails the load with
     * DIRT_SCENE_ERR_STRICT after all of them are logged. */
    bool strict;
    /* References (glTF buffer and image URIs, OBJ mtllib, MTL texture maps)
     * may lead outside the scene's folder: by default one that does (an
     * absolute path, "..", a symbolic link out) fails the load with
     * DIRT_SCENE_ERR_OUTSIDE, naming it. */
    bool allow_outside;
} dirt_load_opts;

/* Loads a scene file; the loader is picked by the name's extension: ".obj"
 * (any case) is a Wavefront OBJ with its MTL libraries (mtllib, resolved
 * beside the .obj), ".gltf" and ".glb" glTF 2.0; any other name is glTF
 * when its bytes are (the .glb magic, or a JSON object), else it fails
 * with DIRT_SCENE_ERR_FORMAT. Every file is read only when it is a regular
 * file (a FIFO, device or directory fails at once with NOT_REGULAR) whose
 * size fits what is left of the budget (TOO_LARGE), and every file a
 * scene references must lie in the scene's folder (OUTSIDE; see
 * dirt_load_opts.allow_outside). Returns NULL on failure (unreadable or
 * malformed file: truncated data, out-of-range indices, non-finite
 * positions, nesting or size past the opts' limits, a glTF 1.0 file
 * (VERSION), a glTF extension in extensionsRequired that
 * dirt_scene_gltf_extensions() does not list (DIRT_SCENE_ERR_UNSUPPORTED,
 * the log names it)...) after logging the reason; dirt_scene_last_error()
 * tells the reason's id. Missing or undecodable textures, a missing MTL
 * library, an extension of extensionsUsed that is ignored, or MTL
 * statements without an equivalent only warn (once per load and kind; with
 * dirt_load_opts.strict they fail the load): the material falls back to its
 * factor (a white default texture) or to the default material. An OBJ
 * scene is one node with one static mesh (no cameras, lights or
 * animation); its MTL materials map onto the metallic-roughness model as
 * doc/scenes.md says. Messages name files and quote the names a scene
 * gives (materials, groups, images), never other bytes of a file. `opts`
 * may be NULL. */
DIRT_API dirt_scene *dirt_scene_load(const char *path, const dirt_load_opts *opts);

/* The glTF extensions the loader honours, NULL-terminated, in one list that
 * decides both checks above ("KHR_lights_punctual", ...). */
DIRT_API const char *const *dirt_scene_gltf_extensions(void);

/* Loads a glTF held in memory: `size` bytes of .glb (they start with "glTF")
 * or of .gltf JSON (not necessarily NUL-terminated), whose buffers and images
 * must be embedded (data URIs, or the .glb BIN chunk); an external URI is an
 * error, no file is ever read. `name` labels the data in messages and names
 * the scene (its file stem, as for dirt_scene_load: "room.glb" -> "room").
 * The bytes are not kept: the caller may free them on return. Same failure
 * behaviour as dirt_scene_load; `opts` may be NULL. */
DIRT_API dirt_scene *dirt_scene_load_memory(const void *data, size_t size, const char *name,
                                            const dirt_load_opts *opts);
/* (When `name` ends in ".obj" the bytes are OBJ text, loaded as by
 * dirt_scene_load_obj_memory without MTL text.) */

/* Loads an OBJ held in memory: `obj_size` bytes of OBJ text and, optional
 * (NULL / 0), `mtl_size` bytes of MTL text that stands for the first
 * mtllib statement (without it, mtllib only warns and faces get the default
 * material). Texture maps cannot be read from memory: they warn and the
 * materials keep their factors. `name` as for dirt_scene_load_memory. Same
 * failure behaviour as dirt_scene_load; `opts` may be NULL. */
DIRT_API dirt_scene *dirt_scene_load_obj_memory(const void *obj, size_t obj_size, const void *mtl,
                                                size_t mtl_size, const char *name,
                                                const dirt_load_opts *opts);

/* The project's own default scene, data/default_scene.gltf embedded into the
 * library at build time (nothing is read from disk), named "default": a
 * closed Cornell-style room (red left wall, green right wall, white
 * floor/ceiling/back/front) with boxes and spheres of different materials
 * (diffuse, metal, glossy), lit by an emissive ceiling panel, and one camera
 * inside the room near the front wall looking at the back wall. Never fails
 * except on out-of-memory (NULL, logged). */
DIRT_API dirt_scene *dirt_scene_create_default(void);

DIRT_API void dirt_scene_destroy(dirt_scene *scene);

/* Writes a human-readable summary of the scene to `out` (a FILE *), one
 * labelled line per item with the labels padded to one column: name;
 * triangles; meshes (primitives); nodes; materials; textures; emitters
 * (emissive materials and the triangles that use them, per frame); cameras,
 * then one line each (index, name, type, yfov in degrees and aspect, or
 * xmag/ymag, near/far, node); punctual lights, then one line each (index,
 * name, type, colour, intensity with its unit, range, cone angles); clips,
 * then one line each (index, name, duration, channels, bounds over the clip
 * as dirt_scene_clip_bounds gives them); and the rest pose's bounds.
 * Returns false (logged) on NULL arguments, out-of-memory or a write error.
 * Evaluates the scene (dirt_scene_clip_bounds once per clip). */
DIRT_API bool dirt_scene_print_info(const dirt_scene *scene, void *out);

/* Read-only views into the scene. Pointers are owned by the scene. */
DIRT_API const char *dirt_scene_name(const dirt_scene *scene);
DIRT_API size_t dirt_scene_num_materials(const dirt_scene *scene);
DIRT_API const dirt_material *dirt_scene_materials(const dirt_scene *scene);
/* True when the material emits (max(emissive) * emissive_strength is
 * positive and finite): its triangles are area lights in every engine. */
DIRT_API bool dirt_material_is_emissive(const dirt_material *m);
DIRT_API size_t dirt_scene_num_textures(const dirt_scene *scene);
DIRT_API const dirt_texture *dirt_scene_textures(const dirt_scene *scene);
DIRT_API size_t dirt_scene_num_cameras(const dirt_scene *scene);
DIRT_API const dirt_camera_def *dirt_scene_cameras(const dirt_scene *scene);
DIRT_API size_t dirt_scene_num_lights(const dirt_scene *scene);
DIRT_API const dirt_light_def *dirt_scene_lights(const dirt_scene *scene);
DIRT_API size_t dirt_scene_num_nodes(const dirt_scene *scene);
/* Name of node i ("" when unnamed), NULL when out of range. */
DIRT_API const char *dirt_scene_node_name(const dirt_scene *scene, size_t node);

/* The files the load read, the scene file first, then every buffer,
 * image and MTL library in the order it was read, as the loader opened
 * them (joined to the scene's folder); none for a scene from memory or the
 * default scene. NULL when out of range. Programs keep their outputs apart
 * from these (dirt/input.h). */
DIRT_API size_t dirt_scene_num_files(const dirt_scene *scene);
DIRT_API const char *dirt_scene_file(const dirt_scene *scene, size_t i);

/* Triangles every frame of this scene has. */
DIRT_API size_t dirt_scene_num_triangles(const dirt_scene *scene);

/* Animation clips (glTF animations). */
DIRT_API size_t dirt_scene_num_clips(const dirt_scene *scene);
DIRT_API const char *dirt_scene_clip_name(const dirt_scene *scene, size_t clip);
/* Length of the clip in seconds (largest sampler input time). */
DIRT_API float dirt_scene_clip_duration(const dirt_scene *scene, size_t clip);

/* Options for dirt_scene_evaluate. Zero-initialised = defaults:
 * clip 0 (the first animation, if any), time clamped to the clip. */
typedef struct dirt_eval_opts {
    int clip;           /* clip index; -1 = no animation (rest pose) */
    bool loop;          /* wrap t into [0, duration) instead of clamping */
    bool all_clips;     /* apply every clip at once (ignores `clip`) */
} dirt_eval_opts;

/* A camera evaluated at time t, in world space. */
typedef struct dirt_camera {
    float eye[3];
    float forward[3], up[3], right[3]; /* orthonormal; looks along forward */
    float view[16];     /* world -> eye, column-major, eye looks down -Z */
    enum dirt_camera_type type;
    float yfov;         /* radians */
    float aspect;       /* 0 = use the image's */
    float znear, zfar;
    float xmag, ymag;
    /* Thin lens (0 = pinhole). Not in glTF; set by applications. */
    float aperture_radius, focus_distance;
} dirt_camera;

/* A light evaluated at time t, in world space. */
typedef struct dirt_light {
    enum dirt_light_type type;
    float position[3];
    float direction[3]; /* direction the light shines (directional/spot) */
    float color[3];     /* color * intensity */
    float range;
    float inner_cone, outer_cone;
} dirt_light;

/* The world-space triangle soup of one time step. Arrays hold 3 entries per
 * triangle: vertex v of primitive p is at index 3*p + v. */
typedef struct dirt_frame {
    size_t num_triangles;
    float (*position)[3];
    float (*normal)[3];       /* unit length, world space */
    float (*uv)[2];           /* UV0, (0,0) when the mesh has none */
    float (*tangent)[4];      /* xyz unit world tangent (0 where the mesh has
                                 none), w handedness +1 / -1 (the bitangent is
                                 cross(normal, tangent.xyz) * w); NULL when no
                                 mesh of the scene has tangents */
    uint32_t *material;       /* per triangle, index into the scene's materials */
    uint32_t *instance;       /* per triangle, mesh instance it came from */
    float bounds_min[3], bounds_max[3]; /* of all positions; 0 if no triangles */

    size_t num_nodes;
    float (*node_world)[16];  /* world matrix of every node, column-major */

    size_t num_cameras;
    dirt_camera *cameras;
    size_t num_lights;
    dirt_light *lights;
    float time;               /* the t actually evaluated (after clamp/loop) */
} dirt_frame;

/* Evaluates the scene at time t (seconds). `opts` may be NULL. Returns a new
 * frame owned by the caller (dirt_frame_destroy), or NULL on out-of-memory.
 * Deterministic: the same (scene, t, opts) gives the same bits. */
DIRT_API dirt_frame *dirt_scene_evaluate(const dirt_scene *scene, float t,
                                         const dirt_eval_opts *opts);

/* Re-evaluates into an existing frame of the same scene (no allocation). */
DIRT_API bool dirt_scene_evaluate_into(const dirt_scene *scene, float t,
                                       const dirt_eval_opts *opts, dirt_frame *frame);

DIRT_API void dirt_frame_destroy(dirt_frame *frame);

/* Union of the frame bounds over the animation `opts` selects (NULL = clip
 * 0; see dirt_eval_opts): the frames at t = 0, at every key time of the
 * clip (every clip when all_clips) and at n uniform times i * D / n,
 * i = 1..n, over its duration D (the longest clip's when all_clips), with
 * n = 120 per second of D, at least 64 and at most 2048. With no animation
 * (no clips, clip -1, a clip that does not exist) the rest pose's bounds
 * (opts->loop is honoured, so a looping clip's last instant is its first).
 * Bounds are exact at those times; a frame between two samples lies inside
 * up to the distance a vertex moves in D / n. All 0 when the scene has no
 * triangles. Returns false (logged) on NULL arguments or out-of-memory;
 * deterministic. Cost: up to about 2100 evaluations of the scene. */
DIRT_API bool dirt_scene_clip_bounds(const dirt_scene *scene, const dirt_eval_opts *opts,
                                     float min[3], float max[3]);

/* The automatic camera for an axis-aligned box (min <= max componentwise):
 * a perspective pinhole looking at the box centre from the +Z side, slightly
 * above (direction (0, 0.3, 1) from the centre), 45 degree vertical field of
 * view, at the distance where the box's bounding sphere exactly fits that
 * vertical field of view; near/far planes enclose the sphere. Its aspect is
 * 0, i.e. the image's: with images at least as wide as tall (aspect >= 1)
 * the whole sphere is in view; a portrait image crops its sides. A box with
 * no extent frames a sphere of radius 1 around its centre. Pure function of
 * the six floats: the same box gives the same bits. Pass the bounds of
 * dirt_scene_clip_bounds to frame a whole clip with one camera for every
 * frame (no zoom as objects move). */
DIRT_API void dirt_camera_auto_bounds(const float min[3], const float max[3], dirt_camera *out);

/* dirt_camera_auto_bounds of one frame's bounds (radius-1 sphere at the
 * origin for a NULL frame or one without triangles). Used when the scene has
 * no camera; it follows the frame, so over an animation it zooms as objects
 * move (dirt_scene_clip_bounds + dirt_camera_auto_bounds does not). */
DIRT_API void dirt_camera_auto(const dirt_frame *frame, dirt_camera *out);

/* The camera a frame is seen from by default: its first camera when that is
 * a perspective one, else dirt_camera_auto (the techniques' views need a
 * perspective camera). */
DIRT_API void dirt_camera_default(const dirt_frame *frame, dirt_camera *out);

/* Builds a camera looking from eye at target with the given up vector. */
DIRT_API void dirt_camera_look_at(dirt_camera *cam, const float eye[3],
                                  const float target[3], const float up[3]);

/* A perspective camera given by its pose and lens, as dirt-render's
 * --eye/--look-at/--up/--fov/--znear/--zfar and dirt-view's free camera
 * spell it: the same numbers give the same camera in both. */
typedef struct dirt_camera_look {
    float eye[3], target[3], up[3];
    float fov_deg;              /* vertical field of view in degrees (0 = 45) */
    float znear, zfar;          /* 0 = 1e-3 of |target - eye| / infinite */
} dirt_camera_look;

/* The camera of `look` (pinhole, aspect from the image). */
DIRT_API void dirt_camera_from_look(const dirt_camera_look *look, dirt_camera *out);

/* Column-major projection matrix (OpenGL clip space, -1..1 depth) of the
 * camera for an image of the given aspect (width / height) when the camera
 * has none. Infinite far plane when zfar is 0. */
DIRT_API void dirt_camera_projection(const dirt_camera *cam, float image_aspect,
                                     float out[16]);

#ifdef __cplusplus
}
#endif
#endif
