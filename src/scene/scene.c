/* DIRT engine: scene ownership, validation of the node graph, accessors. */
#include "scene/scene_internal.h"

#include "dirt/input.h"
#include "dirt/log.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void scene_copy_name(char *dst, size_t size, const char *src)
{
    if (size == 0)
        return;
    if (!src)
        src = "";
    size_t n = strlen(src);
    if (n >= size)
        n = size - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

dirt_scene *scene_new(const char *name)
{
    dirt_scene *s = calloc(1, sizeof(*s));
    if (!s) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory allocating a scene");
        return NULL;
    }
    scene_copy_name(s->name, sizeof(s->name), name);
    return s;
}

void scene_mat4_identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void scene_mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; c++) {
        for (int row = 0; row < 4; row++) {
            r[c * 4 + row] = a[0 * 4 + row] * b[c * 4 + 0] + a[1 * 4 + row] * b[c * 4 + 1] +
                             a[2 * 4 + row] * b[c * 4 + 2] + a[3 * 4 + row] * b[c * 4 + 3];
        }
    }
    memcpy(out, r, sizeof(r));
}

void scene_mat4_from_trs(float out[16], const float t[3], const float q[4],
                         const float s[3])
{
    float x = q[0], y = q[1], z = q[2], w = q[3];
    float xx = x * x, yy = y * y, zz = z * z;
    float xy = x * y, xz = x * z, yz = y * z;
    float wx = w * x, wy = w * y, wz = w * z;
    /* Columns of R scaled by S. */
    out[0] = (1.0f - 2.0f * (yy + zz)) * s[0];
    out[1] = (2.0f * (xy + wz)) * s[0];
    out[2] = (2.0f * (xz - wy)) * s[0];
    out[3] = 0.0f;
    out[4] = (2.0f * (xy - wz)) * s[1];
    out[5] = (1.0f - 2.0f * (xx + zz)) * s[1];
    out[6] = (2.0f * (yz + wx)) * s[1];
    out[7] = 0.0f;
    out[8] = (2.0f * (xz + wy)) * s[2];
    out[9] = (2.0f * (yz - wx)) * s[2];
    out[10] = (1.0f - 2.0f * (xx + yy)) * s[2];
    out[11] = 0.0f;
    out[12] = t[0];
    out[13] = t[1];
    out[14] = t[2];
    out[15] = 1.0f;
}

void dirt_material_default(dirt_material *m)
{
    memset(m, 0, sizeof(*m));
    for (int k = 0; k < 4; k++)
        m->base_color[k] = 1.0f;
    m->metallic = m->roughness = 1.0f;
    m->emissive_strength = 1.0f;
    m->base_color_tex = m->metallic_roughness_tex = m->emissive_tex = DIRT_NO_TEXTURE;
    m->normal_tex = m->transmission_tex = m->specular_tex = m->specular_color_tex =
        DIRT_NO_TEXTURE;
    m->normal_scale = 1.0f;
    m->alpha_mode = DIRT_ALPHA_OPAQUE;
    m->alpha_cutoff = 0.5f;
    m->ior = 1.5f;
    m->specular = 1.0f;
    for (int k = 0; k < 3; k++)
        m->specular_color[k] = 1.0f;
    /* (field by field: a struct assignment may leave padding undefined, and
     * materials are compared bytewise) */
    for (int k = 0; k < DIRT_NUM_TEX_SLOTS; k++)
        m->xf[k].scale[0] = m->xf[k].scale[1] = 1.0f;
}

