/*
 * brdf_models.h - every lobe model of SPEC.md, written once.
 *
 * This header is the single source of truth for the model formulas. It is written in the
 * common subset of C11 and OpenCL C so that the same text is compiled
 *   - by the OpenCL driver for the device, with REAL = float or a float vector (float16), and
 *   - by the host compiler as the double-precision reference, with REAL = double.
 * The includer defines REAL (the evaluation type, scalar or vector) and RSCALAR (its element
 * type) before including this file. Nothing else in the project writes a model's formula.
 *
 * Conventions: c = cos x of the lobe angle (x = psi for the Phong family, theta_h for the Blinn
 * family), n = shininess, p0/p1 = the model's parameters (see host/core/models.c for their names and
 * ranges). Lobe models are defined for c in [0, 1]; a negative cosine is treated as 0.
 * Formulas are written for accuracy in float: (c - 1) is exact for c >= 0.5 (Sterbenz), and
 * Q^(1/n) - 1 is computed as expm1(log(Q)/n) to avoid cancellation at large n.
 */
#ifndef BRDF_MODELS_H
#define BRDF_MODELS_H

#if !defined(REAL) || !defined(RSCALAR)
#error "define REAL (evaluation type) and RSCALAR (its element type) before including brdf_models.h"
#endif

#ifdef __OPENCL_VERSION__
#define BRDF_FN static inline
#else
#ifndef BRDF_HOST_JIT   /* a user model's host evaluator (host/core/hostjit.c) declares its own */
#include <math.h>
#endif
#define BRDF_FN static inline
#endif

/* A literal in the element type, so that float code never promotes to double. */
#define RC(x) ((RSCALAR)(x))
/* A scalar broadcast to REAL (a vector literal in OpenCL C, a cast in C). */
#define RSPLAT(x) ((REAL)(x))

#define BRDF_PI 3.14159265358979323846

/* Model ids shared by the kernels and the host registry (host/core/models.c). */
enum brdf_model_id {
    BRDF_PHONG = 0,   /* c^n, reference of the Phong family (x = psi)               */
    BRDF_BLINN,       /* c^n, reference of the Blinn family (x = theta_h)           */
    BRDF_CQ2,         /* (n/2 (c-1) + 1)^2, classic cosine-quadratic                */
    BRDF_FVOL,        /* (0.463 n (c-1) + 1)^2, paper 1                             */
    BRDF_FVOL64,      /* (29/64 n (c-1) + 1)^2, paper 1's cheap variant             */
    BRDF_SCHLICK,     /* c / (n - n c + c)                                          */
    BRDF_LYON,        /* (1 - n (1-c) / 2^k)^(2^k), p0 = k                          */
    BRDF_FQ,          /* (k_Q(n) (c-1) + 1)^2, p0 = Q                               */
    BRDF_FQ2,         /* ((0.448 n + 0.099)(c-1) + 1)^2, paper 2                    */
    BRDF_FQ2N,        /* 0.214 (0.807 + n) * fq2, paper 2's normalised form         */
    BRDF_PHONGN,      /* (n+2)/(2 pi) c^n                                           */
    BRDF_BLINNN,      /* (n+2)(n+4) / (8 pi (2^(-n/2) + n)) c^n                     */
    BRDF_BECKMANN,    /* Beckmann D(theta_h; alpha(n))                              */
    BRDF_GGX,         /* GGX D(theta_h; alpha(n))                                   */
    BRDF_QUAD,        /* ((a n + b)(c-1) + 1)^2, p0 = a, p1 = b: the fitted family  */
    BRDF_PHONGPOW,    /* c^n through the pow() built-in: the literal pow() reference */
    BRDF_USER,        /* a user model compiled at run time (brdf_user_eval)         */
    BRDF_MODEL_COUNT
};

/* Epicentre zone end, as a cosine: the reference c^n equals e^(-0.511) there (SPEC.md). */
BRDF_FN REAL brdf_zone_epicentre_cos(REAL n) { return exp(RC(-0.511) / n); }

/* The lobe c^n, written as exp(n ln c), the way a shader compiler lowers pow (GPUs: exp2
 * and log2 units). PoCL 3.1's vector pow() runs at scalar speed (16-30 cycles a value) while
 * exp(n log c) costs about 1.6; the literal pow() stays available as the model phongpow.
 * In float, exp(n ln c) has a relative error of about |n ln c| ulp: below 1 ulp where
 * c^n > e^-1, and the double host reference checks every figure. c = 0 gives exp(-inf) = 0.
 * The host's tuned C baseline defines BRDF_POW_LOBE as powf. */
