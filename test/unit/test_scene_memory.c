/* The load budget holds what a load holds (issue 23, "Decoders outside the
 * budget"): for each shape of file that costs the parsers most per byte
 * (a glTF JSON of tiny values, of empty materials, of long strings; a .glb's
 * BIN chunk; an external buffer; a PNG and a JPEG texture; an OBJ of faces,
 * of vertices, of long polygons, of groups; an MTL of materials), a child
 * process loads a generated file and reports its peak resident memory's
 * growth; it must stay within what the load charged to the budget (plus a
 * fixed allowance for the allocator), so that dirt_load_opts.max_bytes
 * bounds the memory. The figures per input byte are printed
 * (doc/scenes.md, "Memory", quotes them). Then the attacks of the issue,
 * each at the default budget: a small PNG declaring 16384 x 16384 pixels
 * in a glTF, a .gltf whose extras hold 2.2 million numbers, an OBJ of 1.4
 * million faces: each fails with TOO_LARGE and a peak far below what it
 * would have taken. */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <stb_image_write.h>

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

/* Allocator slack allowed beyond the charge: glibc keeps freed memory and
 * maps in 128 KiB steps; the loaders' fixed overheads (a tinygltf model,
 * streams). */
#define SLACK_MB 6.0

/* Under AddressSanitizer (dirt.sh asan) its redzones and quarantine of
 * freed memory change every peak: the figures are printed and the loads
 * checked, the peaks not. */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

static double maxrss_mb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024.0;
}

typedef struct outcome {
    int error;        /* enum dirt_scene_error of the load */
    double peak_mb;   /* peak RSS growth of the child */
    double charged_mb;/* the most the load charged to the budget at once */
} outcome;

/* The child's part (this program run as "--load PATH MAX_BYTES", a fresh
 * process, so that no memory of the parent's is reused): loads PATH and
 * writes the outcome to stdout. */
static int child_load(const char *path, const char *max)
{
    size_t max_bytes = (size_t)strtoull(max, NULL, 10);
    double base = maxrss_mb();
    dirt_load_opts o = {.max_bytes = max_bytes};
    dirt_scene *s = dirt_scene_load(path, &o);
    outcome r = {.error = (int)dirt_scene_last_error(), .peak_mb = maxrss_mb() - base};
    r.charged_mb = (double)scene_budget_peak() / (1 << 20);
    dirt_scene_destroy(s);
    printf("%d %.3f %.3f\n", r.error, r.peak_mb, r.charged_mb);
    return 0;
}

/* Loads `path` in a new process with `max_bytes` (0: default) and returns
 * what happened there. */
static outcome load_in_child(const char *path, size_t max_bytes)
{
    outcome out = {.error = -1};
    char cmd[1024];
    snprintf(cmd, sizeof(cmd), "/proc/%ld/exe --load '%s' %zu", (long)getpid(), path, max_bytes);
    fflush(NULL);
    /* Every allocation filled (glibc's MALLOC_PERTURB_), so that the peak
     * counts what was allocated, touched or not: the same figures under
     * meson test, which sets it, and alone. */
    setenv("MALLOC_PERTURB_", "165", 1);
    FILE *p = popen(cmd, "r");
    if (!p)
        return out;
    if (fscanf(p, "%d %lf %lf", &out.error, &out.peak_mb, &out.charged_mb) != 3)
        out.error = -1;
    if (pclose(p) != 0)
        out.error = -1;
    return out;
}

static size_t file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n > 0 ? (size_t)n : 0;
}

/* Loads `name` with a budget large enough, and checks that the peak stayed
 * within the charge (+ SLACK_MB) and that the load succeeded. `beside`:
 * the file it references (NULL: none), counted in the input bytes. */
static void measure(const char *name, const char *beside)
{
    const char *path = tmp_file(name);
    outcome r = load_in_child(path, (size_t)4 << 30);
    double in_mb = (double)(file_size(path) + (beside ? file_size(tmp_file(beside)) : 0)) / (1 << 20);
    fprintf(stderr, "%-22s %8.2f MB file: peak %8.1f MB (%6.1f per byte), charged %8.1f MB "
            "(%6.1f per byte)\n", name, in_mb, r.peak_mb, r.peak_mb / in_mb, r.charged_mb,
            r.charged_mb / in_mb);
    CHECK_MSG(r.error == DIRT_SCENE_ERR_OK, "%s: load failed (%s)", name,
              r.error < 0 ? "child died" : dirt_scene_error_name((enum dirt_scene_error)r.error));
    CHECK_MSG(UNDER_ASAN || r.peak_mb <= r.charged_mb + SLACK_MB,
              "%s: peak %.1f MB beyond the %.1f MB charged to the budget", name, r.peak_mb,
              r.charged_mb);
}

