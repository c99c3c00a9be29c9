/* Views of the image-space acceleration structure and tile-frustum math. */
#include "views/views.h"

#include <math.h>
#include <string.h>

#include "dirt/log.h"

static void mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; c++) {
        for (int row = 0; row < 4; row++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    }
    memcpy(out, r, sizeof(r));
}

static void perspective(float out[16], float cot_y, float aspect, float n, float f)
{
    memset(out, 0, 16 * sizeof(float));
    out[0] = cot_y / aspect;
    out[5] = cot_y;
    out[10] = (f + n) / (n - f);
    out[11] = -1.0f;
    out[14] = 2.0f * f * n / (n - f);
}

/* World -> eye for an eye at `eye` looking along `fwd` with `up`. */
static void look(float out[16], const float eye[3], const float fwd[3], const float up[3])
{
    float r[3] = {fwd[1] * up[2] - fwd[2] * up[1], fwd[2] * up[0] - fwd[0] * up[2],
                  fwd[0] * up[1] - fwd[1] * up[0]};
    float rl = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int i = 0; i < 3; i++)
        r[i] /= rl;
    float u[3] = {r[1] * fwd[2] - r[2] * fwd[1], r[2] * fwd[0] - r[0] * fwd[2],
                  r[0] * fwd[1] - r[1] * fwd[0]};
    memset(out, 0, 16 * sizeof(float));
    for (int i = 0; i < 3; i++) {
        out[i * 4 + 0] = r[i];
        out[i * 4 + 1] = u[i];
        out[i * 4 + 2] = -fwd[i];
    }
    out[12] = -(r[0] * eye[0] + r[1] * eye[1] + r[2] * eye[2]);
    out[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    out[14] = fwd[0] * eye[0] + fwd[1] * eye[1] + fwd[2] * eye[2];
    out[15] = 1.0f;
}

/* Largest depth of a bounds corner along `fwd` from `eye` (may be <= 0). */
static float max_corner_depth(const float eye[3], const float fwd[3], const float bmin[3],
                              const float bmax[3])
{
    float best = -INFINITY;
    for (int i = 0; i < 8; i++) {
        float c[3] = {(i & 1) ? bmax[0] : bmin[0], (i & 2) ? bmax[1] : bmin[1],
                      (i & 4) ? bmax[2] : bmin[2]};
        float d = (c[0] - eye[0]) * fwd[0] + (c[1] - eye[1]) * fwd[1] + (c[2] - eye[2]) * fwd[2];
        best = fmaxf(best, d);
    }
    return best;
}

static void finish_view(dirt_view *v, int width, int height, int S)
{
    mat4_mul(v->view_proj, v->proj, v->view);
    v->width = width;
    v->height = height;
    v->tiles_x = (width + S - 1) / S;
    v->tiles_y = (height + S - 1) / S;
    int m = v->tiles_x > v->tiles_y ? v->tiles_x : v->tiles_y;
    v->num_levels = 1;
    while ((1 << (v->num_levels - 1)) < m)
        v->num_levels++;
}

