/* test_usermodel_host.c - a user model's double reference on the host (host/core/hostjit.c),
 * the registry's interface for run-time models, and the per-session program cache
 * (host/core/programs.c).
 *
 * Host part (no device): a user model's model_eval_host is its text compiled for the host
 * in double, so it gives values without any OpenCL session; each expected value is the
 * formula written a second time in this file (or a built-in model with the same formula),
 * and OpenCL C's built-in functions follow their definitions in the OpenCL C specification
 * (written out here independently of the prelude).
 * Device part: one build of a kernel file per user model per session, whichever engine asks,
 * released with the session. */
#include "accuracy.h"
#include "check.h"
#include "clsession.h"
#include "exitcodes.h"
#include "field.h"
#include "hemisphere.h"
#include "hostjit.h"
#include "models.h"
#include "programs.h"
#include "testutil.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const struct model_spec *register_expr(const char *arg, struct model_spec *spec)
{
    struct user_model *um = NULL;
    char err[512] = "";
    int rc = usermodel_parse_expression(arg, &um, err, sizeof err);
    if (rc == 0)
        rc = usermodel_register(um, err, sizeof err);
    CHECK(rc == 0, "registering %s: %s", arg, err);
    if (rc)
        return NULL;
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)(strchr(arg, '=') - arg), arg);
    rc = model_spec_parse(name, spec, err, sizeof err);
    CHECK(rc == 0, "parsing %s: %s", name, err);
    return rc ? NULL : spec;
}

/* The docs' example: the cosine-quadratic with k = 0.45 n, zeroed past its root. */
static double sq_closed_form(double c, double n)
{
    double b = 0.45 * n * (c - 1.0) + 1.0;
    b = b > 0 ? b : 0.0;
    return b * b;
}

static void host_checks(void)
{
    struct model_spec sq, quad, ocl, np;
    char err[512];

    /* 1. Values without a device: the formula itself, and the built-in quad:a=0.45,b=0. */
    if (register_expr("sq=fmax(0.45*n*(c-1)+1,0)*fmax(0.45*n*(c-1)+1,0)", &sq)) {
        CHECK(model_spec_parse("quad:a=0.45,b=0", &quad, err, sizeof err) == 0, "%s", err);
        double worst = 0, worst_quad = 0;
        int count = 0;
        for (double n = 1; n <= 1e6; n *= 3.7)
            for (int i = 0; i <= 200; ++i) {
                double c = i / 200.0;
                double v = model_eval_host(&sq, c, n), e = sq_closed_form(c, n);
                double q = model_eval_host(&quad, c, n);
                double d = fabs(v - e) / (e > 1e-300 ? e : 1.0), dq = fabs(v - q) / (q > 1e-300 ? q : 1.0);
                if (!(d <= worst)) worst = d;
                if (!(dq <= worst_quad)) worst_quad = dq;
                ++count;
            }
        /* The same operations in double: equal but for the last bit at most. */
        CHECK(worst <= 4e-16, "sq on the host vs its closed form: largest relative difference %g", worst);
        CHECK(worst_quad <= 4e-16, "sq vs quad:a=0.45,b=0: largest relative difference %g", worst_quad);
        CHECK(count > 2000, "points %d", count);
        /* c < 0 is clamped to 0 as for every model (brdf_eval). */
        CHECK(model_eval_host(&sq, -0.5, 3.0) == sq_closed_form(0.0, 3.0), "negative cosine");
        CHECK(usermodel_host_ready(usermodel_of(&sq)), "sq compiles on the host");
    }

    /* 2. OpenCL C's scalar built-ins, by their definitions (OpenCL C 1.2, section 6.12). */
    if (register_expr("ocl=clamp(c, 0.25, 0.75) + 2*step(0.5, c) + 4*mix(1.0, 3.0, c) + 8*sign(c - 0.5)"
                      " + 16*pown(c, 3) + 32*rootn(c, 3) + 64*select(1.0, 2.0, (long)(c > 0.6))"
                      " + 128*rsqrt(n) + 256*smoothstep(0.2, 0.8, c) + 512*mad(c, n, 1.0)"
                      " + 1024*max(c, 0.3) + 2048*min(c, 0.3) + 4096*degrees(c) + 8192*powr(c, n)", &ocl)) {
        for (int i = 0; i <= 10; ++i) {
            double c = i / 10.0, n = 7.5;
            double cl = c < 0.25 ? 0.25 : c > 0.75 ? 0.75 : c;
            double st = c < 0.5 ? 0.0 : 1.0;
            double mx = 1.0 + 2.0 * c;
            double sg = c > 0.5 ? 1.0 : c < 0.5 ? -1.0 : 0.0;
            double t = (c - 0.2) / 0.6;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double e = cl + 2 * st + 4 * mx + 8 * sg + 16 * c * c * c + 32 * cbrt(c) +
                       64 * (c > 0.6 ? 2.0 : 1.0) + 128 / sqrt(n) + 256 * t * t * (3 - 2 * t) +
                       512 * (c * n + 1) + 1024 * (c > 0.3 ? c : 0.3) + 2048 * (c < 0.3 ? c : 0.3) +
                       4096 * c * 180 / 3.14159265358979323846 + 8192 * pow(c, n);
            CHECK_NEAR(model_eval_host(&ocl, c, n), e, 1e-12 * fabs(e), "OpenCL built-ins at c");
        }
    }

    /* 3. native_* in the reference: its exact counterpart (docs/user-models.md). */
    if (register_expr("np=native_powr(c, n) + half_exp(-n*c)", &np))
        for (int i = 1; i <= 10; ++i) {
            double c = i / 10.0, n = 13.0;
            CHECK_NEAR(model_eval_host(&np, c, n), pow(c, n) + exp(-n * c), 1e-15, "native_powr + half_exp");
        }

    /* 4. A model file with two parameters. */
    {
        static const char text[] = "/* brdfbench-model\n * name: twop\n * param: a 0 2 0.5\n * param: b -1 1 0\n */\n"
                                   "REAL helper(REAL x) { return x * x; }\n"
                                   "REAL twop(REAL c, REAL n, RSCALAR a, RSCALAR b) {\n"
                                   "    return helper(fmax((a * n + b) * (c - 1.0) + 1.0, 0.0));\n}\n";
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(text, strlen(text), "twop.cl", &um, err, sizeof err);
        if (rc == 0)
            rc = usermodel_register(um, err, sizeof err);
        CHECK(rc == 0, "twop.cl: %s", err);
        struct model_spec tw;
        if (rc == 0 && model_spec_parse("twop:a=0.7,b=0.2", &tw, err, sizeof err) == 0)
            for (int i = 0; i <= 20; ++i) {
                double c = i / 20.0, n = 9.0, k = 0.7 * n + 0.2, b = k * (c - 1) + 1;
                b = b > 0 ? b : 0;
                CHECK_NEAR(model_eval_host(&tw, c, n), b * b, 1e-15, "twop:a=0.7,b=0.2");
            }
    }

    /* 5. A text that is OpenCL C but not C (mul24 is an OpenCL integer built-in): no host
       evaluator, the reason names the function, and without a device no value. */
    struct model_spec m24;
    if (register_expr("m24=pow(c, n) * mul24(1, 1)", &m24)) {
        const struct user_model *um = usermodel_of(&m24);
        CHECK(!usermodel_host_ready(um), "mul24 compiled on the host");
        CHECK(strstr(um->host_error, "mul24") != NULL, "reason: %s", um->host_error);
        CHECK(isnan(model_eval_host(&m24, 0.5, 2.0)), "a value without its device reference");
    }

    /* 6. The registry evaluates run-time models through the runtime they registered. */
    CHECK(models_runtime(sq.info) != NULL && models_runtime(models_find("fq2")) == NULL, "models_runtime");
}

