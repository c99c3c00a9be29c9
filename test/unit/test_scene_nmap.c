/* Normal maps and KHR_texture_transform in the glTF loader and the scene
 * evaluation (src/scene/gltf.cpp, tangent.c, anim.c), on files written
 * here: a unit quad in the z = 0 plane (normal +z, uv = (x, 1 - y): the
 * image upright, so the bitangent dp/dv is -y) with a normal map.
 * - Without TANGENT: tangents are generated, (1, 0, 0) with handedness -1,
 *   and follow the instances: a node turned 90 degrees about z gives
 *   (0, 1, 0, -1), a node mirrored by scale (-1, 1, 1) gives (-1, 0, 0)
 *   with the handedness flipped to +1.
 * - With TANGENT (0.6, 0.8, 0, 1): the file's tangents, rigidly moved, morphed
 *   by a target's TANGENT deltas at weight 0.5, and skinned by a joint turned
 *   90 degrees about z.
 * - The material: normal texture, scale, and the KHR_texture_transform of
 *   each slot read (offset, rotation, scale; texCoord override); a texCoord
 *   other than 0 warns; the extension, used or required, is supported (no
 *   "ignores" warning, no UNSUPPORTED).
 * - A scene without normal maps and without TANGENT has no tangent array.
 * - OBJ: `norm` is read as a normal map (tangents generated), `map_bump`
 *   warns. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <stb_image_write.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#define TOL 1e-6

static int warn_lines_with(const char *needle);
static char log_buf[1 << 16];
static size_t log_len;

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user;
    fprintf(stderr, "  [log %d] %s:%d: %s\n", (int)level, file ? file : "-", line, msg);
    if (level == DIRT_LOG_WARN || level == DIRT_LOG_ERROR)
        log_len += (size_t)snprintf(log_buf + log_len, sizeof(log_buf) - log_len, "%s\n", msg);
    if (log_len >= sizeof(log_buf))
        log_len = sizeof(log_buf) - 1;
}

static int warn_lines_with(const char *needle)
{
    int n = 0;
    for (const char *p = log_buf; (p = strstr(p, needle)); p += strlen(needle))
        n++;
    return n;
}

/* The buffer: positions, normals, uvs, tangents, indices, morph deltas,
 * joints, weights. */
typedef struct quad_buffer {
    float pos[4][3], nrm[4][3], uv[4][2], tan[4][4];
    uint16_t idx[6];
    float tpos[4][3], ttan[4][3];
    uint8_t joints[4][4];
    float weights[4][4];
} quad_buffer;

static char *quad_buffer_uri(void)
{
    quad_buffer b;
    memset(&b, 0, sizeof(b));
    const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int v = 0; v < 4; v++) {
        b.pos[v][0] = xy[v][0], b.pos[v][1] = xy[v][1];
        b.nrm[v][2] = 1.0f;
        b.uv[v][0] = xy[v][0], b.uv[v][1] = 1.0f - xy[v][1];
        b.tan[v][0] = 0.6f, b.tan[v][1] = 0.8f, b.tan[v][3] = 1.0f;
        b.ttan[v][0] = -0.6f, b.ttan[v][1] = 0.2f;
        b.weights[v][0] = 1.0f;
    }
    const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(b.idx, idx, sizeof(idx));
    _Static_assert(sizeof(quad_buffer) == 380, "packed buffer");
    return data_uri(&b, sizeof(b));
}

/* Accessors and views of quad_buffer (offsets as laid out above). */
static const char *accessors_json =
    "\"bufferViews\":["
    "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":32},"
    "{\"buffer\":0,\"byteOffset\":128,\"byteLength\":64},"
    "{\"buffer\":0,\"byteOffset\":192,\"byteLength\":12},"
    "{\"buffer\":0,\"byteOffset\":204,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":252,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":300,\"byteLength\":16},"
    "{\"buffer\":0,\"byteOffset\":316,\"byteLength\":64}],"
    "\"accessors\":["
    "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
    "\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
    "{\"bufferView\":3,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"},"
    "{\"bufferView\":4,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
    "{\"bufferView\":5,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":6,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":7,\"componentType\":5121,\"count\":4,\"type\":\"VEC4\"},"
    "{\"bufferView\":8,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"}]";

