/* lobe_formulas.h - every registry model's formula written a second time, from docs/definitions.md's
 * tables, for the tests' independent expected values. It deliberately does not include
 * kernels/brdf_models.h and is written differently where it can be: in s = 1 - c (given
 * separately so that it is exact near the peak),
 * tan^2 rather than sin^2/c^2, Lyon's power by pow() rather than k squarings. A constant
 * changed in the header (0.463, 0.448, 0.099, 0.214, 0.807, alpha(n), ...) therefore shows as
 * a difference between the program and this table (test_model_table.c), and the brute-force
 * figures built on it (indep.c) differ from the program's published ones. */
#ifndef BRDF_TEST_LOBE_FORMULAS_H
#define BRDF_TEST_LOBE_FORMULAS_H

#include <complex.h>
#include <math.h>
#include <string.h>

static const double lf_pi = 3.14159265358979323846;

/* docs/definitions.md, "Zones and metrics": the epicentre ends where c^n = e^(-0.511). */
static inline double lf_epicentre_end_x(double n) { return acos(exp(-0.511 / n)); }

/* c^n with s = 1 - c known exactly: exp(n log1p(-s)); 0 at c = 0. */
static inline double lf_pow(double s, double n) { return s >= 1 ? 0.0 : exp(n * log1p(-s)); }

/* (1 - k s)^2, zeroed past its root (docs/definitions.md: "zeroed where its base k(c-1)+1 <= 0"). */
static inline double lf_quad(double s, double k)
{
    double base = 1 - k * s;
    return base > 0 ? base * base : 0.0;
}

/* paper 2: k_Q(n) = (sqrt(Q) - 1) / (Q^(1/n) - 1); 1 - Q^(1/n) = -expm1(ln Q / n) keeps its
   digits at large n (pow() would lose 5 of them at n = 20000). */
static inline double lf_k_q(double n, double q) { return (1 - sqrt(q)) / -expm1(log(q) / n); }

/* docs/definitions.md: alpha(n) = sqrt(2/(n+2)), so alpha^2 = 2/(n+2). */
static inline double lf_alpha2(double n) { return 2 / (n + 2); }

/* ---- the physically based models as lobes (host/core/models.c): the BRDF with the light at
 * the normal (L = N) and theta_h = acos(c), so N.V = L.V = 2c^2 - 1 = 1 - 4s + 2s^2 and
 * V.H = N.H = c. */

/* Smith G1 of Beckmann, Walter et al. 2007's rational form in a = cot(theta) / alpha; 1 from
   a = 1.6 on. */
static inline double lf_g1_beckmann(double x, double a2)
{
    double a = x / sqrt(a2 * (1 - x * x));
    return a >= 1.6 ? 1.0 : (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a);
}
/* Smith G1 of GGX: 2 / (1 + sqrt(1 + alpha^2 tan^2)). */
static inline double lf_g1_ggx(double x, double a2) { return 2 / (1 + sqrt(1 + a2 * (1 - x * x) / (x * x))); }

/* He et al. 1991's presets (host/core/models.c): lambda, sigma0, tau (um), n, k, a. */
static const double lf_he_presets[4][6] = {
    { 0.55, 0.10, 1.00, 0.958, 6.69, 0.0 },    /* rough aluminium */
    { 0.55, 0.02, 1.00, 0.958, 6.69, 0.0 },    /* polished aluminium */
    { 0.55, 0.10, 1.00, 0.43, 2.455, 0.0 },    /* gold */
    { 0.55, 0.10, 1.00, 1.49, 0.0, 0.15 },     /* plastic */
};
/* Unpolarised Fresnel reflectance by complex arithmetic (Snell with a complex index). */
static inline double lf_fresnel(double c, double n, double k)
{
    double complex m = n + k * I, ct = csqrt(1 - (1 - c * c) / (m * m));
    double complex rs = (c - m * ct) / (c + m * ct), rp = (m * c - ct) / (m * c + ct);
    return 0.5 * (cabs(rs) * cabs(rs) + cabs(rp) * cabs(rp));
}
/* Smith shadowing of He's Gaussian surface at cosine c. */
static inline double lf_he_shadow(double c, double s0, double tau)
{
    if (c >= 1)
        return 1;
    double e = tau * c / (2 * s0 * sqrt(1 - c * c));
    return (1 - 0.5 * erfc(e)) / (1 + 0.5 * (exp(-e * e) / (sqrt(lf_pi) * e) - erfc(e)));
}
/* He's BRDF with L = N and V at cosine nv (> 0): z0 by bisection of
   sqrt(pi/2) z = sigma0 K_r / 4 exp(-z^2 / (2 sigma0^2)) (K_i = 0 at normal incidence), the
   sum with lgamma, stopped as the model stops it (past m = g, a term below 2^-24 of the sum). */
