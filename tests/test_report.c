/* test_report.c - heatmap fields, plots and the report, from small sweeps made here:
 *   - a reference against itself gives a zero field, drawn uniformly in the bottom colour;
 *   - a field cell at the epicentre's end matches the closed form of docs/definitions.md there;
 *   - the colour under the heatmap's maximum marker is the colour map's top;
 *   - field and plot JSON survive a round trip, and broken files are refused with the file,
 *     line and problem named;
 *   - every picture decodes with its expected size;
 *   - report.md links only files that exist; its throughput section is drawn from the rows of
 *     throughput.json (the figures worked by hand below). */
#define _POSIX_C_SOURCE 200809L
#include "accuracy.h"
#include "accuracy_report.h"
#include "check.h"
#include "clsession.h"
#include "draw.h"
#include "exitcodes.h"
#include "field_report.h"
#include "models.h"
#include "outdir.h"
#include "plots.h"
#include "rdoc_read.h"
#include "report.h"
#include "report_docs.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* matplotlib's viridis, first and last entries x 255 (see test_draw.c) */
static const int VIRIDIS_BOTTOM[3] = {68, 1, 84}, VIRIDIS_TOP[3] = {253, 231, 37};
static const int NODATA[3] = {90, 90, 100}; /* draw.h: NaN cells */

static char dir[256];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

static int near(const unsigned char *p, const int want[3], int tol)
{
    for (int k = 0; k < 3; k++)
        if (abs((int)p[k] - want[k]) > tol) return 0;
    return 1;
}

static const struct field_grid small = {21, 31, 2.0, 1000.0};

/* Draws fr's heatmap as name in the test's folder, its panels' layout in L, and reads the picture
 * back: its pixels (to be freed) and size, or NULL after a failed check. */
static unsigned char *heatmap_drawn(const struct field_result *fr, const char *name, struct draw_panel_layout L[2], int *w,
                                    int *h)
{
    char path[512], err[1024];
    path_in(path, sizeof path, name);
    CHECK(field_draw_heatmap(path, fr, L, err, sizeof err) == 0, "draw: %s", err);
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, w, h, &img, err, sizeof err) != 0) {
        CHECK(0, "read %s: %s", name, err);
        return NULL;
    }
    return img;
}

static void test_self_field(struct field_ctx *fc)
{
    struct model_spec phong = spec("phong");
    struct field_result fr;
    CHECK(field_run(fc, &phong, &small, &fr) == 0, "field of phong");
    if (!fr.epi_rel) return;
    size_t cells = (size_t)small.rows * small.cols, zero = 0, nan_or_zero = 0;
    for (size_t i = 0; i < cells; i++) {
        zero += fr.epi_rel[i] == 0.0f;
        nan_or_zero += isnan(fr.att_abs[i]) || fr.att_abs[i] == 0.0f;
    }
    /* f and f_ref are the same expression at the same input: every difference is exactly 0 */
    CHECK(zero == cells && nan_or_zero == cells, "phong vs phong: %zu / %zu zero cells", zero, cells);
    struct draw_panel_layout L[2];
    int w, h;
    unsigned char *img = heatmap_drawn(&fr, "heatmap_phong.png", L, &w, &h);
    if (img) {
        CHECK(w == L[0].image_w && h == L[0].image_h, "size %dx%d vs layout %dx%d", w, h, L[0].image_w, L[0].image_h);
        long off = 0, grey = 0, bottom = 0;
        for (int y = L[0].plot_y; y < L[0].plot_y + L[0].plot_h; y++)
            for (int x = L[0].plot_x; x < L[0].plot_x + L[0].plot_w; x++)
                off += !near(img + 3 * ((size_t)y * w + x), VIRIDIS_BOTTOM, 0);
        CHECK(off == 0, "%ld epicentre pixels of a zero field are not the bottom colour", off);
        for (int y = L[1].plot_y; y < L[1].plot_y + L[1].plot_h; y++)
            for (int x = L[1].plot_x; x < L[1].plot_x + L[1].plot_w; x++) {
                const unsigned char *p = img + 3 * ((size_t)y * w + x);
                if (near(p, VIRIDIS_BOTTOM, 0)) bottom++;
                else if (near(p, NODATA, 0)) grey++;
            }
        CHECK(bottom + grey == (long)L[1].plot_w * L[1].plot_h && bottom > 0,
              "attenuation of a zero field: %ld bottom + %ld no-data of %d", bottom, grey, L[1].plot_w * L[1].plot_h);
        CHECK(L[0].max_px == -1 && L[1].max_px == -1, "a zero field has no maximum marker");
        free(img);
    }
    field_result_free(&fr);
}

