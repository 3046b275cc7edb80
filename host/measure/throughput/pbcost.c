/* pbcost.c - the physically based models' cost beside the lobes, He's terms per evaluation
 * and the white-furnace albedo at normal incidence (see pbcost.h); pbcost_report.c writes. */
#include "pbcost.h"
#include "runner.h"
#include "lcg.h"
#include "programs.h"

#include "exitcodes.h"
#include "outdir.h"
#include "stats.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

#define PBCOST_STREAMS 2       /* kernels/throughput.cl, TP_VEC_KERNEL */
#define PBCOST_LANES 16

void pbcost_options_default(struct pbcost_options *o)
{
    memset(o, 0, sizeof *o);
    o->n = 100;
    o->reps = 9;
    o->min_time = 0.02;
}

/* The rows: pow(), the lobes the papers compare with, then every physically based model of the
   registry (He once per material preset, its cost depends on the roughness). */
static int make_rows(struct pbcost_result *r)
{
    static const char *const lobes[] = { "phong", "blinn", "fq2" };
    struct pbcost_row *row = &r->rows[r->count++];
    model_spec_default(models_find("phong"), &row->spec);
    snprintf(row->name, sizeof row->name, "pow()");
    row->kind = 3;
    r->pow_row = 0;
    for (int i = 0; i < 3; ++i) {
        row = &r->rows[r->count];
        model_spec_default(models_find(lobes[i]), &row->spec);
        strcpy(row->name, row->spec.label);   /* a label fits: MODEL_LABEL_MAX < sizeof name */
        row->kind = row->spec.info->lobe == LOBE_PSI ? 0 : 1;
        if (strcmp(lobes[i], "fq2") == 0)
            r->fq2 = r->count;
        if (strcmp(lobes[i], "phong") == 0)
            r->phong = r->count;
        r->count++;
    }
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *info = models_at(i);
        if (info->family != MODEL_FAMILY_PHYSICAL)
            continue;
        int variants = info->kernel_id == BRDF_HE ? BRDF_HE_PRESETS : 1;
        for (int v = 0; v < variants && r->count < PBCOST_MAX_ROWS; ++v) {
            row = &r->rows[r->count++];
            model_spec_default(info, &row->spec);
            if (info->kernel_id == BRDF_HE) {
                char text[64], err[256];
                snprintf(text, sizeof text, "he:material=%d", v);
                if (model_spec_parse(text, &row->spec, err, sizeof err))
                    return EXIT_RUNTIME;
            }
            strcpy(row->name, row->spec.label);   /* a label fits: MODEL_LABEL_MAX < sizeof name */
            row->kind = 2;
            row->physical = 1;
        }
    }
    /* the user full BRDFs (GLSL/HLSL functions of vectors, .brdf files) and the measured tables */
    for (int i = 0; i < r->o.nfull && r->count < PBCOST_MAX_ROWS; ++i) {
        if (!model_is_full(r->o.full[i].info))
            continue;
        row = &r->rows[r->count++];
        row->spec = r->o.full[i];
        strcpy(row->name, row->spec.label);
        row->kind = 4;
    }
    for (int i = 0; i < r->o.nmeasured && r->count < PBCOST_MAX_ROWS; ++i) {
        row = &r->rows[r->count++];
        model_spec_default(models_find("phong"), &row->spec);   /* unused: n only */
        snprintf(row->name, sizeof row->name, "merl:%.*s", (int)sizeof row->name - 6, r->o.measured[i]->name);
        row->kind = 5;
        row->merl = r->o.measured[i];
    }
    return 0;
}

/* The double reference of a row at given cosines, as tp_vec_eval computes it on the device. */
static double row_eval_host(const struct pbcost_row *row, double nl, double nv, double lv, double n)
{
    if (row->kind == 2)
        return brdf_pb_eval(row->spec.info->kernel_id, nl, nv, lv, n, row->spec.params[0], row->spec.params[1]);
    if (!(nl > 0 && nv > 0))
        return 0;
    double c = row->kind == 1 ? (nl + nv) / sqrt(fmax(2 + 2 * lv, 1e-12)) : 2 * nl * nv - lv;
    if (row->kind == 3)
        return pow(fmax(c, 0.0), n);
    return model_eval_host(&row->spec, c, n);
}


