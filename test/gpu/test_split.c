/* Arrays past one storage block (src/gl/split.h; doc/architecture.md,
 * "Arrays past one storage block"):
 *  1. accessors: glsl/test/split.comp writes and reads every split array in
 *     three layouts: one storage block; one texel-buffer part (the block
 *     below the arrays, the parts at the texel-buffer limit); 2..4 parts
 *     (the block lowered to 4096 bytes: gl_gpu_set_block_bytes, the
 *     in-process DIRT_MAX_BLOCK_BYTES). What the stores, the exchanges, the
 *     min and the max wrote reads back on the CPU record for record, and the
 *     loads return what the CPU and the stores wrote;
 *  2. a closed room of 3600 small triangles traced by DIRT and MMRT with the
 *     block lowered so that their arrays come in 2..8 parts (each array is
 *     checked to be split, so the test cannot pass unsplit): the hits of
 *     every ray type equal the unsplit structure's bit for bit (primitive,
 *     t, barycentrics) and DIRT's agree with Embree's (>= 99.9 %, as
 *     test_dirt_hits); same-seed path-traced images equal the unsplit ones
 *     bit for bit, and DIRT's equals Embree's within float rounding
 *     (relative MSE below 1e-4, as test_dirt_pt);
 *  3. past what the GPU holds in one array (more than DIRT_SPLIT_MAX_PARTS
 *     parts) a build fails before any upload with one error naming what to
 *     change, and the same object builds once the scene fits again. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dirt/ads.h"
#include "dirt/ads_internal.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "gl/program.h"
#include "gpu.h"
#include "mmrt/mmrt_internal.h"
#include "session_util.h"

/* ---- 1. accessors ---- */

enum { A_VERT, A_MAT, A_CAND, A_NODE, A_HEAD, A_MHEAD, A_MTAIL, A_MID, A_MDATA, A_DEPTH, A_N };

/* Records of each array: 2..4 parts of a 4096-byte block. */
static const size_t counts[A_N] = {70, 2500, 600, 1200, 2500, 2500, 2500, 400, 400, 1200};

static const gl_split_desc *descs[A_N];

static uint32_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof(u));
    return u;
}

static float vfloat(size_t v, int j)
{
    /* vertex v's position (j < 4) and normal (j >= 4) */
    static const float add[8] = {0.0f, 0.25f, -1.5f, 0.5f, 1.0f, 2.0f, 3.0f, -0.125f};
    return (float)v * (j & 1 ? -1.0f : 1.0f) + add[j];
}

/* One layout: `block` 0 = the driver's; `parts_at_limit` keeps the parts at
 * the texel-buffer limit (one part) while the block is below the arrays. */