static bool check_node_refs(const dirt_scene *s)
{
    for (size_t i = 0; i < s->num_nodes; i++) {
        const scene_node *n = &s->nodes[i];
        if (n->mesh < -1 || (n->mesh >= 0 && (size_t)n->mesh >= s->num_meshes)) {
            SCENE_FAIL(REFERENCE, "node %zu: mesh %d out of range (%zu meshes)", i, n->mesh,
                       s->num_meshes);
            return false;
        }
        if (n->skin < -1 || (n->skin >= 0 && (size_t)n->skin >= s->num_skins)) {
            SCENE_FAIL(REFERENCE, "node %zu: skin %d out of range (%zu skins)", i, n->skin,
                       s->num_skins);
            return false;
        }
        if (n->camera < -1 ||
            (n->camera >= 0 && (size_t)n->camera >= s->num_camera_protos)) {
            SCENE_FAIL(REFERENCE, "node %zu: camera %d out of range (%zu cameras)", i, n->camera,
                       s->num_camera_protos);
            return false;
        }
        if (n->light < -1 || (n->light >= 0 && (size_t)n->light >= s->num_light_protos)) {
            SCENE_FAIL(REFERENCE, "node %zu: light %d out of range (%zu lights)", i, n->light,
                       s->num_light_protos);
            return false;
        }
    }
    for (size_t k = 0; k < s->num_skins; k++) {
        const scene_skin *sk = &s->skins[k];
        for (size_t j = 0; j < sk->num_joints; j++) {
            if (sk->joints[j] < 0 || (size_t)sk->joints[j] >= s->num_nodes) {
                SCENE_FAIL(REFERENCE, "skin %zu: joint %zu is node %d, out of range (%zu nodes)", k, j,
                           sk->joints[j], s->num_nodes);
                return false;
            }
        }
    }
    return true;
}

/* Sets parents; fails on a child index out of range, a node listed as a child
 * twice (two parents) or a node that is its own child. */
static bool link_parents(dirt_scene *s)
{
    for (size_t i = 0; i < s->num_nodes; i++)
        s->nodes[i].parent = -1;
    for (size_t i = 0; i < s->num_nodes; i++) {
        const scene_node *n = &s->nodes[i];
        for (size_t c = 0; c < n->num_children; c++) {
            int ch = n->children[c];
            if (ch < 0 || (size_t)ch >= s->num_nodes) {
                SCENE_FAIL(REFERENCE, "node %zu: child %d out of range (%zu nodes)", i, ch,
                           s->num_nodes);
                return false;
            }
            if ((size_t)ch == i) {
                SCENE_FAIL(HIERARCHY, "node %zu is its own child (node cycle)", i);
                return false;
            }
            if (s->nodes[ch].parent != -1) {
                SCENE_FAIL(HIERARCHY, "node %d has more than one parent (%d and %zu)", ch,
                           s->nodes[ch].parent, i);
                return false;
            }
            s->nodes[ch].parent = (int)i;
        }
    }
    return true;
}

/* Pre-order walk of the subtree at `root` with an explicit stack (children in
 * file order). Calls visit(s, node, user) for each node; `stack` has room for
 * num_nodes entries. Cycle-free graphs only. */
typedef void (*visit_fn)(dirt_scene *s, int node, void *user);

static void walk(dirt_scene *s, int root, int *stack, visit_fn visit, void *user)
{
    size_t top = 0;
    stack[top++] = root;
    while (top > 0) {
        int n = stack[--top];
        visit(s, n, user);
        const scene_node *node = &s->nodes[n];
        for (size_t c = node->num_children; c > 0; c--)
            stack[top++] = node->children[c - 1];
    }
}

static void visit_order(dirt_scene *s, int node, void *user)
{
    size_t *count = user;
    s->eval_order[(*count)++] = node;
}

typedef struct gather_state {
    size_t num_instances, num_cameras, num_lights;
    bool fill;
} gather_state;

