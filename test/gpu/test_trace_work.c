/* Work counters (doc/dirt-trace.md, "Work counters"):
 *  - the counting build of DIRT's trace finds the same hits as the plain
 *    build, bit for bit (primitive, view, t, u, v), for every ray type on
 *    the default scene (views single and cube+camera, large primitives on,
 *    off, on through their grid, on with sub-tile rectangles, and those with
 *    the grid and bucket occupancy masks);
 *  - its counts equal a CPU count made another way: for rays that hit
 *    nothing (tmax half-way to Embree's hit, or leaving the scene), on a
 *    level-0 march of one view, the CPU cuts the ray at every tile line it
 *    crosses (double precision), so the Hi-Z steps are the pieces, the
 *    tiles walked are the pieces whose depth span meets the tile's bounds
 *    and, with bucket occupancy masks (dirt_ads_opts.bucket_masks), whose
 *    buckets in the span hold a node (the lists read back: the trace skips
 *    the others by the tile's mask; without masks, none read back, every
 *    such tile is walked, and the runs see some: the count before the
 *    masks; runs with and without on the same rays),
 *    the list nodes are the lengths of the lists of the buckets the span
 *    overlaps (read back from the structure) and the triangle tests the
 *    distinct primitives among them (exact while at most four distinct ones
 *    are met, the trace's rejection cache; else between that and the
 *    nodes). Rays within rounding of a tile line, a depth bound or a bucket
 *    edge are left out (counted, at most 15 %); the same with adaptive
 *    depth buckets (the span's fine bins, then the buckets of the edges
 *    read back), on the default scene's diffuse rays and the soup;
 *  - the same on the default scene with its large primitives tested by
 *    every ray (one test each per ray more) and through their grid (the
 *    CPU cuts the ray at the grid's cell lines too: each cell the walk
 *    enters is a march step, and each large primitive is tested once, in
 *    the first cell whose depth range (read back) the span meets; the walk
 *    stops once every primitive the view's cells hold was tested);
 *  - with sub-tile rectangles (default scene's diffuse rays, the soup,
 *    uniform and adaptive buckets) a node whose rectangle (read back) misses
 *    the cells of the piece's NDC box widened by DIRT_SUBTILE_MARGIN cells
 *    is a node read but no test (rays within rounding of a cell line left
 *    out as above);
 *  - with node depth ranges (default scene's diffuse rays, the soup,
 *    uniform buckets with masks and adaptive ones with rectangles) a node
 *    whose range (read back) misses the span's sub-slabs in its bucket is a
 *    node read but no test (rays within rounding of a sub-slab edge left
 *    out as above);
 *  - the full pyramid walks the same tiles, nodes and triangle tests as
 *    the level-0 march (rays within rounding left out as above) and finds
 *    the same hits, with and without the from_surfaces hint; with it, a ray
 *    the level-0 march ends in one step takes one step; camera rays through
 *    the camera view's pixel centres take one step each (their piece's
 *    march starts at level 0);
 *  - Embree's BVH walk (ref/bvh_work.c) finds Embree's closest hits and
 *    occlusion, and its counts are bounded: an any-hit walk never does more
 *    than the closest-hit walk, no walk tests more triangles than there
 *    are, and a ray that hits tested at least one. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "check.h"
#include "common/layout.h"
#include "dirt/ads.h"
#include "dirt/ads_internal.h"
#include "dirt/scene.h"
#include "gpu.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

static uint32_t g_rng = 12345u; /* ads_rand's state: the soups and the rays */

static size_t g_skipped, g_empty_walked; /* check_counts' empty tiles, all runs */
static bool g_verbose; /* print the CPU count's pieces (DIRT_TEST_VERBOSE, rays that differ) */

typedef struct cpu_count {
    bool ambiguous;
    uint32_t steps, tiles, nodes, distinct;
    uint32_t skipped; /* tiles met but not walked: no node in the span's buckets (with
                         bucket masks) */
    uint32_t empty;   /* tiles met whose span's buckets are all empty, walked (without
                         bucket masks) */
    uint32_t large_steps, large_tests; /* the large primitives' (count_large) */
} cpu_count;

