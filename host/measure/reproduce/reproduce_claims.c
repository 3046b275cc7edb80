/* reproduce_claims.c - both papers' claims as a table (one row per claim: paper and figure, what
 * is claimed, the claimed value, the tolerance rule, the sweep it is measured on, the method),
 * run by one function, reproduce_add_papers. A row's measure hook gives the measured value, its
 * annotate hook the measured text and the notes (where it was measured, why it differs). */
#include "reproduce_claims.h"
#include "accuracy.h"
#include "exitcodes.h"

#include <gsl/gsl_fit.h>
#include <gsl/gsl_poly.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* k_Q(n) of f_Q, from the model header itself (its single definition), in double. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

#define ZONE_K BRDF_ZONE_K           /* kernels/brdf_shared.h: the epicentre ends where c^n = exp(-0.511) */

/* ---- the table's vocabulary ------------------------------------------------------------------- */

enum claim_rule {
    RULE_NEAR,      /* |measured - claimed| <= tol */
    RULE_HOLDS,     /* the measure hook's value is non-zero */
    RULE_AT_MOST,   /* measured <= claimed */
};

/* Which extreme of a sweep a row reads when it has no measure hook of its own. */
enum claim_metric {
    METRIC_NONE,
    METRIC_EPI_REL,     /* the epicentre's max delta, printed in % */
    METRIC_WHOLE_ABS,   /* the whole range's max Delta */
};

/* What the hooks share: the run, and the figures worked out once for several rows. */
struct claim_env {
    struct repro *p;
    double claimed;                  /* the row's claimed value; a measure hook may work it out (eq. 14) */
    /* paper 1 */
    double host[4], dev[4], agree;   /* eq. 11's four integrals on the host and the device */
    double kfit, at_k[4];            /* the zone constant that gives the claimed constant, eq. 11 with it */
    int coefs_ok;                    /* all three eq. 12 coefficients reproduced */
    double x0, x1, c0, c1, d0, d1;   /* eq. 12's roots: measured, the paper's, the device's */
    double xi64;                     /* 29/64 */
    double z_fvol64, rmin, rmax, rmin_n, rmax_n, smin, smax, s45_n;
    long worse;
    char where[512];
    /* paper 2 */
    struct model_spec phong;
    double q_best;                                /* the minimising Q of the Q sweep */
    double worst_n;                               /* fig. 4 */
    double k_a, k_b, k_worst, kappa;              /* least-squares fit of k_Q(n) */
    char qgrid[256];                              /* the Q sweep, in words */
    double coef_a, coef_b;                        /* least-squares fit of coef(n) */
    double dev_theirs, dev_theirs_n, dev_own, dev_own_n, alb_max, alb_max_n, above_from;
    long above;
};

struct claim_row {
    const char *kind;                /* NULL: "claim" */
    const char *id, *source, *text;
    const char *claimed_text;
    double claimed;
    enum claim_rule rule;
    double tol;
    const char *tol_text;
    int sweep;                       /* SW_*: the sweep read by `metric` and named by the grid note */
    enum claim_metric metric;
    int grid_note;                   /* say how much twice the samples moves the sweep's figure */
    double arg;                      /* a per-row parameter of the hooks (a term, an n) */
    size_t value_at;                 /* no measure hook: offsetof the measured double in claim_env (0: the
                                        sweep's `metric`) */
    const char *measured_fmt;        /* the measured text from the measured value (NULL: the hook writes it) */
    const char *method;              /* NULL: the annotate hook writes it */
    double (*measure)(struct claim_env *e, const struct claim_row *row);
    int (*annotate)(struct claim_env *e, const struct claim_row *row, struct claim *c);
};

static const char *const digit = "+-0.001 (one unit in the last printed digit)";
static const char *const digit_rel = "+-0.001% (one unit in the last printed digit)";
static const char *const digit_5 = "+-1e-5 (one unit in the last printed digit)";
static const char *const digit_01 = "+-0.1 (one unit in the last printed digit)";
static const char *const eq11_method = "host: nested adaptive GSL QAG in x and n (rel. 1e-12); device: Gauss-Legendre "
                                       "in u = cos x (float), outer sum in double";
static const char *const sweep_method = "device sweep, n in [2, 1000] step 1, polished in double";
static const char *const p1_sweeps = "device sweeps of fvol, cq2, schlick, n in [16, 1000] step 1";
static const char *const q_method = "device sweeps over Q; GSL Brent over Q";
static const char *const k_fit_method = "GSL gsl_fit_linear on k_Q(n) at n = 2, 3, ..., 1000";
static const char *const coef_method = "adaptive GSL QAG of the registry's fq2, gran(n) capped at pi/2";
static const char *const coef_fit_method = "GSL gsl_fit_linear on coef(n) at n = 2, 3, ..., 1000";

static const struct accuracy_result *sweep(const struct claim_env *e, int sw) { return &e->p->sw[sw]; }
static double per_n_rel(const struct accuracy_result *a, long i) { return a->per_n[i].epi_rel_d.value; }

static const struct acc_extreme *row_extreme(const struct claim_env *e, const struct claim_row *row)
{
    const struct accuracy_result *a = sweep(e, row->sweep);
    return row->metric == METRIC_EPI_REL ? &a->epicentre : &a->whole;
}

static double measure_extreme(struct claim_env *e, const struct claim_row *row)
{
    return row_extreme(e, row)->value;
}

/* The measured text of a sweep extreme, as paper 2's rows print it. */
static int annotate_extreme(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    const struct acc_extreme *x = row_extreme(e, row);
    if (row->metric == METRIC_EPI_REL)
        setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g, x = %.5f", 100 * x->value, x->n, x->x);
    else
        setf(c->measured_text, sizeof c->measured_text, "%.5f at n = %g, x = %.4f", x->value, x->n, x->x);
    return 0;
}

/* ---- paper 1: the figures several rows share ------------------------------------------------ */

