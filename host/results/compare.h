/* compare.h - `brdfbench compare`: the results of several runs side by side, the first one the
 * baseline. A run is a run folder or a single result file of any command: throughput.json,
 * accuracy.json, render.json, fit.json, frontier.json.
 *
 * The files are read as rows of the result document (rdoc_read.h), so compare knows no file's
 * layout. Every figure of every run becomes a cell of a row; rows are matched across runs by their
 * keys (throughput: device, model with parameters, build-option variant, n mode; accuracy:
 * device, model, figure, grid; render: device, scene, model; fit: the fitted role or model,
 * grid; frontier: model). A row found in only some runs is kept, its missing cells marked.
 * One run whose rows carry several devices (`--device all`) is laid out as one column per
 * device, as if each device were a run.
 *
 * Verdicts against the baseline:
 *   - a speed (evaluations/s, Mpixel/s): the Mann-Whitney test of the two runs' repetitions
 *     (ranktest.h) at level alpha: "faster" or "slower" when it tells them apart, else "same";
 *     "undecided" when the sample sizes cannot reach alpha at all (too few repetitions).
 *     A file that keeps only min/median/max (render.json): "same" when the two min..max
 *     ranges overlap.
 *   - an accuracy figure (an error, lower is better; a PSNR, higher is better) or another
 *     value: "unchanged" when both round to the same 4 significant digits, else "changed"
 *     with the signed change, and whether that is better or worse. */
#ifndef BRDF_COMPARE_H
#define BRDF_COMPARE_H

#include "rdoc_read.h"
#include "schemas.h"
#include <stddef.h>

#define CMP_MAX_RUNS 16
#define CMP_MAX_CTX 32
#define CMP_TEXT 256
#define CMP_DEFAULT_ALPHA 0.05
#define CMP_DEFAULT_THRESHOLD 0.10   /* 10%: the smallest change a speed verdict calls (scripts/bench_compare.sh) */
#define CMP_WARN_REPS 5             /* fewer repetitions per side: compare warns */

/* The kinds are the result documents' (rdoc_read.h), in their order. */
enum cmp_kind {
    CMP_THROUGHPUT = RD_KIND_THROUGHPUT,
    CMP_ACCURACY = RD_KIND_ACCURACY,
    CMP_RENDER = RD_KIND_RENDER,
    CMP_FIT = RD_KIND_FIT,
    CMP_FRONTIER = RD_KIND_FRONTIER,
    CMP_MEASURED = RD_KIND_MEASURED,
    CMP_KIND_COUNT = RD_KIND_COUNT
};
const char *cmp_kind_name(int kind);      /* "throughput", ... */

/* What a figure means for a verdict. */
enum cmp_sense {
    CMP_SPEED = 0,   /* higher is better; decided by the repetitions */
    CMP_ERROR,       /* lower is better; decided at the 4th significant digit */
    CMP_SCORE,       /* higher is better (PSNR); 4th significant digit */
    CMP_VALUE        /* neither (a fitted coefficient); 4th significant digit */
};

enum cmp_verdict {
    CMP_V_NONE = 0,      /* the baseline's own cell, or a cell with nothing to compare */
    CMP_V_MISSING,       /* the row is not in this run (or not in the baseline) */
    CMP_V_FAILED,        /* the figure failed in this run or the baseline */
    CMP_V_SAME,
    CMP_V_FASTER,
    CMP_V_SLOWER,
    CMP_V_UNDECIDED,     /* too few repetitions for the test to reach alpha */
    CMP_V_UNCHANGED,
    CMP_V_BETTER,        /* changed at the 4th digit, for the better */
    CMP_V_WORSE,         /* changed at the 4th digit, for the worse */
    CMP_V_CHANGED,       /* changed at the 4th digit (a value with no better or worse) */
    CMP_V_NOISY          /* the repetitions spread too widely to decide a change of the asked size */
};
const char *cmp_verdict_name(int v);      /* "same", "slower", "changed, worse", ... */

struct cmp_cell {
    int present;                 /* the row exists in this run */
    int ok;                      /* its figure was measured */
    char reason[CMP_TEXT];       /* why not, when present && !ok */
    double value;                /* the figure (a speed: the median) */
    double lo, hi;               /* a speed's min and max; NAN when unknown */
    double *reps;                /* a speed's repetitions (malloc'd), or NULL */
    int nreps;
    /* against the baseline's cell of the same row */
    double ratio;                /* value / baseline value (NAN when either is missing or 0) */
    double change;               /* value - baseline value */
    double p;                    /* the rank test's two-sided p (NAN when not tested) */
    double p_adj;                /* p after Holm's correction over the run's speed rows (= p without --holm) */
    double ci_lo, ci_hi;         /* the ratio's confidence interval at 1 - alpha (Hodges-Lehmann on logs) */
    int basis;                   /* what decided a speed: enum cmp_basis */
    double *norm;                /* a speed's normalised repetitions (rate / the run's reference kernel
                                    in the same round; malloc'd), or NULL */
    int nnorm;
    int norm_cpu;                /* norm holds the normalised rates per CPU second */
    int retries, disturbed;      /* preemption retries and disturbed repetitions behind the figure */
    int verdict;                 /* enum cmp_verdict */
};

/* What a speed verdict was decided on. */
enum cmp_basis {
    CMP_BASIS_NONE = 0,
    CMP_BASIS_NORMALISED,        /* both runs' normalised repetitions (the drift of the machine cancelled) */
    CMP_BASIS_ABSOLUTE,          /* both runs' absolute repetitions */
    CMP_BASIS_RANGES,            /* min..max ranges only (no repetitions kept) */
    CMP_BASIS_CPU                /* both runs' normalised rates per CPU second (a CPU device) */
};

