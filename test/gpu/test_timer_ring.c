/* Timing that never stalls (issue 16, item 4; gl/gl.h, gl_timer): with the
 * GPU clock every timer owns a ring of time queries, an asynchronous end
 * harvests only results that have arrived, and the frame graph's
 * asynchronous timers (the path tracer's) report late times that a drain at
 * the readback completes. On llvmpipe the GPU clock is forced
 * (dirt_gpu_opts.gpu_timing: its GL_TIME_ELAPSED works, it only does not
 * time rasterization). Checked, by the GPU's query counts
 * (dirt_gpu_queries):
 *  - the rule: gpu_timing gives the GPU clock on a software renderer,
 *    cpu_timing still wins;
 *  - gl_timer: a blocking end waits (counted), asynchronous ends never wait
 *    (only a begin that finds the ring full may, and counts it), nothing is
 *    ever more than GL_TIMER_RING in flight, a drain leaves nothing in flight
 *    and reports every result once (the times add up to the blocking
 *    reads'), a discard reports none;
 *  - the frame graph: an asynchronous execute issues no wait, a blocking one
 *    one per pass; fg_drain_timers gives every pass's rest;
 *  - the path tracer (dirt_pt) and the session (DIRT and MMRT engines, 1 and
 *    4 bounces): dirt_pt_add_samples / dirt_session_add_samples of several
 *    samples issue ZERO query-result waits; after dirt_pt_read /
 *    dirt_session_image every query issued has been harvested, and every
 *    pass's total has the GPU clock, is >= 0 and >= what add_samples gave;
 *    the blocking paths (the build graphs, dirt_ads_trace) still count. */
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "dirt/ads.h"
#include "integrator/pathtrace.h"
#include "dirt/session.h"
#include "gl/gl.h"
#include "gl/graph_gl.h"
#include "gl/program.h"
#include "gpu.h"

#define W 32
#define H 32
#define SAMPLES 5 /* per add_samples call */

static dirt_gpu_query_counts counts(const dirt_gpu *gpu)
{
    return dirt_gpu_queries(gpu);
}

/* Queries ended whose result nobody read yet. */
static uint64_t in_flight(const dirt_gpu *gpu)
{
    dirt_gpu_query_counts c = counts(gpu);
    return c.issued - c.harvested - c.dropped;
}

/* Real work to time: a compute dispatch of glsl/test/spin.comp. */
typedef struct work {
    GLuint prog, out;
    GLuint tex, fbo; /* BIG x BIG target of the clears */
} work;

#define BIG 2048 /* RGBA32F: 64 MiB */

static void run_work(const work *w)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, w->out);
    glUseProgram(w->prog);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); /* the last run wrote the same words */
    glDispatchCompute(64, 1, 1);
    glUseProgram(0);
}

/* ---- the rule ---- */

static void check_rule(void)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.gpu_timing = true, .cpu_timing = true,
                                                     .sync_debug = true});
    CHECK(gpu != NULL);
    if (!gpu)
        return;
    CHECK(dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU); /* cpu_timing wins */
    gpu->opts.cpu_timing = false;
    CHECK(dirt_gpu_clock(gpu) == DIRT_CLOCK_GPU);
    gpu->caps.timer_query = false;
    CHECK(dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU);
    gpu->caps.timer_query = true;
    gpu->opts.gpu_timing = false;
    CHECK(dirt_gpu_clock(gpu) == (gpu->caps.software ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU));
    dirt_gpu_destroy(gpu);
}

/* ---- gl_timer ---- */

