/* The two conservative-raster paths of the DIRT build give the same
 * structure: with GL_NV_conservative_raster (NVIDIA) and with the
 * emulation every other test forces (bounding box + 0.51 tile, then the
 * exact clip), the default scene (cube + camera views, S in {1, 2, 4}, B = 8)
 * yields the same primitives in every (bucket, tile) list (as sets: the
 * order within a list follows the atomics) and the same pair and node
 * counts. Where the extension is absent (llvmpipe) the test skips, in CI
 * too, and says so: there is no second path to compare. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/layout.h"
#include "dirt/ads.h"
#include "gpu.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* The sorted primitives of list h; returns the count (at most `max`). */
static size_t list(const dirt_ads_data *d, size_t h, uint32_t *out, size_t max)
{
    size_t n = 0;
    for (uint32_t k = d->heads[h]; k != DIRT_LIST_END && n < max; k = d->nodes[k][1])
        out[n++] = d->nodes[k][0];
    qsort(out, n, sizeof(*out), cmp_u32);
    return n;
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    if (!dirt_gpu_get_caps(gpu)->nv_conservative_raster) {
        fprintf(stderr, "GL_NV_conservative_raster is absent (%s): only the emulation exists "
                        "here, nothing to compare; skipping%s\n",
                dirt_gpu_get_caps(gpu)->renderer,
                test_in_ci() ? " (also in CI: dirt.sh's CI_MAY_SKIP names this test)" : "");
        dirt_gpu_destroy(gpu);
        return TEST_SKIP;
    }
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    dirt_camera cam = f->cameras[0];
    static const int sizes[] = {1, 2, 4};
    for (size_t s = 0; s < sizeof(sizes) / sizeof(sizes[0]); s++) {
        dirt_ads_data d[2];
        dirt_ads_stats st[2];
        for (int emu = 0; emu < 2; emu++) {
            dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64,
                                         .height = 48, .face_size = 32, .tile_size = sizes[s]},
                               .buckets = 8, .force_emulation = emu == 1};
            dirt_ads *ads = dirt_ads_create(gpu, &o);
            CHECK(ads && dirt_ads_build(ads, f, &cam));
            st[emu] = *dirt_ads_get_stats(ads);
            CHECK(st[emu].conservative_nv == (emu == 0));
            CHECK(dirt_ads_read(ads, &d[emu]));
            dirt_ads_destroy(ads);
        }
        CHECK(st[0].samples == st[1].samples && st[0].nodes == st[1].nodes);
        size_t lists = (size_t)d[0].buckets * (size_t)d[0].num_tiles, differ = 0;
        size_t cap = (size_t)st[0].primitives + 1;
        uint32_t *a = malloc(cap * sizeof(*a)), *b = malloc(cap * sizeof(*b));
        for (size_t h = 0; a && b && h < lists; h++) {
            size_t na = list(&d[0], h, a, cap), nb = list(&d[1], h, b, cap);
            differ += na != nb || memcmp(a, b, na * sizeof(*a)) != 0;
        }
        CHECK_MSG(differ == 0, "S=%d: %zu of %zu lists differ between NV and emulation",
                  sizes[s], differ, lists);
        fprintf(stderr, "S=%d: NV %llu pairs, emulation %llu pairs; %zu lists differ\n",
                sizes[s], (unsigned long long)st[0].samples, (unsigned long long)st[1].samples,
                differ);
        free(a);
        free(b);
        dirt_ads_data_free(&d[0]);
        dirt_ads_data_free(&d[1]);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
