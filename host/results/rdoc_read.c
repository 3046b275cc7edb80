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
#include "models.h"
#include "outdir.h"
#include "rdoc_upgrade_energy.h"
#include "schemas.h"
#include "rdoc_upgrade_claims.h"
#include "rdoc_upgrade_frontier.h"
#include "rdoc_upgrade_measured.h"

typedef int (*layout_reader)(const struct jr_doc *, struct rdoc *, char *, size_t);
static int upgrade_throughput_v3(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_accuracy_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_render_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_fit_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_field_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
static int upgrade_fit_family_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);

/* The kinds: what they are called, their file and the version written now; a kind with one
 * file per model (field_MODEL.json: a heatmap's grid, whose maxima the accuracy rows give
 * refined) is read when named, not as part of a run folder. */
static const struct {
    const char *name, *file, *schema;
} kinds[RD_KIND_COUNT] = {
    { "throughput", "throughput.json", THROUGHPUT_SCHEMA },
    { "accuracy", "accuracy.json", ACCURACY_SCHEMA },
    { "render", "render.json", RENDER_SCHEMA },
    { "fit", "fit.json", FIT_SCHEMA },
    { "frontier", "frontier.json", FRONTIER_SCHEMA },
    { "claims", "claims.json", CLAIMS_SCHEMA },
    { "q_sweep", "q_sweep.json", Q_SWEEP_SCHEMA },
    { "physical", "physical.json", PBCOST_SCHEMA },
    { "energy", "energy.json", ENERGY_SCHEMA },
    { "measured", "measured.json", MEASURED_SCHEMA },
    { "field", "field_MODEL.json", FIELD_SCHEMA },
    { "fit_family", "fit.json", FIT_FAMILY_SCHEMA },   /* `fit --family`'s fit.json */
};

/* The schemas read by their layout: each previous version of a kind, with the function that
 * turns it into rows (its rows are those the version written now carries). */
static const struct {
    const char *schema;
    int kind;
    layout_reader read;
} layouts[] = {
    /* /4 is /3 with a rows member that lacks what the throughput page reads */
    { THROUGHPUT_SCHEMA_V4, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    { THROUGHPUT_SCHEMA_V3, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    /* /2 is /3 without the normalised rates, /1 without the repetitions (compare refuses it:
       nothing to decide a verdict on; plot draws its rates): the same function, which takes
       what is there */
    { THROUGHPUT_SCHEMA_V2, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    { THROUGHPUT_SCHEMA_V1, RD_KIND_THROUGHPUT, upgrade_throughput_v3 },
    { ACCURACY_SCHEMA_V1, RD_KIND_ACCURACY, upgrade_accuracy_v1 },
    { RENDER_SCHEMA_V1, RD_KIND_RENDER, upgrade_render_v1 },
    { FIT_SCHEMA_V1, RD_KIND_FIT, upgrade_fit_v1 },
    /* /2 of these has the layout of /1 and rows without what report.md shows (the reference,
       the maxima's positions, the verdict, the pictures, ...): read by that layout, its rows
       member left aside */
    { ACCURACY_SCHEMA_V2, RD_KIND_ACCURACY, upgrade_accuracy_v1 },
    { RENDER_SCHEMA_V2, RD_KIND_RENDER, upgrade_render_v1 },
    { FIT_SCHEMA_V2, RD_KIND_FIT, upgrade_fit_v1 },
    { ENERGY_SCHEMA_V1, RD_KIND_ENERGY, upgrade_energy_v1 },
    { FRONTIER_SCHEMA_V1, RD_KIND_FRONTIER, upgrade_frontier_v1 },
    /* rdoc_upgrade_claims.c */
    { CLAIMS_SCHEMA_V1, RD_KIND_CLAIMS, upgrade_claims_v1 },
    { Q_SWEEP_SCHEMA_V1, RD_KIND_Q_SWEEP, upgrade_q_sweep_v1 },
    { PBCOST_SCHEMA_V1, RD_KIND_PHYSICAL, upgrade_physical_v1 },
    { FIELD_SCHEMA_V1, RD_KIND_FIELD, upgrade_field_v1 },
    { FIT_FAMILY_SCHEMA_V1, RD_KIND_FIT_FAMILY, upgrade_fit_family_v1 },
    /* /2 is /1 with a rows member of the accuracy figures alone: read by the same layout */
    { FRONTIER_SCHEMA_V2, RD_KIND_FRONTIER, upgrade_frontier_v1 },
    { MEASURED_SCHEMA_V1, RD_KIND_MEASURED, upgrade_measured_v1 },
};

const char *rd_kind_name(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].name : "?"; }
const char *rd_kind_file(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].file : "?"; }
const char *rd_kind_schema(int k) { return k >= 0 && k < RD_KIND_COUNT ? kinds[k].schema : "?"; }

void rd_kind_names(char *out, size_t len)
{
    if (len)
        out[0] = '\0';
    for (int k = 0; k < RD_KIND_COUNT && len; ++k)
        snprintf(out + strlen(out), len - strlen(out), "%s%s", k ? ", " : "", kinds[k].name);
}

void rd_kind_files(char *out, size_t len)
{
    if (len)
        out[0] = '\0';
    for (int k = 0; k < RD_KIND_COUNT && len; ++k) {
        int seen = strstr(kinds[k].file, "MODEL") != NULL;   /* one file per model: named, not found */
        for (int e = 0; e < k; ++e)
            seen |= strcmp(kinds[e].file, kinds[k].file) == 0;
        if (!seen)
            snprintf(out + strlen(out), len - strlen(out), "%s%s", *out ? ", " : "", kinds[k].file);
    }
}

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

/* Whether results a and b are of the same device, build variant and n mode. */
static int same_figure_set(const struct jr_value *a, const struct jr_value *b)
{
    static const char *const keys[] = { "device", "variant", "n_mode" };
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; ++k)
        if (strcmp(jr_str_or(a, keys[k], ""), jr_str_or(b, keys[k], "")) != 0)
            return 0;
    return 1;
}

