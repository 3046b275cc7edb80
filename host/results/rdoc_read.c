/* rdoc_read.c - each kind's result file as rows. A file of the version written now carries its
 * rows (its "rows" member, written where the figures are measured: rdoc_json_rows_member) and
 * is read by one generic path, the same as a brdfbench.rows/1 document. A file of a previous
 * version, written before the files carried rows, is read by the upgrade function of its schema
 * (one per old schema, below; frontier's and measured's in host/results/upgrade/): the one
 * place that still knows those layouts, so a baseline kept from an earlier version keeps working. */
#include "rdoc_read.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "compare_check.h"
#include "jsonr.h"
#include "outdir.h"
#include "schemas.h"
#include "rdoc_upgrade_frontier.h"
#include "rdoc_upgrade_measured.h"

typedef int (*layout_reader)(const struct jr_doc *, struct rdoc *, char *, size_t);
static int upgrade_throughput_v3(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_accuracy_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_render_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_fit_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

/* The kinds: what they are called, their file and the version written now. */
static const struct {
    const char *name, *file, *schema;
} kinds[RD_KIND_COUNT] = {
    { "throughput", "throughput.json", THROUGHPUT_SCHEMA },
    { "accuracy", "accuracy.json", ACCURACY_SCHEMA },
    { "render", "render.json", RENDER_SCHEMA },
    { "fit", "fit.json", FIT_SCHEMA },
    { "frontier", "frontier.json", FRONTIER_SCHEMA },
    { "measured", "measured.json", MEASURED_SCHEMA },
};

/* The schemas read by their layout: each previous version of a kind, with the function that
 * turns it into rows (its rows are those the version written now carries). */
static const struct {
    const char *schema;
    int kind;
    layout_reader read;
} layouts[] = {
    { THROUGHPUT_SCHEMA_V3, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    /* /2 is /3 without the normalised rates, /1 without the repetitions (compare refuses it:
       nothing to decide a verdict on; plot draws its rates): the same function, which takes
       what is there */
    { THROUGHPUT_SCHEMA_V2, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    { THROUGHPUT_SCHEMA_V1, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    { ACCURACY_SCHEMA_V1, RD_KIND_ACCURACY, upgrade_accuracy_v1 },
    { RENDER_SCHEMA_V1, RD_KIND_RENDER, upgrade_render_v1 },
    { FIT_SCHEMA_V1, RD_KIND_FIT, upgrade_fit_v1 },
    { FRONTIER_SCHEMA_V1, RD_KIND_FRONTIER, upgrade_frontier_v1 },
    /* /2 is /1 with a rows member of the accuracy figures alone: read by the same layout */
    { FRONTIER_SCHEMA_V2, RD_KIND_FRONTIER, upgrade_frontier_v1 },
    { MEASURED_SCHEMA_V1, RD_KIND_MEASURED, upgrade_measured_v1 },
};

const char *rd_kind_name(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].name : "?"; }
const char *rd_kind_file(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].file : "?"; }
const char *rd_kind_schema(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].schema : "?"; }

int rd_kind_of_name(const char *name)
{
    for (int k = 0; k < RD_KIND_COUNT; ++k)
        if (name && strcmp(name, kinds[k].name) == 0)
            return k;
    return -1;
}

/* ---- members ------------------------------------------------------------------------------ */

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

/* The array of numbers at obj's key into *reps (kept only when the metric has none yet);
 * 0, or 2 with err when it is not numbers. */
static int take_reps(const struct jr_doc *j, const struct jr_value *obj, const char *key, double **reps, int *n,
                     char *err, size_t errlen)
{
    double *v = NULL;
    size_t count = 0;
    if (jr_need_num_array(j, obj, key, &v, &count, err, errlen))
        return 2;
    if (!*reps && count > 0) {
        *reps = v;
        *n = (int)count;
    } else {
        free(v);
    }
    return 0;
}

/* A row's status: not ok with the reason (the status itself when no reason is given). */
static void row_status(struct rd_row *r, const struct jr_value *obj)
{
    const char *status = jr_str_or(obj, "status", "ok");
    if (strcmp(status, "ok") != 0)
        rd_row_fail(r, status, jr_str_or(obj, "reason", status));
    r->line = obj ? obj->line : 0;
}

/* The context block's plain members, as text. */
static void read_context(struct rd_context *c, const struct jr_value *ctx)
{
    static const char *const keys[] = { "device", "platform", "platform_version", "device_version", "driver_version",
                                        "compute_units", "host_cpu", "host_cores", "git_revision", "brdfbench_version",
                                        "build_options", "pocl_affinity", "date" };
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i) {
        const struct jr_value *v = jr_get(ctx, keys[i]);
        char buf[64];
        if (v && v->type == JR_STR) {
            rd_ctx_put(c, keys[i], v->str);
        } else if (v && v->type == JR_NUM) {
            snprintf(buf, sizeof buf, "%.10g", v->num);
            rd_ctx_put(c, keys[i], buf);
        }
    }
}

