/* DIRT Trace and Fetch, host side. */
#include <stdlib.h>
#include <string.h>

#include "dirt/ads_internal.h"
#include "gl/program.h"

/* Record sizes and offsets are checked in test/common/layout_check.c. */

bool ads_trace_gl(dirt_ads *a, GLuint rays, GLuint hits, uint32_t count,
                  const dirt_trace_opts *opts_in, bool link, dirt_trace_stats *stats)
{
    dirt_trace_opts opts = opts_in ? *opts_in : (dirt_trace_opts){0};
    if (!gl_buffer_ensure(a->gpu, &a->hit_heads, &a->hit_heads_size, (size_t)a->set.num_tiles * 4 + 4, false,
                "dirt hit heads"))
        return false;
    gl_group_push("dirt trace");
    /* Rays may come from a shader (the integrator's ray generation); the
     * clears below overwrite what earlier traces wrote with shaders; the
     * structure's arrays come from the build's shaders (image loads once
     * split: ads_split_barriers). */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    ads_split_barriers(a));
    static const uint32_t zero = 0, end = DIRT_LIST_END;
    if (stats) /* per-call abort count; else it accumulates until reset */
        glClearNamedBufferSubData(a->counters, GL_R32UI, 8, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &zero);
    if (link)
        glClearNamedBufferData(a->hit_heads, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    ads_bind_all(a);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    /* Only a linking trace touches the hit lists (the barrier checker takes a
     * bound writable block as written). */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HIT_HEADS, link ? a->hit_heads : 0);
    if (opts.work)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_WORK, opts.work);
    /* Alpha-tested traversal, the large primitives, counting, their grid,
     * the sub-tile rectangles and the bucket masks: each its own build of
     * the shader, compiled when first used (without them, the trace has
     * none of their code). */
    const dirt_trace_alpha *al = &opts.alpha;
    bool large = a->stats.num_large > 0;
    bool grid = large && a->opts.large_grid;
    gl_split_program *prog = &a->prog_trace[(al->materials ? 1 : 0) | (large ? 2 : 0) |
                                            (opts.work ? 4 : 0) | (grid ? 8 : 0) |
                                            (a->opts.sub_tiles ? 16 : 0) |
                                            (ads_has_masks(a) ? 32 : 0) |
                                            (a->node_depths_stored ? 64 : 0)];
    glsl_define defs[8];
    int n = 0;
    if (a->opts.depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE)
        defs[n++] = (glsl_define){"DIRT_ADAPTIVE", "1"};
    if (al->materials)
        defs[n++] = (glsl_define){"DIRT_TRACE_ALPHA", "1"};
    if (large)
        defs[n++] = (glsl_define){"DIRT_TRACE_LARGE", "1"};
    if (opts.work)
        defs[n++] = (glsl_define){"DIRT_TRACE_COUNT", "1"};
    if (grid)
        defs[n++] = (glsl_define){"DIRT_TRACE_LARGE_GRID", "1"};
    if (a->opts.sub_tiles)
        defs[n++] = (glsl_define){"DIRT_SUB_TILES", "1"};
    if (ads_has_masks(a))
        defs[n++] = (glsl_define){"DIRT_BUCKET_MASKS", "1"};
    if (a->node_depths_stored) /* (a build that stored none: the plain lists' build) */
        defs[n++] = (glsl_define){"DIRT_NODE_DEPTHS", "1"};
    const char *paths[] = {"dirt/trace.comp", NULL};
    if (!ads_program_extra(a, prog, "dirt/trace.comp", paths, defs, (size_t)n,
                           ADS_TRACE_ARRAYS, al->materials ? al->texels : NULL)) {
        gl_group_pop();
        return false;
    }
    glUseProgram(prog->id);
    glUniform1ui(DIRT_LOC_TRACE_COUNT, count);
    glUniform1i(DIRT_LOC_TRACE_HIZ_TOP, opts.hiz_levels > 0 ? opts.hiz_levels - 1 : -1);
    glUniform1i(DIRT_LOC_TRACE_ANY_HIT, opts.any_hit ? 1 : 0);
    glUniform1i(DIRT_LOC_TRACE_LINK, link ? 1 : 0);
    glUniform1i(DIRT_LOC_TRACE_FROM_SURFACES, opts.from_surfaces ? 1 : 0);
    /* Alpha test: the integrator's tables and the per-primitive materials. */
    if (al->materials) {
        glUniform1i(DIRT_LOC_ALPHA_ENABLED, 1);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_MODEL_MATERIALS, al->materials);
        gl_split_bind(al->texels);
        glUniform4ui(DIRT_LOC_ALPHA_KEY, al->seed, al->sample, al->bounce, al->dim);
        glUniform1ui(DIRT_LOC_ALPHA_FIRST_PIXEL, al->first_pixel);
    }
    /* Timed here only when called on its own (stats requested); inside a
     * frame graph the graph times the pass (GL timer queries don't nest). */
    if (stats)
        gl_timer_begin(&a->trace_timer);
    gl_dispatch_rays(opts.batch, count, 0);
    if (stats)
        gl_timer_end(&a->trace_timer);
    glUseProgram(0);
    gl_group_pop();
    if (stats) {
        *stats = (dirt_trace_stats){.rays = count, .ms = a->trace_timer.ms,
                                    .clock = a->trace_timer.clock};
        struct dirt_gpu_ads_counters c;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        if (!gl_buffer_read(a->counters, 0, sizeof(c), &c))
            return false;
        stats->aborted = c.fill.z;
        if (c.fill.z)
            DIRT_WARN("%u of %u rays ran out of march steps", c.fill.z, count);
    }
    return gl_check("dirt trace");
}

