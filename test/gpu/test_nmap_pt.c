/* Normal maps and texture transforms in every engine (issue 14 item 2
 * acceptance: "an image made with a normal map differs from one without
 * it, and equals Embree's"): sessions of the dirt, mmrt and embree engines,
 * same seed.
 * - A scene written here: a floor with a bump normal map (tangents
 *   generated: the file has no TANGENT) and a checker base colour, both
 *   with KHR_texture_transform (rotation, scale, offset), and a back wall
 *   with the same map, TANGENT from the file, seen through a mirroring
 *   node (scale -1: the handedness flips); lit by an emissive ceiling
 *   panel and a point light. The same file without normalTexture is the
 *   reference without the map.
 * - FlightHelmet (normal maps with TANGENT) under the built-in sky, and the
 *   same scene with every material's normal map cleared.
 * For each: DIRT's image against Embree's, relative MSE below 1e-6 (GPU
 * and CPU follow the same paths; measured values printed); MMRT within its
 * documented thickness error (relMSE below 0.6, mean luminance within 25 %
 * of Embree's, as test_env_pt); and the image without the normal map
 * differs clearly from the one with it (relMSE above 1e-3, in both
 * engines). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "../unit/test_scene_util.h"
#include "check.h"
#include "integrator/integrator.h"
#include "dirt/session.h"
#include "gpu.h"
#include "session_util.h"

#define W 64
#define H 48
#define SPP 4
#define DIRT_MAX_REL_MSE 1e-6
#define MMRT_MAX_REL_MSE 0.6
#define MIN_MAP_EFFECT 1e-3

/* A copy of the session's image after SPP samples of `engine`. */
static dirt_image *render(dirt_gpu *gpu, const dirt_scene *scene, enum dirt_engine engine,
                          const dirt_env *env)
{
    dirt_session_opts o = {.engine = engine, .width = W, .height = H, .bounces = 3, .seed = 11,
                           .env = env};
    return test_session_render(gpu, scene, &o, SPP);
}

typedef struct images {
    dirt_image *embree, *dirt, *mmrt;
} images;

static images compare(dirt_gpu *gpu, const char *label, const dirt_scene *scene,
                      const dirt_env *env)
{
    images r = {render(gpu, scene, DIRT_ENGINE_EMBREE, env),
                render(gpu, scene, DIRT_ENGINE_DIRT, env),
                render(gpu, scene, DIRT_ENGINE_MMRT, env)};
    if (r.embree && r.dirt && r.mmrt) {
        double rd = dirt_image_rel_mse(r.dirt, r.embree), rm = dirt_image_rel_mse(r.mmrt, r.embree);
        double le = test_mean_luminance(r.embree), lm = test_mean_luminance(r.mmrt);
        fprintf(stderr, "%-34s DIRT relMSE %.3g, MMRT relMSE %.3g (mean %.4f vs Embree %.4f)\n",
                label, rd, rm, lm, le);
        CHECK(le > 0.01);
        CHECK_MSG(rd < DIRT_MAX_REL_MSE, "%s: DIRT relMSE %.3g", label, rd);
        CHECK_MSG(rm < MMRT_MAX_REL_MSE, "%s: MMRT relMSE %.3g", label, rm);
        CHECK(lm > 0.75 * le && lm < 1.25 * le);
    }
    return r;
}

static void images_free(images *r)
{
    dirt_image_destroy(r->embree);
    dirt_image_destroy(r->dirt);
    dirt_image_destroy(r->mmrt);
}

/* The map matters: with and without it, in Embree and in DIRT. */
static void map_effect(const char *label, const images *with, const images *without)
{
    if (!with->embree || !without->embree || !with->dirt || !without->dirt)
        return;
    double re = dirt_image_rel_mse(without->embree, with->embree);
    double rd = dirt_image_rel_mse(without->dirt, with->dirt);
    fprintf(stderr, "%-34s without the normal map: relMSE %.3g (Embree), %.3g (DIRT)\n", label,
            re, rd);
    CHECK_MSG(re > MIN_MAP_EFFECT && rd > MIN_MAP_EFFECT, "%s: the normal map changes nothing",
              label);
}

/* ---- the generated scene ------------------------------------------------ */

/* 32 x 32 bumps: h = sin(2 pi x / 16) sin(2 pi y / 16), n = (-h_x, -h_y, 1)
 * (a steep slope), encoded as (n + 1) / 2. */