/* A 2 x 2 PNG beside the .gltf files. */
static void write_png(void)
{
    uint8_t px[16] = {128, 128, 255, 255, 200, 100, 230, 255,
                      90, 160, 220, 255, 128, 128, 255, 255};
    CHECK(stbi_write_png(tmp_file("nm.png"), 2, 2, 4, px, 8) != 0);
}

/* Scene A: the quad without TANGENT, three instances; material 0 with a
 * normal map and transforms. `ext` is the extensions line. */
static char *scene_a(const char *ext, const char *buffer)
{
    return strf(
        "{\"asset\":{\"version\":\"2.0\"},%s\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
        "\"nodes\":[{\"mesh\":0},"
        "{\"mesh\":0,\"rotation\":[0,0,0.70710678,0.70710678]},"
        "{\"mesh\":0,\"scale\":[-1,1,1]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
        "\"TEXCOORD_0\":2},\"indices\":4,\"material\":0}]}],"
        "\"images\":[{\"uri\":\"nm.png\"}],\"textures\":[{\"source\":0}],"
        "\"materials\":[{\"name\":\"bumpy\","
        "\"normalTexture\":{\"index\":0,\"scale\":0.75,\"extensions\":{\"KHR_texture_transform\":"
        "{\"offset\":[0.1,0.2],\"rotation\":0.3,\"scale\":[2,3]}}},"
        "\"pbrMetallicRoughness\":{"
        "\"baseColorTexture\":{\"index\":0,\"texCoord\":1,\"extensions\":{\"KHR_texture_transform\":"
        "{\"offset\":[0.5,0],\"texCoord\":0}}},"
        "\"metallicRoughnessTexture\":{\"index\":0,\"texCoord\":1}},"
        "\"emissiveFactor\":[1,1,1],"
        "\"emissiveTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":"
        "{\"scale\":[-1,0.5],\"texCoord\":2}}}}],"
        "\"buffers\":[{\"byteLength\":380,\"uri\":\"%s\"}],%s}",
        ext, buffer, accessors_json);
}

/* Scene B: the quad with TANGENT: rigid (node 0), morphed (mesh 1, weight
 * 0.5), skinned by joint node 3 turned 90 degrees about z (node 2). */
static char *scene_b(const char *buffer, bool normal_map)
{
    return strf(
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],"
        "\"nodes\":[{\"mesh\":0,\"translation\":[5,0,0]},{\"mesh\":1},{\"mesh\":2,\"skin\":0},"
        "{\"rotation\":[0,0,0.70710678,0.70710678]}],"
        "\"skins\":[{\"joints\":[3]}],"
        "\"meshes\":["
        "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2,"
        "\"TANGENT\":3},\"indices\":4,\"material\":0}]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2,"
        "\"TANGENT\":3},\"indices\":4,\"material\":0,"
        "\"targets\":[{\"POSITION\":5,\"TANGENT\":6}]}],\"weights\":[0.5]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2,"
        "\"TANGENT\":3,\"JOINTS_0\":7,\"WEIGHTS_0\":8},\"indices\":4,\"material\":0}]}],"
        "\"images\":[{\"uri\":\"nm.png\"}],\"textures\":[{\"source\":0}],"
        "\"materials\":[{%s}],"
        "\"buffers\":[{\"byteLength\":380,\"uri\":\"%s\"}],%s}",
        normal_map ? "\"normalTexture\":{\"index\":0}" : "\"name\":\"plain\"", buffer,
        accessors_json);
}

static void check_tangent(const dirt_frame *f, size_t tri, double x, double y, double z,
                          double w, const char *what)
{
    for (int k = 0; k < 3; k++) {
        const float *t = f->tangent[3 * tri + k];
        CHECK_MSG(fabs(t[0] - x) <= TOL && fabs(t[1] - y) <= TOL && fabs(t[2] - z) <= TOL &&
                      t[3] == (float)w,
                  "%s: triangle %zu vertex %d tangent (%.7f %.7f %.7f %g), expected "
                  "(%.7f %.7f %.7f %g)", what, tri, k, t[0], t[1], t[2], t[3], x, y, z, w);
    }
}

