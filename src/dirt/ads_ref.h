/* CPU reference of the DIRT acceleration structure and the checker that
 * compares a GPU build against it. Double precision; slow but exact. */
#ifndef DIRT_DIRT_ADS_REF_H
#define DIRT_DIRT_ADS_REF_H

#include <stdbool.h>
#include <stdint.h>

#include "dirt/ads.h"

typedef struct ads_ref_entry {
    uint32_t prim;
    double zmin, zmax;
    double box[4]; /* NDC bounding box of the clipped polygon (xmin, xmax, ymin, ymax) */
} ads_ref_entry;

/* Per global tile, the primitives whose clipped polygon is non-empty
 * (planes moved out by eps, see dirt_clip_triangle_tile), sorted by id:
 * entries[offsets[t] .. offsets[t+1]). The large primitives (`large`,
 * num_large of them: dirt_ads_data.large) are in no tile. */
typedef struct ads_ref {
    int num_tiles;
    uint32_t *offsets;
    ads_ref_entry *entries;
    uint64_t num_entries;
} ads_ref;

bool ads_ref_build(const dirt_view_set *set, const dirt_frame *frame, double eps,
                   const uint32_t *large, int num_large, ads_ref *out);
void ads_ref_free(ads_ref *ref);

/* Result of comparing a GPU build with the references. */
typedef struct ads_check_report {
    uint64_t tiles, required_pairs, gpu_pairs, allowed_pairs;
    uint64_t missing;          /* required pair absent from the GPU lists */
    uint64_t beyond_tolerance; /* GPU pair not even in the allowed set */
    uint64_t duplicates;       /* a primitive twice in one bucket list */
    uint64_t bad_buckets;      /* buckets not exactly those the range overlaps */
    uint64_t bad_bounds;       /* tile depth bounds outside the reference sandwich */
    uint64_t bad_list_links;   /* node index out of range in a list */
    uint64_t bad_masks;        /* tiles whose occupancy mask (one bit per depth
                                  slab, uniform buckets) is empty where the lists
                                  are not or the reverse, or misses a slab an exact
                                  range meets, or has one no allowed range meets;
                                  0 when there are no masks */
    uint64_t bad_rects;        /* sub-tile rectangles (dirt_ads_data.rects): a pair
                                  whose rectangle misses a cell of its exact clip's
                                  box, takes one beyond its widened clip's box
                                  widened by DIRT_SUBTILE_MARGIN cells, or differs
                                  between its buckets */
    uint64_t bad_node_depths;  /* node depth ranges (dirt_ads_data.node_depths): a
                                  node whose sub-slabs miss one of its exact range's
                                  in its bucket, take one beyond its widened range's,
                                  or run backwards (lo > hi) */
} ads_check_report;

/* The cells {x0, x1, y0, y1} of the DIRT_SUBTILE_GRID grid over tile
 * (tx, ty) of view v (tile size S) that NDC box b = {xmin, xmax, ymin, ymax}
 * widened by `margin` cells meets, clamped to the tile. */
void ads_ref_box_cells(const dirt_view *v, int S, int tx, int ty, const double b[4],
                       double margin, int cells[4]);

/* The cells {x0, x1, y0, y1} of sub-tile rectangle byte r (common/layout.h). */
void ads_ref_rect_cells(uint8_t r, int cells[4]);

/* Checks `data` (read back from a build over `set`, `frame`, B buckets;
 * its large primitives left out) against the exact references at eps 0
 * (must be present) and
 * 2 * DIRT_CLIP_EPS (may be present). Depth bounds and bucket edges are
 * compared with relative tolerance `tol`. With sub-tile rectangles
 * (data->rects) every pair's rectangle holds the cells of the exact clip's
 * NDC box (eps 0) and lies within those of the widened clip's box widened
 * by DIRT_SUBTILE_MARGIN cells (bad_rects). With node depth ranges
 * (data->node_depths) every node's sub-slabs hold those of the pair's
 * exact range in its bucket and lie within those of its widened range,
 * with the structure's own buckets, uniform or adaptive
 * (bad_node_depths). */
bool ads_check(const dirt_view_set *set, const dirt_frame *frame, const dirt_ads_data *data,
               double tol, ads_check_report *report);

/* CPU min/max pyramid from level 0 of `data` (same layout), compared
 * exactly with the GPU's; returns the number of differing entries. */
uint64_t ads_check_pyramid(const dirt_view_set *set, const dirt_ads_data *data);

#endif
