/* compare_report.c - writes a comparison (compare.h): the table on stdout and compare.md,
 * compare.csv, compare.json and compare.png. Nothing here reads a run or decides a verdict. */
#include "compare_report.h"
#include "context.h"
#include "draw.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "outdir.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

static const char *sense_name(int s)
{
    static const char *const n[] = { "speed", "error", "score", "value" };
    return s >= 0 && s <= CMP_VALUE ? n[s] : "?";
}

static const char *basis_name(int b)
{
    static const char *const n[] = { "", "normalised", "absolute", "ranges", "normalised per CPU second" };
    return b >= 0 && b <= CMP_BASIS_CPU ? n[b] : "?";
}

/* A value as the table shows it: rates in G/s or M/s, the rest with 4 significant digits. */
static void fmt_value(char *buf, size_t len, const struct cmp_row *r, double v)
{
    if (!isfinite(v))
        snprintf(buf, len, "-");
    else if (r->sense == CMP_SPEED && strstr(r->metric, "evals_per_s"))
        snprintf(buf, len, "%.4g G", v * 1e-9);
    else
        snprintf(buf, len, "%.4g", v);
}

/* The row's name in a table: device, key and (where a kind has several) the figure. */
static void row_label(char *buf, size_t len, const struct cmp_row *r)
{
    /* a throughput row's rate goes by its key alone; the figures beside it (the tuned C loop's
       rate, the accuracy) are named */
    if (r->kind == CMP_THROUGHPUT && (strcmp(r->metric, "evals_per_s") == 0 || strcmp(r->metric, "flops_per_s") == 0))
        snprintf(buf, len, "%s%s%s", r->device, *r->device ? " | " : "", r->key);
    else
        snprintf(buf, len, "%s%s%s: %s", r->device, *r->device ? " | " : "", r->key, r->metric);
}

/* One cell as text: the value, and against the baseline the ratio or change and the verdict. */
static void cell_text(char *buf, size_t len, const struct compare_set *set, const struct cmp_row *r, int k)
{
    const struct cmp_cell *c = &r->cell[k];
    char v[48];
    if (!c->present) {
        snprintf(buf, len, "(not in this run)");
        return;
    }
    if (!c->ok) {
        snprintf(buf, len, "failed: %.60s", c->reason);
        return;
    }
    fmt_value(v, sizeof v, r, c->value);
    if (k == 0) {
        snprintf(buf, len, "%10s", v);
        return;
    }
    if (c->verdict == CMP_V_MISSING) {
        snprintf(buf, len, "%s (baseline: none)", v);
        return;
    }
    if (c->verdict == CMP_V_FAILED) {
        snprintf(buf, len, "%s (baseline failed)", v);
        return;
    }
    /* value, ratio or change, verdict: aligned within a column */
    if (r->sense == CMP_SPEED) {
        if (isfinite(c->p) && isfinite(c->ci_lo))
            snprintf(buf, len, "%10s %7.3fx [%.3f, %.3f] %-9s (p %.2g)", v, c->ratio, c->ci_lo,
                     isfinite(c->ci_hi) ? c->ci_hi : INFINITY, cmp_verdict_name(c->verdict), set->holm ? c->p_adj : c->p);
        else if (isfinite(c->p))
            snprintf(buf, len, "%10s %7.3fx %-9s (p %.2g)", v, c->ratio, cmp_verdict_name(c->verdict), c->p);
        else
            snprintf(buf, len, "%10s %7.3fx %-9s", v, c->ratio, cmp_verdict_name(c->verdict));
    } else if (c->verdict == CMP_V_UNCHANGED) {
        snprintf(buf, len, "%10s %10s unchanged", v, "");
    } else {
        snprintf(buf, len, "%10s %+10.3g %s", v, c->change, cmp_verdict_name(c->verdict));
    }
    (void)set;
}