static void test_generated(const char *buffer)
{
    char *json = scene_a("\"extensionsUsed\":[\"KHR_texture_transform\"],", buffer);
    write_text(tmp_file("gen.gltf"), json);
    free(json);
    log_len = 0;
    log_buf[0] = '\0';
    dirt_scene *s = dirt_scene_load(tmp_file("gen.gltf"), NULL);
    CHECK(s != NULL);
    if (!s)
        return;
    CHECK(warn_lines_with("ignores") == 0); /* the extension is supported */
    /* base colour's textureInfo texCoord 1 is overridden by the transform's
     * 0; metallic-roughness (1) and emissive (override 2) warn. */
    CHECK_MSG(warn_lines_with("uses TEXCOORD_") == 2, "%d TEXCOORD warnings",
              warn_lines_with("uses TEXCOORD_"));
    CHECK(warn_lines_with("baseColorTexture uses") == 0);
    CHECK(dirt_scene_num_materials(s) == 1);
    const dirt_material *m = &dirt_scene_materials(s)[0];
    CHECK(m->normal_tex >= 0 && m->normal_scale == 0.75f);
    const dirt_tex_transform *n = &m->xf[DIRT_SLOT_NORMAL], *b = &m->xf[DIRT_SLOT_BASE_COLOR],
                             *e = &m->xf[DIRT_SLOT_EMISSIVE];
    CHECK(n->set && n->offset[0] == 0.1f && n->offset[1] == 0.2f && n->rotation == 0.3f &&
          n->scale[0] == 2.0f && n->scale[1] == 3.0f);
    CHECK(b->set && b->offset[0] == 0.5f && b->offset[1] == 0.0f && b->rotation == 0.0f &&
          b->scale[0] == 1.0f && b->scale[1] == 1.0f);
    CHECK(e->set && e->scale[0] == -1.0f && e->scale[1] == 0.5f && e->offset[0] == 0.0f);
    CHECK(!m->xf[DIRT_SLOT_METALLIC_ROUGHNESS].set);
    /* A normal map is linear: its texture is not the sRGB base colour's. */
    CHECK(m->normal_tex != m->base_color_tex && !dirt_scene_textures(s)[m->normal_tex].srgb);

    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f && f->num_triangles == 6 && f->tangent != NULL);
    if (f && f->tangent) {
        check_tangent(f, 0, 1, 0, 0, -1, "generated");
        check_tangent(f, 1, 1, 0, 0, -1, "generated");
        check_tangent(f, 2, 0, 1, 0, -1, "turned 90 degrees");
        check_tangent(f, 4, -1, 0, 0, 1, "mirrored");
        check_tangent(f, 5, -1, 0, 0, 1, "mirrored");
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);

    /* Required: supported, the load succeeds. */
    json = scene_a("\"extensionsUsed\":[\"KHR_texture_transform\"],"
                   "\"extensionsRequired\":[\"KHR_texture_transform\"],", buffer);
    write_text(tmp_file("req.gltf"), json);
    free(json);
    s = dirt_scene_load(tmp_file("req.gltf"), NULL);
    CHECK(s != NULL && dirt_scene_last_error() == DIRT_SCENE_ERR_OK);
    dirt_scene_destroy(s);
}

static void test_file_tangents(const char *buffer)
{
    char *json = scene_b(buffer, true);
    write_text(tmp_file("tan.gltf"), json);
    free(json);
    dirt_scene *s = dirt_scene_load(tmp_file("tan.gltf"), NULL);
    CHECK(s != NULL);
    if (!s)
        return;
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f && f->num_triangles == 6 && f->tangent != NULL);
    if (f && f->tangent) {
        check_tangent(f, 0, 0.6, 0.8, 0, 1, "TANGENT, translated");
        /* (0.6, 0.8, 0) + 0.5 (-0.6, 0.2, 0) = (0.3, 0.9, 0), normalised. */
        double l = sqrt(0.09 + 0.81);
        check_tangent(f, 2, 0.3 / l, 0.9 / l, 0, 1, "morphed");
        /* Turned 90 degrees about z: (x, y) -> (-y, x). */
        check_tangent(f, 4, -0.8, 0.6, 0, 1, "skinned");
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);

    /* No normal map: the file's tangents are still kept. */
    json = scene_b(buffer, false);
    write_text(tmp_file("plain_tan.gltf"), json);
    free(json);
    s = dirt_scene_load(tmp_file("plain_tan.gltf"), NULL);
    CHECK(s != NULL);
    f = s ? dirt_scene_evaluate(s, 0.0f, NULL) : NULL;
    CHECK(f && f->tangent != NULL && dirt_scene_materials(s)[0].normal_tex == DIRT_NO_TEXTURE);
    if (f && f->tangent)
        check_tangent(f, 0, 0.6, 0.8, 0, 1, "TANGENT without a normal map");
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
}

