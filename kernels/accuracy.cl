/*
 * accuracy.cl - the dense-grid accuracy sweep and a point probe.
 *
 * One work-item owns one shininess n and loops over both zones of docs/definitions.md sixteen samples
 * at a time (float16: PoCL vectorises explicit vectors to 512 bits and evaluates the vector
 * forms of exp/log, while its scalar forms are not vectorised). Each work-item reduces its
 * own samples, so no barrier is needed.
 *
 * Samples are placed and evaluated in s = 1 - c = 1 - cos x, never in c: a float cosine has
 * only 6e-8 of room below 1, so at n = 1e6 the whole epicentre (s <= 5.1e-7) is eight float
 * cosines, while a float s keeps 24 bits there. The models take s through brdf_eval_s (their
 * formulas are written in c - 1 = -s) and the reference lobe is exp(n log1p(-s)) (brdf_pow_lobe_s).
 *   epicentre:   s uniform over [0, s_e], s_e = 1 - exp(-0.511/n) = -expm1(-0.511/n), both
 *                ends included;
 *   attenuation: s = s_e (1/s_e)^t, t = j/samples, j = 1..samples: geometric from s_e to 1
 *                (x = pi/2), so the lobe's fall-off, about s_e..20 s_e at every n, gets a
 *                fixed share of the samples whatever n is.
 * No sample needs a cosine: the epicentre's are multiples of a step, the attenuation's a
 * per-lane factor times one scalar exp2 per 16 samples.
 *
 * Per n it writes ACC_OUT_STRIDE floats at the positions of brdf_shared.h's enum acc_out_field:
 * the max relative error in the epicentre, the max absolute errors in the attenuation and in
 * the epicentre, each with the s where it occurs, and the number of invalid model values (NaN,
 * Inf or negative) with the first such s. The s values are the exact float inputs the models saw, so the host can recompute every
 * reduced figure in double at the same input.
 *
 * Built with -DACC_REF_TABLE (a reference that is a user model, whose text a program beside the
 * model's cannot hold), the reference is not evaluated here but read from ref_table: a first
 * launch (table_pass 0) writes every sample's s there (per n: the epicentre's samples, then the
 * attenuation's), the host replaces each with the reference's double value rounded to float
 * (host/measure/accuracy/accuracy.c), and a second launch (table_pass 1) compares.
 */
/* ACC_W samples per step of the loop: 16 (float16, for PoCL, which vectorises explicit vectors
   to 512 bits) or 1 (scalar float: a driver that vectorises across work-items itself, as
   Mesa's llvmpipe and GPU compilers do, and for which sixteen-lane code is sixteen times the
   program; host/measure/accuracy/accuracy.c picks it). The samples are the same either way. */
#ifndef ACC_W
#define ACC_W 16
#endif
#if ACC_W == 16
#define REAL float16
#define ACC_IVEC int16
#define ACC_TRUE_COUNT(m) (-(m))          /* a true vector comparison is -1 per lane */
#define ACC_LANES lanes16()
#elif ACC_W == 1
#define REAL float
#define ACC_IVEC int
#define ACC_TRUE_COUNT(m) ((m) != 0)      /* a true scalar comparison is 1 */
#define ACC_LANES 0.0f
#else
#error "ACC_W must be 16 or 1"
#endif
#define RSCALAR float
/* PoCL leaves the model dispatch out of line on its own (a call per evaluation, four per
   iteration), and each call spills the loop's sixteen-lane accumulators to the stack and back;
   inlined, the loop keeps them in registers (with the inline ln of brdf_pow_lobe_s, about 1.25x
   on `brdfbench accuracy --models fvol --samples 32768`, scripts/bench_sweep.sh). */
#define BRDF_EVAL_FN __attribute__((always_inline)) static inline
/* The reference lobe's ln u written out, not called (brdf_models.h, brdf_ln_unit). */
#define BRDF_LN_UNIT(u) brdf_ln_unit(u)
/* The reference lobe in s: exp(n ln(1 - s)), brdf_models.h's brdf_pow_lobe_s. */
#define BRDF_POW_LOBE_CS(c, s, n) brdf_pow_lobe_s((s), (n))
#include "brdf_models.h"