static inline double lf_he(double c, double nv, int preset)
{
    const double *p = lf_he_presets[preset];
    double lambda = p[0], s0 = p[1], tau = p[2], kw = 2 * lf_pi / lambda;
    double tr = sqrt(1 - nv * nv) / nv, kr = tr * erfc(tau / (2 * s0 * tr));
    double lo = 0, hi = s0 * kr + 1e-300;
    for (int i = 0; i < 200; ++i) {
        double z = 0.5 * (lo + hi);
        if (sqrt(lf_pi / 2) * z - s0 / 4 * kr * exp(-z * z / (2 * s0 * s0)) > 0)
            hi = z;
        else
            lo = z;
    }
    double z0 = 0.5 * (lo + hi), sigma = s0 / sqrt(1 + z0 * z0 / (s0 * s0));
    double g = pow(kw * sigma * (1 + nv), 2);
    double x = 4 * kw * kw * c * c * (1 - c * c) * tau * tau / 4;    /* v_xy^2 tau^2 / 4 */
    double sum = 0;
    for (int m = 1; m <= 2000; ++m) {
        double term = exp(m * log(g) - g - lgamma(m + 1.0) - x / m) / m;
        sum += term;
        if (m >= g && term <= 5.9604644775390625e-8 * sum)
            break;
    }
    double S = lf_he_shadow(nv, s0, tau);
    /* G = (v.v / v_z)^2 = (4c^2 / 2c^2)^2 = 4; the bisector's cosine is c */
    double dd = lf_fresnel(c, p[3], p[4]) * 4 * S / (lf_pi * nv) * kw * kw * tau * tau / 16 * sum;
    double cone = 0.99984769515639123916;                            /* cos 1 degree */
    /* the mirror term over the 1-degree source, written symmetrically: F at the bisector,
       1 / sqrt(cos theta_i cos theta_r) (He's F(theta_i) / cos theta_i at the mirror itself) */
    double sp = nv >= cone ? lf_fresnel(c, p[3], p[4]) * exp(-g) * S / (sqrt(nv) * 2 * lf_pi * (1 - cone)) : 0;
    return sp + dd + p[5];
}

static inline double lf_physical(const char *id, double c, double s, double n, double p0, double p1)
{
    double nv = 1 - 4 * s + 2 * s * s;
    if (!(nv > 0))
        return 0.0;
    double a2 = lf_alpha2(n), t2 = s * (2 - s) / (c * c);
    double db = exp(-t2 / a2) / (lf_pi * a2 * c * c * c * c), dg = a2 / (lf_pi * c * c * c * c * (a2 + t2) * (a2 + t2));
    double s5 = s * s * s * s * s;
    if (!strcmp(id, "ct-beckmann"))   /* D F G1(1) G1(nv) / (4 nv), G1(1) = 1, Schlick F at V.H = c */
        return db * (p0 + (1 - p0) * s5) * lf_g1_beckmann(nv, a2) / (4 * nv);
    if (!strcmp(id, "ct-ggx"))
        return dg * (p0 + (1 - p0) * s5) * lf_g1_ggx(nv, a2) / (4 * nv);
    if (!strcmp(id, "brady"))        /* paper 2's print: D G / (a^-2 b^-2 tan^2 + 0.9994) */
        return db * lf_g1_beckmann(nv, a2) / (t2 / (p0 * p0 * p1 * p1) + 0.9994);
    if (!strcmp(id, "he"))
        return lf_he(c, nv, (int)p0);
    return NAN;
}

