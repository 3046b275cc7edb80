/* plots.c - figure data for line plots and bar charts: builders from results, plots.json
 * in both directions, and drawing through draw.h. */
#include "plots.h"

#include "draw.h"
#include "context.h"
#include "jsonr.h"
#include "jsonw.h"
#include "outdir.h"
#include "rdoc_read.h"
#include "room.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const double half_pi = 1.57079632679489661923;

#define CURVE_POINTS 721
#define MAX_PLOT_POINTS 1000

void plots_init(struct plot_set *set) { memset(set, 0, sizeof *set); }

static void figure_free(struct plot_figure *f)
{
    for (int s = 0; s < f->nseries; s++) {
        free(f->series[s].x);
        free(f->series[s].y);
    }
    f->nseries = 0;
}

void plots_free(struct plot_set *set)
{
    for (int i = 0; i < set->count; i++) figure_free(&set->figs[i]);
    free(set->figs);
    memset(set, 0, sizeof *set);
}

struct plot_figure *plots_add(struct plot_set *set, int kind, const char *file, const char *caption)
{
    struct plot_figure *figs = room_for_one(set->figs, set->count, &set->cap, sizeof *figs, 8);
    if (!figs) return NULL;
    set->figs = figs;
    struct plot_figure *f = &set->figs[set->count++];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->highlight = -1;
    snprintf(f->file, sizeof f->file, "%s", file);
    snprintf(f->caption, sizeof f->caption, "%s", caption ? caption : "");
    return f;
}

int plot_series_add(struct plot_figure *fig, const char *label, int colour, int dashed, const double *x,
                    const double *y, size_t count)
{
    if (fig->nseries >= PLOT_MAX_SERIES) return -1;
    struct plot_series *s = &fig->series[fig->nseries];
    memset(s, 0, sizeof *s);
    size_t bytes = (count ? count : 1) * sizeof(double);
    s->x = malloc(bytes);
    s->y = malloc(bytes);
    if (!s->x || !s->y) {
        free(s->x);
        free(s->y);
        return -1;
    }
    if (count) {
        memcpy(s->x, x, count * sizeof(double));
        memcpy(s->y, y, count * sizeof(double));
    }
    s->count = count;
    s->colour = colour;
    s->dashed = dashed;
    snprintf(s->label, sizeof s->label, "%s", label ? label : "");
    fig->nseries++;
    return 0;
}

int plot_colour_known(const char *name) { return draw_colour_index(name) != DRAW_COLOUR_UNKNOWN; }

/* A model's colour; a user model (no colour of its own) takes the palette's first. */
static int colour_of_info(const struct model_info *info)
{
    int i = info ? draw_colour_index(info->colour) : DRAW_COLOUR_UNKNOWN;
    return i == DRAW_COLOUR_UNKNOWN ? 0 : i;
}

int plot_model_colour(const struct model_spec *m) { return colour_of_info(m->info); }

static void set_text(char *dst, size_t len, const char *src) { snprintf(dst, len, "%s", src ? src : ""); }

/* ---- builders ------------------------------------------------------------------- */

