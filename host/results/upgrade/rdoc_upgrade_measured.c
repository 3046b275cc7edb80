/* rdoc_upgrade_measured.c - the rows of a brdfbench.measured/1 file (rdoc_upgrade_measured.h).
 * Every figure of the rows is a member of its material in the layout; the material's key, its
 * pictures' stem, is not: it is made again from the names in order (report_measured_stem), as
 * the run that wrote the file named its pictures. */
#include "rdoc_upgrade_measured.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report_measured.h"

#define MAX_MATERIALS 512   /* MEASURED_MAX_MATERIALS: a run never holds more */
#define STEM 300

/* The figures of a fit object: its name in the layout and in the rows, and whether the fit is
   a Cook-Torrance one (alpha, n_of_alpha, F0 instead of n). */
static const struct { const char *member, *name; int physical; } fits[] = {
    { "blinn_phong", "blinn-phong", 0 }, { "ct_beckmann", "ct-beckmann", 1 }, { "ct_ggx", "ct-ggx", 1 },
};

static int fit_rows(struct rdoc *d, const struct jr_value *mat, const char *stem)
{
    for (size_t k = 0; k < sizeof fits / sizeof fits[0]; ++k) {
        const struct jr_value *f = jr_get(mat, fits[k].member);
        if (!f || f->type != JR_OBJ)
            f = NULL;
        struct rd_row *r = rdoc_row(d, "", fits[k].name);
        if (!r)
            return -1;
        rd_row_key(r, "material", NULL, stem);
        rd_row_key(r, MEASURED_FIT_KEY, "fit ", fits[k].name);
        const char *status = f ? jr_str_or(f, "status", "ok") : "missing";
        if (strcmp(status, "ok") != 0)
            rd_row_fail(r, status, f ? jr_str_or(f, "reason", "") : "no such fit in the file");
        static const char *const plain[] = { "n" }, *const physical[] = { "alpha", "n_of_alpha", "F0" };
        if (fits[k].physical)
            for (size_t q = 0; q < 3; ++q)
                rd_row_metric(d, r, physical[q], "1", RD_NEITHER, 0, f ? jr_num_or_nan(f, physical[q]) : NAN);
        else
            rd_row_metric(d, r, plain[0], "1", RD_NEITHER, 0, f ? jr_num_or_nan(f, plain[0]) : NAN);
        rd_row_metric(d, r, "ks", "1/sr", RD_NEITHER, 0, f ? jr_num_or_nan(f, "ks") : NAN);
        rd_row_metric(d, r, "kd", "1/sr", RD_NEITHER, 0, f ? jr_num_or_nan(f, "kd") : NAN);
        rd_row_metric(d, r, "rms", "1", RD_LOWER, 0, f ? jr_num_or_nan(f, "rms") : NAN);
        rd_row_metric(d, r, "rms_fit_cells", "1", RD_LOWER, 0, f ? jr_num_or_nan(f, "rms_fit_cells") : NAN);
        rd_row_metric(d, r, "iterations", "1", RD_NEITHER, 0, f ? jr_num_or_nan(f, "iterations") : NAN);
    }
    return 0;
}

