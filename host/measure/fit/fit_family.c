/* fit_family.c - any family: its minimax by Nelder-Mead on host figures, and the device sweeps
 * of the result (see fit.h). */
#include "fit.h"
#include "fit_internal.h"
#include "fit_report.h"
#include "context.h"
#include "exitcodes.h"
#include "outdir.h"
#include "refine.h"
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

static const double half_pi = 1.57079632679489661923;

/* ---- any family: minimax by Nelder-Mead on host figures ------------------------------------ */

#define FAM_EPI_SAMPLES 32      /* per n, epicentre grid before the Brent polish */
#define FAM_ATT_SAMPLES 96      /* per n, attenuation grid before the Brent polish */
#define FAM_SEARCH_N 48         /* n values the search sees (the figures use the whole grid) */
#define FAM_NM_ITER 400
/* A model whose double reference costs a device launch per value (model_eval_host_on_device:
   a user model whose text does not compile on the host), about a thousand times slower than a
   host evaluation: its search uses coarser sizes, and no trade-off curve. */
#define FAM_SLOW_EPI 12
#define FAM_SLOW_ATT 24
#define FAM_SLOW_SEARCH_N 12
#define FAM_SLOW_NM_ITER 120
#define FAM_NM_STARTS 3
#define FAM_PENALTY 100.0       /* exact penalty on a cap's excess */

double fit_power_eval(double c, double n, double a, double b, int m)
{
    return brdf_power(fmax(c, 0.0), a * n + b, m);
}

/* How finely a family's figures are found: samples per zone and Nelder-Mead iterations (fewer
   for a model whose host evaluation runs on the device, fit_family_run). */
struct fam_precision {
    int epi_samples, att_samples, nm_iter;
};
static const struct fam_precision fam_fine = { FAM_EPI_SAMPLES, FAM_ATT_SAMPLES, FAM_NM_ITER },
                                  fam_slow = { FAM_SLOW_EPI, FAM_SLOW_ATT, FAM_SLOW_NM_ITER };

struct fam_eval {
    struct model_spec spec;       /* registry or user model; unused with power_m */
    const struct fam_precision *prec;
    int power_m;
    double n, sign;
    int abs_mode;                 /* 0: |f/r - 1|, 1: |f - r| */
};

static double fam_value(const struct fam_eval *e, double c)
{
    if (e->power_m)
        return fit_power_eval(c, e->n, e->spec.params[0], e->spec.params[1], e->power_m);
    return model_eval_host(&e->spec, c, e->n);
}

static double fam_error(double x, void *p)
{
    const struct fam_eval *e = p;
    double c = fmax(cos(x), 0.0), f = fam_value(e, c), r = fit_reference_eval(c, e->n);
    double v = e->abs_mode ? fabs(f - r) : fabs(f / r - 1.0);
    return isfinite(v) ? v : 1e30;
}

/* Largest error over [x0, x0 + w] sampled at x0 + w (j/S)^power, polished around the best. */
static double fam_zone_max(struct fam_eval *e, double x0, double w, int samples, int power)
{
    double best = -1, xs[3];
    int bj = 0;
    for (int j = 0; j <= samples; ++j) {
        double t = (double)j / samples, x = x0 + w * (power == 2 ? t * t : t);
        double v = fam_error(x, e);
        if (v > best) { best = v; bj = j; }
    }
    for (int k = -1; k <= 1; ++k) {
        int j = bj + k < 0 ? 0 : bj + k > samples ? samples : bj + k;
        double t = (double)j / samples;
        xs[k + 1] = x0 + w * (power == 2 ? t * t : t);
    }
    double x, v;
    if (refine_maximum(fam_error, e, xs[0], xs[1], xs[2], &x, &v) == 0 && v > best)
        best = v;
    return best;
}

static void fam_at_n(struct fam_eval *e, double n, double *max_rel, double *max_abs)
{
    double xe = zone_epicentre_end(n);
    e->n = n;
    e->abs_mode = 0;
    *max_rel = fam_zone_max(e, 0.0, xe, e->prec->epi_samples, 1);
    e->abs_mode = 1;
    *max_abs = fam_zone_max(e, xe, half_pi - xe, e->prec->att_samples, 2);
}

