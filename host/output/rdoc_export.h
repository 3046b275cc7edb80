/* rdoc_export.h - the result document's rows (rdoc.h) in the formats that other benchmark
 * tools read, so brdfbench's figures can join a project's existing comparisons and dashboards:
 *
 *  - gbench: google/benchmark's JSON (what `--benchmark_format=json` writes), which
 *    `compare.py benchmarks A.json B.json` of google/benchmark's tools compares. Only timed
 *    figures (rates) go there, as the time of a million items: a row's metric is one benchmark,
 *    each repetition one "iteration" entry (real_time = 1e12 / rate in us, the time of
 *    items_per_iteration = 1e6 evaluations or FLOPs; items_per_second = the rate; cpu_time is
 *    the same time, for brdfbench times device work, not a CPU thread; iterations 1), followed by the mean, median, stddev and cv aggregates as google/benchmark
 *    computes them over the repetitions. A row not measured is an entry with error_occurred.
 *  - bmf: Bencher Metric Format, { benchmark: { measure: { value, lower_value, upper_value } } }:
 *    the benchmark is the row, the measure the metric's name, the value its figure (a rate's
 *    median) and the bounds the repetitions' min and max where there are some. Every metric of
 *    every measured row, accuracy figures included (a measure's direction is set in Bencher's
 *    threshold, not in the file).
 *  - action: github-action-benchmark's custom JSON, an array of { name, unit, value, range,
 *    extra }. The tool takes one direction per file (customBiggerIsBetter or
 *    customSmallerIsBetter), so the rows are split by direction: RD_HIGHER gives the rates and
 *    PSNRs (for customBiggerIsBetter), RD_LOWER the errors and costs (for
 *    customSmallerIsBetter). Metrics of neither direction (fitted coefficients) are in bmf only.
 *
 * Non-finite figures never reach these files (none of the formats has a null figure). */
#ifndef BRDF_RDOC_EXPORT_H
#define BRDF_RDOC_EXPORT_H

#include <stddef.h>

#include "mdbuf.h"
#include "rdoc.h"

/* The name of a row's metric in the exports: the device (when the rows name several), the
 * row's label, and the metric's name when the row has more than one metric exported, joined
 * by sep ("/" for gbench, " | " for the others). */
void rdoc_export_name(const struct rdoc *d, const struct rd_row *r, const struct rd_metric *m, int with_metric,
                      const char *sep, char *out, size_t outlen);

/* Each appends one JSON document to out. Returns 0, or 2 with a one-line reason when the rows
 * hold nothing that the format takes (gbench: no timed figure; action: no figure of that
 * direction). */
int rdoc_gbench(const struct rdoc *d, struct md_buf *out, char *err, size_t errlen);
int rdoc_bmf(const struct rdoc *d, struct md_buf *out, char *err, size_t errlen);
int rdoc_action(const struct rdoc *d, int direction, struct md_buf *out, char *err, size_t errlen);

#endif
