/* indep.c - the tests' own brute-force figures, from tests/lobe_formulas.h only (no project
 * code, no kernels/brdf_models.h), printed as JSON for the shell tests that compare them with
 * what the program publishes (claims.json, fit.json, the gates of tests/gates/papers.json).
 *
 * The method differs from the program's on purpose: per n, the epicentre [0, x_e] is a
 * uniform grid of 257 points in x, the attenuation zone (x_e, pi/2] a grid of 513 points
 * geometric in x (x_e (pi/2 / x_e)^t); every local maximum of the grid (end points included)
 * is refined by golden-section search over its two neighbouring cells to 1e-13 of the cell,
 * and the errors are computed in s = 1 - c = 2 sin^2(x/2), exact near the peak.
 *
 *   indep maxima N_MIN N_MAX SPEC...   per model: max delta over the epicentre, max Delta over
 *                                      the attenuation zone and over the epicentre, each with n
 *                                      and x, and the per-n maxima (integer steps of n)
 *   indep bestq N_MIN N_MAX            the Q in [0.6, 0.7] minimising fq's max delta over the
 *                                      range (golden section on Q), with its figures
 *   indep limit N                      the per-n minimax k of (k(c-1)+1)^2 (golden section on k)
 * A SPEC is id or id:p0 or id:p0,p1 (the parameters by position: lyon:2, fq:0.64,
 * quad:0.45,0.1). */
#include "lobe_formulas.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double half_pi = 1.57079632679489661923;

struct model {
    char id[32];
    double p0, p1;
};

static double lobe(const struct model *m, double x, double n)
{
    double sh = sin(x / 2), s = 2 * sh * sh;
    return lf_eval(m->id, cos(x), s, n, m->p0, m->p1);
}
static double ref(double x, double n)
{
    double sh = sin(x / 2);
    return lf_pow(2 * sh * sh, n);
}

enum err_kind { REL, ABS };
static double err_at(const struct model *m, enum err_kind e, double x, double n)
{
    double r = ref(x, n), d = fabs(lobe(m, x, n) - r);
    return e == REL ? d / r : d;
}

/* Golden-section maximum of g over [lo, hi]. */
static double golden_max(const struct model *m, enum err_kind e, double n, double lo, double hi, double *xbest)
{
    const double g = 0.6180339887498949;
    double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
    double fc = err_at(m, e, c, n), fd = err_at(m, e, d, n);
    double tol = 1e-13 * (hi - lo);
    while (b - a > tol) {
        if (fc >= fd) {
            b = d, d = c, fd = fc;
            c = b - g * (b - a), fc = err_at(m, e, c, n);
        } else {
            a = c, c = d, fc = fd;
            d = a + g * (b - a), fd = err_at(m, e, d, n);
        }
    }
    double x = 0.5 * (a + b), f = err_at(m, e, x, n);
    *xbest = x;
    return f;
}

/* The largest error over the grid xs[0..count-1], each local maximum refined. */
static double zone_max(const struct model *m, enum err_kind e, double n, const double *xs, int count, double *at_x)
{
    double best = -1, bx = xs[0];
    double *v = malloc(sizeof(double) * (size_t)count);
    for (int i = 0; i < count; ++i)
        v[i] = err_at(m, e, xs[i], n);
    for (int i = 0; i < count; ++i) {
        int left = i == 0 || v[i] >= v[i - 1], right = i == count - 1 || v[i] >= v[i + 1];
        if (!(left && right))
            continue;
        double x = xs[i], f = v[i];
        if (f > best)
            best = f, bx = x;
        double lo = xs[i > 0 ? i - 1 : 0], hi = xs[i < count - 1 ? i + 1 : count - 1];
        if (hi > lo) {
            double xr, fr = golden_max(m, e, n, lo, hi, &xr);
            if (fr > best)
                best = fr, bx = xr;
        }
    }
    free(v);
    *at_x = bx;
    return best;
}

struct per_n {
    double rel, rel_x, att, att_x, epi_abs, epi_abs_x;
};

static int rel_only;    /* bestq and limit need only the epicentre's max delta */

static void figures_at(const struct model *m, double n, struct per_n *out)
{
    enum { E = 257, A = 513 };
    double xe = lf_epicentre_end_x(n), xs[A];
    for (int i = 0; i < E; ++i)
        xs[i] = xe * i / (E - 1);
    out->rel = zone_max(m, REL, n, xs, E, &out->rel_x);
    if (rel_only) {
        out->epi_abs = out->att = out->epi_abs_x = out->att_x = 0;
        return;
    }
    out->epi_abs = zone_max(m, ABS, n, xs, E, &out->epi_abs_x);
    for (int i = 0; i < A; ++i)
        xs[i] = xe * pow(half_pi / xe, (double)i / (A - 1));
    out->att = zone_max(m, ABS, n, xs, A, &out->att_x);
}

static int parse_model(const char *text, struct model *m)
{
    memset(m, 0, sizeof *m);
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    if (len >= sizeof m->id)
        return -1;
    memcpy(m->id, text, len);
    if (colon && sscanf(colon + 1, "%lf,%lf", &m->p0, &m->p1) < 1)
        return -1;
    return isnan(lf_eval(m->id, 0.9, 0.1, 10, m->p0, m->p1)) ? -1 : 0;
}