int plots_add_curves(struct plot_set *set, const char *file, const char *caption, const char *title, double n,
                     const struct model_spec *models, int count)
{
    if (count < 1) return -1;
    struct plot_figure *f = plots_add(set, PLOT_LINES, file, caption);
    if (!f) return -1;
    set_text(f->title, sizeof f->title, title);
    const char *var = models[0].info->lobe == LOBE_PSI ? "psi" : "theta_h";
    snprintf(f->x_label, sizeof f->x_label, "x = %s (rad)", var);
    snprintf(f->y_label, sizeof f->y_label, "f(cos x, n = %g)", n);
    /* x up to 4 x_e(n): the whole lobe and the start of its tail, readable at any n
       (the reference is below exp(-16 * 0.511) there); capped at pi/2 */
    double x_end = fmin(half_pi, 4 * zone_epicentre_end(n));
    f->x_min = 0;
    f->x_max = x_end;
    double x[CURVE_POINTS], y[CURVE_POINTS];
    for (int i = 0; i < CURVE_POINTS; i++) x[i] = x_end * i / (CURVE_POINTS - 1);
    struct model_spec ref;
    model_reference_spec(&models[0], &ref);
    for (int k = -1; k < count; k++) {
        const struct model_spec *m = k < 0 ? &ref : &models[k];
        if (k >= 0 && strcmp(m->label, ref.label) == 0) continue;
        for (int i = 0; i < CURVE_POINTS; i++) y[i] = model_eval_host(m, cos(x[i]), n);
        char label[MODEL_LABEL_MAX + 16];
        if (k < 0) snprintf(label, sizeof label, "%s (reference)", m->label);
        else snprintf(label, sizeof label, "%s", m->label);
        /* every other model dashed, so curves that coincide stay distinguishable */
        if (plot_series_add(f, label, k < 0 ? DRAW_COLOUR_BLACK : plot_model_colour(m), k >= 0 && k % 2 == 1, x, y,
                            CURVE_POINTS))
            return -1;
    }
    f->nvlines = 1;
    f->vlines[0] = zone_epicentre_end(n);
    snprintf(f->vline_labels[0], sizeof f->vline_labels[0], "x_e(%g): epicentre end", n);
    return 0;
}

static int family_ok(const struct model_info *info, const enum model_family *families, int nfamilies)
{
    if (nfamilies <= 0) return 1;
    for (int i = 0; i < nfamilies; i++)
        if (info->family == families[i]) return 1;
    return 0;
}

int plots_add_max_vs_n(struct plot_set *set, const char *file, const char *caption, const char *title,
                       const struct accuracy_result *res, int count, int relative, const enum model_family *families,
                       int nfamilies)
{
    struct plot_figure *f = plots_add(set, PLOT_LINES, file, caption);
    if (!f) return -1;
    set_text(f->title, sizeof f->title, title);
    snprintf(f->x_label, sizeof f->x_label, "shininess n (log)");
    snprintf(f->y_label, sizeof f->y_label, "%s",
             relative ? "max relative error delta over the epicentre" : "max absolute error Delta over [0, pi/2]");
    f->x_log = 1;
    f->y_format = relative ? 1 /* DRAW_FMT_PERCENT */ : 0;
    double lo = INFINITY, hi = -INFINITY;
    for (int m = 0; m < count; m++) {
        const struct accuracy_result *r = &res[m];
        if (!r->per_n || r->n_count < 1) continue;
        if (strcmp(r->model.label, r->reference.label) == 0) continue;
        if (!family_ok(r->model.info, families, nfamilies)) continue;
        long nb = r->n_count < MAX_PLOT_POINTS ? r->n_count : MAX_PLOT_POINTS;
        double *x = malloc((size_t)nb * sizeof *x), *y = malloc((size_t)nb * sizeof *y);
        if (!x || !y) {
            free(x);
            free(y);
            return -1;
        }
        /* bins of consecutive n; each keeps its largest error (so no peak is lost) at its n */
        for (long b = 0; b < nb; b++) {
            long i0 = b * r->n_count / nb, i1 = (b + 1) * r->n_count / nb;
            double best = NAN, at = r->per_n[i0].n;
            for (long i = i0; i < i1; i++) {
                const struct acc_per_n *p = &r->per_n[i];
                double v = relative ? p->epi_rel : fmax(p->att_abs, p->epi_abs);
                if (isfinite(v) && !(v <= best)) best = v, at = p->n;
            }
            x[b] = at;
            y[b] = best;
        }
        lo = fmin(lo, r->per_n[0].n);
        hi = fmax(hi, r->per_n[r->n_count - 1].n);
        char label[96];
        snprintf(label, sizeof label, "%s", r->model.label);
        /* every other series dashed, so curves that coincide (fq and fq2) both stay visible */
        int rc = plot_series_add(f, label, plot_model_colour(&r->model), f->nseries % 2 == 1, x, y, (size_t)nb);
        free(x);
        free(y);
        if (rc) return -1;
    }
    if (f->nseries == 0) {   /* no model of these families ran: no empty plot */
        figure_free(f);
        set->count--;
        return 1;
    }
    if (hi > lo) {
        f->x_min = lo;
        f->x_max = hi;
    }
    if (lo < 16 && hi > 16) { /* paper 1 reports over n in [16, 1000] */
        f->nvlines = 1;
        f->vlines[0] = 16;
        snprintf(f->vline_labels[0], sizeof f->vline_labels[0], "n = 16 (paper 1's range starts)");
    }
    return 0;
}