static void accessors(dirt_gpu *gpu, int64_t block, bool parts_at_limit, int want)
{
    gl_gpu_set_block_bytes(gpu, block);
    if (parts_at_limit)
        gpu->caps.block_override = 0;
    gl_split arr[A_N];
    memset(arr, 0, sizeof(arr));
    gl_split_layout lay[A_N];
    bool ok = true;
    for (int a = 0; a < A_N; a++) {
        ok = ok && gl_split_ensure(gpu, &arr[a], descs[a], counts[a]);
        lay[a] = arr[a].layout;
        int parts = arr[a].layout.parts;
        CHECK_MSG(want == 2 ? parts >= 2 : parts == want, "%s: %d parts, want %s%d",
                  descs[a]->label, parts, want == 2 ? ">= " : "", want);
    }
    CHECK(ok);
    gl_split_program prog = {0};
    const char *paths[] = {"test/split.comp", NULL};
    CHECK(ok && gl_split_program_ensure(&prog, "test/split.comp", paths, NULL, 0, descs, lay, A_N));
    if (!ok || !prog.id) {
        for (int a = 0; a < A_N; a++)
            gl_split_release(&arr[a]);
        gl_gpu_set_block_bytes(gpu, 0);
        return;
    }
    /* What the CPU writes: the vertices and the materials. */
    size_t nv = counts[A_VERT];
    float *verts = malloc(nv * 24 * sizeof(float));
    uint32_t *mats = malloc(counts[A_MAT] * sizeof(uint32_t));
    for (size_t v = 0; v < 3 * nv; v++)
        for (int j = 0; j < 8; j++)
            verts[8 * v + (size_t)j] = vfloat(v, j);
    for (size_t i = 0; i < counts[A_MAT]; i++)
        mats[i] = (uint32_t)(i * 7 + 3);
    CHECK(gl_split_write(&arr[A_VERT], 0, nv, verts));
    CHECK(gl_split_write(&arr[A_MAT], 0, counts[A_MAT], mats));
    static const uint32_t end = DIRT_LIST_END;
    gl_split_clear(&arr[A_HEAD], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    size_t maxn = 0;
    for (int a = 0; a < A_N; a++)
        maxn = counts[a] > maxn ? counts[a] : maxn;
    uint32_t in[12] = {0, 0, 0, 0,
                       (uint32_t)counts[A_VERT], (uint32_t)counts[A_MAT],
                       (uint32_t)counts[A_CAND], (uint32_t)counts[A_NODE],
                       (uint32_t)counts[A_HEAD], (uint32_t)counts[A_MHEAD],
                       (uint32_t)counts[A_MID], (uint32_t)counts[A_DEPTH]};
    /* (storage blocks of the driver's size whatever the test's block) */
    GLuint bin = gl_buffer_create(NULL, sizeof(in), in, false, "split test in");
    size_t out_bytes = maxn * 9 * 16;
    GLuint bout = gl_buffer_create(NULL, out_bytes, NULL, true, "split test out");
    uint32_t *out = calloc(maxn * 36, sizeof(uint32_t));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_IN, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, bout);
    for (int a = 0; a < A_N; a++)
        gl_split_bind(&arr[a]);
    glUseProgram(prog.id);
    glDispatchCompute((GLuint)DIRT_GROUPS(maxn), 1, 1); /* op 0: write */
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    CHECK(gl_buffer_read(bout, 0, counts[A_HEAD] * 16, out));
    size_t bad = 0;
    for (size_t i = 0; i < counts[A_HEAD]; i++)
        bad += out[4 * i] != DIRT_LIST_END; /* the exchange returned the cleared head */
    in[0] = 1;
    glNamedBufferSubData(bin, 0, 16, in);
    glDispatchCompute((GLuint)DIRT_GROUPS(maxn), 1, 1); /* op 1: read */
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(0);
    CHECK(gl_buffer_read(bout, 0, out_bytes, out));
    /* The loads. */
    for (size_t i = 0; i < maxn; i++) {
        const uint32_t *o = out + 36 * i;
        uint32_t want_o[36] = {0};
        if (i < nv) {
            for (int j = 0; j < 4; j++) {
                want_o[j] = fbits(vfloat(3 * i + 2, j));
                want_o[4 + j] = fbits(vfloat(3 * i, 4 + j));
            }
            for (int j = 0; j < 3; j++)
                want_o[8 + j] = fbits(vfloat(3 * i + 1, j));
        }
        if (i < counts[A_MAT])
            want_o[11] = (uint32_t)(i * 7 + 3);
        if (i < counts[A_CAND]) {
            want_o[12] = (uint32_t)i, want_o[13] = (uint32_t)(3 * i);
            want_o[14] = (uint32_t)(i + 11), want_o[15] = (uint32_t)(i + 13);
        }
        if (i < counts[A_NODE])
            want_o[16] = (uint32_t)i, want_o[17] = ~(uint32_t)i;
        if (i < counts[A_HEAD])
            want_o[18] = (uint32_t)i ^ 0x55u;
        uint32_t zmin = 1000 + (uint32_t)i / 2, zmax = 2000 + (uint32_t)i;
        if (1000 + 2 * (uint32_t)i > zmax)
            zmax = 1000 + 2 * (uint32_t)i;
        if (i < counts[A_DEPTH])
            want_o[19] = zmin, want_o[22] = zmax;
        if (i < counts[A_MHEAD])
            want_o[20] = (uint32_t)i + 2, want_o[21] = (uint32_t)i + 1 + 100;
        if (i < counts[A_MID]) {
            want_o[24] = 2 * (uint32_t)i, want_o[25] = 2 * (uint32_t)i + 1;
            want_o[26] = ~(uint32_t)i, want_o[27] = (uint32_t)i;
            for (int j = 0; j < 4; j++)
                want_o[28 + j] = (uint32_t)i + (uint32_t)j;
            want_o[32] = fbits((float)i * 0.5f), want_o[33] = fbits(-(float)i);
            want_o[34] = fbits(1.0f / (float)(i + 1)), want_o[35] = fbits(3.0f);
        }
        for (int j = 0; j < 36; j++) {
            if (o[j] != want_o[j] && bad++ < 10)
                fprintf(stderr, "  record %zu word %d: %u, want %u\n", i, j, o[j], want_o[j]);
        }
    }
    /* What the stores wrote, read back by the CPU. */
    uint32_t *back = malloc(counts[A_MAT] * 16);
    if (gl_split_read(&arr[A_CAND], 0, counts[A_CAND], back)) {
        for (size_t i = 0; i < counts[A_CAND]; i++)
            bad += back[4 * i] != i || back[4 * i + 1] != 3 * i || back[4 * i + 2] != i + 11 ||
                   back[4 * i + 3] != i + 13;
    }
    if (gl_split_read(&arr[A_NODE], 0, counts[A_NODE], back)) {
        for (size_t i = 0; i < counts[A_NODE]; i++)
            bad += back[2 * i] != i || back[2 * i + 1] != ~(uint32_t)i;
    }
    if (gl_split_read(&arr[A_MTAIL], 0, counts[A_MTAIL], back)) {
        for (size_t i = 0; i < counts[A_MTAIL]; i++)
            bad += back[i] != i + 101;
    }
    if (gl_split_read(&arr[A_MDATA], 0, counts[A_MDATA], back)) {
        for (size_t i = 0; i < counts[A_MDATA]; i++)
            bad += back[8 * i + 3] != i + 3 || back[8 * i + 7] != fbits(3.0f);
    }
    if (gl_split_read(&arr[A_DEPTH], 0, counts[A_DEPTH], back)) {
        for (size_t i = 0; i < counts[A_DEPTH]; i++)
            bad += back[2 * i] != 1000 + i / 2;
    }
    fprintf(stderr, "accessors, %s: %zu wrong words\n",
            want == 0 ? "one storage block" : want == 1 ? "one texel-buffer part" : "2..4 parts",
            bad);
    CHECK(bad == 0);
    CHECK(gl_check("split accessors"));
    free(back);
    free(out);
    free(verts);
    free(mats);
    gl_buffer_destroy(&bin);
    gl_buffer_destroy(&bout);
    gl_split_program_destroy(&prog);
    for (int a = 0; a < A_N; a++)
        gl_split_release(&arr[a]);
    gl_gpu_set_block_bytes(gpu, 0);
}

