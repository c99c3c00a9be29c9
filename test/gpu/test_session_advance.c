/* dirt_session_advance (dirt/session.h): a sample split into pieces over
 * many calls gives the pixels of dirt_session_add_samples bit for bit, in
 * the path tracers and in embree (pieces of tiles; its progressive image
 * is a mean of means, so it equals 1 + 1 + 1 samples of add_samples), with
 * the image in chunks too, and embree at a size whose last tiles are
 * partial; while a sample is in progress the
 * image, the display texture and the sample count are those of the
 * completed samples; add_samples completes the sample in progress; a
 * restart drops it; a bad budget is refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/session.h"
#include "gl/gl.h"
#include "gpu.h"

#define W 48
#define H 36
#define SPP 3

/* True when both images have the same size, channels and bits. */
static bool same_image(const dirt_image *a, const dirt_image *b)
{
    if (!a || !b || a->width != b->width || a->height != b->height ||
        a->channel_count != b->channel_count)
        return false;
    size_t n = (size_t)a->width * a->height;
    if (memcmp(a->rgba, b->rgba, 4 * n * sizeof(float)))
        return false;
    for (int c = 0; c < a->channel_count; c++) {
        const float *o = dirt_image_find_channel(b, a->channels[c].name);
        if (!o || memcmp(a->channels[c].data, o, n * sizeof(float)))
            return false;
    }
    return true;
}

static dirt_image *copy_image(const dirt_image *img)
{
    if (!img)
        return NULL;
    dirt_image *c = dirt_image_create(img->width, img->height);
    CHECK(c != NULL);
    memcpy(c->rgba, img->rgba, 4 * sizeof(float) * img->width * img->height);
    for (int i = 0; i < img->channel_count; i++) {
        float *d = dirt_image_add_channel(c, img->channels[i].name);
        memcpy(d, img->channels[i].data, sizeof(float) * img->width * img->height);
    }
    return c;
}

/* The display texture holds `img`'s beauty. */
static bool display_is(dirt_session *s, const dirt_image *img)
{
    GLuint tex = dirt_session_display_texture(s);
    if (!img)
        return false;
    size_t n = (size_t)img->width * img->height;
    float *px = malloc(sizeof(float) * 4 * n);
    bool ok = tex && px && gl_texture_read_rgba32f(tex, img->width, img->height, px) &&
              memcmp(px, img->rgba, sizeof(float) * 4 * n) == 0;
    free(px);
    return ok;
}

/* SPP samples at once (`one_by_one`: 1 + 1 + 1, for embree, whose
 * progressive image is a mean of means): the reference. */
static dirt_image *reference(dirt_gpu *gpu, const dirt_scene *scene, const dirt_session_opts *o,
                             bool one_by_one)
{
    dirt_session *s = dirt_session_create(gpu, scene, o);
    CHECK(s != NULL);
    for (int i = 0; s && i < (one_by_one ? SPP : 1); i++)
        CHECK(dirt_session_add_samples(s, one_by_one ? 1 : SPP, NULL, NULL));
    dirt_image *ref = s ? copy_image(dirt_session_image(s)) : NULL;
    CHECK(ref != NULL);
    dirt_session_destroy(s);
    return ref;
}

/* SPP samples by dirt_session_advance with budget 0 (one smallest piece a
 * call): a sample spans several calls (`split`: the path tracers), the part
 * grows within a sample, and between its pieces the image, the display
 * and the count are the last completed sample's; the end equals `ref`. */
static void check_pieces(dirt_gpu *gpu, const dirt_scene *scene, const dirt_session_opts *o,
                         const dirt_image *ref, bool split, const char *what)
{
    dirt_session *s = dirt_session_create(gpu, scene, o);
    CHECK(s != NULL);
    if (!s)
        return;
    dirt_image *last = NULL; /* the image after the last completed sample */
    int calls = 0, done = 0, stale = 0, parts_bad = 0, max_calls = 0, sample_calls = 0;
    double part = 0;
    while (done < SPP && calls < 100000) {
        bool completed = true;
        CHECK(dirt_session_advance(s, 0, &completed));
        calls++;
        sample_calls++;
        double p = dirt_session_sample_part(s);
        if (completed) {
            done++;
            parts_bad += p != 0.0 || dirt_session_samples(s) != done;
            dirt_image_destroy(last);
            last = copy_image(dirt_session_image(s));
            max_calls = sample_calls > max_calls ? sample_calls : max_calls;
            sample_calls = 0;
            part = 0;
            continue;
        }
        parts_bad += !(p > part && p < 1.0) || dirt_session_samples(s) != done;
        part = p;
        /* In progress: what is shown is the completed samples. */
        if (done > 0 && (calls % 3 == 0 || part > 0.9))
            stale += !same_image(dirt_session_image(s), last) || !display_is(s, last);
    }
    CHECK_MSG(done == SPP, "%s: %d samples after %d calls", what, done, calls);
    CHECK_MSG(split ? max_calls > 4 : max_calls == 1,
              "%s: a sample took up to %d calls of budget 0", what, max_calls);
    CHECK_MSG(parts_bad == 0, "%s: %d calls with a wrong part or count", what, parts_bad);
    CHECK_MSG(stale == 0, "%s: %d looks in a sample's midst did not show the completed samples",
              what, stale);
    CHECK_MSG(same_image(ref, dirt_session_image(s)),
              "%s: %d samples in %d pieces differ from %d at once", what, SPP, calls, SPP);
    CHECK_MSG(display_is(s, ref), "%s: the display texture differs from the image", what);
    fprintf(stderr, "%s: %d samples in %d calls (up to %d a sample) == %d at once\n", what, SPP,
            calls, max_calls, SPP);
    dirt_image_destroy(last);
    dirt_session_destroy(s);
}

