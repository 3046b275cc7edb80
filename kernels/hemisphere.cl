/*
 * hemisphere.cl - the hemisphere sweep of a full BRDF f(L, V; p) against its reference
 * (docs/definitions.md, "Full BRDFs over the hemisphere"; host/engine/hemisphere.c runs it).
 *
 * One work-item owns one parameter value p and one theta_h row of the grid of
 * kernels/hemisphere_geom.h and loops over theta_d and phi_d. A grid point where N.L <= 0 or
 * N.V <= 0 is not a sample: it is counted (HEMI_O_BELOW) and neither model is evaluated there.
 *
 * Two passes over the same samples (the `pass` argument):
 *   0: the row's largest reference value (HEMI_O_REF_PEAK); the host takes the largest over a
 *      parameter value's rows, and the epicentre at p is where f_ref >= e^-0.511 of it;
 *   1: every figure of the row, given each parameter value's epicentre threshold.
 * The sample indices written are exact in a float (below 2^24), so the host recomputes each
 * figure in double at the very grid point the device picked.
 *
 * The model and its reference are built in as constants (-D options, hemisphere.c):
 * HEMI_M_KIND / HEMI_M_ID / HEMI_M_PSI and HEMI_R_KIND / HEMI_R_ID / HEMI_R_PSI, kinds of
 * hemisphere_geom.h; so the compiler emits those two models' code alone.
 * pvals holds 6 floats per parameter value: the model's n, p0, p1, then the reference's.
 */
#define REAL float
#define RSCALAR float
/* The lobes' c^n from s = 1 - c (brdf_pow_lobe_s), as the lobe sweep takes it: a sharp lobe's
   float cosine has no digits left near c = 1, its s keeps them (s = 2 sin^2(theta_h/2) here). */
#define BRDF_POW_LOBE_CS(c, s, n) brdf_pow_lobe_s((s), (n))
#include "brdf_models.h"
#include "hemisphere_geom.h"

#ifndef HEMI_M_KIND
#error "hemisphere.cl is built with -DHEMI_M_KIND, -DHEMI_M_ID, -DHEMI_M_PSI and the HEMI_R_ ones"
#endif

/* A lobe model of the registry at c, s = 1 - c (id a constant: the switch folds away). */
static float hemi_lobe(const int id, float c, float s, float n, float p0, float p1)
{
    switch (id) {
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) case BRDF_##E: return EVAL;
#include "brdf_model_list.h"
#undef BRDF_MODEL
    default: return NAN;
    }
}

/* One model's value at a sample: L, V about N = z, with N.L, N.V, L.V, cos theta_h and
   s_h = 1 - cos theta_h (kept to full precision for sharp lobes), cos theta_d = V.H. */
static float hemi_eval(const int kind, const int id, const int psi, const float *L, const float *V, float nl, float nv,
                       float lv, float ch, float sh, float cd, float n, float p0, float p1)
{
    if (kind == HEMI_KIND_LOBE) {
        if (psi) {   /* c = R.V, R = 2 (N.L) N - L */
            float c = fmax(2.0f * nl * nv - lv, 0.0f);
            return hemi_lobe(id, c, 1.0f - c, n, p0, p1);
        }
        return hemi_lobe(id, ch, sh, n, p0, p1);
    }
    if (kind == HEMI_KIND_PHYSICAL)
        return brdf_pb_eval_h(id, nl, nv, lv, ch, cd, n, p0, p1, 1.0f);
#ifdef BRDF_HAVE_USER_FULL
    if (kind == HEMI_KIND_USER_FULL)
        return brdf_user_full(L[0], L[1], L[2], V[0], V[1], V[2], 0.0f, 0.0f, 1.0f, n, p0, p1);
#endif
    return NAN;
}

