/* Malformed glTF input must fail cleanly: NULL plus a logged error, never a
 * crash (run it under ASan/UBSan). Missing or undecodable textures only warn.
 * Every file is written by this test (small JSON with base64 data-URI
 * buffers, hand-made .glb containers); ../shared is used only for one extra
 * truncated real .glb when present. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <stb_image_write.h>

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

/* The reference file: a quad of 4 vertices and 2 triangles. Variants below
 * patch one thing each. */
typedef struct variant {
    const char *positions_extra; /* extra POSITION accessor fields */
    int nan_at;                  /* > 0: position component nan_at-1 set to NaN */
    int bad_index;               /* > 0: index value written at position 5 */
    const char *accessor_index;  /* index accessor JSON override (count/offset) */
    const char *nodes;           /* "nodes" JSON array override */
    const char *scene_nodes;     /* scene node list override */
    const char *mesh_extra;      /* extra primitive fields */
    const char *view_length;     /* bufferView byteLength override */
    const char *extra;           /* extra top-level members */
    const char *extra_views;     /* extra bufferViews, each preceded by ',' */
} variant;

#define VARIANT(...) ((variant){__VA_ARGS__})

/* Buffer: 4 positions (48 bytes) then 6 uint16 indices (12 bytes). */
static void quad_buffer(uint8_t out[60], const variant *v)
{
    float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    if (v->nan_at > 0)
        pos[v->nan_at - 1] = NAN;
    if (v->bad_index > 0)
        idx[5] = (uint16_t)v->bad_index;
    memcpy(out, pos, 48);
    memcpy(out + 48, idx, 12);
}

static char *quad_json(const variant *v, const char *buffer_json)
{
    return strf(
        "{\"asset\":{\"version\":\"2.0\"},%s\"scene\":0,\"scenes\":[{\"nodes\":%s}],"
        "\"nodes\":%s,"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1%s}]}],"
        "\"buffers\":[%s],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%s}%s],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"%s},"
        "%s]}",
        v->extra ? v->extra : "", v->scene_nodes ? v->scene_nodes : "[0]",
        v->nodes ? v->nodes : "[{\"mesh\":0}]", v->mesh_extra ? v->mesh_extra : "",
        buffer_json, v->view_length ? v->view_length : "60",
        v->extra_views ? v->extra_views : "",
        v->positions_extra ? v->positions_extra : "",
        v->accessor_index ? v->accessor_index
                          : "{\"bufferView\":0,\"byteOffset\":48,\"componentType\":5123,"
                            "\"count\":6,\"type\":\"SCALAR\"}");
}

/* Writes the variant as a .gltf with an embedded buffer and loads it. */
static dirt_scene *load_variant(const variant *v, const char *name)
{
    uint8_t buf[60];
    quad_buffer(buf, v);
    char *uri = data_uri(buf, sizeof(buf));
    char *bj = strf("{\"byteLength\":60,\"uri\":\"%s\"}", uri);
    char *json = quad_json(v, bj);
    const char *path = tmp_file(name);
    write_text(path, json);
    free(uri);
    free(bj);
    free(json);
    fprintf(stderr, "-- %s\n", name);
    return dirt_scene_load(path, NULL);
}

/* Expects the last load to have failed with id `want` and a logged error. */
#define CHECK_FAILED(s, want, name)                                                      \
    do {                                                                                 \
        enum dirt_scene_error got_ = dirt_scene_last_error();                            \
        CHECK_MSG((s) == NULL, "%s loaded", (name));                                     \
        CHECK_MSG(log_errors_ > 0, "%s: no error logged", (name));                       \
        CHECK_MSG(got_ == (want), "%s: error %s, expected %s", (name),                   \
                  dirt_scene_error_name(got_), dirt_scene_error_name(want));             \
    } while (0)

/* Expects the load to fail with id DIRT_SCENE_ERR_<want> and a logged error. */
static void expect_fail_id(const variant *v, const char *name, enum dirt_scene_error want,
                           const char *why)
{
    log_capture_start();
    dirt_scene *s = load_variant(v, name);
    CHECK_MSG(s == NULL, "%s (%s) loaded", name, why);
    CHECK_FAILED(s, want, name);
    dirt_scene_destroy(s);
}
#define expect_fail(v, name, id, why) expect_fail_id((v), (name), DIRT_SCENE_ERR_##id, (why))

