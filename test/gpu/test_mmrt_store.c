/* MMRT store completeness (issue 7). The CPU oracle is the exact coverage of
 * normal rasterization: triangle T stores a fragment in pixel p of view v
 * iff the ray through p's centre hits T between the view's near and far
 * planes (pixel centres within 0.01 px of an edge are left to the
 * rasterizer's snapping and tie rule and accepted either way). Checked:
 *  - every required (primitive, pixel) fragment stored, nothing else, no
 *    duplicate; its depth, barycentrics, uv, normal and material right;
 *  - inside each quad every pixel has exactly one fragment of its two
 *    triangles, the shared diagonal included (watertight);
 *  - structure: each node in exactly one list, in the bucket its depth maps
 *    to (uniform in linear depth between the pixel's bounds), lists sorted
 *    by (depth, primitive), prev/next consistent, tails the last nodes,
 *    pixel bounds exactly the min/max of the stored depths, Hi-Z pyramid
 *    equal to the CPU min/max pyramid;
 *  - overflow: a start from capacity 1 gives the same lists as an ample run;
 *  - both reorder sorts (registers, in-list) give the same lists;
 *  - past the GPU's storage block limit (12.3 M fragments, 393 MB of data
 *    nodes) the pools split (gl/split.h): the build keeps every fragment,
 *    and the object still builds a small frame afterwards.
 * Scenes: layered axis-aligned quads (sizes not multiples of anything, a
 * 37-deep stack that forces the chunked sort) in single and cube+camera
 * views, B in {1, 3, 8}; the default scene in cube+camera views. */
#include <stdio.h>

#include "dirt/log.h"

#include "common/mmrt_layout.h"
#include "gpu.h"
#include "test_mmrt_common.h"

/* Pixel centres this close to an edge (pixels) are left to the rasterizer:
 * vertex snapping (1/256 px on llvmpipe) and the tie rule. */
#define TOL_PX 0.01

typedef struct report {
    uint64_t pixels, fragments, required, ambiguous, found;
    uint64_t missing, extra, duplicates, bad_depth, bad_attr;
    uint64_t quad_pixels, diagonal_pixels, bad_watertight;
    uint64_t bad_link, bad_prev, bad_pixel, unsorted, bad_bucket, bad_bounds, bad_tail, lost;
    uint64_t bad_pyramid;
} report;

/* Fragments of each pixel: indices into the node arrays, grouped by pixel
 * (counting sort on the data nodes' pixel). */
typedef struct by_pixel {
    uint32_t *offsets; /* pixels + 1 */
    uint32_t *nodes;
} by_pixel;

static void group_by_pixel(const dirt_mmrt_data *d, by_pixel *bp)
{
    bp->offsets = calloc((size_t)d->num_pixels + 2, sizeof(uint32_t));
    bp->nodes = malloc(((size_t)d->num_nodes + 1) * sizeof(uint32_t));
    for (uint32_t n = 0; n < d->num_nodes; n++) {
        uint32_t g = d->data[n].pixel;
        if (g < (uint32_t)d->num_pixels)
            bp->offsets[g + 1]++;
    }
    for (int g = 0; g < d->num_pixels; g++)
        bp->offsets[g + 1] += bp->offsets[g];
    uint32_t *fill = calloc((size_t)d->num_pixels + 1, sizeof(uint32_t));
    for (uint32_t n = 0; n < d->num_nodes; n++) {
        uint32_t g = d->data[n].pixel;
        if (g < (uint32_t)d->num_pixels)
            bp->nodes[bp->offsets[g] + fill[g]++] = n;
    }
    free(fill);
}

