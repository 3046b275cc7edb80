/* cmd_reproduce.c - `brdfbench reproduce`: every claim of both papers re-derived and given a
 * verdict; claims.json, claims.md, q_sweep.json, energy.json and the table on stdout. */
#include "accuracy.h"
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "reproduce.h"

#include <stdio.h>
#include <string.h>

static int run_reproduce(struct cl_session *s, const char *run_dir, int quiet, void *opt)
{
    struct reproduce_options *o = opt;
    o->io = (struct engine_io){ run_dir, quiet };
    return reproduce_run(s, o, NULL);
}

int cmd_reproduce(int argc, char **argv)
{
    char err[1024];
    struct reproduce_options opt;
    reproduce_options_default(&opt);
    struct cli_engine_run e;
    cli_engine_init(&e, "reproduce", "claims.json", run_reproduce, &opt);
    const struct cli_flag flags[] = {
        CLI_FLAGS_ENGINE(&e),
        CLI_FLAG_SAMPLES_WHY(&opt.samples, ACC_MAX_SAMPLES / 2,
                             "a multiple of 16 in [16, 2097152]: half the 4194304 of other commands, since the "
                             "grid check reruns each claim sweep at twice N"),
        { .name = "--no-grid-check", .kind = CLI_SWITCH, .dest = &opt.grid_check, .set = 0,
          .help = "skip re-running each claim sweep at twice the samples" },
        { .name = "--q-step", .value = "X", .kind = CLI_DOUBLE, .dest = &opt.q_step, .min = 1e-4, .max = 0.5,
          .help = "step of the Q sweep over (0, 1)" },
        { .name = "--q-samples", .value = "N", .kind = CLI_LONG, .dest = &opt.q_samples, .min = ACC_MIN_SAMPLES,
          .max = ACC_MAX_SAMPLES, .multiple = 16, .help = "samples per zone and per n of the Q sweep" },
        { .name = "--q-n-step", .value = "X", .kind = CLI_DOUBLE, .dest = &opt.q_n_step, .min = 0.01, .max = 499,
          .help = "n step of the Q sweep" },
        { .name = "--no-energy", .kind = CLI_SWITCH, .dest = &opt.energy, .set = 0,
          .help = "skip the albedo and reciprocity checks" },
    };
    const struct cli_command cmd = {
        .name = "reproduce",
        .about = "  Re-derives the claims of both papers and gives each a verdict: eq. 11-12 by host (GSL)\n"
                 "  and device quadrature, the max delta / max Delta figures by the device sweep, the Q sweep of\n"
                 "  paper 2's figs. 2-3, coef(n) and its fits, energy and reciprocity. Writes claims.json,\n"
                 "  claims.md, q_sweep.json and energy.json.\n",
        CLI_TABLE(flags),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    /* The Q grid keeps clear of 0 and 1, where f_Q is not defined. */
    opt.q_min = opt.q_step;
    opt.q_max = 1.0 - opt.q_step * 0.5;
    if (opt.q_max >= 1.0 - 1e-9)
        opt.q_max = 1.0 - 1e-6;
    if (reproduce_options_check(&opt, err, sizeof err))
        goto usage_error;

    int rc = cli_run_engine(&e);
    if (!rc && !e.quiet && !e.tmp_dir[0])
        printf("written: %s/claims.json, claims.md, q_sweep.json%s\n", e.run_dir, opt.energy ? ", energy.json" : "");
    return rc;

usage_error:
    fprintf(stderr, "brdfbench reproduce: %s\n", err);
    return EXIT_USAGE;
}
