/* cmd_report.c - `brdfbench report RUN_DIR`: rebuilds report.md of a run of `brdfbench all`
 * from the run folder alone (run.json and the result files beside it), the same page `all`
 * wrote. No device is used and nothing is recomputed. */
#define _DEFAULT_SOURCE
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "report.h"

#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* --output inside the run folder may only be its report.md: the page never replaces a result
 * file it is made from. Returns 0, or -1 with a message. */
static int output_inside_run(const char *out, const char *dir, char *err, size_t errlen)
{
    char own[4200], run[PATH_MAX], parent[PATH_MAX], copy[4200];
    if (strcmp(out, "-") == 0 || path_join(own, sizeof own, dir, "report.md") || output_paths_same(out, own)) return 0;
    snprintf(copy, sizeof copy, "%s", out);
    if (!realpath(dir, run) || !realpath(dirname(copy), parent)) return 0; /* output_file_check judged it */
    size_t n = strlen(run);
    if (strncmp(parent, run, n) != 0 || (parent[n] != '\0' && parent[n] != '/')) return 0;
    snprintf(err, errlen, "--output: '%s' is inside RUN_DIR '%s' (accepted: RUN_DIR/report.md, a file outside the run "
                          "folder, or -)", out, dir);
    return -1;
}

int cmd_report(int argc, char **argv)
{
    const char *out = NULL;
    char err[1024];
    const struct cli_flag flags[] = {
        CLI_FLAG_OUTPUT(&out, "RUN_DIR/report.md"),
    };
    const struct cli_command cmd = {
        .name = "report",
        .synopsis = "[RUN_DIR] [--output FILE|-]",
        .about = "  Rebuilds report.md of a run folder of `brdfbench all` (default: results/latest) from its\n"
                 "  files alone: run.json (the command, the steps, the pictures and their captions) and the\n"
                 "  result files beside it. The page is the one `all` wrote; no device is used.\n",
        CLI_TABLE(flags),
        .max_positional = 1,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc) return cli_parse_exit(&cmd, prc, err);
    const char *dir = args.npositional ? args.positional[0] : "results/latest";
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "brdfbench report: RUN_DIR '%s' is not a folder (accepted: a run folder of brdfbench all)\n",
                dir);
        return EXIT_USAGE;
    }
    if (out && (output_file_check("--output", out, err, sizeof err) || output_inside_run(out, dir, err, sizeof err))) {
        fprintf(stderr, "brdfbench report: %s\n", err);
        return EXIT_USAGE;
    }
    /* the run folder is input: report.md written into it never follows a link out of it */
    if (!out) outdir_confine(dir);
    int rc = report_rebuild(dir, out, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench report: %s\n", err);
        return rc == 2 ? EXIT_USAGE : EXIT_RUNTIME;
    }
    return EXIT_OK;
}