/* The context and, for a --device all file, each device's context. */
static void read_contexts(const struct jr_doc *j, struct rdoc *d)
{
    const struct jr_value *ctx = jr_get(&j->root, "context");
    read_context(&d->ctx, ctx);
    const struct jr_value *devices = jr_get(ctx, "devices");
    if (!devices || devices->type != JR_ARR || devices->count < 2)
        return;
    char all[RD_TEXT] = "";
    for (size_t i = 0; i < devices->count; ++i) {
        const struct jr_value *dv = &devices->items[i];
        const char *tag = jr_str_or(dv, "tag", jr_str_or(dv, "device", "?"));
        snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", i ? "; " : "", tag);
        struct rd_device *rd = rdoc_device(d, tag);
        if (rd)
            read_context(&rd->ctx, dv);
    }
    rd_ctx_put(&d->ctx, "devices", all);
}

/* "n 2..1000 step 1, 4096 samples per zone" from a context's grid, or "". */
static void grid_text(const struct jr_value *ctx, char *out, size_t len)
{
    const struct jr_value *g = jr_get(ctx, "grid");
    out[0] = '\0';
    if (g)
        snprintf(out, len, "n %g..%g step %g, %g samples per zone", jr_num_or_nan(g, "n_min"), jr_num_or_nan(g, "n_max"),
                 jr_num_or_nan(g, "n_step"), jr_num_or_nan(g, "samples_per_zone"));
}

/* ---- brdfbench.throughput/3 (and /2, /1) ---------------------------------------------------- */

/* A throughput context block's settings and machine record, as context lines. */
static void throughput_context(struct rd_context *c, const struct jr_value *tp, int *disturbed)
{
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "%g reps, min time %g s, %g work-items, n %g, n range %g:%g", jr_num_or_nan(tp, "reps"),
             jr_num_or_nan(tp, "min_time_s"), jr_num_or_nan(tp, "work_items"), jr_num_or_nan(tp, "n_uniform"),
             jr_num_or_nan(tp, "n_lo"), jr_num_or_nan(tp, "n_hi"));
    rd_ctx_put(c, "throughput settings", buf);
    const struct jr_value *rn = jr_get(tp, "runner");
    snprintf(buf, sizeof buf, "load %s -> %s", jr_str_or(tp, "loadavg_start", "?"), jr_str_or(tp, "loadavg_end", "?"));
    if (rn)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), ", steal %.3g s, %g of %g launches retried, %g reps disturbed",
                 jr_num_or_nan(rn, "steal_seconds"), jr_num_or_nan(rn, "preemption_retries"), jr_num_or_nan(rn, "launches"),
                 jr_num_or_nan(rn, "disturbed_reps"));
    rd_ctx_put(c, "machine", buf);
    if (disturbed && rn && jr_num_or_nan(rn, "disturbed_reps") > 0)
        *disturbed = (int)jr_num_or_nan(rn, "disturbed_reps");
}

/* A rate: "name" {min, median, max} of obj, with its repetitions in "name_reps". */
static struct rd_metric *rate_metric(const struct jr_doc *j, struct rdoc *d, struct rd_row *r, const struct jr_value *obj,
                                     const char *name, const char *unit, char *err, size_t errlen, int *rc)
{
    const struct jr_value *f = jr_get(obj, name);
    struct rd_metric *m = rd_row_metric(d, r, name, unit, RD_HIGHER, 1, jr_num_or_nan(f, "median"));
    char reps[RD_NAME + 8];
    snprintf(reps, sizeof reps, "%s_reps", name);
    *rc = 0;
    if (!m)
        return NULL;
    m->lo = jr_num_or_nan(f, "min");
    m->hi = jr_num_or_nan(f, "max");
    if (jr_get(obj, reps))
        *rc = take_reps(j, obj, reps, &m->reps, &m->nreps, err, errlen);
    return m;
}

