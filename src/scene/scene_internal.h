/* DIRT engine: scene model internals, shared by the glTF and OBJ loaders
 * (C++) and the animation evaluator (C).
 *
 * Builders (gltf.cpp, obj.cpp) allocate a scene with scene_new(),
 * fill nodes, meshes, skins, materials, textures, camera/light prototypes and
 * clips with malloc'd arrays, then call scene_finalize() with the root nodes
 * of the scene to show. scene_finalize() validates the hierarchy and derives
 * everything the evaluator needs (instances, evaluation order, offsets).
 * dirt_scene_destroy() frees every array below with free(). */
#ifndef DIRT_SCENE_INTERNAL_H
#define DIRT_SCENE_INTERNAL_H

#include "dirt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Upper bound on the vertices, indices or keys of one array, so that every
 * size computation below stays far from overflow. */
#define SCENE_MAX_COUNT ((size_t)1 << 28)

typedef struct scene_node {
    char name[64];
    int parent;              /* -1 for a root (set by scene_finalize) */
    int *children;
    size_t num_children;
    /* Rest pose. When has_matrix is set the node is not animatable and
     * `matrix` (column-major) is its local transform; otherwise T * R * S. */
    float translation[3];
    float rotation[4];       /* quaternion x, y, z, w */
    float scale[3];
    bool has_matrix;
    float matrix[16];
    int mesh, skin, camera, light;  /* -1 when absent; camera/light index the
                                       prototypes */
    float *weights;          /* morph weights of this instance, NULL = mesh's */
    size_t num_weights;
    size_t weight_offset;    /* into the evaluator's per-node weights (finalize) */
} scene_node;

/* One triangle-list primitive. Vertex attributes are per vertex; indices are
 * always present (non-indexed glTF primitives get 0..n-1) and every index is
 * < num_vertices. */
typedef struct scene_prim {
    uint32_t material;           /* index into scene materials */
    size_t num_vertices;
    float (*position)[3];
    float (*normal)[3];          /* NULL: flat normals at evaluation */
    float (*uv)[2];              /* NULL: (0,0) */
    uint16_t (*joints)[4];       /* NULL when the primitive has no skin data */
    float (*weights)[4];         /* sum to 1 (normalised at load) */
    size_t num_targets;          /* morph targets */
    float (*target_position)[3]; /* num_targets * num_vertices deltas,
                                    target-major, NULL if no target has one */
    float (*target_normal)[3];   /* same layout, NULL if none */
    float (*tangent)[4];         /* TANGENT: xyz unit (or 0 where degenerate),
                                    w handedness +1 / -1; from the file or
                                    scene_prim_generate_tangents. NULL: none */
    float (*target_tangent)[3];  /* morph deltas of tangent.xyz, the layout of
                                    target_normal, NULL if none */
    size_t num_triangles;
    uint32_t *indices;           /* 3 * num_triangles */
} scene_prim;

typedef struct scene_mesh {
    char name[64];
    scene_prim *prims;
    size_t num_prims;
    float *weights;              /* default morph weights, num_weights long */
    size_t num_weights;          /* max num_targets over the primitives */
    size_t num_triangles;        /* sum over the primitives */
} scene_mesh;

typedef struct scene_skin {
    int *joints;                 /* node indices */
    float (*inverse_bind)[16];   /* one per joint, column-major */
    size_t num_joints;
    size_t joint_offset;         /* into the evaluator's joint matrices */
} scene_skin;

enum scene_path {
    SCENE_PATH_TRANSLATION = 0,
    SCENE_PATH_ROTATION = 1,
    SCENE_PATH_SCALE = 2,
    SCENE_PATH_WEIGHTS = 3,
};

enum scene_interp {
    SCENE_INTERP_STEP = 0,
    SCENE_INTERP_LINEAR = 1,
    SCENE_INTERP_CUBIC = 2,
};

/* Keyframes. `values` holds num_keys elements of `width` floats, or for
 * cubic splines num_keys triples (in-tangent, value, out-tangent) of
 * elements. Times are finite and non-decreasing. */
typedef struct scene_sampler {
    enum scene_interp interp;
    size_t num_keys;
    float *times;
    size_t width;
    float *values;
} scene_sampler;

typedef struct scene_channel {
    int node;
    enum scene_path path;
    int sampler;                 /* index into the clip's samplers */
} scene_channel;

typedef struct scene_clip {
    char name[64];
    scene_channel *channels;
    size_t num_channels;
    scene_sampler *samplers;
    size_t num_samplers;
    float duration;              /* largest key time */
} scene_clip;