/* Mixed: pieces, then add_samples(2) completes the one in progress and adds
 * one; then 5 ms slices to SPP. A restart (set_camera) in a sample's midst
 * drops it: 0 samples, no part, then SPP at once (`one_by_one`: 1 + 1 + 1)
 * equal `ref` again. */
static void check_mixed(dirt_gpu *gpu, const dirt_scene *scene, const dirt_session_opts *o,
                        const dirt_image *ref, bool one_by_one, const char *what)
{
    dirt_session *s = dirt_session_create(gpu, scene, o);
    CHECK(s != NULL);
    if (!s)
        return;
    bool completed = true;
    for (int i = 0; i < 3; i++)
        CHECK(dirt_session_advance(s, 0, &completed) && !completed);
    CHECK(dirt_session_sample_part(s) > 0 && dirt_session_samples(s) == 0);
    CHECK(dirt_session_add_samples(s, 2, NULL, NULL));
    CHECK(dirt_session_samples(s) == 2 && dirt_session_sample_part(s) == 0);
    int calls = 0;
    while (dirt_session_samples(s) < SPP && calls++ < 100000)
        CHECK(dirt_session_advance(s, 5, NULL));
    CHECK_MSG(same_image(ref, dirt_session_image(s)), "%s: pieces + 2 + 5 ms slices differ",
              what);
    /* a restart in a sample's midst */
    CHECK(dirt_session_advance(s, 0, &completed) && !completed);
    CHECK(dirt_session_sample_part(s) > 0);
    CHECK(dirt_session_set_camera(s, DIRT_CAMERA_DEFAULT, 0, NULL));
    CHECK(dirt_session_samples(s) == 0 && dirt_session_sample_part(s) == 0);
    for (int i = 0; i < (one_by_one ? SPP : 1); i++)
        CHECK(dirt_session_add_samples(s, one_by_one ? 1 : SPP, NULL, NULL));
    CHECK_MSG(same_image(ref, dirt_session_image(s)), "%s: after a restart in a sample's midst",
              what);
    dirt_session_destroy(s);
}

static void check_engine(dirt_gpu *gpu, const dirt_scene *scene, dirt_session_opts o, bool split,
                         const char *what)
{
    bool embree = o.engine == DIRT_ENGINE_EMBREE;
    dirt_image *ref = reference(gpu, scene, &o, embree);
    check_pieces(gpu, scene, &o, ref, split, what);
    if (split)
        check_mixed(gpu, scene, &o, ref, embree, what);
    dirt_image_destroy(ref);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    dirt_session_opts dirt = {.width = W, .height = H, .bounces = 2, .seed = 3};
    check_engine(gpu, scene, dirt, true, "dirt");
    dirt_session_opts mmrt = {.engine = DIRT_ENGINE_MMRT, .width = W, .height = H,
                              .bounces = 2, .march = DIRT_MMRT_MARCH_LINEAR, .seed = 5};
    check_engine(gpu, scene, mmrt, true, "mmrt, linear march");
    /* The image in chunks of 640 pixels (the pieces stay within one). */
    setenv("DIRT_PT_CHUNK_PIXELS", "640", 1);
    check_engine(gpu, scene, dirt, true, "dirt, chunks of 640");
    check_engine(gpu, scene, mmrt, true, "mmrt, linear march, chunks of 640");
    unsetenv("DIRT_PT_CHUNK_PIXELS");
    /* Direct visibility: a piece is the whole camera view. */
    dirt_session_opts vis = dirt;
    vis.direct_visibility = true;
    check_engine(gpu, scene, vis, false, "dirt, direct visibility");
    /* Embree in pieces of 16 x 16 tiles: 48 x 36 is 3 x 3 tiles, the last
     * row 4 pixels high; 53 x 36 has a partial last column too. */
    dirt_session_opts embree = {.engine = DIRT_ENGINE_EMBREE, .width = W, .height = H,
                                .bounces = 2, .seed = 3};
    check_engine(gpu, scene, embree, true, "embree");
    embree.width = 53;
    embree.seed = 9;
    check_engine(gpu, scene, embree, true, "embree, 53 x 36");
    /* A bad budget. */
    dirt_session *s = dirt_session_create(gpu, scene, &dirt);
    CHECK(s && !dirt_session_advance(s, -1, NULL) &&
          dirt_session_last_error() == DIRT_SESSION_ERR_ARGUMENT);
    CHECK(s && !dirt_session_advance(s, NAN, NULL) &&
          dirt_session_last_error() == DIRT_SESSION_ERR_ARGUMENT);
    dirt_session_destroy(s);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
