/* cmd_all.c - `brdfbench all`, the main job: the accuracy sweep of every model, the Q sweep
 * of f_Q, the error fields and heatmaps, the plots, and whatever other parts exist (claims,
 * throughput, image passes), into a new run folder results/<date-time>/ with results/latest
 * pointing at it and report.md there. One progress line per step on stderr, with a live
 * bar when stderr is a terminal. */
#define _POSIX_C_SOURCE 200809L
#include "cmd_all_internal.h"

#include "accuracy.h"
#include "accuracy_report.h"
#include "cli_run.h"
#include "cli_table.h"
#include "draw.h"
#include "commands.h"
#include "context.h"
#include "exitcodes.h"
#include "field_report.h"
#include "fit.h"
#include "frontier.h"
#include "measured.h"
#include "measured_report.h"
#include "outdir.h"
#include "plots.h"
#include "render.h"
#include "reproduce.h"
#include "throughput.h"
#include "heatmaps_shared.h"
#include "report.h"
#include "room.h"
#include "usermodel.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- progress ------------------------------------------------------------------- */

/* The steps of this run: one more with --measured. */
static int all_steps(const struct all_run *r) { return ALL_STEPS_BASE + (r->measured_dir != NULL); }

double all_elapsed(const struct all_run *r) { return wall_seconds() - r->t0; }

/* A live bar on a terminal: [#####.....] 7/14 fvol */
void all_progress(const struct all_run *r, const char *what, int done, int total, const char *item)
{
    if (!r->tty || r->quiet || total <= 0) return;
    int width = 30, fill = done * width / total;
    char bar[64];
    for (int i = 0; i < width; i++) bar[i] = i < fill ? '#' : '.';
    bar[width] = 0;
    fprintf(stderr, "\r\033[K[%6.1f s] %-10s [%s] %d/%d %s", all_elapsed(r), what, bar, done, total, item ? item : "");
    fflush(stderr);
}

/* A line of the report's step list (run.json). Out of memory, the line is lost, not the run. */
static void add_step(struct all_run *r, const char *name, const char *msg, double secs, int exit_code)
{
    struct report_step *steps = room_for_one(r->steps, r->nsteps, &r->capsteps, sizeof *steps, 16);
    if (!steps) return;
    r->steps = steps;
    struct report_step *st = &r->steps[r->nsteps++];
    snprintf(st->name, sizeof st->name, "%s", name);
    snprintf(st->message, sizeof st->message, "%s", msg);
    st->seconds = secs;
    st->exit_code = exit_code;
}

/* The line that closes a step: on stderr and in the report's step list. */
void all_step_done(struct all_run *r, const char *name, double started, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    double secs = wall_seconds() - started;
    r->step++;
    if (!r->quiet) {
        if (r->tty) fprintf(stderr, "\r\033[K");
        fprintf(stderr, "[%6.1f s] step %d/%d %-10s %s (%.1f s)\n", all_elapsed(r), r->step, all_steps(r), name, msg, secs);
    }
    add_step(r, name, msg, secs, 0);
    outdir_reassert_signal_handlers();   /* in front of the OpenCL compiler's (outdir.h) */
}

static void add_picture(struct all_run *r, const char *file, int section, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void add_picture(struct all_run *r, const char *file, int section, const char *fmt, ...)
{
    struct report_picture *pics = room_for_one(r->pics, r->npics, &r->cappics, sizeof *pics, 32);
    if (!pics) return; /* the picture stays on disk, only its report entry is lost */
    r->pics = pics;
    struct report_picture *p = &r->pics[r->npics++];
    snprintf(p->file, sizeof p->file, "%s", file);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->caption, sizeof p->caption, fmt, ap);
    va_end(ap);
    p->section = section;
    p->not_drawn[0] = '\0';
}

