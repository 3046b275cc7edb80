/* rdoc_export.c - the rows as google/benchmark JSON, Bencher Metric Format and
 * github-action-benchmark's custom JSON (see rdoc_export.h for what goes where). */
#include "rdoc_export.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jsonw.h"
#include "stats.h"

/* Metrics of a row that the format takes: timed (gbench), finite of a direction (action;
 * direction < 0: any, for bmf). */
static int takes(const struct rd_metric *m, int timed_only, int direction)
{
    if (timed_only)
        return m->timed && ((m->nreps > 0) || isfinite(m->value));
    if (!isfinite(m->value))
        return 0;
    return direction < 0 || m->direction == direction;
}

static int count_taken(const struct rd_row *r, int timed_only, int direction)
{
    int n = 0;
    for (int m = 0; m < r->nmetrics; ++m)
        n += takes(&r->metrics[m], timed_only, direction);
    return n;
}

void rdoc_export_name(const struct rdoc *d, const struct rd_row *r, const struct rd_metric *m, int with_metric,
                      const char *sep, char *out, size_t outlen)
{
    size_t len = 0;
    out[0] = 0;
    if (*r->device && rdoc_distinct_devices(d) > 1)
        len += (size_t)snprintf(out, outlen, "%s%s", r->device, sep);
    /* the label's " | " separators become sep; a row with no label is named by its keys */
    char keys[RD_TEXT * 2] = "";
    const char *label = r->label;
    if (!*label) {
        for (int k = 0; k < r->nkeys; ++k)
            snprintf(keys + strlen(keys), sizeof keys - strlen(keys), "%s%s", k ? " | " : "", r->keys[k].value);
        label = *keys ? keys : r->model;
    }
    for (const char *s = label; *s && len + 1 < outlen;) {
        if (strncmp(s, " | ", 3) == 0) {
            len += (size_t)snprintf(out + len, outlen - len, "%s", sep);
            s += 3;
        } else {
            out[len++] = *s++;
            out[len] = 0;
        }
    }
    if (with_metric && m && len < outlen)
        snprintf(out + len, outlen - len, "%s%s", sep, m->name);
}

static int flush(struct jw *w, struct md_buf *out, char *err, size_t errlen)
{
    int bad = w->out.failed || w->malformed || w->depth != 0;
    if (!bad) {
        md_append(out, w->out.s ? w->out.s : "", w->out.len);
        md_append(out, "\n", 1);
    }
    jw_free(w);
    if (bad)
        snprintf(err, errlen, "out of memory writing the export");
    return bad ? 3 : 0;
}

/* ---- google/benchmark ------------------------------------------------------------------- */

/* An iteration is a million items (evaluations, FLOPs): its time in microseconds, 1e12 / rate,
 * is a number of a few digits for rates from 1e6 to 1e12 per second, which compare.py's
 * table (whole units) shows. */
#define GB_ITEMS 1e6

/* google/benchmark's statistics of a sample: mean, median (the mean of the two middle values
 * for an even count), sample standard deviation (n - 1; 0 for one value), and cv = stddev / mean. */
struct gb_stats {
    double mean, median, stddev, cv;
};

static struct gb_stats stats_of(const double *v, int n)
{
    struct gb_stats s = { NAN, NAN, NAN, NAN };
    double *t = malloc((size_t)(n > 0 ? n : 1) * sizeof *t);
    if (!t || n <= 0) {
        free(t);
        return s;
    }
    double sum = 0;
    for (int i = 0; i < n; ++i)
        sum += (t[i] = v[i]);
    s.mean = sum / n;
    qsort(t, (size_t)n, sizeof *t, stats_cmp_double);
    s.median = stats_median_sorted(t, (size_t)n);
    double ss = 0;
    for (int i = 0; i < n; ++i)
        ss += (t[i] - s.mean) * (t[i] - s.mean);
    s.stddev = n > 1 ? sqrt(ss / (n - 1)) : 0;
    s.cv = s.mean != 0 ? s.stddev / s.mean : NAN;
    free(t);
    return s;
}

static void gb_common(struct jw *w, const char *name, const char *run_name, int family, const char *run_type, int reps)
{
    jw_kv_str(w, "name", name);
    jw_kv_int(w, "family_index", family);
    jw_kv_int(w, "per_family_instance_index", 0);
    jw_kv_str(w, "run_name", run_name);
    jw_kv_str(w, "run_type", run_type);
    jw_kv_int(w, "repetitions", reps);
}

