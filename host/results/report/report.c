/* report.c - report.md of a run folder (see report.h). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "infile.h"
#include "jsonr.h"
#include "outdir.h"
#include "plots.h"
#include "report_docs.h"
#include "report_run.h"
#include "room.h"
#include "schemas.h"


#include <errno.h>
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

/* What report.md is made of, as read from the run folder. */
struct report_input {
    const char *run_dir;
    struct report_run_doc run;
    struct report_docs docs;          /* the result files' rows: what the sections are drawn from */
    struct report_picture *pictures;  /* run.json's, then those of the image passes */
    int npictures, cap;
    int out_of_memory;
};

static void add_picture(struct report_input *in, const char *file, int section, const char *caption,
                        const char *not_drawn)
{
    struct report_picture *pictures = room_for_one(in->pictures, in->npictures, &in->cap, sizeof *pictures, 32);
    if (!pictures) {
        in->out_of_memory = 1;
        return;
    }
    in->pictures = pictures;
    struct report_picture *p = &in->pictures[in->npictures++];
    snprintf(p->file, sizeof p->file, "%s", file);
    snprintf(p->caption, sizeof p->caption, "%s", caption);
    snprintf(p->not_drawn, sizeof p->not_drawn, "%s", not_drawn ? not_drawn : "");
    p->section = section;
}

static void add_image_picture(void *ctx, const char *file, const char *caption)
{
    add_picture(ctx, file, REPORT_IMAGES, caption, NULL);
}

/* A number member of o, or of o's member obj (NULL: o itself); NAN when absent. */
static double num_at(const struct jr_value *o, const char *obj, const char *key)
{
    const struct jr_value *v = obj ? jr_get(o, obj) : o;
    return v ? jr_num_or_nan(v, key) : NAN;
}

/* A result document of the run folder, checked against its schema (or `older`, a previous
 * version with the same members, when not NULL). Returns 0, 1 when the file does not exist, or
 * 2 with a message. */
static int read_doc(const char *run_dir, const char *name, const char *schema, const char *older, struct jr_doc *d,
                    char *err, size_t errlen)
{
    char path[4200];
    const char *have;
    if (path_join(path, sizeof path, run_dir, name)) {
        snprintf(err, errlen, "%s/%s: path too long", run_dir, name);
        return 2;
    }
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) return 1;
    if (jr_parse_file(path, d, err, errlen)) return 2;
    if (jr_need_str(d, &d->root, "schema", &have, err, errlen) ||
        (strcmp(have, schema) != 0 && !(older && strcmp(have, older) == 0) && jr_fail(d, &d->root, err, errlen, "schema \"%s\" is not %s", have, schema))) {
        jr_free(d);
        return 2;
    }
    return 0;
}

static const char *accuracy_status_text(struct md_buf *b, const struct jr_value *r)
{
    const char *status = jr_str_or(r, "status", ""), *reason = jr_str_or(r, "reason", "");
    if (strcmp(status, "failed") == 0 || strcmp(status, "device_disagrees") == 0) {
        md_printf(b, " %s: ", status);
        md_cell_text(b, reason);
        return " |\n";
    }
    if (strcmp(status, "invalid_values") == 0) {
        md_printf(b, " %lld invalid values (first at n = %g, x = %g)", (long long)num_at(r, "invalid", "count"),
                  num_at(r, "invalid", "at_n"), num_at(r, "invalid", "at_x"));
        return " |\n";
    }
    if (strcmp(jr_str_or(r, "label", ""), jr_str_or(r, "reference", "")) == 0) return " reference (zero by definition) |\n";
    return " ok |\n";
}