static int prepare_paper1(struct claim_env *e)
{
    struct repro *p = e->p;
    for (int t = 0; t < 4; ++t)
        if (eq11_host(ZONE_K, 16.0, 256.0, t, &e->host[t])) {
            fprintf(stderr, "brdfbench reproduce: eq. 11: GSL quadrature failed (term %d)\n", t);
            return EXIT_RUNTIME;
        }
    int rc = integrate_eq11_device(&p->ic, ZONE_K, 16.0, 256.0, e->dev);
    if (rc)
        return rc;
    e->agree = 0;
    for (int t = 0; t < 4; ++t)
        e->agree = fmax(e->agree, fabs(e->host[t] - e->dev[t]) / fabs(e->host[t]));
    /* The zone constant K (c^n = exp(-K) at the zone end) that would give the claimed constant
       coefficient: a diagnostic of how the paper's numbers may have been computed. */
    struct k_ctx kc = { 3, 1.40119 };
    e->kfit = root_brent(eq11_term_minus, &kc, 0.50, 0.52);
    for (int t = 0; t < 4; ++t)
        e->at_k[t] = NAN;
    if (isfinite(e->kfit))
        for (int t = 0; t < 4; ++t)
            eq11_host(e->kfit, 16.0, 256.0, t, &e->at_k[t]);
    e->coefs_ok = 1;
    e->x0 = e->x1 = e->c0 = e->c1 = e->d0 = e->d1 = NAN;
    gsl_poly_solve_quadratic(e->host[1], e->host[2], e->host[3] - e->host[0], &e->x0, &e->x1);
    gsl_poly_solve_quadratic(0.12026, -0.71068, 1.40119 - 1.098, &e->c0, &e->c1);
    gsl_poly_solve_quadratic(e->dev[1], e->dev[2], e->dev[3] - e->dev[0], &e->d0, &e->d1);
    e->xi64 = 29.0 / 64.0;
    return 0;
}

/* ---- paper 1: eq. 11-14 ----------------------------------------------------------------------- */

static double measure_eq11(struct claim_env *e, const struct claim_row *row) { return e->host[(int)row->arg]; }

static int annotate_eq11_lhs(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    note_add(c, "Device quadrature %.7f.", e->dev[0]);
    return 0;
}

static int annotate_eq12(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    int t = (int)row->arg;
    e->coefs_ok &= c->reproduced;
    note_add(c, "Device quadrature %.7f; measured/claimed - 1 = %+.2e.", e->dev[t], e->host[t] / row->claimed - 1);
    if (!c->reproduced && isfinite(e->kfit))
        note_add(c, "Diagnostic: the zone end that reproduces the claimed constant is c^n = exp(-%.6f) (-ln 0.6 = "
                    "%.6f: c^n = 0.6) instead of exp(-0.511); with it the three coefficients are %.5f, %.5f, %.5f "
                    "(claimed 0.12026, -0.71068, 1.40119) and the left side %.4f.", e->kfit, -log(0.6), e->at_k[1],
                 e->at_k[2], e->at_k[3], e->at_k[0]);
    return 0;
}

static int annotate_xi(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "%.5f (both roots: %.5f, %.4f)", e->x0, e->x0, e->x1);
    note_add(c, "The paper's own eq. 12 gives %.5f and %.4f; the device's coefficients give %.5f and %.4f. The larger "
                "root would make the lobe far narrower than c^n and is not the model.", e->c0, e->c1, e->d0, e->d1);
    if (!e->coefs_ok)
        note_add(c, "The root holds although the coefficients differ in their 4th digit: it is insensitive to them.");
    return 0;
}

static int annotate_xi64(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    double xi64 = e->xi64, rhs64 = e->host[1] * xi64 * xi64 + e->host[2] * xi64 + e->host[3];
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *fv64 = sweep(e, SW_FVOL64);
    setf(c->measured_text, sizeof c->measured_text, "29/64 = %.6f (%+.2f%%)", xi64, 100 * (xi64 / 0.463 - 1));
    note_add(c, "The nearest 64th of 0.463 (and of the measured root %.5f) is 30/64 = 0.46875 (%+.2f%%). At xi = 29/64 "
                "the right side of eq. 11 is %.5f, %+.2f%% off the left side.", e->x0, 100 * (30.0 / 64 / 0.463 - 1),
             rhs64, 100 * (rhs64 / e->host[0] - 1));
    note_add(c, "In the epicentre the 29/64 variant is nevertheless the more accurate one over n in [16, 1000]: "
                "max delta %.4f%% (fvol64) against %.4f%% (fvol).", 100 * fv64->epicentre.value,
             100 * fv->epicentre.value);
    return 0;
}

/* Eq. 14: the angle F_VOL is zeroed from; the claimed value is eq. 14 itself at n = 16. */
static double measure_eq14(struct claim_env *e, const struct claim_row *row)
{
    double n16 = row->arg;
    e->claimed = acos((29.0 * n16 - 64.0) / (29.0 * n16));
    e->z_fvol64 = model_zero("fvol64", n16);
    return model_zero("fvol", n16);
}

static int annotate_eq14(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    double eq14 = c->claimed, z_fvol = c->measured;
    setf(c->claimed_text, sizeof c->claimed_text, "%.6f rad", eq14);
    setf(c->measured_text, sizeof c->measured_text, "%.6f rad (F_VOL's own zero)", z_fvol);
    /* F_VOL's unclipped base at eq. 14's angle: 1 - 0.463 * 64/29 (paper 1's xi). */
    double base = 1.0 - 0.463 * 64.0 / 29.0;
    note_add(c, "Eq. 14 is the zero of the 29/64 variant (fvol64's zero: %.6f rad, %.1e from it). F_VOL with "
                "xi = 0.463 is zero from acos(1 - 1/(0.463 n)) = %.6f rad on; zeroed only from eq. 14's angle, it "
                "would rise back to %.2e there.", e->z_fvol64, fabs(e->z_fvol64 - eq14), z_fvol, base * base);
    return 0;
}

/* ---- paper 1: figs. 3 and 5 ------------------------------------------------------------------- */

