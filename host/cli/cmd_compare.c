/* cmd_compare.c - `brdfbench compare A B [C ...]`: runs (folders or result files) side by side
 * against the first; the table on stdout, compare.md/.csv/.json/.png, and the CI conditions
 * --fail-if-slower and --fail-if-less-accurate (exit 1). No device is used. */
#define _POSIX_C_SOURCE 200809L
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "compare.h"
#include "compare_report.h"
#include "exitcodes.h"
#include "outdir.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The warnings on stderr: too few repetitions for a verdict, runs disturbed by other work. */
static void print_warnings(const struct compare_set *set)
{
    int few = compare_few_reps(set);
    if (few)
        fprintf(stderr, "brdfbench compare: warning: a rate has only %d repetition%s (fewer than %d): its verdict has "
                        "little power; take more (throughput --reps 10)\n", few, few == 1 ? "" : "s", set->min_reps);
    for (int k = 0; k < set->nruns; ++k)
        if (set->run[k].disturbed)
            fprintf(stderr, "brdfbench compare: warning: %s was disturbed: %d repetition%s stayed preempted by other "
                            "work after the retries (see its \"machine\" context)\n", set->run[k].name,
                    set->run[k].disturbed, set->run[k].disturbed == 1 ? "" : "s");
}

/* What was written into the run folder (the chart only when drawn). */
static void print_written(const char *run_dir)
{
    char png[4200];
    struct stat st;   /* the chart is drawn only when a run has a row to chart */
    int chart = path_join(png, sizeof png, run_dir, "compare.png") == 0 && lstat(png, &st) == 0;
    printf("written: %s/compare.md, compare.csv, compare.json%s\n", run_dir, chart ? ", compare.png" : "");
}

/* --fail-if-slower and --fail-if-less-accurate: the failing rows named on stderr, EXIT_GATE_FAIL;
 * else 0. */
static int report_failures(const struct compare_set *set, double slower_pct, int less_accurate)
{
    int rc = 0;
    char *why = NULL;
    int failing = compare_failures(set, slower_pct, less_accurate, &why);
    if (failing) {
        fprintf(stderr, "brdfbench compare: %d row%s fail%s the %s:\n%s", failing, failing == 1 ? "" : "s",
                failing == 1 ? "s" : "", slower_pct >= 0 && less_accurate ? "conditions" : "condition",
                why ? why : "");
        rc = EXIT_GATE_FAIL;
    }
    free(why);
    return rc;
}

