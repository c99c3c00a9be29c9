/* Honest glTF extensions (src/scene/gltf.cpp, dirt_scene_gltf_extensions):
 * an extension of extensionsRequired the loader does not support fails the
 * load with DIRT_SCENE_ERR_UNSUPPORTED and a message naming it (also when
 * what it changes breaks the parse); one of extensionsUsed that is ignored
 * warns once; the supported ones load without a word, KHR_mesh_quantization
 * with its integer attributes read right; doc/scenes.md lists exactly the
 * loader's list. Every file is written here. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/image.h"
#include "integrator/integrator.h"
#include "dirt/scene.h"

#include <stdio.h>
#include <string.h>

#ifndef DIRT_TEST_DOC_DIR
#error "DIRT_TEST_DOC_DIR must name the doc/ folder"
#endif

static char log_text[1 << 16];
static size_t log_len;
static int log_err, log_warn;

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level > DIRT_LOG_WARN)
        return;
    log_err += level == DIRT_LOG_ERROR;
    log_warn += level == DIRT_LOG_WARN;
    int n = snprintf(log_text + log_len, sizeof(log_text) - log_len, "%s %s\n",
                     level == DIRT_LOG_ERROR ? "E" : "W", msg);
    if (n > 0 && (size_t)n < sizeof(log_text) - log_len)
        log_len += (size_t)n;
    fprintf(stderr, "  [%s] %s\n", level == DIRT_LOG_ERROR ? "error" : "warn", msg);
}

static void log_start(void)
{
    dirt_log_set_callback(capture, NULL);
    log_len = 0;
    log_text[0] = '\0';
    log_err = log_warn = 0;
}

/* Captured lines of kind "E" or "W" containing `needle`. */
static int lines_with(char kind, const char *needle)
{
    int n = 0;
    for (const char *p = log_text; *p;) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        char line[2048];
        if (len >= sizeof(line))
            len = sizeof(line) - 1;
        memcpy(line, p, len);
        line[len] = '\0';
        n += line[0] == kind && strstr(line, needle) != NULL;
        p += len + (e ? 1 : 0);
    }
    return n;
}

/* The quad of 4 positions (floats) and 6 uint16 indices, with `extra`
 * top-level members, `prim_extra` primitive members and `buffer` as its
 * buffer JSON (NULL: the embedded data URI). */
static char *quad(const char *extra, const char *prim_extra, const char *buffer)
{
    float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    uint8_t b[60];
    memcpy(b, pos, 48);
    memcpy(b + 48, idx, 12);
    char *uri = data_uri(b, sizeof(b));
    char *bj = buffer ? strf("%s", buffer) : strf("{\"byteLength\":60,\"uri\":\"%s\"}", uri);
    char *j = strf(
        "{\"asset\":{\"version\":\"2.0\"},%s\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":0},\"indices\":1%s}]}],\"buffers\":[%s],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":60}],\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":0,\"byteOffset\":48,\"componentType\":5123,\"count\":6,"
        "\"type\":\"SCALAR\"}]}",
        extra, prim_extra, bj);
    free(uri);
    free(bj);
    return j;
}

static dirt_scene *load_text(const char *name, const char *json)
{
    log_start();
    const char *path = tmp_file(name);
    write_text(path, json);
    return dirt_scene_load(path, NULL);
}

static void expect_unsupported(const char *name, const char *json, const char *const *names,
                               size_t n)
{
    dirt_scene *s = load_text(name, json);
    CHECK_MSG(s == NULL, "%s loaded", name);
    CHECK_MSG(dirt_scene_last_error() == DIRT_SCENE_ERR_UNSUPPORTED, "%s: error %s", name,
              dirt_scene_error_name(dirt_scene_last_error()));
    for (size_t i = 0; i < n; i++)
        CHECK_MSG(lines_with('E', names[i]) >= 1, "%s: no error names %s", name, names[i]);
    dirt_scene_destroy(s);
    /* The same from memory. */
    log_start();
    s = dirt_scene_load_memory(json, strlen(json), name, NULL);
    CHECK_MSG(s == NULL && dirt_scene_last_error() == DIRT_SCENE_ERR_UNSUPPORTED,
              "%s from memory: %s", name, dirt_scene_error_name(dirt_scene_last_error()));
    CHECK(lines_with('E', names[0]) >= 1);
    dirt_scene_destroy(s);
}