static int annotate_fig3_fvol(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL);
    setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g, x = %.4f", 100 * fv->epicentre.value,
         fv->epicentre.n, fv->epicentre.x);
    long last_ok = -1;
    for (long i = 0; i < fv->n_count && per_n_rel(fv, i) <= 0.019 + 0.001; ++i)
        last_ok = i;
    if (last_ok >= 0)
        note_add(c, "The claim holds at n = %g (%.4f%%) and stays within +-0.1%% of it only up to n = %g; the "
                    "per-n max delta grows with n to %.4f%% at n = %g.", fv->per_n[0].n, 100 * per_n_rel(fv, 0),
                 fv->per_n[last_ok].n, 100 * fv->epicentre.value, fv->epicentre.n);
    setf(c->method, sizeof c->method, "device sweep, n in [16, 1000] step 1, %ld samples per zone, polished in double",
         e->p->o->samples);
    return 0;
}

static double measure_fig3_order(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *f2 = sweep(e, SW_CQ2_P1), *fs = sweep(e, SW_SCHLICK);
    e->worse = 0;
    for (long i = 0; i < fv->n_count; ++i)
        if (!(per_n_rel(fv, i) < per_n_rel(f2, i) && per_n_rel(fv, i) < per_n_rel(fs, i)))
            ++e->worse;
    return e->worse == 0;
}

static int annotate_fig3_order(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *f2 = sweep(e, SW_CQ2_P1), *fs = sweep(e, SW_SCHLICK);
    setf(c->measured_text, sizeof c->measured_text, "F_VOL %.4f%%, F2 %.4f%%, F_S %.4f%%; lower at %ld of %ld n",
         100 * fv->epicentre.value, 100 * f2->epicentre.value, 100 * fs->epicentre.value, fv->n_count - e->worse,
         fv->n_count);
    note_add(c, "F2 at n = %g, F_S at n = %g (range maxima).", f2->epicentre.n, fs->epicentre.n);
    return 0;
}

/* "4.5 times": the ratio of the range maxima, and the largest per-n ratio ("up to"). */
static double measure_ratio_45(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *f2 = sweep(e, SW_CQ2_P1), *fs = sweep(e, SW_SCHLICK);
    e->rmin = INFINITY, e->rmax = -1, e->rmin_n = NAN, e->rmax_n = NAN, e->smin = INFINITY, e->smax = -1;
    e->s45_n = NAN;
    for (long i = 0; i < fv->n_count; ++i) {
        double q = per_n_rel(f2, i) / per_n_rel(fv, i), s = per_n_rel(fs, i) / per_n_rel(fv, i);
        if (q < e->rmin) { e->rmin = q; e->rmin_n = fv->per_n[i].n; }
        if (q > e->rmax) { e->rmax = q; e->rmax_n = fv->per_n[i].n; }
        e->smin = fmin(e->smin, s);
        e->smax = fmax(e->smax, s);
        if (isnan(e->s45_n) && i > 0 && (per_n_rel(fs, i - 1) / per_n_rel(fv, i - 1) - 4.5) * (s - 4.5) <= 0)
            e->s45_n = fv->per_n[i].n;
    }
    return f2->epicentre.value / fv->epicentre.value;
}

static int annotate_ratio_45(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    if (fabs(e->rmax - 4.5) <= 0.1)
        c->reproduced = 1;   /* the "up to" reading */
    setf(c->measured_text, sizeof c->measured_text, "%.3f (ratio of the max deltas); per-n ratio %.3f..%.3f",
         c->measured, e->rmin, e->rmax);
    note_add(c, "Per-n ratio F2/F_VOL: %.3f at n = %g to %.3f at n = %g; it reaches 4.5 at no n of [16, 1000]. "
                "Against Schlick the per-n ratio is %.3f..%.3f", e->rmin, e->rmin_n, e->rmax, e->rmax_n, e->smin,
             e->smax);
    if (isfinite(e->s45_n))
        note_add(c, "and passes 4.5 at n = %g.", e->s45_n);
    else
        note_add(c, ".");
    return 0;
}

/* Fig. 5: where the max Delta lies, and its order. */
static double measure_fig5_zone(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    static const int set[3] = { SW_FVOL, SW_SCHLICK, SW_CQ2_P1 };
    static const char *const names[3] = { "F_VOL", "F_S", "F2" };
    int all_att = 1;
    size_t used = 0;
    e->where[0] = '\0';
    for (int k = 0; k < 3; ++k) {
        const struct accuracy_result *a = sweep(e, set[k]);
        long epi_wins = 0;
        for (long i = 0; i < a->n_count; ++i)
            if (a->per_n[i].epi_abs_d.value > a->per_n[i].att_abs_d.value)
                ++epi_wins;
        int in_att = a->whole.x > zone_epicentre_end(a->whole.n) && epi_wins == 0;
        all_att &= in_att;
        used += (size_t)snprintf(e->where + used, used < sizeof e->where ? sizeof e->where - used : 0,
                                 "%s%s %.4f at n = %g, x = %.4f (x_e = %.4f); the epicentre's max Delta is the larger "
                                 "at %ld of %ld n", k ? "; " : "",
                                 names[k], a->whole.value, a->whole.n, a->whole.x, zone_epicentre_end(a->whole.n),
                                 epi_wins, a->n_count);
    }
    return all_att;
}

static int annotate_fig5_zone(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "%s",
         c->reproduced ? "attenuation zone for all three" : "not for all");
    note_add(c, "%s.", e->where);
    return 0;
}

static double measure_fig5_order(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *f2 = sweep(e, SW_CQ2_P1), *fs = sweep(e, SW_SCHLICK);
    return fv->attenuation.value < f2->attenuation.value && fv->attenuation.value < fs->attenuation.value;
}

static int annotate_fig5_order(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct accuracy_result *fv = sweep(e, SW_FVOL), *f2 = sweep(e, SW_CQ2_P1), *fs = sweep(e, SW_SCHLICK);
    setf(c->measured_text, sizeof c->measured_text, "F_VOL %.4f, F2 %.4f, F_S %.4f", fv->attenuation.value,
         f2->attenuation.value, fs->attenuation.value);
    return 0;
}