static void visit_gather(dirt_scene *s, int node, void *user)
{
    gather_state *g = user;
    const scene_node *n = &s->nodes[node];
    if (n->mesh >= 0) {
        if (g->fill) {
            scene_instance *in = &s->instances[g->num_instances];
            in->node = node;
            in->mesh = n->mesh;
            in->skin = n->skin;
            in->first_triangle = s->num_triangles;
            s->num_triangles += s->meshes[n->mesh].num_triangles;
        }
        g->num_instances++;
    }
    if (n->camera >= 0) {
        if (g->fill) {
            dirt_camera_def *c = &s->cameras[g->num_cameras];
            *c = s->camera_protos[n->camera];
            c->node = node;
        }
        g->num_cameras++;
    }
    if (n->light >= 0) {
        if (g->fill) {
            dirt_light_def *l = &s->lights[g->num_lights];
            *l = s->light_protos[n->light];
            l->node = node;
        }
        g->num_lights++;
    }
}

static bool check_skinned_instances(const dirt_scene *s)
{
    for (size_t i = 0; i < s->num_instances; i++) {
        const scene_instance *in = &s->instances[i];
        if (in->skin < 0)
            continue;
        const scene_skin *sk = &s->skins[in->skin];
        const scene_mesh *m = &s->meshes[in->mesh];
        for (size_t p = 0; p < m->num_prims; p++) {
            const scene_prim *pr = &m->prims[p];
            if (!pr->joints)
                continue;
            for (size_t v = 0; v < pr->num_vertices; v++) {
                for (int k = 0; k < 4; k++) {
                    if (pr->weights[v][k] != 0.0f && pr->joints[v][k] >= sk->num_joints) {
                        SCENE_FAIL(INDEX, "node %d: mesh %d primitive %zu vertex %zu uses joint %u "
                                   "but skin %d has %zu joints",
                                   in->node, in->mesh, p, v, (unsigned)pr->joints[v][k],
                                   in->skin, sk->num_joints);
                        return false;
                    }
                }
            }
        }
    }
    return true;
}

/* Warns when the scene shows nothing: no triangles at all, or only
 * triangles of zero area in the rest pose (morphs or skins may still give
 * them area later; the images are then black or background only). */
static void warn_degenerate(dirt_scene *s)
{
    size_t zero = 0;
    for (size_t k = 0; k < s->num_instances; k++) {
        const scene_mesh *m = &s->meshes[s->instances[k].mesh];
        for (size_t p = 0; p < m->num_prims; p++) {
            const scene_prim *pr = &m->prims[p];
            for (size_t t = 0; t < pr->num_triangles; t++) {
                const float *a = pr->position[pr->indices[3 * t]];
                const float *b = pr->position[pr->indices[3 * t + 1]];
                const float *c = pr->position[pr->indices[3 * t + 2]];
                float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]};
                zero += n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f;
            }
        }
    }
    s->stats.zero_area = zero;
    if (s->num_triangles == 0)
        SCENE_WARN("scene '%s' has no triangles to show: every image will be background only",
                  s->name);
    else if (zero == s->num_triangles)
        SCENE_WARN("scene '%s': all %zu triangles have zero area (in the rest pose): the "
                  "images will be background only",
                  s->name, s->num_triangles);
}

