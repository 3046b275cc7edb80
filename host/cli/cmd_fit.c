/* cmd_fit.c - `brdfbench fit`: the cosine-quadratic family's accuracy limit per n and its best
 * affine k(n) = a n + b, written as fit.json and usable everywhere as quad:a=...,b=... */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "fit.h"
#include "outdir.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int fit_call_objective(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    int *objective = dest;
    if (strcmp(value, "max_rel") == 0)
        *objective = FIT_MAX_REL;
    else if (strcmp(value, "max_abs") == 0)
        *objective = FIT_MAX_ABS;
    else {
        snprintf(err, errlen, "%s: '%s' is not an objective (accepted: max_rel, max_abs)", flag, value);
        return EXIT_USAGE;
    }
    return 0;
}

static int run_fit(struct cl_session *s, const char *run_dir, int quiet, void *opt)
{
    struct fit_options *o = opt;
    o->io = (struct engine_io){ run_dir, quiet };
    return fit_wants_family(o) ? fit_family_run(s, o, NULL) : fit_run(s, o, NULL);
}

int cmd_fit(int argc, char **argv)
{
    char err[1024];
    struct fit_options opt;
    fit_options_default(&opt);
    struct cli_engine_run e;
    cli_engine_init(&e, "fit", "fit.json", run_fit, &opt);
    e.complete_on = EXIT_GATE_FAIL;   /* no member meets the cap: fit.json says why */
    const struct cli_flag flags[] = {
        CLI_FLAG_N_MIN(&opt.n_min),
        CLI_FLAG_N_MAX(&opt.n_max),
        CLI_FLAG_N_STEP(&opt.n_step),
        { .name = "--max-abs", .value = "X", .kind = CLI_DOUBLE, .dest = &opt.max_abs_cap, .min = FIT_CAP_MIN,
          .max = 1.0, .help = "cap on the attenuation zone's max Delta", .def = "none" },
        { .name = "--family", .value = "ID", .kind = CLI_TEXT, .dest = CLI_DEST(const char *, &opt.model), .def = "",
          .help = "fit another family instead: a registry or user model with one or two continuous parameters "
                  "(gauss, pow3, pow4, fq, quad, or a user model of --model-file with param: lines, e.g. "
                  "--model-file my.cl --family my)" },
        { .name = "--power", .value = "M", .kind = CLI_INT, .dest = CLI_DEST(int, &opt.power_m), .min = 1,
          .max = FIT_POWER_M_MAX, .def = "", .help = "fit the power family ((a n + b)(c-1) + 1)^M" },
        { .name = "--objective", .value = "WHAT", .kind = CLI_CALL, .dest = &opt.objective,
          .call = fit_call_objective, .range = "max_rel or max_abs", .def = "max_rel",
          .help = "what a family fit minimises: the epicentre's max delta or the attenuation's max Delta" },
        { .name = "--max-rel", .value = "X", .kind = CLI_DOUBLE, .dest = &opt.max_rel_cap, .min = FIT_CAP_MIN,
          .max = 1.0, .def = "none", .help = "with --objective max_abs: cap on the epicentre's max delta" },
        CLI_FLAG_SAMPLES(&opt.samples),
        CLI_FLAGS_ENGINE(&e),
        CLI_FLAGS_USERMODEL,
    };
    const struct cli_command cmd = {
        .name = "fit",
        .about = "  For f = (k(n)(c-1) + 1)^2 (zeroed past its root): the per-n k that minimises the epicentre's\n"
                 "  max delta (the family's limit), and the affine k(n) = a n + b that minimises the largest max\n"
                 "  delta over the n range; measured on the device beside fq2, fvol and cq2.\n"
                 "  With --family or --power, the minimax fit of that family's one or two continuous\n"
                 "  parameters, and the trade-off between the two figures.\n",
        .epilog = "  Exit codes: 0 done, 1 no member of the family meets the cap (fit.json says why),\n"
                  "  2 bad input, 3 a runtime error.\n",
        CLI_TABLE(flags),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (fit_options_check(&opt, err, sizeof err))
        goto usage_error;

    int rc = cli_run_engine(&e);
    if ((!rc || rc == EXIT_GATE_FAIL) && !e.quiet) {
        if (!e.tmp_dir[0])
            printf("written: %s/fit.json\n", e.run_dir);
        if (e.json_path)
            printf("written: %s\n", e.json_path);
    }
    return rc;

usage_error:
    fprintf(stderr, "brdfbench fit: %s\n", err);
    return EXIT_USAGE;
}
