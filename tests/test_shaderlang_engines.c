/* test_shaderlang_engines.c - specular functions written in the styles of engine shader
 * libraries (tests/test_shaderlang_files/style_*.{hlsl,glsl}, written for this test: an HLSL
 * BRDF library with PI macros, Pow5, rcp, saturate and float3 swizzles; GLSL light functions with
 * mix and an inout accumulator; a GLSL PBR file with function-like macros, #ifdef and a
 * square() helper; a tutorial's fragment shader of functions of vectors, mix of vec3, a const
 * PI), each run as written with a one-line wrapper that maps the sweep's n to a
 * roughness, evaluated through the model's own evaluation of (L, V, N) (model_eval_full_host:
 * the translated text, compiled as the double reference) at five points each, against the same
 * formulas written a second time here in C, reduced to luminance (0.2126 R + 0.7152 G + 0.0722 B,
 * the weights docs/user-models.md gives for a colour-valued BRDF). */
#include "check.h"
#include "models.h"
#include "usermodel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI_ = 3.14159265358979323846;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double clamp01(double x) { return fmin(fmax(x, 0.0), 1.0); }
static double lum(const double *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
static void half_vector(const double *L, const double *V, double *H)
{
    double h[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] }, len = sqrt(dot3(h, h));
    for (int i = 0; i < 3; ++i)
        H[i] = h[i] / len;
}

/* style_unreal.hlsl: GGX in a^2 form, the joint Smith visibility approximation
   0.5 / (NoL (NoV (1 - a) + a) + NoV (NoL (1 - a) + a)), Schlick with saturate(50 g) as F90,
   a = roughness^2 = 2/(n + 2) (roughness = sqrt(2/(n+2))), F0 = (s, 0.9 s, 0.8 s). */
static double ue_c(const double *L, const double *V, const double *N, double n, double s)
{
    double r = sqrt(2.0 / (n + 2.0)), a2 = r * r, H[3];
    half_vector(L, V, H);
    double NoH = clamp01(dot3(N, H)), NoV = fmax(dot3(N, V), 1e-5), NoL = fmax(dot3(N, L), 1e-5);
    double VoH = clamp01(dot3(V, H));
    double d = (NoH * a2 - NoH) * NoH + 1.0, D = a2 / (PI_ * d * d);
    double a = sqrt(a2);
    double vis = 0.5 / (NoL * (NoV * (1 - a) + a) + NoV * (NoL * (1 - a) + a));
    double f0[3] = { s, 0.9 * s, 0.8 * s }, fc = pow(1.0 - VoH, 5.0), F[3];
    for (int i = 0; i < 3; ++i)
        F[i] = (D * vis) * (clamp01(50.0 * f0[1]) * fc + (1.0 - fc) * f0[i]);
    return lum(F);
}

/* style_godot.glsl: D = (alpha / (1 - NoH^2 + (NoH alpha)^2))^2 / pi, V = 0.5 / mix(2 NoL NoV,
   NoL + NoV, alpha), F = f0 + (f90 - f0) (1 - LoH)^5 with f90 = clamp(dot(f0, 16.5)), alpha =
   roughness^2 = sqrt(2/(n + 2)), f0 = (0.04, 0.05, 0.06). */
static double gd_c(const double *L, const double *V, const double *N, double n)
{
    double alpha = sqrt(2.0 / (n + 2.0)), H[3];
    half_vector(L, V, H);
    double NoL = fmax(dot3(N, L), 0.0), NoV = fmax(dot3(N, V), 1e-4), NoH = clamp01(dot3(N, H));
    double LoH = clamp01(dot3(L, H));
    double k = alpha / (1.0 - NoH * NoH + (NoH * alpha) * (NoH * alpha)), D = k * k / PI_;
    double G = 0.5 / (2.0 * NoL * NoV + (NoL + NoV - 2.0 * NoL * NoV) * alpha);
    double f0[3] = { 0.04, 0.05, 0.06 }, f90 = clamp01((f0[0] + f0[1] + f0[2]) * 50.0 * 0.33), F[3];
    for (int i = 0; i < 3; ++i)
        F[i] = D * G * (f0[i] + (f90 - f0[i]) * pow(1.0 - LoH, 5.0));
    return lum(F);
}

/* style_babylon.glsl: Trowbridge-Reitz a^2 / (pi (NoH^2 (a^2 - 1) + 1)^2), the correlated
   visibility 0.5 / (NoL sqrt(NoV^2 (1 - a^2) + a^2) + NoV sqrt(NoL^2 (1 - a^2) + a^2)), NoV as
   |N.V| + 1e-6, Schlick between r0 = (0.5, 0.4, 0.3) and 1, alpha = sqrt(2/(n + 2)). */