static const char *kind_heading(int kind)
{
    switch (kind) {
    case CMP_THROUGHPUT: return "throughput: evaluations/s, median of the repetitions; against the baseline: the ratio "
                                "(Hodges-Lehmann, on the normalised rates where both runs have them) with its "
                                "confidence interval, and the Mann-Whitney test of the repetitions";
    case CMP_ACCURACY: return "accuracy: max delta (epicentre), max Delta (attenuation, whole range), the count of invalid "
                              "values; against the "
                              "baseline: the signed change, at the 4th significant digit";
    case CMP_RENDER: return "render: image error (max |error|, RMSE, PSNR: 4th significant digit) and Mpixel/s (the "
                            "min..max ranges overlap: same)";
    case CMP_FIT: return "fit: the fitted coefficients and their max delta and max Delta (4th significant digit)";
    case CMP_FRONTIER: return "frontier: each model's rate (repetitions tested where the file keeps them) and "
                              "accuracy (4th significant digit)";
    case CMP_MEASURED: return "measured: each material's fits and each lobe's error against it (4th significant "
                              "digit)";
    }
    return "?";
}

/* The context rows worth showing side by side, in this order; others follow as read. */
static const char *const ctx_order[] = { "files", "device", "devices", "platform", "platform_version", "device_version",
                                         "driver_version", "compute_units", "host_cpu", "host_cores", "git_revision",
                                         "brdfbench_version", "build_options", "pocl_affinity", "kernel sources", "throughput settings", "machine", "accuracy grid",
                                         "fit grid", "date" };

static const char *ctx_value(const struct compare_set *set, int k, const char *key)
{
    if (strcmp(key, "files") == 0)
        return set->run[k].files;
    return compare_context(set, k, key);
}

/* 1 when run k's value differs from the baseline's. */
static int ctx_differs(const struct compare_set *set, int k, const char *key)
{
    const char *a = ctx_value(set, 0, key), *b = ctx_value(set, k, key);
    return !a || !b ? a != b : strcmp(a, b) != 0;
}

static int ctx_shown(const char *key)
{
    for (size_t i = 0; i < sizeof ctx_order / sizeof ctx_order[0]; ++i)
        if (strcmp(ctx_order[i], key) == 0)
            return 1;
    return 0;
}

/* Every context key of every run, in ctx_order first. */
static int ctx_keys(const struct compare_set *set, const char **keys, int max)
{
    int n = 0;
    for (size_t i = 0; i < sizeof ctx_order / sizeof ctx_order[0] && n < max; ++i) {
        int any = strcmp(ctx_order[i], "files") == 0;
        for (int k = 0; k < set->nruns; ++k)
            any |= compare_context(set, k, ctx_order[i]) != NULL;
        if (any)
            keys[n++] = ctx_order[i];
    }
    for (int k = 0; k < set->nruns; ++k)
        for (int c = 0; c < set->run[k].nctx && n < max; ++c) {
            const char *key = set->run[k].ctx_key[c];
            int seen = ctx_shown(key);
            for (int j = 0; j < n && !seen; ++j)
                seen = strcmp(keys[j], key) == 0;
            if (!seen)
                keys[n++] = key;
        }
    return n;
}

/* How many rows of this kind run k has, and of them how many got each verdict. */
static int verdict_counts(const struct compare_set *set, int k, int kind, int count[CMP_V_NOISY + 1])
{
    int rows = 0;
    memset(count, 0, (CMP_V_NOISY + 1) * sizeof *count);
    for (int i = 0; i < set->nrows; ++i)
        if (set->rows[i].kind == kind) {
            ++rows;
            count[set->rows[i].cell[k].verdict]++;
        }
    return rows;
}

static void counts_line(struct md_buf *b, const struct compare_set *set, int kind)
{
    for (int k = 1; k < set->nruns; ++k) {
        int count[CMP_V_NOISY + 1];
        int rows = verdict_counts(set, k, kind, count);
        if (!rows)
            return;
        md_printf(b, "%s against %s: %d row%s", set->run[k].name, set->run[0].name, rows, rows == 1 ? "" : "s");
        const char *sep = ": ";
        for (int v = CMP_V_MISSING; v <= CMP_V_NOISY; ++v)
            if (count[v]) {
                md_printf(b, "%s%d %s", sep, count[v], cmp_verdict_name(v));
                sep = ", ";
            }
        md_printf(b, "\n");
    }
}

/* The header line of a table with a column per run: markdown with the rule cell `rule` per
 * run, or text with the first column w0 wide and each run's name in w[k] after `gap`. */