bool scene_finalize(dirt_scene *s, const int *roots, size_t num_roots)
{
    int *stack = NULL;
    bool *seen = NULL;

    if (!check_node_refs(s) || !link_parents(s))
        goto error;

    size_t n = s->num_nodes;
    stack = malloc((n ? n : 1) * sizeof(*stack));
    seen = calloc(n ? n : 1, sizeof(*seen));
    s->eval_order = malloc((n ? n : 1) * sizeof(*s->eval_order));
    if (!stack || !seen || !s->eval_order) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory finalizing scene '%s'", s->name);
        goto error;
    }

    /* With at most one parent per node, a node unreachable from the
     * parentless nodes lies on a cycle. */
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        if (s->nodes[i].parent == -1)
            walk(s, (int)i, stack, visit_order, &count);
    }
    if (count != n) {
        SCENE_FAIL(HIERARCHY, "scene '%s': node cycle (%zu of %zu nodes unreachable from a root)",
                   s->name, n - count, n);
        goto error;
    }

    /* The shown roots: validated, parentless, without duplicates. */
    if (!roots) {
        for (size_t i = 0; i < n; i++)
            num_roots += s->nodes[i].parent == -1;
    }
    s->roots = malloc((num_roots ? num_roots : 1) * sizeof(*s->roots));
    if (!s->roots) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory finalizing scene '%s'", s->name);
        goto error;
    }
    if (!roots) {
        for (size_t i = 0; i < n; i++) {
            if (s->nodes[i].parent == -1)
                s->roots[s->num_roots++] = (int)i;
        }
    } else {
        for (size_t i = 0; i < num_roots; i++) {
            int r = roots[i];
            if (r < 0 || (size_t)r >= n) {
                SCENE_FAIL(REFERENCE, "scene '%s': root node %d out of range (%zu nodes)", s->name, r,
                           n);
                goto error;
            }
            if (s->nodes[r].parent != -1) {
                SCENE_WARN("scene '%s': root node %d has a parent; ignored", s->name, r);
                continue;
            }
            if (seen[r]) {
                SCENE_WARN("scene '%s': root node %d listed twice; ignored", s->name, r);
                continue;
            }
            seen[r] = true;
            s->roots[s->num_roots++] = r;
        }
    }

    /* Node weights must match their mesh's morph target count. */
    s->total_weights = 0;
    for (size_t i = 0; i < n; i++) {
        scene_node *node = &s->nodes[i];
        node->weight_offset = s->total_weights;
        if (node->mesh < 0)
            continue;
        size_t nw = s->meshes[node->mesh].num_weights;
        if (node->weights && node->num_weights != nw) {
            SCENE_WARN("node %zu: %zu morph weights but mesh %d has %zu targets; using the "
                      "mesh's", i, node->num_weights, node->mesh, nw);
            free(node->weights);
            node->weights = NULL;
            node->num_weights = 0;
        }
        s->total_weights += nw;
    }
    s->total_joints = 0;
    for (size_t k = 0; k < s->num_skins; k++) {
        s->skins[k].joint_offset = s->total_joints;
        s->total_joints += s->skins[k].num_joints;
    }
    s->max_prim_vertices = 0;
    for (size_t m = 0; m < s->num_meshes; m++) {
        for (size_t p = 0; p < s->meshes[m].num_prims; p++) {
            if (s->meshes[m].prims[p].num_vertices > s->max_prim_vertices)
                s->max_prim_vertices = s->meshes[m].prims[p].num_vertices;
        }
    }

    /* Two passes over the shown hierarchy: count, then fill. */
    gather_state g = {0};
    for (size_t r = 0; r < s->num_roots; r++)
        walk(s, s->roots[r], stack, visit_gather, &g);
    s->instances = calloc(g.num_instances ? g.num_instances : 1, sizeof(*s->instances));
    s->cameras = calloc(g.num_cameras ? g.num_cameras : 1, sizeof(*s->cameras));
    s->lights = calloc(g.num_lights ? g.num_lights : 1, sizeof(*s->lights));
    if (!s->instances || !s->cameras || !s->lights) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory finalizing scene '%s'", s->name);
        goto error;
    }
    s->num_instances = g.num_instances;
    s->num_cameras = g.num_cameras;
    s->num_lights = g.num_lights;
    s->num_triangles = 0;
    g = (gather_state){.fill = true};
    for (size_t r = 0; r < s->num_roots; r++)
        walk(s, s->roots[r], stack, visit_gather, &g);
    if (s->num_triangles > UINT32_MAX / 3) {
        SCENE_FAIL(TOO_LARGE, "scene '%s': %zu triangles is too many", s->name, s->num_triangles);
        goto error;
    }

    if (!check_skinned_instances(s))
        goto error;
    warn_degenerate(s);

    free(stack);
    free(seen);
    return true;