/* Keeps the larger of (best, value) and the cosine that produced it; NaN never wins. */
#define KEEP_MAX(best, best_c, value, c)                    \
    do {                                                    \
        ACC_IVEC m_ = isgreater((value), (best));           \
        best = select(best, (value), m_);                   \
        best_c = select(best_c, (c), m_);                   \
    } while (0)

static float16 lanes16(void)
{
    return (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f,
                     8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f);
}

#if ACC_W == 16
/* Index and value of the largest lane (the first one on ties). */
static int argmax_lane(float16 v)
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

static void store_lanes(float16 v, float *a) { vstore16(v, 0, a); }
static void store_ilanes(int16 v, int *a) { vstore16(v, 0, a); }
#ifdef ACC_REF_TABLE
static void table_store(float16 v, __global float *p) { vstore16(v, 0, p); }
static float16 table_load(__global const float *p) { return vload16(0, p); }
#endif
#else
static int argmax_lane(float v) { (void)v; return 0; }
static float lane_of(float v, int k) { (void)k; return v; }
static void store_lanes(float v, float *a) { a[0] = v; }
static void store_ilanes(int v, int *a) { a[0] = v; }
#ifdef ACC_REF_TABLE
static void table_store(float v, __global float *p) { p[0] = v; }
static float table_load(__global const float *p) { return p[0]; }
#endif
#endif

