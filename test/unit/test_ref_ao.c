/* Ambient occlusion mode of the reference renderer (src/ref/render.c).
 *  - an open plane: every AO ray escapes, AO is exactly 1 in every pixel;
 *  - inside a closed box with a max distance longer than the box diagonal:
 *    every AO ray is blocked, AO is exactly 0;
 *  - between two parallel planes a distance h apart with max distance R > h:
 *    a cosine ray at angle theta is blocked iff h / cos theta <= R, so
 *    AO = P(cos theta < h / R) = (h / R)^2. Checked within 5 binomial
 *    standard errors of the image mean (stated in the log);
 *  - the result does not depend on the thread count (bit-identical), and the
 *    progress callback reports increasing counts ending at the total. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ref/ref.h"

typedef struct mesh {
    dirt_frame f;
    float pos[64][3];
    uint32_t mat[24];
} mesh;

static void quad(mesh *m, const float a[3], const float b[3], const float c[3], const float d[3])
{
    size_t n = m->f.num_triangles;
    const float *v[6] = {a, b, c, a, c, d};
    for (int i = 0; i < 6; i++)
        memcpy(m->pos[3 * n + (size_t)i], v[i], sizeof(float[3]));
    m->mat[n] = m->mat[n + 1] = 0;
    m->f.num_triangles = n + 2;
    m->f.position = m->pos;
    m->f.material = m->mat;
    m->f.normal = NULL; /* flat shading from the geometric normal */
}

static void plane_y(mesh *m, float y, float half, bool up)
{
    float a[3] = {-half, y, -half}, b[3] = {-half, y, half}, c[3] = {half, y, half},
          d[3] = {half, y, -half};
    if (up)
        quad(m, a, b, c, d);
    else
        quad(m, a, d, c, b);
}

static dirt_material grey(void)
{
    dirt_material m;
    dirt_material_default(&m);
    m.base_color[0] = m.base_color[1] = m.base_color[2] = m.base_color[3] = 0.8f;
    m.metallic = 0.0f;
    return m;
}

static void camera(dirt_camera *c, float ex, float ey, float ez, float tx, float ty, float tz)
{
    float eye[3] = {ex, ey, ez}, target[3] = {tx, ty, tz}, up[3] = {0, 1, 0};
    memset(c, 0, sizeof(*c));
    dirt_camera_look_at(c, eye, target, up);
    c->type = DIRT_CAMERA_PERSPECTIVE;
    c->yfov = 1.0f;
}

typedef struct progress {
    uint64_t last, total, calls;
    bool monotonic;
} progress;

static void on_progress(void *user, uint64_t done, uint64_t total)
{
    progress *p = user;
    if (done <= p->last || done > total)
        p->monotonic = false;
    p->last = done;
    p->total = total;
    p->calls++;
}

static dirt_image *render_ao(const mesh *m, const dirt_camera *c, float dist, int spp, int threads,
                             progress *prog)
{
    dirt_material mat = grey();
    dirt_ref_materials mats = {&mat, 1, NULL, 0, NULL};
    dirt_ref_opts o = {0};
    o.width = 32;
    o.height = 32;
    o.spp = spp;
    o.mode = DIRT_REF_MODE_AO;
    o.ao_distance = dist;
    o.threads = threads;
    o.seed = 3u;
    if (prog) {
        o.progress = on_progress;
        o.progress_user = prog;
    }
    return dirt_ref_render_materials(&mats, &m->f, c, &o, NULL);
}

/* Counts pixels whose RGB is not exactly v. */
static int count_not(const dirt_image *img, float v)
{
    int bad = 0;
    for (int i = 0; i < img->width * img->height; i++)
        bad += img->rgba[4 * i] != v || img->rgba[4 * i + 1] != v || img->rgba[4 * i + 2] != v;
    return bad;
}

