/*
 * hemisphere.cl - the hemisphere sweep of a full BRDF f(L, V; p) against its reference
 * (docs/definitions.md, "Full BRDFs over the hemisphere"; host/measure/accuracy/hemisphere.c runs it).
 *
 * One work-item owns one parameter value p and one theta_h row of the grid of
 * kernels/hemisphere_geom.h and loops over theta_d and, HEMI_W lanes at a time, phi_d. A grid
 * point where N.L <= 0 or N.V <= 0 is not a sample: it is counted (HEMI_O_BELOW), and its lane's
 * values (computed alongside, as a vector unit does) are never used.
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
 * With HEMI_R_KIND == HEMI_KIND_TABLE the reference's values are read from rtab instead: one
 * float per (parameter value, theta_h row, theta_d, phi_d), each row of phi_d padded to a
 * multiple of HEMI_W; a value that is not finite marks a point the reference does not cover
 * (counted in HEMI_O_UNCOVERED, not a sample). Other kinds ignore rtab.
 */
/* HEMI_W lanes per step: 16 (float16, for PoCL, which vectorises explicit vectors to 512 bits
   and calls the vector forms of sin, cos, exp, pow) or 1 (scalar float, for a driver that
   vectorises across work-items itself, as Mesa's llvmpipe does; hemisphere.c picks it as the
   lobe sweep picks ACC_W). The samples are the same either way. */
#ifndef HEMI_W
#define HEMI_W 16
#endif
#if HEMI_W == 16
#define REAL float16
#define HEMI_IVEC int16
#define HEMI_COUNT(m) (-(m))         /* a true vector comparison is -1 per lane */
#define HEMI_LANES ((float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f, \
                              12.0f, 13.0f, 14.0f, 15.0f))
#elif HEMI_W == 1
#define REAL float
#define HEMI_IVEC int
#define HEMI_COUNT(m) ((m) != 0)
#define HEMI_LANES 0.0f
#else
#error "HEMI_W must be 16 or 1"
#endif
#if HEMI_W == 16
#define HEMI_TAB_LOAD(p) vload16(0, (p))
#else
#define HEMI_TAB_LOAD(p) (*(p))
#endif
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
static REAL hemi_lobe(const int id, REAL c, REAL s, REAL n, float p0, float p1)
{
    switch (id) {
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) case BRDF_##E: return EVAL;
#include "brdf_model_list.h"
#undef BRDF_MODEL
    default: return (REAL)(NAN);
    }
}

/* One model's value at a sample: L, V about N = z, with N.L, N.V, L.V, cos theta_h and
   s_h = 1 - cos theta_h (kept to full precision for sharp lobes), cos theta_d = V.H. */
static REAL hemi_eval(const int kind, const int id, const int psi, const REAL *L, const REAL *V, REAL nl, REAL nv,
                      REAL lv, REAL ch, REAL sh, REAL cd, REAL n, float p0, float p1)
{
    if (kind == HEMI_KIND_LOBE) {
        if (psi) {   /* c = R.V, R = 2 (N.L) N - L */
            REAL c = fmax(2.0f * nl * nv - lv, 0.0f);
            return hemi_lobe(id, c, 1.0f - c, n, p0, p1);
        }
        return hemi_lobe(id, ch, sh, n, p0, p1);
    }
    if (kind == HEMI_KIND_PHYSICAL)
        return brdf_pb_eval_h(id, nl, nv, lv, ch, cd, n, p0, p1, 1.0f);
#ifdef BRDF_HAVE_USER_FULL
    if (kind == HEMI_KIND_USER_FULL)
        return brdf_user_full(L[0], L[1], L[2], V[0], V[1], V[2], (REAL)(0.0f), (REAL)(0.0f), (REAL)(1.0f), n, p0, p1);
#endif
    return (REAL)(NAN);
}

/* Keeps the larger of (best, value) and its sample index; NaN never wins. */
#define KEEP_MAX(best, best_at, value, at)                  \
    do {                                                    \
        HEMI_IVEC m_ = isgreater((value), (best));          \
        best = select(best, (value), m_);                   \
        best_at = select(best_at, (at), m_);                \
    } while (0)

#if HEMI_W == 16
static float lane_max(float16 v, float16 at, float *at_out)
{
    float a[16], b[16];
    vstore16(v, 0, a);
    vstore16(at, 0, b);
    int k = 0;
    for (int i = 1; i < 16; ++i)
        if (a[i] > a[k] || (a[i] == a[k] && b[i] < b[k]))   /* ties: the first sample */
            k = i;
    *at_out = b[k];
    return a[k];
}
static float lane_sum(float16 v) { float a[16]; vstore16(v, 0, a); float s = 0; for (int i = 0; i < 16; ++i) s += a[i]; return s; }
static int lane_isum(int16 v) { int a[16]; vstore16(v, 0, a); int s = 0; for (int i = 0; i < 16; ++i) s += a[i]; return s; }
#else
static float lane_max(float v, float at, float *at_out) { *at_out = at; return v; }
static float lane_sum(float v) { return v; }
static int lane_isum(int v) { return v; }
#endif

