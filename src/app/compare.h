/* dirt-compare's outputs: every finished configuration is one cJSON row
 * (schema: doc/compare.md); results.json, results.csv, table.md and the
 * plots are all written from the rows, so a resumed sweep rewrites them
 * from what it read back. */
#ifndef DIRT_APP_COMPARE_H
#define DIRT_APP_COMPARE_H

#include <stdbool.h>
#include <stddef.h>

#include <cjson/cJSON.h>

/* Writes DIR/results.json (the document: {"tool", "schema_version",
 * "configurations": rows}) and DIR/results.csv, atomically. */
bool compare_write_results(const char *prog, const char *dir, const cJSON *doc);
/* DIR/table.md in the layout of the DIRT paper's Table 2, and the MMRT
 * thickness summary (best per scene beside the default). */
bool compare_write_table(const char *prog, const char *dir, const cJSON *doc);
/* The figures (compare_plots.c): per figure DIR/NAME.dat (its data),
 * NAME.svg and NAME.png through gnuplot (run as a program on DIR/plots.gp);
 * a figure none of whose series has two points is not drawn (and its files
 * of an earlier run are removed). False with the reason printed when a
 * file cannot be written or gnuplot is missing or fails. */
bool compare_write_plots(const char *prog, const char *dir, const cJSON *doc);
/* The rows of DIR/results.json from an earlier run (NULL when none or
 * unreadable: the sweep then starts afresh). */
cJSON *compare_read_results(const char *dir);

/* ---- shared by compare_report.c and compare_plots.c ---- */

/* The value at a dotted path ("dirt.build.min_ms") of a row; NULL when
 * absent. compare_jd: its number or NAN; compare_js: its string or "". */
const cJSON *compare_jget(const cJSON *o, const char *path);
double compare_jd(const cJSON *o, const char *path);
const char *compare_js(const cJSON *o, const char *path);
/* True when the row's status is "ok". */
bool compare_row_ok(const cJSON *r);

/* A growing text (zero-initialised: empty). On out-of-memory the text
 * stops growing. */
typedef struct compare_buf {
    char *p;
    size_t n, cap;
} compare_buf;
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void compare_bprintf(compare_buf *b, const char *fmt, ...);
/* Writes `b` to DIR/NAME atomically and frees it (empty again); false with
 * the reason printed. */
bool compare_write_buf(const char *prog, const char *dir, const char *name, compare_buf *b);

#endif