/* Records the outcome of another command's part: on failure its section says so. */
static void part(struct all_run *r, const char *name, int which, int rc)
{
    struct report_part_state *ps = &r->parts[which];
    ps->ran = 1;
    if (rc == 0) return;
    snprintf(ps->missing, sizeof ps->missing, "this part failed (exit %d); its message is in the run's error output.",
             rc);
    r->part_failures++;
    if (!r->part_rc || rc == EXIT_RUNTIME) r->part_rc = rc == EXIT_NO_DEVICE ? EXIT_RUNTIME : rc;
    r->step++;
    outdir_reassert_signal_handlers();
    if (r->tty) fprintf(stderr, "\r\033[K");
    fprintf(stderr, "[%6.1f s] step %d/%d %-10s FAILED (exit %d)\n", all_elapsed(r), r->step, all_steps(r), name, rc);
    add_step(r, name, "", 0, rc);
}

static void picture_failed(struct all_run *r, const char *msg)
{
    if (!r->picture_failures) snprintf(r->picture_error, sizeof r->picture_error, "%s", msg);
    r->picture_failures++;
    if (r->tty) fprintf(stderr, "\r\033[K");
    fprintf(stderr, "brdfbench all: %s\n", msg);
}

/* A reference, against itself or another implementation of the same lobe (phongpow): its
 * error is zero by definition, up to float rounding. */
static int is_self_referenced(const struct model_spec *m)
{
    struct model_spec ref;
    model_reference_spec(m, &ref);
    return strcmp(ref.label, m->label) == 0 || m->info->family == MODEL_FAMILY_REFERENCE;
}

/* ---- steps ---------------------------------------------------------------------- */

static int step_accuracy(struct all_run *r)
{
    double t = wall_seconds();
    char err[1024], path[4200];
    int rc;
    if (accuracy_grid_check(&r->set.grid, &r->run.s, err, sizeof err)) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        return EXIT_USAGE;
    }
    r->acc = calloc((size_t)r->nmodels, sizeof *r->acc);
    if (!r->acc) return EXIT_RUNTIME;
    for (int m = 0; m < r->nmodels; m++) {
        all_progress(r, "accuracy", m, r->nmodels, r->models[m].label);
        if ((rc = accuracy_run(&r->actx, &r->models[m], &r->set.grid, &r->acc[m])) != 0) return rc;
        r->nacc = m + 1;
    }
    path_join(path, sizeof path, r->run_dir, "accuracy.json");
    /* the rows written as accuracy.json's rows member go to the report as they are: its accuracy
       table is drawn from them, not from the file read back (`brdfbench report` reads the file,
       and gives the same page) */
    struct rdoc *rows = NULL;
    if (accuracy_write_json_keep(path, r->acc, r->nacc, &r->run.s, r->actx.build_options, &rows, err, sizeof err))
        goto fail;
    rc = report_docs_put(&r->docs, "accuracy.json", rows, err, sizeof err);
    free(rows);
    if (rc) goto fail;
    path_join(path, sizeof path, r->run_dir, "accuracy.csv");
    if (accuracy_write_csv(path, r->acc, r->nacc, err, sizeof err)) goto fail;
    all_step_done(r, "accuracy", t, "%d models, n in [%g, %g] step %g, %ld samples per zone -> accuracy.json, accuracy.csv",
              r->nacc, r->set.grid.n_min, r->set.grid.n_max, r->set.grid.n_step, r->set.grid.samples);
    return 0;
fail:
    fprintf(stderr, "brdfbench all: %s\n", err);
    return EXIT_RUNTIME;
}

/* max delta (epicentre) and max Delta (whole range) of f_Q for Q on a grid, and of f2
 * (cq2), which does not depend on Q, on the same n grid: paper 2 figs. 2-3, into the run object
 * (run.h: q_sweep). The claims check runs that sweep too (q_sweep.json): when it ran, its
 * figures are already there (all_step_claims), so the plots show the figures its verdicts use. */
