/* test_fp16.c - shader code written in half evaluated in binary16 (docs/user-models.md,
 * "Precision as written"):
 *   - the rounding helper of the fp16 build (kernels/brdf_models.h, brdf_round_half through
 *     RHALF), scalar and 16-wide, run on the device through a tiny kernel, against a table of
 *     binary16 values worked by hand below (each row says how);
 *   - a spherical-Gaussian Phong lobe written in half (tests/test_shaderlang_files/
 *     phongapprox_half.hlsl; in GLSL under `precision mediump float`, phongapprox_mediump.glsl), evaluated by the fp16 build at five points, against the same
 *     formula simulated here in C, every step rounded to binary16 by to_binary16 (written from
 *     the format's definition, independently of the device's helper);
 *   - its accuracy row: fp16 figures beside the fp32 ones, the fp16 error the larger, the max
 *     Delta recomputed at its point with the simulation against phongn in double, the JSON row's
 *     fp16 member, and no fp16 member for the same lobe written in float. */
#include "accuracy.h"
#include "accuracy_report.h"
#include "check.h"
#include "clsession.h"
#include "models.h"
#include "testutil.h"
#include "usermodel.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* x rounded to binary16 (1 + 10 bits of significand, exponents -14..15, subnormals down to
 * 2^-24), to nearest with ties to even: x's binade [2^e, 2^(e+1)) (at least e = -14, the
 * subnormals' spacing) has spacing 2^(e-10); nearbyint in the default rounding mode rounds a
 * tie to the even multiple; past 65504 (the largest finite) the result is infinite. */
static double to_binary16(double x)
{
    if (isnan(x) || isinf(x) || x == 0)
        return x;
    int e2;
    frexp(fabs(x), &e2);   /* |x| = m 2^e2, m in [0.5, 1): the binade is 2^(e2 - 1) */
    int e = e2 - 1 < -14 ? -14 : e2 - 1;
    double q = ldexp(1.0, e - 10);
    double r = nearbyint(fabs(x) / q) * q;
    return copysign(r > 65504.0 ? INFINITY : r, x);
}

/* The hand-worked table: an input (a float) and its binary16 value. */
static const struct {
    float in;
    double want;
    const char *why;
} table[] = {
    { 1.0f, 1.0, "1 is a binary16 value" },
    { 1.0f + 0x1p-11f, 1.0, "halfway between 1 and 1 + 2^-10: ties to the even significand, 1" },
    { 1.0f + 3 * 0x1p-11f, 1.0 + 0x1p-9, "halfway between 1 + 2^-10 (odd) and 1 + 2^-9 (even): up" },
    { 1.0f + 0x1p-11f + 0x1p-20f, 1.0 + 0x1p-10, "just above halfway: up to 1 + 2^-10" },
    { 2049.0f, 2048.0, "spacing 2 in [2048, 4096): 2049 is a tie, 2048 (significand 0) is even" },
    { 2051.0f, 2052.0, "2051 between 2050 (odd significand 1) and 2052 (2): up" },
    { 0.1f, 0.0999755859375, "0.1 = 1.6 x 2^-4, 0.6 x 1024 = 614.4 -> 614: 1638 x 2^-14" },
    { -2.5f, -2.5, "exact, sign kept" },
    { 65504.0f, 65504.0, "the largest finite binary16, (2 - 2^-10) 2^15" },
    { 65519.0f, 65504.0, "below the halfway point 65520 to the next step 65536: 65504" },
    { 65520.0f, INFINITY, "halfway between 65504 (odd significand 1023) and 2^16 (even): 2^16 overflows" },
    { -65520.0f, -INFINITY, "the same below zero" },
    { 1e9f, INFINITY, "far past the range" },
    { 0x1p-14f, 0x1p-14, "the smallest normal" },
    { 1023 * 0x1p-24f, 1023 * 0x1p-24, "the largest subnormal, 1023 x 2^-24" },
    { 1023.5f * 0x1p-24f, 0x1p-14, "halfway between the largest subnormal (odd) and 2^-14 (1024 x 2^-24, even)" },
    { 0x1p-24f, 0x1p-24, "the smallest subnormal, 2^-24" },
    { 0x1p-25f, 0.0, "2^-25 is halfway between 0 (even) and 2^-24 (odd): 0" },
    { 0x1p-25f + 0x1p-35f, 0x1p-24, "just above halfway: 2^-24" },
    { 3 * 0x1p-25f, 0x1p-23, "1.5 x 2^-24: halfway between 2^-24 (odd) and 2 x 2^-24 (even)" },
    { 0x1p-26f, 0.0, "below halfway: 0" },
    { -0x1p-25f, -0.0, "the negative tie: -0" },
};
#define TABLE_N ((int)(sizeof table / sizeof table[0]))

