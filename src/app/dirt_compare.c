/* dirt-compare: memory, time and quality of DIRT against the fragment
 * A-buffer (MMRT) over sweeps of settings, on the render session
 * (dirt/session.h). Outputs in DIR (app/compare.h, doc/compare.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/compare.h"
#include "app/options.h"
#include "app/provenance.h"
#include "app/sequence.h"
#include "app/setup.h"
#include "dirt/clock.h"
#include "dirt/env.h"
#include "dirt/log.h"
#include "dirt/session.h"
#include "dirt/version.h"

#define PROG "dirt-compare"
#define MAX_LIST 16
#define MAX_SCENES 16
#define MAX_REPEAT 64

typedef struct int_list { int n; int v[MAX_LIST]; } int_list;
typedef struct dbl_list { int n; double v[MAX_LIST]; } dbl_list;

/* The sweep and the measurement, from the shared option table. */
typedef struct options {
    const char *scenes[MAX_SCENES];
    int num_scenes;
    const char *dir;
    int_list w, h, views, tile, dbuckets, mbuckets, march, samples, spp, bounces;
    dbl_list thickness, time;   /* thickness < 0: a fraction of the diagonal */
    int warmup, repeat, agree_w, agree_h, face;
    int large;                  /* --large: 0 none, else up to that many */
    bool large_grid;            /* --large-grid: DIRT's large primitives through their grid */
    bool sub_tiles;             /* --sub-tiles: DIRT's list nodes with sub-tile rectangles */
    bool bucket_masks;          /* --bucket-masks: DIRT's per-tile bucket occupancy masks */
    bool node_depths;           /* --node-depths: DIRT's list nodes with depth ranges */
    bool quality, images, quiet;
    bool count_work;            /* --count-work: each row's work per ray type */
    uint32_t seed;
    const char *env_path;       /* --env FILE|sky, for every scene */
    dirt_env_opts env;          /* --env-intensity, --env-rotation */
    float background[3];        /* --background, for every scene */
    bool background_set;
} options;

static const char *const *const view_names = app_views_names;
static const char *const *const march_names = app_march_names;

static void to_ints(const app_list *l, int_list *out)
{
    out->n = l->n;
    for (int i = 0; i < l->n; i++)
        out->v[i] = (int)l->v[i][0];
}

/* The sweep of the parsed options; false after printing why. */
static bool from_app(const app_opts *a, options *o)
{
    memset(o, 0, sizeof(*o));
    o->num_scenes = a->num_scenes;
    for (int i = 0; i < a->num_scenes; i++)
        o->scenes[i] = a->scenes[i];
    o->dir = a->output;
    const app_list *res = &a->lists[APP_OPT_RES];
    o->w.n = o->h.n = res->n;
    for (int i = 0; i < res->n; i++) {
        o->w.v[i] = (int)res->v[i][0];
        o->h.v[i] = (int)res->v[i][1];
    }
    to_ints(&a->lists[APP_OPT_VIEWS], &o->views);
    to_ints(&a->lists[APP_OPT_TILE], &o->tile);
    to_ints(&a->lists[APP_OPT_DIRT_BUCKETS], &o->dbuckets);
    to_ints(&a->lists[APP_OPT_MMRT_BUCKETS], &o->mbuckets);
    to_ints(&a->lists[APP_OPT_MARCH], &o->march);
    to_ints(&a->lists[APP_OPT_SAMPLES], &o->samples);
    to_ints(&a->lists[APP_OPT_SPP], &o->spp);
    to_ints(&a->lists[APP_OPT_BOUNCES], &o->bounces);
    /* --thickness-rel's fractions follow --thickness's values (negated:
     * resolved per scene). */
    static const app_list none;
    const app_list *th = &a->lists[APP_OPT_THICKNESS], *rel = &a->lists[APP_OPT_THICKNESS_REL];
    if (!a->given[APP_OPT_THICKNESS] && rel->n)
        th = &none;
    if (th->n + rel->n > MAX_LIST) {
        cli_error(PROG, "--thickness and --thickness-rel: at most %d values", MAX_LIST);
        return false;
    }
    for (int i = 0; i < th->n; i++)
        o->thickness.v[o->thickness.n++] = th->v[i][0];
    for (int i = 0; i < rel->n; i++)
        o->thickness.v[o->thickness.n++] = -rel->v[i][0];
    if (a->frames.count > MAX_LIST) {
        cli_error(PROG, "--frames: at most %d frames", MAX_LIST);
        return false;
    }
    for (size_t i = 0; i < a->frames.count; i++)
        o->time.v[o->time.n++] = (double)a->frames.frames[i] / a->fps;
    for (int i = 0; !a->frames.count && i < a->lists[APP_OPT_TIME].n; i++)
        o->time.v[o->time.n++] = a->lists[APP_OPT_TIME].v[i][0];
    o->warmup = a->warmup;
    o->repeat = a->repeat;
    o->agree_w = a->agree_res[0];
    o->agree_h = a->agree_res[1];
    o->face = a->s.face_size;
    o->large = (int)a->large;
    o->large_grid = a->s.large_grid;
    o->sub_tiles = a->s.sub_tiles;
    o->bucket_masks = a->s.bucket_masks;
    o->node_depths = a->s.node_depths;
    o->quality = !a->no_quality;
    o->count_work = a->s.count_work;
    o->images = a->images;
    o->quiet = a->quiet;
    o->seed = a->s.seed;
    o->env_path = a->env_path;
    o->env = (dirt_env_opts){.intensity = a->env_intensity, .rotation = a->env_rotation};
    memcpy(o->background, a->s.background, sizeof(o->background));
    o->background_set = a->given[APP_OPT_BACKGROUND];
    return true;
}

/* ---- one configuration ---- */

typedef struct config {
    int scene, w, h, views, tile, dbuckets, mbuckets, march, samples, spp, bounces;
    double thickness, time; /* thickness < 0: a fraction of the diagonal */
} config;

