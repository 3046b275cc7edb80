/* energy.c - device quadrature (eq. 11 terms, directional albedo), closed forms at normal
 * incidence, the reciprocity check, and energy.json. See energy.h. */
#include "energy.h"
#include "lcg.h"
#include "energy_report.h"
#include "accuracy.h"
#include "context.h"
#include "exitcodes.h"
#include "outdir.h"
#include "stats.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double half_pi = 1.57079632679489661923;
static const double two_pi = 6.28318530717958647692;
#define BRDF_PI_D 3.14159265358979323846

#define EQ11_PANELS 8          /* geometric panels of n for the outer sum */
#define EQ11_OUTER_ORDER 32
#define EQ11_INNER_ORDER 32
#define RECIP_PAIRS 8192
/* Agreement expected between the float device quadrature and a closed form, and between a
 * quadrature and its refinement (panels split, twice the azimuth points). */
#define ENERGY_TOLERANCE 2e-5

/* The configurations of the albedo tables. */
static const double energy_n[ENERGY_N_COUNT] = { 2, 4, 10, 100, 1000 };

int integrate_open(struct integrate_ctx *c, struct cl_session *s)
{
    memset(c, 0, sizeof *c);
    c->s = s;
    static const char *const names[] = { "eq11_terms", "albedo_partial", "reciprocity_pairs" };
    cl_kernel *const kernels[] = { &c->eq11, &c->albedo, &c->recip };
    return clsession_build_kernels(s, "integrate.cl", NULL, "", &c->program, 3, names, kernels);
}

void integrate_close(struct integrate_ctx *c)
{
    cl_kernel *const kernels[] = { &c->eq11, &c->albedo, &c->recip };
    clsession_release_kernels(&c->program, 3, kernels);
}

/* Gauss-Legendre node i of order `order` on [a, b] (GSL's fixed tables). */
static int gl_nodes(int order, double a, double b, double *x, double *w)
{
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc((size_t)order);
    if (!t)
        return -1;
    for (int i = 0; i < order; ++i)
        gsl_integration_glfixed_point(a, b, (size_t)i, &x[i], &w[i], t);
    gsl_integration_glfixed_table_free(t);
    return 0;
}

