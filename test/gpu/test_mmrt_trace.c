/* MMRT trace (issue 7), against an exact CPU ray-triangle loop over the
 * frame:
 *  - targeted rays: from points around the camera towards known interior
 *    points of the quads (layered, behind the camera, walls, floor). Rays
 *    whose CPU closest hit is sampled finely enough by the view that marches
 *    it (by any view with all_views; the surface's depth changes by less
 *    than the thickness across a pixel there: MMRT's own sampling condition) and is laterally robust (8 rays
 *    shifted by two pixel footprints of the coarsest view agree on the
 *    primitive) must hit exactly that primitive with
 *    the Hi-Z walk and the conservative linear march; the jittered linear
 *    march (30 samples per view) is reported and held to >= 90 %;
 *  - thickness semantics: rays stopped half a thickness before a surface hit
 *    it (at their end) with the thickness and miss it without;
 *  - every hit of every mode (targeted rays, random rays through the quads
 *    scene and the default scene, single and cube+camera views) is a real
 *    surface within the thickness: the ray through the centre of the hit
 *    fragment's pixel meets the reported primitive there (the fragment
 *    exists), and the hit point's depth in the hit view is within the
 *    thickness of that surface point's depth; t in [tmin, tmax], the record's
 *    view/data node/barycentrics/depth consistent with the stored fragment.
 * Prints every count. */
#include <stdio.h>

#include "gpu.h"
#include "test_mmrt_common.h"

#define THICKNESS 0.02f

static float frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

/* CPU closest hit of ray (o, d) in [tmin, tmax], ignoring the two
 * triangles of quad `skip` (-1: none): primitive or DIRT_HIT_NONE. */
static uint32_t cpu_closest(const dirt_frame *f, const double o[3], const double d[3],
                            double tmin, double tmax, int skip, double *t_out)
{
    uint32_t best = DIRT_HIT_NONE;
    double bt = tmax;
    for (size_t p = 0; p < f->num_triangles; p++) {
        if (skip >= 0 && p / 2 == (size_t)skip)
            continue;
        float tri[3][3];
        mt_tri(f, p, tri);
        double t, u, v;
        if (!mt_ray_plane(o, d, tri, &t, &u, &v))
            continue;
        if (u >= 0 && v >= 0 && u + v <= 1 && t >= tmin && t < bt) {
            bt = t;
            best = (uint32_t)p;
        }
    }
    if (t_out)
        *t_out = bt;
    return best;
}

/* Largest pixel footprint (world units) of any view at world point p. */
static double footprint(const dirt_view_set *set, const double p[3])
{
    double fp = 0;
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        double c[4];
        mt_clip(v, p, c);
        if (c[3] <= v->znear)
            continue;
        fp = fmax(fp, c[3] * 2.0 / (v->proj[0] * v->width));
        fp = fmax(fp, c[3] * 2.0 / (v->proj[5] * v->height));
    }
    return fp;
}

/* True when world point p lies in some view's frustum, `margin` pixels
 * inside its sides. */
static bool in_views(const dirt_view_set *set, const double p[3], double margin)
{
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        double c[4];
        mt_clip(v, p, c);
        if (c[3] <= v->znear || c[3] >= v->zfar)
            continue;
        double mx = 2.0 * margin / v->width, my = 2.0 * margin / v->height;
        if (fabs(c[0] / c[3]) < 1 - mx && fabs(c[1] / c[3]) < 1 - my)
            return true;
    }
    return false;
}

/* True when some view samples the surface through world point p (unit
 * normal n) finely enough for the thickness: p inside the view (2 pixels
 * from its sides) and the surface's depth changing by at most `thickness`
 * across one pixel there (footprint * tan(angle to the view ray)). A ray
 * crossing the surface in that pixel then has the fragment within the
 * thickness of its depth span: MMRT's sampling condition. */
