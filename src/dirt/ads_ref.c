#include "dirt/ads_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/layout.h"
#include "dirt/log.h"

typedef struct pair {
    uint32_t tile;
    ads_ref_entry e;
} pair;

static int cmp_pair(const void *a, const void *b)
{
    const pair *x = a, *y = b;
    if (x->tile != y->tile)
        return x->tile < y->tile ? -1 : 1;
    return x->e.prim < y->e.prim ? -1 : x->e.prim > y->e.prim;
}

bool ads_ref_build(const dirt_view_set *set, const dirt_frame *f, double eps,
                   const uint32_t *large, int num_large, ads_ref *out)
{
    memset(out, 0, sizeof(*out));
    size_t cap = 1024, n = 0;
    pair *pairs = malloc(cap * sizeof(*pairs));
    out->offsets = calloc((size_t)set->num_tiles + 1, sizeof(uint32_t));
    if (!pairs || !out->offsets)
        goto oom;
    for (int vi = 0; vi < set->count; vi++) {
        const dirt_view *v = &set->views[vi];
        for (size_t p = 0; p < f->num_triangles; p++) {
            bool is_large = false;
            for (int k = 0; k < num_large; k++)
                is_large = is_large || large[k] == p;
            if (is_large)
                continue;
            const float(*tri)[3] = (const float(*)[3])f->position[3 * p];
            int rect[4];
            if (!dirt_triangle_tile_rect(v, set->tile_size, tri, 1.0, rect))
                continue;
            for (int ty = rect[2]; ty <= rect[3]; ty++) {
                for (int tx = rect[0]; tx <= rect[1]; tx++) {
                    double lo, hi;
                    double box[4];
                    if (!dirt_clip_triangle_tile_box(v, set->tile_size, tx, ty, tri, eps, &lo,
                                                     &hi, box))
                        continue;
                    if (n == cap) {
                        cap *= 2;
                        pair *g = realloc(pairs, cap * sizeof(*pairs));
                        if (!g)
                            goto oom;
                        pairs = g;
                    }
                    pairs[n++] = (pair){(uint32_t)(v->tile_base + ty * v->tiles_x + tx),
                                        {(uint32_t)p, lo, hi, {box[0], box[1], box[2], box[3]}}};
                }
            }
        }
    }
    qsort(pairs, n, sizeof(*pairs), cmp_pair);
    out->entries = malloc((n ? n : 1) * sizeof(*out->entries));
    if (!out->entries)
        goto oom;
    for (size_t i = 0; i < n; i++) {
        out->entries[i] = pairs[i].e;
        out->offsets[pairs[i].tile + 1]++;
    }
    for (int t = 0; t < set->num_tiles; t++)
        out->offsets[t + 1] += out->offsets[t];
    out->num_tiles = set->num_tiles;
    out->num_entries = n;
    free(pairs);
    return true;
oom:
    DIRT_ERROR("out of memory building the reference structure");
    free(pairs);
    ads_ref_free(out);
    return false;
}

void ads_ref_free(ads_ref *r)
{
    if (!r)
        return;
    free(r->offsets);
    free(r->entries);
    memset(r, 0, sizeof(*r));
}

static const ads_ref_entry *find_entry(const ads_ref *r, int tile, uint32_t prim)
{
    uint32_t lo = r->offsets[tile], hi = r->offsets[tile + 1];
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (r->entries[mid].prim < prim)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < r->offsets[tile + 1] && r->entries[lo].prim == prim ? &r->entries[lo] : NULL;
}

/* Node depth ranges (common/layout.h, DIRT_NODE_DEPTH_*): the sub-slab of
 * depth z in bucket b of tile t, as dirt_node_depth_q and
 * dirt_node_depth_sub (dirt/structure.glsl) in double, with the structure's
 * buckets (uniform, or the tile's edges read back); -1 for an empty
 * bucket (adaptive: equal edges), whose nodes' ranges say nothing (every
 * sub-slab is 0 there, in the trace too). */
static int node_sub_of(const dirt_ads_data *d, int t, int b, double z, double tmin, double range)
{
    double n = d->edges ? d->fine_bins : d->buckets, q = 0, q0 = b, q1 = b + 1;
    if (range > 0)
        q = fmin(fmax(n * (z - tmin) / range, -1.0), n + 1);
    if (d->edges) {
        const uint16_t *e = d->edges + (size_t)(d->buckets + 1) * (size_t)t;
        q0 = e[b];
        q1 = e[b + 1];
    }
    if (!(q1 > q0))
        return -1;
    double s = floor(DIRT_NODE_DEPTH_SLABS * (q - q0) / (q1 - q0));
    return s < 0 ? 0 : s > DIRT_NODE_DEPTH_SLABS - 1 ? DIRT_NODE_DEPTH_SLABS - 1 : (int)s;
}

