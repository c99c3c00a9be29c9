/* DIRT engine: lights and camera rays of the light-transport model
 * (doc/light-transport.md, "Lights" and "Camera"). */
#include "integrator/integrator.h"

#include <math.h>
#include <stdlib.h>

#include "dirt/log.h"
#include "core/vec3.h"

bool dirt_punctual_light(const dirt_light *light, dirt_vec3 p, dirt_vec3 *wi,
                         float *dist, dirt_vec3 *li)
{
    dirt_vec3 color = v3_load(light->color);
    if (light->type == DIRT_LIGHT_DIRECTIONAL) {
        dirt_vec3 d = v3_normalize(v3_load(light->direction));
        if (v3_is_zero(d))
            return false;
        *wi = v3_neg(d);
        *dist = INFINITY;
        *li = color;
        return !v3_is_zero(color);
    }
    dirt_vec3 to = v3_sub(v3_load(light->position), p);
    float d2 = v3_dot(to, to);
    if (!(d2 > 0.0f) || !isfinite(d2))
        return false;
    float d = sqrtf(d2);
    *wi = v3_scale(to, 1.0f / d);
    *dist = d;
    float att = 1.0f / d2;
    if (light->range > 0.0f) {
        float r = d / light->range;
        float r2 = r * r;
        att *= clamp01(1.0f - r2 * r2);
    }
    if (light->type == DIRT_LIGHT_SPOT) {
        dirt_vec3 sd = v3_normalize(v3_load(light->direction));
        float cd = -v3_dot(sd, *wi); /* cosine between spot axis and light -> p */
        float co = cosf(light->outer_cone), ci = cosf(light->inner_cone);
        float s = clamp01((cd - co) / fmaxf(1e-3f, ci - co));
        att *= s * s;
    }
    *li = v3_scale(color, att);
    return att > 0.0f && !v3_is_zero(color);
}

bool dirt_area_lights_build(dirt_area_lights *out, const dirt_frame *frame,
                            const dirt_material *materials, size_t num_materials)
{
    size_t n = 0;
    out->count = 0;
    out->prim = NULL;
    out->cdf = NULL;
    out->total_area = 0.0f;
    for (size_t p = 0; p < frame->num_triangles; p++) {
        uint32_t m = frame->material[p];
        if (m < num_materials && dirt_material_is_emissive(&materials[m]))
            n++;
    }
    if (n == 0)
        return true;
    out->prim = malloc(n * sizeof(*out->prim));
    out->cdf = malloc(n * sizeof(*out->cdf));
    if (!out->prim || !out->cdf) {
        DIRT_ERROR("area lights: out of memory for %zu emissive triangles", n);
        dirt_area_lights_free(out);
        return false;
    }
    double sum = 0.0;
    size_t k = 0;
    for (size_t p = 0; p < frame->num_triangles; p++) {
        uint32_t m = frame->material[p];
        if (m >= num_materials || !dirt_material_is_emissive(&materials[m]))
            continue;
        dirt_vec3 p0 = v3_load(frame->position[3 * p]);
        dirt_vec3 e1 = v3_sub(v3_load(frame->position[3 * p + 1]), p0);
        dirt_vec3 e2 = v3_sub(v3_load(frame->position[3 * p + 2]), p0);
        float area = 0.5f * v3_length(v3_cross(e1, e2));
        if (!(area > 0.0f) || !isfinite(area))
            continue;
        sum += area;
        out->prim[k] = (uint32_t)p;
        out->cdf[k] = (float)sum;
        k++;
    }
    out->count = k;
    out->total_area = (float)sum;
    if (k == 0)
        dirt_area_lights_free(out);
    return true;
}

void dirt_area_lights_free(dirt_area_lights *lights)
{
    if (!lights)
        return;
    free(lights->prim);
    free(lights->cdf);
    lights->prim = NULL;
    lights->cdf = NULL;
    lights->count = 0;
    lights->total_area = 0.0f;
}

size_t dirt_cdf_find(const float *cdf, size_t n, float x)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (cdf[mid] > x)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

size_t dirt_area_lights_select(const dirt_area_lights *lights, float u)
{
    return dirt_cdf_find(lights->cdf, lights->count, u * lights->total_area);
}

void dirt_camera_ray(const dirt_camera *cam, int width, int height, float px,
                     float py, float lens_u, float lens_v, dirt_vec3 *org,
                     dirt_vec3 *dir)
{
    float aspect = cam->aspect > 0.0f ? cam->aspect : (float)width / (float)height;
    if (!(aspect > 0.0f) || !isfinite(aspect))
        aspect = 1.0f;
    float nx = 2.0f * px / (float)width - 1.0f;
    float ny = 1.0f - 2.0f * py / (float)height;
    dirt_vec3 eye = v3_load(cam->eye), fwd = v3_load(cam->forward);
    dirt_vec3 right = v3_load(cam->right), up = v3_load(cam->up);
    if (cam->type == DIRT_CAMERA_ORTHOGRAPHIC) {
        float ymag = cam->ymag > 0.0f ? cam->ymag : 1.0f;
        float xmag = cam->xmag > 0.0f ? cam->xmag : ymag * aspect;
        *org = v3_mad(v3_mad(eye, right, nx * xmag), up, ny * ymag);
        *dir = v3_normalize(fwd);
        return;
    }
    float yfov = cam->yfov > 0.0f ? cam->yfov : 0.785398163f; /* as dirt_camera_projection */
    float th = tanf(0.5f * yfov);
    /* d . forward = 1: the point at parameter f along d lies on the plane
     * perpendicular to forward at distance f. */
    dirt_vec3 d = v3_mad(v3_mad(fwd, right, nx * th * aspect), up, ny * th);
    if (cam->aperture_radius > 0.0f && cam->focus_distance > 0.0f) {
        float lx, ly;
        dirt_sample_disk(lens_u, lens_v, &lx, &ly);
        dirt_vec3 focus = v3_mad(eye, d, cam->focus_distance);
        dirt_vec3 lens = v3_mad(v3_mad(eye, right, lx * cam->aperture_radius), up,
                                ly * cam->aperture_radius);
        *org = lens;
        *dir = v3_normalize(v3_sub(focus, lens));
    } else {
        *org = eye;
        *dir = v3_normalize(d);
    }
}