int integrate_eq11_device(struct integrate_ctx *c, double zone_k, double n_lo, double n_hi, double out[EQ11_TERMS])
{
    int rc = 0;
    cl_int e;
    cl_mem bn = NULL, bt = NULL, bw = NULL, bo = NULL;
    enum { NN = EQ11_PANELS * EQ11_OUTER_ORDER };
    double nx[NN], nw[NN], tx[EQ11_INNER_ORDER], tw[EQ11_INNER_ORDER];
    float fn[NN], ft[EQ11_INNER_ORDER], fw[EQ11_INNER_ORDER], fo[EQ11_TERMS * NN];
    /* The terms fall like 1/n: panels equal in log n keep each one equally smooth. */
    double r = pow(n_hi / n_lo, 1.0 / EQ11_PANELS);
    for (int p = 0; p < EQ11_PANELS; ++p) {
        double a = n_lo * pow(r, p), b = (p == EQ11_PANELS - 1) ? n_hi : n_lo * pow(r, p + 1);
        if (gl_nodes(EQ11_OUTER_ORDER, a, b, nx + p * EQ11_OUTER_ORDER, nw + p * EQ11_OUTER_ORDER))
            return EXIT_RUNTIME;
    }
    if (gl_nodes(EQ11_INNER_ORDER, 0.0, 1.0, tx, tw))
        return EXIT_RUNTIME;
    for (int i = 0; i < NN; ++i)
        fn[i] = (float)nx[i];
    for (int i = 0; i < EQ11_INNER_ORDER; ++i) {
        ft[i] = (float)tx[i];
        fw[i] = (float)tw[i];
    }
    bn = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof fn, fn, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(eq11 n)", done);
    bt = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof ft, ft, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(eq11 t)", done);
    bw = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof fw, fw, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(eq11 w)", done);
    bo = clCreateBuffer(c->s->ctx, CL_MEM_WRITE_ONLY, sizeof fo, NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(eq11 out)", done);
    float k = (float)zone_k;
    cl_int count = NN, tcount = EQ11_INNER_ORDER;
    CL_SET_ARGS_GOTO(done, c->eq11, 0, CL_ARG(k), CL_ARG(bn), CL_ARG(count), CL_ARG(bt), CL_ARG(bw), CL_ARG(tcount),
                     CL_ARG(bo));
    size_t global = NN;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(c->s->queue, c->eq11, 1, NULL, &global, NULL, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clsession_finish(c->s, c->eq11, NULL), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(c->s->queue, bo, CL_TRUE, 0, sizeof fo, fo, 0, NULL, NULL), done);
    for (int j = 0; j < EQ11_TERMS; ++j) {   /* enum eq11_term's order */
        double sum = 0;
        for (int i = 0; i < NN; ++i)
            sum += nw[i] * (double)fo[EQ11_TERMS * i + j];
        out[j] = sum;
    }
done:
    if (bo) clReleaseMemObject(bo);
    if (bw) clReleaseMemObject(bw);
    if (bt) clReleaseMemObject(bt);
    if (bn) clReleaseMemObject(bn);
    return rc;
}

int albedo_mode_of(const struct model_info *m)
{
    if (m->family == MODEL_FAMILY_MICROFACET)
        return ALBEDO_MICRO;
    if (m->family == MODEL_FAMILY_NORMALISED)
        return m->lobe == LOBE_PSI ? ALBEDO_PSI : ALBEDO_HALF;
    return -1;
}

/* The first polar angle where the lobe is exactly 0 (a quadratic past its root), or NAN. */
static double lobe_zero(const struct model_spec *m, double n)
{
    enum { SCAN = 4096 };
    double prev = 0;
    for (int j = 1; j <= SCAN; ++j) {
        double x = half_pi * j / SCAN;
        if (model_eval_host(m, cos(x), n) == 0.0) {
            double lo = prev, hi = x;
            for (int it = 0; it < 80; ++it) {
                double mid = 0.5 * (lo + hi);
                if (model_eval_host(m, cos(mid), n) == 0.0) hi = mid; else lo = mid;
            }
            return hi;
        }
        prev = x;
    }
    return NAN;
}

/* Panels of the polar angle for one configuration: graded from the lobe's width (the
 * epicentre end x_e(n)) by doublings to pi/2, plus the kinks of the integrand. Writes
 * ENERGY_MAX_NODES nodes and weights (unused ones with weight 0). refine splits every panel. */
static int polar_nodes(const struct model_spec *m, int mode, double n, double theta_i, int refine, double *x,
                       double *w)
{
    double edges[2 * ENERGY_MAX_PANELS + 8];
    int ne = 0;
    double s = zone_epicentre_end(n);
    edges[ne++] = 0.0;
    edges[ne++] = half_pi;
    for (double e = s / 4; e < half_pi && ne < ENERGY_MAX_PANELS - 6; e *= 2)
        edges[ne++] = e;
    if (mode == ALBEDO_PSI) {
        if (theta_i > 0) edges[ne++] = half_pi - theta_i;   /* the lobe's hemisphere meets the horizon */
    } else if (mode == ALBEDO_HALF || mode == ALBEDO_MICRO) {
        edges[ne++] = 0.5 * (half_pi - theta_i);             /* V on the horizon in L's plane */
        edges[ne++] = 0.5 * (half_pi + theta_i);
    }
    double z = lobe_zero(m, n);
    if (isfinite(z)) edges[ne++] = z;
    qsort(edges, (size_t)ne, sizeof edges[0], stats_cmp_double);
    int kept = 0;
    for (int i = 0; i < ne; ++i)
        if (edges[i] >= 0 && edges[i] <= half_pi && (kept == 0 || edges[i] - edges[kept - 1] > 1e-9))
            edges[kept++] = edges[i];
    if (refine) {
        double fine[2 * ENERGY_MAX_PANELS + 8];
        int nf = 0;
        for (int i = 0; i + 1 < kept; ++i) {
            fine[nf++] = edges[i];
            fine[nf++] = 0.5 * (edges[i] + edges[i + 1]);
        }
        fine[nf++] = edges[kept - 1];
        memcpy(edges, fine, (size_t)nf * sizeof edges[0]);
        kept = nf;
    }
    int panels = kept - 1;
    if (panels > ENERGY_MAX_PANELS)
        return -1;
    for (int i = 0; i < ENERGY_MAX_NODES; ++i)
        x[i] = w[i] = 0.0;
    for (int p = 0; p < panels; ++p)
        if (gl_nodes(ENERGY_GL_ORDER, edges[p], edges[p + 1], x + p * ENERGY_GL_ORDER, w + p * ENERGY_GL_ORDER))
            return -1;
    return 0;
}

static int albedo_device_ex(struct integrate_ctx *c, const struct model_spec *m, int mode, const double *n,
                            const double *theta_i, int count, int refine, double *out)
{
    int rc = 0;
    cl_int e;
    cl_mem bn = NULL, bt = NULL, bx = NULL, bw = NULL, bo = NULL;
    size_t total = (size_t)count * ENERGY_MAX_NODES;
    float *fn = malloc((size_t)count * sizeof *fn), *ft = malloc((size_t)count * sizeof *ft);
    float *fx = malloc(total * sizeof *fx), *fw = malloc(total * sizeof *fw), *fo = malloc(total * sizeof *fo);
    double x[ENERGY_MAX_NODES], w[ENERGY_MAX_NODES];
    if (!fn || !ft || !fx || !fw || !fo) {
        fprintf(stderr, "brdfbench: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (int i = 0; i < count; ++i) {
        fn[i] = (float)n[i];
        ft[i] = (float)theta_i[i];
        if (polar_nodes(m, mode, n[i], theta_i[i], refine, x, w)) {
            fprintf(stderr, "brdfbench: albedo quadrature: too many panels for %s at n = %g\n", m->label, n[i]);
            rc = EXIT_RUNTIME;
            goto done;
        }
        for (int p = 0; p < ENERGY_MAX_NODES; ++p) {
            fx[(size_t)i * ENERGY_MAX_NODES + p] = (float)x[p];
            fw[(size_t)i * ENERGY_MAX_NODES + p] = (float)w[p];
        }
    }
    bn = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float), fn, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(albedo n)", done);
    bt = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float), ft, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(albedo theta_i)", done);
    bx = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, total * sizeof(float), fx, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(albedo nodes)", done);
    bw = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, total * sizeof(float), fw, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(albedo weights)", done);
    bo = clCreateBuffer(c->s->ctx, CL_MEM_WRITE_ONLY, total * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(albedo out)", done);
    cl_int id = m->info->kernel_id, md = mode, nodes = ENERGY_MAX_NODES;
    cl_int phi = refine ? 2 * ENERGY_PHI_COUNT : ENERGY_PHI_COUNT;
    float p0 = (float)m->params[0], p1 = (float)m->params[1];
    CL_SET_ARGS_GOTO(done, c->albedo, 0, CL_ARG(id), CL_ARG(p0), CL_ARG(p1), CL_ARG(md), CL_ARG(bn), CL_ARG(bt),
                     CL_ARG(bx), CL_ARG(bw), CL_ARG(nodes), CL_ARG(phi), CL_ARG(bo));
    size_t global[2] = { ENERGY_MAX_NODES, (size_t)count };
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(c->s->queue, c->albedo, 2, NULL, global, NULL, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clsession_finish(c->s, c->albedo, m->label), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(c->s->queue, bo, CL_TRUE, 0, total * sizeof(float), fo, 0, NULL, NULL), done);
    for (int i = 0; i < count; ++i) {
        double sum = 0;
        for (int p = 0; p < ENERGY_MAX_NODES; ++p)
            sum += (double)fo[(size_t)i * ENERGY_MAX_NODES + p];
        out[i] = sum;
    }
done:
    if (bo) clReleaseMemObject(bo);
    if (bw) clReleaseMemObject(bw);
    if (bx) clReleaseMemObject(bx);
    if (bt) clReleaseMemObject(bt);
    if (bn) clReleaseMemObject(bn);
    free(fo);
    free(fw);
    free(fx);
    free(ft);
    free(fn);
    return rc;
}

int albedo_device(struct integrate_ctx *c, const struct model_spec *m, int mode, const double *n,
                  const double *theta_i, int count, double *out)
{
    return albedo_device_ex(c, m, mode, n, theta_i, count, 0, out);
}

/* int_0^1 (k(u-1) + 1)^2 u du with the quadratic zeroed past u0 = 1 - 1/k: with t = 1 - u,
 * int_0^T (1 - k t)^2 (1 - t) dt, T = min(1, 1/k):
 *   k <= 1: 1/2 - k/3 + k^2/12;   k >= 1: 1/(3k) - 1/(12 k^2). */
static double quadratic_moment(double k)
{
    return k <= 1.0 ? 0.5 - k / 3.0 + k * k / 12.0 : 1.0 / (3.0 * k) - 1.0 / (12.0 * k * k);
}

static double albedo_one(double n)
{
    (void)n;
    return 1.0;
}

/* Paper 2's coefficients (docs/definitions.md): coef(n) = 0.214 (0.807 + n), k(n) = 0.448 n + 0.099. */
static double fq2n_albedo(double n)
{
    return 0.214 * (0.807 + n) * two_pi * quadratic_moment(0.448 * n + 0.099);
}

/* int_{theta_h < pi/4} D cos dw = 1 - exp(-tan^2(pi/4)/alpha^2), alpha^2 = 2/(n+2). */
static double beckmann_albedo(double n)
{
    return -expm1(-(n + 2.0) / 2.0);
}

static double ggx_albedo(double n)
{
    return (n + 2.0) / (n + 4.0);
}

/* The models whose normal-incidence albedo has a closed form: its value at n and how it is derived. */
static const struct {
    const char *id;
    double (*value)(double n);
    const char *derivation;
} closed_forms[] = {
    { "phongn", albedo_one, "(n+2)/(2 pi) 2 pi int_0^1 u^(n+1) du = 1 (R = N, the lobe fits in the hemisphere)" },
    { "blinnn", albedo_one,
      "Giesen: 2 pi int_0^(pi/2) cos^n(theta_o/2) cos(theta_o) sin(theta_o) dtheta_o = "
      "8 pi (2^(-n/2) + n)/((n+2)(n+4)), the normalisation's inverse" },
    { "fq2n", fq2n_albedo,
      "0.214 (0.807 + n) 2 pi int_0^1 ((0.448n + 0.099)(u-1) + 1)^2 u du, the quadratic "
      "zeroed past its root: a polynomial integral" },
    { "beckmann", beckmann_albedo,
      "int over theta_h < pi/4 (V above the horizon) of D cos(theta_h) dw_h = "
      "1 - exp(-1/alpha^2) = 1 - exp(-(n+2)/2)" },
    { "ggx", ggx_albedo,
      "int over theta_h < pi/4 of D cos(theta_h) dw_h = tan^2(pi/4)/(alpha^2 + tan^2(pi/4)) "
      "= (n+2)/(n+4)" },
};

int albedo_closed_form_normal(const struct model_spec *m, int mode, double n, double *value, const char **derivation)
{
    if (mode == ALBEDO_DCOS) {
        *value = 1.0;
        *derivation = "int D cos(theta_h) dw_h = 1: the normalisation of a microfacet distribution";
        return 1;
    }
    for (size_t i = 0; i < sizeof closed_forms / sizeof closed_forms[0]; ++i)
        if (strcmp(m->info->id, closed_forms[i].id) == 0) {
            *value = closed_forms[i].value(n);
            *derivation = closed_forms[i].derivation;
            return 1;
        }
    return 0;
}

/* ---- reciprocity -------------------------------------------------------------------------- */


static void unit_sphere(uint64_t *st, double v[3])
{
    double z = 2 * lcg_unit(st) - 1, phi = two_pi * lcg_unit(st), r = sqrt(fmax(0, 1 - z * z));
    v[0] = r * cos(phi);
    v[1] = r * sin(phi);
    v[2] = z;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A direction in N's hemisphere: uniform, or (near) within `spread` of the direction `around`. */
static void hemisphere_dir(uint64_t *st, const double nrm[3], const double *around, double spread, double v[3])
{
    for (int tries = 0; tries < 1000; ++tries) {
        if (around) {
            double u[3];
            unit_sphere(st, u);
            double s = spread * lcg_unit(st);
            for (int i = 0; i < 3; ++i)
                v[i] = around[i] + s * u[i];
        } else {
            unit_sphere(st, v);
        }
        double len = sqrt(dot3(v, v));
        for (int i = 0; i < 3; ++i)
            v[i] /= len;
        if (dot3(v, nrm) > 1e-3)
            return;
    }
    memcpy(v, nrm, 3 * sizeof(double));
}

static double lobe_cosine_host(int lobe, const double nrm[3], const double l[3], const double v[3])
{
    if (lobe == LOBE_PSI) {
        double r[3], nl = dot3(nrm, l);
        for (int i = 0; i < 3; ++i)
            r[i] = 2 * nl * nrm[i] - l[i];
        return dot3(r, v);
    }
    double h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
    double len = sqrt(dot3(h, h));
    for (int i = 0; i < 3; ++i)
        h[i] /= len;
    return dot3(nrm, h);
}

static void keep_worst(struct recip_worst *w, double diff, double n, const double *dirs, double a, double b)
{
    if (!(diff <= w->diff)) {
        w->diff = diff;
        w->n = n;
        memcpy(w->nrm, dirs, 3 * sizeof(double));
        memcpy(w->l, dirs + 3, 3 * sizeof(double));
        memcpy(w->v, dirs + 6, 3 * sizeof(double));
        w->f_lv = a;
        w->f_vl = b;
    }
}

int reciprocity_check(struct integrate_ctx *c, const struct model_spec *m, long pairs, struct recip_worst *device,
                      struct recip_worst *host)
{
    int rc = 0;
    cl_int e;
    cl_mem bd = NULL, bn = NULL, bo = NULL;
    double *dirs = malloc((size_t)pairs * 9 * sizeof *dirs), *nv = malloc((size_t)pairs * sizeof *nv);
    float *fd = malloc((size_t)pairs * 9 * sizeof *fd), *fn = malloc((size_t)pairs * sizeof *fn);
    float *fo = malloc((size_t)pairs * RECIP_STRIDE * sizeof *fo);
    memset(device, 0, sizeof *device);
    memset(host, 0, sizeof *host);
    device->diff = host->diff = -1;   /* the first pair is always kept */
    if (!dirs || !nv || !fd || !fn || !fo) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    uint64_t st = 0x2545f4914f6cdd1dULL;
    for (long i = 0; i < pairs; ++i) {
        double *d = dirs + 9 * i;
        /* n log-uniform over [2, 1000]; half the pairs with V near the mirror direction of L,
           where the lobe is not 0, the other half uniform over the hemisphere. */
        nv[i] = 2.0 * pow(500.0, lcg_unit(&st));
        unit_sphere(&st, d);
        hemisphere_dir(&st, d, NULL, 0, d + 3);
        double r[3], nl = dot3(d, d + 3);
        for (int k = 0; k < 3; ++k)
            r[k] = 2 * nl * d[k] - d[3 + k];
        hemisphere_dir(&st, d, (i % 2) ? r : NULL, 3.0 * zone_epicentre_end(nv[i]), d + 6);
        for (int k = 0; k < 9; ++k)
            fd[9 * i + k] = (float)d[k];
        fn[i] = (float)nv[i];
        nv[i] = fn[i];   /* the host sees the n the device sees */
    }
    bd = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)pairs * 9 * sizeof(float), fd, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity dirs)", done);
    bn = clCreateBuffer(c->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)pairs * sizeof(float), fn, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity n)", done);
    bo = clCreateBuffer(c->s->ctx, CL_MEM_WRITE_ONLY, (size_t)pairs * RECIP_STRIDE * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity out)", done);
    cl_int id = m->info->kernel_id, lobe = m->info->lobe == LOBE_PSI ? 0 : 1, count = (cl_int)pairs;
    float p0 = (float)m->params[0], p1 = (float)m->params[1];
    CL_SET_ARGS_GOTO(done, c->recip, 0, CL_ARG(id), CL_ARG(p0), CL_ARG(p1), CL_ARG(lobe), CL_ARG(bd), CL_ARG(bn),
                     CL_ARG(count), CL_ARG(bo));
    size_t global = (size_t)pairs;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(c->s->queue, c->recip, 1, NULL, &global, NULL, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clsession_finish(c->s, c->recip, m->label), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(c->s->queue, bo, CL_TRUE, 0, (size_t)pairs * RECIP_STRIDE * sizeof(float), fo, 0, NULL,
                                      NULL), done);
    for (long i = 0; i < pairs; ++i) {
        double dd[9];
        for (int k = 0; k < 9; ++k)
            dd[k] = fd[9 * i + k];   /* the float directions both sides used */
        double peak = fabs(model_eval_host(m, 1.0, nv[i]));
        if (!(peak > 0))
            peak = 1.0;
        const float lv = fo[RECIP_STRIDE * i + RECIP_LV], vl = fo[RECIP_STRIDE * i + RECIP_VL];   /* f(L, V), f(V, L) */
        keep_worst(device, fabs((double)lv - (double)vl) / peak, nv[i], dd, lv, vl);
        int lb = m->info->lobe;
        double a = model_eval_host(m, lobe_cosine_host(lb, dd, dd + 3, dd + 6), nv[i]);
        double b = model_eval_host(m, lobe_cosine_host(lb, dd, dd + 6, dd + 3), nv[i]);
        keep_worst(host, fabs(a - b) / peak, nv[i], dd, a, b);
        device->eval_error = fmax(device->eval_error, fmax(fabs(lv - a), fabs(vl - b)) / peak);
    }