static void check_timer(dirt_gpu *gpu, const work *w)
{
    gl_timer t;
    CHECK(gl_timer_init(&t, gpu, "ring test"));
    CHECK(t.clock == DIRT_CLOCK_GPU);

    /* blocking: one region, one wait, its own time */
    dirt_gpu_query_counts c0 = counts(gpu);
    double blocking_ms = 0;
    for (int i = 0; i < 4; i++) {
        gl_timer_begin(&t);
        run_work(w);
        gl_timer_end(&t);
        CHECK(t.ms >= 0 && gl_timer_pending(&t) == 0);
        blocking_ms += t.ms;
    }
    dirt_gpu_query_counts c1 = counts(gpu);
    CHECK_MSG(c1.waits - c0.waits == 4 && c1.issued - c0.issued == 4 &&
              c1.harvested - c0.harvested == 4,
              "4 blocking ends: %llu waits, %llu issued, %llu harvested",
              (unsigned long long)(c1.waits - c0.waits),
              (unsigned long long)(c1.issued - c0.issued),
              (unsigned long long)(c1.harvested - c0.harvested));

    /* asynchronous: no end waits; at most the ring in flight */
    const int n = 3 * GL_TIMER_RING;
    double async_ms = 0;
    int max_pending = 0;
    for (int i = 0; i < n; i++) {
        gl_timer_begin(&t);
        run_work(w);
        gl_timer_end_async(&t);
        CHECK(t.ms >= 0);
        async_ms += t.ms;
        if (gl_timer_pending(&t) > max_pending)
            max_pending = gl_timer_pending(&t);
    }
    dirt_gpu_query_counts c2 = counts(gpu);
    CHECK_MSG(c2.waits - c1.waits <= c2.ring_waits - c1.ring_waits,
              "%d asynchronous ends: %llu waits, %llu of them by a full ring", n,
              (unsigned long long)(c2.waits - c1.waits),
              (unsigned long long)(c2.ring_waits - c1.ring_waits));
    CHECK(max_pending <= GL_TIMER_RING);
    CHECK(c2.issued - c1.issued == (uint64_t)n);
    fprintf(stderr, "gl_timer: %d asynchronous ends, at most %d in flight, %llu full-ring "
                    "waits; %g ms reported before the drain\n", n, max_pending,
            (unsigned long long)(c2.ring_waits - c1.ring_waits), async_ms);
    int pending = gl_timer_pending(&t);
    double late = -1;
    CHECK(gl_timer_drain(&t, &late) == pending);
    CHECK(late >= 0 && gl_timer_pending(&t) == 0 && in_flight(gpu) == 0);
    async_ms += late;
    /* every region reported once: n regions of the same work time about
     * n/4 blocking ones (loose: llvmpipe's clock is the CPU's) */
    fprintf(stderr, "gl_timer: async %g ms for %d regions, blocking %g ms for 4\n",
            async_ms, n, blocking_ms);
    CHECK(async_ms > 0);

    /* a full ring: regions whose results cannot have arrived by the next
     * end (clears of a large target, which llvmpipe rasterizes on its own
     * threads after the flush that asking for availability makes): the
     * ring fills, the next begin reads its oldest result first (counted as
     * a ring wait, and as a wait when that result had not arrived yet),
     * whose time the next end reports; nothing is lost */
    c0 = counts(gpu);
    int full = 0; /* begins that found the ring full */
    for (int i = 0; i < GL_TIMER_RING + 4; i++) {
        full += gl_timer_pending(&t) == GL_TIMER_RING;
        gl_timer_begin(&t);
        CHECK(gl_timer_pending(&t) < GL_TIMER_RING);
        for (int k = 0; k < 2; k++) {
            const float color[4] = {(float)k, 0.5f, 0.25f, 1};
            glClearNamedFramebufferfv(w->fbo, GL_COLOR, 0, color);
        }
        gl_timer_end_async(&t);
        CHECK(gl_timer_pending(&t) <= GL_TIMER_RING && t.ms >= 0);
    }
    c1 = counts(gpu);
    fprintf(stderr, "gl_timer: clears: ring full at %d begins, %llu ring waits, %llu waits\n",
            full, (unsigned long long)(c1.ring_waits - c0.ring_waits),
            (unsigned long long)(c1.waits - c0.waits));
    CHECK(c1.ring_waits - c0.ring_waits == (uint64_t)full);
    CHECK(c1.waits - c0.waits <= (uint64_t)full);
    /* llvmpipe is slow enough at this that the ring fills (a fast GPU may
     * keep up: then nothing waits at all) */
    CHECK(!dirt_gpu_get_caps(gpu)->software || full > 0);
    pending = gl_timer_pending(&t);
    CHECK(gl_timer_drain(&t, &late) == pending && late >= 0);
    CHECK(in_flight(gpu) == 0);

    /* discard: nothing in flight is reported afterwards */
    gl_timer_discard(&t);
    CHECK(gl_timer_drain(&t, &late) == 0 && late == 0 && gl_timer_pending(&t) == 0);
    gl_timer_begin(&t);
    run_work(w);
    gl_timer_end(&t);
    CHECK(t.ms >= 0);

    /* a timer released in flight drops its queries (counted) */
    gl_timer_begin(&t);
    run_work(w);
    gl_timer_end_async(&t);
    pending = gl_timer_pending(&t);
    dirt_gpu_query_counts c3 = counts(gpu);
    gl_timer_release(&t);
    CHECK(counts(gpu).dropped - c3.dropped == (uint64_t)pending && in_flight(gpu) == 0);
}

