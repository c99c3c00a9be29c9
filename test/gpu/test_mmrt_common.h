/* Shared by the MMRT tests: hand-made frames of axis-aligned quads, the
 * pixel-centre rays of a view and an exact (double) ray-triangle test: the
 * CPU oracle of what normal rasterization must store. */
#ifndef DIRT_TEST_MMRT_COMMON_H
#define DIRT_TEST_MMRT_COMMON_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mmrt/mmrt.h"
#include "dirt/scene.h"
#include "views/views.h"

/* A frame with room for `cap` triangles; num_triangles counts those added. */
static inline dirt_frame *mt_frame_new(size_t cap)
{
    dirt_frame *f = calloc(1, sizeof(*f));
    f->position = calloc(3 * cap, sizeof(*f->position));
    f->normal = calloc(3 * cap, sizeof(*f->normal));
    f->uv = calloc(3 * cap, sizeof(*f->uv));
    f->material = calloc(cap, sizeof(*f->material));
    f->instance = calloc(cap, sizeof(*f->instance));
    return f;
}

static inline void mt_frame_free(dirt_frame *f)
{
    if (!f)
        return;
    free(f->position);
    free(f->normal);
    free(f->uv);
    free(f->material);
    free(f->instance);
    free(f);
}

static inline void mt_frame_bounds(dirt_frame *f)
{
    for (int k = 0; k < 3; k++) {
        f->bounds_min[k] = INFINITY;
        f->bounds_max[k] = -INFINITY;
    }
    for (size_t i = 0; i < 3 * f->num_triangles; i++) {
        for (int k = 0; k < 3; k++) {
            f->bounds_min[k] = fminf(f->bounds_min[k], f->position[i][k]);
            f->bounds_max[k] = fmaxf(f->bounds_max[k], f->position[i][k]);
        }
    }
}

/* An axis-aligned quad: the plane x[axis] = at, spanning [a0, a1] on the
 * next axis and [b0, b1] on the one after (cyclic), normal along +/- axis.
 * Two triangles (c0 c1 c2), (c0 c2 c3): primitive ids 2q and 2q+1 when it is
 * the q-th quad added. Material = quad index; uv = the in-plane coordinates;
 * the shading normal is the face normal. */
typedef struct mt_quad {
    int axis;
    float at, a0, a1, b0, b1;
    float facing; /* +1 or -1: normal direction along the axis */
} mt_quad;

static inline void mt_add_quad(dirt_frame *f, const mt_quad *q)
{
    int ia = (q->axis + 1) % 3, ib = (q->axis + 2) % 3;
    float c[4][3];
    const float ab[4][2] = {{q->a0, q->b0}, {q->a1, q->b0}, {q->a1, q->b1}, {q->a0, q->b1}};
    for (int i = 0; i < 4; i++) {
        c[i][q->axis] = q->at;
        c[i][ia] = ab[i][0];
        c[i][ib] = ab[i][1];
    }
    static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; t++) {
        size_t p = f->num_triangles++;
        f->material[p] = (uint32_t)(p / 2);
        for (int v = 0; v < 3; v++) {
            int k = tri[t][v];
            memcpy(f->position[3 * p + v], c[k], sizeof(c[k]));
            float n[3] = {0, 0, 0};
            n[q->axis] = q->facing;
            memcpy(f->normal[3 * p + v], n, sizeof(n));
            f->uv[3 * p + v][0] = ab[k][0];
            f->uv[3 * p + v][1] = ab[k][1];
        }
    }
}

/* World-space ray through the centre of pixel (x, y) of view v: org = the
 * view's centre of projection; dir scaled so that the parameter along it is
 * the eye-space depth. */
static inline void mt_pixel_ray(const dirt_view *v, int x, int y, double org[3], double dir[3])
{
    double xn = (x + 0.5) / v->width * 2.0 - 1.0, yn = (y + 0.5) / v->height * 2.0 - 1.0;
    double e[3] = {xn / v->proj[0], yn / v->proj[5], -1.0};
    for (int i = 0; i < 3; i++) {
        org[i] = v->eye[i];
        dir[i] = v->view[i * 4 + 0] * e[0] + v->view[i * 4 + 1] * e[1] +
                 v->view[i * 4 + 2] * e[2];
    }
}

/* Ray o + t d against triangle p (no culling): t and the barycentrics (u, v)
 * of vertices 1 and 2 of the intersection with the triangle's plane. False
 * when the ray is parallel to the plane. The point is inside the triangle
 * when u, v, 1 - u - v >= 0. */
