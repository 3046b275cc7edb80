/*
 * brdf_models.h - every lobe model of docs/definitions.md, written once.
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

/* A build specialised to one model (-DBRDF_ONLY_MODEL=id and -DBRDF_ONLY_REF=its reference's
   id, host/core/programs.c) switches on those constants: the compiler then emits their cases
   alone, and the other models' code is never generated (a driver that inlines every case into
   every call, such as Mesa's rusticl, spends minutes and gigabytes on the full dispatch). */

/* The dispatch over model ids (brdf_eval, brdf_eval_cs, brdf_eval_s): a kernel may define
 * BRDF_EVAL_FN to force it inline (accuracy.cl does; see there), and so does the host's tuned C
 * (host/support/hostc_baseline.c): left to itself, GCC calls the whole switch out of line once
 * per evaluation, with the model id an argument, and nothing is vectorised. */
#ifndef BRDF_EVAL_FN
#define BRDF_EVAL_FN BRDF_FN
#endif

/* A literal in the element type, so that float code never promotes to double. */
#define RC(x) ((RSCALAR)(x))
/* A scalar broadcast to REAL (a vector literal in OpenCL C, a cast in C). */
#define RSPLAT(x) ((REAL)(x))

/* RHALF(x): a value of a shader's half-precision code (half, min16float, mediump: the
 * shader-language translator wraps each such operation's result, host/core/shader/shaderlang_check.c).
 * The fp16 build of the accuracy sweep (-DBRDF_FP16, host/measure/accuracy/accuracy.c) rounds it to
 * binary16, to nearest with ties to even, through vstore_half_rte and reads it back with
 * vload_half: both are core OpenCL C on every device, with or without cl_khr_fp16. Every other
 * build (float, the double reference, the host's C) keeps the value as it is. */
#if defined(BRDF_FP16) && defined(__OPENCL_VERSION__)
__attribute__((overloadable)) static inline float brdf_round_half(float x)
{
    ushort b[1];
    vstore_half_rte(x, 0, (__private half *)b);
    return vload_half(0, (__private const half *)b);
}
__attribute__((overloadable)) static inline float16 brdf_round_half(float16 x)
{
    ushort b[16];
    vstore_half16_rte(x, 0, (__private half *)b);
    return vload_half16(0, (__private const half *)b);
}
#define RHALF(x) brdf_round_half(x)
#else
#define RHALF(x) (x)
#endif

#define BRDF_PI 3.14159265358979323846

#include "brdf_shared.h"

/* Model ids shared by the kernels and the host registry (host/core/models.c), in the order of
   kernels/brdf_model_list.h; a user model (compiled at run time, brdf_user_eval) comes last. */
enum brdf_model_id {
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) BRDF_##E,
#include "brdf_model_list.h"
#undef BRDF_MODEL
    BRDF_USER,
    BRDF_MODEL_COUNT
};

/* Epicentre zone end, as a cosine: the reference c^n equals e^(-0.511) there (docs/definitions.md). */
BRDF_FN REAL brdf_zone_epicentre_cos(REAL n) { return exp(RC(-BRDF_ZONE_K) / n); }

/* The lobe c^n, written as exp(n ln c), the way a shader compiler lowers pow (GPUs: exp2
 * and log2 units). PoCL 3.1's vector pow() runs at scalar speed (16-30 cycles a value) while
 * exp(n log c) costs about 1.6; the literal pow() stays available as the model phongpow.
 * In float, exp(n ln c) has a relative error of about |n ln c| ulp: below 1 ulp where
 * c^n > e^-1, and the double host reference checks every figure. c = 0 gives exp(-inf) = 0.
 * The host's tuned C baseline evaluates the same exp(n ln c), as the kernels do. */
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
/* ln u for u = 0 or u in [2^-24, 1] (the u = 1 - s above). On the device it is written out
 * rather than called: PoCL 3.1's vector log is an out-of-line SLEEF call, and every call in the
 * sweep's loop spills its sixteen-lane accumulators to the stack and back. u = m 2^k with m in
 * [sqrt(1/2), sqrt(2)), f = m - 1, t = f / (2 + f): ln m = 2 atanh t = 2t + 2t^3 (1/3 + t^2/5 +
 * t^4/7 + t^6/9 + ...), |t| <= 0.1716, so the series' next term is below 2^-28 of the sum; and
 * 2t = f - t f, which keeps the exact f as the leading term: ln m = f - t (f - 2 t^2 q). ln 2
 * is split so that k ln2_hi is exact. Every float u in [2^-24, 1] against the double log:
 * at most 0.94 ulp (SLEEF's logf_u10 is within 1.0); tests/test_ln_unit.c checks it. */
#ifdef __OPENCL_VERSION__
#define BRDF_LN_UNIT_BODY(F, I)                                                                    \
    I ix = as_##I(u) + (0x3f800000 - 0x3f3504f3);                                                  \
    F k = convert_##F(((ix >> 23) & 0xff) - 127);                                                  \
    F f = as_##F((ix & 0x007fffff) + 0x3f3504f3) - 1.0f;                                           \
    F t = f / (2.0f + f), t2 = t * t;                                                              \
    F q = fma(t2, fma(t2, fma(t2, 1.0f / 9.0f, 1.0f / 7.0f), 1.0f / 5.0f), 1.0f / 3.0f);            \
    F lnm = fma(-t, fma(-2.0f * t2, q, f), f);                                                     \
    return select(fma(k, 0.693145751953125f, fma(k, 1.428606765330187e-06f, lnm)), (F)(-INFINITY), \
                  u <= 0.0f)
__attribute__((overloadable)) static inline float brdf_ln_unit(float u) { BRDF_LN_UNIT_BODY(float, int); }
__attribute__((overloadable)) static inline float16 brdf_ln_unit(float16 u) { BRDF_LN_UNIT_BODY(float16, int16); }
#endif
/* The ln u of brdf_pow_lobe_s: log by default (the host's double; and field.cl, whose heatmap
 * cells stay bit-identical to a model written as exp(n log c)); accuracy.cl, where the sweep's
 * speed depends on it, defines it as brdf_ln_unit. */
