/* dirt-compare's outputs from the rows (app/compare.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/compare.h"
#include "dirt/file.h"
#include "dirt/raytypes.h"

static const cJSON *jget(const cJSON *o, const char *path)
{
    char buf[128];
    snprintf(buf, sizeof(buf), "%s", path);
    const cJSON *x = o;
    for (char *save = NULL, *tok = strtok_r(buf, ".", &save); tok && x;
         tok = strtok_r(NULL, ".", &save))
        x = cJSON_GetObjectItemCaseSensitive(x, tok);
    return x;
}

static double jd(const cJSON *o, const char *path)
{
    const cJSON *x = jget(o, path);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

static const char *js(const cJSON *o, const char *path)
{
    const cJSON *x = jget(o, path);
    return cJSON_IsString(x) ? x->valuestring : "";
}

static bool row_ok(const cJSON *r)
{
    return !strcmp(js(r, "status"), "ok");
}

typedef struct buf {
    char *p;
    size_t n, cap;
} buf;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void bprintf(buf *b, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int k = vsnprintf(b->p ? b->p + b->n : NULL, b->p ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (k < 0)
            return;
        if (b->p && b->n + (size_t)k < b->cap) {
            b->n += (size_t)k;
            return;
        }
        size_t cap = (b->cap + (size_t)k + 1) * 2;
        char *p = realloc(b->p, cap);
        if (!p)
            return;
        b->p = p, b->cap = cap;
    }
}

static bool write_buf(const char *prog, const char *dir, const char *name, buf *b)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    bool ok = dirt_write_file_atomic(path, b->p ? b->p : "", b->n);
    if (!ok)
        cli_error(prog, "cannot write %s", path);
    free(b->p);
    *b = (buf){0};
    return ok;
}

/* Rows of one scene, resolution, spp and bounces: MMRT's settings vary. */
static bool same_group(const cJSON *p, const cJSON *a)
{
    return !strcmp(js(p, "scene.path"), js(a, "scene.path")) &&
           jd(p, "settings.width") == jd(a, "settings.width") &&
           jd(p, "settings.height") == jd(a, "settings.height") &&
           jd(p, "settings.spp") == jd(a, "settings.spp") &&
           jd(p, "settings.bounces") == jd(a, "settings.bounces");
}

/* "1.921 (0.2 % of the diagonal), hiz" / "..., linear 30". */
static void setting_str(const cJSON *r, char *out, size_t n)
{
    double t = jd(r, "mmrt.thickness_used"), d = jd(r, "scene.diagonal");
    char march[32];
    if (!strcmp(js(r, "settings.mmrt_march"), "linear") && jd(r, "settings.mmrt_samples") > 0)
        snprintf(march, sizeof(march), "linear %.0f", jd(r, "settings.mmrt_samples"));
    else
        snprintf(march, sizeof(march), "%s", js(r, "settings.mmrt_march"));
    snprintf(out, n, "%.4g (%.2g %% of the diagonal), %s", t, d > 0 ? 100 * t / d : NAN, march);
}

