/* run.h - one run of a command: what its steps share for the run's life, held in one object
 * instead of file-scope state.
 *
 *   s        the OpenCL session, and with it what its engines share (clsession.h's tables):
 *            the program cache (programs.c: each build once per run) and the sweeps already
 *            run (accuracy.c: each sweep once per run). Closing the session releases both.
 *   q_sweep  results of earlier steps that a later step uses: the Q sweep of paper 2's
 *            figs. 2-3 (in `all`, the claims check's, handed to the plots in memory).
 *
 * Every command that opens a device opens it through brdf_run_open (cli_run.c's
 * cli_run_session is its one caller), so every run starts from the same empty object. */
#ifndef BRDF_RUN_H
#define BRDF_RUN_H

#include "clsession.h"

#include <stddef.h>
#include <string.h>

#define RUN_MAX_Q 256

/* max delta (epicentre) and max Delta (whole range) of f_Q for each Q of a grid, and of f2 (cq2),
 * which does not depend on Q, on the same grid of n. */
struct run_q_sweep {
    int n;                               /* values held; 0: no Q sweep has run */
    double q[RUN_MAX_Q], max_rel[RUN_MAX_Q], max_abs[RUN_MAX_Q];
    double f2_max_rel, f2_max_abs;
};

struct brdf_run {
    struct cl_session s;
    int open;                            /* s is open (brdf_run_close closes it) */
    struct run_q_sweep q_sweep;
};

/* Empties the run and opens its session on platform/device (clsession_open's indices and
 * returns, message in err). */
static inline int brdf_run_open(struct brdf_run *run, int platform_index, int device_index, char *err, size_t errlen)
{
    memset(run, 0, sizeof *run);
    int rc = clsession_open(&run->s, platform_index, device_index, err, errlen);
    run->open = rc == 0;
    return rc;
}

/* Closes the session (its program cache and sweeps go with it); safe on a run never opened or
 * closed already. */
static inline void brdf_run_close(struct brdf_run *run)
{
    if (run->open)
        clsession_close(&run->s);
    run->open = 0;
}

#endif