/* Harness check: host and device quadrature of eq. 11 agree. */
static double measure_eq11_device(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    return e->agree <= 1e-6;
}

static int annotate_eq11_device(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "%.2e", e->agree);
    c->measured = e->agree;
    if (e->agree > 1e-6)
        e->p->consistency_failed = 1;
    return 0;
}

/* ---- paper 2: the figures several rows share ------------------------------------------------ */

/* Our least-squares fit of k_Q(n), Q = 0.64, over the integer n of [2, 1000]. */
static void fit_k_q(struct claim_env *e)
{
    double nv[999], kv[999];
    for (int i = 0; i < 999; ++i) {
        nv[i] = 2.0 + i;
        kv[i] = brdf_k_q(nv[i], 0.64);
    }
    double cov00, cov01, cov11, ss;
    gsl_fit_linear(nv, 1, kv, 1, 999, &e->k_b, &e->k_a, &cov00, &cov01, &cov11, &ss);
    e->k_worst = 0;
    for (int i = 0; i < 999; ++i)
        e->k_worst = fmax(e->k_worst, fabs((e->k_a * nv[i] + e->k_b) / kv[i] - 1));
    e->kappa = (1 - 0.8) / -log(0.64);
}

/* coef(n) fitted as a (b + n) over the integer n of [2, 1000], and the paper's fit against it. */
static void fit_coef(struct claim_env *e)
{
    double nv[999], cv[999];
    for (int i = 0; i < 999; ++i) {
        nv[i] = 2.0 + i;
        cv[i] = paper2_coef(nv[i]);
    }
    double c0, cov00, cov01, cov11, ss;
    gsl_fit_linear(nv, 1, cv, 1, 999, &c0, &e->coef_a, &cov00, &cov01, &cov11, &ss);
    e->coef_b = c0 / e->coef_a;
    e->dev_theirs = -1, e->dev_theirs_n = NAN, e->dev_own = -1, e->dev_own_n = NAN, e->alb_max = -1;
    e->alb_max_n = NAN;
    e->above = 0;
    e->above_from = NAN;
    for (int i = 0; i < 999; ++i) {
        double t = 0.214 * (0.807 + nv[i]) / cv[i], o = e->coef_a * (e->coef_b + nv[i]) / cv[i];
        if (fabs(t - 1) > e->dev_theirs) { e->dev_theirs = fabs(t - 1); e->dev_theirs_n = nv[i]; }
        if (fabs(o - 1) > e->dev_own) { e->dev_own = fabs(o - 1); e->dev_own_n = nv[i]; }
        if (t > e->alb_max) { e->alb_max = t; e->alb_max_n = nv[i]; }
        if (t > 1) {
            ++e->above;
            if (isnan(e->above_from)) e->above_from = nv[i];
        }
    }
}

static void prepare_paper2(struct claim_env *e)
{
    const struct repro *p = e->p;
    model_spec_default(models_find("phong"), &e->phong);
    e->q_best = p->q_best;
    fit_k_q(e);
    fit_coef(e);
    snprintf(e->qgrid, sizeof e->qgrid, "Q sweep: Q = %g..%g step %g, n in [2, 1000] step %g, %ld samples per zone "
                                        "(q_sweep.json)", p->o->q_min, p->q[p->nq - 1], p->o->q_step, p->o->q_n_step,
             p->o->q_samples);
}

/* ---- paper 2: the sweeps over n -------------------------------------------------------------- */

static int annotate_fq(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    annotate_extreme(e, row, c);
    const struct accuracy_result *fq = sweep(e, SW_FQ);
    double nv[999];
    for (long i = 0; i < 999; ++i)
        nv[i] = 2.0 + (double)i;
    struct fq_ctx fc = { nv, 999, row->claimed, 0 };
    double q_at = root_brent(fq_max_rel_minus_target, &fc, 0.60, 0.6499);
    note_add(c, "The maximum lies inside the zone (x = %.5f < x_e = %.5f), so the zone's end does not enter; the "
                "per-n max delta rises with n towards %.4f%% (n = 1e6, host double), so 1.255%% is reached at no "
                "n, and the grid does not move it (below).", fq->epicentre.x, zone_epicentre_end(fq->epicentre.n),
             100 * host_max_rel_at(&fq->model, 1e6));
    if (isfinite(q_at))
        note_add(c, "1.255%% is f_Q's max delta over [2, 1000] at Q = %.5f.", q_at);
    return 0;
}

static double measure_fq2_zone(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    const struct accuracy_result *fq2 = sweep(e, SW_FQ2);
    return fq2->whole.x > zone_epicentre_end(fq2->whole.n);
}

static int annotate_fq2_zone(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct accuracy_result *fq2 = sweep(e, SW_FQ2);
    setf(c->measured_text, sizeof c->measured_text, "x = %.4f > x_e = %.4f at n = %g", fq2->whole.x,
         zone_epicentre_end(fq2->whole.n), fq2->whole.n);
    return 0;
}

static int annotate_f2_rel(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    annotate_extreme(e, row, c);
    const struct accuracy_result *f2 = sweep(e, SW_CQ2_P2);
    strncat(c->measured_text, " (the zone end)", sizeof c->measured_text - strlen(c->measured_text) - 1);
    struct cq2_zone_ctx zc = { &f2->model, &e->phong, f2->epicentre.n, row->claimed };
    double kz = root_brent(cq2_end_minus, &zc, 0.45, 0.60);
    note_add(c, "f2's delta grows up to the zone's end; its per-n max rises with n towards %.4f%% (n = 1e6, host "
                "double), so 7.924%% is reached at no n.", 100 * host_max_rel_at(&f2->model, 1e6));
    if (isfinite(kz))
        note_add(c, "Diagnostic: at n = %g it would need the zone to end where c^n = exp(-%.4f) instead of "
                    "exp(-0.511).", zc.n, kz);
    return 0;
}

static double measure_ratio_63(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    return sweep(e, SW_CQ2_P2)->epicentre.value / sweep(e, SW_FQ2)->epicentre.value;
}

