/* field.c - heatmap error fields: device evaluation, double check, JSON and the picture. */
#include "field.h"

#include "accuracy.h"
#include "draw.h"
#include "exitcodes.h"
#include "jsonr.h"
#include "context.h"
#include "jsonw.h"
#include "programs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double half_pi = 1.57079632679489661923;

static double x_e_of(double n) { return acos(exp(-0.511 / n)); }

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
    static const char *const names[] = { "field_grid" };
    cl_kernel *const kernels[] = { &f->kernel };
    return clsession_build_kernels(s, "field.cl", f->build_options, &f->program, 1, names, kernels);
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
    r->n = NULL;
    r->epi_rel = r->att_abs = NULL;
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
    CL_CHECK_GOTO(clSetKernelArg(kernel, 0, sizeof id, &id), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 1, sizeof p0, &p0), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 2, sizeof p1, &p1), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 3, sizeof rid, &rid), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 4, sizeof rp0, &rp0), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 5, sizeof rp1, &rp1), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 6, sizeof bn, &bn), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 7, sizeof rows, &rows), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 8, sizeof cols, &cols), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 9, sizeof log_u, &log_u), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 10, sizeof be, &be), done);
    CL_CHECK_GOTO(clSetKernelArg(kernel, 11, sizeof ba, &ba), done);
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

/* ---- JSON ------------------------------------------------------------------------ */

static void jw_peak(struct jw *w, const char *key, const struct field_peak *p)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, "value", p->value);
    jw_kv_num(w, "n", p->n);
    jw_kv_num(w, "x", p->x);
    jw_kv_int(w, "row", p->row);
    jw_kv_int(w, "col", p->col);
    jw_obj_end(w);
}

static void jw_field(struct jw *w, const char *key, const float *v, size_t count)
{
    jw_kv_arr(w, key);
    /* 9 significant digits give back every float exactly, so a redraw finds the same peaks
       (with 4, cells near the maximum tie and the first one wins) and draws the same picture. */
    for (size_t i = 0; i < count; i++) jw_numf(w, v[i], 9);
    jw_arr_end(w);
}

