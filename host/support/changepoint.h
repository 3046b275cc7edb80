/* changepoint.h - where a series of runs changed: binary segmentation with compare's rule.
 *
 * A series is one row's figure over T runs in order, each run a sample (its repetitions, on a
 * log scale: a ratio is a shift). A segment [a, b) of runs is split at k (the runs a..k-1
 * before, k..b-1 after) when
 *  - the Mann-Whitney test of the pooled repetitions after against those before, and
 *  - the run-level test: the mean of the runs' levels (each run's median) after against
 *    before, over the spread of whole runs (Student's t; the spread from the series'
 *    successive differences, which a step moves only once), since the repetitions of one run
 *    share its drift and are not independent across runs,
 * both give p * m < alpha, m the splits the segment offers (Bonferroni over the splits tried),
 * AND the Hodges-Lehmann shift of the repetitions, a ratio, is beyond the minimum change:
 * |log ratio| > log(1 + min_change). Significance and size, as compare decides faster or
 * slower: a large shift the runs cannot tell from noise is no change, and neither is a small
 * real one. Of the splits that pass, the one with the smallest p (then the largest shift) is
 * taken, and both halves are searched again, until no split passes.
 *
 * A segment inside the series holds at least min_seg runs (2 by default), so that one odd run
 * (an outlier: a run disturbed by other work) is not a segment of its own; only the latest
 * run may stand alone, so that a regression is seen in the run that brought it.
 *
 * Once every change is found, each one's ratio, interval and p are taken again between the
 * segments on either side of it (the search found it against a wider segment, which may hold
 * other changes). The interval is the Hodges-Lehmann shift's distribution-free interval at
 * level 1 - alpha / m, as a ratio. Calibration: scripts/bench_history_calibration.sh. */
#ifndef BRDF_CHANGEPOINT_H
#define BRDF_CHANGEPOINT_H

#define CP_MAX_CHANGES 64

struct cp_sample {
    const double *v;   /* the run's values (positive: rates), or NULL */
    int n;
};

struct cp_settings {
    double alpha;        /* family-wise level over a segment's splits (0.05) */
    double min_change;   /* the smallest relative change called (0.10) */
    int min_seg;         /* the fewest runs of a segment inside the series (2) */
};
void cp_defaults(struct cp_settings *s);

struct cp_change {
    int at;              /* the first run after the change */
    double ratio;        /* after / before (Hodges-Lehmann on the logs, exponentiated) */
    double lo, hi;       /* its interval */
    double p;            /* Bonferroni-adjusted p of the split: the larger of the two tests' */
    int m;               /* the splits tried in the segment where it was found (the correction) */
};

/* The changes of the series runs[0..T), in order of `at`. Returns their count (0..CP_MAX_CHANGES),
 * or -1 when out of memory. Runs with no positive finite value are left out of the tests (they
 * belong to no side). */
int cp_find(const struct cp_sample *runs, int T, const struct cp_settings *s, struct cp_change *out);

/* The ratio of the last segment to the one before it (the latest change's), NAN when there is
 * no change. */
double cp_latest_ratio(const struct cp_change *c, int n);

#endif