int main(void)
{
    dirt_camera c;

    /* Open plane, seen from above at an angle (some pixels see the sky). */
    mesh plane;
    memset(&plane, 0, sizeof(plane));
    plane_y(&plane, 0.0f, 10.0f, true);
    camera(&c, 0.0f, 2.0f, 6.0f, 0.0f, 0.0f, 0.0f);
    dirt_image *img = render_ao(&plane, &c, 0.0f, 16, 0, NULL);
    CHECK(img != NULL);
    if (img) {
        int bad = count_not(img, 1.0f);
        CHECK_MSG(bad == 0, "open plane: %d pixels with AO != 1", bad);
    }
    dirt_image_destroy(img);

    /* Closed box [-1,1]^3 (diagonal 3.46), AO distance 5, camera inside. */
    mesh box;
    memset(&box, 0, sizeof(box));
    {
        float p[8][3];
        for (int i = 0; i < 8; i++) {
            p[i][0] = (i & 1) ? 1.0f : -1.0f;
            p[i][1] = (i & 2) ? 1.0f : -1.0f;
            p[i][2] = (i & 4) ? 1.0f : -1.0f;
        }
        static const int q[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                    {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
        for (int f = 0; f < 6; f++)
            quad(&box, p[q[f][0]], p[q[f][1]], p[q[f][2]], p[q[f][3]]);
    }
    camera(&c, 0.3f, 0.2f, 0.5f, -1.0f, -0.5f, -1.0f);
    img = render_ao(&box, &c, 5.0f, 16, 0, NULL);
    CHECK(img != NULL);
    if (img) {
        int bad = count_not(img, 0.0f);
        CHECK_MSG(bad == 0, "closed box: %d pixels with AO != 0", bad);
    }
    dirt_image_destroy(img);
    /* The same box with AO distance 0 (= infinite): still fully occluded. */
    img = render_ao(&box, &c, 0.0f, 4, 0, NULL);
    CHECK(img && count_not(img, 0.0f) == 0);
    dirt_image_destroy(img);

    /* Two planes h = 1 apart, R = 2: AO = 0.25. Camera between them looking
     * down at the floor; the floor's facing side is up, the ceiling's down. */
    mesh slab;
    memset(&slab, 0, sizeof(slab));
    plane_y(&slab, 0.0f, 1000.0f, true);
    plane_y(&slab, 1.0f, 1000.0f, false);
    camera(&c, 0.0f, 0.9f, 0.0f, 0.0f, 0.0f, -0.3f);
    progress prog = {0, 0, 0, true};
    img = render_ao(&slab, &c, 2.0f, 64, 0, &prog);
    CHECK(img != NULL);
    if (img) {
        double s = 0.0;
        int n = img->width * img->height;
        for (int i = 0; i < n; i++)
            s += img->rgba[4 * i];
        double mean = s / n, p = 0.25, se = sqrt(p * (1 - p) / (n * 64.0));
        fprintf(stderr, "slab AO %.5f expected %.5f, s.e. %.5f (%.1f s.e.)\n", mean, p, se,
                (mean - p) / se);
        CHECK_NEAR(mean, p, 5.0 * se);
        /* Thread count does not change a single bit. */
        dirt_image *one = render_ao(&slab, &c, 2.0f, 64, 1, NULL);
        dirt_image *three = render_ao(&slab, &c, 2.0f, 64, 3, NULL);
        CHECK(one && three);
        if (one && three) {
            CHECK(memcmp(one->rgba, img->rgba, (size_t)n * 4 * sizeof(float)) == 0);
            CHECK(memcmp(three->rgba, img->rgba, (size_t)n * 4 * sizeof(float)) == 0);
        }
        dirt_image_destroy(one);
        dirt_image_destroy(three);
    }
    dirt_image_destroy(img);
    CHECK(prog.monotonic);
    CHECK(prog.calls == 4); /* one per 16x16 tile */
    CHECK(prog.total == 32u * 32u * 64u && prog.last == prog.total);

    /* Invalid options are refused. */
    dirt_material mat = grey();
    dirt_ref_materials mats = {&mat, 1, NULL, 0, NULL};
    dirt_ref_opts bad = {0};
    bad.spp = -1;
    CHECK(dirt_ref_render_materials(&mats, &slab.f, &c, &bad, NULL) == NULL);
    bad.spp = 1;
    bad.ao_distance = -1.0f;
    CHECK(dirt_ref_render_materials(&mats, &slab.f, &c, &bad, NULL) == NULL);
    dirt_ref_materials none = {&mat, 0, NULL, 0, NULL}; /* material 0 out of range */
    dirt_ref_opts ok = {0};
    ok.width = ok.height = 4;
    CHECK(dirt_ref_render_materials(&none, &slab.f, &c, &ok, NULL) == NULL);
    return check_finish();
}
