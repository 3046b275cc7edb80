/* accuracy.c - the dense-grid sweep on the device and its double-precision check. */
#include "accuracy.h"
#include "lcg.h"
#include "exitcodes.h"
#include "programs.h"
#include "refine.h"
#include "brdf_shared.h"
#include "room.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ACC_PROBE_POINTS 4096

static const double half_pi = 1.57079632679489661923;

double zone_epicentre_end(double n) { return acos(exp(-BRDF_ZONE_K / n)); }
double zone_epicentre_end_s(double n) { return -expm1(-BRDF_ZONE_K / n); }
double angle_of_s(double s) { return 2.0 * asin(sqrt(0.5 * s)); }

double error_abs_host(const struct model_spec *m, const struct model_spec *ref, double c, double n)
{
    return fabs(model_eval_host(m, c, n) - model_eval_host(ref, c, n));
}

double error_rel_host(const struct model_spec *m, const struct model_spec *ref, double c, double n)
{
    double r = model_eval_host(ref, c, n);
    return fabs(model_eval_host(m, c, n) - r) / r;
}

long accuracy_grid_count(const struct accuracy_grid *g)
{
    double span = (g->n_max - g->n_min) / g->n_step;
    if (!(span >= 0) || span > 1e12)
        return -1;
    long count = (long)floor(span + 1e-9) + 1;
    if (g->n_min + (double)(count - 1) * g->n_step < g->n_max * (1 - 1e-12))
        ++count;   /* n_max itself is always a grid point */
    return count;
}

double accuracy_grid_n(const struct accuracy_grid *g, long i)
{
    long count = accuracy_grid_count(g);
    double v = (i >= count - 1) ? g->n_max : g->n_min + (double)i * g->n_step;
    return (double)(float)v;   /* the device sees n as a float */
}

int accuracy_grid_check(const struct accuracy_grid *g, const struct cl_session *s, char *err, size_t errlen)
{
    if (!isfinite(g->n_min) || g->n_min < ACC_MIN_N || g->n_min > ACC_MAX_N) {
        snprintf(err, errlen, "--n-min: %.9g is out of range (accepted: %g <= n-min <= %g)", g->n_min, ACC_MIN_N,
                 ACC_MAX_N);
        return EXIT_USAGE;
    }
    if (!isfinite(g->n_max) || g->n_max < ACC_MIN_N || g->n_max > ACC_MAX_N) {
        snprintf(err, errlen, "--n-max: %.9g is out of range (accepted: %g <= n-max <= %g)", g->n_max, ACC_MIN_N,
                 ACC_MAX_N);
        return EXIT_USAGE;
    }
    if (g->n_min >= g->n_max) {
        snprintf(err, errlen, "--n-min (%g) must be below --n-max (%g)", g->n_min, g->n_max);
        return EXIT_USAGE;
    }
    if (!isfinite(g->n_step) || g->n_step <= 0) {
        snprintf(err, errlen, "--n-step: %g is out of range (accepted: a number > 0)", g->n_step);
        return EXIT_USAGE;
    }
    long count = accuracy_grid_count(g);
    if (count < 2 || count > ACC_MAX_N_COUNT) {
        snprintf(err, errlen, "--n-step: %g gives %ld values of n (accepted: 2 to %ld)", g->n_step, count,
                 ACC_MAX_N_COUNT);
        return EXIT_USAGE;
    }
    if (g->samples < ACC_MIN_SAMPLES || g->samples > ACC_MAX_SAMPLES || g->samples % 16 != 0) {
        snprintf(err, errlen, "--samples: %ld is out of range (accepted: a multiple of 16 in [%d, %ld])",
                 g->samples, ACC_MIN_SAMPLES, ACC_MAX_SAMPLES);
        return EXIT_USAGE;
    }
    if ((double)count * (double)g->samples > ACC_MAX_WORK) {
        snprintf(err, errlen, "--samples: %ld samples x %ld values of n is more than %.0e points per model",
                 g->samples, count, ACC_MAX_WORK);
        return EXIT_USAGE;
    }
    if (s) {
        double bytes = (double)count * ACC_OUT_STRIDE * sizeof(float);
        if (bytes > (double)s->max_alloc || bytes > 0.5 * (double)s->global_mem) {
            snprintf(err, errlen, "--n-step: %ld values of n need %.3g bytes, more than the device allows (%.3g)",
                     count, bytes, (double)s->max_alloc);
            return EXIT_USAGE;
        }
    }
    return 0;
}

int accuracy_open(struct accuracy_ctx *a, struct cl_session *s, const char *build_options)
{
    memset(a, 0, sizeof *a);
    a->s = s;
    snprintf(a->build_options, sizeof a->build_options, "%s", build_options ? build_options : "");
    /* a session that specialises builds each model's program when it is first asked for
       (kernels_for, host/core/programs.h), never the program of every model, and with the
       scalar loop (kernels/accuracy.cl, ACC_W) */
    if (s->specialise) {
        size_t n = strlen(a->build_options);
        snprintf(a->build_options + n, sizeof a->build_options - n, "%s-DACC_W=1", n ? " " : "");
        return 0;
    }
    static const char *const names[] = { "accuracy_sweep", "models_probe" };
    cl_kernel *const kernels[] = { &a->sweep, &a->probe };
    return clsession_build_kernels(s, "accuracy.cl", NULL, a->build_options, &a->program, 2, names, kernels);
}

void accuracy_close(struct accuracy_ctx *a)
{
    cl_kernel *const kernels[] = { &a->sweep, &a->probe };
    clsession_release_kernels(&a->program, 2, kernels);
    cl_kernel *const table_kernels[] = { &a->table_sweep, &a->table_probe };
    clsession_release_kernels(&a->table_program, 2, table_kernels);
}

int accuracy_reference_is_table(const struct model_spec *ref)
{
    return ref && ref->info && !model_is_builtin(ref->info);
}