static double bj_c(const double *L, const double *V, const double *N, double n)
{
    double a = sqrt(2.0 / (n + 2.0)), a2 = a * a, H[3];
    half_vector(L, V, H);
    double NoL = clamp01(dot3(N, L)), NoV = fabs(dot3(N, V)) + 1e-6, NoH = clamp01(dot3(N, H));
    double VoH = clamp01(dot3(V, H));
    double d = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (PI_ * d * d);
    double vis = 0.5 / (NoL * sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * sqrt(NoL * NoL * (1.0 - a2) + a2));
    double r0[3] = { 0.5, 0.4, 0.3 }, F[3];
    for (int i = 0; i < 3; ++i)
        F[i] = (r0[i] + (1.0 - r0[i]) * pow(1.0 - VoH, 5.0)) * (D * vis);
    return lum(F);
}

/* style_learnopengl.glsl: D = a2 / (pi (NoH^2 (a2 - 1) + 1)^2) with a = roughness^2 = sqrt(2/(n+2)),
   G = G1(NoV) G1(NoL), G1(x) = x / (x (1 - k) + k), k = (roughness + 1)^2 / 8, F = F0 + (1 - F0)
   (1 - HoV)^5 with F0 = 0.04 + (albedo - 0.04) 0.5, albedo (0.9, 0.6, 0.3); D G F / (4 NoV NoL + 1e-4). */
static double lo_c(const double *L, const double *V, const double *N, double n)
{
    double rough = sqrt(sqrt(2.0 / (n + 2.0))), a = rough * rough, a2 = a * a, H[3];
    half_vector(L, V, H);
    double NoH = fmax(dot3(N, H), 0.0), NoV = fmax(dot3(N, V), 0.0), NoL = fmax(dot3(N, L), 0.0);
    double d = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (PI_ * d * d);
    double k = (rough + 1.0) * (rough + 1.0) / 8.0;
    double G = NoV / (NoV * (1.0 - k) + k) * (NoL / (NoL * (1.0 - k) + k));
    double albedo[3] = { 0.9, 0.6, 0.3 }, F[3], HoV = fmax(dot3(H, V), 0.0);
    for (int i = 0; i < 3; ++i) {
        double f0 = 0.04 + (albedo[i] - 0.04) * 0.5;
        F[i] = D * G * (f0 + (1.0 - f0) * pow(clamp01(1.0 - HoV), 5.0)) / (4.0 * NoV * NoL + 0.0001);
    }
    return lum(F);
}

static int load(const char *file, const char *label, struct model_spec *spec)
{
    char path[1024], err[600] = "";
    const char *src = getenv("SRC_DIR");
    snprintf(path, sizeof path, "%s/tests/test_shaderlang_files/%s", src ? src : ".", file);
    int rc = usermodel_load_file(path, NULL, err, sizeof err);
    CHECK(rc == 0, "loading %s: %s", file, err);
    if (rc == 0) {
        rc = model_spec_parse(label, spec, err, sizeof err);
        CHECK(rc == 0, "parsing %s: %s", label, err);
    }
    return rc == 0 && usermodel_host_ready(usermodel_of(spec)) && model_is_full(spec->info);
}

static void unit(const double *in, double *out)
{
    double len = sqrt(dot3(in, in));
    for (int i = 0; i < 3; ++i)
        out[i] = in[i] / len;
}

int main(void)
{
    /* five points: L, V, N (normalised here) and n; the last two with a tilted normal */
    static const double pts[5][10] = {
        { 0, 0, 1, 0.3, 0, 0.95, 0, 0, 1, 10 },
        { 0.2, 0.1, 1, -0.4, 0.2, 0.9, 0, 0, 1, 50 },
        { 0.6, 0, 0.8, -0.6, 0, 0.8, 0, 0, 1, 3 },
        { 0.1, 0.5, 0.9, 0.3, -0.2, 0.9, 0.1, 0.05, 1, 200 },
        { 0.7, 0.2, 0.5, 0.2, 0.6, 0.7, -0.2, 0.1, 1, 1.5 },
    };
    static const struct {
        const char *file, *label;
        int kind;
    } models[] = { { "style_unreal.hlsl", "styleue:Spec=0.6", 0 }, { "style_godot.glsl", "stylegd", 1 },
                   { "style_babylon.glsl", "stylebj", 2 }, { "style_learnopengl.glsl", "stylelo", 3 } };
    for (int m = 0; m < 4; ++m) {
        struct model_spec spec;
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(models[m].label, ":"), models[m].label);
        if (!load(models[m].file, models[m].label, &spec))
            continue;
        for (int p = 0; p < 5; ++p) {
            double L[3], V[3], N[3], n = pts[p][9];
            unit(pts[p], L);
            unit(pts[p] + 3, V);
            unit(pts[p] + 6, N);
            double got = model_eval_full_host(&spec, L, V, N, n);
            int kind = models[m].kind;
            double want = kind == 0 ? ue_c(L, V, N, n, 0.6) : kind == 1 ? gd_c(L, V, N, n)
                          : kind == 2 ? bj_c(L, V, N, n) : lo_c(L, V, N, n);
            CHECK(fabs(got - want) <= 1e-9 * fabs(want), "%s at point %d (n = %g): %.12g, C %.12g", name, p, n, got,
                  want);
            printf("%s point %d: %.9g (C %.9g)\n", name, p, got, want);
        }
    }
    return check_summary();
}
