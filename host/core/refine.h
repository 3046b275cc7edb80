/* refine.h - one-dimensional Brent searches in double precision (GSL): a minimum, a root,
 * and the polish of a maximum found on a device grid, so that a reported figure does not
 * depend on the grid. */
#ifndef BRDF_REFINE_H
#define BRDF_REFINE_H

/* Brent minimisation of f over [lo, hi] from m, which must lie below both ends (GSL's
 * bracket); stops when the bracket is within epsabs + epsrel |x| or after max_iter steps.
 * Writes the minimiser; returns 0, or -1 when GSL refused the bracket (x_out untouched). */
int brent_minimum(double (*f)(double x, void *ctx), void *ctx, double lo, double m, double hi,
                  double epsabs, double epsrel, int max_iter, double *x_out);

/* Brent root of f over [lo, hi], where f changes sign; same stopping rule. Writes the root;
 * returns 0, or -1 when GSL refused the interval (root_out untouched). */
int brent_root(double (*f)(double x, void *ctx), void *ctx, double lo, double hi,
               double epsabs, double epsrel, int max_iter, double *root_out);

/* Maximises g over [a, b], starting from m (a <= m <= b), the best grid point. When g(m) is
 * not above both ends (a maximum at an end), the best of the three is returned.
 * Writes the maximiser and the maximum; returns 0, or -1 if GSL failed (then m is kept). */
int refine_maximum(double (*g)(double x, void *ctx), void *ctx, double a, double m, double b,
                   double *x_out, double *g_out);

#endif
