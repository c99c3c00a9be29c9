/* Adaptive depth buckets (dirt_ads_opts.depth_buckets; doc/dirt-build.md,
 * "Adaptive depth buckets"):
 *  - lists, entry for entry, and edges, value for value, against a CPU
 *    build that learns the edges on its own: it reads each (tile,
 *    primitive)'s fine bins from a uniform build of B' = 4 B buckets (the
 *    fine bins are that build's buckets; that build is checked against the
 *    exact CPU clip by ads_check), sorts the fine bins of the tile's range
 *    ends (two per primitive), takes the quantiles (edge b = 1 + the
 *    ceil(b C / B)-th smallest of the C ends, 0 for an empty tile) and puts
 *    each primitive in the
 *    buckets of its end bins (binary search over the edges); the depth
 *    bounds and pyramid equal the uniform build's bit for bit; default
 *    scene, a random soup, CesiumMilkTruck (t = 0.5; in CI a missing
 *    ../shared fails), views single and cube+camera, S in {1, 2, 4}, B in
 *    {1, 3, 8, 16}, raster and compute build;
 *  - the trace through adaptive buckets finds the uniform trace's hits bit
 *    for bit (primitive, view, t, u, v) for every ray type (camera G-buffer
 *    rays, closest and any hit), default scene and Cornell box, single and
 *    cube+camera, S = 1 and 2, B = 8, and agrees with Embree as the uniform
 *    trace does (cube+camera: 99.9 % of the rays); and on a dense soup with
 *    random rays from inside it (B = 4 and 16), bit for bit with the
 *    uniform trace and Embree's hit for every ray;
 *  - the memory figures (edges B/2 uints per tile, histogram 4 B uints per
 *    tile, in the totals), B above 1024 refused, and a session switched to
 *    adaptive buckets remakes the structure and renders the uniform one's
 *    image bit for bit; so does the alpha planes' scene (trace builds with
 *    alpha tests and large primitives, and with large primitives and work
 *    counters). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ads_common.h"
#include "alpha_scene.h"
#include "common/layout.h"
#include "dirt/scene.h"
#include "dirt/session.h"
#include "gpu.h"
#include "ref/raytypes.h"
#include "ref/ref.h"

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The bucket of fine bin f: how many of the edges e[1..B-1] are at or below
 * f (e is non-decreasing: the last index whose edge is <= f). */
static int bucket_of_bin(const int *e, int B, int f)
{
    int lo = 1, hi = B; /* first index in [1, B) with e > f, B if none */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (e[mid] > f)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo - 1;
}

/* The CPU's adaptive structure from the uniform fine-bin build `u` (B' =
 * 4 B): its entries (sorted, as list_triples) and edges ((B + 1) per tile);
 * false when `u` is not a contiguous fine-bin range per primitive. */
