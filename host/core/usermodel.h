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
 * whose kernel_id is BRDF_USER; the registry (host/models.c) finds it by name, and
 * model_eval_host() sends BRDF_USER to usermodel_eval_host(), the device double reference.
 */
#ifndef BRDF_USERMODEL_H
#define BRDF_USERMODEL_H

#include <stddef.h>

#include "clsession.h"
#include "models.h"

#define USERMODEL_MAX 8                    /* user models per run */
#define USERMODEL_MAX_FILE (256 * 1024)    /* bytes of a model file */
#define USERMODEL_MAX_EXPR 1000            /* characters of a --model expression */
#define USERMODEL_NAME_MAX 48

struct user_model {
    struct model_info info;        /* first member: spec->info of a user model points here */
    char name[USERMODEL_NAME_MAX + 1];
    char function[USERMODEL_NAME_MAX + 1];
    char reference[32];
    char description[256];
    char formula[USERMODEL_MAX_EXPR + 8];
    char param_names[MODEL_MAX_PARAMS][USERMODEL_NAME_MAX + 1];
    char origin[512];              /* the file's path, or "--model NAME" */
    int from_file;
    char *device_source;           /* appended after a kernel file: #line, the user's text, a wrapper */

    /* The reference on the device (usermodel_reference_open). */
    struct cl_session *ref_session;
    cl_program ref_program;
    cl_kernel ref_point;
    cl_mem ref_out;
    int ref_is_double;             /* 0: the device has no cl_khr_fp64 and the reference is float */
    int ref_warned;
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
    "                     e.g. --model 'sq=(0.45*n*(c-1)+1)*(0.45*n*(c-1)+1)'; repeatable\n"

/* Builds kernels/<kernel_file> for model m: for a user model with its text appended and
 * its build options (a failed build shows the log with the user's line numbers and returns
 * EXIT_USAGE), for a built-in model as clsession_build does. */
int usermodel_build(struct cl_session *s, const char *kernel_file, const struct model_spec *m,
                    const char *options, cl_program *out);
/* The same with extra text placed between the kernel file and the user model's text (a
 * library that generates kernels per model id, such as throughput's TP_MODEL_KERNELS). */
int usermodel_build_ex(struct cl_session *s, const char *kernel_file, const char *extra_before,
                       const struct model_spec *m, const char *options, cl_program *out);

/* Kernels for user models, for a library that builds one program for all the built-in models
 * (render.c's shade.cl, field.c's field.cl): a user model gets its own build of the same
 * kernel file on first use, and its reference on the device is opened with it. */
struct usermodel_builds {
    struct cl_session *s;
    char kernel_file[64], kernel_name[64], options[512];
    int count;
    struct {
        const struct model_info *model;
        cl_program program;
        cl_kernel kernel;
    } item[USERMODEL_MAX];
};
void usermodel_builds_init(struct usermodel_builds *b, struct cl_session *s, const char *kernel_file,
                           const char *kernel_name, const char *options);
/* The kernel that evaluates model m: `shared` for a built-in model, else the kernel of the
 * user model's own build. Returns 0 or an exit code (EXIT_USAGE: the model does not compile). */
int usermodel_builds_kernel(struct usermodel_builds *b, const struct model_spec *m, cl_kernel shared,
                            cl_kernel *out);
void usermodel_builds_close(struct usermodel_builds *b);

/* The options that usermodel_build adds for a user model's float builds. */
#define USERMODEL_FLOAT_OPTIONS "-DBRDF_HAVE_USER_MODEL -cl-single-precision-constant"

/* Builds the user model's reference on the device of s (double where the device has
 * cl_khr_fp64; the environment variable BRDFBENCH_NO_FP64=1 forces the float fallback, to
 * test it). Idempotent. Returns 0 or an exit code. */
int usermodel_reference_open(const struct user_model *um, struct cl_session *s);
void usermodel_reference_close(const struct user_model *um);
/* NULL when the reference is double, else a one-line note for the output. */
const char *usermodel_reference_note(const struct user_model *um);
/* The reference value of a user model at (c, n) with spec's parameters; NAN when its
 * reference is not open (or the device failed: reported once on stderr). */
double usermodel_eval_host(const struct model_spec *m, double c, double n);

#endif
