/* DIRT engine: the image, environment and file-tree fuzz targets and their
 * seed corpora (fuzz_inputs.h). */
#define _XOPEN_SOURCE 700 /* realpath(3), symlink(2) */
#include "fuzz_inputs.h"

#include "../unit/test_scene_util.h"
#include "dirt/image.h"
#include "dirt/input.h"
#include "integrator/integrator.h"
#include "dirt/scene.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int dirt_fuzz_outcome;

#define FUZZ_BUDGET ((size_t)64 << 20)

/* ---- a private folder for the files the entries write ---- */

static char work_dir[64];

static void remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        DIR *d = opendir(path);
        struct dirent *e;
        while (d && (e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char sub[PATH_MAX];
            snprintf(sub, sizeof(sub), "%s/%s", path, e->d_name);
            remove_tree(sub);
        }
        if (d)
            closedir(d);
        rmdir(path);
    } else {
        unlink(path);
    }
}

static void remove_work_dir(void)
{
    if (work_dir[0])
        remove_tree(work_dir);
}

/* The process's folder (made once, removed at exit). */
static const char *work(void)
{
    if (!work_dir[0]) {
        snprintf(work_dir, sizeof(work_dir), "/tmp/dirt_fuzz_work_XXXXXX");
        if (!mkdtemp(work_dir)) {
            perror("mkdtemp");
            abort();
        }
        atexit(remove_work_dir);
    }
    return work_dir;
}

static bool put_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    bool ok = f && (n == 0 || fwrite(data, 1, n, f) == n);
    if (f && fclose(f) != 0)
        ok = false;
    return ok;
}

/* ---- images ---- */

/* A .glb: one triangle whose base colour texture is `img` (a buffer view
 * after the triangle's 44 bytes). Caller frees *out. */
static size_t textured_glb(const uint8_t *img, size_t n, uint8_t **out)
{
    size_t pad = (n + 3) & ~(size_t)3;
    uint8_t *bin = calloc(44 + pad + 1, 1);
    if (!bin)
        abort();
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[3] = {0, 1, 2};
    memcpy(bin, pos, 36);
    memcpy(bin + 36, idx, 6);
    if (n)
        memcpy(bin + 44, img, n);
    char *j = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":"
                   "[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
                   "\"indices\":1,\"material\":0}]}],\"materials\":[{"
                   "\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
                   "\"textures\":[{\"source\":0}],\"images\":[{\"bufferView\":2,\"mimeType\":"
                   "\"image/png\"}],\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":["
                   "{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,"
                   "\"byteLength\":6},{\"buffer\":0,\"byteOffset\":44,\"byteLength\":%zu}],"
                   "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
                   "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},{\"bufferView\":1,"
                   "\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]}",
                   44 + pad, n);
    size_t len = make_glb(j, bin, 44 + pad, out);
    free(j);
    free(bin);
    return len;
}

static volatile float sink;

/* Reads every value of an image (a short plane is then ASan's to see). */
static bool touch_image(const dirt_image *img)
{
    if (img->width < 1 || img->height < 1 || img->width > DIRT_IMAGE_MAX_DIM ||
        img->height > DIRT_IMAGE_MAX_DIM)
        return false;
    size_t n = (size_t)img->width * (size_t)img->height;
    float s = 0;
    for (size_t i = 0; i < 4 * n; i++)
        s += img->rgba[i];
    for (int c = 0; c < img->channel_count; c++) {
        for (size_t i = 0; i < n; i++)
            s += img->channels[c].data[i];
    }
    sink = s;
    return true;
}

