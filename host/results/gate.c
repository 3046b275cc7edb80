/* gate.c - the gates file, the sweeps it needs and the judgement (gate.h); the reports are
 * written by gate_report.c. */
#define _DEFAULT_SOURCE   /* realpath */
#define _POSIX_C_SOURCE 200809L
#include "gate.h"
#include "gate_internal.h"
#include "energy.h"
#include "exitcodes.h"
#include "infile.h"
#include "jsonr.h"
#include "measured.h"
#include "outdir.h"
#include "programs.h"
#include "rdoc_read.h"
#include "usermodel.h"
#include "hemisphere.h"

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const struct {
    const char *name, *meaning;
} metrics[GATE_METRIC_COUNT] = {
    { "epicentre.max_rel", "max relative error |f - f_ref| / f_ref over the epicentre zone" },
    { "epicentre.max_abs", "max absolute error |f - f_ref| over the epicentre zone" },
    { "attenuation.max_abs", "max absolute error |f - f_ref| over the attenuation zone" },
    { "whole.max_abs", "max absolute error |f - f_ref| over x in [0, pi/2]" },
    { "energy.max_abs_dev", "max over n of |2 pi int_0^(pi/2) f(cos x, n) cos x sin x dx - 1|" },
    { "albedo.max", "max directional albedo over n and theta_i = 0, 5, ..., 85 degrees (normalised and "
                    "microfacet models; device quadrature of host/measure/energy/energy.h)" },
    { "invalid.count", "model values that were NaN, Inf or negative in the sweep" },
    { "measured.rms", "the lobe's RMS error against the measured material of \"measured\" (a MERL file), at the "
                      "Blinn-Phong fit's n and scale (brdfbench measured's err_measured)" },
    { "hemisphere.epicentre.max_rel", "a full BRDF over the hemisphere (N.L > 0, N.V > 0): max relative error where "
                                      "f_ref >= e^-0.511 of its peak, over n in the gate's range (8 values)" },
    { "hemisphere.attenuation.max_abs", "a full BRDF over the hemisphere: max absolute error where f_ref is below "
                                        "e^-0.511 of its peak" },
    { "hemisphere.whole.max_abs", "a full BRDF over the hemisphere: max absolute error over every sample" },
    { "hemisphere.rms", "a full BRDF over the hemisphere: RMS of cos(theta_i) (f - f_ref) over dw_i dw_o, its "
                        "largest over n" },
};

const char *gate_metric_name(enum gate_metric m) { return metrics[m].name; }

int gate_metric_is_hemisphere(enum gate_metric m)
{
    return m == GATE_HEMI_EPI_REL || m == GATE_HEMI_ATT_ABS || m == GATE_HEMI_WHOLE_ABS || m == GATE_HEMI_RMS;
}

int gate_metric_needs_sweep(enum gate_metric m)
{
    return m != GATE_ENERGY_MAX_DEV && m != GATE_ALBEDO_MAX && m != GATE_MEASURED_RMS && !gate_metric_is_hemisphere(m);
}

#define GATE_ALBEDO_MAX_N 1000       /* values of n of an albedo gate (each costs 18 quadratures) */

/* ---- parsing the gates file ------------------------------------------------------------ */

static const char *type_word(enum jr_type t)
{
    static const char *w[] = { "null", "a boolean", "a number", "a string", "an array", "an object" };
    return w[t];
}

/* A member's value of the expected type, or NULL when absent. Returns 0 or EXIT_USAGE. */
static int member(const struct jr_doc *d, const struct jr_value *obj, const char *key, enum jr_type type,
                  const char *where, const struct jr_value **out, char *err, size_t errlen)
{
    *out = jr_get(obj, key);
    if (*out && (*out)->type != type)
        return jr_fail(d, *out, err, errlen, "%s\"%s\" is %s, %s expected", where, key, type_word((*out)->type),
                       type_word(type));
    return 0;
}

static void list_metrics(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int m = 0; m < GATE_METRIC_COUNT && used < len; ++m)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", m ? ", " : "", metrics[m].name);
}

/* A path named in the gates file: relative paths are relative to the gates file's folder. */
static int resolve_path(char *out, size_t outlen, const char *base_dir, const char *path)
{
    int n = (path[0] == '/' || !base_dir || !*base_dir) ? snprintf(out, outlen, "%s", path)
                                                          : snprintf(out, outlen, "%s/%s", base_dir, path);
    return (n < 0 || (size_t)n >= outlen) ? -1 : 0;
}

