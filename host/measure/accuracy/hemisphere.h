/* hemisphere.h - the hemisphere sweep of a full BRDF f(L, V; p) against its reference
 * (docs/definitions.md, "Full BRDFs over the hemisphere"): the device evaluates both over
 * Rusinkiewicz's (theta_h, theta_d, phi_d) where N.L > 0 and N.V > 0 (kernels/hemisphere.cl),
 * for every value p of one parameter axis; the host recomputes each figure in double at the
 * device's grid point, refines each maximum in double until its 4th significant digit stays,
 * and checks the device against double with the float floor of docs/definitions.md. */
#ifndef BRDF_HEMISPHERE_H
#define BRDF_HEMISPHERE_H

#include "clsession.h"
#include "merl.h"
#include "models.h"

#define HEMI_DEFAULT_NH 48
#define HEMI_DEFAULT_ND 48
#define HEMI_DEFAULT_NP 96
#define HEMI_MIN_CELLS 4
#define HEMI_MAX_CELLS 2048
#define HEMI_DEFAULT_POINTS 8
#define HEMI_MAX_POINTS 4096
#define HEMI_PROBE_POINTS 4096
#define HEMI_MAX_WORK 5e8          /* grid points x axis values of one run */
/* "a few units of 2^-24 peak" (docs/definitions.md, Device check) */
#define HEMI_FLOOR_UNITS 8.0
/* Values of a table reference (a user model or a measured material as the reference: one per
   grid point and axis value, kernels/hemisphere.cl's rtab): 64 MiB of floats on the device and
   128 MiB of doubles on the host at most (8 axis values of the MERL tables' 90x90x180 fit) */
#define HEMI_MAX_TABLE (1L << 24)

/* What an axis sweeps: the shininess slot under one of its engine names, or a named parameter. */
enum hemi_quantity { HQ_N, HQ_ALPHA, HQ_ROUGHNESS, HQ_M, HQ_PARAM };

struct hemi_axis {
    char name[64];              /* n, alpha, roughness, m, a parameter's name, or PARAM:ROLE */
    enum hemi_quantity q;
    char target[64];            /* --axis PARAM:ROLE: the model's parameter PARAM takes the axis's values,
                                   which are ROLE's (q); "" otherwise */
    double min, max;
    int count;                  /* values of the axis, ends included */
    int geometric;              /* spacing: 1 geometric, 0 uniform */
};

/* A fixed value given with --param NAME=VALUE. */
struct hemi_fixed {
    char name[64];
    double value;
};
#define HEMI_MAX_FIXED 4

struct hemi_grid {
    int nh, nd, np;             /* theta_h rows, theta_d and phi_d cells (kernels/hemisphere_geom.h) */
};

/* One maximum and where it lies. */
struct hemi_extreme {
    double value, p, th, td, pd;
};

struct hemi_per_p {
    double p;                          /* the axis value */
    double mvals[3], rvals[3];         /* the model's and the reference's n, p0, p1 (in double; the device's are these rounded to float) */
    double peak;                       /* max f_ref over the samples (device) */
    /* as the device found them (float values, double angles of the grid point) */
    struct hemi_extreme dev_epi_rel, dev_att_abs, dev_whole_abs;
    /* recomputed in double at the device's point, then refined in double */
    struct hemi_extreme epi_rel, att_abs, whole_abs;
    double chk_epi_rel, chk_att_abs, chk_whole_abs;   /* |device - double| at the device's point */
    double dbl_epi_rel, dbl_att_abs, dbl_whole_abs;   /* the double figure at the device's point */
    double rms;                        /* RMS of cos(theta_i) (f - f_ref) over dw_i dw_o, in double */
    double rms_device;                 /* the same quadrature summed by the device in float */
    long long used, below, invalid, eval_below, uncovered;
};

struct hemi_check {
    int exceeded;
    const char *figure;
    double diff, p, units;
};

struct hemi_result {
    struct model_spec model, reference;
    int model_kind, ref_kind;          /* HEMI_KIND_* of kernels/hemisphere_geom.h */
    struct hemi_axis axis;
    struct hemi_grid grid;
    int p_count;
    struct hemi_per_p *per_p;
    struct hemi_extreme epicentre, attenuation, whole, rms;   /* over the range, refined in double */
    struct hemi_extreme grid_epicentre, grid_attenuation, grid_whole;   /* as the device found them */
    long long used, below, invalid, eval_below, uncovered;
    int ref_table;                     /* 1: the device read the reference's double values (a table reference) */
    double *ref_values;                /* those values in double, per (p, theta_h, theta_d, phi_d); NAN: not covered */
    double float_cancellation;         /* max |f_device - f_double| / peak at random samples */
    double ref_float_error;            /* the same of the reference */
    int checks_at_float_noise;         /* figures the device resolves only to its float noise */
    double peak_ratio;                 /* f / f_ref at L = V = N (farthest from 1 over the axis) */
    struct hemi_check check;
    double device_seconds, points;
    int ok, device_disagrees;
    char reason[640];
};

