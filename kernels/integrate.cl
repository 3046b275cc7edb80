/*
 * integrate.cl - quadrature on the device, and the reciprocity probe.
 *
 *   eq11_terms        the inner integrals of paper 1's eq. 11 at one shininess n per work-item
 *                     (the host adds the outer Gauss-Legendre sum over n in double)
 *   albedo_partial    one polar node of the directional albedo  int f(L, V) cos(theta_o) dw_o
 *                     per work-item (the host adds the polar sum in double)
 *   reciprocity_pairs f(L, V) and f(V, L) at given direction triples (N, L, V)
 *
 * Scalar float throughout: these are small integrals, not throughput kernels. Every model
 * value comes from brdf_eval (kernels/brdf_models.h).
 */
#define REAL float
#define RSCALAR float
#include "brdf_models.h"
#include "integrate_shared.h"   /* the albedo modes and the records' positions */

#define INT_PI_F 3.14159265358979324f

/*
 * Eq. 11 after u = cos x (cos x sin x dx = -u du): every term is an integral over
 * u in [c_e, 1], c_e = exp(-K/n). With h = 1 - c_e = -expm1(-K/n) and u = 1 - h t, t in [0, 1],
 * (u - 1) = -h t is exact and u^(n+1) = exp((n+1) log1p(-h t)), so the rounding of u near 1
 * (float spacing 6e-8, amplified n times by a power) never enters.
 * out[EQ11_TERMS i + t], t of enum eq11_term (integrate_shared.h) = int u^(n+1) du,
 * n^2 int (u-1)^2 u du, 2n int (u-1) u du, int u du.
 */
__kernel void eq11_terms(const float zone_k, __global const float *n_values, const int n_count,
                         __global const float *t_nodes, __global const float *t_weights, const int t_count,
                         __global float *out)
{
    const int i = (int)get_global_id(0);
    if (i >= n_count)
        return;
    const float n = n_values[i];
    const float h = -expm1(-zone_k / n);
    float lhs = 0.0f, a = 0.0f, b = 0.0f, c = 0.0f;
    for (int q = 0; q < t_count; ++q) {
        const float ht = h * t_nodes[q], w = t_weights[q];
        const float u = 1.0f - ht;
        lhs += w * exp((n + 1.0f) * log1p(-ht));
        a += w * ht * ht * u;
        b -= w * ht * u;
        c += w * u;
    }
    __global float *o = out + (size_t)i * EQ11_TERMS;
    o[EQ11_T_LOBE] = h * lhs;
    o[EQ11_T_SQUARE] = n * n * h * a;
    o[EQ11_T_LINEAR] = 2.0f * n * h * b;
    o[EQ11_T_CONST] = h * c;
}

/* int_0^{2 pi} max(a + b cos(phi), 0) dphi for b >= 0, in closed form. */
static float clipped_cos_integral(float a, float b)
{
    if (a >= b)
        return 2.0f * INT_PI_F * a;
    if (a <= -b)
        return 0.0f;
    const float phi0 = acos(-a / b);
    return 2.0f * (a * phi0 + b * sin(phi0));
}

/*
 * One polar node of the directional albedo for one configuration (n, theta_i), N = z and
 * L = (sin theta_i, 0, cos theta_i). Writes weight * sin(polar) * (azimuthal integral).
 *   ALBEDO_PSI:   polar = psi around R; cos theta_o = cos psi cos theta_i + sin psi sin theta_i cos phi,
 *                 clipped at the horizon; the azimuthal integral is exact.
 *   ALBEDO_HALF, ALBEDO_MICRO: polar = theta_h around N; V = 2 (L.H) H - L, dw_o = 4 (L.H) dw_h;
 *                 the azimuth by the trapezoid rule (periodic) over phi_count points.
 *   ALBEDO_DCOS:  D cos theta_h, no clipping: the microfacet normalisation (1 exactly).
 */
__kernel void albedo_partial(const int model, const float p0, const float p1, const int mode,
                             __global const float *n_cfg, __global const float *theta_i_cfg,
                             __global const float *nodes, __global const float *weights,
                             const int node_count, const int phi_count, __global float *out)
{
    const int p = (int)get_global_id(0);
    const int cfg = (int)get_global_id(1);
    if (p >= node_count)
        return;
    const size_t at = (size_t)cfg * (size_t)node_count + (size_t)p;
    const float w = weights[at];
    if (w == 0.0f) {
        out[at] = 0.0f;   /* padding */
        return;
    }
    const float n = n_cfg[cfg], ti = theta_i_cfg[cfg];
    const float polar = nodes[at];
    const float cp = cos(polar), sp = sin(polar);
    const float cti = cos(ti), sti = sin(ti);
    float azimuthal = 0.0f;
    if (mode == ALBEDO_PSI) {
        azimuthal = brdf_eval(model, cp, n, p0, p1) * clipped_cos_integral(cp * cti, sp * sti);
    } else if (mode == ALBEDO_DCOS) {
        azimuthal = 2.0f * INT_PI_F * brdf_eval(model, cp, n, p0, p1) * cp;
    } else {
        const float f = brdf_eval(model, cp, n, p0, p1);
        const float dphi = 2.0f * INT_PI_F / (float)phi_count;
        float sum = 0.0f;
        for (int j = 0; j < phi_count; ++j) {
            const float phi = dphi * ((float)j + 0.5f);
            const float ldoth = sti * sp * cos(phi) + cti * cp;
            const float ndotv = 2.0f * ldoth * cp - cti;
            if (ldoth <= 0.0f || ndotv <= 0.0f)
                continue;   /* V below the horizon, or H facing away from L */
            sum += (mode == ALBEDO_HALF) ? f * ndotv * 4.0f * ldoth : f * ldoth / cti;
        }
        azimuthal = sum * dphi;
    }
    out[at] = w * sp * azimuthal;
}

/* The cosine a lobe model reads: cos psi = R.V with R = 2 (N.L) N - L (lobe 0), or
   cos theta_h = N.H with H = normalize(L + V) (lobe 1), as an image pass computes it. */
static float lobe_cosine(int lobe, float3 nrm, float3 l, float3 v)
{
    if (lobe == 0) {
        const float3 r = 2.0f * dot(nrm, l) * nrm - l;
        return dot(r, v);
    }
    return dot(nrm, normalize(l + v));
}

__kernel void reciprocity_pairs(const int model, const float p0, const float p1, const int lobe,
                                __global const float *dirs, __global const float *n_values, const int count,
                                __global float *out)
{
    const int i = (int)get_global_id(0);
    if (i >= count)
        return;
    const float3 nrm = vload3(3 * i + 0, dirs), l = vload3(3 * i + 1, dirs), v = vload3(3 * i + 2, dirs);
    const float n = n_values[i];
    __global float *o = out + (size_t)i * RECIP_STRIDE;
    o[RECIP_LV] = brdf_eval(model, lobe_cosine(lobe, nrm, l, v), n, p0, p1);
    o[RECIP_VL] = brdf_eval(model, lobe_cosine(lobe, nrm, v, l), n, p0, p1);
}
