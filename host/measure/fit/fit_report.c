/* fit_report.c - the writing side of `brdfbench fit`: fit.json and the printed summary.
 * fit.c measures; this file only turns a filled struct fit_report into text. */
#include "fit_report.h"
#include "context.h"
#include "jsonw.h"
#include "rdoc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void jw_extreme_obj(struct jw *w, const char *key, const char *metric, const struct acc_extreme *e)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, metric, e->value);
    jw_kv_num(w, "at_n", e->n);
    jw_kv_num(w, "at_x", e->x);
    if (!isfinite(e->value))
        jw_kv_str(w, "reason", "no finite values");
    jw_obj_end(w);
}

/* The two zones' figures, each with the n where it is reached, as every fit record names them. */
static void jw_zone_figures(struct jw *w, double max_rel, double max_rel_n, double max_abs, double max_abs_n)
{
    jw_kv_num(w, "max_rel", max_rel);
    jw_kv_num(w, "max_rel_at_n", max_rel_n);
    jw_kv_num(w, "max_abs", max_abs);
    jw_kv_num(w, "max_abs_at_n", max_abs_n);
}

/* A device sweep's figures, and the whole range's max Delta; all NAN when there is no sweep
 * (r NULL). */
static void jw_sweep_figures(struct jw *w, const struct accuracy_result *r)
{
    if (r)
        jw_zone_figures(w, r->epicentre.value, r->epicentre.n, r->attenuation.value, r->attenuation.n);
    else
        jw_zone_figures(w, NAN, NAN, NAN, NAN);
    jw_kv_num(w, "max_abs_whole", r ? r->whole.value : NAN);
}

static void jw_sweep_summary(struct jw *w, const struct accuracy_result *r)
{
    jw_obj_begin(w);
    jw_kv_str(w, "model", r->model.label);
    jw_kv_str(w, "reference", r->reference.label);
    jw_sweep_figures(w, r);
    jw_extreme_obj(w, "epicentre", "max_rel", &r->epicentre);
    jw_extreme_obj(w, "attenuation", "max_abs", &r->attenuation);
    jw_obj_end(w);
}

/* The fitted model's block: parameters, device figures, host figures, cap. */
static void jw_fit_model(struct jw *w, const struct fit_model *m)
{
    jw_kv_str(w, "status", m->fit.feasible ? "ok" : "infeasible");
    if (!m->fit.feasible)
        jw_kv_str(w, "reason", m->fit.reason[0] ? m->fit.reason : "no fit");
    jw_kv_str(w, "model", m->fit.feasible ? m->spec_text : "");
    jw_kv_num(w, "a", m->fit.feasible ? m->spec.params[0] : NAN);
    jw_kv_num(w, "b", m->fit.feasible ? m->spec.params[1] : NAN);
    jw_sweep_figures(w, m->have_sweep ? &m->sweep : NULL);
    jw_kv_num(w, "max_abs_cap", m->fit.cap);
    if (!isfinite(m->fit.cap))
        jw_kv_str(w, "max_abs_cap_reason", "no cap");
    jw_kv_obj(w, "host_check");
    jw_zone_figures(w, m->fit.max_rel, m->fit.max_rel_n, m->fit.max_abs, m->fit.max_abs_n);
    jw_kv_str(w, "what", "the same figures from the fit's own double-precision evaluation (exact stationary point "
                         "in the epicentre; 256-sample grid + Brent in the attenuation zone)");
    jw_obj_end(w);
}

/* A row of fit figures: its role (the fit, or the model compared) and the grid; the fitted
   coefficients (neither better higher nor lower) where the row is a fit; its device sweep's
   max delta and max Delta. */