/* The label of the model's own reference where a result of the same device has it, else NULL
   (the engine's model_reference attribute: the registry's reference of the label, measured in
   the same run). A model the registry does not know here (a user model of that run) has the
   result whose rate gives the file's ratio_to_model_reference, to the bit (the file's numbers
   are written with 17 digits, so the division is the engine's). */
static const char *model_reference_in(const struct jr_value *results, const struct jr_value *row, char *buf,
                                      size_t len)
{
    struct model_spec spec, ref;
    char why[200];
    if (strcmp(jr_str_or(row, "kind", ""), "model") != 0)
        return NULL;
    if (model_spec_parse(jr_str_or(row, "label", ""), &spec, why, sizeof why) == 0) {
        model_reference_spec(&spec, &ref);
        for (size_t i = 0; i < results->count; ++i)
            if (strcmp(jr_str_or(&results->items[i], "label", ""), ref.label) == 0 &&
                strcmp(jr_str_or(&results->items[i], "device", ""), jr_str_or(row, "device", "")) == 0) {
                snprintf(buf, len, "%s", ref.label);
                return buf;
            }
        return NULL;
    }
    double q = jr_num_or_nan(row, "ratio_to_model_reference"), f = jr_num_or_nan(jr_get(row, "evals_per_s"), "median");
    for (size_t i = 0; isfinite(q) && i < results->count; ++i) {
        const struct jr_value *o = &results->items[i];
        double g = jr_num_or_nan(jr_get(o, "evals_per_s"), "median");
        if (same_figure_set(o, row) && strcmp(jr_str_or(o, "status", ""), "ok") == 0 && g > 0 && f / g == q) {
            snprintf(buf, len, "%s", jr_str_or(o, "label", ""));
            return buf;
        }
    }
    return NULL;
}

/* What the throughput page reads of a result beside its rate (report_throughput.h): the model's
   reference, the tuned C loop's rate (default variant) or why its ratio is missing, the
   accuracy against the double reference, and the note of values not all finite. */
static int throughput_page_record(const struct jr_doc *j, struct rdoc *d, struct rd_row *r,
                                  const struct jr_value *results, const struct jr_value *row, char *err, size_t errlen)
{
    char ref[RD_TEXT];
    if (model_reference_in(results, row, ref, sizeof ref))
        rd_row_attr(r, "model_reference", ref);
    const struct jr_value *hc = jr_get(row, "host_c"), *acc = jr_get(row, "accuracy");
    int deflt = strcmp(jr_str_or(row, "variant", ""), "default") == 0;
    if (deflt && hc && strcmp(jr_str_or(hc, "status", ""), "ok") == 0) {
        int rc;
        struct rd_metric *m = rate_metric(j, d, r, hc, "evals_per_s", "1/s", err, errlen, &rc);
        if (m)
            snprintf(m->name, sizeof m->name, "host_c.evals_per_s");
        if (rc || (m && take_normalised(j, hc, m, err, errlen)))
            return 2;
    }
    if (acc && strcmp(jr_str_or(acc, "status", ""), "ok") == 0)
        rd_row_metric(d, r, "accuracy.max_diff_of_peak", "1", RD_NEITHER, 0, jr_num_or_nan(acc, "max_diff_of_peak"));
    if (acc && jr_num_or_nan(acc, "nonfinite") > 0)
        rd_row_metric(d, r, "accuracy.nonfinite", "1", RD_NEITHER, 0, jr_num_or_nan(acc, "nonfinite"));
    const struct jr_value *finite = jr_get(row, "values_finite");
    if (r->ok && finite && finite->type == JR_BOOL && !finite->num)
        rd_row_text(d, r, "note", jr_str_or(row, "note", "some values were NaN or Inf under these build options"));
    if (deflt && hc && jr_get(hc, "sums_check") && strcmp(jr_str_or(hc, "status", ""), "failed") == 0)
        rd_row_text(d, r, "host_c_reason", jr_str_or(hc, "reason", "failed"));
    return 0;
}

