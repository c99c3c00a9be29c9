/* OBJ + MTL scenes (src/scene/obj.cpp): the MTL -> metallic-roughness
 * mapping of doc/scenes.md value by value, textures (map_Kd, '\' paths,
 * missing maps), polygons (n corners -> n - 2 triangles in file order, a
 * concave one cut into ears), normals from the file or flat, UVs flipped to
 * glTF's origin, loads from memory, and bad files: every one fails cleanly
 * with its id (or, for what is only unsupported, warns once). Every file is
 * written here; ../shared is used for CornellBox-Original.obj. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <stb_image_write.h>

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#define PI 3.14159265358979323846

/* Every message of the load in progress, one per line ("E " / "W "). */
static char log_text[1 << 17];
static size_t log_len;
static int log_err, log_warn;

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level == DIRT_LOG_ERROR)
        log_err++;
    else if (level == DIRT_LOG_WARN)
        log_warn++;
    else
        return;
    int n = snprintf(log_text + log_len, sizeof(log_text) - log_len, "%s %s\n",
                     level == DIRT_LOG_ERROR ? "E" : "W", msg);
    if (n > 0 && (size_t)n < sizeof(log_text) - log_len)
        log_len += (size_t)n;
    fprintf(stderr, "  [%s] %s\n", level == DIRT_LOG_ERROR ? "error" : "warn", msg);
}

static void quiet(void *user, enum dirt_log_level level, const char *file, int line,
                  const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

static void log_start(void)
{
    dirt_log_set_callback(capture, NULL);
    log_len = 0;
    log_text[0] = '\0';
    log_err = log_warn = 0;
}

/* Lines of the captured log (of kind "E"/"W", or any: NULL) containing
 * `needle`. */
static int log_lines_with(const char *kind, const char *needle)
{
    int n = 0;
    const char *p = log_text;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        char line[2048];
        if (len >= sizeof(line))
            len = sizeof(line) - 1;
        memcpy(line, p, len);
        line[len] = '\0';
        if ((!kind || line[0] == kind[0]) && strstr(line, needle))
            n++;
        p += len + (e ? 1 : 0);
    }
    return n;
}

#define CHECK_FAILED(s, want, name)                                                      \
    do {                                                                                 \
        enum dirt_scene_error got_ = dirt_scene_last_error();                            \
        CHECK_MSG((s) == NULL, "%s loaded", (name));                                     \
        CHECK_MSG(log_err > 0, "%s: no error logged", (name));                           \
        CHECK_MSG(got_ == DIRT_SCENE_ERR_##want, "%s: error %s, expected %s", (name),    \
                  dirt_scene_error_name(got_), #want);                                   \
    } while (0)

static const dirt_material *find_material(const dirt_scene *s, const char *name)
{
    for (size_t i = 0; i < dirt_scene_num_materials(s); i++) {
        if (!strcmp(dirt_scene_materials(s)[i].name, name))
            return &dirt_scene_materials(s)[i];
    }
    return NULL;
}

static float roughness_of_ns(float ns)
{
    return powf(2.0f / (ns + 2.0f), 0.25f);
}

/* ---- the mapping -------------------------------------------------------- */

static const char mapping_mtl[] =
    "# materials for test_scene_obj\n"
    "newmtl diffuse\n  Kd 0.5 0.25 0.125\n  Ks 0 0 0\n  Ns 100\n  illum 2\n  Ni 1.0\n"
    "newmtl glossy\n  Kd 0.2 0.2 0.2\n  Ks 0.5 0.5 0.5\n  Ns 98\n  illum 2\n"
    "newmtl mirror\n  Kd 0 0 0\n  Ks 0.9 0.8 0.7\n  Ns 1000\n  illum 3\n"
    "newmtl pbr\n  Kd 1 1 1\n  Pr 0\n  Pm 1\n"
    "newmtl matte\n  Kd 0.3 0.3 0.3\n  Ks 1 1 1\n  Ns 50\n  illum 1\n"
    "newmtl noillum\n  Kd 0.3 0.3 0.3\n  Ks 1 1 1\n  Ns 50\n"
    "newmtl lamp\r\n  Kd 0.78 0.78 0.78\r\n  Ke 17 12 4\r\n"
    "newmtl textured\n  map_Kd tex.png\n"
    "newmtl tinted\n\tKd 0.5 0.5 0.5\n\tmap_Kd sub\\tex2.png\n"
    "newmtl glass\n  Kd 1 1 1\n  illum 7\n  d 0.5\n  map_bump nm.png\n"
    "newmtl glass2\n  Kd 1 1 1\n  illum 4\n  Tr 0.5\n  Ni 1.33\n  Tf 0.5 0.8 1\n"
    "newmtl missing\n  Kd 0.5 0.5 0.5\n  map_Kd nothere.png\n  Xy 1 2 3\n";

/* A quad per material (corners 1..4 of z = 0, UVs, one normal), a triangle
 * without normals, and a face of a material no library defines. */
static const char mapping_obj[] =
    "# test_scene_obj mapping\n"
    "mtllib mapping.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.25 0.75\n"
    "vn 0 0 1\n"
    "g first\n"
    "usemtl diffuse\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "usemtl glossy\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "usemtl mirror\nf 1//1 2//1 3//1\n"
    "usemtl pbr\nf 1 2 3\n"
    "o second\n"
    "usemtl matte\nf 1 2 3\n"
    "usemtl noillum\nf 1 2 3\n"
    "usemtl lamp\nf 1 2 3\n"
    "usemtl textured\nf 1/1 2/2 3/3\n"
    "usemtl tinted\nf 1 2 3\n"
    "usemtl glass\nf 1 2 3\n"
    "usemtl glass2\nf 1 2 3\n"
    "usemtl missing\nf 1 2 3\n"
    "usemtl nosuch\nf 1 2 5\n"
    "usemtl diffuse\nf 2 1 5\n"
    "l 1 2\n";

static void write_png(const char *path, int w, int h, uint8_t seed)
{
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < w * h * 4; i++)
        px[i] = (uint8_t)(seed + 17 * i);
    CHECK(stbi_write_png(path, w, h, 4, px, w * 4) != 0);
}

