/* accuracy_report.c - writes the sweep's results: JSON contract, per-n CSV, a table. */
#include "accuracy_report.h"
#include "context.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "outdir.h"
#include "rdoc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double accuracy_check_in_digits(const struct accuracy_result *r) { return r->check.units; }

static void jw_extreme(struct jw *w, const char *key, const char *metric, const char *grid_metric,
                       const struct acc_extreme *e, const struct acc_extreme *g, const char *reason)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, metric, e->value);
    jw_kv_num(w, "at_n", e->n);
    jw_kv_num(w, "at_x", e->x);
    jw_kv_num(w, grid_metric, g->value);
    if (!isfinite(e->value))
        jw_kv_str(w, "reason", reason && *reason ? reason : "no finite values");
    jw_obj_end(w);
}

int accuracy_write_json(const char *path, const struct accuracy_result *res, int count,
                        const struct cl_session *s, const char *build_options, char *err, size_t errlen)
{
    return accuracy_write_json_full(path, res, count, NULL, 0, s, build_options, err, errlen);
}

/* accuracy.json's rows, built from the results in memory: a row per model of the lobe sweep
   (keys label and grid; attributes n_min, n_max, n_step and reference; the sweep's figures, the
   device check's float cancellation and, for code in half, the fp16 figures, each an error:
   lower is better, not timed; then what report.md's table shows beside them: where each maximum
   and the first invalid value lie (n, x: neither better higher nor lower) and the device check
   in units of the 4th significant digit), then the hemisphere sweep's rows (hemisphere_rows).
   The context carries the grid as text and its numbers (accuracy n_min, n_max, n_step, samples
   per zone). */
static void accuracy_rows(struct rdoc *d, const struct accuracy_result *res, int count,
                          const struct hemi_result *hres, int hcount)
{
    char grid[RD_TEXT] = "", text[RD_TEXT];
    double n_step = NAN;
    if (count > 0) {
        const struct accuracy_grid *g = &res[0].grid;
        snprintf(grid, sizeof grid, "n %g..%g step %g, %g samples per zone", g->n_min, g->n_max, g->n_step,
                 (double)g->samples);
        n_step = g->n_step;
    }
    rd_ctx_put(&d->ctx, "accuracy grid", grid);
    if (count > 0) {
        const struct accuracy_grid *g = &res[0].grid;
        const struct { const char *key; double v; } num[] = {
            { "accuracy n_min", g->n_min }, { "accuracy n_max", g->n_max }, { "accuracy n_step", g->n_step },
            { "accuracy samples per zone", (double)g->samples } };
        for (size_t k = 0; k < sizeof num / sizeof num[0]; ++k) {
            snprintf(text, sizeof text, "%.17g", num[k].v);
            rd_ctx_put(&d->ctx, num[k].key, text);
        }
    }
    for (int i = 0; i < count; ++i) {
        const struct accuracy_result *r = &res[i];
        struct rd_row *row = rdoc_row(d, "", r->model.label);
        if (!row)
            return;
        snprintf(text, sizeof text, "%.120s", r->model.label);
        rd_row_key(row, "label", NULL, text);
        snprintf(text, sizeof text, "%.120s", grid);
        rd_row_key(row, "grid", NULL, text);
        const char *status = accuracy_status(r);
        if (strcmp(status, "ok") != 0)
            rd_row_fail(row, status, r->reason[0] ? r->reason : status);
        snprintf(text, sizeof text, "%.17g", r->grid.n_min);
        rd_row_attr(row, "n_min", text);
        snprintf(text, sizeof text, "%.17g", r->grid.n_max);
        rd_row_attr(row, "n_max", text);
        snprintf(text, sizeof text, "%.17g", n_step);
        rd_row_attr(row, "n_step", text);
        rd_row_attr(row, "reference", r->reference.label);
        rd_row_metric(d, row, "epicentre.max_rel", "1", RD_LOWER, 0, r->epicentre.value);
        rd_row_metric(d, row, "attenuation.max_abs", "1", RD_LOWER, 0, r->attenuation.value);
        rd_row_metric(d, row, "whole.max_abs", "1", RD_LOWER, 0, r->whole.value);
        rd_row_metric(d, row, "invalid.count", "1", RD_LOWER, 0, (double)r->invalid_count);
        if (isfinite(r->probe_rel_diff))   /* written as null otherwise: no figure */
            rd_row_metric(d, row, "check.float_cancellation", "1", RD_LOWER, 0, r->probe_rel_diff);
        if (r->fp16.present) {   /* the same sweep of the code's binary16 build */
            rd_row_metric(d, row, "fp16.max_rel", "1", RD_LOWER, 0, r->fp16.epicentre.value);
            rd_row_metric(d, row, "fp16.max_abs", "1", RD_LOWER, 0, r->fp16.attenuation.value);
            rd_row_metric(d, row, "fp16.invalid_count", "1", RD_LOWER, 0, (double)r->fp16.invalid_count);
        }
        const struct { const char *name; double v; } at[] = {
            { "epicentre.at_n", r->epicentre.n }, { "epicentre.at_x", r->epicentre.x },
            { "attenuation.at_n", r->attenuation.n }, { "attenuation.at_x", r->attenuation.x },
            { "invalid.at_n", r->invalid_n }, { "invalid.at_x", r->invalid_x } };
        for (size_t k = 0; k < sizeof at / sizeof at[0]; ++k)
            rd_row_metric(d, row, at[k].name, at[k].name[strlen(at[k].name) - 1] == 'x' ? "rad" : "1", RD_NEITHER, 0,
                          at[k].v);
        rd_row_metric(d, row, "check.in_4th_digit_units", "4th-digit units", RD_LOWER, 0, accuracy_check_in_digits(r));
    }
    hemisphere_rows(d, hres, hcount, n_step);
}

