/*
 * usermodel_ref.cl - the reference of a user model: its own text compiled a second time, in
 * double where the device has cl_khr_fp64 (USERMODEL_REF_DOUBLE), else in float.
 *
 * The host (host/core/usermodel.c) appends the user model's text after this file and defines
 * BRDF_HAVE_USER_MODEL, so brdf_eval(BRDF_USER, ...) reaches it through brdf_models.h exactly
 * as in the float and float16 builds. The host's double-precision checks of the accuracy
 * sweep (recomputing each per-n figure, polishing maxima) call usermodel_ref_point.
 */
#ifdef USERMODEL_REF_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define REAL double
#define RSCALAR double
#else
#define REAL float
#define RSCALAR float
#endif
#include "brdf_models.h"

/* One model value: the host asks for single points (a Brent search runs on the host). */
__kernel void usermodel_ref_point(const RSCALAR p0, const RSCALAR p1, const RSCALAR c, const RSCALAR n,
                                  __global RSCALAR *out)
{
    if (get_global_id(0) == 0)
        out[0] = brdf_eval(BRDF_USER, c, n, p0, p1);
}