/* Random unit vectors in the upper hemisphere (cosine >= 0.05 to z). */
static void hemi(uint64_t *st, double v[3])
{
    for (;;) {
        double x = 2 * lcg_unit(st) - 1, y = 2 * lcg_unit(st) - 1, z = lcg_unit(st);
        double l = sqrt(x * x + y * y + z * z);
        if (l > 1e-3 && l <= 1 && z / l >= 0.05) {
            v[0] = x / l;
            v[1] = y / l;
            v[2] = z / l;
            return;
        }
    }
}

/* Device against double at random (N = z, L, V): half of the V near L's mirror direction, so
   the highlights are sampled; the largest |difference| relative to the sample's peak. */
static void sample_pair(uint64_t *st, int i, double l[3], double v[3])
{
    hemi(st, l);
    if (i % 2) {
        double spread = 0.3 * lcg_unit(st);
        double d[3];
        hemi(st, d);
        v[0] = -l[0] + spread * (d[0] - 0.5);
        v[1] = -l[1] + spread * (d[1] - 0.5);
        v[2] = l[2];
        double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; ++k)
            v[k] /= len;
    } else {
        hemi(st, v);
    }
}

/* The double reference of a user full BRDF or a measured row at the device's float vectors,
   zeroed below the surface as tp_full_eval does. */
static double full_eval_host(const struct pbcost_row *row, const double L[3], const double V[3], const double N[3],
                             double n)
{
    double nl = L[0] * N[0] + L[1] * N[1] + L[2] * N[2], nv = V[0] * N[0] + V[1] * N[1] + V[2] * N[2];
    if (!(nl > 0 && nv > 0))
        return 0;
    return row->kind == 5 ? merl_luminance(row->merl, L, V, N) : model_eval_full_host(&row->spec, L, V, N, n);
}

/* The rows' double values at the check's points, P of them into out: run through
   model_run_isolated, so that a user model's code is called in one sandbox for all of them
   rather than in a round trip to it per value. g: a vector row's planes (Lxyz Vxyz Nxyz n);
   else the cosines nl, nv, lv, n. */
struct check_values_ctx {
    const struct pbcost_row *row;
    const float *g, *nl, *nv, *lv, *nn;
    int count;
};

static void check_values(void *vctx, void *vout)
{
    const struct check_values_ctx *c = vctx;
    double *out = vout;
    int P = c->count;
    for (int i = 0; i < P; ++i) {
        if (!c->g) {
            out[i] = row_eval_host(c->row, c->nl[i], c->nv[i], c->lv[i], c->nn[i]);
            continue;
        }
        double L[3], V[3], N[3];
        for (int j = 0; j < 3; ++j) {
            L[j] = c->g[j * P + i];
            V[j] = c->g[(3 + j) * P + i];
            N[j] = c->g[(6 + j) * P + i];
        }
        out[i] = full_eval_host(c->row, L, V, N, c->g[9 * P + i]);
    }
}

static int check_values_run(const struct check_values_ctx *c, double *out)
{
    if (c->row->kind == 5 || c->row->kind == 2 || c->row->kind == 3) {   /* measured, built-in, the power */
        check_values((void *)c, out);
        return 0;
    }
    return model_run_isolated(&c->row->spec, check_values, (void *)c, out, (size_t)c->count * sizeof *out);
}

/* check_row for the rows of vectors (kinds 4, 5): the same random pairs about N = z, passed as
   the vectors themselves (planes Lxyz Vxyz Nxyz n). */