int plots_add_against_q(struct plot_set *set, const char *file, const char *caption, const char *title,
                        const char *y_label, int y_format, const double *q, const double *fq, int count,
                        const char *fq_label, double baseline, const char *baseline_label, double mark_q)
{
    int finite = 0;
    for (int i = 0; i < count; i++) finite += isfinite(q[i]) && isfinite(fq[i]);
    if (finite == 0) return 1;   /* nothing to draw: no figure (an empty plot is never drawn) */
    struct plot_figure *f = plots_add(set, PLOT_LINES, file, caption);
    if (!f) return -1;
    set_text(f->title, sizeof f->title, title);
    set_text(f->x_label, sizeof f->x_label, "Q");
    set_text(f->y_label, sizeof f->y_label, y_label);
    f->y_format = y_format;
    if (plot_series_add(f, fq_label, colour_of_info(models_find("fq")), 0, q, fq, (size_t)count))
        return -1;
    f->series[0].markers = count <= 80;
    if (isfinite(baseline)) {
        double bx[2] = {q[0], q[count - 1]}, by[2] = {baseline, baseline};
        if (plot_series_add(f, baseline_label, DRAW_COLOUR_BLACK, 1, bx, by, 2)) return -1;
    }
    if (isfinite(mark_q)) {
        f->nvlines = 1;
        f->vlines[0] = mark_q;
        snprintf(f->vline_labels[0], sizeof f->vline_labels[0], "Q = %g", mark_q);
    }
    return 0;
}

int plots_add_bars(struct plot_set *set, const char *file, const char *caption, const char *title,
                   const char *x_label, const char *const *labels, const double *values, const double *lo,
                   const double *hi, int count, int highlight)
{
    if (count < 1 || count > PLOT_MAX_BARS) return -1;
    struct plot_figure *f = plots_add(set, PLOT_BARS, file, caption);
    if (!f) return -1;
    set_text(f->title, sizeof f->title, title);
    set_text(f->x_label, sizeof f->x_label, x_label);
    double idx[PLOT_MAX_BARS];
    for (int i = 0; i < count; i++) {
        idx[i] = i;
        set_text(f->bar_labels[i], sizeof f->bar_labels[i], labels[i]);
    }
    f->nbars = count;
    f->highlight = highlight;
    if (plot_series_add(f, "value", 0, 0, idx, values, (size_t)count)) return -1;
    if (lo && hi && (plot_series_add(f, "low", 0, 0, idx, lo, (size_t)count) ||
                     plot_series_add(f, "high", 0, 0, idx, hi, (size_t)count)))
        return -1;
    return 0;
}

