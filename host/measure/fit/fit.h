/* fit.h - the cosine-quadratic family f = (k(n)(c - 1) + 1)^2, zeroed past its root:
 * its accuracy limit per n (the minimax k(n) of the epicentre's max delta) and the best
 * affine k(n) = a n + b over a range of n (minimax of max delta over the whole range,
 * optionally with a cap on the attenuation zone's max Delta). The fitted model is the
 * registry's `quad:a=...,b=...`, so every command can use it.
 *
 * Per n, f/c^n - 1 is unimodal over the epicentre (its derivative in c vanishes once, at
 * c* = n(k-1)/(k(n-2))), so the epicentre's max delta is exact from three points; the
 * attenuation zone's max Delta is found on a grid and polished with GSL Brent. f falls
 * pointwise as k grows, so each error side is monotone in k and every "error <= t" set of k
 * is an interval: the affine minimax is a bisection on t over a two-variable feasibility
 * problem, solved exactly. The fitted model's figures are then measured by the device sweep
 * (accuracy.h) beside fq2, fvol and cq2. */
#ifndef BRDF_FIT_H
#define BRDF_FIT_H

#include "schemas.h"
#include <stddef.h>

#include "accuracy.h"
#include "clsession.h"
#include "engine.h"

#define FIT_COMPARE_COUNT 3          /* fq2, fvol, cq2 */
#define FIT_TRADEOFF_POINTS 5
#define FIT_CAP_MIN 1e-6             /* smallest cap on max delta or max Delta accepted */

enum fit_objective { FIT_MAX_REL = 0, FIT_MAX_ABS };

struct fit_options {
    struct engine_io io;             /* the run folder (NULL: no fit.json) and --quiet (engine.h) */
    double n_min, n_max, n_step;     /* the n grid, as the accuracy sweep's */
    double max_abs_cap;              /* cap on the attenuation zone's max Delta; NAN: none */
    long samples;                    /* samples per zone of the device sweeps */
    /* Any family (fit_family_run): a registry or user model with one or two continuous
       parameters, or the power family ((a n + b)(c - 1) + 1)^m at a fixed m. */
    const char *model;               /* NULL: the quadratic family's exact fit above */
    int power_m;                     /* 0: none; 1..16: the power family at this m */
    int objective;                   /* enum fit_objective: what is minimised */
    double max_rel_cap;              /* cap on the epicentre's max delta; NAN: none */
};

void fit_options_default(struct fit_options *o);

/* Errors of f = (k(c-1)+1)^2 (zeroed past its root) against c^n at one n, in double.
 * over = max (f/r - 1), under = max (1 - f/r) over the epicentre (both >= 0); the max delta
 * is the larger. The abs_ pair is the same for f - r and r - f over the attenuation zone. */
struct fit_sides {
    double over, under;
};
struct fit_sides fit_epicentre_sides(double n, double k);
struct fit_sides fit_attenuation_sides(double n, double k);
double fit_epicentre_max_rel(double n, double k);
double fit_attenuation_max_abs(double n, double k);

/* The per-n minimax: the k that minimises the epicentre's max delta, and that minimum
 * (the family's accuracy limit at n). Returns 0, or -1 if GSL failed. */
int fit_minimax_k(double n, double *k_out, double *max_rel_out);

struct fit_limit {
    double n, k, max_rel;
};

struct fit_affine {
    double a, b;
    int feasible;                     /* 0: no affine k(n) meets the cap (see reason) */
    double cap;                       /* NAN: none */
    double max_rel, max_rel_n;        /* host (double) objective at (a, b) */
    double max_abs, max_abs_n;        /* host attenuation max Delta at (a, b) */
    char reason[256];
};

/* Best affine k(n) over the n values given (count >= 2, increasing): minimises the largest
 * epicentre max delta, with every attenuation max Delta <= cap when cap is finite.
 * limit[] holds fit_minimax_k at the same n (a lower bound of the objective). */
int fit_affine_minimax(const double *n, long count, const struct fit_limit *limit, double cap,
                       struct fit_affine *out);

