/* GLSL source assembly: #include resolution and #define injection.
 * Pure C, no GL: shared by the run-time program loader and the build-time
 * validator (dirt-glsl-pp), so both see exactly the same text. */
#ifndef DIRT_GL_GLSL_SOURCE_H
#define DIRT_GL_GLSL_SOURCE_H

#include <stdbool.h>
#include <stddef.h>

/* One injected macro: `#define name value` (value may be NULL or ""). */
typedef struct glsl_define {
    const char *name;
    const char *value;
} glsl_define;

#define GLSL_MAX_FILES 64

/* Files that went into an assembled source. Index i is the source-string
 * number used in the `#line` directives of the text, so compiler messages
 * of the form "i:LINE" name files[i]. */
typedef struct glsl_files {
    int count;
    char path[GLSL_MAX_FILES][256]; /* relative to the glsl root */
} glsl_files;

/* Directory of the shader sources when they are not the library's own:
 * $DIRT_GLSL_DIR when set and not empty (development: edited shaders are
 * read at every program compile), else the folder of glsl_set_root, else NULL, which glsl_assemble takes as
 * the sources embedded into the library at build time (glsl/embed.py). */
const char *glsl_root(void);
/* The folder glsl_root() gives when $DIRT_GLSL_DIR is not set (copied;
 * NULL or "": the embedded sources again). For the program, not the
 * library: a viewer run from its build tree reads its source tree. */
void glsl_set_root(const char *dir);

struct glsl_embedded_file;
/* The embedded file `rel` (relative to glsl/), NULL when there is none. */
const struct glsl_embedded_file *glsl_embedded_find(const char *rel);

/* Reads `path` (relative to `root`; a NULL root: the embedded sources),
 * which must start with a #version line, inserts the defines right after
 * it, and replaces every line `#include "rel/path.glsl"` (relative to
 * `root`) by that file's text. A file
 * is included at most once (later includes of it are dropped), so cycles are
 * harmless. Returns a malloc'd string or NULL after logging (missing file,
 * missing #version, malformed include, too many files). `files` may be NULL. */
char *glsl_assemble(const char *root, const char *path, const glsl_define *defines,
                    size_t num_defines, glsl_files *files);

/* Pipeline stage from a file name's extension (.vert .tesc .tese .geom .frag
 * .comp), as a short name ("vert", ...), or NULL when unknown. */
const char *glsl_stage_of(const char *path);

#endif
