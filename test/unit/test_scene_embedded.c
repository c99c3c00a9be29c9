/* The embedded default scene (data/default_scene.gltf, loaded through
 * dirt_scene_load_memory) is exactly the scene the engine used to build in C:
 * the procedural construction that src/scene/default_scene.c held before the
 * scene became a file is kept below, unchanged, as the oracle, and every
 * field that reaches a technique (vertices, indices, materials, nodes,
 * cameras, lights, the evaluated frame) must match it bit for bit. Also
 * checks dirt_scene_load_memory's contract: .gltf and .glb from memory, the
 * scene name, refused external references and bad input. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/log.h"
#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- oracle: the former C construction of the default scene ------------- */

/* Growable vertex/index arrays of one primitive under construction. */
typedef struct builder {
    float (*pos)[3];
    float (*nrm)[3];
    float (*uv)[2];
    size_t nv, cap_v;
    uint32_t *idx;
    size_t ni, cap_i;
    bool oom;
} builder;

static bool reserve(builder *b, size_t nv, size_t ni)
{
    if (b->oom)
        return false;
    if (b->nv + nv > b->cap_v) {
        size_t cap = (b->nv + nv) * 2;
        float (*p)[3] = realloc(b->pos, cap * sizeof(*p));
        if (p)
            b->pos = p;
        float (*n)[3] = realloc(b->nrm, cap * sizeof(*n));
        if (n)
            b->nrm = n;
        float (*t)[2] = realloc(b->uv, cap * sizeof(*t));
        if (t)
            b->uv = t;
        if (!p || !n || !t) {
            b->oom = true;
            return false;
        }
        b->cap_v = cap;
    }
    if (b->ni + ni > b->cap_i) {
        size_t cap = (b->ni + ni) * 2;
        uint32_t *i = realloc(b->idx, cap * sizeof(*i));
        if (!i) {
            b->oom = true;
            return false;
        }
        b->idx = i;
        b->cap_i = cap;
    }
    return true;
}

static uint32_t add_vertex(builder *b, const float p[3], const float n[3], float u, float v)
{
    uint32_t i = (uint32_t)b->nv++;
    memcpy(b->pos[i], p, sizeof(b->pos[i]));
    memcpy(b->nrm[i], n, sizeof(b->nrm[i]));
    b->uv[i][0] = u;
    b->uv[i][1] = v;
    return i;
}

static void add_triangle(builder *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
    b->idx[b->ni++] = i0;
    b->idx[b->ni++] = i1;
    b->idx[b->ni++] = i2;
}

/* Quad o, o+u, o+u+v, o+v facing along u x v (counter-clockwise seen from
 * that side). */
static void add_quad(builder *b, const float o[3], const float u[3], const float v[3])
{
    if (!reserve(b, 4, 6))
        return;
    float n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                  u[0] * v[1] - u[1] * v[0]};
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= l;
    float p1[3], p2[3], p3[3];
    for (int k = 0; k < 3; k++) {
        p1[k] = o[k] + u[k];
        p2[k] = o[k] + u[k] + v[k];
        p3[k] = o[k] + v[k];
    }
    uint32_t i0 = add_vertex(b, o, n, 0.0f, 0.0f);
    uint32_t i1 = add_vertex(b, p1, n, 1.0f, 0.0f);
    uint32_t i2 = add_vertex(b, p2, n, 1.0f, 1.0f);
    uint32_t i3 = add_vertex(b, p3, n, 0.0f, 1.0f);
    add_triangle(b, i0, i1, i2);
    add_triangle(b, i0, i2, i3);
}

