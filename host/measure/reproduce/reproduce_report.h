/* reproduce_report.h - the state of a claims run (reproduce.c fills it) and its writers
 * (reproduce_report.c: the rows, claims.json, claims.md, q_sweep.json, the printed table). */
#ifndef BRDF_REPRODUCE_REPORT_H
#define BRDF_REPRODUCE_REPORT_H

#include <stdio.h>

#include "accuracy.h"
#include "clsession.h"
#include "energy.h"
#include "pbcost.h"
#include "reproduce.h"

enum sweep_id { SW_FVOL, SW_FVOL64, SW_CQ2_P1, SW_SCHLICK, SW_FQ, SW_FQ2, SW_CQ2_P2, SW_COUNT };

struct repro {
    struct cl_session *s;
    const struct reproduce_options *o;
    struct reproduce_report *r;
    struct accuracy_ctx actx;
    struct integrate_ctx ic;
    struct accuracy_result sw[SW_COUNT];
    int have_sw[SW_COUNT];
    double grid_change[SW_COUNT];     /* in units of the 4th significant digit; NAN: not checked */
    /* Q sweep */
    int nq;
    double *q, *q_rel, *q_rel_n, *q_abs, *q_att;
    double f2_rel, f2_abs;
    double q_best, q_best_host_rel;
    struct accuracy_result fq_best;
    int have_fq_best;
    /* energy */
    struct energy_summary energy;
    int have_energy;
    /* the physically based models' cost, He's terms, their albedo (physical.json) */
    struct pbcost_result physical;
    int have_physical;
    int consistency_failed;
};

/* The rows of the run's files, built in memory once: written as each file's rows member and
 * drawn as claims.md (report_claims.h says what they hold). */
struct rdoc;
struct repro_rows {
    struct rdoc *claims, *q_sweep, *physical;   /* physical: NULL when the cost was not measured */
};
/* Returns 0, or -1 with "out of memory" in err (nothing kept). */
int reproduce_rows(const struct repro *p, struct repro_rows *rows, char *err, size_t errlen);
void reproduce_rows_free(struct repro_rows *rows);
/* claims.md's text (malloc'd; NULL when out of memory). */
char *reproduce_claims_markdown(const struct repro_rows *rows);
/* claims.json and q_sweep.json, each with its rows. Return 0, or non-zero with a message in err. */
int reproduce_write_claims_json(const struct repro *p, const struct rdoc *rows, const char *path, char *err,
                                size_t errlen);
int reproduce_write_q_sweep_json(const struct repro *p, const struct rdoc *rows, const char *path, char *err,
                                 size_t errlen);
/* One row per claim with its verdict, and the summary line. */
void reproduce_print_table(FILE *f, const struct repro *p);

#endif