static void write_normal_map(const char *path)
{
    enum { S = 32 };
    uint8_t px[S * S * 4];
    const double k = 2.0 * 3.14159265358979 / 16.0, a = 1.5;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            double hx = a * cos(k * x) * sin(k * y), hy = a * sin(k * x) * cos(k * y);
            double l = sqrt(hx * hx + hy * hy + 1.0);
            double n[3] = {-hx / l, -hy / l, 1.0 / l};
            for (int c = 0; c < 3; c++)
                px[4 * (y * S + x) + c] = (uint8_t)lround((n[c] * 0.5 + 0.5) * 255.0);
            px[4 * (y * S + x) + 3] = 255;
        }
    CHECK(stbi_write_png(path, S, S, 4, px, S * 4) != 0);
}

static void write_checker(const char *path)
{
    enum { S = 8 };
    uint8_t px[S * S * 4];
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            bool odd = (x / 2 + y / 2) % 2;
            uint8_t c[4] = {odd ? 230 : 90, odd ? 230 : 140, odd ? 230 : 220, 255};
            memcpy(&px[4 * (y * S + x)], c, 4);
        }
    CHECK(stbi_write_png(path, S, S, 4, px, S * 4) != 0);
}

/* Geometry: floor (y = 0, |x|, |z| <= 2, up), back wall (z = -2, 0 <= y
 * <= 3, facing +z, with TANGENT), ceiling light (y = 2.9, facing down). */
typedef struct scene_buffer {
    float floor_pos[4][3], floor_nrm[4][3], floor_uv[4][2];
    float wall_pos[4][3], wall_nrm[4][3], wall_uv[4][2], wall_tan[4][4];
    float light_pos[4][3], light_nrm[4][3];
    uint16_t idx[6];
} scene_buffer;

static char *scene_json(bool normal_map, const char *uri)
{
    const char *nm_floor = normal_map
        ? "\"normalTexture\":{\"index\":0,\"scale\":0.9,\"extensions\":{\"KHR_texture_transform\":"
          "{\"offset\":[0.1,0.3],\"rotation\":0.4,\"scale\":[1.5,1]}}},"
        : "";
    const char *nm_wall = normal_map ? "\"normalTexture\":{\"index\":0}," : "";
    return strf(
        "{\"asset\":{\"version\":\"2.0\"},"
        "\"extensionsUsed\":[\"KHR_texture_transform\",\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\","
        "\"intensity\":6,\"color\":[1,0.9,0.8]}]}},"
        "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":1,\"scale\":[-1,1,1]},{\"mesh\":2},"
        "{\"translation\":[1.2,1.6,0.8],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],"
        "\"meshes\":["
        "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
        "\"indices\":9,\"material\":0}]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":3,\"NORMAL\":4,\"TEXCOORD_0\":5,"
        "\"TANGENT\":6},\"indices\":9,\"material\":1}]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":7,\"NORMAL\":8},\"indices\":9,"
        "\"material\":2}]}],"
        "\"materials\":["
        "{\"name\":\"floor\",%s\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1,"
        "\"extensions\":{\"KHR_texture_transform\":{\"rotation\":-0.2,\"scale\":[2,2],"
        "\"offset\":[0.05,0]}}},\"metallicFactor\":0,\"roughnessFactor\":0.5}},"
        "{\"name\":\"wall\",%s\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.7,0.6,0.5,1],"
        "\"metallicFactor\":0,\"roughnessFactor\":0.35}},"
        "{\"name\":\"light\",\"emissiveFactor\":[4,4,4],"
        "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]}}],"
        "\"images\":[{\"uri\":\"bumps.png\"},{\"uri\":\"checker.png\"}],"
        "\"textures\":[{\"source\":0},{\"source\":1}],"
        "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}],"
        "\"bufferViews\":["
        "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":32},"
        "{\"buffer\":0,\"byteOffset\":128,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":176,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":224,\"byteLength\":32},"
        "{\"buffer\":0,\"byteOffset\":256,\"byteLength\":64},"
        "{\"buffer\":0,\"byteOffset\":320,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":368,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":416,\"byteLength\":12}],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[-2,0,-2],\"max\":[2,0,2]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
        "{\"bufferView\":3,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[-2,0,-2],\"max\":[2,3,-2]},"
        "{\"bufferView\":4,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":5,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
        "{\"bufferView\":6,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"},"
        "{\"bufferView\":7,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[-0.6,2.9,-1],\"max\":[0.6,2.9,0.2]},"
        "{\"bufferView\":8,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":9,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}",
        nm_floor, nm_wall, sizeof(scene_buffer), uri);
}