/* The CSV's columns: name and the row's JSON path. */
static const char *const csv_cols[][2] = {
    {"id", "id"}, {"status", "status"}, {"reason", "reason"},
    {"scene", "scene.name"}, {"triangles", "scene.triangles"},
    {"width", "settings.width"}, {"height", "settings.height"},
    {"views", "settings.views"}, {"time", "settings.time"}, {"spp", "settings.spp"},
    {"bounces", "settings.bounces"}, {"dirt_tile_size", "settings.dirt_tile_size"},
    {"dirt_buckets", "settings.dirt_buckets"}, {"mmrt_buckets", "settings.mmrt_buckets"},
    {"mmrt_thickness", "settings.mmrt_thickness"},
    {"mmrt_thickness_used", "mmrt.thickness_used"}, {"mmrt_march", "settings.mmrt_march"},
    {"mmrt_samples", "settings.mmrt_samples"},
    {"warmup", "settings.warmup"}, {"repeat", "settings.repeat"},
    {"lighting", "lighting.source"}, {"lighting_environment", "lighting.environment"},
    {"lighting_summary", "lighting.summary"},
    {"clock", "environment.clock"},
    {"mmrt_fragments", "mmrt.records"}, {"mmrt_used_bytes", "mmrt.memory.structure_used"},
    {"mmrt_allocated_bytes", "mmrt.memory.structure_allocated"},
    {"mmrt_formula_bytes", "mmrt.memory.formula.bytes"},
    {"mmrt_build_min_ms", "mmrt.build.min_ms"}, {"mmrt_build_median_ms", "mmrt.build.median_ms"},
    {"mmrt_build_max_ms", "mmrt.build.max_ms"}, {"mmrt_trace_min_ms", "mmrt.trace.min_ms"},
    {"mmrt_trace_median_ms", "mmrt.trace.median_ms"}, {"mmrt_trace_max_ms", "mmrt.trace.max_ms"},
    {"mmrt_rays", "mmrt.rays"}, {"mmrt_rel_mse", "mmrt.rel_mse"},
    {"dirt_id_nodes", "dirt.records"}, {"dirt_samples_np", "dirt.samples_np"},
    {"dirt_used_bytes", "dirt.memory.structure_used"},
    {"dirt_allocated_bytes", "dirt.memory.structure_allocated"},
    {"dirt_formula_bytes", "dirt.memory.formula.bytes"},
    {"dirt_build_min_ms", "dirt.build.min_ms"}, {"dirt_build_median_ms", "dirt.build.median_ms"},
    {"dirt_build_max_ms", "dirt.build.max_ms"}, {"dirt_trace_min_ms", "dirt.trace.min_ms"},
    {"dirt_trace_median_ms", "dirt.trace.median_ms"}, {"dirt_trace_max_ms", "dirt.trace.max_ms"},
    {"dirt_rays", "dirt.rays"}, {"dirt_rel_mse", "dirt.rel_mse"},
    {"ratio_records", "ratios.records"}, {"ratio_memory", "ratios.memory"},
    {"ratio_build", "ratios.build"}, {"ratio_trace", "ratios.trace"},
    {"mmrt_frame_median_ms", "mmrt.frame.median_ms"},
    {"dirt_frame_median_ms", "dirt.frame.median_ms"}, {"ratio_frame", "ratios.frame"},
};

static void csv_field(buf *b, const cJSON *x)
{
    if (cJSON_IsNumber(x)) {
        bprintf(b, "%.10g", x->valuedouble);
    } else if (cJSON_IsString(x)) {
        bprintf(b, "\"");
        for (const char *c = x->valuestring; *c; c++)
            bprintf(b, *c == '"' ? "\"\"" : "%c", *c);
        bprintf(b, "\"");
    } else if (cJSON_IsBool(x)) {
        bprintf(b, cJSON_IsTrue(x) ? "true" : "false");
    }
}

bool compare_write_results(const char *prog, const char *dir, const cJSON *doc)
{
    char *text = cJSON_Print(doc);
    if (!text)
        return false;
    buf b = {0};
    bprintf(&b, "%s\n", text);
    free(text);
    bool ok = write_buf(prog, dir, "results.json", &b);
    size_t ncols = sizeof(csv_cols) / sizeof(csv_cols[0]);
    for (size_t c = 0; c < ncols; c++)
        bprintf(&b, "%s%s", c ? "," : "", csv_cols[c][0]);
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        bprintf(&b, ",dirt_agree_%s,mmrt_agree_%s", dirt_ray_type_names[t],
                dirt_ray_type_names[t]);
    bprintf(&b, "\n");
    const cJSON *r;
    cJSON_ArrayForEach(r, jget(doc, "configurations"))
    {
        for (size_t c = 0; c < ncols; c++) {
            if (c)
                bprintf(&b, ",");
            csv_field(&b, jget(r, csv_cols[c][1]));
        }
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            char p[96];
            for (int e = 0; e < 2; e++) {
                snprintf(p, sizeof(p), "%s.agreement.fraction.%s", e ? "mmrt" : "dirt",
                         dirt_ray_type_names[t]);
                bprintf(&b, ",");
                csv_field(&b, jget(r, p));
            }
        }
        bprintf(&b, "\n");
    }
    return write_buf(prog, dir, "results.csv", &b) && ok;
}

