/* The render session (dirt/session.h): progressive accumulation equals one
 * render of all samples, bit for bit, in every GPU engine; the display
 * texture holds the same pixels; option changes restart only when the image
 * changes; the automatic camera is one camera for a whole animation; the
 * stats record adds up. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/integrator_layout.h"
#include "integrator/gpu_tables.h"
#include "dirt/session.h"
#include "session/session_internal.h"
#include "gl/gl.h"
#include "gpu.h"

/* The environment table without an environment (dirt_gpu_env_pack). */
#define ENV_NONE_BYTES (sizeof(struct dirt_gpu_model_env) + sizeof(float))
/* The model's tangent table of a scene without normal maps: one zero record
 * (dirt_gpu_model_tangent). */
#define TANGENTS_NONE_BYTES 16

#define W 48
#define H 36

/* True when both images have the same size, channels and bits. */
static bool same_image(const dirt_image *a, const dirt_image *b)
{
    if (a->width != b->width || a->height != b->height ||
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
    dirt_image *c = dirt_image_create(img->width, img->height);
    CHECK(c != NULL);
    memcpy(c->rgba, img->rgba, 4 * sizeof(float) * img->width * img->height);
    for (int i = 0; i < img->channel_count; i++) {
        float *d = dirt_image_add_channel(c, img->channels[i].name);
        memcpy(d, img->channels[i].data, sizeof(float) * img->width * img->height);
    }
    return c;
}

/* 1 + 1 + 2 samples, then 4 at once in a fresh session: the same image. */
static void check_progressive(dirt_gpu *gpu, const dirt_scene *scene, dirt_session_opts o,
                              const char *what)
{
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    if (!s)
        return;
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    const dirt_image *two = dirt_session_image(s); /* reading in between changes nothing */
    CHECK(two != NULL);
    CHECK(dirt_session_add_samples(s, 2, NULL, NULL));
    CHECK(dirt_session_samples(s) == 4);
    dirt_image *steps = copy_image(dirt_session_image(s));
    const dirt_session_stats *st = dirt_session_get_stats(s);
    CHECK(st->samples == 4 && st->rays > 0 && st->aborted == 0);

    /* The display texture: the same pixels, never through the CPU image. */
    GLuint tex = dirt_session_display_texture(s);
    CHECK(tex != 0);
    float *px = malloc(sizeof(float) * 4 * W * H);
    CHECK(px && gl_texture_read_rgba32f(tex, W, H, px));
    CHECK_MSG(memcmp(px, steps->rgba, sizeof(float) * 4 * W * H) == 0,
              "%s: display texture differs from the image", what);
    free(px);

    dirt_session *one = dirt_session_create(gpu, scene, &o);
    CHECK(one && dirt_session_add_samples(one, 4, NULL, NULL));
    const dirt_image *all = one ? dirt_session_image(one) : NULL;
    CHECK_MSG(all && same_image(steps, all), "%s: 1+1+2 samples differ from 4", what);
    /* Not trivially equal: 2 samples differ from 4. */
    dirt_session_reset(one);
    CHECK(dirt_session_samples(one) == 0);
    CHECK(dirt_session_add_samples(one, 2, NULL, NULL));
    const dirt_image *half = dirt_session_image(one);
    CHECK_MSG(half && !same_image(steps, half), "%s: 2 samples equal 4", what);
    fprintf(stderr, "%s: 1+1+2 samples == 4 samples, display texture == image\n", what);
    dirt_image_destroy(steps);
    dirt_session_destroy(one);
    dirt_session_destroy(s);
}

static void check_restarts(dirt_gpu *gpu, const dirt_scene *scene)
{
    dirt_session_opts o = {.width = W, .height = H, .views = DIRT_SESSION_VIEWS_SINGLE};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s && dirt_session_add_samples(s, 2, NULL, NULL));
    /* The default bucket count is the device's: 8 on a software renderer. */
    CHECK(s && dirt_ads_buckets(dirt_session_ads(s)) == dirt_session_auto_buckets(gpu));
    CHECK(dirt_session_auto_buckets(gpu) == (dirt_gpu_get_caps(gpu)->software ? 8 : 16));
    bool restarted = true;
    o.threads = 3; /* how the work is done, not the image */
    CHECK(dirt_session_set_opts(s, &o, &restarted) && !restarted);
    CHECK(dirt_session_samples(s) == 2);
    o.seed = 9;
    CHECK(dirt_session_set_opts(s, &o, &restarted) && restarted);
    CHECK(dirt_session_samples(s) == 0);
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    o.buckets = 3; /* the structure */
    CHECK(dirt_session_set_opts(s, &o, &restarted) && restarted);
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    CHECK(dirt_session_get_stats(s)->ads.bytes_heads ==
          (uint64_t)3 * 4 * ((W + 1) / 2) * ((H + 1) / 2));
    /* The large primitives (the default scene's walls): up to 16, 2, none. */
    static const int larges[] = {0, 2, -1};
    int kept[3];
    for (int i = 0; i < 3; i++) {
        o.large = larges[i];
        CHECK(dirt_session_set_opts(s, &o, &restarted) && restarted == (i > 0));
        CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
        kept[i] = dirt_session_get_stats(s)->ads.num_large;
    }
    CHECK_MSG(kept[0] > 2 && kept[1] == 2 && kept[2] == 0, "large primitives kept: %d, %d, %d",
              kept[0], kept[1], kept[2]);
    o.large = 17;
    CHECK(!dirt_session_check_opts(&o, NULL, 0));
    o.large = 0;
    /* Bad options are refused and the old ones kept. */
    dirt_session_opts bad = o;
    bad.tile_size = 3;
    CHECK(!dirt_session_set_opts(s, &bad, &restarted));
    CHECK(dirt_session_get_opts(s)->tile_size == 0);
    dirt_session_destroy(s);
}

