/* gate_report.c - the writing side of gate.c: one line per gate and the summary, the JUnit
 * XML and the JSON result (gate_report.h). */
#define _POSIX_C_SOURCE 200809L
#include "gate_report.h"
#include "context.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "outdir.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- reports --------------------------------------------------------------------------- */

static void bound_text(const struct gate *g, char *buf, size_t len)
{
    if (g->has_min && g->has_max)
        snprintf(buf, len, "[%.6g, %.6g]", g->min, g->max);
    else if (g->has_max)
        snprintf(buf, len, "max %.6g", g->max);
    else
        snprintf(buf, len, "min %.6g", g->min);
}

/* The one line of a gate, without the PASS/FAIL word. */
static void gate_line(const struct gate *g, char *buf, size_t len)
{
    char bound[96], where[96] = "", margin[64] = "", base[240] = "", claimed[64] = "";
    bound_text(g, bound, sizeof bound);
    char nt[32];
    accuracy_format_n(g->at_n, nt, sizeof nt);   /* as many digits as the float n needs */
    if (isfinite(g->at_n) && isfinite(g->at_x))
        snprintf(where, sizeof where, " at n=%s x=%.4g", nt, g->at_x);
    else if (isfinite(g->at_n))
        snprintf(where, sizeof where, " at n=%s", nt);
    if (isfinite(g->margin) && isfinite(g->margin_rel))
        snprintf(margin, sizeof margin, "; margin %+.3g (%+.3g%%)", g->margin, 100.0 * g->margin_rel);
    else if (isfinite(g->margin))
        snprintf(margin, sizeof margin, "; margin %+.3g", g->margin);
    if (g->baseline_status == GATE_BASELINE_OK || g->baseline_status == GATE_BASELINE_REGRESSION)
        snprintf(base, sizeof base, "; baseline %.6g (%+.3g%%)", g->baseline,
                 isfinite(g->baseline_change) ? 100.0 * g->baseline_change : 0.0);
    else if (g->baseline_status == GATE_BASELINE_MISSING)
        snprintf(base, sizeof base, "; baseline: %s", g->baseline_note[0] ? g->baseline_note : "no matching entry");
    if (g->has_claimed)
        snprintf(claimed, sizeof claimed, "; claimed %.6g", g->claimed);
    snprintf(buf, len, "%s: measured %.7g%s; bound %s%s%s%s%s%s", g->name, g->measured, where, bound, margin, base,
             claimed, g->reason[0] ? " -- " : "", g->reason);
}

void gate_set_print(FILE *f, const struct gate_set *gs)
{
    char line[1400];
    for (int i = 0; i < gs->count; ++i) {
        const struct gate *g = &gs->gates[i];
        gate_line(g, line, sizeof line);
        fprintf(f, "%s  %s\n", g->status == GATE_PASS ? "PASS" : g->status == GATE_FAIL ? "FAIL" : "----", line);
    }
    int failed = gate_set_failures(gs);
    fprintf(f, "%d gates: %d passed, %d failed (%s; %d sweeps)\n", gs->count, gs->count - failed, failed, gs->path,
            gs->sweeps_run);
}



/* Escaped text for an XML attribute or element; control characters (not allowed in XML 1.0)
   become spaces. */
static void xml_text(struct md_buf *b, const char *t)
{
    for (; *t; ++t) {
        switch (*t) {
        case '&': md_append(b, "&amp;", 5); break;
        case '<': md_append(b, "&lt;", 4); break;
        case '>': md_append(b, "&gt;", 4); break;
        case '"': md_append(b, "&quot;", 6); break;
        case '\'': md_append(b, "&apos;", 6); break;
        default:
            if ((unsigned char)*t < 0x20 && *t != '\n' && *t != '\t')
                md_append(b, " ", 1);
            else
                md_append(b, t, 1);
        }
    }
}

