// GPU path tracer: buffers and helpers shared by its passes. Mirrors the
// CPU reference (src/ref/render.c): same vertex construction, same random
// dimensions, same next-event estimation and MIS, so both follow the same
// paths for a given (seed, pixel, sample). Needs common/layout.h and
// integrator/model.glsl (with DIRT_MODEL_BUFFERS).

#include "common/geometry.glsl"

#include "common/vertices.glsl"
layout(std430, binding = DIRT_BIND_PATHS) buffer Paths {
    dirt_gpu_path paths[];
};

layout(location = DIRT_LOC_PT_PIXELS) uniform uint u_pixels;
layout(location = DIRT_LOC_PT_WIDTH) uniform int u_width;
layout(location = DIRT_LOC_PT_HEIGHT) uniform int u_height;
layout(location = DIRT_LOC_PT_SEED) uniform uint u_seed;
layout(location = DIRT_LOC_PT_SAMPLE) uniform uint u_sample;
layout(location = DIRT_LOC_PT_BOUNCE) uniform uint u_bounce;    // k: the path event being shaded
layout(location = DIRT_LOC_PT_BOUNCES) uniform uint u_bounces;   // K: scattering events allowed
layout(location = DIRT_LOC_PT_SLOT) uniform uint u_slot;      // ring slot of G_k
layout(location = DIRT_LOC_PT_AO_DISTANCE) uniform float u_ao_distance;
// The image is worked through in chunks (wavefronts) of u_pixels records:
// record p of the per-pixel buffers is image pixel u_pixel_offset + p, which
// keys the random numbers and gives the pixel's coordinates.
layout(location = DIRT_LOC_PT_PIXEL_OFFSET) uniform uint u_pixel_offset;
// The tracer's surface_offset (views/tracer.h): rays leaving a surface start
// this much farther off it along ng; shadow rays stop this far off the
// emitter's plane. 0 for DIRT (the reference's rays exactly).
layout(location = DIRT_LOC_PT_SURFACE_OFFSET) uniform float u_surface_offset;

#define SHADOW_SHORTEN 1e-4

float ray_epsilon(vec3 p)
{
    float m = max(abs(p.x), max(abs(p.y), abs(p.z)));
    return 1e-4 * max(1.0, m);
}

vec3 tri_vertex(uint prim, uint k)
{
    return dirt_vertex_pos_at(3u * prim + k);
}

vec3 tri_point(uint prim, float b1, float b2)
{
    vec3 r = tri_vertex(prim, 0u) * (1.0 - b1 - b2);
    r = r + tri_vertex(prim, 1u) * b1;
    return r + tri_vertex(prim, 2u) * b2;
}

vec2 tri_uv(uint prim, float b1, float b2)
{
    float b0 = 1.0 - b1 - b2;
    dirt_gpu_vertex a = dirt_vertex_at(3u * prim), b = dirt_vertex_at(3u * prim + 1u),
                    c = dirt_vertex_at(3u * prim + 2u);
    vec2 t0 = vec2(a.position.w, a.normal.w);
    vec2 t1 = vec2(b.position.w, b.normal.w);
    vec2 t2 = vec2(c.position.w, c.normal.w);
    return b0 * t0 + b1 * t1 + b2 * t2;
}

vec3 tri_normal_ng(uint prim)
{
    vec3 p0 = tri_vertex(prim, 0u);
    return dirt_normalize_g(cross(tri_vertex(prim, 1u) - p0, tri_vertex(prim, 2u) - p0));
}

// Solid-angle pdf with which next-event estimation picks direction `dir`
// towards a point of emissive triangle `prim` at distance `dist`.
float light_pdf(uint prim, vec3 dir, float dist)
{
    if (dirt_model_lights.counts.x == 0u)
        return 0.0;
    float cos_l = abs(dot(tri_normal_ng(prim), dir));
    if (!(cos_l > 0.0))
        return 0.0;
    return dist * dist / (cos_l * dirt_model_lights.area.x * float(dirt_nee_sources_g()));
}

// Solid-angle pdf with which next-event estimation picks direction `dir` of
// the environment (= env_light_pdf of the reference).
float env_light_pdf(vec3 dir)
{
    return dirt_env_pdf_g(dir) / float(dirt_nee_sources_g());
}

// A path vertex (= make_vertex of the reference).
struct pt_vertex {
    uint prim;
    vec3 p, ng, t, b, n, wo;
    bool front;
    dirt_surface_g surf;
    vec3 le, origin;
    vec3 origin_below; // origin of rays transmitted through the surface (-ng side)
};

