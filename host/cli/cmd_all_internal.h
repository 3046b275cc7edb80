/* cmd_all_internal.h - what the files of `brdfbench all` share (cmd_all.c: the command, its own
 * steps and the report; cmd_all_parts.c: the parts other commands make). Internal to them. */
#ifndef BRDF_CMD_ALL_INTERNAL_H
#define BRDF_CMD_ALL_INTERNAL_H

#include "accuracy.h"
#include "cli.h"
#include "clsession.h"
#include "field.h"
#include "plots.h"
#include "report.h"
#include "report_docs.h"
#include "run.h"

#define ALL_MAX_MODELS 64
#define ALL_MAX_Q RUN_MAX_Q
#define ALL_STEPS_BASE 10

struct all_settings {
    int quick;
    struct accuracy_grid grid;     /* the main sweep */
    struct accuracy_grid q_grid;   /* each f_Q of the Q sweep */
    double q_min, q_max, q_step;
    struct field_grid field;
};

struct all_run {
    struct all_settings set;
    struct brdf_run run;           /* the session and what the steps share: the Q sweep's figures */
    struct accuracy_ctx actx;
    int actx_open;
    const char *results_root;
    char run_dir[4200];            /* where the run is written: the staging folder */
    char final_dir[4096];          /* where it goes when complete: --out or results/<date-time> */
    char command[1024];
    double t0;
    int step;
    int tty;
    int quiet;                     /* no progress or step lines, no closing path */
    struct model_spec models[ALL_MAX_MODELS];
    int nmodels;
    int models_given;              /* --models: every step measures just those */
    struct accuracy_result *acc;
    int nacc;
    struct plot_set plots;
    struct report_picture *pics;
    int npics, cappics;
    struct report_step *steps;     /* the step list of report.md (run.json) */
    int nsteps, capsteps;
    int picture_failures;
    int part_failures, part_rc;
    char picture_error[1024];
    struct report_part_state parts[REPORT_PART_COUNT];
    struct report_docs docs;       /* rows the steps hold in memory, for report.md (report_docs_put):
                                      a file put there is not read back */
    char images_note[512];         /* the scenes left out */
    const char *measured_dir;      /* --measured DIR: the measured materials' section */
    const char *out_dir;           /* --out, or NULL: a new folder under results_root */
    struct device_options dev;
    int shared_scale;              /* --shared-scale */
};

/* Seconds since the run began. */
double all_elapsed(const struct all_run *r);
/* A live bar on a terminal: [#####.....] 7/14 fvol */
void all_progress(const struct all_run *r, const char *what, int done, int total, const char *item);
/* The line that closes a step: on stderr and in the report's step list. */
void all_step_done(struct all_run *r, const char *name, double started, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* The parts of other commands (cmd_all_parts.c): each returns 0 or its exit code, which part()
 * records in its report section. */
int all_step_claims(struct all_run *r);
int all_step_fit(struct all_run *r);
int all_step_throughput(struct all_run *r);
int all_step_images(struct all_run *r);
int all_step_frontier(struct all_run *r);
int all_step_measured(struct all_run *r);

#endif