/* One fitted model with its device-measured figures. */
struct fit_model {
    struct fit_affine fit;
    char spec_text[128];              /* quad:a=...,b=... */
    struct model_spec spec;
    struct accuracy_result sweep;     /* the device sweep of the fitted model */
    int have_sweep;
};

struct fit_report {
    struct fit_options opt;
    struct accuracy_grid grid;
    long n_count;
    struct fit_limit *limit;          /* per n of the grid */
    double limit_max, limit_max_n;    /* the family's limit over the range */
    struct fit_model main;            /* with opt.max_abs_cap (none by default) */
    struct fit_model at_fq2_cap;      /* capped at fq2's own attenuation max Delta */
    struct accuracy_result compare[FIT_COMPARE_COUNT];
    int compare_count;
    /* The delta-Delta trade-off between the two fits: the best max delta for caps spaced
       from fq2's max Delta to the uncapped fit's (host figures). */
    struct fit_affine tradeoff[FIT_TRADEOFF_POINTS];
    int tradeoff_count;
    int beats_fq2_rel, not_worse_abs; /* the main fit against fq2 */
    char verdict[512];
    double seconds;
};

/* Runs the fit and the device sweeps; writes o->io.out_dir/fit.json when out_dir is not NULL
 * and prints a summary unless o->io.quiet. The report is filled when `report` is not NULL (free
 * it with fit_report_free). Returns 0 or an exit code. */
int fit_run(struct cl_session *s, const struct fit_options *o, struct fit_report *report);
/* 1 when the options ask for more than the quadratic family's exact fit (another family, the
 * max_abs objective, a cap on max delta): fit_family_run serves them. */
int fit_wants_family(const struct fit_options *o);
void fit_report_free(struct fit_report *r);
/* Checks the options (range, step, cap, samples). Returns 0 or EXIT_USAGE with a message. */
int fit_options_check(const struct fit_options *o, char *err, size_t errlen);

/* ---- any family: minimax by Nelder-Mead (GSL) on host figures ------------------------------ */

#define FIT_POWER_M_MAX 16

/* One fitted point of a family: its parameters and its figures over the whole n grid. */
struct fit_point {
    int ok;                           /* 0: the search found no point meeting the cap (reason) */
    double params[2];
    double cap;                       /* NAN: none */
    double max_rel, max_rel_n;        /* host double figures over every n of the grid */
    double max_abs, max_abs_n;
    char reason[160];
};

struct fit_family_report {
    struct fit_options opt;
    struct accuracy_grid grid;
    char family[96];                  /* the model id, or "power:m=M" */
    int nparams;
    char param_names[2][16];
    struct fit_point best;            /* the objective, with its cap */
    struct fit_point min_rel, min_abs;/* the two ends of the trade-off, uncapped */
    struct fit_point tradeoff[FIT_TRADEOFF_POINTS];
    int tradeoff_count;
    char spec_text[128];              /* the fitted model for --models, or "" (power m > 4) */
    struct accuracy_result sweep;     /* the device sweep of the fitted model */
    int have_sweep;
    double seconds;
};

/* The power family ((a n + b)(c - 1) + 1)^m zeroed past its root, in double (the header's
 * brdf_power), for the fit and the tests. */
double fit_power_eval(double c, double n, double a, double b, int m);

/* Host figures of a family point over the n values given: the epicentre's max delta and the
 * attenuation's max Delta, each per n by a grid polished with Brent. family NULL: power m. */
void fit_family_figures(const struct model_spec *family, int power_m, const double *params, const double *n,
                        long count, struct fit_point *out);

/* Runs a family fit (options with model or power_m set), the device sweep of the result when
 * it is a registry or user model, writes o->io.out_dir/fit.json, prints unless o->io.quiet. */
int fit_family_run(struct cl_session *s, const struct fit_options *o, struct fit_family_report *report);
void fit_family_report_free(struct fit_family_report *r);

/* Beaudoin and Guardado 2002: for f = max(0, A c + 1 - A)^m against c^n, the A that makes the
 * largest positive and negative errors of f - c^n over c in [0, 1] equal (bisection on A), and
 * that largest |f - c^n|. Returns 0, or -1 when no A in (0, max(n, 1)] balances them. */
int fit_bg_exact_a(double n, int m, double *a_out, double *max_abs_out);

#endif