static int write_json(const char *path, const struct accuracy_result *res, int count, const struct hemi_result *hres,
                      int hcount, const struct cl_session *s, const char *build_options, struct rdoc **keep, char *err,
                      size_t errlen);

int accuracy_write_json_full(const char *path, const struct accuracy_result *res, int count,
                             const struct hemi_result *hres, int hcount, const struct cl_session *s,
                             const char *build_options, char *err, size_t errlen)
{
    return write_json(path, res, count, hres, hcount, s, build_options, NULL, err, errlen);
}

int accuracy_write_json_keep(const char *path, const struct accuracy_result *res, int count,
                             const struct cl_session *s, const char *build_options, struct rdoc **rows, char *err,
                             size_t errlen)
{
    *rows = NULL;
    return write_json(path, res, count, NULL, 0, s, build_options, rows, err, errlen);
}

/* The file, and its rows: freed, or handed over in *keep when the file is written. */
static int write_json(const char *path, const struct accuracy_result *res, int count, const struct hemi_result *hres,
                      int hcount, const struct cl_session *s, const char *build_options, struct rdoc **keep, char *err,
                      size_t errlen)
{
    struct rdoc *d = rdoc_new(ACCURACY_SCHEMA, "accuracy", "accuracy.json", err, errlen);
    if (!d)
        return -1;
    accuracy_rows(d, res, count, hres, hcount);
    if (rdoc_built(d, err, errlen))
        return -1;
    struct jw w;
    jw_doc_begin(&w, ACCURACY_SCHEMA, s, build_options);
    if (count > 0) {
        const struct accuracy_grid *g = &res[0].grid;
        jw_kv_obj(&w, "grid");
        jw_kv_fields(&w, g, accuracy_grid_n_fields, ACCURACY_GRID_N_FIELDS);
        jw_kv_int(&w, "n_count", res[0].n_count);
        jw_kv_int(&w, "samples_per_zone", g->samples);
        jw_kv_str(&w, "epicentre", "s = 1 - cos x uniform over [0, s_e(n)], s_e(n) = 1 - exp(-0.511/n), both ends included");
        jw_kv_str(&w, "attenuation", "s = s_e (1/s_e)^t, t = j/samples, j = 1..samples (geometric from s_e to 1, x = pi/2)");
        jw_kv_str(&w, "maxima", "located on the device grid (float), recomputed and polished in double on the host (GSL Brent)");
        jw_obj_end(&w);
    }
    jw_obj_end(&w);   /* context */
    jw_kv_arr(&w, "results");
    for (int i = 0; i < count; ++i) {
        const struct accuracy_result *r = &res[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "model", r->model.info->id);
        jw_kv_str(&w, "label", r->model.label);
        jw_kv_obj(&w, "params");
        for (int p = 0; p < r->model.info->nparams; ++p)
            jw_kv_num(&w, r->model.info->params[p].name, r->model.params[p]);
        jw_obj_end(&w);
        jw_kv_str(&w, "reference", r->reference.label);
        /* a user model as the reference: its values from the host, in double (a table the device reads) */
        jw_kv_str(&w, "reference_source",
                  accuracy_reference_is_table(&r->reference) ? "host double values" : "device code");
        jw_kv_num(&w, "n_min", r->grid.n_min);
        jw_kv_num(&w, "n_max", r->grid.n_max);
        jw_kv_str(&w, "status", accuracy_status(r));
        if (r->reason[0])
            jw_kv_str(&w, "reason", r->reason);
        jw_extreme(&w, "epicentre", "max_rel", "grid_max_rel", &r->epicentre, &r->grid_epicentre, r->reason);
        jw_extreme(&w, "attenuation", "max_abs", "grid_max_abs", &r->attenuation, &r->grid_attenuation, r->reason);
        jw_extreme(&w, "whole", "max_abs", "grid_max_abs", &r->whole, &r->grid_whole, r->reason);
        jw_kv_obj(&w, "check");
        jw_kv_num(&w, "max_rel_diff", r->check_rel_diff);
        jw_kv_num(&w, "max_abs_diff", r->check_abs_diff);
        jw_kv_num(&w, "probe_max_diff_of_peak", r->probe_rel_diff);
        jw_kv_num(&w, "in_4th_digit_units", accuracy_check_in_digits(r));
        jw_kv_num(&w, "float_cancellation", r->probe_rel_diff);
        jw_kv_num(&w, "bound_4th_digit_units", ACC_CHECK_BOUND_UNITS);
        jw_kv_num(&w, "float_floor_of_peak", ACC_CHECK_FLOAT_FLOOR);
        jw_kv_str(&w, "worst_figure", r->check.figure);
        jw_kv_num(&w, "worst_at_n", r->check.n);
        jw_kv_num(&w, "worst_diff", r->check.diff);
        jw_kv_str(&w, "status", r->check.exceeded ? "exceeded" : "ok");
        jw_kv_str(&w, "what", "every per-n device figure recomputed in double at the device's own input (s = 1 - cos x), "
                              "in units of the 4th significant digit of the reported figure it stands behind; the bound "
                              "is half a unit (then the device's choice of grid point costs at most one unit), and "
                              "differences below float_floor_of_peak times the reference's peak are float rounding, and "
                              "differences within twice float_cancellation (brought to the figure's scale) are the "
                              "model's own float error; "
                              "probe: model values at 4096 points against double, relative to the reference's peak");
        jw_obj_end(&w);
        if (r->fp16.present) {
            /* binary16 code: the same sweep of its fp16 build beside the fp32 figures above */
            jw_kv_obj(&w, "fp16");
            jw_kv_num(&w, "max_rel", r->fp16.epicentre.value);
            jw_kv_num(&w, "max_rel_at_n", r->fp16.epicentre.n);
            jw_kv_num(&w, "max_rel_at_x", r->fp16.epicentre.x);
            jw_kv_num(&w, "max_abs", r->fp16.attenuation.value);
            jw_kv_num(&w, "max_abs_at_n", r->fp16.attenuation.n);
            jw_kv_num(&w, "max_abs_at_x", r->fp16.attenuation.x);
            jw_kv_num(&w, "ratio_rel_to_fp32", r->fp16.ratio_rel);
            jw_kv_num(&w, "ratio_abs_to_fp32", r->fp16.ratio_abs);
            jw_kv_int(&w, "invalid_count", r->fp16.invalid_count);
            jw_kv_str(&w, "evaluation", "every half operation's result rounded to binary16 (round to nearest even, "
                                        "vstore_half_rte) on the device; the reference in double");
            jw_kv_bool(&w, "device_has_cl_khr_fp16", r->fp16.device_fp16);
            jw_kv_str(&w, "what", "max_rel: max delta over the epicentre, max_abs: max Delta over the attenuation "
                                  "zone, each at the per-n maximum the device grid found; ratios over the fp32 "
                                  "figures (epicentre.max_rel, attenuation.max_abs)");
            jw_obj_end(&w);
        }
        jw_kv_obj(&w, "invalid");
        jw_kv_int(&w, "count", r->invalid_count);
        jw_kv_num(&w, "at_n", r->invalid_n);
        jw_kv_num(&w, "at_x", r->invalid_x);
        jw_obj_end(&w);
        jw_kv_obj(&w, "timing");
        jw_kv_num(&w, "device_seconds", r->device_seconds);
        jw_kv_num(&w, "points", r->points);
        jw_kv_num(&w, "gpoints_per_s", r->points / r->device_seconds * 1e-9);
        jw_kv_str(&w, "timer", r->timer_wall ? "wall time: the driver's profiling events gave no time"
                                             : "profiling events");
        jw_obj_end(&w);
        /* the largest |device - double| of single model values over the reference's peak: float
           cancellation in the model's form, a figure of its own */
        jw_kv_num(&w, "float_cancellation", r->probe_rel_diff);
        jw_obj_end(&w);
    }
    hemisphere_json_rows(&w, hres, hcount);
    jw_arr_end(&w);
    rdoc_json_rows_member(&w, d);
    jw_obj_end(&w);
    int rc = jw_write_file_free(&w, path, err, errlen);
    if (keep && rc == 0)
        *keep = d;
    else
        rdoc_delete(d);
    return rc;
}

