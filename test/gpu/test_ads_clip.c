/* The DIRT build's exact depth range per (primitive, tile) candidate
 * (glsl/dirt/clip.glsl), case by case:
 *  - inside:   triangles within one tile (range = their vertices' depths);
 *  - contains: large oblique triangles over many tiles (range from the
 *              tile's corner rays on the triangle's plane);
 *  - crossing: edges across tiles, at every tile size;
 *  - near:     triangles crossing the near plane and passing behind the eye;
 *  - far:      triangles crossing the far plane (frame bounds that leave
 *              part of the geometry out), and both planes at once (a
 *              pentagon after the near/far clip);
 *  - degenerate: collinear, single-point and edge-on triangles;
 *  - on tiles: vertices at tile corners, on tile edges and on the planes
 *              moved out by DIRT_CLIP_EPS, edges along a row of those corners
 *              (three constraints meeting at one point).
 * No primitive is kept out as large (dirt_ads_opts.large = -1): every
 * triangle goes through the clip.
 * Every case is checked against the CPU reference (ads_check: no missing
 * pair, nothing beyond the allowed set, exact buckets, bounds in the
 * sandwich, Hi-Z exact) at S = 1, 2, 4 in views single and cube+camera, and
 * compared with the plain Sutherland-Hodgman clip of every candidate
 * (dirt_ads_opts.reference_clip), tile by tile: the same primitives except
 * boundary pairs (reached only by the eps-moved planes, which rounding
 * decides for either build), and where the primitives are the same, the
 * same depth bounds up to float rounding (bit for bit in the inside case). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "common/layout.h"
#include "dirt/log.h"
#include "gpu.h"

enum { W = 64, H = 48 };

static const float TAN_Y = 0.57735027f; /* tan(30 degrees): yfov 60 degrees */

/* Camera at z = 3 looking down -z; world point at eye depth d whose NDC
 * position is (x, y) in a W x H view. */
static void at_ndc(float d, double x, double y, float out[3])
{
    out[0] = (float)(x * d * TAN_Y * W / H);
    out[1] = (float)(y * d * TAN_Y);
    out[2] = 3.0f - d;
}

/* NDC x of pixel column i of the W-wide view (a tile edge when i % S == 0). */
static double ndc_x(double i)
{
    return -1.0 + 2.0 * i / W;
}

static double ndc_y(double j)
{
    return -1.0 + 2.0 * j / H;
}


/* Per tile, the sorted (primitive << 8 | bucket) pairs of a read-back
 * structure (B <= 256 here). */
static uint64_t *tile_lists(const dirt_ads_data *d, uint32_t **offsets)
{
    uint32_t *off = calloc((size_t)d->num_tiles + 1, sizeof(*off));
    uint64_t *out = malloc(((size_t)d->num_nodes + 1) * sizeof(*out));
    size_t n = 0;
    for (int t = 0; t < d->num_tiles; t++) {
        off[t] = (uint32_t)n;
        for (int b = 0; b < d->buckets; b++) {
            for (uint32_t node = d->heads[(size_t)b * d->num_tiles + t];
                 node != DIRT_LIST_END && n < d->num_nodes; node = d->nodes[node][1])
                out[n++] = ((uint64_t)d->nodes[node][0] << 8) | (uint64_t)b;
        }
        for (size_t i = off[t] + 1; i < n; i++) { /* insertion sort: short lists */
            uint64_t v = out[i];
            size_t j = i;
            while (j > off[t] && out[j - 1] > v) {
                out[j] = out[j - 1];
                j--;
            }
            out[j] = v;
        }
    }
    off[d->num_tiles] = (uint32_t)n;
    *offsets = off;
    return out;
}

