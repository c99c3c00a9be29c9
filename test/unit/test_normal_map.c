/* Normal maps and texture transforms of the light-transport model
 * (src/integrator/texture.c, doc/light-transport.md sections 1 and 2)
 * against hand-computed values:
 * - dirt_tex_transform_matrix / _apply: the identity (exact, also for
 *   non-finite uvs, which read as 0), the two examples of the
 *   KHR_texture_transform spec (offset (0, 1), rotation pi/2, scale 0.5
 *   "utilizes only the lower left quadrant of the source image, rotated
 *   clockwise 90 degrees"; offset (0, 1), scale (1, -1) "inverts the T
 *   axis"), and T R S of one general transform computed in double.
 * - dirt_material_surface reads every slot at its own transformed uv.
 * - dirt_material_normal_ts: (2 c - 1) (s, s, 1) normalised, for decoded
 *   texels c of 1 x 1 maps, with the normal slot's transform; none without
 *   a map.
 * - dirt_normal_map_apply: the tangent frame (t, cross(n, t) w, n) for both
 *   handednesses, a tangent not orthogonal to n (orthogonalised), degenerate
 *   tangents (n itself), and a tilted frame against its explicit
 *   construction. */
#include "check.h"

#include "core/vec3.h"
#include "integrator/integrator.h"
#include "dirt/scene.h"

#include <math.h>
#include <string.h>

static bool near(double a, double b, double tol) { return fabs(a - b) <= tol; }

static bool near3(dirt_vec3 a, double x, double y, double z, double tol)
{
    return near(a.x, x, tol) && near(a.y, y, tol) && near(a.z, z, tol);
}

static void apply(const dirt_tex_transform *xf, float u, float v, float out[2])
{
    float m[6];
    dirt_tex_transform_matrix(xf, m);
    dirt_tex_transform_apply(m, u, v, out);
}

