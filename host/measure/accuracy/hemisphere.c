/* hemisphere.c - the hemisphere sweep of a full BRDF (hemisphere.h): the parameter axis and its
 * conversions, the device passes of kernels/hemisphere.cl, the double recomputation and
 * refinement of every maximum, the device-vs-double check with its float floor. */
#include "hemisphere.h"
#include "accuracy.h"
#include "exitcodes.h"
#include "lcg.h"
#include "programs.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#include "hemisphere_geom.h"

static const double pi = 3.14159265358979323846;

/* A full BRDF is measured over the hemisphere, except where its file declares it a lobe of one
 * angle that the hemisphere's reference cannot take: a Phong lobe in psi (its reference's variable
 * is the angle between R and V, not theta_h), and a Fresnel or shadowing-masking term measured
 * against a built-in term (a function of one angle and its parameter: docs/user-models.md). */
int hemisphere_applies(const struct model_spec *m)
{
    if (model_is_full(m->info)) {
        const struct model_info *ref = m->info->reference_id ? models_find(m->info->reference_id) : NULL;
        int psi_declared = model_lobe_declared(m->info) && m->info->lobe == LOBE_PSI;
        return !psi_declared && !(ref && ref->family == MODEL_FAMILY_TERM);
    }
    return model_is_builtin(m->info) && m->info->family == MODEL_FAMILY_PHYSICAL;
}

/* A measured reference's kernel_id: no row of the registry has it. */
#define HEMI_MEASURED_ID (-2)

int hemisphere_applies_against(const struct model_spec *m, const struct model_spec *named_ref)
{
    if (named_ref && model_is_full(m->info) && model_is_builtin(named_ref->info) &&
        named_ref->info->family == MODEL_FAMILY_TERM)
        return 0;
    return hemisphere_applies(m);
}

/* HEMI_KIND_* of a model, or -1 when the sweep cannot evaluate it (a user lobe model). */
static int model_kind(const struct model_spec *m)
{
    if (m->info->kernel_id == HEMI_MEASURED_ID && !model_is_builtin(m->info) && !models_runtime(m->info))
        return HEMI_KIND_MEASURED;
    if (model_is_full(m->info))
        return HEMI_KIND_USER_FULL;
    if (!model_is_builtin(m->info))
        return -1;
    return m->info->family == MODEL_FAMILY_PHYSICAL ? HEMI_KIND_PHYSICAL : HEMI_KIND_LOBE;
}

int hemisphere_reference_ok(const struct model_spec *ref)
{
    int k = model_kind(ref);
    return k == HEMI_KIND_LOBE || k == HEMI_KIND_PHYSICAL || k == HEMI_KIND_USER_FULL || k == HEMI_KIND_MEASURED;
}

/* 1 when the device reads the reference's values from the host's table (kernels/hemisphere.cl):
   a user model (a program holds one user model's text, the measured model's) or a measured one. */
static int kind_is_table(int kind) { return kind == HEMI_KIND_USER_FULL || kind == HEMI_KIND_MEASURED; }

/* ---- a measured reference ------------------------------------------------------------------ */

int hemisphere_measured_open(const char *path, struct hemi_measured *hm, struct model_spec *spec, char *err,
                             size_t errlen)
{
    memset(hm, 0, sizeof *hm);
    int rc = merl_read(path, &hm->mat, err, errlen);
    if (rc)
        return rc;
    snprintf(hm->id, sizeof hm->id, "merl:%.290s", hm->mat.name);
    hm->info.id = hm->id;
    hm->info.kernel_id = HEMI_MEASURED_ID;
    hm->info.family = MODEL_FAMILY_REFERENCE;
    hm->info.lobe = LOBE_THETA_H;
    hm->info.nparams = 0;
    hm->info.reference_id = hm->id;
    hm->info.formula = "the luminance of the measured table's cell (nearest, no interpolation)";
    hm->info.description = "a measured material (MERL format)";
    hm->info.kind = MODEL_KIND_OTHER;
    memset(spec, 0, sizeof *spec);
    spec->info = &hm->info;
    snprintf(spec->label, sizeof spec->label, "%.*s", (int)sizeof spec->label - 1, hm->id);
    return 0;
}

void hemisphere_measured_close(struct hemi_measured *hm)
{
    merl_free(&hm->mat);
}

/* The measured reference's value at L, V about N = z: its cell's luminance, NAN where a channel
   of the cell was not measured (that grid point is no sample). */
static double measured_eval(const struct model_spec *m, const double L[3], const double V[3])
{
    static const double N[3] = { 0, 0, 1 };
    const struct hemi_measured *hm = (const struct hemi_measured *)m->info;   /* info is its first member */
    double th, td, pd, rgb[3];
    merl_half_diff(L, V, N, &th, &td, &pd);
    if (!isfinite(th) || !isfinite(td) || !isfinite(pd))
        return NAN;
    if (!merl_cell(&hm->mat, merl_index(th, td, pd, NULL, NULL, NULL), rgb))
        return NAN;
    return brdf_merl_luminance(rgb[0], rgb[1], rgb[2]);
}

/* ---- the axis ------------------------------------------------------------------------------ */

static const struct { const char *name; enum hemi_quantity q; } quantities[] = {
    { "n", HQ_N }, { "alpha", HQ_ALPHA }, { "roughness", HQ_ROUGHNESS }, { "m", HQ_M },
};

double hemi_to_alpha(enum hemi_quantity q, double v)
{
    switch (q) {
    case HQ_N: return sqrt(2.0 / (v + 2.0));   /* alpha = sqrt(2/(n+2)) */
    case HQ_ROUGHNESS: return v * v;          /* alpha = r^2 */
    case HQ_ALPHA:
    case HQ_M: return v;                      /* Beckmann m = alpha */
    default: return NAN;
    }
}

double hemi_from_alpha(enum hemi_quantity q, double a)
{
    switch (q) {
    case HQ_N: return 2.0 / (a * a) - 2.0;
    case HQ_ROUGHNESS: return sqrt(a);
    case HQ_ALPHA:
    case HQ_M: return a;
    default: return NAN;
    }
}

static int parse_number(const char *s, const char *end, double *out)
{
    char buf[64];
    size_t len = (size_t)(end - s);
    if (len == 0 || len >= sizeof buf)
        return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *e;
    *out = strtod(buf, &e);
    return (*e || !isfinite(*out)) ? -1 : 0;
}

