/* cmd_frontier.c - `brdfbench frontier`: flag parsing and orchestration of frontier_run. */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "frontier.h"
#include "outdir.h"

#include <stdio.h>
#include <sys/stat.h>
#include <string.h>

static int run_frontier(struct cl_session *s, const char *run_dir, int quiet, void *opt)
{
    struct frontier_options *o = opt;
    o->io = (struct engine_io){ run_dir, quiet };
    return frontier_run(s, o, NULL);
}

int cmd_frontier(int argc, char **argv)
{
    char err[1024];
    struct frontier_options opt;
    frontier_options_default(&opt);
    struct cli_engine_run e;
    cli_engine_init(&e, "frontier", "frontier.json", run_frontier, &opt);
    const char *models_text = NULL;
    int models_given = 0, no_image = 0, rounds = opt.rounds, reps = opt.reps;
    const struct cli_flag flags[] = {
        CLI_FLAG_MODELS(&models_text, &models_given,
                        "the references, the papers' models, the engines' approximations and the frozen fits; "
                        "with --model or --model-file, those and the user models"),
        CLI_FLAG_SAMPLES(&opt.samples),
        { .name = "--reps", .value = "N", .kind = CLI_INT, .dest = CLI_DEST(int, &reps), .min = 1, .max = 100,
          .help = "timed launches per figure" },
        { .name = "--rounds", .value = "N", .kind = CLI_INT, .dest = CLI_DEST(int, &rounds), .min = 1,
          .max = FRONTIER_MAX_ROUNDS,
          .help = "rounds over every model; a rate is the median of the rounds' medians, its spread their min..max" },
        { .name = "--no-image", .kind = CLI_SWITCH, .dest = CLI_DEST(int, &no_image), .set = 1,
          .help = "no teapot pass (no PSNR)" },
        CLI_FLAGS_ENGINE(&e),
        CLI_FLAGS_USERMODEL,
    };
    const struct cli_command cmd = {
        .name = "frontier",
        .about = "  Every model's cost (device evaluations/s, n uniform and n varying, and its operation count)\n"
                 "  against its accuracy (max delta, max Delta over n in [2, 1000] and [16, 1000]; teapot PSNR),\n"
                 "  the Pareto front, two scatter plots and which lobe to ship for a budget. Writes\n"
                 "  frontier.json, frontier.csv, frontier_max_rel.png and frontier_max_abs.png.\n",
        CLI_TABLE(flags),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    opt.rounds = rounds;
    opt.reps = reps;
    if (no_image)
        opt.image_w = opt.image_h = 0;
    int n = models_given ? cli_model_list(models_text, opt.models, FRONTIER_MAX_MODELS, err, sizeof err)
                         : cli_frontier_default_models(opt.models, FRONTIER_MAX_MODELS, err, sizeof err);
    if (n < 0)
        goto usage_error;
    opt.model_count = n;
    int rc = cli_run_engine(&e);
    if (!rc && !e.quiet && !e.tmp_dir[0]) {
        char png[4200];
        struct stat st;   /* the plots are drawn only when a model has a rate to plot */
        int plots = path_join(png, sizeof png, e.run_dir, "frontier_max_rel.png") == 0 && lstat(png, &st) == 0;
        printf("written: %s/frontier.json, frontier.csv%s%s\n", e.run_dir,
               plots ? ", frontier_max_rel.png, frontier_max_abs.png" : " (no plots: no model has a measured rate)",
               opt.image_w > 0 ? " and frontier_teapot/" : "");
    }
    return rc;

usage_error:
    fprintf(stderr, "brdfbench frontier: %s\n", err);
    return EXIT_USAGE;
}
