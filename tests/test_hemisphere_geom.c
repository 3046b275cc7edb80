/* test_hemisphere_geom.c - the hemisphere sweep's geometry and axis conversions, no device:
 * (theta_h, theta_d, phi_d) -> (L, V) of host/measure/accuracy/hemisphere.c against host/core/merl.c's
 * merl_half_diff (the MERL lookup's conversion, its inverse) at random angles; the identities
 * of Rusinkiewicz's coordinates (N.H = cos theta_h, V.H = cos theta_d, L.V = cos 2 theta_d,
 * unit vectors); the conversions of docs/definitions.md at values worked by hand. */
#include "check.h"
#include "hemisphere.h"
#include "lcg.h"
#include "merl.h"

#include <math.h>
#include <stdint.h>

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The angle between a and b on the circle, in [0, pi]. */
static double circle_diff(double a, double b)
{
    double d = fmod(fabs(a - b), 2 * M_PI);
    return d > M_PI ? 2 * M_PI - d : d;
}

static void test_against_merl(void)
{
    CHECK_CASE("half/difference -> (L, V) against merl_half_diff");
    uint64_t state = 12345;
    const double N[3] = { 0, 0, 1 };
    int worst_ok = 1;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        /* away from the poles of the coordinates, where an angle is undefined (theta_h = 0 leaves
           phi_h free, theta_d = 0 leaves phi_d free) */
        double th = 0.01 + (M_PI / 2 - 0.02) * lcg_unit(&state);
        double td = 0.01 + (M_PI / 2 - 0.02) * lcg_unit(&state);
        double pd = 0.01 + (M_PI - 0.02) * lcg_unit(&state);
        double L[3], V[3], th2, td2, pd2;
        hemisphere_dirs(th, td, pd, L, V);
        merl_half_diff(L, V, N, &th2, &td2, &pd2);
        double d = fmax(fabs(th - th2), fmax(fabs(td - td2), circle_diff(pd, pd2)));
        if (d > worst)
            worst = d;
        /* unit vectors and the coordinates' identities, written here from their definitions */
        double H[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] };
        double hn = sqrt(dot(H, H));
        if (fabs(dot(L, L) - 1) > 1e-14 || fabs(dot(V, V) - 1) > 1e-14 || fabs(H[2] / hn - cos(th)) > 1e-14 ||
            fabs(dot(V, H) / hn - cos(td)) > 1e-14 || fabs(dot(L, V) - cos(2 * td)) > 1e-14)
            worst_ok = 0;
    }
    CHECK(worst < 1e-9, "largest angle difference %.3g rad over 20000 random (theta_h, theta_d, phi_d)", worst);
    CHECK(worst_ok, "unit L and V, N.H = cos theta_h, V.H = cos theta_d, L.V = cos 2 theta_d at every pair");
    /* one pair by hand: theta_h = 0 puts H on N, so L = D = (sin td cos pd, sin td sin pd, cos td) */
    double L[3], V[3];
    hemisphere_dirs(0, M_PI / 3, M_PI / 2, L, V);
    CHECK(fabs(L[0]) < 1e-15 && fabs(L[1] - sqrt(3) / 2) < 1e-15 && fabs(L[2] - 0.5) < 1e-15 &&
          fabs(V[1] + sqrt(3) / 2) < 1e-15 && fabs(V[2] - 0.5) < 1e-15,
          "theta_h = 0, theta_d = pi/3, phi_d = pi/2: L = (%g, %g, %g), V = (%g, %g, %g)", L[0], L[1], L[2], V[0],
          V[1], V[2]);
}

static void test_conversions(void)
{
    CHECK_CASE("axis conversions");
    /* alpha = sqrt(2/(n+2)): n = 2 -> sqrt(1/2); n = 98 -> sqrt(0.02) */
    CHECK_NEAR(hemi_to_alpha(HQ_N, 2), sqrt(0.5), 1e-15, "alpha(n = 2)");
    CHECK_NEAR(hemi_to_alpha(HQ_N, 98), sqrt(0.02), 1e-15, "alpha(n = 98)");
    /* alpha = r^2: r = 0.5 -> 0.25; Beckmann m = alpha */
    CHECK_NEAR(hemi_to_alpha(HQ_ROUGHNESS, 0.5), 0.25, 0, "alpha(roughness = 0.5)");
    CHECK_NEAR(hemi_to_alpha(HQ_M, 0.3), 0.3, 0, "alpha(m = 0.3)");
    /* back: alpha = 0.5 -> n = 2/0.25 - 2 = 6, roughness = sqrt(0.5) */
    CHECK_NEAR(hemi_from_alpha(HQ_N, 0.5), 6, 1e-14, "n(alpha = 0.5)");
    CHECK_NEAR(hemi_from_alpha(HQ_ROUGHNESS, 0.5), sqrt(0.5), 1e-15, "roughness(alpha = 0.5)");
    /* roughness of Phong's n (the form): r = (2/(n+2))^(1/4); n = 30 -> (1/16)^(1/4) = 0.5 */
    CHECK_NEAR(hemi_from_alpha(HQ_ROUGHNESS, hemi_to_alpha(HQ_N, 30)), 0.5, 1e-15, "roughness(n = 30)");
}

static void test_axis_parse(void)
{
    CHECK_CASE("--axis and --param parsing");
    struct hemi_axis a;
    char err[256];
    CHECK(hemisphere_axis_parse("roughness=0.1:0.9", &a, err, sizeof err) == 0 && a.q == HQ_ROUGHNESS &&
          a.min == 0.1 && a.max == 0.9, "roughness=0.1:0.9 -> %d [%g, %g]", (int)a.q, a.min, a.max);
    CHECK(hemisphere_axis_parse("F0", &a, err, sizeof err) == 0 && a.q == HQ_PARAM && isnan(a.min), "F0");
    CHECK(hemisphere_axis_parse("m=0.5:0.1", &a, err, sizeof err) == 2, "a reversed range is refused");
    CHECK(hemisphere_axis_parse("9x", &a, err, sizeof err) == 2, "a name that is no identifier is refused");
    struct hemi_fixed f[HEMI_MAX_FIXED];
    int count = 0;
    CHECK(hemisphere_fixed_parse("F0=0.04", f, &count, err, sizeof err) == 0 && count == 1 && f[0].value == 0.04,
          "F0=0.04");
    CHECK(hemisphere_fixed_parse("F0=", f, &count, err, sizeof err) == 2 && count == 1, "F0= is refused");
}

int main(void)
{
    test_against_merl();
    test_conversions();
    test_axis_parse();
    return check_summary();
}