int accuracy_reference_check(const struct accuracy_grid *g, const struct model_spec *ref, const struct cl_session *s,
                             char *err, size_t errlen)
{
    if (!accuracy_reference_is_table(ref))
        return 0;
    long count = accuracy_grid_count(g);
    double points = (double)count * 2.0 * (double)g->samples;
    if (count < 1)   /* a grid that accuracy_grid_check refuses */
        return 0;
    if (points > (double)ACC_MAX_TABLE_POINTS) {
        snprintf(err, errlen, "--samples: %s is evaluated by the host at each of %.4g samples (%ld values of n x 2 "
                              "zones x %ld samples) (accepted: at most %ld with a user model as --reference)",
                 ref->label, points, count, g->samples, ACC_MAX_TABLE_POINTS);
        return EXIT_USAGE;
    }
    double bytes = points * sizeof(float);
    if (s && (bytes > (double)s->max_alloc || bytes > 0.5 * (double)s->global_mem)) {
        snprintf(err, errlen, "--samples: the table of %s's values needs %.3g bytes, more than the device allows "
                              "(%.3g)", ref->label, bytes, (double)s->max_alloc);
        return EXIT_USAGE;
    }
    return 0;
}

/* The kernels of the table build (ACC_REF_TABLE) that evaluate model m. */
static int table_kernels_for(struct accuracy_ctx *a, const struct model_spec *m, cl_kernel *sweep, cl_kernel *probe)
{
    if (!a->table_options[0])
        snprintf(a->table_options, sizeof a->table_options, "%s%s-DACC_REF_TABLE", a->build_options,
                 a->build_options[0] ? " " : "");
    int rc = 0;
    if (!a->s->specialise && !a->table_program && model_is_builtin(m->info)) {
        static const char *const names[] = { "accuracy_sweep", "models_probe" };
        cl_kernel *const kernels[] = { &a->table_sweep, &a->table_probe };
        rc = clsession_build_kernels(a->s, "accuracy.cl", NULL, a->table_options, &a->table_program, 2, names,
                                     kernels);
    }
    if (rc == 0)
        rc = programs_kernel(a->s, "accuracy.cl", a->table_options, m, "accuracy_sweep", a->table_sweep, sweep);
    if (rc == 0)
        rc = programs_kernel(a->s, "accuracy.cl", a->table_options, m, "models_probe", a->table_probe, probe);
    if (rc == 0)   /* the reference's double evaluation on the host */
        rc = programs_host(a->s, a->reference);
    return rc;
}

/* The sweep and probe kernels that evaluate model m (host/core/programs.h: the shared ones,
 * or those of a build with the model's text, cached for the session). */
static int kernels_for(struct accuracy_ctx *a, const struct model_spec *m, cl_kernel *sweep, cl_kernel *probe)
{
    if (accuracy_reference_is_table(a->reference))
        return table_kernels_for(a, m, sweep, probe);
    if (a->reference) {   /* --reference: a build with that reference's case where builds are specialised */
        int rc = programs_kernel_ref(a->s, "accuracy.cl", a->build_options, m, a->reference, "accuracy_sweep",
                                     a->sweep, sweep);
        if (rc == 0)
            rc = programs_kernel_ref(a->s, "accuracy.cl", a->build_options, m, a->reference, "models_probe", a->probe,
                                     probe);
        return rc;
    }
    int rc = programs_kernel(a->s, "accuracy.cl", a->build_options, m, "accuracy_sweep", a->sweep, sweep);
    if (rc == 0)
        rc = programs_kernel(a->s, "accuracy.cl", a->build_options, m, "models_probe", a->probe, probe);
    return rc;
}

/* The reference model m is measured against: --reference's, or its own. */
static void reference_of(const struct accuracy_ctx *a, const struct model_spec *m, struct model_spec *ref)
{
    if (a->reference)
        *ref = *a->reference;
    else
        model_reference_spec(m, ref);
}

int accuracy_prepare(struct accuracy_ctx *a, const struct model_spec *m)
{
    cl_kernel sweep, probe;
    return kernels_for(a, m, &sweep, &probe);
}

void accuracy_result_free(struct accuracy_result *r)
{
    free(r->per_n);
    r->per_n = NULL;
}

int accuracy_probe(struct accuracy_ctx *a, const struct model_spec *m, const float *c, const float *n,
                   size_t count, float *out)
{
    int rc = 0;
    cl_kernel sweep_unused, probe;
    if ((rc = kernels_for(a, m, &sweep_unused, &probe)) != 0)
        return rc;
    cl_int id = m->info->kernel_id;
    float p0 = (float)m->params[0], p1 = (float)m->params[1];
    CL_SET_ARGS_GOTO(done, probe, 0, CL_ARG(id), CL_ARG(p0), CL_ARG(p1));
    rc = cl_run_points16(a->s, probe, 3, c, n, count, out);
done:
    return rc;
}

/* The error function that a refinement maximises: x -> error at cos x for fixed n. */
struct refine_ctx {
    const struct model_spec *m, *ref;
    double n;
    int relative;
};

static double refine_error(double s, void *p)
{
    const struct refine_ctx *r = p;
    double c = 1.0 - s;
    /* Where the model is invalid (NaN, Inf, negative) the point is counted elsewhere and
       never becomes a maximum, as on the device. */
    double f = model_eval_host(r->m, c, r->n);
    if (!(f >= 0) || !isfinite(f))
        return -INFINITY;
    return r->relative ? error_rel_host(r->m, r->ref, c, r->n) : error_abs_host(r->m, r->ref, c, r->n);
}

enum zone { ZONE_EPICENTRE, ZONE_ATTENUATION };

/* The grid bracket [lo, hi] around s: one sample either side, as the kernel spaces them
   (kernels/accuracy.cl), and at least `lattice` either side, within the zone. */
static void grid_bracket(enum zone z, double n, long samples, double s, double lattice, double *lo, double *hi)
{
    double s_e = zone_epicentre_end_s(n);
    if (z == ZONE_EPICENTRE) {
        double h = fmax(s_e / (double)(samples - 1), lattice);
        *lo = fmax(0.0, s - h);
        *hi = fmin(s_e, s + h);
        return;
    }
    /* s = s_e r^j, r = (1/s_e)^(1/samples). */
    double log_r = -log(s_e) / (double)samples;
    double j = log_r > 0 ? log(fmax(s, s_e) / s_e) / log_r : 0.0;
    *lo = fmax(s_e, fmin(s_e * exp((j - 1.0) * log_r), s - lattice));
    *hi = fmin(1.0, fmax(s_e * exp((j + 1.0) * log_r), s + lattice));
}

/* The step of the float cosines that a model seeing only c was evaluated on (kernels/accuracy.cl
   moves its samples onto them): 2^-24 below 1. At large n it is coarser than the grid, so
   the polish searches one such step either side of the device's best point. 0 for the models
   that take s. */