typedef struct diff {
    int tiles;       /* tiles compared */
    int boundary;    /* tiles whose primitives differ only by boundary pairs */
    int other;       /* tiles whose primitives differ otherwise */
    int lists;       /* tiles with the same primitives and bounds but other buckets
                        (a range moved across a bucket edge by rounding) */
    int bounds;      /* tiles with the same primitives whose bounds differ in a bit */
    double max_rel;  /* largest relative difference of those bounds */
} diff;

/* Is `prim` a required pair of tile t (its exact clip, eps 0, non-empty)? */
static bool required(const ads_ref *req, int t, uint32_t prim)
{
    for (uint32_t k = req->offsets[t]; k < req->offsets[t + 1]; k++)
        if (req->entries[k].prim == prim)
            return true;
    return false;
}

/* Compares the fast build `a` with the reference clip's `b`, tile by tile.
 * Pairs the exact clip does not have but the eps-moved planes reach
 * (boundary pairs) may be in either build: float rounding decides them. */
static diff compare(const dirt_ads_data *a, const dirt_ads_data *b, const ads_ref *req)
{
    diff r = {a->num_tiles, 0, 0, 0, 0, 0.0};
    uint32_t *oa, *ob;
    uint64_t *la = tile_lists(a, &oa), *lb = tile_lists(b, &ob);
    for (int t = 0; t < a->num_tiles; t++) {
        /* The primitives of each list (sorted, buckets dropped). */
        bool same_prims = true, only_boundary = true;
        uint32_t i = oa[t], j = ob[t];
        while (i < oa[t + 1] || j < ob[t + 1]) {
            uint64_t pa = i < oa[t + 1] ? la[i] >> 8 : UINT64_MAX;
            uint64_t pb = j < ob[t + 1] ? lb[j] >> 8 : UINT64_MAX;
            uint64_t p = pa < pb ? pa : pb;
            if (pa != pb) {
                same_prims = false;
                if (required(req, t, (uint32_t)p))
                    only_boundary = false;
            }
            while (i < oa[t + 1] && la[i] >> 8 == p)
                i++;
            while (j < ob[t + 1] && lb[j] >> 8 == p)
                j++;
        }
        if (!same_prims) {
            if (only_boundary)
                r.boundary++;
            else
                r.other++;
            continue;
        }
        bool same_bounds = true;
        for (int k = 0; k < 2; k++) {
            float x = a->depth[t][k], y = b->depth[t][k];
            if (memcmp(&x, &y, sizeof(x))) {
                same_bounds = false;
                double rel = isinf(x) || isinf(y) ? INFINITY
                                                  : fabs((double)x - y) / fmax(fabs(y), 1e-30);
                r.max_rel = fmax(r.max_rel, rel);
            }
        }
        if (!same_bounds)
            r.bounds++;
        uint32_t na = oa[t + 1] - oa[t], nb = ob[t + 1] - ob[t];
        if (same_bounds && (na != nb || memcmp(la + oa[t], lb + ob[t], na * sizeof(*la))))
            r.lists++;
    }
    free(la);
    free(lb);
    free(oa);
    free(ob);
    return r;
}

/* Builds `o` with the fast range and with the reference clip; compares. */
static diff build_compare(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                          const dirt_camera *cam, dirt_ads_opts o)
{
    diff r = {0, 0, 0, 0, 0, 0.0};
    dirt_ads_data d[2];
    ads_ref req = {0};
    bool ok = true;
    for (int i = 0; i < 2; i++) {
        o.reference_clip = i == 1;
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        ok = ok && ads && dirt_ads_build(ads, f, cam) && dirt_ads_read(ads, &d[i]);
        if (ok && i == 0)
            ok = ads_ref_build(dirt_ads_views(ads), f, 0.0, d[0].large, d[0].num_large, &req);
        dirt_ads_destroy(ads);
    }
    CHECK(ok);
    if (!ok)
        return r;
    r = compare(&d[0], &d[1], &req);
    fprintf(stderr, "%-12s %-11s S=%d: %5d tiles; primitives differ by boundary pairs in %d, "
            "otherwise in %d; bounds differ in %d (max rel %.2g); buckets in %d\n", label,
            mode_name(o.views.mode), o.views.tile_size, r.tiles, r.boundary, r.other, r.bounds,
            r.max_rel, r.lists);
    CHECK_MSG(r.other == 0, "%s: a required pair is missing from one build (%d tiles)", label,
              r.other);
    CHECK_MSG(r.max_rel <= ADS_DEPTH_TOL, "%s: bounds differ from the reference clip by %.3g",
              label, r.max_rel);
    for (int i = 0; i < 2; i++)
        dirt_ads_data_free(&d[i]);
    ads_ref_free(&req);
    return r;
}