/* A scene and the lighting it is measured under (resolve_lighting). */
typedef struct scene_info {
    const char *path, *name;
    dirt_scene *scene;
    uint64_t triangles;
    double diagonal;
    uint64_t emitters;          /* emissive triangles (dirt_material_is_emissive), time 0 */
    size_t lights;              /* punctual lights */
    const char *source;         /* "scene", "fallback", "--env" or "--background" */
    const char *environment;    /* "none", "sky", "map" or "background" */
    const dirt_env *env;        /* the session's env (borrowed; NULL: the background) */
    float background[3];
    char summary[1200];         /* one line for the table and the CSV */
    char key[1100];             /* the lighting's part of a configuration's id */
} scene_info;

static double median3(double *v, int n, double *mn, double *mx)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1], v[j - 1] = t;
        }
    *mn = v[0], *mx = v[n - 1];
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static cJSON *stat_json(double *v, int n, enum dirt_clock clock)
{
    double mn, mx, md = median3(v, n, &mn, &mx);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "clock", dirt_clock_names[clock]);
    cJSON_AddNumberToObject(o, "min_ms", mn);
    cJSON_AddNumberToObject(o, "median_ms", md);
    cJSON_AddNumberToObject(o, "max_ms", mx);
    return o;
}

static int g_face; /* --face: one value for the whole sweep */
static int g_large; /* --dirt-large: one value for the whole sweep */
static bool g_large_grid; /* --large-grid: likewise */
static bool g_sub_tiles;  /* --sub-tiles: likewise */
static bool g_bucket_masks; /* --bucket-masks: likewise */
static bool g_node_depths; /* --node-depths: likewise */
static enum dirt_depth_buckets g_depth_buckets; /* --depth-buckets: DIRT's, the whole sweep */

/* The library's messages, printed as its default sink prints them; the
 * first error since the configuration began is kept for the row's reason. */
static char g_first_error[400];

static void log_sink(void *user, enum dirt_log_level level, const char *file, int line,
                     const char *msg)
{
    (void)user;
    static const char *const tags[] = {"error", "warning", "info", "debug"};
    if (file) {
        const char *src = strstr(file, "src/");
        fprintf(stderr, "dirt: %s: %s:%d: %s\n", tags[level], src ? src : file, line, msg);
    } else {
        fprintf(stderr, "dirt: %s\n", msg);
    }
    if (level == DIRT_LOG_ERROR && !g_first_error[0])
        snprintf(g_first_error, sizeof(g_first_error), "%s", msg);
}

/* "ENGINE: WHAT: the first error logged", or "(see the log)" without one. */
static void set_reason(char *why, size_t n, const char *engine, const char *what)
{
    if (g_first_error[0])
        snprintf(why, n, "%s: %s: %s", engine, what, g_first_error);
    else
        snprintf(why, n, "%s: %s (see the log)", engine, what);
}

/* The shortest decimal that reads back as the float `v` (0.2f: 0.2, not
 * 0.200000003), for the outputs. */
static double shortest(float v)
{
    char t[32];
    for (int p = 1; p < 10; p++) {
        snprintf(t, sizeof(t), "%.*g", p, (double)v);
        if ((float)strtod(t, NULL) == v)
            break;
    }
    return strtod(t, NULL);
}

/* Decides the lighting of `si` (its scene loaded, frame `f` at time 0):
 * --env / --background for every scene (beside the scene's own lights);
 * else the scene's own emitters and punctual lights with a black
 * environment; else, for a scene with neither, the built-in sky, `*sky`
 * (made on first use; the caller destroys it). False (logged) when the sky
 * cannot be made. */
static bool resolve_lighting(scene_info *si, const dirt_frame *f, const options *o,
                             const dirt_env *env_map, dirt_env **sky)
{
    const dirt_material *m = dirt_scene_materials(si->scene);
    size_t nm = dirt_scene_num_materials(si->scene);
    si->emitters = 0;
    for (size_t t = 0; f && t < f->num_triangles; t++)
        si->emitters += f->material[t] < nm && dirt_material_is_emissive(&m[f->material[t]]);
    si->lights = dirt_scene_num_lights(si->scene);
    /* "its own lights (2 emissive triangles and 1 punctual light)" */
    char own[160] = "no light of its own", tri[64] = "", pun[64] = "";
    if (si->emitters)
        snprintf(tri, sizeof(tri), "%llu emissive triangle%s", (unsigned long long)si->emitters,
                 si->emitters == 1 ? "" : "s");
    if (si->lights)
        snprintf(pun, sizeof(pun), "%zu punctual light%s", si->lights, si->lights == 1 ? "" : "s");
    if (si->emitters || si->lights)
        snprintf(own, sizeof(own), "its own lights (%s%s%s)", tri,
                 si->emitters && si->lights ? " and " : "", pun);
    memset(si->background, 0, sizeof(si->background));
    si->env = NULL;
    if (o->env_path) {
        si->source = "--env";
        si->environment = !strcmp(o->env_path, "sky") ? "sky" : "map";
        si->env = env_map;
        float in = o->env.intensity > 0 ? o->env.intensity : 1;
        snprintf(si->summary, sizeof(si->summary),
                 "--env %s (intensity %g, rotation %g deg) and %s", o->env_path,
                 shortest(in), shortest(o->env.rotation), own);
        snprintf(si->key, sizeof(si->key), "env=%s,%g,%g", o->env_path, shortest(in),
                 shortest(o->env.rotation));
    } else if (o->background_set) {
        si->source = "--background";
        si->environment = "background";
        memcpy(si->background, o->background, sizeof(si->background));
        double r = shortest(o->background[0]), g = shortest(o->background[1]),
               b = shortest(o->background[2]);
        snprintf(si->summary, sizeof(si->summary),
                 "--background %g,%g,%g (a constant environment) and %s", r, g, b,
                 own);
        snprintf(si->key, sizeof(si->key), "bg=%g,%g,%g", r, g, b);
    } else if (si->emitters || si->lights) {
        si->source = "scene";
        si->environment = "none";
        snprintf(si->summary, sizeof(si->summary),
                 "as authored: %s; no environment (black)", own);
        snprintf(si->key, sizeof(si->key), "scene");
    } else {
        if (!*sky && !(*sky = dirt_env_sky(NULL)))
            return false;
        si->source = "fallback";
        si->environment = "sky";
        si->env = *sky;
        snprintf(si->summary, sizeof(si->summary),
                 "fallback: no light of its own, so the built-in sky (as --env sky)");
        snprintf(si->key, sizeof(si->key), "sky");
    }
    return true;
}