/* Neither a normal map nor TANGENT: no tangent array; the default scene
 * likewise. */
static void test_none(const char *buffer)
{
    char *json = strf(
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{"
        "\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":4}]}],"
        "\"buffers\":[{\"byteLength\":380,\"uri\":\"%s\"}],%s}", buffer, accessors_json);
    write_text(tmp_file("none.gltf"), json);
    free(json);
    dirt_scene *s = dirt_scene_load(tmp_file("none.gltf"), NULL);
    dirt_frame *f = s ? dirt_scene_evaluate(s, 0.0f, NULL) : NULL;
    CHECK(f && f->tangent == NULL);
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
    s = dirt_scene_create_default();
    f = s ? dirt_scene_evaluate(s, 0.0f, NULL) : NULL;
    CHECK(f && f->tangent == NULL);
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
}

/* OBJ: `norm` is a tangent-space normal map (its -bm the scale), tangents
 * are generated (vt (x, y) is stored as (x, 1 - y): tangent +x, handedness
 * -1); `map_bump` (a height map) only warns. */
static void test_obj(void)
{
    write_text(tmp_file("nm.mtl"), "newmtl bumpy\nKd 0.5 0.5 0.5\nnorm -bm 0.5 nm.png\n"
                                   "map_bump nm.png\n");
    write_text(tmp_file("nm.obj"), "mtllib nm.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                   "usemtl bumpy\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    log_len = 0;
    log_buf[0] = '\0';
    dirt_scene *s = dirt_scene_load(tmp_file("nm.obj"), NULL);
    CHECK(s != NULL);
    if (!s)
        return;
    const dirt_material *m = &dirt_scene_materials(s)[0];
    CHECK(m->normal_tex >= 0 && m->normal_scale == 0.5f &&
          !dirt_scene_textures(s)[m->normal_tex].srgb);
    CHECK(warn_lines_with("map_bump (height) maps ignored") == 1);
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f && f->num_triangles == 2 && f->tangent);
    if (f && f->tangent) {
        check_tangent(f, 0, 1, 0, 0, -1, "OBJ");
        check_tangent(f, 1, 1, 0, 0, -1, "OBJ");
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
}

/* The generator on its own: a quad whose uvs are (y, x) (tangent +y,
 * bitangent +x = -cross(n, t): handedness -1) and one with degenerate uvs
 * (every vertex (0.5, 0.5): no tangent, (0, 0, 0, 1)). */
static void test_generator(void)
{
    float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    float uv[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    scene_prim p = {.num_vertices = 4, .position = pos, .uv = uv, .num_triangles = 2,
                    .indices = idx};
    CHECK(scene_prim_generate_tangents(&p) && p.tangent);
    for (int v = 0; v < 4 && p.tangent; v++)
        CHECK_MSG(fabsf(p.tangent[v][0]) < TOL && fabsf(p.tangent[v][1] - 1.0f) < TOL &&
                      p.tangent[v][2] == 0.0f && p.tangent[v][3] == -1.0f,
                  "vertex %d: (%g %g %g %g)", v, p.tangent[v][0], p.tangent[v][1],
                  p.tangent[v][2], p.tangent[v][3]);
    free(p.tangent);
    p.tangent = NULL;
    for (int v = 0; v < 4; v++)
        uv[v][0] = uv[v][1] = 0.5f;
    CHECK(scene_prim_generate_tangents(&p) && p.tangent);
    for (int v = 0; v < 4 && p.tangent; v++)
        CHECK(p.tangent[v][0] == 0.0f && p.tangent[v][1] == 0.0f && p.tangent[v][2] == 0.0f &&
              p.tangent[v][3] == 1.0f);
    free(p.tangent);
    p.tangent = NULL;
    p.uv = NULL;
    CHECK(scene_prim_generate_tangents(&p) && !p.tangent);
}

int main(void)
{
    dirt_log_set_callback(capture, NULL);
    write_png();
    char *buffer = quad_buffer_uri();
    test_generated(buffer);
    test_file_tangents(buffer);
    test_none(buffer);
    test_obj();
    test_generator();
    free(buffer);
    static const char *const files[] = {"nm.png", "gen.gltf", "req.gltf", "tan.gltf",
                                        "plain_tan.gltf", "none.gltf", "nm.mtl", "nm.obj"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    return check_finish();
}
