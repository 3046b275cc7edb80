/* hemisphere_report.c - the hemisphere sweep's figures: its rows of accuracy.json (read back by
 * rdoc_read.c as hemisphere.* metrics), its per-parameter CSV lines and the printed table. */
#include "hemisphere_report.h"

#include "rdoc.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void extreme(struct jw *w, const char *key, const char *metric, const struct hemi_extreme *e,
                    const struct hemi_extreme *grid)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, metric, e->value);
    jw_kv_num(w, "at_p", e->p);
    jw_kv_num(w, "at_theta_h", e->th);
    jw_kv_num(w, "at_theta_d", e->td);
    jw_kv_num(w, "at_phi_d", e->pd);
    if (grid)
        jw_kv_num(w, "grid_value", grid->value);
    jw_obj_end(w);
}

void hemisphere_rows(struct rdoc *d, const struct hemi_result *res, int count, double n_step)
{
    char text[RD_TEXT];
    for (int i = 0; i < count; ++i) {
        const struct hemi_result *r = &res[i];
        struct rd_row *row = rdoc_row(d, "", r->model.label);
        if (!row)
            return;
        snprintf(text, sizeof text, "%.120s", r->model.label);
        rd_row_key(row, "label", NULL, text);
        /* a full BRDF's row: its axis and hemisphere grid are its grid */
        snprintf(text, sizeof text, "vs %.60s, hemisphere %.40s %.9g..%.9g x%.0f, %.0fx%.0fx%.0f", r->reference.label,
                 r->axis.name, r->axis.min, r->axis.max, (double)r->axis.count, (double)r->grid.nh,
                 (double)r->grid.nd, (double)r->grid.np);
        rd_row_key(row, "grid", NULL, text);
        const char *status = hemisphere_status(r);
        if (strcmp(status, "ok") != 0)
            rd_row_fail(row, status, r->reason[0] ? r->reason : status);
        /* no n range of its own: the attributes say so (nan), as the rows of earlier files */
        rd_row_attr(row, "n_min", "nan");
        rd_row_attr(row, "n_max", "nan");
        snprintf(text, sizeof text, "%.17g", n_step);
        rd_row_attr(row, "n_step", text);
        rd_row_attr(row, "reference", r->reference.label);
        const struct { const char *name; double v; } fig[] = {
            { "hemisphere.epicentre.max_rel", r->epicentre.value },
            { "hemisphere.attenuation.max_abs", r->attenuation.value },
            { "hemisphere.whole.max_abs", r->whole.value },
            { "hemisphere.rms", r->rms.value },
            { "hemisphere.float_cancellation", r->float_cancellation },
            { "hemisphere.evaluated_below_horizon", (double)r->eval_below },
        };
        for (size_t f = 0; f < sizeof fig / sizeof fig[0]; ++f)
            rd_row_metric(d, row, fig[f].name, "1", RD_LOWER, 0, fig[f].v);
    }
}

void hemisphere_json_rows(struct jw *w, const struct hemi_result *res, int count)
{
    for (int i = 0; i < count; ++i) {
        const struct hemi_result *r = &res[i];
        jw_obj_begin(w);
        jw_kv_str(w, "model", r->model.info->id);
        jw_kv_str(w, "label", r->model.label);
        jw_kv_str(w, "sweep", "hemisphere");
        jw_kv_obj(w, "params");
        for (int p = 0; p < r->model.info->nparams; ++p)
            jw_kv_num(w, r->model.info->params[p].name, r->model.params[p]);
        jw_obj_end(w);
        jw_kv_str(w, "reference", r->reference.label);
        /* how the device had the reference: its own code, or the host's double values read from a
           table (a user model or a measured material as the reference) */
        jw_kv_str(w, "reference_source", hemisphere_reference_source(r));
        jw_kv_str(w, "status", hemisphere_status(r));
        if (r->reason[0])
            jw_kv_str(w, "reason", r->reason);
        jw_kv_obj(w, "hemisphere");
        jw_kv_obj(w, "axis");
        jw_kv_str(w, "name", r->axis.name);
        jw_kv_num(w, "min", r->axis.min);
        jw_kv_num(w, "max", r->axis.max);
        jw_kv_int(w, "count", r->axis.count);
        jw_kv_str(w, "spacing", r->axis.geometric ? "geometric" : "uniform");
        jw_obj_end(w);
        jw_kv_obj(w, "grid");
        jw_kv_int(w, "theta_h", r->grid.nh);
        jw_kv_int(w, "theta_d", r->grid.nd);
        jw_kv_int(w, "phi_d", r->grid.np);
        jw_kv_str(w, "what", "theta_h = pi/2 ((i + 1/2)/NH)^2, theta_d = pi/2 (j + 1/2)/ND, phi_d = pi (k + 1/2)/NP; "
                             "samples where N.L > 0 and N.V > 0");
        jw_obj_end(w);
        extreme(w, "epicentre", "max_rel", &r->epicentre, &r->grid_epicentre);
        extreme(w, "attenuation", "max_abs", &r->attenuation, &r->grid_attenuation);
        extreme(w, "whole", "max_abs", &r->whole, &r->grid_whole);
        jw_kv_num(w, "rms", r->rms.value);
        jw_kv_num(w, "rms_at_p", r->rms.p);
        jw_kv_num(w, "float_cancellation", r->float_cancellation);
        jw_kv_num(w, "peak_ratio", r->peak_ratio);
        jw_kv_obj(w, "samples");
        jw_kv_int(w, "used", r->used);
        jw_kv_int(w, "below_horizon", r->below);
        jw_kv_int(w, "evaluated_below_horizon", r->eval_below);
        jw_kv_int(w, "invalid", r->invalid);
        jw_kv_int(w, "uncovered", r->uncovered);
        jw_obj_end(w);
        jw_kv_obj(w, "check");
        jw_kv_str(w, "status", r->check.exceeded ? "exceeded" : "ok");
        jw_kv_str(w, "worst_figure", r->check.figure ? r->check.figure : "");
        jw_kv_num(w, "worst_diff", r->check.diff);
        jw_kv_num(w, "worst_at_p", r->check.p);
        jw_kv_num(w, "in_4th_digit_units", r->check.units);
        jw_kv_num(w, "reference_float_error", r->ref_float_error);
        jw_kv_int(w, "figures_at_float_noise", r->checks_at_float_noise);
        jw_kv_str(w, "what", "each per-p device maximum recomputed in double at its grid point: within half a unit of "
                             "the figure's 4th significant digit; a figure whose double value is below 2^-23 of the "
                             "reference's peak is ok within 8 x 2^-24 of the peak or within twice the float noise of "
                             "the model and reference values (float_cancellation + reference_float_error: max "
                             "|f_device - f_double| / peak at 4096 random samples); figures_at_float_noise counts "
                             "those ok only by that floor");
        jw_obj_end(w);
        jw_kv_arr(w, "per_p");
        for (int k = 0; k < r->p_count; ++k) {
            const struct hemi_per_p *pp = &r->per_p[k];
            jw_obj_begin(w);
            jw_kv_num(w, "p", pp->p);
            jw_kv_nums(w, "model_n_p0_p1", pp->mvals, 3);
            jw_kv_nums(w, "reference_n_p0_p1", pp->rvals, 3);
            jw_kv_num(w, "peak", pp->peak);
            extreme(w, "epicentre", "max_rel", &pp->epi_rel, &pp->dev_epi_rel);
            extreme(w, "attenuation", "max_abs", &pp->att_abs, &pp->dev_att_abs);
            extreme(w, "whole", "max_abs", &pp->whole_abs, &pp->dev_whole_abs);
            jw_kv_num(w, "rms", pp->rms);
            jw_kv_num(w, "rms_device", pp->rms_device);
            jw_kv_int(w, "samples", pp->used);
            jw_obj_end(w);
        }
        jw_arr_end(w);
        jw_obj_end(w);   /* hemisphere */
        jw_kv_obj(w, "timing");
        jw_kv_num(w, "device_seconds", r->device_seconds);
        jw_kv_num(w, "points", r->points);
        jw_obj_end(w);
        jw_obj_end(w);
    }
}

