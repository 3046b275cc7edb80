/* cmd_all_parts.c - the parts of `brdfbench all` that other commands make: the claims
 * (reproduce), the fit, throughput, the image passes (render), the frontier and the measured
 * materials, each with the options of the main job, its files in the run folder and its page
 * for report.md. */
#define _POSIX_C_SOURCE 200809L
#include "cmd_all_internal.h"

#include "cli_table.h"
#include "exitcodes.h"
#include "fit.h"
#include "frontier.h"
#include "measured.h"
#include "measured_report.h"
#include "outdir.h"
#include "render.h"
#include "reproduce.h"
#include "throughput.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A part's page beside its JSON (report_part_page), drawn from the rows of that JSON by the function
   that draws report.md's section of the part. */
static int write_page(struct all_run *r, int which, const char *text)
{
    char path[4300], err[1024];
    const char *page = report_part_page(which);
    if (path_join(path, sizeof path, r->run_dir, page) || write_file_atomic(path, text, strlen(text), err, sizeof err)) {
        fprintf(stderr, "brdfbench all: %s: %s\n", page, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

/* A part's run failed: its message, and the exit code passed on to part(). */
static int part_failed(const char *what, int rc)
{
    fprintf(stderr, "brdfbench all: %s failed (exit %d)\n", what, rc);
    return rc;
}

/* The claims check's options: the papers' grids, or coarse ones for --quick. */
static void claims_options(const struct all_run *r, struct reproduce_options *o)
{
    reproduce_options_default(o);
    if (!r->set.quick) return;
    o->samples = 256;
    o->grid_check = 0;
    o->q_min = 0.30;
    o->q_max = 0.90;
    o->q_step = 0.05;
    o->q_samples = 128;
    o->q_n_step = 25;
    o->energy = 0;
    o->physical = 0;   /* the physically based models' cost: not for a trial run */
}

/* The claims of both papers (reproduce.h): claims.json, claims.md, q_sweep.json, energy.json. */
int all_step_claims(struct all_run *r)
{
    double t = wall_seconds();
    struct reproduce_options o;
    struct reproduce_report rep;
    claims_options(r, &o);
    memset(&rep, 0, sizeof rep);
    all_progress(r, "claims", 0, 1, "reproduce");
    o.io = (struct engine_io){ r->run_dir, 1 };
    int rc = reproduce_run(&r->run.s, &o, &rep);
    if (!rc)
        r->run.q_sweep = rep.q_sweep;   /* the Q step and the plots take it from the run, not the file */
    if (!rc && !rep.markdown)
        snprintf(r->parts[REPORT_PART_CLAIMS].missing, sizeof r->parts[0].missing,
                 "the claims check ran but gave no table.");
    if (!rc)
        all_step_done(r, "claims", t, "%d rows: %d reproduced, %d not reproduced, %d within noise -> claims.json, "
                      "claims.md, q_sweep.json%s", rep.count, rep.reproduced, rep.not_reproduced, rep.within_noise,
                      o.energy ? ", energy.json" : "");
    reproduce_report_free(&rep);
    return rc ? part_failed("the claims check", rc) : 0;
}

/* Beyond the papers (fit.h): the family's per-n limit and the best affine k(n) = a n + b,
 * beside fq2, fvol and cq2 over the same range -> fit.json (report.md's section comes from it). */
int all_step_fit(struct all_run *r)
{
    double t = wall_seconds();
    struct fit_options o;
    struct fit_report rep;
    fit_options_default(&o);
    o.n_step = r->set.quick ? 25 : o.n_step;
    o.samples = r->set.quick ? 256 : o.samples;
    memset(&rep, 0, sizeof rep);
    all_progress(r, "fit", 0, 1, "fitting");
    o.io = (struct engine_io){ r->run_dir, 1 };
    int rc = fit_run(&r->run.s, &o, &rep);
    if (!rc) all_step_done(r, "fit", t, "best affine %s -> fit.json", rep.main.spec_text);
    fit_report_free(&rep);
    return rc ? part_failed("the fit", rc) : 0;
}

/* Throughput (throughput.h) with the configuration made for the main job: every model, three
 * sets of build options, both n modes, the C baseline and the sweep timing. Bars of the
 * default build options per n mode go with the plots. */
int all_step_throughput(struct all_run *r)
{
    double t = wall_seconds();
    struct throughput_options o;
    throughput_options_default(&o);
    o.model_count = 0;
    for (int m = 0; m < r->nmodels && o.model_count < TP_MAX_MODELS; m++) o.models[o.model_count++] = r->models[m];
    if (r->set.quick) {
        o.reps = 2;
        o.min_time = 1e-3;
        o.variants = 1u << TP_VARIANT_DEFAULT;
        o.host_c = 0;
        o.sweep = 0;
    }
    char err[1024];
    o.io = (struct engine_io){ r->run_dir, 1 };
    if (throughput_options_check(&o, err, sizeof err)) {
        fprintf(stderr, "brdfbench all: throughput: %s\n", err);
        return EXIT_USAGE;
    }
    all_progress(r, "throughput", 0, 1, "measuring");
    struct throughput_result res = { 0 };
    int rc = throughput_run(&r->run.s, &o, &res);
    if (rc) {
        throughput_result_free(&res);
        return part_failed("the throughput measurement", rc);
    }
    if (res.markdown) {
        rc = write_page(r, REPORT_PART_THROUGHPUT, res.markdown);
        throughput_result_free(&res);
        if (rc) return rc;
    } else {
        snprintf(r->parts[REPORT_PART_THROUGHPUT].missing, sizeof r->parts[0].missing,
                 "the throughput measurement ran but gave no table.");
    }
    all_step_done(r, "throughput", t, "%d models -> throughput.json, throughput.csv", o.model_count);
    return 0;
}

/* The image passes (render.h) at a size that keeps the main job short: images 960 x 540,
 * timings at 1920 x 1080 (5 launches after 2 warm-ups). A scene whose data package is not
 * installed is left out and the report says so. */
int all_step_images(struct all_run *r)
{
    double t = wall_seconds();
    char missing[512] = "";
    struct render_options o;
    render_options_default(&o);
    o.width = r->set.quick ? 320 : 960;
    o.height = r->set.quick ? 180 : 540;
    o.ntime_sizes = 1;
    o.time_w[0] = r->set.quick ? 320 : 1920;
    o.time_h[0] = r->set.quick ? 180 : 1080;
    o.reps = r->set.quick ? 1 : 5;
    o.warmup = r->set.quick ? 1 : 2;
    o.io = (struct engine_io){ r->run_dir, 1 };
    o.nmodels = 0;
    for (int m = 0; m < r->nmodels && o.nmodels < RENDER_MAX_MODELS; m++) o.models[o.nmodels++] = r->models[m];
    if (access(o.teapot_path, R_OK) != 0) {
        o.scene_on[RENDER_TEAPOT] = 0;
        snprintf(missing + strlen(missing), sizeof missing - strlen(missing),
                 " The teapot was left out: %s is missing (Debian package %s).", o.teapot_path, RENDER_TEAPOT_PACKAGE);
    }
    if (access(o.bunny_path, R_OK) != 0) {
        o.scene_on[RENDER_BUNNY] = 0;
        snprintf(missing + strlen(missing), sizeof missing - strlen(missing),
                 " The bunny was left out: %s is missing (Debian package %s).", o.bunny_path, RENDER_BUNNY_PACKAGE);
    }
    all_progress(r, "images", 0, 1, "render");
    struct render_result res;
    int rc = render_run(&r->run.s, &o, &res);
    render_result_free(&res);
    if (rc) {
        fprintf(stderr, "brdfbench all: image passes: %s\n", res.err);
        return rc;
    }
    snprintf(r->images_note, sizeof r->images_note, "%s", missing[0] ? missing + 1 : "");
    all_step_done(r, "images", t, "%d models on %s%s%s at %dx%d, timed at %dx%d -> render.json, render/", o.nmodels,
              "spheres", o.scene_on[RENDER_TEAPOT] ? ", teapot" : "", o.scene_on[RENDER_BUNNY] ? ", bunny" : "",
              o.width, o.height, o.time_w[0], o.time_h[0]);
    return 0;
}

/* Which lobe to ship (frontier.h): every lobe approximation's cost against its accuracy, with
 * shorter timings than `brdfbench frontier` (2 rounds of 3 launches of 10 ms) to keep the main job short. */
int all_step_frontier(struct all_run *r)
{
    double t = wall_seconds();
    struct frontier_options o;
    frontier_options_default(&o);
    o.reps = 3;
    o.rounds = 2;
    o.min_time = 0.01;
    o.samples = r->set.quick ? 256 : 512;
    /* --models: those; else frontier's own set of lobe approximations and the user models */
    if (r->models_given) {
        for (int m = 0; m < r->nmodels && o.model_count < FRONTIER_MAX_MODELS; m++)
            o.models[o.model_count++] = r->models[m];
        if (r->nmodels > FRONTIER_MAX_MODELS)
            fprintf(stderr, "brdfbench all: warning: the frontier measures the first %d of the %d models\n",
                    FRONTIER_MAX_MODELS, r->nmodels);
    } else {
        char err[1024];
        int n = cli_frontier_default_models(o.models, FRONTIER_MAX_MODELS, err, sizeof err);
        if (n < 0) {
            fprintf(stderr, "brdfbench all: the frontier: %s\n", err);
            return EXIT_USAGE;
        }
        o.model_count = n;
    }
    all_progress(r, "frontier", 0, 1, "measuring");
    struct frontier_result res = { 0 };
    o.io = (struct engine_io){ r->run_dir, 1 };
    int rc = frontier_run(&r->run.s, &o, &res);
    if (!rc && res.markdown) rc = write_page(r, REPORT_PART_FRONTIER, res.markdown);
    else if (!rc)
        snprintf(r->parts[REPORT_PART_FRONTIER].missing, sizeof r->parts[0].missing,
                 "the frontier ran but gave no section.");
    frontier_result_free(&res);
    if (rc) return part_failed("the frontier", rc);
    all_step_done(r, "frontier", t, "cost against accuracy -> frontier.json, frontier.csv, frontier_*.png");
    return 0;
}

/* The measured materials of --measured DIR (measured.h): measured.json, its pictures and a
 * section of report.md. */
int all_step_measured(struct all_run *r)
{
    double t = wall_seconds();
    char err[4600];
    char **files = NULL;
    int nfiles = 0;
    struct measured_options o;
    measured_options_default(&o);
    struct measured_report rep;
    memset(&rep, 0, sizeof rep);
    int rc = measured_collect(r->measured_dir, &files, &nfiles, err, sizeof err);
    if (!rc) {
        all_progress(r, "measured", 0, 1, "fitting");
        o.io = (struct engine_io){ r->run_dir, 1 };
        o.paths = files;
        o.count = nfiles;
        rc = measured_run(&r->run.s, &o, &rep);
        snprintf(err, sizeof err, "%s", rep.err);
    }
    if (rc && err[0])
        fprintf(stderr, "brdfbench all: --measured: %s\n", err);
    if (!rc) {
        struct md_buf md;
        md_init(&md);
        measured_markdown(&md, &rep);
        rc = md.failed ? EXIT_RUNTIME : write_page(r, REPORT_PART_MEASURED, md.s ? md.s : "");
        md_free(&md);
    }
    if (!rc) {
        all_step_done(r, "measured", t, "%d materials -> measured.json, measured_*.png", rep.count);
    }
    measured_report_free(&rep);
    measured_paths_free(files, nfiles);
    return rc;
}

