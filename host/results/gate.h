/* gate.h - accuracy gates for CI: a gates file (JSON, docs/gates.md) lists checks of a model's
 * figure over an n range against bounds; the gate command runs only the sweeps they need,
 * prints one line per gate, writes JUnit XML and JSON (gate_report.h), and compares with a baseline. */
#ifndef BRDF_GATE_H
#define BRDF_GATE_H

#include "schemas.h"
#include <stdio.h>

#include "accuracy.h"
#include "clsession.h"
#include "models.h"

#define GATE_MAX_GATES 1000
#define GATE_DEFAULT_TOLERANCE 1e-3            /* --tolerance: relative regression allowed */
#define GATE_BASELINE_FLOOR 1e-9               /* absolute slack of a baseline comparison */

enum gate_metric {
    GATE_EPICENTRE_MAX_REL,   /* max relative error over the epicentre zone (docs/definitions.md delta) */
    GATE_EPICENTRE_MAX_ABS,   /* max absolute error over the epicentre zone */
    GATE_ATTENUATION_MAX_ABS, /* max absolute error over the attenuation zone (docs/definitions.md Delta) */
    GATE_WHOLE_MAX_ABS,       /* max absolute error over x in [0, pi/2] */
    GATE_ENERGY_MAX_DEV,      /* max over n of |2 pi int_0^(pi/2) f cos x sin x dx - 1| */
    GATE_ALBEDO_MAX,          /* max directional albedo over n and theta_i (host/measure/energy/energy.h) */
    GATE_INVALID_COUNT,       /* model values that were NaN, Inf or negative in the sweep */
    GATE_MEASURED_RMS,        /* the lobe's error against a measured material (host/measure/measured/measured.h) */
    GATE_HEMI_EPI_REL,        /* a full BRDF over the hemisphere (host/measure/accuracy/hemisphere.h): max delta, epicentre */
    GATE_HEMI_ATT_ABS,        /* ... max Delta over the attenuation samples */
    GATE_HEMI_WHOLE_ABS,      /* ... max Delta over every sample */
    GATE_HEMI_RMS,            /* ... RMS of cos(theta_i) (f - f_ref), its largest over the axis */
    GATE_METRIC_COUNT
};

/* 1 for the metrics of the hemisphere sweep (hemisphere.*). */
int gate_metric_is_hemisphere(enum gate_metric m);
/* The name of a metric in a gates file ("epicentre.max_rel") and what it measures. */
const char *gate_metric_name(enum gate_metric m);

enum gate_status { GATE_NOT_RUN, GATE_PASS, GATE_FAIL };
enum gate_baseline_status { GATE_BASELINE_NONE, GATE_BASELINE_OK, GATE_BASELINE_REGRESSION,
                            GATE_BASELINE_MISSING };

struct gate {
    /* As declared. */
    char name[200];
    struct model_spec model;
    enum gate_metric metric;
    struct accuracy_grid grid;
    int has_min, has_max;
    double min, max;
    int has_claimed;
    double claimed;            /* a paper's figure, reported beside the measured one */
    char note[256];
    int line, col;             /* where the gate is in the gates file */
    int accept_device_disagreement; /* "accept_device_disagreement": true: judged on the figure alone */
    char measured_path[4096];  /* "measured": the MERL file of a measured.rms gate, resolved */
    int has_reference;         /* "reference": a hemisphere.* gate's reference, named (else the family's) */
    struct model_spec reference;

    /* Measured. */
    enum gate_status status;
    double measured, at_n, at_x;
    double margin, margin_rel; /* distance to the nearer bound: > 0 inside, < 0 outside */
    long long invalid_count;   /* invalid model values in the gate's n range */
    double invalid_n, invalid_x;
    struct acc_check check;    /* device vs double over the gate's n values (accuracy.h) */
    char reason[700];          /* why it failed, or a note */
    double seconds;            /* wall time of the work first done for this gate */

    /* Against a baseline (--baseline). */
    enum gate_baseline_status baseline_status;
    char baseline_note[200];   /* GATE_BASELINE_MISSING: why no baseline figure was used */
    double baseline, baseline_change;   /* value, and (measured - baseline) / |baseline| */
};

struct gate_set {
    char path[4096];           /* the gates file, as given */
    char description[512];
    int count;
    struct gate *gates;
    char baseline_path[4096];  /* "" when no baseline */
    double tolerance;
    int sweeps_run;            /* sweeps the gates needed */
};

/* Parses a gates file's text. name is used in messages ("name:line:col: problem"); model
 * files named in it are read relative to base_dir. User models it defines are registered
 * (host/core/usermodel.h). outside_allowed (gate --allow-outside-model-files): by default a
 * "model_file" or "measured" file must lie in base_dir or below it, links resolved, since a
 * model file is a program run on the host (docs/gates.md); 1 lifts that. Returns 0, or
 * EXIT_USAGE with a message. No device is needed. */
int gate_set_parse_text(const char *text, size_t len, const char *name, const char *base_dir, int outside_allowed,
                        struct gate_set *out, char *err, size_t errlen);
/* The same for the gates file at path (base_dir: its folder). */
int gate_set_load(const char *path, int outside_allowed, struct gate_set *out, char *err, size_t errlen);
void gate_set_free(struct gate_set *g);

/* Reads a baseline: a run folder holding accuracy.json, or such a file. Sets each gate's
 * baseline fields (compared after gate_set_run). Returns 0 or EXIT_USAGE. */
int gate_set_baseline(struct gate_set *g, const char *path, double tolerance, char *err, size_t errlen);

/* Checks every gate's grid against the device's limits. Returns 0 or EXIT_USAGE. */
int gate_set_check_device(const struct gate_set *g, const struct cl_session *s, char *err, size_t errlen);
/* Runs the sweeps and integrals the gates need and judges every gate. progress (may be NULL)
 * gets one line per sweep. Returns 0 or an exit code (a runtime failure, a user model that
 * does not compile). */
int gate_set_run(struct gate_set *g, struct cl_session *s, FILE *progress);
/* Number of gates that failed (after gate_set_run). */
int gate_set_failures(const struct gate_set *g);


#endif
