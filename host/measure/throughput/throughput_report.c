/* throughput_report.c - writes what a throughput run measured: its rows, throughput.json
 * (schema in throughput.h) and throughput.csv (one line per row); the summary tables for stdout
 * and throughput.md are the page of the rows (report_throughput.c). Nothing here measures. */
#include "throughput_report.h"
#include "context.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "outdir.h"
#include "rdoc.h"
#include "report_throughput.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the tuned C baseline's flags (CMakeLists.txt, BRDFBENCH_HOSTC_MARCH) */
#ifndef BRDF_HOSTC_FLAGS
#define BRDF_HOSTC_FLAGS "-O3 -march=native -fno-math-errno"
#endif

static const char *const nmode_names[TP_NMODE_COUNT] = { "uniform", "varying" };

static double ratio(double a, double b) { return (a > 0 && b > 0 && isfinite(a) && isfinite(b)) ? a / b : NAN; }

static double peak_fma_per_s(const struct tp_run *r)
{
    return r->peak.ok ? r->peak.rate.median / 2.0 : NAN;
}

/* Ratios of entry i under variant v and mode m (NAN when a side is missing). */
struct tp_ratios {
    double to_reference, to_model_reference, to_host_c, of_peak;
};

static struct tp_ratios ratios_of(const struct tp_run *r, int i, int v, int m)
{
    const struct tp_entry *e = &r->e[i];
    const struct tp_figure *f = &e->dev[v][m];
    struct tp_ratios q = { NAN, NAN, NAN, NAN };
    if (!f->ok)
        return q;
    const struct tp_figure *pw = &r->e[0].dev[v][m];
    q.to_reference = pw->ok ? ratio(f->rate.median, pw->rate.median) : NAN;
    if (e->ref_entry >= 0 && r->e[e->ref_entry].dev[v][m].ok)
        q.to_model_reference = ratio(f->rate.median, r->e[e->ref_entry].dev[v][m].rate.median);
    if (e->hostc[m].ok)
        q.to_host_c = ratio(f->rate.median, e->hostc[m].rate.median);
    q.of_peak = ratio(f->rate.median, peak_fma_per_s(r));
    return q;
}

static void jw_stats(struct jw *w, const char *key, struct tp_stats s)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, "min", s.min);
    jw_kv_num(w, "median", s.median);
    jw_kv_num(w, "max", s.max);
    jw_obj_end(w);
}

static void jw_ratio(struct jw *w, const char *key, double v, const char *why_missing)
{
    jw_kv_num(w, key, v);
    if (!isfinite(v)) {
        char k[96];
        snprintf(k, sizeof k, "%s_reason", key);
        jw_kv_str(w, k, why_missing);
    }
}

/* Every timed launch's rate, in the order they ran: what a comparison of two runs tests. */
static void jw_reps(struct jw *w, const char *key, const struct tp_figure *f)
{
    jw_kv_arr(w, key);
    for (int k = 0; f->ok && k < f->nreps; ++k)
        jw_num(w, f->rep_seconds[k] > 0 ? f->per_launch / f->rep_seconds[k] : NAN);
    jw_arr_end(w);
}

/* The runner's record of a figure: its normalised rates (rate over the peak kernel's rate in
   the same round), its preemption retries, and which timer gave its times. */
static void jw_runner_fields(struct jw *w, const struct tp_figure *f)
{
    int norm = f->ok && f->has_norm, cn = f->ok && f->has_cpu_norm;
    jw_stats(w, "normalised", norm ? f->norm : (struct tp_stats){ NAN, NAN, NAN });
    jw_kv_nums(w, "normalised_reps", f->rep_norm, norm ? (size_t)f->nreps : 0);
    jw_stats(w, "normalised_cpu", cn ? f->cpu_norm : (struct tp_stats){ NAN, NAN, NAN });
    jw_kv_nums(w, "normalised_cpu_reps", f->rep_cpu_norm, cn ? (size_t)f->nreps : 0);
    jw_kv_nums(w, "cpu_seconds_reps", f->rep_cpu, f->ok ? (size_t)f->nreps : 0);
    jw_kv_int(w, "preemption_retries", f->retries);
    jw_kv_int(w, "disturbed_reps", f->disturbed);
    jw_kv_str(w, "timer", f->timer_wall ? "wall time: the driver's profiling events gave no time" : "profiling events");
}

