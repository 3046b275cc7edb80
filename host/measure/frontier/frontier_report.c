/* frontier_report.c - frontier.json, frontier.csv, the two scatter plots, the printed table and
 * the "Which lobe to ship" markdown, from a filled struct frontier_report (frontier.c). */
#include "frontier_report.h"
#include "context.h"
#include "draw.h"
#include "plots.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "rdoc.h"
#include "outdir.h"

#include <math.h>
#include <unistd.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const range_names[2] = { "n_2_1000", "n_16_1000" };

#define FRONTIER_UNMEASURED "no finite error figure (the model's values are NaN or Inf): not a point of the front"

/* frontier.json's "definitions": what each figure of a row means. */
static const char *const frontier_definitions[][2] = {
    { "rate", "device evaluations per second, throughput kernels with the default build options, timed "
              "by the runner (host/core/runner.h): rounds x reps rounds over every model in a fresh random "
              "order with the peak kernel as each round's reference; median, min and max over the rounds; "
              "uniform: one n per launch, varying: n per evaluation" },
    { "normalised", "rate / the peak kernel's rate in the same round (per CPU second on a CPU device "
                    "where the runner keeps it): what the front is decided on" },
    { "max_rel", "largest epicentre delta over the n range (device sweep polished in double)" },
    { "max_abs", "largest attenuation-zone Delta over the n range" },
    { "psnr_db", "teapot image pass against the model's reference, 8-bit sRGB, peak 255" },
    { "front", "Pareto set over (uniform normalised rate, max_rel and max_abs over n in [2, 1000]); two "
               "rates whose medians are within 10% of each other (compare's minimum change) count as equal" },
    { "ops", "per evaluation: arith = FMA/mul/add/sub/conversions, minmax = min/max/select, div, "
             "transc = exp/log/pow/acos/sqrt/expm1 calls (docs/frontier.md)" },
};

/* frontier.json's rows: one per model with its accuracy over each n range (max delta and max
   Delta, lower is better) and its teapot PSNR. */
static void frontier_rows(struct rdoc *d, const struct frontier_report *r)
{
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        struct rd_row *rr = rdoc_row(d, "", row->spec.label);
        if (!rr)
            return;
        rd_row_key(rr, "model", NULL, row->spec.label);
        if (!(isfinite(row->max_rel[0]) && isfinite(row->max_abs[0])))
            rd_row_fail(rr, "failed", FRONTIER_UNMEASURED);
        for (int k = 0; k < 2; ++k) {
            char name[RD_NAME];
            snprintf(name, sizeof name, "%s.max_rel", range_names[k]);
            rd_row_metric(d, rr, name, "1", RD_LOWER, 0, row->max_rel[k]);
            snprintf(name, sizeof name, "%s.max_abs", range_names[k]);
            rd_row_metric(d, rr, name, "1", RD_LOWER, 0, row->max_abs[k]);
        }
        rd_row_metric(d, rr, "psnr_db", "dB", RD_HIGHER, 0, row->psnr_db);
    }
}