/* How the large primitives are traced in check_counts. */
enum large_mode { LARGE_NONE, LARGE_ALL, LARGE_GRID, LARGE_MODES };
static const char *const large_mode_names[] = {"no large", "large tested by every ray",
                                               "large through their grid"};

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The CPU count of one ray over view 0 (the only view) of `set`, level 0. */
static cpu_count count_ray(const dirt_view_set *set, const dirt_ads_data *d, const dirt_ray *r)
{
    cpu_count c = {0};
    const dirt_view *v = &set->views[0];
    int S = set->tile_size, B = d->buckets;
    double co[4] = {0}, cd[4] = {0};
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++) {
            co[i] += (double)v->view_proj[4 * k + i] * r->org[k];
            cd[i] += (double)v->view_proj[4 * k + i] * r->dir[k];
        }
        co[i] += v->view_proj[12 + i];
    }
    /* The segment in the frustum: -w <= x, y, z <= w. */
    double t0 = r->tmin, t1 = r->tmax;
    for (int p = 0; p < 6; p++) {
        double s = p & 1 ? -1 : 1;
        double a = co[3] + s * co[p >> 1], b = cd[3] + s * cd[p >> 1];
        if (b == 0) {
            if (a < 0)
                return c;
        } else if (b > 0) {
            t0 = fmax(t0, -a / b);
        } else {
            t1 = fmin(t1, -a / b);
        }
    }
    if (!(t0 < t1))
        return c;
    double len = t1 - t0, eps = 1e-5 * len;
    /* Every crossing of a tile line inside the segment. */
    int nx = v->tiles_x + 1, ny = v->tiles_y + 1;
    double *cuts = malloc((size_t)(nx + ny + 2) * sizeof(double));
    int n = 0;
    cuts[n++] = t0;
    for (int axis = 0; axis < 2; axis++) {
        int lines = axis ? ny : nx, size = axis ? v->height : v->width;
        for (int k = 0; k < lines; k++) {
            double X = -1.0 + 2.0 * fmin((double)k * S, size) / size;
            double den = cd[axis] - X * cd[3];
            if (den == 0)
                continue;
            double t = -(co[axis] - X * co[3]) / den;
            if (g_verbose && t > t0 - len && t < t1 + len)
                fprintf(stderr, "    axis %d line %d at t %.9g (segment [%.9g, %.9g])\n", axis, k,
                        t, t0, t1);
            if (t > t0 - eps && t < t1 + eps)
                cuts[n++] = t;
        }
    }
    cuts[n++] = t1;
    qsort(cuts, (size_t)n, sizeof(double), cmp_d);
    uint32_t seen[4096];
    for (int i = 0; i + 1 < n; i++) {
        double ta = cuts[i], tb = cuts[i + 1];
        if (tb - ta < eps) {
            /* a corner, or a line through an end: rounding decides */
            if (!(i == 0 && ta == t0 && tb == t0) && !(i + 2 == n && tb == t1 && ta == t1))
                c.ambiguous = true;
            continue;
        }
        double tm = 0.5 * (ta + tb), w = co[3] + tm * cd[3];
        double ndc[2] = {(co[0] + tm * cd[0]) / w, (co[1] + tm * cd[1]) / w};
        double fx = (ndc[0] * 0.5 + 0.5) * v->width / S, fy = (ndc[1] * 0.5 + 0.5) * v->height / S;
        int tx = (int)floor(fx), ty = (int)floor(fy);
        /* A ray running along a tile line (a mirror ray in the plane of a
         * row through the eye): which side is rounding's. */
        if (fabs(fx - round(fx)) < 1e-4 || fabs(fy - round(fy)) < 1e-4)
            c.ambiguous = true;
        if (tx < 0 || ty < 0 || tx >= v->tiles_x || ty >= v->tiles_y) {
            c.ambiguous = true;
            continue;
        }
        c.steps++;
        int gt = set->level_base[0][0] + ty * v->tiles_x + tx;
        double zlo = d->depth[gt][0], zhi = d->depth[gt][1];
        double wa = co[3] + ta * cd[3], wb = co[3] + tb * cd[3];
        double lo = fmin(wa, wb), hi = fmax(wa, wb);
        if (g_verbose)
            fprintf(stderr, "    piece [%.9g, %.9g] tile (%d, %d) span [%.9g, %.9g] bounds "
                    "[%.9g, %.9g]\n", ta, tb, tx, ty, lo, hi, zlo, zhi);
        if (!(zlo <= zhi) || hi < zlo || lo > zhi) {
            if (zlo <= zhi && (fabs(hi - zlo) < 1e-5 * fabs(zlo) + 1e-7 ||
                               fabs(lo - zhi) < 1e-5 * fabs(zhi) + 1e-7))
                c.ambiguous = true;
            continue;
        }
        if (fabs(hi - zlo) < 1e-5 * fabs(zlo) + 1e-7 || fabs(lo - zhi) < 1e-5 * fabs(zhi) + 1e-7)
            c.ambiguous = true;
        double range = zhi - zlo;
        int ba = 0, bb = 0;
        /* adaptive buckets: the fine bins (H of them), then the bucket whose
         * edges (read back) hold the bin */
        int H = d->edges ? d->fine_bins : B;
        if (range > 0) {
            double fa = H * (wa - zlo) / range, fb = H * (wb - zlo) / range;
            if ((fabs(fa - round(fa)) < 1e-3 && fa > 0.5 && fa < H - 0.5) ||
                (fabs(fb - round(fb)) < 1e-3 && fb > 0.5 && fb < H - 0.5))
                c.ambiguous = true;
            ba = (int)fmin(fmax(floor(fa), 0), H - 1);
            bb = (int)fmin(fmax(floor(fb), 0), H - 1);
        }
        if (d->edges) {
            const uint16_t *e = d->edges + (size_t)(B + 1) * (size_t)gt;
            int fa = ba, fb = bb;
            ba = bb = 0;
            for (int k = 1; k < B; k++) {
                ba += e[k] <= fa;
                bb += e[k] <= fb;
            }
        }
        /* the occupancy (a structure with masks: opts.bucket_masks, B <= 32)
         * a tile is not walked by: with adaptive buckets when its lists in
         * the span's buckets are all empty, with uniform ones when its mask
         * (read back) has no bit of the span's depth slabs (rays within
         * rounding of a slab edge left out); without masks it is walked (its
         * empty lists read) */
        bool any = false;
        for (int b = ba < bb ? ba : bb; b <= (ba < bb ? bb : ba); b++)
            any = any || d->heads[(size_t)b * d->num_tiles + gt] != DIRT_LIST_END;
        bool walk = any;
        if (d->masks && !d->edges) {
            double sa = 0, sb = 0;
            if (range > 0) {
                sa = DIRT_BUCKET_MASK_SLABS * (wa - zlo) / range;
                sb = DIRT_BUCKET_MASK_SLABS * (wb - zlo) / range;
                if ((fabs(sa - round(sa)) < 1e-3 && sa > 0.5 &&
                     sa < DIRT_BUCKET_MASK_SLABS - 0.5) ||
                    (fabs(sb - round(sb)) < 1e-3 && sb > 0.5 && sb < DIRT_BUCKET_MASK_SLABS - 0.5))
                    c.ambiguous = true;
            }
            int s0 = (int)fmin(fmax(floor(fmin(sa, sb)), 0), DIRT_BUCKET_MASK_SLABS - 1);
            int s1 = (int)fmin(fmax(floor(fmax(sa, sb)), 0), DIRT_BUCKET_MASK_SLABS - 1);
            uint32_t bits = 0;
            for (int s = s0; s <= s1; s++)
                bits |= 1u << s;
            walk = (d->masks[gt] & bits) != 0;
        }
        if (!walk && d->masks) {
            c.skipped++;
            continue;
        }
        c.empty += !any;
        c.tiles++;
        /* sub-tile rectangles (d->rects): the cells of the grid over the
         * tile that the piece's NDC box widened by DIRT_SUBTILE_MARGIN
         * cells meets; a node whose cells miss them is read, not tested */
        int seg[4] = {0, DIRT_SUBTILE_GRID - 1, 0, DIRT_SUBTILE_GRID - 1};
        if (d->rects) {
            double wa2 = co[3] + ta * cd[3], wb2 = co[3] + tb * cd[3];
            double ea[2] = {(co[0] + ta * cd[0]) / wa2, (co[1] + ta * cd[1]) / wa2};
            double eb[2] = {(co[0] + tb * cd[0]) / wb2, (co[1] + tb * cd[1]) / wb2};
            double box[4] = {fmin(ea[0], eb[0]), fmax(ea[0], eb[0]), fmin(ea[1], eb[1]),
                             fmax(ea[1], eb[1])};
            ads_ref_box_cells(v, S, tx, ty, box, DIRT_SUBTILE_MARGIN, seg);
            double nd[4];
            dirt_view_tile_ndc(v, S, tx, ty, nd);
            for (int k = 0; k < 4; k++) {
                double cell = (nd[(k & 2) + 1] - nd[k & 2]) / DIRT_SUBTILE_GRID;
                double u = (box[k] - nd[k & 2]) / cell + (k & 1 ? 1 : -1) * DIRT_SUBTILE_MARGIN;
                if (fabs(u - round(u)) < 1e-3 && u > 0.5 && u < DIRT_SUBTILE_GRID - 0.5)
                    c.ambiguous = true;
            }
        }
        /* node depth ranges (d->node_depths): the span's sub-slabs in each
         * bucket (its ends placed in the tile as H or B parts, then cut into
         * the bucket's 16); a node whose sub-slabs miss them is read, not
         * tested (these rays hit nothing: no narrowing to a hit) */
        double qs[2] = {0, 0};
        for (int k = 0; d->node_depths && range > 0 && k < 2; k++)
            qs[k] = fmin(fmax(H * ((k ? hi : lo) - zlo) / range, -1.0), H + 1.0);
        for (int b = ba < bb ? ba : bb; b <= (ba < bb ? bb : ba); b++) {
            int rs[2] = {0, DIRT_NODE_DEPTH_SLABS - 1};
            if (d->node_depths) {
                double q0 = b, q1 = b + 1;
                if (d->edges) {
                    q0 = d->edges[(size_t)(B + 1) * (size_t)gt + (size_t)b];
                    q1 = d->edges[(size_t)(B + 1) * (size_t)gt + (size_t)b + 1];
                }
                for (int k = 0; k < 2; k++) {
                    double s = q1 > q0 ? DIRT_NODE_DEPTH_SLABS * (qs[k] - q0) / (q1 - q0) : 0;
                    if (fabs(s - round(s)) < 1e-3 && s > 0.5 && s < DIRT_NODE_DEPTH_SLABS - 0.5)
                        c.ambiguous = true;
                    rs[k] = (int)fmin(fmax(floor(s), 0), DIRT_NODE_DEPTH_SLABS - 1);
                }
            }
            for (uint32_t node = d->heads[(size_t)b * d->num_tiles + gt]; node != DIRT_LIST_END;
                 node = d->nodes[node][1]) {
                uint32_t p = d->nodes[node][0];
                c.nodes++;
                if (d->node_depths &&
                    ((d->node_depths[node] & 15) > rs[1] || (d->node_depths[node] >> 4) < rs[0]))
                    continue;
                if (d->rects) {
                    int g[4];
                    ads_ref_rect_cells(d->rects[node], g);
                    if (g[0] > seg[1] || g[1] < seg[0] || g[2] > seg[3] || g[3] < seg[2])
                        continue;
                }
                bool known = false;
                for (uint32_t k = 0; k < c.distinct && !known; k++)
                    known = seen[k] == p;
                if (!known && c.distinct < 4096)
                    seen[c.distinct++] = p;
            }
        }
    }
    free(cuts);
    return c;
}

