/* fit_internal.h - inside fit: what its files share. Not an interface for other modules. */
#ifndef BRDF_FIT_INTERNAL_H
#define BRDF_FIT_INTERNAL_H

#include <stddef.h>

#include "accuracy.h"
#include "fit.h"

/* The reference lobe of the family, in double. */
double fit_reference_eval(double c, double n);
/* The start of fit_run and fit_family_run: the report r (of size bytes) zeroed, its options
 * and grid set, the clock read; 0, or EXIT_USAGE with the message on stderr. */
int fit_start(struct cl_session *s, const struct fit_options *o, void *r, size_t size,
              struct fit_options *opt, struct accuracy_grid *g, double *t0);

#endif