static bool cpu_adaptive(const dirt_ads_data *u, int B, uint64_t **entries, size_t *count,
                         int **edges_out)
{
    size_t n_u = 0;
    uint64_t *fine = list_triples(u, &n_u); /* sorted by tile, bin, prim */
    if (!fine)
        return false;
    int T = u->num_tiles, H = u->buckets;
    int *edges = malloc((size_t)(B + 1) * (size_t)T * sizeof(int));
    uint64_t *out = malloc((n_u + 1) * (size_t)B * sizeof(*out));
    /* per tile: (prim, bin) pairs sorted by prim */
    uint64_t *pb = malloc((n_u + 1) * sizeof(*pb));
    int *ends = malloc(2 * (n_u + 1) * sizeof(int));
    size_t n = 0, i = 0;
    bool ok = true;
    for (int t = 0; t < T; t++) {
        size_t j = i;
        while (j < n_u && (int)(fine[j] >> 40) == t)
            j++;
        size_t m = 0;
        for (size_t k = i; k < j; k++) {
            int bin = (int)((fine[k] >> 32) & 0xFF);
            pb[m++] = ((uint64_t)(uint32_t)fine[k] << 32) | (uint32_t)bin;
        }
        /* each primitive's first and last bin: its range's ends */
        qsort(pb, m, sizeof(*pb), cmp_u64);
        size_t nends = 0;
        for (size_t k = 0; k < m; k++) {
            uint32_t prim = (uint32_t)(pb[k] >> 32);
            if (k == 0 || (uint32_t)(pb[k - 1] >> 32) != prim)
                ends[nends++] = (int)(uint32_t)pb[k];
            if (k + 1 == m || (uint32_t)(pb[k + 1] >> 32) != prim)
                ends[nends++] = (int)(uint32_t)pb[k];
        }
        /* the quantiles of the sorted ends */
        qsort(ends, nends, sizeof(int), cmp_int);
        int *e = edges + (size_t)(B + 1) * (size_t)t;
        e[0] = 0;
        e[B] = H;
        for (int b = 1; b < B; b++) {
            uint64_t q = ((uint64_t)b * nends + (uint64_t)B - 1) / (uint64_t)B;
            e[b] = q == 0 ? 0 : ends[q - 1] + 1;
        }
        /* each primitive's bins: one contiguous run; its buckets */
        for (size_t k = 0; k < m;) {
            size_t l = k;
            uint32_t prim = (uint32_t)(pb[k] >> 32);
            while (l < m && (uint32_t)(pb[l] >> 32) == prim)
                l++;
            int f0 = (int)(uint32_t)pb[k], f1 = (int)(uint32_t)pb[l - 1];
            if (f1 - f0 + 1 != (int)(l - k))
                ok = false;
            int b0 = bucket_of_bin(e, B, f0), b1 = bucket_of_bin(e, B, f1);
            for (int b = b0; b <= b1; b++)
                out[n++] = ((uint64_t)t << 40) | ((uint64_t)b << 32) | prim;
            k = l;
        }
        i = j;
    }
    CHECK_MSG(ok, "the uniform fine-bin build has a primitive in non-adjacent bins");
    qsort(out, n, sizeof(*out), cmp_u64);
    free(fine);
    free(pb);
    free(ends);
    *entries = out;
    *count = n;
    *edges_out = edges;
    return ok;
}

/* The adaptive build at `o` against the CPU's adaptive structure made from
 * the uniform build at 4 B. */
