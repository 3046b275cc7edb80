/* history.h - each row's series over many runs and where it changed (brdfbench history).
 *
 * The runs are result documents of one kind (throughput by default), from the store of runs
 * (store.h) or from run folders and files, ordered by the commit's date where every run's
 * context has one ("commit_date"), else by the run's date. A row of the history is one figure
 * of one row of the documents: its kind, device (the row's, or the run's), label (model,
 * variant, n mode, ...) and metric. Its series is one sample per run: the repetitions
 * normalised by the reference kernel where every run has them (the machine's drift cancels,
 * as in compare), else the absolute repetitions, else the figure alone.
 *
 * Timed figures get change points by binary segmentation with compare's rule and a run-level
 * test (changepoint.h); other figures (accuracy) a change wherever the figure moves in its 4th
 * significant digit from the run before, as compare calls an accuracy figure changed.
 *
 * Written: history.json (brdfbench.history/1: the runs, each row's medians and changes, and
 * every change as {label, run, commit, ratio, interval, p}), history.md, history.png (small
 * multiples: each row's absolute rate per run with its min and max, its normalised rate
 * scaled to the absolute one's level at its first run, a dotted line at each change) and
 * history_normalised.png (every row's rate over its first segment's, one plot). */
#ifndef BRDF_HISTORY_H
#define BRDF_HISTORY_H

#include <stddef.h>

#include "changepoint.h"
#include "rdoc.h"


struct hist_run {
    char name[256];        /* the run folder's name, the file, or the store's name for it */
    char date[64], commit_date[64], commit[64], device[RD_TEXT];
    struct rdoc doc;
};

struct hist_change {
    int at;                /* index of the first run after it */
    double ratio, lo, hi, p;   /* lo, hi, p: NAN for a figure that is not timed */
};

struct hist_row {
    char kind[32], device[RD_TEXT], label[RD_TEXT], metric[RD_NAME], unit[24];
    int direction, timed;
    char basis[16];        /* "normalised", "absolute" or "value" */
    double *median;        /* per run: the sample's median, NAN where the run lacks the row */
    double *lo, *hi;       /* per run: the sample's min and max */
    double *nmedian;       /* per run: the normalised repetitions' median (NAN: none) */
    struct hist_change changes[CP_MAX_CHANGES];
    int nchanges;
};

struct hist_set {
    struct hist_run *runs;     /* in order (history_order sorts them) */
    int nruns;
    char order[16];            /* "commit date" or "run date" */
    struct hist_row *rows;
    int nrows;
    struct cp_settings cp;
};

/* Sorts the runs by commit date when every run has one, else by run date (stable). */
void history_order(struct hist_set *h);
/* Builds the rows and finds their changes. Returns 0, or 3 when out of memory. */
int history_evaluate(struct hist_set *h);
/* The rows whose latest run sits in a segment slower than the one before by more than pct
 * percent (timed, higher-is-better figures), one line each into *out (malloc'd). Returns
 * their count. */
int history_slower(const struct hist_set *h, double pct, char **out);
/* history.json, history.md, history.png and history_normalised.png in dir. Returns 0, or 3
 * with err. */
int history_write(const struct hist_set *h, const char *dir, const char *source, char *err, size_t errlen);
void history_free(struct hist_set *h);

#endif
