/* test_models.c - every model's identities in double (the host reference) and every model
 * on the device against the double reference at edge and random points.
 * Expected values come from closed forms and identities named beside each check. */
#include "accuracy.h"
#include "check.h"
#include "exitcodes.h"
#include "models.h"
#include "testutil.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 2 pi * integral over [0, pi/2] of g(x) cos x sin x dx, by GSL adaptive quadrature. */
struct hemi { const struct model_spec *m; double n; int half_angle; };
static double hemi_integrand(double x, void *p)
{
    const struct hemi *h = p;
    /* half_angle: a Blinn lobe seen at normal incidence, theta_h = theta_o / 2. */
    double c = cos(h->half_angle ? x / 2 : x);
    return model_eval_host(h->m, c, h->n) * cos(x) * sin(x);
}
static double hemisphere_integral(const struct model_spec *m, double n, int half_angle)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    struct hemi h = { m, n, half_angle };
    gsl_function f = { hemi_integrand, &h };
    double result = NAN, abserr;
    gsl_integration_qag(&f, 0, M_PI / 2, 1e-13, 1e-12, 1000, GSL_INTEG_GAUSS61, w, &result, &abserr);
    gsl_integration_workspace_free(w);
    return 2 * M_PI * result;
}

/* D(theta_h) cos(theta_h) over the hemisphere of microfacet normals is 1 for a normalised
 * distribution (the definition of a microfacet D). */
static double d_integrand(double x, void *p)
{
    const struct hemi *h = p;
    return model_eval_host(h->m, cos(x), h->n) * cos(x) * sin(x);
}
static double d_projected_area(const struct model_spec *m, double n)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    struct hemi h = { m, n, 0 };
    gsl_function f = { d_integrand, &h };
    double result = NAN, abserr;
    gsl_integration_qag(&f, 0, M_PI / 2, 1e-13, 1e-12, 1000, GSL_INTEG_GAUSS61, w, &result, &abserr);
    gsl_integration_workspace_free(w);
    return 2 * M_PI * result;
}