/* A node carrying a mesh, reached from the scene roots. */
typedef struct scene_instance {
    int node;
    int mesh;
    int skin;                    /* -1 = rigid */
    size_t first_triangle;       /* primitive id of its first triangle */
} scene_instance;

/* Counters gathered while loading (for diagnostics and tests). */
typedef struct scene_load_stats {
    size_t weights_normalized;   /* vertices whose WEIGHTS_0 summed to a value
                                    farther than 1e-6 from 1 */
    size_t textures_failed;      /* referenced images missing/undecodable */
    size_t prims_skipped;        /* point/line primitives, or no POSITION */
    size_t zero_area;            /* instanced triangles of zero area in the rest
                                    pose (scene_finalize) */
} scene_load_stats;

struct dirt_scene {
    char name[256];

    scene_node *nodes;
    size_t num_nodes;
    scene_mesh *meshes;
    size_t num_meshes;
    scene_skin *skins;
    size_t num_skins;
    dirt_material *materials;
    size_t num_materials;
    dirt_texture *textures;
    size_t num_textures;
    dirt_camera_def *camera_protos; /* as in the file; node = -1 */
    size_t num_camera_protos;
    dirt_light_def *light_protos;
    size_t num_light_protos;
    scene_clip *clips;
    size_t num_clips;

    /* Derived by scene_finalize. */
    int *roots;                  /* the shown scene's root nodes, in order */
    size_t num_roots;
    int *eval_order;             /* every node, parents before children */
    scene_instance *instances;   /* depth-first over roots, pre-order */
    size_t num_instances;
    dirt_camera_def *cameras;    /* one per camera node, depth-first */
    size_t num_cameras;
    dirt_light_def *lights;      /* one per light node, depth-first */
    size_t num_lights;
    size_t num_triangles;
    size_t total_weights;        /* sum of mesh num_weights over mesh nodes */
    size_t total_joints;         /* sum of skin joints */
    size_t max_prim_vertices;

    scene_load_stats stats;

    char **files;                /* dirt_scene_file: read by the load */
    size_t num_files;
};

/* A zeroed scene with the given name, NULL (logged) on out-of-memory. */
dirt_scene *scene_new(const char *name);

/* Validates the node graph (child indices in range, at most one parent per
 * node, no cycles), the references of nodes (mesh, skin, camera, light),
 * skins (joint indices) and skinned instances (JOINTS_0 < joint count), then
 * derives the fields marked "derived" above. `roots` are the nodes of the
 * scene to show; NULL with num_roots 0 means every parentless node. Returns
 * false (logged) on an invalid scene. */
bool scene_finalize(dirt_scene *scene, const int *roots, size_t num_roots);

/* Makes p->tangent (which must be NULL) for a normal map when the file
 * gives none: per vertex, the sum over its triangles of the UV-derivative
 * tangent T = (e1 dv2 - e2 dv1) / r and bitangent B = (e2 du1 - e1 du2) / r
 * (e = edges from the first corner, (du, dv) their UV differences, r = du1
 * dv2 - du2 dv1; triangles with r 0 or not finite add nothing), summed in
 * double; then t = normalize(T - n (n . T)) with n the vertex normal (the
 * sum of the adjacent triangles' cross(e1, e2) when the primitive has no
 * normals), w = dot(cross(n, t), B) < 0 ? -1 : 1; a vertex where t is 0
 * or not finite gets (0, 0, 0, 1) (no normal map there). Nothing to do
 * (true, tangent stays NULL) without UVs or vertices. False (logged) on
 * out-of-memory. doc/light-transport.md, "Normal maps". */
bool scene_prim_generate_tangents(scene_prim *p);

/* Copies `src` into a fixed-size name field, truncating, always terminated. */
void scene_copy_name(char *dst, size_t size, const char *src);

/* Records why this thread's current load fails: the first id recorded since
 * scene_error_reset() wins (later, more general messages keep it). */
void scene_set_error(enum dirt_scene_error e);
/* Logs an error and records its id: SCENE_FAIL(RANGE, "fmt", ...). */
#define SCENE_FAIL(id, ...) (scene_set_error(DIRT_SCENE_ERR_##id), DIRT_ERROR(__VA_ARGS__))
void scene_error_reset(void);
enum dirt_scene_error scene_error_get(void);

/* ---- the load in progress on this thread (scene.c) ----------------------
 * dirt_scene_load* begin it (scene_load_begin) and end it
 * (scene_load_end); the loaders read files, charge the budget and warn
 * through it. */

/* Starts a load with `opts` (defaults filled in; copied) and `dir`, the
 * folder its references resolve in and must stay in (NULL for a scene
 * from memory: no file is read). Sets the budget to opts->max_bytes. */
