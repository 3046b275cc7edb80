/* compare.c - reads the runs that `brdfbench compare` is given, matches their rows by key and
 * decides each cell's verdict against the baseline (see compare.h); compare_report.c writes. */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"
#include "compare_check.h"
#include "jsonr.h"
#include "outdir.h"
#include "ranktest.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *const kind_names[CMP_KIND_COUNT] = { "throughput", "accuracy", "render", "fit", "frontier" };
static const char *const kind_files[CMP_KIND_COUNT] = { "throughput.json", "accuracy.json", "render.json", "fit.json",
                                                        "frontier.json" };
static const char *const kind_schemas[CMP_KIND_COUNT] = { THROUGHPUT_SCHEMA, ACCURACY_SCHEMA, RENDER_SCHEMA, FIT_SCHEMA,
                                                          FRONTIER_SCHEMA };

const char *cmp_kind_name(int k) { return k >= 0 && k < CMP_KIND_COUNT ? kind_names[k] : "?"; }

const char *cmp_verdict_name(int v)
{
    switch (v) {
    case CMP_V_NONE: return "";
    case CMP_V_MISSING: return "missing";
    case CMP_V_FAILED: return "failed";
    case CMP_V_SAME: return "same";
    case CMP_V_FASTER: return "faster";
    case CMP_V_SLOWER: return "slower";
    case CMP_V_UNDECIDED: return "undecided";
    case CMP_V_UNCHANGED: return "unchanged";
    case CMP_V_BETTER: return "changed, better";
    case CMP_V_WORSE: return "changed, worse";
    case CMP_V_CHANGED: return "changed";
    case CMP_V_NOISY: return "noisy";
    }
    return "?";
}

static void fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* ---- rows ------------------------------------------------------------------------------ */

/* Where a file's figures go while it is read. */
struct cmp_reader {
    struct compare_set *set;
    int run;
    int kind;
    int oom;
    char dup[CMP_TEXT + 80];   /* the first key given twice in the file, or "" */
};

static struct cmp_cell *cell_for(struct cmp_reader *rd, const char *device, const char *key, const char *model,
                                 const char *metric, int sense)
{
    struct compare_set *set = rd->set;
    for (int i = 0; i < set->nrows; ++i) {
        struct cmp_row *r = &set->rows[i];
        if (r->kind == rd->kind && strcmp(r->device, device) == 0 && strcmp(r->key, key) == 0 &&
            strcmp(r->metric, metric) == 0)
            return &r->cell[rd->run];
    }
    if (set->nrows == set->cap) {
        int cap = set->cap ? 2 * set->cap : 64;
        struct cmp_row *nr = realloc(set->rows, (size_t)cap * sizeof *nr);
        if (!nr) {
            rd->oom = 1;
            return NULL;
        }
        set->rows = nr;
        set->cap = cap;
    }
    struct cmp_row *r = &set->rows[set->nrows++];
    memset(r, 0, sizeof *r);
    r->kind = rd->kind;
    r->sense = sense;
    snprintf(r->device, sizeof r->device, "%s", device);
    snprintf(r->key, sizeof r->key, "%s", key);
    snprintf(r->model, sizeof r->model, "%s", model);
    snprintf(r->metric, sizeof r->metric, "%s", metric);
    return &r->cell[rd->run];
}

/* The array of numbers at obj's key as c's repetitions (the rank test's sample), unless c has
 * them already; 0, or 2 with err when the array is not numbers. */
static int take_reps(const struct jr_doc *d, const struct jr_value *obj, const char *key, struct cmp_cell *c,
                     char *err, size_t errlen)
{
    double *reps = NULL;
    size_t n = 0;
    if (jr_need_num_array(d, obj, key, &reps, &n, err, errlen))
        return 2;
    if (!c->reps && n > 0) {
        c->reps = reps;
        c->nreps = (int)n;
    } else {
        free(reps);
    }
    return 0;
}