/* The page's document texts (the launches behind each median, the C loop's threads: the
   machine's cores where the file records none, as the run used them) and a row per model of
   the accuracy sweep (points, and each side's points per second from its seconds). */
static void throughput_sweep(struct rdoc *d, const struct jr_value *root, const struct jr_value *tp)
{
    char buf[64];
    if (tp && isfinite(jr_num_or_nan(tp, "reps"))) {
        snprintf(buf, sizeof buf, "%.0f", jr_num_or_nan(tp, "reps"));
        rdoc_text(d, "reps", buf);
    }
    double threads = tp ? jr_num_or_nan(tp, "host_c_threads") : NAN;
    if (!(threads > 0))
        threads = jr_num_or_nan(jr_get(root, "context"), "host_cores");
    if (isfinite(threads)) {
        snprintf(buf, sizeof buf, "%.0f", threads);
        rdoc_text(d, "tuned_c_threads", buf);
    }
    const struct jr_value *sw = jr_get(root, "sweep"), *models = jr_get(sw, "models");
    if (!sw || strcmp(jr_str_or(sw, "status", "not run"), "not run") == 0)
        return;
    rdoc_textf(d, "sweep_grid", "n %g..%g step %g, %.0f samples per zone", jr_num_or_nan(sw, "n_min"),
               jr_num_or_nan(sw, "n_max"), jr_num_or_nan(sw, "n_step"), jr_num_or_nan(sw, "samples_per_zone"));
    if (jr_get(sw, "reason"))
        rdoc_text(d, "sweep_reason", jr_str_or(sw, "reason", ""));
    /* the sweep of a --device all file is its first device's, as its other sections are */
    const struct jr_value *devs = jr_get(jr_get(root, "context"), "devices");
    const char *device = devs && devs->type == JR_ARR && devs->count >= 2
                             ? jr_str_or(&devs->items[0], "tag", jr_str_or(&devs->items[0], "device", "?")) : "";
    for (size_t i = 0; models && models->type == JR_ARR && i < models->count; ++i) {
        const struct jr_value *m = &models->items[i];
        struct rd_row *r = rdoc_row(d, device, jr_str_or(m, "label", ""));
        if (!r)
            return;
        rd_row_key(r, "label", NULL, jr_str_or(m, "label", ""));
        rd_row_key(r, "sweep", NULL, "accuracy sweep");
        row_status(r, m);
        double pts = jr_num_or_nan(m, "points");
        rd_row_metric(d, r, "points", "1", RD_NEITHER, 0, pts);
        static const char *const sides[2][2] = { { "device_points_per_s", "device_seconds" },
                                                 { "host_c_points_per_s", "host_c_seconds" } };
        for (int k = 0; k < 2; ++k) {
            const struct jr_value *sec = jr_get(m, sides[k][1]);
            struct rd_metric *x = rd_row_metric(d, r, sides[k][0], "1/s", RD_HIGHER, 1,
                                                r->ok ? pts / jr_num_or_nan(sec, "median") : NAN);
            if (x && r->ok) {
                x->lo = pts / jr_num_or_nan(sec, "max");
                x->hi = pts / jr_num_or_nan(sec, "min");
            }
        }
    }
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
        if (rc || (m && take_normalised(j, row, m, err, errlen)) ||
            throughput_page_record(j, d, r, rows, row, err, errlen))
            return 2;
        r->retries = (int)fmax(0, jr_num_or_nan(row, "preemption_retries"));
        r->disturbed = (int)fmax(0, jr_num_or_nan(row, "disturbed_reps"));
    }
    throughput_sweep(d, &j->root, tp);
    return 0;
}

/* ---- brdfbench.accuracy/1 ------------------------------------------------------------------ */