static int accuracy_table(struct md_buf *b, const struct report_input *in, char *err, size_t errlen)
{
    struct jr_doc d;
    md_printf(b, "## Accuracy per model\n\n");
    int rc = read_doc(in->run_dir, "accuracy.json", ACCURACY_SCHEMA, ACCURACY_SCHEMA_V1, &d, err, errlen);
    const struct jr_value *rows = rc ? NULL : jr_get(&d.root, "results");
    if (rc == 2) return 2;
    if (!rows || rows->type != JR_ARR || rows->count < 1) {
        md_printf(b, "Not available: the accuracy sweep did not run.\n\n");
        if (!rc) jr_free(&d);
        return 0;
    }
    const struct jr_value *ctx = jr_get(&d.root, "context"), *grid = ctx ? jr_get(ctx, "grid") : NULL;
    if (grid)
        md_printf(b,
                  "Dense grid: n from %g to %g in steps of %g, %ld samples per zone per n; each maximum located on the "
                  "device (float) and then recomputed and refined in double on the host. delta = |f - f_ref| / f_ref "
                  "over the epicentre x in [0, x_e(n)], x_e(n) = acos(exp(-0.511/n)); Delta = |f - f_ref| over the "
                  "attenuation zone (x_e(n), pi/2] and over the whole range. x is psi for the Phong family, theta_h "
                  "for the Blinn family and the microfacet distributions.\n\n",
                  num_at(grid, NULL, "n_min"), num_at(grid, NULL, "n_max"), num_at(grid, NULL, "n_step"),
                  (long)num_at(grid, NULL, "samples_per_zone"));
    md_printf(b, "| model | reference | max delta, epicentre | at n | at x (rad) | max Delta, attenuation | at n | at x (rad) "
                 "| max Delta, whole range | device vs double (4th-digit units) | status |\n");
    md_printf(b, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (size_t i = 0; i < rows->count; i++) {
        const struct jr_value *r = &rows->items[i];
        md_printf(b, "| `");
        md_cell_text(b, jr_str_or(r, "label", ""));
        md_printf(b, "` | `");
        md_cell_text(b, jr_str_or(r, "reference", ""));
        md_printf(b, "` |");
        md_pct(b, num_at(r, "epicentre", "max_rel"));
        md_num(b, num_at(r, "epicentre", "at_n"), "%.6g");
        md_num(b, num_at(r, "epicentre", "at_x"), "%.5f");
        md_num(b, num_at(r, "attenuation", "max_abs"), "%.4g");
        md_num(b, num_at(r, "attenuation", "at_n"), "%.6g");
        md_num(b, num_at(r, "attenuation", "at_x"), "%.5f");
        md_num(b, num_at(r, "whole", "max_abs"), "%.4g");
        md_num(b, num_at(r, "check", "in_4th_digit_units"), "%.2g");
        md_printf(b, "%s", accuracy_status_text(b, r));
    }
    md_printf(b, "\n");
    jr_free(&d);
    return 0;
}

static void not_available(struct md_buf *b, const char *why)
{
    md_printf(b, "Not available: %s\n\n", why ? why : "this part did not run.");
}

/* A part's state: 0 when its section can be made, else the reason is printed and 1 returned. */
static int part_unavailable(struct md_buf *b, const struct report_input *in, int part)
{
    if (in->run.part_ran[part] && !in->run.part_missing[part]) return 0;
    not_available(b, in->run.part_ran[part] ? in->run.part_missing[part] : NULL);
    return 1;
}

/* A part's own page (claims.md, throughput.md, ...) as a section of this one. */
static int page_block(struct md_buf *b, const struct report_input *in, const char *heading, int part, char *err,
                      size_t errlen)
{
    md_printf(b, "## %s\n\n", heading);
    if (part_unavailable(b, in, part)) return 0;
    char path[4200], why[200], *text = NULL;
    size_t len = 0;
    const char *page = report_part_page(part);
    if (path_join(path, sizeof path, in->run_dir, page)) {
        snprintf(err, errlen, "%s/%s: path too long", in->run_dir, page);
        return 2;
    }
    int rc = infile_read(path, 0, (size_t)64 << 20, &text, &len, why, sizeof why);
    if (rc) {
        snprintf(err, errlen, "%s: %s (run.json records its part as done)", path, rc == -2 ? "out of memory" : why);
        return rc == -2 ? 3 : 2;
    }
    /* claims.md and throughput.md are pages of their own; frontier.md and measured.md are
       written as this section */
    if (part == REPORT_PART_CLAIMS || part == REPORT_PART_THROUGHPUT) md_embed(b, text);
    else md_printf(b, "%s", text);
    md_printf(b, "\n\n");
    free(text);
    return 0;
}

/* "Beyond the papers": the family's limit, the best affine fit (uncapped and capped at fq2's
 * max Delta) and the models it is compared with, from fit.json. A fit's row is there when its
 * device sweep ran: then it leads fit.json's "compare" list, in that order. */
static int fit_block(struct md_buf *b, const struct report_input *in, char *err, size_t errlen)
{
    struct jr_doc d;
    md_printf(b, "## Beyond the papers: the best affine cosine-quadratic model\n\n");
    if (part_unavailable(b, in, REPORT_PART_FIT)) return 0;
    int rc = read_doc(in->run_dir, "fit.json", FIT_SCHEMA, FIT_SCHEMA_V1, &d, err, errlen);
    if (rc == 1) snprintf(err, errlen, "%s/fit.json: missing (run.json records its part as done)", in->run_dir);
    if (rc) return 2;
    const struct jr_value *root = &d.root, *cmp = jr_get(root, "compare"), *ctx = jr_get(root, "context");
    const struct jr_value *grid = ctx ? jr_get(ctx, "grid") : NULL;
    if (!cmp || cmp->type != JR_ARR || !grid) {
        jr_free(&d);
        snprintf(err, errlen, "%s/fit.json: no \"compare\" list or no context grid", in->run_dir);
        return 2;
    }
    md_printf(b, "For f = (k(n)(c - 1) + 1)^2 zeroed past its root, over n in [%g, %g] (`brdfbench fit`, `fit.json`):\n\n",
              num_at(grid, NULL, "n_min"), num_at(grid, NULL, "n_max"));
    md_printf(b, "| model | max δ (epicentre) | max Δ (attenuation) |\n|---|---|---|\n");
    md_printf(b, "| per-n minimax k(n): the family's limit | %.4f%% (n = %g) | |\n",
              100 * num_at(root, "limit_overall", "max_rel"), num_at(root, "limit_overall", "at_n"));
    const struct jr_value *fits[2] = { root, jr_get(root, "capped_at_fq2") };
    static const char *const notes[2] = { " (best affine, uncapped)", " (max Δ capped at fq2's)" };
    size_t k = 0;
    for (int i = 0; i < 2; ++i) {
        const char *model = fits[i] ? jr_str_or(fits[i], "model", "") : "";
        if (!model[0] || k >= cmp->count || strcmp(jr_str_or(&cmp->items[k], "model", ""), model) != 0) continue;
        md_printf(b, "| `%s`%s | %.4f%% | %.5f |\n", model, notes[i], 100 * num_at(&cmp->items[k], "epicentre", "max_rel"),
                  num_at(&cmp->items[k], "attenuation", "max_abs"));
        k++;
    }
    for (; k < cmp->count; ++k)
        md_printf(b, "| %s | %.4f%% | %.5f |\n", jr_str_or(&cmp->items[k], "model", ""),
                  100 * num_at(&cmp->items[k], "epicentre", "max_rel"), num_at(&cmp->items[k], "attenuation", "max_abs"));
    const struct jr_value *verdict = jr_get(root, "verdict");
    if (verdict && jr_str_or(verdict, "text", "")[0]) md_printf(b, "\n%s\n", jr_str_or(verdict, "text", ""));
    md_printf(b, "\n\n");
    jr_free(&d);
    return 0;
}

/* The image passes: the scenes left out, then render.json's summary with its pictures. */
static int images_block(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    md_printf(b, "## Image passes\n\n");
    if (part_unavailable(b, in, REPORT_PART_IMAGES)) return 0;
    const char *note = in->run.images_note;
    md_printf(b, "%s", note);
    if (note[0]) md_printf(b, "\n\n");
    if (report_render_summary(in->run_dir, b, add_image_picture, in, err, errlen)) return 2;
    md_printf(b, "\n\n");
    return 0;
}

/* A picture's file name that can stand as a markdown link target and alt text as it is. */
static int safe_link(const char *f)
{
    for (const char *p = f; *p; ++p)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || strchr("._-/", *p)))
            return 0;
    return *f != '\0';
}