static double c_lattice(const struct model_spec *m)
{
    return model_sees_only_c(m) ? 0x1p-24 : 0.0;
}

/* Polishes one per-n maximum in double: from the device's grid maximum at s = 1 - c,
 * a Brent search over the grid bracket around it, kept inside the zone. */
static struct acc_extreme refine_one(const struct accuracy_result *r, enum zone z, int relative, double n, float s_dev)
{
    struct acc_extreme e = { NAN, n, NAN };
    if (!(s_dev >= 0))
        return e;
    struct refine_ctx rc = { &r->model, &r->reference, n, relative };
    double s_e = zone_epicentre_end_s(n);
    double ends[2] = { z == ZONE_EPICENTRE ? 0.0 : s_e, z == ZONE_EPICENTRE ? s_e : 1.0 };
    double x0 = fmin(fmax((double)s_dev, ends[0]), ends[1]), lo, hi;
    /* Where the error is flat near its maximum, float noise can put the device's best sample a
       few samples away from the true maximum; a maximum found at an end of the bracket that is
       not an end of the zone means the error still rises beyond it, so the bracket walks on.
       Each step raises the value, so the walk ends at a local maximum. */
    for (int walk = 0; walk < 64; ++walk) {
        grid_bracket(z, n, r->grid.samples, x0, c_lattice(&r->model), &lo, &hi);
        x0 = fmin(fmax(x0, lo), hi);
        refine_maximum(refine_error, &rc, lo, x0, hi, &e.x, &e.value);
        int rises_on = (e.x == lo && lo > ends[0]) || (e.x == hi && hi < ends[1]);
        if (!rises_on || e.x == x0)
            break;
        x0 = e.x;
    }
    /* The zone's ends compete too: where two local maxima are nearly equal (a minimax
       design equioscillates), float noise may have picked the smaller one on the device. */
    for (int k = 0; k < 2; ++k) {
        double v = refine_error(ends[k], &rc);
        if (v > e.value) {
            e.value = v;
            e.x = ends[k];
        }
    }
    if (!(e.value > -INFINITY))   /* every candidate invalid */
        e.value = NAN;
    e.x = angle_of_s(e.x);
    return e;
}

static void check_per_n(struct accuracy_result *r);

/* The per-n figures in double (run by model_run_isolated: in the host reference's sandbox for a
 * user model; out is r->per_n's copy to fill). */
static void double_stage(void *ctx, void *out_v)
{
    struct accuracy_result *r = ctx;
    struct acc_per_n *out = out_v;
    check_per_n(r);
    for (long i = 0; i < r->n_count; ++i) {
        struct acc_per_n *p = &r->per_n[i];
        /* A zone where the device met no valid model value has no figure: the double stage
           does not search it on its own (a model can overflow in float and not in double). */
        p->epi_rel_d = refine_one(r, ZONE_EPICENTRE, 1, p->n, p->epi_rel >= 0 ? p->epi_rel_s : NAN);
        p->att_abs_d = refine_one(r, ZONE_ATTENUATION, 0, p->n, p->att_abs >= 0 ? p->att_abs_s : NAN);
        p->epi_abs_d = refine_one(r, ZONE_EPICENTRE, 0, p->n, p->epi_abs >= 0 ? p->epi_abs_s : NAN);
    }
    if (out != r->per_n)
        memcpy(out, r->per_n, (size_t)r->n_count * sizeof *out);
}

/* The largest of a per-n figure over the n grid. */
static void range_max_double(const struct accuracy_result *r, size_t offset, struct acc_extreme *out)
{
    out->value = out->n = out->x = NAN;
    for (long i = 0; i < r->n_count; ++i) {
        const struct acc_extreme *e = (const struct acc_extreme *)((const char *)&r->per_n[i] + offset);
        if (e->value > out->value || (isnan(out->value) && isfinite(e->value)))
            *out = *e;
    }
}

static void range_max_device(const struct accuracy_result *r, size_t value_offset, size_t s_offset,
                             struct acc_extreme *out)
{
    out->value = out->n = out->x = NAN;
    for (long i = 0; i < r->n_count; ++i) {
        float v = *(const float *)((const char *)&r->per_n[i] + value_offset);
        float s = *(const float *)((const char *)&r->per_n[i] + s_offset);
        if (v >= 0 && (v > out->value || isnan(out->value))) {
            out->value = v;
            out->n = r->per_n[i].n;
            out->x = angle_of_s((double)s);
        }
    }
}

/* |device - double| of one device figure at its own s; NAN when the device had none. */
static double check_one(const struct accuracy_result *r, float value, float s, double n, int relative)
{
    if (!(value >= 0))
        return NAN;
    double c = 1.0 - (double)s;
    double d = relative ? error_rel_host(&r->model, &r->reference, c, n) : error_abs_host(&r->model, &r->reference, c, n);
    return fabs((double)value - d);   /* NaN (the host finds no value) compares as a disagreement below */
}

/* Recomputes every per-n figure in double at the device's own inputs. */
static void check_per_n(struct accuracy_result *r)
{
    for (long i = 0; i < r->n_count; ++i) {
        struct acc_per_n *p = &r->per_n[i];
        p->ref_peak = fabs(model_eval_host(&r->reference, 1.0, p->n));
        p->chk_epi_rel = check_one(r, p->epi_rel, p->epi_rel_s, p->n, 1);
        p->chk_att_abs = check_one(r, p->att_abs, p->att_abs_s, p->n, 0);
        p->chk_epi_abs = check_one(r, p->epi_abs, p->epi_abs_s, p->n, 0);
    }
}

/* The largest device-vs-double differences over n, from the per-n ones. */
static void check_maxima(struct accuracy_result *r)
{
    r->check_rel_diff = r->check_abs_diff = 0;
    for (long i = 0; i < r->n_count; ++i) {
        const struct acc_per_n *p = &r->per_n[i];
        if (p->epi_rel >= 0 && !(p->chk_epi_rel <= r->check_rel_diff)) r->check_rel_diff = p->chk_epi_rel;
        if (p->att_abs >= 0 && !(p->chk_att_abs <= r->check_abs_diff)) r->check_abs_diff = p->chk_att_abs;
        if (p->epi_abs >= 0 && !(p->chk_epi_abs <= r->check_abs_diff)) r->check_abs_diff = p->chk_epi_abs;
    }
}

double fourth_digit_unit(double v)
{
    return (v > 0 && isfinite(v)) ? pow(10.0, floor(log10(v)) - 3.0) : 0.0;
}

