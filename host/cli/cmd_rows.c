/* cmd_rows.c - `brdfbench rows FILE|RUN_DIR`: the figures of result files as the rows of the
 * result document (rdoc.h): every row's keys, status and metrics with unit and direction, as
 * markdown, CSV or JSON (brdfbench.rows/1, which compare and gate --baseline read back). No
 * device is used and nothing is recomputed. */
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "mdbuf.h"
#include "outdir.h"
#include "rdoc_export.h"
#include "rdoc_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum rows_format { ROWS_MD = 0, ROWS_CSV, ROWS_JSON, ROWS_GBENCH, ROWS_BMF, ROWS_ACTION, ROWS_ACTION_SMALLER, ROWS_NFORMATS };

static int call_format(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    static const char *const names[] = { "md", "csv", "json", "gbench", "bmf", "action", "action-smaller" };
    for (int f = 0; f < ROWS_NFORMATS; ++f)
        if (strcmp(value, names[f]) == 0) {
            *(int *)dest = f;
            return 0;
        }
    snprintf(err, errlen, "%s: '%s' is not a format (accepted: md, csv, json) nor an export (gbench, bmf, action, "
                          "action-smaller)", flag, value);
    return EXIT_USAGE;
}

static int call_kind(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    int k = rd_kind_of_name(value);
    if (k < 0) {
        char names[256];
        rd_kind_names(names, sizeof names);
        snprintf(err, errlen, "%s: '%s' is not a kind of result (accepted: %s)", flag, value, names);
        return EXIT_USAGE;
    }
    *(int *)dest = k;
    return 0;
}

/* The documents of path (a file: one; a folder: its kinds' files, only the one of kind `only`
 * when it is >= 0). Returns 0 with *n, or EXIT_USAGE with a message. */
static int read_docs(const char *path, int only, struct rdoc docs[RD_KIND_COUNT], int *n, char *err, size_t errlen)
{
    struct stat st;
    *n = 0;
    if (stat(path, &st) != 0) {
        snprintf(err, errlen, "%s: no such file or folder (accepted: a result file or a run folder)", path);
        return EXIT_USAGE;
    }
    if (S_ISDIR(st.st_mode)) {
        if (rdoc_read_folder(path, only, docs, n, err, errlen))
            return EXIT_USAGE;
    } else {
        if (rdoc_read_file(path, &docs[0], err, errlen))
            return EXIT_USAGE;
        *n = 1;
        if (only >= 0 && rd_kind_of_name(docs[0].kind) != only) {   /* a file of another kind */
            rdoc_free(&docs[0]);
            *n = 0;
        }
    }
    if (*n == 0) {
        char files[512];
        rd_kind_files(files, sizeof files);
        snprintf(err, errlen, "%s: no result file%s%s (accepted: %s, or a brdfbench.rows/1 document)", path,
                 only >= 0 ? " of kind " : "", only >= 0 ? rd_kind_name(only) : "", files);
        return EXIT_USAGE;
    }
    return 0;
}

