#version 450 core
// Raster preview: simple direct lighting without shadows. Emission plus the
// Lambert term of every light (punctual lights and emissive surfaces lumped
// into points), plus a small ambient term.
#include "common/layout.h"
#include "common/color.glsl"

#define PI 3.14159265358979

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;

layout(location = DIRT_LOC_PREVIEW_EYE) uniform vec3 u_eye;
layout(location = DIRT_LOC_PREVIEW_FORWARD) uniform vec3 u_forward; // unit camera axis
layout(location = DIRT_LOC_PREVIEW_MATERIAL) uniform int u_material;
layout(location = DIRT_LOC_PREVIEW_NUM_LIGHTS) uniform int u_num_lights;
layout(location = DIRT_LOC_PREVIEW_AMBIENT) uniform float u_ambient;

layout(binding = DIRT_UNIT_PREVIEW_BASE_COLOR) uniform sampler2D u_base_color_tex;
layout(binding = DIRT_UNIT_PREVIEW_EMISSIVE) uniform sampler2D u_emissive_tex;

layout(std430, binding = DIRT_BIND_PREVIEW_MATERIALS) readonly buffer Materials {
    dirt_gpu_material materials[];
};
layout(std430, binding = DIRT_BIND_PREVIEW_LIGHTS) readonly buffer Lights {
    dirt_gpu_light lights[];
};

layout(location = 0) out vec4 out_color;
layout(location = 1) out vec4 out_aov; // xyz shading normal facing the camera, w depth

// Radiance-like factor (irradiance / pi times pi cancels) arriving at p with
// normal n from light l.
vec3 light_contribution(dirt_gpu_light l, vec3 p, vec3 n)
{
    int kind = int(l.position.w);
    vec3 wi;
    float atten = 1.0;
    if (kind == DIRT_PREVIEW_LIGHT_DIRECTIONAL) {
        wi = -l.direction.xyz;
    } else {
        vec3 d = l.position.xyz - p;
        float dist2 = max(dot(d, d), 1e-8);
        wi = d * inversesqrt(dist2);
        atten = 1.0 / dist2;
        float range = l.color.w;
        if (range > 0.0) {
            float r = sqrt(dist2) / range;
            atten *= clamp(1.0 - r * r * r * r, 0.0, 1.0);
        }
        if (kind == DIRT_PREVIEW_LIGHT_SPOT) {
            float cd = dot(l.direction.xyz, -wi);
            float t = clamp((cd - l.cone.y) / max(l.cone.x - l.cone.y, 1e-4), 0.0, 1.0);
            atten *= t * t;
        } else if (kind == DIRT_PREVIEW_LIGHT_EMITTER) {
            atten *= max(dot(l.direction.xyz, -wi), 0.0);
        }
    }
    return l.color.rgb * atten * max(dot(n, wi), 0.0);
}

void main()
{
    dirt_gpu_material m = materials[u_material];
    vec4 base = m.base_color;
    if (m.textures.x >= 0)
        base *= vec4(srgb_to_linear(texture(u_base_color_tex, v_uv).rgb), texture(u_base_color_tex, v_uv).a);
    vec3 emission = m.emissive.rgb;
    if (m.textures.z >= 0)
        emission *= srgb_to_linear(texture(u_emissive_tex, v_uv).rgb);

    vec3 n = normalize(v_normal);
    vec3 to_eye = normalize(u_eye - v_position);
    if (dot(n, to_eye) < 0.0)
        n = -n; // shade the side the camera sees
    vec3 e = vec3(0.0);
    for (int i = 0; i < u_num_lights; i++)
        e += light_contribution(lights[i], v_position, n);
    vec3 albedo = base.rgb * (1.0 - 0.5 * m.pbr.x);
    out_color = vec4(emission + albedo / PI * e + u_ambient * albedo, 1.0);
    out_aov = vec4(n, dot(v_position - u_eye, u_forward));
}