static struct cmp_cell *put_value(struct cmp_reader *rd, const char *device, const char *key, const char *model,
                                  const char *metric, int sense, double v, const char *reason)
{
    struct cmp_cell *c = cell_for(rd, device, key, model, metric, sense);
    if (c && c->present && !rd->dup[0])
        snprintf(rd->dup, sizeof rd->dup, "%s%s%.200s (%s)", device, *device ? " | " : "", key, metric);
    if (!c || c->present)
        return NULL;
    c->present = 1;
    c->ok = isfinite(v) && !(reason && *reason);
    c->value = v;
    c->lo = c->hi = NAN;
    if (!c->ok)
        snprintf(c->reason, sizeof c->reason, "%s", reason && *reason ? reason : "not a finite number");
    return c;
}

static const char *str_member(const struct jr_value *obj, const char *key, const char *dflt)
{
    const struct jr_value *v = jr_get(obj, key);
    return v && v->type == JR_STR ? v->str : dflt;
}

static double num_member(const struct jr_value *obj, const char *key)
{
    const struct jr_value *v = jr_get(obj, key);
    return v && v->type == JR_NUM ? v->num : NAN;
}

/* A dotted path of object members ("epicentre.max_rel"), or NULL. */
static const struct jr_value *path_get(const struct jr_value *obj, const char *path)
{
    char buf[128];
    snprintf(buf, sizeof buf, "%s", path);
    const struct jr_value *v = obj;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ".", &save); tok && v; tok = strtok_r(NULL, ".", &save))
        v = jr_get(v, tok);
    return v;
}

static void ctx_put(struct cmp_run *run, const char *key, const char *value)
{
    for (int i = 0; i < run->nctx; ++i)
        if (strcmp(run->ctx_key[i], key) == 0)
            return;   /* the first file that names it wins */
    if (run->nctx == CMP_MAX_CTX || !value)
        return;
    snprintf(run->ctx_key[run->nctx], sizeof run->ctx_key[0], "%s", key);
    snprintf(run->ctx_value[run->nctx], sizeof run->ctx_value[0], "%s", value);
    run->nctx++;
}

/* The context block's plain members, as text. */
static void read_context(struct cmp_run *run, const struct jr_value *ctx)
{
    static const char *const keys[] = { "device", "platform", "platform_version", "device_version", "driver_version",
                                        "compute_units", "host_cpu", "host_cores", "git_revision", "brdfbench_version",
                                        "build_options", "pocl_affinity", "date" };
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i) {
        const struct jr_value *v = jr_get(ctx, keys[i]);
        char buf[64];
        if (!v)
            continue;
        if (v->type == JR_STR)
            ctx_put(run, keys[i], v->str);
        else if (v->type == JR_NUM) {
            snprintf(buf, sizeof buf, "%.10g", v->num);
            ctx_put(run, keys[i], buf);
        }
    }
}

/* "n 2..1000 step 1, 4096 samples per zone" from a context's grid, or "". */
static void grid_text(const struct jr_value *ctx, char *out, size_t len)
{
    const struct jr_value *g = jr_get(ctx, "grid");
    out[0] = '\0';
    if (!g)
        return;
    snprintf(out, len, "n %g..%g step %g, %g samples per zone", num_member(g, "n_min"), num_member(g, "n_max"),
             num_member(g, "n_step"), num_member(g, "samples_per_zone"));
}

/* Rows of a file that name their device: the tag is kept in the key only when the file holds
   more than one device (a --device all run); one device is the context's. */
static int distinct_devices(const struct jr_value *rows, const char *member)
{
    const char *first = NULL;
    for (size_t i = 0; rows && i < rows->count; ++i) {
        const char *d = str_member(&rows->items[i], member, NULL);
        if (!d)
            continue;
        if (!first)
            first = d;
        else if (strcmp(first, d) != 0)
            return 2;
    }
    return first ? 1 : 0;
}

/* ---- the files ------------------------------------------------------------------------- */