/* A model file is a program run on the host (compiled by libtcc into this process, and by
 * the OpenCL driver): a gates file may name only the model files in its own folder or below
 * it, unless the command line allows others (outside_allowed, passed down from gate_set_load). */

/* 1 when path (which exists) lies in base_dir or below it, links resolved. */
static int lies_inside(const char *path, const char *base_dir)
{
    char rp[PATH_MAX], rb[PATH_MAX];
    if (!realpath(base_dir, rb) || !realpath(path, rp))
        return 0;
    size_t n = strlen(rb);
    if (n == 1 && rb[0] == '/')
        return 1;
    return strncmp(rp, rb, n) == 0 && rp[n] == '/';
}

/* The user model a gate declares with "model_file" or "expression", registered. */
static int gate_user_model(const struct jr_doc *d, const char *where,
                           const struct jr_value *model_v, const struct jr_value *file_v,
                           const struct jr_value *expr_v, const char *base_dir, int outside_allowed, char *err,
                           size_t errlen)
{
    char msg[1024];
    if (file_v && expr_v)
        return jr_fail(d, expr_v, err, errlen, "%sgive either \"model_file\" or \"expression\", not both", where);
    if (file_v) {
        char path[4096];
        const struct user_model *um = NULL;
        if (!file_v->str[0] || resolve_path(path, sizeof path, base_dir, file_v->str))
            return jr_fail(d, file_v, err, errlen, "%s\"model_file\" is empty or too long", where);
        struct stat st;
        if (!outside_allowed && stat(path, &st) == 0 && !lies_inside(path, base_dir && *base_dir ? base_dir : "."))
            return jr_fail(d, file_v, err, errlen,
                           "%s\"model_file\" '%.200s' lies outside the gates file's folder %s; a model file is a "
                           "program that brdfbench runs on the host, so a gates file names only those in its own "
                           "folder (--allow-outside-model-files lifts this)", where, file_v->str,
                           base_dir && *base_dir ? base_dir : ".");
        if (usermodel_load_file(path, &um, msg, sizeof msg))
            return jr_fail(d, file_v, err, errlen, "%s%s", where, msg);
        /* "model" names the model of that file (with parameters, if any). */
        char id[USERMODEL_NAME_MAX + 2];
        snprintf(id, sizeof id, "%.*s", (int)strcspn(model_v->str, ":"), model_v->str);
        if (strcmp(id, um->name) != 0)
            return jr_fail(d, model_v, err, errlen, "%smodel '%.60s' is not the model of %.200s (it declares '%s')",
                           where, id, path, um->name);
        return 0;
    }
    if (expr_v) {
        char text[USERMODEL_NAME_MAX + USERMODEL_MAX_EXPR + 8];
        if (strchr(model_v->str, ':'))
            return jr_fail(d, model_v, err, errlen, "%san expression model takes no parameters (\"model\": a name)",
                           where);
        const struct model_info *taken = models_find(model_v->str);
        if (usermodel_of_info(taken) && !usermodel_of_info(taken)->from_file &&
            strcmp(usermodel_of_info(taken)->formula, expr_v->str) == 0)
            return 0;   /* the same expression model, declared by an earlier gate */
        int tn = snprintf(text, sizeof text, "%s=%s", model_v->str, expr_v->str);
        if (tn < 0 || (size_t)tn >= sizeof text)
            return jr_fail(d, expr_v, err, errlen, "%s\"expression\" is longer than %d characters", where,
                           USERMODEL_MAX_EXPR);
        struct user_model *um = NULL;
        if (usermodel_parse_expression(text, &um, msg, sizeof msg) || usermodel_register(um, msg, sizeof msg))
            return jr_fail(d, expr_v, err, errlen, "%s%s", where, msg);
        return 0;
    }
    return 0;
}