static struct rd_row *fit_row(struct rdoc *d, const char *role, const char *grid, int with_coefs, double a, double b,
                              double max_rel, double max_abs)
{
    struct rd_row *row = rdoc_row(d, "", "fit");
    if (!row)
        return NULL;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%.120s", role);
    rd_row_key(row, "role", NULL, text);
    snprintf(text, sizeof text, "%.*s", with_coefs ? 200 : 120, grid);
    rd_row_key(row, "grid", NULL, text);
    if (with_coefs) {
        rd_row_metric(d, row, "a", "1", RD_NEITHER, 0, a);
        rd_row_metric(d, row, "b", "1", RD_NEITHER, 0, b);
    }
    rd_row_metric(d, row, "max_rel", "1", RD_LOWER, 0, max_rel);
    rd_row_metric(d, row, "max_abs", "1", RD_LOWER, 0, max_abs);
    return row;
}

/* A fitted model's row: infeasible (no coefficients) with the fit's reason; its attribute model
   names the model its device sweep ran ("" when none ran: report.md then has no line for it). */
static void fitted_row(struct rdoc *d, const char *role, const char *grid, const struct fit_model *m)
{
    const int ok = m->fit.feasible;
    struct rd_row *row = fit_row(d, role, grid, 1, ok ? m->spec.params[0] : NAN, ok ? m->spec.params[1] : NAN,
                                 m->have_sweep ? m->sweep.epicentre.value : NAN,
                                 m->have_sweep ? m->sweep.attenuation.value : NAN);
    if (row && !ok)
        rd_row_fail(row, "infeasible", m->fit.reason[0] ? m->fit.reason : "no fit");
    if (row)
        rd_row_attr(row, "model", m->have_sweep ? m->sweep.model.label : "");
}

/* fit.json's rows: the best affine fit, the fit capped at fq2's max Delta, the family's limit
   (the per-n minimax k(n): its largest max delta over the grid and the n where it is reached),
   and the models the fits are compared with (fq2 first; attribute model, the label in full),
   over the run's grid; the context's fit n_min and n_max, and the verdict as the document's
   text. */
static void fit_rows(struct rdoc *d, const struct fit_report *r)
{
    char grid[RD_TEXT], text[RD_TEXT];
    snprintf(grid, sizeof grid, "n %g..%g step %g, %g samples per zone", r->grid.n_min, r->grid.n_max, r->grid.n_step,
             (double)r->grid.samples);
    rd_ctx_put(&d->ctx, "fit grid", grid);
    snprintf(text, sizeof text, "%.17g", r->grid.n_min);
    rd_ctx_put(&d->ctx, "fit n_min", text);
    snprintf(text, sizeof text, "%.17g", r->grid.n_max);
    rd_ctx_put(&d->ctx, "fit n_max", text);
    fitted_row(d, "best affine k(n)", grid, &r->main);
    fitted_row(d, "capped at fq2's max Delta", grid, &r->at_fq2_cap);
    struct rd_row *limit = rdoc_row(d, "", "fit");
    if (limit) {
        rd_row_key(limit, "role", NULL, "per-n minimax k(n): the family's limit");
        snprintf(text, sizeof text, "%.120s", grid);
        rd_row_key(limit, "grid", NULL, text);
        rd_row_metric(d, limit, "max_rel", "1", RD_LOWER, 0, r->limit_max);
        rd_row_metric(d, limit, "at_n", "1", RD_NEITHER, 0, r->limit_max_n);
    }
    for (int i = 0; i < r->compare_count; ++i) {
        struct rd_row *row = fit_row(d, r->compare[i].model.label, grid, 0, NAN, NAN, r->compare[i].epicentre.value,
                                     r->compare[i].attenuation.value);
        if (row)
            rd_row_attr(row, "model", r->compare[i].model.label);
    }
    rdoc_text(d, "verdict", r->verdict);
}

