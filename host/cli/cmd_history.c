/* cmd_history.c - `brdfbench history`: each row's series over the stored runs (store.h) or over
 * run folders and result files named on the command line, its change points (changepoint.h),
 * history.json, history.md and the trend pictures (history.h), and a CI check. No device. */
#define _POSIX_C_SOURCE 200809L
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "history.h"
#include "outdir.h"
#include "rdoc_read.h"
#include "store.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

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

/* The context members a run is ordered and named by. */
static void run_context(struct hist_run *r)
{
    const char *v;
    snprintf(r->date, sizeof r->date, "%s", (v = rd_ctx_get(&r->doc.ctx, "date")) ? v : "");
    snprintf(r->commit_date, sizeof r->commit_date, "%s", (v = rd_ctx_get(&r->doc.ctx, "commit_date")) ? v : "");
    snprintf(r->commit, sizeof r->commit, "%s", (v = rd_ctx_get(&r->doc.ctx, "git_revision")) ? v : "");
    snprintf(r->device, sizeof r->device, "%s", (v = rd_ctx_get(&r->doc.ctx, "device")) ? v : "");
}

/* The runs of the paths named: a run folder gives its file of the kind, a file itself. */
static int runs_from_paths(struct hist_set *h, const struct cli_args *args, int kind, char *err, size_t errlen)
{
    h->runs = calloc((size_t)args->npositional, sizeof *h->runs);
    if (!h->runs) {
        snprintf(err, errlen, "out of memory");
        return EXIT_RUNTIME;
    }
    for (int a = 0; a < args->npositional; ++a) {
        const char *path = args->positional[a];
        struct hist_run *r = &h->runs[h->nruns];
        struct stat st;
        int found = 0;
        if (stat(path, &st) != 0) {
            snprintf(err, errlen, "%s: no such file or folder (accepted: a run folder, a result file or a rows document)",
                     path);
            return EXIT_USAGE;
        }
        if (S_ISDIR(st.st_mode)) {
            /* the folder's file of the kind (only that one is opened) */
            struct rdoc *tmp = calloc(RD_KIND_COUNT, sizeof *tmp);
            if (!tmp) {
                snprintf(err, errlen, "out of memory");
                return EXIT_RUNTIME;
            }
            int bad = rdoc_read_folder(path, kind, tmp, &found, err, errlen);
            if (!bad && found)
                r->doc = tmp[0];
            free(tmp);
            if (bad)
                return EXIT_USAGE;
        } else {
            if (rdoc_read_file(path, &r->doc, err, errlen))
                return EXIT_USAGE;
            found = 1;
            if (rd_kind_of_name(r->doc.kind) != kind) {
                snprintf(err, errlen, "%s: a result of kind %s, not %s (accepted: --kind %s)", path, r->doc.kind,
                         rd_kind_name(kind), r->doc.kind);
                rdoc_free(&r->doc);
                return EXIT_USAGE;
            }
        }
        if (!found) {
            snprintf(err, errlen, "%s: no %s in the folder (accepted: a run folder with one, or --kind)", path,
                     rd_kind_file(kind));
            return EXIT_USAGE;
        }
        h->nruns++;
        char p[1024];
        snprintf(p, sizeof p, "%s", path);
        size_t n = strlen(p);
        while (n > 1 && p[n - 1] == '/')
            p[--n] = 0;
        const char *slash = strrchr(p, '/');
        snprintf(r->name, sizeof r->name, "%s", S_ISDIR(st.st_mode) && slash ? slash + 1 : p);
        run_context(r);
    }
    history_order(h);
    return 0;
}

