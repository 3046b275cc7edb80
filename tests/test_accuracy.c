/* test_accuracy.c - the dense-grid sweep against independent derivations:
 *   - cq2 at n = 2 has no error at all (cq2 = c^2 there, docs/definitions.md);
 *   - cq2's epicentre maximum at large n sits at the zone end, where its value has a closed
 *     form: u = 1 - e^(-0.511/n), delta = 1 - (1 - n u / 2)^2 / e^(-0.511);
 *   - per-n maxima of several models match a brute-force maximum over 400001 points in
 *     double on the host (no device, no refinement);
 *   - doubling the samples moves no reported figure in its 4th significant digit;
 *   - the grid helpers' counts, worked by hand;
 *   - each sweep once per session, and nothing shared between sessions. */
#include "accuracy.h"
#include "check.h"
#include "exitcodes.h"
#include "models.h"
#include "testutil.h"

#include <math.h>
#include <string.h>
#include <stdio.h>
#include <stdlib.h>

static void test_grid_helpers(void)
{
    struct accuracy_grid g = { 2, 1000, 1, 64 };
    CHECK(accuracy_grid_count(&g) == 999, "2..1000 step 1 has 999 values (got %ld)", accuracy_grid_count(&g));
    g.n_step = 0.5;
    CHECK(accuracy_grid_count(&g) == 1997, "step 0.5 has 1997 values");
    g.n_min = 2; g.n_max = 10; g.n_step = 3;   /* 2, 5, 8 and n_max = 10 itself */
    CHECK(accuracy_grid_count(&g) == 4 && accuracy_grid_n(&g, 3) == 10 && accuracy_grid_n(&g, 2) == 8,
          "n_max always included");
    char err[256];
    struct accuracy_grid bad = { 5, 5, 1, 64 };
    CHECK(accuracy_grid_check(&bad, NULL, err, sizeof err) == EXIT_USAGE, "n-min = n-max rejected");
    struct accuracy_grid bad2 = { 2, 100, 1, 100 };
    CHECK(accuracy_grid_check(&bad2, NULL, err, sizeof err) == EXIT_USAGE, "samples not a multiple of 16 rejected");
}

/* Brute force in double: max over x of the error, on a uniform grid of `points` in [lo, hi]. */
static double brute_max(const struct model_spec *m, const struct model_spec *ref, double n, double lo, double hi,
                        int relative, int points)
{
    double best = 0;
    for (int i = 0; i <= points; ++i) {
        double x = lo + (hi - lo) * i / points, c = cos(x);
        double e = relative ? error_rel_host(m, ref, c, n) : error_abs_host(m, ref, c, n);
        if (e > best)
            best = e;
    }
    return best;
}

static int run(struct accuracy_ctx *a, const char *model, double n_min, double n_max, double step, long samples,
               struct accuracy_result *r)
{
    struct model_spec m = spec(model);
    struct accuracy_grid g = { n_min, n_max, step, samples };
    return accuracy_run(a, &m, &g, r);
}

