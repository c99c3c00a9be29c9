/* The Z AOV of the GPU techniques: the depth of the first hit of the
 * pinhole ray through each pixel centre, as the Embree reference defines it
 * (src/ref/render.c): rays made on the CPU by dirt_camera_ray, traced by the
 * technique's tracer in batches that fit one storage block, the depth
 * computed on the CPU with the reference's own float operations. */
#include "integrator/depth.h"

#include <math.h>
#include <stdlib.h>

#include "common/layout.h"
#include "core/vec3.h"
#include "integrator/integrator.h"
#include "gl/gl.h"
#include "integrator/rng.h"

bool pt_depth_render(dirt_gpu *gpu, const dirt_tracer *tracer, const dirt_camera *cam, int width,
                     int height, size_t start, size_t count, size_t batch,
                     const dirt_trace_alpha *alpha, float *depth, float *ids)
{
    size_t pixels = (size_t)width * (size_t)height;
    if (start > pixels)
        start = pixels;
    if (count > pixels - start)
        count = pixels - start;
    pixels = start + count;
    if (!batch || batch > count)
        batch = count ? count : 1;
    dirt_ray *rays = malloc(batch * sizeof(*rays));
    dirt_hit *hits = malloc(batch * sizeof(*hits));
    GLuint rbuf = gl_buffer_create(gpu, batch * sizeof(*rays), NULL, false, "pt depth rays");
    GLuint hbuf = gl_buffer_create(gpu, batch * sizeof(*hits), NULL, true, "pt depth hits");
    bool ok = rays && hits && rbuf && hbuf;
    if (!ok)
        DIRT_ERROR("out of memory for the depth pass (%zu rays)", batch);
    dirt_vec3 forward = v3_normalize(v3_load(cam->forward)), eye = v3_load(cam->eye);
    gl_group_push("pt depth");
    for (size_t first = start; ok && first < pixels; first += batch) {
        size_t n = pixels - first < batch ? pixels - first : batch;
        /* A randomised tracer keys these rays by pixel, as the samples'. */
        if (tracer->restart)
            tracer->restart(tracer->self);
        if (tracer->begin_chunk)
            tracer->begin_chunk(tracer->self, (uint32_t)first);
        for (size_t i = 0; i < n; i++) {
            size_t p = first + i;
            dirt_vec3 org, dir;
            dirt_camera_ray(cam, width, height, (float)(p % (size_t)width) + 0.5f,
                            (float)(p / (size_t)width) + 0.5f, 0.0f, 0.0f, &org, &dir);
            rays[i] = (dirt_ray){{org.x, org.y, org.z}, 0.0f, {dir.x, dir.y, dir.z}, INFINITY};
        }
        if (tracer->set_alpha) {
            dirt_trace_alpha a = {0};
            if (alpha && alpha->materials) {
                a = *alpha;
                a.sample = DIRT_RNG_SAMPLE_AOV;
                a.bounce = 0;
                a.dim = DIRT_RNG_DIM_ALPHA_PATH;
                a.first_pixel = (uint32_t)first;
            }
            tracer->set_alpha(tracer->self, &a);
        }
        ok = gl_buffer_write(rbuf, 0, n * sizeof(*rays), rays) &&
             tracer->trace(tracer->self, rbuf, hbuf, (uint32_t)n, 0);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        ok = ok && gl_buffer_read(hbuf, 0, n * sizeof(*hits), hits);
        for (size_t i = 0; ok && i < n; i++) {
            if (ids)
                ids[first + i] = hits[i].prim == DIRT_HIT_NONE ? -1.0f : (float)hits[i].prim;
            if (hits[i].prim == DIRT_HIT_NONE) {
                depth[first + i] = INFINITY;
                continue;
            }
            dirt_vec3 p = v3_mad(v3_load(rays[i].org), v3_load(rays[i].dir), hits[i].t);
            depth[first + i] = v3_dot(v3_sub(p, eye), forward);
        }
    }
    gl_group_pop();
    gl_buffer_destroy(&rbuf);
    gl_buffer_destroy(&hbuf);
    free(rays);
    free(hits);
    return ok;
}