/* The point kernels (cl_run_points16's arguments: c, n, out): the 16-wide helper and the scalar
   one, each over 16 values per work-item. */
static const char probe_source[] =
    "__kernel void half16_probe(__global const float *x, __global const float *unused, __global float *out)\n"
    "{\n"
    "    const size_t i = get_global_id(0);\n"
    "    vstore16(RHALF(vload16(i, x)), i, out);\n"
    "}\n"
    "__kernel void half1_probe(__global const float *x, __global const float *unused, __global float *out)\n"
    "{\n"
    "    const size_t i = get_global_id(0);\n"
    "    for (int k = 0; k < 16; ++k)\n"
    "        out[16 * i + k] = RHALF(x[16 * i + k]);\n"
    "}\n";

static int same_value(double got, double want)
{
    if (isnan(want))
        return isnan(got);
    return got == want && signbit(got) == signbit(want);
}

static void test_table_by_hand(void)
{
    /* the simulation agrees with every hand-worked row (so it can stand for them below) */
    for (int i = 0; i < TABLE_N; ++i)
        CHECK(same_value(to_binary16(table[i].in), table[i].want), "simulated binary16 of %a: %a, want %a (%s)",
              (double)table[i].in, to_binary16(table[i].in), table[i].want, table[i].why);
}

static void test_helper_on_device(struct cl_session *s)
{
    cl_program prog = NULL;
    cl_kernel k16 = NULL, k1 = NULL;
    static const char *const names[] = { "half16_probe", "half1_probe" };
    cl_kernel *const kernels[] = { &k16, &k1 };
    CHECK(clsession_build_kernels(s, "accuracy.cl", probe_source, "-DBRDF_FP16=1", &prog, 2, names, kernels) == 0,
          "accuracy.cl of the fp16 build with the probes builds");
    if (!k16 || !k1)
        return;
    float x[TABLE_N + 2], unused[TABLE_N + 2] = { 0 }, out[TABLE_N + 2];
    for (int i = 0; i < TABLE_N; ++i)
        x[i] = table[i].in;
    x[TABLE_N] = NAN;        /* NaN stays NaN, infinity stays infinity */
    x[TABLE_N + 1] = INFINITY;
    cl_kernel ks[2] = { k16, k1 };
    for (int w = 0; w < 2; ++w) {
        memset(out, 0, sizeof out);
        CHECK(cl_run_points16(s, ks[w], 0, x, unused, TABLE_N + 2, out) == 0, "%s runs", names[w]);
        for (int i = 0; i < TABLE_N; ++i)
            CHECK(same_value(out[i], table[i].want), "%s: RHALF(%a) = %a, want %a (%s)", names[w], (double)x[i],
                  (double)out[i], table[i].want, table[i].why);
        CHECK(isnan(out[TABLE_N]), "%s: RHALF(NaN) is NaN, got %g", names[w], (double)out[TABLE_N]);
        CHECK(isinf(out[TABLE_N + 1]) && out[TABLE_N + 1] > 0, "%s: RHALF(inf) = %g", names[w],
              (double)out[TABLE_N + 1]);
    }
    clsession_release_kernels(&prog, 2, kernels);
}

/* phongapprox_half.hlsl step by step in binary16, as its half code is written:
 *   norm = (n + 2.0) * 0.1591549;  k = Power * 1.442695;  lobe = exp2(k * NoH - k);
 *   return norm * lobe;  (c and n arrive in half; each literal is a half constant) */
static double sgphong_binary16(double c, double n)
{
    double h_c = to_binary16(c), h_n = to_binary16(n);
    double norm = to_binary16(to_binary16(h_n + 2.0) * to_binary16(0.1591549));
    double k = to_binary16(h_n * to_binary16(1.442695));
    double lobe = to_binary16(exp2(to_binary16(to_binary16(k * h_c) - k)));
    return to_binary16(norm * lobe);
}

/* The same formula with no rounding at all (what the float build approximates). */
static double sgphong_exact(double c, double n)
{
    double k = n * 1.442695;
    return (n + 2.0) * 0.1591549 * exp2(k * c - k);
}

static int load_model(const char *file, const char *label, struct model_spec *m)
{
    char path[1024], err[600] = "";
    const char *src = getenv("SRC_DIR");
    snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/%s", src ? src : ".", file);
    int rc = usermodel_load_file(path, NULL, err, sizeof err);
    CHECK(rc == 0, "loading %s: %s", path, err);
    if (rc == 0) {
        rc = model_spec_parse(label, m, err, sizeof err);
        CHECK(rc == 0, "%s: %s", label, err);
    }
    return rc;
}

