/* The memory qualifiers of a shader's storage blocks and images, read from
 * its assembled source (glsl_assemble). Pure C, no GL. The barrier checker
 * (check.c) needs them: GL's program introspection gives every block's and
 * image's binding but not whether the shader reads or writes it.
 *
 * The text is preprocessed as far as qualifiers need: object-like #define
 * and #undef, #ifdef, #ifndef, #if and #elif over defined(), integer
 * literals, macros with integer values and C's operators, #else, #endif.
 * A condition it cannot evaluate (a function-like macro) counts as both
 * true and false: the declarations of both branches are read, and a name
 * declared with different qualifiers gets the union of their accesses. */
#ifndef DIRT_GL_GLSL_IFACE_H
#define DIRT_GL_GLSL_IFACE_H

#include <stdbool.h>

enum glsl_access {
    GLSL_READ = 1,
    GLSL_WRITE = 2,
    GLSL_READ_WRITE = 3,
};

/* A storage block (`buffer Name { ... }`: name is the block name) or an
 * image uniform (`uniform image2D name`: the uniform's name). */
typedef struct glsl_decl {
    char name[64];
    bool image;
    enum glsl_access access; /* readonly: READ; writeonly: WRITE; else READ_WRITE */
} glsl_decl;

/* Writes the declarations of `text` to `out` (at most `max`, merged by
 * name) and returns how many it wrote, a number above `max` when they did
 * not all fit, or -1 when `text` is NULL. */
int glsl_memory_decls(const char *text, glsl_decl *out, int max);

#endif