/* A run's measured peak (its reference kernel) as a row of its own. */
static int put_peak(const struct jr_doc *j, struct rdoc *d, const char *device, const struct jr_value *pk, char *err,
                    size_t errlen)
{
    if (!pk || pk->type != JR_OBJ)
        return 0;
    struct rd_row *r = rdoc_row(d, device, "peak");
    if (!r)
        return 0;
    rd_row_key(r, "reference", NULL, "peak (reference kernel)");
    const char *status = jr_str_or(pk, "status", "ok");
    if (strcmp(status, "ok") != 0)
        rd_row_fail(r, status, jr_str_or(pk, "reason", "failed"));
    int rc;
    rate_metric(j, d, r, pk, "flops_per_s", "FLOP/s", err, errlen, &rc);
    return rc;
}

/* The normalised rates per CPU second where the run has them (a CPU device), else the
   normalised rates. */
static int take_normalised(const struct jr_doc *j, const struct jr_value *row, struct rd_metric *m, char *err,
                           size_t errlen)
{
    static const char *const norm_keys[2] = { "normalised_cpu_reps", "normalised_reps" };
    for (int q = 0; q < 2 && !m->norm; ++q) {
        if (!jr_get(row, norm_keys[q]))
            continue;
        if (take_reps(j, row, norm_keys[q], &m->norm, &m->nnorm, err, errlen))
            return 2;
        m->norm_cpu = q == 0 && m->norm;
    }
    return 0;
}

static int throughput_peaks(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *devs = jr_get(jr_get(&j->root, "context"), "devices");
    if (!devs || devs->type != JR_ARR || devs->count < 2)
        return put_peak(j, d, "", jr_get(&j->root, "peak"), err, errlen);
    for (size_t i = 0; i < devs->count; ++i) {
        const struct jr_value *dv = &devs->items[i];
        const char *tag = jr_str_or(dv, "tag", jr_str_or(dv, "device", "?"));
        if (put_peak(j, d, tag, jr_get(dv, "peak"), err, errlen))
            return 2;
        struct rd_device *rd = rdoc_device(d, tag);
        if (rd && jr_get(dv, "throughput"))
            throughput_context(&rd->ctx, jr_get(dv, "throughput"), NULL);
    }
    return 0;
}

static void kernel_sources(struct rdoc *d, const struct jr_value *tp)
{
    const struct jr_value *fp = jr_get(tp, "kernel_sources_fnv1a64");
    char buf[RD_TEXT] = "";
    for (size_t i = 0; fp && fp->type == JR_OBJ && i < fp->count; ++i)
        if (fp->items[i].type == JR_STR)
            snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s %.8s", i ? ", " : "", fp->keys[i],
                     fp->items[i].str);
    if (buf[0])
        rd_ctx_put(&d->ctx, "kernel sources", buf);
}

/* The upgrade of brdfbench.throughput/3 (and of /2 and /1, which hold less of the same): a row
 * for each device's peak kernel (flops_per_s), then one per result (keys label, variant, n mode;
 * attribute kind) with its evals_per_s, its range, repetitions and normalised repetitions; the
 * context lines "throughput settings", "machine" and "kernel sources". */
static int upgrade_throughput_v3(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *rows;
    if (jr_need(j, &j->root, "results", JR_ARR, &rows, err, errlen) || throughput_peaks(j, d, err, errlen))
        return 2;
    const struct jr_value *tp = jr_get(jr_get(&j->root, "context"), "throughput");
    if (tp) {
        throughput_context(&d->ctx, tp, &d->disturbed);
        kernel_sources(d, tp);
    }
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        const char *label, *variant, *mode;
        if (jr_need_str(j, row, "label", &label, err, errlen) || jr_need_str(j, row, "variant", &variant, err, errlen) ||
            jr_need_str(j, row, "n_mode", &mode, err, errlen))
            return 2;
        struct rd_row *r = rdoc_row(d, jr_str_or(row, "device", ""), label);
        if (!r)
            continue;
        rd_row_key(r, "label", NULL, label);
        rd_row_key(r, "variant", NULL, variant);
        rd_row_key(r, "n_mode", "n ", mode);
        rd_row_attr(r, "kind", jr_str_or(row, "kind", ""));
        row_status(r, row);
        int rc;
        struct rd_metric *m = rate_metric(j, d, r, row, "evals_per_s", "1/s", err, errlen, &rc);
        if (rc || (m && take_normalised(j, row, m, err, errlen)))
            return 2;
        r->retries = (int)fmax(0, jr_num_or_nan(row, "preemption_retries"));
        r->disturbed = (int)fmax(0, jr_num_or_nan(row, "disturbed_reps"));
    }
    return 0;
}

