/* refine.c - GSL Brent searches: minimum, root, and the polish of a grid maximum. */
#include "refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <math.h>

int brent_minimum(double (*f)(double x, void *ctx), void *ctx, double lo, double m, double hi,
                  double epsabs, double epsrel, int max_iter, double *x_out)
{
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_function fn = { f, ctx };
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    int rc = -1;
    if (s && gsl_min_fminimizer_set(s, &fn, m, lo, hi) == GSL_SUCCESS) {
        int status = GSL_CONTINUE;
        for (int i = 0; i < max_iter && status == GSL_CONTINUE; ++i) {
            if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS)
                break;
            status = gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), epsabs,
                                           epsrel);
        }
        *x_out = gsl_min_fminimizer_x_minimum(s);
        rc = 0;
    }
    if (s)
        gsl_min_fminimizer_free(s);
    gsl_set_error_handler(old);
    return rc;
}

int brent_root(double (*f)(double x, void *ctx), void *ctx, double lo, double hi,
               double epsabs, double epsrel, int max_iter, double *root_out)
{
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_function fn = { f, ctx };
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    int rc = -1;
    if (s && gsl_root_fsolver_set(s, &fn, lo, hi) == GSL_SUCCESS) {
        int status = GSL_CONTINUE;
        for (int i = 0; i < max_iter && status == GSL_CONTINUE; ++i) {
            if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS)
                break;
            status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), epsabs,
                                            epsrel);
        }
        *root_out = gsl_root_fsolver_root(s);
        rc = 0;
    }
    if (s)
        gsl_root_fsolver_free(s);
    gsl_set_error_handler(old);
    return rc;
}

struct negated {
    double (*g)(double, void *);
    void *ctx;
};

static double negate(double x, void *p)
{
    const struct negated *ng = p;
    return -ng->g(x, ng->ctx);
}

int refine_maximum(double (*g)(double x, void *ctx), void *ctx, double a, double m, double b,
                   double *x_out, double *g_out)
{
    double ga = g(a, ctx), gm = g(m, ctx), gb = g(b, ctx);
    double bx = m, bg = gm;
    if (ga > bg) { bx = a; bg = ga; }
    if (gb > bg) { bx = b; bg = gb; }
    *x_out = bx;
    *g_out = bg;
    if (!(gm > ga && gm > gb) || !(b > a))
        return 0;   /* the maximum is at an end of the bracket: nothing to polish */

    struct negated ng = { g, ctx };
    double xm;
    if (brent_minimum(negate, &ng, a, m, b, 1e-14, 1e-12, 200, &xm) != 0)
        return -1;
    double gx = g(xm, ctx);
    if (gx > bg) {
        *x_out = xm;
        *g_out = gx;
    }
    return 0;
}
