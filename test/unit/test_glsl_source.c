/* The shader assembler: #include resolution (once per file, relative to the
 * root), #define injection after #version, #line bookkeeping, and the
 * errors for missing files, missing #version and malformed includes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "gl/glsl_embedded.h"
#include "gl/glsl_source.h"

static char root[256];

static void put(const char *rel, const char *text)
{
    char path[512];
    snprintf(path, sizeof(path), "%s/%s", root, rel);
    char *slash = strrchr(path, '/');
    *slash = '\0';
    mkdir(path, 0700);
    *slash = '/';
    FILE *f = fopen(path, "wb");
    fputs(text, f);
    fclose(f);
}

/* Number of times `needle` occurs in `s`. */
static int count(const char *s, const char *needle)
{
    int n = 0;
    for (const char *p = s; (p = strstr(p, needle)); p += strlen(needle))
        n++;
    return n;
}

/* Bytes of `path`, NUL-terminated (malloc'd; *size without the NUL), NULL
 * when unreadable. */
static char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)n + 1)) &&
            fread(buf, 1, (size_t)n, f) == (size_t)n) {
            buf[n] = '\0';
            *size = (size_t)n;
        } else {
            free(buf);
            buf = NULL;
        }
    }
    fclose(f);
    return buf;
}

/* The library's embedded shaders are the source tree's glsl/ byte for byte,
 * every one of them, and assemble (root NULL) to the same text as from the
 * tree; DIRT_GLSL_DIR overrides them. */
static void check_embedded(const char *tree)
{
    CHECK(glsl_embedded_count > 20);
    size_t found = 0;
    for (size_t i = 0; i < glsl_embedded_count; i++) {
        const glsl_embedded_file *e = &glsl_embedded_files[i];
        if (i > 0)
            CHECK(strcmp(glsl_embedded_files[i - 1].path, e->path) < 0);
        CHECK(glsl_embedded_find(e->path) == e);
        char path[1024];
        snprintf(path, sizeof(path), "%s/%s", tree, e->path);
        size_t size = 0;
        char *disk = slurp(path, &size);
        CHECK(disk && size == e->size && memcmp(disk, e->text, size) == 0 && e->text[size] == 0);
        if (disk && size == e->size && memcmp(disk, e->text, size) == 0)
            found++;
        free(disk);
        const char *stage = glsl_stage_of(e->path);
        if (stage) {
            glsl_define defs[] = {{"DIRT_NUM_VIEWS", "7"}};
            char *a = glsl_assemble(NULL, e->path, defs, 1, NULL);
            char *b = glsl_assemble(tree, e->path, defs, 1, NULL);
            CHECK(a && b && strcmp(a, b) == 0);
            free(a);
            free(b);
        }
    }
    CHECK(found == glsl_embedded_count);
    CHECK(glsl_embedded_find("views/hiz.comp") != NULL);
    CHECK(glsl_embedded_find("views/nope.comp") == NULL);
    CHECK(glsl_embedded_find("") == NULL);
    CHECK(glsl_assemble(NULL, "views/nope.comp", NULL, 0, NULL) == NULL);

    unsetenv("DIRT_GLSL_DIR");
    CHECK(glsl_root() == NULL);
    setenv("DIRT_GLSL_DIR", "", 1);
    CHECK(glsl_root() == NULL);
    setenv("DIRT_GLSL_DIR", root, 1);
    CHECK(glsl_root() && strcmp(glsl_root(), root) == 0);
    /* A tree of its own: main.comp exists only there. */
    char *over = glsl_assemble(glsl_root(), "main.comp", NULL, 0, NULL);
    CHECK(over != NULL);
    free(over);
    CHECK(glsl_assemble(NULL, "main.comp", NULL, 0, NULL) == NULL);
    unsetenv("DIRT_GLSL_DIR");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_glsl_source GLSL_SOURCE_DIR\n");
        return 2;
    }
    snprintf(root, sizeof(root), "/tmp/dirt-glsl-test-XXXXXX");
    if (!mkdtemp(root))
        return 1;
    put("common/a.glsl", "// a\n#include \"common/b.glsl\"\nfloat a_fn() { return b_fn(); }\n");
    put("common/b.glsl", "float b_fn() { return 2.0; }\n");
    put("main.comp",
        "#version 450 core\n"
        "#include \"common/a.glsl\"\n"
        "  #  include \"common/b.glsl\"\n"
        "void main() { float x = a_fn() * FACTOR; }\n");
    put("noversion.comp", "void main() {}\n");
    put("missing.comp", "#version 450\n#include \"common/nope.glsl\"\n");
    put("bad.comp", "#version 450\n#include common/a.glsl\n");
    put("cycle.comp", "#version 450\n#include \"c1.glsl\"\n");
    put("c1.glsl", "#include \"c2.glsl\"\nint c1;\n");
    put("c2.glsl", "#include \"c1.glsl\"\nint c2;\n");

    glsl_define defs[] = {{"FACTOR", "3.0"}, {"EMPTY", NULL}};
    glsl_files files;
    char *src = glsl_assemble(root, "main.comp", defs, 2, &files);
    CHECK(src != NULL);
    if (src) {
        /* #version stays first; defines come right after it. */
        CHECK(strncmp(src, "#version 450 core\n#define FACTOR 3.0\n#define EMPTY \n", 52) == 0);
        /* b.glsl is included exactly once although named twice. */
        CHECK(count(src, "float b_fn()") == 1);
        CHECK(count(src, "float a_fn()") == 1);
        /* b's text comes before a's use of it. */
        CHECK(strstr(src, "float b_fn()") < strstr(src, "float a_fn()"));
        /* File table: main=0, a=1, b=2, and #line directives name them. */
        CHECK(files.count == 3);
        CHECK(strcmp(files.path[0], "main.comp") == 0);
        CHECK(strcmp(files.path[1], "common/a.glsl") == 0);
        CHECK(strcmp(files.path[2], "common/b.glsl") == 0);
        CHECK(strstr(src, "#line 1 1\n") != NULL);
        CHECK(strstr(src, "#line 1 2\n") != NULL);
        /* After a's include, main resumes at its line 3. */
        CHECK(strstr(src, "#line 3 0\n") != NULL);
        CHECK(strstr(src, "#include") == NULL);
        free(src);
    }
    CHECK(glsl_assemble(root, "noversion.comp", NULL, 0, NULL) == NULL);
    CHECK(glsl_assemble(root, "missing.comp", NULL, 0, NULL) == NULL);
    CHECK(glsl_assemble(root, "bad.comp", NULL, 0, NULL) == NULL);
    CHECK(glsl_assemble(root, "does-not-exist.comp", NULL, 0, NULL) == NULL);
    src = glsl_assemble(root, "cycle.comp", NULL, 0, NULL);
    CHECK(src != NULL);
    if (src) {
        CHECK(count(src, "int c1;") == 1 && count(src, "int c2;") == 1);
        free(src);
    }

    CHECK(glsl_stage_of("x/y.comp") && strcmp(glsl_stage_of("x/y.comp"), "comp") == 0);
    CHECK(glsl_stage_of("a.frag") && strcmp(glsl_stage_of("a.frag"), "frag") == 0);
    CHECK(glsl_stage_of("a.glsl") == NULL);
    CHECK(glsl_stage_of("noext") == NULL);

    check_embedded(argv[1]);

    char cmd[600];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", root);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", root);
    return check_finish();
}