int field_write_json(const char *path, const struct field_result *r, const struct cl_session *s, char *err,
                     size_t errlen)
{
    struct jw w;
    jw_doc_begin(&w, FIELD_SCHEMA, s, "");
    jw_obj_end(&w);
    jw_kv_str(&w, "model", r->model.label);
    jw_kv_str(&w, "reference", r->reference.label);
    jw_kv_obj(&w, "grid");
    jw_kv_int(&w, "rows", r->grid.rows);
    jw_kv_int(&w, "cols", r->grid.cols);
    jw_kv_num(&w, "n_min", r->grid.n_min);
    jw_kv_num(&w, "n_max", r->grid.n_max);
    jw_kv_num(&w, "u_max", r->u_max);
    jw_kv_str(&w, "rows_are", "n, log-spaced from n_min to n_max (as float)");
    jw_kv_str(&w, "epicentre_x", "x = t x_e(n), t = col/(cols-1); x_e(n) = acos(exp(-0.511/n))");
    jw_kv_str(&w, "attenuation_x", "x = x_e(n) u_max^t, t = col/(cols-1); null past pi/2");
    jw_kv_arr(&w, "n");
    for (int i = 0; i < r->grid.rows; i++) jw_num(&w, r->n[i]);
    jw_arr_end(&w);
    jw_obj_end(&w);
    jw_peak(&w, "epicentre_max_rel", &r->epi_peak);
    jw_peak(&w, "attenuation_max_abs", &r->att_peak);
    jw_kv_obj(&w, "check");
    jw_kv_num(&w, "max_rel_diff", r->check_rel_diff);
    jw_kv_num(&w, "max_abs_diff", r->check_abs_diff);
    jw_kv_int(&w, "cells", r->check_cells);
    jw_kv_str(&w, "what", "device float cells against the double host reference at the same nominal x and n");
    jw_obj_end(&w);
    jw_kv_num(&w, "device_seconds", r->device_seconds);
    size_t cells = (size_t)r->grid.rows * r->grid.cols;
    jw_field(&w, "epicentre_rel", r->epi_rel, cells);
    jw_field(&w, "attenuation_abs", r->att_abs, cells);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

static int read_field_array(const struct jr_doc *d, const struct jr_value *root, const char *key, size_t cells,
                            float **out, char *err, size_t errlen)
{
    double *a = NULL;
    size_t count = 0;
    if (jr_need_num_array(d, root, key, &a, &count, err, errlen)) return 2;
    if (count != cells) {
        free(a);
        return jr_fail(d, jr_get(root, key), err, errlen, "\"%s\" has %zu values, rows x cols is %zu", key, count, cells);
    }
    float *f = malloc(cells * sizeof *f);
    if (!f) {
        free(a);
        return jr_fail(d, root, err, errlen, "out of memory");
    }
    for (size_t i = 0; i < cells; i++) f[i] = (float)a[i];
    free(a);
    *out = f;
    return 0;
}

int field_read_json(const char *path, struct field_result *r, char *err, size_t errlen)
{
    struct jr_doc d;
    memset(r, 0, sizeof *r);
    if (jr_parse_file(path, &d, err, errlen)) return 2;
    const struct jr_value *root = &d.root, *grid;
    const char *schema, *model, *ref;
    double rows, cols, *n = NULL;
    size_t nn = 0;
    char why[256];
    int rc = 2;
    if (jr_need_str(&d, root, "schema", &schema, err, errlen)) goto done;
    if (strcmp(schema, FIELD_SCHEMA) != 0) {
        jr_fail(&d, jr_get(root, "schema"), err, errlen, "schema \"%s\", expected \"%s\"", schema, FIELD_SCHEMA);
        goto done;
    }
    if (jr_need_str(&d, root, "model", &model, err, errlen) || jr_need_str(&d, root, "reference", &ref, err, errlen) ||
        jr_need(&d, root, "grid", JR_OBJ, &grid, err, errlen) || jr_need_num(&d, grid, "rows", &rows, err, errlen) ||
        jr_need_num(&d, grid, "cols", &cols, err, errlen) || jr_need_num(&d, grid, "n_min", &r->grid.n_min, err, errlen) ||
        jr_need_num(&d, grid, "n_max", &r->grid.n_max, err, errlen) || jr_need_num(&d, grid, "u_max", &r->u_max, err, errlen) ||
        jr_need_num_array(&d, grid, "n", &n, &nn, err, errlen))
        goto done;
    if (model_spec_parse(model, &r->model, why, sizeof why)) {
        jr_fail(&d, jr_get(root, "model"), err, errlen, "%s", why);
        goto done;
    }
    if (model_spec_parse(ref, &r->reference, why, sizeof why)) {
        jr_fail(&d, jr_get(root, "reference"), err, errlen, "%s", why);
        goto done;
    }
    if (!(rows == floor(rows) && cols == floor(cols) && rows >= 2 && cols >= 2 && rows <= 10000 && cols <= 10000)) {
        jr_fail(&d, grid, err, errlen, "grid rows/cols must be integers in [2, 10000]");
        goto done;
    }
    r->grid.rows = (int)rows;
    r->grid.cols = (int)cols;
    if (field_grid_check(&r->grid, why, sizeof why) || !(r->u_max >= 1)) {
        jr_fail(&d, grid, err, errlen, "%s", r->u_max >= 1 ? why : "u_max must be a number >= 1");
        goto done;
    }
    if (nn != (size_t)r->grid.rows) {
        jr_fail(&d, jr_get(grid, "n"), err, errlen, "\"n\" has %zu values, rows is %d", nn, r->grid.rows);
        goto done;
    }
    for (size_t i = 0; i < nn; i++)
        if (!(n[i] > 0)) {
            jr_fail(&d, jr_get(grid, "n"), err, errlen, "\"n\" item %zu is not a positive number", i);
            goto done;
        }
    r->n = n;
    n = NULL;
    size_t cells = (size_t)r->grid.rows * r->grid.cols;
    if (read_field_array(&d, root, "epicentre_rel", cells, &r->epi_rel, err, errlen) ||
        read_field_array(&d, root, "attenuation_abs", cells, &r->att_abs, err, errlen))
        goto done;
    /* the check block is informative; absent in hand-made files is fine */
    const struct jr_value *check = jr_get(root, "check");
    r->check_rel_diff = r->check_abs_diff = NAN;
    if (check) {
        double v;
        if (!jr_need_num(&d, check, "max_rel_diff", &v, err, errlen)) r->check_rel_diff = v;
        if (!jr_need_num(&d, check, "max_abs_diff", &v, err, errlen)) r->check_abs_diff = v;
        err[0] = 0;
    }
    field_find_peaks(r);
    rc = 0;
done:
    free(n);
    jr_free(&d);
    if (rc) field_result_free(r);
    return rc;
}

void field_safe_label(const char *label, char *out, size_t len)
{
    size_t k = 0;
    for (const char *p = label; *p && k + 1 < len; p++) {
        char c = *p;
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-')
            out[k++] = c;
        else if (c == ':' || c == ',')
            out[k++] = '_';
    }
    if (len) out[k] = 0;
}

/* ---- picture ------------------------------------------------------------------------ */

int field_draw_heatmap(const char *path, const struct field_result *r, struct draw_panel_layout *layout, char *err,
                       size_t errlen)
{
    const char *var = r->model.info->lobe == LOBE_PSI ? "psi" : "theta_h";
    char title[1024], sub0[160], sub1[160], xl0[160], xl1[160];
    char peak0[160] = "no finite value", peak1[160] = "no finite value";
    if (isfinite(r->epi_peak.value))
        snprintf(peak0, sizeof peak0, "max delta %.4g%% at n = %.4g, %s = %.4g rad", 100 * r->epi_peak.value,
                 r->epi_peak.n, var, r->epi_peak.x);
    if (isfinite(r->att_peak.value))
        snprintf(peak1, sizeof peak1, "max Delta %.4g at n = %.4g, %s = %.4g rad", r->att_peak.value, r->att_peak.n, var,
                 r->att_peak.x);
    snprintf(title, sizeof title, "%s against %s:  %s\n%s;  %s  (on this %dx%d grid)", r->model.label,
             r->reference.label, r->model.info->formula, peak0, peak1, r->grid.cols, r->grid.rows);
    snprintf(sub0, sizeof sub0, "relative error delta(x, n) over the epicentre");
    snprintf(sub1, sizeof sub1, "absolute error Delta(x, n) over the attenuation zone");
    snprintf(xl0, sizeof xl0, "x / x_e(n),  x = %s,  x_e(n) = acos(exp(-0.511/n))", var);
    snprintf(xl1, sizeof xl1, "x / x_e(n) (log),  x = %s;  grey: past pi/2", var);
    struct draw_heatmap_panel p[2];
    memset(p, 0, sizeof p);
    for (int k = 0; k < 2; k++) {
        p[k].cols = r->grid.cols;
        p[k].rows = r->grid.rows;
        p[k].y_min = r->n[0];
        p[k].y_max = r->n[r->grid.rows - 1];
        p[k].y_log = 1;
        p[k].y_label = "shininess n (log)";
        p[k].cmap = DRAW_CMAP_VIRIDIS;
        p[k].mark_max = 1;
    }
    p[0].values = r->epi_rel;
    p[0].x_min = 0, p[0].x_max = 1, p[0].x_label = xl0;
    p[0].value_format = DRAW_FMT_PERCENT;
    p[0].bar_label = "relative error delta";
    p[0].subtitle = sub0;
    p[1].values = r->att_abs;
    p[1].x_min = 1, p[1].x_max = r->u_max, p[1].x_log = 1, p[1].x_label = xl1;
    p[1].value_format = DRAW_FMT_PLAIN;
    p[1].bar_label = "absolute error Delta";
    p[1].subtitle = sub1;
    return draw_heatmap_figure(path, title, 2, p, layout, err, errlen);
}
