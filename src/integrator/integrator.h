/* DIRT engine: the light-transport model shared by the CPU reference
 * (src/ref, Embree) and the GPU integrator (glsl/).
 *
 * Everything here is a small pure function of plain floats: no ray casting,
 * no allocation except the area-light table, no global state. The GLSL side
 * implements the same formulas (doc/light-transport.md is the specification;
 * the random numbers come from src/integrator/rng.h, doc/rng.md).
 *
 * Conventions
 *  - BSDF directions are in the local shading frame: the shading normal is
 *    +z, both wo (towards the viewer) and wi (towards the light) point away
 *    from the surface and are unit length.
 *  - f(wo, wi) is the BSDF without the cosine; "weight" is f * cos / pdf.
 *  - pdfs are per unit solid angle, except where a name says area.
 *  - Colours are linear RGB. */
#ifndef DIRT_INTEGRATOR_H
#define DIRT_INTEGRATOR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dirt/env.h"
#include "dirt/scene.h"

#include "core/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* GGX alpha below which the specular lobe is a perfect mirror (delta). */
#define DIRT_ALPHA_DELTA 1e-3f
/* Dielectric normal-incidence reflectance of glTF (IOR 1.5). */
#define DIRT_DIELECTRIC_F0 0.04f
/* Relative index of refraction within this of 1: an index-matched
 * interface, whose transmission is a delta (the straight-through
 * refraction) however rough the surface (doc/light-transport.md). */
#define DIRT_ETA_MATCHED 1e-3f
/* Russian roulette starts at path vertex DIRT_RR_START_VERTEX + 1
 * (i.e. after this many scattering events). */
#define DIRT_RR_START_VERTEX 3

/* BSDF parameters at one surface point (after texturing). */
typedef struct dirt_bsdf {
    dirt_vec3 base_color; /* linear, each in [0,1] */
    float metallic;       /* [0,1] */
    float alpha;          /* GGX alpha = roughness^2; < DIRT_ALPHA_DELTA: mirror */
    float specular;       /* dielectric specular weight s (KHR_materials_specular
                             specularFactor x specularTexture.a) in [0,1];
                             glTF default 1 */
    dirt_vec3 f0;         /* dielectric F0 colour before the weight:
                             min(dirt_ior_f0(ior) x specularColor, 1) per
                             channel, each in [0,1]; glTF default 0.04 */
    float transmission;   /* KHR_materials_transmission t in [0,1]: the share
                             of the dielectric base that is specular
                             transmission instead of diffuse; 0 = opaque */
    float eta;            /* relative index of refraction across the surface,
                             n(far side) / n(wo's side), > 0: the material's
                             dirt_ior_eta(ior) when wo is on the front
                             (winding) side, its inverse on the back (the
                             integrators flip it; dirt_material_surface
                             gives the front's) */
} dirt_bsdf;

/* Result of dirt_bsdf_sample. */
typedef struct dirt_bsdf_sample {
    dirt_vec3 wi;     /* sampled direction, local frame: wi.z > 0 reflected,
                         wi.z < 0 transmitted (through the surface) */
    dirt_vec3 weight; /* f * |wi.z| / pdf (for the mirror: F / p_spec; for
                         the delta transmission: (1 - m) t (1 - F_t) base /
                         (eta^2 p_trans)) */
    float pdf;        /* solid-angle pdf of the non-delta part (0 when delta) */
    bool delta;       /* a delta lobe (mirror or smooth transmission) was chosen */
} dirt_bsdf_sample;

/* ---- BSDF (src/integrator/bsdf.c) --------------------------------------- */

/* True when the specular lobe is a perfect mirror (alpha < DIRT_ALPHA_DELTA). */
bool dirt_bsdf_is_delta(const dirt_bsdf *b);
/* True when the transmission lobe is a delta: a smooth surface (alpha <
 * DIRT_ALPHA_DELTA) or an index-matched one (|eta - 1| < DIRT_ETA_MATCHED). */
bool dirt_bsdf_transmission_is_delta(const dirt_bsdf *b);