/* ---- 2., 3. the techniques ---- */

/* A closed 4 x 3 x 5 room (white, red and green walls, an emissive ceiling
 * panel) holding a 5 x 4 grid of UV spheres of 180 triangles: 3626
 * triangles as OBJ + MTL text. */
static dirt_scene *room_scene(void)
{
    size_t cap = 1 << 20, len = 0;
    char *obj = malloc(cap);
    int nv = 0;
#define OUT(...) (len += (size_t)snprintf(obj + len, cap - len, __VA_ARGS__))
    OUT("mtllib room.mtl\n");
    static const float room[8][3] = {{-2, 0, 0}, {2, 0, 0}, {2, 3, 0}, {-2, 3, 0},
                                     {-2, 0, -5}, {2, 0, -5}, {2, 3, -5}, {-2, 3, -5}};
    for (int i = 0; i < 8; i++)
        OUT("v %g %g %g\n", room[i][0], room[i][1], room[i][2]);
    /* faces wound to face inwards */
    OUT("usemtl white\nf 1 5 6\nf 1 6 2\nf 4 3 7\nf 4 7 8\nf 5 8 7\nf 5 7 6\nf 1 2 3\nf 1 3 4\n");
    OUT("usemtl red\nf 1 4 8\nf 1 8 5\nusemtl green\nf 2 6 7\nf 2 7 3\n");
    OUT("v -0.5 2.99 -3\nv 0.5 2.99 -3\nv 0.5 2.99 -2\nv -0.5 2.99 -2\n");
    OUT("usemtl light\nf 9 12 11\nf 9 11 10\n");
    nv = 12;
    const int lat = 10, lon = 10;
    for (int s = 0; s < 20; s++) {
        float cx = -1.5f + 0.75f * (float)(s % 5), cy = 0.5f + 0.6f * (float)(s / 5 % 4),
              cz = -2.2f - 0.5f * (float)(s % 3), r = 0.21f;
        int base = nv + 1;
        for (int i = 0; i <= lat; i++) {
            float th = 3.14159265f * (float)i / (float)lat;
            for (int j = 0; j < lon; j++) {
                float ph = 6.2831853f * (float)j / (float)lon;
                OUT("v %.7g %.7g %.7g\n", cx + r * sinf(th) * cosf(ph), cy + r * cosf(th),
                    cz + r * sinf(th) * sinf(ph));
                nv++;
            }
        }
        OUT("usemtl %s\n", s % 2 ? "white" : "glossy");
        for (int i = 0; i < lat; i++) {
            for (int j = 0; j < lon; j++) {
                int a = base + i * lon + j, b = base + i * lon + (j + 1) % lon;
                int c = a + lon, d = b + lon;
                if (i > 0)
                    OUT("f %d %d %d\n", a, b, d);
                if (i < lat - 1)
                    OUT("f %d %d %d\n", a, d, c);
            }
        }
    }
#undef OUT
    static const char mtl[] =
        "newmtl white\nKd 0.73 0.73 0.73\nnewmtl red\nKd 0.63 0.065 0.05\n"
        "newmtl green\nKd 0.14 0.45 0.091\nnewmtl glossy\nKd 0.2 0.3 0.7\nKs 0.5 0.5 0.5\n"
        "Ns 200\nnewmtl light\nKd 0 0 0\nKe 15 15 15\n";
    dirt_scene *sc = dirt_scene_load_obj_memory(obj, len, mtl, sizeof(mtl) - 1, "room", NULL);
    free(obj);
    return sc;
}

