// Exact clipping of a triangle against a tile frustum, in clip space.
// Mirrors dirt_clip_triangle_tile() (src/views/views.c), which is the CPU
// reference: same planes, same Sutherland-Hodgman order, float instead of
// double. Needs common/layout.h.

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

// Clips triangle (c0, c1, c2) (clip space of view v) against tile t, every
// plane moved out by eps (side planes: eps tile widths, near/far: eps/100 in
// NDC). Returns false when nothing is left, else the eye-space depth range
// (clip w) of the clipped polygon.
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
    for (int i = 0; i < n; i++) {
        zmin = min(zmin, a[i].w);
        zmax = max(zmax, a[i].w);
    }
    return n > 0;
}
