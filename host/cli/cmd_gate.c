/* cmd_gate.c - `brdfbench gate GATES.json`: accuracy gates for CI (docs/gates.md). */
#include "cli.h"
#include "clsession.h"
#include "commands.h"
#include "exitcodes.h"
#include "gate.h"
#include "outdir.h"
#include "gate_report.h"
#include "usermodel.h"

#include <stdio.h>
#include <string.h>

static void gate_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench gate GATES.json [OPTIONS]\n"
            "  Runs the accuracy sweeps that the gates of GATES.json need (docs/gates.md) and checks each\n"
            "  gate's figure against its bounds: one line per gate (PASS/FAIL, measured, bound, margin).\n"
            "  Exit 0: every gate passed; 1: a gate failed; 2: bad gates file or option; 3: runtime error;\n"
            "  77: no OpenCL device.\n"
            "  --junit FILE       write JUnit XML, one testcase per gate\n"
            "  --json FILE        write the results as JSON (schema %s)\n"
            "  --baseline PATH    compare with an earlier accuracy.json (a run folder or the file itself): a\n"
            "                     figure above baseline + tolerance x |baseline| + %g fails as a regression\n"
            "  --tolerance REL    relative tolerance of --baseline, in [0, 1] (default %g)\n"
            "  --quiet            no progress lines on stderr\n"
            USERMODEL_OPTIONS_HELP
            DEVICE_OPTIONS_HELP,
            GATE_RESULT_SCHEMA, GATE_BASELINE_FLOOR, GATE_DEFAULT_TOLERANCE);
}

int cmd_gate(int argc, char **argv)
{
    char err[2048];
    struct device_options dev;
    device_options_init(&dev);
    const char *gates_path = NULL, *junit = NULL, *json = NULL, *baseline = NULL;
    double tolerance = GATE_DEFAULT_TOLERANCE;
    int quiet = 0, tolerance_given = 0;

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = usermodel_cli_flag(argc, argv, &i, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            gate_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (cli_flag_is(a, "--junit")) {
            if (!(junit = cli_flag_value(argc, argv, &i, "--junit", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--json")) {
            if (!(json = cli_flag_value(argc, argv, &i, "--json", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--baseline")) {
            if (!(baseline = cli_flag_value(argc, argv, &i, "--baseline", err, sizeof err)))
                goto usage_error;
            if (!*baseline) {
                snprintf(err, sizeof err, "--baseline: empty path (accepted: a run folder or an accuracy.json)");
                goto usage_error;
            }
        } else if (cli_flag_is(a, "--tolerance")) {
            if (cli_double_value(argc, argv, &i, "--tolerance", 0.0, 1.0, &tolerance, err, sizeof err))
                goto usage_error;
            tolerance_given = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench gate --help)", a);
            goto usage_error;
        } else if (gates_path) {
            snprintf(err, sizeof err, "one gates file expected, got '%s' and '%s'", gates_path, a);
            goto usage_error;
        } else {
            gates_path = a;
        }
    }
    if (!gates_path) {
        snprintf(err, sizeof err, "a gates file is missing (usage: brdfbench gate GATES.json [OPTIONS])");
        goto usage_error;
    }
    if (junit && json && output_paths_same(junit, json)) {
        snprintf(err, sizeof err, "--json: '%s' is the file --junit names ('%s'); each report needs its own file",
                 json, junit);
        goto usage_error;
    }
    if (tolerance_given && !baseline) {
        snprintf(err, sizeof err, "--tolerance: only with --baseline");
        goto usage_error;
    }

    struct gate_set gs;
    int rc = gate_set_load(gates_path, &gs, err, sizeof err);
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
    if ((junit && gate_output_check("--junit", junit, err, sizeof err)) ||
        (json && gate_output_check("--json", json, err, sizeof err))) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        gate_set_free(&gs);
        return EXIT_RUNTIME;
    }

    struct cl_session s;
    rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        gate_set_free(&gs);
        return rc;
    }
    if ((rc = gate_set_check_device(&gs, &s, err, sizeof err)) != 0) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        goto done;
    }
    if (!quiet)
        fprintf(stderr, "device: %s (%s)\n", s.device_name, s.platform_version);
    if ((rc = gate_set_run(&gs, &s, quiet ? NULL : stderr)) != 0)
        goto done;
    gate_set_print(stdout, &gs);
    fflush(stdout);
    if ((junit && gate_set_write_junit(&gs, junit, &s, err, sizeof err)) ||
        (json && gate_set_write_json(&gs, json, &s, err, sizeof err))) {
        fprintf(stderr, "brdfbench gate: %s\n", err);
        rc = EXIT_RUNTIME;
        goto done;
    }
    rc = gate_set_failures(&gs) > 0 ? EXIT_GATE_FAIL : EXIT_OK;
done:
    clsession_close(&s);
    gate_set_free(&gs);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench gate: %s\n", err);
    return EXIT_USAGE;
}
