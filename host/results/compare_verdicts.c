/* compare_verdicts.c - compare's verdicts: whether two runs' figures agree, and the rows that
 * changed (see compare.h). */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"
#include "compare_check.h"
#include "jsonr.h"
#include "outdir.h"
#include "ranktest.h"
#include "mdbuf.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- verdicts -------------------------------------------------------------------------- */

static int same_4_digits(double a, double b)
{
    char x[40], y[40];
    snprintf(x, sizeof x, "%.3e", a);
    snprintf(y, sizeof y, "%.3e", b);
    return strcmp(x, y) == 0;
}

/* The logarithms of a sample's positive finite values (the rest NAN): malloc'd. */
static double *logs_of(const double *v, int n)
{
    double *l = malloc((size_t)(n > 0 ? n : 1) * sizeof *l);
    for (int i = 0; l && i < n; ++i)
        l[i] = isfinite(v[i]) && v[i] > 0 ? log(v[i]) : NAN;
    return l;
}

/* A speed cell's test against the baseline's: ratio, interval and p; the verdict follows once
   every row's p is known (Holm). */
static void judge_speed(const struct compare_set *set, const struct cmp_cell *b, struct cmp_cell *c, int same_device)
{
    const double *x, *y;
    int nx, ny;
    /* normalised rates compare a device with itself (the drift of the machine cancels); two
       devices are compared on what they deliver */
    if (!set->absolute && same_device && b->norm && c->norm && b->nnorm > 0 && c->nnorm > 0 &&
        b->norm_cpu == c->norm_cpu) {
        c->basis = c->norm_cpu ? CMP_BASIS_CPU : CMP_BASIS_NORMALISED;
        x = c->norm, nx = c->nnorm, y = b->norm, ny = b->nnorm;
    } else if (b->nreps > 0 && c->nreps > 0) {
        c->basis = CMP_BASIS_ABSOLUTE;
        x = c->reps, nx = c->nreps, y = b->reps, ny = b->nreps;
    } else {
        c->basis = isfinite(b->lo) && isfinite(b->hi) && isfinite(c->lo) && isfinite(c->hi) ? CMP_BASIS_RANGES
                                                                                               : CMP_BASIS_NONE;
        c->verdict = c->basis == CMP_BASIS_NONE ? CMP_V_UNDECIDED
                     : c->hi < b->lo ? CMP_V_SLOWER : c->lo > b->hi ? CMP_V_FASTER : CMP_V_SAME;
        return;
    }
    struct ranktest_result t;
    double *lx = logs_of(x, nx), *ly = logs_of(y, ny), est, lo, hi;
    if (lx && ly && ranktest_mann_whitney(lx, nx, ly, ny, &t) == 0 &&
        ranktest_shift_ci(lx, nx, ly, ny, set->alpha, &est, &lo, &hi) == 0) {
        c->p = c->p_adj = t.p;
        c->ratio = exp(est);
        c->ci_lo = exp(lo);
        c->ci_hi = exp(hi);
        c->verdict = t.p_min > set->alpha ? CMP_V_UNDECIDED : CMP_V_SAME;   /* refined in decide_speed */
        if (t.u > 0.5 * nx * ny)
            c->verdict = -c->verdict;   /* marks "x above y" until decide_speed */
    } else {
        c->verdict = CMP_V_UNDECIDED;
    }
    free(lx);
    free(ly);
}

/* The rule itself, once: faster or slower when p is below alpha and the ratio is beyond the
   band 1 +- threshold; noisy when not and the interval is wider than the band; same otherwise. */
static int speed_verdict(int above, double p, double ratio, double ci_lo, double ci_hi, double alpha, double threshold)
{
    double band = log1p(threshold);
    if (p < alpha && fabs(log(ratio)) > band)
        return above ? CMP_V_FASTER : CMP_V_SLOWER;
    if (!(log(ci_hi) - log(ci_lo) <= 2 * band))
        return CMP_V_NOISY;
    return CMP_V_SAME;
}

/* The verdict of a tested speed cell, from its (adjusted) p, ratio and interval. */
static void decide_speed(const struct compare_set *set, struct cmp_cell *c)
{
    int above = c->verdict < 0;
    int v = above ? -c->verdict : c->verdict;
    if (v != CMP_V_SAME) {
        c->verdict = v;
        return;
    }
    c->verdict = speed_verdict(above, c->p_adj, c->ratio, c->ci_lo, c->ci_hi, set->alpha, set->threshold);
}

