/* test_fit.c - the quadratic family's per-n figures and fits against independent derivations:
 *   - at n = 2 the minimax k is 1 with no error: (1 (c-1) + 1)^2 = c^2 = c^n (cq2 = c^2 there);
 *   - the exact per-n epicentre max delta (stationary point) and the attenuation max Delta
 *     (grid + Brent) against brute force over 200001 points in double;
 *   - the per-n minimax balances the two error sides and no nearby k does better;
 *   - at large n the limit tends to the n -> infinity minimax of |(1 - kappa a)^2 e^a - 1| over
 *     a in [0, 0.511] (c = 1 - a/n, c^n -> e^-a), found here by a plain search;
 *   - the affine minimax is never worse than fq2's own line, nor better than the per-n limit,
 *     and is locally optimal; with a cap every n meets it (brute force), and an impossible
 *     cap is reported. No device is needed. */
#include "accuracy.h"
#include "check.h"
#include "fit.h"
#include "models.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const double half_pi = 1.57079632679489661923;

/* (k(c-1)+1)^2 zeroed past its root, and c^n: through the registry (quad with a = 0, b = k). */
static struct model_spec quad_k(double k)
{
    struct model_spec m;
    model_spec_default(models_find("quad"), &m);
    m.params[0] = 0;
    m.params[1] = k;
    return m;
}

static double brute_epi_pts(double n, double k, int pts)
{
    struct model_spec m = quad_k(k), ref;
    model_spec_default(models_find("phong"), &ref);
    double xe = zone_epicentre_end(n), best = 0;
    for (int i = 0; i <= pts; ++i)
        best = fmax(best, error_rel_host(&m, &ref, cos(xe * i / (double)pts), n));
    return best;
}

static double brute_epi(double n, double k) { return brute_epi_pts(n, k, 200000); }

static double brute_att_pts(double n, double k, int pts)
{
    struct model_spec m = quad_k(k), ref;
    model_spec_default(models_find("phong"), &ref);
    double xe = zone_epicentre_end(n), best = 0;
    for (int i = 1; i <= pts; ++i) {
        /* denser near x_e, where the lobe falls off */
        double t = i / (double)pts, x = xe + (half_pi - xe) * t * t;
        best = fmax(best, error_abs_host(&m, &ref, fmax(cos(x), 0.0), n));
    }
    return best;
}

static double brute_att(double n, double k) { return brute_att_pts(n, k, 200000); }

static void test_per_n(void)
{
    double k, e;
    CHECK(fit_minimax_k(2.0, &k, &e) == 0, "minimax at n = 2 runs");
    CHECK_NEAR(k, 1.0, 1e-9, "minimax k at n = 2 (cq2 = c^2)");
    CHECK_NEAR(e, 0.0, 1e-12, "minimax max delta at n = 2");

    static const double cases[][2] = { { 3, 1.4 }, { 16, 7.3 }, { 100, 45 }, { 1000, 448.1 }, { 1000, 500 },
                                       { 50, 40 }, { 7.5, 2.0 }, { 200, 5 } };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        double n = cases[i][0], kk = cases[i][1];
        double exact = fit_epicentre_max_rel(n, kk), brute = brute_epi(n, kk);
        /* the brute force is a lower bound, within its grid's resolution */
        CHECK(exact >= brute - 1e-12 && exact - brute <= 1e-8 * fmax(1.0, exact) + 1e-10,
              "epicentre max delta at n = %g, k = %g: exact %.12g, brute force %.12g", n, kk, exact, brute);
        double att = fit_attenuation_max_abs(n, kk), batt = brute_att(n, kk);
        CHECK(att >= batt - 1e-12 && att - batt <= 1e-7,
              "attenuation max Delta at n = %g, k = %g: %.12g, brute force %.12g", n, kk, att, batt);
    }

    static const double ns[] = { 3, 16, 100, 1000 };
    for (size_t i = 0; i < sizeof ns / sizeof ns[0]; ++i) {
        double n = ns[i];
        CHECK(fit_minimax_k(n, &k, &e) == 0, "minimax at n = %g runs", n);
        struct fit_sides s = fit_epicentre_sides(n, k);
        CHECK_NEAR(s.over, s.under, 1e-10, "the minimax balances over- and under-estimation");
        for (int sgn = -1; sgn <= 1; sgn += 2)
            CHECK(fit_epicentre_max_rel(n, k * (1 + sgn * 1e-4)) >= e,
                  "no better k near the minimax at n = %g", n);
        CHECK_NEAR(e, brute_epi(n, k), 1e-8, "the minimax value matches brute force");
    }
}

