/* cmd_fit.c - `brdfbench fit`: the cosine-quadratic family's accuracy limit per n and its best
 * affine k(n) = a n + b, written as fit.json and usable everywhere as quad:a=...,b=... */
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "fit.h"
#include "outdir.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void fit_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench fit [OPTIONS]\n"
            "  For f = (k(n)(c-1) + 1)^2 (zeroed past its root): the per-n k that minimises the epicentre's\n"
            "  max delta (the family's limit), and the affine k(n) = a n + b that minimises the largest max\n"
            "  delta over the n range; measured on the device beside fq2, fvol and cq2.\n"
            "  --n-min X          smallest shininess (default 2; > 0)\n"
            "  --n-max X          largest shininess (default 1000; <= 1e6)\n"
            "  --n-step X         step of n (default 1; n-max is always included)\n"
            "  --max-abs X        cap on the attenuation zone's max Delta, 0 < X <= 1 (default: none)\n"
            "  --samples N        samples per zone of the device sweeps, a multiple of 16 (default %d)\n"
            "  --out DIR          write fit.json into DIR\n"
            "                     (default: a new folder results/<date-time>/, with results/latest)\n"
            "  --quiet            no summary on stdout\n"
            DEVICE_OPTIONS_HELP,
            ACC_DEFAULT_SAMPLES);
}

int cmd_fit(int argc, char **argv)
{
    char err[1024];
    struct fit_options opt;
    fit_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL;
    int quiet = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = accuracy_grid_flag(argc, argv, &i, &opt.n_min, &opt.n_max, &opt.n_step, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            fit_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_path_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--max-abs")) {
            if (cli_double_value(argc, argv, &i, "--max-abs", 1e-300, 1.0, &opt.max_abs_cap, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--samples")) {
            if (cli_long_value(argc, argv, &i, "--samples", ACC_MIN_SAMPLES, ACC_MAX_SAMPLES, &opt.samples, err,
                               sizeof err))
                goto usage_error;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench fit --help)", a);
            goto usage_error;
        }
    }
    if (fit_options_check(&opt, err, sizeof err))
        goto usage_error;

    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        return rc;
    }
    char run_dir[4096];
    if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    rc = fit_run(&s, run_dir, &opt, quiet, NULL);
    if (!rc && !out_dir && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        rc = EXIT_RUNTIME;
    }
    if (!rc && !quiet)
        printf("written: %s/fit.json\n", run_dir);
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench fit: %s\n", err);
    return EXIT_USAGE;
}