/* The range's maxima of a model; per-n arrays printed when print_arrays. */
struct range {
    double rel, rel_n, rel_x, att, att_n, att_x, epi_abs, epi_abs_n;
};
static void range_figures(const struct model *m, double lo, double hi, struct range *r, FILE *arrays)
{
    memset(r, 0, sizeof *r);
    r->rel = r->att = r->epi_abs = -1;
    if (arrays)
        fprintf(arrays, "\"per_n\": [");
    for (double n = lo; n <= hi + 1e-9; n += 1) {
        struct per_n p;
        figures_at(m, n, &p);
        if (p.rel > r->rel)
            r->rel = p.rel, r->rel_n = n, r->rel_x = p.rel_x;
        if (p.att > r->att)
            r->att = p.att, r->att_n = n, r->att_x = p.att_x;
        if (p.epi_abs > r->epi_abs)
            r->epi_abs = p.epi_abs, r->epi_abs_n = n;
        if (arrays)
            fprintf(arrays, "%s{\"n\": %.17g, \"rel\": %.17g, \"att\": %.17g, \"epi_abs\": %.17g}", n > lo ? ", " : "",
                    n, p.rel, p.att, p.epi_abs);
    }
    if (arrays)
        fprintf(arrays, "], ");
}

static void print_range(const char *spec, const struct range *r)
{
    printf("\"spec\": \"%s\", \"max_rel\": %.17g, \"max_rel_n\": %.17g, \"max_rel_x\": %.17g, "
           "\"att_max_abs\": %.17g, \"att_n\": %.17g, \"att_x\": %.17g, \"epi_max_abs\": %.17g, \"epi_abs_n\": %.17g}",
           spec, r->rel, r->rel_n, r->rel_x, r->att, r->att_n, r->att_x, r->epi_abs, r->epi_abs_n);
}

static double fq_objective(double q, double lo, double hi, struct range *r)
{
    struct model m;
    memset(&m, 0, sizeof m);
    strcpy(m.id, "fq");
    m.p0 = q;
    range_figures(&m, lo, hi, r, NULL);
    return r->rel;
}

int main(int argc, char **argv)
{
    if (argc >= 5 && !strcmp(argv[1], "maxima")) {
        double lo = atof(argv[2]), hi = atof(argv[3]);
        printf("[");
        for (int i = 4; i < argc; ++i) {
            struct model m;
            if (parse_model(argv[i], &m)) {
                fprintf(stderr, "indep: unknown model '%s'\n", argv[i]);
                return 2;
            }
            struct range r;
            printf("%s{", i > 4 ? ",\n" : "");
            range_figures(&m, lo, hi, &r, stdout);
            print_range(argv[i], &r);
        }
        printf("]\n");
        return 0;
    }
    if (argc == 4 && !strcmp(argv[1], "bestq")) {
        double lo = atof(argv[2]), hi = atof(argv[3]);
        const double g = 0.6180339887498949;
        double a = 0.6, b = 0.7, c = b - g * (b - a), d = a + g * (b - a);
        struct range r;
        rel_only = 1;
        double fc = fq_objective(c, lo, hi, &r), fd = fq_objective(d, lo, hi, &r);
        while (b - a > 1e-7) {
            if (fc <= fd) {
                b = d, d = c, fd = fc;
                c = b - g * (b - a), fc = fq_objective(c, lo, hi, &r);
            } else {
                a = c, c = d, fc = fd;
                d = a + g * (b - a), fd = fq_objective(d, lo, hi, &r);
            }
        }
        double q = 0.5 * (a + b);
        rel_only = 0;
        fq_objective(q, lo, hi, &r);
        char spec[64];
        snprintf(spec, sizeof spec, "fq:%.10f", q);
        printf("{\"Q\": %.17g, ", q);
        print_range(spec, &r);
        printf("\n");
        return 0;
    }
    if (argc == 3 && !strcmp(argv[1], "limit")) {
        double n = atof(argv[2]);
        struct model m;
        memset(&m, 0, sizeof m);
        strcpy(m.id, "quad");
        rel_only = 1;
        const double g = 0.6180339887498949;
        double a = 0.3 * n, b = 0.6 * n + 1;
        struct per_n p;
        for (int it = 0; it < 200 && b - a > 1e-13 * n; ++it) {
            double c = b - g * (b - a), d = a + g * (b - a);
            m.p1 = c;
            figures_at(&m, n, &p);
            double fc = p.rel;
            m.p1 = d;
            figures_at(&m, n, &p);
            if (fc <= p.rel)
                b = d;
            else
                a = c;
        }
        m.p1 = 0.5 * (a + b);
        figures_at(&m, n, &p);
        printf("{\"n\": %.17g, \"k\": %.17g, \"max_rel\": %.17g}\n", n, m.p1, p.rel);
        return 0;
    }
    fprintf(stderr, "usage: indep maxima N_MIN N_MAX SPEC... | indep bestq N_MIN N_MAX | indep limit N\n");
    return 2;
}
