/* history.c - rows over many runs, their change points, and what history writes (see
 * history.h). */
#define _POSIX_C_SOURCE 200809L
#include "history.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "draw.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "outdir.h"
#include "schemas.h"
#include "stats.h"

/* ---- order --------------------------------------------------------------------------------- */

/* by_commit: the commit dates first (every run has one), then the run dates. */
static int cmp_runs(const struct hist_run *x, const struct hist_run *y, int by_commit)
{
    int c = by_commit ? strcmp(x->commit_date, y->commit_date) : 0;
    if (!c)
        c = strcmp(x->date, y->date);
    return c;
}

void history_order(struct hist_set *h)
{
    int all = h->nruns > 0;
    for (int i = 0; i < h->nruns; ++i)
        all &= h->runs[i].commit_date[0] != 0;
    snprintf(h->order, sizeof h->order, "%s", all ? "commit date" : "run date");
    /* insertion sort: stable, so runs of the same date keep the order they were given in */
    for (int i = 1; i < h->nruns; ++i) {
        struct hist_run t = h->runs[i];
        int j = i - 1;
        while (j >= 0 && cmp_runs(&h->runs[j], &t, all) > 0) {
            h->runs[j + 1] = h->runs[j];
            --j;
        }
        h->runs[j + 1] = t;
    }
}

/* ---- rows ---------------------------------------------------------------------------------- */

static const char *row_device(const struct hist_run *run, const struct rd_row *r)
{
    return *r->device ? r->device : run->device;
}

/* The row's metric in run k, or NULL. */
static const struct rd_metric *lookup(const struct hist_set *h, int k, const struct hist_row *hr)
{
    const struct rdoc *d = &h->runs[k].doc;
    if (strcmp(d->kind, hr->kind) != 0)
        return NULL;
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        if (r->ok && strcmp(r->label, hr->label) == 0 && strcmp(row_device(&h->runs[k], r), hr->device) == 0)
            return rd_row_find(r, hr->metric);
    }
    return NULL;
}

static int find_row(const struct hist_set *h, const char *kind, const char *device, const char *label,
                    const char *metric)
{
    for (int i = 0; i < h->nrows; ++i)
        if (!strcmp(h->rows[i].kind, kind) && !strcmp(h->rows[i].device, device) && !strcmp(h->rows[i].label, label) &&
            !strcmp(h->rows[i].metric, metric))
            return i;
    return -1;
}

static double median_of(const double *v, int n, double *lo, double *hi)
{
    double *t = malloc((size_t)(n > 0 ? n : 1) * sizeof *t);
    int k = 0;
    for (int i = 0; t && i < n; ++i)
        if (isfinite(v[i]))
            t[k++] = v[i];
    double m = NAN;
    *lo = *hi = NAN;
    if (k > 0) {
        qsort(t, (size_t)k, sizeof *t, stats_cmp_double);
        m = stats_median_sorted(t, (size_t)k);
        *lo = t[0];
        *hi = t[k - 1];
    }
    free(t);
    return m;
}

static int same_4_digits(double a, double b)
{
    char x[40], y[40];
    snprintf(x, sizeof x, "%.3e", a);
    snprintf(y, sizeof y, "%.3e", b);
    return strcmp(x, y) == 0;
}