static bool resolvable(const dirt_view_set *set, const double p[3], const double n[3],
                       double thickness, bool owner_only)
{
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        double c[4];
        mt_clip(v, p, c);
        if (c[3] <= v->znear || c[3] >= v->zfar)
            continue;
        if (owner_only && i > 0) {
            /* With view switching only the first view holding p marches
             * the part of the ray around it. */
            bool earlier = false;
            for (int j = 0; j < i && !earlier; j++) {
                double cj[4];
                mt_clip(&set->views[j], p, cj);
                earlier = cj[3] > set->views[j].znear && cj[3] < set->views[j].zfar &&
                          fabs(cj[0]) <= cj[3] && fabs(cj[1]) <= cj[3];
            }
            if (earlier)
                return false;
        }
        if (fabs(c[0] / c[3]) > 1 - 4.0 / v->width || fabs(c[1] / c[3]) > 1 - 4.0 / v->height)
            continue;
        double e[3] = {p[0] - v->eye[0], p[1] - v->eye[1], p[2] - v->eye[2]};
        double el = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        double cs = fabs(e[0] * n[0] + e[1] * n[1] + e[2] * n[2]) / el;
        if (cs < 1e-6)
            continue;
        double fp = fmax(c[3] * 2.0 / (v->proj[0] * v->width), c[3] * 2.0 / (v->proj[5] * v->height));
        if (fp * sqrt(1 - cs * cs) / cs <= thickness)
            return true;
        if (owner_only)
            return false;
    }
    return false;
}

/* True when 8 copies of the ray shifted sideways by `delta` all have the
 * same CPU closest primitive `prim` (ignoring quad `skip`, the one a bounce
 * ray leaves: shifted copies may start behind it). */
static bool robust(const dirt_frame *f, const double o[3], const double d[3], double tmax,
                   double delta, uint32_t prim, int skip)
{
    double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double n[3] = {d[0] / dl, d[1] / dl, d[2] / dl};
    double a[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0};
    double e1[3] = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]};
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++)
        e1[k] /= l1;
    double e2[3] = {n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2],
                    n[0] * e1[1] - n[1] * e1[0]};
    for (int s = 0; s < 8; s++) {
        double ang = s * 0.78539816339744831;
        double so[3];
        for (int k = 0; k < 3; k++)
            so[k] = o[k] + delta * (cos(ang) * e1[k] + sin(ang) * e2[k]);
        if (cpu_closest(f, so, d, 0, tmax, skip, NULL) != prim)
            return false;
    }
    return true;
}

typedef struct hit_report {
    uint64_t rays, hits, checked, bad_surface, bad_depth, bad_t, bad_record, no_fragment;
    double worst_depth_error; /* in units of the thickness */
} hit_report;

/* The thickness property and record consistency of every hit. */
static void check_hits(const dirt_view_set *set, const dirt_frame *f, const dirt_mmrt_data *d,
                       const dirt_ray *rays, const dirt_hit *hits, size_t n, float thickness,
                       hit_report *r)
{
    for (size_t i = 0; i < n; i++) {
        const dirt_hit *h = &hits[i];
        r->rays++;
        if (h->owner != i)
            r->bad_record++;
        if (h->prim == DIRT_HIT_NONE)
            continue;
        r->hits++;
        if (h->prim >= f->num_triangles || h->next >= d->num_nodes) {
            r->bad_record++;
            continue;
        }
        const dirt_mmrt_data_node *dn = &d->data[h->next];
        int x, y, vi = mt_view_of(set, dn->pixel, &x, &y);
        if (vi < 0 || (uint32_t)vi != h->view || dn->prim != h->prim || dn->u != h->u ||
            dn->v != h->v || d->ids[h->next].z != h->reserved) {
            r->bad_record++;
            continue;
        }
        if (!(h->t >= rays[i].tmin && h->t <= rays[i].tmax))
            r->bad_t++;
        const dirt_view *v = &set->views[vi];
        float tri[3][3];
        mt_tri(f, h->prim, tri);
        double zs;
        if (mt_coverage(v, tri, x, y, 0.01, &zs) == 0) {
            r->no_fragment++; /* the pixel centre's ray misses the primitive */
            continue;
        }
        r->checked++;
        double p[3], c[4];
        for (int k = 0; k < 3; k++)
            p[k] = (double)rays[i].org[k] + (double)h->t * rays[i].dir[k];
        mt_clip(v, p, c);
        double err = fabs(c[3] - zs);
        double tol = thickness + 2e-5 * zs + 1e-5;
        if (err > tol)
            r->bad_depth++;
        if (fabs(h->reserved - zs) > 1e-5 * zs + 1e-6)
            r->bad_surface++;
        r->worst_depth_error = fmax(r->worst_depth_error, err / thickness);
    }
}

static const char *march_name(const dirt_mmrt_trace_opts *o)
{
    return o->march == DIRT_MMRT_MARCH_HIZ ? (o->all_views ? "hi-z-all" : "hi-z")
           : o->samples < 0 ? "linear-cons" : "linear-30";
}