static int valid_name(const char *s, size_t len)
{
    if (len == 0 || len >= 48)
        return 0;
    for (size_t i = 0; i < len; ++i)
        if (!(s[i] == '_' || (s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') ||
              (i > 0 && s[i] >= '0' && s[i] <= '9')))
            return 0;
    return 1;
}

int hemisphere_axis_parse(const char *text, struct hemi_axis *a, char *err, size_t errlen)
{
    const char *eq = strchr(text, '=');
    size_t nlen = eq ? (size_t)(eq - text) : strlen(text);
    /* PARAM:ROLE: a model parameter under another name than the engines' (e.g. a .brdf file's c
       that is GGX's alpha) */
    const char *role = memchr(text, ':', nlen);
    size_t plen = role ? (size_t)(role - text) : nlen;
    if (!valid_name(text, plen) || (role && !valid_name(role + 1, nlen - plen - 1))) {
        snprintf(err, errlen, "--axis: '%.60s' is not NAME or NAME=MIN:MAX (accepted: n, alpha, roughness, m or a "
                              "parameter of the model, e.g. --axis roughness=0.1:0.9; or PARAM:ROLE[=MIN:MAX], e.g. "
                              "--axis c:alpha)", text);
        return EXIT_USAGE;
    }
    memcpy(a->name, text, nlen);
    a->name[nlen] = '\0';
    a->target[0] = '\0';
    const char *qname = a->name;
    if (role) {
        memcpy(a->target, text, plen);
        a->target[plen] = '\0';
        qname = a->name + plen + 1;
    }
    a->q = HQ_PARAM;
    for (size_t i = 0; i < sizeof quantities / sizeof quantities[0]; ++i)
        if (strcmp(qname, quantities[i].name) == 0)
            a->q = quantities[i].q;
    if (role && a->q == HQ_PARAM) {
        snprintf(err, errlen, "--axis: '%.60s': the role '%s' is unknown (accepted roles: n, alpha, roughness, m, "
                              "e.g. --axis c:alpha)", text, qname);
        return EXIT_USAGE;
    }
    a->min = a->max = NAN;
    if (eq) {
        const char *colon = strchr(eq + 1, ':');
        if (!colon || parse_number(eq + 1, colon, &a->min) || parse_number(colon + 1, colon + strlen(colon), &a->max) ||
            !(a->min < a->max)) {
            snprintf(err, errlen, "--axis: '%.60s': the range is MIN:MAX, two numbers with MIN < MAX (e.g. "
                                  "--axis roughness=0.1:0.9)", text);
            return EXIT_USAGE;
        }
    }
    return 0;
}

int hemisphere_fixed_parse(const char *text, struct hemi_fixed *fixed, int *count, char *err, size_t errlen)
{
    const char *eq = strchr(text, '=');
    size_t nlen = eq ? (size_t)(eq - text) : 0;
    double v;
    if (!eq || !valid_name(text, nlen) || parse_number(eq + 1, eq + strlen(eq), &v)) {
        snprintf(err, errlen, "--param: '%.60s' is not NAME=VALUE with a finite number (e.g. --param F0=0.04)", text);
        return EXIT_USAGE;
    }
    if (*count >= HEMI_MAX_FIXED) {
        snprintf(err, errlen, "--param: more than %d values (accepted: at most %d --param)", HEMI_MAX_FIXED,
                 HEMI_MAX_FIXED);
        return EXIT_USAGE;
    }
    memcpy(fixed[*count].name, text, nlen);
    fixed[*count].name[nlen] = '\0';
    fixed[*count].value = v;
    ++*count;
    return 0;
}

static int param_index(const struct model_spec *m, const char *name)
{
    for (int k = 0; k < m->info->nparams; ++k)
        if (strcmp(m->info->params[k].name, name) == 0)
            return k;
    return -1;
}

/* The range of a shininess quantity from the n range (alpha falls as n grows). */
static void quantity_range(enum hemi_quantity q, double n_min, double n_max, double *lo, double *hi)
{
    if (q == HQ_N) {
        *lo = n_min;
        *hi = n_max;
        return;
    }
    *lo = hemi_from_alpha(q, hemi_to_alpha(HQ_N, n_max));
    *hi = hemi_from_alpha(q, hemi_to_alpha(HQ_N, n_min));
}

int hemisphere_axis_check(struct hemi_axis *a, const struct hemi_fixed *fixed, int nfixed,
                          const struct model_spec *m, const struct model_spec *ref, double n_min, double n_max,
                          char *err, size_t errlen)
{
    if (!hemisphere_reference_ok(ref)) {
        snprintf(err, errlen, "--reference: %s is a lobe of c and n, not a BRDF of (L, V), so it cannot be the "
                              "reference of the full BRDF %s (accepted: a built-in model, e.g. blinn, ggx or "
                              "ct-ggx:F0=0.04, a full user model or its file, or merl:FILE.binary)", ref->label,
                 m->label);
        return EXIT_USAGE;
    }
    for (int i = 0; i < nfixed; ++i)
        if (param_index(m, fixed[i].name) < 0 && strcmp(fixed[i].name, "n") != 0) {
            snprintf(err, errlen, "--param: %s has no parameter '%s' (accepted: n%s%s%s%s)", m->label, fixed[i].name,
                     m->info->nparams > 0 ? ", " : "", m->info->nparams > 0 ? m->info->params[0].name : "",
                     m->info->nparams > 1 ? ", " : "", m->info->nparams > 1 ? m->info->params[1].name : "");
            return EXIT_USAGE;
        }
    for (int i = 0; i < nfixed; ++i) {
        /* a value the model's own range refuses is refused here too (a bool of a .brdf file is an
           integer parameter in [0, 1]) */
        int k = param_index(m, fixed[i].name);
        if (k < 0)
            continue;
        const struct model_param *pp = &m->info->params[k];
        double v = fixed[i].value;
        if (!(v >= pp->min && v <= pp->max) || (pp->integer && v != floor(v))) {
            if (pp->integer && pp->min == 0 && pp->max == 1)
                snprintf(err, errlen, "--param: %s=%g is out of range (accepted: 0 or 1)", fixed[i].name, v);
            else
                snprintf(err, errlen, "--param: %s=%g is out of range (accepted: %s in [%g, %g])", fixed[i].name, v,
                         pp->integer ? "an integer" : "a number", pp->min, pp->max);
            return EXIT_USAGE;
        }
    }
    if (a->target[0]) {
        int k = param_index(m, a->target);
        if (k < 0) {
            snprintf(err, errlen, "--axis: %s has no parameter '%s' (accepted: %s%s%s)", m->label, a->target,
                     m->info->nparams > 0 ? m->info->params[0].name : "none",
                     m->info->nparams > 1 ? ", " : "", m->info->nparams > 1 ? m->info->params[1].name : "");
            return EXIT_USAGE;
        }
        const struct model_param *pp = &m->info->params[k];
        double lo, hi;
        quantity_range(a->q, 0.0, 1e6, &lo, &hi);
        lo = fmax(lo, pp->min);
        hi = fmin(hi, pp->max);
        if (isnan(a->min)) {
            quantity_range(a->q, n_min, n_max, &a->min, &a->max);
            a->min = fmax(a->min, lo);
            a->max = fmin(a->max, hi);
        }
        if (!(a->min >= lo && a->max <= hi && a->min > 0 && a->min < a->max)) {
            snprintf(err, errlen, "--axis: %s=%g:%g is out of range (accepted: %g <= %s <= %g, the range of both "
                                  "%s and %s)", a->name, a->min, a->max, lo, a->target, hi, a->target, a->name +
                                  strlen(a->target) + 1);
            return EXIT_USAGE;
        }
        a->geometric = a->max / a->min > 10;
        return 0;
    }
    if (a->q == HQ_PARAM) {
        int k = param_index(m, a->name);
        if (k < 0) {
            snprintf(err, errlen, "--axis: %s has no parameter '%s' (accepted: n, alpha, roughness, m%s%s%s%s)",
                     m->label, a->name, m->info->nparams > 0 ? ", " : "",
                     m->info->nparams > 0 ? m->info->params[0].name : "", m->info->nparams > 1 ? ", " : "",
                     m->info->nparams > 1 ? m->info->params[1].name : "");
            return EXIT_USAGE;
        }
        const struct model_param *pp = &m->info->params[k];
        if (isnan(a->min)) {
            a->min = pp->min;
            a->max = pp->max;
        } else if (a->min < pp->min || a->max > pp->max) {
            snprintf(err, errlen, "--axis: %s=%g:%g is outside the declared range of %s (accepted: %g to %g)",
                     a->name, a->min, a->max, a->name, pp->min, pp->max);
            return EXIT_USAGE;
        }
        a->geometric = 0;
        return 0;
    }
    double lo, hi;
    quantity_range(a->q, 0.0, 1e6, &lo, &hi);   /* every n the registry accepts */
    if (isnan(a->min))
        quantity_range(a->q, n_min, n_max, &a->min, &a->max);
    else if (a->min < lo || a->max > hi || !(a->min > 0)) {
        snprintf(err, errlen, "--axis: %s=%g:%g is out of range (accepted: %g <= %s <= %g)", a->name, a->min, a->max,
                 lo, a->name, hi);
        return EXIT_USAGE;
    }
    a->geometric = a->min > 0 && a->max / a->min > 10;
    return 0;
}

int hemisphere_grid_check(const struct hemi_grid *g, int points, char *err, size_t errlen)
{
    if (g->nh < HEMI_MIN_CELLS || g->nh > HEMI_MAX_CELLS || g->nd < HEMI_MIN_CELLS || g->nd > HEMI_MAX_CELLS ||
        g->np < HEMI_MIN_CELLS || g->np > HEMI_MAX_CELLS) {
        snprintf(err, errlen, "--hemisphere-grid: %dx%dx%d is out of range (accepted: each of theta_h, theta_d, "
                              "phi_d cells in [%d, %d])", g->nh, g->nd, g->np, HEMI_MIN_CELLS, HEMI_MAX_CELLS);
        return EXIT_USAGE;
    }
    if ((double)g->nd * g->np >= 16777216.0) {
        snprintf(err, errlen, "--hemisphere-grid: %d x %d cells per theta_h row is more than 2^24 (accepted: fewer)",
                 g->nd, g->np);
        return EXIT_USAGE;
    }
    /* every sample is also summed in double on the host (the RMS): beyond this a run takes minutes */
    if ((double)points * g->nh * g->nd * g->np > HEMI_MAX_WORK) {
        snprintf(err, errlen, "--hemisphere-grid: %dx%dx%d cells x %d axis values is %.3g grid points (accepted: at "
                              "most %.0e; fewer cells or --axis-points)", g->nh, g->nd, g->np, points,
                 (double)points * g->nh * g->nd * g->np, HEMI_MAX_WORK);
        return EXIT_USAGE;
    }
    if (points < 1 || points > HEMI_MAX_POINTS) {
        snprintf(err, errlen, "--axis-points: %d is out of range (accepted: 1 to %d)", points, HEMI_MAX_POINTS);
        return EXIT_USAGE;
    }
    return 0;
}

/* The axis value of index i of count. */
static double axis_value(const struct hemi_axis *a, int i)
{
    if (a->count <= 1)
        return a->min;
    if (i == a->count - 1)
        return a->max;
    double t = (double)i / (double)(a->count - 1);
    return a->geometric ? a->min * pow(a->max / a->min, t) : a->min + (a->max - a->min) * t;
}

/* 1 when a model's shininess argument is n: a built-in, or a BRDF Explorer file (its wrapper
   hands n to its `n`, or alpha(n) to its `alpha`: docs/user-models.md). */
static int slot_is_n(const struct model_spec *m)
{
    if (model_is_builtin(m->info))
        return 1;
    /* the registry's words for a run-time model: "user model 'NAME' (ORIGIN)" */
    const struct model_runtime *rt = models_runtime(m->info);
    size_t len = rt && rt->what ? strlen(rt->what) : 0;
    return len > 6 && strcmp(rt->what + len - 6, ".brdf)") == 0;
}

/* The shininess slot of a model: n, converted from the axis, for a built-in or a .brdf file; a
   shader function's own argument takes the axis's quantity as it is (the user names what the
   argument is with --axis: n, alpha, roughness, m). */
static double slot_value(const struct model_spec *m, enum hemi_quantity axis_q, double v)
{
    if (!slot_is_n(m) || axis_q == HQ_N)
        return v;
    return hemi_from_alpha(HQ_N, hemi_to_alpha(axis_q, v));
}

/* The model's and the reference's (n, p0, p1) at one axis value v (already a float). */
static void values_at(const struct hemi_axis *a, const struct hemi_fixed *fixed, int nfixed,
                      const struct model_spec *m, const struct model_spec *ref, double v, double mv[3], double rv[3])
{
    double slot_n = 100.0, fixed_n = NAN;   /* the slot's value when the axis is a named parameter */
    for (int i = 0; i < nfixed; ++i)
        if (strcmp(fixed[i].name, "n") == 0)
            fixed_n = fixed[i].value;
    if (!isnan(fixed_n))
        slot_n = fixed_n;
    enum hemi_quantity q = a->q == HQ_PARAM ? HQ_N : a->q;
    double qv = a->q == HQ_PARAM ? slot_n : v;
    mv[0] = slot_value(m, q, qv);
    rv[0] = slot_value(ref, q, qv);
    for (int k = 0; k < 2; ++k) {
        mv[k + 1] = k < m->info->nparams ? m->params[k] : 0.0;
        rv[k + 1] = k < ref->info->nparams ? ref->params[k] : 0.0;
    }
    for (int i = 0; i < nfixed; ++i) {
        int k = param_index(m, fixed[i].name);
        if (k >= 0)
            mv[k + 1] = fixed[i].value;
    }
    if (a->target[0]) {
        /* the model's parameter takes the axis's values as they are (it is the role's quantity);
           the reference's slot got them converted above */
        int k = param_index(m, a->target);
        if (k >= 0)
            mv[k + 1] = v;
    }
    if (a->q == HQ_PARAM) {
        int k = param_index(m, a->name), rk = param_index(ref, a->name);
        mv[k + 1] = v;
        if (rk >= 0)   /* the same parameter of the reference follows the axis (like with like) */
            rv[rk + 1] = v;
    }
    /* v is a float, as the device sees it; the converted values stay double here: the reference's
       converted n in double gives the model's own alpha exactly, so a model equal to its
       reference through a conversion measures 0 in double, and the device's rounding of the
       converted values is float noise that the check's floor covers */
}

/* ---- double evaluation ---------------------------------------------------------------------- */

void hemisphere_dirs(double th, double td, double pd, double L[3], double V[3])
{
    hemi_dirs(sin(th), cos(th), sin(td), cos(td), sin(pd), cos(pd), L, V);
}

double hemisphere_eval_host(const struct model_spec *m, int kind, const double L[3], const double V[3],
                            const double vals[3])
{
    static const double N[3] = { 0, 0, 1 };
    double nl = L[2], nv = V[2];
    double lv = L[0] * V[0] + L[1] * V[1] + L[2] * V[2];
    double hx = L[0] + V[0], hy = L[1] + V[1], hz = L[2] + V[2];
    double hn = sqrt(hx * hx + hy * hy + hz * hz);
    double ch = hz / hn, cd = (V[0] * hx + V[1] * hy + V[2] * hz) / hn;
    /* 1 - cos theta_h without cancellation: sin^2 theta_h / (1 + cos theta_h) */
    double sh = (hx * hx + hy * hy) / (hn * hn) / (1.0 + ch);
    switch (kind) {
    case HEMI_KIND_LOBE:
        if (m->info->lobe == LOBE_PSI) {
            double c = fmax(2.0 * nl * nv - lv, 0.0);
            return brdf_eval_cs(m->info->kernel_id, c, 1.0 - c, vals[0], vals[1], vals[2]);
        }
        return brdf_eval_cs(m->info->kernel_id, ch, sh, vals[0], vals[1], vals[2]);
    case HEMI_KIND_PHYSICAL:
        return brdf_pb_eval_h(m->info->kernel_id, nl, nv, lv, ch, cd, vals[0], vals[1], vals[2], 1.0);
    case HEMI_KIND_USER_FULL: {
        struct model_spec s = *m;
        s.params[0] = vals[1];
        s.params[1] = vals[2];
        return model_eval_full_host(&s, L, V, N, vals[0]);
    }
    case HEMI_KIND_MEASURED:
        return measured_eval(m, L, V);
    default:
        return NAN;
    }
}

/* ---- refinement in double ------------------------------------------------------------------- */

enum figure { FIG_EPI_REL, FIG_ATT_ABS, FIG_WHOLE_ABS };

struct fig_ctx {
    const struct hemi_result *r;
    const struct hemi_per_p *pp;
    double threshold;                  /* the epicentre's f_ref at this p */
    enum figure fig;
};

/* The figure's error at (th, td, phi_d), or -INFINITY where it is no sample of the figure:
   below the horizon, outside its zone, or an invalid model value. */
static double figure_at(const struct fig_ctx *c, double th, double td, double pd)
{
    if (!(th >= 0 && th < pi / 2 && td >= 0 && td < pi / 2))
        return -INFINITY;
    double L[3], V[3];
    hemisphere_dirs(th, td, pd, L, V);
    if (!(L[2] > 0 && V[2] > 0))
        return -INFINITY;
    double f = hemisphere_eval_host(&c->r->model, c->r->model_kind, L, V, c->pp->mvals);
    double r = hemisphere_eval_host(&c->r->reference, c->r->ref_kind, L, V, c->pp->rvals);
    if (!(f >= 0) || !isfinite(f) || !isfinite(r))
        return -INFINITY;
    int epi = r >= c->threshold;
    if ((c->fig == FIG_EPI_REL && !epi) || (c->fig == FIG_ATT_ABS && epi))
        return -INFINITY;
    return c->fig == FIG_EPI_REL ? fabs(f - r) / r : fabs(f - r);
}

/* Local lattice refinement around (th, td, pd): 5^3 points over the box, move to the best,
   halve the box when the best is inside it (walk on when it is at its side), until the value's
   4th significant digit has stayed over four halvings and the box is below 1e-7 rad. */
static struct hemi_extreme refine(const struct fig_ctx *c, double th, double td, double pd, double hth, double htd,
                                  double hpd)
{
    struct hemi_extreme e = { figure_at(c, th, td, pd), c->pp->p, th, td, pd };
    int stable = 0;
    double last_unit_value = e.value;
    for (int iter = 0; iter < 200 && (stable < 4 || hth > 1e-7); ++iter) {
        double best = e.value, bth = e.th, btd = e.td, bpd = e.pd;
        for (int a = -2; a <= 2; ++a)
            for (int b = -2; b <= 2; ++b)
                for (int k = -2; k <= 2; ++k) {
                    double x = e.th + 0.5 * a * hth, y = e.td + 0.5 * b * htd, z = e.pd + 0.5 * k * hpd;
                    double v = figure_at(c, x, y, z);
                    if (v > best) {
                        best = v;
                        bth = x;
                        btd = y;
                        bpd = z;
                    }
                }
        int inside = fabs(bth - e.th) < 0.9 * hth && fabs(btd - e.td) < 0.9 * htd && fabs(bpd - e.pd) < 0.9 * hpd;
        e.value = best;
        e.th = bth;
        e.td = btd;
        e.pd = bpd;
        if (inside) {
            hth *= 0.5;
            htd *= 0.5;
            hpd *= 0.5;
            double unit = fourth_digit_unit(e.value);
            stable = (unit == 0 || fabs(e.value - last_unit_value) < 0.5 * unit) ? stable + 1 : 0;
            last_unit_value = e.value;
        }
    }
    if (!(e.value > -INFINITY))
        e.value = NAN;
    /* phi_d back into [0, pi) (reciprocity: the pair at phi_d + pi is the same one swapped) */
    e.pd = fmod(fmod(e.pd, pi) + pi, pi);
    return e;
}

/* ---- programs -------------------------------------------------------------------------------- */

void hemisphere_open(struct hemi_ctx *h, struct cl_session *s, const char *build_options)
{
    memset(h, 0, sizeof *h);
    h->s = s;
    snprintf(h->build_options, sizeof h->build_options, "%s", build_options ? build_options : "");
}

void hemisphere_close(struct hemi_ctx *h)
{
    for (int i = 0; i < h->nprogs; ++i) {
        cl_kernel *const k[] = { &h->progs[i].sweep, &h->progs[i].probe };
        clsession_release_kernels(&h->progs[i].program, 2, k);
    }
    h->nprogs = 0;
}

/* Lanes per step of the kernel's loop (kernels/hemisphere.cl, HEMI_W). */
static int hemi_lanes(const struct hemi_ctx *h) { return h->s->specialise ? 1 : 16; }

static int kernels_for(struct hemi_ctx *h, const struct hemi_result *r, cl_kernel *sweep, cl_kernel *probe)
{
    char options[256];
    /* a session that specialises (a driver that vectorises across work-items itself) gets the
       scalar loop, as the lobe sweep's ACC_W */
    snprintf(options, sizeof options, "%.120s%s-DHEMI_M_KIND=%d -DHEMI_M_ID=%d -DHEMI_M_PSI=%d -DHEMI_R_KIND=%d "
             "-DHEMI_R_ID=%d -DHEMI_R_PSI=%d -DHEMI_W=%d", h->build_options, h->build_options[0] ? " " : "",
             r->model_kind, r->model.info->kernel_id, r->model.info->lobe == LOBE_PSI,
             r->ref_table ? HEMI_KIND_TABLE : r->ref_kind, r->ref_table ? 0 : r->reference.info->kernel_id,
             r->reference.info->lobe == LOBE_PSI, hemi_lanes(h));
    if (!model_is_builtin(r->model.info)) {
        int rc = programs_kernel(h->s, "hemisphere.cl", options, &r->model, "hemisphere_sweep", NULL, sweep);
        if (!rc)
            rc = programs_kernel(h->s, "hemisphere.cl", options, &r->model, "hemisphere_probe", NULL, probe);
        return rc;
    }
    for (int i = 0; i < h->nprogs; ++i)
        if (strcmp(h->progs[i].options, options) == 0) {
            *sweep = h->progs[i].sweep;
            *probe = h->progs[i].probe;
            return 0;
        }
    if (h->nprogs == (int)(sizeof h->progs / sizeof h->progs[0]))
        hemisphere_close(h);   /* a run of more pairs than the cache holds builds again */
    struct hemi_prog *p = &h->progs[h->nprogs];
    memset(p, 0, sizeof *p);
    snprintf(p->options, sizeof p->options, "%s", options);
    static const char *const names[] = { "hemisphere_sweep", "hemisphere_probe" };
    cl_kernel *const kernels[] = { &p->sweep, &p->probe };
    int rc = clsession_build_kernels(h->s, "hemisphere.cl", NULL, options, &p->program, 2, names, kernels);
    if (rc)
        return rc;
    ++h->nprogs;
    *sweep = p->sweep;
    *probe = p->probe;
    return 0;
}

/* ---- the run --------------------------------------------------------------------------------- */

int hemisphere_default_reference(const struct model_spec *m, const struct hemi_axis *axis, struct model_spec *ref,
                                 char *err, size_t errlen)
{
    model_reference_spec(m, ref);
    if (strcmp(ref->info->id, m->info->id) == 0 && model_is_builtin(m->info)) {
        *ref = *m;   /* a built-in physical model against itself, with its own parameters */
        return 0;
    }
    int mk = model_kind(m), rk = model_kind(ref);
    if (mk < 0 || rk < 0 || rk == HEMI_KIND_USER_FULL) {
        snprintf(err, errlen, "%s: its reference %s cannot be measured over the hemisphere: name one with "
                              "--reference (e.g. --reference blinn)", m->label, ref->label);
        return EXIT_USAGE;
    }
    /* the lobe's peak, L = V = N, at the middle of the axis (n = 100 for a parameter's axis) */
    struct hemi_axis a = *axis;
    double lo = a.min, hi = a.max;
    if (a.q != HQ_PARAM && isnan(lo))
        quantity_range(a.q, 2.0, 1000.0, &lo, &hi);
    double v = a.q == HQ_PARAM ? 100.0 : sqrt(lo * hi);
    a.q = a.q == HQ_PARAM ? HQ_N : a.q;
    double L[3] = { 0, 0, 1 }, mv[3], rv[3];
    values_at(&a, NULL, 0, m, ref, v, mv, rv);
    double f = hemisphere_eval_host(m, mk, L, L, mv), fr = hemisphere_eval_host(ref, rk, L, L, rv);
    double ratio = f / fr;
    if (!(fabs(ratio - 1.0) <= 0.01)) {
        snprintf(err, errlen, "%s: no --reference named, and its family's reference %s differs from it at the lobe's "
                              "peak (L = V = N, %s = %.4g) by the ratio %.6g (accepted: within 1%%): name one with "
                              "--reference", m->label, ref->label, a.q == HQ_N ? "n" : a.name, v, ratio);
        return EXIT_USAGE;
    }
    return 0;
}

const char *hemisphere_status(const struct hemi_result *r)
{
    return !r->ok ? "failed" : r->device_disagrees ? "device_disagrees" : r->invalid ? "invalid_values" : "ok";
}

const char *hemisphere_reference_source(const struct hemi_result *r)
{
    return r->ref_kind == HEMI_KIND_MEASURED ? "measured table" : r->ref_table ? "host double values" : "device code";
}

void hemisphere_result_free(struct hemi_result *r)
{
    free(r->per_p);
    r->per_p = NULL;
    free(r->ref_values);
    r->ref_values = NULL;
}

int hemisphere_table_check(const struct model_spec *ref, const struct hemi_grid *g, int points, char *err,
                           size_t errlen)
{
    if (!kind_is_table(model_kind(ref)))
        return 0;
    double values = (double)points * g->nh * g->nd * (double)((g->np + 15) / 16 * 16);
    if (values > (double)HEMI_MAX_TABLE) {
        snprintf(err, errlen, "--reference: %s is evaluated by the host at each of %.4g grid points x axis values "
                              "(accepted: at most %ld; fewer --hemisphere-grid cells or --axis-points)", ref->label,
                 values, HEMI_MAX_TABLE);
        return EXIT_USAGE;
    }
    return 0;
}

/* The reference's double values at every grid point above the horizon (NAN elsewhere) into out,
   per (p, theta_h, theta_d, phi_d): run through model_run_isolated, so that a user model's code
   is called directly in its sandbox's child for the whole table, not a round trip per value. */
static void fill_values(void *vctx, void *vout)
{
    const struct hemi_result *r = vctx;
    const struct hemi_grid *g = &r->grid;
    double *out = vout;
    for (int ip = 0; ip < r->p_count; ++ip)
        for (int i = 0; i < g->nh; ++i) {
            double th = hemi_theta_h(i, g->nh);
            for (int j = 0; j < g->nd; ++j) {
                double td = hemi_theta_d(j, g->nd);
                double *row = out + (((size_t)ip * g->nh + i) * g->nd + j) * g->np;
                for (int k = 0; k < g->np; ++k) {
                    double L[3], V[3];
                    hemisphere_dirs(th, td, hemi_phi_d(k, g->np), L, V);
                    row[k] = L[2] > 0 && V[2] > 0
                                 ? hemisphere_eval_host(&r->reference, r->ref_kind, L, V, r->per_p[ip].rvals)
                                 : NAN;
                }
            }
        }
}

/* A table reference's values (hemisphere.h, ref_table): each grid point's above the horizon in
   double (r->ref_values, kept for the RMS), and as floats in a device buffer, phi_d's rows padded
   to the kernel's lanes; *buf is a one-float buffer for other references (the kernel's rtab). */
static int reference_table(struct hemi_ctx *h, struct hemi_result *r, float **ftab, cl_mem *buf)
{
    int rc = 0;
    cl_int e;
    const struct hemi_grid *g = &r->grid;
    if (!r->ref_table) {
        float zero = 0;
        *buf = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof zero, &zero, &e);
        CL_CHECK_ERR_GOTO(e, "clCreateBuffer(hemisphere reference table)", done);
        return 0;
    }
    int lanes = hemi_lanes(h), np_pad = (g->np + lanes - 1) / lanes * lanes;
    size_t rows = (size_t)r->p_count * g->nh * g->nd, cells = rows * (size_t)g->np;
    r->ref_values = malloc(cells * sizeof *r->ref_values);
    *ftab = malloc(rows * (size_t)np_pad * sizeof **ftab);
    if (!r->ref_values || !*ftab) {
        fprintf(stderr, "brdfbench: out of memory for the values of the reference %s\n", r->reference.label);
        return EXIT_RUNTIME;
    }
    if ((rc = model_run_isolated(&r->reference, fill_values, r, r->ref_values, cells * sizeof *r->ref_values)) != 0)
        return rc;
    for (size_t row = 0; row < rows; ++row)
        for (int k = 0; k < np_pad; ++k)
            (*ftab)[row * np_pad + k] = k < g->np ? (float)r->ref_values[row * g->np + k] : NAN;
    *buf = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, rows * (size_t)np_pad * sizeof(float),
                          *ftab, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(hemisphere reference table)", done);
done:
    return rc;
}

