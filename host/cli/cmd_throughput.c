/* cmd_throughput.c - `brdfbench throughput`: every model's evaluations per second on the
 * device, against the pow() built-in, tuned C and the device's peak, under three sets of build
 * options; written as throughput.json, throughput.csv and a table. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "pbcost.h"
#include "throughput.h"
#include "usermodel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void throughput_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench throughput [OPTIONS]\n"
            "  Evaluations per second of every model on the OpenCL device, with inputs made in registers\n"
            "  and outputs summed, beside the pow() built-in, a tuned C loop doing the same work\n"
            "  (-O3 -march=native, one thread per CPU) and the device's measured FMA peak; under the\n"
            "  build options default, -cl-fast-relaxed-math and -cl-denorms-are-zero, each with what it\n"
            "  does to accuracy against the double reference.\n"
            "  --models LIST        comma-separated models with parameters (default: all; see brdfbench list)\n"
            "  --reps N             timed launches per figure, 1 to %d (default 5)\n"
            "  --min-time S         seconds one timed launch lasts at least, %g to %g (default 0.02)\n"
            "  --variants LIST      build options to measure: default,fast-relaxed-math,denorms-are-zero\n"
            "                       (default: all three)\n"
            "  --n-modes LIST       uniform (one n per launch), varying (one n per evaluation) (default: both)\n"
            "  --variant-n-modes LIST  n modes for the non-default variants (default: uniform)\n"
            "  --n X                the uniform n (default 100; 0 < n <= %g)\n"
            "  --n-range LO:HI      the range of the varying n (default 2:1000)\n"
            "  --work-items N       device work-items per launch, 1 to %d (default: 32 per compute unit)\n"
            "  --threads N          threads of the C baseline, 1 to 256 (default: the online CPUs)\n"
            "  --no-host-c          skip the C baseline\n"
            "  --sweep              also time the accuracy sweep (kernels/accuracy.cl) against the same\n"
            "                       sweep in tuned C with powf (on by default; --no-sweep skips it)\n"
            "  --sweep-samples N    samples per zone of that sweep (default %d; a multiple of 16)\n"
            "  --sweep-n-step X     its step of n over [2, 1000] (default 1)\n"
            "  --sweep-reps N       its timed runs per model, 1 to %d (default 3)\n"
            "  --out DIR            write throughput.json and throughput.csv into DIR (and, without\n"
            "                       --models, physical.json: the physically based models' cost)\n"
            "                       (default: a new folder results/<date-time>/, with results/latest)\n"
            "  --quiet              no table on stdout, no progress on stderr\n"
            USERMODEL_OPTIONS_HELP
            DEVICE_OPTIONS_HELP
            DEVICE_LIST_HELP
            "  POCL_AFFINITY=1 is set unless the environment sets it: it pins PoCL's threads to CPUs,\n"
            "  so that a run does not land on one thread.\n",
            TP_MAX_REPS, TP_MIN_TIME_MIN, TP_MIN_TIME_MAX, ACC_MAX_N, TP_MAX_WORK_ITEMS, ACC_DEFAULT_SAMPLES,
            TP_MAX_REPS);
}

/* A comma-separated list of names into a bit set; names[i] sets bit i. */
static int parse_name_set(const char *arg, const char *text, const char *(*name_of)(int), int count, unsigned *out,
                          char *err, size_t errlen)
{
    char buf[256];
    if (strlen(text) >= sizeof buf || !*text) {
        snprintf(err, errlen, "%s: expected a comma-separated list", arg);
        return EXIT_USAGE;
    }
    strcpy(buf, text);
    unsigned set = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int found = -1;
        for (int i = 0; i < count; ++i)
            if (strcmp(tok, name_of(i)) == 0)
                found = i;
        if (found < 0) {
            char accepted[256] = "";
            for (int i = 0; i < count; ++i)
                snprintf(accepted + strlen(accepted), sizeof accepted - strlen(accepted), "%s%s", i ? ", " : "",
                         name_of(i));
            snprintf(err, errlen, "%s: unknown '%s' (accepted: %s)", arg, tok, accepted);
            return EXIT_USAGE;
        }
        set |= 1u << found;
    }
    if (!set) {
        snprintf(err, errlen, "%s: expected a comma-separated list", arg);
        return EXIT_USAGE;
    }
    *out = set;
    return 0;
}

