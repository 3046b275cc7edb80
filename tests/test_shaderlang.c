/* test_shaderlang.c - user models written as GLSL or HLSL (host/core/shader/shaderlang.c), through
 * the user-model parser and their double reference on the host; no device needed.
 *
 * Expected values are each formula written a second time here in C (the shader functions by
 * their GLSL/HLSL definitions: saturate = clamp to [0, 1], lerp = mix = x + (y - x) a,
 * reflect(I, N) = I - 2 dot(N, I) N, step, smoothstep as in the GLSL specification), or a
 * built-in model with the same formula (lyon:k=2 is (1 - n (1 - c) / 4)^4, zeroed past its root),
 * or the same lobe written in the OpenCL C form; error positions are counted by hand in the
 * texts below. */
#include "check.h"
#include "hostjit.h"
#include "models.h"
#include "shaderlang.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int register_expr(const char *arg, struct model_spec *spec)
{
    struct user_model *um = NULL;
    char err[600] = "";
    int rc = usermodel_parse_expression(arg, &um, err, sizeof err);
    if (rc == 0)
        rc = usermodel_register(um, err, sizeof err);
    CHECK(rc == 0, "registering %s: %s", arg, err);
    if (rc)
        return 0;
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)(strchr(arg, '=') - arg), arg);
    rc = model_spec_parse(name, spec, err, sizeof err);
    CHECK(rc == 0, "parsing %s: %s", name, err);
    return rc == 0 && usermodel_host_ready(usermodel_of(spec));
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

/* The error of a --model text, or of a file text, that must fail. */
static const char *expr_error(const char *arg)
{
    static char err[600];
    struct user_model *um = NULL;
    err[0] = '\0';
    int rc = usermodel_parse_expression(arg, &um, err, sizeof err);
    if (rc == 0) {
        usermodel_free(um);
        snprintf(err, sizeof err, "(accepted)");
    }
    return err;
}

static double issue_lobe(double c, double n)
{
    double t = 1 - 0.25 * n * (1 - c);
    t = t > 0 ? t : 0;
    return t * t * t * t;
}

struct feature {
    const char *arg;
    double (*expect)(double c, double n);
};

static double f_saturate(double c, double n) { (void)n; double x = 1.5 * c; return x < 0 ? 0 : x > 1 ? 1 : x; }
static double f_lerp(double c, double n) { (void)n; return c + (1.0 - c) * 0.25; }
static double f_mad(double c, double n) { return c * n + 1.0; }
static double f_rsqrt(double c, double n) { (void)n; return 1.0 / sqrt(c + 1.0) + 1.0 / sqrt(c + 2.0); }
static double f_clamp(double c, double n) { double x = n * (c - 0.9); return x < 0 ? 0 : x > 1 ? 1 : x; }
static double f_step(double c, double n) { (void)n; return c < 0.5 ? 0.0 : 1.0; }
static double f_smooth(double c, double n)
{
    (void)n;
    double t = (c - 0.2) / 0.6;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}
static double f_exp2(double c, double n) { return exp2(n * (c - 1.0)); }
static double f_pow(double c, double n) { return pow(c, n); }
static double f_piecewise(double c, double n) { (void)n; return c < 0.5 ? 0.0 : c < 0.75 ? c : 2.0 * c; }
static double f_ternary(double c, double n) { (void)n; return c > 0.5 ? c : 0.5; }
static double f_casts(double c, double n) { (void)n; return c + 0.5; }
static double f_suffix(double c, double n) { (void)n; return 0.5 * c + 0.25; }
static double f_intdiv(double c, double n) { (void)n; return c + 1.0; }
static double f_swizzle(double c, double n) { return 2.0 * c + n; }
static double f_compound(double c, double n) { (void)n; double t = c; t += 1.0; t *= 2.0; t -= c; t /= 2.0; return t; }
static double f_loop(double c, double n) { (void)n; double b = c * c; b *= b; return b * b; }
static double f_cross(double c, double n) { (void)n; return c; }
static double f_dot3(double c, double n) { (void)n; return 3.0 * c * c; }
static double f_length(double c, double n) { (void)n; return sqrt(c * c + 1.0 + 4.0); }
static double f_normalize(double c, double n) { (void)n; double l = sqrt(c * c + 1.0 + 4.0); return c / l; }
static double f_min_max(double c, double n) { return fmin(fmax(c, 0.25), 0.75) * n; }
static double f_mix(double c, double n) { (void)n; return 0.0 + (c - 0.0) * c; }
static double f_bool(double c, double n) { return (c > 0.3 && !(c > 0.8)) || n > 100 ? 1.0 : 0.0; }
static double f_frac(double c, double n) { double x = c * n; return x - floor(x); }

static double f_brace(double c, double n) { (void)n; return c * 2.0 + 1.0; }
static double f_int_of_float(double c, double n) { (void)n; return trunc(c * 10.0) / 10.0; }
static double f_faceforward(double c, double n) { (void)n; return c - 0.5 < 0 ? c + 1.0 : -(c + 1.0); }

static double f_arr_const(double c, double n) { (void)n; return 0.5 * c + 0.25 * c + 0.125 * c; }
static double f_arr_runtime(double c, double n) { (void)n; return 3.0 * c + 1.0; }
static double f_vec_index(double c, double n) { (void)n; return (c + 3.0) * (c + 3.0); }
static double f_arr_write(double c, double n) { (void)n; return 1.0 + c * (2.0 * c); }
static double f_vec_pow(double c, double n) { (void)n; return pow(c, 2.2) + pow(0.5, 2.2); }

static double f_while_halve(double c, double n)
{
    (void)n;
    double x = c + 0.05;
    while (x > 0.1)
        x = x * 0.5;
    return x;
}
static double f_do_three(double c, double n) { (void)n; return c + c + c; }
static double f_min16(double c, double n) { (void)n; return c * 2.0; }