static void print_hits(const char *label, const char *mode, const char *march,
                       const hit_report *r, const dirt_mmrt_trace_stats *st)
{
    fprintf(stderr,
            "%-9s %-11s %-11s: %5llu rays, %5llu hits, %5llu checked | surface %llu depth %llu "
            "t %llu record %llu no-fragment %llu | worst depth error %.2f thickness | "
            "steps %llu pixels %llu nodes %llu aborted %llu\n",
            label, mode, march, (unsigned long long)r->rays, (unsigned long long)r->hits,
            (unsigned long long)r->checked, (unsigned long long)r->bad_surface,
            (unsigned long long)r->bad_depth, (unsigned long long)r->bad_t,
            (unsigned long long)r->bad_record, (unsigned long long)r->no_fragment,
            r->worst_depth_error, (unsigned long long)st->steps,
            (unsigned long long)st->pixels_tested,
            (unsigned long long)st->nodes_visited, (unsigned long long)st->aborted);
    CHECK(r->checked > 0 && r->hits > 0);
    CHECK(r->bad_surface == 0);
    CHECK(r->bad_depth == 0);
    CHECK(r->bad_t == 0);
    CHECK(r->bad_record == 0);
    CHECK(r->no_fragment == 0);
    CHECK(st->aborted == 0);
}

#define NMARCH 4
static const dirt_mmrt_trace_opts marches[NMARCH] = {
    {.march = DIRT_MMRT_MARCH_HIZ, .thickness = THICKNESS, .count = true},
    {.march = DIRT_MMRT_MARCH_HIZ, .thickness = THICKNESS, .count = true, .all_views = true},
    {.march = DIRT_MMRT_MARCH_LINEAR, .samples = -1, .thickness = THICKNESS, .count = true},
    {.march = DIRT_MMRT_MARCH_LINEAR, .samples = 30, .thickness = THICKNESS, .seed = 7,
     .count = true},
};

/* Targeted rays: from near the camera to interior points of every quad. */
static size_t targeted_rays(const dirt_frame *f, int nquads, dirt_ray *out, size_t max)
{
    static const float frac[6][2] = {{0.23f, 0.61f}, {0.71f, 0.37f}, {0.15f, 0.45f},
                                     {0.62f, 0.88f}, {0.81f, 0.52f}, {0.38f, 0.09f}};
    unsigned seed = 12345;
    size_t n = 0;
    for (int q = 0; q < nquads; q++) {
        const float *c0 = f->position[6 * q], *c1 = f->position[6 * q + 1];
        const float *c3 = f->position[6 * q + 5];
        for (int k = 0; k < 6; k++) {
            for (int j = 0; j < 4 && n < max; j++) {
                float target[3], org[3];
                for (int a = 0; a < 3; a++) {
                    target[a] = c0[a] + frac[k][0] * (c1[a] - c0[a]) + frac[k][1] * (c3[a] - c0[a]);
                    org[a] = 0.6f * (frand(&seed) - 0.5f);
                }
                dirt_ray *r = &out[n++];
                for (int a = 0; a < 3; a++) {
                    r->org[a] = org[a];
                    r->dir[a] = target[a] - org[a];
                }
                r->tmin = 0;
                r->tmax = 1.5f;
            }
        }
    }
    return n;
}

/* Bounce rays: from interior points of one quad (moved 3 thicknesses off
 * its front side) towards interior points of other quads in front of it,
 * leaving at least 17 degrees off the plane. */