static void runs_header(struct md_buf *b, const struct compare_set *set, int md, const char *first,
                        const char *rule, int w0, const int *w, const char *gap)
{
    if (md) {
        md_printf(b, "| %s |", first);
        for (int k = 0; k < set->nruns; ++k)
            md_printf(b, " %s |", set->run[k].name);
        md_printf(b, "\n|---|");
        for (int k = 0; k < set->nruns; ++k)
            md_printf(b, "%s", rule);
    } else {
        md_printf(b, "  %-*s", w0, first);
        for (int k = 0; k < set->nruns; ++k)
            md_printf(b, "%s%-*s", gap, w[k], set->run[k].name);
    }
    md_printf(b, "\n");
}

/* The runs' context side by side: a line per key, "=" where a run has the first's value. */
static void context_table(struct md_buf *b, const struct compare_set *set, int md)
{
    int R = set->nruns;
    const char *keys[CMP_MAX_CTX + 16];
    int nk = ctx_keys(set, keys, (int)(sizeof keys / sizeof keys[0]));
    int w0 = 20, w = 12;
    for (int k = 0; k < R; ++k) {
        w = (int)fmax(w, strlen(set->run[k].name));
        for (int i = 0; i < nk; ++i) {
            const char *v = ctx_value(set, k, keys[i]);
            if (v && (k == 0 || ctx_differs(set, k, keys[i])))
                w = (int)fmax(w, fmin(72, strlen(v)));
        }
    }
    int wk[CMP_MAX_RUNS];
    for (int k = 0; k < R; ++k)
        wk[k] = w;
    if (md)
        md_printf(b, "## Context\n\n");
    runs_header(b, set, md, md ? "" : "context", "---|", w0, wk, " ");
    for (int i = 0; i < nk; ++i) {
        int differs = 0;
        for (int k = 1; k < R; ++k)
            differs |= ctx_differs(set, k, keys[i]);
        if (md)
            md_printf(b, "| %s%s%s |", differs ? "**" : "", keys[i], differs ? "**" : "");
        else
            md_printf(b, "%c %-*s", differs ? '*' : ' ', w0, keys[i]);
        for (int k = 0; k < R; ++k) {
            const char *v = ctx_value(set, k, keys[i]);
            char cell[CMP_TEXT + 8];
            if (k > 0 && !ctx_differs(set, k, keys[i]))
                snprintf(cell, sizeof cell, "=");
            else
                snprintf(cell, sizeof cell, "%s", v ? v : "-");
            if (md) {
                md_printf(b, " ");
                md_cell_text(b, cell);
                md_printf(b, "%s |", differs && k > 0 && strcmp(cell, "=") != 0 ? " (differs)" : "");
            } else {
                md_printf(b, " %-*.*s", w, 72, cell);
            }
        }
        md_printf(b, "\n");
    }
    md_printf(b, md ? "\n`=`: as the first column; **bold**: differs from it.\n\n"
                    : "(* differs from the first column; = as the first column)\n\n");
}

/* One row of a kind's table: its label (marked when only in some runs) and a cell per run. */
static void row_line(struct md_buf *b, const struct compare_set *set, int md, const struct cmp_row *r,
                     int pass, int wl, const int *wc)
{
    char label[2 * CMP_TEXT + 80], cell[CMP_TEXT + 80];
    row_label(label, sizeof label, r);
    if (md) {
        md_printf(b, "| ");
        md_cell_text(b, label);
        md_printf(b, "%s |", pass ? " (only in some runs)" : "");
    } else {
        md_printf(b, "  %-*.*s", wl, 70, label);
    }
    for (int k = 0; k < set->nruns; ++k) {
        cell_text(cell, sizeof cell, set, r, k);
        if (md) {
            md_printf(b, " ");
            md_cell_text(b, cell);
            md_printf(b, " |");
        } else {
            md_printf(b, "  %-*.*s", wc[k], 70, cell);
        }
    }
    md_printf(b, "\n");
}

/* The table of one kind of row (nothing when there is none): rows in every run first, then
   the others, then the verdict counts. */
