/* gate_run.c - running a gates file: every gate measured and given its verdict (see gate.h). */
#define _DEFAULT_SOURCE   /* realpath */
#define _POSIX_C_SOURCE 200809L
#include "gate.h"
#include "gate_internal.h"
#include "hemisphere.h"
#include "energy.h"
#include "exitcodes.h"
#include "infile.h"
#include "jsonr.h"
#include "measured.h"
#include "outdir.h"
#include "programs.h"
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- running --------------------------------------------------------------------------- */

int gate_set_check_device(const struct gate_set *g, const struct cl_session *s, char *err, size_t errlen)
{
    char msg[1024];
    for (int i = 0; i < g->count; ++i)
        if (gate_metric_needs_sweep(g->gates[i].metric) && accuracy_grid_check(&g->gates[i].grid, s, msg, sizeof msg)) {
            snprintf(err, errlen, "%s:%d:%d: gate %d: grid: %s", g->path, g->gates[i].line, g->gates[i].col, i + 1,
                     msg);
            return EXIT_USAGE;
        }
    return 0;
}

/* A sweep that the gates need: a model over a grid. */
struct gate_sweep {
    struct model_spec model;
    struct accuracy_grid grid;
    struct accuracy_result result;
    int ran;
};

/* 1 when x lies on the lattice a + k h (k >= 0 integer), within rounding. */
static int on_lattice(double x, double a, double h)
{
    double k = (x - a) / h;
    return k >= -1e-9 && fabs(k - nearbyint(k)) <= 1e-9 * fmax(1.0, fabs(k));
}

/* 1 when sweep grid s holds every n value of gate grid g (so g's figures can be read off s). */
static int grid_covers(const struct accuracy_grid *s, const struct accuracy_grid *g)
{
    return s->samples == g->samples && gate_same_number(s->n_step, g->n_step) && s->n_min <= g->n_min &&
           s->n_max >= g->n_max && on_lattice(g->n_min, s->n_min, s->n_step) &&
           (gate_same_number(g->n_max, s->n_max) || on_lattice(g->n_max, s->n_min, s->n_step));
}

static int same_model(const struct model_spec *a, const struct model_spec *b)
{
    return a->info == b->info && strcmp(a->label, b->label) == 0;
}

/* Keeps the larger of best and e (NaN never wins over a number). */
static void keep_max(struct acc_extreme *best, const struct acc_extreme *e)
{
    if (e->value > best->value || (isnan(best->value) && isfinite(e->value)))
        *best = *e;
}

/* Reads a gate's figure off a sweep over a grid that covers its own. */
static void gate_from_sweep(struct gate *g, const struct accuracy_result *r)
{
    float lo = (float)g->grid.n_min, hi = (float)g->grid.n_max;
    struct acc_extreme best = { NAN, NAN, NAN };
    long long invalid = 0;
    g->invalid_n = g->invalid_x = NAN;
    for (long i = 0; i < r->n_count; ++i) {
        const struct acc_per_n *p = &r->per_n[i];
        if (p->n < lo || p->n > hi)
            continue;
        if (p->invalid_count > 0) {
            if (invalid == 0) {
                g->invalid_n = p->n;
                g->invalid_x = angle_of_s((double)p->invalid_s);
            }
            invalid += (long long)p->invalid_count;
        }
        switch (g->metric) {
        case GATE_EPICENTRE_MAX_REL:   keep_max(&best, &p->epi_rel_d); break;
        case GATE_EPICENTRE_MAX_ABS:   keep_max(&best, &p->epi_abs_d); break;
        case GATE_ATTENUATION_MAX_ABS: keep_max(&best, &p->att_abs_d); break;
        case GATE_WHOLE_MAX_ABS:       keep_max(&best, &p->epi_abs_d); keep_max(&best, &p->att_abs_d); break;
        default: break;
        }
    }
    g->invalid_count = invalid;
    /* The device-vs-double check over the gate's own n values, against its own figure. */
    accuracy_check_figures(r, g->grid.n_min, g->grid.n_max,
                           g->metric == GATE_EPICENTRE_MAX_REL ? best.value : NAN,
                           g->metric == GATE_ATTENUATION_MAX_ABS ? best.value : NAN,
                           g->metric == GATE_WHOLE_MAX_ABS || g->metric == GATE_EPICENTRE_MAX_ABS ? best.value : NAN,
                           &g->check);
    if (g->metric == GATE_INVALID_COUNT) {
        g->measured = (double)invalid;
        g->at_n = g->invalid_n;
        g->at_x = g->invalid_x;
    } else {
        g->measured = best.value;
        g->at_n = best.n;
        g->at_x = best.x;
    }
}

