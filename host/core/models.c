/* models.c - the model registry and the double-precision host evaluation.
 * The host reference compiles kernels/brdf_models.h with REAL = double, so each formula
 * exists once; this file adds only names, parameter domains and descriptions. */
#include "models.h"
#include "exitcodes.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

static const struct model_info registry[] = {
#define BRDF_MODEL(E, C_ONLY, EVAL, ...) { .kernel_id = BRDF_##E, __VA_ARGS__ },
#include "brdf_model_list.h"
#undef BRDF_MODEL
};

_Static_assert(sizeof registry / sizeof registry[0] == BRDF_USER,
               "every model id before BRDF_USER has a registry entry");

const char *model_family_name(enum model_family f)
{
    static const char *const names[MODEL_FAMILY_COUNT] = {
        "reference", "quadratic", "rational", "normalised", "microfacet", "gaussian",
        "power", "angular", "bits", "physical", "user", "term" };
    return f >= 0 && f < MODEL_FAMILY_COUNT ? names[f] : "?";
}

const char *model_kind_name(enum model_kind k)
{
    static const char *const names[MODEL_KIND_COUNT] = { "reference", "paper", "engine", "tuned", "other" };
    return k >= 0 && k < MODEL_KIND_COUNT ? names[k] : "?";
}

int models_count(void) { return (int)(sizeof registry / sizeof registry[0]); }

int model_is_builtin(const struct model_info *info)
{
    for (int i = 0; i < models_count(); ++i)
        if (info == &registry[i])
            return 1;
    return 0;
}

const struct model_info *models_at(int i)
{
    return (i >= 0 && i < models_count()) ? &registry[i] : NULL;
}

/* The models added at run time (models_register: the user models, usermodel.c): the process's,
 * not a run's, because they are defined by the command line's flags before any run opens and
 * every layer resolves a model's name (models_find, model_spec_parse) with no run at hand. One
 * table for every kind of registered model. */
static struct {
    const struct model_info *info;
    const struct model_runtime *rt;
} user_models[MODELS_MAX_USER];
static int user_model_count;

int models_user_count(void) { return user_model_count; }

const struct model_info *models_user_at(int i) { return i >= 0 && i < user_model_count ? user_models[i].info : NULL; }

int models_register(const struct model_info *info, const struct model_runtime *rt)
{
    if (user_model_count >= MODELS_MAX_USER || !rt || !rt->eval_host)
        return -1;
    user_models[user_model_count].info = info;
    user_models[user_model_count].rt = rt;
    ++user_model_count;
    return 0;
}

void models_unregister_all(void) { user_model_count = 0; }

const struct model_runtime *models_runtime(const struct model_info *info)
{
    for (int i = 0; i < user_model_count; ++i)
        if (user_models[i].info == info)
            return user_models[i].rt;
    return NULL;
}

const struct model_info *models_find(const char *id)
{
    for (int i = 0; i < models_count(); ++i)
        if (strcmp(registry[i].id, id) == 0)
            return &registry[i];
    for (int i = 0; i < user_model_count; ++i)
        if (strcmp(user_models[i].info->id, id) == 0 ||
            (user_models[i].rt->alias && strcmp(user_models[i].rt->alias, id) == 0))
            return user_models[i].info;
    return NULL;
}

static void model_spec_make_label(struct model_spec *s)
{
    size_t used = (size_t)snprintf(s->label, sizeof s->label, "%s", s->info->id);
    for (int p = 0; p < s->info->nparams && used < sizeof s->label; ++p)
        used += (size_t)snprintf(s->label + used, sizeof s->label - used, "%s%s=%.10g",
                                 p == 0 ? ":" : ",", s->info->params[p].name, s->params[p]);
}

void model_spec_default(const struct model_info *info, struct model_spec *out)
{
    memset(out, 0, sizeof *out);
    out->info = info;
    for (int p = 0; p < info->nparams; ++p)
        out->params[p] = info->params[p].def;
    model_spec_make_label(out);
}

static void list_model_ids(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < models_count() && used < len; ++i)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "", registry[i].id);
    for (int i = 0; i < user_model_count && used < len; ++i)
        used += (size_t)snprintf(buf + used, len - used, ", %s", user_models[i].info->id);
}

/* Parses one "name=value" assignment into spec; *assigned has a bit per parameter already
   given, and a parameter given twice is refused. */