/* Axis-aligned unit cube [-0.5, 0.5]^3, faces outward. */
static void add_cube(builder *b)
{
    static const float faces[6][3][3] = {
        {{0.5f, -0.5f, -0.5f}, {0, 1, 0}, {0, 0, 1}},   /* +x */
        {{-0.5f, -0.5f, -0.5f}, {0, 0, 1}, {0, 1, 0}},  /* -x */
        {{-0.5f, 0.5f, -0.5f}, {0, 0, 1}, {1, 0, 0}},   /* +y */
        {{-0.5f, -0.5f, -0.5f}, {1, 0, 0}, {0, 0, 1}},  /* -y */
        {{-0.5f, -0.5f, 0.5f}, {1, 0, 0}, {0, 1, 0}},   /* +z */
        {{-0.5f, -0.5f, -0.5f}, {0, 1, 0}, {1, 0, 0}},  /* -z */
    };
    for (int f = 0; f < 6; f++)
        add_quad(b, faces[f][0], faces[f][1], faces[f][2]);
}

/* Unit UV sphere, `slices` around y, `stacks` from pole to pole, outward
 * winding, smooth normals; no degenerate pole triangles. */
static void add_sphere(builder *b, int slices, int stacks)
{
    const float pi = 3.14159265358979f;
    size_t nv = (size_t)(slices + 1) * (size_t)(stacks + 1);
    if (!reserve(b, nv, (size_t)slices * (size_t)stacks * 6))
        return;
    uint32_t base = (uint32_t)b->nv;
    for (int i = 0; i <= stacks; i++) {
        float theta = pi * (float)i / (float)stacks;
        for (int j = 0; j <= slices; j++) {
            float phi = 2.0f * pi * (float)j / (float)slices;
            float p[3] = {sinf(theta) * cosf(phi), cosf(theta), -sinf(theta) * sinf(phi)};
            add_vertex(b, p, p, (float)j / (float)slices, (float)i / (float)stacks);
        }
    }
    for (int i = 0; i < stacks; i++) {
        for (int j = 0; j < slices; j++) {
            uint32_t a = base + (uint32_t)(i * (slices + 1) + j);
            uint32_t c = a + (uint32_t)(slices + 1);
            /* Ring i is above ring i+1; phi grows counter-clockwise seen from
             * +y, so (a, c, c+1) faces outward. */
            if (i != stacks - 1) /* (c, c+1) collapse at the south pole */
                add_triangle(b, a, c, c + 1);
            if (i != 0) /* (a, a+1) collapse at the north pole */
                add_triangle(b, a, c + 1, a + 1);
        }
    }
}

/* Moves the builder's arrays into `p`. */
static bool finish_prim(builder *b, uint32_t material, scene_prim *p)
{
    if (b->oom) {
        free(b->pos);
        free(b->nrm);
        free(b->uv);
        free(b->idx);
        memset(b, 0, sizeof(*b));
        return false;
    }
    p->material = material;
    p->num_vertices = b->nv;
    p->position = b->pos;
    p->normal = b->nrm;
    p->uv = b->uv;
    p->num_triangles = b->ni / 3;
    p->indices = b->idx;
    memset(b, 0, sizeof(*b));
    return true;
}

enum { MAT_WHITE, MAT_RED, MAT_GREEN, MAT_LIGHT, MAT_METAL, MAT_GLOSSY, NUM_MATERIALS };

static void set_material(dirt_material *m, const char *name, float r, float g, float b,
                         float metallic, float roughness)
{
    dirt_material_default(m); /* the glTF defaults of every other field */
    scene_copy_name(m->name, sizeof(m->name), name);
    m->base_color[0] = r;
    m->base_color[1] = g;
    m->base_color[2] = b;
    m->base_color[3] = 1.0f;
    m->base_color_tex = DIRT_NO_TEXTURE;
    m->metallic = metallic;
    m->roughness = roughness;
    m->metallic_roughness_tex = DIRT_NO_TEXTURE;
    m->emissive_strength = 1.0f;
    m->emissive_tex = DIRT_NO_TEXTURE;
}

