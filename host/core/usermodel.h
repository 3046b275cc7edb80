/* usermodel.h - user-defined models, compiled at run time by the OpenCL driver.
 *
 * A user model is OpenCL C text that defines f(c, n[, p0[, p1]]): either a model file
 * (--model-file FILE.cl: a header comment names the model and declares its parameters, then
 * the function) or a one-line expression of c and n (--model 'name=EXPR'). The format is
 * documented in docs/user-models.md.
 *
 * How it is compiled: the model's text is appended after a kernel file that includes
 * kernels/brdf_models.h, with -DBRDF_HAVE_USER_MODEL, so that brdf_eval(BRDF_USER, ...) calls
 * it like a built-in model. The same text is compiled for REAL = float16 (the sweeps), float
 * (scalar kernels) and double (its reference, kernels/usermodel_ref.cl, on the device where it
 * has cl_khr_fp64). Float builds use -cl-single-precision-constant, so an unsuffixed literal
 * such as 0.5 is a float there and a double in the reference.
 *
 * How the rest of the program finds it: struct user_model begins with a struct model_info
 * whose kernel_id is BRDF_USER and carries a struct model_runtime; usermodel_register hands
 * both to the registry (models_register, host/core/models.h), which then finds the model by
 * name and evaluates it through the runtime without knowing this file. Device programs are
 * built from the runtime's text by host/core/programs.c.
 *
 * Its double reference: the same text compiled as C for the host by host/core/hostjit.c
 * (a function call per value, as for a built-in model). A text that is OpenCL C but not C
 * falls back to a double build on the device (kernels/usermodel_ref.cl), one launch per
 * value, and says so on stderr.
 */
#ifndef BRDF_USERMODEL_H
#define BRDF_USERMODEL_H

#include <stddef.h>

#include "clsession.h"
#include "hostjit.h"
#include "models.h"

#define USERMODEL_MAX 8                    /* user models per run */
/* Bytes of a model file: a longer one can hold an expression whose chain of terms overflows
 * the OpenCL compiler's stack (25,000 terms in 250 KB crashed libclang; 12,000 in 120 KB built). */
#define USERMODEL_MAX_FILE (64 * 1024)
#define USERMODEL_MAX_EXPR 1000            /* characters of a --model expression */
#define USERMODEL_NAME_MAX 48
#define USERMODEL_CACHE 64                 /* points of the host reference's value cache */

struct user_model {
    struct model_info info;        /* first member: spec->info of a user model points here */
    char name[USERMODEL_NAME_MAX + 1];
    char function[USERMODEL_NAME_MAX + 1];
    char reference[32];
    char description[256];
    char formula[USERMODEL_MAX_EXPR + 8];
    char param_names[MODEL_MAX_PARAMS][USERMODEL_NAME_MAX + 1];
    char origin[512];              /* the file's path, or "--model NAME" */
    /* A .brdf file's model in its file's namespace, NAME@FILE.brdf (FILE.brdf: the file's name
       without its folder): its name when NAME is a built-in's or another model's, else a
       second name it answers to; "" when NAME@FILE.brdf would not be a model name. */
    char qualified[USERMODEL_NAME_MAX + 1];
    int from_file;
    int full;                      /* a full BRDF: its text defines brdfbench_full (shaderlang.h) */
    int lobe_declared;             /* its header names its lobe (a .brdf file's psi is always declared) */
    char *device_source;           /* appended after a kernel file: #line, the user's text, a wrapper */
    char what[600];                /* "user model 'NAME' (ORIGIN)", for messages */
    struct model_runtime runtime;  /* what the registry and host/core/programs.c use */

    /* The reference on the host (hostjit.h), compiled on first use, and the values of the
       last points asked of it (usermodel_eval_host). */
    struct hostjit *host;
    struct usermodel_cached { double key[4], value; int valid; } cache[USERMODEL_CACHE];
    long long cache_hits, cache_misses;
    int host_tried;
    char host_error[512];          /* why the text does not compile as C */

    /* The fallback reference on the device (usermodel_reference_open). */
    struct cl_session *ref_session;
    cl_program ref_program;
    cl_kernel ref_point;
    cl_mem ref_out;
    int ref_is_double;             /* 0: the device has no cl_khr_fp64 and the reference is float */
    int ref_warned;
    int ref_noted;                 /* the fallback has been announced */
    long long ref_calls;
};

