/* test_throughput.c - nothing is timed that is not the real model:
 *   - the throughput kernels' point form (tp_points_X, model id a compile-time constant) gives
 *     the values of the accuracy kernels' probe (runtime id) and of the double reference;
 *   - the timed kernels' sums (tp_uniform_X, tp_varying_X) equal the sum of the double
 *     reference over the inputs they generate, regenerated here one by one (tp_input_at);
 *   - the tuned C baseline's sums equal the same double sums, the device's on a small launch
 *     (tp_check_host_c, the check before a "x tuned C" ratio), and fvol and fq2 written here;
 *   - the C sweep reports the device sweep's per-n maxima;
 *   - a whole run on a tiny configuration writes a throughput.json with every figure finite.
 * Expected values come from the double-precision host reference (model_eval_host, pow); no
 * test asserts a time. */
#include "accuracy.h"
#include "check.h"
#include "clsession.h"
#include "exitcodes.h"
#include "hostc_baseline.h"
#include "jsonr.h"
#include "models.h"
#include "throughput.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define POINTS 512

/* Probe points: half in the epicentre, half out to 4 x_e, n in [2, 1000]. */
static void points(float *c, float *n, int count)
{
    for (int i = 0; i < count; ++i) {
        double nv = 2.0 + 998.0 * (double)((i * 37) % count) / (double)count;
        double x_e = zone_epicentre_end(nv), u = (double)((i * 11) % 97) / 96.0;
        double x = (i % 2 == 0) ? u * x_e : fmin(M_PI / 2, x_e + u * 3.0 * x_e);
        c[i] = (float)cos(x);
        n[i] = (float)nv;
    }
}

/* The models of the test: the default set, plus the fitted family with non-default parameters. */
static int test_models(struct model_spec *out, int max)
{
    int count = model_spec_list_default(out, max - 2);
    out[count++] = spec("quad:a=0.45,b=0.2");
    out[count++] = spec("lyon:k=4");
    return count;
}

static double ref_peak(const struct model_spec *m, double n)
{
    struct model_spec ref;
    model_reference_spec(m, &ref);
    double p = fabs(model_eval_host(&ref, 1.0, n));
    return p > 0 ? p : 1.0;
}

static void test_points(struct tp_program *p, struct accuracy_ctx *a, const struct model_spec *models, int count)
{
    float c[POINTS], n[POINTS], tp[POINTS], acc[POINTS];
    points(c, n, POINTS);
    for (int k = 0; k < count; ++k) {
        const struct model_spec *m = &models[k];
        if (tp_program_points(p, m, c, n, POINTS, tp) || accuracy_probe(a, m, c, n, POINTS, acc)) {
            CHECK(0, "%s: points kernels ran", m->label);
            continue;
        }
        double worst_acc = 0, worst_ref = 0;
        for (int i = 0; i < POINTS; ++i) {
            double peak = ref_peak(m, n[i]);
            double d_acc = fabs((double)tp[i] - (double)acc[i]) / peak;
            double d_ref = fabs((double)tp[i] - model_eval_host(m, c[i], n[i])) / peak;
            /* a NaN stays the worst value: a later finite difference must not replace it */
            if (!isnan(worst_acc) && !(d_acc <= worst_acc)) worst_acc = d_acc;
            if (!isnan(worst_ref) && !(d_ref <= worst_ref)) worst_ref = d_ref;
        }
        /* The same float formula in both kernels: at most a few roundings apart (fused or not). */
        CHECK(worst_acc <= 1e-6, "%s: throughput vs accuracy kernel differ by %.3g of the peak", m->label, worst_acc);
        /* Float against double: the accuracy check of the sweep sees at most ~3e-7 of the
           peak for these models (lyon's squarings are the worst); 2e-6 leaves room. */
        CHECK(worst_ref <= 2e-6, "%s: throughput kernel vs double reference %.3g of the peak", m->label, worst_ref);
    }
    /* The pow() built-in against pow in double, relative to 1 (the lobe's peak). */
    if (tp_program_points(p, NULL, c, n, POINTS, tp) == 0) {
        double worst = 0;
        for (int i = 0; i < POINTS; ++i) {
            /* not fmax, which drops a NaN: a NaN must fail the check below */
            double d = fabs((double)tp[i] - pow((double)c[i], (double)n[i]));
            if (!isnan(worst) && !(d <= worst)) worst = d;
        }
        CHECK(worst <= 2e-6, "pow() built-in vs double pow: %.3g", worst);
    } else {
        CHECK(0, "pow points kernel ran");
    }
}

