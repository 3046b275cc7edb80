/* reproduce.c - the claims of both papers, re-derived and given verdicts (see reproduce.h). */
#include "reproduce.h"
#include "reproduce_claims.h"
#include "reproduce_report.h"
#include "accuracy.h"
#include "context.h"
#include "energy.h"
#include "exitcodes.h"
#include "fit.h"
#include "models.h"
#include "outdir.h"
#include "refine.h"
#include "room.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void reproduce_options_default(struct reproduce_options *o)
{
    memset(o, 0, sizeof *o);
    o->samples = ACC_DEFAULT_SAMPLES;
    o->grid_check = 1;
    o->q_min = 0.01;
    o->q_max = 0.99;
    o->q_step = 0.01;
    o->q_samples = 1024;
    o->q_n_step = 1.0;
    o->energy = 1;
    o->physical = 1;
}

int reproduce_options_check(const struct reproduce_options *o, char *err, size_t errlen)
{
    struct accuracy_grid g = { 2, 1000, 1, o->samples }, q = { 2, 1000, o->q_n_step, o->q_samples };
    if (accuracy_grid_check(&g, NULL, err, errlen))
        return EXIT_USAGE;
    if (accuracy_grid_check(&q, NULL, err, errlen)) {
        /* name the Q sweep's own flags */
        char inner[512];
        snprintf(inner, sizeof inner, "%s", err);
        snprintf(err, errlen, "Q sweep: %s (flags --q-samples, --q-n-step)", inner);
        return EXIT_USAGE;
    }
    if (!(o->q_min > 0 && o->q_max < 1 && o->q_min <= o->q_max && o->q_step > 0) ||
        (o->q_max - o->q_min) / o->q_step > 10000) {
        snprintf(err, errlen, "--q-min/--q-max/--q-step: need 0 < q-min <= q-max < 1 and at most 10000 steps "
                              "(got %g, %g, %g)", o->q_min, o->q_max, o->q_step);
        return EXIT_USAGE;
    }
    return 0;
}

/* ---- a claim row and its verdict --------------------------------------------------------------- */

struct claim *claim_add(struct reproduce_report *r, const char *kind, const char *id, const char *source,
                        const char *text)
{
    struct claim *rows = room_for_one(r->rows, r->count, &r->cap, sizeof *rows, 64);
    if (!rows)
        return NULL;
    r->rows = rows;
    struct claim *c = &r->rows[r->count++];
    memset(c, 0, sizeof *c);
    snprintf(c->kind, sizeof c->kind, "%s", kind);
    snprintf(c->id, sizeof c->id, "%s", id);
    snprintf(c->source, sizeof c->source, "%s", source);
    snprintf(c->text, sizeof c->text, "%s", text);
    c->claimed = c->measured = NAN;
    return c;
}

void setf(char *dst, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, len, fmt, ap);
    va_end(ap);
}

void note_add(struct claim *c, const char *fmt, ...)
{
    size_t used = strlen(c->note);
    if (used + 1 >= sizeof c->note)
        return;
    if (used > 0) {
        c->note[used++] = ' ';
        c->note[used] = '\0';
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->note + used, sizeof c->note - used, fmt, ap);
    va_end(ap);
}

/* A numeric claim with a tolerance: reproduced when |measured - claimed| <= tol (a hair of
 * relative slack so a value exactly at the bound is not lost to rounding). */
void claim_number(struct claim *c, const char *claimed_text, double claimed, double measured, double tol,
                  const char *tol_text)
{
    snprintf(c->claimed_text, sizeof c->claimed_text, "%s", claimed_text);
    c->claimed = claimed;
    c->measured = measured;
    snprintf(c->tolerance, sizeof c->tolerance, "%s", tol_text);
    c->reproduced = isfinite(measured) && fabs(measured - claimed) <= tol * (1 + 1e-9) + 1e-15;
    /* For a printed number, say whether the paper rounded or truncated the measured value. */
    if (c->reproduced && strstr(tol_text, "last printed digit")) {
        double rounded = round(measured / tol) * tol, cut = trunc(measured / tol) * tol;
        if (fabs(rounded - claimed) < 1e-3 * tol)
            note_add(c, "The measured value rounds to the printed one.");
        else if (fabs(cut - claimed) < 1e-3 * tol)
            note_add(c, "The printed value is the measured one truncated, not rounded.");
    }
}

