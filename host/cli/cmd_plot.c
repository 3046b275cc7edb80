/* cmd_plot.c - `brdfbench plot` and `brdfbench heatmap`: redraw a run folder's pictures
 * from its JSON (plots.json, field_<model>.json) without recomputing anything and without
 * an OpenCL device. A missing or malformed JSON file is named with the problem (exit 2); a
 * picture that cannot be written is reported (exit 3) and the other pictures are still drawn. */
#define _POSIX_C_SOURCE 200809L
#include "cli_table.h"
#include "draw.h"
#include "jsonr.h"
#include "commands.h"
#include "exitcodes.h"
#include "field_report.h"
#include "heatmaps_shared.h"
#include "outdir.h"
#include "plots.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>


/* Redraws one field file; returns 0, 2 (input) or 3 (picture). Messages start with
   "brdfbench CMD: " and, for a model the user named, "--label LABEL: ". */
/* quiet (--quiet): no list of the pictures drawn (errors are still said) */
static int redraw_field(const char *cmd, const char *model, const char *dir, const char *json_name, int quiet,
                        int *drawn)
{
    char path[4096], png[4096], name[512], err[1024], what[320] = "";
    struct field_result fr;
    if (model)
        snprintf(what, sizeof what, "--label %s: ", model);
    if (path_join(path, sizeof path, dir, json_name)) {
        fprintf(stderr, "brdfbench %s: %s%s/%s: path too long\n", cmd, what, dir, json_name);
        return EXIT_USAGE;
    }
    if (field_read_json(path, &fr, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s%s\n", cmd, what, err);
        return EXIT_USAGE;
    }
    /* field_<stem>.json -> heatmap_<stem>.png */
    size_t len = strlen(json_name);
    snprintf(name, sizeof name, "heatmap_%.*s.png", (int)(len - strlen("field_") - strlen(".json")),
             json_name + strlen("field_"));
    int rc = 0;
    if (path_join(png, sizeof png, dir, name) || field_draw_heatmap(png, &fr, NULL, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", cmd, err);
        rc = EXIT_RUNTIME;
    } else {
        if (!quiet)
            printf("%s\n", png);
        ++*drawn;
    }
    field_result_free(&fr);
    return rc;
}

/* The labels of the models of a run (each field file's "model"), comma-separated. */
static void run_labels(const char *dir, char *out, size_t len)
{
    size_t count = 0, used = 0;
    char **names = field_file_names(dir, &count);
    out[0] = '\0';
    for (size_t i = 0; i < count; i++) {
        char path[4096], err[256];
        struct jr_doc doc;
        const char *label = NULL;
        int parsed = path_join(path, sizeof path, dir, names[i]) == 0 && jr_parse_file(path, &doc, err, sizeof err) == 0;
        if (parsed && jr_need_str(&doc, &doc.root, "model", &label, err, sizeof err) != 0)
            label = NULL;
        if (used < len)
            used += (size_t)snprintf(out + used, len - used, "%s%s", i ? ", " : "", label ? label : names[i]);
        if (parsed)
            jr_free(&doc);
        free(names[i]);
    }
    free(names);
}

/* Every field_*.json of dir in name order (or only the one of `model`). */
static int redraw_heatmaps(const char *cmd, const char *dir, const char *model, int quiet, int *drawn, int *worst)
{
    if (model) {
        char stem[256], name[320], path[4096];
        struct stat st;
        field_safe_label(model, stem, sizeof stem);
        snprintf(name, sizeof name, "field_%s.json", stem);
        if (path_join(path, sizeof path, dir, name) == 0 && stat(path, &st) != 0) {
            char labels[2048];
            run_labels(dir, labels, sizeof labels);
            fprintf(stderr, "brdfbench %s: --label %s: %s has no model of that label (accepted: %s)\n", cmd, model,
                    dir, labels[0] ? labels : "none: the run holds no field_<model>.json");
            *worst = EXIT_USAGE;
            return 0;
        }
        int rc = redraw_field(cmd, model, dir, name, quiet, drawn);
        if (rc > *worst) *worst = rc;
        return 0;
    }
    size_t count = 0;
    char **names = field_file_names(dir, &count);
    if (!names && count == 0) {
        DIR *probe = opendir(dir);
        if (!probe) {
            fprintf(stderr, "brdfbench %s: %s: cannot open the run folder\n", cmd, dir);
            *worst = EXIT_USAGE;
            return -1;
        }
        closedir(probe);
    }
    for (size_t i = 0; i < count; i++) {
        int rc = redraw_field(cmd, NULL, dir, names[i], quiet, drawn);
        if (rc == EXIT_USAGE || (rc && *worst != EXIT_USAGE)) *worst = rc;
        free(names[i]);
    }
    free(names);
    return (int)count;
}

static int redraw(int argc, char **argv, int heatmaps_only)
{
    const char *name = heatmaps_only ? "heatmap" : "plot";
    const char *dir = NULL, *model = NULL;
    int shared = 0, quiet = 0;
    char err[1024];
    const struct cli_flag plot_flags[] = { CLI_FLAG_SHARED_SCALE(&shared), CLI_FLAG_QUIET(&quiet) };
    const struct cli_flag heatmap_flags[] = {
        CLI_FLAG_SHARED_SCALE(&shared),
        CLI_FLAG_QUIET(&quiet),
        { .name = "--label", .value = "LABEL", .kind = CLI_TEXT, .dest = &model,
          .help = "redraw only the model of this label, as the run names it (e.g. fvol or fq:Q=0.64)",
          .def = "every model of the run" },
        { .name = "--model", .kind = CLI_RENAMED,
          .help = "the model to redraw is chosen with --label LABEL (--model NAME=EXPR defines a user model in "
                  "the commands that evaluate models)" },
    };
    const struct cli_command cmd = {
        .name = name,
        .synopsis = heatmaps_only ? "[RUN_DIR] [--label LABEL] [--shared-scale] [--quiet]" : "[RUN_DIR] [--shared-scale] [--quiet]",
        .about = heatmaps_only
                     ? "  Redraws heatmap_<model>.png from field_<model>.json in RUN_DIR (default: results/latest),\n"
                       "  every model or only one. No device is used.\n"
                     : "  Redraws every picture of a run folder (default: results/latest) from its JSON: the plots\n"
                       "  from plots.json and the heatmaps from field_<model>.json. No device is used.\n",
        .flags = heatmaps_only ? heatmap_flags : plot_flags,
        .nflags = heatmaps_only ? (int)(sizeof heatmap_flags / sizeof heatmap_flags[0])
                                : (int)(sizeof plot_flags / sizeof plot_flags[0]),
        .max_positional = 1,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    if (prc) {
        fprintf(stderr, "brdfbench %s: %s\n", name, err);
        return EXIT_USAGE;
    }
    if (args.npositional)
        dir = args.positional[0];
    if (!dir) dir = "results/latest";
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "brdfbench %s: RUN_DIR '%s' is not a folder (accepted: a run folder of brdfbench all)\n", name,
                dir);
        return EXIT_USAGE;
    }
    if (draw_module_check(err, sizeof err)) {   /* one line, not one per picture */
        fprintf(stderr, "brdfbench %s: %s\n", name, err);
        return EXIT_RUNTIME;
    }
    /* the run folder is input: the pictures written into it never follow a link out of it */
    outdir_confine(dir);
    int worst = 0, drawn = 0;
    if (!heatmaps_only) {
        char path[4096];
        struct plot_set set;
        if (path_join(path, sizeof path, dir, "plots.json")) {
            fprintf(stderr, "brdfbench %s: %s: path too long\n", name, dir);
            return EXIT_USAGE;
        }
        if (plots_read_json(path, &set, err, sizeof err)) {
            fprintf(stderr, "brdfbench %s: %s\n", name, err);
            return EXIT_USAGE;
        }
        for (int i = 0; i < set.count; i++) {
            char png[4096];
            if (path_join(png, sizeof png, dir, set.figs[i].file) ||
                plot_figure_draw(&set.figs[i], png, err, sizeof err)) {
                fprintf(stderr, "brdfbench %s: %s\n", name, err);
                worst = EXIT_RUNTIME;
            } else {
                if (!quiet)
                    printf("%s\n", png);
                drawn++;
            }
        }
        plots_free(&set);
    }
    int nfields = redraw_heatmaps(name, dir, model, quiet, &drawn, &worst);
    if (model && worst == EXIT_USAGE)
        return worst;   /* the one line above says what is wrong with --model */
    if (heatmaps_only && !model && nfields == 0) {
        fprintf(stderr, "brdfbench %s: %s holds no field_<model>.json to draw from\n", name, dir);
        return EXIT_USAGE;
    }
    if ((nfields > 0 || model) && worst != EXIT_USAGE) {
        /* the page of every model on one scale, and with --shared-scale each heatmap on it */
        int scaled = 0, rc = plots_heatmaps_shared(dir, shared, model, &scaled, err, sizeof err);
        if (rc) {
            fprintf(stderr, "brdfbench %s: %s\n", name, err);
            if (rc > worst) worst = rc;
        } else {
            if (!quiet)
                printf("%s/%s\n", dir, HEATMAPS_SHARED_FILE);
        }
    }
    if (!quiet)
        fprintf(stderr, "brdfbench %s: %d picture(s) redrawn in %s\n", name, drawn, dir);
    return worst;
}

int cmd_plot(int argc, char **argv) { return redraw(argc, argv, 0); }
int cmd_heatmap(int argc, char **argv) { return redraw(argc, argv, 1); }