static void compare_lists(dirt_gpu *gpu, const char *label, const dirt_frame *f,
                          const dirt_camera *cam, dirt_ads_opts o)
{
    int B = o.buckets;
    dirt_ads_data du, da;
    dirt_ads_opts ou = o;
    ou.buckets = DIRT_ADAPT_FINE * B;
    ou.depth_buckets = DIRT_DEPTH_BUCKETS_UNIFORM;
    o.depth_buckets = DIRT_DEPTH_BUCKETS_ADAPTIVE;
    dirt_ads *au = ads_build_read(gpu, &ou, f, cam, &du);
    dirt_ads *aa = ads_build_read(gpu, &o, f, cam, &da);
    if (!au || !aa)
        goto done;
    const dirt_view_set *set = dirt_ads_views(aa);
    int T = da.num_tiles;
    /* the fine-bin build itself against the exact CPU clip */
    ads_check_report r = {0};
    CHECK(ads_check(dirt_ads_views(au), f, &du, ADS_DEPTH_TOL, &r));
    CHECK(r.missing == 0 && r.beyond_tolerance == 0 && r.duplicates == 0 &&
          r.bad_buckets == 0 && r.bad_bounds == 0 && r.bad_list_links == 0 &&
          r.bad_masks == 0);
    bool same_depth = du.pyramid_size == da.pyramid_size &&
                      memcmp(du.depth, da.depth, (size_t)da.pyramid_size * 8) == 0;
    CHECK_MSG(same_depth, "%s: adaptive depth bounds differ from uniform's", label);
    CHECK(da.fine_bins == DIRT_ADAPT_FINE * B && da.edges != NULL && du.edges == NULL);
    uint64_t *cpu = NULL, *gpu_e = NULL;
    int *edges = NULL;
    size_t nc = 0, ng = 0;
    if (!cpu_adaptive(&du, B, &cpu, &nc, &edges) || !(gpu_e = list_triples(&da, &ng)))
        goto free_lists;
    size_t bad_edges = 0, nonempty = 0, nonuniform = 0;
    for (int t = 0; t < T; t++) {
        const uint16_t *g = da.edges + (size_t)(B + 1) * (size_t)t;
        const int *c = edges + (size_t)(B + 1) * (size_t)t;
        bool differ = false, uni = true;
        for (int b = 0; b <= B; b++) {
            differ |= g[b] != c[b];
            uni &= c[b] == DIRT_ADAPT_FINE * b;
        }
        bad_edges += differ;
        nonempty += c[B - (B > 1)] > 0 || B == 1;
        nonuniform += !uni && c[1] > 0;
    }
    /* the bucket occupancy masks: exactly the CPU structure's buckets with
     * an entry */
    size_t bad_masks = 0;
    bool want_masks = o.bucket_masks && B <= DIRT_BUCKET_MASK_MAX_BUCKETS;
    CHECK_MSG((da.masks != NULL) == want_masks,
              "%s B=%d: bucket masks %s", label, B, da.masks ? "present" : "missing");
    if (da.masks) {
        uint32_t *m = calloc((size_t)T + 1, sizeof(*m));
        for (size_t k = 0; k < nc; k++)
            m[cpu[k] >> 40] |= 1u << ((cpu[k] >> 32) & 0xFFu);
        for (int t = 0; t < T; t++)
            bad_masks += m[t] != da.masks[t];
        free(m);
    }
    size_t differ = 0, i = 0, j = 0;
    while (i < nc || j < ng) {
        if (j == ng || (i < nc && cpu[i] < gpu_e[j]))
            differ++, i++;
        else if (i == nc || gpu_e[j] < cpu[i])
            differ++, j++;
        else
            i++, j++;
    }
    const dirt_ads_stats *su = dirt_ads_get_stats(au), *sa = dirt_ads_get_stats(aa);
    fprintf(stderr, "%-16s %-11s S=%d B=%-2d %s: %6d tiles (%zu with edges not uniform) | "
            "entries CPU %7zu, GPU %7zu, differ %zu | edges differ in %zu tiles, masks in %zu "
            "| c %.2f (the fine-bin build's %.2f)\n", label, mode_name(o.views.mode),
            set->tile_size, B, o.build == DIRT_BUILD_COMPUTE ? "compute" : "raster", T,
            nonuniform, nc, ng, differ, bad_edges, bad_masks, sa->buckets_per_sample,
            su->buckets_per_sample);
    CHECK(ng > 0 && nonempty > 0);
    CHECK_MSG(differ == 0 && nc == ng, "%s S=%d B=%d %s: %zu list entries differ from the CPU's",
              label, set->tile_size, B, mode_name(o.views.mode), differ);
    CHECK_MSG(bad_edges == 0, "%s S=%d B=%d %s: edges differ in %zu tiles", label,
              set->tile_size, B, mode_name(o.views.mode), bad_edges);
    CHECK_MSG(bad_masks == 0, "%s S=%d B=%d %s: bucket masks differ from the CPU's in %zu tiles",
              label, set->tile_size, B, mode_name(o.views.mode), bad_masks);
    CHECK(sa->samples == su->samples && sa->nodes == ng);
    CHECK(sa->depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE &&
          su->depth_buckets == DIRT_DEPTH_BUCKETS_UNIFORM);
    /* memory: B/2 edge words and 4 B histogram bins per tile, and a mask
     * per tile when B has them, in the totals */
    CHECK(sa->bytes_bucket_edges == (uint64_t)(B / 2) * (uint64_t)T * 4);
    CHECK(sa->bytes_bucket_histogram == (uint64_t)DIRT_ADAPT_FINE * B * (uint64_t)T * 4);
    CHECK(su->bytes_bucket_edges == 0 && su->bytes_bucket_histogram == 0);
    CHECK(sa->bytes_bucket_masks == (want_masks ? (uint64_t)T * 4 : 0));
    CHECK(sa->bytes_total_used == sa->bytes_vertices + sa->bytes_depth + sa->bytes_heads +
                                      sa->bytes_nodes_used + sa->bytes_candidates_used +
                                      sa->bytes_bucket_edges + sa->bytes_bucket_histogram +
                                      sa->bytes_bucket_masks);
    CHECK(sa->depth_runs == 1 && sa->fill_runs == 1);
free_lists:
    free(cpu);
    free(gpu_e);
    free(edges);
done:
    if (au)
        dirt_ads_data_free(&du);
    if (aa)
        dirt_ads_data_free(&da);
    dirt_ads_destroy(au);
    dirt_ads_destroy(aa);
}