int accuracy_write_csv(const char *path, const struct accuracy_result *res, int count, char *err, size_t errlen)
{
    return accuracy_write_csv_full(path, res, count, NULL, 0, err, errlen);
}

int accuracy_write_csv_full(const char *path, const struct accuracy_result *res, int count,
                            const struct hemi_result *hres, int hcount, char *err, size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    /* column names carry their unit (docs/csv-columns.md); the JSON keys stay as they are */
    md_printf(&b, "model,n,epicentre_max_rel_fraction,epicentre_at_x_rad,attenuation_max_abs,attenuation_at_x_rad,"
                  "whole_max_abs,whole_at_x_rad,invalid_count\n");
    for (int i = 0; i < count && !b.failed; ++i) {
        const struct accuracy_result *r = &res[i];
        for (long k = 0; k < r->n_count && !b.failed; ++k) {
            const struct acc_per_n *p = &r->per_n[k];
            const struct acc_extreme *whole = p->att_abs_d.value >= p->epi_abs_d.value ? &p->att_abs_d : &p->epi_abs_d;
            /* The label may hold commas (quad:a=..,b=..): quote it. */
            md_printf(&b, "\"%s\",%.9g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.0f\n", r->model.label, p->n,
                      p->epi_rel_d.value, p->epi_rel_d.x, p->att_abs_d.value, p->att_abs_d.x, whole->value, whole->x,
                      p->invalid_count);
        }
    }
    hemisphere_csv_lines(&b, hres, hcount);
    return md_write_file_free(&b, path, err, errlen);
}

