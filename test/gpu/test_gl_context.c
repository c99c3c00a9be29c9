/* The GL layer: a 4.5 core context headless, the capability probe agrees
 * with the driver, GL errors reach the engine log through debug output,
 * labels stick, timers measure, programs compile from glsl/ with defines and
 * report compile errors. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gpu.h"

static int logged_gl_errors;

static void on_log(void *user, enum dirt_log_level level, const char *file, int line,
                   const char *msg)
{
    (void)user, (void)file, (void)line;
    if (level <= DIRT_LOG_WARN && strstr(msg, "GL "))
        logged_gl_errors++;
    fprintf(stderr, "[log %d] %s\n", level, msg);
}

/* The EGL platform choice: surfaceless and device give what they name, the
 * DIRT_GPU environment chooses when the options say auto, auto prefers a
 * hardware device over Mesa (on a machine with only llvmpipe: surfaceless). */
static void check_platforms(const dirt_gpu_caps *first)
{
    static const struct { enum dirt_gpu_platform p; const char *env, *want; } cases[] = {
        {DIRT_GPU_PLATFORM_SURFACELESS, NULL, "egl-surfaceless"},
        {DIRT_GPU_PLATFORM_DEVICE, NULL, "egl-device"},
        {DIRT_GPU_PLATFORM_AUTO, "device", "egl-device"},
        {DIRT_GPU_PLATFORM_AUTO, "surfaceless", "egl-surfaceless"},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        if (cases[i].env)
            setenv("DIRT_GPU", cases[i].env, 1);
        dirt_gpu *g = dirt_gpu_create(&(dirt_gpu_opts){.platform = cases[i].p, .sync_debug = true});
        unsetenv("DIRT_GPU");
        CHECK_MSG(g != NULL, "no context on the %s platform", cases[i].want);
        if (!g)
            continue;
        const dirt_gpu_caps *c = dirt_gpu_get_caps(g);
        CHECK_MSG(!strncmp(c->platform, cases[i].want, strlen(cases[i].want)),
                  "asked for %s, got %s", cases[i].want, c->platform);
        dirt_gpu_destroy(g);
    }
    /* auto: a hardware device when there is one, else not the software device. */
    bool hw = !first->software;
    CHECK_MSG(hw ? !strcmp(first->platform, "egl-device") : !strcmp(first->platform, "egl-surfaceless"),
              "auto gave %s on %s", first->platform, first->renderer);
    setenv("DIRT_GPU", "nonsense", 1);
    CHECK(dirt_gpu_create(&(dirt_gpu_opts){0}) == NULL);
    unsetenv("DIRT_GPU");
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    CHECK(c->gl_major * 10 + c->gl_minor >= 45);
    CHECK(c->renderer[0] != '\0');
    CHECK(c->platform && strncmp(c->platform, "egl-", 4) == 0);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    CHECK(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    CHECK(c->max_ssbo_size > 0);

    /* The probe's conservative-raster answer equals the extension list's. */
    bool listed = false;
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++)
        listed |= strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i),
                         "GL_NV_conservative_raster") == 0;
    CHECK(c->nv_conservative_raster == listed);
    if (strstr(c->renderer, "llvmpipe"))
        CHECK(c->software && !c->nv_conservative_raster);

    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    CHECK(strstr(desc, c->renderer) != NULL);
    CHECK(strstr(desc, "conservative raster") != NULL);

    /* A deliberate GL error goes through debug output into the log. */
    dirt_log_set_callback(on_log, NULL);
    uint64_t before = dirt_gpu_error_count(gpu);
    glEnable(0xDEAD); /* GL_INVALID_ENUM */
    CHECK(dirt_gpu_error_count(gpu) == before + 1);
    CHECK(logged_gl_errors == 1);
    CHECK(!gl_check("expected error drained") || true);
    dirt_log_set_callback(NULL, NULL);

    /* Labels. */
    GLuint buf = gl_buffer_create(gpu, 256, NULL, true, "test buffer");
    CHECK(buf != 0);
    char label[64] = {0};
    glGetObjectLabel(GL_BUFFER, buf, sizeof(label), NULL, label);
    CHECK(strcmp(label, "test buffer") == 0);

    /* An oversized buffer is refused with a clear error, not a GL crash. */
    GLuint huge = gl_buffer_create(gpu, (size_t)c->max_ssbo_size + 1, NULL, false, "huge");
    CHECK(huge == 0);

    /* Compute program from glsl/ with an injected define writes the value. */
    glsl_define def[] = {{"TEST_VALUE", "1234u"}};
    GLuint prog = gl_program_compute("test/write_value.comp", def, 1);
    CHECK(prog != 0);
    if (prog) {
        gl_timer t;
        CHECK(gl_timer_init(&t, gpu, "test timer"));
        CHECK(t.ms == -1 && t.clock == dirt_gpu_clock(gpu));
        glUseProgram(prog);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, buf);
        gl_timer_begin(&t);
        glDispatchCompute(1, 1, 1);
        gl_timer_end(&t);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        uint32_t out[4] = {0};
        CHECK(gl_buffer_read(buf, 0, sizeof(out), out));
        CHECK(out[0] == 1234u && out[1] == 1235u);
        /* one clock: the CPU one on a software renderer (its time queries
         * do not time the work), else the GPU's time query */
        CHECK(t.clock == (c->software ? DIRT_CLOCK_CPU : DIRT_CLOCK_GPU));
        CHECK(c->software ? t.ms > 0 : t.ms >= 0);
        gl_timer_release(&t);
        gl_program_destroy(&prog);
    }
    /* Without the define the shader does not compile: reported, 0 returned. */
    CHECK(gl_program_compute("test/write_value.comp", NULL, 0) == 0);

    gl_buffer_destroy(&buf);
    CHECK(gl_check("end of test"));
    check_platforms(dirt_gpu_get_caps(gpu));
    dirt_gpu_destroy(gpu);
    dirt_gpu_destroy(NULL);
    return check_finish();
}
