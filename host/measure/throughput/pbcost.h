/* pbcost.h - the cost of the physically based BRDFs measured beside the lobes (the papers'
 * argument that physically based models are too costly for real-time use): evaluations per
 * second from full vectors (N, L, V) made in registers (kernels/throughput.cl, tp_vec_*), for
 * pow(), Phong, Blinn-Phong, fq2 and every physically based model of the registry, with the
 * ratios to fq2 and to Phong taken within one run; the He model's terms per evaluation; and
 * each physically based model's white-furnace albedo at normal incidence. pbcost.c measures,
 * pbcost_report.c writes physical.json (with its rows) and the table; the page's section is drawn
 * from the rows (report_claims.h). */
#ifndef BRDF_PBCOST_H
#define BRDF_PBCOST_H

#include "schemas.h"
#include <stdio.h>

#include "clsession.h"
#include "compare.h"
#include "engine.h"
#include "merl.h"
#include "models.h"

#define PBCOST_MAX_ROWS 24
#define PBCOST_MAX_MEASURED 4    /* measured materials as rows (--measured) */
#define PBCOST_CHECK_TOL 1e-3    /* a row's check: |device - double| / peak at most this */
#define PBCOST_CHECK_POINTS 4096
#define PBCOST_TERMS_THETA 5     /* theta = 0, 30, 60, 75, 85 degrees */
#define PBCOST_TERMS_RATIO 6     /* sigma0 / lambda = 0.01, 0.05, 0.1, 0.2, 0.5, 1 */
#define PBCOST_MAX_REPS 64       /* normalised repetitions kept per row */

struct pbcost_options {
    struct engine_io io;         /* the run folder (physical.json; NULL: none written) and --quiet (engine.h) */
    double n;                    /* shininess of the lobes and of alpha(n) (default 100) */
    int reps;                    /* timed launches per row (default 9) */
    double min_time;             /* seconds one timed launch lasts at least (default 0.02) */
    long work_items;             /* 0: clsession_default_work_items */
    int nfull;                   /* full BRDFs of (L, V, N) given by the user (model_is_full) */
    struct model_spec full[PBCOST_MAX_MEASURED];
    int nmeasured;               /* measured materials timed as rows (table lookups) */
    const struct merl_material *measured[PBCOST_MAX_MEASURED];
};
void pbcost_options_default(struct pbcost_options *o);

struct pbcost_row {
    struct model_spec spec;      /* the model (for pow(): phong's spec) */
    char name[MODEL_LABEL_MAX + 16];
    int kind;                    /* 0 lobe of R.V, 1 lobe of N.H, 2 physically based, 3 pow(),
                                    4 a user full BRDF of (L, V, N), 5 a measured material */
    const struct merl_material *merl;   /* kind 5 */
    char status[8];              /* "ok", or "check" where the device misses the double reference */
    int physical;
    long iters;
    double evals_per_launch;
    double med_s, min_s, max_s;  /* per launch, profiling events */
    double evals_per_s;          /* evals_per_launch / med_s: the median launch */
    double evals_per_s_fastest;  /* evals_per_launch / min_s */
    /* Each repetition's rate over the reference's (the pow() row, timed at the start, middle and
       end of every round: host/core/runner.h), per CPU second on a CPU device; the ratios are
       compare's Hodges-Lehmann estimates on them, each with compare's verdict (rank test, the
       interval, the minimum effect CMP_DEFAULT_THRESHOLD at CMP_DEFAULT_ALPHA). */
    int nnorm;
    double norm_reps[PBCOST_MAX_REPS];
    double ratio_to_fq2, ratio_to_phong, ratio_to_pow;   /* this row's evaluations/s over theirs */
    struct compare_speed vs_fq2, vs_phong;
    double check_max_abs_of_peak;   /* |device - double| / largest double value of the sample */
    double terms_mean, terms_max;    /* He: terms of the directional-diffuse sum (double host) */
    double albedo_normal;        /* white-furnace albedo at normal incidence (double); NAN: lobe */
    double albedo_normal_error;  /* the quadrature's error estimate */
};

struct pbcost_result {
    struct pbcost_options o;
    long work_items;
    int count;
    struct pbcost_row rows[PBCOST_MAX_ROWS];
    int fq2, phong, pow_row;     /* row indices */
    /* He's terms per evaluation over (theta, sigma0/lambda): in the mirror direction and 20
       degrees past it in the plane of incidence (tau = 1 um, lambda = 0.55 um, rough aluminium) */
    double terms_theta[PBCOST_TERMS_THETA], terms_ratio[PBCOST_TERMS_RATIO];
    int terms_mirror[PBCOST_TERMS_THETA][PBCOST_TERMS_RATIO];
    int terms_off[PBCOST_TERMS_THETA][PBCOST_TERMS_RATIO];
    double seconds;
};

/* Measures every row (progress on stderr unless o->io.quiet); with o->io.out_dir, writes
 * physical.json there and prints the table on stdout unless quiet (`brdfbench throughput` runs
 * it beside its own rows; reproduce reads the rows alone). Returns 0 or an exit code (a message
 * on stderr). */
int pbcost_run(struct cl_session *s, const struct pbcost_options *o, struct pbcost_result *r);

/* The number of terms He's directional-diffuse sum takes (double host, float-resolution
 * stopping rule) for unit vectors given by their cosines, with the rough aluminium preset's
 * wavelength, tau and index and rms roughness sigma0 (micrometres). */
int pbcost_he_terms(double nl, double nv, double lv, double sigma0);

/* Writers (pbcost_report.c). pbcost_rows: physical.json's rows (report_claims.h says what they
 * hold), NULL with "out of memory" in err; free with rdoc_delete. pbcost_write_json writes rows
 * as the file's rows member (NULL: the rows of r, made here). */
struct rdoc;
struct rdoc *pbcost_rows(const struct pbcost_result *r, char *err, size_t errlen);
int pbcost_write_json(const char *path, const struct cl_session *s, const struct pbcost_result *r,
                      const struct rdoc *rows, char *err, size_t errlen);
void pbcost_print_table(FILE *f, const struct pbcost_result *r);

#endif