static char *scene_buffer_uri(void)
{
    scene_buffer b;
    memset(&b, 0, sizeof(b));
    /* Counter-clockwise from the front with indices 0 1 2, 0 2 3. */
    const float floor[4][3] = {{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}};
    const float wall[4][3] = {{-2, 0, -2}, {2, 0, -2}, {2, 3, -2}, {-2, 3, -2}};
    const float light[4][3] = {{-0.6f, 2.9f, -1}, {0.6f, 2.9f, -1}, {0.6f, 2.9f, 0.2f},
                               {-0.6f, 2.9f, 0.2f}};
    for (int v = 0; v < 4; v++) {
        memcpy(b.floor_pos[v], floor[v], sizeof(floor[v]));
        b.floor_nrm[v][1] = 1.0f;
        b.floor_uv[v][0] = (floor[v][0] + 2.0f) * 0.5f;
        b.floor_uv[v][1] = (floor[v][2] + 2.0f) * 0.5f;
        memcpy(b.wall_pos[v], wall[v], sizeof(wall[v]));
        b.wall_nrm[v][2] = 1.0f;
        b.wall_uv[v][0] = (wall[v][0] + 2.0f) * 0.6f;
        b.wall_uv[v][1] = (3.0f - wall[v][1]) * 0.6f;
        b.wall_tan[v][0] = 1.0f, b.wall_tan[v][3] = -1.0f; /* bitangent dp/dv = -y */
        memcpy(b.light_pos[v], light[v], sizeof(light[v]));
        b.light_nrm[v][1] = -1.0f;
    }
    const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(b.idx, idx, sizeof(idx));
    _Static_assert(sizeof(scene_buffer) == 428, "buffer layout");
    return data_uri(&b, sizeof(b));
}

static dirt_scene *generated_scene(bool normal_map)
{
    char *uri = scene_buffer_uri();
    char *json = scene_json(normal_map, uri);
    const char *name = normal_map ? "bumpy.gltf" : "flat.gltf";
    write_text(tmp_file(name), json);
    free(json);
    free(uri);
    dirt_scene *s = dirt_scene_load(tmp_file(name), NULL);
    CHECK_MSG(s != NULL, "cannot load %s", name);
    if (s && normal_map) {
        const dirt_material *m = dirt_scene_materials(s);
        CHECK(m[0].normal_tex >= 0 && m[1].normal_tex >= 0 && m[0].xf[DIRT_SLOT_NORMAL].set &&
              m[0].xf[DIRT_SLOT_BASE_COLOR].set);
    }
    return s;
}

static dirt_scene *shared_scene(const char *rel)
{
    const char *dir = test_shared_dir();
    if (!dir)
        return NULL;
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/%s", dir, rel);
    dirt_scene *s = dirt_scene_load(path, NULL);
    CHECK_MSG(s != NULL, "cannot load %s", path);
    return s;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    write_normal_map(tmp_file("bumps.png"));
    write_checker(tmp_file("checker.png"));
    dirt_scene *bumpy = generated_scene(true), *flat = generated_scene(false);
    if (bumpy && flat) {
        images a = compare(gpu, "generated, normal maps", bumpy, NULL);
        images b = compare(gpu, "generated, no normal map", flat, NULL);
        map_effect("generated", &a, &b);
        images_free(&a);
        images_free(&b);
    }
    dirt_scene_destroy(bumpy);
    dirt_scene_destroy(flat);

    dirt_env *sky = dirt_env_sky(&(dirt_env_opts){.rotation = 30.0f});
    dirt_scene *helmet = shared_scene("gltf/FlightHelmet/FlightHelmet.gltf");
    if (helmet && sky) {
        size_t mapped = 0;
        for (size_t i = 0; i < dirt_scene_num_materials(helmet); i++)
            mapped += dirt_scene_materials(helmet)[i].normal_tex != DIRT_NO_TEXTURE;
        CHECK(mapped > 0);
        images a = compare(gpu, "FlightHelmet, sky, normal maps", helmet, sky);
        /* The same scene with its normal maps cleared (the scene's
         * materials are the test's to change: it owns the scene). */
        dirt_material *mats = (dirt_material *)dirt_scene_materials(helmet);
        for (size_t i = 0; i < dirt_scene_num_materials(helmet); i++)
            mats[i].normal_tex = DIRT_NO_TEXTURE;
        images b = compare(gpu, "FlightHelmet, sky, maps cleared", helmet, sky);
        map_effect("FlightHelmet", &a, &b);
        images_free(&a);
        images_free(&b);
    }
    dirt_scene_destroy(helmet);
    dirt_env_destroy(sky);
    static const char *const files[] = {"bumps.png", "checker.png", "bumpy.gltf", "flat.gltf"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    dirt_gpu_destroy(gpu);
    return check_finish();
}