static void test_required(void)
{
    /* Draco: the primitive's data is in the extension (here a stand-in). */
    static const char *const draco[] = {"KHR_draco_mesh_compression"};
    char *j = quad("\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
                   "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],",
                   ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":0,"
                   "\"attributes\":{\"POSITION\":0}}}",
                   NULL);
    expect_unsupported("draco.gltf", j, draco, 1);
    free(j);
    /* Two of them, with a supported one between: both named. */
    static const char *const two[] = {"EXT_meshopt_compression", "KHR_texture_basisu"};
    j = quad("\"extensionsRequired\":[\"EXT_meshopt_compression\",\"KHR_lights_punctual\","
             "\"KHR_texture_basisu\",\"EXT_meshopt_compression\"],",
             "", NULL);
    expect_unsupported("two.gltf", j, two, 2);
    CHECK(lines_with('E', "extensions EXT_meshopt_compression, KHR_texture_basisu,") == 1);
    free(j);
    /* What the extension changes breaks the parse (a buffer only its
     * decoder could read): still the extension is the reason given. */
    j = quad("\"extensionsRequired\":[\"EXT_meshopt_compression\"],", "",
             "{\"byteLength\":60,\"uri\":\"compressed-elsewhere.bin\"}");
    expect_unsupported("meshopt_broken.gltf", j, two, 1);
    free(j);
    /* .glb too. */
    j = quad("\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],", "",
             "{\"byteLength\":60}");
    float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    uint8_t bin[60];
    memcpy(bin, pos, 48);
    memcpy(bin + 48, idx, 12);
    uint8_t *glb = NULL;
    size_t n = make_glb(j, bin, sizeof(bin), &glb);
    write_bytes(tmp_file("draco.glb"), glb, n);
    log_start();
    dirt_scene *s = dirt_scene_load(tmp_file("draco.glb"), NULL);
    CHECK(s == NULL && dirt_scene_last_error() == DIRT_SCENE_ERR_UNSUPPORTED);
    CHECK(lines_with('E', "KHR_draco_mesh_compression") >= 1);
    dirt_scene_destroy(s);
    free(glb);
    free(j);
    /* The id has a name and a message of its own. */
    CHECK(strcmp(dirt_scene_error_name(DIRT_SCENE_ERR_UNSUPPORTED), "UNSUPPORTED") == 0);
    CHECK(strstr(dirt_scene_error_str(DIRT_SCENE_ERR_UNSUPPORTED), "extension") != NULL);
}

static void test_used(void)
{
    /* Ignored extensions warn once each (listed twice, and used by a
     * material); supported ones say nothing. */
    char *j = quad("\"extensionsUsed\":[\"KHR_materials_sheen\",\"KHR_lights_punctual\","
                   "\"KHR_materials_sheen\",\"KHR_materials_clearcoat\","
                   "\"KHR_materials_emissive_strength\"],"
                   "\"materials\":[{\"extensions\":{\"KHR_materials_sheen\":"
                   "{\"sheenColorFactor\":[1,1,1]}}}],",
                   ",\"material\":0", NULL);
    dirt_scene *s = load_text("used.gltf", j);
    CHECK(s != NULL && dirt_scene_num_triangles(s) == 2);
    CHECK(lines_with('W', "KHR_materials_sheen") == 1);
    CHECK(lines_with('W', "KHR_materials_clearcoat") == 1);
    CHECK(lines_with('W', "KHR_lights_punctual") == 0);
    CHECK(lines_with('W', "KHR_materials_emissive_strength") == 0);
    CHECK(log_err == 0 && log_warn == 2);
    dirt_scene_destroy(s);
    free(j);
    /* Required and supported: loads quietly. */
    j = quad("\"extensionsUsed\":[\"KHR_lights_punctual\",\"KHR_materials_emissive_strength\"],"
             "\"extensionsRequired\":[\"KHR_lights_punctual\","
             "\"KHR_materials_emissive_strength\"],",
             "", NULL);
    s = load_text("required_ok.gltf", j);
    CHECK(s != NULL && log_err == 0 && log_warn == 0);
    dirt_scene_destroy(s);
    free(j);
}

/* KHR_mesh_quantization: positions as SHORT (not normalized), normals as
 * normalized BYTE, texture coordinates as normalized UNSIGNED_SHORT. */
