/* hostc_sweep.c - the accuracy sweep of kernels/accuracy.cl in tuned C, one n at a time: the
 * baseline of the sweep's speed (host/support/hostc_baseline.c runs it on every CPU).
 *
 * A file of its own because the sweep evaluates the reference lobe in s = 1 - cos x, as
 * exp(n log1p(-s)) (BRDF_POW_LOBE_CS), where the throughput baseline evaluates c^n with powf:
 * brdf_models.h is compiled once per file, with one choice each. Same flags as
 * hostc_baseline.c (CMakeLists.txt): -O3 -march=native -fno-math-errno, <tgmath.h> float
 * functions, fmax as a compare.
 */
#define _GNU_SOURCE
#include <tgmath.h>

static inline float hostc_fmaxf(float a, float b) { return (a > b || b != b) ? a : b; }
static inline float hostc_fminf(float a, float b) { return (a < b || b != b) ? a : b; }
#undef fmax
#define fmax(a, b) hostc_fmaxf((a), (b))
#undef fmin
#define fmin(a, b) hostc_fminf((a), (b))
#define BRDF_POW_LOBE(c, n) powf((c), (n))
#define BRDF_POW_LOBE_CS(c, s, n) expf((n) * log1pf(-(s)))

#define REAL float
#define RSCALAR float
/* the model dispatch inlined into each per-id loop, where its switch folds to one case */
#define BRDF_EVAL_FN __attribute__((always_inline)) static inline
#include "brdf_models.h"

#include "hostc_baseline.h"

#define HOSTC_IDS(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8) X(9) X(10) X(11) X(12) X(13) X(14) X(15) X(16) \
    X(17) X(18) X(19) X(20) X(21) X(22) X(23) X(24) X(25) X(26) X(27) X(28) X(29) X(30) X(31) X(32) X(33) \
    X(34) X(35) X(36) X(37) X(38) X(39)
_Static_assert(BRDF_MODEL_COUNT <= 40, "hostc_sweep_n_any covers model ids 0..39");

/* One n of accuracy_sweep (kernels/accuracy.cl), sample by sample, in s = 1 - cos x as the
 * kernel places and evaluates them. */
static inline __attribute__((always_inline)) void hostc_sweep_n(const int id, float p0, float p1, int ref,
                                                                float rp0, float rp1, float n, long samples,
                                                                float *o)
{
    const float s_e = -expm1(-(float)BRDF_ZONE_K / n);
    const float epi_step = s_e / (float)(samples - 1);
    const float log2_r = -log2(s_e) / (float)samples;
    float att_lane[16];
    for (int l = 0; l < 16; ++l)
        att_lane[l] = s_e * exp2((float)(l + 1) * log2_r);
    float epi_rel = -1.0f, epi_rel_s = 0.0f, epi_abs = -1.0f, epi_abs_s = 0.0f, att_abs = -1.0f, att_abs_s = 0.0f;
    long bad = 0;
    float bad_s = NAN;
    for (long i = 0; i < samples; i += 16) {
        const float att_base = exp2((float)i * log2_r);
        for (int l = 0; l < 16; ++l) {
            /* Epicentre: s uniform over [0, s_e]. Comparisons with > keep NaN out, as isgreater. */
            float s = fmin(((float)i + (float)l) * epi_step, s_e);
            float f = brdf_eval_s(id, s, n, p0, p1), r = brdf_eval_s(ref, s, n, rp0, rp1);
            /* An invalid model value (NaN, Inf, negative) is counted and kept out of the maxima. */
            if (f < 0.0f || !isfinite(f)) {
                if (bad++ == 0) bad_s = s;
            } else {
                float d = fabs(f - r), rel = d / r;
                if (rel > epi_rel) { epi_rel = rel; epi_rel_s = s; }
                if (d > epi_abs) { epi_abs = d; epi_abs_s = s; }
            }
            /* Attenuation: s geometric from s_e to 1. */
            s = fmin(att_lane[l] * att_base, 1.0f);
            f = brdf_eval_s(id, s, n, p0, p1);
            r = brdf_eval_s(ref, s, n, rp0, rp1);
            if (f < 0.0f || !isfinite(f)) {
                if (bad++ == 0) bad_s = s;
            } else if (fabs(f - r) > att_abs) {
                att_abs = fabs(f - r);
                att_abs_s = s;
            }
        }
    }
    o[0] = epi_rel; o[1] = epi_rel_s;
    o[2] = att_abs; o[3] = att_abs_s;
    o[4] = epi_abs; o[5] = epi_abs_s;
    o[6] = (float)bad;  o[7] = bad_s;
}

void hostc_sweep_n_any(int id, float p0, float p1, int ref, float rp0, float rp1, float n, long samples,
                              float *o)
{
    switch (id) {
#define HOSTC_CASE(k) case k: hostc_sweep_n(k, p0, p1, ref, rp0, rp1, n, samples, o); return;
    HOSTC_IDS(HOSTC_CASE)
#undef HOSTC_CASE
    default: return;
    }
}