static dirt_session_opts session_opts(const scene_info *si, const config *c, enum dirt_engine e,
                                      float thickness, uint32_t seed)
{
    return (dirt_session_opts){.face_size = g_face,
        .engine = e, .width = c->w, .height = c->h, .views = (enum dirt_session_views)c->views,
        .tile_size = e == DIRT_ENGINE_DIRT ? c->tile : 0,
        .buckets = e == DIRT_ENGINE_DIRT ? c->dbuckets : c->mbuckets,
        .large = g_large ? g_large : -1, .large_grid = g_large_grid, .sub_tiles = g_sub_tiles,
        .bucket_masks = g_bucket_masks, .node_depths = g_node_depths,
        .depth_buckets = e == DIRT_ENGINE_DIRT ? g_depth_buckets : DIRT_DEPTH_BUCKETS_UNIFORM,
        .march = (enum dirt_mmrt_march)c->march, .march_samples = c->samples,
        .thickness = thickness,
        .bounces = c->bounces, .seed = seed, .env = si->env,
        .background = {si->background[0], si->background[1], si->background[2]}};
}

static const char *ray_key(int t)
{
    return dirt_ray_type_names[t];
}

/* Measures one technique; NULL with `why` on failure. */
static cJSON *measure(dirt_gpu *gpu, const scene_info *si, const config *c, enum dirt_engine e,
                      float thickness, const options *o, const dirt_image *ref, char *why,
                      size_t whysz, const char *image_path)
{
    dirt_session_opts so = session_opts(si, c, e, thickness, o->seed);
    dirt_session *s = dirt_session_create(gpu, si->scene, &so);
    if (!s) {
        set_reason(why, whysz, dirt_engine_names[e], "the session could not be made");
        return NULL;
    }
    bool ok = true;
    for (int r = 0; ok && r < o->warmup; r++)
        ok = dirt_session_set_time(s, c->time, NULL) &&
             dirt_session_add_samples(s, c->spp, NULL, NULL);
    static double pass_ms[32][MAX_REPEAT], build[MAX_REPEAT], trace[MAX_REPEAT],
        total[MAX_REPEAT], frame[MAX_REPEAT];
    dirt_session_stats st;
    memset(&st, 0, sizeof(st));
    enum dirt_clock pass_clock[32] = {0};
    for (int r = 0; ok && r < o->repeat; r++) {
        /* set_time restarts the accumulation and marks the frame changed:
         * every repeat rebuilds the structure and traces spp samples. */
        ok = dirt_session_set_time(s, c->time, NULL) &&
             dirt_session_add_samples(s, c->spp, NULL, NULL);
        if (!ok)
            break;
        /* this repeat's pass times, complete (GPU clock: they come late) */
        dirt_session_drain_times(s);
        st = *dirt_session_get_stats(s);
        for (int p = 0; p < st.num_passes && p < 32; p++) {
            pass_ms[p][r] = st.passes[p].ms;
            if (r && pass_clock[p] != st.passes[p].clock) {
                snprintf(why, whysz, "%s: pass %s changed clock between repeats",
                         dirt_engine_names[e], st.passes[p].name);
                ok = false;
            }
            pass_clock[p] = st.passes[p].clock;
        }
        build[r] = st.build_ms, trace[r] = st.trace_ms, total[r] = st.total_ms;
        /* The whole frame: every pass, the structure's and the path
         * tracer's (raygen, traces, fetch, shade, resolve, accumulate). */
        frame[r] = 0.0;
        for (int p = 0; p < st.num_passes; p++)
            frame[r] += st.passes[p].ms;
    }
    const dirt_image *img = ok ? dirt_session_image(s) : NULL;
    if (!ok || !img) {
        if (!why[0])
            set_reason(why, whysz, dirt_engine_names[e], "build or render failed");
        dirt_session_destroy(s);
        return NULL;
    }
    if (st.aborted)
        DIRT_WARN("%s: %llu rays aborted", dirt_engine_names[e], (unsigned long long)st.aborted);
    cJSON *j = cJSON_CreateObject();
    cJSON *passes = cJSON_AddArrayToObject(j, "passes");
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    for (int p = 0; p < st.num_passes && p < 32; p++) {
        cJSON *pj = stat_json(pass_ms[p], o->repeat, pass_clock[p]);
        cJSON_AddStringToObject(pj, "name", st.passes[p].name);
        cJSON_AddItemToArray(passes, pj);
        if (pass_clock[p] != DIRT_CLOCK_NONE)
            clock = pass_clock[p];
    }
    /* The build and trace sums are in the passes' one clock (the session
     * never mixes: dirt_gpu_clock). */
    cJSON_AddItemToObject(j, "build", stat_json(build, o->repeat, clock));
    cJSON_AddItemToObject(j, "trace", stat_json(trace, o->repeat, clock));
    cJSON_AddItemToObject(j, "frame", stat_json(frame, o->repeat, clock));
    cJSON_AddItemToObject(j, "total", stat_json(total, o->repeat, DIRT_CLOCK_CPU));
    cJSON_AddNumberToObject(j, "rays", (double)st.rays);
    cJSON_AddNumberToObject(j, "aborted", (double)st.aborted);
    cJSON_AddNumberToObject(j, "mrays_per_s", st.mrays_per_s);
    cJSON *mem = cJSON_AddObjectToObject(j, "memory");
    cJSON *bufs = cJSON_AddArrayToObject(mem, "buffers");
    for (int b = 0; b < st.num_buffers; b++) {
        cJSON *bj = cJSON_CreateObject();
        cJSON_AddStringToObject(bj, "name", st.buffers[b].name);
        cJSON_AddNumberToObject(bj, "used", (double)st.buffers[b].used);
        cJSON_AddNumberToObject(bj, "allocated", (double)st.buffers[b].allocated);
        cJSON_AddItemToArray(bufs, bj);
    }
    cJSON_AddNumberToObject(mem, "session_used", (double)st.bytes_total_used);
    cJSON_AddNumberToObject(mem, "session_allocated", (double)st.bytes_total_allocated);
    /* The structure's bytes and the paper's formula for them. */
    double formula = 0, exact_formula = 0, exact_measured = 0, extra = 0;
    const char *formula_name, *note;
    if (st.has_ads) {
        const dirt_ads_stats *a = &st.ads;
        double tiles = (double)a->tiles;
        formula_name = "dirt_table3";
        formula = a->bytes_table3;
        /* Table 3 = tiles (8 B x 1.33 + 4 B x B) + 8 B x c n_p: heads and
         * nodes are exact; the 1.33 stands for the pyramid's real levels. */
        exact_formula = formula - 8.0 * 1.33 * tiles;
        /* (the nodes' bytes: the pool's used bytes are more where the
         * compute build's work records took more of it) */
        exact_measured = (double)a->bytes_heads + 8.0 * (double)a->nodes;
        extra = (double)a->bytes_depth - 8.0 * 1.33 * tiles;
        note = "heads + id nodes equal 4 B x B x tiles + 8 B x c x n_p exactly; the depth "
               "bounds are the real pyramid levels (the formula estimates them as 1.33 x "
               "8 B per tile; depth_extra = measured - estimate); the vertex buffer and the "
               "bucket occupancy masks (--bucket-masks: 4 B per tile, B <= 32) are not in the "
               "formula";
        cJSON_AddStringToObject(j, "records_kind", "id_nodes");
        cJSON_AddNumberToObject(j, "records", (double)a->nodes);
        cJSON_AddNumberToObject(j, "samples_np", (double)a->samples);
        cJSON_AddNumberToObject(j, "buckets_per_sample", a->buckets_per_sample);
        cJSON_AddNumberToObject(j, "large_primitives", a->num_large);
        cJSON_AddNumberToObject(mem, "structure_used", (double)a->bytes_total_used);
        cJSON_AddNumberToObject(mem, "structure_allocated", (double)a->bytes_total_allocated);
        cJSON_AddNumberToObject(mem, "tiles", tiles);
    } else {
        const dirt_mmrt_stats *m = &st.mmrt;
        formula_name = "mmrt_dllb";
        formula = m->bytes_paper;
        /* pixels (8 B depth + 8 B x B heads/tails) + fragments (12 + 32 B):
         * level 0 of the depth bounds, heads, id and data nodes. */
        exact_formula = formula;
        exact_measured = 8.0 * (double)m->pixels + (double)(m->bytes_heads +
                         m->bytes_id_nodes_used + m->bytes_data_nodes_used);
        extra = (double)m->bytes_depth - 8.0 * (double)m->pixels;
        note = "level 0 of the depth bounds + heads/tails + id and data nodes equal pixels x "
               "(8 + 8 B) + fragments x (12 + 32) B exactly; the Hi-Z levels above 0 "
               "(depth_extra) and the vertex buffer are not in the formula";
        cJSON_AddStringToObject(j, "records_kind", "fragments");
        cJSON_AddNumberToObject(j, "records", (double)m->fragments);
        cJSON_AddNumberToObject(j, "max_layers", m->max_layers);
        cJSON_AddNumberToObject(mem, "structure_used", (double)m->bytes_total_used);
        cJSON_AddNumberToObject(mem, "structure_allocated", (double)m->bytes_total_allocated);
        cJSON_AddNumberToObject(mem, "tiles", (double)m->pixels);
    }
    cJSON *fj = cJSON_AddObjectToObject(mem, "formula");
    cJSON_AddStringToObject(fj, "name", formula_name);
    cJSON_AddNumberToObject(fj, "bytes", formula);
    cJSON_AddNumberToObject(fj, "exact_part_formula", exact_formula);
    cJSON_AddNumberToObject(fj, "exact_part_measured", exact_measured);
    cJSON_AddBoolToObject(fj, "equal", fabs(exact_formula - exact_measured) < 0.5);
    cJSON_AddNumberToObject(fj, "depth_extra", extra);
    cJSON_AddStringToObject(fj, "note", note);
    cJSON_AddNumberToObject(j, "rel_mse", ref ? dirt_image_rel_mse(img, ref) : NAN);
    if (image_path)
        cli_write_image(PROG, img, image_path, 0, false, true);
    if (o->quality) {
        dirt_session_agreement ag;
        int aw = o->agree_w ? o->agree_w : c->w, ah = o->agree_h ? o->agree_h : c->h;
        if (!dirt_session_hit_agreement(s, aw, ah, o->seed, &ag)) {
            set_reason(why, whysz, dirt_engine_names[e], "hit agreement failed");
            cJSON_Delete(j);
            dirt_session_destroy(s);
            return NULL;
        }
        cJSON *aj = cJSON_AddObjectToObject(j, "agreement");
        cJSON *fr = cJSON_AddObjectToObject(aj, "fraction");
        cJSON *rj = cJSON_AddObjectToObject(aj, "rays");
        cJSON *mj = cJSON_AddObjectToObject(aj, "trace_ms");
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            cJSON_AddNumberToObject(fr, ray_key(t), ag.fraction[t]);
            cJSON_AddNumberToObject(rj, ray_key(t), (double)ag.rays[t]);
            cJSON_AddNumberToObject(mj, ray_key(t), ag.ms[t]);
        }
        cJSON_AddStringToObject(aj, "clock", dirt_clock_names[ag.clock]);
        cJSON_AddNumberToObject(aj, "aborted", (double)ag.aborted);
        cJSON_AddNumberToObject(aj, "gbuffer_width", aw);
        cJSON_AddNumberToObject(aj, "gbuffer_height", ah);
        if (e == DIRT_ENGINE_MMRT)
            cJSON_AddNumberToObject(j, "thickness_used", ag.thickness);
    }
    if (o->count_work) {
        /* Counted once, on the last repeat's structure (the session counts
         * at the build it is asked for; no restart, the image is kept). */
        dirt_session_opts wo = *dirt_session_get_opts(s);
        wo.count_work = true;
        cJSON *sj = NULL;
        if (dirt_session_set_opts(s, &wo, NULL) && dirt_session_build(s))
            sj = dirt_session_stats_json(dirt_session_get_stats(s));
        cJSON *wj = sj ? cJSON_DetachItemFromObject(sj, "work") : NULL;
        cJSON_Delete(sj);
        if (!wj) {
            set_reason(why, whysz, dirt_engine_names[e], "work counting failed");
            cJSON_Delete(j);
            dirt_session_destroy(s);
            return NULL;
        }
        cJSON_AddItemToObject(j, "work", wj);
    }
    dirt_session_destroy(s);
    return j;
}