/* The kernel sources the run compiled (embedded, or --kernel-dir's), fingerprinted. */
static const char *const fingerprinted[] = { "brdf_models.h", "throughput.cl", "accuracy.cl", "peak.cl" };
#define FINGERPRINTED (sizeof fingerprinted / sizeof fingerprinted[0])

/* The FNV-1a 64-bit hash of a kernel source in hex, or "unreadable". */
static void kernel_fingerprint(const char *file, char hex[24])
{
    size_t len = 0;
    char *src = clsession_kernel_source(file, &len);
    if (!src) {
        snprintf(hex, 24, "unreadable");
        return;
    }
    unsigned long long h = 0xcbf29ce484222325ULL;   /* FNV-1a, 64 bits */
    for (size_t k = 0; k < len; ++k)
        h = (h ^ (unsigned char)src[k]) * 0x100000001b3ULL;
    snprintf(hex, 24, "%016llx", h);
    free(src);
}

/* A fingerprint of the kernel sources the run compiled: a kernel changed without a commit
   still shows in the context that compare lays side by side. */
static void jw_kernel_fingerprints(struct jw *w, char hex[][24])
{
    jw_kv_obj(w, "kernel_sources_fnv1a64");
    for (size_t i = 0; i < FINGERPRINTED; ++i)
        jw_kv_str(w, fingerprinted[i], hex[i]);
    jw_obj_end(w);
}

static const char *const tp_definitions[][2] = {
    { "evals_per_s", "model evaluations per second: work-items x iterations x 64 over the launch time (profiling events); min/median/max over the timed launches" },
    { "evals_per_s_wall", "the same over wall time, enqueue to clFinish" },
    { "evals_per_s_reps", "evals_per_s of every timed launch, in the order they ran (empty when the figure failed); brdfbench compare tests two runs' repetitions against each other" },
    { "ratio_to_reference", "evals_per_s / evals_per_s of the pow(c, n) built-in, same build options and n mode, same run" },
    { "ratio_to_model_reference", "evals_per_s / evals_per_s of the model's own reference (phong, phongn, blinnn) as brdf_models.h evaluates it" },
    { "ratio_to_host_c", "evals_per_s / evals_per_s of tuned C doing the same evaluations (host/support/hostc_baseline.c: \"host_c_flags\", pthreads over the online CPUs, powf for c^n)" },
    { "fraction_of_peak", "evals_per_s / the device's measured peak in FMA per second (peak_fma float16 chains; flops / 2): the inverse is the model's cost in FMA slots" },
    { "inputs", "c sweeps [0, 1) per work-item in steps of 1/(64 iters), made in registers; n uniform = a kernel argument, n varying = a different n in [n_lo, n_hi] for every evaluation" },
    { "accuracy.max_diff_of_peak", "largest |device value - double reference value| / |reference lobe at c = 1| over 4096 probe points, half in the epicentre, half out to 4 x_e, n over [n_lo, n_hi]" },
};

/* A reference lobe computed by another formula than its reference (phongpow: pow(c, n)
   against phong): its sweep differs from C's by design, so it is left out of the run's
   agreement figure (its own figure stays in the model's entry). */
static int sweep_alternative(const char *label)
{
    const struct model_info *mi = models_find(label);
    return mi && mi->family == MODEL_FAMILY_REFERENCE && strcmp(mi->id, mi->reference_id) != 0;
}

/* Steps (v, i, m) to the next measured row (variant v, entry i, n mode m), in the order the
 * result files list them; start from v = i = 0, m = -1. 0 when there is none left. */
static int next_measured(const struct tp_run *r, int *v, int *i, int *m)
{
    if (r->nentries <= 0)
        return 0;
    for (;;) {
        if (++*m == TP_NMODE_COUNT) {
            *m = 0;
            if (++*i == r->nentries) {
                *i = 0;
                if (++*v == TP_VARIANT_COUNT)
                    return 0;
            }
        }
        if (variant_on(r, *v) && r->e[*i].measured[*v][*m])
            return 1;
    }
}