/* One row's series and changes. */
static int evaluate_row(struct hist_set *h, struct hist_row *hr)
{
    int T = h->nruns;
    struct cp_sample *samples = calloc((size_t)(T > 0 ? T : 1), sizeof *samples);
    hr->median = malloc((size_t)(T > 0 ? T : 1) * sizeof(double));
    hr->lo = malloc((size_t)(T > 0 ? T : 1) * sizeof(double));
    hr->hi = malloc((size_t)(T > 0 ? T : 1) * sizeof(double));
    hr->nmedian = malloc((size_t)(T > 0 ? T : 1) * sizeof(double));
    if (!samples || !hr->median || !hr->lo || !hr->hi || !hr->nmedian) {
        free(samples);
        return 3;
    }
    /* normalised repetitions where every run with the row has them, of one kind (per CPU second
       or not): then the machine's drift cancels */
    int present = 0, norm_all = 1, cpu = -1;
    for (int k = 0; k < T; ++k) {
        const struct rd_metric *m = lookup(h, k, hr);
        if (!m)
            continue;
        ++present;
        if (!(m->norm && m->nnorm > 0) || (cpu >= 0 && m->norm_cpu != cpu))
            norm_all = 0;
        cpu = m->norm_cpu;
    }
    int reps_all = present > 0;
    for (int k = 0; k < T; ++k) {
        const struct rd_metric *m = lookup(h, k, hr);
        if (m && !(m->reps && m->nreps > 0))
            reps_all = 0;
    }
    snprintf(hr->basis, sizeof hr->basis, "%s", hr->timed && norm_all && present ? "normalised"
                                                : hr->timed && reps_all ? "absolute" : "value");
    for (int k = 0; k < T; ++k) {
        const struct rd_metric *m = lookup(h, k, hr);
        hr->median[k] = hr->lo[k] = hr->hi[k] = hr->nmedian[k] = NAN;
        if (!m)
            continue;
        if (m->norm && m->nnorm > 0) {
            double nlo, nhi;
            hr->nmedian[k] = median_of(m->norm, m->nnorm, &nlo, &nhi);
        }
        if (!strcmp(hr->basis, "normalised"))
            samples[k].v = m->norm, samples[k].n = m->nnorm;
        else if (!strcmp(hr->basis, "absolute"))
            samples[k].v = m->reps, samples[k].n = m->nreps;
        else
            samples[k].v = &m->value, samples[k].n = 1;
        /* the series drawn and listed: the figure itself (a rate's median), its min and max */
        if (m->reps && m->nreps > 0)
            hr->median[k] = median_of(m->reps, m->nreps, &hr->lo[k], &hr->hi[k]);
        else
            hr->median[k] = hr->lo[k] = hr->hi[k] = m->value;
    }
    hr->nchanges = 0;
    if (hr->timed && strcmp(hr->basis, "value") != 0) {
        struct cp_change c[CP_MAX_CHANGES];
        int n = cp_find(samples, T, &h->cp, c);
        if (n < 0) {
            free(samples);
            return 3;
        }
        for (int i = 0; i < n; ++i)
            hr->changes[i] = (struct hist_change){ c[i].at, c[i].ratio, c[i].lo, c[i].hi, c[i].p };
        hr->nchanges = n;
    } else {
        /* a figure computed, not timed: changed where its 4th significant digit moves */
        int prev = -1;
        for (int k = 0; k < T && hr->nchanges < CP_MAX_CHANGES; ++k) {
            if (!isfinite(hr->median[k]))
                continue;
            if (prev >= 0 && !same_4_digits(hr->median[prev], hr->median[k]))
                hr->changes[hr->nchanges++] =
                    (struct hist_change){ k, hr->median[prev] != 0 ? hr->median[k] / hr->median[prev] : NAN, NAN,
                                          NAN, NAN };
            prev = k;
        }
    }
    free(samples);
    return 0;
}

int history_evaluate(struct hist_set *h)
{
    int cap = 0;
    for (int k = 0; k < h->nruns; ++k) {
        const struct rdoc *d = &h->runs[k].doc;
        for (int i = 0; i < d->nrows; ++i) {
            const struct rd_row *r = &d->rows[i];
            for (int m = 0; m < r->nmetrics; ++m) {
                const struct rd_metric *x = &r->metrics[m];
                const char *dev = row_device(&h->runs[k], r);
                if (x->direction == RD_NEITHER || find_row(h, d->kind, dev, r->label, x->name) >= 0)
                    continue;   /* a fitted coefficient has no better or worse: not followed */
                if (h->nrows == cap) {
                    cap = cap ? 2 * cap : 32;
                    struct hist_row *g = realloc(h->rows, (size_t)cap * sizeof *g);
                    if (!g)
                        return 3;
                    h->rows = g;
                }
                struct hist_row *hr = &h->rows[h->nrows++];
                memset(hr, 0, sizeof *hr);
                snprintf(hr->kind, sizeof hr->kind, "%s", d->kind);
                snprintf(hr->device, sizeof hr->device, "%s", dev);
                snprintf(hr->label, sizeof hr->label, "%s", r->label);
                snprintf(hr->metric, sizeof hr->metric, "%s", x->name);
                snprintf(hr->unit, sizeof hr->unit, "%s", x->unit);
                hr->direction = x->direction;
                hr->timed = x->timed;
            }
        }
    }
    for (int i = 0; i < h->nrows; ++i)
        if (evaluate_row(h, &h->rows[i]))
            return 3;
    return 0;
}