static void test_reference_loads(void)
{
    log_capture_start();
    dirt_scene *s = load_variant(&VARIANT(0), "good.gltf");
    CHECK(s != NULL);
    CHECK(log_errors_ == 0);
    if (s) {
        CHECK(dirt_scene_num_triangles(s) == 2);
        /* No material in the file: the glTF default material is added. */
        CHECK(dirt_scene_num_materials(s) == 1);
        dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
        CHECK(f != NULL);
        if (f) {
            CHECK(f->material[0] == 0 && f->material[1] == 0);
            /* No normals in the file: flat normals (0,0,1) from the CCW quad. */
            CHECK_NEAR(f->normal[0][2], 1.0, 1e-6);
            CHECK_NEAR(f->normal[5][2], 1.0, 1e-6);
            CHECK_NEAR(f->position[4][0], 1.0, 0.0); /* triangle 1 = (0,2,3) */
            CHECK_NEAR(f->position[4][1], 1.0, 0.0);
        }
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);
}

static void test_malformed(void)
{
    expect_fail(&VARIANT(.bad_index = 4), "index_range.gltf", INDEX, "index 4 of 4 vertices");
    expect_fail(&VARIANT(.bad_index = 60000), "index_far.gltf", INDEX, "index 60000");
    expect_fail(&VARIANT(.nan_at = 5), "nan.gltf", NOT_FINITE, "NaN position");
    expect_fail(&VARIANT(.nan_at = 1), "nan0.gltf", NOT_FINITE, "NaN position");
    /* Accessor ranges. */
    expect_fail(&VARIANT(.accessor_index = "{\"bufferView\":0,\"byteOffset\":48,"
                                           "\"componentType\":5123,\"count\":7,"
                                           "\"type\":\"SCALAR\"}"),
                "acc_count.gltf", RANGE, "index accessor runs past its buffer view");
    expect_fail(&VARIANT(.accessor_index = "{\"bufferView\":0,\"byteOffset\":1000,"
                                           "\"componentType\":5123,\"count\":6,"
                                           "\"type\":\"SCALAR\"}"),
                "acc_offset.gltf", RANGE, "accessor offset past its buffer view");
    expect_fail(&VARIANT(.view_length = "600"), "view_length.gltf", TRUNCATED,
                "buffer view longer than its buffer");
    expect_fail(&VARIANT(.view_length = "40"), "view_short.gltf", RANGE,
                "POSITION accessor longer than its buffer view");
    expect_fail(&VARIANT(.accessor_index = "{\"bufferView\":7,\"componentType\":5123,"
                                           "\"count\":6,\"type\":\"SCALAR\"}"),
                "view_ref.gltf", REFERENCE, "bufferView 7 does not exist");
    expect_fail(&VARIANT(.accessor_index = "{\"bufferView\":0,\"byteOffset\":48,"
                                           "\"componentType\":5126,\"count\":3,"
                                           "\"type\":\"SCALAR\"}"),
                "index_float.gltf", TYPE, "float indices");
    /* Node graph. */
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]"),
                "cycle2.gltf", HIERARCHY, "node cycle 0 -> 1 -> 0");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0},{\"children\":[2]},{\"children\":[1]}]"),
                "cycle_detached.gltf", HIERARCHY, "cycle 1 -> 2 -> 1 outside the scene");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"children\":[0]}]"), "cycle_self.gltf", HIERARCHY,
                "node is its own child");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"children\":[2]},{\"children\":[2]},{}]",
                         .scene_nodes = "[0,1]"),
                "two_parents.gltf", HIERARCHY, "node 2 has two parents");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"children\":[5]}]"), "child_ref.gltf", REFERENCE,
                "child 5 does not exist");
    /* References. */
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":3}]"), "mesh_ref.gltf", REFERENCE, "mesh 3");
    expect_fail(&VARIANT(.mesh_extra = ",\"material\":2"), "material_ref.gltf", REFERENCE, "material 2");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"skin\":1}]"), "skin_ref.gltf", REFERENCE, "skin 1");
    expect_fail(&VARIANT(.nodes = "[{\"mesh\":0,\"camera\":0}]"), "camera_ref.gltf", REFERENCE,
                "camera 0");
    expect_fail(&VARIANT(.mesh_extra = ",\"targets\":[{\"POSITION\":9}]"), "acc_ref.gltf", REFERENCE,
                "accessor 9");
    expect_fail(&VARIANT(.scene_nodes = "[4]"), "root_ref.gltf", REFERENCE, "scene root 4");
    expect_fail(&VARIANT(.extra = "\"skins\":[{\"joints\":[7]}],"), "joint_ref.gltf", REFERENCE,
                "skin joint node 7");
    expect_fail(&VARIANT(.extra = "\"animations\":[{\"samplers\":[{\"input\":1,\"output\":0}],"
                                  "\"channels\":[{\"sampler\":0,\"target\":{\"node\":3,"
                                  "\"path\":\"translation\"}}]}],"),
                "anim_node_ref.gltf", REFERENCE, "animation target node 3");
    expect_fail(&VARIANT(.extra = "\"animations\":[{\"samplers\":[{\"input\":1,\"output\":0}],"
                                  "\"channels\":[{\"sampler\":2,\"target\":{\"node\":0,"
                                  "\"path\":\"translation\"}}]}],"),
                "anim_sampler_ref.gltf", REFERENCE, "animation sampler 2");
    /* Skinned instance whose JOINTS_0 exceeds the skin's joint count; the
     * same file with an in-range joint loads. */
    for (int pass = 0; pass < 2; pass++) {
        /* Buffer: quad (60 bytes) + joints 4 x ubyte4 (16) + weights 4 x vec4 (64). */
        uint8_t buf[140];
        quad_buffer(buf, &VARIANT(0));
        for (int v = 0; v < 4; v++) {
            uint8_t j[4] = {(uint8_t)(v == 3 ? (pass == 0 ? 2 : 1) : 0), 0, 0, 0};
            float w[4] = {1, 0, 0, 0};
            memcpy(buf + 60 + 4 * v, j, 4);
            memcpy(buf + 76 + 16 * v, w, 16);
        }
        char *uri = data_uri(buf, sizeof(buf));
        char *json = strf(
            "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0,1]}],"
            "\"nodes\":[{\"mesh\":0,\"skin\":0},{\"children\":[2]},{}],"
            "\"skins\":[{\"joints\":[1,2]}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":2,"
            "\"WEIGHTS_0\":3},\"indices\":1}]}],"
            "\"buffers\":[{\"byteLength\":140,\"uri\":\"%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":140}],"
            "\"accessors\":["
            "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":48,\"componentType\":5123,\"count\":6,"
            "\"type\":\"SCALAR\"},"
            "{\"bufferView\":0,\"byteOffset\":60,\"componentType\":5121,\"count\":4,"
            "\"type\":\"VEC4\"},"
            "{\"bufferView\":0,\"byteOffset\":76,\"componentType\":5126,\"count\":4,"
            "\"type\":\"VEC4\"}]}",
            uri);
        const char *path = tmp_file("joint_range.gltf");
        write_text(path, json);
        free(uri);
        free(json);
        log_capture_start();
        dirt_scene *s = dirt_scene_load(path, NULL);
        if (pass == 0) {
            CHECK_FAILED(s, DIRT_SCENE_ERR_INDEX, "joint 2 of a 2-joint skin");
        } else {
            CHECK_MSG(s != NULL, "joint 1 of a 2-joint skin failed");
            CHECK(s && s->num_instances == 1 && s->instances[0].skin == 0);
        }
        dirt_scene_destroy(s);
    }
    /* Not JSON at all / not glTF. */
    {
        const char *path = tmp_file("garbage.gltf");
        write_text(path, "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {]");
        log_capture_start();
        dirt_scene *s = dirt_scene_load(path, NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_SYNTAX, "garbage.gltf");
        dirt_scene_destroy(s);
        path = tmp_file("empty.gltf");
        write_text(path, "");
        log_capture_start();
        s = dirt_scene_load(path, NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_EMPTY, "empty.gltf");
        dirt_scene_destroy(s);
    }
}

