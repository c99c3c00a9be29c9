/* The memory qualifiers the barrier checker reads from a shader's source
 * (gl/glsl_iface.h): storage blocks and image uniforms with readonly,
 * writeonly or neither; qualifiers through macros; #ifdef / #ifndef / #if /
 * #elif / #else chains, including conditions on macro values; conditions
 * it cannot evaluate read both branches (union of accesses); comments and
 * continuation lines; real shaders of glsl/ with their variants
 * (common/ray_batch.glsl's qualifier macro both ways). The barrier
 * checker also logs an error for any active block of a program that the
 * parse did not find (src/gl/check.c). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl/glsl_iface.h"
#include "gl/glsl_source.h"

static const glsl_decl *find(const glsl_decl *d, int n, const char *name, bool image)
{
    for (int i = 0; i < n; i++) {
        if (!strcmp(d[i].name, name) && d[i].image == image)
            return &d[i];
    }
    return NULL;
}

#define EXPECT(name, image, acc)                                                   \
    do {                                                                           \
        const glsl_decl *x_ = find(d, n, name, image);                             \
        CHECK_MSG(x_ && x_->access == (acc), "%s: %s", name,                        \
                  x_ ? (x_->access == GLSL_READ ? "read" : x_->access == GLSL_WRITE ? \
                        "write" : "read-write") : "missing");                      \
    } while (0)

int main(void)
{
    glsl_decl d[32];
    const char *src =
        "#version 450 core\n"
        "#define ACCESS readonly\n"
        "#define BATCH 0\n"
        "#define TWO (1 + 1)\n"
        "#define F(x) ((x) + 1)\n"
        "layout(std430, binding = 3) readonly buffer In { uint a[]; };\n"
        "layout(std430, binding = 4) writeonly buffer Out { uint b[]; } out_b;\n"
        "layout(std430, binding = 5) buffer Both { uint c; };\n"
        "layout(std430, binding = 6) ACCESS buffer Macro { uint m[]; };\n"
        "/* layout(binding = 9) writeonly buffer Commented { uint z; }; */\n"
        "// layout(binding = 9) buffer Commented2 { uint z; };\n"
        "#ifdef NOT_DEFINED\n"
        "layout(binding = 7) writeonly buffer Hidden { uint h; };\n"
        "#elif TWO == 2 && !defined(NOT_DEFINED)\n"
        "layout(binding = 7) readonly buffer Shown { uint s; };\n"
        "#else\n"
        "layout(binding = 7) writeonly buffer Hidden2 { uint h; };\n"
        "#endif\n"
        "#if BATCH\n"
        "layout(binding = 8) buffer Batch { uint w; };\n"
        "#else\n"
        "layout(binding = 8) readonly buffer Batch { uint w; };\n"
        "#endif\n"
        "#if F(1) == 2\n"
        "layout(binding = 10) readonly buffer Unknown { uint u; };\n"
        "#else\n"
        "layout(binding = 10) writeonly buffer Unknown { uint u; };\n"
        "#endif\n"
        "#if 1 + 2 * 3 == 7 && 8 >> 1 == 4 && (1 << 2 | 1) == 5 && 3 < 1 << 2 && \\\n"
        "    6 % 4 - 1 == 1 && 1 + 1 << 1 == 4 && (6 & 3 ^ 1) == 3 && 7 / 2 >= 3\n"
        "layout(binding = 13) readonly buffer Precedence { uint p; };\n"
        "#else\n"
        "layout(binding = 13) writeonly buffer Precedence { uint p; };\n"
        "#endif\n"
        "#ifndef ACCESS\n"
        "#error no\n"
        "#endif\n"
        "#undef ACCESS\n"
        "#define ACCESS writeonly\n"
        "layout(std430, binding = 11) ACCESS buffer Later { uint l[]; };\n"
        "layout(binding = 0, r32ui) uniform readonly uimage2D img_in;\n"
        "layout(binding = 1, rgba32f) writeonly uniform image2D img_out;\n"
        "layout(binding = 2, r32ui) uniform uimage2DArray img_rw;\n"
        "layout(std430, binding = 12) restrict readonly \\\n"
        "    buffer Split { uint q; };\n"
        "void f(image2D not_a_uniform) {}\n"
        "void main() { uint buffer_like = 0u; }\n";
    int n = glsl_memory_decls(src, d, 32);
    CHECK(n == 13);
    EXPECT("Precedence", false, GLSL_READ); /* C precedence */
    EXPECT("In", false, GLSL_READ);
    EXPECT("Out", false, GLSL_WRITE);
    EXPECT("Both", false, GLSL_READ_WRITE);
    EXPECT("Macro", false, GLSL_READ);
    CHECK(!find(d, n, "Commented", false) && !find(d, n, "Commented2", false));
    CHECK(!find(d, n, "Hidden", false) && !find(d, n, "Hidden2", false));
    EXPECT("Shown", false, GLSL_READ);
    EXPECT("Batch", false, GLSL_READ);
    EXPECT("Unknown", false, GLSL_READ_WRITE); /* both branches: the union */
    EXPECT("Later", false, GLSL_WRITE);
    EXPECT("img_in", true, GLSL_READ);
    EXPECT("img_out", true, GLSL_WRITE);
    EXPECT("img_rw", true, GLSL_READ_WRITE);
    EXPECT("Split", false, GLSL_READ);
    CHECK(!find(d, n, "not_a_uniform", true));
    CHECK(glsl_memory_decls(NULL, d, 32) == -1);
    CHECK(glsl_memory_decls(src, d, 2) > 2); /* more than fit: said so */

    /* The real shaders: ray_batch.glsl's macro qualifier both ways. */
    const char *root = glsl_root();
    char *text = glsl_assemble(root, "mmrt/trace.comp", NULL, 0, NULL);
    n = glsl_memory_decls(text, d, 32);
    free(text);
    EXPECT("RayBatch", false, GLSL_READ);
    EXPECT("Rays", false, GLSL_READ);
    EXPECT("Hits", false, GLSL_WRITE);
    EXPECT("Counters", false, GLSL_READ_WRITE);
    CHECK(!find(d, n, "Vertices", false)); /* only with DIRT_TRACE_ALPHA */
    glsl_define alpha = {"DIRT_TRACE_ALPHA", "1"};
    text = glsl_assemble(root, "mmrt/trace.comp", &alpha, 1, NULL);
    n = glsl_memory_decls(text, d, 32);
    free(text);
    EXPECT("Vertices", false, GLSL_READ);
    text = glsl_assemble(root, "integrator/raygen.comp", NULL, 0, NULL);
    n = glsl_memory_decls(text, d, 32);
    free(text);
    EXPECT("RayBatch", false, GLSL_READ_WRITE); /* DIRT_RAY_BATCH_ACCESS defined empty */
    text = glsl_assemble(root, "integrator/display.comp", NULL, 0, NULL);
    n = glsl_memory_decls(text, d, 32);
    free(text);
    CHECK(n > 0);
    return check_finish();
}
