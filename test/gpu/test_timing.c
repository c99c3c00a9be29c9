/* The one timing rule (dirt_gpu_clock; doc/frame-graph.md, Timing):
 *  - the rule: the CPU clock (glFinish + wall clock) when the GPU was
 *    created with dirt_gpu_opts.cpu_timing, when the renderer is software
 *    (llvmpipe: its time queries do not time rasterization; unless
 *    gpu_timing, for tests) or has no timer queries; else GL_TIME_ELAPSED
 *    queries. Checked on the real context and
 *    on the same context presented as hardware (caps poked through
 *    gl/gl.h), so a rule that ignores cpu_timing fails here on llvmpipe too;
 *  - every figure follows it, nothing re-decides: a gl_timer, a frame-graph
 *    pass and the graph's totals, an ADS build and trace, the path tracer's
 *    passes, the session's stats record; Embree's figures are CPU times;
 *  - a CPU-clock pass covers its work: the GPU is idle when its body starts
 *    (glFinish before), its own work is done when the execute returns
 *    (glFinish after), and its ms spans the body (> 0). The work includes
 *    clears of a large target, which llvmpipe rasterizes on its own threads
 *    after the call returns, so a missing glFinish shows on llvmpipe too. */
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "dirt/ads.h"
#include "dirt/clock.h"
#include "integrator/pathtrace.h"
#include "dirt/session.h"
#include "gl/gl.h"
#include "gl/graph_gl.h"
#include "gl/program.h"
#include "gpu.h"

#define W 32
#define H 32
#define SPIN_GROUPS 256 /* x DIRT_GROUP_SIZE invocations of glsl/test/spin.comp */
#define BIG 2048        /* side of the RGBA32F target the work clears (64 MiB) */

static const char *name_of(enum dirt_clock c)
{
    return (unsigned)c < 3 ? dirt_clock_names[c] : "?";
}

static bool signaled(GLsync s)
{
    GLint status = 0;
    glGetSynciv(s, GL_SYNC_STATUS, 1, NULL, &status);
    return status == GL_SIGNALED;
}

/* The rule as a truth table over the context's inputs (restored after). */
static void check_rule(dirt_gpu *gpu)
{
    dirt_gpu_caps caps = gpu->caps;
    dirt_gpu_opts opts = gpu->opts;
    for (int bits = 0; bits < 16; bits++) {
        gpu->opts.cpu_timing = bits & 1;
        gpu->caps.software = bits & 2;
        gpu->caps.timer_query = !(bits & 4);
        gpu->opts.gpu_timing = bits & 8; /* tests: the queries on a software renderer */
        bool cpu = (bits & 1) || (bits & 4) || ((bits & 2) && !(bits & 8));
        enum dirt_clock want = cpu ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU;
        CHECK_MSG(dirt_gpu_clock(gpu) == want,
                  "cpu_timing %d, software %d, timer queries %d, gpu_timing %d: %s", bits & 1,
                  !!(bits & 2), !(bits & 4), !!(bits & 8), name_of(dirt_gpu_clock(gpu)));
    }
    gpu->caps = caps;
    gpu->opts = opts;
}

/* ---- a frame-graph pass of real work ---- */

typedef struct spin {
    GLuint prog, out;
    GLuint tex, fbo;        /* BIG x BIG target of the clears */
    GLsync before, after;   /* work issued before the execute; the pass's own */
    bool before_done;       /* `before` had signaled when the body started */
    double body_ms;         /* the body's own span (CPU) */
} spin;

/* Compute work (llvmpipe runs it inside glDispatchCompute) and raster work
 * (llvmpipe bins it and rasterizes on other threads after a flush, so it is
 * still in flight when a fence is made). */
static void work(const spin *s)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, s->out);
    glUseProgram(s->prog);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); /* the last spin wrote the same words */
    glDispatchCompute(SPIN_GROUPS, 1, 1);
    glUseProgram(0);
    for (int k = 0; k < 2; k++) {
        const float c[4] = {(float)k, 0.5f, 0.25f, 1};
        glClearNamedFramebufferfv(s->fbo, GL_COLOR, 0, c);
    }
}

static bool exec_spin(fg_ctx *ctx, void *user)
{
    (void)ctx;
    spin *s = user;
    double t0 = dirt_clock_ms();
    s->before_done = s->before && signaled(s->before);
    work(s);
    s->after = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    s->body_ms = dirt_clock_ms() - t0;
    return true;
}