/* ---- the frame graph ---- */

static bool exec_work(fg_ctx *ctx, void *user)
{
    (void)ctx;
    run_work(user);
    return true;
}

static void check_graph(dirt_gpu *gpu, work *w)
{
    fg_graph *g = gl_graph_create(gpu);
    CHECK(g != NULL);
    if (!g)
        return;
    GLuint buf = gl_buffer_create(gpu, 256, NULL, false, "ring graph out");
    fg_res out = fg_import_buffer(g, "out", buf, 256);
    const int passes = 3;
    for (int i = 0; i < passes; i++) {
        char name[16];
        snprintf(name, sizeof(name), "work %d", i);
        fg_pass *p = fg_add_pass(g, name, FG_COMPUTE, exec_work, w);
        fg_use(p, out, FG_SSBO_READ, NULL);
        fg_write(p, out, FG_SSBO_WRITE);
    }
    CHECK(fg_compile(g));
    double sum[3] = {0};
    dirt_gpu_query_counts c0 = counts(gpu);
    for (int run = 0; run < 6; run++) {
        CHECK(fg_execute(g, &(fg_exec_opts){.validate = true, .async_timers = true}));
        fg_stats st;
        CHECK(fg_get_stats(g, &st) && st.clock == DIRT_CLOCK_GPU && st.ms >= 0);
        for (int i = 0; i < passes; i++) {
            CHECK(st.passes[i].clock == DIRT_CLOCK_GPU && st.passes[i].ms >= 0);
            sum[i] += st.passes[i].ms;
        }
    }
    dirt_gpu_query_counts c1 = counts(gpu);
    CHECK_MSG(c1.waits == c0.waits, "asynchronous executes: %llu waits",
              (unsigned long long)(c1.waits - c0.waits));
    CHECK(c1.issued - c0.issued == 6 * passes);
    double late[3];
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    CHECK(fg_drain_timers(g, late, passes, &clock));
    CHECK(in_flight(gpu) == 0);
    CHECK(clock == DIRT_CLOCK_GPU || c1.harvested - c0.harvested == 6 * passes);
    for (int i = 0; i < passes; i++)
        CHECK(late[i] >= 0 && sum[i] + late[i] > 0);
    /* drained: nothing more */
    CHECK(fg_drain_timers(g, late, passes, &clock) && clock == DIRT_CLOCK_NONE);
    /* blocking executes still wait, once per pass */
    c1 = counts(gpu);
    CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
    dirt_gpu_query_counts c2 = counts(gpu);
    CHECK_MSG(c2.waits - c1.waits == (uint64_t)passes, "blocking execute: %llu waits",
              (unsigned long long)(c2.waits - c1.waits));
    /* discard: an execute's late times are not reported by a drain */
    CHECK(fg_execute(g, &(fg_exec_opts){.async_timers = true}));
    fg_discard_timers(g);
    CHECK(fg_drain_timers(g, late, passes, &clock) && clock == DIRT_CLOCK_NONE);
    CHECK(in_flight(gpu) == 0);
    fg_destroy(g);
    gl_buffer_destroy(&buf);
}

/* ---- the path tracer and the session ---- */

static const char *clock_name(enum dirt_clock c)
{
    return (unsigned)c < 3 ? dirt_clock_names[c] : "?";
}