static void kind_table(struct md_buf *b, const struct compare_set *set, int md, int kind)
{
    int R = set->nruns;
    int nrows = 0, wl = 10, wc[CMP_MAX_RUNS];
    for (int k = 0; k < R; ++k)
        wc[k] = (int)strlen(set->run[k].name);
    for (int i = 0; i < set->nrows; ++i) {
        const struct cmp_row *r = &set->rows[i];
        if (r->kind != kind)
            continue;
        ++nrows;
        char label[2 * CMP_TEXT + 80], cell[CMP_TEXT + 80];
        row_label(label, sizeof label, r);
        wl = (int)fmax(wl, fmin(70, strlen(label)));
        for (int k = 0; k < R; ++k) {
            cell_text(cell, sizeof cell, set, r, k);
            wc[k] = (int)fmax(wc[k], fmin(70, strlen(cell)));
        }
    }
    if (!nrows)
        return;
    if (md)
        md_printf(b, "## %s\n\n", cmp_kind_name(kind));
    md_printf(b, md ? "%s (alpha %.3g).\n\n" : "%s (alpha %.3g)\n\n", kind_heading(kind), set->alpha);
    runs_header(b, set, md, "row", "---:|", wl, wc, "  ");
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            int some = 0;
            for (int i = 0; i < set->nrows; ++i)
                some |= set->rows[i].kind == kind && !set->rows[i].in_all;
            if (!some)
                break;
            if (!md)
                md_printf(b, "  rows found in only some of the runs:\n");
        }
        for (int i = 0; i < set->nrows; ++i) {
            const struct cmp_row *r = &set->rows[i];
            if (r->kind == kind && r->in_all == (pass == 0))
                row_line(b, set, md, r, pass, wl, wc);
        }
    }
    md_printf(b, "\n");
    counts_line(b, set, kind);
    md_printf(b, "\n");
}

char *compare_text(const struct compare_set *set, int md)
{
    struct md_buf b;
    md_init(&b);
    int R = set->nruns;
    if (md)
        md_printf(&b, "# Comparison of %d %s\n\n", R, set->by_device ? "devices of one run" : "runs");
    for (int k = 0; k < R; ++k)
        md_printf(&b, "%s%s = %s%s\n", md ? "- " : "", set->run[k].name, set->run[k].path,
                  k == 0 ? (set->by_device ? " (baseline device)" : " (baseline)") : "");
    md_printf(&b, "\n");
    context_table(&b, set, md);
    for (int kind = 0; kind < CMP_KIND_COUNT; ++kind)
        kind_table(&b, set, md, kind);
    if (b.failed) {
        md_free(&b);
        return NULL;
    }
    return b.s;
}

/* ---- files ------------------------------------------------------------------------------- */

static void csv_text(struct md_buf *b, const char *s)
{
    md_printf(b, "\"");
    for (; *s; ++s)
        md_printf(b, *s == '"' ? "\"\"" : "%c", *s);
    md_printf(b, "\"");
}

static void csv_num(struct md_buf *b, double v)
{
    if (isfinite(v))
        md_printf(b, ",%.9g", v);
    else
        md_printf(b, ",");
}

static int write_csv(const struct compare_set *set, const char *path, char *err, size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    md_printf(&b, "kind,device,key,metric,sense,run,present,status,value,min,max,reps,ratio,change,p,p_adjusted,ratio_ci_lo,"
                  "ratio_ci_hi,basis,verdict,reason\n");
    for (int i = 0; i < set->nrows; ++i) {
        const struct cmp_row *r = &set->rows[i];
        for (int k = 0; k < set->nruns; ++k) {
            const struct cmp_cell *c = &r->cell[k];
            md_printf(&b, "%s,", cmp_kind_name(r->kind));
            csv_text(&b, r->device);
            md_printf(&b, ",");
            csv_text(&b, r->key);
            md_printf(&b, ",%s,%s,", r->metric, sense_name(r->sense));
            csv_text(&b, set->run[k].name);
            md_printf(&b, ",%d,%s", c->present, !c->present ? "missing" : c->ok ? "ok" : "failed");
            csv_num(&b, c->present && c->ok ? c->value : NAN);
            csv_num(&b, c->lo);
            csv_num(&b, c->hi);
            md_printf(&b, ",%d", c->nreps);
            csv_num(&b, c->ratio);
            csv_num(&b, c->change);
            csv_num(&b, c->p);
            csv_num(&b, c->p_adj);
            csv_num(&b, c->ci_lo);
            csv_num(&b, c->ci_hi);
            md_printf(&b, ",%s", basis_name(c->basis));
            md_printf(&b, ",%s,", k == 0 ? "baseline" : cmp_verdict_name(c->verdict));
            csv_text(&b, c->present && !c->ok ? c->reason : "");
            md_printf(&b, "\n");
        }
    }
    int rc = b.failed ? -1 : write_file_atomic(path, b.s, b.len, err, errlen);
    if (b.failed)
        snprintf(err, errlen, "out of memory writing %.900s", path);
    md_free(&b);
    return rc;
}

