/* cmd_gate.c - `brdfbench gate GATES.json`: accuracy gates for CI (docs/gates.md). */
#define _POSIX_C_SOURCE 200809L
#include "cli_run.h"
#include "cli_table.h"
#include "clsession.h"
#include "commands.h"
#include "exitcodes.h"
#include "gate.h"
#include "outdir.h"
#include "gate_report.h"
#include "usermodel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* With --quiet, only the gates that did not pass (the verdict's errors). */
static void print_gates(FILE *f, const struct gate_set *gs, int quiet)
{
    if (!quiet) {
        gate_set_print(f, gs);
        return;
    }
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (!m) {
        gate_set_print(f, gs);
        return;
    }
    gate_set_print(m, gs);
    fclose(m);
    for (char *line = text; line && *line;) {
        char *nl = strchr(line, '\n');
        size_t n = nl ? (size_t)(nl - line + 1) : strlen(line);
        if (strncmp(line, "PASS  ", 6) != 0 && strncmp(line, "FAIL  ", 6) != 0 && strncmp(line, "----  ", 6) != 0)
            ; /* the summary line */
        else if (strncmp(line, "PASS  ", 6) != 0)
            fwrite(line, 1, n, f);
        line += n;
    }
    free(text);
}

/* The checks of the parsed flags and the gates file named: 0, or -1 with the message in err. */
static int check_args(const struct cli_args *args, const char *baseline, const char *junit, const char *json,
                      int tolerance_given, char *err, size_t errlen)
{
    if (args->npositional > 1) {
        snprintf(err, errlen, "one gates file expected, got '%s' and '%s'", args->positional[0], args->positional[1]);
        return -1;
    }
    if (baseline && !*baseline) {
        snprintf(err, errlen, "--baseline: empty path (accepted: a run folder or an accuracy.json)");
        return -1;
    }
    if (cli_is_stdout(junit) && cli_is_stdout(json)) {
        snprintf(err, errlen, "--junit - and --json -: one document at a time on standard output");
        return -1;
    }
    if (!args->npositional) {
        snprintf(err, errlen, "a gates file is missing (usage: brdfbench gate GATES.json [OPTIONS])");
        return -1;
    }
    if (junit && json && output_paths_same(junit, json)) {
        snprintf(err, errlen, "--json: '%s' is the file --junit names ('%s'); each report needs its own file",
                 json, junit);
        return -1;
    }
    if (tolerance_given && !baseline) {
        snprintf(err, errlen, "--tolerance: only with --baseline");
        return -1;
    }
    return 0;
}

/* --junit and --json, each a file or standard output. 0, or EXIT_RUNTIME with the message on stderr. */
static int write_reports(const struct gate_set *gs, const struct cl_session *s, const char *junit, const char *json)
{
    char err[2048];
    for (int k = 0; k < 2; ++k) {
        const char *path = k == 0 ? junit : json;
        if (!path)
            continue;
        struct cli_output o;
        const char *wp;
        int wrc = cli_output_path(&o, path, k == 0 ? "junit.xml" : "gate.json", &wp, err, sizeof err);
        if (!wrc)
            wrc = k == 0 ? gate_set_write_junit(gs, wp, s, err, sizeof err)
                         : gate_set_write_json(gs, wp, s, err, sizeof err);
        int frc = cli_output_finish(&o, !wrc, err, sizeof err);
        if (wrc || frc) {
            fprintf(stderr, "brdfbench gate: %s\n", err);
            return EXIT_RUNTIME;
        }
    }
    return 0;
}

