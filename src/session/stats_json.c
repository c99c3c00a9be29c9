/* The session's stats as JSON, through cJSON. */
#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/file.h"
#include "dirt/log.h"
#include "dirt/session.h"
#include "session/session_internal.h"

/* The figures every frame and the summary share. */
static void add_figures(cJSON *o, const dirt_session_stats *s)
{
    cJSON_AddNumberToObject(o, "build_ms", s->build_ms);
    cJSON_AddNumberToObject(o, "trace_ms", s->trace_ms);
    cJSON_AddNumberToObject(o, "fetch_ms", s->fetch_ms);
    cJSON_AddNumberToObject(o, "visibility_ms", s->visibility_ms);
    cJSON_AddNumberToObject(o, "shade_ms", s->shade_ms);
    cJSON_AddNumberToObject(o, "total_ms", s->total_ms);
    cJSON_AddNumberToObject(o, "rays", (double)s->rays);
    cJSON_AddNumberToObject(o, "mrays_per_s", s->mrays_per_s);
    cJSON_AddNumberToObject(o, "aborted_rays", (double)s->aborted);
    cJSON_AddNumberToObject(o, "invalid_samples", (double)s->invalid_samples);
    cJSON_AddNumberToObject(o, "bytes_total", (double)s->bytes_total_used);
    cJSON_AddNumberToObject(o, "bytes_allocated", (double)s->bytes_total_allocated);
    if (s->events > 0) {
        cJSON *ev = cJSON_AddArrayToObject(o, "paths_per_event");
        for (int k = 1; ev && k <= s->events; k++)
            cJSON_AddItemToArray(ev, cJSON_CreateNumber((double)s->paths_at_event[k]));
    }
}

/* Technique figures, per-pass times and per-buffer bytes of one record. */
static void add_details(cJSON *o, const dirt_session_stats *s)
{
    if (s->has_ads) {
        const dirt_ads_stats *a = &s->ads;
        cJSON *b = cJSON_AddObjectToObject(o, "bytes");
        cJSON_AddNumberToObject(b, "vertices", (double)a->bytes_vertices);
        cJSON_AddNumberToObject(b, "depth bounds", (double)a->bytes_depth);
        cJSON_AddNumberToObject(b, "list heads", (double)a->bytes_heads);
        cJSON_AddNumberToObject(b, "id nodes", (double)a->bytes_nodes_used);
        cJSON_AddNumberToObject(b, "id nodes allocated", (double)a->bytes_nodes_allocated);
        cJSON_AddNumberToObject(b, "candidates", (double)a->bytes_candidates_used);
        cJSON_AddNumberToObject(b, "candidates allocated", (double)a->bytes_candidates_allocated);
        cJSON_AddNumberToObject(b, "large grid", (double)a->bytes_large_grid);
        cJSON_AddNumberToObject(b, "bucket masks", (double)a->bytes_bucket_masks);
        if (a->depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE) {
            cJSON_AddNumberToObject(b, "bucket edges", (double)a->bytes_bucket_edges);
            cJSON_AddNumberToObject(b, "bucket histogram", (double)a->bytes_bucket_histogram);
        }
        cJSON_AddStringToObject(o, "depth_buckets",
                                a->depth_buckets == DIRT_DEPTH_BUCKETS_ADAPTIVE ? "adaptive"
                                                                                : "uniform");
        cJSON_AddNumberToObject(o, "samples_np", (double)a->samples);
        cJSON_AddNumberToObject(o, "nodes", (double)a->nodes);
        cJSON_AddNumberToObject(o, "buckets_per_sample", a->buckets_per_sample);
        cJSON_AddNumberToObject(o, "fill_runs", a->fill_runs);
        cJSON_AddNumberToObject(o, "depth_runs", a->depth_runs);
        cJSON_AddBoolToObject(o, "bound_pass", a->bound_pass);
        cJSON_AddBoolToObject(o, "node_depths", a->node_depths);
        cJSON_AddStringToObject(o, "build", a->build == DIRT_BUILD_COMPUTE ? "compute" : "raster");
        cJSON_AddNumberToObject(o, "work_records", (double)a->work_records);
        cJSON_AddNumberToObject(o, "large_primitives", a->num_large);
        cJSON_AddNumberToObject(o, "bytes_table3", a->bytes_table3);
    } else if (s->has_mmrt) {
        /* The same keys as DIRT's where they mean the same; "list heads"
         * holds heads and tails. */
        const dirt_mmrt_stats *m = &s->mmrt;
        cJSON *b = cJSON_AddObjectToObject(o, "bytes");
        cJSON_AddNumberToObject(b, "vertices", (double)m->bytes_vertices);
        cJSON_AddNumberToObject(b, "depth bounds", (double)m->bytes_depth);
        cJSON_AddNumberToObject(b, "list heads", (double)m->bytes_heads);
        cJSON_AddNumberToObject(b, "id nodes", (double)m->bytes_id_nodes_used);
        cJSON_AddNumberToObject(b, "id nodes allocated", (double)m->bytes_id_nodes_allocated);
        cJSON_AddNumberToObject(b, "data nodes", (double)m->bytes_data_nodes_used);
        cJSON_AddNumberToObject(b, "data nodes allocated", (double)m->bytes_data_nodes_allocated);
        cJSON_AddNumberToObject(o, "fragments", (double)m->fragments);
        cJSON_AddNumberToObject(o, "max_layers", m->max_layers);
        cJSON_AddNumberToObject(o, "store_runs", m->store_runs);
        cJSON_AddNumberToObject(o, "bytes_paper", m->bytes_paper);
    }
    cJSON *passes = cJSON_AddArrayToObject(o, "passes");
    for (int i = 0; i < s->num_passes; i++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "name", s->passes[i].name);
        cJSON_AddNumberToObject(p, "ms", s->passes[i].ms);
        cJSON_AddStringToObject(p, "clock", dirt_clock_names[s->passes[i].clock]);
        cJSON_AddItemToArray(passes, p);
    }
    cJSON *buffers = cJSON_AddArrayToObject(o, "buffers");
    for (int i = 0; i < s->num_buffers; i++) {
        cJSON *b = cJSON_CreateObject();
        cJSON_AddStringToObject(b, "name", s->buffers[i].name);
        cJSON_AddNumberToObject(b, "used", (double)s->buffers[i].used);
        cJSON_AddNumberToObject(b, "allocated", (double)s->buffers[i].allocated);
        cJSON_AddItemToArray(buffers, b);
    }
}