cJSON *compare_read_results(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/results.json", dir);
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = n > 0 ? malloc((size_t)n + 1) : NULL;
    cJSON *doc = NULL;
    if (text && fread(text, 1, (size_t)n, f) == (size_t)n) {
        text[n] = 0;
        doc = cJSON_Parse(text);
    }
    free(text);
    fclose(f);
    cJSON *rows = doc ? cJSON_DetachItemFromObject(doc, "configurations") : NULL;
    cJSON_Delete(doc);
    return cJSON_IsArray(rows) ? rows : (cJSON_Delete(rows), NULL);
}

static double mb(double bytes)
{
    return bytes / 1048576.0;
}

bool compare_write_table(const char *prog, const char *dir, const cJSON *doc)
{
    buf b = {0};
    const cJSON *rows = jget(doc, "configurations"), *r, *first = NULL;
    cJSON_ArrayForEach(r, rows) if (row_ok(r) && !first) first = r;
    bprintf(&b, "# DIRT vs MMRT (dirt-compare)\n\n");
    if (first)
        bprintf(&b, "Machine: %s  \nRenderer: %s  \nCommit: %s  \nTimes: %s clock, median of "
                "%g repeats after %g warm-up (min-max in results.csv/json); build = the "
                "structure's passes, trace = every trace pass of spp samples of path "
                "tracing, frame = every pass: the build and spp whole samples (raygen, "
                "traces, fetch, shade, resolve, accumulate).\n\n",
                js(first, "environment.machine"), js(first, "environment.renderer"),
                js(first, "environment.commit"), js(first, "environment.clock"),
                jd(first, "settings.repeat"), jd(first, "settings.warmup"));
    /* The lighting, per scene (the same in each of its rows). */
    bprintf(&b, "Lighting per scene (the same for MMRT, DIRT and the Embree reference; "
                "doc/compare.md, \"Lighting\"):\n\n");
    cJSON_ArrayForEach(r, rows)
    {
        bool seen = false;
        for (const cJSON *p = rows->child; p != r && !seen; p = p->next)
            seen = !strcmp(js(p, "scene.path"), js(r, "scene.path")) &&
                   !strcmp(js(p, "lighting.summary"), js(r, "lighting.summary"));
        if (!seen)
            bprintf(&b, "- %s: %s\n", js(r, "scene.name"),
                    *js(r, "lighting.summary") ? js(r, "lighting.summary")
                                               : "not recorded (a row of an older run)");
    }
    bprintf(&b, "\n");
    bprintf(&b, "In the layout of the DIRT paper's Table 2 (MMRT / DIRT at equal settings). "
                "Records: MMRT fragments, DIRT id nodes (c n_p). MB: the structure's used "
                "bytes. Ratios DIRT / MMRT.\n\n");
    bprintf(&b, "| scene | triangles | resolution | views | S | B (D/M) | thickness | spp "
                "| MMRT fragments | MMRT MB | MMRT build ms | MMRT trace ms | DIRT entries | "
                "DIRT MB | DIRT build ms | DIRT trace ms | entries ratio | MB ratio | build "
                "ratio | trace ratio | frame ratio | MMRT relMSE | DIRT relMSE | status |\n");
    bprintf(&b, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
                "---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        bprintf(&b, "| %s | %.0f | %.0fx%.0f | %s | %.0f | %.0f/%.0f | %.4g | %.0f |",
                js(r, "scene.name"), jd(r, "scene.triangles"), jd(r, "settings.width"),
                jd(r, "settings.height"), js(r, "settings.views"),
                jd(r, "settings.dirt_tile_size"), jd(r, "settings.dirt_buckets"),
                jd(r, "settings.mmrt_buckets"),
                isnan(jd(r, "mmrt.thickness_used")) ? jd(r, "settings.mmrt_thickness")
                                                    : jd(r, "mmrt.thickness_used"),
                jd(r, "settings.spp"));
        if (!row_ok(r)) {
            bprintf(&b, " | | | | | | | | | | | | | | | | failed: %s |\n", js(r, "reason"));
            continue;
        }
        bprintf(&b, " %.0f | %.2f | %.2f | %.2f | %.0f | %.2f | %.2f | %.2f | %.3f | %.3f | "
                    "%.3f | %.3f | %.3f | %.3g | %.3g | ok |\n",
                jd(r, "mmrt.records"), mb(jd(r, "mmrt.memory.structure_used")),
                jd(r, "mmrt.build.median_ms"), jd(r, "mmrt.trace.median_ms"),
                jd(r, "dirt.records"), mb(jd(r, "dirt.memory.structure_used")),
                jd(r, "dirt.build.median_ms"), jd(r, "dirt.trace.median_ms"),
                jd(r, "ratios.records"), jd(r, "ratios.memory"), jd(r, "ratios.build"),
                jd(r, "ratios.trace"), jd(r, "ratios.frame"), jd(r, "mmrt.rel_mse"),
                jd(r, "dirt.rel_mse"));
    }
    /* Memory against the formulas. */
    bprintf(&b, "\n## Memory against the analytic formulas\n\n"
                "DIRT: its Table 3 (`bytes_table3`); MMRT: the DLLB formula of its paper "
                "(`bytes_paper`). \"exact part\": the terms the formula counts exactly, "
                "measured vs formula; depth extra: measured depth bounds minus what the "
                "formula counts for them (by design, see doc/compare.md).\n\n"
                "| scene | resolution | technique | used MB | allocated MB | formula MB | "
                "exact part measured | exact part formula | equal | depth extra B |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        if (!row_ok(r))
            continue;
        for (int e = 0; e < 2; e++) {
            const cJSON *m = jget(r, e ? "dirt.memory" : "mmrt.memory");
            bprintf(&b, "| %s | %.0fx%.0f | %s | %.3f | %.3f | %.3f | %.0f | %.0f | %s | %.0f |\n",
                    js(r, "scene.name"), jd(r, "settings.width"), jd(r, "settings.height"),
                    e ? "DIRT" : "MMRT", mb(jd(m, "structure_used")),
                    mb(jd(m, "structure_allocated")), mb(jd(m, "formula.bytes")),
                    jd(m, "formula.exact_part_measured"), jd(m, "formula.exact_part_formula"),
                    cJSON_IsTrue(jget(m, "formula.equal")) ? "yes" : "**no**",
                    jd(m, "formula.depth_extra"));
        }
    }
    /* Agreement. */
    bprintf(&b, "\n## Hit agreement with Embree per ray type (%%)\n\n| scene | resolution | "
                "thickness | technique |");
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        bprintf(&b, " %s |", dirt_ray_type_names[t]);
    bprintf(&b, "\n|---|---|---|---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        if (!row_ok(r) || !jget(r, "dirt.agreement"))
            continue;
        for (int e = 0; e < 2; e++) {
            bprintf(&b, "| %s | %.0fx%.0f | %.4g | %s |", js(r, "scene.name"),
                    jd(r, "settings.width"), jd(r, "settings.height"),
                    jd(r, "mmrt.thickness_used"), e ? "MMRT" : "DIRT");
            for (int t = 0; t < DIRT_RAY_TYPES; t++) {
                char p[96];
                snprintf(p, sizeof(p), "%s.agreement.fraction.%s", e ? "mmrt" : "dirt",
                         dirt_ray_type_names[t]);
                bprintf(&b, " %.2f |", 100 * jd(r, p));
            }
            bprintf(&b, "\n");
        }
    }
    /* MMRT's best setting per scene (thickness, march, samples) beside its
     * default (default thickness, Hi-Z), with their images. */
    bprintf(&b, "\n## MMRT's best setting per scene (relMSE of the path-traced image vs "
                "Embree)\n\nDefault: MMRT's default thickness (0.2 %% of the scene's diagonal) "
                "and the Hi-Z march; best: the lowest relMSE over the thicknesses, marches and "
                "samples swept at that scene, resolution and spp.\n\n"
                "| scene | resolution | spp | default | relMSE at default | best setting | "
                "relMSE at best | DIRT relMSE | images (MMRT default, MMRT best, Embree) |\n"
                "|---|---|---|---|---|---|---|---|---|\n");
    int nrows = cJSON_GetArraySize(rows);
    for (int i = 0; i < nrows; i++) {
        const cJSON *a = cJSON_GetArrayItem(rows, i);
        if (!row_ok(a))
            continue;
        bool seen = false;
        for (int k = 0; k < i && !seen; k++) {
            const cJSON *p = cJSON_GetArrayItem(rows, k);
            seen = row_ok(p) && same_group(p, a);
        }
        if (seen)
            continue;
        const cJSON *def = NULL, *best = NULL;
        for (int k = i; k < nrows; k++) {
            const cJSON *p = cJSON_GetArrayItem(rows, k);
            if (!row_ok(p) || !same_group(p, a))
                continue;
            bool is_def = cJSON_IsTrue(jget(p, "settings.mmrt_default")) ||
                          (!jget(p, "settings.mmrt_default") &&
                           cJSON_IsTrue(jget(p, "settings.mmrt_thickness_default")) &&
                           !strcmp(js(p, "settings.mmrt_march"), "hiz"));
            if (is_def && !def)
                def = p;
            if (!best || jd(p, "mmrt.rel_mse") < jd(best, "mmrt.rel_mse"))
                best = p;
        }
        char ds[96] = "not swept (add 0 and hiz)", de[32] = "-", bs[96], im[256] = "-";
        if (def) {
            setting_str(def, ds, sizeof(ds));
            snprintf(de, sizeof(de), "%.4g", jd(def, "mmrt.rel_mse"));
        }
        setting_str(best, bs, sizeof(bs));
        if (*js(best, "images.mmrt"))
            snprintf(im, sizeof(im), "%s%s%s, [best](%s), [Embree](%s)",
                     def && *js(def, "images.mmrt") ? "[default](" : "",
                     def && *js(def, "images.mmrt") ? js(def, "images.mmrt") : "-",
                     def && *js(def, "images.mmrt") ? ")" : "", js(best, "images.mmrt"),
                     js(best, "images.embree"));
        bprintf(&b, "| %s | %.0fx%.0f | %.0f | %s | %s | %s | %.4g | %.3g | %s |\n",
                js(a, "scene.name"), jd(a, "settings.width"), jd(a, "settings.height"),
                jd(a, "settings.spp"), ds, de, bs, jd(best, "mmrt.rel_mse"),
                jd(def ? def : best, "dirt.rel_mse"), im);
    }
    return write_buf(prog, dir, "table.md", &b);
}

