/* hostc_sweep.c - the accuracy sweep of kernels/accuracy.cl in tuned C, one n at a time: the
 * baseline of the sweep's speed (host/support/hostc_baseline.c runs it on every CPU).
 *
 * A file of its own because the sweep evaluates the reference lobe in s = 1 - cos x
 * (BRDF_POW_LOBE_CS as brdf_pow_lobe_s, as kernels/accuracy.cl), where the throughput
 * baseline evaluates it in c: brdf_models.h is compiled once per file, with one choice
 * each. Same flags as hostc_baseline.c (CMakeLists.txt): -O3 -march=native -fno-math-errno, <tgmath.h> float
 * functions in libmvec's vector forms (hostc_vecmath.h), fmax as a compare.
 */
#define _GNU_SOURCE
#include <tgmath.h>
#include "hostc_vecmath.h"

static inline float hostc_fmaxf(float a, float b) { return (a > b || b != b) ? a : b; }
static inline float hostc_fminf(float a, float b) { return (a < b || b != b) ? a : b; }
#undef fmax
#define fmax(a, b) hostc_fmaxf((a), (b))
#undef fmin
#define fmin(a, b) hostc_fminf((a), (b))
/* the reference lobe in s as the device's sweep evaluates it: exp(n (ln u + e/u)), u = 1 - s
   (brdf_models.h, brdf_pow_lobe_s), with logf for ln u */
#define BRDF_POW_LOBE_CS(c, s, n) brdf_pow_lobe_s((s), (n))

#define REAL float
#define RSCALAR float
/* the model dispatch inlined into each per-id loop, where its switch folds to one case */
#define BRDF_EVAL_FN __attribute__((always_inline)) static inline
#include "brdf_models.h"

#include "hostc_baseline.h"

/* Samples per block: each block's inputs are made, then the model and its reference are
   evaluated over the whole block by their own loops (a function per id, its switch folded,
   vectorised), then the block is reduced lane by lane. A multiple of 16. */
#define HOSTC_BLOCK 256

typedef void (*hostc_block_fn)(const float *s, float *f, int count, float n, float p0, float p1);

#define HOSTC_BLOCK_FN(name, k)                                                                            \
    static __attribute__((noinline)) void hostc_block_##name(const float *s, float *f, int count, float n,\
                                                          float p0, float p1)                            \
    {                                                                                                    \
        for (int j = 0; j < count; ++j)                                                                  \
            f[j] = brdf_eval_s(k, s[j], n, p0, p1);                                                      \
    }
/* one instance per row of the model list (its descriptors: kernels/brdf_model_list.h) */
#define BRDF_MODEL(ENUM, C_ONLY, EVAL, ...) HOSTC_BLOCK_FN(ENUM, BRDF_##ENUM)
#include "brdf_model_list.h"
#undef BRDF_MODEL
#undef HOSTC_BLOCK_FN

static hostc_block_fn hostc_block_of(int id)
{
    switch (id) {
#define BRDF_MODEL(ENUM, C_ONLY, EVAL, ...) case BRDF_##ENUM: return hostc_block_##ENUM;
#include "brdf_model_list.h"
#undef BRDF_MODEL
    default: return NULL;
    }
}

/* The 16 lanes of the kernel's reductions: each lane keeps its own maxima and where they occur,
   so the figures are the kernel's (on ties the first lane wins, kernels/accuracy.cl). */
struct hostc_lanes {
    float epi_rel[16], epi_rel_s[16], epi_abs[16], epi_abs_s[16], att_abs[16], att_abs_s[16], bad_s[16];
    int bad[16];
};

/* Folds count samples (a multiple of 16) of one zone into the lanes: f the model, r the
   reference at s. An invalid model value (NaN, Inf, negative) is counted, and its error is NaN,
   which never wins a maximum (comparisons with >, as isgreater). */
static inline __attribute__((always_inline)) void hostc_fold(struct hostc_lanes *L, int epicentre, const float *s,
                                                             const float *f, const float *r, int count)
{
    for (int q = 0; q < count; q += 16)
        for (int l = 0; l < 16; ++l) {
            float fv = f[q + l], sv = s[q + l];
            int invalid = fv < 0.0f || !isfinite(fv);
            L->bad_s[l] = invalid ? fminf(L->bad_s[l], sv) : L->bad_s[l];   /* the smallest invalid s */
            L->bad[l] += invalid;
            float d = invalid ? NAN : fabs(fv - r[q + l]);
            if (epicentre) {
                float rel = d / r[q + l];
                int m = rel > L->epi_rel[l];
                L->epi_rel[l] = m ? rel : L->epi_rel[l];
                L->epi_rel_s[l] = m ? sv : L->epi_rel_s[l];
                m = d > L->epi_abs[l];
                L->epi_abs[l] = m ? d : L->epi_abs[l];
                L->epi_abs_s[l] = m ? sv : L->epi_abs_s[l];
            } else {
                int m = d > L->att_abs[l];
                L->att_abs[l] = m ? d : L->att_abs[l];
                L->att_abs_s[l] = m ? sv : L->att_abs_s[l];
            }
        }
}