bool ads_fetch_gl(dirt_ads *a, bool raster, GLuint rays, GLuint hits, uint32_t count,
                  GLuint gpoints, uint32_t slot, GLuint batch)
{
    struct dirt_gpu_fetch_params fp = {.config = {count, slot, 0, 0}};
    glNamedBufferSubData(a->fetch_params, 0, sizeof(fp), &fp);
    gl_group_push(raster ? "dirt fetch (raster)" : "dirt fetch (compute)");
    ads_bind_all(a);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_GPOINTS, gpoints);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_FETCH_PARAMS, a->fetch_params);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HIT_HEADS, a->hit_heads);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(raster ? a->prog_fetch_miss.id : a->prog_fetch.id);
    gl_dispatch_rays(batch, count, 0);
    if (raster) {
        /* The misses' shading points, then the hits': the barrier checker
         * tracks whole buffers, and two commands writing one need it. */
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        if (a->fetch_fbo_w != a->set.atlas_width || a->fetch_fbo_h != a->set.atlas_height) {
            glNamedFramebufferParameteri(a->fetch_fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH,
                                         a->set.atlas_width);
            glNamedFramebufferParameteri(a->fetch_fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT,
                                         a->set.atlas_height);
            a->fetch_fbo_w = a->set.atlas_width;
            a->fetch_fbo_h = a->set.atlas_height;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, a->fetch_fbo);
        glViewport(0, 0, a->set.atlas_width, a->set.atlas_height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glUseProgram(a->prog_fetch_raster.id);
        glBindVertexArray(a->fetch_vao);
        if (a->num_primitives)
            glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(a->num_primitives * 3));
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glUseProgram(0);
    gl_group_pop();
    return gl_check("dirt fetch");
}

static bool upload_rays(dirt_ads *a, const dirt_ray *rays, size_t count)
{
    if (count > UINT32_MAX / 2) {
        DIRT_ERROR("too many rays in one batch (%zu)", count);
        return false;
    }
    size_t bytes = count * sizeof(dirt_ray);
    if (!gl_buffer_ensure(a->gpu, &a->rays, &a->rays_size, bytes, false, "dirt rays") ||
        !gl_buffer_ensure(a->gpu, &a->hits, &a->hits_size, bytes, true, "dirt hits"))
        return false;
    glNamedBufferSubData(a->rays, 0, (GLsizeiptr)bytes, rays);
    return true;
}

