/* report_frontier.h - the "Which lobe to ship" page (frontier.md, and report.md's section of
 * that name) as a function of frontier.json's rows: `brdfbench frontier` writes its page by
 * calling it on the rows it has just built, report.md's section calls it on the rows read back
 * from the run folder (through the upgrade of an older frontier.json), so the two agree. */
#ifndef BRDF_REPORT_FRONTIER_H
#define BRDF_REPORT_FRONTIER_H

#include "mdbuf.h"
#include "rdoc.h"

/* What the page reads from the rows (frontier_report.c writes them, rdoc_upgrade_frontier.c
 * gives them for an older file): a row per model (key "model", attribute "kind", text "source",
 * text "psnr_reason" when the PSNR is no number) with the metrics n_2_1000.max_rel,
 * n_2_1000.max_abs, n_16_1000.max_rel, n_16_1000.max_abs, psnr_db, evals_per_s_uniform and
 * evals_per_s_varying (median, min and max over the rounds) and on_front (1 or 0); the context
 * lines "rounds" and "reps". */
#define FRONTIER_RATE_UNIFORM "evals_per_s_uniform"
#define FRONTIER_RATE_VARYING "evals_per_s_varying"

/* The body of "Which lobe to ship" (no heading): the table, the sources, the front, the most
 * accurate model per budget of evaluations/s and the plots. Returns 0, or -1 out of memory. */
int report_frontier_page(struct md_buf *b, const struct rdoc *frontier);
/* 1 when some model has a measured uniform rate: the plots have a point to draw. */
int report_frontier_drawable(const struct rdoc *frontier);

#endif
