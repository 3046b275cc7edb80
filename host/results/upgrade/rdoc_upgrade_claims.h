/* rdoc_upgrade_claims.h - inside rdoc_read.c: the upgrade functions of claims.json,
 * q_sweep.json and physical.json's first versions (written before the files carried their
 * rows), which rebuild from each layout the rows the version written now carries
 * (report_claims.h says what they hold). Not an interface for other modules. */
#ifndef BRDF_RDOC_UPGRADE_CLAIMS_H
#define BRDF_RDOC_UPGRADE_CLAIMS_H

#include <stddef.h>

#include "jsonr.h"
#include "rdoc.h"

/* Each returns 0, or 2 with "FILE:LINE:COL: ..." in err. */
int upgrade_claims_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
int upgrade_q_sweep_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
int upgrade_physical_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

#endif
