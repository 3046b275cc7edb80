/* throughput.c - measures every model's cost on the device against pow(), tuned C and the
 * device's peak (see throughput.h for the protocol); throughput_report.c writes the results. */
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
#include "rdoc.h"
#include "runner.h"
#include "stats.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static const char *const variant_names[TP_VARIANT_COUNT] = { "default", "fast-relaxed-math", "denorms-are-zero", "ab" };
/* the ab variant's options are the run's (throughput_options.ab_options) */
static const char *const variant_opts[TP_VARIANT_COUNT] = { "", "-cl-fast-relaxed-math", "-cl-denorms-are-zero", "" };
static const char *const nmode_names[TP_NMODE_COUNT] = { "uniform", "varying" };

const char *tp_variant_name(int v) { return v >= 0 && v < TP_VARIANT_COUNT ? variant_names[v] : "?"; }
const char *tp_variant_options(int v) { return v >= 0 && v < TP_VARIANT_COUNT ? variant_opts[v] : ""; }
const char *tp_nmode_name(int m) { return m >= 0 && m < TP_NMODE_COUNT ? nmode_names[m] : "?"; }

void throughput_options_default(struct throughput_options *o)
{
    memset(o, 0, sizeof *o);
    o->model_count = 0;
    o->reps = 5;
    o->min_time = 0.02;
    o->variants = (1u << TP_VARIANT_AB) - 1;   /* the three; ab with --ab-options */
    o->n_modes = (1u << TP_NMODE_COUNT) - 1;
    o->variant_n_modes = 1u << TP_N_UNIFORM;
    o->host_c = 1;
    o->threads = 0;
    o->work_items = 0;
    o->n_uniform = 100;
    o->n_lo = 2;
    o->n_hi = 1000;
    o->sweep = 1;
    o->sweep_grid = (struct accuracy_grid){ 2.0, 1000.0, 1.0, ACC_DEFAULT_SAMPLES };
    o->sweep_reps = 3;
    o->base_options = NULL;
    o->seed = 0x5eed0001ULL;
}

int throughput_options_check(const struct throughput_options *o, char *err, size_t errlen)
{
    if (o->model_count < 0 || o->model_count > TP_MAX_MODELS) {
        snprintf(err, errlen, "--models: %d models (accepted: 1 to %d)", o->model_count, TP_MAX_MODELS);
        return EXIT_USAGE;
    }
    if (o->reps < 1 || o->reps > TP_MAX_REPS) {
        snprintf(err, errlen, "--reps: %d is out of range (accepted: 1 to %d)", o->reps, TP_MAX_REPS);
        return EXIT_USAGE;
    }
    if (!(o->min_time >= TP_MIN_TIME_MIN && o->min_time <= TP_MIN_TIME_MAX)) {
        snprintf(err, errlen, "--min-time: %g is out of range (accepted: %g to %g seconds)", o->min_time,
                 TP_MIN_TIME_MIN, TP_MIN_TIME_MAX);
        return EXIT_USAGE;
    }
    if (o->variants == 0 || o->variants >= (1u << TP_VARIANT_COUNT)) {
        snprintf(err, errlen, "--variants: none selected (accepted: default, fast-relaxed-math, denorms-are-zero)");
        return EXIT_USAGE;
    }
    if (((o->variants >> TP_VARIANT_AB) & 1u) != (o->ab_options != NULL)) {
        snprintf(err, errlen, "--variants: ab is the variant of --ab-options OPTIONS (give both, or neither)");
        return EXIT_USAGE;
    }
    if (o->n_modes == 0 || o->n_modes >= (1u << TP_NMODE_COUNT) || o->variant_n_modes >= (1u << TP_NMODE_COUNT)) {
        snprintf(err, errlen, "--n-modes: none selected (accepted: uniform, varying)");
        return EXIT_USAGE;
    }
    if (o->threads < 0 || o->threads > 256) {
        snprintf(err, errlen, "--threads: %d is out of range (accepted: 1 to 256, 0 for the online CPUs)", o->threads);
        return EXIT_USAGE;
    }
    if (o->work_items < 0 || o->work_items > TP_MAX_WORK_ITEMS) {
        snprintf(err, errlen, "--work-items: %ld is out of range (accepted: 1 to %d)", o->work_items,
                 TP_MAX_WORK_ITEMS);
        return EXIT_USAGE;
    }
    if (!(o->n_uniform > 0 && o->n_uniform <= ACC_MAX_N)) {
        snprintf(err, errlen, "--n: %g is out of range (accepted: 0 < n <= %g)", o->n_uniform, ACC_MAX_N);
        return EXIT_USAGE;
    }
    if (!(o->n_lo > 0 && o->n_hi <= ACC_MAX_N && o->n_lo < o->n_hi)) {
        snprintf(err, errlen, "--n-range: [%g, %g] is out of range (accepted: 0 < lo < hi <= %g)", o->n_lo, o->n_hi,
                 ACC_MAX_N);
        return EXIT_USAGE;
    }
    if (o->sweep) {
        if (o->sweep_reps < 1 || o->sweep_reps > TP_MAX_REPS) {
            snprintf(err, errlen, "--sweep-reps: %d is out of range (accepted: 1 to %d)", o->sweep_reps, TP_MAX_REPS);
            return EXIT_USAGE;
        }
        int rc = accuracy_grid_check(&o->sweep_grid, NULL, err, errlen);
        if (rc)
            return rc;
    }
    return 0;
}