static void test_missing_files(void)
{
    log_capture_start();
    dirt_scene *s = dirt_scene_load("/nonexistent/dir/none.gltf", NULL);
    CHECK_FAILED(s, DIRT_SCENE_ERR_IO, "none.gltf");
    CHECK(strstr(log_last_error_, "none.gltf") != NULL);
    log_capture_start();
    s = dirt_scene_load(tmp_dir(), NULL); /* a directory: refused at once */
    CHECK_FAILED(s, DIRT_SCENE_ERR_NOT_REGULAR, "a directory");
    log_capture_start();
    s = dirt_scene_load(NULL, NULL);
    CHECK_FAILED(s, DIRT_SCENE_ERR_ARGUMENT, "NULL path");
    log_capture_start();
    s = dirt_scene_load("", NULL);
    CHECK_FAILED(s, DIRT_SCENE_ERR_ARGUMENT, "empty path");

    /* External .bin: complete, then truncated, then absent. */
    uint8_t buf[60];
    quad_buffer(buf, &VARIANT(0));
    char *json = quad_json(&VARIANT(0), "{\"byteLength\":60,\"uri\":\"quad.bin\"}");
    write_text(tmp_file("external.gltf"), json);
    free(json);
    write_bytes(tmp_file("quad.bin"), buf, 60);
    log_capture_start();
    s = dirt_scene_load(tmp_file("external.gltf"), NULL);
    CHECK_MSG(s != NULL, "external .bin");
    CHECK(s && dirt_scene_num_triangles(s) == 2);
    dirt_scene_destroy(s);
    write_bytes(tmp_file("quad.bin"), buf, 30);
    log_capture_start();
    s = dirt_scene_load(tmp_file("external.gltf"), NULL);
    CHECK_FAILED(s, DIRT_SCENE_ERR_TRUNCATED, "truncated .bin");
    dirt_scene_destroy(s);
    remove(tmp_file("quad.bin"));
    log_capture_start();
    s = dirt_scene_load(tmp_file("external.gltf"), NULL);
    CHECK_FAILED(s, DIRT_SCENE_ERR_EXTERNAL, "missing .bin");
    dirt_scene_destroy(s);
}