/* Every member of a gate object is one of the known keys. */
static int gate_known_members(const struct jr_doc *d, const struct jr_value *gv, const char *where, char *err,
                              size_t errlen)
{
    static const char *keys[] = { "model", "model_file", "expression", "metric", "n_min", "n_max", "n_step",
                                  "samples", "min", "max", "name", "claimed", "note", "accept_device_disagreement",
                                  "measured", "reference", NULL };
    for (size_t k = 0; k < gv->count; ++k) {
        int known = 0;
        for (int j = 0; keys[j] && !known; ++j)
            known = strcmp(gv->keys[k], keys[j]) == 0;
        if (!known)
            return jr_fail(d, &gv->items[k], err, errlen,
                           "%sunknown member \"%.40s\" (accepted: model, model_file, expression, metric, n_min, "
                           "n_max, n_step, samples, min, max, name, claimed, note, accept_device_disagreement, measured, "
                           "reference)", where,
                           gv->keys[k]);
    }
    return 0;
}

/* The gate's metric (metric_v) and what it needs: a model albedo.max can take, and for
   measured.rms the "measured" file. */
static int gate_metric(const struct jr_doc *d, const struct jr_value *gv, const struct jr_value *metric_v,
                       const char *where, const char *base_dir, int outside_allowed, struct gate *g, char *err,
                       size_t errlen)
{
    char msg[1024];
    const struct jr_value *v;
    int metric = -1;
    for (int m = 0; m < GATE_METRIC_COUNT; ++m)
        if (strcmp(metric_v->str, metrics[m].name) == 0)
            metric = m;
    if (metric < 0) {
        list_metrics(msg, sizeof msg);
        return jr_fail(d, metric_v, err, errlen, "%sunknown metric '%.60s' (accepted: %s)", where, metric_v->str, msg);
    }
    g->metric = (enum gate_metric)metric;
    if (gate_metric_is_hemisphere(g->metric) && !hemisphere_applies(&g->model))
        return jr_fail(d, metric_v, err, errlen, "%s%s needs a full BRDF (a user model of L, V, N, ct-ggx, "
                       "ct-beckmann, brady or he; %s is a lobe)", where, metrics[g->metric].name, g->model.label);
    if (g->metric == GATE_ALBEDO_MAX && albedo_mode_of(g->model.info) < 0)
        return jr_fail(d, metric_v, err, errlen, "%salbedo.max needs a normalised or microfacet model (%s is %s)",
                       where, g->model.info->id, model_family_name(g->model.info->family));

    /* "reference": what a hemisphere.* gate measures its full BRDF against (as accuracy's
       --reference: a built-in with parameters, or a full user model the gates file declares) */
    if (member(d, gv, "reference", JR_STR, where, &v, err, errlen))
        return EXIT_USAGE;
    if (v && !gate_metric_is_hemisphere(g->metric))
        return jr_fail(d, v, err, errlen, "%s\"reference\" is read only by the hemisphere.* metrics (this gate's is %s)",
                       where, metrics[g->metric].name);
    if (v) {
        if (model_spec_parse(v->str, &g->reference, msg, sizeof msg))
            return jr_fail(d, v, err, errlen, "%s\"reference\": %s", where, msg);
        if (!hemisphere_reference_ok(&g->reference))
            return jr_fail(d, v, err, errlen, "%s\"reference\": %s is a lobe of c and n, not a BRDF of (L, V) "
                           "(accepted: a built-in, e.g. ct-ggx:F0=0.04 or ggx, or a full user model of the gates "
                           "file)", where, g->reference.label);
        g->has_reference = 1;
    }
    if (member(d, gv, "measured", JR_STR, where, &v, err, errlen))
        return EXIT_USAGE;
    if (v && g->metric != GATE_MEASURED_RMS)
        return jr_fail(d, v, err, errlen, "%s\"measured\" is read only by the metric measured.rms (this gate's is %s)",
                       where, metrics[g->metric].name);
    if (!v && g->metric == GATE_MEASURED_RMS)
        return jr_fail(d, metric_v, err, errlen, "%smeasured.rms needs \"measured\": the path of a MERL .binary file",
                       where);
    if (v && (!v->str[0] || resolve_path(g->measured_path, sizeof g->measured_path, base_dir, v->str)))
        return jr_fail(d, v, err, errlen, "%s\"measured\" is empty or too long", where);
    /* A gates file reads only the materials of its own folder, as it runs only the model
       files there: a CI's gates file from a pull request may not read /etc/passwd into the log. */
    struct stat st;
    if (v && !outside_allowed && stat(g->measured_path, &st) == 0 &&
        !lies_inside(g->measured_path, base_dir && *base_dir ? base_dir : "."))
        return jr_fail(d, v, err, errlen,
                       "%s\"measured\" '%.200s' lies outside the gates file's folder %s; a gates file reads only "
                       "the materials in its own folder (--allow-outside-model-files lifts this)", where, v->str,
                       base_dir && *base_dir ? base_dir : ".");
    return 0;
}