__kernel void hemisphere_sweep(const int pass, __global const float *pvals, __global const float *threshold,
                               const int p_count, const int nh, const int nd, const int np, __global float *out,
                               __global const float *rtab)
{
    const int gid = (int)get_global_id(0);
    if (gid >= p_count * nh)
        return;
    const int ip = gid / nh, ih = gid % nh;
    const REAL mn = (REAL)(pvals[6 * ip]), rn = (REAL)(pvals[6 * ip + 3]);
    const float mp0 = pvals[6 * ip + 1], mp1 = pvals[6 * ip + 2];
    const float rp0 = pvals[6 * ip + 4], rp1 = pvals[6 * ip + 5];
    const float th = hemi_theta_h(ih, nh);
    const REAL sth = (REAL)(sin(th)), cth = (REAL)(cos(th));
    const REAL sh = (REAL)(2.0f * sin(0.5f * th) * sin(0.5f * th));   /* 1 - cos theta_h without cancellation */
    const float t_epi = pass ? threshold[ip] : 0.0f;
    const REAL lane = HEMI_LANES;
    const float pd_step = (float)(2.0 * HEMI_HALF_PI) / (float)np;

    REAL epi_rel = (REAL)(-1.0f), epi_abs = (REAL)(-1.0f), att_abs = (REAL)(-1.0f), ref_peak = (REAL)(0.0f);
    REAL epi_rel_at = (REAL)(-1.0f), epi_abs_at = (REAL)(-1.0f), att_abs_at = (REAL)(-1.0f);
    HEMI_IVEC used = (HEMI_IVEC)(0), below = (HEMI_IVEC)(0), invalid = (HEMI_IVEC)(0), eval_below = (HEMI_IVEC)(0);
    HEMI_IVEC uncovered = (HEMI_IVEC)(0);
    const int np_pad = (np + HEMI_W - 1) / HEMI_W * HEMI_W;   /* rtab's row length */
    float sumsq = 0.0f;
    for (int j = 0; j < nd; ++j) {
        const float td = hemi_theta_d(j, nd);
        const REAL sd = (REAL)(sin(td)), cd = (REAL)(cos(td));
        const REAL lv = (REAL)(2.0f * cos(td) * cos(td) - 1.0f);   /* L.V = cos 2 theta_d */
        REAL row_sumsq = (REAL)(0.0f);
        for (int k = 0; k < np; k += HEMI_W) {
            const REAL kk = (float)k + lane;
            const REAL pd = (kk + 0.5f) * pd_step;   /* hemi_phi_d of kernels/hemisphere_geom.h, per lane */
            REAL L[3], V[3];
            hemi_dirs(sth, cth, sd, cd, sin(pd), cos(pd), L, V);
            const REAL nl = L[2], nv = V[2];
            const HEMI_IVEC in_grid = isless(kk, (float)np);
            const HEMI_IVEC over = isgreater(nl, 0.0f) & isgreater(nv, 0.0f) & in_grid;
            below += HEMI_COUNT(in_grid & !over);
#if HEMI_R_KIND == HEMI_KIND_TABLE
            const REAL r = HEMI_TAB_LOAD(rtab + ((size_t)(ip * nh + ih) * (size_t)nd + (size_t)j) * (size_t)np_pad + k);
            const HEMI_IVEC above = over & isfinite(r);
            uncovered += HEMI_COUNT(over & !isfinite(r));
#else
            const HEMI_IVEC above = over;
            const REAL r = hemi_eval(HEMI_R_KIND, HEMI_R_ID, HEMI_R_PSI, L, V, nl, nv, lv, cth, sh, cd, rn, rp0, rp1);
#endif
            used += HEMI_COUNT(above);
            eval_below += HEMI_COUNT(above & !(isgreater(L[2], 0.0f) & isgreater(V[2], 0.0f)));
            ref_peak = select(ref_peak, fmax(ref_peak, r), above);
            if (!pass)
                continue;
            const REAL f = hemi_eval(HEMI_M_KIND, HEMI_M_ID, HEMI_M_PSI, L, V, nl, nv, lv, cth, sh, cd, mn, mp0, mp1);
            /* an invalid model value (NaN, Inf, negative) is counted, never a maximum */
            const HEMI_IVEC bad = above & (isless(f, 0.0f) | !isfinite(f));
            invalid += HEMI_COUNT(bad);
            const HEMI_IVEC ok = above & !bad;
            const REAL d = select((REAL)(NAN), fabs(f - r), ok);
            const REAL at = (float)(j * np) + kk;
            const HEMI_IVEC epi = isgreaterequal(r, t_epi);
            KEEP_MAX(epi_rel, epi_rel_at, select((REAL)(NAN), d / r, epi), at);
            KEEP_MAX(epi_abs, epi_abs_at, select((REAL)(NAN), d, epi), at);
            KEEP_MAX(att_abs, att_abs_at, select(d, (REAL)(NAN), epi), at);
            /* the pair at phi_d + pi is this one with L and V swapped: its weight cos^2 theta_o */
            row_sumsq += select((REAL)(0.0f), (nl * nl + nv * nv) * d * d, ok);
        }
        sumsq += sin(td) * cos(td) * lane_sum(row_sumsq);
    }
    const float u = ((float)ih + 0.5f) / (float)nh;
    const float dth = (float)(2.0 * HEMI_HALF_PI) * u / (float)nh;   /* d theta_h = pi u du */
    __global float *o = out + (size_t)gid * HEMI_OUT_STRIDE;
    float at;
    o[HEMI_O_EPI_REL] = lane_max(epi_rel, epi_rel_at, &at);
    o[HEMI_O_EPI_REL_AT] = at;
    o[HEMI_O_ATT_ABS] = lane_max(att_abs, att_abs_at, &at);
    o[HEMI_O_ATT_ABS_AT] = at;
    o[HEMI_O_EPI_ABS] = lane_max(epi_abs, epi_abs_at, &at);
    o[HEMI_O_EPI_ABS_AT] = at;
    o[HEMI_O_SUMSQ] = sumsq * sin(th) * dth;
    o[HEMI_O_USED] = (float)lane_isum(used);
    o[HEMI_O_BELOW] = (float)lane_isum(below);
    o[HEMI_O_INVALID] = (float)lane_isum(invalid);
    o[HEMI_O_EVAL_BELOW] = (float)lane_isum(eval_below);
    float unused;
    o[HEMI_O_REF_PEAK] = lane_max(ref_peak, (REAL)(0.0f), &unused);
    o[HEMI_O_UNCOVERED] = (float)lane_isum(uncovered);
}

