/* DIRT engine, src/ref: Embree 3 BVH over one dirt_frame and ray queries.
 *
 * One triangle geometry (geomID 0) holds every triangle of the frame in
 * order, so Embree's primID is the frame's primitive id. */
#include "ref/ref.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/clock.h"
#include "integrator/integrator.h"
#include "dirt/log.h"
#include "ref/parallel.h"

struct dirt_ref_accel {
    RTCDevice device;
    RTCScene scene;
    const float *vertices; /* Embree-owned copy: 3 floats per vertex, 3 vertices per triangle */
    size_t prims;
    bool high_quality;
    dirt_ref_build_stats stats;
    /* Alpha test (opts.alpha): the borrowed materials and, per build, the
     * frame's per-triangle materials and UVs (copies; NULL when no triangle
     * is alpha-tested: then no filter is installed). */
    dirt_ref_materials alpha;
    bool has_alpha;
    uint32_t *alpha_material; /* per triangle */
    float *alpha_uv;          /* 6 per triangle: (u, v) of its 3 vertices; 0 without UVs */
};

/* The intersect context of a query, extended by the ray's alpha key (the
 * filter function casts the context back). */
typedef struct alpha_context {
    struct RTCIntersectContext ctx; /* first member */
    uint32_t key;
} alpha_context;

/* Embree filter (intersection and occlusion): rejects the hits that the
 * alpha test does not accept (valid[i] = 0 makes Embree go on). */
static void alpha_filter(const struct RTCFilterFunctionNArguments *args)
{
    const dirt_ref_accel *a = args->geometryUserPtr;
    const alpha_context *c = (const alpha_context *)args->context;
    for (unsigned i = 0; i < args->N; i++) {
        if (args->valid[i] != -1)
            continue;
        /* RTCHitN is SoA (Ng x/y/z, u, v, primID, ...; rtcore_ray.h's
         * RTCHitN_* accessors, C++ only). */
        const float *hf = (const float *)args->hit;
        uint32_t p = ((const uint32_t *)args->hit)[5 * args->N + i];
        if (p >= a->prims)
            continue;
        const dirt_material *m = &a->alpha.materials[a->alpha_material[p]];
        if (!dirt_material_alpha_tested(m))
            continue;
        /* UV as tri_uv of render.c: b0 t0 + b1 t1 + b2 t2. */
        float b1 = hf[3 * args->N + i], b2 = hf[4 * args->N + i];
        float b0 = 1.0f - b1 - b2;
        const float *t = a->alpha_uv + 6 * (size_t)p;
        float u = b0 * t[0] + b1 * t[2] + b2 * t[4];
        float v = b0 * t[1] + b1 * t[3] + b2 * t[5];
        if (!dirt_alpha_accept(m, a->alpha.textures, a->alpha.num_textures, u, v, c->key, p))
            args->valid[i] = 0;
    }
}

/* Copies the frame's per-triangle materials and UVs when a triangle is
 * alpha-tested (a->has_alpha). False after logging (out of memory, a
 * material index out of range). */
static bool alpha_setup(dirt_ref_accel *a, const dirt_frame *frame)
{
    free(a->alpha_material);
    free(a->alpha_uv);
    a->alpha_material = NULL;
    a->alpha_uv = NULL;
    a->has_alpha = false;
    size_t n = frame ? frame->num_triangles : 0;
    if (!a->alpha.materials || n == 0 ||
        !dirt_materials_alpha_tested(a->alpha.materials, a->alpha.num_materials))
        return true;
    bool any = false;
    for (size_t p = 0; p < n; p++) {
        if (frame->material[p] >= a->alpha.num_materials) {
            DIRT_ERROR("accel: triangle %zu has material %u, the alpha materials are %zu", p,
                       frame->material[p], a->alpha.num_materials);
            return false;
        }
        any = any || dirt_material_alpha_tested(&a->alpha.materials[frame->material[p]]);
    }
    if (!any)
        return true;
    a->alpha_material = malloc(n * sizeof(uint32_t));
    a->alpha_uv = calloc(6 * n, sizeof(float));
    if (!a->alpha_material || !a->alpha_uv) {
        DIRT_ERROR("out of memory for the alpha test of %zu triangles", n);
        return false;
    }
    memcpy(a->alpha_material, frame->material, n * sizeof(uint32_t));
    if (frame->uv)
        memcpy(a->alpha_uv, frame->uv, 3 * n * sizeof(float[2]));
    a->has_alpha = true;
    return true;
}

static void embree_error(void *user, enum RTCError code, const char *str)
{
    (void)user;
    DIRT_ERROR("Embree error %d: %s", (int)code, str ? str : "(no message)");
}

