/* test_report_pages.c - the frontier and measured pages (report_frontier.h, report_measured.h)
 * as functions of rows, without a device: rows built by hand (frontier) and a hand-written
 * brdfbench.measured/1 file read through its upgrade (measured). Every expected line below is
 * written by hand from the figures in this file (the page's formats: %.3g rates, %.4f%% and
 * %.4f errors, %.5g/%.4g measured figures), and the budget table's choices are worked out by
 * hand in the comments. The frontier rows written as a brdfbench.rows/1 document and read back
 * give the same page: the engine's page (rows in memory) and report.md's (rows from the file)
 * agree. */
#include "check.h"
#include "mdbuf.h"
#include "rdoc_read.h"
#include "report_frontier.h"
#include "report_measured.h"
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static char dir[4096];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

/* A model row of frontier.json's rows, as frontier_rows declares it. */
static void frontier_model(struct rdoc *d, const char *label, const char *kind, const double uniform[3],
                           double varying, const double rel[2], const double abs_[2], double psnr, const char *why,
                           int front)
{
    struct rd_row *r = rdoc_row(d, "", label);
    rd_row_key(r, "model", NULL, label);
    rd_row_attr(r, "kind", kind);
    static const char *const names[4] = { "n_2_1000.max_rel", "n_2_1000.max_abs", "n_16_1000.max_rel",
                                          "n_16_1000.max_abs" };
    for (int k = 0; k < 2; ++k) {
        rd_row_metric(d, r, names[2 * k], "1", RD_LOWER, 0, rel[k]);
        rd_row_metric(d, r, names[2 * k + 1], "1", RD_LOWER, 0, abs_[k]);
    }
    rd_row_metric(d, r, "psnr_db", "dB", RD_HIGHER, 0, psnr);
    struct rd_metric *m = rd_row_metric(d, r, FRONTIER_RATE_UNIFORM, "1/s", RD_NEITHER, 0, uniform[1]);
    m->lo = uniform[0];
    m->hi = uniform[2];
    m = rd_row_metric(d, r, FRONTIER_RATE_VARYING, "1/s", RD_NEITHER, 0, varying);
    m->lo = m->hi = varying;
    rd_row_metric(d, r, "on_front", "1", RD_NEITHER, 0, front);
    rd_row_textf(d, r, "source", "the %s lobe | a source with a bar", label);
    if (why)
        rd_row_text(d, r, "psnr_reason", why);
}

static char *page_of(const struct rdoc *d, int (*page)(struct md_buf *, const struct rdoc *))
{
    struct md_buf b;
    md_init(&b);
    CHECK(page(&b, d) == 0, "the page is made");
    return b.s;
}

static void has(const char *page, const char *want)
{
    CHECK(page && strstr(page, want), "the page holds \"%s\":\n%s", want, page ? page : "(none)");
}