/* Rays of every type (dirt/raytypes.h) from a 48 x 36 G-buffer: n[t] of
 * type t. */
typedef struct ray_set {
    size_t n[DIRT_RAY_TYPES];
    dirt_ray *rays[DIRT_RAY_TYPES];
    dirt_ref_hit *ref[DIRT_RAY_TYPES];
} ray_set;

static bool same_hits(const dirt_hit *a, const dirt_hit *b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (a[i].prim != b[i].prim || fbits(a[i].t) != fbits(b[i].t) ||
            fbits(a[i].u) != fbits(b[i].u) || fbits(a[i].v) != fbits(b[i].v))
            return false;
    }
    return true;
}

/* DIRT's hits of every type into hits[t] (n each). */
static bool dirt_hits(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam,
                      const ray_set *rs, dirt_hit **hits, bool split)
{
    dirt_ads_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 64, .height = 48,
                                 .face_size = 32, .tile_size = 1},
                       .buckets = 8, .force_emulation = true};
    dirt_ads *ads = dirt_ads_create(gpu, &o);
    bool ok = ads && dirt_ads_build(ads, f, cam);
    CHECK(ok);
    if (ok && split) {
        gl_split *arr[] = {&ads->vertices, &ads->cands, &ads->nodes, &ads->heads, &ads->depth};
        for (size_t i = 0; i < sizeof(arr) / sizeof(arr[0]); i++)
            CHECK_MSG(arr[i]->layout.parts >= 2, "DIRT's %s: %d parts", arr[i]->desc->label,
                      arr[i]->layout.parts);
    }
    for (int t = DIRT_RAY_PRIMARY; ok && t < DIRT_RAY_TYPES; t++) {
        dirt_trace_stats ts;
        dirt_trace_opts to = {.any_hit = t == DIRT_RAY_VISIBILITY};
        ok = dirt_ads_trace(ads, rs->rays[t], rs->n[t], hits[t], &to, &ts) && ts.aborted == 0;
    }
    CHECK(ok);
    dirt_ads_destroy(ads);
    return ok;
}

