/* accuracy_report.h - accuracy.json, accuracy.csv and the printed table. */
#ifndef BRDF_ACCURACY_REPORT_H
#define BRDF_ACCURACY_REPORT_H

#include "schemas.h"
#include <stdio.h>

#include "accuracy.h"
#include "hemisphere_report.h"


/* The largest device-vs-double difference of a result, in units of the 4th significant
 * digit of the figure it belongs to (so "far below 1" means the digits printed hold). */
double accuracy_check_in_digits(const struct accuracy_result *r);

int accuracy_write_json(const char *path, const struct accuracy_result *res, int count,
                        const struct cl_session *s, const char *build_options, char *err, size_t errlen);
/* The same documents with the hemisphere sweep's rows after the lobe sweep's (hres may be NULL). */
int accuracy_write_json_full(const char *path, const struct accuracy_result *res, int count,
                             const struct hemi_result *hres, int hcount, const struct cl_session *s,
                             const char *build_options, char *err, size_t errlen);
/* accuracy_write_json, the rows it wrote as the file's rows member handed to the caller in *rows
 * (malloc'd; the caller frees them with rdoc_delete, or moves them): `all` gives them to its
 * report, which then draws the accuracy table from memory, not from the file read back. */
struct rdoc;
int accuracy_write_json_keep(const char *path, const struct accuracy_result *res, int count,
                             const struct cl_session *s, const char *build_options, struct rdoc **rows, char *err,
                             size_t errlen);
int accuracy_write_csv_full(const char *path, const struct accuracy_result *res, int count,
                            const struct hemi_result *hres, int hcount, char *err, size_t errlen);
int accuracy_write_csv(const char *path, const struct accuracy_result *res, int count, char *err, size_t errlen);
void accuracy_print_table(FILE *f, const struct accuracy_result *res, int count);

#endif
