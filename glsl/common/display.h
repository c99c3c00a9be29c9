/* The display transforms shared by C and GLSL: the tone-map operators and
 * curves, the sRGB transfer function, the heat ramp and the luminance
 * weights. The PNG writer (src/io/png.c), the DIRT debug pictures
 * (src/dirt/debug.c) and the window's presentation shader
 * (glsl/present/present.frag) all use these names, so a picture in a
 * window and the PNG of the same image agree.
 *
 * This file must stay valid as both C11 and GLSL 4.50: #define and #if
 * only.
 * Float constants carry the f suffix, which both languages accept, so C
 * computes in float exactly as written. */
#ifndef DIRT_COMMON_DISPLAY_H
#define DIRT_COMMON_DISPLAY_H

/* ---- Tone-map operators: the values of enum dirt_tonemap (dirt/types.h,
 * the consumer API, which cannot include this file; src/io/png.c checks
 * that they agree) ---- */

#define DIRT_TONEMAP_ID_CLAMP 0
#define DIRT_TONEMAP_ID_REINHARD 1
#define DIRT_TONEMAP_ID_ACES 2

/* Narkowicz 2015 fit of the ACES filmic curve (sRGB primaries), for x > 0:
 *   x (A x + B) / (x (C x + D) + E)        (0 for x <= 0 and NaN) */
#define DIRT_ACES_A 2.51f
#define DIRT_ACES_B 0.03f
#define DIRT_ACES_C 2.43f
#define DIRT_ACES_D 0.59f
#define DIRT_ACES_E 0.14f

/* ---- sRGB transfer (IEC 61966-2-1) of a value v in (0, 1) ----
 *   v <= DIRT_SRGB_LINEAR_MAX: DIRT_SRGB_LINEAR_SCALE * v
 *   else: DIRT_SRGB_SCALE * v^DIRT_SRGB_EXPONENT - DIRT_SRGB_OFFSET
 * The 8-bit value is round(255 * s) (dirt_linear_to_srgb8). */
#define DIRT_SRGB_LINEAR_MAX 0.0031308f
#define DIRT_SRGB_LINEAR_SCALE 12.92f
#define DIRT_SRGB_SCALE 1.055f
#define DIRT_SRGB_OFFSET 0.055f
#define DIRT_SRGB_EXPONENT (1.0f / 2.4f)

/* ---- Heat ramp ----
 * x in [0, 1] (clamped) runs through DIRT_HEAT_KEYS colours at equal steps,
 * linearly between neighbours: black, blue, red, yellow, white. Each key is
 * three floats, for a C initialiser {DIRT_HEAT_KEY_0} or a GLSL
 * vec3(DIRT_HEAT_KEY_0). */
#define DIRT_HEAT_KEYS 5
#define DIRT_HEAT_KEY_0 0.0f, 0.0f, 0.0f /* black */
#define DIRT_HEAT_KEY_1 0.0f, 0.0f, 1.0f /* blue */
#define DIRT_HEAT_KEY_2 1.0f, 0.0f, 0.0f /* red */
#define DIRT_HEAT_KEY_3 1.0f, 1.0f, 0.0f /* yellow */
#define DIRT_HEAT_KEY_4 1.0f, 1.0f, 1.0f /* white */
#if DIRT_HEAT_KEYS != 5
#error "common/display.h: the ramp's users (debug.c, present.frag) list the keys one by one"
#endif

/* ---- Luminance of linear Rec. 709 RGB (the presentation's difference view) ---- */
#define DIRT_LUMA_R 0.2126f
#define DIRT_LUMA_G 0.7152f
#define DIRT_LUMA_B 0.0722f

/* ---- Presentation modes of glsl/present/present.frag (src/gl/present.c
 * maps enum dirt_present_mode of dirt/window.h onto them) ---- */
#define DIRT_PRESENT_ID_COLOR 0
#define DIRT_PRESENT_ID_HEAT 1
#define DIRT_PRESENT_ID_SIGNED 2
#define DIRT_PRESENT_ID_DIFF 3

#endif
