/* A small glTF scene with alpha-tested planes, written by the test into a
 * temporary directory and loaded from there (the files are removed again):
 * a white floor (y = 0, x -3..3, z -2..5: its edges out of the camera's
 * view) and a grey back wall (z = -2), a 1 x 1 emitter
 * under y = 2.9 facing down, a red double-sided MASK plane at z = 0
 * (x -1.2..0.2, y 0.2..1.8, cutoff 0.4, an 8 x 8 texture of 2 x 2 blocks
 * alternately opaque and transparent, repeated twice) and a green BLEND
 * plane at z = 0.6 (x 0..1.5, y 0.3..1.5, alpha factor 0.6 times a 4 x 4
 * texture whose alpha grows 40, 100, 160, 220 along u); the camera at
 * (0, 1.2, 4) looks along -z. `opaque`: the same scene with both planes
 * OPAQUE (the alpha test's effect). */
#ifndef DIRT_TEST_ALPHA_SCENE_H
#define DIRT_TEST_ALPHA_SCENE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dirt/image.h"
#include "dirt/scene.h"

static inline dirt_scene *alpha_scene_load(bool opaque)
{
    char dir[] = "/tmp/dirt_alpha_scene_XXXXXX";
    if (!mkdtemp(dir))
        return NULL;
    enum { QUADS = 5 };
    static const float q[QUADS][4][3] = {
        {{-3, 0, 5}, {3, 0, 5}, {3, 0, -2}, {-3, 0, -2}},             /* floor, +y */
        {{-3, 0, -2}, {3, 0, -2}, {3, 3, -2}, {-3, 3, -2}},           /* back wall, +z */
        {{-0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, -0.5f}, {0.5f, 2.9f, 0.5f}, {-0.5f, 2.9f, 0.5f}},
        {{-1.2f, 0.2f, 0}, {0.2f, 0.2f, 0}, {0.2f, 1.8f, 0}, {-1.2f, 1.8f, 0}}, /* MASK */
        {{0, 0.3f, 0.6f}, {1.5f, 0.3f, 0.6f}, {1.5f, 1.5f, 0.6f}, {0, 1.5f, 0.6f}}, /* BLEND */
    };
    static const float nrm[QUADS][3] = {{0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, 1}, {0, 0, 1}};
    /* UVs of the corners (glTF: v down): the mask repeats twice. */
    static const float uvs[QUADS][4][2] = {
        {{0, 1}, {1, 1}, {1, 0}, {0, 0}}, {{0, 1}, {1, 1}, {1, 0}, {0, 0}},
        {{0, 1}, {1, 1}, {1, 0}, {0, 0}}, {{0, 2}, {2, 2}, {2, 0}, {0, 0}},
        {{0, 1}, {1, 1}, {1, 0}, {0, 0}}};
    /* Buffer: per quad 4 positions, 4 normals, 4 uvs, then 6 uint16 indices. */
    uint8_t bin[QUADS * (4 * 12 + 4 * 12 + 4 * 8 + 12)];
    size_t off = 0;
    for (int k = 0; k < QUADS; k++) {
        memcpy(bin + off, q[k], 48);
        off += 48;
        for (int v = 0; v < 4; v++, off += 12)
            memcpy(bin + off, nrm[k], 12);
        memcpy(bin + off, uvs[k], 32);
        off += 32;
        static const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
        memcpy(bin + off, idx, 12);
        off += 12;
    }
    char path[256];
    snprintf(path, sizeof(path), "%s/alpha.bin", dir);
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(bin, 1, sizeof(bin), f) == sizeof(bin);
    if (f)
        fclose(f);
    uint8_t mask[8 * 8 * 4], ramp[4 * 4 * 4];
    for (int j = 0; j < 8; j++) {
        for (int i = 0; i < 8; i++) {
            uint8_t *p = mask + 4 * (j * 8 + i);
            p[0] = p[1] = p[2] = 255;
            p[3] = ((i / 2 + j / 2) % 2 == 0) ? 255 : 0;
        }
    }
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 4; i++) {
            uint8_t *p = ramp + 4 * (j * 4 + i);
            p[0] = p[1] = p[2] = 255;
            p[3] = (uint8_t)(40 + 60 * i);
        }
    }
    char mpath[256], rpath[256], gpath[256];
    snprintf(mpath, sizeof(mpath), "%s/mask.png", dir);
    snprintf(rpath, sizeof(rpath), "%s/ramp.png", dir);
    ok = ok && dirt_write_png_rgba8(mpath, 8, 8, mask) && dirt_write_png_rgba8(rpath, 4, 4, ramp);
    /* Accessors: per quad k, views 4k (positions), 4k+1 (normals), 4k+2
     * (uvs), 4k+3 (indices). */
    char views[4096] = "", accs[8192] = "", prims[2048] = "";
    size_t vl = 0, al = 0, pl = 0;
    off = 0;
    for (int k = 0; k < QUADS; k++) {
        static const int sizes[4] = {48, 48, 32, 12};
        for (int c = 0; c < 4; c++) {
            vl += (size_t)snprintf(views + vl, sizeof(views) - vl,
                                   "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%d}",
                                   k || c ? "," : "", off, sizes[c]);
            off += (size_t)sizes[c];
        }
        float lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
            lo[a] = hi[a] = q[k][0][a];
            for (int v = 1; v < 4; v++) {
                lo[a] = q[k][v][a] < lo[a] ? q[k][v][a] : lo[a];
                hi[a] = q[k][v][a] > hi[a] ? q[k][v][a] : hi[a];
            }
        }
        al += (size_t)snprintf(
            accs + al, sizeof(accs) - al,
            "%s{\"bufferView\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
            "\"min\":[%g,%g,%g],\"max\":[%g,%g,%g]},"
            "{\"bufferView\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
            "{\"bufferView\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
            "{\"bufferView\":%d,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}",
            k ? "," : "", 4 * k, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], 4 * k + 1, 4 * k + 2,
            4 * k + 3);
        pl += (size_t)snprintf(prims + pl, sizeof(prims) - pl,
                               "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d},"
                               "\"indices\":%d,\"material\":%d}",
                               k ? "," : "", 4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3, k);
    }
    char json[20000];
    snprintf(json, sizeof(json),
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],"
             "\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
             "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0,1.2,4]}],"
             "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,"
             "\"znear\":0.01}}],"
             "\"meshes\":[{\"primitives\":[%s]}],"
             "\"materials\":["
             "{\"name\":\"floor\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.8,0.8,1],"
             "\"metallicFactor\":0,\"roughnessFactor\":1}},"
             "{\"name\":\"wall\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.6,0.7,1],"
             "\"metallicFactor\":0,\"roughnessFactor\":0.5}},"
             "{\"name\":\"light\",\"emissiveFactor\":[1,0.9,0.8],\"extensions\":"
             "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":6}},"
             "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0}},"
             "{\"name\":\"mask\",%s\"doubleSided\":true,\"pbrMetallicRoughness\":"
             "{\"baseColorFactor\":[0.9,0.2,0.1,1],\"baseColorTexture\":{\"index\":0},"
             "\"metallicFactor\":0,\"roughnessFactor\":0.6}},"
             "{\"name\":\"blend\",%s\"pbrMetallicRoughness\":"
             "{\"baseColorFactor\":[0.1,0.8,0.2,0.6],\"baseColorTexture\":{\"index\":1},"
             "\"metallicFactor\":0,\"roughnessFactor\":0.3}}],"
             "\"textures\":[{\"source\":0},{\"source\":1}],"
             "\"images\":[{\"uri\":\"mask.png\"},{\"uri\":\"ramp.png\"}],"
             "\"accessors\":[%s],\"bufferViews\":[%s],"
             "\"buffers\":[{\"uri\":\"alpha.bin\",\"byteLength\":%zu}]}",
             prims, opaque ? "" : "\"alphaMode\":\"MASK\",\"alphaCutoff\":0.4,",
             opaque ? "" : "\"alphaMode\":\"BLEND\",", accs, views, sizeof(bin));
    snprintf(gpath, sizeof(gpath), "%s/alpha.gltf", dir);
    f = ok ? fopen(gpath, "wb") : NULL;
    ok = f && fwrite(json, 1, strlen(json), f) == strlen(json);
    if (f)
        fclose(f);
    dirt_scene *s = ok ? dirt_scene_load(gpath, NULL) : NULL;
    remove(gpath);
    remove(path);
    remove(mpath);
    remove(rpath);
    rmdir(dir);
    return s;
}

#endif