static void pictures(struct md_buf *b, const struct report_input *in, int section)
{
    int any = 0;
    for (int i = 0; i < in->npictures; i++) {
        const struct report_picture *p = &in->pictures[i];
        if (p->section != section) continue;
        any = 1;
        if (p->not_drawn[0]) {
            md_printf(b, "Not drawn, ");
            md_code(b, p->file);
            md_printf(b, ": ");
            md_cell_text(b, p->not_drawn);
            md_printf(b, "\n\n");
        } else if (file_exists(in->run_dir, p->file) && safe_link(p->file)) {
            md_printf(b, "![%s](%s)\n\n*", p->file, p->file);
            md_cell_text(b, p->caption);
            md_printf(b, "*\n\n");
        } else {
            md_printf(b, "Picture ");
            md_code(b, p->file);
            md_printf(b, " was not written, or its name is no plain file name (see the run's error output): ");
            md_cell_text(b, p->caption);
            md_printf(b, "\n\n");
        }
    }
    if (!any) md_printf(b, "No pictures in this section.\n\n");
}

static void header(struct md_buf *b, const struct report_input *in)
{
    const struct report_run_doc *run = &in->run;
    md_printf(b, "# brdfbench report\n\n");
    md_printf(b, "| | |\n|---|---|\n");
    md_printf(b, "| command | ");
    md_code(b, run->command);
    md_printf(b, " |\n| date (UTC) | ");
    md_cell_text(b, run->date);
    md_printf(b, " |\n");
    if (run->device) {
        md_printf(b, "| OpenCL device | ");
        md_cell_text(b, run->device);
        md_printf(b, " |\n| platform | ");
        md_cell_text(b, run->platform_version);
        md_printf(b, " |\n");
    }
    md_printf(b, "| host CPU | ");
    md_cell_text(b, run->host_cpu);
    md_printf(b, " |\n");
    md_printf(b, "| git revision | ");
    md_code(b, run->git_revision);
    md_printf(b, " |\n");
    if (run->wall_seconds >= 0) md_printf(b, "| wall time | %.1f s |\n", run->wall_seconds);
    static const struct { const char *file, *what; } data[] = {
        {"run.json", "what this page is made from with the files below (`brdfbench report` rebuilds it)"},
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
    if (plots_run_is_quick(in->run_dir))
        md_printf(b, "\n**Coarse grids (`--quick`): a trial run, not for figures.** Every picture carries the stamp "
                     "\"%s\".\n", PLOTS_QUICK_STAMP);
    md_printf(b, "\nData files beside this page:");
    for (size_t i = 0; i < sizeof data / sizeof data[0]; i++)
        if (file_exists(in->run_dir, data[i].file)) md_printf(b, " `%s`: %s;", data[i].file, data[i].what);
    md_printf(b, " `field_<model>.json`: every heatmap's grid. ");
    {
        /* the folder as the user named it: inline code, whatever it holds */
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "brdfbench plot %s", run->folder);
        md_code(b, cmd);
    }
    md_printf(b, " redraws the plots and heatmaps from them without recomputing.\n\n");
}