/* The model's and the reference's values at given samples, HEMI_W per work-item (out: the
   model's count values, then the reference's), which host/measure/accuracy/hemisphere.c compares with
   double: the float-cancellation figures. th, td, pd: count angles each; every run of 16
   consecutive samples shares one parameter value, pv[i / 16]. */
#if HEMI_W == 16
#define HEMI_LOAD(a, i) vload16((i), (a))
#define HEMI_STORE(v, i, a) vstore16((v), (i), (a))
#else
#define HEMI_LOAD(a, i) ((a)[i])
#define HEMI_STORE(v, i, a) ((a)[i] = (v))
#endif
__kernel void hemisphere_probe(__global const float *pvals, __global const float *th_v, __global const float *td_v,
                               __global const float *pd_v, __global const int *pv, const int count,
                               __global float *out)
{
    const int i = (int)get_global_id(0);
    if (i * HEMI_W >= count)
        return;
    const int ip = pv[i * HEMI_W / 16];
    const REAL th = HEMI_LOAD(th_v, i), td = HEMI_LOAD(td_v, i), pd = HEMI_LOAD(pd_v, i);
    const REAL sd = sin(td), cd = cos(td), sth = sin(th), cth = cos(th);
    REAL L[3], V[3];
    hemi_dirs(sth, cth, sd, cd, sin(pd), cos(pd), L, V);
    const REAL sh = 2.0f * sin(0.5f * th) * sin(0.5f * th);
    const REAL lv = 2.0f * cd * cd - 1.0f;
    const REAL f = hemi_eval(HEMI_M_KIND, HEMI_M_ID, HEMI_M_PSI, L, V, L[2], V[2], lv, cth, sh, cd,
                             (REAL)(pvals[6 * ip]), pvals[6 * ip + 1], pvals[6 * ip + 2]);
    const REAL r = hemi_eval(HEMI_R_KIND, HEMI_R_ID, HEMI_R_PSI, L, V, L[2], V[2], lv, cth, sh, cd,
                             (REAL)(pvals[6 * ip + 3]), pvals[6 * ip + 4], pvals[6 * ip + 5]);
    HEMI_STORE(f, i, out);
    HEMI_STORE(r, i, out + count);
}
