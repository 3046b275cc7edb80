/*
 * field.cl - the error fields behind the heatmaps: delta(x, n) over the epicentre and
 * Delta(x, n) over the attenuation zone (docs/definitions.md), on a grid normalised per n.
 *
 * One work-item per grid cell (column, row); row = one shininess n, column = one position
 * along the normalised x axis of each zone:
 *   epicentre:   x = t * x_e(n),           t = col / (cols - 1) in [0, 1]
 *   attenuation: x = x_e(n) * u_max^t      (x / x_e(n) log-spaced from 1 to u_max);
 *                cells past pi/2 are NaN (outside the zone for that n).
 * Scalar float on purpose: the grid is small (a few 10^4 cells), so the simplest
 * evaluation of brdf_eval_s is the clearest one. Cells are evaluated in s = 1 - cos x =
 * 2 sin^2(x/2), as the accuracy sweep does (kernels/accuracy.cl): a float cosine cannot
 * resolve the epicentre at large n.
 */
#define REAL float
#define RSCALAR float
#define BRDF_POW_LOBE_CS(c, s, n) brdf_pow_lobe_s((s), (n))
#include "brdf_models.h"

/* s = 1 - cos x without cancellation. */
static float s_of_x(float x)
{
    const float h = sin(0.5f * x);
    return 2.0f * h * h;
}

#define FIELD_HALF_PI 1.57079632679489662f

__kernel void field_grid(const int model, const float p0, const float p1,
                         const int ref_model, const float rp0, const float rp1,
                         __global const float *n_values, const int rows, const int cols,
                         const float log_u_max,
                         __global float *epi_rel, __global float *att_abs)
{
    const int col = (int)get_global_id(0);
    const int row = (int)get_global_id(1);
    if (col >= cols || row >= rows)
        return;
    const float n = n_values[row];
    const float s_e = -expm1(-(float)BRDF_ZONE_K / n);
    const float x_e = 2.0f * asin(sqrt(0.5f * s_e));   /* epicentre end (docs/definitions.md), acos(1 - s_e) */
    const float t = (float)col / (float)(cols - 1);
    const size_t at = (size_t)row * (size_t)cols + (size_t)col;

    /* A model that sees only c (phongpow, a user model) is compared at the float c it saw. */
    const int c_only = brdf_sees_only_c(model);
    float s = s_of_x(t * x_e);
    if (c_only)
        s = 1.0f - (1.0f - s);
    float f = brdf_eval_s(model, s, n, p0, p1);
    float r = brdf_eval_s(ref_model, s, n, rp0, rp1);
    epi_rel[at] = fabs(f - r) / r;

    const float x = x_e * exp(t * log_u_max);
    float d = NAN;
    if (x <= FIELD_HALF_PI + 1e-5f) {   /* the last column of the largest n lands on pi/2, give or take float rounding */
        s = fmin(s_of_x(x), 1.0f);
        if (c_only)
            s = 1.0f - (1.0f - s);
        f = brdf_eval_s(model, s, n, p0, p1);
        r = brdf_eval_s(ref_model, s, n, rp0, rp1);
        d = fabs(f - r);
    }
    att_abs[at] = d;
}
