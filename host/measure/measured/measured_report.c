/* measured_report.c - measured.json (with its rows), the printed table, the pictures and the page
 * of `brdfbench measured` (measured_report.h). measured.c measures; this file only turns the
 * results into files. The page is report_measured_page (host/results/report) of the rows. */
#include "measured_report.h"

#include "context.h"
#include "draw.h"
#include "jsonw.h"
#include "outdir.h"
#include "rdoc.h"
#include "report_measured.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MEASURED_RATIO_REASON "the lobe equals the fitted Blinn-Phong on every cell"

#define METRIC_TEXT                                                                                                 \
    "per cell r = ln(1 + cos(theta_i) f_model) - ln(1 + cos(theta_i) Y), Y the measured luminance "               \
    "0.2126 R + 0.7152 G + 0.0722 B (sr^-1) at the cell's centre; fits minimise sum r^2 (gsl_multifit_nlinear, "  \
    "Levenberg-Marquardt, finite-difference Jacobian); errors are sqrt(mean r^2) over every used cell"

void measured_file_name(const char *name, char *out, size_t len)
{
    report_measured_file_name(name, out, len);
}

/* measured.json's rows (report_measured.h says what each holds): a row per material, per fit
   and per lobe, keyed by the material's picture stem. */
static void measured_rows(struct rdoc *d, const struct measured_report *r)
{
    static const char *const rgb[3] = { "negative_cells.red", "negative_cells.green", "negative_cells.blue" };
    char buf[32];
    snprintf(buf, sizeof buf, "%ld", r->opt.fit_cells);
    rd_ctx_put(&d->ctx, "fit_cells_max", buf);
    for (int i = 0; i < r->count; ++i) {
        const struct measured_material *m = &r->materials[i];
        /* measured_run names the pictures; a report made otherwise, by the name's file-name form */
        char stem[300];
        if (m->stem[0])
            snprintf(stem, sizeof stem, "%s", m->stem);
        else
            measured_file_name(m->name, stem, sizeof stem);
        struct rd_row *row = rdoc_row(d, "", "");
        if (!row)
            return;
        rd_row_key(row, "material", NULL, stem);
        const struct { const char *name; long v; } counts[] = {
            { "cells", m->cells }, { "unmeasured_cells", m->unmeasured }, { rgb[0], m->negative[0] },
            { rgb[1], m->negative[1] }, { rgb[2], m->negative[2] }, { "below_horizon_cells", m->below_horizon },
            { "used_cells", m->used_cells }, { "fit_cells", m->fit_cells }, { "device_check.points", m->device_points },
            { "device_check.same_cell", m->device_same_cell },
        };
        for (size_t k = 0; k < sizeof counts / sizeof counts[0]; ++k)
            rd_row_metric(d, row, counts[k].name, "1", RD_NEITHER, 0, (double)counts[k].v);
        rd_row_metric(d, row, "device_check.value_differs", "1", RD_LOWER, 0, (double)m->device_value_diff);
        rd_row_text(d, row, "name", m->name);
        rd_row_text(d, row, "path", m->path);
        rd_row_text(d, row, "device_check", m->device_points == 0 ? "not run" : m->device_ok ? "ok" : "mismatch");
        for (int k = 0; k < MFIT_COUNT; ++k) {
            const struct measured_fit *f = &m->fit[k];
            struct rd_row *fr = rdoc_row(d, "", measured_fit_name[k]);
            if (!fr)
                return;
            rd_row_key(fr, "material", NULL, stem);
            rd_row_key(fr, MEASURED_FIT_KEY, "fit ", measured_fit_name[k]);
            if (!f->ok)
                rd_row_fail(fr, strcmp(f->reason, "not run") == 0 ? "not run" : "not converged", f->reason);
            if (k == MFIT_BLINN) {
                rd_row_metric(d, fr, "n", "1", RD_NEITHER, 0, f->n);
            } else {
                rd_row_metric(d, fr, "alpha", "1", RD_NEITHER, 0, f->alpha);
                rd_row_metric(d, fr, "n_of_alpha", "1", RD_NEITHER, 0, f->n);
                rd_row_metric(d, fr, "F0", "1", RD_NEITHER, 0, f->f0);
            }
            rd_row_metric(d, fr, "ks", "1/sr", RD_NEITHER, 0, f->ks);
            rd_row_metric(d, fr, "kd", "1/sr", RD_NEITHER, 0, f->kd);
            rd_row_metric(d, fr, "rms", "1", RD_LOWER, 0, f->rms);
            rd_row_metric(d, fr, "rms_fit_cells", "1", RD_LOWER, 0, f->rms_fit);
            rd_row_metric(d, fr, "iterations", "1", RD_NEITHER, 0, f->iterations);
        }
        for (int l = 0; l < m->nlobes; ++l) {
            const struct measured_lobe *lb = &m->lobes[l];
            struct rd_row *lr = rdoc_row(d, "", lb->spec.label);
            if (!lr)
                return;
            rd_row_key(lr, "material", NULL, stem);
            rd_row_key(lr, MEASURED_LOBE_KEY, NULL, lb->spec.label);
            rd_row_metric(d, lr, "err_measured", "1", RD_LOWER, 0, lb->err_measured);
            rd_row_metric(d, lr, "err_phong", "1", RD_LOWER, 0, lb->err_phong);
            rd_row_metric(d, lr, "ratio", "1", RD_NEITHER, 0, lb->ratio);
            if (!isfinite(lb->ratio))
                rd_row_text(d, lr, "ratio_reason", MEASURED_RATIO_REASON);
        }
    }
}