static void test_fvol_field(struct field_ctx *fc)
{
    struct model_spec fvol = spec("fvol");
    struct field_result fr;
    CHECK(field_run(fc, &fvol, &small, &fr) == 0, "field of fvol");
    if (!fr.epi_rel) return;
    /* closed form at the epicentre's end (last column), docs/definitions.md: c = exp(-0.511/n),
     * c^n = exp(-0.511), delta = |(0.463 n (c - 1) + 1)^2 - c^n| / c^n. Row 0 is n = 2. */
    double n = 2, c = exp(-0.511 / n), ref = exp(-0.511), q = 0.463 * n * (c - 1) + 1;
    double want = fabs(q * q - ref) / ref;
    CHECK_NEAR(fr.epi_rel[small.cols - 1], want, 2e-5, "fvol delta at n = 2, x = x_e");
    /* x = 0 is exact for every lobe model: f(1) = f_ref(1) = 1 */
    CHECK(fr.epi_rel[0] == 0.0f, "delta at x = 0 is %g", fr.epi_rel[0]);
    /* the attenuation zone of the largest n reaches pi/2 in the last column (u_max's definition) */
    size_t last = (size_t)small.rows * small.cols - 1;
    CHECK(!isnan(fr.att_abs[last]), "last cell of the largest n is inside the zone");
    CHECK(isnan(fr.att_abs[small.cols - 1]), "n = 2 ends before the largest reach: NaN");
    CHECK(fr.check_cells > 0 && fr.check_rel_diff < 1e-4, "device vs double %g over %d cells", fr.check_rel_diff,
          fr.check_cells);

    struct draw_panel_layout L[2];
    int w, h;
    unsigned char *img = heatmap_drawn(&fr, "heatmap_fvol.png", L, &w, &h);
    if (img) {
        for (int k = 0; k < 2; k++) {
            CHECK(L[k].max_px >= 0, "panel %d has a marker", k);
            if (L[k].max_px >= 0) {
                const unsigned char *p = img + 3 * ((size_t)L[k].max_py * w + L[k].max_px);
                CHECK(near(p, VIRIDIS_TOP, 3), "panel %d: colour %d,%d,%d under the marker", k, p[0], p[1], p[2]);
            }
        }
        CHECK(L[0].max_row == fr.epi_peak.row && L[0].max_col == fr.epi_peak.col, "marker on the field's peak");
        free(img);
    }

    /* JSON round trip: 4 significant digits */
    char path[512], err[1024];
    path_in(path, sizeof path, "field_fvol.json");
    CHECK(field_write_json(path, &fr, NULL, err, sizeof err) == 0, "write: %s", err);
    struct field_result back;
    CHECK(field_read_json(path, &back, err, sizeof err) == 0, "read: %s", err);
    if (back.epi_rel) {
        size_t cells = (size_t)small.rows * small.cols, bad = 0;
        for (size_t i = 0; i < cells; i++) {
            double a = fr.epi_rel[i], b = back.epi_rel[i];
            if (fabs(a - b) > 5e-4 * fabs(a) + 1e-30) bad++;
            a = fr.att_abs[i], b = back.att_abs[i];
            if (isnan(a) != isnan(b) || (!isnan(a) && fabs(a - b) > 5e-4 * fabs(a) + 1e-30)) bad++;
        }
        CHECK(bad == 0, "%zu cells changed by more than the 4 digits kept", bad);
        CHECK(strcmp(back.model.label, "fvol") == 0 && strcmp(back.reference.label, "phong") == 0, "labels");
        CHECK(back.epi_peak.row == fr.epi_peak.row && back.epi_peak.col == fr.epi_peak.col, "same peak cell");
        field_result_free(&back);
    }
    field_result_free(&fr);
}

