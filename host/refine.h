/* refine.h - local maximisation in double precision (GSL Brent), used to polish a maximum
 * found on a device grid so that a reported figure does not depend on the grid. */
#ifndef BRDF_REFINE_H
#define BRDF_REFINE_H

/* Maximises g over [a, b], starting from m (a <= m <= b), the best grid point. When g(m) is
 * not above both ends (a maximum at an end), the best of the three is returned.
 * Writes the maximiser and the maximum; returns 0, or -1 if GSL failed (then m is kept). */
int refine_maximum(double (*g)(double x, void *ctx), void *ctx, double a, double m, double b,
                   double *x_out, double *g_out);

#endif