int fit_write_json(const char *path, const struct fit_report *r, const struct cl_session *s,
                          const char *build_options, char *err, size_t errlen)
{
    struct rdoc *d = rdoc_new(FIT_SCHEMA, "fit", "fit.json", err, errlen);
    if (!d)
        return -1;
    fit_rows(d, r);
    if (rdoc_built(d, err, errlen))
        return -1;
    struct jw w;
    jw_doc_begin(&w, FIT_SCHEMA, s, build_options);
    jw_kv_obj(&w, "grid");
    jw_kv_fields(&w, &r->grid, accuracy_grid_n_fields, ACCURACY_GRID_N_FIELDS);
    jw_kv_int(&w, "n_count", r->n_count);
    jw_kv_int(&w, "samples_per_zone", r->grid.samples);
    jw_kv_str(&w, "figures", "max_rel / max_abs: the device sweep (brdfbench accuracy) polished in double");
    jw_obj_end(&w);
    jw_obj_end(&w);   /* context */
    jw_kv_str(&w, "family", "f = (k(n) (c - 1) + 1)^2, zeroed past its root; reference c^n (phong)");
    jw_kv_str(&w, "objective", "minimise over (a, b) the largest epicentre max delta over the n grid, "
                               "k(n) = a n + b; optional cap on the attenuation zone's max Delta");
    jw_fit_model(&w, &r->main);
    jw_kv_obj(&w, "limit_overall");
    jw_kv_num(&w, "max_rel", r->limit_max);
    jw_kv_num(&w, "at_n", r->limit_max_n);
    jw_kv_str(&w, "what", "largest over the grid of the per-n minimax: no k(n) of the family does better "
                          "over this range");
    jw_obj_end(&w);
    static const struct jw_field limit[] = {
        JW_FIELD(JWF_NUM, struct fit_limit, n, "n"), JW_FIELD(JWF_NUM, struct fit_limit, k, "k"),
        JW_FIELD(JWF_NUM, struct fit_limit, max_rel, "max_rel"),
    };
    jw_kv_records(&w, "limit", r->limit, (size_t)r->n_count, sizeof *r->limit, JW_FIELDS(limit));
    jw_kv_obj(&w, "capped_at_fq2");
    jw_fit_model(&w, &r->at_fq2_cap);
    jw_obj_end(&w);
    jw_kv_obj(&w, "tradeoff");
    jw_kv_str(&w, "what", "best affine fit for caps on the attenuation's max Delta between fq2's and the uncapped "
                          "fit's (host double figures)");
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct fit_affine, MEMBER, KEY)
    static const struct jw_field point[] = {
        F(JWF_NUM, cap, "max_abs_cap"), F(JWF_NUM, a, "a"), F(JWF_NUM, b, "b"), F(JWF_NUM, max_rel, "max_rel"),
        F(JWF_NUM, max_abs, "max_abs"),
    };
    #undef F
    jw_kv_records(&w, "points", r->tradeoff, (size_t)r->tradeoff_count, sizeof *r->tradeoff, JW_FIELDS(point));
    jw_obj_end(&w);
    jw_kv_arr(&w, "compare");
    if (r->main.have_sweep)
        jw_sweep_summary(&w, &r->main.sweep);
    if (r->at_fq2_cap.have_sweep)
        jw_sweep_summary(&w, &r->at_fq2_cap.sweep);
    for (int i = 0; i < r->compare_count; ++i)
        jw_sweep_summary(&w, &r->compare[i]);
    jw_arr_end(&w);
    jw_kv_obj(&w, "verdict");
    jw_kv_bool(&w, "beats_fq2_max_rel", r->beats_fq2_rel);
    jw_kv_bool(&w, "max_abs_not_worse_than_fq2", r->not_worse_abs);
    jw_kv_str(&w, "text", r->verdict);
    jw_obj_end(&w);
    jw_kv_num(&w, "seconds", r->seconds);
    rdoc_json_rows_member(&w, d);
    rdoc_delete(d);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

static void print_row(FILE *f, const char *label, const char *note, const struct accuracy_result *r)
{
    fprintf(f, "  %-36s %9.4f%% %7g  %9.5f %7g  %s\n", label, 100.0 * r->epicentre.value, r->epicentre.n,
            r->attenuation.value, r->attenuation.n, note);
}

