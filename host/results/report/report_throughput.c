/* report_throughput.c - the throughput page drawn from throughput.json's rows
 * (report_throughput.h): the device peak, the default build options' table with its derived
 * columns, the build options' table (speed beside accuracy) and the accuracy sweep's line.
 * Every ratio is computed here from the rates of the rows, as the engine computes the ratios of
 * its JSON detail (throughput_report.c): a over b where both are finite and positive. */
#include "report_throughput.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_VARIANT "default"

/* The rows of one device, and what the page walks them by. */
struct tp_view {
    const struct rdoc *d;
    const char *device;
    const struct rd_row *peak;
    const char **variants, **modes, **labels;   /* in the order of the rows (modes: uniform first) */
    int nvariants, nmodes, nlabels;
};

static double ratio(double a, double b) { return (a > 0 && b > 0 && isfinite(a) && isfinite(b)) ? a / b : NAN; }

static const char *key(const struct rd_row *r, const char *name)
{
    const char *v = rd_row_key_value(r, name);
    return v ? v : "";
}

static int on_device(const struct tp_view *w, const struct rd_row *r) { return strcmp(r->device, w->device) == 0; }

/* A measured row: a model (or the pow() built-in) in a build variant and an n mode. */
static int is_result(const struct rd_row *r)
{
    return rd_row_key_value(r, "label") && rd_row_key_value(r, "variant") && rd_row_key_value(r, "n_mode");
}

static int is_sweep(const struct rd_row *r) { return rd_row_key_value(r, "sweep") && rd_row_key_value(r, "label"); }

static int builtin(const struct rd_row *r) { return strcmp(key(r, "kind"), "builtin") == 0; }

/* Adds s to the list when it is not there yet. */
static void add_once(const char **list, int *n, const char *s)
{
    for (int i = 0; i < *n; ++i)
        if (strcmp(list[i], s) == 0)
            return;
    list[(*n)++] = s;
}

/* The result row of label in variant and n mode, or NULL. */
static const struct rd_row *find(const struct tp_view *w, const char *label, const char *variant, const char *mode)
{
    for (int i = 0; i < w->d->nrows; ++i) {
        const struct rd_row *r = &w->d->rows[i];
        if (on_device(w, r) && is_result(r) && strcmp(key(r, "label"), label) == 0 &&
            strcmp(key(r, "variant"), variant) == 0 && (!mode || strcmp(key(r, "n_mode"), mode) == 0))
            return r;
    }
    return NULL;
}

/* The pow() built-in's row in the same variant and n mode as r, or NULL. */
static const struct rd_row *builtin_of(const struct tp_view *w, const struct rd_row *r)
{
    for (int i = 0; i < w->d->nrows; ++i) {
        const struct rd_row *p = &w->d->rows[i];
        if (on_device(w, p) && is_result(p) && builtin(p) && strcmp(key(p, "variant"), key(r, "variant")) == 0 &&
            strcmp(key(p, "n_mode"), key(r, "n_mode")) == 0)
            return p;
    }
    return NULL;
}

/* A row's measured rate: its evals_per_s when the row is ok, else NAN. */
static double rate_of(const struct rd_row *r) { return r && r->ok ? rd_row_value(r, "evals_per_s") : NAN; }

static double peak_fma_per_s(const struct tp_view *w)
{
    return w->peak && w->peak->ok ? rd_row_value(w->peak, "flops_per_s") / 2.0 : NAN;
}

