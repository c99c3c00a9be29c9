/* Memory accounting: the bytes the structures report as used equal the
 * analytic formulas evaluated with independently measured counts, and the
 * bytes reported as allocated are what GL really holds.
 *  - DIRT (default scene, 64x48 camera + six 32x32 faces, S = 2, B = 8;
 *    raster and compute builds):
 *    used = 96 B x primitives (vertices) + 8 B x pyramid entries (depth
 *    bounds and mips) + 4 B x B x tiles (list heads) + with
 *    opts.bucket_masks 4 B x tiles (bucket occupancy masks, B <= 32; none
 *    without) + 8 B x the larger of the nodes and 2 x the compute build's
 *    work records (the node pool holds the records first) + 16 B x
 *    n_p (the build's candidates) + with opts.large_grid 8 B x large
 *    primitives x cells of their grid (per view, the first pyramid level of
 *    at most DIRT_LARGE_GRID cells per side; none without), with the nodes and the (primitive, tile)
 *    pairs n_p counted by walking every list of the structure read back (not
 *    the GPU's counters); the DIRT paper's Table 3 (8 B x 1.33 + 4 B x B per tile
 *    + 8 B x c x n_p) then differs from the depth, heads and nodes only by the
 *    mip factor: the pyramid holds between 1 and 1.34 entries per tile.
 *  - MMRT (same views, B = 4): used = vertices + 8 B x pyramid + 2 x 4 B x B
 *    x pixels (heads and tails) + (12 + 32) B x fragments; the MMRT paper's
 *    formula is pixels x (8 + 8 B) + fragments x (12 + 32) exactly.
 *  - Both: each buffer's GL_BUFFER_SIZE equals the allocated figure. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "dirt/ads.h"
#include "dirt/ads_internal.h"
#include "mmrt/mmrt.h"
#include "gl/gl.h"
#include "gpu.h"
#include "mmrt/mmrt_internal.h"

static uint64_t gl_size(GLuint buf)
{
    GLint64 n = -1;
    glGetNamedBufferParameteri64v(buf, GL_BUFFER_SIZE, &n);
    return n < 0 ? 0 : (uint64_t)n;
}

/* What GL holds of a split array (every part), which its stats must say. */
static uint64_t split_size(const gl_split *s)
{
    uint64_t n = 0;
    for (int k = 0; k < DIRT_SPLIT_MAX_PARTS && s->buf[k]; k++)
        n += gl_size(s->buf[k]);
    CHECK(n == gl_split_bytes(s));
    return n;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static void check_dirt(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam, bool grid,
                       bool masks_on, enum dirt_build_mode build)
{
    const int B = 8;
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64, .height = 48,
                                 .face_size = 32, .tile_size = 2},
                       .buckets = B, .force_emulation = true, .large_grid = grid,
                       .bucket_masks = masks_on, .build = build};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    CHECK(ads && dirt_ads_build(ads, f, cam));
    if (!ads)
        return;
    const dirt_ads_stats *st = dirt_ads_get_stats(ads);
    const dirt_view_set *set = dirt_ads_views(ads);
    dirt_ads_data d;
    CHECK(dirt_ads_read(ads, &d));
    uint64_t walked = 0, pairs = 0;
    uint32_t *prims = malloc(((size_t)d.num_nodes + 1) * sizeof(*prims));
    for (int t = 0; prims && t < d.num_tiles; t++) {
        size_t k = 0;
        for (int b = 0; b < d.buckets; b++) {
            for (uint32_t n = d.heads[(size_t)b * d.num_tiles + t];
                 n != DIRT_LIST_END && walked <= d.num_nodes; n = d.nodes[n][1]) {
                walked++;
                if (k < d.num_nodes)
                    prims[k++] = d.nodes[n][0];
            }
        }
        qsort(prims, k, sizeof(*prims), cmp_u32);
        for (size_t i = 0; i < k; i++)
            pairs += i == 0 || prims[i] != prims[i - 1];
    }
    free(prims);
    dirt_ads_data_free(&d);
    CHECK_MSG(pairs == st->samples, "lists hold %llu (primitive, tile) pairs, stats say %llu",
              (unsigned long long)pairs, (unsigned long long)st->samples);
    CHECK_MSG(walked == st->nodes, "lists hold %llu nodes, stats say %llu",
              (unsigned long long)walked, (unsigned long long)st->nodes);
    uint64_t tiles = (uint64_t)set->num_tiles, pyramid = (uint64_t)set->pyramid_size;
    /* the node pool: the compute build's work records (16 B each) use it
     * before the nodes */
    uint64_t pool = 2 * st->work_records > walked ? 2 * st->work_records : walked;
    CHECK(build == DIRT_BUILD_COMPUTE ? st->work_records > 0 : st->work_records == 0);
    /* the large primitives' grid (only with opts.large_grid): 8 B per
     * large primitive and cell, the cells of the first pyramid level of at
     * most DIRT_LARGE_GRID per side */
    uint64_t cells = 0;
    for (int v = 0; grid && v < set->count; v++) {
        int L = 0, tx = set->views[v].tiles_x, ty = set->views[v].tiles_y;
        while ((tx + (1 << L) - 1) >> L > DIRT_LARGE_GRID || (ty + (1 << L) - 1) >> L > DIRT_LARGE_GRID)
            L++;
        cells += (uint64_t)((tx + (1 << L) - 1) >> L) * (uint64_t)((ty + (1 << L) - 1) >> L);
    }
    CHECK(st->num_large > 0);
    CHECK(st->bytes_large_grid == 8 * cells * (uint64_t)st->num_large);
    CHECK(ads->large_cells_size >= st->bytes_large_grid &&
          st->bytes_large_grid_allocated == ads->large_cells_size);
    /* the bucket occupancy masks (opts.bucket_masks, B <= 32): 4 B per
     * tile, after the heads; none without the option */
    uint64_t masks = masks_on && B <= DIRT_BUCKET_MASK_MAX_BUCKETS ? 4 * tiles : 0;
    CHECK(st->bytes_bucket_masks == masks);
    uint64_t formula = 96 * st->primitives + 8 * pyramid + 4 * (uint64_t)B * tiles + masks + 8 * pool +
                       16 * pairs + 8 * cells * (uint64_t)st->num_large;
    CHECK_MSG(st->bytes_total_used == formula, "DIRT used %llu B, formula %llu B",
              (unsigned long long)st->bytes_total_used, (unsigned long long)formula);
    double per_tile = (double)pyramid / (double)tiles;
    CHECK_MSG(per_tile >= 1.0 && per_tile <= 1.34, "pyramid: %.3f entries per tile", per_tile);
    double ads_bytes = (double)(st->bytes_depth + st->bytes_heads + 8 * walked);
    double table3 = (double)tiles * (8.0 * 1.33 + 4.0 * B) + 8.0 * st->buckets_per_sample *
                                                                 (double)st->samples;
    CHECK_NEAR(st->bytes_table3, table3, 1e-6 * table3);
    CHECK_NEAR(table3 - ads_bytes, 8.0 * (1.33 * (double)tiles - (double)pyramid), 1.0);
    /* What GL holds. */
    CHECK(split_size(&ads->heads) == st->bytes_heads + st->bytes_bucket_masks);
    CHECK(split_size(&ads->depth) == st->bytes_depth);
    CHECK(split_size(&ads->nodes) == st->bytes_nodes_allocated);
    CHECK(split_size(&ads->cands) == st->bytes_candidates_allocated);
    CHECK(split_size(&ads->vertices) >= st->bytes_vertices);
    fprintf(stderr, "DIRT%s%s%s: %llu primitives, %llu tiles, %llu pyramid entries, %llu nodes "
                    "(walked), %llu work records: used %llu B = formula; Table 3 %.0f B vs "
                    "structure %.0f B\n",
            build == DIRT_BUILD_COMPUTE ? " (compute build)" : "",
            grid ? " (large primitives' grid)" : "", masks_on ? " (bucket masks)" : "",
            (unsigned long long)st->primitives,
            (unsigned long long)tiles,
            (unsigned long long)pyramid, (unsigned long long)walked,
            (unsigned long long)st->work_records, (unsigned long long)st->bytes_total_used,
            table3, ads_bytes);
    dirt_ads_destroy(ads);
}

