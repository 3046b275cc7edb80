/* frontier.h - `brdfbench frontier`: for every model of a run, its cost (device evaluations/s,
 * n uniform and n varying, measured in the same run by the throughput engine's protocol, and
 * the operation count of its formula) beside its accuracy (max delta in the epicentre and max
 * Delta in the attenuation zone over n in [2, 1000] and [16, 1000], from the accuracy engine's
 * device sweep polished in double, and the PSNR of its teapot image pass from the render
 * engine); the Pareto set over (cost, max delta, max Delta), where two costs whose measured
 * min-max spreads overlap count as equal. frontier_report.c writes frontier.json,
 * frontier.csv, the two scatter plots and the "Which lobe to ship" markdown. */
#ifndef BRDF_FRONTIER_H
#define BRDF_FRONTIER_H

#include "schemas.h"
#include <stddef.h>

#include "clsession.h"
#include "engine.h"
#include "models.h"

#define FRONTIER_MAX_MODELS 32
#define FRONTIER_MAX_ROUNDS 16

/* Costs within this fraction of each other are a tie on the front (as compare's default
 * minimum change: scripts/bench_compare.sh). */
#define FRONTIER_MIN_CHANGE 0.10

struct frontier_row {
    struct model_spec spec;
    int kind;                         /* enum model_kind (host/core/models.h) */
    struct model_ops ops;
    double rate[2][3];                /* [uniform, varying][min, median, max] evaluations/s over the
                                         rounds' medians; NAN: missing */
    double norm[2][3];                /* the same over the peak kernel's rate in the same round
                                         (host/core/runner.h): what the front is decided on */
    char rate_reason[160];
    double max_rel[2], max_rel_n[2];  /* [n from 2, n from 16]; host-polished device sweep */
    double max_abs[2], max_abs_n[2];
    double psnr_db;                   /* teapot pass; NAN: identical images or missing */
    char psnr_reason[96];
    int on_front;
};

struct frontier_options {
    struct engine_io io;              /* the run folder and --quiet (engine.h) */
    struct model_spec models[FRONTIER_MAX_MODELS];
    int model_count;                  /* 0: frontier_default_models */
    long samples;                     /* accuracy sweep samples per zone */
    int reps;                         /* timed launches per model per round */
    int rounds;                       /* rounds over every model (1..FRONTIER_MAX_ROUNDS) */
    double min_time;                  /* seconds a timed launch lasts at least */
    int image_w, image_h;             /* teapot pass; 0: no image pass */
};

struct frontier_report {
    struct frontier_options opt;
    struct frontier_row rows[FRONTIER_MAX_MODELS];
    int count;
    int fq2;                          /* row of fq2, or -1 */
    double seconds;
};

void frontier_options_default(struct frontier_options *o);
/* The default set: the references, the papers' models, the engines' approximations and the
 * frozen fits, every one against phong. Returns the count. */
int frontier_default_models(struct model_spec *out, int max);
/* The operation table entry of a model id. */
/* The descriptor's operation count, or none for a user model. */
struct model_ops frontier_ops_of(const struct model_info *info);

/* The Pareto front: on_front[i] = 1 when no other point is at least as good in all three
 * (cost higher or within overlapping spreads, max delta and max Delta not larger) and better
 * in one (a cost is better only when the spreads do not overlap). rate_lo/rate_hi are each
 * point's min and max rate. */
void frontier_pareto(const double *rate_lo, const double *rate_hi, const double *max_rel, const double *max_abs,
                     int count, int *on_front);

/* What a run gives back: the "Which lobe to ship" section for report.md (malloc'd). */
struct frontier_result {
    char *markdown;
};
void frontier_result_free(struct frontier_result *r);

/* Measures, writes o->io.out_dir's frontier.json, frontier.csv, frontier_max_rel.png and
 * frontier_max_abs.png, prints the table unless o->io.quiet. Returns 0 or an exit code. res
 * may be NULL. */
int frontier_run(struct cl_session *s, const struct frontier_options *o, struct frontier_result *res);

#endif