static int launch_pass(struct hemi_ctx *h, cl_kernel k, int pass, cl_mem bp, cl_mem bt, int p_count,
                       const struct hemi_grid *g, cl_mem bo, cl_mem brt, const char *label, double *seconds)
{
    int rc = 0;
    cl_event ev = NULL;
    cl_int ps = pass, pc = p_count, nh = g->nh, nd = g->nd, np = g->np;
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(ps), CL_ARG(bp), CL_ARG(bt), CL_ARG(pc), CL_ARG(nh), CL_ARG(nd), CL_ARG(np),
                     CL_ARG(bo), CL_ARG(brt));
    size_t local = 4, global = ((size_t)p_count * (size_t)g->nh + local - 1) / local * local;
    double t0 = wall_seconds();
    if ((rc = clsession_launch(h->s, k, 1, &global, &local, label, &ev)) != 0)
        goto done;
    int used_wall = 0;
    *seconds += cl_event_seconds_or_wall(ev, wall_seconds() - t0, &used_wall);
done:
    if (ev)
        clReleaseEvent(ev);
    return rc;
}

/* The device's maximum of one figure at one p: over the rows, with its grid point. */
static void row_max(const float *raw, int p, const struct hemi_grid *g, int value_at, struct hemi_extreme *out,
                    int *row_out, int *at_out)
{
    out->value = -1;
    *row_out = *at_out = -1;
    for (int ih = 0; ih < g->nh; ++ih) {
        const float *o = raw + ((size_t)p * g->nh + ih) * HEMI_OUT_STRIDE;
        if (o[value_at] >= 0 && o[value_at] > out->value) {
            out->value = o[value_at];
            *row_out = ih;
            *at_out = (int)o[value_at + 1];
        }
    }
    if (*row_out < 0) {
        out->value = out->th = out->td = out->pd = NAN;
        return;
    }
    out->th = hemi_theta_h(*row_out, g->nh);
    out->td = hemi_theta_d(*at_out / g->np, g->nd);
    out->pd = hemi_phi_d(*at_out % g->np, g->np);
}

