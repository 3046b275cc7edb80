/* brdf_shared.h - the facts the host and the kernels must agree on, written once and included
 * on both sides (the host's C and every kernel file, through kernels/brdf_models.h or
 * directly): the zones' constant, the layout of the kernels' outputs and the shapes of the
 * timed loops. Plain constants, no REAL: the host includes it without choosing a type. */
#ifndef BRDF_SHARED_H
#define BRDF_SHARED_H

/* The epicentre ends where the reference c^n equals exp(-BRDF_ZONE_K) (docs/definitions.md):
   x_e(n) = acos(exp(-0.511/n)), as s = 1 - cos x: s_e(n) = -expm1(-0.511/n). */
#define BRDF_ZONE_K 0.511

/* accuracy_sweep's output record: ACC_OUT_STRIDE floats per n (per work-item of a chunked sweep),
   at these positions. kernels/accuracy.cl and the tuned-C sweep (host/support/hostc_sweep.c)
   write them; host/measure/accuracy/accuracy.c and the throughput sweep's check
   (host/measure/throughput/throughput.c) read them. Each maximum's s is the float input the
   model saw there. */
enum acc_out_field {
    ACC_O_EPI_REL = 0,     /* max relative error in the epicentre */
    ACC_O_EPI_REL_S = 1,   /* the s where it occurs */
    ACC_O_ATT_ABS = 2,     /* max absolute error in the attenuation */
    ACC_O_ATT_ABS_S = 3,
    ACC_O_EPI_ABS = 4,     /* max absolute error in the epicentre */
    ACC_O_EPI_ABS_S = 5,
    ACC_O_INVALID = 6,     /* number of invalid model values (NaN, Inf or negative) */
    ACC_O_INVALID_S = 7,   /* the smallest s of one (NaN: none) */
    ACC_OUT_STRIDE = 8     /* floats per record */
};

/* The throughput loops: independent streams per work-item and lanes per stream
   (kernels/throughput.cl; host/support/hostc_baseline.c repeats the loop in C on the same inputs) */
#define TP_STREAMS 4
#define TP_LANES 16

/* The FMA peak kernel: chains per work-item and steps per iteration (kernels/peak.cl); the host
   counts work-items x iterations x PEAK_UNROLL x PEAK_CHAINS x lanes x 2 flops */
#define PEAK_CHAINS 16
#define PEAK_UNROLL 4

#endif