/* True when the BSDF can send light through the surface (t > 0 and
 * metallic < 1): the integrators then accept directions below the
 * geometric surface (next-event estimation, path continuation). */
bool dirt_bsdf_transmits(const dirt_bsdf *b);

/* F0 of an interface between air and index `ior` (KHR_materials_ior):
 * ((ior - 1) / (ior + 1))^2 computed in double (1.5 -> exactly 0.04f); 0
 * and +inf give 1 (the specular-glossiness conversion), NaN or negative
 * the glTF default 0.04. */
float dirt_ior_f0(float ior);
/* The index refraction uses: ior when >= 1 and finite, else 1 (index
 * matched: glTF allows only ior >= 1, or 0 for F0 = 1). */
float dirt_ior_eta(float ior);

/* Schlick Fresnel of the whole specular lobe at cos theta = c (RGB):
 *   F(c) = (1 - m) ((1 - t) F_d(c) + t F_t(c)) + m (base + (1 - base) x(c)),
 *   F_d(c) = s (f0 + (1 - f0) x(c))   (dielectric, per channel),
 *   F_t(c) = F_d(c_t), c_t = c when eta >= 1, else the cosine of the
 *            refracted direction sqrt(1 - (1 - c^2) / eta^2); 1 on total
 *            internal reflection            (the transmissive interface),
 * x(c) = (1 - clamp(c, 0, 1))^5. On the front of a glTF material (eta =
 * ior >= 1) F_t = F_d. */
dirt_vec3 dirt_bsdf_fresnel(const dirt_bsdf *b, float c);
/* The dielectric part F_d(c) alone, scalar: its largest channel (glTF
 * KHR_materials_specular's max_value; the diffuse base is weighted by 1
 * minus it). */
float dirt_bsdf_fresnel_dielectric(const dirt_bsdf *b, float c);
/* The interface's F_t(c), scalar (largest channel); 1 on total internal
 * reflection. The transmission lobe is weighted by 1 minus it. */
float dirt_bsdf_fresnel_interface(const dirt_bsdf *b, float c);

/* GGX normal distribution D(h) for the local half vector h (unit). */
float dirt_ggx_d(float alpha, dirt_vec3 h);
/* Smith Lambda of direction w, G1 = 1 / (1 + Lambda). */
float dirt_ggx_lambda(float alpha, dirt_vec3 w);
/* Height-correlated Smith masking-shadowing G2 = 1 / (1 + L(wo) + L(wi)). */
float dirt_ggx_g2(float alpha, dirt_vec3 wo, dirt_vec3 wi);

/* Probability of choosing the specular (reflection) lobe when sampling
 * from wo. */
float dirt_bsdf_spec_probability(const dirt_bsdf *b, dirt_vec3 wo);
/* The lobe probabilities from wo: *p_spec (reflection), *p_trans
 * (transmission); diffuse takes max(0, 1 - p_spec - p_trans). From the
 * weights w_s = Y(F(wo.z)), w_d = (1 - m)(1 - t) Y(base)(1 - F_d(wo.z)),
 * w_t = (1 - m) t Y(base)(1 - F'(wo.z)), F' = F_t for a delta
 * transmission, F_d for a rough one; p = w / sum (p_spec 1/2, p_trans 0
 * when all are 0). */
void dirt_bsdf_lobe_probabilities(const dirt_bsdf *b, dirt_vec3 wo, float *p_spec,
                                  float *p_trans);

/* f(wo, wi) of the non-delta part: for wi.z > 0 diffuse + GGX reflection
 * (diffuse only when the specular lobe is a delta), symmetric in wo and wi;
 * for wi.z < 0 the rough GGX transmission (Walter et al. 2007, radiance
 * form: f(wi, wo) with 1 / eta = eta^2 f(wo, wi)), zero when it is a delta
 * or t = 0. Zero when wo.z <= 0 or wi.z == 0. */
dirt_vec3 dirt_bsdf_eval(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi);

/* Solid-angle pdf with which dirt_bsdf_sample returns wi from wo, for the
 * non-delta part: for wi.z > 0 p_spec * pdf_vndf + p_diff * wi.z / pi (the
 * first term absent for a mirror), for wi.z < 0 p_trans * pdf of the
 * refracted visible normal (absent for a delta transmission). Zero when
 * wo.z <= 0 or wi.z == 0. */
