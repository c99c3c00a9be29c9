/* gpu-facts: the driver facts that decide how the engine runs on a device
 * (perf/gpu-check.sh prints them first), as a Markdown list on stdout:
 *   - the renderer, its version and the EGL platform;
 *   - conservative rasterization: every extension named *conservative_rast*,
 *     and whether DIRT's build uses GL_NV_conservative_raster or emulates it;
 *   - the storage block limit (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) and, in
 *     effect, DIRT_MAX_BLOCK_BYTES; the texel-buffer limit
 *     (GL_MAX_TEXTURE_BUFFER_SIZE), the texture and image units, and what
 *     that makes of the split arrays (src/gl/split.h): the most triangles
 *     the scene's vertex array holds, and in how many parts;
 *   - the timers: GL_QUERY_COUNTER_BITS of GL_TIME_ELAPSED and GL_TIMESTAMP,
 *     the smallest nonzero step between 2000 consecutive GL_TIMESTAMP
 *     readings (the resolution seen; an upper bound on the tick), and the
 *     clock the engine times passes with (dirt_gpu_clock).
 *     gpu-facts [--cpu-timing]
 * Exit 0; 3 without an OpenGL 4.5 context. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "dirt/stats.h"
#include "dirt/gpu.h"
#include "dirt/log.h"
#include "gl/gl.h"
#include "gl/split.h"

static void drop(void *user, enum dirt_log_level level, const char *file, int line,
                 const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

/* The most records of `d` one array holds on `gpu` (gl_split_plan, whose
 * refusals are silenced here), and the layout at that count. */
static uint64_t most_records(const dirt_gpu *gpu, const gl_split_desc *d,
                             gl_split_layout *at)
{
    dirt_log_set_callback(drop, NULL);
    uint64_t lo = 1, hi = (uint64_t)1 << 40;
    gl_split_layout l = {0};
    *at = l;
    if (!gl_split_plan(gpu, d, (size_t)lo, at))
        lo = 0;
    else
        while (lo < hi) { /* the largest count that plans: in [lo, hi] */
            uint64_t mid = lo + (hi - lo + 1) / 2;
            if (gl_split_plan(gpu, d, (size_t)mid, &l)) {
                lo = mid;
                *at = l;
            } else {
                hi = mid - 1;
            }
        }
    dirt_log_set_callback(NULL, NULL);
    return lo;
}

int main(int argc, char **argv)
{
    bool cpu_timing = argc > 1 && !strcmp(argv[1], "--cpu-timing");
    if (argc > 1 && !cpu_timing) {
        fprintf(stderr, "usage: gpu-facts [--cpu-timing]\n");
        return 2;
    }
    dirt_gpu *gpu = dirt_gpu_create(&(dirt_gpu_opts){.no_debug = true, .cpu_timing = cpu_timing});
    if (!gpu) {
        fprintf(stderr, "gpu-facts: no OpenGL 4.5 context (see the error above)\n");
        return 3;
    }
    const dirt_gpu_caps *c = dirt_gpu_get_caps(gpu);
    printf("- renderer: %s (%s), OpenGL %s, EGL platform %s\n", c->renderer, c->vendor,
           c->version, c->platform);

    printf("- conservative raster extensions:");
    GLint n = 0, found = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strstr(e, "conservative_rast")) {
            printf("%s %s", found ? "," : "", e);
            found++;
        }
    }
    printf("%s; DIRT's raster build %s\n", found ? "" : " none",
           c->nv_conservative_raster ? "uses GL_NV_conservative_raster"
                                     : "emulates conservative raster (no GL_NV_conservative_raster)");

    printf("- storage block: GL_MAX_SHADER_STORAGE_BLOCK_SIZE %lld bytes (%.1f MiB)",
           (long long)c->driver_ssbo_size, c->driver_ssbo_size / 1048576.0);
    if (c->block_override > 0)
        printf("; DIRT_MAX_BLOCK_BYTES lowers it to %lld bytes", (long long)c->block_override);
    printf("; %d bindings\n", c->max_ssbo_bindings);
    printf("- texel buffers: GL_MAX_TEXTURE_BUFFER_SIZE %lld texels (%.1f MiB of RGBA32F); "
           "%d texture units, %d image units\n", (long long)c->max_texel_buffer,
           (double)c->max_texel_buffer * 16 / 1048576.0, c->max_texture_units,
           c->max_image_units);
    gl_split_layout l;
    uint64_t tris = most_records(gpu, &gl_split_vertices, &l);
    uint64_t one = c->max_ssbo_size > 0 ? (uint64_t)c->max_ssbo_size / gl_split_vertices.record_bytes
                                        : 0;
    printf("- scene vertices (%zu bytes a triangle): %llu triangles in one storage block, "
           "at most %llu in one array (%d parts of %llu triangles, %s)\n",
           gl_split_vertices.record_bytes, (unsigned long long)one, (unsigned long long)tris,
           l.parts, l.parts ? (unsigned long long)1 << l.shift : 0ull,
           l.parts ? "texel buffers" : "one block");

    GLint bits_elapsed = 0, bits_stamp = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits_elapsed);
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits_stamp);
    GLint64 prev = 0, step = 0, t = 0;
    glGetInteger64v(GL_TIMESTAMP, &prev);
    int distinct = 0;
    for (int i = 0; i < 2000; i++) {
        glGetInteger64v(GL_TIMESTAMP, &t);
        if (t > prev) {
            if (!step || t - prev < step)
                step = t - prev;
            distinct++;
        }
        prev = t;
    }
    static const char *const clocks[] = {"GPU timer queries", "the CPU clock around glFinish"};
    enum dirt_clock ck = dirt_gpu_clock(gpu);
    printf("- timers: GL_TIME_ELAPSED %d bits, GL_TIMESTAMP %d bits; smallest step between "
           "2000 GL_TIMESTAMP readings %lld ns (%d steps seen); passes are timed with %s%s\n",
           bits_elapsed, bits_stamp, (long long)step, distinct,
           ck == DIRT_CLOCK_GPU ? clocks[0] : clocks[1],
           c->software ? " (a software renderer: timer queries do not time rasterization)" : "");
    dirt_gpu_destroy(gpu);
    return 0;
}
