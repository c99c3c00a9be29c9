/* The non-BSDF parts of the light-transport model (doc/light-transport.md):
 * texture filtering (bilinear, repeat, sRGB decode before filtering),
 * material texturing, punctual lights (inverse square, glTF range window,
 * smooth spot cone), area-weighted emissive triangle selection, and camera
 * rays (pinhole field of view, thin-lens focus, orthographic). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "integrator/integrator.h"
#include "integrator/rng.h"

#define PI 3.14159265358979323846

static void check_textures(void)
{
    /* 2 x 2 texture: row 0 = (0, 255), row 1 = (64, 128) in red; green 255
     * everywhere; blue = 188 (sRGB 0.50289 linear); alpha 51. */
    uint8_t px[16] = {0, 255, 188, 51, 255, 255, 188, 51, 64, 255, 188, 51, 128, 255, 188, 51};
    dirt_texture t;
    memset(&t, 0, sizeof(t));
    t.width = 2;
    t.height = 2;
    t.rgba = px;
    float o[4];
    /* Texel centres return the texel. */
    dirt_texture_sample(&t, false, 0.25f, 0.25f, o);
    CHECK_NEAR(o[0], 0.0, 1e-6);
    CHECK_NEAR(o[3], 0.2, 1e-6);
    dirt_texture_sample(&t, false, 0.75f, 0.25f, o);
    CHECK_NEAR(o[0], 1.0, 1e-6);
    dirt_texture_sample(&t, false, 0.25f, 0.75f, o);
    CHECK_NEAR(o[0], 64.0 / 255.0, 1e-6);
    /* Centre of the texture: mean of the four. */
    dirt_texture_sample(&t, false, 0.5f, 0.5f, o);
    CHECK_NEAR(o[0], (0 + 255 + 64 + 128) / 4.0 / 255.0, 1e-6);
    /* Repeat: u = 0 lies halfway between texel 1 (wrapped) and texel 0. */
    dirt_texture_sample(&t, false, 0.0f, 0.25f, o);
    CHECK_NEAR(o[0], 0.5, 1e-6);
    float a[4], b[4];
    dirt_texture_sample(&t, false, -0.8f, 2.3f, a);
    dirt_texture_sample(&t, false, 0.2f, 0.3f, b);
    CHECK_NEAR(a[0], b[0], 1e-5);
    dirt_texture_sample(&t, false, 7.2f, -5.7f, a);
    CHECK_NEAR(a[0], b[0], 1e-5);
    /* sRGB: decoded per texel, then filtered; alpha stays linear. */
    dirt_texture_sample(&t, true, 0.5f, 0.5f, o);
    double lin = (dirt_srgb_to_linear(0) + dirt_srgb_to_linear(1) + dirt_srgb_to_linear(64 / 255.0f) +
                  dirt_srgb_to_linear(128 / 255.0f)) / 4.0;
    CHECK_NEAR(o[0], lin, 1e-6);
    CHECK_NEAR(o[2], 0.502886, 1e-5);
    CHECK_NEAR(o[3], 0.2, 1e-6);
    CHECK_NEAR(dirt_srgb_to_linear(0.5f), 0.214041, 1e-5);
    CHECK_NEAR(dirt_srgb_to_linear(0.04f), 0.04 / 12.92, 1e-7);
    /* Missing texture = white; non-finite uv reads as 0. */
    dirt_texture_sample(NULL, true, 0.3f, 0.3f, o);
    CHECK(o[0] == 1.0f && o[3] == 1.0f);
    dirt_texture_sample(&t, false, NAN, INFINITY, a);
    dirt_texture_sample(&t, false, 0.0f, 0.0f, b);
    CHECK(a[0] == b[0]);

    /* Material: factors times textures, roughness from G, metallic from B. */
    uint8_t mr_px[4] = {0, 128, 255, 255};
    dirt_texture tex[2];
    memset(tex, 0, sizeof(tex));
    tex[0] = t;
    tex[1].width = tex[1].height = 1;
    tex[1].rgba = mr_px;
    dirt_material m;
    dirt_material_default(&m);
    m.base_color[0] = m.base_color[1] = m.base_color[2] = m.base_color[3] = 0.5f;
    m.base_color_tex = 0;
    m.metallic = 0.5f;
    m.roughness = 1.0f;
    m.metallic_roughness_tex = 1;
    m.emissive[0] = 2.0f;
    m.emissive_strength = 3.0f;
    m.emissive_tex = 7; /* out of range: white */
    dirt_surface s;
    dirt_material_surface(&m, 1.0f, tex, 2, 0.75f, 0.25f, &s);
    CHECK_NEAR(s.bsdf.base_color.x, 0.5, 1e-6);                       /* 0.5 * 1 */
    CHECK_NEAR(s.bsdf.base_color.y, 0.5, 1e-6);                       /* 0.5 * 1 */
    CHECK_NEAR(s.bsdf.base_color.z, 0.5 * 0.502886, 1e-5);
    CHECK_NEAR(s.bsdf.alpha, (128 / 255.0) * (128 / 255.0), 1e-6);
    CHECK_NEAR(s.bsdf.metallic, 0.5, 1e-6);
    CHECK_NEAR(s.emission.x, 6.0, 1e-6);
    CHECK(s.emission.y == 0.0f);
    CHECK(dirt_material_is_emissive(&m));
    m.emissive_strength = 0.0f;
    CHECK(!dirt_material_is_emissive(&m));
}