#ifndef BRDF_LN_UNIT
#define BRDF_LN_UNIT(u) log(u)
#endif
BRDF_FN REAL brdf_pow_lobe_s(REAL s, REAL n)
{
    REAL u = RC(1.0) - s;
    return exp(n * (BRDF_LN_UNIT(u) + BRDF_SMALL_DIVIDE((RC(1.0) - u) - s, fmax(u, RC(1e-30)))));
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

/* ---- the approximations engines use (docs/definitions.md, "The approximations engines use") ---------- */

/* The Gaussian lobe exp(k (c - 1)) = exp(-k s); engines write exp2(k/ln 2 (c - 1)), the same
 * function. */
BRDF_FN REAL brdf_gauss_lobe_s(REAL s, REAL k) { return exp(-k * s); }

/* The power family (k (c - 1) + 1)^m zeroed past its root, m an integer in [1, 16], by
 * squarings and multiplies (binary exponentiation; a constant m unrolls). */
BRDF_FN REAL brdf_power(REAL c, REAL k, int m)
{
    REAL base = fmax(k * (c - RC(1.0)) + RC(1.0), RC(0.0));
    REAL result = RSPLAT(1.0);
    for (; m > 0; m >>= 1) {
        if (m & 1)
            result = result * base;
        base = base * base;
    }
    return result;
}

/* Beaudoin and Guardado 2002: max(0, A c + B)^m with B = 1 - A, i.e. the power family with
 * k = A. Their A comes from a per-n bisection (host/measure/fit/fit.c, bg_exact_a, for the claim);
 * the device gets it from the affine fit A(n) = alpha_m n + beta_m of those bisection values
 * over n in [2, 1000] (least squares in relative terms), within 2.4% of the bisection A
 * (at n = 2) for every m. m = 2^j, j = 1..4 (the registry's parameter j). */
#define BRDF_BG_ALPHA_2 0.355728074
#define BRDF_BG_BETA_2 0.264367919
#define BRDF_BG_ALPHA_4 0.211256260
#define BRDF_BG_BETA_4 0.157725393
#define BRDF_BG_ALPHA_8 0.114952593
#define BRDF_BG_BETA_8 0.085811949
#define BRDF_BG_ALPHA_16 0.059933489
#define BRDF_BG_BETA_16 0.044726082
/* The power family's base, zeroed past its root, and its cube and fourth power written out
 * (what the device runs: no loop to unroll), and 2^j by j squarings as Lyon's. */
BRDF_FN REAL brdf_power_base_s(REAL s, REAL k) { return fmax(RC(1.0) - k * s, RC(0.0)); }
BRDF_FN REAL brdf_cube_s(REAL s, REAL k)
{
    REAL b = brdf_power_base_s(s, k);
    return b * b * b;
}
BRDF_FN REAL brdf_fourth_s(REAL s, REAL k)
{
    REAL b = brdf_power_base_s(s, k);
    REAL b2 = b * b;
    return b2 * b2;
}
BRDF_FN REAL brdf_squarings_s(REAL s, REAL k, int j)
{
    REAL b = brdf_power_base_s(s, k);
    for (int i = 0; i < j; ++i)
        b = b * b;
    return b;
}

BRDF_FN REAL brdf_bg_a(REAL n, int m)
{
    if (m <= 2) return n * RC(BRDF_BG_ALPHA_2) + RC(BRDF_BG_BETA_2);
    if (m <= 4) return n * RC(BRDF_BG_ALPHA_4) + RC(BRDF_BG_BETA_4);
    if (m <= 8) return n * RC(BRDF_BG_ALPHA_8) + RC(BRDF_BG_BETA_8);
    return n * RC(BRDF_BG_ALPHA_16) + RC(BRDF_BG_BETA_16);
}

/* Kuijk and Blake 1989, in the angle alpha = acos c = 2 asin(sqrt(s/2)) (s = 1 - c: the
 * form that keeps alpha's precision near c = 1, where acos of a float cosine has none):
 * 1 - alpha^2/(ab) below a,
 * (alpha - b)^2 / (b (b - a)) from a to b, 0 beyond; zeroed where negative (the exchanged
 * a and b give a > b, and the first piece then falls below 0). */
BRDF_FN REAL brdf_kb_a(REAL n) { return (n + RC(5.6)) / (n * (RC(0.09) * n + RC(5.2))); }
BRDF_FN REAL brdf_kb_b(REAL n) { return (n + RC(65.0)) / (RC(5.0) * n + RC(31.7)); }
BRDF_FN REAL brdf_kuijk_blake_s(REAL s, REAL a, REAL b)
{
    REAL alpha = RC(2.0) * asin(sqrt(fmax(s, RC(0.0)) * RC(0.5)));
    REAL inner = RC(1.0) - alpha * alpha / (a * b);
    REAL outer = (alpha - b) * (alpha - b) / (b * (b - a));
    REAL f = alpha < a ? inner : (alpha < b ? outer : RSPLAT(0.0));
    return fmax(f, RC(0.0));
}

/* The integer-bit pow (Schraudolph 1999 style): the float whose bits are
 * n (bits(c) - bits(1)) + bits(1), with bits(1.0f) = 0x3f800000; a negative result is 0.
 * On the device it is written as shaders write it, on the float's bits (scalar and float16):
 * the product n (bits(c) - bits(1)) in float, truncated to an integer (saturating), then the
 * integer add, so the only float rounding is the product's (about 1e-7 of the value).
 * The host reference reproduces the same arithmetic in double: bits(c) - bits(1) is
 * 2^23 (e + m - 1) for c = m 2^e (m in [1, 2)), and a bit pattern t >= 0 is read back the same
 * way, so the host figure is the trick's own error, not float rounding. */
#ifdef __OPENCL_VERSION__
__attribute__((overloadable)) static inline float brdf_bitpow(float c, float n)
{
    int t = convert_int_sat_rtz(n * convert_float(as_int(c) - 0x3f800000)) + 0x3f800000;
    return as_float(max(t, 0));
}
__attribute__((overloadable)) static inline float16 brdf_bitpow(float16 c, float16 n)
{
    int16 t = convert_int16_sat_rtz(n * convert_float16(as_int16(c) - 0x3f800000)) + 0x3f800000;
    return as_float16(max(t, 0));
}
#else
BRDF_FN REAL brdf_bitpow(REAL c, REAL n)
{
    /* log2 as the bit pattern reads it: e + (m - 1), with c = m 2^e, m in [1, 2) */
    int e;
    double mant = frexp((double)c, &e);   /* c = mant 2^e, mant in [0.5, 1) */
    double l2 = (c > 0) ? (double)(e - 1) + (2.0 * mant - 1.0) : -HUGE_VAL;
    double t = (double)n * l2 + 127.0;   /* the result's bits / 2^23 */
    if (!(t > 0))
        return (REAL)0.0;
    if (t < 1.0)                          /* a subnormal bit pattern: t 2^23 units of 2^-149 */
        return (REAL)ldexp(t, -126);
    double te = floor(t);
    return (REAL)ldexp(1.0 + (t - te), (int)te - 127);
}
#endif

/* Frozen minimax members of the families above: the least largest epicentre max delta over
 * n in [2, 1000] step 1, as found by `brdfbench fit --family pow3|pow4|gauss` (docs/frontier.md
 * gives the commands and their figures: pow4fit 0.567% / 0.0723, pow3fit 0.760% / 0.0809,
 * gaussfit 1.100% / 0.1299 for max delta / max Delta). */
#define BRDF_CUBEFIT_A 0.3106866803
#define BRDF_CUBEFIT_B 0.07545118726
#define BRDF_QUARTFIT_A 0.2371428753
#define BRDF_QUARTFIT_B 0.05221691603
#define BRDF_GAUSSFIT_A 1.020199565
#define BRDF_GAUSSFIT_B 0.1774327237
/* ---- physically based BRDFs: f(N, L, V) from the three cosines N.L, N.V, L.V -------------- */

#ifdef __OPENCL_VERSION__
/* b where cond holds, else a, for every REAL: a scalar comparison gives an int (1 or 0), a
   vector one an int or long vector (-1 or 0), which select() takes only for vectors. */
#define BRDF_SELECT(a, b, cond) brdf_sel((a), (b), (cond))
#define BRDF_RSQRT(x) rsqrt(x)
#define BRDF_SEL_VEC(T, I)                                                                     \
    static inline T __attribute__((overloadable)) brdf_sel(T a, T b, I c) { return select(a, b, c); } \
    static inline int __attribute__((overloadable)) brdf_any_lane(I x) { return any(x); }
static inline float __attribute__((overloadable)) brdf_sel(float a, float b, int c) { return c ? b : a; }
/* Whether any lane of a comparison holds. */
static inline int __attribute__((overloadable)) brdf_any_lane(int x) { return x != 0; }
BRDF_SEL_VEC(float2, int2)
BRDF_SEL_VEC(float4, int4)
BRDF_SEL_VEC(float8, int8)
BRDF_SEL_VEC(float16, int16)
#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
static inline double __attribute__((overloadable)) brdf_sel(double a, double b, int c) { return c ? b : a; }
BRDF_SEL_VEC(double2, long2)
BRDF_SEL_VEC(double4, long4)
BRDF_SEL_VEC(double8, long8)
BRDF_SEL_VEC(double16, long16)
#endif
#else
#define BRDF_SELECT(a, b, cond) ((cond) ? (b) : (a))
#define BRDF_RSQRT(x) (1.0 / sqrt(x))
#define brdf_any_lane(x) ((x) != 0)
#endif

/* Separable Smith masking G1 of GGX for a direction with cosine x to the normal. */
BRDF_FN REAL brdf_smith_g1_ggx(REAL x, REAL alpha)
{
    REAL a2 = alpha * alpha;
    return RC(2.0) * x / (x + sqrt(a2 + (RC(1.0) - a2) * x * x));
}

/* Smith G1 of Beckmann in the rational form of Walter et al. 2007. */
BRDF_FN REAL brdf_smith_g1_beckmann(REAL x, REAL alpha)
{
    REAL a = x / (alpha * sqrt(fmax(RC(1.0) - x * x, RC(1e-12))));
    REAL g = (RC(3.535) * a + RC(2.181) * a * a) / (RC(1.0) + RC(2.276) * a + RC(2.577) * a * a);
    return BRDF_SELECT(g, RSPLAT(1.0), a >= RC(1.6));
}

/* Schlick's Fresnel from the cosine between V and H. */
BRDF_FN REAL brdf_fresnel_schlick(REAL vdoth, RSCALAR f0)
{
    REAL m = RC(1.0) - vdoth;
    REAL m2 = m * m;
    return f0 + (RC(1.0) - f0) * (m2 * m2 * m);
}

/* ---- terms of a microfacet BRDF as lobes of one cosine (the TERM rows of brdf_model_list.h) ----
 * c is the cosine of the angle of incidence with L and V mirrored about N (H = N, so
 * N.L = N.V = L.H = c), the geometry where F and G show; n is the term's own axis: the index of
 * refraction for a Fresnel term, the shininess of alpha = sqrt(2/(n+2)) for a G term. */

/* Exact Fresnel reflectance of unpolarised light at a dielectric of relative index eta, for the
 * cosine c of the angle of incidence (Cook and Torrance 1982's form): with g^2 = eta^2 - 1 + c^2,
 * F = (g - c)^2 / (2 (g + c)^2) (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2); 1 where g^2 < 0
 * (eta < 1 past the critical angle: total internal reflection). */
BRDF_FN REAL brdf_fresnel_dielectric(REAL c, REAL eta)
{
    REAL g2 = eta * eta - RC(1.0) + c * c;
    REAL g = sqrt(fmax(g2, RC(0.0)));
    REAL a = (g - c) / fmax(g + c, RC(1e-30));
    REAL b = (c * (g + c) - RC(1.0)) / (c * (g - c) + RC(1.0));
    return BRDF_SELECT(RC(0.5) * a * a * (RC(1.0) + b * b), RSPLAT(1.0), g2 < RC(0.0));
}

/* Schlick's approximation of it: F0 + (1 - F0) (1 - c)^5 with F0 = ((eta - 1) / (eta + 1))^2, the
 * exact value at normal incidence; s = 1 - c. */
BRDF_FN REAL brdf_fresnel_schlick_eta(REAL s, REAL eta)
{
    REAL r = (eta - RC(1.0)) / (eta + RC(1.0));
    REAL f0 = r * r;
    REAL s2 = s * s;
    return f0 + (RC(1.0) - f0) * (s2 * s2 * s);
}

/* Smith's masking-shadowing of GGX for light and view cosines nl, nv (both > 0), with
 * q(x) = sqrt(a^2 + (1 - a^2) x^2) = x sqrt(1 + a^2 tan^2): separable, G1(nl) G1(nv) with
 * G1(x) = 2x / (x + q(x)) (Walter et al. 2007), and height-correlated, 1 / (1 + Lambda(nl) +
 * Lambda(nv)) with Lambda(x) = (q(x)/x - 1)/2, i.e. 2 nl nv / (nv q(nl) + nl q(nv)) (Heitz 2014). */
BRDF_FN REAL brdf_smith_ggx_separable(REAL nl, REAL nv, REAL alpha)
{
    return brdf_smith_g1_ggx(nl, alpha) * brdf_smith_g1_ggx(nv, alpha);
}
BRDF_FN REAL brdf_smith_ggx_correlated(REAL nl, REAL nv, REAL alpha)
{
    REAL a2 = alpha * alpha;
    REAL ql = sqrt(a2 + (RC(1.0) - a2) * nl * nl), qv = sqrt(a2 + (RC(1.0) - a2) * nv * nv);
    return RC(2.0) * nl * nv / fmax(nv * ql + nl * qv, RC(1e-30));   /* 0, not 0/0, at nl = nv = 0 */
}

/* Fresnel reflectance of unpolarised light, (F_s + F_p) / 2, at an interface with complex index
 * n_re + i n_im, for the cosine c of the angle of incidence (Born & Wolf's a, b form:
 * 2a^2 = sqrt(A^2 + 4 n^2 k^2) + A, 2b^2 = sqrt(A^2 + 4 n^2 k^2) - A, A = n^2 - k^2 - sin^2). */
BRDF_FN REAL brdf_fresnel_complex(REAL c, RSCALAR n_re, RSCALAR n_im)
{
    c = fmin(fmax(c, RC(1e-6)), RC(1.0));
    REAL s2 = brdf_sin2(c);
    REAL big_a = RC(n_re * n_re - n_im * n_im) - s2;
    REAL root = sqrt(big_a * big_a + RC(4.0 * n_re * n_re * n_im * n_im));
    REAL a = sqrt(fmax(RC(0.5) * (root + big_a), RC(0.0)));
    REAL b2 = fmax(RC(0.5) * (root - big_a), RC(0.0));
    REAL fs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);
    REAL st = s2 / c; /* sin * tan */
    REAL fp = fs * ((a - st) * (a - st) + b2) / ((a + st) * (a + st) + b2);
    return RC(0.5) * (fs + fp);
}

