/* cmd_reproduce.c - `brdfbench reproduce`: every claim of both papers re-derived and given a
 * verdict; claims.json, claims.md, q_sweep.json, energy.json and the table on stdout. */
#include "accuracy.h"
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "reproduce.h"

#include <stdio.h>
#include <string.h>

static void reproduce_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench reproduce [OPTIONS]\n"
            "  Re-derives the claims of both papers (SPEC.md) and gives each a verdict: eq. 11-12 by host (GSL)\n"
            "  and device quadrature, the max delta / max Delta figures by the device sweep, the Q sweep of\n"
            "  paper 2's figs. 2-3, coef(n) and its fits, energy and reciprocity.\n"
            "  --out DIR          write claims.json, claims.md, q_sweep.json, energy.json into DIR\n"
            "                     (default: a new folder results/<date-time>/, with results/latest)\n"
            "  --samples N        samples per zone of the claim sweeps, a multiple of 16 (default %d)\n"
            "  --no-grid-check    skip re-running each claim sweep at twice the samples\n"
            "  --q-step X         step of the Q sweep over (0, 1) (default 0.01; 0 < X < 1)\n"
            "  --q-samples N      samples per zone of the Q sweep, a multiple of 16 (default 1024)\n"
            "  --q-n-step X       n step of the Q sweep (default 1)\n"
            "  --no-energy        skip the albedo and reciprocity checks\n"
            "  --quiet            no table on stdout\n"
            DEVICE_OPTIONS_HELP,
            ACC_DEFAULT_SAMPLES);
}

int cmd_reproduce(int argc, char **argv)
{
    char err[1024];
    struct reproduce_options opt;
    reproduce_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL;
    int quiet = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            reproduce_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(a, "--no-grid-check") == 0) {
            opt.grid_check = 0;
        } else if (strcmp(a, "--no-energy") == 0) {
            opt.energy = 0;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_path_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--samples")) {
            if (cli_long_multiple_value(argc, argv, &i, "--samples", ACC_MIN_SAMPLES, ACC_MAX_SAMPLES / 2, 16,
                                        &opt.samples, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--q-step")) {
            if (cli_double_value(argc, argv, &i, "--q-step", 1e-4, 0.5, &opt.q_step, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--q-samples")) {
            if (cli_long_multiple_value(argc, argv, &i, "--q-samples", ACC_MIN_SAMPLES, ACC_MAX_SAMPLES, 16,
                                        &opt.q_samples, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--q-n-step")) {
            if (cli_double_value(argc, argv, &i, "--q-n-step", 0.01, 499, &opt.q_n_step, err, sizeof err))
                goto usage_error;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench reproduce --help)", a);
            goto usage_error;
        }
    }
    /* The Q grid keeps clear of 0 and 1, where f_Q is not defined. */
    opt.q_min = opt.q_step;
    opt.q_max = 1.0 - opt.q_step * 0.5;
    if (opt.q_max >= 1.0 - 1e-9)
        opt.q_max = 1.0 - 1e-6;
    if (reproduce_options_check(&opt, err, sizeof err))
        goto usage_error;

    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        return rc;
    }
    char run_dir[4096];
    if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    rc = reproduce_run_ex(&s, run_dir, &opt, quiet, NULL);
    if (!rc && !out_dir && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench reproduce: %s\n", err);
        rc = EXIT_RUNTIME;
    }
    if (!rc && !quiet)
        printf("written: %s/claims.json, claims.md, q_sweep.json%s\n", run_dir, opt.energy ? ", energy.json" : "");
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench reproduce: %s\n", err);
    return EXIT_USAGE;
}