static void check_lights(void)
{
    dirt_light l;
    memset(&l, 0, sizeof(l));
    l.type = DIRT_LIGHT_POINT;
    l.position[1] = 2.0f;
    l.color[0] = l.color[1] = l.color[2] = 8.0f;
    dirt_vec3 p = {0, 0, 0}, wi, li;
    float d;
    CHECK(dirt_punctual_light(&l, p, &wi, &d, &li));
    CHECK_NEAR(d, 2.0, 1e-6);
    CHECK_NEAR(wi.y, 1.0, 1e-6);
    CHECK_NEAR(li.x, 2.0, 1e-6); /* 8 / 2^2 */
    l.range = 4.0f;              /* window 1 - (2/4)^4 */
    CHECK(dirt_punctual_light(&l, p, &wi, &d, &li));
    CHECK_NEAR(li.x, 2.0 * (1.0 - 1.0 / 16.0), 1e-6);
    l.range = 1.5f;
    CHECK(!dirt_punctual_light(&l, p, &wi, &d, &li));
    l.range = 0.0f;

    /* Spot shining down -y, inner 0.2, outer 0.4 rad. */
    l.type = DIRT_LIGHT_SPOT;
    l.direction[1] = -1.0f;
    l.inner_cone = 0.2f;
    l.outer_cone = 0.4f;
    CHECK(dirt_punctual_light(&l, p, &wi, &d, &li)); /* on the axis */
    CHECK_NEAR(li.x, 2.0, 1e-6);
    float ang = 0.3f; /* halfway in angle between the cones */
    dirt_vec3 q = {2.0f * tanf(ang), 0.0f, 0.0f};
    CHECK(dirt_punctual_light(&l, q, &wi, &d, &li));
    double s = (cos(ang) - cos(0.4)) / (cos(0.2) - cos(0.4));
    CHECK_NEAR(li.x, 8.0 / (d * d) * s * s, 1e-5);
    q.x = 2.0f * tanf(0.45f); /* outside the outer cone */
    CHECK(!dirt_punctual_light(&l, q, &wi, &d, &li));
    q.x = 2.0f * tanf(0.1f); /* inside the inner cone: full */
    CHECK(dirt_punctual_light(&l, q, &wi, &d, &li));
    CHECK_NEAR(li.x, 8.0 / (d * d), 1e-5);

    /* Directional: from -direction, no falloff, infinite distance. */
    l.type = DIRT_LIGHT_DIRECTIONAL;
    l.direction[0] = 0.0f;
    l.direction[1] = -2.0f;
    l.direction[2] = 0.0f;
    CHECK(dirt_punctual_light(&l, p, &wi, &d, &li));
    CHECK(isinf(d));
    CHECK_NEAR(wi.y, 1.0, 1e-6);
    CHECK_NEAR(li.x, 8.0, 1e-6);
}

static void check_area_lights(void)
{
    /* Three triangles: emissive areas 1 and 3, one non-emissive. */
    float pos[9][3] = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                       {0, 0, 1}, {3, 0, 1}, {0, 2, 1}};
    uint32_t mat[3] = {0, 1, 0};
    dirt_material m[2];
    memset(m, 0, sizeof(m));
    m[0].emissive[1] = 1.0f;
    m[0].emissive_strength = 1.0f;
    dirt_frame f;
    memset(&f, 0, sizeof(f));
    f.num_triangles = 3;
    f.position = pos;
    f.material = mat;
    dirt_area_lights al;
    CHECK(dirt_area_lights_build(&al, &f, m, 2));
    CHECK(al.count == 2);
    CHECK(al.prim[0] == 0 && al.prim[1] == 2);
    CHECK_NEAR(al.total_area, 4.0, 1e-6);
    CHECK(dirt_area_lights_select(&al, 0.0f) == 0);
    CHECK(dirt_area_lights_select(&al, 0.2499f) == 0);
    CHECK(dirt_area_lights_select(&al, 0.25f) == 1);
    CHECK(dirt_area_lights_select(&al, 1.0f - 1.0f / 16777216.0f) == 1);
    int n1 = 0;
    for (uint32_t i = 0; i < 100000; i++)
        n1 += dirt_area_lights_select(&al, dirt_rng_float(3, i, 0, 1, DIRT_RNG_DIM_LIGHT_TRI)) == 1;
    /* p = 0.75, s.e. = sqrt(.75 .25 / 1e5) = 1.4e-3; 5 sigma */
    CHECK_NEAR(n1 / 100000.0, 0.75, 7e-3);
    dirt_area_lights_free(&al);
    dirt_area_lights_free(&al); /* idempotent */
    CHECK(dirt_light_source_count(2, 3) == 4);
    CHECK(dirt_light_source_count(0, 3) == 3);
}