/* Lambert's W0(x) for x >= 0: Newton's method on w e^w = x from log1p(x), which lies above the
 * root, where the function is convex: the iterates fall monotonically (8 steps reach double
 * precision for x up to 1e6). */
BRDF_FN REAL brdf_lambert_w0(REAL x)
{
    REAL w = log1p(x);
    for (int i = 0; i < 8; ++i)
        w = w - (w - x * exp(-w)) / (w + RC(1.0));
    return w;
}

/* He et al. 1991: K(theta) = tan(theta) erfc(tau / (2 sigma0 tan(theta))), from the cosine. */
BRDF_FN REAL brdf_he_k(REAL c, RSCALAR sigma0, RSCALAR tau)
{
    REAL s = sqrt(brdf_sin2(c));
    REAL t = s / c;
    return t * erfc(RC(tau / (2.0 * sigma0)) * c / fmax(s, RC(1e-30)));
}

/* He et al. 1991: the shadowing function S(theta) (Smith's, for a Gaussian surface of rms slope
 * 2 sigma0 / tau): (1 - erfc(e)/2) / (Lambda + 1), Lambda = (exp(-e^2)/(sqrt(pi) e) - erfc(e))/2,
 * e = tau cot(theta) / (2 sigma0). */
BRDF_FN REAL brdf_he_shadow(REAL c, RSCALAR sigma0, RSCALAR tau)
{
    REAL s = fmax(sqrt(brdf_sin2(c)), RC(1e-30));
    REAL e = fmax(RC(tau / (2.0 * sigma0)) * c / s, RC(1e-30));
    REAL ec = erfc(e);
    REAL lambda = RC(0.5) * (exp(-e * e) / (RC(1.7724538509055160273) * e) - ec);
    return (RC(1.0) - RC(0.5) * ec) / (lambda + RC(1.0));
}