float dirt_bsdf_pdf(const dirt_bsdf *b, dirt_vec3 wo, dirt_vec3 wi);

/* Samples wi from wo with three uniform numbers in [0,1): u_lobe picks the
 * lobe (specular when u_lobe < p_spec, transmission when p_trans > 0 and
 * u_lobe >= p_spec + p_diff, else diffuse), (u1, u2) the direction (GGX
 * visible normals, reflected or refracted, or cosine). False when wo.z <=
 * 0, when the sample falls on the wrong side of the surface (or refraction
 * is impossible: total internal reflection) or when its weight is zero (the
 * path ends). */
bool dirt_bsdf_sample_dir(const dirt_bsdf *b, dirt_vec3 wo, float u_lobe,
                          float u1, float u2, dirt_bsdf_sample *out);

/* ---- warps and frames (src/integrator/bsdf.c) --------------------------- */

/* Cosine-weighted hemisphere about +z: r = sqrt(u1), phi = 2 pi u2,
 * (r cos phi, r sin phi, sqrt(1 - u1)); pdf = z / pi. */
dirt_vec3 dirt_sample_cosine(float u1, float u2);

/* GGX visible normal from wo (wo.z > 0) by the spherical-cap method:
 * pdf of h = G1(wo) max(0, wo.h) D(h) / wo.z. */
dirt_vec3 dirt_sample_ggx_vndf(float alpha, dirt_vec3 wo, float u1, float u2);

/* Uniform point on the unit disk: r = sqrt(u1), phi = 2 pi u2 -> (x, y). */
void dirt_sample_disk(float u1, float u2, float *x, float *y);

/* Uniform barycentrics on a triangle: s = sqrt(u1), b1 = 1 - s, b2 = u2 s;
 * the point is (1 - b1 - b2) p0 + b1 p1 + b2 p2. */
void dirt_sample_triangle(float u1, float u2, float *b1, float *b2);

/* Orthonormal basis (t, b, n) about the unit vector n (Duff et al. 2017):
 * s = n.z >= 0 ? 1 : -1, a = -1 / (s + n.z), c = n.x n.y a,
 * t = (1 + s n.x^2 a, s c, -s n.x), b = (c, s + n.y^2 a, -n.y). */
void dirt_onb(dirt_vec3 n, dirt_vec3 *t, dirt_vec3 *b);

/* Power heuristic with exponent 2: a^2 / (a^2 + b^2), 0 when both are 0. */
float dirt_mis_power(float a, float b);

/* Russian-roulette survival probability for path throughput beta:
 * min(1, max(beta.x, beta.y, beta.z)). */
float dirt_rr_survival(dirt_vec3 beta);

/* ---- textures and materials (src/integrator/texture.c) ------------------ */

/* sRGB transfer function, decode (exact piecewise formula). */
float dirt_srgb_to_linear(float c);

/* Bilinear texture lookup with repeat wrapping. Texel (i, j) has its centre
 * at uv ((i + 0.5) / w, (j + 0.5) / h), row j = 0 is the first row of the
 * image. Each of the four texels is converted to float (c / 255) and, when
 * `srgb`, its RGB decoded to linear before filtering; alpha is never
 * decoded. A NULL texture, or one with no pixels, reads as (1,1,1,1).
 * Non-finite u or v read as 0. */
void dirt_texture_sample(const dirt_texture *tex, bool srgb, float u, float v,
                         float out[4]);

/* Surface description at a hit: BSDF parameters and emitted radiance. */
typedef struct dirt_surface {
    dirt_bsdf bsdf;
    dirt_vec3 emission;   /* emitted radiance (front side, or both sides when
                             double_sided) */
    bool double_sided;
} dirt_surface;

