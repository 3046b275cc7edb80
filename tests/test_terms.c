/* test_terms.c - the built-in terms of a microfacet BRDF (kernels/brdf_model_list.h, family
 * term) at values worked by hand: exact dielectric Fresnel and Schlick's approximation at
 * index 1.5 (F0 = 0.04) at 0, 60, 80 and 89 degrees, and separable against height-correlated
 * Smith G of GGX at (theta_i, theta_o, alpha) = (60, 45, 0.5) degrees and in the mirrored
 * geometry of the rows at (60, 60, 1). The expected values are closed forms written below
 * from Snell's law and the Smith Lambda of GGX, not from brdf_models.h's forms. No device. */
#include "check.h"
#include "models.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"

static double pi(void) { return 3.14159265358979323846; }

/* A built-in row at cosine c and axis n, in double (the registry's host evaluation). */
static double row(const char *id, double c, double n)
{
    struct model_spec m;
    char err[256];
    if (model_spec_parse(id, &m, err, sizeof err) != 0) {
        CHECK(0, "%s: %s", id, err);
        return NAN;
    }
    return model_eval_host(&m, c, n);
}

/* Unpolarised Fresnel at index n from Snell's law, the angle given in degrees:
 * sin t = sin i / n, r_s = (cos i - n cos t) / (cos i + n cos t),
 * r_p = (n cos i - cos t) / (n cos i + cos t), F = (r_s^2 + r_p^2) / 2. */
static double snell_fresnel(double deg, double n)
{
    double i = deg * pi() / 180, st = sin(i) / n, ct = sqrt(1 - st * st);
    double rs = (cos(i) - n * ct) / (cos(i) + n * ct), rp = (n * cos(i) - ct) / (n * cos(i) + ct);
    return (rs * rs + rp * rp) / 2;
}

static void near(double a, double b, double tol, const char *what, double deg)
{
    CHECK(fabs(a - b) <= tol, "%s at %g deg: %.17g vs %.17g (tol %g)", what, deg, a, b, tol);
}

static void fresnel(void)
{
    CHECK_CASE("fresnel at index 1.5");
    /* 0 degrees: r_s = -r_p = (1 - 1.5) / (1 + 1.5) = -0.2: F = 0.2^2 = 0.04 = F0 */
    CHECK_NEAR(row("fresnel", 1.0, 1.5), 0.04, 1e-15, "F(0 deg)");
    CHECK_NEAR(row("fresnel-schlick", 1.0, 1.5), 0.04, 1e-15, "Schlick(0 deg) = F0");
    /* 60 degrees: sin t = (sqrt(3)/2) / 1.5 = 1/sqrt(3), cos t = sqrt(2/3);
       r_s = (1/2 - sqrt(3/2)) / (1/2 + sqrt(3/2)) = (1 - sqrt(6)) / (1 + sqrt(6)),
       r_p = (3/4 - sqrt(2/3)) / (3/4 + sqrt(2/3)): F = 0.0891867128...
       Schlick: 0.04 + 0.96 (1/2)^5 = 0.07 */
    double rs = (1 - sqrt(6.0)) / (1 + sqrt(6.0)), rp = (0.75 - sqrt(2.0 / 3)) / (0.75 + sqrt(2.0 / 3));
    double f60 = (rs * rs + rp * rp) / 2;
    CHECK_NEAR(f60, 0.0891867128, 1e-10, "the closed form at 60 deg");
    CHECK_NEAR(row("fresnel", 0.5, 1.5), f60, 1e-14, "F(60 deg)");
    CHECK_NEAR(row("fresnel-schlick", 0.5, 1.5), 0.07, 1e-15, "Schlick(60 deg)");
    /* 80 and 89 degrees, from Snell's law (values to 10 digits: 0.3877043547, 0.9041849498);
       Schlick 0.04 + 0.96 (1 - cos)^5: 0.4099100910, 0.9191018918 */
    static const struct { double deg, f, schlick; } at[] = { { 80, 0.3877043547, 0.4099100910 },
                                                             { 89, 0.9041849498, 0.9191018918 } };
    for (int k = 0; k < 2; ++k) {
        double c = cos(at[k].deg * pi() / 180);
        near(snell_fresnel(at[k].deg, 1.5), at[k].f, 1e-10, "Snell's form", at[k].deg);
        near(row("fresnel", c, 1.5), snell_fresnel(at[k].deg, 1.5), 1e-14, "F", at[k].deg);
        near(0.04 + 0.96 * pow(1 - c, 5), at[k].schlick, 1e-10, "Schlick's form", at[k].deg);
        near(row("fresnel-schlick", c, 1.5), at[k].schlick, 1e-10, "fresnel-schlick", at[k].deg);
    }
    /* Schlick's error against the exact term: -0.0192 at 60, +0.0222 at 80, +0.0149 at 89 deg */
    CHECK_NEAR(row("fresnel-schlick", 0.5, 1.5) - row("fresnel", 0.5, 1.5), 0.07 - 0.0891867128, 1e-10,
               "Schlick - F at 60 deg");
    /* grazing (90 deg) and below index 1 past the critical angle: total reflection, 1 (the row
       itself is 0 at c = 0, on the horizon: brdf_fresnel_dielectric gives the limit) */
    CHECK_NEAR(brdf_fresnel_dielectric(0.0, 1.5), 1.0, 1e-15, "F(90 deg) = 1");
    CHECK(row("fresnel", 0.0, 1.5) == 0.0, "the row is 0 on the horizon");
    /* n = 1/1.5 (glass to air): critical angle asin(1/1.5) = 41.8 deg; at 60 deg it reflects all */
    CHECK_NEAR(row("fresnel", 0.5, 1 / 1.5), 1.0, 1e-15, "total internal reflection");
    /* below the critical angle, F(i, 1/n) = F(t, n) with sin t = n sin i (the same interface) */
    double i = 30 * pi() / 180, t = asin(1.5 * sin(i));
    CHECK_NEAR(row("fresnel", cos(i), 1 / 1.5), snell_fresnel(t * 180 / pi(), 1.5), 1e-14, "reciprocity of F");
}