/* The rows of r (rdoc_delete), or NULL with the reason in err. */
static struct rdoc *measured_doc(const struct measured_report *r, char *err, size_t errlen)
{
    struct rdoc *d = rdoc_new(MEASURED_SCHEMA, "measured", "measured.json", err, errlen);
    if (!d)
        return NULL;
    measured_rows(d, r);
    return rdoc_built(d, err, errlen) ? NULL : d;
}

static void jw_fit(struct jw *w, const char *key, const struct measured_fit *f, int physical)
{
    jw_kv_obj(w, key);
    jw_kv_str(w, "status", f->ok ? "ok" : strcmp(f->reason, "not run") == 0 ? "not run" : "not converged");
    if (!f->ok)
        jw_kv_str(w, "reason", f->reason);
    if (physical) {
        jw_kv_num(w, "alpha", f->alpha);
        jw_kv_num(w, "n_of_alpha", f->n);
        jw_kv_num(w, "F0", f->f0);
    } else {
        jw_kv_num(w, "n", f->n);
    }
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct measured_fit, MEMBER, KEY)
    static const struct jw_field fit[] = {
        F(JWF_NUM, ks, "ks"), F(JWF_NUM, kd, "kd"), F(JWF_NUM, rms, "rms"), F(JWF_NUM, rms_fit, "rms_fit_cells"),
        F(JWF_INT, iterations, "iterations"),
    };
    #undef F
    jw_kv_fields(w, f, JW_FIELDS(fit));
    jw_obj_end(w);
}