void fit_print(FILE *f, const struct fit_report *r)
{
    fprintf(f, "fit: f = (k(n)(c-1) + 1)^2, k(n) = a n + b, minimax of the epicentre's max delta over n in "
               "[%g, %g] step %g (%ld values); device sweep %ld samples per zone\n",
            r->grid.n_min, r->grid.n_max, r->grid.n_step, r->n_count, r->grid.samples);
    fprintf(f, "family limit (per-n minimax k): max delta %.4f%% at n = %g\n", 100.0 * r->limit_max, r->limit_max_n);
    fprintf(f, "  %-36s %10s %7s  %9s %7s\n", "model", "max delta", "at n", "max Delta", "at n");
    if (r->main.have_sweep)
        print_row(f, r->main.spec_text, isfinite(r->main.fit.cap) ? "fit (capped)" : "fit", &r->main.sweep);
    else
        fprintf(f, "  fit: %s\n", r->main.fit.reason);
    if (r->at_fq2_cap.have_sweep)
        print_row(f, r->at_fq2_cap.spec_text, "fit, max Delta capped at fq2's", &r->at_fq2_cap.sweep);
    else
        fprintf(f, "  fit capped at fq2's max Delta: %s\n", r->at_fq2_cap.fit.reason);
    for (int i = 0; i < r->compare_count; ++i)
        print_row(f, r->compare[i].model.label, "", &r->compare[i]);
    if (r->tradeoff_count > 0) {
        fprintf(f, "trade-off (host figures): cap on max Delta -> best max delta:");
        for (int j = 0; j < r->tradeoff_count; ++j)
            fprintf(f, "%s %.5f -> %.4f%%", j ? "," : "", r->tradeoff[j].cap, 100 * r->tradeoff[j].max_rel);
        fprintf(f, "\n");
    }
    fprintf(f, "verdict: %s\n", r->verdict);
    if (r->main.have_sweep)
        fprintf(f, "use it: --models %s\n", r->main.spec_text);
}

/* ---- a family fit ------------------------------------------------------------------------- */

static void jw_fit_point(struct jw *w, const struct fit_family_report *r, const char *key, const struct fit_point *p)
{
    jw_kv_obj(w, key);
    jw_kv_str(w, "status", p->ok ? "ok" : "infeasible");
    if (!p->ok)
        jw_kv_str(w, "reason", p->reason);
    for (int k = 0; k < r->nparams; ++k)
        jw_kv_num(w, r->param_names[k], p->params[k]);
    jw_kv_num(w, "cap", p->cap);
    if (!isfinite(p->cap))
        jw_kv_str(w, "cap_reason", "no cap");
    jw_zone_figures(w, p->max_rel, p->max_rel_n, p->max_abs, p->max_abs_n);
    jw_obj_end(w);
}

/* A point's figures as metrics: its parameters and cap (neither: what was found, not how
 * well), its two errors (lower) and the n where each is reached (neither). */
static void family_point_metrics(struct rdoc *d, struct rd_row *row, const struct fit_family_report *r,
                                 const double *params, double cap, double max_rel, double max_rel_n, double max_abs,
                                 double max_abs_n)
{
    for (int k = 0; params && k < r->nparams; ++k)
        rd_row_metric(d, row, r->param_names[k], "1", RD_NEITHER, 0, params[k]);
    if (!isnan(cap))
        rd_row_metric(d, row, "cap", "1", RD_NEITHER, 0, cap);
    rd_row_metric(d, row, "max_rel", "1", RD_LOWER, 0, max_rel);
    if (!isnan(max_rel_n))
        rd_row_metric(d, row, "max_rel.at_n", "1", RD_NEITHER, 0, max_rel_n);
    rd_row_metric(d, row, "max_abs", "1", RD_LOWER, 0, max_abs);
    if (!isnan(max_abs_n))
        rd_row_metric(d, row, "max_abs.at_n", "1", RD_NEITHER, 0, max_abs_n);
}

