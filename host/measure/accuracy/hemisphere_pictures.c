/* hemisphere_pictures.c - pictures of the hemisphere sweep (accuracy --pictures): a full BRDF's
 * errors over (theta_h, theta_d) at the phi_d and parameter value of its largest Delta, in double
 * (delta where f_ref is in the epicentre, Delta everywhere; grey below the horizon), and its
 * per-parameter maxima against the parameter. */
#include "hemisphere_pictures.h"
#include "draw.h"
#include "exitcodes.h"
#include "field_report.h"
#include "outdir.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PIC_CELLS 96

/* The heatmap's cells in double, rel (delta) then abs (Delta), 2 PIC_CELLS^2 floats into vout:
   in one sandbox for a user model's code (model_run_isolated_pair), not a round trip per value. */
struct cells_ctx {
    const struct hemi_result *r;
    const struct hemi_per_p *pp;
    double pd, threshold;
};

static void heatmap_cells(void *vctx, void *vout)
{
    const struct cells_ctx *c = vctx;
    float *rel = vout, *abs_err = rel + PIC_CELLS * PIC_CELLS;
    for (int row = 0; row < PIC_CELLS; ++row)
        for (int col = 0; col < PIC_CELLS; ++col) {
            double th = (col + 0.5) / PIC_CELLS * (M_PI / 2), td = (row + 0.5) / PIC_CELLS * (M_PI / 2);
            double L[3], V[3];
            hemisphere_dirs(th, td, c->pd, L, V);
            float a = NAN, d = NAN;
            if (L[2] > 0 && V[2] > 0) {
                double f = hemisphere_eval_host(&c->r->model, c->r->model_kind, L, V, c->pp->mvals);
                double fr = hemisphere_eval_host(&c->r->reference, c->r->ref_kind, L, V, c->pp->rvals);
                a = (float)fabs(f - fr);
                if (fr >= c->threshold)
                    d = (float)(fabs(f - fr) / fr);
            }
            rel[row * PIC_CELLS + col] = d;
            abs_err[row * PIC_CELLS + col] = a;
        }
}

static int heatmap(const struct hemi_result *r, const char *dir, const char *safe, char *err, size_t errlen)
{
    const struct hemi_extreme *w = isfinite(r->whole.value) ? &r->whole : &r->epicentre;
    const struct hemi_per_p *pp = NULL;
    for (int i = 0; i < r->p_count; ++i)
        if (r->per_p[i].p == w->p)
            pp = &r->per_p[i];
    if (!pp || !isfinite(w->pd))
        return 0;   /* no figure: nothing to draw */
    float *rel = malloc(2 * PIC_CELLS * PIC_CELLS * sizeof *rel), *abs_err = rel + PIC_CELLS * PIC_CELLS;
    if (!rel) {
        snprintf(err, errlen, "out of memory for the hemisphere heatmap of %s", r->model.label);
        return EXIT_RUNTIME;
    }
    const struct cells_ctx cc = { r, pp, w->pd, exp(-0.511) * pp->peak };
    int rc = model_run_isolated_pair(&r->model, &r->reference, heatmap_cells, (void *)&cc, rel,
                                     2 * PIC_CELLS * PIC_CELLS * sizeof *rel);
    if (rc) {
        free(rel);
        snprintf(err, errlen, "the double values of the hemisphere heatmap of %s failed", r->model.label);
        return rc;
    }
    char sub_rel[160], sub_abs[160], title[400], name[300], path[4400];
    snprintf(sub_rel, sizeof sub_rel, "delta where f_ref >= e^-0.511 peak");
    snprintf(sub_abs, sizeof sub_abs, "Delta (grey: below the horizon)");
    snprintf(title, sizeof title, "%s against %s at %s = %.6g, phi_d = %.4g rad\nthe parameter and phi_d of the "
             "largest Delta", r->model.label, r->reference.label, r->axis.name, pp->p, w->pd);
    struct draw_heatmap_panel panels[2] = {
        { .cols = PIC_CELLS, .rows = PIC_CELLS, .values = rel, .x_min = 0, .x_max = 90, .x_label = "theta_h (deg)",
          .y_min = 0, .y_max = 90, .y_label = "theta_d (deg)", .cmap = DRAW_CMAP_VIRIDIS,
          .value_format = DRAW_FMT_PERCENT, .bar_label = "relative error delta", .subtitle = sub_rel, .mark_max = 1 },
        { .cols = PIC_CELLS, .rows = PIC_CELLS, .values = abs_err, .x_min = 0, .x_max = 90,
          .x_label = "theta_h (deg)", .y_min = 0, .y_max = 90, .y_label = "theta_d (deg)", .cmap = DRAW_CMAP_INFERNO,
          .bar_label = "absolute error Delta", .subtitle = sub_abs, .mark_max = 1 },
    };
    snprintf(name, sizeof name, "hemisphere_heatmap_%s.png", safe);
    path_join(path, sizeof path, dir, name);
    rc = draw_heatmap_figure(path, title, 2, panels, NULL, err, errlen) ? EXIT_RUNTIME : 0;
    free(rel);
    return rc;
}

