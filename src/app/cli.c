#include "app/cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

void cli_error(const char *prog, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", prog);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

bool cli_int(const char *prog, const char *option, const char *text, long lo, long hi,
             long *out)
{
    char *end = NULL;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : 0;
    if (!text || !*text || *end || errno || v < lo || v > hi) {
        cli_error(prog, "%s expects an integer in [%ld, %ld], got '%s'", option, lo, hi,
                  text ? text : "");
        return false;
    }
    *out = v;
    return true;
}

bool cli_float(const char *prog, const char *option, const char *text, double lo, double hi,
               double *out)
{
    char *end = NULL;
    errno = 0;
    double v = text ? strtod(text, &end) : 0;
    if (!text || !*text || *end || errno || !isfinite(v) || v < lo || v > hi) {
        cli_error(prog, "%s expects a number in [%g, %g], got '%s'", option, lo, hi,
                  text ? text : "");
        return false;
    }
    *out = v;
    return true;
}

bool cli_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

bool cli_output_dir_ok(const char *prog, const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(dir, sizeof(dir), ".");
    } else if (slash == path) {
        snprintf(dir, sizeof(dir), "/");
    } else {
        snprintf(dir, sizeof(dir), "%.*s", (int)(slash - path), path);
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        cli_error(prog, "cannot write '%s': directory '%s' does not exist", path, dir);
        return false;
    }
    if (access(dir, W_OK) != 0) {
        cli_error(prog, "cannot write '%s': directory '%s' is not writable", path, dir);
        return false;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error(prog, "cannot write '%s': it is a directory", path);
        return false;
    }
    return true;
}
