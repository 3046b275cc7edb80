/* report.c - report.md of a run folder (see report.h). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "jsonr.h"
#include "outdir.h"
#include "plots.h"
#include "rdoc_read.h"
#include "report_claims.h"
#include "report_accuracy.h"
#include "report_docs.h"
#include "report_render.h"
#include "report_frontier.h"
#include "report_measured.h"
#include "report_run.h"
#include "report_throughput.h"
#include "room.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int report_file_exists(const char *dir, const char *name)
{
    char path[4096];
    struct stat st;
    if (path_join(path, sizeof path, dir, name)) return 0;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

/* ---- the rows the page is drawn from (report_docs.h) ------------------------------------ */

void report_docs_init(struct report_docs *docs, const char *run_dir)
{
    memset(docs, 0, sizeof *docs);
    docs->run_dir = run_dir;
}

void report_docs_free(struct report_docs *docs)
{
    for (int i = 0; i < docs->count; ++i)
        if (docs->state[i] == 0)
            rdoc_free(&docs->doc[i]);
    docs->count = 0;
}

const struct rdoc *report_doc(struct report_docs *docs, const char *file, int *rc, char *err, size_t errlen)
{
    int i = 0;
    while (i < docs->count && strcmp(docs->file[i], file) != 0)
        ++i;
    if (i == docs->count) {
        if (docs->count == REPORT_DOCS_MAX) {
            snprintf(err, errlen, "%s/%s: more result files than the report reads (%d)", docs->run_dir, file,
                     REPORT_DOCS_MAX);
            *rc = 2;
            return NULL;
        }
        snprintf(docs->file[i], sizeof docs->file[i], "%s", file);
        docs->count++;
        char path[4200];
        struct stat st;
        if (path_join(path, sizeof path, docs->run_dir, file)) {
            snprintf(docs->why[i], sizeof docs->why[i], "%s/%s: path too long", docs->run_dir, file);
            docs->state[i] = 2;
        } else if (stat(path, &st) != 0) {
            snprintf(docs->why[i], sizeof docs->why[i], "%s/%s: missing", docs->run_dir, file);
            docs->state[i] = 1;
        } else {
            docs->state[i] = rdoc_read_file(path, &docs->doc[i], docs->why[i], sizeof docs->why[i]) ? 2 : 0;
        }
    }
    *rc = docs->state[i];
    if (*rc) {
        snprintf(err, errlen, "%s", docs->why[i]);
        return NULL;
    }
    return &docs->doc[i];
}