static void lists_frame(dirt_gpu *gpu, const char *label, const dirt_frame *f)
{
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    static const int sizes[] = {1, 2, 4};
    static const int buckets[] = {1, 3, 8, 16};
    static const enum dirt_view_mode modes[] = {DIRT_VIEWS_SINGLE, DIRT_VIEWS_CUBE_CAMERA};
    for (int m = 0; m < 2; m++)
        for (int s = 0; s < 3; s++)
            for (int b = 0; b < 4; b++) {
                dirt_ads_opts o = {
                    .views = {.mode = modes[m], .width = 48, .height = 36, .face_size = 24,
                              .tile_size = sizes[s]},
                    .buckets = buckets[b], .force_emulation = true,
                    .bucket_masks = s != 1, /* (S = 2: without) */
                    .build = (m + s + b) & 1 ? DIRT_BUILD_COMPUTE : DIRT_BUILD_RASTER};
                compare_lists(gpu, label, f, &cam, o);
            }
}

static uint32_t g_rng = 777u;
static float frand(void)
{
    return ads_rand(&g_rng);
}

/* Small random triangles in a unit box, denser near one corner (depth
 * clusters). */
static dirt_frame *soup(size_t n)
{
    dirt_frame *f = frame_new(n);
    for (size_t t = 0; t < n; t++) {
        float c[3], p[3][3];
        for (int k = 0; k < 3; k++) {
            float x = frand();
            c[k] = t % 3 ? x * x * x : x;
        }
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                p[v][k] = c[k] + 0.1f * (frand() - 0.5f);
        set_tri(f, t, p[0], p[1], p[2]);
    }
    frame_bounds(f);
    return f;
}