/* The attack `name` fails at the default budget with TOO_LARGE, its peak
 * under `limit_mb`. */
static void attack(const char *name, double limit_mb)
{
    outcome r = load_in_child(tmp_file(name), 0);
    fprintf(stderr, "%-22s default budget: %s, peak %.1f MB\n", name,
            r.error < 0 ? "child died" : dirt_scene_error_name((enum dirt_scene_error)r.error),
            r.peak_mb);
    CHECK_MSG(r.error == DIRT_SCENE_ERR_TOO_LARGE, "%s: %s, not TOO_LARGE", name,
              r.error < 0 ? "child died" : dirt_scene_error_name((enum dirt_scene_error)r.error));
    CHECK_MSG(r.peak_mb < (UNDER_ASAN ? 4 * limit_mb : limit_mb), "%s: peak %.1f MB (limit %.1f)",
              name, r.peak_mb, limit_mb);
}

/* A file of `head`, `count` times `item` (separated by `sep`), `tail`. */
static void write_repeated(const char *name, const char *head, const char *item, const char *sep,
                           size_t count, const char *tail)
{
    FILE *f = fopen(tmp_file(name), "wb");
    if (!f) {
        perror(name);
        exit(1);
    }
    fputs(head, f);
    for (size_t i = 0; i < count; i++) {
        if (i)
            fputs(sep, f);
        fputs(item, f);
    }
    fputs(tail, f);
    fclose(f);
}

/* A one-triangle glTF whose base colour texture is the image file `image`
 * (a URI beside it). */
static void textured_gltf(const char *name, const char *image)
{
    uint8_t buf[44] = {0};
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[3] = {0, 1, 2};
    memcpy(buf, pos, 36);
    memcpy(buf + 36, idx, 6);
    char *uri = data_uri(buf, sizeof(buf));
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
                   "\"material\":0}]}],\"materials\":[{\"pbrMetallicRoughness\":{"
                   "\"baseColorTexture\":{\"index\":0}}}],\"textures\":[{\"source\":0}],"
                   "\"images\":[{\"uri\":\"%s\"}],\"buffers\":[{\"byteLength\":44,\"uri\":\"%s\"}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,"
                   "\"byteOffset\":36,\"byteLength\":6}],\"accessors\":[{\"bufferView\":0,"
                   "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],"
                   "\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5123,\"count\":3,"
                   "\"type\":\"SCALAR\"}]}",
                   image, uri);
    write_text(tmp_file(name), j);
    free(j);
    free(uri);
}

static void write_png_file(const char *name, int w, int h, bool noise)
{
    uint8_t *px = malloc((size_t)w * (size_t)h * 4);
    if (!px)
        exit(1);
    uint32_t x = 12345;
    for (size_t i = 0; i < (size_t)w * (size_t)h * 4; i++) {
        x = x * 1664525u + 1013904223u;
        px[i] = noise ? (uint8_t)(x >> 24) : 128;
    }
    if (!stbi_write_png(tmp_file(name), w, h, 4, px, w * 4))
        exit(1);
    free(px);
}

static void write_jpg_file(const char *name, int w, int h)
{
    uint8_t *px = malloc((size_t)w * (size_t)h * 3);
    if (!px)
        exit(1);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++)
        px[i] = (uint8_t)(i * 7);
    if (!stbi_write_jpg(tmp_file(name), w, h, 3, px, 90))
        exit(1);
    free(px);
}

/* A PNG declaring w x h pixels whose data is only a few rows: the size the
 * header declares, as the attack file. */
