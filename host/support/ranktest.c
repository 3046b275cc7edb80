/* ranktest.c - the Mann-Whitney test (see ranktest.h). Ranks are doubled so that mid-ranks
 * are integers, and the exact null distribution of the rank sum of x is counted over all
 * C(N, nx) draws from the pooled ranks. Counts are kept in doubles: C(40, 20) < 2^53. */
#include "ranktest.h"
#include "stats.h"

#include <gsl/gsl_cdf.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct rt_item {
    double v;
    int from_x;
};

static int rt_cmp(const void *a, const void *b)
{
    double x = ((const struct rt_item *)a)->v, y = ((const struct rt_item *)b)->v;
    return (x > y) - (x < y);
}

/* Two-sided p from the exact distribution of the doubled rank sum of m draws among the
 * doubled ranks r[0..N): P(|S - E| >= dev). Also the smallest such p (at the largest |S - E|). */
static int rt_exact(const long *r, int N, int m, double dev2, double *p, double *p_min)
{
    long smax = 0;
    for (int i = 0; i < N; ++i)
        smax += r[i];
    /* ways[k][s]: the number of k-subsets of the ranks seen so far with doubled sum s */
    size_t cols = (size_t)smax + 1;
    double *ways = calloc((size_t)(m + 1) * cols, sizeof *ways);
    if (!ways)
        return -1;
    ways[0] = 1;
    for (int i = 0; i < N; ++i)
        for (int k = (i + 1 < m ? i + 1 : m); k >= 1; --k)
            for (long s = smax; s >= r[i]; --s)
                ways[(size_t)k * cols + (size_t)s] += ways[(size_t)(k - 1) * cols + (size_t)(s - r[i])];
    const double *row = ways + (size_t)m * cols;
    double total = 0, mean2 = 0;
    for (long s = 0; s <= smax; ++s) {
        total += row[s];
        mean2 += row[s] * (double)s;
    }
    mean2 /= total;   /* = m (N + 1), doubled */
    double tail = 0, far = 0, far_count = 0;
    for (long s = 0; s <= smax; ++s) {
        if (row[s] == 0)
            continue;
        double d = fabs((double)s - mean2);
        if (d >= dev2 - 1e-9)
            tail += row[s];
        if (d > far + 1e-9) {
            far = d;
            far_count = row[s];
        } else if (fabs(d - far) <= 1e-9) {
            far_count += row[s];
        }
    }
    *p = fmin(1.0, tail / total);
    *p_min = fmin(1.0, far_count / total);
    free(ways);
    return 0;
}

int ranktest_mann_whitney(const double *x, int nx, const double *y, int ny, struct ranktest_result *out)
{
    memset(out, 0, sizeof *out);
    int m = 0, n = 0;
    struct rt_item *it = malloc(((size_t)(nx > 0 ? nx : 0) + (size_t)(ny > 0 ? ny : 0) + 1) * sizeof *it);
    if (!it)
        return -1;
    for (int i = 0; i < nx; ++i)
        if (isfinite(x[i]))
            it[m++] = (struct rt_item){ x[i], 1 };
    for (int j = 0; j < ny; ++j)
        if (isfinite(y[j]))
            it[m + n++] = (struct rt_item){ y[j], 0 };
    if (m == 0 || n == 0) {
        free(it);
        return -1;
    }
    int N = m + n;
    qsort(it, (size_t)N, sizeof *it, rt_cmp);
    long *r2 = malloc((size_t)N * sizeof *r2);   /* doubled mid-ranks, in sorted order */
    if (!r2) {
        free(it);
        return -1;
    }
    long w2 = 0;           /* doubled rank sum of x */
    double tie_term = 0;   /* sum of t^3 - t over groups of ties */
    for (int i = 0; i < N;) {
        int j = i;
        while (j + 1 < N && it[j + 1].v == it[i].v)
            ++j;
        long mid2 = (long)(i + 1) + (long)(j + 1);   /* 2 x mid-rank of ranks i+1..j+1 */
        for (int k = i; k <= j; ++k) {
            r2[k] = mid2;
            if (it[k].from_x)
                w2 += mid2;
        }
        double t = j - i + 1;
        tie_term += t * t * t - t;
        i = j + 1;
    }
    out->u = 0.5 * (double)w2 - 0.5 * m * (m + 1.0);
    double mean_u = 0.5 * m * n;
    if (N <= RANKTEST_EXACT_MAX) {
        /* |U - E U| = |W - E W|: the same deviation on the doubled rank sum */
        double dev2 = 2.0 * fabs(out->u - mean_u);
        int rc = rt_exact(r2, N, m, dev2, &out->p, &out->p_min);
        out->exact = 1;
        free(r2);
        free(it);
        return rc;
    }
    double var = m * (double)n / 12.0 * ((N + 1.0) - tie_term / ((double)N * (N - 1.0)));
    if (var <= 0) {
        out->p = out->p_min = 1.0;   /* every value tied: nothing tells the sides apart */
    } else {
        double z = fmax(0.0, fabs(out->u - mean_u) - 0.5) / sqrt(var);
        out->p = fmin(1.0, erfc(z / sqrt(2.0)));
        out->p_min = fmin(1.0, erfc(fmax(0.0, mean_u - 0.5) / sqrt(var) / sqrt(2.0)));
    }
    free(r2);
    free(it);
    return 0;
}

