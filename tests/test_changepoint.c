/* test_changepoint.c - the change points of history (host/support/changepoint.c) on synthetic
 * series whose changes are known by construction: 12 runs of 10 repetitions each, every
 * repetition the row's rate times a jitter written below (within +-3% per repetition and +-2%
 * per run, deterministic), with a step, a drift or an outlier planted. Expected changes and
 * ratios come from the planting: a 30% step from run 7 (index 6) is rates * 0.7 for runs 6..11,
 * so the change is at 6 with a ratio of 0.7 (up to the jitter, a few percent). No device. */
#include "changepoint.h"
#include "check.h"

#include <math.h>
#include <string.h>

#define T 12
#define R 10

static double vals[T][R];
static struct cp_sample runs[T];

/* The jitter of repetition i of run r: (1 + 0.03 sin(1.7 i + 2.3 r)) (1 + 0.02 cos(1.3 r)). */
static double jitter(int r, int i) { return (1 + 0.03 * sin(1.7 * i + 2.3 * r)) * (1 + 0.02 * cos(1.3 * r)); }

/* Run r's repetitions: 1e8 per second times scale[r] times the jitter. */
static void make(const double scale[T])
{
    for (int r = 0; r < T; ++r) {
        for (int i = 0; i < R; ++i)
            vals[r][i] = 1e8 * scale[r] * jitter(r, i);
        runs[r].v = vals[r];
        runs[r].n = R;
    }
}

static int find(struct cp_change *c)
{
    struct cp_settings s;
    cp_defaults(&s);
    return cp_find(runs, T, &s, c);
}