/* Replaces the accel's scene with a BVH over `frame`; on failure the scene
 * is an empty committed scene (or NULL when even that failed). */
static bool build(dirt_ref_accel *a, const dirt_frame *frame)
{
    double t0 = dirt_clock_ms();
    if (a->scene) {
        rtcReleaseScene(a->scene);
        a->scene = NULL;
    }
    a->vertices = NULL;
    a->prims = 0;
    memset(&a->stats, 0, sizeof(a->stats));

    a->scene = rtcNewScene(a->device);
    if (!a->scene) {
        DIRT_ERROR("rtcNewScene failed");
        return false;
    }
    rtcSetSceneFlags(a->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(a->scene, a->high_quality ? RTC_BUILD_QUALITY_HIGH
                                                      : RTC_BUILD_QUALITY_MEDIUM);
    size_t n = frame ? frame->num_triangles : 0;
    if (n > UINT32_MAX / 3) {
        DIRT_ERROR("frame has %zu triangles; the reference supports at most %u", n,
                   UINT32_MAX / 3);
        rtcCommitScene(a->scene);
        return false;
    }
    if (n > 0) {
        RTCGeometry g = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!g) {
            DIRT_ERROR("rtcNewGeometry failed");
            rtcCommitScene(a->scene);
            return false;
        }
        float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                           3 * sizeof(float), 3 * n);
        uint32_t *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                3 * sizeof(uint32_t), n);
        if (!v || !idx) {
            DIRT_ERROR("Embree could not allocate buffers for %zu triangles", n);
            rtcReleaseGeometry(g);
            rtcCommitScene(a->scene);
            return false;
        }
        memcpy(v, frame->position, 3 * n * sizeof(float[3]));
        for (size_t i = 0; i < 3 * n; i++)
            idx[i] = (uint32_t)i;
        if (!alpha_setup(a, frame)) {
            rtcReleaseGeometry(g);
            rtcCommitScene(a->scene);
            return false;
        }
        if (a->has_alpha) {
            rtcSetGeometryUserData(g, a);
            rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
            rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
        }
        rtcCommitGeometry(g);
        unsigned id = rtcAttachGeometry(a->scene, g);
        rtcReleaseGeometry(g);
        if (id != 0) {
            DIRT_ERROR("Embree gave geometry id %u, expected 0", id);
            rtcCommitScene(a->scene);
            return false;
        }
        a->vertices = v;
    }
    double t1 = dirt_clock_ms();
    rtcCommitScene(a->scene);
    double t2 = dirt_clock_ms();
    enum RTCError err = rtcGetDeviceError(a->device);
    if (err != RTC_ERROR_NONE) {
        DIRT_ERROR("Embree BVH build of %zu triangles failed (error %d)", n, (int)err);
        rtcReleaseScene(a->scene);
        a->scene = NULL;
        a->vertices = NULL;
        return false;
    }
    a->prims = n;
    a->stats.prims = n;
    a->stats.upload_ms = t1 - t0;
    a->stats.build_ms = t2 - t1;
    a->stats.mprims_per_s = a->stats.build_ms > 0.0 ? (double)n / (a->stats.build_ms * 1e3) : 0.0;
    return true;
}

dirt_ref_accel *dirt_ref_accel_create(const dirt_frame *frame,
                                      const dirt_ref_accel_opts *opts)
{
    dirt_ref_accel_opts o = {0};
    char config[64];
    if (opts)
        o = *opts;
    if (!frame) {
        DIRT_ERROR("dirt_ref_accel_create: frame is NULL");
        return NULL;
    }
    dirt_ref_accel *a = calloc(1, sizeof(*a));
    if (!a) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    a->high_quality = o.high_quality;
    if (o.alpha)
        a->alpha = *o.alpha;
    if (o.threads > 0)
        snprintf(config, sizeof(config), "threads=%d,verbose=0", o.threads);
    else
        snprintf(config, sizeof(config), "verbose=0");
    a->device = rtcNewDevice(config);
    if (!a->device) {
        DIRT_ERROR("rtcNewDevice(\"%s\") failed (error %d)", config, (int)rtcGetDeviceError(NULL));
        goto error;
    }
    rtcSetDeviceErrorFunction(a->device, embree_error, NULL);
    if (!build(a, frame))
        goto error;
    return a;

error:
    dirt_ref_accel_destroy(a);
    return NULL;
}

bool dirt_ref_accel_update(dirt_ref_accel *accel, const dirt_frame *frame)
{
    if (!accel || !frame) {
        DIRT_ERROR("dirt_ref_accel_update: NULL argument");
        return false;
    }
    return build(accel, frame);
}

