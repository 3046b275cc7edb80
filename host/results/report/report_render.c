/* report_render.c - report.md's image passes from render.json's rows (report_render.h). */
#define _POSIX_C_SOURCE 200809L
#include "report_render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "outdir.h"
#include "report.h"
#include "report_accuracy.h"

static const char *attr(const struct rd_row *r, const char *name)
{
    const char *v = rd_row_key_value(r, name);
    return v ? v : "";
}

/* A model's row of a scene: it has a reference and no He role (scene_rows). */
static int is_model_row(const struct rd_row *r)
{
    return rd_row_key_value(r, "reference") && rd_row_key_value(r, "scene_name") && !rd_row_key_value(r, "he");
}

static int same_scene(const struct rd_row *a, const struct rd_row *b)
{
    return strcmp(a->device, b->device) == 0 && strcmp(attr(a, "scene_name"), attr(b, "scene_name")) == 0;
}

/* The timed entry of a selected model at the scene's first timed size ("W x H"), or NULL. */
static const struct rd_row *timing_of(const struct rdoc *d, const struct rd_row *first, const char *label,
                                      const char *size)
{
    for (int i = 0; i < d->nrows; i++) {
        const struct rd_row *r = &d->rows[i];
        const char *scene = rd_row_key_value(r, "scene");
        if (!rd_row_key_value(r, "size") || strcmp(r->device, first->device) != 0 || !scene ||
            strcmp(scene, attr(first, "scene_name")) != 0 || strcmp(attr(r, "size"), size) != 0 ||
            strcmp(attr(r, "selected_model"), "true") != 0 || strcmp(r->model, label) != 0)
            continue;
        return r;
    }
    return NULL;
}

/* A timed row's figure at its size: NAME@WxH. */
static double at_size(const struct rd_row *r, const char *name, const char *size)
{
    char metric[RD_NAME];
    snprintf(metric, sizeof metric, "%s@%s", name, size);
    return r ? rd_row_value(r, metric) : NAN;
}

/* A scene's He comparison: He's model beside Blinn-Phong fitted to it and the cheap lobes at that
 * n, with the contact sheets. */
static void he_comparison(const struct rdoc *d, const struct rd_row *first, const char *run_dir, struct md_buf *md,
                          const char *name, void (*add)(void *ctx, const char *file, const char *caption), void *ctx)
{
    const struct rd_row *fit = NULL;
    for (int i = 0; i < d->nrows && !fit; i++)
        if (strcmp(attr(&d->rows[i], "he"), "fit") == 0 && same_scene(&d->rows[i], first))
            fit = &d->rows[i];
    if (!fit)
        return;
    md_printf(md, "%s shaded by He et al. 1991 (`%s`) beside Blinn-Phong fitted to its specular radiance by least "
                  "squares (n = %.4g, scale %.4g, relative rms residual %.3g) and the cheap lobes at that n, errors "
                  "against He's image:\n\n| shaded by | max abs error | mean abs error | max abs vs the fit |\n"
                  "|---|---:|---:|---:|\n",
              name, attr(fit, "against"), rd_row_value(fit, "n_fit"), rd_row_value(fit, "k_fit"),
              rd_row_value(fit, "relative_rms_residual"));
    int k = 0;
    for (int i = 0; i < d->nrows; i++) {
        const struct rd_row *e = &d->rows[i];
        if (strcmp(attr(e, "he"), "entry") != 0 || !same_scene(e, first))
            continue;
        const char *entry = attr(e, "shaded_by");
        md_printf(md, "| `");
        md_cell_text(md, entry);
        md_printf(md, "` |");
        report_md_num(md, rd_row_value(e, "max_abs"), "%.4g");
        report_md_num(md, rd_row_value(e, "mean_abs"), "%.4g");
        report_md_num(md, rd_row_value(e, "max_abs_vs_blinn_fit"), "%.4g");
        md_printf(md, "\n");
        const char *contact = rd_row_text_get(e, "contact_sheet");
        /* the pictures of the fit and of fq2 (the others are in the run folder) */
        if (contact && add && report_file_exists(run_dir, contact) && (k == 0 || strncmp(entry, "fq2@", 4) == 0)) {
            char caption[400];
            snprintf(caption, sizeof caption, "%s: He's model, %s, |error| against He (max %.3g)", name, entry,
                     rd_row_value(e, "max_abs"));
            add(ctx, contact, caption);
        }
        k++;
    }
    md_printf(md, "\n");
}

