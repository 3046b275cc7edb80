/* test_runner.c - the measurement runner (host/core/runner.h) driven by a fake clock and fake
 * launches: the rounds' orders (every item once, the reference at a round's start, middle and
 * end, a fresh order per round, the same orders for the same seed), the calibration's
 * iteration count worked by hand, drift cancelled exactly by the normalised rates, preemption
 * retries and persistent contention, and a failing item. No device; no time is asserted. */
#include "check.h"
#include "runner.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The fake machine: wall and CPU clocks advanced by the launches. */
struct fake {
    double wall, cpu;
    double slow;            /* every launch takes slow x its cost (a machine slowed down) */
    int threads;            /* threads a launch keeps busy */
    long launches;
    long preempt_every;     /* every k-th launch gets a tenth of its CPU time (0: never) */
    int always_preempted;
};

static double fake_wall(void *ctx) { return ((struct fake *)ctx)->wall; }
static double fake_cpu(void *ctx) { return ((struct fake *)ctx)->cpu; }

struct fake_item {
    struct fake *m;
    double cost;            /* seconds per iteration */
    int fail_after;         /* launches before it fails (0: never) */
    int launched;
    long last_iters;
};

static int fake_launch(void *ctx, long iters, double *seconds, char *reason, size_t len)
{
    struct fake_item *it = ctx;
    struct fake *m = it->m;
    if (it->fail_after && ++it->launched > it->fail_after) {
        snprintf(reason, len, "the fake launch failed");
        return -1;
    }
    ++m->launches;
    it->last_iters = iters;
    double t = (double)iters * it->cost * m->slow;
    int pre = m->always_preempted || (m->preempt_every && m->launches % m->preempt_every == 0);
    m->wall += t;
    m->cpu += t * m->threads * (pre ? 0.1 : 1.0);
    *seconds = t;
    return 0;
}

/* A slowdown from the 3rd round on (the fake clock's progress hook). */
static void slow_down(void *ctx, int done, int rounds)
{
    (void)rounds;
    if (done == 2)
        ((struct fake *)ctx)->slow = 2.0;
}

/* A case's fake machine, its runner and up to 5 items. */
struct rig {
    struct fake m;
    struct runner r;
    struct runner_item items[5];
    struct fake_item fi[5];
};

/* The runner over n fake items of the given costs on the rig's machine, item 0 the reference,
   for `rounds` rounds (0: the runner's default). */
static void setup(struct rig *g, int n, const double *costs, int rounds)
{
    for (int i = 0; i < n; ++i) {
        g->fi[i] = (struct fake_item){ &g->m, costs[i], 0, 0, 0 };
        g->items[i] = (struct runner_item){ .name = "fake", .launch = fake_launch, .ctx = &g->fi[i], .calibrate = 1,
                                            .work_per_iter = 1000.0 * (i + 1), .cpu_threads = g->m.threads };
    }
    runner_init(&g->r, g->items, n);
    g->r.clock = (struct runner_clock){ fake_wall, fake_cpu, &g->m };
    g->r.min_time = 0.02;
    g->r.reference = 0;
    if (rounds)
        g->r.rounds = rounds;
}