/* Parses a model file's text (path names it in messages: "path:line: problem"). On success
 * *out is a new model, not yet registered. Returns 0 or EXIT_USAGE. No device is needed. */
int usermodel_parse_file_text(const char *text, size_t len, const char *path, struct user_model **out,
                              char *err, size_t errlen);
/* Parses "name=EXPR" (the value of --model). Returns 0 or EXIT_USAGE. */
int usermodel_parse_expression(const char *arg, struct user_model **out, char *err, size_t errlen);
/* Reads and parses a model file and registers it; a file already registered (same path)
 * is found again. *out may be NULL. Returns 0 or EXIT_USAGE. */
int usermodel_load_file(const char *path, const struct user_model **out, char *err, size_t errlen);
/* Registers a parsed model (takes ownership, also on failure). Returns 0 or EXIT_USAGE
 * (a name taken by a built-in or another user model, or too many user models). */
int usermodel_register(struct user_model *um, char *err, size_t errlen);
void usermodel_free(struct user_model *um);
/* Forgets every registered user model (their device objects must be closed first). */
void usermodel_clear_all(void);

int usermodel_count(void);
const struct user_model *usermodel_at(int i);
/* The names of the registered user models, comma-separated ("" when none). */
const char *usermodel_names(void);
/* Appends every registered user model, with its default parameters, to a list of *count
 * models (at most max). Returns 0, or EXIT_USAGE with a message when the list is full. */
int usermodel_append_all(struct model_spec *models, int *count, int max, char *err, size_t errlen);
/* The user model behind a spec or a registry entry, or NULL for a built-in model. */
const struct user_model *usermodel_of(const struct model_spec *m);
const struct user_model *usermodel_of_info(const struct model_info *info);

#define USERMODEL_OPTIONS_HELP \
    "  --model-file FILE  add the user model of FILE.cl (see docs/user-models.md); repeatable\n" \
    "  --model NAME=EXPR  add a user model given by an OpenCL C expression of c and n,\n" \
    "                     e.g. --model 'sq=fmax(0.45*n*(c-1)+1,0)*fmax(0.45*n*(c-1)+1,0)';\n" \
    "                     repeatable\n"

/* The options that a user model's float builds add to a kernel file's (programs.c); a full
 * BRDF's add USERMODEL_FULL_OPTION too, which declares brdf_user_full. */
#define USERMODEL_FLOAT_OPTIONS "-DBRDF_HAVE_USER_MODEL -cl-single-precision-constant"
#define USERMODEL_FULL_OPTION " -DBRDF_HAVE_USER_FULL"


/* Compiles the model's host reference now (it is compiled on first use otherwise). Returns 1
 * when the model is evaluated on the host, 0 when its text is not C (the reason is in
 * um->host_error) and its reference needs the device. */
int usermodel_host_ready(const struct user_model *um);

/* Builds the user model's reference on the device of s (double where the device has
 * cl_khr_fp64; the environment variable BRDFBENCH_NO_FP64=1 forces the float fallback, to
 * test it), for a model whose text does not compile on the host. Idempotent. Returns 0 or an
 * exit code. The registry reaches it through the model's runtime (open_host). */
int usermodel_reference_open(const struct user_model *um, struct cl_session *s);
void usermodel_reference_close(const struct user_model *um);
/* NULL when the reference is double, else a one-line note for the output. */
const char *usermodel_reference_note(const struct user_model *um);
/* The reference value of a user model at (c, n) with spec's parameters: on the host, or on
 * the device where the text is not C; NAN when that reference is not open (or the device
 * failed: reported once on stderr). */
double usermodel_eval_host(const struct model_spec *m, double c, double n);

/* Runs fn(ctx, out), a phase of work that evaluates model m's host reference value after
 * value (a search), in the sandbox's child as a whole (hostjit_isolated), so that the phase
 * costs no round trip per value; the outlen bytes of out come back. For a built-in model, or
 * a user model evaluated on the device, fn runs here. A crash in the child ends the run as a
 * crash of the per-value sandbox does (exit 3). BRDFBENCH_TEST_PHASE_IN_PROCESS=1 runs fn here
 * always (scripts/bench_hostref_sandbox.sh compares the two). Returns 0. */
int usermodel_isolated(const struct model_spec *m, void (*fn)(void *ctx, void *out), void *ctx, void *out,
                       size_t outlen);

#endif
