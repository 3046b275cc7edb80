/* test_rdoc.c - the result document (rdoc.h, rdoc_read.h): hand-written result files of each
 * kind read as rows, and the rows written as CSV, markdown and brdfbench.rows/1 and read back.
 * Every expected key, label, unit, direction and value below is written by hand from the file
 * text in the same test, not taken from the program's output. No device. */
#include "check.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "rdoc_read.h"
#include "schemas.h"
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static char dir[4096];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

/* Writes text as the file `name` of the test folder and reads it as rows: rdoc_read_file's code. */
static int rows_of(const char *name, const char *text, struct rdoc *d, char *err, size_t errlen)
{
    char path[4200];
    path_in(path, sizeof path, name);
    test_write_file(path, text);
    return rdoc_read_file(path, d, err, errlen);
}

static const struct rd_row *row_labelled(const struct rdoc *d, const char *label)
{
    for (int i = 0; i < d->nrows; ++i)
        if (strcmp(d->rows[i].label, label) == 0)
            return &d->rows[i];
    return NULL;
}

/* Lines of text ending in "\r\n" or "\n". */
static int count_lines(const char *s)
{
    int n = 0;
    for (; s && *s; ++s)
        n += *s == '\n';
    return n;
}

static void check_throughput(void)
{
    CHECK_CASE("throughput.json as rows");
    char path[4200], err[512];
    struct rdoc d;
    CHECK(rows_of("throughput.json",
        "{\"schema\": \"brdfbench.throughput/3\",\n"
        " \"context\": {\"device\": \"dev0\", \"throughput\": {\"reps\": 3, \"runner\": {\"disturbed_reps\": 2}}},\n"
        " \"peak\": {\"status\": \"ok\", \"flops_per_s\": {\"min\": 1e10, \"median\": 2e10, \"max\": 3e10},\n"
        "          \"flops_per_s_reps\": [1e10, 2e10, 3e10]},\n"
        " \"results\": [\n"
        "  {\"label\": \"pow\", \"kind\": \"builtin\", \"variant\": \"default\", \"n_mode\": \"uniform\", \"status\": \"ok\",\n"
        "   \"evals_per_s\": {\"min\": 1e8, \"median\": 2e8, \"max\": 4e8}, \"evals_per_s_reps\": [4e8, 2e8, 1e8],\n"
        "   \"normalised_reps\": [0.5, 0.25, 0.125], \"normalised_cpu_reps\": [0.75, 0.5, 0.25],\n"
        "   \"preemption_retries\": 1, \"disturbed_reps\": 2},\n"
        "  {\"label\": \"fq2\", \"kind\": \"model\", \"variant\": \"fast\", \"n_mode\": \"varying\", \"status\": \"failed\",\n"
        "   \"reason\": \"the kernel failed\", \"evals_per_s\": {\"min\": null, \"median\": null, \"max\": null}}]}\n",
                  &d, err, sizeof err) == 0, "read: %s", err);
    CHECK(strcmp(d.kind, "throughput") == 0 && strcmp(d.file, "throughput.json") == 0, "kind %s file %s", d.kind,
          d.file);
    CHECK(d.nrows == 3, "the peak and two results: %d rows", d.nrows);
    CHECK(d.disturbed == 2, "the runner's disturbed repetitions: %d", d.disturbed);
    CHECK(rd_ctx_get(&d.ctx, "device") && strcmp(rd_ctx_get(&d.ctx, "device"), "dev0") == 0, "context device");
    const struct rd_row *pk = row_labelled(&d, "peak (reference kernel)");
    CHECK(pk && pk->nmetrics == 1 && strcmp(pk->metrics[0].name, "flops_per_s") == 0, "the peak's rate");
    if (pk && pk->nmetrics == 1) {
        CHECK(strcmp(pk->metrics[0].unit, "FLOP/s") == 0 && pk->metrics[0].direction == RD_HIGHER &&
              pk->metrics[0].timed, "FLOP/s, higher is better, timed");
        CHECK(pk->metrics[0].value == 2e10 && pk->metrics[0].lo == 1e10 && pk->metrics[0].hi == 3e10 &&
              pk->metrics[0].nreps == 3, "median 2e10, range 1e10..3e10, 3 repetitions");
    }
    const struct rd_row *pw = row_labelled(&d, "pow | default | n uniform");
    CHECK(pw != NULL, "the label joins label, variant and 'n ' + n_mode");
    if (pw) {
        const struct rd_metric *m = rd_row_find(pw, "evals_per_s");
        CHECK(m && m->value == 2e8 && m->lo == 1e8 && m->hi == 4e8 && strcmp(m->unit, "1/s") == 0, "pow's rate");
        CHECK(m && m->nreps == 3 && m->reps[0] == 4e8 && m->reps[2] == 1e8, "the repetitions in file order");
        /* per CPU second first, where the file has them */
        CHECK(m && m->norm_cpu && m->nnorm == 3 && m->norm[0] == 0.75, "normalised per CPU second");
        CHECK(pw->ok && pw->retries == 1 && pw->disturbed == 2, "status ok, 1 retry, 2 disturbed");
        CHECK(strcmp(rd_row_key_value(pw, "kind"), "builtin") == 0, "kind as an attribute");
        CHECK(strcmp(pw->model, "pow") == 0, "model for grouping");
    }
    const struct rd_row *fq = row_labelled(&d, "fq2 | fast | n varying");
    CHECK(fq && !fq->ok && strcmp(fq->reason, "the kernel failed") == 0 && strcmp(fq->status, "failed") == 0,
          "a failed row keeps its status and reason");
    CHECK(fq && fq->nmetrics == 1 && isnan(fq->metrics[0].value), "its rate is missing, not 0");

    /* CSV: a header and one line per metric (1 + 1 + 1 metrics) */
    struct md_buf b;
    md_init(&b);
    rdoc_csv(&d, &b);
    CHECK(count_lines(b.s) == 1 + 3, "CSV lines: %d", count_lines(b.s));
    CHECK(b.s && strncmp(b.s, "device,\"reference\",\"label\",\"variant\",\"n_mode\",\"kind\",status,", 60) == 0,
          "CSV header: the device, every key in order of appearance: %.80s", b.s ? b.s : "");
    CHECK(b.s && strstr(b.s, "\"failed\",\"the kernel failed\",\"evals_per_s\",\"1/s\",higher,,,,0\r\n"),
          "a failed row: status, reason, empty value and range, no repetitions");
    md_free(&b);

    /* markdown: one table row per metric, the failed one says why */
    md_init(&b);
    rdoc_markdown(&d, &b);
    CHECK(b.s && strstr(b.s, "| pow | default | n uniform | evals_per_s |") == NULL,
          "a label's '|' is escaped in a markdown cell");
    CHECK(b.s && strstr(b.s, "| pow \\| default \\| n uniform | evals_per_s | 2e+08 | 1/s | higher | 1e+08..4e+08 | 3 |"),
          "pow's line: %s", b.s ? b.s : "");
    CHECK(b.s && strstr(b.s, "not measured: the kernel failed"), "the failed row's reason");
    md_free(&b);

    /* brdfbench.rows/1 written and read back: the same rows, keys, values and repetitions */
    md_init(&b);
    rdoc_json(&d, &b);
    path_in(path, sizeof path, "rows.json");
    test_write_file(path, b.s ? b.s : "");
    md_free(&b);
    struct rdoc back;
    CHECK(rdoc_read_file(path, &back, err, sizeof err) == 0, "rows/1 read back: %s", err);
    CHECK(back.nrows == d.nrows && strcmp(back.kind, "throughput") == 0 && back.disturbed == 2, "same rows and kind");
    for (int i = 0; i < back.nrows && i < d.nrows; ++i) {
        const struct rd_row *x = &d.rows[i], *y = &back.rows[i];
        CHECK(strcmp(x->label, y->label) == 0 && x->ok == y->ok && x->nkeys == y->nkeys &&
              x->nmetrics == y->nmetrics && x->retries == y->retries, "row %d: %s / %s", i, x->label, y->label);
        for (int m = 0; m < x->nmetrics && m < y->nmetrics; ++m) {
            const struct rd_metric *p = &x->metrics[m], *q = &y->metrics[m];
            int same = (p->value == q->value || (isnan(p->value) && isnan(q->value))) && p->nreps == q->nreps &&
                       p->nnorm == q->nnorm && p->norm_cpu == q->norm_cpu && p->direction == q->direction &&
                       p->timed == q->timed && strcmp(p->unit, q->unit) == 0;
            for (int k = 0; same && k < p->nreps; ++k)
                same = p->reps[k] == q->reps[k];
            CHECK(same, "row %d metric %s round trip", i, p->name);
        }
    }
    const struct rd_row *pw2 = row_labelled(&back, "pow | default | n uniform");
    CHECK(pw2 && strcmp(rd_row_key_value(pw2, "n_mode"), "uniform") == 0 && rd_row_key_value(pw2, "kind") &&
          strcmp(rd_row_key_value(pw2, "kind"), "builtin") == 0, "keys and attributes read back");
    rdoc_free(&back);
    rdoc_free(&d);
}