done:
    if (bo) clReleaseMemObject(bo);
    if (bn) clReleaseMemObject(bn);
    if (bd) clReleaseMemObject(bd);
    free(fo);
    free(fn);
    free(fd);
    free(nv);
    free(dirs);
    return rc;
}

/* ---- energy_run: tables and checks (energy_report.c writes them) -------------------------- */

int energy_run(struct cl_session *s, const char *out_dir, int quiet, struct energy_summary *summary)
{
    struct energy_summary *local = NULL;
    struct energy_summary *sum = summary;
    if (!sum) {
        local = calloc(1, sizeof *local);
        if (!local)
            return EXIT_RUNTIME;
        sum = local;
    }
    memset(sum, 0, sizeof *sum);
    double t0 = wall_seconds();
    struct integrate_ctx ic;
    int rc = integrate_open(&ic, s);
    if (rc) {
        free(local);
        return rc;
    }
    enum { CFG = ENERGY_N_COUNT * ENERGY_THETA_COUNT };
    double cn[CFG], cti[CFG], fine[CFG];
    for (int i = 0; i < ENERGY_N_COUNT; ++i) {
        sum->table_n[i] = energy_n[i];
        for (int j = 0; j < ENERGY_THETA_COUNT; ++j) {
            cn[i * ENERGY_THETA_COUNT + j] = (double)(float)energy_n[i];
            cti[i * ENERGY_THETA_COUNT + j] = 5.0 * j * BRDF_PI_D / 180.0;
        }
    }
    sum->all_closed_forms_agree = 1;
    sum->quadrature_tolerance = ENERGY_TOLERANCE;
    /* Every normalised or microfacet model of the registry; microfacet ones twice (their
       albedo, and their normalisation D cos theta_h). */
    for (int mi = 0; mi < models_count() && sum->count < ENERGY_MAX_MODELS; ++mi) {
        const struct model_info *info = models_at(mi);
        int base_mode = albedo_mode_of(info);
        if (base_mode < 0)
            continue;
        for (int pass = 0; pass < (base_mode == ALBEDO_MICRO ? 2 : 1); ++pass) {
            int mode = pass ? ALBEDO_DCOS : base_mode;
            struct energy_model_summary *ms = &sum->models[sum->count];
            model_spec_default(info, &ms->spec);
            ms->mode = mode;
            ms->normal_max_diff = ms->dcos_max_diff = NAN;
            int count = mode == ALBEDO_DCOS ? ENERGY_N_COUNT : CFG;
            double *nn = cn, *tt = cti;
            double dn[ENERGY_N_COUNT], dt[ENERGY_N_COUNT];
            if (mode == ALBEDO_DCOS) {   /* independent of theta_i */
                for (int i = 0; i < ENERGY_N_COUNT; ++i) {
                    dn[i] = (double)(float)energy_n[i];
                    dt[i] = 0;
                }
                nn = dn;
                tt = dt;
            }
            double *val = ms->albedo;
            if ((rc = albedo_device_ex(&ic, &ms->spec, mode, nn, tt, count, 0, val)) != 0 ||
                (rc = albedo_device_ex(&ic, &ms->spec, mode, nn, tt, count, 1, fine)) != 0)
                goto done;
            ms->max_albedo = -1;
            ms->refine_change = 0;
            for (int i = 0; i < count; ++i) {
                ms->refine_change = fmax(ms->refine_change, fabs(fine[i] - val[i]));
                if (val[i] > ms->max_albedo) {
                    ms->max_albedo = val[i];
                    ms->max_at_n = nn[i];
                    ms->max_at_theta_deg = tt[i] * 180.0 / BRDF_PI_D;
                }
            }
            int cols = mode == ALBEDO_DCOS ? 1 : ENERGY_THETA_COUNT;
            ms->cols = cols;
            double worst = -1;
            for (int i = 0; i < ENERGY_N_COUNT; ++i) {
                double cf;
                const char *why;
                double dev = val[i * cols];
                ms->normal_n[i] = nn[i * cols];
                ms->normal_closed[i] = NAN;
                ms->normal_derivation[i] = NULL;
                if (albedo_closed_form_normal(&ms->spec, mode, nn[i * cols], &cf, &why)) {
                    double d = fabs(dev - cf);
                    ms->normal_closed[i] = cf;
                    ms->normal_derivation[i] = why;
                    if (d > worst) {
                        worst = d;
                        ms->normal_diff_at_n = nn[i * cols];
                    }
                }
            }
            if (worst >= 0) {
                ms->normal_max_diff = worst;
                if (mode == ALBEDO_DCOS)
                    ms->dcos_max_diff = worst;
                if (worst > ENERGY_TOLERANCE)
                    sum->all_closed_forms_agree = 0;
            }
            sum->count++;
        }
    }

    sum->recip_pairs = RECIP_PAIRS;
    for (int mi = 0; mi < models_count() && sum->recip_count < ENERGY_MAX_MODELS; ++mi) {
        struct recip_summary *rs = &sum->recip[sum->recip_count];
        model_spec_default(models_at(mi), &rs->spec);
        if ((rc = reciprocity_check(&ic, &rs->spec, RECIP_PAIRS, &rs->device, &rs->host)) != 0)
            goto done;
        sum->recip_count++;
    }

    if ((rc = reciprocity_image_pass(s, RECIP_PAIRS, sum->pass, ENERGY_MAX_MODELS, &sum->pass_count)) != 0)
        goto done;
    sum->seconds = wall_seconds() - t0;
    rc = energy_write(s, sum, summary != NULL, out_dir);
    if (rc == 0 && !quiet)
        energy_print_table(stdout, sum);
done:
    integrate_close(&ic);
    free(local);
    return rc;
}