static int annotate_ratio_63(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)e;
    (void)row;
    note_add(c, "The paper's own figures give 7.924/1.256 = %.3f; the difference is f2's max delta (P2-f2-rel).",
             7.924 / 1.256);
    return 0;
}

/* ---- paper 2: k_Q(n) and the Q sweep ------------------------------------------------------- */

/* Fig. 4: the linear fit of k_Q(n), Q = 0.64, over n in [2, 1000] step 0.01. */
static double measure_fig4(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    double worst = -1;
    e->worst_n = NAN;
    for (long i = 0; i <= 99800; ++i) {
        double n = 2.0 + 0.01 * (double)i;
        double d = fabs((0.448 * n + 0.099) / brdf_k_q(n, 0.64) - 1.0);
        if (d > worst) { worst = d; e->worst_n = n; }
    }
    return worst;
}

static int annotate_fig4(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g", 100 * c->measured, e->worst_n);
    note_add(c, "At the bound: k_Q(2) = 1 exactly (Q^(1/2) = sqrt(Q)) and the fit gives 0.995 there.");
    return 0;
}

static int annotate_k_a(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    note_add(c, "Our least-squares fit over the integer n of [2, 1000]: %.6f n + %.6f, within %.3f%% of k_Q(n). "
                "The large-n slope of k_Q is (1 - sqrt(Q))/(-ln Q) = %.6f.", e->k_a, e->k_b, 100 * e->k_worst,
             e->kappa);
    return 0;
}

static int annotate_k_b(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    note_add(c, "k_Q(n) = %.6f n + %.6f + O(1/n) (1/expm1 series), so an unweighted fit over [2, 1000] lands "
                "near %.3f; the paper's sample of n is not stated.", e->kappa, 0.5 * (1 - 0.8), 0.5 * (1 - 0.8));
    return 0;
}

static int annotate_q_best(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct accuracy_result *qb = &e->p->fq_best, *fq = sweep(e, SW_FQ);
    setf(c->measured_text, sizeof c->measured_text, "Q = %.4f: max delta %.4f%%, max Delta %.5f", e->p->q_best,
         100 * qb->epicentre.value, qb->whole.value);
    note_add(c, "At Q = 0.64: max delta %.4f%%, max Delta %.5f. The minimiser trades a %.1f%% larger max Delta for "
                "the lower max delta; the paper states 0.64 as the more accurate value.", 100 * fq->epicentre.value,
             fq->whole.value, 100 * (qb->whole.value / fq->whole.value - 1));
    note_add(c, "%s; the minimiser by GSL Brent on the exact per-n figures, then measured by the device sweep "
                "(4096 samples).", e->qgrid);
    return 0;
}

static int annotate_q_06(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "Q = %.4f", e->p->q_best);
    note_add(c, "%s.", e->qgrid);
    return 0;
}

static double measure_fig3_p2(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    return sweep(e, SW_FQ)->whole.value < sweep(e, SW_CQ2_P2)->whole.value;
}

/* Fig. 3 over the Q sweep: the runs of Q where f_Q's max Delta is not below f2's. */
static int annotate_fig3_p2(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct repro *p = e->p;
    int below = 0;
    char runs[256] = "";
    size_t used = 0;
    for (int i = 0; i < p->nq; ++i) {
        if (p->q_abs[i] < p->f2_abs) {
            ++below;
            continue;
        }
        int j = i;
        while (j + 1 < p->nq && !(p->q_abs[j + 1] < p->f2_abs))
            ++j;
        if (used < sizeof runs)
            used += (size_t)snprintf(runs + used, sizeof runs - used, "%s%g..%g", used ? ", " : "", p->q[i], p->q[j]);
        i = j;
    }
    setf(c->measured_text, sizeof c->measured_text, "f_Q %.5f, f2 %.5f", sweep(e, SW_FQ)->whole.value,
         sweep(e, SW_CQ2_P2)->whole.value);
    note_add(c, "Over the Q sweep f_Q's max Delta is below f2's at %d of %d Q%s%s%s", below, p->nq,
             runs[0] ? " (not at Q = " : ".", runs, runs[0] ? ")." : "");
    return 0;
}

/* ---- paper 2: coef(n) ---------------------------------------------------------------------- */

static double measure_coef(struct claim_env *e, const struct claim_row *row)
{
    (void)e;
    return paper2_coef(row->arg);
}

static int annotate_coef_a(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    note_add(c, "Our least-squares fit over the integer n of [2, 1000]: coef(n) = %.6f (%.5f + n).", e->coef_a,
             e->coef_b);
    return 0;
}

static int annotate_coef_b(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)e;
    (void)row;
    note_add(c, "An unweighted fit over every integer n follows the large-n slope; the paper fitted a 50-value "
                "sample with symbolic regression (TuringBot: 0.213896 (0.807175 + n)).");
    return 0;
}

static int annotate_coef_dev(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    setf(c->measured_text, sizeof c->measured_text, "%.5f at n = %g", e->dev_theirs, e->dev_theirs_n);
    note_add(c, "With our least-squares fit %.6f (%.5f + n) it is %.5f at n = %g.", e->coef_a, e->coef_b, e->dev_own,
             e->dev_own_n);
    return 0;
}

static double measure_energy(struct claim_env *e, const struct claim_row *row)
{
    (void)row;
    return e->alb_max <= 1.0 + 1e-9;
}

static int annotate_energy(struct claim_env *e, const struct claim_row *row, struct claim *c)
{
    (void)row;
    const struct repro *p = e->p;
    c->claimed = 1.0;
    c->measured = e->alb_max;
    setf(c->measured_text, sizeof c->measured_text, "albedo up to %.6f (n = %g, normal incidence)", e->alb_max,
         e->alb_max_n);
    if (e->above > 0)
        note_add(c, "Above 1 at %ld of the 999 integer n in [2, 1000], the first n = %g; the normal-incidence albedo "
                    "is coef_fit(n) 2 pi int ..., the largest over incidence angles (energy.json).", e->above,
                 e->above_from);
    if (p->have_energy)
        for (int i = 0; i < p->energy.count; ++i)
            if (strcmp(p->energy.models[i].spec.info->id, "fq2n") == 0)
                note_add(c, "Device albedo table: largest %.6f at n = %g, theta_i = %g deg.",
                         p->energy.models[i].max_albedo, p->energy.models[i].max_at_n,
                         p->energy.models[i].max_at_theta_deg);
    return 0;
}