/* throughput.json, part by part (tp_write_json). */
static void json_context(struct jw *w, const struct tp_run *r, char hex[][24])
{
    const struct throughput_options *o = r->o;
    const char *aff = getenv("POCL_AFFINITY");
    jw_kv_str(w, "pocl_affinity", aff ? aff : "(unset)");
    jw_kv_obj(w, "throughput");
    jw_kv_int(w, "reps", o->reps);
    jw_kv_num(w, "min_time_s", o->min_time);
    jw_kv_int(w, "work_items", r->work_items);
    size_t local;   /* the launches' work-group size (clsession_group_size; 0: the driver's choice) */
    clsession_group_size(r->s, (size_t)r->work_items, &local);
    jw_kv_int(w, "local_size", (long)local);
    jw_kv_int(w, "evaluations_per_iteration", TP_EVALS_PER_ITER);
    jw_kv_num(w, "n_uniform", (float)o->n_uniform);
    jw_kv_num(w, "n_lo", o->n_lo);
    jw_kv_num(w, "n_hi", o->n_hi);
    jw_kv_int(w, "host_c_threads", o->host_c ? r->threads : 0);
    jw_kv_str(w, "host_c_flags", BRDF_HOSTC_FLAGS);
    jw_kv_str(w, "loadavg_start", r->load_start);
    jw_kv_str(w, "loadavg_end", r->load_end);
    jw_kv_obj(w, "runner");
    jw_kv_int(w, "rounds", r->rounds);
    jw_kv_str(w, "order", "every figure once per round, in a fresh random order each round");
    jw_kv_int(w, "seed", (long)(r->seed & 0x7fffffffffffffffULL));
    jw_kv_str(w, "reference", "peak_fma (kernels/peak.cl), timed in every round");
    jw_kv_int(w, "launches", r->launches);
    jw_kv_int(w, "preemption_retries", r->retried);
    jw_kv_int(w, "disturbed_reps", r->disturbed);
    jw_kv_num(w, "steal_seconds", r->steal_start >= 0 && r->steal_end >= 0 ? r->steal_end - r->steal_start : NAN);
    jw_obj_end(w);
    jw_kernel_fingerprints(w, hex);
    jw_obj_end(w);
    jw_obj_end(w);   /* context */

}

