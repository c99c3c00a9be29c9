/* Poisoned memory (dirt_gpu_opts.poison, DIRT_POISON=1): new buffers and
 * textures hold DIRT_GPU_POISON_WORD (a NaN as a float, out of range as an
 * index) in every word or channel, buffers made with data hold the data,
 * and a frame-graph transient reads as poison wherever no pass of the
 * execute wrote it: in a transient that shares the memory of one an earlier
 * pass filled (aliasing), and in the next execute. The same graph on a GPU
 * without poison reads the earlier transient's stale values there: what
 * the poison makes visible. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "gl/graph_gl.h"
#include "gl/program.h"
#include "gpu.h"

enum { N = 1000 }; /* words of each graph buffer */

static GLuint prog_fill;

static dirt_gpu *make_gpu(bool poison)
{
    return test_gpu_opts(&(dirt_gpu_opts){.sync_debug = true, .poison = poison});
}

static uint32_t bits_of(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* New buffers: the word everywhere (and its byte in a size that is no
 * multiple of 4); data given at creation stays. */
static void check_buffers(dirt_gpu *gpu)
{
    size_t size = 4 * 1024 + 3;
    GLuint b = gl_buffer_create(gpu, size, NULL, true, "poison test");
    uint8_t *got = malloc(size);
    CHECK(b && got && gl_buffer_read(b, 0, size, got));
    int bad = 0;
    for (size_t i = 0; got && i + 4 <= size; i += 4) {
        uint32_t w;
        memcpy(&w, got + i, 4);
        bad += w != DIRT_GPU_POISON_WORD;
    }
    for (size_t i = size / 4 * 4; got && i < size; i++)
        bad += got[i] != DIRT_GPU_POISON_UNORM;
    CHECK_MSG(bad == 0, "%d words of a new buffer are not the poison", bad);
    float f;
    memcpy(&f, got, 4);
    CHECK(isnan(f));
    gl_buffer_destroy(&b);
    uint32_t data[64];
    for (int i = 0; i < 64; i++)
        data[i] = (uint32_t)i * 3u;
    b = gl_buffer_create(gpu, sizeof(data), data, true, "poison test data");
    uint32_t back[64];
    CHECK(b && gl_buffer_read(b, 0, sizeof(back), back) && !memcmp(back, data, sizeof(data)));
    gl_buffer_destroy(&b);
    free(got);
}

/* New textures: every level of float (32 and 16 bit), integer, normalized
 * and depth formats, 2D and arrays. */
static void check_textures(void)
{
    GLuint t = gl_texture_2d(GL_RGBA32F, 5, 3, 2, "poison rgba32f");
    float px[5 * 3 * 4];
    glGetTextureImage(t, 1, GL_RGBA, GL_FLOAT, sizeof(px), px); /* level 1: 2x1 */
    CHECK(bits_of(px[0]) == DIRT_GPU_POISON_WORD && bits_of(px[7]) == DIRT_GPU_POISON_WORD);
    gl_texture_destroy(&t);

    t = gl_texture_2d(GL_RG16F, 4, 4, 1, "poison rg16f");
    CHECK(t != 0);
    glGetTextureImage(t, 0, GL_RG, GL_FLOAT, sizeof(px), px);
    int nans = 0;
    for (int i = 0; i < 4 * 4 * 2; i++)
        nans += isnan(px[i]);
    CHECK_MSG(nans == 32, "%d of 32 half-float channels are NaN", nans);
    gl_texture_destroy(&t);

    t = gl_texture_2d_array(GL_R32UI, 3, 2, 4, 1, "poison r32ui array");
    uint32_t u[3 * 2 * 4];
    glGetTextureImage(t, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, sizeof(u), u);
    int bad = 0;
    for (int i = 0; i < 3 * 2 * 4; i++)
        bad += u[i] != DIRT_GPU_POISON_WORD;
    CHECK_MSG(bad == 0, "%d texels of an r32ui array are not the poison", bad);
    gl_texture_destroy(&t);

    t = gl_texture_2d(GL_RGBA8, 2, 2, 1, "poison rgba8");
    uint8_t b8[2 * 2 * 4];
    glGetTextureImage(t, 0, GL_RGBA, GL_UNSIGNED_BYTE, sizeof(b8), b8);
    bad = 0;
    for (int i = 0; i < 16; i++)
        bad += b8[i] != DIRT_GPU_POISON_UNORM;
    CHECK_MSG(bad == 0, "%d channels of an rgba8 texture are not the poison", bad);
    gl_texture_destroy(&t);

    t = gl_texture_2d(GL_DEPTH_COMPONENT32F, 2, 2, 1, "poison depth");
    float d[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    glGetTextureImage(t, 0, GL_DEPTH_COMPONENT, GL_FLOAT, sizeof(d), d);
    CHECK(d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f && d[3] == 0.0f);
    gl_texture_destroy(&t);
    CHECK(gl_check("poisoned textures"));
}

/* The graph: "fill a" writes all N words of transient a, "read a" reads
 * them back; "fill b" writes the first N / 2 words of transient b, which
 * shares a's memory, and "read b" reads all N. */
typedef struct job {
    fg_res res;
    uint32_t count, seed;
    uint32_t *out;
} job;

static bool exec_fill(fg_ctx *ctx, void *user)
{
    (void)ctx;
    job *j = user;
    glUseProgram(prog_fill);
    glUniform1ui(DIRT_LOC_TEST_FILL_COUNT, j->count);
    glUniform1ui(DIRT_LOC_TEST_FILL_SEED, j->seed);
    glDispatchCompute((GLuint)DIRT_GROUPS(j->count), 1, 1);
    glUseProgram(0);
    return true;
}

static bool exec_read(fg_ctx *ctx, void *user)
{
    job *j = user;
    return fg_gl_read_buffer(ctx, j->res, 0, N * 4, j->out);
}

/* Runs the graph twice on `gpu`; *stale counts the words of b's unwritten
 * half equal to a's values there, *poisoned those holding the poison, over
 * both executes. */
static void run_graph(dirt_gpu *gpu, int *stale, int *poisoned)
{
    *stale = *poisoned = 0;
    fg_graph *g = gl_graph_create(gpu);
    CHECK(g != NULL);
    if (!g)
        return;
    static uint32_t out_a[N], out_b[N];
    job a = {.count = N, .seed = 11, .out = out_a}, b = {.count = N / 2, .seed = 500, .out = out_b};
    a.res = fg_buffer(g, "a", &(fg_buf_desc){.bytes = N * 4, .readback = true});
    b.res = fg_buffer(g, "b", &(fg_buf_desc){.bytes = N * 4, .readback = true});
    job *jobs[2] = {&a, &b};
    const char *names[2][2] = {{"fill a", "read a"}, {"fill b", "read b"}};
    for (int k = 0; k < 2; k++) {
        fg_pass *p = fg_add_pass(g, names[k][0], FG_COMPUTE, exec_fill, jobs[k]);
        fg_use(p, jobs[k]->res, FG_SSBO_WRITE,
               &(fg_use_opts){.bind = true, .binding = DIRT_BIND_TEST_OUT});
        p = fg_add_pass(g, names[k][1], FG_COMPUTE, exec_read, jobs[k]);
        fg_read(p, jobs[k]->res, FG_TRANSFER_READ);
        fg_keep(p);
    }
    CHECK(fg_compile(g));
    fg_stats st;
    CHECK(fg_get_stats(g, &st) && st.allocated_bytes == N * 4); /* b shares a's memory */
    for (int e = 0; e < 2; e++) {
        memset(out_a, 0, sizeof(out_a));
        memset(out_b, 0, sizeof(out_b));
        CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
        int wrong = 0;
        for (uint32_t i = 0; i < N; i++)
            wrong += out_a[i] != (i * 37u + a.seed) % 1000u ||
                     (i < N / 2 && out_b[i] != (i * 37u + b.seed) % 1000u);
        CHECK_MSG(wrong == 0, "%d words a pass wrote read back wrong", wrong);
        for (uint32_t i = N / 2; i < N; i++) {
            *stale += out_b[i] == out_a[i];
            *poisoned += out_b[i] == DIRT_GPU_POISON_WORD;
        }
    }
    fg_destroy(g);
}

int main(void)
{
    /* The environment switch. */
    setenv("DIRT_POISON", "1", 1);
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    CHECK(dirt_gpu_poisons(gpu));
    dirt_gpu_destroy(gpu);
    setenv("DIRT_POISON", "0", 1);
    gpu = make_gpu(false);
    CHECK(gpu && !dirt_gpu_poisons(gpu));
    dirt_gpu_destroy(gpu);
    unsetenv("DIRT_POISON");

    gpu = make_gpu(true);
    CHECK(gpu && dirt_gpu_poisons(gpu));
    if (!gpu)
        return check_finish();
    prog_fill = gl_program_compute("graph_test/fill.comp", NULL, 0);
    CHECK(prog_fill != 0);
    check_buffers(gpu);
    check_textures();
    int stale, poisoned;
    run_graph(gpu, &stale, &poisoned);
    CHECK_MSG(poisoned == N && stale == 0,
              "poison on: of b's unwritten half over two executes, %d words hold the poison, "
              "%d a's values (want %d and 0)", poisoned, stale, N);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    gl_program_destroy(&prog_fill);
    dirt_gpu_destroy(gpu);

    /* Without poison the unwritten half silently reads a's values. */
    gpu = make_gpu(false);
    CHECK(gpu != NULL);
    if (!gpu)
        return check_finish();
    prog_fill = gl_program_compute("graph_test/fill.comp", NULL, 0);
    run_graph(gpu, &stale, &poisoned);
    CHECK_MSG(stale == N && poisoned == 0,
              "poison off: %d words of b's unwritten half hold a's values, %d the poison "
              "(want %d and 0)", stale, poisoned, N);
    gl_program_destroy(&prog_fill);
    dirt_gpu_destroy(gpu);
    fprintf(stderr, "poison: new buffers and textures, and the unwritten half of an aliased "
                    "transient, read as the poison; without it, as the stale values\n");
    return check_finish();
}