/* CPU check of the fast build at S = 1, 2, 4, both view modes, and the
 * comparison with the reference clip. */
static void run_case(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                     const dirt_camera *cam)
{
    static const int sizes[] = {1, 2, 4};
    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE_CAMERA};
    for (int m = 0; m < 2; m++) {
        for (int s = 0; s < 3; s++) {
            dirt_ads_opts o = {
                .views = {.mode = modes[m], .width = W, .height = H, .face_size = 32,
                          .tile_size = sizes[s]},
                .buckets = 8,
                .force_emulation = true,
                .large = -1,
                .bucket_masks = true,
            };
            build_and_check(gpu, label, f, cam, &o);
            build_compare(gpu, label, f, cam, o);
        }
    }
}

/* The camera of every case: at z = 3, looking at the origin, 60 degrees. */
static dirt_camera camera(void)
{
    dirt_camera cam = {.type = DIRT_CAMERA_PERSPECTIVE, .yfov = 1.0471976f, .znear = 0.1f};
    dirt_camera_look_at(&cam, (const float[3]){0, 0, 3}, (const float[3]){0, 0, 0},
                        (const float[3]){0, 1, 0});
    return cam;
}

/* Small triangles well inside single tiles of the 4x4 grid, at several
 * depths: every candidate of the S = 4 build is the inside case. */
static void case_inside(dirt_gpu *gpu, const dirt_camera *cam)
{
    enum { N = 60 };
    dirt_frame *f = frame_new(N);
    unsigned seed = 7;
    for (int t = 0; t < N; t++) {
        int tx = (int)(ads_rand(&seed) * (W / 4)), ty = (int)(ads_rand(&seed) * (H / 4));
        float d = 0.5f + 1.5f * ads_rand(&seed);
        float p[3][3];
        for (int k = 0; k < 3; k++) {
            double x = ndc_x(4 * tx + 1.2 + 1.6 * ads_rand(&seed));
            double y = ndc_y(4 * ty + 1.2 + 1.6 * ads_rand(&seed));
            /* depths up to 4x apart within one triangle */
            at_ndc(d * (1.0f + 3.0f * ads_rand(&seed)), x, y, p[k]);
        }
        set_tri(f, (size_t)t, p[0], p[1], p[2]);
    }
    frame_bounds(f);
    /* At S = 4 every range is its vertices' depths: the bounds equal the
     * reference clip's bit for bit. */
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H,
                                 .tile_size = 4},
                       .buckets = 8, .force_emulation = true, .large = -1};
    build_and_check(gpu, "inside S=4", f, cam, &o);
    diff r = build_compare(gpu, "inside", f, cam, o);
    CHECK(r.tiles > 0 && r.boundary == 0 && r.bounds == 0 && r.lists == 0);
    run_case(gpu, "inside", f, cam);
    frame_free(f);
}

/* Two large oblique triangles (a floor seen at a grazing angle and a tilted
 * wall) covering most tiles; a few small ones on top. */
