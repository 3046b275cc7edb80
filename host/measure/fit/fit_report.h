/* fit_report.h - fit.json and the printed summary of a fit (the writing side of fit.c). */
#ifndef BRDF_FIT_REPORT_H
#define BRDF_FIT_REPORT_H

#include <stdio.h>

#include "fit.h"

/* Writes fit.json (schema FIT_SCHEMA, context block). Returns 0 or -1 with a message in err. */
int fit_write_json(const char *path, const struct fit_report *r, const struct cl_session *s,
                   const char *build_options, char *err, size_t errlen);
/* The summary table, the trade-off and the verdict. */
void fit_print(FILE *f, const struct fit_report *r);

/* The same for a family fit (fit_family_run): schema FIT_FAMILY_SCHEMA. */
int fit_family_write_json(const char *path, const struct fit_family_report *r, const struct cl_session *s,
                          char *err, size_t errlen);
void fit_family_print(FILE *f, const struct fit_family_report *r);

#endif