static int step_q_sweep(struct all_run *r)
{
    double t = wall_seconds();
    char err[1024];
    int rc;
    struct run_q_sweep *qs = &r->run.q_sweep;
    if (r->parts[REPORT_PART_CLAIMS].ran && !r->parts[REPORT_PART_CLAIMS].missing[0]) {
        /* the claims check ran its own Q sweep: use it */
        if (qs->n > 0) {
            all_step_done(r, "Q sweep", t, "f_Q for %d values of Q in [%g, %g], the claims check's (q_sweep.json)",
                          qs->n, qs->q[0], qs->q[qs->n - 1]);
            return 0;
        }
        fprintf(stderr, "brdfbench all: the claims check gave no Q sweep of 1 to %d values; running the Q sweep "
                "here\n", RUN_MAX_Q);
    }
    const struct accuracy_grid *g = &r->set.q_grid;
    if (accuracy_grid_check(g, &r->run.s, err, sizeof err)) {
        fprintf(stderr, "brdfbench all: Q sweep: %s\n", err);
        return EXIT_USAGE;
    }
    qs->n = 0;
    int total = (int)floor((r->set.q_max - r->set.q_min) / r->set.q_step + 1e-9) + 1;
    if (total > RUN_MAX_Q) total = RUN_MAX_Q;
    for (int i = 0; i < total; i++) {
        double q = r->set.q_min + i * r->set.q_step;
        char text[64];
        struct model_spec m;
        struct accuracy_result res;
        snprintf(text, sizeof text, "fq:Q=%.6g", q);
        if (model_spec_parse(text, &m, err, sizeof err)) {
            fprintf(stderr, "brdfbench all: Q sweep: %s\n", err);
            return EXIT_USAGE;
        }
        all_progress(r, "Q sweep", i, total, text);
        if ((rc = accuracy_run(&r->actx, &m, g, &res)) != 0) return rc;
        qs->q[qs->n] = q;
        qs->max_rel[qs->n] = res.epicentre.value;
        qs->max_abs[qs->n] = res.whole.value;
        qs->n++;
        accuracy_result_free(&res);
    }
    struct model_spec f2;
    struct accuracy_result res;
    qs->f2_max_rel = qs->f2_max_abs = NAN;
    if (model_spec_parse("cq2", &f2, err, sizeof err) == 0) {
        if ((rc = accuracy_run(&r->actx, &f2, g, &res)) != 0) return rc;
        qs->f2_max_rel = res.epicentre.value;
        qs->f2_max_abs = res.whole.value;
        accuracy_result_free(&res);
    }
    all_step_done(r, "Q sweep", t, "f_Q for %d values of Q in [%g, %g], n in [%g, %g] step %g, %ld samples per zone",
                  qs->n, r->set.q_min, qs->q[qs->n - 1], g->n_min, g->n_max, g->n_step, g->samples);
    return 0;
}

static int step_heatmaps(struct all_run *r)
{
    double t = wall_seconds();
    struct field_ctx f;
    int rc = field_open(&f, &r->run.s, "");
    if (rc) return rc;
    int drawn = 0, total = 0;
    double worst_rel = 0, worst_abs = 0;
    for (int m = 0; m < r->nmodels; m++)
        if (!is_self_referenced(&r->models[m])) total++;
    for (int m = 0; m < r->nmodels; m++) {
        const struct model_spec *spec = &r->models[m];
        if (is_self_referenced(spec)) continue; /* zero by definition: nothing to see */
        all_progress(r, "heatmaps", drawn, total, spec->label);
        struct field_result fr;
        if ((rc = field_run(&f, spec, &r->set.field, &fr)) != 0) break;
        worst_rel = fmax(worst_rel, fr.check_rel_diff);
        if (fr.att_peak.value > 0) worst_abs = fmax(worst_abs, fr.check_abs_diff / fr.att_peak.value);
        char safe[96], name[160], path[4300], err[1024];
        field_safe_label(spec->label, safe, sizeof safe);
        snprintf(name, sizeof name, "field_%s.json", safe);
        path_join(path, sizeof path, r->run_dir, name);
        if (field_write_json(path, &fr, &r->run.s, err, sizeof err)) {
            fprintf(stderr, "brdfbench all: %s\n", err);
            field_result_free(&fr);
            rc = EXIT_RUNTIME;
            break;
        }
        snprintf(name, sizeof name, "heatmap_%s.png", safe);
        path_join(path, sizeof path, r->run_dir, name);
        if (field_draw_heatmap(path, &fr, NULL, err, sizeof err)) picture_failed(r, err);
        else drawn++;
        add_picture(r, name, REPORT_HEATMAPS,
                    "%s against %s: delta over the epicentre (left), Delta over the attenuation zone (right); "
                    "grid maxima %.4g%% and %.4g",
                    spec->label, fr.reference.label, 100 * fr.epi_peak.value, fr.att_peak.value);
        field_result_free(&fr);
    }
    field_close(&f);
    if (rc) return rc;
    all_step_done(r, "heatmaps", t, "%d of %d pictures, %dx%d cells per zone, n in [%g, %g]; device vs double on sampled "
              "cells: delta within %.2g (absolute), Delta within %.2g%% of its maximum",
              drawn, total, r->set.field.cols, r->set.field.rows, r->set.field.n_min, r->set.field.n_max, worst_rel,
              100 * worst_abs);
    return 0;
}