/* The sum of the double reference over every input a launch generates. */
static double reference_sum(const struct model_spec *m, const struct tp_inputs *in, double *abs_sum)
{
    double s = 0, a = 0;
    for (long g = 0; g < in->work_items; ++g)
        for (long i = 0; i < in->iters; ++i)
            for (int u = 0; u < TP_STREAMS; ++u)
                for (int l = 0; l < 16; ++l) {
                    float c, n;
                    tp_input_at(in, g, i, u, l, &c, &n);
                    double v = m ? model_eval_host(m, c, n) : pow((double)c, (double)n);
                    s += v;
                    a += fabs(v);
                }
    *abs_sum = a;
    return s;
}

static void test_sums(struct tp_program *p, const struct model_spec *models, int count)
{
    double worst_rel = 0;
    struct throughput_options o;
    throughput_options_default(&o);
    /* small n, so that most inputs fall inside every lobe and the sums are made of real values */
    o.n_uniform = 5;
    o.n_lo = 2;
    o.n_hi = 12;
    const long work_items = 3, iters = 7;
    float dev[3 * 16], host[3 * 16];
    for (int k = -1; k < count; ++k) {
        const struct model_spec *m = k < 0 ? NULL : &models[k];
        const char *label = m ? m->label : "pow";
        for (int mode = 0; mode < TP_NMODE_COUNT; ++mode) {
            struct tp_inputs in;
            tp_inputs_for(&o, mode, work_items, iters, &in);
            double abs_sum, expect = reference_sum(m, &in, &abs_sum);
            /* Each value is off from double by at most 2e-6 of its reference lobe's peak (see
               test_points; near a quadratic's root that is a large part of a tiny value), and
               the float sums add ~iters roundings of their size: both bounds together. */
            double peak = m ? fmax(ref_peak(m, o.n_hi), ref_peak(m, o.n_lo)) : 1.0;
            double tol = 1e-5 * abs_sum + 2e-6 * peak * (double)(work_items * iters * TP_EVALS_PER_ITER);
            double t;
            if (tp_program_launch(p, m, mode, &o, work_items, iters, dev, &t)) {
                CHECK(0, "%s %s: timed kernel ran", label, tp_nmode_name(mode));
            } else {
                double s = 0;
                for (int i = 0; i < 3 * 16; ++i)
                    s += dev[i];
                CHECK(fabs(s - expect) <= tol, "%s %s: device sum %.9g, double reference %.9g (tol %.3g)", label,
                      tp_nmode_name(mode), s, expect, tol);
                worst_rel = fmax(worst_rel, fabs(s - expect) / fabs(expect));
            }
            char err[256];
            if (hostc_throughput(m ? m->info->kernel_id : -1, m ? (float)m->params[0] : 0,
                                 m ? (float)m->params[1] : 0, &in, 2, host, &t, err, sizeof err)) {
                CHECK(0, "%s: C baseline ran: %s", label, err);
            } else {
                double s = 0;
                for (int i = 0; i < 3 * 16; ++i)
                    s += host[i];
                CHECK(fabs(s - expect) <= tol, "%s %s: C sum %.9g, double reference %.9g", label, tp_nmode_name(mode),
                      s, expect);
            }
        }
    }
    printf("largest relative difference of a timed kernel's sum from the double reference: %.3g\n", worst_rel);
}

/* The C baseline's sums check (tp_check_host_c, which decides whether a "x tuned C" ratio is
   printed): on a small launch of every model the device's sums and the C loop's agree; and a few
   of the C loop's lane sums equal fvol and fq2 evaluated here, from their definitions
   (docs/definitions.md: (0.463 n (c - 1) + 1)^2 and ((0.448 n + 0.099)(c - 1) + 1)^2, zeroed
   where the base is <= 0), at inputs generated here from the kernel's rules
   (kernels/throughput.cl: c = ((16 u + lane) + phase) dc, phase = (gid mod 64)/64, then
   c += 64 dc per iteration; dc = 1 / (64 iters)). */
static double written_fvol(double c, double n)
{
    double b = 0.463 * n * (c - 1.0) + 1.0;
    return b > 0 ? b * b : 0.0;
}
static double written_fq2(double c, double n)
{
    double b = (0.448 * n + 0.099) * (c - 1.0) + 1.0;
    return b > 0 ? b * b : 0.0;
}

