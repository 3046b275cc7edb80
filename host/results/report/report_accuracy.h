/* report_accuracy.h - report.md's accuracy table and fit section, drawn from the rows of
 * accuracy.json and fit.json alone (rdoc.h): what accuracy_rows / hemisphere_rows and fit_rows
 * build where the figures are measured, or the upgrade of a previous file (rdoc_read.c). */
#ifndef BRDF_REPORT_ACCURACY_H
#define BRDF_REPORT_ACCURACY_H

#include "mdbuf.h"
#include "rdoc.h"

/* A cell " 12.34% |" (v a fraction) or " n/a |" when v is not finite. */
void report_md_pct(struct md_buf *b, double v);
/* A cell " <fmt of v> |" or " n/a |" when v is not finite. */
void report_md_num(struct md_buf *b, double v, const char *fmt);

/* "## Accuracy per model": the grid paragraph (from the context's accuracy n_min, n_max,
 * n_step, samples per zone) and a table line per row of acc (NULL: the sweep did not run). */
void report_accuracy_table(struct md_buf *b, const struct rdoc *acc);

/* The body of "Beyond the papers" from fit.json's rows: the family's limit, the fits (uncapped,
 * capped at fq2's max Delta) and the models compared, then the verdict. Returns 0, or 2 with a
 * message naming the file when its rows lack the fit's grid. */
int report_fit_block(struct md_buf *b, const struct rdoc *fit, const char *run_dir, char *err, size_t errlen);

#endif
