/* report_accuracy.c - report.md's accuracy table and fit section from rows (report_accuracy.h). */
#include "report_accuracy.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void report_md_pct(struct md_buf *b, double v)
{
    if (isfinite(v)) md_printf(b, " %.4g%% |", 100 * v);
    else md_printf(b, " n/a |");
}

void report_md_num(struct md_buf *b, double v, const char *fmt)
{
    if (isfinite(v)) {
        md_printf(b, " ");
        md_printf(b, fmt, v);
        md_printf(b, " |");
    } else {
        md_printf(b, " n/a |");
    }
}

/* A context line's number (written with 17 digits), or NAN when the line is not there. */
static double ctx_num(const struct rdoc *d, const char *key)
{
    const char *v = rd_ctx_get(&d->ctx, key);
    char *end;
    if (!v || !*v) return NAN;
    double x = strtod(v, &end);
    return *end ? NAN : x;
}

/* A row's status cell: why it was not measured, its invalid values, or ok. */
static void status_cell(struct md_buf *b, const struct rd_row *r)
{
    if (strcmp(r->status, "failed") == 0 || strcmp(r->status, "device_disagrees") == 0) {
        md_printf(b, " %s: ", r->status);
        /* a row failed without a reason carries its status word as the reason */
        md_cell_text(b, strcmp(r->reason, r->status) == 0 ? "" : r->reason);
        md_printf(b, " |\n");
    } else if (strcmp(r->status, "invalid_values") == 0) {
        md_printf(b, " %lld invalid values (first at n = %g, x = %g) |\n", (long long)rd_row_value(r, "invalid.count"),
                  rd_row_value(r, "invalid.at_n"), rd_row_value(r, "invalid.at_x"));
    } else if (strcmp(r->model, rd_row_key_value(r, "reference") ? rd_row_key_value(r, "reference") : "") == 0) {
        md_printf(b, " reference (zero by definition) |\n");
    } else {
        md_printf(b, " ok |\n");
    }
}

void report_accuracy_table(struct md_buf *b, const struct rdoc *acc)
{
    md_printf(b, "## Accuracy per model\n\n");
    if (!acc || acc->nrows < 1) {
        md_printf(b, "Not available: the accuracy sweep did not run.\n\n");
        return;
    }
    if (rd_ctx_get(&acc->ctx, "accuracy n_min"))
        md_printf(b,
                  "Dense grid: n from %g to %g in steps of %g, %ld samples per zone per n; each maximum located on the "
                  "device (float) and then recomputed and refined in double on the host. delta = |f - f_ref| / f_ref "
                  "over the epicentre x in [0, x_e(n)], x_e(n) = acos(exp(-0.511/n)); Delta = |f - f_ref| over the "
                  "attenuation zone (x_e(n), pi/2] and over the whole range. x is psi for the Phong family, theta_h "
                  "for the Blinn family and the microfacet distributions.\n\n",
                  ctx_num(acc, "accuracy n_min"), ctx_num(acc, "accuracy n_max"), ctx_num(acc, "accuracy n_step"),
                  (long)ctx_num(acc, "accuracy samples per zone"));
    md_printf(b, "| model | reference | max delta, epicentre | at n | at x (rad) | max Delta, attenuation | at n | at x (rad) "
                 "| max Delta, whole range | device vs double (4th-digit units) | status |\n");
    md_printf(b, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < acc->nrows; i++) {
        const struct rd_row *r = &acc->rows[i];
        const char *ref = rd_row_key_value(r, "reference");
        md_printf(b, "| `");
        md_cell_text(b, r->model);
        md_printf(b, "` | `");
        md_cell_text(b, ref ? ref : "");
        md_printf(b, "` |");
        /* a hemisphere sweep's row has its figures under hemisphere.*: its cells here are n/a */
        report_md_pct(b, rd_row_value(r, "epicentre.max_rel"));
        report_md_num(b, rd_row_value(r, "epicentre.at_n"), "%.6g");
        report_md_num(b, rd_row_value(r, "epicentre.at_x"), "%.5f");
        report_md_num(b, rd_row_value(r, "attenuation.max_abs"), "%.4g");
        report_md_num(b, rd_row_value(r, "attenuation.at_n"), "%.6g");
        report_md_num(b, rd_row_value(r, "attenuation.at_x"), "%.5f");
        report_md_num(b, rd_row_value(r, "whole.max_abs"), "%.4g");
        report_md_num(b, rd_row_value(r, "check.in_4th_digit_units"), "%.2g");
        status_cell(b, r);
    }
    md_printf(b, "\n");
}

/* The fit's rows: the family's limit, the two fits and the models compared (fit_rows). */
#define FIT_ROLE_LIMIT "per-n minimax k(n): the family's limit"
static const char *const fit_roles[2] = { "best affine k(n)", "capped at fq2's max Delta" };

static const char *role_of(const struct rd_row *r)
{
    const char *role = rd_row_key_value(r, "role");
    return role ? role : "";
}

int report_fit_block(struct md_buf *b, const struct rdoc *fit, const char *run_dir, char *err, size_t errlen)
{
    const struct rd_row *limit = rdoc_find_row(fit, "role", FIT_ROLE_LIMIT);
    if (!rd_ctx_get(&fit->ctx, "fit n_min") || !limit) {
        snprintf(err, errlen, "%s/fit.json: no fit grid or no family limit in its rows", run_dir);
        return 2;
    }
    md_printf(b, "For f = (k(n)(c - 1) + 1)^2 zeroed past its root, over n in [%g, %g] (`brdfbench fit`, `fit.json`):\n\n",
              ctx_num(fit, "fit n_min"), ctx_num(fit, "fit n_max"));
    md_printf(b, "| model | max δ (epicentre) | max Δ (attenuation) |\n|---|---|---|\n");
    md_printf(b, "| per-n minimax k(n): the family's limit | %.4f%% (n = %g) | |\n", 100 * rd_row_value(limit, "max_rel"),
              rd_row_value(limit, "at_n"));
    /* a fit's line is there when its device sweep ran: its row then names the model swept */
    static const char *const notes[2] = { " (best affine, uncapped)", " (max Δ capped at fq2's)" };
    for (int i = 0; i < 2; ++i) {
        const struct rd_row *r = rdoc_find_row(fit, "role", fit_roles[i]);
        const char *model = r ? rd_row_key_value(r, "model") : NULL;
        if (model && model[0])
            md_printf(b, "| `%s`%s | %.4f%% | %.5f |\n", model, notes[i], 100 * rd_row_value(r, "max_rel"),
                      rd_row_value(r, "max_abs"));
    }
    for (int i = 0; i < fit->nrows; ++i) {
        const struct rd_row *r = &fit->rows[i];
        const char *role = role_of(r);
        if (strcmp(role, FIT_ROLE_LIMIT) == 0 || strcmp(role, fit_roles[0]) == 0 || strcmp(role, fit_roles[1]) == 0)
            continue;
        const char *model = rd_row_key_value(r, "model");   /* the label in full (the role key is cut at 120) */
        md_printf(b, "| %s | %.4f%% | %.5f |\n", model ? model : role, 100 * rd_row_value(r, "max_rel"),
                  rd_row_value(r, "max_abs"));
    }
    const char *verdict = rdoc_text_or(fit, "verdict", "");
    if (verdict[0]) md_printf(b, "\n%s\n", verdict);
    md_printf(b, "\n\n");
    return 0;
}
