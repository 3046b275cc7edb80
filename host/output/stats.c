/* stats.c - the shared comparison and medians (stats.h). */
#include "stats.h"

#include <math.h>
#include <stdlib.h>

int stats_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double stats_median_sorted(const double *v, size_t n)
{
    if (n == 0)
        return NAN;
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double stats_median_finite(double *v, size_t n)
{
    size_t good = 0;
    for (size_t j = 0; j < n; ++j)
        if (isfinite(v[j]))
            v[good++] = v[j];
    qsort(v, good, sizeof *v, stats_cmp_double);
    return stats_median_sorted(v, good);
}
