/* cmd_frontier.c - `brdfbench frontier`: flag parsing and orchestration of frontier_run. */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "frontier.h"

#include <stdio.h>
#include <sys/stat.h>
#include <string.h>

int cmd_frontier(int argc, char **argv)
{
    char err[1024];
    struct frontier_options opt;
    frontier_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL, *models_text = NULL, *json_path = NULL;
    int quiet = 0;
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
        CLI_FLAG_OUT(&out_dir, CLI_DEF_OUT "; with --json and no --out, no folder"),
        CLI_FLAG_JSON(&json_path),
        CLI_FLAG_QUIET(&quiet),
        CLI_FLAGS_USERMODEL,
        CLI_FLAGS_DEVICE(&dev),
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
    struct cl_session s;
    char run_dir[4096], tmp_dir[512];
    int rc = cli_run_check_documents("frontier", json_path, NULL);
    if (!rc)
        rc = cli_run_open("frontier", &s, &dev, out_dir, json_path && !out_dir, run_dir, sizeof run_dir, tmp_dir,
                          sizeof tmp_dir);
    if (rc)
        return rc;
    /* the tables stay off standard output when the document goes there */
    quiet = quiet || cli_is_stdout(json_path);
    rc = frontier_run(&s, &opt, run_dir, quiet, NULL);
    if (!rc)
        rc = cli_run_finish("frontier", out_dir, tmp_dir, run_dir, "frontier.json", json_path);
    else
        cli_temp_dir_remove(tmp_dir);
    if (!rc && !quiet && !tmp_dir[0]) {
        char png[4200];
        struct stat st;   /* the plots are drawn only when a model has a rate to plot */
        int plots = path_join(png, sizeof png, run_dir, "frontier_max_rel.png") == 0 && lstat(png, &st) == 0;
        printf("written: %s/frontier.json, frontier.csv%s%s\n", run_dir,
               plots ? ", frontier_max_rel.png, frontier_max_abs.png" : " (no plots: no model has a measured rate)",
               opt.image_w > 0 ? " and frontier_teapot/" : "");
    }
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench frontier: %s\n", err);
    return EXIT_USAGE;
}