int history_slower(const struct hist_set *h, double pct, char **out)
{
    int count = 0;
    size_t len = 0;
    *out = NULL;
    for (int i = 0; i < h->nrows; ++i) {
        const struct hist_row *r = &h->rows[i];
        if (!r->timed || r->direction != RD_HIGHER || r->nchanges == 0)
            continue;
        const struct hist_change *c = &r->changes[r->nchanges - 1];
        if (!(c->ratio < 1.0 - pct / 100.0))
            continue;
        ++count;
        str_appendf(out, &len, "%s%s%s %s: the latest run (%s) is in a segment %.3gx the one before, from run %d (%s, "
                          "commit %s; interval %.3g..%.3g, p = %.2g)\n",
               r->device, *r->device ? " | " : "", r->label, r->metric, h->runs[h->nruns - 1].name, c->ratio,
               c->at + 1, h->runs[c->at].name, *h->runs[c->at].commit ? h->runs[c->at].commit : "?", c->lo, c->hi,
               c->p);
    }
    return count;
}

/* ---- writing ------------------------------------------------------------------------------- */

static void json_change(struct jw *w, const struct hist_set *h, const struct hist_row *r, const struct hist_change *c,
                        int with_row)
{
    jw_obj_begin(w);
    if (with_row) {
        jw_kv_str(w, "label", r->label);
        jw_kv_str(w, "device", r->device);
        jw_kv_str(w, "metric", r->metric);
    }
    jw_kv_str(w, "run", h->runs[c->at].name);
    jw_kv_int(w, "index", c->at + 1);
    jw_kv_str(w, "commit", h->runs[c->at].commit);
    jw_kv_str(w, "date", h->runs[c->at].date);
    jw_kv_num(w, "ratio", c->ratio);
    if (isfinite(c->lo) && isfinite(c->hi)) {
        double iv[2] = { c->lo, c->hi };
        jw_kv_nums(w, "interval", iv, 2);
    } else {
        jw_key(w, "interval");
        jw_null(w);
    }
    jw_kv_num(w, "p", c->p);
    jw_obj_end(w);
}