vec3 to_local(vec3 w, vec3 t, vec3 b, vec3 n)
{
    return vec3(dot(w, t), dot(w, b), dot(w, n));
}

vec3 from_local(vec3 w, vec3 t, vec3 b, vec3 n)
{
    return w.x * t + w.y * b + w.z * n;
}

// Builds the vertex from a fetched shading point; `dir` is the unit
// direction of the arriving ray (normalize of the traced ray's), `bary` the
// barycentrics of vertices 1 and 2 of the hit (its dirt_gpu_hit's
// bary_t.xy, those of the shading point), which interpolate the texture uv
// and the tangents of a normal-mapped material. The geometric normal comes
// from the primitive's vertices (dirt_gpu_gpoint: what a record holds).
pt_vertex make_vertex(dirt_gpu_gpoint g, vec3 dir, vec2 bary)
{
    pt_vertex v;
    v.prim = floatBitsToUint(g.pos_prim.w);
    v.p = g.pos_prim.xyz;
    vec3 ng = dirt_geometric_normal(tri_vertex(v.prim, 0u), tri_vertex(v.prim, 1u),
                                    tri_vertex(v.prim, 2u));
    v.front = dot(ng, dir) < 0.0;
    if (!v.front)
        ng = -ng;
    v.ng = ng;
    vec3 ns = ng;
    vec3 n = g.n_mat.xyz;
    uint mat = floatBitsToUint(g.n_mat.w);
    vec2 uv = tri_uv(v.prim, bary.x, bary.y);
    vec3 n_ts;
    uint t0 = 3u * v.prim;
    if (t0 + 2u < dirt_model_tangent_count_g() && dirt_material_normal_ts_g(mat, uv, n_ts)) {
        // Normal map (= make_vertex of the reference): the front side's
        // normal, flipped below like the interpolated one.
        float b0 = 1.0 - bary.x - bary.y;
        vec4 a = dirt_model_tangent_g(t0), b = dirt_model_tangent_g(t0 + 1u),
             c = dirt_model_tangent_g(t0 + 2u);
        vec3 t = a.xyz * b0 + b.xyz * bary.x + c.xyz * bary.y;
        float w = b0 * a.w + bary.x * b.w + bary.y * c.w;
        n = dirt_normal_map_apply_g(n, t, w, n_ts);
    }
    if (!v.front)
        n = -n;
    if (dirt_is_finite_g(n) && dot(n, n) > 0.0 && dot(n, ng) > 0.0)
        ns = n;
    vec3 wo_world = -dir;
    dirt_onb_g(ns, v.t, v.b);
    v.n = ns;
    v.wo = to_local(wo_world, v.t, v.b, v.n);
    if (v.wo.z <= 0.0) {
        v.n = ng;
        dirt_onb_g(ng, v.t, v.b);
        v.wo = to_local(wo_world, v.t, v.b, v.n);
    }
    v.surf = dirt_material_surface_g(mat, uv);
    if (!v.front) // leaving the material: the relative index inverts
        v.surf.bsdf.eta = 1.0 / v.surf.bsdf.eta;
    v.le = (v.front || v.surf.double_sided) ? v.surf.emission : vec3(0.0);
    v.origin = v.p + ng * ray_epsilon(v.p);
    v.origin_below = v.p + ng * -ray_epsilon(v.p);
    if (u_surface_offset > 0.0) {
        v.origin += ng * u_surface_offset;
        v.origin_below -= ng * u_surface_offset;
    }
    return v;
}

// Whether light from world direction wi can reach v's BSDF, and on which
// side (= light_side of the reference): above the geometric surface, or
// below it (below) when the BSDF transmits; the local wl must agree.
bool light_side(pt_vertex v, vec3 wi, out vec3 wl, out bool below)
{
    float d = dot(wi, v.ng);
    wl = to_local(wi, v.t, v.b, v.n);
    below = d < 0.0;
    if (d > 0.0)
        return wl.z > 0.0;
    return below && dirt_bsdf_transmits_g(v.surf.bsdf) && wl.z < 0.0;
}

uint path_flags(dirt_gpu_path s)
{
    return floatBitsToUint(s.radiance.w);
}

void set_flags(inout dirt_gpu_path s, uint f)
{
    s.radiance.w = uintBitsToFloat(f);
}