static void steps(struct md_buf *b, const struct report_input *in)
{
    const struct jr_value *st = in->run.steps;
    md_printf(b, "Steps:\n\n");
    for (size_t i = 0; i < st->count; i++) {
        const struct jr_value *s = &st->items[i];
        md_printf(b, "%zu. **", i + 1);
        md_text(b, jr_str_or(s, "name", ""));
        md_printf(b, "**: ");
        if (strcmp(jr_str_or(s, "status", ""), "ok") == 0) {
            md_text(b, jr_str_or(s, "message", ""));
            md_printf(b, " (%.1f s)\n", num_at(s, NULL, "seconds"));
        } else {
            md_printf(b, "failed (exit %d)\n", (int)num_at(s, NULL, "exit_code"));
        }
    }
    md_printf(b, "%zu. **report**: report.md\n\n", st->count + 1);
}

static int read_pictures(struct report_input *in)
{
    const struct jr_value *pics = in->run.pictures;
    for (size_t i = 0; i < pics->count; i++) {
        const struct jr_value *p = &pics->items[i], *nd = jr_get(p, "not_drawn");
        add_picture(in, jr_str_or(p, "file", ""), report_section_of(jr_str_or(p, "section", "")), jr_str_or(p, "caption", ""),
                    nd && nd->type == JR_STR ? nd->str : NULL);
    }
    return in->out_of_memory ? 3 : 0;
}