static void json_builds(struct jw *w, const struct tp_run *r)
{
    jw_kv_arr(w, "builds");
    for (int v = 0; v < TP_VARIANT_COUNT; ++v) {
        if (!variant_on(r, v))
            continue;
        jw_obj_begin(w);
        jw_kv_str(w, "variant", tp_variant_name(v));
        jw_kv_str(w, "build_options", r->options[v]);
        jw_kv_str(w, "status", r->built[v] ? "ok" : "failed");
        jw_kv_num(w, "build_seconds", r->build_seconds[v]);
        if (!r->built[v])
            jw_kv_str(w, "reason", r->build_reason[v]);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}

static void json_peak(struct jw *w, const struct tp_run *r)
{
    jw_kv_obj(w, "peak");
    jw_kv_str(w, "status", r->peak.ok ? "ok" : "failed");
    if (!r->peak.ok)
        jw_kv_str(w, "reason", r->peak.reason);
    jw_kv_str(w, "kernel", r->s->specialise ? "kernels/peak.cl: 16 independent float FMA chains per work-item (PEAK_W=1), 2 flops per step"
                                            : "kernels/peak.cl: 16 independent float16 FMA chains per work-item, 2 flops per lane and step");
    jw_kv_str(w, "build_options", r->peak_options);
    jw_kv_num(w, "build_seconds", r->peak_build_seconds);
    jw_stats(w, "flops_per_s", r->peak.rate);
    jw_stats(w, "flops_per_s_wall", r->peak.rate_wall);
    jw_kv_num(w, "fma_per_s", peak_fma_per_s(r));
    jw_reps(w, "flops_per_s_reps", &r->peak);
    jw_kv_str(w, "which", "timed once in every round of the runner, among the models: the reference of their "
                          "normalised rates");
    jw_obj_end(w);
}

static void json_host_c(struct jw *w, const struct tp_run *r, const struct tp_entry *e, int m)
{
    const struct throughput_options *o = r->o;
    jw_kv_obj(w, "host_c");
    if (!o->host_c) {
        jw_kv_str(w, "status", "not run");
    } else {
        jw_kv_str(w, "status", e->hostc[m].ok ? "ok" : "failed");
        if (!e->hostc[m].ok)
            jw_kv_str(w, "reason", e->hostc[m].reason);
        jw_stats(w, "evals_per_s", e->hostc[m].ok ? e->hostc[m].rate : (struct tp_stats){ NAN, NAN, NAN });
        jw_reps(w, "evals_per_s_reps", &e->hostc[m]);
        jw_runner_fields(w, &e->hostc[m]);
        jw_kv_int(w, "iterations_per_work_item", e->hostc[m].iters);
        jw_kv_num(w, "checksum", e->hostc[m].ok ? e->hostc[m].checksum : NAN);
        jw_kv_int(w, "threads", r->threads);
        if (e->hostc[m].checked) {   /* the C loop's sums against the device's, same inputs */
            const struct tp_sums_check *k = &e->hostc[m].check;
            jw_kv_obj(w, "sums_check");
            jw_kv_str(w, "status", k->agree ? "agree" : "differ");
            jw_kv_int(w, "iterations_per_work_item", k->iters);
            jw_kv_int(w, "work_items", k->work_items);
            jw_kv_num(w, "device_sum", k->device_sum);
            jw_kv_num(w, "c_sum", k->c_sum);
            jw_kv_num(w, "relative_difference", k->rel_diff);
            jw_kv_num(w, "tolerance", TP_CHECK_TOL);
            jw_obj_end(w);
        }
    }
    jw_obj_end(w);
}

/* One row of "results": entry i in build variant v and n mode m. */
static void json_result(struct jw *w, const struct tp_run *r, int v, int i, int m)
{
    const struct throughput_options *o = r->o;
    const struct tp_entry *e = &r->e[i];
    const struct tp_figure *f = &e->dev[v][m];
    struct tp_ratios q = ratios_of(r, i, v, m);
    jw_obj_begin(w);
    jw_kv_str(w, "model", e->m ? e->m->info->id : "pow");
    jw_kv_str(w, "label", e->label);
    jw_kv_str(w, "kind", e->m ? "model" : "builtin");
    jw_kv_str(w, "formula", e->m ? e->m->info->formula : "pow(c, n), the OpenCL built-in");
    jw_kv_str(w, "variant", tp_variant_name(v));
    jw_kv_str(w, "build_options", r->options[v]);
    jw_kv_str(w, "n_mode", nmode_names[m]);
    jw_kv_str(w, "status", f->ok ? "ok" : "failed");
    if (!f->ok)
        jw_kv_str(w, "reason", f->reason);
    jw_stats(w, "evals_per_s", f->ok ? f->rate : (struct tp_stats){ NAN, NAN, NAN });
    jw_reps(w, "evals_per_s_reps", f);
    jw_runner_fields(w, f);
    jw_stats(w, "evals_per_s_wall", f->ok ? f->rate_wall : (struct tp_stats){ NAN, NAN, NAN });
    jw_stats(w, "seconds", f->ok ? f->sec : (struct tp_stats){ NAN, NAN, NAN });
    jw_stats(w, "seconds_wall", f->ok ? f->sec_wall : (struct tp_stats){ NAN, NAN, NAN });
    jw_kv_int(w, "iterations_per_work_item", f->iters);
    jw_kv_num(w, "evaluations_per_launch", f->per_launch);
    jw_kv_num(w, "checksum", f->ok ? f->checksum : NAN);
    jw_kv_bool(w, "values_finite", f->ok && f->finite);
    if (f->ok && !f->finite)
        jw_kv_str(w, "note", "some values were NaN or Inf under these build options (their sum is not "
                             "finite); the rate is the rate of that code");
    jw_ratio(w, "ratio_to_reference", q.to_reference, f->ok ? "the pow() built-in was not measured" : f->reason);
    jw_ratio(w, "ratio_to_model_reference", q.to_model_reference,
             f->ok ? "the model's reference is not part of this run" : f->reason);
    jw_ratio(w, "ratio_to_host_c", q.to_host_c,
             !f->ok ? f->reason : !o->host_c ? "the C baseline was not run (--no-host-c)"
                     : e->hostc[m].reason);
    jw_ratio(w, "fraction_of_peak", q.of_peak, f->ok ? r->peak.reason : f->reason);
    json_host_c(w, r, e, m);
    jw_kv_obj(w, "accuracy");
    jw_kv_str(w, "status", e->acc_ok[v] ? "ok" : "failed");
    if (!e->acc_ok[v])
        jw_kv_str(w, "reason", e->acc_reason[v][0] ? e->acc_reason[v] : "not measured");
    jw_kv_num(w, "max_diff_of_peak", e->acc_max_diff[v]);
    jw_kv_int(w, "nonfinite", e->acc_nonfinite[v]);
    jw_kv_int(w, "points", TP_ACC_POINTS);
    jw_obj_end(w);
    jw_obj_end(w);
}

static void json_sweep_models(struct jw *w, const struct tp_run *r)
{
    jw_kv_arr(w, "models");
    for (int k = 0; k < r->nsw; ++k) {
        const struct tp_sweep_model *s = &r->sw[k];
        jw_obj_begin(w);
        jw_kv_str(w, "label", s->label);
        jw_kv_str(w, "status", s->ok ? "ok" : "failed");
        if (!s->ok)
            jw_kv_str(w, "reason", s->reason);
        jw_stats(w, "device_seconds", s->ok ? s->dev_s : (struct tp_stats){ NAN, NAN, NAN });
        jw_stats(w, "host_c_seconds", s->ok ? s->hostc_s : (struct tp_stats){ NAN, NAN, NAN });
        jw_kv_num(w, "points", s->points);
        jw_ratio(w, "speedup_vs_host_c", s->ok ? ratio(s->hostc_s.median, s->dev_s.median) : NAN, s->reason);
        jw_kv_num(w, "agreement_max_rel_diff", s->ok ? s->agree : NAN);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}

static void json_sweep_ran(struct jw *w, const struct tp_run *r)
{
    const struct throughput_options *o = r->o;
    double dsum = 0, hsum = 0, pts = 0, agree = 0;
    int all_ok = r->nsw > 0 && !r->sweep_reason[0];
    for (int k = 0; k < r->nsw; ++k) {
        if (!r->sw[k].ok) {
            all_ok = 0;
            continue;
        }
        dsum += r->sw[k].dev_s.median;
        hsum += r->sw[k].hostc_s.median;
        pts += r->sw[k].points;
        if (!sweep_alternative(r->sw[k].label))
            agree = fmax(agree, r->sw[k].agree);
    }
    jw_kv_str(w, "status", all_ok ? "ok" : "partial");
    if (r->sweep_reason[0])
        jw_kv_str(w, "reason", r->sweep_reason);
    jw_kv_str(w, "what", "kernels/accuracy.cl (as brdfbench accuracy runs it) against the same sweep in tuned C "
                         "(the same samples in s = 1 - cos x, the reference lobe as the device's exp(n ln(1 - s))), per model: "
                         "median of the timed runs; a model whose C figures differ from the device's by more "
                         "than 1e-2 (agreement_max_rel_diff) is failed, with no ratio");
    jw_kv_num(w, "n_min", o->sweep_grid.n_min);
    jw_kv_num(w, "n_max", o->sweep_grid.n_max);
    jw_kv_num(w, "n_step", o->sweep_grid.n_step);
    jw_kv_int(w, "n_count", r->sweep_n_count);
    jw_kv_int(w, "samples_per_zone", o->sweep_grid.samples);
    jw_kv_int(w, "reps", o->sweep_reps);
    jw_kv_num(w, "build_seconds", r->sweep_build_seconds);
    jw_kv_num(w, "device_seconds", dsum > 0 ? dsum : NAN);
    jw_kv_num(w, "host_c_seconds", hsum > 0 ? hsum : NAN);
    jw_kv_num(w, "points", pts);
    jw_kv_num(w, "device_points_per_s", dsum > 0 ? pts / dsum : NAN);
    jw_kv_num(w, "host_c_points_per_s", hsum > 0 ? pts / hsum : NAN);
    jw_ratio(w, "speedup_vs_host_c", ratio(hsum, dsum), "no model was timed on both sides");
    jw_kv_num(w, "agreement_max_rel_diff", agree);
    jw_kv_str(w, "agreement_what", "largest relative difference between the device's and C's per-n maxima, "
                                   "relative to at least 1e-4 (their sample cosines differ by float rounding), "
                                   "over the models but those in agreement_excludes (a second formula of a "
                                   "reference lobe, such as phongpow); every model's own figure is in models");
    jw_kv_arr(w, "agreement_excludes");
    for (int k = 0; k < r->nsw; ++k)
        if (sweep_alternative(r->sw[k].label))
            jw_str(w, r->sw[k].label);
    jw_arr_end(w);
    json_sweep_models(w, r);
}

/* The per-launch rates of a figure's timed launches, in the order they ran (NAN for a launch
   with no time), into rates; their count (0 for a failed figure). */
static int launch_rates(const struct tp_figure *f, double rates[TP_MAX_REPS])
{
    for (int k = 0; f->ok && k < f->nreps; ++k)
        rates[k] = f->rep_seconds[k] > 0 ? f->per_launch / f->rep_seconds[k] : NAN;
    return f->ok ? f->nreps : 0;
}

/* A timed rate as a metric: the median over the launches, its min..max and every launch's
   rate (the rank test of compare reads these). */
static struct rd_metric *rate_metric(struct rdoc *d, struct rd_row *row, const char *name, const char *unit,
                                     const struct tp_figure *f, struct tp_stats s)
{
    double rates[TP_MAX_REPS];
    struct rd_metric *m = rd_row_metric(d, row, name, unit, RD_HIGHER, 1, s.median);
    if (!m)
        return NULL;
    m->lo = s.min;
    m->hi = s.max;
    rd_metric_reps(d, m, rates, launch_rates(f, rates));
    return m;
}

/* A sweep time's rate: the model's points over each timed run (the fastest run the largest). */
static struct rd_metric *sweep_rate(struct rdoc *d, struct rd_row *row, const char *name, double points,
                                    struct tp_stats s, int ok)
{
    struct rd_metric *m = rd_row_metric(d, row, name, "1/s", RD_HIGHER, 1, ok ? points / s.median : NAN);
    if (m && ok) {
        m->lo = points / s.max;
        m->hi = points / s.min;
    }
    return m;
}

/* The run's rows (rdoc.h): the peak kernel's (its reference), then one per measured model,
   build variant and n mode, in the order of "results", then one per model of the accuracy
   sweep; the run's settings and machine record as context lines. What compare, gate
   --baseline, plot and rows read, and what the throughput page is drawn from
   (report_throughput.h lists what it takes). */
static void tp_rows(const struct tp_run *r, char hex[][24], struct rdoc *d)
{
    const struct throughput_options *o = r->o;
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "%g reps, min time %g s, %g work-items, n %g, n range %g:%g", (double)o->reps,
             o->min_time, (double)r->work_items, (double)(float)o->n_uniform, o->n_lo, o->n_hi);
    rd_ctx_put(&d->ctx, "throughput settings", buf);
    snprintf(buf, sizeof buf, "load %s -> %s, steal %.3g s, %g of %g launches retried, %g reps disturbed",
             r->load_start, r->load_end, r->steal_start >= 0 && r->steal_end >= 0 ? r->steal_end - r->steal_start : NAN,
             (double)r->retried, (double)r->launches, (double)r->disturbed);
    rd_ctx_put(&d->ctx, "machine", buf);
    d->disturbed = r->disturbed > 0 ? (int)r->disturbed : 0;
    buf[0] = '\0';
    for (size_t i = 0; i < FINGERPRINTED; ++i)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s %.8s", i ? ", " : "", fingerprinted[i], hex[i]);
    rd_ctx_put(&d->ctx, "kernel sources", buf);
    /* the page's words: the launches behind each median, the C loop's threads (the machine's
       online CPUs unless --threads says), the sweep's grid and why it measured nothing */
    rdoc_textf(d, "reps", "%d", o->reps);
    rdoc_textf(d, "tuned_c_threads", "%d", r->threads);
    if (r->sweep_ran)
        rdoc_textf(d, "sweep_grid", "n %g..%g step %g, %ld samples per zone", o->sweep_grid.n_min,
                   o->sweep_grid.n_max, o->sweep_grid.n_step, o->sweep_grid.samples);
    if (r->sweep_ran && r->sweep_reason[0])
        rdoc_text(d, "sweep_reason", r->sweep_reason);

    struct rd_row *row = rdoc_row(d, "", "peak");
    if (!row)
        return;
    rd_row_key(row, "reference", NULL, "peak (reference kernel)");
    if (!r->peak.ok)
        rd_row_fail(row, "failed", r->peak.reason);
    rate_metric(d, row, "flops_per_s", "FLOP/s", &r->peak, r->peak.rate);

    for (int v = 0, i = 0, m = -1; next_measured(r, &v, &i, &m);) {
        const struct tp_entry *e = &r->e[i];
        const struct tp_figure *f = &e->dev[v][m];
        if (!(row = rdoc_row(d, "", e->label)))
            return;
        rd_row_key(row, "label", NULL, e->label);
        rd_row_key(row, "variant", NULL, tp_variant_name(v));
        rd_row_key(row, "n_mode", "n ", nmode_names[m]);
        rd_row_attr(row, "kind", e->m ? "model" : "builtin");
        if (e->ref_entry >= 0)   /* the model's own reference, measured in this run */
            rd_row_attr(row, "model_reference", r->e[e->ref_entry].label);
        if (!f->ok)
            rd_row_fail(row, "failed", f->reason);
        struct rd_metric *mt = rate_metric(d, row, "evals_per_s", "1/s", f,
                                           f->ok ? f->rate : (struct tp_stats){ NAN, NAN, NAN });
        /* normalised per CPU second where the runner kept them (a CPU device), else per the
           reference's rate */
        if (mt && f->ok && f->has_cpu_norm)
            rd_metric_normalised(d, mt, f->rep_cpu_norm, f->nreps, 1);
        else if (mt && f->ok && f->has_norm)
            rd_metric_normalised(d, mt, f->rep_norm, f->nreps, 0);
        /* the tuned C loop doing the same evaluations: timed beside the default variant */
        const struct tp_figure *c = &e->hostc[m];
        if (v == TP_VARIANT_DEFAULT && o->host_c && c->ok) {
            struct rd_metric *cm = rate_metric(d, row, "host_c.evals_per_s", "1/s", c, c->rate);
            if (cm && c->has_cpu_norm)
                rd_metric_normalised(d, cm, c->rep_cpu_norm, c->nreps, 1);
            else if (cm && c->has_norm)
                rd_metric_normalised(d, cm, c->rep_norm, c->nreps, 0);
        }
        if (e->acc_ok[v])
            rd_row_metric(d, row, "accuracy.max_diff_of_peak", "1", RD_NEITHER, 0, e->acc_max_diff[v]);
        if (e->acc_nonfinite[v] > 0)
            rd_row_metric(d, row, "accuracy.nonfinite", "1", RD_NEITHER, 0, (double)e->acc_nonfinite[v]);
        if (f->ok && !f->finite)
            rd_row_text(d, row, "note", "some values were NaN or Inf under these build options (their sum is not "
                                        "finite); the rate is the rate of that code");
        if (v == TP_VARIANT_DEFAULT && o->host_c && c->checked && !c->ok)
            rd_row_text(d, row, "host_c_reason", c->reason);
        row->retries = f->retries > 0 ? f->retries : 0;
        row->disturbed = f->disturbed > 0 ? f->disturbed : 0;
    }
    for (int k = 0; r->sweep_ran && k < r->nsw; ++k) {
        const struct tp_sweep_model *s = &r->sw[k];
        if (!(row = rdoc_row(d, "", s->label)))
            return;
        rd_row_key(row, "label", NULL, s->label);
        rd_row_key(row, "sweep", NULL, "accuracy sweep");
        if (!s->ok)
            rd_row_fail(row, "failed", s->reason);
        rd_row_metric(d, row, "points", "1", RD_NEITHER, 0, s->points);
        sweep_rate(d, row, "device_points_per_s", s->points, s->dev_s, s->ok);
        sweep_rate(d, row, "host_c_points_per_s", s->points, s->hostc_s, s->ok);
    }
}

/* The run's rows (tp_rows), or NULL with "out of memory" in err. */
struct rdoc *tp_rows_new(const struct tp_run *r, char *err, size_t errlen)
{
    char hex[FINGERPRINTED][24];
    for (size_t i = 0; i < FINGERPRINTED; ++i)
        kernel_fingerprint(fingerprinted[i], hex[i]);
    struct rdoc *d = rdoc_new(THROUGHPUT_SCHEMA, "throughput", "throughput.json", err, errlen);
    if (!d)
        return NULL;
    tp_rows(r, hex, d);
    return rdoc_built(d, err, errlen) ? NULL : d;
}

int tp_write_json(const struct tp_run *r, const struct rdoc *d, const char *path, char *err, size_t errlen)
{
    char hex[FINGERPRINTED][24];
    for (size_t i = 0; i < FINGERPRINTED; ++i)
        kernel_fingerprint(fingerprinted[i], hex[i]);
    struct jw w;
    jw_doc_begin(&w, THROUGHPUT_SCHEMA, r->s, r->options[TP_VARIANT_DEFAULT]);
    json_context(&w, r, hex);

    jw_kv_texts(&w, "definitions", JW_TEXTS(tp_definitions));

    json_builds(&w, r);
    json_peak(&w, r);
    jw_kv_arr(&w, "results");
    for (int v = 0, i = 0, m = -1; next_measured(r, &v, &i, &m);)
        json_result(&w, r, v, i, m);
    jw_arr_end(&w);

    jw_kv_obj(&w, "sweep");
    if (!r->sweep_ran)
        jw_kv_str(&w, "status", "not run");
    else
        json_sweep_ran(&w, r);
    jw_obj_end(&w);
    rdoc_json_rows_member(&w, d);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

/* A number for CSV: empty when missing. */
static void tx_num(struct md_buf *t, double v)
{
    if (isfinite(v))
        md_printf(t, ",%.6g", v);
    else
        md_printf(t, ",");
}

int tp_write_csv(const struct tp_run *r, const char *path, char *err, size_t errlen)
{
    struct md_buf t;
    md_init(&t);
    md_printf(&t, "model,label,variant,build_options,n_mode,status,evals_per_s_min,evals_per_s_median,"
                  "evals_per_s_max,evals_per_s_wall_median,ratio_to_reference,ratio_to_model_reference,"
                  "ratio_to_host_c,fraction_of_peak,host_c_evals_per_s_median,max_diff_of_peak,reason\n");
    for (int v = 0, i = 0, m = -1; next_measured(r, &v, &i, &m);) {
        const struct tp_entry *e = &r->e[i];
        const struct tp_figure *f = &e->dev[v][m];
        struct tp_ratios q = ratios_of(r, i, v, m);
        md_printf(&t, "\"%s\",\"%s\",\"%s\",\"%s\",\"%s\",\"%s\"", e->m ? e->m->info->id : "pow", e->label,
                  tp_variant_name(v), r->options[v], nmode_names[m], f->ok ? "ok" : "failed");
        tx_num(&t, f->ok ? f->rate.min : NAN);
        tx_num(&t, f->ok ? f->rate.median : NAN);
        tx_num(&t, f->ok ? f->rate.max : NAN);
        tx_num(&t, f->ok ? f->rate_wall.median : NAN);
        tx_num(&t, q.to_reference);
        tx_num(&t, q.to_model_reference);
        tx_num(&t, q.to_host_c);
        tx_num(&t, q.of_peak);
        tx_num(&t, e->hostc[m].ok ? e->hostc[m].rate.median : NAN);
        tx_num(&t, e->acc_max_diff[v]);
        /* reasons never hold a double quote: they are written by this program */
        md_printf(&t, ",\"%s\"\n", f->ok ? "" : f->reason);
    }
    return md_write_file_free(&t, path, err, errlen);
}

char *tp_tables_text(const struct rdoc *d, int md)
{
    struct md_buf t;
    md_init(&t);
    if (report_throughput_page(&t, d, md)) {
        md_free(&t);
        return NULL;
    }
    return t.s ? t.s : calloc(1, 1);
}
