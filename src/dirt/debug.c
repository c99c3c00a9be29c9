/* Pictures and printed stats of a built DIRT structure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/display.h"
#include "common/layout.h"
#include "dirt/ads.h"
#include "dirt/image.h"
#include "dirt/ads_internal.h"
#include "dirt/file.h"
#include "dirt/log.h"

static const char *view_name(const dirt_view *v)
{
    static const char *faces[] = {"px", "nx", "py", "ny", "pz", "nz"};
    return v->face < 0 ? "camera" : faces[v->face];
}

/* Heat colour of x in [0, 1]: the ramp of common/display.h (black, blue,
 * red, yellow, white), as the window's HEAT presentation draws it. */
static void heat(float x, float rgb[3])
{
    static const float keys[DIRT_HEAT_KEYS][3] = {{DIRT_HEAT_KEY_0}, {DIRT_HEAT_KEY_1},
                                                  {DIRT_HEAT_KEY_2}, {DIRT_HEAT_KEY_3},
                                                  {DIRT_HEAT_KEY_4}};
    const int last = DIRT_HEAT_KEYS - 1;
    x = fminf(fmaxf(x, 0), 1) * (float)last;
    int i = (int)x < last ? (int)x : last - 1;
    float t = x - (float)i;
    for (int k = 0; k < 3; k++)
        rgb[k] = keys[i][k] + t * (keys[i + 1][k] - keys[i][k]);
}

static bool save(dirt_image *img, const char *dir, int vi, const char *vname, const char *what,
                 bool quiet)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/ads_v%d_%s_%s.png", dir, vi, vname, what);
    if (!dirt_image_write_png(img, path, NULL))
        return false;
    if (!quiet)
        printf("wrote %s\n", path);
    return true;
}

bool dirt_ads_write_debug(dirt_ads *ads, const char *dir, bool quiet)
{
    dirt_ads_data d;
    if (!dirt_ads_read(ads, &d))
        return false;
    const dirt_view_set *set = dirt_ads_views(ads);
    uint32_t *len = calloc((size_t)d.num_tiles + 1, sizeof(uint32_t));
    bool ok = len != NULL;
    uint32_t longest = 1;
    for (int b = 0; ok && b < d.buckets; b++) {
        for (int t = 0; t < d.num_tiles; t++) {
            uint32_t steps = 0;
            for (uint32_t n = d.heads[(size_t)b * d.num_tiles + t];
                 n != DIRT_LIST_END && n < d.num_nodes && steps <= d.num_nodes; n = d.nodes[n][1])
                steps++;
            len[t] += steps;
            if (len[t] > longest)
                longest = len[t];
        }
    }
    for (int vi = 0; ok && vi < set->count; vi++) {
        const dirt_view *v = &set->views[vi];
        dirt_image *img = dirt_image_create(v->tiles_x, v->tiles_y);
        if (!img) {
            ok = false;
            break;
        }
        /* Tile rows are bottom-up; image rows top-down. */
        for (int what = 0; ok && what < 3; what++) {
            for (int ty = 0; ty < v->tiles_y; ty++) {
                for (int tx = 0; tx < v->tiles_x; tx++) {
                    int t = v->tile_base + ty * v->tiles_x + tx;
                    float *px = img->rgba + ((size_t)(v->tiles_y - 1 - ty) * v->tiles_x + tx) * 4;
                    px[3] = 1;
                    if (what == 0) {
                        heat((float)len[t] / (float)longest, px);
                    } else if (d.depth[t][0] > d.depth[t][1]) {
                        px[0] = 0.2f, px[1] = px[2] = 0;
                    } else {
                        float z = d.depth[t][what == 1 ? 0 : 1];
                        float g = 1.0f - (z - v->znear) / (v->zfar - v->znear);
                        px[0] = px[1] = px[2] = fminf(fmaxf(g, 0), 1);
                    }
                }
            }
            static const char *names[] = {"lists", "zmin", "zmax"};
            ok = save(img, dir, vi, view_name(v), names[what], quiet);
        }
        dirt_image_destroy(img);
    }
    if (ok && ads->graph) {
        /* The build's three graphs (build, fill, bound), one digraph each. */
        char path[4096];
        snprintf(path, sizeof(path), "%s/ads_graph.dot", dir);
        char *dots[3] = {fg_dot(ads->graph), fg_dot(ads->fill), fg_dot(ads->bound)};
        size_t bytes = 0;
        for (int i = 0; i < 3; i++)
            bytes += dots[i] ? strlen(dots[i]) : 0;
        char *dot = dots[0] && dots[1] && dots[2] ? malloc(bytes + 1) : NULL;
        if (dot) {
            dot[0] = 0;
            for (int i = 0; i < 3; i++)
                strcat(dot, dots[i]);
        }
        ok = dot && dirt_write_file_atomic(path, dot, strlen(dot));
        free(dot);
        for (int i = 0; i < 3; i++)
            free(dots[i]);
        if (ok && !quiet)
            printf("wrote %s\n", path);
    }
    if (!quiet && ok)
        printf("longest tile list: %u nodes\n", longest);
    free(len);
    dirt_ads_data_free(&d);
    return ok;
}

