/* rdoc_upgrade_energy.h - energy.json of its previous version (brdfbench.energy/1, before the
 * file carried its rows) as rows: the upgrade function rdoc_read.c's layouts table names. */
#ifndef BRDF_RDOC_UPGRADE_ENERGY_H
#define BRDF_RDOC_UPGRADE_ENERGY_H

#include <stddef.h>

#include "jsonr.h"
#include "rdoc.h"

/* The rows host/measure/energy/energy_report.c's energy_rows builds, from the layout: a row per
 * model and integrand of "albedo", per model of "reciprocity" and of "reciprocity_image_pass",
 * and the context lines "energy quadrature tolerance" and "energy reciprocity pairs". Returns 0,
 * or 2 with "FILE:LINE:COL: ..." when a section is missing. */
int upgrade_energy_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

#endif