/* A throughput context block's settings and machine record, as context lines of run. */
static void throughput_context(struct cmp_run *run, const struct jr_value *tp, int *disturbed)
{
    char buf[CMP_TEXT];
    snprintf(buf, sizeof buf, "%g reps, min time %g s, %g work-items, n %g, n range %g:%g", num_member(tp, "reps"),
             num_member(tp, "min_time_s"), num_member(tp, "work_items"), num_member(tp, "n_uniform"),
             num_member(tp, "n_lo"), num_member(tp, "n_hi"));
    ctx_put(run, "throughput settings", buf);
    const struct jr_value *rn = jr_get(tp, "runner");
    snprintf(buf, sizeof buf, "load %s -> %s", str_member(tp, "loadavg_start", "?"), str_member(tp, "loadavg_end", "?"));
    if (rn)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), ", steal %.3g s, %g of %g launches retried, %g reps disturbed",
                 num_member(rn, "steal_seconds"), num_member(rn, "preemption_retries"), num_member(rn, "launches"),
                 num_member(rn, "disturbed_reps"));
    ctx_put(run, "machine", buf);
    if (disturbed && rn && num_member(rn, "disturbed_reps") > 0)
        *disturbed = (int)num_member(rn, "disturbed_reps");
}

/* A run's measured peak (its reference kernel) as a speed row of its own. */
static int put_peak(struct cmp_reader *rd, const struct jr_doc *d, const char *device, const struct jr_value *pk,
                    char *err, size_t errlen)
{
    if (!pk || pk->type != JR_OBJ)
        return 0;
    const struct jr_value *f = jr_get(pk, "flops_per_s");
    int ok = strcmp(str_member(pk, "status", "ok"), "ok") == 0;
    struct cmp_cell *c = put_value(rd, device, "peak (reference kernel)", "peak", "flops_per_s", CMP_SPEED,
                                   num_member(f, "median"), ok ? NULL : str_member(pk, "reason", "failed"));
    if (!c)
        return 0;
    c->lo = num_member(f, "min");
    c->hi = num_member(f, "max");
    return jr_get(pk, "flops_per_s_reps") ? take_reps(d, pk, "flops_per_s_reps", c, err, errlen) : 0;
}

static int read_throughput(struct cmp_reader *rd, const struct jr_doc *d, char *err, size_t errlen)
{
    const struct jr_value *rows;
    if (jr_need(d, &d->root, "results", JR_ARR, &rows, err, errlen))
        return 2;
    const struct jr_value *ctx = jr_get(&d->root, "context"), *tp = jr_get(ctx, "throughput");
    const struct jr_value *devs = jr_get(ctx, "devices");
    int several = devs && devs->type == JR_ARR && devs->count > 1;
    if (several) {
        for (size_t i = 0; i < devs->count; ++i) {
            const struct jr_value *dv = &devs->items[i];
            const char *tag = str_member(dv, "tag", str_member(dv, "device", "?"));
            if (put_peak(rd, d, tag, jr_get(dv, "peak"), err, errlen))
                return 2;
            for (int j = 0; j < rd->set->ndevices; ++j)
                if (strcmp(rd->set->devices[j].name, tag) == 0 && jr_get(dv, "throughput"))
                    throughput_context(&rd->set->devices[j], jr_get(dv, "throughput"), NULL);
        }
    } else if (put_peak(rd, d, "", jr_get(&d->root, "peak"), err, errlen)) {
        return 2;
    }
    if (tp) {
        char buf[CMP_TEXT];
        throughput_context(&rd->set->run[rd->run], tp, &rd->set->run[rd->run].disturbed);
        const struct jr_value *fp = jr_get(tp, "kernel_sources_fnv1a64");
        buf[0] = '\0';
        for (size_t i = 0; fp && fp->type == JR_OBJ && i < fp->count; ++i)
            if (fp->items[i].type == JR_STR)
                snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s %.8s", i ? ", " : "", fp->keys[i],
                         fp->items[i].str);
        if (buf[0])
            ctx_put(&rd->set->run[rd->run], "kernel sources", buf);
    }
    int tagged = distinct_devices(rows, "device") > 1;
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        const char *label, *variant, *mode;
        if (jr_need_str(d, row, "label", &label, err, errlen) || jr_need_str(d, row, "variant", &variant, err, errlen) ||
            jr_need_str(d, row, "n_mode", &mode, err, errlen))
            return 2;
        const char *status = str_member(row, "status", "ok");
        char key[CMP_TEXT];
        snprintf(key, sizeof key, "%s | %s | n %s", label, variant, mode);
        const struct jr_value *eps = jr_get(row, "evals_per_s");
        double med = num_member(eps, "median");
        int ok = strcmp(status, "ok") == 0;
        struct cmp_cell *c = put_value(rd, tagged ? str_member(row, "device", "") : "", key, label, "evals_per_s",
                                       CMP_SPEED, med, ok ? NULL : str_member(row, "reason", status));
        if (!c)
            continue;
        c->lo = num_member(eps, "min");
        c->hi = num_member(eps, "max");
        if (take_reps(d, row, "evals_per_s_reps", c, err, errlen))
            return 2;
        /* the normalised rates per CPU second where the run has them (a CPU device), else the
           normalised rates */
        static const char *const norm_keys[2] = { "normalised_cpu_reps", "normalised_reps" };
        for (int q = 0; q < 2 && !c->norm; ++q) {
            if (!jr_get(row, norm_keys[q]))
                continue;
            double *nr = NULL;
            size_t nn = 0;
            if (jr_need_num_array(d, row, norm_keys[q], &nr, &nn, err, errlen))
                return 2;
            if (nn > 0) {
                c->norm = nr;
                c->nnorm = (int)nn;
                c->norm_cpu = q == 0;
            } else {
                free(nr);
            }
        }
        c->retries = (int)fmax(0, num_member(row, "preemption_retries"));
        c->disturbed = (int)fmax(0, num_member(row, "disturbed_reps"));
    }
    return 0;
}

