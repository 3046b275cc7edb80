/* accuracy.h - the dense-grid accuracy sweep as a library: the device sweeps both zones of
 * docs/definitions.md for every n, the host recomputes every reduced figure in double at the device's
 * own inputs, and polishes the range maxima with a local maximisation in double. */
#ifndef BRDF_ACCURACY_H
#define BRDF_ACCURACY_H

#include "jsonw.h"

#include "clsession.h"
#include "models.h"

#define ACC_DEFAULT_SAMPLES 4096
#define ACC_MIN_SAMPLES 16
#define ACC_MAX_SAMPLES (1L << 22)
/* Below 0.1 the epicentre ends within e^(-5.11) of c = 0 and the lobe falls from e^-0.511 to 0
 * inside the last few float steps of s = 1 - c (below n = 0.03 the zone end itself rounds to
 * s = 1, where the lobe is 0): no float grid resolves it. */
#define ACC_MIN_N 0.1
#define ACC_MAX_N 1e6
/* The device-vs-double check (accuracy_run): a figure is trusted when every per-n device value
 * behind it, recomputed in double at the device's own input, differs by at most half a unit in
 * the 4th significant digit of the reported figure: the device then picks a grid point whose
 * true value is within one unit of the grid's best, and the double polish only climbs from
 * there. Differences below ACC_CHECK_FLOAT_FLOOR times the reference's peak (16 float ulps of
 * 1) are float rounding, which no float device can do better than, and are never flagged; nor
 * are, for a figure below float resolution of the peak (2^-23), differences within twice the
 * model's own float error at that point (its float-cancellation figure, probe_rel_diff, brought to
 * the figure's scale): one form of a formula losing digits in float is reported as that figure,
 * not as a search failure. */
#define ACC_CHECK_BOUND_UNITS 0.5
#define ACC_CHECK_FLOAT_FLOOR 1.9073486328125e-06   /* 2^-19 */
/* "a few units of 2^-24 of the peak" below float resolution (docs/definitions.md, Device check) */
#define ACC_CHECK_FLOOR_UNITS 8.0
#define ACC_MAX_N_COUNT 10000000L
#define ACC_MAX_WORK 1e12        /* n values x samples: beyond this a sweep would run for hours */

struct accuracy_grid {
    double n_min, n_max, n_step;   /* n_min, n_min + step, ..., and n_max itself */
    long samples;                  /* per zone per n, a multiple of 16 */
};

/* n_min, n_max and n_step of a grid as every result document writes them (jw_kv_fields). */
#define ACCURACY_GRID_N_FIELDS 3
extern const struct jw_field accuracy_grid_n_fields[ACCURACY_GRID_N_FIELDS];

/* One maximum with where it occurs. value is NAN when there is none (see status). */
struct acc_extreme {
    double value, n, x;
};

/* Per-n figures: as the device reduced them (float, with s = 1 - cos x where they occur),
 * the same maxima polished in double on the host (value and x), and |device - double| of
 * each device figure recomputed in double at the device's own s (NAN when there was none). */
struct acc_per_n {
    double n;
    float epi_rel, epi_rel_s;
    float att_abs, att_abs_s;
    float epi_abs, epi_abs_s;
    float invalid_count, invalid_s;
    struct acc_extreme epi_rel_d, att_abs_d, epi_abs_d;
    double chk_epi_rel, chk_att_abs, chk_epi_abs;
    double ref_peak;               /* the reference's peak f_ref(1, n), the scale of Delta */
};

/* The verdict of the device-vs-double check over some n values, for given figures. */
struct acc_check {
    double units;                  /* worst |device - double| in units of the 4th digit of its figure */
    double diff, n;                /* that difference and where (NAN when nothing was compared) */
    const char *figure;            /* "epicentre.max_rel", "attenuation.max_abs" or "whole.max_abs" */
    int exceeded;                  /* 1 when beyond ACC_CHECK_BOUND_UNITS and the float floor */
};

struct accuracy_result {
    struct model_spec model, reference;
    struct accuracy_grid grid;
    long n_count;
    struct acc_per_n *per_n;
    /* Range maxima over n of the per-n maxima polished in double. */
    struct acc_extreme epicentre, attenuation, whole;
    /* The same maxima as the device found them on its grid, in float. */
    struct acc_extreme grid_epicentre, grid_attenuation, grid_whole;
    /* Largest |device - double host| over every per-n reduced figure, recomputed at the
       device's own inputs: for relative figures (delta) and absolute figures (Delta). */
    double check_rel_diff, check_abs_diff;
    struct acc_check check;        /* the verdict on the reported figures */
    /* Largest relative difference of single model values at random probe points. */
    double probe_rel_diff;
    long long invalid_count;       /* model values that were NaN, Inf or negative */
    double invalid_n, invalid_x;   /* the first such point */
    double device_seconds;         /* sum of kernel times (profiling events) */
    int timer_wall;                /* the events gave no time: device_seconds is wall time */
    double points;                 /* samples evaluated (each: the model and its reference) */
    int ok;                        /* 0 when figures are missing; reason says why */
    int device_disagrees;          /* the check exceeded its bound: reason says where */
    /* A model with binary16 code (its runtime's fp16): the same sweep of its fp16 build (every
       half operation rounded to binary16, kernels/brdf_models.h RHALF). Each per-n maximum is
       located on the device grid, then the fp16 value there is taken from the device and the
       reference's in double on the host; the ratios are over the fp32 figures above. */
    struct {
        int present;
        struct acc_extreme epicentre, attenuation; /* max delta (relative), max Delta (absolute) */
        double ratio_rel, ratio_abs;               /* over epicentre.value, attenuation.value */
        long long invalid_count;                   /* fp16 values that were NaN, Inf or negative */
        int device_fp16;                           /* the device has cl_khr_fp16 (not used: emulated) */
        double device_seconds;
    } fp16;
    char reason[640];
};