/* The hemisphere sweep of a full user model (Blinn-Phong as BRDF Explorer's files write it, so
 * the built-in blinn is its reference) evaluates the model in double at every grid point (the
 * RMS), at the probe's samples and through the refinement: hundreds of thousands of values. They
 * are computed in its sandbox's child in a few stages, not asked for one by one: a request to
 * the sandbox (hostjit_round_trips) waits for the other process to be scheduled, twice, which on
 * a busy machine made a run of seconds take minutes. Counted: each value taken outside a stage
 * is a request (the P peak ratios at L = V = N, where the model's n is the axis value), and a
 * sandboxed stage asks for one value first (usermodel_isolated: (c, n) = (1, 1), which the
 * model's cache of recent values holds from the first stage, the probe's, on), so P + 1
 * requests; before the stages, one per value: 16 x 16 x 32 x P for the RMS alone. */
static void hemisphere_trips(struct cl_session *s)
{
    static const char text[] = "analytic\n::begin parameters\nfloat n 1 1000 100\n::end parameters\n"
                               "::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)\n{\n"
                               "    vec3 H = normalize(L + V);\n    return vec3(pow(max(0.0, dot(N, H)), n));\n}\n"
                               "::end shader\n";
    struct user_model *um = NULL;
    char err[512] = "";
    int rc = usermodel_parse_file_text(text, sizeof text - 1, "tripbp.brdf", &um, err, sizeof err);
    if (rc == 0)
        rc = usermodel_register(um, err, sizeof err);
    CHECK(rc == 0, "registering tripbp.brdf: %s", err);
    struct model_spec m, ref;
    if (rc || model_spec_parse("tripbp", &m, err, sizeof err) || model_spec_parse("blinn", &ref, err, sizeof err)) {
        CHECK(0, "tripbp or blinn: %s", err);
        return;
    }
    struct hemi_axis axis;
    memset(&axis, 0, sizeof axis);
    CHECK(hemisphere_axis_parse("n", &axis, err, sizeof err) == 0, "--axis n: %s", err);
    axis.count = 2;
    CHECK(hemisphere_axis_check(&axis, NULL, 0, &m, &ref, 2, 300, err, sizeof err) == 0, "the axis: %s", err);
    struct hemi_grid g = { 16, 16, 32 };
    struct hemi_ctx h;
    struct hemi_result r;
    hemisphere_open(&h, s, "");
    unsigned long before = hostjit_round_trips();
    rc = hemisphere_run(&h, &m, &ref, &axis, NULL, 0, &g, &r);
    unsigned long trips = hostjit_round_trips() - before;
    CHECK(rc == 0, "the hemisphere sweep of tripbp against blinn: exit %d", rc);
    CHECK(trips == (unsigned long)axis.count + 1, "requests to the sandbox: %lu (expected P + 1 = %d)", trips,
          axis.count + 1);
    /* the model is blinn written again: its figures are rounding, the double RMS below 1e-12 of
       the peak (the double stage ran and handed its values back) */
    CHECK(rc == 0 && r.p_count == 2 && r.per_p[0].rms < 1e-12 * r.per_p[0].peak && r.per_p[0].peak > 0,
          "tripbp against blinn: RMS %g at peak %g", rc ? NAN : r.per_p[0].rms, rc ? NAN : r.per_p[0].peak);
    if (rc == 0)
        hemisphere_result_free(&r);
    hemisphere_close(&h);

    /* model_eval_host_many: the values of one call are model_eval_host's, in one sandbox stage
       (one request: the stage's first value) */
    struct model_spec sq;
    if (model_spec_parse("sq", &sq, err, sizeof err) == 0) {
        enum { K = 1000 };
        static double c[K], n[K], v[K];
        for (int i = 0; i < K; ++i) {
            c[i] = (i + 0.5) / K;
            n[i] = 2.0 + i % 37;
        }
        before = hostjit_round_trips();
        CHECK(model_eval_host_many(&sq, c, n, K, v) == 0, "model_eval_host_many of sq");
        CHECK(hostjit_round_trips() - before == 1, "model_eval_host_many: %lu requests (expected 1)",
              hostjit_round_trips() - before);
        double worst = 0;
        for (int i = 0; i < K; ++i)
            worst = fmax(worst, fabs(v[i] - sq_closed_form(c[i], n[i])));
        CHECK(worst <= 1e-15, "model_eval_host_many of sq against its formula: %g", worst);
    }
}