/* Specs from a list of ids the papers' figures use; ids missing from the registry are skipped. */
static int specs_of(const char *const *ids, int n, struct model_spec *out)
{
    int k = 0;
    char err[256];
    for (int i = 0; i < n; i++)
        if (model_spec_parse(ids[i], &out[k], err, sizeof err) == 0) k++;
    return k;
}

static int step_plots(struct all_run *r)
{
    double t = wall_seconds();
    char err[1024], path[4200];
    struct model_spec specs[8];
    int n;
    /* paper 1, fig. 2: F_B, F_S, F_VOL, F_2 at n = 16 */
    static const char *const fig2[] = {"phong", "schlick", "fvol", "cq2"};
    if ((n = specs_of(fig2, 4, specs)) > 0)
        plots_add_curves(&r->plots, "curves_n16_paper1_fig2.png",
                         "f against x at n = 16: phong (reference), schlick, fvol, cq2 (paper 1, fig. 2)",
                         "Lobes at n = 16 (paper 1, fig. 2)", 16, specs, n);
    /* paper 2, fig. 5: f_Q2, f_2, f_b at n = 20 (and f_Q itself) */
    static const char *const fig5[] = {"phong", "fq2", "fq", "cq2"};
    if ((n = specs_of(fig5, 4, specs)) > 0)
        plots_add_curves(&r->plots, "curves_n20_paper2_fig5.png",
                         "f against x at n = 20: phong (reference), fq2, fq (Q = 0.64), cq2 (paper 2, fig. 5)",
                         "Lobes at n = 20 (paper 2, fig. 5)", 20, specs, n);
    /* paper 1 figs. 3, 5 and paper 2 fig. 6: per-n maxima, lobe approximations */
    static const enum model_family lobe_families[] = {MODEL_FAMILY_QUADRATIC, MODEL_FAMILY_RATIONAL, MODEL_FAMILY_USER};
    static const enum model_family norm_families[] = {MODEL_FAMILY_NORMALISED, MODEL_FAMILY_MICROFACET};
    plots_add_max_vs_n(&r->plots, "max_rel_error_epicentre_vs_n.png",
                       "max delta over the epicentre against n, lobe approximations against phong (paper 1 fig. 3, "
                       "paper 2 fig. 6a)",
                       "Max relative error delta over the epicentre, per n", r->acc, r->nacc, 1, lobe_families, 3);
    plots_add_max_vs_n(&r->plots, "max_abs_error_vs_n.png",
                       "max Delta over [0, pi/2] against n, lobe approximations against phong (paper 1 fig. 5, "
                       "paper 2 fig. 6b)",
                       "Max absolute error Delta over [0, pi/2], per n", r->acc, r->nacc, 0, lobe_families, 3);
    static const char *const norm_files[2] = {"max_rel_error_epicentre_vs_n_normalised.png",
                                              "max_abs_error_vs_n_normalised.png"};
    int norm_empty = plots_add_max_vs_n(&r->plots, norm_files[0],
                                        "max delta over the epicentre against n, normalised and microfacet lobes "
                                        "against their normalised references",
                                        "Max relative error delta over the epicentre, normalised lobes", r->acc,
                                        r->nacc, 1, norm_families, 2) == 1;
    plots_add_max_vs_n(&r->plots, norm_files[1],
                       "max Delta over [0, pi/2] against n, normalised and microfacet lobes against their normalised "
                       "references",
                       "Max absolute error Delta over [0, pi/2], normalised lobes", r->acc, r->nacc, 0, norm_families,
                       2);
    for (int k = 0; norm_empty && k < 2; k++) {   /* said in report.md, never drawn empty */
        add_picture(r, norm_files[k], REPORT_PLOTS, "normalised lobes against n");
        if (r->npics > 0 && strcmp(r->pics[r->npics - 1].file, norm_files[k]) == 0)
            snprintf(r->pics[r->npics - 1].not_drawn, sizeof r->pics[0].not_drawn,
                     "no normalised or microfacet model ran (--models named none: fq2n, phongn, blinnn, beckmann, "
                     "ggx, ...)");
    }
    const struct run_q_sweep *qs = &r->run.q_sweep;
    if (qs->n > 0) {
        plots_add_against_q(&r->plots, "fq_max_rel_error_vs_q.png",
                            "max delta of f_Q over the epicentre (n in [2, 1000]) against Q, with f2 (paper 2, fig. 2)",
                            "f_Q: max relative error delta over the epicentre against Q (paper 2, fig. 2)",
                            "max delta over the epicentre", 1, qs->q, qs->max_rel, qs->n, "fq (f_Q)", qs->f2_max_rel,
                            "cq2 (f2), independent of Q", 0.64);
        plots_add_against_q(&r->plots, "fq_max_abs_error_vs_q.png",
                            "max Delta of f_Q over [0, pi/2] (n in [2, 1000]) against Q, with f2 (paper 2, fig. 3)",
                            "f_Q: max absolute error Delta against Q (paper 2, fig. 3)", "max Delta over [0, pi/2]", 0,
                            qs->q, qs->max_abs, qs->n, "fq (f_Q)", qs->f2_max_abs, "cq2 (f2), independent of Q", 0.64);
    }
    /* throughput bars, when the throughput step wrote its results */
    path_join(path, sizeof path, r->run_dir, "throughput.json");
    if (access(path, R_OK) == 0) {
        static const char *const modes[2] = {"uniform", "varying"};
        for (int k = 0; k < 2; k++) {
            char file[64], caption[200];
            snprintf(file, sizeof file, "throughput_%s_n.png", modes[k]);
            snprintf(caption, sizeof caption,
                     "evaluations per second per model with n %s, default build options; the pow() built-in dark",
                     modes[k]);
            if (plots_add_throughput(&r->plots, path, modes[k], file, caption, err, sizeof err) == 2) {
                fprintf(stderr, "brdfbench all: %s\n", err);
                return EXIT_RUNTIME;
            }
        }
    }
    path_join(path, sizeof path, r->run_dir, "plots.json");
    if (plots_write_json(&r->plots, path, &r->run.s, err, sizeof err)) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        return EXIT_RUNTIME;
    }
    int drawn = 0;
    for (int i = 0; i < r->plots.count; i++) {
        const struct plot_figure *f = &r->plots.figs[i];
        all_progress(r, "plots", i, r->plots.count, f->file);
        path_join(path, sizeof path, r->run_dir, f->file);
        if (plot_figure_draw(f, path, err, sizeof err)) picture_failed(r, err);
        else drawn++;
        add_picture(r, f->file, f->kind == PLOT_BARS ? REPORT_THROUGHPUT : REPORT_PLOTS, "%s", f->caption);
    }
    all_step_done(r, "plots", t, "%d of %d pictures -> plots.json", drawn, r->plots.count);
    return 0;
}