static size_t bounce_rays(const dirt_frame *f, int nquads, const mt_quad *quads, dirt_ray *out,
                          int *from, size_t max)
{
    unsigned seed = 777;
    size_t n = 0;
    for (int tries = 0; tries < 100000 && n < max; tries++) {
        int qa = (int)(frand(&seed) * nquads) % nquads, qb = (int)(frand(&seed) * nquads) % nquads;
        if (qa == qb)
            continue;
        float pa[3], pb[3];
        const float *a0 = f->position[6 * qa], *a1 = f->position[6 * qa + 1], *a3 = f->position[6 * qa + 5];
        const float *b0 = f->position[6 * qb], *b1 = f->position[6 * qb + 1], *b3 = f->position[6 * qb + 5];
        float ua = 0.1f + 0.8f * frand(&seed), va = 0.1f + 0.8f * frand(&seed);
        float ub = 0.1f + 0.8f * frand(&seed), vb = 0.1f + 0.8f * frand(&seed);
        for (int k = 0; k < 3; k++) {
            pa[k] = a0[k] + ua * (a1[k] - a0[k]) + va * (a3[k] - a0[k]);
            pb[k] = b0[k] + ub * (b1[k] - b0[k]) + vb * (b3[k] - b0[k]);
        }
        int ax = quads[qa].axis;
        pa[ax] += 3 * THICKNESS * quads[qa].facing;
        float d[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (d[ax] * quads[qa].facing < 0.3f * len)
            continue;
        from[n] = qa;
        dirt_ray *r = &out[n++];
        memcpy(r->org, pa, sizeof(pa));
        memcpy(r->dir, d, sizeof(d));
        r->tmin = 0;
        r->tmax = 1.5f;
    }
    return n;
}

static size_t random_rays(const dirt_frame *f, unsigned seed, dirt_ray *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        dirt_ray *r = &out[i];
        for (int a = 0; a < 3; a++) {
            float lo = f->bounds_min[a], hi = f->bounds_max[a];
            r->org[a] = lo + (0.1f + 0.8f * frand(&seed)) * (hi - lo);
        }
        float z = 2 * frand(&seed) - 1, phi = 6.2831853f * frand(&seed), s = sqrtf(1 - z * z);
        r->dir[0] = s * cosf(phi);
        r->dir[1] = s * sinf(phi);
        r->dir[2] = z;
        r->tmin = 0;
        r->tmax = INFINITY;
    }
    return n;
}

/* Traces `rays` with every march mode; checks hits; for targeted rays also
 * the primitive agreement on robust rays. */
static void run(dirt_gpu *gpu, const char *label, const dirt_frame *f, const dirt_camera *cam,
                enum dirt_view_mode mode, int size, const dirt_ray *rays, size_t n, bool targeted,
                const int *from)
{
    dirt_mmrt_opts o = {.views = {.mode = mode, .width = size, .height = size * 3 / 4,
                                  .face_size = size},
                        .buckets = 4};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
    CHECK(m != NULL);
    if (!m)
        return;
    bool ok = dirt_mmrt_build(m, f, cam);
    CHECK(ok);
    dirt_mmrt_data d;
    if (!ok || !dirt_mmrt_read(m, &d)) {
        CHECK(false);
        dirt_mmrt_destroy(m);
        return;
    }
    const dirt_view_set *set = dirt_mmrt_views(m);
    /* CPU expectation and robustness of targeted rays. */
    uint32_t *expect = calloc(n, sizeof(uint32_t));
    uint8_t *is_robust = calloc(n, 1), *is_robust_any = calloc(n, 1);
    size_t nrobust = 0, nrobust_any = 0;
    if (targeted) {
        for (size_t i = 0; i < n; i++) {
            double org[3] = {rays[i].org[0], rays[i].org[1], rays[i].org[2]};
            double dir[3] = {rays[i].dir[0], rays[i].dir[1], rays[i].dir[2]};
            double t;
            int skip = from ? from[i] : -1;
            expect[i] = cpu_closest(f, org, dir, rays[i].tmin, rays[i].tmax, -1, &t);
            if (expect[i] == DIRT_HIT_NONE)
                continue;
            double hp[3];
            for (int k = 0; k < 3; k++)
                hp[k] = org[k] + t * dir[k];
            double delta = 2.0 * fmax(footprint(set, hp), footprint(set, org));
            float tri[3][3];
            mt_tri(f, expect[i], tri);
            double e1[3], e2[3];
            for (int k = 0; k < 3; k++) {
                e1[k] = (double)tri[1][k] - tri[0][k];
                e2[k] = (double)tri[2][k] - tri[0][k];
            }
            double nn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
            double nl = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            for (int k = 0; k < 3; k++)
                nn[k] /= nl;
            bool lateral = in_views(set, hp, 3.0) &&
                           robust(f, org, dir, rays[i].tmax, delta, expect[i], skip);
            is_robust[i] = lateral && resolvable(set, hp, nn, THICKNESS, true);
            is_robust_any[i] = lateral && resolvable(set, hp, nn, THICKNESS, false);
            nrobust += is_robust[i];
            nrobust_any += is_robust_any[i];
        }
    }
    dirt_hit *hits = calloc(n, sizeof(*hits));
    for (int k = 0; k < NMARCH; k++) {
        dirt_mmrt_trace_stats st;
        ok = dirt_mmrt_trace_cpu(m, rays, n, hits, &marches[k], &st);
        CHECK(ok);
        if (!ok)
            continue;
        CHECK(st.thickness == THICKNESS);
        hit_report r = {0};
        check_hits(set, f, &d, rays, hits, n, THICKNESS, &r);
        print_hits(label, mt_mode_name(mode), march_name(&marches[k]), &r, &st);
        CHECK(st.hits == r.hits);
        if (targeted) {
            const uint8_t *rob = marches[k].all_views ? is_robust_any : is_robust;
            size_t nrob = marches[k].all_views ? nrobust_any : nrobust;
            size_t agree = 0, missed = 0, cpu_hits = 0, agree_all = 0;
            for (size_t i = 0; i < n; i++) {
                cpu_hits += expect[i] != DIRT_HIT_NONE;
                agree_all += expect[i] != DIRT_HIT_NONE && hits[i].prim == expect[i];
                if (!rob[i])
                    continue;
                agree += hits[i].prim == expect[i];
                missed += hits[i].prim == DIRT_HIT_NONE;
            }
            fprintf(stderr, "          agreement: %zu rays, %zu sampled+robust: %zu hit the CPU's "
                    "primitive (%.2f %%), %zu missed | all %zu CPU hits: %.2f %% agree\n", n,
                    nrob, agree, nrob ? 100.0 * agree / nrob : 0.0, missed, cpu_hits,
                    cpu_hits ? 100.0 * agree_all / cpu_hits : 0.0);
            CHECK(nrob * 4 > n);
            if (k < 3)
                CHECK(agree == nrob);
            else
                CHECK(agree * 10 >= nrob * 9);
        }
    }
    /* The default thickness is 0.2 % of the scene diagonal. */
    dirt_mmrt_trace_stats st;
    CHECK(dirt_mmrt_trace_cpu(m, rays, 1, hits, NULL, &st));
    const float *lo = f->bounds_min, *hi = f->bounds_max;
    float diag = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    CHECK_NEAR(st.thickness, 0.002 * diag, 1e-5 * diag);
    free(hits);
    free(expect);
    free(is_robust);
    free(is_robust_any);
    dirt_mmrt_data_free(&d);
    dirt_mmrt_destroy(m);
}