/* Where the directional-diffuse sum stops: a term below float resolution of the running sum,
 * past the terms' peak (m >= g). BRDF_HE_MAX_TERMS bounds the loop. */
#define BRDF_HE_EPS 5.9604644775390625e-8
#define BRDF_HE_MAX_TERMS 2000

/* The directional-diffuse sum of He et al. 1991,
 *   sum_{m >= 1} g^m e^(-g) / (m! m) exp(-x / m),   x = v_xy^2 tau^2 / 4,
 * each term formed in logarithms (g^m e^-g / m! underflows for g > 87 in float), and the number
 * of terms each lane took. */
struct brdf_he_sum_result {
    REAL sum;
    REAL terms;
};
BRDF_FN struct brdf_he_sum_result brdf_he_dd_sum(REAL g, REAL x)
{
    struct brdf_he_sum_result r;
    REAL lng = log(fmax(g, RC(1e-30)));
    REAL lt = -g;                       /* log(g^m e^-g / m!) at m = 0 */
    REAL active = BRDF_SELECT(RSPLAT(0.0), RSPLAT(1.0), g > RC(0.0));
    r.sum = RSPLAT(0.0);
    r.terms = RSPLAT(0.0);
    for (int m = 1; m <= BRDF_HE_MAX_TERMS && brdf_any_lane(active > RC(0.5)); ++m) {
        RSCALAR rm = (RSCALAR)m;
        lt = lt + lng - RC(log(rm));
        REAL term = exp(lt - x / rm) / rm;
        r.sum = r.sum + term * active;
        r.terms = r.terms + active;
        active = BRDF_SELECT(active, RSPLAT(0.0), (g <= rm) & (term <= RC(BRDF_HE_EPS) * r.sum));
    }
    return r;
}

