#version 450 core
// DIRT Trace (paper section 4.2.1): the closest hit of every ray of a batch,
// through the per-primitive image-space structure.
//
// The ray is clipped to every view frustum and cut into pieces in order of
// t, each in one view (camera view first when present, then the others by
// the parameter at which the ray enters them); a piece is marched cell by
// cell on the Hi-Z pyramid (from a starting level, see trace_view): a cell
// whose depth bounds the ray's depth span misses is skipped (and the march
// climbs a level where it leaves the parent cell), otherwise the march
// descends; at level 0 (a tile) the buckets the ray's depth span overlaps
// are walked in the ray's depth direction with exact watertight
// ray-triangle tests. A hit counts only if it lies in the
// tile's frustum (planes moved out by DIRT_CLIP_EPS, as in the build) and is
// the closest so far. Scanning stops after a bucket once the best hit lies
// within the depth slabs scanned so far (a primitive stored in several
// buckets can give a hit beyond the current slab; stopping there could skip
// a nearer primitive of the next bucket). Cell exits are solved exactly in
// clip space, where tile boundaries are planes linear in the ray parameter.
// Large primitives (built with DIRT_TRACE_LARGE, when the structure has
// some; dirt/large.glsl: in no list) are tested first, with the ray's whole
// segment; such a hit counts where the ray is inside a view (where a listed
// primitive's hit would be found), and the march then runs up to it.
// With their grid (built with DIRT_TRACE_LARGE_GRID as well, when the
// structure has one: dirt_ads_opts.large_grid) they are tested per piece
// instead, before its march: a march over the view's large primitives' grid
// (common/layout.h) tests each one at most once per ray, in the first cell
// whose depth range for it the ray's depth span meets; the acceptance rule
// is the same, so the hits are the same bit for bit.
// Alpha (built with DIRT_TRACE_ALPHA, for scenes with MASK or BLEND
// materials: integrator/alpha.glsl, u_alpha): a candidate of such a material
// that the alpha test rejects is not a hit, and the walk goes on as if it
// were not in the list. The variant without it is the opaque scenes' trace,
// untouched (the unused test in the inner loop cost llvmpipe 3x).
// Adaptive depth buckets (built with DIRT_ADAPTIVE, for a structure built
// so; common/constants.h, DIRT_ADAPT_*): a depth's bucket comes from its
// fine bin through the tile's edges, as in the build's count pass, and a
// bucket's depth slab ends at its edges' fine-bin boundaries.
// Sub-tile rectangles (built with DIRT_SUB_TILES, for a structure built
// with them: dirt_ads_opts.sub_tiles; common/layout.h): a node whose cells
// the ray's segment in the tile misses is skipped before its vertices are
// read (see g_seg_lim).
// Bucket occupancy masks (built with DIRT_BUCKET_MASKS, for a structure
// built with them: dirt_ads_opts.bucket_masks, B <= 32; common/constants.h):
// a tile none of whose buckets in the ray's depth span holds a node is not
// walked (see walk_tile).
// Node depth ranges (built with DIRT_NODE_DEPTHS, for a build that stored
// them: dirt_ads_opts.node_depths, dirt_ads_stats.node_depths;
// common/layout.h; a build that did not is traced without): a node whose
// depth range in its bucket misses the ray's depth span there is skipped
// before its vertices are read (see walk_tile).
// Work counters (built with DIRT_TRACE_COUNT; the plain build has none):
// work[i] = (tiles walked, Hi-Z steps, list nodes read, exact triangle
// tests, large primitives' included) of ray i.
#if defined(DIRT_TRACE_LARGE_GRID) && !defined(DIRT_TRACE_LARGE)
#define DIRT_TRACE_LARGE 1 // (the grid is the large primitives')
#endif
#include "common/layout.h"
#include "common/ray_batch.glsl"
#ifdef DIRT_TRACE_ALPHA
#include "integrator/alpha.glsl"
#endif

layout(local_size_x = DIRT_GROUP_SIZE) in;

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
layout(std430, binding = DIRT_BIND_PARAMS) readonly buffer Params {
    dirt_gpu_ads_params params;
};
#define DIRT_DEPTH_READONLY
#include "common/depth.glsl"
#define DIRT_HEADS_READONLY
#define DIRT_NODES_READONLY
#ifdef DIRT_TRACE_LARGE_GRID
#define DIRT_CANDIDATES_NONE // (not read: a storage block fewer for the grid's)
#else
#define DIRT_CANDIDATES_READONLY
#endif
#include "dirt/structure.glsl"
layout(std430, binding = DIRT_BIND_COUNTERS) buffer Counters {
    dirt_gpu_ads_counters counters;
};
layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_HITS) writeonly buffer Hits {
    dirt_gpu_hit hits[];
};
layout(std430, binding = DIRT_BIND_HIT_HEADS) buffer HitHeads {
    uint hit_heads[];
};
#ifdef DIRT_TRACE_LARGE_GRID
layout(std430, binding = DIRT_BIND_LARGE_CELLS) readonly buffer LargeCells {
    uvec2 large_cells[];
};
#endif
#ifdef DIRT_TRACE_COUNT
layout(std430, binding = DIRT_BIND_WORK) writeonly buffer Work {
    uvec4 work[];
};
uvec4 g_work = uvec4(0u);
#define COUNT_WORK(c) g_work.c++
#else
#define COUNT_WORK(c)
#endif