/* ---- figures ---------------------------------------------------------------------------- */

struct tp_stats tp_stats_of(const double *v, int n)
{
    struct tp_stats s = { NAN, NAN, NAN };
    double sorted[TP_MAX_REPS];
    int k = 0;
    for (int i = 0; i < n; ++i)
        if (isfinite(v[i]))
            sorted[k++] = v[i];
    if (k == 0)
        return s;
    qsort(sorted, (size_t)k, sizeof *sorted, stats_cmp_double);
    s.min = sorted[0];
    s.max = sorted[k - 1];
    s.median = stats_median_sorted(sorted, (size_t)k);
    return s;
}

/* Rates from times: the fastest launch gives the largest rate. */
struct tp_stats tp_rates_of(struct tp_stats seconds, double work)
{
    struct tp_stats r = { work / seconds.max, work / seconds.median, work / seconds.min };
    return r;
}

void tp_fig_fail(struct tp_figure *f, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(f->reason, sizeof f->reason, fmt, ap);
    va_end(ap);
    f->ok = 0;
}

double tp_sum_floats(const float *v, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; ++i)
        s += v[i];
    return s;
}

/* ---- the throughput program --------------------------------------------------------------- */

int tp_program_build(struct tp_program *p, struct cl_session *s, const struct model_spec *models, int count,
                     int variant, const char *base_options)
{
    memset(p, 0, sizeof *p);
    p->s = s;
    p->variant = variant;
    snprintf(p->options, sizeof p->options, "%s%s%s", base_options ? base_options : "",
             base_options && *base_options && *tp_variant_options(variant) ? " " : "", tp_variant_options(variant));
    if (s->specialise)   /* the scalar kernels (kernels/throughput.cl, TP_W) */
        snprintf(p->options + strlen(p->options), sizeof p->options - strlen(p->options), "%s-DTP_W=1",
                 p->options[0] ? " " : "");
    char extra[TP_MAX_MODELS * 32 + 64];
    size_t used = 0;
    extra[0] = '\0';
    int rc = 0;
    for (int i = 0; i < count && p->id_count < TP_MAX_MODELS && rc == 0; ++i) {
        int id = models[i].info->kernel_id;
        /* A model that the shared build does not serve (a user model) gets throughput.cl with
           its kernel set and its own text, from the run's cache (host/core/programs.h). */
        char own_extra[64];
        cl_program own = NULL;
        snprintf(own_extra, sizeof own_extra, "TP_MODEL_KERNELS(%d)\n", id);
        rc = programs_program(s, "throughput.cl", own_extra, p->options, &models[i], NULL, &own);
        if (own) {
            int known = 0;
            for (int k = 0; k < p->user_count; ++k)
                known |= p->user[k].model == models[i].info;
            if (!known && p->user_count < TP_MAX_MODELS) {
                p->user[p->user_count].model = models[i].info;
                p->user[p->user_count++].program = own;
            }
        }
        if (rc || own)
            continue;
        int seen = 0;
        for (int k = 0; k < p->id_count; ++k)
            seen |= p->ids[k] == id;
        if (seen)
            continue;
        p->ids[p->id_count++] = id;
        used += (size_t)snprintf(extra + used, sizeof extra - used, "TP_MODEL_KERNELS(%d)\n", id);
    }
    if (rc == 0) {
        rc = clsession_build(s, "throughput.cl", extra, p->options, &p->program);
        p->build_seconds = s->last_build_seconds;
    }
    return rc;
}

