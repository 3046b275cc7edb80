/* test_physical.c - the physically based BRDFs of kernels/brdf_models.h in double (the host
 * reference): Cook-Torrance in full, the printed Brady form, and He et al. 1991 with its parts
 * (Lambert W, complex Fresnel, shadowing, the directional-diffuse sum). Expected values come
 * from closed forms, limits and the formulas written a second time here, each named beside
 * its check; GSL supplies the independent pieces (Lambert W, a root finder). */
#include "check.h"
#include "exitcodes.h"
#include "models.h"
#include "pbcost.h"
#include "render.h"
#include "testutil.h"

#include <complex.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_lambert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static void unit3(double *v)
{
    double l = sqrt(dot3(v, v));
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}
/* A direction at polar angle theta (degrees) and azimuth phi (degrees) around N = z. */
static void dir3(double theta, double phi, double *v)
{
    double t = theta * M_PI / 180, p = phi * M_PI / 180;
    v[0] = sin(t) * cos(p);
    v[1] = sin(t) * sin(p);
    v[2] = cos(t);
}

/* The z0 equation of He et al. 1991, sqrt(pi/2) z = sigma0/4 (Ki + Kr) exp(-z^2 / (2 sigma0^2)),
 * solved here by GSL's Brent root finder (independent of the model's Lambert-W form). */
struct z0_eq { double sigma0, ksum; };
static double z0_residual(double z, void *p)
{
    const struct z0_eq *e = p;
    return sqrt(M_PI / 2) * z - e->sigma0 / 4 * e->ksum * exp(-z * z / (2 * e->sigma0 * e->sigma0));
}
static double z0_brent(double sigma0, double ksum)
{
    struct z0_eq e = { sigma0, ksum };
    gsl_function f = { z0_residual, &e };
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    double hi = sigma0 * ksum + 1e-12;
    gsl_root_fsolver_set(s, &f, 0.0, hi);
    double z = 0;
    for (int i = 0; i < 200; ++i) {
        gsl_root_fsolver_iterate(s);
        z = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0, 1e-15) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return z;
}

/* He's directional-diffuse term written out from the paper's definitions with explicit wave
 * and polarisation vectors: k_i = -L, k_r = V, s = k x n / |k x n|, p = s x k, and
 * G = (v.v / v_z)^2 / |k_r x k_i|^4 [(s_r.k_i)^2 + (p_r.k_i)^2] [(s_i.k_r)^2 + (p_i.k_r)^2];
 * the sum with tgamma, 400 terms. */
static double fresnel_unpolarised_test(double c, double n, double k);
static double he_dd_reference(const double *L, const double *V, double lambda, double sigma0, double tau, double n_re,
                              double n_im)
{
    const double N[3] = { 0, 0, 1 };
    double ki[3] = { -L[0], -L[1], -L[2] }, kr[3] = { V[0], V[1], V[2] };
    double ci = dot3(N, L), cr = dot3(N, V);
    double kwave = 2 * M_PI / lambda;
    double ti = sqrt(1 - ci * ci) / ci, tr = sqrt(1 - cr * cr) / cr;
    double Ki = ti * erfc(tau / (2 * sigma0 * ti)), Kr = tr * erfc(tau / (2 * sigma0 * tr));
    double z0 = z0_brent(sigma0, Ki + Kr);
    double sigma = sigma0 / sqrt(1 + z0 * z0 / (sigma0 * sigma0));
    double v[3] = { kr[0] - ki[0], kr[1] - ki[1], kr[2] - ki[2] };
    double g = pow(kwave * sigma * v[2], 2);
    double vxy2 = kwave * kwave * (v[0] * v[0] + v[1] * v[1]);
    double si[3], sr[3], pi_[3], pr[3], x[3];
    cross3(ki, N, si);
    unit3(si);
    cross3(si, ki, pi_);
    cross3(kr, N, sr);
    unit3(sr);
    cross3(sr, kr, pr);
    cross3(kr, ki, x);
    double x2 = dot3(x, x);
    double bracket_r = pow(dot3(sr, ki), 2) + pow(dot3(pr, ki), 2);
    double bracket_i = pow(dot3(si, kr), 2) + pow(dot3(pi_, kr), 2);
    double G = pow(dot3(v, v) / v[2], 2) / (x2 * x2) * bracket_r * bracket_i;
    double sum = 0;
    for (int m = 1; m <= 400; ++m)
        sum += exp(m * log(g) - g - lgamma(m + 1.0)) / m * exp(-vxy2 * tau * tau / (4.0 * m));
    double D = M_PI * M_PI * tau * tau / (4 * lambda * lambda) * sum;
    /* shadowing: Smith's function for a Gaussian surface, written from erfc again */
    double S = 1;
    for (int j = 0; j < 2; ++j) {
        double c = j ? cr : ci, cot = c / sqrt(1 - c * c), e = tau * cot / (2 * sigma0);
        double lam = 0.5 * (exp(-e * e) / (sqrt(M_PI) * e) - erfc(e));
        S *= (1 - 0.5 * erfc(e)) / (lam + 1);
    }
    double b = sqrt(dot3(v, v)) / 2;   /* cosine of the bisector angle */
    double F = fresnel_unpolarised_test(b, n_re, n_im);
    return F * G * S / (M_PI * ci * cr) * D;
}

