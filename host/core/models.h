/* models.h - the model registry: ids, parameters with ranges, references, descriptions.
 * The registry drives the CLI, the listing and every loop over models; the formulas
 * themselves live only in kernels/brdf_models.h. */
#ifndef BRDF_MODELS_REGISTRY_H
#define BRDF_MODELS_REGISTRY_H

#include <stddef.h>

#define MODEL_MAX_PARAMS 2
#define MODEL_LABEL_MAX 96

enum lobe_variable { LOBE_PSI, LOBE_THETA_H };

/* What a formula is; model_family_name gives the word the outputs print. */
enum model_family {
    MODEL_FAMILY_REFERENCE = 0,
    MODEL_FAMILY_QUADRATIC,
    MODEL_FAMILY_RATIONAL,
    MODEL_FAMILY_NORMALISED,
    MODEL_FAMILY_MICROFACET,
    MODEL_FAMILY_GAUSSIAN,
    MODEL_FAMILY_POWER,
    MODEL_FAMILY_ANGULAR,
    MODEL_FAMILY_BITS,
    MODEL_FAMILY_PHYSICAL,
    MODEL_FAMILY_USER,
    MODEL_FAMILY_TERM,      /* a term of a microfacet BRDF: Fresnel, shadowing-masking */
    MODEL_FAMILY_COUNT
};
const char *model_family_name(enum model_family f);

/* Where a model comes from, for the frontier's marks; model_kind_name gives the word. */
enum model_kind {
    MODEL_KIND_REFERENCE = 0,
    MODEL_KIND_PAPER,      /* the papers' models */
    MODEL_KIND_ENGINE,     /* cheap lobes shipped by engines */
    MODEL_KIND_TUNED,      /* brdfbench's fitted families */
    MODEL_KIND_OTHER,
    MODEL_KIND_COUNT
};
const char *model_kind_name(enum model_kind k);

/* The operation count of a formula per evaluation (docs/frontier.md holds the table):
 * fused multiply-adds, multiplies and adds (counted together), min/max/select, divides,
 * transcendental calls. known = 0: not counted (not a cheap lobe, or a user model). */
struct model_ops {
    int known;
    int arith, minmax, div, transc;
    const char *note;
};

struct model_param {
    const char *name;
    double min, max, def;
    int integer;          /* 1 when only integer values are accepted */
    const char *meaning;
};

/* One model's descriptor: a row of kernels/brdf_model_list.h for a built-in model. */
struct model_info {
    const char *id;
    int kernel_id;                  /* enum brdf_model_id */
    enum model_family family;
    enum lobe_variable lobe;        /* psi (Phong family) or theta_h (Blinn family) */
    int nparams;
    struct model_param params[MODEL_MAX_PARAMS];
    const char *reference_id;       /* the model its errors are measured against */
    const char *formula;            /* formula in words */
    const char *root;               /* where a quadratic model is zeroed, or NULL */
    const char *description;
    int in_default_set;             /* part of "all models" */
    enum model_kind kind;
    struct model_ops ops;
    int frontier_rank;              /* position in the frontier's default set; 0: not in it */
    const char *frontier_variants;  /* more specs of the model in that set, "a,b"; or NULL */
    const char *colour;             /* plot colour by name (draw_colour_index); "black": a reference */
};

/* A model with parameter values, e.g. "fq:Q=0.64". */
struct model_spec {
    const struct model_info *info;
    double params[MODEL_MAX_PARAMS];
    char label[MODEL_LABEL_MAX];    /* canonical text: id, or id:name=value,... */
};

int models_count(void);
const struct model_info *models_at(int i);
/* 1 for a row of the registry (kernels/brdf_model_list.h), 0 for a model added at run time. */
int model_is_builtin(const struct model_info *info);
const struct model_info *models_find(const char *id);

/* Parses "id" or "id:name=value,name=value". Returns 0, or 2 with a one-line message. */
int model_spec_parse(const char *text, struct model_spec *out, char *err, size_t errlen);
/* Default parameters for a registry entry. */
void model_spec_default(const struct model_info *info, struct model_spec *out);
/* Parses a comma-free list separated by ';' or a list "a,b:k=2,c" (a parameter list after ':'
 * binds to its model). "all" gives every model of the default set. Returns count or -2 on error. */
int model_spec_list_parse(const char *text, struct model_spec *out, int max, char *err, size_t errlen);
/* The default set: every registry model with in_default_set. */
int model_spec_list_default(struct model_spec *out, int max);
/* The reference model of a spec, with default parameters. */
void model_reference_spec(const struct model_spec *spec, struct model_spec *ref);
/* Double-precision host evaluation of the model (the reference implementation); a model
 * registered at run time is evaluated by its own model_runtime. */
double model_eval_host(const struct model_spec *spec, double c, double n);

/* Models added at run time (user models, host/core/usermodel.h) join the registry through
 * this interface, with what the registry cannot know about them: their OpenCL C text for the
 * device builds and their double-precision host evaluation. models_find finds them like the
 * built-in ones; they are not part of models_count/models_at (the registry proper). The
 * registry knows nothing else of where they come from. */
