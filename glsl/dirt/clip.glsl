// The exact eye-depth range of a triangle inside a tile frustum, in clip
// space, for the DIRT build. The CPU reference is dirt_clip_triangle_tile()
// (src/views/views.c): a Sutherland-Hodgman clip against the tile frustum's
// six planes, every plane moved out by eps (side planes: eps tile widths,
// near/far: eps/100 in NDC depth); the range is the min/max clip w of the
// clipped polygon. Needs common/layout.h.
//
// The GPU computes the same range without building the polygon (which needs
// dynamically indexed arrays: slow everywhere, and on a SIMD CPU rasterizer
// a gather and a scatter per vertex and plane). Clip w is linear on the
// triangle, so its extremes over the convex clipped polygon are at the
// polygon's vertices, and every vertex is one of
//   (a) a triangle vertex inside the frustum (triangle inside the tile:
//       range = the vertices' depths, bit for bit what the clip gives),
//   (b) a triangle edge crossing a side plane inside the other side planes
//       (a real crossing); (a) and (b) are the ends of each edge's part
//       inside the tile (Liang-Barsky, with the clip's tests and formulas),
//   (c) a corner ray of the tile frustum piercing the triangle (tile inside
//       the triangle: range = the triangle's plane on the four corner rays),
//       found where the segment a side plane cuts from the triangle crosses
//       the perpendicular side planes (the clip's own construction, so it
//       stays on the triangle however oblique the triangle is).
// The near and far planes do not depend on the tile: the geometry stage
// clips the triangle against them once (dirt_clip_near_far, the same
// Sutherland-Hodgman steps in registers) and the fragment stage takes the
// resulting polygon (at most 5 vertices) as a fan of triangles, each fully in
// front of the eye (w > 0), against the four side planes
// (dirt_range_tile). Each candidate point is computed and tested without
// branches, with the clip's own formulas and tests (>= 0 against the
// eps-moved planes), so it agrees with the clip up to float rounding.
//
// With DIRT_CLIP_SH the build runs the plain Sutherland-Hodgman clip of
// every candidate instead (dirt_clip_tile): the reference the fast path is
// compared against in tests and benchmarks.

#define DIRT_CLIP_MAX 12

// Tile (tx, ty)'s NDC rectangle (x0, x1, y0, y1) of a view.
vec4 dirt_tile_ndc(dirt_gpu_view v, int S, ivec2 t)
{
    ivec2 lo = t * S;
    ivec2 hi = min(lo + S, v.size.xy);
    vec2 sz = vec2(v.size.xy);
    return vec4(-1.0 + 2.0 * float(lo.x) / sz.x, -1.0 + 2.0 * float(hi.x) / sz.x,
                -1.0 + 2.0 * float(lo.y) / sz.y, -1.0 + 2.0 * float(hi.y) / sz.y);
}

// Tile t's rectangle with every side moved out by eps tile widths: the side
// planes of its frustum are x = X0 w, x = X1 w, y = Y0 w, y = Y1 w for
// (X0, X1, Y0, Y1).
vec4 dirt_tile_rect(dirt_gpu_view v, int S, ivec2 t, float eps)
{
    vec4 r = dirt_tile_ndc(v, S, t);
    float ex = eps * 2.0 * float(S) / float(v.size.x);
    float ey = eps * 2.0 * float(S) / float(v.size.y);
    return vec4(r.x - ex, r.y + ex, r.z - ey, r.w + ey);
}

#ifdef DIRT_SUB_TILES
// Sub-tile rectangles (common/layout.h, DIRT_SUBTILE_*): the clip functions
// also min/max the NDC (x / w, y / w) of the clipped polygon's vertices
// into g_box = (xmin, xmax, ymin, ymax); dirt_subtile_rect turns it into
// the candidate's rectangle. The vertices are those the range takes: the
// ends of each edge's part inside the tile ((a) and (b)) and the tile's
// corners where a corner ray pierces the triangle ((c)); every point of the
// clipped polygon is a convex combination of them, so the box holds the
// polygon's projection (up to float rounding, which DIRT_SUBTILE_MARGIN
// covers many times over).
vec4 g_box = vec4(0.0);