/* One figure at one p: the device's maximum, the double at its point, the refined maximum. */
static void one_figure(const struct hemi_result *r, struct hemi_per_p *pp, const float *raw, int p, enum figure fig,
                       int value_at, double threshold, struct hemi_extreme *dev, struct hemi_extreme *dbl,
                       double *chk, double *dbl_at)
{
    int row, at;
    row_max(raw, p, &r->grid, value_at, dev, &row, &at);
    dev->p = pp->p;
    dbl->value = dbl->th = dbl->td = dbl->pd = NAN;
    dbl->p = pp->p;
    *chk = *dbl_at = NAN;
    if (row < 0)
        return;
    struct fig_ctx c = { r, pp, threshold, fig };
    *dbl_at = figure_at(&c, dev->th, dev->td, dev->pd);
    if (!(*dbl_at > -INFINITY))
        *dbl_at = NAN;   /* the double finds no sample of the figure there: a disagreement below */
    *chk = fabs(dev->value - *dbl_at);
    if (r->ref_kind == HEMI_KIND_MEASURED) {
        /* the table is constant over each of its cells: a refined maximum would walk to a cell's
           edge and measure the table's step, not the model; the figure is the grid's maximum,
           recomputed in double at its point (docs/definitions.md) */
        dbl->value = *dbl_at;
        dbl->th = dev->th;
        dbl->td = dev->td;
        dbl->pd = dev->pd;
        return;
    }
    /* the box: one grid cell either side (theta_h's cells widen as u^2 does) */
    double u = (row + 0.5) / r->grid.nh;
    double hth = 2.0 * (pi / 2) * (u + 1.0 / r->grid.nh) / r->grid.nh;
    *dbl = refine(&c, dev->th, dev->td, dev->pd, hth, 2.0 * (pi / 2) / r->grid.nd, 2.0 * pi / r->grid.np);
    dbl->p = pp->p;
}