/* ---- brdfbench.accuracy/1 ------------------------------------------------------------------ */

/* The upgrade of brdfbench.accuracy/1: the context line "accuracy grid"; a row per result
 * (keys label and grid; attributes n_min, n_max, n_step). A lobe sweep's row has
 * epicentre.max_rel, attenuation.max_abs, whole.max_abs, invalid.count, check.float_cancellation
 * (where written) and, for code in half, fp16.max_rel, fp16.max_abs, fp16.invalid_count; a
 * hemisphere sweep's row (a "hemisphere" member) its grid "vs REF, hemisphere AXIS ..", the
 * attribute reference and its hemisphere.* figures. */
static int upgrade_accuracy_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    static const char *const figures[] = { "epicentre.max_rel", "attenuation.max_abs", "whole.max_abs",
                                           "invalid.count" };
    const struct jr_value *rows;
    if (jr_need(j, &j->root, "results", JR_ARR, &rows, err, errlen))
        return 2;
    char grid[RD_TEXT], text[RD_TEXT];
    const struct jr_value *g = jr_get(jr_get(&j->root, "context"), "grid");
    grid_text(jr_get(&j->root, "context"), grid, sizeof grid);
    rd_ctx_put(&d->ctx, "accuracy grid", grid);
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        const char *label;
        if (jr_need_str(j, row, "label", &label, err, errlen))
            return 2;
        struct rd_row *r = rdoc_row(d, jr_str_or(row, "device", ""), label);
        if (!r)
            continue;
        snprintf(text, sizeof text, "%.120s", label);
        rd_row_key(r, "label", NULL, text);
        const struct jr_value *hemi = jr_get(row, "hemisphere");
        if (hemi) {   /* a full BRDF's row: its axis and hemisphere grid are its grid */
            const struct jr_value *axis = jr_get(hemi, "axis"), *hg = jr_get(hemi, "grid");
            snprintf(text, sizeof text, "vs %.60s, hemisphere %.40s %.9g..%.9g x%.0f, %.0fx%.0fx%.0f",
                     jr_str_or(row, "reference", "?"), jr_str_or(axis, "name", "?"), jr_num_or_nan(axis, "min"),
                     jr_num_or_nan(axis, "max"), jr_num_or_nan(axis, "count"), jr_num_or_nan(hg, "theta_h"),
                     jr_num_or_nan(hg, "theta_d"), jr_num_or_nan(hg, "phi_d"));
        } else {
            snprintf(text, sizeof text, "%.120s", grid);
        }
        rd_row_key(r, "grid", NULL, text);
        row_status(r, row);
        snprintf(text, sizeof text, "%.17g", jr_num_or_nan(row, "n_min"));
        rd_row_attr(r, "n_min", text);
        snprintf(text, sizeof text, "%.17g", jr_num_or_nan(row, "n_max"));
        rd_row_attr(r, "n_max", text);
        snprintf(text, sizeof text, "%.17g", jr_num_or_nan(g, "n_step"));
        rd_row_attr(r, "n_step", text);
        if (hemi) {
            /* a full BRDF's row of the hemisphere sweep (host/measure/accuracy/hemisphere_report.c): its own
               metrics, never the lobe sweep's names */
            static const char *const hfigures[][2] = {
                { "epicentre.max_rel", "hemisphere.epicentre.max_rel" },
                { "attenuation.max_abs", "hemisphere.attenuation.max_abs" },
                { "whole.max_abs", "hemisphere.whole.max_abs" },
                { "rms", "hemisphere.rms" },
                { "float_cancellation", "hemisphere.float_cancellation" },
                { "samples.evaluated_below_horizon", "hemisphere.evaluated_below_horizon" },
            };
            rd_row_attr(r, "reference", jr_str_or(row, "reference", ""));
            for (size_t f = 0; f < sizeof hfigures / sizeof hfigures[0]; ++f) {
                const struct jr_value *v = path_get(hemi, hfigures[f][0]);
                rd_row_metric(d, r, hfigures[f][1], "1", RD_LOWER, 0, v && v->type == JR_NUM ? v->num : NAN);
            }
            continue;
        }
        for (size_t f = 0; f < sizeof figures / sizeof figures[0]; ++f) {
            const struct jr_value *v = path_get(row, figures[f]);
            rd_row_metric(d, r, figures[f], "1", RD_LOWER, 0, v && v->type == JR_NUM ? v->num : NAN);
        }
        const struct jr_value *fc = path_get(row, "check.float_cancellation");
        if (fc && fc->type == JR_NUM)   /* written since the device check's float floor */
            rd_row_metric(d, r, "check.float_cancellation", "1", RD_LOWER, 0, fc->num);
        const struct jr_value *h16 = jr_get(row, "fp16");
        if (h16 && h16->type == JR_OBJ) {   /* code in half: its binary16 build's sweep */
            static const char *const f16[][2] = { { "max_rel", "fp16.max_rel" }, { "max_abs", "fp16.max_abs" },
                                                  { "invalid_count", "fp16.invalid_count" } };
            for (size_t f = 0; f < sizeof f16 / sizeof f16[0]; ++f)
                rd_row_metric(d, r, f16[f][1], "1", RD_LOWER, 0, jr_num_or_nan(h16, f16[f][0]));
        }
    }
    return 0;
}