int frontier_write_json(const char *path, const struct frontier_report *r, const struct cl_session *s, char *err,
                        size_t errlen)
{
    struct rdoc *d = rdoc_new(FRONTIER_SCHEMA, "frontier", "frontier.json", err, errlen);
    if (!d)
        return -1;
    frontier_rows(d, r);
    if (rdoc_built(d, err, errlen))
        return -1;
    struct jw w;
    jw_doc_begin(&w, FRONTIER_SCHEMA, s, "");
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct frontier_options, MEMBER, KEY)
    static const struct jw_field options[] = {
        F(JWF_LONG, samples, "samples_per_zone"), F(JWF_INT, reps, "reps"), F(JWF_INT, rounds, "rounds"),
        F(JWF_NUM, min_time, "min_time_s"), F(JWF_INT, image_w, "image_width"), F(JWF_INT, image_h, "image_height"),
    };
    #undef F
    jw_kv_fields(&w, &r->opt, JW_FIELDS(options));
    jw_obj_end(&w);
    jw_kv_texts(&w, "definitions", JW_TEXTS(frontier_definitions));
    jw_kv_arr(&w, "models");
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "model", row->spec.label);
        jw_kv_str(&w, "kind", model_kind_name(row->kind));
        jw_kv_str(&w, "source", row->spec.info->description);
        jw_kv_bool(&w, "on_front", row->on_front);
        int measured = isfinite(row->max_rel[0]) && isfinite(row->max_abs[0]);
        jw_kv_str(&w, "status", measured ? "ok" : "failed");
        if (!measured)
            jw_kv_str(&w, "reason", FRONTIER_UNMEASURED);
        for (int m = 0; m < 2; ++m) {
            jw_kv_obj(&w, m ? "rate_varying" : "rate_uniform");
            jw_kv_num(&w, "min", row->rate[m][0]);
            jw_kv_num(&w, "median", row->rate[m][1]);
            jw_kv_num(&w, "max", row->rate[m][2]);
            jw_kv_obj(&w, "normalised");
            jw_kv_num(&w, "min", row->norm[m][0]);
            jw_kv_num(&w, "median", row->norm[m][1]);
            jw_kv_num(&w, "max", row->norm[m][2]);
            jw_obj_end(&w);
            if (!isfinite(row->rate[m][1]))
                jw_kv_str(&w, "reason", row->rate_reason[0] ? row->rate_reason : "not measured");
            jw_obj_end(&w);
        }
        jw_kv_obj(&w, "ops");
        if (row->ops.known) {
            jw_kv_int(&w, "arith", row->ops.arith);
            jw_kv_int(&w, "minmax", row->ops.minmax);
            jw_kv_int(&w, "div", row->ops.div);
            jw_kv_int(&w, "transc", row->ops.transc);
        } else {
            jw_kv_str(&w, "status", "unknown");
        }
        jw_kv_str(&w, "note", row->ops.note);
        jw_obj_end(&w);
        for (int k = 0; k < 2; ++k) {
            jw_kv_obj(&w, range_names[k]);
            jw_kv_num(&w, "max_rel", row->max_rel[k]);
            jw_kv_num(&w, "max_rel_at_n", row->max_rel_n[k]);
            jw_kv_num(&w, "max_abs", row->max_abs[k]);
            jw_kv_num(&w, "max_abs_at_n", row->max_abs_n[k]);
            jw_obj_end(&w);
        }
        jw_kv_num(&w, "psnr_db", row->psnr_db);
        if (!isfinite(row->psnr_db))
            jw_kv_str(&w, "psnr_reason", row->psnr_reason[0] ? row->psnr_reason : "not measured");
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_num(&w, "seconds", r->seconds);
    rdoc_json_rows_member(&w, d);
    rdoc_delete(d);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

int frontier_write_csv(const char *path, const struct frontier_report *r, char *err, size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    /* column names carry their unit (docs/csv-columns.md); the JSON keys stay as they are */
    md_printf(&b, "model,kind,on_front,evals_per_s_uniform_median,evals_per_s_uniform_min,evals_per_s_uniform_max,"
                  "evals_per_s_varying_median,arith_ops,minmax_ops,div_ops,transc_ops,max_rel_fraction_n2_1000,"
                  "max_abs_n2_1000,max_rel_fraction_n16_1000,max_abs_n16_1000,psnr_db\n");
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        md_printf(&b, "\"%s\",%s,%d,%.6g,%.6g,%.6g,%.6g,", row->spec.label, model_kind_name(row->kind), row->on_front,
                  row->rate[0][1], row->rate[0][0], row->rate[0][2], row->rate[1][1]);
        if (row->ops.known)
            md_printf(&b, "%d,%d,%d,%d,", row->ops.arith, row->ops.minmax, row->ops.div, row->ops.transc);
        else
            md_printf(&b, ",,,,");
        md_printf(&b, "%.6g,%.6g,%.6g,%.6g,", row->max_rel[0], row->max_abs[0], row->max_rel[1], row->max_abs[1]);
        if (isfinite(row->psnr_db))
            md_printf(&b, "%.4g\n", row->psnr_db);
        else
            md_printf(&b, "\n");
    }
    return md_write_file_free(&b, path, err, errlen);
}

int frontier_plots_drawable(const struct frontier_report *r)
{
    for (int i = 0; i < r->count; ++i)
        if (isfinite(r->rows[i].rate[0][1]) && r->rows[i].rate[0][1] > 0)
            return 1;
    return 0;
}

