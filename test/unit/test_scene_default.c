/* The built-in default scene: a closed Cornell-style room with one emissive
 * ceiling panel, red left / green right walls, a camera inside looking at
 * the back wall, consistent winding and a modest triangle count. */
#include "check.h"

#include "dirt/scene.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

static void sub3(double o[3], const float a[3], const float b[3])
{
    o[0] = (double)a[0] - b[0];
    o[1] = (double)a[1] - b[1];
    o[2] = (double)a[2] - b[2];
}

static void cross3(double o[3], const double a[3], const double b[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Moller-Trumbore, both sides, with a tiny tolerance on the barycentric
 * range so that rays through shared edges count as hits. Returns t or -1. */
static double ray_triangle(const double o[3], const double d[3], const float *p0,
                           const float *p1, const float *p2)
{
    double e1[3], e2[3], s[3], pv[3], qv[3];
    sub3(e1, p1, p0);
    sub3(e2, p2, p0);
    cross3(pv, d, e2);
    double det = dot3(e1, pv);
    if (fabs(det) < 1e-14)
        return -1.0;
    double inv = 1.0 / det;
    double p0d[3] = {p0[0], p0[1], p0[2]};
    s[0] = o[0] - p0d[0];
    s[1] = o[1] - p0d[1];
    s[2] = o[2] - p0d[2];
    double u = dot3(s, pv) * inv;
    if (u < -1e-9 || u > 1.0 + 1e-9)
        return -1.0;
    cross3(qv, s, e1);
    double v = dot3(d, qv) * inv;
    if (v < -1e-9 || u + v > 1.0 + 1e-9)
        return -1.0;
    double t = dot3(e2, qv) * inv;
    return t > 1e-9 ? t : -1.0;
}

/* Closest hit along the ray, or SIZE_MAX. */
static size_t closest_hit(const dirt_frame *f, const double o[3], const double d[3],
                          double *t_out)
{
    size_t best = SIZE_MAX;
    double bt = INFINITY;
    for (size_t t = 0; t < f->num_triangles; t++) {
        double h = ray_triangle(o, d, f->position[3 * t], f->position[3 * t + 1],
                                f->position[3 * t + 2]);
        if (h > 0.0 && h < bt) {
            bt = h;
            best = t;
        }
    }
    *t_out = bt;
    return best;
}

/* Deterministic uniform directions on the sphere. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

int main(void)
{
    dirt_scene *s = dirt_scene_create_default();
    CHECK(s != NULL);
    if (!s)
        return check_finish();
    CHECK(strcmp(dirt_scene_name(s), "default") == 0);
    size_t ntri = dirt_scene_num_triangles(s);
    fprintf(stderr, "default scene: %zu triangles, %zu materials\n", ntri,
            dirt_scene_num_materials(s));
    CHECK(ntri >= 100 && ntri <= 5000);
    CHECK(dirt_scene_num_clips(s) == 0);
    CHECK(dirt_scene_num_textures(s) == 0);

    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f != NULL);
    if (!f) {
        dirt_scene_destroy(s);
        return check_finish();
    }

    /* Bounds: the room spans x,z in [-1,1], y in [0,2]. */
    CHECK_NEAR(f->bounds_min[0], -1.0, 1e-6);
    CHECK_NEAR(f->bounds_max[0], 1.0, 1e-6);
    CHECK_NEAR(f->bounds_min[1], 0.0, 1e-6);
    CHECK_NEAR(f->bounds_max[1], 2.0, 1e-6);
    CHECK_NEAR(f->bounds_min[2], -1.0, 1e-6);
    CHECK_NEAR(f->bounds_max[2], 1.0, 1e-6);

    /* Exactly one emissive material, bright (emissive * strength > 1), and all
     * of its triangles lie near the ceiling, facing down. */
    const dirt_material *m = dirt_scene_materials(s);
    size_t nmat = dirt_scene_num_materials(s), emissive = 0, light = SIZE_MAX;
    float light_centre[3] = {0, 0, 0};
    for (size_t i = 0; i < nmat; i++) {
        if (m[i].emissive[0] > 0 || m[i].emissive[1] > 0 || m[i].emissive[2] > 0) {
            emissive++;
            light = i;
        }
    }
    CHECK(emissive == 1);
    if (light != SIZE_MAX) {
        CHECK(m[light].emissive[0] * m[light].emissive_strength > 10.0f);
        CHECK(m[light].emissive[0] >= m[light].emissive[1] &&
              m[light].emissive[1] >= m[light].emissive[2]); /* warm */
        size_t lt = 0, near_ceiling = 0;
        for (size_t t = 0; t < f->num_triangles; t++) {
            if (f->material[t] != light)
                continue;
            lt++;
            for (int k = 0; k < 3; k++) {
                for (int c = 0; c < 3; c++)
                    light_centre[c] += f->position[3 * t + k][c];
            }
            bool ok = f->normal[3 * t][1] < -0.99f;
            for (int k = 0; k < 3; k++)
                ok &= f->position[3 * t + k][1] > 1.9f && f->position[3 * t + k][1] < 2.0f;
            near_ceiling += ok;
        }
        CHECK(lt >= 2);
        CHECK(near_ceiling == lt);
        for (int c = 0; c < 3 && lt; c++)
            light_centre[c] /= (float)(3 * lt);
    }

    /* Red left wall at x = -1 facing +x, green right wall at x = +1 facing -x. */
    size_t red = 0, green = 0, metal = 0, glossy = 0;
    for (size_t t = 0; t < f->num_triangles; t++) {
        const dirt_material *mt = &m[f->material[t]];
        const float *p = f->position[3 * t], *n = f->normal[3 * t];
        if (mt->base_color[0] > 0.5f && mt->base_color[1] < 0.2f && mt->base_color[2] < 0.2f)
            red += fabsf(p[0] + 1.0f) < 1e-6f && n[0] > 0.99f;
        if (mt->base_color[1] > 0.3f && mt->base_color[0] < 0.3f && mt->base_color[2] < 0.3f)
            green += fabsf(p[0] - 1.0f) < 1e-6f && n[0] < -0.99f;
        metal += mt->metallic == 1.0f && mt->roughness < 0.1f;
        glossy += mt->metallic == 0.0f && mt->roughness > 0.1f && mt->roughness < 0.5f;
    }
    CHECK(red >= 2);
    CHECK(green >= 2);
    CHECK(metal > 0);
    CHECK(glossy > 0);

    /* Unit normals, and the stored winding agrees with the shading normal
     * (counter-clockwise seen from the front) for every triangle. */
    size_t bad_unit = 0, bad_wind = 0;
    for (size_t t = 0; t < f->num_triangles; t++) {
        double e1[3], e2[3], g[3];
        sub3(e1, f->position[3 * t + 1], f->position[3 * t]);
        sub3(e2, f->position[3 * t + 2], f->position[3 * t]);
        cross3(g, e1, e2);
        double nsum[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) {
            const float *n = f->normal[3 * t + k];
            double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            bad_unit += fabs(l - 1.0) > 1e-4;
            nsum[0] += n[0];
            nsum[1] += n[1];
            nsum[2] += n[2];
        }
        bad_wind += dot3(g, nsum) <= 0.0;
    }
    CHECK(bad_unit == 0);
    CHECK_MSG(bad_wind == 0, "%zu triangles wound against their normals", bad_wind);

    /* One camera, inside the room, near the front wall, looking at the back
     * wall (forward ~ -z), a field of view of about 60-70 degrees. */
    CHECK(dirt_scene_num_cameras(s) == 1);
    CHECK(f->num_cameras == 1);
    if (f->num_cameras == 1) {
        const dirt_camera *c = &f->cameras[0];
        CHECK(c->eye[0] > -1 && c->eye[0] < 1 && c->eye[1] > 0 && c->eye[1] < 2 &&
              c->eye[2] > 0.5f && c->eye[2] < 1);
        CHECK(c->forward[2] < -0.99f);
        CHECK(c->up[1] > 0.99f);
        CHECK(c->yfov >= 55.0 * 3.14159265358979 / 180.0 &&
              c->yfov <= 75.0 * 3.14159265358979 / 180.0);
        CHECK(c->znear > 0.0f && c->znear <= 0.05f);

        /* The back wall's corners are inside the view frustum (square image)... */
        float proj[16];
        dirt_camera_projection(c, 1.0f, proj);
        /* ... and so is the centre of the ceiling light (last point). */
        const float corners[5][3] = {{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1},
                                     {light_centre[0], light_centre[1], light_centre[2]}};
        CHECK(light != SIZE_MAX);
        for (int k = 0; k < 5; k++) {
            const float *v = c->view, *p = corners[k];
            float e[4];
            for (int r = 0; r < 4; r++)
                e[r] = v[r] * p[0] + v[4 + r] * p[1] + v[8 + r] * p[2] + v[12 + r];
            float clip[4];
            for (int r = 0; r < 4; r++)
                clip[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2] +
                          proj[12 + r] * e[3];
            CHECK(clip[3] > 0.0f);
            CHECK(fabsf(clip[0] / clip[3]) <= 1.0f && fabsf(clip[1] / clip[3]) <= 1.0f);
        }

        /* Closed room: 1000 random rays from the camera all hit something,
         * and the hits stay inside the room. */
        double o[3] = {c->eye[0], c->eye[1], c->eye[2]};
        size_t misses = 0, outside = 0;
        for (int i = 0; i < 1000; i++) {
            double z = 2.0 * rnd() - 1.0, a = 2.0 * 3.14159265358979 * rnd();
            double r = sqrt(1.0 - z * z);
            double d[3] = {r * cos(a), r * sin(a), z};
            double t;
            if (closest_hit(f, o, d, &t) == SIZE_MAX) {
                misses++;
                continue;
            }
            double h[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
            outside += fabs(h[0]) > 1.0 + 1e-5 || h[1] < -1e-5 || h[1] > 2.0 + 1e-5 ||
                       fabs(h[2]) > 1.0 + 1e-5;
        }
        CHECK_MSG(misses == 0, "%zu of 1000 rays escaped the room", misses);
        CHECK(outside == 0);

        /* Looking straight ahead the camera sees the back wall or an object
         * in front of it, not empty space; straight up it sees the ceiling
         * (or the light). */
        double t;
        double ahead[3] = {c->forward[0], c->forward[1], c->forward[2]};
        CHECK(closest_hit(f, o, ahead, &t) != SIZE_MAX && t <= 2.0);
        double upd[3] = {0, 1, 0};
        CHECK(closest_hit(f, o, upd, &t) != SIZE_MAX && fabs(o[1] + t - 2.0) < 0.03);
    }

    /* dirt_camera_auto frames the bounds from +z. */
    dirt_camera ac;
    dirt_camera_auto(f, &ac);
    CHECK(ac.eye[2] > 1.0f);
    CHECK(ac.forward[2] < 0.0f);
    CHECK(ac.znear > 0.0f && ac.zfar > ac.znear);

    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
    dirt_scene_destroy(NULL);
    dirt_frame_destroy(NULL);
    return check_finish();
}
