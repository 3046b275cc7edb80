/* main.c - the brdfbench command line: dispatches to one subcommand. */
#include <stdio.h>
#include <string.h>

#include "cli_table.h"
#include "commands.h"
#include "context.h"
#include "exitcodes.h"
#include "outdir.h"

struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *help;
};

static const struct command commands[] = {
    { "list", cmd_list, "the models (formulas, parameters, references) and the OpenCL devices" },
    { "accuracy", cmd_accuracy, "dense-grid accuracy sweep of models on the OpenCL device" },
    { "all", cmd_all, "the main job: every sweep, heatmap, plot and report.md in results/<date-time>/" },
    { "plot", cmd_plot, "redraw every picture of a run folder from its JSON (no device)" },
    { "heatmap", cmd_heatmap, "redraw the heatmaps of a run folder from its field JSON (no device)" },
    { "gate", cmd_gate, "accuracy gates for CI: checks figures of a gates file against bounds (JUnit, JSON)" },
    { "render", cmd_render, "full-image shading passes (spheres, teapot, bunny): error images, metrics, Mpixel/s" },
    { "reproduce", cmd_reproduce, "re-derive every claim of both papers: claims.json, claims.md and a table" },
    { "fit", cmd_fit, "the cosine-quadratic family's accuracy limit and its best affine k(n) (quad:a=..,b=..)" },
    { "throughput", cmd_throughput, "evaluations/s of every model vs pow(), tuned C and the device peak; build-option variants" },
    { "version", cmd_version, "the program's version and git revision (also --version after any command)" },
    { "compare", cmd_compare, "runs side by side against a baseline: faster/slower/same, accuracy changes (no device)" },
    /* more commands below, one per line */
    { "frontier", cmd_frontier, "cost against accuracy of every lobe approximation: the Pareto front, plots, which to ship" },
};

static void usage(FILE *f)
{
    fprintf(f, "usage: brdfbench COMMAND [OPTIONS]   (brdfbench COMMAND --help for its options)\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].help);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        cli_print_version(stdout);
        return EXIT_OK;
    }
    /* -h is --help for every command (no command takes -h otherwise). */
    static char help_flag[] = "--help";
    for (int i = 2; i < argc; ++i)
        if (strcmp(argv[i], "-h") == 0)
            argv[i] = help_flag;
    /* a run stopped by a signal leaves no half-written outputs (outdir.h) */
    outdir_install_signal_handlers();
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        if (strcmp(argv[1], commands[i].name) == 0) {
            int rc = commands[i].run(argc - 1, argv + 1);
            /* A run that failed leaves no empty folder it made (a folder that existed stays). */
            if (rc != EXIT_OK && rc != EXIT_GATE_FAIL)
                outdir_remove_own_empty();
            return rc;
        }
    fprintf(stderr, "brdfbench: unknown command '%s' (accepted:", argv[1]);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        fprintf(stderr, " %s", commands[i].name);
    fprintf(stderr, ")\n");
    return EXIT_USAGE;
}