static void gb_times(struct jw *w, double us, double items_per_s)
{
    jw_kv_num(w, "real_time", us);
    jw_kv_num(w, "cpu_time", us);
    jw_kv_str(w, "time_unit", "us");
    jw_kv_num(w, "items_per_second", items_per_s);
    jw_kv_num(w, "items_per_iteration", GB_ITEMS);
}

/* One timed metric as google/benchmark writes a benchmark run with repetitions. */
static void gb_metric(struct jw *w, const char *name, int family, const struct rd_metric *m)
{
    const double *rates = m->nreps > 0 ? m->reps : &m->value;
    int n = m->nreps > 0 ? m->nreps : 1;
    double *ns = malloc((size_t)n * sizeof *ns);
    if (!ns) {
        w->out.failed = 1;
        return;
    }
    int kept = 0;   /* a rate that is not positive and finite is no time */
    double *r = malloc((size_t)n * sizeof *r);
    if (!r) {
        free(ns);
        w->out.failed = 1;
        return;
    }
    for (int i = 0; i < n; ++i)
        if (isfinite(rates[i]) && rates[i] > 0) {
            r[kept] = rates[i];
            ns[kept++] = GB_ITEMS * 1e6 / rates[i];
        }
    for (int i = 0; i < kept; ++i) {
        jw_obj_begin(w);
        gb_common(w, name, name, family, "iteration", kept);
        jw_kv_int(w, "repetition_index", i);
        jw_kv_int(w, "threads", 1);
        jw_kv_int(w, "iterations", 1);
        gb_times(w, ns[i], r[i]);
        jw_obj_end(w);
    }
    if (kept > 1) {   /* google/benchmark writes the aggregates of two or more repetitions */
        struct gb_stats t = stats_of(ns, kept), q = stats_of(r, kept);
        static const char *const agg[] = { "mean", "median", "stddev", "cv" };
        const double tv[] = { t.mean, t.median, t.stddev, t.cv }, qv[] = { q.mean, q.median, q.stddev, q.cv };
        for (int a = 0; a < 4; ++a) {
            char aname[640];
            snprintf(aname, sizeof aname, "%s_%s", name, agg[a]);
            jw_obj_begin(w);
            gb_common(w, aname, name, family, "aggregate", kept);
            jw_kv_int(w, "threads", 1);
            jw_kv_str(w, "aggregate_name", agg[a]);
            jw_kv_str(w, "aggregate_unit", a == 3 ? "percentage" : "time");
            jw_kv_int(w, "iterations", kept);
            gb_times(w, tv[a], qv[a]);
            jw_obj_end(w);
        }
    }
    free(ns);
    free(r);
}

int rdoc_gbench(const struct rdoc *d, struct md_buf *out, char *err, size_t errlen)
{
    int any = 0;
    for (int i = 0; i < d->nrows; ++i)
        any += count_taken(&d->rows[i], 1, -1);
    if (!any) {
        snprintf(err, errlen, "--format gbench: %s holds no timed figure (gbench takes rates; "
                              "accuracy figures go to --format bmf or action-smaller)", d->file);
        return 2;
    }
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_obj(&w, "context");
    const char *date = rd_ctx_get(&d->ctx, "date"), *cores = rd_ctx_get(&d->ctx, "host_cores");
    jw_kv_str(&w, "date", date ? date : "");
    jw_kv_str(&w, "executable", "brdfbench");
    if (cores)
        jw_kv_int(&w, "num_cpus", atoi(cores));
    /* the run's own context as custom context strings, as AddCustomContext writes them */
    for (int c = 0; c < d->ctx.count; ++c)
        if (strcmp(d->ctx.key[c], "date") != 0)
            jw_kv_str(&w, d->ctx.key[c], d->ctx.value[c]);
    jw_kv_str(&w, "brdfbench_source", d->file);
    jw_obj_end(&w);
    jw_kv_arr(&w, "benchmarks");
    int family = 0;
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        int taken = count_taken(r, 1, -1);
        int timed = 0;
        for (int m = 0; m < r->nmetrics; ++m)
            timed += r->metrics[m].timed;
        if (!r->ok && timed) {   /* a rate not measured: google/benchmark's error entry, no times */
            char name[600];
            rdoc_export_name(d, r, NULL, 0, "/", name, sizeof name);
            jw_obj_begin(&w);
            gb_common(&w, name, name, family++, "iteration", 0);
            jw_kv_bool(&w, "error_occurred", 1);
            jw_kv_str(&w, "error_message", r->reason);
            jw_obj_end(&w);
            continue;
        }
        for (int m = 0; r->ok && m < r->nmetrics; ++m) {
            if (!takes(&r->metrics[m], 1, -1))
                continue;
            char name[600];
            rdoc_export_name(d, r, &r->metrics[m], taken > 1, "/", name, sizeof name);
            gb_metric(&w, name, family++, &r->metrics[m]);
        }
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    return flush(&w, out, err, errlen);
}