/* max over a in [0, 0.511] of |(1 - kappa a)^2 e^a - 1|, on a fine grid. */
static double asym_err(double kappa)
{
    double best = 0;
    for (int i = 0; i <= 20000; ++i) {
        double a = 0.511 * i / 20000.0, b = 1 - kappa * a;
        best = fmax(best, fabs(b * b * exp(a) - 1));
    }
    return best;
}

static void test_asymptote(void)
{
    /* golden section over kappa in [0.4, 0.5] (the error is quasi-convex in kappa) */
    double lo = 0.4, hi = 0.5, g = 0.5 * (sqrt(5.0) - 1);
    for (int it = 0; it < 80; ++it) {
        double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (asym_err(m1) < asym_err(m2)) hi = m2; else lo = m1;
    }
    double limit = asym_err(0.5 * (lo + hi)), k, e;
    CHECK(fit_minimax_k(1e6, &k, &e) == 0, "minimax at n = 1e6 runs");
    CHECK(fabs(e / limit - 1) < 1e-4, "n = 1e6 limit %.9g vs the n -> infinity minimax %.9g", e, limit);
    CHECK(fabs(k / 1e6 - 0.5 * (lo + hi)) < 1e-4, "k/n at n = 1e6 (%.9g) vs kappa (%.9g)", k / 1e6, 0.5 * (lo + hi));
}

static void test_affine(void)
{
    /* n = 2, 4, ..., 400 */
    enum { N = 200 };
    double n[N];
    struct fit_limit lim[N];
    double limit_max = 0;
    for (int i = 0; i < N; ++i) {
        n[i] = 2.0 + 2.0 * i;
        lim[i].n = n[i];
        fit_minimax_k(n[i], &lim[i].k, &lim[i].max_rel);
        limit_max = fmax(limit_max, lim[i].max_rel);
    }
    struct fit_affine f;
    CHECK(fit_affine_minimax(n, N, lim, NAN, &f) == 0 && f.feasible, "uncapped fit runs: %s", f.reason);
    double fq2_line = 0;
    for (int i = 0; i < N; ++i)
        fq2_line = fmax(fq2_line, brute_epi_pts(n[i], 0.448 * n[i] + 0.099, 20000));
    CHECK(f.max_rel >= limit_max - 1e-12, "fit %.9g is no better than the per-n limit %.9g", f.max_rel, limit_max);
    CHECK(f.max_rel <= fq2_line + 1e-9, "fit %.9g is no worse than fq2's line %.9g (brute force)", f.max_rel, fq2_line);
    /* local optimality: small moves of (a, b) do not lower the largest max delta */
    for (int da = -1; da <= 1; ++da)
        for (int db = -1; db <= 1; ++db) {
            if (!da && !db)
                continue;
            double a = f.a * (1 + 1e-5 * da), b = f.b + 1e-4 * db, worst = 0;
            for (int i = 0; i < N; ++i)
                worst = fmax(worst, fit_epicentre_max_rel(n[i], a * n[i] + b));
            CHECK(worst >= f.max_rel * (1 - 1e-9), "(a, b) moved by (%d, %d) gives %.12g < %.12g", da, db, worst,
                  f.max_rel);
        }

    /* With a cap: every n of the grid keeps max Delta under it (brute force on every 4th n). */
    double cap = 0.128;
    struct fit_affine fc;
    CHECK(fit_affine_minimax(n, N, lim, cap, &fc) == 0 && fc.feasible, "capped fit runs: %s", fc.reason);
    for (int i = 0; i < N; i += 4) {
        double d = brute_att_pts(n[i], fc.a * n[i] + fc.b, 50000);
        CHECK(d <= cap + 1e-9, "capped fit at n = %g: max Delta %.9g > cap", n[i], d);
    }
    CHECK(fc.max_rel >= f.max_rel - 1e-12, "a cap cannot improve max delta (%.9g vs %.9g)", fc.max_rel, f.max_rel);

    /* An impossible cap at n = 1000 alone: no k of a coarse scan meets it either. */
    double n1[2] = { 999, 1000 };
    struct fit_limit l1[2];
    for (int i = 0; i < 2; ++i) {
        l1[i].n = n1[i];
        fit_minimax_k(n1[i], &l1[i].k, &l1[i].max_rel);
    }
    double tiny = 1e-3, best_any = INFINITY;
    for (int j = 1; j <= 400; ++j)
        best_any = fmin(best_any, brute_att_pts(1000, 1000.0 * j / 400.0, 20000));
    struct fit_affine fi;
    CHECK(best_any > tiny, "no k meets the tiny cap by brute force (best %.6g)", best_any);
    CHECK(fit_affine_minimax(n1, 2, l1, tiny, &fi) != 0 && !fi.feasible && fi.reason[0],
          "an impossible cap is reported as infeasible");
}

int main(void)
{
    test_per_n();
    test_asymptote();
    test_affine();
    return check_summary();
}