layout(location = DIRT_LOC_TRACE_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_TRACE_HIZ_TOP) uniform int u_hiz_top;  // highest level a march climbs to; < 0 = top
layout(location = DIRT_LOC_TRACE_ANY_HIT) uniform int u_any_hit;  // 1: stop at the first accepted hit
layout(location = DIRT_LOC_TRACE_LINK) uniform int u_link;     // 1: link hits per ADS tile (raster Fetch)
layout(location = DIRT_LOC_TRACE_FROM_SURFACES) uniform int u_from_surfaces; // 1: rays leave surfaces

#define MAX_STEPS 65536

// Set when a loop ended without reaching its exit condition. Mesa's
// llvmpipe caps the loop iterations of one invocation (all loops together,
// 65535) and silently leaves loops past that; such rays are counted as
// aborted instead of being reported as (possibly wrong) misses.
bool g_cut = false;

// The ray's alpha key (dirt_alpha_ray_key_g; set when u_alpha != 0).
uint g_alpha_key = 0u;

// The last four primitives the ray's test rejected. A primitive is listed
// in every tile and bucket its clipped footprint overlaps, so a march meets
// the same candidate in cell after cell, in every view; one of these is not
// tested again. A rejection is for good: a miss of the triangle, or a hit at
// or before tmin, stays one; so does a hit at or beyond tmax, since tmax
// only shrinks (it is best.t, or the float after best.t for a primitive
// below best.prim, and a new best either lies before best.t or ties it
// with a lower primitive; either way no rejected t gets below the new
// tmax). A candidate whose hit lies outside the tile is not kept: it counts
// in the tile it lies in.
uvec4 g_never = uvec4(DIRT_NO_HIT);

#ifdef DIRT_SUB_TILES
// The cells of the 4 x 4 grid over the tile being walked that the ray's
// segment in it, [t, texit] of the march, may meet (the NDC box of its ends,
// widened by DIRT_SUBTILE_MARGIN cells, clamped to the tile), as limits on a
// node's rectangle fields (common/layout.h): (x1, 3 - x0, y1, 3 - y0) of the
// segment's cells; a node is skipped when a field exceeds its limit (its
// cells lie beside the segment's). Set by trace_view before walk_tile.
//
// Why the hits stay the same: a hit accepted in this tile at a parameter s
// in [t, texit] lies on the segment, so its NDC lies in the segment's box
// (NDC moves monotonically along a segment with w > 0), and on the
// primitive's part inside the tile frustum (planes moved out by eps), so in
// the box the build took the node's cells from; both boxes are widened by
// far more than float rounding, so the cells meet and the node is tested.
// A hit the plain walk would accept here at s outside [t, texit] (in the
// tile's eps band, or before the near plane) may be skipped. If s lies in
// some view's segment, the piece holding s is marched in a view whose
// frustum holds the hit point, and the march is at s in a tile T' whose
// frustum holds it (pieces and cells cover their parameter ranges without
// gaps; a boundary parameter is in both cells), where the primitive is
// listed with cells holding the point, and T''s segment holds s: found
// there, unless the march stopped before s, which it does only for a hit
// at or before s (t >= best.t; the bucket early stop, whose slabs hold every
// nearer hit of the tile; any-hit, which wants any hit): the closest hit and
// its tie-break by primitive id are the same. Any-hit rays may return
// another hit than the plain trace, never a miss for a hit inside a view.
// A hit outside every view's segment (in a border tile's eps band beyond
// the view, or nearer than the near plane) is not in the structure: the
// plain trace finds it only by chance, this one need not.
uvec4 g_seg_lim = uvec4(3u);

// g_seg_lim of the segment [ta, tb] of ray (co, cd) (clip space) in the
// tile of NDC rectangle [nlo, nhi]. The whole tile where an end is not in
// front of the eye (not so in a march, whose pieces lie in a view).
uvec4 segment_cells(vec4 co, vec4 cd, float ta, float tb, vec2 nlo, vec2 nhi)
{
    vec4 a = co + ta * cd, b = co + tb * cd;
    if (!(a.w > 0.0 && b.w > 0.0))
        return uvec4(3u);
    vec2 cell = (nhi - nlo) / float(DIRT_SUBTILE_GRID);
    vec2 ua = (a.xy / a.w - nlo) / cell, ub = (b.xy / b.w - nlo) / cell;
    float m = float(DIRT_SUBTILE_MARGIN), top = float(DIRT_SUBTILE_GRID - 1);
    vec2 lo = clamp(floor(min(ua, ub) - m), vec2(0.0), vec2(top));
    vec2 hi = clamp(floor(max(ua, ub) + m), vec2(0.0), vec2(top));
    return uvec4(uint(hi.x), uint(top - lo.x), uint(hi.y), uint(top - lo.y));
}
#endif

// Whether the ray sees primitive p at barycentrics (u, w) (alpha test).
bool alpha_accept(uint p, float u, float w)
{
#ifndef DIRT_TRACE_ALPHA
    return true;
#else
    if (u_alpha == 0)
        return true;
    uint m = dirt_prim_material(p);
    if (!dirt_material_alpha_tested_g(m))
        return true;
    dirt_gpu_vertex a = dirt_vertex_at(3u * p), b = dirt_vertex_at(3u * p + 1u),
                    c = dirt_vertex_at(3u * p + 2u);
    vec2 t0 = vec2(a.position.w, a.normal.w);
    vec2 t1 = vec2(b.position.w, b.normal.w);
    vec2 t2 = vec2(c.position.w, c.normal.w);
    return dirt_alpha_accept_g(m, dirt_alpha_uv_g(t0, t1, t2, u, w), g_alpha_key, p);
#endif
}

