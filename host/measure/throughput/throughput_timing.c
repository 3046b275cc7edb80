/* throughput_timing.c - timing through the measurement runner (host/core/runner.h): the kernels
 * ready to launch, the device and tuned-C items, the peak kernel as every round's reference,
 * and tp_bench_run, which times every job of a run in interleaved rounds (see throughput.h). */
#define _POSIX_C_SOURCE 200809L
#include "throughput.h"
#include "lcg.h"
#include "throughput_report.h"
#include "throughput_internal.h"
#include "context.h"
#include "exitcodes.h"
#include "hostc_baseline.h"
#include "outdir.h"
#include "programs.h"
#include "runner.h"
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A kernel ready to launch, with the arguments that depend on the iteration count. */
struct tp_kernel_run {
    struct cl_session *s;
    cl_kernel k;
    int kind;                     /* 0: uniform, 1: varying, 2: peak */
    const struct throughput_options *o;
    size_t global, local;
    cl_mem out;
    double work_per_iter;         /* work of one iteration over the whole launch */
};

/* The argument setters below return CL_SUCCESS or the error, with why saying which kernel and
   argument (cl_set_args). */
static cl_int tp_set_iters(struct tp_kernel_run *r, long iters, char *why, size_t whylen)
{
    cl_int e, it = (cl_int)iters;
    if (r->kind == 2)
        return CL_SET_ARGS_WHY(r->k, 2, why, whylen, CL_ARG(it));
    struct tp_inputs in;
    tp_inputs_for(r->o, r->kind == 1 ? TP_N_VARYING : TP_N_UNIFORM, (long)r->global, iters, &in);
    if (r->kind == 0)
        return CL_SET_ARGS_WHY(r->k, 3, why, whylen, CL_ARG(in.dc), CL_ARG(it));
    if ((e = CL_SET_ARGS_WHY(r->k, 2, why, whylen, CL_ARG(in.dn_step))) != CL_SUCCESS)
        return e;
    return CL_SET_ARGS_WHY(r->k, 5, why, whylen, CL_ARG(in.dc), CL_ARG(it));
}

/* Sets the arguments that stay fixed: n, parameters, output. */
static cl_int tp_set_fixed(struct tp_kernel_run *r, const struct model_spec *m, char *why, size_t whylen)
{
    cl_int e;
    float p0 = m ? (float)m->params[0] : 0.0f, p1 = m ? (float)m->params[1] : 0.0f;
    struct tp_inputs in;
    tp_inputs_for(r->o, r->kind == 1 ? TP_N_VARYING : TP_N_UNIFORM, (long)r->global, 1, &in);
    if (r->kind == 2) {
        float a = 0.999f, b = 0.001f;   /* x <- a x + b converges to 1 */
        if ((e = CL_SET_ARGS_WHY(r->k, 0, why, whylen, CL_ARG(a), CL_ARG(b))) != CL_SUCCESS)
            return e;
        return CL_SET_ARGS_WHY(r->k, 3, why, whylen, CL_ARG(r->out));
    }
    if (r->kind == 0) {
        if ((e = CL_SET_ARGS_WHY(r->k, 0, why, whylen, CL_ARG(in.n_uniform), CL_ARG(p0), CL_ARG(p1))) != CL_SUCCESS)
            return e;
        return CL_SET_ARGS_WHY(r->k, 5, why, whylen, CL_ARG(r->out));
    }
    if ((e = CL_SET_ARGS_WHY(r->k, 0, why, whylen, CL_ARG(in.n_lo), CL_ARG(in.dn_lane))) != CL_SUCCESS ||
        (e = CL_SET_ARGS_WHY(r->k, 3, why, whylen, CL_ARG(p0), CL_ARG(p1))) != CL_SUCCESS)
        return e;
    return CL_SET_ARGS_WHY(r->k, 7, why, whylen, CL_ARG(r->out));
}

/* One launch: event time and wall time (enqueue to finish); where the driver's profiling
   events give no time, the wall time stands in for the event time and *used_wall says so
   (cl_event_seconds_or_wall). Returns an OpenCL error, with why saying which call failed, or 0. */
