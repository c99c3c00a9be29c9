/* Raster preview on the frame graph (llvmpipe): the graph compiles and runs
 * "preview draw" then "preview readback" with no barrier between them; its
 * validation finds no missing barrier over renders of different sizes (the
 * recompile path) and of frames that grow the imported vertex and light
 * buffers (fg_set_import); identical renders give identical pixels, also
 * after a resize and back; the DOT export names both passes. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dirt/log.h"
#include "raster/raster.h"
#include "dirt/scene.h"
#include "gpu.h"

#define W1 64
#define H1 48
#define W2 160
#define H2 120

static char log_text[32768];
static int log_errors;

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user;
    if (level > DIRT_LOG_WARN)
        return;
    fprintf(stderr, "%s: %s:%d: %s\n", level == DIRT_LOG_ERROR ? "error" : "warning",
            file ? file : "-", line, msg);
    if (level == DIRT_LOG_ERROR)
        log_errors++;
    size_t len = strlen(log_text);
    snprintf(log_text + len, sizeof(log_text) - len, "%s\n", msg);
}

/* The stats of every successful render: the two passes in order, no barrier
 * needed (no incoherent shader writes anywhere), clean validation, colour +
 * depth targets of the image's size, both passes timed by the GPU's one
 * clock `clock` (the CPU clock on llvmpipe, where then every time is > 0)
 * and the total their sum. */
static void check_stats(const dirt_raster_stats *st, int w, int h, enum dirt_clock clock)
{
    CHECK(st->num_passes == 2);
    if (st->num_passes != 2)
        return;
    CHECK(strcmp(st->passes[0].name, "preview draw") == 0);
    CHECK(strcmp(st->passes[1].name, "preview readback") == 0);
    CHECK(st->passes[0].barrier == 0 && st->passes[1].barrier == 0);
    CHECK(st->validation_errors == 0);
    CHECK_MSG(st->transient_bytes == (size_t)w * (size_t)h * (16 + 16 + 4),
              "transient %zu bytes at %dx%d", st->transient_bytes, w, h);
    CHECK(st->imported_bytes > 0);
    for (int i = 0; i < 2; i++) {
        const dirt_raster_pass_stats *p = &st->passes[i];
        CHECK_MSG(p->clock == clock && (clock == DIRT_CLOCK_CPU ? p->ms > 0 : p->ms >= 0),
                  "pass %s: %g ms, %s clock", p->name, p->ms, dirt_clock_names[p->clock]);
    }
    CHECK(st->clock == clock);
    CHECK_NEAR(st->ms, st->passes[0].ms + st->passes[1].ms, 1e-9);
}

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = calloc(1, 1 << 20);
    if (text) {
        size_t n = fread(text, 1, (1 << 20) - 1, f);
        text[n] = '\0';
    }
    fclose(f);
    return text;
}

int main(void)
{
    dirt_log_set_callback(capture, NULL);
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    dirt_scene *scene = dirt_scene_create_default();
    CHECK(scene != NULL);
    dirt_frame *f = scene ? dirt_scene_evaluate(scene, 0, NULL) : NULL;
    CHECK(f && f->num_cameras >= 1 && f->num_triangles > 4);
    dirt_raster *r = scene ? dirt_raster_create(gpu, scene) : NULL;
    CHECK(r != NULL);
    float *small = calloc((size_t)W1 * H1 * 4, sizeof(float));
    float *a = calloc((size_t)W2 * H2 * 4, sizeof(float));
    float *b = calloc((size_t)W2 * H2 * 4, sizeof(float));
    float *c = calloc((size_t)W2 * H2 * 4, sizeof(float));
    CHECK(small && a && b && c);
    if (!f || f->num_cameras < 1 || f->num_triangles <= 4 || !r || !small || !a || !b || !c)
        goto done;
    const dirt_camera *cam = &f->cameras[0];
    const char *dot_path = "test_raster_graph.dot";
    enum dirt_clock clock = dirt_gpu_clock(gpu);
    CHECK(clock == (dirt_gpu_get_caps(gpu)->software ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU));

    /* Nothing compiled yet: no DOT (logged). */
    remove(dot_path);
    CHECK(!dirt_raster_write_dot(r, dot_path));
    CHECK(strstr(log_text, "render a frame first") != NULL);
    log_text[0] = '\0';
    log_errors = 0;

    /* 1. A few triangles and no punctual lights at W1 x H1. */
    dirt_frame part = *f;
    part.num_triangles = 4;
    part.num_lights = 0;
    dirt_raster_stats st1, st;
    memset(&st1, 0xff, sizeof(st1));
    CHECK(dirt_raster_render(r, &part, cam, W1, H1, NULL, small, NULL, &st1));
    check_stats(&st1, W1, H1, clock);

    /* 2. The whole frame at W2 x H2: recompile, vertex and light buffers grow
     *    (their imports are repointed). */
    CHECK(dirt_raster_render(r, f, cam, W2, H2, NULL, a, NULL, &st));
    check_stats(&st, W2, H2, clock);
    CHECK(st.num_lights >= 1);
    CHECK_MSG(st.imported_bytes > st1.imported_bytes, "imported %zu then %zu bytes",
              st1.imported_bytes, st.imported_bytes);

    /* 3. Same render again: same pixels. */
    CHECK(dirt_raster_render(r, f, cam, W2, H2, NULL, b, NULL, &st));
    check_stats(&st, W2, H2, clock);
    CHECK(memcmp(a, b, (size_t)W2 * H2 * 4 * sizeof(float)) == 0);

    /* 4. Resize down and back: still clean, still the same pixels. */
    CHECK(dirt_raster_render(r, f, cam, W1, H1, NULL, small, NULL, &st));
    check_stats(&st, W1, H1, clock);
    CHECK(dirt_raster_render(r, f, cam, W2, H2, NULL, c, NULL, &st));
    check_stats(&st, W2, H2, clock);
    CHECK(memcmp(a, c, (size_t)W2 * H2 * 4 * sizeof(float)) == 0);
    size_t lit = 0;
    for (size_t i = 0; i < (size_t)W2 * H2; i++)
        lit += a[i * 4] + a[i * 4 + 1] + a[i * 4 + 2] > 0;
    CHECK_MSG(lit > (size_t)W2 * H2 / 2, "%zu of %d pixels lit", lit, W2 * H2);

    /* 5. DOT of the graph as compiled for the last size. */
    CHECK(dirt_raster_write_dot(r, dot_path));
    char *dot = read_file(dot_path);
    CHECK(dot != NULL);
    if (dot) {
        CHECK(strstr(dot, "digraph") != NULL);
        CHECK(strstr(dot, "preview draw") != NULL);
        CHECK(strstr(dot, "preview readback") != NULL);
        CHECK(strstr(dot, "preview color") != NULL);
        CHECK(strstr(dot, "preview vertices") != NULL);
    }
    free(dot);
    remove(dot_path);

    CHECK_MSG(log_errors == 0, "errors logged:\n%s", log_text);
    CHECK(strstr(log_text, "validation") == NULL);
    CHECK(dirt_gpu_error_count(gpu) == 0);
done:
    free(small);
    free(a);
    free(b);
    free(c);
    dirt_raster_destroy(r);
    dirt_frame_destroy(f);
    dirt_scene_destroy(scene);
    dirt_gpu_destroy(gpu);
    dirt_log_set_callback(NULL, NULL);
    return check_finish();
}