static bool mmrt_hits(dirt_gpu *gpu, const dirt_frame *f, const dirt_camera *cam,
                      const ray_set *rs, dirt_hit **hits, int want_split)
{
    dirt_mmrt_opts o = {.views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = 96, .height = 72,
                                  .face_size = 48},
                        .buckets = 4};
    dirt_mmrt *m = dirt_mmrt_create(gpu, &o);
    bool ok = m && dirt_mmrt_build(m, f, cam);
    CHECK(ok);
    if (ok && want_split) {
        gl_split *arr[MMRT_NUM_ARRAYS];
        mmrt_arrays(m, arr);
        for (int i = 0; i < MMRT_NUM_ARRAYS; i++) {
            if (want_split & (1 << i))
                CHECK_MSG(arr[i]->layout.parts >= 2, "MMRT's %s: %d parts",
                          arr[i]->desc->label, arr[i]->layout.parts);
        }
    }
    for (int t = DIRT_RAY_PRIMARY; ok && t < DIRT_RAY_TYPES; t++)
        ok = dirt_mmrt_trace_cpu(m, rs->rays[t], rs->n[t], hits[t], NULL, NULL);
    CHECK(ok);
    dirt_mmrt_destroy(m);
    return ok;
}

static dirt_image *render(dirt_gpu *gpu, const dirt_scene *scene, enum dirt_engine e)
{
    dirt_session_opts o = {.engine = e, .width = 48, .height = 36, .tile_size = 1, .buckets = 8,
                           .seed = 3};
    return test_session_render(gpu, scene, &o, 2);
}

static bool same_image(const dirt_image *a, const dirt_image *b)
{
    return a && b && !memcmp(a->rgba, b->rgba, sizeof(float) * 4 * (size_t)a->width * a->height);
}

static int limit_errors;

static void on_log(void *user, enum dirt_log_level level, const char *file, int line,
                   const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level == DIRT_LOG_ERROR)
        limit_errors += strstr(msg, "more than this GPU holds in one array") &&
                        strstr(msg, "fewer triangles") ? 1 : 1000;
}