int report_docs_put(struct report_docs *docs, const char *file, struct rdoc *rdoc, char *err, size_t errlen)
{
    int i = 0;
    while (i < docs->count && strcmp(docs->file[i], file) != 0)
        ++i;
    if (i < docs->count || docs->count == REPORT_DOCS_MAX || strlen(file) >= sizeof docs->file[0]) {
        snprintf(err, errlen, "%s: %s", file,
                 i < docs->count ? "already among the report's rows" : "more result files than the report reads");
        rdoc_free(rdoc);
        memset(rdoc, 0, sizeof *rdoc);
        return -1;
    }
    snprintf(docs->file[i], sizeof docs->file[i], "%s", file);
    docs->state[i] = 0;
    docs->why[i][0] = '\0';
    docs->doc[i] = *rdoc;   /* moved: its rows and texts are docs' now */
    memset(rdoc, 0, sizeof *rdoc);
    docs->count++;
    return 0;
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

/* "Accuracy per model", from accuracy.json's rows (report_accuracy.c). */
static int accuracy_table(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    int rc;
    const struct rdoc *acc = report_doc(&in->docs, "accuracy.json", &rc, err, errlen);
    if (rc == 2) return 2;
    report_accuracy_table(b, acc);
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

/* A part's section drawn from the rows of its result file by its page function (the function
 * the engine wrote its page with): "Which lobe to ship" from frontier.json, "Measured
 * materials" from measured.json. */
static int rows_block(struct md_buf *b, struct report_input *in, const char *heading, int part, const char *file,
                      int (*page)(struct md_buf *, const struct rdoc *), char *err, size_t errlen)
{
    md_printf(b, "## %s\n\n", heading);
    if (part_unavailable(b, in, part)) return 0;
    int rc;
    const struct rdoc *d = report_doc(&in->docs, file, &rc, err, errlen);
    if (!d) {
        if (rc == 1) snprintf(err + strlen(err), errlen - strlen(err), " (run.json records its part as done)");
        return 2;
    }
    if (page(b, d)) return 3;
    md_printf(b, "\n\n");
    return 0;
}

/* The claims of the papers: the page reproduce wrote as claims.md, drawn here from the same rows
 * (claims.json's, q_sweep.json's grid, physical.json's when the claims run measured the cost)
 * and embedded as claims.md was: its title dropped, its headings one level down. */
static int claims_block(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    md_printf(b, "## Claims of the papers\n\n");
    if (part_unavailable(b, in, REPORT_PART_CLAIMS)) return 0;
    int rc;
    const struct rdoc *claims = report_doc(&in->docs, "claims.json", &rc, err, errlen), *q_sweep = NULL, *physical = NULL;
    if (claims) q_sweep = report_doc(&in->docs, "q_sweep.json", &rc, err, errlen);
    if (q_sweep && rd_ctx_get(&claims->ctx, REPORT_CLAIMS_PHYSICAL_CTX)) {
        physical = report_doc(&in->docs, "physical.json", &rc, err, errlen);
        if (!physical) q_sweep = NULL;
    }
    if (!q_sweep) {   /* missing or unreadable, though run.json says the part ran */
        size_t n = strlen(err);
        snprintf(err + n, errlen - n, " (run.json records its part as done)");
        return 2;
    }
    struct md_buf page;
    md_init(&page);
    rc = report_claims_page(&page, claims, q_sweep, physical);
    if (!rc) md_embed(b, page.s ? page.s : "");
    md_free(&page);
    if (rc) return rc;
    md_printf(b, "\n\n");
    return 0;
}

/* "Beyond the papers": the family's limit, the best affine fit (uncapped and capped at fq2's
 * max Delta) and the models it is compared with, from fit.json's rows (report_accuracy.c). */
static int fit_block(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    md_printf(b, "## Beyond the papers: the best affine cosine-quadratic model\n\n");
    if (part_unavailable(b, in, REPORT_PART_FIT)) return 0;
    int rc;
    const struct rdoc *fit = report_doc(&in->docs, "fit.json", &rc, err, errlen);
    if (rc == 1) snprintf(err, errlen, "%s/fit.json: missing (run.json records its part as done)", in->run_dir);
    if (rc) return 2;
    return report_fit_block(b, fit, in->run_dir, err, errlen);
}

/* The image passes: the scenes left out, then render.json's summary with its pictures. */
static int images_block(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    md_printf(b, "## Image passes\n\n");
    if (part_unavailable(b, in, REPORT_PART_IMAGES)) return 0;
    const char *note = in->run.images_note;
    md_printf(b, "%s", note);
    if (note[0]) md_printf(b, "\n\n");
    int rc;
    const struct rdoc *render = report_doc(&in->docs, "render.json", &rc, err, errlen);
    if (rc) return 2;
    report_render_summary(render, in->run_dir, b, add_image_picture, in);
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
        } else if (report_file_exists(in->run_dir, p->file) && safe_link(p->file)) {
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

/* "Throughput": the throughput page drawn from throughput.json's rows (report_throughput.h),
 * taken in as a page of its own (md_embed), as throughput.md was. */
static int throughput_block(struct md_buf *b, struct report_input *in, char *err, size_t errlen)
{
    md_printf(b, "## Throughput\n\n");
    if (part_unavailable(b, in, REPORT_PART_THROUGHPUT)) return 0;
    int rc;
    const struct rdoc *tp = report_doc(&in->docs, "throughput.json", &rc, err, errlen);
    if (!tp) {
        if (rc == 1) snprintf(err, errlen, "%s/throughput.json: missing (run.json records its part as done)", in->run_dir);
        return 2;
    }
    struct md_buf page;
    md_init(&page);
    if (report_throughput_page(&page, tp, 1)) {
        md_free(&page);
        snprintf(err, errlen, "out of memory");
        return 3;
    }
    md_embed(b, page.s ? page.s : "");
    md_printf(b, "\n\n");
    md_free(&page);
    return 0;
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
        if (report_file_exists(in->run_dir, data[i].file)) md_printf(b, " `%s`: %s;", data[i].file, data[i].what);
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
    int rc = claims_block(b, in, err, errlen);
    if (!rc) rc = fit_block(b, in, err, errlen);
    if (!rc) rc = accuracy_table(b, in, err, errlen);
    if (!rc) rc = throughput_block(b, in, err, errlen);
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
        (rc = rows_block(b, in, "Which lobe to ship", REPORT_PART_FRONTIER, "frontier.json", report_frontier_page, err,
                         errlen)) != 0)
        return rc;
    if (in->run.part_ran[REPORT_PART_MEASURED] &&
        (rc = rows_block(b, in, "Measured materials", REPORT_PART_MEASURED, "measured.json", report_measured_page, err,
                         errlen)) != 0)
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