struct energy_ctx {
    const struct model_spec *m;
    double n;
};

/* 2 pi f(c, n) c: the integrand of the energy over c = cos x in [0, 1]
   (2 pi int_0^(pi/2) f(cos x) cos x sin x dx = 2 pi int_0^1 f(c) c dc). */
static double energy_integrand(double c, void *p)
{
    const struct energy_ctx *e = p;
    return 2.0 * 3.14159265358979323846 * model_eval_host(e->m, c, e->n) * c;
}

/* The energy 2 pi int_0^1 f(c, n) c dc by GSL's adaptive quadrature, with break points where
   a lobe of width ~1/n changes fastest. NAN when the integral fails or f is not finite. */
static double energy_at(const struct model_spec *m, double n, gsl_integration_workspace *w)
{
    struct energy_ctx ctx = { m, n };
    gsl_function fn = { energy_integrand, &ctx };
    double pts[8];
    size_t np = 0;
    pts[np++] = 0.0;
    static const double widths[] = { 64.0, 16.0, 4.0, 1.0 };
    for (int k = 0; k < 4; ++k) {
        double c = 1.0 - widths[k] / n;
        if (c > pts[np - 1] + 1e-12 && c < 1.0)
            pts[np++] = c;
    }
    pts[np++] = 1.0;
    double result = NAN, abserr = NAN;
    int status = gsl_integration_qagp(&fn, pts, np, 1e-13, 1e-10, 1000, w, &result, &abserr);
    if (!isfinite(result) || (status != GSL_SUCCESS && !(abserr <= 1e-9 * fmax(1.0, fabs(result)))))
        return NAN;
    return result;
}

static void gate_energy(struct gate *g)
{
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    long count = accuracy_grid_count(&g->grid);
    g->measured = g->at_n = g->at_x = NAN;
    int bad = 0;
    for (long i = 0; w && i < count; ++i) {
        double n = accuracy_grid_n(&g->grid, i);
        double dev = fabs(energy_at(&g->model, n, w) - 1.0);
        if (!isfinite(dev)) {
            if (!bad++)
                snprintf(g->reason, sizeof g->reason, "the energy integral failed or was not finite at n = %g", n);
            continue;
        }
        if (isnan(g->measured) || dev > g->measured) {
            g->measured = dev;
            g->at_n = n;
        }
    }
    if (!w)
        snprintf(g->reason, sizeof g->reason, "out of memory");
    else if (bad)
        g->measured = NAN;   /* a maximum that skipped points is no maximum */
    if (w)
        gsl_integration_workspace_free(w);
    gsl_set_error_handler(old);
}

/* The largest directional albedo over the gate's n values and theta_i = 0, 5, ..., 85
   degrees: at_n, and at_x = theta_i in radians. */
