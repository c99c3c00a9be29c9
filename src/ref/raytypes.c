#include "ref/raytypes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrator/integrator.h"
#include "dirt/log.h"
#include "integrator/rng.h"
#include "core/vec3.h"

_Static_assert(sizeof(dirt_ray) == sizeof(dirt_ref_ray), "ray layouts");

static void light_target(const dirt_scene *scene, const dirt_frame *f, float diag, float out[3])
{
    const dirt_material *mat = dirt_scene_materials(scene);
    double acc[3] = {0}, nrm[3] = {0}, area = 0;
    for (size_t t = 0; t < f->num_triangles; t++) {
        if (!dirt_material_is_emissive(&mat[f->material[t]]))
            continue;
        const float *a = f->position[3 * t], *b = f->position[3 * t + 1], *c = f->position[3 * t + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        double ar = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const float *sn = f->normal[3 * t];
        double flip = n[0] * sn[0] + n[1] * sn[1] + n[2] * sn[2] < 0 ? -1 : 1;
        for (int k = 0; k < 3; k++) {
            acc[k] += ar * (a[k] + b[k] + c[k]) / 3;
            nrm[k] += flip * n[k];
        }
        area += ar;
    }
    if (area > 0) {
        double nl = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (int k = 0; k < 3; k++)
            out[k] = (float)(acc[k] / area + (nl > 0 ? 1e-3 * diag * nrm[k] / nl : 0));
    } else if (f->num_lights) {
        memcpy(out, f->lights[0].position, 12);
    } else {
        out[0] = 0.5f * (f->bounds_min[0] + f->bounds_max[0]);
        out[1] = f->bounds_max[1] + 0.1f * diag;
        out[2] = 0.5f * (f->bounds_min[2] + f->bounds_max[2]);
    }
}

bool dirt_gbuffer_build(const dirt_ref_accel *accel, const dirt_scene *scene,
                        const dirt_frame *f, const dirt_camera *cam, int w, int h,
                        dirt_gbuffer *g)
{
    memset(g, 0, sizeof(*g));
    size_t n = (size_t)w * (size_t)h;
    dirt_ref_ray *rays = malloc(n * sizeof(*rays));
    dirt_ref_hit *hits = malloc(n * sizeof(*hits));
    g->pixel = malloc(n * sizeof(*g->pixel));
    g->prim = malloc(n * sizeof(*g->prim));
    g->position = malloc(n * sizeof(*g->position));
    g->normal = malloc(n * sizeof(*g->normal));
    g->view_dir = malloc(n * sizeof(*g->view_dir));
    if (!rays || !hits || !g->pixel || !g->prim || !g->position || !g->normal || !g->view_dir) {
        DIRT_ERROR("out of memory for a %dx%d G-buffer", w, h);
        free(rays);
        free(hits);
        dirt_gbuffer_free(g);
        return false;
    }
    g->width = w;
    g->height = h;
    float d[3] = {f->bounds_max[0] - f->bounds_min[0], f->bounds_max[1] - f->bounds_min[1],
                  f->bounds_max[2] - f->bounds_min[2]};
    float diag = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    g->epsilon = 1e-4f * (diag > 0 ? diag : 1);
    light_target(scene, f, diag, g->light);
    dirt_ray *primary = (dirt_ray *)rays;
    dirt_rays_generate(g, cam, DIRT_RAY_PRIMARY, 0, primary);
    dirt_ref_intersect(accel, rays, hits, n, 0);
    for (size_t i = 0; i < n; i++) {
        if (hits[i].prim == DIRT_REF_MISS)
            continue;
        size_t k = g->count++;
        dirt_vec3 dir = {rays[i].dir[0], rays[i].dir[1], rays[i].dir[2]};
        float s = hits[i].ng[0] * dir.x + hits[i].ng[1] * dir.y + hits[i].ng[2] * dir.z > 0 ? -1 : 1;
        g->pixel[k] = (uint32_t)i;
        g->prim[k] = hits[i].prim;
        for (int c = 0; c < 3; c++) {
            g->position[k][c] = rays[i].org[c] + hits[i].t * rays[i].dir[c];
            g->normal[k][c] = s * hits[i].ng[c];
        }
        g->view_dir[k][0] = dir.x, g->view_dir[k][1] = dir.y, g->view_dir[k][2] = dir.z;
    }
    free(rays);
    free(hits);
    return true;
}

void dirt_gbuffer_free(dirt_gbuffer *g)
{
    if (!g)
        return;
    free(g->pixel);
    free(g->prim);
    free(g->position);
    free(g->normal);
    free(g->view_dir);
    memset(g, 0, sizeof(*g));
}

static dirt_vec3 to_world(dirt_vec3 l, dirt_vec3 n)
{
    dirt_vec3 t, b;
    dirt_onb(n, &t, &b);
    return (dirt_vec3){l.x * t.x + l.y * b.x + l.z * n.x, l.x * t.y + l.y * b.y + l.z * n.y,
                       l.x * t.z + l.y * b.z + l.z * n.z};
}

size_t dirt_rays_generate(const dirt_gbuffer *g, const dirt_camera *cam, enum dirt_ray_type type,
                          uint32_t seed, dirt_ray *out)
{
    if (type == DIRT_RAY_PRIMARY) {
        size_t k = 0;
        for (int y = 0; y < g->height; y++) {
            for (int x = 0; x < g->width; x++, k++) {
                dirt_vec3 o, d;
                dirt_camera_ray(cam, g->width, g->height, x + 0.5f, y + 0.5f, 0.5f, 0.5f, &o, &d);
                out[k] = (dirt_ray){{o.x, o.y, o.z}, 0.0f, {d.x, d.y, d.z}, INFINITY};
            }
        }
        return k;
    }
    for (size_t i = 0; i < g->count; i++) {
        dirt_vec3 n = v3_load(g->normal[i]), v = v3_load(g->view_dir[i]);
        float o[3];
        for (int c = 0; c < 3; c++)
            o[c] = g->position[i][c] + g->epsilon * g->normal[i][c];
        dirt_vec3 d;
        float tmax = INFINITY;
        float u1 = dirt_rng_float(seed, g->pixel[i], 0, 0, 0);
        float u2 = dirt_rng_float(seed, g->pixel[i], 0, 0, 1);
        float dn = v.x * n.x + v.y * n.y + v.z * n.z;
        dirt_vec3 mirror = {v.x - 2 * dn * n.x, v.y - 2 * dn * n.y, v.z - 2 * dn * n.z};
        switch (type) {
        case DIRT_RAY_VISIBILITY:
            d = (dirt_vec3){g->light[0] - o[0], g->light[1] - o[1], g->light[2] - o[2]};
            tmax = 1.0f;
            break;
        case DIRT_RAY_SPECULAR:
            d = mirror;
            break;
        case DIRT_RAY_GLOSSY: {
            /* Visible normal about n for wo = -v, reflected. */
            dirt_vec3 t, b;
            dirt_onb(n, &t, &b);
            dirt_vec3 wo = {-(v.x * t.x + v.y * t.y + v.z * t.z), -(v.x * b.x + v.y * b.y + v.z * b.z),
                            -dn};
            dirt_vec3 hl = dirt_sample_ggx_vndf(0.1f, wo, u1, u2);
            float wh = wo.x * hl.x + wo.y * hl.y + wo.z * hl.z;
            dirt_vec3 wi = {2 * wh * hl.x - wo.x, 2 * wh * hl.y - wo.y, 2 * wh * hl.z - wo.z};
            if (wi.z <= 0)
                wi = (dirt_vec3){-wi.x, -wi.y, -wi.z}; /* keep above the surface */
            d = to_world(wi, n);
            break;
        }
        default:
            d = to_world(dirt_sample_cosine(u1, u2), n);
            break;
        }
        out[i] = (dirt_ray){{o[0], o[1], o[2]}, 0.0f, {d.x, d.y, d.z}, tmax};
    }
    return g->count;
}