/* The upgrade of brdfbench.accuracy/1 (and /2): the context line "accuracy grid" and the grid's
 * numbers; a row per result (keys label and grid; attributes n_min, n_max, n_step). A lobe
 * sweep's row has the attribute reference, epicentre.max_rel, attenuation.max_abs,
 * whole.max_abs, invalid.count, check.float_cancellation (where written), for code in half
 * fp16.max_rel, fp16.max_abs, fp16.invalid_count, then epicentre.at_n/at_x,
 * attenuation.at_n/at_x, invalid.at_n/at_x and check.in_4th_digit_units; a
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
    if (g) {   /* the grid's numbers, for report.md */
        static const char *const num[][2] = { { "n_min", "accuracy n_min" }, { "n_max", "accuracy n_max" },
                                              { "n_step", "accuracy n_step" },
                                              { "samples_per_zone", "accuracy samples per zone" } };
        for (size_t k = 0; k < sizeof num / sizeof num[0]; ++k) {
            snprintf(text, sizeof text, "%.17g", jr_num_or_nan(g, num[k][0]));
            rd_ctx_put(&d->ctx, num[k][1], text);
        }
    }
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
        rd_row_attr(r, "reference", jr_str_or(row, "reference", ""));
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
        /* what report.md shows beside the figures: where the maxima and the first invalid value
           lie, and the device check in 4th-digit units */
        static const char *const at[] = { "epicentre.at_n", "epicentre.at_x", "attenuation.at_n", "attenuation.at_x",
                                          "invalid.at_n", "invalid.at_x" };
        for (size_t f = 0; f < sizeof at / sizeof at[0]; ++f) {
            const struct jr_value *v = path_get(row, at[f]);
            rd_row_metric(d, r, at[f], at[f][strlen(at[f]) - 1] == 'x' ? "rad" : "1", RD_NEITHER, 0,
                          v && v->type == JR_NUM ? v->num : NAN);
        }
        const struct jr_value *units = path_get(row, "check.in_4th_digit_units");
        rd_row_metric(d, r, "check.in_4th_digit_units", "4th-digit units", RD_LOWER, 0,
                      units && units->type == JR_NUM ? units->num : NAN);
    }
    return 0;
}

/* ---- render.json --------------------------------------------------------------------------- */

/* A row's error figures from a render.json metrics object (names, units, directions as
   host/measure/render/render_report.c declares them): none where they are not finite in a
   measured row (the PSNR of identical images). */
static void render_figures(struct rdoc *d, struct rd_row *r, const struct jr_value *met, const struct jr_value *entry)
{
    static const struct { const char *name, *unit; int direction; } metrics[] = {
        { "max_abs", "1", RD_LOWER }, { "rmse", "1", RD_LOWER }, { "psnr_db", "dB", RD_HIGHER },
        { "share_above_threshold", "1", RD_LOWER } };
    static const char *const he[] = { "max_abs", "mean_abs", "max_abs_vs_blinn_fit" };
    for (size_t k = 0; met && k < (entry ? 3 : sizeof metrics / sizeof metrics[0]); ++k) {
        const char *name = entry ? he[k] : metrics[k].name;
        double v = jr_num_or_nan(entry && k == 2 ? entry : met, name);
        if (!isfinite(v) && r->ok)
            continue;   /* a PSNR of identical images is null (infinite): nothing to compare */
        rd_row_metric(d, r, name, entry ? "1" : metrics[k].unit, entry ? RD_LOWER : metrics[k].direction, 0, v);
    }
}

/* A scene's image figures: a row per model, with the texts report.md shows (the device-vs-double
   check, the picture files; on the first, the scene's source, contact sheet and timed size). */
static void render_models(struct rdoc *d, const struct jr_value *sc, const char *scene, const char *device)
{
    const struct jr_value *img = jr_get(sc, "image"), *models = jr_get(sc, "models");
    const struct jr_value *timings = jr_get(sc, "timings");
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
        rd_row_attr(r, "scene_name", scene);
        rd_row_attr(r, "reference", jr_str_or(mo, "reference", ""));
        row_status(r, met);
        render_figures(d, r, met, NULL);
        const struct jr_value *within = jr_get(jr_get(mo, "double_reference_check"), "within_bound");
        if (within && within->type == JR_BOOL)
            rd_row_text(d, r, "double_reference_check", within->num ? "within bound" : "outside bound");
        static const char *const files[] = { "image", "error_image", "signed_error_image", "contact_sheet" };
        const struct jr_value *fo = jr_get(mo, "files");
        for (size_t f = 0; fo && f < sizeof files / sizeof files[0]; ++f)
            if (jr_str_or(fo, files[f], NULL))
                rd_row_text(d, r, files[f], jr_str_or(fo, files[f], ""));
        if (m == 0) {
            if (jr_str_or(sc, "source", NULL))
                rd_row_text(d, r, "scene_source", jr_str_or(sc, "source", ""));
            if (jr_str_or(img, "contact_sheet", NULL))
                rd_row_text(d, r, "scene_contact_sheet", jr_str_or(img, "contact_sheet", ""));
            if (timings && timings->type == JR_ARR && timings->count > 0)
                rd_row_textf(d, r, "scene_timed_size", "%.0f x %.0f", jr_num_or_nan(&timings->items[0], "width"),
                             jr_num_or_nan(&timings->items[0], "height"));
        }
    }
}

