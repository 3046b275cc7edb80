/* throughput.h - every model's cost on the OpenCL device (docs/definitions.md, Throughput), side by side
 * with the pow() built-in, a tuned C loop doing the same work, and the device's measured peak;
 * under three sets of build options, each with what it does to accuracy. Optionally the
 * accuracy sweep itself against the same sweep in tuned C.
 *
 * Timing protocol (docs/architecture.md, habit 7): every program build is timed on its own; each kernel
 * is first launched with the exact NDRange it is timed with (PoCL compiles per launch shape);
 * the iterations per launch are calibrated until one launch takes --min-time; then --reps
 * launches give min / median / max from the OpenCL profiling events and from wall time. All
 * ratios are between figures measured in the same run. */
#ifndef BRDF_THROUGHPUT_H
#define BRDF_THROUGHPUT_H

#include "schemas.h"
#include "accuracy.h"
#include "engine.h"
#include "clsession.h"
#include "models.h"
#include "brdf_shared.h"   /* TP_STREAMS, PEAK_CHAINS */

/* Version 3 adds the runner's record: context.throughput.runner, and per figure its normalised
 * rates (normalised, normalised_reps), preemption retries and timer; the peak's flops_per_s_reps
 * replace flops_per_s_first/last. Version 2 added evals_per_s_reps. compare reads 2 and 3;
 * plot reads 1 to 3. */
#define TP_EVALS_PER_ITER (16 * TP_STREAMS)
#define TP_MAX_MODELS 64
#define TP_MAX_REPS 1000
#define TP_MIN_TIME_MIN 1e-4
#define TP_MIN_TIME_MAX 10.0
#define TP_MAX_WORK_ITEMS 65536
#define TP_MAX_ITERS (1L << 24)

/* Build-option variants: what each does to speed, and to accuracy against the double reference. */
/* TP_VARIANT_AB: the default variant with the build options of --ab-options added, measured in the
 * same interleaved rounds as the default one (an A/B comparison in one process). */
enum tp_variant { TP_VARIANT_DEFAULT = 0, TP_VARIANT_FAST_RELAXED, TP_VARIANT_DENORMS_ZERO, TP_VARIANT_AB, TP_VARIANT_COUNT };
/* How n reaches the model: one value per launch (a material), or one per evaluation (a map). */
enum tp_nmode { TP_N_UNIFORM = 0, TP_N_VARYING, TP_NMODE_COUNT };

const char *tp_variant_name(int v);      /* "default", "fast-relaxed-math", "denorms-are-zero" */
const char *tp_variant_options(int v);   /* "", "-cl-fast-relaxed-math", "-cl-denorms-are-zero" */
const char *tp_nmode_name(int m);        /* "uniform", "varying" */

struct throughput_options {
    struct engine_io io;         /* the run folder and --quiet (engine.h) */
    struct model_spec models[TP_MAX_MODELS];
    int model_count;             /* 0: every model of the default set */
    int reps;                    /* rounds of the runner: timed launches per figure, 1..TP_MAX_REPS */
    double min_time;             /* seconds one timed launch takes at least */
    unsigned variants;           /* bit (1 << enum tp_variant) per variant to measure */
    unsigned n_modes;            /* bit (1 << enum tp_nmode) per mode to measure */
    unsigned variant_n_modes;    /* n modes measured under the non-default variants */
    int host_c;                  /* time the C baseline too */
    int threads;                 /* C baseline threads; 0: the online CPUs */
    long work_items;             /* device work-items per launch (0: clsession_default_work_items) */
    double n_uniform;            /* n of the uniform mode */
    double n_lo, n_hi;           /* range of n in the varying mode */
    int sweep;                   /* also time the accuracy sweep against the same sweep in C */
    struct accuracy_grid sweep_grid;
    int sweep_reps;
    const char *base_options;    /* build options added to every variant (NULL: none) */
    unsigned long long seed;     /* of the runner's round orders (host/core/runner.h) */
    const char *ab_options;      /* the build options of TP_VARIANT_AB (NULL: no A/B) */
};

/* The configuration `brdfbench throughput` starts from, and the one `brdfbench all` runs
 * (about 20 s on a 2-core machine): every model, 3 variants, both n modes, C baseline, sweep. */
void throughput_options_default(struct throughput_options *o);
/* Checks every field against its domain. Returns 0 or EXIT_USAGE with a one-line message. */
int throughput_options_check(const struct throughput_options *o, char *err, size_t errlen);

