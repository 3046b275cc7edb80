/* test_stats.c - the shared comparison and medians (host/core/stats.c) against values worked
 * by hand: an odd count's middle value, an even count's mean of the middle two, the non-finite
 * values left out, none left (NAN), and qsort with the comparison giving ascending order. No
 * device. */
#include "check.h"
#include "stats.h"

#include <math.h>
#include <stdlib.h>

int main(void)
{
    CHECK_CASE("comparison");
    double a = 1, b = 2;
    CHECK(stats_cmp_double(&a, &b) < 0 && stats_cmp_double(&b, &a) > 0 && stats_cmp_double(&a, &a) == 0,
          "1 < 2, 2 > 1, 1 = 1");
    double v[] = { 5, -1, 3, 2, 4 };
    qsort(v, 5, sizeof *v, stats_cmp_double);
    CHECK(v[0] == -1 && v[1] == 2 && v[2] == 3 && v[3] == 4 && v[4] == 5, "sorted: %g %g %g %g %g", v[0], v[1], v[2],
          v[3], v[4]);

    CHECK_CASE("median of sorted values");
    const double odd[] = { 1, 2, 10 };            /* the middle one: 2 */
    CHECK_NEAR(stats_median_sorted(odd, 3), 2, 0, "1 2 10");
    const double even[] = { 1, 2, 4, 10 };        /* (2 + 4) / 2 = 3 */
    CHECK_NEAR(stats_median_sorted(even, 4), 3, 0, "1 2 4 10");
    CHECK_NEAR(stats_median_sorted(odd, 1), 1, 0, "one value");
    CHECK(isnan(stats_median_sorted(odd, 0)), "no value: NAN");

    CHECK_CASE("median of the finite values");
    double mixed[] = { 7, NAN, 1, INFINITY, 4, -INFINITY, 2 };   /* finite: 1 2 4 7 -> (2 + 4) / 2 = 3 */
    CHECK_NEAR(stats_median_finite(mixed, 7), 3, 0, "7 nan 1 inf 4 -inf 2");
    double unsorted[] = { 9, 3, 6 };                               /* 3 6 9 -> 6 */
    CHECK_NEAR(stats_median_finite(unsorted, 3), 6, 0, "9 3 6");
    double none[] = { NAN, INFINITY };
    CHECK(isnan(stats_median_finite(none, 2)), "no finite value: NAN");
    CHECK(isnan(stats_median_finite(none, 0)), "no value: NAN");

    return check_summary();
}
