/* test_shaderlang_arrays.c - array parameters of shader-language functions (GLSL's
 * `const in vec3 v[4]`, as engine files declare them): tests/test_shaderlang_files/array_param.glsl,
 * written for this test, evaluated through the model's double evaluation (model_eval_host: the
 * translated text compiled on the host) at five points against the same functions written a
 * second time here in C. The array is passed by value: the callee's write to its copy does not
 * reach the caller's array. */
#include "check.h"
#include "models.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* weightedSum: s = sum_i w[i] p[i] x, returned as s.x + 2 s.y + 3 s.z; scratch: 10 w0 + w1 + w2
   (its own copy); the model adds the caller's w[0] = c, unchanged by scratch. */
static double arrparam_c(double c, double n)
{
    double w[3] = { c, n, 1.0 }, p[3][3] = { { 1, 0, 0 }, { 0, c, 0 }, { 0.5, 0.25, n } }, s[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            s[k] += w[i] * p[i][k] * 2.0;
    double a = s[0] + 2.0 * s[1] + 3.0 * s[2];
    double b = 10.0 * w[0] + w[1] + w[2];
    return a + b + w[0];
}

int main(void)
{
    char path[1024], err[600] = "";
    const char *src = getenv("SRC_DIR");
    snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/array_param.glsl", src ? src : ".");
    int rc = usermodel_load_file(path, NULL, err, sizeof err);
    CHECK(rc == 0, "loading array_param.glsl: %s", err);
    struct model_spec spec;
    if (rc == 0) {
        rc = model_spec_parse("arrparam", &spec, err, sizeof err);
        CHECK(rc == 0, "parsing arrparam: %s", err);
    }
    if (rc == 0 && usermodel_host_ready(usermodel_of(&spec))) {
        static const double pts[5][2] = { { 0.999, 10 }, { 0.95, 50 }, { 0.8, 3 }, { 0.5, 1.5 }, { 0.0, 200 } };
        for (int p = 0; p < 5; ++p) {
            double got = model_eval_host(&spec, pts[p][0], pts[p][1]), want = arrparam_c(pts[p][0], pts[p][1]);
            CHECK(fabs(got - want) <= 1e-12 * fabs(want), "arrparam at c = %g, n = %g: %.15g, C %.15g", pts[p][0],
                  pts[p][1], got, want);
            printf("arrparam(%g, %g) = %.12g (C %.12g)\n", pts[p][0], pts[p][1], got, want);
        }
    } else {
        CHECK(0, "arrparam has no host evaluation");
    }
    return check_summary();
}