/* The gate's grid (the accuracy command's defaults where not given), its bounds and the
   claimed value. */
static int gate_grid_bounds(const struct jr_doc *d, const struct jr_value *gv, const char *where, struct gate *g,
                            char *err, size_t errlen)
{
    char msg[1024];
    g->grid.n_min = 2.0;
    g->grid.n_max = 1000.0;
    g->grid.n_step = 1.0;
    g->grid.samples = ACC_DEFAULT_SAMPLES;
    static const char *num_keys[] = { "n_min", "n_max", "n_step", "samples", "min", "max", "claimed" };
    const struct jr_value *nv[7];
    for (int k = 0; k < 7; ++k)
        if (member(d, gv, num_keys[k], JR_NUM, where, &nv[k], err, errlen))
            return EXIT_USAGE;
    if (nv[0] && !(nv[0]->num >= ACC_MIN_N && nv[0]->num <= ACC_MAX_N))
        return jr_fail(d, nv[0], err, errlen, "%s\"n_min\" %.10g is out of range (accepted: %g <= n_min <= %g)", where,
                       nv[0]->num, ACC_MIN_N, ACC_MAX_N);
    if (nv[1] && !(nv[1]->num >= ACC_MIN_N && nv[1]->num <= ACC_MAX_N))
        return jr_fail(d, nv[1], err, errlen, "%s\"n_max\" %.10g is out of range (accepted: %g <= n_max <= %g)", where,
                       nv[1]->num, ACC_MIN_N, ACC_MAX_N);
    if (nv[2] && !(nv[2]->num > 0 && nv[2]->num <= ACC_MAX_N))
        return jr_fail(d, nv[2], err, errlen, "%s\"n_step\" %.10g is out of range (accepted: 0 < n_step <= %g)", where,
                       nv[2]->num, ACC_MAX_N);
    if (nv[3] && !(nv[3]->num >= ACC_MIN_SAMPLES && nv[3]->num <= (double)ACC_MAX_SAMPLES &&
                   nv[3]->num == floor(nv[3]->num) && fmod(nv[3]->num, 16.0) == 0))
        return jr_fail(d, nv[3], err, errlen, "%s\"samples\" %.10g is out of range (accepted: a multiple of 16 in "
                       "[%d, %ld])", where, nv[3]->num, ACC_MIN_SAMPLES, ACC_MAX_SAMPLES);
    if (nv[0]) g->grid.n_min = nv[0]->num;
    if (nv[1]) g->grid.n_max = nv[1]->num;
    if (nv[2]) g->grid.n_step = nv[2]->num;
    if (nv[3]) g->grid.samples = (long)nv[3]->num;
    if (!(g->grid.n_min < g->grid.n_max))
        return jr_fail(d, nv[0] ? nv[0] : (nv[1] ? nv[1] : gv), err, errlen,
                       "%s\"n_min\" (%.10g) must be below \"n_max\" (%.10g)", where, g->grid.n_min, g->grid.n_max);
    if (accuracy_grid_check(&g->grid, NULL, msg, sizeof msg))
        return jr_fail(d, gv, err, errlen, "%sgrid: %s", where, msg);
    if (g->metric == GATE_ALBEDO_MAX && accuracy_grid_count(&g->grid) > GATE_ALBEDO_MAX_N)
        return jr_fail(d, gv, err, errlen, "%salbedo.max over %ld values of n (accepted: at most %d; raise \"n_step\")",
                       where, accuracy_grid_count(&g->grid), GATE_ALBEDO_MAX_N);
    if (!nv[4] && !nv[5])
        return jr_fail(d, gv, err, errlen, "%sa bound is missing: give \"max\" (and optionally \"min\")", where);
    if (nv[4]) { g->has_min = 1; g->min = nv[4]->num; }
    if (nv[5]) { g->has_max = 1; g->max = nv[5]->num; }
    if (g->has_min && g->has_max && !(g->min <= g->max))
        return jr_fail(d, nv[4], err, errlen, "%s\"min\" (%.10g) is above \"max\" (%.10g)", where, g->min, g->max);
    if (nv[6]) { g->has_claimed = 1; g->claimed = nv[6]->num; }
    return 0;
}