static void test_mapping(void)
{
    write_text(tmp_file("mapping.mtl"), mapping_mtl);
    write_text(tmp_file("mapping.obj"), mapping_obj);
    write_png(tmp_file("tex.png"), 2, 2, 10);
    mkdir(tmp_file("sub"), 0755);
    write_png(tmp_file("sub/tex2.png"), 4, 1, 90);

    log_start();
    dirt_scene *s = dirt_scene_load(tmp_file("mapping.obj"), NULL);
    CHECK_MSG(s != NULL, "mapping.obj failed: %s", dirt_scene_error_name(dirt_scene_last_error()));
    if (!s)
        return;
    CHECK(log_err == 0);
    CHECK(dirt_scene_last_error() == DIRT_SCENE_ERR_OK);
    CHECK(strcmp(dirt_scene_name(s), "mapping") == 0);
    /* 2 quads (4 triangles) + 12 triangles. */
    CHECK_MSG(dirt_scene_num_triangles(s) == 16, "%zu triangles", dirt_scene_num_triangles(s));
    CHECK(dirt_scene_num_materials(s) == 13); /* 12 + the default one */
    CHECK(dirt_scene_num_cameras(s) == 0 && dirt_scene_num_lights(s) == 0);
    CHECK(dirt_scene_num_clips(s) == 0 && dirt_scene_num_nodes(s) == 1);

    const dirt_material *m = find_material(s, "diffuse");
    CHECK(m && m->base_color[0] == 0.5f && m->base_color[1] == 0.25f &&
          m->base_color[2] == 0.125f && m->base_color[3] == 1.0f);
    CHECK(m && m->metallic == 0.0f && m->roughness == 1.0f); /* Ks black: no highlight */
    CHECK(m && m->emissive[0] == 0.0f && m->base_color_tex == DIRT_NO_TEXTURE);
    CHECK(m && !m->double_sided && m->emissive_strength == 1.0f);
    m = find_material(s, "glossy");
    CHECK(m && m->metallic == 0.0f && m->base_color[0] == 0.2f);
    CHECK(m && fabsf(m->roughness - roughness_of_ns(98)) < 1e-6f);
    m = find_material(s, "mirror");
    CHECK(m && m->metallic == 1.0f && m->base_color[0] == 0.9f && m->base_color[1] == 0.8f &&
          m->base_color[2] == 0.7f);
    CHECK(m && fabsf(m->roughness - roughness_of_ns(1000)) < 1e-6f);
    m = find_material(s, "pbr");
    CHECK(m && m->metallic == 1.0f && m->roughness == 0.0f && m->base_color[0] == 1.0f);
    m = find_material(s, "matte");
    CHECK(m && m->metallic == 0.0f && m->roughness == 1.0f); /* illum 1 */
    m = find_material(s, "noillum");
    CHECK(m && fabsf(m->roughness - roughness_of_ns(50)) < 1e-6f); /* read as illum 2 */
    m = find_material(s, "lamp");
    CHECK(m && m->emissive[0] == 17.0f && m->emissive[1] == 12.0f && m->emissive[2] == 4.0f);
    CHECK(m && m->base_color[0] == 0.78f && m->emissive_tex == DIRT_NO_TEXTURE);
    m = find_material(s, "textured");
    CHECK(m && m->base_color[0] == 1.0f && m->base_color_tex >= 0); /* map alone */
    if (m && m->base_color_tex >= 0) {
        const dirt_texture *t = &dirt_scene_textures(s)[m->base_color_tex];
        CHECK(t->width == 2 && t->height == 2 && t->srgb && t->rgba[0] == 10 &&
              t->rgba[1] == 27 && strcmp(t->name, "tex.png") == 0);
    }
    m = find_material(s, "tinted");
    CHECK(m && m->base_color[0] == 0.5f && m->base_color_tex >= 0);
    if (m && m->base_color_tex >= 0) {
        const dirt_texture *t = &dirt_scene_textures(s)[m->base_color_tex];
        CHECK(t->width == 4 && t->height == 1 && t->rgba[0] == 90);
    }
    m = find_material(s, "missing");
    CHECK(m && m->base_color_tex == DIRT_NO_TEXTURE && m->base_color[0] == 0.5f);
    CHECK(dirt_scene_num_textures(s) == 2);
    CHECK(s->stats.textures_failed == 1);
    m = find_material(s, "default");
    CHECK(m && m->base_color[0] == 0.8f && m->metallic == 0.0f && m->roughness == 1.0f);

    /* Glass (illum 4, 6, 7, 9): transmission 1 of index Ni (when stated),
     * tinted by Tf (when stated); an opaque material keeps ior 1.5 whatever
     * its Ni. */
    m = find_material(s, "glass");
    CHECK(m && m->transmission == 1.0f && m->ior == 1.5f && m->metallic == 0.0f &&
          m->base_color[0] == 1.0f && m->base_color[2] == 1.0f);
    m = find_material(s, "glass2");
    CHECK(m && m->transmission == 1.0f && m->ior == 1.33f && m->base_color[0] == 0.5f &&
          m->base_color[1] == 0.8f && m->base_color[2] == 1.0f);
    m = find_material(s, "diffuse");
    CHECK(m && m->transmission == 0.0f && m->ior == 1.5f);
    /* What has no place in the model warns once per kind, naming it. */
    /* Glass is transmission, no warning of its illum; its d / Tr is not
     * also coverage (warned once, naming the first); other materials' d / Tr
     * are BLEND coverage (test_scene_alpha). */
    CHECK(log_lines_with("W", "illum 7") == 0);
    CHECK(log_lines_with("W", "illum 4") == 0);
    CHECK(log_lines_with("W", "d / Tr") == 1);
    CHECK(log_lines_with("W", "2 materials, first 'glass'") == 1);
    m = find_material(s, "glass");
    CHECK(m && m->alpha_mode == DIRT_ALPHA_OPAQUE && m->base_color[3] == 1.0f);
    m = find_material(s, "glass2");
    CHECK(m && m->alpha_mode == DIRT_ALPHA_OPAQUE && m->base_color[3] == 1.0f);
    CHECK(log_lines_with("W", "bump") == 1);
    CHECK(log_lines_with("W", "nothere.png") == 1);
    /* An unknown statement is warned about, never quoted (issue 23). */
    CHECK(log_lines_with("W", "unknown MTL statements ignored") == 1);
    CHECK(log_lines_with("W", "Xy") == 0);
    CHECK(log_lines_with("W", "nosuch") == 1);
    CHECK(log_lines_with("W", "1 line and 0 point elements ignored") == 1);

    /* Triangles in file order, each of its face's material; normals from
     * the file or flat; UVs with v flipped. */
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f != NULL);
    if (f) {
        static const char *const order[] = {
            "diffuse", "diffuse", "glossy", "glossy", "mirror", "pbr", "matte",
            "noillum", "lamp", "textured", "tinted", "glass", "glass2", "missing",
            "default", "diffuse"};
        size_t tri = 0;
        for (size_t k = 0; k < sizeof(order) / sizeof(order[0]) && tri < f->num_triangles; k++) {
            const dirt_material *want = find_material(s, order[k]);
            CHECK_MSG(want && f->material[tri] == (uint32_t)(want - dirt_scene_materials(s)),
                      "triangle %zu: material %u, expected '%s'", tri, f->material[tri],
                      order[k]);
            tri++;
        }
        /* The first quad: fan (1,2,3), (1,3,4); normal (0,0,1) from vn. */
        CHECK(f->position[0][0] == 0.0f && f->position[1][0] == 1.0f && f->position[2][1] == 1.0f);
        CHECK(f->position[5][0] == 0.0f && f->position[5][1] == 1.0f);
        CHECK(f->normal[0][2] == 1.0f);
        /* vt 0.25 0.75 (corner 4 of the quad = corner 2 of triangle 1) -> (0.25, 0.25). */
        CHECK(f->uv[5][0] == 0.25f && f->uv[5][1] == 0.25f);
        CHECK(f->uv[1][0] == 1.0f && f->uv[1][1] == 1.0f); /* vt 1 0 -> (1, 1) */
        /* The last triangle, (2, 1, 5) without normals: flat, cross order. */
        size_t last = f->num_triangles - 1;
        CHECK(f->normal[3 * last][0] == 0.0f && f->normal[3 * last][1] == 1.0f &&
              f->normal[3 * last][2] == 0.0f);
        CHECK(f->uv[3 * last][0] == 0.0f && f->uv[3 * last][1] == 0.0f);
        dirt_frame_destroy(f);
    }
    CHECK(dirt_scene_print_info(s, stderr));
    dirt_scene_destroy(s);

    /* The same files as "MAPPING.OBJ": the loader goes by the extension in
     * any case. */
    write_text(tmp_file("MAPPING.OBJ"), mapping_obj);
    log_start();
    s = dirt_scene_load(tmp_file("MAPPING.OBJ"), NULL);
    CHECK(s && dirt_scene_num_triangles(s) == 16);
    dirt_scene_destroy(s);
}

