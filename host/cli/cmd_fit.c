/* cmd_fit.c - `brdfbench fit`: the cosine-quadratic family's accuracy limit per n and its best
 * affine k(n) = a n + b, written as fit.json and usable everywhere as quad:a=...,b=... */
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "fit.h"
#include "outdir.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int cmd_fit(int argc, char **argv)
{
    char err[1024];
    struct fit_options opt;
    fit_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL, *json_path = NULL;
    int quiet = 0;
    const struct cli_flag flags[] = {
        CLI_FLAG_N_MIN(&opt.n_min),
        CLI_FLAG_N_MAX(&opt.n_max),
        CLI_FLAG_N_STEP(&opt.n_step),
        { .name = "--max-abs", .value = "X", .kind = CLI_DOUBLE, .dest = &opt.max_abs_cap, .min = 1e-300, .max = 1.0,
          .help = "cap on the attenuation zone's max Delta", .range = "0 < X <= 1", .def = "none" },
        CLI_FLAG_SAMPLES(&opt.samples, ACC_MAX_SAMPLES),
        CLI_FLAG_OUT(&out_dir, CLI_DEF_OUT "; with --json and no --out, no folder"),
        CLI_FLAG_JSON(&json_path),
        CLI_FLAG_QUIET(&quiet),
        CLI_FLAGS_DEVICE(&dev),
    };
    const struct cli_command cmd = {
        .name = "fit",
        .about = "  For f = (k(n)(c-1) + 1)^2 (zeroed past its root): the per-n k that minimises the epicentre's\n"
                 "  max delta (the family's limit), and the affine k(n) = a n + b that minimises the largest max\n"
                 "  delta over the n range; measured on the device beside fq2, fvol and cq2.\n",
        .flags = flags,
        .nflags = (int)(sizeof flags / sizeof flags[0]),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    if (prc)
        goto usage_error;
    if (fit_options_check(&opt, err, sizeof err))
        goto usage_error;

    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        return rc;
    }
    char run_dir[4096], tmp_dir[512] = "";
    if (json_path && !out_dir) {
        if (cli_temp_dir(tmp_dir, sizeof tmp_dir, err, sizeof err)) {
            fprintf(stderr, "brdfbench fit: %s\n", err);
            clsession_close(&s);
            return EXIT_RUNTIME;
        }
        snprintf(run_dir, sizeof run_dir, "%s", tmp_dir);
    } else if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    /* the summary stays off standard output when the document goes there */
    rc = fit_run(&s, run_dir, &opt, quiet || cli_is_stdout(json_path), NULL);
    if (!rc && !out_dir && !json_path && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench fit: %s\n", err);
        rc = EXIT_RUNTIME;
    }
    if (!rc && json_path) {
        char src[4200];
        path_join(src, sizeof src, run_dir, "fit.json");
        if (cli_deliver(src, "--json", json_path, err, sizeof err)) {
            fprintf(stderr, "brdfbench fit: %s\n", err);
            rc = EXIT_RUNTIME;
        }
    }
    cli_temp_dir_remove(tmp_dir);
    if (!rc && !quiet && !cli_is_stdout(json_path)) {
        if (!tmp_dir[0])
            printf("written: %s/fit.json\n", run_dir);
        if (json_path)
            printf("written: %s\n", json_path);
    }
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench fit: %s\n", err);
    return EXIT_USAGE;
}