static void config_id(const options *o, const scene_info *si, const config *c, char *buf,
                      size_t n)
{
    char march[32];
    snprintf(march, sizeof(march), "%s", march_names[c->march]);
    if (c->march == DIRT_MMRT_MARCH_LINEAR && c->samples) /* linear alone: 30 samples */
        snprintf(march, sizeof(march), "linear%d", c->samples);
    snprintf(buf, n, "%s|%dx%d|f%d|%s|t%g|spp%d|k%d|S%d|Bd%d|L%d|Bm%d|th%g|%s|w%d|r%d|q%d|s%u|%s",
             si->path, c->w, c->h, o->face, view_names[c->views], c->time, c->spp, c->bounces, c->tile,
             c->dbuckets, o->large, c->mbuckets, c->thickness, march, o->warmup,
             o->repeat, o->quality ? 1 : 0, o->seed, si->key);
    if (o->large_grid) /* (ids without it as before: earlier runs' rows still match) */
        snprintf(buf + strlen(buf), n - strlen(buf), "|G1");
    if (o->sub_tiles) /* (likewise) */
        snprintf(buf + strlen(buf), n - strlen(buf), "|T1");
    if (o->bucket_masks) /* (likewise) */
        snprintf(buf + strlen(buf), n - strlen(buf), "|M1");
    if (o->node_depths) /* (likewise) */
        snprintf(buf + strlen(buf), n - strlen(buf), "|N1");
}

