/* field.c - heatmap error fields: device evaluation and the double check (field_report.c writes,
 * reads and draws them). */
#include "field.h"

#include "accuracy.h"
#include "exitcodes.h"
#include "programs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double half_pi = 1.57079632679489661923;

static double x_e_of(double n) { return zone_epicentre_end(n); }

int field_grid_check(const struct field_grid *g, char *err, size_t errlen)
{
    if (g->rows < 2 || g->rows > 10000 || g->cols < 2 || g->cols > 10000 ||
        (long)g->rows * g->cols > FIELD_MAX_CELLS) {
        snprintf(err, errlen, "field grid %dx%d out of range (accepted: 2..10000 a side, at most %ld cells)",
                 g->cols, g->rows, FIELD_MAX_CELLS);
        return EXIT_USAGE;
    }
    if (!(isfinite(g->n_min) && isfinite(g->n_max) && g->n_min > 0 && g->n_max > g->n_min && g->n_max <= 1e6)) {
        snprintf(err, errlen, "field n range [%g, %g] out of range (accepted: 0 < n_min < n_max <= 1e6)", g->n_min,
                 g->n_max);
        return EXIT_USAGE;
    }
    return 0;
}

double field_row_n(const struct field_grid *g, int row)
{
    if (row <= 0) return g->n_min;
    if (row >= g->rows - 1) return g->n_max;
    return g->n_min * pow(g->n_max / g->n_min, (double)row / (g->rows - 1));
}

double field_epi_x(const struct field_result *r, int row, int col)
{
    return x_e_of(r->n[row]) * (double)col / (r->grid.cols - 1);
}

double field_att_x(const struct field_result *r, int row, int col)
{
    return x_e_of(r->n[row]) * exp((double)col / (r->grid.cols - 1) * log(r->u_max));
}

int field_open(struct field_ctx *f, struct cl_session *s, const char *build_options)
{
    memset(f, 0, sizeof *f);
    f->s = s;
    snprintf(f->build_options, sizeof f->build_options, "%s", build_options ? build_options : "");
    if (s->specialise)   /* each model's program on first use (host/core/programs.h) */
        return 0;
    static const char *const names[] = { "field_grid" };
    cl_kernel *const kernels[] = { &f->kernel };
    return clsession_build_kernels(s, "field.cl", NULL, f->build_options, &f->program, 1, names, kernels);
}

void field_close(struct field_ctx *f)
{
    cl_kernel *const kernels[] = { &f->kernel };
    clsession_release_kernels(&f->program, 1, kernels);
}

void field_result_free(struct field_result *r)
{
    free(r->n);
    free(r->epi_rel);
    free(r->att_abs);
    free(r->standin);
    r->n = NULL;
    r->epi_rel = r->att_abs = NULL;
    r->standin = NULL;
}

static void find_peak(const struct field_result *r, const float *v, int attenuation, struct field_peak *p)
{
    p->value = NAN;
    p->row = p->col = -1;
    p->n = p->x = NAN;
    size_t cells = (size_t)r->grid.rows * r->grid.cols;
    for (size_t i = 0; i < cells; i++)
        if (isfinite(v[i]) && !(v[i] <= p->value)) {
            p->value = v[i];
            p->row = (int)(i / r->grid.cols);
            p->col = (int)(i % r->grid.cols);
        }
    if (p->row >= 0) {
        p->n = r->n[p->row];
        p->x = attenuation ? field_att_x(r, p->row, p->col) : field_epi_x(r, p->row, p->col);
    }
}

void field_find_peaks(struct field_result *r)
{
    find_peak(r, r->epi_rel, 0, &r->epi_peak);
    find_peak(r, r->att_abs, 1, &r->att_peak);
}

/* Compares sampled cells (a lattice plus both peaks) with the double host reference at
 * the same nominal x and n. */