/* The stored runs of the kind, in the store's order (commit date, else run date). */
static int runs_from_store(struct hist_set *h, const char *db, int kind, char *err, size_t errlen)
{
    struct store *s = NULL;
    struct store_run *list = NULL;
    int n = 0;
    int rc = store_open(db, 0, &s, err, errlen);
    if (!rc)
        rc = store_list(s, rd_kind_name(kind), &list, &n, err, errlen);
    if (!rc && n > 0 && !(h->runs = calloc((size_t)n, sizeof *h->runs))) {
        snprintf(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
    }
    for (int i = 0; !rc && i < n; ++i) {
        struct hist_run *r = &h->runs[h->nruns];
        rc = store_read(s, list[i].id, &r->doc, err, errlen);
        if (rc)
            break;
        h->nruns++;
        snprintf(r->name, sizeof r->name, "%s", list[i].name);
        run_context(r);
    }
    if (!rc)
        history_order(h);   /* the same order as for files (stable: the store's order among equals) */
    free(list);
    store_close(s);
    return rc;
}

int cmd_history(int argc, char **argv)
{
    const char *db = NULL, *out = "results/history";
    int kind = RD_KIND_THROUGHPUT;
    double slower_pct = -1, alpha = 0.05, min_change_pct = -1;
    char err[1600];
    const struct cli_flag flags[] = {
        CLI_FLAG_DB(&db),
        { .name = "--kind", .value = "KIND", .kind = CLI_CALL, .dest = &kind, .call = call_kind,
          .range = "throughput, accuracy, render, fit or frontier", .def = "throughput",
          .help = "only the results of this kind" },
        CLI_FLAG_OUT(&out, "results/history"),
        /* the same words as compare's flags: here the baseline is the segment before the latest run's */
        { .name = "--fail-if-slower", .value = "PCT", .kind = CLI_DOUBLE, .dest = &slower_pct, .min = 0, .max = 100,
          .help = "exit 1 naming every rate that is slower than the baseline (by the test) by more than PCT percent",
          .def = "" },
        { .name = "--alpha", .value = "P", .kind = CLI_DOUBLE, .dest = &alpha, .min = 1e-6, .max = 0.5,
          .help = "the rank test's level", .range = "1e-6 to 0.5" },
        { .name = "--min-change", .value = "PCT", .kind = CLI_DOUBLE, .dest = &min_change_pct, .min = 0, .max = 100,
          .help = "the smallest change a rate's verdict calls (default: --fail-if-slower's PCT, else 10)", .def = "" },
    };
    const struct cli_command cmd = {
        .name = "history",
        .synopsis = "[--db FILE | RUN_DIR|FILE...] [--kind KIND] [--out DIR] [--fail-if-slower PCT]",
        .about = "  Each row (model, variant, n mode, device; one metric) over many runs: the stored runs of\n"
                 "  --db (results/history.sqlite when no run is named) or the run folders, result files and\n"
                 "  rows documents named, ordered by commit date (where every run's context has one) or run\n"
                 "  date. A timed row changes where binary segmentation splits its runs by compare's rule:\n"
                 "  the Mann-Whitney test of the repetitions after against before, and a t test of the\n"
                 "  runs' levels against how much whole runs differ, both Bonferroni-corrected over the\n"
                 "  segment's splits, give p < --alpha and the Hodges-Lehmann ratio is beyond\n"
                 "  --min-change. Writes history.json (changes: label, run, commit, ratio, interval, p),\n"
                 "  history.md and the trend pictures into --out. --fail-if-slower: the baseline is the\n"
                 "  segment before the latest run's. No device is used.\n",
        CLI_TABLE(flags),
        .max_positional = CLI_MAX_POSITIONAL,
    };
    struct cli_args args;
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (db && args.npositional > 0) {
        fprintf(stderr, "brdfbench history: --db and run folders or files given together (accepted: one of them)\n");
        return EXIT_USAGE;
    }
    struct hist_set h;
    memset(&h, 0, sizeof h);
    cp_defaults(&h.cp);
    h.cp.alpha = alpha;
    /* as compare: the minimum change is --fail-if-slower's when only that is given */
    h.cp.min_change = (min_change_pct >= 0 ? min_change_pct : slower_pct >= 0 ? slower_pct : 10) / 100;
    char source[1100];
    int rc;
    if (args.npositional > 0) {
        snprintf(source, sizeof source, "%d run folders or files", args.npositional);
        rc = runs_from_paths(&h, &args, kind, err, sizeof err);
    } else {
        if (!db)
            db = STORE_DEFAULT_PATH;
        snprintf(source, sizeof source, "%s", db);
        rc = runs_from_store(&h, db, kind, err, sizeof err);
    }
    if (!rc && h.nruns == 1 && args.npositional == 0) {
        /* a store's first run (a CI job's first day): no series yet, nothing to compare or fail */
        printf("history: %s holds 1 run of kind %s: no series yet (a history takes 2 or more); nothing written\n",
               source, rd_kind_name(kind));
        history_free(&h);
        return 0;
    }
    if (!rc && h.nruns < 2) {
        snprintf(err, sizeof err, "%s holds %d run%s of kind %s (a history takes 2 or more)", source, h.nruns,
                 h.nruns == 1 ? "" : "s", rd_kind_name(kind));
        rc = EXIT_USAGE;
    }
    if (!rc && outdir_prepare(out, "--out", err, sizeof err))
        rc = EXIT_USAGE;
    if (!rc && history_evaluate(&h)) {
        snprintf(err, sizeof err, "out of memory");
        rc = EXIT_RUNTIME;
    }
    if (!rc && history_write(&h, out, source, err, sizeof err))
        rc = EXIT_RUNTIME;
    if (rc) {
        fprintf(stderr, "brdfbench history: %s\n", err);
        history_free(&h);
        return rc;
    }
    int nchanges = 0;
    for (int i = 0; i < h.nrows; ++i)
        nchanges += h.rows[i].nchanges;
    printf("history: %d runs (by %s), %d rows, %d change%s\n", h.nruns, h.order, h.nrows, nchanges,
           nchanges == 1 ? "" : "s");
    for (int i = 0; i < h.nrows; ++i)
        for (int c = 0; c < h.rows[i].nchanges; ++c) {
            const struct hist_row *r = &h.rows[i];
            const struct hist_change *x = &r->changes[c];
            printf("  %s%s%s %s: from run %d (%s): %.3gx", r->device, *r->device ? " | " : "", r->label, r->metric,
                   x->at + 1, h.runs[x->at].name, x->ratio);
            if (x->lo == x->lo)
                printf(" [%.3g, %.3g], p = %.2g", x->lo, x->hi, x->p);
            printf("\n");
        }
    int timed = 0;
    for (int i = 0; i < h.nrows; ++i)
        timed += h.rows[i].timed;
    printf("written: %s/history.json, history.md, history.png%s\n", out, timed ? ", history_normalised.png" : "");
    if (slower_pct >= 0) {
        char *lines = NULL;
        int n = history_slower(&h, slower_pct, &lines);
        if (n > 0) {
            fprintf(stderr, "%s", lines ? lines : "");
            fprintf(stderr, "brdfbench history: %d row%s slower than %g%% in the latest run's segment\n", n,
                    n == 1 ? "" : "s", slower_pct);
            rc = EXIT_GATE_FAIL;
        }
        free(lines);
    }
    history_free(&h);
    return rc;
}