static int check_full_row(struct cl_session *s, cl_program prog, struct pbcost_row *row, double n, cl_mem table)
{
    enum { P = PBCOST_CHECK_POINTS };
    static float g[10 * P], out[P];
    uint64_t st = 0x51ed2701a3b4c5d6ULL;
    for (int i = 0; i < P; ++i) {
        double l[3], v[3], nz[3] = { 0, 0, 1 };
        sample_pair(&st, i, l, v);
        for (int k = 0; k < 3; ++k) {
            g[k * P + i] = (float)l[k];
            g[(3 + k) * P + i] = (float)v[k];
            g[(6 + k) * P + i] = (float)nz[k];
        }
        g[9 * P + i] = (float)n;
    }
    char name[64];
    snprintf(name, sizeof name, "tp_full_points_%d", row->kind);
    int rc = 0;
    cl_int e;
    cl_mem b[2] = { NULL, NULL };
    cl_kernel k = clCreateKernel(prog, name, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateKernel(tp_full_points)", done);
    float p0 = (float)row->spec.params[0], p1 = (float)row->spec.params[1];
    cl_uint count = P;
    b[0] = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof g, g, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(tp_full_points input)", done);
    b[1] = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, sizeof out, NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(tp_full_points output)", done);
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(p0), CL_ARG(p1), CL_ARG(b[0]), CL_ARG(count), CL_ARG(b[1]), CL_ARG(table));
    size_t global = P / PBCOST_LANES;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &global, NULL, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clsession_finish(s, k, NULL), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(s->queue, b[1], CL_TRUE, 0, sizeof out, out, 0, NULL, NULL), done);
    static double host[P];
    double peak = 0, worst = 0;
    const struct check_values_ctx cv = { row, g, NULL, NULL, NULL, NULL, P };
    if ((rc = check_values_run(&cv, host)) != 0)
        goto done;
    for (int i = 0; i < P; ++i)
        peak = fmax(peak, fabs(host[i]));
    for (int i = 0; i < P; ++i) {
        double d = fabs(out[i] - host[i]) / fmax(peak, 1e-300);
        if (!(d <= worst))
            worst = d;   /* a NaN stays the worst */
    }
    row->check_max_abs_of_peak = worst;
    row->terms_mean = row->terms_max = NAN;
done:
    for (int j = 1; j >= 0; --j)
        if (b[j])
            clReleaseMemObject(b[j]);
    if (k)
        clReleaseKernel(k);
    return rc;
}

static int check_row(struct cl_session *s, cl_program prog, struct pbcost_row *row, double n)
{
    enum { P = PBCOST_CHECK_POINTS };
    static float nl[P], nv[P], lv[P], nn[P], out[P];
    uint64_t st = 0x51ed2701a3b4c5d6ULL;
    for (int i = 0; i < P; ++i) {
        double l[3], v[3];
        sample_pair(&st, i, l, v);
        nl[i] = (float)l[2];
        nv[i] = (float)v[2];
        lv[i] = (float)(l[0] * v[0] + l[1] * v[1] + l[2] * v[2]);
        nn[i] = (float)n;
    }
    char name[128];
    if (row->kind == 3)
        snprintf(name, sizeof name, "tp_vec_points_pow");
    else
        snprintf(name, sizeof name, "tp_vec_points_%d", row->spec.info->kernel_id);
    int rc = 0;
    cl_int e;
    cl_kernel k = clCreateKernel(prog, name, &e);
    cl_mem b[5] = { NULL };
    const float *src[4] = { nl, nv, lv, nn };
    CL_CHECK_ERR_GOTO(e, "clCreateKernel(tp_vec_points)", done);
    float p0 = (float)row->spec.params[0], p1 = (float)row->spec.params[1];
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(p0), CL_ARG(p1));
    for (int j = 0; j < 4; ++j) {
        b[j] = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof nl, (void *)src[j], &e);
        CL_CHECK_ERR_GOTO(e, "clCreateBuffer(tp_vec_points input)", done);
        CL_SET_ARGS_GOTO(done, k, (cl_uint)(2 + j), CL_ARG(b[j]));
    }
    b[4] = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, sizeof out, NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(tp_vec_points output)", done);
    CL_SET_ARGS_GOTO(done, k, 6, CL_ARG(b[4]));
    size_t global = P / PBCOST_LANES;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &global, NULL, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clsession_finish(s, k, NULL), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(s->queue, b[4], CL_TRUE, 0, sizeof out, out, 0, NULL, NULL), done);
    double peak = 0, worst = 0;
    static double host[P];
    const struct check_values_ctx cv = { row, NULL, nl, nv, lv, nn, P };
    if ((rc = check_values_run(&cv, host)) != 0)
        goto done;
    for (int i = 0; i < P; ++i)
        peak = fmax(peak, fabs(host[i]));
    row->terms_mean = row->terms_max = NAN;
    double tsum = 0, tmax = 0;
    for (int i = 0; i < P; ++i) {
        double h = host[i];
        double d = fabs(out[i] - h) / fmax(peak, 1e-300);
        if (!(d <= worst))
            worst = d;   /* a NaN stays the worst */
        if (row->kind == 2 && row->spec.info->kernel_id == BRDF_HE && nl[i] > 0 && nv[i] > 0) {
            int m = (int)row->spec.params[0];
            double t = 0;
            brdf_he_terms(nl[i], nv[i], lv[i], brdf_he_preset(m, 0), brdf_he_preset(m, 1), brdf_he_preset(m, 2),
                          brdf_he_preset(m, 3), brdf_he_preset(m, 4), 0.0, &t);
            tsum += t;
            tmax = fmax(tmax, t);
        }
    }
    row->check_max_abs_of_peak = worst;
    if (row->kind == 2 && row->spec.info->kernel_id == BRDF_HE) {
        row->terms_mean = tsum / P;
        row->terms_max = tmax;
    }
