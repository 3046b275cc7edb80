/*
 * accuracy.cl - the dense-grid accuracy sweep and a point probe.
 *
 * One work-item owns one shininess n and loops over both zones of SPEC.md sixteen samples
 * at a time (float16: PoCL vectorises explicit vectors to 512 bits and evaluates the vector
 * forms of pow/cos/exp, while its scalar forms are not vectorised). Each work-item reduces
 * its own samples, so no barrier is needed.
 *
 * Sample cosines come from native_cos: on PoCL 3.1 it is 4x cheaper than cos over [0, pi/2]
 * (measured 1.9 ulp against 1.4 ulp for cos there). The cosine only places a sample: every
 * figure is taken at the exact float cosine the model saw, which the kernel reports.
 *
 * Per n it writes ACC_OUT_STRIDE floats:
 *   [0] max relative error in the epicentre   [1] the cosine where it occurs
 *   [2] max absolute error in the attenuation [3] the cosine where it occurs
 *   [4] max absolute error in the epicentre   [5] the cosine where it occurs
 *   [6] number of invalid model values (NaN, Inf or negative) [7] the first such cosine
 * The cosines are the exact float inputs the model saw, so the host can recompute every
 * reduced figure in double at the same input.
 */
#define REAL float16
#define RSCALAR float
#include "brdf_models.h"

#define ACC_OUT_STRIDE 8
#define HALF_PI_F 1.57079632679489662f

/* Keeps the larger of (best, value) and the cosine that produced it; NaN never wins. */
#define KEEP_MAX(best, best_c, value, c)                    \
    do {                                                    \
        int16 m_ = isgreater((value), (best));              \
        best = select(best, (value), m_);                   \
        best_c = select(best_c, (c), m_);                   \
    } while (0)

static float16 lanes16(void)
{
    return (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f,
                     8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f);
}

/* Index and value of the largest lane (the first one on ties). */
static int argmax16(float16 v)
{
    float a[16];
    vstore16(v, 0, a);
    int k = 0;
    for (int i = 1; i < 16; ++i)
        if (a[i] > a[k])
            k = i;
    return k;
}

static float lane_of(float16 v, int k)
{
    float a[16];
    vstore16(v, 0, a);
    return a[k];
}

__kernel void accuracy_sweep(const int model, const float p0, const float p1,
                             const int ref_model, const float rp0, const float rp1,
                             __global const float *n_values, const int n_count,
                             const int samples, __global float *out)
{
    const int gid = (int)get_global_id(0);
    if (gid >= n_count)
        return;
    const float n = n_values[gid];
    const float16 nv = (float16)(n);
    const float x_e = acos(exp(-0.511f / n));    /* epicentre end (SPEC.md) */
    const float width = HALF_PI_F - x_e;         /* attenuation zone width */
    const float inv_last = 1.0f / (float)(samples - 1);
    const float inv_count = 1.0f / (float)samples;
    const float16 lane = lanes16();

    float16 epi_rel = (float16)(-1.0f), epi_rel_c = (float16)(0.0f);
    float16 epi_abs = (float16)(-1.0f), epi_abs_c = (float16)(0.0f);
    float16 att_abs = (float16)(-1.0f), att_abs_c = (float16)(0.0f);
    int16 bad = (int16)(0);
    float16 bad_c = (float16)(NAN);

    for (int i = 0; i < samples; i += 16) {
        const float16 j = (float16)((float)i) + lane;

        /* Epicentre: x uniform over [0, x_e], both ends included. */
        float16 c = fmax(native_cos(x_e * (j * inv_last)), 0.0f);
        float16 f = brdf_eval(model, c, nv, p0, p1);
        float16 r = brdf_eval(ref_model, c, nv, rp0, rp1);
        /* An invalid model value (NaN, Inf, negative) is counted, not folded into a maximum:
           its error becomes NaN, which never wins. */
        int16 invalid = isless(f, 0.0f) | !isfinite(f);
        bad_c = select(bad_c, c, invalid & isnan(bad_c));
        bad -= invalid;                           /* a true comparison is -1 per lane */
        float16 d = select(fabs(f - r), (float16)(NAN), invalid);
        KEEP_MAX(epi_rel, epi_rel_c, d / r, c);
        KEEP_MAX(epi_abs, epi_abs_c, d, c);

        /* Attenuation: x = x_e + width t^2, t in (0, 1]; t^2 crowds samples near x_e,
           where the lobe falls off, while still reaching pi/2. */
        float16 t = (j + 1.0f) * inv_count;
        c = fmax(native_cos(x_e + width * (t * t)), 0.0f);
        f = brdf_eval(model, c, nv, p0, p1);
        r = brdf_eval(ref_model, c, nv, rp0, rp1);
        invalid = isless(f, 0.0f) | !isfinite(f);
        bad_c = select(bad_c, c, invalid & isnan(bad_c));
        bad -= invalid;
        d = select(fabs(f - r), (float16)(NAN), invalid);
        KEEP_MAX(att_abs, att_abs_c, d, c);
    }

    __global float *o = out + (size_t)gid * ACC_OUT_STRIDE;
    int k = argmax16(epi_rel);
    o[0] = lane_of(epi_rel, k);
    o[1] = lane_of(epi_rel_c, k);
    k = argmax16(att_abs);
    o[2] = lane_of(att_abs, k);
    o[3] = lane_of(att_abs_c, k);
    k = argmax16(epi_abs);
    o[4] = lane_of(epi_abs, k);
    o[5] = lane_of(epi_abs_c, k);
    int bad_total = 0;
    float first_bad = NAN;
    int ba[16];
    float bc[16];
    vstore16(bad, 0, ba);
    vstore16(bad_c, 0, bc);
    for (int q = 0; q < 16; ++q) {
        bad_total += ba[q];
        if (isnan(first_bad) && !isnan(bc[q]))
            first_bad = bc[q];
    }
    o[6] = (float)bad_total;
    o[7] = first_bad;
}

/* Evaluates a model at given points, 16 per work-item, through the same float16 code path
 * as the sweep. count is a multiple of 16. */
__kernel void models_probe(const int model, const float p0, const float p1,
                           __global const float *c, __global const float *n, __global float *out)
{
    const size_t i = get_global_id(0);
    vstore16(brdf_eval(model, vload16(i, c), vload16(i, n), p0, p1), i, out);
}