/* ---- reciprocity of the image pass ---------------------------------------------------------- */
#include "raster.h"
#include "render.h"

/* The reciprocity pass's G-buffer: random pixels in front of the eye at the origin, lit by the
   lamp, each with its n and a normal facing both (half of them near the half vector). */
static void recip_gbuffer(struct gbuffer *g, long pairs, const double eye[3], const double lamp[3])
{
    uint64_t st = 0x9e3779b97f4a7c15ULL;
    float *px = gbuffer_plane(g, GB_PX), *py = gbuffer_plane(g, GB_PY), *pz = gbuffer_plane(g, GB_PZ);
    float *nx = gbuffer_plane(g, GB_NX), *ny = gbuffer_plane(g, GB_NY), *nz = gbuffer_plane(g, GB_NZ);
    float *sh = gbuffer_plane(g, GB_SHIN);
    for (long i = 0; i < pairs; ++i) {
        double pos[3] = { 2 * lcg_unit(&st) - 1, 2 * lcg_unit(&st) - 1, -1 - 2 * lcg_unit(&st) }, v[3], l[3], h[3], nrm[3];
        double n = 2.0 * pow(500.0, lcg_unit(&st));
        for (int k = 0; k < 3; ++k) {
            v[k] = eye[k] - pos[k];
            l[k] = lamp[k] - pos[k];
        }
        double lv = sqrt(dot3(v, v)), ll = sqrt(dot3(l, l));
        for (int k = 0; k < 3; ++k) {
            v[k] /= lv;
            l[k] /= ll;
            h[k] = v[k] + l[k];
        }
        double lh = sqrt(dot3(h, h));
        for (int k = 0; k < 3; ++k)
            h[k] /= lh;
        /* The normal near the half vector (the lobe's peak) for half the pixels, anywhere in
           the cone of directions facing both L and V for the others. */
        for (int tries = 0;; ++tries) {
            double u[3];
            unit_sphere(&st, u);
            double spread = (i % 2) ? 3.0 * zone_epicentre_end(n) * lcg_unit(&st) : 1.5 * lcg_unit(&st);
            for (int k = 0; k < 3; ++k)
                nrm[k] = h[k] + spread * u[k];
            double len = sqrt(dot3(nrm, nrm));
            for (int k = 0; k < 3; ++k)
                nrm[k] /= len;
            if ((dot3(nrm, l) > 0.02 && dot3(nrm, v) > 0.02) || tries > 100)
                break;
        }
        px[i] = (float)pos[0]; py[i] = (float)pos[1]; pz[i] = (float)pos[2];
        nx[i] = (float)nrm[0]; ny[i] = (float)nrm[1]; nz[i] = (float)nrm[2];
        sh[i] = (float)n;
    }
}