/* Folds one per-n difference d, against reported figure f, into the verdict. A figure below float
   resolution of the reference's peak (2^-23 scale: a model equal to its reference in double) has
   no maximum a float device could miss: its device value is ok within a few units of 2^-24 scale
   or within twice the model's own float error there (noise: its float-cancellation figure, the
   probe's largest |device - double| over the reference's peak, brought to the figure's scale),
   docs/definitions.md, Device check. Above it the 4th-digit bound holds as before. */
static void check_fold(struct acc_check *out, double d, double figure, double scale, double noise, double n,
                       const char *name, int device_had_value)
{
    if (!device_had_value || isnan(figure))
        return;
    double unit = fourth_digit_unit(figure);
    /* A NaN difference (the double finds no value where the device did) is a disagreement. */
    int below_resolution = figure < 0x1p-23 * scale;   /* nothing of it a float device could resolve */
    int exceeded = (isnan(d) || d > ACC_CHECK_BOUND_UNITS * unit) && !(d <= ACC_CHECK_FLOAT_FLOOR * scale) &&
                   !(below_resolution && d <= fmax(ACC_CHECK_FLOOR_UNITS * 0x1p-24 * scale, 2.0 * noise));
    /* A figure below the float floor (a model equal to its reference, ~1e-16 in double) has no
       4th digit a float device could give: its units are not counted unless it is exceeded. */
    double units = isnan(d) ? INFINITY : unit > 0 ? d / unit : (d > 0 ? INFINITY : 0.0);
    if (!exceeded && !(figure >= ACC_CHECK_FLOAT_FLOOR * scale))
        units = 0;
    /* The worst is the one that exceeds, then the most units. */
    if ((exceeded && !out->exceeded) || (exceeded == out->exceeded && !(units <= out->units))) {
        out->units = units;
        out->diff = d;
        out->n = n;
        out->figure = name;
        out->exceeded = exceeded;
    }
}

void accuracy_check_figures(const struct accuracy_result *r, double n_lo, double n_hi, double epi_rel,
                            double att_abs, double whole_abs, struct acc_check *out)
{
    out->units = 0;
    out->diff = out->n = NAN;
    out->figure = "";
    out->exceeded = 0;
    float lo = (float)n_lo, hi = (float)n_hi;
    for (long i = 0; i < r->n_count; ++i) {
        const struct acc_per_n *p = &r->per_n[i];
        if (p->n < lo || p->n > hi)
            continue;
        double scale = p->ref_peak > 0 && isfinite(p->ref_peak) ? p->ref_peak : 1.0;
        /* the model's float noise: over the peak at any point; relative where the reference is at
           least e^-0.511 of its peak (the epicentre) */
        double noise = isfinite(r->probe_rel_diff) ? r->probe_rel_diff : 0.0;
        check_fold(out, p->chk_epi_rel, epi_rel, 1.0, noise / exp(-BRDF_ZONE_K), p->n, "epicentre.max_rel",
                   p->epi_rel >= 0);
        check_fold(out, p->chk_att_abs, att_abs, scale, noise * scale, p->n, "attenuation.max_abs", p->att_abs >= 0);
        /* Both zones' absolute figures stand behind the whole range's maximum. */
        check_fold(out, p->chk_att_abs, whole_abs, scale, noise * scale, p->n, "whole.max_abs", p->att_abs >= 0);
        check_fold(out, p->chk_epi_abs, whole_abs, scale, noise * scale, p->n, "whole.max_abs", p->epi_abs >= 0);
    }
}

void accuracy_format_n(double n, char *buf, size_t len)
{
    for (int digits = 6; digits <= 9; ++digits) {
        snprintf(buf, len, "%.*g", digits, n);
        if (strtof(buf, NULL) == (float)n)
            return;
    }
}

#define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct accuracy_grid, MEMBER, KEY)
const struct jw_field accuracy_grid_n_fields[ACCURACY_GRID_N_FIELDS] = {
    F(JWF_NUM, n_min, "n_min"), F(JWF_NUM, n_max, "n_max"), F(JWF_NUM, n_step, "n_step"),
};
#undef F

const char *accuracy_status(const struct accuracy_result *r)
{
    return !r->ok ? "failed" : r->device_disagrees ? "device_disagrees" : r->invalid_count ? "invalid_values" : "ok";
}

/* Compares single model values at pseudo-random points of both zones with the double
 * reference; the difference is relative to the reference lobe's peak f_ref(1, n). */
static int check_probe(struct accuracy_ctx *a, struct accuracy_result *r)
{
    float *c = malloc(ACC_PROBE_POINTS * sizeof *c), *n = malloc(ACC_PROBE_POINTS * sizeof *n);
    float *out = malloc(ACC_PROBE_POINTS * sizeof *out);
    double *host = NULL;
    int rc = 0;
    if (!c || !n || !out) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    uint64_t state = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < ACC_PROBE_POINTS; ++i) {
        double u = lcg_unit(&state);
        double v = lcg_unit(&state);
        double nv = r->per_n[(long)(u * (double)r->n_count) % r->n_count].n;
        double x_e = zone_epicentre_end(nv);
        /* Half the points in the epicentre, half over the lobe's fall-off (out to 4 x_e). */
        double x = (i % 2 == 0) ? v * x_e : fmin(half_pi, x_e + v * 3.0 * x_e);
        c[i] = (float)cos(x);
        n[i] = (float)nv;
    }
    rc = accuracy_probe(a, &r->model, c, n, ACC_PROBE_POINTS, out);
    if (rc)
        goto done;
    /* the double values, each model's in one sandbox stage for a user model's code */
    if (!(host = malloc(ACC_PROBE_POINTS * 2 * sizeof *host))) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    double *peak = host + ACC_PROBE_POINTS;
    if ((rc = model_values_and_peaks(&r->model, &r->reference, c, n, ACC_PROBE_POINTS, host, peak)) != 0)
        goto done;
    r->probe_rel_diff = 0;
    for (int i = 0; i < ACC_PROBE_POINTS; ++i) {
        double d = fabs((double)out[i] - host[i]) / (peak[i] > 0 ? peak[i] : 1.0);
        if (!(d <= r->probe_rel_diff))
            r->probe_rel_diff = d;
    }
done:
    free(host);
    free(out);
    free(n);
    free(c);
    return rc;
}

