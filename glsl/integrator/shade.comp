#version 450 core
// Path tracer, Shade at event k (= one iteration of the reference's
// path_sample loop): emission of G_k with MIS, then — unless k > K — one
// next-event sample (its shadow ray goes out; the contribution waits in
// `pending` until resolve.comp knows the ray's fate) and one BSDF sample
// that becomes the ray of event k + 1 (with Russian roulette from
// DIRT_RR_START_VERTEX). With DIRT_AO: ambient occlusion instead (one cosine
// ray of length u_ao_distance from the first hit).
#include "common/layout.h"
#define DIRT_MODEL_BUFFERS 1
#include "common/rng.glsl"
#include "integrator/model.glsl"
#include "integrator/pt_common.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_GPOINTS) readonly buffer GPoints {
    dirt_gpu_gpoint gpoints[];
};
layout(std430, binding = DIRT_BIND_HITS) readonly buffer Hits {
    dirt_gpu_hit hits[];
};
// The rays of event k (read: the arriving direction), then those of k + 1.
layout(std430, binding = DIRT_BIND_RAYS) buffer Rays {
    dirt_gpu_ray rays[];
};
layout(std430, binding = DIRT_BIND_SHADOW_RAYS) writeonly buffer ShadowRays {
    dirt_gpu_ray shadow_rays[];
};
// The event's batch: ray i continues the path of pixel owner[i] (its hit,
// its ray of event k + 1 and its shadow ray are entry i, its path state and
// shading points the pixel's).
#define DIRT_RAY_BATCH_ALWAYS 1
#include "common/ray_batch.glsl"

// The shadow ray from a vertex's ray origin `org` (origin, or origin_below
// for light through the surface) to the light point y, stopping
// SHADOW_SHORTEN short of it (= occluded_to of the reference): aimed from
// the origin itself, not along the direction from v.p, which would end the
// ray ray_epsilon off y and could take it through the light.
void shadow_to(vec3 org, vec3 y, out vec3 dir, out float tmax)
{
    vec3 d = y - org;
    float len = length(d);
    dir = len > 0.0 ? d * (1.0 / len) : vec3(0.0, 0.0, 1.0);
    tmax = len > 0.0 ? len * (1.0 - SHADOW_SHORTEN) : -1.0; // -1: unoccluded
}

