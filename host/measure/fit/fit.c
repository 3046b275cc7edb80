/* fit.c - the accuracy limit of the cosine-quadratic family and its best affine k(n)
 * (see fit.h for the method). Everything here is double precision on the host; the device
 * sweep of accuracy.c then measures the fitted model beside fq2, fvol and cq2. */
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

#define FIT_ATT_SAMPLES 256     /* host grid of the attenuation zone before the Brent polish */
#define FIT_ROOT_ITER 200
#define FIT_BISECT_ITER 200
#define FIT_FEAS_SAMPLES 64     /* grid over the slope a before the Brent polish */

void fit_options_default(struct fit_options *o)
{
    memset(o, 0, sizeof *o);
    o->n_min = 2.0;
    o->n_max = 1000.0;
    o->n_step = 1.0;
    o->max_abs_cap = NAN;
    o->samples = ACC_DEFAULT_SAMPLES;
    o->model = NULL;
    o->power_m = 0;
    o->objective = FIT_MAX_REL;
    o->max_rel_cap = NAN;
}

int fit_options_check(const struct fit_options *o, char *err, size_t errlen)
{
    struct accuracy_grid g = { o->n_min, o->n_max, o->n_step, o->samples };
    int rc = accuracy_grid_check(&g, NULL, err, errlen);
    if (rc)
        return rc;
    /* Below FIT_CAP_MIN a cap is finer than the device's float figures resolve (an absolute
       Delta near 1e-7, a relative delta near 6e-8): it cannot be checked, so it is refused. */
    if (!isnan(o->max_abs_cap) && !(o->max_abs_cap >= FIT_CAP_MIN && o->max_abs_cap <= 1)) {
        snprintf(err, errlen, "--max-abs: %g is out of range (accepted: %g <= cap <= 1)", o->max_abs_cap, FIT_CAP_MIN);
        return EXIT_USAGE;
    }
    if (!isnan(o->max_rel_cap) && !(o->max_rel_cap >= FIT_CAP_MIN && o->max_rel_cap <= 1)) {
        snprintf(err, errlen, "--max-rel: %g is out of range (accepted: %g <= cap <= 1)", o->max_rel_cap, FIT_CAP_MIN);
        return EXIT_USAGE;
    }
    if (o->power_m && (o->power_m < 1 || o->power_m > FIT_POWER_M_MAX)) {
        snprintf(err, errlen, "--power: %d is out of range (accepted: 1 <= m <= %d)", o->power_m, FIT_POWER_M_MAX);
        return EXIT_USAGE;
    }
    if (o->power_m && o->model) {
        snprintf(err, errlen, "--power and --family name two families (accepted: one of them)");
        return EXIT_USAGE;
    }
    if (o->objective == FIT_MAX_ABS && !isnan(o->max_abs_cap)) {
        snprintf(err, errlen, "--max-abs caps the figure --objective max_abs minimises (accepted: --max-rel with it)");
        return EXIT_USAGE;
    }
    if (o->objective == FIT_MAX_REL && !isnan(o->max_rel_cap)) {
        snprintf(err, errlen, "--max-rel caps the figure --objective max_rel minimises (accepted: --max-abs with it)");
        return EXIT_USAGE;
    }
    return 0;
}

/* ---- the family at one n ------------------------------------------------------------- */

/* The registry's default spec of model `id`, made into *spec on the first call (*ready). */
static const struct model_spec *default_spec_once(const char *id, struct model_spec *spec, int *ready)
{
    if (!*ready) {
        model_spec_default(models_find(id), spec);
        *ready = 1;
    }
    return spec;
}

/* f = (k(c-1)+1)^2 zeroed past its root is the registry's quad model with a = 0, b = k, so
 * the formula is the header's (kernels/brdf_models.h), evaluated in double. */
static const struct model_spec *family_base(void)
{
    static struct model_spec quad;
    static int ready;
    return default_spec_once("quad", &quad, &ready);
}

static const struct model_spec *reference_base(void)
{
    static struct model_spec phong;
    static int ready;
    return default_spec_once("phong", &phong, &ready);
}

static double family_eval(double c, double n, double k)
{
    struct model_spec m = *family_base();
    m.params[0] = 0.0;
    m.params[1] = k;
    return model_eval_host(&m, c, n);
}