// ---- watertight ray-triangle test (Woop, Benthin, Wald, JCGT 2013) ----

struct ray_setup {
    vec3 org;
    int kx, ky, kz;
    vec3 shear;  // Sx, Sy, Sz
};

ray_setup setup_ray(vec3 org, vec3 dir)
{
    ray_setup r;
    r.org = org;
    vec3 a = abs(dir);
    r.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    if (dir[r.kz] < 0.0) {
        int tmp = r.kx;
        r.kx = r.ky;
        r.ky = tmp;
    }
    r.shear = vec3(dir[r.kx] / dir[r.kz], dir[r.ky] / dir[r.kz], 1.0 / dir[r.kz]);
    return r;
}

// True for a hit with t in (tmin, tmax); u, v weight vertices 1 and 2.
bool intersect(ray_setup r, vec3 p0, vec3 p1, vec3 p2, float tmin, float tmax,
               out float t, out float u, out float v)
{
    vec3 A = p0 - r.org, B = p1 - r.org, C = p2 - r.org;
    float Ax = A[r.kx] - r.shear.x * A[r.kz], Ay = A[r.ky] - r.shear.y * A[r.kz];
    float Bx = B[r.kx] - r.shear.x * B[r.kz], By = B[r.ky] - r.shear.y * B[r.kz];
    float Cx = C[r.kx] - r.shear.x * C[r.kz], Cy = C[r.ky] - r.shear.y * C[r.kz];
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U == 0.0 || V == 0.0 || W == 0.0) {
        // Edge cases: redo the 2D edge tests in double precision.
        U = float(double(Cx) * double(By) - double(Cy) * double(Bx));
        V = float(double(Ax) * double(Cy) - double(Ay) * double(Cx));
        W = float(double(Bx) * double(Ay) - double(By) * double(Ax));
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0))
        return false;
    float det = U + V + W;
    if (det == 0.0)
        return false;
    float Az = r.shear.z * A[r.kz], Bz = r.shear.z * B[r.kz], Cz = r.shear.z * C[r.kz];
    float T = U * Az + V * Bz + W * Cz;
    float inv = 1.0 / det;
    t = T * inv;
    if (!(t > tmin && t < tmax))
        return false;
    u = V * inv;
    v = W * inv;
    return true;
}

// ---- view helpers ----

mat4 view_matrix(dirt_gpu_view v)
{
    return mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
}

int level_base(dirt_gpu_view v, int d)
{
    return v.level_base[d >> 2][d & 3];
}

ivec2 level_size(dirt_gpu_view v, int d)
{
    return (v.size.zw + (1 << d) - 1) >> d;
}

// A clip-space point's position in tile units of a view of `tiles` tiles
// (w > 0), and the tile holding it, clamped to the view's `count` tiles.
vec2 tile_coord(vec4 c, vec2 tiles)
{
    return (c.xy / c.w * 0.5 + 0.5) * tiles;
}

ivec2 tile_of(vec4 c, vec2 tiles, ivec2 count)
{
    return clamp(ivec2(floor(tile_coord(c, tiles))), ivec2(0), count - 1);
}

// Clips [t0, t1] to the view frustum; false when nothing is left.
bool clip_to_view(vec4 co, vec4 cd, inout float t0, inout float t1)
{
    vec4 planes[6] = vec4[6](vec4(1, 0, 0, 1), vec4(-1, 0, 0, 1), vec4(0, 1, 0, 1),
                             vec4(0, -1, 0, 1), vec4(0, 0, 1, 1), vec4(0, 0, -1, 1));
    for (int i = 0; i < 6; i++) {
        float a = dot(planes[i], co), b = dot(planes[i], cd);
        if (b == 0.0) {
            if (a < 0.0)
                return false;
        } else {
            float t = -a / b;
            if (b > 0.0)
                t0 = max(t0, t);
            else
                t1 = min(t1, t);
        }
    }
    return t0 <= t1;
}

// Parameter where the ray crosses the NDC line coordinate X (axis 0 = x,
// 1 = y): c[axis](t) = X * c.w(t).
float cross_t(vec4 co, vec4 cd, int axis, float X)
{
    float den = cd[axis] - X * cd.w;
    return den == 0.0 ? 1e30 : -(co[axis] - X * co.w) / den;
}

// Parameter where the ray leaves the NDC slab [lo, hi] of one axis, moving
// with NDC velocity sign `motion`. When the crossing solves to t or earlier,
// either the ray approaches its vanishing point inside the slab and never
// leaves on this axis (1e30), or rounding put the crossing just behind:
// leave now (t). Leaving now always makes progress: the march then forces
// the next cell past the boundary (trace_view).
float exit_t(vec4 co, vec4 cd, int axis, float t, float motion, float lo, float hi)
{
    if (motion == 0.0)
        return 1e30;
    float X = motion > 0.0 ? hi : lo;
    float s = cross_t(co, cd, axis, X);
    if (s > t)
        return s;
    bool never = cd.w > 0.0 && (motion > 0.0 ? cd[axis] / cd.w <= X : cd[axis] / cd.w >= X);
    return never ? 1e30 : t;
}