bool dirt_views_setup(dirt_view_set *out, const dirt_camera *cam, const float bmin[3],
                      const float bmax[3], const dirt_view_opts *opts_in, int max_atlas_width)
{
    dirt_view_opts o = opts_in ? *opts_in : (dirt_view_opts){0};
    if (o.width <= 0)
        o.width = 640;
    if (o.height <= 0)
        o.height = 480;
    if (o.face_size <= 0)
        o.face_size = (o.width > o.height ? o.width : o.height) / 2;
    if (o.face_size <= 0)
        o.face_size = 1;
    if (o.tile_size == 0)
        o.tile_size = 2;
    if (o.tile_size != 1 && o.tile_size != 2 && o.tile_size != 4 && o.tile_size != 8) {
        DIRT_ERROR("tile size %d: must be 1, 2, 4 or 8", o.tile_size);
        return false;
    }
    if (o.width > 16384 || o.height > 16384 || o.face_size > 16384) {
        DIRT_ERROR("view size %dx%d / face %d: at most 16384", o.width, o.height, o.face_size);
        return false;
    }
    memset(out, 0, sizeof(*out));
    out->tile_size = o.tile_size;
    out->camera_view = -1;
    const int S = o.tile_size;

    float diag = sqrtf((bmax[0] - bmin[0]) * (bmax[0] - bmin[0]) +
                       (bmax[1] - bmin[1]) * (bmax[1] - bmin[1]) +
                       (bmax[2] - bmin[2]) * (bmax[2] - bmin[2]));
    if (!(diag > 0) || !isfinite(diag))
        diag = 1.0f;

    if (o.mode == DIRT_VIEWS_SINGLE || o.mode == DIRT_VIEWS_CUBE_CAMERA) {
        if (cam->type != DIRT_CAMERA_PERSPECTIVE) {
            DIRT_ERROR("the camera view needs a perspective camera (use cube views)");
            return false;
        }
        dirt_view *v = &out->views[out->count];
        out->camera_view = out->count++;
        v->face = -1;
        memcpy(v->eye, cam->eye, sizeof(v->eye));
        memcpy(v->forward, cam->forward, sizeof(v->forward));
        memcpy(v->view, cam->view, sizeof(v->view));
        v->znear = cam->znear > 0 ? cam->znear : 1e-3f * diag;
        float far = max_corner_depth(cam->eye, cam->forward, bmin, bmax);
        v->zfar = fmaxf(far * 1.001f + 1e-4f * diag, v->znear * 1.01f);
        float yfov = cam->yfov > 0 ? cam->yfov : 0.785398163f;
        perspective(v->proj, 1.0f / tanf(0.5f * yfov), (float)o.width / (float)o.height,
                    v->znear, v->zfar);
        finish_view(v, o.width, o.height, S);
    }
    if (o.mode == DIRT_VIEWS_CUBE || o.mode == DIRT_VIEWS_CUBE_CAMERA) {
        static const float fwd[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        static const float up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                       {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        float n = 1e-2f * diag;
        for (int f = 0; f < 6; f++) {
            dirt_view *v = &out->views[out->count++];
            v->face = f;
            for (int i = 0; i < 3; i++) {
                v->eye[i] = cam->eye[i] - n * fwd[f][i];
                v->forward[i] = fwd[f][i];
            }
            look(v->view, v->eye, fwd[f], up[f]);
            v->znear = n;
            float far = max_corner_depth(v->eye, fwd[f], bmin, bmax);
            v->zfar = fmaxf(far * 1.001f + 1e-4f * diag, n * 1.01f);
            perspective(v->proj, 1.0f, 1.0f, v->znear, v->zfar);
            finish_view(v, o.face_size, o.face_size, S);
        }
    }
    /* Global tile numbering, raster atlas and pyramid layout. */
    for (int i = 0; i < out->count; i++) {
        dirt_view *v = &out->views[i];
        v->tile_base = out->num_tiles;
        v->atlas_x = out->atlas_width;
        out->num_tiles += v->tiles_x * v->tiles_y;
        out->atlas_width += v->tiles_x;
        if (v->tiles_y > out->atlas_height)
            out->atlas_height = v->tiles_y;
        if (v->num_levels > out->num_levels)
            out->num_levels = v->num_levels;
    }
    if (max_atlas_width > 0 && out->atlas_width > max_atlas_width) {
        DIRT_ERROR("the views need a %d tile wide raster, more than this GPU's %d; use "
                   "larger tiles or smaller views", out->atlas_width, max_atlas_width);
        return false;
    }
    int base = 0;
    for (int d = 0; d < out->num_levels; d++) {
        for (int i = 0; i < out->count; i++) {
            const dirt_view *v = &out->views[i];
            out->level_base[d][i] = base;
            int w = (v->tiles_x + (1 << d) - 1) >> d, h = (v->tiles_y + (1 << d) - 1) >> d;
            base += w * h;
        }
    }
    out->pyramid_size = base;
    return true;
}

void dirt_view_tile_ndc(const dirt_view *v, int S, int tx, int ty, double out[4])
{
    int x0 = tx * S, x1 = tx * S + S, y0 = ty * S, y1 = ty * S + S;
    if (x1 > v->width)
        x1 = v->width;
    if (y1 > v->height)
        y1 = v->height;
    out[0] = -1.0 + 2.0 * x0 / v->width;
    out[1] = -1.0 + 2.0 * x1 / v->width;
    out[2] = -1.0 + 2.0 * y0 / v->height;
    out[3] = -1.0 + 2.0 * y1 / v->height;
}

static void to_clip(const dirt_view *v, const float p[3], double c[4])
{
    const float *m = v->view_proj;
    for (int r = 0; r < 4; r++)
        c[r] = (double)m[r] * p[0] + (double)m[4 + r] * p[1] + (double)m[8 + r] * p[2] +
               (double)m[12 + r];
}

double dirt_view_depth(const dirt_view *v, const float p[3])
{
    double c[4];
    to_clip(v, p, c);
    return c[3];
}

/* Sutherland-Hodgman step: keeps the part of polygon `in` (n vertices) where
 * dot(plane, c) >= 0. Returns the new vertex count. */
static int clip_plane(double in[][4], int n, double out[][4], const double plane[4])
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = in[i], *b = in[(i + 1) % n];
        double da = plane[0] * a[0] + plane[1] * a[1] + plane[2] * a[2] + plane[3] * a[3];
        double db = plane[0] * b[0] + plane[1] * b[1] + plane[2] * b[2] + plane[3] * b[3];
        if (da >= 0) {
            memcpy(out[m++], a, 4 * sizeof(double));
        }
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            for (int k = 0; k < 4; k++)
                out[m][k] = a[k] + t * (b[k] - a[k]);
            m++;
        }
    }
    return m;
}

