/* hemisphere_report.h - writers of the hemisphere sweep's figures (rows of accuracy.json, CSV
 * lines of accuracy.csv, the printed table). */
#ifndef BRDF_HEMISPHERE_REPORT_H
#define BRDF_HEMISPHERE_REPORT_H

#include <stdio.h>

#include "hemisphere.h"
#include "jsonw.h"
#include "mdbuf.h"

/* One object per result, inside the "results" array being written. */
struct rdoc;
/* The hemisphere sweep's rows of accuracy.json (after the lobe sweep's): a row per model, keys
 * label and grid (reference, axis, hemisphere grid), its hemisphere.* figures; n_step is the
 * lobe grid's (NaN without one), kept as the rows' attribute the way earlier files read. */
void hemisphere_rows(struct rdoc *d, const struct hemi_result *res, int count, double n_step);
void hemisphere_json_rows(struct jw *w, const struct hemi_result *res, int count);
/* accuracy.csv's columns, one line per parameter value (n is the axis value). */
void hemisphere_csv_lines(struct md_buf *b, const struct hemi_result *res, int count);
void hemisphere_print_table(FILE *f, const struct hemi_result *res, int count);

#endif