int cmd_rows(int argc, char **argv)
{
    const char *out = "-";
    int format = ROWS_MD, only = -1;
    char err[1024];
    const struct cli_flag flags[] = {
        { .name = "--format", .value = "FMT", .kind = CLI_CALL, .dest = &format, .call = call_format,
          .range = "md, csv, json, gbench, bmf, action or action-smaller", .def = "md",
          .help = "markdown tables, CSV (one line per metric of a row), JSON (brdfbench.rows/1); for other tools: "
                  "gbench (google/benchmark JSON of the rates, for its compare.py), bmf (Bencher Metric Format, "
                  "every figure), action (github-action-benchmark customBiggerIsBetter: rates, PSNR) or "
                  "action-smaller (customSmallerIsBetter: errors)" },
        { .name = "--kind", .value = "KIND", .kind = CLI_CALL, .dest = &only, .call = call_kind,
          .range = "throughput, accuracy, render, fit or frontier", .def = "every kind found",
          .help = "only the results of this kind" },
        CLI_FLAG_OUTPUT(&out, "-"),
    };
    const struct cli_command cmd = {
        .name = "rows",
        .synopsis = "FILE|RUN_DIR [--format md|csv|json|gbench|bmf|action|action-smaller] [--kind KIND] [--output FILE|-]",
        .about = "  The figures of a result file (throughput.json, accuracy.json, render.json, fit.json,\n"
                 "  frontier.json) or of a run folder's files, as rows: each row's keys, its status and its\n"
                 "  metrics with unit and direction (higher or lower is better), range and repetitions. These\n"
                 "  are the rows compare matches across runs and gate --baseline reads. No device is used.\n"
                 "  gbench, bmf and action write them for google/benchmark's compare.py, Bencher and\n"
                 "  github-action-benchmark (docs/ci.md, \"Exports\"). --kind with RUN_DIR opens that kind's file\n"
                 "  only; csv, json and the exports write one document, so a folder of several kinds needs it.\n",
        CLI_TABLE(flags),
        .max_positional = 1,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc) return cli_parse_exit(&cmd, prc, err);
    if (args.npositional != 1) {
        fprintf(stderr, "brdfbench rows: expected FILE|RUN_DIR (a result file or a run folder)\n");
        return EXIT_USAGE;
    }
    if (output_file_check("--output", out, err, sizeof err)) {
        fprintf(stderr, "brdfbench rows: %s\n", err);
        return EXIT_USAGE;
    }
    /* on the heap: a document holds its context and its devices' (about 170 kB), one per kind */
    struct rdoc *docs = calloc(RD_KIND_COUNT, sizeof *docs);
    int n = 0;
    if (!docs) {
        fprintf(stderr, "brdfbench rows: out of memory\n");
        return EXIT_RUNTIME;
    }
    if (read_docs(args.positional[0], only, docs, &n, err, sizeof err)) {
        fprintf(stderr, "brdfbench rows: %s\n", err);
        free(docs);
        return EXIT_USAGE;
    }
    int rc = EXIT_OK;
    if (format != ROWS_MD && n > 1) {
        static const char *const fnames[] = { "md", "csv", "json", "gbench", "bmf", "action", "action-smaller" };
        fprintf(stderr, "brdfbench rows: --format %s writes one document and %s holds %d (name one with --kind: %s, "
                        "%s%s)\n", fnames[format], args.positional[0], n, docs[0].kind,
                docs[1].kind, n > 2 ? ", ..." : "");
        rc = EXIT_USAGE;
    } else {
        struct md_buf b;
        md_init(&b);
        int xrc = 0;
        for (int i = 0; i < n && !xrc; ++i) {
            if (format == ROWS_GBENCH)
                xrc = rdoc_gbench(&docs[i], &b, err, sizeof err);
            else if (format == ROWS_BMF)
                xrc = rdoc_bmf(&docs[i], &b, err, sizeof err);
            else if (format == ROWS_ACTION || format == ROWS_ACTION_SMALLER)
                xrc = rdoc_action(&docs[i], format == ROWS_ACTION ? RD_HIGHER : RD_LOWER, &b, err, sizeof err);
            else if (format == ROWS_JSON)
                rdoc_json(&docs[i], &b);
            else if (format == ROWS_CSV)
                rdoc_csv(&docs[i], &b);
            else
                rdoc_markdown(&docs[i], &b);
        }
        if (xrc) {   /* nothing the format takes: nothing written */
            md_free(&b);
            fprintf(stderr, "brdfbench rows: %s\n", err);
            rc = xrc;
        } else if (md_write_file_free(&b, out, err, sizeof err)) {
            fprintf(stderr, "brdfbench rows: %s\n", err);
            rc = EXIT_RUNTIME;
        }
    }
    for (int i = 0; i < n; ++i)
        rdoc_free(&docs[i]);
    free(docs);
    return rc;
}
