/* test_redraw.c - `brdfbench plot RUN` and `heatmap RUN` redraw a run's own pictures: a
 * picture drawn from the results in memory and the same picture drawn again from the JSON
 * written for it are the same file, byte for byte (same pixels, so same maxima, rings,
 * titles and size), and the peaks read back are the peaks that were found:
 *   - the heatmap of fq2 on the default grid (121 x 181 cells over n in [2, 1000]), where
 *     many cells near the maximum agree in their 4th digit;
 *   - a plot of max delta against Q with values and a marked Q at full double precision,
 *     and a plot of f against x. */
#include "check.h"
#include "draw.h"
#include "exitcodes.h"
#include "field_report.h"
#include "heatmaps_shared.h"
#include "models.h"
#include "plots.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* 1 when files a and b hold the same bytes. */
static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb)
            same = 0;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return same;
}

static void test_plots(const char *dir)
{
    struct plot_set set;
    plots_init(&set);
    double q[13], v[13];
    for (int i = 0; i < 13; ++i) {
        q[i] = 0.3 + 0.05 * i + 1e-9 * i;                            /* digits beyond the 7th */
        v[i] = 0.0115312345678 + 0.2 * (q[i] - 0.651234567) * (q[i] - 0.651234567);
    }
    CHECK(plots_add_against_q(&set, "q.png", "caption", "max delta of f_Q against Q", "max delta", 1, q, v, 13,
                              "f_Q", 0.0758812345678, "f2", 0.651234567) == 0, "Q plot built");
    struct model_spec m[2] = { spec("fq2"), spec("cq2") };
    CHECK(plots_add_curves(&set, "curves.png", "caption", "f at n = 16", 16.0, m, 2) == 0, "curves built");
    /* no empty plot: a Q sweep with no finite value adds no figure */
    double none[3] = {NAN, NAN, NAN};
    CHECK(plots_add_against_q(&set, "empty.png", "c", "t", "y", 1, q, none, 3, "f_Q", NAN, "", NAN) == 1 &&
              set.count == 2, "an all-NaN Q sweep added a figure (%d figures)", set.count);
    char first[4200], json[4200], again[4200], err[1024];
    snprintf(first, sizeof first, "%s/first", dir);
    snprintf(again, sizeof again, "%s/again", dir);
    snprintf(json, sizeof json, "%s/plots.json", dir);
    CHECK(mkdir(first, 0755) == 0 && mkdir(again, 0755) == 0, "folders");
    CHECK(plots_draw(&set, first, err, sizeof err) == 0, "drawn: %s", err);
    CHECK(plots_write_json(&set, json, NULL, err, sizeof err) == 0, "plots.json written: %s", err);
    struct plot_set back;
    CHECK(plots_read_json(json, &back, err, sizeof err) == 0, "plots.json read: %s", err);
    CHECK(plots_draw(&back, again, err, sizeof err) == 0, "redrawn: %s", err);
    const char *files[] = { "q.png", "curves.png" };
    for (int k = 0; k < 2; ++k) {
        char a[8500], b[8500];
        snprintf(a, sizeof a, "%s/%s", first, files[k]);
        snprintf(b, sizeof b, "%s/%s", again, files[k]);
        CHECK(same_file(a, b), "%s: the redraw differs from the picture of the run", files[k]);
    }
    plots_free(&back);
    plots_free(&set);
}

/* A run folder's accuracy.json with the grid of its context block (nothing else is read). */
static void write_grid(const char *dir, double n_step, long samples)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/accuracy.json", dir);
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "{\"schema\": \"brdfbench.accuracy/1\", \"context\": {\"grid\": {\"n_min\": 2, \"n_max\": 1000, "
               "\"n_step\": %g, \"samples_per_zone\": %ld}}, \"results\": []}\n", n_step, samples);
    fclose(f);
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* The quick stamp follows the run folder's grid: all --quick's (n step 10, 256 samples) and
 * coarser is quick, the full grid (step 1, 4096 samples) and a folder without accuracy.json are
 * not; a plot redrawn in a quick folder carries the band, in the others it is the plain picture. */