done:
    for (int j = 0; j < 5; ++j)
        if (b[j])
            clReleaseMemObject(b[j]);
    if (k)
        clReleaseKernel(k);
    return rc;
}

/* One launch of a row's throughput kernel with `iters` iterations; *seconds from the profiling
   events (wall time where the driver gives none). */
static int launch(struct cl_session *s, cl_kernel k, long iters, double *seconds, size_t global)
{
    int rc = 0;
    cl_int it = (cl_int)iters;
    float step = (float)(0.754877666 / (double)iters);
    cl_event ev = NULL;
    CL_SET_ARGS_GOTO(done, k, 3, CL_ARG(step), CL_ARG(it));
    /* each work-item is a long loop already (clsession_group_size: 1 on a CPU device) */
    size_t local;
    const size_t *lp = clsession_group_size(s, global, &local);
    double t0 = wall_seconds();
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &global, lp, 0, NULL, &ev), done);
    CL_CHECK_GOTO(clsession_finish(s, k, NULL), done);
    *seconds = cl_event_seconds_or_wall(ev, wall_seconds() - t0, NULL);
done:
    if (ev)
        clReleaseEvent(ev);
    return rc;
}

/* A row's kernel as an item of the runner. */
struct pbcost_launch {
    struct cl_session *s;
    cl_kernel k;
    size_t global;
};

static int pbcost_item_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    struct pbcost_launch *l = ctx;
    if (launch(l->s, l->k, iters, seconds, l->global)) {
        snprintf(reason, reason_len, "a launch failed (see stderr)");
        return -1;
    }
    return 0;
}

/* White-furnace albedo at normal incidence: 2 pi int_0^(pi/2) f(L = N, V(theta)) cos sin dtheta
   (with L = N the BRDF depends on theta_o alone), GSL adaptive quadrature in double with a
   break at the edge of He's 1-degree source cone. */
