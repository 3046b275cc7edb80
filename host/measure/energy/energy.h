/* energy.h - device quadrature (kernels/integrate.cl) and the energy and reciprocity checks.
 *
 *  - Directional albedo a(theta_i) = int f(L, V) cos(theta_o) dw_o over the upper hemisphere,
 *    for the registry's normalised and microfacet models, by quadrature on the device:
 *    composite Gauss-Legendre in the lobe's polar angle (panels graded to the lobe's width,
 *    with edges at the kinks: the model's zero, the horizon), exact or trapezoid azimuth.
 *    Microfacet distributions D are taken as the BRDF D / (4 cos theta_i cos theta_o)
 *    (F = G = 1), whose albedo at normal incidence is int D cos(theta_h) dw_h over the
 *    half-vectors that reflect above the horizon; their normalisation int D cos(theta_h) dw_h
 *    over the whole hemisphere (exactly 1) is computed as well.
 *  - Closed forms at normal incidence (each with its derivation in energy.c) check them.
 *  - Reciprocity f(L, V) = f(V, L) for every registry model at random direction triples
 *    (N, L, V), on the device (float) and on the host (double), worst pair reported. */
#ifndef BRDF_ENERGY_H
#define BRDF_ENERGY_H

#include "schemas.h"
#include <stddef.h>

#include "clsession.h"
#include "models.h"
#include "integrate_shared.h"   /* enum albedo_mode, the kernels' records (kernels/) */

#define ENERGY_GL_ORDER 16        /* Gauss-Legendre nodes per panel */
#define ENERGY_MAX_PANELS 28
#define ENERGY_MAX_NODES (ENERGY_GL_ORDER * ENERGY_MAX_PANELS)
#define ENERGY_PHI_COUNT 1024     /* azimuth points of the half-vector modes */
#define ENERGY_MAX_MODELS 24
#define ENERGY_N_COUNT 5          /* albedo tables: n in {2, 4, 10, 100, 1000} */
#define ENERGY_THETA_COUNT 18     /* and theta_i = 0, 5, ..., 85 degrees */

/* The program of kernels/integrate.cl, built once. */
struct integrate_ctx {
    struct cl_session *s;
    cl_program program;
    cl_kernel eq11, albedo, recip;
};
int integrate_open(struct integrate_ctx *c, struct cl_session *s);
void integrate_close(struct integrate_ctx *c);

/* Paper 1's eq. 11 on the device: out[0..EQ11_TERMS-1] (enum eq11_term's order) = the double
 * integrals over n in [n_lo, n_hi] and x in [0, acos(exp(-zone_k/n))] of c^n, n^2 (c-1)^2,
 * 2n (c-1) and 1, each times cos x sin x.
 * Inner integrals on the device (float), the outer Gauss-Legendre sum on the host (double). */
int integrate_eq11_device(struct integrate_ctx *c, double zone_k, double n_lo, double n_hi, double out[EQ11_TERMS]);

/* The albedo mode of a registry model: ALBEDO_PSI / ALBEDO_HALF for a normalised lobe,
 * ALBEDO_MICRO for a microfacet distribution, -1 for a model that is not normalised. */
int albedo_mode_of(const struct model_info *m);
/* Directional albedo of model m (mode as above, or ALBEDO_DCOS) at count configurations
 * (n[i], theta_i[i] in radians), on the device. Returns 0 or an exit code. */
int albedo_device(struct integrate_ctx *c, const struct model_spec *m, int mode, const double *n,
                  const double *theta_i, int count, double *out);
/* The closed form at normal incidence, where one is derived (returns 1 and writes value and a
 * one-line derivation), else 0. */
int albedo_closed_form_normal(const struct model_spec *m, int mode, double n, double *value, const char **derivation);

/* The worst pair of a reciprocity check. diff = |f(L,V) - f(V,L)| / f(c = 1, n) (the lobe's peak). */
struct recip_worst {
    double diff, n;
    double eval_error;        /* largest |device - double host| / peak of single values (device only) */
    double nrm[3], l[3], v[3];
    double f_lv, f_vl;
};
int reciprocity_check(struct integrate_ctx *c, const struct model_spec *m, long pairs, struct recip_worst *device,
                      struct recip_worst *host);

/* Reciprocity of the image pass itself (kernels/shade.cl through host/measure/render/render.h), for every
 * model the image passes shade, Cook-Torrance included: each pair (L, V) is one pixel shaded
 * twice, with eye and point light swapped; S = specular / (E (N.L) ks) must agree. diff is
 * |S(L,V) - S(V,L)| / max(|S(L,V)|, |S(V,L)|, 1e-6 f(c = 1, n)). */
struct recip_pass_summary {
    struct model_spec spec;
    int mode;                                   /* render_shading_mode */
    double device_worst, host_worst;
    double n, nrm[3], l[3], v[3], s_lv, s_vl;   /* the device's worst pixel */
    long lit;                                   /* pairs lit both ways */
};
/* Fills out[0..*count-1] for the image passes' default models. Returns 0 or an exit code. */
int reciprocity_image_pass(struct cl_session *s, long pairs, struct recip_pass_summary *out, int max, int *count);

/* What energy_run found, per model, for the claims table. */
struct energy_model_summary {
    struct model_spec spec;
    int mode;
    double max_albedo, max_at_n, max_at_theta_deg;
    double normal_max_diff, normal_diff_at_n;   /* device vs closed form at normal incidence; NAN: none */
    double dcos_max_diff;                       /* microfacet normalisation vs 1; NAN: not microfacet */
    double refine_change;                       /* largest change when the quadrature is refined */
    int cols;                                   /* ENERGY_THETA_COUNT, or 1 (ALBEDO_DCOS) */
    double albedo[ENERGY_N_COUNT * ENERGY_THETA_COUNT];  /* rows: n, columns: theta_i */
    double normal_n[ENERGY_N_COUNT];            /* normal incidence: n as the device took it */
    double normal_closed[ENERGY_N_COUNT];       /* the closed form there; NAN: none derived */
    const char *normal_derivation[ENERGY_N_COUNT];
};
struct recip_summary {
    struct model_spec spec;
    struct recip_worst device, host;
};
struct energy_summary {
    double table_n[ENERGY_N_COUNT];
    int count;
    struct energy_model_summary models[ENERGY_MAX_MODELS];
    int recip_count;
    struct recip_summary recip[ENERGY_MAX_MODELS];
    long recip_pairs;
    int pass_count;
    struct recip_pass_summary pass[ENERGY_MAX_MODELS];
    double quadrature_tolerance;                /* agreement bound used for the checks */
    int all_closed_forms_agree;
    double seconds;
    char *json;                                 /* energy.json's text (malloc'd; energy_summary_free) */
};

/* The albedo tables and the reciprocity check for the registry's models; writes
 * out_dir/energy.json when out_dir is not NULL. Returns 0 or an exit code. */
int energy_run(struct cl_session *s, const char *out_dir, int quiet, struct energy_summary *summary);
void energy_summary_free(struct energy_summary *summary);

#endif