static int against_p(const struct hemi_result *r, const char *dir, const char *safe, char *err, size_t errlen)
{
    int n = r->p_count;
    double *x = malloc((size_t)n * sizeof *x), *y0 = malloc((size_t)n * sizeof *y0),
           *y1 = malloc((size_t)n * sizeof *y1);
    if (!x || !y0 || !y1) {
        free(x);
        free(y0);
        free(y1);
        snprintf(err, errlen, "out of memory for the plots of %s", r->model.label);
        return EXIT_RUNTIME;
    }
    for (int i = 0; i < n; ++i) {
        x[i] = r->per_p[i].p;
        y0[i] = r->per_p[i].epi_rel.value;
        y1[i] = r->per_p[i].whole_abs.value;
    }
    char title[300], name[300], path[4400];
    int rc = 0;
    const struct { const char *file, *what, *ylabel; const double *y; int fmt; } plots[2] = {
        { "hemisphere_max_rel_vs_p", "max delta over the epicentre", "max delta", y0, DRAW_FMT_PERCENT },
        { "hemisphere_max_abs_vs_p", "max Delta over the hemisphere", "max Delta", y1, 0 },
    };
    for (int k = 0; k < 2 && !rc; ++k) {
        struct draw_series s = { .x = x, .y = plots[k].y, .count = n, .label = r->model.label, .colour = 0,
                                 .markers = 1 };
        snprintf(title, sizeof title, "%s against %s: %s, per %s", r->model.label, r->reference.label, plots[k].what,
                 r->axis.name);
        struct draw_line_plot plot = { .title = title, .x_label = r->axis.name, .y_label = plots[k].ylabel,
                                       .x_log = r->axis.geometric, .y_format = plots[k].fmt, .nseries = 1,
                                       .series = &s };
        snprintf(name, sizeof name, "%s_%s.png", plots[k].file, safe);
        path_join(path, sizeof path, dir, name);
        if (draw_line_plot(path, &plot, err, errlen))
            rc = EXIT_RUNTIME;
    }
    free(x);
    free(y0);
    free(y1);
    return rc;
}

int hemisphere_draw(const struct hemi_result *res, int count, const char *dir, int *drawn, char *err, size_t errlen)
{
    *drawn = 0;
    for (int i = 0; i < count; ++i) {
        char safe[128];
        field_safe_label(res[i].model.label, safe, sizeof safe);
        int rc = heatmap(&res[i], dir, safe, err, errlen);
        if (!rc)
            rc = against_p(&res[i], dir, safe, err, errlen);
        if (rc)
            return rc;
        *drawn += 3;
    }
    return 0;
}
