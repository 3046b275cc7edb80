/* cmd_store.c - `brdfbench store add|list|export`: run folders and result files put into the
 * SQLite store of runs (store.h), listed, and written back as rows documents. No device. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE   /* timegm */
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "mdbuf.h"
#include "outdir.h"
#include "rdoc_read.h"
#include "store.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define STORE_MAX_DOCS 512   /* documents one add takes (a run folder gives up to RD_KIND_COUNT) */

static int call_kind(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    if (rd_kind_of_name(value) < 0) {
        char names[256];
        rd_kind_names(names, sizeof names);
        snprintf(err, errlen, "%s: '%s' is not a kind of result (accepted: %s)", flag, value, names);
        return EXIT_USAGE;
    }
    *(const char **)dest = value;
    return 0;
}

/* --commit-date: an ISO 8601 time (git show -s --format=%cI) with a zone, kept in UTC so that
   dates of several zones order as text. */
static int call_commit_date(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    int y, mo, d, h, mi, sec, n = 0, zh = 0, zm = 0;
    char sign = 0;
    const char *z = NULL;
    if (sscanf(value, "%4d-%2d-%2dT%2d:%2d:%2d%n", &y, &mo, &d, &h, &mi, &sec, &n) == 6 && n == 19) {
        z = value + n;
        if (strcmp(z, "Z") == 0)
            sign = '+';
        else if ((z[0] == '+' || z[0] == '-') && strlen(z) == 6 && sscanf(z + 1, "%2d:%2d", &zh, &zm) == 2 &&
                 z[3] == ':' && zh <= 14 && zm < 60)
            sign = z[0];
    }
    if (!sign || y < 1970 || y > 9999 || mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || sec > 60) {
        snprintf(err, errlen, "%s: '%s' is not a date and time with its zone (accepted: ISO 8601 as "
                              "2026-03-01T10:00:00Z or 2026-03-01T11:00:00+01:00, git show -s --format=%%cI)", flag, value);
        return EXIT_USAGE;
    }
    struct tm tm = { .tm_year = y - 1900, .tm_mon = mo - 1, .tm_mday = d, .tm_hour = h, .tm_min = mi, .tm_sec = sec };
    time_t t = timegm(&tm) - (sign == '-' ? -1 : 1) * (time_t)(zh * 3600 + zm * 60);
    struct tm u;
    gmtime_r(&t, &u);
    strftime((char *)dest, 32, "%Y-%m-%dT%H:%M:%SZ", &u);
    return 0;
}

#define FLAG_KIND(DEST)                                                                                     \
    { .name = "--kind", .value = "KIND", .kind = CLI_CALL, .dest = (DEST), .call = call_kind,                    \
      .range = "throughput, accuracy, render, fit or frontier", .def = "every kind", .help = "only the results of this kind" }

#define FLAG_COMMIT_DATE(DEST)                                                                               \
    { .name = "--commit-date", .value = "DATE", .kind = CLI_CALL, .dest = (DEST), .call = call_commit_date,       \
      .range = "ISO 8601 with a zone, e.g. 2026-03-01T10:00:00Z", .def = "none",                                   \
      .help = "add: the date of the commit the runs measured (git show -s --format=%cI), kept in each run's "       \
              "context where it has none; history orders runs by it when every run has one" }

static const char about[] =
    "  The store of runs: an SQLite database (results/history.sqlite unless --db) of result\n"
    "  documents with their context (commit, date, device, driver, build options, machine load),\n"
    "  that brdfbench history reads. add: each RUN_DIR's result files (or a result file or rows\n"
    "  document; 64 names a call), stored once by a content hash (adding a run again stores\n"
    "  nothing), in one transaction that two CI jobs may run at once. list: the stored runs in\n"
    "  date order. export: each stored run as a rows document (brdfbench.rows/1) in --out DIR,\n"
    "  ID-KIND.rows.json each. --kind: add only the files, list or export only the runs, of\n"
    "  that kind. A file that is not a brdfbench store is refused (exit 2; 3 for a damaged\n"
    "  one). No device is used.\n";

/* The name a run is stored under: the folder's last component, or the file's path. */
static void run_name(const char *path, int is_dir, char *out, size_t len)
{
    char p[1024];
    snprintf(p, sizeof p, "%s", path);
    size_t n = strlen(p);
    while (n > 1 && p[n - 1] == '/')
        p[--n] = 0;
    const char *slash = strrchr(p, '/');
    snprintf(out, len, "%s", is_dir && slash ? slash + 1 : p);
}

