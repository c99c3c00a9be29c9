/* Every hand-written glMemoryBarrier is needed, and the barrier checker
 * (src/gl/check.c) proves it: a workload that reaches every call site of
 * glMemoryBarrier in src/ (sessions of every GPU engine and Fetch, chunked
 * and whole, samples whole and in pieces, direct visibility, pool growth, the display texture and a
 * shader sampling it, structure pictures, the technique APIs that read
 * back) runs clean with the checker counting; then once per call site
 * with that one call issuing nothing (gl_check_drop_barrier), and every
 * such run must report a hazard. The call sites are the ones the checker
 * saw, and every `glMemoryBarrier(` in the source (src/, the frame graph's
 * own call aside: graph_gpu and graph_barrier test its derived bits) must
 * be among them, so a new barrier without a case here fails this test.
 * Prints, per site, the hazards its removal causes. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "dirt/ads.h"
#include "dirt/session.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "mmrt/mmrt.h"
#include "gpu.h"

#define W 24
#define H 18

static dirt_gpu *gpu;
static bool quiet;          /* the runs with a barrier dropped: no hazard messages */
static char first_hazard[1024];

static void on_log(void *user, enum dirt_log_level level, const char *file, int line,
                   const char *msg)
{
    (void)user, (void)file, (void)line;
    bool hazard = strncmp(msg, "barrier check:", 14) == 0 && !strstr(msg, "test hook");
    if (quiet && hazard && !first_hazard[0])
        snprintf(first_hazard, sizeof(first_hazard), "%s", msg);
    if (!(quiet && hazard) && level <= DIRT_LOG_WARN)
        fprintf(stderr, "%s\n", msg);
}
static dirt_scene *scene;
static GLuint prog_sample;

/* A shader reads the display texture as the window's draw does (a texture
 * fetch after the display pass's image stores). */
static void sample_texture(GLuint tex)
{
    static GLuint out;
    if (!out)
        out = gl_buffer_create(gpu, 64, NULL, true, "barriers sample out");
    glUseProgram(prog_sample);
    glBindTextureUnit(DIRT_UNIT_TEST, tex);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, out);
    glDispatchCompute(1, 1, 1);
    glUseProgram(0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); /* the next call's write */
}

/* One session: samples (1 + 1), its image, its display texture (sampled,
 * and read back) and, for the structure engines, its pictures. */
static void session(dirt_session_opts o, const char *chunk)
{
    if (chunk)
        setenv("DIRT_PT_CHUNK_PIXELS", chunk, 1);
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    unsetenv("DIRT_PT_CHUNK_PIXELS");
    CHECK(s != NULL);
    if (!s)
        return;
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    GLuint tex = dirt_session_display_texture(s);
    CHECK(tex != 0);
    sample_texture(tex);
    CHECK(dirt_session_add_samples(s, 1, NULL, NULL));
    CHECK(dirt_session_image(s) != NULL);
    tex = dirt_session_display_texture(s);
    float *px = malloc(sizeof(float) * 4 * W * H);
    CHECK(tex && px && gl_texture_read_rgba32f(tex, W, H, px));
    free(px);
    /* A sample in pieces (dirt_session_advance: the accumulation bound in
     * ranges), then one in progress: the display and the image of the
     * completed samples, from their copy. */
    bool done = false;
    for (int i = 0; i < 100000 && !done; i++)
        CHECK(dirt_session_advance(s, 0, &done));
    CHECK(dirt_session_advance(s, 0, &done));
    tex = dirt_session_display_texture(s);
    CHECK(tex != 0);
    sample_texture(tex);
    CHECK(dirt_session_image(s) != NULL);
    if (o.engine == DIRT_ENGINE_DIRT || o.engine == DIRT_ENGINE_MMRT) {
        dirt_image *pic = dirt_session_picture(s, DIRT_PICTURE_LISTS, NULL);
        CHECK(pic != NULL);
        dirt_image_destroy(pic);
    }
    dirt_session_destroy(s);
}