/* The material presets of the He model (p0): wavelength and roughness in micrometres.
 * field: 0 wavelength, 1 sigma0 (rms height), 2 tau (autocorrelation length), 3 n, 4 k
 * (complex index n + ik at the wavelength), 5 uniform-diffuse BRDF a (1/sr). The indices are
 * published values at 550 nm (host/core/models.c names the sources); the roughness pairs are
 * chosen to span the model's regimes (see there). */
#define BRDF_HE_PRESETS 4
BRDF_FN RSCALAR brdf_he_preset(int preset, int field)
{
    switch (preset * 8 + field) {
    /* 0: rough aluminium, sigma0/lambda = 0.18 */
    case 0: return RC(0.55); case 1: return RC(0.10); case 2: return RC(1.00);
    case 3: return RC(0.958); case 4: return RC(6.69); case 5: return RC(0.0);
    /* 1: polished aluminium, sigma0/lambda = 0.036 (the specular term dominates) */
    case 8: return RC(0.55); case 9: return RC(0.02); case 10: return RC(1.00);
    case 11: return RC(0.958); case 12: return RC(6.69); case 13: return RC(0.0);
    /* 2: gold, sigma0/lambda = 0.18 */
    case 16: return RC(0.55); case 17: return RC(0.10); case 18: return RC(1.00);
    case 19: return RC(0.43); case 20: return RC(2.455); case 21: return RC(0.0);
    /* 3: a plastic (PMMA-like dielectric, n = 1.49) with a uniform-diffuse term */
    case 24: return RC(0.55); case 25: return RC(0.10); case 26: return RC(1.00);
    case 27: return RC(1.49); case 28: return RC(0.0); case 29: return RC(0.15);
    default: return RC(0.0);
    }
}

/* Angular radius of the light source the specular (mirror) term of the He model sees: the
 * specular term is a delta in the mirror direction, spread here over a source of 1 degree. */
#define BRDF_HE_SOURCE_COS 0.99984769515639123916
#define BRDF_HE_SOURCE_SOLID_ANGLE (2.0 * BRDF_PI * (1.0 - BRDF_HE_SOURCE_COS))

/* He et al. 1991, rho = rho_sp + rho_dd + rho_ud for unit N, L, V given as their cosines:
 *   rho_sp = F(b) e^-g S / (sqrt(cos theta_i cos theta_r) dw)   inside the source's cone around R,
 *            else 0: He's F(theta_i) e^-g S / (cos theta_i dw) at the mirror direction itself,
 *            where the delta sits (b = theta_i = theta_r there), written symmetrically so that
 *            the finite cone keeps the BRDF reciprocal
 *   rho_dd = F(b) G S / (pi cos theta_i cos theta_r) * pi^2 tau^2 / (4 lambda^2) * sum(g, x)
 *   rho_ud = a
 * with v = k (V + L) (k = 2 pi / lambda), g = (k sigma (cos theta_i + cos theta_r))^2 the
 * effective roughness, sigma = sigma0 / sqrt(1 + z0^2 / sigma0^2) where
 * sqrt(pi/2) z0 = sigma0 (K_i + K_r) / 4 exp(-z0^2 / (2 sigma0^2)), i.e. (z0/sigma0)^2 =
 * W0(((K_i + K_r) / (4 sqrt(pi/2)))^2); S = S(theta_i) S(theta_r); F(b) the Fresnel
 * reflectance at the bisector, cos b = |V + L| / 2; G = (v.v / v_z)^2 (He's geometric factor
 * for unpolarised light: the two polarisation brackets each equal |k_r x k_i|^2);
 * x = v_xy^2 tau^2 / 4. terms (may be 0) receives the number of terms of the sum. */