void accuracy_print_table(FILE *f, const struct accuracy_result *res, int count)
{
    fprintf(f, "%-22s %-8s %10s %8s %8s  %9s %8s %8s  %9s  %8s\n", "model", "ref", "max delta", "at n", "at x",
            "max Delta", "at n", "at x", "whole", "Gpts/s");
    fprintf(f, "%-22s %-8s %10s %8s %8s  %9s %8s %8s  %9s  %8s\n", "", "", "(epicentre)", "", "(rad)",
            "(atten.)", "", "(rad)", "max Delta", "");
    for (int i = 0; i < count; ++i) {
        const struct accuracy_result *r = &res[i];
        char epi[32], att[32], whole[32];
        /* A figure that does not exist (no finite value) is "-", never a number. */
        if (isfinite(r->epicentre.value)) snprintf(epi, sizeof epi, "%9.4g%%", 100.0 * r->epicentre.value);
        else snprintf(epi, sizeof epi, "%10s", "-");
        if (isfinite(r->attenuation.value)) snprintf(att, sizeof att, "%9.4g", r->attenuation.value);
        else snprintf(att, sizeof att, "%9s", "-");
        if (isfinite(r->whole.value)) snprintf(whole, sizeof whole, "%9.4g", r->whole.value);
        else snprintf(whole, sizeof whole, "%9s", "-");
        /* n as the device sees it (a float), in as many digits as it takes (up to 9). */
        char en[24] = "       -", ex[24] = "       -", an[24] = "       -", ax[24] = "       -";
        char nt[24];
        if (isfinite(r->epicentre.value)) {
            accuracy_format_n(r->epicentre.n, nt, sizeof nt);
            snprintf(en, sizeof en, "%8s", nt);
            snprintf(ex, sizeof ex, "%8.4g", r->epicentre.x);
        }
        if (isfinite(r->attenuation.value)) {
            accuracy_format_n(r->attenuation.n, nt, sizeof nt);
            snprintf(an, sizeof an, "%8s", nt);
            snprintf(ax, sizeof ax, "%8.4g", r->attenuation.x);
        }
        fprintf(f, "%-22s %-8s %s %s %s  %s %s %s  %s  %8.3g\n", r->model.label, r->reference.info->id, epi, en, ex,
                att, an, ax, whole, r->points / r->device_seconds * 1e-9);
        if (r->fp16.present)   /* the same code in binary16, beside the fp32 line */
            fprintf(f, "  fp16: max delta %.4g%% (%.3gx fp32), max Delta %.4g (%.3gx fp32), %lld invalid values\n",
                    100.0 * r->fp16.epicentre.value, r->fp16.ratio_rel, r->fp16.attenuation.value, r->fp16.ratio_abs,
                    r->fp16.invalid_count);
        if (strcmp(accuracy_status(r), "ok") != 0)
            fprintf(f, "  status: %s\n", accuracy_status(r));
        if (r->reason[0])
            fprintf(f, "  note: %s\n", r->reason);
    }
}