/* The "model texels" buffer of the stats: listed once, used = allocated =
 * the size of the scene's packed texel buffer. Returns its bytes. */
static uint64_t model_texel_bytes(const dirt_session_stats *st, const dirt_scene *scene)
{
    dirt_gpu_texel_buffer tb;
    CHECK(dirt_gpu_textures_pack(dirt_scene_textures(scene), dirt_scene_num_textures(scene), &tb));
    uint64_t bytes = 0;
    int listed = 0;
    for (int i = 0; i < st->num_buffers; i++) {
        if (strcmp(st->buffers[i].name, "model texels") != 0)
            continue;
        listed++;
        bytes = st->buffers[i].used;
        CHECK(st->buffers[i].allocated == st->buffers[i].used);
    }
    CHECK_MSG(listed == 1 && bytes == tb.size, "model texels listed %d times, %llu bytes, "
              "packed %zu", listed, (unsigned long long)bytes, tb.size);
    dirt_gpu_texel_buffer_free(&tb);
    return bytes;
}

/* The stats record: build passes and the path tracer's, tagged with a clock;
 * the buffers add up to the totals and to the technique's own figures. */
static void check_stats(dirt_gpu *gpu, const dirt_scene *scene)
{
    dirt_session_opts o = {.width = W, .height = H};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
    const dirt_session_stats *st = dirt_session_get_stats(s);
    bool software = dirt_gpu_get_caps(gpu)->software;
    uint64_t used = 0, allocated = 0;
    for (int i = 0; i < st->num_buffers; i++) {
        used += st->buffers[i].used;
        allocated += st->buffers[i].allocated;
        CHECK(st->buffers[i].used <= st->buffers[i].allocated);
    }
    CHECK(used == st->bytes_total_used && allocated == st->bytes_total_allocated);
    CHECK(st->has_ads && st->ads.bytes_total_used < st->bytes_total_used);
    /* The integrator's buffers: 2 x 32 + 2 x 32 + 3 x 32 + 80 + 2 x 4 + 48
     * bytes per pixel (rays, hits, the shading ring, paths, the two ray
     * batches' owners, the sums), the batches' two 16-byte headers and the
     * paths per event (65 x 4 bytes), the environment table (no
     * environment: its header and one float), the tangent table (no normal
     * maps: one record) and the scene's textures. */
    CHECK(st->bytes_total_used - st->ads.bytes_total_used - model_texel_bytes(st, scene) ==
          (uint64_t)W * H * 360 + 2 * 16 + 65 * 4 + ENV_NONE_BYTES + TANGENTS_NONE_BYTES);
    int build = 0, pt = 0;
    for (int i = 0; i < st->num_passes; i++) {
        const dirt_pass_time *p = &st->passes[i];
        CHECK_MSG(p->clock == (software ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU),
                  "pass %s measured by %s", p->name, dirt_clock_names[p->clock]);
        for (int k = 0; k < DIRT_ADS_NUM_PASSES; k++)
            build += !strcmp(p->name, dirt_ads_pass_names[k]);
        pt += !strcmp(p->name, "trace") || !strcmp(p->name, "shade");
    }
    CHECK(build == DIRT_ADS_NUM_PASSES && pt == 2);
    CHECK(st->build_ms > 0 && st->trace_ms > 0 && st->rays >= (uint64_t)W * H);
    dirt_session_destroy(s);
}