static void test_glb(void)
{
    /* A hand-made .glb of the reference quad (buffer 0 = BIN chunk). */
    uint8_t buf[60];
    quad_buffer(buf, &VARIANT(0));
    char *json = quad_json(&VARIANT(0), "{\"byteLength\":60}");
    uint8_t *glb = NULL;
    size_t n = make_glb(json, buf, sizeof(buf), &glb);
    free(json);
    const char *path = tmp_file("quad.glb");
    write_bytes(path, glb, n);
    log_capture_start();
    dirt_scene *s = dirt_scene_load(path, NULL);
    CHECK_MSG(s != NULL, "hand-made .glb does not load");
    CHECK(s && dirt_scene_num_triangles(s) == 2);
    dirt_scene_destroy(s);

    /* Every truncation must fail: inside the header, the JSON chunk, the BIN
     * chunk header and the BIN data. */
    size_t cuts[] = {3, 11, 19, 40, n - 68, n - 60, n - 30, n - 1};
    for (size_t i = 0; i < sizeof(cuts) / sizeof(cuts[0]); i++) {
        write_bytes(path, glb, cuts[i]);
        log_capture_start();
        s = dirt_scene_load(path, NULL);
        CHECK_MSG(s == NULL, ".glb truncated to %zu of %zu bytes loaded", cuts[i], n);
        /* 3 bytes lack even the magic: JSON that does not parse. */
        CHECK_FAILED(s, cuts[i] < 4 ? DIRT_SCENE_ERR_SYNTAX : DIRT_SCENE_ERR_TRUNCATED,
                     "truncated .glb");
        dirt_scene_destroy(s);
        if (cuts[i] < 20)
            continue;
        /* The same cut with the header's total length patched to match, so
         * that only the chunk lengths tell. */
        uint8_t *cut = malloc(cuts[i]);
        CHECK(cut != NULL);
        if (!cut)
            continue;
        memcpy(cut, glb, cuts[i]);
        put_le32(cut + 8, (uint32_t)cuts[i]);
        write_bytes(path, cut, cuts[i]);
        free(cut);
        log_capture_start();
        s = dirt_scene_load(path, NULL);
        CHECK_MSG(s == NULL, ".glb cut to %zu bytes (length patched) loaded", cuts[i]);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TRUNCATED, "cut .glb, length patched");
        dirt_scene_destroy(s);
    }
    /* A consistent header with a BIN chunk shorter than the buffer. */
    {
        char *j2 = quad_json(&VARIANT(0), "{\"byteLength\":64}");
        uint8_t *g2 = NULL;
        size_t n2 = make_glb(j2, buf, sizeof(buf), &g2);
        write_bytes(path, g2, n2);
        log_capture_start();
        s = dirt_scene_load(path, NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TRUNCATED, ".glb buffer longer than its BIN chunk");
        dirt_scene_destroy(s);
        free(j2);
        free(g2);
    }
    free(glb);

    /* The first half of a real .glb, when ../shared is present. */
    const char *shared = test_shared_dir();
    if (shared) {
        char real[4096];
        snprintf(real, sizeof(real), "%s/scenes/gltf/Fox/Fox.glb", shared);
        FILE *f = fopen(real, "rb");
        CHECK(f != NULL);
        if (f) {
            fseek(f, 0, SEEK_END);
            long len = ftell(f);
            fseek(f, 0, SEEK_SET);
            uint8_t *data = malloc((size_t)len);
            CHECK(data && fread(data, 1, (size_t)len, f) == (size_t)len);
            fclose(f);
            write_bytes(tmp_file("half.glb"), data, (size_t)len / 2);
            log_capture_start();
            s = dirt_scene_load(tmp_file("half.glb"), NULL);
            CHECK_FAILED(s, DIRT_SCENE_ERR_TRUNCATED, "half of Fox.glb");
            dirt_scene_destroy(s);
            free(data);
        }
    }
}