/* A scene: its source, contact sheet, a table line per model and He's comparison. */
static void scene(const struct rdoc *d, const struct rd_row *first, const char *run_dir, struct md_buf *md,
                  void (*add)(void *ctx, const char *file, const char *caption), void *ctx)
{
    const char *name = attr(first, "scene_name");
    md_printf(md, "### Scene: %s\n\n", name);
    const char *src = rd_row_text_get(first, "scene_source");
    if (src) md_printf(md, "Source: `%s`.\n\n", src);
    const char *grid = rd_row_text_get(first, "scene_contact_sheet");
    if (grid && add) {
        char caption[200];
        snprintf(caption, sizeof caption, "%s: every model (rows) at each shininess (columns), with its error image", name);
        add(ctx, grid, caption);
    }
    double tw = NAN, th = NAN;
    char size[48] = "";
    const char *timed = rd_row_text_get(first, "scene_timed_size");
    if (timed && sscanf(timed, "%lf x %lf", &tw, &th) == 2) snprintf(size, sizeof size, "%gx%g", tw, th);
    md_printf(md, "| model | reference | max abs error | RMSE | PSNR (dB) | share above threshold | double check | "
                  "Mpixel/s | of copy | speed-up vs reference | files |\n");
    md_printf(md, "|---|---|---:|---:|---:|---:|---|---:|---:|---:|---|\n");
    for (int i = 0; i < d->nrows; i++) {
        const struct rd_row *m = &d->rows[i];
        if (!is_model_row(m) || !same_scene(m, first)) continue;
        const char *label = m->model, *ref = attr(m, "reference");
        md_printf(md, "| `");
        md_cell_text(md, label);
        md_printf(md, "` | `");
        md_cell_text(md, ref);
        md_printf(md, "` |");
        report_md_num(md, rd_row_value(m, "max_abs"), "%.4g");
        report_md_num(md, rd_row_value(m, "rmse"), "%.4g");
        report_md_num(md, rd_row_value(m, "psnr_db"), "%.1f");
        report_md_pct(md, rd_row_value(m, "share_above_threshold"));
        const char *check = rd_row_text_get(m, "double_reference_check");
        md_printf(md, " %s |", !check ? "n/a" : strcmp(check, "within bound") == 0 ? "within bound" : "**outside bound**");
        const struct rd_row *te = size[0] ? timing_of(d, first, label, size) : NULL;
        report_md_num(md, at_size(te, "mpixel_per_s", size), "%.0f");
        report_md_num(md, at_size(te, "fraction_of_copy", size), "%.2f");
        report_md_num(md, at_size(te, "speedup_vs_reference", size), "%.2f");
        static const char *const links[][2] = { { "image", "image" }, { "error_image", "error" },
                                                { "signed_error_image", "signed error" } };
        for (size_t f = 0; f < sizeof links / sizeof links[0]; f++) {
            const char *file = rd_row_text_get(m, links[f][0]);
            if (file && report_file_exists(run_dir, file)) md_printf(md, " [%s](%s)", links[f][1], file);
        }
        md_printf(md, " |\n");
        /* a model against itself has a black error image: its contact sheet shows nothing new */
        const char *contact = rd_row_text_get(m, "contact_sheet");
        if (contact && strcmp(label, ref) != 0 && add) {
            char caption[400];
            snprintf(caption, sizeof caption, "%s, %s against %s: reference, model, |error| (max %.3g, PSNR %.1f dB)",
                     name, label, ref, rd_row_value(m, "max_abs"), rd_row_value(m, "psnr_db"));
            add(ctx, contact, caption);
        }
    }
    if (isfinite(tw)) md_printf(md, "\nTimed at %.0f x %.0f.\n", tw, th);
    md_printf(md, "\n");
    he_comparison(d, first, run_dir, md, name, add, ctx);
}

void report_render_summary(const struct rdoc *render, const char *run_dir, struct md_buf *md,
                           void (*add)(void *ctx, const char *file, const char *caption), void *ctx)
{
    md_printf(md, "Each model shades full images on the device; its error image is |model - reference| of the "
                  "specular radiance (inferno, colour bar in the picture), the reference being the model's own "
                  "(phong, blinn, or the normalised lobes). Metrics over the foreground pixels; PSNR on the 8-bit "
                  "colours; timing: median kernel time at the timed size, as Mpixel/s and as a fraction of a copy "
                  "kernel moving the same bytes. Files: `render.json`, `render/<scene>/`.");
    md_printf(md, "\n\n");
    /* the scenes in the order of their first model's row */
    for (int i = 0; i < render->nrows; i++) {
        const struct rd_row *r = &render->rows[i];
        if (!is_model_row(r)) continue;
        int seen = 0;
        for (int k = 0; k < i && !seen; k++)
            seen = is_model_row(&render->rows[k]) && same_scene(&render->rows[k], r);
        if (!seen) scene(render, r, run_dir, md, add, ctx);
    }
}
