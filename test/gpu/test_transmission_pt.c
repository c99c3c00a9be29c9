/* Transmission in every engine (issue 14 item 4 acceptance: "same seed:
 * DIRT == Embree (relMSE below 1e-6) on a transmissive sphere in the
 * default room; MMRT within its documented thickness error"). The default
 * scene's glTF (data/default_scene.gltf) with its glossy blue sphere made
 * glass through the extensions a file would use (KHR_materials_transmission
 * 1, KHR_materials_ior 1.5, KHR_materials_specular colour), smooth (delta
 * refraction: paths through the sphere, no NEE) and rough (roughness 0.3:
 * NEE through the surface, shadow rays from the far side), and the metal
 * sphere made tinted rough glass of ior 1.33; rendered by the dirt, mmrt and
 * embree engines at 64 x 48, 4 spp, 6 bounces, same seed:
 * - DIRT against Embree: relative MSE below 1e-6 (GPU and CPU follow the
 *   same paths; measured values are printed);
 * - MMRT within its documented thickness error (doc/mmrt.md): with 6
 *   bounces and 4 spp its same-seed relMSE on the unchanged default scene
 *   is already 2.9 (paths diverge after MMRT's first approximate hit; the
 *   0.6 bound of test_mmrt_pt is for 3 bounces and 8 spp), so the glass
 *   scenes must stay within MMRT_REL_FACTOR of that opaque value, and their
 *   mean luminance within 25 % of Embree's;
 * - the glass matters: Embree's image differs from the opaque scene's (same
 *   seed: any difference is the material; the glossy sphere covers few
 *   pixels, hence the low bound). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "integrator/integrator.h"
#include "dirt/session.h"
#include "gpu.h"
#include "session_util.h"

#ifndef DIRT_TEST_DATA_DIR
#error "DIRT_TEST_DATA_DIR must name the data/ folder"
#endif

#define W 64
#define H 48
#define SPP 4
#define DIRT_MAX_REL_MSE 1e-6
/* MMRT's relMSE on a glass scene, at most this times its relMSE on the
 * opaque default scene (same settings). */
#define MMRT_REL_FACTOR 1.5

static dirt_image *render(dirt_gpu *gpu, const dirt_scene *scene, enum dirt_engine engine)
{
    dirt_session_opts o = {.engine = engine, .width = W, .height = H, .bounces = 6, .seed = 7};
    return test_session_render(gpu, scene, &o, SPP);
}

static char *read_text(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    CHECK_MSG(f != NULL, "cannot open %s", path);
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    if (t && fread(t, 1, (size_t)n, f) == (size_t)n) {
        t[n] = '\0';
        *len = (size_t)n;
    } else {
        free(t);
        t = NULL;
    }
    fclose(f);
    return t;
}

/* `text` with `from` replaced by `to` (once; it must be there). Frees
 * `text`; NULL when `from` is missing. */
static char *edit(char *text, const char *from, const char *to)
{
    if (!text)
        return NULL;
    const char *at = strstr(text, from);
    CHECK_MSG(at != NULL, "default_scene.gltf has no '%s'", from);
    char *out = NULL;
    if (at) {
        size_t a = (size_t)(at - text), lf = strlen(from), lt = strlen(to), n = strlen(text);
        out = malloc(n - lf + lt + 1);
        memcpy(out, text, a);
        memcpy(out + a, to, lt);
        memcpy(out + a + lt, at + lf, n - a - lf + 1);
    }
    free(text);
    return out;
}

static dirt_scene *load(char *text, const char *name)
{
    dirt_scene *s = text ? dirt_scene_load_memory(text, strlen(text), name, NULL) : NULL;
    CHECK_MSG(s != NULL, "%s does not load", name);
    free(text);
    return s;
}

/* The two sphere materials of default_scene.gltf, as they are written there. */
#define GLOSSY "{\"name\": \"glossy_blue\","
#define GLOSSY_PBR "\"baseColorFactor\": [0.1, 0.25, 0.8, 1], \"metallicFactor\": 0, \"roughnessFactor\": 0.3}"
#define METAL "{\"name\": \"metal\","
#define METAL_PBR "\"baseColorFactor\": [0.95, 0.93, 0.88, 1], \"metallicFactor\": 1, \"roughnessFactor\": 0.05}"

static double mmrt_opaque = -1.0; /* MMRT's relMSE on the opaque scene */