static void test_c_sums_check(struct tp_program *p, const struct model_spec *models, int count)
{
    struct throughput_options o;
    throughput_options_default(&o);
    const long work_items = 5;
    for (int k = -1; k < count; ++k) {
        const struct model_spec *m = k < 0 ? NULL : &models[k];
        for (int mode = 0; mode < TP_NMODE_COUNT; ++mode) {
            struct tp_sums_check chk;
            char err[256];
            if (tp_check_host_c(p, m, mode, &o, work_items, 2, &chk, err, sizeof err)) {
                CHECK(0, "%s: sums check ran: %s", m ? m->label : "pow", err);
                continue;
            }
            CHECK(chk.agree && chk.iters == TP_CHECK_ITERS, "%s %s: device sum %.9g, C sum %.9g (rel %.3g)",
                  m ? m->label : "pow", tp_nmode_name(mode), chk.device_sum, chk.c_sum, chk.rel_diff);
        }
    }
    /* a few lanes of the C loop against the formulas written above, uniform n = 5 (a wide lobe:
       most of the 64 values of a lane are inside it) */
    const char *names[2] = { "fvol", "fq2" };
    for (int f = 0; f < 2; ++f) {
        struct model_spec m = spec(names[f]);
        const long iters = TP_CHECK_ITERS, items = 3;
        const double n = 5.0;
        const float dc = (float)(1.0 / (64.0 * (double)iters));
        struct tp_inputs in = { .varying = 0, .n_uniform = (float)n, .dc = dc, .iters = iters, .work_items = items };
        float sums[3 * 16];
        double t;
        char err[256];
        if (hostc_throughput(m.info->kernel_id, 0, 0, &in, 1, sums, &t, err, sizeof err)) {
            CHECK(0, "%s: C loop ran: %s", names[f], err);
            continue;
        }
        for (long g = 0; g < items; ++g)
            for (int lane = 0; lane < 16; lane += 5) {
                double expect = 0;
                for (int u = 0; u < TP_STREAMS; ++u) {
                    /* the float steps as the kernel takes them (the start is exact; each step rounds) */
                    float c = ((float)(16 * u + lane) + (float)(g % 64) / 64.0f) * dc;
                    for (long i = 0; i < iters; ++i, c += 64.0f * dc)
                        expect += f == 0 ? written_fvol(c, n) : written_fq2(c, n);
                }
                /* 64 float values in [0, 1], each within a few ulp of its double, summed in float:
                   64 roundings of at most 2^-24 of the sum each, 1e-5 of it leaves room */
                CHECK(fabs((double)sums[g * 16 + lane] - expect) <= 1e-5 * expect && expect > 1.0, "%s lane sum, work-item %ld lane %d: C %.9g, "
                      "written here %.9g", names[f], g, lane, sums[g * 16 + lane], expect);
            }
    }
}

/* The C sweep does the sweep's work: each per-n figure it reports is the model's error in
   double at the cosine it reports, and it is the device's figure up to where the two sides'
   samples fall (their cos implementations round differently; at a zone end the error is steep
   in c, so 1e-3 relative). Invalid counts are equal. */
static void test_sweep(struct accuracy_ctx *a)
{
    const char *names[] = { "fvol", "fq2n", "lyon:k=3", "ggx" };
    struct accuracy_grid g = { 2, 300, 37, 256 };
    long count = accuracy_grid_count(&g);
    float nv[16], dev[16 * 8], host[16 * 8];
    for (long i = 0; i < count; ++i)
        nv[i] = (float)accuracy_grid_n(&g, i);
    for (int k = 0; k < 4; ++k) {
        struct model_spec m = spec(names[k]), ref;
        model_reference_spec(&m, &ref);
        double t;
        char err[256];
        if (accuracy_sweep_device(a, &m, &g, dev, &t) ||
            hostc_sweep(m.info->kernel_id, (float)m.params[0], (float)m.params[1], ref.info->kernel_id,
                        (float)ref.params[0], (float)ref.params[1], nv, count, g.samples, 2, host, &t, err,
                        sizeof err)) {
            CHECK(0, "%s: sweeps ran", names[k]);
            continue;
        }
        for (long i = 0; i < count; ++i) {
            const float *h = host + i * 8;
            double n = nv[i];
            /* float against double at the same input: a few roundings of the lobe's peak */
            double tol = 2e-6 * fmax(1.0, ref_peak(&m, n));
            /* the sweep reports where each figure occurs as s = 1 - cos x (kernels/accuracy.cl) */
            CHECK_NEAR(h[0], error_rel_host(&m, &ref, 1.0 - h[1], n), 2e-6, "C epicentre delta at its s");
            CHECK_NEAR(h[2], error_abs_host(&m, &ref, 1.0 - h[3], n), tol, "C attenuation Delta at its s");
            CHECK_NEAR(h[4], error_abs_host(&m, &ref, 1.0 - h[5], n), tol, "C epicentre Delta at its s");
            for (int q = 0; q < 6; q += 2) {
                double d = fabs((double)dev[i * 8 + q] - (double)h[q]);
                CHECK(d <= 1e-3 * fabs((double)dev[i * 8 + q]) + 1e-9, "%s n=%g figure %d: device %.9g, C %.9g",
                      names[k], n, q, dev[i * 8 + q], h[q]);
            }
            CHECK(dev[i * 8 + 6] == h[6], "%s n=%g: invalid counts %g vs %g", names[k], n, dev[i * 8 + 6], h[6]);
        }
    }
}