static void field_check(struct field_result *r)
{
    const struct field_grid *g = &r->grid;
    int rstep = g->rows > 12 ? g->rows / 12 : 1, cstep = g->cols > 16 ? g->cols / 16 : 1;
    double drel = 0, dabs = 0;
    int cells = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int row = 0; row < g->rows; row += (pass ? g->rows : rstep))
            for (int col = 0; col < g->cols; col += (pass ? g->cols : cstep)) {
                int rr = row, cc = col;
                if (pass) { /* the peaks */
                    if (r->epi_peak.row < 0) continue;
                    rr = r->epi_peak.row, cc = r->epi_peak.col;
                }
                double n = r->n[rr];
                size_t at = (size_t)rr * g->cols + cc;
                double h = error_rel_host(&r->model, &r->reference, cos(field_epi_x(r, rr, cc)), n);
                if (isfinite(h) && isfinite(r->epi_rel[at])) drel = fmax(drel, fabs(h - r->epi_rel[at]));
                if (pass && r->att_peak.row >= 0) rr = r->att_peak.row, cc = r->att_peak.col;
                at = (size_t)rr * g->cols + cc;
                double x = field_att_x(r, rr, cc);
                if (x <= half_pi && isfinite(r->att_abs[at])) {
                    h = error_abs_host(&r->model, &r->reference, fmax(cos(x), 0.0), r->n[rr]);
                    if (isfinite(h)) dabs = fmax(dabs, fabs(h - r->att_abs[at]));
                }
                cells++;
            }
    r->check_rel_diff = drel;
    r->check_abs_diff = dabs;
    r->check_cells = cells;
}

int field_run(struct field_ctx *f, const struct model_spec *m, const struct field_grid *g, struct field_result *out)
{
    int rc = 0;
    char err[256];
    memset(out, 0, sizeof *out);
    if ((rc = field_grid_check(g, err, sizeof err)) != 0) {
        fprintf(stderr, "brdfbench: %s\n", err);
        return rc;
    }
    cl_kernel kernel;   /* a user model's own build of field.cl, or the shared one */
    if ((rc = programs_kernel(f->s, "field.cl", f->build_options, m, "field_grid", f->kernel, &kernel)) != 0)
        return rc;
    out->model = *m;
    model_reference_spec(m, &out->reference);
    out->grid = *g;
    out->u_max = half_pi / x_e_of((double)(float)g->n_max);
    size_t cells = (size_t)g->rows * g->cols;
    cl_mem bn = NULL, be = NULL, ba = NULL;
    cl_event ev = NULL;
    float *nf = malloc((size_t)g->rows * sizeof *nf);
    out->n = malloc((size_t)g->rows * sizeof *out->n);
    out->epi_rel = malloc(cells * sizeof *out->epi_rel);
    out->att_abs = malloc(cells * sizeof *out->att_abs);
    if (!nf || !out->n || !out->epi_rel || !out->att_abs) {
        fprintf(stderr, "brdfbench: out of memory for a %dx%d field\n", g->cols, g->rows);
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (int i = 0; i < g->rows; i++) {
        nf[i] = (float)field_row_n(g, i);
        out->n[i] = nf[i];
    }
    cl_int e;
    bn = clCreateBuffer(f->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)g->rows * sizeof(float), nf, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(field n)", done);
    be = clCreateBuffer(f->s->ctx, CL_MEM_WRITE_ONLY, cells * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(field epicentre)", done);
    ba = clCreateBuffer(f->s->ctx, CL_MEM_WRITE_ONLY, cells * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(field attenuation)", done);
    cl_int id = m->info->kernel_id, rid = out->reference.info->kernel_id, rows = g->rows, cols = g->cols;
    float p0 = (float)m->params[0], p1 = (float)m->params[1];
    float rp0 = (float)out->reference.params[0], rp1 = (float)out->reference.params[1];
    float log_u = (float)log(out->u_max);
    CL_SET_ARGS_GOTO(done, kernel, 0, CL_ARG(id), CL_ARG(p0), CL_ARG(p1), CL_ARG(rid), CL_ARG(rp0), CL_ARG(rp1),
                     CL_ARG(bn), CL_ARG(rows), CL_ARG(cols), CL_ARG(log_u), CL_ARG(be), CL_ARG(ba));
    size_t global[2] = {(size_t)cols, (size_t)rows};
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(f->s->queue, kernel, 2, NULL, global, NULL, 0, NULL, &ev), done);
    CL_CHECK_GOTO(clsession_finish(f->s, kernel, m->label), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(f->s->queue, be, CL_TRUE, 0, cells * sizeof(float), out->epi_rel, 0, NULL, NULL), done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(f->s->queue, ba, CL_TRUE, 0, cells * sizeof(float), out->att_abs, 0, NULL, NULL), done);
    out->device_seconds = cl_event_seconds(ev);
    field_find_peaks(out);
    field_check(out);
done:
    if (ev) clReleaseEvent(ev);
    if (ba) clReleaseMemObject(ba);
    if (be) clReleaseMemObject(be);
    if (bn) clReleaseMemObject(bn);
    free(nf);
    if (rc) field_result_free(out);
    return rc;
}