double fit_reference_eval(double c, double n)
{
    return model_eval_host(reference_base(), c, n);
}

struct fit_sides fit_epicentre_sides(double n, double k)
{
    /* g(c) = f/c^n - 1 has one stationary point where base > 0 (d ln g / dc = 2k/base - n/c),
       so its extremes over [c_e, 1] are at c_e, at 1 (g = 0) and at c*. */
    double ce = cos(zone_epicentre_end(n));
    double cand[2] = { ce, n * (k - 1.0) / (k * (n - 2.0)) };
    struct fit_sides s = { 0.0, 0.0 };
    for (int i = 0; i < 2; ++i) {
        double c = cand[i];
        if (!(c >= ce && c <= 1.0))
            continue;   /* NaN (n = 2, k = 1) or outside the zone */
        double g = family_eval(c, n, k) / fit_reference_eval(c, n) - 1.0;
        if (g > s.over) s.over = g;
        if (-g > s.under) s.under = -g;
    }
    return s;
}

double fit_epicentre_max_rel(double n, double k)
{
    struct fit_sides s = fit_epicentre_sides(n, k);
    return fmax(s.over, s.under);
}

struct att_ctx {
    double n, k, sign;
};

static double att_signed(double x, void *p)
{
    const struct att_ctx *a = p;
    double c = fmax(cos(x), 0.0);
    return a->sign * (family_eval(c, a->n, a->k) - fit_reference_eval(c, a->n));
}

struct fit_sides fit_attenuation_sides(double n, double k)
{
    /* The zone (x_e, pi/2] sampled as the device sweep samples it (x_e + w t^2), then each
       side's best sample polished with Brent in double. */
    double xe = zone_epicentre_end(n), w = half_pi - xe;
    double best_v[2] = { -INFINITY, -INFINITY };
    int best_j[2] = { 1, 1 };
    for (int j = 1; j <= FIT_ATT_SAMPLES; ++j) {
        double t = (double)j / FIT_ATT_SAMPLES;
        double c = fmax(cos(xe + w * t * t), 0.0);
        double h = family_eval(c, n, k) - fit_reference_eval(c, n);
        if (h > best_v[0]) { best_v[0] = h; best_j[0] = j; }
        if (-h > best_v[1]) { best_v[1] = -h; best_j[1] = j; }
    }
    double out[2];
    for (int side = 0; side < 2; ++side) {
        int j = best_j[side];
        double tl = (double)(j - 1) / FIT_ATT_SAMPLES, tm = (double)j / FIT_ATT_SAMPLES,
               th = (double)(j < FIT_ATT_SAMPLES ? j + 1 : j) / FIT_ATT_SAMPLES;
        struct att_ctx ctx = { n, k, side == 0 ? 1.0 : -1.0 };
        double x, v;
        refine_maximum(att_signed, &ctx, xe + w * tl * tl, xe + w * tm * tm, xe + w * th * th, &x, &v);
        out[side] = fmax(v, best_v[side]);
    }
    struct fit_sides s = { fmax(out[0], 0.0), fmax(out[1], 0.0) };
    return s;
}

double fit_attenuation_max_abs(double n, double k)
{
    struct fit_sides s = fit_attenuation_sides(n, k);
    return fmax(s.over, s.under);
}

/* ---- monotone root finding in k ---------------------------------------------------------- */

enum side_fn { EPI_OVER, EPI_UNDER, EPI_BALANCE, ATT_OVER, ATT_UNDER };

struct side_ctx {
    double n, target;
    enum side_fn which;
};

static double side_value(double k, void *p)
{
    const struct side_ctx *s = p;
    switch (s->which) {
    case EPI_OVER: return fit_epicentre_sides(s->n, k).over - s->target;
    case EPI_UNDER: return fit_epicentre_sides(s->n, k).under - s->target;
    case EPI_BALANCE: {
        struct fit_sides e = fit_epicentre_sides(s->n, k);
        return e.over - e.under;
    }
    case ATT_OVER: return fit_attenuation_sides(s->n, k).over - s->target;
    case ATT_UNDER: return fit_attenuation_sides(s->n, k).under - s->target;
    }
    return NAN;
}