/* The large primitives' counts of one ray over view 0 of `a` (built with
 * large primitives): without the grid every ray tests each of them once;
 * with it, the CPU cuts the ray at the grid's cell lines (the level's
 * tile lines and the view's edges, double precision) and walks the cells
 * in order of t: each cell is a march step, and there each large primitive
 * not tested yet whose cell range (the grid read back from the build's
 * staging copy) the piece's depth span meets is tested; the walk stops
 * before a cell once every primitive the view's cells hold was tested.
 * Ranges and cuts within rounding make the ray ambiguous. */
static void count_large(const dirt_ads *a, const dirt_ray *r, enum large_mode mode, cpu_count *c)
{
    int nl = a->stats.num_large;
    if (mode == LARGE_ALL)
        c->large_tests = (uint32_t)nl;
    if (mode != LARGE_GRID)
        return;
    const dirt_view *v = &a->set.views[0];
    struct dirt_i4 g = a->large_grid[0];
    int L = g.x & 0xFFFF;
    uint32_t met = (uint32_t)g.x >> 16, tested = 0;
    int cs = a->set.tile_size << L; /* a cell's pixels per side */
    double co[4] = {0}, cd[4] = {0};
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++) {
            co[i] += (double)v->view_proj[4 * k + i] * r->org[k];
            cd[i] += (double)v->view_proj[4 * k + i] * r->dir[k];
        }
        co[i] += v->view_proj[12 + i];
    }
    double t0 = r->tmin, t1 = r->tmax;
    for (int p = 0; p < 6; p++) {
        double s = p & 1 ? -1 : 1;
        double aa = co[3] + s * co[p >> 1], b = cd[3] + s * cd[p >> 1];
        if (b == 0) {
            if (aa < 0)
                return;
        } else if (b > 0) {
            t0 = fmax(t0, -aa / b);
        } else {
            t1 = fmin(t1, -aa / b);
        }
    }
    if (!(t0 < t1))
        return;
    double len = t1 - t0, eps = 1e-5 * len;
    double cuts[2 * (DIRT_LARGE_GRID + 2) + 2];
    int n = 0;
    cuts[n++] = t0;
    for (int axis = 0; axis < 2; axis++) {
        int lines = (axis ? g.w : g.z) + 1, size = axis ? v->height : v->width;
        for (int k = 0; k < lines; k++) {
            double X = -1.0 + 2.0 * fmin((double)k * cs, size) / size;
            double den = cd[axis] - X * cd[3];
            if (den == 0)
                continue;
            double t = -(co[axis] - X * co[3]) / den;
            if (t > t0 - eps && t < t1 + eps)
                cuts[n++] = t;
        }
    }
    cuts[n++] = t1;
    qsort(cuts, (size_t)n, sizeof(double), cmp_d);
    for (int i = 0; i + 1 < n; i++) {
        double ta = cuts[i], tb = cuts[i + 1];
        if (tb - ta < eps) {
            if (!(i == 0 && ta == t0 && tb == t0) && !(i + 2 == n && tb == t1 && ta == t1))
                c->ambiguous = true;
            continue;
        }
        if ((met & ~tested) == 0)
            return;
        double tm = 0.5 * (ta + tb), w = co[3] + tm * cd[3];
        double fx = ((co[0] + tm * cd[0]) / w * 0.5 + 0.5) * v->width / cs;
        double fy = ((co[1] + tm * cd[1]) / w * 0.5 + 0.5) * v->height / cs;
        int cx = (int)floor(fx), cy = (int)floor(fy);
        if (cx < 0 || cy < 0 || cx >= g.z || cy >= g.w) {
            c->ambiguous = true;
            continue;
        }
        c->large_steps++;
        double wa = co[3] + ta * cd[3], wb = co[3] + tb * cd[3];
        double lo = fmin(wa, wb), hi = fmax(wa, wb);
        const uint32_t(*e)[2] = &a->large_staging[(size_t)g.y + ((size_t)cy * (size_t)g.z +
                                                                 (size_t)cx) * (size_t)nl];
        for (int k = 0; k < nl; k++) {
            if (tested & 1u << k)
                continue;
            float zlo, zhi;
            memcpy(&zlo, &e[k][0], 4);
            memcpy(&zhi, &e[k][1], 4);
            if (zlo <= zhi && (fabs(hi - zlo) < 1e-5 * fabs(zlo) + 1e-7 ||
                               fabs(lo - zhi) < 1e-5 * fabs(zhi) + 1e-7))
                c->ambiguous = true;
            if (!(zlo <= zhi) || hi < zlo || lo > zhi)
                continue;
            tested |= 1u << k;
            c->large_tests++;
        }
    }
}

