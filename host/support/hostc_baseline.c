/* hostc_baseline.c - tuned C doing the work of kernels/throughput.cl and kernels/accuracy.cl,
 * the baseline that PoCL's rates are divided by.
 *
 * Built with its own flags (CMakeLists.txt): -O3 -march=native -fno-math-errno. The model
 * formulas come from kernels/brdf_models.h compiled for float through <tgmath.h>, so that
 * exp, log, sqrt... are the float functions. Two choices make it the tuned C a programmer
 * would write rather than a straw man:
 *  - fmax is written as a compare (same result for every input, NaN included): GCC 12 calls
 *    fmaxf out of line unless NaNs are ruled out, which stops the loops from vectorising;
 *  - each loop keeps 4 x 16 independent sums and inputs, the layout of the kernels, which GCC
 *    vectorises to 512 bits without reassociating anything.
 * Transcendental functions are glibc's vector forms (libmvec, declared in hostc_vecmath.h), as
 * the kernels call SLEEF's; every model is the kernels' formula (the lobe c^n as exp(n log c),
 * brdf_models.h), and the pow() row is powf. The sums of each loop are checked against the
 * device's (throughput.h, tp_check_host_c) before its rate is a baseline.
 */
#define _GNU_SOURCE
#include <tgmath.h>
#include "hostc_vecmath.h"

/* IEEE fmax as a compare: a when b is NaN, b when a is NaN, else the larger. */
static inline float hostc_fmaxf(float a, float b) { return (a > b || b != b) ? a : b; }
#undef fmax
#define fmax(a, b) hostc_fmaxf((a), (b))

#define REAL float
#define RSCALAR float
/* the model dispatch inlined into each per-id loop, where its switch folds to one case */
#define BRDF_EVAL_FN __attribute__((always_inline)) static inline
#include "brdf_models.h"

#include "hostc_baseline.h"

#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define HOSTC_MAX_THREADS 256

static double hostc_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int hostc_default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > HOSTC_MAX_THREADS ? HOSTC_MAX_THREADS : (int)n;
}

int hostc_supports(int model_id) { return model_id >= 0 && model_id < BRDF_USER; }

/* The model, or the powf built-in for id < 0. With id a constant the switch folds away. */
static inline __attribute__((always_inline)) float hostc_eval(const int id, float c, float n, float p0, float p1)
{
    return id < 0 ? powf(c, n) : brdf_eval(id, c, n, p0, p1);
}

void tp_input_at(const struct tp_inputs *in, long gid, long i, int u, int lane, float *c, float *n)
{
    const float dc_step = in->dc * (float)(TP_LANES * TP_STREAMS);
    const float phase = (float)(gid % 64) * (1.0f / 64.0f);
    float cv = ((float)(TP_LANES * u + lane) + phase) * in->dc;
    float nv = in->varying ? fmaf((float)(TP_LANES * u + lane), in->dn_lane, in->n_lo) : in->n_uniform;
    for (long k = 0; k < i; ++k) {   /* the same rounded steps as the loops */
        cv += dc_step;
        if (in->varying)
            nv += in->dn_step;
    }
    *c = cv;
    *n = nv;
}

/* One work-item of tp_uniform_X / tp_varying_X. */
static inline __attribute__((always_inline)) void hostc_work_item(const int id, float p0, float p1,
                                                                  const struct tp_inputs *in, long gid,
                                                                  float *sum16)
{
    float c[TP_STREAMS][TP_LANES], n[TP_STREAMS][TP_LANES], acc[TP_STREAMS][TP_LANES];
    const float dc = in->dc, dc_step = dc * (float)(TP_LANES * TP_STREAMS);
    const float phase = (float)(gid % 64) * (1.0f / 64.0f);
    for (int u = 0; u < TP_STREAMS; ++u)
        for (int l = 0; l < TP_LANES; ++l) {
            c[u][l] = ((float)(TP_LANES * u + l) + phase) * dc;
            n[u][l] = fmaf((float)(TP_LANES * u + l), in->dn_lane, in->n_lo);
            acc[u][l] = 0.0f;
        }
    if (in->varying) {
        const float dn_step = in->dn_step;
        for (long i = 0; i < in->iters; ++i)
            for (int u = 0; u < TP_STREAMS; ++u)
                for (int l = 0; l < TP_LANES; ++l) {
                    acc[u][l] += hostc_eval(id, c[u][l], n[u][l], p0, p1);
                    c[u][l] += dc_step;
                    n[u][l] += dn_step;
                }
    } else {
        const float nu = in->n_uniform;
        for (long i = 0; i < in->iters; ++i)
            for (int u = 0; u < TP_STREAMS; ++u)
                for (int l = 0; l < TP_LANES; ++l) {
                    acc[u][l] += hostc_eval(id, c[u][l], nu, p0, p1);
                    c[u][l] += dc_step;
                }
    }
    for (int l = 0; l < TP_LANES; ++l)
        sum16[l] = (acc[0][l] + acc[1][l]) + (acc[2][l] + acc[3][l]);
}

/* Per-model instances (one per row of kernels/brdf_model_list.h) with the id a constant (the model's switch folds away inside: brdf_eval is
   forced inline above), each a function of its own that runs a thread's whole share of the
   work-items. Left to its heuristics, GCC kept brdf_eval out of line in the one function that
   held all the models' copies: a call and a run-time switch per evaluation, nothing vectorised, about
   100x slower than the same loop with the model inlined (perf: 66% of the time in brdf_eval). */
typedef void (*hostc_items_fn)(float p0, float p1, const struct tp_inputs *in, long first, long step, float *sums);