static void check_frontier(void)
{
    CHECK_CASE("frontier page");
    struct rdoc d;
    rdoc_init(&d, "brdfbench.frontier/3", "frontier", "frontier.json");
    rd_ctx_put(&d.ctx, "rounds", "2");
    rd_ctx_put(&d.ctx, "reps", "3");
    /* rates [min, median, max]; errors [n from 2, n from 16] */
    frontier_model(&d, "phong", "reference", (double[3]){ 1e9, 2e9, 3e9 }, 1e9, (double[2]){ 0, 0 },
                   (double[2]){ 0, 0 }, NAN, "identical to its reference: PSNR is infinite", 1);
    frontier_model(&d, "fq2", "paper", (double[3]){ 1e10, 2e10, 3e10 }, 1.5e10, (double[2]){ 0.0125, 0.0125 },
                   (double[2]){ 0.128, 0.128 }, 44.0, NULL, 1);
    frontier_model(&d, "slowgood", "tuned", (double[3]){ 4e9, 5e9, 6e9 }, 5e9, (double[2]){ 0.005, 0.004 },
                   (double[2]){ 0.07, 0.05 }, 48.84, NULL, 0);
    frontier_model(&d, "fastbad", "engine", (double[3]){ 3e10, 4e10, 5e10 }, 4e10, (double[2]){ 0.1, 0.1 },
                   (double[2]){ 0.2, 0.2 }, 30.0, NULL, 1);
    CHECK(!d.oom, "rows built");
    char *page = page_of(&d, report_frontier_page);
    has(page, "(the median over 2 rounds over every model of each round's median of 3 launches;");
    has(page, "| phong | reference | **yes** | 2e+09 | 1e+09 | 0.0000% | 0.0000 | 0.0000% | 0.0000 | identical to its "
              "reference: PSNR is infinite |\n");
    has(page, "| fq2 | paper | **yes** | 2e+10 | 1.5e+10 | 1.2500% | 0.1280 | 1.2500% | 0.1280 | 44.0 |\n");
    has(page, "| slowgood | tuned |  | 5e+09 | 5e+09 | 0.5000% | 0.0700 | 0.4000% | 0.0500 | 48.8 |\n");
    /* a source's '|' escaped as a table cell's */
    has(page, "- `fq2`: the fq2 lobe \\| a source with a bar\n");
    has(page, "\nThe front: phong, fq2, fastbad.\n");
    /* budget fq2's min rate 1e10: a model counts when its max rate reaches it; slowgood (max 6e9)
       does not, fq2 (max 3e10, max delta 1.25%) beats fastbad (10%); a quarter of it, 2.5e9:
       slowgood (0.5% from n = 2, 0.4% from 16) is the most accurate; any cost: slowgood again
       (phong, a reference, is left out) */
    has(page, "| at least fq2's rate | fq2 (1.2500%, 0.1280; 2e+10/s) | fq2 (1.2500%, 0.1280; 2e+10/s) |\n");
    has(page, "| at least a quarter of fq2's rate | slowgood (0.5000%, 0.0700; 5e+09/s) | slowgood (0.4000%, 0.0500; "
              "5e+09/s) |\n");
    has(page, "| any cost | slowgood (0.5000%, 0.0700; 5e+09/s) | slowgood (0.4000%, 0.0500; 5e+09/s) |\n");
    has(page, "![evaluations/s against max delta](frontier_max_rel.png)\n");

    /* the same rows written as a rows document and read back: the same page */
    char path[4200];
    path_in(path, sizeof path, "frontier.rows.json");
    struct md_buf json;
    md_init(&json);
    rdoc_json(&d, &json);
    test_write_file(path, json.s);
    md_free(&json);
    struct rdoc back;
    char err[512];
    CHECK(rdoc_read_file(path, &back, err, sizeof err) == 0, "rows read back: %s", err);
    char *again = page_of(&back, report_frontier_page);
    CHECK(page && again && strcmp(page, again) == 0, "the page of the rows read back differs:\n%s\n---\n%s", page,
          again);
    free(again);
    rdoc_free(&back);
    free(page);
    rdoc_free(&d);

    /* no fq2 and no rate: no budget table, no plots */
    rdoc_init(&d, "brdfbench.frontier/3", "frontier", "frontier.json");
    frontier_model(&d, "cq2", "paper", (double[3]){ NAN, NAN, NAN }, NAN, (double[2]){ 0.07, 0.07 },
                   (double[2]){ 0.16, 0.16 }, NAN, "no image pass", 0);
    page = page_of(&d, report_frontier_page);
    has(page, "| cq2 | paper |  | nan | nan | 7.0000% | 0.1600 | 7.0000% | 0.1600 | no image pass |\n");
    has(page, "\nThe front: .\n");
    has(page, "fq2 is not in this run (or its rate is missing): no budgets relative to it.\n");
    has(page, "are not drawn: no model has a measured rate.\n");
    CHECK(!report_frontier_drawable(&d), "no rate: nothing to draw");
    free(page);
    rdoc_free(&d);
}

