/* energy_report.h - energy.json and the printed tables of energy_run (energy.c measures). */
#ifndef BRDF_ENERGY_REPORT_H
#define BRDF_ENERGY_REPORT_H

#include <stdio.h>

#include "energy.h"

/* energy.json from a finished summary: kept in summary->json when keep_json, written to
 * out_dir/energy.json when out_dir is not NULL. Returns 0 or an exit code (a message on
 * stderr). */
int energy_write(const struct cl_session *s, struct energy_summary *sum, int keep_json, const char *out_dir);
/* The albedo and reciprocity tables as energy_run prints them. */
void energy_print_table(FILE *f, const struct energy_summary *sum);

#endif