static void png_to_vec(void *ctx, void *data, int size)
{
    char **out = ctx;
    *out = data_uri(data, (size_t)size);
}

/* Materials whose textures are: missing (file absent), not an image, in a
 * buffer view outside its buffer -- all three load with a warning and fall
 * back to the factor -- and a valid 2x2 PNG embedded as a data URI, used as
 * base colour (sRGB) and metallic-roughness (linear): decoded to RGBA8, rows
 * top to bottom as stored. */
static void test_textures(void)
{
    /* Texels: row 0 = red, green; row 1 = blue, white (RGB, no alpha). */
    static const uint8_t rgb[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    char *png_uri = NULL;
    CHECK(stbi_write_png_to_func(png_to_vec, &png_uri, 2, 2, 3, rgb, 6) != 0);
    if (!png_uri)
        return;
    write_text(tmp_file("broken.png"), "this is not a PNG file");
    char *extra = strf(
        "\"materials\":[{\"name\":\"missing\",\"pbrMetallicRoughness\":{"
        "\"baseColorFactor\":[0.5,0.25,1,1],\"baseColorTexture\":{\"index\":0}}},"
        "{\"name\":\"broken\",\"emissiveFactor\":[1,1,1],\"emissiveTexture\":{\"index\":1},"
        "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":5}}},"
        "{\"name\":\"outside\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":2}}},"
        "{\"name\":\"good\",\"doubleSided\":true,\"pbrMetallicRoughness\":{"
        "\"metallicFactor\":0.25,\"roughnessFactor\":0.75,"
        "\"baseColorTexture\":{\"index\":3},\"metallicRoughnessTexture\":{\"index\":3}}}],"
        "\"textures\":[{\"source\":0},{\"source\":1},{\"source\":2},{\"source\":3}],"
        "\"images\":[{\"uri\":\"no_such_image.png\"},{\"uri\":\"broken.png\"},"
        "{\"bufferView\":1,\"mimeType\":\"image/png\"},{\"uri\":\"%s\"}],",
        png_uri);
    free(png_uri);
    log_capture_start();
    dirt_scene *s = load_variant(
        &VARIANT(.extra = extra, .mesh_extra = ",\"material\":1",
                 .extra_views = ",{\"buffer\":0,\"byteOffset\":100000,\"byteLength\":50}"),
        "textures.gltf");
    free(extra);
    CHECK_MSG(s != NULL, "missing texture made the load fail");
    CHECK(log_errors_ == 0);
    CHECK(log_warnings_ >= 3);
    if (s) {
        CHECK(dirt_scene_num_materials(s) == 4);
        const dirt_material *m = dirt_scene_materials(s);
        CHECK(m[0].base_color_tex == DIRT_NO_TEXTURE);
        CHECK_NEAR(m[0].base_color[1], 0.25, 0.0);
        CHECK(m[1].emissive_tex == DIRT_NO_TEXTURE);
        CHECK_NEAR(m[1].emissive_strength, 5.0, 0.0);
        CHECK_NEAR(m[0].emissive_strength, 1.0, 0.0);
        CHECK(m[2].base_color_tex == DIRT_NO_TEXTURE);
        CHECK(s->stats.textures_failed == 3);
        CHECK(m[3].double_sided && !m[0].double_sided);
        CHECK_NEAR(m[3].metallic, 0.25, 0.0);
        CHECK_NEAR(m[3].roughness, 0.75, 0.0);
        /* One image, two colour spaces: two textures. */
        CHECK(dirt_scene_num_textures(s) == 2);
        int bc = m[3].base_color_tex, mr = m[3].metallic_roughness_tex;
        CHECK(bc >= 0 && mr >= 0 && bc != mr && (size_t)bc < dirt_scene_num_textures(s) &&
              (size_t)mr < dirt_scene_num_textures(s));
        if (bc >= 0 && mr >= 0 && bc != mr) {
            const dirt_texture *t = dirt_scene_textures(s);
            CHECK(t[bc].srgb && !t[mr].srgb);
            CHECK(t[bc].width == 2 && t[bc].height == 2);
            static const uint8_t rgba[16] = {255, 0, 0, 255, 0, 255, 0, 255,
                                             0, 0, 255, 255, 255, 255, 255, 255};
            CHECK(memcmp(t[bc].rgba, rgba, 16) == 0);
            CHECK(memcmp(t[mr].rgba, rgba, 16) == 0);
        }
        dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
        CHECK(f && f->material[0] == 1);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);
}