__kernel void hemisphere_sweep(const int pass, __global const float *pvals, __global const float *threshold,
                               const int p_count, const int nh, const int nd, const int np, __global float *out)
{
    const int gid = (int)get_global_id(0);
    if (gid >= p_count * nh)
        return;
    const int ip = gid / nh, ih = gid % nh;
    const float mn = pvals[6 * ip], mp0 = pvals[6 * ip + 1], mp1 = pvals[6 * ip + 2];
    const float rn = pvals[6 * ip + 3], rp0 = pvals[6 * ip + 4], rp1 = pvals[6 * ip + 5];
    const float th = hemi_theta_h(ih, nh);
    const float sth = sin(th), cth = cos(th);
    const float sh = 2.0f * sin(0.5f * th) * sin(0.5f * th);   /* 1 - cos theta_h without cancellation */
    const float t_epi = pass ? threshold[ip] : 0.0f;

    float epi_rel = -1.0f, epi_abs = -1.0f, att_abs = -1.0f, ref_peak = 0.0f;
    int epi_rel_at = -1, epi_abs_at = -1, att_abs_at = -1;
    int used = 0, below = 0, invalid = 0, eval_below = 0;
    float sumsq = 0.0f;
    for (int j = 0; j < nd; ++j) {
        const float td = hemi_theta_d(j, nd);
        const float sd = sin(td), cd = cos(td);
        const float lv = 2.0f * cd * cd - 1.0f;   /* L.V = cos 2 theta_d */
        float row_sumsq = 0.0f;
        for (int k = 0; k < np; ++k) {
            const float pd = hemi_phi_d(k, np);
            float L[3], V[3];
            hemi_dirs(sth, cth, sd, cd, sin(pd), cos(pd), L, V);
            const float nl = L[2], nv = V[2];
            if (!(nl > 0.0f && nv > 0.0f)) {
                ++below;
                continue;
            }
            eval_below += !(L[2] > 0.0f && V[2] > 0.0f);
            ++used;
            const float r = hemi_eval(HEMI_R_KIND, HEMI_R_ID, HEMI_R_PSI, L, V, nl, nv, lv, cth, sh, cd, rn, rp0, rp1);
            ref_peak = fmax(ref_peak, r);
            if (!pass)
                continue;
            const float f = hemi_eval(HEMI_M_KIND, HEMI_M_ID, HEMI_M_PSI, L, V, nl, nv, lv, cth, sh, cd, mn, mp0, mp1);
            if (!(f >= 0.0f) || !isfinite(f)) {   /* counted, never a maximum */
                ++invalid;
                continue;
            }
            const float d = fabs(f - r);
            const int at = j * np + k;
            if (r >= t_epi) {
                const float rel = d / r;
                if (rel > epi_rel) { epi_rel = rel; epi_rel_at = at; }
                if (d > epi_abs) { epi_abs = d; epi_abs_at = at; }
            } else if (d > att_abs) {
                att_abs = d;
                att_abs_at = at;
            }
            /* the pair at phi_d + pi is this one with L and V swapped: its weight cos^2 theta_o */
            row_sumsq += (nl * nl + nv * nv) * d * d;
        }
        sumsq += sd * cd * row_sumsq;
    }
    const float u = ((float)ih + 0.5f) / (float)nh;
    const float dth = (float)(2.0 * HEMI_HALF_PI) * u / (float)nh;   /* d theta_h = pi u du */
    __global float *o = out + (size_t)gid * HEMI_OUT_STRIDE;
    o[HEMI_O_EPI_REL] = epi_rel;
    o[HEMI_O_EPI_REL_AT] = (float)epi_rel_at;
    o[HEMI_O_ATT_ABS] = att_abs;
    o[HEMI_O_ATT_ABS_AT] = (float)att_abs_at;
    o[HEMI_O_EPI_ABS] = epi_abs;
    o[HEMI_O_EPI_ABS_AT] = (float)epi_abs_at;
    o[HEMI_O_SUMSQ] = sumsq * sth * dth;
    o[HEMI_O_USED] = (float)used;
    o[HEMI_O_BELOW] = (float)below;
    o[HEMI_O_INVALID] = (float)invalid;
    o[HEMI_O_EVAL_BELOW] = (float)eval_below;
    o[HEMI_O_REF_PEAK] = ref_peak;
}

/* The model's and the reference's values at given samples (out: 2 floats per sample), which
   host/engine/hemisphere.c compares with double: the float-cancellation figures. pts holds 4 floats per sample: theta_h, theta_d, phi_d and the
   parameter value's index into pvals. */
__kernel void hemisphere_probe(__global const float *pvals, __global const float *pts, const int count,
                               __global float *out)
{
    const int i = (int)get_global_id(0);
    if (i >= count)
        return;
    const float th = pts[4 * i], td = pts[4 * i + 1], pd = pts[4 * i + 2];
    const int ip = (int)pts[4 * i + 3];
    const float sd = sin(td), cd = cos(td), sth = sin(th), cth = cos(th);
    float L[3], V[3];
    hemi_dirs(sth, cth, sd, cd, sin(pd), cos(pd), L, V);
    const float sh = 2.0f * sin(0.5f * th) * sin(0.5f * th);
    const float lv = 2.0f * cd * cd - 1.0f;
    out[2 * i] = hemi_eval(HEMI_M_KIND, HEMI_M_ID, HEMI_M_PSI, L, V, L[2], V[2], lv, cth, sh, cd, pvals[6 * ip],
                           pvals[6 * ip + 1], pvals[6 * ip + 2]);
    out[2 * i + 1] = hemi_eval(HEMI_R_KIND, HEMI_R_ID, HEMI_R_PSI, L, V, L[2], V[2], lv, cth, sh, cd, pvals[6 * ip + 3],
                               pvals[6 * ip + 4], pvals[6 * ip + 5]);
}