error:
    free(stack);
    free(seen);
    return false;
}

static void free_prim(scene_prim *p)
{
    free(p->position);
    free(p->normal);
    free(p->uv);
    free(p->joints);
    free(p->weights);
    free(p->target_position);
    free(p->target_normal);
    free(p->tangent);
    free(p->target_tangent);
    free(p->indices);
}

void dirt_scene_destroy(dirt_scene *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->num_nodes; i++) {
        free(s->nodes[i].children);
        free(s->nodes[i].weights);
    }
    free(s->nodes);
    for (size_t i = 0; i < s->num_meshes; i++) {
        for (size_t p = 0; p < s->meshes[i].num_prims; p++)
            free_prim(&s->meshes[i].prims[p]);
        free(s->meshes[i].prims);
        free(s->meshes[i].weights);
    }
    free(s->meshes);
    for (size_t i = 0; i < s->num_skins; i++) {
        free(s->skins[i].joints);
        free(s->skins[i].inverse_bind);
    }
    free(s->skins);
    free(s->materials);
    for (size_t i = 0; i < s->num_textures; i++)
        free(s->textures[i].rgba);
    free(s->textures);
    free(s->camera_protos);
    free(s->light_protos);
    for (size_t i = 0; i < s->num_clips; i++) {
        for (size_t k = 0; k < s->clips[i].num_samplers; k++) {
            free(s->clips[i].samplers[k].times);
            free(s->clips[i].samplers[k].values);
        }
        free(s->clips[i].samplers);
        free(s->clips[i].channels);
    }
    free(s->clips);
    free(s->roots);
    free(s->eval_order);
    free(s->instances);
    free(s->cameras);
    free(s->lights);
    for (size_t i = 0; i < s->num_files; i++)
        free(s->files[i]);
    free(s->files);
    free(s);
}

/* ---- load errors -------------------------------------------------------- */

static _Thread_local enum dirt_scene_error load_error;

void scene_set_error(enum dirt_scene_error e)
{
    if (load_error == DIRT_SCENE_ERR_OK)
        load_error = e;
}

void scene_error_reset(void)
{
    load_error = DIRT_SCENE_ERR_OK;
}

enum dirt_scene_error scene_error_get(void)
{
    return load_error;
}

enum dirt_scene_error dirt_scene_last_error(void)
{
    return load_error;
}

const char *dirt_scene_error_str(enum dirt_scene_error e)
{
    static const char *const msg[] = {
#define DIRT_SCENE_ERR_MSG_(id, text) text,
        DIRT_SCENE_ERRORS(DIRT_SCENE_ERR_MSG_)
#undef DIRT_SCENE_ERR_MSG_
    };
    return (unsigned)e < DIRT_SCENE_NUM_ERRORS ? msg[e] : "?";
}

const char *dirt_scene_error_name(enum dirt_scene_error e)
{
    static const char *const name[] = {
#define DIRT_SCENE_ERR_NAME_(id, text) #id,
        DIRT_SCENE_ERRORS(DIRT_SCENE_ERR_NAME_)
#undef DIRT_SCENE_ERR_NAME_
    };
    return (unsigned)e < DIRT_SCENE_NUM_ERRORS ? name[e] : "?";
}

/* ---- the load in progress ---------------------------------------------- */

static _Thread_local struct {
    dirt_load_opts opts;
    char *dir;               /* references resolve here; NULL from memory */
    size_t left;             /* budget */
    size_t lowest;           /* the least left so far (scene_budget_peak) */
    size_t warnings;
    char **files;
    size_t num_files, cap_files;
} load;

static void forget_files(void)
{
    for (size_t i = 0; i < load.num_files; i++)
        free(load.files[i]);
    free(load.files);
    load.files = NULL;
    load.num_files = load.cap_files = 0;
}