#ifdef DIRT_NODE_DEPTHS
// The parts a tile's depth range is cut into to place a depth for the node
// depth ranges (dirt_node_depth_q): its fine bins with adaptive buckets, its
// B buckets with uniform ones (as the count pass does).
#ifdef DIRT_ADAPTIVE
#define NODE_Q_PARTS(B) (DIRT_ADAPT_FINE * (B))
#else
#define NODE_Q_PARTS(B) (B)
#endif
#endif

struct best_hit {
    float t, u, v;
    uint prim;
    int view;
};

// Walks the buckets of tile `tile` (global index `gt`) that the ray's depth
// span [wa, wb] overlaps. Returns true when a hit inside the tile was found.
// DIRT_BUCKET_MASKS (a structure with bucket occupancy masks:
// dirt_ads_opts.bucket_masks, B <= DIRT_BUCKET_MASK_MAX_BUCKETS): a tile is
// not walked when no candidate's depth range meets the span's depth slabs
// (uniform buckets; dirt_mask_slab) or none of its buckets in the span
// holds a node (adaptive). Exact: a hit accepted in the tile within the span
// lies in its primitive's range there, so a slab of that range is one of the
// span's; a hit in the tile's eps band outside the span is found in the tile
// whose span holds it (see g_seg_lim). The buckets of a walked tile are
// walked as without.
// DIRT_NODE_DEPTHS (node depth ranges): a node whose sub-slabs in its
// bucket (dirt_node_depth_sub) miss the span's there is skipped, exact for
// the same reason: such a hit's depth lies in both its primitive's range
// and the span, and the sub-slab is monotonic in depth.
bool walk_tile(ray_setup rs, vec4 co, vec4 cd, dirt_gpu_view v, int view, ivec2 tile, uint gt,
               float wa, float wb, float tmin, inout best_hit best)
{
    int B = params.config.z;
    uint T = uint(params.config.w);
    int S = params.config.y;
    uvec2 e = dirt_depth(gt);
    float zlo = uintBitsToFloat(e.x), zhi = uintBitsToFloat(e.y);
    float range = zhi - zlo;
    int ba = 0, bb = 0;
#ifdef DIRT_ADAPTIVE
    int H = DIRT_ADAPT_FINE * B;
    ba = dirt_adapt_bucket(gt, dirt_fine_bin(wa, zlo, range, H), B, T);
    bb = dirt_adapt_bucket(gt, dirt_fine_bin(wb, zlo, range, H), B, T);
#else
    if (range > 0.0) {
        ba = clamp(int(floor(float(B) * (wa - zlo) / range)), 0, B - 1);
        bb = clamp(int(floor(float(B) * (wb - zlo) / range)), 0, B - 1);
    }
#endif
#ifdef DIRT_BUCKET_MASKS
    // The tile's bucket occupancy (dirt/structure.glsl): a tile with no node
    // in the span's buckets holds nothing for the ray and is not walked
    // (reading the mask is part of the level-0 Hi-Z step, not a tile
    // walked).
#ifdef DIRT_ADAPTIVE
    uint span_bits = dirt_bucket_bits(ba, bb);
#else
    uint span_bits = dirt_bucket_bits(dirt_mask_slab(wa, zlo, range), dirt_mask_slab(wb, zlo, range));
#endif
    if ((dirt_bucket_occupancy(gt, B, T) & span_bits) == 0u)
        return false;
    COUNT_WORK(x);
#endif
    int step = bb >= ba ? 1 : -1;
#ifdef DIRT_NODE_DEPTHS
    // The span's ends as positions in the tile (dirt_node_depth_q), nearer
    // first; its far end moves to each hit found.
    float qa = dirt_node_depth_q(min(wa, wb), zlo, range, NODE_Q_PARTS(B));
    float qb = dirt_node_depth_q(max(wa, wb), zlo, range, NODE_Q_PARTS(B));
#endif
    // The tile's NDC rectangle, moved out like the build's clip.
    ivec2 lo = tile * S, hi = min(lo + S, v.size.xy);
    vec2 sz = vec2(v.size.xy);
    vec2 e2 = float(DIRT_CLIP_EPS) * 2.0 * float(S) / sz;
    vec2 rlo = -1.0 + 2.0 * vec2(lo) / sz - e2, rhi = -1.0 + 2.0 * vec2(hi) / sz + e2;
    bool found = false;
    for (int b = ba;; b += step) {
        uint node = dirt_head(uint(b) * T + gt);
#ifdef DIRT_NODE_DEPTHS
        // The span's sub-slabs in this bucket: a node whose range has none
        // of them is skipped before its vertices are read.
#ifdef DIRT_ADAPTIVE
        float q0 = float(dirt_adapt_edge(gt, b, B, T)), q1 = float(dirt_adapt_edge(gt, b + 1, B, T));
#else
        float q0 = float(b), q1 = float(b + 1);
#endif
        uint ra = dirt_node_depth_sub(qa, q0, q1), rb = dirt_node_depth_sub(qb, q0, q1);
#endif
        while (node != DIRT_LIST_END) {
            uvec2 n = dirt_node(node);
            COUNT_WORK(z);
#ifdef DIRT_NODE_DEPTHS
            uint d = n.y >> DIRT_NODE_DEPTH_SHIFT;
            node = dirt_node_next_of(n.y);
            // (a read node, not a test; not kept in g_never)
            if ((d & 15u) > rb || (d >> 4) < ra)
                continue;
#else
            node = n.y;
#endif
            uint p = n.x;
#ifdef DIRT_SUB_TILES
            // (a read node, not a test; not kept in g_never: the primitive
            // may meet the ray in another tile)
            uint r = p >> DIRT_SUBTILE_SHIFT;
            p &= DIRT_SUBTILE_PRIM_MASK;
            if (any(greaterThan(uvec4(r, r >> 2, r >> 4, r >> 6) & 3u, g_seg_lim)))
                continue;
#endif
            float t, u, w;
            // Ties at the same t go to the lower primitive id: the lists'
            // order comes from the build's atomics and varies between runs.
            float tmax = best.prim != DIRT_NO_HIT && p < best.prim
                             ? uintBitsToFloat(floatBitsToUint(best.t) + 1u) : best.t;
            if (any(equal(g_never, uvec4(p))))
                continue;
            COUNT_WORK(w);
            if (!intersect(rs, dirt_vertex_pos_at(3u * p), dirt_vertex_pos_at(3u * p + 1u),
                           dirt_vertex_pos_at(3u * p + 2u), tmin, tmax, t, u, w)) {
                g_never = uvec4(p, g_never.xyz);
                continue;
            }
            vec4 c = co + t * cd;
            vec2 ndc = c.xy / c.w;
            if (c.w <= 0.0 || any(lessThan(ndc, rlo)) || any(greaterThan(ndc, rhi)))
                continue;
            if (!alpha_accept(p, u, w))
                continue; // alpha-tested away: not a hit
            best.t = t;
            best.u = u;
            best.v = w;
            best.prim = p;
            best.view = view;
            found = true;
            if (u_any_hit != 0)
                return true;
#ifdef DIRT_NODE_DEPTHS
            // The span now ends at the hit: a nearer hit (or a tie) of
            // another primitive in this tile lies at the hit's depth or
            // before it along the ray, inside that primitive's range, so a
            // node whose range lies wholly beyond is skipped.
            float qh = dirt_node_depth_q(co.w + t * cd.w, zlo, range, NODE_Q_PARTS(B));
            if (cd.w > 0.0)
                qb = min(qb, qh);
            else if (cd.w < 0.0)
                qa = max(qa, qh);
            ra = dirt_node_depth_sub(qa, q0, q1);
            rb = dirt_node_depth_sub(qb, q0, q1);
#endif
        }
        if (node != DIRT_LIST_END)
            g_cut = true;
        if (found) {
            float wh = co.w + best.t * cd.w;
#ifdef DIRT_ADAPTIVE
            // (the bucket's depth edges: its first and past-last fine bins')
            if (step > 0 && (b == B - 1 ||
                             wh <= zlo + float(dirt_adapt_edge(gt, b + 1, B, T)) * range / float(H)))
                break;
            if (step < 0 &&
                (b == 0 || wh >= zlo + float(dirt_adapt_edge(gt, b, B, T)) * range / float(H)))
                break;
#else
            if (step > 0 && (b == B - 1 || wh <= zlo + float(b + 1) * range / float(B)))
                break;
            if (step < 0 && (b == 0 || wh >= zlo + float(b) * range / float(B)))
                break;
#endif
        }
        if (b == bb)
            break;
    }
    return found;
}

