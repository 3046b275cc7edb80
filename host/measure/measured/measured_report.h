/* measured_report.h - the writing side of `brdfbench measured`: measured.json, the printed table
 * and the pictures (each lobe's error against the material beside its error against the fitted
 * Blinn-Phong; per material the slice of the measured lobe with the fitted curves). */
#ifndef BRDF_MEASURED_REPORT_H
#define BRDF_MEASURED_REPORT_H

#include <stdio.h>

#include "mdbuf.h"
#include "measured.h"

int measured_write_json(const char *path, const struct measured_report *r, const struct cl_session *s, char *err,
                        size_t errlen);
void measured_print(FILE *f, const struct measured_report *r);
/* measured_errors_<name>.png and measured_slice_<name>.png per material into dir. */
int measured_write_plots(const char *dir, const struct measured_report *r, char *err, size_t errlen);
/* report.md's section (brdfbench all --measured DIR): per material the fits and the lobes'
 * errors, with the pictures measured_write_plots wrote: report_measured_page of the rows
 * measured.json carries. Returns 0, or -1 out of memory (md->failed set). */
int measured_markdown(struct md_buf *md, const struct measured_report *r);
/* The file-name form of a material's name: characters outside [A-Za-z0-9._-] become '_'
 * (report_measured_file_name). */
void measured_file_name(const char *name, char *out, size_t len);

#endif