#define HOSTC_ITEMS_FN(name, k)                                                                             \
    static __attribute__((noinline)) void name(float p0, float p1, const struct tp_inputs *in,  \
                                                          long first, long step, float *sums)             \
    {                                                                                                     \
        float local[TP_LANES];                                                                            \
        for (long gid = first; gid < in->work_items; gid += step)                                         \
            hostc_work_item(k, p0, p1, in, gid, sums ? sums + gid * TP_LANES : local);                    \
    }
/* one instance per row of the model list (its descriptors: kernels/brdf_model_list.h) */
#define BRDF_MODEL(ENUM, C_ONLY, EVAL, ...) HOSTC_ITEMS_FN(hostc_items_##ENUM, BRDF_##ENUM)
#include "brdf_model_list.h"
#undef BRDF_MODEL
HOSTC_ITEMS_FN(hostc_items_pow, -1)   /* the powf built-in */
#undef HOSTC_ITEMS_FN

static hostc_items_fn hostc_items_of(int id)
{
    switch (id) {
#define BRDF_MODEL(ENUM, C_ONLY, EVAL, ...) case BRDF_##ENUM: return hostc_items_##ENUM;
#include "brdf_model_list.h"
#undef BRDF_MODEL
    default: return hostc_items_pow;
    }
}

/* ---- threads ------------------------------------------------------------------------- */

struct hostc_job {
    int sweep;                  /* 0: throughput, 1: sweep */
    int id, ref;
    float p0, p1, rp0, rp1;
    const struct tp_inputs *in;
    float *sums;                /* throughput: work_items x 16 */
    const float *n_values;      /* sweep */
    long n_count, samples;
    float *out;                 /* sweep: n_count x 8 */
    int thread, threads;
};

static void *hostc_thread(void *arg)
{
    struct hostc_job *j = arg;
    if (!j->sweep) {
        hostc_items_of(j->id)(j->p0, j->p1, j->in, j->thread, j->threads, j->sums);
    } else {
        for (long i = j->thread; i < j->n_count; i += j->threads)
            hostc_sweep_n_any(j->id, j->p0, j->p1, j->ref, j->rp0, j->rp1, j->n_values[i], j->samples,
                              j->out + i * ACC_OUT_STRIDE);
    }
    return NULL;
}

/* Runs job on `threads` threads, each pinned to its own CPU where possible (an unpinned
   thread can land on a busy core and the pair then runs at the speed of one). */
static int hostc_run_threads(const struct hostc_job *proto, int threads, double *seconds, char *err, size_t errlen)
{
    if (threads < 1 || threads > HOSTC_MAX_THREADS) {
        snprintf(err, errlen, "host C baseline: %d threads (accepted: 1 to %d)", threads, HOSTC_MAX_THREADS);
        return -1;
    }
    struct hostc_job jobs[HOSTC_MAX_THREADS];
    pthread_t tid[HOSTC_MAX_THREADS];
    int started = 0, rc = 0;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    double t0 = hostc_now();
    for (int t = 0; t < threads; ++t) {
        jobs[t] = *proto;
        jobs[t].thread = t;
        jobs[t].threads = threads;
        pthread_attr_t attr;
        pthread_attr_init(&attr);
        if (cpus > 1) {
            cpu_set_t set;
            CPU_ZERO(&set);
            CPU_SET((int)(t % cpus), &set);
            pthread_attr_setaffinity_np(&attr, sizeof set, &set);
        }
        int e = pthread_create(&tid[t], &attr, hostc_thread, &jobs[t]);
        pthread_attr_destroy(&attr);
        if (e != 0) {
            snprintf(err, errlen, "host C baseline: pthread_create failed (%s)", strerror(e));
            rc = -1;
            break;
        }
        ++started;
    }
    for (int t = 0; t < started; ++t)
        pthread_join(tid[t], NULL);
    *seconds = hostc_now() - t0;
    return rc;
}

int hostc_throughput(int model_id, float p0, float p1, const struct tp_inputs *in, int threads, float *sums,
                     double *seconds, char *err, size_t errlen)
{
    if (model_id >= 0 && !hostc_supports(model_id)) {
        snprintf(err, errlen, "host C baseline: no C loop for model id %d (user models run on the device only)",
                 model_id);
        return -1;
    }
    struct hostc_job job;
    memset(&job, 0, sizeof job);
    job.id = model_id < 0 ? -1 : model_id;
    job.p0 = p0;
    job.p1 = p1;
    job.in = in;
    job.sums = sums;
    return hostc_run_threads(&job, threads, seconds, err, errlen);
}

int hostc_sweep(int model_id, float p0, float p1, int ref_id, float rp0, float rp1, const float *n_values,
                long n_count, long samples, int threads, float *out, double *seconds, char *err, size_t errlen)
{
    if (!hostc_supports(model_id) || !hostc_supports(ref_id)) {
        snprintf(err, errlen, "host C baseline: no C loop for model id %d / reference id %d", model_id, ref_id);
        return -1;
    }
    if (samples < 2) {
        snprintf(err, errlen, "host C baseline: %ld samples per zone (accepted: at least 2)", samples);
        return -1;
    }
    struct hostc_job job;
    memset(&job, 0, sizeof job);
    job.sweep = 1;
    job.id = model_id;
    job.ref = ref_id;
    job.p0 = p0;
    job.p1 = p1;
    job.rp0 = rp0;
    job.rp1 = rp1;
    job.n_values = n_values;
    job.n_count = n_count;
    job.samples = samples;
    job.out = out;
    return hostc_run_threads(&job, threads, seconds, err, errlen);
}