static void smith(void)
{
    CHECK_CASE("smith ggx");
    /* (theta_i, theta_o, alpha) = (60, 45 deg, 0.5): q(x) = sqrt(a^2 + (1 - a^2) x^2) = x sqrt(1 + a^2 tan^2)
       is sqrt(7)/4 at x = 1/2 and sqrt(10)/4 at x = sqrt(2)/2. Separable: G1(x) = 2x / (x + q):
       4 / (2 + sqrt(7)) and 4 / (2 + sqrt(5)), G = 16 / ((2 + sqrt 7)(2 + sqrt 5)) = 0.8130197652.
       Height-correlated: 1 / (1 + Lambda_i + Lambda_o), Lambda = (q/x - 1)/2, q/x = sqrt(7)/2 and
       sqrt(5)/2: 1 + Lambda_i + Lambda_o = (sqrt(7) + sqrt(5))/4, G = 4 / (sqrt(7) + sqrt(5)) = 0.8193666671. */
    double nl = 0.5, nv = sqrt(0.5);
    double sep = 16 / ((2 + sqrt(7.0)) * (2 + sqrt(5.0))), cor = 4 / (sqrt(7.0) + sqrt(5.0));
    CHECK_NEAR(sep, 0.8130197652, 1e-10, "separable closed form");
    CHECK_NEAR(cor, 0.8193666671, 1e-10, "correlated closed form");
    CHECK_NEAR(brdf_smith_ggx_separable(nl, nv, 0.5), sep, 1e-14, "separable G at (60, 45, 0.5)");
    CHECK_NEAR(brdf_smith_ggx_correlated(nl, nv, 0.5), cor, 1e-14, "correlated G at (60, 45, 0.5)");
    /* one direction at the normal: Lambda = 0 there, and the two forms are one (why L = N hides G) */
    CHECK_NEAR(brdf_smith_ggx_separable(1.0, nv, 0.5), brdf_smith_ggx_correlated(1.0, nv, 0.5), 1e-15,
               "equal with L = N");
    /* the rows: mirrored L and V at 60 deg, alpha = 1 (n = 0: sqrt(2/2)): q = 1, G1(1/2) = 2/3,
       separable (2/3)^2 = 4/9; Lambda(1/2) = 1/2, correlated 1 / (1 + 1/2 + 1/2) = 1/2 */
    CHECK_NEAR(row("smith-ggx", 0.5, 0.0), 4.0 / 9, 1e-15, "smith-ggx row at 60 deg, alpha 1");
    CHECK_NEAR(row("smith-ggx-hc", 0.5, 0.0), 0.5, 1e-15, "smith-ggx-hc row at 60 deg, alpha 1");
    /* n = 30: alpha = sqrt(2/32) = 1/4; at normal incidence both are 1 */
    CHECK_NEAR(row("smith-ggx", 1.0, 30), 1.0, 1e-15, "G(0 deg) = 1");
    CHECK_NEAR(row("smith-ggx-hc", 1.0, 30), 1.0, 1e-15, "G(0 deg) = 1 (correlated)");
}

int main(void)
{
    fresnel();
    smith();
    return check_summary();
}