static void write_lying_png(const char *name, int w, int h)
{
    write_png_file("small.png", 64, 64, false);
    size_t n = file_size(tmp_file("small.png"));
    uint8_t *b = malloc(n);
    FILE *f = fopen(tmp_file("small.png"), "rb");
    if (!b || !f || fread(b, 1, n, f) != n)
        exit(1);
    fclose(f);
    /* IHDR: 8-byte signature, length, "IHDR", width, height (big-endian);
     * the CRC is left stale (stb_image does not check it). */
    for (int k = 0; k < 4; k++) {
        b[16 + k] = (uint8_t)((uint32_t)w >> (24 - 8 * k));
        b[20 + k] = (uint8_t)((uint32_t)h >> (24 - 8 * k));
    }
    write_bytes(tmp_file(name), b, n);
    free(b);
}

static void glb_with_bin(const char *name, size_t bin_floats)
{
    float *bin = calloc(bin_floats, sizeof(float));
    if (!bin)
        exit(1);
    size_t verts = bin_floats / 3;
    for (size_t i = 0; i < verts * 3; i++)
        bin[i] = (float)(i % 7);
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                   "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                   "{\"POSITION\":0}}]}],\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":"
                   "[{\"buffer\":0,\"byteLength\":%zu}],\"accessors\":[{\"bufferView\":0,"
                   "\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\",\"min\":[0,0,0],"
                   "\"max\":[6,6,6]}]}",
                   bin_floats * 4, bin_floats * 4, verts);
    uint8_t *glb = NULL;
    size_t n = make_glb(j, (const uint8_t *)bin, bin_floats * 4, &glb);
    write_bytes(tmp_file(name), glb, n);
    free(glb);
    free(j);
    free(bin);
}

static void external_bin(const char *name, const char *bin_name, size_t verts)
{
    float *bin = calloc(verts * 3, sizeof(float));
    if (!bin)
        exit(1);
    for (size_t i = 0; i < verts * 3; i++)
        bin[i] = (float)(i % 5);
    write_bytes(tmp_file(bin_name), bin, verts * 12);
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                   "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                   "{\"POSITION\":0}}]}],\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu}],\"accessors\":["
                   "{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
                   "\"min\":[0,0,0],\"max\":[4,4,4]}]}",
                   verts * 12, bin_name, verts * 12, verts);
    write_text(tmp_file(name), j);
    free(j);
    free(bin);
}

/* A .gltf of one long data-URI buffer (the strings' cost). */
static void data_uri_gltf(const char *name, size_t bytes)
{
    uint8_t *b = malloc(bytes);
    if (!b)
        exit(1);
    for (size_t i = 0; i < bytes; i++)
        b[i] = (uint8_t)(i * 13);
    char *uri = data_uri(b, bytes);
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,"
                   "\"uri\":\"%s\"}]}", bytes, uri);
    write_text(tmp_file(name), j);
    free(j);
    free(uri);
    free(b);
}

static const char gltf_head[] = "{\"asset\":{\"version\":\"2.0\"},";

