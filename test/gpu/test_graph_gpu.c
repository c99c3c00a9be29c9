/* Frame graph on a real GL context (llvmpipe in CI): two chains of
 * compute -> compute -> raster -> readback give the pixels the CPU computes;
 * the second chain reuses the first one's memory (aliasing); the graph's own
 * validation passes, and reports a barrier the test hook drops, and so does
 * the barrier checker (src/gl/check.c), which sees the GL calls. A second
 * graph runs attachment-less raster passes doing image atomics at half
 * resolution (the shape of DIRT's build passes). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "dirt/log.h"
#include "gl/program.h"
#include "gpu.h"
#include "gl/graph_gl.h"

enum { W = 37, H = 23 };

static struct {
    GLuint fill, to_image, draw, splat;
} prog;

typedef struct chain {
    fg_res values, image, target;
    uint32_t seed;
    float *pixels;          /* W * H * 4 read back */
} chain;

static char log_text[32768];

/* GL errors, the barrier checker's hazards aside (both count in
 * dirt_gpu_error_count). */
static uint64_t gl_errors(const dirt_gpu *gpu)
{
    return dirt_gpu_error_count(gpu) - dirt_gpu_barrier_counts(gpu).total;
}

/* Hazards of kind k the checker found so far. */
static uint64_t hazards(const dirt_gpu *gpu, enum dirt_gpu_hazard k)
{
    return dirt_gpu_barrier_counts(gpu).hazards[k];
}

/* The log holds a barrier check message with both parts (the call sites'
 * line numbers in between). */
static bool checker_said(const char *a, const char *b)
{
    const char *p = strstr(log_text, a);
    return p && strstr(p, b) != NULL;
}

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user;
    if (level > DIRT_LOG_WARN)
        return;
    fprintf(stderr, "%s: %s:%d: %s\n", level == DIRT_LOG_ERROR ? "error" : "warning",
            file ? file : "-", line, msg);
    size_t len = strlen(log_text);
    snprintf(log_text + len, sizeof(log_text) - len, "%s\n", msg);
}

static bool exec_fill(fg_ctx *ctx, void *user)
{
    chain *c = user;
    int w, h;
    fg_resolution(ctx, &w, &h);
    glUseProgram(prog.fill);
    glUniform1ui(DIRT_LOC_TEST_FILL_COUNT, (GLuint)(w * h));
    glUniform1ui(DIRT_LOC_TEST_FILL_SEED, c->seed);
    glDispatchCompute((GLuint)DIRT_GROUPS(w * h), 1, 1);
    fg_report_used(ctx, c->values, (size_t)w * (size_t)h * 4);
    return true;
}

static bool exec_to_image(fg_ctx *ctx, void *user)
{
    (void)user;
    int w, h;
    fg_resolution(ctx, &w, &h);
    glUseProgram(prog.to_image);
    glUniform2i(DIRT_LOC_TEST_TO_IMAGE_SIZE, w, h);
    glDispatchCompute((GLuint)DIRT_GROUPS_2D(w), (GLuint)DIRT_GROUPS_2D(h), 1);
    return true;
}

static bool exec_draw(fg_ctx *ctx, void *user)
{
    (void)ctx;
    (void)user;
    glUseProgram(prog.draw);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return true;
}

static bool exec_readback(fg_ctx *ctx, void *user)
{
    chain *c = user;
    return fg_gl_read_texture(ctx, c->target, 0, c->pixels, (size_t)W * H * 4 * sizeof(float));
}

