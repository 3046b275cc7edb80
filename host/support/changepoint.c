/* changepoint.c - binary segmentation of a series of runs with compare's rule (see
 * changepoint.h). */
#include "changepoint.h"

#include <gsl/gsl_cdf.h>

#include <math.h>
#include <stdlib.h>

#include "ranktest.h"
#include "stats.h"

void cp_defaults(struct cp_settings *s)
{
    s->alpha = 0.05;
    s->min_change = 0.10;   /* compare's CMP_DEFAULT_THRESHOLD */
    s->min_seg = 2;
}

/* The logs of runs [a, b)'s positive finite values into out; returns the count. */
static int pool(const struct cp_sample *runs, int a, int b, double *out)
{
    int n = 0;
    for (int r = a; r < b; ++r)
        for (int i = 0; runs[r].v && i < runs[r].n; ++i)
            if (isfinite(runs[r].v[i]) && runs[r].v[i] > 0)
                out[n++] = log(runs[r].v[i]);
    return n;
}

static int has_values(const struct cp_sample *s)
{
    for (int i = 0; s->v && i < s->n; ++i)
        if (isfinite(s->v[i]) && s->v[i] > 0)
            return 1;
    return 0;
}

/* The median of the logs of a run's positive finite values (NAN: none). tmp: room for n. */
static double run_level(const struct cp_sample *s, double *tmp)
{
    int n = 0;
    for (int i = 0; s->v && i < s->n; ++i)
        if (isfinite(s->v[i]) && s->v[i] > 0)
            tmp[n++] = log(s->v[i]);
    if (n == 0)
        return NAN;
    qsort(tmp, (size_t)n, sizeof *tmp, stats_cmp_double);
    return stats_median_sorted(tmp, (size_t)n);
}

struct cp_state {
    const struct cp_sample *runs;
    int T, last;                 /* last: the latest run with values */
    const struct cp_settings *s;
    double *before, *after;      /* room for every value of the series */
    double *level;               /* each run's level: the median of its logs (NAN: no values) */
    double run_sd;               /* the spread of the levels from run to run (run_spread) */
    int run_df;
    struct cp_change *out;
    int n;
};

struct cp_split {
    int k;
    double p;   /* Bonferroni-adjusted */
};

static int cmp_split(const void *x, const void *y)
{
    const struct cp_split *a = x, *b = y;
    return (a->p > b->p) - (a->p < b->p);
}

/* Whether a split at k of [a, b) leaves each side enough runs with values. */
static int split_allowed(const struct cp_state *st, int a, int b, int k)
{
    if (!has_values(&st->runs[k]))
        return 0;   /* a split falls just before a run that was measured */
    int nl = 0, nr = 0;
    for (int r = a; r < k; ++r)
        nl += has_values(&st->runs[r]);
    for (int r = k; r < b; ++r)
        nr += has_values(&st->runs[r]);
    /* a side holds min_seg runs, except a last segment that ends with the latest run */
    int right_min = b > st->last ? 1 : st->s->min_seg;
    return nl >= st->s->min_seg && nr >= right_min;
}

/* The run-level test of a split at k of [a, b): the difference of the mean levels of the runs
 * after and before, over the runs' own spread. The repetitions of one run are not independent
 * of the other runs' (a run drifts as a whole), so a shift the pooled repetitions call
 * significant must also stand out from how much whole runs differ. The spread is the whole
 * series' (st->run_sd): from its successive differences, which a step moves only once.
 * Student's t with st->run_df degrees of freedom; two-sided p. */
static double run_level_p(const struct cp_state *st, int a, int b, int k)
{
    double sa = 0, sb = 0;
    int na = 0, nb = 0;
    for (int r = a; r < b; ++r) {
        double l = st->level[r];
        if (!isfinite(l))
            continue;
        if (r < k)
            sa += l, ++na;
        else
            sb += l, ++nb;
    }
    if (na < 1 || nb < 1)
        return 1;
    double d = fabs(sb / nb - sa / na), se = st->run_sd * sqrt(1.0 / na + 1.0 / nb);
    if (!(se > 0))
        return d > 0 ? 0 : 1;   /* runs without spread: any shift stands out */
    return fmin(1.0, 2 * gsl_cdf_tdist_Q(d / se, st->run_df));
}

/* The spread of the runs' levels: the median absolute successive difference over
 * 0.6745 sqrt(2) (for independent levels of spread s the differences have spread s sqrt(2),
 * and their median absolute value is 0.6745 times that), robust to a few steps. */
static void run_spread(struct cp_state *st, double *tmp)
{
    int n = 0;
    double prev = NAN;
    for (int r = 0; r < st->T; ++r) {
        if (!isfinite(st->level[r]))
            continue;
        if (isfinite(prev))
            tmp[n++] = fabs(st->level[r] - prev);
        prev = st->level[r];
    }
    st->run_df = n > 1 ? n - 1 : 1;
    if (n == 0) {
        st->run_sd = 0;
        return;
    }
    qsort(tmp, (size_t)n, sizeof *tmp, stats_cmp_double);
    double med = stats_median_sorted(tmp, (size_t)n);
    st->run_sd = med / (0.6745 * sqrt(2.0));
}