/* An explicit work-group size for the sweep. Left to PoCL, a range such as 999 = 27 x 37
 * became a single work-group and ran on one thread; a few work-items per group leaves enough
 * groups (about 8 per compute unit) to keep every thread busy. */
/* Work-items per n of the sweep (kernels/accuracy.cl's chunks): 1 on a CPU device, where the
   values of n already outnumber the cores; on a GPU, doubled until the launch holds 512
   work-items per compute unit (clsession_default_work_items) or a chunk would hold fewer than
   256 samples, each chunk a multiple of 16 samples (the kernel's vector width). */
long sweep_chunks(const struct cl_session *s, long count, long samples)
{
    /* BRDFBENCH_SWEEP_CHUNKS=K forces K (a power of 2 dividing samples / 16), so that the
       chunked path can be checked on any device (tests/test_sweep_chunks.sh) */
    const char *force = getenv("BRDFBENCH_SWEEP_CHUNKS");
    if (force && *force) {
        long k = strtol(force, NULL, 10);
        if (k >= 1 && (k & (k - 1)) == 0 && (samples / 16) % k == 0)
            return k;
    }
    if (s->is_cpu || count <= 0)
        return 1;
    long target = clsession_default_work_items(s, 1L << 24), chunks = 1;
    while (count * chunks < target && (samples / 16) % (chunks * 2) == 0 && samples / (chunks * 2) >= 256)
        chunks *= 2;
    return chunks;
}

/* The per-n maxima of a chunked sweep (kernels/accuracy.cl's record, ACC_OUT_STRIDE floats
   per work-item, chunks consecutive work-items per n) merged into one record per n, as one
   work-item over all the samples would have written it: each maximum the first chunk's that
   no later chunk exceeds (isgreater: a NaN never wins), its position with it; the invalid
   values summed; the invalid position the smallest s of any chunk. */
void accuracy_merge_chunks(const float *chunked, long count, long chunks, float *raw)
{
    /* each maximum of the record and the position of its s (kernels/brdf_shared.h) */
    static const int acc_maxima[3][2] = {
        { ACC_O_EPI_REL, ACC_O_EPI_REL_S }, { ACC_O_ATT_ABS, ACC_O_ATT_ABS_S }, { ACC_O_EPI_ABS, ACC_O_EPI_ABS_S }
    };
    for (long i = 0; i < count; ++i) {
        const float *c = chunked + (size_t)i * (size_t)chunks * ACC_OUT_STRIDE;
        float *o = raw + (size_t)i * ACC_OUT_STRIDE;
        memcpy(o, c, ACC_OUT_STRIDE * sizeof *o);
        for (long k = 1; k < chunks; ++k) {
            const float *q = c + (size_t)k * ACC_OUT_STRIDE;
            for (int j = 0; j < 3; ++j) {
                const int f = acc_maxima[j][0], at = acc_maxima[j][1];
                if (isgreater(q[f], o[f]) || (isnan(o[f]) && !isnan(q[f]))) {
                    o[f] = q[f];
                    o[at] = q[at];
                }
            }
            o[ACC_O_INVALID] += q[ACC_O_INVALID];
            /* the smallest invalid s (fminf: a NaN is no position) */
            o[ACC_O_INVALID_S] = fminf(o[ACC_O_INVALID_S], q[ACC_O_INVALID_S]);
        }
    }
}

static size_t sweep_local_size(long count, cl_uint compute_units)
{
    long per_group = count / (8L * (long)(compute_units ? compute_units : 1));
    return (size_t)(per_group < 1 ? 1 : per_group > 8 ? 8 : per_group);
}

/* The fp16 figures of a model with binary16 code (accuracy_result's fp16): its fp16 build
 * (-DBRDF_FP16: kernels/brdf_models.h's RHALF rounds) swept on the same grid; at each per-n
 * maximum the device found, the fp16 value is probed on the device and the reference's taken
 * in double here, so the figures are fp16 against double as the fp32 ones are. Returns 0 or
 * an exit code. */