BRDF_FN REAL brdf_he_terms(REAL nl, REAL nv, REAL lv, RSCALAR lambda, RSCALAR sigma0, RSCALAR tau,
                           RSCALAR n_re, RSCALAR n_im, RSCALAR ud, REAL *terms)
{
    REAL ci = fmax(nl, RC(1e-6)), cr = fmax(nv, RC(1e-6));
    RSCALAR k = RC(2.0 * BRDF_PI) / lambda;
    REAL amp = (brdf_he_k(ci, sigma0, tau) + brdf_he_k(cr, sigma0, tau)) * RC(0.19947114020071633897); /* /(4 sqrt(pi/2)) */
    REAL sigma = sigma0 * BRDF_RSQRT(RC(1.0) + brdf_lambert_w0(amp * amp));
    REAL vz = ci + cr;
    REAL ksv = k * sigma * vz;
    REAL g = ksv * ksv;
    REAL vv = fmax(RC(2.0) + RC(2.0) * lv, RC(1e-12));
    REAL vxy2 = fmax(vv - vz * vz, RC(0.0));
    struct brdf_he_sum_result dd = brdf_he_dd_sum(g, vxy2 * RC(k * k * tau * tau * 0.25));
    if (terms)
        *terms = dd.terms;
    REAL shadow = brdf_he_shadow(ci, sigma0, tau) * brdf_he_shadow(cr, sigma0, tau);
    REAL geo = vv / vz;
    REAL rho_dd = brdf_fresnel_complex(RC(0.5) * sqrt(vv), n_re, n_im) * geo * geo * shadow /
                  (RC(BRDF_PI) * ci * cr) * RC(k * k * tau * tau / 16.0) * dd.sum;
    REAL rv = RC(2.0) * nl * nv - lv;   /* R.V */
    REAL rho_sp = brdf_fresnel_complex(RC(0.5) * sqrt(vv), n_re, n_im) * exp(-g) * shadow /
                  (sqrt(ci * cr) * RC(BRDF_HE_SOURCE_SOLID_ANGLE));
    rho_sp = BRDF_SELECT(RSPLAT(0.0), rho_sp, rv >= RC(BRDF_HE_SOURCE_COS));
    REAL f = rho_sp + rho_dd + ud;
    return BRDF_SELECT(RSPLAT(0.0), f, (nl > RC(0.0)) & (nv > RC(0.0)));
}

/* tan^2 theta_h from its cosine. */
BRDF_FN REAL brdf_tan2(REAL c) { return brdf_sin2(c) / fmax(c * c, RC(1e-30)); }

/* A physically based model's BRDF f(L, V) from nl = N.L, nv = N.V, lv = L.V (unit vectors),
 * with ch = N.H and vh = V.H of the half vector H = (L + V) / |L + V| (brdf_pb_eval_ud forms
 * them), shininess n (alpha(n) for the microfacet ones) and the model's parameters. 0 where L
 * or V is below the surface. ud_scale multiplies He's uniform-diffuse term (0 in the image
 * passes, which add their own diffuse term). */
BRDF_FN REAL brdf_pb_eval_h(int id, REAL nl, REAL nv, REAL lv, REAL ch, REAL vh, REAL n, RSCALAR p0, RSCALAR p1,
                            RSCALAR ud_scale)
{
    REAL cl = fmax(nl, RC(1e-6)), cv = fmax(nv, RC(1e-6));
    REAL alpha = brdf_alpha_from_n(n);
    REAL f;
    switch (id) {
    case BRDF_CT_BECKMANN:
        f = brdf_d_beckmann(ch, alpha) * brdf_fresnel_schlick(vh, p0) *
            brdf_smith_g1_beckmann(cl, alpha) * brdf_smith_g1_beckmann(cv, alpha) / (RC(4.0) * cl * cv);
        break;
    case BRDF_CT_GGX:
        f = brdf_d_ggx(ch, alpha) * brdf_fresnel_schlick(vh, p0) *
            brdf_smith_g1_ggx(cl, alpha) * brdf_smith_g1_ggx(cv, alpha) / (RC(4.0) * cl * cv);
        break;
    case BRDF_BRADY:
        f = brdf_d_beckmann(ch, alpha) * brdf_smith_g1_beckmann(cl, alpha) * brdf_smith_g1_beckmann(cv, alpha) /
            (brdf_tan2(ch) / RC(p0 * p0 * p1 * p1) + RC(0.9994));
        break;
    case BRDF_HE: {
        int m = (int)p0;
        return brdf_he_terms(nl, nv, lv, brdf_he_preset(m, 0), brdf_he_preset(m, 1), brdf_he_preset(m, 2),
                             brdf_he_preset(m, 3), brdf_he_preset(m, 4), ud_scale * brdf_he_preset(m, 5), 0);
    }
    default:
        return RSPLAT(NAN);
    }
    return BRDF_SELECT(RSPLAT(0.0), f, (nl > RC(0.0)) & (nv > RC(0.0)));
}
BRDF_FN REAL brdf_pb_eval_ud(int id, REAL nl, REAL nv, REAL lv, REAL n, RSCALAR p0, RSCALAR p1, RSCALAR ud_scale)
{
    REAL vv = fmax(RC(2.0) + RC(2.0) * lv, RC(1e-12));
    REAL hinv = BRDF_RSQRT(vv);
    REAL ch = fmax((nl + nv) * hinv, RC(0.0));   /* N.H */
    REAL vh = RC(0.5) * vv * hinv;                /* V.H = |L + V| / 2 */
    return brdf_pb_eval_h(id, nl, nv, lv, ch, vh, n, p0, p1, ud_scale);
}
BRDF_FN REAL brdf_pb_eval(int id, REAL nl, REAL nv, REAL lv, REAL n, RSCALAR p0, RSCALAR p1)
{
    return brdf_pb_eval_ud(id, nl, nv, lv, n, p0, p1, RC(1.0));
}

/* A physically based model as a lobe of one cosine c: the BRDF with the light at the normal
 * (N.L = 1) and the viewer where theta_h = acos(c), i.e. N.V = L.V = 2c^2 - 1 (0 past
 * theta_h = 45 degrees, where V goes below the horizon). N.H = V.H = c are passed as they are:
 * rebuilt from 2c^2 - 1 in float they would lose the digits a sharp lobe needs. */
BRDF_FN REAL brdf_pb_lobe(int id, REAL c, REAL n, RSCALAR p0, RSCALAR p1)
{
    REAL nv = RC(2.0) * c * c - RC(1.0);
    return BRDF_SELECT(brdf_pb_eval_h(id, RSPLAT(1.0), nv, nv, c, c, n, p0, p1, RC(1.0)), RSPLAT(0.0),
                       nv <= RC(0.0));
}

