/* dirt-compare's results, CSV and table from the rows (app/compare.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/compare.h"
#include "dirt/file.h"
#include "dirt/types.h"

const cJSON *compare_jget(const cJSON *o, const char *path)
{
    char buf[128];
    snprintf(buf, sizeof(buf), "%s", path);
    const cJSON *x = o;
    for (char *save = NULL, *tok = strtok_r(buf, ".", &save); tok && x;
         tok = strtok_r(NULL, ".", &save))
        x = cJSON_GetObjectItemCaseSensitive(x, tok);
    return x;
}

double compare_jd(const cJSON *o, const char *path)
{
    const cJSON *x = compare_jget(o, path);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

const char *compare_js(const cJSON *o, const char *path)
{
    const cJSON *x = compare_jget(o, path);
    return cJSON_IsString(x) ? x->valuestring : "";
}

bool compare_row_ok(const cJSON *r)
{
    return !strcmp(compare_js(r, "status"), "ok");
}

void compare_bprintf(compare_buf *b, const char *fmt, ...)
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

bool compare_write_buf(const char *prog, const char *dir, const char *name, compare_buf *b)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    bool ok = dirt_write_file_atomic(path, b->p ? b->p : "", b->n);
    if (!ok)
        cli_error(prog, "cannot write %s", path);
    free(b->p);
    *b = (compare_buf){0};
    return ok;
}

/* Rows of one scene, resolution, spp and bounces: MMRT's settings vary. */
static bool same_group(const cJSON *p, const cJSON *a)
{
    return !strcmp(compare_js(p, "scene.path"), compare_js(a, "scene.path")) &&
           compare_jd(p, "settings.width") == compare_jd(a, "settings.width") &&
           compare_jd(p, "settings.height") == compare_jd(a, "settings.height") &&
           compare_jd(p, "settings.spp") == compare_jd(a, "settings.spp") &&
           compare_jd(p, "settings.bounces") == compare_jd(a, "settings.bounces");
}

