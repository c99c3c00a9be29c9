#version 450 core
// The window's presentation (src/gl/present.c, dirt_gpu_present of
// gl/window.h): each pixel of the destination rectangle shows the nearest
// texel of an RGBA32F image (texelFetch), in one of the modes below, as the
// 8-bit sRGB value dirt_image_write_png stores for it. The default
// framebuffer is not an sRGB one: the encoding is done here and the value
// written is already the 8-bit code (q / 255), so the framebuffer's
// conversion to 8 bits (round to nearest) gives q back.
//
// Non-finite values are recognised from their bits: the compiler may assume
// a float comparison never sees a NaN.
#include "common/constants.h"
#include "common/display.h"

layout(binding = DIRT_UNIT_PRESENT_A) uniform sampler2D u_image;
layout(binding = DIRT_UNIT_PRESENT_B) uniform sampler2D u_image_b;

layout(location = DIRT_LOC_PRESENT_RECT) uniform ivec4 u_rect;
layout(location = DIRT_LOC_PRESENT_MODE) uniform int u_mode;
layout(location = DIRT_LOC_PRESENT_SCALE) uniform float u_scale;
layout(location = DIRT_LOC_PRESENT_TONEMAP) uniform int u_tonemap;
layout(location = DIRT_LOC_PRESENT_CHANNEL) uniform int u_channel;
layout(location = DIRT_LOC_PRESENT_RANGE) uniform vec2 u_range;
layout(location = DIRT_LOC_PRESENT_SPLIT) uniform float u_split;
layout(location = DIRT_LOC_PRESENT_SPLIT_LINE) uniform int u_split_line;

layout(location = 0) out vec4 out_color;

bool is_nan(float v)
{
    return (floatBitsToUint(v) & 0x7fffffffu) > 0x7f800000u;
}

bool is_finite(float v)
{
    return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u;
}

// The tone-map curve of src/io/png.c for one exposed value; the result is
// clamped by srgb8. Reinhard and ACES give 0 for x <= 0 and NaN, and for
// +inf too: png.c's inf / inf is a NaN, which the 8-bit step maps to 0.
float tonemap(float x)
{
    if (u_tonemap == DIRT_TONEMAP_ID_CLAMP)
        return x;
    if (!is_finite(x) || x <= 0.0)
        return 0.0;
    if (u_tonemap == DIRT_TONEMAP_ID_REINHARD)
        return x / (1.0f + x);
    return (x * (DIRT_ACES_A * x + DIRT_ACES_B)) / (x * (DIRT_ACES_C * x + DIRT_ACES_D) + DIRT_ACES_E);
}

// dirt_linear_to_srgb8 as a normalised value: round(255 * srgb(clamp(v))) / 255.
float srgb8(float v)
{
    if (is_nan(v) || v <= 0.0)
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    float s = v <= DIRT_SRGB_LINEAR_MAX ? DIRT_SRGB_LINEAR_SCALE * v
                                        : DIRT_SRGB_SCALE * pow(v, DIRT_SRGB_EXPONENT) - DIRT_SRGB_OFFSET;
    return clamp(floor(s * 255.0 + 0.5), 0.0, 255.0) / 255.0;
}

vec3 srgb8(vec3 v)
{
    return vec3(srgb8(v.r), srgb8(v.g), srgb8(v.b));
}

// The heat ramp of src/dirt/debug.c.
vec3 heat(float x)
{
    const vec3 keys[DIRT_HEAT_KEYS] = vec3[](vec3(DIRT_HEAT_KEY_0), vec3(DIRT_HEAT_KEY_1),
                                             vec3(DIRT_HEAT_KEY_2), vec3(DIRT_HEAT_KEY_3),
                                             vec3(DIRT_HEAT_KEY_4));
    x = clamp(x, 0.0, 1.0) * float(DIRT_HEAT_KEYS - 1);
    int i = min(int(x), DIRT_HEAT_KEYS - 2);
    float t = x - float(i);
    return keys[i] + t * (keys[i + 1] - keys[i]);
}

float luminance(vec3 c)
{
    return DIRT_LUMA_R * c.r + DIRT_LUMA_G * c.g + DIRT_LUMA_B * c.b;
}

// The texel of `image` under this pixel: pixel i of the rectangle (from its
// left, rows from its top) shows texel floor(i * size / rect size).
vec4 fetch(sampler2D image)
{
    ivec2 size = textureSize(image, 0);
    ivec2 p = ivec2(gl_FragCoord.xy) - u_rect.xy;
    ivec2 local = ivec2(p.x, u_rect.w - 1 - p.y);
    ivec2 t = (local * size) / u_rect.zw;
    return texelFetch(image, clamp(t, ivec2(0), size - 1), 0);
}

vec3 heat_of(float v)
{
    if (!is_finite(v))
        return vec3(0.0);
    return heat((v - u_range.x) / (u_range.y - u_range.x));
}

void main()
{
    bool right = u_split >= 0.0 && gl_FragCoord.x >= u_split;
    if (u_split >= 0.0 && u_split_line != 0 && floor(gl_FragCoord.x) == floor(u_split)) {
        out_color = vec4(1.0);
        return;
    }
    vec3 rgb;
    if (u_mode == DIRT_PRESENT_ID_DIFF) {
        vec3 a = fetch(u_image).rgb, b = fetch(u_image_b).rgb;
        rgb = srgb8(heat_of(abs(luminance(a) - luminance(b))));
    } else {
        vec4 c = right ? fetch(u_image_b) : fetch(u_image);
        if (u_mode == DIRT_PRESENT_ID_HEAT)
            rgb = srgb8(heat_of(c[u_channel]));
        else if (u_mode == DIRT_PRESENT_ID_SIGNED)
            rgb = srgb8(c.rgb * 0.5 + 0.5);
        else
            rgb = vec3(srgb8(tonemap(c.r * u_scale)), srgb8(tonemap(c.g * u_scale)),
                       srgb8(tonemap(c.b * u_scale)));
    }
    out_color = vec4(rgb, 1.0);
}
