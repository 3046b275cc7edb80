/* reproduce.c - the claims of both papers, re-derived and given verdicts (see reproduce.h). */
#include "reproduce.h"
#include "reproduce_report.h"
#include "accuracy.h"
#include "context.h"
#include "energy.h"
#include "exitcodes.h"
#include "fit.h"
#include "models.h"
#include "outdir.h"
#include "refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_poly.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* k_Q(n) of f_Q, from the model header itself (its single definition), in double. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

static const double half_pi = 1.57079632679489661923;
static const double two_pi = 6.28318530717958647692;
#define ZONE_K BRDF_ZONE_K           /* kernels/brdf_shared.h: the epicentre ends where c^n = exp(-0.511) */

void reproduce_options_default(struct reproduce_options *o)
{
    o->samples = ACC_DEFAULT_SAMPLES;
    o->grid_check = 1;
    o->q_min = 0.01;
    o->q_max = 0.99;
    o->q_step = 0.01;
    o->q_samples = 1024;
    o->q_n_step = 1.0;
    o->energy = 1;
    o->physical = 1;
}

int reproduce_options_check(const struct reproduce_options *o, char *err, size_t errlen)
{
    struct accuracy_grid g = { 2, 1000, 1, o->samples }, q = { 2, 1000, o->q_n_step, o->q_samples };
    if (accuracy_grid_check(&g, NULL, err, errlen))
        return EXIT_USAGE;
    if (accuracy_grid_check(&q, NULL, err, errlen)) {
        /* name the Q sweep's own flags */
        char inner[512];
        snprintf(inner, sizeof inner, "%s", err);
        snprintf(err, errlen, "Q sweep: %s (flags --q-samples, --q-n-step)", inner);
        return EXIT_USAGE;
    }
    if (!(o->q_min > 0 && o->q_max < 1 && o->q_min <= o->q_max && o->q_step > 0) ||
        (o->q_max - o->q_min) / o->q_step > 10000) {
        snprintf(err, errlen, "--q-min/--q-max/--q-step: need 0 < q-min <= q-max < 1 and at most 10000 steps "
                              "(got %g, %g, %g)", o->q_min, o->q_max, o->q_step);
        return EXIT_USAGE;
    }
    return 0;
}

/* ---- the claims table ----------------------------------------------------------------------- */

static struct claim *claim_add(struct reproduce_report *r, const char *kind, const char *id, const char *source,
                               const char *text)
{
    if (r->count == r->cap) {
        int cap = r->cap ? 2 * r->cap : 64;
        struct claim *nr = realloc(r->rows, (size_t)cap * sizeof *nr);
        if (!nr)
            return NULL;
        r->rows = nr;
        r->cap = cap;
    }
    struct claim *c = &r->rows[r->count++];
    memset(c, 0, sizeof *c);
    snprintf(c->kind, sizeof c->kind, "%s", kind);
    snprintf(c->id, sizeof c->id, "%s", id);
    snprintf(c->source, sizeof c->source, "%s", source);
    snprintf(c->text, sizeof c->text, "%s", text);
    c->claimed = c->measured = NAN;
    return c;
}

static void setf(char *dst, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void setf(char *dst, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, len, fmt, ap);
    va_end(ap);
}