/* The linked structure against its own invariants. */
static void check_structure(const dirt_view_set *set, const dirt_mmrt_data *d, report *r)
{
    const uint32_t P = (uint32_t)d->num_pixels, B = (uint32_t)d->buckets;
    uint8_t *seen = calloc((size_t)d->num_nodes + 1, 1);
    uint64_t visited = 0;
    for (uint32_t g = 0; g < P; g++) {
        float zmin = d->depth[g][0], zmax = d->depth[g][1];
        float lo = INFINITY, hi = 0;
        uint32_t count = 0;
        for (uint32_t b = 0; b < B; b++) {
            uint32_t slot = b * P + g, prev = DIRT_MMRT_END, n = d->heads[slot];
            while (n != DIRT_MMRT_END) {
                if (n >= d->num_nodes) {
                    r->bad_link++;
                    break;
                }
                if (seen[n]) {
                    r->bad_link++; /* a node in two lists, or a cycle */
                    break;
                }
                seen[n] = 1;
                visited++;
                count++;
                const dirt_mmrt_id_node *id = &d->ids[n];
                if (id->prev != prev)
                    r->bad_prev++;
                if (d->data[n].pixel != g)
                    r->bad_pixel++;
                if (prev != DIRT_MMRT_END) {
                    float zp = d->ids[prev].z;
                    if (zp > id->z || (zp == id->z && d->data[prev].prim >= d->data[n].prim))
                        r->unsorted++;
                }
                /* Bucket: floor(B (z - zmin) / range), clamped; within a
                 * hair of a bucket edge either side is accepted. */
                double range = (double)zmax - zmin;
                double x = range > 0 ? B * ((double)id->z - zmin) / range : 0.0;
                long b0 = (long)floor(x - 1e-4), b1 = (long)floor(x + 1e-4);
                b0 = b0 < 0 ? 0 : b0 > (long)B - 1 ? (long)B - 1 : b0;
                b1 = b1 < 0 ? 0 : b1 > (long)B - 1 ? (long)B - 1 : b1;
                if ((long)b < b0 || (long)b > b1)
                    r->bad_bucket++;
                if (id->z < zmin || id->z > zmax)
                    r->bad_bounds++;
                lo = fminf(lo, id->z);
                hi = fmaxf(hi, id->z);
                prev = n;
                n = id->next;
            }
            if (d->tails[slot] != prev)
                r->bad_tail++;
        }
        if (count ? (lo != zmin || hi != zmax) : (zmin != INFINITY || zmax != 0.0f))
            r->bad_bounds++;
    }
    r->lost += d->num_nodes - visited;
    free(seen);

    /* Hi-Z pyramid: level d = min/max over the (up to) 2x2 children. */
    for (int lv = 1; lv < set->num_levels; lv++) {
        for (int i = 0; i < set->count; i++) {
            const dirt_view *v = &set->views[i];
            if (lv >= v->num_levels)
                continue;
            int cw = (v->width + (1 << (lv - 1)) - 1) >> (lv - 1);
            int ch = (v->height + (1 << (lv - 1)) - 1) >> (lv - 1);
            int w = (v->width + (1 << lv) - 1) >> lv, h = (v->height + (1 << lv) - 1) >> lv;
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    float lo = INFINITY, hi = 0;
                    for (int j = 0; j < 2; j++) {
                        for (int k = 0; k < 2; k++) {
                            int cx = 2 * x + k, cy = 2 * y + j;
                            if (cx < cw && cy < ch) {
                                const float *e = d->depth[set->level_base[lv - 1][i] + cy * cw + cx];
                                lo = fminf(lo, e[0]);
                                hi = fmaxf(hi, e[1]);
                            }
                        }
                    }
                    const float *e = d->depth[set->level_base[lv][i] + y * w + x];
                    if (e[0] != lo || e[1] != hi)
                        r->bad_pyramid++;
                }
            }
        }
    }
}