/* The field reader's refusals, host only: missing file, truncated text, wrong count. */
static void test_field_read_errors(void)
{
    char path[512], err[1024];
    struct field_result back;
    path_in(path, sizeof path, "missing.json");
    CHECK(field_read_json(path, &back, err, sizeof err) == 2 && strstr(err, path), "missing file: %s", err);
    path_in(path, sizeof path, "broken.json");
    test_write_file(path, "{\"schema\": \"brdfbench.field/1\",\n \"model\": \"fvol\",\n \"grid\": {\"rows\": 2,,}}\n");
    CHECK(field_read_json(path, &back, err, sizeof err) == 2 && strstr(err, path) && strstr(err, ":3:"),
          "malformed file names file and line 3: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.field/1\", \"model\": \"fvol\", \"reference\": \"phong\",\n"
                     "\"grid\": {\"rows\": 2, \"cols\": 2, \"n_min\": 2, \"n_max\": 10, \"u_max\": 3, \"n\": [2, 10]},\n"
                     "\"epicentre_rel\": [0, 0, 0], \"attenuation_abs\": [0, 0, 0, 0]}\n");
    CHECK(field_read_json(path, &back, err, sizeof err) == 2 && strstr(err, "epicentre_rel") && strstr(err, ":3:"),
          "short array named: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.field/1\", \"model\": \"nosuch\", \"reference\": \"phong\"}");
    CHECK(field_read_json(path, &back, err, sizeof err) == 2 && strstr(err, path), "bad model: %s", err);
}