/* Well-formed edge cases that must load: strips and fans become triangle
 * lists, points are skipped, a scene without triangles is empty. */
/* Degenerate scenes load but warn: no triangles at all, or only triangles
 * of zero area; the reference quad does not warn. */
static void test_degenerate(void)
{
    const char *empty = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                        "\"nodes\":[{}]}";
    log_capture_start();
    dirt_scene *s = dirt_scene_load_memory(empty, strlen(empty), "no_triangles.gltf", NULL);
    CHECK(s != NULL && dirt_scene_num_triangles(s) == 0);
    CHECK_MSG(log_warnings_ == 1, "no triangles: %d warnings", log_warnings_);
    dirt_scene_destroy(s);

    /* The quad with every position at the origin: 2 zero-area triangles. */
    uint8_t buf[60];
    quad_buffer(buf, &VARIANT(0));
    memset(buf, 0, 48);
    char *uri = data_uri(buf, sizeof(buf));
    char *bj = strf("{\"byteLength\":60,\"uri\":\"%s\"}", uri);
    char *json = quad_json(&VARIANT(0), bj);
    log_capture_start();
    s = dirt_scene_load_memory(json, strlen(json), "zero_area.gltf", NULL);
    CHECK(s != NULL && dirt_scene_num_triangles(s) == 2);
    CHECK(s && s->stats.zero_area == 2);
    CHECK_MSG(log_warnings_ == 1, "zero-area triangles: %d warnings", log_warnings_);
    dirt_scene_destroy(s);
    free(json);
    free(bj);
    free(uri);

    quad_buffer(buf, &VARIANT(0));
    uri = data_uri(buf, sizeof(buf));
    bj = strf("{\"byteLength\":60,\"uri\":\"%s\"}", uri);
    json = quad_json(&VARIANT(0), bj);
    log_capture_start();
    s = dirt_scene_load_memory(json, strlen(json), "quad.gltf", NULL);
    CHECK(s != NULL && s->stats.zero_area == 0);
    CHECK_MSG(log_warnings_ == 0, "the reference quad: %d warnings", log_warnings_);
    dirt_scene_destroy(s);
    free(json);
    free(bj);
    free(uri);
}

static void test_topologies(void)
{
    /* 5 vertices on a zig-zag; strip: (0,1,2) (2,1,3) (2,3,4); fan: (1,2,0)
     * (2,3,0) (3,4,0); points: skipped. Non-indexed. */
    float pos[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0};
    char *uri = data_uri(pos, sizeof(pos));
    char *json = strf(
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":5},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":6},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":0},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":1}]}],"
        "\"buffers\":[{\"byteLength\":60,\"uri\":\"%s\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":60}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":5,"
        "\"type\":\"VEC3\"}]}",
        uri);
    write_text(tmp_file("topology.gltf"), json);
    free(uri);
    free(json);
    log_capture_start();
    dirt_scene *s = dirt_scene_load(tmp_file("topology.gltf"), NULL);
    CHECK(s != NULL);
    CHECK(log_warnings_ >= 2); /* points and lines skipped */
    if (s) {
        CHECK(dirt_scene_num_triangles(s) == 6);
        CHECK(s->stats.prims_skipped == 2);
        dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
        CHECK(f != NULL);
        if (f) {
            static const int expect[6][3] = {{0, 1, 2}, {2, 1, 3}, {2, 3, 4},
                                             {1, 2, 0}, {2, 3, 0}, {3, 4, 0}};
            for (int t = 0; t < 6; t++) {
                for (int k = 0; k < 3; k++) {
                    const float *p = f->position[3 * t + k];
                    const float *q = &pos[3 * expect[t][k]];
                    CHECK_MSG(p[0] == q[0] && p[1] == q[1] && p[2] == q[2],
                              "triangle %d corner %d", t, k);
                }
                /* The strip's triangles keep one winding (every second one
                 * is flipped back): all three face +z. */
                if (t < 3)
                    CHECK(f->normal[3 * t][2] > 0.99f);
            }
            dirt_frame_destroy(f);
        }
    }
    dirt_scene_destroy(s);

    /* Zero triangles: only points. */
    uri = data_uri(pos, sizeof(pos));
    json = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                "\"nodes\":[{\"mesh\":0}],"
                "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":0}]}],"
                "\"buffers\":[{\"byteLength\":60,\"uri\":\"%s\"}],"
                "\"bufferViews\":[{\"buffer\":0,\"byteLength\":60}],"
                "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":5,"
                "\"type\":\"VEC3\"}]}",
                uri);
    write_text(tmp_file("points.gltf"), json);
    free(uri);
    free(json);
    s = dirt_scene_load(tmp_file("points.gltf"), NULL);
    CHECK(s != NULL);
    if (s) {
        CHECK(dirt_scene_num_triangles(s) == 0);
        dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
        CHECK(f && f->num_triangles == 0 && f->bounds_min[0] == 0.0f);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);

    /* Minimal file: no scenes, no nodes. */
    write_text(tmp_file("minimal.gltf"), "{\"asset\":{\"version\":\"2.0\"}}");
    s = dirt_scene_load(tmp_file("minimal.gltf"), NULL);
    CHECK(s != NULL && dirt_scene_num_triangles(s) == 0);
    dirt_scene_destroy(s);
}