int cmd_compare(int argc, char **argv)
{
    char err[1200];
    int quiet = 0, less_accurate = 0, holm = 0, absolute = 0, confirm = 0;
    const char *out_dir = NULL, *json_path = NULL;
    double alpha = CMP_DEFAULT_ALPHA, slower_pct = -1, threshold_pct = -1;
    const struct cli_flag flags[] = {
        CLI_FLAG_OUT(&out_dir, "a new folder results/<date-time>/; results/latest stays; with --json and no --out, "
                               "no folder"),
        CLI_FLAG_JSON(&json_path),
        { .name = "--alpha", .value = "P", .kind = CLI_DOUBLE, .dest = &alpha, .min = 1e-6, .max = 0.5,
          .help = "the rank test's level", .range = "1e-6 to 0.5" },
        { .name = "--fail-if-slower", .value = "PCT", .kind = CLI_DOUBLE, .dest = &slower_pct, .min = 0, .max = 100,
          .help = "exit 1 naming every rate that is slower than the baseline (by the test) by more than PCT percent",
          .def = "" },
        { .name = "--min-change", .value = "PCT", .kind = CLI_DOUBLE, .dest = &threshold_pct, .min = 0, .max = 100,
          .help = "the smallest change a rate's verdict calls (default: --fail-if-slower's PCT, else 10)", .def = "" },
        { .name = "--holm", .kind = CLI_SWITCH, .dest = &holm, .set = 1,
          .help = "Holm's family-wise correction of the p-values over each run's rates (for CI gates over many rows)" },
        { .name = "--confirm", .kind = CLI_SWITCH, .dest = &confirm, .set = 1,
          .help = "the runs after the first are its confirmations (the same run timed again): a rate fails "
                  "--fail-if-slower only when every run finds it slower" },
        { .name = "--absolute", .kind = CLI_SWITCH, .dest = &absolute, .set = 1,
          .help = "decide on the absolute rates, not the rates normalised by the run's reference kernel" },
        { .name = "--fail-if-less-accurate", .kind = CLI_SWITCH, .dest = &less_accurate, .set = 1,
          .help = "exit 1 naming every accuracy figure worse at its 4th digit" },
        CLI_FLAG_QUIET(&quiet),
    };
    const struct cli_command cmd = {
        .name = "compare",
        .synopsis = "BASELINE RUN [RUN ...] [OPTIONS]",
        .about = "  The results of several runs side by side, the first one the baseline. A run is a run\n"
                 "  folder or one result file of any command: throughput.json, accuracy.json, render.json,\n"
                 "  fit.json, frontier.json. Rows are matched by their keys (throughput: model, build\n"
                 "  options, n mode; accuracy: model, figure, grid; render: scene, model; frontier: model);\n"
                 "  rows found in only some runs are listed as such. One run of --device all alone lays\n"
                 "  its devices side by side. Writes compare.md, compare.csv, compare.json, compare.png.\n"
                 "  Verdicts: a rate is decided on its normalised repetitions (each over the reference kernel\n"
                 "  timed in the same round, so that the machine's drift cancels; --absolute: the raw rates):\n"
                 "  faster / slower when the Mann-Whitney test of the two runs' repetitions gives p < --alpha\n"
                 "  (Holm-adjusted with --holm) and the ratio is beyond 1 +- --min-change; noisy when the\n"
                 "  ratio's confidence interval is too wide to decide a change of that size; same otherwise;\n"
                 "  undecided when there are too few repetitions to reach --alpha. An accuracy figure is\n"
                 "  unchanged or changed (better / worse) at its 4th significant digit.\n"
                 "  Example: brdfbench compare results/base results/latest --fail-if-slower 10 --holm\n",
        CLI_TABLE(flags),
        .epilog = "  Exit codes: 0 done, 1 a --fail-if condition holds, 2 a missing path, a file of another\n"
                  "  schema or version, runs with nothing in common, or a bad flag, 3 an output not written.\n",
        .max_positional = CLI_MAX_POSITIONAL,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    const char **paths = args.positional;
    int npaths = args.npositional;
    if (npaths > CMP_MAX_RUNS) {
        snprintf(err, sizeof err, "at most %d runs (accepted: 1 to %d)", CMP_MAX_RUNS, CMP_MAX_RUNS);
        goto usage_error;
    }
    if (npaths == 0) {
        snprintf(err, sizeof err, "expected BASELINE RUN [RUN ...] (run folders or result files; see --help)");
        goto usage_error;
    }
    struct compare_set *set = calloc(1, sizeof *set);
    if (!set) {
        fprintf(stderr, "brdfbench compare: out of memory\n");
        return EXIT_RUNTIME;
    }
    /* the table stays off standard output when the document goes there */
    quiet = quiet || cli_is_stdout(json_path);
    int rc = cli_run_check_documents("compare", json_path, NULL);
    if (rc)
        goto done;
    rc = compare_load(set, paths, npaths, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench compare: %s\n", err);
        goto done;
    }
    set->threshold = (threshold_pct >= 0 ? threshold_pct : slower_pct >= 0 ? slower_pct : 100 * CMP_DEFAULT_THRESHOLD) / 100;
    set->holm = holm;
    set->absolute = absolute;
    set->confirm = confirm;
    compare_evaluate(set, alpha);
    if (!quiet) {
        char *t = compare_text(set, 0);
        if (t)
            fputs(t, stdout);
        free(t);
    }
    print_warnings(set);
    /* --json - alone: the document straight onto stdout; no folder (and no chart) is made */
    if (json_path && !out_dir && cli_is_stdout(json_path)) {
        if (compare_print_json(set, stdout, "--json -", err, sizeof err)) {
            fprintf(stderr, "brdfbench compare: %s\n", err);
            rc = EXIT_RUNTIME;
            goto done;
        }
        rc = report_failures(set, slower_pct, less_accurate);
        goto done;
    }
    char run_dir[4096], tmp_dir[512];
    if (cli_run_folder("compare", out_dir, json_path && !out_dir, run_dir, sizeof run_dir, tmp_dir, sizeof tmp_dir)) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (compare_write(set, run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench compare: %s\n", err);
        cli_temp_dir_remove(tmp_dir);
        rc = EXIT_RUNTIME;
        goto done;
    }
    /* compare never moves results/latest: out_dir given as the run folder itself */
    if (json_path && cli_run_deliver("compare", run_dir, "compare.json", "--json", json_path))
        rc = EXIT_RUNTIME;
    cli_temp_dir_remove(tmp_dir);
    if (rc)
        goto done;
    if (!quiet && !tmp_dir[0])
        print_written(run_dir);
    rc = report_failures(set, slower_pct, less_accurate);
done:
    compare_free(set);
    free(set);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench compare: %s\n", err);
    return EXIT_USAGE;
}