/* One model's two launches (spec_a: eye and lamp as given, spec_b: swapped) compared pixel by
   pixel, and the same with the pass's double reference; the worst pair into r. */
static void recip_compare(struct recip_pass_summary *r, const struct render_options *o, const struct gbuffer *g,
                          long pairs, const float *spec_a, const float *spec_b, const double eye[3],
                          const double lamp[3], const struct render_light *la, const struct render_light *lb)
{
    const float *px = gbuffer_plane(g, GB_PX), *py = gbuffer_plane(g, GB_PY), *pz = gbuffer_plane(g, GB_PZ);
    const float *nx = gbuffer_plane(g, GB_NX), *ny = gbuffer_plane(g, GB_NY), *nz = gbuffer_plane(g, GB_NZ);
    const float *sh = gbuffer_plane(g, GB_SHIN);
    for (long i = 0; i < pairs; ++i) {
        double pos[3] = { px[i], py[i], pz[i] }, nrm[3] = { nx[i], ny[i], nz[i] }, v[3], l[3];
        for (int k = 0; k < 3; ++k) {
            v[k] = eye[k] - pos[k];
            l[k] = lamp[k] - pos[k];
        }
        double ea = 1.0 / dot3(l, l), eb = 1.0 / dot3(v, v);
        double lv = sqrt(dot3(v, v)), ll = sqrt(dot3(l, l));
        for (int k = 0; k < 3; ++k) {
            v[k] /= lv;
            l[k] /= ll;
        }
        double nl = dot3(nrm, l), nv = dot3(nrm, v);
        if (!(nl > 0.01 && nv > 0.01))
            continue;
        double n = sh[i], floor_v = 1e-6 * fabs(model_eval_host(&r->spec, 1.0, n));
        double sa = spec_a[i] / (ea * nl * o->ks), sb = spec_b[i] / (eb * nv * o->ks);
        double dd = fabs(sa - sb) / fmax(fmax(fabs(sa), fabs(sb)), floor_v);
        r->lit++;
        if (dd > r->device_worst) {
            r->device_worst = dd;
            r->n = n;
            memcpy(r->nrm, nrm, sizeof nrm);
            memcpy(r->l, l, sizeof l);
            memcpy(r->v, v, sizeof v);
            r->s_lv = sa;
            r->s_vl = sb;
        }
        double ha, hb, rad;
        render_shade_ref(&r->spec, r->mode, la, o, pos, nrm, n, &ha, &rad);
        render_shade_ref(&r->spec, r->mode, lb, o, pos, nrm, n, &hb, &rad);
        ha /= ea * nl * o->ks;
        hb /= eb * nv * o->ks;
        r->host_worst = fmax(r->host_worst, fabs(ha - hb) / fmax(fmax(fabs(ha), fabs(hb)), floor_v));
    }
}

