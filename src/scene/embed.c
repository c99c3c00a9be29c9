/* DIRT engine build tool: turns a file into a C source defining
 *
 *     const unsigned char NAME[];   (the file's bytes, then one 0 byte)
 *     const size_t NAME_size;       (the file's size, without that 0)
 *
 * Usage: embed INPUT OUTPUT NAME. NAME must be a C identifier. Exit status 0
 * on success; on failure a message on stderr, status 1 and no OUTPUT left. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const char *what, const char *path, FILE *in, FILE *out)
{
    fprintf(stderr, "embed: %s '%s'\n", what, path);
    if (in)
        fclose(in);
    if (out)
        fclose(out);
    return 1;
}

static int valid_identifier(const char *s)
{
    if (!*s || (*s >= '0' && *s <= '9'))
        return 0;
    for (; *s; s++) {
        char c = *s;
        if (!(c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              (c >= '0' && c <= '9')))
            return 0;
    }
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 4 || !valid_identifier(argv[3])) {
        fprintf(stderr, "usage: embed INPUT OUTPUT C_IDENTIFIER\n");
        return 1;
    }
    const char *in_path = argv[1], *out_path = argv[2], *name = argv[3];
    FILE *in = fopen(in_path, "rb");
    if (!in)
        return fail("cannot open", in_path, NULL, NULL);
    FILE *out = fopen(out_path, "wb");
    if (!out)
        return fail("cannot create", out_path, in, NULL);

    const char *base = strrchr(in_path, '/');
    base = base ? base + 1 : in_path;
    fprintf(out, "/* Generated from %s by src/scene/embed.c; do not edit. */\n", base);
    fprintf(out, "#include <stddef.h>\n\n");
    fprintf(out, "extern const unsigned char %s[];\nextern const size_t %s_size;\n\n", name,
            name);
    fprintf(out, "const unsigned char %s[] = {\n", name);
    unsigned char buf[4096];
    size_t n, total = 0;
    while ((n = fread(buf, 1, sizeof(buf), in)) > 0) {
        for (size_t i = 0; i < n; i++, total++)
            fprintf(out, "%s0x%02x,%s", total % 16 ? " " : "    ", buf[i],
                    total % 16 == 15 ? "\n" : "");
    }
    int bad_read = ferror(in) != 0;
    fclose(in);
    fprintf(out, "%s    0x00\n};\n\nconst size_t %s_size = %zu;\n", total % 16 ? "\n" : "",
            name, total);
    int bad_write = ferror(out) != 0;
    if (fclose(out) != 0)
        bad_write = 1;
    if (bad_read || bad_write) {
        remove(out_path);
        fprintf(stderr, "embed: cannot %s '%s'\n", bad_read ? "read" : "write",
                bad_read ? in_path : out_path);
        return 1;
    }
    return 0;
}