static void check_pt(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *f, int bounces)
{
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    dirt_ads *ads = dirt_ads_create(gpu, &(dirt_ads_opts){
        .views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H, .tile_size = 2},
        .buckets = 4});
    dirt_gpu_query_counts c0 = counts(gpu);
    CHECK(ads && dirt_ads_build(ads, f, &cam));
    if (!ads)
        return;
    /* the build graph blocks (once per frame): its waits still count */
    dirt_gpu_query_counts c1 = counts(gpu);
    CHECK_MSG(c1.waits > c0.waits, "the ADS build waited %llu times",
              (unsigned long long)(c1.waits - c0.waits));
    /* so does dirt_ads_trace's own timer */
    dirt_ray ray = {.org = {cam.eye[0], cam.eye[1], cam.eye[2]},
                    .dir = {cam.forward[0], cam.forward[1], cam.forward[2]}, .tmax = 1e30f};
    dirt_hit hit;
    dirt_trace_stats ts;
    CHECK(dirt_ads_trace(ads, &ray, 1, &hit, NULL, &ts));
    CHECK(ts.clock == DIRT_CLOCK_GPU && ts.ms >= 0);
    dirt_gpu_query_counts c2 = counts(gpu);
    CHECK(c2.waits - c1.waits == 1);

    dirt_pt *pt = dirt_pt_create(gpu, scene);
    dirt_image *img = dirt_image_create(W, H);
    CHECK(pt && img && dirt_pt_reset(pt, W, H));
    dirt_pt_opts po = {.bounces = bounces, .bounces_set = true};
    const dirt_tracer *tr = dirt_ads_tracer(ads, NULL);
    double sum[DIRT_PT_NUM_PASSES] = {0};
    for (int call = 0; pt && img && call < 2; call++) {
        dirt_gpu_query_counts b = counts(gpu);
        dirt_pt_stats ps;
        CHECK(dirt_pt_add_samples(pt, tr, f, &cam, &po, SAMPLES, &ps));
        dirt_gpu_query_counts a = counts(gpu);
        CHECK_MSG(a.waits == b.waits && a.ring_waits == b.ring_waits,
                  "dirt_pt_add_samples of %d samples, %d bounces: %llu query-result waits "
                  "(%llu by a full ring), %llu queries", SAMPLES, bounces,
                  (unsigned long long)(a.waits - b.waits),
                  (unsigned long long)(a.ring_waits - b.ring_waits),
                  (unsigned long long)(a.issued - b.issued));
        CHECK(a.issued > b.issued);
        CHECK(ps.clock == DIRT_CLOCK_GPU);
        for (int i = 0; i < DIRT_PT_NUM_PASSES; i++) {
            CHECK(ps.pass_ms[i] >= 0);
            sum[i] += ps.pass_ms[i];
        }
    }
    if (pt && img) {
        uint64_t pending = in_flight(gpu);
        CHECK(dirt_pt_read(pt, img, NULL));
        CHECK_MSG(in_flight(gpu) == 0, "%llu queries still in flight after dirt_pt_read",
                  (unsigned long long)in_flight(gpu));
        dirt_pt_stats late;
        dirt_pt_take_late_times(pt, false, &late);
        CHECK(pending == 0 || late.clock == DIRT_CLOCK_GPU);
        fprintf(stderr, "dirt_pt, %d bounces: %llu queries in flight before the readback; "
                        "late trace %g ms of %g\n", bounces, (unsigned long long)pending,
                late.pass_ms[DIRT_PT_PASS_TRACE],
                sum[DIRT_PT_PASS_TRACE] + late.pass_ms[DIRT_PT_PASS_TRACE]);
        for (int i = 0; i < DIRT_PT_NUM_PASSES; i++)
            CHECK(late.pass_ms[i] >= 0);
        CHECK(sum[DIRT_PT_PASS_TRACE] + late.pass_ms[DIRT_PT_PASS_TRACE] > 0);
        /* given once */
        dirt_pt_take_late_times(pt, true, &late);
        CHECK(late.clock == DIRT_CLOCK_NONE && late.trace_ms == 0);
    }
    /* dirt_pt_render's figures include the late times: nothing in flight */
    dirt_pt_stats rs;
    CHECK(pt && img && dirt_pt_render(pt, tr, f, &cam, &po, img, &rs));
    CHECK(in_flight(gpu) == 0 && rs.clock == DIRT_CLOCK_GPU && rs.trace_ms > 0);
    dirt_image_destroy(img);
    dirt_pt_destroy(pt);
    dirt_ads_destroy(ads);
}