static bool build_room(scene_mesh *mesh)
{
    /* Walls face inward: each quad's u x v points into the room. */
    static const float white[4][3][3] = {
        {{-1, 0, -1}, {0, 0, 2}, {2, 0, 0}}, /* floor, +y */
        {{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}}, /* ceiling, -y */
        {{-1, 0, -1}, {2, 0, 0}, {0, 2, 0}}, /* back wall z=-1, +z */
        {{-1, 0, 1}, {0, 2, 0}, {2, 0, 0}},  /* front wall z=+1, -z */
    };
    static const float red[3][3] = {{-1, 0, -1}, {0, 2, 0}, {0, 0, 2}};  /* x=-1, +x */
    static const float green[3][3] = {{1, 0, -1}, {0, 0, 2}, {0, 2, 0}}; /* x=+1, -x */
    builder b = {0};
    scene_copy_name(mesh->name, sizeof(mesh->name), "room");
    for (int i = 0; i < 4; i++)
        add_quad(&b, white[i][0], white[i][1], white[i][2]);
    if (!finish_prim(&b, MAT_WHITE, &mesh->prims[mesh->num_prims]))
        return false;
    mesh->num_prims++;
    add_quad(&b, red[0], red[1], red[2]);
    if (!finish_prim(&b, MAT_RED, &mesh->prims[mesh->num_prims]))
        return false;
    mesh->num_prims++;
    add_quad(&b, green[0], green[1], green[2]);
    if (!finish_prim(&b, MAT_GREEN, &mesh->prims[mesh->num_prims]))
        return false;
    mesh->num_prims++;
    return true;
}

static bool build_single(scene_mesh *mesh, const char *name, uint32_t material, int shape)
{
    builder b = {0};
    scene_copy_name(mesh->name, sizeof(mesh->name), name);
    if (shape == 0) {
        /* Ceiling light: 0.5 x 0.5 quad just below the ceiling, facing down,
         * centred at (0, 1.98, -0.3): above the objects and, unlike the
         * ceiling's centre, inside the camera's view. */
        static const float o[3] = {-0.25f, 1.98f, -0.55f}, u[3] = {0.5f, 0, 0},
                           v[3] = {0, 0, 0.5f};
        add_quad(&b, o, u, v);
    } else if (shape == 1) {
        add_cube(&b);
    } else {
        add_sphere(&b, 24, 16);
    }
    if (!finish_prim(&b, material, &mesh->prims[0]))
        return false;
    mesh->num_prims = 1;
    return true;
}

static void set_node(scene_node *n, const char *name, int mesh, const float t[3],
                     float yaw_deg, const float s[3])
{
    float half = 0.5f * yaw_deg * 3.14159265358979f / 180.0f;
    scene_copy_name(n->name, sizeof(n->name), name);
    n->parent = -1;
    n->mesh = mesh;
    n->skin = -1;
    n->camera = -1;
    n->light = -1;
    memcpy(n->translation, t, sizeof(n->translation));
    n->rotation[0] = 0.0f;
    n->rotation[1] = sinf(half);
    n->rotation[2] = 0.0f;
    n->rotation[3] = cosf(half);
    memcpy(n->scale, s, sizeof(n->scale));
}

