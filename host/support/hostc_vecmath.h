/* hostc_vecmath.h - the float functions of <math.h> that glibc's vector math library (libmvec)
 * has in vector form, declared as such for the tuned C baseline (hostc_baseline.c,
 * hostc_sweep.c) so that GCC vectorises loops that call them, as PoCL calls SLEEF's vector
 * forms on the device. glibc declares them so only under -ffast-math (bits/math-vector.h);
 * the baseline keeps IEEE semantics everywhere else. libmvec's float functions are within
 * 4 ulp (glibc's manual, "Errors in Math Functions"); the baseline's sums are checked against
 * the device's before a ratio is printed. Include after <math.h> or <tgmath.h>; link libmvec. */
#ifndef BRDF_HOSTC_VECMATH_H
#define BRDF_HOSTC_VECMATH_H

/* the same condition as CMakeLists.txt's link with libmvec (BRDF_MVEC) */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define HOSTC_VEC __attribute__((__simd__("notinbranch")))
HOSTC_VEC float expf(float);
HOSTC_VEC float exp2f(float);
HOSTC_VEC float expm1f(float);
HOSTC_VEC float logf(float);
HOSTC_VEC float log2f(float);
HOSTC_VEC float log1pf(float);
HOSTC_VEC float powf(float, float);
HOSTC_VEC float sinf(float);
HOSTC_VEC float cosf(float);
HOSTC_VEC float tanf(float);
HOSTC_VEC float acosf(float);
HOSTC_VEC float asinf(float);
HOSTC_VEC float atanf(float);
HOSTC_VEC float atan2f(float, float);
HOSTC_VEC float cbrtf(float);
HOSTC_VEC float tanhf(float);
HOSTC_VEC float hypotf(float, float);
#undef HOSTC_VEC
#endif

#endif