#ifndef BRDF_POW_LOBE
#define BRDF_POW_LOBE(c, n) exp((n) * log(c))
#endif
BRDF_FN REAL brdf_pow_lobe(REAL c, REAL n) { return BRDF_POW_LOBE(c, n); }
/* The lobe in s = 1 - c, exp(n ln(1 - s)), for the kernels that place their samples in s (a
 * float cosine has only 6e-8 of room below 1: at n = 1e6 the whole epicentre is eight float
 * cosines). ln(1 - s) = log1p(-s), but PoCL's vector log1p costs about as much as the rest of
 * a sweep's sample, so it is written as ln u + e/u with u = 1 - s rounded and e = (1 - u) - s
 * its rounding error, which the arithmetic gives exactly (both differences are of close
 * numbers, Sterbenz): ln(1 - s) = ln u + ln(1 + e/u), and |e/u| <= 2^-24 in float leaves
 * ln(1 + e/u) = e/u to 2^-49. As s -> 0, u = 1 and it is -s; at s = 1 (c = 0) it is
 * ln 0 = -inf and the lobe 0 (the divisor is kept off 0). e/u is a correction of 2^-24, so
 * the device may divide approximately. */
#ifdef __OPENCL_VERSION__
#define BRDF_SMALL_DIVIDE(a, b) native_divide((a), (b))
#else
#define BRDF_SMALL_DIVIDE(a, b) ((a) / (b))
#endif
BRDF_FN REAL brdf_pow_lobe_s(REAL s, REAL n)
{
    REAL u = RC(1.0) - s;
    return exp(n * (log(u) + BRDF_SMALL_DIVIDE((RC(1.0) - u) - s, fmax(u, RC(1e-30)))));
}
/* The lobe given both c and s = 1 - c. By default it is brdf_pow_lobe(c); a kernel that
 * samples s defines BRDF_POW_LOBE_CS(c, s, n) as brdf_pow_lobe_s(s, n). */
#ifndef BRDF_POW_LOBE_CS
#define BRDF_POW_LOBE_CS(c, s, n) BRDF_POW_LOBE(c, n)
#endif
BRDF_FN REAL brdf_pow_lobe_cs(REAL c, REAL s, REAL n)
{
    (void)c;
    (void)s;   /* one of the two is used, as the includer chooses */
    return BRDF_POW_LOBE_CS(c, s, n);
}

/* The cosine-quadratic core in s = 1 - c, (k (c - 1) + 1)^2 = (1 - k s)^2, zeroed past its
   root so that it never rises again. */
BRDF_FN REAL brdf_quadratic_s(REAL s, REAL k)
{
    REAL base = fmax(RC(1.0) - k * s, RC(0.0));
    return base * base;
}
BRDF_FN REAL brdf_quadratic(REAL c, REAL k) { return brdf_quadratic_s(RC(1.0) - c, k); }

/* k_Q(n) = (sqrt(Q) - 1) / (Q^(1/n) - 1) (paper 2), with Q^(1/n) - 1 = expm1(ln Q / n). */
BRDF_FN REAL brdf_k_q(REAL n, RSCALAR q)
{
    return (sqrt(q) - RC(1.0)) / expm1(RSPLAT(log(q)) / n);
}

/* Lyon 1993: (1 - n s / 2^k)^(2^k), s = 1 - c, by k squarings, 0 where n s > 2^k. */
BRDF_FN REAL brdf_lyon_s(REAL s, REAL n, int k)
{
    REAL base = fmax(RC(1.0) - n * s * RC(exp2(-(RSCALAR)k)), RC(0.0));
    for (int i = 0; i < k; ++i)
        base = base * base;
    return base;
}
BRDF_FN REAL brdf_lyon(REAL c, REAL n, int k) { return brdf_lyon_s(RC(1.0) - c, n, k); }

/* Microfacet roughness from shininess: alpha(n) = sqrt(2 / (n + 2)). */
BRDF_FN REAL brdf_alpha_from_n(REAL n) { return sqrt(RC(2.0) / (n + RC(2.0))); }

/* sin^2 from the cosine as (1 - c)(1 + c): exact-ish in float near c = 1, where 1 - c*c
   would cancel (1 - c is exact for c >= 0.5). */
BRDF_FN REAL brdf_sin2_cs(REAL c, REAL s) { return s * (RC(1.0) + c); }
BRDF_FN REAL brdf_sin2(REAL c) { return brdf_sin2_cs(c, RC(1.0) - c); }

/* Beckmann D = exp(-tan^2 / a^2) / (pi a^2 cos^4); tends to 0 at grazing (c -> 0).
   Given c and s = 1 - c. */
BRDF_FN REAL brdf_d_beckmann_cs(REAL c, REAL s, REAL alpha)
{
    REAL a2 = alpha * alpha;
    REAL c2 = c * c;
    /* -tan^2/a^2 = -sin^2 / (c^2 a^2); at c = 0 it is -inf and exp gives 0, so the
       denominator is only kept away from 0 to avoid 0/0. */
    return exp(-brdf_sin2_cs(c, s) / (c2 * a2)) / (RC(BRDF_PI) * a2 * fmax(c2 * c2, RC(1e-30)));
}
BRDF_FN REAL brdf_d_beckmann(REAL c, REAL alpha) { return brdf_d_beckmann_cs(c, RC(1.0) - c, alpha); }

