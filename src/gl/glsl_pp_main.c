/* dirt-glsl-pp: build-time tool. Writes the assembled text of one shader
 * (includes resolved, defines injected) exactly as the run-time loader makes
 * it, so glslangValidator checks what the driver will compile.
 *   dirt-glsl-pp ROOT PATH OUT [NAME=VALUE ...]
 * Exit 0 on success, 2 on failure (nothing written). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/glsl_source.h"

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: dirt-glsl-pp ROOT PATH OUT [NAME=VALUE ...]\n");
        return 2;
    }
    glsl_define defs[32];
    size_t n = 0;
    for (int i = 4; i < argc && n < 32; i++, n++) {
        char *eq = strchr(argv[i], '=');
        if (eq)
            *eq = '\0';
        defs[n] = (glsl_define){argv[i], eq ? eq + 1 : ""};
    }
    char *src = glsl_assemble(argv[1], argv[2], defs, n, NULL);
    if (!src)
        return 2;
    FILE *f = fopen(argv[3], "wb");
    if (!f || fputs(src, f) < 0 || fclose(f) != 0) {
        fprintf(stderr, "dirt-glsl-pp: cannot write %s\n", argv[3]);
        free(src);
        return 2;
    }
    free(src);
    return 0;
}