// The rectangle byte (common/layout.h) of g_box in tile t of view v: the
// cells of the grid over the tile's NDC rectangle (not moved out) that the
// box widened by DIRT_SUBTILE_MARGIN cells meets, clamped to the tile (the
// eps band beyond the tile falls in its border cells). The whole tile (0)
// when the box is empty or not a number (never so for a polygon in front of
// the eye; kept conservative anyway).
uint dirt_subtile_rect(dirt_gpu_view v, int S, ivec2 t)
{
    if (!all(greaterThanEqual(g_box.yw, g_box.xz)))
        return 0u;
    vec4 r = dirt_tile_ndc(v, S, t);
    vec2 org = r.xz, cell = vec2(r.y - r.x, r.w - r.z) / float(DIRT_SUBTILE_GRID);
    float m = float(DIRT_SUBTILE_MARGIN), top = float(DIRT_SUBTILE_GRID - 1);
    vec2 lo = clamp(floor((g_box.xz - org) / cell - m), vec2(0.0), vec2(top));
    vec2 hi = clamp(floor((g_box.yw - org) / cell + m), vec2(0.0), vec2(top));
    uvec2 a = uvec2(lo), b = uvec2(top - hi);
    return a.x | (b.x << 2) | (a.y << 4) | (b.y << 6);
}
#endif

// Clips triangle (c0, c1, c2) (clip space of view v) against tile t, every
// plane moved out by eps (side planes: eps tile widths, near/far: eps/100 in
// NDC). Returns false when nothing is left, else the eye-space depth range
// (clip w) of the clipped polygon. The reference variant (DIRT_CLIP_SH).
bool dirt_clip_tile(dirt_gpu_view v, int S, ivec2 t, vec4 c0, vec4 c1, vec4 c2, float eps,
                    out float zmin, out float zmax)
{
    vec4 r = dirt_tile_ndc(v, S, t);
    float ex = eps * 2.0 * float(S) / float(v.size.x);
    float ey = eps * 2.0 * float(S) / float(v.size.y);
    float ez = eps * 1e-2;
    vec4 planes[6] = vec4[6](
        vec4(1, 0, 0, -(r.x - ex)), vec4(-1, 0, 0, r.y + ex),
        vec4(0, 1, 0, -(r.z - ey)), vec4(0, -1, 0, r.w + ey),
        vec4(0, 0, 1, 1.0 + ez), vec4(0, 0, -1, 1.0 + ez));
    vec4 a[DIRT_CLIP_MAX];
    vec4 b[DIRT_CLIP_MAX];
    a[0] = c0;
    a[1] = c1;
    a[2] = c2;
    int n = 3;
    for (int k = 0; k < 6 && n > 0; k++) {
        vec4 pl = planes[k];
        int m = 0;
        for (int i = 0; i < n; i++) {
            vec4 p = a[i];
            vec4 q = a[(i + 1) % n];
            float dp = dot(pl, p);
            float dq = dot(pl, q);
            if (dp >= 0.0)
                b[m++] = p;
            if ((dp >= 0.0) != (dq >= 0.0))
                b[m++] = p + (dp / (dp - dq)) * (q - p);
        }
        n = m;
        for (int i = 0; i < n; i++)
            a[i] = b[i];
    }
    zmin = 1.0 / 0.0;
    zmax = 0.0;
#ifdef DIRT_SUB_TILES
    g_box = vec4(1.0 / 0.0, -1.0 / 0.0, 1.0 / 0.0, -1.0 / 0.0);
#endif
    for (int i = 0; i < n; i++) {
        zmin = min(zmin, a[i].w);
        zmax = max(zmax, a[i].w);
#ifdef DIRT_SUB_TILES
        vec2 q = a[i].xy / a[i].w;
        g_box = vec4(min(g_box.x, q.x), max(g_box.y, q.x), min(g_box.z, q.y), max(g_box.w, q.y));
#endif
    }
    return n > 0;
}

// ---- near and far planes (geometry stage, once per triangle and view) ----

// One Sutherland-Hodgman step of polygon (p, n), n in {0, 3, 4}, against the
// plane dot(pl, c) >= 0, written with constant indices only (the polygon
// stays in registers): at most 5 vertices come out.
void dirt_clip_step(inout vec4 p[5], inout int n, vec4 pl)
{
    vec4 o[5] = p;
    int m = 0;
    for (int i = 0; i < 4; i++) {
        vec4 a = p[i];
        vec4 b = i + 1 < n ? p[i + 1] : p[0];
        float da = dot(pl, a);
        float db = dot(pl, b);
        bool live = i < n;
        bool keep = live && da >= 0.0;
        bool cut = live && (da >= 0.0) != (db >= 0.0);
        vec4 x = a + (da / (da - db)) * (b - a);
        for (int s = 0; s < 5; s++)
            o[s] = keep && m == s ? a : o[s];
        m += keep ? 1 : 0;
        for (int s = 0; s < 5; s++)
            o[s] = cut && m == s ? x : o[s];
        m += cut ? 1 : 0;
    }
    p = o;
    n = m;
}

