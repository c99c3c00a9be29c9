/* What a scene may read (issue 23): regular files only (a FIFO, a device, a
 * directory fail at once, as the scene, a buffer, an image, an MTL library
 * or a texture map), references confined to the scene's folder ("..",
 * absolute paths, symbolic links out fail with OUTSIDE unless
 * allow_outside), no message echoing a file's bytes, strict loading
 * (every warning fails), glTF 1.0 and unknown formats refused, OBJ indices
 * past 32 bits and nan/inf coordinates, and the list of files a load read.
 * Every file is made here. A hang fails the test (alarm). */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"

#include <signal.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Every log line, to check that none carries a file's secret. */
static char log_all_[1 << 16];
static size_t log_len_;
static int errors_, warnings_;

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user, (void)file, (void)line;
    errors_ += level == DIRT_LOG_ERROR;
    warnings_ += level == DIRT_LOG_WARN;
    size_t n = strlen(msg);
    if (log_len_ + n + 2 < sizeof(log_all_)) {
        memcpy(log_all_ + log_len_, msg, n);
        log_len_ += n;
        log_all_[log_len_++] = '\n';
        log_all_[log_len_] = 0;
    }
    fprintf(stderr, "  [%s] %s\n", level == DIRT_LOG_ERROR ? "error" : "warn", msg);
}

static void log_reset(void)
{
    log_len_ = 0;
    log_all_[0] = 0;
    errors_ = warnings_ = 0;
}

static const char *err_name(void)
{
    return dirt_scene_error_name(dirt_scene_last_error());
}

/* Loads `path` with `opts`, expecting failure with `want` (or success when
 * want is DIRT_SCENE_ERR_OK); returns the scene on success. */
static dirt_scene *expect(const char *path, const dirt_load_opts *opts, enum dirt_scene_error want,
                          const char *what)
{
    log_reset();
    fprintf(stderr, "-- %s\n", what);
    dirt_scene *s = dirt_scene_load(path, opts);
    enum dirt_scene_error got = dirt_scene_last_error();
    if (want == DIRT_SCENE_ERR_OK) {
        CHECK_MSG(s != NULL, "%s: failed (%s)", what, err_name());
    } else {
        CHECK_MSG(s == NULL, "%s: loaded", what);
        CHECK_MSG(got == want, "%s: error %s, expected %s", what, err_name(),
                  dirt_scene_error_name(want));
        CHECK_MSG(errors_ > 0, "%s: no error logged", what);
        dirt_scene_destroy(s);
        s = NULL;
    }
    return s;
}

/* A one-triangle glTF in `dir` whose buffer is `buffer_uri` (44 bytes: 3
 * positions, 3 uint16 indices + padding) and, when `image_uri` is given,
 * whose base colour texture is that image. */
static void tri_gltf(const char *path, const char *buffer_uri, const char *image_uri,
                     const char *extra)
{
    char *img = image_uri ? strf(",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":"
                                 "{\"index\":0}}}],\"textures\":[{\"source\":0}],\"images\":"
                                 "[{\"uri\":\"%s\"}]", image_uri)
                          : strf("%s", "");
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},%s\"scenes\":[{\"nodes\":[0]}],"
                   "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                   "{\"POSITION\":0},\"indices\":1%s}]}],\"buffers\":[{\"byteLength\":44,"
                   "\"uri\":\"%s\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
                   "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],\"accessors\":["
                   "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
                   "\"min\":[0,0,0],\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5123,"
                   "\"count\":3,\"type\":\"SCALAR\"}]%s}",
                   extra ? extra : "", image_uri ? ",\"material\":0" : "", buffer_uri, img);
    write_text(path, j);
    free(j);
    free(img);
}

static void tri_bin(const char *path)
{
    uint8_t buf[44] = {0};
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[3] = {0, 1, 2};
    memcpy(buf, pos, 36);
    memcpy(buf + 36, idx, 6);
    write_bytes(path, buf, sizeof(buf));
}

static void png(const char *path)
{
    uint8_t px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 255};
    if (!stbi_write_png(path, 2, 2, 4, px, 8))
        exit(1);
}

static char scene_dir[600], outside_dir[600];