/* What a run gives back: the summary tables as markdown, for report.md (malloc'd; NULL on
 * failure). */
struct throughput_result {
    char *markdown;
};
void throughput_result_free(struct throughput_result *r);

/* Measures, prints a table on stdout unless o->io.quiet, and writes o->io.out_dir's
 * throughput.json and throughput.csv. A figure that cannot be measured (build failure, timer
 * error) is a row with status and reason, not a failure of the run. Returns 0 or an exit code
 * (EXIT_RUNTIME when the results cannot be written or the device fails outright). r may be NULL. */
int throughput_run(struct cl_session *s, const struct throughput_options *o, struct throughput_result *r);

/* ---- lower level, for tests ------------------------------------------------------------ */

/* The throughput program of one variant: a kernel set per model plus the pow() built-in. */
struct tp_program {
    struct cl_session *s;
    cl_program program;
    int variant;
    char options[256];
    double build_seconds;
    int ids[TP_MAX_MODELS];       /* kernel ids compiled in */
    int id_count;
    /* Each user model's own build of throughput.cl (its kernels named by BRDF_USER), and in
       a session that specialises each built-in model's (host/core/programs.h). */
    struct {
        const struct model_info *model;
        cl_program program;
    } user[TP_MAX_MODELS];
    int user_count;
};

/* Builds kernels/throughput.cl with one kernel set per distinct model id of models, and a
 * build of its own for each user model. Returns 0 or an exit code; the build log is printed
 * on failure (EXIT_USAGE: a user model does not compile). */
int tp_program_build(struct tp_program *p, struct cl_session *s, const struct model_spec *models, int count,
                     int variant, const char *base_options);
void tp_program_release(struct tp_program *p);
/* Evaluates model m (NULL: the pow() built-in) at count points with the tp_points kernel. */
int tp_program_points(struct tp_program *p, const struct model_spec *m, const float *c, const float *n,
                      size_t count, float *out);
/* One launch of tp_uniform/tp_varying for m (NULL: pow) over work_items work-items and iters
 * iterations; sums receives work_items x 16 partial sums. Uses the n of o. */
int tp_program_launch(struct tp_program *p, const struct model_spec *m, int nmode, const struct throughput_options *o,
                      long work_items, long iters, float *sums, double *event_seconds);
/* One model (NULL: pow) in one n mode, timed by tp_time_set. */
struct tp_timed {
    const struct model_spec *m;
    int nmode;
    /* filled */
    int ok;
    char reason[240];
    double rate[3];              /* evaluations/s: min, median, max over the rounds */
    double norm[3];              /* rate / the peak kernel's rate in the same round (per CPU second on a CPU
                                    device): min, median, max */
    int nreps;
};
/* Times t[0..count) from program p in the runner's interleaved rounds (o->reps rounds, o->min_time
 * per launch, o->seed), the peak kernel as every round's reference. Returns 0 (a figure that
 * cannot be measured has ok 0 and its reason), or EXIT_RUNTIME when out of memory. */
int tp_time_set(struct tp_program *p, struct tp_timed *t, int count, const struct throughput_options *o,
                long work_items, int quiet);
/* The C baseline's sums against the device's: model m (NULL: pow) in n mode nmode, one launch of
 * each over work_items work-items and TP_CHECK_ITERS iterations, the same inputs. The two add the
 * same values in the same order, so they differ only by the float functions' last bits (libm
 * against the device's): agreed when |device - C| <= TP_CHECK_TOL x the sum of |C's sums|.
 * Another result means the C loop does other work than the kernel and its rate is no baseline.
 * Returns 0 with *agree, or an exit code (a launch failed: err says which). */
#define TP_CHECK_ITERS 16
/* The C sweep's per-n figures against the device's (throughput.c, rel_diff): agreed up to this. */
#define TP_SWEEP_AGREE_TOL 1e-2
#define TP_CHECK_TOL 1e-4
struct tp_sums_check {
    long iters, work_items;
    double device_sum, c_sum, c_abs_sum, rel_diff;
    int agree;
};
int tp_check_host_c(struct tp_program *p, const struct model_spec *m, int nmode, const struct throughput_options *o,
                    long work_items, int threads, struct tp_sums_check *out, char *err, size_t errlen);
/* The inputs of such a launch, for tp_input_at (host/support/hostc_baseline.h). */
struct tp_inputs;
void tp_inputs_for(const struct throughput_options *o, int nmode, long work_items, long iters, struct tp_inputs *in);

#endif