static void check_accuracy(void)
{
    CHECK_CASE("accuracy.json as rows");
    char err[512];
    struct rdoc d;
    CHECK(rows_of("accuracy.json",
        "{\"schema\": \"brdfbench.accuracy/1\",\n"
        " \"context\": {\"grid\": {\"n_min\": 2, \"n_max\": 1000, \"n_step\": 1, \"samples_per_zone\": 4096}},\n"
        " \"results\": [\n"
        "  {\"label\": \"fq2\", \"n_min\": 2, \"n_max\": 1000, \"status\": \"ok\",\n"
        "   \"epicentre\": {\"max_rel\": 0.01257}, \"attenuation\": {\"max_abs\": 0.0214},\n"
        "   \"whole\": {\"max_abs\": 0.0214}, \"invalid\": {\"count\": 0}},\n"
        "  {\"label\": \"cq2\", \"n_min\": 2, \"n_max\": 1000, \"status\": \"device_disagrees\",\n"
        "   \"reason\": \"device and double disagree\", \"epicentre\": {\"max_rel\": null}}]}\n",
                  &d, err, sizeof err) == 0, "read: %s", err);
    CHECK(d.nrows == 2, "two rows: %d", d.nrows);
    const char *grid = "n 2..1000 step 1, 4096 samples per zone";
    CHECK(rd_ctx_get(&d.ctx, "accuracy grid") && strcmp(rd_ctx_get(&d.ctx, "accuracy grid"), grid) == 0,
          "the grid as a context line");
    char label[300];
    snprintf(label, sizeof label, "fq2 | %s", grid);
    const struct rd_row *fq = row_labelled(&d, label);
    /* the four figures, then where the maxima and the first invalid value lie and the device
       check in 4th-digit units (not in this file: NAN) */
    CHECK(fq && fq->nmetrics == 11, "fq2: the model and the grid, four figures and seven the report shows");
    if (fq && fq->nmetrics == 11) {
        for (int k = 4; k < 10; ++k)
            CHECK(isnan(fq->metrics[k].value) && fq->metrics[k].direction == RD_NEITHER &&
                  strstr(fq->metrics[k].name, ".at_"), "position %d: %s, neither better higher nor lower", k,
                  fq->metrics[k].name);
        CHECK(strcmp(fq->metrics[10].name, "check.in_4th_digit_units") == 0 && isnan(fq->metrics[10].value) &&
              fq->metrics[10].direction == RD_LOWER, "the device check: %s", fq->metrics[10].name);
        static const char *const names[4] = { "epicentre.max_rel", "attenuation.max_abs", "whole.max_abs",
                                              "invalid.count" };
        static const double values[4] = { 0.01257, 0.0214, 0.0214, 0 };
        for (int k = 0; k < 4; ++k)
            CHECK(strcmp(fq->metrics[k].name, names[k]) == 0 && fq->metrics[k].value == values[k] &&
                  fq->metrics[k].direction == RD_LOWER && !fq->metrics[k].timed, "figure %d: %s = %g, lower is better",
                  k, fq->metrics[k].name, fq->metrics[k].value);
        CHECK(strcmp(rd_row_key_value(fq, "n_min"), "2") == 0 && strcmp(rd_row_key_value(fq, "n_max"), "1000") == 0 &&
              strcmp(rd_row_key_value(fq, "n_step"), "1") == 0, "the n range and step as attributes");
    }
    snprintf(label, sizeof label, "cq2 | %s", grid);
    const struct rd_row *cq = row_labelled(&d, label);
    CHECK(cq && !cq->ok && strcmp(cq->status, "device_disagrees") == 0 &&
          strcmp(cq->reason, "device and double disagree") == 0, "cq2's status word and reason");
    /* lines: 1 schema, 2 context, 3 "results", 4-6 fq2, 7 cq2 */
    CHECK(cq && cq->line == 7, "cq2's row starts on line 7 of the file: %d", cq ? cq->line : -1);
    rdoc_free(&d);
}

