/* brdf_shared.h - the facts the host and the kernels must agree on, written once and included
 * on both sides (the host's C and every kernel file, through kernels/brdf_models.h or
 * directly): the zones' constant, the layout of the kernels' outputs and the shapes of the
 * timed loops. Plain constants, no REAL: the host includes it without choosing a type. */
#ifndef BRDF_SHARED_H
#define BRDF_SHARED_H

/* The epicentre ends where the reference c^n equals exp(-BRDF_ZONE_K) (docs/definitions.md):
   x_e(n) = acos(exp(-0.511/n)), as s = 1 - cos x: s_e(n) = -expm1(-0.511/n). */
#define BRDF_ZONE_K 0.511

/* accuracy_sweep's output: floats per n (kernels/accuracy.cl writes them, host/measure/accuracy/accuracy.c
   reads them) */
#define ACC_OUT_STRIDE 8

/* The throughput loops: independent streams per work-item and lanes per stream
   (kernels/throughput.cl; host/support/hostc_baseline.c repeats the loop in C on the same inputs) */
#define TP_STREAMS 4
#define TP_LANES 16

/* The FMA peak kernel: chains per work-item and steps per iteration (kernels/peak.cl); the host
   counts work-items x iterations x PEAK_UNROLL x PEAK_CHAINS x lanes x 2 flops */
#define PEAK_CHAINS 16
#define PEAK_UNROLL 4

#endif