static int body(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    header(b, in);
    steps(b, in);
    int rc = page_block(b, in, "Claims of the papers", REPORT_PART_CLAIMS, err, errlen);
    if (!rc) rc = fit_block(b, in, err, errlen);
    if (!rc) rc = accuracy_table(b, in, err, errlen);
    if (!rc) rc = page_block(b, in, "Throughput", REPORT_PART_THROUGHPUT, err, errlen);
    if (rc) return rc;
    pictures(b, in, REPORT_THROUGHPUT);
    md_printf(b, "## Error heatmaps\n\n");
    md_printf(b, "Per model against its reference: left, the relative error delta(x, n) over the epicentre, x "
                 "normalised per n as x / x_e(n) in [0, 1]; right, the absolute error Delta(x, n) over the attenuation "
                 "zone, x / x_e(n) on a log axis from 1 to the largest reach of pi/2 (grey where x passes pi/2 for that "
                 "n). n on a log axis; colour map viridis, scaled from 0 to each panel's maximum, which is ringed. The "
                 "maxima in the titles are those of the picture's grid; the table above gives the refined ones.\n\n");
    pictures(b, in, REPORT_HEATMAPS);
    md_printf(b, "## Plots\n\n");
    pictures(b, in, REPORT_PLOTS);
    if ((rc = images_block(b, in, err, errlen)) != 0) return rc;
    pictures(b, in, REPORT_IMAGES);
    if (in->run.part_ran[REPORT_PART_FRONTIER] &&
        (rc = page_block(b, in, "Which lobe to ship", REPORT_PART_FRONTIER, err, errlen)) != 0)
        return rc;
    if (in->run.part_ran[REPORT_PART_MEASURED] &&
        (rc = page_block(b, in, "Measured materials", REPORT_PART_MEASURED, err, errlen)) != 0)
        return rc;
    return in->out_of_memory ? 3 : 0;
}

int report_build_docs(const char *run_dir, struct report_docs *docs, char **text, char *err, size_t errlen)
{
    /* on the heap: the rows of every result file are large for a stack */
    struct report_input *in = calloc(1, sizeof *in);
    struct md_buf b;
    *text = NULL;
    if (!in) {
        snprintf(err, errlen, "report.md: out of memory");
        return 3;
    }
    in->run_dir = run_dir;
    if (report_run_read(run_dir, &in->run, err, errlen)) {
        free(in);
        return 2;
    }
    in->docs = *docs;   /* the sections read (and add to) the caller's docs; handed back below */
    in->docs.run_dir = run_dir;
    md_init(&b);
    int rc = read_pictures(in);
    if (!rc) rc = body(&b, in, err, errlen);
    if (!rc && b.failed) rc = 3;
    if (rc == 3) snprintf(err, errlen, "report.md: out of memory");
    *docs = in->docs;
    report_run_free(&in->run);
    free(in->pictures);
    free(in);
    if (rc) {
        md_free(&b);
        return rc;
    }
    *text = b.s;
    return 0;
}