bool dirt_fuzz_image_one(const uint8_t *data, size_t size)
{
    dirt_fuzz_outcome = 0;
    if (size < 1)
        return true;
    int how = data[0] % 3;
    const uint8_t *bytes = data + 1;
    size_t n = size - 1;
    if (how == 0) {
        uint8_t *glb = NULL;
        size_t len = textured_glb(bytes, n, &glb);
        dirt_load_opts lo = {.max_bytes = FUZZ_BUDGET};
        dirt_scene *s = dirt_scene_load_memory(glb, len, "fuzz_texture.glb", &lo);
        free(glb);
        if (!s)
            return dirt_scene_last_error() != DIRT_SCENE_ERR_OK;
        bool ok = dirt_scene_num_textures(s) <= 2;
        for (size_t t = 0; ok && t < dirt_scene_num_textures(s); t++) {
            const dirt_texture *tx = &dirt_scene_textures(s)[t];
            ok = tx->width > 0 && tx->height > 0 && tx->rgba;
            unsigned sum = 0;
            for (size_t i = 0; ok && i < (size_t)tx->width * (size_t)tx->height * 4; i++)
                sum += tx->rgba[i];
            sink = (float)sum;
        }
        dirt_fuzz_outcome = dirt_scene_num_textures(s) > 0;
        dirt_scene_destroy(s);
        return ok;
    }
    char path[128];
    snprintf(path, sizeof(path), "%s/image.%s", work(), how == 1 ? "exr" : "hdr");
    if (!put_file(path, bytes, n))
        abort();
    enum dirt_input_error e = DIRT_INPUT_ERR_OK;
    dirt_image_read_opts ro = {.max_bytes = FUZZ_BUDGET};
    dirt_image *img = dirt_image_read(path, &ro, &e);
    if (!img)
        return e != DIRT_INPUT_ERR_OK;
    bool ok = e == DIRT_INPUT_ERR_OK && touch_image(img);
    dirt_fuzz_outcome = 1;
    dirt_image_destroy(img);
    return ok;
}

bool dirt_fuzz_env_one(const uint8_t *data, size_t size)
{
    dirt_fuzz_outcome = 0;
    if (size < 1)
        return true;
    char path[128];
    snprintf(path, sizeof(path), "%s/map.%s", work(), data[0] & 1 ? "hdr" : "exr");
    if (!put_file(path, data + 1, size - 1))
        abort();
    char why[512] = "";
    dirt_env_opts eo = {.max_bytes = FUZZ_BUDGET, .rotation = 30.0f};
    dirt_env *env = dirt_env_load(path, &eo, why, sizeof(why));
    if (!env) {
        /* The reason starts with an id. */
        for (int e = 1; e < DIRT_INPUT_NUM_ERRORS; e++) {
            const char *id = dirt_input_error_name((enum dirt_input_error)e);
            if (!strncmp(why, id, strlen(id)) && why[strlen(id)] == ':')
                return true;
        }
        fprintf(stderr, "fuzz: an environment failed without an id: %s\n", why);
        return false;
    }
    bool ok = env->width >= 1 && env->height >= 1;
    static const float dirs[][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.6f, 0.3f, 0.74f}};
    float s = 0;
    for (size_t k = 0; ok && k < sizeof(dirs) / sizeof(dirs[0]); k++) {
        dirt_vec3 d = {dirs[k][0], dirs[k][1], dirs[k][2]};
        dirt_vec3 c = dirt_env_eval(env, d);
        s += c.x + dirt_env_pdf(env, d);
        dirt_vec3 wi, li;
        float pdf;
        if (dirt_env_sample(env, 0.1f * (float)k, 0.5f, 0.25f, &wi, &pdf, &li))
            ok = pdf > 0 && isfinite(pdf);
    }
    sink = s;
    dirt_fuzz_outcome = 1;
    dirt_env_destroy(env);
    return ok;
}

/* ---- file trees ---- */

/* Whether `name` may be written under R/s: allowed bytes only, not empty,
 * not absolute, and never above R (".." counted). */
static bool name_ok(const char *name)
{
    if (!name[0] || name[0] == '/')
        return false;
    int depth = 1; /* R/s is one below R */
    for (const char *p = name; *p;) {
        const char *e = strchr(p, '/');
        size_t k = e ? (size_t)(e - p) : strlen(p);
        if (k == 2 && p[0] == '.' && p[1] == '.')
            depth--;
        else if (k && !(k == 1 && p[0] == '.'))
            depth++;
        if (depth < 0)
            return false;
        p += k + (e ? 1 : 0);
        if (!e)
            break;
    }
    for (const char *p = name; *p; p++) {
        char c = *p;
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '.' || c == '_' || c == '-' || c == '/'))
            return false;
    }
    return true;
}

