/*
 * peak.cl - the device's measured peak of float arithmetic, as clpeak measures it: chains of
 * fused multiply-adds on float16, with enough independent chains per work-item (16) to cover
 * the FMA latency on every pipe. x <- x a + b with 0 < a < 1 converges to b / (1 - a), so the
 * values stay normal and finite for any number of iterations.
 *
 * One iteration is PEAK_UNROLL steps of PEAK_CHAINS chains of 16 lanes: 2 flops per lane and
 * step. The host counts flops as work-items x iters x PEAK_UNROLL x PEAK_CHAINS x PEAK_W x 2.
 */
#include "brdf_shared.h"   /* PEAK_CHAINS, PEAK_UNROLL */
/* Lanes per chain: 16 (float16) for PoCL, which vectorises explicit vectors; 1 (float) for a
   driver that vectorises across work-items itself (Mesa's llvmpipe, GPU compilers), where a
   float16 chain is sixteen times the program (host/measure/throughput/throughput.c passes -DPEAK_W=1). */
#ifndef PEAK_W
#define PEAK_W 16
#endif
#if PEAK_W == 16
#define PEAK_T float16
#define PEAK_LANES (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f)
#define PEAK_STORE(v, gid, out) vstore16((v), (gid), (out))
#elif PEAK_W == 1
#define PEAK_T float
#define PEAK_LANES 0.0f
#define PEAK_STORE(v, gid, out) ((out)[gid] = (v))
#else
#error "PEAK_W must be 16 or 1"
#endif

#define PEAK_STEP(x) x = fma(x, a, b)
#define PEAK_STEP_ALL                                                                  \
    PEAK_STEP(x0); PEAK_STEP(x1); PEAK_STEP(x2); PEAK_STEP(x3);                       \
    PEAK_STEP(x4); PEAK_STEP(x5); PEAK_STEP(x6); PEAK_STEP(x7);                       \
    PEAK_STEP(x8); PEAK_STEP(x9); PEAK_STEP(x10); PEAK_STEP(x11);                     \
    PEAK_STEP(x12); PEAK_STEP(x13); PEAK_STEP(x14); PEAK_STEP(x15)

__kernel void peak_fma(const float a_in, const float b_in, const int iters, __global float *out)
{
    const int gid = (int)get_global_id(0);
    const PEAK_T a = (PEAK_T)(a_in), b = (PEAK_T)(b_in);
    const PEAK_T s = PEAK_LANES * 1e-3f + (float)(gid % 64) * 1e-4f;
    PEAK_T x0 = s, x1 = s + 0.01f, x2 = s + 0.02f, x3 = s + 0.03f;
    PEAK_T x4 = s + 0.04f, x5 = s + 0.05f, x6 = s + 0.06f, x7 = s + 0.07f;
    PEAK_T x8 = s + 0.08f, x9 = s + 0.09f, x10 = s + 0.10f, x11 = s + 0.11f;
    PEAK_T x12 = s + 0.12f, x13 = s + 0.13f, x14 = s + 0.14f, x15 = s + 0.15f;
    for (int i = 0; i < iters; ++i) {
        PEAK_STEP_ALL;
        PEAK_STEP_ALL;
        PEAK_STEP_ALL;
        PEAK_STEP_ALL;
    }
    PEAK_STORE(((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7)) +
               ((x8 + x9) + (x10 + x11)) + ((x12 + x13) + (x14 + x15)), gid, out);
}