/* Folds one check into the verdict: the device's figure at its grid point against the double
   one there. Within half a unit of the figure's 4th significant digit it is ok; below float
   resolution of the peak (a double figure under 2^-23 peak: nothing a float device could
   resolve, no maximum to miss) it is ok within a few units of 2^-24 peak or within twice the
   float noise of the model and reference values there (their float-cancellation figures at this
   scale), docs/definitions.md, Device check. Beyond that the device computed something else, or
   its float noise is more than half a unit of the figure: it could have missed the maximum. */
static void fold_check(struct hemi_result *r, double d, double dbl_at, double figure, double scale, double noise,
                       double p, const char *name)
{
    if (isnan(figure) && isnan(d))
        return;
    double unit = fourth_digit_unit(figure);
    int below_resolution = dbl_at < 0x1p-23 * scale;
    int within_noise = (below_resolution && d <= fmax(HEMI_FLOOR_UNITS * 0x1p-24 * scale, 2.0 * noise)) ||
                       d <= ACC_CHECK_FLOAT_FLOOR * scale;
    int exceeded = (isnan(d) || d > 0.5 * unit) && !within_noise;
    double units = isnan(d) ? INFINITY : unit > 0 ? d / unit : 0.0;
    if (!exceeded && units > 0.5)
        ++r->checks_at_float_noise;
    if (!exceeded && below_resolution)
        units = 0;
    if ((exceeded && !r->check.exceeded) || (exceeded == r->check.exceeded && !(units <= r->check.units))) {
        r->check.exceeded = exceeded;
        r->check.units = units;
        r->check.diff = d;
        r->check.p = p;
        r->check.figure = name;
    }
}