/* ---- render.json --------------------------------------------------------------------------- */

/* A scene's image figures: a row per model. */
static void render_models(struct rdoc *d, const struct jr_value *sc, const char *scene, const char *device)
{
    static const struct { const char *name, *unit; int direction; } metrics[] = {
        { "max_abs", "1", RD_LOWER }, { "rmse", "1", RD_LOWER }, { "psnr_db", "dB", RD_HIGHER } };
    const struct jr_value *img = jr_get(sc, "image"), *models = jr_get(sc, "models");
    char text[RD_TEXT];
    for (size_t m = 0; models && m < models->count; ++m) {
        const struct jr_value *mo = &models->items[m], *met = jr_get(mo, "metrics");
        const char *model = jr_str_or(mo, "model", "?");
        struct rd_row *r = rdoc_row(d, device, model);
        if (!r)
            return;
        snprintf(text, sizeof text, "%s %gx%g", scene, jr_num_or_nan(img, "width"), jr_num_or_nan(img, "height"));
        rd_row_key(r, "scene", NULL, text);
        rd_row_key(r, "model", NULL, model);
        row_status(r, met);
        for (size_t k = 0; met && k < sizeof metrics / sizeof metrics[0]; ++k) {
            double v = jr_num_or_nan(met, metrics[k].name);
            if (!isfinite(v) && r->ok)
                continue;   /* a PSNR of identical images is null (infinite): nothing to compare */
            rd_row_metric(d, r, metrics[k].name, metrics[k].unit, metrics[k].direction, 0, v);
        }
    }
}

/* A scene's timings: a row per timed entry and image size. */
static int render_timings(const struct jr_doc *j, struct rdoc *d, const struct jr_value *sc, const char *scene,
                          const char *device, char *err, size_t errlen)
{
    const struct jr_value *timings = jr_get(sc, "timings");
    for (size_t t = 0; timings && t < timings->count; ++t) {
        const struct jr_value *tm = &timings->items[t], *entries = jr_get(tm, "entries");
        char metric[64];
        snprintf(metric, sizeof metric, "mpixel_per_s@%gx%g", jr_num_or_nan(tm, "width"), jr_num_or_nan(tm, "height"));
        for (size_t e = 0; entries && e < entries->count; ++e) {
            const struct jr_value *en = &entries->items[e];
            const char *name = jr_str_or(en, "name", jr_str_or(en, "model", "?"));
            struct rd_row *r = rdoc_row(d, device, jr_str_or(en, "model", name));
            if (!r)
                return 0;
            rd_row_key(r, "scene", NULL, scene);
            rd_row_key(r, "entry", NULL, name);
            const char *reason = jr_str_or(en, "reason", NULL);
            if (reason && *reason)
                rd_row_fail(r, "failed", reason);
            double v = jr_num_or_nan(en, "mpixel_per_s"), med = jr_num_or_nan(en, "median_ms");
            struct rd_metric *m = rd_row_metric(d, r, metric, "Mpixel/s", RD_HIGHER, 1, v);
            if (!m || !r->ok || !isfinite(v))
                continue;
            /* Mpixel/s is inversely proportional to the time: the slowest run gives lo */
            m->lo = v * med / jr_num_or_nan(en, "max_ms");
            m->hi = v * med / jr_num_or_nan(en, "min_ms");
            /* the launches' own rates, for the rank test (an older render.json without them is
               compared by its min..max range) */
            if (jr_get(en, "mpixel_per_s_reps") &&
                take_reps(j, en, "mpixel_per_s_reps", &m->reps, &m->nreps, err, errlen))
                return 2;
        }
    }
    return 0;
}