// Next-event estimation at v (= sample_light of the reference): returns the
// contribution (before the throughput) and sets the shadow ray's origin
// (v.origin, or v.origin_below for light through the surface), direction
// and length; false when nothing can be sampled.
bool sample_light(pt_vertex v, uint key, out vec3 contrib, out vec3 org_out, out vec3 wi_out,
                  out float tmax)
{
    contrib = vec3(0.0);
    org_out = v.origin;
    wi_out = vec3(0.0, 0.0, 1.0);
    tmax = -1.0;
    uint n = dirt_nee_sources_g();
    if (n == 0u)
        return false;
    float us = dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_SELECT);
    uint s = uint(us * float(n));
    if (s >= n)
        s = n - 1u;
    uint area = dirt_model_lights.counts.x;
    if (area > 0u && s == 0u) {
        uint idx = dirt_area_lights_select_g(dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_TRI));
        uint prim = dirt_model_area_prim[idx];
        float b1, b2;
        dirt_sample_triangle_g(dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_U),
                               dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_V), b1, b2);
        vec3 y = tri_point(prim, b1, b2);
        vec3 to = y - v.p;
        float dist = length(to);
        if (!(dist > 0.0))
            return false;
        vec3 wi = to / dist;
        vec3 wl;
        bool below;
        if (!light_side(v, wi, wl, below))
            return false;
        org_out = below ? v.origin_below : v.origin;
        float cos_l = -dot(tri_normal_ng(prim), wi);
        uint m = dirt_prim_material(prim);
        bool two = (dirt_model_materials[m].textures.w & DIRT_MODEL_MAT_DOUBLE_SIDED) != 0;
        if (cos_l < 0.0 && !two)
            return false;
        vec3 f = dirt_bsdf_eval_g(v.surf.bsdf, v.wo, wl);
        if (dirt_is_zero_g(f))
            return false;
        float pdf_l = light_pdf(prim, wi, dist);
        if (!(pdf_l > 0.0) || isinf(pdf_l))
            return false;
        dirt_surface_g ls = dirt_material_surface_g(m, tri_uv(prim, b1, b2));
        if (dirt_is_zero_g(ls.emission))
            return false;
        float w = dirt_mis_power_g(pdf_l, dirt_bsdf_pdf_g(v.surf.bsdf, v.wo, wl));
        contrib = f * ls.emission * (abs(wl.z) * w / pdf_l);
        if (u_surface_offset > 0.0) {
            // Stop the shadow ray u_surface_offset off the light's plane
            // (the tracer accepts surfaces within a thickness of the ray);
            // receiver and light point too close to each other's planes for
            // that: untraced, unoccluded.
            vec3 nl = tri_normal_ng(prim);
            if (dot(nl, v.p - y) < 0.0)
                nl = -nl;
            float off = u_surface_offset;
            vec3 side = below ? -v.ng : v.ng;
            if (dot(y - v.p, side) < 2.0 * off || dot(v.p - y, nl) < 2.0 * off) {
                wi_out = wi;
                tmax = -1.0;
                return true;
            }
            y += nl * off;
        }
        shadow_to(org_out, y, wi_out, tmax);
        return true;
    }
    if (dirt_env_samples_g() && s == n - 1u) {
        vec3 wi, le;
        float pdf_e;
        if (!dirt_env_sample_g(dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_TRI),
                               dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_U),
                               dirt_rng_next_float(key, DIRT_RNG_DIM_LIGHT_V), wi, pdf_e, le))
            return false;
        vec3 wl;
        bool below;
        if (!light_side(v, wi, wl, below))
            return false;
        org_out = below ? v.origin_below : v.origin;
        vec3 f = dirt_bsdf_eval_g(v.surf.bsdf, v.wo, wl);
        if (dirt_is_zero_g(f))
            return false;
        float pdf_l = pdf_e / float(n);
        float w = dirt_mis_power_g(pdf_l, dirt_bsdf_pdf_g(v.surf.bsdf, v.wo, wl));
        contrib = f * le * (abs(wl.z) * w / pdf_l);
        wi_out = wi;
        tmax = DIRT_INFINITY_G;
        return true;
    }
    dirt_gpu_model_light light = dirt_model_punctual[s - (area > 0u ? 1u : 0u)];
    vec3 wi, li;
    float dist;
    if (!dirt_punctual_light_g(light, v.p, wi, dist, li))
        return false;
    vec3 wl;
    bool below;
    if (!light_side(v, wi, wl, below))
        return false;
    org_out = below ? v.origin_below : v.origin;
    vec3 f = dirt_bsdf_eval_g(v.surf.bsdf, v.wo, wl);
    if (dirt_is_zero_g(f))
        return false;
    contrib = f * li * (abs(wl.z) * float(n));
    wi_out = wi;
    tmax = DIRT_INFINITY_G;
    if (!isinf(dist))
        shadow_to(org_out, v.p + wi * dist, wi_out, tmax);
    return true;
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= dirt_batch_count(u_pixels))
        return;
    uint p = dirt_batch_owner(i);
    dirt_gpu_path s = paths[p];
    uint flags = path_flags(s);
    vec3 dir = normalize(rays[i].dir_tmax.xyz);
    // Inactive rays by default: tmax < tmin finds nothing.
    rays[i].dir_tmax = vec4(0.0, 0.0, 1.0, -1.0);
    shadow_rays[i].dir_tmax = vec4(0.0, 0.0, 1.0, -1.0);
    s.pending = vec4(0.0);
    if ((flags & DIRT_PATH_ALIVE) == 0u) {
        paths[p] = s;
        return;
    }
    dirt_gpu_gpoint g = gpoints[3u * p + u_slot];
    vec3 beta = s.beta_pdf.xyz;
    if (floatBitsToUint(g.pos_prim.w) == DIRT_NO_HIT) {
#ifdef DIRT_AO
        s.radiance.xyz = vec3(1.0); // camera ray missed: unoccluded
#else
        vec3 le = dirt_env_eval_g(dir);
        float w = 1.0;
        if ((flags & DIRT_PATH_PREV_DELTA) == 0u && !dirt_is_zero_g(le))
            w = dirt_mis_power_g(s.beta_pdf.w, env_light_pdf(dir));
        s.radiance.xyz += beta * le * w;
#endif
        set_flags(s, flags & ~DIRT_PATH_ALIVE);
        paths[p] = s;
        return;
    }
    pt_vertex v = make_vertex(g, dir, hits[i].bary_t.xy);
    if (u_bounce == 1u) {
        s.first_albedo = vec4(v.surf.bsdf.base_color, 0.0);
        s.first_normal = vec4(v.n, 0.0);
        flags |= DIRT_PATH_FIRST_HIT;
    }