struct albedo_ctx { const struct pbcost_row *row; double n; };
static double albedo_integrand(double t, void *p)
{
    const struct albedo_ctx *a = p;
    double c = cos(t);
    return brdf_pb_eval(a->row->spec.info->kernel_id, 1.0, c, c, a->n, a->row->spec.params[0],
                        a->row->spec.params[1]) * c * sin(t);
}
static void albedo_row(struct pbcost_row *row, double n)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
    struct albedo_ctx a = { row, n };
    gsl_function f = { albedo_integrand, &a };
    double pts[3] = { 0, acos(BRDF_HE_SOURCE_COS), M_PI / 2 };
    double v = NAN, err = NAN;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    if (w && gsl_integration_qagp(&f, pts, 3, 1e-12, 1e-9, 2000, w, &v, &err) != 0 && !isfinite(v))
        v = NAN;
    gsl_set_error_handler(old);
    if (w)
        gsl_integration_workspace_free(w);
    row->albedo_normal = 2 * M_PI * v;
    row->albedo_normal_error = 2 * M_PI * err;
}

int pbcost_he_terms(double nl, double nv, double lv, double sigma0)
{
    double t = 0;
    brdf_he_terms(nl, nv, lv, brdf_he_preset(0, 0), sigma0, brdf_he_preset(0, 2), brdf_he_preset(0, 3),
                  brdf_he_preset(0, 4), 0.0, &t);
    return (int)t;
}

static void terms_table(struct pbcost_result *r)
{
    static const double th[PBCOST_TERMS_THETA] = { 0, 30, 60, 75, 85 };
    static const double ra[PBCOST_TERMS_RATIO] = { 0.01, 0.05, 0.1, 0.2, 0.5, 1.0 };
    double lambda = brdf_he_preset(0, 0);
    for (int i = 0; i < PBCOST_TERMS_THETA; ++i) {
        r->terms_theta[i] = th[i];
        double t = th[i] * M_PI / 180, to = fmin(th[i] + 20, 89) * M_PI / 180;
        for (int j = 0; j < PBCOST_TERMS_RATIO; ++j) {
            r->terms_ratio[j] = ra[j];
            /* mirror: L = (sin t, 0, cos t), V = (-sin t, 0, cos t); off: V at to in the plane */
            r->terms_mirror[i][j] = pbcost_he_terms(cos(t), cos(t), cos(2 * t), ra[j] * lambda);
            r->terms_off[i][j] = pbcost_he_terms(cos(t), cos(to), cos(t) * cos(to) - sin(t) * sin(to), ra[j] * lambda);
        }
    }
}

/* A row's throughput kernel (and a measured row's table, a dummy for a user BRDF's), its
   arguments set and its device values checked against the double reference. The caller
   releases *kern and *table. */
static int row_setup(struct cl_session *s, cl_program prog, const struct pbcost_options *o, struct pbcost_row *row,
                     cl_mem out, cl_kernel *kern, cl_mem *table)
{
    int rc = 0;
    cl_int e;
    char name[64];
    cl_program rprog = prog;   /* a user full BRDF: throughput.cl with its text (programs.h) */
    if (row->kind == 4 &&
        (rc = programs_program(s, "throughput.cl", "TP_FULL_MODEL_KERNELS(4)\n", "", &row->spec, NULL, &rprog)))
        return rc;
    if (row->kind == 3)
        snprintf(name, sizeof name, "tp_vec_pow");
    else if (row->kind >= 4)
        snprintf(name, sizeof name, "tp_full_%d", row->kind);
    else
        snprintf(name, sizeof name, "tp_vec_%d", row->spec.info->kernel_id);
    *kern = clCreateKernel(rprog, name, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateKernel(tp_vec)", done);
    float n = (float)o->n, p0 = (float)row->spec.params[0], p1 = (float)row->spec.params[1];
    CL_SET_ARGS_GOTO(done, *kern, 0, CL_ARG(n), CL_ARG(p0), CL_ARG(p1));
    CL_SET_ARGS_GOTO(done, *kern, 5, CL_ARG(out));
    if (row->kind >= 4) {
        if (row->kind == 5) {
            if ((rc = merl_table_buffer(s, row->merl, table)) != 0)
                return rc;
        } else {
            *table = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY, 16 * sizeof(float), NULL, &e);
            CL_CHECK_ERR_GOTO(e, "clCreateBuffer(physical dummy table)", done);
        }
        CL_SET_ARGS_GOTO(done, *kern, 6, CL_ARG(*table));
        rc = check_full_row(s, rprog, row, o->n, *table);
    } else {
        rc = check_row(s, prog, row, o->n);
    }
    if (rc)
        return rc;
    snprintf(row->status, sizeof row->status, "%s", row->check_max_abs_of_peak <= PBCOST_CHECK_TOL ? "ok" : "check");
done:
    return rc;
}

