/* Environment maps and images read with bounds (issue 23): a 52-byte .hdr
 * declaring 16384 x 8192 texels and no pixels, and truncated .hdr files
 * (run-length and flat), fail with TRUNCATED at once and in little memory
 * (they used to load, one at 5.8 GB in 19 s); an EXR without colour
 * channels fails with NO_COLOUR instead of giving a black sky (with Y it
 * is grey); a truncated EXR fails with TRUNCATED; a FIFO, a device (through
 * a symbolic link named .hdr) or a directory fails with NOT_REGULAR without
 * blocking; a map larger than the budget (dirt_env_opts.max_bytes) fails
 * with TOO_LARGE before it is decoded; the reasons start with their ids. */
#include "check.h"

#include "dirt/image.h"
#include "integrator/integrator.h"
#include "dirt/log.h"

#include <signal.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static char dir[] = "/tmp/dirt_test_env_files_XXXXXX";

static const char *path_of(const char *name)
{
    static char b[4][512];
    static int k;
    char *p = b[k++ & 3];
    snprintf(p, 512, "%s/%s", dir, name);
    return p;
}

static void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n)
        exit(1);
    fclose(f);
}

static size_t read_all(const char *path, unsigned char **out)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        exit(1);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *out = malloc((size_t)n);
    if (!*out || fread(*out, 1, (size_t)n, f) != (size_t)n)
        exit(1);
    fclose(f);
    return (size_t)n;
}

static double peak_mb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024.0;
}

/* dirt_env_load of `name` fails and its reason starts with `id`. */
static void expect_env_fails(const char *name, const dirt_env_opts *opts, const char *id)
{
    char why[512] = "";
    dirt_env *e = dirt_env_load(path_of(name), opts, why, sizeof(why));
    fprintf(stderr, "-- %s: %s\n", name, e ? "loaded" : why);
    CHECK_MSG(e == NULL, "%s loaded", name);
    CHECK_MSG(strncmp(why, id, strlen(id)) == 0 && why[strlen(id)] == ':',
              "%s: reason '%s', expected %s", name, why, id);
    dirt_env_destroy(e);
}

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "a read blocked (a FIFO?)\n";
    ssize_t w = write(2, msg, sizeof(msg) - 1);
    (void)w;
    _exit(1);
}

/* A 64 x 32 map, RGBE run-length encoded by stb_image_write. */
static void write_map_hdr(const char *name, int w, int h)
{
    float *rgb = malloc((size_t)w * h * 3 * sizeof(float));
    for (int k = 0; k < w * h * 3; k++)
        rgb[k] = (float)(k % 17) * 0.25f + 0.1f;
    CHECK(stbi_write_hdr(path_of(name), w, h, 3, rgb) != 0);
    free(rgb);
}