/* The RMS of cos(theta_i) (f - f_ref) at one p in double, over the grid's samples (the kernel's
   quadrature: midpoints, the Jacobian 4 cos td sin td sin th, phi_h's 2 pi, phi_d folded onto
   [0, pi) with the weight cos^2 ti + cos^2 to), divided by the measure (2 pi)^2 of the pair of
   hemispheres. An invalid model value adds nothing, as on the device. */
static double rms_double(const struct hemi_result *r, const struct hemi_per_p *pp, int ip)
{
    const struct hemi_grid *g = &r->grid;
    double sum = 0;
    for (int i = 0; i < g->nh; ++i) {
        double th = hemi_theta_h(i, g->nh), u = (i + 0.5) / g->nh;
        double row = 0;
        for (int j = 0; j < g->nd; ++j) {
            double td = hemi_theta_d(j, g->nd), part = 0;
            for (int k = 0; k < g->np; ++k) {
                double L[3], V[3];
                hemisphere_dirs(th, td, hemi_phi_d(k, g->np), L, V);
                if (!(L[2] > 0 && V[2] > 0))
                    continue;
                double f = hemisphere_eval_host(&r->model, r->model_kind, L, V, pp->mvals);
                double fr = r->ref_values
                                ? r->ref_values[(((size_t)ip * g->nh + i) * g->nd + j) * g->np + k]
                                : hemisphere_eval_host(&r->reference, r->ref_kind, L, V, pp->rvals);
                if (!(f >= 0) || !isfinite(f) || !isfinite(fr))
                    continue;
                part += (L[2] * L[2] + V[2] * V[2]) * (f - fr) * (f - fr);
            }
            row += sin(td) * cos(td) * part;
        }
        sum += row * sin(th) * pi * u / g->nh;
    }
    return sqrt(sum * 8.0 * pi * (pi / 2 / g->nd) * (pi / g->np) / (4.0 * pi * pi));
}

/* The double stage of every p: the RMS and the three figures (the double at the device's
   maximum, then refined), into out (p_count hemi_per_p, copies of r->per_p with these filled).
   Run through model_run_isolated_pair, so that a user model's code (the model's, the
   reference's) is called directly in one sandbox for the whole stage: the RMS and the
   refinement ask for values one at a time, hundreds of thousands of them, and a round trip to
   the sandbox per value made the stage wait on the scheduler for each on a busy machine. */
struct double_stage_ctx {
    const struct hemi_result *r;
    const float *raw;
    const float *thr;
};

static void double_stage(void *vctx, void *vout)
{
    const struct double_stage_ctx *c = vctx;
    const struct hemi_result *r = c->r;
    struct hemi_per_p *out = vout;
    for (int i = 0; i < r->p_count; ++i) {
        struct hemi_per_p *pp = &out[i];
        *pp = r->per_p[i];
        pp->rms = rms_double(r, pp, i);
        double t = c->thr[i];
        one_figure(r, pp, c->raw, i, FIG_EPI_REL, HEMI_O_EPI_REL, t, &pp->dev_epi_rel, &pp->epi_rel,
                   &pp->chk_epi_rel, &pp->dbl_epi_rel);
        one_figure(r, pp, c->raw, i, FIG_ATT_ABS, HEMI_O_ATT_ABS, t, &pp->dev_att_abs, &pp->att_abs,
                   &pp->chk_att_abs, &pp->dbl_att_abs);
        one_figure(r, pp, c->raw, i, FIG_WHOLE_ABS, HEMI_O_EPI_ABS, t, &pp->dev_whole_abs, &pp->whole_abs,
                   &pp->chk_whole_abs, &pp->dbl_whole_abs);
    }
}

static void range_max(const struct hemi_result *r, size_t off, struct hemi_extreme *out)
{
    out->value = out->p = out->th = out->td = out->pd = NAN;
    for (int i = 0; i < r->p_count; ++i) {
        const struct hemi_extreme *e = (const struct hemi_extreme *)((const char *)&r->per_p[i] + off);
        if (e->value > out->value || (isnan(out->value) && isfinite(e->value)))
            *out = *e;
    }
}

/* The probe's double values: the model's at each of count samples, then the reference's
   (vout: 2 count doubles), in one sandbox for a user model's code (model_run_isolated_pair). */
struct probe_values_ctx {
    const struct hemi_result *r;
    const float *pts;
    const int *pv;
    int count;
};

static void probe_values(void *vctx, void *vout)
{
    const struct probe_values_ctx *c = vctx;
    double *o = vout;
    for (int i = 0; i < c->count; ++i) {
        const struct hemi_per_p *pp = &c->r->per_p[c->pv[i / 16]];
        double L[3], V[3];
        hemisphere_dirs(c->pts[i], c->pts[c->count + i], c->pts[2 * c->count + i], L, V);
        o[i] = hemisphere_eval_host(&c->r->model, c->r->model_kind, L, V, pp->mvals);
        o[c->count + i] = hemisphere_eval_host(&c->r->reference, c->r->ref_kind, L, V, pp->rvals);
    }
}

/* The model and its reference on the device at random samples against double: their
   float-cancellation figures. Each run of 16 samples shares one parameter value. */