int frontier_write_plots(const char *dir, const struct frontier_report *r, char *err, size_t errlen)
{
    if (!frontier_plots_drawable(r)) {
        /* no point to draw: no plot, and none of an earlier run left beside these tables */
        for (int fig = 0; fig < 2; ++fig) {
            char path[4300];
            path_join(path, sizeof path, dir, fig == 0 ? "frontier_max_rel.png" : "frontier_max_abs.png");
            if (unlink(path) != 0 && errno != ENOENT) {
                snprintf(err, errlen, "%s: cannot remove the plot of an earlier run: %s", path, strerror(errno));
                return -1;
            }
        }
        return 0;
    }
    double x[FRONTIER_MAX_MODELS], y[FRONTIER_MAX_MODELS];
    const char *labels[FRONTIER_MAX_MODELS];
    int kinds[FRONTIER_MAX_MODELS], front[FRONTIER_MAX_MODELS];
    for (int fig = 0; fig < 2; ++fig) {
        int n = 0;
        for (int i = 0; i < r->count; ++i) {
            const struct frontier_row *row = &r->rows[i];
            /* a reference is exact up to rounding: drawn at the axis floor, not at 1e-16 */
            x[n] = row->kind == MODEL_KIND_REFERENCE ? 0.0 : fig == 0 ? row->max_rel[0] : row->max_abs[0];
            y[n] = row->rate[0][1];
            labels[n] = row->spec.label;
            kinds[n] = row->kind == MODEL_KIND_REFERENCE ? DRAW_MARK_REFERENCE
                       : row->kind == MODEL_KIND_PAPER   ? DRAW_MARK_PAPER
                                                 : DRAW_MARK_OTHER;
            front[n] = row->on_front;
            n++;
        }
        struct draw_scatter sc = { fig == 0 ? "Cost and accuracy: evaluations/s against max delta (n in [2, 1000])"
                                            : "Cost and accuracy: evaluations/s against max Delta (n in [2, 1000])",
                                   fig == 0 ? "max delta in the epicentre (log)" : "max Delta in the attenuation zone (log)",
                                   "device evaluations/s, n uniform (log)",
                                   fig == 0 ? DRAW_FMT_PERCENT : DRAW_FMT_PLAIN,
                                   n, x, y, labels, kinds, front };
        char path[4300];
        path_join(path, sizeof path, dir, fig == 0 ? "frontier_max_rel.png" : "frontier_max_abs.png");
        if (draw_scatter_plot(path, &sc, err, errlen) || plots_stamp_if_quick(path, 0, err, errlen))
            return -1;
    }
    return 0;
}

void frontier_print(FILE *f, const struct frontier_report *r)
{
    fprintf(f, "%-14s %-9s %5s %11s %11s %6s %10s %9s %10s %9s %7s\n", "model", "kind", "front", "uniform/s",
            "varying/s", "ops", "delta 2..", "Delta 2..", "delta 16..", "Delta 16..", "PSNR");
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        char ops[16] = "?";
        if (row->ops.known)
            snprintf(ops, sizeof ops, "%d/%d/%d", row->ops.arith + row->ops.minmax, row->ops.div, row->ops.transc);
        char psnr[16] = "-";   /* not measured (--no-image) or not finite: no "nan" */
        if (isfinite(row->psnr_db))
            snprintf(psnr, sizeof psnr, "%.1f", row->psnr_db);
        fprintf(f, "%-14s %-9s %5s %11.4g %11.4g %6s %9.4f%% %9.5f %9.4f%% %9.5f %7s\n", row->spec.label,
                model_kind_name(row->kind), row->on_front ? "yes" : "", row->rate[0][1], row->rate[1][1], ops,
                100 * row->max_rel[0], row->max_abs[0], 100 * row->max_rel[1], row->max_abs[1], psnr);
    }
}

/* The most accurate non-reference model (least max delta, then least max Delta) whose rate
   is at least `budget` (its max rate >= budget: spreads again); -1 if none. */