static void test_hdr(void)
{
    /* The file: a header declaring 16384 x 8192 and no pixels. */
    static const char lie[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n";
    write_bytes(path_of("lie.hdr"), lie, sizeof(lie) - 1);
    CHECK(sizeof(lie) - 1 == 52);
    double rss0 = peak_mb();
    clock_t t0 = clock();
    expect_env_fails("lie.hdr", NULL, "TRUNCATED");
    double grew = peak_mb() - rss0, secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    fprintf(stderr, "52-byte .hdr: %.3f s CPU, peak RSS grew %.1f MB\n", secs, grew);
    CHECK_MSG(grew < 16.0, "the 52-byte .hdr grew the peak RSS by %.1f MB", grew);
    CHECK_MSG(secs < 1.0, "the 52-byte .hdr took %.2f s", secs);

    /* A run-length encoded map cut in half, and cut by one byte. */
    write_map_hdr("rle.hdr", 64, 32);
    char why[512];
    dirt_env *e = dirt_env_load(path_of("rle.hdr"), NULL, why, sizeof(why));
    CHECK_MSG(e && e->width == 64 && e->height == 32, "the whole map: %s", why);
    dirt_env_destroy(e);
    unsigned char *b = NULL;
    size_t n = read_all(path_of("rle.hdr"), &b);
    write_bytes(path_of("rle_half.hdr"), b, n / 2);
    expect_env_fails("rle_half.hdr", NULL, "TRUNCATED");
    write_bytes(path_of("rle_short.hdr"), b, n - 1);
    expect_env_fails("rle_short.hdr", NULL, "TRUNCATED");
    /* A run past the row's end. */
    size_t hdr_end = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        if (b[i] == '\n' && b[i + 1] == '-') {
            while (b[i + 1] != '\n')
                i++;
            hdr_end = i + 2;
            break;
        }
    }
    CHECK(hdr_end > 0 && b[hdr_end] == 2 && b[hdr_end + 1] == 2);
    unsigned char *bad = malloc(n);
    memcpy(bad, b, n);
    bad[hdr_end + 4] = 128 + 127; /* a run of 127 in a row of 64 */
    write_bytes(path_of("rle_run.hdr"), bad, n);
    expect_env_fails("rle_run.hdr", NULL, "INVALID");
    free(bad);
    free(b);
    /* Flat (width under 8): 4 x 4 texels need 64 bytes of pixels. */
    write_map_hdr("flat.hdr", 4, 4);
    n = read_all(path_of("flat.hdr"), &b);
    e = dirt_env_load(path_of("flat.hdr"), NULL, why, sizeof(why));
    CHECK_MSG(e && e->width == 4, "a flat map: %s", why);
    dirt_env_destroy(e);
    write_bytes(path_of("flat_short.hdr"), b, n - 4);
    expect_env_fails("flat_short.hdr", NULL, "TRUNCATED");
    free(b);
    /* Not RGBE at all; another pixel format. */
    write_bytes(path_of("text.hdr"), "hello\n", 6);
    expect_env_fails("text.hdr", NULL, "INVALID");
    static const char xyze[] = "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 2\n0000000000000000";
    write_bytes(path_of("xyze.hdr"), xyze, sizeof(xyze) - 1);
    expect_env_fails("xyze.hdr", NULL, "INVALID");
    /* Over the budget: a 64 x 32 map needs its file and 44 bytes a texel
     * (stb_image's RGB, the image's RGBA, the map's RGB and cdf). */
    size_t need = read_all(path_of("rle.hdr"), &b) + 64 * 32 * 44;
    free(b);
    expect_env_fails("rle.hdr", &(dirt_env_opts){.max_bytes = need - 1}, "TOO_LARGE");
    e = dirt_env_load(path_of("rle.hdr"), &(dirt_env_opts){.max_bytes = need}, why, sizeof(why));
    CHECK_MSG(e != NULL, "a map within its budget: %s", why);
    dirt_env_destroy(e);
}

