/* stats.h - the order statistics every timing, export and quadrature part shares: qsort's comparison of
 * doubles and the median, written once (the renderer's timing, the runner's rounds, the rank
 * test, the energy quadrature's nodes). */
#ifndef BRDF_STATS_H
#define BRDF_STATS_H

#include <stddef.h>

/* qsort's comparison of two doubles, ascending (NaN compares equal to everything: sort finite
 * values only). */
int stats_cmp_double(const void *a, const void *b);

/* The median of n sorted values: the middle one, or the mean of the middle two; NAN when n is 0. */
double stats_median_sorted(const double *v, size_t n);

/* The median of v's finite values (v is rearranged: its finite values sorted first); NAN when
 * none is finite. */
double stats_median_finite(double *v, size_t n);

#endif
