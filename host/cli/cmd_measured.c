/* cmd_measured.c - `brdfbench measured FILE|DIR ...`: measured materials (MERL .binary files, a
 * folder's .binary files) fitted by Blinn-Phong and Cook-Torrance, and every cheap lobe measured
 * against them and against the fitted Blinn-Phong (host/measure/measured/measured.h). */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "measured.h"
#include "measured_report.h"
#include "merl.h"
#include "outdir.h"

#include <stdio.h>
#include <string.h>

/* The measurement and its files: measured.json and the slices' pictures in the run folder. */
struct measured_job {
    struct measured_options *opt;
    char **files;
    int nfiles;
    struct measured_report rep;
};

static int run_measured(struct cl_session *s, const char *run_dir, int quiet, void *ctx)
{
    struct measured_job *job = ctx;
    job->opt->io = (struct engine_io){ run_dir, quiet };
    job->opt->paths = job->files;
    job->opt->count = job->nfiles;
    int rc = measured_run(s, job->opt, &job->rep);
    if (rc && job->rep.err[0])
        fprintf(stderr, "brdfbench measured: %s\n", job->rep.err);
    return rc;
}

int cmd_measured(int argc, char **argv)
{
    char err[4600];
    struct measured_options opt;
    measured_options_default(&opt);
    struct measured_job job = { .opt = &opt };
    struct cli_engine_run e;
    cli_engine_init(&e, "measured", "measured.json", run_measured, &job);
    const char *models = NULL;
    int models_given = 0;
    const struct cli_flag flags[] = {
        { .name = "--fit-cells", .value = "N", .kind = CLI_LONG, .dest = CLI_DEST(long, &opt.fit_cells),
          .min = MEASURED_MIN_FIT_CELLS, .max = MEASURED_MAX_FIT_CELLS,
          .help = "at most N cells in each fit (an even stride through the used cells); errors are always over "
                  "every used cell" },
        CLI_FLAG_MODELS(&models, &models_given,
                        "every cheap lobe: the registry's approximations of cos^n, without the two-parameter families"),
        CLI_FLAGS_ENGINE(&e),
        CLI_FLAGS_USERMODEL,
    };
    const struct cli_command cmd = {
        .name = "measured",
        .synopsis = "FILE|DIR ... [OPTIONS]",
        .about = "  Measured materials (MERL .binary files, Matusik et al. 2003; a folder: its .binary files):\n"
                 "  Blinn-Phong ks cos(theta_h)^n + kd and Cook-Torrance (Beckmann, GGX: alpha, F0, ks, kd) fitted\n"
                 "  by least squares on luminance in ln(1 + cos(theta_i) f), then every cheap lobe at the fitted n,\n"
                 "  scaled the same way, against the material and against the fitted Blinn-Phong.\n"
                 "  Writes measured.json, measured_errors_<name>.png and measured_slice_<name>.png.\n",
        .epilog = "  Exit codes: 0 done, 2 bad input (a malformed file is named with what is wrong), 3 a runtime "
                  "error.\n",
        .max_positional = CLI_MAX_POSITIONAL,
        CLI_TABLE(flags),
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (args.npositional == 0) {
        snprintf(err, sizeof err, "expected a MERL .binary file or a folder of them (brdfbench measured FILE|DIR ...)");
        return cli_parse_exit(&cmd, EXIT_USAGE, err);
    }
    if (models_given) {
        int n = cli_model_list(models, opt.lobes, MEASURED_MAX_LOBES, err, sizeof err);
        if (n < 0)
            return cli_parse_exit(&cmd, EXIT_USAGE, err);
        opt.nlobes = n;
    }
    char **files = NULL;
    int nfiles = 0;
    for (int i = 0; i < args.npositional; ++i)
        if (measured_collect(args.positional[i], &files, &nfiles, err, sizeof err)) {
            measured_paths_free(files, nfiles);
            return cli_parse_exit(&cmd, EXIT_USAGE, err);
        }

    job.files = files;
    job.nfiles = nfiles;
    int rc = cli_run_engine(&e);
    if (rc)
        outdir_remove_own_empty();
    if (!rc && !e.quiet) {
        measured_print(stdout, &job.rep);
        if (!e.tmp_dir[0])
            printf("written: %s/measured.json\n", e.run_dir);
        if (e.json_path)
            printf("written: %s\n", e.json_path);
    }
    measured_report_free(&job.rep);
    measured_paths_free(files, nfiles);
    return rc;
}