static dirt_scene *oracle_create_default(void)
{
    enum { NUM_MESHES = 6, NUM_NODES = 7 };
    dirt_scene *s = scene_new("default");
    if (!s)
        return NULL;

    s->materials = calloc(NUM_MATERIALS, sizeof(*s->materials));
    s->meshes = calloc(NUM_MESHES, sizeof(*s->meshes));
    s->nodes = calloc(NUM_NODES, sizeof(*s->nodes));
    s->camera_protos = calloc(1, sizeof(*s->camera_protos));
    if (!s->materials || !s->meshes || !s->nodes || !s->camera_protos)
        goto oom;
    s->num_materials = NUM_MATERIALS;
    s->num_meshes = NUM_MESHES;
    s->num_nodes = NUM_NODES;
    s->num_camera_protos = 1;

    set_material(&s->materials[MAT_WHITE], "white", 0.73f, 0.73f, 0.73f, 0.0f, 1.0f);
    set_material(&s->materials[MAT_RED], "red", 0.63f, 0.065f, 0.05f, 0.0f, 1.0f);
    set_material(&s->materials[MAT_GREEN], "green", 0.14f, 0.45f, 0.091f, 0.0f, 1.0f);
    set_material(&s->materials[MAT_LIGHT], "light", 1.0f, 1.0f, 1.0f, 0.0f, 1.0f);
    /* Warm light: emissive * strength = (17, 12, 4). */
    s->materials[MAT_LIGHT].emissive[0] = 1.0f;
    s->materials[MAT_LIGHT].emissive[1] = 12.0f / 17.0f;
    s->materials[MAT_LIGHT].emissive[2] = 4.0f / 17.0f;
    s->materials[MAT_LIGHT].emissive_strength = 17.0f;
    set_material(&s->materials[MAT_METAL], "metal", 0.95f, 0.93f, 0.88f, 1.0f, 0.05f);
    set_material(&s->materials[MAT_GLOSSY], "glossy_blue", 0.1f, 0.25f, 0.8f, 0.0f, 0.3f);

    static const int prims_per_mesh[NUM_MESHES] = {3, 1, 1, 1, 1, 1};
    for (int i = 0; i < NUM_MESHES; i++) {
        s->meshes[i].prims = calloc((size_t)prims_per_mesh[i], sizeof(scene_prim));
        if (!s->meshes[i].prims)
            goto oom;
    }
    if (!build_room(&s->meshes[0]) ||
        !build_single(&s->meshes[1], "light", MAT_LIGHT, 0) ||
        !build_single(&s->meshes[2], "tall_box", MAT_WHITE, 1) ||
        !build_single(&s->meshes[3], "short_box", MAT_WHITE, 1) ||
        !build_single(&s->meshes[4], "metal_sphere", MAT_METAL, 2) ||
        !build_single(&s->meshes[5], "glossy_sphere", MAT_GLOSSY, 2))
        goto oom;
    for (int i = 0; i < NUM_MESHES; i++) {
        for (size_t p = 0; p < s->meshes[i].num_prims; p++)
            s->meshes[i].num_triangles += s->meshes[i].prims[p].num_triangles;
    }

    static const float zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    set_node(&s->nodes[0], "room", 0, zero, 0.0f, one);
    set_node(&s->nodes[1], "light", 1, zero, 0.0f, one);
    /* Objects sit in the back half of the room: from a camera at the front
     * wall at eye height the floor near the camera is out of view. */
    set_node(&s->nodes[2], "tall_box", 2, (const float[3]){-0.35f, 0.6f, -0.45f}, 20.0f,
             (const float[3]){0.55f, 1.2f, 0.55f});
    set_node(&s->nodes[3], "short_box", 3, (const float[3]){0.4f, 0.275f, -0.15f}, -18.0f,
             (const float[3]){0.55f, 0.55f, 0.55f});
    set_node(&s->nodes[4], "metal_sphere", 4, (const float[3]){0.4f, 0.77f, -0.15f}, 0.0f,
             (const float[3]){0.22f, 0.22f, 0.22f});
    set_node(&s->nodes[5], "glossy_sphere", 5, (const float[3]){0.5f, 0.2f, -0.75f}, 0.0f,
             (const float[3]){0.2f, 0.2f, 0.2f});
    /* The camera at the front wall looks down its local -Z towards the back
     * wall, pitched up by atan(0.2 / 1.95) (it looks at (0, 1.2, -1)) so
     * that with a 70 degree field of view the whole back wall, both side
     * walls and the ceiling light are in view. */
    set_node(&s->nodes[6], "camera", -1, (const float[3]){0.0f, 1.0f, 0.95f}, 0.0f, one);
    {
        float half = 0.5f * atanf(0.2f / 1.95f); /* about +x: -Z tilts up */
        s->nodes[6].rotation[0] = sinf(half);
        s->nodes[6].rotation[1] = 0.0f;
        s->nodes[6].rotation[2] = 0.0f;
        s->nodes[6].rotation[3] = cosf(half);
    }
    s->nodes[6].camera = 0;

    dirt_camera_def *cam = &s->camera_protos[0];
    scene_copy_name(cam->name, sizeof(cam->name), "default");
    cam->type = DIRT_CAMERA_PERSPECTIVE;
    cam->yfov = 70.0f * 3.14159265358979f / 180.0f;
    cam->aspect = 0.0f;
    cam->znear = 0.01f;
    cam->zfar = 100.0f;
    cam->node = -1;

    if (!scene_finalize(s, NULL, 0)) {
        DIRT_ERROR("default scene failed validation");
        dirt_scene_destroy(s);
        return NULL;
    }
    return s;

oom:
    DIRT_ERROR("out of memory building the default scene");
    dirt_scene_destroy(s);
    return NULL;
}