/* report_build and report_rebuild: a docs of the folder's files alone, on the heap. */
static struct report_docs *folder_docs(const char *run_dir, char *err, size_t errlen)
{
    struct report_docs *docs = malloc(sizeof *docs);
    if (docs)
        report_docs_init(docs, run_dir);
    else
        snprintf(err, errlen, "report.md: out of memory");
    return docs;
}

static void folder_docs_free(struct report_docs *docs)
{
    report_docs_free(docs);
    free(docs);
}

int report_build(const char *run_dir, char **text, char *err, size_t errlen)
{
    struct report_docs *docs = folder_docs(run_dir, err, errlen);
    *text = NULL;
    if (!docs) return 3;
    int rc = report_build_docs(run_dir, docs, text, err, errlen);
    folder_docs_free(docs);
    return rc;
}

int report_rebuild_docs(const char *run_dir, struct report_docs *docs, const char *out, char *err, size_t errlen)
{
    char *text = NULL, path[4200];
    int rc = report_build_docs(run_dir, docs, &text, err, errlen);
    if (rc) return rc;
    if (!out && path_join(path, sizeof path, run_dir, "report.md")) {
        snprintf(err, errlen, "%s/report.md: path too long", run_dir);
        rc = 3;
    } else {
        rc = write_file_atomic(out ? out : path, text, strlen(text), err, errlen) ? 3 : 0;
    }
    free(text);
    return rc;
}

int report_rebuild(const char *run_dir, const char *out, char *err, size_t errlen)
{
    struct report_docs *docs = folder_docs(run_dir, err, errlen);
    if (!docs) return 3;
    int rc = report_rebuild_docs(run_dir, docs, out, err, errlen);
    folder_docs_free(docs);
    return rc;
}

/* ---- image passes (render.json) ------------------------------------------------------ */

