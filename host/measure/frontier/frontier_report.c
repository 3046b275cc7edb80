/* frontier_report.c - frontier.json, frontier.csv, the two scatter plots, the printed table and
 * the "Which lobe to ship" markdown, from a filled struct frontier_report (frontier.c). The
 * markdown is report_frontier_page (host/results/report) of the rows frontier.json carries. */
#include "frontier_report.h"
#include "context.h"
#include "draw.h"
#include "plots.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "rdoc.h"
#include "report_frontier.h"
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
   Delta, lower is better) and its teapot PSNR; then what the "Which lobe to ship" page shows
   (report_frontier.h): the model's kind and source, its rates (median, min and max over the
   rounds) and whether it is on the front, figures of direction neither (the frontier's short
   timing is no verdict's: throughput.json's rates are), and why a PSNR is missing. The context
   lines rounds and reps say how the rates were timed. */
static void frontier_rows(struct rdoc *d, const struct frontier_report *r)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%d", r->opt.rounds);
    rd_ctx_put(&d->ctx, "rounds", buf);
    snprintf(buf, sizeof buf, "%d", r->opt.reps);
    rd_ctx_put(&d->ctx, "reps", buf);
    for (int i = 0; i < r->count; ++i) {
        const struct frontier_row *row = &r->rows[i];
        struct rd_row *rr = rdoc_row(d, "", row->spec.label);
        if (!rr)
            return;
        rd_row_key(rr, "model", NULL, row->spec.label);
        rd_row_attr(rr, "kind", model_kind_name(row->kind));
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
        for (int m = 0; m < 2; ++m) {
            struct rd_metric *rate = rd_row_metric(d, rr, m ? FRONTIER_RATE_VARYING : FRONTIER_RATE_UNIFORM, "1/s",
                                                   RD_NEITHER, 0, row->rate[m][1]);
            if (rate) {
                rate->lo = row->rate[m][0];
                rate->hi = row->rate[m][2];
            }
        }
        rd_row_metric(d, rr, "on_front", "1", RD_NEITHER, 0, row->on_front ? 1.0 : 0.0);
        rd_row_text(d, rr, "source", row->spec.info->description);
        if (!isfinite(row->psnr_db))
            rd_row_text(d, rr, "psnr_reason", row->psnr_reason[0] ? row->psnr_reason : "not measured");
    }
}

/* The rows of r (rdoc_delete), or NULL with the reason in err. */
static struct rdoc *frontier_doc(const struct frontier_report *r, char *err, size_t errlen)
{
    struct rdoc *d = rdoc_new(FRONTIER_SCHEMA, "frontier", "frontier.json", err, errlen);
    if (!d)
        return NULL;
    frontier_rows(d, r);
    return rdoc_built(d, err, errlen) ? NULL : d;
}

int frontier_write_json(const char *path, const struct frontier_report *r, const struct cl_session *s, char *err,
                        size_t errlen)
{
    struct rdoc *d = frontier_doc(r, err, errlen);
    if (!d)
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

char *frontier_markdown(const struct frontier_report *r)
{
    char err[256];
    struct rdoc *d = frontier_doc(r, err, sizeof err);
    if (!d)
        return NULL;
    struct md_buf b;
    md_init(&b);
    int rc = report_frontier_page(&b, d);
    rdoc_delete(d);
    if (rc) {
        md_free(&b);
        return NULL;
    }
    return b.s;   /* the caller frees */
}
