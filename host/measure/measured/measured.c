/* measured.c - the measurement of `brdfbench measured` (measured.h): the fits by GSL's nonlinear
 * least squares, each lobe's error against the material and against the fitted Blinn-Phong, the
 * slices of the pictures and the device lookup's check. measured_run ends by writing measured.json and
 * the pictures through measured_report.c's writers. */
#include "measured.h"
#include "measured_report.h"

#include "exitcodes.h"
#include "outdir.h"
#include "programs.h"
#include "report_measured.h"

#include <dirent.h>
#include <errno.h>
#include <sys/stat.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

const int measured_slice_td[MEASURED_SLICES] = { 0, 30, 60 };
const char *const measured_fit_name[MFIT_COUNT] = { "blinn-phong", "ct-beckmann", "ct-ggx" };

/* Rec. 709 luminance weights (they sum to 1, so a grey material's Y is its value). */
static const double lum_w[3] = { 0.2126, 0.7152, 0.0722 };

void measured_options_default(struct measured_options *o)
{
    memset(o, 0, sizeof *o);
    o->fit_cells = MEASURED_DEFAULT_FIT_CELLS;
    o->nlobes = measured_default_lobes(o->lobes, MEASURED_MAX_LOBES);
}

int measured_default_lobes(struct model_spec *out, int max)
{
    int count = 0;
    for (int i = 0; i < models_count() && count < max; ++i) {
        const struct model_info *m = models_at(i);
        if (strcmp(m->reference_id, "phong") != 0 || m->family == MODEL_FAMILY_REFERENCE || m->nparams >= 2)
            continue;
        model_spec_default(m, &out[count++]);
    }
    return count;
}

/* One used cell: the cosines the models take and the measured luminance. */
struct cell_geo {
    double nl, nv, lv, ch, vh;
    double y;
    double log_y;     /* ln(1 + nl y), the metric's measured side, computed once */
};

static void cell_geometry(long idx, struct cell_geo *g, double L[3], double V[3])
{
    int i = (int)(idx / (MERL_TD * MERL_PD)), j = (int)(idx / MERL_PD % MERL_TD), k = (int)(idx % MERL_PD);
    double th, td, pd;
    merl_cell_centre(i, j, k, &th, &td, &pd);
    merl_dirs(th, td, pd, L, V);
    g->nl = L[2];
    g->nv = V[2];
    g->lv = L[0] * V[0] + L[1] * V[1] + L[2] * V[2];
    g->ch = cos(th);
    g->vh = cos(td);   /* V.H = L.H = cos(theta_d) */
}

static double alpha_to_n(double alpha) { return 2.0 / (alpha * alpha) - 2.0; }

/* The fitted model k with parameters (n or alpha, f0, ks, kd) at cell g. */
static double fit_value_geo(int k, double n, double f0, double ks, double kd, const struct cell_geo *g)
{
    if (k == MFIT_BLINN)
        return ks * pow(fmax(g->ch, 0.0), n) + kd;
    int id = k == MFIT_CT_BECKMANN ? BRDF_CT_BECKMANN : BRDF_CT_GGX;
    return kd + ks * brdf_pb_eval_h(id, g->nl, g->nv, g->lv, g->ch, g->vh, n, f0, 0.0, 1.0);
}

/* The metric's residual of a model value f against the measured luminance y at a cell. */
static double residual(double f, const struct cell_geo *g)
{
    double r = log1p(g->nl * f) - g->log_y;
    return isfinite(r) ? r : 1e3;   /* a parameter vector past the models' domain: far off, never NaN */
}

/* ---- the fits ------------------------------------------------------------------------------- */

struct fit_data {
    const struct cell_geo *cells;
    const long *pick;     /* the fit's cells, indices into cells */
    long count;
    int model;
};

/* Parameters: Blinn-Phong x = (ln n, ln ks, ln kd); Cook-Torrance x = (ln alpha, logit F0,
 * ln ks, ln kd): positive n, alpha, ks, kd and F0 in (0, 1) without bounds on x. */
static void unpack(int model, const double *x, double *n, double *f0, double *ks, double *kd, double *alpha)
{
    if (model == MFIT_BLINN) {
        *n = exp(x[0]);
        *f0 = NAN;
        *alpha = NAN;
        *ks = exp(x[1]);
        *kd = exp(x[2]);
    } else {
        *alpha = exp(x[0]);
        *n = alpha_to_n(*alpha);
        *f0 = 1.0 / (1.0 + exp(-x[1]));
        *ks = exp(x[2]);
        *kd = exp(x[3]);
    }
}