/* The gate's name (or one made of its model, metric and grid), note and
   accept_device_disagreement. */
static int gate_labels(const struct jr_doc *d, const struct jr_value *gv, const char *where, struct gate *g,
                       char *err, size_t errlen)
{
    const struct jr_value *v;
    if (member(d, gv, "name", JR_STR, where, &v, err, errlen))
        return EXIT_USAGE;
    if (v) {
        if (!v->str[0] || strlen(v->str) >= sizeof g->name)
            return jr_fail(d, v, err, errlen, "%s\"name\" must have 1 to %zu characters", where, sizeof g->name - 1);
        snprintf(g->name, sizeof g->name, "%s", v->str);
    } else {
        snprintf(g->name, sizeof g->name, "%s %s n=[%g,%g]", g->model.label, metrics[g->metric].name,
                 g->grid.n_min, g->grid.n_max);
    }
    if (member(d, gv, "note", JR_STR, where, &v, err, errlen))
        return EXIT_USAGE;
    if (v)
        snprintf(g->note, sizeof g->note, "%s", v->str);
    if (member(d, gv, "accept_device_disagreement", JR_BOOL, where, &v, err, errlen))
        return EXIT_USAGE;
    g->accept_device_disagreement = v && v->num != 0;
    return 0;
}

static int parse_gate(const struct jr_doc *d, const struct jr_value *gv, int index, const char *base_dir,
                      int outside_allowed, struct gate *g, char *err, size_t errlen)
{
    char where[32], msg[1024];
    snprintf(where, sizeof where, "gate %d: ", index + 1);
    memset(g, 0, sizeof *g);
    g->line = gv->line;
    g->col = gv->col;
    if (gv->type != JR_OBJ)
        return jr_fail(d, gv, err, errlen, "%sa gate is an object, found %s", where, type_word(gv->type));
    if (gate_known_members(d, gv, where, err, errlen))
        return EXIT_USAGE;
    const struct jr_value *model_v, *file_v, *expr_v, *metric_v;
    if (member(d, gv, "model", JR_STR, where, &model_v, err, errlen) ||
        member(d, gv, "model_file", JR_STR, where, &file_v, err, errlen) ||
        member(d, gv, "expression", JR_STR, where, &expr_v, err, errlen) ||
        member(d, gv, "metric", JR_STR, where, &metric_v, err, errlen))
        return EXIT_USAGE;
    if (!model_v)
        return jr_fail(d, gv, err, errlen, "%s\"model\" is missing (e.g. \"fq2\" or \"fq:Q=0.64\")", where);
    if (!metric_v) {
        list_metrics(msg, sizeof msg);
        return jr_fail(d, gv, err, errlen, "%s\"metric\" is missing (accepted: %s)", where, msg);
    }
    if (gate_user_model(d, where, model_v, file_v, expr_v, base_dir, outside_allowed, err, errlen))
        return EXIT_USAGE;
    if (model_spec_parse(model_v->str, &g->model, msg, sizeof msg))
        return jr_fail(d, model_v, err, errlen, "%s%s", where, msg);
    if (gate_metric(d, gv, metric_v, where, base_dir, outside_allowed, g, err, errlen) ||
        gate_grid_bounds(d, gv, where, g, err, errlen) || gate_labels(d, gv, where, g, err, errlen))
        return EXIT_USAGE;
    g->measured = g->at_n = g->at_x = NAN;
    g->invalid_n = g->invalid_x = NAN;
    g->baseline = g->baseline_change = NAN;
    return 0;
}

