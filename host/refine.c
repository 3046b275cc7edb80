/* refine.c - Brent maximisation with GSL around a grid maximum. */
#include "refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <math.h>

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

    gsl_error_handler_t *old = gsl_set_error_handler_off();
    struct negated ng = { g, ctx };
    gsl_function fn = { negate, &ng };
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    int rc = -1;
    if (s && gsl_min_fminimizer_set_with_values(s, &fn, m, -gm, a, -ga, b, -gb) == GSL_SUCCESS) {
        int status = GSL_CONTINUE;
        for (int iter = 0; iter < 200 && status == GSL_CONTINUE; ++iter) {
            if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS)
                break;
            double lo = gsl_min_fminimizer_x_lower(s), hi = gsl_min_fminimizer_x_upper(s);
            status = gsl_min_test_interval(lo, hi, 1e-14, 1e-12);
        }
        double xm = gsl_min_fminimizer_x_minimum(s);
        double gx = g(xm, ctx);
        if (gx > bg) {
            *x_out = xm;
            *g_out = gx;
        }
        rc = 0;
    }
    if (s)
        gsl_min_fminimizer_free(s);
    gsl_set_error_handler(old);
    return rc;
}
