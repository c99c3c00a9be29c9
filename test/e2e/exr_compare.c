/* DIRT engine: a small image checker for the e2e scripts.
 *   exr_compare A.exr B.exr MAX_REL_MSE   relative MSE of A against B (the
 *                                         reference) at most MAX_REL_MSE
 *   exr_compare --not-black A.exr MIN     mean luminance of A at least MIN
 *   exr_compare --mean A.exr REF.exr TOL  mean luminances within a factor
 *                                         1 +- TOL of each other
 *   exr_compare --exact A.exr B.exr       the same size and channels, every
 *                                         pixel value bit for bit
 *   exr_compare --attrs A.exr NAME...     each NAME is a string attribute
 *                                         of A's header with a value that is
 *                                         not empty (read with OpenEXR's
 *                                         own API); prints NAME=VALUE lines
 * Prints the figure; exit 0 when the condition holds, 1 when it does not,
 * 2 on unreadable input. */
#include "dirt/image.h"

#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --exact: 0 when a and b hold the same bits in every plane, else 1. */
static int exact(const char *pa, const char *pb)
{
    dirt_image *a = dirt_image_read_exr(pa), *b = dirt_image_read_exr(pb);
    int rc = 2;
    if (!a || !b)
        goto done;
    rc = 1;
    size_t n = (size_t)a->width * (size_t)a->height;
    if (a->width != b->width || a->height != b->height || a->channel_count != b->channel_count) {
        printf("%s vs %s: sizes or channel counts differ\n", pa, pb);
        goto done;
    }
    if (memcmp(a->rgba, b->rgba, 4 * n * sizeof(float)) != 0) {
        printf("%s vs %s: RGBA differ\n", pa, pb);
        goto done;
    }
    for (int c = 0; c < a->channel_count; c++) {
        const float *q = dirt_image_find_channel(b, a->channels[c].name);
        if (!q || memcmp(a->channels[c].data, q, n * sizeof(float)) != 0) {
            printf("%s vs %s: channel %s differs\n", pa, pb, a->channels[c].name);
            goto done;
        }
    }
    printf("%s vs %s: identical pixels (%d extra channels)\n", pa, pb, a->channel_count);
    rc = 0;
done:
    dirt_image_destroy(a);
    dirt_image_destroy(b);
    return rc;
}

/* --attrs: 0 when every name is a non-empty string attribute of part 0. */
static int attrs(const char *path, int n, char **names)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "exr_compare: cannot read %s\n", path);
        return 2;
    }
    int rc = 0;
    for (int i = 0; i < n; i++) {
        const char *value = NULL;
        int32_t len = 0;
        if (exr_attr_get_string(ctx, 0, names[i], &len, &value) != EXR_ERR_SUCCESS || !value ||
            len <= 0) {
            printf("%s: no string attribute '%s'\n", path, names[i]);
            rc = 1;
            continue;
        }
        printf("%s=%.*s\n", names[i], (int)len, value);
    }
    exr_finish(&ctx);
    return rc;
}

/* Mean Rec. 709 luminance; -1 when unreadable. */
static double mean_luminance(const char *path)
{
    dirt_image *a = dirt_image_read_exr(path);
    if (!a)
        return -1;
    double sum = 0;
    size_t n = (size_t)a->width * (size_t)a->height;
    for (size_t i = 0; i < n; i++)
        sum += 0.2126 * a->rgba[4 * i] + 0.7152 * a->rgba[4 * i + 1] + 0.0722 * a->rgba[4 * i + 2];
    dirt_image_destroy(a);
    return n ? sum / (double)n : 0;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "--exact"))
        return exact(argv[2], argv[3]);
    if (argc >= 4 && !strcmp(argv[1], "--attrs"))
        return attrs(argv[2], argc - 3, argv + 3);
    if (argc == 5 && !strcmp(argv[1], "--mean")) {
        double a = mean_luminance(argv[2]), b = mean_luminance(argv[3]), tol = atof(argv[4]);
        if (a < 0 || b < 0)
            return 2;
        printf("%s: mean luminance %.6g, %s: %.6g (ratio within 1 +- %.3g)\n", argv[2], a,
               argv[3], b, tol);
        return b > 0 && a / b >= 1 - tol && a / b <= 1 + tol ? 0 : 1;
    }
    if (argc == 4 && !strcmp(argv[1], "--not-black")) {
        double mean = mean_luminance(argv[2]);
        if (mean < 0)
            return 2;
        double min = atof(argv[3]);
        printf("%s: mean luminance %.6g (at least %.6g)\n", argv[2], mean, min);
        return mean >= min ? 0 : 1;
    }
    if (argc != 4) {
        fprintf(stderr, "usage: exr_compare A.exr REF.exr MAX_REL_MSE | --not-black A.exr MIN | "
                        "--mean A.exr REF.exr TOL | --exact A.exr B.exr | --attrs A.exr NAME...\n");
        return 2;
    }
    dirt_image *a = dirt_image_read_exr(argv[1]), *b = dirt_image_read_exr(argv[2]);
    if (!a || !b || a->width != b->width || a->height != b->height) {
        fprintf(stderr, "exr_compare: cannot compare %s and %s\n", argv[1], argv[2]);
        return 2;
    }
    double rel = dirt_image_rel_mse(a, b), max = atof(argv[3]);
    printf("%s vs %s: relMSE %.3g (at most %.3g)\n", argv[1], argv[2], rel, max);
    dirt_image_destroy(a);
    dirt_image_destroy(b);
    return rel <= max ? 0 : 1;
}
