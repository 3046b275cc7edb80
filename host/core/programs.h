/* programs.h - the one place that turns a run's models into what evaluates them: device
 * programs and host evaluators, cached for the life of the OpenCL session.
 *
 * An engine builds each kernel file once for the built-in models (every built-in formula is
 * in kernels/brdf_models.h, so one build serves them all). A model registered at run time
 * (host/core/models.h: struct model_runtime) needs the kernel file with its own text
 * appended: that build is made here on first use and kept until clsession_close, so each
 * (kernel file, options, model) is compiled once per run whichever engines ask for it. The
 * engines do not ask what kind of model they hold: they pass their own kernel for the
 * built-in models and receive the kernel that evaluates the model at hand.
 *
 * Each call also makes the model's double-precision host evaluation (model_eval_host) ready,
 * which for some run-time models needs the device.
 */
#ifndef BRDF_PROGRAMS_H
#define BRDF_PROGRAMS_H

#include "clsession.h"
#include "models.h"

/* The kernel kernel_name of kernel_file (built with options) that evaluates model m: `shared`
 * (the engine's own build, for the built-in models) when m is built-in, else the kernel of
 * the cached build with m's text. In a session that specialises (clsession.h), a built-in
 * model gets a cached build of its own too, with -DBRDF_ONLY_MODEL and -DBRDF_ONLY_REF (its
 * reference), so that a driver never compiles the dispatch of every model. The cache owns that kernel (do not release it); the same
 * kernel object is handed to every engine of the session, so set its arguments before each
 * launch. Returns 0, EXIT_USAGE when m's text does not compile (its build log and a line
 * naming the model are on stderr), or EXIT_RUNTIME. */
int programs_kernel(struct cl_session *s, const char *kernel_file, const char *options, const struct model_spec *m,
                    const char *kernel_name, cl_kernel shared, cl_kernel *out);

/* The same, for a build that evaluates m against ref (--reference) instead of m's own reference
 * (a specialised build keeps that reference's case: -DBRDF_ONLY_REF). ref NULL: m's own. */
int programs_kernel_ref(struct cl_session *s, const char *kernel_file, const char *options, const struct model_spec *m,
                        const struct model_spec *ref, const char *kernel_name, cl_kernel shared, cl_kernel *out);

/* The program of kernel_file with extra_before (text placed between the kernel file and the
 * model's text; may be NULL) and options that evaluates m: `shared` when m is built-in, else
 * the cached build with m's text. The cache owns it (do not release it). Same returns. */
int programs_program(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                     const struct model_spec *m, cl_program shared, cl_program *out);

/* Makes model_eval_host(m, ...) ready on session s (nothing to do for a built-in model).
 * programs_kernel and programs_program do it too. Returns 0 or an exit code. */
int programs_host(struct cl_session *s, const struct model_spec *m);

/* Releases every build and host evaluator cached for s (clsession_close calls it). */
void programs_release(struct cl_session *s);

/* Builds made so far by the cache for s (for tests). */
int programs_build_count(const struct cl_session *s);

#endif
