/* throughput_report.h - what a throughput run measured (struct tp_run, filled by
 * throughput.c) and its writers in throughput_report.c: its rows, throughput.json and
 * throughput.csv; the page (text for stdout, throughput.md) is drawn from the rows. Internal to the throughput
 * engine: other code reads its results through throughput.json. */
#ifndef BRDF_THROUGHPUT_REPORT_H
#define BRDF_THROUGHPUT_REPORT_H

#include <stddef.h>

#include "throughput.h"

#define TP_ACC_POINTS 4096       /* probe points per model and variant */
#define TP_REASON 240

struct tp_stats {
    double min, median, max;
};

/* One timed thing: a device kernel or the C loop. */
struct tp_figure {
    int ok;
    char reason[TP_REASON];
    struct tp_stats sec, sec_wall;     /* per launch */
    struct tp_stats rate, rate_wall;   /* work per second */
    long iters;
    double per_launch;                 /* work per launch: evaluations (flops for the peak) */
    double checksum;                   /* sum of the last launch's outputs */
    int finite;                        /* 0: some values were NaN or Inf (timed all the same) */
    int nreps;                         /* timed launches, in the order they ran */
    double rep_seconds[TP_MAX_REPS];   /* each one's time (profiling events; C: wall) */
    /* the runner's normalised rates (host/core/runner.h): each repetition's rate over the
       reference kernel's rate in the same round */
    int has_norm;
    double rep_norm[TP_MAX_REPS];
    double rep_cpu[TP_MAX_REPS];       /* the process's CPU seconds over each repetition */
    int has_cpu_norm;
    double rep_cpu_norm[TP_MAX_REPS];  /* normalised rates per CPU second (runner.h, cpu_norm) */
    struct tp_stats cpu_norm;
    struct tp_stats norm;
    int retries, disturbed;            /* launches retried for preemption; reps kept disturbed */
    int timer_wall;                    /* the driver gave no profiling time: wall time used */
    int checked;                       /* C figures: its sums compared with the device's (check) */
    struct tp_sums_check check;
};

/* A measured thing: a model of the run, or the pow() built-in (m = NULL). */
struct tp_entry {
    const struct model_spec *m;
    char label[MODEL_LABEL_MAX];
    int ref_entry;                               /* entry of its registry reference, or -1 */
    int skipped;                                 /* user model: not measured */
    struct tp_figure hostc[TP_NMODE_COUNT];
    struct tp_figure dev[TP_VARIANT_COUNT][TP_NMODE_COUNT];
    int measured[TP_VARIANT_COUNT][TP_NMODE_COUNT];
    /* accuracy of the variant against the double reference at probe points */
    int acc_ok[TP_VARIANT_COUNT];
    char acc_reason[TP_VARIANT_COUNT][TP_REASON];
    double acc_max_diff[TP_VARIANT_COUNT];
    long acc_nonfinite[TP_VARIANT_COUNT];
};

struct tp_sweep_model {
    char label[MODEL_LABEL_MAX];
    int ok;
    char reason[TP_REASON];
    struct tp_stats dev_s, hostc_s;
    double points;
    double agree;                                /* largest relative difference of per-n maxima */
};

struct tp_run {
    struct cl_session *s;
    const struct throughput_options *o;
    struct model_spec models[TP_MAX_MODELS];
    int nmodels;
    struct tp_entry *e;                          /* [0] is pow() */
    int nentries;
    long work_items;
    int threads;
    int built[TP_VARIANT_COUNT];
    char build_reason[TP_VARIANT_COUNT][TP_REASON];
    char options[TP_VARIANT_COUNT][256];
    double build_seconds[TP_VARIANT_COUNT];
    struct tp_figure peak;                       /* the runner's reference item, timed every round */
    /* the runner's record (host/core/runner.h) */
    long launches, retried, disturbed;
    int rounds;
    uint64_t seed;
    double steal_start, steal_end;               /* seconds of steal time (/proc/stat), -1: unknown */
    double peak_build_seconds;
    char peak_options[256];
    /* sweep */
    int sweep_ran;
    char sweep_reason[TP_REASON];
    long sweep_n_count;
    struct tp_sweep_model *sw;
    int nsw;
    double sweep_build_seconds;
    char load_start[64], load_end[64];           /* /proc/loadavg: other work on the machine */
};

static inline int variant_on(const struct tp_run *r, int v) { return (r->o->variants >> v) & 1u; }

static inline int nmode_on(const struct tp_run *r, int v, int m)
{
    unsigned modes = v == TP_VARIANT_DEFAULT || v == TP_VARIANT_AB ? r->o->n_modes : r->o->variant_n_modes;
    return (modes >> m) & 1u;
}

struct rdoc;
/* The run's rows (rdoc.h), as throughput.json carries them and the page is drawn from them:
 * rdoc_delete them; NULL with "out of memory" in err. */
struct rdoc *tp_rows_new(const struct tp_run *r, char *err, size_t errlen);
/* throughput.json (its detail and the rows d) and throughput.csv of a run. Return 0, or -1 with
 * err filled. */
int tp_write_json(const struct tp_run *r, const struct rdoc *d, const char *path, char *err, size_t errlen);
int tp_write_csv(const struct tp_run *r, const char *path, char *err, size_t errlen);
/* The page of the rows (report_throughput.h) as text (md = 0) or markdown (md = 1, throughput.md):
 * malloc'd, NULL when out of memory. */
char *tp_tables_text(const struct rdoc *d, int md);

#endif