static const struct feature features[] = {
    { "f1=saturate(c*1.5)", f_saturate },
    { "f2=lerp(c, 1.0, 0.25)", f_lerp },
    { "f3=mad(c, n, 1.0f)", f_mad },
    { "f4=rsqrt(c+1.0) + inversesqrt(c+2.0)", f_rsqrt },
    { "f5=clamp(n*(c-0.9), 0, 1)", f_clamp },
    { "f6=step(0.5, c)", f_step },
    { "f7=smoothstep(0.2, 0.8, c)", f_smooth },
    { "f8=exp2(n*(c-1.0))", f_exp2 },
    { "f9=pow(c, n)", f_pow },
    { "f10=if (c < 0.5) return 0.0; else if (c < 0.75) { return c; } return 2.0*c;", f_piecewise },
    { "f11=c > 0.5 ? c : 0.5", f_ternary },
    { "f12=float(1) * (float)c + float(2)/4", f_casts },
    { "f13=0.5h * c + 0.25f", f_suffix },
    { "f14=1/2 + c + 3/2", f_intdiv },
    { "f15=vec4 v = vec4(c, n, 1.0, 2.0); return v.w * v.x + v.zy.y;", f_swizzle },
    { "f16=float t = c; t += 1.0; t *= 2.0; t -= c; t /= 2.0; return t;", f_compound },
    { "f17=float b = c; for (int i = 0; i < 3; i++) b *= b; return b;", f_loop },
    { "f18=cross(vec3(1,0,0), vec3(0,1,0)).z * c", f_cross },
    { "f19=float3 v = float3(c, c, c); return dot(v, v);", f_dot3 },
    { "f20=length(vec3(c, 1.0, 2.0))", f_length },
    { "f21=normalize(vec3(c, 1.0, 2.0)).x", f_normalize },
    { "f22=min(max(c, 0.25), 0.75) * n", f_min_max },
    { "f23=mix(0.0, c, c)", f_mix },
    { "f24=bool b = c > 0.3 && !(c > 0.8); if (b || n > 100.0) return 1.0; return 0.0;", f_bool },
    { "f25=fract(c*n)", f_frac },
    /* integers chosen by a condition on c become floats (a lane's int would differ from its neighbour's) */
    { "f26=c < 0.5 ? 0 : 1", f_step },
    /* an HLSL brace initialiser (an int among the floats, a trailing comma), int() of a lane's value
       (its integer part), faceforward (N where dot(Nref, I) < 0, else -N) */
    { "f27=float3 v = { c, 1, 2.0, }; return v.x * v.z + v.y;", f_brace },
    { "f28=return float(int(c * 10.0)) / 10.0;", f_int_of_float },
    /* arrays (constant and run-time indices, a GLSL constructor, an HLSL list with a trailing
       comma, a local array written by index) and vectors indexed like arrays */
    { "f30=const float w[3] = float[3](0.5, 0.25, 0.125); float s = 0.0; for (int i = 0; i < 3; i++) s += w[i] * c; "
      "return s;", f_arr_const },
    { "f31=static const float w[] = { 1.0, 2.0, 3.0, }; int k = 2; return w[k] * c + w[0];", f_arr_runtime },
    { "f32=vec3 v = vec3(c, 2.0 * c, 3.0); v[1] = v[0] + v[2]; return v[1] * v.y;", f_vec_index },
    { "f33=float a[4]; int j = 1; a[j] = c; a[j + 1] = 2.0 * c; a[0] += 1.0; return a[0] + a[1] * a[2];",
      f_arr_write },
    { "f34=vec3 x = vec3(c, 0.5, 1.0); return pow(x[0], 2.2) + pow(x[1], 2.2);", f_vec_pow },
    /* while and do loops, lane by lane (each lane stops when its condition fails), an int counter
       stepped by a condition that is the same in every lane */
    { "f35=float x = c + 0.05; while (x > 0.1) x = x * 0.5; return x;", f_while_halve },
    /* HLSL's min16float vectors and precision qualifiers are floats here */
    { "f37=min16float2 v = min16float2(c, 2.0); mediump float t = v.x * v.y; return t;", f_min16 },
    /* HLSL attributes before loops and branches are hints, nothing to the value */
    { "f38=float b = c; [unroll] for (int i = 0; i < 3; i++) b *= b; [branch] if (c < 0.0) b = 0.0; "
      "[unroll(4)] for (int j = 0; j < 0; j++) b = 0.0; return b;", f_loop },
    { "f36=float s = 0.0; int i = 0; do { s += c; i++; } while (i < 3); return s;", f_do_three },
    { "f29=vec3 f = faceforward(vec3(c, 1.0, 0.0), vec3(0.0, 0.0, c - 0.5), vec3(0.0, 0.0, 1.0)); return f.x + f.y;",
      f_faceforward },
    { NULL, NULL } };

