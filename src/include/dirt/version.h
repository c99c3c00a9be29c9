/* DIRT engine: the library's version.
 *
 * The macros are the version a program was compiled against; dirt_version()
 * is the version of the library it runs with. The major number is the API's:
 * it names the shared library (libdirt.so.MAJOR). The build fails when these
 * macros differ from meson's project version (src/core/meson.build). */
#ifndef DIRT_VERSION_H
#define DIRT_VERSION_H

#define DIRT_VERSION_MAJOR 0
#define DIRT_VERSION_MINOR 1
#define DIRT_VERSION_PATCH 0

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* "MAJOR.MINOR.PATCH" of the library in use; a static string. */
DIRT_API const char *dirt_version(void);
/* The commit the library was built from (`git describe --always --dirty`),
 * or "unknown" outside a git checkout; a static string. */
DIRT_API const char *dirt_version_commit(void);

#ifdef __cplusplus
}
#endif

#endif