static void test_quantization(void)
{
    int16_t pos[12] = {0, 0, 0, 300, 0, 0, 300, 200, 0, 0, 200, 0};
    int8_t nrm[16] = {0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0};
    uint16_t uv[8] = {0, 0, 65535, 0, 65535, 65535, 0, 32768};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    /* Positions padded to 8 bytes per vertex (attribute alignment). */
    uint8_t c[32 + 16 + 16 + 12];
    memset(c, 0, sizeof(c));
    for (int v = 0; v < 4; v++)
        memcpy(c + 8 * v, pos + 3 * v, 6);
    memcpy(c + 32, nrm, 16);
    memcpy(c + 48, uv, 16);
    memcpy(c + 64, idx, 12);
    char *uri = data_uri(c, sizeof(c));
    char *j = strf(
        "{\"asset\":{\"version\":\"2.0\"},"
        "\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
        "\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[0.01,0.01,0.01]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
        "\"TEXCOORD_0\":2},\"indices\":3}]}],"
        "\"buffers\":[{\"byteLength\":76,\"uri\":\"%s\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":32,\"byteStride\":8},"
        "{\"buffer\":0,\"byteOffset\":32,\"byteLength\":16,\"byteStride\":4},"
        "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":16},"
        "{\"buffer\":0,\"byteOffset\":64,\"byteLength\":12}],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5122,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5120,\"normalized\":true,\"count\":4,"
        "\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5123,\"normalized\":true,\"count\":4,"
        "\"type\":\"VEC2\"},"
        "{\"bufferView\":3,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}",
        uri);
    dirt_scene *s = load_text("quantized.gltf", j);
    CHECK_MSG(s != NULL, "quantized.gltf: %s", dirt_scene_error_name(dirt_scene_last_error()));
    CHECK(log_err == 0 && log_warn == 0);
    dirt_frame *f = s ? dirt_scene_evaluate(s, 0.0f, NULL) : NULL;
    CHECK(f != NULL);
    if (f) {
        CHECK_NEAR(f->position[1][0], 3.0, 1e-6);   /* 300 * 0.01 */
        CHECK_NEAR(f->position[2][1], 2.0, 1e-6);   /* 200 * 0.01 */
        CHECK_NEAR(f->normal[0][2], 1.0, 1e-6);     /* 127 / 127 */
        CHECK_NEAR(f->uv[1][0], 1.0, 1e-6);         /* 65535 / 65535 */
        CHECK_NEAR(f->uv[5][1], 32768.0 / 65535.0, 1e-6);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);
    free(uri);
    free(j);
}

/* KHR_materials_transmission, _ior, _specular: factors and textures read
 * (the specular colour texture as sRGB, the others linear), invalid values
 * warned and left at the glTF defaults, ior 0 (F0 1) accepted, ior below 1
 * refused; required, they load. */