// The part of triangle c (clip space) between the near and far planes (moved
// out by eps/100 in NDC depth): polygon p[0 .. n-1], n in {0, 3, 4, 5}, in
// the triangle's winding. The triangle itself when it is inside both.
void dirt_clip_near_far(vec4 c[3], float eps, out vec4 p[5], out int n)
{
    p = vec4[5](c[0], c[1], c[2], c[2], c[2]);
    n = 3;
    float k = 1.0 + eps * 1e-2;
    vec3 z = vec3(c[0].z, c[1].z, c[2].z), w = vec3(c[0].w, c[1].w, c[2].w);
    if (any(lessThan(z + k * w, vec3(0.0))) || any(lessThan(k * w - z, vec3(0.0)))) {
        dirt_clip_step(p, n, vec4(0.0, 0.0, 1.0, k));
        dirt_clip_step(p, n, vec4(0.0, 0.0, -1.0, k));
    }
}

// ---- side planes (fragment stage, once per candidate tile) ----

float dirt_min3(vec3 a)
{
    return min(a.x, min(a.y, a.z));
}

float dirt_max3(vec3 a)
{
    return max(a.x, max(a.y, a.z));
}

// One side plane, with values d at the three vertices (>= 0 inside), on the
// edges (i, i+1) at once (the other end's values are d.yzx): narrows each
// edge's inside part [t0, t1] (Liang-Barsky) with the clip's own test and
// crossing parameter t = d / (d - d.yzx), which it returns. An edge with
// both ends outside gets t0 = 2: empty.
vec3 dirt_edges_plane(vec3 d, inout vec3 t0, inout vec3 t1)
{
    bvec3 ia = greaterThanEqual(d, vec3(0.0)), ib = greaterThanEqual(d.yzx, vec3(0.0));
    vec3 t = d / (d - d.yzx);
    t0 = max(t0, mix(mix(vec3(2.0), t, ib), vec3(0.0), ia)); // entering: t
    t1 = min(t1, mix(mix(vec3(1.0), t, ia), vec3(1.0), ib)); // leaving: t
    return t;
}

// (c) for one x side plane (values d, crossing parameters t on the edges):
// it meets the triangle in the segment between its two crossing points A
// and B (none or two edges cross: edges 0 and 1, 1 and 2, or 0 and 2).
// Where a y side plane (values p or q) changes sign along that segment is a
// corner ray of the tile; it is cut there exactly as the clip cuts that edge
// of its polygon, so the point stays on the triangle however oblique the
// triangle is. The other two side planes hold there: w > 0. Returns which
// corner rays pierce it: (the p plane's, the q plane's).
bvec2 dirt_range_corners(vec3 d, vec3 t, vec3 p, vec3 q, vec3 w, inout float lo,
                         inout float hi)
{
    bvec3 cut = notEqual(greaterThanEqual(d, vec3(0.0)), greaterThanEqual(d.yzx, vec3(0.0)));
    vec3 pt = p + t * (p.yzx - p), qt = q + t * (q.yzx - q), wt = w + t * (w.yzx - w);
    vec3 A = cut.x ? vec3(pt.x, qt.x, wt.x) : vec3(pt.y, qt.y, wt.y);
    vec3 B = cut.z ? vec3(pt.z, qt.z, wt.z) : vec3(pt.y, qt.y, wt.y);
    bvec2 sign_change = notEqual(greaterThanEqual(A.xy, vec2(0.0)),
                                 greaterThanEqual(B.xy, vec2(0.0)));
    bool seg = any(cut);
    vec2 u = A.xy / (A.xy - B.xy);
    vec2 wc = A.z + u * (B.z - A.z);
    bool kp = seg && sign_change.x, kq = seg && sign_change.y;
    lo = min(lo, min(kp ? wc.x : 1.0 / 0.0, kq ? wc.y : 1.0 / 0.0));
    hi = max(hi, max(kp ? wc.x : 0.0, kq ? wc.y : 0.0));
    return bvec2(kp, kq);
}