__kernel void accuracy_sweep(const int model, const float p0, const float p1,
                             const int ref_model, const float rp0, const float rp1,
                             __global const float *n_values, const int n_count,
                             const int samples, const int chunks, __global float *out
#ifdef ACC_REF_TABLE
                             , const int table_pass, __global float *ref_table
#endif
                             )
{
    /* chunks work-items per n, each over a contiguous run of the samples (1 on a CPU device;
       a GPU needs more work-items than there are values of n): work-item gid writes its own
       maxima and the host keeps the largest of each n's chunks (accuracy_sweep_device). */
    const int gid = (int)get_global_id(0);
    if (gid >= n_count * chunks)
        return;
    const int per = samples / chunks;   /* a multiple of ACC_W (the host chooses chunks so) */
    const int i0 = (gid % chunks) * per, i1 = i0 + per;
    const float n = n_values[gid / chunks];
    const REAL nv = (REAL)(n);
    const float s_e = -expm1(-(float)BRDF_ZONE_K / n);               /* epicentre end in s (docs/definitions.md) */
    const REAL lane = ACC_LANES;
    /* Epicentre: s = s_e j / (samples - 1), j = i + lane. */
    const float epi_step = s_e / (float)(samples - 1);
    /* Attenuation: s = s_e r^j, r = (1/s_e)^(1/samples), j = i + lane + 1: a scalar exp2 per
       16 samples times a per-lane factor r^(lane + 1), so no rounding accumulates. */
    const float log2_r = -log2(s_e) / (float)samples;
    const REAL att_lane = s_e * exp2((lane + 1.0f) * log2_r);
    /* A model that sees only c (phongpow's pow(c, n), a user model) gets c = 1 - s rounded to
       float: s is moved onto that lattice first, so that the model, its reference and the
       host's double recomputation all work at the one input the model really saw. */
    const int c_only = brdf_sees_only_c(model);

    REAL epi_rel = (REAL)(-1.0f), epi_rel_s = (REAL)(0.0f);
    REAL epi_abs = (REAL)(-1.0f), epi_abs_s = (REAL)(0.0f);
    REAL att_abs = (REAL)(-1.0f), att_abs_s = (REAL)(0.0f);
    ACC_IVEC bad = (ACC_IVEC)(0);
    REAL bad_s = (REAL)(NAN);

#ifdef ACC_REF_TABLE
    __global float *tab = ref_table + (size_t)(gid / chunks) * 2 * (size_t)samples;   /* this n's samples */
#endif
    for (int i = i0; i < i1; i += ACC_W) {
        /* Epicentre (the last sample is s_e itself, up to rounding). */
        REAL s = fmin(((float)i + lane) * epi_step, s_e);
        if (c_only) {   /* onto the float cosines, never past the zone's end */
            const REAL c = 1.0f - s;
            s = select(1.0f - c, 1.0f - nextafter(c, (REAL)(2.0f)), isgreater(1.0f - c, s_e));
        }
#ifdef ACC_REF_TABLE
        if (table_pass == 0) {   /* the samples only: the epicentre's now, the attenuation's below */
            table_store(s, tab + i);
        } else {
#endif
        REAL f = brdf_eval_s(model, s, nv, p0, p1);
#ifdef ACC_REF_TABLE
        REAL r = table_load(tab + i);
#else
        REAL r = brdf_eval_s(ref_model, s, nv, rp0, rp1);
#endif
        /* An invalid model value (NaN, Inf, negative) is counted, not folded into a maximum:
           its error becomes NaN, which never wins. */
        ACC_IVEC invalid = isless(f, 0.0f) | !isfinite(f);
        bad_s = select(bad_s, fmin(bad_s, s), invalid);   /* the smallest invalid s */
        bad += ACC_TRUE_COUNT(invalid);
        REAL d = select(fabs(f - r), (REAL)(NAN), invalid);
        KEEP_MAX(epi_rel, epi_rel_s, d / r, s);
        KEEP_MAX(epi_abs, epi_abs_s, d, s);
#ifdef ACC_REF_TABLE
        }
#endif

        /* Attenuation; s never passes 1 (x = pi/2). */
        s = fmin(att_lane * exp2((float)i * log2_r), 1.0f);
        if (c_only) {   /* onto the float cosines, never before the zone's start */
            const REAL c = 1.0f - s;
            s = select(1.0f - c, 1.0f - nextafter(c, (REAL)(0.0f)), isless(1.0f - c, s_e));
        }
#ifdef ACC_REF_TABLE
        if (table_pass == 0) {
            table_store(s, tab + samples + i);
            continue;
        }
        REAL f = brdf_eval_s(model, s, nv, p0, p1);
        REAL r = table_load(tab + samples + i);
        ACC_IVEC invalid;
        REAL d;
#else
        f = brdf_eval_s(model, s, nv, p0, p1);
        r = brdf_eval_s(ref_model, s, nv, rp0, rp1);
#endif
        invalid = isless(f, 0.0f) | !isfinite(f);
        bad_s = select(bad_s, fmin(bad_s, s), invalid);   /* the smallest invalid s */
        bad += ACC_TRUE_COUNT(invalid);
        d = select(fabs(f - r), (REAL)(NAN), invalid);
        KEEP_MAX(att_abs, att_abs_s, d, s);
    }

    __global float *o = out + (size_t)gid * ACC_OUT_STRIDE;
    int k = argmax_lane(epi_rel);
    o[ACC_O_EPI_REL] = lane_of(epi_rel, k);
    o[ACC_O_EPI_REL_S] = lane_of(epi_rel_s, k);
    k = argmax_lane(att_abs);
    o[ACC_O_ATT_ABS] = lane_of(att_abs, k);
    o[ACC_O_ATT_ABS_S] = lane_of(att_abs_s, k);
    k = argmax_lane(epi_abs);
    o[ACC_O_EPI_ABS] = lane_of(epi_abs, k);
    o[ACC_O_EPI_ABS_S] = lane_of(epi_abs_s, k);
    int bad_total = 0;
    float first_bad = NAN;
    int ba[ACC_W];
    float bc[ACC_W];
    store_ilanes(bad, ba);
    store_lanes(bad_s, bc);
    for (int q = 0; q < ACC_W; ++q) {
        bad_total += ba[q];
        first_bad = fmin(first_bad, bc[q]);   /* the smallest invalid s: any launch shape gives it */
    }
    o[ACC_O_INVALID] = (float)bad_total;
    o[ACC_O_INVALID_S] = first_bad;
}

/* Evaluates a model at given points, 16 per work-item, through the same float16 code path
 * as the sweep. count is a multiple of 16. */
__kernel void models_probe(const int model, const float p0, const float p1,
                           __global const float *c, __global const float *n, __global float *out)
{
    const size_t i = get_global_id(0);
#if ACC_W == 16
    vstore16(brdf_eval(model, vload16(i, c), vload16(i, n), p0, p1), i, out);
#else
    for (size_t k = 16 * i; k < 16 * i + 16; ++k)
        out[k] = brdf_eval(model, c[k], n[k], p0, p1);
#endif
}