static void test_host_identities(void)
{
    struct model_spec cq2 = spec("cq2"), lyon1 = spec("lyon:k=1"), phong = spec("phong");
    /* cq2 at n = 2 is (c - 1 + 1)^2 = c^2 = the Phong lobe at n = 2 (docs/definitions.md's formula). */
    for (double c = 0; c <= 1.0; c += 1.0 / 64)
        CHECK_NEAR(model_eval_host(&cq2, c, 2.0), c * c, 1e-15, "cq2(c, 2) = c^2");
    /* Lyon with k = 1 is (1 - n(1-c)/2)^2 = cq2 (docs/definitions.md). */
    for (double n = 2; n <= 1000; n *= 1.7)
        for (double c = 0; c <= 1.0; c += 1.0 / 128)
            CHECK_NEAR(model_eval_host(&lyon1, c, n), model_eval_host(&cq2, c, n), 1e-14, "lyon:k=1 = cq2");
    /* Lyon with k squarings at 1 - c = 2^k/(n * 2) is (1/2)^(2^k), worked by hand. */
    struct model_spec lyon3 = spec("lyon:k=3");
    CHECK_NEAR(model_eval_host(&lyon3, 1 - 4.0 / 100, 100), pow(0.5, 8), 1e-15, "lyon:k=3 at half base");
    /* f_Q equals c^n exactly where c^n = Q, i.e. at c = Q^(1/n) (paper 2's construction). */
    const double qs[] = { 0.2, 0.5, 0.64, 0.9 };
    for (int q = 0; q < 4; ++q) {
        char text[64];
        snprintf(text, sizeof text, "fq:Q=%g", qs[q]);
        struct model_spec fq = spec(text);
        for (double n = 2; n <= 1000; n *= 2.3) {
            double c = pow(qs[q], 1 / n);
            CHECK_NEAR(model_eval_host(&fq, c, n), qs[q], 1e-12, text);
            CHECK_NEAR(model_eval_host(&phong, c, n), qs[q], 1e-12, "phong at c = Q^(1/n)");
        }
    }
    /* Every quadratic model is 0 past its root and never rises again: the root of
       (k(c-1)+1)^2 is c0 = 1 - 1/k (for fq2: (448n - 901)/(448n + 99), docs/definitions.md). */
    const char *quads[] = { "cq2", "fvol", "fvol64", "fq2", "fq:Q=0.64", "lyon:k=2", "lyon:k=4", "quad:a=0.45,b=0.1" };
    for (int i = 0; i < 8; ++i) {
        struct model_spec m = spec(quads[i]);
        for (double n = 3; n <= 1000; n *= 1.9) {
            double prev = INFINITY;
            int rises = 0, nonzero_past_root = 0;
            double root = NAN;
            for (int j = 4096; j >= 0; --j) {    /* c from 1 down to 0 */
                double c = j / 4096.0, f = model_eval_host(&m, c, n);
                if (f > prev)
                    rises = 1;
                if (f == 0 && isnan(root))
                    root = c;
                if (!isnan(root) && f != 0)
                    nonzero_past_root = 1;
                prev = f;
            }
            CHECK(!rises && !nonzero_past_root, "%s at n = %g: rises %d, nonzero past root %d", quads[i], n, rises,
                  nonzero_past_root);
        }
    }
    struct model_spec fq2 = spec("fq2");
    for (double n = 3; n <= 1000; n *= 3) {
        double root = (448 * n - 901) / (448 * n + 99);
        CHECK(model_eval_host(&fq2, root - 1e-9, n) == 0, "fq2 zero just past its root at n = %g", n);
        CHECK(model_eval_host(&fq2, root + 1e-6, n) > 0, "fq2 positive before its root at n = %g", n);
    }
    /* The normalised references integrate to 1: 2 pi int (n+2)/(2 pi) c^n cos sin = 1 in closed
       form; Giesen's Blinn-Phong factor makes the lobe at normal incidence (theta_h = theta_o/2)
       integrate to 1; Beckmann and GGX D have unit projected area (microfacet definition). */
    struct model_spec phongn = spec("phongn"), blinnn = spec("blinnn"), beck = spec("beckmann"), ggx = spec("ggx");
    const double ns[] = { 2, 7.5, 64, 1000 };
    for (int i = 0; i < 4; ++i) {
        CHECK_NEAR(hemisphere_integral(&phongn, ns[i], 0), 1.0, 1e-9, "phongn integrates to 1");
        CHECK_NEAR(hemisphere_integral(&blinnn, ns[i], 1), 1.0, 1e-9, "blinnn integrates to 1");
        CHECK_NEAR(d_projected_area(&beck, ns[i]), 1.0, 1e-9, "Beckmann D projected area");
        CHECK_NEAR(d_projected_area(&ggx, ns[i]), 1.0, 1e-9, "GGX D projected area");
    }
    /* Beckmann and GGX with alpha(n) = sqrt(2/(n+2)) peak at 1/(pi alpha^2) = (n+2)/(2 pi),
       the normalised Blinn-Phong D's peak (worked by hand from the formulas at c = 1). */
    CHECK_NEAR(model_eval_host(&beck, 1.0, 98), 100 / (2 * M_PI), 1e-12, "Beckmann peak");
    CHECK_NEAR(model_eval_host(&ggx, 1.0, 98), 100 / (2 * M_PI), 1e-12, "GGX peak");
    /* Schlick at c = 1 is 1 and at c = 0 is 0 (c / (n - n c + c)). */
    struct model_spec sch = spec("schlick");
    CHECK_NEAR(model_eval_host(&sch, 1.0, 50), 1.0, 0, "schlick(1)");
    CHECK_NEAR(model_eval_host(&sch, 0.0, 50), 0.0, 0, "schlick(0)");
}

