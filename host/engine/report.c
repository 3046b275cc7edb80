/* report.c - report.md of a run folder (see report.h). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "accuracy_report.h"
#include "jsonr.h"
#include "outdir.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int file_exists(const char *dir, const char *name)
{
    char path[4096];
    struct stat st;
    if (path_join(path, sizeof path, dir, name)) return 0;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

static void md_pct(struct md_buf *b, double v)
{
    if (isfinite(v)) md_printf(b, " %.4g%% |", 100 * v);
    else md_printf(b, " n/a |");
}

static void md_num(struct md_buf *b, double v, const char *fmt)
{
    if (isfinite(v)) {
        md_printf(b, " ");
        md_printf(b, fmt, v);
        md_printf(b, " |");
    } else {
        md_printf(b, " n/a |");
    }
}

static void accuracy_table(struct md_buf *b, const struct report_input *in)
{
    md_printf(b, "## Accuracy per model\n\n");
    if (!in->acc || in->nacc < 1) {
        md_printf(b, "Not available: the accuracy sweep did not run.\n\n");
        return;
    }
    if (in->acc_grid)
        md_printf(b,
                  "Dense grid: n from %g to %g in steps of %g, %ld samples per zone per n; each maximum located on the "
                  "device (float) and then recomputed and refined in double on the host. delta = |f - f_ref| / f_ref "
                  "over the epicentre x in [0, x_e(n)], x_e(n) = acos(exp(-0.511/n)); Delta = |f - f_ref| over the "
                  "attenuation zone (x_e(n), pi/2] and over the whole range. x is psi for the Phong family, theta_h "
                  "for the Blinn family and the microfacet distributions.\n\n",
                  in->acc_grid->n_min, in->acc_grid->n_max, in->acc_grid->n_step, in->acc_grid->samples);
    md_printf(b, "| model | reference | max delta, epicentre | at n | at x (rad) | max Delta, attenuation | at n | at x (rad) "
                 "| max Delta, whole range | device vs double (4th-digit units) | status |\n");
    md_printf(b, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < in->nacc; i++) {
        const struct accuracy_result *r = &in->acc[i];
        md_printf(b, "| `");
        md_cell_text(b, r->model.label);
        md_printf(b, "` | `");
        md_cell_text(b, r->reference.label);
        md_printf(b, "` |");
        md_pct(b, r->epicentre.value);
        md_num(b, r->epicentre.n, "%.6g");
        md_num(b, r->epicentre.x, "%.5f");
        md_num(b, r->attenuation.value, "%.4g");
        md_num(b, r->attenuation.n, "%.6g");
        md_num(b, r->attenuation.x, "%.5f");
        md_num(b, r->whole.value, "%.4g");
        md_num(b, accuracy_check_in_digits(r), "%.2g");
        if (!r->ok) {
            md_printf(b, " failed: ");
            md_cell_text(b, r->reason);
            md_printf(b, " |\n");
        } else if (r->device_disagrees) {
            md_printf(b, " device_disagrees: ");
            md_cell_text(b, r->reason);
            md_printf(b, " |\n");
        } else if (r->invalid_count) {
            md_printf(b, " %lld invalid values (first at n = %g, x = %g) |\n", r->invalid_count, r->invalid_n, r->invalid_x);
        } else if (strcmp(r->model.label, r->reference.label) == 0) {
            md_printf(b, " reference (zero by definition) |\n");
        } else {
            md_printf(b, " ok |\n");
        }
    }
    md_printf(b, "\n");
}

static void block(struct md_buf *b, const char *heading, const struct report_block *blk)
{
    md_printf(b, "## %s\n\n", heading);
    if (blk->markdown) md_printf(b, "%s\n\n", blk->markdown);
    else md_printf(b, "Not available: %s\n\n", blk->missing ? blk->missing : "this part did not run.");
}

static void pictures(struct md_buf *b, const struct report_input *in, int section)
{
    int any = 0;
    for (int i = 0; i < in->npictures; i++) {
        const struct report_picture *p = &in->pictures[i];
        if (p->section != section) continue;
        any = 1;
        if (p->not_drawn[0]) {
            md_printf(b, "Not drawn, `%s`: ", p->file);
            md_cell_text(b, p->not_drawn);
            md_printf(b, "\n\n");
        } else if (file_exists(in->run_dir, p->file)) {
            md_printf(b, "![%s](%s)\n\n*", p->file, p->file);
            md_cell_text(b, p->caption);
            md_printf(b, "*\n\n");
        } else {
            md_printf(b, "Picture `%s` was not written (see the run's error output): ", p->file);
            md_cell_text(b, p->caption);
            md_printf(b, "\n\n");
        }
    }
    if (!any) md_printf(b, "No pictures in this section.\n\n");
}

char *report_markdown(const struct report_input *in)
{
    struct md_buf b;
    md_init(&b);
    md_printf(&b, "# brdfbench report\n\n");
    md_printf(&b, "| | |\n|---|---|\n");
    md_printf(&b, "| command | `%s` |\n", in->command ? in->command : "brdfbench all");
    if (in->date) md_printf(&b, "| date (UTC) | %s |\n", in->date);
    if (in->device) {
        md_printf(&b, "| OpenCL device | ");
        md_cell_text(&b, in->device);
        md_printf(&b, " |\n| platform | ");
        md_cell_text(&b, in->platform_version);
        md_printf(&b, " |\n");
    }
    if (in->host_cpu) {
        md_printf(&b, "| host CPU | ");
        md_cell_text(&b, in->host_cpu);
        md_printf(&b, " |\n");
    }
    if (in->git_revision) md_printf(&b, "| git revision | `%s` |\n", in->git_revision);
    if (in->wall_seconds >= 0) md_printf(&b, "| wall time | %.1f s |\n", in->wall_seconds);
    static const struct { const char *file, *what; } data[] = {
        {"accuracy.json", "the accuracy sweep (and `accuracy.csv`, per model per n)"},
        {"claims.json", "the claims with verdicts (and `claims.md`)"},
        {"fit.json", "the best affine cosine-quadratic model and the family's per-n limit"},
        {"q_sweep.json", "f_Q against Q"},
        {"energy.json", "albedo and reciprocity checks"},
        {"throughput.json", "throughput (and `throughput.csv`)"},
        {"render.json", "the image passes (pictures in `render/<scene>/`)"},
        {"plots.json", "every plot's data"},
        {"frontier.json", "cost against accuracy of every lobe approximation (and `frontier.csv`)"},
        {"measured.json", "the lobes against measured materials"},
    };
    md_printf(&b, "\nData files beside this page:");
    for (size_t i = 0; i < sizeof data / sizeof data[0]; i++)
        if (file_exists(in->run_dir, data[i].file)) md_printf(&b, " `%s`: %s;", data[i].file, data[i].what);
    md_printf(&b, " `field_<model>.json`: every heatmap's grid. `brdfbench plot %s` redraws the plots and heatmaps "
                  "from them without recomputing.\n\n",
              in->shown_dir ? in->shown_dir : in->run_dir);
    if (in->steps_md) md_printf(&b, "Steps:\n\n%s\n", in->steps_md);

    block(&b, "Claims of the papers", &in->claims);
    block(&b, "Beyond the papers: the best affine cosine-quadratic model", &in->fit);
    accuracy_table(&b, in);
    block(&b, "Throughput", &in->throughput);
    pictures(&b, in, REPORT_THROUGHPUT);

    md_printf(&b, "## Error heatmaps\n\n");
    md_printf(&b, "Per model against its reference: left, the relative error delta(x, n) over the epicentre, x "
                  "normalised per n as x / x_e(n) in [0, 1]; right, the absolute error Delta(x, n) over the attenuation "
                  "zone, x / x_e(n) on a log axis from 1 to the largest reach of pi/2 (grey where x passes pi/2 for that "
                  "n). n on a log axis; colour map viridis, scaled from 0 to each panel's maximum, which is ringed. The "
                  "maxima in the titles are those of the picture's grid; the table above gives the refined ones.\n\n");
    pictures(&b, in, REPORT_HEATMAPS);
    md_printf(&b, "## Plots\n\n");
    pictures(&b, in, REPORT_PLOTS);
    block(&b, "Image passes", &in->images);
    pictures(&b, in, REPORT_IMAGES);
    if (in->frontier.markdown || in->frontier.missing)
        block(&b, "Which lobe to ship", &in->frontier);
    if (in->measured.markdown || in->measured.missing)
        block(&b, "Measured materials", &in->measured);
    if (in->notes_md) md_printf(&b, "## Notes\n\n%s\n", in->notes_md);
    if (b.failed) {
        md_free(&b);
        return NULL;
    }
    return b.s;
}

int report_write(const struct report_input *in, char *err, size_t errlen)
{
    char *text = report_markdown(in);
    if (!text) {
        snprintf(err, errlen, "report.md: out of memory");
        return -1;
    }
    char path[4096];
    int rc = path_join(path, sizeof path, in->run_dir, "report.md");
    if (rc) snprintf(err, errlen, "%s/report.md: path too long", in->run_dir);
    else rc = write_file_atomic(path, text, strlen(text), err, errlen);
    free(text);
    return rc ? -1 : 0;
}

/* ---- image passes (render.json) ------------------------------------------------------ */

