/* DIRT engine, src/ref: Embree's BVH walked by a counting traversal (the
 * work counters of doc/dirt-trace.md, "Work counters").
 *
 * Embree's kernels do not say how many nodes a query visits, so the
 * hierarchy is built by Embree's own builder (rtcBuildBVH: SAH, medium
 * quality like dirt_ref_accel's scene, branching factor 4 and up to 4
 * triangles per leaf, the shape of Embree's BVH4 with Triangle4 leaves) and
 * walked here: ordered closest-hit traversal (children by entry distance,
 * nodes entered beyond the best hit so far are culled), or any hit. Every
 * node taken from the stack counts as one node visited, and every triangle
 * of a leaf reached counts as one triangle test. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "ref/parallel.h"
#include "ref/ref.h"

#define BVH_WIDTH 4
#define BVH_LEAF 4
#define BVH_STACK 256

typedef struct bvh_node {
    bool leaf;
    unsigned n;                  /* children or triangles */
    struct bvh_node *child[BVH_WIDTH];
    float lo[BVH_WIDTH][3], hi[BVH_WIDTH][3];
    uint32_t prim[BVH_LEAF];
} bvh_node;

struct dirt_ref_bvh {
    RTCDevice device;
    RTCBVH bvh;
    bvh_node *root;              /* NULL for an empty frame */
    float (*position)[3];        /* copy, 3 per triangle */
    size_t prims;
};

static void *create_node(RTCThreadLocalAllocator alloc, unsigned int count, void *user)
{
    (void)user;
    bvh_node *n = rtcThreadLocalAlloc(alloc, sizeof(bvh_node), 16);
    memset(n, 0, sizeof(*n));
    n->n = count;
    return n;
}

static void set_children(void *node, void **children, unsigned int count, void *user)
{
    (void)user;
    bvh_node *n = node;
    for (unsigned i = 0; i < count && i < BVH_WIDTH; i++)
        n->child[i] = children[i];
}

static void set_bounds(void *node, const struct RTCBounds **bounds, unsigned int count, void *user)
{
    (void)user;
    bvh_node *n = node;
    for (unsigned i = 0; i < count && i < BVH_WIDTH; i++) {
        n->lo[i][0] = bounds[i]->lower_x;
        n->lo[i][1] = bounds[i]->lower_y;
        n->lo[i][2] = bounds[i]->lower_z;
        n->hi[i][0] = bounds[i]->upper_x;
        n->hi[i][1] = bounds[i]->upper_y;
        n->hi[i][2] = bounds[i]->upper_z;
    }
}

static void *create_leaf(RTCThreadLocalAllocator alloc, const struct RTCBuildPrimitive *prims,
                         size_t count, void *user)
{
    (void)user;
    bvh_node *n = rtcThreadLocalAlloc(alloc, sizeof(bvh_node), 16);
    memset(n, 0, sizeof(*n));
    n->leaf = true;
    n->n = (unsigned)(count < BVH_LEAF ? count : BVH_LEAF);
    for (unsigned i = 0; i < n->n; i++)
        n->prim[i] = prims[i].primID;
    return n;
}

void dirt_ref_bvh_destroy(dirt_ref_bvh *b)
{
    if (!b)
        return;
    if (b->bvh)
        rtcReleaseBVH(b->bvh);
    if (b->device)
        rtcReleaseDevice(b->device);
    free(b->position);
    free(b);
}

