/* Raster preview of the default scene (llvmpipe): the emissive ceiling panel
 * is the brightest region of the image, the left wall shows red and the
 * right wall green, and the run raises no GL error. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "raster/raster.h"
#include "dirt/scene.h"
#include "gpu.h"

#define W 160
#define H 120

/* World point -> pixel (x right, y down); false when behind the camera. */
static bool project(const dirt_camera *cam, const float p[3], float *px, float *py)
{
    float proj[16], e[4], c[4];
    dirt_camera_projection(cam, (float)W / H, proj);
    for (int r = 0; r < 4; r++)
        e[r] = cam->view[0 * 4 + r] * p[0] + cam->view[1 * 4 + r] * p[1] +
               cam->view[2 * 4 + r] * p[2] + cam->view[3 * 4 + r];
    for (int r = 0; r < 4; r++)
        c[r] = proj[0 * 4 + r] * e[0] + proj[1 * 4 + r] * e[1] + proj[2 * 4 + r] * e[2] +
               proj[3 * 4 + r] * e[3];
    if (c[3] <= 0)
        return false;
    *px = (c[0] / c[3] * 0.5f + 0.5f) * W;
    *py = (1.0f - (c[1] / c[3] * 0.5f + 0.5f)) * H;
    return true;
}

static float lum(const float *p)
{
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

static const float *pixel_at(const float *img, const dirt_camera *cam, float x, float y,
                             float z)
{
    float px, py, p[3] = {x, y, z};
    if (!project(cam, p, &px, &py) || px < 0 || py < 0 || px >= W || py >= H)
        return NULL;
    return img + ((size_t)py * W + (size_t)px) * 4;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    CHECK(f && f->num_cameras >= 1);
    dirt_raster *r = dirt_raster_create(gpu, scene);
    CHECK(r != NULL);
    float *img = calloc((size_t)W * H * 4, sizeof(float));
    const dirt_camera *cam = &f->cameras[0];
    dirt_raster_stats st;
    CHECK(dirt_raster_render(r, f, cam, W, H, NULL, img, NULL, &st));
    CHECK(st.num_lights >= 1);

    /* Projected bounding box of the emissive triangles. */
    const dirt_material *mat = dirt_scene_materials(scene);
    float x0 = W, y0 = H, x1 = -1, y1 = -1;
    for (size_t t = 0; t < f->num_triangles; t++) {
        const dirt_material *m = &mat[f->material[t]];
        if (m->emissive[0] + m->emissive[1] + m->emissive[2] <= 0)
            continue;
        for (int v = 0; v < 3; v++) {
            float px, py;
            if (project(cam, f->position[3 * t + v], &px, &py)) {
                x0 = fminf(x0, px), y0 = fminf(y0, py);
                x1 = fmaxf(x1, px), y1 = fmaxf(y1, py);
            }
        }
    }
    CHECK_MSG(x1 > x0 && y1 > y0, "light projects to [%g,%g]x[%g,%g]", x0, x1, y0, y1);
    float in_max = 0, out_max = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            float l = lum(img + ((size_t)y * W + x) * 4);
            CHECK(isfinite(l));
            bool inside = x + 0.5f >= x0 && x + 0.5f <= x1 && y + 0.5f >= y0 && y + 0.5f <= y1;
            if (inside)
                in_max = fmaxf(in_max, l);
            else
                out_max = fmaxf(out_max, l);
        }
    }
    fprintf(stderr, "light region max luminance %.3f, elsewhere %.3f\n", in_max, out_max);
    CHECK(in_max > out_max);
    CHECK(in_max > 1.0f);

    /* Upper parts of the side walls, above every object in the room. */
    const float *left = pixel_at(img, cam, -0.999f, 1.8f, -0.5f);
    const float *right = pixel_at(img, cam, 0.999f, 1.8f, -0.5f);
    CHECK(left && right);
    if (left && right) {
        fprintf(stderr, "left wall %.3f %.3f %.3f, right wall %.3f %.3f %.3f\n", left[0],
                left[1], left[2], right[0], right[1], right[2]);
        CHECK(left[0] > 2 * left[1] && left[0] > 2 * left[2]);
        CHECK(right[1] > 2 * right[0] && right[1] > 2 * right[2]);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);

    free(img);
    dirt_raster_destroy(r);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