/* A scene's timings: a row per timed entry and image size (attributes size, selected_model):
   its speed with range and repetitions, its fraction of the copy kernel and its speed-up
   against its reference. */
static int render_timings(const struct jr_doc *j, struct rdoc *d, const struct jr_value *sc, const char *scene,
                          const char *device, char *err, size_t errlen)
{
    const struct jr_value *timings = jr_get(sc, "timings");
    for (size_t t = 0; timings && t < timings->count; ++t) {
        const struct jr_value *tm = &timings->items[t], *entries = jr_get(tm, "entries");
        char metric[64], size[28];
        snprintf(size, sizeof size, "%gx%g", jr_num_or_nan(tm, "width"), jr_num_or_nan(tm, "height"));
        for (size_t e = 0; entries && e < entries->count; ++e) {
            const struct jr_value *en = &entries->items[e], *sel = jr_get(en, "selected_model");
            const char *name = jr_str_or(en, "name", jr_str_or(en, "model", "?"));
            struct rd_row *r = rdoc_row(d, device, jr_str_or(en, "model", name));
            if (!r)
                return 0;
            rd_row_key(r, "scene", NULL, scene);
            rd_row_key(r, "entry", NULL, name);
            rd_row_attr(r, "size", size);
            rd_row_attr(r, "selected_model", sel && sel->type == JR_BOOL && sel->num ? "true" : "false");
            const char *reason = jr_str_or(en, "reason", NULL);
            if (reason && *reason)
                rd_row_fail(r, "failed", reason);
            double v = jr_num_or_nan(en, "mpixel_per_s"), med = jr_num_or_nan(en, "median_ms");
            snprintf(metric, sizeof metric, "mpixel_per_s@%s", size);
            struct rd_metric *m = rd_row_metric(d, r, metric, "Mpixel/s", RD_HIGHER, 1, v);
            if (m && r->ok && isfinite(v)) {
                /* Mpixel/s is inversely proportional to the time: the slowest run gives lo */
                m->lo = v * med / jr_num_or_nan(en, "max_ms");
                m->hi = v * med / jr_num_or_nan(en, "min_ms");
                /* the launches' own rates, for the rank test (an older render.json without them is
                   compared by its min..max range) */
                if (jr_get(en, "mpixel_per_s_reps") &&
                    take_reps(j, en, "mpixel_per_s_reps", &m->reps, &m->nreps, err, errlen))
                    return 2;
            }
            snprintf(metric, sizeof metric, "fraction_of_copy@%s", size);
            rd_row_metric(d, r, metric, "1", RD_HIGHER, 0, jr_num_or_nan(en, "fraction_of_copy"));
            if (jr_get(en, "speedup_vs_reference")) {
                snprintf(metric, sizeof metric, "speedup_vs_reference@%s", size);
                rd_row_metric(d, r, metric, "1", RD_HIGHER, 0, jr_num_or_nan(en, "speedup_vs_reference"));
            }
        }
    }
    return 0;
}