void tp_program_release(struct tp_program *p)
{
    if (p->program)
        clReleaseProgram(p->program);
    p->program = NULL;
    p->user_count = 0;   /* the user models' builds belong to the run's cache */
}

/* The user model's own program, or NULL (a built-in model, or pow). */
static cl_program tp_user_program(const struct tp_program *p, const struct model_spec *m)
{
    for (int k = 0; m && k < p->user_count; ++k)
        if (p->user[k].model == m->info)
            return p->user[k].program;
    return NULL;
}

int tp_has(const struct tp_program *p, const struct model_spec *m)
{
    if (!m)
        return 1;
    if (tp_user_program(p, m))
        return 1;
    for (int k = 0; k < p->id_count; ++k)
        if (p->ids[k] == m->info->kernel_id)
            return 1;
    return 0;
}

cl_kernel tp_kernel(struct tp_program *p, const char *kind, const struct model_spec *m, cl_int *e)
{
    char name[64];
    if (m)
        snprintf(name, sizeof name, "tp_%s_%d", kind, m->info->kernel_id);
    else
        snprintf(name, sizeof name, "tp_%s_pow", kind);
    cl_program user = tp_user_program(p, m);
    return clsession_create_kernel(user ? user : p->program, name, e);
}

void tp_inputs_for(const struct throughput_options *o, int nmode, long work_items, long iters, struct tp_inputs *in)
{
    memset(in, 0, sizeof *in);
    in->varying = nmode == TP_N_VARYING;
    in->n_uniform = (float)o->n_uniform;
    in->n_lo = (float)o->n_lo;
    in->dn_lane = (float)((o->n_hi - o->n_lo) / (double)TP_EVALS_PER_ITER);
    in->dn_step = (float)((double)in->dn_lane / (double)iters);
    in->dc = (float)(1.0 / ((double)TP_EVALS_PER_ITER * (double)iters));
    in->iters = iters;
    in->work_items = work_items;
}
/* ---- a whole run -------------------------------------------------------------------------- */

/* Probe points as in the accuracy check: half in the epicentre, half over the fall-off (out to
   4 x_e), n spread over the varying range. */
static void tp_probe_points(const struct throughput_options *o, float *c, float *n, int count)
{
    uint64_t state = 0x2545f4914f6cdd1dULL;
    for (int i = 0; i < count; ++i) {
        double u = lcg_unit(&state);
        double v = lcg_unit(&state);
        double nv = (double)(float)(o->n_lo + u * (o->n_hi - o->n_lo));
        double x_e = zone_epicentre_end(nv);
        double x = (i % 2 == 0) ? v * x_e : fmin(1.57079632679489662, x_e + v * 3.0 * x_e);
        c[i] = (float)cos(x);
        n[i] = (float)nv;
    }
}

/* A model whose values are NaN or Inf at some of the probe points computes nothing
   that counts: its accuracy and its rates are failed, with the reason (a rate of such code
   read as "206 G/s, 118% of peak"). */
static void tp_mark_nonfinite(struct tp_entry *e, int v, long bad)
{
    snprintf(e->acc_reason[v], TP_REASON, "%ld of %d values were NaN or Inf",
             bad, TP_ACC_POINTS);
    for (int m = 0; m < TP_NMODE_COUNT; ++m) {
        struct tp_figure *f = &e->dev[v][m];
        if (!f->ok)
            continue;
        f->ok = 0;
        snprintf(f->reason, sizeof f->reason, "the model's values are not finite (%ld of %d accuracy points NaN or "
                 "Inf); its rate is not a figure", bad, TP_ACC_POINTS);
    }
}