static void check_render_fit(void)
{
    CHECK_CASE("render.json and fit.json as rows");
    char err[512];
    struct rdoc d;
    CHECK(rows_of("render.json",
        "{\"schema\": \"brdfbench.render/1\", \"scenes\": [{\"scene\": \"spheres\",\n"
        " \"image\": {\"width\": 64, \"height\": 32},\n"
        " \"models\": [{\"model\": \"fq2\", \"metrics\": {\"max_abs\": 0.5, \"rmse\": 0.25, \"psnr_db\": null}}],\n"
        " \"timings\": [{\"width\": 128, \"height\": 128, \"entries\": [{\"name\": \"fq2\", \"model\": \"fq2\",\n"
        "   \"mpixel_per_s\": 10, \"median_ms\": 2, \"min_ms\": 1, \"max_ms\": 4, \"mpixel_per_s_reps\": [5, 10, 20]}]}]}]}\n",
                  &d, err, sizeof err) == 0, "render read: %s", err);
    const struct rd_row *img = row_labelled(&d, "spheres 64x32 | fq2");
    /* the null PSNR of an ok row is left out: identical images, nothing to compare */
    CHECK(img && img->nmetrics == 2 && rd_row_find(img, "rmse") && rd_row_find(img, "rmse")->value == 0.25 &&
          !rd_row_find(img, "psnr_db"), "max_abs and rmse, no PSNR");
    const struct rd_row *tm = row_labelled(&d, "spheres | fq2");
    const struct rd_metric *r = tm ? rd_row_find(tm, "mpixel_per_s@128x128") : NULL;
    /* Mpixel/s = 10 at the median 2 ms: 10 * 2 / 4 = 5 at the slowest, 10 * 2 / 1 = 20 at the fastest */
    CHECK(r && r->timed && r->value == 10 && r->lo == 5 && r->hi == 20 && r->nreps == 3 &&
          strcmp(r->unit, "Mpixel/s") == 0, "the timing row: rate, range from the times, repetitions");
    rdoc_free(&d);

    CHECK(rows_of("fit.json",
        "{\"schema\": \"brdfbench.fit/1\", \"context\": {\"grid\": {\"n_min\": 2, \"n_max\": 10, \"n_step\": 1,\n"
        " \"samples_per_zone\": 64}}, \"a\": 0.25, \"b\": 0.5, \"max_rel\": 0.01, \"max_abs\": 0.02,\n"
        " \"compare\": [{\"model\": \"quad:a=0.25,b=0.5\", \"max_rel\": 0.01}, {\"model\": \"fq2\", \"max_rel\": 0.02,\n"
        "   \"max_abs\": 0.03}]}\n",
                  &d, err, sizeof err) == 0, "fit read: %s", err);
    /* the fit itself (its coefficients and figures) and fq2; the quadratic's own compare row
       is the fit again under a label that moves with its coefficients: left out */
    CHECK(d.nrows == 3, "three rows: %d", d.nrows);
    /* the family's limit: no limit_overall in this file, its figures NAN */
    const struct rd_row *lim = row_labelled(&d, "per-n minimax k(n): the family's limit | n 2..10 step 1, 64 samples per zone");
    CHECK(lim && lim->nmetrics == 2 && isnan(rd_row_value(lim, "max_rel")) && rd_row_find(lim, "at_n") &&
          rd_row_find(lim, "at_n")->direction == RD_NEITHER, "the family's limit row: max_rel, at_n");
    const struct rd_row *best = row_labelled(&d, "best affine k(n) | n 2..10 step 1, 64 samples per zone");
    CHECK(best && best->nmetrics == 4 && rd_row_find(best, "a")->value == 0.25 &&
          rd_row_find(best, "a")->direction == RD_NEITHER && rd_row_find(best, "max_abs")->value == 0.02,
          "the best affine k(n): a, b (neither better), max_rel, max_abs");
    rdoc_free(&d);
}