int plots_add_throughput(struct plot_set *set, const char *json_path, const char *n_mode, const char *file,
                         const char *caption, char *err, size_t errlen)
{
    struct rdoc d;
    if (rdoc_read_file(json_path, &d, err, errlen)) return 2;
    int rc = 2;
    if (rd_kind_of_name(d.kind) != RD_KIND_THROUGHPUT) {
        snprintf(err, errlen, "%s: the figures of %s (schema %s), expected \"%s\"", json_path, d.file, d.schema,
                 THROUGHPUT_SCHEMA);
        goto done;
    }
    const char *labels[PLOT_MAX_BARS];
    double med[PLOT_MAX_BARS], lo[PLOT_MAX_BARS], hi[PLOT_MAX_BARS];
    int count = 0, highlight = -1;
    for (int i = 0; i < d.nrows && count < PLOT_MAX_BARS; i++) {
        const struct rd_row *row = &d.rows[i];
        const char *variant = rd_row_key_value(row, "variant"), *mode = rd_row_key_value(row, "n_mode");
        const struct rd_metric *rate = rd_row_find(row, "evals_per_s");
        if (!variant || !mode || !rate || strcmp(variant, "default") != 0 || strcmp(mode, n_mode) != 0) continue;
        /* in G evaluations per second; a failed row stays as "n/a" */
        med[count] = rate->value * 1e-9;
        lo[count] = rate->lo * 1e-9;
        hi[count] = rate->hi * 1e-9;
        labels[count] = rd_row_key_value(row, "label");
        const char *kind = rd_row_key_value(row, "kind");
        if (kind && strcmp(kind, "builtin") == 0) highlight = count;
        count++;
    }
    if (count == 0) {
        snprintf(err, errlen, "%s: no rows of the default build options with n %s", json_path, n_mode);
        rc = 1;
        goto done;
    }
    char title[160];
    snprintf(title, sizeof title, "Throughput per model, n %s (default build options)", n_mode);
    rc = plots_add_bars(set, file, caption, title,
                        "G evaluations per second, log scale (median; whisker: min..max of the repeats)", labels, med,
                        lo, hi, count, highlight) ? 2 : 0;
    if (rc) snprintf(err, errlen, "%s: out of memory", json_path);
    else set->figs[set->count - 1].x_log = 1;   /* pow() and the cheap lobes are decades apart */
done:
    rdoc_free(&d);
    return rc;
}

/* ---- the quick-run stamp ------------------------------------------------------------------ */

/* A context line's number of the rows, or NAN when it is not there or no number. */
static double ctx_number(const struct rdoc *d, const char *key)
{
    const char *v = rd_ctx_get(&d->ctx, key);
    char *end;
    double x = v && *v ? strtod(v, &end) : NAN;
    return v && *v && !*end ? x : NAN;
}

/* The grid of run_dir/accuracy.json (its rows' context: accuracy n_step, samples per zone): 1
   quick, 0 not, -1 unreadable. */
static int accuracy_json_quick(const char *path)
{
    struct rdoc d;
    char err[512];
    if (rdoc_read_file(path, &d, err, sizeof err)) return -1;
    double step = ctx_number(&d, "accuracy n_step"), samples = ctx_number(&d, "accuracy samples per zone");
    rdoc_free(&d);
    if (!isfinite(step) || !isfinite(samples)) return -1;
    return step >= 10 || samples <= 256;   /* all --quick: n step 10, 256 samples per zone */
}

bool plots_run_is_quick(const char *run_dir)
{
    /* the last answer, kept while the file is the same one (its inode, size and time): a cache of
       a file's content, not a run's state */
    static char last_dir[4096];
    static struct stat last_st;
    static int last_answer = -1;
    char path[4200];
    struct stat st;
    if (path_join(path, sizeof path, run_dir, "accuracy.json") || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return false;
    if (last_answer >= 0 && strcmp(last_dir, run_dir) == 0 && st.st_ino == last_st.st_ino &&
        st.st_dev == last_st.st_dev && st.st_size == last_st.st_size && st.st_mtim.tv_sec == last_st.st_mtim.tv_sec &&
        st.st_mtim.tv_nsec == last_st.st_mtim.tv_nsec)
        return last_answer == 1;
    int q = accuracy_json_quick(path);
    snprintf(last_dir, sizeof last_dir, "%s", run_dir);
    last_st = st;
    last_answer = q == 1;
    return q == 1;
}

int plots_stamp_if_quick(const char *png, int up, char *err, size_t errlen)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", png);
    for (int k = 0; k <= up; k++) {   /* the picture's folder, then `up` more */
        char *slash = strrchr(dir, '/');
        if (!slash) {   /* a relative name: "." and one ".." per level left */
            snprintf(dir, sizeof dir, ".");
            for (int j = k; j < up; j++) strncat(dir, "/..", sizeof dir - strlen(dir) - 1);
            break;
        }
        *slash = '\0';
        if (dir[0] == '\0') snprintf(dir, sizeof dir, "/");
    }
    if (!plots_run_is_quick(dir)) return 0;
    return draw_stamp_png(png, PLOTS_QUICK_STAMP, err, errlen);
}

/* ---- drawing ---------------------------------------------------------------------- */