static void tp_accuracy(struct tp_run *r, struct tp_program *p, int v, const float *c, const float *n, float *out)
{
    for (int i = 0; i < r->nentries; ++i) {
        struct tp_entry *e = &r->e[i];
        e->acc_ok[v] = 0;
        e->acc_max_diff[v] = NAN;
        if (e->skipped) {
            snprintf(e->acc_reason[v], TP_REASON, "not measured");
            continue;
        }
        if (tp_program_points(p, e->m, c, n, TP_ACC_POINTS, out)) {
            snprintf(e->acc_reason[v], TP_REASON, "the points kernel failed (see stderr)");
            continue;
        }
        /* The model's double reference (for a user model: host/core/programs.h). */
        if (programs_host(r->s, e->m)) {
            snprintf(e->acc_reason[v], TP_REASON, "the user model's double reference failed (see stderr)");
            continue;
        }
        /* the double values, each model's in one sandbox stage for a user model's code */
        static double host[TP_ACC_POINTS], peak[TP_ACC_POINTS];
        if (!e->m) {   /* the power kernel's own row (no model) */
            for (int k = 0; k < TP_ACC_POINTS; ++k) {
                host[k] = pow((double)c[k], (double)n[k]);
                peak[k] = 1.0;
            }
        } else {
            struct model_spec ref;
            model_reference_spec(e->m, &ref);
            if (model_values_and_peaks(e->m, &ref, c, n, TP_ACC_POINTS, host, peak)) {
                snprintf(e->acc_reason[v], TP_REASON, "the user model's double reference failed (see stderr)");
                continue;
            }
        }
        double worst = 0;
        long bad = 0;
        for (int k = 0; k < TP_ACC_POINTS; ++k) {
            if (!isfinite(out[k])) {
                ++bad;   /* a lobe is finite everywhere; NaN or Inf is a broken model */
                continue;
            }
            double d = fabs((double)out[k] - host[k]) / (peak[k] > 0 ? peak[k] : 1.0);
            if (!(d <= worst))
                worst = d;
        }
        e->acc_ok[v] = bad == 0;
        e->acc_max_diff[v] = bad == TP_ACC_POINTS ? NAN : worst;
        e->acc_nonfinite[v] = bad;
        if (bad)
            tp_mark_nonfinite(e, v, bad);
    }
}

/* Builds the program of every variant (each build timed on its own), then measures model by
 * model with the variants back to back and the C baseline interleaved with the default
 * variant, so that every ratio compares figures taken moments apart. */