/* Makes the folders above `path` (inside the tree). */
static void make_parents(const char *path)
{
    char p[PATH_MAX];
    snprintf(p, sizeof(p), "%s", path);
    for (char *s = strchr(p + 1, '/'); s; s = strchr(s + 1, '/')) {
        *s = 0;
        mkdir(p, 0700);
        *s = '/';
    }
}

/* `path` is under the folder `dir` (both real paths). */
static bool under(const char *dir, const char *path)
{
    size_t n = strlen(dir);
    return strncmp(dir, path, n) == 0 && (path[n] == '/' || path[n] == 0);
}

bool dirt_fuzz_files_one(const uint8_t *data, size_t size)
{
    dirt_fuzz_outcome = 0;
    char root[256];
    snprintf(root, sizeof(root), "%s/tree_XXXXXX", work());
    if (!mkdtemp(root))
        abort();
    char sdir[300], odir[300];
    snprintf(sdir, sizeof(sdir), "%s/s", root);
    snprintf(odir, sizeof(odir), "%s/o", root);
    mkdir(sdir, 0700);
    mkdir(odir, 0700);
    char scene[PATH_MAX] = "";
    size_t p = 0;
    for (int records = 0; p + 2 <= size && records < 32; records++) {
        int kind = data[p] & 3;
        size_t nl = data[p + 1];
        p += 2;
        if (p + nl + 2 > size)
            break;
        char name[256];
        memcpy(name, data + p, nl);
        name[nl] = 0;
        p += nl;
        size_t cl = (size_t)data[p] | (size_t)data[p + 1] << 8;
        p += 2;
        if (cl > size - p)
            cl = size - p;
        const uint8_t *content = data + p;
        p += cl;
        if (memchr(name, 0, nl) || !name_ok(name))
            continue;
        char path[PATH_MAX];
        snprintf(path, sizeof(path), "%s/%s", sdir, name);
        make_parents(path);
        if (kind == 0) {
            if (put_file(path, content, cl) && !scene[0])
                snprintf(scene, sizeof(scene), "%s", path);
        } else if (kind == 1) {
            mkdir(path, 0700);
        } else if (kind == 2) {
            char target[256];
            size_t tl = cl < sizeof(target) - 1 ? cl : sizeof(target) - 1;
            memcpy(target, content, tl);
            target[tl] = 0;
            if (!memchr(content, 0, tl) && name_ok(target))
                (void)symlink(target, path);
        } else {
            mkfifo(path, 0600);
        }
    }
    bool ok = true;
    if (scene[0]) {
        /* The scene's folder, as the loader takes it: the folder its path
         * names, resolved (R/s, or above it for a scene named "../x"). */
        char real_s[PATH_MAX], sfold[PATH_MAX];
        snprintf(sfold, sizeof(sfold), "%s", scene);
        *strrchr(sfold, '/') = 0;
        if (!realpath(sfold, real_s))
            abort();
        for (int allow = 0; ok && allow < 2; allow++) {
            dirt_load_opts lo = {.max_bytes = FUZZ_BUDGET, .allow_outside = allow != 0};
            dirt_scene *s = dirt_scene_load(scene, &lo);
            if (!s) {
                ok = dirt_scene_last_error() != DIRT_SCENE_ERR_OK;
                if (!ok)
                    fprintf(stderr, "fuzz: a failed load left no error id\n");
                continue;
            }
            dirt_fuzz_outcome |= !allow;
            /* Confined, every file read lies in the scene's folder. */
            for (size_t i = 0; ok && !allow && i < dirt_scene_num_files(s); i++) {
                char real[PATH_MAX];
                const char *f = dirt_scene_file(s, i);
                if (realpath(f, real) && !under(real_s, real)) {
                    fprintf(stderr, "fuzz: a confined load read '%s'\n", f);
                    ok = false;
                }
            }
            dirt_scene_destroy(s);
        }
    }
    remove_tree(root);
    return ok;
}

/* ---- seed corpora ---- */

static int put_seed(const char *dir, const char *name, uint8_t tag, const void *data, size_t n)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    uint8_t *b = malloc(n + 1);
    if (!b)
        return 0;
    b[0] = tag;
    memcpy(b + 1, data, n);
    bool ok = put_file(path, b, n + 1);
    free(b);
    if (!ok)
        perror(path);
    return ok ? 1 : 0;
}

