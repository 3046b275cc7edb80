/* measured.h - `brdfbench measured`: each cheap lobe measured against real materials (MERL
 * files, host/core/merl.h). Per material:
 *   - Blinn-Phong f = ks cos(theta_h)^n + kd fitted to the measured cells by least squares
 *     (gsl_multifit_nlinear), on luminance Y = 0.2126 R + 0.7152 G + 0.0722 B, in the metric
 *     r = ln(1 + cos(theta_i) f_model) - ln(1 + cos(theta_i) Y) per cell;
 *   - every cheap lobe f(c, n) of the registry at that n and scaled the same way,
 *     ks f(cos theta_h, n) + kd, against the measurement and against the fitted Blinn-Phong:
 *     the RMS of the same residual over every measured cell, and their ratio;
 *   - Cook-Torrance with Beckmann and with GGX (roughness alpha, Schlick's F0, scale ks, plus
 *     kd) fitted the same way, from kernels/brdf_models.h's host double versions;
 *   - the device lookup (kernels/merl.cl) at every cell's centre against the host's table.
 * Cells used: measured in all three channels, with L and V of the cell's centre above the
 * surface. The fits see an evenly strided subset of them (fit_cells); every figure of error
 * is over all of them. */
#ifndef BRDF_MEASURED_H
#define BRDF_MEASURED_H

#include "schemas.h"
#include <stdio.h>

#include "clsession.h"
#include "engine.h"
#include "merl.h"
#include "models.h"

#define MEASURED_MAX_LOBES 32
#define MEASURED_MAX_MATERIALS 512
#define MEASURED_SLICES 3                 /* theta_d of the slice pictures */
#define MEASURED_DEFAULT_FIT_CELLS 20000
#define MEASURED_MIN_FIT_CELLS 100
#define MEASURED_MAX_FIT_CELLS 1458000

/* The theta_d cells of the slices (0, 30 and 60 degrees at their low edge) and the phi_d cell
 * (90 degrees). */
extern const int measured_slice_td[MEASURED_SLICES];
#define MEASURED_SLICE_PD 90

enum measured_fit_model { MFIT_BLINN = 0, MFIT_CT_BECKMANN, MFIT_CT_GGX, MFIT_COUNT };
extern const char *const measured_fit_name[MFIT_COUNT];   /* "blinn-phong", "ct-beckmann", "ct-ggx" */

struct measured_options {
    long fit_cells;                       /* at most this many cells in a fit */
    int skip_physical;                    /* 1: no Cook-Torrance fits (their entries NaN, "not run") */
    int nlobes;
    struct model_spec lobes[MEASURED_MAX_LOBES];
    struct engine_io io;                  /* the run folder (measured.json, the slices' pictures; NULL:
                                             none written) and --quiet: no progress (engine.h) */
    char *const *paths;                   /* the MERL files of measured_run */
    int count;
};

struct measured_fit {
    int ok;                               /* GSL's driver converged (else reason) */
    char reason[200];
    double n, ks, kd;                     /* Blinn-Phong: n; Cook-Torrance: the n of alpha, 2/alpha^2 - 2 */
    double alpha, f0;                     /* Cook-Torrance only (NaN for Blinn-Phong) */
    double rms;                           /* RMS residual over every used cell */
    double rms_fit;                       /* over the fit's cells */
    int iterations;
};

struct measured_lobe {
    struct model_spec spec;
    double err_measured;                  /* RMS residual against the measured cells */
    double err_phong;                     /* RMS of the same residual against the fitted Blinn-Phong */
    double ratio;                         /* err_measured / err_phong (NaN where err_phong is 0) */
};

struct measured_slice {
    double theta_h_deg[MERL_TH];          /* the cells' centres */
    double measured[MERL_TH];             /* luminance, NaN where not used */
    double fit[MFIT_COUNT][MERL_TH];
};

struct measured_material {
    char name[256], path[4096];
    char stem[300];                       /* its pictures' name part, unique in the run (measured_run) */
    long cells, unmeasured, negative[3];
    long below_horizon;                   /* measured cells whose L or V lies below the surface */
    long used_cells, fit_cells;
    struct measured_fit fit[MFIT_COUNT];
    int nlobes;
    struct measured_lobe lobes[MEASURED_MAX_LOBES];
    struct measured_slice slice[MEASURED_SLICES];
    /* the device lookup at every cell's centre */
    long device_points, device_same_cell, device_value_diff;
    int device_ok;
};

void measured_options_default(struct measured_options *o);
/* The default lobes: every registry model that approximates cos^n (reference phong, not itself
 * a reference), with its default parameters; the families of two continuous parameters
 * (quad, gauss, pow3, pow4) are left out, their frozen fits stay in. Returns the count. */
int measured_default_lobes(struct model_spec *out, int max);

/* Fits and measures one material read by merl_read. Returns 0 or an exit code. */
int measured_material_run(struct cl_session *s, const struct merl_material *mat, const struct measured_options *o,
                          struct measured_material *out);

/* The materials of a run. */
struct measured_report {
    struct measured_options opt;
    int count;
    struct measured_material *materials;
    char err[4600];                       /* measured_run's message (empty when it is on stderr already) */
};

/* Appends to *paths (count *count, malloc'd strings) arg itself, or when arg is a folder its
 * *.binary files in name order. Returns 0 or EXIT_USAGE with a message (arg missing, a folder
 * without .binary files, more than MEASURED_MAX_MATERIALS). */
int measured_collect(const char *arg, char ***paths, int *count, char *err, size_t errlen);
void measured_paths_free(char **paths, int count);
/* Reads the materials of arg (a MERL file or a folder of them, as measured_collect) into
 * out[0..*count), at most max of them: what the flag `flag` (--measured) of throughput and render
 * loads before any work. Returns 0 or EXIT_USAGE/EXIT_RUNTIME with a one-line message in err
 * (nothing kept on failure). */
int measured_load(const char *flag, const char *arg, int max, struct merl_material *out, int *count, char *err,
                  size_t errlen);

/* Reads and measures each file of o->paths in turn (one table in memory at a time) into out
 * (its materials allocated here; measured_report_free), a progress line per material on stderr
 * unless o->io.quiet, then writes measured.json and the slices' pictures into o->io.out_dir.
 * Returns 0, EXIT_USAGE with the reader's message in out->err when a file is malformed (out
 * then holds no material), or an exit code (out->err empty when the message is already on
 * stderr). Like render's, the message is left to the caller, which runs it as a command or as
 * a step of all. */
int measured_run(struct cl_session *s, const struct measured_options *o, struct measured_report *out);
void measured_report_free(struct measured_report *r);

#endif