static void device_checks(struct cl_session *s)
{
    struct model_spec sq, fq2, m24;
    char err[256];
    CHECK(model_spec_parse("sq", &sq, err, sizeof err) == 0, "%s", err);
    CHECK(model_spec_parse("fq2", &fq2, err, sizeof err) == 0, "%s", err);
    CHECK(model_spec_parse("m24", &m24, err, sizeof err) == 0, "%s", err);

    /* Two sweep contexts and a field context ask for the user model: accuracy.cl is built
       once with it, field.cl once; a built-in model adds no build to the cache. */
    struct accuracy_ctx a1, a2;
    struct field_ctx f;
    CHECK(accuracy_open(&a1, s, "") == 0, "accuracy_open 1");
    CHECK(accuracy_open(&a2, s, "") == 0, "accuracy_open 2");
    CHECK(field_open(&f, s, "") == 0, "field_open");
    CHECK(programs_build_count(s) == 0, "builds before any user model: %d", programs_build_count(s));
    CHECK(accuracy_prepare(&a1, &fq2) == 0, "prepare fq2");
    CHECK(programs_build_count(s) == 0, "a built-in model made a build: %d", programs_build_count(s));
    CHECK(accuracy_prepare(&a1, &sq) == 0, "prepare sq in context 1");
    CHECK(accuracy_prepare(&a2, &sq) == 0, "prepare sq in context 2");
    CHECK(programs_build_count(s) == 1, "accuracy.cl with sq: %d builds (expected 1)", programs_build_count(s));
    cl_kernel k1 = NULL, k2 = NULL;
    CHECK(programs_kernel(s, "field.cl", "", &sq, "field_grid", f.kernel, &k1) == 0, "field kernel");
    CHECK(programs_kernel(s, "field.cl", "", &sq, "field_grid", f.kernel, &k2) == 0, "field kernel again");
    CHECK(k1 && k1 == k2 && k1 != f.kernel, "the field kernel of sq is cached");
    CHECK(programs_kernel(s, "field.cl", "", &fq2, "field_grid", f.kernel, &k1) == 0 && k1 == f.kernel,
          "a built-in model gets the shared kernel");
    CHECK(programs_build_count(s) == 2, "after field.cl: %d builds (expected 2)", programs_build_count(s));

    /* The fallback: a model that is not C gets its double reference from the device. */
    if (s->has_fp64) {
        CHECK(programs_host(s, &m24) == 0, "the device reference of m24");
        CHECK_NEAR(model_eval_host(&m24, 0.5, 3.0), 0.125, 1e-15, "m24 = c^n at c = 0.5, n = 3 on the device");
    }
    accuracy_close(&a1);
    accuracy_close(&a2);
    field_close(&f);
    hemisphere_trips(s);
    clsession_close(s);
    CHECK(programs_build_count(s) == 0, "the session's builds are released with it: %d", programs_build_count(s));
}

int main(void)
{
    host_checks();
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == 0)
        device_checks(&s);
    usermodel_clear_all();
    return test_summary(rc);
}