/* The upgrade of brdfbench.render/1: per scene a row per model (keys scene "NAME WxH", model;
 * max_abs, rmse, psnr_db) and a row per timed entry and image size (keys scene, entry;
 * mpixel_per_s@WxH with its range and repetitions). */
static int upgrade_render_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *scenes;
    if (jr_need(j, &j->root, "scenes", JR_ARR, &scenes, err, errlen))
        return 2;
    for (size_t i = 0; i < scenes->count; ++i) {
        const struct jr_value *sc = &scenes->items[i];
        const char *scene;
        if (jr_need_str(j, sc, "scene", &scene, err, errlen))
            return 2;
        const char *device = jr_str_or(sc, "device", "");   /* a --device all run tags its scenes */
        render_models(d, sc, scene, device);
        if (render_timings(j, d, sc, scene, device, err, errlen))
            return 2;
    }
    return 0;
}

/* ---- brdfbench.fit/1 ------------------------------------------------------------------------- */

/* A row of fit figures: the coefficients where the row is the fit itself, then its errors. */
static void fit_row(struct rdoc *d, const struct jr_value *obj, const char *role, const char *grid, int with_coefs)
{
    static const char *const errs[] = { "max_rel", "max_abs" };
    static const char *const coefs[] = { "a", "b" };
    struct rd_row *r = rdoc_row(d, "", "fit");
    if (!r)
        return;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%.120s", role);
    rd_row_key(r, "role", NULL, text);
    snprintf(text, sizeof text, "%.*s", with_coefs ? 200 : 120, grid);
    rd_row_key(r, "grid", NULL, text);
    row_status(r, obj);
    for (int k = 0; with_coefs && k < 2; ++k)
        rd_row_metric(d, r, coefs[k], "1", RD_NEITHER, 0, jr_num_or_nan(obj, coefs[k]));
    for (int k = 0; k < 2; ++k)
        rd_row_metric(d, r, errs[k], "1", RD_LOWER, 0, jr_num_or_nan(obj, errs[k]));
}

/* The upgrade of brdfbench.fit/1: the best affine fit and the fit capped at fq2's max Delta
 * (a, b, max_rel, max_abs), then each compared model (max_rel, max_abs); the context line
 * "fit grid". */
static int upgrade_fit_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    char grid[RD_TEXT];
    grid_text(jr_get(&j->root, "context"), grid, sizeof grid);
    rd_ctx_put(&d->ctx, "fit grid", grid);
    fit_row(d, &j->root, "best affine k(n)", grid, 1);
    const struct jr_value *capped = jr_get(&j->root, "capped_at_fq2");
    if (capped && capped->type == JR_OBJ)
        fit_row(d, capped, "capped at fq2's max Delta", grid, 1);
    const struct jr_value *cmp = jr_get(&j->root, "compare");
    for (size_t i = 0; cmp && cmp->type == JR_ARR && i < cmp->count; ++i) {
        const char *model = jr_str_or(&cmp->items[i], "model", "?");
        if (strncmp(model, "quad:", 5) == 0)
            continue;   /* the fitted model itself: its label moves with its coefficients */
        fit_row(d, &cmp->items[i], model, grid, 0);
    }
    return 0;
}

/* ---- files --------------------------------------------------------------------------------- */

