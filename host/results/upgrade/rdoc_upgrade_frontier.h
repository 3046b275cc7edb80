/* rdoc_upgrade_frontier.h - frontier.json of a previous version (brdfbench.frontier/1, and /2,
 * whose rows member lacks what the page reads) as the rows the version written now carries;
 * for rdoc_read.c's table of layouts. */
#ifndef BRDF_RDOC_UPGRADE_FRONTIER_H
#define BRDF_RDOC_UPGRADE_FRONTIER_H

#include <stddef.h>

#include "jsonr.h"
#include "rdoc.h"

/* A row per entry of "models" with the figures frontier_rows (frontier_report.c) gives, read
 * from the layout; the context lines rounds and reps. Returns 0, or 2 with a message. */
int upgrade_frontier_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

#endif