void scene_load_begin(const dirt_load_opts *opts, const char *dir)
{
    free(load.dir);
    forget_files();
    load.opts = *opts;
    load.dir = dir ? strdup(dir) : NULL;
    load.left = load.lowest = opts->max_bytes;
    load.warnings = 0;
}

const dirt_load_opts *scene_load_opts(void)
{
    return &load.opts;
}

bool scene_charge(size_t count, size_t each, const char *what)
{
    if (each != 0 && count > load.left / each) {
        SCENE_FAIL(TOO_LARGE,
                   "%s: %zu x %zu bytes exceed what is left of the load budget (%zu bytes of "
                   "%zu; dirt_load_opts.max_bytes, --max-scene-memory)",
                   what, count, each, load.left, load.opts.max_bytes);
        return false;
    }
    load.left -= count * each;
    if (load.left < load.lowest)
        load.lowest = load.left;
    return true;
}

void scene_refund(size_t count, size_t each)
{
    size_t n = count * each;
    load.left = n > load.opts.max_bytes - load.left ? load.opts.max_bytes : load.left + n;
}

size_t scene_budget_peak(void)
{
    return load.opts.max_bytes - load.lowest;
}

bool scene_budget_fits(size_t count, size_t each)
{
    return each == 0 || count <= load.left / each;
}

size_t scene_budget_left(void)
{
    return load.left;
}

void scene_count_warning(void)
{
    load.warnings++;
}

static bool remember_file(const char *path)
{
    if (load.num_files == load.cap_files) {
        size_t c = load.cap_files ? 2 * load.cap_files : 8;
        char **grown = realloc(load.files, c * sizeof(char *));
        if (!grown)
            return false;
        load.files = grown;
        load.cap_files = c;
    }
    char *copy = strdup(path);
    if (!copy)
        return false;
    load.files[load.num_files++] = copy;
    return true;
}

/* Reads `path` within the budget (`copies` times its size), charges it and
 * records it. *missing (when given) is set, nothing logged, for a file that
 * does not exist. */
static unsigned char *read_charged(const char *path, const char *label, size_t copies,
                                   size_t *size, bool *missing)
{
    enum dirt_input_error e;
    size_t n = 0;
    size_t limit = copies ? load.left / copies : load.left;
    unsigned char *data = dirt_input_read(path, limit ? limit : 1, &n, &e);
    if (!data) {
        int err = errno;
        if (e == DIRT_INPUT_ERR_MISSING && missing) {
            *missing = true;
            return NULL;
        }
        if (e == DIRT_INPUT_ERR_NOT_REGULAR)
            SCENE_FAIL(NOT_REGULAR, "%s: not a regular file (a directory, FIFO, socket or "
                       "device): refused", label);
        else if (e == DIRT_INPUT_ERR_TOO_LARGE)
            SCENE_FAIL(TOO_LARGE, "%s: the file (%zu times its size) exceeds what is left of "
                       "the load budget (%zu bytes of %zu; dirt_load_opts.max_bytes, "
                       "--max-scene-memory)", label, copies ? copies : 1, load.left,
                       load.opts.max_bytes);
        else
            SCENE_FAIL(IO, "%s: cannot read it: %s", label, strerror(err));
        return NULL;
    }
    if (!scene_charge(n, copies ? copies : 1, label) || !remember_file(path)) {
        if (scene_error_get() == DIRT_SCENE_ERR_OK)
            SCENE_FAIL(OUT_OF_MEMORY, "%s: out of memory", label);
        free(data);
        return NULL;
    }
    *size = n;
    return data;
}

unsigned char *scene_read_scene_file(const char *path, size_t copies, size_t *size)
{
    char label[4200];
    snprintf(label, sizeof(label), "'%s'", path);
    bool missing = false;
    unsigned char *data = read_charged(path, label, copies, size, &missing);
    if (missing)
        SCENE_FAIL(IO, "cannot open '%s': %s", path, strerror(ENOENT));
    if (data && *size == 0) {
        SCENE_FAIL(EMPTY, "'%s' is empty", path);
        free(data);
        return NULL;
    }
    return data;
}