bool dirt_clip_triangle_tile(const dirt_view *v, int S, int tx, int ty, const float p[3][3],
                             double eps, double *zmin, double *zmax)
{
    return dirt_clip_triangle_tile_box(v, S, tx, ty, p, eps, zmin, zmax, NULL);
}

bool dirt_clip_triangle_tile_box(const dirt_view *v, int S, int tx, int ty,
                                 const float p[3][3], double eps, double *zmin, double *zmax,
                                 double box[4])
{
    double r[4];
    dirt_view_tile_ndc(v, S, tx, ty, r);
    double ex = eps * 2.0 * S / v->width, ey = eps * 2.0 * S / v->height, ez = eps * 1e-2;
    /* Plane coefficients on (x, y, z, w) of clip space. */
    const double planes[6][4] = {
        {1, 0, 0, -(r[0] - ex)}, {-1, 0, 0, r[1] + ex},
        {0, 1, 0, -(r[2] - ey)}, {0, -1, 0, r[3] + ey},
        {0, 0, 1, 1 + ez},       {0, 0, -1, 1 + ez},
    };
    double a[12][4], b[12][4];
    int n = 3;
    for (int i = 0; i < 3; i++)
        to_clip(v, p[i], a[i]);
    for (int k = 0; k < 6 && n > 0; k += 2) {
        n = clip_plane(a, n, b, planes[k]);
        n = clip_plane(b, n, a, planes[k + 1]);
    }
    if (n == 0)
        return false;
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < n; i++) {
        lo = fmin(lo, a[i][3]);
        hi = fmax(hi, a[i][3]);
    }
    *zmin = lo;
    *zmax = hi;
    if (box) {
        box[0] = box[2] = INFINITY;
        box[1] = box[3] = -INFINITY;
        for (int i = 0; i < n; i++) {
            double x = a[i][0] / a[i][3], y = a[i][1] / a[i][3];
            box[0] = fmin(box[0], x), box[1] = fmax(box[1], x);
            box[2] = fmin(box[2], y), box[3] = fmax(box[3], y);
        }
    }
    return true;
}

bool dirt_triangle_tile_rect(const dirt_view *v, int S, const float p[3][3], double margin,
                             int rect[4])
{
    double a[4][4], b[4][4];
    for (int i = 0; i < 3; i++)
        to_clip(v, p[i], a[i]);
    /* Keep w >= near / 2 so the projection is finite (points nearer than
     * the near plane cannot be inside any tile frustum). */
    const double plane[4] = {0, 0, 0, 1};
    double half_near[4];
    int n = 3;
    for (int i = 0; i < n; i++) {
        memcpy(half_near, a[i], sizeof(half_near));
        half_near[3] -= 0.5 * v->znear;
        memcpy(b[i], half_near, sizeof(half_near));
    }
    n = clip_plane(b, n, a, plane);
    if (n == 0)
        return false;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int i = 0; i < n; i++) {
        double w = a[i][3] + 0.5 * v->znear;
        double px = (a[i][0] / w * 0.5 + 0.5) * v->width;
        double py = (a[i][1] / w * 0.5 + 0.5) * v->height;
        x0 = fmin(x0, px), x1 = fmax(x1, px);
        y0 = fmin(y0, py), y1 = fmax(y1, py);
    }
    double m = margin * S;
    int tx0 = (int)floor((fmax(x0 - m, 0.0)) / S), tx1 = (int)floor(fmin(x1 + m, v->width - 1e-9) / S);
    int ty0 = (int)floor((fmax(y0 - m, 0.0)) / S), ty1 = (int)floor(fmin(y1 + m, v->height - 1e-9) / S);
    if (x1 + m < 0 || y1 + m < 0 || x0 - m > v->width || y0 - m > v->height)
        return false;
    if (tx1 >= v->tiles_x)
        tx1 = v->tiles_x - 1;
    if (ty1 >= v->tiles_y)
        ty1 = v->tiles_y - 1;
    if (tx0 > tx1 || ty0 > ty1)
        return false;
    rect[0] = tx0, rect[1] = tx1, rect[2] = ty0, rect[3] = ty1;
    return true;
}