int measured_write_json(const char *path, const struct measured_report *r, const struct cl_session *s, char *err,
                        size_t errlen)
{
    struct rdoc *d = measured_doc(r, err, errlen);
    if (!d)
        return -1;
    struct jw w;
    jw_doc_begin(&w, MEASURED_SCHEMA, s, "");
    jw_kv_obj(&w, "grid");
    jw_kv_int(&w, "fit_cells_max", r->opt.fit_cells);
    jw_kv_str(&w, "fit_cells", "an even stride through the used cells, prime to 180 (the phi_d period)");
    jw_obj_end(&w);
    jw_obj_end(&w);   /* context */
    jw_kv_str(&w, "metric", METRIC_TEXT);
    jw_kv_str(&w, "fit_variable", "luminance: one fit per material, not per channel");
    jw_kv_str(&w, "lookup", "the cell holding the direction (no interpolation); fits and errors at cell centres");
    jw_kv_str(&w, "used_cells", "measured in all three channels, with L and V of the cell's centre above the surface");
    jw_kv_str(&w, "models",
              "blinn-phong: ks cos(theta_h)^n + kd; ct-beckmann, ct-ggx: kd + ks D F G / (4 N.L N.V) with "
              "alpha and Schlick's F0 (kernels/brdf_models.h); lobes: ks f(cos theta_h, n) + kd at the blinn-phong "
              "fit's n, ks, kd");
    jw_kv_arr(&w, "materials");
    for (int i = 0; i < r->count; ++i) {
        const struct measured_material *m = &r->materials[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "name", m->name);
        jw_kv_str(&w, "path", m->path);
        jw_kv_int(&w, "cells", m->cells);
        jw_kv_int(&w, "unmeasured_cells", m->unmeasured);
        jw_kv_arr(&w, "negative_cells_rgb");
        for (int c = 0; c < 3; ++c)
            jw_int(&w, m->negative[c]);
        jw_arr_end(&w);
        #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct measured_material, MEMBER, KEY)
        static const struct jw_field cells[] = {
            F(JWF_LONG, below_horizon, "below_horizon_cells"), F(JWF_LONG, used_cells, "used_cells"),
            F(JWF_LONG, fit_cells, "fit_cells"),
        };
        #undef F
        jw_kv_fields(&w, m, JW_FIELDS(cells));
        jw_fit(&w, "blinn_phong", &m->fit[MFIT_BLINN], 0);
        jw_fit(&w, "ct_beckmann", &m->fit[MFIT_CT_BECKMANN], 1);
        jw_fit(&w, "ct_ggx", &m->fit[MFIT_CT_GGX], 1);
        jw_kv_arr(&w, "lobes");
        for (int l = 0; l < m->nlobes; ++l) {
            const struct measured_lobe *lb = &m->lobes[l];
            jw_obj_begin(&w);
            jw_kv_str(&w, "model", lb->spec.label);
            jw_kv_num(&w, "err_measured", lb->err_measured);
            jw_kv_num(&w, "err_phong", lb->err_phong);
            jw_kv_num(&w, "ratio", lb->ratio);
            if (!isfinite(lb->ratio))
                jw_kv_str(&w, "ratio_reason", MEASURED_RATIO_REASON);
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        jw_kv_obj(&w, "device_check");
        jw_kv_str(&w, "status", m->device_points == 0 ? "not run" : m->device_ok ? "ok" : "mismatch");
        jw_kv_str(&w, "what", "kernels/merl.cl at every cell's centre (float directions): its cell and that cell's "
                              "float value against the host's double table");
        jw_kv_int(&w, "points", m->device_points);
        jw_kv_int(&w, "same_cell", m->device_same_cell);
        jw_kv_int(&w, "value_differs", m->device_value_diff);
        jw_obj_end(&w);
        jw_kv_obj(&w, "slices");
        jw_kv_num(&w, "phi_d_deg", (MEASURED_SLICE_PD + 0.5) * 180.0 / MERL_PD);
        jw_kv_str(&w, "null", "a cell not measured, or with L or V below the surface (a fit not run: every value)");
        jw_kv_nums(&w, "theta_h_deg", m->slice[0].theta_h_deg, MERL_TH);
        jw_kv_arr(&w, "theta_d");
        for (int sl = 0; sl < MEASURED_SLICES; ++sl) {
            const struct measured_slice *s2 = &m->slice[sl];
            jw_obj_begin(&w);
            jw_kv_num(&w, "theta_d_deg", (measured_slice_td[sl] + 0.5) * 90.0 / MERL_TD);
            jw_kv_nums(&w, "measured", s2->measured, MERL_TH);
            for (int k = 0; k < MFIT_COUNT; ++k)
                jw_kv_nums(&w, measured_fit_name[k], s2->fit[k], MERL_TH);
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        jw_obj_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    rdoc_json_rows_member(&w, d);
    rdoc_delete(d);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

void measured_print(FILE *f, const struct measured_report *r)
{
    for (int i = 0; i < r->count; ++i) {
        const struct measured_material *m = &r->materials[i];
        const struct measured_fit *bp = &m->fit[MFIT_BLINN], *be = &m->fit[MFIT_CT_BECKMANN],
                                  *gg = &m->fit[MFIT_CT_GGX];
        fprintf(f, "%s: %ld cells used (%ld unmeasured, %ld below the surface), fits on %ld; device lookup %s\n",
                m->name, m->used_cells, m->unmeasured, m->below_horizon, m->fit_cells,
                m->device_points == 0 ? "not run" : m->device_ok ? "ok" : "MISMATCH");
        fprintf(f, "  blinn-phong  n %-10.5g ks %-10.5g kd %-10.5g rms %.4g%s\n", bp->n, bp->ks, bp->kd, bp->rms,
                bp->ok ? "" : " (not converged)");
        fprintf(f, "  ct-beckmann  alpha %-8.5g F0 %-8.4g ks %-10.5g kd %-10.5g rms %.4g%s\n", be->alpha, be->f0,
                be->ks, be->kd, be->rms, be->ok ? "" : " (not converged)");
        fprintf(f, "  ct-ggx       alpha %-8.5g F0 %-8.4g ks %-10.5g kd %-10.5g rms %.4g%s\n", gg->alpha, gg->f0,
                gg->ks, gg->kd, gg->rms, gg->ok ? "" : " (not converged)");
        fprintf(f, "  %-14s %12s %12s %9s\n", "lobe", "vs measured", "vs phong", "ratio");
        for (int l = 0; l < m->nlobes; ++l) {
            const struct measured_lobe *lb = &m->lobes[l];
            fprintf(f, "  %-14s %12.5g %12.5g %9.4g\n", lb->spec.label, lb->err_measured, lb->err_phong, lb->ratio);
        }
    }
}

static int plots_of(const char *dir, const struct measured_material *m, char *err, size_t errlen)
{
    char fname[300], file[400], path[4500];
    if (m->stem[0])
        snprintf(fname, sizeof fname, "%s", m->stem);
    else
        measured_file_name(m->name, fname, sizeof fname);

    /* each lobe: its error against the material (y) beside its error against Blinn-Phong (x) */
    double x[MEASURED_MAX_LOBES], y[MEASURED_MAX_LOBES];
    const char *labels[MEASURED_MAX_LOBES];
    int marks[MEASURED_MAX_LOBES], front[MEASURED_MAX_LOBES];
    for (int l = 0; l < m->nlobes; ++l) {
        x[l] = m->lobes[l].err_phong;
        y[l] = m->lobes[l].err_measured;
        labels[l] = m->lobes[l].spec.label;
        marks[l] = DRAW_MARK_OTHER;
        front[l] = 0;
    }
    char title[400];
    snprintf(title, sizeof title, "%s: each lobe's error against the material and against the fitted Blinn-Phong",
             m->name);
    struct draw_scatter sc = { title, "RMS error against the fitted Blinn-Phong lobe (log)",
                               "RMS error against the measured material (log)", DRAW_FMT_PLAIN, m->nlobes, x, y,
                               labels, marks, front };
    snprintf(file, sizeof file, "measured_errors_%s.png", fname);
    path_join(path, sizeof path, dir, file);
    if (m->nlobes > 0 && draw_scatter_plot_plain(path, &sc, err, errlen))
        return -1;

    /* the slice: measured luminance against theta_h with the fitted curves */
    struct draw_series series[MEASURED_SLICES * (1 + MFIT_COUNT)];
    char names[MEASURED_SLICES * (1 + MFIT_COUNT)][80];
    int ns = 0;
    for (int sl = 0; sl < MEASURED_SLICES; ++sl) {
        double td = (measured_slice_td[sl] + 0.5) * 90.0 / MERL_TD;
        snprintf(names[ns], sizeof names[ns], "measured, theta_d %.1f", td);
        series[ns] = (struct draw_series){ m->slice[sl].theta_h_deg, m->slice[sl].measured, MERL_TH, names[ns], sl, 0,
                                           1 };
        ++ns;
        for (int k = 0; k < MFIT_COUNT; ++k) {
            snprintf(names[ns], sizeof names[ns], "%s fit, theta_d %.1f", measured_fit_name[k], td);
            /* Blinn-Phong dashed in its slice's colour, the Cook-Torrance fits dashed in colours of their own */
            series[ns] = (struct draw_series){ m->slice[sl].theta_h_deg, m->slice[sl].fit[k], MERL_TH, names[ns],
                                               (MEASURED_SLICES * k + sl) % 10, 1, 0 };
            ++ns;
        }
    }
    snprintf(title, sizeof title, "%s: luminance against theta_h at phi_d = 90 deg, measured and fitted", m->name);
    struct draw_line_plot lp;
    memset(&lp, 0, sizeof lp);
    lp.title = title;
    lp.x_label = "theta_h (degrees)";
    lp.y_label = "BRDF luminance (1/sr, log)";
    lp.y_log = 1;
    lp.x_min = 0;
    lp.x_max = 90;
    lp.nseries = ns;
    lp.series = series;
    snprintf(file, sizeof file, "measured_slice_%s.png", fname);
    path_join(path, sizeof path, dir, file);
    return draw_line_plot(path, &lp, err, errlen);
}

int measured_write_plots(const char *dir, const struct measured_report *r, char *err, size_t errlen)
{
    for (int i = 0; i < r->count; ++i)
        if (plots_of(dir, &r->materials[i], err, errlen))
            return -1;
    return 0;
}

int measured_markdown(struct md_buf *md, const struct measured_report *r)
{
    char err[256];
    struct rdoc *d = measured_doc(r, err, sizeof err);
    if (!d) {
        md->failed = 1;
        return -1;
    }
    int rc = report_measured_page(md, d);
    rdoc_delete(d);
    return rc;
}
