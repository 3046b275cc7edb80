/*
 * hemisphere_geom.h - the hemisphere sweep's geometry, written once for the device (REAL = float,
 * kernels/hemisphere.cl) and the host's double check (REAL = double, host/measure/accuracy/hemisphere.c).
 *
 * Rusinkiewicz's half/difference angles about N = z (docs/definitions.md, "Full BRDFs over the
 * hemisphere"), with phi_h = 0: the difference vector D = (sin td cos pd, sin td sin pd, cos td)
 * rotated by +theta_h about y is L, and V is L mirrored about H = (sin th, 0, cos th); the same
 * convention as host/core/merl.c's merl_dirs, so (th, td, pd) are the MERL tables' angles.
 *
 * The grid: theta_h = pi/2 u^2, u = (i + 1/2)/NH (the MERL tables' square-root spacing: sharp
 * lobes get samples near theta_h = 0), theta_d = pi/2 (j + 1/2)/ND, phi_d = pi (k + 1/2)/NP
 * (phi_d in [0, pi): an isotropic, reciprocal BRDF repeats itself at phi_d + pi with L and V
 * swapped). Midpoints, so no sample lies on theta_d = pi/2 or on the grid's ends.
 */
#ifndef BRDF_HEMISPHERE_GEOM_H
#define BRDF_HEMISPHERE_GEOM_H

/* The kernel's output record per (parameter value, theta_h row): HEMI_OUT_STRIDE floats, at
   these positions (kernels/hemisphere.cl writes them, host/measure/accuracy/hemisphere.c reads
   them). */
enum hemi_out_field {
    HEMI_O_EPI_REL = 0,      /* max relative error over the epicentre samples */
    HEMI_O_EPI_REL_AT = 1,   /* its sample index j NP + k within the row */
    HEMI_O_ATT_ABS = 2,      /* max absolute error over the other samples */
    HEMI_O_ATT_ABS_AT = 3,
    HEMI_O_EPI_ABS = 4,      /* max absolute error over the epicentre samples */
    HEMI_O_EPI_ABS_AT = 5,
    HEMI_O_SUMSQ = 6,        /* sum of sin(th) dth cos td sin td (cos^2 ti + cos^2 to) (f - f_ref)^2 */
    HEMI_O_USED = 7,         /* samples with N.L > 0 and N.V > 0 (evaluated) */
    HEMI_O_BELOW = 8,        /* grid points with N.L <= 0 or N.V <= 0 (not samples, not evaluated) */
    HEMI_O_INVALID = 9,      /* model values NaN, Inf or negative (excluded from the maxima) */
    HEMI_O_EVAL_BELOW = 10,  /* evaluated samples whose vectors the model saw below the horizon: 0 */
    HEMI_O_REF_PEAK = 11,    /* the row's largest reference value */
    HEMI_O_UNCOVERED = 12,   /* grid points above the horizon where a table reference has no value
                                (a measured material's unmeasured cell): not samples */
    HEMI_OUT_STRIDE = 13     /* floats per record */
};

/* Where a model's value comes from in the sweep (the kernel is built with the kind and id of
   the model and of its reference as constants). */
#define HEMI_KIND_LOBE 0       /* a lobe model f(c, n) lifted: c = N.H (theta_h lobe) or R.V (psi lobe) */
#define HEMI_KIND_PHYSICAL 1   /* a built-in physical model (brdf_pb_eval_h) */
#define HEMI_KIND_USER_FULL 2  /* a user full BRDF of (L, V, N) (brdf_user_full) */
#define HEMI_KIND_MEASURED 3   /* a measured material's table (the host's lookup, hemisphere.c) */
/* A reference the device reads from a buffer of its values at the grid's points, computed by the
   host in double (a user model as the reference of another: a program holds one user model's
   text; a measured material): HEMI_R_KIND only. */
#define HEMI_KIND_TABLE 4

#define HEMI_HALF_PI 1.57079632679489661923

/* The grid's angles (see above). */
BRDF_FN RSCALAR hemi_theta_h(int i, int nh)
{
    RSCALAR u = ((RSCALAR)i + RC(0.5)) / (RSCALAR)nh;
    return RC(HEMI_HALF_PI) * u * u;
}
BRDF_FN RSCALAR hemi_theta_d(int j, int nd) { return RC(HEMI_HALF_PI) * ((RSCALAR)j + RC(0.5)) / (RSCALAR)nd; }
BRDF_FN RSCALAR hemi_phi_d(int k, int np) { return RC(2.0 * HEMI_HALF_PI) * ((RSCALAR)k + RC(0.5)) / (RSCALAR)np; }

/* L and V about N = z from the sines and cosines of theta_h, theta_d and phi_d (REAL: a lane per
   sample on the device, double on the host). */
BRDF_FN void hemi_dirs(REAL sth, REAL cth, REAL sd, REAL cd, REAL spd, REAL cpd, REAL *L, REAL *V)
{
    REAL dx = sd * cpd, dy = sd * spd;
    L[0] = dx * cth + cd * sth;
    L[1] = dy;
    L[2] = cd * cth - dx * sth;
    V[0] = cd * sth - dx * cth;
    V[1] = -dy;
    V[2] = cd * cth + dx * sth;
}

#endif