static int read_accuracy(struct cmp_reader *rd, const struct jr_doc *d, char *err, size_t errlen)
{
    static const char *const figures[] = { "epicentre.max_rel", "attenuation.max_abs", "whole.max_abs" };
    const struct jr_value *rows;
    if (jr_need(d, &d->root, "results", JR_ARR, &rows, err, errlen))
        return 2;
    char grid[CMP_TEXT];
    grid_text(jr_get(&d->root, "context"), grid, sizeof grid);
    ctx_put(&rd->set->run[rd->run], "accuracy grid", grid);
    int tagged = distinct_devices(rows, "device") > 1;
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        const char *label;
        if (jr_need_str(d, row, "label", &label, err, errlen))
            return 2;
        const char *status = str_member(row, "status", "ok");
        char key[CMP_TEXT];
        snprintf(key, sizeof key, "%.120s | %.120s", label, grid);
        for (size_t f = 0; f < sizeof figures / sizeof figures[0]; ++f) {
            const struct jr_value *v = path_get(row, figures[f]);
            double x = v && v->type == JR_NUM ? v->num : NAN;
            put_value(rd, tagged ? str_member(row, "device", "") : "", key, label, figures[f], CMP_ERROR, x,
                      strcmp(status, "ok") == 0 ? NULL : str_member(row, "reason", status));
        }
    }
    return 0;
}

