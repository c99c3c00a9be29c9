/* dirt_scene_print_info: the summary of the default scene, line for line,
 * and of a small written glTF with every kind of camera and light and one
 * animation clip. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The summary as one malloc'd string, NULL when printing failed. */
static char *info_text(const dirt_scene *s)
{
    FILE *f = tmpfile();
    if (!f)
        return NULL;
    bool ok = dirt_scene_print_info(s, f);
    long n = ftell(f);
    char *text = ok && n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (text) {
        rewind(f);
        size_t got = fread(text, 1, (size_t)n, f);
        text[got] = '\0';
    }
    fclose(f);
    return text;
}

/* Compares the summary line by line with `expected` (NULL-terminated). */
static void check_lines(const char *what, const char *text, const char *const *expected)
{
    const char *p = text;
    size_t i = 0;
    for (; expected[i]; i++) {
        const char *eol = p ? strchr(p, '\n') : NULL;
        if (!eol) {
            CHECK_MSG(false, "%s: line %zu missing, expected '%s'", what, i + 1, expected[i]);
            return;
        }
        size_t len = (size_t)(eol - p);
        CHECK_MSG(len == strlen(expected[i]) && memcmp(p, expected[i], len) == 0,
                  "%s: line %zu is\n  '%.*s'\nexpected\n  '%s'", what, i + 1, (int)len, p,
                  expected[i]);
        p = eol + 1;
    }
    CHECK_MSG(p && *p == '\0', "%s: extra lines after line %zu: '%s'", what, i, p);
}

static void check_default(void)
{
    static const char *const expected[] = {
        "scene      'default'",
        "triangles  1478",
        "meshes     6 (8 primitives, 6 instances)",
        "nodes      7",
        "materials  6",
        "textures   0",
        "emitters   2 triangles, 1 emissive material",
        "cameras    1",
        "  0  'default'  perspective  yfov 70 deg  aspect of the image  near 0.01  far 100  "
        "node 6 'camera'",
        "lights     0",
        "clips      0",
        "bounds     (-1, 0, -1) .. (1, 2, 1), size 2 x 2 x 2 (rest pose)",
        NULL,
    };
    dirt_scene *s = dirt_scene_create_default();
    CHECK(s != NULL);
    if (!s)
        return;
    char *text = info_text(s);
    CHECK(text != NULL);
    if (text) {
        fputs(text, stderr);
        check_lines("default scene", text, expected);
    }
    free(text);
    dirt_scene_destroy(s);
}

/* One triangle moving +2 in x over a 2 s clip, two cameras, three lights. */
static void check_small(void)
{
    static const float bin[] = {
        0, 0, 0, 1, 0, 0, 0, 1, 0, /* positions */
        0, 2,                      /* key times */
        0, 0, 0, 2, 0, 0,          /* translations */
    };
    char *uri = data_uri(bin, sizeof(bin));
    char *json = strf(
        "{\"asset\":{\"version\":\"2.0\"},"
        "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
        "{\"name\":\"sun\",\"type\":\"directional\",\"color\":[1,0.5,0.25],\"intensity\":3},"
        "{\"name\":\"bulb\",\"type\":\"point\",\"intensity\":40,\"range\":5},"
        "{\"name\":\"lamp\",\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.5,"
        "\"outerConeAngle\":0.75}}]}},"
        "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
        "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":8},"
        "{\"buffer\":0,\"byteOffset\":44,\"byteLength\":24}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\","
        "\"min\":[0],\"max\":[2]},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}],"
        "\"meshes\":[{\"name\":\"tri\",\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"cameras\":[{\"name\":\"wide\",\"type\":\"perspective\",\"perspective\":"
        "{\"yfov\":0.5,\"aspectRatio\":1.5,\"znear\":0.1}},"
        "{\"name\":\"plan\",\"type\":\"orthographic\",\"orthographic\":"
        "{\"xmag\":2,\"ymag\":1,\"znear\":0.01,\"zfar\":10}}],"
        "\"nodes\":[{\"name\":\"mover\",\"mesh\":0},{\"name\":\"cam_a\",\"camera\":0},"
        "{\"name\":\"cam_b\",\"camera\":1},"
        "{\"name\":\"l0\",\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"name\":\"l1\",\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
        "{\"name\":\"l2\",\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}],"
        "\"animations\":[{\"name\":\"slide\",\"samplers\":[{\"input\":1,\"output\":2}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}],"
        "\"scenes\":[{\"nodes\":[0,1,2,3,4,5]}]}",
        sizeof(bin), uri);
    static const char *const expected[] = {
        "scene      'small'",
        "triangles  1",
        "meshes     1 (1 primitive, 1 instance)",
        "nodes      6",
        "materials  1",
        "textures   0",
        "emitters   0 triangles, 0 emissive materials",
        "cameras    2",
        "  0  'wide'  perspective  yfov 28.65 deg  aspect 1.5  near 0.1  far infinite  "
        "node 1 'cam_a'",
        "  1  'plan'  orthographic  xmag 2  ymag 1  near 0.01  far 10  node 2 'cam_b'",
        "lights     3",
        "  0  'sun'  directional  colour (1, 0.5, 0.25)  intensity 3 lx  node 3 'l0'",
        "  1  'bulb'  point  colour (1, 1, 1)  intensity 40 cd  range 5  node 4 'l1'",
        "  2  'lamp'  spot  colour (1, 1, 1)  intensity 1 cd  range infinite  "
        "cone 28.65..42.97 deg  node 5 'l2'",
        "clips      1",
        "  0  'slide'  2 s  1 channel  bounds (0, 0, 0) .. (3, 1, 0), size 3 x 1 x 0",
        "bounds     (0, 0, 0) .. (1, 1, 0), size 1 x 1 x 0 (rest pose)",
        NULL,
    };
    write_text(tmp_file("small.gltf"), json);
    dirt_scene *s = dirt_scene_load(tmp_file("small.gltf"), NULL);
    CHECK(s != NULL);
    if (s) {
        char *text = info_text(s);
        CHECK(text != NULL);
        if (text) {
            fputs(text, stderr);
            check_lines("small scene", text, expected);
        }
        free(text);
        dirt_scene_destroy(s);
    }
    free(json);
    free(uri);
    static const char *const names[] = {"small.gltf"};
    tmp_cleanup(names, 1);
}

int main(void)
{
    check_default();
    check_small();
    CHECK(!dirt_scene_print_info(NULL, stderr)); /* logs an error */
    return check_finish();
}
