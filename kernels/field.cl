/*
 * field.cl - the error fields behind the heatmaps: delta(x, n) over the epicentre and
 * Delta(x, n) over the attenuation zone (SPEC.md), on a grid normalised per n.
 *
 * One work-item per grid cell (column, row); row = one shininess n, column = one position
 * along the normalised x axis of each zone:
 *   epicentre:   x = t * x_e(n),           t = col / (cols - 1) in [0, 1]
 *   attenuation: x = x_e(n) * u_max^t      (x / x_e(n) log-spaced from 1 to u_max);
 *                cells past pi/2 are NaN (outside the zone for that n).
 * Scalar float on purpose: the grid is small (a few 10^4 cells), so the simplest
 * evaluation of brdf_eval is the clearest one.
 */
#define REAL float
#define RSCALAR float
#include "brdf_models.h"

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
    const float x_e = acos(exp(-0.511f / n));    /* epicentre end (SPEC.md) */
    const float t = (float)col / (float)(cols - 1);
    const size_t at = (size_t)row * (size_t)cols + (size_t)col;

    float c = cos(t * x_e);
    float f = brdf_eval(model, c, n, p0, p1);
    float r = brdf_eval(ref_model, c, n, rp0, rp1);
    epi_rel[at] = fabs(f - r) / r;

    const float x = x_e * exp(t * log_u_max);
    float d = NAN;
    if (x <= FIELD_HALF_PI + 1e-5f) {   /* the last column of the largest n lands on pi/2, give or take float rounding */
        c = fmax(cos(x), 0.0f);
        f = brdf_eval(model, c, n, p0, p1);
        r = brdf_eval(ref_model, c, n, rp0, rp1);
        d = fabs(f - r);
    }
    att_abs[at] = d;
}