/* The CPU count against the counting trace on missing rays, and the full
 * pyramid against the level-0 march on `rays`. */
static void check_counts(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                         const dirt_camera *cam, dirt_ray *rays, size_t n, int buckets,
                         enum large_mode mode, enum dirt_depth_buckets depth_buckets,
                         bool sub_tiles, bool masks, bool node_depths)
{
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_ref_hit *ref = malloc(n * sizeof(*ref));
    dirt_hit *hits = malloc(n * sizeof(*hits));
    dirt_trace_work *w0 = malloc(n * sizeof(*w0)), *wf = malloc(n * sizeof(*wf));
    dirt_ray *miss = malloc(n * sizeof(*miss));
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = 64, .height = 48,
                                 .tile_size = 2},
                       .buckets = buckets, .force_emulation = true,
                       .large = mode == LARGE_NONE ? -1 : 0, .large_grid = mode == LARGE_GRID,
                       .depth_buckets = depth_buckets, .sub_tiles = sub_tiles,
                       .bucket_masks = masks, .node_depths = node_depths};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(accel && ads && dirt_ads_build(ads, f, cam));
    if (ads && mode != LARGE_NONE)
        CHECK_MSG(ads->stats.num_large > 0, "%s: no large primitives", label);
    dirt_ads_data d;
    bool have = ads && dirt_ads_read(ads, &d);
    CHECK(have);
    if (!have || !accel)
        goto done;
    /* masks (and the skip the CPU count models by them) only with the option */
    CHECK_MSG((d.masks != NULL) == (masks && buckets <= DIRT_BUCKET_MASK_MAX_BUCKETS),
              "%s: bucket masks %s", label, d.masks ? "present" : "missing");
    /* Missing rays: tmax half-way to Embree's hit. */
    dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, n, 0);
    for (size_t i = 0; i < n; i++) {
        miss[i] = rays[i];
        if (ref[i].prim != DIRT_REF_MISS)
            miss[i].tmax = rays[i].tmin + 0.5f * (ref[i].t - rays[i].tmin);
    }
    dirt_trace_opts level0 = {.hiz_levels = 1};
    dirt_trace_stats ts;
    CHECK(dirt_ads_trace_work(ads, miss, n, hits, &level0, &ts, w0));
    CHECK(ts.aborted == 0);
    size_t checked = 0, ambiguous = 0, hit = 0, exact_tests = 0, walked = 0, skipped = 0;
    size_t empty = 0;
    size_t large_steps = 0, large_tests = 0;
    size_t bad[4] = {0};
    for (size_t i = 0; i < n; i++) {
        if (hits[i].prim != DIRT_HIT_NONE) {
            hit++;
            continue;
        }
        cpu_count c = count_ray(dirt_ads_views(ads), &d, &miss[i]);
        count_large(ads, &miss[i], mode, &c);
        if (c.ambiguous) {
            ambiguous++;
            continue;
        }
        checked++;
        walked += c.tiles;
        skipped += c.skipped;
        empty += c.empty;
        large_steps += c.large_steps;
        large_tests += c.large_tests;
        uint32_t tests = w0[i].triangle_tests - c.large_tests;
        bool b[4] = {w0[i].hiz_steps != c.steps + c.large_steps, w0[i].tiles != c.tiles,
                     w0[i].list_nodes != c.nodes,
                     w0[i].triangle_tests < c.large_tests ||
                         (c.distinct <= 4 ? tests != c.distinct
                                          : tests < c.distinct || tests > c.nodes)};
        exact_tests += c.distinct <= 4;
        for (int k = 0; k < 4; k++) {
            bad[k] += b[k];
            if (b[k] && bad[k] <= 1 && getenv("DIRT_TEST_VERBOSE")) {
                fprintf(stderr, "  ray %zu org %.9g %.9g %.9g dir %.9g %.9g %.9g t [%.9g, %.9g]\n",
                        i, miss[i].org[0], miss[i].org[1], miss[i].org[2], miss[i].dir[0],
                        miss[i].dir[1], miss[i].dir[2], miss[i].tmin, miss[i].tmax);
                g_verbose = true;
                count_ray(dirt_ads_views(ads), &d, &miss[i]);
                g_verbose = false;
            }
            if (b[k] && bad[k] <= 3)
                fprintf(stderr, "  %s ray %zu: GPU (%u steps, %u tiles, %u nodes, %u tests), CPU "
                        "(%u + %u large steps, %u tiles, %u nodes, %u distinct + %u large "
                        "tests)\n", label, i, w0[i].hiz_steps, w0[i].tiles, w0[i].list_nodes,
                        w0[i].triangle_tests, c.steps, c.large_steps, c.tiles, c.nodes,
                        c.distinct, c.large_tests);
        }
    }
    fprintf(stderr, "%s B=%d, %s, masks %s: %zu missing rays checked (%zu tiles walked, %zu "
            "of them empty in the span's buckets, %zu skipped by the masks, %zu with exact triangle "
            "tests; large primitives: %zu "
            "grid steps, %zu tests), %zu within rounding left out, %zu found a hit; differ: "
            "steps %zu, tiles %zu, nodes %zu, tests %zu\n",
            label, buckets, large_mode_names[mode], masks ? "on" : "off", checked, walked,
            empty, skipped, exact_tests,
            large_steps,
            large_tests, ambiguous, hit, bad[0], bad[1], bad[2], bad[3]);
    CHECK_MSG(hit <= n / 100, "%s: %zu of %zu shortened rays found a hit", label, hit, n);
    CHECK_MSG(ambiguous <= n * 15 / 100, "%s: %zu of %zu rays left out", label, ambiguous, n);
    /* (the large primitives out of the lists leave the walls' tiles empty) */
    CHECK(walked > (mode == LARGE_NONE ? checked : checked / 4) && exact_tests > checked / 5);
    /* the grid's walk counted on most rays, and it tests fewer than all */
    if (mode == LARGE_GRID)
        CHECK(large_steps > checked / 2 && large_tests > 0 &&
              large_tests < checked * (size_t)ads->stats.num_large);
    for (int k = 0; k < 4; k++)
        CHECK_MSG(bad[k] == 0, "%s: count %d differs on %zu rays", label, k, bad[k]);
    /* tiles whose span's buckets are empty: with the masks skipped, without
     * them walked (the count before the masks); main checks that some are
     * met each way */
    CHECK_MSG(masks ? empty == 0 : skipped == 0, "%s, masks %s: %zu empty tiles skipped, %zu "
              "walked", label, masks ? "on" : "off", skipped, empty);
    if (masks)
        g_skipped += skipped;
    else
        g_empty_walked += empty;
    /* The full pyramid walks the same tiles and lists in fewer steps, and
     * finds the same hits, with the march of a ray's first piece starting
     * at level 0 (from_surfaces) or at the lowest level whose cell holds the
     * piece (without): a ray the level-0 march ends in one step (its first
     * tile held its hit, or all of it) takes one step with from_surfaces
     * too, where a march from the top would descend to that tile first. */
    dirt_hit *hits_f = malloc(n * sizeof(*hits_f));
    for (int m = 0; m < 4; m++) {
        dirt_ray *rs = m & 1 ? rays : miss;
        dirt_trace_opts full = {.from_surfaces = m >= 2};
        CHECK(dirt_ads_trace_work(ads, rs, n, hits, &level0, NULL, w0));
        CHECK(dirt_ads_trace_work(ads, rs, n, hits_f, &full, NULL, wf));
        size_t differ = 0, left_out = 0, other_hits = 0, one_step = 0, not_one = 0;
        uint64_t s0 = 0, sf = 0;
        for (size_t i = 0; i < n; i++) {
            other_hits += memcmp(&hits[i], &hits_f[i], sizeof(hits[i])) != 0;
            cpu_count c = count_ray(dirt_ads_views(ads), &d, &rs[i]);
            count_large(ads, &rs[i], mode, &c);
            if (c.ambiguous) {
                left_out++;
                continue;
            }
            differ += w0[i].tiles != wf[i].tiles || w0[i].list_nodes != wf[i].list_nodes ||
                      w0[i].triangle_tests != wf[i].triangle_tests;
            s0 += w0[i].hiz_steps;
            sf += wf[i].hiz_steps;
            if (full.from_surfaces && mode != LARGE_GRID && w0[i].hiz_steps == 1) {
                one_step++;
                not_one += wf[i].hiz_steps != 1;
            }
        }
        fprintf(stderr, "%s %s rays%s: full pyramid %.2f steps per ray, level 0 %.2f; %zu rays "
                "walk other tiles or lists (%zu within rounding left out), %zu other hits; "
                "%zu rays of one level-0 step, %zu of them more with the pyramid\n", label,
                m & 1 ? "whole" : "missing", full.from_surfaces ? " from surfaces" : "",
                (double)sf / n, (double)s0 / n, differ, left_out, other_hits, one_step, not_one);
        CHECK_MSG(differ == 0, "%s: %zu rays differ between the pyramid and level 0", label,
                  differ);
        CHECK_MSG(other_hits == 0, "%s: %zu hits differ between the pyramid and level 0", label,
                  other_hits);
        CHECK_MSG(not_one == 0, "%s: %zu of %zu rays of one level-0 step take more from "
                  "surfaces", label, not_one, one_step);
        if (m >= 2 && mode != LARGE_GRID)
            CHECK_MSG(one_step > n / 50, "%s: %zu of %zu rays of one level-0 step", label,
                      one_step, n);
    }
    free(hits_f);
    dirt_ads_data_free(&d);
