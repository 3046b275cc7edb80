/* field_report.c - a heatmap error field's JSON (written and read back) and its picture. */
#include "field_report.h"

#include "context.h"
#include "draw.h"
#include "plots.h"
#include "exitcodes.h"
#include "jsonr.h"
#include "jsonw.h"
#include "rdoc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- JSON ------------------------------------------------------------------------ */

static void jw_peak(struct jw *w, const char *key, const struct field_peak *p)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, "value", p->value);
    jw_kv_num(w, "n", p->n);
    jw_kv_num(w, "x", p->x);
    jw_kv_int(w, "row", p->row);
    jw_kv_int(w, "col", p->col);
    jw_obj_end(w);
}

static void jw_field(struct jw *w, const char *key, const float *v, size_t count)
{
    jw_kv_arr(w, key);
    /* 9 significant digits give back every float exactly, so a redraw finds the same peaks
       (with 4, cells near the maximum tie and the first one wins) and draws the same picture. */
    for (size_t i = 0; i < count; i++) jw_numf(w, v[i], 9);
    jw_arr_end(w);
}

/* The field's rows: one row, the model against its reference, with the maxima of the
 * picture's grid (the accuracy sweep's rows hold the refined ones) and where they are, and the
 * device-against-double check of its cells. */
static struct rdoc *field_rows(const char *path, const struct field_result *r, char *err, size_t errlen)
{
    const char *base = strrchr(path, '/');
    struct rdoc *d = rdoc_new(FIELD_SCHEMA, "field", base ? base + 1 : path, err, errlen);
    if (!d)
        return NULL;
    char grid[RD_TEXT];
    snprintf(grid, sizeof grid, "%d n x %d x, n %g..%g log-spaced, attenuation to %g x_e", r->grid.rows, r->grid.cols,
             r->grid.n_min, r->grid.n_max, r->u_max);
    rd_ctx_put(&d->ctx, "heatmap grid", grid);
    struct rd_row *row = rdoc_row(d, NULL, r->model.label);
    if (row) {
        rd_row_key(row, "model", NULL, r->model.label);
        rd_row_attr(row, "reference", r->reference.label);
        static const struct {
            const char *name, *unit;
            int direction;
        } m[] = {
            { "epicentre.max_rel", "1", RD_LOWER }, { "epicentre.max_rel.at_n", "1", RD_NEITHER },
            { "epicentre.max_rel.at_x", "rad", RD_NEITHER }, { "attenuation.max_abs", "1", RD_LOWER },
            { "attenuation.max_abs.at_n", "1", RD_NEITHER }, { "attenuation.max_abs.at_x", "rad", RD_NEITHER },
            { "check.max_rel_diff", "1", RD_LOWER }, { "check.max_abs_diff", "1", RD_LOWER },
        };
        const double v[] = { r->epi_peak.value, r->epi_peak.n, r->epi_peak.x, r->att_peak.value, r->att_peak.n,
                             r->att_peak.x, r->check_rel_diff, r->check_abs_diff };
        for (size_t k = 0; k < sizeof m / sizeof m[0]; ++k)
            rd_row_metric(d, row, m[k].name, m[k].unit, m[k].direction, 0, v[k]);
    }
    return rdoc_built(d, err, errlen) ? NULL : d;
}