/* A file of the version written now carries its rows: the "rows" member, written by
   rdoc_json_rows_member from rows built by hand, is what the reader returns (its layout,
   here an empty "models", is not read); that version without the member is refused. */
static void check_rows_member(void)
{
    CHECK_CASE("a result file's rows member");
    char path[4200], err[512];
    struct rdoc built, d;
    rdoc_init(&built, FRONTIER_SCHEMA, "frontier", "frontier.json");
    rd_ctx_put(&built.ctx, "frontier note", "by hand");
    struct rd_row *r = rdoc_row(&built, "", "fq2");
    rd_row_key(r, "model", NULL, "fq2");
    rd_row_metric(&built, r, "n_2_1000.max_rel", "1", RD_LOWER, 0, 0.004);
    struct rd_metric *rate = rd_row_metric(&built, r, "evals_per_s", "1/s", RD_HIGHER, 1, 3e9);
    const double reps[3] = { 2e9, 3e9, 4e9 }, norm[3] = { 0.5, 0.75, 1 };
    rate->lo = 2e9;
    rate->hi = 4e9;
    CHECK(rd_metric_reps(&built, rate, reps, 3) == 0 && rd_metric_normalised(&built, rate, norm, 3, 1) == 0,
          "repetitions kept");
    struct rd_row *bad = rdoc_row(&built, "", "nanm");
    rd_row_key(bad, "model", NULL, "nanm");
    rd_row_fail(bad, NULL, "no finite error figure");
    rd_row_metric(&built, bad, "psnr_db", "dB", RD_HIGHER, 0, NAN);
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_str(&w, "schema", FRONTIER_SCHEMA);
    jw_kv_obj(&w, "context");
    jw_kv_str(&w, "device", "dev0");
    jw_obj_end(&w);
    jw_kv_arr(&w, "models");
    jw_arr_end(&w);
    rdoc_json_rows_member(&w, &built);
    jw_obj_end(&w);
    path_in(path, sizeof path, "frontier.json");
    CHECK(jw_write_file_free(&w, path, err, sizeof err) == 0, "written: %s", err);
    rdoc_free(&built);
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 0, "read: %s", err);
    CHECK(d.nrows == 2 && strcmp(d.kind, "frontier") == 0 && strcmp(d.schema, FRONTIER_SCHEMA) == 0,
          "two rows of kind frontier: %d %s", d.nrows, d.kind);
    /* the file's context block first (device), then the member's own lines */
    CHECK(d.ctx.count == 2 && strcmp(d.ctx.key[0], "device") == 0 && strcmp(d.ctx.key[1], "frontier note") == 0 &&
          strcmp(d.ctx.value[1], "by hand") == 0, "context: device, then the kind's line");
    const struct rd_row *fq = row_labelled(&d, "fq2");
    const struct rd_metric *m = fq ? rd_row_find(fq, "evals_per_s") : NULL;
    CHECK(fq && fq->ok && fq->nmetrics == 2 && rd_row_find(fq, "n_2_1000.max_rel")->value == 0.004 &&
          rd_row_find(fq, "n_2_1000.max_rel")->direction == RD_LOWER, "fq2's error, lower is better");
    CHECK(m && m->timed && m->value == 3e9 && m->lo == 2e9 && m->hi == 4e9 && m->nreps == 3 && m->reps[2] == 4e9 &&
          m->nnorm == 3 && m->norm[1] == 0.75 && m->norm_cpu && strcmp(m->unit, "1/s") == 0, "the rate as declared");
    const struct rd_row *nm = row_labelled(&d, "nanm");
    CHECK(nm && !nm->ok && strcmp(nm->status, "failed") == 0 && strcmp(nm->reason, "no finite error figure") == 0 &&
          nm->nmetrics == 1 && isnan(nm->metrics[0].value), "the failed row, its reason and its missing PSNR");
    rdoc_free(&d);

    test_write_file(path, "{\"schema\": \"brdfbench.frontier/3\", \"models\": []}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 2 && strstr(err, "without its \"rows\""),
          "the current version without its rows: %s", err);
    /* the previous version of the same layout reads by that layout (its upgrade function) */
    test_write_file(path, "{\"schema\": \"brdfbench.frontier/1\", \"models\": [{\"model\": \"fq2\",\n"
                          " \"n_2_1000\": {\"max_rel\": 0.004, \"max_rel_at_n\": 2, \"max_abs\": 0.01}, \"psnr_db\": 40}]}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 0, "frontier/1 read: %s", err);
    fq = row_labelled(&d, "fq2");
    /* max_rel, max_abs and the PSNR; the n where a maximum is reached is no figure */
    /* the rows of the version written now: the ranges' figures (null where the file has none),
       the PSNR, both rates (null: no rate member) and the front (0: no on_front member) */
    CHECK(fq && fq->nmetrics == 8 && rd_row_find(fq, "n_2_1000.max_abs")->value == 0.01 &&
          isnan(rd_row_find(fq, "n_16_1000.max_rel")->value) && isnan(rd_row_value(fq, "evals_per_s_uniform")) &&
          rd_row_value(fq, "on_front") == 0 &&
          rd_row_find(fq, "psnr_db")->direction == RD_HIGHER && strcmp(rd_row_find(fq, "psnr_db")->unit, "dB") == 0,
          "frontier/1: the rows frontier/3 carries");
    rdoc_free(&d);
}