void hemisphere_csv_lines(struct md_buf *b, const struct hemi_result *res, int count)
{
    for (int i = 0; i < count && !b->failed; ++i)
        for (int k = 0; k < res[i].p_count && !b->failed; ++k) {
            const struct hemi_per_p *pp = &res[i].per_p[k];
            md_printf(b, "\"%s\",%.9g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%lld\n", res[i].model.label, pp->p,
                      pp->epi_rel.value, pp->epi_rel.th, pp->att_abs.value, pp->att_abs.th, pp->whole_abs.value,
                      pp->whole_abs.th, pp->invalid);
        }
}

void hemisphere_print_table(FILE *f, const struct hemi_result *res, int count)
{
    if (count <= 0)
        return;
    fprintf(f, "\nfull BRDFs over the hemisphere (N.L > 0, N.V > 0; angles in rad: theta_h theta_d phi_d)\n");
    for (int i = 0; i < count; ++i) {
        const struct hemi_result *r = &res[i];
        fprintf(f, "%s against %s, %s in [%g, %g] (%d values), grid %dx%dx%d: %lld samples, %lld grid points below "
                   "the horizon (not samples), %lld evaluated below it\n",
                r->model.label, r->reference.label, r->axis.name, r->axis.min, r->axis.max, r->axis.count, r->grid.nh,
                r->grid.nd, r->grid.np, r->used, r->below, r->eval_below);
        if (r->uncovered > 0)
            fprintf(f, "  %lld grid points above the horizon where the reference has no value (not samples)\n",
                    r->uncovered);
        const struct { const char *what; const struct hemi_extreme *e; int pct; } rows[] = {
            { "max delta (epicentre)", &r->epicentre, 1 },
            { "max Delta (attenuation)", &r->attenuation, 0 },
            { "max Delta (whole)", &r->whole, 0 },
        };
        for (size_t k = 0; k < sizeof rows / sizeof rows[0]; ++k) {
            const struct hemi_extreme *e = rows[k].e;
            if (!isfinite(e->value)) {
                fprintf(f, "  %-24s -\n", rows[k].what);
                continue;
            }
            fprintf(f, "  %-24s %.4g%s at %s = %.6g, (%.5g, %.5g, %.5g)\n", rows[k].what,
                    rows[k].pct ? 100 * e->value : e->value, rows[k].pct ? "%" : "", r->axis.name, e->p, e->th, e->td,
                    e->pd);
        }
        fprintf(f, "  %-24s %.4g at %s = %.6g\n", "RMS cos(ti) (f - f_ref)", r->rms.value, r->axis.name, r->rms.p);
        fprintf(f, "  %-24s %.3g of the peak; f/f_ref at L = V = N: %.6g\n", "float cancellation",
                r->float_cancellation, r->peak_ratio);
        fprintf(f, "  status: %s%s%s\n", hemisphere_status(r), r->reason[0] ? "; " : "", r->reason);
    }
}