/* The kind a schema string names, by its name before the '/' ("brdfbench.fit/1" -> fit), or
   -1; *layout: the reader of that version by its layout (NULL: none, which for the version
   written now means the file carries its rows). */
static int kind_of_schema(const char *schema, layout_reader *layout)
{
    *layout = NULL;
    for (size_t i = 0; i < sizeof layouts / sizeof layouts[0]; ++i)
        if (strcmp(schema, layouts[i].schema) == 0)
            *layout = layouts[i].read;
    for (int k = 0; k < RD_KIND_COUNT; ++k) {
        size_t n = (size_t)(strchr(kinds[k].schema, '/') - kinds[k].schema) + 1;
        if (strncmp(schema, kinds[k].schema, n) == 0)
            return k;
    }
    return -1;
}

static int read_doc(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const char *schema;
    if (jr_need_str(j, &j->root, "schema", &schema, err, errlen))
        return 2;
    if (strcmp(schema, ROWS_SCHEMA) == 0)
        return compare_check_doc(j, err, errlen) || rdoc_from_rows_json(j, d, err, errlen) ? 2 : 0;
    layout_reader layout;
    int kind = kind_of_schema(schema, &layout);
    if (kind < 0) {
        snprintf(err, errlen, "%s: schema \"%.60s\" is not a result file with figures (accepted: %s, %s, %s, %s, %s, %s)",
                 j->name, schema, kinds[0].schema, kinds[1].schema, kinds[2].schema, kinds[3].schema,
                 kinds[4].schema, ROWS_SCHEMA);
        return 2;
    }
    const int current = strcmp(schema, kinds[kind].schema) == 0;
    if (!current && !layout) {
        snprintf(err, errlen, "%s: schema \"%.60s\", this version reads \"%s\" (run the command again with this version)",
                 j->name, schema, kinds[kind].schema);
        return 2;
    }
    const struct jr_value *rows = jr_get(&j->root, "rows");
    if (layout)
        rows = NULL;   /* a previous version is read by its layout: a rows member it has (frontier/2's)
                          lacks what the rows carry now, an old frontier layout's "rows" is its array */
    if (!layout && !rows) {
        snprintf(err, errlen, "%s: schema \"%.60s\" without its \"rows\" (accepted: the file as brdfbench writes it, "
                 "which carries its rows)", j->name, schema);
        return 2;
    }
    if (compare_check_doc(j, err, errlen))
        return 2;
    rdoc_init(d, schema, kinds[kind].name, kinds[kind].file);
    read_contexts(j, d);
    /* a file of the version written now is read by its rows; one of a previous version, by the
       layout of its version */
    if (rows ? rdoc_from_rows_member(j, rows, d, err, errlen) : layout(j, d, err, errlen)) {
        rdoc_free(d);
        return 2;
    }
    if (d->oom) {
        snprintf(err, errlen, "out of memory reading %s", j->name);
        rdoc_free(d);
        return 2;
    }
    for (int i = 0; i < d->nrows; ++i)
        if (d->rows[i].truncated) {
            snprintf(err, errlen, "%s: row '%.60s...': its keys do not fit (at most %d keys, a label and each key of "
                     "at most %d bytes): two distinct rows could read as one", j->name, d->rows[i].label, RD_MAX_KEYS,
                     RD_TEXT - 1);
            rdoc_free(d);
            return 2;
        }
    return 0;
}

int rdoc_read_file(const char *path, struct rdoc *d, char *err, size_t errlen)
{
    struct jr_doc j;
    memset(d, 0, sizeof *d);
    if (jr_parse_file(path, &j, err, errlen))
        return 2;
    int rc = read_doc(&j, d, err, errlen);
    jr_free(&j);
    return rc;
}

int rdoc_read_folder(const char *dir, int only, struct rdoc d[RD_KIND_COUNT], int *found, char *err, size_t errlen)
{
    *found = 0;
    for (int k = 0; k < RD_KIND_COUNT; ++k) {
        char file[4200];
        struct stat st;
        if ((only >= 0 && k != only) || path_join(file, sizeof file, dir, kinds[k].file) || stat(file, &st) != 0)
            continue;
        if (rdoc_read_file(file, &d[*found], err, errlen)) {
            for (int i = 0; i < *found; ++i)
                rdoc_free(&d[i]);
            return 2;
        }
        ++*found;
    }
    return 0;
}