static int gate_albedo(struct gate *g, struct integrate_ctx *ic)
{
    long count = accuracy_grid_count(&g->grid) * GATE_ALBEDO_THETA_COUNT;
    double *n = malloc((size_t)count * sizeof *n), *th = malloc((size_t)count * sizeof *th);
    double *out = malloc((size_t)count * sizeof *out);
    int rc = 0;
    g->measured = g->at_n = g->at_x = NAN;
    if (!n || !th || !out) {
        fprintf(stderr, "brdfbench gate: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (long i = 0; i < count; ++i) {
        n[i] = accuracy_grid_n(&g->grid, i / GATE_ALBEDO_THETA_COUNT);
        th[i] = (double)(i % GATE_ALBEDO_THETA_COUNT) * 5.0 * 3.14159265358979323846 / 180.0;
    }
    if ((rc = albedo_device(ic, &g->model, albedo_mode_of(g->model.info), n, th, (int)count, out)) != 0)
        goto done;
    for (long i = 0; i < count; ++i) {
        if (!isfinite(out[i])) {
            snprintf(g->reason, sizeof g->reason, "the albedo quadrature was not finite at n = %g", n[i]);
            g->measured = NAN;
            break;
        }
        if (isnan(g->measured) || out[i] > g->measured) {
            g->measured = out[i];
            g->at_n = n[i];
            g->at_x = th[i];
        }
    }
done:
    free(n);
    free(th);
    free(out);
    return rc;
}

/* A measured.rms gate: the lobe at the Blinn-Phong fit of the material (measured.h); at_n is
 * that fit's n. A malformed file is EXIT_USAGE, named. */
static int gate_measured(struct gate *g, struct cl_session *s)
{
    char err[4600];
    struct merl_material mat;
    int rc = merl_read(g->measured_path, &mat, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        return rc;
    }
    struct measured_options o;
    measured_options_default(&o);
    o.nlobes = 1;
    o.lobes[0] = g->model;
    o.skip_physical = 1;   /* the gate needs the Blinn-Phong fit only */
    struct measured_material *r = malloc(sizeof *r);
    if (!r) {
        merl_free(&mat);
        fprintf(stderr, "brdfbench gate: out of memory\n");
        return EXIT_RUNTIME;
    }
    rc = measured_material_run(s, &mat, &o, r);
    if (!rc) {
        g->measured = r->lobes[0].err_measured;
        g->at_n = r->fit[MFIT_BLINN].n;
        if (!r->device_ok) {   /* judged as no figure: gate_judge fails it with this reason */
            g->measured = NAN;
            snprintf(g->reason, sizeof g->reason, "the device lookup disagrees with the host's table on %ld cells",
                     r->device_points - r->device_same_cell + r->device_value_diff);
        }
    }
    free(r);
    merl_free(&mat);
    return rc;
}

/* A hemisphere.* gate: the full BRDF against its family reference (refused references fail the
   gate with the refusal's words) over n in the gate's range, 8 values, the default grid. */
static int gate_hemisphere(struct gate *g, struct hemi_ctx *h)
{
    struct hemi_axis axis = { .name = "n", .q = HQ_N, .min = g->grid.n_min, .max = g->grid.n_max,
                              .count = HEMI_DEFAULT_POINTS };
    struct hemi_grid grid = { HEMI_DEFAULT_NH, HEMI_DEFAULT_ND, HEMI_DEFAULT_NP };
    struct model_spec ref;
    char err[512];
    g->measured = g->at_n = g->at_x = NAN;
    if (g->has_reference)
        ref = g->reference;
    if ((!g->has_reference && hemisphere_default_reference(&g->model, &axis, &ref, err, sizeof err)) ||
        hemisphere_axis_check(&axis, NULL, 0, &g->model, &ref, g->grid.n_min, g->grid.n_max, err, sizeof err)) {
        snprintf(g->reason, sizeof g->reason, "%s", err);
        return 0;
    }
    axis.geometric = axis.min > 0 && axis.max / axis.min > 10;
    struct hemi_result r;
    int rc = hemisphere_run(h, &g->model, &ref, &axis, NULL, 0, &grid, &r);
    if (rc)
        return rc;
    const struct hemi_extreme *e = g->metric == GATE_HEMI_EPI_REL ? &r.epicentre
                                   : g->metric == GATE_HEMI_ATT_ABS ? &r.attenuation
                                   : g->metric == GATE_HEMI_WHOLE_ABS ? &r.whole : &r.rms;
    g->measured = e->value;
    g->at_n = e->p;
    g->at_x = e->th;
    g->invalid_count = r.invalid;
    g->invalid_n = g->invalid_x = NAN;
    g->check.exceeded = r.check.exceeded;
    g->check.figure = r.check.figure ? r.check.figure : "";
    g->check.units = r.check.units;
    g->check.diff = r.check.diff;
    g->check.n = r.check.p;
    if (r.reason[0])
        snprintf(g->reason, sizeof g->reason, "%s", r.reason);
    hemisphere_result_free(&r);
    return 0;
}

/* PASS/FAIL against the bounds and the baseline. */
static void gate_judge(struct gate *g, double tolerance)
{
    char why[720] = "";
    int fail = 0;
    if (!isfinite(g->measured)) {
        fail = 1;
        snprintf(why, sizeof why, "%s", g->reason[0] ? g->reason : "no finite value was measured");
        g->margin = g->margin_rel = NAN;
    } else {
        double m_hi = g->has_max ? g->max - g->measured : INFINITY;
        double m_lo = g->has_min ? g->measured - g->min : INFINITY;
        g->margin = fmin(m_hi, m_lo);
        double bound = m_hi <= m_lo ? g->max : g->min;
        g->margin_rel = bound != 0 ? g->margin / fabs(bound) : NAN;
        if (g->margin < 0) {
            fail = 1;
            if (m_hi < 0)
                snprintf(why, sizeof why, "measured %.6g is above max %.6g", g->measured, g->max);
            else
                snprintf(why, sizeof why, "measured %.6g is below min %.6g", g->measured, g->min);
        }
        if (g->check.exceeded) {
            size_t used = strlen(why);
            char nt[32];
            accuracy_format_n(g->check.n, nt, sizeof nt);
            snprintf(why + used, sizeof why - used,
                     "%sdevice and double disagree on %s at n = %s by %.4g units of its 4th significant digit "
                     "(bound %g)%s", used ? "; " : "", g->check.figure, nt, g->check.units,
                     ACC_CHECK_BOUND_UNITS, g->accept_device_disagreement ? ", accepted by the gate" : "");
            if (!g->accept_device_disagreement)
                fail = 1;
        }
        if (g->metric != GATE_INVALID_COUNT && g->invalid_count > 0) {
            fail = 1;
            size_t used = strlen(why);
            char nt[32];
            accuracy_format_n(g->invalid_n, nt, sizeof nt);
            snprintf(why + used, sizeof why - used,
                     "%s%lld model values were NaN, Inf or negative (first at n = %s, x = %.6g)",
                     used ? "; " : "", g->invalid_count, nt, g->invalid_x);
        }
    }
    if (g->baseline_status == GATE_BASELINE_OK || g->baseline_status == GATE_BASELINE_REGRESSION) {
        g->baseline_change = g->baseline != 0 ? (g->measured - g->baseline) / fabs(g->baseline) : NAN;
        double allowed = tolerance * fabs(g->baseline) + GATE_BASELINE_FLOOR;
        if (!(g->measured - g->baseline <= allowed)) {
            g->baseline_status = GATE_BASELINE_REGRESSION;
            fail = 1;
            size_t used = strlen(why);
            snprintf(why + used, sizeof why - used, "%sregression: %.6g against baseline %.6g (%+.3g%%, tolerance %g%%)",
                     used ? "; " : "", g->measured, g->baseline, 100.0 * g->baseline_change, 100.0 * tolerance);
        } else {
            g->baseline_status = GATE_BASELINE_OK;
        }
    }
    g->status = fail ? GATE_FAIL : GATE_PASS;
    if (fail || g->check.exceeded)
        snprintf(g->reason, sizeof g->reason, "%s", why);
}

int gate_set_run(struct gate_set *gs, struct cl_session *s, FILE *progress)
{
    int rc = 0;
    struct accuracy_ctx actx;
    memset(&actx, 0, sizeof actx);
    struct integrate_ctx ic;
    int ic_open = 0;
    struct hemi_ctx hctx;
    int hctx_open = 0;
    struct gate_sweep *sweeps = calloc((size_t)gs->count, sizeof *sweeps);
    int *plan = malloc((size_t)gs->count * sizeof *plan), *order = malloc((size_t)gs->count * sizeof *order);
    int nsweeps = 0, sweeps_done = 0;
    if (!sweeps || !plan || !order) {
        fprintf(stderr, "brdfbench gate: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    /* Plan: widest grids first, so a narrower gate on the same model reads its figure off a
       wider sweep that holds its n values instead of running its own. */
    for (int i = 0; i < gs->count; ++i)
        order[i] = i;
    for (int i = 1; i < gs->count; ++i)
        for (int j = i; j > 0; --j) {
            const struct accuracy_grid *a = &gs->gates[order[j - 1]].grid, *b = &gs->gates[order[j]].grid;
            if (b->n_max - b->n_min <= a->n_max - a->n_min)
                break;
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    for (int k = 0; k < gs->count; ++k) {
        int i = order[k];
        struct gate *g = &gs->gates[i];
        plan[i] = -1;
        if (!gate_metric_needs_sweep(g->metric))
            continue;
        for (int j = 0; j < nsweeps && plan[i] < 0; ++j)
            if (same_model(&sweeps[j].model, &g->model) && grid_covers(&sweeps[j].grid, &g->grid))
                plan[i] = j;
        if (plan[i] < 0) {
            sweeps[nsweeps].model = g->model;
            sweeps[nsweeps].grid = g->grid;
            plan[i] = nsweeps++;
        }
    }
    gs->sweeps_run = nsweeps;
    if ((rc = accuracy_open(&actx, s, "")) != 0)
        goto done;
    /* Every user model compiles before the first sweep runs. */
    for (int i = 0; i < gs->count && !rc; ++i)
        rc = accuracy_prepare(&actx, &gs->gates[i].model);
    if (rc)
        goto done;
    for (int i = 0; i < gs->count; ++i) {
        struct gate *g = &gs->gates[i];
        double t0 = wall_seconds();
        if (plan[i] >= 0) {
            struct gate_sweep *sw = &sweeps[plan[i]];
            if (!sw->ran) {
                if ((rc = accuracy_run(&actx, &sw->model, &sw->grid, &sw->result)) != 0)
                    goto done;
                sw->ran = 1;
                ++sweeps_done;
                if (progress)
                    fprintf(progress, "sweep %d/%d: %s n=[%g,%g] step %g, %ld samples per zone (%.2f s)\n",
                            sweeps_done, nsweeps, sw->model.label, sw->grid.n_min, sw->grid.n_max, sw->grid.n_step,
                            sw->grid.samples, wall_seconds() - t0);
            }
            gate_from_sweep(g, &sw->result);
            if (sw->result.reason[0] && sw->result.invalid_count == 0)
                snprintf(g->reason, sizeof g->reason, "%s", sw->result.reason);
        } else if (gate_metric_is_hemisphere(g->metric)) {
            if (!hctx_open) {
                hemisphere_open(&hctx, s, "");
                hctx_open = 1;
            }
            if ((rc = gate_hemisphere(g, &hctx)) != 0)
                goto done;
            if (progress)
                fprintf(progress, "hemisphere: %s n=[%g,%g] (%.2f s)\n", g->model.label, g->grid.n_min,
                        g->grid.n_max, wall_seconds() - t0);
        } else if (g->metric == GATE_MEASURED_RMS) {
            if ((rc = gate_measured(g, s)) != 0)
                goto done;
            if (progress)
                fprintf(progress, "measured: %s against %s (%.2f s)\n", g->model.label, g->measured_path,
                        wall_seconds() - t0);
        } else if (g->metric == GATE_ALBEDO_MAX) {
            if (!ic_open) {
                if ((rc = integrate_open(&ic, s)) != 0)
                    goto done;
                ic_open = 1;
            }
            if ((rc = gate_albedo(g, &ic)) != 0)
                goto done;
            if (progress)
                fprintf(progress, "albedo: %s n=[%g,%g] step %g (%.2f s)\n", g->model.label, g->grid.n_min,
                        g->grid.n_max, g->grid.n_step, wall_seconds() - t0);
        } else {
            if ((rc = programs_host(s, &g->model)) != 0)   /* the model's double evaluation (programs.h) */
                goto done;
            gate_energy(g);
            if (progress)
                fprintf(progress, "energy: %s n=[%g,%g] step %g (%.2f s)\n", g->model.label, g->grid.n_min,
                        g->grid.n_max, g->grid.n_step, wall_seconds() - t0);
        }
        g->seconds = wall_seconds() - t0;
        gate_judge(g, gs->tolerance);
    }
done:
    if (hctx_open)
        hemisphere_close(&hctx);
    if (ic_open)
        integrate_close(&ic);
    accuracy_close(&actx);
    if (sweeps)
        for (int j = 0; j < nsweeps; ++j)
            if (sweeps[j].ran)
                accuracy_result_free(&sweeps[j].result);
    free(sweeps);
    free(plan);
    free(order);
    return rc;
}

int gate_set_failures(const struct gate_set *g)
{
    int n = 0;
    for (int i = 0; i < g->count; ++i)
        n += g->gates[i].status == GATE_FAIL;
    return n;
}