done:
    dirt_ads_destroy(ads);
    dirt_ref_accel_destroy(accel);
    free(ref);
    free(hits);
    free(w0);
    free(wf);
    free(miss);
}

/* The counting build against the plain one: the same hits, bit for bit. */
static void check_same_hits(dirt_gpu *gpu, dirt_scene *scene, const dirt_frame *f,
                            const dirt_camera *cam)
{
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    CHECK(accel && dirt_gbuffer_build(accel, scene, f, cam, 48, 36, &g));
    size_t n = 48 * 36;
    dirt_ray *rays = malloc(n * sizeof(*rays));
    dirt_hit *a = malloc(n * sizeof(*a)), *b = malloc(n * sizeof(*b));
    dirt_trace_work *w = malloc(n * sizeof(*w));
    for (int k = 0; k < 10; k++) { /* k >> 1: large on, off, on through their grid, on
                                      with sub-tile rectangles, and with those and the
                                      bucket masks */
        dirt_ads_opts o = {.views = {.mode = k & 1 ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA,
                                     .width = 64, .height = 48, .face_size = 32, .tile_size = 2},
                           .buckets = 8, .force_emulation = true, .large = k >> 1 == 1 ? -1 : 0,
                           .large_grid = k >> 1 == 2 || k >> 1 == 4,
                           .sub_tiles = k >> 1 >= 3, .bucket_masks = k >> 1 == 4};
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        CHECK(ads && dirt_ads_build(ads, f, cam));
        for (int t = 0; ads && t < DIRT_RAY_TYPES; t++) {
            size_t cnt = dirt_rays_generate(&g, cam, (enum dirt_ray_type)t, 3, rays);
            dirt_trace_opts to = {.any_hit = t == DIRT_RAY_VISIBILITY};
            CHECK(dirt_ads_trace(ads, rays, cnt, a, &to, NULL));
            CHECK(dirt_ads_trace_work(ads, rays, cnt, b, &to, NULL, w));
            size_t differ = 0;
            uint64_t tests = 0;
            for (size_t i = 0; i < cnt; i++) {
                differ += memcmp(&a[i], &b[i], sizeof(a[i])) != 0;
                tests += w[i].triangle_tests;
            }
            CHECK_MSG(differ == 0, "%s large %s %s: %zu of %zu hits differ with counting",
                      k & 1 ? "single" : "cube+camera",
                      k >> 1 == 1 ? "off" : k >> 1 ? "grid" : "on",
                      dirt_ray_type_names[t], differ, cnt);
            CHECK(tests > 0);
        }
        dirt_ads_destroy(ads);
    }
    free(rays);
    free(a);
    free(b);
    free(w);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
}

