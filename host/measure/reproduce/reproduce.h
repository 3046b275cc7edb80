/* reproduce.h - re-derives every claim of both papers (docs/definitions.md, "What the papers claim") and
 * gives each a verdict: claims.json, claims.md, q_sweep.json, energy.json and a table.
 *
 * Every figure is measured, never assumed: max delta / max Delta by the device sweep
 * (accuracy.h, polished in double), the integrals of paper 1's eq. 11 by nested adaptive
 * quadrature on the host (GSL) and independently on the device (kernels/integrate.cl),
 * paper 2's coef(n) by adaptive quadrature of f_Q2 itself, the fits by least squares (GSL).
 * A claim is "reproduced" when the measured value is within the stated tolerance of the
 * claimed one (for a printed number: one unit in its last printed digit, which accepts the
 * paper's rounding or truncation); otherwise "not reproduced", with the measured value and,
 * where it can be found, why. */
#ifndef BRDF_REPRODUCE_H
#define BRDF_REPRODUCE_H

#include "schemas.h"
#include <stddef.h>

#include "clsession.h"
#include "engine.h"
#include "run.h"


struct reproduce_options {
    struct engine_io io;     /* the run folder and --quiet (engine.h) */
    long samples;            /* samples per zone of the claim sweeps (default 4096) */
    int grid_check;          /* re-run each claim sweep at twice the samples (default 1) */
    double q_min, q_max, q_step;   /* the Q sweep behind paper 2's figs. 2-3 */
    long q_samples;          /* samples per zone of the Q sweep (default 1024) */
    double q_n_step;         /* n step of the Q sweep (default 1) */
    int energy;              /* run the albedo and reciprocity checks (default 1) */
    int physical;            /* measure the physically based models' cost (pbcost.h; default 1) */
};
void reproduce_options_default(struct reproduce_options *o);
/* Checks the options. Returns 0 or EXIT_USAGE with a one-line message. */
int reproduce_options_check(const struct reproduce_options *o, char *err, size_t errlen);

struct claim {
    char id[32];
    char kind[8];            /* "claim" (a paper's) or "check" (a closed form the harness must meet) */
    char source[96];         /* paper, equation or figure */
    char text[320];          /* what is claimed */
    char claimed_text[64];
    double claimed;          /* NAN when the claim is not a number */
    char measured_text[192];
    double measured;
    char tolerance[160];
    int reproduced;
    int undecided;           /* a timing that cannot decide it: "within noise" (reproduced is then 0) */
    char note[768];          /* where it was measured, and why it differs */
    char method[192];
};

struct reproduce_report {
    struct claim *rows;
    int count, cap;
    int reproduced, not_reproduced, within_noise;
    char *markdown;          /* claims.md's text (malloc'd) */
    double seconds;
    /* The Q sweep behind paper 2's figs. 2-3 (also in q_sweep.json), for a later step of the
       same run (`all`'s plots), each figure as q_sweep.json has it (NaN where the file has null);
       n 0 when it ran no Q or more than RUN_MAX_Q. */
    struct run_q_sweep q_sweep;
};

/* Checks every claim and writes claims.json, claims.md, q_sweep.json (and energy.json) into
 * o->io.out_dir, the table on stdout unless o->io.quiet; fills `report` when not NULL (free
 * with reproduce_report_free): the rows and claims.md's markdown, for the main job's report. */
int reproduce_run(struct cl_session *s, const struct reproduce_options *o, struct reproduce_report *report);
void reproduce_report_free(struct reproduce_report *r);


/* Paper 1's eq. 11 on the host (nested adaptive GSL quadrature in x and n):
 * term 0: c^n, 1: n^2 (c-1)^2, 2: 2n (c-1), 3: 1, each times cos x sin x, over
 * x in [0, acos(exp(-zone_k/n))], n in [n_lo, n_hi]. Returns 0 or -1 (GSL failed). */
int eq11_host(double zone_k, double n_lo, double n_hi, int term, double *out);
/* coef(n) = 1/(2 pi int_0^gran(n) f_Q2 cos g sin g dg), gran(n) = acos((448n - 901)/(448n + 99))
 * capped at pi/2, by adaptive quadrature of the registry's fq2 (paper 2). */
double paper2_coef(double n);

#endif