/* Rays from the camera through a grid of pixels. */
static void camera_rays(const dirt_frame *f, dirt_ray *rays, int n)
{
    float c[3];
    for (int k = 0; k < 3; k++)
        c[k] = 0.5f * (f->bounds_min[k] + f->bounds_max[k]);
    for (int i = 0; i < n; i++) {
        float t = (float)i / (float)n;
        float org[3] = {c[0] + 0.1f * t, c[1] + 0.05f, c[2] + 0.1f};
        float dir[3] = {0.3f - 0.6f * t, -0.2f + 0.4f * (float)((i * 7) % n) / (float)n,
                        -1.0f};
        rays[i] = (dirt_ray){{org[0], org[1], org[2]}, 0.0f, {dir[0], dir[1], dir[2]}, 1e30f};
    }
}

/* The technique APIs: DIRT trace (with stats), trace + Fetch, direct
 * visibility; MMRT trace (with stats). */
static void apis(void)
{
    dirt_frame *f = dirt_scene_evaluate(scene, 0.0f, NULL);
    dirt_camera cam;
    dirt_camera_auto(f, &cam);
    enum { N = 64 };
    dirt_ray rays[N];
    dirt_hit hits[N];
    camera_rays(f, rays, N);
    dirt_ads *a = dirt_ads_create(gpu, &(dirt_ads_opts){
        .views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H}});
    CHECK(a && dirt_ads_build(a, f, &cam));
    dirt_ads_data data;
    CHECK(a && dirt_ads_read(a, &data)); /* right after the build */
    dirt_ads_data_free(&data);
    dirt_trace_stats ts;
    CHECK(a && dirt_ads_trace(a, rays, N, hits, NULL, &ts));
    dirt_gpoint gp[N];
    CHECK(a && dirt_ads_trace_fetch(a, rays, N, DIRT_FETCH_RASTER, gp));
    dirt_ray *vr = malloc(sizeof(*vr) * W * H);
    dirt_hit *vh = malloc(sizeof(*vh) * W * H);
    CHECK(a && vr && vh && dirt_ads_direct_visibility(a, vr, vh));
    free(vr);
    free(vh);
    dirt_ads_destroy(a);
    dirt_mmrt *m = dirt_mmrt_create(gpu, &(dirt_mmrt_opts){
        .views = {.mode = DIRT_VIEWS_CUBE_CAMERA, .width = W, .height = H}});
    dirt_mmrt_trace_stats ms;
    CHECK(m && dirt_mmrt_build(m, f, &cam));
    CHECK(m && dirt_mmrt_trace_cpu(m, rays, N, hits, &(dirt_mmrt_trace_opts){.count = true},
                                   &ms));
    /* The tracer's trace and Fetch called as the test mmrt_pt does, outside
     * a frame graph, then read back. */
    const dirt_tracer *tr = m ? dirt_mmrt_tracer(m, NULL) : NULL;
    GLuint br = gl_buffer_create(gpu, N * sizeof(dirt_ray), rays, false, "barriers rays");
    GLuint bh = gl_buffer_create(gpu, N * sizeof(dirt_hit), NULL, true, "barriers hits");
    GLuint bg = gl_buffer_create(gpu, 3 * N * 32, NULL, true, "barriers gpoints");
    CHECK(tr && tr->trace(tr->self, br, bh, N, 0) && tr->fetch(tr->self, br, bh, N, bg, 0));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the test's readback */
    CHECK(gl_buffer_read(bg, 0, 32, hits));
    gl_buffer_destroy(&br);
    gl_buffer_destroy(&bh);
    gl_buffer_destroy(&bg);
    dirt_mmrt_destroy(m);
    dirt_frame_destroy(f);
}

static void workload(void)
{
    const dirt_session_opts base = {.width = W, .height = H, .bounces = 2, .seed = 7};
    dirt_session_opts o = base;
    session(o, NULL);                                /* DIRT, compute Fetch */
    o.fetch = DIRT_FETCH_RASTER;
    session(o, "200");                               /* raster Fetch, chunked */
    o = base;
    o.views = DIRT_SESSION_VIEWS_SINGLE;
    o.direct_visibility = true;
    session(o, NULL);                                /* direct visibility */
    o = base;
    o.build = DIRT_SESSION_BUILD_COMPUTE;
    session(o, NULL);                                /* the compute build */
    o = base;
    o.depth_buckets = DIRT_DEPTH_BUCKETS_ADAPTIVE;
    session(o, NULL);                                /* adaptive depth buckets */
    o = base;
    o.engine = DIRT_ENGINE_MMRT;
    o.march = DIRT_MMRT_MARCH_LINEAR;
    session(o, "200");                               /* MMRT, chunked */
    o.march = DIRT_MMRT_MARCH_HIZ;
    session(o, NULL);
    o = base;
    o.engine = DIRT_ENGINE_RASTER;
    session(o, NULL);
    apis();
}