// Marches the ray through one view over [t0, t1]. Returns false when the
// march ran out of steps (the ray is then reported as aborted).
//
// The march covers [t0, t1] without gaps: a cell is entered at exactly the
// parameter where the previous one was left, and its depth span starts
// there. Which cell the ray is in at that parameter is not decided by
// locating the point alone (on the boundary just crossed, rounding can put
// it on either side): along each axis the tile index can only move in the
// ray's NDC direction (NDC coordinates are monotonic along a segment with
// w > 0), so the march keeps a bound per axis, the tile last visited, moved
// past the boundary whenever a cell is left on that axis, and the located
// tile is held to it. (Formerly t stepped past each exit by eps_t and the
// point was located there: the next cell's depth span then began eps_t late
// and missed a wall lying at the depth of that instant, one seen square-on
// by a cube face, whose tiles' zmin = zmax; and where the ray moved slowly
// in NDC the point could still locate in the old cell, whose exit had to be
// given up as "never", and the march went on in the wrong tile column. Both
// let rays leave the default scene's closed room.)
bool trace_view(ray_setup rs, vec3 org, vec3 dir, int view, float tmin, float t0, float t1,
                bool first, inout best_hit best)
{
    dirt_gpu_view v = views[view];
    mat4 vp = view_matrix(v);
    vec4 co = vp * vec4(org, 1.0), cd = vp * vec4(dir, 0.0);
    int S = params.config.y;
    int top = v.placement.z - 1;
    if (u_hiz_top >= 0)
        top = min(top, u_hiz_top);
    vec2 tiles = vec2(v.size.xy) / float(S);
    // Direction of motion in NDC: c.xy / c.w moves with the sign of
    // cd.xy c.w - c.xy cd.w, which is the same for every t (the t terms
    // cancel): one sign for the whole segment.
    vec2 motion = cd.xy * co.w - co.xy * cd.w;
    bvec2 back = lessThan(motion, vec2(0.0));
    // The tile bound per axis (the tile index never goes below it when moving
    // up, never above it when moving down); none at the start.
    ivec2 bound = mix(ivec2(-1), v.size.zw, back);
    bool tail = false;
    float t = t0;
    // The starting level (any level is exact: a march's skips and walks
    // hold for cells of every level): 0 where `first` (the ray's first
    // piece, at its origin, of a ray leaving a surface: the surface lies in
    // its tile's bounds, so that tile is walked at once instead of after a
    // descent from the top); else the lowest level at which one cell holds
    // both ends of the piece (a higher cell has the same segment and looser
    // bounds; a camera ray in the camera view stays in its pixel's tile:
    // level 0).
    int d = top;
    if (first) {
        d = 0;
    } else {
        vec4 ca = co + t0 * cd, cb = co + t1 * cd;
        if (ca.w > 0.0 && cb.w > 0.0) {
            ivec2 x = tile_of(ca, tiles, v.size.zw) ^ tile_of(cb, tiles, v.size.zw);
            d = min(top, findMSB(x.x | x.y) + 1);
        }
    }
    for (int steps = 0; steps < MAX_STEPS; steps++) {
        if (t >= best.t)
            return true;
        COUNT_WORK(y);
        vec4 c = co + t * cd;
        vec2 tc = tile_coord(c, tiles);
        ivec2 size = level_size(v, d);
        // A point on a cell boundary belongs to the cell it moves into.
        ivec2 tile = ivec2(mix(floor(tc), ceil(tc) - 1.0, back));
        tile = mix(max(tile, bound), min(tile, bound), back);
        // A bound past the view's last tile: the ray has left the view on
        // that axis within rounding of t1; the clamped cell takes the rest
        // of the segment.
        tail = tail || any(mix(greaterThanEqual(bound, v.size.zw), lessThan(bound, ivec2(0)), back));
        tile = clamp(tile, ivec2(0), v.size.zw - 1);
        bound = tile;
        ivec2 cell = clamp(tile >> d, ivec2(0), size - 1);
        // The cell's NDC rectangle and the parameter where the ray leaves it.
        ivec2 plo = (cell << d) * S, phi = min(((cell + 1) << d) * S, v.size.xy);
        vec2 sz = vec2(v.size.xy);
        vec2 nlo = -1.0 + 2.0 * vec2(plo) / sz, nhi = -1.0 + 2.0 * vec2(phi) / sz;
        float tx = exit_t(co, cd, 0, t, motion.x, nlo.x, nhi.x);
        float ty = exit_t(co, cd, 1, t, motion.y, nlo.y, nhi.y);
        float texit = tail ? t1 : max(min(min(tx, ty), t1), t);
        float wa = co.w + t * cd.w, wb = co.w + texit * cd.w;
        uvec2 e = dirt_depth(level_base(v, d) + cell.y * size.x + cell.x);
        float zlo = uintBitsToFloat(e.x), zhi = uintBitsToFloat(e.y);
        bool skip = max(wa, wb) < zlo || min(wa, wb) > zhi;
        if (!skip && d > 0) {
            d--;
            continue;
        }
        if (!skip) {
#ifndef DIRT_BUCKET_MASKS
            COUNT_WORK(x); // (with the masks walk_tile counts it, unless it skips the tile)
#endif
            uint gt = uint(v.placement.x + cell.y * v.size.z + cell.x);
#ifdef DIRT_SUB_TILES
            g_seg_lim = segment_cells(co, cd, t, texit, nlo, nhi);
#endif
            if (walk_tile(rs, co, cd, v, view, cell, gt, wa, wb, tmin, best))
                return true;
        }
        // Leave the cell: the next one starts at texit, past the boundary of
        // every axis left there.
        if (texit >= t1)
            return true;
        ivec2 past = mix((cell + 1) << d, (cell << d) - 1, back);
        bvec2 left = bvec2(tx <= texit, ty <= texit);
        bound = mix(bound, past, left);
        t = texit;
        // The march climbs a level only when it leaves the parent cell: the
        // next cell of the same parent is looked at on this level (its
        // bounds are tighter than the parent's; climbing there would look at
        // the parent again and descend to it).
        ivec2 nextc = cell + mix(ivec2(1), ivec2(-1), back) * ivec2(left);
        if (any(notEqual(nextc >> 1, cell >> 1)))
            d = min(d + 1, top);
    }
    return false;
}