/* ---- plots (gnuplot) ---- */

static bool write_dat(const char *prog, const char *dir, const char *name, buf *b)
{
    return write_buf(prog, dir, name, b);
}

bool compare_write_plots(const char *prog, const char *dir, const cJSON *doc)
{
    const cJSON *rows = jget(doc, "configurations"), *r;
    buf b = {0};
    /* plot.dat: one line per ok row, blocks per scene (two blank lines); its
     * last columns number the rows across the blocks and label them with the
     * scene and the settings that vary (the x axis of ratios_per_scene:
     * gnuplot's column 0 restarts per block). */
    bprintf(&b, "# scene pixels triangles mmrt_MB dirt_MB mmrt_build dirt_build mmrt_trace "
                "dirt_trace ratio_mem ratio_build ratio_trace thickness_rel");
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        bprintf(&b, " mmrt_%s dirt_%s", dirt_ray_type_names[t], dirt_ray_type_names[t]);
    bprintf(&b, " mmrt_relmse dirt_relmse ratio_frame row label\n");
    const char *last = NULL;
    int blocks = 0, nok = 0;
    bool agreement = false; /* any agreement figure (none with --no-quality) */
    cJSON_ArrayForEach(r, rows)
    {
        if (!row_ok(r))
            continue;
        nok++;
        if (!last || strcmp(last, js(r, "scene.name"))) {
            if (last)
                bprintf(&b, "\n\n");
            blocks++;
            last = js(r, "scene.name");
        }
        bprintf(&b, "\"%s\" %.0f %.0f %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g",
                js(r, "scene.name"), jd(r, "settings.width") * jd(r, "settings.height"),
                jd(r, "scene.triangles"), mb(jd(r, "mmrt.memory.structure_used")),
                mb(jd(r, "dirt.memory.structure_used")), jd(r, "mmrt.build.median_ms"),
                jd(r, "dirt.build.median_ms"), jd(r, "mmrt.trace.median_ms"),
                jd(r, "dirt.trace.median_ms"), jd(r, "ratios.memory"), jd(r, "ratios.build"),
                jd(r, "ratios.trace"), jd(r, "mmrt.thickness_used") / jd(r, "scene.diagonal"));
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            char p[96];
            for (int e = 0; e < 2; e++) {
                snprintf(p, sizeof(p), "%s.agreement.fraction.%s", e ? "dirt" : "mmrt",
                         dirt_ray_type_names[t]);
                double v = jd(r, p);
                agreement |= !isnan(v);
                bprintf(&b, isnan(v) ? " NaN" : " %.6g", 100 * v);
            }
        }
        bprintf(&b, " %.6g %.6g %.6g %d \"%s %.0fx%.0f S%.0f B%.0f/%.0f th %.2g%%\"\n",
                jd(r, "mmrt.rel_mse"), jd(r, "dirt.rel_mse"), jd(r, "ratios.frame"), nok - 1,
                js(r, "scene.name"), jd(r, "settings.width"), jd(r, "settings.height"),
                jd(r, "settings.dirt_tile_size"), jd(r, "settings.dirt_buckets"),
                jd(r, "settings.mmrt_buckets"),
                100 * jd(r, "mmrt.thickness_used") / jd(r, "scene.diagonal"));
    }
    if (!write_dat(prog, dir, "plot.dat", &b))
        return false;
    if (!nok)
        return true; /* nothing to plot */
    /* One gnuplot script, each plot to SVG and PNG. */
    static const struct {
        const char *name, *xlabel, *ylabel, *body;
        bool logx;
        int height; /* pixels; 0 = 500 (the rotated labels of a row each want room) */
    } plots[] = {
        /* A key per scene: below the plot, small, when there are many. */
        {"memory_vs_resolution", "pixels", "structure MB",
         "if (NB > 4) { set key below horizontal font ',7' }\n"
         "plot for [i=0:NB-1] D u 2:4 index i w lp t word(SC, i+1).' MMRT', "
         "for [i=0:NB-1] D u 2:5 index i w lp dt 2 t word(SC, i+1).' DIRT'\n"
         "set key outside right vertical font ''", true},
        {"time_vs_resolution", "pixels", "median ms",
         "if (NB > 2) { set key below horizontal font ',7' }\n"
         "plot for [i=0:NB-1] D u 2:6 index i w lp t word(SC, i+1).' MMRT build', "
         "for [i=0:NB-1] D u 2:7 index i w lp t word(SC, i+1).' DIRT build', "
         "for [i=0:NB-1] D u 2:8 index i w lp dt 2 t word(SC, i+1).' MMRT trace', "
         "for [i=0:NB-1] D u 2:9 index i w lp dt 2 t word(SC, i+1).' DIRT trace'\n"
         "set key outside right vertical font ''", true},
        {"memory_vs_triangles", "triangles", "structure MB",
         "plot D u 3:4 w p pt 7 t 'MMRT', D u 3:5 w p pt 5 t 'DIRT'", true},
        {"time_vs_triangles", "triangles", "median ms",
         "plot D u 3:6 w p pt 7 t 'MMRT build', D u 3:7 w p pt 5 t 'DIRT build', "
         "D u 3:8 w p pt 6 t 'MMRT trace', D u 3:9 w p pt 4 t 'DIRT trace'", true},
        {"ratios_per_scene", "configuration", "DIRT / MMRT",
         "set xtics rotate by -45 font ',8'\n"
         "plot D u 27:10:xtic(28) w lp t 'memory', D u 27:11 w lp t 'build', "
         "D u 27:12 w lp t 'trace', D u 27:26 w lp t 'frame'\n"
         "set xtics norotate font ''", false, 760},
        {"agreement_vs_thickness", "MMRT thickness / scene diagonal", "agreement with Embree %",
         "plot for [k=0:4] D u 13:(column(14+2*k)) w lp t word(RT, k+1)", true},
    };
    buf g = {0};
    bprintf(&g, "D = '%s/plot.dat'\nNB = %d\nRT = '", dir, blocks);
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        bprintf(&g, "%s%s", t ? " " : "", dirt_ray_type_names[t]);
    bprintf(&g, "'\nSC = '");
    last = NULL;
    cJSON_ArrayForEach(r, rows)
    {
        if (!row_ok(r) || (last && !strcmp(last, js(r, "scene.name"))))
            continue;
        bprintf(&g, "%s", last ? " " : "");
        for (const char *c = js(r, "scene.name"); *c; c++)
            bprintf(&g, "%c", *c == ' ' || *c == '\'' || *c == '_' ? '-' : *c);
        last = js(r, "scene.name");
    }
    bprintf(&g, "'\nset key outside right\nset grid\nset datafile missing 'NaN'\n");
    for (size_t p = 0; p < sizeof(plots) / sizeof(plots[0]); p++) {
        /* Without agreement figures (--no-quality) that plot has no points. */
        if (!agreement && !strcmp(plots[p].name, "agreement_vs_thickness"))
            continue;
        for (int f = 0; f < 2; f++) {
            /* noenhanced: names with '_' are not subscripts */
            bprintf(&g, "set terminal %s noenhanced size 900,%d\nset output '%s/%s.%s'\n",
                    f ? "pngcairo" : "svg", plots[p].height ? plots[p].height : 500, dir,
                    plots[p].name, f ? "png" : "svg");
            char title[64];
            snprintf(title, sizeof(title), "%s", plots[p].name);
            for (char *c = title; *c; c++)
                *c = *c == '_' ? ' ' : *c;
            bprintf(&g, "set title '%s'\nset xlabel '%s'\nset ylabel '%s'\n%s\n%s\nset output\n",
                    title, plots[p].xlabel, plots[p].ylabel,
                    plots[p].logx ? "set logscale x" : "unset logscale x", plots[p].body);
        }
    }
    if (!write_buf(prog, dir, "plots.gp", &g))
        return false;
    char cmd[2200];
    snprintf(cmd, sizeof(cmd), "gnuplot '%s/plots.gp' 2>'%s/plots.log'", dir, dir);
    int st = system(cmd);
    if (st != 0) {
        cli_error(prog, "gnuplot failed (exit %d; is gnuplot-nox installed? see %s/plots.log)",
                  st, dir);
        return false;
    }
    return true;
}