static void tp_measure_models(struct tp_run *r, int quiet)
{
    struct tp_program prog[TP_VARIANT_COUNT];
    memset(prog, 0, sizeof prog);
    for (int v = 0; v < TP_VARIANT_COUNT; ++v) {
        if (!variant_on(r, v))
            continue;
        char ab[600];
        if (v == TP_VARIANT_AB)   /* the run's own options, then the A/B side's */
            snprintf(ab, sizeof ab, "%s%s%s", r->o->base_options ? r->o->base_options : "",
                     r->o->base_options && *r->o->base_options ? " " : "", r->o->ab_options);
        int rc = tp_program_build(&prog[v], r->s, r->models, r->nmodels, v, v == TP_VARIANT_AB ? ab : r->o->base_options);
        snprintf(r->options[v], sizeof r->options[v], "%s", prog[v].options);
        r->build_seconds[v] = prog[v].build_seconds;
        if (rc) {
            snprintf(r->build_reason[v], TP_REASON,
                     "building kernels/throughput.cl with \"%.150s\" failed (build log on stderr)", prog[v].options);
            continue;
        }
        r->built[v] = 1;
        if (!quiet)
            fprintf(stderr, "throughput: %s build %.2f s\n", tp_variant_name(v), prog[v].build_seconds);
    }
    /* every figure of the run in one set of interleaved rounds: each model in each n mode
       and variant, its C loop, and the peak kernel as the reference */
    int cap = r->nentries * TP_NMODE_COUNT * (TP_VARIANT_COUNT + 1), njobs = 0;
    struct tp_job *jobs = calloc((size_t)cap, sizeof *jobs);
    for (int i = 0; jobs && i < r->nentries; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m)
            for (int v = 0; v < TP_VARIANT_COUNT; ++v) {
                if (!variant_on(r, v) || !nmode_on(r, v, m))
                    continue;
                struct tp_entry *en = &r->e[i];
                struct tp_figure *f = &en->dev[v][m];
                memset(f, 0, sizeof *f);
                en->measured[v][m] = 1;
                if (en->skipped)
                    tp_fig_fail(f, "user models are not compiled into the throughput kernels");
                else if (!r->built[v])
                    tp_fig_fail(f, "%s", r->build_reason[v]);
                jobs[njobs++] = (struct tp_job){ f, &prog[v], en->m, m };
                if (v != TP_VARIANT_DEFAULT || !r->o->host_c)
                    continue;
                struct tp_figure *c = &en->hostc[m];
                memset(c, 0, sizeof *c);
                if (en->m && !hostc_supports(en->m->info->kernel_id))
                    tp_fig_fail(c, "no C loop for this model (user models run on the device only)");
                jobs[njobs++] = (struct tp_job){ c, NULL, en->m, m };
            }
    struct tp_bench b = { r->s, r->o, r->work_items, r->threads, r->peak_options, &r->peak, 0, 0, 0, 0, 0 };
    snprintf(r->peak_options, sizeof r->peak_options, "%s", r->o->base_options ? r->o->base_options : "");
    if (jobs)
        tp_bench_run(&b, jobs, njobs, quiet);
    r->peak_build_seconds = b.peak_build_seconds;
    r->launches = b.launches;
    r->retried = b.retried;
    r->disturbed = b.disturbed;
    r->rounds = b.rounds;
    for (int i = 0; !quiet && i < r->nentries; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m)
            for (int v = 0; v < TP_VARIANT_COUNT; ++v) {
                if (!variant_on(r, v) || !nmode_on(r, v, m))
                    continue;
                const struct tp_figure *f = &r->e[i].dev[v][m];
                fprintf(stderr, "throughput: %-18s %-8s %-17s %8.3g G/s%s%s\n", r->e[i].label, nmode_names[m],
                        tp_variant_name(v), f->ok ? f->rate.median * 1e-9 : NAN, f->ok ? "" : "  ",
                        f->ok ? "" : f->reason);
            }
    free(jobs);
    /* The C loop's work must be the kernel's: its sums against the device's at one small
       launch of each, before any ratio is printed (a C figure of other work is no baseline). */
    for (int i = 0; r->o->host_c && r->built[TP_VARIANT_DEFAULT] && i < r->nentries; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m) {
            struct tp_figure *hc = &r->e[i].hostc[m];
            if (!hc->ok)
                continue;
            char err[256] = "";
            hc->checked = 1;
            if (tp_check_host_c(&prog[TP_VARIANT_DEFAULT], r->e[i].m, m, r->o, r->work_items, r->threads, &hc->check,
                                err, sizeof err))
                tp_fig_fail(hc, "its sums could not be checked against the device's (%.200s); no ratio", err);
            else if (!hc->check.agree)
                tp_fig_fail(hc, "its sums differ from the device's on the same inputs (device %.9g, C %.9g, "
                                "relative difference %.3g over %ld iterations x %ld work-items): not the same work; "
                                "no ratio", hc->check.device_sum, hc->check.c_sum, hc->check.rel_diff,
                            hc->check.iters, hc->check.work_items);
        }
    float *c = malloc(TP_ACC_POINTS * sizeof *c), *n = malloc(TP_ACC_POINTS * sizeof *n);
    float *vals = malloc(TP_ACC_POINTS * sizeof *vals);
    if (c && n && vals)
        tp_probe_points(r->o, c, n, TP_ACC_POINTS);
    for (int v = 0; v < TP_VARIANT_COUNT; ++v) {
        if (r->built[v] && c && n && vals)
            tp_accuracy(r, &prog[v], v, c, n, vals);
        tp_program_release(&prog[v]);
    }
    free(vals);
    free(n);
    free(c);
}