void claim_bool(struct claim *c, const char *claimed_text, int holds, const char *tol_text)
{
    snprintf(c->claimed_text, sizeof c->claimed_text, "%s", claimed_text);
    snprintf(c->tolerance, sizeof c->tolerance, "%s", tol_text);
    c->reproduced = holds;
}

/* ---- the run ------------------------------------------------------------------------------ */

static const struct {
    const char *model;
    double n_min;
} sweep_defs[SW_COUNT] = {
    [SW_FVOL] = { "fvol", 16 }, [SW_FVOL64] = { "fvol64", 16 }, [SW_CQ2_P1] = { "cq2", 16 },
    [SW_SCHLICK] = { "schlick", 16 }, [SW_FQ] = { "fq:Q=0.64", 2 }, [SW_FQ2] = { "fq2", 2 }, [SW_CQ2_P2] = { "cq2", 2 },
};

static int sweep_run(struct repro *p, const char *text, double n_min, long samples, struct accuracy_result *out)
{
    char err[512];
    struct model_spec m;
    if (model_spec_parse(text, &m, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_RUNTIME;
    }
    struct accuracy_grid g = { n_min, 1000.0, 1.0, samples };
    if (accuracy_grid_check(&g, p->s, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_USAGE;
    }
    return accuracy_run(&p->actx, &m, &g, out);
}

static int run_sweeps(struct repro *p)
{
    for (int i = 0; i < SW_COUNT; ++i) {
        int rc = sweep_run(p, sweep_defs[i].model, sweep_defs[i].n_min, p->o->samples, &p->sw[i]);
        if (rc)
            return rc;
        p->have_sw[i] = 1;
        p->grid_change[i] = NAN;
        long fine_samples = 2 * p->o->samples;
        if (p->o->grid_check && fine_samples <= ACC_MAX_SAMPLES) {
            struct accuracy_result fine;
            rc = sweep_run(p, sweep_defs[i].model, sweep_defs[i].n_min, fine_samples, &fine);
            if (rc)
                return rc;
            const struct accuracy_result *a = &p->sw[i];
            double ue = fourth_digit_unit(a->epicentre.value), ua = fourth_digit_unit(a->attenuation.value);
            double ce = ue > 0 ? fabs(fine.epicentre.value - a->epicentre.value) / ue : 0;
            double ca = ua > 0 ? fabs(fine.attenuation.value - a->attenuation.value) / ua : 0;
            p->grid_change[i] = fmax(ce, ca);
            accuracy_result_free(&fine);
        }
    }
    return 0;
}

/* A figure as q_sweep.json carries it: a value that is not finite is written as null, read as NaN. */
static double as_written(double v) { return isfinite(v) ? v : NAN; }

/* The Q sweep's figures for the report's caller (reproduce_report.q_sweep): the run's, or none
   (n 0) when there are none or more than RUN_MAX_Q. */
static void keep_q_sweep(const struct repro *p, struct run_q_sweep *out)
{
    out->n = 0;
    if (p->nq < 1 || p->nq > RUN_MAX_Q)
        return;
    for (int i = 0; i < p->nq; ++i) {
        out->q[i] = as_written(p->q[i]);
        out->max_rel[i] = as_written(p->q_rel[i]);
        out->max_abs[i] = as_written(p->q_abs[i]);
    }
    out->f2_max_rel = as_written(p->f2_rel);
    out->f2_max_abs = as_written(p->f2_abs);
    out->n = p->nq;
}

static int run_q_sweep(struct repro *p)
{
    const struct reproduce_options *o = p->o;
    int total = (int)floor((o->q_max - o->q_min) / o->q_step + 1e-9) + 1;
    p->q = calloc((size_t)total, sizeof *p->q);
    p->q_rel = calloc((size_t)total, sizeof *p->q_rel);
    p->q_rel_n = calloc((size_t)total, sizeof *p->q_rel_n);
    p->q_abs = calloc((size_t)total, sizeof *p->q_abs);
    p->q_att = calloc((size_t)total, sizeof *p->q_att);
    if (!p->q || !p->q_rel || !p->q_rel_n || !p->q_abs || !p->q_att)
        return EXIT_RUNTIME;
    struct accuracy_grid g = { 2.0, 1000.0, o->q_n_step, o->q_samples };
    char err[512];
    if (accuracy_grid_check(&g, p->s, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: Q sweep: %s\n", err);
        return EXIT_USAGE;
    }
    int best = 0;
    for (int i = 0; i < total; ++i) {
        double q = o->q_min + i * o->q_step;
        struct model_spec m;
        char text[64];
        snprintf(text, sizeof text, "fq:Q=%.10g", q);
        if (model_spec_parse(text, &m, err, sizeof err)) {
            fprintf(stderr, "brdfbench reproduce: Q sweep: %s\n", err);
            return EXIT_RUNTIME;
        }
        struct accuracy_result res;
        int rc = accuracy_run(&p->actx, &m, &g, &res);
        if (rc)
            return rc;
        p->q[i] = q;
        p->q_rel[i] = res.epicentre.value;
        p->q_rel_n[i] = res.epicentre.n;
        p->q_abs[i] = res.whole.value;
        p->q_att[i] = res.attenuation.value;
        accuracy_result_free(&res);
        if (p->q_rel[i] < p->q_rel[best])
            best = i;
        p->nq = i + 1;
    }
    struct model_spec f2;
    model_spec_default(models_find("cq2"), &f2);
    struct accuracy_result res;
    int rc = accuracy_run(&p->actx, &f2, &g, &res);
    if (rc)
        return rc;
    p->f2_rel = res.epicentre.value;
    p->f2_abs = res.whole.value;
    accuracy_result_free(&res);

    /* The minimising Q: GSL Brent on the exact per-n figures over the integer n of [2, 1000]
       (fit.h), bracketed by the sweep's best grid point; then the device sweep at that Q. */
    long nc = 999;
    double *nv = malloc((size_t)nc * sizeof *nv);
    if (!nv)
        return EXIT_RUNTIME;
    for (long i = 0; i < nc; ++i)
        nv[i] = 2.0 + (double)i;
    struct fq_ctx fc = { nv, nc, 0, 0 };
    double lo = p->q[best > 0 ? best - 1 : 0], hi = p->q[best < p->nq - 1 ? best + 1 : best], m = p->q[best];
    double fm = fq_max_rel(m, &fc);
    if (lo < m && hi > m && fm < fq_max_rel(lo, &fc) && fm < fq_max_rel(hi, &fc))
        m = minimise_brent(fq_max_rel, &fc, lo, m, hi);
    p->q_best = m;
    p->q_best_host_rel = fq_max_rel(m, &fc);
    free(nv);
    char text[64];
    snprintf(text, sizeof text, "fq:Q=%.10g", p->q_best);
    rc = sweep_run(p, text, 2.0, o->samples, &p->fq_best);
    if (rc)
        return rc;
    p->have_fq_best = 1;
    return 0;
}

/* ---- the approximations engines use (docs/definitions.md) --------------------------------------------- */

static int add_engines(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    double a = NAN, err = NAN;
    int rc = fit_bg_exact_a(18.0, 2, &a, &err);
    if (!(c = claim_add(r, "claim", "BG-A-18", "Beaudoin and Guardado 2002 (ShaderX), table",
                        "m = 2, n = 18: A = 6.645 balances the largest errors of max(0, A c + 1 - A)^2 - c^n")))
        return EXIT_RUNTIME;
    claim_number(c, "6.645", 6.645, rc ? NAN : a, 0.001, "+-0.001 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f", a);
    setf(c->method, sizeof c->method, "bisection on A; each side's maximum over c in [0, 1] on a 2049-point grid "
                                      "polished with Brent, in double (fit_bg_exact_a)");
    if (!(c = claim_add(r, "claim", "BG-err-18", "Beaudoin and Guardado 2002 (ShaderX), table",
                        "m = 2, n = 18: the largest |f - c^n| over c in [0, 1] is 0.0631")))
        return EXIT_RUNTIME;
    claim_number(c, "0.0631", 0.0631, rc ? NAN : err, 0.0001, "+-1e-4 (one unit in the last printed digit)");
    setf(c->measured_text, sizeof c->measured_text, "%.5f", err);
    setf(c->method, sizeof c->method, "at the balancing A above");
    return 0;
}

/* ---- harness checks: energy, reciprocity, grid ------------------------------------------ */

static int add_checks(struct repro *p)
{
    struct reproduce_report *r = p->r;
    struct claim *c;
    if (p->have_energy) {
        const struct energy_summary *e = &p->energy;
        for (int i = 0; i < e->count; ++i) {
            const struct energy_model_summary *m = &e->models[i];
            if (!isfinite(m->normal_max_diff))
                continue;
            char id[32], what[256], tol[96];
            snprintf(id, sizeof id, "C-albedo-%s%s", m->spec.info->id, m->mode == ALBEDO_DCOS ? "-norm" : "");
            double cf;
            const char *why = "";
            albedo_closed_form_normal(&m->spec, m->mode, 2.0, &cf, &why);
            snprintf(what, sizeof what, "%s %s: device quadrature at normal incidence equals the closed form (%s)",
                     m->spec.info->id, m->mode == ALBEDO_DCOS ? "normalisation" : "albedo", why);
            snprintf(tol, sizeof tol, "|device - closed form| <= %.0e at n = 2, 4, 10, 100, 1000", e->quadrature_tolerance);
            if (!(c = claim_add(r, "check", id, "closed form", what)))
                return EXIT_RUNTIME;
            claim_bool(c, "closed form", m->normal_max_diff <= e->quadrature_tolerance, tol);
            c->measured = m->normal_max_diff;
            setf(c->measured_text, sizeof c->measured_text, "largest difference %.2e (n = %g)", m->normal_max_diff,
                 m->normal_diff_at_n);
            note_add(c, "Refining the quadrature (panels halved, twice the azimuth points) changes the table by at "
                        "most %.1e.", m->refine_change);
            setf(c->method, sizeof c->method, "device albedo quadrature (energy.json)");
        }
        double worst_host = 0, worst_dev = 0, worst_eval = 0;
        const char *worst_model = "";
        const struct recip_worst *wd = NULL;
        for (int i = 0; i < e->recip_count; ++i) {
            worst_host = fmax(worst_host, e->recip[i].host.diff);
            worst_eval = fmax(worst_eval, e->recip[i].device.eval_error);
            if (e->recip[i].device.diff >= worst_dev) {
                worst_dev = e->recip[i].device.diff;
                worst_model = e->recip[i].spec.label;
                wd = &e->recip[i].device;
            }
        }
        double pass_dev = 0, pass_host = 0;
        const struct recip_pass_summary *pw = NULL;
        int ct = 0;
        for (int i = 0; i < e->pass_count; ++i) {
            pass_host = fmax(pass_host, e->pass[i].host_worst);
            if (e->pass[i].mode >= 2)
                ++ct;
            if (!pw || e->pass[i].device_worst > pass_dev) {
                pass_dev = e->pass[i].device_worst;
                pw = &e->pass[i];
            }
        }
        if (!(c = claim_add(r, "claim", "P2-reciprocity", "paper 2, BRDF property 2",
                            "f(L, V) = f(V, L) (Helmholtz reciprocity) for every model, as the image passes "
                            "evaluate it")))
            return EXIT_RUNTIME;
        claim_bool(c, "f(L,V) = f(V,L)", worst_host <= 1e-9 && pass_host <= 1e-9 && e->pass_count > 0 && pass_dev <= 1e-5,
                   "double: relative difference <= 1e-9; the float image pass: <= 1e-5 (rounding of its products)");
        c->measured = pass_dev;
        setf(c->measured_text, sizeof c->measured_text, "image pass: float %.1e, double %.1e (relative); lobes: "
             "double %.1e of peak", pass_dev, pass_host, worst_host);
        if (pw)
            note_add(c, "Image pass (kernels/shade.cl), %d models of which %d Cook-Torrance, %ld pixels each shaded "
                        "twice with eye and light swapped: worst float difference %.1e (%s, n = %.4g).",
                     e->pass_count, ct, e->recip_pairs, pass_dev, pw->spec.label, pw->n);
        if (wd)
            note_add(c, "Lobe functions alone, %ld random (N, L, V) per registry model: in double within %.1e of "
                        "peak; in float with R formed as a vector the worst pair (%s, n = %.4g) differs by %.1e of "
                        "peak, the size of a single float value's error (%.1e): rounding of the lobe's cosine "
                        "amplified n times. cos psi = 2(N.L)(N.V) - L.V and N.H are symmetric in L, V.",
                     e->recip_pairs, worst_host, worst_model, wd->n, worst_dev, worst_eval);
        setf(c->method, sizeof c->method, "device image pass and its double reference; lobe kernel (energy.json)");
    }
    double worst = 0;
    const char *where = "";
    for (int i = 0; i < SW_COUNT; ++i)
        if (isfinite(p->grid_change[i]) && p->grid_change[i] >= worst) {
            worst = p->grid_change[i];
            where = sweep_defs[i].model;
        }
    if (p->o->grid_check) {
        if (!(c = claim_add(r, "check", "C-grid", "docs/definitions.md, zones and metrics",
                            "refining the sweep grid no longer moves a reported max delta or max Delta in its 4th "
                            "significant digit")))
            return EXIT_RUNTIME;
        claim_bool(c, "< 0.5 unit", worst < 0.5, "change < 0.5 of a unit in the 4th significant digit");
        c->measured = worst;
        setf(c->measured_text, sizeof c->measured_text, "largest change %.2g unit (%s)", worst, where);
        setf(c->method, sizeof c->method, "every claim sweep re-run with %ld samples per zone", 2 * p->o->samples);
    }
    double k2, e2;
    if (fit_minimax_k(2.0, &k2, &e2) == 0) {
        if (!(c = claim_add(r, "check", "C-fit-k2", "identity",
                            "the per-n minimax k of (k(c-1)+1)^2 at n = 2 is 1 (cq2 = c^2 there, delta = 0)")))
            return EXIT_RUNTIME;
        claim_number(c, "1", 1.0, k2, 1e-9, "+-1e-9");
        setf(c->measured_text, sizeof c->measured_text, "k = %.12f, max delta %.1e", k2, e2);
        setf(c->method, sizeof c->method, "fit.h: exact per-n max delta, GSL Brent on its two sides");
    }
    return 0;
}

/* ---- the papers' cost argument, measured ----------------------------------------------------- */

/* Paper 1: "physically accurate BRDFs do not always comply with the requirements of highly
 * productive graphics systems"; paper 2: "physically based BRDFs are computationally complex,
 * so their use in real-time systems is limited". Measured as every physically based model's
 * evaluations/s against fq2's and against Phong's, from the same (N, L, V), in one run of the
 * runner (pbcost.h), each pair decided by compare's rule (compare_speed_rule: rank test, the
 * Hodges-Lehmann ratio and its interval, the minimum effect). The claim holds when every such
 * pair is decided "slower"; it fails when some pair is decided "faster" or "same" (a physically
 * based model that costs no more than a lobe); otherwise the timings cannot decide it: within
 * noise. */
static int add_physical(struct repro *p)
{
    if (!p->have_physical)
        return 0;
    const struct pbcost_result *ph = &p->physical;
    double lo_fq2 = INFINITY, hi_fq2 = 0, lo_ph = INFINITY, hi_ph = 0;
    const char *lo_name = "", *hi_name = "";
    char per_model[700] = "", not_slower[300] = "", noisy[300] = "";
    size_t used = 0, used_ns = 0, used_no = 0;
    for (int i = 0; i < ph->count; ++i) {
        const struct pbcost_row *row = &ph->rows[i];
        if (!row->physical)
            continue;
        if (row->ratio_to_fq2 < lo_fq2) {
            lo_fq2 = row->ratio_to_fq2;
            lo_name = row->name;
        }
        if (row->ratio_to_fq2 > hi_fq2) {
            hi_fq2 = row->ratio_to_fq2;
            hi_name = row->name;
        }
        lo_ph = fmin(lo_ph, row->ratio_to_phong);
        hi_ph = fmax(hi_ph, row->ratio_to_phong);
        const struct compare_speed *vs[2] = { &row->vs_fq2, &row->vs_phong };
        static const char *const against[2] = { "fq2", "Phong" };
        for (int k = 0; k < 2; ++k) {
            int v = vs[k]->verdict;
            if (v == CMP_V_SLOWER)
                continue;
            int decided = v == CMP_V_FASTER || v == CMP_V_SAME;
            char *buf = decided ? not_slower : noisy;
            size_t *u = decided ? &used_ns : &used_no, cap = decided ? sizeof not_slower : sizeof noisy;
            if (*u < cap)
                *u += (size_t)snprintf(buf + *u, cap - *u, "%s%s vs %s %.3gx [%.3g, %.3g] (%s)", *u ? ", " : "",
                                       row->name, against[k], vs[k]->ratio, vs[k]->ci_lo, vs[k]->ci_hi,
                                       cmp_verdict_name(v));
        }
        if (used < sizeof per_model)
            used += (size_t)snprintf(per_model + used, sizeof per_model - used, "%s%s %.3g/%.3g", used ? ", " : "",
                                     row->name, row->ratio_to_fq2, row->ratio_to_phong);
    }
    static const struct {
        const char *id, *source, *text;
    } rows[2] = {
        { "P1-physical-cost", "paper 1, sec. 2",
          "physically accurate BRDFs do not always comply with the requirements of highly productive graphics "
          "systems (the cost argument for empirical lobes)" },
        { "P2-physical-cost", "paper 2, review of BRDFs",
          "physically based BRDFs are computationally complex, so their use in real-time systems is limited" },
    };
    for (int k = 0; k < 2; ++k) {
        struct claim *c = claim_add(p->r, "claim", rows[k].id, rows[k].source, rows[k].text);
        if (!c)
            return EXIT_RUNTIME;
        claim_bool(c, "slower than the lobes", used_ns == 0 && used_no == 0,
                   "compare's rule (alpha 0.05, effect > 10%) decides each physically based model slower than "
                   "fq2 and Phong; one faster or same: not; else within noise");
        c->undecided = used_ns == 0 && used_no > 0;
        c->measured = hi_fq2;
        setf(c->measured_text, sizeof c->measured_text, "%.3g-%.3gx fq2's rate, %.3g-%.3gx Phong's", lo_fq2, hi_fq2,
             lo_ph, hi_ph);
        note_add(c, "Evaluations/s relative to fq2 / to Phong (exp(n ln c)) on %s: %s. Slowest %s, fastest %s.",
                 p->s->device_name, per_model, lo_name, hi_name);
        if (used_ns)
            note_add(c, "Decided not slower: %s: the cost argument does not hold against that lobe here.", not_slower);
        if (used_no)
            note_add(c, "Not decided (the repetitions cannot tell it from noise): %s.", noisy);
        setf(c->method, sizeof c->method, "physical.json: tp_vec_* kernels, %d interleaved rounds, pow() the "
             "reference; compare's rule, n = %g", ph->o.reps, ph->o.n);
    }
    return 0;
}

void reproduce_report_free(struct reproduce_report *r)
{
    free(r->rows);
    free(r->markdown);
    memset(r, 0, sizeof *r);
}

static void repro_free(struct repro *p)
{
    for (int i = 0; i < SW_COUNT; ++i)
        if (p->have_sw[i])
            accuracy_result_free(&p->sw[i]);
    if (p->have_fq_best)
        accuracy_result_free(&p->fq_best);
    free(p->q);
    free(p->q_rel);
    free(p->q_rel_n);
    free(p->q_abs);
    free(p->q_att);
    accuracy_close(&p->actx);
    integrate_close(&p->ic);
    energy_summary_free(&p->energy);
}

int reproduce_run(struct cl_session *s, const struct reproduce_options *o, struct reproduce_report *report)
{
    char err[1024];
    struct reproduce_report local;
    struct reproduce_report *r = report ? report : &local;
    memset(r, 0, sizeof *r);
    if (reproduce_options_check(o, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return EXIT_USAGE;
    }
    double t0 = wall_seconds();
    struct repro p;
    struct repro_rows rows = { 0 };
    memset(&p, 0, sizeof p);
    p.s = s;
    p.o = o;
    p.r = r;
    int rc = accuracy_open(&p.actx, s, "");
    if (!rc)
        rc = integrate_open(&p.ic, s);
    if (!rc && !o->io.quiet)
        fprintf(stderr, "reproduce: claim sweeps...\n");
    if (!rc)
        rc = run_sweeps(&p);
    if (!rc && !o->io.quiet)
        fprintf(stderr, "reproduce: Q sweep (%g..%g step %g)...\n", o->q_min, o->q_max, o->q_step);
    if (!rc)
        rc = run_q_sweep(&p);
    if (!rc && o->energy) {
        if (!o->io.quiet)
            fprintf(stderr, "reproduce: albedo and reciprocity...\n");
        rc = energy_run(s, NULL, 1, &p.energy);   /* energy.json is written with the other files */
        p.have_energy = rc == 0;
    }
    if (!rc && o->physical) {
        if (!o->io.quiet)
            fprintf(stderr, "reproduce: cost of the physically based models...\n");
        struct pbcost_options po;
        pbcost_options_default(&po);
        po.io.quiet = o->io.quiet;   /* no folder: reproduce writes the rows with its own files */
        rc = pbcost_run(s, &po, &p.physical);
        p.have_physical = rc == 0;
    }
    if (!rc)
        rc = reproduce_add_papers(&p);
    if (!rc)
        rc = add_engines(&p);
    if (!rc)
        rc = add_checks(&p);
    if (!rc)
        rc = add_physical(&p);
    if (rc)
        goto done;
    for (int i = 0; i < r->count; ++i) {
        if (r->rows[i].reproduced)
            r->reproduced++;
        else if (r->rows[i].undecided)
            r->within_noise++;
        else
            r->not_reproduced++;
    }
    r->seconds = wall_seconds() - t0;
    keep_q_sweep(&p, &r->q_sweep);
    /* the rows of every file, once: each file's rows member, and claims.md drawn from them */
    if (reproduce_rows(&p, &rows, err, sizeof err) == 0 && !(r->markdown = reproduce_claims_markdown(&rows)))
        snprintf(err, sizeof err, "claims.md: out of memory");
    if (!r->markdown) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (o->io.out_dir) {
        char path[4200];
        path_join(path, sizeof path, o->io.out_dir, "claims.json");
        if (reproduce_write_claims_json(&p, rows.claims, path, err, sizeof err) == 0) {
            path_join(path, sizeof path, o->io.out_dir, "claims.md");
            if (write_file_atomic(path, r->markdown, strlen(r->markdown), err, sizeof err) == 0) {
                path_join(path, sizeof path, o->io.out_dir, "q_sweep.json");
                if (reproduce_write_q_sweep_json(&p, rows.q_sweep, path, err, sizeof err) == 0) {
                    err[0] = '\0';
                    if (p.have_energy && p.energy.json) {
                        path_join(path, sizeof path, o->io.out_dir, "energy.json");
                        write_file_atomic(path, p.energy.json, strlen(p.energy.json), err, sizeof err);
                    }
                    if (!err[0] && p.have_physical) {
                        path_join(path, sizeof path, o->io.out_dir, "physical.json");
                        pbcost_write_json(path, s, &p.physical, rows.physical, err, sizeof err);
                    }
                }
            }
        }
        if (err[0]) {
            fprintf(stderr, "brdfbench reproduce: %s\n", err);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    if (!o->io.quiet)
        reproduce_print_table(stdout, &p);
    if (p.consistency_failed) {
        fprintf(stderr, "brdfbench reproduce: host and device quadrature of eq. 11 disagree (row C-eq11-device)\n");
        rc = EXIT_RUNTIME;
    }
done:
    reproduce_rows_free(&rows);
    repro_free(&p);
    if (!report)
        reproduce_report_free(r);
    return rc;
}