static void ratio(cJSON *to, const char *name, double dirt, double mmrt)
{
    cJSON_AddNumberToObject(to, name, mmrt > 0 ? dirt / mmrt : NAN);
}

static double jnum(const cJSON *o, const char *a, const char *b)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, a);
    if (b)
        x = cJSON_GetObjectItemCaseSensitive(x, b);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

typedef struct env {
    char machine[256], renderer[512], clock[8];
} env;

static void machine_string(char *buf, size_t n)
{
    struct utsname u;
    char cpu[160] = "unknown CPU";
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[256];
    while (f && fgets(line, sizeof(line), f)) {
        if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
            snprintf(cpu, sizeof(cpu), "%s", strchr(line, ':') + 2);
            cpu[strcspn(cpu, "\n")] = 0;
            break;
        }
    }
    if (f)
        fclose(f);
    uname(&u);
    snprintf(buf, n, "%s %s %s, %s, %ld CPUs", u.sysname, u.release, u.machine, cpu,
             sysconf(_SC_NPROCESSORS_ONLN));
}

/* 64-bit FNV-1a of a configuration's id: its images' names, the same in
 * every run whatever the sweep around it (a position in the sweep is not:
 * a rerun with longer lists would overwrite the images of kept rows). */
static unsigned long long id_hash(const char *id)
{
    unsigned long long h = 1469598103934665603ull;
    for (const unsigned char *p = (const unsigned char *)id; *p; p++)
        h = (h ^ *p) * 1099511628211ull;
    return h;
}