struct accuracy_ctx {
    struct cl_session *s;
    cl_program program;
    cl_kernel sweep, probe;
    char build_options[256];
    int timer_wall;                /* the driver's profiling events gave no time: wall time used */
    const struct model_spec *reference;   /* NULL: each model's own reference; else this one (--reference) */
    /* A reference that is a user model is read from a table of its double values (kernels/accuracy.cl,
       ACC_REF_TABLE): that build's kernels, made on first use (the shared ones where builds are not
       specialised), and its options. */
    cl_program table_program;
    cl_kernel table_sweep, table_probe;
    char table_options[288];
};


/* Validates a grid against its domains and the device's limits before any allocation.
 * Returns 0 or EXIT_USAGE with a one-line message naming the argument. */
int accuracy_grid_check(const struct accuracy_grid *g, const struct cl_session *s, char *err, size_t errlen);
/* Number of n values of a grid and the i-th one (as the device sees it: rounded to float). */
long accuracy_grid_count(const struct accuracy_grid *g);
double accuracy_grid_n(const struct accuracy_grid *g, long i);

/* A reference that is a user model is evaluated by the host in double at every sample of the
 * sweep (n values x 2 zones x samples), held as a table the device reads. */
#define ACC_MAX_TABLE_POINTS 16777216L
/* 1 when ref is such a reference (a user model: no case of the device's model dispatch). */
int accuracy_reference_is_table(const struct model_spec *ref);
/* Checks that grid g's table for reference ref fits (its points, and the device's memory when s
 * is given). Returns 0 or EXIT_USAGE with a one-line message naming the argument. */
int accuracy_reference_check(const struct accuracy_grid *g, const struct model_spec *ref, const struct cl_session *s,
                             char *err, size_t errlen);

/* Builds the sweep program once. Returns 0 or an exit code. */
int accuracy_open(struct accuracy_ctx *a, struct cl_session *s, const char *build_options);
void accuracy_close(struct accuracy_ctx *a);
/* Builds what model m needs beyond the shared program (host/core/programs.h): for a user model
 * its own sweep program and its host reference; nothing for a built-in model. accuracy_run calls it too; calling it
 * first reports a user model's compile error (EXIT_USAGE) before any sweep runs. */
int accuracy_prepare(struct accuracy_ctx *a, const struct model_spec *m);
/* Runs the sweep of one model over a checked grid. Returns 0 or an exit code. A sweep asked
 * for again on the same session (the same model, grid, device, driver, build options and
 * reference) is not run again: out receives a copy of the first one's result (the session
 * keeps them, clsession.h: sweeps). */
int accuracy_run(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                 struct accuracy_result *out);
/* How many sweeps accuracy_run gave from an earlier one on session s, and forgetting them all
 * (a test that changes what a sweep would give; clsession_close does it too). */
long accuracy_reused_sweeps(const struct cl_session *s);
void accuracy_forget_sweeps(struct cl_session *s);
void accuracy_result_free(struct accuracy_result *r);
/* Only the device part of a sweep, for timing it: runs the kernel of model m over grid g and
 * returns its raw per-n output (n_count x 8 floats as kernels/accuracy.cl lays them out; raw may
 * be NULL) and the kernel's time from its profiling event (NAN if the timer failed).
 * Returns 0 or an exit code. */
/* The sweep's work-items per n on device s (1 on a CPU device; more on a GPU, so that the
 * launch fills it) and the merge of their per-chunk maxima into one record per n
 * (ACC_OUT_STRIDE floats each), as accuracy_sweep_device does it. */
struct cl_session;
long sweep_chunks(const struct cl_session *s, long count, long samples);
void accuracy_merge_chunks(const float *chunked, long count, long chunks, float *raw);
int accuracy_sweep_device(struct accuracy_ctx *a, const struct model_spec *m, const struct accuracy_grid *g,
                          float *raw, double *device_seconds);
/* Evaluates a model on the device at count points (c[i], n[i]); out has count values. */
int accuracy_probe(struct accuracy_ctx *a, const struct model_spec *m, const float *c, const float *n,
                   size_t count, float *out);

/* The check over the n values in [n_lo, n_hi] of figures measured as max_rel (epicentre),
 * max_abs over the attenuation zone and over the whole range (each NAN when not wanted). */
void accuracy_check_figures(const struct accuracy_result *r, double n_lo, double n_hi, double epi_rel,
                            double att_abs, double whole_abs, struct acc_check *out);
/* n as the device sees it (a float), in the fewest digits that give that float back
 * (0.1, 999000.5, 1e+06; up to 9). */
void accuracy_format_n(double n, char *buf, size_t len);
/* The JSON status word of a result: ok, invalid_values, device_disagrees or failed. */
const char *accuracy_status(const struct accuracy_result *r);

/* One unit in the 4th significant digit of v (the unit every device-vs-double and grid check is
 * told in); 0 when v is not a positive finite number. */
double fourth_digit_unit(double v);

/* Zone geometry in double (docs/definitions.md): x_e(n), and the same end as s = 1 - cos x_e = -expm1(-0.511/n). */
double zone_epicentre_end(double n);
double zone_epicentre_end_s(double n);
/* x = acos(1 - s), without the cancellation: 2 asin(sqrt(s/2)). */
double angle_of_s(double s);
/* Double-precision errors at cosine c: relative |f - r| / r and absolute |f - r|. */
double error_rel_host(const struct model_spec *m, const struct model_spec *ref, double c, double n);
double error_abs_host(const struct model_spec *m, const struct model_spec *ref, double c, double n);

#endif