static cl_int tp_launch_once(struct tp_kernel_run *r, long iters, double *event_s, double *wall_s, int *used_wall,
                             char *why, size_t whylen)
{
    cl_event ev = NULL;
    cl_int e = tp_set_iters(r, iters, why, whylen);
    if (e != CL_SUCCESS)
        return e;
    double t0 = wall_seconds();
    const char *call = "clEnqueueNDRangeKernel";
    e = clEnqueueNDRangeKernel(r->s->queue, r->k, 1, NULL, &r->global, r->local ? &r->local : NULL, 0, NULL, &ev);
    if (e == CL_SUCCESS) {
        call = "clFinish";
        e = clsession_finish(r->s, r->k, NULL);
    }
    if (e != CL_SUCCESS)
        snprintf(why, whylen, "%s failed with %s", call, cl_error_name(e));
    *wall_s = wall_seconds() - t0;
    *event_s = (e == CL_SUCCESS) ? cl_event_seconds_or_wall(ev, *wall_s, used_wall) : NAN;
    if (ev)
        clReleaseEvent(ev);
    return e;
}

/* ---- timing through the runner (host/core/runner.h) ------------------------------------ */

/* A device item of the runner: a kernel ready to launch, with its own output buffer. */
struct tp_dev_ctx {
    struct tp_kernel_run kr;
    int timer_wall;               /* the profiling events gave no time: wall time used */
};

static int tp_dev_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    struct tp_dev_ctx *d = ctx;
    double wall;
    int used_wall = 0;
    char why[256] = "";
    cl_int e = tp_launch_once(&d->kr, iters, seconds, &wall, &used_wall, why, sizeof why);
    if (e != CL_SUCCESS) {
        snprintf(reason, reason_len, "launch: %s", why);
        return -1;
    }
    d->timer_wall |= used_wall;   /* the figure says which timer gave its times */
    return 0;
}

/* A C item of the runner: the tuned C loop of the same model, n mode and work-items. */
struct tp_c_ctx {
    const struct throughput_options *o;
    const struct model_spec *m;       /* NULL: powf */
    int nmode;
    long work_items;
    int threads;
    float *sums;
};

static int tp_c_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    struct tp_c_ctx *j = ctx;
    struct tp_inputs in;
    tp_inputs_for(j->o, j->nmode, j->work_items, iters, &in);
    if (hostc_throughput(j->m ? j->m->info->kernel_id : -1, j->m ? (float)j->m->params[0] : 0.0f,
                         j->m ? (float)j->m->params[1] : 0.0f, &in, j->threads, j->sums, seconds, reason, reason_len))
        return -1;
    *seconds = fmax(*seconds, 1e-9);
    return 0;
}

/* A figure from the runner's record of its item. */
static void tp_fill_item(struct tp_figure *f, const struct runner_item *it, const float *out, size_t nout, int timer_wall)
{
    if (!it->ok) {
        tp_fig_fail(f, "%s", it->reason);
        return;
    }
    int reps = it->nreps < TP_MAX_REPS ? it->nreps : TP_MAX_REPS;
    f->iters = it->iters;
    f->per_launch = it->work_per_iter * (double)it->iters;
    f->sec = tp_stats_of(it->seconds, reps);
    f->sec_wall = tp_stats_of(it->wall, reps);
    f->rate = tp_rates_of(f->sec, f->per_launch);
    f->rate_wall = tp_rates_of(f->sec_wall, f->per_launch);
    f->checksum = out ? tp_sum_floats(out, nout) : NAN;
    f->nreps = reps;
    memcpy(f->rep_seconds, it->seconds, (size_t)reps * sizeof *it->seconds);
    memcpy(f->rep_cpu, it->cpu, (size_t)reps * sizeof *it->cpu);
    f->has_norm = it->norm != NULL;
    if (it->norm) {
        memcpy(f->rep_norm, it->norm, (size_t)reps * sizeof *it->norm);
        f->norm = tp_stats_of(it->norm, reps);
    }
    f->has_cpu_norm = it->cpu_norm != NULL;
    if (it->cpu_norm) {
        memcpy(f->rep_cpu_norm, it->cpu_norm, (size_t)reps * sizeof *it->cpu_norm);
        f->cpu_norm = tp_stats_of(it->cpu_norm, reps);
    }
    f->retries = it->retries;
    f->disturbed = it->disturbed;
    f->timer_wall = timer_wall;
    f->ok = 1;
    f->finite = isfinite(f->checksum);
}