/* Camera rays through the camera view's pixel centres stay in one tile of
 * it: the march of their one piece starts at level 0 (the lowest level whose
 * cell holds the piece) and takes one step, walked or skipped, where a march
 * from the pyramid's top would descend to the tile first. */
static void check_camera_steps(dirt_gpu *gpu, dirt_scene *scene, const dirt_frame *f,
                               const dirt_camera *cam)
{
    enum { W = 64, H = 48 };
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    bool have_g = accel && dirt_gbuffer_build(accel, scene, f, cam, W, H, &g);
    CHECK(have_g);
    dirt_ray *rays = malloc(W * H * sizeof(*rays));
    dirt_hit *hits = malloc(W * H * sizeof(*hits));
    dirt_trace_work *w = malloc(W * H * sizeof(*w));
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H,
                                 .tile_size = 2},
                       .buckets = 8, .force_emulation = true, .large = -1};
    dirt_ads *ads = have_g ? dirt_ads_create(gpu, &o) : NULL;
    CHECK(ads && dirt_ads_build(ads, f, cam));
    if (ads && have_g) {
        size_t cnt = dirt_rays_generate(&g, cam, DIRT_RAY_PRIMARY, 3, rays), more = 0, hit = 0;
        CHECK(cnt == (size_t)W * H && dirt_ads_trace_work(ads, rays, cnt, hits, NULL, NULL, w));
        for (size_t i = 0; i < cnt; i++) {
            more += w[i].hiz_steps != 1;
            hit += hits[i].prim != DIRT_HIT_NONE;
        }
        fprintf(stderr, "camera rays: %zu, %zu hit; %zu take more than one Hi-Z step\n", cnt,
                hit, more);
        CHECK_MSG(more == 0, "%zu of %zu camera rays take more than one Hi-Z step", more, cnt);
        CHECK(hit > cnt / 2);
    }
    dirt_ads_destroy(ads);
    free(rays);
    free(hits);
    free(w);
    if (have_g)
        dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
}