struct hemi_ctx {
    struct cl_session *s;
    char build_options[256];
    /* built-in model pairs' programs, built on first use (a user model's are programs.c's) */
    struct hemi_prog { char options[256]; cl_program program; cl_kernel sweep, probe; } progs[8];
    int nprogs;
};

/* A measured material as the sweep's reference (--reference merl:FILE.binary): the luminance of
 * its table's cell holding (theta_h, theta_d, phi_d), NAN where a channel was not measured. info
 * comes first, so that a model_spec names it (spec.info == &hm->info); it is no model of the
 * registry. */
struct hemi_measured {
    struct model_info info;
    char id[300];
    struct merl_material mat;
};
/* Reads the material of path into *hm and names it in *spec ("merl:NAME"). 0 or EXIT_USAGE /
 * EXIT_RUNTIME with a one-line message in err (the reader's, which starts with the path). */
int hemisphere_measured_open(const char *path, struct hemi_measured *hm, struct model_spec *spec, char *err,
                             size_t errlen);
void hemisphere_measured_close(struct hemi_measured *hm);
/* 1 when a model can be the reference of the hemisphere sweep: a built-in, a full user model, a
 * measured material. */
int hemisphere_reference_ok(const struct model_spec *ref);

/* 1 when the model is measured by the hemisphere sweep: a user full BRDF or a built-in
 * physical model (its lobe sweep puts V below the horizon past 45 degrees). */
int hemisphere_applies(const struct model_spec *m);

/* hemisphere_applies, with the reference named on the command line (NULL: none): a full BRDF
 * measured against a built-in Fresnel or shadowing-masking term is that term's lobe of one angle,
 * as when its header names the term. */
int hemisphere_applies_against(const struct model_spec *m, const struct model_spec *named_ref);

/* Parses --axis NAME[=MIN:MAX] or PARAM:ROLE[=MIN:MAX] into *a (count and n range from the caller). 0 or EXIT_USAGE. */
int hemisphere_axis_parse(const char *text, struct hemi_axis *a, char *err, size_t errlen);
/* Parses --param NAME=VALUE (appended to fixed; *count updated). 0 or EXIT_USAGE. */
int hemisphere_fixed_parse(const char *text, struct hemi_fixed *fixed, int *count, char *err, size_t errlen);
/* Checks an axis and the fixed values against the model and reference (names, ranges, that the
 * reference can be lifted), filling the axis range where it was not given. 0 or EXIT_USAGE. */
int hemisphere_axis_check(struct hemi_axis *a, const struct hemi_fixed *fixed, int nfixed,
                          const struct model_spec *m, const struct model_spec *ref, double n_min, double n_max,
                          char *err, size_t errlen);
/* Checks that a reference the host evaluates at every grid point (a user model, a measured
 * material) has room for its values (HEMI_MAX_TABLE). 0 or EXIT_USAGE. */
int hemisphere_table_check(const struct model_spec *ref, const struct hemi_grid *g, int points, char *err,
                           size_t errlen);
/* Checks a grid. 0 or EXIT_USAGE. */
int hemisphere_grid_check(const struct hemi_grid *g, int points, char *err, size_t errlen);

/* The axis conversions engines use (docs/definitions.md): to and from alpha. */
double hemi_to_alpha(enum hemi_quantity q, double v);
double hemi_from_alpha(enum hemi_quantity q, double alpha);

/* The reference a full model is measured against when none is named: its family's (the user
 * model's header, or itself for a built-in). Refused (EXIT_USAGE, naming --reference and the
 * ratio) when model and reference differ by more than 1% at the lobe's peak L = V = N. */
int hemisphere_default_reference(const struct model_spec *m, const struct hemi_axis *axis, struct model_spec *ref,
                                 char *err, size_t errlen);

void hemisphere_open(struct hemi_ctx *h, struct cl_session *s, const char *build_options);
void hemisphere_close(struct hemi_ctx *h);
/* Runs the sweep of m against ref over the axis and grid. 0 or an exit code. */
int hemisphere_run(struct hemi_ctx *h, const struct model_spec *m, const struct model_spec *ref,
                   const struct hemi_axis *axis, const struct hemi_fixed *fixed, int nfixed,
                   const struct hemi_grid *g, struct hemi_result *out);
void hemisphere_result_free(struct hemi_result *r);
const char *hemisphere_status(const struct hemi_result *r);
/* How the device had the reference: "device code", "host double values" (a user model as the
 * reference) or "measured table" (its cells looked up by the host). */
const char *hemisphere_reference_source(const struct hemi_result *r);

/* A model's value in double at L, V about N = z (kind HEMI_KIND_*; vals = n, p0, p1). */
double hemisphere_eval_host(const struct model_spec *m, int kind, const double L[3], const double V[3],
                            const double vals[3]);
/* L and V of the half/difference angles in double (kernels/hemisphere_geom.h). */
void hemisphere_dirs(double th, double td, double pd, double L[3], double V[3]);

#endif
