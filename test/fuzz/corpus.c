/* DIRT engine: the scene fuzz target's seed corpus, made here (see
 * fuzz_scene.h): the reference quad as .gltf and .glb, animation (LINEAR,
 * STEP, CUBICSPLINE, two clips), morph targets with animated weights, a
 * skin, a sparse accessor without bufferView, strips and fans, a camera and
 * a light, the embedded default scene, quantized positions, OBJ + MTL; and
 * invalid ones (truncated .glb, deep nesting, a huge count, an index out of
 * range, a node cycle, a required extension the loader lacks, OBJ indices
 * past the vertices or zero, an infinite OBJ position). */
#include "fuzz_scene.h"

#include "../unit/test_scene_util.h"
#include "scene/scene_internal.h"

#include <stdio.h>
#include <string.h>

/* Buffer: 4 positions (48 B), 6 uint16 indices (12 B), 2 key times (8 B),
 * 2 translations (24 B), 2 rotations (32 B), 2 x 3 cubic scales (72 B),
 * 4 morph deltas (48 B), 2 weights (8 B), 4 ubyte4 joints (16 B), 4 vec4
 * weights (64 B), 2 mat4 (128 B), sparse: 1 uint16 index (2 B + 2 pad),
 * 1 vec3 (12 B). */
enum {
    OFF_POS = 0, OFF_IDX = 48, OFF_T = 60, OFF_TR = 68, OFF_ROT = 92, OFF_SC = 124,
    OFF_MORPH = 196, OFF_W = 244, OFF_J = 252, OFF_SW = 268, OFF_IBM = 332,
    OFF_SPI = 460, OFF_SPV = 464, BUF_LEN = 476
};

static void make_buffer(uint8_t *b)
{
    memset(b, 0, BUF_LEN);
    float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    float t[2] = {0, 1};
    float tr[6] = {0, 0, 0, 1, 2, 3};
    float rot[8] = {0, 0, 0, 1, 0, 0.7071068f, 0, 0.7071068f};
    float sc[18] = {0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0};
    float morph[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    float w[2] = {0, 1};
    uint8_t j[16] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    float sw[16] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    float ibm[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                     1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    uint16_t spi = 2;
    float spv[3] = {0.5f, 0.5f, 0.5f};
    memcpy(b + OFF_POS, pos, sizeof(pos));
    memcpy(b + OFF_IDX, idx, sizeof(idx));
    memcpy(b + OFF_T, t, sizeof(t));
    memcpy(b + OFF_TR, tr, sizeof(tr));
    memcpy(b + OFF_ROT, rot, sizeof(rot));
    memcpy(b + OFF_SC, sc, sizeof(sc));
    memcpy(b + OFF_MORPH, morph, sizeof(morph));
    memcpy(b + OFF_W, w, sizeof(w));
    memcpy(b + OFF_J, j, sizeof(j));
    memcpy(b + OFF_SW, sw, sizeof(sw));
    memcpy(b + OFF_IBM, ibm, sizeof(ibm));
    memcpy(b + OFF_SPI, &spi, sizeof(spi));
    memcpy(b + OFF_SPV, spv, sizeof(spv));
}

/* The accessors every file shares (indices into the one buffer view). */
static char *accessors(void)
{
    return strf(
        "\"accessors\":["
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]},"                                          /* 0 */
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\","
        "\"min\":[0],\"max\":[1]},"                                                  /* 2 */
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":2,\"type\":\"VEC4\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5121,\"count\":4,\"type\":\"VEC4\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"},"
        "{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5126,\"count\":2,\"type\":\"MAT4\"},"
        "{\"componentType\":5126,\"count\":4,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
        "\"indices\":{\"bufferView\":0,\"byteOffset\":%d,\"componentType\":5123},"
        "\"values\":{\"bufferView\":0,\"byteOffset\":%d}}}]",                       /* 11 */
        OFF_POS, OFF_IDX, OFF_T, OFF_TR, OFF_ROT, OFF_SC, OFF_MORPH, OFF_W, OFF_J, OFF_SW,
        OFF_IBM, OFF_SPI, OFF_SPV);
}

/* A whole .gltf: `body` (members before "accessors") plus the shared
 * buffer, view and accessors; `buffer` is the buffer's JSON. */
static char *gltf(const char *body, const char *buffer)
{
    char *acc = accessors();
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},%s,\"buffers\":[%s],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%d}],%s}",
                   body, buffer, BUF_LEN, acc);
    free(acc);
    return j;
}