/* The family fit's rows: the fit, the two ends of the trade-off, each trade-off point (with its
 * cap on max Delta) and the device sweep of the fitted model. */
static struct rdoc *family_rows(const char *path, const struct fit_family_report *r, char *err, size_t errlen)
{
    const char *base = strrchr(path, '/');
    struct rdoc *d = rdoc_new(FIT_FAMILY_SCHEMA, "fit_family", base ? base + 1 : path, err, errlen);
    if (!d)
        return NULL;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%s, objective %s", r->family, r->opt.objective == FIT_MAX_ABS ? "max_abs" : "max_rel");
    rd_ctx_put(&d->ctx, "family fit", text);
    static const char *const names[3] = { "fit", "min_max_rel", "min_max_abs" };
    const struct fit_point *pts[3] = { &r->best, &r->min_rel, &r->min_abs };
    for (int i = 0; i < 3; ++i) {
        struct rd_row *row = rdoc_row(d, NULL, r->family);
        if (!row)
            break;
        rd_row_key(row, "point", NULL, names[i]);
        if (!pts[i]->ok)
            rd_row_fail(row, "infeasible", pts[i]->reason);
        family_point_metrics(d, row, r, pts[i]->params, pts[i]->cap, pts[i]->max_rel, pts[i]->max_rel_n,
                             pts[i]->max_abs, pts[i]->max_abs_n);
    }
    for (int j = 0; j < r->tradeoff_count; ++j) {
        struct rd_row *row = rdoc_row(d, NULL, r->family);
        if (!row)
            break;
        /* keyed by its place (the caps themselves move with the two ends between runs) */
        snprintf(text, sizeof text, "tradeoff %d of %d", j + 1, r->tradeoff_count);
        rd_row_key(row, "point", NULL, text);
        family_point_metrics(d, row, r, r->tradeoff[j].params, r->tradeoff[j].cap, r->tradeoff[j].max_rel, NAN,
                             r->tradeoff[j].max_abs, NAN);
    }
    struct rd_row *row = rdoc_row(d, NULL, r->family);
    if (row) {
        rd_row_key(row, "point", NULL, "device");
        if (r->have_sweep) {
            rd_row_attr(row, "model", r->sweep.model.label);
            family_point_metrics(d, row, r, NULL, NAN, r->sweep.epicentre.value, r->sweep.epicentre.n,
                                 r->sweep.attenuation.value, r->sweep.attenuation.n);
        } else {
            rd_row_fail(row, "not measured", r->best.ok ? "no device kernel for this family (power m other than 2, 3, "
                                                          "4)" : "no fitted model");
        }
    }
    return rdoc_built(d, err, errlen) ? NULL : d;
}

