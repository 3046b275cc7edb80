/* frontier_report.h - the writing side of frontier.c: frontier.json, frontier.csv, the two
 * scatter plots and the "Which lobe to ship" markdown. */
#ifndef BRDF_FRONTIER_REPORT_H
#define BRDF_FRONTIER_REPORT_H

#include <stdio.h>

#include "frontier.h"

int frontier_write_json(const char *path, const struct frontier_report *r, const struct cl_session *s, char *err,
                        size_t errlen);
int frontier_write_csv(const char *path, const struct frontier_report *r, char *err, size_t errlen);
/* Two pictures: evaluations/s against max delta and against max Delta (both log axes). */
/* 1 when some model has a measured rate: the plots have a point to draw (else they are not
 * drawn, an earlier run's are removed, and the markdown says so). */
int frontier_plots_drawable(const struct frontier_report *r);
int frontier_write_plots(const char *dir, const struct frontier_report *r, char *err, size_t errlen);
/* The table on f. */
void frontier_print(FILE *f, const struct frontier_report *r);
/* The body of "Which lobe to ship" (no heading): report_frontier_page of the rows frontier.json
 * carries (the table, the front and the most accurate model per budget), which report.md's
 * section draws from the same rows (malloc'd; NULL when out of memory). */
char *frontier_markdown(const struct frontier_report *r);

#endif
