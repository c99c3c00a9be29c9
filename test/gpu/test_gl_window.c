/* The windowed context: GLFW opens a window with a GL 4.5 core context
 * (run under xvfb-run by test_gl_window.sh), the probe reports the "glfw"
 * platform, a cleared and swapped frame reads back the clear colour, and
 * the window reports its size. Skips (77) without a display. */
#include <string.h>

#include "check.h"
#include "gl/gl.h"
#include "gl/window.h"

int main(void)
{
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.window = true, .width = 160, .height = 90,
                                                     .title = "dirt test"});
    if (!gpu) {
        fprintf(stderr, "no window system: skipping\n");
        return TEST_SKIP;
    }
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    CHECK(c->gl_major * 10 + c->gl_minor >= 45);
    CHECK(c->platform && strcmp(c->platform, "glfw") == 0);
    int w = 0, h = 0;
    dirt_gpu_window_size(gpu, &w, &h);
    CHECK(w == 160 && h == 90);
    CHECK(!dirt_gpu_window_should_close(gpu));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char px[4] = {0};
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    CHECK(px[0] >= 63 && px[0] <= 65 && px[1] >= 127 && px[1] <= 128 && px[2] >= 190 &&
          px[2] <= 192);
    dirt_gpu_window_swap(gpu);
    dirt_gpu_window_poll(gpu);
    CHECK(dirt_gpu_error_count(gpu) == 0);
    dirt_gpu_destroy(gpu);
    return check_finish();
}