/* Relative difference of two per-n figures. Below 1e-4 a figure is float noise (a model equal
   to its reference, such as cq2 at n = 2), so differences are taken relative to at least that. */
static double rel_diff(float a, float b)
{
    double s = fmax(fmax(fabs((double)a), fabs((double)b)), 1e-4);
    return fabs((double)a - (double)b) / s;
}

/* One side of the sweep's timing as an item of the runner: the device sweep of a model, or
   (c set) the same sweep in tuned C. A sweep is fixed work: not calibrated. */
struct tp_sweep_item {
    struct accuracy_ctx *a;
    const struct model_spec *m, *ref;
    const struct accuracy_grid *g;
    const float *nv;
    long count;
    int threads, c;
    float *out;                   /* the sweep's per-n figures, for the agreement check */
};

static int tp_sweep_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    struct tp_sweep_item *w = ctx;
    (void)iters;
    if (!w->c) {
        if (accuracy_sweep_device(w->a, w->m, w->g, w->out, seconds)) {
            snprintf(reason, reason_len, "the device sweep failed (see stderr)");
            return -1;
        }
        return 0;
    }
    return hostc_sweep(w->m->info->kernel_id, (float)w->m->params[0], (float)w->m->params[1], w->ref->info->kernel_id,
                       (float)w->ref->params[0], (float)w->ref->params[1], w->nv, w->count, w->g->samples, w->threads,
                       w->out, seconds, reason, reason_len)
               ? -1 : 0;
}

/* The accuracy sweep on the device (its own kernel, as `brdfbench accuracy` runs it) against
   the same sweep in C, every model's two sides items of one runner: warmed up, then
   o->sweep_reps rounds in a fresh random order each. */