/* A scene's He comparison: the Blinn-Phong fit's row, then one per model shaded at its n. */
static void render_he(struct rdoc *d, const struct jr_value *sc, const char *scene, const char *device)
{
    const struct jr_value *hc = jr_get(sc, "he_comparison"), *img = jr_get(sc, "image");
    const struct jr_value *entries = jr_get(hc, "entries");
    if (!entries || entries->type != JR_ARR)
        return;
    char key[RD_TEXT];
    snprintf(key, sizeof key, "%s %gx%g", scene, jr_num_or_nan(img, "width"), jr_num_or_nan(img, "height"));
    const char *he = jr_str_or(hc, "model", "?");
    for (long k = -1; k < (long)entries->count; ++k) {
        const struct jr_value *en = k < 0 ? NULL : &entries->items[k];
        const char *name = en ? jr_str_or(en, "name", "?") : "Blinn-Phong fit";
        struct rd_row *r = rdoc_row(d, device, en ? name : he);
        if (!r)
            return;
        rd_row_key(r, "scene", NULL, key);
        rd_row_key(r, "against", NULL, he);
        rd_row_key(r, "shaded_by", NULL, name);
        rd_row_attr(r, "scene_name", scene);
        rd_row_attr(r, "he", en ? "entry" : "fit");
        if (!en) {
            rd_row_metric(d, r, "n_fit", "1", RD_NEITHER, 0, jr_num_or_nan(hc, "n_fit"));
            rd_row_metric(d, r, "k_fit", "1", RD_NEITHER, 0, jr_num_or_nan(hc, "k_fit"));
            rd_row_metric(d, r, "relative_rms_residual", "1", RD_LOWER, 0, jr_num_or_nan(hc, "relative_rms_residual"));
            continue;
        }
        row_status(r, jr_get(en, "metrics"));
        render_figures(d, r, jr_get(en, "metrics"), en);
        const char *contact = jr_str_or(jr_get(en, "files"), "contact_sheet", NULL);
        if (contact)
            rd_row_text(d, r, "contact_sheet", contact);
    }
}

/* The upgrade of brdfbench.render/1 (and /2): per scene a row per model (keys scene "NAME WxH",
 * model; attributes scene_name, reference; max_abs, rmse, psnr_db, share_above_threshold; texts
 * double_reference_check and the files), a row per timed entry and image size (keys scene,
 * entry; attributes size, selected_model; mpixel_per_s@WxH with its range and repetitions,
 * fraction_of_copy@WxH, speedup_vs_reference@WxH) and He's comparison (keys scene, against,
 * shaded_by). */
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
        render_he(d, sc, scene, device);
    }
    return 0;
}

/* ---- brdfbench.fit/1 ------------------------------------------------------------------------- */

/* A row of fit figures: the coefficients where the row is the fit itself, then its errors. */
static struct rd_row *fit_row(struct rdoc *d, const struct jr_value *obj, const char *role, const char *grid,
                              int with_coefs)
{
    static const char *const errs[] = { "max_rel", "max_abs" };
    static const char *const coefs[] = { "a", "b" };
    struct rd_row *r = rdoc_row(d, "", "fit");
    if (!r)
        return NULL;
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
    return r;
}

/* The upgrade of brdfbench.fit/1 (and /2): the best affine fit and the fit capped at fq2's max
 * Delta (a, b, max_rel, max_abs; attribute model: the model its device sweep ran, which then
 * leads the "compare" list, else ""), the family's limit (max_rel, at_n), then each compared
 * model (max_rel, max_abs; attribute model); the context lines "fit grid", "fit n_min",
 * "fit n_max" and the document's text "verdict". */
static int upgrade_fit_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    char grid[RD_TEXT], text[RD_TEXT];
    (void)err;
    (void)errlen;
    const struct jr_value *g = jr_get(jr_get(&j->root, "context"), "grid");
    grid_text(jr_get(&j->root, "context"), grid, sizeof grid);
    rd_ctx_put(&d->ctx, "fit grid", grid);
    if (g) {   /* the n range report.md names */
        snprintf(text, sizeof text, "%.17g", jr_num_or_nan(g, "n_min"));
        rd_ctx_put(&d->ctx, "fit n_min", text);
        snprintf(text, sizeof text, "%.17g", jr_num_or_nan(g, "n_max"));
        rd_ctx_put(&d->ctx, "fit n_max", text);
    }
    const struct jr_value *cmp = jr_get(&j->root, "compare");
    size_t ncmp = cmp && cmp->type == JR_ARR ? cmp->count : 0, k = 0;
    const struct jr_value *fits[2] = { &j->root, jr_get(&j->root, "capped_at_fq2") };
    static const char *const roles[2] = { "best affine k(n)", "capped at fq2's max Delta" };
    for (int i = 0; i < 2; ++i) {
        if (!fits[i] || fits[i]->type != JR_OBJ)
            continue;
        struct rd_row *r = fit_row(d, fits[i], roles[i], grid, 1);
        /* a fit whose sweep ran leads the compare list, in this order */
        const char *model = jr_str_or(fits[i], "model", "");
        const int swept = model[0] && k < ncmp && strcmp(jr_str_or(&cmp->items[k], "model", ""), model) == 0;
        k += swept;
        if (r)
            rd_row_attr(r, "model", swept ? model : "");
    }
    const struct jr_value *lim = jr_get(&j->root, "limit_overall");
    struct rd_row *r = rdoc_row(d, "", "fit");
    if (r) {
        rd_row_key(r, "role", NULL, "per-n minimax k(n): the family's limit");
        snprintf(text, sizeof text, "%.120s", grid);
        rd_row_key(r, "grid", NULL, text);
        rd_row_metric(d, r, "max_rel", "1", RD_LOWER, 0, jr_num_or_nan(lim, "max_rel"));
        rd_row_metric(d, r, "at_n", "1", RD_NEITHER, 0, jr_num_or_nan(lim, "at_n"));
    }
    for (size_t i = 0; i < ncmp; ++i) {
        const char *model = jr_str_or(&cmp->items[i], "model", "?");
        if (strncmp(model, "quad:", 5) == 0)
            continue;   /* the fitted model itself: its label moves with its coefficients */
        struct rd_row *c = fit_row(d, &cmp->items[i], model, grid, 0);
        if (c)
            rd_row_attr(c, "model", model);
    }
    rdoc_text(d, "verdict", jr_str_or(jr_get(&j->root, "verdict"), "text", ""));
    return 0;
}