static int fit_residuals(const gsl_vector *x, void *params, gsl_vector *f)
{
    const struct fit_data *d = params;
    double n, f0, ks, kd, alpha;
    unpack(d->model, x->data, &n, &f0, &ks, &kd, &alpha);
    for (long i = 0; i < d->count; ++i) {
        const struct cell_geo *g = &d->cells[d->pick[i]];
        gsl_vector_set(f, (size_t)i, residual(fit_value_geo(d->model, n, f0, ks, kd, g), g));
    }
    return GSL_SUCCESS;
}

static double cost_of(const struct fit_data *d, const double *x)
{
    double n, f0, ks, kd, alpha, sum = 0;
    unpack(d->model, x, &n, &f0, &ks, &kd, &alpha);
    for (long i = 0; i < d->count; ++i) {
        const struct cell_geo *g = &d->cells[d->pick[i]];
        double r = residual(fit_value_geo(d->model, n, f0, ks, kd, g), g);
        sum += r * r;
    }
    return sum;
}

/* A start for (ks, kd) given the lobe's shape b_i: linear least squares of ks b_i + kd against
 * y_i weighted by the metric's first-order sensitivity w/(1 + w y), kept positive. */
static void linear_start(const struct fit_data *d, const double *b, double *ks, double *kd)
{
    double sbb = 0, sb = 0, s1 = 0, sby = 0, sy = 0, ymean = 0;
    for (long i = 0; i < d->count; ++i) {
        const struct cell_geo *g = &d->cells[d->pick[i]];
        double w = g->nl / (1 + g->nl * g->y), w2 = w * w;
        sbb += w2 * b[i] * b[i];
        sb += w2 * b[i];
        s1 += w2;
        sby += w2 * b[i] * g->y;
        sy += w2 * g->y;
        ymean += g->y;
    }
    ymean /= (double)d->count;
    double det = sbb * s1 - sb * sb;
    *ks = det != 0 ? (sby * s1 - sb * sy) / det : ymean;
    *kd = det != 0 ? (sbb * sy - sb * sby) / det : ymean;
    double floor_value = fmax(ymean, 1e-12) * 1e-6;
    if (!(*ks > floor_value))
        *ks = floor_value;
    if (!(*kd > floor_value))
        *kd = floor_value;
}

/* The starting points of a fit: a grid over n (Blinn-Phong: the best one) or over alpha for
 * each of three F0 (Cook-Torrance: the best alpha of each F0, since the fit cannot cross the
 * flat ends of the logit in F0), (ks, kd) by linear_start at each. Returns the number of starts. */
#define FIT_MAX_STARTS 3
static int fit_starts(const struct fit_data *d, double x[FIT_MAX_STARTS][4])
{
    double *b = malloc((size_t)d->count * sizeof *b);
    memset(x, 0, sizeof(double) * FIT_MAX_STARTS * 4);
    if (!b) {
        x[0][0] = d->model == MFIT_BLINN ? log(100.0) : log(0.2);
        return 1;
    }
    if (d->model == MFIT_BLINN) {
        double best = INFINITY;
        for (int gi = 0; gi <= 40; ++gi) {
            double n = pow(10.0, 5.0 * gi / 40.0);   /* 1 .. 1e5 */
            for (long i = 0; i < d->count; ++i)
                b[i] = pow(fmax(d->cells[d->pick[i]].ch, 0.0), n);
            double ks, kd;
            linear_start(d, b, &ks, &kd);
            double t[4] = { log(n), log(ks), log(kd), 0 };
            double c = cost_of(d, t);
            if (c < best) {
                best = c;
                memcpy(x[0], t, sizeof t);
            }
        }
        free(b);
        return 1;
    }
    static const double f0s[FIT_MAX_STARTS] = { 0.04, 0.3, 0.9 };
    int id = d->model == MFIT_CT_BECKMANN ? BRDF_CT_BECKMANN : BRDF_CT_GGX;
    for (int fi = 0; fi < FIT_MAX_STARTS; ++fi) {
        double best = INFINITY;
        for (int gi = 0; gi <= 24; ++gi) {
            double alpha = pow(10.0, -2.5 + 2.5 * gi / 24.0);   /* 0.003 .. 1 */
            for (long i = 0; i < d->count; ++i) {
                const struct cell_geo *g = &d->cells[d->pick[i]];
                b[i] = brdf_pb_eval_h(id, g->nl, g->nv, g->lv, g->ch, g->vh, alpha_to_n(alpha), f0s[fi], 0.0, 1.0);
            }
            double ks, kd;
            linear_start(d, b, &ks, &kd);
            double t[4] = { log(alpha), log(f0s[fi] / (1 - f0s[fi])), log(ks), log(kd) };
            double c = cost_of(d, t);
            if (c < best) {
                best = c;
                memcpy(x[fi], t, sizeof t);
            }
        }
    }
    free(b);
    return FIT_MAX_STARTS;
}