static void test_shapes(void)
{
    /* glTF JSON: the values of extras (numbers, small objects), empty
     * materials and nodes (their structs), minimal accessors. */
    char head[256];
    snprintf(head, sizeof(head), "%s\"extras\":[", gltf_head);
    write_repeated("extras_numbers.gltf", head, "0", ",", 400000, "]}");
    write_repeated("extras_objects.gltf", head, "{\"a\":0}", ",", 100000, "]}");
    write_repeated("extras_strings.gltf", head, "\"abcdefghijklmnopqrstuvwxyz\"", ",", 100000, "]}");
    snprintf(head, sizeof(head), "%s\"materials\":[", gltf_head);
    write_repeated("materials.gltf", head, "{}", ",", 40000, "]}");
    snprintf(head, sizeof(head), "%s\"nodes\":[", gltf_head);
    write_repeated("nodes.gltf", head, "{}", ",", 100000, "]}");
    snprintf(head, sizeof(head), "%s\"cameras\":[", gltf_head);
    write_repeated("cameras.gltf", head, "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":1}}", ",", 40000, "]}");
    snprintf(head, sizeof(head), "%s\"meshes\":[{\"primitives\":[", gltf_head);
    write_repeated("primitives.gltf", head, "{\"attributes\":{}}", ",", 60000, "]}]}");
    snprintf(head, sizeof(head), "%s\"accessors\":[", gltf_head);
    write_repeated("accessors.gltf", head,
                   "{\"componentType\":5126,\"count\":1,\"type\":\"SCALAR\"}", ",", 40000, "]}");
    data_uri_gltf("data_uri.gltf", 8 << 20);
    glb_with_bin("bin.glb", 6 << 20);
    external_bin("external.gltf", "external.bin", 2 << 20);
    write_png_file("noise.png", 1024, 1024, true);
    textured_gltf("png_texture.gltf", "noise.png");
    write_jpg_file("photo.jpg", 1536, 1024);
    textured_gltf("jpg_texture.gltf", "photo.jpg");
    /* OBJ: faces, vertices, long polygons, groups, texture coordinates. */
    write_repeated("faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "f 1 2 3", "\n", 400000, "\n");
    write_repeated("vertices.obj", "", "v 0 0 0", "\n", 600000, "\nf 1 2 3\n");
    {
        FILE *f = fopen(tmp_file("polygons.obj"), "wb");
        if (!f)
            exit(1);
        for (int i = 0; i < 200; i++)
            fprintf(f, "v %d %d 0\n", i % 20, i / 20);
        for (int k = 0; k < 20000; k++) {
            fputs("f", f);
            for (int c = 1; c <= 40; c++)
                fprintf(f, " %d", c);
            fputc('\n', f);
        }
        fclose(f);
    }
    write_repeated("groups.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "g a\nf 1 2 3", "\n", 100000, "\n");
    write_repeated("texcoords.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "vt 0 0\nvn 0 0 1", "\n",
                   300000, "\nf 1/1/1 2/2/2 3/3/3\n");
    write_text(tmp_file("materials.obj"), "mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_repeated("many.mtl", "", "newmtl m", "\n", 20000, "\n");

    static const char *const shapes[][2] = {
        {"extras_numbers.gltf", NULL}, {"extras_objects.gltf", NULL},
        {"extras_strings.gltf", NULL}, {"materials.gltf", NULL}, {"nodes.gltf", NULL},
        {"cameras.gltf", NULL}, {"primitives.gltf", NULL}, {"accessors.gltf", NULL},
        {"data_uri.gltf", NULL}, {"bin.glb", NULL}, {"external.gltf", "external.bin"},
        {"png_texture.gltf", "noise.png"}, {"jpg_texture.gltf", "photo.jpg"},
        {"faces.obj", NULL}, {"vertices.obj", NULL}, {"polygons.obj", NULL},
        {"groups.obj", NULL}, {"texcoords.obj", NULL}, {"materials.obj", "many.mtl"}};
    for (size_t i = 0; i < sizeof(shapes) / sizeof(shapes[0]); i++)
        measure(shapes[i][0], shapes[i][1]);
}

static void test_attacks(void)
{
    /* A PNG of a few KB declaring 16384 x 16384 (1 GiB of pixels): was
     * decoded at 3.2 GB in a glTF. */
    write_lying_png("huge.png", 16384, 16384);
    textured_gltf("huge_texture.gltf", "huge.png");
    attack("huge_texture.gltf", 32.0);
    /* 2.2 million numbers in extras (4.4 MB): about 500 MB of parsed JSON. */
    char head[256];
    snprintf(head, sizeof(head), "%s\"extras\":[", gltf_head);
    write_repeated("extras_attack.gltf", head, "0", ",", 2200000, "]}");
    attack("extras_attack.gltf", 48.0);
    /* 2 million faces (16 MB): about 350 MB in the OBJ parser. */
    write_repeated("faces_attack.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "f 1 2 3", "\n", 2000000,
                   "\n");
    attack("faces_attack.obj", 48.0);
}

int main(int argc, char **argv)
{
    dirt_log_set_level(DIRT_LOG_ERROR);
    if (argc == 4 && !strcmp(argv[1], "--load"))
        return child_load(argv[2], argv[3]);
    test_shapes();
    test_attacks();
    static const char *const files[] = {
        "extras_numbers.gltf", "extras_objects.gltf", "extras_strings.gltf", "materials.gltf",
        "nodes.gltf", "cameras.gltf", "primitives.gltf", "accessors.gltf", "data_uri.gltf",
        "bin.glb", "external.gltf", "external.bin", "noise.png", "png_texture.gltf",
        "photo.jpg", "jpg_texture.gltf", "faces.obj", "vertices.obj", "polygons.obj",
        "groups.obj", "texcoords.obj", "materials.obj", "many.mtl", "small.png", "huge.png",
        "huge_texture.gltf", "extras_attack.gltf", "faces_attack.obj"};
    tmp_cleanup(files, sizeof(files) / sizeof(files[0]));
    return check_finish();
}
