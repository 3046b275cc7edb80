/* test_frontier.c - the approximations engines use, the family fit and the Pareto set, each
 * against a value derived here independently of the program:
 *   - the spherical Gaussian exp(n (c - 1)) against c^n: with u = n (1 - c),
 *     c^n = exp(-u - u^2/(2n) - O(u^3/n^2)), so f/c^n - 1 ~ u^2/(2n), largest at the
 *     epicentre's end u_e = n (1 - exp(-0.511/n)) ~ 0.511: max delta ~ 0.511^2/(2n) at large n;
 *   - the quadratic family at n = 2: k = 1 gives (c - 1 + 1)^2 = c^2 = c^n, no error;
 *   - Beaudoin and Guardado's A at n = 18, m = 2 by a bisection written here (a plain grid
 *     over c in [0, 1], nothing shared with the program), and the device model's affine A(n)
 *     within the 2.4% its header states, read back from the model's own values;
 *   - the Pareto set of a hand-made table of points;
 *   - the bit trick: c = 1 gives 1 for any n; c = 2^-j with integer n gives 2^-(n j) exactly
 *     (bits(c) - bits(1) = -j 2^23 is exact); c = 0.75, n = 2 gives 0.5 (worked by hand on the
 *     bit patterns: 0x3f400000 - 0x3f800000 = -2^22, times 2 is -2^23, plus 0x3f800000 is
 *     0x3f000000 = 0.5);
 *   - the power family at m = 1 equals the affine line (a n + b)(c - 1) + 1 written here.
 * No device is needed. */
#include "accuracy.h"
#include "check.h"
#include "fit.h"
#include "frontier.h"
#include "frontier_report.h"
#include "models.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static struct model_spec spec_of(const char *text)
{
    struct model_spec m;
    char err[256];
    if (model_spec_parse(text, &m, err, sizeof err)) {
        fprintf(stderr, "cannot parse %s: %s\n", text, err);
        memset(&m, 0, sizeof m);
    }
    return m;
}

static void test_gaussian_large_n(void)
{
    struct model_spec sg = spec_of("sg");
    const double ns[] = { 500.0, 1000.0, 4000.0 };
    for (int i = 0; i < 3; ++i) {
        double n = ns[i], params[2] = { 0, 0 };
        struct fit_point pt;
        fit_family_figures(&sg, 0, params, &n, 1, &pt);
        double closed = 0.511 * 0.511 / (2.0 * n);
        /* the next terms are O(1/n^2) relative to this one: 1% is ample at n >= 500 */
        CHECK(fabs(pt.max_rel / closed - 1.0) < 0.01, "sg at n = %g: max delta %.6g vs 0.511^2/(2n) = %.6g", n,
              pt.max_rel, closed);
    }
}

static void test_quadratic_exact_at_2(void)
{
    double k = NAN, rel = NAN;
    CHECK(fit_minimax_k(2.0, &k, &rel) == 0, "fit_minimax_k(2) ran");
    CHECK_NEAR(k, 1.0, 1e-9, "the minimax k at n = 2 is 1");
    CHECK(rel < 1e-12, "no error at n = 2: %g", rel);
    /* and the family's power form at m = 2 agrees: (1 (c-1) + 1)^2 = c^2 */
    for (double c = 0.0; c <= 1.0; c += 0.125)
        CHECK_NEAR(fit_power_eval(c, 2.0, 0.0, 1.0, 2), c * c, 1e-15, "power m = 2, k = 1 is c^2");
}

/* Beaudoin and Guardado's balance, independently: the largest f - c^n and c^n - f over a
   uniform grid of 200001 cosines, and a bisection on A. */
static void bg_sides_here(double n, double a, int m, int pts, double *over, double *under)
{
    *over = *under = 0;
    for (int i = 0; i <= pts; ++i) {
        double c = i / (double)pts, base = a * c + 1.0 - a;
        double f = base > 0 ? pow(base, m) : 0.0, d = f - pow(c, n);
        if (d > *over) *over = d;
        if (-d > *under) *under = -d;
    }
}

static double bg_a_here(double n, int m, int pts, double *err)
{
    double lo = 0.0, hi = n, over, under;
    for (int it = 0; it < 50; ++it) {
        double a = 0.5 * (lo + hi);
        bg_sides_here(n, a, m, pts, &over, &under);
        if (over > under) lo = a; else hi = a;
    }
    double a = 0.5 * (lo + hi);
    bg_sides_here(n, a, m, pts, &over, &under);
    *err = fmax(over, under);
    return a;
}

static void test_beaudoin_guardado(void)
{
    double err_here, a_here = bg_a_here(18.0, 2, 200000, &err_here);
    double a = NAN, err = NAN;
    CHECK(fit_bg_exact_a(18.0, 2, &a, &err) == 0, "fit_bg_exact_a(18, 2) ran");
    /* the grid here resolves c to 5e-6: A and the error agree to far better than the table's digits */
    CHECK_NEAR(a, a_here, 1e-4, "A at n = 18, m = 2 against the bisection here");
    CHECK_NEAR(err, err_here, 1e-5, "largest |f - c^n| at n = 18, m = 2");
    /* the device model's A(n): f(c) = (1 - (1 - c) A)^m, so A = (1 - f^(1/m)) / (1 - c), read at
       c = 1 - 1/(2 A_exact), well inside the root (a coarser grid: the bound is 2.5%) */
    const double ns[] = { 2.0, 18.0, 100.0, 1000.0 };
    for (int j = 1; j <= 2; ++j) {
        int m = 1 << j;
        char text[32];
        snprintf(text, sizeof text, "bg:j=%d", j);
        struct model_spec bg = spec_of(text);
        for (int i = 0; i < 4; ++i) {
            double e, exact = bg_a_here(ns[i], m, 20000, &e), s = 0.5 / exact;
            double f = model_eval_host(&bg, 1.0 - s, ns[i]);
            double a_model = (1.0 - pow(f, 1.0 / m)) / s;
            CHECK(fabs(a_model / exact - 1.0) <= 0.025, "bg m = %d, n = %g: A(n) %.6g vs bisection %.6g", m, ns[i],
                  a_model, exact);
        }
    }
}