/* The same AOV set from dirt, mmrt and embree (beauty, albedo, N, Z), and
 * DIRT's Z equal to Embree's to float precision (MMRT's within a few
 * thicknesses: its hits are fragments within the thickness). */
static void check_aovs(dirt_gpu *gpu, const dirt_scene *scene)
{
    const enum dirt_engine engines[] = {DIRT_ENGINE_DIRT, DIRT_ENGINE_MMRT, DIRT_ENGINE_EMBREE};
    dirt_image *img[3] = {0};
    for (int e = 0; e < 3; e++) {
        dirt_session *s = dirt_session_create(
            gpu, scene, &(dirt_session_opts){.engine = engines[e], .width = W, .height = H});
        CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
        const dirt_image *im = s ? dirt_session_image(s) : NULL;
        img[e] = im ? copy_image(im) : NULL;
        dirt_session_destroy(s);
    }
    if (!img[0] || !img[1] || !img[2])
        return;
    for (int e = 0; e < 2; e++) {
        CHECK(img[e]->channel_count == img[2]->channel_count);
        for (int c = 0; c < img[2]->channel_count; c++)
            CHECK_MSG(dirt_image_find_channel(img[e], img[2]->channels[c].name),
                      "%s lacks channel %s", dirt_engine_names[engines[e]],
                      img[2]->channels[c].name);
    }
    const float *zr = dirt_image_find_channel(img[2], "Z");
    const float *zd = dirt_image_find_channel(img[0], "Z");
    const float *zm = dirt_image_find_channel(img[1], "Z");
    int hits = 0, bad_d = 0, bad_m = 0;
    for (int i = 0; zr && zd && zm && i < W * H; i++) {
        if (isinf(zr[i])) {
            bad_d += !isinf(zd[i]);
            continue;
        }
        hits++;
        bad_d += !(fabsf(zd[i] - zr[i]) <= 1e-5f * zr[i]);
        bad_m += !(fabsf(zm[i] - zr[i]) <= 0.05f * zr[i]);
    }
    CHECK_MSG(hits > W * H / 2 && bad_d == 0, "DIRT Z differs from Embree's at %d of %d", bad_d,
              hits);
    CHECK_MSG(bad_m <= hits / 50, "MMRT Z far from Embree's at %d of %d", bad_m, hits);
    /* ID: DIRT's first hits are Embree's (exact), primitive for primitive. */
    const float *ir = dirt_image_find_channel(img[2], "ID");
    const float *id = dirt_image_find_channel(img[0], "ID");
    int bad_id = 0, id_hits = 0;
    for (int i = 0; ir && id && i < W * H; i++) {
        bad_id += id[i] != ir[i];
        id_hits += ir[i] >= 0;
    }
    CHECK(ir && id);
    CHECK_MSG(bad_id == 0 && id_hits == hits, "DIRT ID differs from Embree's at %d pixels "
              "(%d hits, %d by Z)", bad_id, id_hits, hits);
    /* The raster preview: beauty, N and Z (rasterized depth at pixel centres). */
    dirt_session *r = dirt_session_create(
        gpu, scene, &(dirt_session_opts){.engine = DIRT_ENGINE_RASTER, .width = W, .height = H});
    CHECK(r && dirt_session_add_samples(r, 1, NULL, NULL));
    const dirt_image *ri = r ? dirt_session_image(r) : NULL;
    const float *zp = ri ? dirt_image_find_channel(ri, "Z") : NULL;
    CHECK(zp && dirt_image_find_channel(ri, "N.X") && dirt_image_find_channel(ri, "N.Z"));
    int bad_r = 0;
    for (int i = 0; zp && zr && i < W * H; i++)
        bad_r += isinf(zr[i]) ? !isinf(zp[i]) : !(fabsf(zp[i] - zr[i]) <= 1e-4f * zr[i]);
    CHECK_MSG(bad_r == 0, "raster Z differs from Embree's at %d pixels", bad_r);
    dirt_session_destroy(r);
    fprintf(stderr, "AOVs: one channel set; Z: DIRT == Embree on %d hit pixels, MMRT off at %d\n",
            hits, bad_m);
    for (int e = 0; e < 3; e++)
        dirt_image_destroy(img[e]);
}