/* Adaptive against uniform hits (bit for bit) and against Embree. */
static void compare_hits(dirt_gpu *gpu, const char *label, dirt_scene *scene)
{
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    enum { GW = 48, GH = 36 };
    CHECK(accel && dirt_gbuffer_build(accel, scene, f, &cam, GW, GH, &g));
    size_t n = GW * GH;
    dirt_ray *rays = malloc(n * sizeof(*rays));
    dirt_hit *h[2] = {malloc(n * sizeof(dirt_hit)), malloc(n * sizeof(dirt_hit))};
    dirt_ref_hit *ref = malloc(n * sizeof(*ref));
    for (int k = 0; k < 4; k++) {
        dirt_ads *ads[2];
        for (int a = 0; a < 2; a++) {
            dirt_ads_opts o = {
                .views = {.mode = k & 1 ? DIRT_VIEWS_SINGLE : DIRT_VIEWS_CUBE_CAMERA,
                          .width = 64, .height = 48, .face_size = 32, .tile_size = k & 2 ? 2 : 1},
                .buckets = 8, .force_emulation = true, .bucket_masks = k != 0,
                .depth_buckets = a ? DIRT_DEPTH_BUCKETS_ADAPTIVE : DIRT_DEPTH_BUCKETS_UNIFORM};
            ads[a] = dirt_ads_create(gpu, &o);
            CHECK(ads[a] && dirt_ads_build(ads[a], f, &cam));
        }
        for (int t = 0; ads[0] && ads[1] && t < DIRT_RAY_TYPES; t++) {
            size_t cnt = dirt_rays_generate(&g, &cam, (enum dirt_ray_type)t, 5, rays);
            bool vis = t == DIRT_RAY_VISIBILITY;
            dirt_trace_opts to = {.any_hit = vis};
            dirt_trace_stats ts[2] = {{0}, {0}};
            for (int a = 0; a < 2; a++)
                CHECK(dirt_ads_trace(ads[a], rays, cnt, h[a], &to, &ts[a]));
            CHECK(ts[0].aborted == 0 && ts[1].aborted == 0);
            if (vis) {
                uint8_t *occ = malloc(cnt + 1);
                dirt_ref_occluded(accel, (const dirt_ref_ray *)rays, occ, cnt, 0);
                size_t differ = 0, agree = 0;
                for (size_t i = 0; i < cnt; i++) {
                    differ += (h[0][i].prim != DIRT_HIT_NONE) != (h[1][i].prim != DIRT_HIT_NONE);
                    agree += (h[1][i].prim != DIRT_HIT_NONE) == (occ[i] != 0);
                }
                free(occ);
                CHECK_MSG(differ == 0, "%s k=%d visibility: %zu of %zu occlusions differ", label,
                          k, differ, cnt);
                if (!(k & 1))
                    CHECK_MSG(agree >= cnt * 999 / 1000, "%s k=%d visibility: %zu of %zu agree "
                              "with Embree", label, k, agree, cnt);
                continue;
            }
            dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, cnt, 0);
            size_t differ = 0, agree = 0, found = 0;
            for (size_t i = 0; i < cnt; i++) {
                differ += h[0][i].prim != h[1][i].prim || h[0][i].view != h[1][i].view ||
                          memcmp(&h[0][i].u, &h[1][i].u, 3 * sizeof(float)) != 0;
                bool dh = h[1][i].prim != DIRT_HIT_NONE, eh = ref[i].prim != DIRT_REF_MISS;
                found += dh;
                agree += dh == eh && (!dh || h[1][i].prim == ref[i].prim ||
                                      fabs(h[1][i].t - ref[i].t) <= 1e-4 * fmax(ref[i].t, 1e-3));
            }
            fprintf(stderr, "%-8s %-11s S=%d %-10s: %zu rays, %zu hits, %zu differ from the "
                    "uniform trace, %zu agree with Embree\n", label,
                    k & 1 ? "single" : "cube+camera", k & 2 ? 2 : 1, dirt_ray_type_names[t], cnt,
                    found, differ, agree);
            CHECK_MSG(differ == 0, "%s k=%d %s: %zu of %zu hits differ from uniform buckets'",
                      label, k, dirt_ray_type_names[t], differ, cnt);
            CHECK(found > 0);
            if (!(k & 1))
                CHECK_MSG(agree >= cnt * 999 / 1000, "%s k=%d %s: %zu of %zu agree with Embree",
                          label, k, dirt_ray_type_names[t], agree, cnt);
        }
        dirt_ads_destroy(ads[0]);
        dirt_ads_destroy(ads[1]);
    }
    free(rays);
    free(h[0]);
    free(h[1]);
    free(ref);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

/* A dense soup and random rays from inside it: adaptive against uniform
 * hits (bit for bit) and against Embree (every ray), where one primitive
 * spans several buckets and the early stop after a bucket matters. */