static void test_pareto(void)
{
    /* name: rate spread [lo, hi], max delta, max Delta; the expected verdict by hand */
    const double lo[] = { 9, 20, 9.5, 10.8, 30, 5, 19 };
    const double hi[] = { 11, 22, 10.5, 12, 31, 6, 21 };
    const double rel[] = { 0.01, 0.02, 0.02, 0.01, 0.5, 0.005, 0.03 };
    const double ab[] = { 0.1, 0.2, 0.2, 0.1, 0.5, 0.3, 0.2 };
    /* A on: nothing as accurate is surely faster (D ties it: overlapping spreads, same figures).
       B on: only E is faster, and E is worse. C off: A ties its cost and is better on both.
       D on: A only ties it. E on: the fastest. F on: the least max delta.
       G off: B's spread overlaps G's and B is better on max delta, equal on max Delta. */
    const int expected[] = { 1, 1, 0, 1, 1, 1, 0 };
    int front[7];
    frontier_pareto(lo, hi, rel, ab, 7, front);
    for (int i = 0; i < 7; ++i)
        CHECK(front[i] == expected[i], "point %c: on_front %d, expected %d", 'A' + i, front[i], expected[i]);
    /* a missing figure keeps a point off the front and does not dominate the others */
    const double lo2[] = { 9, NAN }, hi2[] = { 11, NAN }, rel2[] = { 0.1, 0.0 }, ab2[] = { 0.1, 0.0 };
    int front2[2];
    frontier_pareto(lo2, hi2, rel2, ab2, 2, front2);
    CHECK(front2[0] == 1 && front2[1] == 0, "a point without a rate: %d %d", front2[0], front2[1]);
}

static void test_bitpow(void)
{
    struct model_spec b = spec_of("bitpow");
    const double ns[] = { 1.0, 2.0, 7.5, 137.25, 1000.0 };
    for (int i = 0; i < 5; ++i)
        CHECK(model_eval_host(&b, 1.0, ns[i]) == 1.0, "c = 1, n = %g gives 1", ns[i]);
    for (int j = 1; j <= 4; ++j)
        for (int n = 1; n * j <= 120; n += 7)
            CHECK(model_eval_host(&b, ldexp(1.0, -j), n) == ldexp(1.0, -n * j), "c = 2^-%d, n = %d", j, n);
    CHECK(model_eval_host(&b, 0.75, 2.0) == 0.5, "c = 0.75, n = 2 gives 0.5 (by hand)");
    CHECK(model_eval_host(&b, 0.0, 2.0) == 0.0, "c = 0 gives 0");
}

static void test_power_m1(void)
{
    for (double c = 0.5; c <= 1.0; c += 0.0625) {
        double want = fmax((0.3 * 10 + 0.2) * (c - 1) + 1, 0.0);
        CHECK_NEAR(fit_power_eval(c, 10.0, 0.3, 0.2, 1), want, 1e-15, "power m = 1 is the clamped line");
    }
}

/* No empty plot: a frontier whose models have no measured rate draws no scatter plot, removes
 * an earlier run's, and its markdown says the plots are not drawn instead of linking them. */
static void test_no_empty_plots(void)
{
    static struct frontier_report r;
    memset(&r, 0, sizeof r);
    r.count = 2;
    r.fq2 = -1;
    r.rows[0].spec = spec("phong");
    r.rows[1].spec = spec("fq2");
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 3; k++) r.rows[i].rate[0][k] = r.rows[i].rate[1][k] = NAN;
    CHECK(!frontier_plots_drawable(&r), "rates all NaN, yet a plot to draw");
    char dir[4096], path[4200], err[512];
    CHECK(test_tmpdir_make(dir, sizeof dir, "frontier_empty") == 0, "tmp folder");
    snprintf(path, sizeof path, "%s/frontier_max_rel.png", dir);
    FILE *f = fopen(path, "w");   /* an earlier run's plot */
    if (f) fclose(f);
    CHECK(frontier_write_plots(dir, &r, err, sizeof err) == 0, "write: %s", err);
    CHECK(access(path, F_OK) != 0, "an empty frontier left a plot");
    char *md = frontier_markdown(&r);
    CHECK(md && !strstr(md, "frontier_max_rel.png)") && strstr(md, "not drawn"), "markdown links a plot not drawn");
    free(md);
    r.rows[1].rate[0][1] = 1e9;
    CHECK(frontier_plots_drawable(&r), "one rate, yet nothing to draw");
    test_tmpdir_done(dir);
}

int main(void)
{
    test_gaussian_large_n();
    test_quadratic_exact_at_2();
    test_beaudoin_guardado();
    test_pareto();
    test_bitpow();
    test_power_m1();
    test_no_empty_plots();
    return check_summary();
}