/* The upgrade of brdfbench.field/1: the row field_report.c's field_rows() makes, from the
 * peaks and the check block of the layout. */
static int upgrade_field_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const char *model, *ref;
    const struct jr_value *grid;
    if (jr_need_str(j, &j->root, "model", &model, err, errlen) || jr_need_str(j, &j->root, "reference", &ref, err, errlen) ||
        jr_need(j, &j->root, "grid", JR_OBJ, &grid, err, errlen))
        return 2;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%.0f n x %.0f x, n %g..%g log-spaced, attenuation to %g x_e", jr_num_or_nan(grid, "rows"),
             jr_num_or_nan(grid, "cols"), jr_num_or_nan(grid, "n_min"), jr_num_or_nan(grid, "n_max"),
             jr_num_or_nan(grid, "u_max"));
    rd_ctx_put(&d->ctx, "heatmap grid", text);
    struct rd_row *r = rdoc_row(d, NULL, model);
    if (!r)
        return 0;
    rd_row_key(r, "model", NULL, model);
    rd_row_attr(r, "reference", ref);
    r->line = j->root.line;
    static const struct {
        const char *path, *name, *unit;
        int direction;
    } m[] = {
        { "epicentre_max_rel.value", "epicentre.max_rel", "1", RD_LOWER },
        { "epicentre_max_rel.n", "epicentre.max_rel.at_n", "1", RD_NEITHER },
        { "epicentre_max_rel.x", "epicentre.max_rel.at_x", "rad", RD_NEITHER },
        { "attenuation_max_abs.value", "attenuation.max_abs", "1", RD_LOWER },
        { "attenuation_max_abs.n", "attenuation.max_abs.at_n", "1", RD_NEITHER },
        { "attenuation_max_abs.x", "attenuation.max_abs.at_x", "rad", RD_NEITHER },
        { "check.max_rel_diff", "check.max_rel_diff", "1", RD_LOWER },
        { "check.max_abs_diff", "check.max_abs_diff", "1", RD_LOWER },
    };
    for (size_t k = 0; k < sizeof m / sizeof m[0]; ++k) {
        const struct jr_value *v = path_get(&j->root, m[k].path);
        rd_row_metric(d, r, m[k].name, m[k].unit, m[k].direction, 0, v && v->type == JR_NUM ? v->num : NAN);
    }
    return 0;
}

/* A family point's figures from its layout object: its parameters (the members that are not
 * one of the known figures), cap, errors and where they are reached; as family_rows() in
 * host/measure/fit/fit_report.c declares them. */
static void family_point(struct rdoc *d, struct rd_row *r, const struct jr_value *o, const char *cap_key)
{
    static const char *const known[] = { "status", "reason", "cap", "cap_reason", "max_abs_cap", "max_rel",
                                         "max_rel_at_n", "max_abs", "max_abs_at_n", "model" };
    for (size_t k = 0; k < o->count; ++k) {
        size_t i = 0;
        while (i < sizeof known / sizeof known[0] && strcmp(o->keys[k], known[i]) != 0)
            ++i;
        if (i == sizeof known / sizeof known[0] && o->items[k].type == JR_NUM)
            rd_row_metric(d, r, o->keys[k], "1", RD_NEITHER, 0, o->items[k].num);
    }
    const struct jr_value *cap = cap_key ? jr_get(o, cap_key) : NULL;
    if (cap && cap->type == JR_NUM)
        rd_row_metric(d, r, "cap", "1", RD_NEITHER, 0, cap->num);
    static const struct { const char *key, *name; int direction; } fig[] = {
        { "max_rel", "max_rel", RD_LOWER }, { "max_rel_at_n", "max_rel.at_n", RD_NEITHER },
        { "max_abs", "max_abs", RD_LOWER }, { "max_abs_at_n", "max_abs.at_n", RD_NEITHER },
    };
    for (size_t k = 0; k < sizeof fig / sizeof fig[0]; ++k) {
        const struct jr_value *v = jr_get(o, fig[k].key);
        if (v || fig[k].direction == RD_LOWER)
            rd_row_metric(d, r, fig[k].name, "1", fig[k].direction, 0, v && v->type == JR_NUM ? v->num : NAN);
    }
}