/* The stored fragments against the exact coverage oracle. */
static void check_coverage(const dirt_view_set *set, const dirt_frame *f, const dirt_mmrt_data *d,
                           int nquads, report *r)
{
    by_pixel bp;
    group_by_pixel(d, &bp);
    uint8_t *hit = calloc(f->num_triangles + 1, 1);
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        for (int y = 0; y < v->height; y++) {
            for (int x = 0; x < v->width; x++) {
                uint32_t g = (uint32_t)(v->tile_base + y * v->width + x);
                r->pixels++;
                uint32_t b = bp.offsets[g], e = bp.offsets[g + 1];
                memset(hit, 0, f->num_triangles + 1);
                for (uint32_t k = b; k < e; k++) {
                    uint32_t prim = d->data[bp.nodes[k]].prim;
                    if (prim >= f->num_triangles) {
                        r->extra++;
                        continue;
                    }
                    if (hit[prim])
                        r->duplicates++;
                    hit[prim] = 1;
                }
                for (size_t p = 0; p < f->num_triangles; p++) {
                    float tri[3][3];
                    mt_tri(f, p, tri);
                    double depth = 0;
                    int cov = mt_coverage(v, tri, x, y, TOL_PX, &depth);
                    if (cov < 0) {
                        r->ambiguous++;
                        continue;
                    }
                    if (!cov) {
                        if (hit[p])
                            r->extra++;
                        continue;
                    }
                    r->required++;
                    if (!hit[p]) {
                        r->missing++;
                        continue;
                    }
                    r->found++;
                    /* Attributes of the stored fragment. */
                    for (uint32_t k = b; k < e; k++) {
                        uint32_t n = bp.nodes[k];
                        const dirt_mmrt_data_node *dn = &d->data[n];
                        if (dn->prim != p)
                            continue;
                        if (fabs(d->ids[n].z - depth) > 1e-5 * depth + 1e-6)
                            r->bad_depth++;
                        double o[3], dir[3], t, u, w;
                        mt_pixel_ray(v, x, y, o, dir);
                        mt_ray_plane(o, dir, tri, &t, &u, &w);
                        double uv[2], nrm[3];
                        for (int c = 0; c < 2; c++)
                            uv[c] = (1 - u - w) * f->uv[3 * p][c] + u * f->uv[3 * p + 1][c] +
                                    w * f->uv[3 * p + 2][c];
                        for (int c = 0; c < 3; c++)
                            nrm[c] = (1 - u - w) * f->normal[3 * p][c] +
                                     u * f->normal[3 * p + 1][c] + w * f->normal[3 * p + 2][c];
                        double nl = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
                        float dec[3];
                        dirt_mmrt_unpack_normal(dn->normal_oct, dec);
                        double dot = (dec[0] * nrm[0] + dec[1] * nrm[1] + dec[2] * nrm[2]) / nl;
                        if (fabs(dn->u - u) > 2e-3 || fabs(dn->v - w) > 2e-3 ||
                            fabs(dn->uv[0] - uv[0]) > 2e-3 * (1 + fabs(uv[0])) ||
                            fabs(dn->uv[1] - uv[1]) > 2e-3 * (1 + fabs(uv[1])) ||
                            dn->material != f->material[p] || !(dot > 0.9999))
                            r->bad_attr++;
                    }
                }
                /* Watertight quads: one fragment of the quad per pixel well
                 * inside it, the shared diagonal included. */
                for (int q = 0; q < nquads; q++) {
                    float t0[3][3], t1[3][3];
                    mt_tri(f, 2 * (size_t)q, t0);
                    mt_tri(f, 2 * (size_t)q + 1, t1);
                    /* Quad corners c0 c1 c2 c3 = t0[0], t0[1], t0[2], t1[2]. */
                    const float *cs[4] = {t0[0], t0[1], t0[2], t1[2]};
                    double s[4][2];
                    bool front = true;
                    for (int k = 0; k < 4; k++) {
                        double pw[3] = {cs[k][0], cs[k][1], cs[k][2]}, c[4];
                        mt_clip(v, pw, c);
                        front &= c[3] > 0.5 * v->znear;
                        s[k][0] = (c[0] / c[3] * 0.5 + 0.5) * v->width;
                        s[k][1] = (c[1] / c[3] * 0.5 + 0.5) * v->height;
                    }
                    if (!front)
                        continue;
                    double px = x + 0.5, py = y + 0.5, sgn = 0;
                    bool inside = true;
                    for (int k = 0; k < 4 && inside; k++) {
                        const double *a = s[k], *bb = s[(k + 1) % 4];
                        double ex = bb[0] - a[0], ey = bb[1] - a[1];
                        double len = sqrt(ex * ex + ey * ey);
                        double cr = (ex * (py - a[1]) - ey * (px - a[0])) / (len > 0 ? len : 1);
                        if (sgn == 0)
                            sgn = cr > 0 ? 1 : -1;
                        if (cr * sgn < 0.02)
                            inside = false;
                    }
                    double depth;
                    if (!inside || mt_coverage(v, t0, x, y, 0, &depth) < 0)
                        continue;
                    r->quad_pixels++;
                    int c0 = mt_coverage(v, t0, x, y, TOL_PX, &depth);
                    int c1 = mt_coverage(v, t1, x, y, TOL_PX, &depth);
                    if (c0 < 0 && c1 < 0)
                        r->diagonal_pixels++;
                    if (hit[2 * q] + hit[2 * q + 1] != 1)
                        r->bad_watertight++;
                }
            }
        }
    }
    free(hit);
    free(bp.offsets);
    free(bp.nodes);
}

