#include "gl/glsl_source.h"

#include "gl/glsl_embedded.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"

static char set_root[4096];

const char *glsl_root(void)
{
    const char *env = getenv("DIRT_GLSL_DIR");
    return env && *env ? env : set_root[0] ? set_root : NULL;
}

void glsl_set_root(const char *dir)
{
    snprintf(set_root, sizeof(set_root), "%s", dir && strlen(dir) < sizeof(set_root) ? dir : "");
}

const glsl_embedded_file *glsl_embedded_find(const char *rel)
{
    size_t lo = 0, hi = glsl_embedded_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(rel, glsl_embedded_files[mid].path);
        if (c == 0)
            return &glsl_embedded_files[mid];
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    return NULL;
}

/* Growable string. */
typedef struct sbuf {
    char *data;
    size_t len, cap;
    bool oom;
} sbuf;

static void sb_append(sbuf *b, const char *s, size_t n)
{
    if (b->oom)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 4096;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *d = realloc(b->data, cap);
        if (!d) {
            b->oom = true;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

static void sb_printf(sbuf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof(tmp), fmt, ap);
    va_end(ap);
    if (n > 0)
        sb_append(b, tmp, (size_t)n < sizeof(tmp) ? (size_t)n : sizeof(tmp) - 1);
}

/* How messages name a root: the directory, or the embedded glsl/. */
static const char *root_name(const char *root)
{
    return root ? root : "glsl (embedded)";
}

static char *read_text(const char *root, const char *rel)
{
    if (!root) {
        const glsl_embedded_file *e = glsl_embedded_find(rel);
        char *copy = e ? malloc(e->size + 1) : NULL;
        if (!e)
            DIRT_ERROR("no shader source glsl/%s in the library (set DIRT_GLSL_DIR to read "
                       "shaders from a directory)", rel);
        else if (!copy)
            DIRT_ERROR("out of memory reading shader source glsl/%s", rel);
        else
            memcpy(copy, e->text, e->size + 1);
        return copy;
    }
    char full[4096];
    snprintf(full, sizeof(full), "%s/%s", root, rel);
    FILE *f = fopen(full, "rb");
    if (!f) {
        DIRT_ERROR("cannot open shader source %s", full);
        return NULL;
    }
    char *text = NULL;
    if (fseek(f, 0, SEEK_END) != 0)
        goto error;
    long size = ftell(f);
    if (size < 0 || fseek(f, 0, SEEK_SET) != 0)
        goto error;
    text = malloc((size_t)size + 1);
    if (!text || fread(text, 1, (size_t)size, f) != (size_t)size)
        goto error;
    text[size] = '\0';
    fclose(f);
    return text;
error:
    DIRT_ERROR("cannot read shader source %s", full);
    free(text);
    fclose(f);
    return NULL;
}

static int find_file(const glsl_files *files, const char *rel)
{
    for (int i = 0; i < files->count; i++) {
        if (strcmp(files->path[i], rel) == 0)
            return i;
    }
    return -1;
}

/* Parses `#include "x"` at the start of `line` (leading blanks allowed).
 * Returns 1 and fills `out` for an include, 0 for another line, -1 when the
 * include is malformed. */
static int parse_include(const char *line, size_t len, char *out, size_t out_size)
{
    size_t i = 0;
    while (i < len && (line[i] == ' ' || line[i] == '\t'))
        i++;
    if (i >= len || line[i] != '#')
        return 0;
    i++;
    while (i < len && (line[i] == ' ' || line[i] == '\t'))
        i++;
    if (len - i < 7 || strncmp(line + i, "include", 7) != 0)
        return 0;
    i += 7;
    while (i < len && (line[i] == ' ' || line[i] == '\t'))
        i++;
    if (i >= len || line[i] != '"')
        return -1;
    size_t start = ++i;
    while (i < len && line[i] != '"')
        i++;
    if (i >= len || i - start == 0 || i - start >= out_size)
        return -1;
    memcpy(out, line + start, i - start);
    out[i - start] = '\0';
    return 1;
}

static bool append_file(sbuf *b, const char *root, const char *rel, glsl_files *files,
                        const glsl_define *defines, size_t num_defines, bool top)
{
    if (files->count >= GLSL_MAX_FILES) {
        DIRT_ERROR("shader %s: more than %d included files", rel, GLSL_MAX_FILES);
        return false;
    }
    int index = files->count++;
    snprintf(files->path[index], sizeof(files->path[index]), "%s", rel);
    char *text = read_text(root, rel);
    if (!text)
        return false;
    bool ok = true;
    bool seen_version = false;
    int line_no = 0;
    if (!top)
        sb_printf(b, "#line 1 %d\n", index);
    for (char *p = text; *p && ok;) {
        char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        line_no++;
        char inc[256];
        int kind = parse_include(p, len, inc, sizeof(inc));
        if (kind < 0) {
            DIRT_ERROR("%s/%s:%d: malformed #include", root_name(root), rel, line_no);
            ok = false;
        } else if (kind > 0) {
            if (find_file(files, inc) < 0) {
                ok = append_file(b, root, inc, files, NULL, 0, false);
                sb_printf(b, "#line %d %d\n", line_no + 1, index);
            } else {
                sb_append(b, "\n", 1); /* keep line numbers */
            }
        } else {
            sb_append(b, p, len);
            sb_append(b, "\n", 1);
            if (top && !seen_version) {
                const char *q = p;
                while (q < p + len && (*q == ' ' || *q == '\t'))
                    q++;
                if (strncmp(q, "#version", 8) == 0) {
                    seen_version = true;
                    for (size_t d = 0; d < num_defines; d++) {
                        sb_printf(b, "#define %s %s\n", defines[d].name,
                                  defines[d].value ? defines[d].value : "");
                    }
                    sb_printf(b, "#line %d %d\n", line_no + 1, index);
                } else if (len > 0 && strncmp(q, "//", 2) != 0 && q < p + len) {
                    DIRT_ERROR("%s/%s: the first line must be #version", root_name(root), rel);
                    ok = false;
                }
            }
        }
        p = eol ? eol + 1 : p + len;
    }
    if (ok && top && !seen_version) {
        DIRT_ERROR("%s/%s: no #version line", root_name(root), rel);
        ok = false;
    }
    free(text);
    return ok;
}

char *glsl_assemble(const char *root, const char *path, const glsl_define *defines,
                    size_t num_defines, glsl_files *files)
{
    glsl_files local;
    if (!files)
        files = &local;
    files->count = 0;
    sbuf b = {0};
    if (!append_file(&b, root, path, files, defines, num_defines, true) || b.oom) {
        if (b.oom)
            DIRT_ERROR("out of memory assembling shader %s", path);
        free(b.data);
        return NULL;
    }
    return b.data;
}

const char *glsl_stage_of(const char *path)
{
    static const char *stages[] = {"vert", "tesc", "tese", "geom", "frag", "comp"};
    const char *dot = strrchr(path, '.');
    if (!dot)
        return NULL;
    for (size_t i = 0; i < sizeof(stages) / sizeof(stages[0]); i++) {
        if (strcmp(dot + 1, stages[i]) == 0)
            return stages[i];
    }
    return NULL;
}
