/* Helpers of the GPU tests that render through sessions (header-only, for
 * test executables; include after check.h). */
#ifndef DIRT_TEST_SESSION_UTIL_H
#define DIRT_TEST_SESSION_UTIL_H

#include <string.h>

#include "check.h"
#include "dirt/session.h"

/* Mean Rec. 709 luminance of the image's RGB. */
static inline double test_mean_luminance(const dirt_image *img)
{
    double s = 0.0;
    for (int i = 0; i < img->width * img->height; i++)
        s += 0.2126 * img->rgba[4 * i] + 0.7152 * img->rgba[4 * i + 1] +
             0.0722 * img->rgba[4 * i + 2];
    return s / (img->width * img->height);
}

/* A copy of the RGBA of a session on `scene` with options `o` (width and
 * height as given there) after `spp` samples; NULL (after a failed CHECK)
 * when the session fails. The caller destroys it. */
static inline dirt_image *test_session_render(dirt_gpu *gpu, const dirt_scene *scene,
                                              const dirt_session_opts *o, int spp)
{
    dirt_session *s = dirt_session_create(gpu, scene, o);
    CHECK(s != NULL);
    if (!s)
        return NULL;
    dirt_image *copy = NULL;
    if (dirt_session_add_samples(s, spp, NULL, NULL)) {
        const dirt_image *img = dirt_session_image(s);
        CHECK(img && img->width == o->width && img->height == o->height);
        if (img && img->width == o->width && img->height == o->height &&
            (copy = dirt_image_create(o->width, o->height)))
            memcpy(copy->rgba, img->rgba, sizeof(float) * 4 * (size_t)o->width * o->height);
    }
    CHECK(copy != NULL);
    dirt_session_destroy(s);
    return copy;
}

#endif