/* One configuration: DIRT, MMRT and the Embree reference; the row. */
static cJSON *run_config(dirt_gpu *gpu, const scene_info *si, const config *c,
                         const options *o, const env *ev, const char *id)
{
    char why[512] = "";
    g_first_error[0] = 0;
    double t0 = dirt_clock_ms();
    float th = (float)(c->thickness < 0 ? -c->thickness * si->diagonal : c->thickness);
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "id", id);
    cJSON *sj = cJSON_AddObjectToObject(row, "scene");
    cJSON_AddStringToObject(sj, "path", si->path);
    cJSON_AddStringToObject(sj, "name", si->name);
    cJSON_AddNumberToObject(sj, "triangles", (double)si->triangles);
    cJSON_AddNumberToObject(sj, "diagonal", si->diagonal);
    cJSON *set = cJSON_AddObjectToObject(row, "settings");
    cJSON_AddNumberToObject(set, "width", c->w);
    cJSON_AddNumberToObject(set, "height", c->h);
    cJSON_AddNumberToObject(set, "face_size", o->face);
    cJSON_AddStringToObject(set, "views", view_names[c->views]);
    cJSON_AddNumberToObject(set, "time", c->time);
    cJSON_AddNumberToObject(set, "spp", c->spp);
    cJSON_AddNumberToObject(set, "bounces", c->bounces);
    cJSON_AddNumberToObject(set, "dirt_tile_size", c->tile);
    cJSON_AddNumberToObject(set, "dirt_buckets", c->dbuckets);
    cJSON_AddNumberToObject(set, "dirt_large", o->large);
    cJSON_AddBoolToObject(set, "dirt_large_grid", o->large_grid);
    cJSON_AddBoolToObject(set, "dirt_sub_tiles", o->sub_tiles);
    cJSON_AddBoolToObject(set, "dirt_bucket_masks", o->bucket_masks);
    cJSON_AddBoolToObject(set, "dirt_node_depths", o->node_depths);
    cJSON_AddStringToObject(set, "dirt_depth_buckets", app_depth_buckets_names[g_depth_buckets]);
    cJSON_AddNumberToObject(set, "mmrt_buckets", c->mbuckets);
    cJSON_AddNumberToObject(set, "mmrt_thickness", th);
    cJSON_AddBoolToObject(set, "mmrt_thickness_default", th == 0);
    cJSON_AddStringToObject(set, "mmrt_march", march_names[c->march]);
    cJSON_AddNumberToObject(set, "mmrt_samples",
                            c->march == DIRT_MMRT_MARCH_LINEAR ? (c->samples ? c->samples : 30) : 0);
    cJSON_AddBoolToObject(set, "mmrt_default",
                          th == 0 && c->march == DIRT_MMRT_MARCH_HIZ);
    cJSON_AddNumberToObject(set, "warmup", o->warmup);
    cJSON_AddNumberToObject(set, "repeat", o->repeat);
    cJSON_AddNumberToObject(set, "seed", o->seed);
    cJSON *lj = cJSON_AddObjectToObject(row, "lighting");
    cJSON_AddStringToObject(lj, "source", si->source);
    cJSON_AddStringToObject(lj, "summary", si->summary);
    cJSON_AddNumberToObject(lj, "emitter_triangles", (double)si->emitters);
    cJSON_AddNumberToObject(lj, "punctual_lights", (double)si->lights);
    cJSON_AddStringToObject(lj, "environment", si->environment);
    if (o->env_path)
        cJSON_AddStringToObject(lj, "env", o->env_path);
    else
        cJSON_AddNullToObject(lj, "env");
    cJSON_AddNumberToObject(lj, "env_intensity", o->env.intensity > 0 ? o->env.intensity : 1);
    cJSON_AddNumberToObject(lj, "env_rotation", o->env.rotation);
    cJSON *bj = cJSON_AddArrayToObject(lj, "background");
    for (int k = 0; k < 3; k++)
        cJSON_AddItemToArray(bj, cJSON_CreateNumber(shortest(si->background[k])));
    cJSON *ej = cJSON_AddObjectToObject(row, "environment");
    cJSON_AddStringToObject(ej, "machine", ev->machine);
    cJSON_AddStringToObject(ej, "renderer", ev->renderer);
    cJSON_AddStringToObject(ej, "clock", ev->clock);
    cJSON_AddStringToObject(ej, "commit", dirt_version_commit());
    /* The reference: Embree with the same seed, camera and settings. */
    const dirt_image *ref = NULL;
    dirt_session *rs = NULL;
    if (o->quality) {
        dirt_session_opts ro = session_opts(si, c, DIRT_ENGINE_EMBREE, 0, o->seed);
        rs = dirt_session_create(gpu, si->scene, &ro);
        ref = rs && dirt_session_set_time(rs, c->time, NULL) &&
                      dirt_session_add_samples(rs, c->spp, NULL, NULL)
                  ? dirt_session_image(rs)
                  : NULL;
        if (!ref)
            set_reason(why, sizeof(why), "embree", "the reference failed");
        else
            cJSON_AddNumberToObject(cJSON_AddObjectToObject(row, "embree"), "total_ms",
                                    dirt_session_get_stats(rs)->total_ms);
    }
    char ipath[3][1024];
    if (o->images) {
        cJSON *ij = cJSON_AddObjectToObject(row, "images"); /* relative to DIR */
        for (int k = 0; k < 3; k++) {
            const char *e = k == 0 ? "dirt" : k == 1 ? "mmrt" : "embree";
            char rel[64];
            snprintf(rel, sizeof(rel), "images/%016llx_%s.png", id_hash(id), e);
            snprintf(ipath[k], sizeof(ipath[k]), "%s/%s", o->dir, rel);
            cJSON_AddStringToObject(ij, e, rel);
        }
    }
    if (ref && o->images)
        cli_write_image(PROG, ref, ipath[2], 0, false, true);
    cJSON *dj = why[0] ? NULL
                       : measure(gpu, si, c, DIRT_ENGINE_DIRT, 0, o, ref, why, sizeof(why),
                                 o->images ? ipath[0] : NULL);
    cJSON *mj = why[0] ? NULL
                       : measure(gpu, si, c, DIRT_ENGINE_MMRT, th, o, ref, why, sizeof(why),
                                 o->images ? ipath[1] : NULL);
    dirt_session_destroy(rs);
    if (dj && mj) {
        cJSON_AddItemToObject(row, "dirt", dj);
        cJSON_AddItemToObject(row, "mmrt", mj);
        cJSON *r = cJSON_AddObjectToObject(row, "ratios");
        ratio(r, "records", jnum(dj, "records", NULL), jnum(mj, "records", NULL));
        ratio(r, "memory", jnum(dj, "memory", "structure_used"),
              jnum(mj, "memory", "structure_used"));
        ratio(r, "build", jnum(dj, "build", "median_ms"), jnum(mj, "build", "median_ms"));
        ratio(r, "trace", jnum(dj, "trace", "median_ms"), jnum(mj, "trace", "median_ms"));
        ratio(r, "frame", jnum(dj, "frame", "median_ms"), jnum(mj, "frame", "median_ms"));
        cJSON_AddStringToObject(row, "status", "ok");
        cJSON_AddNullToObject(row, "reason");
    } else {
        cJSON_Delete(dj);
        cJSON_Delete(mj);
        cJSON_AddStringToObject(row, "status", "failed");
        cJSON_AddStringToObject(row, "reason", why[0] ? why : "unknown failure");
    }
    cJSON_AddNumberToObject(row, "seconds", (dirt_clock_ms() - t0) / 1000.0);
    return row;
}