int field_write_json(const char *path, const struct field_result *r, const struct cl_session *s, char *err,
                     size_t errlen)
{
    struct rdoc *rows = field_rows(path, r, err, errlen);
    if (!rows)
        return -1;
    struct jw w;
    jw_doc_begin(&w, FIELD_SCHEMA, s, "");
    jw_obj_end(&w);
    jw_kv_str(&w, "model", r->model.label);
    jw_kv_str(&w, "reference", r->reference.label);
    /* what a redraw needs of a model it may not know (a user model): its formula and lobe angle */
    jw_kv_str(&w, "formula", r->model.info->formula ? r->model.info->formula : "");
    jw_kv_str(&w, "lobe", r->model.info->lobe == LOBE_PSI ? "psi" : "theta_h");
    jw_kv_obj(&w, "grid");
    jw_kv_int(&w, "rows", r->grid.rows);
    jw_kv_int(&w, "cols", r->grid.cols);
    jw_kv_num(&w, "n_min", r->grid.n_min);
    jw_kv_num(&w, "n_max", r->grid.n_max);
    jw_kv_num(&w, "u_max", r->u_max);
    jw_kv_str(&w, "rows_are", "n, log-spaced from n_min to n_max (as float)");
    jw_kv_str(&w, "epicentre_x", "x = t x_e(n), t = col/(cols-1); x_e(n) = acos(exp(-0.511/n))");
    jw_kv_str(&w, "attenuation_x", "x = x_e(n) u_max^t, t = col/(cols-1); null past pi/2");
    jw_kv_arr(&w, "n");
    for (int i = 0; i < r->grid.rows; i++) jw_num(&w, r->n[i]);
    jw_arr_end(&w);
    jw_obj_end(&w);
    jw_peak(&w, "epicentre_max_rel", &r->epi_peak);
    jw_peak(&w, "attenuation_max_abs", &r->att_peak);
    jw_kv_obj(&w, "check");
    jw_kv_num(&w, "max_rel_diff", r->check_rel_diff);
    jw_kv_num(&w, "max_abs_diff", r->check_abs_diff);
    jw_kv_int(&w, "cells", r->check_cells);
    jw_kv_str(&w, "what", "device float cells against the double host reference at the same nominal x and n");
    jw_obj_end(&w);
    jw_kv_num(&w, "device_seconds", r->device_seconds);
    size_t cells = (size_t)r->grid.rows * r->grid.cols;
    jw_field(&w, "epicentre_rel", r->epi_rel, cells);
    jw_field(&w, "attenuation_abs", r->att_abs, cells);
    rdoc_json_rows_member(&w, rows);
    rdoc_delete(rows);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

static int read_field_array(const struct jr_doc *d, const struct jr_value *root, const char *key, size_t cells,
                            float **out, char *err, size_t errlen)
{
    double *a = NULL;
    size_t count = 0;
    if (jr_need_num_array(d, root, key, &a, &count, err, errlen)) return 2;
    if (count != cells) {
        free(a);
        return jr_fail(d, jr_get(root, key), err, errlen, "\"%s\" has %zu values, rows x cols is %zu", key, count, cells);
    }
    float *f = malloc(cells * sizeof *f);
    if (!f) {
        free(a);
        return jr_fail(d, root, err, errlen, "out of memory");
    }
    for (size_t i = 0; i < cells; i++) f[i] = (float)a[i];
    free(a);
    *out = f;
    return 0;
}

int field_read_json(const char *path, struct field_result *r, char *err, size_t errlen)
{
    struct jr_doc d;
    memset(r, 0, sizeof *r);
    /* a field holds two grids of at most FIELD_MAX_CELLS values, about 13 bytes each as written
       (9 digits): a file far larger is refused by its size, before jansson spends seconds on it */
    if (jr_parse_file_max(path, (size_t)2 * FIELD_MAX_CELLS * 20 + ((size_t)1 << 20), &d, err, errlen)) return 2;
    const struct jr_value *root = &d.root, *grid;
    const char *schema, *model, *ref;
    double rows, cols, *n = NULL;
    size_t nn = 0;
    char why[256];
    int rc = 2;
    if (jr_need_str(&d, root, "schema", &schema, err, errlen)) goto done;
    if (strcmp(schema, FIELD_SCHEMA) != 0 && strcmp(schema, FIELD_SCHEMA_V1) != 0) {
        jr_fail(&d, jr_get(root, "schema"), err, errlen, "schema \"%s\", expected \"%s\" (or \"%s\")", schema,
                FIELD_SCHEMA, FIELD_SCHEMA_V1);
        goto done;
    }
    if (jr_need_str(&d, root, "model", &model, err, errlen) || jr_need_str(&d, root, "reference", &ref, err, errlen) ||
        jr_need(&d, root, "grid", JR_OBJ, &grid, err, errlen) || jr_need_num(&d, grid, "rows", &rows, err, errlen) ||
        jr_need_num(&d, grid, "cols", &cols, err, errlen) || jr_need_num(&d, grid, "n_min", &r->grid.n_min, err, errlen) ||
        jr_need_num(&d, grid, "n_max", &r->grid.n_max, err, errlen) || jr_need_num(&d, grid, "u_max", &r->u_max, err, errlen) ||
        jr_need_num_array(&d, grid, "n", &n, &nn, err, errlen))
        goto done;
    if (model_spec_parse(model, &r->model, why, sizeof why)) {
        /* A model this process does not know (a user model of the run that wrote the file): the
           picture needs only its label, formula and lobe angle, which the file carries. */
        const char *formula = NULL, *lobe = NULL;
        const struct jr_value *fv = jr_get(root, "formula"), *lv = jr_get(root, "lobe");
        if ((fv && jr_need_str(&d, root, "formula", &formula, err, errlen)) ||
            (lv && jr_need_str(&d, root, "lobe", &lobe, err, errlen)))
            goto done;
        if (lobe && strcmp(lobe, "psi") != 0 && strcmp(lobe, "theta_h") != 0) {
            jr_fail(&d, lv, err, errlen, "lobe \"%s\" is not psi or theta_h", lobe);
            goto done;
        }
        if (strlen(model) >= sizeof r->model.label) {
            jr_fail(&d, jr_get(root, "model"), err, errlen, "%s", why);
            goto done;
        }
        size_t flen = formula ? strlen(formula) + 1 : 1, mlen = strlen(model) + 1;
        r->standin = calloc(1, sizeof *r->standin + flen + mlen);
        if (!r->standin) {
            snprintf(err, errlen, "%s: out of memory", path);
            goto done;
        }
        char *id = (char *)(r->standin + 1), *f = id + mlen;
        memcpy(id, model, mlen);
        memcpy(f, formula ? formula : "", flen);
        r->standin->id = id;
        r->standin->kernel_id = -1;
        r->standin->family = MODEL_FAMILY_USER;
        r->standin->lobe = lobe && strcmp(lobe, "theta_h") == 0 ? LOBE_THETA_H : LOBE_PSI;
        r->standin->formula = formula ? f : "(the formula is not in this field file)";
        r->standin->description = "a model of the run that wrote this field file";
        memset(&r->model, 0, sizeof r->model);
        r->model.info = r->standin;
        snprintf(r->model.label, sizeof r->model.label, "%s", model);
    }
    if (model_spec_parse(ref, &r->reference, why, sizeof why)) {
        jr_fail(&d, jr_get(root, "reference"), err, errlen, "%s", why);
        goto done;
    }
    if (!(rows == floor(rows) && cols == floor(cols) && rows >= 2 && cols >= 2 && rows <= 10000 && cols <= 10000)) {
        jr_fail(&d, grid, err, errlen, "grid rows/cols must be integers in [2, 10000]");
        goto done;
    }
    r->grid.rows = (int)rows;
    r->grid.cols = (int)cols;
    if (field_grid_check(&r->grid, why, sizeof why) || !(r->u_max >= 1)) {
        jr_fail(&d, grid, err, errlen, "%s", r->u_max >= 1 ? why : "u_max must be a number >= 1");
        goto done;
    }
    if (nn != (size_t)r->grid.rows) {
        jr_fail(&d, jr_get(grid, "n"), err, errlen, "\"n\" has %zu values, rows is %d", nn, r->grid.rows);
        goto done;
    }
    for (size_t i = 0; i < nn; i++)
        if (!(n[i] > 0)) {
            jr_fail(&d, jr_get(grid, "n"), err, errlen, "\"n\" item %zu is not a positive number", i);
            goto done;
        }
    r->n = n;
    n = NULL;
    size_t cells = (size_t)r->grid.rows * r->grid.cols;
    if (read_field_array(&d, root, "epicentre_rel", cells, &r->epi_rel, err, errlen) ||
        read_field_array(&d, root, "attenuation_abs", cells, &r->att_abs, err, errlen))
        goto done;
    /* the check block is informative; absent in hand-made files is fine */
    const struct jr_value *check = jr_get(root, "check");
    r->check_rel_diff = r->check_abs_diff = NAN;
    if (check) {
        double v;
        if (!jr_need_num(&d, check, "max_rel_diff", &v, err, errlen)) r->check_rel_diff = v;
        if (!jr_need_num(&d, check, "max_abs_diff", &v, err, errlen)) r->check_abs_diff = v;
        err[0] = 0;
    }
    field_find_peaks(r);
    rc = 0;
done:
    free(n);
    jr_free(&d);
    if (rc) field_result_free(r);
    return rc;
}

void field_safe_label(const char *label, char *out, size_t len)
{
    size_t k = 0;
    for (const char *p = label; *p && k + 1 < len; p++) {
        char c = *p;
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-')
            out[k++] = c;
        else if (c == ':' || c == ',')
            out[k++] = '_';
    }
    if (len) out[k] = 0;
}

/* ---- picture ------------------------------------------------------------------------ */

void field_heatmap_panels(const struct field_result *r, double epi_vmax, double att_vmax,
                          struct draw_heatmap_panel *p, struct field_panel_text *t)
{
    const char *var = r->model.info->lobe == LOBE_PSI ? "psi" : "theta_h";
    const char *shared = " (shared)";   /* the scale of every model of the run: the bar's height holds no more */
    snprintf(t->sub[0], sizeof t->sub[0], "relative error delta(x, n) over the epicentre");
    snprintf(t->sub[1], sizeof t->sub[1], "absolute error Delta(x, n) over the attenuation zone");
    snprintf(t->x_label[0], sizeof t->x_label[0], "x / x_e(n),  x = %s,  x_e(n) = acos(exp(-0.511/n))", var);
    snprintf(t->x_label[1], sizeof t->x_label[1], "x / x_e(n) (log),  x = %s;  grey: past pi/2", var);
    snprintf(t->bar[0], sizeof t->bar[0], "relative error delta%s", epi_vmax > 0 ? shared : "");
    snprintf(t->bar[1], sizeof t->bar[1], "absolute error Delta%s", att_vmax > 0 ? shared : "");
    memset(p, 0, 2 * sizeof *p);
    for (int k = 0; k < 2; k++) {
        p[k].cols = r->grid.cols;
        p[k].rows = r->grid.rows;
        p[k].y_min = r->n[0];
        p[k].y_max = r->n[r->grid.rows - 1];
        p[k].y_log = 1;
        p[k].y_label = "shininess n (log)";
        p[k].cmap = DRAW_CMAP_VIRIDIS;
        p[k].mark_max = 1;
        p[k].subtitle = t->sub[k];
        p[k].x_label = t->x_label[k];
        p[k].bar_label = t->bar[k];
        p[k].vmax = k == 0 ? epi_vmax : att_vmax;   /* <= 0: the panel's own [0, max] */
    }
    p[0].values = r->epi_rel;
    p[0].x_min = 0, p[0].x_max = 1;
    p[0].value_format = DRAW_FMT_PERCENT;
    p[1].values = r->att_abs;
    p[1].x_min = 1, p[1].x_max = r->u_max, p[1].x_log = 1;
    p[1].value_format = DRAW_FMT_PLAIN;
}

int field_draw_heatmap_scaled(const char *path, const struct field_result *r, double epi_vmax, double att_vmax,
                              struct draw_panel_layout *layout, char *err, size_t errlen)
{
    const char *var = r->model.info->lobe == LOBE_PSI ? "psi" : "theta_h";
    char title[1024];
    char peak0[160] = "no finite value", peak1[160] = "no finite value";
    if (isfinite(r->epi_peak.value))
        snprintf(peak0, sizeof peak0, "max delta %.4g%% at n = %.4g, %s = %.4g rad", 100 * r->epi_peak.value,
                 r->epi_peak.n, var, r->epi_peak.x);
    if (isfinite(r->att_peak.value))
        snprintf(peak1, sizeof peak1, "max Delta %.4g at n = %.4g, %s = %.4g rad", r->att_peak.value, r->att_peak.n, var,
                 r->att_peak.x);
    snprintf(title, sizeof title, "%s against %s:  %s\n%s;  %s  (on this %dx%d grid)", r->model.label,
             r->reference.label, r->model.info->formula, peak0, peak1, r->grid.cols, r->grid.rows);
    struct draw_heatmap_panel p[2];
    struct field_panel_text t;
    field_heatmap_panels(r, epi_vmax, att_vmax, p, &t);
    if (draw_heatmap_figure(path, title, 2, p, layout, err, errlen)) return -1;
    return plots_stamp_if_quick(path, 0, err, errlen);
}

int field_draw_heatmap(const char *path, const struct field_result *r, struct draw_panel_layout *layout, char *err,
                       size_t errlen)
{
    return field_draw_heatmap_scaled(path, r, 0, 0, layout, err, errlen);
}
