/* runner.h - the one measurement runner: every launch brdfbench times goes through it
 * (docs/architecture.md, habit 7; docs/timing.md).
 *
 * A run is a set of items (a kernel in one launch shape, the C baseline, a fixed sweep...),
 * each a function that does `iters` units of work once and returns the seconds it took. The
 * runner:
 *   1. warms every item up with its exact launch shape (one launch of 1 iteration);
 *   2. calibrates the iterations of every calibrated item until one launch takes min_time
 *      (grown from 1, scaled, checked once more at the scaled count);
 *   3. times `rounds` rounds; each round launches every item once, in a fresh random order
 *      (seeded, so a run can be replayed), and the reference item at the round's start,
 *      middle and end;
 *   4. keeps every repetition: its seconds, its rate (work / seconds), and its rate over the
 *      round's reference rate (the median of the reference's three): the normalised rate. A
 *      machine slowed down for a while slows the reference too, and the ratio cancels it;
 *   5. on a CPU device, checks each launch for preemption: the process's CPU time over the
 *      launch short of busy_fraction x wall time x the device's threads means another process
 *      had the cores. Such a launch is retried up to max_retries times (not in a round that
 *      follows one where most launches were preempted: persistent contention, where retrying
 *      only costs time); retries and repetitions kept disturbed are counted per item and for
 *      the run. On such a device the rates per CPU second (work / the process's CPU time over
 *      the launch) are kept too, normalised the same way: another process's share of the
 *      cores stretches the wall time of a launch but hardly its CPU time.
 * The clock is injectable (struct runner_clock) so that the tests drive the runner with a
 * fake clock and fake launches. */
#ifndef BRDF_RUNNER_H
#define BRDF_RUNNER_H

#include <stddef.h>
#include <stdint.h>

#define RUNNER_MAX_ROUNDS 1000
#define RUNNER_MAX_ITERS (1L << 24)
#define RUNNER_REASON 256
#define RUNNER_DEFAULT_BUSY 0.6
#define RUNNER_DEFAULT_RETRIES 2
#define RUNNER_REF_PER_ROUND 3   /* reference launches per round: at its start, middle and end */

/* One launch of an item: does iters units of work and stores the seconds it took (the
 * device's profiling time, or wall time where there is none). Returns 0, or -1 with reason
 * filled (the item then fails; the run goes on). */
typedef int (*runner_launch_fn)(void *ctx, long iters, double *seconds, char *reason, size_t reason_len);

struct runner_item {
    /* set by the caller */
    const char *name;                /* for messages */
    runner_launch_fn launch;
    void *ctx;
    int calibrate;                   /* 1: iterations calibrated to min_time; 0: iters as given */
    long iters;                      /* in when !calibrate; the calibrated count when calibrate */
    double work_per_iter;            /* units of work (evaluations, flops, pixels) of one iteration */
    int cpu_threads;                 /* threads a launch keeps busy (0: no preemption check) */
    /* filled by runner_run */
    int ok;
    char reason[RUNNER_REASON];
    int nreps;
    double *seconds;                 /* [nreps], malloc'd: each repetition, in round order */
    double *wall;                    /* [nreps]: the wall time around each (the runner's clock) */
    double *cpu;                     /* [nreps]: the process's CPU time over each */
    double *rate;                    /* [nreps]: work / seconds */
    double *norm;                    /* [nreps]: rate / the reference's rate in the same round (NULL: no reference) */
    double *cpu_norm;                /* [nreps]: the same with both rates per CPU second (work / the process's CPU
                                        time): on a CPU device, what another process's share of the cores leaves
                                        alone (NULL: no reference, or cpu_threads 0) */
    int retries;                     /* launches retried for preemption */
    int disturbed;                   /* repetitions kept although still preempted after the retries */
};

/* The clocks the runner reads: wall time and the process's CPU time (user + system, every
 * thread), in seconds. NULL members: the real clocks (CLOCK_MONOTONIC, getrusage). */
struct runner_clock {
    double (*wall)(void *ctx);
    double (*cpu)(void *ctx);
    void *ctx;
};

struct runner {
    struct runner_item *items;
    int nitems;
    int reference;                   /* index of the reference item, or -1 */
    int rounds;                      /* 1..RUNNER_MAX_ROUNDS */
    double min_time;                 /* seconds a calibrated launch takes at least */
    int max_retries;                 /* per repetition, for preemption */
    double busy_fraction;            /* preempted: CPU < busy_fraction x wall x cpu_threads */
    uint64_t seed;                   /* of the rounds' orders */
    struct runner_clock clock;
    /* optional: called after each round (progress lines) */
    void (*progress)(void *ctx, int round_done, int rounds);
    void *progress_ctx;
    /* filled by runner_run */
    int *order;                      /* [rounds x round_len], malloc'd: the launch order of each round */
    int round_len;                   /* launches per round: the items, the reference RUNNER_REF_PER_ROUND times */
    long launches, retried, disturbed;
    int persistent_rounds;           /* rounds after which most launches had been preempted: no retries next */
    /* internal */
    long round_launches, round_preempted;
    int persistent;
};

/* Defaults: no reference, 5 rounds, min_time 0.02 s, 2 retries, busy fraction 0.6, a fixed seed. */
void runner_init(struct runner *r, struct runner_item *items, int nitems);
/* Runs the protocol above. Returns 0 (items that failed say so in their ok and reason), or
 * -1 when out of memory. */
int runner_run(struct runner *r);
/* Frees what runner_run allocated (the items' arrays and the order). */
void runner_release(struct runner *r);

/* The process's CPU time in seconds (getrusage, every thread). */
double runner_process_cpu_seconds(void);
/* The machine's steal time so far, in seconds (/proc/stat's steal column over USER_HZ), or -1. */
double runner_steal_seconds(void);
/* The load average line of /proc/loadavg (first three fields), or "unknown". */
void runner_loadavg(char *buf, size_t len);

#endif