static int read_render(struct cmp_reader *rd, const struct jr_doc *d, char *err, size_t errlen)
{
    static const struct { const char *name; int sense; } metrics[] = {
        { "max_abs", CMP_ERROR }, { "rmse", CMP_ERROR }, { "psnr_db", CMP_SCORE } };
    const struct jr_value *scenes;
    if (jr_need(d, &d->root, "scenes", JR_ARR, &scenes, err, errlen))
        return 2;
    int tagged = distinct_devices(scenes, "device") > 1;     /* a --device all run tags its scenes */
    for (size_t i = 0; i < scenes->count; ++i) {
        const struct jr_value *sc = &scenes->items[i];
        const char *scene;
        if (jr_need_str(d, sc, "scene", &scene, err, errlen))
            return 2;
        const char *sdev = tagged ? str_member(sc, "device", "") : "";
        const struct jr_value *img = jr_get(sc, "image"), *models = jr_get(sc, "models"), *timings = jr_get(sc, "timings");
        char key[CMP_TEXT];
        for (size_t m = 0; models && m < models->count; ++m) {
            const struct jr_value *mo = &models->items[m];
            const char *model = str_member(mo, "model", "?");
            const struct jr_value *met = jr_get(mo, "metrics");
            const char *status = str_member(met, "status", "ok");
            const char *reason = strcmp(status, "ok") == 0 ? NULL : str_member(met, "reason", status);
            snprintf(key, sizeof key, "%s %gx%g | %s", scene, num_member(img, "width"), num_member(img, "height"), model);
            for (size_t k = 0; met && k < sizeof metrics / sizeof metrics[0]; ++k) {
                double v = num_member(met, metrics[k].name);
                if (!isfinite(v) && !reason)
                    continue;   /* a PSNR of identical images is null (infinite): nothing to compare */
                put_value(rd, sdev, key, model, metrics[k].name, metrics[k].sense, v, reason);
            }
        }
        for (size_t t = 0; timings && t < timings->count; ++t) {
            const struct jr_value *tm = &timings->items[t], *entries = jr_get(tm, "entries");
            char metric[64];
            snprintf(metric, sizeof metric, "mpixel_per_s@%gx%g", num_member(tm, "width"), num_member(tm, "height"));
            for (size_t e = 0; entries && e < entries->count; ++e) {
                const struct jr_value *en = &entries->items[e];
                const char *name = str_member(en, "name", str_member(en, "model", "?"));
                snprintf(key, sizeof key, "%s | %s", scene, name);
                double v = num_member(en, "mpixel_per_s"), med = num_member(en, "median_ms");
                struct cmp_cell *c = put_value(rd, sdev, key, str_member(en, "model", name), metric, CMP_SPEED, v,
                                               str_member(en, "reason", NULL));
                if (c && c->ok) {
                    /* Mpixel/s is inversely proportional to the time: the slowest run gives lo */
                    c->lo = v * med / num_member(en, "max_ms");
                    c->hi = v * med / num_member(en, "min_ms");
                    /* the launches' own rates, for the rank test (an older render.json without
                       them is compared by its min..max range) */
                    if (jr_get(en, "mpixel_per_s_reps") && take_reps(d, en, "mpixel_per_s_reps", c, err, errlen))
                        return 2;
                }
            }
        }
    }
    return 0;
}

static void put_fit_figures(struct cmp_reader *rd, const struct jr_value *obj, const char *key, int with_coefs)
{
    static const char *const errs[] = { "max_rel", "max_abs" };
    static const char *const coefs[] = { "a", "b" };
    const char *status = str_member(obj, "status", "ok");
    const char *reason = strcmp(status, "ok") == 0 ? NULL : str_member(obj, "reason", status);
    for (int k = 0; with_coefs && k < 2; ++k)
        put_value(rd, "", key, "fit", coefs[k], CMP_VALUE, num_member(obj, coefs[k]), reason);
    for (int k = 0; k < 2; ++k)
        put_value(rd, "", key, "fit", errs[k], CMP_ERROR, num_member(obj, errs[k]), reason);
}

static int read_fit(struct cmp_reader *rd, const struct jr_doc *d, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    char grid[CMP_TEXT], key[CMP_TEXT];
    grid_text(jr_get(&d->root, "context"), grid, sizeof grid);
    ctx_put(&rd->set->run[rd->run], "fit grid", grid);
    snprintf(key, sizeof key, "best affine k(n) | %.200s", grid);
    put_fit_figures(rd, &d->root, key, 1);
    const struct jr_value *capped = jr_get(&d->root, "capped_at_fq2");
    if (capped && capped->type == JR_OBJ) {
        snprintf(key, sizeof key, "capped at fq2's max Delta | %.200s", grid);
        put_fit_figures(rd, capped, key, 1);
    }
    const struct jr_value *cmp = jr_get(&d->root, "compare");
    for (size_t i = 0; cmp && cmp->type == JR_ARR && i < cmp->count; ++i) {
        const char *model = str_member(&cmp->items[i], "model", "?");
        if (strncmp(model, "quad:", 5) == 0)
            continue;   /* the fitted model itself: its label moves with its coefficients */
        snprintf(key, sizeof key, "%.120s | %.120s", model, grid);
        put_fit_figures(rd, &cmp->items[i], key, 0);
    }
    return 0;
}

/* frontier.json: rows keyed by model; every number of a row (and of its objects, one level
   down) whose name says what it is: a rate (per_s; an object of min/median/max gives its
   median and range) is a speed, psnr a score, max_rel/max_abs/rmse an error. */
static int frontier_sense(const char *name)
{
    if (strstr(name, "per_s"))
        return CMP_SPEED;
    if (strstr(name, "psnr"))
        return CMP_SCORE;
    if (strstr(name, "max_rel") || strstr(name, "max_abs") || strstr(name, "rmse"))
        return CMP_ERROR;
    return -1;
}