static const char *in_scene(const char *name)
{
    static char b[4][800];
    static int k;
    char *p = b[k++ & 3];
    snprintf(p, 800, "%s/%s", scene_dir, name);
    return p;
}

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "a load blocked (a FIFO?): the test hangs\n";
    ssize_t w = write(2, msg, sizeof(msg) - 1);
    (void)w;
    _exit(1);
}

static void test_special_files(void)
{
    /* The scene: a FIFO (no writer: opening it would block), /dev/zero
     * (endless), a directory. */
    mkfifo(in_scene("fifo.gltf"), 0600);
    alarm(20);
    expect(in_scene("fifo.gltf"), NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a FIFO as the scene");
    expect("/dev/zero", NULL, DIRT_SCENE_ERR_NOT_REGULAR, "/dev/zero as the scene");
    expect(scene_dir, NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a directory as the scene");
    /* A FIFO as a buffer, an image, an MTL library, a texture map. */
    mkfifo(in_scene("fifo.bin"), 0600);
    tri_gltf(in_scene("fifo_buffer.gltf"), "fifo.bin", NULL, NULL);
    expect(in_scene("fifo_buffer.gltf"), NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a FIFO as a buffer");
    tri_bin(in_scene("tri.bin"));
    mkfifo(in_scene("fifo.png"), 0600);
    tri_gltf(in_scene("fifo_image.gltf"), "tri.bin", "fifo.png", NULL);
    expect(in_scene("fifo_image.gltf"), NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a FIFO as an image");
    mkfifo(in_scene("fifo.mtl"), 0600);
    write_text(in_scene("fifo_mtl.obj"), "mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("fifo_mtl.obj"), NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a FIFO as an mtllib");
    write_text(in_scene("fifo_map.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd fifo.png\n");
    write_text(in_scene("fifo_map.obj"),
               "mtllib fifo_map.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    expect(in_scene("fifo_map.obj"), NULL, DIRT_SCENE_ERR_NOT_REGULAR, "a FIFO as a map_Kd");
    /* /dev/zero as the MTL library (absolute: outside; allowed, then not
     * a regular file). */
    write_text(in_scene("zero_mtl.obj"), "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("zero_mtl.obj"), NULL, DIRT_SCENE_ERR_OUTSIDE, "mtllib /dev/zero");
    dirt_load_opts out = {.allow_outside = true};
    expect(in_scene("zero_mtl.obj"), &out, DIRT_SCENE_ERR_NOT_REGULAR,
           "mtllib /dev/zero, outside paths allowed");
    alarm(0);
}

static void test_confinement(void)
{
    /* Files outside the scene's folder: a buffer, an image, an MTL library
     * and a texture map through "..", an absolute mtllib, a symbolic link
     * inside the folder that leads out. The outside files hold a secret
     * that no message may show. */
    snprintf(outside_dir, sizeof(outside_dir), "%s/outside", tmp_dir());
    mkdir(outside_dir, 0700);
    char p[800];
    snprintf(p, sizeof(p), "%s/secret.bin", outside_dir);
    tri_bin(p);
    snprintf(p, sizeof(p), "%s/secret.png", outside_dir);
    png(p);
    snprintf(p, sizeof(p), "%s/passwd", outside_dir);
    write_text(p, "root:SECRETPASSWORD:0:0:root:/root:/bin/bash\nSECRETWORD SECRETVALUE\n");

    tri_gltf(in_scene("up_buffer.gltf"), "../outside/secret.bin", NULL, NULL);
    expect(in_scene("up_buffer.gltf"), NULL, DIRT_SCENE_ERR_OUTSIDE, "a buffer URI with ..");
    CHECK_MSG(strstr(log_all_, "../outside/secret.bin") != NULL, "the message names the URI");
    dirt_load_opts allow = {.allow_outside = true};
    dirt_scene *s = expect(in_scene("up_buffer.gltf"), &allow, DIRT_SCENE_ERR_OK,
                           "a buffer URI with .., allowed");
    dirt_scene_destroy(s);

    tri_gltf(in_scene("up_image.gltf"), "tri.bin", "../outside/secret.png", NULL);
    expect(in_scene("up_image.gltf"), NULL, DIRT_SCENE_ERR_OUTSIDE, "an image URI with ..");
    s = expect(in_scene("up_image.gltf"), &allow, DIRT_SCENE_ERR_OK, "an image URI with .., allowed");
    CHECK(s && dirt_scene_num_textures(s) == 1);
    dirt_scene_destroy(s);

    char target[800];
    snprintf(target, sizeof(target), "%s/secret.bin", outside_dir);
    if (symlink(target, in_scene("link.bin")) != 0)
        perror("symlink");
    tri_gltf(in_scene("link_buffer.gltf"), "link.bin", NULL, NULL);
    expect(in_scene("link_buffer.gltf"), NULL, DIRT_SCENE_ERR_OUTSIDE,
           "a buffer through a symbolic link that leads out");
    if (symlink(outside_dir, in_scene("linkdir")) != 0)
        perror("symlink");
    tri_gltf(in_scene("linkdir_buffer.gltf"), "linkdir/missing.bin", NULL, NULL);
    expect(in_scene("linkdir_buffer.gltf"), NULL, DIRT_SCENE_ERR_OUTSIDE,
           "a missing file under a symbolic link that leads out");
    /* A subfolder is inside; so is a symbolic link that stays inside. */
    mkdir(in_scene("sub"), 0700);
    tri_bin(in_scene("sub/tri.bin"));
    if (symlink("sub/tri.bin", in_scene("inner_link.bin")) != 0)
        perror("symlink");
    tri_gltf(in_scene("sub_buffer.gltf"), "sub/../sub/tri.bin", NULL, NULL);
    s = expect(in_scene("sub_buffer.gltf"), NULL, DIRT_SCENE_ERR_OK, "a subfolder's buffer");
    dirt_scene_destroy(s);
    tri_gltf(in_scene("inner_link.gltf"), "inner_link.bin", NULL, NULL);
    s = expect(in_scene("inner_link.gltf"), NULL, DIRT_SCENE_ERR_OK, "a link that stays inside");
    dirt_scene_destroy(s);

    /* OBJ: mtllib with .., absolute, and a texture map with .. */
    write_text(in_scene("up_mtl.obj"), "mtllib ../outside/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("up_mtl.obj"), NULL, DIRT_SCENE_ERR_OUTSIDE, "mtllib with ..");
    char *abs_obj = strf("mtllib %s/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", outside_dir);
    write_text(in_scene("abs_mtl.obj"), abs_obj);
    free(abs_obj);
    expect(in_scene("abs_mtl.obj"), NULL, DIRT_SCENE_ERR_OUTSIDE, "an absolute mtllib");
    CHECK_MSG(strstr(log_all_, "SECRET") == NULL, "a refused file's bytes were logged");
    /* Allowed: the "library" is read, and none of its lines is echoed. */
    s = expect(in_scene("abs_mtl.obj"), &allow, DIRT_SCENE_ERR_OK, "an absolute mtllib, allowed");
    CHECK_MSG(strstr(log_all_, "SECRET") == NULL, "a file's bytes were logged:\n%s", log_all_);
    dirt_scene_destroy(s);
    write_text(in_scene("up_map.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd ../outside/secret.png\n");
    write_text(in_scene("up_map.obj"), "mtllib up_map.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    expect(in_scene("up_map.obj"), NULL, DIRT_SCENE_ERR_OUTSIDE, "map_Kd with ..");
    s = expect(in_scene("up_map.obj"), &allow, DIRT_SCENE_ERR_OK, "map_Kd with .., allowed");
    CHECK(s && dirt_scene_num_textures(s) == 1);
    dirt_scene_destroy(s);

    /* A "scene" that is not one: its bytes are not echoed by the parser's
     * message (nlohmann's "last read" excerpt is cut). */
    snprintf(p, sizeof(p), "%s/passwd", outside_dir);
    char *copy = strf("{\"asset\": SECRETPASSWORD }");
    write_text(in_scene("secret.gltf"), copy);
    free(copy);
    expect(in_scene("secret.gltf"), NULL, DIRT_SCENE_ERR_SYNTAX, "a JSON syntax error");
    CHECK_MSG(strstr(log_all_, "SECRET") == NULL, "the parser echoed the file:\n%s", log_all_);
    expect(p, NULL, DIRT_SCENE_ERR_FORMAT, "/etc/passwd-like file as the scene");
    CHECK_MSG(strstr(log_all_, "SECRET") == NULL, "the loader echoed the file:\n%s", log_all_);
}

static void test_strict(void)
{
    /* A missing texture and an ignored extension only warn; strict, they
     * fail (STRICT), after every warning is said. */
    tri_gltf(in_scene("missing_tex.gltf"), "tri.bin", "nope.png", NULL);
    dirt_scene *s = expect(in_scene("missing_tex.gltf"), NULL, DIRT_SCENE_ERR_OK, "missing texture");
    CHECK(warnings_ > 0);
    dirt_scene_destroy(s);
    dirt_load_opts strict = {.strict = true};
    expect(in_scene("missing_tex.gltf"), &strict, DIRT_SCENE_ERR_STRICT, "missing texture, strict");
    CHECK(warnings_ > 0);
    tri_gltf(in_scene("ext_used.gltf"), "tri.bin", NULL,
             "\"extensionsUsed\":[\"KHR_materials_clearcoat\"],");
    s = expect(in_scene("ext_used.gltf"), NULL, DIRT_SCENE_ERR_OK, "ignored extension");
    dirt_scene_destroy(s);
    expect(in_scene("ext_used.gltf"), &strict, DIRT_SCENE_ERR_STRICT, "ignored extension, strict");
    write_text(in_scene("missing_mtl.obj"), "mtllib nope.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("missing_mtl.obj"), &strict, DIRT_SCENE_ERR_STRICT, "missing mtllib, strict");
    /* A clean scene loads strict. */
    tri_gltf(in_scene("clean.gltf"), "tri.bin", NULL, NULL);
    s = expect(in_scene("clean.gltf"), &strict, DIRT_SCENE_ERR_OK, "clean scene, strict");
    CHECK(warnings_ == 0);
    dirt_scene_destroy(s);
}

static void test_versions_formats(void)
{
    /* glTF 1.0 and an unknown major version; a .glb of version 1. */
    write_text(in_scene("v1.gltf"), "{\"asset\":{\"version\":\"1.0\"}}");
    expect(in_scene("v1.gltf"), NULL, DIRT_SCENE_ERR_VERSION, "asset.version 1.0");
    write_text(in_scene("v3.gltf"), "{\"asset\":{\"version\":\"3.0\"}}");
    expect(in_scene("v3.gltf"), NULL, DIRT_SCENE_ERR_VERSION, "asset.version 3.0");
    write_text(in_scene("min21.gltf"), "{\"asset\":{\"version\":\"2.1\",\"minVersion\":\"2.1\"}}");
    expect(in_scene("min21.gltf"), NULL, DIRT_SCENE_ERR_VERSION, "minVersion 2.1");
    write_text(in_scene("v21.gltf"), "{\"asset\":{\"version\":\"2.1\"}}");
    dirt_scene *s = expect(in_scene("v21.gltf"), NULL, DIRT_SCENE_ERR_OK, "asset.version 2.1");
    dirt_scene_destroy(s);
    uint8_t *glb = NULL;
    size_t n = make_glb("{\"asset\":{\"version\":\"2.0\"}}", NULL, 0, &glb);
    glb[4] = 1; /* the container's version */
    write_bytes(in_scene("v1.glb"), glb, n);
    free(glb);
    expect(in_scene("v1.glb"), NULL, DIRT_SCENE_ERR_VERSION, "a .glb of version 1");
    /* A .ply, and a file without an extension that is not glTF. */
    write_text(in_scene("model.ply"), "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
    expect(in_scene("model.ply"), NULL, DIRT_SCENE_ERR_FORMAT, "a .ply file");
    CHECK_MSG(strstr(log_all_, "unsupported format") != NULL, "no 'unsupported format'");
    /* ... while glTF bytes under another name load. */
    tri_gltf(in_scene("scene.json"), "tri.bin", NULL, NULL);
    s = expect(in_scene("scene.json"), NULL, DIRT_SCENE_ERR_OK, "glTF named .json");
    dirt_scene_destroy(s);
}

static void test_obj_numbers(void)
{
    /* 2^32 + 1 wrapped to vertex 1 in tinyobjloader; 2^31 to a negative
     * (relative) index. */
    write_text(in_scene("wrap.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4294967297 2 3\n");
    expect(in_scene("wrap.obj"), NULL, DIRT_SCENE_ERR_INDEX, "index 2^32 + 1");
    write_text(in_scene("wrap31.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2147483648 2 3\n");
    expect(in_scene("wrap31.obj"), NULL, DIRT_SCENE_ERR_INDEX, "texture index 2^31");
    write_text(in_scene("big.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n");
    expect(in_scene("big.obj"), NULL, DIRT_SCENE_ERR_INDEX, "a 20-digit index");
    /* nan and inf positions (read as 0 by tinyobjloader) of a used vertex. */
    write_text(in_scene("nan.obj"), "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("nan.obj"), NULL, DIRT_SCENE_ERR_NOT_FINITE, "v nan");
    write_text(in_scene("inf.obj"), "v 0 0 0\nv 1 -INF 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("inf.obj"), NULL, DIRT_SCENE_ERR_NOT_FINITE, "v -INF");
    write_text(in_scene("nan_unused.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan nan nan\nf 1 2 3\n");
    dirt_scene *s = expect(in_scene("nan_unused.obj"), NULL, DIRT_SCENE_ERR_OK, "unused nan vertex");
    dirt_scene_destroy(s);
    write_text(in_scene("word.obj"), "v 0 zero 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("word.obj"), NULL, DIRT_SCENE_ERR_SYNTAX, "a coordinate that is a word");
    write_text(in_scene("short.obj"), "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect(in_scene("short.obj"), NULL, DIRT_SCENE_ERR_SYNTAX, "a v with two coordinates");
    /* A nan normal counts as absent: flat normals. */
    write_text(in_scene("nan_normal.obj"),
               "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn nan 0 1\nf 1//1 2//1 3//1\n");
    s = expect(in_scene("nan_normal.obj"), NULL, DIRT_SCENE_ERR_OK, "nan normal");
    if (s) {
        dirt_frame *f = dirt_scene_evaluate(s, 0, NULL);
        CHECK(f && f->normal[0][2] == 1.0f && f->normal[0][0] == 0.0f);
        dirt_frame_destroy(f);
    }
    dirt_scene_destroy(s);
}

static void test_file_list(void)
{
    /* The files a load read: the scene, its buffer, its image. */
    png(in_scene("tex.png"));
    tri_gltf(in_scene("listed.gltf"), "tri.bin", "tex.png", NULL);
    dirt_scene *s = expect(in_scene("listed.gltf"), NULL, DIRT_SCENE_ERR_OK, "file list");
    CHECK(s && dirt_scene_num_files(s) == 3);
    if (s && dirt_scene_num_files(s) == 3) {
        CHECK(strcmp(dirt_scene_file(s, 0), in_scene("listed.gltf")) == 0);
        CHECK(strstr(dirt_scene_file(s, 1), "tri.bin") != NULL);
        CHECK(strstr(dirt_scene_file(s, 2), "tex.png") != NULL);
        CHECK(dirt_scene_file(s, 3) == NULL);
    }
    dirt_scene_destroy(s);
    write_text(in_scene("listed.mtl"), "newmtl m\nmap_Kd tex.png\n");
    write_text(in_scene("listed.obj"), "mtllib listed.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                       "usemtl m\nf 1/1 2/1 3/1\n");
    s = expect(in_scene("listed.obj"), NULL, DIRT_SCENE_ERR_OK, "OBJ file list");
    CHECK(s && dirt_scene_num_files(s) == 3);
    if (s && dirt_scene_num_files(s) == 3) {
        CHECK(strstr(dirt_scene_file(s, 1), "listed.mtl") != NULL);
        CHECK(strstr(dirt_scene_file(s, 2), "tex.png") != NULL);
    }
    dirt_scene_destroy(s);
    s = dirt_scene_create_default();
    CHECK(s && dirt_scene_num_files(s) == 0);
    dirt_scene_destroy(s);
}

int main(void)
{
    signal(SIGALRM, on_alarm);
    snprintf(scene_dir, sizeof(scene_dir), "%s/scene", tmp_dir());
    mkdir(scene_dir, 0700);
    dirt_log_set_callback(capture, NULL);
    test_special_files();
    test_confinement();
    test_strict();
    test_versions_formats();
    test_obj_numbers();
    test_file_list();
    dirt_log_set_callback(NULL, NULL);
    char cmd[1400];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", tmp_dir());
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", tmp_dir());
    return check_finish();
}
