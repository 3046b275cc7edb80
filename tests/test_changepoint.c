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

static int find_min(struct cp_change *c, double min_change)
{
    struct cp_settings s;
    cp_defaults(&s);
    s.min_change = min_change;
    return cp_find(runs, T, &s, c);
}

/* Run levels measured on this project's 2-core test machine (PoCL, scripts/
 * bench_history_calibration.sh with its default flags, identical code in every run): each run's
 * median normalised rate per CPU second over the first run's. levels_flat: fq2 | n uniform in a
 * series where the machine held one state (levels 0.974..1.002: a between-run jitter of about
 * 1%). levels_state: cq2 | n uniform in a series where the machine changed state after run 2
 * (the model kernels 1.20x faster from run 3 on, the reference kernel not: a level shift that
 * normalising by the reference does not cancel). */
static const double levels_flat[T] = { 1.000, 0.996, 0.993, 0.989, 0.994, 0.991,
                                       0.990, 0.990, 1.002, 0.992, 0.974, 0.993 };
static const double levels_state[T] = { 1.000, 1.003, 1.206, 1.198, 1.205, 1.197,
                                        1.206, 1.205, 1.204, 1.202, 1.196, 1.202 };

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

    CHECK_CASE("measured between-run jitter, identical code");
    /* the levels' largest ratio is 1.002 / 0.974 = 1.029, and every run's repetitions carry the
       same +-3% pattern and a +-2% run term: no split's shift comes near the 10% minimum */
    for (int r = 0; r < T; ++r)
        scale[r] = levels_flat[r];
    make(scale);
    n = find(c);
    CHECK(n == 0, "%d changes on measured jitter (first at %d, ratio %g)", n, n ? c[0].at : -1, n ? c[0].ratio : 0);

    CHECK_CASE("measured between-run jitter with a 30% step from run 7");
    /* the same levels times 0.7 from index 6: the change at 6, its ratio 0.7 times the levels'
       ratio across the step (0.974..1.002 over 0.989..1.000, within 3%) and the jitter */
    for (int r = 0; r < T; ++r)
        scale[r] = levels_flat[r] * (r >= 6 ? 0.7 : 1);
    make(scale);
    n = find(c);
    CHECK(n == 1 && c[0].at == 6 && c[0].ratio > 0.66 && c[0].ratio < 0.74, "%d changes, at %d, ratio %g", n,
          n ? c[0].at : -1, n ? c[0].ratio : 0);

    CHECK_CASE("a machine state shift of 1.20x after run 2");
    /* levels 1.000, 1.003, then 1.196..1.206: a sustained shift of 1.20 (up to the jitter), which
       no test of one series can tell from a change of the code: at the 10% minimum it is called,
       at index 2; a minimum of 25% (log 1.25 = 0.223 > log 1.206 = 0.187) leaves it */
    for (int r = 0; r < T; ++r)
        scale[r] = levels_state[r];
    make(scale);
    n = find(c);
    CHECK(n == 1 && c[0].at == 2 && c[0].ratio > 1.15 && c[0].ratio < 1.25, "10%%: %d changes, at %d, ratio %g", n,
          n ? c[0].at : -1, n ? c[0].ratio : 0);
    n = find_min(c, 0.25);
    CHECK(n == 0, "25%%: %d changes (first at %d, ratio %g)", n, n ? c[0].at : -1, n ? c[0].ratio : 0);

    CHECK_CASE("a machine state shift and a 30% step from run 7");
    /* the same levels times 0.7 from index 6: at 10%, both the state (at 2, 1.20) and the step
       (at 6, 0.7); at 25%, the step alone (|log 0.7| = 0.357 > 0.223) */
    for (int r = 0; r < T; ++r)
        scale[r] = levels_state[r] * (r >= 6 ? 0.7 : 1);
    make(scale);
    n = find(c);
    CHECK(n == 2 && c[0].at == 2 && c[1].at == 6 && c[1].ratio > 0.66 && c[1].ratio < 0.74,
          "10%%: %d changes, at %d and %d", n, n ? c[0].at : -1, n > 1 ? c[1].at : -1);
    n = find_min(c, 0.25);
    CHECK(n == 1 && c[0].at == 6 && c[0].ratio > 0.66 && c[0].ratio < 0.74, "25%%: %d changes, at %d, ratio %g", n,
          n ? c[0].at : -1, n ? c[0].ratio : 0);

    CHECK_CASE("the same series twice: the same changes");
    {
        struct cp_change again[CP_MAX_CHANGES];
        n = find(c);
        int m = find(again);
        int same = n == m && n >= 0;
        /* field by field: the struct's padding is not part of the result */
        for (int i = 0; same && i < n; ++i)
            same = c[i].at == again[i].at && c[i].ratio == again[i].ratio && c[i].lo == again[i].lo &&
                   c[i].hi == again[i].hi && c[i].p == again[i].p && c[i].m == again[i].m;
        CHECK(same, "%d and %d changes, or they differ", n, m);
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