/* Fresnel for unpolarised light with a complex index m = n + ik, from complex arithmetic:
 * r_s = (cos - m cos_t) / (cos + m cos_t), r_p = (m cos - cos_t) / (m cos + cos_t),
 * cos_t = sqrt(1 - sin^2 / m^2) (principal root). */
static double fresnel_unpolarised_test(double c, double n, double k)
{
    double complex m = n + k * I;
    double s2 = 1 - c * c;
    double complex ct = csqrt(1 - s2 / (m * m));
    double complex rs = (c - m * ct) / (c + m * ct), rp = (m * c - ct) / (m * c + ct);
    return 0.5 * (pow(cabs(rs), 2) + pow(cabs(rp), 2));
}

/* compare's rule as the cost claims use it (compare_speed_rule), on samples built here: x is y
   scaled by a known factor, so the Hodges-Lehmann ratio is that factor exactly (every pairwise
   difference of logarithms is shifted by its log, and the unscaled differences are symmetric
   about 0); the verdict follows from the factor against the 10% minimum effect, and from the
   spread against the band. */
static void test_speed_rule(void)
{
    const double base[9] = { 1.0, 1.01, 0.99, 1.02, 0.98, 1.0, 1.005, 0.995, 1.0 };
    double y[9], half[9], near[9], wide[9], wide2[9];
    const double spread[9] = { 0.5, 2.0, 1.0, 0.6, 1.8, 0.7, 1.5, 0.9, 1.2 };
    for (int i = 0; i < 9; ++i) {
        y[i] = 3.0 * base[i];
        half[i] = 0.5 * y[i];
        near[i] = 1.05 * y[i];
        wide[i] = spread[i];
        wide2[i] = spread[(i + 4) % 9];
    }
    struct compare_speed c;
    CHECK(compare_speed_rule(half, 9, y, 9, 0.05, 0.10, &c) == 0, "rule ran");
    CHECK(fabs(c.ratio - 0.5) < 1e-12 && c.verdict == CMP_V_SLOWER && c.p < 0.05 && c.ci_hi < 1,
          "half the rate: ratio %.15g (0.5), slower (%s), p %.3g", c.ratio, cmp_verdict_name(c.verdict), c.p);
    CHECK(compare_speed_rule(y, 9, half, 9, 0.05, 0.10, &c) == 0 && fabs(c.ratio - 2.0) < 1e-12 &&
          c.verdict == CMP_V_FASTER, "twice the rate: faster (%s)", cmp_verdict_name(c.verdict));
    /* 5% apart, a tight spread: beyond noise but below the minimum effect */
    CHECK(compare_speed_rule(near, 9, y, 9, 0.05, 0.10, &c) == 0 && fabs(c.ratio - 1.05) < 1e-12 &&
          c.verdict == CMP_V_SAME, "5%% apart: same (%s), ratio %.15g", cmp_verdict_name(c.verdict), c.ratio);
    /* a spread of 4x: the interval is wider than the band 1/1.1..1.1, so it cannot decide */
    CHECK(compare_speed_rule(wide, 9, wide2, 9, 0.05, 0.10, &c) == 0 && c.verdict == CMP_V_NOISY,
          "a 4x spread: noisy (%s), interval %.3g..%.3g", cmp_verdict_name(c.verdict), c.ci_lo, c.ci_hi);
    /* one repetition a side cannot reach alpha = 0.05 */
    CHECK(compare_speed_rule(half, 1, y, 1, 0.05, 0.10, &c) == 0 && c.verdict == CMP_V_UNDECIDED,
          "one repetition each: undecided (%s)", cmp_verdict_name(c.verdict));
}

