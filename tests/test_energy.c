/* test_energy.c - the device albedo quadrature and the reciprocity check against closed forms:
 *   - normalised Phong at normal incidence: R = N, (n+2)/(2 pi) 2 pi int_0^1 u^(n+1) du = 1;
 *   - normalised Blinn-Phong at normal incidence: 1 (Giesen's derivation: theta_o = 2 theta_h);
 *   - Beckmann D / (4 cos cos) at normal incidence: only theta_h < pi/4 reflects above the
 *     horizon, int D cos dw over it = 1 - exp(-tan^2(pi/4)/alpha^2) = 1 - exp(-(n+2)/2)
 *     (substitute u = tan^2); GGX: tan^2/(alpha^2 + tan^2) at pi/4 = (n+2)/(n+4);
 *   - D cos over the whole half-vector hemisphere: 1 for both (normalisation);
 *   - fq2n at normal incidence: 0.214 (0.807 + n) 2 pi int_0^1 (k(u-1)+1)^2 u du, k = 0.448n + 0.099,
 *     the quadratic zeroed past u0 = 1 - 1/k: with t = 1 - u, int_0^min(1,1/k) (1-kt)^2 (1-t) dt =
 *     1/2 - k/3 + k^2/12 (k <= 1) or 1/(3k) - 1/(12k^2) (k >= 1), worked by hand;
 *   - normalised Phong at 30 degrees, n = 1000: the lobe is far from the horizon, the azimuthal
 *     part of N.V integrates to 0, so the albedo is N.R = cos 30 deg;
 *   - reciprocity: cos psi = 2(N.L)(N.V) - L.V and N.H are symmetric in L and V, so in double
 *     f(L,V) = f(V,L) up to rounding for every registry model; Cook-Torrance's D F G / (4 N.L N.V)
 *     is symmetric too (F reads V.H = L.H, G = G1(L) G1(V)), so the image pass, shaded with eye
 *     and light swapped, gives the same S up to float rounding of its products. */
#include "check.h"
#include "energy.h"
#include "exitcodes.h"
#include "models.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>

static const double pi = 3.14159265358979323846;

static double moment(double k) { return k <= 1 ? 0.5 - k / 3 + k * k / 12 : 1 / (3 * k) - 1 / (12 * k * k); }

/* The albedos at normal incidence worked out in closed form above, as functions of n. */
static double one(double n) { (void)n; return 1.0; }
static double beckmann_normal(double n) { return 1.0 - exp(-(n + 2) / 2); }
static double ggx_normal(double n) { return (n + 2) / (n + 4); }
static double fq2n_normal(double n) { return 0.214 * (0.807 + n) * 2 * pi * moment(0.448 * n + 0.099); }

static const struct {
    const char *model;
    int mode;
    double (*expect)(double n);
    const char *what;
} normal_incidence[] = {
    { "phongn", ALBEDO_PSI, one, "phongn albedo at normal incidence" },
    { "blinnn", ALBEDO_HALF, one, "blinnn albedo at normal incidence (Giesen)" },
    { "beckmann", ALBEDO_MICRO, beckmann_normal, "beckmann albedo at normal incidence" },
    { "beckmann", ALBEDO_DCOS, one, "beckmann: int D cos = 1" },
    { "ggx", ALBEDO_MICRO, ggx_normal, "ggx albedo at normal incidence" },
    { "ggx", ALBEDO_DCOS, one, "ggx: int D cos = 1" },
    { "fq2n", ALBEDO_PSI, fq2n_normal, "fq2n albedo at normal incidence (polynomial integral)" },
};