/* A whole run on a tiny configuration: well-formed JSON, every figure finite. */
static void test_run(struct cl_session *s)
{
    struct throughput_options o;
    throughput_options_default(&o);
    o.models[0] = spec("fvol");
    o.models[1] = spec("phong");
    o.models[2] = spec("beckmann");
    o.model_count = 3;
    o.reps = 2;
    o.min_time = 0.002;
    o.work_items = 4;
    o.sweep_grid = (struct accuracy_grid){ 2, 50, 16, 64 };
    o.sweep_reps = 1;
    char dir[512];
    if (test_tmpdir_make(dir, sizeof dir, "test_throughput") != 0) {
        CHECK(0, "mkdtemp");
        return;
    }
    o.io = (struct engine_io){ dir, 1 };
    struct throughput_result tr = { 0 };
    int rc = throughput_run(s, &o, &tr);
    CHECK(rc == 0, "throughput_run returned %d", rc);
    CHECK(tr.markdown && strstr(tr.markdown, "| fvol | uniform |"), "markdown table has the fvol row");
    throughput_result_free(&tr);
    char path[600], err[1024];
    snprintf(path, sizeof path, "%s/throughput.json", dir);
    struct jr_doc d;
    if (jr_parse_file(path, &d, err, sizeof err)) {
        CHECK(0, "throughput.json parses strictly: %s", err);
        test_tmpdir_done(dir);
        return;
    }
    const char *schema = NULL;
    CHECK(jr_need_str(&d, &d.root, "schema", &schema, err, sizeof err) == 0 && strcmp(schema, THROUGHPUT_SCHEMA) == 0,
          "schema");
    const struct jr_value *ctx = jr_get(&d.root, "context"), *res = jr_get(&d.root, "results");
    CHECK(ctx && jr_get(ctx, "device") && jr_get(ctx, "platform_version") && jr_get(ctx, "git_revision"),
          "context block");
    /* 1 built-in + 3 models; default: 2 n modes, other two variants: uniform only */
    CHECK(res && res->type == JR_ARR && res->count == 4 * 2 + 4 * 1 * 2, "results rows: %zu",
          res ? res->count : (size_t)0);
    for (size_t i = 0; res && i < res->count; ++i) {
        const struct jr_value *row = &res->items[i];
        const char *label = "", *status = "", *variant = "";
        jr_need_str(&d, row, "label", &label, err, sizeof err);
        jr_need_str(&d, row, "status", &status, err, sizeof err);
        jr_need_str(&d, row, "variant", &variant, err, sizeof err);
        CHECK(strcmp(status, "ok") == 0, "%s %s: status %s", label, variant, status);
        const struct jr_value *ev = jr_get(row, "evals_per_s");
        double med = NAN, lo = NAN, hi = NAN, rref = NAN, peak = NAN, rc_ = NAN;
        if (ev) {
            jr_need_num(&d, ev, "median", &med, err, sizeof err);
            jr_need_num(&d, ev, "min", &lo, err, sizeof err);
            jr_need_num(&d, ev, "max", &hi, err, sizeof err);
        }
        CHECK(med > 0 && lo <= med && med <= hi && isfinite(hi), "%s %s: rates %g <= %g <= %g", label, variant, lo,
              med, hi);
        jr_need_num(&d, row, "ratio_to_reference", &rref, err, sizeof err);
        jr_need_num(&d, row, "fraction_of_peak", &peak, err, sizeof err);
        CHECK(rref > 0 && isfinite(rref) && peak > 0 && isfinite(peak), "%s %s: ratios finite", label, variant);
        if (strcmp(variant, "default") == 0) {
            jr_need_num(&d, row, "ratio_to_host_c", &rc_, err, sizeof err);
            CHECK(rc_ > 0 && isfinite(rc_), "%s: ratio to C finite", label);
        }
        const struct jr_value *acc = jr_get(row, "accuracy");
        double diff = NAN;
        if (acc)
            jr_need_num(&d, acc, "max_diff_of_peak", &diff, err, sizeof err);
        /* the default build: as test_points; the others may relax accuracy, but not to garbage */
        CHECK(isfinite(diff) && diff < (strcmp(variant, "default") == 0 ? 2e-6 : 1e-3), "%s %s: accuracy %g", label,
              variant, diff);
    }
    const struct jr_value *sw = jr_get(&d.root, "sweep");
    double speedup = NAN, agree = NAN;
    if (sw) {
        jr_need_num(&d, sw, "speedup_vs_host_c", &speedup, err, sizeof err);
        jr_need_num(&d, sw, "agreement_max_rel_diff", &agree, err, sizeof err);
    }
    CHECK(speedup > 0 && isfinite(speedup), "sweep ratio finite (%g)", speedup);
    CHECK(agree <= 1e-3, "device and C sweeps agree (%g)", agree);
    jr_free(&d);
    snprintf(path, sizeof path, "%s/throughput.csv", dir);
    FILE *f = fopen(path, "r");
    char line[1024] = "";
    int lines = 0;
    if (f) {
        if (fgets(line, sizeof line, f))
            ++lines;
        CHECK(strncmp(line, "model,label,variant,", 20) == 0, "csv header");
        while (fgets(line, sizeof line, f))
            ++lines;
        fclose(f);
    }
    CHECK(lines == 1 + 16, "csv has a header and 16 rows (%d lines)", lines);
    test_tmpdir_done(dir);
}

