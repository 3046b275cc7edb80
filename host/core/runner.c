/* runner.c - the one measurement runner (runner.h): warm-up, calibration, interleaved rounds
 * with a reference item, preemption retries, every repetition kept. */
#define _POSIX_C_SOURCE 200809L
#include "runner.h"
#include "stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

double runner_process_cpu_seconds(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return NAN;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static double real_wall(void *ctx)
{
    (void)ctx;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double real_cpu(void *ctx)
{
    (void)ctx;
    return runner_process_cpu_seconds();
}

double runner_steal_seconds(void)
{
    FILE *f = fopen("/proc/stat", "r");
    if (!f)
        return -1;
    unsigned long long v[8] = { 0 };
    int n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                   &v[7]);
    fclose(f);
    long hz = sysconf(_SC_CLK_TCK);
    if (n != 8 || hz <= 0)
        return -1;
    return (double)v[7] / (double)hz;
}

void runner_loadavg(char *buf, size_t len)
{
    snprintf(buf, len, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3)
        snprintf(buf, len, "%.2f %.2f %.2f", a, b, c);
    fclose(f);
}

void runner_init(struct runner *r, struct runner_item *items, int nitems)
{
    memset(r, 0, sizeof *r);
    r->items = items;
    r->nitems = nitems;
    r->reference = -1;
    r->rounds = 5;
    r->min_time = 0.02;
    r->max_retries = RUNNER_DEFAULT_RETRIES;
    r->busy_fraction = RUNNER_DEFAULT_BUSY;
    r->seed = 0x9e3779b97f4a7c15ULL;
}

/* splitmix64: the rounds' shuffles (independent of the probe points' LCG). */
static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static void shuffle(int *v, int n, uint64_t *state)
{
    for (int i = n - 1; i > 0; --i) {
        int j = (int)(next_random(state) % (uint64_t)(i + 1));
        int t = v[i];
        v[i] = v[j];
        v[j] = t;
    }
}

static void item_fail(struct runner_item *it, const char *why)
{
    if (it->ok) {
        it->ok = 0;
        if (!it->reason[0])
            snprintf(it->reason, sizeof it->reason, "%s", why);
    }
}

/* One launch with its CPU-time check: 0 and *seconds, *preempted; or -1 (the item failed). */
static int launch_once(struct runner *r, struct runner_item *it, long iters, double *seconds, int *preempted,
                       double *wall_out, double *cpu_out)
{
    double w0 = r->clock.wall(r->clock.ctx), c0 = r->clock.cpu(r->clock.ctx);
    char why[RUNNER_REASON] = "";
    if (it->launch(it->ctx, iters, seconds, why, sizeof why)) {
        item_fail(it, why[0] ? why : "the launch failed");
        return -1;
    }
    double wall = r->clock.wall(r->clock.ctx) - w0, cpu = r->clock.cpu(r->clock.ctx) - c0;
    ++r->launches;
    if (!(*seconds > 0) || !isfinite(*seconds)) {
        item_fail(it, "the timer gave no time for a launch");
        return -1;
    }
    *wall_out = wall;
    *cpu_out = cpu;
    *preempted = it->cpu_threads > 0 && isfinite(cpu) && wall > 0 &&
                 cpu < r->busy_fraction * wall * (double)it->cpu_threads;
    return 0;
}

/* A repetition: launched again while preempted, up to max_retries times; not while the
   contention is persistent (most of the previous round's launches preempted), when a retry
   would only cost time: those repetitions are counted as disturbed. */
static int timed_rep(struct runner *r, struct runner_item *it, double *seconds, double *wall, double *cpu,
                     int *disturbed)
{
    int preempted = 0;
    for (int attempt = 0;; ++attempt) {
        if (launch_once(r, it, it->iters, seconds, &preempted, wall, cpu))
            return -1;
        ++r->round_launches;
        r->round_preempted += preempted;
        if (!preempted || attempt >= r->max_retries || r->persistent)
            break;
        ++it->retries;
        ++r->retried;
    }
    *disturbed = preempted;
    return 0;
}

static long scaled_iters(long iters, double t, double min_time)
{
    return (long)fmin((double)RUNNER_MAX_ITERS, fmax(1.0, ceil((double)iters * min_time / t)));
}

/* Iterations grown until a launch takes a quarter of min_time, then scaled to min_time and
   checked: a launch at the scaled count short of half of min_time (the growth step landed on
   a busy moment) is scaled again, twice at most. */
static int calibrate(struct runner *r, struct runner_item *it)
{
    double t, w, cw;
    int pre;
    long iters = 1;
    for (;;) {
        if (launch_once(r, it, iters, &t, &pre, &w, &cw))
            return -1;
        if (t >= 0.25 * r->min_time || iters >= RUNNER_MAX_ITERS)
            break;
        double grow = fmin(fmax(0.5 * r->min_time / t, 2.0), 1000.0);
        iters = (long)fmin((double)RUNNER_MAX_ITERS, ceil((double)iters * grow));
    }
    iters = scaled_iters(iters, t, r->min_time);
    for (int k = 0; k < 2 && iters < RUNNER_MAX_ITERS; ++k) {
        if (launch_once(r, it, iters, &t, &pre, &w, &cw))
            return -1;
        if (t >= 0.5 * r->min_time)
            break;
        iters = scaled_iters(iters, t, r->min_time);
    }
    it->iters = iters;
    return 0;
}

/* One timed repetition of item i, kept in its arrays; its rate, or NAN when it failed. */
static double take_rep(struct runner *r, int i)
{
    struct runner_item *it = &r->items[i];
    if (!it->ok)
        return NAN;
    double t, w, cpu;
    int dist = 0;
    if (timed_rep(r, it, &t, &w, &cpu, &dist))
        return NAN;
    it->cpu[it->nreps] = cpu;
    it->disturbed += dist;
    r->disturbed += dist;
    it->seconds[it->nreps] = t;
    it->wall[it->nreps] = w;
    it->rate[it->nreps] = it->work_per_iter * (double)it->iters / t;
    return it->rate[it->nreps++];
}

int runner_run(struct runner *r)
{
    if (!r->clock.wall)
        r->clock.wall = real_wall;
    if (!r->clock.cpu)
        r->clock.cpu = real_cpu;
    int n = r->nitems, rounds = r->rounds < 1 ? 1 : r->rounds > RUNNER_MAX_ROUNDS ? RUNNER_MAX_ROUNDS : r->rounds;
    int has_ref = r->reference >= 0 && r->reference < n;
    int refs = has_ref ? RUNNER_REF_PER_ROUND : 0;
    r->round_len = n - (has_ref ? 1 : 0) + refs;
    r->order = malloc((size_t)rounds * (size_t)(r->round_len > 0 ? r->round_len : 1) * sizeof *r->order);
    int *others = malloc((size_t)(n > 0 ? n : 1) * sizeof *others);
    double *round_rate = malloc((size_t)(n > 0 ? n : 1) * sizeof *round_rate);
    if (!r->order || !others || !round_rate) {
        free(others);
        free(round_rate);
        return -1;
    }
    for (int i = 0; i < n; ++i) {
        struct runner_item *it = &r->items[i];
        size_t cap = (size_t)rounds * (size_t)(has_ref && i == r->reference ? refs : 1);
        it->ok = 1;
        it->reason[0] = '\0';
        it->nreps = it->retries = it->disturbed = 0;
        it->seconds = calloc(cap, sizeof *it->seconds);
        it->rate = calloc(cap, sizeof *it->rate);
        it->wall = calloc(cap, sizeof *it->wall);
        it->cpu = calloc(cap, sizeof *it->cpu);
        it->norm = has_ref ? calloc(cap, sizeof *it->norm) : NULL;
        it->cpu_norm = has_ref && it->cpu_threads > 0 ? calloc(cap, sizeof *it->cpu_norm) : NULL;
        if (!it->seconds || !it->rate || !it->wall || !it->cpu || (has_ref && !it->norm) ||
            (has_ref && it->cpu_threads > 0 && !it->cpu_norm)) {
            free(others);
            free(round_rate);
            return -1;
        }
    }
    /* warm-up with the exact launch shape, then calibration */
    for (int i = 0; i < n; ++i) {
        struct runner_item *it = &r->items[i];
        double t, w, cw;
        int pre;
        if (launch_once(r, it, 1, &t, &pre, &w, &cw))
            continue;
        if (it->calibrate)
            calibrate(r, it);
        else if (it->iters < 1)
            it->iters = 1;
    }
    uint64_t state = r->seed;
    for (int k = 0; k < rounds; ++k) {
        /* the other items in a fresh random order, the reference at the start, the middle and
           the end of the round: the median of its three rates is the round's reference rate */
        int m = 0;
        for (int i = 0; i < n; ++i)
            if (!has_ref || i != r->reference)
                others[m++] = i;
        shuffle(others, m, &state);
        int *ord = r->order + (size_t)k * (size_t)r->round_len, len = 0;
        double ref_rates[RUNNER_REF_PER_ROUND], ref_cpu[RUNNER_REF_PER_ROUND];
        int nref = 0;
        for (int q = 0; q <= m; ++q) {
            while (nref < refs && q == (m * nref) / (refs - 1)) {
                ord[len++] = r->reference;
                struct runner_item *ri = &r->items[r->reference];
                ref_rates[nref] = take_rep(r, r->reference);
                ref_cpu[nref] = isfinite(ref_rates[nref]) && ri->cpu[ri->nreps - 1] > 0
                                    ? ri->work_per_iter * (double)ri->iters / ri->cpu[ri->nreps - 1] : NAN;
                ++nref;
            }
            if (q < m) {
                ord[len++] = others[q];
                round_rate[others[q]] = take_rep(r, others[q]);
            }
        }
        if (has_ref) {
            double ref = stats_median_finite(ref_rates, (size_t)nref);
            double refc = stats_median_finite(ref_cpu, (size_t)nref);
            for (int i = 0; i < n; ++i) {
                struct runner_item *it = &r->items[i];
                int first = i == r->reference ? it->nreps - nref : it->nreps - 1;
                if (!it->ok || it->nreps == 0 || (i != r->reference && !isfinite(round_rate[i])))
                    continue;
                for (int j = first < 0 ? 0 : first; j < it->nreps; ++j) {
                    it->norm[j] = ref > 0 ? it->rate[j] / ref : NAN;
                    if (it->cpu_norm)
                        it->cpu_norm[j] = refc > 0 && it->cpu[j] > 0
                                              ? it->work_per_iter * (double)it->iters / it->cpu[j] / refc : NAN;
                }
            }
        }
        r->persistent = r->round_launches > 0 && 2 * r->round_preempted > r->round_launches;
        r->persistent_rounds += r->persistent;
        r->round_launches = r->round_preempted = 0;
        if (r->progress)
            r->progress(r->progress_ctx, k + 1, rounds);
    }
    free(others);
    free(round_rate);
    r->rounds = rounds;
    return 0;
}

void runner_release(struct runner *r)
{
    for (int i = 0; i < r->nitems; ++i) {
        struct runner_item *it = &r->items[i];
        free(it->seconds);
        free(it->rate);
        free(it->wall);
        free(it->cpu);
        free(it->norm);
        free(it->cpu_norm);
        it->cpu_norm = NULL;
        it->seconds = it->rate = it->wall = it->cpu = it->norm = NULL;
    }
    free(r->order);
    r->order = NULL;
}
