/* dirt-view's script parser (view_script.h). */
#include "app/view_script.h"

#include "dirt/input.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const struct {
    const char *word;
    enum vs_kind kind;
    int nums;        /* numbers that follow (camera: see below) */
    int min_nums;
    bool text;       /* a path or value follows */
} verbs[] = {
    {"wait-frames", VS_WAIT_FRAMES, 1, 1, false}, {"wait-samples", VS_WAIT_SAMPLES, 1, 1, false},
    {"wait-file", VS_WAIT_FILE, 0, 0, true},
    {"orbit", VS_ORBIT, 2, 2, false}, {"pan", VS_PAN, 2, 2, false},
    {"dolly", VS_DOLLY, 1, 1, false}, {"fly", VS_FLY, 3, 3, false},
    {"camera", VS_CAMERA, 0, 0, false}, {"key", VS_KEY, 1, 0, false},
    {"click", VS_CLICK, 2, 2, false}, {"set", VS_SET, 0, 0, true},
    {"resize", VS_RESIZE, 2, 2, false}, {"screenshot", VS_SCREENSHOT, 0, 0, true},
    {"save-image", VS_SAVE_IMAGE, 0, 0, true}, {"report", VS_REPORT, 0, 0, true},
    {"print-camera", VS_PRINT_CAMERA, 0, 0, false}, {"quit", VS_QUIT, 0, 0, false},
    {"zoom", VS_ZOOM, 3, 1, false}, {"pan-image", VS_PAN_IMAGE, 2, 2, false},
    {"bookmark", VS_BOOKMARK, 0, 0, false},
};

static bool number(const char *tok, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(tok, &end);
    if (end == tok || *end || errno || !isfinite(v))
        return false;
    *out = v;
    return true;
}

/* Splits `line` in place into at most `max` blank-separated words. */
static int split(char *line, char **words, int max)
{
    int n = 0;
    for (char *p = strtok(line, " \t\r"); p && n < max; p = strtok(NULL, " \t\r"))
        words[n++] = p;
    return n;
}

static bool ends_with(const char *s, const char *ext)
{
    size_t n = strlen(s), m = strlen(ext);
    if (n < m)
        return false;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if ((c >= 'A' && c <= 'Z' ? c + 32 : c) != ext[i])
            return false;
    }
    return true;
}

static bool parse_line(char *line, int no, vs_action *a, char *why, size_t size)
{
    char *w[8];
    int n = split(line, w, 8);
    memset(a, 0, sizeof(*a));
    a->line = no;
    size_t v = 0, nv = sizeof(verbs) / sizeof(verbs[0]);
    while (v < nv && strcmp(w[0], verbs[v].word))
        v++;
    if (v == nv) {
        snprintf(why, size, "line %d: unknown action '%s'", no, w[0]);
        return false;
    }
    a->kind = verbs[v].kind;
    int args = n - 1;
    switch (a->kind) {
    case VS_CAMERA:
        if (args != 1) {
            snprintf(why, size, "line %d: camera takes one of: an index, auto, default", no);
            return false;
        }
        if (!strcmp(w[1], "auto") || !strcmp(w[1], "default")) {
            snprintf(a->name, sizeof(a->name), "%s", w[1]);
        } else if (!number(w[1], &a->num[0]) || a->num[0] < 0 || a->num[0] != floor(a->num[0])) {
            snprintf(why, size, "line %d: camera '%s' is not an index, auto or default", no, w[1]);
            return false;
        }
        return true;
    case VS_KEY:
        if (args < 1 || args > 2) {
            snprintf(why, size, "line %d: key takes a key name and optional frames", no);
            return false;
        }
        snprintf(a->name, sizeof(a->name), "%s", w[1]);
        a->num[0] = 1;
        if (args == 2 && (!number(w[2], &a->num[0]) || a->num[0] < 1)) {
            snprintf(why, size, "line %d: key frames '%s' must be a number >= 1", no, w[2]);
            return false;
        }
        return true;
    case VS_ZOOM:
        if (args == 1 && !strcmp(w[1], "fit")) {
            snprintf(a->name, sizeof(a->name), "fit");
            return true;
        }
        if (args != 1 && args != 3) {
            snprintf(why, size, "line %d: zoom takes a factor and optionally a window pixel X Y, "
                     "or fit", no);
            return false;
        }
        a->num[1] = a->num[2] = -1; /* the window's centre */
        for (int k = 0; k < args; k++) {
            if (!number(w[1 + k], &a->num[k]) || (k == 0 && !(a->num[0] > 0 && a->num[0] <= 64))) {
                snprintf(why, size, "line %d: zoom '%s' must be a factor in (0, 64], or fit", no,
                         w[1 + k]);
                return false;
            }
        }
        return true;
    case VS_BOOKMARK:
        if (args != 2 || (strcmp(w[1], "save") && strcmp(w[1], "go") && strcmp(w[1], "delete")) ||
            !number(w[2], &a->num[0]) || a->num[0] < 1 || a->num[0] > 9 ||
            a->num[0] != floor(a->num[0])) {
            snprintf(why, size, "line %d: bookmark takes save, go or delete and a slot 1 .. 9", no);
            return false;
        }
        snprintf(a->name, sizeof(a->name), "%s", w[1]);
        return true;
    case VS_SET:
        if (args != 2) {
            snprintf(why, size, "line %d: set takes an option and a value", no);
            return false;
        }
        snprintf(a->name, sizeof(a->name), "%s", w[1]);
        snprintf(a->text, sizeof(a->text), "%s", w[2]);
        return true;
    case VS_WAIT_FILE: case VS_SCREENSHOT: case VS_SAVE_IMAGE: case VS_REPORT: {
        const char *ext = a->kind == VS_SCREENSHOT ? ".png" : a->kind == VS_REPORT ? ".json"
                          : a->kind == VS_WAIT_FILE ? "" : NULL;
        if (args != 1 || (ext && !ends_with(w[1], ext)) ||
            (!ext && !ends_with(w[1], ".exr") && !ends_with(w[1], ".png"))) {
            snprintf(why, size, "line %d: %s takes one %s%spath", no, verbs[v].word,
                     ext ? ext : ".exr or .png", ext && !*ext ? "" : " ");
            return false;
        }
        if (strlen(w[1]) >= sizeof(a->text)) {
            snprintf(why, size, "line %d: path too long", no);
            return false;
        }
        snprintf(a->text, sizeof(a->text), "%s", w[1]);
        return true;
    }
    default:
        break;
    }
    if (args < verbs[v].min_nums || args > verbs[v].nums) {
        snprintf(why, size, "line %d: %s takes %d number(s), got %d", no, verbs[v].word,
                 verbs[v].nums, args);
        return false;
    }
    for (int k = 0; k < args; k++) {
        if (!number(w[1 + k], &a->num[k])) {
            snprintf(why, size, "line %d: '%s' is not a number", no, w[1 + k]);
            return false;
        }
    }
    bool bad = false;
    if (a->kind == VS_WAIT_FRAMES || a->kind == VS_WAIT_SAMPLES)
        bad = a->num[0] < 0 || a->num[0] > 1e9 || a->num[0] != floor(a->num[0]);
    else if (a->kind == VS_DOLLY)
        bad = !(a->num[0] > 0);
    else if (a->kind == VS_RESIZE)
        bad = a->num[0] < 16 || a->num[1] < 16 || a->num[0] > 16384 || a->num[1] > 16384;
    if (bad) {
        snprintf(why, size, "line %d: %s: value out of range", no, verbs[v].word);
        return false;
    }
    return true;
}