/* The largest lane of v (the first one on ties) and its s, into o[at], o[at_s]. */
static void hostc_lane_max(const float *v, const float *s, float *o, int at, int at_s)
{
    int k = 0;
    for (int l = 1; l < 16; ++l)
        if (v[l] > v[k])
            k = l;
    o[at] = v[k];
    o[at_s] = s[k];
}

/* One n of accuracy_sweep (kernels/accuracy.cl): the same samples in s = 1 - cos x, the same
   evaluations and the same lane-wise reductions. */
void hostc_sweep_n_any(int id, float p0, float p1, int ref, float rp0, float rp1, float n, long samples, float *o)
{
    hostc_block_fn model = hostc_block_of(id), reference = hostc_block_of(ref);
    if (!model || !reference)
        return;
    const float s_e = -expm1(-(float)BRDF_ZONE_K / n);
    const float epi_step = s_e / (float)(samples - 1);
    const float log2_r = -log2(s_e) / (float)samples;
    const int c_only = brdf_sees_only_c(id);
    float att_lane[16];
    for (int l = 0; l < 16; ++l)
        att_lane[l] = s_e * exp2(((float)l + 1.0f) * log2_r);
    struct hostc_lanes L;
    for (int l = 0; l < 16; ++l) {
        L.epi_rel[l] = L.epi_abs[l] = L.att_abs[l] = -1.0f;
        L.epi_rel_s[l] = L.epi_abs_s[l] = L.att_abs_s[l] = 0.0f;
        L.bad_s[l] = NAN;
        L.bad[l] = 0;
    }
    float s[HOSTC_BLOCK], f[HOSTC_BLOCK], r[HOSTC_BLOCK];
    for (long i0 = 0; i0 < samples; i0 += HOSTC_BLOCK) {
        /* whole steps of 16, as the kernel's loop (i < samples, 16 lanes a step) */
        const long left = (samples - i0 + 15) / 16 * 16;
        const int count = (int)(left < HOSTC_BLOCK ? left : HOSTC_BLOCK);
        /* Epicentre: s uniform over [0, s_e], the last sample s_e itself up to rounding. */
        for (int q = 0; q < count; q += 16)
            for (int l = 0; l < 16; ++l)
                s[q + l] = fmin(((float)(i0 + q) + (float)l) * epi_step, s_e);
        if (c_only)   /* onto the float cosines, never past the zone's end (as the kernel) */
            for (int j = 0; j < count; ++j) {
                const float c = 1.0f - s[j];
                s[j] = 1.0f - c > s_e ? 1.0f - nextafterf(c, 2.0f) : 1.0f - c;
            }
        model(s, f, count, n, p0, p1);
        reference(s, r, count, n, rp0, rp1);
        hostc_fold(&L, 1, s, f, r, count);
        /* Attenuation: s geometric from s_e to 1, a per-lane factor times one exp2 per 16. */
        for (int q = 0; q < count; q += 16) {
            const float base = exp2((float)(i0 + q) * log2_r);
            for (int l = 0; l < 16; ++l)
                s[q + l] = fmin(att_lane[l] * base, 1.0f);
        }
        if (c_only)   /* never before the zone's start */
            for (int j = 0; j < count; ++j) {
                const float c = 1.0f - s[j];
                s[j] = 1.0f - c < s_e ? 1.0f - nextafterf(c, 0.0f) : 1.0f - c;
            }
        model(s, f, count, n, p0, p1);
        reference(s, r, count, n, rp0, rp1);
        hostc_fold(&L, 0, s, f, r, count);
    }
    hostc_lane_max(L.epi_rel, L.epi_rel_s, o, ACC_O_EPI_REL, ACC_O_EPI_REL_S);
    hostc_lane_max(L.att_abs, L.att_abs_s, o, ACC_O_ATT_ABS, ACC_O_ATT_ABS_S);
    hostc_lane_max(L.epi_abs, L.epi_abs_s, o, ACC_O_EPI_ABS, ACC_O_EPI_ABS_S);
    long bad = 0;
    float first_bad = NAN;
    for (int l = 0; l < 16; ++l) {
        bad += L.bad[l];
        first_bad = fminf(first_bad, L.bad_s[l]);
    }
    o[ACC_O_INVALID] = (float)bad;
    o[ACC_O_INVALID_S] = first_bad;
}