/* The generator's inputs, worked by hand for the first evaluations of a launch. */
static void test_inputs(void)
{
    struct throughput_options o;
    throughput_options_default(&o);   /* n uniform 100, varying over [2, 1000] */
    struct tp_inputs in;
    tp_inputs_for(&o, TP_N_VARYING, 2, 4, &in);
    float c, n;
    tp_input_at(&in, 0, 0, 0, 0, &c, &n);
    CHECK(c == 0.0f && n == 2.0f, "first input: c = 0, n = n_lo (got %g, %g)", c, n);
    /* stream 1, lane 3 of work-item 0: index 19 of 64 per iteration, dc = 1/(64 x 4) */
    tp_input_at(&in, 0, 0, 1, 3, &c, &n);
    CHECK_NEAR(c, 19.0 / 256.0, 1e-7, "c of index 19");
    CHECK_NEAR(n, 2.0 + 19.0 * 998.0 / 64.0, 1e-4, "n of index 19");
    /* the last iteration of the last lane stays below c = 1 and n = n_hi */
    tp_input_at(&in, 1, 3, 3, 15, &c, &n);
    CHECK(c < 1.0f && n <= 1000.0f + 1e-3f, "last input inside the ranges (c %g, n %g)", c, n);
    tp_inputs_for(&o, TP_N_UNIFORM, 2, 4, &in);
    tp_input_at(&in, 1, 2, 2, 5, &c, &n);
    CHECK(n == 100.0f, "uniform n is n (got %g)", n);
}

int main(void)
{
    test_inputs();
    struct cl_session s;
    char err[512];
    int rc = clsession_open(&s, -1, -1, err, sizeof err);
    if (rc) {
        fprintf(stderr, "%s\n", err);
        check_summary();
        /* test_inputs ran on the host: its failure is not hidden by the skip */
        return check_failed ? 1 : rc == EXIT_NO_DEVICE ? 77 : rc;
    }
    struct model_spec models[TP_MAX_MODELS];
    int count = test_models(models, TP_MAX_MODELS);
    struct tp_program p;
    struct accuracy_ctx a;
    if (tp_program_build(&p, &s, models, count, TP_VARIANT_DEFAULT, NULL) || accuracy_open(&a, &s, "")) {
        CHECK(0, "programs build");
        clsession_close(&s);
        return check_summary();
    }
    test_points(&p, &a, models, count);
    test_sums(&p, models, count);
    test_c_sums_check(&p, models, count);
    test_sweep(&a);
    tp_program_release(&p);
    accuracy_close(&a);
    test_run(&s);
    clsession_close(&s);
    return check_summary();
}