struct tp_progress {
    int quiet;
    double t0, last;
};

static void tp_round_done(void *ctx, int done, int rounds)
{
    struct tp_progress *p = ctx;
    double now = wall_seconds();
    if (!p->quiet && (now - p->last > 1.0 || done == rounds)) {
        fprintf(stderr, "throughput: round %d of %d (%.1f s)\n", done, rounds, now - p->t0);
        p->last = now;
    }
}

/* The peak kernel, the reference of every round: built into *prog and ready in *d. */
static int tp_peak_setup(struct cl_session *s, const char *options, long work_items, cl_program *prog,
                         struct tp_dev_ctx *d, const struct throughput_options *o, struct tp_figure *f, double *build_s)
{
    memset(d, 0, sizeof *d);
    cl_int e;
    /* scalar chains for a driver that vectorises across work-items (kernels/peak.cl, PEAK_W) */
    int lanes = s->specialise ? 1 : 16;
    char opts[400];
    snprintf(opts, sizeof opts, "%s%s%s", options ? options : "", s->specialise && options && *options ? " " : "",
             s->specialise ? "-DPEAK_W=1" : "");
    if (clsession_build(s, "peak.cl", NULL, opts, prog)) {
        tp_fig_fail(f, "building kernels/peak.cl failed (build log on stderr)");
        return -1;
    }
    *build_s = s->last_build_seconds;
    d->kr.s = s;
    d->kr.o = o;
    d->kr.kind = 2;
    d->kr.global = (size_t)work_items;
    clsession_group_size(s, d->kr.global, &d->kr.local);   /* 0: the driver chooses */
    d->kr.work_per_iter = (double)work_items * PEAK_UNROLL * PEAK_CHAINS * lanes * 2;
    d->kr.k = clsession_create_kernel(*prog, "peak_fma", &e);
    if (e != CL_SUCCESS) {
        tp_fig_fail(f, "clCreateKernel(peak_fma) failed with %s", cl_error_name(e));
        return -1;
    }
    d->kr.out = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, (size_t)work_items * 16 * sizeof(float), NULL, &e);
    if (e != CL_SUCCESS) {
        tp_fig_fail(f, "clCreateBuffer failed with %s", cl_error_name(e));
        return -1;
    }
    char why[256];
    if ((e = tp_set_fixed(&d->kr, NULL, why, sizeof why)) != CL_SUCCESS) {
        tp_fig_fail(f, "%s", why);
        return -1;
    }
    return 0;
}

static void tp_dev_release(struct tp_dev_ctx *d)
{
    if (d->kr.out)
        clReleaseMemObject(d->kr.out);
    if (d->kr.k)
        clReleaseKernel(d->kr.k);
    d->kr.out = NULL;
    d->kr.k = NULL;
}

/* A job's device item: its kernel, output buffer and fixed arguments (0), or -1 with the job's
   figure failed. */
static int tp_dev_item(struct tp_bench *b, struct tp_job *j, struct tp_dev_ctx *d, size_t nout, int cpu_threads,
                       struct runner_item *it)
{
    struct cl_session *s = b->s;
    cl_int e = CL_SUCCESS;
    d->kr.s = s;
    d->kr.o = b->o;
    d->kr.kind = j->nmode == TP_N_VARYING ? 1 : 0;
    d->kr.global = (size_t)b->work_items;
    clsession_group_size(s, d->kr.global, &d->kr.local);   /* each work-item is a long loop already */
    d->kr.work_per_iter = (double)b->work_items * TP_EVALS_PER_ITER;
    if (!tp_has(j->prog, j->m)) {
        tp_fig_fail(j->f, "model %s is not in the throughput program", j->m ? j->m->label : "pow");
        return -1;
    }
    if ((d->kr.k = tp_kernel(j->prog, tp_nmode_name(j->nmode), j->m, &e)), e != CL_SUCCESS) {
        tp_fig_fail(j->f, "clCreateKernel failed with %s", cl_error_name(e));
        return -1;
    }
    d->kr.out = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, nout * sizeof(float), NULL, &e);
    if (e != CL_SUCCESS) {
        tp_fig_fail(j->f, "clCreateBuffer(sums) failed with %s", cl_error_name(e));
        return -1;
    }
    char why[256];
    if ((e = tp_set_fixed(&d->kr, j->m, why, sizeof why)) != CL_SUCCESS) {
        tp_fig_fail(j->f, "%s", why);
        return -1;
    }
    *it = (struct runner_item){ .name = j->m ? j->m->label : "pow", .launch = tp_dev_launch, .ctx = d,
                                .calibrate = 1, .work_per_iter = d->kr.work_per_iter,
                                .cpu_threads = cpu_threads };
    return 0;
}

