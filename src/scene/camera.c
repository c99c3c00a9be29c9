/* DIRT engine: camera pose and projection helpers. */
#include "scene/scene_internal.h"

#include <math.h>
#include <string.h>

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(float out[3], const float a[3], const float b[3])
{
    float r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                  a[0] * b[1] - a[1] * b[0]};
    memcpy(out, r, sizeof(r));
}

static bool normalize3(float v[3])
{
    float l2 = dot3(v, v);
    if (!(l2 > 1e-30f) || !isfinite(l2))
        return false;
    float inv = 1.0f / sqrtf(l2);
    v[0] *= inv;
    v[1] *= inv;
    v[2] *= inv;
    return true;
}

/* World -> eye: rows right, up, -forward; the eye moves to the origin. */
static void set_view(dirt_camera *c)
{
    float *v = c->view;
    v[0] = c->right[0];
    v[4] = c->right[1];
    v[8] = c->right[2];
    v[1] = c->up[0];
    v[5] = c->up[1];
    v[9] = c->up[2];
    v[2] = -c->forward[0];
    v[6] = -c->forward[1];
    v[10] = -c->forward[2];
    v[3] = v[7] = v[11] = 0.0f;
    v[12] = -dot3(c->right, c->eye);
    v[13] = -dot3(c->up, c->eye);
    v[14] = dot3(c->forward, c->eye);
    v[15] = 1.0f;
}

void scene_camera_set_basis(dirt_camera *c, const float fwd[3], const float up_hint[3])
{
    float f[3] = {fwd[0], fwd[1], fwd[2]};
    if (!normalize3(f)) {
        f[0] = 0.0f;
        f[1] = 0.0f;
        f[2] = -1.0f;
    }
    float r[3];
    cross3(r, f, up_hint);
    if (!normalize3(r)) {
        /* Up parallel to forward: any perpendicular axis will do. */
        float alt[3] = {0.0f, 0.0f, 0.0f};
        alt[fabsf(f[1]) < 0.9f ? 1 : 0] = 1.0f;
        cross3(r, f, alt);
        normalize3(r);
    }
    float u[3];
    cross3(u, r, f);
    memcpy(c->forward, f, sizeof(f));
    memcpy(c->right, r, sizeof(r));
    memcpy(c->up, u, sizeof(u));
    set_view(c);
}

/* Sets the pose fields (eye, forward, up, right, view) only; projection and
 * lens parameters are left as they are. */
void dirt_camera_look_at(dirt_camera *cam, const float eye[3], const float target[3],
                         const float up[3])
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    memcpy(cam->eye, eye, sizeof(cam->eye));
    scene_camera_set_basis(cam, f, up);
}

void dirt_camera_from_look(const dirt_camera_look *look, dirt_camera *out)
{
    memset(out, 0, sizeof(*out));
    dirt_camera_look_at(out, look->eye, look->target, look->up);
    float d[3] = {look->target[0] - look->eye[0], look->target[1] - look->eye[1],
                  look->target[2] - look->eye[2]};
    float dist = sqrtf(dot3(d, d));
    out->type = DIRT_CAMERA_PERSPECTIVE;
    out->yfov = (look->fov_deg > 0.0f ? look->fov_deg : 45.0f) * 0.0174532925f;
    out->znear = look->znear > 0.0f ? look->znear : fmaxf(dist * 1e-3f, 1e-6f);
    out->zfar = look->zfar > out->znear ? look->zfar : 0.0f;
    out->focus_distance = dist > 0.0f ? dist : 1.0f;
}

void dirt_camera_auto_bounds(const float min[3], const float max[3], dirt_camera *out)
{
    static const float yfov = 0.785398163f; /* 45 degrees */
    float c[3], d[3];
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5f * (min[k] + max[k]);
        d[k] = max[k] - min[k];
    }
    float r = 0.5f * sqrtf(dot3(d, d));
    if (!isfinite(c[0]) || !isfinite(c[1]) || !isfinite(c[2]))
        c[0] = c[1] = c[2] = 0.0f;
    if (!(r > 1e-6f) || !isfinite(r))
        r = 1.0f;
    /* Far enough that the bounding sphere fits the vertical field of view. */
    float dist = r / sinf(0.5f * yfov);
    float dir[3] = {0.0f, 0.3f, 1.0f};
    normalize3(dir);
    float eye[3] = {c[0] + dir[0] * dist, c[1] + dir[1] * dist, c[2] + dir[2] * dist};
    static const float up[3] = {0.0f, 1.0f, 0.0f};

    memset(out, 0, sizeof(*out));
    dirt_camera_look_at(out, eye, c, up);
    out->type = DIRT_CAMERA_PERSPECTIVE;
    out->yfov = yfov;
    out->aspect = 0.0f;
    out->znear = fmaxf((dist - r) * 0.5f, r * 1e-3f);
    out->zfar = dist + 2.0f * r;
    out->xmag = out->ymag = r;
    out->aperture_radius = 0.0f;
    out->focus_distance = dist;
}

void dirt_camera_auto(const dirt_frame *frame, dirt_camera *out)
{
    static const float zero[3] = {0.0f, 0.0f, 0.0f};
    if (frame && frame->num_triangles > 0)
        dirt_camera_auto_bounds(frame->bounds_min, frame->bounds_max, out);
    else
        dirt_camera_auto_bounds(zero, zero, out);
}

void dirt_camera_projection(const dirt_camera *cam, float image_aspect, float out[16])
{
    float aspect = cam->aspect > 0.0f ? cam->aspect : image_aspect;
    if (!(aspect > 0.0f) || !isfinite(aspect))
        aspect = 1.0f;
    float n = cam->znear > 0.0f ? cam->znear : 1e-3f;
    float f = cam->zfar;
    memset(out, 0, 16 * sizeof(float));
    if (cam->type == DIRT_CAMERA_ORTHOGRAPHIC) {
        float ymag = cam->ymag > 0.0f ? cam->ymag : 1.0f;
        float xmag = cam->xmag > 0.0f ? cam->xmag : ymag * aspect;
        if (!(f > n))
            f = n + 1.0f;
        out[0] = 1.0f / xmag;
        out[5] = 1.0f / ymag;
        out[10] = 2.0f / (n - f);
        out[14] = (f + n) / (n - f);
        out[15] = 1.0f;
        return;
    }
    float yfov = cam->yfov > 0.0f ? cam->yfov : 0.785398163f;
    float cot = 1.0f / tanf(0.5f * yfov);
    out[0] = cot / aspect;
    out[5] = cot;
    out[11] = -1.0f;
    if (f > n) {
        out[10] = (f + n) / (n - f);
        out[14] = 2.0f * f * n / (n - f);
    } else {
        out[10] = -1.0f;
        out[14] = -2.0f * n;
    }
}

void dirt_camera_default(const dirt_frame *frame, dirt_camera *out)
{
    if (frame->num_cameras && frame->cameras[0].type == DIRT_CAMERA_PERSPECTIVE)
        *out = frame->cameras[0];
    else
        dirt_camera_auto(frame, out);
}