/* The largest c with P(U <= c) <= tail for U of sizes m, n without ties, or -1: the k-subsets
   of the ranks 1..N with rank sum s counted by dynamic programming, U = S - m (m + 1) / 2.
   N <= RANKTEST_EXACT_MAX. */
static long u_null_critical(int m, int n, double tail)
{
    int N = m + n;
    long smax = (long)N * (N + 1) / 2;
    size_t cols = (size_t)smax + 1;
    double *ways = calloc((size_t)(m + 1) * cols, sizeof *ways);
    if (!ways)
        return -1;
    ways[0] = 1;
    for (int r = 1; r <= N; ++r)
        for (int k = (r < m ? r : m); k >= 1; --k)
            for (long s = smax; s >= r; --s)
                ways[(size_t)k * cols + (size_t)s] += ways[(size_t)(k - 1) * cols + (size_t)(s - r)];
    const double *row = ways + (size_t)m * cols;
    double total = 0, below = 0;
    for (long s = 0; s <= smax; ++s)
        total += row[s];
    long base = (long)m * (m + 1) / 2, c = -1;
    for (long s = base; s <= smax; ++s) {
        below += row[s];
        if (!(below / total <= tail))
            break;
        c = s - base;
    }
    free(ways);
    return c;
}

int ranktest_shift_ci(const double *x, int nx, const double *y, int ny, double alpha, double *est, double *lo,
                      double *hi)
{
    *est = *lo = *hi = NAN;
    int m = 0, n = 0;
    for (int i = 0; i < nx; ++i)
        m += isfinite(x[i]) != 0;
    for (int j = 0; j < ny; ++j)
        n += isfinite(y[j]) != 0;
    if (m == 0 || n == 0 || !(alpha > 0 && alpha < 1))
        return -1;
    size_t mn = (size_t)m * (size_t)n;
    double *d = malloc(mn * sizeof *d);
    if (!d)
        return -1;
    size_t k = 0;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            if (isfinite(x[i]) && isfinite(y[j]))
                d[k++] = x[i] - y[j];
    qsort(d, mn, sizeof *d, stats_cmp_double);
    *est = stats_median_sorted(d, mn);
    /* c: the largest count with P(U <= c) <= alpha / 2; the interval runs from the (c+1)-th
       smallest difference to the (c+1)-th largest */
    long c = -1;
    if (m + n <= RANKTEST_EXACT_MAX) {
        c = u_null_critical(m, n, 0.5 * alpha);
    } else {
        double z = -gsl_cdf_ugaussian_Pinv(0.5 * alpha);
        c = (long)floor(0.5 * (double)mn - z * sqrt((double)mn * (m + n + 1.0) / 12.0) - 0.5);
        if (c >= (long)mn / 2)
            c = (long)mn / 2 - 1;
    }
    if (c >= 0) {
        *lo = d[c];
        *hi = d[mn - 1 - (size_t)c];
    } else {
        *lo = -INFINITY;
        *hi = INFINITY;
    }
    free(d);
    return 0;
}