void scene_load_begin(const dirt_load_opts *opts, const char *dir);
/* The options of the load in progress. */
const dirt_load_opts *scene_load_opts(void);

/* Charges `count` x `each` bytes to the budget (overflow-safe); false
 * (logged with `what`, TOO_LARGE) when they do not fit. */
bool scene_charge(size_t count, size_t each, const char *what);
/* Gives back a part of an earlier charge (a decoder's working memory, once
 * freed). */
void scene_refund(size_t count, size_t each);
/* Whether `count` x `each` bytes fit in what is left (nothing charged). */
bool scene_budget_fits(size_t count, size_t each);
size_t scene_budget_left(void);
/* The most the load in progress (or the last one) had charged at once: a
 * bound on the memory it held (test scene_memory). */
size_t scene_budget_peak(void);

/* A warning about the scene: logged and counted (a strict load fails at
 * its end when any was given). */
void scene_count_warning(void);
#define SCENE_WARN(...) (scene_count_warning(), DIRT_WARN(__VA_ARGS__))

/* Reads the scene file `path` itself (dirt/input.h: a regular file, its
 * size within the budget, charged `copies` times: the bytes and what the
 * parser copies of them). NULL after logging (IO, EMPTY, NOT_REGULAR,
 * TOO_LARGE); the data is NUL-terminated, free() it. */
unsigned char *scene_read_scene_file(const char *path, size_t copies, size_t *size);

/* Reads a file the scene references: `ref` as the scene writes it (quoted
 * in messages), `path` that reference resolved against the load's folder,
 * `what` its role ("buffer", "image", "mtllib"). The path must stay in the
 * folder (unless opts.allow_outside; else OUTSIDE), be a regular file
 * (NOT_REGULAR) whose size, times `copies`, fits the budget (TOO_LARGE);
 * it is then charged and recorded (dirt_scene_file). A file that does not
 * exist returns NULL with *missing set and nothing logged (the caller fails
 * or warns); other failures are logged with their id. NUL-terminated,
 * free() it. */
unsigned char *scene_read_ref_file(const char *path, const char *ref, const char *what,
                                   size_t copies, size_t *size, bool *missing);

/* Ends the load: a failed load (`s` NULL) gets an id (INVALID when no site
 * named one); a strict load with warnings fails (STRICT, `s` destroyed);
 * a successful one takes the list of files read. Returns the scene or
 * NULL. */
dirt_scene *scene_load_end(dirt_scene *s);

/* Reads a .gltf or .glb file into a finalized scene, NULL (logged, id
 * recorded by scene_set_error) on error; inside a load begun by
 * scene_load_begin. `opts` is never NULL and has its defaults filled in
 * (max_bytes, max_depth > 0). */
dirt_scene *scene_load_gltf(const char *path, const dirt_load_opts *opts);

/* The same from `size` bytes in memory (.glb when they start with "glTF",
 * else .gltf JSON); `label` names them in messages and its file stem names
 * the scene. External URIs are refused (an error), never read. */
dirt_scene *scene_load_gltf_memory(const void *data, size_t size, const char *label,
                                   const dirt_load_opts *opts);

/* Reads an OBJ file (and the MTL libraries it names, beside it) into a
 * finalized scene: one node, one mesh with a primitive per run of faces of
 * one material, in file order. NULL (logged, id recorded) on error. */
dirt_scene *scene_load_obj(const char *path, const dirt_load_opts *opts);

/* The same from memory: `mtl` (may be NULL) stands for the first mtllib;
 * nothing is read from files (texture maps warn). */
dirt_scene *scene_load_obj_memory(const void *obj, size_t obj_size, const void *mtl,
                                  size_t mtl_size, const char *label,
                                  const dirt_load_opts *opts);

/* data/default_scene.gltf, embedded at build time (generated by embed.c). */
extern const unsigned char scene_default_gltf[];
extern const size_t scene_default_gltf_size;

/* Column-major 4x4 helpers shared by the evaluator and the builders. */
void scene_mat4_identity(float m[16]);
void scene_mat4_mul(float out[16], const float a[16], const float b[16]);
void scene_mat4_from_trs(float out[16], const float t[3], const float q[4],
                         const float s[3]);

/* Sets forward (normalised `fwd`), right, up (orthonormalised against
 * `up_hint`) and the view matrix of `cam` from its eye. Degenerate inputs
 * fall back to -Z forward / any perpendicular up. */
void scene_camera_set_basis(dirt_camera *cam, const float fwd[3],
                            const float up_hint[3]);

#ifdef __cplusplus
}
#endif
#endif