static int pbcost_measure(struct cl_session *s, const struct pbcost_options *o, struct pbcost_result *r)
{
    const int quiet = o->io.quiet;
    memset(r, 0, sizeof *r);
    r->o = *o;
    double t0 = wall_seconds();
    int rc = make_rows(r);
    if (rc)
        return rc;
    terms_table(r);
    for (int i = 0; i < r->count; ++i)
        r->rows[i].albedo_normal = r->rows[i].albedo_normal_error = NAN;
    for (int i = 0; i < r->count; ++i)
        if (r->rows[i].physical)
            albedo_row(&r->rows[i], o->n);

    /* one program: throughput.cl with a TP_VEC_MODEL_KERNELS line per model id */
    char extra[2048] = "";
    size_t used = 0;
    for (int i = 0; i < r->count; ++i)
        if (r->rows[i].kind == 5) {
            used += (size_t)snprintf(extra + used, sizeof extra - used, "TP_FULL_MODEL_KERNELS(5)\n");
            break;
        }
    for (int i = 0; i < r->count; ++i) {
        const struct pbcost_row *row = &r->rows[i];
        if (row->kind >= 3)
            continue;
        int dup = 0;
        for (int j = 0; j < i; ++j)
            dup |= r->rows[j].kind < 3 && r->rows[j].spec.info->kernel_id == row->spec.info->kernel_id;
        if (!dup)
            used += (size_t)snprintf(extra + used, sizeof extra - used, "TP_VEC_MODEL_KERNELS(%d, %d)\n",
                                     row->spec.info->kernel_id, row->kind);
    }
    cl_program prog = NULL;
    cl_kernel kern[PBCOST_MAX_ROWS] = { NULL };
    cl_mem table[PBCOST_MAX_ROWS] = { NULL };   /* a measured row's table; a small dummy else */
    cl_mem out = NULL;
    if (!quiet)
        fprintf(stderr, "physical: building the full-vector kernels...\n");
    if ((rc = clsession_build(s, "throughput.cl", extra, "", &prog)) != 0)
        return rc;
    r->work_items = o->work_items > 0 ? o->work_items : clsession_default_work_items(s, 65536);   /* throughput.h TP_MAX_WORK_ITEMS */
    size_t global = (size_t)r->work_items;
    cl_int e;
    out = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, global * PBCOST_LANES * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(physical out)", done);
    for (int i = 0; i < r->count; ++i)
        if ((rc = row_setup(s, prog, o, &r->rows[i], out, &kern[i], &table[i])) != 0)
            goto done;
    /* warm-up, calibration and the timed launches by the measurement runner (host/core/runner.h):
       the rows interleaved in a fresh random order each round, so that their ratios compare
       moments apart */
    {
        struct runner_item items[PBCOST_MAX_ROWS];
        struct pbcost_launch ctx[PBCOST_MAX_ROWS];
        memset(items, 0, sizeof items);
        for (int i = 0; i < r->count; ++i) {
            ctx[i] = (struct pbcost_launch){ s, kern[i], global };
            items[i] = (struct runner_item){ .name = r->rows[i].kind >= 4 ? r->rows[i].name : r->rows[i].spec.label,
                                             .launch = pbcost_item_launch,
                                             .ctx = &ctx[i], .calibrate = 1,
                                             .work_per_iter = (double)global * PBCOST_STREAMS * PBCOST_LANES,
                                             .cpu_threads = s->is_cpu ? (int)s->compute_units : 0 };
        }
        struct runner run;
        runner_init(&run, items, r->count);
        run.rounds = o->reps;
        run.min_time = o->min_time;
        /* the pow() row is every round's reference: the rows' rates over its rate in the same
           round cancel the machine's drift, and the ratios between rows are taken on those */
        run.reference = r->pow_row;
        if (runner_run(&run)) {
            runner_release(&run);
            rc = EXIT_RUNTIME;
            goto done;
        }
        for (int i = 0; i < r->count && rc == 0; ++i) {
            struct pbcost_row *row = &r->rows[i];
            const struct runner_item *it = &items[i];
            if (!it->ok || it->nreps == 0) {
                fprintf(stderr, "brdfbench: physical: %s: %s\n", row->name, it->reason);
                rc = EXIT_RUNTIME;
                break;
            }
            double *v = it->seconds;
            int k = it->nreps;
            qsort(v, (size_t)k, sizeof *v, stats_cmp_double);
            row->iters = it->iters;
            row->evals_per_launch = (double)global * (double)row->iters * PBCOST_STREAMS * PBCOST_LANES;
            row->min_s = v[0];
            row->max_s = v[k - 1];
            row->med_s = stats_median_sorted(v, (size_t)k);
            row->evals_per_s = row->med_s > 0 ? row->evals_per_launch / row->med_s : NAN;
            row->evals_per_s_fastest = row->min_s > 0 ? row->evals_per_launch / row->min_s : NAN;
            /* per CPU second where the runner keeps it (a CPU device: another process's share of
               the cores stretches a launch's wall time but hardly its CPU time) */
            const double *norm = it->cpu_norm ? it->cpu_norm : it->norm;
            row->nnorm = norm ? (k < PBCOST_MAX_REPS ? k : PBCOST_MAX_REPS) : 0;
            for (int j = 0; j < row->nnorm; ++j)
                row->norm_reps[j] = norm[j];
        }
        runner_release(&run);
        if (rc)
            goto done;
    }
    /* compare's rule on the normalised repetitions: each row against fq2 and against Phong */
    for (int i = 0; i < r->count; ++i) {
        struct pbcost_row *row = &r->rows[i];
        const struct pbcost_row *fq2 = &r->rows[r->fq2], *ph = &r->rows[r->phong], *pw = &r->rows[r->pow_row];
        struct compare_speed to_pow;
        compare_speed_rule(row->norm_reps, row->nnorm, fq2->norm_reps, fq2->nnorm, CMP_DEFAULT_ALPHA,
                           CMP_DEFAULT_THRESHOLD, &row->vs_fq2);
        compare_speed_rule(row->norm_reps, row->nnorm, ph->norm_reps, ph->nnorm, CMP_DEFAULT_ALPHA,
                           CMP_DEFAULT_THRESHOLD, &row->vs_phong);
        compare_speed_rule(row->norm_reps, row->nnorm, pw->norm_reps, pw->nnorm, CMP_DEFAULT_ALPHA,
                           CMP_DEFAULT_THRESHOLD, &to_pow);
        row->ratio_to_fq2 = row->vs_fq2.ratio;
        row->ratio_to_phong = row->vs_phong.ratio;
        row->ratio_to_pow = to_pow.ratio;
    }
    r->seconds = wall_seconds() - t0;
done:
    for (int i = 0; i < PBCOST_MAX_ROWS; ++i) {
        if (kern[i])
            clReleaseKernel(kern[i]);
        if (table[i])
            clReleaseMemObject(table[i]);
    }
    if (out)
        clReleaseMemObject(out);
    if (prog)
        clReleaseProgram(prog);
    return rc;
}

int pbcost_run(struct cl_session *s, const struct pbcost_options *o, struct pbcost_result *r)
{
    int rc = pbcost_measure(s, o, r);
    if (rc || !o->io.out_dir)
        return rc;
    char path[4200], err[512];
    path_join(path, sizeof path, o->io.out_dir, "physical.json");
    if (pbcost_write_json(path, s, r, NULL, err, sizeof err)) {
        fprintf(stderr, "brdfbench: %s\n", err);
        return EXIT_RUNTIME;
    }
    if (!o->io.quiet)
        pbcost_print_table(stdout, r);
    return 0;
}
