/* hostc_baseline.h - the same work as the throughput kernels and the accuracy sweep, done by
 * tuned C on the host (compiled with -O3 -march=native, threaded with pthreads), so that a
 * PoCL rate can be read as a ratio to what the CPU does without OpenCL. The models come from
 * kernels/brdf_models.h compiled for float, one loop per model id with the id a compile-time
 * constant, exactly as the kernels are specialised. */
#ifndef BRDF_HOSTC_BASELINE_H
#define BRDF_HOSTC_BASELINE_H

#include <stddef.h>

/* The inputs of one throughput launch (kernels/throughput.cl documents them). */
struct tp_inputs {
    int varying;          /* 0: n uniform, 1: n varies per evaluation */
    float n_uniform;      /* uniform n */
    float n_lo, dn_lane, dn_step;   /* varying n */
    float dc;             /* cosine step: 1 / (64 iters) */
    long iters;           /* loop iterations per work-item */
    long work_items;      /* work-items of the launch */
};

/* The cosine and shininess of one evaluation: work-item gid, iteration i, stream u (0..3),
 * lane (0..15), as the kernels generate them. For tests and checks; the loops do not call it. */
void tp_input_at(const struct tp_inputs *in, long gid, long i, int u, int lane, float *c, float *n);

/* 1 when model id has a C loop here (every built-in id; not user models). */
int hostc_supports(int model_id);

/* Evaluates model id (or the powf built-in when model_id < 0) over the launch's inputs on
 * `threads` threads. sums (work_items x 16 floats, may be NULL) receives each work-item's
 * partial sums, laid out as the kernel's output. Returns 0, or -1 with a message (unsupported
 * model, thread creation failed). *seconds is the wall time of the whole evaluation. */
int hostc_throughput(int model_id, float p0, float p1, const struct tp_inputs *in, int threads, float *sums,
                     double *seconds, char *err, size_t errlen);

/* One n of the sweep (host/support/hostc_sweep.c): writes kernels/accuracy.cl's record (kernels/brdf_shared.h,
   enum acc_out_field). */
void hostc_sweep_n_any(int id, float p0, float p1, int ref, float rp0, float rp1, float n, long samples, float *o);
/* The accuracy sweep of kernels/accuracy.cl in C: same zones, sampling in s = 1 - cos x,
 * reductions and output layout (ACC_OUT_STRIDE floats per n), with the reference lobe as
 * expf(n log1pf(-s)). Returns 0 or -1 with a message. */
int hostc_sweep(int model_id, float p0, float p1, int ref_id, float rp0, float rp1, const float *n_values,
                long n_count, long samples, int threads, float *out, double *seconds, char *err, size_t errlen);

/* The number of threads the baseline uses by default: the online CPUs. */
int hostc_default_threads(void);

#endif