/* The `glMemoryBarrier(` calls of the source tree, as "src/...:line". */
static int source_sites(const char *root, char sites[][128], int max)
{
    char cmd[4200];
    snprintf(cmd, sizeof(cmd),
             "cd '%s' && grep -rn --include='*.c' 'glMemoryBarrier(' src | "
             "grep -v -e '^src/gl/check.c' -e '^src/gl/poison.c' -e '^src/gl/graph_gl.c'",
             root);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    int n = 0;
    char line[1024];
    while (fgets(line, sizeof(line), p)) {
        char *c1 = strchr(line, ':');
        char *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        if (!c2 || n >= max)
            continue;
        *c2 = '\0';
        snprintf(sites[n++], 128, "%.127s", line);
    }
    pclose(p);
    return n;
}

int main(int argc, char **argv)
{
    /* Counting, not aborting: the runs below drop barriers on purpose. */
    gpu = test_gpu_opts(&(dirt_gpu_opts){.sync_debug = true, .check_barriers = true});
    if (!gpu)
        return TEST_SKIP;
    const char *root = argc > 1 ? argv[1] : ".";
    dirt_log_set_callback(on_log, NULL);
    scene = dirt_scene_create_default();
    prog_sample = gl_program_compute("test/sample_texture.comp", NULL, 0);
    CHECK(scene && prog_sample);
    if (!scene || !prog_sample)
        return check_finish();

    workload();
    dirt_gpu_barrier_check clean = dirt_gpu_barrier_counts(gpu);
    CHECK_MSG(clean.on && clean.total == 0, "the workload itself has %llu hazards",
              (unsigned long long)clean.total);
    fprintf(stderr, "workload: %llu commands, %llu barriers checked, no hazard\n",
            (unsigned long long)clean.commands, (unsigned long long)clean.barriers);

    enum { MAX = 128 };
    static gl_barrier_site seen[MAX];
    int nseen = gl_check_barrier_sites(gpu, seen, MAX);
    static char src[MAX][128];
    int nsrc = source_sites(root, src, MAX);
    CHECK_MSG(nsrc > 10, "%d glMemoryBarrier calls found in %s/src", nsrc, root);
    for (int i = 0; i < nsrc; i++) {
        bool hit = false;
        for (int j = 0; j < nseen && !hit; j++)
            hit = !strcmp(seen[j].site, src[i]);
        CHECK_MSG(hit, "the barrier at %s is never called by the workload: give it a case",
                  src[i]);
    }
    int tested = 0;
    for (int j = 0; j < nseen && j < MAX; j++) {
        if (strncmp(seen[j].site, "src/", 4) != 0 || strstr(seen[j].site, "src/gl/graph_gl.c"))
            continue; /* the test's own, and the frame graph's derived ones */
        dirt_gpu_barrier_check before = dirt_gpu_barrier_counts(gpu);
        gl_check_drop_barrier(gpu, seen[j].site);
        quiet = true;
        first_hazard[0] = '\0';
        workload();
        quiet = false;
        uint64_t dropped = gl_check_dropped(gpu);
        gl_check_drop_barrier(gpu, NULL);
        dirt_gpu_barrier_check after = dirt_gpu_barrier_counts(gpu);
        uint64_t found = after.total - before.total;
        fprintf(stderr, "without %s (%llu calls): %llu hazards (%llu RAW, %llu WAW, %llu WAR)\n",
                seen[j].site, (unsigned long long)dropped, (unsigned long long)found,
                (unsigned long long)(after.hazards[0] - before.hazards[0]),
                (unsigned long long)(after.hazards[1] - before.hazards[1]),
                (unsigned long long)(after.hazards[2] - before.hazards[2]));
        if (first_hazard[0])
            fprintf(stderr, "  first: %s\n", first_hazard + 15);
        CHECK_MSG(dropped > 0 && found > 0, "dropping the barrier at %s goes unnoticed",
                  seen[j].site);
        tested++;
    }
    fprintf(stderr, "%d hand-written barrier sites, each needed\n", tested);
    gl_program_destroy(&prog_sample);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    dirt_log_set_callback(NULL, NULL);
    return check_finish();
}