int compare_speed_rule(const double *x, int nx, const double *y, int ny, double alpha, double threshold,
                       struct compare_speed *out)
{
    struct ranktest_result t;
    double *lx = logs_of(x, nx), *ly = logs_of(y, ny), est, lo, hi;
    int rc = -1;
    out->verdict = CMP_V_UNDECIDED;
    out->ratio = out->ci_lo = out->ci_hi = out->p = NAN;
    if (lx && ly && ranktest_mann_whitney(lx, nx, ly, ny, &t) == 0 &&
        ranktest_shift_ci(lx, nx, ly, ny, alpha, &est, &lo, &hi) == 0) {
        out->p = t.p;
        out->ratio = exp(est);
        out->ci_lo = exp(lo);
        out->ci_hi = exp(hi);
        out->verdict = t.p_min > alpha ? CMP_V_UNDECIDED
                                       : speed_verdict(t.u > 0.5 * nx * ny, t.p, out->ratio, out->ci_lo, out->ci_hi,
                                                       alpha, threshold);
        rc = 0;
    }
    free(lx);
    free(ly);
    return rc;
}

static void judge(const struct compare_set *set, const struct cmp_row *row, const struct cmp_cell *b,
                  struct cmp_cell *c, int same_device)
{
    c->ratio = c->change = c->p = c->p_adj = c->ci_lo = c->ci_hi = NAN;
    c->basis = CMP_BASIS_NONE;
    if (!b->present || !c->present) {
        c->verdict = CMP_V_MISSING;
        return;
    }
    if (!b->ok || !c->ok) {
        c->verdict = CMP_V_FAILED;
        return;
    }
    c->change = c->value - b->value;
    c->ratio = b->value != 0 ? c->value / b->value : NAN;
    if (row->sense == CMP_SPEED) {
        judge_speed(set, b, c, same_device);
        return;
    }
    if (same_4_digits(b->value, c->value))
        c->verdict = CMP_V_UNCHANGED;
    else if (row->sense == CMP_ERROR)
        c->verdict = c->value < b->value ? CMP_V_BETTER : CMP_V_WORSE;
    else if (row->sense == CMP_SCORE)
        c->verdict = c->value > b->value ? CMP_V_BETTER : CMP_V_WORSE;
    else
        c->verdict = CMP_V_CHANGED;
}

static int cmp_p(const void *a, const void *b)
{
    double x = (*(struct cmp_cell *const *)a)->p, y = (*(struct cmp_cell *const *)b)->p;
    return (x > y) - (x < y);
}

/* Holm's step-down adjustment over run k's tested speed cells: the i-th smallest p (from 0)
   times (m - i), made monotone, capped at 1. */
static void holm_adjust(struct compare_set *set, int k)
{
    struct cmp_cell **t = malloc((size_t)(set->nrows > 0 ? set->nrows : 1) * sizeof *t);
    if (!t)
        return;
    int m = 0;
    for (int i = 0; i < set->nrows; ++i) {
        struct cmp_cell *c = &set->rows[i].cell[k];
        if (set->rows[i].sense == CMP_SPEED && isfinite(c->p))
            t[m++] = c;
    }
    qsort(t, (size_t)m, sizeof *t, cmp_p);
    double run_max = 0;
    for (int i = 0; i < m; ++i) {
        double adj = fmin(1.0, t[i]->p * (double)(m - i));
        run_max = fmax(run_max, adj);
        t[i]->p_adj = run_max;
    }
    free(t);
}

void compare_evaluate(struct compare_set *set, double alpha)
{
    set->alpha = alpha;
    int same_device[CMP_MAX_RUNS] = { 0 };
    for (int k = 1; k < set->nruns; ++k) {
        const char *a = compare_context(set, 0, "device"), *b = compare_context(set, k, "device");
        same_device[k] = !set->by_device && (!a || !b || strcmp(a, b) == 0);
    }
    set->rows_in_all = set->rows_in_some = 0;
    for (int i = 0; i < set->nrows; ++i) {
        struct cmp_row *r = &set->rows[i];
        r->in_all = 1;
        for (int k = 0; k < set->nruns; ++k)
            r->in_all &= r->cell[k].present;
        if (r->in_all)
            set->rows_in_all++;
        else
            set->rows_in_some++;
        r->cell[0].ratio = r->cell[0].ok ? 1.0 : NAN;
        r->cell[0].change = r->cell[0].ok ? 0.0 : NAN;
        r->cell[0].p = r->cell[0].p_adj = r->cell[0].ci_lo = r->cell[0].ci_hi = NAN;
        r->cell[0].verdict = r->cell[0].present ? CMP_V_NONE : CMP_V_MISSING;
        for (int k = 1; k < set->nruns; ++k)
            judge(set, r, &r->cell[0], &r->cell[k], same_device[k]);
    }
    for (int k = 1; k < set->nruns; ++k) {
        if (set->holm)
            holm_adjust(set, k);
        for (int i = 0; i < set->nrows; ++i) {
            struct cmp_cell *c = &set->rows[i].cell[k];
            if (set->rows[i].sense == CMP_SPEED && (c->basis == CMP_BASIS_NORMALISED || c->basis == CMP_BASIS_CPU ||
                                                    c->basis == CMP_BASIS_ABSOLUTE))
                decide_speed(set, c);
        }
    }
}

