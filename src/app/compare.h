/* dirt-compare's outputs: every finished configuration is one cJSON row
 * (schema: doc/compare.md); results.json, results.csv, table.md and the
 * plots are all written from the rows, so a resumed sweep rewrites them
 * from what it read back. */
#ifndef DIRT_APP_COMPARE_H
#define DIRT_APP_COMPARE_H

#include <stdbool.h>

#include <cjson/cJSON.h>

/* Writes DIR/results.json (the document: {"tool", "schema_version",
 * "configurations": rows}) and DIR/results.csv, atomically. */
bool compare_write_results(const char *prog, const char *dir, const cJSON *doc);
/* DIR/table.md in the layout of the DIRT paper's Table 2, and the MMRT
 * thickness summary (best per scene beside the default). */
bool compare_write_table(const char *prog, const char *dir, const cJSON *doc);
/* SVG and PNG plots through gnuplot (run as a program). False with the
 * reason printed when gnuplot is missing or fails. */
bool compare_write_plots(const char *prog, const char *dir, const cJSON *doc);
/* The rows of DIR/results.json from an earlier run (NULL when none or
 * unreadable: the sweep then starts afresh). */
cJSON *compare_read_results(const char *dir);

#endif
