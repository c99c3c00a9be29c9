#version 450 core
// MMRT trace: one invocation per ray of a batch (dirt_gpu_ray ->
// dirt_gpu_hit, closest hit). View switching (MMRT paper 3.4): the ray's
// [tmin, tmax] is split into pieces, each marched in one view only -- the
// first in priority order (the camera view when there is one, then the cube
// faces) whose frustum holds it -- in order of t, and the first hit ends the
// ray. With u_all_views, every view is marched over the whole segment
// [tmin, best t] instead, keeping the closest hit (more hits found, and more
// false ones from views that see a surface obliquely). In a view the piece is
// marched in image space:
//  Hi-Z:   a walk over the min/max pyramid of the per-pixel depth bounds:
//          the cell of the current point at level L is left in one step when
//          the ray's depth span across it (widened by the thickness) misses
//          the cell's bounds (then L goes up), else L goes down; at level 0
//          the pixel's lists are tested with the exact depth span of the
//          ray inside that pixel. With u_top_level = 0 this visits every
//          pixel the projected segment crosses (linear conservative).
//  linear: N samples along the projected segment, jittered by a hash of
//          (seed, ray, view); sample i tests the pixel under it with the
//          ray's depth span between the midpoints to its neighbours.
// Pixel test (MMRT paper 3.4): early skip when the span misses the pixel's
// bounds, bucket skipping (only the buckets the span overlaps), list walk in
// the ray's depth direction (head -> next when depth grows along the ray,
// tail -> prev when it shrinks); the first fragment whose depth is within
// u_thickness of the span is the hit. The hit's t is where the ray's depth
// equals the fragment's, clamped to the span.
// Alpha (built with DIRT_TRACE_ALPHA, for scenes with MASK or BLEND
// materials: integrator/alpha.glsl, u_alpha; the opaque scenes' variant is
// the trace without it): a fragment of such a material
// that the alpha test rejects is passed over, and the walk goes on
// with the next fragment. The test reads the texture where the ray meets the
// fragment's primitive's plane (the fragment's own uv, at its pixel centre,
// is up to half a pixel's footprint off: too coarse for masks a few pixels
// wide seen by secondary rays).
#include "common/layout.h"
#include "common/ray_batch.glsl"
#include "common/mmrt_layout.h"
#include "mmrt/abuffer.glsl"
#ifdef DIRT_TRACE_ALPHA
#include "integrator/alpha.glsl"
#endif

layout(local_size_x = DIRT_GROUP_SIZE) in;

#ifdef DIRT_TRACE_ALPHA
#include "common/vertices.glsl"
#endif
layout(std430, binding = DIRT_BIND_VIEWS) readonly buffer Views {
    dirt_gpu_view views[];
};
#define DIRT_DEPTH_READONLY
#include "common/depth.glsl"
layout(std430, binding = DIRT_BIND_MMRT_PARAMS) readonly buffer Params {
    dirt_mmrt_gpu_params params;
};
#define MMRT_HEADS_READONLY
#define MMRT_TAILS_READONLY
#define MMRT_IDS_READONLY
#define MMRT_DATA_READONLY
#include "mmrt/arrays.glsl"
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) buffer Counters {
    dirt_mmrt_gpu_counters counters;
};
layout(std430, binding = DIRT_BIND_RAYS) readonly buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_HITS) writeonly buffer Hits {
    dirt_gpu_hit hits[];
};

layout(location = DIRT_LOC_MMRT_TRACE_COUNT) uniform uint u_count;
layout(location = DIRT_LOC_MMRT_TRACE_MARCH) uniform int u_march;      // 0 Hi-Z, 1 linear
layout(location = DIRT_LOC_MMRT_TRACE_SAMPLES) uniform int u_samples;    // linear: samples per view
layout(location = DIRT_LOC_MMRT_TRACE_TOP_LEVEL) uniform int u_top_level;  // Hi-Z: highest level used
layout(location = DIRT_LOC_MMRT_TRACE_THICKNESS) uniform float u_thickness;
layout(location = DIRT_LOC_MMRT_TRACE_SEED) uniform uint u_seed;
// Ray i of this batch is ray u_first_ray + owner(i) of its wavefront
// (jitter key; common/ray_batch.glsl).
layout(location = DIRT_LOC_MMRT_TRACE_FIRST_RAY) uniform uint u_first_ray;
layout(location = DIRT_LOC_MMRT_TRACE_STATS) uniform int u_stats;      // count pixels / nodes visited
layout(location = DIRT_LOC_MMRT_TRACE_ALL_VIEWS) uniform int u_all_views;  // every view over the whole segment

#define BIG 3.0e38

struct hit_state {
    uint node;    // id/data node, DIRT_LIST_END = none yet
    int view;
    float t;      // best t so far (the segment's end while none)
    float z;
};