static void check_refused(void)
{
    CHECK_CASE("files that are not results");
    char path[4200], err[512];
    struct rdoc d;
    path_in(path, sizeof path, "plots.json");
    test_write_file(path, "{\"schema\": \"brdfbench.plots/1\", \"figures\": []}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 2 && strstr(err, path) &&
          strstr(err, "is not a result file with figures"), "another schema: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.accuracy/7\", \"results\": []}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 2 && strstr(err, "this version reads \"brdfbench.accuracy/3\""),
          "another version: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.accuracy/1\", \"results\": [{\"label\": \"a|b\"}]}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 2 && strstr(err, "'|'"), "a label that breaks tables: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.rows/1\", \"source\": {\"kind\": \"accuracy\"}, \"rows\": [\n"
                          " {\"keys\": {}, \"metrics\": [{\"name\": \"x\", \"direction\": \"up\"}]}]}\n");
    CHECK(rdoc_read_file(path, &d, err, sizeof err) == 2 && strstr(err, "accepted: higher, lower, neither"),
          "a rows document with a direction of another word: %s", err);
    /* what compare would decide on: a timed rate below 0, a repetition that is no number, a
       figure past 1e100, a unit that breaks a table */
    static const struct { const char *metric, *want; } bad[] = {
        { "{\"name\": \"r\", \"direction\": \"higher\", \"timed\": true, \"value\": -5}", "\"value\" is -5 (accepted: a rate" },
        { "{\"name\": \"r\", \"direction\": \"higher\", \"timed\": true, \"value\": 5, \"reps\": [1, \"x\"]}",
          "\"reps\" is not a number" },
        { "{\"name\": \"e\", \"direction\": \"lower\", \"timed\": false, \"value\": 1e200}", "\"value\" is 1e+200" },
        { "{\"name\": \"e\", \"direction\": \"lower\", \"unit\": \"a|b\", \"value\": 1}", "\"unit\" holds '|'" },
        /* a figure declared lower-is-better is a magnitude whatever its name (a cost, a count) */
        { "{\"name\": \"cost\", \"direction\": \"lower\", \"timed\": false, \"value\": -1}",
          "\"value\" of cost is -1 (accepted: a figure where lower is better is in [0, 1e+100]" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        char text[600];
        snprintf(text, sizeof text, "{\"schema\": \"brdfbench.rows/1\", \"source\": {\"kind\": \"accuracy\"}, "
                 "\"rows\": [{\"keys\": {}, \"metrics\": [%s]}]}\n", bad[k].metric);
        CHECK(rows_of("rows_bad.json", text, &d, err, sizeof err) == 2 && strstr(err, bad[k].want),
              "rows document %zu refused with %s: %s", k, bad[k].want, err);
    }
}