static void check_session(dirt_gpu *gpu, const dirt_scene *scene, enum dirt_engine engine,
                          int bounces)
{
    dirt_session_opts o = {.engine = engine, .width = W, .height = H,
                           .views = DIRT_SESSION_VIEWS_SINGLE, .bounces = bounces};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s != NULL);
    if (!s)
        return;
    const char *en = dirt_engine_names[engine];
    dirt_gpu_query_counts c0 = counts(gpu);
    CHECK(dirt_session_build(s));
    dirt_gpu_query_counts c1 = counts(gpu);
    CHECK_MSG(c1.waits > c0.waits, "%s build: %llu waits (blocking timers)", en,
              (unsigned long long)(c1.waits - c0.waits));
    dirt_session_stats before;
    for (int call = 0; call < 2; call++) {
        dirt_gpu_query_counts b = counts(gpu);
        CHECK(dirt_session_add_samples(s, SAMPLES, NULL, NULL));
        dirt_gpu_query_counts a = counts(gpu);
        CHECK_MSG(a.waits == b.waits && a.ring_waits == b.ring_waits,
                  "%s session, %d bounces: add_samples of %d samples made %llu query-result "
                  "waits (%llu by a full ring) for %llu queries", en, bounces, SAMPLES,
                  (unsigned long long)(a.waits - b.waits),
                  (unsigned long long)(a.ring_waits - b.ring_waits),
                  (unsigned long long)(a.issued - b.issued));
        CHECK(a.issued > b.issued);
    }
    before = *dirt_session_get_stats(s);
    uint64_t pending = in_flight(gpu);
    CHECK(dirt_session_image(s) != NULL);
    CHECK_MSG(in_flight(gpu) == 0, "%s session: %llu queries not harvested after the image",
              en, (unsigned long long)in_flight(gpu));
    const dirt_session_stats *st = dirt_session_get_stats(s);
    CHECK(st->num_passes == before.num_passes && st->num_passes > 0);
    double late = 0;
    for (int i = 0; i < st->num_passes; i++) {
        const dirt_pass_time *p = &st->passes[i];
        CHECK_MSG(p->clock == DIRT_CLOCK_GPU && p->ms >= 0 && p->ms >= before.passes[i].ms,
                  "%s session, pass %s: %g ms (%g before the image), %s clock", en, p->name,
                  p->ms, before.passes[i].ms, clock_name(p->clock));
        late += p->ms - before.passes[i].ms;
    }
    CHECK_MSG(pending == 0 || late > 0, "%s session: %llu queries in flight, %g ms late", en,
              (unsigned long long)pending, late);
    CHECK(st->trace_ms >= before.trace_ms && st->shade_ms >= before.shade_ms);
    CHECK(st->trace_ms > 0);
    fprintf(stderr, "%s session, %d bounces: %llu queries in flight before the image, "
                    "%g ms late\n", en, bounces, (unsigned long long)pending, late);
    /* read again: nothing more to add */
    dirt_session_drain_times(s);
    CHECK(dirt_session_get_stats(s)->trace_ms == st->trace_ms);
    dirt_session_destroy(s);
}

int main(void)
{
    dirt_gpu *probe = test_gpu();
    if (!probe)
        return TEST_SKIP;
    bool queries = dirt_gpu_get_caps(probe)->timer_query;
    dirt_gpu_destroy(probe);
    if (!queries) {
        fprintf(stderr, "no GL timer queries: skipping\n");
        return TEST_SKIP;
    }
    check_rule();
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.gpu_timing = true, .sync_debug = true});
    CHECK(gpu && dirt_gpu_clock(gpu) == DIRT_CLOCK_GPU);
    if (!gpu)
        return check_finish();
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = scene ? dirt_scene_evaluate(scene, 0, NULL) : NULL;
    work w = {.prog = gl_program_compute("test/spin.comp", NULL, 0)};
    w.out = gl_buffer_create(gpu, 64 * DIRT_GROUP_SIZE * 4, NULL, false, "ring work");
    w.tex = gl_texture_2d(GL_RGBA32F, BIG, BIG, 1, "ring clears");
    glCreateFramebuffers(1, &w.fbo);
    glNamedFramebufferTexture(w.fbo, GL_COLOR_ATTACHMENT0, w.tex, 0);
    CHECK(scene && f && w.prog && w.out && w.tex &&
          glCheckNamedFramebufferStatus(w.fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    if (f && w.prog && w.out) {
        check_timer(gpu, &w);
        check_graph(gpu, &w);
        for (int b = 1; b <= 4; b += 3) {
            check_pt(gpu, scene, f, b);
            check_session(gpu, scene, DIRT_ENGINE_DIRT, b);
        }
        check_session(gpu, scene, DIRT_ENGINE_MMRT, 1);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    glDeleteFramebuffers(1, &w.fbo);
    gl_texture_destroy(&w.tex);
    gl_buffer_destroy(&w.out);
    gl_program_destroy(&w.prog);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
