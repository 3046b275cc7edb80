/* reproduce_claims.h - inside reproduce: the claim rows and their verdicts (reproduce_claims.c:
 * both papers' claims as a table, one row per claim) and the host numerics behind them
 * (reproduce_math.c). Not an interface for other modules. */
#ifndef BRDF_REPRODUCE_CLAIMS_H
#define BRDF_REPRODUCE_CLAIMS_H

#include <stddef.h>

#include "models.h"
#include "reproduce.h"
#include "reproduce_report.h"

/* ---- a claim row and its verdict (reproduce_claims.c) ---- */

/* Appends a row (NULL when out of memory); claimed and measured start as NAN. */
struct claim *claim_add(struct reproduce_report *r, const char *kind, const char *id, const char *source,
                        const char *text);
void setf(char *dst, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Appends a sentence to the row's note. */
void note_add(struct claim *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* A numeric claim: reproduced when |measured - claimed| <= tol (a hair of relative slack). */
void claim_number(struct claim *c, const char *claimed_text, double claimed, double measured, double tol,
                  const char *tol_text);
/* A claim that holds or does not. */
void claim_bool(struct claim *c, const char *claimed_text, int holds, const char *tol_text);
/* Paper 1's and paper 2's claims, in the order of claims.json. Returns 0 or an exit code. */
int reproduce_add_papers(struct repro *p);

/* ---- host numerics (reproduce_math.c) ---- */

/* A root of f over [lo, hi] (sign change required), GSL Brent. NAN when there is none. */
double root_brent(double (*f)(double, void *), void *ctx, double lo, double hi);
/* GSL Brent minimisation over [lo, hi] from m (f(m) below both ends required). */
double minimise_brent(double (*f)(double, void *), void *ctx, double lo, double m, double hi);

/* The largest per-n epicentre max delta of f_Q over n values, from the exact per-n figure of
 * the quadratic family (fit.h): f_Q is that family with k = k_Q(n). */
struct fq_ctx {
    const double *n;
    long count;
    double target;
    double at_n;
};
double fq_max_rel(double q, void *p);
double fq_max_rel_minus_target(double q, void *p);

/* The largest delta of a model over the epicentre at one n, on the host in double. */
double host_max_rel_at(const struct model_spec *m, double n);

/* Eq. 11's term `term` over n in [16, 256] with the zone ending at c^n = exp(-k), minus target. */
struct k_ctx {
    int term;
    double target;
};
double eq11_term_minus(double k, void *p);

/* The first angle where a model is exactly 0 at n (a quadratic past its root), by bisection. */
double model_zero(const char *id, double n);

/* cq2's delta at the end of a zone that ends where c^n = exp(-K), minus target. */
struct cq2_zone_ctx {
    const struct model_spec *m, *ref;
    double n, target;
};
double cq2_end_minus(double k, void *p);

#endif
