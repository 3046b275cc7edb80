/* cmd_frontier.c - `brdfbench frontier`: flag parsing and orchestration of frontier_run. */
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "frontier.h"
#include "outdir.h"
#include "usermodel.h"

#include <stdio.h>
#include <string.h>

static void frontier_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench frontier [OPTIONS]\n"
            "  Every model's cost (device evaluations/s, n uniform and n varying, and its operation count)\n"
            "  against its accuracy (max delta, max Delta over n in [2, 1000] and [16, 1000]; teapot PSNR),\n"
            "  the Pareto front, two scatter plots and which lobe to ship for a budget.\n"
            "  --models LIST      models to compare (default: references, the papers' models, the engines'\n"
            "                     approximations and the frozen fits; see brdfbench list)\n"
            "  --samples N        accuracy samples per zone, a multiple of 16 in [16, 65536] (default 1024)\n"
            "  --reps N           timed launches per model per round, 1..100 (default 3)\n"
            "  --rounds N         rounds over every model, 1..16 (default 3); a rate is the median of the\n"
            "                     rounds' medians, its spread their min..max\n"
            "  --no-image         no teapot pass (no PSNR)\n"
            "  --out DIR          write frontier.json, frontier.csv, frontier_max_rel.png, frontier_max_abs.png\n"
            "                     (default: a new folder results/<date-time>/, with results/latest)\n"
            "  --quiet            no table on stdout\n"
            "  --model-file FILE  add the user model of FILE.cl (see docs/user-models.md); repeatable\n"
            "  --model NAME=EXPR  add a user model given by an OpenCL C expression of c and n; repeatable\n"
            "                     (without --models: the default set and the user models)\n"
            DEVICE_OPTIONS_HELP);
}

int cmd_frontier(int argc, char **argv)
{
    char err[1024];
    struct frontier_options opt;
    frontier_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL, *models_text = NULL;
    int quiet = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = usermodel_cli_flag(argc, argv, &i, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            frontier_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(a, "--no-image") == 0) {
            opt.image_w = opt.image_h = 0;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_flag_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--models")) {
            if (!(models_text = cli_flag_value(argc, argv, &i, "--models", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--samples")) {
            if (cli_long_value(argc, argv, &i, "--samples", 16, 65536, &opt.samples, err, sizeof err))
                goto usage_error;
            if (opt.samples % 16) {
                snprintf(err, sizeof err, "--samples: %ld is not a multiple of 16 (accepted: 16..65536, multiples of 16)",
                         opt.samples);
                goto usage_error;
            }
        } else if (cli_flag_is(a, "--rounds")) {
            long rounds;
            if (cli_long_value(argc, argv, &i, "--rounds", 1, FRONTIER_MAX_ROUNDS, &rounds, err, sizeof err))
                goto usage_error;
            opt.rounds = (int)rounds;
        } else if (cli_flag_is(a, "--reps")) {
            long reps;
            if (cli_long_value(argc, argv, &i, "--reps", 1, 100, &reps, err, sizeof err))
                goto usage_error;
            opt.reps = (int)reps;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench frontier --help)", a);
            goto usage_error;
        }
    }
    if (models_text) {
        int n = model_spec_list_parse(models_text, opt.models, FRONTIER_MAX_MODELS, err, sizeof err);
        if (n < 0)
            goto usage_error;
        opt.model_count = n;
    } else if (usermodel_count() > 0) {
        /* the default set and the user models */
        opt.model_count = frontier_default_models(opt.models, FRONTIER_MAX_MODELS);
        if (usermodel_append_all(opt.models, &opt.model_count, FRONTIER_MAX_MODELS, err, sizeof err))
            goto usage_error;
    }
    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench frontier: %s\n", err);
        return rc;
    }
    char run_dir[4096];
    if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench frontier: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    rc = frontier_run(&s, &opt, run_dir, quiet, NULL);
    if (!rc && !out_dir && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench frontier: %s\n", err);
        rc = EXIT_RUNTIME;
    }
    if (!rc && !quiet)
        printf("written: %s/frontier.json\n", run_dir);
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench frontier: %s\n", err);
    return EXIT_USAGE;
}