bool vs_parse(const char *text, view_script *out, char *why, size_t size)
{
    memset(out, 0, sizeof(*out));
    size_t cap = 0;
    int no = 0;
    for (const char *p = text; *p;) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        no++;
        char line[8192];
        if (len >= sizeof(line)) {
            snprintf(why, size, "line %d: too long", no);
            goto error;
        }
        memcpy(line, p, len);
        line[len] = '\0';
        p += len + (eol ? 1 : 0);
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *q = line;
        while (*q == ' ' || *q == '\t' || *q == '\r')
            q++;
        if (!*q)
            continue;
        if (out->count == cap) {
            cap = cap ? 2 * cap : 16;
            vs_action *grown = realloc(out->actions, cap * sizeof(*grown));
            if (!grown) {
                snprintf(why, size, "out of memory");
                goto error;
            }
            out->actions = grown;
        }
        if (!parse_line(q, no, &out->actions[out->count], why, size))
            goto error;
        out->count++;
    }
    return true;
error:
    vs_free(out);
    return false;
}

bool vs_load(const char *path, view_script *out, char *why, size_t size)
{
    memset(out, 0, sizeof(*out));
    enum dirt_input_error e;
    size_t len = 0;
    char *text = dirt_input_read(path, (size_t)64 << 20, &len, &e);
    if (!text) {
        snprintf(why, size, "%s: cannot read script '%s': %s%s%s", dirt_input_error_name(e), path,
                 dirt_input_error_str(e), e == DIRT_INPUT_ERR_IO ? ": " : "",
                 e == DIRT_INPUT_ERR_IO ? strerror(errno) : "");
        return false;
    }
    bool ok;
    if (memchr(text, '\0', len)) {
        snprintf(why, size, "INVALID: script '%s' is not text", path);
        free(text);
        return false;
    }
    char inner[512];
    ok = vs_parse(text, out, inner, sizeof(inner));
    if (!ok)
        snprintf(why, size, "script '%s', %s", path, inner);
    free(text);
    return ok;
}

size_t vs_outputs(const view_script *s, const char **out, char (*png)[4200], size_t max)
{
    size_t n = 0;
    for (size_t i = 0; i < s->count && n < max; i++) {
        const vs_action *a = &s->actions[i];
        if (a->kind != VS_SCREENSHOT && a->kind != VS_SAVE_IMAGE && a->kind != VS_REPORT)
            continue;
        out[n++] = a->text;
        size_t len = strlen(a->text);
        if (a->kind == VS_SAVE_IMAGE && n < max && len >= 4 &&
            !strcasecmp(a->text + len - 4, ".exr")) {
            snprintf(png[n], 4200, "%.*s.png", (int)(len - 4), a->text);
            out[n] = png[n];
            n++;
        }
    }
    return n;
}

void vs_free(view_script *s)
{
    free(s->actions);
    s->actions = NULL;
    s->count = 0;
}