int gate_set_write_junit(const struct gate_set *gs, const char *path, const struct cl_session *s, char *err,
                         size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    int failed = gate_set_failures(gs);
    double total = 0;
    for (int i = 0; i < gs->count; ++i)
        total += gs->gates[i].seconds;
    char stamp[64];
    utc_now_iso(stamp, sizeof stamp);
    md_printf(&b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    md_printf(&b, "<testsuites name=\"brdfbench gate\" tests=\"%d\" failures=\"%d\" errors=\"0\" time=\"%.3f\">\n",
              gs->count, failed, total);
    md_printf(&b, "  <testsuite name=\"");
    xml_text(&b, gs->path);
    md_printf(&b, "\" tests=\"%d\" failures=\"%d\" errors=\"0\" skipped=\"0\" time=\"%.3f\" timestamp=\"", gs->count,
              failed, total);
    xml_text(&b, stamp);
    md_printf(&b, "\">\n    <properties>\n");
    const char *props[][2] = { { "device", s ? s->device_name : "" }, { "platform_version", s ? s->platform_version : "" },
                               { "brdfbench_version", BRDF_VERSION }, { "git_revision", brdf_git_revision },
                               { "baseline", gs->baseline_path } };
    for (size_t k = 0; k < sizeof props / sizeof props[0]; ++k) {
        if (!props[k][1][0])
            continue;
        md_printf(&b, "      <property name=\"%s\" value=\"", props[k][0]);
        xml_text(&b, props[k][1]);
        md_printf(&b, "\"/>\n");
    }
    md_printf(&b, "    </properties>\n");
    char line[1400];
    for (int i = 0; i < gs->count; ++i) {
        const struct gate *g = &gs->gates[i];
        gate_line(g, line, sizeof line);
        md_printf(&b, "    <testcase classname=\"brdfbench.gate.");
        xml_text(&b, g->model.info->id);
        md_printf(&b, "\" name=\"");
        xml_text(&b, g->name);
        md_printf(&b, "\" time=\"%.3f\">\n", g->seconds);
        if (g->status == GATE_FAIL) {
            const char *type = g->baseline_status == GATE_BASELINE_REGRESSION ? "regression"
                               : !isfinite(g->measured)                        ? "no_value"
                               : g->check.exceeded && !g->accept_device_disagreement ? "device_disagrees"
                               : g->invalid_count > 0 && g->metric != GATE_INVALID_COUNT ? "invalid_values"
                                                                               : "bound";
            md_printf(&b, "      <failure type=\"%s\" message=\"", type);
            xml_text(&b, g->reason);
            md_printf(&b, "\">");
            xml_text(&b, line);
            md_printf(&b, "</failure>\n");
        }
        md_printf(&b, "      <system-out>");
        xml_text(&b, line);
        md_printf(&b, "</system-out>\n    </testcase>\n");
    }
    md_printf(&b, "  </testsuite>\n</testsuites>\n");
    return md_write_file_free(&b, path, err, errlen);
}

/* A gate's measured figure, in the order gate.json holds it. */
#define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct gate, MEMBER, KEY)
static const struct jw_field figure_fields[] = {
    F(JWF_NUM, measured, "measured"), F(JWF_NUM, at_n, "at_n"), F(JWF_NUM, at_x, "at_x"),
    F(JWF_NUM, margin, "margin"), F(JWF_NUM, margin_rel, "margin_rel"), F(JWF_LLONG, invalid_count, "invalid_count"),
};
#undef F

int gate_set_write_json(const struct gate_set *gs, const char *path, const struct cl_session *s, char *err,
                        size_t errlen)
{
    struct jw w;
    jw_doc_begin(&w, GATE_RESULT_SCHEMA, s, "");
    jw_obj_end(&w);
    jw_kv_str(&w, "gates_file", gs->path);
    if (gs->description[0])
        jw_kv_str(&w, "description", gs->description);
    int failed = gate_set_failures(gs);
    jw_kv_obj(&w, "summary");
    jw_kv_int(&w, "gates", gs->count);
    jw_kv_int(&w, "passed", gs->count - failed);
    jw_kv_int(&w, "failed", failed);
    jw_kv_int(&w, "sweeps", gs->sweeps_run);
    jw_obj_end(&w);
    jw_key(&w, "baseline");
    if (gs->baseline_path[0]) {
        jw_obj_begin(&w);
        jw_kv_str(&w, "path", gs->baseline_path);
        jw_kv_num(&w, "tolerance", gs->tolerance);
        jw_kv_num(&w, "floor", GATE_BASELINE_FLOOR);
        jw_obj_end(&w);
    } else {
        jw_null(&w);
    }
    jw_kv_arr(&w, "gates");
    for (int i = 0; i < gs->count; ++i) {
        const struct gate *g = &gs->gates[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "name", g->name);
        jw_kv_str(&w, "model", g->model.info->id);
        jw_kv_str(&w, "label", g->model.label);
        jw_kv_str(&w, "reference", g->has_reference ? g->reference.label : g->model.info->reference_id);
        jw_kv_bool(&w, "user_model", models_runtime(g->model.info) != NULL);
        jw_kv_str(&w, "metric", gate_metric_name(g->metric));
        jw_kv_fields(&w, &g->grid, accuracy_grid_n_fields, ACCURACY_GRID_N_FIELDS);
        jw_kv_int(&w, "samples", g->grid.samples);
        jw_key(&w, "min");
        g->has_min ? jw_num(&w, g->min) : jw_null(&w);
        jw_key(&w, "max");
        g->has_max ? jw_num(&w, g->max) : jw_null(&w);
        jw_kv_str(&w, "status", g->status == GATE_PASS ? "pass" : g->status == GATE_FAIL ? "fail" : "not_run");
        jw_kv_fields(&w, g, JW_FIELDS(figure_fields));
        if (g->check.figure) {   /* set for the metrics a sweep measures */
            jw_kv_obj(&w, "device_check");
            jw_kv_str(&w, "status", g->check.exceeded ? "exceeded" : "ok");
            jw_kv_num(&w, "in_4th_digit_units", g->check.units);
            jw_kv_num(&w, "bound_4th_digit_units", ACC_CHECK_BOUND_UNITS);
            jw_kv_str(&w, "worst_figure", g->check.figure);
            jw_kv_num(&w, "worst_at_n", g->check.n);
            jw_kv_bool(&w, "accepted", g->accept_device_disagreement);
            jw_obj_end(&w);
        }
        if (g->reason[0])
            jw_kv_str(&w, "reason", g->reason);
        else if (!isfinite(g->measured))
            jw_kv_str(&w, "reason", "not measured");
        if (g->has_claimed)
            jw_kv_num(&w, "claimed", g->claimed);
        if (g->note[0])
            jw_kv_str(&w, "note", g->note);
        if (g->baseline_status != GATE_BASELINE_NONE) {
            jw_kv_obj(&w, "baseline");
            jw_kv_str(&w, "status", g->baseline_status == GATE_BASELINE_OK           ? "ok"
                                    : g->baseline_status == GATE_BASELINE_REGRESSION ? "regression"
                                                                                     : "missing");
            jw_kv_num(&w, "value", g->baseline);
            jw_kv_num(&w, "change_rel", g->baseline_change);
            jw_obj_end(&w);
        }
        jw_kv_num(&w, "seconds", g->seconds);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}
