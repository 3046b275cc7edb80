/* cmd_throughput.c - `brdfbench throughput`: every model's evaluations per second on the
 * device, against the pow() built-in, tuned C and the device's peak, under three sets of build
 * options; written as throughput.json, throughput.csv and a table. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "measured.h"
#include "pbcost.h"
#include "throughput.h"
#include "usermodel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static int call_variants(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    return parse_name_set(flag, v, tp_variant_name, TP_VARIANT_COUNT, dest, err, errlen);
}

static int call_n_modes(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    return parse_name_set(flag, v, tp_nmode_name, TP_NMODE_COUNT, dest, err, errlen);
}

/* The checks of the parsed flags, and the options they make (the models, the A/B variant):
 * 0, or -1 with the message in err. */
static int check_args(struct throughput_options *o, const char *json_path, const char *csv_path,
                      const char *models_text, int models_given, const char *ab_options, char *err, size_t errlen)
{
    if (cli_is_stdout(json_path) && cli_is_stdout(csv_path)) {
        snprintf(err, errlen, "--json - and --csv -: one document at a time on standard output");
        return -1;
    }
    if (!(o->n_lo < o->n_hi)) {
        snprintf(err, errlen, "--n-min (%g) must be below --n-max (%g)", o->n_lo, o->n_hi);
        return -1;
    }
    if (!models_given && usermodel_count() > 0)
        models_text = usermodel_names();   /* with a user model and no --models: the user models */
    int n = cli_model_list(models_text, o->models, TP_MAX_MODELS, err, errlen);
    if (n >= 0)
        n = cli_add_unlisted_user_models(o->models, n, TP_MAX_MODELS, err, errlen);
    if (n < 0)
        return -1;
    o->model_count = n;
    if (ab_options) {
        if (!*ab_options || strlen(ab_options) > 400) {
            snprintf(err, errlen, "--ab-options: expected OpenCL build options (1 to 400 characters)");
            return -1;
        }
        o->ab_options = ab_options;
        o->variants |= 1u << TP_VARIANT_AB;
    }
    if (throughput_options_check(o, err, errlen))
        return -1;
    return 0;
}

/* --ab-options: OUT/ab/a and OUT/ab/b for `brdfbench compare`. */
static int write_ab(const char *run_dir, const char *ab_options, int tp_quiet)
{
    char e2[1100];
    if (cli_write_ab(run_dir, ab_options, e2, sizeof e2)) {
        fprintf(stderr, "brdfbench throughput: %s\n", e2);
        return EXIT_RUNTIME;
    }
    if (!tp_quiet)
        printf("A/B in one process: brdfbench compare %s/ab/a %s/ab/b\n", run_dir, run_dir);
    return 0;
}

/* --measured's materials (read before anything is made) and the full BRDFs among the models,
 * for the physically based models' table: 0, or the exit code (EXIT_USAGE with the message in err). */
static int load_materials(const char *measured_arg, const struct throughput_options *o, struct merl_material *mats,
                          struct pbcost_options *po, char *err, size_t errlen)
{
    if (measured_arg) {
        int lrc = measured_load("--measured", measured_arg, PBCOST_MAX_MEASURED, mats, &po->nmeasured, err, errlen);
        if (lrc)
            return lrc;
        for (int i = 0; i < po->nmeasured; ++i)
            po->measured[i] = &mats[i];
    }
    for (int i = 0; i < o->model_count && po->nfull < PBCOST_MAX_MEASURED; ++i)
        if (model_is_full(o->models[i].info))
            po->full[po->nfull++] = o->models[i];
    return 0;
}

/* The physically based models from full vectors (pbcost.h), in a run of the default set, and
 * with the user full BRDFs and measured materials. */
static int run_physical(struct cl_session *s, const struct pbcost_options *po, const char *run_dir, int tp_quiet)
{
    if (!s->specialise) {
        struct pbcost_options o = *po;
        o.io = (struct engine_io){ run_dir, tp_quiet };
        struct pbcost_result *r = malloc(sizeof *r);
        int rc = r ? pbcost_run(s, &o, r) : EXIT_RUNTIME;
        free(r);
        return rc;
    }
    /* its kernels are float16 (kernels/throughput.cl, TP_W) */
    fprintf(stderr, "throughput: the physically based models' full-vector table is not run on %s: its kernels "
                    "are float16 only, which this driver compiles for minutes (PoCL runs it)\n",
            s->platform_name);
    return 0;
}

