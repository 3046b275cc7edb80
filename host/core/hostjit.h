/* hostjit.h - a model's OpenCL C text compiled for the host in double, at run time.
 *
 * A user model's text (docs/user-models.md) is written for REAL = float16, float and double.
 * Its double form is its reference: every figure of the accuracy sweep is recomputed and
 * polished with it, value by value. On the host that costs a function call, as for a
 * built-in model (host/core/models.c compiles kernels/brdf_models.h as C); on an OpenCL
 * device each value would be a kernel launch. So the same text is compiled here as C with
 * REAL = double by libtcc (Debian's libtcc-dev), after a prelude that declares OpenCL C's
 * scalar built-in functions for double (the C99 ones from the host's libm, the others such
 * as clamp, step, select, mix, powr, pown, rsqrt written out).
 *
 * Not every OpenCL C text is C: vector literals, conversions (convert_*, as_*), address
 * spaces in pointers... Such a text does not compile here; hostjit_compile says why and its
 * caller falls back to the device (host/core/usermodel.c).
 */
#ifndef BRDF_HOSTJIT_H
#define BRDF_HOSTJIT_H

#include <stddef.h>

struct hostjit;

/* The evaluator: brdf_eval(BRDF_USER, c, n, p0, p1) of kernels/brdf_models.h in double. */
typedef double (*hostjit_fn)(double c, double n, double p0, double p1);

/* Compiles models_header (the text of kernels/brdf_models.h) followed by model_text (which
 * defines brdf_user_eval, as appended to a kernel file for the device). Returns NULL with
 * the compiler's first message in err (file:line: error ...) when the text is not C. */
struct hostjit *hostjit_compile(const char *models_header, const char *model_text, char *err, size_t errlen);
hostjit_fn hostjit_function(const struct hostjit *j);
/* A full BRDF's function of the vectors (L, V, N components, n, p0, p1), the text's
 * brdfbench_host_full, or NULL where the text defines none. */
typedef double (*hostjit_full_fn)(double lx, double ly, double lz, double vx, double vy, double vz, double nx,
                                  double ny, double nz, double n, double p0, double p1);
hostjit_full_fn hostjit_full_function(const struct hostjit *j);
void hostjit_free(struct hostjit *j);

/* The sandbox. The compiled text is a user's code: the evaluations of a run go through a
 * child process, forked on the first one, that has closed every descriptor and entered a
 * seccomp filter (exit, futex, sched_yield: nothing else), so that a wild write, had one got
 * past the parse check (usermodel_check_code), lands in the child's copy of memory and no
 * system call can follow it. Requests and values, up to 512 at a time, pass through one
 * shared block of memory, the only memory the two share (hostjit.c). Each returns 0, or -1 when the child is gone (a crash, a kill):
 * hostjit_failure then says how, and every later call fails too. hostjit_function and
 * hostjit_full_function call the code in this process, for tests only. */
int hostjit_eval(struct hostjit *j, double c, double n, double p0, double p1, double *out);
/* count values, args holding c, n, p0, p1 for each */
int hostjit_eval_many(struct hostjit *j, const double *args, size_t count, double *out);
/* args: L, V, N (3 each), n, p0, p1 */
int hostjit_eval_full(struct hostjit *j, const double args[12], double *out);
const char *hostjit_failure(const struct hostjit *j);
/* The requests this process has handed to sandbox children so far (every hostjit's): a
 * measure of how often brdfbench's work waited for the other process, which a phase of many
 * values avoids by running in one child (hostjit_isolated, model_run_isolated). */
unsigned long hostjit_round_trips(void);
/* A whole phase of brdfbench's own work that evaluates the model value after value (a
 * search that asks for one point at a time, where a round trip per value would cost more
 * than the formula): fn(ctx, out) runs in a forked child under the same filter, widened to
 * the memory calls malloc needs (never PROT_EXEC), where the model's code is called
 * directly; the outlen bytes it leaves in out come back to out, nothing else does. Every
 * hostjit it uses must have been compiled before. tick(tctx, c, n), when given, is called
 * in brdfbench whenever the child has gone on to another value (the deadline's mark).
 * Returns 0, or -1 with why (the child's crash, a signal). */
int hostjit_isolated(void (*fn)(void *ctx, void *out), void *ctx, void *out, size_t outlen,
                     void (*tick)(void *tctx, double c, double n), void *tctx, char *why, size_t whylen);


#endif