/* A material of a brdfbench.measured/1 file: its counts, fits and lobes as the layout holds them. */
#define MATERIAL(NAME, CHECK_STATUS, GGX_ALPHA)                                                                   \
    "{\"name\": \"" NAME "\", \"path\": \"x/" NAME ".binary\", \"cells\": 1458000, \"unmeasured_cells\": 10,"    \
    " \"negative_cells_rgb\": [0, 1, 2], \"below_horizon_cells\": 20, \"used_cells\": 1000, \"fit_cells\": 500,"  \
    " \"blinn_phong\": {\"status\": \"ok\", \"n\": 64, \"ks\": 2.5, \"kd\": 0.08, \"rms\": 0.01,"                  \
    "   \"rms_fit_cells\": 0.009, \"iterations\": 6},"                                                           \
    " \"ct_beckmann\": {\"status\": \"not run\", \"reason\": \"not run\", \"alpha\": null, \"n_of_alpha\": null,"  \
    "   \"F0\": null, \"ks\": null, \"kd\": null, \"rms\": null, \"rms_fit_cells\": null, \"iterations\": 0},"     \
    " \"ct_ggx\": {\"status\": \"ok\", \"alpha\": " GGX_ALPHA ", \"n_of_alpha\": 48, \"F0\": 0.3, \"ks\": 1.5,"    \
    "   \"kd\": 0.05, \"rms\": 0.002, \"rms_fit_cells\": 0.002, \"iterations\": 12},"                            \
    " \"lobes\": [{\"model\": \"fq2\", \"err_measured\": 0.125, \"err_phong\": 0.0625, \"ratio\": 2},"            \
    "   {\"model\": \"blinn\", \"err_measured\": 0.01, \"err_phong\": 0, \"ratio\": null,"                         \
    "    \"ratio_reason\": \"the lobe equals the fitted Blinn-Phong on every cell\"}],"                           \
    " \"device_check\": {\"status\": \"" CHECK_STATUS "\", \"points\": 1458000, \"same_cell\": 1458000,"          \
    "   \"value_differs\": 0}}"

static void check_measured(void)
{
    CHECK_CASE("measured page from a measured/1 file");
    char path[4200], err[512];
    path_in(path, sizeof path, "measured.json");
    /* two materials named gold (a/gold.binary, b/gold.binary): the second's pictures are gold-2 */
    test_write_file(path, "{\"schema\": \"brdfbench.measured/1\", \"context\": {\"device\": \"dev\", \"grid\":"
                          " {\"fit_cells_max\": 2000}}, \"materials\": [" MATERIAL("gold", "ok", "0.2") ", "
                          MATERIAL("gold", "mismatch", "0.25") "]}\n");
    struct rdoc d;
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 0, "measured/1 read: %s", err);
    if (check_failed)
        return;
    CHECK(strcmp(d.kind, "measured") == 0 && d.nrows == 2 * (1 + 3 + 2), "a row per material, fit and lobe: %d",
          d.nrows);
    CHECK(strcmp(rd_ctx_get(&d.ctx, "fit_cells_max"), "2000") == 0, "the context line fit_cells_max");
    const struct rd_row *beck = rdoc_find_row(&d, "fit", "ct-beckmann");
    CHECK(beck && !beck->ok && strcmp(beck->status, "not run") == 0 && strcmp(beck->label, "gold | fit ct-beckmann") == 0,
          "the fit not run: a failed row");
    CHECK(strcmp(d.rows[6].label, "gold-2") == 0 && strcmp(d.rows[11].label, "gold-2 | blinn") == 0,
          "the second gold keyed gold-2: %s, %s", d.rows[6].label, d.rows[11].label);
    char *page = page_of(&d, report_measured_page);
    has(page, "### gold\n\n1000 cells used (10 unmeasured, 20 below the surface); device lookup ok at every cell.\n\n");
    has(page, "| blinn-phong | n = 64, ks = 2.5, kd = 0.08 | 0.01 |\n"
              "| ct-beckmann | alpha = nan, F0 = nan, ks = nan, kd = nan | nan |\n"
              "| ct-ggx | alpha = 0.2, F0 = 0.3, ks = 1.5, kd = 0.05 | 0.002 |\n\n");
    has(page, "| fq2 | 0.125 | 0.0625 | 2 |\n| blinn | 0.01 | 0 | nan |\n");
    has(page, "(measured_errors_gold.png)");
    has(page, "device lookup **disagrees**.\n");
    has(page, "| ct-ggx | alpha = 0.25, F0 = 0.3,");
    has(page, "![gold-2: the measured slice with the fitted curves](measured_slice_gold-2.png)\n");
    free(page);
    rdoc_free(&d);
}

int main(void)
{
    static void (*const tests[])(void) = { check_frontier, check_measured };
    return test_run_in_tmpdir(dir, sizeof dir, "test_report_pages", tests, sizeof tests / sizeof tests[0]);
}