static int test_device(struct accuracy_ctx *a)
{
    int rc;
    struct accuracy_result r;

    /* cq2 = c^2 = phong at n = 2: no error anywhere. */
    if ((rc = run(a, "cq2", 2, 3, 1, 256, &r)))
        return rc;
    CHECK(r.per_n[0].epi_rel <= 1e-6 && r.per_n[0].epi_rel_d.value <= 1e-15, "cq2 at n = 2: device %g, double %g",
          r.per_n[0].epi_rel, r.per_n[0].epi_rel_d.value);
    CHECK(r.per_n[0].att_abs_d.value <= 1e-15, "cq2 at n = 2: attenuation %g", r.per_n[0].att_abs_d.value);
    accuracy_result_free(&r);

    /* cq2's epicentre maximum at the zone end (closed form above). */
    if ((rc = run(a, "cq2", 900, 1000, 50, 1024, &r)))
        return rc;
    for (long i = 0; i < r.n_count; ++i) {
        double n = r.per_n[i].n, u = -expm1(-0.511 / n);
        double expect = 1 - (1 - n * u / 2) * (1 - n * u / 2) / exp(-0.511);
        CHECK_NEAR(r.per_n[i].epi_rel_d.value, expect, 1e-12, "cq2 zone-end delta");
        CHECK_NEAR(r.per_n[i].epi_rel_d.x, acos(exp(-0.511 / n)), 1e-12, "cq2 max at the zone end");
    }
    CHECK(r.epicentre.n == 1000, "cq2's delta grows with n: range maximum at n = 1000 (got %g)", r.epicentre.n);
    accuracy_result_free(&r);

    /* Per-n maxima against brute force in double (400001 points per zone). */
    const char *models[] = { "fvol", "fq2", "schlick", "lyon:k=3", "ggx", "fq2n" };
    const double ns[] = { 3, 16, 137, 1000 };
    for (int k = 0; k < 6; ++k) {
        struct model_spec m = spec(models[k]), ref;
        model_reference_spec(&m, &ref);
        for (int j = 0; j < 4; ++j) {
            if ((rc = run(a, models[k], ns[j], ns[j] + 1, 1, 2048, &r)))
                return rc;
            double xe = zone_epicentre_end(ns[j]);
            double be = brute_max(&m, &ref, ns[j], 0, xe, 1, 400000);
            double ba = brute_max(&m, &ref, ns[j], xe, M_PI / 2, 0, 400000);
            /* Brute force on a finite grid is below the true maximum by about (step)^2 x
               curvature; where two local maxima are equal to float resolution the device may
               locate either (the polished value is then within ~1e-7 relative): 1e-6 covers both. */
            CHECK(fabs(r.per_n[0].epi_rel_d.value - be) <= 1e-6 * be + 1e-12, "%s n=%g epicentre: sweep %.10g brute %.10g",
                  models[k], ns[j], r.per_n[0].epi_rel_d.value, be);
            CHECK(fabs(r.per_n[0].att_abs_d.value - ba) <= 1e-6 * ba + 1e-12, "%s n=%g attenuation: sweep %.10g brute %.10g",
                  models[k], ns[j], r.per_n[0].att_abs_d.value, ba);
            accuracy_result_free(&r);
        }
    }

    /* Convergence: doubling the samples moves no range figure in its 4th significant digit. */
    for (int k = 0; k < 6; ++k) {
        struct accuracy_result r1, r2;
        if ((rc = run(a, models[k], 2, 300, 1, 512, &r1)) || (rc = run(a, models[k], 2, 300, 1, 1024, &r2)))
            return rc;
        const double v1[] = { r1.epicentre.value, r1.attenuation.value, r1.whole.value };
        const double v2[] = { r2.epicentre.value, r2.attenuation.value, r2.whole.value };
        for (int q = 0; q < 3; ++q) {
            double unit = pow(10, floor(log10(v2[q])) - 3);
            CHECK(fabs(v1[q] - v2[q]) < 0.5 * unit, "%s figure %d: %.8g vs %.8g", models[k], q, v1[q], v2[q]);
        }
        /* The device's float figures agree with the double recomputation far (10x) below that
           digit. Float resolution sets the scale: a few ulp (6e-8 each) of a model value,
           amplified by the 2^k of Lyon's squarings (8 for k = 3), is about 5e-7 of a figure of
           about 3.5e-2, whose 4th-digit unit is 1e-5. */
        CHECK(r2.check_rel_diff < 0.1 * pow(10, floor(log10(r2.epicentre.value)) - 3), "%s check %.3g", models[k],
              r2.check_rel_diff);
        accuracy_result_free(&r1);
        accuracy_result_free(&r2);
    }

    /* Each figure once: the same sweep asked for again, from another context of the same
     * session, is a copy of the first (the counter counts it); a sweep recomputed after
     * accuracy_forget_sweeps gives the same figures, so the copy is what a second run gives;
     * another grid or another model is run, not copied. */
    {
        struct accuracy_ctx b;
        struct accuracy_result r1, r2, r3, r4;
        if ((rc = accuracy_open(&b, a->s, "")) != 0) return rc;
        accuracy_forget_sweeps(a->s);
        long hits = accuracy_reused_sweeps(a->s);
        if ((rc = run(a, "fq2", 2, 200, 3, 256, &r1)) || (rc = run(&b, "fq2", 2, 200, 3, 256, &r2))) return rc;
        CHECK(accuracy_reused_sweeps(a->s) == hits + 1, "the second ask is reused (%ld -> %ld)", hits,
              accuracy_reused_sweeps(a->s));
        CHECK(r2.per_n != r1.per_n && r2.n_count == r1.n_count &&
                  memcmp(r2.per_n, r1.per_n, (size_t)r1.n_count * sizeof *r1.per_n) == 0 &&
                  r2.epicentre.value == r1.epicentre.value && r2.attenuation.value == r1.attenuation.value,
              "a reused sweep is an own copy of the first");
        if ((rc = run(&b, "fq2", 2, 200, 4, 256, &r3))) return rc;
        CHECK(accuracy_reused_sweeps(a->s) == hits + 1 && r3.n_count != r1.n_count, "another grid is run");
        accuracy_result_free(&r3);
        if ((rc = run(&b, "fvol", 2, 200, 3, 256, &r3))) return rc;
        CHECK(accuracy_reused_sweeps(a->s) == hits + 1 && r3.epicentre.value != r1.epicentre.value,
              "another model is run");
        accuracy_forget_sweeps(a->s);
        if ((rc = run(&b, "fq2", 2, 200, 3, 256, &r4))) return rc;
        CHECK(accuracy_reused_sweeps(a->s) == hits + 1, "after forgetting, the sweep runs again");
        CHECK(r4.epicentre.value == r1.epicentre.value && r4.attenuation.value == r1.attenuation.value &&
                  r4.whole.value == r1.whole.value && r4.epicentre.n == r1.epicentre.n,
              "a sweep run again gives the copy's figures: fq2 %.17g vs %.17g", r4.epicentre.value, r1.epicentre.value);
        accuracy_result_free(&r1);
        accuracy_result_free(&r2);
        accuracy_result_free(&r3);
        accuracy_result_free(&r4);
        accuracy_close(&b);
    }

    /* The sweeps already run belong to the run's session (host/core/run.h), not to the process:
     * another session on the same device starts with none and runs the sweep itself, and its
     * count is its own; closing it leaves the first session's sweeps and count as they were. */
    {
        struct cl_session s2;
        char err[512];
        if ((rc = clsession_open(&s2, -1, -1, err, sizeof err)) != 0) return rc;
        struct accuracy_ctx c;
        struct accuracy_result r1, r2;
        if ((rc = accuracy_open(&c, &s2, "")) != 0) return rc;
        if ((rc = run(a, "fq2", 2, 200, 5, 256, &r1))) return rc;   /* remembered in a->s */
        long hits = accuracy_reused_sweeps(a->s);
        int kept = a->s->sweeps.count;
        CHECK(accuracy_reused_sweeps(&s2) == 0 && s2.sweeps.count == 0, "a new session holds no sweeps");
        if ((rc = run(&c, "fq2", 2, 200, 5, 256, &r2))) return rc;
        CHECK(accuracy_reused_sweeps(&s2) == 0 && s2.sweeps.count == 1, "the new session ran the sweep itself");
        CHECK(accuracy_reused_sweeps(a->s) == hits, "the first session's count is its own");
        CHECK(r2.epicentre.value == r1.epicentre.value, "the same sweep gives the same figure: %.17g vs %.17g",
              r2.epicentre.value, r1.epicentre.value);
        accuracy_result_free(&r1);
        accuracy_result_free(&r2);
        accuracy_close(&c);
        clsession_close(&s2);
        CHECK(s2.sweeps.count == 0 && s2.sweeps.items == NULL, "closing a session releases its sweeps");
        CHECK(a->s->sweeps.count == kept, "closing another session leaves this one's sweeps (%d)", kept);
    }
    return 0;
}

int main(void)
{
    test_grid_helpers();
    return test_accuracy_main(test_device);
}