uint g_steps = 0u;
// The ray and its alpha key (dirt_alpha_ray_key_g; set when u_alpha != 0).
uint g_alpha_key = 0u;
vec3 g_org = vec3(0.0), g_dir = vec3(0.0);

// Whether the ray sees the fragment of data node n: the alpha test at the
// UV where the ray meets the plane of the fragment's primitive (barycentrics
// of that point, Moller-Trumbore without the bounds test), the fragment's
// uv when the ray is parallel to the plane.
bool alpha_accept(uint n)
{
#ifndef DIRT_TRACE_ALPHA
    return true;
#else
    if (u_alpha == 0)
        return true;
    dirt_mmrt_gpu_data d = mmrt_data(n);
    if (!dirt_material_alpha_tested_g(d.ids.y))
        return true;
    uint p = d.ids.x;
    dirt_gpu_vertex v0 = dirt_vertex_at(3u * p), v1 = dirt_vertex_at(3u * p + 1u),
                    v2 = dirt_vertex_at(3u * p + 2u);
    vec3 e1 = v1.position.xyz - v0.position.xyz, e2 = v2.position.xyz - v0.position.xyz;
    vec3 pv = cross(g_dir, e2);
    float det = dot(e1, pv);
    vec2 uv = d.attr.zw;
    if (det != 0.0) {
        vec3 tv = g_org - v0.position.xyz;
        float b1 = dot(tv, pv) / det, b2 = dot(g_dir, cross(tv, e1)) / det;
        uv = dirt_alpha_uv_g(vec2(v0.position.w, v0.normal.w), vec2(v1.position.w, v1.normal.w),
                             vec2(v2.position.w, v2.normal.w), b1, b2);
    }
    return dirt_alpha_accept_g(d.ids.y, uv, g_alpha_key, p);
#endif
}
uint g_pixels_tested = 0u;
uint g_nodes_visited = 0u;

// Tests the fragments of global pixel g against the ray's depth span over
// [ta, tb] (clip-space ray co + t cd of the current view). On a hit with
// t < h.t, records it and returns true.
bool test_pixel(uint g, float ta, float tb, vec4 co, vec4 cd, int view, inout hit_state h)
{
    g_pixels_tested++;
    uvec2 bb = dirt_depth(g);
    float zmin = uintBitsToFloat(bb.x), zmax = uintBitsToFloat(bb.y);
    float za = co.w + ta * cd.w, zb = co.w + tb * cd.w;
    float lo = min(za, zb) - u_thickness, hi = max(za, zb) + u_thickness;
    if (!(zmin <= zmax) || hi < zmin || lo > zmax)
        return false; // empty pixel or early skip
    float range = zmax - zmin;
    int B = params.config.y;
    // A hair wider than [lo, hi] so a shader-to-shader difference in the
    // rounding of the bucket formula can never skip the right bucket.
    float m = range * 1e-5;
    int b0 = mmrt_bucket(lo - m, zmin, range, B);
    int b1 = mmrt_bucket(hi + m, zmin, range, B);
    uint pixels = uint(params.config.z);
    bool forward = cd.w >= 0.0; // depth grows along the ray
    for (int k = 0; k <= b1 - b0; k++) {
        int b = forward ? b0 + k : b1 - k;
        uint slot = uint(b) * pixels + g;
        uint n = forward ? mmrt_head(slot) : mmrt_tail(slot);
        while (n != DIRT_LIST_END) {
            g_nodes_visited++;
            float z = uintBitsToFloat(mmrt_id(n, uint(DIRT_MMRT_ID_Z)));
            if (forward ? z > hi : z < lo)
                return false; // sorted: nothing further along can match
            if ((forward ? z >= lo : z <= hi) && alpha_accept(n)) {
                float t = 0.5 * (ta + tb);
                if (cd.w != 0.0)
                    t = clamp((z - co.w) / cd.w, min(ta, tb), max(ta, tb));
                if (h.node != DIRT_LIST_END && t >= h.t)
                    return false; // not closer than the hit of an earlier view
                h.node = n;
                h.view = view;
                h.t = t;
                h.z = z;
                return true;
            }
            n = mmrt_id(n, uint(forward ? DIRT_MMRT_ID_NEXT : DIRT_MMRT_ID_PREV));
        }
    }
    return false;
}

vec2 to_pixels(dirt_gpu_view v, vec4 c)
{
    return (c.xy / c.w * 0.5 + 0.5) * vec2(v.size.xy);
}

// t at which the ray's pixel coordinate along `axis` equals `X` (pixels).
float cross_at(dirt_gpu_view v, vec4 co, vec4 cd, int axis, float X)
{
    float b = 2.0 * X / float(v.size[axis]) - 1.0;
    float den = cd[axis] - b * cd.w;
    return den != 0.0 ? (b * co.w - co[axis]) / den : BIG;
}

