#include "dirt/log.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static enum dirt_log_level g_level = DIRT_LOG_INFO;
static int g_level_init;
static dirt_log_fn g_fn;
static void *g_user;

static void init_level(void)
{
    if (g_level_init)
        return;
    g_level_init = 1;
    const char *env = getenv("DIRT_LOG");
    if (!env)
        return;
    static const char *names[] = {"error", "warn", "info", "debug"};
    for (int i = 0; i < 4; i++) {
        if (strcmp(env, names[i]) == 0)
            g_level = (enum dirt_log_level)i;
    }
}

void dirt_log_set_level(enum dirt_log_level level)
{
    g_level_init = 1;
    g_level = level;
}

enum dirt_log_level dirt_log_get_level(void)
{
    init_level();
    return g_level;
}

void dirt_log_set_callback(dirt_log_fn fn, void *user)
{
    g_fn = fn;
    g_user = user;
}

void dirt_logv(enum dirt_log_level level, const char *file, int line,
               const char *fmt, va_list ap)
{
    init_level();
    if (level > g_level)
        return;
    char msg[2048];
    vsnprintf(msg, sizeof(msg), fmt, ap);
    if (g_fn) {
        g_fn(g_user, level, file, line, msg);
        return;
    }
    static const char *tags[] = {"error", "warning", "info", "debug"};
    if (file) {
        /* Show the path relative to src/ so messages stay short. */
        const char *s = strstr(file, "src/");
        fprintf(stderr, "dirt: %s: %s:%d: %s\n", tags[level], s ? s : file, line, msg);
    } else {
        fprintf(stderr, "dirt: %s\n", msg);
    }
}

void dirt_log(enum dirt_log_level level, const char *file, int line,
              const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    dirt_logv(level, file, line, fmt, ap);
    va_end(ap);
}