#ifdef BRDF_HAVE_USER_MODEL
/* Supplied by a user model file compiled at run time. */
BRDF_FN REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1);
#endif
#ifdef BRDF_HAVE_USER_FULL
/* A user full BRDF at the vectors L, V, N of a scene (luminance; docs/user-models.md). */
BRDF_FN REAL brdf_user_full(REAL lx, REAL ly, REAL lz, REAL vx, REAL vy, REAL vz, REAL nx, REAL ny, REAL nz, REAL n,
                            RSCALAR p0, RSCALAR p1);
#endif

/* Evaluate model `id` at cosine c, given as c and s = 1 - c (c in [0, 1]), and shininess n
   with parameters p0, p1. Formulas written in c - 1 take -s, which keeps every digit of
   1 - c near c = 1 where a float c has none left; with s = 1 - c computed from c (brdf_eval)
   the results are those of the same formulas in c, bit for bit (c - 1 = -(1 - c) exactly). */
/* The dispatch's cases, switched on ID: a constant ID (a specialised build) makes the compiler
   emit that case alone. */
#ifdef BRDF_HAVE_USER_MODEL
#define BRDF_USER_CASE case BRDF_USER: return brdf_user_eval(c, n, p0, p1);
#else
#define BRDF_USER_CASE
#endif
/* The dispatch's cases, one per row of kernels/brdf_model_list.h. */
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) case BRDF_##E: return EVAL;

BRDF_EVAL_FN REAL brdf_eval_cs(int id, REAL c, REAL s, REAL n, RSCALAR p0, RSCALAR p1)
{
#ifdef BRDF_ONLY_MODEL
    /* a build specialised to one model and its reference (-DBRDF_ONLY_MODEL, -DBRDF_ONLY_REF) */
    if (id == BRDF_ONLY_MODEL) {
        switch (BRDF_ONLY_MODEL) {
#include "brdf_model_list.h"
        BRDF_USER_CASE
        default: break;
        }
    }
#ifdef BRDF_ONLY_REF
    if (id == BRDF_ONLY_REF) {
        switch (BRDF_ONLY_REF) {
#include "brdf_model_list.h"
        BRDF_USER_CASE
        default: break;
        }
    }
#endif
    return RSPLAT(NAN);
#else
    switch (id) {
#include "brdf_model_list.h"
    BRDF_USER_CASE
    default: return RSPLAT(NAN);
    }
#endif
}
#undef BRDF_MODEL

/* 1 when model id's formula takes c alone, not s = 1 - c (kernels/brdf_model_list.h's C_ONLY,
   and every user model): the accuracy sweep then hands it c rounded from s, as a shader would. */
BRDF_FN int brdf_sees_only_c(int id)
{
    switch (id) {
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) case BRDF_##E: return C_ONLY;
#include "brdf_model_list.h"
#undef BRDF_MODEL
    default: return 1;
    }
}

/* Evaluate model `id` at cosine c and shininess n with parameters p0, p1. */
BRDF_EVAL_FN REAL brdf_eval(int id, REAL c, REAL n, RSCALAR p0, RSCALAR p1)
{
    c = fmax(c, RC(0.0));
    return brdf_eval_cs(id, c, RC(1.0) - c, n, p0, p1);
}

/* Evaluate model `id` at s = 1 - c, s in [0, 1] (the accuracy sweep's variable). */
BRDF_EVAL_FN REAL brdf_eval_s(int id, REAL s, REAL n, RSCALAR p0, RSCALAR p1)
{
    s = fmin(s, RC(1.0));
    return brdf_eval_cs(id, RC(1.0) - s, s, n, p0, p1);
}


/* ---- measured BRDFs: the MERL table (Matusik, Pfister, Brand, McMillan 2003; docs/measured.md) ---- */

/* The table's dimensions (theta_h, theta_d, phi_d) and each channel's scale to sr^-1. */
#define BRDF_MERL_TH 90
#define BRDF_MERL_TD 90
#define BRDF_MERL_PD 180
#define BRDF_MERL_CELLS (BRDF_MERL_TH * BRDF_MERL_TD * BRDF_MERL_PD)
#define BRDF_MERL_SCALE_R (1.0 / 1500.0)
#define BRDF_MERL_SCALE_G (1.15 / 1500.0)
#define BRDF_MERL_SCALE_B (1.66 / 1500.0)

/* Rusinkiewicz's half/difference angles of unit L and V about N = z (tangent space):
 * H = (L + V)/|L + V|, theta_h = angle(N, H), phi_h its azimuth; D = L rotated by -phi_h about N
 * and then by -theta_h about the binormal y, theta_d = angle(N, D), phi_d its azimuth in
 * (-pi, pi]. The polar angles come from atan2 of the sine and the cosine: acos of a float
 * cosine has no digits left below theta ~ 3e-4, where the table's second theta_h cell starts
 * (1.9e-4). At H = N the azimuth phi_h is 0 (atan2(0, 0) = 0). */
BRDF_FN void brdf_merl_half_diff(RSCALAR lx, RSCALAR ly, RSCALAR lz, RSCALAR vx, RSCALAR vy, RSCALAR vz,
                                 RSCALAR *theta_h, RSCALAR *theta_d, RSCALAR *phi_d)
{
    RSCALAR hx = lx + vx, hy = ly + vy, hz = lz + vz;
    RSCALAR hxy = sqrt(hx * hx + hy * hy);
    RSCALAR th = atan2(hxy, hz);
    RSCALAR ph = atan2(hy, hx);
    RSCALAR cp = cos(ph), sp = sin(ph), ct = cos(th), st = sin(th);
    RSCALAR x1 = lx * cp + ly * sp, y1 = -lx * sp + ly * cp;   /* rotated by -phi_h about z */
    RSCALAR x2 = x1 * ct - lz * st, z2 = x1 * st + lz * ct;    /* then by -theta_h about y */
    *theta_h = th;
    *theta_d = atan2(sqrt(x2 * x2 + y1 * y1), z2);
    *phi_d = atan2(y1, x2);
}