/* run.json, then report.md made as `brdfbench report` makes it from the run folder, with the rows
 * the steps put into r->docs taken from memory instead of their files. */
static int step_report(struct all_run *r, double wall)
{
    double t = wall_seconds();
    char err[1024];
    struct report_run run = {
        .command = r->command,
        .folder = r->final_dir,
        .wall_seconds = wall,
        .steps = r->steps,
        .nsteps = r->nsteps,
        .images_note = r->images_note,
        .pictures = r->pics,
        .npictures = r->npics,
    };
    memcpy(run.parts, r->parts, sizeof run.parts);
    int rc = report_run_write(r->run_dir, &run, &r->run.s, err, sizeof err) ? EXIT_RUNTIME : 0;
    if (!rc) rc = report_rebuild_docs(r->run_dir, &r->docs, NULL, err, sizeof err) ? EXIT_RUNTIME : 0;
    if (rc) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        return rc;
    }
    r->step++;
    if (!r->quiet)
        fprintf(stderr, "[%6.1f s] step %d/%d %-10s %s/report.md (%.1f s)\n", all_elapsed(r), r->step, all_steps(r),
                "report", r->final_dir, wall_seconds() - t);
    return 0;
}

/* The side-by-side heatmap page, when the run has fields to show (a run of references alone has
 * none). */