static void add_chain(fg_graph *g, chain *c, const char *suffix)
{
    char name[64];
    snprintf(name, sizeof(name), "values_%s", suffix);
    c->values = fg_buffer(g, name, &(fg_buf_desc){.per_pixel = 4});
    snprintf(name, sizeof(name), "image_%s", suffix);
    c->image = fg_texture(g, name, &(fg_tex_desc){.format = FG_R32F});
    snprintf(name, sizeof(name), "target_%s", suffix);
    c->target = fg_texture(g, name, &(fg_tex_desc){.format = FG_RGBA32F});

    snprintf(name, sizeof(name), "fill_%s", suffix);
    fg_pass *fill = fg_add_pass(g, name, FG_COMPUTE, exec_fill, c);
    fg_use(fill, c->values, FG_SSBO_WRITE, &(fg_use_opts){.bind = true, .binding = DIRT_BIND_TEST_OUT});
    snprintf(name, sizeof(name), "to_image_%s", suffix);
    fg_pass *conv = fg_add_pass(g, name, FG_COMPUTE, exec_to_image, c);
    fg_use(conv, c->values, FG_SSBO_READ, &(fg_use_opts){.bind = true, .binding = DIRT_BIND_TEST_IN});
    fg_use(conv, c->image, FG_IMAGE_STORE, &(fg_use_opts){.bind = true, .binding = DIRT_UNIT_TEST});
    snprintf(name, sizeof(name), "draw_%s", suffix);
    fg_pass *draw = fg_add_pass(g, name, FG_RASTER, exec_draw, c);
    fg_use(draw, c->image, FG_SAMPLED, &(fg_use_opts){.bind = true, .binding = DIRT_UNIT_TEST});
    fg_use(draw, c->target, FG_COLOR, &(fg_use_opts){.binding = 0});
    snprintf(name, sizeof(name), "readback_%s", suffix);
    fg_pass *rb = fg_add_pass(g, name, FG_COMPUTE, exec_readback, c);
    fg_read(rb, c->target, FG_TRANSFER_READ);
    fg_keep(rb);
}

typedef struct splat {
    fg_res counts;
    uint32_t add;
    uint32_t *out;
    int width, height;
} splat;

static bool exec_clear(fg_ctx *ctx, void *user)
{
    splat *sp = user;
    return fg_gl_clear(ctx, sp->counts);
}

static bool exec_splat(fg_ctx *ctx, void *user)
{
    (void)ctx;
    splat *sp = user;
    glUseProgram(prog.splat);
    glUniform1ui(DIRT_LOC_TEST_SPLAT_ADD, sp->add);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return true;
}

static bool exec_read_counts(fg_ctx *ctx, void *user)
{
    splat *sp = user;
    fg_texture_size(ctx, sp->counts, &sp->width, &sp->height, NULL, NULL);
    return fg_gl_read_texture(ctx, sp->counts, 0, sp->out, (size_t)W * H * sizeof(uint32_t));
}

