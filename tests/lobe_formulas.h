/* lobe_formulas.h - every registry model's formula written a second time, from SPEC.md's
 * tables, for the tests' independent expected values. It deliberately does not include
 * kernels/brdf_models.h and is written differently where it can be: in s = 1 - c (given
 * separately so that it is exact near the peak),
 * tan^2 rather than sin^2/c^2, Lyon's power by pow() rather than k squarings. A constant
 * changed in the header (0.463, 0.448, 0.099, 0.214, 0.807, alpha(n), ...) therefore shows as
 * a difference between the program and this table (test_model_table.c), and the brute-force
 * figures built on it (indep.c) differ from the program's published ones. */
#ifndef BRDF_TEST_LOBE_FORMULAS_H
#define BRDF_TEST_LOBE_FORMULAS_H

#include <math.h>
#include <string.h>

static const double lf_pi = 3.14159265358979323846;

/* SPEC.md, "Zones and metrics": the epicentre ends where c^n = e^(-0.511). */
static inline double lf_epicentre_end_x(double n) { return acos(exp(-0.511 / n)); }

/* c^n with s = 1 - c known exactly: exp(n log1p(-s)); 0 at c = 0. */
static inline double lf_pow(double s, double n) { return s >= 1 ? 0.0 : exp(n * log1p(-s)); }

/* (1 - k s)^2, zeroed past its root (SPEC.md: "zeroed where its base k(c-1)+1 <= 0"). */
static inline double lf_quad(double s, double k)
{
    double base = 1 - k * s;
    return base > 0 ? base * base : 0.0;
}

/* paper 2: k_Q(n) = (sqrt(Q) - 1) / (Q^(1/n) - 1); 1 - Q^(1/n) = -expm1(ln Q / n) keeps its
   digits at large n (pow() would lose 5 of them at n = 20000). */
static inline double lf_k_q(double n, double q) { return (1 - sqrt(q)) / -expm1(log(q) / n); }

/* SPEC.md: alpha(n) = sqrt(2/(n+2)), so alpha^2 = 2/(n+2). */
static inline double lf_alpha2(double n) { return 2 / (n + 2); }

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
    return NAN;
}

#endif
