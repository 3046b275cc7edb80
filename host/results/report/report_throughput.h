/* report_throughput.h - the throughput page (throughput.md, report.md's "Throughput" section and
 * the tables `brdfbench throughput` prints) as a function of throughput.json's rows: the engine
 * calls it on the rows it has just built, report.md on the rows it reads back, so the two agree
 * by construction. */
#ifndef BRDF_REPORT_THROUGHPUT_H
#define BRDF_REPORT_THROUGHPUT_H

#include "mdbuf.h"
#include "rdoc.h"

/* The page of a throughput run's rows into b: markdown (md = 1, throughput.md) or the text
 * tables for a terminal (md = 0). What it reads (tp_rows in throughput_report.c writes them, the
 * upgrade of an older file in rdoc_read.c gives the same):
 *   the peak row (key "reference"): its flops_per_s, or its reason;
 *   each result row (keys label, variant, n_mode; attributes kind, model_reference): its
 *     evals_per_s with its range, host_c.evals_per_s (the tuned C loop, default variant),
 *     accuracy.max_diff_of_peak and accuracy.nonfinite; texts note (values not all finite) and
 *     host_c_reason (the C loop's sums are not the device's: no ratio);
 *   each accuracy sweep row (keys label, sweep): points, device_points_per_s,
 *     host_c_points_per_s;
 *   the document's texts reps, tuned_c_threads, sweep_grid and sweep_reason.
 * Rows of several devices give each device's tables in turn, under its name. Returns 0, or -1
 * when out of memory (b->failed). */
int report_throughput_page(struct md_buf *b, const struct rdoc *tp, int md);

#endif