/* Embree's BVH walk: Embree's answers, bounded counts. */
static void check_bvh(const char *label, const dirt_frame *f, const dirt_ray *rays, size_t n)
{
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_ref_bvh *bvh = dirt_ref_bvh_create(f);
    CHECK(accel && bvh);
    if (!accel || !bvh)
        goto done;
    const dirt_ref_ray *rr = (const dirt_ref_ray *)rays;
    dirt_ref_hit *ref = malloc(n * sizeof(*ref)), *got = malloc(n * sizeof(*got));
    dirt_ref_work *wc = malloc(n * sizeof(*wc)), *wa = malloc(n * sizeof(*wa));
    uint8_t *occ = malloc(n);
    dirt_ref_intersect(accel, rr, ref, n, 0);
    dirt_ref_occluded(accel, rr, occ, n, 0);
    dirt_ref_bvh_trace(bvh, rr, n, false, got, wc, 0);
    size_t wrong = 0, bad = 0, hits = 0;
    uint64_t nodes = 0, tests = 0;
    for (size_t i = 0; i < n; i++) {
        bool eh = ref[i].prim != DIRT_REF_MISS, gh = got[i].prim != DIRT_REF_MISS;
        hits += eh;
        wrong += eh != gh || (eh && got[i].prim != ref[i].prim &&
                              fabsf(got[i].t - ref[i].t) > 1e-5f * fmaxf(ref[i].t, 1e-3f));
        bad += wc[i].triangle_tests > f->num_triangles || (gh && wc[i].triangle_tests == 0) ||
               (wc[i].triangle_tests && !wc[i].bvh_nodes);
        nodes += wc[i].bvh_nodes;
        tests += wc[i].triangle_tests;
    }
    dirt_ref_bvh_trace(bvh, rr, n, true, got, wa, 0);
    size_t wrong_any = 0, more = 0;
    for (size_t i = 0; i < n; i++) {
        wrong_any += (got[i].prim != DIRT_REF_MISS) != (occ[i] != 0);
        more += wa[i].triangle_tests > wc[i].triangle_tests || wa[i].bvh_nodes > wc[i].bvh_nodes;
    }
    fprintf(stderr, "%s BVH walk: %zu rays, %zu hit; %.2f nodes, %.2f triangle tests per ray; "
            "%zu closest and %zu any hits differ from Embree's\n", label, n, hits,
            (double)nodes / n, (double)tests / n, wrong, wrong_any);
    CHECK_MSG(wrong == 0, "%s: %zu closest hits differ", label, wrong);
    CHECK_MSG(wrong_any == 0, "%s: %zu occlusions differ", label, wrong_any);
    CHECK(bad == 0 && more == 0);
    CHECK(hits > n / 4);
    free(ref);
    free(got);
    free(wc);
    free(wa);
    free(occ);
done:
    dirt_ref_bvh_destroy(bvh);
    dirt_ref_accel_destroy(accel);
}