static void check_graph_pass(dirt_gpu *gpu, enum dirt_clock want)
{
    spin s = {.prog = gl_program_compute("test/spin.comp", NULL, 0)};
    size_t bytes = (size_t)SPIN_GROUPS * DIRT_GROUP_SIZE * 4;
    s.out = gl_buffer_create(gpu, bytes, NULL, false, "spin out");
    s.tex = gl_texture_2d(GL_RGBA32F, BIG, BIG, 1, "timing target");
    glCreateFramebuffers(1, &s.fbo);
    glNamedFramebufferTexture(s.fbo, GL_COLOR_ATTACHMENT0, s.tex, 0);
    fg_graph *g = gl_graph_create(gpu);
    CHECK(s.prog && s.out && s.tex && s.fbo && g);
    CHECK(glCheckNamedFramebufferStatus(s.fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    if (!s.prog || !s.out || !s.tex || !g)
        goto done;
    /* Declared: the clears (transfer writes need no barrier, so from the
     * second execute on no glMemoryBarrier, which waits on llvmpipe, runs
     * before the pass). The spin buffer is the body's own, outside the graph. */
    fg_res target = fg_import_texture(g, "timing target", s.tex,
                                      &(fg_tex_desc){.format = FG_RGBA32F, .width = BIG,
                                                     .height = BIG});
    fg_pass *p = fg_add_pass(g, "spin", FG_COMPUTE, exec_spin, &s);
    fg_write(p, target, FG_TRANSFER_WRITE);
    CHECK(fg_compile(g));
    for (int run = 0; run < 2; run++) {
        /* real work in flight before the pass: a CPU-clock pass waits for it
         * before its clock starts */
        work(&s);
        s.before = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        double t0 = dirt_clock_ms();
        CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
        double exec_ms = dirt_clock_ms() - t0;
        bool after_done = s.after && signaled(s.after);
        fg_stats st;
        CHECK(fg_get_stats(g, &st) && st.num_passes == 1);
        const fg_pass_stats *ps = &st.passes[0];
        CHECK_MSG(ps->clock == want && st.clock == want, "graph pass: %s clock, total %s",
                  name_of(ps->clock), name_of(st.clock));
        CHECK(st.ms == ps->ms);
        if (run == 1)
            fprintf(stderr, "spin pass: %.3f ms (%s clock), body %.3f ms, execute %.3f ms\n",
                    ps->ms, name_of(ps->clock), s.body_ms, exec_ms);
        if (want == DIRT_CLOCK_CPU) {
            CHECK_MSG(s.before_done, "the GPU was still busy when the CPU clock started");
            CHECK_MSG(after_done, "the pass's work was not done when its CPU clock stopped");
            CHECK_MSG(ps->ms > 0 && ps->ms >= s.body_ms && ps->ms <= exec_ms,
                      "pass %g ms, body %g ms, execute %g ms", ps->ms, s.body_ms, exec_ms);
        } else {
            CHECK(ps->ms >= 0);
        }
        glDeleteSync(s.before);
        if (s.after)
            glDeleteSync(s.after);
        s.before = s.after = NULL;
    }
    /* timers off: nothing measured, whatever the clock */
    CHECK(fg_execute(g, &(fg_exec_opts){.no_timers = true}));
    fg_stats st;
    CHECK(fg_get_stats(g, &st) && st.clock == DIRT_CLOCK_NONE && st.passes[0].ms == -1);
    if (s.after)
        glDeleteSync(s.after);
done:
    fg_destroy(g);
    if (s.fbo)
        glDeleteFramebuffers(1, &s.fbo);
    gl_texture_destroy(&s.tex);
    gl_buffer_destroy(&s.out);
    gl_program_destroy(&s.prog);
}

/* ---- the techniques and the session ---- */

static void check_gl_timer(dirt_gpu *gpu, enum dirt_clock want)
{
    gl_timer t;
    CHECK(gl_timer_init(&t, gpu, "timing test"));
    CHECK(t.clock == want && t.ms == -1);
    gl_timer_begin(&t);
    glFinish();
    gl_timer_end(&t);
    CHECK(t.clock == want && (want == DIRT_CLOCK_CPU ? t.ms > 0 : t.ms >= 0));
    gl_timer_release(&t);
}

static void check_techniques(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *f,
                             enum dirt_clock want)
{
    bool cpu = want == DIRT_CLOCK_CPU;
    dirt_camera cam;
    dirt_camera_default(f, &cam);
    dirt_ads *ads = dirt_ads_create(gpu, &(dirt_ads_opts){
        .views = {.mode = DIRT_VIEWS_SINGLE, .width = W, .height = H, .tile_size = 2},
        .buckets = 4});
    CHECK(ads && dirt_ads_build(ads, f, &cam));
    if (!ads)
        return;
    const dirt_ads_stats *as = dirt_ads_get_stats(ads);
    CHECK_MSG(as->clock == want, "ads build: %s clock", name_of(as->clock));
    for (int i = 0; i < DIRT_ADS_NUM_PASSES; i++) {
        if (i == DIRT_ADS_PASS_TILES && as->build != DIRT_BUILD_COMPUTE) /* compute's only */
            CHECK_MSG(as->ms[i] == 0, "ads pass %s: %g ms", dirt_ads_pass_names[i], as->ms[i]);
        else
            CHECK_MSG(cpu ? as->ms[i] > 0 : as->ms[i] >= 0, "ads pass %s: %g ms",
                      dirt_ads_pass_names[i], as->ms[i]);
    }

    dirt_ray ray = {.org = {cam.eye[0], cam.eye[1], cam.eye[2]},
                    .dir = {cam.forward[0], cam.forward[1], cam.forward[2]}, .tmax = 1e30f};
    dirt_hit hit;
    dirt_trace_stats ts;
    CHECK(dirt_ads_trace(ads, &ray, 1, &hit, NULL, &ts));
    CHECK_MSG(ts.clock == want && (cpu ? ts.ms > 0 : ts.ms >= 0), "ads trace: %g ms, %s",
              ts.ms, name_of(ts.clock));

    dirt_pt *pt = dirt_pt_create(gpu, scene);
    dirt_image *img = dirt_image_create(W, H);
    dirt_pt_stats ps;
    CHECK(pt && img &&
          dirt_pt_render(pt, dirt_ads_tracer(ads, NULL), f, &cam,
                         &(dirt_pt_opts){.spp = 1, .bounces = 1, .bounces_set = true}, img, &ps));
    CHECK_MSG(ps.clock == want, "path tracer: %s clock", name_of(ps.clock));
    CHECK_MSG(cpu ? ps.pass_ms[DIRT_PT_PASS_TRACE] > 0 && ps.pass_ms[DIRT_PT_PASS_SHADE] > 0
                  : ps.pass_ms[DIRT_PT_PASS_TRACE] >= 0,
              "trace %g ms, shade %g ms", ps.pass_ms[DIRT_PT_PASS_TRACE],
              ps.pass_ms[DIRT_PT_PASS_SHADE]);
    dirt_image_destroy(img);
    dirt_pt_destroy(pt);
    dirt_ads_destroy(ads);
}

/* Every pass of the session's stats record carries `want` (GPU engines) or
 * the CPU clock (Embree, CPU work), with a time of its own. */
static void check_session(dirt_gpu *gpu, const dirt_scene *scene, enum dirt_engine engine,
                          enum dirt_clock want)
{
    dirt_session_opts o = {.engine = engine, .width = W, .height = H,
                           .views = DIRT_SESSION_VIEWS_SINGLE, .bounces = 1, .threads = 2};
    dirt_session *s = dirt_session_create(gpu, scene, &o);
    CHECK(s && dirt_session_add_samples(s, 1, NULL, NULL));
    if (!s)
        return;
    const dirt_session_stats *st = dirt_session_get_stats(s);
    CHECK(st->num_passes > 0);
    for (int i = 0; i < st->num_passes; i++) {
        const dirt_pass_time *p = &st->passes[i];
        CHECK_MSG(p->clock == want && p->ms >= 0, "%s session, pass %s: %g ms, %s clock",
                  dirt_engine_names[engine], p->name, p->ms, name_of(p->clock));
    }
    dirt_session_destroy(s);
}

static void check_figures(dirt_gpu *gpu, const dirt_scene *scene, const dirt_frame *f,
                          enum dirt_clock want)
{
    CHECK(dirt_gpu_clock(gpu) == want);
    check_gl_timer(gpu, want);
    check_graph_pass(gpu, want);
    check_techniques(gpu, scene, f, want);
    check_session(gpu, scene, DIRT_ENGINE_DIRT, want);
    CHECK(dirt_gpu_error_count(gpu) == 0);
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    dirt_frame *f = scene ? dirt_scene_evaluate(scene, 0, NULL) : NULL;
    CHECK(scene && f);
    if (!f)
        return check_finish();
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    bool software = c->software;
    fprintf(stderr, "%s: default clock %s\n", c->renderer, name_of(dirt_gpu_clock(gpu)));
    check_rule(gpu);

    /* 1. As created (zero options): llvmpipe is software, so the CPU clock. */
    enum dirt_clock natural = software || !c->timer_query ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU;
    CHECK(!software || natural == DIRT_CLOCK_CPU);
    check_figures(gpu, scene, f, natural);
    check_session(NULL, scene, DIRT_ENGINE_EMBREE, DIRT_CLOCK_CPU);

    /* 2. Presented as hardware with timer queries: the query clock, read
     *    through the same code (llvmpipe's queries give some ms >= 0). */
    dirt_gpu_caps real = gpu->caps;
    gpu->caps.software = false;
    gpu->caps.timer_query = true;
    check_figures(gpu, scene, f, DIRT_CLOCK_GPU);
    gpu->caps = real;
    dirt_gpu_destroy(gpu);

    /* 3. Created with cpu_timing: the CPU clock, also where the queries
     *    would time the work (presented as hardware again). */
    gpu = dirt_gpu_create(&(dirt_gpu_opts){.cpu_timing = true});
    CHECK(gpu != NULL);
    if (gpu) {
        CHECK(dirt_gpu_clock(gpu) == DIRT_CLOCK_CPU);
        check_figures(gpu, scene, f, DIRT_CLOCK_CPU);
        gpu->caps.software = false;
        gpu->caps.timer_query = true;
        check_figures(gpu, scene, f, DIRT_CLOCK_CPU);
        dirt_gpu_destroy(gpu);
    }
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    return check_finish();
}