static void check_camera(void)
{
    dirt_camera c;
    memset(&c, 0, sizeof(c));
    float eye[3] = {1, 2, 3}, target[3] = {1, 2, -7}, up[3] = {0, 1, 0};
    dirt_camera_look_at(&c, eye, target, up);
    c.type = DIRT_CAMERA_PERSPECTIVE;
    c.yfov = (float)(PI / 2.0); /* tan(yfov/2) = 1 */
    dirt_vec3 o, d;
    dirt_camera_ray(&c, 200, 100, 100.0f, 50.0f, 0.5f, 0.5f, &o, &d);
    CHECK_NEAR(o.x, 1.0, 1e-6);
    CHECK_NEAR(d.z, -1.0, 1e-6);
    /* Top-left corner: x = -aspect, y = +1 at unit distance. */
    dirt_camera_ray(&c, 200, 100, 0.0f, 0.0f, 0.5f, 0.5f, &o, &d);
    CHECK_NEAR(d.x / -d.z, -2.0, 1e-5);
    CHECK_NEAR(d.y / -d.z, 1.0, 1e-5);
    CHECK_NEAR(d.x * d.x + d.y * d.y + d.z * d.z, 1.0, 1e-6);
    /* Thin lens: every lens sample of a pixel passes through the same point
     * on the plane of focus; origins spread over the aperture. */
    c.aperture_radius = 0.1f;
    c.focus_distance = 5.0f;
    dirt_vec3 focus = {0, 0, 0};
    int bad = 0;
    float maxr = 0.0f;
    for (uint32_t i = 0; i < 1000; i++) {
        dirt_camera_ray(&c, 200, 100, 37.3f, 81.2f, dirt_rng_float(1, i, 0, 0, 2),
                        dirt_rng_float(1, i, 0, 0, 3), &o, &d);
        float t = (-2.0f - o.z) / d.z; /* plane z = 3 - 5 */
        dirt_vec3 pf = {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
        if (i == 0)
            focus = pf;
        else if (fabsf(pf.x - focus.x) > 1e-4f || fabsf(pf.y - focus.y) > 1e-4f)
            bad++;
        float r = sqrtf((o.x - 1) * (o.x - 1) + (o.y - 2) * (o.y - 2));
        if (r > maxr)
            maxr = r;
        if (fabsf(o.z - 3.0f) > 1e-6f)
            bad++;
    }
    CHECK(bad == 0);
    CHECK(maxr <= 0.1f + 1e-6f && maxr > 0.09f);
    /* The pinhole ray of the same pixel goes through the same focus point. */
    c.aperture_radius = 0.0f;
    dirt_camera_ray(&c, 200, 100, 37.3f, 81.2f, 0.9f, 0.9f, &o, &d);
    float t = (-2.0f - o.z) / d.z;
    CHECK_NEAR(o.x + t * d.x, focus.x, 1e-4);
    CHECK_NEAR(o.y + t * d.y, focus.y, 1e-4);
    /* Orthographic: parallel rays, origins spanning +-xmag, +-ymag. */
    c.type = DIRT_CAMERA_ORTHOGRAPHIC;
    c.xmag = 4.0f;
    c.ymag = 2.0f;
    dirt_camera_ray(&c, 200, 100, 0.0f, 100.0f, 0.5f, 0.5f, &o, &d);
    CHECK_NEAR(o.x, 1.0 - 4.0, 1e-5);
    CHECK_NEAR(o.y, 2.0 - 2.0, 1e-5);
    CHECK_NEAR(d.z, -1.0, 1e-6);
}

int main(void)
{
    check_textures();
    check_lights();
    check_area_lights();
    check_camera();
    return check_finish();
}