static double num_or_nan(const struct jr_value *o, const char *key)
{
    const struct jr_value *v = jr_get(o, key);
    return v && v->type == JR_NUM ? v->num : NAN;
}

static const char *str_or(const struct jr_value *o, const char *key, const char *dflt)
{
    const struct jr_value *v = jr_get(o, key);
    return v && v->type == JR_STR ? v->str : dflt;
}

/* The timing entry of a selected model in a scene's first timing size, or NULL. */
static const struct jr_value *timing_of(const struct jr_value *scene, const char *label, double *w, double *h)
{
    const struct jr_value *timings = jr_get(scene, "timings");
    if (!timings || timings->type != JR_ARR || timings->count < 1) return NULL;
    const struct jr_value *t = &timings->items[0];
    *w = num_or_nan(t, "width");
    *h = num_or_nan(t, "height");
    const struct jr_value *entries = jr_get(t, "entries");
    if (!entries || entries->type != JR_ARR) return NULL;
    for (size_t i = 0; i < entries->count; i++) {
        const struct jr_value *e = &entries->items[i];
        const struct jr_value *sel = jr_get(e, "selected_model");
        if (strcmp(str_or(e, "model", ""), label) == 0 && sel && sel->type == JR_BOOL && sel->num) return e;
    }
    return NULL;
}