static void print_report(const char *label, const dirt_mmrt_opts *o, const dirt_mmrt_stats *st,
                         const report *r)
{
    fprintf(stderr,
            "%-8s %-11s B=%d %s: %6llu pixels, %6llu fragments (layers avg %.2f max %u, long "
            "lists %llu, runs %d) | required %llu found %llu ambiguous %llu | missing %llu "
            "extra %llu dup %llu depth %llu attr %llu | quad px %llu (diagonal %llu) "
            "watertight %llu | links %llu prev %llu pixel %llu unsorted %llu bucket %llu "
            "bounds %llu tails %llu lost %llu pyramid %llu\n",
            label, mt_mode_name(o->views.mode), o->buckets,
            st->sort == DIRT_MMRT_SORT_LIST ? "list" : "regs", (unsigned long long)r->pixels,
            (unsigned long long)st->fragments, st->avg_layers, st->max_layers,
            (unsigned long long)st->long_lists, st->store_runs,
            (unsigned long long)r->required, (unsigned long long)r->found,
            (unsigned long long)r->ambiguous,
            (unsigned long long)r->missing,
            (unsigned long long)r->extra, (unsigned long long)r->duplicates,
            (unsigned long long)r->bad_depth, (unsigned long long)r->bad_attr,
            (unsigned long long)r->quad_pixels, (unsigned long long)r->diagonal_pixels,
            (unsigned long long)r->bad_watertight, (unsigned long long)r->bad_link,
            (unsigned long long)r->bad_prev, (unsigned long long)r->bad_pixel,
            (unsigned long long)r->unsorted, (unsigned long long)r->bad_bucket,
            (unsigned long long)r->bad_bounds, (unsigned long long)r->bad_tail,
            (unsigned long long)r->lost, (unsigned long long)r->bad_pyramid);
}

/* Builds and checks; returns the build (caller destroys) for comparisons. */
static dirt_mmrt *build_and_check(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                                  const dirt_camera *cam, const dirt_mmrt_opts *o,
                                  int nquads, dirt_mmrt_data *out)
{
    dirt_mmrt *m = dirt_mmrt_create(gpu, o);
    CHECK(m != NULL);
    if (!m)
        return NULL;
    bool ok = dirt_mmrt_build(m, f, cam);
    CHECK(ok);
    if (!ok || !dirt_mmrt_read(m, out)) {
        CHECK(false);
        dirt_mmrt_destroy(m);
        return NULL;
    }
    const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
    const dirt_view_set *set = dirt_mmrt_views(m);
    report r = {0};
    check_structure(set, out, &r);
    check_coverage(set, f, out, nquads, &r);
    print_report(label, o, st, &r);
    CHECK(st->fragments == out->num_nodes);
    CHECK(st->fragments > 0 && r.required > 0);
    CHECK(r.missing == 0);
    CHECK(r.extra == 0);
    CHECK(r.duplicates == 0);
    CHECK(r.bad_depth == 0);
    CHECK(r.bad_attr == 0);
    CHECK(r.bad_watertight == 0);
    CHECK(r.bad_link == 0 && r.bad_prev == 0 && r.bad_pixel == 0);
    CHECK(r.unsorted == 0);
    CHECK(r.bad_bucket == 0);
    CHECK(r.bad_bounds == 0);
    CHECK(r.bad_tail == 0);
    CHECK(r.lost == 0);
    CHECK(r.bad_pyramid == 0);
    CHECK(r.ambiguous * 10 < r.required); /* the oracle decides nearly everything */
    CHECK(st->covered_pixels > 0 && st->max_layers >= 1);
    CHECK(st->bytes_id_nodes_used == st->fragments * 12);
    CHECK(st->bytes_data_nodes_used == st->fragments * 32);
    CHECK(st->bytes_heads == 8ull * (uint64_t)o->buckets * st->pixels);
    return m;
}

/* Per (bucket, pixel) list contents as (depth bits, primitive) must match. */
static uint64_t compare_lists(const dirt_mmrt_data *a, const dirt_mmrt_data *b)
{
    if (a->num_pixels != b->num_pixels || a->buckets != b->buckets ||
        a->num_nodes != b->num_nodes)
        return UINT64_MAX;
    uint64_t diff = 0;
    size_t slots = (size_t)a->num_pixels * (size_t)a->buckets;
    for (size_t s = 0; s < slots; s++) {
        uint32_t na = a->heads[s], nb = b->heads[s];
        while (na != DIRT_MMRT_END && nb != DIRT_MMRT_END && na < a->num_nodes &&
               nb < b->num_nodes) {
            if (memcmp(&a->ids[na].z, &b->ids[nb].z, 4) != 0 ||
                a->data[na].prim != b->data[nb].prim ||
                memcmp(&a->data[na].u, &b->data[nb].u, 16) != 0)
                diff++;
            na = a->ids[na].next;
            nb = b->ids[nb].next;
        }
        if ((na == DIRT_MMRT_END) != (nb == DIRT_MMRT_END))
            diff++;
    }
    return diff;
}