/* ---- the table -------------------------------------------------------------------------------- */

#define ENV(field) offsetof(struct claim_env, field)
#define EQ12_TEXT(what) "eq. 12, " what
#define COEF_TEXT(n, v) "coef(" n ") = 1/(2 pi int_0^gran(n) f_Q2 cos g sin g dg) is " v " (fig. 7)"

static const struct claim_row paper_rows[] = {
    /* paper 1 */
    { .id = "P1-eq11-lhs", .source = "paper 1, eq. 11-12",
      .text = "left side of eq. 11: int_16^256 int_0^x_e(n) cos^n(x) cos(x) sin(x) dx dn, x_e(n) = acos(exp(-0.511/n))",
      .claimed_text = "1.098", .claimed = 1.098, .tol = 0.001, .tol_text = digit, .arg = 0,
      .method = eq11_method, .measure = measure_eq11, .measured_fmt = "%.7f", .annotate = annotate_eq11_lhs },
    { .id = "P1-eq12-a", .source = "paper 1, eq. 12",
      .text = EQ12_TEXT("coefficient of xi^2: int int n^2 (c-1)^2 cos x sin x dx dn"),
      .claimed_text = "0.12026", .claimed = 0.12026, .tol = 1e-5, .tol_text = digit_5,
      .arg = 1, .method = eq11_method, .measure = measure_eq11, .measured_fmt = "%.7f", .annotate = annotate_eq12 },
    { .id = "P1-eq12-b", .source = "paper 1, eq. 12",
      .text = EQ12_TEXT("coefficient of xi: int int 2n (c-1) cos x sin x dx dn"),
      .claimed_text = "-0.71068", .claimed = -0.71068, .tol = 1e-5, .tol_text = digit_5,
      .arg = 2, .method = eq11_method, .measure = measure_eq11, .measured_fmt = "%.7f", .annotate = annotate_eq12 },
    { .id = "P1-eq12-c", .source = "paper 1, eq. 12", .text = EQ12_TEXT("constant: int int cos x sin x dx dn"),
      .claimed_text = "1.40119", .claimed = 1.40119, .tol = 1e-5, .tol_text = digit_5,
      .arg = 3, .method = eq11_method, .measure = measure_eq11, .measured_fmt = "%.7f", .annotate = annotate_eq12 },
    { .id = "P1-xi", .source = "paper 1, eq. 12-13",
      .text = "xi = 0.463 solves eq. 12 (the smaller root; F_VOL = (0.463 n (c-1) + 1)^2)",
      .claimed_text = "0.463", .claimed = 0.463, .tol = 0.001, .tol_text = digit, .value_at = ENV(x0),
      .method = "roots of the measured quadratic (GSL gsl_poly_solve_quadratic)", .annotate = annotate_xi },
    { .id = "P1-xi64", .source = "paper 1, after eq. 13",
      .text = "29/64 may be used as the approximate value of xi = 0.463",
      .claimed_text = "0.463", .claimed = 0.463, .tol = 1.0 / 128.0,
      .tol_text = "|29/64 - 0.463| <= 1/128, i.e. 29/64 is the nearest 64th", .value_at = ENV(xi64),
      .method = "arithmetic; device sweeps of fvol and fvol64", .annotate = annotate_xi64 },
    { .id = "P1-eq14", .source = "paper 1, eq. 14",
      .text = "F_VOL reaches zero at acos((29n - 64)/(29n)) (shown at n = 16)",
      .claimed_text = "0.533600", .tol = 1e-9, .tol_text = "an identity: +-1e-9 rad", .arg = 16,
      .method = "bisection on the registry's models in double", .measure = measure_eq14, .annotate = annotate_eq14 },
    { .id = "P1-fig3-fvol", .source = "paper 1, fig. 3",
      .text = "F_VOL's max delta in the epicentre over n in [16, 1000] is 1.9%",
      .claimed_text = "1.9%", .claimed = 0.019, .tol = 0.001, .tol_text = "+-0.1% (one unit in the last printed digit)",
      .sweep = SW_FVOL, .metric = METRIC_EPI_REL, .grid_note = 1, .annotate = annotate_fig3_fvol },
    { .id = "P1-fig3-order", .source = "paper 1, fig. 3",
      .text = "F_VOL's max delta in the epicentre is well below F2's and F_S's over n in [16, 1000]",
      .claimed_text = "F_VOL < F2, F_S", .rule = RULE_HOLDS, .tol_text = "at every n of the grid",
      .sweep = SW_CQ2_P1, .grid_note = 1, .method = p1_sweeps, .measure = measure_fig3_order,
      .annotate = annotate_fig3_order },
    { .id = "P1-4.5x", .source = "paper 1, abstract and conclusions",
      .text = "F_VOL reproduces the glare's epicentre up to 4.5 times more accurately than the classic "
              "cosine-quadratic F2",
      .claimed_text = "4.5", .claimed = 4.5, .tol = 0.1, .tol_text = digit_01, .method = p1_sweeps,
      .measure = measure_ratio_45, .annotate = annotate_ratio_45 },
    { .id = "P1-fig5-zone", .source = "paper 1, figs. 5-6",
      .text = "the max Delta of F_VOL, F_S and F2 against F_B lies in the attenuation zone",
      .claimed_text = "attenuation zone", .rule = RULE_HOLDS,
      .tol_text = "the whole-range max Delta at x > x_e(n), at every n",
      .method = "device sweeps, n in [16, 1000] step 1, per-n maxima of both zones", .measure = measure_fig5_zone,
      .annotate = annotate_fig5_zone },
    { .id = "P1-fig5-order", .source = "paper 1, fig. 5 and text",
      .text = "F_VOL's max Delta is lower than F_S's and F2's (a more realistic attenuation zone)",
      .claimed_text = "F_VOL < F2, F_S", .rule = RULE_HOLDS, .tol_text = "range maxima over [16, 1000]",
      .method = "device sweeps, n in [16, 1000] step 1", .measure = measure_fig5_order,
      .annotate = annotate_fig5_order },
    { .kind = "check", .id = "C-eq11-device", .source = "harness",
      .text = "host (GSL, in x) and device (Gauss-Legendre, in u = cos x) quadrature of eq. 11 agree",
      .claimed_text = "<= 1e-6 relative", .rule = RULE_HOLDS,
      .tol_text = "largest relative difference of the four integrals <= 1e-6", .method = eq11_method,
      .measure = measure_eq11_device, .annotate = annotate_eq11_device },
    /* paper 2 */
    { .id = "P2-fq", .source = "paper 2, text after fig. 3",
      .text = "f_Q with Q = 0.64: max delta in the epicentre over n in [2, 1000] is 1.255%",
      .claimed_text = "1.255%", .claimed = 0.01255, .tol = 1e-5, .tol_text = digit_rel, .sweep = SW_FQ,
      .metric = METRIC_EPI_REL, .grid_note = 1, .method = sweep_method, .annotate = annotate_fq },
    { .id = "P2-fq2-rel", .source = "paper 2, fig. 6(a)",
      .text = "f_Q2: max delta in the epicentre over n in [2, 1000] is 1.256%",
      .claimed_text = "1.256%", .claimed = 0.01256, .tol = 1e-5, .tol_text = digit_rel, .sweep = SW_FQ2,
      .metric = METRIC_EPI_REL, .grid_note = 1, .method = sweep_method },
    { .id = "P2-fq2-abs", .source = "paper 2, fig. 6(b)", .text = "f_Q2: max Delta over n in [2, 1000] is 0.128",
      .claimed_text = "0.128", .claimed = 0.128, .tol = 0.001, .tol_text = digit, .sweep = SW_FQ2,
      .metric = METRIC_WHOLE_ABS, .grid_note = 1, .method = sweep_method },
    { .id = "P2-fq2-zone", .source = "paper 2, discussion", .text = "f_Q2's max Delta lies in the attenuation zone",
      .claimed_text = "attenuation zone", .rule = RULE_HOLDS, .tol_text = "x > x_e(n) at the maximum",
      .method = sweep_method, .measure = measure_fq2_zone, .annotate = annotate_fq2_zone },
    { .id = "P2-f2-rel", .source = "paper 2, discussion",
      .text = "f2 (classic cosine-quadratic): max delta in the epicentre over n in [2, 1000] is 7.924%",
      .claimed_text = "7.924%", .claimed = 0.07924, .tol = 1e-5, .tol_text = digit_rel, .sweep = SW_CQ2_P2,
      .metric = METRIC_EPI_REL, .grid_note = 1, .method = sweep_method, .annotate = annotate_f2_rel },
    { .id = "P2-f2-abs", .source = "paper 2, discussion", .text = "f2: max Delta over n in [2, 1000] is 0.162",
      .claimed_text = "0.162", .claimed = 0.162, .tol = 0.001, .tol_text = digit, .sweep = SW_CQ2_P2,
      .metric = METRIC_WHOLE_ABS, .grid_note = 1, .method = sweep_method },
    { .id = "P2-6.3x", .source = "paper 2, conclusions",
      .text = "f_Q2 reproduces the epicentre 6.3 times more accurately than f2 (ratio of the max deltas)",
      .claimed_text = "6.3", .claimed = 6.3, .tol = 0.1, .tol_text = digit_01, .method = sweep_method,
      .measure = measure_ratio_63, .measured_fmt = "%.3f", .annotate = annotate_ratio_63 },
    { .id = "P2-fig4", .source = "paper 2, fig. 4",
      .text = "0.448n + 0.099 is within 0.5% of k_Q(n) = (sqrt(Q) - 1)/(Q^(1/n) - 1), Q = 0.64, for n in [2, 1000]",
      .claimed_text = "<= 0.5%", .claimed = 0.005, .rule = RULE_AT_MOST, .tol_text = "max |fit/k_Q - 1| <= 0.5%",
      .method = "k_Q from the model header in double, n in [2, 1000] step 0.01", .measure = measure_fig4,
      .annotate = annotate_fig4 },
    { .id = "P2-fit-k-a", .source = "paper 2, text before fig. 4",
      .text = "linear regression of k_Q(n), Q = 0.64, over n in [2, 1000]: slope 0.448",
      .claimed_text = "0.448", .claimed = 0.448, .tol = 0.001, .tol_text = digit, .value_at = ENV(k_a),
      .method = k_fit_method, .measured_fmt = "%.6f", .annotate = annotate_k_a },
    { .id = "P2-fit-k-b", .source = "paper 2, text before fig. 4",
      .text = "linear regression of k_Q(n), Q = 0.64, over n in [2, 1000]: intercept 0.099",
      .claimed_text = "0.099", .claimed = 0.099, .tol = 0.001, .tol_text = digit, .value_at = ENV(k_b),
      .method = k_fit_method, .measured_fmt = "%.6f", .annotate = annotate_k_b },
    { .id = "P2-fig2-Q", .source = "paper 2, figs. 2-3 and text",
      .text = "Q = 0.64 gives f_Q's most accurate epicentre (chosen among Q near 0.6)",
      .claimed_text = "0.64", .claimed = 0.64, .tol = 0.005,
      .tol_text = "+-0.005 (0.64 is the minimiser rounded to 2 decimals)",
      .value_at = ENV(q_best), .method = q_method, .annotate = annotate_q_best },
    { .id = "P2-fig2-0.6", .source = "paper 2, fig. 2",
      .text = "the most accurate epicentre approximation is reached at Q about 0.6",
      .claimed_text = "0.6", .claimed = 0.6, .tol = 0.1, .tol_text = digit_01, .value_at = ENV(q_best),
      .method = q_method, .annotate = annotate_q_06 },
    { .id = "P2-fig3", .source = "paper 2, fig. 3 and text", .text = "f_Q's max Delta (Q = 0.64) is lower than f2's",
      .claimed_text = "f_Q < f2", .rule = RULE_HOLDS, .tol_text = "range maxima over [2, 1000]", .method = sweep_method,
      .measure = measure_fig3_p2, .annotate = annotate_fig3_p2 },
    { .id = "P2-coef-2", .source = "paper 2, fig. 7", .text = COEF_TEXT("2", "0.634"), .claimed_text = "0.634",
      .claimed = 0.634, .tol = 0.001, .tol_text = digit, .arg = 2, .method = coef_method, .measure = measure_coef,
      .measured_fmt = "%.6f" },
    { .id = "P2-coef-3", .source = "paper 2, fig. 7", .text = COEF_TEXT("3", "0.833"), .claimed_text = "0.833",
      .claimed = 0.833, .tol = 0.001, .tol_text = digit, .arg = 3, .method = coef_method, .measure = measure_coef,
      .measured_fmt = "%.6f" },
    { .id = "P2-coef-4", .source = "paper 2, fig. 7", .text = COEF_TEXT("4", "1.04"), .claimed_text = "1.04",
      .claimed = 1.04, .tol = 0.01, .tol_text = "+-0.01 (one unit in the last printed digit)", .arg = 4,
      .method = coef_method, .measure = measure_coef, .measured_fmt = "%.6f" },
    { .id = "P2-coef-10", .source = "paper 2, fig. 7", .text = COEF_TEXT("10", "2.313"), .claimed_text = "2.313",
      .claimed = 2.313, .tol = 0.001, .tol_text = digit, .arg = 10, .method = coef_method, .measure = measure_coef,
      .measured_fmt = "%.6f" },
    { .id = "P2-coef-fit-a", .source = "paper 2, figs. 9-10",
      .text = "coef(n) fitted as a (b + n) over n in [2, 1000]: a = 0.214", .claimed_text = "0.214", .claimed = 0.214,
      .tol = 0.001, .tol_text = digit, .value_at = ENV(coef_a), .method = coef_fit_method,
      .measured_fmt = "%.6f", .annotate = annotate_coef_a },
    { .id = "P2-coef-fit-b", .source = "paper 2, figs. 9-10",
      .text = "coef(n) fitted as a (b + n) over n in [2, 1000]: b = 0.807", .claimed_text = "0.807", .claimed = 0.807,
      .tol = 0.001, .tol_text = digit, .value_at = ENV(coef_b), .method = coef_fit_method,
      .measured_fmt = "%.5f", .annotate = annotate_coef_b },
    { .id = "P2-coef-dev", .source = "paper 2, fig. 11",
      .text = "max |coef_fit(n) 2 pi int ... - 1| over n in [2, 1000] is 53e-3 for coef_fit = 0.214 (0.807 + n)",
      .claimed_text = "53e-3", .claimed = 0.053, .tol = 0.001,
      .tol_text = "+-1e-3 (one unit in the last printed digit)",
      .value_at = ENV(dev_theirs), .method = "coef(n) by adaptive quadrature at n = 2, 3, ..., 1000",
      .annotate = annotate_coef_dev },
    { .id = "P2-energy", .source = "paper 2, discussion and conclusions",
      .text = "f_Q2 with coef(n) = 0.214 (0.807 + n) obeys the energy conservation law (directional albedo <= 1)",
      .claimed_text = "albedo <= 1", .rule = RULE_HOLDS,
      .tol_text = "albedo <= 1 + 1e-9 (the quadrature's accuracy is 1e-12)",
      .method = "coef(n) by adaptive quadrature at n = 2, 3, ..., 1000; device albedo", .measure = measure_energy,
      .annotate = annotate_energy },
};