int plot_figure_draw(const struct plot_figure *f, const char *path, char *err, size_t errlen)
{
    if (f->kind == PLOT_BARS) {
        if (f->nseries < 1 || f->nbars < 1 || (int)f->series[0].count != f->nbars) {
            snprintf(err, errlen, "%s: bar figure without values", path);
            return -1;
        }
        const char *labels[PLOT_MAX_BARS];
        for (int i = 0; i < f->nbars; i++) labels[i] = f->bar_labels[i];
        struct draw_bar_chart c;
        memset(&c, 0, sizeof c);
        c.title = f->title;
        c.x_label = f->x_label;
        c.nbars = f->nbars;
        c.labels = labels;
        c.values = f->series[0].y;
        if (f->nseries >= 3 && (int)f->series[1].count == f->nbars && (int)f->series[2].count == f->nbars) {
            c.err_lo = f->series[1].y;
            c.err_hi = f->series[2].y;
        }
        c.highlight = f->highlight;
        c.x_log = f->x_log;   /* the value axis; plots.json's x_log */
        if (draw_bar_chart(path, &c, err, errlen)) return -1;
        return plots_stamp_if_quick(path, 0, err, errlen);
    }
    struct draw_series s[PLOT_MAX_SERIES];
    for (int i = 0; i < f->nseries; i++) {
        s[i].x = f->series[i].x;
        s[i].y = f->series[i].y;
        s[i].count = (int)f->series[i].count;
        s[i].label = f->series[i].label[0] ? f->series[i].label : NULL;
        s[i].colour = f->series[i].colour;
        s[i].dashed = f->series[i].dashed;
        s[i].markers = f->series[i].markers;
    }
    const char *vl[PLOT_MAX_VLINES];
    for (int i = 0; i < f->nvlines; i++) vl[i] = f->vline_labels[i];
    struct draw_line_plot p;
    memset(&p, 0, sizeof p);
    p.title = f->title;
    p.x_label = f->x_label;
    p.y_label = f->y_label;
    p.x_log = f->x_log;
    p.y_log = f->y_log;
    p.x_min = f->x_min, p.x_max = f->x_max, p.y_min = f->y_min, p.y_max = f->y_max;
    p.y_format = f->y_format;
    p.nseries = f->nseries;
    p.series = s;
    p.nvlines = f->nvlines;
    p.vlines = f->vlines;
    p.vline_labels = vl;
    if (draw_line_plot(path, &p, err, errlen)) return -1;
    return plots_stamp_if_quick(path, 0, err, errlen);
}

int plots_draw(const struct plot_set *set, const char *dir, char *err, size_t errlen)
{
    int failed = 0;
    for (int i = 0; i < set->count; i++) {
        char path[4096], why[1024];
        if (path_join(path, sizeof path, dir, set->figs[i].file)) {
            snprintf(why, sizeof why, "%s/%s: path too long", dir, set->figs[i].file);
        } else if (plot_figure_draw(&set->figs[i], path, why, sizeof why) == 0) {
            continue;
        }
        if (!failed) snprintf(err, errlen, "%s", why);
        failed++;
    }
    return failed;
}

/* ---- plots.json ---------------------------------------------------------------------- */

static void jw_doubles(struct jw *w, const char *key, const double *v, size_t n)
{
    jw_kv_arr(w, key);
    /* 17 significant digits give back every double exactly: a redraw is the same picture. */
    for (size_t i = 0; i < n; i++) jw_numf(w, v[i], 17);
    jw_arr_end(w);
}