static int best_within(const struct frontier_report *r, double budget, int range)
{
    int best = -1;
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        if (row->kind == MODEL_KIND_REFERENCE || !isfinite(row->max_rel[range]) || !isfinite(row->rate[0][2]))
            continue;
        if (budget > 0 && row->rate[0][2] < budget)
            continue;
        if (best < 0 || row->max_rel[range] < r->rows[best].max_rel[range] ||
            (row->max_rel[range] == r->rows[best].max_rel[range] &&
             row->max_abs[range] < r->rows[best].max_abs[range]))
            best = i;
    }
    return best;
}

char *frontier_markdown(const struct frontier_report *r)
{
    struct md_buf b;
    md_init(&b);
    md_printf(&b, "Cost is the device's evaluations/s with n uniform (the median over %d rounds over every model of "
                  "each round's median of %d launches; spreads over the rounds that overlap count as equal), "
                  "accuracy the largest epicentre delta and attenuation Delta (frontier.json, frontier.csv, "
                  "frontier_max_rel.png, frontier_max_abs.png).\n\n", r->opt.rounds, r->opt.reps);
    md_printf(&b, "| model | kind | front | evals/s (uniform) | evals/s (varying) | max delta, n >= 2 | max Delta, n >= 2 "
                  "| max delta, n >= 16 | max Delta, n >= 16 | teapot PSNR (dB) |\n");
    md_printf(&b, "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        md_printf(&b, "| %s | %s | %s | %.3g | %.3g | %.4f%% | %.4f | %.4f%% | %.4f | ", row->spec.label,
                  model_kind_name(row->kind), row->on_front ? "**yes**" : "", row->rate[0][1], row->rate[1][1],
                  100 * row->max_rel[0], row->max_abs[0], 100 * row->max_rel[1], row->max_abs[1]);
        if (isfinite(row->psnr_db))
            md_printf(&b, "%.1f |\n", row->psnr_db);
        else
            md_printf(&b, "%s |\n", row->psnr_reason);
    }
    md_printf(&b, "\nSources (brdfbench list; docs/frontier.md has the formulas and the operation counts):\n\n");
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        md_printf(&b, "- `%s`: ", row->spec.label);
        md_cell_text(&b, row->spec.info->description);
        md_printf(&b, "\n");
    }
    md_printf(&b, "\nThe front: ");
    for (int i = 0, k = 0; i < r->count; ++i)
        if (r->rows[i].on_front)
            md_printf(&b, "%s%s", k++ ? ", " : "", r->rows[i].spec.label);
    md_printf(&b, ".\n\n");
    if (r->fq2 >= 0 && isfinite(r->rows[r->fq2].rate[0][0])) {
        double fq2_lo = r->rows[r->fq2].rate[0][0];
        double budgets[3] = { fq2_lo, 0.25 * fq2_lo, 0.0 };
        const char *names[3] = { "at least fq2's rate", "at least a quarter of fq2's rate", "any cost" };
        md_printf(&b, "The most accurate approximation (least max delta, then least max Delta; the references excluded) "
                      "for a budget of evaluations/s:\n\n| budget | n from 2 | n from 16 |\n|---|---|---|\n");
        for (int k = 0; k < 3; ++k) {
            md_printf(&b, "| %s |", names[k]);
            for (int range = 0; range < 2; ++range) {
                int i = best_within(r, budgets[k], range);
                if (i < 0)
                    md_printf(&b, " none |");
                else
                    md_printf(&b, " %s (%.4f%%, %.4f; %.3g/s) |", r->rows[i].spec.label, 100 * r->rows[i].max_rel[range],
                              r->rows[i].max_abs[range], r->rows[i].rate[0][1]);
            }
            md_printf(&b, "\n");
        }
    } else {
        md_printf(&b, "fq2 is not in this run (or its rate is missing): no budgets relative to it.\n");
    }
    if (frontier_plots_drawable(r))
        md_printf(&b, "\n![evaluations/s against max delta](frontier_max_rel.png)\n"
                      "![evaluations/s against max Delta](frontier_max_abs.png)\n");
    else
        md_printf(&b, "\nThe plots of evaluations/s against max delta and max Delta are not drawn: no model has a "
                      "measured rate.\n");
    if (b.failed) {
        md_free(&b);
        return NULL;
    }
    return b.s;   /* the caller frees */
}
