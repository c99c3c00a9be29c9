/* DIRT engine: evaluation of a scene at time t into a world-space triangle
 * soup (animation sampling, node hierarchy, morph targets, skinning).
 *
 * Output winding: triangles are emitted counter-clockwise as seen from their
 * front side. glTF reverses the front-face winding of nodes whose world
 * matrix has a negative determinant; for such rigid instances vertices 1 and
 * 2 are swapped so that consumers never need to know. */
#include "scene/scene_internal.h"

#include "dirt/log.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A frame plus the scratch space evaluation needs, so that re-evaluation
 * never allocates. `pub` must stay the first member: dirt_frame pointers
 * handed out are pointers to it. */
typedef struct frame_impl {
    dirt_frame pub;
    const dirt_scene *scene;
    float (*trs)[10];     /* per node: translation, rotation (xyzw), scale */
    float *weights;       /* per mesh node, at scene_node.weight_offset */
    float (*joint)[16];   /* per skin joint: jointWorld * inverseBind */
    float (*vpos)[3];     /* per vertex of the primitive being emitted */
    float (*vnrm)[3];
    float (*vtan)[4];     /* tangents (xyz not normalised, w handedness) */
} frame_impl;

/* ---- small vector / quaternion helpers ---------------------------------- */

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(float out[3], const float a[3], const float b[3])
{
    float r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                  a[0] * b[1] - a[1] * b[0]};
    memcpy(out, r, sizeof(r));
}

/* Normalises v in place; returns false (v untouched) when its length is zero
 * or not finite. */
static bool normalize3(float v[3])
{
    float l2 = dot3(v, v);
    if (!(l2 > 1e-30f) || !isfinite(l2))
        return false;
    float inv = 1.0f / sqrtf(l2);
    v[0] *= inv;
    v[1] *= inv;
    v[2] *= inv;
    return true;
}

static void normalize_quat(float q[4])
{
    float l2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!(l2 > 1e-30f) || !isfinite(l2)) {
        q[0] = q[1] = q[2] = 0.0f;
        q[3] = 1.0f;
        return;
    }
    float inv = 1.0f / sqrtf(l2);
    for (int i = 0; i < 4; i++)
        q[i] *= inv;
}

/* Spherical interpolation along the shorter arc; result normalised. */
static void slerp(float out[4], const float a[4], const float b_in[4], float u)
{
    float b[4] = {b_in[0], b_in[1], b_in[2], b_in[3]};
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0f) {
        d = -d;
        for (int i = 0; i < 4; i++)
            b[i] = -b[i];
    }
    float wa, wb;
    if (d > 0.9995f) {
        wa = 1.0f - u;
        wb = u;
    } else {
        float theta = acosf(d);
        float st = sinf(theta);
        wa = sinf((1.0f - u) * theta) / st;
        wb = sinf(u * theta) / st;
    }
    for (int i = 0; i < 4; i++)
        out[i] = wa * a[i] + wb * b[i];
    normalize_quat(out);
}

/* 3x3 cofactor matrix of the upper-left block of column-major m, scaled by
 * the sign of its determinant: maps normals like the inverse transpose up to
 * a positive factor. Returns the determinant. */
static float normal_matrix(float out[9], const float m[16])
{
    const float *c0 = &m[0], *c1 = &m[4], *c2 = &m[8];
    float x[3], y[3], z[3];
    cross3(x, c1, c2); /* columns of the cofactor matrix */
    cross3(y, c2, c0);
    cross3(z, c0, c1);
    float det = dot3(c0, x);
    float sg = det < 0.0f ? -1.0f : 1.0f;
    for (int i = 0; i < 3; i++) {
        out[0 + i] = x[i] * sg;
        out[3 + i] = y[i] * sg;
        out[6 + i] = z[i] * sg;
    }
    return det;
}

/* n' = cof * n with cof columns (x, y, z) as built by normal_matrix: the
 * inverse transpose is cof / det, so n' = sum_j cof_col_j * n_j. */
static void apply_normal(float out[3], const float nm[9], const float n[3])
{
    float r[3];
    for (int i = 0; i < 3; i++)
        r[i] = nm[0 + i] * n[0] + nm[3 + i] * n[1] + nm[6 + i] * n[2];
    memcpy(out, r, sizeof(r));
}

