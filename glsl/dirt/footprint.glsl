// The conservative tile footprint of a triangle in one view, shared by the
// raster build (dirt/build.geom: the quad it emits, the bound it counts) and
// the compute build (dirt/tiles.comp, dirt/range.comp), so both examine the
// same candidate tiles. Needs common/layout.h.
//
// dirt_footprint: c = the triangle's clip-space vertices in view v. False
// when the triangle is rejected (all three vertices beyond one plane of the
// view frustum, moved out a little so a touching triangle is kept, or all
// nearer than near / 2). Else [lo, hi] (tile coordinates of the view, x and
// y) is the bounding box of its projection after clipping against
// w >= near / 2 (nothing nearer lies in a tile frustum), widened by 0.51
// tiles and clamped to the view, non-empty: every tile the triangle's
// projection touches has its centre strictly inside. crosses_near: a
// vertex is nearer than near / 2.
bool dirt_footprint(dirt_gpu_view v, int S, vec4 c[3], out vec2 lo, out vec2 hi,
                    out bool crosses_near)
{
    lo = vec2(0.0);
    hi = vec2(0.0);
    crosses_near = false;
    float m = 1.0 + 1e-3;
    if ((c[0].x > m * c[0].w && c[1].x > m * c[1].w && c[2].x > m * c[2].w) ||
        (c[0].x < -m * c[0].w && c[1].x < -m * c[1].w && c[2].x < -m * c[2].w) ||
        (c[0].y > m * c[0].w && c[1].y > m * c[1].w && c[2].y > m * c[2].w) ||
        (c[0].y < -m * c[0].w && c[1].y < -m * c[1].w && c[2].y < -m * c[2].w) ||
        (c[0].z > m * c[0].w && c[1].z > m * c[1].w && c[2].z > m * c[2].w) ||
        (c[0].w < 0.5 * v.eye_near.w && c[1].w < 0.5 * v.eye_near.w &&
         c[2].w < 0.5 * v.eye_near.w))
        return false;
    float wmin = 0.5 * v.eye_near.w;
    vec2 blo = vec2(1e30), bhi = vec2(-1e30);
    vec2 tiles = vec2(v.size.xy) / float(S);
    for (int i = 0; i < 3; i++) {
        vec4 p = c[i], q = c[(i + 1) % 3];
        if (p.w >= wmin) {
            vec2 t = (p.xy / p.w * 0.5 + 0.5) * tiles;
            blo = min(blo, t);
            bhi = max(bhi, t);
        } else {
            crosses_near = true;
        }
        if ((p.w >= wmin) != (q.w >= wmin)) {
            vec4 s = p + ((wmin - p.w) / (q.w - p.w)) * (q - p);
            vec2 t = (s.xy / wmin * 0.5 + 0.5) * tiles;
            blo = min(blo, t);
            bhi = max(bhi, t);
        }
    }
    vec2 tmax = vec2(v.size.zw);
    lo = clamp(blo - 0.51, vec2(0.0), tmax);
    hi = clamp(bhi + 0.51, vec2(0.0), tmax);
    return lo.x < hi.x && lo.y < hi.y;
}

// The candidate tiles of footprint [lo, hi]: those whose centres lie in it
// widened by 0.01 (vertex snapping), so at least the fragments a quad over
// [lo, hi] makes (and those of a hardware conservative raster, whose tiles
// meet the triangle, so their centres lie within 0.5 of it). ivec4(x0, y0,
// nx, ny): nx x ny tiles from (x0, y0), inside the view (lo >= 0, hi <=
// the view's tiles).
ivec4 dirt_footprint_tiles(vec2 lo, vec2 hi)
{
    vec2 a = ceil(lo - 0.01 - 0.5), b = floor(hi + 0.01 - 0.5);
    vec2 n = max(b - a + 1.0, vec2(0.0));
    return ivec4(ivec2(a), ivec2(n));
}

// Chunks (DIRT_BUILD_CHUNK tiles) per work record of the compute build for a
// footprint of n tiles: all of them up to DIRT_BUILD_LANE_TILES (one record,
// each lane takes up to that many tiles, so the vertices and the near/far
// clip are computed once per lane, not per tile), more when records of
// DIRT_BUILD_LANE_TILES chunks would be more than DIRT_BUILD_MAX_RECORDS
// (which bounds the loops of both passes; common/constants.h).
uint dirt_build_chunks(uint n)
{
    uint chunks = (n + uint(DIRT_BUILD_CHUNK) - 1u) / uint(DIRT_BUILD_CHUNK);
    uint spread = (chunks + uint(DIRT_BUILD_MAX_RECORDS) - 1u) / uint(DIRT_BUILD_MAX_RECORDS);
    return max(min(uint(DIRT_BUILD_LANE_TILES), chunks), spread);
}