/* The timing entry of a selected model in a scene's first timing size, or NULL. */
static const struct jr_value *timing_of(const struct jr_value *scene, const char *label, double *w, double *h)
{
    const struct jr_value *timings = jr_get(scene, "timings");
    if (!timings || timings->type != JR_ARR || timings->count < 1) return NULL;
    const struct jr_value *t = &timings->items[0];
    *w = jr_num_or_nan(t, "width");
    *h = jr_num_or_nan(t, "height");
    const struct jr_value *entries = jr_get(t, "entries");
    if (!entries || entries->type != JR_ARR) return NULL;
    for (size_t i = 0; i < entries->count; i++) {
        const struct jr_value *e = &entries->items[i];
        const struct jr_value *sel = jr_get(e, "selected_model");
        if (strcmp(jr_str_or(e, "model", ""), label) == 0 && sel && sel->type == JR_BOOL && sel->num) return e;
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
              name, jr_str_or(hc, "model", "?"), jr_num_or_nan(hc, "n_fit"), jr_num_or_nan(hc, "k_fit"),
              jr_num_or_nan(hc, "relative_rms_residual"));
    for (size_t k = 0; k < entries->count; k++) {
        const struct jr_value *e = &entries->items[k], *mt = jr_get(e, "metrics"), *files = jr_get(e, "files");
        md_printf(md, "| `");
        md_cell_text(md, jr_str_or(e, "name", "?"));
        md_printf(md, "` |");
        md_num(md, mt ? jr_num_or_nan(mt, "max_abs") : NAN, "%.4g");
        md_num(md, mt ? jr_num_or_nan(mt, "mean_abs") : NAN, "%.4g");
        md_num(md, jr_num_or_nan(e, "max_abs_vs_blinn_fit"), "%.4g");
        md_printf(md, "\n");
        const char *contact = files ? jr_str_or(files, "contact_sheet", NULL) : NULL;
        /* the pictures of the fit and of fq2 (the others are in the run folder) */
        if (contact && add && file_exists(run_dir, contact) &&
            (k == 0 || strncmp(jr_str_or(e, "name", ""), "fq2@", 4) == 0)) {
            char caption[400];
            snprintf(caption, sizeof caption, "%s: He's model, %s, |error| against He (max %.3g)", name,
                     jr_str_or(e, "name", "?"), mt ? jr_num_or_nan(mt, "max_abs") : NAN);
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
        md_printf(md, " Images %.0f x %.0f.", jr_num_or_nan(size, "width"), jr_num_or_nan(size, "height"));
    md_printf(md, "\n\n");
    for (size_t si = 0; si < scenes->count; si++) {
        const struct jr_value *sc = &scenes->items[si];
        const char *name = jr_str_or(sc, "scene", "?");
        const struct jr_value *models = jr_get(sc, "models"), *image = jr_get(sc, "image");
        md_printf(md, "### Scene: %s\n\n", name);
        const char *src = jr_str_or(sc, "source", NULL);
        if (src) md_printf(md, "Source: `%s`.\n\n", src);
        if (!models || models->type != JR_ARR) continue;
        const char *grid = image ? jr_str_or(image, "contact_sheet", NULL) : NULL;
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
            const char *label = jr_str_or(m, "model", "?");
            md_printf(md, "| `");
            md_cell_text(md, label);
            md_printf(md, "` | `");
            md_cell_text(md, jr_str_or(m, "reference", "?"));
            md_printf(md, "` |");
            md_num(md, mt ? jr_num_or_nan(mt, "max_abs") : NAN, "%.4g");
            md_num(md, mt ? jr_num_or_nan(mt, "rmse") : NAN, "%.4g");
            md_num(md, mt ? jr_num_or_nan(mt, "psnr_db") : NAN, "%.1f");
            md_pct(md, mt ? jr_num_or_nan(mt, "share_above_threshold") : NAN);
            const struct jr_value *within = chk ? jr_get(chk, "within_bound") : NULL;
            md_printf(md, " %s |", within && within->type == JR_BOOL ? (within->num ? "within bound" : "**outside bound**")
                                                                   : "n/a");
            const struct jr_value *te = timing_of(sc, label, &tw, &th);
            md_num(md, te ? jr_num_or_nan(te, "mpixel_per_s") : NAN, "%.0f");
            md_num(md, te ? jr_num_or_nan(te, "fraction_of_copy") : NAN, "%.2f");
            md_num(md, te ? jr_num_or_nan(te, "speedup_vs_reference") : NAN, "%.2f");
            const char *img = files ? jr_str_or(files, "image", NULL) : NULL;
            const char *errimg = files ? jr_str_or(files, "error_image", NULL) : NULL;
            const char *contact = files ? jr_str_or(files, "contact_sheet", NULL) : NULL;
            if (img && file_exists(run_dir, img)) md_printf(md, " [image](%s)", img);
            if (errimg && file_exists(run_dir, errimg)) md_printf(md, " [error](%s)", errimg);
            const char *signed_img = files ? jr_str_or(files, "signed_error_image", NULL) : NULL;
            if (signed_img && file_exists(run_dir, signed_img)) md_printf(md, " [signed error](%s)", signed_img);
            md_printf(md, " |\n");
            /* a model against itself has a black error image: its contact sheet shows nothing new */
            if (contact && strcmp(label, jr_str_or(m, "reference", "")) != 0 && add) {
                char caption[400];
                snprintf(caption, sizeof caption, "%s, %s against %s: reference, model, |error| (max %.3g, PSNR %.1f dB)",
                         name, label, jr_str_or(m, "reference", "?"), mt ? jr_num_or_nan(mt, "max_abs") : NAN,
                         mt ? jr_num_or_nan(mt, "psnr_db") : NAN);
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
