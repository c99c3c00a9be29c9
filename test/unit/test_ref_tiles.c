/* The reference path tracer in parts (dirt_ref_opts.first_tile, num_tiles,
 * into): on the default scene at 37 x 21 pixels (3 x 2 tiles of 16, the
 * last column 5 pixels wide, the last row 5 high), pieces of tiles rendered
 * into one image equal the whole render bit for bit in every channel; a
 * part alone leaves the other pixels 0 and counts only its own samples;
 * ranges outside the image, an image of another size or without a
 * render's channels are refused (NULL) and the given image is kept. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "ref/ref.h"

#define W 37
#define H 21

static bool same(const dirt_image *a, const dirt_image *b)
{
    size_t n = (size_t)W * H;
    if (!a || !b || a->channel_count != b->channel_count ||
        memcmp(a->rgba, b->rgba, 4 * n * sizeof(float)))
        return false;
    for (int c = 0; c < a->channel_count; c++) {
        const float *o = dirt_image_find_channel(b, a->channels[c].name);
        if (!o || memcmp(a->channels[c].data, o, n * sizeof(float)))
            return false;
    }
    return true;
}

int main(void)
{
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *frame = scene ? dirt_scene_evaluate(scene, 0.0f, NULL) : NULL;
    CHECK(frame != NULL && frame->num_cameras > 0);
    if (!frame || frame->num_cameras == 0) {
        dirt_frame_destroy(frame);
        dirt_scene_destroy(scene);
        return check_finish();
    }
    dirt_camera cam = frame->cameras[0];
    dirt_ref_accel *accel = dirt_ref_accel_create(frame, NULL);
    CHECK(accel != NULL);
    CHECK(dirt_ref_num_tiles(W, H) == 6 && dirt_ref_num_tiles(16, 16) == 1 &&
          dirt_ref_num_tiles(0, 5) == 0);
    dirt_ref_opts o = {.width = W, .height = H, .spp = 2, .first_sample = 3, .bounces = 3,
                       .seed = 11, .accel = accel};
    dirt_ref_stats st;
    dirt_image *whole = dirt_ref_render(scene, frame, &cam, &o, &st);
    CHECK(whole != NULL && st.samples == 2u * W * H);

    /* pieces: tile 0, tiles 1..2, then the rest (num_tiles 0) */
    const size_t first[3] = {0, 1, 3}, count[3] = {1, 2, 0};
    dirt_image *parts = NULL;
    uint64_t samples = 0;
    for (int i = 0; i < 3; i++) {
        dirt_ref_opts p = o;
        p.first_tile = first[i];
        p.num_tiles = count[i];
        p.into = parts;
        dirt_image *r = dirt_ref_render(scene, frame, &cam, &p, &st);
        CHECK(r != NULL && (!parts || r == parts));
        parts = r ? r : parts;
        samples += st.samples;
    }
    CHECK_MSG(same(whole, parts), "tiles rendered in 3 pieces differ from the whole render");
    CHECK_MSG(samples == 2u * W * H, "the pieces counted %llu samples", (unsigned long long)samples);

    /* a part alone: tile 5 (the bottom right, 5 x 5 pixels) */
    dirt_ref_opts p = o;
    p.first_tile = 5;
    p.num_tiles = 1;
    dirt_image *last = dirt_ref_render(scene, frame, &cam, &p, &st);
    CHECK(last != NULL && st.samples == 2u * 5 * 5);
    if (last && whole) {
        int bad = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t i = (size_t)y * W + x;
                bool in = x >= 32 && y >= 16;
                for (int k = 0; k < 4; k++)
                    bad += in ? last->rgba[4 * i + k] != whole->rgba[4 * i + k]
                              : last->rgba[4 * i + k] != 0.0f;
            }
        CHECK_MSG(bad == 0, "%d values of a one-tile part wrong", bad);
    }

    /* refused */
    p = o;
    p.first_tile = 6;
    CHECK(dirt_ref_render(scene, frame, &cam, &p, NULL) == NULL);
    p.first_tile = 4;
    p.num_tiles = 3;
    CHECK(dirt_ref_render(scene, frame, &cam, &p, NULL) == NULL);
    dirt_image *small = dirt_image_create(W - 1, H);
    p = o;
    p.into = small;
    CHECK(small && dirt_ref_render(scene, frame, &cam, &p, NULL) == NULL);
    dirt_image *bare = dirt_image_create(W, H);
    p.into = bare;
    CHECK(bare && dirt_ref_render(scene, frame, &cam, &p, NULL) == NULL);
    CHECK(small->width == W - 1 && bare->width == W); /* kept, not destroyed */

    dirt_image_destroy(small);
    dirt_image_destroy(bare);
    dirt_image_destroy(last);
    dirt_image_destroy(parts);
    dirt_image_destroy(whole);
    dirt_ref_accel_destroy(accel);
    dirt_frame_destroy(frame);
    dirt_scene_destroy(scene);
    return check_finish();
}