/* Peak resident memory of this process so far, in MB. */
static double peak_rss_mb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024.0; /* Linux: kB */
}

/* The two files of issue 11, made here: 20,000 nested arrays in `extras`
 * (a parser recursion per level: it used to crash), and one POSITION
 * accessor of 2^28 VEC3 elements with no bufferView (it used to grow to
 * 9 GB before failing). Each must fail with its id, quickly, without the
 * memory. Then the limits are settable: a budget or a depth below the
 * reference quad's needs makes it fail, and brackets inside strings do not
 * count. */
static void test_limits(void)
{
    double rss0 = peak_rss_mb();
    clock_t t0 = clock();
    {
        size_t depth = 20000;
        size_t len = 64 + 2 * depth;
        char *json = malloc(len + 128);
        CHECK(json != NULL);
        if (!json)
            return;
        size_t n = (size_t)sprintf(json, "{\"asset\":{\"version\":\"2.0\"},\"extras\":");
        memset(json + n, '[', depth);
        n += depth;
        memset(json + n, ']', depth);
        n += depth;
        n += (size_t)sprintf(json + n, "}");
        write_bytes(tmp_file("deep.gltf"), json, n);
        log_capture_start();
        dirt_scene *s = dirt_scene_load(tmp_file("deep.gltf"), NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_DEEP, "deep.gltf");
        dirt_scene_destroy(s);
        /* The same nesting inside a .glb's JSON chunk, from memory. */
        uint8_t *glb = NULL;
        json[n] = 0;
        size_t gn = make_glb(json, NULL, 0, &glb);
        log_capture_start();
        s = dirt_scene_load_memory(glb, gn, "deep.glb", NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_DEEP, "deep.glb");
        dirt_scene_destroy(s);
        free(glb);
        free(json);
    }
    {
        const char *huge =
            "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
            "\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
            "\"accessors\":[{\"componentType\":5126,\"count\":268435456,\"type\":\"VEC3\","
            "\"min\":[0,0,0],\"max\":[0,0,0]}]}";
        write_text(tmp_file("huge.gltf"), huge);
        log_capture_start();
        dirt_scene *s = dirt_scene_load(tmp_file("huge.gltf"), NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_LARGE, "huge.gltf");
        dirt_scene_destroy(s);
        /* An animation's key times: 2^28 floats (1 GiB), no bufferView. */
        char *idx = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                         "\"nodes\":[{}],\"animations\":[{\"samplers\":[{\"input\":0,"
                         "\"output\":0}],\"channels\":[{\"sampler\":0,\"target\":{"
                         "\"node\":0,\"path\":\"translation\"}}]}],"
                         "\"accessors\":[{\"componentType\":5126,\"count\":%u,"
                         "\"type\":\"SCALAR\",\"min\":[0],\"max\":[0]}]}",
                         1u << 28);
        log_capture_start();
        s = dirt_scene_load_memory(idx, strlen(idx), "huge_keys.gltf", NULL);
        CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_LARGE, "huge_keys.gltf");
        dirt_scene_destroy(s);
        free(idx);
    }
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    double grew = peak_rss_mb() - rss0;
    fprintf(stderr, "crafted files: %.3f s CPU, peak RSS grew %.1f MB\n", secs, grew);
    CHECK_MSG(grew < 200.0, "the crafted files grew the peak RSS by %.1f MB", grew);
    CHECK_MSG(secs < 5.0, "the crafted files took %.1f s", secs);

    /* Settable limits, on the reference quad (4 positions, 6 indices). */
    uint8_t buf[60];
    quad_buffer(buf, &VARIANT(0));
    char *uri = data_uri(buf, sizeof(buf));
    char *bj = strf("{\"byteLength\":60,\"uri\":\"%s\"}", uri);
    char *json = quad_json(&VARIANT(0), bj);
    dirt_load_opts tight = {.max_bytes = 64};
    log_capture_start();
    dirt_scene *s = dirt_scene_load_memory(json, strlen(json), "tight.gltf", &tight);
    CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_LARGE, "quad with a 64-byte budget");
    dirt_scene_destroy(s);
    /* The quad's JSON (about 700 bytes) costs its parsers about 16 KB
     * (doc/scenes.md, "Memory"). */
    dirt_load_opts enough = {.max_bytes = 64 << 10};
    log_capture_start();
    s = dirt_scene_load_memory(json, strlen(json), "enough.gltf", &enough);
    CHECK_MSG(s != NULL, "quad with a 64 KB budget failed (%s)",
              dirt_scene_error_name(dirt_scene_last_error()));
    CHECK(dirt_scene_last_error() == DIRT_SCENE_ERR_OK);
    dirt_scene_destroy(s);
    /* The quad nests 6 deep: {"meshes":[{"primitives":[{"attributes":{ */
    dirt_load_opts shallow = {.max_depth = 5};
    log_capture_start();
    s = dirt_scene_load_memory(json, strlen(json), "shallow.gltf", &shallow);
    CHECK_FAILED(s, DIRT_SCENE_ERR_TOO_DEEP, "quad with max_depth 5");
    dirt_scene_destroy(s);
    /* Brackets inside a string (with an escaped quote) are not nesting. */
    char *strs = strf("{\"asset\":{\"version\":\"2.0\",\"generator\":\"\\\"[[[[[[[[{{{{\"},%s",
                      json + 1);
    dirt_load_opts six = {.max_depth = 6};
    log_capture_start();
    s = dirt_scene_load_memory(strs, strlen(strs), "strings.gltf", &six);
    CHECK_MSG(s != NULL, "brackets inside a string counted as nesting (%s)",
              dirt_scene_error_name(dirt_scene_last_error()));
    dirt_scene_destroy(s);
    free(strs);
    free(json);
    free(bj);
    free(uri);
    /* Every id has a name and a message; out of range is "?". */
    for (int e = 0; e < DIRT_SCENE_NUM_ERRORS; e++)
        CHECK(strcmp(dirt_scene_error_str((enum dirt_scene_error)e), "?") != 0);
    CHECK(strcmp(dirt_scene_error_name(DIRT_SCENE_ERR_TOO_DEEP), "TOO_DEEP") == 0);
    CHECK(strcmp(dirt_scene_error_str(DIRT_SCENE_NUM_ERRORS), "?") == 0);
}

int main(void)
{
    test_limits();
    test_degenerate();
    test_reference_loads();
    test_malformed();
    test_missing_files();
    test_glb();
    test_textures();
    test_topologies();
    dirt_log_set_callback(NULL, NULL);

    static const char *const files[] = {
        "good.gltf", "index_range.gltf", "index_far.gltf", "nan.gltf", "nan0.gltf",
        "acc_count.gltf", "acc_offset.gltf", "view_length.gltf", "view_short.gltf",
        "view_ref.gltf", "index_float.gltf", "cycle2.gltf", "cycle_detached.gltf",
        "cycle_self.gltf", "two_parents.gltf", "child_ref.gltf", "mesh_ref.gltf",
        "material_ref.gltf", "skin_ref.gltf", "camera_ref.gltf", "acc_ref.gltf",
        "root_ref.gltf", "joint_ref.gltf", "anim_node_ref.gltf", "anim_sampler_ref.gltf",
        "joint_range.gltf", "garbage.gltf", "empty.gltf", "external.gltf", "quad.bin",
        "quad.glb", "half.glb", "broken.png", "textures.gltf", "topology.gltf",
        "points.gltf", "minimal.gltf", "deep.gltf", "huge.gltf"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    return check_finish();
}
