/* test_ranktest.c - the Mann-Whitney test against values worked by hand: U as a count of
 * pairs, exact two-sided p-values from the counts of the null distribution (listed in each
 * comment), ties by mid-ranks, and the normal approximation against its formula written out
 * here a second time. No device. */
#include "check.h"
#include "ranktest.h"

#include <math.h>
#include <stdlib.h>

static struct ranktest_result mw(const double *x, int nx, const double *y, int ny)
{
    struct ranktest_result r;
    int rc = ranktest_mann_whitney(x, nx, y, ny, &r);
    CHECK(rc == 0, "ranktest_mann_whitney returned %d", rc);
    return r;
}

int main(void)
{
    /* 3 against 3, fully separated: U = 0. Of the C(6,3) = 20 equally likely draws, one has
       U = 0 and one U = 9, so the two-sided p is 2/20. */
    {
        double x[] = { 1, 2, 3 }, y[] = { 4, 5, 6 };
        struct ranktest_result r = mw(x, 3, y, 3);
        CHECK_NEAR(r.u, 0, 0, "U, x below y");
        CHECK_NEAR(r.p, 0.1, 1e-15, "p, 3 vs 3 separated");
        CHECK_NEAR(r.p_min, 0.1, 1e-15, "smallest p of 3 vs 3");
        CHECK(r.exact, "exact at 6 values");
        r = mw(y, 3, x, 3);
        CHECK_NEAR(r.u, 9, 0, "U, x above y: all 9 pairs");
        CHECK_NEAR(r.p, 0.1, 1e-15, "p is symmetric");
    }
    /* 5 against 5 separated: 2 of C(10,5) = 252 draws are as extreme. */
    {
        double x[] = { 10, 9, 8, 7, 6 }, y[] = { 5, 4, 3, 2, 1 };
        struct ranktest_result r = mw(x, 5, y, 5);
        CHECK_NEAR(r.u, 25, 0, "U of 5 above 5");
        CHECK_NEAR(r.p, 2.0 / 252.0, 1e-15, "p, 5 vs 5 separated");
        CHECK(r.p < 0.05, "5 reps each can reach 0.05");
    }
    /* Interleaved 1,3,5 against 2,4,6: pairs with x > y are 3>2, 5>2, 5>4, so U = 3; E U = 4.5.
       The null counts of U = 0..9 for 3 vs 3 are 1,1,2,3,3,3,3,2,1,1 (partitions of U into at
       most 3 parts of at most 3); |U - 4.5| >= 1.5 holds for U <= 3 or U >= 6: 7 + 7 = 14 of 20. */
    {
        double x[] = { 1, 3, 5 }, y[] = { 2, 4, 6 };
        struct ranktest_result r = mw(x, 3, y, 3);
        CHECK_NEAR(r.u, 3, 0, "U interleaved");
        CHECK_NEAR(r.p, 0.7, 1e-15, "p interleaved");
    }
    /* Ties: x = {1, 2}, y = {2, 3}. Pooled ranks 1, 2.5, 2.5, 4; W_x = 3.5, so U = 3.5 - 3 = 0.5
       (the pair 2 = 2 counts half). Rank sums of the 6 draws of two: 3.5, 3.5, 5, 5, 6.5, 6.5
       around E W = 5: four are at least 1.5 away, p = 4/6. */
    {
        double x[] = { 1, 2 }, y[] = { 2, 3 };
        struct ranktest_result r = mw(x, 2, y, 2);
        CHECK_NEAR(r.u, 0.5, 0, "U with a tie");
        CHECK_NEAR(r.p, 4.0 / 6.0, 1e-15, "p with a tie");
    }
    /* A sample against itself: every value tied with its copy, U = nx ny / 2 and p = 1. */
    {
        double x[] = { 3.5, 1.25, 7, 2, 9 };
        struct ranktest_result r = mw(x, 5, x, 5);
        CHECK_NEAR(r.u, 12.5, 0, "U of a sample against itself");
        CHECK_NEAR(r.p, 1.0, 1e-15, "p of a sample against itself");
        double t[] = { 4, 4, 4 };
        r = mw(t, 3, t, 2);
        CHECK_NEAR(r.p, 1.0, 1e-15, "all values tied");
    }
    /* Non-finite values are left out: {1, 2, 3, NaN} against {4, 5, 6} is the first case. */
    {
        double x[] = { 1, NAN, 2, 3 }, y[] = { 4, 5, INFINITY, 6 };
        struct ranktest_result r = mw(x, 4, y, 4);
        CHECK_NEAR(r.p, 0.1, 1e-15, "NaN and Inf left out");
        struct ranktest_result bad;
        double only_nan[] = { NAN };
        CHECK(ranktest_mann_whitney(only_nan, 1, y, 3, &bad) == -1, "a side with no finite value is refused");
    }
    /* Unequal sizes, 2 against 4 separated: 2 of C(6,2) = 15 draws are as extreme (both
       smallest or both largest): p = 2/15. */
    {
        double x[] = { 0.5, 0.25 }, y[] = { 1, 2, 3, 4 };
        struct ranktest_result r = mw(x, 2, y, 4);
        CHECK_NEAR(r.p, 2.0 / 15.0, 1e-15, "p, 2 vs 4 separated");
    }
    /* Normal approximation, 30 against 30 (past the exact limit): x = 1..30 and
       y = 16.5..45.5, no ties. U_x counts x_i > y_j: x = k beats the k - 16 values of y below
       it for k = 17..30, sum 1 + ... + 14 = 105. E U = 450, var = 30*30*61/12 = 4575;
       z = (|105 - 450| - 0.5) / sqrt(4575), p = erfc(z / sqrt 2). */
    {
        double x[30], y[30];
        for (int i = 0; i < 30; ++i) {
            x[i] = i + 1;
            y[i] = i + 16.5;
        }
        struct ranktest_result r = mw(x, 30, y, 30);
        CHECK(!r.exact, "60 values: normal approximation");
        CHECK_NEAR(r.u, 105, 0, "U of the overlap");
        double z = (345.0 - 0.5) / sqrt(4575.0);
        CHECK_NEAR(r.p, erfc(z / sqrt(2.0)), 1e-12, "normal p");
    }
    /* The exact branch against brute force: 7 against 5 values with ties, every one of the
       C(12, 7) = 792 draws of 7 pooled values enumerated here, U counted pair by pair. */
    {
        double x[] = { 1, 2, 2, 4, 5, 7, 7 }, y[] = { 2, 3, 6, 7, 8 };
        double pool[12];
        for (int i = 0; i < 7; ++i)
            pool[i] = x[i];
        for (int j = 0; j < 5; ++j)
            pool[7 + j] = y[j];
        double u_obs = 0;
        for (int i = 0; i < 7; ++i)
            for (int j = 0; j < 5; ++j)
                u_obs += x[i] > y[j] ? 1.0 : x[i] == y[j] ? 0.5 : 0.0;
        int total = 0, tail = 0;
        for (unsigned mask = 0; mask < (1u << 12); ++mask) {
            if (__builtin_popcount(mask) != 7)
                continue;
            double u = 0;
            for (int a = 0; a < 12; ++a)
                for (int b = 0; b < 12; ++b)
                    if ((mask >> a & 1u) && !(mask >> b & 1u))
                        u += pool[a] > pool[b] ? 1.0 : pool[a] == pool[b] ? 0.5 : 0.0;
            ++total;
            tail += fabs(u - 17.5) >= fabs(u_obs - 17.5) - 1e-9;
        }
        CHECK(total == 792, "C(12, 7) draws: %d", total);
        struct ranktest_result r = mw(x, 7, y, 5);
        CHECK_NEAR(r.u, u_obs, 0, "U with ties, 7 vs 5");
        CHECK_NEAR(r.p, (double)tail / total, 1e-13, "exact p against enumeration");
    }
    /* Hodges-Lehmann shift and its interval, worked by hand. x = {11..15}, y = {1..5}: the 25
       differences x_i - y_j are 6 (once), 7 (twice), ..., 10 (five times), ..., 14 (once); their
       median (13th) is 10. For 5 against 5, P(U <= 2) = 4/252 = 0.0159 <= 0.025 and
       P(U <= 3) = 7/252 = 0.0278 > 0.025 (counts of the U distribution: 1, 1, 2, 3), so the 95%
       interval runs from the 3rd smallest difference (7) to the 3rd largest (13). */
    {
        double x[] = { 11, 12, 13, 14, 15 }, y[] = { 1, 2, 3, 4, 5 }, est, lo, hi;
        CHECK(ranktest_shift_ci(x, 5, y, 5, 0.05, &est, &lo, &hi) == 0, "shift_ci");
        CHECK_NEAR(est, 10, 0, "Hodges-Lehmann estimate");
        CHECK_NEAR(lo, 7, 0, "95% interval: 3rd smallest difference");
        CHECK_NEAR(hi, 13, 0, "95% interval: 3rd largest difference");
        /* at alpha 0.2: P(U <= 4) = 12/252 = 0.0476 <= 0.1, P(U <= 5) = 19/252 = 0.0754 <= 0.1,
           P(U <= 6) = 28/252 = 0.111 > 0.1: c = 5, from the 6th smallest (8) to the 6th largest (12) */
        CHECK(ranktest_shift_ci(x, 5, y, 5, 0.2, &est, &lo, &hi) == 0, "shift_ci at 0.2");
        CHECK_NEAR(lo, 8, 0, "80% interval: 6th smallest difference");
        CHECK_NEAR(hi, 12, 0, "80% interval: 6th largest difference");
    }
    /* Too few values for the level: 2 against 2 can give no p below 1/6, so a 95% interval
       has no finite end. */
    {
        double x[] = { 3, 4 }, y[] = { 1, 2 }, est, lo, hi;
        CHECK(ranktest_shift_ci(x, 2, y, 2, 0.05, &est, &lo, &hi) == 0, "shift_ci 2 vs 2");
        CHECK(isinf(lo) && isinf(hi) && lo < 0 && hi > 0, "2 vs 2: unbounded interval (%g, %g)", lo, hi);
        CHECK_NEAR(est, 2, 0, "2 vs 2: median of {1, 2, 2, 3}");
    }
    /* Large samples (normal approximation): 30 against 30, y = x + 1 exactly: every one of the
       900 differences of x_i + 1 - x_j is an integer shift; the estimate is the true shift 1
       and the interval holds it. The critical count is floor(450 - 1.96 sqrt(900 * 61 / 12) - 0.5)
       = floor(450 - 132.6 - 0.5) = 316 (written out here). */
    {
        double x[30], y[30], est, lo, hi;
        for (int i = 0; i < 30; ++i) {
            x[i] = i + 1.0;
            y[i] = i;
        }
        CHECK(ranktest_shift_ci(x, 30, y, 30, 0.05, &est, &lo, &hi) == 0, "shift_ci 30 vs 30");
        CHECK_NEAR(est, 1, 0, "30 vs 30: estimate");
        /* differences d = 1 + (i - j): value v occurs 30 - |v - 1| times; the 317th smallest */
        int count = 0;
        double d317 = 0;
        for (int v = -28; v <= 30 && count < 317; ++v) {
            count += 30 - abs(v - 1);
            d317 = v;
        }
        CHECK_NEAR(lo, d317, 0, "30 vs 30: 317th smallest difference");
        CHECK_NEAR(hi, 2 - d317, 0, "30 vs 30: symmetric upper end");
    }
    return check_summary();
}