static void frontier_members(struct cmp_reader *rd, const struct jr_doc *d, const struct jr_value *obj,
                             const char *prefix, const char *model, const char *dev, int depth)
{
    for (size_t k = 0; k < obj->count; ++k) {
        const struct jr_value *v = &obj->items[k];
        char name[64];
        snprintf(name, sizeof name, "%s%s%s", prefix, *prefix ? "." : "", obj->keys[k]);
        int sense = frontier_sense(name);
        if (v->type == JR_OBJ && sense == CMP_SPEED && jr_get(v, "median")) {
            struct cmp_cell *c = put_value(rd, dev, model, model, name, sense, num_member(v, "median"), NULL);
            if (c) {
                c->lo = num_member(v, "min");
                c->hi = num_member(v, "max");
            }
        } else if (v->type == JR_OBJ && depth < 1) {
            frontier_members(rd, d, v, name, model, dev, depth + 1);
        } else if ((v->type == JR_NUM || v->type == JR_NULL) && sense >= 0 && !strstr(name, "_at")) {
            put_value(rd, dev, model, model, name, sense, v->type == JR_NUM ? v->num : NAN, NULL);
        } else if (v->type == JR_ARR && sense == CMP_SPEED && strstr(name, "_reps")) {
            /* the repetitions of the rate named without _reps */
            char base[64];
            snprintf(base, sizeof base, "%.*s", (int)(strstr(name, "_reps") - name), name);
            struct cmp_cell *c = cell_for(rd, dev, model, model, base, CMP_SPEED);
            char e[8];   /* a frontier file's array that is not numbers is left out, as before */
            if (c)
                take_reps(d, obj, obj->keys[k], c, e, sizeof e);
        }
    }
}

static int read_frontier(struct cmp_reader *rd, const struct jr_doc *d, char *err, size_t errlen)
{
    static const char *const arrays[] = { "results", "models", "points", "rows" };
    const struct jr_value *rows = NULL;
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0] && !rows; ++i) {
        const struct jr_value *v = jr_get(&d->root, arrays[i]);
        if (v && v->type == JR_ARR)
            rows = v;
    }
    if (!rows) {
        fail(err, errlen, "%s: no array of rows (results, models, points or rows)", d->name);
        return 2;
    }
    int tagged = distinct_devices(rows, "device") > 1;
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        if (row->type != JR_OBJ)
            continue;
        const char *model = str_member(row, "model", str_member(row, "label", NULL));
        if (!model) {
            fail(err, errlen, "%s:%d:%d: a row without \"model\" or \"label\"", d->name, row->line, row->col);
            return 2;
        }
        frontier_members(rd, d, row, "", model, tagged ? str_member(row, "device", "") : "", 0);
    }
    return 0;
}

typedef int (*reader_fn)(struct cmp_reader *, const struct jr_doc *, char *, size_t);
static const reader_fn readers[CMP_KIND_COUNT] = { read_throughput, read_accuracy, read_render, read_fit,
                                                   read_frontier };

/* The kind a schema string names ("brdfbench.fit/1" -> CMP_FIT), or -1. */
static int kind_of_schema(const char *schema)
{
    for (int k = 0; k < CMP_KIND_COUNT; ++k) {
        size_t n = strchr(kind_schemas[k], '/') - kind_schemas[k] + 1;
        if (strncmp(schema, kind_schemas[k], n) == 0)
            return k;
    }
    return -1;
}