/* Fits model d->model by gsl_multifit_nlinear (Levenberg-Marquardt on the trust-region
 * driver, finite-difference Jacobian) from each of fit_starts; the fit of least cost is kept. */
static void fit_material(const struct fit_data *d, struct measured_fit *out)
{
    size_t p = d->model == MFIT_BLINN ? 3 : 4;
    double starts[FIT_MAX_STARTS][4];
    int nstarts = fit_starts(d, starts);
    memset(out, 0, sizeof *out);
    out->rms_fit = INFINITY;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_multifit_nlinear_fdf fdf;
    memset(&fdf, 0, sizeof fdf);
    fdf.f = fit_residuals;
    fdf.n = (size_t)d->count;
    fdf.p = p;
    fdf.params = (void *)d;
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;
    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, fdf.n, p);
    if (!w) {
        snprintf(out->reason, sizeof out->reason, "out of memory for the fit");
        gsl_set_error_handler(old);
        return;
    }
    for (int st = 0; st < nstarts; ++st) {
        gsl_vector_view xv = gsl_vector_view_array(starts[st], p);
        int info = 0;
        int status = gsl_multifit_nlinear_init(&xv.vector, &fdf, w);
        if (status == GSL_SUCCESS)
            status = gsl_multifit_nlinear_driver(400, 1e-12, 1e-12, 1e-14, NULL, NULL, &info, w);
        double x[4] = { 0, 0, 0, 0 };
        gsl_vector *xs = gsl_multifit_nlinear_position(w);
        for (size_t i = 0; i < p; ++i)
            x[i] = gsl_vector_get(xs, i);
        double rms = sqrt(cost_of(d, x) / (double)d->count);
        if (!(rms < out->rms_fit))
            continue;
        out->rms_fit = rms;
        out->iterations = (int)gsl_multifit_nlinear_niter(w);
        /* GSL_EMAXITER and GSL_ENOPROG leave the best point found so far: kept, with the reason */
        out->ok = status == GSL_SUCCESS;
        out->reason[0] = '\0';
        if (!out->ok)
            snprintf(out->reason, sizeof out->reason, "gsl_multifit_nlinear_driver: %s after %d iterations",
                     gsl_strerror(status), out->iterations);
        unpack(d->model, x, &out->n, &out->f0, &out->ks, &out->kd, &out->alpha);
    }
    gsl_multifit_nlinear_free(w);
    gsl_set_error_handler(old);
}

/* The fit's cells: an even stride through the used cells, the stride made prime to 180 (phi_d's
 * period) so that the subset does not alias with the table's layout. */
static long *fit_pick(long used, long max, long *count)
{
    long stride = used > max ? (used + max - 1) / max : 1;
    while (stride > 1 && (stride % 2 == 0 || stride % 3 == 0 || stride % 5 == 0))
        ++stride;
    long n = (used + stride - 1) / stride;
    long *pick = malloc((size_t)n * sizeof *pick);
    if (!pick)
        return NULL;
    for (long i = 0; i < n; ++i)
        pick[i] = i * stride;
    *count = n;
    return pick;
}

/* ---- the run -------------------------------------------------------------------------------- */

