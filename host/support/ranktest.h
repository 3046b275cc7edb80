/* ranktest.h - the Mann-Whitney (Wilcoxon rank-sum) test of two samples, for telling two
 * runs' repetitions of one figure apart. GSL has no rank test.
 *
 * Ties get mid-ranks. For up to RANKTEST_EXACT_MAX values in all, the null distribution is
 * exact: every way of drawing nx of the pooled mid-ranks is counted (by dynamic programming
 * over the rank sums), ties included, so the p-value is the permutation test's. Above that,
 * the normal approximation with the tie-corrected variance and a continuity correction. */
#ifndef BRDF_RANKTEST_H
#define BRDF_RANKTEST_H

#define RANKTEST_EXACT_MAX 40

struct ranktest_result {
    double u;        /* U of x: pairs with x > y, plus half the pairs with x == y */
    double p;        /* two-sided p-value: P(|U - nx ny / 2| >= observed) under the null */
    double p_min;    /* the smallest two-sided p these sample sizes (and ties) can give */
    int exact;       /* 1: exact null distribution; 0: normal approximation */
};

/* Tests x[0..nx) against y[0..ny); non-finite values are left out. Returns 0, or -1 when a
 * side has no finite value or there is no memory. */
int ranktest_mann_whitney(const double *x, int nx, const double *y, int ny, struct ranktest_result *out);

/* The Hodges-Lehmann estimate of the shift x - y (the median of the nx ny differences) and
 * its distribution-free confidence interval at level 1 - alpha (the differences' order
 * statistics at the Mann-Whitney critical count: exact for up to RANKTEST_EXACT_MAX values,
 * normal approximation above). Samples too small for the level give an unbounded interval
 * (-inf, inf). Applied to logarithms it gives a ratio's estimate and interval. Returns 0, or
 * -1 when a side has no finite value. */
int ranktest_shift_ci(const double *x, int nx, const double *y, int ny, double alpha, double *est, double *lo,
                      double *hi);

#endif
