/* rdoc_upgrade_measured.h - measured.json of brdfbench.measured/1 (before the file carried its
 * rows) as the rows the version written now carries; for rdoc_read.c's table of layouts. */
#ifndef BRDF_RDOC_UPGRADE_MEASURED_H
#define BRDF_RDOC_UPGRADE_MEASURED_H

#include <stddef.h>

#include "jsonr.h"
#include "rdoc.h"

/* The rows measured_rows (measured_report.c) gives, read from the "materials" of the layout:
 * per material its row, its three fits' rows and its lobes' rows (report_measured.h); the
 * context line fit_cells_max. Returns 0, or 2 with a message. */
int upgrade_measured_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

#endif