static int view_open(struct tp_view *w, const struct rdoc *d, const char *device)
{
    memset(w, 0, sizeof *w);
    w->d = d;
    w->device = device;
    size_t n = (size_t)d->nrows + 2;
    w->variants = calloc(n, sizeof *w->variants);
    w->modes = calloc(n, sizeof *w->modes);
    w->labels = calloc(n, sizeof *w->labels);
    if (!w->variants || !w->modes || !w->labels)
        return -1;
    /* the n modes in the engine's order (uniform, varying), then any other */
    static const char *const known[] = { "uniform", "varying" };
    for (size_t k = 0; k < sizeof known / sizeof known[0]; ++k)
        for (int i = 0; i < d->nrows; ++i)
            if (on_device(w, &d->rows[i]) && is_result(&d->rows[i]) && strcmp(key(&d->rows[i], "n_mode"), known[k]) == 0) {
                w->modes[w->nmodes++] = known[k];
                break;
            }
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        if (!on_device(w, r))
            continue;
        if (!w->peak && rd_row_key_value(r, "reference"))
            w->peak = r;
        if (!is_result(r))
            continue;
        add_once(w->variants, &w->nvariants, key(r, "variant"));
        add_once(w->modes, &w->nmodes, key(r, "n_mode"));
        add_once(w->labels, &w->nlabels, key(r, "label"));
    }
    return 0;
}

static void view_close(struct tp_view *w)
{
    free(w->variants);
    free(w->modes);
    free(w->labels);
}

static int variant_on(const struct tp_view *w, const char *v)
{
    for (int i = 0; i < w->nvariants; ++i)
        if (strcmp(w->variants[i], v) == 0)
            return 1;
    return 0;
}

/* A figure in G/s with 3 significant digits, or a dash. */
static const char *gfmt(char *buf, size_t len, double v)
{
    if (isfinite(v))
        snprintf(buf, len, "%.3g", v * 1e-9);
    else
        snprintf(buf, len, "-");
    return buf;
}

static const char *xfmt(char *buf, size_t len, double v, const char *suffix)
{
    if (isfinite(v))
        snprintf(buf, len, "%.3g%s", v, suffix);
    else
        snprintf(buf, len, "-");
    return buf;
}

/* The name a table gives a row: the model's label, or the built-in's (long or short). */
static const char *shown(const struct rd_row *r, const char *builtin_name)
{
    return builtin(r) ? builtin_name : key(r, "label");
}