/* ---- Bencher Metric Format ---------------------------------------------------------------- */

int rdoc_bmf(const struct rdoc *d, struct md_buf *out, char *err, size_t errlen)
{
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        if (!r->ok || count_taken(r, 0, -1) == 0)
            continue;   /* BMF has no place for a figure not measured */
        char name[600];
        rdoc_export_name(d, r, NULL, 0, " | ", name, sizeof name);
        jw_kv_obj(&w, name);
        for (int m = 0; m < r->nmetrics; ++m) {
            const struct rd_metric *x = &r->metrics[m];
            if (!takes(x, 0, -1))
                continue;
            jw_kv_obj(&w, x->name);
            jw_kv_num(&w, "value", x->value);
            if (isfinite(x->lo) && isfinite(x->hi)) {
                jw_kv_num(&w, "lower_value", x->lo);
                jw_kv_num(&w, "upper_value", x->hi);
            }
            jw_obj_end(&w);
        }
        jw_obj_end(&w);
    }
    jw_obj_end(&w);
    return flush(&w, out, err, errlen);
}

/* ---- github-action-benchmark ---------------------------------------------------------------- */

int rdoc_action(const struct rdoc *d, int direction, struct md_buf *out, char *err, size_t errlen)
{
    int any = 0;
    for (int i = 0; i < d->nrows; ++i)
        any += d->rows[i].ok ? count_taken(&d->rows[i], 0, direction) : 0;
    if (!any) {
        snprintf(err, errlen, "--format %s: %s holds no figure where %s is better (try --format %s)",
                 direction == RD_HIGHER ? "action" : "action-smaller", d->file,
                 direction == RD_HIGHER ? "higher" : "lower", direction == RD_HIGHER ? "action-smaller" : "action");
        return 2;
    }
    struct jw w;
    jw_init(&w);
    jw_arr_begin(&w);
    const char *commit = rd_ctx_get(&d->ctx, "git_revision"), *device = rd_ctx_get(&d->ctx, "device");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        if (!r->ok)
            continue;
        int taken = count_taken(r, 0, direction);
        for (int m = 0; m < r->nmetrics; ++m) {
            const struct rd_metric *x = &r->metrics[m];
            if (!takes(x, 0, direction))
                continue;
            char name[600], range[96] = "", extra[700];
            rdoc_export_name(d, r, x, taken > 1 || r->nmetrics > 1, " | ", name, sizeof name);
            jw_obj_begin(&w);
            jw_kv_str(&w, "name", name);
            jw_kv_str(&w, "unit", x->unit);
            jw_kv_num(&w, "value", x->value);
            if (isfinite(x->lo) && isfinite(x->hi)) {
                /* the spread of the repetitions, as the action shows it ("± x") */
                snprintf(range, sizeof range, "± %.4g", 0.5 * (x->hi - x->lo));
                jw_kv_str(&w, "range", range);
            }
            int len = snprintf(extra, sizeof extra, "device: %s\ncommit: %s",
                               *r->device ? r->device : device ? device : "?", commit ? commit : "?");
            if (x->nreps > 0 && isfinite(x->lo) && isfinite(x->hi) && len > 0 && (size_t)len < sizeof extra)
                snprintf(extra + len, sizeof extra - (size_t)len, "\nmedian of %d repetitions, min..max %.4g..%.4g",
                         x->nreps, x->lo, x->hi);
            jw_kv_str(&w, "extra", extra);
            jw_obj_end(&w);
        }
    }
    jw_arr_end(&w);
    return flush(&w, out, err, errlen);
}