/* Textures a material at (u, v), each slot's lookup at its own transformed
 * uv (dirt_tex_transform_apply of the slot's dirt_tex_transform_matrix):
 *   base     = base_color.rgb * sRGB(base_color_tex).rgb
 *   roughness= clamp(roughness * mr_tex.g), metallic = clamp(metallic * mr_tex.b)
 *   alpha    = roughness^2
 *   emission = emissive * emissive_strength * sRGB(emissive_tex).rgb
 *   specular = clamp(clamp(specular * m->specular) * specular_tex.a)
 *   f0       = clamp((dirt_ior_f0(ior) * specular_color) * sRGB(specular_color_tex).rgb)
 *   transmission = clamp(transmission * transmission_tex.r)
 *   eta      = dirt_ior_eta(ior)   (the front side's)
 * Texture indices out of [0, num_textures) read as the white default.
 * `specular` is an extra factor on the material's specular weight (1 for
 * plain glTF; 0 turns the dielectric reflection off: exactly Lambert). */
void dirt_material_surface(const dirt_material *m, float specular,
                           const dirt_texture *textures, size_t num_textures,
                           float u, float v, dirt_surface *out);

/* ---- alpha coverage (src/integrator/texture.c; doc/light-transport.md
 * section 1, "Alpha") ----------------------------------------------------- */

/* Coverage at UV (u, v): base_color[3] * T(base_color_tex).a (linear: alpha
 * is never sRGB-decoded), not clamped. 1 x the factor without a texture. */
float dirt_material_coverage(const dirt_material *m, const dirt_texture *textures,
                             size_t num_textures, float u, float v);

/* True when the material's hits are tested during traversal (MASK, BLEND). */
bool dirt_material_alpha_tested(const dirt_material *m);

/* Whether a ray sees the hit of primitive `prim` at UV (u, v) of material m:
 * OPAQUE (or an unknown mode) always; MASK when coverage >= alpha_cutoff;
 * BLEND when dirt_rng_alpha(ray_key, prim) < coverage (stochastic
 * transparency: the hit is ignored with probability 1 - coverage).
 * `ray_key` = dirt_rng_u32(seed, pixel, sample, bounce,
 * DIRT_RNG_DIM_ALPHA_PATH or _SHADOW) (integrator/rng.h, doc/rng.md). An
 * ignored hit is not a hit: traversal goes on to the next one. */
bool dirt_alpha_accept(const dirt_material *m, const dirt_texture *textures,
                       size_t num_textures, float u, float v, uint32_t ray_key, uint32_t prim);

/* True when any of the materials is alpha-tested. */
bool dirt_materials_alpha_tested(const dirt_material *materials, size_t count);

/* ---- texture transforms and normal maps (src/integrator/texture.c) ------ */

/* The uv matrix of a KHR_texture_transform, uv' = M (u, v, 1), as its two
 * rows m = (m00, m01, m02, m10, m11, m12): M = T(offset) R(rotation)
 * S(scale) with the rotation of the extension's prose and examples (the
 * uvs turn counter-clockwise in the image, whose v runs down):
 *   c = cosf(rotation), s = sinf(rotation)
 *   m = (scale.x c, scale.y s, offset.x,  -(scale.x s), scale.y c, offset.y)
 * The identity (no trigonometry) when xf is NULL or not set. */
void dirt_tex_transform_matrix(const dirt_tex_transform *xf, float m[6]);

/* uv' = M (u, v, 1) of a matrix from dirt_tex_transform_matrix, u and v
 * read as 0 when not finite (as a lookup reads them):
 *   out[0] = (m00 u + m01 v) + m02,  out[1] = (m10 u + m11 v) + m12
 * (each product rounded, no fused multiply-add). The identity returns
 * (u, v) exactly (-0 as +0). */
void dirt_tex_transform_apply(const float m[6], float u, float v, float out[2]);

/* The tangent-space normal of the material's normal map at (u, v), the
 * normal slot's transform applied: c = T(normal_tex, uv') (linear RGB),
 *   n_ts = normalize(((2 c.r - 1) s, (2 c.g - 1) s, 2 c.b - 1)),
 * s = normal_scale. False (n_ts unset) when the material has no normal map
 * (index outside [0, num_textures)) or n_ts is zero or not finite. */
bool dirt_material_normal_ts(const dirt_material *m, const dirt_texture *textures,
                             size_t num_textures, float u, float v, dirt_vec3 *n_ts);