int reciprocity_image_pass(struct cl_session *s, long pairs, struct recip_pass_summary *out, int max, int *count)
{
    char err[512];
    int rc = 0;
    *count = 0;
    struct render_options o;
    render_options_default(&o);
    struct render_device d;
    memset(&d, 0, sizeof d);
    struct gbuffer g;
    memset(&g, 0, sizeof g);
    cl_mem gbuf = NULL, orgba = NULL, ospec = NULL;
    float *spec_a = malloc((size_t)pairs * sizeof *spec_a), *spec_b = malloc((size_t)pairs * sizeof *spec_b);
    if (!spec_a || !spec_b || gbuffer_alloc(&g, (int)pairs, 1, err, sizeof err)) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = render_device_open(&d, s, &o, err, sizeof err)) != 0) {
        fprintf(stderr, "brdfbench: %s\n", err);
        goto done;
    }
    /* The eye at the origin and a point light at P (launch A), then swapped (launch B): at
       each pixel, V of one launch is L of the other, computed by the same float operations. */
    const double eye[3] = { 0, 0, 0 }, lamp[3] = { 0.7, 0.4, 0.2 };
    recip_gbuffer(&g, pairs, eye, lamp);
    cl_int e;
    gbuf = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, g.stride * GB_NPLANES * sizeof(float),
                          g.data, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity G-buffer)", done);
    orgba = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g.stride * sizeof(cl_uint), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity rgba)", done);
    ospec = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g.stride * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(reciprocity spec)", done);
    struct render_light la = { { eye[0], eye[1], eye[2] }, { lamp[0], lamp[1], lamp[2] }, 1, 1.0 };
    struct render_light lb = { { lamp[0], lamp[1], lamp[2] }, { eye[0], eye[1], eye[2] }, 1, 1.0 };
    for (int m = 0; m < o.nmodels && *count < max; ++m) {
        struct recip_pass_summary *r = &out[*count];
        memset(r, 0, sizeof *r);
        r->spec = o.models[m];
        r->mode = render_shading_mode(&r->spec);
        r->device_worst = r->host_worst = -1;
        double t;
        if ((rc = render_device_shade(&d, gbuf, g.stride, g.npix, orgba, ospec, &r->spec, r->mode, &la, &o, NULL,
                                      spec_a, &t)) != 0 ||
            (rc = render_device_shade(&d, gbuf, g.stride, g.npix, orgba, ospec, &r->spec, r->mode, &lb, &o, NULL,
                                      spec_b, &t)) != 0)
            goto done;
        recip_compare(r, &o, &g, pairs, spec_a, spec_b, eye, lamp, &la, &lb);
        (*count)++;
    }
done:
    if (ospec) clReleaseMemObject(ospec);
    if (orgba) clReleaseMemObject(orgba);
    if (gbuf) clReleaseMemObject(gbuf);
    if (d.program) render_device_close(&d);
    gbuffer_free(&g);
    free(spec_b);
    free(spec_a);
    return rc;
}

void energy_summary_free(struct energy_summary *summary)
{
    free(summary->json);
    summary->json = NULL;
}