int cmd_gate(int argc, char **argv)
{
    char err[2048];
    struct device_options dev;
    device_options_init(&dev);
    const char *gates_path = NULL, *junit = NULL, *json = NULL, *baseline = NULL;
    double tolerance = GATE_DEFAULT_TOLERANCE;
    int quiet = 0, tolerance_given = 0, outside_model_files = 0;
    char baseline_help[256];
    snprintf(baseline_help, sizeof baseline_help,
             "compare with an earlier accuracy.json (a run folder or the file itself): a figure above baseline + "
             "tolerance x |baseline| + %g fails as a regression", GATE_BASELINE_FLOOR);

    const struct cli_flag flags[] = {
        { .name = "--junit", .value = "FILE|-", .kind = CLI_PATH, .dest = &junit, .def = "",
          .help = "write JUnit XML, one testcase per gate, to FILE ('-': standard output)" },
        CLI_FLAG_JSON(&json),
        { .name = "--baseline", .value = "PATH", .kind = CLI_TEXT, .dest = &baseline, .def = "",
          .help = baseline_help },
        { .name = "--tolerance", .value = "REL", .kind = CLI_DOUBLE, .dest = &tolerance, .min = 0.0, .max = 1.0,
          .given = &tolerance_given, .help = "relative tolerance of --baseline" },
        CLI_FLAG_QUIET(&quiet),
        { .name = "--allow-outside-model-files", .kind = CLI_SWITCH, .dest = &outside_model_files, .set = 1,
          .help = "let the gates file name model files and measured materials outside its own folder (a model "
                  "file is a program run on the host: only for gates files you trust)" },
        CLI_FLAGS_USERMODEL,
        CLI_FLAGS_DEVICE(&dev),
    };
    const struct cli_command cmd = {
        .name = "gate",
        .synopsis = "GATES.json [OPTIONS]",
        .about = "  Runs the accuracy sweeps that the gates of GATES.json need (docs/gates.md) and checks each\n"
                 "  gate's figure against its bounds: one line per gate (PASS/FAIL, measured, bound, margin);\n"
                 "  with --quiet only the gates that did not pass. --json writes schema " GATE_RESULT_SCHEMA ".\n"
                 "  Exit 0: every gate passed; 1: a gate failed; 2: bad gates file or option; 3: runtime error;\n"
                 "  77: no OpenCL device.\n",
        CLI_TABLE(flags),
        .max_positional = 2,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    gates_path = args.npositional ? args.positional[0] : NULL;
    if (check_args(&args, baseline, junit, json, tolerance_given, err, sizeof err))
        goto usage_error;

    struct gate_set gs;
    int rc = gate_set_load(gates_path, outside_model_files, &gs, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        return rc;
    }
    if (baseline && (rc = gate_set_baseline(&gs, baseline, tolerance, err, sizeof err)) != 0) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        gate_set_free(&gs);
        return rc;
    }
    /* The outputs can be written: found out before any sweep runs. */
    if ((junit && !cli_is_stdout(junit) && output_file_check("--junit", junit, err, sizeof err)) ||
        (json && !cli_is_stdout(json) && output_file_check("--json", json, err, sizeof err))) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        gate_set_free(&gs);
        return EXIT_RUNTIME;
    }

    struct brdf_run run;
    struct cl_session *s = &run.s;
    rc = cli_run_session("gate", &run, &dev);
    if (rc) {
        gate_set_free(&gs);
        return rc;
    }
    if ((rc = gate_set_check_device(&gs, s, err, sizeof err)) != 0) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        goto done;
    }
    if (!quiet)
        fprintf(stderr, "device: %s (%s)\n", s->device_name, s->platform_version);
    if ((rc = gate_set_run(&gs, s, quiet ? NULL : stderr)) != 0)
        goto done;
    /* a document on standard output: the gate lines go to stderr */
    print_gates(cli_is_stdout(junit) || cli_is_stdout(json) ? stderr : stdout, &gs, quiet);
    fflush(stdout);
    if ((rc = write_reports(&gs, s, junit, json)) != 0)
        goto done;
    rc = gate_set_failures(&gs) > 0 ? EXIT_GATE_FAIL : EXIT_OK;
done:
    brdf_run_close(&run);
    gate_set_free(&gs);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench gate: %s\n", err);
    return EXIT_USAGE;
}