static bool put(const char *dir, const char *name, const void *data, size_t n, int *count)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(data, 1, n, f) == n;
    if (f && fclose(f) != 0)
        ok = false;
    if (!ok)
        perror(path);
    *count += ok;
    return ok;
}

int dirt_fuzz_write_corpus(const char *dir)
{
    uint8_t buf[BUF_LEN];
    make_buffer(buf);
    char *uri = data_uri(buf, sizeof(buf));
    char *bj = strf("{\"byteLength\":%d,\"uri\":\"%s\"}", BUF_LEN, uri);
    char *glb_buffer = strf("{\"byteLength\":%d}", BUF_LEN);
    static const char quad[] =
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]";
    static const char anim[] =
        "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"children\":[2]},"
        "{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"animations\":[{\"samplers\":[{\"input\":2,\"output\":3},"
        "{\"input\":2,\"output\":4,\"interpolation\":\"STEP\"},"
        "{\"input\":2,\"output\":5,\"interpolation\":\"CUBICSPLINE\"}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}},"
        "{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"rotation\"}},"
        "{\"sampler\":2,\"target\":{\"node\":2,\"path\":\"scale\"}}]},"
        "{\"samplers\":[{\"input\":2,\"output\":4}],\"channels\":[{\"sampler\":0,"
        "\"target\":{\"node\":2,\"path\":\"rotation\"}}]}]";
    static const char morph[] =
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
        "\"targets\":[{\"POSITION\":6}]}],\"weights\":[0.5]}],"
        "\"animations\":[{\"samplers\":[{\"input\":2,\"output\":7}],\"channels\":[{\"sampler\":0,"
        "\"target\":{\"node\":0,\"path\":\"weights\"}}]}]";
    static const char skin[] =
        "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0,\"skin\":0},{\"children\":[2]},"
        "{\"translation\":[0,1,0]}],\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":10}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":8,"
        "\"WEIGHTS_0\":9},\"indices\":1}]}],"
        "\"animations\":[{\"samplers\":[{\"input\":2,\"output\":4}],\"channels\":[{\"sampler\":0,"
        "\"target\":{\"node\":2,\"path\":\"rotation\"}}]}]";
    static const char sparse[] =
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
        "\"targets\":[{\"POSITION\":11}]},{\"attributes\":{\"POSITION\":0},\"mode\":5},"
        "{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":6}],\"weights\":[1]}]";
    static const char camlight[] =
        "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\","
        "\"intensity\":5,\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.5}},"
        "{\"type\":\"directional\",\"color\":[1,0.5,0.5]}]}},"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.01}}],"
        "\"materials\":[{\"emissiveFactor\":[1,1,1],\"pbrMetallicRoughness\":{"
        "\"metallicFactor\":0.5}}],"
        "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},{\"camera\":0,"
        "\"translation\":[0,0,3]},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},"
        "\"rotation\":[0,0,0,1]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
        "\"material\":0}]}]";
    static const char bad_index[] =
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":8}]}]";
    static const char cycle[] =
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]";
    static const struct {
        const char *name, *body;
    } files[] = {{"quad.gltf", quad},         {"anim.gltf", anim},
                 {"morph.gltf", morph},       {"skin.gltf", skin},
                 {"sparse_strip.gltf", sparse}, {"camera_light.gltf", camlight},
                 {"bad_index.gltf", bad_index}, {"cycle.gltf", cycle}};
    int count = 0;
    bool ok = true;
    for (size_t i = 0; ok && i < sizeof(files) / sizeof(files[0]); i++) {
        char *j = gltf(files[i].body, bj);
        ok = put(dir, files[i].name, j, strlen(j), &count);
        free(j);
    }
    /* .glb versions of two, and a truncated one. */
    static const char *const glb_bodies[] = {quad, anim};
    static const char *const glb_names[] = {"quad.glb", "anim.glb"};
    for (size_t i = 0; ok && i < 2; i++) {
        char *j = gltf(glb_bodies[i], glb_buffer);
        uint8_t *g = NULL;
        size_t n = make_glb(j, buf, sizeof(buf), &g);
        ok = put(dir, glb_names[i], g, n, &count);
        if (ok && i == 0)
            ok = put(dir, "truncated.glb", g, n - 100, &count);
        free(g);
        free(j);
    }
    /* Nesting past the default limit, and a huge accessor without a view. */
    if (ok) {
        char deep[2 * 300 + 64];
        size_t n = (size_t)sprintf(deep, "{\"asset\":{\"version\":\"2.0\"},\"extras\":");
        memset(deep + n, '[', 300);
        memset(deep + n + 300, ']', 300);
        n += 600;
        deep[n++] = '}';
        ok = put(dir, "deep.gltf", deep, n, &count);
    }
    if (ok) {
        static const char huge[] =
            "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
            "\"accessors\":[{\"componentType\":5126,\"count\":268435456,\"type\":\"VEC3\","
            "\"min\":[0,0,0],\"max\":[0,0,0]}]}";
        ok = put(dir, "huge.gltf", huge, sizeof(huge) - 1, &count);
    }
    if (ok)
        ok = put(dir, "default.gltf", scene_default_gltf, scene_default_gltf_size, &count);
    /* Extensions: one required that the loader lacks (fails), a quantized
     * (SHORT) position accessor under KHR_mesh_quantization (loads). */
    if (ok) {
        char *body = strf("\"extensionsUsed\":[\"KHR_draco_mesh_compression\","
                          "\"KHR_texture_transform\"],"
                          "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],%s", quad);
        char *j = gltf(body, bj);
        ok = put(dir, "draco_required.gltf", j, strlen(j), &count);
        free(j);
        free(body);
    }
    if (ok) {
        char *j = strf("{\"asset\":{\"version\":\"2.0\"},"
                       "\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
                       "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                       "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                       "\"buffers\":[%s],\"bufferViews\":[{\"buffer\":0,\"byteLength\":24,"
                       "\"byteStride\":8}],\"accessors\":[{\"bufferView\":0,"
                       "\"componentType\":5122,\"count\":3,\"type\":\"VEC3\"}]}",
                       bj);
        ok = put(dir, "quantized.gltf", j, strlen(j), &count);
        free(j);
    }
    /* OBJ (dirt_fuzz_load: a '#' first; the MTL text after a NUL byte):
     * materials of every mapped kind, a quad, a concave pentagon, relative
     * indices, normals, UVs, a line, a tag; one without MTL; and three that
     * must fail (an index past the vertices, a zero index, an infinite
     * position). */
    static const char obj[] =
        "# fuzz seed\nmtllib a.mtl\n"
        "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
        "g walls\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/1/1 5/2/1\ns 1\n"
        "o light\nusemtl lamp\nf -5//1 -4//1 -3//1 -1//1\nusemtl nosuch\nf 1 2 3\n"
        "l 1 2\nt crease 2/1/0 1 2 0.5\np 1\n";
    static const char mtl[] =
        "newmtl red\n Kd 0.6 0.1 0.1\n Ks 0.5 0.5 0.5\n Ns 80\n illum 2\n d 0.9\n"
        " map_Kd -s 2 2 1 tex\\red.png\n map_bump bump.png\n Xq 1\n"
        "newmtl lamp\r\n Kd 0.8 0.8 0.8\r\n Ke 17 12 4\r\n map_Ke glow.png\r\n"
        "newmtl metal\n Kd 0 0 0\n Ks 0.9 0.9 0.9\n Ns 1000\n illum 3\n"
        "newmtl pbr\n Kd 1 1 1\n Pr 0.3\n Pm 1\n illum 7\n Tr 0.5\n";
    if (ok) {
        size_t n = sizeof(obj) - 1, m = sizeof(mtl) - 1;
        char both[sizeof(obj) + sizeof(mtl)];
        memcpy(both, obj, n);
        both[n] = '\0';
        memcpy(both + n + 1, mtl, m);
        ok = put(dir, "scene.obj", both, n + 1 + m, &count) &&
             put(dir, "no_mtl.obj", obj, n, &count);
    }
    static const char *const bad_obj[][2] = {
        {"obj_index.obj", "# past\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"},
        {"obj_zero.obj", "# zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"},
        {"obj_inf.obj", "# inf\nv 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}};
    for (size_t i = 0; ok && i < sizeof(bad_obj) / sizeof(bad_obj[0]); i++)
        ok = put(dir, bad_obj[i][0], bad_obj[i][1], strlen(bad_obj[i][1]), &count);
    free(glb_buffer);
    free(bj);
    free(uri);
    return ok ? count : -1;
}
