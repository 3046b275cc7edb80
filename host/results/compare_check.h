/* compare_check.h - what every reader of results (rdoc_read.h: compare, gate --baseline, plot,
 * rows) accepts in a result file before it reads a figure: the
 * figures are numbers (or null, "not measured") in their range, the labels are one line of
 * table-safe text. A hand-edited or corrupted file is refused with exit 2 naming the file, the
 * line and column and the member, instead of reading as "failed" or as a better figure. */
#ifndef BRDF_COMPARE_CHECK_H
#define BRDF_COMPARE_CHECK_H

#include <stddef.h>

#include "jsonr.h"

#include "rdoc.h"

#define CMP_MAX_RATE RD_MAX_RATE    /* a rate: evaluations, pixels or FLOPs per second */
#define CMP_MAX_ERROR RD_MAX_VALUE  /* an error (max_rel, max_abs, rmse) */

/* Checks every member of d. Returns 0, or 2 with "FILE:LINE:COL: problem (accepted: ...)". */
int compare_check_doc(const struct jr_doc *d, char *err, size_t errlen);

#endif