static int test_sgphong(struct accuracy_ctx *a)
{
    struct model_spec m, mf, mm;
    if (load_model("phongapprox_half.hlsl", "sgphong", &m) || load_model("phongapprox_float.hlsl", "sgphongf", &mf) ||
        load_model("phongapprox_mediump.glsl", "sgphongm", &mm))
        return 0;
    const struct model_runtime *rt = models_runtime(m.info), *rtf = models_runtime(mf.info);
    CHECK(rt && rt->fp16, "the lobe written in half has binary16 code");
    CHECK(rtf && !rtf->fp16, "the lobe written in float has none");
    CHECK(models_runtime(mm.info) && models_runtime(mm.info)->fp16, "the GLSL lobe under precision mediump has too");

    /* five points of (c, n): the peak, points on the lobe, one past its fall-off */
    static const float pc[5] = { 1.0f, 0.999f, 0.99f, 0.95f, 0.7f }, pn[5] = { 10.0f, 200.0f, 50.0f, 30.0f, 3.0f };
    float got16[5], got32[5], gotm[5];
    struct accuracy_ctx h;
    int rc = accuracy_open(&h, a->s, "-DBRDF_FP16=1");
    CHECK(rc == 0, "the fp16 build's sweep program");
    if (rc)
        return rc;
    rc = accuracy_probe(&h, &m, pc, pn, 5, got16);
    if (rc == 0)
        rc = accuracy_probe(&h, &mm, pc, pn, 5, gotm);
    accuracy_close(&h);
    if (rc == 0)
        rc = accuracy_probe(a, &m, pc, pn, 5, got32);
    CHECK(rc == 0, "the lobe evaluated at five points (fp16 and fp32 builds)");
    if (rc)
        return rc;
    for (int i = 0; i < 5; ++i) {
        double want = sgphong_binary16(pc[i], pn[i]), exact = sgphong_exact(pc[i], pn[i]);
        /* +, -, * of binary16 values done in float and rounded once are exactly binary16's (float's
           24 bits are at least 2 x 11 + 2: the double rounding is innocuous); exp2 is float's on
           the device and double's here, so its rounding may land one binary16 step apart. */
        double step = ldexp(1.0, ilogb(want) - 10);
        CHECK(fabs(got16[i] - want) <= step, "fp16 sgphong(%g, %g) = %.9g, binary16 simulation %.9g", (double)pc[i],
              (double)pn[i], (double)got16[i], want);
        CHECK(fabs(gotm[i] - want) <= step, "fp16 sgphongm(%g, %g) = %.9g (GLSL, mediump), binary16 simulation %.9g",
              (double)pc[i], (double)pn[i], (double)gotm[i], want);
        CHECK(to_binary16(got16[i]) == got16[i], "fp16 sgphong(%g, %g) = %.9g is a binary16 value", (double)pc[i],
              (double)pn[i], (double)got16[i]);
        CHECK(fabs(got32[i] - exact) <= 1e-5 * exact, "fp32 sgphong(%g, %g) = %.9g, exact %.9g", (double)pc[i],
              (double)pn[i], (double)got32[i], exact);
        printf("sgphong(%g, %g): fp16 %.9g (simulated %.9g), fp32 %.9g, exact %.9g\n", (double)pc[i], (double)pn[i],
               (double)got16[i], want, (double)got32[i], exact);
    }

    /* HLSL's literal 0.1h is a half constant (1638 x 2^-14 = 0.0999755859375, worked in the table
       above) even in a float product; 0.1 without the suffix takes the float's precision */
    {
        struct user_model *um = NULL;
        char err[600] = "";
        struct model_spec hl;
        int ok = usermodel_parse_expression("hlit=float y = c * 0.1h; float z = c * 0.1; return y + 8.0 * z;", &um,
                                            err, sizeof err) == 0 &&
                 usermodel_register(um, err, sizeof err) == 0 && model_spec_parse("hlit", &hl, err, sizeof err) == 0;
        CHECK(ok, "hlit: %s", err);
        float hc[2] = { 0.5f, 0.75f }, hn[2] = { 1.0f, 1.0f }, hv[2];
        if (ok && accuracy_open(&h, a->s, "-DBRDF_FP16=1") == 0) {
            CHECK(accuracy_probe(&h, &hl, hc, hn, 2, hv) == 0, "hlit on the device");
            accuracy_close(&h);
            for (int i = 0; i < 2; ++i) {
                float want = hc[i] * 0.0999755859375f + 8.0f * (hc[i] * 0.1f);
                CHECK(fabsf(hv[i] - want) <= 1e-6f, "hlit(%g) = %.9g, want %.9g", (double)hc[i], (double)hv[i],
                      (double)want);
            }
        }
    }

    /* the accuracy rows: fp16 beside fp32 for the half lobe, the fp16 error the larger; none
       for the float lobe, whose fp32 figures are the half lobe's (the same formula) */
    struct accuracy_grid g = { 2, 200, 22, 1024 };
    struct accuracy_result r, rf;
    memset(&r, 0, sizeof r);
    memset(&rf, 0, sizeof rf);
    rc = accuracy_run(a, &m, &g, &r);
    if (rc == 0)
        rc = accuracy_run(a, &mf, &g, &rf);
    CHECK(rc == 0, "the accuracy sweeps run");
    if (rc == 0) {
        CHECK(r.ok && r.fp16.present, "the half lobe's row has fp16 figures");
        CHECK(!rf.fp16.present, "the float lobe's row has none");
        CHECK(fabs(r.epicentre.value - rf.epicentre.value) <= 1e-6 * rf.epicentre.value &&
                  fabs(r.attenuation.value - rf.attenuation.value) <= 1e-6 * rf.attenuation.value,
              "fp32 figures of the half lobe (%.6g, %.6g) are the float lobe's (%.6g, %.6g)", r.epicentre.value,
              r.attenuation.value, rf.epicentre.value, rf.attenuation.value);
        CHECK(r.fp16.epicentre.value > r.epicentre.value && r.fp16.attenuation.value > r.attenuation.value,
              "fp16 errors (%.4g, %.4g) above fp32's (%.4g, %.4g)", r.fp16.epicentre.value, r.fp16.attenuation.value,
              r.epicentre.value, r.attenuation.value);
        CHECK(fabs(r.fp16.ratio_rel - r.fp16.epicentre.value / r.epicentre.value) < 1e-12 &&
                  fabs(r.fp16.ratio_abs - r.fp16.attenuation.value / r.attenuation.value) < 1e-12,
              "the ratios are fp16 over fp32");
        /* the fp16 max Delta at its point, recomputed here: the simulated binary16 lobe against
           phongn's (n + 2)/(2 pi) c^n in double, at the cosine the row names */
        double n = r.fp16.attenuation.n, c = cos(r.fp16.attenuation.x);
        double d = fabs(sgphong_binary16(c, n) - (n + 2.0) / (2.0 * 3.14159265358979323846) * pow(c, n));
        CHECK(fabs(d - r.fp16.attenuation.value) <= 0x1p-10 * (n + 2.0) / (2.0 * 3.14159265358979323846) + 1e-6,
              "fp16 max Delta %.6g at n = %g, x = %.6g; simulated there %.6g", r.fp16.attenuation.value, n,
              r.fp16.attenuation.x, d);
        /* the row as written: an fp16 member with the same figures; none for the float lobe */
        char dir[512], path[600], err[300];
        if (test_tmpdir_make(dir, sizeof dir, "test_fp16") == 0) {
            snprintf(path, sizeof path, "%s/acc.json", dir);
            struct accuracy_result both[2] = { r, rf };
            CHECK(accuracy_write_json(path, both, 2, a->s, "", err, sizeof err) == 0, "accuracy.json: %s", err);
            json_error_t je;
            json_t *doc = json_load_file(path, 0, &je);
            json_t *rows = json_object_get(doc, "results");
            json_t *f16 = json_object_get(json_array_get(rows, 0), "fp16");
            CHECK(f16 && json_number_value(json_object_get(f16, "max_rel")) == r.fp16.epicentre.value &&
                      json_number_value(json_object_get(f16, "max_abs")) == r.fp16.attenuation.value &&
                      json_number_value(json_object_get(f16, "ratio_rel_to_fp32")) == r.fp16.ratio_rel &&
                      json_is_boolean(json_object_get(f16, "device_has_cl_khr_fp16")),
                  "the half lobe's JSON row has its fp16 member");
            CHECK(json_array_size(rows) == 2 && !json_object_get(json_array_get(rows, 1), "fp16"),
                  "the float lobe's JSON row has none");
            json_decref(doc);
            test_tmpdir_done(dir);
        }
        printf("sgphong fp32: max delta %.4g, max Delta %.4g; fp16: max delta %.4g (%.3gx), max Delta %.4g (%.3gx)\n",
               r.epicentre.value, r.attenuation.value, r.fp16.epicentre.value, r.fp16.ratio_rel,
               r.fp16.attenuation.value, r.fp16.ratio_abs);
    }
    accuracy_result_free(&r);
    accuracy_result_free(&rf);
    return rc;
}

int main(void)
{
    test_table_by_hand();
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == 0) {
        test_helper_on_device(&s);
        struct accuracy_ctx a;
        if ((rc = accuracy_open(&a, &s, "")) == 0) {
            rc = test_sgphong(&a);
            accuracy_close(&a);
        }
        clsession_close(&s);
        CHECK(rc == 0, "device checks ran (rc %d)", rc);
    }
    return test_summary(rc);
}