// The grid's trace (DIRT_TRACE_LARGE_GRID): the views the ray passes
// through are globals here (main; locals without the grid): camera view
// first, then by entry parameter; enter / leave: the clipped segment in
// view order[j]; g_views of them.
#ifdef DIRT_TRACE_LARGE_GRID
int g_views = 0;
int order[DIRT_GPU_MAX_VIEWS];
float enter[DIRT_GPU_MAX_VIEWS];
float leave[DIRT_GPU_MAX_VIEWS];

// The large primitives tested so far (bit k: params.large slot k). One test
// per ray is enough: a miss stays a miss, a hit outside every view's segment
// stays outside, and one at or beyond tmax stays beyond it (tmax only
// shrinks; see g_never).
uint g_large_tested = 0u;

// Tests large primitive k (slot) with the ray's whole segment; a hit counts
// when it lies in some view's segment, its view the first of those in the
// march order. True when it became the best hit.
bool test_large(ray_setup rs, uint k, float tmin, inout best_hit best)
{
    g_large_tested |= 1u << k;
    uint p = params.large[k >> 2u][k & 3u];
    float tmax = best.prim != DIRT_NO_HIT && p < best.prim
                     ? uintBitsToFloat(floatBitsToUint(best.t) + 1u) : best.t;
    float th, u, w;
    COUNT_WORK(w);
    if (!intersect(rs, dirt_vertex_pos_at(3u * p), dirt_vertex_pos_at(3u * p + 1u),
                   dirt_vertex_pos_at(3u * p + 2u), tmin, tmax, th, u, w))
        return false;
    int hv = -1;
    for (int j = 0; j < g_views && hv < 0; j++) {
        if (enter[j] <= th && th <= leave[j])
            hv = order[j];
    }
    if (hv < 0 || !alpha_accept(p, u, w))
        return false;
    best.t = th;
    best.u = u;
    best.v = w;
    best.prim = p;
    best.view = hv;
    return true;
}