int cmd_throughput(int argc, char **argv)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "throughput", cmd_throughput, "throughput.json", "results");
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct throughput_options o;
    throughput_options_default(&o);
    struct device_options dev;
    device_options_init(&dev);
    const char *models_text = "all", *out_dir = NULL;
    int quiet = 0, models_given = 0;
    long lv;

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = NULL;
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = usermodel_cli_flag(argc, argv, &i, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            throughput_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(a, "--no-host-c") == 0) {
            o.host_c = 0;
        } else if (strcmp(a, "--sweep") == 0) {
            o.sweep = 1;
        } else if (strcmp(a, "--no-sweep") == 0) {
            o.sweep = 0;
        } else if (cli_flag_is(a, "--models")) {
            if (!(models_text = cli_flag_value(argc, argv, &i, "--models", err, sizeof err)))
                goto usage_error;
            models_given = 1;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_path_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--reps")) {
            if (cli_long_value(argc, argv, &i, "--reps", 1, TP_MAX_REPS, &lv, err, sizeof err))
                goto usage_error;
            o.reps = (int)lv;
        } else if (cli_flag_is(a, "--min-time")) {
            if (cli_double_value(argc, argv, &i, "--min-time", TP_MIN_TIME_MIN, TP_MIN_TIME_MAX, &o.min_time, err,
                                 sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--variants")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--variants", err, sizeof err)) ||
                parse_name_set("--variants", v, tp_variant_name, TP_VARIANT_COUNT, &o.variants, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--n-modes")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--n-modes", err, sizeof err)) ||
                parse_name_set("--n-modes", v, tp_nmode_name, TP_NMODE_COUNT, &o.n_modes, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--variant-n-modes")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--variant-n-modes", err, sizeof err)) ||
                parse_name_set("--variant-n-modes", v, tp_nmode_name, TP_NMODE_COUNT, &o.variant_n_modes, err,
                               sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--n")) {
            if (cli_double_value(argc, argv, &i, "--n", 1e-300, ACC_MAX_N, &o.n_uniform, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--n-range")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--n-range", err, sizeof err)))
                goto usage_error;
            char lo[64], hi[64];
            const char *colon = strchr(v, ':');
            if (!colon || (size_t)(colon - v) >= sizeof lo || strlen(colon + 1) >= sizeof hi) {
                snprintf(err, sizeof err, "--n-range: '%s' is not LO:HI (accepted: 0 < LO < HI <= %g)", v, ACC_MAX_N);
                goto usage_error;
            }
            memcpy(lo, v, (size_t)(colon - v));
            lo[colon - v] = '\0';
            strcpy(hi, colon + 1);
            if (cli_parse_double("--n-range LO", lo, 1e-300, ACC_MAX_N, &o.n_lo, err, sizeof err) ||
                cli_parse_double("--n-range HI", hi, 1e-300, ACC_MAX_N, &o.n_hi, err, sizeof err))
                goto usage_error;
            if (!(o.n_lo < o.n_hi)) {
                snprintf(err, sizeof err, "--n-range: LO (%g) must be below HI (%g)", o.n_lo, o.n_hi);
                goto usage_error;
            }
        } else if (cli_flag_is(a, "--work-items")) {
            if (cli_long_value(argc, argv, &i, "--work-items", 1, TP_MAX_WORK_ITEMS, &o.work_items, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--threads")) {
            if (cli_long_value(argc, argv, &i, "--threads", 1, 256, &lv, err, sizeof err))
                goto usage_error;
            o.threads = (int)lv;
        } else if (cli_flag_is(a, "--sweep-samples")) {
            if (cli_long_multiple_value(argc, argv, &i, "--sweep-samples", ACC_MIN_SAMPLES, ACC_MAX_SAMPLES, 16,
                                        &o.sweep_grid.samples, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--sweep-n-step")) {
            if (cli_double_value(argc, argv, &i, "--sweep-n-step", 1e-3, 998, &o.sweep_grid.n_step, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--sweep-reps")) {
            if (cli_long_value(argc, argv, &i, "--sweep-reps", 1, TP_MAX_REPS, &lv, err, sizeof err))
                goto usage_error;
            o.sweep_reps = (int)lv;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench throughput --help)", a);
            goto usage_error;
        }
    }
    if (!models_given && usermodel_count() > 0)
        models_text = usermodel_names();   /* with a user model and no --models: the user models */
    int n = model_spec_list_parse(models_text, o.models, TP_MAX_MODELS, err, sizeof err);
    if (n < 0)
        goto usage_error;
    o.model_count = n;
    if (throughput_options_check(&o, err, sizeof err))
        goto usage_error;

    /* PoCL reads this when the platform is first opened. */
    setenv("POCL_AFFINITY", "1", 0);
    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench throughput: %s\n", err);
        return rc;
    }
    char run_dir[4096];
    if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench throughput: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    rc = throughput_run(&s, &o, run_dir, quiet);
    if (!rc && !models_given)   /* the physically based models from full vectors (pbcost.h) */
        rc = pbcost_run_write(&s, run_dir, quiet);
    if (!rc && !out_dir && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench throughput: %s\n", err);
        rc = EXIT_RUNTIME;
    }
    clsession_close(&s);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench throughput: %s\n", err);
    return EXIT_USAGE;
}
