/* DIRT engine: logging.
 *
 * Every failure path in the library logs why (with file:line) before it
 * returns false/NULL. Messages go to stderr unless a callback is installed. */
#ifndef DIRT_LOG_H
#define DIRT_LOG_H

#include <stdarg.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

enum dirt_log_level {
    DIRT_LOG_ERROR = 0,
    DIRT_LOG_WARN  = 1,
    DIRT_LOG_INFO  = 2,
    DIRT_LOG_DEBUG = 3,
};

/* Receives one formatted message (no trailing newline). `file` is a source
 * path or NULL; `line` is 0 when `file` is NULL. */
typedef void (*dirt_log_fn)(void *user, enum dirt_log_level level,
                            const char *file, int line, const char *msg);

/* Messages above `level` are dropped. Default: DIRT_LOG_INFO, or the value of
 * the environment variable DIRT_LOG (error|warn|info|debug) when set. */
DIRT_API void dirt_log_set_level(enum dirt_log_level level);
DIRT_API enum dirt_log_level dirt_log_get_level(void);

/* Replaces the stderr sink; NULL restores it. Not thread-safe against
 * concurrent logging: call it at start-up. */
DIRT_API void dirt_log_set_callback(dirt_log_fn fn, void *user);

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
DIRT_API void dirt_log(enum dirt_log_level level, const char *file, int line,
                       const char *fmt, ...);
DIRT_API void dirt_logv(enum dirt_log_level level, const char *file, int line,
                        const char *fmt, va_list ap);

#define DIRT_ERROR(...) dirt_log(DIRT_LOG_ERROR, __FILE__, __LINE__, __VA_ARGS__)
#define DIRT_WARN(...)  dirt_log(DIRT_LOG_WARN, __FILE__, __LINE__, __VA_ARGS__)
#define DIRT_INFO(...)  dirt_log(DIRT_LOG_INFO, NULL, 0, __VA_ARGS__)
#define DIRT_DEBUG(...) dirt_log(DIRT_LOG_DEBUG, __FILE__, __LINE__, __VA_ARGS__)

#ifdef __cplusplus
}
#endif
#endif