#ifdef DIRT_AO
    uint akey = dirt_rng_key(u_seed, u_pixel_offset + p, u_sample, 1u);
    vec3 awl = dirt_sample_cosine_g(dirt_rng_next_float(akey, DIRT_RNG_DIM_BSDF_U),
                                    dirt_rng_next_float(akey, DIRT_RNG_DIM_BSDF_V));
    vec3 awi = dirt_normalize_g(from_local(awl, v.t, v.b, v.n));
    if (dot(awi, v.ng) > 0.0) {
        shadow_rays[i].origin_tmin = vec4(v.origin, 0.0);
        shadow_rays[i].dir_tmax = vec4(awi, u_ao_distance);
        s.pending = vec4(1.0, 1.0, 1.0, 1.0);
    }
    set_flags(s, flags & ~DIRT_PATH_ALIVE);
    paths[p] = s;
#else
    if (!dirt_is_zero_g(v.le)) {
        float w = 1.0;
        if ((flags & DIRT_PATH_PREV_DELTA) == 0u)
            w = dirt_mis_power_g(s.beta_pdf.w, light_pdf(v.prim, dir, hits[i].bary_t.z));
        s.radiance.xyz += beta * v.le * w;
    }
    if (u_bounce > u_bounces) {
        set_flags(s, flags & ~DIRT_PATH_ALIVE);
        paths[p] = s;
        return;
    }
    uint key = dirt_rng_key(u_seed, u_pixel_offset + p, u_sample, u_bounce);
    vec3 contrib, lorg, lwi;
    float ltmax;
    if (sample_light(v, key, contrib, lorg, lwi, ltmax)) {
        shadow_rays[i].origin_tmin = vec4(lorg, 0.0);
        shadow_rays[i].dir_tmax = vec4(lwi, ltmax);
        s.pending = vec4(beta * contrib, 1.0);
    }
    vec3 wi_l, weight;
    float pdf;
    bool delta;
    bool alive = dirt_bsdf_sample_dir_g(v.surf.bsdf, v.wo,
                                        dirt_rng_next_float(key, DIRT_RNG_DIM_LOBE),
                                        dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_U),
                                        dirt_rng_next_float(key, DIRT_RNG_DIM_BSDF_V),
                                        wi_l, weight, pdf, delta);
    vec3 wi = from_local(wi_l, v.t, v.b, v.n);
    bool below = wi_l.z < 0.0; // transmitted through the surface
    float side = dot(wi, v.ng);
    if (alive && (below ? !(side < 0.0) : side <= 0.0))
        alive = false; // the shading and geometric sides disagree
    if (alive) {
        beta *= weight;
        s.beta_pdf = vec4(beta, pdf);
        flags = delta ? (flags | DIRT_PATH_PREV_DELTA) : (flags & ~DIRT_PATH_PREV_DELTA);
        if (u_bounce >= uint(DIRT_RR_START_VERTEX_G)) {
            float q = dirt_rr_survival_g(beta);
            if (q < 1.0) {
                if (!(dirt_rng_next_float(key, DIRT_RNG_DIM_RR) < q))
                    alive = false;
                else
                    s.beta_pdf.xyz = beta / q;
            }
        }
    }
    if (alive) {
        rays[i].origin_tmin = vec4(below ? v.origin_below : v.origin, 0.0);
        rays[i].dir_tmax = vec4(dirt_normalize_g(wi), DIRT_INFINITY_G);
    } else {
        flags &= ~DIRT_PATH_ALIVE;
    }
    set_flags(s, flags);
    paths[p] = s;
#endif
}