/* Searches [a, b) and, when a split passes, both halves. Returns 0 or -1 (no memory).
 * Every split's rank test first (cheap); the Hodges-Lehmann shift (every pair of values) only
 * for the splits in order of p while p < alpha, until the ones of the smallest p that pass are
 * known: the same choice as testing every split fully, without the pairs of the others. */
static int segment(struct cp_state *st, int a, int b)
{
    int m = 0;
    for (int k = a + 1; k < b; ++k)
        m += split_allowed(st, a, b, k);
    if (m == 0)
        return 0;
    struct cp_split *sp = malloc((size_t)m * sizeof *sp);
    if (!sp)
        return -1;
    int n = 0;
    for (int k = a + 1; k < b; ++k) {
        if (!split_allowed(st, a, b, k))
            continue;
        int ny = pool(st->runs, a, k, st->before), nx = pool(st->runs, k, b, st->after);
        struct ranktest_result t;
        if (ranktest_mann_whitney(st->after, nx, st->before, ny, &t) != 0) {
            free(sp);
            return -1;
        }
        sp[n].k = k;
        /* both tests at level alpha / m: the repetitions', and the runs' levels' */
        sp[n++].p = fmin(1.0, fmax(t.p, run_level_p(st, a, b, k)) * m);
    }
    qsort(sp, (size_t)n, sizeof *sp, cmp_split);
    int best = -1;
    double best_p = INFINITY, best_shift = 0, best_lo = NAN, best_hi = NAN;
    for (int i = 0; i < n && sp[i].p < st->s->alpha; ++i) {
        if (best >= 0 && sp[i].p > best_p)
            break;   /* a larger p can no longer be chosen */
        int k = sp[i].k;
        int ny = pool(st->runs, a, k, st->before), nx = pool(st->runs, k, b, st->after);
        double est, lo, hi;
        if (ranktest_shift_ci(st->after, nx, st->before, ny, st->s->alpha / m, &est, &lo, &hi) != 0) {
            free(sp);
            return -1;
        }
        if (!(fabs(est) > log1p(st->s->min_change)))
            continue;
        if (best < 0 || fabs(est) > fabs(best_shift)) {
            best = k;
            best_p = sp[i].p;
            best_shift = est;
            best_lo = lo;
            best_hi = hi;
        }
    }
    free(sp);
    if (best < 0)
        return 0;
    if (segment(st, a, best))
        return -1;
    if (st->n < CP_MAX_CHANGES) {
        struct cp_change *c = &st->out[st->n++];
        c->at = best;
        c->ratio = exp(best_shift);
        c->lo = exp(best_lo);
        c->hi = exp(best_hi);
        c->p = best_p;
        c->m = m;
    }
    return segment(st, best, b);
}

int cp_find(const struct cp_sample *runs, int T, const struct cp_settings *s, struct cp_change *out)
{
    int total = 0, last = -1;
    for (int r = 0; r < T; ++r) {
        total += runs[r].v ? runs[r].n : 0;
        if (has_values(&runs[r]))
            last = r;
    }
    struct cp_state st = { .runs = runs, .T = T, .last = last, .s = s, .out = out, .n = 0 };
    st.before = malloc((size_t)(total > 0 ? total : 1) * sizeof(double));
    st.after = malloc((size_t)(total > 0 ? total : 1) * sizeof(double));
    st.level = malloc((size_t)(T > 0 ? T : 1) * sizeof(double));
    for (int r = 0; st.level && st.before && r < T; ++r)
        st.level[r] = run_level(&runs[r], st.before);
    if (st.level && st.before)
        run_spread(&st, st.before);
    int rc = st.before && st.after && st.level ? segment(&st, 0, T) : -1;
    /* each change's ratio and interval between the segments on either side of it (the search
       found it against a wider segment, which may hold other changes) */
    for (int i = 0; !rc && i < st.n; ++i) {
        int a = i > 0 ? out[i - 1].at : 0, b = i + 1 < st.n ? out[i + 1].at : T;
        int ny = pool(runs, a, out[i].at, st.before), nx = pool(runs, out[i].at, b, st.after);
        struct ranktest_result t;
        double est, lo, hi;
        if (ranktest_mann_whitney(st.after, nx, st.before, ny, &t) != 0 ||
            ranktest_shift_ci(st.after, nx, st.before, ny, s->alpha / out[i].m, &est, &lo, &hi) != 0) {
            rc = -1;
            break;
        }
        out[i].ratio = exp(est);
        out[i].lo = exp(lo);
        out[i].hi = exp(hi);
        out[i].p = fmin(1.0, fmax(t.p, run_level_p(&st, a, b, out[i].at)) * out[i].m);
    }
    free(st.before);
    free(st.after);
    free(st.level);
    return rc ? -1 : st.n;   /* segment recurses left first: the changes come in order of at */
}

double cp_latest_ratio(const struct cp_change *c, int n) { return n > 0 ? c[n - 1].ratio : NAN; }