static inline bool mt_ray_plane(const double o[3], const double d[3], const float p[3][3], double *t,
                         double *u, double *v)
{
    double e1[3], e2[3], s[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p[1][k] - p[0][k];
        e2[k] = (double)p[2][k] - p[0][k];
        s[k] = o[k] - p[0][k];
    }
    double h[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                   d[0] * e2[1] - d[1] * e2[0]};
    double a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(a) < 1e-300)
        return false;
    double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                   s[0] * e1[1] - s[1] * e1[0]};
    *u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / a;
    *v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / a;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / a;
    return isfinite(*t);
}

/* Vertices of primitive `prim` of frame f. */
static inline void mt_tri(const dirt_frame *f, size_t prim, float p[3][3])
{
    memcpy(p, f->position[3 * prim], 9 * sizeof(float));
}

/* Clip-space coordinates of world point p in view v (double). */
static inline void mt_clip(const dirt_view *v, const double p[3], double c[4])
{
    const float *m = v->view_proj;
    for (int r = 0; r < 4; r++)
        c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* How triangle p covers the centre of pixel (x, y) of view v under normal
 * rasterization: 1 covered, 0 not, -1 ambiguous: the centre is within `tol`
 * pixels of the projection of an edge's part in front of the view (vertex
 * snapping and the tie rule decide there), or the sample is at the near or
 * far plane. *depth gets the eye-space depth of the sample. */
static inline int mt_coverage(const dirt_view *v, const float p[3][3], int x, int y, double tol,
                              double *depth)
{
    double o[3], d[3], t, u, w;
    mt_pixel_ray(v, x, y, o, d);
    if (!mt_ray_plane(o, d, p, &t, &u, &w))
        return 0; /* edge-on: rasterizes to nothing */
    *depth = t;
    int inside = u >= 0 && w >= 0 && u + w <= 1;
    double dz = 1e-6 * t;
    if (fabs(t - v->znear) < dz + 1e-9 || fabs(t - v->zfar) < dz)
        return inside ? -1 : 0;
    bool in_depth = t >= v->znear && t <= v->zfar;
    double c[3][4];
    for (int i = 0; i < 3; i++) {
        double q[3] = {p[i][0], p[i][1], p[i][2]};
        mt_clip(v, q, c[i]);
    }
    /* Distance (pixels) of the pixel centre to each edge's projected part
     * with w >= near / 2. */
    double px = x + 0.5, py = y + 0.5, wmin = 0.5 * v->znear;
    for (int i = 0; i < 3; i++) {
        double a[4], b[4];
        memcpy(a, c[i], sizeof(a));
        memcpy(b, c[(i + 1) % 3], sizeof(b));
        if (a[3] < wmin && b[3] < wmin)
            continue;
        if (a[3] < wmin || b[3] < wmin) {
            double *lo = a[3] < wmin ? a : b, *hi = a[3] < wmin ? b : a;
            double s = (wmin - lo[3]) / (hi[3] - lo[3]);
            for (int k = 0; k < 4; k++)
                lo[k] += s * (hi[k] - lo[k]);
        }
        double ax = (a[0] / a[3] * 0.5 + 0.5) * v->width, ay = (a[1] / a[3] * 0.5 + 0.5) * v->height;
        double bx = (b[0] / b[3] * 0.5 + 0.5) * v->width, by = (b[1] / b[3] * 0.5 + 0.5) * v->height;
        double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
        double s = l2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / l2 : 0;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
        double dx = ax + s * ex - px, dy = ay + s * ey - py;
        if (dx * dx + dy * dy < tol * tol)
            return -1;
    }
    return inside && in_depth;
}

/* Name of a view mode. */
static inline const char *mt_mode_name(enum dirt_view_mode m)
{
    return m == DIRT_VIEWS_SINGLE ? "single" : m == DIRT_VIEWS_CUBE ? "cube" : "cube+camera";
}

/* The view and pixel (x, y) of global pixel g. */
static inline int mt_view_of(const dirt_view_set *set, uint32_t g, int *x, int *y)
{
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        int n = v->width * v->height;
        if ((int)g >= v->tile_base && (int)g < v->tile_base + n) {
            int l = (int)g - v->tile_base;
            *x = l % v->width;
            *y = l / v->width;
            return i;
        }
    }
    return -1;
}

#endif