static bool in_ci(void)
{
    const char *ci = getenv("CI");
    return ci && !strcmp(ci, "true");
}

/* The automatic camera (also the default for a scene without cameras)
 * frames the whole clip: the same camera, bit for bit, at every frame of an
 * animation whose bounds move; and the image height follows its 4:3. */
static void check_auto_camera(dirt_gpu *gpu)
{
    const char *dir = getenv("DIRT_SHARED_DIR");
    char path[4096];
    snprintf(path, sizeof(path), "%s/scenes/gltf/BoxAnimated/BoxAnimated.gltf",
             dir ? dir : "../shared");
    dirt_scene *scene = dirt_scene_load(path, NULL);
    if (!scene) {
        CHECK_MSG(!in_ci(), "%s is missing (CI=true: the shared scenes must be present)", path);
        fprintf(stderr, "no %s: skipping the animated camera check\n", path);
        return;
    }
    CHECK(dirt_scene_num_cameras(scene) == 0 && dirt_scene_num_clips(scene) > 0);
    dirt_session *s = dirt_session_create(gpu, scene, &(dirt_session_opts){.width = 40});
    CHECK(s != NULL);
    if (!s) {
        dirt_scene_destroy(scene);
        return;
    }
    int w, h;
    dirt_session_size(s, &w, &h);
    CHECK(w == 40 && h == 30);
    float duration = dirt_scene_clip_duration(scene, 0);
    dirt_camera first = *dirt_session_camera(s);
    bool moved = false;
    for (int i = 0; i <= 10; i++) {
        float t = duration * (float)i / 10.0f;
        CHECK(dirt_session_set_time(s, t, NULL));
        CHECK_MSG(memcmp(dirt_session_camera(s), &first, sizeof(first)) == 0,
                  "the automatic camera changed at t = %g", t);
        /* The per-frame framing would have moved: the check can fail. */
        dirt_camera per_frame;
        dirt_camera_auto(dirt_session_frame(s), &per_frame);
        moved |= memcmp(&per_frame, &first, sizeof(first)) != 0;
    }
    CHECK_MSG(moved, "BoxAnimated's per-frame automatic camera never moved");
    /* Explicitly automatic: the same camera. */
    CHECK(dirt_session_set_camera(s, DIRT_CAMERA_AUTO, 0, NULL));
    CHECK(memcmp(dirt_session_camera(s), &first, sizeof(first)) == 0);
    CHECK(!dirt_session_set_camera(s, DIRT_CAMERA_SCENE, 0, NULL)); /* it has none */
    fprintf(stderr, "automatic camera: one camera over BoxAnimated's %.2f s clip\n", duration);
    dirt_session_destroy(s);
    dirt_scene_destroy(scene);
}

/* Chunks (wavefronts): with the path tracer forced to chunks of 200 pixels
 * (192 after rounding to work groups: 9 chunks of the 48x36 image, the last
 * partial), 1 + 1 + 2 samples give the unchunked 4-sample image bit for bit,
 * the display texture covers the whole image, and the bytes are one chunk's
 * buffers (312 B per pixel and 292 B) plus the whole image's sums (48 B per pixel)
 * and the scene's textures. */
static void check_chunks(dirt_gpu *gpu, const dirt_scene *scene, dirt_session_opts o,
                         const char *what)
{
    dirt_session *whole = dirt_session_create(gpu, scene, &o);
    CHECK(whole && dirt_session_add_samples(whole, 4, NULL, NULL));
    const dirt_image *ref = whole ? dirt_session_image(whole) : NULL;
    CHECK(ref != NULL);
    setenv("DIRT_PT_CHUNK_PIXELS", "200", 1);
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    unsetenv("DIRT_PT_CHUNK_PIXELS");
    CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
    CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
    CHECK(s && dirt_session_add_samples(s, 2, NULL, NULL));
    const dirt_image *img = s ? dirt_session_image(s) : NULL;
    CHECK_MSG(img && ref && same_image(ref, img), "%s: chunked 1+1+2 differs from unchunked 4",
              what);
    GLuint tex = s ? dirt_session_display_texture(s) : 0;
    float *px = malloc(sizeof(float) * 4 * W * H);
    CHECK(tex && px && gl_texture_read_rgba32f(tex, W, H, px));
    CHECK_MSG(img && px && memcmp(px, img->rgba, sizeof(float) * 4 * W * H) == 0,
              "%s: chunked display texture differs from the image", what);
    free(px);
    const dirt_session_stats *st = s ? dirt_session_get_stats(s) : NULL;
    if (st && st->has_ads)
        CHECK(st->bytes_total_used - st->ads.bytes_total_used - model_texel_bytes(st, scene) ==
              (uint64_t)192 * 312 + 292 + (uint64_t)W * H * 48 + ENV_NONE_BYTES +
                  TANGENTS_NONE_BYTES);
    fprintf(stderr, "%s: chunks of 192 pixels, 1+1+2 == unchunked 4, display == image\n",
            what);
    dirt_session_destroy(s);
    dirt_session_destroy(whole);
}

