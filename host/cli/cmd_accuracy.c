/* cmd_accuracy.c - `brdfbench accuracy`: the dense-grid sweep of models on the device,
 * written as accuracy.json, accuracy.csv and a table. */
#include "accuracy.h"
#include "accuracy_report.h"
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "field.h"
#include "field_report.h"
#include "hemisphere.h"
#include "hemisphere_pictures.h"
#include "heatmaps_shared.h"
#include "outdir.h"
#include "plots.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_MODELS 64

static int self_referenced(const struct model_spec *m) { return strcmp(m->info->id, m->info->reference_id) == 0; }

/* A model's error field as field_LABEL.json and its heatmap as heatmap_LABEL.png in run_dir
 * (LABEL made safe for a file name); 0, or EXIT_RUNTIME with the message on stderr. */
static int write_field_files(struct cl_session *s, const struct field_result *fr, const char *label,
                             const char *run_dir)
{
    char err[1024], name[200], path[4400], safe[96];
    field_safe_label(label, safe, sizeof safe);
    snprintf(name, sizeof name, "field_%s.json", safe);
    path_join(path, sizeof path, run_dir, name);
    if (field_write_json(path, fr, s, err, sizeof err) == 0) {
        snprintf(name, sizeof name, "heatmap_%s.png", safe);
        path_join(path, sizeof path, run_dir, name);
        if (field_draw_heatmap(path, fr, NULL, err, sizeof err) == 0)
            return 0;
    }
    fprintf(stderr, "brdfbench accuracy: %s\n", err);
    return EXIT_RUNTIME;
}

/* --pictures: each model's error field and heatmap over the run's range of n, and the per-n
 * maxima of every model against n (plots.json and its pictures), in run_dir. */