/* clear -> splat(+1) -> splat(+2) -> readback on a W/2 x H/2 r32ui image. */
static void test_attachmentless(dirt_gpu *gpu)
{
    uint32_t *out = calloc((size_t)W * H, sizeof(uint32_t));
    splat s1 = {.add = 1, .out = out}, s2 = {.add = 2, .out = out};
    fg_graph *g = gl_graph_create(gpu);
    CHECK(g && out);
    if (!g || !out)
        goto done;
    fg_set_resolution(g, W, H);
    fg_res counts = fg_texture(g, "counts", &(fg_tex_desc){.format = FG_R32UI, .div = 2});
    s1.counts = s2.counts = counts;
    fg_pass *clear = fg_add_pass(g, "clear", FG_COMPUTE, exec_clear, &s1);
    fg_write(clear, counts, FG_TRANSFER_WRITE);
    const fg_tex_desc half = {.div = 2};
    fg_pass *p1 = fg_add_pass(g, "splat1", FG_RASTER, exec_splat, &s1);
    fg_use(p1, counts, FG_IMAGE_ATOMIC, &(fg_use_opts){.bind = true, .binding = DIRT_UNIT_TEST});
    fg_set_raster_size(p1, &half);
    fg_pass *p2 = fg_add_pass(g, "splat2", FG_RASTER, exec_splat, &s2);
    fg_use(p2, counts, FG_IMAGE_ATOMIC, &(fg_use_opts){.bind = true, .binding = DIRT_UNIT_TEST});
    fg_set_raster_size(p2, &half);
    fg_pass *rb = fg_add_pass(g, "read_counts", FG_COMPUTE, exec_read_counts, &s1);
    fg_read(rb, counts, FG_TRANSFER_READ);
    fg_keep(rb);
    CHECK(fg_compile(g));
    CHECK(fg_pass_barrier(g, "splat1") == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "splat2") == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "read_counts") == GL_TEXTURE_UPDATE_BARRIER_BIT);
    /* the readback's TEXTURE_UPDATE already ordered the atomics before the
     * next execute's clear */
    CHECK(fg_pass_barrier(g, "clear") == 0);
    for (int run = 0; run < 2; run++) {
        memset(out, 0xff, (size_t)W * H * sizeof(uint32_t));
        CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
        CHECK(s1.width == (W + 1) / 2 && s1.height == (H + 1) / 2);
        int bad = 0;
        for (int i = 0; i < s1.width * s1.height; i++)
            bad += out[i] != 3;
        CHECK_MSG(bad == 0, "%d of %d pixels are not 3 (first %u)", bad,
                  s1.width * s1.height, out[0]);
    }
    log_text[0] = '\0';
    uint64_t raw = hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE);
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "splat2"}));
    CHECK(strstr(log_text, "pass 'splat2' accesses 'counts' (image atomic) after pass "
                           "'splat1' wrote 'counts' (image atomic) with no "
                           "GL_SHADER_IMAGE_ACCESS_BARRIER_BIT in between") != NULL);
    CHECK(hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE) == raw + 1);
    CHECK(checker_said("barrier check: draw of 'graph test splat'",
                       "in 'splat2' reads texture 'counts' (image load) after draw of 'graph test "
                       "splat' (test/gpu/test_graph_gpu.c:"));
    CHECK(checker_said("in 'splat1' wrote it (image store or atomic) with no "
                       "GL_SHADER_IMAGE_ACCESS_BARRIER_BIT in between", ""));
done:
    fg_destroy(g);
    free(out);
}

/* Counts pixels that differ from the CPU's result for `seed`. */
static int check_pixels(const chain *c)
{
    int bad = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            uint32_t i = (uint32_t)(y * W + x);
            float r = (float)((i * 37u + c->seed) % 1000u) / 1000.0f + 0.25f;
            const float want[4] = {r, r * 2.0f, 1.0f - r, 1.0f};
            const float *got = &c->pixels[i * 4];
            for (int k = 0; k < 4; k++) {
                if (!(fabsf(got[k] - want[k]) <= 1e-6f)) {
                    if (bad < 5)
                        fprintf(stderr, "seed %u pixel (%d,%d)[%d]: got %g want %g\n",
                                c->seed, x, y, k, got[k], want[k]);
                    bad++;
                }
            }
        }
    }
    return bad;
}

