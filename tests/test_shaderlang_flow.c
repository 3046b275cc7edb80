/* test_shaderlang_flow.c - break, continue and switch in GLSL and HLSL models
 * (tests/test_shaderlang_files/flow_glsl.glsl, flow_hlsl.hlsl; flow_return.glsl: a switch
 * whose every way in returns ends the function): each value against the same code
 * written here in C, with C's own break, continue and switch (so the translator's lane masks
 * are checked against real control flow), in double on the host (the model's reference) and in
 * float on the device (the sixteen-lane build the sweeps use); and the errors of a misplaced
 * break, continue or case label, at their line and column (counted by hand in the texts below). */
#include "accuracy.h"
#include "check.h"
#include "models.h"
#include "testutil.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* flow_glsl.glsl in C. */
static double flow_glsl(double c, double n, int m, int part)
{
    double s = 0.0;
    for (int i = 0; i < 8; i++) {
        if (i == 1)
            continue;
        if (s > 2.0 * c)
            break;
        s += c * (double)i;
    }
    double p = 1.0, k = 0.0;
    while (k < 20.0) {
        if (p < 1.0 / n)
            break;
        p *= c;
        k += 1.0;
    }
    double q = 0.0;
    for (int a = 0; a < 4; a++) {
        if (a == 2)
            continue;
        for (int b = 0; b < 4; b++) {
            if (b > a)
                break;
            q += c + (double)b;
        }
    }
    double t = 0.0;
    switch (m) {
    case 0:
        t = 1.0;
        break;
    case 1:
        t = 2.0;
        /* fall through */
    case 2:
        t += 3.0 * c;
        break;
    default:
        t = 7.0;
    }
    double u = 0.0;
    for (int j = 0; j < 5; j++) {
        switch (j) {
        case 1:
            continue;
        case 3:
            u += 10.0;
            break;
        default:
            u += c;
        }
        u += 0.5;
    }
    return part == 0 ? s : part == 1 ? p + k : part == 2 ? q : part == 3 ? t : u;
}

/* flow_hlsl.hlsl in C (saturate = clamp to [0, 1], lerp(a, b, t) = a + (b - a) t). */
static double flow_hlsl(double c, double n, int m)
{
    double s = 0.0, k = 0.0;
    do {
        k += 1.0;
        if (k == 2.0)
            continue;
        if (s * n > 40.0)
            break;
        s += c * k;
    } while (k < 6.0);
    double w = 0.0;
    switch (m) {
    default:
        w = -1.0;
        break;
    case 1:
    case 2:
        w = fmin(fmax(c * 2.0, 0.0), 1.0);
        break;
    case 4:
        w = c + (1.0 - c) * 0.25;
    }
    return s + 100.0 * w;
}

/* flow_return.glsl in C. */
static double flow_return(double c, double n, int m)
{
    double x = c;
    switch (m) {
    case 0:
        return c;
    case 1:
        x = c * c;
        /* fall through */
    default:
        return x + n;
    }
}

static int load(const char *file, const char *label, struct model_spec *spec)
{
    char path[1024], err[600] = "";
    const char *src = getenv("SRC_DIR");
    snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/%s", src ? src : ".", file);
    int rc = usermodel_load_file(path, NULL, err, sizeof err);
    CHECK(rc == 0, "loading %s: %s", file, err);
    if (rc)
        return 0;
    rc = model_spec_parse(label, spec, err, sizeof err);
    CHECK(rc == 0, "parsing %s: %s", label, err);
    return rc == 0 && usermodel_host_ready(usermodel_of(spec));
}

static const double cs[5] = { 0.0, 0.15, 0.5, 0.83, 1.0 }, ns[3] = { 2.0, 9.0, 300.0 };

/* The error of a model text that must fail to load. */
static const char *file_error(const char *text)
{
    static char err[600];
    struct user_model *um = NULL;
    err[0] = '\0';
    if (usermodel_parse_file_text(text, strlen(text), "x.glsl", &um, err, sizeof err) == 0) {
        usermodel_free(um);
        return "(loaded)";
    }
    return err;
}