unsigned char *scene_read_ref_file(const char *path, const char *ref, const char *what,
                                   size_t copies, size_t *size, bool *missing)
{
    *missing = false;
    const char *scene = load.num_files ? load.files[0] : "scene";
    if (!load.dir) {
        SCENE_FAIL(EXTERNAL, "'%s': %s '%s' cannot be read by a scene loaded from memory", scene,
                   what, ref);
        return NULL;
    }
    if (!load.opts.allow_outside && !dirt_input_inside(load.dir, path)) {
        SCENE_FAIL(OUTSIDE, "'%s': %s '%s' leads outside the scene's folder '%s': refused "
                   "(--allow-outside-paths, dirt_load_opts.allow_outside, permits it)",
                   scene, what, ref, load.dir);
        return NULL;
    }
    char label[4200];
    snprintf(label, sizeof(label), "'%s': %s '%s'", scene, what, ref);
    return read_charged(path, label, copies, size, missing);
}

dirt_scene *scene_load_end(dirt_scene *s)
{
    if (s && load.opts.strict && load.warnings > 0) {
        SCENE_FAIL(STRICT, "'%s': %zu warning%s about the scene (above): refused by strict "
                   "loading (--strict, dirt_load_opts.strict)", s->name, load.warnings,
                   load.warnings == 1 ? "" : "s");
        dirt_scene_destroy(s);
        s = NULL;
    }
    if (!s) {
        scene_set_error(DIRT_SCENE_ERR_INVALID);
    } else {
        scene_error_reset();
        s->files = load.files;
        s->num_files = load.num_files;
        load.files = NULL;
        load.num_files = load.cap_files = 0;
    }
    forget_files();
    free(load.dir);
    load.dir = NULL;
    return s;
}

/* The options with their defaults filled in. */
static dirt_load_opts resolve_load_opts(const dirt_load_opts *opts)
{
    dirt_load_opts o = opts ? *opts : (dirt_load_opts){0};
    if (o.max_bytes == 0)
        o.max_bytes = DIRT_LOAD_DEFAULT_MAX_BYTES;
    if (o.max_depth <= 0)
        o.max_depth = DIRT_LOAD_DEFAULT_MAX_DEPTH;
    return o;
}

/* True when `name` ends in `ext` (".obj"), in any case. */
static bool has_ext(const char *name, const char *ext)
{
    size_t n = strlen(name), m = strlen(ext);
    if (n < m)
        return false;
    for (size_t i = 0; i < m; i++) {
        char c = name[n - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != ext[i])
            return false;
    }
    return true;
}

static bool is_obj_name(const char *name)
{
    return has_ext(name, ".obj");
}

/* The folder of `path` ("." when it has none). */
static char *folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return strdup(".");
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = 0;
    }
    return d;
}

dirt_scene *dirt_scene_load(const char *path, const dirt_load_opts *opts)
{
    scene_error_reset();
    if (!path || !*path) {
        DIRT_ERROR("dirt_scene_load: no path given");
        scene_set_error(DIRT_SCENE_ERR_ARGUMENT);
        return NULL;
    }
    dirt_load_opts o = resolve_load_opts(opts);
    char *dir = folder_of(path);
    if (!dir) {
        SCENE_FAIL(OUT_OF_MEMORY, "out of memory loading '%s'", path);
        return NULL;
    }
    scene_load_begin(&o, dir);
    free(dir);
    dirt_scene *s;
    if (is_obj_name(path))
        s = scene_load_obj(path, &o);
    else
        s = scene_load_gltf(path, &o);
    return scene_load_end(s);
}