/* A root of side_value over [lo, hi] where it changes sign (GSL Brent). Returns 0 or -1. */
static int root_in(struct side_ctx *ctx, double lo, double hi, double *root)
{
    return brent_root(side_value, ctx, lo, hi, 1e-15, 4e-16, FIT_ROOT_ITER, root);
}

/* The largest useful k at n: beyond it the quadratic reaches zero inside the epicentre. */
static double k_domain_max(double n) { return 1.0 / (1.0 - cos(zone_epicentre_end(n))); }

int fit_minimax_k(double n, double *k_out, double *max_rel_out)
{
    /* over falls and under grows with k: the minimax is where they meet. */
    struct side_ctx ctx = { n, 0.0, EPI_BALANCE };
    double k;
    if (root_in(&ctx, 0.0, k_domain_max(n), &k))
        return -1;
    *k_out = k;
    *max_rel_out = fit_epicentre_max_rel(n, k);
    return 0;
}

/* {k in [k_min, k_max]: side <= target} for a falling side (over) or a rising one (under):
   one end of the interval. */
static double level_bound(double n, enum side_fn which, double target, double k_lo, double k_hi, int falling)
{
    struct side_ctx ctx = { n, target, which };
    double v_lo = side_value(k_lo, &ctx), v_hi = side_value(k_hi, &ctx);
    if (falling) {
        if (v_lo <= 0) return k_lo;
        if (v_hi > 0) return INFINITY;   /* never low enough: empty */
    } else {
        if (v_hi <= 0) return k_hi;
        if (v_lo > 0) return -INFINITY;  /* empty */
    }
    double r;
    if (root_in(&ctx, k_lo, k_hi, &r))
        return falling ? INFINITY : -INFINITY;
    return r;
}

/* ---- the affine minimax ------------------------------------------------------------------ */

struct feas_ctx {
    const double *n, *lo, *hi;
    long count;
};

/* g(a) = min_i (hi_i - a n_i) - max_i (lo_i - a n_i): concave; a feasible b exists iff g >= 0. */
static double feas_gap(double a, void *p)
{
    const struct feas_ctx *f = p;
    double up = INFINITY, down = -INFINITY;
    for (long i = 0; i < f->count; ++i) {
        up = fmin(up, f->hi[i] - a * f->n[i]);
        down = fmax(down, f->lo[i] - a * f->n[i]);
    }
    return up - down;
}

/* Largest gap over a and the (a, b) there (b in the middle of its feasible range). */
static double feas_best(const struct feas_ctx *f, double *a_out, double *b_out)
{
    long last = f->count - 1;
    double span = f->n[last] - f->n[0];
    double a1 = (f->lo[last] - f->hi[0]) / span, a2 = (f->hi[last] - f->lo[0]) / span;
    if (!(a2 >= a1))
        return -INFINITY;
    double best = -INFINITY;
    int bj = 0;
    double grid[FIT_FEAS_SAMPLES + 1];
    for (int j = 0; j <= FIT_FEAS_SAMPLES; ++j) {
        double a = a1 + (a2 - a1) * j / FIT_FEAS_SAMPLES;
        grid[j] = a;
        double g = feas_gap(a, (void *)f);
        if (g > best) { best = g; bj = j; }
    }
    double a = grid[bj], g = best;
    refine_maximum(feas_gap, (void *)f, grid[bj > 0 ? bj - 1 : 0], grid[bj],
                   grid[bj < FIT_FEAS_SAMPLES ? bj + 1 : bj], &a, &g);
    double up = INFINITY, down = -INFINITY;
    for (long i = 0; i < f->count; ++i) {
        up = fmin(up, f->hi[i] - a * f->n[i]);
        down = fmax(down, f->lo[i] - a * f->n[i]);
    }
    *a_out = a;
    *b_out = 0.5 * (up + down);
    return g;
}

static void affine_figures(const double *n, long count, double a, double b, struct fit_affine *out)
{
    out->a = a;
    out->b = b;
    out->max_rel = out->max_abs = -1;
    for (long i = 0; i < count; ++i) {
        double k = a * n[i] + b;
        double e = fit_epicentre_max_rel(n[i], k), d = fit_attenuation_max_abs(n[i], k);
        if (e > out->max_rel) { out->max_rel = e; out->max_rel_n = n[i]; }
        if (d > out->max_abs) { out->max_abs = d; out->max_abs_n = n[i]; }
    }
}