static int read_file(struct compare_set *set, int run, const char *path, char *err, size_t errlen)
{
    struct jr_doc d;
    if (jr_parse_file(path, &d, err, errlen))
        return 2;
    int rc = 2;
    const char *schema;
    if (jr_need_str(&d, &d.root, "schema", &schema, err, errlen))
        goto done;
    int kind = kind_of_schema(schema);
    if (kind < 0) {
        fail(err, errlen, "%s: schema \"%s\" is not one compare reads (%s, %s, %s, %s, %s)", path, schema,
             kind_schemas[0], kind_schemas[1], kind_schemas[2], kind_schemas[3], kind_schemas[4]);
        goto done;
    }
    /* throughput/2 files (no normalised rates) are still compared, on their absolute rates */
    if (strcmp(schema, kind_schemas[kind]) != 0 && strcmp(schema, THROUGHPUT_SCHEMA_V2) != 0) {
        fail(err, errlen, "%s: schema \"%s\", compare reads \"%s\" (run the command again with this version)", path,
             schema, kind_schemas[kind]);
        goto done;
    }
    struct cmp_run *r = &set->run[run];
    const struct jr_value *ctx = jr_get(&d.root, "context");
    if (ctx)
        read_context(r, ctx);
    const struct jr_value *devices = jr_get(ctx, "devices");
    if (devices && devices->type == JR_ARR && devices->count > 1) {
        char all[CMP_TEXT] = "";
        for (size_t i = 0; i < devices->count; ++i) {
            const struct jr_value *dv = &devices->items[i];
            const char *tag = str_member(dv, "tag", str_member(dv, "device", "?"));
            snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", i ? "; " : "", tag);
            int known = 0;
            for (int j = 0; j < set->ndevices; ++j)
                known |= strcmp(set->devices[j].name, tag) == 0;
            if (!known && set->ndevices < CMP_MAX_RUNS) {
                struct cmp_run *dr = &set->devices[set->ndevices++];
                snprintf(dr->name, sizeof dr->name, "%s", tag);
                read_context(dr, dv);
            }
        }
        ctx_put(r, "devices", all);
    }
    snprintf(r->files + strlen(r->files), sizeof r->files - strlen(r->files), "%s%s", r->files[0] ? ", " : "",
             kind_files[kind]);
    if (compare_check_doc(&d, err, errlen))
        goto done;
    struct cmp_reader rd = { .set = set, .run = run, .kind = kind };
    rc = readers[kind](&rd, &d, err, errlen);
    if (!rc && rd.oom) {
        fail(err, errlen, "out of memory reading %s", path);
        rc = 2;
    } else if (!rc && rd.dup[0]) {
        fail(err, errlen, "%s: the row %s appears twice (accepted: one row per key, as brdfbench writes it)", path,
             rd.dup);
        rc = 2;
    }
done:
    jr_free(&d);
    return rc;
}

static int read_run(struct compare_set *set, int run, const char *path, char *err, size_t errlen)
{
    struct cmp_run *r = &set->run[run];
    snprintf(r->path, sizeof r->path, "%s", path);
    /* the heading: the last path component (a file: its folder's name too) */
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", path);
    size_t n = strlen(buf);
    while (n > 1 && buf[n - 1] == '/')
        buf[--n] = '\0';
    struct stat st;
    if (stat(path, &st) != 0) {
        fail(err, errlen, "%s: %s", path, strerror(errno));
        return 2;
    }
    const char *base = strrchr(buf, '/');
    snprintf(r->name, sizeof r->name, "%s", base ? base + 1 : buf);
    if (!S_ISDIR(st.st_mode))
        return read_file(set, run, path, err, errlen);
    int found = 0;
    for (int k = 0; k < CMP_KIND_COUNT; ++k) {
        char file[4200];
        if (path_join(file, sizeof file, path, kind_files[k]))
            continue;
        if (stat(file, &st) != 0)
            continue;
        int rc = read_file(set, run, file, err, errlen);
        if (rc)
            return rc;
        ++found;
    }
    if (!found) {
        fail(err, errlen, "%s: no result file (%s, %s, %s, %s or %s)", path, kind_files[0], kind_files[1],
             kind_files[2], kind_files[3], kind_files[4]);
        return 2;
    }
    return 0;
}