static void test_parsing(void)
{
    struct model_spec s;
    char err[512];
    CHECK(model_spec_parse("fq:Q=0.7", &s, err, sizeof err) == 0 && s.params[0] == 0.7, "fq:Q=0.7");
    CHECK(model_spec_parse("lyon:k=4", &s, err, sizeof err) == 0 && s.params[0] == 4, "lyon:k=4");
    CHECK(model_spec_parse("lyon:k=2.5", &s, err, sizeof err) == EXIT_USAGE && strstr(err, "integer"), "%s", err);
    CHECK(model_spec_parse("fq:Q=1.5", &s, err, sizeof err) == EXIT_USAGE && strstr(err, "[1e-06, 0.999999]"), "%s", err);
    CHECK(model_spec_parse("fq:R=0.5", &s, err, sizeof err) == EXIT_USAGE && strstr(err, "no parameter 'R'"), "%s", err);
    CHECK(model_spec_parse("nosuch", &s, err, sizeof err) == EXIT_USAGE && strstr(err, "unknown model 'nosuch'"), "%s", err);
    CHECK(model_spec_parse("cq2:k=1", &s, err, sizeof err) == EXIT_USAGE && strstr(err, "takes no parameters"), "%s", err);
    CHECK(model_spec_parse("fq:Q=nan", &s, err, sizeof err) == EXIT_USAGE, "NaN parameter");
    struct model_spec list[8];
    CHECK(model_spec_list_parse("cq2,quad:a=0.45,b=0.2,fq2", list, 8, err, sizeof err) == 3 &&
              list[1].params[0] == 0.45 && list[1].params[1] == 0.2 && list[2].info->kernel_id == models_find("fq2")->kernel_id,
          "list with a two-parameter model: %s", err);
    int all = model_spec_list_parse("all", list, 8, err, sizeof err);
    CHECK(all == 8, "8 slots filled by 'all' (got %d)", all);
}

/* Every model on the device (float16 path) against the double reference. Bound: 1e-5 of
 * the reference lobe's peak, two orders below the 4th digit of any figure we report
 * (the smallest reported errors are about 1e-2). */
static int test_device(struct accuracy_ctx *a)
{
    int rc = 0;
    enum { N = 1024 };
    static float c[N], n[N], out[N];
    for (int i = 0; i < models_count(); ++i) {
        struct model_spec m, ref;
        model_spec_default(models_at(i), &m);
        model_reference_spec(&m, &ref);
        unsigned state = 12345u + (unsigned)i;
        for (int k = 0; k < N; ++k) {
            state = state * 1664525u + 1013904223u;
            double nv = 2 + (state >> 8) % 999;
            double cv;
            switch (k % 4) {
            case 0: cv = 1.0; break;                                   /* the peak */
            case 1: cv = 0.0; break;                                   /* grazing */
            case 2: cv = 1.0 - 1.0 / (0.5 * nv); break;                /* near quadratic roots */
            default: cv = cos(((state >> 4) % 100000) / 100000.0 * 4 * acos(exp(-0.511 / nv)));
            }
            c[k] = (float)fmax(cv, 0.0);
            n[k] = (float)nv;
        }
        if ((rc = accuracy_probe(a, &m, c, n, N, out)) != 0)
            break;
        double worst = 0;
        int worst_k = 0;
        for (int k = 0; k < N; ++k) {
            double host = model_eval_host(&m, c[k], n[k]);
            double peak = model_eval_host(&ref, 1.0, n[k]);
            double d = fabs(out[k] - host) / peak;
            /* a NaN stays the worst value: a later finite d must not replace it */
            if (!isnan(worst) && !(d <= worst)) {
                worst = d;
                worst_k = k;
            }
        }
        CHECK(worst <= 1e-5, "%s: device vs double %.3g of the peak at c = %.9g, n = %g", m.label, worst,
              c[worst_k], n[worst_k]);
    }
    return rc;
}

int main(void)
{
    test_host_identities();
    test_parsing();
    return test_accuracy_main(test_device);
}