void dirt_ads_print_stats(const dirt_ads *ads, void *out_)
{
    FILE *out = out_;
    const dirt_ads_stats *s = dirt_ads_get_stats(ads);
    const dirt_view_set *set = dirt_ads_views(ads);
    fprintf(out, "DIRT structure: %d view(s), S=%d, B=%d, %d tiles, %s\n",
            set->count, set->tile_size, dirt_ads_buckets(ads), set->num_tiles,
            s->build == DIRT_BUILD_COMPUTE ? "compute build"
            : s->conservative_nv           ? "GL_NV_conservative_raster rasterization"
                                           : "emulated conservative rasterization");
    fprintf(out, "  primitives %llu, clipped primitive samples n_p %llu, buckets per sample c %.3f, "
            "nodes %llu; passes run: depth %d, fill %d, candidate bound %d\n",
            (unsigned long long)s->primitives, (unsigned long long)s->samples,
            s->buckets_per_sample, (unsigned long long)s->nodes, s->depth_runs, s->fill_runs,
            s->bound_pass ? 1 : 0);
    fprintf(out, "  MB: vertices %.3f, depth+mips %.3f, heads %.3f, nodes %.3f used / %.3f "
            "allocated, candidates %.3f used / %.3f allocated, large primitives' grid %.3f; "
            "total %.3f used / %.3f allocated\n", s->bytes_vertices / 1e6,
            s->bytes_depth / 1e6, s->bytes_heads / 1e6, s->bytes_nodes_used / 1e6,
            s->bytes_nodes_allocated / 1e6, s->bytes_candidates_used / 1e6,
            s->bytes_candidates_allocated / 1e6, s->bytes_large_grid / 1e6,
            s->bytes_total_used / 1e6,
            s->bytes_total_allocated / 1e6);
    double ads_used = (double)(s->bytes_depth + s->bytes_heads + s->bytes_nodes_used);
    fprintf(out, "  Table 3 formula %.3f MB vs measured %.3f MB (depth+heads+nodes; mip "
            "factor %.3f vs 1.33)\n", s->bytes_table3 / 1e6, ads_used / 1e6,
            set->num_tiles ? (double)set->pyramid_size / set->num_tiles : 0.0);
    for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++) {
        fprintf(out, "  pass %-16s", dirt_ads_pass_names[i]);
        if (s->clock != DIRT_CLOCK_NONE && s->ms[i] >= 0)
            fprintf(out, "  %8.3f ms (%s clock)\n", s->ms[i], dirt_clock_names[s->clock]);
        else
            fprintf(out, "       n/a\n");
    }
}
