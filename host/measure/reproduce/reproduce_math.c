/* reproduce_math.c - the host-side numerics behind the claims (see reproduce_claims.h): paper 1's
 * eq. 11 and paper 2's coef(n) by adaptive quadrature, roots and minima by GSL Brent, a model's
 * largest delta on the host. */
#include "reproduce.h"
#include "reproduce_claims.h"
#include "accuracy.h"
#include "fit.h"
#include "models.h"
#include "refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

/* k_Q(n) of f_Q, from the model header itself (its single definition), in double. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

static const double half_pi = 1.57079632679489661923;
static const double two_pi = 6.28318530717958647692;

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
double root_brent(double (*f)(double, void *), void *ctx, double lo, double hi)
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
double fq_max_rel(double q, void *p)
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

double fq_max_rel_minus_target(double q, void *p)
{
    struct fq_ctx *c = p;
    return fq_max_rel(q, c) - c->target;
}

/* GSL Brent minimisation over [lo, hi] from m (f(m) below both ends required). */
double minimise_brent(double (*f)(double, void *), void *ctx, double lo, double m, double hi)
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


double host_max_rel_at(const struct model_spec *m, double n)
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

double eq11_term_minus(double k, void *p)
{
    const struct k_ctx *c = p;
    double v = NAN;
    eq11_host(k, 16.0, 256.0, c->term, &v);
    return v - c->target;
}

/* The first angle where a model is exactly 0 at n (a quadratic past its root), by bisection. */
double model_zero(const char *id, double n)
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

/* cq2's delta at the end of a zone that ends where c^n = exp(-K). */
double cq2_end_minus(double k, void *p)
{
    const struct cq2_zone_ctx *c = p;
    return error_rel_host(c->m, c->ref, exp(-k / c->n), c->n) - c->target;
}