int main(void)
{
    const double costs[5] = { 1e-4, 2e-4, 5e-5, 3e-4, 1e-3 };

    /* Orders and calibration. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 2, 0, 0, 0 } };
        setup(&g, 5, costs, 10);
        CHECK(runner_run(&g.r) == 0, "runner_run");
        /* 4 other items and the reference 3 times per round */
        CHECK(g.r.round_len == 7, "round length %d, expected 4 + 3", g.r.round_len);
        int distinct_orders = 0;
        for (int k = 0; k < g.r.rounds; ++k) {
            const int *o = g.r.order + k * g.r.round_len;
            int seen[5] = { 0 };
            for (int q = 0; q < g.r.round_len; ++q)
                seen[o[q]]++;
            CHECK(seen[0] == 3 && seen[1] == 1 && seen[2] == 1 && seen[3] == 1 && seen[4] == 1,
                  "round %d: every item once, the reference three times", k);
            /* the reference at the start, after the first m/2 = 2 others, and at the end */
            CHECK(o[0] == 0 && o[3] == 0 && o[6] == 0, "round %d: reference at positions 0, 3, 6", k);
            if (k > 0 && memcmp(o, o - g.r.round_len, sizeof *o * (size_t)g.r.round_len) != 0)
                ++distinct_orders;
        }
        CHECK(distinct_orders >= 5, "a fresh order each round: %d of 9 rounds differ from the one before",
              distinct_orders);
        /* item 0, 1e-4 s per iteration, min_time 0.02: 1 iteration takes 1e-4 < 0.25 min_time;
           grown x min(max(0.5 x 0.02 / 1e-4, 2), 1000) = 100 -> 100 iterations take 0.01 >= 0.005;
           scaled to ceil(100 x 0.02 / 0.01) = 200, which takes 0.02 >= 0.01: 200 */
        CHECK(g.items[0].iters == 200, "calibrated iterations %ld, by hand 200", g.items[0].iters);
        /* item 2, 5e-5 s: 1 -> 200 (0.01) -> ceil(200 x 0.02 / 0.01) = 400 */
        CHECK(g.items[2].iters == 400, "calibrated iterations %ld, by hand 400", g.items[2].iters);
        CHECK(g.items[0].nreps == 30 && g.items[1].nreps == 10, "repetitions kept: %d and %d", g.items[0].nreps,
              g.items[1].nreps);
        /* the same seed replays the same orders */
        int *first = malloc(sizeof(int) * (size_t)(g.r.rounds * g.r.round_len));
        memcpy(first, g.r.order, sizeof(int) * (size_t)(g.r.rounds * g.r.round_len));
        int len = g.r.rounds * g.r.round_len;
        runner_release(&g.r);
        setup(&g, 5, costs, 10);
        runner_run(&g.r);
        CHECK(memcmp(first, g.r.order, sizeof(int) * (size_t)len) == 0, "same seed, same orders");
        runner_release(&g.r);
        setup(&g, 5, costs, 10);
        g.r.seed = 12345;
        runner_run(&g.r);
        CHECK(memcmp(first, g.r.order, sizeof(int) * (size_t)len) != 0, "another seed, other orders");
        free(first);
        runner_release(&g.r);
    }

    /* Drift: from the third round on every launch takes twice as long. The absolute rates
       halve; the normalised rates stay (work_i / cost_i) / (work_ref / cost_ref) exactly. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 2, 0, 0, 0 } };
        setup(&g, 5, costs, 6);
        g.r.progress = slow_down;
        g.r.progress_ctx = &g.m;
        CHECK(runner_run(&g.r) == 0, "runner_run with drift");
        for (int i = 1; i < 5; ++i) {
            double expect = (g.items[i].work_per_iter / costs[i]) / (g.items[0].work_per_iter / costs[0]);
            CHECK_NEAR(g.items[i].rate[0] / g.items[i].rate[5], 2.0, 1e-12, "absolute rate halved by the drift");
            for (int k = 0; k < g.items[i].nreps; ++k) {
                CHECK_NEAR(g.items[i].norm[k], expect, 1e-12 * expect, "normalised rate, drift cancelled");
                CHECK_NEAR(g.items[i].cpu_norm[k], expect, 1e-9 * expect, "normalised rate per CPU second");
            }
        }
        CHECK(g.r.retried == 0 && g.r.disturbed == 0, "no preemption: %ld retries", g.r.retried);
        runner_release(&g.r);
    }

    /* Preemption now and then: every 5th launch gets a tenth of its CPU time and is retried;
       the repetitions kept are all whole-CPU ones. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 2, 0, 5, 0 } };
        setup(&g, 3, costs, 8);
        CHECK(runner_run(&g.r) == 0, "runner_run with preemption");
        long kept = 0;
        for (int i = 0; i < 3; ++i)
            kept += g.items[i].nreps;
        CHECK(g.r.retried > 0, "preempted launches retried: %ld", g.r.retried);
        CHECK(g.r.disturbed == 0,
              "every preempted repetition replaced (every 5th launch; 2 retries): %ld kept disturbed", g.r.disturbed);
        long retries = 0;
        for (int i = 0; i < 3; ++i)
            retries += g.items[i].retries;
        CHECK(retries == g.r.retried, "per-item retries add up: %ld vs %ld", retries, g.r.retried);
        CHECK(kept == 8 * (3 + 2), "repetitions: 8 rounds x (2 items + 3 references) = %ld", kept);
        runner_release(&g.r);
    }

    /* Persistent contention: every launch preempted. Round 1 retries (2 per repetition), then
       the runner stops retrying; every repetition is kept and counted disturbed. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 2, 0, 0, 1 } };
        setup(&g, 3, costs, 4);
        CHECK(runner_run(&g.r) == 0, "runner_run, persistent contention");
        /* round 1: 5 repetitions x 2 retries */
        CHECK(g.r.retried == 10, "retries only in the first round: %ld, by hand 10", g.r.retried);
        CHECK(g.r.disturbed == 4 * 5, "all 20 repetitions disturbed: %ld", g.r.disturbed);
        CHECK(g.r.persistent_rounds == 4, "persistent after every round: %d", g.r.persistent_rounds);
        runner_release(&g.r);
    }

    /* No CPU check (a GPU: cpu_threads 0): nothing is preempted whatever the CPU time says. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 0, 0, 0, 1 } };
        setup(&g, 2, costs, 0);
        CHECK(runner_run(&g.r) == 0, "runner_run, no CPU check");
        CHECK(g.r.retried == 0 && g.r.disturbed == 0 && g.items[1].cpu_norm == NULL, "GPU: no retries, no CPU rates");
        runner_release(&g.r);
    }

    /* An item whose 7th launch fails (warm-up 1, calibration 3, then the rounds' 3rd) fails
       alone, with its reason; the others keep every round. */
    {
        struct rig g = { .m = { 0, 0, 1.0, 2, 0, 0, 0 } };
        setup(&g, 3, costs, 5);
        g.fi[1].fail_after = 6;
        CHECK(runner_run(&g.r) == 0, "runner_run with a failing item");
        CHECK(!g.items[1].ok && strstr(g.items[1].reason, "fake launch failed"), "the failing item says why: %s",
              g.items[1].reason);
        CHECK(g.items[2].ok && g.items[2].nreps == 5, "the others go on: %d reps", g.items[2].nreps);
        runner_release(&g.r);
    }
    return check_summary();
}