struct cmp_row {
    int kind;                    /* enum cmp_kind */
    char device[CMP_TEXT];       /* "" when the file names none per row (then the context's) */
    char key[CMP_TEXT];          /* the rest of the key, e.g. "cq2 | default | n uniform" */
    char model[CMP_TEXT];        /* the model (with parameters), for grouping */
    char metric[64];             /* e.g. "evals_per_s", "epicentre.max_rel" */
    int sense;                   /* enum cmp_sense */
    int in_all;                  /* present in every run */
    struct cmp_cell cell[CMP_MAX_RUNS];
};

struct cmp_run {
    char path[1024];             /* as given */
    char name[CMP_TEXT];         /* column heading: the folder's or file's name, or the device */
    char files[CMP_TEXT];        /* the result files read, comma-separated */
    int nctx;
    char ctx_key[CMP_MAX_CTX][48];
    char ctx_value[CMP_MAX_CTX][CMP_TEXT];
    int disturbed;               /* repetitions the runner kept although preempted (context.throughput.runner) */
};

struct compare_set {
    struct cmp_run run[CMP_MAX_RUNS];
    int nruns;
    int by_device;               /* one run's devices laid side by side */
    struct cmp_row *rows;
    int nrows, cap;
    double alpha;
    double threshold;            /* the smallest change a speed verdict calls, as a fraction (0.10: 10%) */
    int holm;                    /* Holm's family-wise correction over each run's speed rows */
    int min_reps;                /* fewer repetitions than this on a side: a warning */
    int absolute;                /* decide on absolute rates even where normalised ones exist */
    int confirm;                 /* --fail-if-slower: a row fails only when every run finds it slower
                                    (the runs after the first are its confirmations) */
    /* the devices a --device all file lists (context.devices): name = tag, with their context */
    struct cmp_run devices[CMP_MAX_RUNS];
    int ndevices;
    /* counts after compare_evaluate */
    int rows_in_all, rows_in_some;
    /* rows by (kind, device, key, metric) while files are read: an open-addressing table of
       row indices + 1 (0: empty), rebuilt when nrows changed behind it (compare.c) */
    int *index;
    int index_cap, index_n;
};

/* Reads the runs at paths[0..npaths) (the first is the baseline). Returns 0, or 2 with a
 * one-line reason: a missing path, a folder without result files, a file of another schema
 * or version, or runs with no row in common. */
int compare_load(struct compare_set *set, const char *const *paths, int npaths, char *err, size_t errlen);

/* Fills every cell's ratio, change, p and verdict against the baseline (alpha: the rank
 * test's level, in (0, 1)), with the threshold, holm, min_reps and absolute fields of set
 * as they are (compare_load sets their defaults: 5%, off, 5, off).
 *
 * A speed: decided on the normalised repetitions where both cells have them (else the
 * absolute ones): the ratio is the Hodges-Lehmann estimate of the ratio of the two samples
 * (on logarithms) with its confidence interval at 1 - alpha; "faster"/"slower" when the rank
 * test's p (Holm-adjusted with holm) is below alpha AND the ratio is beyond 1 +- threshold;
 * "noisy" when not, and the interval is wider than the band 1/(1+threshold)..(1+threshold)
 * (the repetitions cannot tell such a change from noise); "same" otherwise; "undecided" when
 * the sample sizes cannot reach alpha at all. */
void compare_evaluate(struct compare_set *set, double alpha);
/* compare's rule for a speed, on two samples outside a compare set: rates x (the one judged)
 * against rates y (its baseline), each a repetition (normalised or absolute, both alike). The
 * rank test on their logarithms at level alpha, the Hodges-Lehmann ratio x/y with its interval
 * at 1 - alpha, and the minimum effect threshold, as compare_evaluate decides a cell (without
 * Holm): verdict CMP_V_FASTER, CMP_V_SLOWER, CMP_V_SAME, CMP_V_NOISY or CMP_V_UNDECIDED.
 * Returns 0, or -1 when a side has no finite positive value. */
struct compare_speed {
    int verdict;
    double ratio, ci_lo, ci_hi, p;
};
int compare_speed_rule(const double *x, int nx, const double *y, int ny, double alpha, double threshold,
                       struct compare_speed *out);
/* The fewest repetitions of a measured speed cell when below set->min_reps, else 0. */
int compare_few_reps(const struct compare_set *set);

/* The context entry `key` of run r, or NULL. */
const char *compare_context(const struct compare_set *set, int r, const char *key);

/* The rows that fail a CI condition, named one per line into out (NULL: counted only):
 * slower_pct >= 0: a speed row with the verdict "slower" whose ratio is below
 * 1 - slower_pct / 100; less_accurate: an accuracy row (error or PSNR) "changed, worse".
 * Under either condition a row of its sense that the baseline measured and a later run lost
 * (missing there, or failed: status failed or device_disagrees, a figure not finite) fails
 * too. Rows are matched by their keys, which never hold a fitted figure: fit.json's quadratic
 * is compared as the role it plays ("best affine k(n)", "capped at fq2's max Delta"), not by
 * its label quad:a=...,b=..., so two runs whose fit moved a little still match.
 * Returns the number of such cells. */
int compare_failures(const struct compare_set *set, double slower_pct, int less_accurate, char **out);

void compare_free(struct compare_set *set);

#endif