static void soup_hits(dirt_gpu *gpu)
{
    dirt_frame *f = soup(3000);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    enum { N = 4000 };
    dirt_ray *rays = malloc(N * sizeof(*rays));
    for (size_t i = 0; i < N; i++) {
        ads_random_ray(f, &g_rng, &rays[i]);
    }
    dirt_hit *h[2] = {malloc(N * sizeof(dirt_hit)), malloc(N * sizeof(dirt_hit))};
    dirt_ref_hit *ref = malloc(N * sizeof(*ref));
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    CHECK(accel != NULL);
    if (accel)
        dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, N, 0);
    for (int k = 0; accel && k < 4; k++) {
        for (int a = 0; a < 2; a++) {
            dirt_ads_opts o = {
                .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64, .height = 48,
                          .face_size = 48, .tile_size = k & 1 ? 2 : 1},
                .buckets = k & 2 ? 16 : 4, .force_emulation = true, .bucket_masks = k != 0,
                .depth_buckets = a ? DIRT_DEPTH_BUCKETS_ADAPTIVE : DIRT_DEPTH_BUCKETS_UNIFORM};
            dirt_ads *ads = dirt_ads_create(gpu, &o);
            dirt_trace_stats ts = {0};
            CHECK(ads && dirt_ads_build(ads, f, &cam) &&
                  dirt_ads_trace(ads, rays, N, h[a], NULL, &ts));
            CHECK(ts.aborted == 0);
            dirt_ads_destroy(ads);
        }
        size_t differ = 0, wrong = 0, found = 0;
        for (size_t i = 0; i < N; i++) {
            differ += h[0][i].prim != h[1][i].prim || h[0][i].view != h[1][i].view ||
                      memcmp(&h[0][i].u, &h[1][i].u, 3 * sizeof(float)) != 0;
            bool dh = h[1][i].prim != DIRT_HIT_NONE, eh = ref[i].prim != DIRT_REF_MISS;
            found += dh;
            wrong += dh != eh || (dh && h[1][i].prim != ref[i].prim &&
                                  fabs(h[1][i].t - ref[i].t) > 1e-4 * fmax(ref[i].t, 1e-3));
        }
        fprintf(stderr, "soup cube+camera S=%d B=%d: %d rays, %zu hits, %zu differ from the "
                "uniform trace, %zu from Embree\n", k & 1 ? 2 : 1, k & 2 ? 16 : 4, N, found,
                differ, wrong);
        CHECK_MSG(differ == 0, "soup k=%d: %zu of %d hits differ from uniform buckets'", k,
                  differ, N);
        CHECK_MSG(wrong == 0, "soup k=%d: %zu of %d hits differ from Embree's", k, wrong, N);
        CHECK(found > N / 4);
    }
    dirt_ref_accel_destroy(accel);
    free(rays);
    free(h[0]);
    free(h[1]);
    free(ref);
    frame_free(f);
}

/* Options: more than 1024 buckets refused; a session switched to adaptive
 * buckets renders the uniform image bit for bit. */
static void test_session(dirt_gpu *gpu)
{
    dirt_ads *bad = dirt_ads_create(gpu, &(dirt_ads_opts){.buckets = DIRT_ADAPT_MAX_BUCKETS + 1,
                                                          .depth_buckets =
                                                              DIRT_DEPTH_BUCKETS_ADAPTIVE});
    CHECK(bad == NULL);
    dirt_ads_destroy(bad);
    dirt_scene *scene = dirt_scene_create_default();
    enum { W = 80, H = 60 };
    dirt_session_opts o = {.width = W, .height = H, .bounces = 2, .buckets = 8};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    float *img[2] = {NULL, NULL};
    for (int i = 0; s && i < 2; i++) {
        if (i) {
            o.depth_buckets = DIRT_DEPTH_BUCKETS_ADAPTIVE;
            bool restarted = false;
            CHECK(dirt_session_set_opts(s, &o, &restarted) && restarted);
        }
        CHECK(dirt_session_add_samples(s, 2, NULL, NULL));
        const dirt_session_stats *st = dirt_session_get_stats(s);
        CHECK(st->has_ads && st->aborted == 0 &&
              st->ads.depth_buckets ==
                  (i ? DIRT_DEPTH_BUCKETS_ADAPTIVE : DIRT_DEPTH_BUCKETS_UNIFORM));
        /* the session's buffer list (its bytes_total) names the two arrays */
        uint64_t edges = 0, hist = 0, sum = 0;
        for (int k = 0; k < st->num_buffers; k++) {
            sum += st->buffers[k].used;
            if (!strcmp(st->buffers[k].name, "bucket edges"))
                edges += st->buffers[k].used;
            if (!strcmp(st->buffers[k].name, "bucket histogram"))
                hist += st->buffers[k].used;
        }
        CHECK(edges == st->ads.bytes_bucket_edges && hist == st->ads.bytes_bucket_histogram);
        CHECK(i == 0 || (edges > 0 && hist > 0));
        CHECK(sum == st->bytes_total_used);
        const dirt_image *im = dirt_session_image(s);
        CHECK(im && im->width == W && im->height == H);
        if (im) {
            img[i] = malloc(sizeof(float) * 4 * W * H);
            memcpy(img[i], im->rgba, sizeof(float) * 4 * W * H);
        }
    }
    CHECK_MSG(img[0] && img[1] && memcmp(img[0], img[1], sizeof(float) * 4 * W * H) == 0,
              "session: the adaptive buckets' image differs from the uniform one's");
    free(img[0]);
    free(img[1]);
    o.buckets = DIRT_ADAPT_MAX_BUCKETS + 1;
    CHECK(s && !dirt_session_set_opts(s, &o, NULL));
    dirt_session_destroy(s);
    dirt_scene_destroy(scene);
}