int main(void)
{
    /* The barrier checker counts (the test drops barriers on purpose). */
    dirt_gpu *gpu = test_gpu_opts(&(dirt_gpu_opts){.sync_debug = true, .check_barriers = true});
    if (!gpu)
        return TEST_SKIP;
    CHECK(dirt_gpu_barrier_counts(gpu).on);
    dirt_log_set_callback(capture, NULL);
    const char *draw_paths[] = {"graph_test/draw.vert", "graph_test/draw.frag", NULL};
    prog.fill = gl_program_compute("graph_test/fill.comp", NULL, 0);
    prog.to_image = gl_program_compute("graph_test/to_image.comp", NULL, 0);
    prog.draw = gl_program_create("graph test draw", draw_paths, NULL, 0);
    const char *splat_paths[] = {"graph_test/draw.vert", "graph_test/splat.frag", NULL};
    prog.splat = gl_program_create("graph test splat", splat_paths, NULL, 0);
    CHECK(prog.fill && prog.to_image && prog.draw && prog.splat);

    float *pix_a = calloc((size_t)W * H * 4, sizeof(float));
    float *pix_b = calloc((size_t)W * H * 4, sizeof(float));
    chain a = {.seed = 11, .pixels = pix_a}, b = {.seed = 503, .pixels = pix_b};
    fg_graph *g = gl_graph_create(gpu);
    CHECK(g != NULL);
    if (!g || !pix_a || !pix_b || !prog.fill || !prog.to_image || !prog.draw)
        goto done;
    fg_set_resolution(g, W, H);
    add_chain(g, &a, "a");
    add_chain(g, &b, "b");
    CHECK(fg_compile(g));

    /* order and memory: chain b runs after chain a's readback (declaration
     * order) and reuses all three of its allocations */
    CHECK(fg_num_ordered(g) == 8);
    CHECK(fg_position(g, "fill_a") == 0 && fg_position(g, "readback_b") == 7);
    CHECK(fg_num_physical(g) == 3);
    CHECK(fg_physical(g, a.values) == fg_physical(g, b.values));
    CHECK(fg_physical(g, a.image) == fg_physical(g, b.image));
    CHECK(fg_physical(g, a.target) == fg_physical(g, b.target));
    CHECK(fg_pass_barrier(g, "to_image_a") & GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "draw_a") == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "readback_a") == 0);
    /* chain b's fill overwrites memory chain a's to_image read: ordered */
    CHECK(fg_pass_barrier(g, "fill_b") & GL_SHADER_STORAGE_BARRIER_BIT);

    /* validated runs give the right pixels, twice (steady state) */
    fg_exec_opts vopts = {.validate = true};
    for (int run = 0; run < 2; run++) {
        memset(pix_a, 0, (size_t)W * H * 4 * sizeof(float));
        memset(pix_b, 0, (size_t)W * H * 4 * sizeof(float));
        log_text[0] = '\0';
        CHECK(fg_execute(g, &vopts));
        CHECK(strstr(log_text, "validation") == NULL);
        CHECK(check_pixels(&a) == 0);
        CHECK(check_pixels(&b) == 0);
    }
    CHECK(dirt_gpu_error_count(gpu) == 0);
    CHECK(dirt_gpu_barrier_counts(gpu).commands > 0 && dirt_gpu_barrier_counts(gpu).total == 0);

    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    CHECK(s.validation_errors == 0 && s.executions == 2);
    /* every pass timed by the GPU's one clock: the CPU clock on a software
     * renderer (its time queries do not time rasterization), else queries */
    bool software = dirt_gpu_get_caps(gpu)->software;
    enum dirt_clock want = software ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU;
    CHECK(dirt_gpu_clock(gpu) == want);
    double sum = 0;
    for (int i = 0; i < s.num_passes; i++) {
        const fg_pass_stats *p = &s.passes[i];
        CHECK_MSG(p->clock == want && (software ? p->ms > 0 : p->ms >= 0), "pass %s: %g ms, %s",
                  p->name, p->ms, dirt_clock_names[p->clock]);
        sum += p->ms;
    }
    CHECK(s.clock == want);
    CHECK_NEAR(s.ms, sum, 1e-9);
    CHECK(s.resources[0].used_reported && s.resources[0].used_bytes == (size_t)W * H * 4);
    /* aliasing halves the transient memory: 3 allocations for 6 resources */
    const size_t per_chain = (size_t)W * H * (4 + 4 + 16);
    CHECK(s.transient_bytes == 2 * per_chain);
    CHECK(s.allocated_bytes == per_chain);
    fg_print_stats(g, stdout);

    /* the test hook drops derived barriers; the graph's validation (not the
     * pixels, which may come out right by luck) reports them, and so does
     * the barrier checker from the GL calls */
    log_text[0] = '\0';
    uint64_t raw = hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE);
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true,
                                         .debug_drop_barrier = "to_image_a"}));
    CHECK(strstr(log_text, "pass 'to_image_a' accesses 'values_a' (ssbo read) after pass "
                           "'fill_a' wrote 'values_a' (ssbo write) with no "
                           "GL_SHADER_STORAGE_BARRIER_BIT in between") != NULL);
    CHECK(hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE) == raw + 1);
    CHECK(checker_said("barrier check: dispatch of 'graph_test/to_image.comp'",
                       "in 'to_image_a' reads buffer 'values_a+values_b' (storage block read) "
                       "after dispatch of 'graph_test/fill.comp'"));
    CHECK(checker_said("in 'fill_a' wrote it (storage block write) with no "
                       "GL_SHADER_STORAGE_BARRIER_BIT in between", ""));
    log_text[0] = '\0';
    raw = hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE);
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "draw_b"}));
    CHECK(strstr(log_text, "pass 'draw_b' accesses 'image_b' (sampled) after pass "
                           "'to_image_b' wrote 'image_b' (image store) with no "
                           "GL_TEXTURE_FETCH_BARRIER_BIT in between") != NULL);
    CHECK(hazards(gpu, DIRT_GPU_HAZARD_READ_AFTER_WRITE) == raw + 1);
    CHECK(checker_said("in 'draw_b' reads texture 'image_a+image_b' (texture fetch) after "
                       "dispatch of 'graph_test/to_image.comp'",
                       "in 'to_image_b' wrote it (image store or atomic) with no "
                       "GL_TEXTURE_FETCH_BARRIER_BIT in between"));
    log_text[0] = '\0';
    uint64_t war = hazards(gpu, DIRT_GPU_HAZARD_WRITE_AFTER_READ);
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "fill_b"}));
    CHECK(strstr(log_text, "pass 'fill_b' writes 'values_b' (ssbo write) after pass "
                           "'to_image_a' accessed 'values_a' (same memory) (ssbo read) with "
                           "no GL_SHADER_STORAGE_BARRIER_BIT in between") != NULL);
    CHECK(hazards(gpu, DIRT_GPU_HAZARD_WRITE_AFTER_READ) == war + 1);
    CHECK(checker_said("in 'fill_b' writes buffer 'values_a+values_b' (storage block write) "
                       "after dispatch of 'graph_test/to_image.comp'",
                       "in 'to_image_a' accessed it (storage block read) with no "
                       "GL_SHADER_STORAGE_BARRIER_BIT in between: shader write after an access"));
    CHECK(fg_get_stats(g, &s) && s.validation_errors >= 3);

    /* and a normal run afterwards is clean and correct again */
    log_text[0] = '\0';
    CHECK(fg_execute(g, &vopts));
    CHECK(strstr(log_text, "validation") == NULL);
    CHECK(check_pixels(&a) == 0 && check_pixels(&b) == 0);

    /* without aliasing: same pixels, six allocations */
    fg_set_aliasing(g, false);
    CHECK(fg_compile(g));
    CHECK(fg_num_physical(g) == 6);
    CHECK(fg_execute(g, &(fg_exec_opts){.validate = true, .no_timers = true}));
    CHECK(check_pixels(&a) == 0 && check_pixels(&b) == 0);
    CHECK(fg_get_stats(g, &s) && s.clock == DIRT_CLOCK_NONE && s.ms == -1);
    CHECK(gl_errors(gpu) == 0);

    uint64_t total = dirt_gpu_barrier_counts(gpu).total;
    if (prog.splat)
        test_attachmentless(gpu);
    CHECK(gl_errors(gpu) == 0);
    CHECK(dirt_gpu_barrier_counts(gpu).total > total); /* the dropped splat2 barrier */

done:
    fg_destroy(g);
    gl_program_destroy(&prog.fill);
    gl_program_destroy(&prog.to_image);
    gl_program_destroy(&prog.draw);
    gl_program_destroy(&prog.splat);
    free(pix_a);
    free(pix_b);
    dirt_log_set_callback(NULL, NULL);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