/* The shading normal a normal map gives at a point: n = the unit
 * interpolated vertex normal (the front side's), t = the interpolated
 * tangent (any length), w its handedness (only the sign counts):
 *   t' = normalize(t - n (n . t)),  b = cross(n, t') (w < 0 ? -1 : 1),
 *   result = normalize(t' n_ts.x + b n_ts.y + n n_ts.z).
 * Returns n itself when |t - n (n . t)| is not above 1e-3 |t| (no tangent
 * there, a non-finite one, or one (nearly) along n: what is left of it is
 * rounding) or the result is zero. */
dirt_vec3 dirt_normal_map_apply(dirt_vec3 n, dirt_vec3 t, float w, dirt_vec3 n_ts);

/* ---- lights (src/integrator/lights.c) ----------------------------------- */

/* Incident light at point p from a punctual light: *wi = unit direction from
 * p towards the light, *dist = distance (INFINITY for directional), *li =
 * the product (radiant intensity or irradiance) x attenuation, so that the
 * reflected radiance is f * cos * li. Point/spot: color / d^2 times the glTF
 * range window clamp(1 - (d / range)^4, 0, 1) (range 0 = none); spot also
 * times the smooth cone factor s^2, s = clamp((cd - cos_outer) /
 * max(1e-3, cos_inner - cos_outer), 0, 1), cd = cosine between the spot
 * direction and the direction light -> p. Directional: color, from
 * -direction. False when li is zero. */
bool dirt_punctual_light(const dirt_light *light, dirt_vec3 p, dirt_vec3 *wi,
                         float *dist, dirt_vec3 *li);

/* The emissive triangles of a frame, for uniform area-weighted selection:
 * triangle i is chosen with probability area_i / total_area, so a point
 * sampled uniformly on it has area pdf 1 / total_area. */
typedef struct dirt_area_lights {
    size_t count;
    uint32_t *prim;     /* primitive ids, ascending */
    float *cdf;         /* cdf[i] = sum of areas of 0..i (double-summed) */
    float total_area;
} dirt_area_lights;

/* Collects every triangle with positive area whose material is emissive
 * (dirt_material_is_emissive). Triangles whose material index is out of
 * range are skipped. False on out-of-memory (logged). */
bool dirt_area_lights_build(dirt_area_lights *out, const dirt_frame *frame,
                            const dirt_material *materials, size_t num_materials);
void dirt_area_lights_free(dirt_area_lights *lights);

/* The first i in [0, n) with cdf[i] > x, n - 1 when none (binary search of
 * a non-decreasing cdf; n > 0): how the area lights and the environment
 * pick their entry. */
size_t dirt_cdf_find(const float *cdf, size_t n, float x);

/* Index (into prim/cdf) of the triangle selected by u in [0,1): the first i
 * with cdf[i] > u * total_area (binary search). count must be > 0. */
size_t dirt_area_lights_select(const dirt_area_lights *lights, float u);

/* Number of light sources NEE chooses among: 1 for the set of area lights
 * (when not empty) plus one per punctual light. Source s = min(floor(u n),
 * n - 1); source 0 is the area set when there is one. */
static inline unsigned dirt_light_source_count(size_t num_area, size_t num_punctual)
{
    return (unsigned)((num_area > 0 ? 1u : 0u) + num_punctual);
}

/* With an environment light sampled (dirt_env_samples): one more source,
 * the last (s = n - 1). */
static inline unsigned dirt_nee_source_count(size_t num_area, size_t num_punctual, bool env)
{
    return dirt_light_source_count(num_area, num_punctual) + (env ? 1u : 0u);
}

/* ---- environment light (src/integrator/env.c) ---------------------------- */

