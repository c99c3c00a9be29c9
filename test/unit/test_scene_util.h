/* Helpers for the scene tests: a temporary directory, small glTF files
 * written from C (base64 data-URI buffers, .glb containers), and a log
 * capture that counts errors and warnings. */
#ifndef DIRT_TEST_SCENE_UTIL_H
#define DIRT_TEST_SCENE_UTIL_H

#include "dirt/log.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmp_dir_[256];

/* Creates the test's temporary directory once; returns its path. */
static inline const char *tmp_dir(void)
{
    if (!tmp_dir_[0]) {
        snprintf(tmp_dir_, sizeof(tmp_dir_), "/tmp/dirt_scene_test_XXXXXX");
        if (!mkdtemp(tmp_dir_)) {
            perror("mkdtemp");
            exit(1);
        }
    }
    return tmp_dir_;
}

/* Path of `name` inside the temporary directory (static buffer rotation). */
static inline const char *tmp_file(const char *name)
{
    static char bufs[4][512];
    static int next;
    char *b = bufs[next++ & 3];
    snprintf(b, 512, "%s/%s", tmp_dir(), name);
    return b;
}

static inline void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n) {
        perror(path);
        exit(1);
    }
    fclose(f);
}

static inline void write_text(const char *path, const char *text)
{
    write_bytes(path, text, strlen(text));
}

/* Removes the files written and the directory (best effort). */
static inline void tmp_cleanup(const char *const *names, size_t n)
{
    for (size_t i = 0; i < n; i++)
        remove(tmp_file(names[i]));
    if (tmp_dir_[0])
        rmdir(tmp_dir_);
}

/* "data:application/octet-stream;base64,..." of n bytes; caller frees. */
static inline char *data_uri(const void *data, size_t n)
{
    static const char tab[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    static const char prefix[] = "data:application/octet-stream;base64,";
    const uint8_t *p = data;
    size_t len = strlen(prefix) + (n + 2) / 3 * 4 + 1;
    char *out = malloc(len);
    if (!out)
        exit(1);
    strcpy(out, prefix);
    char *o = out + strlen(prefix);
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16;
        if (i + 1 < n)
            v |= (uint32_t)p[i + 1] << 8;
        if (i + 2 < n)
            v |= p[i + 2];
        *o++ = tab[(v >> 18) & 63];
        *o++ = tab[(v >> 12) & 63];
        *o++ = i + 1 < n ? tab[(v >> 6) & 63] : '=';
        *o++ = i + 2 < n ? tab[v & 63] : '=';
    }
    *o = '\0';
    return out;
}

/* printf into a malloc'd string. */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static inline char *strf(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = malloc((size_t)n + 1);
    if (!s)
        exit(1);
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

static inline void put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* A .glb of `json` (buffer 0 without uri = the BIN chunk) and `bin`.
 * Returns the byte count; *out is malloc'd. */
static inline size_t make_glb(const char *json, const void *bin, size_t bin_len, uint8_t **out)
{
    size_t jl = (strlen(json) + 3) & ~(size_t)3;
    size_t bl = (bin_len + 3) & ~(size_t)3;
    size_t total = 12 + 8 + jl + (bin_len ? 8 + bl : 0);
    uint8_t *g = calloc(1, total);
    if (!g)
        exit(1);
    memcpy(g, "glTF", 4);
    put_le32(g + 4, 2);
    put_le32(g + 8, (uint32_t)total);
    put_le32(g + 12, (uint32_t)jl);
    memcpy(g + 16, "JSON", 4);
    memset(g + 20, ' ', jl);
    memcpy(g + 20, json, strlen(json));
    if (bin_len) {
        put_le32(g + 20 + jl, (uint32_t)bl);
        memcpy(g + 24 + jl, "BIN\0", 4);
        memcpy(g + 28 + jl, bin, bin_len);
    }
    *out = g;
    return total;
}

/* Log capture: counts errors and warnings, keeps the last error, and
 * forwards everything to stderr so failures are readable. */
static int log_errors_, log_warnings_;
static char log_last_error_[512];

static inline void capture_log(void *user, enum dirt_log_level level, const char *file, int line,
                        const char *msg)
{
    (void)user;
    if (level == DIRT_LOG_ERROR) {
        log_errors_++;
        snprintf(log_last_error_, sizeof(log_last_error_), "%s", msg);
    } else if (level == DIRT_LOG_WARN) {
        log_warnings_++;
    }
    fprintf(stderr, "  [log %d] %s:%d: %s\n", (int)level, file ? file : "-", line, msg);
}

static inline void log_capture_start(void)
{
    dirt_log_set_callback(capture_log, NULL);
    log_errors_ = log_warnings_ = 0;
    log_last_error_[0] = '\0';
}

#endif