// Hi-Z march of view `vi` over [t0, t1]. Returns false when it ran out of
// steps.
bool march_hiz(int vi, dirt_gpu_view v, vec4 co, vec4 cd, float t0, float t1, int top,
               inout hit_state h)
{
    // Direction of the projected segment (constant: the projection of a
    // line is a line, and w > 0 on the clipped segment).
    vec2 dir = vec2(sign(cd.x * co.w - co.x * cd.w), sign(cd.y * co.w - co.y * cd.w));
    int L = 0;
    float t = t0;
    int steps = 0, max_steps = 8 * (v.size.x + v.size.y) + 64;
    float min_step = (t1 - t0) * 1e-6;
    while (t < t1) {
        if (++steps > max_steps)
            return false;
        g_steps++;
        vec2 p = to_pixels(v, co + t * cd) + dir * 1e-3;
        int s = 1 << L;
        ivec2 lsize = (v.size.xy + (s - 1)) >> L;
        ivec2 cell = clamp(ivec2(floor(p / float(s))), ivec2(0), lsize - 1);
        float tx = dir.x > 0.0 ? cross_at(v, co, cd, 0, float((cell.x + 1) * s))
                 : dir.x < 0.0 ? cross_at(v, co, cd, 0, float(cell.x * s)) : BIG;
        float ty = dir.y > 0.0 ? cross_at(v, co, cd, 1, float((cell.y + 1) * s))
                 : dir.y < 0.0 ? cross_at(v, co, cd, 1, float(cell.y * s)) : BIG;
        // A boundary the projected line only reaches "behind" the eye (the
        // line tends to its vanishing point first) is never crossed.
        tx = tx > t ? tx : BIG;
        ty = ty > t ? ty : BIG;
        float te = min(t1, min(tx, ty));
        if (!(te > t))
            te = min(t1, t + min_step);
        int lb = v.level_base[L >> 2][L & 3];
        uvec2 bb = dirt_depth(uint(lb + cell.y * lsize.x + cell.x));
        float zmin = uintBitsToFloat(bb.x), zmax = uintBitsToFloat(bb.y);
        float za = co.w + t * cd.w, zb = co.w + te * cd.w;
        float lo = min(za, zb) - u_thickness, hi = max(za, zb) + u_thickness;
        if (!(zmin <= zmax) || hi < zmin || lo > zmax) {
            t = te;
            L = min(L + 1, top);
            continue;
        }
        if (L > 0) {
            L--;
            continue;
        }
        uint g = uint(v.placement.x + cell.y * v.size.x + cell.x);
        if (test_pixel(g, t, te, co, cd, vi, h))
            return true;
        t = te;
        L = min(1, top);
    }
    return true;
}

// Screen parameter s in [0, 1] along the projected segment -> ray t
// (1/w is linear in screen space).
float t_of_s(float s, float t0, float t1, float w0, float w1)
{
    float den = (1.0 - s) * w1 + s * w0;
    float a = den > 0.0 ? s * w0 / den : s;
    return t0 + a * (t1 - t0);
}

void march_linear(int vi, dirt_gpu_view v, vec4 co, vec4 cd, float t0, float t1, uint ray,
                  inout hit_state h)
{
    int N = max(u_samples, 1);
    float w0 = co.w + t0 * cd.w, w1 = co.w + t1 * cd.w;
    uint key = dirt_mmrt_hash(dirt_mmrt_hash(u_seed ^ 0x6d6d7274u) ^ (u_first_ray + ray)) ^
               uint(vi);
    float j = float(dirt_mmrt_hash(key) >> 8) * (1.0 / 16777216.0);
    for (int i = 0; i < N; i++) {
        g_steps++;
        float sc = (float(i) + j) / float(N);
        float sa = i == 0 ? 0.0 : (float(i) + j - 0.5) / float(N);
        float sb = i == N - 1 ? 1.0 : (float(i) + j + 0.5) / float(N);
        float tc = t_of_s(sc, t0, t1, w0, w1);
        ivec2 px = clamp(ivec2(floor(to_pixels(v, co + tc * cd))), ivec2(0), v.size.xy - 1);
        uint g = uint(v.placement.x + px.y * v.size.x + px.x);
        if (test_pixel(g, t_of_s(sa, t0, t1, w0, w1), t_of_s(sb, t0, t1, w0, w1), co, cd, vi,
                       h))
            return;
    }
}

// Clips [t0, t1] of the ray co + t cd to the view frustum (Liang-Barsky on
// the six clip planes). False when nothing is left.
bool clip_segment(vec4 co, vec4 cd, inout float t0, inout float t1)
{
    for (int k = 0; k < 6; k++) {
        float sgn = (k & 1) == 0 ? 1.0 : -1.0;
        int axis = k >> 1;
        float a = co.w + sgn * co[axis];
        float b = cd.w + sgn * cd[axis];
        if (b == 0.0) {
            if (a < 0.0)
                return false;
        } else if (b > 0.0) {
            t0 = max(t0, -a / b);
        } else {
            t1 = min(t1, -a / b);
        }
    }
    return t0 < t1;
}