static int store_add_cmd(int argc, char **argv)
{
    const char *db = STORE_DEFAULT_PATH, *kind = NULL;
    char err[1400], commit_date[32] = "";
    const struct cli_flag flags[] = { CLI_FLAG_DB(&db), FLAG_KIND(&kind), FLAG_COMMIT_DATE(commit_date) };
    const struct cli_command cmd = { .name = "store add",
                                     .synopsis = "RUN_DIR|FILE... [--db FILE] [--kind KIND] [--commit-date DATE]",
                                     .about = about, CLI_TABLE(flags), .max_positional = CLI_MAX_POSITIONAL };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (args.npositional < 1) {
        fprintf(stderr, "brdfbench store add: expected RUN_DIR|FILE... (run folders or result files)\n");
        return EXIT_USAGE;
    }
    int only = kind ? rd_kind_of_name(kind) : -1;
    struct rdoc *docs = calloc(STORE_MAX_DOCS, sizeof *docs);
    char(*names)[256] = calloc(STORE_MAX_DOCS, sizeof *names);
    const char **name_ptrs = calloc(STORE_MAX_DOCS, sizeof *name_ptrs);
    int *added = calloc(STORE_MAX_DOCS, sizeof *added);
    int n = 0, rc = EXIT_OK;
    struct store *s = NULL;
    if (!docs || !names || !name_ptrs || !added) {
        fprintf(stderr, "brdfbench store add: out of memory\n");
        rc = EXIT_RUNTIME;
        goto cleanup;
    }
    /* every input read and checked before the store is opened: a bad one adds nothing */
    for (int a = 0; a < args.npositional; ++a) {
        const char *path = args.positional[a];
        struct stat st;
        int found = 0;
        if (stat(path, &st) != 0) {
            fprintf(stderr, "brdfbench store add: %s: no such file or folder (accepted: a run folder, a result file "
                            "or a rows document)\n", path);
            rc = EXIT_USAGE;
            goto cleanup;
        }
        if (n + RD_KIND_COUNT > STORE_MAX_DOCS) {
            fprintf(stderr, "brdfbench store add: more than %d documents in one add (add them in parts)\n",
                    STORE_MAX_DOCS);
            rc = EXIT_USAGE;
            goto cleanup;
        }
        if (S_ISDIR(st.st_mode)) {
            if (rdoc_read_folder(path, only, &docs[n], &found, err, sizeof err)) {
                fprintf(stderr, "brdfbench store add: %s\n", err);
                rc = EXIT_USAGE;
                goto cleanup;
            }
        } else {
            if (rdoc_read_file(path, &docs[n], err, sizeof err)) {
                fprintf(stderr, "brdfbench store add: %s\n", err);
                rc = EXIT_USAGE;
                goto cleanup;
            }
            found = 1;
            if (only >= 0 && rd_kind_of_name(docs[n].kind) != only) {
                rdoc_free(&docs[n]);
                found = 0;
            }
        }
        if (found == 0) {
            char files[512];
            rd_kind_files(files, sizeof files);
            fprintf(stderr, "brdfbench store add: %s: no result file%s%s (accepted: a run folder with any of %s, "
                            "or such a file or a rows document)\n", path, only >= 0 ? " of kind " : "",
                    only >= 0 ? kind : "", files);
            rc = EXIT_USAGE;
            goto cleanup;
        }
        for (int i = 0; i < found; ++i) {
            if (rd_kind_of_name(docs[n + i].kind) < 0) {   /* a rows document names its kind itself */
                fprintf(stderr, "brdfbench store add: %s: a document of kind '%.40s' (accepted: %s, %s, %s, %s, %s)\n",
                        path, docs[n + i].kind, rd_kind_name(0), rd_kind_name(1), rd_kind_name(2), rd_kind_name(3),
                        rd_kind_name(4));
                n += found;
                rc = EXIT_USAGE;
                goto cleanup;
            }
            if (docs[n + i].oom) {
                fprintf(stderr, "brdfbench store add: %s: out of memory\n", path);
                n += found;
                rc = EXIT_RUNTIME;
                goto cleanup;
            }
            run_name(path, S_ISDIR(st.st_mode), names[n + i], sizeof names[0]);
            if (*commit_date)
                rd_ctx_put(&docs[n + i].ctx, "commit_date", commit_date);
            name_ptrs[n + i] = names[n + i];
        }
        n += found;
    }
    rc = store_open(db, 1, &s, err, sizeof err);
    if (!rc)
        rc = store_add(s, docs, name_ptrs, n, added, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench store add: %s\n", err);
        goto cleanup;
    }
    int news = 0;
    for (int i = 0; i < n; ++i) {
        news += added[i];
        printf("%-14s %-10s %s (%d rows)\n", added[i] ? "added" : "already stored", docs[i].kind, names[i],
               docs[i].nrows);
    }
    printf("%s: %d added, %d already stored\n", db, news, n - news);
cleanup:
    store_close(s);
    for (int i = 0; docs && i < n; ++i)
        rdoc_free(&docs[i]);
    free(docs);
    free(names);
    free(name_ptrs);
    free(added);
    return rc;
}