/* One ray type's work: rays, triangle tests and the engine's own counts. */
static void add_work_counts(cJSON *o, enum dirt_engine e, const dirt_session_work *w)
{
    cJSON_AddNumberToObject(o, "rays", (double)w->rays);
    cJSON_AddNumberToObject(o, "triangle_tests", (double)w->triangle_tests);
    if (e == DIRT_ENGINE_DIRT) {
        cJSON_AddNumberToObject(o, "tiles", (double)w->tiles);
        cJSON_AddNumberToObject(o, "hiz_steps", (double)w->hiz_steps);
        cJSON_AddNumberToObject(o, "list_nodes", (double)w->list_nodes);
    } else if (e == DIRT_ENGINE_MMRT) {
        cJSON_AddNumberToObject(o, "fragments", (double)w->fragments);
        cJSON_AddNumberToObject(o, "pixels", (double)w->pixels);
        cJSON_AddNumberToObject(o, "hiz_steps", (double)w->hiz_steps);
    } else {
        cJSON_AddNumberToObject(o, "bvh_nodes", (double)w->bvh_nodes);
    }
}

/* "work": per ray type, the engine's counts and (dirt, mmrt) Embree's over
 * the same rays under "embree". */
static void add_work(cJSON *f, const dirt_session_stats *st)
{
    if (!st->has_work)
        return;
    cJSON *w = cJSON_AddObjectToObject(f, "work");
    for (int t = 0; w && t < DIRT_RAY_TYPES; t++) {
        cJSON *o = cJSON_AddObjectToObject(w, dirt_ray_type_names[t]);
        if (!o)
            break;
        add_work_counts(o, st->engine, &st->work[t]);
        if (st->engine != DIRT_ENGINE_EMBREE) {
            cJSON *e = cJSON_AddObjectToObject(o, "embree");
            if (e)
                add_work_counts(e, DIRT_ENGINE_EMBREE, &st->embree_work[t]);
        }
    }
}

struct cJSON *dirt_session_stats_json(const dirt_session_stats *st)
{
    cJSON *f = cJSON_CreateObject();
    if (!f)
        return NULL;
    cJSON_AddStringToObject(f, "engine", dirt_engine_names[st->engine]);
    cJSON_AddNumberToObject(f, "width", st->width);
    cJSON_AddNumberToObject(f, "height", st->height);
    cJSON_AddNumberToObject(f, "time", st->time);
    cJSON_AddNumberToObject(f, "samples", st->samples);
    cJSON_AddNumberToObject(f, "seed", st->seed);
    add_figures(f, st);
    add_details(f, st);
    add_work(f, st);
    return f;
}