/* compare.json's "definitions": how each kind of row is decided. */
static const char *const compare_definitions[][2] = {
    { "speed", "a rate (higher is better): value = median of the repetitions; decided on the normalised "
               "repetitions (rate / the run's reference kernel in the same round) where both runs have "
               "them, else the absolute ones (basis); ratio = the Hodges-Lehmann estimate of the ratio of "
               "the two samples, ratio_ci its distribution-free interval at 1 - alpha; faster or slower when "
               "the two-sided Mann-Whitney p (p_adjusted: Holm over the run's rates, with --holm) < alpha "
               "and the ratio is beyond 1 +- threshold; noisy when the interval is wider than that band; "
               "same otherwise; undecided when the sample sizes cannot reach alpha; without repetitions, "
               "same when the min..max ranges overlap" },
    { "error", "an error figure (lower is better): unchanged when both round to the same 4 significant "
               "digits, else changed, better or worse; change = value - baseline" },
    { "score", "as error, higher is better (PSNR)" },
    { "value", "as error, with no better or worse (a fitted coefficient)" },
    { "ratio", "value / the baseline's value of the same row" },
};

/* compare.json into path, or (stream not NULL) onto stream, path then naming it in a message */
static int write_json(const struct compare_set *set, const char *path, FILE *stream, char *err, size_t errlen)
{
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_str(&w, "schema", COMPARE_SCHEMA);
    char date[64];
    utc_now_iso(date, sizeof date);
    jw_kv_str(&w, "date", date);
    jw_kv_str(&w, "layout", set->by_device ? "devices of one run" : "runs");
    jw_kv_num(&w, "alpha", set->alpha);
    jw_kv_num(&w, "threshold", set->threshold);
    jw_kv_bool(&w, "holm", set->holm);
    jw_kv_texts(&w, "definitions", JW_TEXTS(compare_definitions));
    jw_kv_arr(&w, "runs");
    const char *keys[CMP_MAX_CTX + 16];
    int nk = ctx_keys(set, keys, (int)(sizeof keys / sizeof keys[0]));
    for (int k = 0; k < set->nruns; ++k) {
        jw_obj_begin(&w);
        jw_kv_str(&w, "name", set->run[k].name);
        jw_kv_str(&w, "path", set->run[k].path);
        jw_kv_bool(&w, "baseline", k == 0);
        jw_kv_str(&w, "files", set->run[k].files);
        jw_kv_obj(&w, "context");
        for (int c = 0; c < set->run[k].nctx; ++c)
            jw_kv_str(&w, set->run[k].ctx_key[c], set->run[k].ctx_value[c]);
        jw_obj_end(&w);
        jw_kv_arr(&w, "context_differs");
        for (int i = 0; k > 0 && i < nk; ++i)
            if (strcmp(keys[i], "files") != 0 && ctx_differs(set, k, keys[i]))
                jw_str(&w, keys[i]);
        jw_arr_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_arr(&w, "rows");
    for (int i = 0; i < set->nrows; ++i) {
        const struct cmp_row *r = &set->rows[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "kind", cmp_kind_name(r->kind));
        jw_kv_str(&w, "device", r->device);
        jw_kv_str(&w, "key", r->key);
        jw_kv_str(&w, "model", r->model);
        jw_kv_str(&w, "metric", r->metric);
        jw_kv_str(&w, "sense", sense_name(r->sense));
        jw_kv_bool(&w, "in_all_runs", r->in_all);
        jw_kv_arr(&w, "cells");
        for (int k = 0; k < set->nruns; ++k) {
            const struct cmp_cell *c = &r->cell[k];
            jw_obj_begin(&w);
            jw_kv_str(&w, "run", set->run[k].name);
            jw_kv_str(&w, "status", !c->present ? "missing" : c->ok ? "ok" : "failed");
            if (c->present && !c->ok)
                jw_kv_str(&w, "reason", c->reason);
            jw_kv_num(&w, "value", c->present && c->ok ? c->value : NAN);
            if (r->sense == CMP_SPEED) {
                jw_kv_num(&w, "min", c->lo);
                jw_kv_num(&w, "max", c->hi);
                jw_kv_nums(&w, "reps", c->reps, (size_t)c->nreps);
            }
            jw_kv_num(&w, "ratio", c->ratio);
            jw_kv_num(&w, "change", c->change);
            if (r->sense == CMP_SPEED) {
                jw_kv_num(&w, "p", c->p);
                jw_kv_num(&w, "p_adjusted", c->p_adj);
                jw_kv_num(&w, "ratio_ci_lo", c->ci_lo);
                jw_kv_num(&w, "ratio_ci_hi", c->ci_hi);
                jw_kv_str(&w, "basis", basis_name(c->basis));
                jw_kv_nums(&w, "normalised_reps", c->norm, (size_t)c->nnorm);
                jw_kv_int(&w, "preemption_retries", c->retries);
                jw_kv_int(&w, "disturbed_reps", c->disturbed);
            }
            jw_kv_str(&w, "verdict", k == 0 ? "baseline" : cmp_verdict_name(c->verdict));
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_arr(&w, "summary");
    for (int k = 1; k < set->nruns; ++k)
        for (int kind = 0; kind < CMP_KIND_COUNT; ++kind) {
            int count[CMP_V_NOISY + 1];
            int rows = verdict_counts(set, k, kind, count);
            if (!rows)
                continue;
            jw_obj_begin(&w);
            jw_kv_str(&w, "run", set->run[k].name);
            jw_kv_str(&w, "kind", cmp_kind_name(kind));
            jw_kv_int(&w, "rows", rows);
            jw_kv_obj(&w, "verdicts");
            for (int v = CMP_V_MISSING; v <= CMP_V_NOISY; ++v)
                if (count[v])
                    jw_kv_int(&w, cmp_verdict_name(v), count[v]);
            jw_obj_end(&w);
            jw_obj_end(&w);
        }
    jw_arr_end(&w);
    jw_obj_end(&w);
    if (!stream)
        return jw_write_file_free(&w, path, err, errlen);
    int rc = jw_write_stream(&w, stream, path, err, errlen);
    jw_free(&w);
    return rc;
}

/* A verdict as the chart's mark. */
static int chart_verdict(int v)
{
    switch (v) {
    case CMP_V_FASTER:
    case CMP_V_BETTER: return DRAW_VERDICT_BETTER;
    case CMP_V_SLOWER:
    case CMP_V_WORSE: return DRAW_VERDICT_WORSE;
    case CMP_V_SAME:
    case CMP_V_UNCHANGED: return DRAW_VERDICT_SAME;
    case CMP_V_MISSING:
    case CMP_V_FAILED: return DRAW_VERDICT_LOST;
    case CMP_V_NONE: return DRAW_VERDICT_NONE;
    default: return DRAW_VERDICT_UNDECIDED;
    }
}

static const char *const sense_title[4] = {"rates (higher is better)", "errors (lower is better)",
                                           "scores (higher is better)", "values"};

/* The chart's data: a panel per kind of row and sense, in that order, every row of it. */
struct chart_data {
    struct draw_verdict_panel panels[CMP_KIND_COUNT * 4];
    char titles[CMP_KIND_COUNT * 4][96];
    int npanels;
    const char **labels;
    char (*label_text)[2 * CMP_TEXT + 80];
    double *ratio;
    int *verdict;
};

static void chart_free(struct chart_data *d)
{
    free(d->labels);
    free(d->label_text);
    free(d->ratio);
    free(d->verdict);
}

static int chart_fill(const struct compare_set *set, struct chart_data *d)
{
    const int N = set->nrows, S = set->nruns;
    memset(d, 0, sizeof *d);
    d->labels = calloc((size_t)N + 1, sizeof *d->labels);
    d->label_text = calloc((size_t)N + 1, sizeof *d->label_text);
    d->ratio = calloc((size_t)N * S + 1, sizeof *d->ratio);
    d->verdict = calloc((size_t)N * S + 1, sizeof *d->verdict);
    if (!d->labels || !d->label_text || !d->ratio || !d->verdict) return -1;
    int at = 0;
    for (int kind = 0; kind < CMP_KIND_COUNT; ++kind)
        for (int sense = 0; sense < 4; ++sense) {
            struct draw_verdict_panel *p = &d->panels[d->npanels];
            int first = at;
            for (int i = 0; i < N; ++i) {
                const struct cmp_row *r = &set->rows[i];
                if (r->kind != kind || r->sense != sense) continue;
                row_label(d->label_text[at], sizeof d->label_text[at], r);
                d->labels[at] = d->label_text[at];
                const struct cmp_cell *b = &r->cell[0];
                double base = b->present && b->ok ? b->value : NAN;
                for (int k = 0; k < S; ++k) {
                    const struct cmp_cell *c = &r->cell[k];
                    int ok = c->present && c->ok && isfinite(base) && base > 0;
                    d->ratio[(size_t)at * S + k] = ok ? c->value / base : NAN;
                    d->verdict[(size_t)at * S + k] = k == 0 ? DRAW_VERDICT_NONE : chart_verdict(c->verdict);
                }
                ++at;
            }
            if (at == first) continue;
            snprintf(d->titles[d->npanels], sizeof d->titles[0], "%s: %s (%d rows)", cmp_kind_name(kind),
                     sense_title[sense], at - first);
            p->title = d->titles[d->npanels];
            p->nrows = at - first;
            p->labels = d->labels + first;
            p->ratio = d->ratio + (size_t)first * S;
            p->verdict = d->verdict + (size_t)first * S;
            ++d->npanels;
        }
    return 0;
}

/* The most bars a verdict chart draws (draw_compare.cpp): past it the chart would be
   unreadable and is not drawn, with a note, while the tables hold every row. */
#define CHART_MAX_BARS 20000

static int write_chart(const struct compare_set *set, const char *path, char *err, size_t errlen)
{
    if (set->nrows > 0 && (long)set->nrows * set->nruns > CHART_MAX_BARS) {
        fprintf(stderr, "brdfbench compare: note: %d rows in %d runs are more than the %d bars a chart shows: no "
                "compare.png (compare.md, .csv and .json hold every row)\n", set->nrows, set->nruns, CHART_MAX_BARS);
        if (unlink(path) != 0 && errno != ENOENT) {
            snprintf(err, errlen, "%s: cannot remove the chart of an earlier compare: %s", path, strerror(errno));
            return -1;
        }
        return 0;
    }
    if (set->nrows == 0) {
        /* nothing to chart: no chart, and none of an earlier compare left beside this one's tables */
        if (unlink(path) != 0 && errno != ENOENT) {
            snprintf(err, errlen, "%s: cannot remove the chart of an earlier compare: %s", path, strerror(errno));
            return -1;
        }
        return 0;
    }
    struct chart_data d;
    if (chart_fill(set, &d)) {
        chart_free(&d);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    const char *series[CMP_MAX_RUNS];
    for (int k = 0; k < set->nruns; ++k)
        series[k] = set->run[k].name;
    char title[512], xlabel[600];
    snprintf(title, sizeof title, "Every row as a ratio to %.200s, a panel per kind of row, each run's verdict at the right",
             set->run[0].name);
    snprintf(xlabel, sizeof xlabel, "ratio to %.200s's value (log; a rate: its median; none: not measured or a baseline of 0)",
             set->run[0].name);
    struct draw_verdict_chart ch = { title, xlabel, set->nruns, series, d.npanels, d.panels, 0 };
    int rc = draw_verdict_chart(path, &ch, err, errlen);
    chart_free(&d);
    return rc;
}

int compare_write(const struct compare_set *set, const char *out_dir, char *err, size_t errlen)
{
    char path[4200];
    char *md = compare_text(set, 1);
    if (!md) {
        snprintf(err, errlen, "out of memory writing compare.md");
        return 3;
    }
    int rc = path_join(path, sizeof path, out_dir, "compare.md") ||
             write_file_atomic(path, md, strlen(md), err, errlen) ||
             path_join(path, sizeof path, out_dir, "compare.csv") || write_csv(set, path, err, errlen) ||
             path_join(path, sizeof path, out_dir, "compare.json") || write_json(set, path, NULL, err, errlen) ||
             path_join(path, sizeof path, out_dir, "compare.png") || write_chart(set, path, err, errlen);
    free(md);
    return rc ? 3 : 0;
}

int compare_print_json(const struct compare_set *set, FILE *f, const char *name, char *err, size_t errlen)
{
    return write_json(set, name, f, err, errlen) ? 3 : 0;
}