/* The upgrade of brdfbench.fit_family/1 (`fit --family`): the rows family_rows() makes. */
static int upgrade_fit_family_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const char *family;
    if (jr_need_str(j, &j->root, "family", &family, err, errlen))
        return 2;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%s, objective %s", family, jr_str_or(&j->root, "objective", "max_rel"));
    rd_ctx_put(&d->ctx, "family fit", text);
    static const char *const names[3] = { "fit", "min_max_rel", "min_max_abs" };
    for (int i = 0; i < 3; ++i) {
        const struct jr_value *o = jr_get(&j->root, names[i]);
        if (!o || o->type != JR_OBJ)
            continue;
        struct rd_row *r = rdoc_row(d, NULL, family);
        if (!r)
            return 0;
        rd_row_key(r, "point", NULL, names[i]);
        row_status(r, o);
        family_point(d, r, o, "cap");
    }
    const struct jr_value *tr = jr_get(&j->root, "tradeoff");
    for (size_t k = 0; tr && tr->type == JR_ARR && k < tr->count; ++k) {
        if (tr->items[k].type != JR_OBJ)
            continue;
        struct rd_row *r = rdoc_row(d, NULL, family);
        if (!r)
            return 0;
        snprintf(text, sizeof text, "tradeoff %zu of %zu", k + 1, tr->count);
        rd_row_key(r, "point", NULL, text);
        r->line = tr->items[k].line;
        family_point(d, r, &tr->items[k], "max_abs_cap");
    }
    const struct jr_value *dev = jr_get(&j->root, "device");
    if (dev && dev->type == JR_OBJ) {
        struct rd_row *r = rdoc_row(d, NULL, family);
        if (!r)
            return 0;
        rd_row_key(r, "point", NULL, "device");
        if (jr_get(dev, "model"))
            rd_row_attr(r, "model", jr_str_or(dev, "model", ""));
        row_status(r, dev);
        if (r->ok)
            family_point(d, r, dev, NULL);
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
    /* rows are checked by what each metric declares (rdoc.c); only a layout is checked by its
       members' names (compare_check.h), since nothing else says what they are */
    if (strcmp(schema, ROWS_SCHEMA) == 0)
        return rdoc_from_rows_json(j, d, err, errlen) ? 2 : 0;
    layout_reader layout;
    int kind = kind_of_schema(schema, &layout);
    if (kind < 0) {
        char accepted[RD_KIND_COUNT * 32 + 32] = "";
        for (int k = 0; k < RD_KIND_COUNT; ++k)
            snprintf(accepted + strlen(accepted), sizeof accepted - strlen(accepted), "%s, ", kinds[k].schema);
        snprintf(err, errlen, "%s: schema \"%.60s\" is not a result file with figures (accepted: %s%s)", j->name,
                 schema, accepted, ROWS_SCHEMA);
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
    /* rows are checked as they are read; q_sweep.json's layout holds its figures as arrays by Q
       under error names (max_rel): its upgrade checks them itself */
    if (!rows && kind != RD_KIND_Q_SWEEP && compare_check_doc(j, err, errlen))
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
        /* a file two kinds share (fit.json: a fit, or a family fit) is read once, and is of the
           kind its schema names; a kind of one file per model is read only when named */
        int seen = 0;
        for (int e = 0; e < k; ++e)
            seen |= strcmp(kinds[e].file, kinds[k].file) == 0;
        if (seen || strstr(kinds[k].file, "MODEL") || path_join(file, sizeof file, dir, kinds[k].file) ||
            stat(file, &st) != 0)
            continue;
        if (only >= 0 && strcmp(kinds[only].file, kinds[k].file) != 0)
            continue;
        if (rdoc_read_file(file, &d[*found], err, errlen)) {
            for (int i = 0; i < *found; ++i)
                rdoc_free(&d[i]);
            return 2;
        }
        if (only >= 0 && strcmp(d[*found].kind, kinds[only].name) != 0) {
            rdoc_free(&d[*found]);
            continue;
        }
        ++*found;
    }
    return 0;
}