static void test_errors(void)
{
    /* A GLSL file is checked by glslang first: its refusal, at the line */
    static const struct {
        const char *text, *want;
    } bad_file[] = {
        { "float f(float c, float n)\n{\n    if (c > 0.5)\n        continue;\n    return c;\n}",
          "x.glsl:4: continue statement only allowed in loops" },
        { "float f(float c, float n)\n{\n    switch (c) { default: break; }\n    return c;\n}",
          "x.glsl:3:5: 'switch': condition must be a scalar integer expression" },
    };
    for (size_t i = 0; i < sizeof bad_file / sizeof bad_file[0]; ++i) {
        const char *e = file_error(bad_file[i].text);
        CHECK(strstr(e, bad_file[i].want) != NULL, "file error %zu: '%s', want '%s'", i, e, bad_file[i].want);
    }
    /* the statements of --model NAME=BODY are brdfbench's to check; columns count from BODY's first
       character (e1: "c = c * 2.0; " is 13 characters, break is at 14; e4: the second case at 49) */
    static const struct {
        const char *arg, *want;
    } bad[] = {
        { "e1=c = c * 2.0; break; return c;", "--model e1:1:14: 'break' outside a loop or switch" },
        { "e2=if (c > 0.5) continue; return c;", "--model e2:1:14: 'continue' outside a loop" },
        { "e3=switch (1) { case 1: continue; } return c;", "--model e3:1:22: 'continue' outside a loop" },
        { "e4=int k = 1; switch (k) { case 1: c = 0.0; break; case 1: break; } return c;",
          "--model e4:1:49: case 1 appears twice in one switch" },
        { "e5=switch (c) { default: break; } return c;", "--model e5:1:9: switch on a float: the selector is an int" },
        { "e6=float x = 1.0; switch (2) { case x: break; } return c;", "--model e6:1:34: a case label is a constant integer" },
        { "e7=case 1: return c;", "--model e7:1:1: 'case' outside a switch" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        static char err[600];
        struct user_model *um = NULL;
        err[0] = '\0';
        int rc = usermodel_parse_expression(bad[i].arg, &um, err, sizeof err);
        if (rc == 0)
            usermodel_free(um);
        CHECK(rc != 0 && strstr(err, bad[i].want) != NULL, "error %zu: '%s', want '%s'", i, err, bad[i].want);
    }
}

static void test_host(struct model_spec mg[4][5], struct model_spec mh[6], struct model_spec mr[4])
{
    char err[600];
    for (int m = 0; m < 4; ++m) {
        char label[64];
        snprintf(label, sizeof label, "flowret:m=%d", m);
        CHECK(model_spec_parse(label, &mr[m], err, sizeof err) == 0, "%s: %s", label, err);
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 3; ++j) {
                double got = model_eval_host(&mr[m], cs[i], ns[j]), want = flow_return(cs[i], ns[j], m);
                CHECK(fabs(got - want) <= 1e-12 * fmax(1.0, fabs(want)), "%s at c=%g n=%g: %.17g, C %.17g", label,
                      cs[i], ns[j], got, want);
            }
    }
    for (int m = 0; m < 4; ++m)
        for (int part = 0; part < 5; ++part) {
            char label[64];
            snprintf(label, sizeof label, "flowglsl:m=%d,part=%d", m, part);
            CHECK(model_spec_parse(label, &mg[m][part], err, sizeof err) == 0, "%s: %s", label, err);
            for (int i = 0; i < 5; ++i)
                for (int j = 0; j < 3; ++j) {
                    double got = model_eval_host(&mg[m][part], cs[i], ns[j]), want = flow_glsl(cs[i], ns[j], m, part);
                    CHECK(fabs(got - want) <= 1e-12 * fmax(1.0, fabs(want)), "%s at c=%g n=%g: %.17g, C %.17g", label,
                          cs[i], ns[j], got, want);
                }
        }
    for (int m = 0; m < 6; ++m) {
        char label[64];
        snprintf(label, sizeof label, "flowhlsl:m=%d", m);
        CHECK(model_spec_parse(label, &mh[m], err, sizeof err) == 0, "%s: %s", label, err);
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 3; ++j) {
                double got = model_eval_host(&mh[m], cs[i], ns[j]), want = flow_hlsl(cs[i], ns[j], m);
                CHECK(fabs(got - want) <= 1e-12 * fmax(1.0, fabs(want)), "%s at c=%g n=%g: %.17g, C %.17g", label,
                      cs[i], ns[j], got, want);
            }
    }
}

/* The same values from the sixteen-lane float build, where the lanes' masks really differ (the
   fifteen points go in one launch, so lanes disagree on every lane-dependent break). */
static int test_device(struct accuracy_ctx *a, struct model_spec mg[4][5], struct model_spec mh[6],
                       struct model_spec mr[4])
{
    float c[15], n[15], out[15];
    for (int i = 0; i < 15; ++i) {
        c[i] = (float)cs[i % 5];
        n[i] = (float)ns[i / 5];
    }
    for (int k = 0; k < 4 * 5 + 6 + 4; ++k) {
        const struct model_spec *m = k < 20 ? &mg[k / 5][k % 5] : k < 26 ? &mh[k - 20] : &mr[k - 26];
        int rc = accuracy_probe(a, m, c, n, 15, out);
        CHECK(rc == 0, "%s on the device", m->label);
        if (rc)
            return rc;
        for (int i = 0; i < 15; ++i) {
            double want = k < 20   ? flow_glsl(c[i], n[i], k / 5, k % 5)
                          : k < 26 ? flow_hlsl(c[i], n[i], k - 20)
                                   : flow_return(c[i], n[i], k - 26);
            CHECK(fabs(out[i] - want) <= 1e-5 * fmax(1.0, fabs(want)), "%s at c=%g n=%g on the device: %.9g, C %.9g",
                  m->label, (double)c[i], (double)n[i], (double)out[i], want);
        }
    }
    return 0;
}

int main(void)
{
    test_errors();
    struct model_spec g, h, r;
    static struct model_spec mg[4][5], mh[6], mr[4];
    if (!load("flow_glsl.glsl", "flowglsl", &g) || !load("flow_hlsl.hlsl", "flowhlsl", &h) ||
        !load("flow_return.glsl", "flowret", &r))
        return check_summary();
    test_host(mg, mh, mr);
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == 0) {
        struct accuracy_ctx a;
        if ((rc = accuracy_open(&a, &s, "")) == 0) {
            rc = test_device(&a, mg, mh, mr);
            accuracy_close(&a);
        }
        clsession_close(&s);
        CHECK(rc == 0, "device checks ran (rc %d)", rc);
    }
    return test_summary(rc);
}