/* The device peak and the default build options' table. */
static void table_default(const struct tp_view *w, struct md_buf *t, int md)
{
    char a[32], b[32], c[32], d[32], e2[32], f2[32], g2[32], h2[32];
    if (w->peak && w->peak->ok)
        md_printf(t, "device peak: %.4g GFLOP/s (float16 FMA chains) = %.4g G FMA/s; fraction of peak = evaluations/s "
                     "per FMA/s\n\n", rd_row_value(w->peak, "flops_per_s") * 1e-9, peak_fma_per_s(w) * 1e-9);
    else
        md_printf(t, "device peak: not measured (%s)\n\n", w->peak ? w->peak->reason : "the file has no peak");
    if (!variant_on(w, DEFAULT_VARIANT))
        return;
    md_printf(t, "%sG evaluations/s, default build options (median of %s launches, profiling events; "
                 "tuned C: %s threads)%s\n\n", md ? "**" : "", rdoc_text_or(w->d, "reps", "?"),
              rdoc_text_or(w->d, "tuned_c_threads", "?"), md ? "**" : "");
    if (md)
        md_printf(t, "| model | n | G evals/s | min - max | x pow() | x model ref | x tuned C | of peak | C G evals/s |\n"
                     "|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    else
        md_printf(t, "%-18s %-8s %10s %17s %8s %8s %9s %8s %10s\n", "model", "n", "G evals/s", "min - max",
                  "x pow()", "x ref", "x tuned C", "of peak", "C G/s");
    for (int m = 0; m < w->nmodes; ++m)
        for (int i = 0; i < w->nlabels; ++i) {
            const struct rd_row *r = find(w, w->labels[i], DEFAULT_VARIANT, w->modes[m]);
            if (!r)
                continue;
            const struct rd_metric *rate = rd_row_find(r, "evals_per_s");
            double f = rate_of(r), host_c = rd_row_value(r, "host_c.evals_per_s");
            const char *ref = rd_row_key_value(r, "model_reference");
            double to_pow = NAN, to_ref = NAN, to_c = NAN, of_peak = NAN;
            if (r->ok) {
                to_pow = ratio(f, rate_of(builtin_of(w, r)));
                to_ref = ref ? ratio(f, rate_of(find(w, ref, DEFAULT_VARIANT, w->modes[m]))) : NAN;
                to_c = ratio(f, host_c);
                of_peak = ratio(f, peak_fma_per_s(w));
            }
            char range[80];
            if (r->ok && rate)
                snprintf(range, sizeof range, "%s - %s", gfmt(a, sizeof a, rate->lo), gfmt(b, sizeof b, rate->hi));
            else
                snprintf(range, sizeof range, "failed");
            md_printf(t, md ? "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n"
                            : "%-18s %-8s %10s %17s %8s %8s %9s %8s %10s\n", shown(r, "pow() built-in"), w->modes[m],
                      gfmt(c, sizeof c, f), range, xfmt(d, sizeof d, to_pow, ""), xfmt(e2, sizeof e2, to_ref, ""),
                      xfmt(f2, sizeof f2, to_c, ""), xfmt(g2, sizeof g2, of_peak * 100, "%"),
                      gfmt(h2, sizeof h2, host_c));
        }
    /* a C loop whose sums are not the device's has no ratio: say so where the ratio is missing */
    for (int m = 0; m < w->nmodes; ++m)
        for (int i = 0; i < w->nlabels; ++i) {
            const struct rd_row *r = find(w, w->labels[i], DEFAULT_VARIANT, w->modes[m]);
            const char *why = r ? rd_row_text_get(r, "host_c_reason") : NULL;
            if (why)
                md_printf(t, "%sx tuned C, %s %s: none: %s\n", md ? "- " : "! ", shown(r, "pow()"), w->modes[m], why);
        }
    md_printf(t, "\n");
}

/* One cell of the build options' table: the rate of label under variant v in n mode m (x the
 * default variant's) and its accuracy. Returns whether the rate's values were not all finite. */
static int variant_cell(const struct tp_view *w, const char *label, const char *v, const char *m, char *cell,
                        size_t cell_len, char *accs, size_t accs_len)
{
    char a[32];
    const struct rd_row *r = find(w, label, v, m), *r0 = find(w, label, DEFAULT_VARIANT, m);
    int finite = !r || !rd_row_text_get(r, "note");
    if (!r || !r->ok)
        snprintf(cell, cell_len, "%s", r ? "failed" : "-");
    else if (strcmp(v, DEFAULT_VARIANT) != 0 && r0 && r0->ok)
        snprintf(cell, cell_len, "%s%s (%.2fx)", finite ? "" : "!", gfmt(a, sizeof a, rate_of(r)),
                 rate_of(r) / rate_of(r0));
    else
        snprintf(cell, cell_len, "%s%s", finite ? "" : "!", gfmt(a, sizeof a, rate_of(r)));
    /* the accuracy belongs to the model and the variant: any n mode's row carries it */
    const struct rd_metric *acc = NULL;
    for (int i = 0; i < w->d->nrows && !acc; ++i) {
        const struct rd_row *q = &w->d->rows[i];
        if (on_device(w, q) && is_result(q) && strcmp(key(q, "label"), label) == 0 && strcmp(key(q, "variant"), v) == 0)
            acc = rd_row_find(q, "accuracy.max_diff_of_peak");
    }
    if (acc) {
        const struct rd_metric *bad = NULL;
        for (int i = 0; i < w->d->nrows && !bad; ++i) {
            const struct rd_row *q = &w->d->rows[i];
            if (on_device(w, q) && is_result(q) && strcmp(key(q, "label"), label) == 0 &&
                strcmp(key(q, "variant"), v) == 0)
                bad = rd_row_find(q, "accuracy.nonfinite");
        }
        snprintf(accs, accs_len, "%.2g%s", acc->value, bad && bad->value > 0 ? "*" : "");
    } else {
        snprintf(accs, accs_len, "-");
    }
    return r && r->ok && !finite;
}

/* Build options: speed beside accuracy, where more than the default options were built. */
static void table_variants(const struct tp_view *w, struct md_buf *t, int md)
{
    if (w->nvariants <= 1 && variant_on(w, DEFAULT_VARIANT))
        return;
    md_printf(t, "%sbuild options: G evaluations/s (x default) | max |device - double| / reference peak%s\n\n",
              md ? "**" : "", md ? "**" : "");
    if (md) {
        md_printf(t, "| model | n |");
        for (int v = 0; v < w->nvariants; ++v)
            md_printf(t, " %s | accuracy |", w->variants[v]);
        md_printf(t, "\n|---|---|");
        for (int v = 0; v < w->nvariants; ++v)
            md_printf(t, "---:|---:|");
        md_printf(t, "\n");
    } else {
        md_printf(t, "%-18s %-8s", "model", "n");
        for (int v = 0; v < w->nvariants; ++v)
            md_printf(t, " %17s %9s", w->variants[v], "accuracy");
        md_printf(t, "\n");
    }
    int nonfinite = 0;
    for (int m = 0; m < w->nmodes; ++m)
        for (int i = 0; i < w->nlabels; ++i) {
            const struct rd_row *any = NULL;
            for (int v = 0; v < w->nvariants && !any; ++v)
                if (strcmp(w->variants[v], DEFAULT_VARIANT) != 0)
                    any = find(w, w->labels[i], w->variants[v], w->modes[m]);
            if (!any)
                continue;
            md_printf(t, md ? "| %s | %s |" : "%-18s %-8s", shown(any, "pow() built-in"), w->modes[m]);
            for (int v = 0; v < w->nvariants; ++v) {
                char cell[64], accs[32];
                nonfinite |= variant_cell(w, w->labels[i], w->variants[v], w->modes[m], cell, sizeof cell, accs,
                                          sizeof accs);
                md_printf(t, md ? " %s | %s |" : " %17s %9s", cell, accs);
            }
            md_printf(t, "\n");
        }
    if (nonfinite)
        md_printf(t, "\n! some values were NaN or Inf under these build options (timed all the same)\n");
    md_printf(t, "\n");
}

/* The accuracy sweep, device against tuned C: its seconds are each model's points over its
 * rate, summed over the models measured on both sides. */
static void table_sweep(const struct tp_view *w, struct md_buf *t)
{
    const char *grid = rdoc_text_get(w->d, "sweep_grid");
    if (!grid)
        return;   /* the sweep did not run */
    double dsum = 0, hsum = 0, pts = 0;
    int ok = 0;
    for (int i = 0; i < w->d->nrows; ++i) {
        const struct rd_row *r = &w->d->rows[i];
        if (!on_device(w, r) || !is_sweep(r) || !r->ok)
            continue;
        double p = rd_row_value(r, "points");
        dsum += p / rd_row_value(r, "device_points_per_s");
        hsum += p / rd_row_value(r, "host_c_points_per_s");
        pts += p;
        ++ok;
    }
    if (ok > 0)
        md_printf(t, "accuracy sweep (%s, %d model%s, %.3g points): device %.3f s (%.3g G points/s), tuned C %.3f s "
                     "(%.3g G points/s): %.2fx\n", grid, ok, ok == 1 ? "" : "s", pts, dsum, pts / dsum * 1e-9, hsum,
                  pts / hsum * 1e-9, hsum / dsum);
    else
        md_printf(t, "accuracy sweep: not measured (%s)\n", rdoc_text_or(w->d, "sweep_reason", "every model failed"));
}

int report_throughput_page(struct md_buf *b, const struct rdoc *tp, int md)
{
    /* the devices in the order of their rows ("" where the rows name none) */
    const char **devices = calloc((size_t)tp->nrows + 1, sizeof *devices);
    int ndevices = 0;
    if (!devices) {
        b->failed = 1;
        return -1;
    }
    for (int i = 0; i < tp->nrows; ++i)
        add_once(devices, &ndevices, tp->rows[i].device);
    for (int k = 0; k < ndevices; ++k) {
        struct tp_view w;
        if (view_open(&w, tp, devices[k])) {
            view_close(&w);
            b->failed = 1;
            break;
        }
        if (ndevices > 1)
            md_printf(b, md ? "**device: %s**\n\n" : "device: %s\n\n", devices[k]);
        table_default(&w, b, md);
        table_variants(&w, b, md);
        table_sweep(&w, b);
        view_close(&w);
    }
    free(devices);
    return b->failed ? -1 : 0;
}