static void test_plots_and_report(struct cl_session *s)
{
    struct accuracy_ctx a;
    CHECK(accuracy_open(&a, s, "") == 0, "accuracy_open");
    struct accuracy_grid g = {2, 200, 9, 64};
    struct accuracy_result res[2];
    struct model_spec ms[2] = {spec("fvol"), spec("cq2")};
    int ok = accuracy_run(&a, &ms[0], &g, &res[0]) == 0 && accuracy_run(&a, &ms[1], &g, &res[1]) == 0;
    CHECK(ok, "two small sweeps");
    accuracy_close(&a);
    if (!ok) return;

    struct plot_set set;
    plots_init(&set);
    static const enum model_family fam[] = {MODEL_FAMILY_QUADRATIC};
    CHECK(plots_add_max_vs_n(&set, "max_rel.png", "caption one", "max delta", res, 2, 1, fam, 1) == 0, "max vs n");
    CHECK(set.count == 1 && set.figs[0].nseries == 2, "two series (fvol and cq2)");
    /* fvol and cq2 are quadratic: a plot of the normalised families has nothing to draw, so it
       is not added (1), never drawn empty */
    static const enum model_family norm[] = {MODEL_FAMILY_NORMALISED, MODEL_FAMILY_MICROFACET};
    CHECK(plots_add_max_vs_n(&set, "norm.png", "c", "t", res, 2, 1, norm, 2) == 1 && set.count == 1,
          "no normalised model: no figure (count %d)", set.count);
    /* the per-n maxima plotted never exceed the refined maximum over the range */
    for (int sidx = 0; sidx < set.figs[0].nseries; sidx++) {
        const struct plot_series *se = &set.figs[0].series[sidx];
        double top = 0;
        for (size_t i = 0; i < se->count; i++) top = fmax(top, se->y[i]);
        CHECK(top <= res[sidx].epicentre.value * (1 + 1e-4), "series %d peak %g above the refined %g", sidx, top,
              res[sidx].epicentre.value);
    }
    CHECK(plots_add_curves(&set, "curves.png", "caption two", "curves", 16, ms, 2) == 0, "curves");
    /* the reference curve is c^n: at x = 0 it is 1, and at the last x it is cos(x)^16 */
    {
        const struct plot_series *ref = &set.figs[1].series[0];
        CHECK(ref->y[0] == 1.0, "phong at x = 0");
        double x = ref->x[ref->count - 1];
        CHECK_NEAR(ref->y[ref->count - 1], pow(cos(x), 16), 1e-12, "phong at the last x");
    }
    const char *labels[3] = {"phong", "fvol", "cq2"};
    double v[3] = {1, 2.5, 2.4};
    CHECK(plots_add_bars(&set, "bars.png", "caption three", "bars", "G evaluations / s", labels, v, NULL, NULL, 3, 0) == 0,
          "bars");
    char err[1024], path[512];
    CHECK(plots_draw(&set, dir, err, sizeof err) == 0, "draw plots: %s", err);
    path_in(path, sizeof path, "plots.json");
    CHECK(plots_write_json(&set, path, NULL, err, sizeof err) == 0, "write plots.json: %s", err);
    struct plot_set back;
    CHECK(plots_read_json(path, &back, err, sizeof err) == 0, "read plots.json: %s", err);
    if (back.count == 3) {
        CHECK(back.figs[0].nseries == 2 && back.figs[0].series[0].count == set.figs[0].series[0].count, "series kept");
        CHECK(back.figs[2].kind == PLOT_BARS && back.figs[2].nbars == 3 && strcmp(back.figs[2].bar_labels[1], "fvol") == 0,
              "bars kept");
        CHECK(fabs(back.figs[1].series[0].y[5] - set.figs[1].series[0].y[5]) <= 1e-6 * set.figs[1].series[0].y[5],
              "values kept to 7 digits");
        /* redraw from the file read back */
        CHECK(plots_draw(&back, dir, err, sizeof err) == 0, "redraw: %s", err);
    } else {
        CHECK(0, "plots.json read back %d figures, want 3", back.count);
    }
    plots_free(&back);
    /* every plot decodes at its size: line plots 1000 x 620 (draw.h's default), bars 1000 wide */
    static const char *files[3] = {"max_rel.png", "curves.png", "bars.png"};
    for (int i = 0; i < 3; i++) {
        int w, h;
        unsigned char *img = NULL;
        path_in(path, sizeof path, files[i]);
        CHECK(draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0, "decode %s: %s", files[i], err);
        if (img) CHECK(w == 1000 && (i == 2 || h == 620), "%s is %dx%d", files[i], w, h);
        free(img);
    }
    /* malformed plots.json */
    path_in(path, sizeof path, "bad_plots.json");
    test_write_file(path, "{\"schema\": \"brdfbench.plots/1\", \"figures\": [\n  {\"file\": \"x.png\"}\n]}\n");
    CHECK(plots_read_json(path, &back, err, sizeof err) == 2 && strstr(err, path) && strstr(err, ":2:") &&
              strstr(err, "caption"),
          "missing member named with file and line: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.plots/1\", \"figures\": [{\"file\": \"../x.png\", \"caption\": \"\","
                     "\"kind\": \"lines\", \"title\": \"\", \"x_label\": \"\", \"y_label\": \"\", \"x_log\": false,"
                     "\"y_log\": false, \"y_format\": \"plain\", \"x_range\": [0, 0], \"y_range\": [0, 0],"
                     "\"vlines\": [], \"series\": []}]}");
    CHECK(plots_read_json(path, &back, err, sizeof err) == 2 && strstr(err, "plain file name"),
          "a path outside the run folder is refused: %s", err);

    /* throughput bars from a hand-written throughput.json: rows of other build options or
     * n modes are left out; medians in G evaluations per second; the built-in is highlighted */
    path_in(path, sizeof path, "throughput.json");
    test_write_file(path, "{\"schema\": \"brdfbench.throughput/1\", \"results\": [\n"
                     " {\"label\": \"pow\", \"kind\": \"builtin\", \"variant\": \"default\", \"n_mode\": \"uniform\","
                     "  \"evals_per_s\": {\"min\": 1e8, \"median\": 2e8, \"max\": 3e8}},\n"
                     " {\"label\": \"fq2\", \"kind\": \"model\", \"variant\": \"default\", \"n_mode\": \"uniform\","
                     "  \"evals_per_s\": {\"min\": 4e10, \"median\": 5e10, \"max\": 5.5e10}},\n"
                     " {\"label\": \"fq2\", \"kind\": \"model\", \"variant\": \"fast-relaxed-math\", \"n_mode\": \"uniform\","
                     "  \"evals_per_s\": {\"min\": 1, \"median\": 1, \"max\": 1}},\n"
                     " {\"label\": \"fq2\", \"kind\": \"model\", \"variant\": \"default\", \"n_mode\": \"varying\","
                     "  \"evals_per_s\": {\"min\": null, \"median\": null, \"max\": null}}]}\n");
    CHECK(plots_add_throughput(&set, path, "uniform", "tp.png", "bars", err, sizeof err) == 0, "throughput bars: %s", err);
    {
        const struct plot_figure *tf = &set.figs[set.count - 1];
        CHECK(tf->kind == PLOT_BARS && tf->nbars == 2 && tf->highlight == 0, "two bars, the built-in first and dark");
        CHECK(tf->nbars == 2 && fabs(tf->series[0].y[1] - 50.0) < 1e-12 && fabs(tf->series[2].y[1] - 55.0) < 1e-12,
              "fq2's median and max in G evaluations per second");
    }
    CHECK(plots_add_throughput(&set, path, "varying", "tp2.png", "bars", err, sizeof err) == 0, "a failed row: %s", err);
    CHECK(isnan(set.figs[set.count - 1].series[0].y[0]), "a null rate stays missing (n/a), not 0");
    test_write_file(path, "{\"schema\": \"brdfbench.throughput/1\", \"results\": [{\"label\": \"x\"}]}");
    CHECK(plots_add_throughput(&set, path, "uniform", "tp3.png", "bars", err, sizeof err) == 2 && strstr(err, path),
          "malformed throughput.json named: %s", err);
    CHECK(plots_draw(&set, dir, err, sizeof err) == 0, "draw bars: %s", err);

    /* report: three pictures exist, one does not, one was left out for want of data (the
       normalised plots when no normalised model ran); only the three are linked, and the fifth
       is named with its reason instead of an empty plot */
    struct report_picture pics[5] = {
        {"max_rel.png", "caption one", REPORT_PLOTS, ""},
        {"curves.png", "caption two", REPORT_PLOTS, ""},
        {"bars.png", "caption three", REPORT_THROUGHPUT, ""},
        {"never_written.png", "caption four", REPORT_PLOTS, ""},
        {"left_out.png", "caption five", REPORT_PLOTS, "no normalised model ran"},
    };
    /* the run folder as `all` leaves it: accuracy.json, the throughput page, run.json */
    path_in(path, sizeof path, "accuracy.json");
    CHECK(accuracy_write_json(path, res, 2, NULL, "", err, sizeof err) == 0, "accuracy.json: %s", err);
    /* throughput.json as the engine writes it, its rows alone read: a peak of 100 GFLOP/s (50 G
       FMA/s), pow() at 1 G/s and fvol at 2.5 G/s (2.4 to 2.6) in the uniform mode */
    path_in(path, sizeof path, "throughput.json");
    test_write_file(path,
        "{\"schema\": \"brdfbench.throughput/5\", \"context\": {}, \"rows\": {\"context\": {}, "
        "\"disturbed_reps\": 0, \"devices\": [], \"texts\": {\"reps\": \"5\", \"tuned_c_threads\": \"2\"}, \"rows\": ["
        "{\"device\": \"\", \"model\": \"peak\", \"keys\": {\"reference\": \"peak (reference kernel)\"}, "
        "\"attributes\": {}, \"row\": \"peak (reference kernel)\", \"status\": \"ok\", \"preemption_retries\": 0, "
        "\"disturbed_reps\": 0, \"metrics\": [{\"name\": \"flops_per_s\", \"unit\": \"FLOP/s\", "
        "\"direction\": \"higher\", \"timed\": true, \"value\": 1e11}]},"
        "{\"device\": \"\", \"model\": \"pow\", \"keys\": {\"label\": \"pow\", \"variant\": \"default\", "
        "\"n_mode\": \"uniform\"}, \"attributes\": {\"kind\": \"builtin\"}, \"row\": \"pow | default | n uniform\", "
        "\"status\": \"ok\", \"preemption_retries\": 0, \"disturbed_reps\": 0, \"metrics\": [{\"name\": "
        "\"evals_per_s\", \"unit\": \"1/s\", \"direction\": \"higher\", \"timed\": true, \"value\": 1e9, "
        "\"min\": 1e9, \"max\": 1e9}]},"
        "{\"device\": \"\", \"model\": \"fvol\", \"keys\": {\"label\": \"fvol\", \"variant\": \"default\", "
        "\"n_mode\": \"uniform\"}, \"attributes\": {\"kind\": \"model\"}, \"row\": \"fvol | default | n uniform\", "
        "\"status\": \"ok\", \"preemption_retries\": 0, \"disturbed_reps\": 0, \"metrics\": [{\"name\": "
        "\"evals_per_s\", \"unit\": \"1/s\", \"direction\": \"higher\", \"timed\": true, \"value\": 2.5e9, "
        "\"min\": 2.4e9, \"max\": 2.6e9}]}]}}\n");
    struct report_step steps[2] = {
        {"accuracy", "2 models", 1.25, 0},
        {"claims", "", 0, 3},
    };
    struct report_run run = {
        .command = "test", .folder = "shown/run", .wall_seconds = -1, .steps = steps, .nsteps = 2,
        .images_note = "", .pictures = pics, .npictures = 5,
    };
    run.parts[REPORT_PART_CLAIMS] = (struct report_part_state){1, "not in this test"};
    run.parts[REPORT_PART_THROUGHPUT].ran = 1;
    run.parts[REPORT_PART_IMAGES] = (struct report_part_state){1, "not in this test"};
    CHECK(report_run_write(dir, &run, NULL, err, sizeof err) == 0, "run.json: %s", err);
    CHECK(report_rebuild(dir, NULL, err, sizeof err) == 0, "report: %s", err);
    path_in(path, sizeof path, "report.md");
    size_t len = 0;
    char *text = test_read_file(path, &len);
    CHECK(text && len > 0, "report.md read");
    if (text) {
        int links = 0, missing = 0;
        /* every markdown link target "](target)" must be a file in the run folder */
        for (char *p = strstr(text, "]("); p; p = strstr(p + 2, "](")) {
            char *end = strchr(p + 2, ')');
            if (!end) break;
            char name[256], full[600];
            snprintf(name, sizeof name, "%.*s", (int)(end - p - 2), p + 2);
            snprintf(full, sizeof full, "%s/%s", dir, name);
            struct stat st;
            links++;
            if (stat(full, &st) != 0) {
                missing++;
                fprintf(stderr, "report links a missing file: %s\n", name);
            }
        }
        CHECK(links == 3 && missing == 0, "%d links, %d to missing files (want 3 and 0)", links, missing);
        CHECK(strstr(text, "Not drawn, `left_out.png`: no normalised model ran") != NULL,
              "report.md says why left_out.png was not drawn");
        CHECK(strstr(text, "never_written.png") && strstr(text, "was not written"), "the missing picture is named");
        CHECK(strstr(text, "`fvol`") && strstr(text, "`cq2`"), "accuracy table rows");
        /* fvol: 2.5 G/s, 2.5 x pow()'s 1 G/s, 2.5 / 50 G FMA/s = 5% of peak; no reference, no C loop */
        CHECK(strstr(text, "## Throughput\n\ndevice peak: 100 GFLOP/s (float16 FMA chains) = 50 G FMA/s;") != NULL,
              "throughput section: the peak line from the peak row");
        CHECK(strstr(text, "| fvol | uniform | 2.5 | 2.4 - 2.6 | 2.5 | - | - | 5% | - |\n") != NULL,
              "throughput section: fvol's row and its ratios, from the rows");
        CHECK(strstr(text, "(median of 5 launches, profiling events; tuned C: 2 threads)") != NULL,
              "throughput section: the launches and threads from the document's texts");
        CHECK(strstr(text, "Not available: not in this test") != NULL, "missing sections say why");
        /* the step list: two steps from run.json (1.25 s shown to a tenth: "1.2" under
           round-half-even of printf, or "1.3"), a failed one, then the report's own line */
        CHECK((strstr(text, "1. **accuracy**: 2 models (1.2 s)\n") || strstr(text, "1. **accuracy**: 2 models (1.3 s)\n")) &&
                  strstr(text, "2. **claims**: failed (exit 3)\n") && strstr(text, "3. **report**: report.md\n"),
              "the step list from run.json");
        CHECK(strstr(text, "`brdfbench plot shown/run`") != NULL, "the folder's shown name from run.json");
        /* the first model's max delta as the table prints it: 100 x the refined value, 4 significant digits */
        char cell[64];
        snprintf(cell, sizeof cell, " %.4g%% |", 100 * res[0].epicentre.value);
        CHECK(strstr(text, cell) != NULL, "the first model's max delta %s in the table", cell);
        /* rebuilt twice, the page is the same */
        char *again = NULL;
        CHECK(report_build(dir, &again, err, sizeof err) == 0 && again && strcmp(again, text) == 0,
              "report_build gives the page report_rebuild wrote");
        free(again);
        /* The rows a run holds in memory (report_docs_put): the rows accuracy.json carries, put
           before the page is built, give the page the file gives; report_doc gives put rows
           without reading a file (memory.json is none); a second put of a name is refused. */
        static struct report_docs docs;   /* large */
        struct rdoc acc, mem;
        report_docs_init(&docs, dir);
        path_in(path, sizeof path, "accuracy.json");
        CHECK(rdoc_read_file(path, &acc, err, sizeof err) == 0 && acc.nrows == 2, "accuracy.json's rows: %s", err);
        int nrows = acc.nrows;
        CHECK(report_docs_put(&docs, "accuracy.json", &acc, err, sizeof err) == 0 && acc.rows == NULL,
              "rows put (and moved): %s", err);
        rdoc_init(&mem, "brdfbench.rows/1", "accuracy", "memory.json");
        CHECK(report_docs_put(&docs, "memory.json", &mem, err, sizeof err) == 0, "a second document put");
        rdoc_init(&mem, "brdfbench.rows/1", "accuracy", "memory.json");
        CHECK(report_docs_put(&docs, "memory.json", &mem, err, sizeof err) == -1 && strstr(err, "already"),
              "the same name twice is refused: %s", err);
        int drc = -1;
        const struct rdoc *got = report_doc(&docs, "accuracy.json", &drc, err, sizeof err);
        CHECK(drc == 0 && got && got->nrows == nrows, "report_doc gives the put rows");
        got = report_doc(&docs, "memory.json", &drc, err, sizeof err);
        CHECK(drc == 0 && got && got->nrows == 0 && strcmp(got->file, "memory.json") == 0,
              "a put document is not looked for in the folder");
        char *from_memory = NULL;
        CHECK(report_build_docs(dir, &docs, &from_memory, err, sizeof err) == 0 && from_memory &&
                  strcmp(from_memory, text) == 0,
              "report.md from the rows in memory is the page from the files");
        free(from_memory);
        report_docs_free(&docs);
        free(text);
    }
    /* a run folder without run.json, and one whose throughput.json is gone, are named */
    char *none = NULL;
    path_in(path, sizeof path, "throughput.json");
    remove(path);
    CHECK(report_build(dir, &none, err, sizeof err) == 2 && none == NULL && strstr(err, "throughput.json"),
          "the missing file is named: %s", err);
    path_in(path, sizeof path, "run.json");
    remove(path);
    CHECK(report_build(dir, &none, err, sizeof err) == 2 && strstr(err, "run.json"), "no run.json: %s", err);
    test_write_file(path, "{\"schema\": \"brdfbench.accuracy/1\"}");
    CHECK(report_build(dir, &none, err, sizeof err) == 2 && strstr(err, "brdfbench.run/1"),
          "another document as run.json: %s", err);
    plots_free(&set);
    accuracy_result_free(&res[0]);
    accuracy_result_free(&res[1]);
}

int main(void)
{
    struct cl_session s;
    char err[1024];
    if (test_tmpdir_make(dir, sizeof dir, "test_report") != 0)
        return 1;
    test_field_read_errors();
    int rc = clsession_open(&s, -1, -1, err, sizeof err);
    if (rc == EXIT_NO_DEVICE) {
        /* the host checks above ran; the device's did not, which ctest shows as a skip */
        printf("no OpenCL device: %s\n", err);
        test_tmpdir_done(dir);
        return check_summary_skipped();
    }
    if (rc) {
        fprintf(stderr, "%s\n", err);
        test_tmpdir_done(dir);
        return 1;
    }
    struct field_ctx fc;
    CHECK(field_open(&fc, &s, "") == 0, "field_open");
    if (fc.kernel) {
        test_self_field(&fc);
        test_fvol_field(&fc);
        field_close(&fc);
    }
    test_plots_and_report(&s);
    clsession_close(&s);
    test_tmpdir_done(dir);
    return check_summary();
}
