/* test_model_table.c - every model's formula against a second writing of it (lobe_formulas.h,
 * from docs/definitions.md's tables, not from kernels/brdf_models.h), in double, at a spread of (c, n):
 * the host reference must agree to 1e-12 of the model's peak and the device (float16, through
 * accuracy_probe) to 1e-5 of it. The device-vs-host tests cannot see a constant changed in
 * the header, since both sides include it; this one can (0.463 -> 0.464 moves fvol by about
 * 1e-3 of its peak where n (1 - c) = 1). Every registry model must have an entry in the
 * table: a model without one is a failure, since nothing independent checks its formula. */
#include "accuracy.h"
#include "check.h"
#include "exitcodes.h"
#include "lobe_formulas.h"
#include "models.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Parameter sets beyond each model's defaults. */
static const char *const extra_specs[] = { "lyon:k=1", "lyon:k=3", "lyon:k=5", "fq:Q=0.3", "fq:Q=0.9",
                                           "quad:a=0.45,b=0.1", "quad:a=0.3,b=1.5", "he:material=1",
                                           "he:material=2", "he:material=3", "ct-ggx:F0=0.04", "brady:a=0.5,b=2" };

enum { NS = 7, US = 13, POINTS = NS * US };
static const double ns[NS] = { 2, 3.5, 16, 57, 256, 1000, 20000 };

/* The points: c = 1 - s with n s = u spread over the lobe and the quadratics' roots (u about
 * 2), plus c = 0, 0.5, 0.93 and a negative cosine (treated as 0: brdf_models.h's convention,
 * which the image passes rely on past the terminator); built as float values so that host and
 * device agree on the input. */
static void points(float *c, float *n)
{
    static const double us[US] = { 0, 0.01, 0.2, 0.511, 1, 1.5, 2.1, 3, 4.5 };
    int k = 0;
    for (int i = 0; i < NS; ++i)
        for (int j = 0; j < US; ++j, ++k) {
            double cv = j < 9 ? 1 - us[j] / ns[i] : (j == 9 ? 0.0 : (j == 10 ? 0.5 : (j == 11 ? 0.93 : -0.25)));
            c[k] = (float)(j < 9 ? fmax(cv, 0.0) : cv);
            n[k] = (float)ns[i];
        }
}

static double table(const struct model_spec *m, double c, double n)
{
    return lf_eval(m->info->id, c, 1 - c, n, m->params[0], m->params[1]);
}

static int check_spec(const struct model_spec *m, struct accuracy_ctx *dev)
{
    float c[POINTS], n[POINTS], out[POINTS];
    points(c, n);
    double worst_host = 0, worst_dev = 0;
    int at_host = 0, at_dev = 0;
    int rc = dev ? accuracy_probe(dev, m, c, n, POINTS, out) : 0;
    for (int k = 0; k < POINTS; ++k) {
        double want = table(m, c[k], n[k]);
        double peak = fmax(fabs(table(m, 1.0, n[k])), 1e-300);
        double dh = fabs(model_eval_host(m, c[k], n[k]) - want) / peak;
        if (!(dh <= worst_host))
            worst_host = dh, at_host = k;
        if (dev && rc == 0) {
            double dd = fabs(out[k] - want) / peak;
            if (!(dd <= worst_dev))
                worst_dev = dd, at_dev = k;
        }
    }
    CHECK(worst_host <= 1e-12, "%s: host reference vs the formula table: %.3g of the peak at c = %.9g, n = %g",
          m->label, worst_host, c[at_host], n[at_host]);
    if (dev) {
        CHECK(rc == 0, "%s: device probe ran (rc %d)", m->label, rc);
        CHECK(worst_dev <= 1e-5, "%s: device vs the formula table: %.3g of the peak at c = %.9g, n = %g", m->label,
              worst_dev, c[at_dev], n[at_dev]);
    }
    return rc;
}

/* The epicentre's end as the host computes it (accuracy.h's zone geometry) against docs/definitions.md's
 * x_e(n) = acos(exp(-0.511/n)) written here. */
static void check_zone_end(void)
{
    for (int i = 0; i < NS; ++i) {
        double x = zone_epicentre_end(ns[i]);
        CHECK(fabs(x - lf_epicentre_end_x(ns[i])) <= 1e-12 * lf_epicentre_end_x(ns[i]),
              "epicentre end at n = %g: %.15g vs acos(exp(-0.511/n)) = %.15g", ns[i], x, lf_epicentre_end_x(ns[i]));
    }
}

static void run_all(struct accuracy_ctx *dev)
{
    for (int i = 0; i < models_count(); ++i) {
        struct model_spec m;
        model_spec_default(models_at(i), &m);
        double probe = table(&m, 0.9, 10);
        CHECK(!isnan(probe), "model '%s' has no entry in tests/lobe_formulas.h: its formula is checked by nothing "
                             "independent", m.label);
        if (!isnan(probe))
            check_spec(&m, dev);
    }
    for (size_t i = 0; i < sizeof extra_specs / sizeof extra_specs[0]; ++i) {
        struct model_spec m = spec(extra_specs[i]);
        check_spec(&m, dev);
    }
}

int main(void)
{
    check_zone_end();
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == EXIT_NO_DEVICE)
        run_all(NULL);   /* the host checks only */
    if (rc)
        return test_summary(rc);
    struct accuracy_ctx a;
    int arc = accuracy_open(&a, &s, "");
    CHECK(arc == 0, "accuracy_open (rc %d)", arc);
    if (arc == 0) {
        run_all(&a);
        accuracy_close(&a);
    }
    clsession_close(&s);
    return check_summary();
}
