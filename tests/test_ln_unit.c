/* test_ln_unit.c - the device's ln u of the sweep's reference lobe (brdf_ln_unit in
 * kernels/brdf_models.h, written out because PoCL's vector log is an out-of-line call) against
 * the C library's double log. Every 61st float from 2^-24 to 1 (the u = 1 - s it is given),
 * both ends of the reduction interval [sqrt(1/2), sqrt(2)) around each power of two, and
 * u = 1 (exactly 0) and u = 0 (-inf). The bound, 1 ulp of the float result, is the accuracy
 * of the SLEEF logf_u10 it replaces (PoCL's vector log). */
#include "check.h"
#include "clsession.h"
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A point kernel (cl_run_points16's arguments: c, n, out) that writes brdf_ln_unit(c). */
static const char probe_source[] =
    "__kernel void ln_probe(__global const float *u, __global const float *unused, __global float *out)\n"
    "{\n"
    "    const size_t i = get_global_id(0);\n"
    "    vstore16(brdf_ln_unit(vload16(i, u)), i, out);\n"
    "}\n";

static float float_of(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static uint32_t bits_of(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

int main(void)
{
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc)
        return test_summary(rc);
    cl_program prog = NULL;
    cl_kernel k = NULL;
    static const char *const names[] = { "ln_probe" };
    cl_kernel *const kernels[] = { &k };
    CHECK(clsession_build_kernels(&s, "accuracy.cl", probe_source, "", &prog, 1, names, kernels) == 0,
          "accuracy.cl with the probe builds, and its ln_probe kernel");

    const uint32_t lo = bits_of(0x1p-24f), hi = bits_of(1.0f);
    /* the sampled floats, three around each of the 25 roots 2^ex sqrt(1/2), then 1 and 0 */
    size_t cap = (hi - lo) / 61 + 1 + 3 * 25 + 2, count = 0;
    float *u = malloc(cap * sizeof *u), *n = calloc(cap, sizeof *n), *out = malloc(cap * sizeof *out);
    CHECK(u && n && out, "memory");
    if (k && u && n && out) {
        for (uint32_t b = lo; b <= hi; b += 61)
            u[count++] = float_of(b);
        for (int ex = -24; ex <= 0; ++ex) {   /* the ends of m in [sqrt(1/2), sqrt(2)) */
            float root = ldexpf(0.70710678f, ex);
            u[count++] = nextafterf(root, 0.0f);
            u[count++] = root;
            u[count++] = nextafterf(root, 1.0f);
        }
        u[count++] = 1.0f;
        u[count++] = 0.0f;
        CHECK(count <= cap, "%zu values in room for %zu", count, cap);
        CHECK(cl_run_points16(&s, k, 0, u, n, count, out) == 0, "ln_probe runs on %zu values", count);

        double worst = 0, worst_u = 0;
        long beyond = 0;
        for (size_t i = 0; i < count; ++i) {
            if (u[i] == 0.0f || u[i] == 1.0f || u[i] < 0x1p-24f)
                continue;
            double ref = log((double)u[i]);
            double ulp = ldexp(1.0, ilogb((float)ref) - 23);   /* of the float nearest ref */
            double err = fabs((double)out[i] - ref) / ulp;
            if (!(err <= 1.0))
                ++beyond;
            if (!(err <= worst)) {
                worst = err;
                worst_u = u[i];
            }
        }
        CHECK(beyond == 0, "ln u within 1 ulp of the double log for every u: %ld beyond, worst %.3f ulp at u = %.9g",
              beyond, worst, worst_u);
        printf("largest error %.3f ulp at u = %.9g over %zu values\n", worst, worst_u, count);
        CHECK(out[count - 2] == 0.0f, "ln 1 = 0 exactly (got %g)", out[count - 2]);
        CHECK(isinf(out[count - 1]) && out[count - 1] < 0, "ln 0 = -inf (got %g)", out[count - 1]);
    }
    free(u);
    free(n);
    free(out);
    clsession_release_kernels(&prog, 1, kernels);
    clsession_close(&s);
    return test_summary(0);
}
