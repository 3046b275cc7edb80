/* shaderlang.h - user models written as a GLSL or HLSL shader would write them, translated
 * into the OpenCL C user-model form of usermodel.h (docs/user-models.md, "Shader-language
 * models").
 *
 * The translation gives one text that serves the three builds (float16 sweeps, float kernels,
 * the double reference): every float value becomes REAL, every literal RSPLAT(number as
 * written, suffix dropped), vectors (vec2/3/4, float2/3/4) become one REAL per component, and
 * if/else and early returns become selections lane by lane (both sides are evaluated, as a GPU
 * does for lanes that disagree). Helper functions are inlined. Every error names the user's own
 * line and column ("file.glsl:3:9: ..."), and the text it produces carries #line directives,
 * so that a compiler's message points into the user's file too.
 *
 * Both functions return 0 with *out a malloc'd text in the model-file form (a header comment,
 * then REAL NAME(REAL c, REAL n[, RSCALAR p0[, RSCALAR p1]])), SHADERLANG_NOT_SHADER when the
 * text is to be read as OpenCL C as before, or EXIT_USAGE with a one-line message in err. */
#ifndef BRDF_SHADERLANG_H
#define BRDF_SHADERLANG_H

#include <stddef.h>

#define SHADERLANG_NOT_SHADER 1

/* A full BRDF of (L, V, N[, X, Y]) (a GLSL/HLSL function of vectors, a .brdf file) also gets a
 * function of the scene's vectors: REAL brdfbench_full(REAL Lx, Ly, Lz, Vx, Vy, Vz, Nx, Ny, Nz,
 * REAL n[, RSCALAR p0[, RSCALAR p1]]), the luminance of the BRDF with the tangents X, Y made
 * from N (usermodel.c wraps it as brdf_user_full). */
#define SHADERLANG_FULL_FUNCTION "brdfbench_full"

/* A model file. Shader language: a name ending in .glsl, .hlsl, .frag, .fx, .fxh or .hlsli,
 * or any other name but .cl whose text does not use REAL or RSCALAR. The header comment is
 * optional: without it the model is named after the file (its name up to the first dot). */
int shaderlang_file(const char *text, size_t len, const char *path, char **out, size_t *outlen, char *err,
                    size_t errlen);

/* The EXPR of --model NAME=EXPR (origin "--model NAME" names it in messages). Statements
 * (';', braces, return, if) are shader language; a bare expression is too unless it uses a name
 * that only OpenCL C knows (select, native_powr, mul24, ...), when it is left to OpenCL C. */
int shaderlang_expression(const char *name, const char *expr, const char *origin, char **out, size_t *outlen,
                          char *err, size_t errlen);

/* -D NAME[=VALUE] of the command line: a define for every shader-language file read after it
 * (its preprocessor, shaderlang_pp.c). Returns 0, or EXIT_USAGE with a one-line message. */
int shaderlang_define(const char *arg, char *err, size_t errlen);
void shaderlang_clear_defines(void);
/* 1 when the preprocessor (glslang) was linked in: #if, function-like macros, -D. */
int shaderlang_has_preprocessor(void);

#endif