// Marches the ray through view `view`'s large primitives' grid over
// [t0, t1] (a piece of the ray, before its march through the tiles) and
// tests every large primitive not tested yet whose depth range in a cell
// the ray's depth span there meets. Any hit of a large primitive in this
// piece lies in one of the cells the march passes, inside that cell's
// range (the build widened both), so it is found here; hits beyond the
// piece are found by later pieces or lie outside every view. The cells are
// walked the way trace_view walks a level: exits solved in clip space, no
// gaps, a tile bound per axis.
void large_view(ray_setup rs, vec3 org, vec3 dir, int view, float tmin, float t0, float t1,
                inout best_hit best)
{
    uint nl = params.cand.w;
    ivec4 g = params.large_grid[view];
    int L = g.x & 0xFFFF;
    uint met = uint(g.x) >> 16u; // the large primitives this view's cells hold
    dirt_gpu_view v = views[view];
    mat4 vp = view_matrix(v);
    vec4 co = vp * vec4(org, 1.0), cd = vp * vec4(dir, 0.0);
    int S = params.config.y;
    vec2 tiles = vec2(v.size.xy) / float(S);
    vec2 motion = cd.xy * co.w - co.xy * cd.w;
    bvec2 back = lessThan(motion, vec2(0.0));
    ivec2 bound = mix(ivec2(-1), v.size.zw, back);
    bool tail = false;
    float t = t0;
    for (int steps = 0; steps < MAX_STEPS; steps++) {
        if (t > best.t || (met & ~g_large_tested) == 0u ||
            (u_any_hit != 0 && best.prim != DIRT_NO_HIT))
            return;
        COUNT_WORK(y);
        vec4 c = co + t * cd;
        vec2 tc = tile_coord(c, tiles);
        ivec2 tile = ivec2(mix(floor(tc), ceil(tc) - 1.0, back));
        tile = mix(max(tile, bound), min(tile, bound), back);
        tail = tail || any(mix(greaterThanEqual(bound, v.size.zw), lessThan(bound, ivec2(0)), back));
        tile = clamp(tile, ivec2(0), v.size.zw - 1);
        bound = tile;
        ivec2 cell = clamp(tile >> L, ivec2(0), g.zw - 1);
        ivec2 plo = (cell << L) * S, phi = min(((cell + 1) << L) * S, v.size.xy);
        vec2 sz = vec2(v.size.xy);
        vec2 nlo = -1.0 + 2.0 * vec2(plo) / sz, nhi = -1.0 + 2.0 * vec2(phi) / sz;
        float tx = exit_t(co, cd, 0, t, motion.x, nlo.x, nhi.x);
        float ty = exit_t(co, cd, 1, t, motion.y, nlo.y, nhi.y);
        float texit = tail ? t1 : max(min(min(tx, ty), t1), t);
        float wa = co.w + t * cd.w, wb = co.w + texit * cd.w;
        float wlo = min(wa, wb), whi = max(wa, wb);
        uint e = uint(g.y) + uint(cell.y * g.z + cell.x) * nl;
        for (uint k = 0u; k < nl; k++) {
            if ((g_large_tested & (1u << k)) != 0u)
                continue;
            uvec2 r = large_cells[e + k];
            if (whi < uintBitsToFloat(r.x) || wlo > uintBitsToFloat(r.y))
                continue;
            if (test_large(rs, k, tmin, best) && u_any_hit != 0)
                return;
        }
        if (texit >= t1)
            return;
        ivec2 past = mix((cell + 1) << L, (cell << L) - 1, back);
        bvec2 left = bvec2(tx <= texit, ty <= texit);
        bound = mix(bound, past, left);
        t = texit;
    }
    g_cut = true;
}
#endif

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_count))
        return;
    uint owner = dirt_batch_owner(i);
    dirt_gpu_ray ray = rays[i];
    vec3 org = ray.origin_tmin.xyz, dir = ray.dir_tmax.xyz;
    float tmin = ray.origin_tmin.w;
    // Active rays (tmax >= tmin) are counted; the host resets the count.
    if (ray.dir_tmax.w >= tmin)
        atomicAdd(counters.fill.w, 1u);
    best_hit best;
    best.t = ray.dir_tmax.w;
    best.u = 0.0;
    best.v = 0.0;
    best.prim = DIRT_NO_HIT;
    best.view = -1;
    ray_setup rs = setup_ray(org, dir);
#ifdef DIRT_TRACE_ALPHA
    if (u_alpha != 0)
        g_alpha_key = dirt_alpha_ray_key_g(owner);
#endif

    // Views and their entry parameters; camera view (index 0 when present)
    // first, the rest by entry parameter (insertion sort, at most 7).
    int n = params.config.x;