static void techniques(dirt_gpu *gpu)
{
    dirt_scene *scene = room_scene();
    CHECK(scene != NULL);
    if (!scene)
        return;
    dirt_frame *f = dirt_scene_evaluate(scene, 0, NULL);
    fprintf(stderr, "room: %zu triangles\n", f->num_triangles);
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    dirt_gbuffer g;
    CHECK(accel && dirt_gbuffer_build(accel, scene, f, &cam, 48, 36, &g));
    ray_set rs;
    dirt_hit *base[DIRT_RAY_TYPES], *split[DIRT_RAY_TYPES];
    size_t most = 48 * 36; /* primary rays: every pixel; the others: the G-buffer's hits */
    for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
        rs.rays[t] = malloc(most * sizeof(dirt_ray));
        rs.ref[t] = malloc(most * sizeof(dirt_ref_hit));
        base[t] = malloc(most * sizeof(dirt_hit));
        split[t] = malloc(most * sizeof(dirt_hit));
        rs.n[t] = dirt_rays_generate(&g, &cam, t, 5, rs.rays[t]);
        CHECK(rs.n[t] > 0 && rs.n[t] <= most);
        dirt_ref_intersect(accel, (const dirt_ref_ray *)rs.rays[t], rs.ref[t], rs.n[t], 0);
    }
    /* DIRT: unsplit, then in 2..8 parts (64 KiB blocks). */
    dirt_hits(gpu, f, &cam, &rs, base, false);
    gl_gpu_set_block_bytes(gpu, 64 << 10);
    dirt_hits(gpu, f, &cam, &rs, split, true);
    gl_gpu_set_block_bytes(gpu, 0);
    for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
        CHECK_MSG(same_hits(base[t], split[t], rs.n[t]), "DIRT %s: split hits differ",
                  dirt_ray_type_names[t]);
        size_t agree = 0;
        for (size_t i = 0; i < rs.n[t]; i++) {
            const dirt_hit *d = &split[t][i];
            const dirt_ref_hit *e = &rs.ref[t][i];
            bool dh = d->prim != DIRT_HIT_NONE, eh = e->prim != DIRT_REF_MISS;
            agree += t == DIRT_RAY_VISIBILITY || !dh || !eh
                         ? dh == eh
                         : d->prim == e->prim || fabs(d->t - e->t) <= 1e-4 * fmax(e->t, 1e-3);
        }
        fprintf(stderr, "DIRT split %s: %.2f %% agree with Embree\n", dirt_ray_type_names[t],
                100.0 * (double)agree / (double)rs.n[t]);
        CHECK(agree >= 0.999 * (double)rs.n[t]);
    }
    /* MMRT: its vertices, A-buffer and depth pyramid in 2..8 parts (its
     * per-primitive materials stay one block: they are 24 times smaller
     * than the vertices). */
    mmrt_hits(gpu, f, &cam, &rs, base, 0);
    gl_gpu_set_block_bytes(gpu, 64 << 10);
    bool built = mmrt_hits(gpu, f, &cam, &rs, split, ~(1 << MMRT_PRIM_MATERIAL));
    gl_gpu_set_block_bytes(gpu, 0);
    for (int t = DIRT_RAY_PRIMARY; built && t < DIRT_RAY_TYPES; t++)
        CHECK_MSG(same_hits(base[t], split[t], rs.n[t]), "MMRT %s: split hits differ",
                  dirt_ray_type_names[t]);
    /* Same-seed images through the sessions (the path tracer chunked too). */
    dirt_image *ref = render(gpu, scene, DIRT_ENGINE_EMBREE);
    for (int e = 0; e < 2; e++) {
        enum dirt_engine engine = e ? DIRT_ENGINE_MMRT : DIRT_ENGINE_DIRT;
        dirt_image *a = render(gpu, scene, engine);
        gl_gpu_set_block_bytes(gpu, 64 << 10);
        dirt_image *b = render(gpu, scene, engine);
        gl_gpu_set_block_bytes(gpu, 0);
        CHECK_MSG(same_image(a, b), "%s: the split render differs from the unsplit one",
                  e ? "mmrt" : "dirt");
        if (!e && ref && b) {
            double rel = dirt_image_rel_mse(b, ref);
            fprintf(stderr, "DIRT split, same seed as Embree: relative MSE %.3g\n", rel);
            CHECK(rel < 1e-4);
        }
        dirt_image_destroy(a);
        dirt_image_destroy(b);
    }
    dirt_image_destroy(ref);
    /* Past what one array holds: one error up front, then the same objects
     * build again. */
    dirt_ads_opts ao = {.views = {.width = 32, .height = 24}, .buckets = 4};
    dirt_mmrt_opts mo = {.views = {.width = 32, .height = 24}, .buckets = 4};
    dirt_ads *ads = dirt_ads_create(gpu, &ao);
    dirt_mmrt *m = dirt_mmrt_create(gpu, &mo);
    CHECK(ads && m);
    if (ads && m) {
        gl_gpu_set_block_bytes(gpu, 4096);
        dirt_log_set_callback(on_log, NULL);
        CHECK(!dirt_ads_build(ads, f, &cam));
        CHECK(!dirt_mmrt_build(m, f, &cam));
        dirt_log_set_callback(NULL, NULL);
        gl_gpu_set_block_bytes(gpu, 0);
        CHECK_MSG(limit_errors == 2, "%d (1000 per other error)", limit_errors);
        CHECK(dirt_ads_build(ads, f, &cam));
        CHECK(dirt_mmrt_build(m, f, &cam));
    }
    dirt_ads_destroy(ads);
    dirt_mmrt_destroy(m);
    for (int t = DIRT_RAY_PRIMARY; t < DIRT_RAY_TYPES; t++) {
        free(rs.rays[t]);
        free(rs.ref[t]);
        free(base[t]);
        free(split[t]);
    }
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    const gl_split_desc *d[A_N] = {
        &gl_split_vertices, &gl_split_prim_material, ads_array_desc[ADS_CANDIDATES],
        ads_array_desc[ADS_NODES], ads_array_desc[ADS_HEADS], mmrt_array_desc[MMRT_HEADS],
        mmrt_array_desc[MMRT_TAILS], mmrt_array_desc[MMRT_IDS], mmrt_array_desc[MMRT_DATA],
        &gl_split_depth};
    memcpy(descs, d, sizeof(d));
    accessors(gpu, 0, false, 0);
    accessors(gpu, 4096, true, 1);
    accessors(gpu, 4096, false, 2);
    techniques(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