/* What the command runs in its run folder: the measurement, the A/B documents, the physically
 * based models' table (not in a temporary folder: --json or --csv without --out delivers
 * throughput's documents only). */
struct throughput_job {
    struct throughput_options *o;
    const struct pbcost_options *po;
    const char *ab_options;
    int physical;                          /* the default set, or full BRDFs or measured materials asked for */
    const struct cli_engine_run *e;        /* its tmp_dir: a temporary folder */
};

static int run_throughput(struct cl_session *s, const char *run_dir, int quiet, void *ctx)
{
    const struct throughput_job *j = ctx;
    j->o->io = (struct engine_io){ run_dir, quiet };
    int rc = throughput_run(s, j->o, NULL);
    if (!rc && j->ab_options)
        rc = write_ab(run_dir, j->ab_options, quiet);
    if (!rc && j->physical && !j->e->tmp_dir[0])
        rc = run_physical(s, j->po, run_dir, quiet);
    return rc;
}

int cmd_throughput(int argc, char **argv)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "throughput", cmd_throughput, "throughput.json", "results", "throughput.csv");
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct throughput_options o;
    throughput_options_default(&o);
    struct throughput_job job = { .o = &o };
    struct cli_engine_run e;
    cli_engine_init(&e, "throughput", "throughput.json", run_throughput, &job);
    e.csv_document = "throughput.csv";
    job.e = &e;
    const char *models_text = "all", *ab_options = NULL;
    int models_given = 0;
    struct cli_model_params mparams = { .count = 0 };
    const char *measured_arg = NULL;

    const struct cli_flag flags[] = {
        CLI_FLAG_MODELS(&models_text, &models_given, "all; with --model or --model-file, only the user models"),
        { .name = "--reps", .value = "N", .kind = CLI_INT, .dest = &o.reps, .min = 1, .max = TP_MAX_REPS,
          .help = "timed launches per figure" },
        { .name = "--min-time", .value = "S", .kind = CLI_DOUBLE, .dest = &o.min_time, .min = TP_MIN_TIME_MIN,
          .max = TP_MIN_TIME_MAX, .help = "seconds one timed launch lasts at least" },
        { .name = "--variants", .value = "LIST", .kind = CLI_CALL, .call = call_variants, .dest = &o.variants,
          .help = "build options to measure: default,fast-relaxed-math,denorms-are-zero", .def = "all three" },
        { .name = "--ab-options", .value = "OPTIONS", .kind = CLI_TEXT, .dest = &ab_options,
          .help = "also measure the default build options plus OPTIONS (variant ab) in the same interleaved rounds, "
                  "and write OUT/ab/a and OUT/ab/b for `brdfbench compare OUT/ab/a OUT/ab/b`: an A/B comparison "
                  "in one process", .def = "" },
        { .name = "--n-modes", .value = "LIST", .kind = CLI_CALL, .call = call_n_modes, .dest = &o.n_modes,
          .help = "uniform (one n per launch), varying (one n per evaluation)", .def = "both" },
        { .name = "--variant-n-modes", .value = "LIST", .kind = CLI_CALL, .call = call_n_modes,
          .dest = &o.variant_n_modes, .help = "n modes for the non-default variants", .def = "uniform" },
        { .name = "--uniform-n", .value = "X", .kind = CLI_DOUBLE, .dest = &o.n_uniform, .min = 1e-300,
          .max = ACC_MAX_N, .help = "the shininess n of the uniform mode" },
        CLI_FLAG_N_MIN(&o.n_lo),
        CLI_FLAG_N_MAX(&o.n_hi),
        { .name = "--work-items", .value = "N", .kind = CLI_LONG, .dest = &o.work_items, .min = 1,
          .max = TP_MAX_WORK_ITEMS, .help = "device work-items per launch", .def = "32 per compute unit on a CPU device, 512 on others" },
        { .name = "--threads", .value = "N", .kind = CLI_INT, .dest = &o.threads, .min = 1, .max = 256,
          .help = "threads of the C baseline", .def = "the online CPUs" },
        { .name = "--no-host-c", .kind = CLI_SWITCH, .dest = &o.host_c, .set = 0, .help = "skip the C baseline" },
        { .name = "--sweep", .kind = CLI_SWITCH, .dest = &o.sweep, .set = 1,
          .help = "also time the accuracy sweep (kernels/accuracy.cl) against the same sweep in tuned C "
                  "(samples in s = 1 - c, the lobe as expf(n log1pf(-s))) (on by default)" },
        { .name = "--no-sweep", .kind = CLI_SWITCH, .dest = &o.sweep, .set = 0, .help = "skip the sweep timing" },
        { .name = "--sweep-samples", .value = "N", .kind = CLI_LONG, .dest = &o.sweep_grid.samples,
          .min = ACC_MIN_SAMPLES, .max = ACC_MAX_SAMPLES, .multiple = 16,
          .help = "samples per zone and per n of the timed sweep" },
        { .name = "--sweep-n-step", .value = "X", .kind = CLI_DOUBLE, .dest = &o.sweep_grid.n_step, .min = 1e-3,
          .max = 998, .help = "step of n of the timed sweep over [2, 1000]" },
        { .name = "--sweep-reps", .value = "N", .kind = CLI_INT, .dest = &o.sweep_reps, .min = 1, .max = TP_MAX_REPS,
          .help = "timed runs per model of the sweep" },
        CLI_FLAG_MEASURED(&measured_arg),
        CLI_FLAGS_DOCUMENTS(&e.out_dir, &e.json_path, &e.csv_path),
        CLI_FLAG_QUIET(&e.quiet),
        CLI_FLAGS_USERMODEL,
        CLI_FLAG_MODEL_PARAM(&mparams),
        CLI_FLAGS_DEVICE(&e.dev),
        { .name = "--n", .kind = CLI_RENAMED, .help = "the uniform mode's shininess is --uniform-n X" },
        { .name = "--n-range", .kind = CLI_RENAMED,
          .help = "the varying mode's range of n is --n-min LO --n-max HI, as in the other commands" },
    };
    const struct cli_command cmd = {
        .name = "throughput",
        .about = "  Evaluations per second of every model on the OpenCL device, with inputs made in registers\n"
                 "  and outputs summed, beside the pow() built-in, a tuned C loop doing the same work\n"
                 "  (-O3 -march=native, one thread per CPU) and the device's measured FMA peak; under the\n"
                 "  build options default, -cl-fast-relaxed-math and -cl-denorms-are-zero, each with what it\n"
                 "  does to accuracy against the double reference. The varying mode draws n from\n"
                 "  [--n-min, --n-max]. Writes throughput.json and throughput.csv.\n",
        CLI_TABLE(flags),
        .epilog = "  POCL_AFFINITY=1 is set unless the environment sets it: it pins PoCL's threads to CPUs,\n"
                  "  so that a run does not land on one thread.\n",
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (check_args(&o, e.json_path, e.csv_path, models_text, models_given, ab_options, err, sizeof err) ||
        cli_apply_model_params(o.models, o.model_count, &mparams, err, sizeof err))
        goto usage_error;
    /* the measured materials, read before anything is made */
    struct merl_material mats[PBCOST_MAX_MEASURED];
    struct pbcost_options po;
    pbcost_options_default(&po);
    int lrc = load_materials(measured_arg, &o, mats, &po, err, sizeof err);
    if (lrc == EXIT_USAGE)
        goto usage_error;
    if (lrc)
        return lrc;
    job.po = &po;
    job.ab_options = ab_options;
    job.physical = (!models_given && usermodel_count() == 0) || po.nfull || po.nmeasured;

    /* PoCL reads this when the platform is first opened. */
    setenv("POCL_AFFINITY", "1", 0);
    int rc = cli_run_engine(&e);
    for (int i = 0; i < po.nmeasured; ++i)
        merl_free(&mats[i]);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench throughput: %s\n", err);
    return EXIT_USAGE;
}
