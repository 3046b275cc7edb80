/* cmd_plot.c - `brdfbench plot` and `brdfbench heatmap`: redraw a run folder's pictures
 * from its JSON (plots.json, field_<model>.json) without recomputing anything and without
 * an OpenCL device. A missing or malformed JSON file is named with the problem (exit 2); a
 * picture that cannot be written is reported (exit 3) and the other pictures are still drawn. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "field.h"
#include "outdir.h"
#include "plots.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static void redraw_usage(FILE *f, const char *name)
{
    if (strcmp(name, "heatmap") == 0)
        fprintf(f, "usage: brdfbench heatmap [RUN_DIR] [--model LABEL]\n"
                   "  Redraws heatmap_<model>.png from field_<model>.json in RUN_DIR (default: results/latest),\n"
                   "  every model or only LABEL (as in the run, e.g. fvol or fq:Q=0.64). No device is used.\n");
    else
        fprintf(f, "usage: brdfbench plot [RUN_DIR]\n"
                   "  Redraws every picture of a run folder (default: results/latest) from its JSON: the plots\n"
                   "  from plots.json and the heatmaps from field_<model>.json. No device is used.\n");
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Redraws one field file; returns 0, 2 (input) or 3 (picture). Messages start with
   "brdfbench CMD: " and, for a model the user named, "--model LABEL: ". */
static int redraw_field(const char *cmd, const char *model, const char *dir, const char *json_name, int *drawn)
{
    char path[4096], png[4096], name[512], err[1024], what[320] = "";
    struct field_result fr;
    if (model)
        snprintf(what, sizeof what, "--model %s: ", model);
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
        printf("%s\n", png);
        ++*drawn;
    }
    field_result_free(&fr);
    return rc;
}

static int is_field_file(const char *name)
{
    size_t n = strlen(name);
    return n > strlen("field_.json") && strncmp(name, "field_", 6) == 0 && strcmp(name + n - 5, ".json") == 0;
}

/* Every field_*.json of dir in name order (or only the one of `model`). */
static int redraw_heatmaps(const char *cmd, const char *dir, const char *model, int *drawn, int *worst)
{
    if (model) {
        char stem[256], name[320];
        field_safe_label(model, stem, sizeof stem);
        snprintf(name, sizeof name, "field_%s.json", stem);
        int rc = redraw_field(cmd, model, dir, name, drawn);
        if (rc > *worst) *worst = rc;
        return 0;
    }
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "brdfbench %s: %s: cannot open the run folder\n", cmd, dir);
        *worst = EXIT_USAGE;
        return -1;
    }
    char **names = NULL;
    size_t count = 0, cap = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!is_field_file(e->d_name)) continue;
        if (count == cap) {
            cap = cap ? cap * 2 : 32;
            char **nn = realloc(names, cap * sizeof *nn);
            if (!nn) break;
            names = nn;
        }
        if (!(names[count] = strdup(e->d_name))) break;
        count++;
    }
    closedir(d);
    qsort(names, count, sizeof *names, cmp_str);
    for (size_t i = 0; i < count; i++) {
        int rc = redraw_field(cmd, NULL, dir, names[i], drawn);
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
    char err[1024];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0) {
            redraw_usage(stdout, name);
            return EXIT_OK;
        } else if (heatmaps_only && cli_flag_is(a, "--model")) {
            if (!(model = cli_flag_value(argc, argv, &i, "--model", err, sizeof err))) {
                fprintf(stderr, "brdfbench %s: %s\n", name, err);
                return EXIT_USAGE;
            }
        } else if (a[0] == '-' || dir) {
            fprintf(stderr, "brdfbench %s: unexpected argument '%s' (see brdfbench %s --help)\n", name, a, name);
            return EXIT_USAGE;
        } else {
            dir = a;
        }
    }
    if (!dir) dir = "results/latest";
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "brdfbench %s: RUN_DIR '%s' is not a folder (accepted: a run folder of brdfbench all)\n", name,
                dir);
        return EXIT_USAGE;
    }
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
                printf("%s\n", png);
                drawn++;
            }
        }
        plots_free(&set);
    }
    int nfields = redraw_heatmaps(name, dir, model, &drawn, &worst);
    if (model && worst == EXIT_USAGE)
        return worst;   /* the one line above says what is wrong with --model */
    if (heatmaps_only && !model && nfields == 0) {
        fprintf(stderr, "brdfbench %s: %s holds no field_<model>.json to draw from\n", name, dir);
        return EXIT_USAGE;
    }
    fprintf(stderr, "brdfbench %s: %d picture(s) redrawn in %s\n", name, drawn, dir);
    return worst;
}

int cmd_plot(int argc, char **argv) { return redraw(argc, argv, 0); }
int cmd_heatmap(int argc, char **argv) { return redraw(argc, argv, 1); }