static int probe(struct hemi_ctx *h, cl_kernel k, cl_mem bp, struct hemi_result *r)
{
    int rc = 0, count = HEMI_PROBE_POINTS, groups = HEMI_PROBE_POINTS / 16;
    cl_int e, cnt = count;
    cl_mem bth = NULL, btd = NULL, bpd = NULL, bpv = NULL, bo = NULL;
    float *pts = malloc((size_t)count * 3 * sizeof *pts), *out = malloc((size_t)count * 2 * sizeof *out);
    int *pv = malloc((size_t)groups * sizeof *pv);
    double *dbl = NULL;
    if (!pts || !out || !pv) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    uint64_t state = 0x2545f4914f6cdd1dULL;
    for (int g = 0; g < groups; ++g)
        pv[g] = g % r->p_count;
    for (int i = 0; i < count; ++i) {
        float th, td, pd;
        double L[3], V[3];
        do {   /* above the horizon, as the float angles give it */
            th = (float)(pi / 2 * lcg_unit(&state) * lcg_unit(&state));   /* denser near theta_h = 0 */
            td = (float)(pi / 2 * lcg_unit(&state));
            pd = (float)(pi * lcg_unit(&state));
            hemisphere_dirs(th, td, pd, L, V);
        } while (!(L[2] > 1e-3 && V[2] > 1e-3));
        pts[i] = th;
        pts[count + i] = td;
        pts[2 * count + i] = pd;
    }
    bth = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float), pts, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(probe theta_h)", done);
    btd = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float),
                         pts + count, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(probe theta_d)", done);
    bpd = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)count * sizeof(float),
                         pts + 2 * count, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(probe phi_d)", done);
    bpv = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)groups * sizeof(int), pv, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(probe parameters)", done);
    bo = clCreateBuffer(h->s->ctx, CL_MEM_WRITE_ONLY, (size_t)count * 2 * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(probe out)", done);
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(bp), CL_ARG(bth), CL_ARG(btd), CL_ARG(bpd), CL_ARG(bpv), CL_ARG(cnt),
                     CL_ARG(bo));
    size_t global = (size_t)count / (size_t)hemi_lanes(h);
    if ((rc = clsession_launch(h->s, k, 1, &global, NULL, r->model.label, NULL)) != 0)
        goto done;
    CL_CHECK_GOTO(clEnqueueReadBuffer(h->s->queue, bo, CL_TRUE, 0, (size_t)count * 2 * sizeof(float), out, 0, NULL,
                                      NULL), done);
    r->float_cancellation = r->ref_float_error = 0;
    if (!(dbl = malloc((size_t)count * 2 * sizeof *dbl))) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    const struct probe_values_ctx pc = { r, pts, pv, count };
    if ((rc = model_run_isolated_pair(&r->model, &r->reference, probe_values, (void *)&pc, dbl,
                                      (size_t)count * 2 * sizeof *dbl)) != 0)
        goto done;
    for (int i = 0; i < count; ++i) {
        const struct hemi_per_p *pp = &r->per_p[pv[i / 16]];
        double f = dbl[i], fr = dbl[count + i];
        if (!(pp->peak > 0))
            continue;
        double d = fabs((double)out[i] - f) / pp->peak, dr = fabs((double)out[count + i] - fr) / pp->peak;
        if (isfinite(f) && isfinite(out[i]) && d > r->float_cancellation)
            r->float_cancellation = d;
        if (isfinite(fr) && isfinite(out[count + i]) && dr > r->ref_float_error)
            r->ref_float_error = dr;
    }
done:
    if (bo) clReleaseMemObject(bo);
    if (bpv) clReleaseMemObject(bpv);
    if (bpd) clReleaseMemObject(bpd);
    if (btd) clReleaseMemObject(btd);
    if (bth) clReleaseMemObject(bth);
    free(dbl);
    free(pv);
    free(out);
    free(pts);
    return rc;
}