// Marches view vi over [t0, t1] of the ray (clipped to the view frustum
// first). False when a Hi-Z walk ran out of steps.
bool march_view(int vi, vec3 org, vec3 dir, float t0, float t1, uint ray, inout hit_state h)
{
    dirt_gpu_view v = views[vi];
    mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
    vec4 co = vp * vec4(org, 1.0), cd = vp * vec4(dir, 0.0);
    if (!clip_segment(co, cd, t0, t1))
        return true;
    if (u_march == 0 || u_samples <= 0) {
        int top = u_march == 0 ? min(u_top_level, v.placement.z - 1) : 0;
        return march_hiz(vi, v, co, cd, t0, t1, max(top, 0), h);
    }
    march_linear(vi, v, co, cd, t0, t1, ray, h);
    return true;
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_count))
        return;
    uint owner = dirt_batch_owner(i); // keys the jitter and the alpha test
    dirt_gpu_ray r = rays[i];
    vec3 org = r.origin_tmin.xyz, dir = r.dir_tmax.xyz;
    float tmin = max(r.origin_tmin.w, 0.0);
    float tmax = min(r.dir_tmax.w, BIG);
    g_org = org;
    g_dir = dir;
#ifdef DIRT_TRACE_ALPHA
    if (u_alpha != 0)
        g_alpha_key = dirt_alpha_ray_key_g(owner);
#endif
    hit_state h;
    h.node = DIRT_LIST_END;
    h.view = -1;
    h.t = tmax;
    h.z = 0.0;
    bool aborted = false;
    int nviews = params.config.x;
    if (u_all_views != 0) {
        // Every view over the whole segment left, closest hit kept.
        for (int vi = 0; vi < nviews; vi++) {
            float t0 = tmin, t1 = h.t;
            if (!march_view(vi, org, dir, t0, t1, owner, h))
                aborted = true;
        }
    } else {
        // View switching: each part of the ray is marched in one view only,
        // the first in priority order (camera, then faces) whose frustum
        // holds it, in order of t; the first hit ends the ray.
        float va[DIRT_GPU_MAX_VIEWS], vb[DIRT_GPU_MAX_VIEWS];
        for (int vi = 0; vi < nviews; vi++) {
            dirt_gpu_view v = views[vi];
            mat4 vp = mat4(v.view_proj[0], v.view_proj[1], v.view_proj[2], v.view_proj[3]);
            float a = tmin, b = tmax;
            if (!clip_segment(vp * vec4(org, 1.0), vp * vec4(dir, 0.0), a, b))
                a = b = BIG;
            va[vi] = a;
            vb[vi] = b;
        }
        float t = tmin;
        for (int pieces = 0; t < tmax && pieces <= 2 * nviews + 1; pieces++) {
            int cur = -1;
            for (int vi = 0; vi < nviews && cur < 0; vi++) {
                if (va[vi] <= t && t < vb[vi])
                    cur = vi;
            }
            // The piece ends where `cur` ends or a view before it begins;
            // outside every view, skip to the next view's start.
            float end = cur >= 0 ? min(vb[cur], tmax) : BIG;
            for (int vi = 0; vi < nviews; vi++) {
                if ((cur < 0 || vi < cur) && va[vi] > t)
                    end = min(end, va[vi]);
            }
            if (cur >= 0) {
                float t0 = t, t1 = end;
                if (!march_view(cur, org, dir, t0, t1, owner, h))
                    aborted = true;
                if (h.node != DIRT_LIST_END)
                    break;
            }
            if (!(end > t) || end >= BIG)
                break;
            t = end;
        }
    }
    dirt_gpu_hit o;
    if (h.node != DIRT_LIST_END) {
        dirt_mmrt_gpu_data d = mmrt_data(h.node);
        o.ids = uvec4(d.ids.x, uint(h.view), owner, h.node);
        o.bary_t = vec4(d.attr.xy, h.t, h.z);
    } else {
        o.ids = uvec4(DIRT_NO_HIT, DIRT_NO_HIT, owner, DIRT_LIST_END);
        o.bary_t = vec4(0.0, 0.0, -1.0, 0.0);
    }
    hits[i] = o;
    if (u_stats != 0) {
        if (h.node != DIRT_LIST_END)
            atomicAdd(counters.trace.x, 1u);
        atomicAdd(counters.trace.y, g_steps);
        atomicAdd(counters.trace.z, g_nodes_visited);
        atomicAdd(counters.trace2.x, g_pixels_tested);
    }
    if (aborted)
        atomicAdd(counters.trace.w, 1u);
}