/* A job's tuned-C item (0), or -1 with the job's figure failed. */
static int tp_c_item(struct tp_bench *b, struct tp_job *j, struct tp_c_ctx *c, size_t nout, struct runner_item *it)
{
    *c = (struct tp_c_ctx){ b->o, j->m, j->nmode, b->work_items, b->threads, malloc(nout * sizeof(float)) };
    if (!c->sums) {
        tp_fig_fail(j->f, "out of memory");
        return -1;
    }
    *it = (struct runner_item){ .name = "C", .launch = tp_c_launch, .ctx = c, .calibrate = 1,
                                .work_per_iter = (double)b->work_items * TP_EVALS_PER_ITER,
                                .cpu_threads = b->threads };
    return 0;
}

/* After the rounds: every timed job's figure from its item and the sums it left. */
static void tp_bench_collect(struct tp_bench *b, struct tp_job *jobs, int njobs, const int *job_item,
                             const struct runner_item *items, const struct tp_dev_ctx *dev,
                             const struct tp_c_ctx *cj, size_t nout, float *host)
{
    for (int i = 0; i < njobs; ++i) {
        int k = job_item[i];
        if (k < 0)
            continue;
        if (jobs[i].prog) {
            cl_int e = clEnqueueReadBuffer(b->s->queue, dev[k].kr.out, CL_TRUE, 0, nout * sizeof(float), host, 0, NULL,
                                           NULL);
            if (e != CL_SUCCESS && items[k].ok)
                tp_fig_fail(jobs[i].f, "reading the sums: clEnqueueReadBuffer failed with %s", cl_error_name(e));
            else
                tp_fill_item(jobs[i].f, &items[k], host, nout, dev[k].timer_wall);
        } else {
            tp_fill_item(jobs[i].f, &items[k], cj[k].sums, nout, 0);
        }
    }
}