static int material_rows(const struct jr_doc *j, struct rdoc *d, const struct jr_value *mat, const char *stem,
                         char *err, size_t errlen)
{
    struct rd_row *r = rdoc_row(d, "", "");
    if (!r)
        return -1;
    r->line = mat->line;
    rd_row_key(r, "material", NULL, stem);
    const struct jr_value *neg = jr_get(mat, "negative_cells_rgb"), *dc = jr_get(mat, "device_check");
    if (dc && dc->type != JR_OBJ)
        dc = NULL;
    double rgb[3] = { NAN, NAN, NAN };
    for (size_t c = 0; neg && neg->type == JR_ARR && c < 3 && c < neg->count; ++c)
        if (neg->items[c].type == JR_NUM)
            rgb[c] = neg->items[c].num;
    const struct { const char *name; double v; } figs[] = {
        { "cells", jr_num_or_nan(mat, "cells") },
        { "unmeasured_cells", jr_num_or_nan(mat, "unmeasured_cells") },
        { "negative_cells.red", rgb[0] }, { "negative_cells.green", rgb[1] }, { "negative_cells.blue", rgb[2] },
        { "below_horizon_cells", jr_num_or_nan(mat, "below_horizon_cells") },
        { "used_cells", jr_num_or_nan(mat, "used_cells") },
        { "fit_cells", jr_num_or_nan(mat, "fit_cells") },
        { "device_check.points", dc ? jr_num_or_nan(dc, "points") : NAN },
        { "device_check.same_cell", dc ? jr_num_or_nan(dc, "same_cell") : NAN },
    };
    for (size_t k = 0; k < sizeof figs / sizeof figs[0]; ++k)
        rd_row_metric(d, r, figs[k].name, "1", RD_NEITHER, 0, figs[k].v);
    rd_row_metric(d, r, "device_check.value_differs", "1", RD_LOWER, 0, dc ? jr_num_or_nan(dc, "value_differs") : NAN);
    rd_row_text(d, r, "name", jr_str_or(mat, "name", ""));
    rd_row_text(d, r, "path", jr_str_or(mat, "path", ""));
    rd_row_text(d, r, "device_check", dc ? jr_str_or(dc, "status", "not run") : "not run");
    if (fit_rows(d, mat, stem))
        return -1;
    const struct jr_value *lobes = jr_get(mat, "lobes");
    for (size_t l = 0; lobes && lobes->type == JR_ARR && l < lobes->count; ++l) {
        const struct jr_value *lb = &lobes->items[l];
        const char *model = lb->type == JR_OBJ ? jr_str_or(lb, "model", NULL) : NULL;
        if (!model)
            return jr_fail(j, lb, err, errlen, "a lobe without \"model\"");
        struct rd_row *lr = rdoc_row(d, "", model);
        if (!lr)
            return -1;
        lr->line = lb->line;
        rd_row_key(lr, "material", NULL, stem);
        rd_row_key(lr, MEASURED_LOBE_KEY, NULL, model);
        rd_row_metric(d, lr, "err_measured", "1", RD_LOWER, 0, jr_num_or_nan(lb, "err_measured"));
        rd_row_metric(d, lr, "err_phong", "1", RD_LOWER, 0, jr_num_or_nan(lb, "err_phong"));
        rd_row_metric(d, lr, "ratio", "1", RD_NEITHER, 0, jr_num_or_nan(lb, "ratio"));
        const char *why = jr_str_or(lb, "ratio_reason", NULL);
        if (why)
            rd_row_text(d, lr, "ratio_reason", why);
    }
    return 0;
}

int upgrade_measured_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *ctx = jr_get(&j->root, "context"), *mats = jr_get(&j->root, "materials");
    const struct jr_value *grid = ctx && ctx->type == JR_OBJ ? jr_get(ctx, "grid") : NULL;
    if (!mats || mats->type != JR_ARR)
        return jr_fail(j, &j->root, err, errlen, "no \"materials\" array (accepted: measured.json as brdfbench writes it)");
    if (mats->count > MAX_MATERIALS)
        return jr_fail(j, mats, err, errlen, "%zu materials (accepted: at most %d, as brdfbench writes them)",
                       mats->count, MAX_MATERIALS);
    double cells_max = grid && grid->type == JR_OBJ ? jr_num_or_nan(grid, "fit_cells_max") : NAN;
    if (isfinite(cells_max)) {
        char buf[32];
        snprintf(buf, sizeof buf, "%ld", (long)cells_max);
        rd_ctx_put(&d->ctx, "fit_cells_max", buf);
    }
    char (*stems)[STEM] = malloc((mats->count ? mats->count : 1) * sizeof *stems);
    const char **taken = malloc((mats->count ? mats->count : 1) * sizeof *taken);
    int rc = 0;
    if (!stems || !taken) {
        d->oom = 1;   /* the caller reports it */
        goto done;
    }
    for (size_t i = 0; i < mats->count && !rc; ++i) {
        const struct jr_value *mat = &mats->items[i];
        if (mat->type != JR_OBJ || !jr_str_or(mat, "name", NULL)) {
            rc = jr_fail(j, mat, err, errlen, "a material without \"name\"");
            break;
        }
        report_measured_stem(jr_str_or(mat, "name", ""), taken, (int)i, stems[i], STEM);
        taken[i] = stems[i];
        rc = material_rows(j, d, mat, stems[i], err, errlen);
    }
    if (rc < 0)
        rc = 0;   /* d->oom, which the caller reports */
done:
    free(stems);
    free(taken);
    return rc;
}