int fit_family_write_json(const char *path, const struct fit_family_report *r, const struct cl_session *s,
                          char *err, size_t errlen)
{
    struct rdoc *rows = family_rows(path, r, err, errlen);
    if (!rows)
        return -1;
    struct jw w;
    jw_doc_begin(&w, FIT_FAMILY_SCHEMA, s, "");
    jw_kv_obj(&w, "grid");
    jw_kv_fields(&w, &r->grid, accuracy_grid_n_fields, ACCURACY_GRID_N_FIELDS);
    jw_kv_int(&w, "samples_per_zone", r->grid.samples);
    jw_kv_str(&w, "figures", "host: every n of the grid, each zone on a grid polished with Brent, in double; "
                             "device: the accuracy sweep of the fitted model");
    jw_obj_end(&w);
    jw_obj_end(&w);   /* context */
    jw_kv_str(&w, "family", r->family);
    jw_kv_str(&w, "objective", r->opt.objective == FIT_MAX_ABS ? "max_abs" : "max_rel");
    jw_kv_str(&w, "method", "Nelder-Mead (GSL nmsimplex2, restarted) on the largest figure over 54 n values of the "
                            "range, a cap as an exact penalty; figures then over every n of the grid");
    jw_kv_str(&w, "model", r->spec_text);
    jw_fit_point(&w, r, "fit", &r->best);
    jw_fit_point(&w, r, "min_max_rel", &r->min_rel);
    jw_fit_point(&w, r, "min_max_abs", &r->min_abs);
    jw_kv_arr(&w, "tradeoff");
    for (int j = 0; j < r->tradeoff_count; ++j) {
        jw_obj_begin(&w);
        for (int k = 0; k < r->nparams; ++k)
            jw_kv_num(&w, r->param_names[k], r->tradeoff[j].params[k]);
        jw_kv_num(&w, "max_abs_cap", r->tradeoff[j].cap);
        jw_kv_num(&w, "max_rel", r->tradeoff[j].max_rel);
        jw_kv_num(&w, "max_abs", r->tradeoff[j].max_abs);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_key(&w, "device");
    if (r->have_sweep) {
        jw_obj_begin(&w);
        jw_kv_str(&w, "model", r->sweep.model.label);
        jw_zone_figures(&w, r->sweep.epicentre.value, r->sweep.epicentre.n, r->sweep.attenuation.value,
                        r->sweep.attenuation.n);
        jw_obj_end(&w);
    } else {
        jw_obj_begin(&w);
        jw_kv_str(&w, "status", "not measured");
        jw_kv_str(&w, "reason", r->best.ok ? "no device kernel for this family (power m other than 2, 3, 4)"
                                           : "no fitted model");
        jw_obj_end(&w);
    }
    jw_kv_num(&w, "seconds", r->seconds);
    rdoc_json_rows_member(&w, rows);
    rdoc_delete(rows);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

static void print_point(FILE *f, const struct fit_family_report *r, const char *what, const struct fit_point *p)
{
    fprintf(f, "  %-34s", what);
    for (int k = 0; k < r->nparams; ++k)
        fprintf(f, " %s=%-14.10g", r->param_names[k], p->params[k]);
    fprintf(f, " max delta %8.4f%% (n = %g)  max Delta %.5f (n = %g)%s\n", 100 * p->max_rel, p->max_rel_n,
            p->max_abs, p->max_abs_n, p->ok ? "" : "  infeasible");
}

void fit_family_print(FILE *f, const struct fit_family_report *r)
{
    fprintf(f, "fit: family %s over n in [%g, %g] step %g; objective %s%s\n", r->family, r->grid.n_min,
            r->grid.n_max, r->grid.n_step, r->opt.objective == FIT_MAX_ABS ? "max_abs" : "max_rel",
            isfinite(r->best.cap) ? " with a cap" : "");
    fprintf(f, "host figures (double, every n of the grid):\n");
    print_point(f, r, "fit", &r->best);
    print_point(f, r, "least max delta", &r->min_rel);
    print_point(f, r, "least max Delta", &r->min_abs);
    if (r->tradeoff_count) {
        fprintf(f, "trade-off: cap on max Delta -> best max delta:");
        for (int j = 0; j < r->tradeoff_count; ++j)
            fprintf(f, "%s %.5f -> %.4f%%", j ? "," : "", r->tradeoff[j].cap, 100 * r->tradeoff[j].max_rel);
        fprintf(f, "\n");
    }
    if (r->have_sweep)
        fprintf(f, "device sweep of %s: max delta %.4f%% (n = %g), max Delta %.5f (n = %g)\n", r->sweep.model.label,
                100 * r->sweep.epicentre.value, r->sweep.epicentre.n, r->sweep.attenuation.value,
                r->sweep.attenuation.n);
    if (r->spec_text[0])
        fprintf(f, "use it: --models %s\n", r->spec_text);
}