struct cl_session;
struct model_runtime {
    const char *device_source;    /* placed after a kernel file: defines brdf_user_eval */
    const char *device_options;   /* options its float builds add to the kernel file's */
    const char *what;             /* names the model in messages: "user model 'sq' (--model sq)" */
    const char *alias;            /* NULL, or a second name models_find knows it by (NAME@FILE.brdf) */
    /* The value at (c, n) with spec's parameters, in double. */
    double (*eval_host)(const struct model_runtime *rt, const struct model_spec *spec, double c, double n);
    /* Makes eval_host ready where it needs a device (NULL: it never does); idempotent.
       Returns 0 or an exit code. */
    int (*open_host)(const struct model_runtime *rt, struct cl_session *s);
    /* Releases what open_host made on the device of s (NULL with open_host). */
    void (*close_host)(const struct model_runtime *rt, struct cl_session *s);
    /* NULL, or a one-line note for the output when eval_host is not a double evaluation. */
    const char *(*note)(const struct model_runtime *rt);
    /* 1 when eval_host runs on the device, a launch per value (NULL: it never does). */
    int (*eval_on_device)(const struct model_runtime *rt);
    /* A full BRDF of (L, V, N) (its device text defines brdf_user_full): its luminance at unit
       vectors in double; NULL for a lobe. */
    double (*eval_full_host)(const struct model_runtime *rt, const struct model_spec *spec, const double L[3],
                             const double V[3], const double N[3], double n);
    /* Runs fn(ctx, out) where a wild write of the model's host code cannot reach this process
       (outlen bytes of out handed back); NULL: fn runs in place. Returns 0 or an exit code. */
    int (*isolated)(const struct model_spec *spec, void (*fn)(void *ctx, void *out), void *ctx, void *out,
                    size_t outlen);
    int lobe_declared;            /* the model's file names its lobe (psi or theta_h) */
    int fp16;                     /* its text computes in binary16 (a shader's half code, RHALF):
                                     the accuracy sweep measures an fp16 build of it too */
};
#define MODELS_MAX_USER 8
/* Returns 0, or -1 when the table is full. */
int models_register(const struct model_info *info, const struct model_runtime *rt);
void models_unregister_all(void);
/* The registered models, in the order registered (usermodel_at reads them as user models). */
int models_user_count(void);
const struct model_info *models_user_at(int i);
/* The runtime of a model registered with models_register, or NULL for a built-in model. */
const struct model_runtime *models_runtime(const struct model_info *info);
/* fn(ctx, out) through spec's runtime's isolation (models of run-time code), else in place.
 * Returns 0 or an exit code. */
int model_run_isolated(const struct model_spec *spec, void (*fn)(void *ctx, void *out), void *ctx, void *out,
                       size_t outlen);
/* fn(ctx, out) as model_run_isolated, for work that evaluates two models (a model and its
 * reference, either built in or of run-time code): one sandbox serves both. */
int model_run_isolated_pair(const struct model_spec *a, const struct model_spec *b,
                            void (*fn)(void *ctx, void *out), void *ctx, void *out, size_t outlen);
/* count values of model_eval_host (c[i], n[i]) or of model_eval_full_host (L, V, N: 3 doubles
 * a point; n[i]) into out, through model_run_isolated: a model of run-time code is called in
 * one sandbox for all of them, not in a round trip to it per value. Returns 0 or an exit code
 * (the sandbox failed: said on stderr). */
int model_eval_host_many(const struct model_spec *spec, const double *c, const double *n, size_t count, double *out);
int model_eval_full_host_many(const struct model_spec *spec, const double *L, const double *V, const double *N,
                              const double *n, size_t count, double *out);
/* The host's side of a check of a model's device values at float points (c[i], n[i]): the
 * model's double values into value and its reference's peak |f_ref(1, n[i])| into peak, each
 * model's through one model_eval_host_many. Returns 0 or an exit code. */
int model_values_and_peaks(const struct model_spec *m, const struct model_spec *ref, const float *c, const float *n,
                           size_t count, double *value, double *peak);
/* 1 when a model registered at run time declares its lobe in its file's header. */
int model_lobe_declared(const struct model_info *info);
/* The note of spec's runtime (NULL for a built-in model or a double evaluation). */
const char *model_eval_note(const struct model_spec *spec);
/* 1 when the model sees only c, not s = 1 - c (brdf_sees_only_c of kernels/brdf_models.h: the
 * rows of kernels/brdf_model_list.h marked C_ONLY, and every model registered at run time,
 * whose text is a function of c). The sweeps evaluate such a model on
 * the float cosines (kernels/accuracy.cl), and its double figures are recomputed there. */
int model_sees_only_c(const struct model_spec *spec);
/* 1 when model_eval_host of the model costs a device launch per value (a user model whose text
 * does not compile on the host): searches that evaluate it many times use coarser grids. */
int model_eval_host_on_device(const struct model_spec *spec);
/* 1 when the model is a full BRDF of (L, V, N) (a runtime with eval_full_host): render and the
 * physical-cost table evaluate it at the scene's vectors (kernels: brdf_user_full). */
int model_is_full(const struct model_info *info);
/* Its value at unit L, V, N and shininess n in double (NAN for a lobe). */
double model_eval_full_host(const struct model_spec *spec, const double L[3], const double V[3], const double N[3],
                            double n);

#endif