static void test_exr(void)
{
    /* An EXR with only a Z channel: no colour, not a black sky. */
    dirt_image *img = dirt_image_create(8, 4);
    float *z = dirt_image_add_channel(img, "Z");
    for (int k = 0; k < 32; k++)
        z[k] = 1.0f + (float)k;
    dirt_image_write_options wo = {0};
    (void)wo;
    CHECK(dirt_image_write_exr(img, path_of("z.exr"), NULL));
    /* (dirt_image_write_exr writes R, G, B, A too: write one without.) */
    dirt_image_destroy(img);
    img = dirt_image_create(8, 4);
    for (int k = 0; k < 32; k++)
        img->rgba[4 * k] = img->rgba[4 * k + 1] = img->rgba[4 * k + 2] = 0.5f;
    CHECK(dirt_image_write_exr(img, path_of("rgb.exr"), NULL));
    char why[512];
    dirt_env *e = dirt_env_load(path_of("rgb.exr"), NULL, why, sizeof(why));
    CHECK_MSG(e && e->rgb[0] == 0.5f, "an RGB map: %s", why);
    dirt_env_destroy(e);
    dirt_image_destroy(img);
    /* Rename the channels of a written file: R, G, B, A -> P, Q, S, Z (same
     * length, the header is otherwise unchanged). */
    unsigned char *b = NULL;
    size_t n = read_all(path_of("rgb.exr"), &b);
    int renamed = 0;
    for (size_t i = 0; i + 2 < n && i < 400; i++) {
        if (b[i] == 0 && (b[i + 1] == 'R' || b[i + 1] == 'G' || b[i + 1] == 'B' ||
                          b[i + 1] == 'A') && b[i + 2] == 0) {
            b[i + 1] = b[i + 1] == 'R' ? 'P' : b[i + 1] == 'G' ? 'Q' : b[i + 1] == 'B' ? 'S' : 'Z';
            renamed++;
        }
    }
    CHECK(renamed == 4);
    write_bytes(path_of("nocolour.exr"), b, n);
    expect_env_fails("nocolour.exr", NULL, "NO_COLOUR");
    /* The same bytes with P renamed Y: grey. */
    for (size_t i = 0; i + 2 < n && i < 400; i++) {
        if (b[i] == 0 && b[i + 1] == 'P' && b[i + 2] == 0)
            b[i + 1] = 'Y';
    }
    write_bytes(path_of("grey.exr"), b, n);
    e = dirt_env_load(path_of("grey.exr"), NULL, why, sizeof(why));
    CHECK_MSG(e && e->rgb[0] == 0.5f && e->rgb[1] == 0.5f, "a Y map: %s", why);
    dirt_env_destroy(e);
    /* A truncated EXR: its last chunks missing. */
    write_bytes(path_of("cut.exr"), b, n - 20);
    expect_env_fails("cut.exr", NULL, "TRUNCATED");
    free(b);
    /* dirt_image_read: the reference image of dirt-render, by extension. */
    enum dirt_input_error err = DIRT_INPUT_ERR_OK;
    CHECK(dirt_image_read(path_of("cut.exr"), NULL, &err) == NULL &&
          err == DIRT_INPUT_ERR_TRUNCATED);
    img = dirt_image_read(path_of("rgb.exr"), NULL, &err);
    CHECK(img && err == DIRT_INPUT_ERR_OK && img->width == 8);
    dirt_image_destroy(img);
    /* 8 x 4 pixels of RGBA in HALF: 16 + 4 x 2 bytes each. */
    CHECK(dirt_image_read(path_of("rgb.exr"), &(dirt_image_read_opts){.max_bytes = 32 * 24 - 1},
                          &err) == NULL && err == DIRT_INPUT_ERR_TOO_LARGE);
    img = dirt_image_read(path_of("rgb.exr"), &(dirt_image_read_opts){.max_bytes = 32 * 32}, &err);
    CHECK(img != NULL);
    dirt_image_destroy(img);
    CHECK(dirt_image_read(path_of("none.exr"), NULL, &err) == NULL &&
          err == DIRT_INPUT_ERR_MISSING);
}

static void test_special(void)
{
    alarm(20);
    mkfifo(path_of("fifo.exr"), 0600);
    expect_env_fails("fifo.exr", NULL, "NOT_REGULAR");
    mkfifo(path_of("fifo.hdr"), 0600);
    expect_env_fails("fifo.hdr", NULL, "NOT_REGULAR");
    if (symlink("/dev/zero", path_of("zero.hdr")) != 0)
        perror("symlink");
    expect_env_fails("zero.hdr", NULL, "NOT_REGULAR");
    mkdir(path_of("dir.exr"), 0700);
    expect_env_fails("dir.exr", NULL, "NOT_REGULAR");
    expect_env_fails("missing.hdr", NULL, "MISSING");
    alarm(0);
}

int main(void)
{
    signal(SIGALRM, on_alarm);
    if (!mkdtemp(dir))
        return 1;
    test_hdr();
    test_exr();
    test_special();
    char cmd[600];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_finish();
}