static int device_check(struct cl_session *s, const struct merl_material *mat, struct measured_material *out)
{
    size_t count = (size_t)MERL_CELLS;
    float *L = malloc(3 * count * sizeof(float)), *V = malloc(3 * count * sizeof(float));
    float *rgb = malloc(3 * count * sizeof(float));
    int *cell = malloc(count * sizeof(int));
    int rc = 0;
    if (!L || !V || !rgb || !cell) {
        fprintf(stderr, "brdfbench measured: out of memory for the device check\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (long idx = 0; idx < MERL_CELLS; ++idx) {
        struct cell_geo g;
        double l[3], v[3];
        cell_geometry(idx, &g, l, v);
        for (int c = 0; c < 3; ++c) {
            L[3 * idx + c] = (float)l[c];
            V[3 * idx + c] = (float)v[c];
        }
    }
    rc = merl_eval_device(s, mat, L, V, count, rgb, cell);
    if (rc)
        goto done;
    out->device_points = MERL_CELLS;
    for (long idx = 0; idx < MERL_CELLS; ++idx) {
        if (cell[idx] == idx)
            out->device_same_cell++;
        for (int c = 0; c < 3; ++c)
            if (cell[idx] >= 0 && cell[idx] < MERL_CELLS &&
                rgb[3 * idx + c] != (float)mat->value[(size_t)c * MERL_CELLS + (size_t)cell[idx]]) {
                out->device_value_diff++;
                break;
            }
    }
    out->device_ok = out->device_same_cell == out->device_points && out->device_value_diff == 0;
done:
    free(L);
    free(V);
    free(rgb);
    free(cell);
    return rc;
}

/* The measured cells above the surface, with their luminance: written to cells, returns how
   many (the cells below the horizon counted in out). */
static long measured_cells(const struct merl_material *mat, struct cell_geo *cells, struct measured_material *out)
{
    long used = 0;
    for (long idx = 0; idx < MERL_CELLS; ++idx) {
        double rgb[3], L[3], V[3];
        if (!merl_cell(mat, idx, rgb))
            continue;
        struct cell_geo g;
        cell_geometry(idx, &g, L, V);
        if (!(g.nl > 0 && g.nv > 0)) {
            out->below_horizon++;
            continue;
        }
        g.y = lum_w[0] * rgb[0] + lum_w[1] * rgb[1] + lum_w[2] * rgb[2];
        g.log_y = log1p(g.nl * g.y);
        cells[used++] = g;
    }
    return used;
}

/* Each fit on the picked cells (the physical ones "not run" with skip_physical), and its rms
   over every used cell. */
static void measured_fits(const struct cell_geo *cells, long used, const long *pick, long npick,
                          const struct measured_options *o, struct measured_material *out)
{
    for (int k = 0; k < MFIT_COUNT; ++k) {
        if (k != MFIT_BLINN && o->skip_physical) {
            struct measured_fit *f = &out->fit[k];
            f->n = f->ks = f->kd = f->alpha = f->f0 = f->rms = f->rms_fit = NAN;
            snprintf(f->reason, sizeof f->reason, "not run");
            continue;
        }
        struct fit_data d = { cells, pick, npick, k };
        fit_material(&d, &out->fit[k]);
        double sum = 0;
        const struct measured_fit *f = &out->fit[k];
        for (long i = 0; i < used; ++i) {
            double r = residual(fit_value_geo(k, f->n, f->f0, f->ks, f->kd, &cells[i]), &cells[i]);
            sum += r * r;
        }
        out->fit[k].rms = sqrt(sum / (double)used);
    }
}

/* Each lobe at the Blinn-Phong fit's n, ks, kd: against the measurement and the fitted lobe;
   -1 when out of memory. */
static int measured_lobes(const struct cell_geo *cells, long used, const struct measured_options *o,
                          struct measured_material *out)
{
    const struct measured_fit *bp = &out->fit[MFIT_BLINN];
    out->nlobes = o->nlobes;
    double *log_phong = malloc((size_t)used * sizeof *log_phong);
    if (!log_phong)
        return -1;
    for (long i = 0; i < used; ++i)
        log_phong[i] = log1p(cells[i].nl * (bp->ks * pow(fmax(cells[i].ch, 0.0), bp->n) + bp->kd));
    for (int l = 0; l < o->nlobes; ++l) {
        struct measured_lobe *lobe = &out->lobes[l];
        lobe->spec = o->lobes[l];
        double sm = 0, sp = 0;
        for (long i = 0; i < used; ++i) {
            const struct cell_geo *g = &cells[i];
            double c = fmax(g->ch, 0.0);
            double lf = log1p(g->nl * (bp->ks * model_eval_host(&lobe->spec, c, bp->n) + bp->kd));
            double rm = lf - g->log_y, rp = lf - log_phong[i];
            sm += rm * rm;
            sp += rp * rp;
        }
        lobe->err_measured = sqrt(sm / (double)used);
        lobe->err_phong = sqrt(sp / (double)used);
        lobe->ratio = lobe->err_phong > 0 ? lobe->err_measured / lobe->err_phong : NAN;
    }
    free(log_phong);
    return 0;
}

/* The slices: theta_h at phi_d = 90 degrees and a few theta_d, measured and fitted. */
static void measured_slices(const struct merl_material *mat, struct measured_material *out)
{
    for (int sl = 0; sl < MEASURED_SLICES; ++sl) {
        struct measured_slice *m = &out->slice[sl];
        for (int i = 0; i < MERL_TH; ++i) {
            long idx = MEASURED_SLICE_PD + MERL_PD * (measured_slice_td[sl] + MERL_TD * (long)i);
            double rgb[3], L[3], V[3];
            struct cell_geo g;
            cell_geometry(idx, &g, L, V);
            double th, td, pd;
            merl_cell_centre(i, measured_slice_td[sl], MEASURED_SLICE_PD, &th, &td, &pd);
            m->theta_h_deg[i] = th * 180 / M_PI;
            int above = g.nl > 0 && g.nv > 0;
            m->measured[i] = merl_cell(mat, idx, rgb) && above
                                 ? lum_w[0] * rgb[0] + lum_w[1] * rgb[1] + lum_w[2] * rgb[2]
                                 : NAN;
            for (int k = 0; k < MFIT_COUNT; ++k) {
                const struct measured_fit *f = &out->fit[k];
                m->fit[k][i] = above ? fit_value_geo(k, f->n, f->f0, f->ks, f->kd, &g) : NAN;
            }
        }
    }
}

int measured_material_run(struct cl_session *s, const struct merl_material *mat, const struct measured_options *o,
                          struct measured_material *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", mat->name);
    snprintf(out->path, sizeof out->path, "%s", mat->path);
    out->cells = MERL_CELLS;
    out->unmeasured = mat->unmeasured;
    memcpy(out->negative, mat->negative, sizeof out->negative);
    for (int i = 0; i < o->nlobes; ++i) {
        int rc = programs_host(s, &o->lobes[i]);
        if (rc)
            return rc;
    }

    struct cell_geo *cells = malloc((size_t)MERL_CELLS * sizeof *cells);
    if (!cells) {
        fprintf(stderr, "brdfbench measured: out of memory\n");
        return EXIT_RUNTIME;
    }
    long used = measured_cells(mat, cells, out);
    out->used_cells = used;
    if (used < MEASURED_MIN_FIT_CELLS) {
        free(cells);
        fprintf(stderr, "brdfbench measured: %s: only %ld measured cells above the surface (at least %d needed)\n",
                mat->path, used, MEASURED_MIN_FIT_CELLS);
        return EXIT_USAGE;
    }
    long npick = 0;
    long *pick = fit_pick(used, o->fit_cells, &npick);
    if (!pick) {
        free(cells);
        fprintf(stderr, "brdfbench measured: out of memory\n");
        return EXIT_RUNTIME;
    }
    out->fit_cells = npick;
    measured_fits(cells, used, pick, npick, o, out);
    if (measured_lobes(cells, used, o, out) != 0) {
        free(pick);
        free(cells);
        fprintf(stderr, "brdfbench measured: out of memory\n");
        return EXIT_RUNTIME;
    }
    measured_slices(mat, out);
    free(pick);
    free(cells);
    return s ? device_check(s, mat, out) : 0;
}

/* ---- a run over files ---------------------------------------------------------------------- */

static int path_add(char ***paths, int *count, const char *path)
{
    if (*count >= MEASURED_MAX_MATERIALS)
        return -1;
    char **p = realloc(*paths, (size_t)(*count + 1) * sizeof *p);
    if (!p)
        return -1;
    *paths = p;
    p[*count] = strdup(path);
    if (!p[*count])
        return -1;
    ++*count;
    return 0;
}

void measured_paths_free(char **paths, int count)
{
    for (int i = 0; i < count; ++i)
        free(paths[i]);
    free(paths);
}

static int binary_entry(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return e->d_name[0] != '.' && n > 7 && strcmp(e->d_name + n - 7, ".binary") == 0;
}

int measured_collect(const char *arg, char ***paths, int *count, char *err, size_t errlen)
{
    struct stat st;
    if (stat(arg, &st) != 0) {
        snprintf(err, errlen, "%s: %s (expected a MERL .binary file or a folder of them)", arg, strerror(errno));
        return EXIT_USAGE;
    }
    if (!S_ISDIR(st.st_mode)) {
        if (path_add(paths, count, arg)) {
            snprintf(err, errlen, "%s: at most %d materials per run", arg, MEASURED_MAX_MATERIALS);
            return EXIT_USAGE;
        }
        return 0;
    }
    struct dirent **list = NULL;
    int n = scandir(arg, &list, binary_entry, alphasort);
    if (n < 0) {
        snprintf(err, errlen, "%s: cannot read the folder: %s", arg, strerror(errno));
        return EXIT_USAGE;
    }
    int rc = 0;
    if (n == 0) {
        snprintf(err, errlen, "%s: no .binary files in the folder (expected MERL files named NAME.binary)", arg);
        rc = EXIT_USAGE;
    }
    for (int i = 0; i < n; ++i) {
        char path[OUTDIR_PATH_MAX];
        if (!rc && (path_join(path, sizeof path, arg, list[i]->d_name) || path_add(paths, count, path))) {
            snprintf(err, errlen, "%s: at most %d materials per run", arg, MEASURED_MAX_MATERIALS);
            rc = EXIT_USAGE;
        }
        free(list[i]);
    }
    free(list);
    return rc;
}

int measured_load(const char *flag, const char *arg, int max, struct merl_material *out, int *count, char *err,
                  size_t errlen)
{
    char **paths = NULL, rerr[1024];
    int n = 0, rc = measured_collect(arg, &paths, &n, rerr, sizeof rerr);
    *count = 0;
    if (!rc && n > max) {
        snprintf(rerr, sizeof rerr, "%s: %d materials, at most %d accepted", arg, n, max);
        rc = EXIT_USAGE;
    }
    for (int i = 0; i < n && !rc; ++i)
        if ((rc = merl_read(paths[i], &out[i], rerr, sizeof rerr)) == 0)
            ++*count;
    if (rc) {
        for (int i = 0; i < *count; ++i)
            merl_free(&out[i]);
        *count = 0;
        snprintf(err, errlen, "%s: %s", flag, rerr);
    }
    measured_paths_free(paths, n);
    return rc;
}

int measured_run(struct cl_session *s, const struct measured_options *o, struct measured_report *out)
{
    memset(out, 0, sizeof *out);
    char *err = out->err;
    const size_t errlen = sizeof out->err;
    char *const *paths = o->paths;
    const int count = o->count;
    FILE *progress = o->io.quiet ? NULL : stderr;
    out->opt = *o;
    out->materials = calloc((size_t)(count > 0 ? count : 1), sizeof *out->materials);
    if (!out->materials) {
        snprintf(err, errlen, "out of memory");
        return EXIT_RUNTIME;
    }
    int rc = 0;
    for (int i = 0; i < count && !rc; ++i) {
        struct merl_material mat;
        rc = merl_read(paths[i], &mat, err, errlen);
        if (rc)
            break;
        if (progress)
            fprintf(progress, "measured: %s (%d of %d)\n", mat.name, i + 1, count);
        rc = measured_material_run(s, &mat, o, &out->materials[out->count]);
        merl_free(&mat);
        if (rc)
            err[0] = '\0';   /* measured_material_run has said why on stderr */
        else
            out->count++;
    }
    if (rc) {
        out->count = 0;
        return rc;
    }
    /* Pictures are named after the material's file name, made safe: two materials whose names
       give one (a/gold.binary and b/gold.binary, "a b" and a_b) would overwrite each other's
       pictures, so a later one takes -2, -3, ... */
    const char *taken[MEASURED_MAX_MATERIALS];
    for (int i = 0; i < out->count && i < MEASURED_MAX_MATERIALS; ++i) {
        struct measured_material *m = &out->materials[i];
        report_measured_stem(m->name, taken, i, m->stem, sizeof m->stem);
        taken[i] = m->stem;
    }
    char path[4300];
    if (o->io.out_dir && (path_join(path, sizeof path, o->io.out_dir, "measured.json") ||
                          measured_write_json(path, out, s, err, errlen) ||
                          measured_write_plots(o->io.out_dir, out, err, errlen)))
        return EXIT_RUNTIME;
    return 0;
}

void measured_report_free(struct measured_report *r)
{
    free(r->materials);
    r->materials = NULL;
    r->count = 0;
}