/* ---- polygons ----------------------------------------------------------- */

static double signed_area_z(const float a[3], const float b[3], const float c[3])
{
    return 0.5 * (((double)b[0] - a[0]) * ((double)c[1] - a[1]) -
                  ((double)b[1] - a[1]) * ((double)c[0] - a[0]));
}

static void test_polygons(void)
{
    /* A concave pentagon (a notch at corner 4: a fan from corner 1 would
     * fold over it), a convex hexagon, a 255-gon (the most a face may have)
     * with every corner on a circle, all in z = 0, counter-clockwise. */
    char *obj = strf("v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\n"
                     "f 1 2 3 4 5\n");
    size_t len = strlen(obj);
    char buf[65536];
    memcpy(buf, obj, len);
    free(obj);
    for (int k = 0; k < 6; k++)
        len += (size_t)sprintf(buf + len, "v %.6f %.6f 0\n", 10 + cos(k * PI / 3),
                               sin(k * PI / 3));
    len += (size_t)sprintf(buf + len, "f -6 -5 -4 -3 -2 -1\n");
    for (int k = 0; k < 255; k++)
        len += (size_t)sprintf(buf + len, "v %.6f %.6f 0\n", 20 + cos(k * 2 * PI / 255),
                               sin(k * 2 * PI / 255));
    len += (size_t)sprintf(buf + len, "f");
    for (int k = 0; k < 255; k++)
        len += (size_t)sprintf(buf + len, " %d", 12 + k);
    len += (size_t)sprintf(buf + len, "\n");
    log_start();
    dirt_scene *s = dirt_scene_load_memory(buf, len, "polygons.obj", NULL);
    CHECK(s != NULL);
    if (!s)
        return;
    CHECK_MSG(dirt_scene_num_triangles(s) == 3 + 4 + 253, "%zu triangles",
              dirt_scene_num_triangles(s));
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f != NULL);
    if (f) {
        double area[3] = {0, 0, 0};
        size_t first[4] = {0, 3, 7, 260}, folded = 0;
        for (int p = 0; p < 3; p++) {
            for (size_t t = first[p]; t < first[p + 1] && t < f->num_triangles; t++) {
                double a = signed_area_z(f->position[3 * t], f->position[3 * t + 1],
                                         f->position[3 * t + 2]);
                folded += a <= 0.0;
                area[p] += a;
                /* Flat normals (no vn): +z, the polygon's side. */
                CHECK(f->normal[3 * t][2] > 0.99f);
            }
        }
        CHECK_MSG(folded == 0, "%zu triangles folded over", folded);
        CHECK_NEAR(area[0], 10.0, 1e-9);
        CHECK_NEAR(area[1], 1.5 * sqrt(3.0), 1e-4);
        CHECK_NEAR(area[2], 0.5 * 255 * sin(2 * PI / 255), 1e-4);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);
}