static void add_shared_page(struct all_run *r, int shared_scale)
{
    char path[4300];
    struct stat st;
    if (path_join(path, sizeof path, r->run_dir, HEATMAPS_SHARED_FILE) || stat(path, &st) != 0) return;
    add_picture(r, HEATMAPS_SHARED_FILE, REPORT_HEATMAPS,
                "every model's delta and Delta fields side by side on one colour scale per panel kind, the largest "
                "over the models%s",
                shared_scale ? " (--shared-scale: the heatmaps above are on the same scales)" : "");
}

/* ---- command ---------------------------------------------------------------------- */

static void settings_default(struct all_settings *s, int quick)
{
    struct accuracy_grid full = {2.0, 1000.0, 1.0, ACC_DEFAULT_SAMPLES};
    struct accuracy_grid fast = {2.0, 1000.0, 10.0, 256};
    s->grid = quick ? fast : full;
    s->q_grid = (struct accuracy_grid){2.0, 1000.0, quick ? 25.0 : 1.0, quick ? 128 : 1024};
    s->q_min = 0.30;
    s->q_max = 0.90;
    s->q_step = quick ? 0.05 : 0.01;
    s->field = (struct field_grid){quick ? 41 : FIELD_DEFAULT_ROWS, quick ? 61 : FIELD_DEFAULT_COLS, 2.0, 1000.0};
    s->quick = quick;
}

static void run_free(struct all_run *r)
{
    for (int m = 0; m < r->nacc; m++) accuracy_result_free(&r->acc[m]);
    free(r->acc);
    plots_free(&r->plots);
    free(r->pics);
    free(r->steps);
    report_docs_free(&r->docs);
    if (r->actx_open) accuracy_close(&r->actx);
}