/* A scene's He comparison (render.json, "he_comparison"): He's model beside Blinn-Phong fitted
 * to it and the cheap lobes at that n, with the contact sheets. */
static void report_he_comparison(const char *run_dir, struct md_buf *md, const struct jr_value *sc, const char *name,
                                 void (*add)(void *ctx, const char *file, const char *caption), void *ctx)
{
    const struct jr_value *hc = jr_get(sc, "he_comparison");
    const struct jr_value *entries = hc ? jr_get(hc, "entries") : NULL;
    if (!entries || entries->type != JR_ARR)
        return;
    md_printf(md, "%s shaded by He et al. 1991 (`%s`) beside Blinn-Phong fitted to its specular radiance by least "
                  "squares (n = %.4g, scale %.4g, relative rms residual %.3g) and the cheap lobes at that n, errors "
                  "against He's image:\n\n| shaded by | max abs error | mean abs error | max abs vs the fit |\n"
                  "|---|---:|---:|---:|\n",
              name, str_or(hc, "model", "?"), num_or_nan(hc, "n_fit"), num_or_nan(hc, "k_fit"),
              num_or_nan(hc, "relative_rms_residual"));
    for (size_t k = 0; k < entries->count; k++) {
        const struct jr_value *e = &entries->items[k], *mt = jr_get(e, "metrics"), *files = jr_get(e, "files");
        md_printf(md, "| `");
        md_cell_text(md, str_or(e, "name", "?"));
        md_printf(md, "` |");
        md_num(md, mt ? num_or_nan(mt, "max_abs") : NAN, "%.4g");
        md_num(md, mt ? num_or_nan(mt, "mean_abs") : NAN, "%.4g");
        md_num(md, num_or_nan(e, "max_abs_vs_blinn_fit"), "%.4g");
        md_printf(md, "\n");
        const char *contact = files ? str_or(files, "contact_sheet", NULL) : NULL;
        /* the pictures of the fit and of fq2 (the others are in the run folder) */
        if (contact && add && file_exists(run_dir, contact) &&
            (k == 0 || strncmp(str_or(e, "name", ""), "fq2@", 4) == 0)) {
            char caption[400];
            snprintf(caption, sizeof caption, "%s: He's model, %s, |error| against He (max %.3g)", name,
                     str_or(e, "name", "?"), mt ? num_or_nan(mt, "max_abs") : NAN);
            add(ctx, contact, caption);
        }
    }
    md_printf(md, "\n");
}