/* Texts of a row and of the document: written into the rows member, read back as they were
   (several lines, a '|', 600 bytes: a text has no length limit), replaced when given again; a
   text with an escape character is refused. Expected values are the strings given here. */
static void check_texts(void)
{
    CHECK_CASE("texts of rows and documents");
    char err[512];
    struct rdoc d;
    rdoc_init(&d, "brdfbench.claims/2", "claims", "claims.json");
    char longtext[601];
    memset(longtext, 'a', 600);
    longtext[600] = 0;
    struct rd_row *r = rdoc_row(&d, NULL, "P1-delta");
    rd_row_key(r, "id", NULL, "P1-delta");
    CHECK(rd_row_text(&d, r, "claim", "max | delta\nsecond line") == 0 && rd_row_text(&d, r, "note", longtext) == 0 &&
          rd_row_textf(&d, r, "note", "%s %d", "replaced", 7) == 0 && rdoc_text(&d, "rule", longtext) == 0,
          "texts added");
    CHECK(r->ntexts == 2 && strcmp(rd_row_text_get(r, "note"), "replaced 7") == 0, "a text given again replaces it");
    CHECK(strcmp(rd_row_text_or(r, "absent", "fb"), "fb") == 0 && rdoc_text_get(&d, "absent") == NULL,
          "absent texts");
    struct md_buf b;
    md_init(&b);
    rdoc_json(&d, &b);
    CHECK(b.s && strstr(b.s, "\"rule\": \"aaaa") && strstr(b.s, "\"claim\": \"max | delta\\nsecond line\""),
          "texts in the JSON");
    struct rdoc back;
    CHECK(rows_of("texts.json", b.s ? b.s : "", &back, err, sizeof err) == 0, "read back: %s", err);
    if (back.nrows == 1) {
        CHECK(strcmp(rd_row_text_or(&back.rows[0], "claim", ""), "max | delta\nsecond line") == 0 &&
              strcmp(rd_row_text_or(&back.rows[0], "note", ""), "replaced 7") == 0 &&
              strcmp(rdoc_text_or(&back, "rule", ""), longtext) == 0, "the texts as they were written");
        rdoc_free(&back);
    } else
        CHECK(0, "one row read back: %d", back.nrows);
    md_free(&b);
    rdoc_free(&d);
    CHECK(rows_of("texts_bad.json", "{\"schema\": \"brdfbench.rows/1\", \"source\": {\"kind\": \"claims\"}, "
                  "\"rows\": [{\"keys\": {}, \"metrics\": [], \"texts\": {\"t\": \"a\\u001b[2Jb\"}}]}\n", &back, err,
                  sizeof err) == 2 && strstr(err, "escape character"), "an escape character refused: %s", err);
}

int main(void)
{
    static void (*const tests[])(void) = { check_throughput, check_accuracy, check_render_fit, check_rows_member,
                                                  check_refused, check_texts };
    return test_run_in_tmpdir(dir, sizeof dir, "test_rdoc", tests, sizeof tests / sizeof tests[0]);
}