static void check_mmrt(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam)
{
    const int B = 4;
    dirt_mmrt_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64, .height = 48,
                                  .face_size = 32, .tile_size = 1},
                        .buckets = B};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
    CHECK(m && dirt_mmrt_build(m, f, cam));
    if (!m)
        return;
    const dirt_mmrt_stats *st = dirt_mmrt_get_stats(m);
    const dirt_view_set *set = dirt_mmrt_views(m);
    uint64_t P = 0;
    for (int v = 0; v < set->count; v++)
        P += (uint64_t)set->views[v].width * (uint64_t)set->views[v].height;
    CHECK(P == st->pixels);
    uint64_t formula = st->bytes_vertices + 8 * (uint64_t)set->pyramid_size +
                       2 * 4 * (uint64_t)B * P + (12 + 32) * st->fragments;
    CHECK_MSG(st->bytes_total_used == formula, "MMRT used %llu B, formula %llu B",
              (unsigned long long)st->bytes_total_used, (unsigned long long)formula);
    CHECK(st->bytes_vertices == st->primitives * (3 * 32 + 4));
    double paper = (double)P * (8.0 + 8.0 * B) + (double)st->fragments * (12 + 32);
    CHECK_NEAR(st->bytes_paper, paper, 0.5);
    CHECK(st->fragments > 0 && st->fragments <= 64 * P);
    CHECK(split_size(&m->heads) == st->bytes_heads / 2 &&
          split_size(&m->tails) == st->bytes_heads / 2);
    CHECK(split_size(&m->ids) == st->bytes_id_nodes_allocated);
    CHECK(split_size(&m->data) == st->bytes_data_nodes_allocated);
    CHECK(split_size(&m->depth) == st->bytes_depth);
    fprintf(stderr, "MMRT: %llu pixels, %llu fragments: used %llu B = formula; paper %.0f B\n",
            (unsigned long long)P, (unsigned long long)st->fragments,
            (unsigned long long)st->bytes_total_used, paper);
    dirt_mmrt_destroy(m);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    CHECK(f != NULL);
    if (f) {
        dirt_camera cam = f->cameras[0];
        check_dirt(gpu, f, &cam, false, false, DIRT_BUILD_RASTER);
        check_dirt(gpu, f, &cam, true, true, DIRT_BUILD_RASTER);
        check_dirt(gpu, f, &cam, false, false, DIRT_BUILD_COMPUTE);
        check_mmrt(gpu, f, &cam);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
