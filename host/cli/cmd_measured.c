/* cmd_measured.c - `brdfbench measured FILE|DIR ...`: measured materials (MERL .binary files, a
 * folder's .binary files) fitted by Blinn-Phong and Cook-Torrance, and every cheap lobe measured
 * against them and against the fitted Blinn-Phong (host/engine/measured.h). */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "measured.h"
#include "measured_report.h"
#include "merl.h"
#include "outdir.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

struct path_list {
    char **paths;
    int count, cap;
};

static int path_add(struct path_list *l, const char *path)
{
    if (l->count >= MEASURED_MAX_MATERIALS)
        return -1;
    if (l->count == l->cap) {
        int cap = l->cap ? 2 * l->cap : 16;
        char **p = realloc(l->paths, (size_t)cap * sizeof *p);
        if (!p)
            return -1;
        l->paths = p;
        l->cap = cap;
    }
    l->paths[l->count] = strdup(path);
    if (!l->paths[l->count])
        return -1;
    l->count++;
    return 0;
}

static void path_list_free(struct path_list *l)
{
    for (int i = 0; i < l->count; ++i)
        free(l->paths[i]);
    free(l->paths);
    memset(l, 0, sizeof *l);
}

static int binary_entry(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return e->d_name[0] != '.' && n > 7 && strcmp(e->d_name + n - 7, ".binary") == 0;
}

/* A FILE, or every *.binary of a DIR in name order. Returns 0 or EXIT_USAGE with a message. */
static int collect(const char *arg, struct path_list *l, char *err, size_t errlen)
{
    struct stat st;
    if (stat(arg, &st) != 0) {
        snprintf(err, errlen, "%s: %s (expected a MERL .binary file or a folder of them)", arg, strerror(errno));
        return EXIT_USAGE;
    }
    if (!S_ISDIR(st.st_mode)) {
        if (path_add(l, arg)) {
            snprintf(err, errlen, "%s: at most %d materials per run", arg, MEASURED_MAX_MATERIALS);
            return EXIT_USAGE;
        }
        return 0;
    }
    struct dirent **list = NULL;
    int n = scandir(arg, &list, binary_entry, alphasort);
    if (n < 0) {
        snprintf(err, errlen, "%s: cannot read the folder: %s", arg, strerror(errno));
        return EXIT_USAGE;
    }
    int rc = 0;
    if (n == 0) {
        snprintf(err, errlen, "%s: no .binary files in the folder (expected MERL files named NAME.binary)", arg);
        rc = EXIT_USAGE;
    }
    for (int i = 0; i < n; ++i) {
        char path[OUTDIR_PATH_MAX];
        if (!rc && (path_join(path, sizeof path, arg, list[i]->d_name) || path_add(l, path))) {
            snprintf(err, errlen, "%s: at most %d materials per run", arg, MEASURED_MAX_MATERIALS);
            rc = EXIT_USAGE;
        }
        free(list[i]);
    }
    free(list);
    return rc;
}

int cmd_measured(int argc, char **argv)
{
    char err[4600];
    struct measured_options opt;
    measured_options_default(&opt);
    struct device_options dev;
    device_options_init(&dev);
    const char *out_dir = NULL, *json_path = NULL, *models = NULL;
    int quiet = 0, models_given = 0;
    const struct cli_flag flags[] = {
        { .name = "--fit-cells", .value = "N", .kind = CLI_LONG, .dest = CLI_DEST(long, &opt.fit_cells),
          .min = MEASURED_MIN_FIT_CELLS, .max = MEASURED_MAX_FIT_CELLS,
          .help = "at most N cells in each fit (an even stride through the used cells); errors are always over "
                  "every used cell" },
        CLI_FLAG_MODELS(&models, &models_given,
                        "every cheap lobe: the registry's approximations of cos^n, without the two-parameter families"),
        CLI_FLAG_OUT(&out_dir, CLI_DEF_OUT "; with --json and no --out, no folder"),
        CLI_FLAG_JSON(&json_path),
        CLI_FLAG_QUIET(&quiet),
        CLI_FLAGS_DEVICE(&dev),
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
    struct path_list files = { 0 };
    for (int i = 0; i < args.npositional; ++i)
        if (collect(args.positional[i], &files, err, sizeof err)) {
            path_list_free(&files);
            return cli_parse_exit(&cmd, EXIT_USAGE, err);
        }
    opt.quiet = quiet;

    struct measured_report rep = { .opt = opt, .count = 0 };
    rep.materials = calloc((size_t)files.count, sizeof *rep.materials);
    if (!rep.materials) {
        fprintf(stderr, "brdfbench measured: out of memory\n");
        path_list_free(&files);
        return EXIT_RUNTIME;
    }
    struct cl_session s;
    char run_dir[4096], tmp_dir[512];
    int rc = cli_run_open("measured", &s, &dev, out_dir, json_path && !out_dir, run_dir, sizeof run_dir, tmp_dir,
                          sizeof tmp_dir);
    if (rc) {
        free(rep.materials);
        path_list_free(&files);
        return rc;
    }
    int table_quiet = quiet || cli_is_stdout(json_path);
    for (int i = 0; i < files.count && !rc; ++i) {
        struct merl_material mat;
        rc = merl_read(files.paths[i], &mat, err, sizeof err);
        if (rc) {
            fprintf(stderr, "brdfbench measured: %s\n", err);
            break;
        }
        if (!table_quiet)
            fprintf(stderr, "measured: %s (%d of %d)\n", mat.name, i + 1, files.count);
        rc = measured_material_run(&s, &mat, &opt, &rep.materials[rep.count]);
        merl_free(&mat);
        if (!rc)
            rep.count++;
    }
    char path[4300];
    if (!rc) {
        path_join(path, sizeof path, run_dir, "measured.json");
        if (measured_write_json(path, &rep, &s, err, sizeof err) ||
            measured_write_plots(tmp_dir[0] ? tmp_dir : run_dir, &rep, err, sizeof err)) {
            fprintf(stderr, "brdfbench measured: %s\n", err);
            rc = EXIT_RUNTIME;
        }
    }
    if (!rc && cli_run_latest("measured", out_dir, tmp_dir, run_dir))
        rc = EXIT_RUNTIME;
    if (!rc && json_path && cli_run_deliver("measured", run_dir, "measured.json", "--json", json_path))
        rc = EXIT_RUNTIME;
    cli_temp_dir_remove(tmp_dir);
    if (rc)
        outdir_remove_own_empty();
    if (!rc && !table_quiet) {
        measured_print(stdout, &rep);
        if (!tmp_dir[0])
            printf("written: %s/measured.json\n", run_dir);
        if (json_path)
            printf("written: %s\n", json_path);
    }
    clsession_close(&s);
    free(rep.materials);
    path_list_free(&files);
    return rc;
}