// Widens [lo, hi] by the depth range of triangle (q0, q1, q2) (clip space,
// in front of the eye) inside the side planes of rectangle R (dirt_tile_rect).
// Leaves it alone when the triangle misses the tile.
void dirt_range_tri(vec4 q0, vec4 q1, vec4 q2, vec4 R, inout float lo, inout float hi)
{
    vec3 x = vec3(q0.x, q1.x, q2.x), y = vec3(q0.y, q1.y, q2.y), w = vec3(q0.w, q1.w, q2.w);
    // Plane values, >= 0 inside: x >= X0 w, x <= X1 w, y >= Y0 w, y <= Y1 w.
    vec3 a0 = x - R.x * w, a1 = R.y * w - x, b0 = y - R.z * w, b1 = R.w * w - y;
    // (a) and (b): the ends of each edge's part inside the four planes. One
    // parameter per vertex and plane decides both neighbours of a point
    // where an edge meets two planes, so such a vertex is never lost.
    vec3 t0 = vec3(0.0), t1 = vec3(1.0);
    vec3 ta0 = dirt_edges_plane(a0, t0, t1);
    vec3 ta1 = dirt_edges_plane(a1, t0, t1);
    dirt_edges_plane(b0, t0, t1);
    dirt_edges_plane(b1, t0, t1);
    vec3 dw = w.yzx - w;
    vec3 w0 = w + t0 * dw;                                    // t0 = 0: w, bit for bit
    vec3 w1 = mix(w + t1 * dw, w.yzx, equal(t1, vec3(1.0)));  // t1 = 1: the next vertex
    bvec3 keep = lessThanEqual(t0, t1);
    lo = min(lo, dirt_min3(mix(vec3(1.0 / 0.0), min(w0, w1), keep)));
    hi = max(hi, dirt_max3(mix(vec3(0.0), max(w0, w1), keep)));
    // (c) the corner rays
    bvec2 k0 = dirt_range_corners(a0, ta0, b0, b1, w, lo, hi);
    bvec2 k1 = dirt_range_corners(a1, ta1, b0, b1, w, lo, hi);
#ifdef DIRT_SUB_TILES
    // The same points' NDC: the edge parts' ends, and the corners (exactly
    // R's: x = X0 w or X1 w, y = Y0 w or Y1 w there).
    vec3 dx = x.yzx - x, dy = y.yzx - y;
    vec3 x0 = x + t0 * dx, y0 = y + t0 * dy;
    vec3 x1 = mix(x + t1 * dx, x.yzx, equal(t1, vec3(1.0)));
    vec3 y1 = mix(y + t1 * dy, y.yzx, equal(t1, vec3(1.0)));
    vec3 nx0 = x0 / w0, nx1 = x1 / w1, ny0 = y0 / w0, ny1 = y1 / w1;
    const vec3 inf = vec3(1.0 / 0.0);
    vec4 b = vec4(dirt_min3(mix(inf, min(nx0, nx1), keep)), dirt_max3(mix(-inf, max(nx0, nx1), keep)),
                  dirt_min3(mix(inf, min(ny0, ny1), keep)), dirt_max3(mix(-inf, max(ny0, ny1), keep)));
    bool kx0 = any(k0), kx1 = any(k1), ky0 = k0.x || k1.x, ky1 = k0.y || k1.y;
    b.x = min(b.x, kx0 ? R.x : kx1 ? R.y : b.x);
    b.y = max(b.y, kx1 ? R.y : kx0 ? R.x : b.y);
    b.z = min(b.z, ky0 ? R.z : ky1 ? R.w : b.z);
    b.w = max(b.w, ky1 ? R.w : ky0 ? R.z : b.w);
    g_box = vec4(min(g_box.x, b.x), max(g_box.y, b.y), min(g_box.z, b.z), max(g_box.w, b.w));
#endif
}

// Depth range of the near/far-clipped polygon (p0 .. p4, n vertices, from
// dirt_clip_near_far) inside tile t of view v, planes moved out by eps.
// False when the polygon misses the tile frustum.
bool dirt_range_tile(dirt_gpu_view v, int S, ivec2 t, vec4 p0, vec4 p1, vec4 p2, vec4 p3,
                     vec4 p4, int n, float eps, out float zmin, out float zmax)
{
    vec4 R = dirt_tile_rect(v, S, t, eps);
    zmin = 1.0 / 0.0;
    zmax = 0.0;
#ifdef DIRT_SUB_TILES
    g_box = vec4(1.0 / 0.0, -1.0 / 0.0, 1.0 / 0.0, -1.0 / 0.0);
#endif
    // The fan (p0, pk, pk+1): one triangle unless the near/far clip cut it.
    for (int k = 1; k + 1 < n; k++) {
        vec4 qa = k == 1 ? p1 : k == 2 ? p2 : p3;
        vec4 qb = k == 1 ? p2 : k == 2 ? p3 : p4;
        dirt_range_tri(p0, qa, qb, R, zmin, zmax);
    }
    return zmin <= zmax;
}