/* The direction d through the upper-left 3x3 block of column-major m
 * (tangents: they follow the surface like its edges). */
static void transform_dir(float out[3], const float m[16], const float d[3])
{
    float r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[i] * d[0] + m[4 + i] * d[1] + m[8 + i] * d[2];
    memcpy(out, r, sizeof(r));
}

static void transform_point(float out[3], const float m[16], const float p[3])
{
    float r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i];
    memcpy(out, r, sizeof(r));
}

/* ---- animation sampling ------------------------------------------------- */

/* Index k of the last key with times[k] <= t, for times[0] <= t < last. */
static size_t find_key(const float *times, size_t n, float t)
{
    size_t lo = 0, hi = n - 1; /* times[lo] <= t < times[hi] */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Samples `smp` at time t into out[0..width). Quaternion outputs (`quat`)
 * are interpolated along the shorter arc and normalised. */
static void sample(const scene_sampler *smp, float t, bool quat, float *out)
{
    size_t w = smp->width, n = smp->num_keys;
    bool cubic = smp->interp == SCENE_INTERP_CUBIC;
    /* Element e of key k: the value itself (cubic: the middle of the triple). */
#define VALUE(k) (smp->values + ((cubic ? 3 * (k) + 1 : (k)) * w))
    if (n == 1 || !(t > smp->times[0])) {
        memcpy(out, VALUE(0), w * sizeof(float));
    } else if (t >= smp->times[n - 1]) {
        memcpy(out, VALUE(n - 1), w * sizeof(float));
    } else {
        size_t k = find_key(smp->times, n, t);
        float t0 = smp->times[k], t1 = smp->times[k + 1];
        float td = t1 - t0;
        float u = td > 0.0f ? (t - t0) / td : 1.0f;
        if (u < 0.0f)
            u = 0.0f;
        if (u > 1.0f)
            u = 1.0f;
        if (smp->interp == SCENE_INTERP_STEP) {
            memcpy(out, VALUE(k), w * sizeof(float));
        } else if (smp->interp == SCENE_INTERP_LINEAR) {
            const float *a = VALUE(k), *b = VALUE(k + 1);
            if (quat) {
                slerp(out, a, b, u);
            } else {
                for (size_t i = 0; i < w; i++)
                    out[i] = a[i] + (b[i] - a[i]) * u;
            }
        } else {
            /* Hermite spline: v_k, out-tangent b_k of key k, in-tangent a_k+1
             * and v_k+1 of key k+1, tangents scaled by the key interval. */
            const float *v0 = VALUE(k), *v1 = VALUE(k + 1);
            const float *b0 = v0 + w, *a1 = v1 - w;
            float u2 = u * u, u3 = u2 * u;
            float h00 = 2.0f * u3 - 3.0f * u2 + 1.0f;
            float h10 = (u3 - 2.0f * u2 + u) * td;
            float h01 = -2.0f * u3 + 3.0f * u2;
            float h11 = (u3 - u2) * td;
            for (size_t i = 0; i < w; i++)
                out[i] = h00 * v0[i] + h10 * b0[i] + h01 * v1[i] + h11 * a1[i];
        }
    }
#undef VALUE
    if (quat)
        normalize_quat(out);
}

/* Local time of a clip of length `dur` for global time t. */
static float clip_time(float t, float dur, bool loop)
{
    if (!isfinite(t) || t < 0.0f)
        t = loop && isfinite(t) && dur > 0.0f ? t : 0.0f;
    if (dur <= 0.0f)
        return 0.0f;
    if (loop) {
        float r = fmodf(t, dur);
        if (r < 0.0f)
            r += dur;
        if (r >= dur)
            r = 0.0f;
        return r;
    }
    return t > dur ? dur : t;
}

static void apply_clip(const dirt_scene *s, const scene_clip *clip, float t,
                       frame_impl *fi)
{
    for (size_t c = 0; c < clip->num_channels; c++) {
        const scene_channel *ch = &clip->channels[c];
        const scene_sampler *smp = &clip->samplers[ch->sampler];
        float *trs = fi->trs[ch->node];
        switch (ch->path) {
        case SCENE_PATH_TRANSLATION:
            sample(smp, t, false, trs + 0);
            break;
        case SCENE_PATH_ROTATION:
            sample(smp, t, true, trs + 3);
            break;
        case SCENE_PATH_SCALE:
            sample(smp, t, false, trs + 7);
            break;
        case SCENE_PATH_WEIGHTS:
            sample(smp, t, false, fi->weights + s->nodes[ch->node].weight_offset);
            break;
        }
    }
}

/* ---- geometry ----------------------------------------------------------- */

/* Morphed, then skinned or rigidly transformed vertices of one primitive into
 * fi->vpos / fi->vnrm (normals not normalised; zero when absent) and, when
 * the primitive has tangents, fi->vtan: morphed by target_tangent, then
 * through the vertex's matrix as directions, the handedness w times the
 * sign of the matrix's determinant (a mirroring transform reverses the
 * bitangent cross(n, t) makes). `det` is the determinant of `world`. */
static void transform_prim(frame_impl *fi, const scene_prim *p, const float *weights,
                           const float *world, const float *nmat, float det,
                           const scene_skin *skin)
{
    size_t nv = p->num_vertices;
    float (*vp)[3] = fi->vpos, (*vn)[3] = fi->vnrm;
    float (*vt)[4] = p->tangent ? fi->vtan : NULL;

    for (size_t v = 0; v < nv; v++) {
        memcpy(vp[v], p->position[v], sizeof(vp[v]));
        if (p->normal)
            memcpy(vn[v], p->normal[v], sizeof(vn[v]));
        else
            vn[v][0] = vn[v][1] = vn[v][2] = 0.0f;
        if (vt)
            memcpy(vt[v], p->tangent[v], sizeof(vt[v]));
    }
    for (size_t k = 0; k < p->num_targets && weights; k++) {
        float w = weights[k];
        if (w == 0.0f)
            continue;
        if (p->target_position) {
            const float (*d)[3] = (const float (*)[3])p->target_position + k * nv;
            for (size_t v = 0; v < nv; v++) {
                vp[v][0] += w * d[v][0];
                vp[v][1] += w * d[v][1];
                vp[v][2] += w * d[v][2];
            }
        }
        if (p->target_normal && p->normal) {
            const float (*d)[3] = (const float (*)[3])p->target_normal + k * nv;
            for (size_t v = 0; v < nv; v++) {
                vn[v][0] += w * d[v][0];
                vn[v][1] += w * d[v][1];
                vn[v][2] += w * d[v][2];
            }
        }
        if (p->target_tangent && vt) {
            const float (*d)[3] = (const float (*)[3])p->target_tangent + k * nv;
            for (size_t v = 0; v < nv; v++) {
                vt[v][0] += w * d[v][0];
                vt[v][1] += w * d[v][1];
                vt[v][2] += w * d[v][2];
            }
        }
    }

    if (skin && p->joints) {
        const float (*jm)[16] = (const float (*)[16])fi->joint + skin->joint_offset;
        for (size_t v = 0; v < nv; v++) {
            float m[16] = {0};
            for (int k = 0; k < 4; k++) {
                float w = p->weights[v][k];
                if (w == 0.0f)
                    continue;
                const float *j = jm[p->joints[v][k]];
                for (int e = 0; e < 16; e++)
                    m[e] += w * j[e];
            }
            float nm[9];
            transform_point(vp[v], m, vp[v]);
            if (p->normal || vt) {
                float d = normal_matrix(nm, m);
                if (p->normal)
                    apply_normal(vn[v], nm, vn[v]);
                if (vt) {
                    transform_dir(vt[v], m, vt[v]);
                    if (d < 0.0f)
                        vt[v][3] = -vt[v][3];
                }
            }
        }
    } else {
        for (size_t v = 0; v < nv; v++) {
            transform_point(vp[v], world, vp[v]);
            if (p->normal)
                apply_normal(vn[v], nmat, vn[v]);
            if (vt) {
                transform_dir(vt[v], world, vt[v]);
                if (det < 0.0f)
                    vt[v][3] = -vt[v][3];
            }
        }
    }
}

static void emit_prim(frame_impl *fi, const scene_prim *p, size_t first, uint32_t inst,
                      bool flip)
{
    dirt_frame *f = &fi->pub;
    for (size_t t = 0; t < p->num_triangles; t++) {
        size_t tri = first + t;
        uint32_t idx[3] = {p->indices[3 * t], p->indices[3 * t + 1], p->indices[3 * t + 2]};
        if (flip) {
            uint32_t tmp = idx[1];
            idx[1] = idx[2];
            idx[2] = tmp;
        }
        float *pos[3];
        for (int k = 0; k < 3; k++) {
            pos[k] = f->position[3 * tri + k];
            memcpy(pos[k], fi->vpos[idx[k]], 3 * sizeof(float));
        }
        float e1[3] = {pos[1][0] - pos[0][0], pos[1][1] - pos[0][1], pos[1][2] - pos[0][2]};
        float e2[3] = {pos[2][0] - pos[0][0], pos[2][1] - pos[0][1], pos[2][2] - pos[0][2]};
        float flat[3];
        cross3(flat, e1, e2);
        if (!normalize3(flat)) {
            flat[0] = 0.0f;
            flat[1] = 1.0f;
            flat[2] = 0.0f;
        }
        for (int k = 0; k < 3; k++) {
            float *n = f->normal[3 * tri + k];
            memcpy(n, fi->vnrm[idx[k]], 3 * sizeof(float));
            if (!normalize3(n))
                memcpy(n, flat, sizeof(flat));
            if (f->tangent) {
                float *tg = f->tangent[3 * tri + k];
                if (p->tangent) {
                    memcpy(tg, fi->vtan[idx[k]], 4 * sizeof(float));
                    if (!normalize3(tg))
                        tg[0] = tg[1] = tg[2] = 0.0f;
                    tg[3] = tg[3] < 0.0f ? -1.0f : 1.0f;
                } else {
                    tg[0] = tg[1] = tg[2] = 0.0f;
                    tg[3] = 1.0f;
                }
            }
            float *uv = f->uv[3 * tri + k];
            if (p->uv) {
                uv[0] = p->uv[idx[k]][0];
                uv[1] = p->uv[idx[k]][1];
            } else {
                uv[0] = uv[1] = 0.0f;
            }
        }
        f->material[tri] = p->material;
        f->instance[tri] = inst;
    }
}

/* ---- cameras and lights ------------------------------------------------- */

static void eval_cameras(const dirt_scene *s, dirt_frame *f)
{
    for (size_t i = 0; i < s->num_cameras; i++) {
        const dirt_camera_def *d = &s->cameras[i];
        const float *w = f->node_world[d->node];
        dirt_camera *c = &f->cameras[i];
        memset(c, 0, sizeof(*c));
        c->eye[0] = w[12];
        c->eye[1] = w[13];
        c->eye[2] = w[14];
        float fwd[3] = {-w[8], -w[9], -w[10]};
        float up[3] = {w[4], w[5], w[6]};
        scene_camera_set_basis(c, fwd, up);
        c->type = d->type;
        c->yfov = d->yfov;
        c->aspect = d->aspect;
        c->znear = d->znear;
        c->zfar = d->zfar;
        c->xmag = d->xmag;
        c->ymag = d->ymag;
    }
}

static void eval_lights(const dirt_scene *s, dirt_frame *f)
{
    for (size_t i = 0; i < s->num_lights; i++) {
        const dirt_light_def *d = &s->lights[i];
        const float *w = f->node_world[d->node];
        dirt_light *l = &f->lights[i];
        memset(l, 0, sizeof(*l));
        l->type = d->type;
        l->position[0] = w[12];
        l->position[1] = w[13];
        l->position[2] = w[14];
        l->direction[0] = -w[8];
        l->direction[1] = -w[9];
        l->direction[2] = -w[10];
        if (!normalize3(l->direction)) {
            l->direction[0] = l->direction[1] = 0.0f;
            l->direction[2] = -1.0f;
        }
        for (int k = 0; k < 3; k++)
            l->color[k] = d->color[k] * d->intensity;
        l->range = d->range;
        l->inner_cone = d->inner_cone;
        l->outer_cone = d->outer_cone;
    }
}

/* ---- evaluation --------------------------------------------------------- */

static void rest_pose(const dirt_scene *s, frame_impl *fi)
{
    for (size_t i = 0; i < s->num_nodes; i++) {
        const scene_node *n = &s->nodes[i];
        float *trs = fi->trs[i];
        memcpy(trs + 0, n->translation, 3 * sizeof(float));
        memcpy(trs + 3, n->rotation, 4 * sizeof(float));
        memcpy(trs + 7, n->scale, 3 * sizeof(float));
        if (n->mesh < 0)
            continue;
        const scene_mesh *m = &s->meshes[n->mesh];
        float *w = fi->weights + n->weight_offset;
        if (n->weights)
            memcpy(w, n->weights, m->num_weights * sizeof(float));
        else if (m->num_weights)
            memcpy(w, m->weights, m->num_weights * sizeof(float));
    }
}

static void eval_frame(const dirt_scene *s, float t, const dirt_eval_opts *opts,
                       frame_impl *fi)
{
    static const dirt_eval_opts defaults = {0};
    dirt_frame *f = &fi->pub;
    if (!opts)
        opts = &defaults;
    if (!isfinite(t))
        t = 0.0f;

    rest_pose(s, fi);

    f->time = t; /* no clip applied: nothing to clamp to */
    if (opts->all_clips && s->num_clips > 0) {
        float longest = 0.0f;
        for (size_t c = 0; c < s->num_clips; c++) {
            const scene_clip *clip = &s->clips[c];
            apply_clip(s, clip, clip_time(t, clip->duration, opts->loop), fi);
            if (clip->duration > longest)
                longest = clip->duration;
        }
        f->time = clip_time(t, longest, opts->loop);
    } else if (opts->clip >= 0 && (size_t)opts->clip < s->num_clips) {
        const scene_clip *clip = &s->clips[opts->clip];
        f->time = clip_time(t, clip->duration, opts->loop);
        apply_clip(s, clip, f->time, fi);
    } else if (opts->clip > 0 || opts->clip < -1) {
        DIRT_WARN("scene '%s': clip %d does not exist (%zu clips); rest pose", s->name,
                  opts->clip, s->num_clips);
    }

    /* World matrices, parents before children. */
    for (size_t i = 0; i < s->num_nodes; i++) {
        int n = s->eval_order[i];
        const scene_node *node = &s->nodes[n];
        float local[16];
        if (node->has_matrix) {
            memcpy(local, node->matrix, sizeof(local));
        } else {
            const float *trs = fi->trs[n];
            scene_mat4_from_trs(local, trs + 0, trs + 3, trs + 7);
        }
        if (node->parent >= 0)
            scene_mat4_mul(f->node_world[n], f->node_world[node->parent], local);
        else
            memcpy(f->node_world[n], local, sizeof(local));
    }

    for (size_t k = 0; k < s->num_skins; k++) {
        const scene_skin *sk = &s->skins[k];
        for (size_t j = 0; j < sk->num_joints; j++) {
            scene_mat4_mul(fi->joint[sk->joint_offset + j], f->node_world[sk->joints[j]],
                           sk->inverse_bind[j]);
        }
    }

    for (size_t i = 0; i < s->num_instances; i++) {
        const scene_instance *in = &s->instances[i];
        const scene_mesh *m = &s->meshes[in->mesh];
        const float *world = f->node_world[in->node];
        const float *weights = m->num_weights ? fi->weights + s->nodes[in->node].weight_offset
                                              : NULL;
        const scene_skin *skin = in->skin >= 0 ? &s->skins[in->skin] : NULL;
        float nmat[9];
        float det = normal_matrix(nmat, world);
        size_t first = in->first_triangle;
        for (size_t p = 0; p < m->num_prims; p++) {
            const scene_prim *pr = &m->prims[p];
            bool skinned = skin && pr->joints;
            transform_prim(fi, pr, weights, world, nmat, det, skinned ? skin : NULL);
            emit_prim(fi, pr, first, (uint32_t)i, !skinned && det < 0.0f);
            first += pr->num_triangles;
        }
    }

    if (f->num_triangles == 0) {
        memset(f->bounds_min, 0, sizeof(f->bounds_min));
        memset(f->bounds_max, 0, sizeof(f->bounds_max));
    } else {
        for (int k = 0; k < 3; k++) {
            f->bounds_min[k] = INFINITY;
            f->bounds_max[k] = -INFINITY;
        }
        size_t nv = 3 * f->num_triangles;
        for (size_t v = 0; v < nv; v++) {
            for (int k = 0; k < 3; k++) {
                float x = f->position[v][k];
                if (x < f->bounds_min[k])
                    f->bounds_min[k] = x;
                if (x > f->bounds_max[k])
                    f->bounds_max[k] = x;
            }
        }
    }

    eval_cameras(s, f);
    eval_lights(s, f);
}

void dirt_frame_destroy(dirt_frame *f)
{
    if (!f)
        return;
    frame_impl *fi = (frame_impl *)f;
    free(f->position);
    free(f->normal);
    free(f->uv);
    free(f->tangent);
    free(f->material);
    free(f->instance);
    free(f->node_world);
    free(f->cameras);
    free(f->lights);
    free(fi->trs);
    free(fi->weights);
    free(fi->joint);
    free(fi->vpos);
    free(fi->vnrm);
    free(fi->vtan);
    free(fi);
}

/* Whether any primitive of the scene has tangents (the frame then has a
 * tangent array). */
static bool scene_has_tangents(const dirt_scene *s)
{
    for (size_t m = 0; m < s->num_meshes; m++)
        for (size_t p = 0; p < s->meshes[m].num_prims; p++)
            if (s->meshes[m].prims[p].tangent)
                return true;
    return false;
}

/* malloc of n elements of `size` bytes, at least one element so that an empty
 * array is still a valid pointer. */
static void *alloc_n(size_t n, size_t size)
{
    return calloc(n ? n : 1, size);
}

dirt_frame *dirt_scene_evaluate(const dirt_scene *s, float t, const dirt_eval_opts *opts)
{
    if (!s) {
        DIRT_ERROR("dirt_scene_evaluate: no scene");
        return NULL;
    }
    frame_impl *fi = calloc(1, sizeof(*fi));
    if (!fi)
        goto error;
    dirt_frame *f = &fi->pub;
    size_t nv = 3 * s->num_triangles;
    fi->scene = s;
    f->num_triangles = s->num_triangles;
    f->num_nodes = s->num_nodes;
    f->num_cameras = s->num_cameras;
    f->num_lights = s->num_lights;
    f->position = alloc_n(nv, sizeof(*f->position));
    f->normal = alloc_n(nv, sizeof(*f->normal));
    f->uv = alloc_n(nv, sizeof(*f->uv));
    if (scene_has_tangents(s))
        f->tangent = alloc_n(nv, sizeof(*f->tangent));
    f->material = alloc_n(s->num_triangles, sizeof(*f->material));
    f->instance = alloc_n(s->num_triangles, sizeof(*f->instance));
    f->node_world = alloc_n(s->num_nodes, sizeof(*f->node_world));
    f->cameras = alloc_n(s->num_cameras, sizeof(*f->cameras));
    f->lights = alloc_n(s->num_lights, sizeof(*f->lights));
    fi->trs = alloc_n(s->num_nodes, sizeof(*fi->trs));
    fi->weights = alloc_n(s->total_weights, sizeof(*fi->weights));
    fi->joint = alloc_n(s->total_joints, sizeof(*fi->joint));
    fi->vpos = alloc_n(s->max_prim_vertices, sizeof(*fi->vpos));
    fi->vnrm = alloc_n(s->max_prim_vertices, sizeof(*fi->vnrm));
    fi->vtan = alloc_n(s->max_prim_vertices, sizeof(*fi->vtan));
    if (!f->position || !f->normal || !f->uv || !f->material || !f->instance ||
        !f->node_world || !f->cameras || !f->lights || !fi->trs || !fi->weights ||
        !fi->joint || !fi->vpos || !fi->vnrm || !fi->vtan ||
        (scene_has_tangents(s) && !f->tangent))
        goto error;
    eval_frame(s, t, opts, fi);
    return f;

error:
    DIRT_ERROR("out of memory evaluating scene '%s' (%zu triangles)", s->name,
               s->num_triangles);
    dirt_frame_destroy(fi ? &fi->pub : NULL);
    return NULL;
}

bool dirt_scene_evaluate_into(const dirt_scene *s, float t, const dirt_eval_opts *opts,
                              dirt_frame *frame)
{
    if (!s || !frame) {
        DIRT_ERROR("dirt_scene_evaluate_into: no scene or frame");
        return false;
    }
    frame_impl *fi = (frame_impl *)frame;
    if (fi->scene != s || frame->num_triangles != s->num_triangles ||
        frame->num_nodes != s->num_nodes) {
        DIRT_ERROR("dirt_scene_evaluate_into: frame was not made by dirt_scene_evaluate "
                   "of scene '%s'", s->name);
        return false;
    }
    eval_frame(s, t, opts, fi);
    return true;
}
