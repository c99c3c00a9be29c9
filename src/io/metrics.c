/* Image error metrics over RGB. Contracts are documented in dirt/image.h. */
#include "dirt/image.h"

#include <math.h>

#include "dirt/log.h"

bool dirt_image_compare(const dirt_image *img, const dirt_image *ref,
                        dirt_image_error *out)
{
    if (!img || !ref || !out || !img->rgba || !ref->rgba) {
        DIRT_ERROR("image compare: NULL argument");
        return false;
    }
    if (img->width != ref->width || img->height != ref->height) {
        DIRT_ERROR("image compare: size mismatch %dx%d vs reference %dx%d",
                   img->width, img->height, ref->width, ref->height);
        return false;
    }
    const size_t count = (size_t)img->width * (size_t)img->height;
    double se = 0.0, rel = 0.0;
    for (size_t i = 0; i < count; i++) {
        const float *a = img->rgba + i * 4;
        const float *b = ref->rgba + i * 4;
        for (int c = 0; c < 3; c++) {
            double d = (double)a[c] - (double)b[c];
            double d2 = d * d;
            se += d2;
            rel += d2 / ((double)b[c] * (double)b[c] + DIRT_REL_MSE_EPSILON);
        }
    }
    const double n = (double)count * 3.0;
    out->mse = se / n;
    out->rmse = sqrt(out->mse);
    out->rel_mse = rel / n;
    return true;
}

double dirt_image_mse(const dirt_image *img, const dirt_image *ref)
{
    dirt_image_error e;
    return dirt_image_compare(img, ref, &e) ? e.mse : NAN;
}

double dirt_image_rmse(const dirt_image *img, const dirt_image *ref)
{
    dirt_image_error e;
    return dirt_image_compare(img, ref, &e) ? e.rmse : NAN;
}

double dirt_image_rel_mse(const dirt_image *img, const dirt_image *ref)
{
    dirt_image_error e;
    return dirt_image_compare(img, ref, &e) ? e.rel_mse : NAN;
}