int tp_bench_run(struct tp_bench *b, struct tp_job *jobs, int njobs, int quiet)
{
    struct cl_session *s = b->s;
    const struct throughput_options *o = b->o;
    int n = njobs + 1, rc = 0;
    struct runner_item *items = calloc((size_t)n, sizeof *items);
    struct tp_dev_ctx *dev = calloc((size_t)n, sizeof *dev);
    struct tp_c_ctx *cj = calloc((size_t)n, sizeof *cj);
    size_t nout = (size_t)b->work_items * 16;
    float *host = malloc(nout * sizeof *host);
    cl_program peak_prog = NULL;
    if (!items || !dev || !cj || !host) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    memset(b->peak, 0, sizeof *b->peak);
    int peak_ok = tp_peak_setup(s, b->peak_options, b->work_items, &peak_prog, &dev[0], o, b->peak,
                                &b->peak_build_seconds) == 0;
    int cpu_threads = s->is_cpu ? (int)(s->compute_units ? s->compute_units : 1) : 0;
    int used = 0;
    /* item 0: the reference */
    if (peak_ok) {
        items[used] = (struct runner_item){ .name = "peak", .launch = tp_dev_launch, .ctx = &dev[0], .calibrate = 1,
                                            .work_per_iter = dev[0].kr.work_per_iter, .cpu_threads = cpu_threads };
        ++used;
    }
    int *job_item = calloc((size_t)n, sizeof *job_item);
    if (!job_item) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (int i = 0; i < njobs; ++i) {
        struct tp_job *j = &jobs[i];
        job_item[i] = -1;
        if (j->f->reason[0])
            continue;   /* failed before timing (a build, a model without a C loop) */
        int ready = j->prog ? tp_dev_item(b, j, &dev[used], nout, cpu_threads, &items[used])
                            : tp_c_item(b, j, &cj[used], nout, &items[used]);
        if (ready == 0)
            job_item[i] = used++;
    }
    struct runner run;
    runner_init(&run, items, used);
    run.reference = peak_ok ? 0 : -1;
    run.rounds = o->reps;
    run.min_time = o->min_time;
    run.seed = o->seed;
    struct tp_progress prog = { quiet, wall_seconds(), wall_seconds() };
    run.progress = tp_round_done;
    run.progress_ctx = &prog;
    if (!quiet)
        fprintf(stderr, "throughput: %d items x %d rounds, interleaved (reference: %s)\n", used, o->reps,
                peak_ok ? "the peak FMA kernel" : "none");
    if (runner_run(&run)) {
        rc = EXIT_RUNTIME;
        runner_release(&run);
        goto done;
    }
    b->launches = run.launches;
    b->retried = run.retried;
    b->disturbed = run.disturbed;
    b->rounds = run.rounds;
    if (peak_ok) {
        cl_int e = clEnqueueReadBuffer(s->queue, dev[0].kr.out, CL_TRUE, 0, nout * sizeof(float), host, 0, NULL, NULL);
        size_t peak_out = (size_t)b->work_items * (s->specialise ? 1 : 16);   /* kernels/peak.cl, PEAK_W */
        tp_fill_item(b->peak, &items[0], e == CL_SUCCESS ? host : NULL, peak_out, dev[0].timer_wall);
    }
    tp_bench_collect(b, jobs, njobs, job_item, items, dev, cj, nout, host);
    runner_release(&run);
    free(job_item);
done:
    for (int i = 0; dev && i < n; ++i)
        tp_dev_release(&dev[i]);
    for (int i = 0; cj && i < n; ++i)
        free(cj[i].sums);
    if (peak_prog)
        clReleaseProgram(peak_prog);
    free(host);
    free(cj);
    free(dev);
    free(items);
    return rc;
}

int tp_program_points(struct tp_program *p, const struct model_spec *m, const float *c, const float *n, size_t count,
                      float *out)
{
    int rc = 0;
    cl_int e;
    cl_kernel k = NULL;
    if (!tp_has(p, m)) {
        fprintf(stderr, "brdfbench: model %s is not in the throughput program\n", m->label);
        return EXIT_RUNTIME;
    }
    k = tp_kernel(p, "points", m, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateKernel(tp_points)", done);
    float p0 = m ? (float)m->params[0] : 0.0f, p1 = m ? (float)m->params[1] : 0.0f;
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(p0), CL_ARG(p1));
    rc = cl_run_points16(p->s, k, 2, c, n, count, out);
done:
    if (k) clReleaseKernel(k);
    return rc;
}

/* A launch of the shared throughput program over work_items work-items of one each. */
static struct tp_kernel_run tp_program_run(const struct tp_program *p, int nmode, const struct throughput_options *o,
                                           long work_items)
{
    struct tp_kernel_run r;
    memset(&r, 0, sizeof r);
    r.s = p->s;
    r.o = o;
    r.kind = nmode == TP_N_VARYING ? 1 : 0;
    r.global = (size_t)work_items;
    clsession_group_size(p->s, r.global, &r.local);
    return r;
}