/* Per-n intervals of k at level t: {k: max delta <= t} intersected with the cap's interval. */
struct level_ctx {
    const double *n;
    long count;
    const double *kstar, *kmax, *cap_lo, *cap_hi;
    double *lo, *hi;
    const struct feas_ctx *feas;
};

static int feasible_at(const struct level_ctx *L, double t, double *a, double *b)
{
    for (long i = 0; i < L->count; ++i) {
        double l = level_bound(L->n[i], EPI_OVER, t, 0.0, L->kstar[i], 1);
        double h = level_bound(L->n[i], EPI_UNDER, t, L->kstar[i], L->kmax[i], 0);
        L->lo[i] = fmax(l, L->cap_lo[i]);
        L->hi[i] = fmin(h, L->cap_hi[i]);
        if (!(L->lo[i] <= L->hi[i]))
            return 0;
    }
    return feas_best(L->feas, a, b) >= 0;
}

int fit_affine_minimax(const double *n, long count, const struct fit_limit *limit, double cap,
                       struct fit_affine *out)
{
    memset(out, 0, sizeof *out);
    out->cap = cap;
    out->a = out->b = out->max_rel = out->max_abs = NAN;
    if (count < 2) {
        snprintf(out->reason, sizeof out->reason, "at least two values of n are needed");
        return -1;
    }
    double *kmax = malloc((size_t)count * sizeof *kmax), *cap_lo = malloc((size_t)count * sizeof *cap_lo),
           *cap_hi = malloc((size_t)count * sizeof *cap_hi), *lo = malloc((size_t)count * sizeof *lo),
           *hi = malloc((size_t)count * sizeof *hi), *kstar = malloc((size_t)count * sizeof *kstar);
    int rc = -1;
    if (!kmax || !cap_lo || !cap_hi || !lo || !hi || !kstar) {
        snprintf(out->reason, sizeof out->reason, "out of memory");
        goto done;
    }
    double floor_t = 0;
    for (long i = 0; i < count; ++i) {
        kmax[i] = k_domain_max(n[i]);
        kstar[i] = limit[i].k;
        floor_t = fmax(floor_t, limit[i].max_rel);
        cap_lo[i] = 0.0;
        cap_hi[i] = kmax[i];
        if (isfinite(cap)) {
            /* The attenuation's f - r falls with k and r - f grows: the cap is an interval. */
            cap_lo[i] = level_bound(n[i], ATT_OVER, cap, 0.0, kmax[i], 1);
            cap_hi[i] = level_bound(n[i], ATT_UNDER, cap, 0.0, kmax[i], 0);
            if (!(cap_lo[i] <= cap_hi[i])) {
                snprintf(out->reason, sizeof out->reason,
                         "no k meets the cap %.6g on the attenuation's max Delta at n = %g", cap, n[i]);
                goto done;
            }
        }
    }
    struct feas_ctx f = { n, lo, hi, count };
    struct level_ctx L = { n, count, kstar, kmax, cap_lo, cap_hi, lo, hi, &f };
    /* Start from the least-squares line through the per-n minimax k: feasible at its own
       objective when there is no cap. */
    double c0, c1, cov00, cov01, cov11, sumsq;
    gsl_fit_linear(n, 1, kstar, 1, (size_t)count, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    struct fit_affine start;
    affine_figures(n, count, c1, c0, &start);
    double t_hi = start.max_rel * (1 + 1e-12) + 1e-15, t_lo = floor_t;
    double a, b, ta, tb;
    /* With a cap the start may break it: widen until feasible (delta <= 1 holds for any k in
       the domain, so t = 1 leaves only the cap). */
    while (!feasible_at(&L, t_hi, &ta, &tb)) {
        if (t_hi >= 1.0) {
            snprintf(out->reason, sizeof out->reason,
                     "no affine k(n) keeps the attenuation's max Delta <= %.6g over the whole range", cap);
            goto done;
        }
        t_hi = fmin(1.0, 2.0 * t_hi);
    }
    a = ta;
    b = tb;
    for (int it = 0; it < FIT_BISECT_ITER && t_hi - t_lo > 1e-13 * t_hi; ++it) {
        double t = 0.5 * (t_lo + t_hi);
        if (feasible_at(&L, t, &ta, &tb)) {
            t_hi = t;
            a = ta;
            b = tb;
        } else {
            t_lo = t;
        }
    }
    affine_figures(n, count, a, b, out);
    out->cap = cap;
    out->feasible = 1;
    rc = 0;
done:
    free(kmax);
    free(cap_lo);
    free(cap_hi);
    free(lo);
    free(hi);
    free(kstar);
    return rc;
}

/* ---- the run: fit, device sweeps, fit.json ---------------------------------------------- */

static const char *const compare_ids[FIT_COMPARE_COUNT] = { "fq2", "fvol", "cq2" };

/* Turns a fitted (a, b) into the registry model text and spec, and sweeps it on the device. */
static int fit_model_finish(struct accuracy_ctx *actx, const struct accuracy_grid *g, struct fit_model *m,
                            const double *n, long count)
{
    char err[512];
    if (!m->fit.feasible)
        return 0;
    snprintf(m->spec_text, sizeof m->spec_text, "quad:a=%.10g,b=%.10g", m->fit.a, m->fit.b);
    if (model_spec_parse(m->spec_text, &m->spec, err, sizeof err)) {
        /* Outside the registry's parameter domain: report, do not sweep. */
        m->fit.feasible = 0;
        snprintf(m->fit.reason, sizeof m->fit.reason, "fitted model is outside the registry's domain: %.200s", err);
        return 0;
    }
    /* The figures belong to the parameters as written (10 significant digits). */
    double cap = m->fit.cap;
    char reason[256];
    memcpy(reason, m->fit.reason, sizeof reason);
    affine_figures(n, count, m->spec.params[0], m->spec.params[1], &m->fit);
    m->fit.cap = cap;
    m->fit.feasible = 1;
    memcpy(m->fit.reason, reason, sizeof reason);
    int rc = accuracy_run(actx, &m->spec, g, &m->sweep);
    if (rc)
        return rc;
    m->have_sweep = 1;
    return 0;
}

void fit_report_free(struct fit_report *r)
{
    free(r->limit);
    r->limit = NULL;
    if (r->main.have_sweep)
        accuracy_result_free(&r->main.sweep);
    if (r->at_fq2_cap.have_sweep)
        accuracy_result_free(&r->at_fq2_cap.sweep);
    for (int i = 0; i < r->compare_count; ++i)
        accuracy_result_free(&r->compare[i]);
    r->main.have_sweep = r->at_fq2_cap.have_sweep = 0;
    r->compare_count = 0;
}

static void fit_verdict(struct fit_report *r)
{
    const struct accuracy_result *fq2 = NULL;
    for (int i = 0; i < r->compare_count; ++i)
        if (strcmp(r->compare[i].model.info->id, "fq2") == 0)
            fq2 = &r->compare[i];
    if (!fq2 || !r->main.have_sweep) {
        snprintf(r->verdict, sizeof r->verdict, "no fitted model to compare (%s)", r->main.fit.reason);
        return;
    }
    const struct accuracy_result *m = &r->main.sweep;
    /* "Not worse" allows the last bits of a tie: both maxima are polished in double. */
    r->beats_fq2_rel = m->epicentre.value < fq2->epicentre.value * (1 - 1e-9);
    r->not_worse_abs = m->attenuation.value <= fq2->attenuation.value * (1 + 1e-9);
    int n = snprintf(r->verdict, sizeof r->verdict,
                     "fit max delta %.4f%% vs fq2 %.4f%% (%s), max Delta %.5f vs fq2 %.5f (%s)",
                     100 * m->epicentre.value, 100 * fq2->epicentre.value,
                     r->beats_fq2_rel ? "better" : "not better", m->attenuation.value, fq2->attenuation.value,
                     r->not_worse_abs ? "not worse" : "worse");
    if (n > 0 && (size_t)n < sizeof r->verdict && r->at_fq2_cap.have_sweep) {
        const struct accuracy_result *c = &r->at_fq2_cap.sweep;
        int beats = c->epicentre.value < fq2->epicentre.value * (1 - 1e-9);
        snprintf(r->verdict + n, sizeof r->verdict - (size_t)n,
                 "; with max Delta capped at fq2's the family's best is %.4f%% (%s fq2); "
                 "the family's limit over the range is %.4f%%",
                 100 * c->epicentre.value, beats ? "better than" : "no better than", 100 * r->limit_max);
    }
}

int fit_wants_family(const struct fit_options *o)
{
    return o->model || o->power_m || o->objective != FIT_MAX_REL || !isnan(o->max_rel_cap);
}

/* The start of fit_run and fit_family_run: the report r (of size bytes) zeroed, its options
 * and grid set, the clock read; 0, or EXIT_USAGE with the message on stderr when the options
 * or the sweep grid they give do not hold on this device. */
int fit_start(struct cl_session *s, const struct fit_options *o, void *r, size_t size,
              struct fit_options *opt, struct accuracy_grid *g, double *t0)
{
    memset(r, 0, size);
    *opt = *o;
    *t0 = wall_seconds();
    char err[1024];
    if (fit_options_check(o, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        return EXIT_USAGE;
    }
    *g = (struct accuracy_grid){ o->n_min, o->n_max, o->n_step, o->samples };
    if (accuracy_grid_check(g, s, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        return EXIT_USAGE;
    }
    return 0;
}

int fit_run(struct cl_session *s, const struct fit_options *o, struct fit_report *report)
{
    char err[1024];
    struct fit_report local;
    struct fit_report *r = report ? report : &local;
    double t0;
    if (fit_start(s, o, r, sizeof *r, &r->opt, &r->grid, &t0))
        return EXIT_USAGE;
    struct accuracy_grid g = r->grid;
    r->n_count = accuracy_grid_count(&g);
    int rc = 0;
    double *n = malloc((size_t)r->n_count * sizeof *n);
    r->limit = malloc((size_t)r->n_count * sizeof *r->limit);
    struct accuracy_ctx actx;
    memset(&actx, 0, sizeof actx);
    if (!n || !r->limit) {
        fprintf(stderr, "brdfbench fit: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    r->limit_max = -1;
    for (long i = 0; i < r->n_count; ++i) {
        n[i] = accuracy_grid_n(&g, i);   /* the n the device sees */
        r->limit[i].n = n[i];
        if (fit_minimax_k(n[i], &r->limit[i].k, &r->limit[i].max_rel)) {
            fprintf(stderr, "brdfbench fit: the per-n minimax failed at n = %g\n", n[i]);
            rc = EXIT_RUNTIME;
            goto done;
        }
        if (r->limit[i].max_rel > r->limit_max) {
            r->limit_max = r->limit[i].max_rel;
            r->limit_max_n = n[i];
        }
    }
    fit_affine_minimax(n, r->n_count, r->limit, o->max_abs_cap, &r->main.fit);

    rc = accuracy_open(&actx, s, "");
    if (rc)
        goto done;
    for (int i = 0; i < FIT_COMPARE_COUNT; ++i) {
        struct model_spec spec;
        model_spec_default(models_find(compare_ids[i]), &spec);
        rc = accuracy_run(&actx, &spec, &g, &r->compare[i]);
        if (rc)
            goto done;
        r->compare_count = i + 1;
    }
    /* fq2's own attenuation max Delta (compare[0]) as the cap of the second fit. */
    fit_affine_minimax(n, r->n_count, r->limit, r->compare[0].attenuation.value, &r->at_fq2_cap.fit);
    rc = fit_model_finish(&actx, &g, &r->main, n, r->n_count);
    if (!rc)
        rc = fit_model_finish(&actx, &g, &r->at_fq2_cap, n, r->n_count);
    if (rc)
        goto done;
    if (r->main.have_sweep && r->at_fq2_cap.have_sweep && !isfinite(o->max_abs_cap)) {
        double lo = r->compare[0].attenuation.value, hi = r->main.sweep.attenuation.value;
        for (int j = 0; j < FIT_TRADEOFF_POINTS && hi > lo; ++j) {
            double cap = lo + (hi - lo) * j / (FIT_TRADEOFF_POINTS - 1);
            if (fit_affine_minimax(n, r->n_count, r->limit, cap, &r->tradeoff[r->tradeoff_count]) == 0)
                r->tradeoff_count++;
        }
    }
    fit_verdict(r);
    r->seconds = wall_seconds() - t0;
    if (o->io.out_dir) {
        char path[4200];
        path_join(path, sizeof path, o->io.out_dir, "fit.json");
        if (fit_write_json(path, r, s, actx.build_options, err, sizeof err)) {
            fprintf(stderr, "brdfbench fit: %s\n", err);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    if (!o->io.quiet)
        fit_print(stdout, r);
    /* A cap that no member of the family meets: fit.json says why, and the exit says so. */
    if (!r->main.fit.feasible) {
        fprintf(stderr, "brdfbench fit: infeasible: %s\n", r->main.fit.reason);
        rc = EXIT_GATE_FAIL;
    }
done:
    accuracy_close(&actx);
    free(n);
    if (!report)
        fit_report_free(r);
    return rc;
}

/* ---- Beaudoin and Guardado's A, by their own criterion -------------------------------------- */

#define BG_GRID 2048
#define BG_BISECT_ITER 100

struct bg_ctx {
    double n, a, sign;
    int m;
};

/* sign (f - c^n) at c, f = max(0, A c + 1 - A)^m (the header's power family, in double). */
static double bg_signed(double c, void *p)
{
    const struct bg_ctx *b = p;
    double base = fmax(b->a * (c - 1.0) + 1.0, 0.0), f = 1.0;
    for (int i = 0; i < b->m; ++i)
        f *= base;
    return b->sign * (f - fit_reference_eval(c, b->n));
}

/* The largest f - c^n and c^n - f over c in [0, 1]: a grid dense near c = 1 (where the lobe
   lives at large n), each side's best sample polished with Brent. */
static void bg_sides(double n, double a, int m, double *over, double *under)
{
    double best[2] = { 0.0, 0.0 };
    int bj[2] = { 0, 0 };
    struct bg_ctx ctx = { n, a, 1.0, m };
    for (int j = 0; j <= BG_GRID; ++j) {
        double t = 1.0 - (double)j / BG_GRID, c = 1.0 - t * t * t;
        double h = bg_signed(c, &ctx);
        if (h > best[0]) { best[0] = h; bj[0] = j; }
        if (-h > best[1]) { best[1] = -h; bj[1] = j; }
    }
    for (int side = 0; side < 2; ++side) {
        int j = bj[side];
        if (best[side] <= 0)
            continue;
        double t0 = 1.0 - (double)(j > 0 ? j - 1 : 0) / BG_GRID, t1 = 1.0 - (double)j / BG_GRID,
               t2 = 1.0 - (double)(j < BG_GRID ? j + 1 : j) / BG_GRID;
        ctx.sign = side == 0 ? 1.0 : -1.0;
        double x, v;
        if (refine_maximum(bg_signed, &ctx, 1.0 - t0 * t0 * t0, 1.0 - t1 * t1 * t1, 1.0 - t2 * t2 * t2, &x, &v) == 0)
            best[side] = fmax(best[side], v);
    }
    *over = best[0];
    *under = best[1];
}

int fit_bg_exact_a(double n, int m, double *a_out, double *max_abs_out)
{
    /* A larger A lowers f everywhere on [0, 1): the over side falls and the under side grows,
       so their balance is a bisection on A (equivalent to one on their k, which A grows with). */
    if (!(n > 0) || m < 1)
        return -1;
    double lo = 0.0, hi = fmax(n, 1.0), over, under;
    bg_sides(n, hi, m, &over, &under);
    if (over > under)
        return -1;
    for (int it = 0; it < BG_BISECT_ITER && hi - lo > 1e-14 * hi; ++it) {
        double a = 0.5 * (lo + hi);
        bg_sides(n, a, m, &over, &under);
        if (over > under)
            lo = a;
        else
            hi = a;
    }
    *a_out = 0.5 * (lo + hi);
    bg_sides(n, *a_out, m, &over, &under);
    *max_abs_out = fmax(over, under);
    return 0;
}