/* An equirectangular environment map: the radiance arriving along every
 * direction from infinitely far away, piecewise constant over its texels,
 * importance-sampled in next-event estimation (doc/light-transport.md,
 * "Environment"). Direction d (world, unit) is rotated by -rotation about
 * +Y into the map's frame, e = R_y(-rotation) d, at azimuth phi =
 * atan2(e.x, -e.z). Its texel is the column i whose edges phi_i = 2 pi i /
 * w - pi hold phi, and the row j whose band row_cos[j + 1] <= e.y <
 * row_cos[j] holds e.y (row 0 at +Y, the first image row): the image's
 * centre looks along -Z, the glTF camera's default view. Both are decided
 * by comparisons of the same floats in C and GLSL, not by atan2 or acos
 * (not correctly rounded in GLSL): the row by a binary search of row_cos,
 * the column (for w >= 4) from a first guess by atan2 corrected by the sign
 * of e.x cos(phi_k) + e.z sin(phi_k) = sin(phi - phi_k) at its edges
 * (col_cos, col_sin). The poles (e.x = e.z = 0) read column 0. A constant
 * background is the 1 x 1 map. The consumer API (dirt/env.h) makes, loads
 * and destroys maps; this is their content. */
struct dirt_env {
    int width, height;
    float *rgb;       /* width * height * 3: texel radiance (times intensity),
                         row 0 = the image's first row (+Y) */
    float *row_cos;   /* height + 1: cos theta at the rows' edges, from 1 to -1
                         (cosf of pi j / height computed in double) */
    float *cdf;       /* width * height, row-major: cumulative texel weights
                         luminance(rgb) * (row_cos[j] - row_cos[j + 1]),
                         summed in double */
    float *col_cos, *col_sin; /* width + 1: cos and sin of the columns'
                         edges phi_i (computed in double) */
    float total;      /* cdf[width * height - 1]; 0: nothing to sample */
    float rot_cos, rot_sin; /* cosf / sinf of the rotation (radians) */
};


/* True when next-event estimation samples the map (total > 0). NULL: false. */
bool dirt_env_samples(const dirt_env *env);

/* Texel (column, row) of unit world direction d (see dirt_env). */
void dirt_env_texel(const dirt_env *env, dirt_vec3 d, int *col, int *row);
/* Radiance arriving along -d, i.e. seen looking along unit direction d.
 * NULL env: 0. */
dirt_vec3 dirt_env_eval(const dirt_env *env, dirt_vec3 d);
/* Solid-angle pdf with which dirt_env_sample returns d:
 * (cdf[k] - cdf[k - 1]) / (total (2 pi / w) (row_cos[j] - row_cos[j + 1]))
 * for d's texel k = j w + i; 0 when the map is not sampled. */
float dirt_env_pdf(const dirt_env *env, dirt_vec3 d);
/* Samples a direction: u_sel picks the texel (the first k with cdf[k] >
 * u_sel * total), (u1, u2) a point of it uniform in solid angle: phi = 2 pi
 * (i + u1) / w - pi, cos theta = row_cos[j] - u2 (row_cos[j] -
 * row_cos[j + 1]). Sets *d (unit, world), *pdf (as dirt_env_pdf, from the
 * texel chosen) and *radiance (the texel's). False when the map is not
 * sampled or the chosen texel has zero weight. */
bool dirt_env_sample(const dirt_env *env, float u_sel, float u1, float u2, dirt_vec3 *d,
                     float *pdf, dirt_vec3 *radiance);

/* ---- camera (src/integrator/lights.c) ----------------------------------- */

/* Primary ray through the continuous pixel position (px, py) of a width x
 * height image (px in [0, width), py in [0, height), py = 0 the top edge).
 * Perspective: through the pinhole at eye, or, when aperture_radius > 0 and
 * focus_distance > 0, from a point of the lens disk (lens_u, lens_v mapped by
 * dirt_sample_disk, scaled by aperture_radius along right/up) towards the
 * point where the pinhole ray meets the plane of focus (perpendicular to
 * forward at focus_distance). Orthographic: parallel rays along forward from
 * eye + x xmag right + y ymag up. aspect = camera aspect, or width / height
 * when the camera has none. *dir is unit length. */
void dirt_camera_ray(const dirt_camera *cam, int width, int height, float px,
                     float py, float lens_u, float lens_v, dirt_vec3 *org,
                     dirt_vec3 *dir);

#ifdef __cplusplus
}
#endif
#endif