static void test_transforms(void)
{
    float m[6], o[2];
    /* Identity: no transform, or one not set. */
    dirt_tex_transform none = {.set = false, .offset = {5, 5}, .rotation = 1, .scale = {3, 3}};
    dirt_tex_transform_matrix(&none, m);
    CHECK(m[0] == 1.0f && m[1] == 0.0f && m[2] == 0.0f && m[3] == 0.0f && m[4] == 1.0f &&
          m[5] == 0.0f);
    dirt_tex_transform_matrix(NULL, m);
    const float us[] = {0.3f, -2.75f, 1e-30f, 123456.7f, 1.0f};
    for (int i = 0; i < 5; i++) {
        dirt_tex_transform_apply(m, us[i], us[4 - i], o);
        CHECK(o[0] == us[i] && o[1] == us[4 - i]);
    }
    dirt_tex_transform_apply(m, NAN, INFINITY, o);
    CHECK(o[0] == 0.0f && o[1] == 0.0f);
    dirt_tex_transform_apply(m, 0.25f, -INFINITY, o);
    CHECK(o[0] == 0.25f && o[1] == 0.0f);

    /* The spec's first example: the unit square onto the lower-left
     * quadrant (u in [0, 0.5], v in [0.5, 1]; v runs down the image),
     * turned: (0, 0) -> (0, 1), (1, 0) -> (0, 0.5), (0, 1) -> (0.5, 1),
     * (1, 1) -> (0.5, 0.5). */
    dirt_tex_transform ex = {.set = true, .offset = {0, 1}, .rotation = 1.57079632679f,
                             .scale = {0.5f, 0.5f}};
    const float corners[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const float expect[4][2] = {{0, 1}, {0, 0.5f}, {0.5f, 1}, {0.5f, 0.5f}};
    for (int i = 0; i < 4; i++) {
        apply(&ex, corners[i][0], corners[i][1], o);
        CHECK_MSG(near(o[0], expect[i][0], 1e-6) && near(o[1], expect[i][1], 1e-6),
                  "spec example corner %d: (%g, %g), expected (%g, %g)", i, o[0], o[1],
                  expect[i][0], expect[i][1]);
    }
    /* The rotation's sign: a small positive rotation moves (1, 0) towards
     * -v (up the image: counter-clockwise as the uvs are drawn). */
    dirt_tex_transform small = {.set = true, .rotation = 0.1f, .scale = {1, 1}};
    apply(&small, 1.0f, 0.0f, o);
    CHECK(near(o[0], cos(0.1), 1e-7) && near(o[1], -sin(0.1), 1e-7));
    /* The spec's second example: v -> 1 - v. */
    dirt_tex_transform flip = {.set = true, .offset = {0, 1}, .scale = {1, -1}};
    apply(&flip, 0.3f, 0.2f, o);
    CHECK(o[0] == 0.3f && near(o[1], 0.8, 1e-7));
    /* T R S of a general transform, in double. */
    dirt_tex_transform g = {.set = true, .offset = {0.25f, -0.5f}, .rotation = 0.3f,
                            .scale = {2.0f, 3.0f}};
    double c = cos(0.3), s = sin(0.3), u = 0.4, v = 0.7;
    double su = 2.0 * u, sv = 3.0 * v;                     /* S */
    double ru = c * su + s * sv, rv = -s * su + c * sv;    /* R */
    apply(&g, 0.4f, 0.7f, o);
    CHECK_MSG(near(o[0], ru + 0.25, 1e-6) && near(o[1], rv - 0.5, 1e-6),
              "general transform: (%.9g, %.9g), expected (%.9g, %.9g)", o[0], o[1], ru + 0.25,
              rv - 0.5);
    dirt_tex_transform_matrix(&g, m);
    CHECK(m[0] == 2.0f * cosf(0.3f) && m[1] == 3.0f * sinf(0.3f) && m[2] == 0.25f &&
          m[3] == -(2.0f * sinf(0.3f)) && m[4] == 3.0f * cosf(0.3f) && m[5] == -0.5f);
}

/* A w x 1 texture of the given RGBA texels. */
static dirt_texture texture(int w, const uint8_t *rgba, uint8_t *store)
{
    memcpy(store, rgba, (size_t)w * 4);
    dirt_texture t = {.width = w, .height = 1, .rgba = store};
    return t;
}

static void test_material_slots(void)
{
    /* Texture 0: 4 x 1 linear values 0, 85, 170, 255 in R and G. */
    uint8_t px[16] = {0, 0, 0, 255, 85, 85, 85, 255, 170, 170, 170, 255, 255, 255, 255, 255};
    uint8_t store[16];
    dirt_texture tex[1] = {texture(4, px, store)};
    dirt_material m;
    dirt_material_default(&m);
    m.metallic_roughness_tex = 0;
    m.base_color_tex = 0;
    m.roughness = 1.0f;
    /* uv (0.125, 0.5) is texel 0's centre; the mr slot shifted by half the
     * texture reads texel 2 there, the base slot scaled by 3 texel 1 (u
     * 0.375). */
    m.xf[DIRT_SLOT_METALLIC_ROUGHNESS] = (dirt_tex_transform){.set = true, .offset = {0.5f, 0},
                                                              .scale = {1, 1}};
    m.xf[DIRT_SLOT_BASE_COLOR] = (dirt_tex_transform){.set = true, .scale = {3, 1}};
    dirt_surface s;
    dirt_material_surface(&m, 1.0f, tex, 1, 0.125f, 0.5f, &s);
    float r = 170.0f / 255.0f;
    CHECK_MSG(near(s.bsdf.alpha, r * r, 1e-6), "mr slot: alpha %g, expected %g", s.bsdf.alpha,
              r * r);
    CHECK_MSG(near(s.bsdf.base_color.x, dirt_srgb_to_linear(85.0f / 255.0f), 1e-6),
              "base slot: %g", s.bsdf.base_color.x);
    /* The transform of one slot does not move another. */
    m.xf[DIRT_SLOT_BASE_COLOR].set = false;
    dirt_material_surface(&m, 1.0f, tex, 1, 0.125f, 0.5f, &s);
    CHECK(s.bsdf.base_color.x == 0.0f);
    /* The extension slots too: transmission (R) shifted by a quarter reads
     * texel 1 at texel 0's centre, specular (A: 255 everywhere) stays 1. */
    m.transmission = 1.0f;
    m.transmission_tex = 0;
    m.specular_tex = 0;
    dirt_material_surface(&m, 1.0f, tex, 1, 0.125f, 0.5f, &s);
    CHECK(s.bsdf.transmission == 0.0f);
    m.xf[DIRT_SLOT_TRANSMISSION] = (dirt_tex_transform){.set = true, .offset = {0.25f, 0},
                                                        .scale = {1, 1}};
    dirt_material_surface(&m, 1.0f, tex, 1, 0.125f, 0.5f, &s);
    CHECK_MSG(near(s.bsdf.transmission, 85.0f / 255.0f, 1e-6), "transmission slot: %g",
              s.bsdf.transmission);
    CHECK(s.bsdf.specular == 1.0f);
}

static void test_normal_ts(void)
{
    uint8_t px[8] = {128, 128, 255, 255, 255, 64, 200, 255}, store[8];
    dirt_texture tex[1] = {texture(2, px, store)};
    dirt_material m;
    dirt_material_default(&m);
    dirt_vec3 n;
    CHECK(!dirt_material_normal_ts(&m, tex, 1, 0.25f, 0.5f, &n)); /* no map */
    m.normal_tex = 1;
    CHECK(!dirt_material_normal_ts(&m, tex, 1, 0.25f, 0.5f, &n)); /* out of range */
    m.normal_tex = 0;
    /* Texel 0 (centre u = 0.25): (128, 128, 255). */
    CHECK(dirt_material_normal_ts(&m, tex, 1, 0.25f, 0.5f, &n));
    double a = 2.0 * 128 / 255 - 1, l = sqrt(2 * a * a + 1);
    CHECK_MSG(near3(n, a / l, a / l, 1 / l, 1e-6), "flat texel: (%g %g %g)", n.x, n.y, n.z);
    /* Texel 1 with scale 0.5: ((2 c - 1) 0.5, (2 c - 1) 0.5, 2 c - 1). */
    m.normal_scale = 0.5f;
    CHECK(dirt_material_normal_ts(&m, tex, 1, 0.75f, 0.5f, &n));
    double x = (2.0 * 255 / 255 - 1) * 0.5, y = (2.0 * 64 / 255 - 1) * 0.5,
           z = 2.0 * 200 / 255 - 1;
    l = sqrt(x * x + y * y + z * z);
    CHECK_MSG(near3(n, x / l, y / l, z / l, 1e-6), "texel 1, scale 0.5: (%g %g %g), "
              "expected (%g %g %g)", n.x, n.y, n.z, x / l, y / l, z / l);
    /* The normal slot's transform: offset 0.5 reads texel 1 at u = 0.25. */
    m.xf[DIRT_SLOT_NORMAL] = (dirt_tex_transform){.set = true, .offset = {0.5f, 0},
                                                 .scale = {1, 1}};
    dirt_vec3 n2;
    CHECK(dirt_material_normal_ts(&m, tex, 1, 0.25f, 0.5f, &n2));
    CHECK(n2.x == n.x && n2.y == n.y && n2.z == n.z);
    /* Scale 0 flattens the map to +z. */
    m.normal_scale = 0.0f;
    CHECK(dirt_material_normal_ts(&m, tex, 1, 0.25f, 0.5f, &n2));
    CHECK(n2.x == 0.0f && n2.y == 0.0f && n2.z == 1.0f);
}

static void test_apply(void)
{
    dirt_vec3 n = v3(0, 0, 1), t = v3(1, 0, 0);
    dirt_vec3 r = dirt_normal_map_apply(n, t, 1.0f, v3(0.6f, 0.0f, 0.8f));
    CHECK(near3(r, 0.6, 0, 0.8, 1e-7));
    /* b = cross(n, t) w: +y for w = 1, -y for w = -1. */
    r = dirt_normal_map_apply(n, t, 1.0f, v3(0.0f, 0.6f, 0.8f));
    CHECK(near3(r, 0, 0.6, 0.8, 1e-7));
    r = dirt_normal_map_apply(n, t, -1.0f, v3(0.0f, 0.6f, 0.8f));
    CHECK(near3(r, 0, -0.6, 0.8, 1e-7));
    r = dirt_normal_map_apply(n, t, -0.2f, v3(0.0f, 0.6f, 0.8f)); /* only the sign counts */
    CHECK(near3(r, 0, -0.6, 0.8, 1e-7));
    /* A tangent with a component along n, and of length 3: orthogonalised. */
    r = dirt_normal_map_apply(n, v3(3.0f, 0.0f, 1.5f), 1.0f, v3(0.6f, 0.0f, 0.8f));
    CHECK(near3(r, 0.6, 0, 0.8, 1e-7));
    /* Degenerate tangents: n itself, bit for bit. */
    dirt_vec3 nn = v3(0.0f, 0.6f, 0.8f);
    r = dirt_normal_map_apply(nn, v3(0, 0, 0), 1.0f, v3(0.6f, 0.0f, 0.8f));
    CHECK(r.x == nn.x && r.y == nn.y && r.z == nn.z);
    r = dirt_normal_map_apply(nn, v3(0.0f, 1.2f, 1.6f), 1.0f, v3(0.6f, 0.0f, 0.8f));
    CHECK(r.x == nn.x && r.y == nn.y && r.z == nn.z);
    r = dirt_normal_map_apply(nn, v3(NAN, 0.0f, 0.0f), 1.0f, v3(0.6f, 0.0f, 0.8f));
    CHECK(r.x == nn.x && r.y == nn.y && r.z == nn.z);
    /* A tilted frame: n = (0, 0.6, 0.8), t = (1, 0, 0), b = cross(n, t) =
     * (0, 0.8, -0.6); n_ts = (0.48, 0.36, 0.8) -> 0.48 t + 0.36 b + 0.8 n. */
    r = dirt_normal_map_apply(nn, v3(1, 0, 0), 1.0f, v3(0.48f, 0.36f, 0.8f));
    CHECK_MSG(near3(r, 0.48, 0.36 * 0.8 + 0.8 * 0.6, -0.36 * 0.6 + 0.8 * 0.8, 1e-6),
              "tilted frame: (%g %g %g)", r.x, r.y, r.z);
}

int main(void)
{
    test_transforms();
    test_material_slots();
    test_normal_ts();
    test_apply();
    return check_finish();
}