/* The flags: the grids, the models and the places. Returns -1 to run, else the exit code. */
static int parse_all(struct all_run *r, int argc, char **argv)
{
    char err[1024];
    const char *models_text = "all";
    int quick = 0;
    device_options_init(&r->dev);
    cli_shell_join(r->command, sizeof r->command, "brdfbench all", argc, argv);

    /* The grid flags: given ones replace the (quick or full) defaults of the main sweep and
       the heatmaps' range of n. */
    struct accuracy_grid g = { 2.0, 1000.0, 1.0, ACC_DEFAULT_SAMPLES };
    int n_min_given = 0, n_max_given = 0, n_step_given = 0, samples_given = 0;
    struct cli_flag flags[] = {
        CLI_FLAG_MODELS(&models_text, NULL, "all, and the user models of --model and --model-file"),
        CLI_FLAG_N_MIN(&g.n_min),
        CLI_FLAG_N_MAX(&g.n_max),
        CLI_FLAG_N_STEP(&g.n_step),
        CLI_FLAG_SAMPLES(&g.samples),
        { .name = "--results-root", .value = "DIR", .kind = CLI_PATH, .dest = &r->results_root,
          .help = "where run folders are made" },
        CLI_FLAG_OUT(&r->out_dir, "a new folder under --results-root, and its latest pointing at it"),
        { .name = "--quick", .kind = CLI_SWITCH, .dest = &quick, .set = 1,
          .help = "coarse grids (seconds; for tests and trials, not for figures): n step 10, 256 samples" },
        CLI_FLAG_QUIET(&r->quiet),
        CLI_FLAG_SHARED_SCALE(&r->shared_scale),
        CLI_FLAG_MEASURED(&r->measured_dir),
        CLI_FLAGS_USERMODEL,
        CLI_FLAGS_DEVICE(&r->dev),
    };
    flags[1].given = &n_min_given;
    flags[2].given = &n_max_given;
    flags[3].given = &n_step_given;
    flags[4].given = &samples_given;
    const struct cli_command cmd = {
        .name = "all",
        .about = "  The main job: the accuracy sweep of every model, the f_Q sweep over Q, error heatmaps,\n"
                 "  plots, and the claims, throughput and image passes where they exist, into a new run\n"
                 "  folder results/<date-time>/ (results/latest points at it) with report.md there.\n"
                 "  The grid flags set the main sweep and the heatmaps' range of n; the claims, the fit and\n"
                 "  the Q sweep keep the papers' grids.\n",
        .flags = flags,
        .nflags = (int)(sizeof flags / sizeof flags[0]),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    if (prc) goto usage_error;
    settings_default(&r->set, quick);
    if (n_min_given) r->set.grid.n_min = r->set.field.n_min = g.n_min;
    if (n_max_given) r->set.grid.n_max = r->set.field.n_max = g.n_max;
    if (n_step_given) r->set.grid.n_step = g.n_step;
    if (samples_given) r->set.grid.samples = g.samples;
    r->nmodels = cli_model_list(models_text, r->models, ALL_MAX_MODELS, err, sizeof err);
    if (r->nmodels < 0) goto usage_error;
    r->models_given = strcmp(models_text, "all") != 0;
    /* User models join the default set; with --models, one the list does not name is measured
       as well, with a note, as accuracy, render and throughput do. */
    if (strcmp(models_text, "all") == 0 && usermodel_append_all(r->models, &r->nmodels, ALL_MAX_MODELS, err, sizeof err))
        goto usage_error;
    if (strcmp(models_text, "all") != 0 &&
        (r->nmodels = cli_add_unlisted_user_models(r->models, r->nmodels, ALL_MAX_MODELS, err, sizeof err)) < 0)
        goto usage_error;
    if (accuracy_grid_check(&r->set.grid, NULL, err, sizeof err)) goto usage_error;
    if (r->measured_dir) {   /* a missing folder fails before the long run, not after it */
        char **files = NULL;
        int nfiles = 0;
        int bad = measured_collect(r->measured_dir, &files, &nfiles, err, sizeof err);
        measured_paths_free(files, nfiles);
        if (bad) {
            fprintf(stderr, "brdfbench all: --measured: %s\n", err);
            return EXIT_USAGE;
        }
    }

    return -1;

usage_error:
    fprintf(stderr, "brdfbench all: %s\n", err);
    return EXIT_USAGE;
}

/* The session, the run's places and the staging folder (outdir_stage_begin). Returns 0 or the
 * exit code, the session closed again on failure. */
static int open_run(struct all_run *r)
{
    char err[1024];
    int rc = cli_run_session("all", &r->run, &r->dev);
    if (rc)
        return rc;
    /* The run is built in a fresh staging folder beside its final place and swapped in only
     * when complete (outdir_stage_begin): a failure, a deadline or a signal leaves an earlier
     * run in --out as it was, and no half run anywhere. The places are checked before any
     * work, so a bad location fails fast. */
    if (!r->out_dir) {
        if (outdir_new_run(r->results_root, r->final_dir, sizeof r->final_dir, err, sizeof err)) {
            fprintf(stderr, "brdfbench all: %s\n", err);
            brdf_run_close(&r->run);
            return EXIT_RUNTIME;
        }
    } else {
        snprintf(r->final_dir, sizeof r->final_dir, "%s", r->out_dir);
    }
    if ((rc = outdir_stage_begin(r->final_dir, r->out_dir ? "--out" : NULL, r->run_dir, sizeof r->run_dir, err,
                                 sizeof err)) != 0) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        brdf_run_close(&r->run);
        return rc == 2 ? EXIT_USAGE : EXIT_RUNTIME;
    }
    report_docs_init(&r->docs, r->run_dir);
    if (!r->quiet)
        fprintf(stderr, "brdfbench all: %s (%s) -> %s%s\n", r->run.s.device_name, r->run.s.platform_version,
                r->final_dir, r->set.quick ? " (quick grids)" : "");
    return 0;
}

/* Every step in turn. The sweep, the heatmaps and the plots are this command's own: a failure
 * there stops the run. The other parts' failures are recorded in their report sections and the
 * run goes on. Returns 0 or the exit code of the step that stopped it. */