static void figures(const struct fam_precision *prec, const struct model_spec *family, int power_m,
                    const double *params, const double *n, long count, struct fit_point *out)
{
    struct fam_eval e;
    memset(&e, 0, sizeof e);
    if (family)
        e.spec = *family;
    e.prec = prec;
    e.power_m = power_m;
    e.spec.params[0] = params[0];
    e.spec.params[1] = params[1];
    out->params[0] = params[0];
    out->params[1] = params[1];
    out->max_rel = out->max_abs = -1;
    for (long i = 0; i < count; ++i) {
        double r, a;
        fam_at_n(&e, n[i], &r, &a);
        if (r > out->max_rel) { out->max_rel = r; out->max_rel_n = n[i]; }
        if (a > out->max_abs) { out->max_abs = a; out->max_abs_n = n[i]; }
    }
}

void fit_family_figures(const struct model_spec *family, int power_m, const double *params, const double *n,
                        long count, struct fit_point *out)
{
    figures(&fam_fine, family, power_m, params, n, count, out);
}

struct fam_search {
    const struct fam_precision *prec;
    const struct model_spec *family;
    int power_m, nparams;
    double lo[2], hi[2], fixed[2];
    const double *n;
    long count;
    int objective;
    double cap;                   /* on the other figure; NAN: none */
};

static double fam_objective(const gsl_vector *v, void *p)
{
    const struct fam_search *S = p;
    double params[2] = { S->fixed[0], S->fixed[1] }, outside = 0;
    for (int k = 0; k < S->nparams; ++k) {
        params[k] = gsl_vector_get(v, (size_t)k);
        if (params[k] < S->lo[k]) outside += S->lo[k] - params[k];
        if (params[k] > S->hi[k]) outside += params[k] - S->hi[k];
    }
    if (outside > 0)
        return 1e3 * (1 + outside);
    struct fit_point pt;
    figures(S->prec, S->family, S->power_m, params, S->n, S->count, &pt);
    double primary = S->objective == FIT_MAX_ABS ? pt.max_abs : pt.max_rel;
    double other = S->objective == FIT_MAX_ABS ? pt.max_rel : pt.max_abs;
    if (isfinite(S->cap) && other > S->cap)
        primary += FAM_PENALTY * (other - S->cap);
    return primary;
}

/* Nelder-Mead from `start`, restarted from its result; writes the best parameters. */
static void fam_minimise(const struct fam_search *S, const double *start, double *best)
{
    const gsl_multimin_fminimizer_type *T = gsl_multimin_fminimizer_nmsimplex2;
    size_t dim = (size_t)S->nparams;
    gsl_multimin_fminimizer *m = gsl_multimin_fminimizer_alloc(T, dim);
    gsl_vector *x = gsl_vector_alloc(dim), *step = gsl_vector_alloc(dim);
    gsl_multimin_function fn = { fam_objective, dim, (void *)S };
    double cur[2] = { start[0], start[1] };
    for (int run = 0; run < FAM_NM_STARTS; ++run) {
        for (size_t k = 0; k < dim; ++k) {
            gsl_vector_set(x, k, cur[k]);
            gsl_vector_set(step, k, fmax(0.05 * fabs(cur[k]), 0.01) / (1 << (2 * run)));
        }
        gsl_multimin_fminimizer_set(m, &fn, x, step);
        for (int it = 0; it < S->prec->nm_iter; ++it) {
            if (gsl_multimin_fminimizer_iterate(m))
                break;
            if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(m), 1e-10) == GSL_SUCCESS)
                break;
        }
        for (size_t k = 0; k < dim; ++k)
            cur[k] = gsl_vector_get(m->x, k);
    }
    best[0] = cur[0];
    best[1] = cur[1];
    gsl_vector_free(step);
    gsl_vector_free(x);
    gsl_multimin_fminimizer_free(m);
}

/* One fitted point: search on the reduced n set, figures on the whole grid. */
static void fam_fit_point(struct fam_search *S, const double *start, int objective, double cap, const double *n_all,
                          long count_all, struct fit_point *out)
{
    S->objective = objective;
    S->cap = cap;
    double best[2];
    fam_minimise(S, start, best);
    figures(S->prec, S->family, S->power_m, best, n_all, count_all, out);
    out->cap = cap;
    double other = objective == FIT_MAX_ABS ? out->max_rel : out->max_abs;
    out->ok = !isfinite(cap) || other <= cap * (1 + 1e-6);
    if (!out->ok)
        snprintf(out->reason, sizeof out->reason, "no parameters found with the %s <= %.6g (best: %.6g)",
                 objective == FIT_MAX_ABS ? "max delta" : "max Delta", cap, other);
}

