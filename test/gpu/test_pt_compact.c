/* Live-path compaction: after event 1 the GPU path tracer traces, fetches
 * and shades only the paths that go on (compact.comp gathers them into the
 * next event's ray batch; every pass over it dispatches indirectly, and the
 * host never reads its size). The oracle is the Embree path tracer with the
 * same seed: it follows the same paths, so the number of paths that reach
 * each event (each batch's size, counted by the GPU) must equal the
 * reference's count of paths cast at that event, exactly:
 *  - DIRT (compute and raster Fetch) on the default scene (a closed room:
 *    paths end by Russian roulette or where a sample fails) and on the
 *    shared Cornell box (open at the front: most continuations leave it,
 *    so event 2 holds under half of event 1's paths), also when the image
 *    is worked through in chunks (DIRT_PT_CHUNK_PIXELS), whose image must
 *    then equal the unchunked one bit for bit;
 *  - MMRT (its misses end other paths): event 1 holds every pixel of every
 *    sample, no event more paths than the one before, the last event fewer
 *    than the first;
 *  - ambient occlusion: one event, every pixel.
 * A compaction that drops or repeats a live path, or keeps a finished one,
 * changes the counts (and the image). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dirt/session.h"
#include "gpu.h"
#include "session_util.h"

#define W 64
#define H 48
#define SPP 2
#define BOUNCES 4

typedef struct counts {
    int events;
    uint64_t n[DIRT_MAX_EVENTS];
    dirt_image *img;
} counts;

static counts run(dirt_gpu *gpu, const dirt_scene *scene, dirt_session_opts o)
{
    counts c = {0};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    if (!s)
        return c;
    CHECK(dirt_session_add_samples(s, SPP, NULL, NULL));
    const dirt_session_stats *st = dirt_session_get_stats(s);
    const dirt_image *img = dirt_session_image(s);
    CHECK(st && img);
    if (st && img) {
        c.events = st->events;
        memcpy(c.n, st->paths_at_event, sizeof(c.n));
        c.img = dirt_image_create(img->width, img->height);
        if (c.img)
            memcpy(c.img->rgba, img->rgba, sizeof(float) * 4 * (size_t)W * H);
    }
    dirt_session_destroy(s);
    return c;
}

static void print(const char *what, const counts *c)
{
    fprintf(stderr, "%-34s", what);
    for (int k = 1; k <= c->events; k++)
        fprintf(stderr, " %llu", (unsigned long long)c->n[k]);
    fprintf(stderr, "\n");
}

static bool same_counts(const counts *a, const counts *b)
{
    return a->events == b->events && !memcmp(a->n, b->n, sizeof(a->n));
}

static void check_scene(dirt_gpu *gpu, const dirt_scene *scene, const char *label, bool open)
{
    dirt_session_opts o = {.width = W, .height = H, .bounces = BOUNCES, .seed = 7,
                           .views = DIRT_SESSION_VIEWS_CUBE_CAMERA, .tile_size = 2,
                           .buckets = 8};
    char what[128];
    o.engine = DIRT_ENGINE_EMBREE;
    counts ref = run(gpu, scene, o);
    snprintf(what, sizeof(what), "%s embree:", label);
    print(what, &ref);
    CHECK(ref.events == BOUNCES + 1 && ref.n[1] == (uint64_t)W * H * SPP);

    o.engine = DIRT_ENGINE_DIRT;
    counts dc = run(gpu, scene, o);
    snprintf(what, sizeof(what), "%s dirt:", label);
    print(what, &dc);
    CHECK_MSG(same_counts(&dc, &ref), "%s: DIRT's paths per event differ from Embree's", label);
    if (open)
        CHECK_MSG(2 * dc.n[2] < dc.n[1], "%s: no compaction to speak of", label);
    else
        CHECK_MSG(dc.n[BOUNCES + 1] < dc.n[1], "%s: no path ended", label);

    o.fetch = DIRT_FETCH_RASTER;
    counts dr = run(gpu, scene, o);
    snprintf(what, sizeof(what), "%s dirt, raster Fetch:", label);
    print(what, &dr);
    CHECK_MSG(same_counts(&dr, &ref), "%s: raster Fetch: paths per event differ", label);
    o.fetch = DIRT_FETCH_COMPUTE;

    /* Chunks of 640 pixels: 5 chunks of the 64x48 image. */
    setenv("DIRT_PT_CHUNK_PIXELS", "640", 1);
    counts dk = run(gpu, scene, o);
    unsetenv("DIRT_PT_CHUNK_PIXELS");
    snprintf(what, sizeof(what), "%s dirt, chunks of 640:", label);
    print(what, &dk);
    CHECK_MSG(same_counts(&dk, &ref), "%s: chunked: paths per event differ", label);
    CHECK_MSG(dk.img && dc.img &&
                  !memcmp(dk.img->rgba, dc.img->rgba, sizeof(float) * 4 * (size_t)W * H),
              "%s: the chunked image differs from the unchunked one", label);

    o.engine = DIRT_ENGINE_MMRT;
    o.buckets = 4;
    counts mc = run(gpu, scene, o);
    snprintf(what, sizeof(what), "%s mmrt:", label);
    print(what, &mc);
    CHECK(mc.events == BOUNCES + 1 && mc.n[1] == (uint64_t)W * H * SPP);
    for (int k = 2; k <= mc.events; k++)
        CHECK_MSG(mc.n[k] <= mc.n[k - 1], "%s: MMRT event %d holds more paths than %d", label,
                  k, k - 1);
    CHECK(mc.n[BOUNCES + 1] < mc.n[1]);

    o.engine = DIRT_ENGINE_DIRT;
    o.buckets = 8;
    o.mode = DIRT_PT_AO;
    counts ao = run(gpu, scene, o);
    CHECK(ao.events == 1 && ao.n[1] == (uint64_t)W * H * SPP);

    counts *all[] = {&ref, &dc, &dr, &dk, &mc, &ao};
    for (size_t i = 0; i < sizeof(all) / sizeof(all[0]); i++)
        dirt_image_destroy(all[i]->img);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *room = dirt_scene_create_default();
    CHECK(room != NULL);
    if (room)
        check_scene(gpu, room, "default", false);
    dirt_scene_destroy(room);
    const char *dir = test_shared_dir();
    if (dir) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox.glb", dir);
        dirt_scene *box = dirt_scene_load(path, NULL);
        CHECK(box != NULL);
        if (box)
            check_scene(gpu, box, "CornellBox.glb", true);
        dirt_scene_destroy(box);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