/* Random rays from inside the bounds (some leave the scene). */
static dirt_ray *random_rays(const dirt_frame *f, size_t n)
{
    dirt_ray *r = malloc(n * sizeof(*r));
    for (size_t i = 0; i < n; i++) {
        ads_random_ray(f, &g_rng, &r[i]);
    }
    return r;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = scene ? dirt_scene_evaluate(scene, 0, NULL) : NULL;
    CHECK(f != NULL);
    if (f) {
        dirt_camera cam;
        dirt_camera_default(f, &cam);
        check_same_hits(gpu, scene, f, &cam);
        check_camera_steps(gpu, scene, f, &cam);
        /* the G-buffer's secondary rays and random rays */
        dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
        dirt_gbuffer g;
        CHECK(accel && dirt_gbuffer_build(accel, scene, f, &cam, 40, 30, &g));
        size_t n = 40 * 30;
        dirt_ray *rays = malloc(n * sizeof(*rays));
        size_t cnt = dirt_rays_generate(&g, &cam, DIRT_RAY_DIFFUSE, 9, rays);
        for (int m = 0; m < LARGE_MODES; m++)
            check_counts(gpu, "default diffuse", f, &cam, rays, cnt, 8, (enum large_mode)m,
                         DIRT_DEPTH_BUCKETS_UNIFORM, false, m != LARGE_ALL, false);
        check_counts(gpu, "default diffuse", f, &cam, rays, cnt, 8, LARGE_NONE,
                     DIRT_DEPTH_BUCKETS_UNIFORM, false, false, false);
        check_counts(gpu, "default diffuse adaptive", f, &cam, rays, cnt, 8, LARGE_NONE,
                     DIRT_DEPTH_BUCKETS_ADAPTIVE, false, true, false);
        check_counts(gpu, "default diffuse sub-tiles", f, &cam, rays, cnt, 8, LARGE_ALL,
                     DIRT_DEPTH_BUCKETS_UNIFORM, true, true, false);
        check_counts(gpu, "default diffuse node depths", f, &cam, rays, cnt, 8, LARGE_NONE,
                     DIRT_DEPTH_BUCKETS_UNIFORM, false, false, true);
        check_bvh("default diffuse", f, rays, cnt);
        cnt = dirt_rays_generate(&g, &cam, DIRT_RAY_SPECULAR, 9, rays);
        for (int m = 0; m < LARGE_MODES; m++)
            check_counts(gpu, "default specular", f, &cam, rays, cnt, 4, (enum large_mode)m,
                         DIRT_DEPTH_BUCKETS_UNIFORM, false, m != LARGE_NONE, false);
        free(rays);
        dirt_gbuffer_free(&g);
        dirt_ref_accel_destroy(accel);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(scene);
    /* A soup of 2,000 small triangles: long lists. */
    dirt_frame *s = ads_soup(2000, 0.12f, &g_rng);
    dirt_camera cam;
    dirt_camera_default(s, &cam);
    dirt_ray *rays = random_rays(s, 3000);
    check_counts(gpu, "soup", s, &cam, rays, 3000, 8, LARGE_NONE, DIRT_DEPTH_BUCKETS_UNIFORM,
                 false, false, false);
    check_counts(gpu, "soup", s, &cam, rays, 3000, 8, LARGE_NONE, DIRT_DEPTH_BUCKETS_UNIFORM,
                 false, true, false);
    check_counts(gpu, "soup adaptive", s, &cam, rays, 3000, 16, LARGE_NONE,
                 DIRT_DEPTH_BUCKETS_ADAPTIVE, false, true, false);
    check_counts(gpu, "soup sub-tiles", s, &cam, rays, 3000, 8, LARGE_NONE,
                 DIRT_DEPTH_BUCKETS_UNIFORM, true, true, false);
    check_counts(gpu, "soup adaptive sub-tiles", s, &cam, rays, 3000, 16, LARGE_NONE,
                 DIRT_DEPTH_BUCKETS_ADAPTIVE, true, false, false);
    check_counts(gpu, "soup node depths", s, &cam, rays, 3000, 8, LARGE_NONE,
                 DIRT_DEPTH_BUCKETS_UNIFORM, false, true, true);
    check_counts(gpu, "soup adaptive node depths", s, &cam, rays, 3000, 16, LARGE_NONE,
                 DIRT_DEPTH_BUCKETS_ADAPTIVE, true, false, true);
    check_bvh("soup", s, rays, 3000);
    /* (default diffuse and the soup, uniform buckets: hundreds each way) */
    CHECK_MSG(g_skipped > 0 && g_empty_walked > 0, "empty tiles: %zu skipped with the masks, "
              "%zu walked without", g_skipped, g_empty_walked);
    free(rays);
    frame_free(s);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