#ifndef DIRT_TRACE_LARGE_GRID
    int order[DIRT_GPU_MAX_VIEWS];
    float enter[DIRT_GPU_MAX_VIEWS];
    float leave[DIRT_GPU_MAX_VIEWS];
#endif
    int m = 0;
    for (int k = 0; k < n; k++) {
        dirt_gpu_view v = views[k];
        mat4 vp = view_matrix(v);
        vec4 co = vp * vec4(org, 1.0), cd = vp * vec4(dir, 0.0);
        float t0 = tmin, t1 = best.t;
        if (!clip_to_view(co, cd, t0, t1))
            continue;
        bool first = v.placement.w < 0;
        int j = m++;
        while (j > 0 && !first && views[order[j - 1]].placement.w >= 0 && enter[j - 1] > t0) {
            order[j] = order[j - 1];
            enter[j] = enter[j - 1];
            leave[j] = leave[j - 1];
            j--;
        }
        order[j] = k;
        enter[j] = t0;
        leave[j] = t1;
    }
#ifdef DIRT_TRACE_LARGE_GRID
    g_views = m;
#elif defined(DIRT_TRACE_LARGE)
    // The large primitives; a hit's view is the first in the order above
    // whose segment holds it.
    uint nl = params.cand.w;
    for (uint k = 0u; k < nl; k++) {
        uint p = params.large[k >> 2u][k & 3u];
        float tmax = best.prim != DIRT_NO_HIT && p < best.prim
                         ? uintBitsToFloat(floatBitsToUint(best.t) + 1u) : best.t;
        float th, u, w;
        COUNT_WORK(w);
        if (!intersect(rs, dirt_vertex_pos_at(3u * p), dirt_vertex_pos_at(3u * p + 1u),
                       dirt_vertex_pos_at(3u * p + 2u), tmin, tmax, th, u, w))
            continue;
        int hv = -1;
        for (int j = 0; j < m && hv < 0; j++) {
            if (enter[j] <= th && th <= leave[j])
                hv = order[j];
        }
        if (hv < 0 || !alpha_accept(p, u, w))
            continue;
        best.t = th;
        best.u = u;
        best.v = w;
        best.prim = p;
        best.view = hv;
        if (u_any_hit != 0)
            break;
    }
#endif
    // The ray is marched piece by piece in order of t, each piece in one
    // view: the first in the order above (camera view, then faces) whose
    // segment holds its start; a piece ends where that view's segment ends
    // or an earlier view's begins. Every intersection in a view's frustum is
    // found by that view's march, so each stretch of the ray needs one view;
    // and in order of t the march ends at the first piece whose hit no
    // later piece can beat (the march of a later piece stops at best.t).
    // A piece keeps its boundary parameters (a march tests whole cells, so
    // a hit on a boundary is found from either side).
    bool aborted = false;
    bool done = false;
    float t = tmin;
    for (int pieces = 0; pieces <= 2 * DIRT_GPU_MAX_VIEWS + 1; pieces++) {
        if (t >= best.t || (u_any_hit != 0 && best.prim != DIRT_NO_HIT)) {
            done = true;
            break;
        }
        int cur = -1;
        for (int j = 0; j < m && cur < 0; j++) {
            if (enter[j] <= t && t < leave[j])
                cur = j;
        }
        float end = cur >= 0 ? leave[cur] : 1e30;
        for (int j = 0; j < m; j++) {
            if ((cur < 0 || j < cur) && enter[j] > t)
                end = min(end, enter[j]);
        }
#ifdef DIRT_TRACE_LARGE_GRID
        // The large primitives this piece meets first (the march then stops
        // at their hit).
        if (cur >= 0)
            large_view(rs, org, dir, order[cur], tmin, t, min(end, best.t), best);
        if (u_any_hit != 0 && best.prim != DIRT_NO_HIT) {
            done = true;
            break;
        }
#endif
        if (cur >= 0 && !trace_view(rs, org, dir, order[cur], tmin, t, min(end, best.t),
                                       pieces == 0 && u_from_surfaces != 0, best))
            aborted = true;
        if (!(end > t) || end >= 1e30) {
            done = true;
            break;
        }
        t = end;
    }
    // Not done: the pieces ran out, or llvmpipe cut the loop (g_cut likewise
    // for the march's loops).
    if (!done || g_cut)
        aborted = true;
    if (aborted)
        atomicAdd(counters.fill.z, 1u);
    uint next = DIRT_LIST_END;
    if (u_link != 0 && best.prim != DIRT_NO_HIT) {
        // The hit's tile in the view it was found in: its hit list is what
        // the raster Fetch walks.
        dirt_gpu_view v = views[best.view];
        vec4 c = view_matrix(v) * vec4(org + best.t * dir, 1.0);
        vec2 tc = (c.xy / c.w * 0.5 + 0.5) * vec2(v.size.xy) / float(params.config.y);
        ivec2 tile = clamp(ivec2(floor(tc)), ivec2(0), v.size.zw - 1);
        next = atomicExchange(hit_heads[uint(v.placement.x + tile.y * v.size.z + tile.x)], i);
    }
    dirt_gpu_hit h;
    h.ids = uvec4(best.prim, uint(best.view), owner, next);
    h.bary_t = vec4(best.u, best.v, best.prim == DIRT_NO_HIT ? -1.0 : best.t, 0.0);
    hits[i] = h;
#ifdef DIRT_TRACE_COUNT
    work[i] = g_work;
#endif
}
