/* Image metrics against hand-computed values. */
#include <math.h>

#include "check.h"
#include "dirt/image.h"

static void set_rgb(dirt_image *img, int i, float r, float g, float b, float a)
{
    img->rgba[i * 4 + 0] = r;
    img->rgba[i * 4 + 1] = g;
    img->rgba[i * 4 + 2] = b;
    img->rgba[i * 4 + 3] = a;
}

int main(void)
{
    dirt_image *a = dirt_image_create(2, 1);
    dirt_image *b = dirt_image_create(2, 1);
    dirt_image *c = dirt_image_create(1, 2);
    CHECK(a && b && c);
    if (!a || !b || !c)
        return check_finish();

    /* img a, reference b; alpha differs on purpose (must be ignored) */
    set_rgb(a, 0, 1.0f, 2.0f, 3.0f, 0.0f);
    set_rgb(a, 1, 0.0f, 0.0f, 0.0f, 1.0f);
    set_rgb(b, 0, 1.0f, 1.0f, 1.0f, 1.0f);
    set_rgb(b, 1, 0.5f, 0.0f, -1.0f, 0.0f);
    /* differences 0, 1, 2, -0.5, 0, 1; squares sum 6.25 over 6 values:
     *   mse  = 6.25 / 6            = 1.0416666667
     *   rmse = sqrt(1.0416666667)  = 1.0206207262
     * ref^2 + 0.01 = 1.01, 1.01, 1.01, 0.26, 0.01, 1.01:
     *   rel  = (1/1.01 + 4/1.01 + 0.25/0.26 + 1/1.01) / 6
     *        = (5.9405940594 + 0.9615384615) / 6 = 1.1503554202 */
    dirt_image_error e = {0};
    CHECK(dirt_image_compare(a, b, &e));
    CHECK_NEAR(e.mse, 1.0416666667, 1e-9);
    CHECK_NEAR(e.rmse, 1.0206207262, 1e-9);
    CHECK_NEAR(e.rel_mse, 1.1503554202, 1e-9);
    CHECK_NEAR(dirt_image_mse(a, b), 1.0416666667, 1e-9);
    CHECK_NEAR(dirt_image_rmse(a, b), 1.0206207262, 1e-9);
    CHECK_NEAR(dirt_image_rel_mse(a, b), 1.1503554202, 1e-9);

    /* relative MSE normalises by the reference (second argument):
     * b against a: ref^2 + 0.01 = 1.01, 4.01, 9.01, 0.01, 0.01, 0.01
     *   rel = (0 + 1/4.01 + 4/9.01 + 0.25/0.01 + 0 + 1/0.01) / 6
     *       = (0.2493765586 + 0.4439511654 + 25 + 100) / 6 = 20.9488879540 */
    CHECK_NEAR(dirt_image_rel_mse(b, a), 20.9488879540, 1e-9);
    CHECK_NEAR(dirt_image_mse(b, a), 1.0416666667, 1e-9);

    /* identical images */
    CHECK(dirt_image_compare(a, a, &e));
    CHECK(e.mse == 0.0 && e.rmse == 0.0 && e.rel_mse == 0.0);

    /* mismatched sizes and NULLs fail */
    CHECK(!dirt_image_compare(a, c, &e));
    CHECK(isnan(dirt_image_rmse(a, c)));
    CHECK(!dirt_image_compare(NULL, b, &e));
    CHECK(!dirt_image_compare(a, b, NULL));

    dirt_image_destroy(a);
    dirt_image_destroy(b);
    dirt_image_destroy(c);
    return check_finish();
}