/* ---- comparison ---------------------------------------------------------- */

#define SAME(what, a, b, n) CHECK_MSG(memcmp((a), (b), (n)) == 0, "%s differs", what)

static void compare_scenes(const dirt_scene *a, const dirt_scene *b)
{
    CHECK(strcmp(a->name, b->name) == 0);
    CHECK(a->num_nodes == b->num_nodes);
    CHECK(a->num_meshes == b->num_meshes);
    CHECK(a->num_materials == b->num_materials);
    CHECK(a->num_textures == b->num_textures);
    CHECK(a->num_camera_protos == b->num_camera_protos);
    CHECK(a->num_light_protos == b->num_light_protos);
    CHECK(a->num_clips == b->num_clips);
    CHECK(a->num_skins == b->num_skins);
    CHECK(a->num_roots == b->num_roots);
    CHECK(a->num_instances == b->num_instances);
    CHECK(a->num_cameras == b->num_cameras);
    CHECK(a->num_lights == b->num_lights);
    CHECK(a->num_triangles == b->num_triangles);
    if (a->num_nodes != b->num_nodes || a->num_meshes != b->num_meshes ||
        a->num_materials != b->num_materials || a->num_cameras != b->num_cameras ||
        a->num_camera_protos != b->num_camera_protos || a->num_lights != b->num_lights ||
        a->num_instances != b->num_instances || a->num_roots != b->num_roots)
        return;

    for (size_t n = 0; n < a->num_nodes; n++) {
        const scene_node *x = &a->nodes[n], *y = &b->nodes[n];
        CHECK_MSG(strcmp(x->name, y->name) == 0, "node %zu: '%s' vs '%s'", n, x->name,
                  y->name);
        SAME("node translation", x->translation, y->translation, sizeof(x->translation));
        SAME("node rotation", x->rotation, y->rotation, sizeof(x->rotation));
        SAME("node scale", x->scale, y->scale, sizeof(x->scale));
        CHECK(x->has_matrix == y->has_matrix);
        CHECK(x->parent == y->parent && x->num_children == y->num_children);
        CHECK(x->mesh == y->mesh && x->skin == y->skin);
        CHECK(x->camera == y->camera && x->light == y->light);
        CHECK(x->num_weights == y->num_weights);
    }
    for (size_t m = 0; m < a->num_meshes; m++) {
        const scene_mesh *x = &a->meshes[m], *y = &b->meshes[m];
        CHECK_MSG(strcmp(x->name, y->name) == 0, "mesh %zu: '%s' vs '%s'", m, x->name,
                  y->name);
        CHECK(x->num_prims == y->num_prims && x->num_triangles == y->num_triangles);
        CHECK(x->num_weights == y->num_weights);
        for (size_t p = 0; p < x->num_prims && p < y->num_prims; p++) {
            const scene_prim *u = &x->prims[p], *v = &y->prims[p];
            CHECK(u->material == v->material);
            CHECK(u->num_vertices == v->num_vertices);
            CHECK(u->num_triangles == v->num_triangles);
            CHECK(u->num_targets == v->num_targets && !v->target_position);
            CHECK(!v->joints && !v->weights);
            CHECK(v->normal != NULL && v->uv != NULL);
            if (u->num_vertices != v->num_vertices || u->num_triangles != v->num_triangles ||
                !v->normal || !v->uv)
                continue;
            SAME("positions", u->position, v->position, u->num_vertices * sizeof(*u->position));
            SAME("normals", u->normal, v->normal, u->num_vertices * sizeof(*u->normal));
            SAME("uvs", u->uv, v->uv, u->num_vertices * sizeof(*u->uv));
            SAME("indices", u->indices, v->indices, u->num_triangles * 3 * sizeof(uint32_t));
        }
    }
    /* Whole structs: names, factors, texture slots, flags (both calloc'd, so
     * padding is zero too). */
    SAME("materials", a->materials, b->materials, a->num_materials * sizeof(dirt_material));
    SAME("camera prototypes", a->camera_protos, b->camera_protos,
         a->num_camera_protos * sizeof(dirt_camera_def));
    SAME("cameras", a->cameras, b->cameras, a->num_cameras * sizeof(dirt_camera_def));
    SAME("lights", a->lights, b->lights, a->num_lights * sizeof(dirt_light_def));
    SAME("roots", a->roots, b->roots, a->num_roots * sizeof(int));
    SAME("instances", a->instances, b->instances, a->num_instances * sizeof(scene_instance));
    SAME("evaluation order", a->eval_order, b->eval_order, a->num_nodes * sizeof(int));
}