static int quad_scene(dirt_frame *f, mt_quad *quads, int max)
{
    static const mt_quad fixed[] = {
        {2, -2.13f, -0.91f, 0.37f, -0.52f, 0.66f, 1},
        {2, -2.77f, -0.43f, 1.21f, -0.87f, 0.29f, 1},
        {2, -3.41f, -1.63f, 0.58f, -0.31f, 1.47f, 1},
        {2, -4.06f, -2.2f, 2.47f, -1.9f, 2.03f, 1},
        {2, -5.29f, -3.9f, 3.7f, -3.3f, 3.1f, 1},
        {2, 2.41f, -1.3f, 1.7f, -1.1f, 0.9f, -1},   /* behind the camera */
        {0, -2.61f, -1.2f, 1.3f, -3.5f, 1.9f, 1},   /* left wall (y, z) */
        {1, -1.73f, -6.2f, 2.6f, -2.9f, 3.3f, 1},   /* floor (z, x) */
        {0, 3.07f, -0.8f, 2.2f, -2.4f, 0.7f, -1},   /* right wall */
    };
    int n = 0;
    for (size_t i = 0; i < sizeof(fixed) / sizeof(fixed[0]) && n < max; i++) {
        quads[n] = fixed[i];
        mt_add_quad(f, &quads[n++]);
    }
    /* A stack 37 deep behind the backdrop's hole-free part: lists longer
     * than the register sort. */
    for (int k = 0; k < 37 && n < max; k++) {
        float s = 1.0f - 0.003f * k;
        quads[n] = (mt_quad){2, -4.31f - 0.0517f * k, 0.41f * s, 1.13f * s, -0.97f * s,
                             -0.23f * s, 1};
        mt_add_quad(f, &quads[n++]);
    }
    mt_frame_bounds(f);
    return n;
}

static int limit_errors;

static void count_limit_errors(void *user, enum dirt_log_level level, const char *file, int line,
                               const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level == DIRT_LOG_ERROR)
        limit_errors++;
    fprintf(stderr, "[log] %s\n", msg);
}

/* Past one storage block: 40 full-view layers at 640x480 need 12.3 M
 * fragments (393 MB of data nodes, more than llvmpipe's 128 MiB block): the
 * build succeeds with every fragment and no error (the pools split), and
 * the object still builds a small frame afterwards. (Past what even the
 * split holds: test_split.) */