/* ---- bad files ---------------------------------------------------------- */

static const char quad_v[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n";

static dirt_scene *load_obj_text(const char *name, const char *body)
{
    log_start();
    char *text = strf("%s%s", quad_v, body);
    dirt_scene *s = dirt_scene_load_memory(text, strlen(text), name, NULL);
    free(text);
    return s;
}

#define EXPECT_FAIL(name, body, id)                                                      \
    do {                                                                                 \
        dirt_scene *s_ = load_obj_text(name, body);                                      \
        CHECK_FAILED(s_, id, name);                                                      \
        dirt_scene_destroy(s_);                                                          \
    } while (0)

static void test_bad(void)
{
    EXPECT_FAIL("past.obj", "f 1 2 5\n", INDEX);
    EXPECT_FAIL("relative.obj", "f -7 1 2\n", INDEX);
    EXPECT_FAIL("zero.obj", "f 0 1 2\n", INDEX);
    EXPECT_FAIL("normal.obj", "f 1//1 2//1 3//9\n", INDEX);
    EXPECT_FAIL("uv.obj", "f 1/1 2/1 3/2\n", INDEX);
    EXPECT_FAIL("inf.obj", "v 1e999 0 0\nf 1 2 5\n", NOT_FINITE);
    /* An unused non-finite vertex is no reason to fail. */
    dirt_scene *s = load_obj_text("inf_unused.obj", "v 1e999 0 0\nf 1 2 3\n");
    CHECK(s && dirt_scene_num_triangles(s) == 1);
    dirt_scene_destroy(s);
    /* 256 corners: more than tinyobjloader's 8-bit corner count holds. */
    char *big = strf("f");
    for (int k = 0; k < 256; k++) {
        char *b = strf("%s %d", big, 1 + k % 4);
        free(big);
        big = b;
    }
    char *b2 = strf("%s\n", big);
    EXPECT_FAIL("256.obj", b2, INVALID);
    free(big);
    free(b2);

    log_start();
    s = dirt_scene_load_memory("", 0, "empty.obj", NULL);
    CHECK_FAILED(s, EMPTY, "empty.obj");
    log_start();
    s = dirt_scene_load(tmp_file("nothere.obj"), NULL);
    CHECK_FAILED(s, IO, "nothere.obj");
    log_start();
    s = dirt_scene_load_obj_memory(NULL, 5, NULL, 0, "null.obj", NULL);
    CHECK_FAILED(s, ARGUMENT, "null.obj");

    /* A budget too small for the triangles. */
    char *text = strf("%sf 1 2 3 4\n", quad_v);
    log_start();
    s = dirt_scene_load_memory(text, strlen(text), "tight.obj", &(dirt_load_opts){.max_bytes = 64});
    CHECK_FAILED(s, TOO_LARGE, "tight.obj");
    log_start();
    s = dirt_scene_load_memory(text, strlen(text), "enough.obj",
                               &(dirt_load_opts){.max_bytes = 4096});
    CHECK(s && dirt_scene_num_triangles(s) == 2);
    dirt_scene_destroy(s);
    free(text);

    /* A missing MTL library and an unknown material only warn: the faces
     * get the default material. */
    write_text(tmp_file("nomtl.obj"), "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "usemtl red\nf 1 2 3\n");
    log_start();
    s = dirt_scene_load(tmp_file("nomtl.obj"), NULL);
    CHECK(s && dirt_scene_num_triangles(s) == 1 && dirt_scene_num_materials(s) == 1);
    CHECK(s && !strcmp(dirt_scene_materials(s)[0].name, "default"));
    CHECK(log_err == 0 && log_lines_with("W", "absent.mtl") >= 1);
    dirt_scene_destroy(s);

    /* Tag lines (subdivision creases) cost tinyobjloader up to 8192 values
     * each (about 330 KB for "t c 8192/8192/8192"), copied into every group
     * after them; they are skipped, so 60 of them before 10 groups stay
     * cheap (unskipped: about 200 MB). */
    size_t cap = 60 * 24 + 10 * 24 + 256, n = 0;
    char *tags = malloc(cap);
    n += (size_t)sprintf(tags, "%s", quad_v);
    for (int k = 0; k < 60; k++)
        n += (size_t)sprintf(tags + n, "t c 8192/8192/8192\n");
    for (int k = 0; k < 10; k++)
        n += (size_t)sprintf(tags + n, "g g%d\nf 1 2 3\n", k);
    struct rusage ru0, ru1;
    getrusage(RUSAGE_SELF, &ru0);
    clock_t c0 = clock();
    log_start();
    s = dirt_scene_load_memory(tags, n, "tags.obj", NULL);
    double secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
    getrusage(RUSAGE_SELF, &ru1);
    CHECK(s && dirt_scene_num_triangles(s) == 10);
    CHECK_MSG(secs < 2.0, "tag lines took %.2f s", secs);
    CHECK_MSG(ru1.ru_maxrss - ru0.ru_maxrss < 50 * 1024, "tag lines grew the peak RSS by %ld KB",
              ru1.ru_maxrss - ru0.ru_maxrss);
    dirt_scene_destroy(s);
    free(tags);

    /* Every prefix of a valid file, and bytes flipped in it: a scene or a
     * failure with an id, never a crash (ASan sees the rest). */
    char *good = strf("%s%s", mapping_obj, "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1 5/1/1\n");
    size_t glen = strlen(good);
    dirt_log_set_callback(quiet, NULL);
    int loaded = 0, failed = 0, no_id = 0;
    for (size_t cut = 0; cut <= glen; cut++) {
        dirt_scene *p = dirt_scene_load_obj_memory(good, cut, mapping_mtl, strlen(mapping_mtl),
                                                   "prefix.obj", NULL);
        if (p)
            loaded++;
        else if (dirt_scene_last_error() == DIRT_SCENE_ERR_OK)
            no_id++;
        else
            failed++;
        dirt_scene_destroy(p);
    }
    uint32_t rng = 12345;
    char *mut = malloc(glen);
    char *mtl = strf("%s", mapping_mtl);
    size_t mlen = strlen(mtl);
    char *mmut = malloc(mlen);
    static const char junk[] = "0123456789/-+. \n\tfvntle#\\";
    for (int k = 0; k < 2000; k++) {
        memcpy(mut, good, glen);
        memcpy(mmut, mtl, mlen);
        for (int j = 0; j < 4; j++) {
            rng = rng * 1664525u + 1013904223u;
            size_t at = (rng >> 8) % glen;
            rng = rng * 1664525u + 1013904223u;
            mut[at] = (rng >> 24) & 1 ? junk[(rng >> 8) % (sizeof(junk) - 1)] : (char)(rng >> 16);
            rng = rng * 1664525u + 1013904223u;
            at = (rng >> 8) % mlen;
            mmut[at] = junk[(rng >> 16) % (sizeof(junk) - 1)];
        }
        dirt_scene *p = dirt_scene_load_obj_memory(mut, glen, mmut, mlen, "mutant.obj", NULL);
        if (p) {
            loaded++;
            dirt_frame *f = dirt_scene_evaluate(p, 0.0f, NULL);
            CHECK(f && f->num_triangles == dirt_scene_num_triangles(p));
            dirt_frame_destroy(f);
        } else if (dirt_scene_last_error() == DIRT_SCENE_ERR_OK) {
            no_id++;
        } else {
            failed++;
        }
        dirt_scene_destroy(p);
    }
    fprintf(stderr, "prefixes and mutants: %d load, %d fail\n", loaded, failed);
    CHECK(no_id == 0);
    CHECK(loaded > 100 && failed > 100);
    free(mut);
    free(mmut);
    free(mtl);
    free(good);
}

/* ---- from memory -------------------------------------------------------- */

static void test_memory(void)
{
    /* dirt_scene_load_memory with a ".obj" name: OBJ text; mtllib cannot be
     * read (a warning, the default material). */
    log_start();
    dirt_scene *s = dirt_scene_load_memory(mapping_obj, strlen(mapping_obj), "mem.obj", NULL);
    CHECK(s && dirt_scene_num_triangles(s) == 16 && dirt_scene_num_materials(s) == 1);
    CHECK(log_lines_with("W", "mapping.mtl") >= 1);
    CHECK(s && !strcmp(dirt_scene_name(s), "mem"));
    dirt_scene_destroy(s);
    /* With the MTL text: its materials; map_Kd cannot be read from memory
     * (one warning for the three materials that have one). */
    log_start();
    s = dirt_scene_load_obj_memory(mapping_obj, strlen(mapping_obj), mapping_mtl,
                                   strlen(mapping_mtl), "mem2.obj", NULL);
    CHECK(s && dirt_scene_num_materials(s) == 13 && dirt_scene_num_textures(s) == 0);
    const dirt_material *m = s ? find_material(s, "mirror") : NULL;
    CHECK(m && m->metallic == 1.0f);
    CHECK(log_lines_with("W", "map_Kd cannot be read by a scene loaded from memory") == 1);
    CHECK(log_lines_with("W", "3 materials") >= 1);
    dirt_scene_destroy(s);
    /* A glTF name still means glTF. */
    log_start();
    s = dirt_scene_load_memory(mapping_obj, strlen(mapping_obj), "mem.gltf", NULL);
    CHECK_FAILED(s, SYNTAX, "OBJ text named .gltf");
}

/* ---- the shared Cornell box --------------------------------------------- */

/* Triangles of an OBJ counted from its text: n - 2 per "f" line of n
 * corners (independent of the loader). */
static size_t count_obj_triangles(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[4096];
    size_t tris = 0;
    while (fgets(line, sizeof(line), f)) {
        const char *p = line + strspn(line, " \t");
        if (p[0] != 'f' || (p[1] != ' ' && p[1] != '\t'))
            continue;
        int corners = 0;
        char *save = NULL;
        for (char *t = strtok_r((char *)p + 1, " \t\r\n", &save); t;
             t = strtok_r(NULL, " \t\r\n", &save))
            corners++;
        if (corners >= 3)
            tris += (size_t)corners - 2;
    }
    fclose(f);
    return tris;
}

static void test_shared(void)
{
    const char *shared = test_shared_dir();
    if (!shared) {
        fprintf(stderr, "no shared assets (DIRT_SHARED_DIR): Cornell box skipped\n");
        return;
    }
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox-Original.obj", shared);
    size_t want = count_obj_triangles(path);
    CHECK_MSG(want == 36, "CornellBox-Original.obj: %zu triangles counted", want);
    log_start();
    dirt_scene *s = dirt_scene_load(path, NULL);
    CHECK_MSG(s != NULL, "cannot load %s", path);
    if (!s)
        return;
    CHECK(log_err == 0 && log_warn == 0);
    CHECK_MSG(dirt_scene_num_triangles(s) == want, "%zu triangles, the file has %zu",
              dirt_scene_num_triangles(s), want);
    CHECK(dirt_scene_num_materials(s) == 8);
    const dirt_material *light = find_material(s, "light");
    CHECK(light && light->emissive[0] == 17.0f && light->emissive[1] == 12.0f &&
          light->emissive[2] == 4.0f);
    size_t emissive = 0;
    for (size_t i = 0; i < dirt_scene_num_materials(s); i++)
        emissive += dirt_scene_materials(s)[i].emissive[0] > 0.0f;
    CHECK(emissive == 1);
    const dirt_material *left = find_material(s, "leftWall");
    CHECK(left && left->base_color[0] == 0.63f && left->metallic == 0.0f &&
          left->roughness == 1.0f);
    /* The light faces down (-y), into the box: it emits from its front. */
    dirt_frame *f = dirt_scene_evaluate(s, 0.0f, NULL);
    CHECK(f != NULL);
    for (size_t t = 0; f && t < f->num_triangles; t++) {
        if (f->material[t] == (uint32_t)(light - dirt_scene_materials(s)))
            CHECK(f->normal[3 * t][1] < -0.99f);
    }
    CHECK(f && f->bounds_min[1] == 0.0f && f->bounds_max[1] == 1.99f);
    dirt_frame_destroy(f);
    dirt_scene_destroy(s);
}

int main(void)
{
    test_mapping();
    test_polygons();
    test_bad();
    test_memory();
    test_shared();
    dirt_log_set_callback(NULL, NULL);
    static const char *const files[] = {"mapping.mtl", "mapping.obj", "MAPPING.OBJ", "tex.png",
                                        "sub/tex2.png", "sub", "nomtl.obj"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    return check_finish();
}