/* Fresnel reflectance of unpolarised light from Snell's law: sin t = sin i / n, r_s = (cos i - n
 * cos t) / (cos i + n cos t), r_p = (n cos i - cos t) / (n cos i + cos t), F = (r_s^2 + r_p^2) / 2;
 * 1 past the critical angle (sin t > 1). */
static inline double lf_fresnel_snell(double ci, double n)
{
    double st = sqrt(1 - ci * ci) / n;
    if (st >= 1)
        return 1.0;
    double ct = sqrt(1 - st * st);
    double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
    return (rs * rs + rp * rp) / 2;
}

/* One model at cosine c (s = 1 - c, both given), shininess n, parameters p0, p1.
 * Returns NAN for an id this table does not know. */
static inline double lf_eval(const char *id, double c, double s, double n, double p0, double p1)
{
    if (c < 0)
        c = 0, s = 1;
    if (!strcmp(id, "phong") || !strcmp(id, "blinn"))
        return lf_pow(s, n);
    if (!strcmp(id, "phongpow"))
        return pow(c, n);
    if (!strcmp(id, "cq2"))
        return lf_quad(s, n / 2);                              /* F2: xi = 1/2 */
    if (!strcmp(id, "fvol"))
        return lf_quad(s, 0.463 * n);                          /* paper 1: xi = 0.463 */
    if (!strcmp(id, "fvol64"))
        return lf_quad(s, 29.0 * n / 64.0);                    /* paper 1: xi = 29/64 */
    if (!strcmp(id, "schlick"))
        return c / (n * s + c);                                /* c / (n - n c + c) */
    if (!strcmp(id, "lyon")) {
        double base = 1 - n * s / pow(2, p0);                  /* (1 - n(1-c)/2^k)^(2^k) */
        return base > 0 ? pow(base, pow(2, p0)) : 0.0;
    }
    if (!strcmp(id, "fq"))
        return lf_quad(s, lf_k_q(n, p0));
    if (!strcmp(id, "fq2"))
        return lf_quad(s, 0.448 * n + 0.099);                  /* paper 2's fit of k_Q */
    if (!strcmp(id, "fq2n"))
        return 0.214 * (0.807 + n) * lf_quad(s, 0.448 * n + 0.099);
    if (!strcmp(id, "phongn"))
        return (n + 2) / (2 * lf_pi) * lf_pow(s, n);
    if (!strcmp(id, "blinnn"))
        return (n + 2) * (n + 4) / (8 * lf_pi * (pow(2, -n / 2) + n)) * lf_pow(s, n);
    if (!strcmp(id, "beckmann")) {
        if (c <= 0)
            return 0.0;                                        /* exp(-inf): 0 at grazing */
        double a2 = lf_alpha2(n), t2 = (1 - c * c) / (c * c);
        return exp(-t2 / a2) / (lf_pi * a2 * c * c * c * c);
    }
    if (!strcmp(id, "ggx")) {
        double a2 = lf_alpha2(n);
        if (c <= 0)
            return a2 / lf_pi;                                 /* the limit of a2/(pi (c^2 a2 + 1 - c^2)^2) */
        double t2 = (1 - c * c) / (c * c), d = a2 + t2;
        return a2 / (lf_pi * c * c * c * c * d * d);
    }
    if (!strcmp(id, "quad"))
        return lf_quad(s, p0 * n + p1);
    /* docs/definitions.md, "The approximations engines use"; the frozen constants as docs/frontier.md
       prints them. */
    if (!strcmp(id, "sg"))
        return exp(-n * s);                                    /* exp(n (c - 1)) */
    if (!strcmp(id, "ue4phong"))
        return exp(-(n + 0.775) * s);
    if (!strcmp(id, "gauss"))
        return exp(-(p0 * n + p1) * s);
    if (!strcmp(id, "gaussfit"))
        return exp(-(1.020199565 * n + 0.1774327237) * s);
    if (!strcmp(id, "pow3") || !strcmp(id, "pow4") || !strcmp(id, "pow3fit") || !strcmp(id, "pow4fit")) {
        int m = id[3] == '3' ? 3 : 4;
        int frozen = strlen(id) > 4;
        double k = frozen ? (m == 3 ? 0.3106866803 * n + 0.07545118726 : 0.2371428753 * n + 0.05221691603)
                          : p0 * n + p1;
        double base = 1 - k * s;
        return base > 0 ? pow(base, m) : 0.0;
    }
    if (!strcmp(id, "bg")) {                                   /* m = 2^j, A(n) = alpha_m n + beta_m */
        static const double alpha[5] = { 0, 0.355728074, 0.211256260, 0.114952593, 0.059933489 };
        static const double beta[5] = { 0, 0.264367919, 0.157725393, 0.085811949, 0.044726082 };
        int j = (int)p0;
        double base = 1 - (alpha[j] * n + beta[j]) * s;       /* A c + 1 - A */
        return base > 0 ? pow(base, pow(2, j)) : 0.0;
    }
    if (!strcmp(id, "kb") || !strcmp(id, "kbswap")) {
        double a = (n + 5.6) / (n * (0.09 * n + 5.2)), b = (n + 65) / (5 * n + 31.7);
        if (!strcmp(id, "kbswap")) {
            double t = a;
            a = b;
            b = t;
        }
        double al = 2 * asin(sqrt(s / 2));                     /* the angle from s = 1 - cos */
        double f = al < a ? 1 - al * al / (a * b) : al < b ? (al - b) * (al - b) / (b * (b - a)) : 0.0;
        return f > 0 ? f : 0.0;
    }
    if (!strcmp(id, "bitpow")) {
        /* bits(c) - bits(1) = 2^23 (e + m - 1) for c = m 2^e, m in [1, 2); the pattern
           t = 2^23 (n (e + m - 1) + 127) read back as 2^(floor t' - 127) (1 + frac t'). */
        if (c <= 0)
            return 0.0;
        int e = ilogb(c);
        double l2 = e + (scalbn(c, -e) - 1), t = n * l2 + 127;
        if (t <= 0)
            return 0.0;
        if (t < 1)
            return t * pow(2, -126);
        double fl = floor(t);
        return pow(2, fl - 127) * (1 + (t - fl));
    }
    if (!strcmp(id, "ct-beckmann") || !strcmp(id, "ct-ggx") || !strcmp(id, "brady") || !strcmp(id, "he"))
        return lf_physical(id, c, s, n, p0, p1);
    /* The terms (c = cos of the angle of incidence, L and V mirrored about N), written here from the
       polarised reflectances and the tangent form of Smith's Lambda, not from brdf_models.h's forms. */
    if ((!strcmp(id, "fresnel") || !strcmp(id, "fresnel-schlick")) && c <= 0)
        return 0.0;                                            /* on the horizon: outside the domain */
    if (!strcmp(id, "fresnel"))
        return lf_fresnel_snell(c, n);
    if (!strcmp(id, "fresnel-schlick")) {
        double f0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
        return f0 + (1 - f0) * pow(s, 5);
    }
    if (!strcmp(id, "smith-ggx") || !strcmp(id, "smith-ggx-hc")) {
        double a2 = lf_alpha2(n);
        if (c <= 0)
            return 0.0;                                        /* both vanish at grazing */
        if (!strcmp(id, "smith-ggx"))
            return lf_g1_ggx(c, a2) * lf_g1_ggx(c, a2);
        double lambda = (-1 + sqrt(1 + a2 * (1 - c * c) / (c * c))) / 2;
        return 1 / (1 + 2 * lambda);
    }
    return NAN;
}

#endif
