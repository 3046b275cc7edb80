/* gate_internal.h - inside gate: what its files share. Not an interface for other modules. */
#ifndef BRDF_GATE_INTERNAL_H
#define BRDF_GATE_INTERNAL_H

#include "gate.h"

#define GATE_ALBEDO_THETA_COUNT 18   /* theta_i = 0, 5, ..., 85 degrees, as energy.json */

/* Whether metric m is measured by an accuracy sweep. */
int gate_metric_needs_sweep(enum gate_metric m);
/* a and b agree to 1e-9 relative. */
int gate_same_number(double a, double b);

#endif