/* Bucket of depth z in a tile with bounds [tmin, tmin + range] (eq. 1a/1b). */
static int bucket_of(double z, double tmin, double range, int B)
{
    if (!(range > 0))
        return 0;
    double b = floor(B * (z - tmin) / range);
    return b < 0 ? 0 : b > B - 1 ? B - 1 : (int)b;
}

/* The depth slab of z in a tile of bounds [tmin, tmin + range], as
 * dirt_mask_slab (dirt/structure.glsl) in double. */
static int slab_of(double z, double tmin, double range)
{
    if (!(range > 0))
        return 0;
    double s = floor(DIRT_BUCKET_MASK_SLABS * (z - tmin) / range);
    return s < 0 ? 0 : s > DIRT_BUCKET_MASK_SLABS - 1 ? DIRT_BUCKET_MASK_SLABS - 1 : (int)s;
}

void ads_ref_box_cells(const dirt_view *v, int S, int tx, int ty, const double b[4],
                       double margin, int cells[4])
{
    double r[4];
    dirt_view_tile_ndc(v, S, tx, ty, r);
    const double top = DIRT_SUBTILE_GRID - 1;
    for (int k = 0; k < 2; k++) {
        double org = r[2 * k], cell = (r[2 * k + 1] - r[2 * k]) / DIRT_SUBTILE_GRID;
        double lo = floor((b[2 * k] - org) / cell - margin);
        double hi = floor((b[2 * k + 1] - org) / cell + margin);
        cells[2 * k] = (int)fmin(fmax(lo, 0.0), top);
        cells[2 * k + 1] = (int)fmin(fmax(hi, 0.0), top);
    }
}

void ads_ref_rect_cells(uint8_t r, int cells[4])
{
    cells[0] = r & 3;
    cells[1] = 3 - ((r >> 2) & 3);
    cells[2] = (r >> 4) & 3;
    cells[3] = 3 - (r >> 6);
}

/* View and tile (tx, ty) of global tile t. */
static const dirt_view *tile_view(const dirt_view_set *set, int t, int *tx, int *ty)
{
    for (int vi = 0; vi < set->count; vi++) {
        const dirt_view *v = &set->views[vi];
        int k = t - v->tile_base;
        if (k >= 0 && k < v->tiles_x * v->tiles_y) {
            *tx = k % v->tiles_x;
            *ty = k / v->tiles_x;
            return v;
        }
    }
    return NULL;
}

/* A primitive's buckets in one tile, as found in the GPU lists (and its
 * sub-tile rectangle byte there; 0 without them). */
typedef struct gpu_pair {
    uint32_t prim;
    int bucket;
    uint8_t rect;
    uint8_t depth; /* its node's depth range byte (node depth ranges; 0 without) */
} gpu_pair;

static int cmp_gpu_pair(const void *a, const void *b)
{
    const gpu_pair *x = a, *y = b;
    if (x->prim != y->prim)
        return x->prim < y->prim ? -1 : 1;
    return (x->bucket > y->bucket) - (x->bucket < y->bucket);
}