static int model_param_assign(struct model_spec *spec, const char *assign, unsigned *assigned, char *err,
                              size_t errlen)
{
    const struct model_info *info = spec->info;
    const char *eq = strchr(assign, '=');
    if (!eq) {
        snprintf(err, errlen, "model '%s': parameter '%s' is not name=value", info->id, assign);
        return 2;
    }
    size_t nlen = (size_t)(eq - assign);
    int which = -1;
    for (int p = 0; p < info->nparams; ++p)
        if (strlen(info->params[p].name) == nlen && strncmp(info->params[p].name, assign, nlen) == 0)
            which = p;
    if (which < 0) {
        if (info->nparams == 0)
            snprintf(err, errlen, "model '%s' takes no parameters (got '%.*s')", info->id, (int)nlen, assign);
        else if (info->nparams == 1)
            snprintf(err, errlen, "model '%s' has no parameter '%.*s' (accepted: %s)", info->id,
                     (int)nlen, assign, info->params[0].name);
        else
            snprintf(err, errlen, "model '%s' has no parameter '%.*s' (accepted: %s, %s)", info->id,
                     (int)nlen, assign, info->params[0].name, info->params[1].name);
        return 2;
    }
    const struct model_param *mp = &info->params[which];
    const char *text = eq + 1;
    if (*assigned & (1u << which)) {
        snprintf(err, errlen, "model '%s': parameter %s given twice (at '%s'; accepted: each parameter once)",
                 info->id, mp->name, assign);
        return 2;
    }
    *assigned |= 1u << which;
    char *end = NULL;
    errno = 0;
    double v = strtod(text, &end);
    if (*text == '\0' || end == text || *end != '\0' || errno == ERANGE || !isfinite(v) ||
        v < mp->min || v > mp->max || (mp->integer && v != floor(v))) {
        if (mp->integer)
            snprintf(err, errlen, "model '%s': parameter %s='%s' must be an integer in [%g, %g]",
                     info->id, mp->name, text, mp->min, mp->max);
        else
            snprintf(err, errlen, "model '%s': parameter %s='%s' must be a number in [%g, %g]",
                     info->id, mp->name, text, mp->min, mp->max);
        return 2;
    }
    spec->params[which] = v;
    return 0;
}