static int store_list_cmd(int argc, char **argv)
{
    const char *db = STORE_DEFAULT_PATH, *kind = NULL;
    char err[1400];
    const struct cli_flag flags[] = { CLI_FLAG_DB(&db), FLAG_KIND(&kind) };
    const struct cli_command cmd = { .name = "store list", .synopsis = "[--db FILE] [--kind KIND]", .about = about,
                                     CLI_TABLE(flags), .max_positional = 0 };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    struct store *s = NULL;
    struct store_run *runs = NULL;
    int n = 0;
    int rc = store_open(db, 0, &s, err, sizeof err);
    if (!rc)
        rc = store_list(s, kind, &runs, &n, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench store list: %s\n", err);
    } else {
        printf("%4s  %-12s  %-10s  %-20s  %-12s  %5s  %s\n", "id", "hash", "kind", "date", "commit", "rows",
               "run | device");
        for (int i = 0; i < n; ++i)
            printf("%4lld  %.12s  %-10s  %-20s  %-12.12s  %5d  %s | %s\n", runs[i].id, runs[i].hash, runs[i].kind,
                   runs[i].date, runs[i].commit, runs[i].nrows, runs[i].name, runs[i].device);
        printf("%s: %d stored run%s\n", db, n, n == 1 ? "" : "s");
    }
    free(runs);
    store_close(s);
    return rc;
}

static int store_export_cmd(int argc, char **argv)
{
    const char *db = STORE_DEFAULT_PATH, *kind = NULL, *out = NULL;
    char err[1400];
    const struct cli_flag flags[] = {
        CLI_FLAG_DB(&db), FLAG_KIND(&kind),
        CLI_FLAG_OUT(&out, ""),
    };
    const struct cli_command cmd = { .name = "store export", .synopsis = "--out DIR [--db FILE] [--kind KIND]",
                                     .about = about, CLI_TABLE(flags), .max_positional = 0 };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (!out) {
        fprintf(stderr, "brdfbench store export: --out DIR is required (the folder the rows documents go to)\n");
        return EXIT_USAGE;
    }
    struct store *s = NULL;
    struct store_run *runs = NULL;
    int n = 0;
    int rc = store_open(db, 0, &s, err, sizeof err);
    if (!rc)
        rc = store_list(s, kind, &runs, &n, err, sizeof err);
    if (!rc && outdir_prepare(out, "--out", err, sizeof err))
        rc = EXIT_USAGE;
    for (int i = 0; !rc && i < n; ++i) {
        char *text = NULL, name[96], path[4200];
        rc = store_text(s, runs[i].id, &text, err, sizeof err);
        if (rc)
            break;
        /* the kind names the file only when it is one of the kinds (a store written by another
           program could hold any text there) */
        snprintf(name, sizeof name, "%lld-%s.rows.json", runs[i].id,
                 rd_kind_of_name(runs[i].kind) >= 0 ? runs[i].kind : "other");
        if (path_join(path, sizeof path, out, name) || write_file_atomic(path, text, strlen(text), err, sizeof err))
            rc = EXIT_RUNTIME;
        else
            printf("%s\n", path);
        free(text);
    }
    if (rc)
        fprintf(stderr, "brdfbench store export: %s\n", err);
    free(runs);
    store_close(s);
    return rc;
}

int cmd_store(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "add") == 0)
        return store_add_cmd(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "list") == 0)
        return store_list_cmd(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "export") == 0)
        return store_export_cmd(argc - 1, argv + 1);
    /* no subcommand: --help (and the man page, the completions) lists every flag of the three */
    const char *db = STORE_DEFAULT_PATH, *kind = NULL, *out = NULL;
    char err[1400], commit_date[32] = "";
    const struct cli_flag flags[] = {
        CLI_FLAG_DB(&db), FLAG_KIND(&kind), FLAG_COMMIT_DATE(commit_date),
        CLI_FLAG_OUT(&out, ""),
    };
    const struct cli_command cmd = {
        .name = "store", .synopsis = "add RUN_DIR|FILE... | list | export --out DIR  [--db FILE] [--kind KIND]",
        .about = about, CLI_TABLE(flags), .max_positional = 1 };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (args.npositional == 1)
        fprintf(stderr, "brdfbench store: '%s' is not a store command (accepted: add, list, export)\n",
                args.positional[0]);
    else
        fprintf(stderr, "brdfbench store: expected a store command (accepted: add, list, export)\n");
    return EXIT_USAGE;
}
