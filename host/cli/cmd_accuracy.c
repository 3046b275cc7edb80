/* cmd_accuracy.c - `brdfbench accuracy`: the dense-grid sweep of models on the device,
 * written as accuracy.json, accuracy.csv and a table. */
#include "accuracy.h"
#include "accuracy_report.h"
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_MODELS 64

static void accuracy_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench accuracy [OPTIONS]\n"
            "  Sweeps every model over (angle, n): max relative error in the epicentre zone, max absolute\n"
            "  error in the attenuation zone and over the whole range, each with where it occurs.\n"
            "  --models LIST      comma-separated models with parameters, e.g. cq2,fq:Q=0.7,lyon:k=4\n"
            "                     (default: all; see brdfbench list)\n"
            "  --n-min X          smallest shininess (default 2; >= 0.1)\n"
            "  --n-max X          largest shininess (default 1000; <= 1e6)\n"
            "  --n-step X         step of n (default 1; real values allowed; n-max is always included)\n"
            "  --samples N        samples per zone per n, a multiple of 16 in [16, %ld] (default %d)\n"
            "  --out DIR          write accuracy.json and accuracy.csv into DIR\n"
            "                     (default: a new folder results/<date-time>/, with results/latest)\n"
            "  --quiet            no table on stdout\n"
            USERMODEL_OPTIONS_HELP
            "                     (with a user model and no --models, only the user models run)\n"
            DEVICE_OPTIONS_HELP
            DEVICE_LIST_HELP,
            ACC_MAX_SAMPLES, ACC_DEFAULT_SAMPLES);
}

int cmd_accuracy(int argc, char **argv)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "accuracy", cmd_accuracy, "accuracy.json", "results");
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct accuracy_grid grid = { 2.0, 1000.0, 1.0, ACC_DEFAULT_SAMPLES };
    struct device_options dev;
    device_options_init(&dev);
    const char *models_text = "all", *out_dir = NULL;
    int quiet = 0, models_given = 0;
    struct model_spec models[MAX_MODELS];

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = accuracy_grid_flag(argc, argv, &i, &grid.n_min, &grid.n_max, &grid.n_step, err, sizeof err);
        if (d == 0)
            d = usermodel_cli_flag(argc, argv, &i, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            accuracy_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (cli_flag_is(a, "--models")) {
            if (!(models_text = cli_flag_value(argc, argv, &i, "--models", err, sizeof err)))
                goto usage_error;
            models_given = 1;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_path_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--samples")) {
            if (cli_long_multiple_value(argc, argv, &i, "--samples", ACC_MIN_SAMPLES, ACC_MAX_SAMPLES, 16,
                                        &grid.samples, err, sizeof err))
                goto usage_error;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench accuracy --help)", a);
            goto usage_error;
        }
    }
    if (!models_given && usermodel_count() > 0)
        models_text = usermodel_names();
    int nmodels = model_spec_list_parse(models_text, models, MAX_MODELS, err, sizeof err);
    if (nmodels < 0)
        goto usage_error;
    if (accuracy_grid_check(&grid, NULL, err, sizeof err))
        goto usage_error;

    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        return rc;
    }
    if (accuracy_grid_check(&grid, &s, err, sizeof err)) {
        clsession_close(&s);
        goto usage_error;
    }
    struct accuracy_ctx actx;
    struct accuracy_result *res = calloc((size_t)nmodels, sizeof *res);
    int done = 0;
    if (!res) {
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    rc = accuracy_open(&actx, &s, "");
    if (rc)
        goto cleanup;
    for (int m = 0; m < nmodels && !rc; ++m)
        rc = accuracy_prepare(&actx, &models[m]);   /* a user model's compile error before any sweep */
    if (rc)
        goto cleanup;
    /* Check the output folder before the sweep, so a bad --out fails fast (and after the
       builds, so a user model that does not compile leaves no folder behind). */
    char run_dir[4096];
    if (out_dir) {
        if (outdir_prepare(out_dir, "--out", err, sizeof err)) {
            fprintf(stderr, "brdfbench accuracy: %s\n", err);
            rc = EXIT_RUNTIME;
            goto cleanup;
        }
        snprintf(run_dir, sizeof run_dir, "%s", out_dir);
    } else if (outdir_prepare("results", NULL, err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    if (!quiet)
        fprintf(stderr, "device: %s (%s); kernel build %.2f s\n", s.device_name, s.platform_version,
                s.last_build_seconds);
    double started = wall_seconds();
    for (int m = 0; m < nmodels; ++m, ++done) {
        rc = accuracy_run(&actx, &models[m], &grid, &res[m]);
        if (rc)
            goto cleanup;
        if (!quiet && wall_seconds() - started > 1.0)   /* a progress line once a run takes a while */
            fprintf(stderr, "accuracy: %d/%d %s done (%.1f s)\n", m + 1, nmodels, models[m].label,
                    wall_seconds() - started);
    }
    if (!out_dir && outdir_new_run("results", run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    char path[4200];
    path_join(path, sizeof path, run_dir, "accuracy.json");
    int wrc = accuracy_write_json(path, res, nmodels, &s, actx.build_options, err, sizeof err);
    if (!wrc) {
        path_join(path, sizeof path, run_dir, "accuracy.csv");
        wrc = accuracy_write_csv(path, res, nmodels, err, sizeof err);
    }
    if (!wrc && !out_dir)
        wrc = outdir_set_latest("results", run_dir, err, sizeof err);
    if (wrc) {
        fprintf(stderr, "brdfbench accuracy: %s\n", err);
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    if (!quiet) {
        accuracy_print_table(stdout, res, nmodels);
        double worst = 0, dev_s = 0, pts = 0;
        int beyond = 0;
        for (int m = 0; m < nmodels; ++m) {
            worst = fmax(worst, accuracy_check_in_digits(&res[m]));
            beyond += res[m].device_disagrees;
            dev_s += res[m].device_seconds;
            pts += res[m].points;
        }
        printf("\ndevice vs double reference: every per-n figure recomputed in double at the device's inputs;\n"
               "largest difference = %.3g of one unit in the 4th significant digit of its figure (bound %g; "
               "%d models beyond it)\n", worst, ACC_CHECK_BOUND_UNITS, beyond);
        printf("device time %.3f s for %.3g points (%.3g G points/s; grid: n in [%g, %g] step %g, %ld samples per zone)\n",
               dev_s, pts, pts / dev_s * 1e-9, grid.n_min, grid.n_max, grid.n_step, grid.samples);
        printf("written: %s/accuracy.json, %s/accuracy.csv\n", run_dir, run_dir);
    }
cleanup:
    for (int m = 0; m < done; ++m)
        accuracy_result_free(&res[m]);
    free(res);
    accuracy_close(&actx);
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench accuracy: %s\n", err);
    return EXIT_USAGE;
}