static void test_quick_stamp(const char *dir)
{
    char quick[4200], full[4200], none[4200], err[1024];
    snprintf(quick, sizeof quick, "%s/quick", dir);
    snprintf(full, sizeof full, "%s/full", dir);
    snprintf(none, sizeof none, "%s/none", dir);
    CHECK(mkdir(quick, 0755) == 0 && mkdir(full, 0755) == 0 && mkdir(none, 0755) == 0, "folders");
    write_grid(quick, 10, 256);
    write_grid(full, 1, 4096);
    CHECK(plots_run_is_quick(quick), "n step 10, 256 samples: not quick");
    CHECK(!plots_run_is_quick(full), "n step 1, 4096 samples: quick");
    CHECK(!plots_run_is_quick(none), "no accuracy.json: quick");
    write_grid(full, 1, 128);   /* coarser in samples alone: quick (the answer follows the file) */
    CHECK(plots_run_is_quick(full), "n step 1, 128 samples: not quick");
    write_grid(full, 1, 4096);
    struct plot_set set;
    plots_init(&set);
    double q[3] = {0.3, 0.5, 0.7}, v[3] = {0.02, 0.01, 0.03};
    CHECK(plots_add_against_q(&set, "q.png", "c", "t", "max delta", 1, q, v, 3, "f_Q", NAN, "", NAN) == 0, "built");
    CHECK(plots_draw(&set, quick, err, sizeof err) == 0 && plots_draw(&set, full, err, sizeof err) == 0 &&
              plots_draw(&set, none, err, sizeof err) == 0, "drawn: %s", err);
    char a[8500], b[8500], c[8500];
    snprintf(a, sizeof a, "%s/q.png", quick);
    snprintf(b, sizeof b, "%s/q.png", full);
    snprintf(c, sizeof c, "%s/q.png", none);
    CHECK(same_file(b, c), "a full run's picture differs from one drawn outside a run");
    CHECK(!same_file(a, b) && file_size(a) > file_size(b), "the quick run's picture has no stamp");
    plots_free(&set);
}

static double largest(const float *v, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i]) && v[i] > m) m = v[i];
    return m;
}

/* --shared-scale: with the fields of fq2 and cq2 in a folder, each heatmap is redrawn on the
 * largest delta and the largest Delta of the two (computed here from the fields), the same
 * picture as drawn with those scales, and the page of both is written. */
static void test_shared_scale(const char *dir, const struct field_result *a, const struct field_result *b,
                              const struct cl_session *s)
{
    char run[4200], path[4300], err[1024];
    snprintf(run, sizeof run, "%s/shared", dir);
    CHECK(mkdir(run, 0755) == 0, "folder");
    const struct field_result *fr[2] = {a, b};
    double epi = 0, att = 0;
    for (int k = 0; k < 2; k++) {
        size_t cells = (size_t)fr[k]->grid.rows * fr[k]->grid.cols;
        epi = fmax(epi, largest(fr[k]->epi_rel, cells));
        att = fmax(att, largest(fr[k]->att_abs, cells));
        char safe[96], name[200];
        field_safe_label(fr[k]->model.label, safe, sizeof safe);
        snprintf(name, sizeof name, "%s/field_%s.json", run, safe);
        CHECK(field_write_json(name, fr[k], s, err, sizeof err) == 0, "field JSON: %s", err);
    }
    int drawn = 0;
    CHECK(plots_heatmaps_shared(run, 1, NULL, &drawn, err, sizeof err) == 0, "shared: %s", err);
    CHECK(drawn == 2, "%d heatmaps redrawn on the shared scale, want 2", drawn);
    snprintf(path, sizeof path, "%s/%s", run, HEATMAPS_SHARED_FILE);
    struct stat st;
    CHECK(stat(path, &st) == 0 && st.st_size > 0, "no %s", HEATMAPS_SHARED_FILE);
    for (int k = 0; k < 2; k++) {
        char safe[96], mine[4300], theirs[4300];
        struct draw_panel_layout lay[2];
        field_safe_label(fr[k]->model.label, safe, sizeof safe);
        snprintf(mine, sizeof mine, "%s/expected_%s.png", dir, safe);
        snprintf(theirs, sizeof theirs, "%s/heatmap_%s.png", run, safe);
        CHECK(field_draw_heatmap_scaled(mine, fr[k], epi, att, lay, err, sizeof err) == 0, "drawn: %s", err);
        CHECK(lay[0].vmax_used == epi && lay[1].vmax_used == att, "%s: scales %g, %g, want %g, %g", safe,
              lay[0].vmax_used, lay[1].vmax_used, epi, att);
        CHECK(same_file(mine, theirs), "%s: the shared-scale heatmap is not drawn on the largest of both", safe);
    }
}

