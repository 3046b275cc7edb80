/* compare_report.h - what `brdfbench compare` writes: the table on stdout, compare.md,
 * compare.csv, compare.json (schema COMPARE_SCHEMA) and compare.png (per model, one bar per
 * run as a ratio to the baseline, with the baseline's noise band). */
#ifndef BRDF_COMPARE_REPORT_H
#define BRDF_COMPARE_REPORT_H

#include <stdio.h>

#include "compare.h"

/* The context side by side and every row, as text (md = 0) or markdown (md = 1): malloc'd,
 * NULL when out of memory. */
char *compare_text(const struct compare_set *set, int md);

/* Writes compare.md, compare.csv, compare.json and compare.png into out_dir. Returns 0, or 3
 * with a message naming the file (earlier files of that name are left as they were). */
int compare_write(const struct compare_set *set, const char *out_dir, char *err, size_t errlen);

/* compare.json's document written onto f (--json - without --out: no folder, no tables, no
 * chart); name is what a message calls it. Returns 0, or 3 with a message. */
int compare_print_json(const struct compare_set *set, FILE *f, const char *name, char *err, size_t errlen);

#endif