bool dirt_ads_trace(dirt_ads *a, const dirt_ray *rays, size_t count, dirt_hit *hits,
                    const dirt_trace_opts *opts, dirt_trace_stats *stats)
{
    dirt_trace_stats local;
    if (!stats)
        stats = &local;
    *stats = (dirt_trace_stats){.ms = -1, .clock = DIRT_CLOCK_NONE};
    if (!count)
        return true;
    /* With stats (always here) ads_trace_gl fenced its writes for readback. */
    if (!upload_rays(a, rays, count) ||
        !ads_trace_gl(a, a->rays, a->hits, (uint32_t)count, opts, false, stats))
        return false;
    return gl_buffer_read(a->hits, 0, count * sizeof(dirt_hit), hits);
}

bool dirt_ads_trace_work(dirt_ads *a, const dirt_ray *rays, size_t count, dirt_hit *hits,
                         const dirt_trace_opts *opts_in, dirt_trace_stats *stats,
                         dirt_trace_work *work)
{
    _Static_assert(sizeof(dirt_trace_work) == 16, "one uvec4 per ray (DIRT_BIND_WORK)");
    dirt_trace_opts opts = opts_in ? *opts_in : (dirt_trace_opts){0};
    if (!count)
        return dirt_ads_trace(a, rays, count, hits, &opts, stats);
    if (!gl_buffer_ensure(a->gpu, &a->work, &a->work_size, count * sizeof(*work), true,
                          "dirt trace work"))
        return false;
    opts.work = a->work;
    if (!dirt_ads_trace(a, rays, count, hits, &opts, stats))
        return false;
    return gl_buffer_read(a->work, 0, count * sizeof(*work), work);
}

bool dirt_ads_trace_fetch(dirt_ads *a, const dirt_ray *rays, size_t count,
                          enum dirt_fetch_mode mode, dirt_gpoint *out)
{
    if (!count)
        return true;
    GLuint gp = gl_buffer_create(a->gpu, count * 3 * sizeof(dirt_gpoint), NULL, true,
                                 "dirt test gpoints");
    /* All ones: a record that Fetch never writes reads as NaNs. */
    static const uint32_t ones = 0xFFFFFFFFu;
    if (gp)
        glClearNamedBufferData(gp, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &ones);
    bool ok = gp && upload_rays(a, rays, count) &&
              ads_trace_gl(a, a->rays, a->hits, (uint32_t)count, NULL,
                           mode == DIRT_FETCH_RASTER, NULL) &&
              ads_fetch_gl(a, mode == DIRT_FETCH_RASTER, a->rays, a->hits, (uint32_t)count, gp, 1,
                           0);
    if (ok) {
        /* Slot 1 of each owner: entries 3 i + 1. */
        dirt_gpoint *all = malloc(count * 3 * sizeof(*all));
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        ok = all && gl_buffer_read(gp, 0, count * 3 * sizeof(*all), all);
        for (size_t i = 0; ok && i < count; i++)
            out[i] = all[3 * i + 1];
        free(all);
    }
    gl_buffer_destroy(&gp);
    return ok;
}

void ads_reset_ray_count(dirt_ads *a)
{
    static const uint32_t zero[2] = {0, 0};
    glClearNamedBufferSubData(a->counters, GL_RG32UI, 8, 8, GL_RG_INTEGER, GL_UNSIGNED_INT,
                              zero);
}

bool ads_read_counts(dirt_ads *a, uint64_t *rays, uint64_t *aborted)
{
    struct dirt_gpu_ads_counters c;
    if (!gl_buffer_read(a->counters, 0, sizeof(c), &c))
        return false;
    *rays = c.fill.w;
    *aborted = c.fill.z;
    return true;
}

void ads_bind_geometry(dirt_ads *a)
{
    gl_split_bind(&a->vertices);
    gl_split_bind(&a->prim_material);
}