static int write_json(const struct hist_set *h, const char *dir, const char *source, char *err, size_t errlen)
{
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_str(&w, "schema", HISTORY_SCHEMA);
    jw_kv_str(&w, "source", source);
    jw_kv_str(&w, "order", h->order);
    jw_kv_obj(&w, "method");
    jw_kv_str(&w, "name", "binary segmentation: the Mann-Whitney test of the pooled repetitions and a t test of "
                          "the runs' levels over their run-to-run spread, both with a Bonferroni correction over "
                          "a segment's splits, and a Hodges-Lehmann shift beyond min_change");
    jw_kv_num(&w, "alpha", h->cp.alpha);
    jw_kv_num(&w, "min_change", h->cp.min_change);
    jw_kv_int(&w, "min_segment_runs", h->cp.min_seg);
    jw_obj_end(&w);
    jw_kv_arr(&w, "runs");
    for (int k = 0; k < h->nruns; ++k) {
        jw_obj_begin(&w);
        jw_kv_int(&w, "index", k + 1);
        jw_kv_str(&w, "name", h->runs[k].name);
        jw_kv_str(&w, "date", h->runs[k].date);
        jw_kv_str(&w, "commit_date", h->runs[k].commit_date);
        jw_kv_str(&w, "commit", h->runs[k].commit);
        jw_kv_str(&w, "device", h->runs[k].device);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_arr(&w, "rows");
    for (int i = 0; i < h->nrows; ++i) {
        const struct hist_row *r = &h->rows[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "kind", r->kind);
        jw_kv_str(&w, "device", r->device);
        jw_kv_str(&w, "label", r->label);
        jw_kv_str(&w, "metric", r->metric);
        jw_kv_str(&w, "unit", r->unit);
        jw_kv_str(&w, "direction", rd_direction_name(r->direction));
        jw_kv_str(&w, "basis", r->basis);
        jw_kv_nums(&w, "values", r->median, (size_t)h->nruns);
        jw_kv_arr(&w, "changes");
        for (int c = 0; c < r->nchanges; ++c)
            json_change(&w, h, r, &r->changes[c], 0);
        jw_arr_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_arr(&w, "changes");
    for (int i = 0; i < h->nrows; ++i)
        for (int c = 0; c < h->rows[i].nchanges; ++c)
            json_change(&w, h, &h->rows[i], &h->rows[i].changes[c], 1);
    jw_arr_end(&w);
    jw_obj_end(&w);
    char path[4200];
    if (path_join(path, sizeof path, dir, "history.json")) {
        jw_free(&w);
        snprintf(err, errlen, "%s: path too long", dir);
        return 3;
    }
    return jw_write_file_free(&w, path, err, errlen) ? 3 : 0;
}

static int write_md(const struct hist_set *h, const char *dir, const char *source, char *err, size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    int nchanges = 0, timed = 0;
    for (int i = 0; i < h->nrows; ++i) {
        nchanges += h->rows[i].nchanges;
        timed += h->rows[i].timed;
    }
    md_printf(&b, "# History\n\n%d runs from %s, ordered by %s; %d rows (%d timed), %d change%s.\n\n", h->nruns, source,
              h->order, h->nrows, timed, nchanges, nchanges == 1 ? "" : "s");
    md_printf(&b, "A timed row changes where binary segmentation splits its runs: the Mann-Whitney test of the "
                  "repetitions after against those before, and a t test of the runs' levels against how much "
                  "whole runs differ, both give p < %g after a Bonferroni correction over the segment's splits, "
                  "and the Hodges-Lehmann ratio is beyond %g%%. A segment inside the series "
                  "holds %d runs or more; the latest run may stand alone. Other figures change where their 4th "
                  "significant digit moves.\n\n",
              h->cp.alpha, 100 * h->cp.min_change, h->cp.min_seg);
    md_printf(&b, "## Changes\n\n");
    if (nchanges == 0) {
        md_printf(&b, "None.\n\n");
    } else {
        md_printf(&b, "| row | metric | from run | commit | ratio | interval | p |\n|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < h->nrows; ++i)
            for (int c = 0; c < h->rows[i].nchanges; ++c) {
                const struct hist_row *r = &h->rows[i];
                const struct hist_change *x = &r->changes[c];
                md_printf(&b, "| ");
                if (*r->device) {
                    md_cell_text(&b, r->device);
                    md_printf(&b, " \\| ");
                }
                md_cell_text(&b, r->label);
                md_printf(&b, " | %s | %d (", r->metric, x->at + 1);
                md_cell_text(&b, h->runs[x->at].name);
                md_printf(&b, ") | ");
                md_cell_text(&b, h->runs[x->at].commit);
                if (isfinite(x->lo))
                    md_printf(&b, " | %.3f | %.3f..%.3f | %.2g |\n", x->ratio, x->lo, x->hi, x->p);
                else
                    md_printf(&b, " | %.4g | | |\n", x->ratio);
            }
        md_printf(&b, "\n");
    }
    md_printf(&b, "## Rows\n\n| row | metric | changes decided on | runs | changes | figure, latest / first run |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < h->nrows; ++i) {
        const struct hist_row *r = &h->rows[i];
        int first = -1, last = -1, n = 0;
        for (int k = 0; k < h->nruns; ++k)
            if (isfinite(r->median[k])) {
                if (first < 0)
                    first = k;
                last = k;
                ++n;
            }
        md_printf(&b, "| ");
        if (*r->device) {
            md_cell_text(&b, r->device);
            md_printf(&b, " \\| ");
        }
        md_cell_text(&b, r->label);
        md_printf(&b, " | %s | %s | %d | %d | ", r->metric, r->basis, n, r->nchanges);
        if (first >= 0 && r->median[first] != 0)
            md_printf(&b, "%.3f |\n", r->median[last] / r->median[first]);
        else
            md_printf(&b, " |\n");
    }
    md_printf(&b, "\n## Runs\n\n| # | run | date | commit |\n|---|---|---|---|\n");
    for (int k = 0; k < h->nruns; ++k) {
        md_printf(&b, "| %d | ", k + 1);
        md_cell_text(&b, h->runs[k].name);
        md_printf(&b, " | ");
        md_cell_text(&b, h->runs[k].date);
        md_printf(&b, " | ");
        md_cell_text(&b, h->runs[k].commit);
        md_printf(&b, " |\n");
    }
    md_printf(&b, "\n![each row over the runs](history.png)\n");
    if (timed > 0)
        md_printf(&b, "\n![every timed row over its first segment](history_normalised.png)\n");
    char path[4200];
    if (path_join(path, sizeof path, dir, "history.md")) {
        md_free(&b);
        snprintf(err, errlen, "%s: path too long", dir);
        return 3;
    }
    return md_write_file_free(&b, path, err, errlen) ? 3 : 0;
}

#define PANEL_W 540
#define PANEL_H 300
#define PANEL_COLS 3
#define MAX_PANELS 48

/* history.png: a line plot per row (the figure per run, a dotted line at each change),
 * drawn one by one and laid out in a grid. */
static int write_multiples(const struct hist_set *h, const char *dir, char *err, size_t errlen)
{
    int n = h->nrows < MAX_PANELS ? h->nrows : MAX_PANELS;
    int rows = (n + PANEL_COLS - 1) / PANEL_COLS;
    int W = PANEL_W * PANEL_COLS, H = PANEL_H * (rows > 0 ? rows : 1);
    unsigned char *img = malloc((size_t)W * (size_t)H * 3);
    double *x = malloc((size_t)(h->nruns > 0 ? h->nruns : 1) * sizeof *x);
    double *vl = malloc(CP_MAX_CHANGES * sizeof *vl);
    double *scaled = malloc((size_t)(h->nruns > 0 ? h->nruns : 1) * sizeof *scaled);
    char tmp[4200], path[4200];
    int rc = 0;
    if (!img || !x || !vl || !scaled) {
        snprintf(err, errlen, "%s: out of memory drawing history.png", dir);
        rc = 3;
        goto done;
    }
    memset(img, 255, (size_t)W * (size_t)H * 3);
    for (int k = 0; k < h->nruns; ++k)
        x[k] = k + 1;
    char tmpname[64];
    snprintf(tmpname, sizeof tmpname, ".history-panel-%ld.png", (long)getpid());
    if (path_join(tmp, sizeof tmp, dir, tmpname) || path_join(path, sizeof path, dir, "history.png")) {
        snprintf(err, errlen, "%s: path too long", dir);
        rc = 3;
        goto done;
    }
    for (int i = 0; i < n && !rc; ++i) {
        const struct hist_row *r = &h->rows[i];
        struct draw_series s[4];
        memset(s, 0, sizeof s);
        s[0] = (struct draw_series){ .x = x, .y = r->median, .count = h->nruns, .label = "absolute", .colour = 0,
                                     .markers = 1 };
        s[1] = (struct draw_series){ .x = x, .y = r->lo, .count = h->nruns, .label = "min, max", .colour = 7,
                                     .dashed = 1 };
        s[2] = (struct draw_series){ .x = x, .y = r->hi, .count = h->nruns, .label = NULL, .colour = 7, .dashed = 1 };
        /* the normalised rate (over the reference kernel) at the absolute rate's level of the
           first run with both: where the machine drifted, the two part */
        double f = NAN;
        for (int k = 0; k < h->nruns && !isfinite(f); ++k)
            if (isfinite(r->median[k]) && isfinite(r->nmedian[k]) && r->nmedian[k] > 0)
                f = r->median[k] / r->nmedian[k];
        for (int k = 0; k < h->nruns; ++k)
            scaled[k] = r->nmedian[k] * f;
        s[3] = (struct draw_series){ .x = x, .y = scaled, .count = h->nruns, .label = "normalised", .colour = 1,
                                     .markers = 1 };
        for (int c = 0; c < r->nchanges; ++c)
            vl[c] = r->changes[c].at + 0.5;   /* between the last run before and the first after */
        char title[RD_TEXT * 2 + 80], ylabel[RD_NAME + 40];
        /* the device in the title only when the rows are of several */
        int several = 0;
        for (int j = 0; j < h->nrows; ++j)
            several |= strcmp(h->rows[j].device, r->device) != 0;
        snprintf(title, sizeof title, "%s%s%s", several ? r->device : "", several ? " | " : "", r->label);
        snprintf(ylabel, sizeof ylabel, "%s (%s)", r->metric, r->unit);
        struct draw_line_plot p;
        memset(&p, 0, sizeof p);
        p.title = title;
        p.x_label = "run";
        p.y_label = ylabel;
        p.x_min = 0.5;
        p.x_max = h->nruns + 0.5;
        p.nseries = !r->timed ? 1 : isfinite(f) ? 4 : 3;
        p.series = s;
        p.nvlines = r->nchanges;
        p.vlines = vl;
        p.width = PANEL_W;
        p.height = PANEL_H;
        int w = 0, ht = 0;
        unsigned char *pix = NULL;
        if (draw_line_plot(tmp, &p, err, errlen) || draw_read_rgb8(tmp, &w, &ht, &pix, err, errlen)) {
            rc = 3;
            break;
        }
        int ox = (i % PANEL_COLS) * PANEL_W, oy = (i / PANEL_COLS) * PANEL_H;
        for (int yy = 0; yy < ht && yy < PANEL_H; ++yy)
            memcpy(img + ((size_t)(oy + yy) * (size_t)W + (size_t)ox) * 3, pix + (size_t)yy * (size_t)w * 3,
                   (size_t)(w < PANEL_W ? w : PANEL_W) * 3);
        free(pix);
    }
    unlink(tmp);
    if (!rc && draw_png_rgb8(path, W, H, img, err, errlen))
        rc = 3;
done:
    free(img);
    free(x);
    free(vl);
    free(scaled);
    return rc;
}

/* history_normalised.png: every timed row's figure over the median of its first segment. */
static int write_normalised(const struct hist_set *h, const char *dir, char *err, size_t errlen)
{
    int T = h->nruns, n = 0;
    double *x = malloc((size_t)(T > 0 ? T : 1) * sizeof *x);
    double *y = malloc((size_t)(h->nrows > 0 ? h->nrows : 1) * (size_t)(T > 0 ? T : 1) * sizeof *y);
    struct draw_series *s = calloc((size_t)(h->nrows > 0 ? h->nrows : 1), sizeof *s);
    double vl[CP_MAX_CHANGES];
    int nvl = 0, rc = 0;
    if (!x || !y || !s) {
        snprintf(err, errlen, "%s: out of memory drawing history_normalised.png", dir);
        rc = 3;
        goto done;
    }
    for (int k = 0; k < T; ++k)
        x[k] = k + 1;
    for (int i = 0; i < h->nrows; ++i) {
        const struct hist_row *r = &h->rows[i];
        if (!r->timed)
            continue;
        int end = r->nchanges ? r->changes[0].at : T;
        double lo, hi, base = median_of(r->median, end, &lo, &hi);
        double *yi = y + (size_t)n * (size_t)T;
        for (int k = 0; k < T; ++k)
            yi[k] = isfinite(base) && base != 0 ? r->median[k] / base : NAN;
        s[n] = (struct draw_series){ .x = x, .y = yi, .count = T, .label = n < 10 ? r->label : NULL,
                                     .colour = n % 10, .markers = 1 };
        for (int c = 0; c < r->nchanges && nvl < CP_MAX_CHANGES; ++c)
            vl[nvl++] = r->changes[c].at + 0.5;
        ++n;
    }
    char path[4200];
    if (path_join(path, sizeof path, dir, "history_normalised.png")) {
        snprintf(err, errlen, "%s: path too long", dir);
        rc = 3;
        goto done;
    }
    struct draw_line_plot p;
    memset(&p, 0, sizeof p);
    p.title = "every timed row over the median of its first segment (dotted: a change in some row)";
    p.x_label = "run";
    p.y_label = "figure / first segment's";
    p.x_min = 0.5;
    p.x_max = T + 0.5;
    p.nseries = n;
    p.series = s;
    p.nvlines = nvl;
    p.vlines = vl;
    if (n > 0 && draw_line_plot(path, &p, err, errlen))
        rc = 3;
    else if (n == 0)
        unlink(path);   /* no timed row: no picture, and none an earlier history left */
done:
    free(x);
    free(y);
    free(s);
    return rc;
}

int history_write(const struct hist_set *h, const char *dir, const char *source, char *err, size_t errlen)
{
    if (write_json(h, dir, source, err, errlen) || write_md(h, dir, source, err, errlen) ||
        write_multiples(h, dir, err, errlen) || write_normalised(h, dir, err, errlen))
        return 3;
    return 0;
}

void history_free(struct hist_set *h)
{
    for (int k = 0; k < h->nruns; ++k)
        rdoc_free(&h->runs[k].doc);
    free(h->runs);
    for (int i = 0; i < h->nrows; ++i) {
        free(h->rows[i].median);
        free(h->rows[i].lo);
        free(h->rows[i].hi);
        free(h->rows[i].nmedian);
    }
    free(h->rows);
    memset(h, 0, sizeof *h);
}
