/* The path tracer's ray sort (dirt_pt_opts.sort_rays, src/integrator/
 * ray_sort.c, glsl/integrator/sort.comp).
 *
 * 1. The sort alone, on batches made here (random origins inside and
 *    outside the grid's box, random directions, copies of 40 rays
 *    scattered through the batch; empty, partial and full batches): the
 *    output batch's header is the input's; its owners are the input's, each
 *    exactly once (every ray is traced once); each output ray is bit for
 *    bit the input ray of its owner; the keys the count pass gave the rays
 *    (read from the scratch buffer) are below DIRT_SORT_BUCKETS, equal for
 *    equal rays, and ascend through the output; nothing past the count is
 *    written; and neighbouring rays of the output lie at most half as far
 *    apart in origin and direction as the input's.
 * 2. Through the path tracer: with the sort, the image (and the paths per
 *    event) of the same seed are bit for bit those without it, for DIRT
 *    (compute and raster Fetch, whole image and in chunks) and MMRT, on the
 *    default scene (diffuse, glossy and mirror-like materials) and on the
 *    shared Cornell box. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/layout.h"
#include "dirt/session.h"
#include "gl/gl.h"
#include "gpu.h"
#include "integrator/ray_sort.h"

#define CAP 3000
#define GARBAGE 0xA5A5A5A5u

static uint32_t rng_state = 12345;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static float rndf(float lo, float hi)
{
    return lo + (hi - lo) * (float)(rnd() & 0xFFFFFF) / (float)0x1000000;
}

static double ray_gap(const struct dirt_gpu_ray *a, const struct dirt_gpu_ray *b)
{
    const dirt_f4 *p[4] = {&a->origin_tmin, &b->origin_tmin, &a->dir_tmax, &b->dir_tmax};
    double d = 0;
    for (int v = 0; v < 4; v += 2)
        d += fabs((double)p[v]->x - p[v + 1]->x) + fabs((double)p[v]->y - p[v + 1]->y) +
             fabs((double)p[v]->z - p[v + 1]->z);
    return d;
}

/* Sorts a batch of n rays of capacity CAP and checks the output. */
static void check_sort(const dirt_ray_sort *rs, dirt_gpu *gpu, uint32_t n)
{
    struct dirt_gpu_ray *in = calloc(CAP, sizeof(*in)), *out = calloc(CAP, sizeof(*out));
    size_t bbytes = sizeof(struct dirt_gpu_ray_batch) + CAP * sizeof(uint32_t);
    uint32_t *bin = calloc(1, bbytes), *bout = calloc(1, bbytes);
    uint32_t *group = calloc(CAP, sizeof(uint32_t));
    int *seen = calloc(CAP, sizeof(int));
    if (!in || !out || !bin || !bout || !group || !seen) {
        CHECK_MSG(false, "out of memory");
        goto done;
    }
    /* owners: the first n of a shuffle of 0 .. CAP - 1 */
    uint32_t *own = bin + 4;
    for (uint32_t i = 0; i < CAP; i++)
        own[i] = i;
    for (uint32_t i = CAP - 1; i > 0; i--) {
        uint32_t j = rnd() % (i + 1), t = own[i];
        own[i] = own[j];
        own[j] = t;
    }
    bin[0] = n ? (n + DIRT_GROUP_SIZE - 1) / DIRT_GROUP_SIZE : 1;
    bin[1] = bin[2] = 1;
    bin[3] = n;
    /* rays: one in five a copy of one of 40 group rays (group g + 1), the
     * others random (group 0); a tenth of the origins outside the box */
    struct dirt_gpu_ray base[40];
    for (int g = 0; g < 40; g++)
        base[g] = (struct dirt_gpu_ray){{rndf(-1, 1), rndf(-1, 1), rndf(-1, 1), 1e-3f},
                                        {rndf(-1, 1), rndf(-1, 1), rndf(-1, 1), 1e30f}};
    for (uint32_t i = 0; i < n; i++) {
        if (rnd() % 5 == 0) {
            group[i] = 1 + rnd() % 40;
            in[i] = base[group[i] - 1];
        } else {
            float s = rnd() % 10 == 0 ? 3.0f : 1.0f;
            in[i] = (struct dirt_gpu_ray){{rndf(-s, s), rndf(-s, s), rndf(-s, s), 0.0f},
                                          {rndf(-1, 1), rndf(-1, 1), rndf(-1, 1), 100.0f}};
            in[i].origin_tmin.w = (float)i; /* every such ray distinct */
        }
    }
    memset(out, 0xA5, CAP * sizeof(*out));
    memset(bout, 0xA5, bbytes);
    dirt_ray_sort_io io = {
        .in_rays = gl_buffer_create(gpu, CAP * sizeof(*in), in, false, "test in rays"),
        .in_batch = gl_buffer_create(gpu, bbytes, bin, false, "test in batch"),
        .out_rays = gl_buffer_create(gpu, CAP * sizeof(*out), out, true, "test out rays"),
        .out_batch = gl_buffer_create(gpu, bbytes, bout, true, "test out batch"),
        .scratch = gl_buffer_create(gpu, dirt_ray_sort_scratch_bytes(CAP), NULL, true,
                                    "test scratch"),
        .capacity = CAP, .bounds_min = {-1, -1, -1}, .bounds_max = {1, 1, 1}};
    CHECK(io.in_rays && io.in_batch && io.out_rays && io.out_batch && io.scratch);
    for (int p = 0; p < DIRT_RAY_SORT_PASSES; p++) {
        dirt_ray_sort_pass(rs, (enum dirt_ray_sort_pass)p, &io);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    CHECK(gl_buffer_read(io.out_rays, 0, CAP * sizeof(*out), out));
    CHECK(gl_buffer_read(io.out_batch, 0, bbytes, bout));
    uint32_t *key = calloc(CAP, sizeof(uint32_t));
    if (key)
        CHECK(gl_buffer_read(io.scratch, DIRT_SORT_BUCKETS * sizeof(uint32_t),
                             CAP * sizeof(uint32_t), key));
    CHECK_MSG(!memcmp(bout, bin, 16), "n %u: header (%u %u %u %u), not the input's", n,
              bout[0], bout[1], bout[2], bout[3]);
    /* owner -> input index */
    int *where = calloc(CAP, sizeof(int));
    for (uint32_t i = 0; where && i < CAP; i++)
        where[i] = -1;
    for (uint32_t i = 0; where && i < n; i++)
        where[own[i]] = (int)i;
    uint32_t bad_owner = 0, repeated = 0, bad_ray = 0, bad_key = 0, descending = 0, past = 0;
    double gap_in = 0, gap_out = 0;
    /* the key of each group of equal rays (~0u: none seen yet) */
    uint32_t group_key[41];
    memset(group_key, 0xFF, sizeof(group_key));
    uint32_t last_key = 0;
    for (uint32_t j = 0; where && key && j < n; j++) {
        uint32_t o = bout[4 + j];
        if (o >= CAP || where[o] < 0) {
            bad_owner++;
            continue;
        }
        if (seen[o]++)
            repeated++;
        uint32_t i = (uint32_t)where[o];
        if (memcmp(&out[j], &in[i], sizeof(in[i])))
            bad_ray++;
        uint32_t k = key[i], g = group[i];
        if (k >= DIRT_SORT_BUCKETS)
            bad_key++;
        if (g > 0 && group_key[g] != ~0u && group_key[g] != k)
            bad_key++;
        if (g > 0)
            group_key[g] = k;
        if (j > 0 && k < last_key)
            descending++;
        last_key = k;
        if (j > 0) {
            gap_in += ray_gap(&in[j], &in[j - 1]);
            gap_out += ray_gap(&out[j], &out[j - 1]);
        }
    }
    const uint32_t *o32 = (const uint32_t *)out;
    for (size_t w = (size_t)n * 8; w < (size_t)CAP * 8; w++)
        past += o32[w] != GARBAGE;
    for (uint32_t j = n; j < CAP; j++)
        past += bout[4 + j] != GARBAGE;
    uint32_t missing = 0;
    for (uint32_t i = 0; i < n; i++)
        missing += !seen[own[i]];
    fprintf(stderr, "n %4u: owners not in the input %u, repeated %u, missing %u; rays not "
            "their owner's %u; bad keys %u, keys descending %u; words written past the count "
            "%u; mean gap between neighbours %.3f unsorted, %.3f sorted\n", n, bad_owner,
            repeated, missing, bad_ray, bad_key, descending, past,
            n > 1 ? gap_in / (n - 1) : 0.0, n > 1 ? gap_out / (n - 1) : 0.0);
    CHECK_MSG(bad_owner == 0 && repeated == 0 && missing == 0,
              "n %u: the output's owners are not the input's, each once", n);
    CHECK_MSG(bad_ray == 0, "n %u: %u output rays are not their owner's input ray", n, bad_ray);
    CHECK_MSG(key && bad_key == 0, "n %u: %u keys out of range or unequal for equal rays", n,
              bad_key);
    CHECK_MSG(descending == 0, "n %u: keys descend %u times through the output", n, descending);
    CHECK_MSG(past == 0, "n %u: %u words written past the batch's count", n, past);
    if (n > 100)
        CHECK_MSG(gap_out < 0.5 * gap_in, "n %u: sorted neighbours no closer (%.3f vs %.3f)", n,
                  gap_out / (n - 1), gap_in / (n - 1));
    free(where);
    free(key);
    gl_buffer_destroy(&io.in_rays);
    gl_buffer_destroy(&io.in_batch);
    gl_buffer_destroy(&io.out_rays);
    gl_buffer_destroy(&io.out_batch);
    gl_buffer_destroy(&io.scratch);
done:
    free(in);
    free(out);
    free(bin);
    free(bout);
    free(group);
    free(seen);
}

/* ---- 2: images with and without the sort ---- */

#define W 64
#define H 48

typedef struct run_out {
    dirt_image *img;
    int events;
    uint64_t paths[DIRT_MAX_EVENTS];
} run_out;

static run_out run(dirt_gpu *gpu, const dirt_scene *scene, dirt_session_opts o)
{
    run_out r = {0};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    if (!s)
        return r;
    CHECK(dirt_session_add_samples(s, 2, NULL, NULL));
    const dirt_image *img = dirt_session_image(s);
    const dirt_session_stats *st = dirt_session_get_stats(s);
    CHECK(img && st);
    if (img && st) {
        r.img = dirt_image_create(img->width, img->height);
        if (r.img)
            memcpy(r.img->rgba, img->rgba, sizeof(float) * 4 * (size_t)img->width * img->height);
        r.events = st->events;
        memcpy(r.paths, st->paths_at_event, sizeof(r.paths));
    }
    dirt_session_destroy(s);
    return r;
}

static void check_images(dirt_gpu *gpu, const dirt_scene *scene, const char *label,
                         dirt_session_opts o, const char *what)
{
    o.sort_rays = false;
    run_out a = run(gpu, scene, o);
    o.sort_rays = true;
    run_out b = run(gpu, scene, o);
    bool same = a.img && b.img && !memcmp(a.img->rgba, b.img->rgba, sizeof(float) * 4 * W * H);
    size_t differ = 0;
    for (size_t i = 0; a.img && b.img && i < 4 * (size_t)W * H; i++)
        differ += memcmp(&a.img->rgba[i], &b.img->rgba[i], sizeof(float)) != 0;
    fprintf(stderr, "%s, %s: %zu of %d values differ sorted vs unsorted; paths at event 2: %llu "
            "vs %llu\n", label, what, differ, 4 * W * H, (unsigned long long)a.paths[2],
            (unsigned long long)b.paths[2]);
    CHECK_MSG(same, "%s, %s: the sorted image differs from the unsorted one", label, what);
    CHECK_MSG(a.events == b.events && !memcmp(a.paths, b.paths, sizeof(a.paths)),
              "%s, %s: paths per event differ", label, what);
    CHECK_MSG(a.paths[2] > 0, "%s, %s: no path reached event 2 (nothing sorted)", label, what);
    dirt_image_destroy(a.img);
    dirt_image_destroy(b.img);
}

static void check_scene(dirt_gpu *gpu, const dirt_scene *scene, const char *label)
{
    dirt_session_opts o = {.engine = DIRT_ENGINE_DIRT, .width = W, .height = H, .bounces = 4,
                           .seed = 11, .views = DIRT_SESSION_VIEWS_CUBE_CAMERA, .tile_size = 2,
                           .buckets = 8};
    check_images(gpu, scene, label, o, "dirt");
    o.fetch = DIRT_FETCH_RASTER;
    check_images(gpu, scene, label, o, "dirt, raster Fetch");
    o.fetch = DIRT_FETCH_COMPUTE;
    setenv("DIRT_PT_CHUNK_PIXELS", "640", 1); /* 5 chunks */
    check_images(gpu, scene, label, o, "dirt, chunks of 640");
    unsetenv("DIRT_PT_CHUNK_PIXELS");
    o.engine = DIRT_ENGINE_MMRT;
    o.buckets = 4;
    check_images(gpu, scene, label, o, "mmrt");
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_ray_sort *rs = dirt_ray_sort_create();
    CHECK(rs != NULL);
    if (rs) {
        const uint32_t sizes[] = {0, 1, 63, 1000, 2345, CAP};
        for (size_t i = 0; i < sizeof(sizes) / sizeof(sizes[0]); i++)
            check_sort(rs, gpu, sizes[i]);
    }
    dirt_ray_sort_destroy(rs);

    dirt_scene *room = dirt_scene_create_default();
    CHECK(room != NULL);
    if (room)
        check_scene(gpu, room, "default");
    dirt_scene_destroy(room);
    const char *dir = test_shared_dir();
    if (dir) {
        char path[4096];
        snprintf(path, sizeof(path), "%s/scenes/cornell/CornellBox.glb", dir);
        dirt_scene *box = dirt_scene_load(path, NULL);
        CHECK(box != NULL);
        if (box)
            check_scene(gpu, box, "CornellBox.glb");
        dirt_scene_destroy(box);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