static void tp_measure_sweep(struct tp_run *r, int quiet)
{
    const struct throughput_options *o = r->o;
    const struct accuracy_grid *g = &o->sweep_grid;
    struct accuracy_ctx actx;
    int opened = 0, n = 0;
    r->sweep_ran = 1;
    r->sweep_n_count = accuracy_grid_count(g);
    r->sw = calloc((size_t)r->nmodels, sizeof *r->sw);
    float *nv = malloc((size_t)r->sweep_n_count * sizeof *nv);
    size_t per = (size_t)r->sweep_n_count * ACC_OUT_STRIDE;
    float *outs = malloc(2 * (size_t)r->nmodels * per * sizeof *outs);
    struct model_spec *refs = calloc((size_t)r->nmodels, sizeof *refs);
    struct tp_sweep_item *si = calloc(2 * (size_t)r->nmodels, sizeof *si);
    struct runner_item *items = calloc(2 * (size_t)r->nmodels, sizeof *items);
    int *first = calloc((size_t)r->nmodels, sizeof *first);
    if (!r->sw || !nv || !outs || !refs || !si || !items || !first) {
        snprintf(r->sweep_reason, TP_REASON, "out of memory for %ld values of n", r->sweep_n_count);
        goto done;
    }
    if (accuracy_grid_check(g, r->s, r->sweep_reason, TP_REASON))
        goto done;
    if (accuracy_open(&actx, r->s, o->base_options ? o->base_options : "")) {
        snprintf(r->sweep_reason, TP_REASON, "building kernels/accuracy.cl failed (build log on stderr)");
        goto done;
    }
    opened = 1;
    r->sweep_build_seconds = r->s->last_build_seconds;
    for (long i = 0; i < r->sweep_n_count; ++i)
        nv[i] = (float)accuracy_grid_n(g, i);
    r->nsw = r->nmodels;
    for (int k = 0; k < r->nmodels; ++k) {
        const struct model_spec *m = &r->models[k];
        struct tp_sweep_model *w = &r->sw[k];
        snprintf(w->label, sizeof w->label, "%s", m->label);
        w->points = (double)r->sweep_n_count * 2.0 * (double)g->samples;
        model_reference_spec(m, &refs[k]);
        first[k] = -1;
        if (!hostc_supports(m->info->kernel_id) || !hostc_supports(refs[k].info->kernel_id)) {
            snprintf(w->reason, TP_REASON, "user models have no C loop; not compared");
            continue;
        }
        first[k] = n;
        for (int c = 0; c < 2; ++c, ++n) {
            si[n] = (struct tp_sweep_item){ &actx, m, &refs[k], g, nv, r->sweep_n_count, r->threads, c,
                                           outs + (size_t)n * per };
            items[n] = (struct runner_item){ .name = m->label, .launch = tp_sweep_launch, .ctx = &si[n],
                                             .calibrate = 0, .iters = 1, .work_per_iter = w->points,
                                             .cpu_threads = c ? r->threads
                                                          : r->s->is_cpu ? (int)r->s->compute_units : 0 };
        }
    }
    if (n == 0)   /* nothing to time: say why rather than "every model failed" */
        snprintf(r->sweep_reason, TP_REASON, "no model has a tuned C loop to compare with (user models have none)");
    struct runner run;
    runner_init(&run, items, n);
    run.rounds = o->sweep_reps;
    run.seed = o->seed;
    if (n > 0 && runner_run(&run)) {
        snprintf(r->sweep_reason, TP_REASON, "out of memory");
        runner_release(&run);
        goto done;
    }
    for (int k = 0; k < r->nmodels; ++k) {
        struct tp_sweep_model *w = &r->sw[k];
        int d = first[k];
        if (d < 0)
            continue;
        const struct runner_item *dv = &items[d], *hc = &items[d + 1];
        if (!dv->ok || !hc->ok) {
            snprintf(w->reason, TP_REASON, "%.200s", !dv->ok ? dv->reason : hc->reason);
            continue;
        }
        w->dev_s = tp_stats_of(dv->seconds, dv->nreps);
        w->hostc_s = tp_stats_of(hc->seconds, hc->nreps);
        w->agree = 0;
        const float *dev = si[d].out, *hco = si[d + 1].out;
        for (long i = 0; i < r->sweep_n_count; ++i)
            for (int j = 0; j < 3; ++j) {   /* the record's maxima (kernels/brdf_shared.h) */
                static const int maxima[3] = { ACC_O_EPI_REL, ACC_O_ATT_ABS, ACC_O_EPI_ABS };
                const size_t q = (size_t)i * ACC_OUT_STRIDE + (size_t)maxima[j];
                double x = rel_diff(dev[q], hco[q]);
                if (!(x <= w->agree))
                    w->agree = x;
            }
        /* The C sweep must do the device's work: per-n maxima apart by more than float noise
           (a figure of float rounding's size, ~1e-7, is compared relative to at least 1e-4:
           up to ~2e-3) mean other samples or another formula, and its time is no baseline. */
        if (!(w->agree <= TP_SWEEP_AGREE_TOL)) {
            snprintf(w->reason, TP_REASON, "the C sweep's per-n figures differ from the device's by %.3g (relative; "
                     "accepted: %g): not the same work; no ratio", w->agree, TP_SWEEP_AGREE_TOL);
            continue;
        }
        w->ok = 1;
        if (!quiet)
            fprintf(stderr, "throughput: sweep %-18s device %.3f s, C %.3f s\n", w->label, w->dev_s.median,
                    w->hostc_s.median);
    }
    if (n > 0)
        runner_release(&run);
done:
    if (opened)
        accuracy_close(&actx);
    free(first);
    free(items);
    free(si);
    free(refs);
    free(outs);
    free(nv);
}