static void test_materials(void)
{
    uint8_t px[8] = {200, 10, 20, 128, 40, 50, 60, 255};
    CHECK(dirt_write_png_rgba8(tmp_file("mat_ext.png"), 2, 1, px));
    char *j = quad(
        "\"extensionsUsed\":[\"KHR_materials_transmission\",\"KHR_materials_ior\","
        "\"KHR_materials_specular\"],\"extensionsRequired\":[\"KHR_materials_transmission\"],"
        "\"images\":[{\"uri\":\"mat_ext.png\"}],\"textures\":[{\"source\":0}],"
        "\"materials\":["
        "{\"name\":\"glass\",\"extensions\":{"
        "\"KHR_materials_transmission\":{\"transmissionFactor\":0.8,"
        "\"transmissionTexture\":{\"index\":0}},"
        "\"KHR_materials_ior\":{\"ior\":1.33},"
        "\"KHR_materials_specular\":{\"specularFactor\":0.5,\"specularTexture\":{\"index\":0},"
        "\"specularColorFactor\":[2,0.5,0],\"specularColorTexture\":{\"index\":0}}}},"
        "{\"name\":\"bad\",\"extensions\":{"
        "\"KHR_materials_transmission\":{\"transmissionFactor\":2},"
        "\"KHR_materials_ior\":{\"ior\":0.5},"
        "\"KHR_materials_specular\":{\"specularFactor\":\"x\",\"specularColorFactor\":[1,-1,1],"
        "\"specularTexture\":{\"index\":7}}}},"
        "{\"name\":\"specgloss\",\"extensions\":{\"KHR_materials_ior\":{\"ior\":0}}}],",
        ",\"material\":0", NULL);
    dirt_scene *s = load_text("mat_ext.gltf", j);
    CHECK(s != NULL && dirt_scene_num_materials(s) >= 3);
    if (s && dirt_scene_num_materials(s) >= 3) {
        const dirt_material *m = dirt_scene_materials(s);
        CHECK(m[0].transmission == 0.8f && m[0].transmission_tex >= 0);
        CHECK(m[0].ior == 1.33f);
        CHECK(m[0].specular == 0.5f && m[0].specular_tex >= 0);
        CHECK(m[0].specular_color[0] == 2.0f && m[0].specular_color[1] == 0.5f &&
              m[0].specular_color[2] == 0.0f && m[0].specular_color_tex >= 0);
        const dirt_texture *t = dirt_scene_textures(s);
        CHECK(m[0].specular_tex == m[0].transmission_tex && !t[m[0].specular_tex].srgb);
        CHECK(m[0].specular_color_tex != m[0].specular_tex && t[m[0].specular_color_tex].srgb);
        CHECK(m[1].transmission == 0.0f && m[1].ior == 1.5f && m[1].specular == 1.0f &&
              m[1].specular_color[1] == 1.0f && m[1].specular_tex == DIRT_NO_TEXTURE);
        CHECK(m[2].ior == 0.0f);
        /* what the renderer reads: transmission = 0.8 x R, specular = 0.5 x A
         * (texel 0 at uv (0.25, 0.5)) */
        dirt_surface sf;
        dirt_material_surface(&m[0], 1.0f, t, dirt_scene_num_textures(s), 0.25f, 0.5f, &sf);
        CHECK_NEAR(sf.bsdf.transmission, 0.8 * 200.0 / 255.0, 1e-6);
        CHECK_NEAR(sf.bsdf.specular, 0.5 * 128.0 / 255.0, 1e-6);
        CHECK(sf.bsdf.eta == 1.33f);
    }
    CHECK(lines_with('W', "material 'bad'") == 5); /* every warning names it */
    CHECK(lines_with('W', "transmissionFactor") == 1 && lines_with('W', "ior") == 1);
    CHECK(log_err == 0 && log_warn == 5); /* 4 values, texture 7 out of range */
    dirt_scene_destroy(s);
    free(j);
}

/* doc/scenes.md lists, between its gltf-extensions markers, exactly the
 * loader's extensions (as `NAME` at the start of a table row). */
static void test_doc_list(void)
{
    const char *const *list = dirt_scene_gltf_extensions();
    CHECK(list != NULL && list[0] != NULL);
    size_t n = 0;
    while (list && list[n])
        n++;
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes.md", DIRT_TEST_DOC_DIR);
    FILE *f = fopen(path, "r");
    CHECK_MSG(f != NULL, "cannot open %s", path);
    if (!f)
        return;
    char line[1024];
    bool in = false, seen_begin = false, seen_end = false;
    size_t rows = 0;
    int found[64] = {0};
    while (fgets(line, sizeof(line), f)) {
        if (strstr(line, "<!-- gltf-extensions:begin -->")) {
            in = seen_begin = true;
            continue;
        }
        if (strstr(line, "<!-- gltf-extensions:end -->")) {
            in = false;
            seen_end = true;
            continue;
        }
        if (!in || strncmp(line, "| `", 3) != 0)
            continue;
        char *name = line + 3, *end = strchr(name, '`');
        if (!end)
            continue;
        *end = '\0';
        rows++;
        bool known = false;
        for (size_t i = 0; i < n && i < 64; i++) {
            if (!strcmp(list[i], name)) {
                known = true;
                found[i]++;
            }
        }
        CHECK_MSG(known, "doc/scenes.md lists %s, which the loader does not support", name);
    }
    fclose(f);
    CHECK(seen_begin && seen_end);
    for (size_t i = 0; i < n && i < 64; i++)
        CHECK_MSG(found[i] == 1, "doc/scenes.md lists %s %d times (want once)", list[i],
                  found[i]);
    CHECK(rows == n);
}

int main(void)
{
    test_required();
    test_used();
    test_quantization();
    test_materials();
    test_doc_list();
    dirt_log_set_callback(NULL, NULL);
    static const char *const files[] = {"draco.gltf", "two.gltf", "meshopt_broken.gltf",
                                        "draco.glb", "used.gltf", "required_ok.gltf",
                                        "quantized.gltf", "mat_ext.gltf", "mat_ext.png"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    return check_finish();
}