static int run_steps(struct all_run *r)
{
    int rc;
    plots_init(&r->plots);
    if ((rc = accuracy_open(&r->actx, &r->run.s, "")) != 0) return rc;
    r->actx_open = 1;
    outdir_reassert_signal_handlers();

    if ((rc = step_accuracy(r)) != 0) return rc;
    part(r, "claims", REPORT_PART_CLAIMS, all_step_claims(r));
    part(r, "fit", REPORT_PART_FIT, all_step_fit(r));
    if ((rc = step_q_sweep(r)) != 0) return rc;
    part(r, "throughput", REPORT_PART_THROUGHPUT, all_step_throughput(r));
    if ((rc = step_heatmaps(r)) != 0) return rc;
    if ((rc = plots_heatmaps_shared_step("all", r->run_dir, r->shared_scale)) != 0) return rc;
    add_shared_page(r, r->shared_scale);
    if ((rc = step_plots(r)) != 0) return rc;
    part(r, "images", REPORT_PART_IMAGES, all_step_images(r));
    part(r, "frontier", REPORT_PART_FRONTIER, all_step_frontier(r));
    if (r->measured_dir)
        part(r, "measured", REPORT_PART_MEASURED, all_step_measured(r));
    return 0;
}

/* After the steps: report.md, then the staged run swapped into place and results/latest.
 * Returns 0 or the exit code. */
static int finish_run(struct all_run *r)
{
    char err[1024];
    int rc = step_report(r, all_elapsed(r));
    if (rc) return rc;
    if (r->part_failures) {
        fprintf(stderr, "brdfbench all: %d part(s) failed (see above); the report says which\n", r->part_failures);
        rc = r->part_rc;
        return rc;
    }
    if (r->picture_failures) {
        fprintf(stderr, "brdfbench all: %d picture(s) could not be written; first: %s\n", r->picture_failures,
                r->picture_error);
        rc = EXIT_RUNTIME;
        return rc;
    }
    if (outdir_stage_commit(err, sizeof err)) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        rc = EXIT_RUNTIME;
        return rc;
    }
    if (!r->out_dir && outdir_set_latest(r->results_root, r->final_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench all: %s\n", err);
        rc = EXIT_RUNTIME;
        return rc;
    }
    if (!r->quiet) {
        if (accuracy_reused_sweeps(&r->run.s) > 0)
            fprintf(stderr, "[%6.1f s] %ld accuracy sweeps asked for by more than one part were run once\n", all_elapsed(r),
                    accuracy_reused_sweeps(&r->run.s));
        fprintf(stderr, "[%6.1f s] done: %s/report.md\n", all_elapsed(r), r->final_dir);
        printf("%s/report.md\n", r->final_dir);
    }
    return 0;
}

int cmd_all(int argc, char **argv)
{
    struct all_run *r = calloc(1, sizeof *r);   /* large: on the heap */
    if (!r) {
        fprintf(stderr, "brdfbench all: out of memory\n");
        return EXIT_RUNTIME;
    }
    r->t0 = wall_seconds();
    r->tty = isatty(STDERR_FILENO);
    r->results_root = "results";
    size_t used = (size_t)snprintf(r->command, sizeof r->command, "brdfbench all");
    for (int i = 1; i < argc && used < sizeof r->command; i++)
        used += (size_t)snprintf(r->command + used, sizeof r->command - used, " %s", argv[i]);
    int rc = parse_all(r, argc, argv);
    if (rc >= 0) goto done;
    char err[1024];
    if (draw_module_check(err, sizeof err)) {   /* the pictures would fail after the long run */
        fprintf(stderr, "brdfbench all: %s\n", err);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = open_run(r)) != 0) goto done;
    rc = run_steps(r);
    if (!rc) rc = finish_run(r);
    if (rc) {
        /* nothing of this run is kept: the staged folder goes, an earlier run stays */
        outdir_stage_abandon();
        fprintf(stderr, "brdfbench all: the run is not kept (exit %d)%s%s%s\n", rc,
                r->out_dir ? "; " : "", r->out_dir ? r->out_dir : "", r->out_dir ? " is as it was before" : "");
    }
    run_free(r);
    brdf_run_close(&r->run);
done:
    free(r);
    return rc;
}