int hemisphere_run(struct hemi_ctx *h, const struct model_spec *m, const struct model_spec *ref,
                   const struct hemi_axis *axis, const struct hemi_fixed *fixed, int nfixed,
                   const struct hemi_grid *g, struct hemi_result *out)
{
    int rc = 0;
    cl_int e;
    cl_mem bp = NULL, bt = NULL, bo = NULL, brt = NULL;
    float *pv = NULL, *thr = NULL, *raw = NULL, *ftab = NULL;
    struct hemi_per_p *staged = NULL;
    cl_kernel sweep, probe_k;
    memset(out, 0, sizeof *out);
    out->model = *m;
    out->reference = *ref;
    /* --param values are the model's parameters in its label too (as models.c writes labels) */
    int changed = 0;
    for (int i = 0; i < nfixed; ++i) {
        int k = param_index(m, fixed[i].name);
        if (k >= 0) {
            out->model.params[k] = fixed[i].value;
            changed = 1;
        }
    }
    if (changed) {
        size_t used = (size_t)snprintf(out->model.label, sizeof out->model.label, "%s", m->info->id);
        for (int k = 0; k < m->info->nparams && used < sizeof out->model.label; ++k)
            used += (size_t)snprintf(out->model.label + used, sizeof out->model.label - used, "%s%s=%.10g",
                                     k ? "," : ":", m->info->params[k].name, out->model.params[k]);
    }
    out->model_kind = model_kind(m);
    out->ref_kind = model_kind(ref);
    out->ref_table = kind_is_table(out->ref_kind);
    out->axis = *axis;
    out->grid = *g;
    out->p_count = axis->count;
    int P = axis->count;
    size_t rows = (size_t)P * (size_t)g->nh;
    if ((rc = kernels_for(h, out, &sweep, &probe_k)) != 0)
        return rc;
    out->per_p = calloc((size_t)P, sizeof *out->per_p);
    pv = malloc((size_t)P * 6 * sizeof *pv);
    thr = malloc((size_t)P * sizeof *thr);
    raw = malloc(rows * HEMI_OUT_STRIDE * sizeof *raw);
    if (!out->per_p || !pv || !thr || !raw) {
        fprintf(stderr, "brdfbench: out of memory for the hemisphere sweep of %s\n", m->label);
        rc = EXIT_RUNTIME;
        goto done;
    }
    out->peak_ratio = 1.0;
    for (int i = 0; i < P; ++i) {
        struct hemi_per_p *pp = &out->per_p[i];
        pp->p = (double)(float)axis_value(axis, i);   /* the axis value as the device sees it */
        values_at(axis, fixed, nfixed, m, ref, pp->p, pp->mvals, pp->rvals);
        for (int k = 0; k < 3; ++k) {
            pv[6 * i + k] = (float)pp->mvals[k];
            pv[6 * i + 3 + k] = (float)pp->rvals[k];
        }
        double N[3] = { 0, 0, 1 };
        double ratio = hemisphere_eval_host(m, out->model_kind, N, N, pp->mvals) /
                       hemisphere_eval_host(ref, out->ref_kind, N, N, pp->rvals);
        if (!(fabs(ratio - 1) <= fabs(out->peak_ratio - 1)))
            out->peak_ratio = ratio;
    }
    bp = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, (size_t)P * 6 * sizeof(float), pv, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(hemisphere parameters)", done);
    if ((rc = reference_table(h, out, &ftab, &brt)) != 0)
        goto done;
    bt = clCreateBuffer(h->s->ctx, CL_MEM_READ_ONLY, (size_t)P * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(hemisphere thresholds)", done);
    bo = clCreateBuffer(h->s->ctx, CL_MEM_WRITE_ONLY, rows * HEMI_OUT_STRIDE * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(hemisphere out)", done);

    /* pass 0: each p's reference peak over the samples, hence its epicentre threshold. A lobe
       model of the registry as the reference peaks at c = 1, i.e. at L = V = N, which the host
       takes below in double: no pass is needed for it. */
    int lobe_ref = out->ref_kind == HEMI_KIND_LOBE;
    if (!lobe_ref) {
        if ((rc = launch_pass(h, sweep, 0, bp, bt, P, g, bo, brt, m->label, &out->device_seconds)) != 0)
            goto done;
        CL_CHECK_GOTO(clEnqueueReadBuffer(h->s->queue, bo, CL_TRUE, 0, rows * HEMI_OUT_STRIDE * sizeof(float), raw,
                                          0, NULL, NULL), done);
    }
    for (int i = 0; i < P; ++i) {
        double peak = 0;
        for (int ih = 0; ih < g->nh && !lobe_ref; ++ih)
            peak = fmax(peak, raw[((size_t)i * g->nh + ih) * HEMI_OUT_STRIDE + HEMI_O_REF_PEAK]);
        /* the peak of a lobe lies at L = V = N, between the grid's first cells: taken there in double */
        double N[3] = { 0, 0, 1 };
        double at_normal = out->ref_kind == HEMI_KIND_MEASURED   /* a table's cell there, which no sample holds */
                               ? NAN : hemisphere_eval_host(ref, out->ref_kind, N, N, out->per_p[i].rvals);
        if (at_normal > peak)
            peak = at_normal;
        out->per_p[i].peak = peak;
        thr[i] = (float)(exp(-BRDF_ZONE_K) * peak);
    }
    CL_CHECK_GOTO(clEnqueueWriteBuffer(h->s->queue, bt, CL_TRUE, 0, (size_t)P * sizeof(float), thr, 0, NULL, NULL),
                  done);
    /* pass 1: the figures */
    if ((rc = launch_pass(h, sweep, 1, bp, bt, P, g, bo, brt, m->label, &out->device_seconds)) != 0)
        goto done;
    CL_CHECK_GOTO(clEnqueueReadBuffer(h->s->queue, bo, CL_TRUE, 0, rows * HEMI_OUT_STRIDE * sizeof(float), raw, 0,
                                      NULL, NULL), done);
    if ((rc = probe(h, probe_k, bp, out)) != 0)
        goto done;
    if (out->ref_table)   /* the device read the reference's double values rounded to float: half an ulp */
        out->ref_float_error = 0x1p-24;
    if (lobe_ref)   /* the samples' largest reference values, from pass 1, never above the peak by more than float
                       rounding: kept as the scale of the check when they are */
        for (int i = 0; i < P; ++i)
            for (int ih = 0; ih < g->nh; ++ih)
                out->per_p[i].peak =
                    fmax(out->per_p[i].peak, raw[((size_t)i * g->nh + ih) * HEMI_OUT_STRIDE + HEMI_O_REF_PEAK]);

    const double rms_scale = 8.0 * pi * (pi / 2 / g->nd) * (pi / g->np) / (4.0 * pi * pi);
    for (int i = 0; i < P; ++i) {
        struct hemi_per_p *pp = &out->per_p[i];
        double sumsq = 0;
        for (int ih = 0; ih < g->nh; ++ih) {
            const float *o = raw + ((size_t)i * g->nh + ih) * HEMI_OUT_STRIDE;
            sumsq += o[HEMI_O_SUMSQ];
            pp->used += (long long)o[HEMI_O_USED];
            pp->below += (long long)o[HEMI_O_BELOW];
            pp->invalid += (long long)o[HEMI_O_INVALID];
            pp->eval_below += (long long)o[HEMI_O_EVAL_BELOW];
            pp->uncovered += (long long)o[HEMI_O_UNCOVERED];
        }
        pp->rms_device = sqrt(sumsq * rms_scale);
        out->used += pp->used;
        out->below += pp->below;
        out->invalid += pp->invalid;
        out->eval_below += pp->eval_below;
        out->uncovered += pp->uncovered;
    }
    struct double_stage_ctx dc = { out, raw, thr };
    staged = malloc((size_t)P * sizeof *staged);
    if (!staged) {
        fprintf(stderr, "brdfbench: out of memory for the hemisphere sweep of %s\n", m->label);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = model_run_isolated_pair(&out->model, &out->reference, double_stage, &dc, staged,
                                      (size_t)P * sizeof *staged)) != 0)
        goto done;
    memcpy(out->per_p, staged, (size_t)P * sizeof *staged);
    for (int i = 0; i < P; ++i) {
        struct hemi_per_p *pp = &out->per_p[i];
        /* the whole domain's maximum: the larger of the two zones' (each refined over all samples) */
        if (pp->att_abs.value > pp->whole_abs.value || isnan(pp->whole_abs.value)) {
            pp->whole_abs = pp->att_abs;
            pp->dev_whole_abs = pp->dev_att_abs;
            pp->chk_whole_abs = pp->chk_att_abs;
            pp->dbl_whole_abs = pp->dbl_att_abs;
        }
        double noise = (out->float_cancellation + out->ref_float_error) * pp->peak;
        double rel = isfinite(pp->epi_rel.value) ? pp->epi_rel.value : 0.0;
        double noise_rel = (out->float_cancellation + (1.0 + rel) * out->ref_float_error) / exp(-BRDF_ZONE_K);
        fold_check(out, pp->chk_epi_rel, pp->dbl_epi_rel, pp->epi_rel.value, 1.0, noise_rel, pp->p,
                   "hemisphere.epicentre.max_rel");
        fold_check(out, pp->chk_att_abs, pp->dbl_att_abs, pp->att_abs.value, pp->peak, noise, pp->p,
                   "hemisphere.attenuation.max_abs");
        fold_check(out, pp->chk_whole_abs, pp->dbl_whole_abs, pp->whole_abs.value, pp->peak, noise, pp->p,
                   "hemisphere.whole.max_abs");
    }
    out->points = (double)out->used;   /* samples (each: the model and its reference), as the lobe sweep counts them */
    range_max(out, offsetof(struct hemi_per_p, epi_rel), &out->epicentre);
    range_max(out, offsetof(struct hemi_per_p, att_abs), &out->attenuation);
    range_max(out, offsetof(struct hemi_per_p, whole_abs), &out->whole);
    range_max(out, offsetof(struct hemi_per_p, dev_epi_rel), &out->grid_epicentre);
    range_max(out, offsetof(struct hemi_per_p, dev_att_abs), &out->grid_attenuation);
    range_max(out, offsetof(struct hemi_per_p, dev_whole_abs), &out->grid_whole);
    out->rms.value = out->rms.p = NAN;
    out->rms.th = out->rms.td = out->rms.pd = NAN;
    for (int i = 0; i < P; ++i)
        if (!(out->per_p[i].rms <= out->rms.value)) {
            out->rms.value = out->per_p[i].rms;
            out->rms.p = out->per_p[i].p;
        }
    out->ok = isfinite(out->whole.value);
    out->device_disagrees = out->check.exceeded;
    size_t used = 0;
    if (!out->ok)
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used, "no finite error values; ");
    if (out->device_disagrees)
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used,
                                 "device and double disagree on %s at %s = %.6g by %.3g (%.4g units of its 4th "
                                 "significant digit; bound 0.5): the device may have missed the maximum; ",
                                 out->check.figure, axis->name, out->check.p, out->check.diff, out->check.units);
    if (out->invalid > 0 && used < sizeof out->reason)
        used += (size_t)snprintf(out->reason + used, sizeof out->reason - used,
                                 "%lld model values were NaN, Inf or negative; they are excluded from the maxima; ",
                                 out->invalid);
    if (used >= 2 && used < sizeof out->reason)
        out->reason[used - 2] = '\0';
done:
    if (bo)
        clReleaseMemObject(bo);
    if (bt)
        clReleaseMemObject(bt);
    if (bp)
        clReleaseMemObject(bp);
    if (brt)
        clReleaseMemObject(brt);
    free(staged);
    free(ftab);
    free(raw);
    free(thr);
    free(pv);
    return rc;
}