bool ads_visibility_gl(dirt_ads *a, GLuint rays, GLuint hits)
{
    if (a->set.camera_view < 0) {
        DIRT_ERROR("direct visibility needs a camera view (views single or cube+camera)");
        return false;
    }
    const dirt_view *v = &a->set.views[a->set.camera_view];
    if (a->vis_w != v->width || a->vis_h != v->height) {
        if (a->vis_fbo)
            glDeleteFramebuffers(1, &a->vis_fbo);
        gl_texture_destroy(&a->vis_color);
        gl_texture_destroy(&a->vis_depth);
        a->vis_color = gl_texture_2d(GL_RGBA32UI, v->width, v->height, 1, "dirt visibility");
        a->vis_depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, v->width, v->height, 1,
                                     "dirt visibility depth");
        if (!a->vis_color || !a->vis_depth)
            return false;
        /* Integer textures are incomplete with linear filtering. */
        glTextureParameteri(a->vis_color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(a->vis_color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glCreateFramebuffers(1, &a->vis_fbo);
        glNamedFramebufferTexture(a->vis_fbo, GL_COLOR_ATTACHMENT0, a->vis_color, 0);
        glNamedFramebufferTexture(a->vis_fbo, GL_DEPTH_ATTACHMENT, a->vis_depth, 0);
        gl_label(GL_FRAMEBUFFER, a->vis_fbo, "dirt visibility");
        if (glCheckNamedFramebufferStatus(a->vis_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            DIRT_ERROR("visibility framebuffer incomplete");
            return false;
        }
        a->vis_w = v->width;
        a->vis_h = v->height;
    }
    if (!gl_buffer_ensure(a->gpu, &a->hit_heads, &a->hit_heads_size, (size_t)a->set.num_tiles * 4 + 4, false,
                "dirt hit heads"))
        return false;
    gl_group_push("dirt direct visibility");
    /* The clear and the resolve's writes of the hit lists follow earlier
     * traces' and Fetches' accesses; the draw reads the structure (image
     * loads once split: ads_split_barriers). */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    ads_split_barriers(a));
    static const uint32_t end = DIRT_LIST_END, zero4[4] = {0, 0, 0, 0};
    static const float one = 1.0f;
    glClearNamedBufferData(a->hit_heads, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    glClearNamedFramebufferuiv(a->vis_fbo, GL_COLOR, 0, zero4);
    glClearNamedFramebufferfv(a->vis_fbo, GL_DEPTH, 0, &one);
    ads_bind_all(a);
    glBindFramebuffer(GL_FRAMEBUFFER, a->vis_fbo);
    glViewport(0, 0, v->width, v->height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glUseProgram(a->prog_vis.id);
    glUniform1i(DIRT_LOC_VISIBILITY_VIEW, a->set.camera_view);
    glBindVertexArray(a->vis_vao);
    if (a->num_primitives)
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(a->num_primitives * 3));
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    /* (The resolve fetches what the draw wrote through the framebuffer:
     * ordered by GL, no barrier.) */
    glUseProgram(a->prog_vis_resolve.id);
    glUniform1i(DIRT_LOC_VIS_RESOLVE_VIEW, a->set.camera_view);
    glBindTextureUnit(DIRT_UNIT_VISIBILITY, a->vis_color);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_RAYS, rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HITS, hits);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_HIT_HEADS, a->hit_heads);
    gl_dispatch_rows((size_t)v->width * v->height);
    glUseProgram(0);
    gl_group_pop();
    return gl_check("dirt direct visibility");
}

bool dirt_ads_direct_visibility(dirt_ads *a, dirt_ray *rays, dirt_hit *hits)
{
    if (a->set.camera_view < 0) {
        DIRT_ERROR("direct visibility needs a camera view");
        return false;
    }
    const dirt_view *v = &a->set.views[a->set.camera_view];
    size_t n = (size_t)v->width * v->height;
    if (!gl_buffer_ensure(a->gpu, &a->rays, &a->rays_size, n * sizeof(dirt_ray), true, "dirt rays") ||
        !gl_buffer_ensure(a->gpu, &a->hits, &a->hits_size, n * sizeof(dirt_hit), true, "dirt hits") ||
        !ads_visibility_gl(a, a->rays, a->hits))
        return false;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return gl_buffer_read(a->rays, 0, n * sizeof(dirt_ray), rays) &&
           gl_buffer_read(a->hits, 0, n * sizeof(dirt_hit), hits);
}