dirt_ref_bvh *dirt_ref_bvh_create(const dirt_frame *frame)
{
    struct RTCBuildPrimitive *prims = NULL;
    dirt_ref_bvh *b = calloc(1, sizeof(*b));
    if (!b)
        goto oom;
    b->prims = frame->num_triangles;
    if (!b->prims)
        return b;
    b->position = malloc(b->prims * 3 * sizeof(*b->position));
    prims = malloc(b->prims * sizeof(*prims));
    if (!b->position || !prims)
        goto oom;
    memcpy(b->position, frame->position, b->prims * 3 * sizeof(*b->position));
    for (size_t i = 0; i < b->prims; i++) {
        const float(*p)[3] = &b->position[3 * i];
        struct RTCBuildPrimitive *q = &prims[i];
        q->lower_x = fminf(fminf(p[0][0], p[1][0]), p[2][0]);
        q->lower_y = fminf(fminf(p[0][1], p[1][1]), p[2][1]);
        q->lower_z = fminf(fminf(p[0][2], p[1][2]), p[2][2]);
        q->upper_x = fmaxf(fmaxf(p[0][0], p[1][0]), p[2][0]);
        q->upper_y = fmaxf(fmaxf(p[0][1], p[1][1]), p[2][1]);
        q->upper_z = fmaxf(fmaxf(p[0][2], p[1][2]), p[2][2]);
        q->geomID = 0;
        q->primID = (unsigned)i;
    }
    b->device = rtcNewDevice("verbose=0");
    if (!b->device) {
        DIRT_ERROR("rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        goto error;
    }
    b->bvh = rtcNewBVH(b->device);
    struct RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof(args);
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = BVH_WIDTH;
    args.minLeafSize = 1;
    args.maxLeafSize = BVH_LEAF;
    args.bvh = b->bvh;
    args.primitives = prims;
    args.primitiveCount = b->prims;
    args.primitiveArrayCapacity = b->prims;
    args.createNode = create_node;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    args.userPtr = b;
    b->root = rtcBuildBVH(&args);
    free(prims);
    prims = NULL;
    if (!b->root) {
        DIRT_ERROR("rtcBuildBVH failed (error %d)", (int)rtcGetDeviceError(b->device));
        goto error;
    }
    return b;
oom:
    DIRT_ERROR("out of memory");
error:
    free(prims);
    dirt_ref_bvh_destroy(b);
    return NULL;
}

/* Entry parameter of box (lo, hi) over [t0, t1], or INFINITY when missed. */
static float box_enter(const float lo[3], const float hi[3], const float org[3],
                       const float inv[3], float t0, float t1)
{
    for (int k = 0; k < 3; k++) {
        float a = (lo[k] - org[k]) * inv[k], b = (hi[k] - org[k]) * inv[k];
        if (a > b) {
            float s = a;
            a = b;
            b = s;
        }
        /* NaN (0 * inf: the origin on a slab plane of a parallel axis)
         * keeps the interval. */
        if (a > t0)
            t0 = a;
        if (b < t1)
            t1 = b;
    }
    return t0 <= t1 ? t0 : INFINITY;
}

/* Moller-Trumbore in double; t in (tmin, tmax). */
static bool tri_hit(const float (*p)[3], const dirt_ref_ray *r, float tmin, float tmax,
                    dirt_ref_hit *h)
{
    double e1[3], e2[3], s[3], pv[3], qv[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p[1][k] - p[0][k];
        e2[k] = (double)p[2][k] - p[0][k];
        s[k] = (double)r->org[k] - p[0][k];
    }
    pv[0] = r->dir[1] * e2[2] - r->dir[2] * e2[1];
    pv[1] = r->dir[2] * e2[0] - r->dir[0] * e2[2];
    pv[2] = r->dir[0] * e2[1] - r->dir[1] * e2[0];
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (det == 0)
        return false;
    double u = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) / det;
    if (u < 0 || u > 1)
        return false;
    qv[0] = s[1] * e1[2] - s[2] * e1[1];
    qv[1] = s[2] * e1[0] - s[0] * e1[2];
    qv[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (r->dir[0] * qv[0] + r->dir[1] * qv[1] + r->dir[2] * qv[2]) / det;
    if (v < 0 || u + v > 1)
        return false;
    double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    if (!(t >= tmin && t <= tmax))
        return false;
    h->t = (float)t;
    h->u = (float)u;
    h->v = (float)v;
    return true;
}

void dirt_ref_bvh_trace1(const dirt_ref_bvh *b, const dirt_ref_ray *r, bool any_hit,
                         dirt_ref_hit *hit, dirt_ref_work *work)
{
    dirt_ref_hit best = {.prim = DIRT_REF_MISS};
    dirt_ref_work w = {0};
    float tmax = r->tmax;
    if (b->root) {
        float inv[3];
        for (int k = 0; k < 3; k++)
            inv[k] = 1.0f / r->dir[k];
        const bvh_node *stack[BVH_STACK];
        float enter[BVH_STACK];
        int top = 0;
        stack[top] = b->root;
        enter[top++] = r->tmin;
        while (top > 0) {
            top--;
            const bvh_node *n = stack[top];
            if (enter[top] > tmax)
                continue; /* culled: the best hit lies before it */
            w.bvh_nodes++;
            if (n->leaf) {
                for (unsigned i = 0; i < n->n; i++) {
                    uint32_t p = n->prim[i];
                    dirt_ref_hit h;
                    w.triangle_tests++;
                    if (!tri_hit(&b->position[3 * p], r, r->tmin, tmax, &h))
                        continue;
                    if (h.t == tmax && best.prim != DIRT_REF_MISS && p > best.prim)
                        continue; /* ties go to the lower id */
                    h.prim = p;
                    best = h;
                    tmax = h.t;
                }
                if (any_hit && best.prim != DIRT_REF_MISS)
                    break;
                continue;
            }
            /* Children hit, pushed far to near so the nearest pops first. */
            float t[BVH_WIDTH];
            int order[BVH_WIDTH], m = 0;
            for (unsigned i = 0; i < n->n; i++) {
                t[i] = box_enter(n->lo[i], n->hi[i], r->org, inv, r->tmin, tmax);
                if (t[i] == INFINITY)
                    continue;
                int j = m++;
                while (j > 0 && t[order[j - 1]] < t[i]) {
                    order[j] = order[j - 1];
                    j--;
                }
                order[j] = (int)i;
            }
            for (int j = 0; j < m && top < BVH_STACK; j++) {
                stack[top] = n->child[order[j]];
                enter[top++] = t[order[j]];
            }
        }
    }
    if (hit)
        *hit = best;
    *work = w;
}

typedef struct trace_batch {
    const dirt_ref_bvh *b;
    const dirt_ref_ray *rays;
    bool any_hit;
    dirt_ref_hit *hits;
    dirt_ref_work *work;
} trace_batch;

static void trace_range(void *ctx, size_t begin, size_t end, int worker)
{
    trace_batch *t = ctx;
    (void)worker;
    for (size_t i = begin; i < end; i++)
        dirt_ref_bvh_trace1(t->b, &t->rays[i], t->any_hit, t->hits ? &t->hits[i] : NULL,
                            &t->work[i]);
}

void dirt_ref_bvh_trace(const dirt_ref_bvh *b, const dirt_ref_ray *rays, size_t count,
                        bool any_hit, dirt_ref_hit *hits, dirt_ref_work *work, int threads)
{
    trace_batch t = {b, rays, any_hit, hits, work};
    ref_parallel_for(count, 1024, threads, trace_range, &t);
}
