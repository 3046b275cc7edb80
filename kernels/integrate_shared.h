/* integrate_shared.h - what kernels/integrate.cl and its host (host/measure/energy/energy.c)
 * agree on, written once and included on both sides: albedo_partial's modes and the positions in the
 * records that eq11_terms and reciprocity_pairs write. Plain constants, no REAL. */
#ifndef BRDF_INTEGRATE_SHARED_H
#define BRDF_INTEGRATE_SHARED_H

/* Modes of albedo_partial. */
enum albedo_mode {
    ALBEDO_PSI = 0,     /* lobe f(cos psi) around R: phong family */
    ALBEDO_HALF = 1,    /* lobe f(cos theta_h) used as the BRDF: blinn family */
    ALBEDO_MICRO = 2,   /* D(theta_h) / (4 cos theta_i cos theta_o): F = G = 1 */
    ALBEDO_DCOS = 3     /* D(theta_h) cos theta_h over the whole half-vector hemisphere */
};

/* Paper 1's eq. 11 term by term (u = cos x over the epicentre, u in [c_e, 1]): eq11_terms writes
   EQ11_TERMS floats per n at these positions; the host's sums over n (integrate_eq11_device's
   out[]) keep the order. */
enum eq11_term {
    EQ11_T_LOBE = 0,    /* int u^(n+1) du: the lobe's side */
    EQ11_T_SQUARE = 1,  /* n^2 int (u-1)^2 u du: the quadratic's (c-1)^2 coefficient */
    EQ11_T_LINEAR = 2,  /* 2n int (u-1) u du: its (c-1) coefficient */
    EQ11_T_CONST = 3,   /* int u du: its constant */
    EQ11_TERMS = 4
};

/* reciprocity_pairs' record per direction triple (N, L, V): f(L, V) and f(V, L). */
enum recip_field {
    RECIP_LV = 0,
    RECIP_VL = 1,
    RECIP_STRIDE = 2
};

#endif