dirt_scene *dirt_scene_load_obj_memory(const void *obj, size_t obj_size, const void *mtl,
                                       size_t mtl_size, const char *name,
                                       const dirt_load_opts *opts)
{
    scene_error_reset();
    if (!name || !*name)
        name = "memory.obj";
    if ((!obj && obj_size > 0) || (!mtl && mtl_size > 0)) {
        DIRT_ERROR("dirt_scene_load_obj_memory: '%s': no data given", name);
        scene_set_error(DIRT_SCENE_ERR_ARGUMENT);
        return NULL;
    }
    dirt_load_opts o = resolve_load_opts(opts);
    scene_load_begin(&o, NULL);
    return scene_load_end(
        scene_load_obj_memory(obj ? obj : "", obj_size, mtl, mtl_size, name, &o));
}

dirt_scene *dirt_scene_load_memory(const void *data, size_t size, const char *name,
                                   const dirt_load_opts *opts)
{
    scene_error_reset();
    if (!name || !*name)
        name = "memory";
    if (!data && size > 0) {
        DIRT_ERROR("dirt_scene_load_memory: '%s': no data given", name);
        scene_set_error(DIRT_SCENE_ERR_ARGUMENT);
        return NULL;
    }
    dirt_load_opts o = resolve_load_opts(opts);
    scene_load_begin(&o, NULL);
    if (is_obj_name(name))
        return scene_load_end(scene_load_obj_memory(data ? data : "", size, NULL, 0, name, &o));
    return scene_load_end(scene_load_gltf_memory(data ? data : "", size, name, &o));
}

size_t dirt_scene_num_files(const dirt_scene *s)
{
    return s ? s->num_files : 0;
}

const char *dirt_scene_file(const dirt_scene *s, size_t i)
{
    return s && i < s->num_files ? s->files[i] : NULL;
}

const char *dirt_scene_name(const dirt_scene *s)
{
    return s ? s->name : "";
}

size_t dirt_scene_num_materials(const dirt_scene *s)
{
    return s ? s->num_materials : 0;
}

const dirt_material *dirt_scene_materials(const dirt_scene *s)
{
    return s ? s->materials : NULL;
}

bool dirt_material_is_emissive(const dirt_material *m)
{
    float e = fmaxf(m->emissive[0], fmaxf(m->emissive[1], m->emissive[2]));
    return e > 0.0f && m->emissive_strength > 0.0f && isfinite(e * m->emissive_strength);
}

size_t dirt_scene_num_textures(const dirt_scene *s)
{
    return s ? s->num_textures : 0;
}

const dirt_texture *dirt_scene_textures(const dirt_scene *s)
{
    return s ? s->textures : NULL;
}

size_t dirt_scene_num_cameras(const dirt_scene *s)
{
    return s ? s->num_cameras : 0;
}

const dirt_camera_def *dirt_scene_cameras(const dirt_scene *s)
{
    return s ? s->cameras : NULL;
}

size_t dirt_scene_num_lights(const dirt_scene *s)
{
    return s ? s->num_lights : 0;
}

const dirt_light_def *dirt_scene_lights(const dirt_scene *s)
{
    return s ? s->lights : NULL;
}

size_t dirt_scene_num_nodes(const dirt_scene *s)
{
    return s ? s->num_nodes : 0;
}

const char *dirt_scene_node_name(const dirt_scene *s, size_t node)
{
    if (!s || node >= s->num_nodes)
        return NULL;
    return s->nodes[node].name;
}

size_t dirt_scene_num_triangles(const dirt_scene *s)
{
    return s ? s->num_triangles : 0;
}

size_t dirt_scene_num_clips(const dirt_scene *s)
{
    return s ? s->num_clips : 0;
}

const char *dirt_scene_clip_name(const dirt_scene *s, size_t clip)
{
    if (!s || clip >= s->num_clips)
        return NULL;
    return s->clips[clip].name;
}

float dirt_scene_clip_duration(const dirt_scene *s, size_t clip)
{
    if (!s || clip >= s->num_clips)
        return 0.0f;
    return s->clips[clip].duration;
}
