/* throughput_internal.h - inside throughput: what throughput.c (options, figures, the
 * program, a whole run) and throughput_timing.c (timing through the runner) share. */
#ifndef BRDF_THROUGHPUT_INTERNAL_H
#define BRDF_THROUGHPUT_INTERNAL_H

#include <stddef.h>

#include "throughput_report.h"

/* One timed thing of a run: a model (NULL: pow) in an n mode, on the device in a program, or
   (prog NULL) its tuned C loop. */
struct tp_job {
    struct tp_figure *f;
    struct tp_program *prog;
    const struct model_spec *m;
    int nmode;
};

/* Times every job and the peak kernel (the reference) in the runner's interleaved rounds.
   Jobs that cannot be set up are failed figures; the others are filled from the runner. */
struct tp_bench {
    struct cl_session *s;
    const struct throughput_options *o;
    long work_items;
    int threads;
    const char *peak_options;
    struct tp_figure *peak;
    double peak_build_seconds;
    /* the run's record */
    long launches, retried, disturbed;
    int rounds;
};

/* Times every job and the peak kernel; fills their figures and b's record. */
int tp_bench_run(struct tp_bench *b, struct tp_job *jobs, int njobs, int quiet);

/* min, median, max of the finite values of v[0..n) (NAN when none). */
struct tp_stats tp_stats_of(const double *v, int n);
/* Rates from times: the fastest launch gives the largest rate. */
struct tp_stats tp_rates_of(struct tp_stats seconds, double work);
/* Marks a figure failed with its reason. */
void tp_fig_fail(struct tp_figure *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
double tp_sum_floats(const float *v, size_t n);
/* Whether the program has model m (NULL: pow), and its kernel of a kind ("uniform", "varying"). */
int tp_has(const struct tp_program *p, const struct model_spec *m);
cl_kernel tp_kernel(struct tp_program *p, const char *kind, const struct model_spec *m, cl_int *e);

#endif