/* Appends to the note. */
static void note_add(struct claim *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note_add(struct claim *c, const char *fmt, ...)
{
    size_t used = strlen(c->note);
    if (used + 1 >= sizeof c->note)
        return;
    if (used > 0) {
        c->note[used++] = ' ';
        c->note[used] = '\0';
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->note + used, sizeof c->note - used, fmt, ap);
    va_end(ap);
}

/* A numeric claim with a tolerance: reproduced when |measured - claimed| <= tol (a hair of
 * relative slack so a value exactly at the bound is not lost to rounding). */
static void claim_number(struct claim *c, const char *claimed_text, double claimed, double measured, double tol,
                         const char *tol_text)
{
    snprintf(c->claimed_text, sizeof c->claimed_text, "%s", claimed_text);
    c->claimed = claimed;
    c->measured = measured;
    snprintf(c->tolerance, sizeof c->tolerance, "%s", tol_text);
    c->reproduced = isfinite(measured) && fabs(measured - claimed) <= tol * (1 + 1e-9) + 1e-15;
    /* For a printed number, say whether the paper rounded or truncated the measured value. */
    if (c->reproduced && strstr(tol_text, "last printed digit")) {
        double rounded = round(measured / tol) * tol, cut = trunc(measured / tol) * tol;
        if (fabs(rounded - claimed) < 1e-3 * tol)
            note_add(c, "The measured value rounds to the printed one.");
        else if (fabs(cut - claimed) < 1e-3 * tol)
            note_add(c, "The printed value is the measured one truncated, not rounded.");
    }
}

static void claim_bool(struct claim *c, const char *claimed_text, int holds, const char *tol_text)
{
    snprintf(c->claimed_text, sizeof c->claimed_text, "%s", claimed_text);
    snprintf(c->tolerance, sizeof c->tolerance, "%s", tol_text);
    c->reproduced = holds;
}

/* ---- paper 1, eq. 11 on the host ------------------------------------------------------------ */

struct eq11_ctx {
    double n, zone_k;
    int term;
    gsl_integration_workspace *inner;
    const struct model_spec *phong;
    int failed;
};

static double eq11_integrand(double x, void *p)
{
    const struct eq11_ctx *e = p;
    double c = cos(x), s = sin(x);
    double cm1 = -2.0 * sin(0.5 * x) * sin(0.5 * x);   /* c - 1 without cancellation */
    double w = c * s, n = e->n;
    switch (e->term) {
    case 0: return model_eval_host(e->phong, c, n) * w;
    case 1: return n * n * cm1 * cm1 * w;
    case 2: return 2.0 * n * cm1 * w;
    default: return w;
    }
}

static double eq11_inner(double n, void *p)
{
    struct eq11_ctx *e = p;
    e->n = n;
    gsl_function fn = { eq11_integrand, e };
    double r, abserr;
    double xe = acos(exp(-e->zone_k / n));
    if (gsl_integration_qag(&fn, 0.0, xe, 0.0, 1e-13, 1000, GSL_INTEG_GAUSS41, e->inner, &r, &abserr))
        e->failed = 1;
    return r;
}

int eq11_host(double zone_k, double n_lo, double n_hi, int term, double *out)
{
    struct model_spec phong;
    model_spec_default(models_find("phong"), &phong);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    struct eq11_ctx e = { 0, zone_k, term, gsl_integration_workspace_alloc(1000), &phong, 0 };
    gsl_integration_workspace *outer = gsl_integration_workspace_alloc(1000);
    int rc = -1;
    if (e.inner && outer) {
        gsl_function fn = { eq11_inner, &e };
        double abserr;
        int st = gsl_integration_qag(&fn, n_lo, n_hi, 0.0, 1e-12, 1000, GSL_INTEG_GAUSS41, outer, out, &abserr);
        rc = (st || e.failed) ? -1 : 0;
    }
    if (outer) gsl_integration_workspace_free(outer);
    if (e.inner) gsl_integration_workspace_free(e.inner);
    gsl_set_error_handler(old);
    return rc;
}

/* ---- paper 2's coef(n) ---------------------------------------------------------------------- */

struct coef_ctx {
    const struct model_spec *fq2;
    double n;
};

static double coef_integrand(double g, void *p)
{
    const struct coef_ctx *c = p;
    double cg = cos(g);
    return model_eval_host(c->fq2, cg, c->n) * cg * sin(g);
}

double paper2_coef(double n)
{
    static struct model_spec fq2;
    static int ready;
    if (!ready) {
        model_spec_default(models_find("fq2"), &fq2);
        ready = 1;
    }
    double arg = (448.0 * n - 901.0) / (448.0 * n + 99.0);
    double gran = arg <= 0 ? half_pi : acos(arg);   /* capped at pi/2 (docs/definitions.md) */
    struct coef_ctx ctx = { &fq2, n };
    gsl_function fn = { coef_integrand, &ctx };
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    double r = NAN, abserr;
    if (ws && gsl_integration_qag(&fn, 0.0, gran, 0.0, 1e-13, 1000, GSL_INTEG_GAUSS41, ws, &r, &abserr))
        r = NAN;
    if (ws) gsl_integration_workspace_free(ws);
    gsl_set_error_handler(old);
    return 1.0 / (two_pi * r);
}

/* ---- small numerical helpers ------------------------------------------------------------ */

/* A root of f over [lo, hi] (sign change required), GSL Brent. NAN when there is none. */
static double root_brent(double (*f)(double, void *), void *ctx, double lo, double hi)
{
    double flo = f(lo, ctx), fhi = f(hi, ctx);
    if (!(flo * fhi <= 0))
        return NAN;
    double r = NAN;
    brent_root(f, ctx, lo, hi, 1e-14, 1e-12, 200, &r);
    return r;
}

/* The largest per-n epicentre max delta of f_Q over n values, from the exact per-n figure of
 * the quadratic family (fit.h): f_Q is that family with k = k_Q(n). */
struct fq_ctx {
    const double *n;
    long count;
    double target;
    double at_n;
};

static double fq_max_rel(double q, void *p)
{
    struct fq_ctx *c = p;
    double best = -1;
    for (long i = 0; i < c->count; ++i) {
        double e = fit_epicentre_max_rel(c->n[i], brdf_k_q(c->n[i], q));
        if (e > best) {
            best = e;
            c->at_n = c->n[i];
        }
    }
    return best;
}

static double fq_max_rel_minus_target(double q, void *p)
{
    struct fq_ctx *c = p;
    return fq_max_rel(q, c) - c->target;
}

/* GSL Brent minimisation over [lo, hi] from m (f(m) below both ends required). */
static double minimise_brent(double (*f)(double, void *), void *ctx, double lo, double m, double hi)
{
    double x = m;
    brent_minimum(f, ctx, lo, m, hi, 1e-12, 1e-10, 200, &x);
    return x;
}

/* Size of one unit in the 4th significant digit of v. */

/* The largest delta of a model over the epicentre at one n, on the host in double: a grid of
 * the zone and a Brent polish (any model; used where the device grid cannot go, n = 1e6). */
struct rel_ctx {
    const struct model_spec *m, *ref;
    double n;
};

static double rel_at(double x, void *p)
{
    const struct rel_ctx *r = p;
    return error_rel_host(r->m, r->ref, cos(x), r->n);
}


static double host_max_rel_at(const struct model_spec *m, double n)
{
    struct model_spec ref;
    model_reference_spec(m, &ref);
    struct rel_ctx ctx = { m, &ref, n };
    enum { G = 4096 };
    double xe = zone_epicentre_end(n), best = -1;
    int bj = 0;
    for (int j = 0; j <= G; ++j) {
        double v = rel_at(xe * j / G, &ctx);
        if (v > best) { best = v; bj = j; }
    }
    double x, v;
    refine_maximum(rel_at, &ctx, xe * (bj > 0 ? bj - 1 : 0) / G, xe * bj / G, xe * (bj < G ? bj + 1 : G) / G, &x, &v);
    return fmax(v, best);
}

/* ---- the run ------------------------------------------------------------------------------ */

static const struct {
    const char *model;
    double n_min;
} sweep_defs[SW_COUNT] = {
    [SW_FVOL] = { "fvol", 16 }, [SW_FVOL64] = { "fvol64", 16 }, [SW_CQ2_P1] = { "cq2", 16 },
    [SW_SCHLICK] = { "schlick", 16 }, [SW_FQ] = { "fq:Q=0.64", 2 }, [SW_FQ2] = { "fq2", 2 }, [SW_CQ2_P2] = { "cq2", 2 },
};

static int sweep_run(struct repro *p, const char *text, double n_min, long samples, struct accuracy_result *out)
{
    char err[512];
    struct model_spec m;
    if (model_spec_parse(text, &m, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_RUNTIME;
    }
    struct accuracy_grid g = { n_min, 1000.0, 1.0, samples };
    if (accuracy_grid_check(&g, p->s, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_USAGE;
    }
    return accuracy_run(&p->actx, &m, &g, out);
}

static int run_sweeps(struct repro *p)
{
    for (int i = 0; i < SW_COUNT; ++i) {
        int rc = sweep_run(p, sweep_defs[i].model, sweep_defs[i].n_min, p->o->samples, &p->sw[i]);
        if (rc)
            return rc;
        p->have_sw[i] = 1;
        p->grid_change[i] = NAN;
        long fine_samples = 2 * p->o->samples;
        if (p->o->grid_check && fine_samples <= ACC_MAX_SAMPLES) {
            struct accuracy_result fine;
            rc = sweep_run(p, sweep_defs[i].model, sweep_defs[i].n_min, fine_samples, &fine);
            if (rc)
                return rc;
            const struct accuracy_result *a = &p->sw[i];
            double ue = fourth_digit_unit(a->epicentre.value), ua = fourth_digit_unit(a->attenuation.value);
            double ce = ue > 0 ? fabs(fine.epicentre.value - a->epicentre.value) / ue : 0;
            double ca = ua > 0 ? fabs(fine.attenuation.value - a->attenuation.value) / ua : 0;
            p->grid_change[i] = fmax(ce, ca);
            accuracy_result_free(&fine);
        }
    }
    return 0;
}

static int run_q_sweep(struct repro *p)
{
    const struct reproduce_options *o = p->o;
    int total = (int)floor((o->q_max - o->q_min) / o->q_step + 1e-9) + 1;
    p->q = calloc((size_t)total, sizeof *p->q);
    p->q_rel = calloc((size_t)total, sizeof *p->q_rel);
    p->q_rel_n = calloc((size_t)total, sizeof *p->q_rel_n);
    p->q_abs = calloc((size_t)total, sizeof *p->q_abs);
    p->q_att = calloc((size_t)total, sizeof *p->q_att);
    if (!p->q || !p->q_rel || !p->q_rel_n || !p->q_abs || !p->q_att)
        return EXIT_RUNTIME;
    struct accuracy_grid g = { 2.0, 1000.0, o->q_n_step, o->q_samples };
    char err[512];
    if (accuracy_grid_check(&g, p->s, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: Q sweep: %s\n", err);
        return EXIT_USAGE;
    }
    int best = 0;
    for (int i = 0; i < total; ++i) {
        double q = o->q_min + i * o->q_step;
        struct model_spec m;
        char text[64];
        snprintf(text, sizeof text, "fq:Q=%.10g", q);
        if (model_spec_parse(text, &m, err, sizeof err)) {
            fprintf(stderr, "brdfbench reproduce: Q sweep: %s\n", err);
            return EXIT_RUNTIME;
        }
        struct accuracy_result res;
        int rc = accuracy_run(&p->actx, &m, &g, &res);
        if (rc)
            return rc;
        p->q[i] = q;
        p->q_rel[i] = res.epicentre.value;
        p->q_rel_n[i] = res.epicentre.n;
        p->q_abs[i] = res.whole.value;
        p->q_att[i] = res.attenuation.value;
        accuracy_result_free(&res);
        if (p->q_rel[i] < p->q_rel[best])
            best = i;
        p->nq = i + 1;
    }
    struct model_spec f2;
    model_spec_default(models_find("cq2"), &f2);
    struct accuracy_result res;
    int rc = accuracy_run(&p->actx, &f2, &g, &res);
    if (rc)
        return rc;
    p->f2_rel = res.epicentre.value;
    p->f2_abs = res.whole.value;
    accuracy_result_free(&res);

    /* The minimising Q: GSL Brent on the exact per-n figures over the integer n of [2, 1000]
       (fit.h), bracketed by the sweep's best grid point; then the device sweep at that Q. */
    long nc = 999;
    double *nv = malloc((size_t)nc * sizeof *nv);
    if (!nv)
        return EXIT_RUNTIME;
    for (long i = 0; i < nc; ++i)
        nv[i] = 2.0 + (double)i;
    struct fq_ctx fc = { nv, nc, 0, 0 };
    double lo = p->q[best > 0 ? best - 1 : 0], hi = p->q[best < p->nq - 1 ? best + 1 : best], m = p->q[best];
    double fm = fq_max_rel(m, &fc);
    if (lo < m && hi > m && fm < fq_max_rel(lo, &fc) && fm < fq_max_rel(hi, &fc))
        m = minimise_brent(fq_max_rel, &fc, lo, m, hi);
    p->q_best = m;
    p->q_best_host_rel = fq_max_rel(m, &fc);
    free(nv);
    char text[64];
    snprintf(text, sizeof text, "fq:Q=%.10g", p->q_best);
    rc = sweep_run(p, text, 2.0, o->samples, &p->fq_best);
    if (rc)
        return rc;
    p->have_fq_best = 1;
    return 0;
}

/* ---- paper 1 ---------------------------------------------------------------------------- */

struct k_ctx {
    int term;
    double target;
};

static double eq11_term_minus(double k, void *p)
{
    const struct k_ctx *c = p;
    double v = NAN;
    eq11_host(k, 16.0, 256.0, c->term, &v);
    return v - c->target;
}

/* The first angle where a model is exactly 0 at n (a quadratic past its root), by bisection. */
static double model_zero(const char *id, double n)
{
    struct model_spec m;
    model_spec_default(models_find(id), &m);
    double lo = 0, hi = half_pi;
    if (model_eval_host(&m, cos(hi), n) != 0.0)
        return NAN;
    for (int it = 0; it < 200; ++it) {
        double mid = 0.5 * (lo + hi);
        if (model_eval_host(&m, cos(mid), n) == 0.0) hi = mid; else lo = mid;
    }
    return hi;
}

static double per_n_rel(const struct accuracy_result *a, long i) { return a->per_n[i].epi_rel_d.value; }

static void grid_note(struct repro *p, struct claim *c, int sw)
{
    if (isfinite(p->grid_change[sw]))
        note_add(c, "Twice the samples per zone moves it by %.2g of a unit in its 4th significant digit.",
                 p->grid_change[sw]);
}

/* A paper-2 claim on one extreme of a sweep over n in [2, 1000]: the paper's printed figure
 * against the sweep's max delta (rel) or max Delta, to one unit in its last printed digit. */
static struct claim *p2_sweep_claim(struct reproduce_report *r, const char *id, const char *source,
                                    const char *text, const char *printed, double claimed,
                                    const struct acc_extreme *e, int rel)
{
    struct claim *c = claim_add(r, "claim", id, source, text);
    if (!c)
        return NULL;
    if (rel) {
        claim_number(c, printed, claimed, e->value, 1e-5, "+-0.001% (one unit in the last printed digit)");
        setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g, x = %.5f", 100 * e->value, e->n, e->x);
    } else {
        claim_number(c, printed, claimed, e->value, 0.001, "+-0.001 (one unit in the last printed digit)");
        setf(c->measured_text, sizeof c->measured_text, "%.5f at n = %g, x = %.4f", e->value, e->n, e->x);
    }
    setf(c->method, sizeof c->method, "%s", "device sweep, n in [2, 1000] step 1, polished in double");
    return c;
}

static int add_paper1(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    double host[4], dev[4];
    for (int t = 0; t < 4; ++t)
        if (eq11_host(ZONE_K, 16.0, 256.0, t, &host[t])) {
            fprintf(stderr, "brdfbench reproduce: eq. 11: GSL quadrature failed (term %d)\n", t);
            return EXIT_RUNTIME;
        }
    int rc = integrate_eq11_device(&p->ic, ZONE_K, 16.0, 256.0, dev);
    if (rc)
        return rc;
    double agree = 0;
    for (int t = 0; t < 4; ++t)
        agree = fmax(agree, fabs(host[t] - dev[t]) / fabs(host[t]));
    const char *method = "host: nested adaptive GSL QAG in x and n (rel. 1e-12); device: Gauss-Legendre in u = cos x "
                         "(float), outer sum in double";

    if (!(c = claim_add(r, "claim", "P1-eq11-lhs", "paper 1, eq. 11-12",
                        "left side of eq. 11: int_16^256 int_0^x_e(n) cos^n(x) cos(x) sin(x) dx dn, "
                        "x_e(n) = acos(exp(-0.511/n))")))
        return EXIT_RUNTIME;
    claim_number(c, "1.098", 1.098, host[0], 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.7f", host[0]);
    note_add(c, "Device quadrature %.7f.", dev[0]);
    setf(c->method, sizeof c->method, "%s", method);

    /* The zone constant K (c^n = exp(-K) at the zone end) that would give the claimed constant
       coefficient: a diagnostic of how the paper's numbers may have been computed. */
    struct k_ctx kc = { 3, 1.40119 };
    double kfit = root_brent(eq11_term_minus, &kc, 0.50, 0.52), at_k[4] = { NAN, NAN, NAN, NAN };
    if (isfinite(kfit))
        for (int t = 0; t < 4; ++t)
            eq11_host(kfit, 16.0, 256.0, t, &at_k[t]);
    static const char *const coef_id[3] = { "P1-eq12-a", "P1-eq12-b", "P1-eq12-c" };
    static const char *const coef_what[3] = {
        "eq. 12, coefficient of xi^2: int int n^2 (c-1)^2 cos x sin x dx dn",
        "eq. 12, coefficient of xi: int int 2n (c-1) cos x sin x dx dn",
        "eq. 12, constant: int int cos x sin x dx dn" };
    static const char *const coef_text[3] = { "0.12026", "-0.71068", "1.40119" };
    static const double coef_claim[3] = { 0.12026, -0.71068, 1.40119 };
    int coefs_ok = 1;
    for (int t = 0; t < 3; ++t) {
        if (!(c = claim_add(r, "claim", coef_id[t], "paper 1, eq. 12", coef_what[t])))
            return EXIT_RUNTIME;
        claim_number(c, coef_text[t], coef_claim[t], host[t + 1], 1e-5, "+-1e-5 (one unit in the last printed digit)");
        coefs_ok &= c->reproduced;
        setf(c->measured_text, sizeof c->measured_text, "%.7f", host[t + 1]);
        note_add(c, "Device quadrature %.7f; measured/claimed - 1 = %+.2e.", dev[t + 1], host[t + 1] / coef_claim[t] - 1);
        if (!c->reproduced && isfinite(kfit))
            note_add(c, "Diagnostic: the zone end that reproduces the claimed constant is c^n = exp(-%.6f) (-ln 0.6 = "
                        "%.6f: c^n = 0.6) instead of exp(-0.511); with it the three coefficients are %.5f, %.5f, %.5f "
                        "(claimed 0.12026, -0.71068, 1.40119) and the left side %.4f.", kfit, -log(0.6), at_k[1],
                     at_k[2], at_k[3], at_k[0]);
        setf(c->method, sizeof c->method, "%s", method);
    }

    double x0 = NAN, x1 = NAN, c0 = NAN, c1 = NAN, d0 = NAN, d1 = NAN;
    gsl_poly_solve_quadratic(host[1], host[2], host[3] - host[0], &x0, &x1);
    gsl_poly_solve_quadratic(0.12026, -0.71068, 1.40119 - 1.098, &c0, &c1);
    gsl_poly_solve_quadratic(dev[1], dev[2], dev[3] - dev[0], &d0, &d1);
    if (!(c = claim_add(r, "claim", "P1-xi", "paper 1, eq. 12-13",
                        "xi = 0.463 solves eq. 12 (the smaller root; F_VOL = (0.463 n (c-1) + 1)^2)")))
        return EXIT_RUNTIME;
    claim_number(c, "0.463", 0.463, x0, 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f (both roots: %.5f, %.4f)", x0, x0, x1);
    note_add(c, "The paper's own eq. 12 gives %.5f and %.4f; the device's coefficients give %.5f and %.4f. The larger "
                "root would make the lobe far narrower than c^n and is not the model.", c0, c1, d0, d1);
    if (!coefs_ok)
        note_add(c, "The root holds although the coefficients differ in their 4th digit: it is insensitive to them.");
    setf(c->method, sizeof c->method, "roots of the measured quadratic (GSL gsl_poly_solve_quadratic)");

    double xi64 = 29.0 / 64.0, rhs64 = host[1] * xi64 * xi64 + host[2] * xi64 + host[3];
    const struct accuracy_result *fv = &p->sw[SW_FVOL], *fv64 = &p->sw[SW_FVOL64];
    if (!(c = claim_add(r, "claim", "P1-xi64", "paper 1, after eq. 13",
                        "29/64 may be used as the approximate value of xi = 0.463")))
        return EXIT_RUNTIME;
    claim_number(c, "0.463", 0.463, xi64, 1.0 / 128.0, "|29/64 - 0.463| <= 1/128, i.e. 29/64 is the nearest 64th");
    setf(c->measured_text, sizeof c->measured_text, "29/64 = %.6f (%+.2f%%)", xi64, 100 * (xi64 / 0.463 - 1));
    note_add(c, "The nearest 64th of 0.463 (and of the measured root %.5f) is 30/64 = 0.46875 (%+.2f%%). At xi = 29/64 "
                "the right side of eq. 11 is %.5f, %+.2f%% off the left side.", x0, 100 * (30.0 / 64 / 0.463 - 1),
             rhs64, 100 * (rhs64 / host[0] - 1));
    note_add(c, "In the epicentre the 29/64 variant is nevertheless the more accurate one over n in [16, 1000]: "
                "max delta %.4f%% (fvol64) against %.4f%% (fvol).", 100 * fv64->epicentre.value, 100 * fv->epicentre.value);
    setf(c->method, sizeof c->method, "arithmetic; device sweeps of fvol and fvol64");

    /* Eq. 14: the angle F_VOL is zeroed from. */
    double n16 = 16.0, eq14 = acos((29.0 * n16 - 64.0) / (29.0 * n16));
    double z_fvol = model_zero("fvol", n16), z_fvol64 = model_zero("fvol64", n16);
    if (!(c = claim_add(r, "claim", "P1-eq14", "paper 1, eq. 14",
                        "F_VOL reaches zero at acos((29n - 64)/(29n)) (shown at n = 16)")))
        return EXIT_RUNTIME;
    claim_number(c, "0.533600", eq14, z_fvol, 1e-9, "an identity: +-1e-9 rad");
    setf(c->claimed_text, sizeof c->claimed_text, "%.6f rad", eq14);
    setf(c->measured_text, sizeof c->measured_text, "%.6f rad (F_VOL's own zero)", z_fvol);
    /* F_VOL's unclipped base at eq. 14's angle: 1 - 0.463 * 64/29 (paper 1's xi). */
    double base = 1.0 - 0.463 * 64.0 / 29.0;
    note_add(c, "Eq. 14 is the zero of the 29/64 variant (fvol64's zero: %.6f rad, %.1e from it). F_VOL with "
                "xi = 0.463 is zero from acos(1 - 1/(0.463 n)) = %.6f rad on; zeroed only from eq. 14's angle, it "
                "would rise back to %.2e there.", z_fvol64, fabs(z_fvol64 - eq14), z_fvol, base * base);
    setf(c->method, sizeof c->method, "bisection on the registry's models in double");

    /* Fig. 3: max delta over [16, 1000]. */
    const struct accuracy_result *f2 = &p->sw[SW_CQ2_P1], *fs = &p->sw[SW_SCHLICK];
    if (!(c = claim_add(r, "claim", "P1-fig3-fvol", "paper 1, fig. 3",
                        "F_VOL's max delta in the epicentre over n in [16, 1000] is 1.9%")))
        return EXIT_RUNTIME;
    claim_number(c, "1.9%", 0.019, fv->epicentre.value, 0.001, "+-0.1% (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g, x = %.4f", 100 * fv->epicentre.value,
         fv->epicentre.n, fv->epicentre.x);
    {
        long last_ok = -1;
        for (long i = 0; i < fv->n_count && per_n_rel(fv, i) <= 0.019 + 0.001; ++i)
            last_ok = i;
        if (last_ok >= 0)
            note_add(c, "The claim holds at n = %g (%.4f%%) and stays within +-0.1%% of it only up to n = %g; the "
                        "per-n max delta grows with n to %.4f%% at n = %g.", fv->per_n[0].n, 100 * per_n_rel(fv, 0),
                     fv->per_n[last_ok].n, 100 * fv->epicentre.value, fv->epicentre.n);
    }
    grid_note(p, c, SW_FVOL);
    setf(c->method, sizeof c->method, "device sweep, n in [16, 1000] step 1, %ld samples per zone, polished in double",
         p->o->samples);

    long worse = 0;
    for (long i = 0; i < fv->n_count; ++i)
        if (!(per_n_rel(fv, i) < per_n_rel(f2, i) && per_n_rel(fv, i) < per_n_rel(fs, i)))
            ++worse;
    if (!(c = claim_add(r, "claim", "P1-fig3-order", "paper 1, fig. 3",
                        "F_VOL's max delta in the epicentre is well below F2's and F_S's over n in [16, 1000]")))
        return EXIT_RUNTIME;
    claim_bool(c, "F_VOL < F2, F_S", worse == 0, "at every n of the grid");
    setf(c->measured_text, sizeof c->measured_text, "F_VOL %.4f%%, F2 %.4f%%, F_S %.4f%%; lower at %ld of %ld n",
         100 * fv->epicentre.value, 100 * f2->epicentre.value, 100 * fs->epicentre.value, fv->n_count - worse,
         fv->n_count);
    note_add(c, "F2 at n = %g, F_S at n = %g (range maxima).", f2->epicentre.n, fs->epicentre.n);
    grid_note(p, c, SW_CQ2_P1);
    setf(c->method, sizeof c->method, "device sweeps of fvol, cq2, schlick, n in [16, 1000] step 1");

    /* "4.5 times": the ratio of the range maxima, and the largest per-n ratio ("up to"). */
    double ratio = f2->epicentre.value / fv->epicentre.value;
    double rmin = INFINITY, rmax = -1, rmin_n = NAN, rmax_n = NAN, smin = INFINITY, smax = -1, s45_n = NAN;
    for (long i = 0; i < fv->n_count; ++i) {
        double q = per_n_rel(f2, i) / per_n_rel(fv, i), s = per_n_rel(fs, i) / per_n_rel(fv, i);
        if (q < rmin) { rmin = q; rmin_n = fv->per_n[i].n; }
        if (q > rmax) { rmax = q; rmax_n = fv->per_n[i].n; }
        smin = fmin(smin, s);
        smax = fmax(smax, s);
        if (isnan(s45_n) && i > 0 && (per_n_rel(fs, i - 1) / per_n_rel(fv, i - 1) - 4.5) * (s - 4.5) <= 0)
            s45_n = fv->per_n[i].n;
    }
    if (!(c = claim_add(r, "claim", "P1-4.5x", "paper 1, abstract and conclusions",
                        "F_VOL reproduces the glare's epicentre up to 4.5 times more accurately than the classic "
                        "cosine-quadratic F2")))
        return EXIT_RUNTIME;
    claim_number(c, "4.5", 4.5, ratio, 0.1, "+-0.1 (one unit in the last printed digit)");
    if (fabs(rmax - 4.5) <= 0.1)
        c->reproduced = 1;   /* the "up to" reading */
    setf(c->measured_text, sizeof c->measured_text, "%.3f (ratio of the max deltas); per-n ratio %.3f..%.3f", ratio,
         rmin, rmax);
    note_add(c, "Per-n ratio F2/F_VOL: %.3f at n = %g to %.3f at n = %g; it reaches 4.5 at no n of [16, 1000]. "
                "Against Schlick the per-n ratio is %.3f..%.3f", rmin, rmin_n, rmax, rmax_n, smin, smax);
    if (isfinite(s45_n))
        note_add(c, "and passes 4.5 at n = %g.", s45_n);
    else
        note_add(c, ".");
    setf(c->method, sizeof c->method, "device sweeps of fvol, cq2, schlick, n in [16, 1000] step 1");

    /* Fig. 5: where the max Delta lies, and its order. */
    const struct accuracy_result *set[3] = { fv, fs, f2 };
    static const char *const names[3] = { "F_VOL", "F_S", "F2" };
    int all_att = 1;
    char where[512] = "";
    size_t used = 0;
    for (int k = 0; k < 3; ++k) {
        const struct accuracy_result *a = set[k];
        long epi_wins = 0;
        for (long i = 0; i < a->n_count; ++i)
            if (a->per_n[i].epi_abs_d.value > a->per_n[i].att_abs_d.value)
                ++epi_wins;
        int in_att = a->whole.x > zone_epicentre_end(a->whole.n) && epi_wins == 0;
        all_att &= in_att;
        used += (size_t)snprintf(where + used, used < sizeof where ? sizeof where - used : 0,
                                 "%s%s %.4f at n = %g, x = %.4f (x_e = %.4f); the epicentre's max Delta is the larger "
                                 "at %ld of %ld n", k ? "; " : "",
                                 names[k], a->whole.value, a->whole.n, a->whole.x, zone_epicentre_end(a->whole.n),
                                 epi_wins, a->n_count);
    }
    if (!(c = claim_add(r, "claim", "P1-fig5-zone", "paper 1, figs. 5-6",
                        "the max Delta of F_VOL, F_S and F2 against F_B lies in the attenuation zone")))
        return EXIT_RUNTIME;
    claim_bool(c, "attenuation zone", all_att, "the whole-range max Delta at x > x_e(n), at every n");
    setf(c->measured_text, sizeof c->measured_text, "%s", all_att ? "attenuation zone for all three" : "not for all");
    note_add(c, "%s.", where);
    setf(c->method, sizeof c->method, "device sweeps, n in [16, 1000] step 1, per-n maxima of both zones");

    if (!(c = claim_add(r, "claim", "P1-fig5-order", "paper 1, fig. 5 and text",
                        "F_VOL's max Delta is lower than F_S's and F2's (a more realistic attenuation zone)")))
        return EXIT_RUNTIME;
    claim_bool(c, "F_VOL < F2, F_S", fv->attenuation.value < f2->attenuation.value &&
                                         fv->attenuation.value < fs->attenuation.value, "range maxima over [16, 1000]");
    setf(c->measured_text, sizeof c->measured_text, "F_VOL %.4f, F2 %.4f, F_S %.4f", fv->attenuation.value,
         f2->attenuation.value, fs->attenuation.value);
    setf(c->method, sizeof c->method, "device sweeps, n in [16, 1000] step 1");

    /* Harness check: the quadratic in xi is the integral of F_VOL itself (the identity behind
       eq. 12), and host and device quadrature agree. */
    if (!(c = claim_add(r, "check", "C-eq11-device", "harness",
                        "host (GSL, in x) and device (Gauss-Legendre, in u = cos x) quadrature of eq. 11 agree")))
        return EXIT_RUNTIME;
    claim_bool(c, "<= 1e-6 relative", agree <= 1e-6, "largest relative difference of the four integrals <= 1e-6");
    setf(c->measured_text, sizeof c->measured_text, "%.2e", agree);
    c->measured = agree;
    if (agree > 1e-6)
        p->consistency_failed = 1;
    setf(c->method, sizeof c->method, "%s", method);
    return 0;
}

/* ---- paper 2 ---------------------------------------------------------------------------- */

struct cq2_zone_ctx {
    const struct model_spec *m, *ref;
    double n, target;
};

/* cq2's delta at the end of a zone that ends where c^n = exp(-K). */
static double cq2_end_minus(double k, void *p)
{
    const struct cq2_zone_ctx *c = p;
    return error_rel_host(c->m, c->ref, exp(-k / c->n), c->n) - c->target;
}

static int add_paper2(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    const struct accuracy_result *fq = &p->sw[SW_FQ], *fq2 = &p->sw[SW_FQ2], *f2 = &p->sw[SW_CQ2_P2];
    const char *sweep_method = "device sweep, n in [2, 1000] step 1, polished in double";
    struct model_spec fq_spec = fq->model, cq2_spec = f2->model, phong;
    model_spec_default(models_find("phong"), &phong);

    /* f_Q, Q = 0.64 */
    if (!(c = p2_sweep_claim(r, "P2-fq", "paper 2, text after fig. 3",
                             "f_Q with Q = 0.64: max delta in the epicentre over n in [2, 1000] is 1.255%", "1.255%",
                             0.01255, &fq->epicentre, 1)))
        return EXIT_RUNTIME;
    {
        long nc = 999;
        double nv[999];
        for (long i = 0; i < nc; ++i)
            nv[i] = 2.0 + (double)i;
        struct fq_ctx fc = { nv, nc, 0.01255, 0 };
        double q_at = root_brent(fq_max_rel_minus_target, &fc, 0.60, 0.6499);
        note_add(c, "The maximum lies inside the zone (x = %.5f < x_e = %.5f), so the zone's end does not enter; the "
                    "per-n max delta rises with n towards %.4f%% (n = 1e6, host double), so 1.255%% is reached at no "
                    "n, and the grid does not move it (below).", fq->epicentre.x, zone_epicentre_end(fq->epicentre.n),
                 100 * host_max_rel_at(&fq_spec, 1e6));
        if (isfinite(q_at))
            note_add(c, "1.255%% is f_Q's max delta over [2, 1000] at Q = %.5f.", q_at);
    }
    grid_note(p, c, SW_FQ);

    /* f_Q2 */
    if (!(c = p2_sweep_claim(r, "P2-fq2-rel", "paper 2, fig. 6(a)",
                             "f_Q2: max delta in the epicentre over n in [2, 1000] is 1.256%", "1.256%", 0.01256,
                             &fq2->epicentre, 1)))
        return EXIT_RUNTIME;
    grid_note(p, c, SW_FQ2);
    if (!(c = p2_sweep_claim(r, "P2-fq2-abs", "paper 2, fig. 6(b)", "f_Q2: max Delta over n in [2, 1000] is 0.128",
                             "0.128", 0.128, &fq2->whole, 0)))
        return EXIT_RUNTIME;
    grid_note(p, c, SW_FQ2);

    if (!(c = claim_add(r, "claim", "P2-fq2-zone", "paper 2, discussion",
                        "f_Q2's max Delta lies in the attenuation zone")))
        return EXIT_RUNTIME;
    claim_bool(c, "attenuation zone", fq2->whole.x > zone_epicentre_end(fq2->whole.n), "x > x_e(n) at the maximum");
    setf(c->measured_text, sizeof c->measured_text, "x = %.4f > x_e = %.4f at n = %g", fq2->whole.x,
         zone_epicentre_end(fq2->whole.n), fq2->whole.n);
    setf(c->method, sizeof c->method, "%s", sweep_method);

    /* f2 */
    if (!(c = p2_sweep_claim(r, "P2-f2-rel", "paper 2, discussion",
                             "f2 (classic cosine-quadratic): max delta in the epicentre over n in [2, 1000] is 7.924%",
                             "7.924%", 0.07924, &f2->epicentre, 1)))
        return EXIT_RUNTIME;
    strncat(c->measured_text, " (the zone end)", sizeof c->measured_text - strlen(c->measured_text) - 1);
    {
        struct cq2_zone_ctx zc = { &cq2_spec, &phong, f2->epicentre.n, 0.07924 };
        double kz = root_brent(cq2_end_minus, &zc, 0.45, 0.60);
        note_add(c, "f2's delta grows up to the zone's end; its per-n max rises with n towards %.4f%% (n = 1e6, host "
                    "double), so 7.924%% is reached at no n.", 100 * host_max_rel_at(&cq2_spec, 1e6));
        if (isfinite(kz))
            note_add(c, "Diagnostic: at n = %g it would need the zone to end where c^n = exp(-%.4f) instead of "
                        "exp(-0.511).", zc.n, kz);
    }
    grid_note(p, c, SW_CQ2_P2);
    if (!(c = p2_sweep_claim(r, "P2-f2-abs", "paper 2, discussion", "f2: max Delta over n in [2, 1000] is 0.162",
                             "0.162", 0.162, &f2->whole, 0)))
        return EXIT_RUNTIME;
    grid_note(p, c, SW_CQ2_P2);

    double ratio = f2->epicentre.value / fq2->epicentre.value;
    if (!(c = claim_add(r, "claim", "P2-6.3x", "paper 2, conclusions",
                        "f_Q2 reproduces the epicentre 6.3 times more accurately than f2 (ratio of the max deltas)")))
        return EXIT_RUNTIME;
    claim_number(c, "6.3", 6.3, ratio, 0.1, "+-0.1 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.3f", ratio);
    note_add(c, "The paper's own figures give 7.924/1.256 = %.3f; the difference is f2's max delta (P2-f2-rel).",
             7.924 / 1.256);
    setf(c->method, sizeof c->method, "%s", sweep_method);

    /* Fig. 4: the linear fit of k_Q(n), Q = 0.64. */
    double worst = -1, worst_n = NAN;
    for (long i = 0; i <= 99800; ++i) {   /* n in [2, 1000] step 0.01 */
        double n = 2.0 + 0.01 * (double)i;
        double e = fabs((0.448 * n + 0.099) / brdf_k_q(n, 0.64) - 1.0);
        if (e > worst) { worst = e; worst_n = n; }
    }
    if (!(c = claim_add(r, "claim", "P2-fig4", "paper 2, fig. 4",
                        "0.448n + 0.099 is within 0.5% of k_Q(n) = (sqrt(Q) - 1)/(Q^(1/n) - 1), Q = 0.64, "
                        "for n in [2, 1000]")))
        return EXIT_RUNTIME;
    snprintf(c->claimed_text, sizeof c->claimed_text, "<= 0.5%%");
    c->claimed = 0.005;
    c->measured = worst;
    c->reproduced = worst <= 0.005 * (1 + 1e-9);
    snprintf(c->tolerance, sizeof c->tolerance, "max |fit/k_Q - 1| <= 0.5%%");
    setf(c->measured_text, sizeof c->measured_text, "%.4f%% at n = %g", 100 * worst, worst_n);
    note_add(c, "At the bound: k_Q(2) = 1 exactly (Q^(1/2) = sqrt(Q)) and the fit gives 0.995 there.");
    setf(c->method, sizeof c->method, "k_Q from the model header in double, n in [2, 1000] step 0.01");

    /* Our least-squares fit of k_Q(n) over the integer n of [2, 1000]. */
    {
        double nv[999], kv[999];
        for (int i = 0; i < 999; ++i) {
            nv[i] = 2.0 + i;
            kv[i] = brdf_k_q(nv[i], 0.64);
        }
        double b0, a1, cov00, cov01, cov11, ss;
        gsl_fit_linear(nv, 1, kv, 1, 999, &b0, &a1, &cov00, &cov01, &cov11, &ss);
        double own_worst = 0;
        for (int i = 0; i < 999; ++i)
            own_worst = fmax(own_worst, fabs((a1 * nv[i] + b0) / kv[i] - 1));
        double kappa = (1 - 0.8) / -log(0.64);
        if (!(c = claim_add(r, "claim", "P2-fit-k-a", "paper 2, text before fig. 4",
                            "linear regression of k_Q(n), Q = 0.64, over n in [2, 1000]: slope 0.448")))
            return EXIT_RUNTIME;
        claim_number(c, "0.448", 0.448, a1, 0.001, "+-0.001 (one unit in the last printed digit)");
        setf(c->measured_text, sizeof c->measured_text, "%.6f", a1);
        note_add(c, "Our least-squares fit over the integer n of [2, 1000]: %.6f n + %.6f, within %.3f%% of k_Q(n). "
                    "The large-n slope of k_Q is (1 - sqrt(Q))/(-ln Q) = %.6f.", a1, b0, 100 * own_worst, kappa);
        setf(c->method, sizeof c->method, "GSL gsl_fit_linear on k_Q(n) at n = 2, 3, ..., 1000");
        if (!(c = claim_add(r, "claim", "P2-fit-k-b", "paper 2, text before fig. 4",
                            "linear regression of k_Q(n), Q = 0.64, over n in [2, 1000]: intercept 0.099")))
            return EXIT_RUNTIME;
        claim_number(c, "0.099", 0.099, b0, 0.001, "+-0.001 (one unit in the last printed digit)");
        setf(c->measured_text, sizeof c->measured_text, "%.6f", b0);
        note_add(c, "k_Q(n) = %.6f n + %.6f + O(1/n) (1/expm1 series), so an unweighted fit over [2, 1000] lands "
                    "near %.3f; the paper's sample of n is not stated.", kappa, 0.5 * (1 - 0.8), 0.5 * (1 - 0.8));
        setf(c->method, sizeof c->method, "GSL gsl_fit_linear on k_Q(n) at n = 2, 3, ..., 1000");
    }

    /* The Q sweep (figs. 2-3). */
    const struct accuracy_result *qb = &p->fq_best;
    char qgrid[256];
    snprintf(qgrid, sizeof qgrid, "Q sweep: Q = %g..%g step %g, n in [2, 1000] step %g, %ld samples per zone "
                                  "(q_sweep.json)", p->o->q_min, p->q[p->nq - 1], p->o->q_step, p->o->q_n_step,
             p->o->q_samples);
    if (!(c = claim_add(r, "claim", "P2-fig2-Q", "paper 2, figs. 2-3 and text",
                        "Q = 0.64 gives f_Q's most accurate epicentre (chosen among Q near 0.6)")))
        return EXIT_RUNTIME;
    claim_number(c, "0.64", 0.64, p->q_best, 0.005, "+-0.005 (0.64 is the minimiser rounded to 2 decimals)");
    setf(c->measured_text, sizeof c->measured_text, "Q = %.4f: max delta %.4f%%, max Delta %.5f", p->q_best,
         100 * qb->epicentre.value, qb->whole.value);
    note_add(c, "At Q = 0.64: max delta %.4f%%, max Delta %.5f. The minimiser trades a %.1f%% larger max Delta for "
                "the lower max delta; the paper states 0.64 as the more accurate value.", 100 * fq->epicentre.value,
             fq->whole.value, 100 * (qb->whole.value / fq->whole.value - 1));
    note_add(c, "%s; the minimiser by GSL Brent on the exact per-n figures, then measured by the device sweep "
                "(4096 samples).", qgrid);
    setf(c->method, sizeof c->method, "device sweeps over Q; GSL Brent over Q");

    if (!(c = claim_add(r, "claim", "P2-fig2-0.6", "paper 2, fig. 2",
                        "the most accurate epicentre approximation is reached at Q about 0.6")))
        return EXIT_RUNTIME;
    claim_number(c, "0.6", 0.6, p->q_best, 0.1, "+-0.1 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "Q = %.4f", p->q_best);
    note_add(c, "%s.", qgrid);
    setf(c->method, sizeof c->method, "device sweeps over Q; GSL Brent over Q");

    {
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
        if (!(c = claim_add(r, "claim", "P2-fig3", "paper 2, fig. 3 and text",
                            "f_Q's max Delta (Q = 0.64) is lower than f2's")))
            return EXIT_RUNTIME;
        claim_bool(c, "f_Q < f2", fq->whole.value < f2->whole.value, "range maxima over [2, 1000]");
        setf(c->measured_text, sizeof c->measured_text, "f_Q %.5f, f2 %.5f", fq->whole.value, f2->whole.value);
        note_add(c, "Over the Q sweep f_Q's max Delta is below f2's at %d of %d Q%s%s%s", below, p->nq,
                 runs[0] ? " (not at Q = " : ".", runs, runs[0] ? ")." : "");
        setf(c->method, sizeof c->method, "%s", sweep_method);
    }

    /* coef(n) */
    static const double coef_n[4] = { 2, 3, 4, 10 };
    static const double coef_claim[4] = { 0.634, 0.833, 1.04, 2.313 };
    static const char *const coef_text[4] = { "0.634", "0.833", "1.04", "2.313" };
    static const double coef_tol[4] = { 0.001, 0.001, 0.01, 0.001 };
    for (int i = 0; i < 4; ++i) {
        char id[32], what[160], tol[96];
        snprintf(id, sizeof id, "P2-coef-%g", coef_n[i]);
        snprintf(what, sizeof what, "coef(%g) = 1/(2 pi int_0^gran(n) f_Q2 cos g sin g dg) is %s (fig. 7)", coef_n[i],
                 coef_text[i]);
        snprintf(tol, sizeof tol, "+-%g (one unit in the last printed digit)", coef_tol[i]);
        if (!(c = claim_add(r, "claim", id, "paper 2, fig. 7", what)))
            return EXIT_RUNTIME;
        double v = paper2_coef(coef_n[i]);
        claim_number(c, coef_text[i], coef_claim[i], v, coef_tol[i], tol);
        setf(c->measured_text, sizeof c->measured_text, "%.6f", v);
        setf(c->method, sizeof c->method, "adaptive GSL QAG of the registry's fq2, gran(n) capped at pi/2");
    }
    double nv[999], cv[999];
    for (int i = 0; i < 999; ++i) {
        nv[i] = 2.0 + i;
        cv[i] = paper2_coef(nv[i]);
    }
    double c0, a1, cov00, cov01, cov11, ss;
    gsl_fit_linear(nv, 1, cv, 1, 999, &c0, &a1, &cov00, &cov01, &cov11, &ss);
    double own_b = c0 / a1;
    double dev_theirs = -1, dev_theirs_n = NAN, dev_own = -1, dev_own_n = NAN, alb_max = -1, alb_max_n = NAN;
    long above = 0;
    double above_from = NAN;
    for (int i = 0; i < 999; ++i) {
        double t = 0.214 * (0.807 + nv[i]) / cv[i], o = a1 * (own_b + nv[i]) / cv[i];
        if (fabs(t - 1) > dev_theirs) { dev_theirs = fabs(t - 1); dev_theirs_n = nv[i]; }
        if (fabs(o - 1) > dev_own) { dev_own = fabs(o - 1); dev_own_n = nv[i]; }
        if (t > alb_max) { alb_max = t; alb_max_n = nv[i]; }
        if (t > 1) {
            ++above;
            if (isnan(above_from)) above_from = nv[i];
        }
    }
    if (!(c = claim_add(r, "claim", "P2-coef-fit-a", "paper 2, figs. 9-10",
                        "coef(n) fitted as a (b + n) over n in [2, 1000]: a = 0.214")))
        return EXIT_RUNTIME;
    claim_number(c, "0.214", 0.214, a1, 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.6f", a1);
    note_add(c, "Our least-squares fit over the integer n of [2, 1000]: coef(n) = %.6f (%.5f + n).", a1, own_b);
    setf(c->method, sizeof c->method, "GSL gsl_fit_linear on coef(n) at n = 2, 3, ..., 1000");
    if (!(c = claim_add(r, "claim", "P2-coef-fit-b", "paper 2, figs. 9-10",
                        "coef(n) fitted as a (b + n) over n in [2, 1000]: b = 0.807")))
        return EXIT_RUNTIME;
    claim_number(c, "0.807", 0.807, own_b, 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f", own_b);
    note_add(c, "An unweighted fit over every integer n follows the large-n slope; the paper fitted a 50-value "
                "sample with symbolic regression (TuringBot: 0.213896 (0.807175 + n)).");
    setf(c->method, sizeof c->method, "GSL gsl_fit_linear on coef(n) at n = 2, 3, ..., 1000");

    if (!(c = claim_add(r, "claim", "P2-coef-dev", "paper 2, fig. 11",
                        "max |coef_fit(n) 2 pi int ... - 1| over n in [2, 1000] is 53e-3 for coef_fit = 0.214 (0.807 + n)")))
        return EXIT_RUNTIME;
    claim_number(c, "53e-3", 0.053, dev_theirs, 0.001, "+-1e-3 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f at n = %g", dev_theirs, dev_theirs_n);
    note_add(c, "With our least-squares fit %.6f (%.5f + n) it is %.5f at n = %g.", a1, own_b, dev_own, dev_own_n);
    setf(c->method, sizeof c->method, "coef(n) by adaptive quadrature at n = 2, 3, ..., 1000");

    if (!(c = claim_add(r, "claim", "P2-energy", "paper 2, discussion and conclusions",
                        "f_Q2 with coef(n) = 0.214 (0.807 + n) obeys the energy conservation law "
                        "(directional albedo <= 1)")))
        return EXIT_RUNTIME;
    claim_bool(c, "albedo <= 1", alb_max <= 1.0 + 1e-9, "albedo <= 1 + 1e-9 (the quadrature's accuracy is 1e-12)");
    c->claimed = 1.0;
    c->measured = alb_max;
    setf(c->measured_text, sizeof c->measured_text, "albedo up to %.6f (n = %g, normal incidence)", alb_max, alb_max_n);
    if (above > 0)
        note_add(c, "Above 1 at %ld of the 999 integer n in [2, 1000], the first n = %g; the normal-incidence albedo "
                    "is coef_fit(n) 2 pi int ..., the largest over incidence angles (energy.json).", above, above_from);
    if (p->have_energy)
        for (int i = 0; i < p->energy.count; ++i)
            if (strcmp(p->energy.models[i].spec.info->id, "fq2n") == 0)
                note_add(c, "Device albedo table: largest %.6f at n = %g, theta_i = %g deg.",
                         p->energy.models[i].max_albedo, p->energy.models[i].max_at_n,
                         p->energy.models[i].max_at_theta_deg);
    setf(c->method, sizeof c->method, "coef(n) by adaptive quadrature at n = 2, 3, ..., 1000; device albedo");
    return 0;
}

/* ---- the approximations engines use (docs/definitions.md) --------------------------------------------- */

static int add_engines(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    double a = NAN, err = NAN;
    int rc = fit_bg_exact_a(18.0, 2, &a, &err);
    if (!(c = claim_add(r, "claim", "BG-A-18", "Beaudoin and Guardado 2002 (ShaderX), table",
                        "m = 2, n = 18: A = 6.645 balances the largest errors of max(0, A c + 1 - A)^2 - c^n")))
        return EXIT_RUNTIME;
    claim_number(c, "6.645", 6.645, rc ? NAN : a, 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f", a);
    setf(c->method, sizeof c->method, "bisection on A; each side's maximum over c in [0, 1] on a 2049-point grid "
                                      "polished with Brent, in double (fit_bg_exact_a)");
    if (!(c = claim_add(r, "claim", "BG-err-18", "Beaudoin and Guardado 2002 (ShaderX), table",
                        "m = 2, n = 18: the largest |f - c^n| over c in [0, 1] is 0.0631")))
        return EXIT_RUNTIME;
    claim_number(c, "0.0631", 0.0631, rc ? NAN : err, 0.0001, "+-1e-4 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f", err);
    setf(c->method, sizeof c->method, "at the balancing A above");
    return 0;
}

/* ---- harness checks: energy, reciprocity, grid ------------------------------------------ */

static int add_checks(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    if (p->have_energy) {
        const struct energy_summary *e = &p->energy;
        for (int i = 0; i < e->count; ++i) {
            const struct energy_model_summary *m = &e->models[i];
            if (!isfinite(m->normal_max_diff))
                continue;
            char id[32], what[256], tol[96];
            snprintf(id, sizeof id, "C-albedo-%s%s", m->spec.info->id, m->mode == ALBEDO_DCOS ? "-norm" : "");
            double cf;
            const char *why = "";
            albedo_closed_form_normal(&m->spec, m->mode, 2.0, &cf, &why);
            snprintf(what, sizeof what, "%s %s: device quadrature at normal incidence equals the closed form (%s)",
                     m->spec.info->id, m->mode == ALBEDO_DCOS ? "normalisation" : "albedo", why);
            snprintf(tol, sizeof tol, "|device - closed form| <= %.0e at n = 2, 4, 10, 100, 1000", e->quadrature_tolerance);
            if (!(c = claim_add(r, "check", id, "closed form", what)))
                return EXIT_RUNTIME;
            claim_bool(c, "closed form", m->normal_max_diff <= e->quadrature_tolerance, tol);
            c->measured = m->normal_max_diff;
            setf(c->measured_text, sizeof c->measured_text, "largest difference %.2e (n = %g)", m->normal_max_diff,
                 m->normal_diff_at_n);
            note_add(c, "Refining the quadrature (panels halved, twice the azimuth points) changes the table by at "
                        "most %.1e.", m->refine_change);
            setf(c->method, sizeof c->method, "device albedo quadrature (energy.json)");
        }
        double worst_host = 0, worst_dev = 0, worst_eval = 0;
        const char *worst_model = "";
        const struct recip_worst *wd = NULL;
        for (int i = 0; i < e->recip_count; ++i) {
            worst_host = fmax(worst_host, e->recip[i].host.diff);
            worst_eval = fmax(worst_eval, e->recip[i].device.eval_error);
            if (e->recip[i].device.diff >= worst_dev) {
                worst_dev = e->recip[i].device.diff;
                worst_model = e->recip[i].spec.label;
                wd = &e->recip[i].device;
            }
        }
        double pass_dev = 0, pass_host = 0;
        const struct recip_pass_summary *pw = NULL;
        int ct = 0;
        for (int i = 0; i < e->pass_count; ++i) {
            pass_host = fmax(pass_host, e->pass[i].host_worst);
            if (e->pass[i].mode >= 2)
                ++ct;
            if (!pw || e->pass[i].device_worst > pass_dev) {
                pass_dev = e->pass[i].device_worst;
                pw = &e->pass[i];
            }
        }
        if (!(c = claim_add(r, "claim", "P2-reciprocity", "paper 2, BRDF property 2",
                            "f(L, V) = f(V, L) (Helmholtz reciprocity) for every model, as the image passes "
                            "evaluate it")))
            return EXIT_RUNTIME;
        claim_bool(c, "f(L,V) = f(V,L)", worst_host <= 1e-9 && pass_host <= 1e-9 && e->pass_count > 0 && pass_dev <= 1e-5,
                   "double: relative difference <= 1e-9; the float image pass: <= 1e-5 (rounding of its products)");
        c->measured = pass_dev;
        setf(c->measured_text, sizeof c->measured_text, "image pass: float %.1e, double %.1e (relative); lobes: "
             "double %.1e of peak", pass_dev, pass_host, worst_host);
        if (pw)
            note_add(c, "Image pass (kernels/shade.cl), %d models of which %d Cook-Torrance, %ld pixels each shaded "
                        "twice with eye and light swapped: worst float difference %.1e (%s, n = %.4g).",
                     e->pass_count, ct, e->recip_pairs, pass_dev, pw->spec.label, pw->n);
        if (wd)
            note_add(c, "Lobe functions alone, %ld random (N, L, V) per registry model: in double within %.1e of "
                        "peak; in float with R formed as a vector the worst pair (%s, n = %.4g) differs by %.1e of "
                        "peak, the size of a single float value's error (%.1e): rounding of the lobe's cosine "
                        "amplified n times. cos psi = 2(N.L)(N.V) - L.V and N.H are symmetric in L, V.",
                     e->recip_pairs, worst_host, worst_model, wd->n, worst_dev, worst_eval);
        setf(c->method, sizeof c->method, "device image pass and its double reference; lobe kernel (energy.json)");
    }
    double worst = 0;
    const char *where = "";
    for (int i = 0; i < SW_COUNT; ++i)
        if (isfinite(p->grid_change[i]) && p->grid_change[i] >= worst) {
            worst = p->grid_change[i];
            where = sweep_defs[i].model;
        }
    if (p->o->grid_check) {
        if (!(c = claim_add(r, "check", "C-grid", "docs/definitions.md, zones and metrics",
                            "refining the sweep grid no longer moves a reported max delta or max Delta in its 4th "
                            "significant digit")))
            return EXIT_RUNTIME;
        claim_bool(c, "< 0.5 unit", worst < 0.5, "change < 0.5 of a unit in the 4th significant digit");
        c->measured = worst;
        setf(c->measured_text, sizeof c->measured_text, "largest change %.2g unit (%s)", worst, where);
        setf(c->method, sizeof c->method, "every claim sweep re-run with %ld samples per zone", 2 * p->o->samples);
    }
    double k2, e2;
    if (fit_minimax_k(2.0, &k2, &e2) == 0) {
        if (!(c = claim_add(r, "check", "C-fit-k2", "identity",
                            "the per-n minimax k of (k(c-1)+1)^2 at n = 2 is 1 (cq2 = c^2 there, delta = 0)")))
            return EXIT_RUNTIME;
        claim_number(c, "1", 1.0, k2, 1e-9, "+-1e-9");
        setf(c->measured_text, sizeof c->measured_text, "k = %.12f, max delta %.1e", k2, e2);
        setf(c->method, sizeof c->method, "fit.h: exact per-n max delta, GSL Brent on its two sides");
    }
    return 0;
}

/* ---- the papers' cost argument, measured ----------------------------------------------------- */

/* Paper 1: "physically accurate BRDFs do not always comply with the requirements of highly
 * productive graphics systems"; paper 2: "physically based BRDFs are computationally complex,
 * so their use in real-time systems is limited". Measured as every physically based model's
 * evaluations/s over fq2's and over Phong's, from the same (N, L, V), in one run. */
static int add_physical(struct repro *p)
{
    if (!p->have_physical)
        return 0;
    const struct pbcost_result *ph = &p->physical;
    double lo_fq2 = INFINITY, hi_fq2 = 0, lo_ph = INFINITY, hi_ph = 0;
    const char *lo_name = "", *hi_name = "";
    char per_model[600] = "";
    size_t used = 0;
    for (int i = 0; i < ph->count; ++i) {
        const struct pbcost_row *row = &ph->rows[i];
        if (!row->physical)
            continue;
        if (row->ratio_to_fq2 < lo_fq2) {
            lo_fq2 = row->ratio_to_fq2;
            lo_name = row->name;
        }
        if (row->ratio_to_fq2 > hi_fq2) {
            hi_fq2 = row->ratio_to_fq2;
            hi_name = row->name;
        }
        lo_ph = fmin(lo_ph, row->ratio_to_phong);
        hi_ph = fmax(hi_ph, row->ratio_to_phong);
        if (used < sizeof per_model)
            used += (size_t)snprintf(per_model + used, sizeof per_model - used, "%s%s %.3g/%.3g", used ? ", " : "",
                                     row->name, row->ratio_to_fq2, row->ratio_to_phong);
    }
    static const struct {
        const char *id, *source, *text;
    } rows[2] = {
        { "P1-physical-cost", "paper 1, sec. 2",
          "physically accurate BRDFs do not always comply with the requirements of highly productive graphics "
          "systems (the cost argument for empirical lobes)" },
        { "P2-physical-cost", "paper 2, review of BRDFs",
          "physically based BRDFs are computationally complex, so their use in real-time systems is limited" },
    };
    for (int k = 0; k < 2; ++k) {
        struct claim *c = claim_add(p->r, "claim", rows[k].id, rows[k].source, rows[k].text);
        if (!c)
            return EXIT_RUNTIME;
        claim_bool(c, "slower than the lobes", hi_fq2 < 1 && hi_ph < 1,
                   "holds when every physically based model evaluates fewer times per second than fq2 and than "
                   "Phong, from the same (N, L, V) in one run");
        c->measured = hi_fq2;
        setf(c->measured_text, sizeof c->measured_text, "%.3g-%.3gx fq2's rate, %.3g-%.3gx Phong's", lo_fq2, hi_fq2,
             lo_ph, hi_ph);
        note_add(c, "Evaluations/s relative to fq2 / to Phong (exp(n ln c)) on %s: %s. Slowest %s, fastest %s.",
                 p->s->device_name, per_model, lo_name, hi_name);
        if (hi_ph >= 1)
            note_add(c, "At least one physically based model is as fast as Phong or faster here: the cost argument "
                        "holds against the cosine-quadratic lobes, not against the Phong lobe.");
        setf(c->method, sizeof c->method, "physical.json: tp_vec_* kernels, fastest of %d launches, n = %g",
             ph->o.reps, ph->o.n);
    }
    return 0;
}

void reproduce_report_free(struct reproduce_report *r)
{
    free(r->rows);
    free(r->markdown);
    memset(r, 0, sizeof *r);
}

static void repro_free(struct repro *p)
{
    for (int i = 0; i < SW_COUNT; ++i)
        if (p->have_sw[i])
            accuracy_result_free(&p->sw[i]);
    if (p->have_fq_best)
        accuracy_result_free(&p->fq_best);
    free(p->q);
    free(p->q_rel);
    free(p->q_rel_n);
    free(p->q_abs);
    free(p->q_att);
    accuracy_close(&p->actx);
    integrate_close(&p->ic);
    energy_summary_free(&p->energy);
}

int reproduce_run_ex(struct cl_session *s, const char *out_dir, const struct reproduce_options *o, int quiet,
                     struct reproduce_report *report)
{
    char err[1024];
    struct reproduce_report local;
    struct reproduce_report *r = report ? report : &local;
    memset(r, 0, sizeof *r);
    if (reproduce_options_check(o, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_USAGE;
    }
    double t0 = wall_seconds();
    struct repro p;
    memset(&p, 0, sizeof p);
    p.s = s;
    p.o = o;
    p.r = r;
    int rc = accuracy_open(&p.actx, s, "");
    if (!rc)
        rc = integrate_open(&p.ic, s);
    if (!rc && !quiet)
        fprintf(stderr, "reproduce: claim sweeps...\n");
    if (!rc)
        rc = run_sweeps(&p);
    if (!rc && !quiet)
        fprintf(stderr, "reproduce: Q sweep (%g..%g step %g)...\n", o->q_min, o->q_max, o->q_step);
    if (!rc)
        rc = run_q_sweep(&p);
    if (!rc && o->energy) {
        if (!quiet)
            fprintf(stderr, "reproduce: albedo and reciprocity...\n");
        rc = energy_run(s, NULL, 1, &p.energy);   /* energy.json is written with the other files */
        p.have_energy = rc == 0;
    }
    if (!rc && o->physical) {
        if (!quiet)
            fprintf(stderr, "reproduce: cost of the physically based models...\n");
        struct pbcost_options po;
        pbcost_options_default(&po);
        rc = pbcost_run(s, &po, &p.physical, quiet);
        p.have_physical = rc == 0;
    }
    if (!rc)
        rc = add_paper1(&p);
    if (!rc)
        rc = add_paper2(&p);
    if (!rc)
        rc = add_engines(&p);
    if (!rc)
        rc = add_checks(&p);
    if (!rc)
        rc = add_physical(&p);
    if (rc)
        goto done;
    for (int i = 0; i < r->count; ++i) {
        if (r->rows[i].reproduced)
            r->reproduced++;
        else
            r->not_reproduced++;
    }
    r->seconds = wall_seconds() - t0;
    r->markdown = reproduce_claims_markdown(&p);
    if (!r->markdown) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (out_dir) {
        char path[4200];
        path_join(path, sizeof path, out_dir, "claims.json");
        if (reproduce_write_claims_json(&p, path, err, sizeof err) == 0) {
            path_join(path, sizeof path, out_dir, "claims.md");
            if (write_file_atomic(path, r->markdown, strlen(r->markdown), err, sizeof err) == 0) {
                path_join(path, sizeof path, out_dir, "q_sweep.json");
                if (reproduce_write_q_sweep_json(&p, path, err, sizeof err) == 0) {
                    err[0] = '\0';
                    if (p.have_energy && p.energy.json) {
                        path_join(path, sizeof path, out_dir, "energy.json");
                        write_file_atomic(path, p.energy.json, strlen(p.energy.json), err, sizeof err);
                    }
                    if (!err[0] && p.have_physical) {
                        path_join(path, sizeof path, out_dir, "physical.json");
                        pbcost_write_json(path, s, &p.physical, err, sizeof err);
                    }
                }
            }
        }
        if (err[0]) {
            fprintf(stderr, "brdfbench reproduce: %s\n", err);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    if (!quiet)
        reproduce_print_table(stdout, &p);
    if (p.consistency_failed) {
        fprintf(stderr, "brdfbench reproduce: host and device quadrature of eq. 11 disagree (row C-eq11-device)\n");
        rc = EXIT_RUNTIME;
    }
done:
    repro_free(&p);
    if (!report)
        reproduce_report_free(r);
    return rc;
}