/* Thickness semantics: rays from the camera's eye towards interior points
 * of the quads facing it, stopped half a thickness (in depth) before the
 * surface, must hit it with the thickness (at t = tmax, the end of their
 * span) in every march mode, and hit nothing with thickness 0. */
static void short_rays(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam,
                       const mt_quad *quads, int nquads)
{
    static const float frac[6][2] = {{0.23f, 0.61f}, {0.71f, 0.37f}, {0.62f, 0.88f},
                                     {0.38f, 0.09f}, {0.15f, 0.45f}, {0.81f, 0.52f}};
    dirt_ray rays[64 * 6];
    uint32_t expect[64 * 6];
    const double cam_px = 1.0 / tan(0.5 * cam->yfov); /* proj[5] of the camera view */
    size_t n = 0;
    for (int q = 0; q < nquads && q < 64; q++) {
        if (quads[q].axis != 2 || quads[q].facing < 0)
            continue;
        const float *c0 = f->position[6 * q], *c1 = f->position[6 * q + 1];
        const float *c3 = f->position[6 * q + 5];
        for (int k = 0; k < 6; k++) {
            double tg[3], o[3] = {0, 0, 0}, d[3], t;
            for (int a = 0; a < 3; a++)
                tg[a] = c0[a] + frac[k][0] * (c1[a] - c0[a]) + frac[k][1] * (c3[a] - c0[a]);
            for (int a = 0; a < 3; a++)
                d[a] = tg[a] / -tg[2]; /* t = depth along the camera axis */
            uint32_t p = cpu_closest(f, o, d, 0, 1e30, -1, &t);
            if (p == DIRT_HIT_NONE || quads[p / 2].axis != 2 ||
                !robust(f, o, d, 1e30, 2.0 * t * 2.0 / (cam_px * 72), p, -1))
                continue;
            dirt_ray *r = &rays[n];
            for (int a = 0; a < 3; a++) {
                r->org[a] = 0;
                r->dir[a] = (float)d[a];
            }
            r->tmin = 0;
            r->tmax = (float)(t - 0.5 * THICKNESS);
            expect[n++] = p;
        }
    }
    dirt_mmrt_opts o = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = 96, .height = 72},
                        .buckets = 4};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
    CHECK(m && dirt_mmrt_build(m, f, cam));
    if (!m)
        return;
    dirt_hit hits[64 * 6];
    for (int k = 0; k < NMARCH; k++) {
        size_t good = 0, none = 0;
        dirt_mmrt_trace_opts to = marches[k];
        CHECK(dirt_mmrt_trace_cpu(m, rays, n, hits, &to, NULL));
        for (size_t i = 0; i < n; i++)
            good += hits[i].prim == expect[i] && fabsf(hits[i].t - rays[i].tmax) < 1e-4f;
        to.thickness = -1;
        CHECK(dirt_mmrt_trace_cpu(m, rays, n, hits, &to, NULL));
        for (size_t i = 0; i < n; i++)
            none += hits[i].prim == DIRT_HIT_NONE;
        fprintf(stderr, "short     single      %-11s: %zu rays stopped 0.5 thickness before a "
                "surface: %zu hit it at tmax, %zu miss with thickness 0\n",
                march_name(&marches[k]), n, good, none);
        CHECK(n > 15 && good == n && none == n);
    }
    dirt_mmrt_destroy(m);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    /* The quads of test_mmrt_store without the deep stack, plus a short
     * stack of three layers 0.1 apart. */
    static const mt_quad quads[] = {
        {2, -2.13f, -0.91f, 0.37f, -0.52f, 0.66f, 1},
        {2, -2.77f, -0.43f, 1.21f, -0.87f, 0.29f, 1},
        {2, -3.41f, -1.63f, 0.58f, -0.31f, 1.47f, 1},
        {2, -4.06f, -2.2f, 2.47f, -1.9f, 2.03f, 1},
        {2, -5.29f, -3.9f, 3.7f, -3.3f, 3.1f, 1},
        {2, 2.41f, -1.3f, 1.7f, -1.1f, 0.9f, -1},
        {0, -2.61f, -1.2f, 1.3f, -3.5f, 1.9f, 1},
        {1, -1.73f, -6.2f, 2.6f, -2.9f, 3.3f, 1},
        {0, 3.07f, -0.8f, 2.2f, -2.4f, 0.7f, -1},
        {2, -4.31f, 0.41f, 1.43f, -0.97f, -0.23f, 1},
        {2, -4.41f, 0.37f, 1.31f, -1.07f, -0.13f, 1},
        {2, -4.51f, 0.33f, 1.19f, -1.17f, -0.03f, 1},
    };
    const int nq = (int)(sizeof(quads) / sizeof(quads[0]));
    dirt_frame *f = mt_frame_new(2 * (size_t)nq);
    for (int q = 0; q < nq; q++)
        mt_add_quad(f, &quads[q]);
    mt_frame_bounds(f);
    dirt_camera cam = {.type = DIRT_CAMERA_PERSPECTIVE, .yfov = 1.0471976f, .znear = 0.05f};
    dirt_camera_look_at(&cam, (const float[3]){0, 0, 0}, (const float[3]){0, 0, -1},
                        (const float[3]){0, 1, 0});

    enum { NT = 12 * 6 * 4, NB = 600, NR = 1500 };
    dirt_ray *rays = calloc(NR, sizeof(*rays));
    size_t nt = targeted_rays(f, nq, rays, NT);
    short_rays(gpu, f, &cam, quads, nq);
    run(gpu, "targeted", f, &cam, DIRT_VIEWS_SINGLE, 96, rays, nt, true, NULL);
    run(gpu, "targeted", f, &cam, DIRT_VIEWS_CUBE_CAMERA, 96, rays, nt, true, NULL);
    int from[NB];
    nt = bounce_rays(f, nq, quads, rays, from, NB);
    run(gpu, "bounce", f, &cam, DIRT_VIEWS_SINGLE, 96, rays, nt, true, from);
    run(gpu, "bounce", f, &cam, DIRT_VIEWS_CUBE_CAMERA, 96, rays, nt, true, from);
    random_rays(f, 99, rays, NR);
    run(gpu, "random", f, &cam, DIRT_VIEWS_SINGLE, 96, rays, NR, false, NULL);
    run(gpu, "random", f, &cam, DIRT_VIEWS_CUBE_CAMERA, 96, rays, NR, false, NULL);
    mt_frame_free(f);

    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    if (scene) {
        dirt_frame *df = dirt_scene_evaluate(scene, 0, NULL);
        dirt_camera dc;
        dirt_camera_default(df, &dc);
        random_rays(df, 5, rays, NR);
        run(gpu, "default", df, &dc, DIRT_VIEWS_CUBE_CAMERA, 96, rays, NR, false, NULL);
        dirt_frame_destroy(df);
        dirt_scene_destroy(scene);
    }
    free(rays);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