static uint8_t *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *b = len > 0 ? malloc((size_t)len) : NULL;
    if (b && fread(b, 1, (size_t)len, f) != (size_t)len) {
        free(b);
        b = NULL;
    }
    fclose(f);
    *n = b ? (size_t)len : 0;
    return b;
}

/* The image seeds' files (made through the project's writers and
 * stb_image_write): a PNG, a JPEG, a BMP, an EXR (float RGBA + extra
 * channels), an EXR of Y only, run-length and flat .hdr; `which` picks
 * one, its bytes in *n (caller frees). */
static uint8_t *seed_image(int which, size_t *n)
{
    char path[128];
    snprintf(path, sizeof(path), "%s/seed.%s", work(),
             which <= 2 ? (which == 0 ? "png" : which == 1 ? "jpg" : "bmp")
                        : which <= 4 ? "exr" : "hdr");
    enum { W = 12, H = 8 };
    uint8_t px[W * H * 4];
    float fx[W * H * 3];
    for (int i = 0; i < W * H * 4; i++)
        px[i] = (uint8_t)(i * 37);
    for (int i = 0; i < W * H * 3; i++)
        fx[i] = (float)(i % 11) * 0.3f;
    bool ok = false;
    if (which == 0)
        ok = stbi_write_png(path, W, H, 4, px, W * 4) != 0;
    else if (which == 1)
        ok = stbi_write_jpg(path, W, H, 4, px, 80) != 0;
    else if (which == 2)
        ok = stbi_write_bmp(path, W, H, 4, px) != 0;
    else if (which == 3 || which == 4) {
        dirt_image *img = dirt_image_create(W, H);
        if (img) {
            for (int i = 0; i < W * H; i++)
                for (int c = 0; c < 4; c++)
                    img->rgba[4 * i + c] = (float)((i + c) % 5);
            float *z = which == 3 ? dirt_image_add_channel(img, "Z") : NULL;
            for (int i = 0; z && i < W * H; i++)
                z[i] = (float)i;
            dirt_exr_options eo = {.half_rgba = which == 4};
            ok = dirt_image_write_exr(img, path, &eo);
            dirt_image_destroy(img);
        }
    } else {
        ok = stbi_write_hdr(path, which == 5 ? W : 4, which == 5 ? H : 4, 3, fx) != 0;
    }
    uint8_t *b = ok ? slurp(path, n) : NULL;
    unlink(path);
    return b;
}