int gate_set_parse_text(const char *text, size_t len, const char *name, const char *base_dir, int outside_allowed,
                        struct gate_set *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", name);
    out->tolerance = GATE_DEFAULT_TOLERANCE;
    struct jr_doc doc;
    if (len == 0) {
        snprintf(err, errlen, "%s: empty file (expected {\"gates\": [...]}, see docs/gates.md)", name);
        return EXIT_USAGE;
    }
    if (jr_parse_text(text, len, name, &doc, err, errlen))
        return EXIT_USAGE;
    int rc = 0;
    const struct jr_value *root = &doc.root, *gates, *v;
    if (root->type != JR_OBJ) {
        rc = jr_fail(&doc, root, err, errlen, "the gates file is an object {\"gates\": [...]}, found %s",
                     type_word(root->type));
        goto done;
    }
    for (size_t k = 0; k < root->count; ++k)
        if (strcmp(root->keys[k], "gates") != 0 && strcmp(root->keys[k], "description") != 0 &&
            strcmp(root->keys[k], "schema") != 0 && strcmp(root->keys[k], "timeout") != 0) {
            rc = jr_fail(&doc, &root->items[k], err, errlen,
                         "unknown member \"%.40s\" (accepted: gates, description, schema, timeout)", root->keys[k]);
            goto done;
        }
    /* "timeout": the deadline of each launch, as --timeout (which wins when both are given). */
    if ((rc = member(&doc, root, "timeout", JR_NUM, "", &v, err, errlen)) != 0)
        goto done;
    if (v && !(v->num >= 0.01 && v->num <= CLSESSION_MAX_TIMEOUT)) {
        rc = jr_fail(&doc, v, err, errlen, "\"timeout\" %g is out of range (accepted: seconds in [0.01, %g])", v->num,
                     CLSESSION_MAX_TIMEOUT);
        goto done;
    }
    if (v)
        clsession_set_timeout(v->num, TIMEOUT_FILE);
    if ((rc = member(&doc, root, "schema", JR_STR, "", &v, err, errlen)) != 0)
        goto done;
    if (v && strcmp(v->str, GATES_SCHEMA) != 0) {
        rc = jr_fail(&doc, v, err, errlen, "schema '%.60s' is not supported (accepted: %s)", v->str, GATES_SCHEMA);
        goto done;
    }
    if ((rc = member(&doc, root, "description", JR_STR, "", &v, err, errlen)) != 0)
        goto done;
    if (v)
        snprintf(out->description, sizeof out->description, "%s", v->str);
    if ((rc = member(&doc, root, "gates", JR_ARR, "", &gates, err, errlen)) != 0)
        goto done;
    if (!gates) {
        rc = jr_fail(&doc, root, err, errlen, "member \"gates\" is missing (an array of gates)");
        goto done;
    }
    if (gates->count == 0 || gates->count > GATE_MAX_GATES) {
        rc = jr_fail(&doc, gates, err, errlen, "\"gates\" has %zu gates (accepted: 1 to %d)", gates->count,
                     GATE_MAX_GATES);
        goto done;
    }
    out->gates = calloc(gates->count, sizeof *out->gates);
    if (!out->gates) {
        snprintf(err, errlen, "%s: out of memory", name);
        rc = EXIT_RUNTIME;
        goto done;
    }
    for (size_t i = 0; i < gates->count; ++i) {
        if ((rc = parse_gate(&doc, &gates->items[i], (int)i, base_dir, outside_allowed, &out->gates[i], err,
                             errlen)) != 0)
            goto done;
        out->count++;
    }
done:
    jr_free(&doc);
    if (rc) {
        free(out->gates);
        out->gates = NULL;
        out->count = 0;
    }
    return rc;
}