/* GGX D = a^2 / (pi cos^4 (a^2 + tan^2)^2) = a^2 / (pi (sin^2 + c^2 a^2)^2). */
BRDF_FN REAL brdf_d_ggx_cs(REAL c, REAL s, REAL alpha)
{
    REAL a2 = alpha * alpha;
    REAL d = brdf_sin2_cs(c, s) + c * c * a2;
    return a2 / (RC(BRDF_PI) * d * d);
}
BRDF_FN REAL brdf_d_ggx(REAL c, REAL alpha) { return brdf_d_ggx_cs(c, RC(1.0) - c, alpha); }

/* Normalisation of Phong: (n + 2) / (2 pi). */
BRDF_FN REAL brdf_phong_norm(REAL n) { return (n + RC(2.0)) / RC(2.0 * BRDF_PI); }

/* Normalisation of Blinn-Phong (Giesen): (n+2)(n+4) / (8 pi (2^(-n/2) + n)). */
BRDF_FN REAL brdf_blinn_norm(REAL n)
{
    return (n + RC(2.0)) * (n + RC(4.0)) / (RC(8.0 * BRDF_PI) * (exp2(-n * RC(0.5)) + n));
}

#ifdef BRDF_HAVE_USER_MODEL
/* Supplied by a user model file compiled at run time. */
BRDF_FN REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1);
#endif

/* Evaluate model `id` at cosine c, given as c and s = 1 - c (c in [0, 1]), and shininess n
   with parameters p0, p1. Formulas written in c - 1 take -s, which keeps every digit of
   1 - c near c = 1 where a float c has none left; with s = 1 - c computed from c (brdf_eval)
   the results are those of the same formulas in c, bit for bit (c - 1 = -(1 - c) exactly). */
BRDF_FN REAL brdf_eval_cs(int id, REAL c, REAL s, REAL n, RSCALAR p0, RSCALAR p1)
{
    switch (id) {
    case BRDF_PHONG:
    case BRDF_BLINN:    return brdf_pow_lobe_cs(c, s, n);
    case BRDF_PHONGPOW: return pow(c, n);
    case BRDF_CQ2:      return brdf_quadratic_s(s, n * RC(0.5));
    case BRDF_FVOL:     return brdf_quadratic_s(s, n * RC(0.463));
    case BRDF_FVOL64:   return brdf_quadratic_s(s, n * RC(29.0 / 64.0));
    case BRDF_SCHLICK:  return c / (n * s + c);
    case BRDF_LYON:     return brdf_lyon_s(s, n, (int)p0);
    case BRDF_FQ:       return brdf_quadratic_s(s, brdf_k_q(n, p0));
    case BRDF_FQ2:      return brdf_quadratic_s(s, n * RC(0.448) + RC(0.099));
    case BRDF_FQ2N:     return RC(0.214) * (RC(0.807) + n) * brdf_quadratic_s(s, n * RC(0.448) + RC(0.099));
    case BRDF_PHONGN:   return brdf_phong_norm(n) * brdf_pow_lobe_cs(c, s, n);
    case BRDF_BLINNN:   return brdf_blinn_norm(n) * brdf_pow_lobe_cs(c, s, n);
    case BRDF_BECKMANN: return brdf_d_beckmann_cs(c, s, brdf_alpha_from_n(n));
    case BRDF_GGX:      return brdf_d_ggx_cs(c, s, brdf_alpha_from_n(n));
    case BRDF_QUAD:     return brdf_quadratic_s(s, n * p0 + p1);
#ifdef BRDF_HAVE_USER_MODEL
    case BRDF_USER:     return brdf_user_eval(c, n, p0, p1);
#endif
    default:            return RSPLAT(NAN);
    }
}

/* Evaluate model `id` at cosine c and shininess n with parameters p0, p1. */
BRDF_FN REAL brdf_eval(int id, REAL c, REAL n, RSCALAR p0, RSCALAR p1)
{
    c = fmax(c, RC(0.0));
    return brdf_eval_cs(id, c, RC(1.0) - c, n, p0, p1);
}

/* Evaluate model `id` at s = 1 - c, s in [0, 1] (the accuracy sweep's variable). */
BRDF_FN REAL brdf_eval_s(int id, REAL s, REAL n, RSCALAR p0, RSCALAR p1)
{
    s = fmin(s, RC(1.0));
    return brdf_eval_cs(id, RC(1.0) - s, s, n, p0, p1);
}

#endif /* BRDF_MODELS_H */