/* The cell of (theta_h, theta_d, phi_d): theta_h_i = floor(90 sqrt(theta_h / (pi/2))),
 * theta_d_i = floor(90 theta_d / (pi/2)), phi_d folded into [0, pi) by reciprocity (phi_d < 0:
 * + pi) and phi_d_i = floor(180 phi_d / pi), each clamped to its range (a NaN angle reads as 0);
 * the flat index phi_d_i + 180 (theta_d_i + 90 theta_h_i). No interpolation: the table's value is
 * that of the cell holding the direction. */
BRDF_FN int brdf_merl_index3(RSCALAR theta_h, RSCALAR theta_d, RSCALAR phi_d, int *ith, int *itd, int *ipd)
{
    if (phi_d < RC(0.0))
        phi_d = phi_d + RC(BRDF_PI);
    RSCALAR fh = floor(sqrt(fmax(theta_h, RC(0.0)) / RC(BRDF_PI / 2.0)) * RC(BRDF_MERL_TH));
    RSCALAR fd = floor(theta_d / RC(BRDF_PI / 2.0) * RC(BRDF_MERL_TD));
    RSCALAR fp = floor(phi_d / RC(BRDF_PI) * RC(BRDF_MERL_PD));
    int i = (int)fmin(fmax(fh, RC(0.0)), RC(BRDF_MERL_TH - 1));
    int j = (int)fmin(fmax(fd, RC(0.0)), RC(BRDF_MERL_TD - 1));
    int k = (int)fmin(fmax(fp, RC(0.0)), RC(BRDF_MERL_PD - 1));
    *ith = i;
    *itd = j;
    *ipd = k;
    return k + BRDF_MERL_PD * (j + BRDF_MERL_TD * i);
}

/* The half/difference angles of unit L, V about a unit normal N of a scene: L and V in the tangent
 * frame (T, B, N), T from the axis least aligned with N made orthogonal to it, B = N x T (for an
 * isotropic table the frame's turn about N drops out), then brdf_merl_half_diff. The host's
 * lookup (host/core/merl.c) and the device's (render, the physical-cost table) share it. */
BRDF_FN void brdf_merl_half_diff_n(RSCALAR lx, RSCALAR ly, RSCALAR lz, RSCALAR vx, RSCALAR vy, RSCALAR vz,
                                   RSCALAR nx, RSCALAR ny, RSCALAR nz, RSCALAR *theta_h, RSCALAR *theta_d,
                                   RSCALAR *phi_d)
{
    RSCALAR ax = fabs(nx), ay = fabs(ny), az = fabs(nz);
    RSCALAR tx = RC(0.0), ty = RC(0.0), tz = RC(0.0);
    if (ax <= ay && ax <= az)
        tx = RC(1.0);
    else if (ay <= az)
        ty = RC(1.0);
    else
        tz = RC(1.0);
    RSCALAR d = tx * nx + ty * ny + tz * nz;
    tx -= d * nx;
    ty -= d * ny;
    tz -= d * nz;
    RSCALAR tl = sqrt(tx * tx + ty * ty + tz * tz);
    tx /= tl;
    ty /= tl;
    tz /= tl;
    RSCALAR bx = ny * tz - nz * ty, by = nz * tx - nx * tz, bz = nx * ty - ny * tx;
    brdf_merl_half_diff(lx * tx + ly * ty + lz * tz, lx * bx + ly * by + lz * bz, lx * nx + ly * ny + lz * nz,
                        vx * tx + vy * ty + vz * tz, vx * bx + vy * by + vz * bz, vx * nx + vy * ny + vz * nz,
                        theta_h, theta_d, phi_d);
}

/* A measured cell's luminance, Y = 0.2126 R + 0.7152 G + 0.0722 B (sr^-1); 0 where a channel is
 * negative (not measured). */
BRDF_FN RSCALAR brdf_merl_luminance(RSCALAR r, RSCALAR g, RSCALAR b)
{
    return r < RC(0.0) || g < RC(0.0) || b < RC(0.0) ? RC(0.0) : RC(0.2126) * r + RC(0.7152) * g + RC(0.0722) * b;
}

#ifdef __OPENCL_VERSION__
/* Sixteen lanes of a measured material's luminance at world-space L, V, N (render's shading
 * pass, the physical-cost table): the table a float buffer in the file's layout, lane by lane
 * (a gather: its cost is memory traffic). */
BRDF_FN float16 brdf_merl_lookup16(__global const float *table, float16 lx, float16 ly, float16 lz, float16 vx,
                                   float16 vy, float16 vz, float16 nx, float16 ny, float16 nz)
{
    float a[9][16], y[16];
    vstore16(lx, 0, a[0]); vstore16(ly, 0, a[1]); vstore16(lz, 0, a[2]);
    vstore16(vx, 0, a[3]); vstore16(vy, 0, a[4]); vstore16(vz, 0, a[5]);
    vstore16(nx, 0, a[6]); vstore16(ny, 0, a[7]); vstore16(nz, 0, a[8]);
    for (int k = 0; k < 16; ++k) {
        float th, td, pd;
        int ih, id, ip;
        brdf_merl_half_diff_n(a[0][k], a[1][k], a[2][k], a[3][k], a[4][k], a[5][k], a[6][k], a[7][k], a[8][k],
                              &th, &td, &pd);
        int idx = brdf_merl_index3(th, td, pd, &ih, &id, &ip);
        y[k] = brdf_merl_luminance(table[idx], table[BRDF_MERL_CELLS + idx], table[2 * BRDF_MERL_CELLS + idx]);
    }
    return vload16(0, y);
}

#endif

#endif /* BRDF_MODELS_H */