static int fp16_stage(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                      struct accuracy_result *out)
{
    const struct model_runtime *rt = models_runtime(m->info);
    if (!rt || !rt->fp16)
        return 0;
    long count = out->n_count;
    float *raw = malloc((size_t)count * ACC_OUT_STRIDE * sizeof *raw);
    float *c = malloc((size_t)count * 2 * sizeof *c), *n = malloc((size_t)count * 2 * sizeof *n);
    float *v = malloc((size_t)count * 2 * sizeof *v);
    char saved[sizeof a->build_options];
    memcpy(saved, a->build_options, sizeof saved);
    int rc = 0;
    if (!raw || !c || !n || !v) {
        fprintf(stderr, "brdfbench: out of memory for %ld values of n\n", count);
        rc = EXIT_RUNTIME;
        goto done;
    }
    size_t used = strlen(a->build_options);
    if (used + 16 >= sizeof a->build_options) {
        fprintf(stderr, "brdfbench: build options too long for the fp16 build\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    snprintf(a->build_options + used, sizeof a->build_options - used, "%s-DBRDF_FP16=1", used ? " " : "");
    int timer_wall = a->timer_wall;
    rc = accuracy_sweep_device(a, m, g, raw, &out->fp16.device_seconds);
    a->timer_wall = timer_wall;
    if (rc)
        goto done;
    /* the probe points: each n's epicentre and attenuation maxima (zone 2i, 2i + 1), at these
       positions of the record (kernels/brdf_shared.h) */
    static const int zone_max[2][2] = { { ACC_O_EPI_REL, ACC_O_EPI_REL_S }, { ACC_O_ATT_ABS, ACC_O_ATT_ABS_S } };
    out->fp16.invalid_count = 0;
    for (long i = 0; i < count; ++i) {
        const float *o = raw + i * ACC_OUT_STRIDE;
        out->fp16.invalid_count += (long long)o[ACC_O_INVALID];
        for (int z = 0; z < 2; ++z) {
            float fig = o[zone_max[z][0]], sv = o[zone_max[z][1]];
            c[2 * i + z] = fig >= 0 && sv >= 0 ? (float)(1.0 - (double)sv) : NAN;
            n[2 * i + z] = (float)out->per_n[i].n;
        }
    }
    for (long k = 0; k < 2 * count; ++k)
        if (isnan(c[k]))
            c[k] = 1.0f;   /* probed, not used */
    rc = accuracy_probe(a, m, c, n, (size_t)(2 * count), v);
    if (rc)
        goto done;
    struct acc_extreme *best[2] = { &out->fp16.epicentre, &out->fp16.attenuation };
    for (int z = 0; z < 2; ++z)
        best[z]->value = best[z]->n = best[z]->x = NAN;
    for (long i = 0; i < count; ++i)
        for (int z = 0; z < 2; ++z) {
            const float *o = raw + i * ACC_OUT_STRIDE;
            long k = 2 * i + z;
            if (!(o[zone_max[z][0]] >= 0) || !(v[k] >= 0) || !isfinite(v[k]))
                continue;
            double r = model_eval_host(&out->reference, (double)c[k], (double)n[k]);
            double d = fabs((double)v[k] - r) / (z == 0 ? r : 1.0);
            if (d > best[z]->value || isnan(best[z]->value)) {
                best[z]->value = d;
                best[z]->n = out->per_n[i].n;
                best[z]->x = angle_of_s(1.0 - (double)c[k]);
            }
        }
    out->fp16.ratio_rel = out->fp16.epicentre.value / out->epicentre.value;
    out->fp16.ratio_abs = out->fp16.attenuation.value / out->attenuation.value;
    out->fp16.device_fp16 = a->s->has_fp16;
    out->fp16.present = 1;
done:
    memcpy(a->build_options, saved, sizeof saved);
    free(v);
    free(n);
    free(c);
    free(raw);
    return rc;
}

static int accuracy_compute(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                            struct accuracy_result *out)
{
    int rc = 0;
    float *nv = NULL, *raw = NULL;
    memset(out, 0, sizeof *out);
    if ((rc = accuracy_prepare(a, m)) != 0)   /* a user model's compile error before any allocation */
        return rc;
    out->model = *m;
    reference_of(a, m, &out->reference);
    out->grid = *g;
    out->n_count = accuracy_grid_count(g);
    long count = out->n_count;
    nv = malloc((size_t)count * sizeof *nv);
    raw = malloc((size_t)count * ACC_OUT_STRIDE * sizeof *raw);
    out->per_n = calloc((size_t)count, sizeof *out->per_n);
    if (!nv || !raw || !out->per_n) {
        fprintf(stderr, "brdfbench: out of memory for %ld values of n\n", count);
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (long i = 0; i < count; ++i)
        nv[i] = (float)accuracy_grid_n(g, i);

    a->timer_wall = 0;
    rc = accuracy_sweep_device(a, m, g, raw, &out->device_seconds);
    out->timer_wall = a->timer_wall;
    if (rc != 0)
        goto done;
    out->points = (double)count * 2.0 * (double)g->samples;

    out->invalid_n = out->invalid_x = NAN;
    for (long i = 0; i < count; ++i) {
        const float *o = raw + i * ACC_OUT_STRIDE;
        struct acc_per_n *p = &out->per_n[i];
        p->n = nv[i];
        p->epi_rel = o[ACC_O_EPI_REL]; p->epi_rel_s = o[ACC_O_EPI_REL_S];
        p->att_abs = o[ACC_O_ATT_ABS]; p->att_abs_s = o[ACC_O_ATT_ABS_S];
        p->epi_abs = o[ACC_O_EPI_ABS]; p->epi_abs_s = o[ACC_O_EPI_ABS_S];
        p->invalid_count = o[ACC_O_INVALID]; p->invalid_s = o[ACC_O_INVALID_S];
        if (o[ACC_O_INVALID] > 0) {
            if (out->invalid_count == 0) {
                out->invalid_n = p->n;
                out->invalid_x = angle_of_s((double)o[ACC_O_INVALID_S]);
            }
            out->invalid_count += (long long)o[ACC_O_INVALID];
        }
    }

    /* The double stage asks a user model for one value at a time: it runs as one phase in
       the host reference's sandbox (model_run_isolated), which hands back the per-n figures. */
    /* A built-in model against a user reference runs in the reference's sandbox (inside one, every
       user model's code is called directly). */
    const struct model_spec *isolate = model_is_builtin(out->model.info) ? &out->reference : &out->model;
    if (model_run_isolated(isolate, double_stage, out, out->per_n, (size_t)count * sizeof *out->per_n) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    check_maxima(out);
    struct acc_extreme epi_abs, grid_epi_abs;
    range_max_double(out, offsetof(struct acc_per_n, epi_rel_d), &out->epicentre);
    range_max_double(out, offsetof(struct acc_per_n, att_abs_d), &out->attenuation);
    range_max_double(out, offsetof(struct acc_per_n, epi_abs_d), &epi_abs);
    range_max_device(out, offsetof(struct acc_per_n, epi_rel), offsetof(struct acc_per_n, epi_rel_s),
                     &out->grid_epicentre);
    range_max_device(out, offsetof(struct acc_per_n, att_abs), offsetof(struct acc_per_n, att_abs_s),
                     &out->grid_attenuation);
    range_max_device(out, offsetof(struct acc_per_n, epi_abs), offsetof(struct acc_per_n, epi_abs_s),
                     &grid_epi_abs);
    out->whole = (epi_abs.value > out->attenuation.value || isnan(out->attenuation.value)) ? epi_abs : out->attenuation;
    out->grid_whole = (grid_epi_abs.value > out->grid_attenuation.value || isnan(out->grid_attenuation.value))
                          ? grid_epi_abs : out->grid_attenuation;
    rc = check_probe(a, out);
    if (rc)
        goto done;
    rc = fp16_stage(a, m, g, out);
    if (rc)
        goto done;

    out->ok = isfinite(out->epicentre.value) && isfinite(out->attenuation.value);
    accuracy_check_figures(out, -INFINITY, INFINITY, out->epicentre.value, out->attenuation.value, out->whole.value,
                           &out->check);
    out->device_disagrees = out->check.exceeded;
    size_t used = 0;
    if (!out->ok)
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used, "no finite error values; ");
    if (out->device_disagrees && used < sizeof out->reason) {
        char nt[32];
        accuracy_format_n(out->check.n, nt, sizeof nt);
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used,
                                 "device and double disagree on %s at n = %s by %.3g (%.4g units of its 4th "
                                 "significant digit; bound %g): the device may have missed the maximum; ",
                                 out->check.figure, nt, out->check.diff, out->check.units, ACC_CHECK_BOUND_UNITS);
        fprintf(stderr, "brdfbench: warning: %s: device and double disagree on %s at n = %s by %.4g units of its "
                        "4th significant digit (bound %g)\n", m->label, out->check.figure, nt, out->check.units,
                ACC_CHECK_BOUND_UNITS);
    }
    if (out->invalid_count > 0 && used < sizeof out->reason) {
        char nt[32];
        accuracy_format_n(out->invalid_n, nt, sizeof nt);
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used,
                                 "%lld model values were NaN, Inf or negative (first at n = %s, x = %.6g); they are "
                                 "excluded from the maxima; ",
                                 out->invalid_count, nt, out->invalid_x);
    }
    if (used >= 2 && used < sizeof out->reason)
        out->reason[used - 2] = '\0';   /* the last "; " */
    const char *note = model_eval_note(m);
    if (note && !out->reason[0])
        snprintf(out->reason, sizeof out->reason, "%s", note);
done:
    free(raw);
    free(nv);
    return rc;
}

/* ---- each figure once ------------------------------------------------------------------
 * A sweep is a function of the model, the grid, the device, its driver and platform, and the
 * program's source and build options (the kernel source is the process's: embedded, or
 * --kernel-dir's): the parts of one run (the claims, the fit, the accuracy table, the
 * frontier, the gates of `all` or `gate`, all on its one session) that ask for the same sweep
 * get the first one's result instead of running it again. */
struct sweep_memo {
    char device[256], driver[256], platform[256], options[256], reference[MODEL_LABEL_MAX];
    int specialise;
    struct model_spec model;
    struct accuracy_grid grid;
    struct accuracy_result result;
};
/* The session's table of sweeps already run (clsession.h: sweeps), so the memo lives with the
   run that asked for them (host/core/run.h) and goes when its session closes. */
#define MEMO(s) ((struct sweep_memo *)(s)->sweeps.items)

/* The key, field by field: the model (its entry, the values of its own parameters, its label),
   the grid, the build options, the device and the reference. */
static int same_sweep(const struct sweep_memo *e, const struct accuracy_ctx *a, const struct model_spec *m,
                      const struct accuracy_grid *g)
{
    if (e->model.info != m->info || strcmp(e->model.label, m->label) != 0)
        return 0;
    for (int p = 0; p < m->info->nparams && p < MODEL_MAX_PARAMS; p++)
        if (e->model.params[p] != m->params[p]) return 0;
    return e->specialise == a->s->specialise && e->grid.n_min == g->n_min && e->grid.n_max == g->n_max &&
           e->grid.n_step == g->n_step && e->grid.samples == g->samples && strcmp(e->options, a->build_options) == 0 &&
           strcmp(e->device, a->s->device_name) == 0 && strcmp(e->driver, a->s->driver_version) == 0 &&
           strcmp(e->platform, a->s->platform_version) == 0 &&
           strcmp(e->reference, a->reference ? a->reference->label : "") == 0;
}

/* A deep copy: dst owns its per-n table. Returns 0, or -1 when out of memory. */
static int copy_result(struct accuracy_result *dst, const struct accuracy_result *src)
{
    *dst = *src;
    dst->per_n = malloc((size_t)src->n_count * sizeof *dst->per_n);
    if (!dst->per_n) return -1;
    memcpy(dst->per_n, src->per_n, (size_t)src->n_count * sizeof *dst->per_n);
    return 0;
}

static void release_sweeps(struct cl_session *s) { accuracy_forget_sweeps(s); }

static void remember(const struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                     const struct accuracy_result *r)
{
    struct cl_session *s = a->s;
    struct sweep_memo *grown = room_for_one(s->sweeps.items, s->sweeps.count, &s->sweeps.cap, sizeof *grown, 32);
    if (!grown) return; /* not remembered: a later ask runs the sweep again */
    s->sweeps.items = grown;
    s->release_sweeps = release_sweeps;
    struct sweep_memo *e = &grown[s->sweeps.count];
    memset(e, 0, sizeof *e);
    snprintf(e->device, sizeof e->device, "%s", s->device_name);
    snprintf(e->driver, sizeof e->driver, "%s", s->driver_version);
    snprintf(e->options, sizeof e->options, "%s", a->build_options);
    snprintf(e->platform, sizeof e->platform, "%s", s->platform_version);
    snprintf(e->reference, sizeof e->reference, "%s", a->reference ? a->reference->label : "");
    e->specialise = s->specialise;
    e->model = *m;
    e->grid = *g;
    if (copy_result(&e->result, r) == 0) s->sweeps.count++;
}

long accuracy_reused_sweeps(const struct cl_session *s) { return s->sweep_reuses; }

void accuracy_forget_sweeps(struct cl_session *s)
{
    for (int i = 0; i < s->sweeps.count; i++) accuracy_result_free(&MEMO(s)[i].result);
    free(s->sweeps.items);
    s->sweeps = (struct cl_session_table){ NULL, 0, 0 };
}

int accuracy_run(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                 struct accuracy_result *out)
{
    for (int i = 0; i < a->s->sweeps.count; i++) {
        const struct sweep_memo *e = &MEMO(a->s)[i];
        if (!same_sweep(e, a, m, g)) continue;
        if (copy_result(out, &e->result)) {
            memset(out, 0, sizeof *out);
            return EXIT_RUNTIME;
        }
        a->s->sweep_reuses++;
        return 0;
    }
    int rc = accuracy_compute(a, m, g, out);
    if (rc == 0 && out->ok) remember(a, m, g, out);
    return rc;
}

/* The reference's values at the sweep's samples: the table holds, per n, the s of each sample
   (the first launch wrote them), replaced by f_ref(1 - s, n) in double rounded to float. Run by
   model_run_isolated in the reference's sandbox. */
struct table_fill {
    const struct model_spec *ref;
    const float *s, *n;
    long count, per_n;
};

static void fill_table(void *ctx, void *out_v)
{
    const struct table_fill *f = ctx;
    float *out = out_v;
    for (long i = 0; i < f->count; ++i)
        for (long k = 0; k < f->per_n; ++k) {
            size_t at = (size_t)i * (size_t)f->per_n + (size_t)k;
            out[at] = (float)model_eval_host(f->ref, 1.0 - (double)f->s[at], (double)f->n[i]);
        }
}

/* Launches the sweep over every n once (chunks work-items per n), adding its time to *seconds. */
static int launch_sweep(struct accuracy_ctx *a, cl_kernel sweep, long count, long chunks, const char *label,
                        double *seconds)
{
    cl_event ev = NULL;
    size_t local = chunks > 1 ? 256 : sweep_local_size(count, a->s->compute_units);
    size_t global = ((size_t)count * (size_t)chunks + local - 1) / local * local;
    double t0 = wall_seconds();
    int rc = clsession_launch(a->s, sweep, 1, &global, &local, label, &ev);
    if (rc == 0) {
        int used_wall = 0;
        double t = cl_event_seconds_or_wall(ev, wall_seconds() - t0, &used_wall);
        *seconds = isnan(*seconds) ? t : *seconds + t;
        a->timer_wall |= used_wall;
    }
    if (ev)
        clReleaseEvent(ev);
    return rc;
}

/* The reference table of a user-model reference: the samples' s from a first launch, their
   reference values from the host, written back for the comparing launch. */
static int reference_table(struct accuracy_ctx *a, cl_kernel sweep, const struct model_spec *ref, const float *nv,
                           long count, long chunks, long samples, cl_mem bt, double *seconds)
{
    int rc = 0;
    size_t points = (size_t)count * 2 * (size_t)samples;
    float *sv = malloc(points * sizeof *sv), *rv = malloc(points * sizeof *rv);
    cl_int pass = 0;
    if (!sv || !rv) {
        fprintf(stderr, "brdfbench: out of memory for the %zu values of %s\n", points, ref->label);
        rc = EXIT_RUNTIME;
        goto done;
    }
    CL_SET_ARGS_GOTO(done, sweep, 11, CL_ARG(pass));
    if ((rc = launch_sweep(a, sweep, count, chunks, ref->label, seconds)) != 0)
        goto done;
    CL_CHECK_GOTO(clEnqueueReadBuffer(a->s->queue, bt, CL_TRUE, 0, points * sizeof *sv, sv, 0, NULL, NULL), done);
    struct table_fill f = { ref, sv, nv, count, 2 * samples };
    if (model_run_isolated(ref, fill_table, &f, rv, points * sizeof *rv) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    CL_CHECK_GOTO(clEnqueueWriteBuffer(a->s->queue, bt, CL_TRUE, 0, points * sizeof *rv, rv, 0, NULL, NULL), done);
    pass = 1;
    CL_SET_ARGS_GOTO(done, sweep, 11, CL_ARG(pass));
done:
    free(rv);
    free(sv);
    return rc;
}

int accuracy_sweep_device(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                          float *raw, double *device_seconds)
{
    int rc = 0;
    cl_int e;
    cl_mem bn = NULL, bo = NULL, bt = NULL;
    cl_kernel sweep, probe_unused;
    float *nv = NULL, *chunked = NULL;
    *device_seconds = NAN;
    if ((rc = kernels_for(a, m, &sweep, &probe_unused)) != 0)
        return rc;
    struct model_spec ref;
    reference_of(a, m, &ref);
    long count = accuracy_grid_count(g);
    nv = malloc((size_t)count * sizeof *nv);
    if (!nv) {
        fprintf(stderr, "brdfbench: out of memory for %ld values of n\n", count);
        return EXIT_RUNTIME;
    }
    for (long i = 0; i < count; ++i)
        nv[i] = (float)accuracy_grid_n(g, i);
    bn = clCreateBuffer(a->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float), nv, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(n values)", done);
    long chunks = sweep_chunks(a->s, count, g->samples);
    size_t nout = (size_t)count * (size_t)chunks;
    bo = clCreateBuffer(a->s->ctx, CL_MEM_WRITE_ONLY, nout * ACC_OUT_STRIDE * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(sweep out)", done);
    cl_int id = m->info->kernel_id, ref_id = ref.info->kernel_id;
    float p0 = (float)m->params[0], p1 = (float)m->params[1];
    float rp0 = (float)ref.params[0], rp1 = (float)ref.params[1];
    cl_int ncount = (cl_int)count, samples = (cl_int)g->samples;
    CL_SET_ARGS_GOTO(done, sweep, 0, CL_ARG(id), CL_ARG(p0), CL_ARG(p1), CL_ARG(ref_id), CL_ARG(rp0), CL_ARG(rp1),
                     CL_ARG(bn), CL_ARG(ncount), CL_ARG(samples));
    cl_int chunks_arg = (cl_int)chunks;
    CL_SET_ARGS_GOTO(done, sweep, 9, CL_ARG(chunks_arg), CL_ARG(bo));
    if (accuracy_reference_is_table(&ref)) {   /* a user model's values, from the host (ACC_REF_TABLE) */
        char err[512];
        if (accuracy_reference_check(g, &ref, a->s, err, sizeof err)) {
            fprintf(stderr, "brdfbench: %s\n", err);
            rc = EXIT_USAGE;
            goto done;
        }
        bt = clCreateBuffer(a->s->ctx, CL_MEM_READ_WRITE, (size_t)count * 2 * (size_t)g->samples * sizeof(float),
                            NULL, &e);
        CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reference table)", done);
        CL_SET_ARGS_GOTO(done, sweep, 12, CL_ARG(bt));
        if ((rc = reference_table(a, sweep, &ref, nv, count, chunks, g->samples, bt, device_seconds)) != 0)
            goto done;
    }
    if ((rc = launch_sweep(a, sweep, count, chunks, m->label, device_seconds)) != 0)
        goto done;
    if (raw && chunks == 1) {
        CL_CHECK_GOTO(clEnqueueReadBuffer(a->s->queue, bo, CL_TRUE, 0, nout * ACC_OUT_STRIDE * sizeof(float), raw, 0,
                                          NULL, NULL), done);
    } else if (raw) {
        chunked = malloc(nout * ACC_OUT_STRIDE * sizeof *chunked);
        if (!chunked) {
            fprintf(stderr, "brdfbench: out of memory for the sweep's %zu chunk maxima\n", nout);
            rc = EXIT_RUNTIME;
            goto done;
        }
        CL_CHECK_GOTO(clEnqueueReadBuffer(a->s->queue, bo, CL_TRUE, 0, nout * ACC_OUT_STRIDE * sizeof(float), chunked,
                                          0, NULL, NULL), done);
        accuracy_merge_chunks(chunked, count, chunks, raw);
    }
done:
    if (bt) clReleaseMemObject(bt);
    if (bo) clReleaseMemObject(bo);
    if (bn) clReleaseMemObject(bn);
    free(nv);
    free(chunked);
    return rc;
}