static void compare_frames(const dirt_frame *a, const dirt_frame *b)
{
    CHECK(a->num_triangles == b->num_triangles);
    CHECK(a->num_nodes == b->num_nodes);
    CHECK(a->num_cameras == b->num_cameras && a->num_lights == b->num_lights);
    if (a->num_triangles != b->num_triangles || a->num_nodes != b->num_nodes ||
        a->num_cameras != b->num_cameras || a->num_lights != b->num_lights)
        return;
    size_t nv = 3 * a->num_triangles;
    size_t bad = 0;
    for (size_t i = 0; i < nv; i++) {
        bad += memcmp(a->position[i], b->position[i], sizeof(a->position[i])) != 0;
        bad += memcmp(a->normal[i], b->normal[i], sizeof(a->normal[i])) != 0;
        bad += memcmp(a->uv[i], b->uv[i], sizeof(a->uv[i])) != 0;
    }
    CHECK_MSG(bad == 0, "%zu vertex attributes differ", bad);
    SAME("triangle materials", a->material, b->material, a->num_triangles * sizeof(uint32_t));
    SAME("triangle instances", a->instance, b->instance, a->num_triangles * sizeof(uint32_t));
    SAME("bounds min", a->bounds_min, b->bounds_min, sizeof(a->bounds_min));
    SAME("bounds max", a->bounds_max, b->bounds_max, sizeof(a->bounds_max));
    SAME("node matrices", a->node_world, b->node_world, a->num_nodes * sizeof(*a->node_world));
    SAME("frame cameras", a->cameras, b->cameras, a->num_cameras * sizeof(dirt_camera));
    SAME("frame lights", a->lights, b->lights, a->num_lights * sizeof(dirt_light));
}

/* ---- dirt_scene_load_memory contract -------------------------------------- */