static bool dir_ok(const char *dir)
{
    /* DIR and its missing parents, as dirt-render makes its outputs' folders */
    struct stat sb;
    char inside[4200], why[4400];
    snprintf(inside, sizeof(inside), "%s/.", dir);
    if (!seq_make_parent_dirs(inside, why, sizeof(why))) {
        cli_error(PROG, "%s", why);
        return false;
    }
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode) || access(dir, W_OK | X_OK) != 0) {
        cli_error(PROG, "%s is not a writable directory", dir);
        return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    static app_opts ao; /* its lists are large */
    app_opts_init(&app_compare_program, &ao);
    int prc = app_parse(&app_compare_program, argc, argv, &ao);
    if (prc != APP_PARSE_OK || ao.help || ao.version) {
        if (prc == APP_PARSE_OK && ao.help)
            app_print_help(&app_compare_program, stdout);
        else if (prc == APP_PARSE_OK)
            prc = app_version(PROG, &ao);
        app_opts_free(&ao);
        return prc;
    }
    options o;
    bool parsed = app_check(&app_compare_program, &ao) && from_app(&ao, &o);
    if (!parsed) {
        app_opts_free(&ao);
        return DIRT_EXIT_USAGE;
    }
    g_face = o.face;
    g_large = o.large;
    g_large_grid = o.large_grid;
    g_sub_tiles = o.sub_tiles;
    g_bucket_masks = o.bucket_masks;
    g_node_depths = o.node_depths;
    g_depth_buckets = ao.s.depth_buckets;
    dirt_log_set_callback(log_sink, NULL);
    if (!o.num_scenes || !o.dir) {
        cli_error(PROG, "%s (see --help)", !o.num_scenes ? "no SCENE given" : "-o DIR is needed");
        app_opts_free(&ao);
        return DIRT_EXIT_USAGE;
    }
    /* Bad input up front: scenes, DIR, configurations. */
    char images_dir[4200];
    snprintf(images_dir, sizeof(images_dir), "%s/images", o.dir);
    scene_info si[MAX_SCENES];
    memset(si, 0, sizeof(si));
    int rc = DIRT_EXIT_OK;
    dirt_env *env_map = NULL, *sky = NULL; /* --env; the fallback */
    if (!app_load_env(PROG, &ao, &env_map))
        rc = DIRT_EXIT_USAGE;
    for (int i = 0; i < o.num_scenes && rc == DIRT_EXIT_OK; i++) {
        si[i].path = o.scenes[i];
        bool def = !strcmp(o.scenes[i], "default");
        si[i].name = def ? "default" : strrchr(o.scenes[i], '/') ? strrchr(o.scenes[i], '/') + 1
                                                               : o.scenes[i];
        if (!(si[i].scene = app_load_scene(PROG, o.scenes[i], &ao))) {
            rc = DIRT_EXIT_USAGE;
            break;
        }
        /* DIR is the outputs': no scene file (nor file of a scene), preset
         * or --env map in it. */
        bool env_file = ao.env_path && strcmp(ao.env_path, "sky");
        cli_io io = {.scene_path = def ? NULL : o.scenes[i], .scene = si[i].scene,
                     .in = {{env_file ? ao.env_path : NULL, "--env"}},
                     .out_dirs = {{o.dir, "", "-o DIR"}, {images_dir, "", "-o DIR"}}};
        for (int k = 0; k < ao.num_presets && k + 1 < CLI_IO_MAX; k++)
            io.in[k + 1][0] = ao.presets[k], io.in[k + 1][1] = "--preset";
        if (cli_check_io(PROG, &io) != DIRT_EXIT_OK) {
            rc = DIRT_EXIT_USAGE;
            break;
        }
        dirt_frame *f = dirt_scene_evaluate(si[i].scene, 0, NULL);
        if (f) {
            si[i].triangles = f->num_triangles;
            double d2 = 0;
            for (int k = 0; k < 3; k++)
                d2 += (double)(f->bounds_max[k] - f->bounds_min[k]) *
                      (f->bounds_max[k] - f->bounds_min[k]);
            si[i].diagonal = sqrt(d2);
        }
        if (!f || !resolve_lighting(&si[i], f, &o, env_map, &sky)) {
            cli_error(PROG, "%s: out of memory (see above)", o.scenes[i]);
            rc = DIRT_EXIT_FAILURE;
        }
        dirt_frame_destroy(f);
    }
    if (rc == DIRT_EXIT_OK && !dir_ok(o.dir))
        rc = DIRT_EXIT_USAGE;
    if (rc == DIRT_EXIT_OK && o.images) {
        char p[1024];
        snprintf(p, sizeof(p), "%s/images", o.dir);
        if (!dir_ok(p))
            rc = DIRT_EXIT_USAGE;
    }
    /* The sweep, MMRT's settings innermost. */
    size_t total = (size_t)o.num_scenes * o.w.n * o.views.n * o.time.n * o.spp.n *
                   o.bounces.n * o.tile.n * o.dbuckets.n * o.mbuckets.n * o.march.n *
                   o.samples.n * o.thickness.n;
    config *cfg = rc == DIRT_EXIT_OK ? calloc(total ? total : 1, sizeof(*cfg)) : NULL;
    size_t n = 0;
    if (rc == DIRT_EXIT_OK && !cfg)
        rc = DIRT_EXIT_FAILURE;
    for (int a = 0; cfg && a < o.num_scenes; a++)
        for (int b = 0; b < o.w.n; b++)
            for (int c = 0; c < o.views.n; c++)
                for (int d = 0; d < o.time.n; d++)
                    for (int e = 0; e < o.spp.n; e++)
                        for (int f = 0; f < o.bounces.n; f++)
                            for (int g = 0; g < o.tile.n; g++)
                                for (int h = 0; h < o.dbuckets.n; h++)
                                    for (int i = 0; i < o.mbuckets.n; i++)
                                        for (int j = 0; j < o.march.n; j++)
                                            for (int l = 0; l < o.samples.n; l++)
                                                for (int k = 0; k < o.thickness.n; k++) {
                                                    /* Hi-Z takes no samples: one row */
                                                    bool hiz = o.march.v[j] == DIRT_MMRT_MARCH_HIZ;
                                                    if (hiz && l > 0)
                                                        continue;
                                                    cfg[n++] = (config){
                                                        a, o.w.v[b], o.h.v[b], o.views.v[c],
                                                        o.tile.v[g], o.dbuckets.v[h],
                                                        o.mbuckets.v[i], o.march.v[j],
                                                        hiz ? 0 : o.samples.v[l], o.spp.v[e],
                                                        o.bounces.v[f], o.thickness.v[k],
                                                        o.time.v[d]};
                                                }
    dirt_gpu *gpu = NULL;
    if (rc == DIRT_EXIT_OK) {
        if (!(gpu = app_gpu(PROG, &ao)))
            rc = DIRT_EXIT_NO_GPU;
    }
    env ev;
    if (gpu) {
        machine_string(ev.machine, sizeof(ev.machine));
        dirt_gpu_describe(gpu, ev.renderer, sizeof(ev.renderer));
        snprintf(ev.clock, sizeof(ev.clock), "%s", dirt_clock_names[dirt_gpu_clock(gpu)]);
        const dirt_gpu_caps *caps = dirt_gpu_get_caps(gpu);
        for (size_t i = 0; i < n && rc == DIRT_EXIT_OK; i++) {
            char why[256];
            for (int e = 0; e < 2 && rc == DIRT_EXIT_OK; e++) {
                dirt_session_opts so = session_opts(&si[cfg[i].scene], &cfg[i],
                                                    e ? DIRT_ENGINE_MMRT : DIRT_ENGINE_DIRT, 0,
                                                    o.seed);
                if (!dirt_session_check_opts(&so, why, sizeof(why))) {
                    cli_error(PROG, "impossible configuration %dx%d (%s): %s", cfg[i].w,
                              cfg[i].h, dirt_engine_names[so.engine], why);
                    rc = DIRT_EXIT_USAGE;
                }
            }
            /* The views share one raster atlas of the views side by side. */
            long atlas = (long)cfg[i].w + 6L * ((cfg[i].w > cfg[i].h ? cfg[i].w : cfg[i].h) / 2);
            if (rc == DIRT_EXIT_OK && (atlas > caps->max_texture_size ||
                                       cfg[i].h > caps->max_texture_size)) {
                cli_error(PROG, "impossible configuration %dx%d: the views' raster atlas "
                          "(%ld px wide) exceeds the GPU's %d", cfg[i].w, cfg[i].h, atlas,
                          caps->max_texture_size);
                rc = DIRT_EXIT_USAGE;
            }
        }
    }
    /* Resume: rows of an earlier run with the same id and status ok. */
    cJSON *doc = NULL, *rows = NULL, *old = NULL;
    if (rc == DIRT_EXIT_OK) {
        old = compare_read_results(o.dir);
        doc = cJSON_CreateObject();
        cJSON_AddStringToObject(doc, "tool", PROG);
        /* What made the results: the command line, version and commit. */
        app_provenance prov;
        app_provenance_init(&prov, argc, argv, NULL);
        cJSON *pj = cJSON_AddObjectToObject(doc, "provenance");
        cJSON_AddStringToObject(pj, "command_line", prov.command_line);
        cJSON_AddStringToObject(pj, "version", dirt_version());
        cJSON_AddStringToObject(pj, "commit", dirt_version_commit());
        cJSON_AddStringToObject(pj, "device", ev.renderer);
        cJSON_AddNumberToObject(doc, "schema_version", 1);
        rows = cJSON_AddArrayToObject(doc, "configurations");
    }
    size_t done = 0, skipped = 0, failed = 0;
    double measured_s = 0;
    int measured = 0;
    double start = dirt_clock_ms();
    for (size_t i = 0; rc == DIRT_EXIT_OK && i < n; i++) {
        char id[1400];
        config_id(&o, &si[cfg[i].scene], &cfg[i], id, sizeof(id));
        cJSON *row = NULL, *it;
        cJSON_ArrayForEach(it, old)
        {
            const cJSON *oid = cJSON_GetObjectItemCaseSensitive(it, "id");
            const cJSON *st = cJSON_GetObjectItemCaseSensitive(it, "status");
            if (cJSON_IsString(oid) && !strcmp(oid->valuestring, id) && cJSON_IsString(st) &&
                !strcmp(st->valuestring, "ok")) {
                row = cJSON_Duplicate(it, 1);
                break;
            }
        }
        if (row) {
            skipped++;
        } else {
            if (!o.quiet) {
                double eta = measured ? measured_s / measured * (double)(n - i - skipped * 0) : -1;
                (void)eta;
                size_t left = n - i;
                if (measured)
                    fprintf(stderr, PROG ": [%zu/%zu] %s; %.0f s elapsed, ETA %.0f s\n", i + 1, n,
                            id, (dirt_clock_ms() - start) / 1000.0,
                            measured_s / measured * (double)left);
                else
                    fprintf(stderr, PROG ": [%zu/%zu] %s; ETA unknown\n", i + 1, n, id);
            }
            row = run_config(gpu, &si[cfg[i].scene], &cfg[i], &o, &ev, id);
            measured_s += jnum(row, "seconds", NULL);
            measured++;
            const cJSON *st = cJSON_GetObjectItemCaseSensitive(row, "status");
            if (strcmp(st->valuestring, "ok")) {
                failed++;
                cli_error(PROG, "configuration %zu failed: %s", i + 1,
                          cJSON_GetObjectItemCaseSensitive(row, "reason")->valuestring);
            }
        }
        cJSON_AddItemToArray(rows, row);
        done++;
        /* Written as each configuration finishes. */
        if (!compare_write_results(PROG, o.dir, doc))
            rc = DIRT_EXIT_FAILURE;
    }
    if (rc == DIRT_EXIT_OK) {
        if (!compare_write_table(PROG, o.dir, doc) || !compare_write_plots(PROG, o.dir, doc))
            rc = DIRT_EXIT_FAILURE;
        if (!o.quiet)
            fprintf(stderr, PROG ": %zu configurations (%zu measured, %zu from the earlier run, "
                    "%zu failed) in %.1f s; results in %s\n", done, done - skipped, skipped,
                    failed, (dirt_clock_ms() - start) / 1000.0, o.dir);
        if (failed)
            rc = DIRT_EXIT_FAILURE;
    }
    cJSON_Delete(doc);
    cJSON_Delete(old);
    free(cfg);
    dirt_gpu_destroy(gpu);
    for (int i = 0; i < o.num_scenes; i++)
        dirt_scene_destroy(si[i].scene);
    dirt_env_destroy(env_map);
    dirt_env_destroy(sky);
    app_opts_free(&ao);
    return rc;
}