static int test_heatmap(const char *dir)
{
    struct cl_session s;
    char err[1024];
    int rc = clsession_open(&s, -1, -1, err, sizeof err);
    if (rc) {
        fprintf(stderr, "%s\n", err);
        return rc;
    }
    struct field_ctx f;
    if ((rc = field_open(&f, &s, "")) != 0)
        return rc;
    struct model_spec m = spec("fq2");
    struct field_grid g = { FIELD_DEFAULT_ROWS, FIELD_DEFAULT_COLS, 2, 1000 };
    struct field_result r, back;
    if ((rc = field_run(&f, &m, &g, &r)) != 0)
        return rc;
    char a[4200], b[4200], json[4200];
    snprintf(a, sizeof a, "%s/heatmap_first.png", dir);
    snprintf(b, sizeof b, "%s/heatmap_again.png", dir);
    snprintf(json, sizeof json, "%s/field_fq2.json", dir);
    CHECK(field_draw_heatmap(a, &r, NULL, err, sizeof err) == 0, "heatmap drawn: %s", err);
    CHECK(field_write_json(json, &r, &s, err, sizeof err) == 0, "field JSON written: %s", err);
    CHECK(field_read_json(json, &back, err, sizeof err) == 0, "field JSON read: %s", err);
    CHECK(back.epi_peak.row == r.epi_peak.row && back.epi_peak.col == r.epi_peak.col &&
              back.epi_peak.value == r.epi_peak.value,
          "epicentre peak read back at row %d col %d (%.9g), found at row %d col %d (%.9g)", back.epi_peak.row,
          back.epi_peak.col, back.epi_peak.value, r.epi_peak.row, r.epi_peak.col, r.epi_peak.value);
    CHECK(back.att_peak.row == r.att_peak.row && back.att_peak.col == r.att_peak.col &&
              back.att_peak.value == r.att_peak.value,
          "attenuation peak read back at row %d col %d, found at row %d col %d", back.att_peak.row,
          back.att_peak.col, r.att_peak.row, r.att_peak.col);
    CHECK(field_draw_heatmap(b, &back, NULL, err, sizeof err) == 0, "heatmap redrawn: %s", err);
    CHECK(same_file(a, b), "the redrawn heatmap differs from the picture of the run");
    struct model_spec m2 = spec("cq2");
    struct field_result r2;
    if ((rc = field_run(&f, &m2, &g, &r2)) != 0)
        return rc;
    test_shared_scale(dir, &r, &r2, &s);
    field_result_free(&r2);
    field_result_free(&back);
    field_result_free(&r);
    field_close(&f);
    clsession_close(&s);
    return 0;
}

int main(void)
{
    char dir[4096];
    if (test_tmpdir_make(dir, sizeof dir, "redraw"))
        return 1;
    test_plots(dir);
    test_quick_stamp(dir);
    int rc = test_heatmap(dir);
    if (rc == EXIT_NO_DEVICE) {
        printf("no OpenCL device: device checks skipped\n");
        test_tmpdir_done(dir);
        return check_summary_skipped();
    }
    CHECK(rc == 0, "device checks ran (rc %d)", rc);
    test_tmpdir_done(dir);
    return check_summary();
}