/* The trace's fuller builds with adaptive buckets link (they add no storage
 * block; llvmpipe allows 16): on the alpha planes' scene the path tracer's
 * trace with alpha tests and large primitives, and the work counters' trace
 * with large primitives; the image is the uniform one's bit for bit. */
static void test_alpha_large_count(dirt_gpu *gpu)
{
    dirt_scene *scene = alpha_scene_load(false);
    CHECK(scene != NULL);
    if (!scene)
        return;
    enum { W = 48, H = 36 };
    float *img[2] = {NULL, NULL};
    for (int i = 0; i < 2; i++) {
        dirt_session_opts o = {.width = W, .height = H, .bounces = 2, .buckets = 8,
                               .count_work = true,
                               .depth_buckets = i ? DIRT_DEPTH_BUCKETS_ADAPTIVE
                                                  : DIRT_DEPTH_BUCKETS_UNIFORM};
        dirt_session *s = dirt_session_create(gpu, scene, &o);
        CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
        const dirt_session_stats *st = s ? dirt_session_get_stats(s) : NULL;
        CHECK(st && st->has_ads && st->has_work && st->ads.num_large > 0 && st->aborted == 0);
        const dirt_image *im = s ? dirt_session_image(s) : NULL;
        if (im) {
            img[i] = malloc(sizeof(float) * 4 * W * H);
            memcpy(img[i], im->rgba, sizeof(float) * 4 * W * H);
        }
        dirt_session_destroy(s);
    }
    CHECK_MSG(img[0] && img[1] && memcmp(img[0], img[1], sizeof(float) * 4 * W * H) == 0,
              "alpha scene: the adaptive buckets' image differs from the uniform one's");
    free(img[0]);
    free(img[1]);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *def = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(def, 0, NULL);
    lists_frame(gpu, "default", f);
    dirt_frame_destroy(f);
    dirt_scene_destroy(def);
    dirt_frame *sp = soup(1500);
    lists_frame(gpu, "soup", sp);
    frame_free(sp);
    const char *shared = test_shared_dir();
    char path[4096];
    if (shared) {
        snprintf(path, sizeof(path), "%s/scenes/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf", shared);
        dirt_scene *sc = dirt_scene_load(path, NULL);
        CHECK(sc != NULL);
        if (sc) {
            dirt_frame *tf = dirt_scene_evaluate(sc, 0.5f, NULL);
            lists_frame(gpu, "CesiumMilkTruck", tf);
            dirt_frame_destroy(tf);
            dirt_scene_destroy(sc);
        }
    } else {
        fprintf(stderr, "../shared absent: default scene and soup only\n");
    }
    compare_hits(gpu, "default", dirt_scene_create_default());
    if (shared) {
        snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox-Original.obj", shared);
        compare_hits(gpu, "cornell", dirt_scene_load(path, NULL));
    }
    soup_hits(gpu);
    test_session(gpu);
    test_alpha_large_count(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