static void test_limits(dirt_gpu *gpu, const dirt_camera *cam, dirt_frame *small)
{
    dirt_frame *f = mt_frame_new(80);
    for (int k = 0; k < 40; k++) {
        mt_quad q = {2, -1.0f - 0.01f * k, -5, 5, -5, 5, 1};
        mt_add_quad(f, &q);
    }
    mt_frame_bounds(f);
    dirt_mmrt_opts o = {.views = {.width = 640, .height = 480}, .buckets = 2};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
    CHECK(m != NULL);
    if (m) {
        const uint64_t frags = 40ull * 640 * 480;
        int64_t max = dirt_gpu_get_caps(gpu)->max_ssbo_size;
        bool over = max > 0 && (int64_t)(frags * 32) > max;
        dirt_log_set_callback(count_limit_errors, NULL);
        bool ok = dirt_mmrt_build(m, f, cam);
        dirt_log_set_callback(NULL, NULL);
        fprintf(stderr, "limits: %llu fragments, max storage block %lld B: build %s, %d "
                "limit error(s) logged\n", (unsigned long long)frags, (long long)max,
                ok ? "succeeded" : "failed", limit_errors);
        CHECK(ok && limit_errors == 0 && dirt_mmrt_get_stats(m)->fragments == frags);
        if (over)
            fprintf(stderr, "  (past one storage block of %lld B: the pools split)\n",
                    (long long)max);
        /* Still usable for a frame that fits. */
        CHECK(dirt_mmrt_build(m, small, cam));
        CHECK(dirt_mmrt_get_stats(m)->fragments > 0);
        dirt_mmrt_destroy(m);
    }
    mt_frame_free(f);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    enum { MAXQ = 64 };
    mt_quad quads[MAXQ];
    dirt_frame *f = mt_frame_new(2 * MAXQ);
    int nq = quad_scene(f, quads, MAXQ);
    dirt_camera cam = {.type = DIRT_CAMERA_PERSPECTIVE, .yfov = 1.0471976f, .znear = 0.05f};
    dirt_camera_look_at(&cam, (const float[3]){0, 0, 0}, (const float[3]){0, 0, -1},
                        (const float[3]){0, 1, 0});

    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE_CAMERA};
    static const int buckets[] = {1, 3, 8};
    for (int mi = 0; mi < 2; mi++) {
        for (int bi = 0; bi < 3; bi++) {
            dirt_mmrt_opts o = {.views = {.mode = modes[mi], .width = 61, .height = 47,
                                          .face_size = 29},
                                .buckets = buckets[bi]};
            dirt_mmrt_data d;
            dirt_mmrt *m = build_and_check(gpu, "quads", f, &cam, &o, nq, &d);
            if (!m)
                continue;
            const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
            if (buckets[bi] == 1)
                CHECK(st->long_lists > 0 && st->max_layers > DIRT_MMRT_SORT_CHUNK);
            if (bi < 2) {
                /* The other sort gives the same lists. */
                dirt_mmrt_opts other = o;
                other.sort = st->sort == DIRT_MMRT_SORT_LIST ? DIRT_MMRT_SORT_REGISTERS
                                                             : DIRT_MMRT_SORT_LIST;
                dirt_mmrt_data dr;
                dirt_mmrt *mr = build_and_check(gpu, "quads/s", f, &cam, &other, nq, &dr);
                if (mr) {
                    uint64_t diff = compare_lists(&d, &dr);
                    fprintf(stderr, "sorts %s and %s: %llu list differences\n",
                            st->sort == DIRT_MMRT_SORT_LIST ? "list" : "registers",
                            other.sort == DIRT_MMRT_SORT_LIST ? "list" : "registers",
                            (unsigned long long)diff);
                    CHECK(diff == 0);
                    CHECK(dirt_mmrt_get_stats(mr)->long_lists == st->long_lists);
                    dirt_mmrt_data_free(&dr);
                    dirt_mmrt_destroy(mr);
                }
            }
            if (bi == 1) {
                /* Overflow: capacity 1 -> grown pools, same lists. */
                dirt_mmrt_opts small = o;
                small.initial_nodes = 1;
                dirt_mmrt_data ds;
                dirt_mmrt *ms = build_and_check(gpu, "quads/1", f, &cam, &small, nq, &ds);
                if (ms) {
                    uint64_t diff = compare_lists(&d, &ds);
                    int runs = dirt_mmrt_get_stats(ms)->store_runs;
                    fprintf(stderr, "overflow from capacity 1: %d store runs, %llu list "
                            "differences against the ample run\n", runs,
                            (unsigned long long)diff);
                    CHECK(runs >= 2);
                    CHECK(diff == 0);
                    /* The grown capacity carries over: the next build runs once. */
                    CHECK(dirt_mmrt_build(ms, f, &cam));
                    CHECK(dirt_mmrt_get_stats(ms)->store_runs == 1);
                    dirt_mmrt_data_free(&ds);
                    dirt_mmrt_destroy(ms);
                }
            }
            dirt_mmrt_data_free(&d);
            dirt_mmrt_destroy(m);
        }
    }
    test_limits(gpu, &cam, f);
    mt_frame_free(f);

    /* The default scene (closed room, boxes, spheres): general triangles,
     * shared edges, near-plane crossings in the cube faces. */
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    if (scene) {
        dirt_frame *df = dirt_scene_evaluate(scene, 0, NULL);
        dirt_camera dc;
        dirt_camera_default(df, &dc);
        dirt_mmrt_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 48,
                                      .height = 36, .face_size = 24},
                            .buckets = 4, .initial_nodes = 1};
        dirt_mmrt_data d;
        dirt_mmrt *m = build_and_check(gpu, "default", df, &dc, &o, 0, &d);
        if (m) {
            CHECK(dirt_mmrt_get_stats(m)->store_runs >= 2);
            dirt_mmrt_print_stats(m, stderr);
            dirt_mmrt_data_free(&d);
            dirt_mmrt_destroy(m);
        }
        dirt_frame_destroy(df);
        dirt_scene_destroy(scene);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