static void case_contains(dirt_gpu *gpu, const dirt_camera *cam)
{
    dirt_frame *f = frame_new(4);
    set_tri(f, 0, (float[3]){-8, -1, 2.5f}, (float[3]){8, -1, 2.5f}, (float[3]){0, -1, -30});
    set_tri(f, 1, (float[3]){-6, -4, -1}, (float[3]){6, -4, -4}, (float[3]){0, 6, -2});
    set_tri(f, 2, (float[3]){-0.1f, 0.1f, 0.5f}, (float[3]){0.2f, 0.1f, 0.4f},
            (float[3]){0, 0.3f, 0.45f});
    set_tri(f, 3, (float[3]){-5, 5, -6}, (float[3]){5, 5, -6}, (float[3]){0, -5, -6});
    frame_bounds(f);
    run_case(gpu, "contains", f, cam);
    frame_free(f);
}

/* Medium random triangles: most candidates are real crossings. */
static void case_crossing(dirt_gpu *gpu, const dirt_camera *cam)
{
    enum { N = 300 };
    dirt_frame *f = frame_new(N);
    unsigned seed = 99;
    for (int t = 0; t < N; t++) {
        float c[3] = {ads_rand(&seed) * 4 - 2, ads_rand(&seed) * 3 - 1.5f, ads_rand(&seed) * 3 - 2};
        float p[3][3];
        float size = 0.05f + 0.4f * ads_rand(&seed);
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                p[k][i] = c[i] + size * (ads_rand(&seed) - 0.5f) * (i == 2 ? 3.0f : 1.0f);
        set_tri(f, (size_t)t, p[0], p[1], p[2]);
    }
    frame_bounds(f);
    run_case(gpu, "crossing", f, cam);
    frame_free(f);
}

/* Triangles through the near plane, some passing behind the eye; and the
 * far plane: the frame's bounds leave the far ends out, so the views' far
 * planes cut them (and one triangle crosses both planes). */
static void case_near_far(dirt_gpu *gpu, const dirt_camera *cam)
{
    dirt_frame *f = frame_new(6);
    set_tri(f, 0, (float[3]){0, 0.1f, 3.5f}, (float[3]){0.5f, 0.5f, 2.0f},
            (float[3]){-0.5f, 0.2f, 2.5f});
    set_tri(f, 1, (float[3]){-3, -1, 6}, (float[3]){3, -1, 6}, (float[3]){0, -1, -2});
    set_tri(f, 2, (float[3]){-0.3f, 0.4f, 2.95f}, (float[3]){0.6f, -0.2f, 2.7f},
            (float[3]){0.1f, 0.1f, 3.2f});
    set_tri(f, 3, (float[3]){-1, 0.5f, 0}, (float[3]){1, 0.7f, -12}, (float[3]){0.5f, -0.5f, -2});
    set_tri(f, 4, (float[3]){-2, 0.3f, 3.6f}, (float[3]){2, 0.2f, -15}, (float[3]){0.3f, -0.8f, -3});
    set_tri(f, 5, (float[3]){-1, -1, -1}, (float[3]){1, -1, -1}, (float[3]){0, 1, -1});
    frame_bounds(f);
    run_case(gpu, "near", f, cam);
    /* Bounds of triangles 0-2 and 5 only: 3 and 4 reach beyond every far plane. */
    for (int k = 0; k < 3; k++) {
        f->bounds_min[k] = INFINITY;
        f->bounds_max[k] = -INFINITY;
    }
    for (int t = 0; t < 6; t++) {
        for (int v = 0; v < 3 && t != 3 && t != 4; v++) {
            for (int k = 0; k < 3; k++) {
                f->bounds_min[k] = fminf(f->bounds_min[k], f->position[3 * t + v][k]);
                f->bounds_max[k] = fmaxf(f->bounds_max[k], f->position[3 * t + v][k]);
            }
        }
    }
    f->bounds_min[2] = -4.0f; /* far planes at about 7 units from the eye */
    run_case(gpu, "far", f, cam);
    frame_free(f);
}