int main(void)
{
    struct model_spec m, a, b, d;
    char err[600];

    /* 1. The issue's example, pasted as it is (t is declared by its first assignment). */
    if (register_expr("q4=t = 1 - 0.25*n*(1-c); t = max(t, 0); return t*t*t*t;", &m))
        for (double n = 1; n <= 2000; n *= 1.9)
            for (int i = 0; i <= 100; ++i) {
                double c = i / 100.0;
                CHECK(model_eval_host(&m, c, n) == issue_lobe(c, n), "q4 at c=%g n=%g: %.17g vs %.17g", c, n,
                      model_eval_host(&m, c, n), issue_lobe(c, n));
            }

    /* 2. lyon:k=2 written in GLSL (a file without a header: named after the file, lyon2). */
    if (load("lyon2.glsl", "lyon2", &m)) {
        CHECK(model_spec_parse("lyon:k=2", &a, err, sizeof err) == 0, "%s", err);
        double worst = 0;
        for (double n = 1; n <= 1e5; n *= 1.7)
            for (int i = 0; i <= 400; ++i) {
                double c = 1.0 - pow(i / 400.0, 3.0);
                double v = model_eval_host(&m, c, n), r = model_eval_host(&a, c, n);
                double rel = fabs(v - r) / (r > 1e-300 ? r : 1.0);
                if (!(rel <= worst))
                    worst = rel;
            }
        /* the built-in works in s = 1 - c given; the file computes 1 - c: the last bits only */
        CHECK(worst <= 1e-13, "lyon2.glsl vs lyon:k=2: largest relative difference %g", worst);
        CHECK(strcmp(usermodel_of(&m)->name, "lyon2") == 0, "the headerless file's model name");
    }

    /* 3. The same lobe in OpenCL C, GLSL and HLSL: the same double values, bit for bit. */
    if (load("quartic_cl.cl", "quartic_cl:k=0.3", &a) && load("quartic_glsl.glsl", "quartic_glsl:k=0.3", &b) &&
        load("quartic_hlsl.hlsl", "quartic_hlsl:k=0.3", &d)) {
        int same = 1;
        for (double n = 1; n <= 1e4; n *= 1.3)
            for (int i = 0; i <= 200; ++i) {
                double c = i / 200.0;
                double x = model_eval_host(&a, c, n), y = model_eval_host(&b, c, n), z = model_eval_host(&d, c, n);
                if (x != y || x != z)
                    same = 0;
                double t = 1.0 - 0.3 * n * (1.0 - c);
                t = t > 0 ? t : 0;
                if (x != t * t * t * t)
                    same = 0;
            }
        CHECK(same, "quartic in OpenCL C, GLSL and HLSL differ (or differ from (1 - k n (1 - c))^4)");
    }

    /* 4. Each construct against its definition (parsed, compiled for the host and evaluated
          without registering: a run holds at most 8 user models). */
    for (int f = 0; features[f].arg; ++f) {
        struct user_model *um = NULL;
        int rc = usermodel_parse_expression(features[f].arg, &um, err, sizeof err);
        CHECK(rc == 0, "%s: %s", features[f].arg, err);
        if (rc)
            continue;
        CHECK(usermodel_host_ready(um), "%s does not compile on the host: %s", features[f].arg, um->host_error);
        if (usermodel_host_ready(um)) {
            double worst = 0;
            for (double n = 1.5; n <= 300; n *= 2.3)
                for (int i = 0; i <= 64; ++i) {
                    double c = i / 64.0;
                    double v = hostjit_function(um->host)(c, n, 0, 0), e = features[f].expect(c, n);
                    double diff = fabs(v - e) / (fabs(e) > 1 ? fabs(e) : 1.0);
                    if (!(diff <= worst))
                        worst = diff;
                }
            CHECK(worst <= 4e-16, "%s: largest difference %g", features[f].arg, worst);
        }
        usermodel_free(um);
    }

    /* 5. Errors at the user's line and column. */
    {
        char path[1024];
        const char *src = getenv("SRC_DIR");
        snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/line3.glsl", src ? src : ".");
        int rc = usermodel_load_file(path, NULL, err, sizeof err);
        /* line 3 is "    float t = pow(c, n) * undefined_thing;": the name begins in column 27; a GLSL
           file's error is the reference compiler's (glslang), at the user's line and column */
        CHECK(rc == 2 && strstr(err, "line3.glsl:3:27: 'undefined_thing': undeclared identifier (glslang, the GLSL "
                                     "reference compiler)"), "%d %s", rc, err);
    }
    static const struct { const char *arg, *message; } errors[] = {
        /* "float t = c; return t +;": the ';' after '+' is character 24 */
        { "e1=float t = c; return t +;", "--model e1:1:24: expected a value, found ';'" },
        { "e2=vec3 v = vec3(c); return v;", "--model e2:1:26: the returned value: a vec3 cannot become a float" },
        { "e3=float t = c;", "--model e3:1:13: the model ends without returning a value" },
        { "e4=saturate(c) * q", "--model e4:1:15: use of undeclared identifier 'q'" },
        { "e5=return dot(vec3(c), vec2(c));", "--model e5:1:21: dot of vectors of different sizes" },
        /* "float x = c; while (x > 0.5) { x = x * 0.5; discard; } return x;": discard is character 45
           (break is supported: test_shaderlang_flow.c) */
        { "e6=float x = c; while (x > 0.5) { x = x * 0.5; discard; } return x;", "--model e6:1:45: discard is not supported" },
        { "e7=vec3 v = vec3(c, n); return v.x;", "--model e7:1:10: vec3(...) needs 3 components, these give 2" },
        { NULL, NULL } };
    for (int i = 0; errors[i].arg; ++i) {
        const char *e = expr_error(errors[i].arg);
        CHECK(strstr(e, errors[i].message) != NULL, "%s: got '%s', expected '%s'", errors[i].arg, e, errors[i].message);
    }

    /* 6. A bare expression that only OpenCL C knows is left to OpenCL C, as before. */
    {
        char *out = NULL;
        size_t len = 0;
        CHECK(shaderlang_expression("o", "pow(c, n) * q", "--model o", &out, &len, err, sizeof err) ==
              SHADERLANG_NOT_SHADER, "an unknown name in a bare expression: %s", err);
        CHECK(shaderlang_expression("o", "native_powr(c, n)", "--model o", &out, &len, err, sizeof err) ==
              SHADERLANG_NOT_SHADER, "native_powr: %s", err);
        free(out);
        static const char cl[] = "/* brdfbench-model\n * name: x\n */\nREAL x(REAL c, REAL n) { return c; }\n";
        CHECK(shaderlang_file(cl, strlen(cl), "x.txt", &out, &len, err, sizeof err) == SHADERLANG_NOT_SHADER,
              "a file that uses REAL is OpenCL C");
        free(out);
    }

    /* 7. A file's parameter needs the header's range; the header's count must match. */
    {
        static const char t1[] = "float f(float c, float n, float k) { return k * c; }\n";
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(t1, strlen(t1), "f.glsl", &um, err, sizeof err);
        CHECK(rc == 2 && strstr(err, "f.glsl:1:33: the model's parameter 'k' needs a range"), "%s", err);
        static const char t2[] = "/* brdfbench-model\n * name: g\n * param: k 0 1 0.5\n */\n"
                                 "float g(float c, float n) { return c; }\n";
        rc = usermodel_parse_file_text(t2, strlen(t2), "g.hlsl", &um, err, sizeof err);
        CHECK(rc == 2 && strstr(err, "g.hlsl:5:7: the model's function takes 0 parameters after c and n, the "
                                     "header declares 1"), "%s", err);
        /* #define, helpers, globals and a header's parameter in a GLSL file */
        static const char t3[] = "/* brdfbench-model\n * name: h\n * param: k 0 4 2\n */\n"
                                 "#define HALF 0.5\nconst float TWO = 2.0;\n"
                                 "float sq(float x) { return x * x; }\n"
                                 "float h(float c, float n, float k) { return sq(c) * HALF * TWO * k; }\n";
        rc = usermodel_parse_file_text(t3, strlen(t3), "h.glsl", &um, err, sizeof err);
        CHECK(rc == 0, "h.glsl: %s", err);
        if (rc == 0) {
            CHECK(usermodel_host_ready(um), "h.glsl on the host: %s", um->host_error);
            if (usermodel_host_ready(um))
                CHECK(hostjit_function(um->host)(0.5, 10.0, 3.0, 0) == 0.25 * 0.5 * 2.0 * 3.0, "h:k=3 at c = 0.5: %g",
                      hostjit_function(um->host)(0.5, 10.0, 3.0, 0));
            usermodel_free(um);
        }
    }
    /* 8. BRDF Explorer files: the full BRDF with L = N and V at 2 theta_h (N.H = c), its
          luminance, against the built-in models that write the same BRDFs (and 0 past
          theta_h = 45 degrees, where V is below the horizon, as for the built-ins). */
    /* p0, p1: the model's parameters at the file's defaults (everytype's bool `normalized` is its
       second parameter, an integer in [0, 1], default 1) */
    static const struct { const char *file, *builtin; double p0, p1; } brdfs[] = {
        { "blinnphong.brdf", "blinn", 0, 0 },
        { "ct_ggx.brdf", "ct-ggx:F0=0.5", 0.5, 0 },
        { "everytype.brdf", "blinnn", 2.0, 1.0 },
        /* full BRDFs of (L, V, N) in GLSL and HLSL files, reduced the same way */
        { "blinn_full.glsl", "blinn", 0, 0 },
        { "ct_full.hlsl", "ct-ggx:F0=0.7", 0.7, 0 },
        { NULL, NULL, 0, 0 } };
    for (int i = 0; brdfs[i].file; ++i) {
        char path[1024], text[8192];
        const char *src = getenv("SRC_DIR");
        snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/%s", src ? src : ".", brdfs[i].file);
        FILE *f = fopen(path, "rb");
        size_t len = f ? fread(text, 1, sizeof text, f) : 0;
        if (f)
            fclose(f);
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(text, len, path, &um, err, sizeof err);
        CHECK(rc == 0, "%s: %s", brdfs[i].file, err);
        if (rc)
            continue;
        struct model_spec ref;
        CHECK(model_spec_parse(brdfs[i].builtin, &ref, err, sizeof err) == 0, "%s", err);
        CHECK(um->info.lobe == LOBE_THETA_H, "%s: lobe theta_h", brdfs[i].file);
        if (strcmp(brdfs[i].file, "everytype.brdf") == 0) {
            /* its bool (declared `bool normalized 1`) is a parameter: an integer in [0, 1], default 1 */
            const struct model_param *q = &um->info.params[1];
            CHECK(um->info.nparams == 2 && strcmp(q->name, "normalized") == 0 && q->integer && q->min == 0 &&
                      q->max == 1 && q->def == 1, "everytype.brdf: bool normalized as parameter 2");
        }
        CHECK(usermodel_host_ready(um), "%s on the host: %s", brdfs[i].file, um->host_error);
        if (usermodel_host_ready(um)) {
            double worst = 0;
            for (double n = 2; n <= 1000; n *= 1.6)
                for (int k = 0; k <= 200; ++k) {
                    double c = k / 200.0;
                    double v = hostjit_function(um->host)(c, n, brdfs[i].p0, brdfs[i].p1), r = model_eval_host(&ref, c, n);
                    if (2 * c * c - 1 <= 0)
                        r = 0; /* V below the horizon: the reduced BRDF is 0 (blinn, blinnn are lobes of any c) */
                    double rel = fabs(v - r) / (fabs(r) > 1e-300 ? fabs(r) : 1.0);
                    if (!(rel <= worst))
                        worst = rel;
                }
            CHECK(worst <= 1e-9, "%s against %s: largest relative difference %g", brdfs[i].file, brdfs[i].builtin,
                  worst);
        }
        usermodel_free(um);
    }
    {
        char path[1024];
        const char *src = getenv("SRC_DIR");
        snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/bad_shader.brdf", src ? src : ".");
        int rc = usermodel_load_file(path, NULL, err, sizeof err);
        /* line 8 of the file (the shader's third line): "    return vec3(pow(dot(N, normalize(L + V)), nn));" */
        CHECK(rc == 2 && strstr(err, "bad_shader.brdf:8:47: use of undeclared identifier 'nn'"), "%s", err);
        static const char t[] = "::begin parameters\nfloat n 1 1000\n::end parameters\n::begin shader\n::end shader\n";
        struct user_model *um = NULL;
        rc = usermodel_parse_file_text(t, strlen(t), "t.brdf", &um, err, sizeof err);
        CHECK(rc == 2 && strstr(err, "t.brdf:2: float takes 4 values after its type (NAME MIN MAX DEFAULT), found 3"),
              "%s", err);
    }
    /* 9. Translation is linear in the unrolled size, and bounded: two nested constant loops of
          64 (4096 bodies; each declaration got a fresh C name by rescanning every earlier one,
          and this never finished) translate, and give the sum written in C here; 256 x 256 is
          refused with the bound in the message. */
    {
        static const char *nested = "float lobe(float c, float n) {\n"
                                    "    float s = 0.0;\n"
                                    "    for (int i = 0; i < %d; i++) {\n"
                                    "        for (int j = 0; j < %d; j++) {\n"
                                    "            float t = c * float(i + j) * 0.001;\n"
                                    "            s += t;\n"
                                    "        }\n"
                                    "    }\n"
                                    "    return s;\n"
                                    "}\n";
        char text[600];
        snprintf(text, sizeof text, nested, 64, 64);
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(text, strlen(text), "nested64.glsl", &um, err, sizeof err);
        CHECK(rc == 0, "nested64.glsl: %s", err);
        if (rc == 0) {
            CHECK(usermodel_host_ready(um), "nested64.glsl on the host: %s", um->host_error);
            if (usermodel_host_ready(um)) {
                double c = 0.75, want = 0.0;
                for (int i = 0; i < 64; ++i)
                    for (int j = 0; j < 64; ++j)
                        want += c * (double)(i + j) * 0.001;
                double got = hostjit_function(um->host)(c, 10.0, 0, 0);
                CHECK(fabs(got - want) <= 1e-12 * want, "nested64 at c = 0.75: %.17g, expected %.17g", got, want);
            }
            usermodel_free(um);
        }
        snprintf(text, sizeof text, nested, 256, 256);
        rc = usermodel_parse_file_text(text, strlen(text), "nested256.glsl", &um, err, sizeof err);
        /* the inner loop (line 4, column 9) is where the 8193rd body would be emitted */
        CHECK(rc == 2 && strstr(err, "nested256.glsl:4:9: the loops unroll to more than 8192 iterations in all"),
              "256 x 256 loops: %d %s", rc, err);
    }
    /* 10. The preprocessor (glslang's, host/core/shader/shaderlang_pp.c). */
    if (!shaderlang_has_preprocessor()) {
        printf("built without glslang: the preprocessor's checks are skipped\n");
    } else {
        /* A Filament-style D_GGX chosen by #if, a function-like macro, a header define: GGX's
           D = a^2 / (pi (c^2 (a^2 - 1) + 1)^2) with a = sqrt(2 / (n + 2)), written here in C;
           with -D SPEC_GGX=0 the #else branch, Beckmann's exp((c^2 - 1) / (a^2 c^2)) / (pi a^2 c^4). */
        static const char dggx[] =
            "/* brdfbench-model\n * name: dggx\n * define: SPEC_GGX=1\n */\n"
            "#define PI 3.14159265358979323846\n"
            "#define MEDIUMP_FLT_MAX 65504.0\n"
            "#define saturateMediump(x) min(x, MEDIUMP_FLT_MAX)\n"
            "#if SPEC_GGX\n"
            "float D_GGX(float roughness, float NoH) {\n"
            "    float oneMinusNoHSquared = 1.0 - NoH * NoH;\n"
            "    float a = NoH * roughness;\n"
            "    float k = roughness / (oneMinusNoHSquared + a * a);\n"
            "    float d = k * k * (1.0 / PI);\n"
            "    return saturateMediump(d);\n"
            "}\n"
            "#elif defined(SPEC_BECKMANN) || !SPEC_GGX\n"
            "float D_GGX(float roughness, float NoH) {\n"
            "    float a2 = roughness * roughness, c2 = NoH * NoH;\n"
            "    return exp((c2 - 1.0) / (a2 * c2)) / (PI * a2 * c2 * c2);\n"
            "}\n"
            "#endif\n"
            "float dggx(float c, float n) { return D_GGX(sqrt(2.0 / (n + 2.0)), c); }\n";
        for (int variant = 0; variant < 2; ++variant) {
            if (variant == 1)
                CHECK(shaderlang_define("SPEC_GGX=0", err, sizeof err) == 0, "-D SPEC_GGX=0: %s", err);
            struct user_model *um = NULL;
            int rc = usermodel_parse_file_text(dggx, strlen(dggx), "dggx.glsl", &um, err, sizeof err);
            CHECK(rc == 0, "dggx.glsl (variant %d): %s", variant, err);
            if (rc == 0 && usermodel_host_ready(um)) {
                double worst = 0;
                for (double n = 2; n <= 2000; n *= 1.7)
                    for (int i = 1; i <= 100; ++i) {
                        double c = i / 100.0, a2 = 2.0 / (n + 2.0), c2 = c * c, e;
                        if (variant == 0) {
                            double t = c2 * (a2 - 1.0) + 1.0;
                            e = fmin(a2 / (M_PI * t * t), 65504.0);
                        } else {
                            e = exp((c2 - 1.0) / (a2 * c2)) / (M_PI * a2 * c2 * c2);
                        }
                        double v = hostjit_function(um->host)(c, n, 0, 0);
                        double rel = fabs(v - e) / (e > 1e-300 ? e : 1.0);
                        if (!(rel <= worst))
                            worst = rel;
                    }
                CHECK(worst <= 1e-12, "dggx.glsl variant %d: largest relative difference %g", variant, worst);
            }
            usermodel_free(um);
        }
        shaderlang_clear_defines();
        /* #undef, __LINE__ (line 5 here) and a function-like macro of two arguments */
        static const char m1[] = "#define K 3.0\n#undef K\n#define K 2.0\n#define MUL(a, b) ((a) * (b))\n"
                                 "float m1(float c, float n) { return MUL(c, c) * K + float(__LINE__); }\n";
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(m1, strlen(m1), "m1.hlsl", &um, err, sizeof err);
        CHECK(rc == 0, "m1.hlsl: %s", err);
        if (rc == 0 && usermodel_host_ready(um))
            CHECK(hostjit_function(um->host)(0.5, 10.0, 0, 0) == 0.25 * 2.0 + 5.0, "m1 at c = 0.5: %g",
                  hostjit_function(um->host)(0.5, 10.0, 0, 0));
        usermodel_free(um);
        /* Errors at the user's line and column through the preprocessor (counted by hand). */
        static const struct { const char *text, *path, *message; } pp_errors[] = {
            /* line 4 "    float t = SQ(c) *   q;": q is in column 25, after a macro call */
            { "#define SQ(x) ((x) * (x))\n#if 1\nfloat e(float c, float n) {\n    float t = SQ(c) *   q;\n"
              "    return t;\n}\n#endif\n", "e1.glsl", "e1.glsl:4:25: 'q': undeclared identifier (glslang" },
            /* the same text as a --model-like file of another name: brdfbench's own message, the column
               found again after the preprocessor */
            { "#define SQ(x) ((x) * (x))\n#if 1\nfloat e(float c, float n) {\n    float t = SQ(c) *   q;\n"
              "    return t;\n}\n#endif\n", "e1.shader", "e1.shader:4:25: use of undeclared identifier 'q'" },
            /* #line 50: the next line is line 50, as a C compiler numbers it */
            { "float e(float c, float n) {\n#line 50\n  return c + zz;\n}\n", "e2.txt",
              "e2.txt:50:14: use of undeclared identifier 'zz'" },
            { "float e(float c, float n) {\n#line 50\n  return c + zz;\n}\n", "e2.glsl",
              "e2.glsl:50:14: 'zz': undeclared identifier (glslang" },
            { "#ifndef X\n#error X is needed\n#endif\nfloat e(float c, float n) { return c; }\n", "e3.glsl",
              "e3.glsl:2: #error: X is needed (glslang's preprocessor)" },
            { "#if 1\nfloat e(float c, float n) { return c; }\n", "e4.glsl", "e4.glsl:3: missing #endif" },
            { "float e(float c, float n) { return c; }\n  #include \"other.glsl\"\n", "e5.glsl",
              "e5.glsl:2:3: #include is not accepted: a model file reads no other file" },
            { "/* brdfbench-model\n * name: e\n * define: 9X=1\n */\nfloat e(float c, float n) { return c; }\n",
              "e6.glsl", "e6.glsl:3: define: '9X=1': expected NAME or NAME=VALUE" },
            { NULL, NULL, NULL } };
        for (int i = 0; pp_errors[i].text; ++i) {
            um = NULL;
            rc = usermodel_parse_file_text(pp_errors[i].text, strlen(pp_errors[i].text), pp_errors[i].path, &um, err,
                                           sizeof err);
            CHECK(rc == 2 && strstr(err, pp_errors[i].message), "%s: got %d '%s', expected '%s'", pp_errors[i].path,
                  rc, err, pp_errors[i].message);
            if (rc == 0)
                usermodel_free(um);
        }
    }
    /* 10b. Indices out of range: a constant one at translation (its column), one known only when
           the model runs gives NaN. */
    {
        const char *e = expr_error("ix1=const float w[2] = { 1.0, 2.0 }; return w[2] * c;");
        /* "const float w[2] = { 1.0, 2.0 }; return w[2] * c;": the index 2 is character 43 */
        CHECK(strstr(e, "--model ix1:1:43: index 2 is out of range: 'w' has 2 elements (0 to 1)") != NULL, "%s", e);
        /* "vec3 v = vec3(c); return v[3];": the 3 is character 28 */
        e = expr_error("ix2=vec3 v = vec3(c); return v[3];");
        CHECK(strstr(e, "--model ix2:1:28: index 3 is out of range: a vec3 has 3 elements (0 to 2)") != NULL, "%s", e);
        struct user_model *um = NULL;
        int rc = usermodel_parse_expression("ix3=float w[2] = { 1.0, 2.0 }; int k = 3; return w[k] + c;", &um, err,
                                            sizeof err);
        CHECK(rc == 0, "ix3: %s", err);
        if (rc == 0 && usermodel_host_ready(um))
            CHECK(isnan(hostjit_function(um->host)(0.5, 2.0, 0, 0)), "ix3: w[3] is not NaN");
        usermodel_free(um);
    }

    /* 10c. A loop that has not ended after the unrolled copies leaves NaN in what it wrote. */
    {
        struct user_model *um = NULL;
        int rc = usermodel_parse_expression("wl=float x = c + 1.0; while (x > 0.0) x = x + 1.0; return x;", &um, err,
                                            sizeof err);
        CHECK(rc == 0, "wl: %s", err);
        if (rc == 0 && usermodel_host_ready(um))
            CHECK(isnan(hostjit_function(um->host)(0.5, 2.0, 0, 0)), "wl: an endless loop's value is not NaN");
        usermodel_free(um);
    }

    /* 11. Overloads, out and inout, the user's names. */
    {
        /* A three.js-style BRDF_BlinnPhong (threejs_blinnphong.glsl, written for this test): F_Schlick
           overloaded for float and vec3, G = 1/4, D = (s/2 + 1)/pi c^s, F = 1 for a white specular
           colour; so the model is phongn / 4 ((n + 2)/(2 pi) c^n, docs/definitions.md) at every
           point, and its delta against phongn is 0.75. */
        struct model_spec ph;
        CHECK(model_spec_parse("phongn", &ph, err, sizeof err) == 0, "%s", err);
        if (load("threejs_blinnphong.glsl", "threeblinn", &m)) {
            double worst = 0;
            for (double n = 2; n <= 1000; n *= 1.6)
                for (int k = 1; k <= 100; ++k) {
                    double c = k / 100.0;
                    double v = model_eval_host(&m, c, n), r = model_eval_host(&ph, c, n);
                    double e = 0.25 * (n * 0.5 + 1.0) / M_PI * pow(c, n);
                    double rel = fabs(v - 0.25 * r) / (r > 1e-300 ? 0.25 * r : 1.0);
                    double rel2 = fabs(v - e) / (e > 1e-300 ? e : 1.0);
                    if (!(rel <= worst))
                        worst = rel;
                    if (!(rel2 <= worst))
                        worst = rel2;
                }
            /* V = 2c H - N makes L + V's z 1 + (2c^2 - 1): a cancellation of about eps / c^2 in N.H,
               which c^n multiplies by n (up to 1000 here) */
            CHECK(worst <= 1e-10, "threejs_blinnphong.glsl against phongn / 4: largest relative difference %g", worst);
        }
        /* out and inout (a swizzle as the argument too), a call as a statement, a void function
           with an early return, a call under if (written back only where the condition holds);
           blinn, brdf, BRDF_x, c and n are the user's names. In C: h = 2c, a = 1 + c + (c > 0.5 ?
           c : 0), v = (c, 2c, 0) then v.x += 1 where c < 0.25; the result h + a n + v.x + v.y. */
        static const char io[] =
            "void split(float x, out float hi, inout float acc) { hi = x * 2.0; acc += x; }\n"
            "void bump(inout vec3 v, float c) { if (c >= 0.25) return; v.x += 1.0; }\n"
            "float blinn(float c, float n) { return c; }\n"
            "float io(float c, float n) {\n"
            "    float h; float a = 1.0; float BRDF_x = blinn(c, n); float brdf = 0.0;\n"
            "    split(c, h, a);\n"
            "    if (c > 0.5) split(BRDF_x, h, a);\n"
            "    vec3 v = vec3(0.0);\n"
            "    split(c, v.y, v.x);\n"
            "    bump(v, c);\n"
            "    return h + a * n + v.x + v.y + brdf;\n"
            "}\n";
        struct user_model *um = NULL;
        int rc = usermodel_parse_file_text(io, strlen(io), "io.glsl", &um, err, sizeof err);
        CHECK(rc == 0, "io.glsl: %s", err);
        if (rc == 0 && usermodel_host_ready(um)) {
            double worst = 0;
            for (double n = 1; n <= 100; n *= 3)
                for (int k = 0; k <= 64; ++k) {
                    double c = k / 64.0;
                    double h = 2 * c, a = 1 + c + (c > 0.5 ? c : 0), vx = c + (c < 0.25 ? 1 : 0), vy = 2 * c;
                    double e = h + a * n + vx + vy, v = hostjit_function(um->host)(c, n, 0, 0);
                    if (!(fabs(v - e) <= worst))
                        worst = fabs(v - e);
                }
            CHECK(worst <= 1e-13, "io.glsl: largest difference %g", worst);
        }
        usermodel_free(um);
        /* overloads by argument types: f(1) takes f(float) (an int converts), f(vec2(..)) the vec2
           one, f(c, c) the two-float one: c + (c + 2c) + c c */
        static const char ov[] = "float f(float x) { return x; }\nfloat f(vec2 v) { return v.x + v.y; }\n"
                                 "float f(float x, float y) { return x * y; }\n"
                                 "float ov(float c, float n) { return f(1) * c + f(vec2(c, 2.0 * c)) + f(c, c); }\n";
        um = NULL;
        rc = usermodel_parse_file_text(ov, strlen(ov), "ov.glsl", &um, err, sizeof err);
        CHECK(rc == 0, "ov.glsl: %s", err);
        if (rc == 0 && usermodel_host_ready(um))
            CHECK(hostjit_function(um->host)(0.5, 3.0, 0, 0) == 0.5 + 1.5 + 0.25, "ov at c = 0.5: %g",
                  hostjit_function(um->host)(0.5, 3.0, 0, 0));
        usermodel_free(um);
        static const struct { const char *text, *path, *message; } ov_errors[] = {
            /* both overloads need one conversion (column 40: the call) */
            { "float g(float x, vec2 y) { return x; }\nfloat g(vec2 x, float y) { return y; }\n"
              "float e(float c, float n) { return g(1.0, 1.0); }\n", "o1.shader",
              "o1.shader:3:36: the call of g is ambiguous" },
            { "float g(float x) { return x; }\nfloat g(float y) { return y; }\n"
              "float e(float c, float n) { return g(c); }\n", "o2.glsl",
              "o2.glsl:2:7: function 'g' is defined twice with the same parameter types (line 1)" },
            { "float g(float x) { return x; }\nfloat g(vec2 y) { return y.x; }\n"
              "float e(float c, float n) { return g(vec3(c)); }\n", "o3.shader",
              "o3.shader:3:36: no function g takes (vec3)" },
            { "void s(out float x) { x = 1.0; }\nfloat e(float c, float n) { s(c + 1.0); return c; }\n", "o4.shader",
              "o4.shader:2:33: an out or inout argument must be a variable or its components" },
            /* the same in a .glsl file: glslang's message (GLSL has no ambiguity rule of this kind) */
            { "float g(float x, vec2 y) { return x; }\nfloat g(vec2 x, float y) { return y; }\n"
              "float e(float c, float n) { return g(1.0, 1.0); }\n", "o5.glsl",
              "o5.glsl:3:36: 'g': no matching overloaded function found (glslang, the GLSL reference compiler)" },
            { NULL, NULL, NULL } };
        for (int i = 0; ov_errors[i].text; ++i) {
            um = NULL;
            rc = usermodel_parse_file_text(ov_errors[i].text, strlen(ov_errors[i].text), ov_errors[i].path, &um, err,
                                           sizeof err);
            CHECK(rc == 2 && strstr(err, ov_errors[i].message), "%s: got %d '%s', expected '%s'", ov_errors[i].path,
                  rc, err, ov_errors[i].message);
            if (rc == 0)
                usermodel_free(um);
        }
    }
    /* 12. Structs: fields of numbers, vectors and structs; locals (zeroed when not set), a
           constructor, a brace initialiser, parameters (in and inout), a returned struct (with an
           early return), fields and their components assigned. In C: k = (c, (0, 2c)); m = (ma,
           (c, 3)) with ma = 1 where c > 0.5 else 0.25; o.inner = m with b.x + 1; q.a = 2c. */
    {
        static const char st[] =
            "struct Ctx { float a; vec2 b; };\n"
            "struct Outer { Ctx inner; float w; };\n"
            "void init(inout Ctx k, float c) { k.a = c; k.b.y = 2.0 * c; }\n"
            "Ctx make(float c) { Ctx k = Ctx(1.0, vec2(c, 3.0)); if (c > 0.5) return k; k.a = 0.25; return k; }\n"
            "float sum(Ctx k) { return k.a + k.b.x + k.b.y; }\n"
            "float st(float c, float n) {\n"
            "    Ctx k;\n"
            "    init(k, c);\n"
            "    Ctx m = make(c);\n"
            "    Outer o = { m, n };\n"
            "    o.inner.b.x += 1.0;\n"
            "    Ctx q = k; q.a *= 2.0;\n"
            "    return sum(k) + sum(o.inner) * o.w + q.a;\n"
            "}\n";
        for (int lang = 0; lang < 2; ++lang) {
            /* as GLSL (checked by glslang too) and under a name only brdfbench reads */
            const char *path = lang ? "st.shader" : "st.glsl";
            struct user_model *um = NULL;
            int rc = usermodel_parse_file_text(st, strlen(st), path, &um, err, sizeof err);
            CHECK(rc == 0, "%s: %s", path, err);
            if (rc == 0 && usermodel_host_ready(um)) {
                double worst = 0;
                for (double n = 1; n <= 100; n *= 3)
                    for (int k = 0; k <= 64; ++k) {
                        double c = k / 64.0, ma = c > 0.5 ? 1.0 : 0.25;
                        double e = 3 * c + (ma + c + 1 + 3) * n + 2 * c, v = hostjit_function(um->host)(c, n, 0, 0);
                        if (!(fabs(v - e) <= worst))
                            worst = fabs(v - e);
                    }
                CHECK(worst <= 1e-12, "%s: largest difference %g", path, worst);
            }
            usermodel_free(um);
        }
        /* columns counted by hand: "float e(float c, float n) { " is 28 characters */
        static const struct { const char *text, *path, *message; } st_errors[] = {
            { "struct P { float a; };\nfloat e(float c, float n) { P p; return p.z; }\n", "s1.shader",
              "s1.shader:2:43: P has no field 'z'" },
            { "struct P { float a; vec2 b; };\nfloat e(float c, float n) { P p = P(c); return p.a; }\n", "s2.shader",
              "s2.shader:2:35: P has 2 fields, 1 value given" },
            { "struct P { float a; };\nfloat e(float c, float n) { P p; return p + c; }\n", "s3.shader",
              "s3.shader:2:43: '+' needs numbers, not P and float" },
            { NULL, NULL, NULL } };
        for (int i = 0; st_errors[i].text; ++i) {
            struct user_model *um = NULL;
            int rc = usermodel_parse_file_text(st_errors[i].text, strlen(st_errors[i].text), st_errors[i].path, &um,
                                               err, sizeof err);
            CHECK(rc == 2 && strstr(err, st_errors[i].message), "%s: got %d '%s', expected '%s'", st_errors[i].path,
                  rc, err, st_errors[i].message);
            if (rc == 0)
                usermodel_free(um);
        }
    }
    /* 13. Matrices: GLSL's mat3 (columns; *, transpose, m[i] a column, a diagonal constructor) and
           HLSL's float3x3 (rows; mul, component-wise *, m[i] a row, a brace list), against the
           same products written in C with A[r][c]. */
    {
        static const char glsl[] =
            "float mt(float c, float n) {\n"
            "    mat3 m = mat3(1.0, 2.0, 3.0,  4.0, 5.0, 6.0,  7.0, 8.0, c);\n"
            "    vec3 v = vec3(c, 1.0, 2.0);\n"
            "    vec3 w = m * v;\n"
            "    vec3 u = v * m;\n"
            "    mat3 p = m * transpose(m);\n"
            "    mat2 d = mat2(2.0);\n"
            "    m[1] = vec3(c);\n"
            "    return w.x + u.y + p[2][1] + d[1][1] + m[1].z + (2.0 * m)[0][2];\n"
            "}\n";
        static const char hlsl[] =
            "float mh(float c, float n) {\n"
            "    float3x3 m = { 1, 2, 3,  4, 5, 6,  7, 8, c };\n"
            "    float3 v = float3(c, 1, 2);\n"
            "    float3 w = mul(m, v);\n"
            "    float3 u = mul(v, m);\n"
            "    float3x3 p = mul(m, transpose(m));\n"
            "    float3x3 h = m * m;\n"
            "    return w.x + u.y + p[2][1] + h[2][2] + m[0].y + mul(v, v);\n"
            "}\n";
        for (int lang = 0; lang < 2; ++lang) {
            const char *text = lang ? hlsl : glsl, *path = lang ? "mh.hlsl" : "mt.glsl";
            struct user_model *um = NULL;
            int rc = usermodel_parse_file_text(text, strlen(text), path, &um, err, sizeof err);
            CHECK(rc == 0, "%s: %s", path, err);
            if (rc == 0 && usermodel_host_ready(um)) {
                double worst = 0;
                for (int k = 0; k <= 32; ++k) {
                    double c = k / 32.0, A[3][3], e;
                    double v[3] = { c, 1, 2 };
                    if (!lang) {
                        /* column-major: column j is (A[0][j], A[1][j], A[2][j]) */
                        double cols[3][3] = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, c } };
                        for (int r = 0; r < 3; ++r)
                            for (int j = 0; j < 3; ++j)
                                A[r][j] = cols[j][r];
                        double wx = A[0][0] * v[0] + A[0][1] * v[1] + A[0][2] * v[2];
                        double uy = v[0] * A[0][1] + v[1] * A[1][1] + v[2] * A[2][1];
                        /* p = A A^T; p[2][1] is column 2, row 1: P(1, 2) */
                        double p21 = A[1][0] * A[2][0] + A[1][1] * A[2][1] + A[1][2] * A[2][2];
                        e = wx + uy + p21 + 2.0 + c + 2.0 * A[2][0];
                    } else {
                        double rows[3][3] = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, c } };
                        memcpy(A, rows, sizeof A);
                        double wx = A[0][0] * v[0] + A[0][1] * v[1] + A[0][2] * v[2];
                        double uy = v[0] * A[0][1] + v[1] * A[1][1] + v[2] * A[2][1];
                        /* p = A A^T; p[2][1] is row 2, column 1: P(2, 1) */
                        double p21 = A[2][0] * A[1][0] + A[2][1] * A[1][1] + A[2][2] * A[1][2];
                        e = wx + uy + p21 + c * c + 2.0 + (c * c + 1.0 + 4.0);
                    }
                    double got = hostjit_function(um->host)(c, 10.0, 0, 0);
                    if (!(fabs(got - e) <= worst))
                        worst = fabs(got - e);
                }
                CHECK(worst <= 1e-12, "%s: largest difference %g", path, worst);
            }
            usermodel_free(um);
        }
    }
    usermodel_clear_all();
    return check_summary();
}