static void compare(dirt_gpu *gpu, const char *label, const dirt_scene *scene,
                    const dirt_image *opaque)
{
    dirt_image *e = render(gpu, scene, DIRT_ENGINE_EMBREE);
    dirt_image *d = render(gpu, scene, DIRT_ENGINE_DIRT);
    dirt_image *m = render(gpu, scene, DIRT_ENGINE_MMRT);
    if (e && d && m) {
        double rd = dirt_image_rel_mse(d, e), rm = dirt_image_rel_mse(m, e);
        double le = test_mean_luminance(e), lm = test_mean_luminance(m);
        double ro = opaque ? dirt_image_rel_mse(e, opaque) : 0.0;
        fprintf(stderr, "%-26s DIRT relMSE %.3g, MMRT relMSE %.3g (mean %.4f vs Embree %.4f), "
                "vs the opaque scene %.3g\n", label, rd, rm, lm, le, ro);
        CHECK(le > 0.01);
        CHECK_MSG(rd < DIRT_MAX_REL_MSE, "%s: DIRT relMSE %.3g", label, rd);
        CHECK(lm > 0.75 * le && lm < 1.25 * le);
        if (!opaque) {
            mmrt_opaque = rm;
        } else {
            CHECK_MSG(mmrt_opaque > 0.0 && rm < MMRT_REL_FACTOR * mmrt_opaque,
                      "%s: MMRT relMSE %.3g, opaque scene %.3g", label, rm, mmrt_opaque);
            CHECK_MSG(ro > 1e-4, "%s: the glass changed nothing (relMSE %.3g)", label, ro);
        }
    }
    dirt_image_destroy(e);
    dirt_image_destroy(d);
    dirt_image_destroy(m);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    size_t len = 0;
    char *text = read_text(DIRT_TEST_DATA_DIR "/default_scene.gltf", &len);
    CHECK(text != NULL);
    dirt_scene *plain = text ? dirt_scene_load_memory(text, len, "default.gltf", NULL) : NULL;
    /* clear smooth glass (delta refraction; the default ior 1.5) */
    char *t = text ? strdup(text) : NULL;
    t = edit(t, GLOSSY, "{\"name\": \"glass\", \"extensions\": {\"KHR_materials_transmission\": "
             "{\"transmissionFactor\": 1}, \"KHR_materials_ior\": {\"ior\": 1.5}},");
    t = edit(t, GLOSSY_PBR, "\"baseColorFactor\": [1, 1, 1, 1], \"metallicFactor\": 0, "
             "\"roughnessFactor\": 0}");
    dirt_scene *smooth = load(t, "smooth.gltf");
    /* rough tinted glass with a specular colour (NEE through the surface) */
    t = text ? strdup(text) : NULL;
    t = edit(t, GLOSSY, "{\"name\": \"frosted\", \"extensions\": {\"KHR_materials_transmission\": "
             "{\"transmissionFactor\": 1}, \"KHR_materials_specular\": "
             "{\"specularColorFactor\": [1.5, 1, 0.5]}},");
    t = edit(t, GLOSSY_PBR, "\"baseColorFactor\": [0.9, 0.95, 1, 1], \"metallicFactor\": 0, "
             "\"roughnessFactor\": 0.3}");
    dirt_scene *rough = load(t, "rough.gltf");
    /* both spheres: the metal one becomes partly transmissive rough water */
    t = text ? strdup(text) : NULL;
    t = edit(t, GLOSSY, "{\"name\": \"glass\", \"extensions\": {\"KHR_materials_transmission\": "
             "{\"transmissionFactor\": 1}},");
    t = edit(t, GLOSSY_PBR, "\"baseColorFactor\": [1, 1, 1, 1], \"metallicFactor\": 0, "
             "\"roughnessFactor\": 0}");
    t = edit(t, METAL, "{\"name\": \"water\", \"extensions\": {\"KHR_materials_transmission\": "
             "{\"transmissionFactor\": 0.9}, \"KHR_materials_ior\": {\"ior\": 1.33}},");
    t = edit(t, METAL_PBR, "\"baseColorFactor\": [0.7, 1, 0.8, 1], \"metallicFactor\": 0, "
             "\"roughnessFactor\": 0.15}");
    dirt_scene *two = load(t, "two.gltf");
    CHECK(plain && smooth && rough && two);
    dirt_image *opaque = plain ? render(gpu, plain, DIRT_ENGINE_EMBREE) : NULL;
    if (plain)
        compare(gpu, "opaque default scene", plain, NULL);
    if (smooth)
        compare(gpu, "smooth glass sphere", smooth, opaque);
    if (rough)
        compare(gpu, "rough glass sphere", rough, opaque);
    if (two)
        compare(gpu, "two glass spheres", two, opaque);
    dirt_image_destroy(opaque);
    dirt_scene_destroy(plain);
    dirt_scene_destroy(smooth);
    dirt_scene_destroy(rough);
    dirt_scene_destroy(two);
    free(text);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