static int tp_run_all(struct cl_session *s, const struct throughput_options *o, const char *out_dir, int quiet,
                      char **markdown)
{
    char err[1024];
    if (markdown)
        *markdown = NULL;
    if (throughput_options_check(o, err, sizeof err)) {
        fprintf(stderr, "brdfbench throughput: %s\n", err);
        return EXIT_USAGE;
    }
    struct tp_run *r = calloc(1, sizeof *r);
    if (!r)
        return EXIT_RUNTIME;
    int rc = 0;
    float *sums = NULL, *csums = NULL;
    struct rdoc *rows = NULL;
    r->s = s;
    r->o = o;
    if (o->model_count > 0) {
        memcpy(r->models, o->models, (size_t)o->model_count * sizeof o->models[0]);
        r->nmodels = o->model_count;
    } else {
        r->nmodels = model_spec_list_default(r->models, TP_MAX_MODELS);
    }
    r->work_items = o->work_items > 0 ? o->work_items : clsession_default_work_items(s, TP_MAX_WORK_ITEMS);
    r->threads = o->threads > 0 ? o->threads : hostc_default_threads();
    r->nentries = r->nmodels + 1;
    r->e = calloc((size_t)r->nentries, sizeof *r->e);
    sums = malloc((size_t)r->work_items * 16 * sizeof *sums);
    csums = malloc((size_t)r->work_items * 16 * sizeof *csums);
    if (!r->e || !sums || !csums) {
        fprintf(stderr, "brdfbench throughput: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    snprintf(r->e[0].label, sizeof r->e[0].label, "pow");
    r->e[0].ref_entry = -1;
    for (int i = 1; i < r->nentries; ++i) {
        struct tp_entry *e = &r->e[i];
        e->m = &r->models[i - 1];
        snprintf(e->label, sizeof e->label, "%s", e->m->label);
        e->skipped = 0;   /* user models run on the device (their own builds); they have no C loop */
        e->ref_entry = -1;
        struct model_spec ref;
        model_reference_spec(e->m, &ref);
        for (int k = 1; k < r->nentries; ++k)
            if (strcmp(r->models[k - 1].label, ref.label) == 0)
                e->ref_entry = k;
    }
    if (!quiet)
        fprintf(stderr, "throughput: %s, %ld work-items, %d model%s, min time %.3g s x %d reps\n", s->device_name,
                r->work_items, r->nmodels, r->nmodels == 1 ? "" : "s", o->min_time, o->reps);
    for (int i = 0; i < r->nentries; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m)
            tp_fig_fail(&r->e[i].hostc[m], !o->host_c ? "the C baseline was not run (--no-host-c)"
                                        : !variant_on(r, TP_VARIANT_DEFAULT) ? "the C baseline runs with the default variant"
                                        : "not measured");
    runner_loadavg(r->load_start, sizeof r->load_start);
    r->steal_start = runner_steal_seconds();
    r->seed = o->seed;
    tp_measure_models(r, quiet);
    if (o->sweep)
        tp_measure_sweep(r, quiet);
    runner_loadavg(r->load_end, sizeof r->load_end);
    r->steal_end = runner_steal_seconds();

    char path[4200];
    /* the rows are what throughput.json carries and what the page is drawn from */
    if (!(rows = tp_rows_new(r, err, sizeof err)) || path_join(path, sizeof path, out_dir, "throughput.json") ||
        tp_write_json(r, rows, path, err, sizeof err) || path_join(path, sizeof path, out_dir, "throughput.csv") ||
        tp_write_csv(r, path, err, sizeof err)) {
        fprintf(stderr, "brdfbench throughput: %s\n", err);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (!quiet) {
        char *t = tp_tables_text(rows, 0);
        if (t)
            fputs(t, stdout);
        printf("written: %s/throughput.json, %s/throughput.csv\n", out_dir, out_dir);
        free(t);
    }
    if (markdown)
        *markdown = tp_tables_text(rows, 1);
done:
    rdoc_delete(rows);
    free(csums);
    free(sums);
    if (r) {
        free(r->sw);
        free(r->e);
        free(r);
    }
    return rc;
}

int throughput_run(struct cl_session *s, const struct throughput_options *o, struct throughput_result *r)
{
    return tp_run_all(s, o, o->io.out_dir, o->io.quiet, r ? &r->markdown : NULL);
}

void throughput_result_free(struct throughput_result *r)
{
    free(r->markdown);
    r->markdown = NULL;
}