static int accuracy_pictures(struct cl_session *s, const struct model_spec *models,
                             const struct accuracy_result *res, int nmodels, const struct accuracy_grid *grid,
                             const char *run_dir, int quiet, int *drawn)
{
    char err[1024], path[4400];
    int rc = 0;
    *drawn = 0;
    struct field_grid fg = { FIELD_DEFAULT_ROWS, FIELD_DEFAULT_COLS, grid->n_min, grid->n_max };
    if (!(grid->n_min < grid->n_max)) {
        if (!quiet)
            fprintf(stderr, "brdfbench accuracy: note: --pictures: one n (%g), so no heatmaps (they span a range of n)\n",
                    grid->n_min);
    } else {
        struct field_ctx f;
        if ((rc = field_open(&f, s, "")) != 0)
            return rc;
        for (int m = 0; m < nmodels && !rc; ++m) {
            if (self_referenced(&models[m]))
                continue;   /* zero by definition: nothing to see */
            struct field_result fr;
            if ((rc = field_run(&f, &models[m], &fg, &fr)) != 0)
                break;
            if ((rc = write_field_files(s, &fr, models[m].label, run_dir)) == 0)
                ++*drawn;
            field_result_free(&fr);
        }
        field_close(&f);
        if (rc)
            return rc;
    }
    struct plot_set set;
    plots_init(&set);
    plots_add_max_vs_n(&set, "max_rel_error_epicentre_vs_n.png",
                       "max delta over the epicentre against n, each model against its reference",
                       "Max relative error delta over the epicentre, per n", res, nmodels, 1, NULL, 0);
    plots_add_max_vs_n(&set, "max_abs_error_vs_n.png",
                       "max Delta over [0, pi/2] against n, each model against its reference",
                       "Max absolute error Delta over [0, pi/2], per n", res, nmodels, 0, NULL, 0);
    path_join(path, sizeof path, run_dir, "plots.json");
    if (plots_write_json(&set, path, s, err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
    } else {
        int failed = plots_draw(&set, run_dir, err, sizeof err);
        if (failed) {
            fprintf(stderr, "brdfbench accuracy: %s\n", err);
            rc = EXIT_RUNTIME;
        }
        *drawn += set.count - failed;
    }
    plots_free(&set);
    return rc;
}

/* The run folder: out_dir (made when missing), or under results/ (its name given after the sweep);
 * none without to_folder. 0, or EXIT_RUNTIME with the message on stderr. */
static int prepare_run_dir(int to_folder, const char *out_dir, char *run_dir, size_t run_dir_len)
{
    char err[1024];
    if (!to_folder)
        return 0;
    if (out_dir) {
        if (outdir_prepare(out_dir, "--out", err, sizeof err)) {
            fprintf(stderr, "brdfbench accuracy: %s\n", err);
            return EXIT_RUNTIME;
        }
        snprintf(run_dir, run_dir_len, "%s", out_dir);
    } else if (outdir_prepare("results", NULL, err, sizeof err) || outdir_check_latest("results", err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        return EXIT_RUNTIME;
    }
    return 0;
}

/* What the documents hold: the lobe sweep's results, then the hemisphere sweep's. */
struct acc_docs {
    const struct accuracy_result *res;
    int nmodels;
    const struct hemi_result *hres;
    int hcount;
    const struct cl_session *s;
    const char *build_options;
};

/* accuracy.json (csv 0) or accuracy.csv (csv 1) at path. */
static int write_document(int csv, const char *path, const struct acc_docs *d, char *err, size_t errlen)
{
    return csv ? accuracy_write_csv_full(path, d->res, d->nmodels, d->hres, d->hcount, err, errlen)
               : accuracy_write_json_full(path, d->res, d->nmodels, d->hres, d->hcount, d->s, d->build_options, err,
                                          errlen);
}

/* --json or --csv: one document where the flag says (a file, or standard output). */
static int write_flag_document(int csv, const char *flag_path, const struct acc_docs *d, char *err, size_t errlen)
{
    struct cli_output o;
    const char *wp;
    int wrc = cli_output_path(&o, flag_path, csv ? "accuracy.csv" : "accuracy.json", &wp, err, errlen);
    if (!wrc)
        wrc = write_document(csv, wp, d, err, errlen);
    int frc = cli_output_finish(&o, !wrc, err, errlen);
    return wrc ? wrc : frc;
}

/* accuracy.json and accuracy.csv in run_dir (when not NULL; results/latest moved to it when
 * set_latest), then the --json and --csv documents. 0, or non-zero with the message in err. */
static int write_documents(const struct acc_docs *d, const char *run_dir, int set_latest, const char *json_path,
                           const char *csv_path, char *err, size_t errlen)
{
    char path[4200];
    int wrc = 0;
    if (run_dir) {
        path_join(path, sizeof path, run_dir, "accuracy.json");
        wrc = write_document(0, path, d, err, errlen);
        if (!wrc) {
            path_join(path, sizeof path, run_dir, "accuracy.csv");
            wrc = write_document(1, path, d, err, errlen);
        }
        if (!wrc && set_latest)
            wrc = outdir_set_latest("results", run_dir, err, errlen);
    }
    if (!wrc && json_path)
        wrc = write_flag_document(0, json_path, d, err, errlen);
    if (!wrc && csv_path)
        wrc = write_flag_document(1, csv_path, d, err, errlen);
    return wrc;
}

/* The checks of the parsed flags: the models (into models; their count, or -1 with the message
 * in err), --pictures against the outputs, the grid, one document on standard output. */
/* pictures: 1 for --pictures, plus 2 for --shared-scale. */
static int check_args(const char *models_text, int models_given, struct model_spec *models, int pictures,
                      const char *out_dir, const char *json_path, const char *csv_path,
                      const struct accuracy_grid *grid, char *err, size_t errlen)
{
    if (!models_given && usermodel_count() > 0)
        models_text = usermodel_names();
    int nmodels = cli_model_list(models_text, models, MAX_MODELS, err, errlen);
    if (nmodels >= 0)
        nmodels = cli_add_unlisted_user_models(models, nmodels, MAX_MODELS, err, errlen);
    if (nmodels < 0)
        return -1;
    if ((pictures & 1) && !out_dir && (json_path || csv_path)) {
        snprintf(err, errlen, "--pictures writes into the run folder: give --out DIR (with --json or --csv "
                              "and no --out there is none)");
        return -1;
    }
    if (pictures == 2) {
        snprintf(err, errlen, "--shared-scale scales the heatmaps of --pictures (accepted: with --pictures)");
        return -1;
    }
    if (accuracy_grid_check(grid, NULL, err, errlen))
        return -1;
    if (cli_is_stdout(json_path) && cli_is_stdout(csv_path)) {
        snprintf(err, errlen, "--json - and --csv -: one document at a time on standard output");
        return -1;
    }
    return nmodels;
}

/* Every model's sweep into res (*done counts the results made), with a progress line once the
 * run takes a while. */
static int sweep_models(struct accuracy_ctx *actx, const struct model_spec *models, int nmodels,
                        const struct accuracy_grid *grid, struct accuracy_result *res, int *done, int quiet)
{
    double started = wall_seconds();
    for (int m = 0; m < nmodels; ++m, ++*done) {
        int rc = accuracy_run(actx, &models[m], grid, &res[m]);
        if (rc)
            return rc;
        if (!quiet && wall_seconds() - started > 1.0)   /* a progress line once a run takes a while */
            fprintf(stderr, "accuracy: %d/%d %s done (%.1f s)\n", m + 1, nmodels, models[m].label,
                    wall_seconds() - started);
    }
    return 0;
}

/* The table, the device-against-double check, the device time and what was written. */
static void print_summary(const struct acc_docs *d, const struct accuracy_grid *g, const char *run_dir,
                          int npictures, const char *json_path, const char *csv_path)
{
    const struct accuracy_result *res = d->res;
    const int nmodels = d->nmodels;
    if (nmodels > 0)
        accuracy_print_table(stdout, res, nmodels);
    hemisphere_print_table(stdout, d->hres, d->hcount);
    double worst = 0, dev_s = 0, pts = 0;
    int beyond = 0;
    for (int m = 0; m < nmodels; ++m) {
        worst = fmax(worst, accuracy_check_in_digits(&res[m]));
        beyond += res[m].device_disagrees;
        dev_s += res[m].device_seconds;
        pts += res[m].points;
    }
    if (nmodels > 0)
        printf("\ndevice vs double reference: every per-n figure recomputed in double at the device's inputs;\n"
           "largest difference = %.3g of one unit in the 4th significant digit of its figure (bound %g; "
           "%d models beyond it)\n", worst, ACC_CHECK_BOUND_UNITS, beyond);
    int wall = 0;
    for (int m = 0; m < nmodels; ++m)
        wall |= res[m].timer_wall;
    if (nmodels > 0)
        printf("device time %.3f s for %.3g points (%.3g G points/s; grid: n in [%g, %g] step %g, %ld samples per zone)%s\n",
           dev_s, pts, pts / dev_s * 1e-9, g->n_min, g->n_max, g->n_step, g->samples,
           wall ? "; wall time: the driver's profiling events gave no time" : "");
    if (run_dir)
        printf("written: %s/accuracy.json, %s/accuracy.csv\n", run_dir, run_dir);
    if (npictures)
        printf("written: %d pictures in %s (heatmap_<model>.png, max_rel_error_epicentre_vs_n.png, "
               "max_abs_error_vs_n.png; full BRDFs: hemisphere_heatmap_<model>.png, "
               "hemisphere_max_rel_vs_p_<model>.png, hemisphere_max_abs_vs_p_<model>.png)\n", npictures, run_dir);
    if (json_path)
        printf("written: %s\n", json_path);
    if (csv_path)
        printf("written: %s\n", csv_path);
}

/* --param NAME=VALUE, repeatable. */
struct fixed_params {
    struct hemi_fixed v[HEMI_MAX_FIXED];
    int count;
};

static int call_param(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    (void)flag;
    struct fixed_params *f = dest;
    return hemisphere_fixed_parse(value, f->v, &f->count, err, errlen);
}

/* The hemisphere sweep's part of a run: its models with their references and axes. */
struct full_plan {
    struct model_spec models[MAX_MODELS], refs[MAX_MODELS];
    struct hemi_axis axes[MAX_MODELS];
    int count;
    struct hemi_grid grid;
    struct model_spec lobe_reference;   /* --reference for the lobe models */
    /* A measured material named by --reference, open for the run (closed by cmd_accuracy). */
    struct hemi_measured measured_ref;
    int measured_ref_open;
};

static int ends_with(const char *s, const char *tail)
{
    size_t a = strlen(s), b = strlen(tail);
    return a >= b && strcmp(s + a - b, tail) == 0;
}

/* 1 when --reference names a model file rather than a model: a path (a '/') or a file name of the
   kinds --model-file reads. */
static int names_file(const char *text)
{
    static const char *const tails[] = { ".brdf", ".glsl", ".hlsl", ".cl" };
    if (strchr(text, '/'))
        return 1;
    for (size_t i = 0; i < sizeof tails / sizeof tails[0]; ++i)
        if (ends_with(text, tails[i]))
            return 1;
    return 0;
}

/* --reference SPEC (docs/user-models.md, "Measured over the hemisphere"): merl:FILE (or
 * FILE.binary), a measured material; user:NAME[:p=v,...], a user model of the command line by its
 * name; a model file (a path, or a .brdf, .glsl, .hlsl or .cl file name that names no model),
 * read as --model-file reads it (the same file as a --model-file is the same model); else a
 * built-in with parameters (ct-ggx:F0=0.04) or a user model's name (NAME@FILE.brdf included).
 * 0, or -1 with the message in err. */
static int resolve_reference(const char *text, struct full_plan *plan, struct model_spec *out, char *err,
                             size_t errlen)
{
    char inner[700];
    if (strncmp(text, "merl:", 5) == 0 || ends_with(text, ".binary")) {
        const char *path = strncmp(text, "merl:", 5) == 0 ? text + 5 : text;
        if (!*path) {
            snprintf(err, errlen, "--reference: merl: names no file (accepted: merl:FILE.binary, a MERL file)");
            return -1;
        }
        if (plan->measured_ref_open) {
            hemisphere_measured_close(&plan->measured_ref);
            plan->measured_ref_open = 0;
        }
        if (hemisphere_measured_open(path, &plan->measured_ref, out, inner, sizeof inner)) {
            snprintf(err, errlen, "--reference: %.*s", (int)errlen - 16, inner);
            return -1;
        }
        plan->measured_ref_open = 1;
        return 0;
    }
    /* the model's id: the text up to its parameters (NAME:p=v) */
    char id[MODEL_LABEL_MAX];
    const char *name = strncmp(text, "user:", 5) == 0 ? text + 5 : text;
    snprintf(id, sizeof id, "%.*s", (int)strcspn(name, ":"), name);
    if (strncmp(text, "user:", 5) == 0) {
        const struct model_info *info = models_find(id);
        if (!info || model_is_builtin(info)) {
            const char *names = usermodel_names();
            snprintf(err, errlen, "--reference: %.60s: no user model of that name (accepted: %s)", text,
                     *names ? names : "none given: --model-file FILE or --model NAME=EXPR first, or --reference FILE");
            return -1;
        }
    }
    /* a file name that is also a model's name (NAME@FILE.brdf, a .brdf file's model) is the model */
    if (names_file(text) && !models_find(id)) {
        const struct user_model *um = NULL;
        if (usermodel_load_file(text, &um, inner, sizeof inner)) {
            const char *why = strncmp(inner, "--model-file: ", 14) == 0 ? inner + 14 : inner;
            snprintf(err, errlen, "--reference: %.*s", (int)errlen - 16, why);
            return -1;
        }
        model_spec_default(&um->info, out);
    } else if (model_spec_parse(name, out, inner, sizeof inner)) {
        snprintf(err, errlen, "--reference: %.*s", (int)errlen - 16, inner);
        return -1;
    }
    const struct user_model *um = usermodel_of(out);
    if (um && um->full && !usermodel_host_ready(um)) {
        /* the sweep compares with the reference's double values, computed on the host */
        snprintf(err, errlen, "--reference: %s: its text does not compile as C for the host's double evaluation "
                              "(%.200s), so it cannot be a reference (accepted: a model file whose text is C, a "
                              "built-in, merl:FILE.binary)", out->label, um->host_error);
        return -1;
    }
    return 0;
}

/* Moves the full BRDFs of models[] into plan (their references and axes checked); returns the
 * count of lobe models left, or -1 with the message in err. */
static int plan_full_models(struct model_spec *models, int nmodels, struct full_plan *plan, const char *reference_text,
                            const char *sweep_text, const struct fixed_params *fixed, int points,
                            const char *grid_text, const struct accuracy_grid *lobe_grid, char *err, size_t errlen)
{
    char tail;
    if (sscanf(grid_text, "%dx%dx%d%c", &plan->grid.nh, &plan->grid.nd, &plan->grid.np, &tail) != 3) {
        snprintf(err, errlen, "--hemisphere-grid: '%.40s' is not NHxNDxNP (accepted: three integers in [%d, %d], "
                              "e.g. 48x48x96)", grid_text, HEMI_MIN_CELLS, HEMI_MAX_CELLS);
        return -1;
    }
    if (hemisphere_grid_check(&plan->grid, points, err, errlen))
        return -1;
    struct model_spec named_ref;
    if (reference_text && resolve_reference(reference_text, plan, &named_ref, err, errlen))
        return -1;
    if (reference_text)
        plan->lobe_reference = named_ref;
    struct hemi_axis axis;
    memset(&axis, 0, sizeof axis);
    if (hemisphere_axis_parse(sweep_text ? sweep_text : "n", &axis, err, errlen))
        return -1;
    axis.count = points;
    int kept = 0;
    for (int m = 0; m < nmodels; ++m) {
        if (!hemisphere_applies_against(&models[m], reference_text ? &named_ref : NULL)) {
            models[kept++] = models[m];
            continue;
        }
        int k = plan->count++;
        plan->models[k] = models[m];
        if (reference_text)
            plan->refs[k] = named_ref;
        else if (hemisphere_default_reference(&models[m], &axis, &plan->refs[k], err, errlen))
            return -1;
        plan->axes[k] = axis;
        if (hemisphere_axis_check(&plan->axes[k], fixed->v, fixed->count, &models[m], &plan->refs[k],
                                  lobe_grid->n_min, lobe_grid->n_max, err, errlen) ||
            hemisphere_table_check(&plan->refs[k], &plan->grid, points, err, errlen))
            return -1;
    }
    const struct user_model *ref_um = reference_text ? usermodel_of(&named_ref) : NULL;
    if (reference_text && kept > 0 && ref_um && !ref_um->full && !usermodel_host_ready(ref_um)) {
        /* the lobe sweep reads a user reference's double values, computed on the host */
        snprintf(err, errlen, "--reference: %s: its text does not compile as C for the host's double evaluation "
                              "(%.200s), so it cannot be a reference (accepted: a model file whose text is C, a "
                              "built-in)", named_ref.label, ref_um->host_error);
        return -1;
    }
    if (reference_text && kept > 0 && !model_is_builtin(named_ref.info) && !(ref_um && !ref_um->full)) {
        /* a lobe model is measured against a lobe: a built-in or a user lobe model (a table of its
           double values, host/measure/accuracy/accuracy.c); a full BRDF or a measured material is a
           reference of the hemisphere sweep */
        snprintf(err, errlen, "--reference: %s is the reference of full BRDFs only, and %s is a lobe model of c and n "
                              "(accepted for a lobe model: a built-in, e.g. blinn or ggx, or a user lobe model)",
                 named_ref.label, models[0].label);
        return -1;
    }
    /* a user lobe reference's table of host values fits the grid (the device's memory is checked once
       the session is open) */
    if (reference_text && kept > 0 && accuracy_reference_check(lobe_grid, &named_ref, NULL, err, errlen))
        return -1;
    if (plan->count == 0 && (sweep_text || fixed->count > 0)) {
        snprintf(err, errlen, "%s applies to the hemisphere sweep of full BRDFs, and none is among the models "
                              "(accepted: with a full user model, ct-ggx, ct-beckmann, brady or he)",
                 sweep_text ? "--axis" : "--param");
        return -1;
    }
    return kept;
}

static int accuracy_main(int argc, char **argv, struct full_plan *plan);

int cmd_accuracy(int argc, char **argv)
{
    struct full_plan *plan = calloc(1, sizeof *plan);   /* large: the models, references and axes */
    if (!plan) {
        fprintf(stderr, "brdfbench accuracy: out of memory\n");
        return EXIT_RUNTIME;
    }
    int rc = accuracy_main(argc, argv, plan);
    if (plan->measured_ref_open)
        hemisphere_measured_close(&plan->measured_ref);
    free(plan);
    return rc;
}

static int accuracy_main(int argc, char **argv, struct full_plan *plan)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "accuracy", cmd_accuracy, "accuracy.json", "results", "accuracy.csv");
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct accuracy_grid grid = { 2.0, 1000.0, 1.0, ACC_DEFAULT_SAMPLES };
    struct device_options dev;
    device_options_init(&dev);
    const char *models_text = "all", *out_dir = NULL, *json_path = NULL, *csv_path = NULL;
    int quiet = 0, models_given = 0, pictures = 0, shared_scale = 0;
    struct model_spec models[MAX_MODELS];
    const char *reference_text = NULL, *sweep_text = NULL, *hgrid_text = "48x48x96";
    struct fixed_params fixed = { .count = 0 };
    int sweep_points = HEMI_DEFAULT_POINTS;

    const struct cli_flag flags[] = {
        CLI_FLAG_MODELS(&models_text, &models_given, "all; with --model or --model-file, only the user models"),
        CLI_FLAG_N_MIN(&grid.n_min), CLI_FLAG_N_MAX(&grid.n_max), CLI_FLAG_N_STEP(&grid.n_step),
        CLI_FLAG_SAMPLES(&grid.samples),
        CLI_FLAGS_DOCUMENTS(&out_dir, &json_path, &csv_path),
        CLI_FLAG_QUIET(&quiet),
        { .name = "--pictures", .kind = CLI_SWITCH, .dest = &pictures, .set = 1,
          .help = "also draw, into the run folder, each model's error heatmap (field_<model>.json and "
                  "heatmap_<model>.png, over the run's range of n) and the max delta and max Delta against n "
                  "of every model (plots.json and two PNGs), user models included; brdfbench plot and heatmap "
                  "redraw them" },
        CLI_FLAG_SHARED_SCALE(&shared_scale),
        CLI_FLAGS_FULLBRDF(&reference_text, &sweep_text, call_param, &fixed, &sweep_points, &hgrid_text),
        CLI_FLAGS_USERMODEL,
        CLI_FLAGS_DEVICE(&dev),
    };
    const struct cli_command cmd = {
        .name = "accuracy",
        .about = "  Sweeps every model over (angle, n): max relative error in the epicentre zone, max absolute\n"
                 "  error in the attenuation zone and over the whole range, each with where it occurs.\n"
                 "  A full BRDF (a user model of L, V, N; ct-ggx, ct-beckmann, brady, he) is measured over the\n"
                 "  hemisphere instead: (theta_h, theta_d, phi_d) where N.L > 0 and N.V > 0, along one parameter axis.\n",
        CLI_TABLE(flags),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    int nmodels = check_args(models_text, models_given, models, pictures + 2 * shared_scale, out_dir, json_path,
                             csv_path, &grid, err, sizeof err);
    if (nmodels < 0)
        goto usage_error;
    /* the full BRDFs leave the lobe list for the hemisphere sweep */
    nmodels = plan_full_models(models, nmodels, plan, reference_text, sweep_text, &fixed, sweep_points, hgrid_text,
                               &grid, err, sizeof err);
    if (nmodels < 0)
        goto usage_error;
    /* --json or --csv without --out: those files only, no run folder. A document on
       standard output leaves the table out. */
    int to_folder = out_dir || (!json_path && !csv_path);
    int doc_on_stdout = cli_is_stdout(json_path) || cli_is_stdout(csv_path);

    struct brdf_run run;
    struct cl_session *s = &run.s;
    int rc = cli_run_check_documents("accuracy", json_path, csv_path);
    if (rc)
        return rc;
    /* an --out that is no usable folder is refused before the kernel builds, not after them */
    if (out_dir && outdir_check_existing(out_dir, "--out", err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        return EXIT_RUNTIME;
    }
    rc = cli_run_session("accuracy", &run, &dev);
    if (rc)
        return rc;
    if (accuracy_grid_check(&grid, s, err, sizeof err) ||
        (reference_text && nmodels > 0 && accuracy_reference_check(&grid, &plan->lobe_reference, s, err, sizeof err))) {
        brdf_run_close(&run);
        goto usage_error;
    }
    struct accuracy_ctx actx;
    struct accuracy_result *res = calloc((size_t)nmodels + 1, sizeof *res);
    int done = 0;
    if (!res) {
        brdf_run_close(&run);
        return EXIT_RUNTIME;
    }
    struct hemi_ctx hctx;
    hemisphere_open(&hctx, s, "");
    struct hemi_result hres[MAX_MODELS];
    int hdone = 0;
    rc = accuracy_open(&actx, s, "");
    if (rc)
        goto cleanup;
    if (reference_text && nmodels > 0)
        actx.reference = &plan->lobe_reference;
    for (int m = 0; m < nmodels && !rc; ++m)
        rc = accuracy_prepare(&actx, &models[m]);   /* a user model's compile error before any sweep */
    if (rc)
        goto cleanup;
    /* Check the output folder before the sweep, so a bad --out fails fast (and after the
       builds, so a user model that does not compile leaves no folder behind). */
    char run_dir[4096] = "";
    if ((rc = prepare_run_dir(to_folder, out_dir, run_dir, sizeof run_dir)))
        goto cleanup;
    if (!quiet)
        fprintf(stderr, "device: %s (%s); %d kernel build%s %.2f s%s\n", s->device_name, s->platform_version,
                s->builds, s->builds == 1 ? "" : "s", s->build_seconds_total,
                s->specialise ? " (one program per model: the rest are built as the sweep reaches them)" : "");
    if ((rc = sweep_models(&actx, models, nmodels, &grid, res, &done, quiet)))
        goto cleanup;
    for (; hdone < plan->count; ++hdone) {
        if ((rc = hemisphere_run(&hctx, &plan->models[hdone], &plan->refs[hdone], &plan->axes[hdone], fixed.v,
                                 fixed.count, &plan->grid, &hres[hdone])) != 0)
            goto cleanup;
    }
    if (to_folder && !out_dir && outdir_new_run("results", run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    const struct acc_docs docs = { res, nmodels, hres, hdone, s, actx.build_options };
    int wrc = write_documents(&docs, to_folder ? run_dir : NULL, !out_dir, json_path, csv_path, err, sizeof err);
    if (wrc) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    int npictures = 0;
    if (pictures && to_folder && nmodels > 0 &&
        (rc = accuracy_pictures(s, models, res, nmodels, &grid, run_dir, quiet, &npictures)) != 0)
        goto cleanup;
    if (pictures && to_folder && nmodels > 0 &&
        (rc = plots_heatmaps_shared_step("accuracy", run_dir, shared_scale)) != 0)
        goto cleanup;
    if (pictures && to_folder && hdone > 0) {
        int hdrawn = 0;
        if ((rc = hemisphere_draw(hres, hdone, run_dir, &hdrawn, err, sizeof err)) != 0) {
            fprintf(stderr, "brdfbench accuracy: %s\n", err);
            goto cleanup;
        }
        npictures += hdrawn;
    }
    if (!quiet && !doc_on_stdout)
        print_summary(&docs, &grid, to_folder ? run_dir : NULL, npictures, json_path, csv_path);
cleanup:
    for (int m = 0; m < hdone; ++m)
        hemisphere_result_free(&hres[m]);
    hemisphere_close(&hctx);
    for (int m = 0; m < done; ++m)
        accuracy_result_free(&res[m]);
    free(res);
    accuracy_close(&actx);
    brdf_run_close(&run);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench accuracy: %s\n", err);
    return EXIT_USAGE;
}