int tp_program_launch(struct tp_program *p, const struct model_spec *m, int nmode, const struct throughput_options *o,
                      long work_items, long iters, float *sums, double *event_seconds)
{
    int rc = 0;
    cl_int e;
    struct tp_kernel_run r = tp_program_run(p, nmode, o, work_items);
    if (!tp_has(p, m)) {
        fprintf(stderr, "brdfbench: model %s is not in the throughput program\n", m->label);
        return EXIT_RUNTIME;
    }
    r.k = tp_kernel(p, tp_nmode_name(nmode), m, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateKernel(tp_uniform/tp_varying)", done);
    r.out = clCreateBuffer(p->s->ctx, CL_MEM_WRITE_ONLY, (size_t)work_items * 16 * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(sums)", done);
    char why[256];
    double wall;
    if (tp_set_fixed(&r, m, why, sizeof why) != CL_SUCCESS ||
        tp_launch_once(&r, iters, event_seconds, &wall, NULL, why, sizeof why) != CL_SUCCESS) {
        fprintf(stderr, "brdfbench: OpenCL error: %s at %s:%d\n", why, __FILE__, __LINE__);
        rc = EXIT_RUNTIME;
        goto done;
    }
    CL_CHECK_GOTO(clEnqueueReadBuffer(p->s->queue, r.out, CL_TRUE, 0, (size_t)work_items * 16 * sizeof(float), sums, 0,
                                      NULL, NULL), done);
done:
    if (r.out) clReleaseMemObject(r.out);
    if (r.k) clReleaseKernel(r.k);
    return rc;
}

int tp_time_set(struct tp_program *p, struct tp_timed *t, int count, const struct throughput_options *o,
                long work_items, int quiet)
{
    struct tp_figure *f = calloc((size_t)count + 1, sizeof *f);
    struct tp_job *jobs = calloc((size_t)count, sizeof *jobs);
    if (!f || !jobs) {
        free(f);
        free(jobs);
        return EXIT_RUNTIME;
    }
    for (int i = 0; i < count; ++i)
        jobs[i] = (struct tp_job){ &f[i + 1], p, t[i].m, t[i].nmode };
    struct tp_bench b = { p->s, o, work_items, 1, o->base_options ? o->base_options : "", &f[0], 0, 0, 0, 0, 0 };
    int rc = tp_bench_run(&b, jobs, count, quiet);
    for (int i = 0; i < count && rc == 0; ++i) {
        const struct tp_figure *g = &f[i + 1];
        t[i].ok = g->ok;
        snprintf(t[i].reason, sizeof t[i].reason, "%s", g->ok ? "" : g->reason[0] ? g->reason : "not measured");
        t[i].rate[0] = g->ok ? g->rate.min : NAN;
        t[i].rate[1] = g->ok ? g->rate.median : NAN;
        t[i].rate[2] = g->ok ? g->rate.max : NAN;
        /* per CPU second where the runner keeps it (a CPU device), else per wall second */
        const struct tp_stats *q = g->has_cpu_norm ? &g->cpu_norm : &g->norm;
        int has = g->ok && (g->has_cpu_norm || g->has_norm);
        t[i].norm[0] = has ? q->min : NAN;
        t[i].norm[1] = has ? q->median : NAN;
        t[i].norm[2] = has ? q->max : NAN;
        t[i].nreps = g->ok ? g->nreps : 0;
    }
    free(jobs);
    free(f);
    return rc;
}

int tp_check_host_c(struct tp_program *p, const struct model_spec *m, int nmode, const struct throughput_options *o,
                    long work_items, int threads, struct tp_sums_check *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    out->iters = TP_CHECK_ITERS;
    out->work_items = work_items;
    size_t nout = (size_t)work_items * 16;
    float *dev = malloc(nout * sizeof *dev), *host = malloc(nout * sizeof *host);
    int rc = 0;
    double t;
    if (!dev || !host) {
        snprintf(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (tp_program_launch(p, m, nmode, o, work_items, TP_CHECK_ITERS, dev, &t)) {
        snprintf(err, errlen, "the device launch of the sums check failed (see stderr)");
        rc = EXIT_RUNTIME;
        goto done;
    }
    struct tp_inputs in;
    tp_inputs_for(o, nmode, work_items, TP_CHECK_ITERS, &in);
    if (hostc_throughput(m ? m->info->kernel_id : -1, m ? (float)m->params[0] : 0.0f, m ? (float)m->params[1] : 0.0f,
                         &in, threads, host, &t, err, errlen)) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (size_t i = 0; i < nout; ++i) {
        out->device_sum += dev[i];
        out->c_sum += host[i];
        out->c_abs_sum += fabs((double)host[i]);
    }
    double d = fabs(out->device_sum - out->c_sum);
    out->rel_diff = out->c_abs_sum > 0 ? d / out->c_abs_sum : (d == 0 ? 0 : INFINITY);
    /* !(a > b): a NaN sum never agrees */
    out->agree = isfinite(out->device_sum) && isfinite(out->c_sum) && out->rel_diff <= TP_CHECK_TOL;
done:
    free(host);
    free(dev);
    return rc;
}
