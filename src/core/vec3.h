/* The engine's one vector-math header: dirt_vec3 operations that mirror
 * GLSL's vec3 operators one float operation at a time, so the CPU reference
 * and the shaders round alike. Header-only. */
#ifndef DIRT_CORE_VEC3_H
#define DIRT_CORE_VEC3_H

#include <math.h>
#include <stdbool.h>

#include "core/vec.h"

static inline dirt_vec3 v3(float x, float y, float z)
{
    dirt_vec3 r = {x, y, z};
    return r;
}
static inline dirt_vec3 v3_load(const float p[3]) { return v3(p[0], p[1], p[2]); }
static inline dirt_vec3 v3_add(dirt_vec3 a, dirt_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline dirt_vec3 v3_sub(dirt_vec3 a, dirt_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline dirt_vec3 v3_mul(dirt_vec3 a, dirt_vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline dirt_vec3 v3_scale(dirt_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline dirt_vec3 v3_neg(dirt_vec3 a) { return v3(-a.x, -a.y, -a.z); }
static inline float v3_dot(dirt_vec3 a, dirt_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline dirt_vec3 v3_cross(dirt_vec3 a, dirt_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_length(dirt_vec3 a) { return sqrtf(v3_dot(a, a)); }
/* Unit vector along a; (0,0,0) stays (0,0,0). */
static inline dirt_vec3 v3_normalize(dirt_vec3 a)
{
    float l = v3_length(a);
    return l > 0.0f ? v3_scale(a, 1.0f / l) : a;
}
static inline dirt_vec3 v3_mad(dirt_vec3 a, dirt_vec3 b, float s) /* a + b*s */
{
    return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
static inline float v3_max_comp(dirt_vec3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }
static inline float v3_luminance(dirt_vec3 a) { return 0.2126f * a.x + 0.7152f * a.y + 0.0722f * a.z; }
static inline bool v3_is_zero(dirt_vec3 a) { return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f; }
static inline bool v3_is_finite(dirt_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
/* Local frame (t, b, n) -> world. */
static inline dirt_vec3 v3_from_local(dirt_vec3 l, dirt_vec3 t, dirt_vec3 b, dirt_vec3 n)
{
    return v3(t.x * l.x + b.x * l.y + n.x * l.z, t.y * l.x + b.y * l.y + n.y * l.z,
              t.z * l.x + b.z * l.y + n.z * l.z);
}
/* World -> local frame (t, b, n). */
static inline dirt_vec3 v3_to_local(dirt_vec3 w, dirt_vec3 t, dirt_vec3 b, dirt_vec3 n)
{
    return v3(v3_dot(w, t), v3_dot(w, b), v3_dot(w, n));
}
static inline float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

#endif