/* Zero-area and edge-on triangles. */
static void case_degenerate(dirt_gpu *gpu, const dirt_camera *cam)
{
    dirt_frame *f = frame_new(6);
    set_tri(f, 0, (float[3]){-1, -0.5f, 0}, (float[3]){0, 0, 0}, (float[3]){1, 0.5f, 0});
    set_tri(f, 1, (float[3]){0.3f, 0.2f, 0}, (float[3]){0.3f, 0.2f, 0}, (float[3]){0.3f, 0.2f, 0});
    set_tri(f, 2, (float[3]){-0.5f, 0, 1}, (float[3]){0.5f, 0, 1}, (float[3]){0, 0, -1});
    set_tri(f, 3, (float[3]){0, -1, 0.5f}, (float[3]){0, 1, -0.5f}, (float[3]){0, 0.5f, -1.5f});
    set_tri(f, 4, (float[3]){-1, 0.1f, 0}, (float[3]){1, 0.1001f, 0}, (float[3]){1, 0.1f, 0});
    set_tri(f, 5, (float[3]){0.5f, -0.6f, 1}, (float[3]){0.2f, -0.3f, 0}, (float[3]){-0.1f, 0, -1});
    frame_bounds(f);
    run_case(gpu, "degenerate", f, cam);
    frame_free(f);
}

/* Vertices on tile corners and edges of the 4x4 grid (so on tile edges of
 * every S), on the same lines moved out by DIRT_CLIP_EPS tiles of S = 1
 * (the planes the GPU clips against), and edges along those lines. */
static void case_on_tiles(dirt_gpu *gpu, const dirt_camera *cam)
{
    enum { N = 200 };
    dirt_frame *f = frame_new(N);
    unsigned seed = 4242;
    const double e = DIRT_CLIP_EPS; /* pixels: one tile of S = 1 */
    int t = 0;
    double max_off = 0;
    for (; t < N; t++) {
        float p[3][3];
        int kind = t % 4;
        double off = kind == 0 ? 0.0 : kind == 1 ? -e : kind == 2 ? e : 0.5;
        for (int k = 0; k < 3; k++) {
            double i = 4 * (int)(ads_rand(&seed) * (W / 4 + 1)), j = 4 * (int)(ads_rand(&seed) * (H / 4 + 1));
            double x = ndc_x(i + off), y = ndc_y(j + off);
            if (k == 2 && kind == 3) /* an edge along a tile row, third vertex off it */
                y = ndc_y(j + 2.5);
            else if (kind == 3)
                y = ndc_y(4 * (int)(t / 4 % (H / 4)) - e);
            at_ndc(1.5f + 2.0f * ads_rand(&seed), x, y, p[k]);
        }
        set_tri(f, (size_t)t, p[0], p[1], p[2]);
    }
    frame_bounds(f);
    /* Sanity: a vertex meant for a tile corner lands on it in clip space. */
    {
        float p[3];
        at_ndc(2.0f, ndc_x(8), ndc_y(12), p);
        dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H,
                                     .tile_size = 1}, .buckets = 1, .force_emulation = true,
                          .large = -1};
        dirt_ads *ads = dirt_ads_create(gpu, &o);
        if (ads && dirt_ads_build(ads, f, cam)) {
            const dirt_view *v = &dirt_ads_views(ads)->views[0];
            const float *m = v->view_proj;
            double c[4];
            for (int r = 0; r < 4; r++)
                c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
            max_off = fmax(fabs(c[0] / c[3] - ndc_x(8)), fabs(c[1] / c[3] - ndc_y(12)));
        }
        dirt_ads_destroy(ads);
        CHECK_MSG(max_off < 1e-6, "corner placement off by %g in NDC", max_off);
    }
    run_case(gpu, "on tiles", f, cam);
    frame_free(f);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_camera cam = camera();
    case_inside(gpu, &cam);
    case_contains(gpu, &cam);
    case_crossing(gpu, &cam);
    case_near_far(gpu, &cam);
    case_degenerate(gpu, &cam);
    case_on_tiles(gpu, &cam);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