static void check_load_memory(const dirt_scene *oracle)
{
    /* The embedded bytes are the JSON of data/default_scene.gltf; the same
     * model as a .glb (JSON chunk, no BIN) loads the same scene. */
    uint8_t *glb = NULL;
    char *json = malloc(scene_default_gltf_size + 1);
    CHECK(json != NULL);
    if (!json)
        return;
    memcpy(json, scene_default_gltf, scene_default_gltf_size);
    json[scene_default_gltf_size] = '\0';
    size_t glb_size = make_glb(json, NULL, 0, &glb);
    dirt_scene *g = dirt_scene_load_memory(glb, glb_size, "room.glb", NULL);
    CHECK(g != NULL);
    if (g) {
        CHECK(strcmp(dirt_scene_name(g), "room") == 0);
        CHECK(dirt_scene_num_triangles(g) == dirt_scene_num_triangles(oracle));
        dirt_scene_destroy(g);
    }
    free(glb);
    free(json);

    /* Not NUL-terminated: loading the first n bytes only must not read past
     * them (a truncated JSON is an error, not a crash). */
    log_capture_start();
    dirt_scene *t = dirt_scene_load_memory(scene_default_gltf, scene_default_gltf_size / 2,
                                           "half.gltf", NULL);
    CHECK(t == NULL);
    CHECK(log_errors_ > 0);

    /* An external buffer is refused: nothing is read from disk, even when
     * the file exists in the working directory. */
    const char *ext_json =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36,"
        "\"uri\":\"tri.bin\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
        "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    write_bytes("tri.bin", tri, sizeof(tri));
    log_capture_start();
    t = dirt_scene_load_memory(ext_json, strlen(ext_json), "external.gltf", NULL);
    CHECK(t == NULL);
    CHECK(log_errors_ > 0);
    dirt_scene_destroy(t);
    remove("tri.bin");
    /* The same file from disk next to tri.bin does load (the reference is
     * valid; only memory loads refuse it). */
    write_bytes(tmp_file("tri.bin"), tri, sizeof(tri));
    write_text(tmp_file("external.gltf"), ext_json);
    log_capture_start();
    t = dirt_scene_load(tmp_file("external.gltf"), NULL);
    CHECK(t != NULL && dirt_scene_num_triangles(t) == 1);
    CHECK(log_errors_ == 0);
    dirt_scene_destroy(t);

    /* Empty, missing or garbage data: NULL and a logged error. */
    log_capture_start();
    CHECK(dirt_scene_load_memory(NULL, 0, "empty", NULL) == NULL);
    CHECK(dirt_scene_load_memory(NULL, 10, "null", NULL) == NULL);
    CHECK(dirt_scene_load_memory("glTF", 4, "short.glb", NULL) == NULL);
    CHECK(dirt_scene_load_memory("{not json", 9, NULL, NULL) == NULL);
    CHECK(log_errors_ >= 4);
    dirt_log_set_callback(NULL, NULL);

    static const char *const names[] = {"tri.bin", "external.gltf"};
    tmp_cleanup(names, 2);
}

int main(void)
{
    dirt_scene *oracle = oracle_create_default();
    dirt_scene *s = dirt_scene_create_default();
    CHECK(oracle != NULL);
    CHECK(s != NULL);
    if (!oracle || !s) {
        dirt_scene_destroy(oracle);
        dirt_scene_destroy(s);
        return check_finish();
    }
    CHECK(strcmp(dirt_scene_name(s), "default") == 0);
    CHECK(s->stats.textures_failed == 0 && s->stats.prims_skipped == 0);
    fprintf(stderr, "embedded default scene: %zu bytes, %zu triangles\n",
            scene_default_gltf_size, dirt_scene_num_triangles(s));
    compare_scenes(oracle, s);

    /* The frame every technique consumes, with and without the (absent)
     * animation. */
    dirt_eval_opts rest = {.clip = -1};
    for (int k = 0; k < 2; k++) {
        dirt_frame *fa = dirt_scene_evaluate(oracle, 0.5f, k ? &rest : NULL);
        dirt_frame *fb = dirt_scene_evaluate(s, 0.5f, k ? &rest : NULL);
        CHECK(fa != NULL && fb != NULL);
        if (fa && fb)
            compare_frames(fa, fb);
        dirt_frame_destroy(fa);
        dirt_frame_destroy(fb);
    }

    /* Loading the file in the source tree gives the same scene, so the
     * embedded bytes are that file. */
#ifdef DIRT_TEST_DATA_DIR
    dirt_scene *d = dirt_scene_load(DIRT_TEST_DATA_DIR "/default_scene.gltf", NULL);
    CHECK(d != NULL);
    if (d) {
        CHECK(strcmp(dirt_scene_name(d), "default_scene") == 0);
        scene_copy_name(d->name, sizeof(d->name), "default");
        compare_scenes(oracle, d);
        dirt_scene_destroy(d);
    }
#endif

    check_load_memory(oracle);

    dirt_scene_destroy(s);
    dirt_scene_destroy(oracle);
    return check_finish();
}