int dirt_fuzz_write_image_corpus(const char *dir)
{
    int count = 0;
    static const char *const names[] = {"png", "jpg", "bmp", "exr", "exr_half", "hdr_rle", "hdr_flat"};
    for (int w = 0; w < 7; w++) {
        size_t n = 0;
        uint8_t *b = seed_image(w, &n);
        if (!b)
            return -1;
        char name[64];
        /* Each as a texture (tag 0) and through dirt_image_read (tag 1 for
         * EXR, 2 for HDR); a truncated copy of each. */
        snprintf(name, sizeof(name), "tex_%s", names[w]);
        count += put_seed(dir, name, 0, b, n);
        uint8_t tag = w == 3 || w == 4 ? 1 : w >= 5 ? 2 : 0;
        if (tag) {
            snprintf(name, sizeof(name), "file_%s", names[w]);
            count += put_seed(dir, name, tag, b, n);
            snprintf(name, sizeof(name), "cut_%s", names[w]);
            count += put_seed(dir, name, tag, b, n * 2 / 3);
            /* As a texture, cut: stb_image's Radiance decoder looped
             * forever on it (the first finding, doc/fuzzing.md). */
            snprintf(name, sizeof(name), "tex_cut_%s", names[w]);
            count += put_seed(dir, name, 0, b, n * 2 / 3);
        } else {
            snprintf(name, sizeof(name), "tex_cut_%s", names[w]);
            count += put_seed(dir, name, 0, b, n / 2);
        }
        free(b);
    }
    /* A PNG header declaring 16384 x 16384; a .hdr declaring 16384 x 8192
     * with no pixels. */
    size_t n = 0;
    uint8_t *b = seed_image(0, &n);
    if (!b)
        return -1;
    b[16] = 0, b[17] = 0, b[18] = 0x40, b[19] = 0;
    b[20] = 0, b[21] = 0, b[22] = 0x40, b[23] = 0;
    count += put_seed(dir, "tex_huge_png", 0, b, n);
    free(b);
    /* A PNG whose IDAT chunk says 1.8 GB: stb_image allocated that much
     * before reading it (the second finding). */
    b = seed_image(0, &n);
    if (!b || n < 41 || memcmp(b + 37, "IDAT", 4) != 0)
        return -1;
    b[33] = 0x6f, b[34] = 0x64, b[35] = 0x65, b[36] = 0x73;
    count += put_seed(dir, "tex_long_chunk_png", 0, b, n);
    free(b);
    static const char lie[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n";
    count += put_seed(dir, "file_lie_hdr", 2, lie, sizeof(lie) - 1);
    return count;
}

int dirt_fuzz_write_env_corpus(const char *dir)
{
    int count = 0;
    static const int which[] = {3, 4, 5, 6};
    static const char *const names[] = {"exr", "exr_half", "hdr_rle", "hdr_flat"};
    for (int k = 0; k < 4; k++) {
        size_t n = 0;
        uint8_t *b = seed_image(which[k], &n);
        if (!b)
            return -1;
        uint8_t tag = which[k] >= 5 ? 1 : 0;
        char name[64];
        snprintf(name, sizeof(name), "env_%s", names[k]);
        count += put_seed(dir, name, tag, b, n);
        snprintf(name, sizeof(name), "env_cut_%s", names[k]);
        count += put_seed(dir, name, tag, b, n - n / 4);
        free(b);
    }
    static const char lie[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n";
    count += put_seed(dir, "env_lie_hdr", 1, lie, sizeof(lie) - 1);
    return count;
}

/* One record of a files input. */
static void record(uint8_t **b, size_t *n, int kind, const char *name, const void *content,
                   size_t cl)
{
    size_t nl = strlen(name);
    *b = realloc(*b, *n + 4 + nl + cl);
    if (!*b)
        abort();
    uint8_t *p = *b + *n;
    p[0] = (uint8_t)kind;
    p[1] = (uint8_t)nl;
    memcpy(p + 2, name, nl);
    p[2 + nl] = (uint8_t)cl;
    p[3 + nl] = (uint8_t)(cl >> 8);
    memcpy(p + 4 + nl, content, cl);
    *n += 4 + nl + cl;
}

static int put_tree(const char *dir, const char *name, const uint8_t *b, size_t n)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    bool ok = put_file(path, b, n);
    if (!ok)
        perror(path);
    return ok ? 1 : 0;
}

int dirt_fuzz_write_files_corpus(const char *dir)
{
    uint8_t bin[44] = {0};
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[3] = {0, 1, 2};
    memcpy(bin, pos, 36);
    memcpy(bin + 36, idx, 6);
    size_t png_n = 0;
    uint8_t *png = seed_image(0, &png_n);
    if (!png)
        return -1;
    /* scene.gltf with its buffer `buf` and, when given, image `img`. */
    char *g[6];
    static const char *const bufs[6] = {"tri.bin", "../o/tri.bin", "sub/tri.bin", "link.bin",
                                        "fifo.bin", "tri.bin"};
    static const char *const imgs[6] = {"tex.png", "../o/tex.png", NULL, "dir.png", "fifo.png",
                                        "missing.png"};
    for (int k = 0; k < 6; k++) {
        char *img = imgs[k] ? strf(",\"materials\":[{\"pbrMetallicRoughness\":{"
                                   "\"baseColorTexture\":{\"index\":0}}}],\"textures\":["
                                   "{\"source\":0}],\"images\":[{\"uri\":\"%s\"}]", imgs[k])
                            : strf("%s", "");
        g[k] = strf("{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":"
                    "[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\""
                    ":0},\"indices\":1%s}]}],\"buffers\":[{\"byteLength\":44,\"uri\":\"%s\"}],"
                    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,"
                    "\"byteOffset\":36,\"byteLength\":6}],\"accessors\":[{\"bufferView\":0,"
                    "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],"
                    "\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5123,\"count\":3,"
                    "\"type\":\"SCALAR\"}]%s}",
                    imgs[k] ? ",\"material\":0" : "", bufs[k], img);
        free(img);
    }
    int count = 0;
    uint8_t *b = NULL;
    size_t n = 0;
    /* 0: a scene with its buffer and texture beside it (loads). */
    record(&b, &n, 0, "scene.gltf", g[0], strlen(g[0]));
    record(&b, &n, 0, "tri.bin", bin, sizeof(bin));
    record(&b, &n, 0, "tex.png", png, png_n);
    count += put_tree(dir, "inside", b, n);
    /* 1: its buffer and texture outside (OUTSIDE; loads when allowed). */
    n = 0;
    record(&b, &n, 0, "scene.gltf", g[1], strlen(g[1]));
    record(&b, &n, 0, "../o/tri.bin", bin, sizeof(bin));
    record(&b, &n, 0, "../o/tex.png", png, png_n);
    count += put_tree(dir, "outside", b, n);
    /* 2: a buffer in a subfolder. */
    n = 0;
    record(&b, &n, 0, "scene.gltf", g[2], strlen(g[2]));
    record(&b, &n, 1, "sub", "", 0);
    record(&b, &n, 0, "sub/tri.bin", bin, sizeof(bin));
    count += put_tree(dir, "subfolder", b, n);
    /* 3: a buffer through a symbolic link out, a directory as the image. */
    n = 0;
    record(&b, &n, 0, "scene.gltf", g[3], strlen(g[3]));
    record(&b, &n, 0, "../o/tri.bin", bin, sizeof(bin));
    record(&b, &n, 2, "link.bin", "../o/tri.bin", 12);
    record(&b, &n, 1, "dir.png", "", 0);
    count += put_tree(dir, "link_out", b, n);
    /* 4: FIFOs as the buffer and the image. */
    n = 0;
    record(&b, &n, 0, "scene.gltf", g[4], strlen(g[4]));
    record(&b, &n, 3, "fifo.bin", "", 0);
    record(&b, &n, 3, "fifo.png", "", 0);
    count += put_tree(dir, "fifos", b, n);
    /* 5: a missing texture. */
    n = 0;
    record(&b, &n, 0, "scene.gltf", g[5], strlen(g[5]));
    record(&b, &n, 0, "tri.bin", bin, sizeof(bin));
    count += put_tree(dir, "missing_texture", b, n);
    /* 6: an OBJ with its MTL and a texture map; 7: the MTL and map outside;
     * 8: a FIFO as the MTL. */
    static const char obj[] = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\n"
                              "f 1/1 2/1 3/1\n";
    static const char mtl[] = "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n";
    n = 0;
    record(&b, &n, 0, "scene.obj", obj, sizeof(obj) - 1);
    record(&b, &n, 0, "m.mtl", mtl, sizeof(mtl) - 1);
    record(&b, &n, 0, "tex.png", png, png_n);
    count += put_tree(dir, "obj_mtl", b, n);
    static const char obj_out[] = "mtllib ../o/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    static const char mtl_out[] = "newmtl m\nmap_Kd ../s/tex.png\nSECRET line\n";
    n = 0;
    record(&b, &n, 0, "scene.obj", obj_out, sizeof(obj_out) - 1);
    record(&b, &n, 0, "../o/m.mtl", mtl_out, sizeof(mtl_out) - 1);
    record(&b, &n, 0, "tex.png", png, png_n);
    count += put_tree(dir, "obj_outside", b, n);
    n = 0;
    record(&b, &n, 0, "scene.obj", obj, sizeof(obj) - 1);
    record(&b, &n, 3, "m.mtl", "", 0);
    count += put_tree(dir, "obj_fifo", b, n);
    /* 9: a scene above R/s (its folder is R), its MTL in R/s: inside. */
    static const char obj_up[] = "mtllib s/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    n = 0;
    record(&b, &n, 0, "../up.obj", obj_up, sizeof(obj_up) - 1);
    record(&b, &n, 0, "m.mtl", mtl, sizeof(mtl) - 1);
    count += put_tree(dir, "obj_above", b, n);
    free(b);
    for (int k = 0; k < 6; k++)
        free(g[k]);
    free(png);
    return count;
}