bool dirt_session_write_stats(const char *path, const dirt_session_stats *frames, size_t count)
{
    return dirt_session_write_stats_attrs(path, frames, count, NULL, 0);
}

bool dirt_session_write_stats_attrs(const char *path, const dirt_session_stats *frames,
                                    size_t count, const dirt_image_attr *attrs, size_t num_attrs)
{
    session_begin();
    if (!count || !frames || !path || (num_attrs && !attrs)) {
        DIRT_ERROR("no frames to write stats of, no path, or no attributes");
        return session_fail(DIRT_SESSION_ERR_ARGUMENT);
    }
    const dirt_session_stats *last = &frames[count - 1];
    /* Means of the times; rays per frame; aborted rays summed; the largest
     * memory; the technique's figures of the last frame. */
    dirt_session_stats mean = *last;
    mean.build_ms = mean.trace_ms = mean.fetch_ms = mean.visibility_ms = mean.shade_ms = 0;
    mean.total_ms = 0;
    mean.rays = mean.aborted = mean.invalid_samples = 0;
    memset(mean.paths_at_event, 0, sizeof(mean.paths_at_event));
    mean.bytes_total_used = mean.bytes_total_allocated = 0;
    for (size_t i = 0; i < count; i++) {
        const dirt_session_stats *f = &frames[i];
        mean.build_ms += f->build_ms / (double)count;
        mean.trace_ms += f->trace_ms / (double)count;
        mean.fetch_ms += f->fetch_ms / (double)count;
        mean.visibility_ms += f->visibility_ms / (double)count;
        mean.shade_ms += f->shade_ms / (double)count;
        mean.total_ms += f->total_ms / (double)count;
        mean.rays += f->rays;
        for (int k = 0; k < DIRT_MAX_EVENTS; k++)
            mean.paths_at_event[k] += f->paths_at_event[k];
        mean.aborted += f->aborted;
        mean.invalid_samples += f->invalid_samples;
        if (f->bytes_total_used > mean.bytes_total_used)
            mean.bytes_total_used = f->bytes_total_used;
        if (f->bytes_total_allocated > mean.bytes_total_allocated)
            mean.bytes_total_allocated = f->bytes_total_allocated;
    }
    mean.rays /= count;
    for (int k = 0; k < DIRT_MAX_EVENTS; k++)
        mean.paths_at_event[k] /= count;

    cJSON *root = cJSON_CreateObject();
    if (!root)
        goto oom;
    cJSON_AddStringToObject(root, "engine", dirt_engine_names[last->engine]);
    cJSON_AddStringToObject(root, "device", last->device);
    cJSON_AddNumberToObject(root, "width", last->width);
    cJSON_AddNumberToObject(root, "height", last->height);
    cJSON_AddNumberToObject(root, "spp", last->samples);
    cJSON_AddNumberToObject(root, "bounces", last->bounces);
    cJSON_AddStringToObject(root, "mode", last->mode == DIRT_PT_AO ? "ao" : "pt");
    cJSON_AddNumberToObject(root, "frames_rendered", (double)count);
    if (num_attrs) {
        cJSON *prov = cJSON_AddObjectToObject(root, "provenance");
        for (size_t i = 0; prov && i < num_attrs; i++)
            cJSON_AddStringToObject(prov, attrs[i].name, attrs[i].value);
    }
    add_figures(root, &mean);
    add_details(root, last);
    cJSON *list = cJSON_AddArrayToObject(root, "frames");
    for (size_t i = 0; list && i < count; i++) {
        cJSON *f = dirt_session_stats_json(&frames[i]);
        if (!f)
            goto oom;
        cJSON_AddItemToArray(list, f);
    }
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    root = NULL;
    if (!text)
        goto oom;
    size_t len = strlen(text);
    char *doc = realloc(text, len + 2);
    if (!doc) {
        free(text);
        goto oom;
    }
    doc[len] = '\n';
    doc[len + 1] = '\0';
    bool ok = dirt_write_file_atomic(path, doc, len + 1);
    free(doc);
    return ok || session_fail(DIRT_SESSION_ERR_IO);
oom:
    cJSON_Delete(root);
    DIRT_ERROR("out of memory writing '%s'", path);
    return session_fail(DIRT_SESSION_ERR_OUT_OF_MEMORY);
}