/* Structure pictures: every DIRT id node and every MMRT fragment is counted
 * once in the list-length picture (sum == the build's own count), bucket
 * occupancy never exceeds the buckets, and zmin <= zmax in every cell. */
static void check_pictures(dirt_gpu *gpu, const dirt_scene *scene)
{
    const enum dirt_engine engines[] = {DIRT_ENGINE_DIRT, DIRT_ENGINE_MMRT};
    for (int e = 0; e < 2; e++) {
        dirt_session *s = dirt_session_create(
            gpu, scene, &(dirt_session_opts){.engine = engines[e], .width = W, .height = H});
        CHECK(s && dirt_session_build(s));
        if (!s)
            continue;
        float top[4] = {0};
        dirt_image *pic[4];
        for (int k = 0; k < 4; k++)
            pic[k] = dirt_session_picture(s, (enum dirt_session_picture)k, &top[k]);
        CHECK(pic[0] && pic[1] && pic[2] && pic[3]);
        if (!pic[0] || !pic[1] || !pic[2] || !pic[3])
            continue;
        const dirt_session_stats *st = dirt_session_get_stats(s);
        /* the defaults (dirt_session_opts.buckets) */
        int buckets = e == 0 ? dirt_session_auto_buckets(gpu) : 4;
        uint64_t want = e == 0 ? st->ads.nodes : st->mmrt.fragments;
        double sum = 0;
        int over = 0, order = 0, cells = 0;
        size_t n = (size_t)pic[0]->width * pic[0]->height;
        for (size_t i = 0; i < n; i++) {
            if (pic[0]->rgba[4 * i + 3] == 0)
                continue;
            cells++;
            sum += pic[0]->rgba[4 * i];
            over += pic[1]->rgba[4 * i] > (float)buckets ||
                    pic[1]->rgba[4 * i] > pic[0]->rgba[4 * i];
            float zmin = pic[2]->rgba[4 * i], zmax = pic[3]->rgba[4 * i];
            order += !isnan(zmin) && !(zmin <= zmax);
        }
        CHECK_MSG(sum == (double)want && want > 0, "%s: list picture sums to %.0f, build %llu",
                  dirt_engine_names[engines[e]], sum, (unsigned long long)want);
        CHECK(over == 0 && order == 0 && cells > 0 && top[1] == (float)buckets && top[0] >= 1);
        for (int k = 0; k < 4; k++)
            dirt_image_destroy(pic[k]);
        dirt_session_destroy(s);
    }
    dirt_session *r = dirt_session_create(
        NULL, scene, &(dirt_session_opts){.engine = DIRT_ENGINE_EMBREE, .width = W, .height = H});
    CHECK(r && !dirt_session_picture(r, DIRT_PICTURE_LISTS, NULL));
    dirt_session_destroy(r);
    fprintf(stderr, "pictures: DIRT nodes and MMRT fragments counted once each\n");
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    dirt_session_opts dirt = {.width = W, .height = H, .bounces = 2, .seed = 3};
    check_progressive(gpu, scene, dirt, "dirt");
    dirt.fetch = DIRT_FETCH_RASTER;
    dirt.views = DIRT_SESSION_VIEWS_SINGLE;
    check_progressive(gpu, scene, dirt, "dirt, raster fetch, single view");
    dirt_session_opts mmrt = {.engine = DIRT_ENGINE_MMRT, .width = W, .height = H,
                              .bounces = 2, .march = DIRT_MMRT_MARCH_LINEAR, .seed = 5};
    check_progressive(gpu, scene, mmrt, "mmrt, linear march");
    check_chunks(gpu, scene, (dirt_session_opts){.width = W, .height = H, .bounces = 2, .seed = 3},
                 "dirt");
    check_chunks(gpu, scene, mmrt, "mmrt, linear march");
    check_restarts(gpu, scene);
    check_stats(gpu, scene);
    check_auto_camera(gpu);
    check_aovs(gpu, scene);
    check_pictures(gpu, scene);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
