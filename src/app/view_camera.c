/* dirt-view's free camera (view_camera.h). */
#include "app/view_camera.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/vec.h"

/* The few vector operations the camera needs (the programs see public
 * headers only). */
static dirt_vec3 v3_load(const float p[3]) { return (dirt_vec3){p[0], p[1], p[2]}; }
static void v3_store(float p[3], dirt_vec3 a) { p[0] = a.x, p[1] = a.y, p[2] = a.z; }
static dirt_vec3 v3_add(dirt_vec3 a, dirt_vec3 b) { return (dirt_vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static dirt_vec3 v3_sub(dirt_vec3 a, dirt_vec3 b) { return (dirt_vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static dirt_vec3 v3_scale(dirt_vec3 a, float s) { return (dirt_vec3){a.x * s, a.y * s, a.z * s}; }
static dirt_vec3 v3_mad(dirt_vec3 a, dirt_vec3 b, float s) { return v3_add(a, v3_scale(b, s)); }
static float v3_dot(dirt_vec3 a, dirt_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static float v3_length(dirt_vec3 a) { return sqrtf(v3_dot(a, a)); }
static dirt_vec3 v3_cross(dirt_vec3 a, dirt_vec3 b)
{
    return (dirt_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static dirt_vec3 v3_normalize(dirt_vec3 a)
{
    float l = v3_length(a);
    return l > 0 ? v3_scale(a, 1.0f / l) : a;
}

static const float DEG = 0.0174532925f;

float vcam_distance(const dirt_camera_look *look)
{
    return v3_length(v3_sub(v3_load(look->target), v3_load(look->eye)));
}

void vcam_from_camera(dirt_camera_look *look, const dirt_camera *cam, float distance)
{
    memset(look, 0, sizeof(*look));
    dirt_vec3 f = v3_normalize(v3_load(cam->forward));
    if (!(distance > 0) || !isfinite(distance))
        distance = 1.0f;
    dirt_vec3 eye = v3_load(cam->eye), target = v3_mad(eye, f, distance);
    v3_store(look->eye, eye);
    v3_store(look->target, target);
    if (fabsf(f.y) < 0.999f)
        look->up[1] = 1.0f;
    else
        memcpy(look->up, cam->up, sizeof(look->up));
    look->fov_deg = cam->yfov > 0 ? cam->yfov / DEG : 45.0f;
    look->znear = cam->znear;
    look->zfar = cam->zfar;
}

/* v rotated by `angle` radians about the unit axis k (Rodrigues). */
static dirt_vec3 rotate(dirt_vec3 v, dirt_vec3 k, float angle)
{
    float c = cosf(angle), s = sinf(angle);
    return v3_add(v3_add(v3_scale(v, c), v3_scale(v3_cross(k, v), s)),
                  v3_scale(k, v3_dot(k, v) * (1.0f - c)));
}

void vcam_orbit(dirt_camera_look *look, float yaw, float pitch)
{
    dirt_vec3 target = v3_load(look->target), up = v3_normalize(v3_load(look->up));
    dirt_vec3 v = v3_sub(v3_load(look->eye), target); /* target -> eye */
    float r = v3_length(v);
    if (!(r > 0))
        return;
    v = rotate(v, up, -yaw * DEG);
    /* The angle between up and the eye direction stays in [1, 179] degrees. */
    float polar = acosf(fmaxf(-1.0f, fminf(1.0f, v3_dot(v3_scale(v, 1.0f / r), up))));
    float next = fmaxf(1.0f * DEG, fminf(179.0f * DEG, polar - pitch * DEG));
    dirt_vec3 right = v3_cross(up, v);
    if (v3_length(right) > 0)
        v = rotate(v, v3_normalize(right), next - polar); /* about up x v: away from up */
    v3_store(look->eye, v3_add(target, v));
}

/* The view's right and up axes (orthonormal, from the look). */
static void axes(const dirt_camera_look *look, dirt_vec3 *fwd, dirt_vec3 *right, dirt_vec3 *up)
{
    dirt_camera c;
    dirt_camera_from_look(look, &c);
    *fwd = v3_load(c.forward);
    *right = v3_load(c.right);
    *up = v3_load(c.up);
}

void vcam_pan(dirt_camera_look *look, float dx, float dy)
{
    dirt_vec3 f, r, u;
    axes(look, &f, &r, &u);
    float fov = (look->fov_deg > 0 ? look->fov_deg : 45.0f) * DEG;
    float h = 2.0f * vcam_distance(look) * tanf(0.5f * fov);
    dirt_vec3 d = v3_add(v3_scale(r, -dx * h), v3_scale(u, -dy * h));
    v3_store(look->eye, v3_add(v3_load(look->eye), d));
    v3_store(look->target, v3_add(v3_load(look->target), d));
}

void vcam_dolly(dirt_camera_look *look, float factor)
{
    dirt_vec3 target = v3_load(look->target);
    dirt_vec3 v = v3_sub(v3_load(look->eye), target);
    float r = v3_length(v);
    if (!(factor > 0) || !(r > 0))
        return;
    float next = fmaxf(r * factor, 1e-4f);
    v3_store(look->eye, v3_add(target, v3_scale(v, next / r)));
}

void vcam_fly(dirt_camera_look *look, float forward, float right, float up)
{
    dirt_vec3 f, r, u;
    axes(look, &f, &r, &u);
    dirt_vec3 d = v3_add(v3_add(v3_scale(f, forward), v3_scale(r, right)), v3_scale(u, up));
    v3_store(look->eye, v3_add(v3_load(look->eye), d));
    v3_store(look->target, v3_add(v3_load(look->target), d));
}

void vcam_format(const dirt_camera_look *l, char *buf, size_t size)
{
    int n = snprintf(buf, size,
                     "--eye %.9g,%.9g,%.9g --look-at %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g "
                     "--fov %.9g",
                     l->eye[0], l->eye[1], l->eye[2], l->target[0], l->target[1], l->target[2],
                     l->up[0], l->up[1], l->up[2], l->fov_deg > 0 ? l->fov_deg : 45.0f);
    if (n > 0 && (size_t)n < size && l->znear > 0)
        n += snprintf(buf + n, size - (size_t)n, " --znear %.9g", l->znear);
    if (n > 0 && (size_t)n < size && l->zfar > 0)
        snprintf(buf + n, size - (size_t)n, " --zfar %.9g", l->zfar);
}
