/* Radiance RGBE (.hdr) reading through stb_image (Debian's libstb). */
#include "dirt/image.h"

#include <stdio.h>
#include <stdlib.h>

#include <stb_image.h>

#include "dirt/log.h"

dirt_image *dirt_image_read_hdr(const char *path)
{
    if (!path) {
        DIRT_ERROR("hdr: NULL path");
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        DIRT_ERROR("hdr: cannot open '%s'", path);
        return NULL;
    }
    if (!stbi_is_hdr_from_file(f)) {
        fclose(f);
        DIRT_ERROR("hdr: '%s' is not a Radiance RGBE file", path);
        return NULL;
    }
    int w = 0, h = 0, comp = 0;
    float *px = stbi_loadf_from_file(f, &w, &h, &comp, 3);
    fclose(f);
    if (!px) {
        DIRT_ERROR("hdr: cannot read '%s': %s", path,
                   stbi_failure_reason() ? stbi_failure_reason() : "unknown error");
        return NULL;
    }
    dirt_image *img = NULL;
    if (w < 1 || h < 1 || w > DIRT_IMAGE_MAX_DIM || h > DIRT_IMAGE_MAX_DIM) {
        DIRT_ERROR("hdr: '%s' is %dx%d, out of range", path, w, h);
        goto done;
    }
    img = dirt_image_create(w, h);
    if (!img)
        goto done;
    for (size_t k = 0; k < (size_t)w * (size_t)h; k++) {
        for (int c = 0; c < 3; c++)
            img->rgba[4 * k + (size_t)c] = px[3 * k + (size_t)c];
        img->rgba[4 * k + 3] = 1.0f;
    }
done:
    stbi_image_free(px);
    return img;
}