int gate_set_load(const char *path, int outside_allowed, struct gate_set *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    /* named on the command line: a pipe is accepted (gate <(make-gates)), a device is not */
    char *buf = NULL, why[256];
    size_t len = 0;
    const size_t max = 4u << 20;
    int r = infile_read(path, INFILE_PIPE_OK, max, &buf, &len, why, sizeof why);
    if (r == -2) {
        snprintf(err, errlen, "%s: out of memory", path);
        return EXIT_RUNTIME;
    }
    if (r != 0) {
        if (strncmp(why, "is a folder", 11) == 0)
            snprintf(err, errlen, "%s: is a folder, not a gates file", path);
        else if (strncmp(why, "is larger", 9) == 0)
            snprintf(err, errlen, "%s: larger than 4 MiB", path);
        else
            snprintf(err, errlen, "%s: cannot read the gates file: %s", path, why);
        return EXIT_USAGE;
    }
    char base[4096];
    snprintf(base, sizeof base, "%s", path);
    char *slash = strrchr(base, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(base, sizeof base, ".");
    if (slash == base)
        snprintf(base, sizeof base, "/");
    int rc = gate_set_parse_text(buf, len, path, base, outside_allowed, out, err, errlen);
    free(buf);
    return rc;
}

void gate_set_free(struct gate_set *g)
{
    free(g->gates);
    g->gates = NULL;
    g->count = 0;
}

/* ---- the baseline ---------------------------------------------------------------------- */

int gate_same_number(double a, double b)
{
    return fabs(a - b) <= 1e-9 * fmax(1.0, fabs(a));
}

/* A row's attribute as a number (NAN when it has none). */
static double row_number(const struct rd_row *r, const char *name)
{
    const char *v = rd_row_key_value(r, name);
    return v ? strtod(v, NULL) : NAN;
}

/* The baseline's figure for gate gt, or why there is none (its baseline_note). */
static void baseline_of(struct gate *gt, const struct rdoc *doc)
{
    gt->baseline_status = GATE_BASELINE_MISSING;
    snprintf(gt->baseline_note, sizeof gt->baseline_note, "no entry for %s over n %g..%g", gt->model.label,
             gt->grid.n_min, gt->grid.n_max);
    /* every row of an accuracy.json is on the same grid: its step is the first row's */
    double base_step = doc->nrows > 0 ? row_number(&doc->rows[0], "n_step") : NAN;
    if (!gate_same_number(base_step, gt->grid.n_step)) {
        snprintf(gt->baseline_note, sizeof gt->baseline_note, "its grid has n_step %g, the gate's %g", base_step,
                 gt->grid.n_step);
        return;
    }
    for (int k = 0; k < doc->nrows; ++k) {
        const struct rd_row *r = &doc->rows[k];
        const char *label = rd_row_key_value(r, "label");
        if (!label || strcmp(label, gt->model.label) != 0 || !gate_same_number(row_number(r, "n_min"), gt->grid.n_min) ||
            !gate_same_number(row_number(r, "n_max"), gt->grid.n_max))
            continue;
        /* the gate's metric is the row's metric of the same name, as the row declares it: a
           baseline bounds a figure where lower is better */
        const struct rd_metric *m = rd_row_find(r, metrics[gt->metric].name);
        if (!r->ok)   /* a failed figure is no bound to hold a run to */
            snprintf(gt->baseline_note, sizeof gt->baseline_note, "the entry of %s is %.40s (line %d), not used",
                     gt->model.label, r->status, r->line);
        else if (m && m->direction != RD_LOWER)
            snprintf(gt->baseline_note, sizeof gt->baseline_note, "the entry of %.60s (line %d) declares %.40s %s is "
                     "better, not used as a bound", gt->model.label, r->line, m->name, rd_direction_name(m->direction));
        else if (m && isfinite(m->value)) {
            gt->baseline = m->value;
            gt->baseline_status = GATE_BASELINE_OK;   /* judged after the run */
        } else
            snprintf(gt->baseline_note, sizeof gt->baseline_note, "the entry of %s (line %d) has no number for "
                     "this metric, not used", gt->model.label, r->line);
        return;
    }
}

int gate_set_baseline(struct gate_set *g, const char *path, double tolerance, char *err, size_t errlen)
{
    char file[sizeof g->baseline_path];
    struct stat st;
    if (stat(path, &st) != 0) {
        snprintf(err, errlen, "--baseline: cannot read %s: %s", path, strerror(errno));
        return EXIT_USAGE;
    }
    if (S_ISDIR(st.st_mode)) {
        if (path_join(file, sizeof file, path, "accuracy.json")) {
            snprintf(err, errlen, "--baseline: path too long");
            return EXIT_USAGE;
        }
    } else {
        snprintf(file, sizeof file, "%s", path);
    }
    struct rdoc doc;
    char msg[1024];
    if (rdoc_read_file(file, &doc, msg, sizeof msg)) {
        snprintf(err, errlen, "--baseline: %s", msg);
        return EXIT_USAGE;
    }
    int rc = 0;
    if (rd_kind_of_name(doc.kind) != RD_KIND_ACCURACY) {
        snprintf(err, errlen, "--baseline: %s: the figures of %s (schema %s), not an accuracy.json (schema %s expected)",
                 file, doc.file, doc.schema, ACCURACY_SCHEMA);
        rc = EXIT_USAGE;
        goto done;
    }
    snprintf(g->baseline_path, sizeof g->baseline_path, "%s", file);
    g->tolerance = tolerance;
    for (int i = 0; i < g->count; ++i)
        baseline_of(&g->gates[i], &doc);
done:
    rdoc_free(&doc);
    return rc;
}