int model_spec_parse(const char *text, struct model_spec *out, char *err, size_t errlen)
{
    char buf[256];
    if (strlen(text) >= sizeof buf) {
        snprintf(err, errlen, "model '%.40s...' is too long (at most %zu characters)", text, sizeof buf - 1);
        return 2;
    }
    strcpy(buf, text);
    char *colon = strchr(buf, ':');
    if (colon)
        *colon = '\0';
    const struct model_info *info = models_find(buf);
    if (!info) {
        char ids[512];
        list_model_ids(ids, sizeof ids);
        snprintf(err, errlen, "unknown model '%s' (accepted: %s)", buf, ids);
        return 2;
    }
    model_spec_default(info, out);
    if (colon) {
        char *save = NULL;
        if (colon[1] == '\0') {
            snprintf(err, errlen, "model '%s': empty parameter list after ':'", info->id);
            return 2;
        }
        unsigned assigned = 0;
        for (char *tok = strtok_r(colon + 1, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
            if (model_param_assign(out, tok, &assigned, err, errlen))
                return 2;
    }
    model_spec_make_label(out);
    return 0;
}

int model_spec_list_default(struct model_spec *out, int max)
{
    int count = 0;
    for (int i = 0; i < models_count() && count < max; ++i)
        if (registry[i].in_default_set)
            model_spec_default(&registry[i], &out[count++]);
    return count;
}

int model_spec_list_parse(const char *text, struct model_spec *out, int max, char *err, size_t errlen)
{
    if (strcmp(text, "all") == 0)
        return model_spec_list_default(out, max);
    /* Split on ','; a token with '=' but no ':' continues the previous model's parameters. */
    char buf[1024], item[512];
    if (strlen(text) >= sizeof buf || text[0] == '\0') {
        snprintf(err, errlen, "--models: expected a comma-separated list of models (1 to %zu characters)",
                 sizeof buf - 1);
        return -2;
    }
    strcpy(buf, text);
    int count = 0;
    item[0] = '\0';
    char *p = buf;
    for (;;) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        int continues = strchr(p, '=') && !strchr(p, ':') && item[0];
        if (*p == '\0') {
            snprintf(err, errlen, "--models: empty entry in list '%s'", text);
            return -2;
        }
        if (continues) {
            if (strlen(item) + strlen(p) + 2 >= sizeof item) {
                snprintf(err, errlen, "--models: entry too long");
                return -2;
            }
            strcat(item, ",");
            strcat(item, p);
        } else {
            if (item[0]) {
                if (count >= max) {
                    snprintf(err, errlen, "--models: at most %d models per run", max);
                    return -2;
                }
                if (model_spec_parse(item, &out[count++], err, errlen))
                    return -2;
            }
            snprintf(item, sizeof item, "%s", p);
        }
        if (!comma)
            break;
        p = comma + 1;
    }
    if (count >= max) {
        snprintf(err, errlen, "--models: at most %d models per run", max);
        return -2;
    }
    if (model_spec_parse(item, &out[count++], err, errlen))
        return -2;
    return count;
}

void model_reference_spec(const struct model_spec *spec, struct model_spec *ref)
{
    const struct model_info *info = models_find(spec->info->reference_id);
    model_spec_default(info ? info : spec->info, ref);
}

double model_eval_host(const struct model_spec *spec, double c, double n)
{
    const struct model_runtime *rt = spec->info->kernel_id == BRDF_USER ? models_runtime(spec->info) : NULL;
    if (rt)
        return rt->eval_host(rt, spec, c, n);
    if (spec->info->kernel_id == BRDF_USER)
        return NAN;   /* a run-time model no longer registered */
    return brdf_eval(spec->info->kernel_id, c, n, spec->params[0], spec->params[1]);
}

const char *model_eval_note(const struct model_spec *spec)
{
    const struct model_runtime *rt = spec ? models_runtime(spec->info) : NULL;
    return rt && rt->note ? rt->note(rt) : NULL;
}

int model_sees_only_c(const struct model_spec *spec)
{
    return brdf_sees_only_c(spec->info->kernel_id);
}

int model_eval_host_on_device(const struct model_spec *spec)
{
    const struct model_runtime *rt = spec ? models_runtime(spec->info) : NULL;
    return rt && rt->eval_on_device && rt->eval_on_device(rt);
}

int model_is_full(const struct model_info *info)
{
    const struct model_runtime *rt = info ? models_runtime(info) : NULL;
    return rt && rt->eval_full_host;
}

double model_eval_full_host(const struct model_spec *spec, const double L[3], const double V[3], const double N[3],
                            double n)
{
    const struct model_runtime *rt = spec ? models_runtime(spec->info) : NULL;
    return rt && rt->eval_full_host ? rt->eval_full_host(rt, spec, L, V, N, n) : NAN;
}

int model_run_isolated(const struct model_spec *spec, void (*fn)(void *ctx, void *out), void *ctx, void *out,
                       size_t outlen)
{
    const struct model_runtime *rt = models_runtime(spec->info);
    if (rt && rt->isolated)
        return rt->isolated(spec, fn, ctx, out, outlen);
    fn(ctx, out);
    return 0;
}

int model_run_isolated_pair(const struct model_spec *a, const struct model_spec *b,
                            void (*fn)(void *ctx, void *out), void *ctx, void *out, size_t outlen)
{
    const struct model_runtime *ra = a ? models_runtime(a->info) : NULL, *rb = b ? models_runtime(b->info) : NULL;
    int ia = ra && ra->isolated, ib = rb && rb->isolated;
    /* Inside one sandbox every run-time model's host code is called directly; a model whose
       double values take a device launch each (its host code did not compile) cannot be
       evaluated there, so fn then runs in place, as model_run_isolated does for one model.
       (model_eval_host_on_device compiles the host code where it has not been yet: in this
       process, before the sandbox, where the compiler may run.) */
    if ((ia && model_eval_host_on_device(a)) || (ib && model_eval_host_on_device(b))) {
        fn(ctx, out);
        return 0;
    }
    return ia ? model_run_isolated(a, fn, ctx, out, outlen) : model_run_isolated(b ? b : a, fn, ctx, out, outlen);
}

struct many_ctx {
    const struct model_spec *spec;
    const double *c, *n, *L, *V, *N;
    size_t count;
};

static void lobe_many(void *vctx, void *vout)
{
    const struct many_ctx *m = vctx;
    double *out = vout;
    for (size_t i = 0; i < m->count; ++i)
        out[i] = model_eval_host(m->spec, m->c[i], m->n[i]);
}

static void full_many(void *vctx, void *vout)
{
    const struct many_ctx *m = vctx;
    double *out = vout;
    for (size_t i = 0; i < m->count; ++i)
        out[i] = model_eval_full_host(m->spec, m->L + 3 * i, m->V + 3 * i, m->N + 3 * i, m->n[i]);
}

int model_eval_host_many(const struct model_spec *spec, const double *c, const double *n, size_t count, double *out)
{
    struct many_ctx m = { spec, c, n, NULL, NULL, NULL, count };
    return count ? model_run_isolated(spec, lobe_many, &m, out, count * sizeof *out) : 0;
}

int model_eval_full_host_many(const struct model_spec *spec, const double *L, const double *V, const double *N,
                              const double *n, size_t count, double *out)
{
    struct many_ctx m = { spec, NULL, n, L, V, N, count };
    return count ? model_run_isolated(spec, full_many, &m, out, count * sizeof *out) : 0;
}

int model_values_and_peaks(const struct model_spec *m, const struct model_spec *ref, const float *c, const float *n,
                           size_t count, double *value, double *peak)
{
    double *dc = malloc(2 * count * sizeof *dc), *dn = dc ? dc + count : NULL;
    if (!dc) {
        fprintf(stderr, "brdfbench: out of memory for the double values of %zu points\n", count);
        return EXIT_RUNTIME;
    }
    for (size_t i = 0; i < count; ++i) {
        dc[i] = c[i];
        dn[i] = n[i];
    }
    int rc = model_eval_host_many(m, dc, dn, count, value);
    for (size_t i = 0; i < count; ++i)
        dc[i] = 1.0;
    if (!rc)
        rc = model_eval_host_many(ref, dc, dn, count, peak);
    for (size_t i = 0; !rc && i < count; ++i)
        peak[i] = fabs(peak[i]);
    free(dc);
    return rc;
}

int model_lobe_declared(const struct model_info *info)
{
    const struct model_runtime *rt = models_runtime(info);
    return rt && rt->lobe_declared;
}