void dirt_ref_accel_destroy(dirt_ref_accel *accel)
{
    if (!accel)
        return;
    if (accel->scene)
        rtcReleaseScene(accel->scene);
    if (accel->device)
        rtcReleaseDevice(accel->device);
    free(accel->alpha_material);
    free(accel->alpha_uv);
    free(accel);
}

void dirt_ref_accel_stats(const dirt_ref_accel *accel, dirt_ref_build_stats *out)
{
    *out = accel->stats;
}

size_t dirt_ref_accel_num_prims(const dirt_ref_accel *accel)
{
    return accel->prims;
}

static void fill_ray(struct RTCRay *r, const dirt_ref_ray *ray)
{
    r->org_x = ray->org[0];
    r->org_y = ray->org[1];
    r->org_z = ray->org[2];
    r->tnear = ray->tmin;
    r->dir_x = ray->dir[0];
    r->dir_y = ray->dir[1];
    r->dir_z = ray->dir[2];
    r->time = 0.0f;
    r->tfar = ray->tmax;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

bool dirt_ref_intersect1(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                         dirt_ref_hit *hit)
{
    return dirt_ref_intersect1_key(accel, ray, 0, hit);
}

bool dirt_ref_intersect1_key(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                             uint32_t alpha_key, dirt_ref_hit *hit)
{
    hit->prim = DIRT_REF_MISS;
    if (!accel->scene || accel->prims == 0)
        return false;
    alpha_context ac;
    rtcInitIntersectContext(&ac.ctx);
    ac.key = alpha_key;
    struct RTCRayHit rh;
    fill_ray(&rh.ray, ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(accel->scene, &ac.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || rh.hit.primID >= accel->prims)
        return false;
    uint32_t p = rh.hit.primID;
    hit->prim = p;
    hit->t = rh.ray.tfar;
    hit->u = rh.hit.u;
    hit->v = rh.hit.v;
    const float *v0 = accel->vertices + 9 * (size_t)p;
    float e1[3], e2[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = v0[3 + i] - v0[i];
        e2[i] = v0[6 + i] - v0[i];
    }
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    float s = l > 0.0f ? 1.0f / l : 0.0f;
    hit->ng[0] = n[0] * s;
    hit->ng[1] = n[1] * s;
    hit->ng[2] = n[2] * s;
    return true;
}

bool dirt_ref_occluded1(const dirt_ref_accel *accel, const dirt_ref_ray *ray)
{
    return dirt_ref_occluded1_key(accel, ray, 0);
}

bool dirt_ref_occluded1_key(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                            uint32_t alpha_key)
{
    if (!accel->scene || accel->prims == 0)
        return false;
    alpha_context ac;
    rtcInitIntersectContext(&ac.ctx);
    ac.key = alpha_key;
    struct RTCRay r;
    fill_ray(&r, ray);
    rtcOccluded1(accel->scene, &ac.ctx, &r);
    return r.tfar == -INFINITY;
}

bool dirt_ref_accel_alpha_tested(const dirt_ref_accel *accel)
{
    return accel->has_alpha;
}

typedef struct batch {
    const dirt_ref_accel *accel;
    const dirt_ref_ray *rays;
    const uint32_t *keys;
    dirt_ref_hit *hits;
    uint8_t *occluded;
} batch;

static void intersect_range(void *ctx, size_t begin, size_t end, int worker)
{
    batch *b = ctx;
    (void)worker;
    for (size_t i = begin; i < end; i++)
        dirt_ref_intersect1_key(b->accel, &b->rays[i], b->keys ? b->keys[i] : 0, &b->hits[i]);
}

static void occluded_range(void *ctx, size_t begin, size_t end, int worker)
{
    batch *b = ctx;
    (void)worker;
    for (size_t i = begin; i < end; i++)
        b->occluded[i] =
            dirt_ref_occluded1_key(b->accel, &b->rays[i], b->keys ? b->keys[i] : 0) ? 1 : 0;
}

void dirt_ref_intersect(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                        dirt_ref_hit *hits, size_t count, int threads)
{
    dirt_ref_intersect_keys(accel, rays, NULL, hits, count, threads);
}

void dirt_ref_occluded(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                       uint8_t *occluded, size_t count, int threads)
{
    dirt_ref_occluded_keys(accel, rays, NULL, occluded, count, threads);
}

void dirt_ref_intersect_keys(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                             const uint32_t *keys, dirt_ref_hit *hits, size_t count,
                             int threads)
{
    batch b = {accel, rays, keys, hits, NULL};
    ref_parallel_for(count, 1024, threads, intersect_range, &b);
}

void dirt_ref_occluded_keys(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                            const uint32_t *keys, uint8_t *occluded, size_t count,
                            int threads)
{
    batch b = {accel, rays, keys, NULL, occluded};
    ref_parallel_for(count, 1024, threads, occluded_range, &b);
}