/* ---- the driver ------------------------------------------------------------------------------- */

static double row_value(struct claim_env *e, const struct claim_row *row)
{
    if (row->measure)
        return row->measure(e, row);
    if (row->value_at)
        return *(const double *)((const char *)e + row->value_at);
    return measure_extreme(e, row);
}

static void judge(struct claim *c, const struct claim_row *row, double claimed, double v)
{
    switch (row->rule) {
    case RULE_NEAR:
        claim_number(c, row->claimed_text, claimed, v, row->tol, row->tol_text);
        break;
    case RULE_HOLDS:
        claim_bool(c, row->claimed_text, v != 0, row->tol_text);
        break;
    case RULE_AT_MOST:
        claim_bool(c, row->claimed_text, v <= claimed * (1 + 1e-9), row->tol_text);
        c->claimed = claimed;
        c->measured = v;
        break;
    }
}

static void grid_note(const struct repro *p, struct claim *c, int sw)
{
    if (isfinite(p->grid_change[sw]))
        note_add(c, "Twice the samples per zone moves it by %.2g of a unit in its 4th significant digit.",
                 p->grid_change[sw]);
}

static int run_row(struct claim_env *e, const struct claim_row *row)
{
    struct claim *c = claim_add(e->p->r, row->kind ? row->kind : "claim", row->id, row->source, row->text);
    if (!c)
        return EXIT_RUNTIME;
    e->claimed = row->claimed;
    double v = row_value(e, row);
    judge(c, row, e->claimed, v);
    if (row->measured_fmt)
        snprintf(c->measured_text, sizeof c->measured_text, row->measured_fmt, c->measured);
    int rc = row->annotate ? row->annotate(e, row, c) : row->measured_fmt ? 0 : annotate_extreme(e, row, c);
    if (rc)
        return rc;
    if (row->grid_note)
        grid_note(e->p, c, row->sweep);
    if (row->method)
        setf(c->method, sizeof c->method, "%s", row->method);
    return 0;
}

int reproduce_add_papers(struct repro *p)
{
    struct claim_env *e = calloc(1, sizeof *e);
    if (!e)
        return EXIT_RUNTIME;
    e->p = p;
    int rc = prepare_paper1(e);
    if (!rc)
        prepare_paper2(e);
    for (size_t i = 0; !rc && i < sizeof paper_rows / sizeof paper_rows[0]; ++i)
        rc = run_row(e, &paper_rows[i]);
    free(e);
    return rc;
}