int plots_write_json(const struct plot_set *set, const char *path, const struct cl_session *s, char *err,
                     size_t errlen)
{
    struct jw w;
    jw_doc_begin(&w, PLOTS_SCHEMA, s, "");
    jw_obj_end(&w);
    jw_kv_arr(&w, "figures");
    for (int i = 0; i < set->count; i++) {
        const struct plot_figure *f = &set->figs[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "file", f->file);
        jw_kv_str(&w, "caption", f->caption);
        jw_kv_str(&w, "kind", f->kind == PLOT_BARS ? "bars" : "lines");
        jw_kv_str(&w, "title", f->title);
        jw_kv_str(&w, "x_label", f->x_label);
        jw_kv_str(&w, "y_label", f->y_label);
        jw_kv_bool(&w, "x_log", f->x_log);
        jw_kv_bool(&w, "y_log", f->y_log);
        jw_kv_str(&w, "y_format", f->y_format == 1 ? "percent" : "plain");
        jw_kv_arr(&w, "x_range");
        jw_num(&w, f->x_min);
        jw_num(&w, f->x_max);
        jw_arr_end(&w);
        jw_kv_arr(&w, "y_range");
        jw_num(&w, f->y_min);
        jw_num(&w, f->y_max);
        jw_arr_end(&w);
        jw_kv_arr(&w, "vlines");
        for (int v = 0; v < f->nvlines; v++) {
            jw_obj_begin(&w);
            jw_kv_num(&w, "x", f->vlines[v]);
            jw_kv_str(&w, "label", f->vline_labels[v]);
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        if (f->kind == PLOT_BARS) {
            jw_kv_arr(&w, "bar_labels");
            for (int b = 0; b < f->nbars; b++) jw_str(&w, f->bar_labels[b]);
            jw_arr_end(&w);
            jw_kv_int(&w, "highlight", f->highlight);
        }
        jw_kv_arr(&w, "series");
        for (int s = 0; s < f->nseries; s++) {
            const struct plot_series *se = &f->series[s];
            jw_obj_begin(&w);
            jw_kv_str(&w, "label", se->label);
            jw_kv_int(&w, "colour", se->colour);
            jw_kv_bool(&w, "dashed", se->dashed);
            jw_kv_bool(&w, "markers", se->markers);
            jw_doubles(&w, "x", se->x, se->count);
            jw_doubles(&w, "y", se->y, se->count);
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

static int need_bool(const struct jr_doc *d, const struct jr_value *o, const char *key, int *out, char *err,
                     size_t errlen)
{
    const struct jr_value *v;
    if (jr_need(d, o, key, JR_BOOL, &v, err, errlen)) return 2;
    *out = v->num != 0;
    return 0;
}

static int need_text(const struct jr_doc *d, const struct jr_value *o, const char *key, char *dst, size_t len,
                     char *err, size_t errlen)
{
    const char *s;
    if (jr_need_str(d, o, key, &s, err, errlen)) return 2;
    if (strlen(s) >= len) return jr_fail(d, jr_get(o, key), err, errlen, "\"%s\" is longer than %zu bytes", key, len - 1);
    snprintf(dst, len, "%s", s);
    return 0;
}

static int need_range(const struct jr_doc *d, const struct jr_value *o, const char *key, double *lo, double *hi,
                      char *err, size_t errlen)
{
    double *a = NULL;
    size_t n = 0;
    if (jr_need_num_array(d, o, key, &a, &n, err, errlen)) return 2;
    if (n != 2) {
        free(a);
        return jr_fail(d, jr_get(o, key), err, errlen, "\"%s\" must hold two numbers", key);
    }
    *lo = isfinite(a[0]) ? a[0] : 0;
    *hi = isfinite(a[1]) ? a[1] : 0;
    free(a);
    return 0;
}

int plot_file_name_ok(const char *name)
{
    size_t n = strlen(name);
    if (n <= 4 || n > 200 || name[0] == '.' || strcmp(name + n - 4, ".png") != 0)
        return 0;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)name[i];
        if (!(isalnum(c) || strchr("._-+=", c)))
            return 0;
    }
    return 1;
}

/* A range given in plots.json (hi > lo; otherwise the data's own range is drawn) must be one a
 * picture can show: its ends normal doubles, its width at least 1e-9 of its ends' size (and a
 * log range a ratio of at least 1 + 1e-9). A hand-edited [1, 1 + 1e-15] or [1e-300, 2e-300]
 * would put the data 1e15 to 1e300 pixels away. */
static int check_range(const struct jr_doc *d, const struct jr_value *o, const char *key, double lo, double hi,
                       int log_axis, char *err, size_t errlen)
{
    if (!(hi > lo))
        return 0;
    double big = fmax(fabs(lo), fabs(hi));
    int ok;
    if (log_axis)
        ok = lo >= 1e-300 && hi <= 1e300 && hi / lo >= 1 + 1e-9;
    else
        ok = big <= 1e300 && hi - lo >= 1e-200 && hi - lo >= 1e-9 * big;
    if (!ok)
        return jr_fail(d, jr_get(o, key), err, errlen,
                       "\"%s\" [%.16g, %.16g] cannot be drawn (accepted: ends within 1e+300 in size, a width of at "
                       "least 1e-200 and 1e-9 of the ends%s; or [0, 0] for the data's own range)",
                       key, lo, hi, log_axis ? ", positive ends with a ratio of at least 1 + 1e-9 on a log axis" : "");
    return 0;
}

static int read_figure(const struct jr_doc *d, const struct jr_value *o, struct plot_figure *f, char *err,
                       size_t errlen)
{
    char kind[16], fmt[16];
    if (need_text(d, o, "file", f->file, sizeof f->file, err, errlen) ||
        need_text(d, o, "caption", f->caption, sizeof f->caption, err, errlen) ||
        need_text(d, o, "kind", kind, sizeof kind, err, errlen) ||
        need_text(d, o, "title", f->title, sizeof f->title, err, errlen) ||
        need_text(d, o, "x_label", f->x_label, sizeof f->x_label, err, errlen) ||
        need_text(d, o, "y_label", f->y_label, sizeof f->y_label, err, errlen) ||
        need_bool(d, o, "x_log", &f->x_log, err, errlen) || need_bool(d, o, "y_log", &f->y_log, err, errlen) ||
        need_text(d, o, "y_format", fmt, sizeof fmt, err, errlen) ||
        need_range(d, o, "x_range", &f->x_min, &f->x_max, err, errlen) ||
        need_range(d, o, "y_range", &f->y_min, &f->y_max, err, errlen))
        return 2;
    /* a picture name is a plain NAME.png inside the run folder: no path, no data file of the
       run (accuracy.json, plots.json, report.md, field_*.json), no hidden or odd name */
    if (!plot_file_name_ok(f->file)) {
        char shown[128];   /* a control character in the name is shown as '?', so the message is one line */
        size_t k = 0;
        for (; f->file[k] && k < sizeof shown - 1; k++)
            shown[k] = (unsigned char)f->file[k] < 0x20 || f->file[k] == 0x7f ? '?' : f->file[k];
        shown[k] = '\0';
        return jr_fail(d, jr_get(o, "file"), err, errlen,
                       "\"file\" is \"%s\" (accepted: NAME.png, a plain file name of letters, digits and "
                       "._-+=, not starting with '.')", shown);
    }
    if (check_range(d, o, "x_range", f->x_min, f->x_max, f->x_log, err, errlen) ||
        check_range(d, o, "y_range", f->y_min, f->y_max, f->y_log, err, errlen))
        return 2;
    if (strcmp(kind, "lines") == 0) f->kind = PLOT_LINES;
    else if (strcmp(kind, "bars") == 0) f->kind = PLOT_BARS;
    else return jr_fail(d, jr_get(o, "kind"), err, errlen, "\"kind\" is \"%s\" (accepted: lines, bars)", kind);
    if (strcmp(fmt, "percent") == 0) f->y_format = 1;
    else if (strcmp(fmt, "plain") == 0) f->y_format = 0;
    else return jr_fail(d, jr_get(o, "y_format"), err, errlen, "\"y_format\" is \"%s\" (accepted: plain, percent)", fmt);
    const struct jr_value *vl, *series;
    if (jr_need(d, o, "vlines", JR_ARR, &vl, err, errlen)) return 2;
    if (vl->count > PLOT_MAX_VLINES) return jr_fail(d, vl, err, errlen, "more than %d vlines", PLOT_MAX_VLINES);
    for (size_t i = 0; i < vl->count; i++) {
        if (jr_need_num(d, &vl->items[i], "x", &f->vlines[i], err, errlen) ||
            need_text(d, &vl->items[i], "label", f->vline_labels[i], sizeof f->vline_labels[i], err, errlen))
            return 2;
        f->nvlines++;
    }
    if (f->kind == PLOT_BARS) {
        const struct jr_value *bl;
        double hl;
        if (jr_need(d, o, "bar_labels", JR_ARR, &bl, err, errlen) || jr_need_num(d, o, "highlight", &hl, err, errlen))
            return 2;
        if (bl->count < 1 || bl->count > PLOT_MAX_BARS)
            return jr_fail(d, bl, err, errlen, "\"bar_labels\" must hold 1 to %d names", PLOT_MAX_BARS);
        for (size_t i = 0; i < bl->count; i++) {
            if (bl->items[i].type != JR_STR) return jr_fail(d, &bl->items[i], err, errlen, "a bar label must be a string");
            set_text(f->bar_labels[i], sizeof f->bar_labels[i], bl->items[i].str);
        }
        f->nbars = (int)bl->count;
        f->highlight = (hl >= 0 && hl < f->nbars && hl == floor(hl)) ? (int)hl : -1;
    }
    if (jr_need(d, o, "series", JR_ARR, &series, err, errlen)) return 2;
    if (series->count > PLOT_MAX_SERIES) return jr_fail(d, series, err, errlen, "more than %d series", PLOT_MAX_SERIES);
    for (size_t i = 0; i < series->count; i++) {
        const struct jr_value *so = &series->items[i];
        struct plot_series *s = &f->series[f->nseries];
        double colour;
        size_t nx = 0, ny = 0;
        memset(s, 0, sizeof *s);
        if (need_text(d, so, "label", s->label, sizeof s->label, err, errlen) ||
            jr_need_num(d, so, "colour", &colour, err, errlen) || need_bool(d, so, "dashed", &s->dashed, err, errlen) ||
            need_bool(d, so, "markers", &s->markers, err, errlen))
            return 2;
        if (!(colour >= -1 && colour <= 9 && colour == floor(colour)))
            return jr_fail(d, jr_get(so, "colour"), err, errlen, "\"colour\" must be an integer in [-1, 9]");
        s->colour = (int)colour;
        if (jr_need_num_array(d, so, "x", &s->x, &nx, err, errlen)) return 2;
        f->nseries++; /* owned from here on, freed with the figure */
        if (jr_need_num_array(d, so, "y", &s->y, &ny, err, errlen)) return 2;
        if (nx != ny) return jr_fail(d, so, err, errlen, "series \"%s\" has %zu x and %zu y values", s->label, nx, ny);
        s->count = nx;
    }
    if (f->kind == PLOT_BARS && (f->nseries < 1 || (int)f->series[0].count != f->nbars))
        return jr_fail(d, o, err, errlen, "a bar figure needs one value per bar label");
    return 0;
}

int plots_read_json(const char *path, struct plot_set *set, char *err, size_t errlen)
{
    struct jr_doc d;
    plots_init(set);
    if (jr_parse_file(path, &d, err, errlen)) return 2;
    const char *schema;
    const struct jr_value *figs;
    int rc = 2;
    if (jr_need_str(&d, &d.root, "schema", &schema, err, errlen)) goto done;
    if (strcmp(schema, PLOTS_SCHEMA) != 0) {
        jr_fail(&d, jr_get(&d.root, "schema"), err, errlen, "schema \"%s\", expected \"%s\"", schema, PLOTS_SCHEMA);
        goto done;
    }
    if (jr_need(&d, &d.root, "figures", JR_ARR, &figs, err, errlen)) goto done;
    for (size_t i = 0; i < figs->count; i++) {
        struct plot_figure *f = plots_add(set, PLOT_LINES, "", "");
        if (!f) {
            jr_fail(&d, figs, err, errlen, "out of memory");
            goto done;
        }
        if (read_figure(&d, &figs->items[i], f, err, errlen)) goto done;
        for (int k = 0; k < set->count - 1; k++)
            if (strcmp(set->figs[k].file, f->file) == 0) {
                jr_fail(&d, jr_get(&figs->items[i], "file"), err, errlen,
                        "figure %zu has the file name \"%s\" of figure %d (each figure needs its own file)", i + 1,
                        f->file, k + 1);
                goto done;
            }
    }
    rc = 0;
done:
    jr_free(&d);
    if (rc) plots_free(set);
    return rc;
}