bool ads_check(const dirt_view_set *set, const dirt_frame *f, const dirt_ads_data *d,
               double tol, ads_check_report *rep)
{
    memset(rep, 0, sizeof(*rep));
    ads_ref req, allow;
    if (!ads_ref_build(set, f, 0.0, d->large, d->num_large, &req))
        return false;
    if (!ads_ref_build(set, f, 2.0 * DIRT_CLIP_EPS, d->large, d->num_large, &allow)) {
        ads_ref_free(&req);
        return false;
    }
    const int B = d->buckets, T = d->num_tiles;
    size_t cap = 256;
    gpu_pair *gp = malloc(cap * sizeof(*gp));
    bool ok = gp != NULL;
    rep->tiles = (uint64_t)T;
    rep->required_pairs = req.num_entries;
    rep->allowed_pairs = allow.num_entries;
    for (int t = 0; ok && t < T; t++) {
        /* Gather (prim, bucket) from the lists of this tile. */
        size_t n = 0;
        for (int b = 0; b < B; b++) {
            uint32_t node = d->heads[(size_t)b * T + t];
            size_t steps = 0;
            while (node != DIRT_LIST_END) {
                if (node >= d->num_nodes || ++steps > d->num_nodes) {
                    rep->bad_list_links++;
                    break;
                }
                if (n == cap) {
                    cap *= 2;
                    gpu_pair *g = realloc(gp, cap * sizeof(*gp));
                    if (!g) {
                        ok = false;
                        break;
                    }
                    gp = g;
                }
                gp[n++] = (gpu_pair){d->nodes[node][0], b, d->rects ? d->rects[node] : 0,
                                     d->node_depths ? d->node_depths[node] : 0};
                node = d->nodes[node][1];
            }
        }
        if (!ok)
            break;
        qsort(gp, n, sizeof(*gp), cmp_gpu_pair);
        double tmin = d->depth[t][0], tmax = d->depth[t][1];
        double range = tmax - tmin;
        /* The occupancy mask (uniform buckets: one bit per depth slab): the
         * slabs of every exact range (shrunk by tol), within those of the
         * widened ones, and empty exactly where the GPU's lists are. */
        uint32_t listed = 0, required = 0, allowed = 0;
        double stol = tol * fmax(fabs(tmax), 1e-6);
        for (size_t i = 0; i < n; i++)
            listed |= 1u << (gp[i].bucket & 31);
        for (uint32_t k = req.offsets[t]; d->masks && k < req.offsets[t + 1]; k++) {
            const ads_ref_entry *r = &req.entries[k];
            double lo = fmin(r->zmin + stol, r->zmax), hi = fmax(r->zmax - stol, lo);
            for (int s = slab_of(lo, tmin, range); s <= slab_of(hi, tmin, range); s++)
                required |= 1u << s;
        }
        for (uint32_t k = allow.offsets[t]; d->masks && k < allow.offsets[t + 1]; k++) {
            const ads_ref_entry *a = &allow.entries[k];
            int amin = slab_of(a->zmin - stol, tmin, range);
            int amax = slab_of(a->zmax + stol, tmin, range);
            for (int s = amin; s <= amax; s++)
                allowed |= 1u << s;
        }
        if (d->masks && ((d->masks[t] == 0) != (listed == 0) || (required & ~d->masks[t]) ||
                         (d->masks[t] & ~allowed)))
            rep->bad_masks++;
        /* Walk the primitives found on the GPU. */
        for (size_t i = 0; i < n;) {
            size_t j = i;
            while (j < n && gp[j].prim == gp[i].prim)
                j++;
            uint32_t prim = gp[i].prim;
            rep->gpu_pairs++;
            bool contiguous = true;
            for (size_t k = i + 1; k < j; k++) {
                if (gp[k].bucket == gp[k - 1].bucket)
                    rep->duplicates++;
                else if (gp[k].bucket != gp[k - 1].bucket + 1)
                    contiguous = false;
            }
            int b0 = gp[i].bucket, b1 = gp[j - 1].bucket;
            const ads_ref_entry *r = find_entry(&req, t, prim);
            const ads_ref_entry *a = find_entry(&allow, t, prim);
            if (!a) {
                rep->beyond_tolerance++;
            } else {
                /* Must cover the buckets of the exact range (shrunk by tol)
                 * and stay within those of the widened one. */
                double s = tol * fmax(fabs(tmax), 1e-6);
                int amin = bucket_of(a->zmin - s, tmin, range, B);
                int amax = bucket_of(a->zmax + s, tmin, range, B);
                bool bad = !contiguous || b0 < amin || b1 > amax;
                if (r) {
                    double lo = fmin(r->zmin + s, r->zmax), hi = fmax(r->zmax - s, lo);
                    if (b0 > bucket_of(lo, tmin, range, B) || b1 < bucket_of(hi, tmin, range, B))
                        bad = true;
                }
                if (bad)
                    rep->bad_buckets++;
            }
            if (d->rects) {
                int tx, ty, g[4], need[4] = {3, 0, 3, 0}, may[4] = {0, 3, 0, 3};
                const dirt_view *v = tile_view(set, t, &tx, &ty);
                ads_ref_rect_cells(gp[i].rect, g);
                bool bad = !v;
                for (size_t k = i + 1; k < j; k++)
                    bad = bad || gp[k].rect != gp[i].rect;
                if (v && r)
                    ads_ref_box_cells(v, set->tile_size, tx, ty, r->box, 0.0, need);
                if (v && a)
                    ads_ref_box_cells(v, set->tile_size, tx, ty, a->box,
                                      DIRT_SUBTILE_MARGIN + 1e-3, may);
                bad = bad || g[0] > need[0] || g[1] < need[1] || g[2] > need[2] ||
                      g[3] < need[3] || g[0] < may[0] || g[1] > may[1] || g[2] < may[2] ||
                      g[3] > may[3] || g[0] > g[1] || g[2] > g[3];
                if (bad && rep->bad_rects < 5)
                    DIRT_WARN("tile %d prim %u: rectangle x %d..%d y %d..%d, needs x %d..%d "
                              "y %d..%d, may x %d..%d y %d..%d", t, prim, g[0], g[1], g[2],
                              g[3], need[0], need[1], need[2], need[3], may[0], may[1],
                              may[2], may[3]);
                rep->bad_rects += bad;
            }
            /* Node depth ranges: each node's sub-slabs hold those of the
             * exact range (shrunk by tol) in its bucket and lie within those
             * of the widened one. */
            double ds = tol * fmax(fabs(tmax), 1e-6);
            for (size_t k = i; d->node_depths && k < j; k++) {
                int b = gp[k].bucket, lo = gp[k].depth & 15, hi = gp[k].depth >> 4;
                bool bad = lo > hi;
                if (node_sub_of(d, t, b, tmin, tmin, range) < 0) {
                    rep->bad_node_depths += bad;
                    continue;
                }
                if (a)
                    bad = bad || lo < node_sub_of(d, t, b, a->zmin - ds, tmin, range) ||
                          hi > node_sub_of(d, t, b, a->zmax + ds, tmin, range);
                if (r) {
                    double rl = fmin(r->zmin + ds, r->zmax), rh = fmax(r->zmax - ds, rl);
                    bad = bad || lo > node_sub_of(d, t, b, rl, tmin, range) ||
                          hi < node_sub_of(d, t, b, rh, tmin, range);
                }
                if (bad && rep->bad_node_depths < 5)
                    DIRT_WARN("tile %d prim %u bucket %d: node depth range %d..%d", t, prim, b,
                              lo, hi);
                rep->bad_node_depths += bad;
            }
            i = j;
        }
        /* Every required pair must be there. */
        for (uint32_t k = req.offsets[t]; k < req.offsets[t + 1]; k++) {
            gpu_pair key = {req.entries[k].prim, -1};
            size_t lo = 0, hi = n;
            while (lo < hi) {
                size_t mid = (lo + hi) / 2;
                if (cmp_gpu_pair(&gp[mid], &key) < 0)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            if (lo >= n || gp[lo].prim != key.prim)
                rep->missing++;
        }
        /* Depth bounds: between the exact and the widened references. */
        uint32_t r0 = req.offsets[t], r1 = req.offsets[t + 1];
        uint32_t a0 = allow.offsets[t], a1 = allow.offsets[t + 1];
        if (a0 == a1) {
            if (!(isinf(tmin) && tmax == 0))
                rep->bad_bounds++;
        } else {
            double rmin = INFINITY, rmax = -INFINITY, amin = INFINITY, amax = -INFINITY;
            for (uint32_t k = r0; k < r1; k++) {
                rmin = fmin(rmin, req.entries[k].zmin);
                rmax = fmax(rmax, req.entries[k].zmax);
            }
            for (uint32_t k = a0; k < a1; k++) {
                amin = fmin(amin, allow.entries[k].zmin);
                amax = fmax(amax, allow.entries[k].zmax);
            }
            double s = tol * fmax(amax, 1e-6);
            if (r0 == r1) {
                /* Only boundary primitives: the GPU may or may not have them. */
                if (!(isinf(tmin) && tmax == 0) && (tmin < amin - s || tmax > amax + s))
                    rep->bad_bounds++;
            } else if (tmin < amin - s || tmin > rmin + s || tmax > amax + s || tmax < rmax - s) {
                rep->bad_bounds++;
            }
        }
    }
    free(gp);
    ads_ref_free(&req);
    ads_ref_free(&allow);
    if (!ok)
        DIRT_ERROR("out of memory checking the structure");
    return ok;
}

uint64_t ads_check_pyramid(const dirt_view_set *set, const dirt_ads_data *d)
{
    uint64_t bad = 0;
    for (int vi = 0; vi < set->count; vi++) {
        const dirt_view *v = &set->views[vi];
        for (int lvl = 1; lvl < v->num_levels; lvl++) {
            int cw = (v->tiles_x + (1 << (lvl - 1)) - 1) >> (lvl - 1);
            int ch = (v->tiles_y + (1 << (lvl - 1)) - 1) >> (lvl - 1);
            int w = (v->tiles_x + (1 << lvl) - 1) >> lvl, h = (v->tiles_y + (1 << lvl) - 1) >> lvl;
            const float(*child)[2] = d->depth + set->level_base[lvl - 1][vi];
            const float(*level)[2] = d->depth + set->level_base[lvl][vi];
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    float lo = INFINITY, hi = 0;
                    for (int j = 0; j < 2; j++) {
                        for (int i = 0; i < 2; i++) {
                            int cx = 2 * x + i, cy = 2 * y + j;
                            if (cx < cw && cy < ch) {
                                lo = fminf(lo, child[cy * cw + cx][0]);
                                hi = fmaxf(hi, child[cy * cw + cx][1]);
                            }
                        }
                    }
                    if (memcmp(&lo, &level[y * w + x][0], 4) || memcmp(&hi, &level[y * w + x][1], 4))
                        bad++;
                }
            }
        }
    }
    return bad;
}