void fit_family_report_free(struct fit_family_report *r)
{
    if (r->have_sweep)
        accuracy_result_free(&r->sweep);
    r->have_sweep = 0;
}

/* The family to fit from the options: the power family's a and b, or the continuous
   parameters of a registry or user model, with their bounds and names; EXIT_USAGE (after a
   message) when there is nothing to fit. */
static int fam_setup(const struct fit_options *o, struct fam_search *S, struct model_spec *family,
                     struct fit_family_report *r)
{
    char err[1024];
    if (o->power_m) {
        S->power_m = o->power_m;
        S->nparams = 2;
        S->lo[0] = 0; S->hi[0] = 10; S->lo[1] = -10; S->hi[1] = 10;
        /* start at the asymptotic minimax slope a m ~ 0.9 (docs/definitions.md) */
        family->params[0] = 0.9 / o->power_m;
        family->params[1] = 0.1;
        snprintf(r->family, sizeof r->family, "power:m=%d", o->power_m);
        snprintf(r->param_names[0], sizeof r->param_names[0], "a");
        snprintf(r->param_names[1], sizeof r->param_names[1], "b");
        return 0;
    }
    if (model_spec_parse(o->model, family, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: --family: %s\n", err);
        return EXIT_USAGE;
    }
    for (int k = 0; k < family->info->nparams; ++k) {
        const struct model_param *mp = &family->info->params[k];
        if (mp->integer)
            continue;
        if (S->nparams == 1 && k == 1 && family->info->params[0].integer) {
            /* only the second is continuous: not supported by the parameter order */
        }
        S->lo[S->nparams] = mp->min;
        S->hi[S->nparams] = mp->max;
        snprintf(r->param_names[S->nparams], sizeof r->param_names[0], "%s", mp->name);
        S->nparams++;
    }
    if (S->nparams == 0 || (family->info->nparams == 2 && family->info->params[0].integer)) {
        fprintf(stderr, "brdfbench fit: --family %s: the model has no continuous parameter to fit "
                        "(accepted: a model with one or two continuous parameters, e.g. gauss, pow3, pow4, fq)\n",
                family->info->id);
        return EXIT_USAGE;
    }
    S->family = family;
    snprintf(r->family, sizeof r->family, "%s", family->info->id);
    return 0;
}

/* The search's n: the first few grid values (the worst often sit at small n), then
   log-spaced up to n_max; returns how many were written to ns. */
static long fam_search_grid(const double *n, long count, int search_n, double *ns)
{
    long nsn = 0;
    for (long i = 0; i < count && i < 6; ++i)
        ns[nsn++] = n[i];
    for (int j = 1; j <= search_n && count > 6; ++j) {
        double v = n[5] * pow(n[count - 1] / n[5], (double)j / search_n);
        ns[nsn++] = j == search_n ? n[count - 1] : v;
    }
    return nsn;
}

/* The fitted points: the two minima, the best under the options' cap, and (unless `slow`)
   the trade-off: the best max delta for caps on max Delta between the two ends. */
static void fam_fit_points(struct fam_search *S, const struct fit_options *o, const struct model_spec *family,
                           const double *n, long count, int slow, struct fit_family_report *r)
{
    double start[2] = { family->params[0], family->params[1] };
    fam_fit_point(S, start, FIT_MAX_REL, NAN, n, count, &r->min_rel);
    fam_fit_point(S, start, FIT_MAX_ABS, NAN, n, count, &r->min_abs);
    r->min_rel.ok = r->min_abs.ok = 1;
    double cap = o->objective == FIT_MAX_ABS ? o->max_rel_cap : o->max_abs_cap;
    const struct fit_point *from = o->objective == FIT_MAX_ABS ? &r->min_abs : &r->min_rel;
    if (isfinite(cap))
        fam_fit_point(S, from->params, o->objective, cap, n, count, &r->best);
    else
        r->best = *from;
    double lo = r->min_abs.max_abs, hi = r->min_rel.max_abs;
    for (int j = 1; j + 1 < FIT_TRADEOFF_POINTS && hi > lo && !slow; ++j) {
        double c = lo + (hi - lo) * j / (FIT_TRADEOFF_POINTS - 1);
        fam_fit_point(S, r->min_rel.params, FIT_MAX_REL, c, n, count, &r->tradeoff[r->tradeoff_count]);
        if (r->tradeoff[r->tradeoff_count].ok)
            r->tradeoff_count++;
    }
}

/* The best point as --models text in r->spec_text (empty when the family has no model id),
   parsed into *fitted; returns whether it parsed. */
static int fam_fitted_spec(const struct fit_options *o, const struct model_spec *family,
                           struct fit_family_report *r, struct model_spec *fitted)
{
    char err[1024];
    const char *id = NULL;
    if (o->power_m == 2) id = "quad";
    else if (o->power_m == 3) id = "pow3";
    else if (o->power_m == 4) id = "pow4";
    if (id)
        snprintf(r->spec_text, sizeof r->spec_text, "%s:a=%.10g,b=%.10g", id, r->best.params[0],
                 r->best.params[1]);
    else if (!o->power_m) {
        struct model_spec t = *family;
        int k2 = 0;
        for (int k = 0; k < family->info->nparams; ++k)
            if (!family->info->params[k].integer)
                t.params[k] = r->best.params[k2++];
        size_t used = (size_t)snprintf(r->spec_text, sizeof r->spec_text, "%s", family->info->id);
        for (int k = 0; k < family->info->nparams && used < sizeof r->spec_text; ++k)
            used += (size_t)snprintf(r->spec_text + used, sizeof r->spec_text - used, "%s%s=%.10g",
                                     k ? "," : ":", family->info->params[k].name, t.params[k]);
    }
    return r->spec_text[0] && model_spec_parse(r->spec_text, fitted, err, sizeof err) == 0;
}

int fit_family_run(struct cl_session *s, const struct fit_options *o, struct fit_family_report *report)
{
    char err[1024];
    struct fit_family_report local;
    struct fit_family_report *r = report ? report : &local;
    double t0;
    if (fit_start(s, o, r, sizeof *r, &r->opt, &r->grid, &t0))
        return EXIT_USAGE;
    struct accuracy_grid g = r->grid;
    struct fam_search S;
    memset(&S, 0, sizeof S);
    struct model_spec family;
    memset(&family, 0, sizeof family);
    if (fam_setup(o, &S, &family, r))
        return EXIT_USAGE;
    r->nparams = S.nparams;
    int slow = !o->power_m && model_eval_host_on_device(&family);
    S.prec = slow ? &fam_slow : &fam_fine;
    int search_n = slow ? FAM_SLOW_SEARCH_N : FAM_SEARCH_N;
    /* The device programs (a user model's own, and its double reference) before the search. */
    struct accuracy_ctx actx;
    memset(&actx, 0, sizeof actx);
    int rc = accuracy_open(&actx, s, "");
    if (!rc && !o->power_m)
        rc = accuracy_prepare(&actx, &family);
    if (rc) {
        accuracy_close(&actx);
        return rc;
    }
    S.fixed[0] = family.params[0];
    S.fixed[1] = family.params[1];
    long count = accuracy_grid_count(&g);
    double *n = malloc((size_t)count * sizeof *n);
    double ns[FAM_SEARCH_N + 8];   /* FAM_SLOW_SEARCH_N is smaller */
    if (!n) {
        fprintf(stderr, "brdfbench fit: out of memory\n");
        accuracy_close(&actx);
        return EXIT_RUNTIME;
    }
    for (long i = 0; i < count; ++i)
        n[i] = accuracy_grid_n(&g, i);
    S.n = ns;
    S.count = fam_search_grid(n, count, search_n, ns);
    fam_fit_points(&S, o, &family, n, count, slow, r);
    /* The fitted model as --models text, and its device sweep. */
    struct model_spec fitted;
    if (r->best.ok && fam_fitted_spec(o, &family, r, &fitted)) {
        rc = accuracy_run(&actx, &fitted, &g, &r->sweep);
        if (!rc)
            r->have_sweep = 1;
    }
    accuracy_close(&actx);
    r->seconds = wall_seconds() - t0;
    if (!rc && o->io.out_dir) {
        char path[4200];
        path_join(path, sizeof path, o->io.out_dir, "fit.json");
        if (fit_family_write_json(path, r, s, err, sizeof err)) {
            fprintf(stderr, "brdfbench fit: %s\n", err);
            rc = EXIT_RUNTIME;
        }
    }
    if (!rc && !o->io.quiet)
        fit_family_print(stdout, r);
    if (!rc && !r->best.ok) {
        fprintf(stderr, "brdfbench fit: infeasible: %s\n", r->best.reason);
        rc = EXIT_GATE_FAIL;
    }
    free(n);
    if (!report)
        fit_family_report_free(r);
    return rc;
}