int main(void)
{
    test_speed_rule();
    /* Lambert W against GSL's gsl_sf_lambert_W0. */
    const double wx[] = { 0, 1e-8, 1e-3, 0.5, 1, 10, 300, 1.3e4, 1e6 };
    for (size_t i = 0; i < sizeof wx / sizeof wx[0]; ++i)
        CHECK_NEAR(brdf_lambert_w0(wx[i]), gsl_sf_lambert_W0(wx[i]), 1e-13 * (1 + gsl_sf_lambert_W0(wx[i])),
                   "Lambert W0 against GSL");

    /* Complex Fresnel: against complex arithmetic at several angles and indices, and the normal
       incidence closed form ((n-1)^2 + k^2) / ((n+1)^2 + k^2). */
    const double idx[][2] = { { 1.49, 0 }, { 0.958, 6.69 }, { 0.43, 2.455 }, { 2.5, 0.3 } };
    for (int i = 0; i < 4; ++i) {
        double n = idx[i][0], k = idx[i][1];
        CHECK_NEAR(brdf_fresnel_complex(1.0, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-12,
                   "Fresnel at normal incidence");
        for (int a = 5; a < 90; a += 10) {
            double c = cos(a * M_PI / 180);
            CHECK_NEAR(brdf_fresnel_complex(c, n, k), fresnel_unpolarised_test(c, n, k), 1e-12,
                       "Fresnel against complex arithmetic");
        }
    }
    /* Brewster's angle of a dielectric: F_p = 0 there, so F = F_s / 2. */
    {
        double n = 1.49, tb = atan(n), c = cos(tb), ct = cos(asin(sin(tb) / n));
        double rs = (c - n * ct) / (c + n * ct);
        CHECK_NEAR(brdf_fresnel_complex(c, n, 0), 0.5 * rs * rs, 1e-12, "Fresnel at Brewster's angle");
    }

    /* Shadowing: 1 at normal incidence, falling towards grazing, 0 in the limit. */
    CHECK_NEAR(brdf_he_shadow(1.0, 0.1, 1.0), 1.0, 1e-15, "S(0) = 1");
    CHECK(brdf_he_shadow(cos(80 * M_PI / 180), 0.1, 1.0) < brdf_he_shadow(cos(60 * M_PI / 180), 0.1, 1.0),
          "S decreases towards grazing");
    CHECK(brdf_he_shadow(1e-9, 0.1, 1.0) < 1e-3, "S -> 0 at grazing (got %g)", brdf_he_shadow(1e-9, 0.1, 1.0));

    /* The directional-diffuse sum: for small g the first term g e^-g e^-x dominates (the rest
       is O(g^2), relative O(g)); at g = 2.5, x = 0.7 it equals the sum written with lgamma. */
    {
        double g = 1e-3, x = 0.4;
        struct brdf_he_sum_result r = brdf_he_dd_sum(g, x);
        double first = g * exp(-g) * exp(-x);
        CHECK(fabs(r.sum - first) / first < g, "small g: first term dominates (rel diff %g)", fabs(r.sum - first) / first);
        CHECK(r.sum > first, "the later terms are positive");
        g = 2.5;
        x = 0.7;
        r = brdf_he_dd_sum(g, x);
        double ref = 0;
        for (int m = 1; m <= 200; ++m)
            ref += exp(m * log(g) - g - lgamma(m + 1.0)) / m * exp(-x / m);
        CHECK_NEAR(r.sum, ref, 2e-7 * ref, "sum(g = 2.5, x = 0.7) against the lgamma form");
        CHECK(r.terms > g && r.terms < 40, "terms taken %g: past the peak, finite", r.terms);
        /* large g: no underflow of e^-g (float would underflow past 87) */
        g = 300;
        r = brdf_he_dd_sum(g, 0.0);
        ref = 0;
        for (int m = 1; m <= 2000; ++m)
            ref += exp(m * log(g) - g - lgamma(m + 1.0)) / m;
        CHECK_NEAR(r.sum, ref, 1e-6 * ref, "sum(g = 300) against the lgamma form");
    }

    /* He's directional-diffuse term against the definitions written out with vectors
       (rough aluminium preset; off the mirror direction, so the specular term is 0). */
    {
        const double cfg[][3] = { { 30, 40, 150 }, { 10, 70, 180 }, { 60, 60, 90 }, { 45, 20, 10 } };
        for (int i = 0; i < 4; ++i) {
            double L[3], V[3];
            dir3(cfg[i][0], 0, L);
            dir3(cfg[i][1], cfg[i][2], V);
            double lambda = 0.55, s0 = 0.1, tau = 1.0, nr = 0.958, ni = 6.69;
            double got = brdf_he_terms(L[2], V[2], dot3(L, V), lambda, s0, tau, nr, ni, 0.0, NULL);
            double want = he_dd_reference(L, V, lambda, s0, tau, nr, ni);
            /* the model stops its sum at float resolution (terms below 2^-24 of the sum, past the
               peak): the tail it drops is a few 1e-8 of the sum at most */
            CHECK_NEAR(got, want, 2e-7 * want, "He rho_dd against the vector form");
        }
    }

    /* g -> 0 (sigma0 -> 0): only the specular term is left: off the mirror direction the BRDF
       vanishes; in the mirror direction it is F(theta_i) e^-g S / (cos theta_i dw) -> F / (cos dw). */
    {
        double L[3], V[3], R[3];
        dir3(35, 0, L);
        dir3(50, 170, V);
        double off = brdf_he_terms(L[2], V[2], dot3(L, V), 0.55, 1e-7, 1.0, 0.958, 6.69, 0.0, NULL);
        dir3(35, 180, R);   /* the mirror direction of L */
        double on = brdf_he_terms(L[2], R[2], dot3(L, R), 0.55, 1e-7, 1.0, 0.958, 6.69, 0.0, NULL);
        double want = fresnel_unpolarised_test(L[2], 0.958, 6.69) / (L[2] * 2 * M_PI * (1 - cos(M_PI / 180)));
        CHECK(off < 1e-9 * on, "g -> 0: off-mirror %g against mirror %g", off, on);
        CHECK_NEAR(on, want, 1e-6 * want, "g -> 0: the specular term F / (cos dw)");
    }

    /* Cook-Torrance at L = V = N: D(0) F0 G1(1)^2 / 4 with G1(1) = 1 (both Smith forms) and
       D(0) = 1 / (pi a^2) for Beckmann and GGX alike; Brady's printed form: D(0) / 0.9994. */
    {
        double n = 2, a2 = 2.0 / (n + 2), f0 = 0.3;
        CHECK_NEAR(brdf_pb_eval(BRDF_CT_BECKMANN, 1, 1, 1, n, f0, 0), f0 / (4 * M_PI * a2), 1e-12, "CT Beckmann at normal");
        CHECK_NEAR(brdf_pb_eval(BRDF_CT_GGX, 1, 1, 1, n, f0, 0), f0 / (4 * M_PI * a2), 1e-12, "CT GGX at normal");
        CHECK_NEAR(brdf_pb_eval(BRDF_BRADY, 1, 1, 1, n, 0.7, 2.0), 1 / (M_PI * a2 * 0.9994), 1e-9, "Brady at normal");
        /* off normal: every factor written again (theta_i = 20, theta_o = 50 degrees, phi = 180). */
        double L[3], V[3], H[3];
        dir3(20, 0, L);
        dir3(50, 180, V);
        for (int k = 0; k < 3; ++k)
            H[k] = L[k] + V[k];
        unit3(H);
        double ch = H[2], vh = dot3(V, H), t2 = (1 - ch * ch) / (ch * ch), al = sqrt(a2);
        double dg = a2 / (M_PI * pow(ch, 4) * pow(a2 + t2, 2));
        double F = f0 + (1 - f0) * pow(1 - vh, 5);
        double g1l = 2 * L[2] / (L[2] + sqrt(a2 + (1 - a2) * L[2] * L[2]));
        double g1v = 2 * V[2] / (V[2] + sqrt(a2 + (1 - a2) * V[2] * V[2]));
        CHECK_NEAR(brdf_pb_eval(BRDF_CT_GGX, L[2], V[2], dot3(L, V), n, f0, 0), dg * F * g1l * g1v / (4 * L[2] * V[2]),
                   1e-12, "CT GGX off normal");
        double db = exp(-t2 / a2) / (M_PI * a2 * pow(ch, 4));
        /* Walter's a = cot(theta) / alpha; G1 = 1 from a = 1.6 on, the rational form below */
        double ab = 1 / (al * tan(acos(V[2])));
        double g1vb = ab >= 1.6 ? 1 : (3.535 * ab + 2.181 * ab * ab) / (1 + 2.276 * ab + 2.577 * ab * ab);
        double al_l = 1 / (al * tan(acos(L[2])));
        double g1lb = al_l >= 1.6 ? 1 : (3.535 * al_l + 2.181 * al_l * al_l) / (1 + 2.276 * al_l + 2.577 * al_l * al_l);
        CHECK(ab < 1.6, "n = 2: V's G1 is in its rational part (a = %g)", ab);
        CHECK_NEAR(brdf_pb_eval(BRDF_BRADY, L[2], V[2], dot3(L, V), n, 0.7, 2.0),
                   db * g1lb * g1vb / (t2 / (0.49 * 4.0) + 0.9994), 1e-12, "Brady off normal");
        /* below the horizon: 0 */
        CHECK(brdf_pb_eval(BRDF_CT_GGX, -0.2, 0.5, 0.1, n, f0, 0) == 0, "L below the surface gives 0");
    }

    /* Reciprocity f(L, V) = f(V, L) of every physically based model (the BRDF is symmetric in
       N.L and N.V by construction; the check guards the code against an asymmetric slip). */
    {
        double L[3], V[3];
        dir3(25, 0, L);
        dir3(55, 140, V);
        const int ids[] = { BRDF_CT_BECKMANN, BRDF_CT_GGX, BRDF_BRADY, BRDF_HE };
        for (int i = 0; i < 4; ++i) {
            double a = brdf_pb_eval(ids[i], L[2], V[2], dot3(L, V), 40, 0.5, 1.0);
            double b = brdf_pb_eval(ids[i], V[2], L[2], dot3(L, V), 40, 0.5, 1.0);
            CHECK_NEAR(a, b, 1e-12 * fabs(a), "reciprocity");
            CHECK(a > 0 && isfinite(a), "model %d gives a positive finite value (%g)", ids[i], a);
        }
    }

    /* The registry knows them, as lobes of one cosine: the BRDF with L = N and theta_h = acos(c). */
    {
        struct model_spec m;
        char err[256];
        CHECK(model_spec_parse("he:material=2", &m, err, sizeof err) == 0, "he:material=2 parses (%s)", err);
        double c = cos(0.2), nv = 2 * c * c - 1;
        CHECK_NEAR(model_eval_host(&m, c, 10), brdf_pb_eval(BRDF_HE, 1, nv, nv, 10, 2, 0), 0, "lobe form of he");
        CHECK(model_spec_parse("he:material=4", &m, err, sizeof err) == 2, "material 4 is out of range");
    }
    /* He's terms per evaluation grow with the roughness (g = (k sigma (cos + cos))^2): at
       normal incidence in the mirror direction the sum's peak sits at m ~ g = (4 pi ratio)^2. */
    {
        int t_smooth = pbcost_he_terms(1, 1, 1, 0.01 * 0.55), t_rough = pbcost_he_terms(1, 1, 1, 1.0 * 0.55);
        double g_rough = pow(4 * M_PI * 1.0, 2);
        CHECK(t_smooth < t_rough, "terms grow with sigma0/lambda (%d, %d)", t_smooth, t_rough);
        CHECK(t_rough > g_rough && t_rough < g_rough + 10 * sqrt(g_rough) + 20,
              "terms past the peak g = %g but within ~10 sqrt(g) of it (%d)", g_rough, t_rough);
    }

    /* The image passes' fit of Blinn-Phong to He's image, on data made exactly of one lobe,
       h_i = 3 a_i c_i^40: it must give back n = 40 and the scale 3 with no residual. */
    {
        enum { P = 2000 };
        static double a[P], c[P], h[P];
        for (int i = 0; i < P; ++i) {
            c[i] = 0.5 + 0.5 * (i + 0.5) / P;
            a[i] = 0.2 + (i % 7) * 0.1;
            h[i] = 3 * a[i] * pow(c[i], 40);
        }
        double n, k, rel;
        render_he_fit(a, c, h, P, &n, &k, &rel);
        CHECK_NEAR(n, 40, 1e-4, "fitted n");
        CHECK_NEAR(k, 3, 1e-4, "fitted scale");
        CHECK(rel < 1e-5, "no residual (%g)", rel);
    }

    /* On the device: every cost row's float kernel against the double reference at random
       (N, L, V), and the ratios of a row to itself. No time is asserted. */
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == 0) {
        struct pbcost_options o;
        pbcost_options_default(&o);
        o.reps = 1;
        o.min_time = 0.001;
        static struct pbcost_result r;
        o.io.quiet = 1;
        CHECK(pbcost_run(&s, &o, &r) == 0, "pbcost_run");
        CHECK(r.count == 11, "rows: pow, phong, blinn, fq2, 2 x Cook-Torrance, Brady, 4 He presets (%d)", r.count);
        for (int i = 0; i < r.count; ++i) {
            CHECK(r.rows[i].check_max_abs_of_peak <= 1e-4, "%s: device vs double %.3g of the peak", r.rows[i].name,
                  r.rows[i].check_max_abs_of_peak);
            CHECK(r.rows[i].evals_per_s > 0 && isfinite(r.rows[i].evals_per_s), "%s: a rate", r.rows[i].name);
        }
        CHECK(r.rows[r.fq2].ratio_to_fq2 == 1 && r.rows[r.phong].ratio_to_phong == 1, "a row against itself is 1");
        clsession_close(&s);
    }
    return test_summary(rc);
}