/* "1.921 (0.2 % of the diagonal), hiz" / "..., linear 30". */
static void setting_str(const cJSON *r, char *out, size_t n)
{
    double t = compare_jd(r, "mmrt.thickness_used"), d = compare_jd(r, "scene.diagonal");
    char march[32];
    if (!strcmp(compare_js(r, "settings.mmrt_march"), "linear") &&
        compare_jd(r, "settings.mmrt_samples") > 0)
        snprintf(march, sizeof(march), "linear %.0f", compare_jd(r, "settings.mmrt_samples"));
    else
        snprintf(march, sizeof(march), "%s", compare_js(r, "settings.mmrt_march"));
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

static void csv_field(compare_buf *b, const cJSON *x)
{
    if (cJSON_IsNumber(x)) {
        if (isfinite(x->valuedouble)) /* not measured: an empty cell, as in the JSON's null */
            compare_bprintf(b, "%.10g", x->valuedouble);
    } else if (cJSON_IsString(x)) {
        compare_bprintf(b, "\"");
        for (const char *c = x->valuestring; *c; c++)
            compare_bprintf(b, *c == '"' ? "\"\"" : "%c", *c);
        compare_bprintf(b, "\"");
    } else if (cJSON_IsBool(x)) {
        compare_bprintf(b, cJSON_IsTrue(x) ? "true" : "false");
    }
}

bool compare_write_results(const char *prog, const char *dir, const cJSON *doc)
{
    char *text = cJSON_Print(doc);
    if (!text)
        return false;
    compare_buf b = {0};
    compare_bprintf(&b, "%s\n", text);
    free(text);
    bool ok = compare_write_buf(prog, dir, "results.json", &b);
    size_t ncols = sizeof(csv_cols) / sizeof(csv_cols[0]);
    for (size_t c = 0; c < ncols; c++)
        compare_bprintf(&b, "%s%s", c ? "," : "", csv_cols[c][0]);
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        compare_bprintf(&b, ",dirt_agree_%s,mmrt_agree_%s", dirt_ray_type_names[t],
                dirt_ray_type_names[t]);
    compare_bprintf(&b, "\n");
    const cJSON *r;
    cJSON_ArrayForEach(r, compare_jget(doc, "configurations"))
    {
        for (size_t c = 0; c < ncols; c++) {
            if (c)
                compare_bprintf(&b, ",");
            csv_field(&b, compare_jget(r, csv_cols[c][1]));
        }
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            char p[96];
            for (int e = 0; e < 2; e++) {
                snprintf(p, sizeof(p), "%s.agreement.fraction.%s", e ? "mmrt" : "dirt",
                         dirt_ray_type_names[t]);
                compare_bprintf(&b, ",");
                csv_field(&b, compare_jget(r, p));
            }
        }
        compare_bprintf(&b, "\n");
    }
    return compare_write_buf(prog, dir, "results.csv", &b) && ok;
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

/* Appends `line` (one table line, with its newline) to `b` unless it is in
 * `listed` already (then adds it there); frees it. */
static void print_once(compare_buf *b, compare_buf *listed, compare_buf *line)
{
    if (!line->p)
        return;
    bool found = false;
    for (const char *q = listed->p ? strstr(listed->p, line->p) : NULL; q && !found;
         q = strstr(q + 1, line->p))
        found = q == listed->p || q[-1] == '\n';
    if (!found) {
        compare_bprintf(b, "%s", line->p);
        compare_bprintf(listed, "%s", line->p);
    }
    free(line->p);
    *line = (compare_buf){0};
}

static double mb(double bytes)
{
    return bytes / 1048576.0;
}

bool compare_write_table(const char *prog, const char *dir, const cJSON *doc)
{
    compare_buf b = {0};
    const cJSON *rows = compare_jget(doc, "configurations"), *r, *first = NULL;
    cJSON_ArrayForEach(r, rows) if (compare_row_ok(r) && !first) first = r;
    compare_bprintf(&b, "# DIRT vs MMRT (dirt-compare)\n\n");
    if (first)
        compare_bprintf(&b, "Machine: %s  \nRenderer: %s  \nCommit: %s  \nTimes: %s clock, "
                        "median of %g repeats after %g warm-up (min-max in results.csv/json); "
                        "build = the structure's passes, trace = every trace pass of spp "
                        "samples of path tracing, frame = every pass: the build and spp whole "
                        "samples (raygen, traces, fetch, shade, resolve, accumulate).\n\n",
                        compare_js(first, "environment.machine"),
                        compare_js(first, "environment.renderer"),
                        compare_js(first, "environment.commit"),
                        compare_js(first, "environment.clock"),
                        compare_jd(first, "settings.repeat"), compare_jd(first, "settings.warmup"));
    /* The lighting, per scene (the same in each of its rows). */
    compare_bprintf(&b, "Lighting per scene (the same for MMRT, DIRT and the Embree reference; "
                        "doc/compare.md, \"Lighting\"):\n\n");
    cJSON_ArrayForEach(r, rows)
    {
        bool seen = false;
        for (const cJSON *p = rows->child; p != r && !seen; p = p->next)
            seen = !strcmp(compare_js(p, "scene.path"), compare_js(r, "scene.path")) &&
                   !strcmp(compare_js(p, "lighting.summary"), compare_js(r, "lighting.summary"));
        if (!seen)
            compare_bprintf(&b, "- %s: %s\n", compare_js(r, "scene.name"),
                            *compare_js(r, "lighting.summary")
                                ? compare_js(r, "lighting.summary")
                                : "not recorded (a row of an older run)");
    }
    compare_bprintf(&b, "\n");
    compare_bprintf(&b, "In the layout of the DIRT paper's Table 2 (MMRT / DIRT at equal "
                        "settings). Records: MMRT fragments, DIRT id nodes (c n_p). MB: the "
                        "structure's used bytes. Ratios DIRT / MMRT. S: DIRT's tile size, with "
                        "+grid, +sub-tiles, +masks, +depths when --large-grid, --sub-tiles, "
                        "--bucket-masks, --node-depths were on.\n\n");
    compare_bprintf(&b, "| scene | triangles | resolution | views | S | B (D/M) | thickness | spp "
                        "| MMRT fragments | MMRT MB | MMRT build ms | MMRT trace ms | DIRT entries "
                        "| DIRT MB | DIRT build ms | DIRT trace ms | entries ratio | MB ratio | "
                        "build ratio | trace ratio | frame ratio | MMRT relMSE | DIRT relMSE | "
                        "status |\n");
    compare_bprintf(&b, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
                        "---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        double th = isnan(compare_jd(r, "mmrt.thickness_used"))
                        ? compare_jd(r, "settings.mmrt_thickness")
                        : compare_jd(r, "mmrt.thickness_used");
        /* DIRT's trace options, when on, beside S (its structure) */
        char opts[64];
        snprintf(opts, sizeof(opts), "%s%s%s%s",
                 cJSON_IsTrue(compare_jget(r, "settings.dirt_large_grid")) ? " +grid" : "",
                 cJSON_IsTrue(compare_jget(r, "settings.dirt_sub_tiles")) ? " +sub-tiles" : "",
                 cJSON_IsTrue(compare_jget(r, "settings.dirt_bucket_masks")) ? " +masks" : "",
                 cJSON_IsTrue(compare_jget(r, "settings.dirt_node_depths")) ? " +depths" : "");
        compare_bprintf(&b, "| %s | %.0f | %.0fx%.0f | %s | %.0f%s | %.0f/%.0f | %.4g | %.0f |",
                        compare_js(r, "scene.name"), compare_jd(r, "scene.triangles"),
                        compare_jd(r, "settings.width"), compare_jd(r, "settings.height"),
                        compare_js(r, "settings.views"), compare_jd(r, "settings.dirt_tile_size"),
                        opts, compare_jd(r, "settings.dirt_buckets"),
                        compare_jd(r, "settings.mmrt_buckets"), th, compare_jd(r, "settings.spp"));
        if (!compare_row_ok(r)) {
            compare_bprintf(&b, " | | | | | | | | | | | | | | | | failed: %s |\n",
                            compare_js(r, "reason"));
            continue;
        }
        compare_bprintf(&b, " %.0f | %.2f | %.2f | %.2f | %.0f | %.2f | %.2f | %.2f | %.3f | "
                            "%.3f | %.3f | %.3f | %.3f | %.3g | %.3g | ok |\n",
                        compare_jd(r, "mmrt.records"),
                        mb(compare_jd(r, "mmrt.memory.structure_used")),
                        compare_jd(r, "mmrt.build.median_ms"),
                        compare_jd(r, "mmrt.trace.median_ms"),
                        compare_jd(r, "dirt.records"),
                        mb(compare_jd(r, "dirt.memory.structure_used")),
                        compare_jd(r, "dirt.build.median_ms"),
                        compare_jd(r, "dirt.trace.median_ms"),
                        compare_jd(r, "ratios.records"), compare_jd(r, "ratios.memory"),
                        compare_jd(r, "ratios.build"), compare_jd(r, "ratios.trace"),
                        compare_jd(r, "ratios.frame"), compare_jd(r, "mmrt.rel_mse"),
                        compare_jd(r, "dirt.rel_mse"));
    }
    /* Memory against the formulas: one line per structure (DIRT's is
     * measured again in every row of MMRT's settings, and MMRT's does not
     * depend on its thickness or march): repeats are left out. */
    compare_buf listed = {0};
    compare_bprintf(&b, "\n## Memory against the analytic formulas\n\n"
                        "DIRT: its Table 3 (`bytes_table3`); MMRT: the DLLB formula of its paper "
                        "(`bytes_paper`). \"exact part\": the terms the formula counts exactly, "
                        "measured vs formula; depth extra: measured depth bounds minus what the "
                        "formula counts for them (by design, see doc/compare.md). One line per "
                        "structure: the same structure measured in several configurations (DIRT's "
                        "beside each MMRT setting, MMRT's at each thickness and march) is listed "
                        "once.\n\n"
                        "| scene | resolution | views | technique | structure | used MB | "
                        "allocated MB | formula MB | exact part measured | exact part formula | "
                        "equal | depth extra B |\n"
                        "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r))
            continue;
        for (int e = 0; e < 2; e++) {
            const cJSON *m = compare_jget(r, e ? "dirt.memory" : "mmrt.memory");
            char setting[96], t[32] = "";
            if (compare_jd(r, "settings.time") != 0)
                snprintf(t, sizeof(t), ", t %g s", compare_jd(r, "settings.time"));
            if (e)
                snprintf(setting, sizeof(setting), "S%g B%g L%g%s",
                         compare_jd(r, "settings.dirt_tile_size"),
                         compare_jd(r, "settings.dirt_buckets"),
                         compare_jd(r, "settings.dirt_large"), t);
            else
                snprintf(setting, sizeof(setting), "B%g%s",
                         compare_jd(r, "settings.mmrt_buckets"), t);
            compare_buf line = {0};
            compare_bprintf(&line, "| %s | %.0fx%.0f | %s | %s | %s | %.3f | %.3f | %.3f | %.0f "
                            "| %.0f | %s | %.0f |\n",
                            compare_js(r, "scene.name"), compare_jd(r, "settings.width"),
                            compare_jd(r, "settings.height"), compare_js(r, "settings.views"),
                            e ? "DIRT" : "MMRT", setting, mb(compare_jd(m, "structure_used")),
                            mb(compare_jd(m, "structure_allocated")),
                            mb(compare_jd(m, "formula.bytes")),
                            compare_jd(m, "formula.exact_part_measured"),
                            compare_jd(m, "formula.exact_part_formula"),
                            cJSON_IsTrue(compare_jget(m, "formula.equal")) ? "yes" : "**no**",
                            compare_jd(m, "formula.depth_extra"));
            print_once(&b, &listed, &line);
        }
    }
    /* Agreement: DIRT's once per structure, MMRT's per thickness and march. */
    compare_bprintf(&b, "\n## Hit agreement with Embree per ray type (%%)\n\n"
                        "DIRT's agreement does not depend on MMRT's settings: it is listed once "
                        "per DIRT setting.\n\n| scene | resolution | technique | setting |");
    for (int t = 0; t < DIRT_RAY_TYPES; t++)
        compare_bprintf(&b, " %s |", dirt_ray_type_names[t]);
    compare_bprintf(&b, "\n|---|---|---|---|---|---|---|---|---|\n");
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r) || !compare_jget(r, "dirt.agreement"))
            continue;
        for (int e = 0; e < 2; e++) {
            char setting[160];
            if (e)
                setting_str(r, setting, sizeof(setting));
            else
                snprintf(setting, sizeof(setting), "S%g B%g",
                         compare_jd(r, "settings.dirt_tile_size"),
                         compare_jd(r, "settings.dirt_buckets"));
            compare_buf line = {0};
            compare_bprintf(&line, "| %s | %.0fx%.0f | %s | %s |", compare_js(r, "scene.name"),
                            compare_jd(r, "settings.width"), compare_jd(r, "settings.height"),
                            e ? "MMRT" : "DIRT", setting);
            for (int t = 0; t < DIRT_RAY_TYPES; t++) {
                char p[96];
                snprintf(p, sizeof(p), "%s.agreement.fraction.%s", e ? "mmrt" : "dirt",
                         dirt_ray_type_names[t]);
                compare_bprintf(&line, " %.2f |", 100 * compare_jd(r, p));
            }
            compare_bprintf(&line, "\n");
            print_once(&b, &listed, &line);
        }
    }
    /* Work per ray (--count-work): counted, not timed. */
    bool any_work = false;
    cJSON_ArrayForEach(r, rows) any_work = any_work || (compare_row_ok(r) &&
                                                        compare_jget(r, "dirt.work"));
    if (any_work) {
        compare_bprintf(&b, "\n## Work per ray (--count-work)\n\nMeans over the hit-agreement "
                            "rays of each type (the camera G-buffer at the image size): DIRT's "
                            "exact triangle tests, tiles walked, Hi-Z steps and list nodes read; "
                            "MMRT's fragments visited (one depth test each); Embree's triangle "
                            "tests and BVH nodes over DIRT's rays (doc/dirt-trace.md, \"Work "
                            "counters\").\n\n| scene | resolution | DIRT setting | ray type | "
                            "DIRT tri tests | tiles | Hi-Z steps | list nodes | MMRT fragments | "
                            "Embree tri tests | Embree BVH nodes | DIRT / Embree tri tests |\n"
                            "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    }
    cJSON_ArrayForEach(r, rows)
    {
        if (!any_work || !compare_row_ok(r) || !compare_jget(r, "dirt.work"))
            continue;
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            char p[128];
            double v[8];
            static const char *const keys[8] = {
                "dirt.work.%s.rays", "dirt.work.%s.triangle_tests", "dirt.work.%s.tiles",
                "dirt.work.%s.hiz_steps", "dirt.work.%s.list_nodes", "mmrt.work.%s.fragments",
                "dirt.work.%s.embree.triangle_tests", "dirt.work.%s.embree.bvh_nodes"};
            for (int k = 0; k < 8; k++) {
                snprintf(p, sizeof(p), keys[k], dirt_ray_type_names[t]);
                v[k] = compare_jget(r, p) ? compare_jd(r, p) : NAN;
            }
            snprintf(p, sizeof(p), "mmrt.work.%s.rays", dirt_ray_type_names[t]);
            double mrays = compare_jget(r, p) ? compare_jd(r, p) : NAN;
            double n = v[0] > 0 ? v[0] : NAN;
            compare_buf line = {0};
            compare_bprintf(&line, "| %s | %.0fx%.0f | S%g B%g | %s | %.2f | %.2f | %.2f | %.2f "
                            "| %.2f | %.2f | %.2f | %.2f |\n",
                            compare_js(r, "scene.name"), compare_jd(r, "settings.width"),
                            compare_jd(r, "settings.height"),
                            compare_jd(r, "settings.dirt_tile_size"),
                            compare_jd(r, "settings.dirt_buckets"), dirt_ray_type_names[t],
                            v[1] / n, v[2] / n, v[3] / n, v[4] / n,
                            mrays > 0 ? v[5] / mrays : NAN, v[6] / n, v[7] / n, v[1] / v[6]);
            print_once(&b, &listed, &line);
        }
    }
    free(listed.p);
    /* MMRT's best setting per scene (thickness, march, samples) beside its
     * default (default thickness, Hi-Z), with their images. */
    compare_bprintf(&b, "\n## MMRT's best setting per scene (relMSE of the path-traced image "
                        "vs Embree)\n\nDefault: MMRT's default thickness (0.2 %% of the scene's "
                        "diagonal) and the Hi-Z march; best: the lowest relMSE over the "
                        "thicknesses, marches and samples swept at that scene, resolution and "
                        "spp.\n\n| scene | resolution | spp | default | relMSE at default | "
                        "best setting | relMSE at best | DIRT relMSE | images (MMRT default, "
                        "MMRT best, Embree) |\n|---|---|---|---|---|---|---|---|---|\n");
    int nrows = cJSON_GetArraySize(rows);
    for (int i = 0; i < nrows; i++) {
        const cJSON *a = cJSON_GetArrayItem(rows, i);
        if (!compare_row_ok(a))
            continue;
        bool seen = false;
        for (int k = 0; k < i && !seen; k++) {
            const cJSON *p = cJSON_GetArrayItem(rows, k);
            seen = compare_row_ok(p) && same_group(p, a);
        }
        if (seen)
            continue;
        const cJSON *def = NULL, *best = NULL;
        for (int k = i; k < nrows; k++) {
            const cJSON *p = cJSON_GetArrayItem(rows, k);
            if (!compare_row_ok(p) || !same_group(p, a))
                continue;
            bool is_def = cJSON_IsTrue(compare_jget(p, "settings.mmrt_default")) ||
                          (!compare_jget(p, "settings.mmrt_default") &&
                           cJSON_IsTrue(compare_jget(p, "settings.mmrt_thickness_default")) &&
                           !strcmp(compare_js(p, "settings.mmrt_march"), "hiz"));
            if (is_def && !def)
                def = p;
            if (!best || compare_jd(p, "mmrt.rel_mse") < compare_jd(best, "mmrt.rel_mse"))
                best = p;
        }
        char ds[96] = "not swept (add 0 and hiz)", de[32] = "-", bs[96], im[256] = "-";
        if (def) {
            setting_str(def, ds, sizeof(ds));
            snprintf(de, sizeof(de), "%.4g", compare_jd(def, "mmrt.rel_mse"));
        }
        setting_str(best, bs, sizeof(bs));
        bool dimg = def && *compare_js(def, "images.mmrt");
        if (*compare_js(best, "images.mmrt"))
            snprintf(im, sizeof(im), "%s%s%s, [best](%s), [Embree](%s)",
                     dimg ? "[default](" : "", dimg ? compare_js(def, "images.mmrt") : "-",
                     dimg ? ")" : "", compare_js(best, "images.mmrt"),
                     compare_js(best, "images.embree"));
        compare_bprintf(&b, "| %s | %.0fx%.0f | %.0f | %s | %s | %s | %.4g | %.3g | %s |\n",
                        compare_js(a, "scene.name"), compare_jd(a, "settings.width"),
                        compare_jd(a, "settings.height"), compare_jd(a, "settings.spp"), ds, de, bs,
                        compare_jd(best, "mmrt.rel_mse"),
                        compare_jd(def ? def : best, "dirt.rel_mse"), im);
    }
    return compare_write_buf(prog, dir, "table.md", &b);
}
