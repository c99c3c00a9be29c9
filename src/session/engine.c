/* What the engines under the session share: the table of engines, the
 * stats helpers, images and the display of CPU images (engine.h). */
#include "session/engine.h"

#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "gl/gl.h"

const engine_ops *const session_engines[DIRT_NUM_ENGINES] = {
    [DIRT_ENGINE_DIRT] = &engine_dirt_ops,
    [DIRT_ENGINE_MMRT] = &engine_mmrt_ops,
    [DIRT_ENGINE_EMBREE] = &engine_embree_ops,
    [DIRT_ENGINE_RASTER] = &engine_raster_ops,
};

const char *const engine_pt_aovs[8] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z",
                                       "Z", "ID"};

/* Which clock measured a figure is the figure's own (dirt_gpu_clock
 * decided); unmeasured figures count 0. */
double engine_measured_ms(double ms, enum dirt_clock clock)
{
    return clock != DIRT_CLOCK_NONE && ms > 0 ? ms : 0;
}

void engine_add_pass(dirt_session_stats *st, const char *name, double ms, enum dirt_clock clock)
{
    for (int i = 0; i < st->num_passes; i++) {
        if (!strcmp(st->passes[i].name, name)) {
            st->passes[i].ms += ms;
            return;
        }
    }
    if (st->num_passes < (int)(sizeof(st->passes) / sizeof(st->passes[0])))
        st->passes[st->num_passes++] = (dirt_pass_time){name, ms, clock};
}

void engine_add_paths_at_event(dirt_session_stats *st, const uint64_t *paths, int events)
{
    if (events > DIRT_PT_MAX_EVENTS - 1)
        events = DIRT_PT_MAX_EVENTS - 1;
    if (events > st->events)
        st->events = events;
    for (int k = 1; k <= events; k++)
        st->paths_at_event[k] += paths[k];
}

void engine_add_buffer(dirt_session_stats *st, const char *name, uint64_t used,
                       uint64_t allocated)
{
    if (st->num_buffers < (int)(sizeof(st->buffers) / sizeof(st->buffers[0])))
        st->buffers[st->num_buffers++] = (dirt_buffer_bytes){name, used, allocated};
    st->bytes_total_used += used;
    st->bytes_total_allocated += allocated;
}

dirt_image *engine_new_image(int width, int height, const char *const *names, int n)
{
    dirt_image *img = dirt_image_create(width, height);
    for (int i = 0; img && i < n; i++) {
        if (!dirt_image_add_channel(img, names[i])) {
            dirt_image_destroy(img);
            img = NULL;
        }
    }
    if (!img)
        session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
    return img;
}

uint32_t engine_display_upload(engine_display *d, dirt_gpu *gpu, const dirt_image *img)
{
    if (!gpu) {
        DIRT_ERROR("no GPU to display on");
        session_fail(DIRT_SESSION_ERR_NO_GPU);
        return 0;
    }
    if (d->current && d->width == img->width && d->height == img->height)
        return d->texture;
    if (!d->texture || d->width != img->width || d->height != img->height) {
        GLuint tex = d->texture;
        gl_texture_destroy(&tex);
        d->texture = gl_texture_2d(GL_RGBA32F, img->width, img->height, 1, "session display");
        if (!d->texture)
            return 0;
        d->width = img->width;
        d->height = img->height;
    }
    if (!gl_texture_upload_rgba32f(d->texture, img->width, img->height, img->rgba))
        return 0;
    d->current = true;
    return d->texture;
}

void engine_display_release(engine_display *d)
{
    GLuint tex = d->texture;
    gl_texture_destroy(&tex);
    *d = (engine_display){0};
}

dirt_view_opts engine_view_opts(const engine_env *env)
{
    const dirt_session_opts *o = env->opts;
    enum dirt_view_mode mode = o->views == DIRT_SESSION_VIEWS_SINGLE ? DIRT_VIEWS_SINGLE
                               : o->views == DIRT_SESSION_VIEWS_CUBE ? DIRT_VIEWS_CUBE
                                                                     : DIRT_VIEWS_CUBE_CAMERA;
    return (dirt_view_opts){.mode = mode, .width = env->width, .height = env->height,
                            .face_size = o->face_size, .tile_size = o->tile_size ? o->tile_size : 2};
}

bool engine_cells_from_lists(engine_cells *c, int count, int buckets, const uint32_t *heads,
                             const uint32_t *next, size_t next_stride, uint32_t num_nodes,
                             uint32_t end, const float (*depth)[2])
{
    c->count = count;
    c->buckets = buckets;
    c->len = calloc((size_t)count + 1, sizeof(uint32_t));
    c->used = calloc((size_t)count + 1, sizeof(uint32_t));
    c->depth = malloc(((size_t)count + 1) * sizeof(*c->depth));
    if (!c->len || !c->used || !c->depth) {
        engine_cells_free(c);
        DIRT_ERROR("out of memory");
        return false;
    }
    for (int b = 0; b < buckets; b++) {
        for (int i = 0; i < count; i++) {
            uint32_t steps = 0;
            for (uint32_t n = heads[(size_t)b * count + i];
                 n != end && n < num_nodes && steps <= num_nodes; n = next[n * next_stride])
                steps++;
            c->len[i] += steps;
            c->used[i] += steps > 0;
        }
    }
    memcpy(c->depth, depth, (size_t)count * sizeof(*c->depth));
    return true;
}

void engine_cells_free(engine_cells *c)
{
    free(c->len);
    free(c->used);
    free(c->depth);
    c->len = c->used = NULL;
    c->depth = NULL;
}