int main(void)
{
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc)
        return test_summary(rc);
    struct integrate_ctx ic;
    CHECK(integrate_open(&ic, &s) == 0, "integrate.cl builds");

    enum { K = 5 };
    const double ns[K] = { 2, 7, 50, 300, 1000 }, zero[K] = { 0, 0, 0, 0, 0 };
    double out[K];
    const double tol = 2e-5;   /* float quadrature on the device */

    for (size_t t = 0; t < sizeof normal_incidence / sizeof normal_incidence[0]; ++t) {
        struct model_spec m = spec(normal_incidence[t].model);
        CHECK(albedo_device(&ic, &m, normal_incidence[t].mode, ns, zero, K, out) == 0, "%s: runs",
              normal_incidence[t].what);
        for (int i = 0; i < K; ++i)
            CHECK_NEAR(out[i], normal_incidence[t].expect(ns[i]), tol, normal_incidence[t].what);
    }

    double n1000 = 1000, t30 = 30 * pi / 180;
    struct model_spec m = spec("phongn");
    CHECK(albedo_device(&ic, &m, ALBEDO_PSI, &n1000, &t30, 1, out) == 0, "phongn at 30 degrees runs");
    CHECK_NEAR(out[0], cos(t30), tol, "phongn albedo at 30 degrees, n = 1000: N.R");
    m = spec("blinnn");
    double tilt[3] = { 20 * pi / 180, 45 * pi / 180, 70 * pi / 180 }, nn[3] = { 100, 100, 100 };
    CHECK(albedo_device(&ic, &m, ALBEDO_HALF, nn, tilt, 3, out) == 0, "blinnn oblique runs");
    CHECK(out[0] < 1 + tol && out[1] < out[0] && out[2] < out[1], "blinnn albedo falls with incidence (%g %g %g)",
          out[0], out[1], out[2]);

    /* Every closed form the albedo module itself states agrees with the device at n = 2. */
    double two = 2, z = 0;
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *info = models_at(i);
        int mode = albedo_mode_of(info);
        if (mode < 0)
            continue;
        struct model_spec ms;
        model_spec_default(info, &ms);
        double cf;
        const char *why;
        if (!albedo_closed_form_normal(&ms, mode, 2.0, &cf, &why))
            continue;
        CHECK(albedo_device(&ic, &ms, mode, &two, &z, 1, out) == 0, "%s albedo runs", info->id);
        CHECK_NEAR(out[0], cf, tol, info->id);
    }

    /* Reciprocity for every registry model. */
    for (int i = 0; i < models_count(); ++i) {
        struct model_spec ms;
        model_spec_default(models_at(i), &ms);
        struct recip_worst dev, host;
        CHECK(reciprocity_check(&ic, &ms, 2048, &dev, &host) == 0, "reciprocity runs for %s", ms.label);
        CHECK(host.diff <= 1e-9, "%s: double f(L,V) - f(V,L) = %.3g of peak", ms.label, host.diff);
        /* the float difference is rounding: no larger than twice a single value's float error */
        CHECK(dev.diff <= 2 * dev.eval_error + 1e-7, "%s: float asymmetry %.3g vs evaluation error %.3g", ms.label,
              dev.diff, dev.eval_error);
    }
    struct recip_pass_summary pass[ENERGY_MAX_MODELS];
    int npass = 0;
    CHECK(reciprocity_image_pass(&s, 1024, pass, ENERGY_MAX_MODELS, &npass) == 0 && npass > 0,
          "image-pass reciprocity runs");
    int ct = 0;
    for (int i = 0; i < npass; ++i) {
        ct += pass[i].mode >= 2;
        CHECK(pass[i].lit > 100, "%s: pairs lit both ways (%ld)", pass[i].spec.label, pass[i].lit);
        CHECK(pass[i].host_worst <= 1e-9, "%s: image pass in double, relative difference %.3g", pass[i].spec.label,
              pass[i].host_worst);
        /* float: a few rounding steps of the products E (N.L) ks S, each 2^-24 relative */
        CHECK(pass[i].device_worst <= 1e-5, "%s: image pass in float, relative difference %.3g", pass[i].spec.label,
              pass[i].device_worst);
    }
    CHECK(ct >= 1, "the image passes' Cook-Torrance models are covered (%d)", ct);
    integrate_close(&ic);
    clsession_close(&s);
    return check_summary();
}