int compare_few_reps(const struct compare_set *set)
{
    int few = 0;
    for (int i = 0; i < set->nrows; ++i)
        for (int k = 0; k < set->nruns; ++k) {
            const struct cmp_cell *c = &set->rows[i].cell[k];
            int n = c->nnorm > 0 ? c->nnorm : c->nreps;
            if (set->rows[i].sense == CMP_SPEED && c->present && c->ok && n > 0 && n < set->min_reps)
                few = few == 0 || n < few ? n : few;
        }
    return few;
}

/* A row the baseline measured that run k lost: missing from it, or failed there (status failed,
   device_disagrees, a figure not finite). A row that was not ok in the baseline either, or that
   is new in run k, is no loss. Returns what happened, or NULL. */
static const char *lost_in(const struct cmp_row *r, int k)
{
    const struct cmp_cell *b = &r->cell[0], *c = &r->cell[k];
    if (!b->present || !b->ok)
        return NULL;
    if (!c->present)
        return "missing from this run";
    return c->ok ? NULL : c->reason;
}

int compare_failures(const struct compare_set *set, double slower_pct, int less_accurate, char **out)
{
    int count = 0;
    size_t len = 0;
    if (out)
        *out = NULL;
    for (int i = 0; i < set->nrows; ++i) {
        const struct cmp_row *r = &set->rows[i];
        /* with confirm, a speed fails only when every run after the baseline finds it slower:
           the first one's rows are named, with the others' ratios */
        int slower_all = set->nruns > 1;
        for (int k = 1; k < set->nruns; ++k) {
            const struct cmp_cell *c = &r->cell[k];
            slower_all &= r->sense == CMP_SPEED && c->verdict == CMP_V_SLOWER && c->ratio < 1.0 - slower_pct / 100.0;
        }
        for (int k = 1; k < set->nruns; ++k) {
            const struct cmp_cell *c = &r->cell[k];
            const char *dev = *r->device ? r->device : "";
            int slower = r->sense == CMP_SPEED && c->verdict == CMP_V_SLOWER && c->ratio < 1.0 - slower_pct / 100.0;
            if (slower_pct >= 0 && slower && (!set->confirm || (k == 1 && slower_all))) {
                ++count;
                str_appendf(out, &len, "%s: %s %s%s%s %s: %.3gx the baseline (p = %.2g)", set->run[k].name,
                       cmp_kind_name(r->kind), dev, *dev ? " | " : "", r->key, r->metric, c->ratio,
                       set->holm ? c->p_adj : c->p);
                for (int q = 2; set->confirm && q < set->nruns; ++q)
                    str_appendf(out, &len, "; confirmed by %s: %.3gx", set->run[q].name, r->cell[q].ratio);
                str_appendf(out, &len, "\n");
            }
            const char *lost = lost_in(r, k);
            int watched = (slower_pct >= 0 && r->sense == CMP_SPEED) ||
                          (less_accurate && (r->sense == CMP_ERROR || r->sense == CMP_SCORE));
            if (lost && watched) {
                ++count;
                str_appendf(out, &len, "%s: %s %s%s%s %s: %s (the baseline has %.4g)\n", set->run[k].name,
                       cmp_kind_name(r->kind), dev, *dev ? " | " : "", r->key, r->metric, lost, r->cell[0].value);
            }
            if (less_accurate && (r->sense == CMP_ERROR || r->sense == CMP_SCORE) && c->verdict == CMP_V_WORSE) {
                ++count;
                str_appendf(out, &len, "%s: %s %s%s%s %s: %.4g against %.4g (%+.3g)\n", set->run[k].name,
                       cmp_kind_name(r->kind), dev, *dev ? " | " : "", r->key, r->metric, c->value,
                       r->cell[0].value, c->change);
            }
        }
    }
    return count;
}

void compare_free(struct compare_set *set)
{
    for (int i = 0; i < set->nrows; ++i)
        for (int k = 0; k < CMP_MAX_RUNS; ++k)
            free(set->rows[i].cell[k].reps), free(set->rows[i].cell[k].norm);
    free(set->rows);
    free(set->index);
    set->index = NULL;
    set->index_cap = set->index_n = 0;
    set->rows = NULL;
    set->nrows = set->cap = 0;
}
