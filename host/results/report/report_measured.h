/* report_measured.h - the "Measured materials" page (measured.md, and report.md's section of
 * that name) as a function of measured.json's rows: `brdfbench all --measured` writes its page
 * by calling it on the rows measured_report.c has just built, report.md's section calls it on
 * the rows read back from the run folder (through the upgrade of a brdfbench.measured/1 file),
 * so the two agree. */
#ifndef BRDF_REPORT_MEASURED_H
#define BRDF_REPORT_MEASURED_H

#include <stddef.h>

#include "mdbuf.h"
#include "rdoc.h"

/* The rows (measured_report.c writes them, rdoc_upgrade_measured.c gives them for a /1 file),
 * all keyed by "material", the material's picture stem (unique in the run):
 * - a row per material (that key alone): texts "name", "path" and "device_check" ("ok",
 *   "mismatch" or "not run"); metrics cells, unmeasured_cells, negative_cells.red, .green,
 *   .blue, below_horizon_cells, used_cells, fit_cells, device_check.points,
 *   device_check.same_cell, device_check.value_differs;
 * - a row per fit (key "fit": blinn-phong, ct-beckmann, ct-ggx; failed "not converged" or
 *   "not run" with the reason): n, ks, kd (Blinn-Phong) or alpha, n_of_alpha, F0, ks, kd
 *   (Cook-Torrance), rms, rms_fit_cells, iterations;
 * - a row per lobe (key "lobe"): err_measured, err_phong, ratio (text "ratio_reason" when the
 *   ratio is no number).
 * The context line fit_cells_max. */
#define MEASURED_FIT_KEY "fit"
#define MEASURED_LOBE_KEY "lobe"

/* Intro, then per material its fits and its lobes' errors with the pictures measured_write_plots
 * draws. Returns 0, or -1 out of memory. */
int report_measured_page(struct md_buf *b, const struct rdoc *measured);

/* The file-name form of a material's name: characters outside [A-Za-z0-9._-] become '_'. */
void report_measured_file_name(const char *name, char *out, size_t len);
/* The stem of a material's pictures: its name's file-name form, or with -2, -3, ... when one of
 * the `count` stems of the materials before it (taken[i]) is that already. */
void report_measured_stem(const char *name, const char *const *taken, int count, char *out, size_t len);

#endif