int report_render_summary(const char *run_dir, struct md_buf *md,
                          void (*add)(void *ctx, const char *file, const char *caption), void *ctx, char *err,
                          size_t errlen)
{
    char path[4096];
    struct jr_doc d;
    if (path_join(path, sizeof path, run_dir, "render.json")) {
        snprintf(err, errlen, "%s/render.json: path too long", run_dir);
        return 2;
    }
    if (jr_parse_file(path, &d, err, errlen)) return 2;
    const struct jr_value *scenes;
    if (jr_need(&d, &d.root, "scenes", JR_ARR, &scenes, err, errlen)) {
        jr_free(&d);
        return 2;
    }
    const struct jr_value *opt = jr_get(&d.root, "options");
    const struct jr_value *size = opt ? jr_get(opt, "image_size") : NULL;
    md_printf(md, "Each model shades full images on the device; its error image is |model - reference| of the "
                  "specular radiance (inferno, colour bar in the picture), the reference being the model's own "
                  "(phong, blinn, or the normalised lobes). Metrics over the foreground pixels; PSNR on the 8-bit "
                  "colours; timing: median kernel time at the timed size, as Mpixel/s and as a fraction of a copy "
                  "kernel moving the same bytes. Files: `render.json`, `render/<scene>/`.");
    if (size && size->type == JR_OBJ)
        md_printf(md, " Images %.0f x %.0f.", num_or_nan(size, "width"), num_or_nan(size, "height"));
    md_printf(md, "\n\n");
    for (size_t si = 0; si < scenes->count; si++) {
        const struct jr_value *sc = &scenes->items[si];
        const char *name = str_or(sc, "scene", "?");
        const struct jr_value *models = jr_get(sc, "models"), *image = jr_get(sc, "image");
        md_printf(md, "### Scene: %s\n\n", name);
        const char *src = str_or(sc, "source", NULL);
        if (src) md_printf(md, "Source: `%s`.\n\n", src);
        if (!models || models->type != JR_ARR) continue;
        const char *grid = image ? str_or(image, "contact_sheet", NULL) : NULL;
        if (grid && add) {
            char caption[200];
            snprintf(caption, sizeof caption, "%s: every model (rows) at each shininess (columns), with its error image",
                     name);
            add(ctx, grid, caption);
        }
        double tw = NAN, th = NAN;
        md_printf(md, "| model | reference | max abs error | RMSE | PSNR (dB) | share above threshold | double check | "
                      "Mpixel/s | of copy | speed-up vs reference | files |\n");
        md_printf(md, "|---|---|---:|---:|---:|---:|---|---:|---:|---:|---|\n");
        for (size_t mi = 0; mi < models->count; mi++) {
            const struct jr_value *m = &models->items[mi], *mt = jr_get(m, "metrics");
            const struct jr_value *chk = jr_get(m, "double_reference_check"), *files = jr_get(m, "files");
            const char *label = str_or(m, "model", "?");
            md_printf(md, "| `");
            md_cell_text(md, label);
            md_printf(md, "` | `");
            md_cell_text(md, str_or(m, "reference", "?"));
            md_printf(md, "` |");
            md_num(md, mt ? num_or_nan(mt, "max_abs") : NAN, "%.4g");
            md_num(md, mt ? num_or_nan(mt, "rmse") : NAN, "%.4g");
            md_num(md, mt ? num_or_nan(mt, "psnr_db") : NAN, "%.1f");
            md_pct(md, mt ? num_or_nan(mt, "share_above_threshold") : NAN);
            const struct jr_value *within = chk ? jr_get(chk, "within_bound") : NULL;
            md_printf(md, " %s |", within && within->type == JR_BOOL ? (within->num ? "within bound" : "**outside bound**")
                                                                   : "n/a");
            const struct jr_value *te = timing_of(sc, label, &tw, &th);
            md_num(md, te ? num_or_nan(te, "mpixel_per_s") : NAN, "%.0f");
            md_num(md, te ? num_or_nan(te, "fraction_of_copy") : NAN, "%.2f");
            md_num(md, te ? num_or_nan(te, "speedup_vs_reference") : NAN, "%.2f");
            const char *img = files ? str_or(files, "image", NULL) : NULL;
            const char *errimg = files ? str_or(files, "error_image", NULL) : NULL;
            const char *contact = files ? str_or(files, "contact_sheet", NULL) : NULL;
            if (img && file_exists(run_dir, img)) md_printf(md, " [image](%s)", img);
            if (errimg && file_exists(run_dir, errimg)) md_printf(md, " [error](%s)", errimg);
            const char *signed_img = files ? str_or(files, "signed_error_image", NULL) : NULL;
            if (signed_img && file_exists(run_dir, signed_img)) md_printf(md, " [signed error](%s)", signed_img);
            md_printf(md, " |\n");
            /* a model against itself has a black error image: its contact sheet shows nothing new */
            if (contact && strcmp(label, str_or(m, "reference", "")) != 0 && add) {
                char caption[400];
                snprintf(caption, sizeof caption, "%s, %s against %s: reference, model, |error| (max %.3g, PSNR %.1f dB)",
                         name, label, str_or(m, "reference", "?"), mt ? num_or_nan(mt, "max_abs") : NAN,
                         mt ? num_or_nan(mt, "psnr_db") : NAN);
                add(ctx, contact, caption);
            }
        }
        if (isfinite(tw)) md_printf(md, "\nTimed at %.0f x %.0f.\n", tw, th);
        md_printf(md, "\n");
        report_he_comparison(run_dir, md, sc, name, add, ctx);
    }
    jr_free(&d);
    return 0;
}