/* One run whose rows name several devices becomes one column per device. */
static void split_devices(struct compare_set *set)
{
    char devs[CMP_MAX_RUNS][CMP_TEXT];
    int ndev = 0;
    for (int i = 0; i < set->nrows; ++i) {
        const char *d = set->rows[i].device;
        if (!*d)
            continue;
        int k = 0;
        while (k < ndev && strcmp(devs[k], d) != 0)
            ++k;
        if (k == ndev && ndev < CMP_MAX_RUNS)
            snprintf(devs[ndev++], sizeof devs[0], "%s", d);
    }
    if (ndev < 2)
        return;
    set->by_device = 1;
    for (int k = ndev - 1; k >= 0; --k) {
        set->run[k] = set->run[0];
        snprintf(set->run[k].name, sizeof set->run[k].name, "%s", devs[k]);
    }
    set->nruns = ndev;
    /* each column's device context from the file's list of devices */
    for (int k = 0; k < ndev; ++k)
        for (int c = 0; c < set->run[k].nctx; ++c) {
            const char *v = NULL;
            for (int j = 0; j < set->ndevices && !v; ++j)
                if (strcmp(set->devices[j].name, devs[k]) == 0)
                    for (int m = 0; m < set->devices[j].nctx && !v; ++m)
                        if (strcmp(set->devices[j].ctx_key[m], set->run[k].ctx_key[c]) == 0)
                            v = set->devices[j].ctx_value[m];
            if (strcmp(set->run[k].ctx_key[c], "device") == 0)
                v = devs[k];
            if (v)
                snprintf(set->run[k].ctx_value[c], sizeof set->run[k].ctx_value[c], "%.250s", v);
        }
    /* rows of device k move to column k of the row with the same key and no device */
    int n = set->nrows;
    for (int i = 0; i < n; ++i) {
        struct cmp_row *r = &set->rows[i];
        if (!*r->device)
            continue;
        int k = 0;
        while (k < ndev && strcmp(devs[k], r->device) != 0)
            ++k;
        if (k == ndev)
            continue;
        struct cmp_reader rd = { .set = set, .run = k, .kind = r->kind };
        struct cmp_cell moved = r->cell[0];
        memset(&r->cell[0], 0, sizeof r->cell[0]);
        char key[CMP_TEXT], model[CMP_TEXT], metric[64];
        int sense = r->sense;
        snprintf(key, sizeof key, "%s", r->key);
        snprintf(model, sizeof model, "%s", r->model);
        snprintf(metric, sizeof metric, "%s", r->metric);
        struct cmp_cell *c = cell_for(&rd, "", key, model, metric, sense);   /* may move set->rows */
        if (c) {
            *c = moved;
        } else {
            free(moved.reps);
            free(moved.norm);
        }
    }
    /* drop the emptied device rows */
    int w = 0;
    for (int i = 0; i < set->nrows; ++i)
        if (!*set->rows[i].device)
            set->rows[w++] = set->rows[i];
    set->nrows = w;
}

int compare_load(struct compare_set *set, const char *const *paths, int npaths, char *err, size_t errlen)
{
    memset(set, 0, sizeof *set);
    set->alpha = CMP_DEFAULT_ALPHA;
    set->threshold = CMP_DEFAULT_THRESHOLD;
    set->min_reps = CMP_WARN_REPS;
    if (npaths < 1 || npaths > CMP_MAX_RUNS) {
        fail(err, errlen, "expected 1 to %d runs (the first is the baseline), got %d", CMP_MAX_RUNS, npaths);
        return 2;
    }
    set->nruns = npaths;
    for (int i = 0; i < npaths; ++i) {
        int rc = read_run(set, i, paths[i], err, errlen);
        if (rc)
            return rc;
    }
    if (npaths == 1) {
        split_devices(set);
        if (!set->by_device) {
            fail(err, errlen, "%s: one run holds one device; give a second run to compare with (or a run of "
                              "--device all)", paths[0]);
            return 2;
        }
    }
    /* something in common: a row of the baseline in at least one other run */
    int common = 0;
    for (int i = 0; i < set->nrows && !common; ++i)
        for (int k = 1; k < set->nruns; ++k)
            common |= set->rows[i].cell[0].present && set->rows[i].cell[k].present;
    if (!common) {
        fail(err, errlen, "%s and %s have no row in common (files: %s / %s)", set->run[0].name,
             set->nruns > 1 ? set->run[1].name : "?", set->run[0].files, set->nruns > 1 ? set->run[1].files : "");
        return 2;
    }
    return 0;
}

const char *compare_context(const struct compare_set *set, int r, const char *key)
{
    for (int i = 0; i < set->run[r].nctx; ++i)
        if (strcmp(set->run[r].ctx_key[i], key) == 0)
            return set->run[r].ctx_value[i];
    return NULL;
}