int main(void)
{
    struct cp_change c[CP_MAX_CHANGES];
    double scale[T];

    CHECK_CASE("jitter only");
    for (int r = 0; r < T; ++r)
        scale[r] = 1;
    make(scale);
    int n = find(c);
    CHECK(n == 0, "%d changes called on jitter alone (first at %d)", n, n > 0 ? c[0].at : -1);
    CHECK(isnan(cp_latest_ratio(c, n)), "no latest ratio without a change");

    CHECK_CASE("30% step from run 7");
    for (int r = 0; r < T; ++r)
        scale[r] = r >= 6 ? 0.7 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 1, "%d changes", n);
    if (n == 1) {
        CHECK(c[0].at == 6, "the change is at run index %d, planted at 6", c[0].at);
        CHECK(c[0].ratio > 0.66 && c[0].ratio < 0.74, "ratio %g, planted 0.7", c[0].ratio);
        CHECK(c[0].lo <= 0.7 && c[0].hi >= 0.7 && c[0].lo < c[0].hi, "interval %g..%g holds 0.7", c[0].lo, c[0].hi);
        CHECK(c[0].p < 0.05, "p %g", c[0].p);
        CHECK_NEAR(cp_latest_ratio(c, n), c[0].ratio, 0, "the latest segment's ratio is that change's");
    }

    CHECK_CASE("30% faster from run 7");
    for (int r = 0; r < T; ++r)
        scale[r] = r >= 6 ? 1.3 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 1 && c[0].at == 6 && c[0].ratio > 1.25 && c[0].ratio < 1.35, "%d changes, at %d, ratio %g", n,
          n ? c[0].at : -1, n ? c[0].ratio : 0);

    CHECK_CASE("8% step: below the minimum change");
    for (int r = 0; r < T; ++r)
        scale[r] = r >= 6 ? 0.92 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 0, "%d changes for a step of 8%% (the rule calls 10%% and more)", n);

    CHECK_CASE("slow drift, 1% a run");
    /* the best split, at 6, compares runs drifted 0..5% with runs drifted 6..11%: a shift of
       about 6%, under the 10% minimum */
    for (int r = 0; r < T; ++r)
        scale[r] = 1 + 0.01 * r;
    make(scale);
    n = find(c);
    CHECK(n == 0, "%d changes for a 1%% drift", n);

    CHECK_CASE("fast drift, 5% a run");
    /* 1.00 .. 1.55: halves differ by about 30%; changes are called, each one faster */
    for (int r = 0; r < T; ++r)
        scale[r] = 1 + 0.05 * r;
    make(scale);
    n = find(c);
    CHECK(n >= 1, "no change for a 55%% drift");
    for (int i = 0; i < n; ++i)
        CHECK(c[i].ratio > 1.1, "drift change %d at %d: ratio %g not faster", i, c[i].at, c[i].ratio);

    CHECK_CASE("one outlier run inside the series");
    for (int r = 0; r < T; ++r)
        scale[r] = r == 4 ? 0.6 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 0, "%d changes for one odd run (first at %d)", n, n ? c[0].at : -1);

    CHECK_CASE("the latest run 30% slower");
    for (int r = 0; r < T; ++r)
        scale[r] = r == 11 ? 0.7 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 1 && c[0].at == 11, "%d changes, at %d (expected one, at 11)", n, n ? c[0].at : -1);
    CHECK(n == 1 && cp_latest_ratio(c, n) > 0.66 && cp_latest_ratio(c, n) < 0.74, "latest ratio %g",
          cp_latest_ratio(c, n));

    /* Whole runs that differ from each other by about 8% (the offsets below, on a log scale:
       their successive differences have a median of 0.08, a spread of 0.08 / (0.6745 sqrt 2) =
       0.084 per run), the latest one 12% under the mean of the others (0.003): pooled, its ten
       repetitions are far from the other 110 and the shift passes 10%, but by whole runs it is
       1.4 spreads off (0.123 / (0.084 sqrt(1 + 1/11))), p about 0.19: no change. */
    static const double offs[T] = { 0.05, -0.06, 0.02, 0.07, -0.04, -0.07, 0.06, -0.02, 0.04, -0.05, 0.03, -0.12 };
    CHECK_CASE("the latest run within the runs' spread");
    for (int r = 0; r < T; ++r)
        scale[r] = exp(offs[r]);
    make(scale);
    n = find(c);
    CHECK(n == 0, "%d changes (first at %d, ratio %g) for a run within the runs' own spread", n, n ? c[0].at : -1,
          n ? c[0].ratio : 0);

    CHECK_CASE("a 30% step among runs that spread");
    /* the same runs with the step from run 7: (0.357 + the offsets' difference) over 0.084
       sqrt(1/6 + 1/6), about 7 spreads: called, at 6 */
    for (int r = 0; r < T; ++r)
        scale[r] = exp(offs[r]) * (r >= 6 ? 0.7 : 1);
    make(scale);
    n = find(c);
    CHECK(n == 1 && c[0].at == 6, "%d changes, at %d", n, n ? c[0].at : -1);

    CHECK_CASE("up 40% from run 4, back from run 8");
    for (int r = 0; r < T; ++r)
        scale[r] = r >= 4 && r < 8 ? 1.4 : 1;
    make(scale);
    n = find(c);
    CHECK(n == 2, "%d changes", n);
    if (n == 2) {
        CHECK(c[0].at == 4 && c[1].at == 8, "changes at %d and %d, planted at 4 and 8", c[0].at, c[1].at);
        CHECK(c[0].ratio > 1.34 && c[0].ratio < 1.46, "up: %g", c[0].ratio);
        CHECK(c[1].ratio > 1 / 1.46 && c[1].ratio < 1 / 1.34, "down: %g", c[1].ratio);
    }

    CHECK_CASE("a run with no values");
    for (int r = 0; r < T; ++r)
        scale[r] = r >= 6 ? 0.7 : 1;
    make(scale);
    runs[3].v = NULL;
    runs[3].n = 0;
    n = find(c);
    CHECK(n == 1 && c[0].at == 6, "%d changes, at %d", n, n ? c[0].at : -1);

    return check_summary();
}
