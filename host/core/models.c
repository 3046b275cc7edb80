/* models.c - the model registry and the double-precision host evaluation.
 * The host reference compiles kernels/brdf_models.h with REAL = double, so each formula
 * exists once; this file adds only names, parameter domains and descriptions. */
#include "models.h"

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

#define NOP { { NULL, 0, 0, 0, 0, NULL } }

static const struct model_info registry[] = {
    { "phong", BRDF_PHONG, "reference", LOBE_PSI, 0, NOP, "phong",
      "cos(psi)^n", NULL, "Phong lobe: the reference of the Phong family", 1 },
    { "blinn", BRDF_BLINN, "reference", LOBE_THETA_H, 0, NOP, "blinn",
      "cos(theta_h)^n", NULL, "Blinn-Phong lobe: the reference of the Blinn family", 1 },
    { "cq2", BRDF_CQ2, "quadratic", LOBE_PSI, 0, NOP, "phong",
      "(n/2 (c-1) + 1)^2", "c = 1 - 2/n", "classic cosine-quadratic F2 (xi = 1/2)", 1 },
    { "fvol", BRDF_FVOL, "quadratic", LOBE_PSI, 0, NOP, "phong",
      "(0.463 n (c-1) + 1)^2", "c = 1 - 1/(0.463 n)", "F_VOL of paper 1 (xi = 0.463)", 1 },
    { "fvol64", BRDF_FVOL64, "quadratic", LOBE_PSI, 0, NOP, "phong",
      "(29/64 n (c-1) + 1)^2", "c = (29n - 64)/(29n)", "paper 1's cheap variant, xi = 29/64", 1 },
    { "schlick", BRDF_SCHLICK, "rational", LOBE_PSI, 0, NOP, "phong",
      "c / (n - n c + c)", NULL, "Schlick's rational approximation F_S", 1 },
    { "lyon", BRDF_LYON, "quadratic", LOBE_PSI, 1,
      { { "k", 1, 16, 2, 1, "number of squarings; the exponent is 2^k" } }, "phong",
      "(1 - n (1-c)/2^k)^(2^k)", "c = 1 - 2^k/n", "Lyon 1993, k squarings (k = 1 is cq2)", 1 },
    { "fq", BRDF_FQ, "quadratic", LOBE_PSI, 1,
      { { "Q", 1e-6, 0.999999, 0.64, 0, "level where f_Q equals c^n exactly" } }, "phong",
      "(k_Q(n) (c-1) + 1)^2, k_Q(n) = (sqrt(Q) - 1)/(Q^(1/n) - 1)", "c = 1 - 1/k_Q(n)",
      "f_Q of paper 2", 1 },
    { "fq2", BRDF_FQ2, "quadratic", LOBE_PSI, 0, NOP, "phong",
      "((0.448 n + 0.099)(c-1) + 1)^2", "c = (448n -901)/(448n + 99)",
      "f_Q2 of paper 2: linear fit of k_Q(n)", 1 },
    { "fq2n", BRDF_FQ2N, "normalised", LOBE_PSI, 0, NOP, "phongn",
      "0.214 (0.807 + n) ((0.448 n + 0.099)(c-1) + 1)^2", "c = (448n - 901)/(448n + 99)",
      "f_Q2 with paper 2's normalising coefficient", 1 },
    { "phongn", BRDF_PHONGN, "normalised", LOBE_PSI, 0, NOP, "phongn",
      "(n+2)/(2 pi) c^n", NULL, "energy-normalised Phong (reference of fq2n)", 1 },
    { "blinnn", BRDF_BLINNN, "normalised", LOBE_THETA_H, 0, NOP, "blinnn",
      "(n+2)(n+4) / (8 pi (2^(-n/2) + n)) c^n", NULL, "energy-normalised Blinn-Phong (Giesen)", 1 },
    { "beckmann", BRDF_BECKMANN, "microfacet", LOBE_THETA_H, 0, NOP, "phongn",
      "exp(-tan^2 / a^2) / (pi a^2 cos^4), a = sqrt(2/(n+2))", NULL,
      "Beckmann distribution D against normalised Blinn-Phong D", 1 },
    { "ggx", BRDF_GGX, "microfacet", LOBE_THETA_H, 0, NOP, "phongn",
      "a^2 / (pi cos^4 (a^2 + tan^2)^2), a = sqrt(2/(n+2))", NULL,
      "GGX distribution D against normalised Blinn-Phong D", 1 },
    { "quad", BRDF_QUAD, "quadratic", LOBE_PSI, 2,
      { { "a", 0, 10, 0.448, 0, "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.099, 0, "offset of k(n) = a n + b" } }, "phong",
      "((a n + b)(c-1) + 1)^2", "c = 1 - 1/(a n + b)",
      "the affine cosine-quadratic family (brdfbench fit)", 0 },
    { "phongpow", BRDF_PHONGPOW, "reference", LOBE_PSI, 0, NOP, "phong",
      "cos(psi)^n through OpenCL's pow()", NULL,
      "the Phong lobe through the pow() built-in: the literal pow()-based reference, for cost", 1 },
    { "sg", BRDF_SG, "gaussian", LOBE_PSI, 0, NOP, "phong",
      "exp(n (c-1))", NULL,
      "spherical Gaussian (Lagarde 2012, 'Spherical Gaussian approximation for Blinn-Phong, Phong and Fresnel'; "
      "engines write exp2(n/ln2 (c-1)))", 0 },
    { "ue4phong", BRDF_UE4PHONG, "gaussian", LOBE_PSI, 0, NOP, "phong",
      "exp((n + 0.775)(c-1))", NULL,
      "UE4 mobile PhongApprox (Karis 2014, 'Physically Based Shading on Mobile')", 0 },
    { "bg", BRDF_BG, "power", LOBE_PSI, 1,
      { { "j", 1, 4, 1, 1, "squarings: the exponent is m = 2^j" } }, "phong",
      "max(0, A c + 1 - A)^m, m = 2^j, A(n) = alpha_m n + beta_m", "c = 1 - 1/A",
      "Beaudoin and Guardado 2002 (ShaderX, 'A non-integer power function on the pixel shader'); A from the "
      "affine fit of their per-n bisection (kernels/brdf_models.h)", 0 },
    { "kb", BRDF_KB, "angular", LOBE_PSI, 0, NOP, "phong",
      "alpha = acos c: 1 - alpha^2/(ab) below a, (alpha-b)^2/(b(b-a)) to b, 0 beyond; "
      "a = (n+5.6)/(n(0.09n+5.2)), b = (n+65)/(5n+31.7)", "alpha = b",
      "Kuijk and Blake 1989 (Computer Graphics Forum 8(4)), a and b as docs/definitions.md writes them", 0 },
    { "kbswap", BRDF_KBSWAP, "angular", LOBE_PSI, 0, NOP, "phong",
      "kb with a and b exchanged, zeroed where negative", "alpha = sqrt(ab)",
      "Kuijk and Blake 1989 with a and b exchanged (Kuijk's later note on the print)", 0 },
    { "bitpow", BRDF_BITPOW, "bits", LOBE_PSI, 0, NOP, "phong",
      "the float whose bits are n (bits(c) - bits(1)) + bits(1)", "c^n < 2^-149",
      "integer-bit pow (Schraudolph 1999 style); the host reproduces the bit arithmetic in double", 0 },
    { "gauss", BRDF_GAUSS, "gaussian", LOBE_PSI, 2,
      { { "a", 0, 10, 1, 0, "slope of k(n) = a n + b" },
        { "b", -10, 10, 0, 0, "offset of k(n) = a n + b" } }, "phong",
      "exp((a n + b)(c-1))", NULL, "the Gaussian family (brdfbench fit; sg is a=1,b=0, ue4phong a=1,b=0.775)", 0 },
    { "pow3", BRDF_CUBE, "power", LOBE_PSI, 2,
      { { "a", 0, 10, 0.31, 0, "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.1, 0, "offset of k(n) = a n + b" } }, "phong",
      "((a n + b)(c-1) + 1)^3", "c = 1 - 1/(a n + b)", "the power family at m = 3 (brdfbench fit)", 0 },
    { "pow4", BRDF_QUART, "power", LOBE_PSI, 2,
      { { "a", 0, 10, 0.237, 0, "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.1, 0, "offset of k(n) = a n + b" } }, "phong",
      "((a n + b)(c-1) + 1)^4", "c = 1 - 1/(a n + b)", "the power family at m = 4 (brdfbench fit)", 0 },
    { "pow3fit", BRDF_CUBEFIT, "power", LOBE_PSI, 0, NOP, "phong",
      "((A3 n + B3)(c-1) + 1)^3, constants in kernels/brdf_models.h", "c = 1 - 1/(A3 n + B3)",
      "cube fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)", 0 },
    { "pow4fit", BRDF_QUARTFIT, "power", LOBE_PSI, 0, NOP, "phong",
      "((A4 n + B4)(c-1) + 1)^4, constants in kernels/brdf_models.h", "c = 1 - 1/(A4 n + B4)",
      "quart fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)", 0 },
    { "gaussfit", BRDF_GAUSSFIT, "gaussian", LOBE_PSI, 0, NOP, "phong",
      "exp((AG n + BG)(c-1)), constants in kernels/brdf_models.h", NULL,
      "gauss fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)", 0 },
    /* Physically based BRDFs f(N, L, V) (kernels/brdf_models.h, brdf_pb_eval). As lobes of one
       cosine they are the BRDF with the light at the normal and theta_h = acos(c); they are
       their own references and not part of the default set of the lobe commands. */
    { "ct-beckmann", BRDF_CT_BECKMANN, "physical", LOBE_THETA_H, 1,
      { { "F0", 0, 1, 0.5, 0, "Schlick's Fresnel reflectance at normal incidence" } }, "ct-beckmann",
      "D F G / (4 N.L N.V): Beckmann D, Schlick F, Smith G (Walter's rational form), a = sqrt(2/(n+2))", NULL,
      "Cook-Torrance in full with the Beckmann distribution (paper 1, eq. 7)", 0 },
    { "ct-ggx", BRDF_CT_GGX, "physical", LOBE_THETA_H, 1,
      { { "F0", 0, 1, 0.5, 0, "Schlick's Fresnel reflectance at normal incidence" } }, "ct-ggx",
      "D F G / (4 N.L N.V): GGX D, Schlick F, separable Smith G of GGX, a = sqrt(2/(n+2))", NULL,
      "Cook-Torrance in full with GGX (Walter et al. 2007; paper 1, eq. 8)", 0 },
    { "brady", BRDF_BRADY, "physical", LOBE_THETA_H, 2,
      { { "a", 0.01, 100, 1, 0, "lobe-shape parameter a of the printed form" },
        { "b", 0.01, 100, 1, 0, "lobe-shape parameter b of the printed form" } }, "brady",
      "D G / (a^-2 b^-2 tan^2(theta_h) + 0.9994), Beckmann D and its Smith G at a(n)", NULL,
      "Brady et al. 2014's metal BRDF as paper 2 prints it (the genBRDF original was not found; "
      "D and G are taken as Cook-Torrance's Beckmann pair)", 0 },
    { "he", BRDF_HE, "physical", LOBE_THETA_H, 1,
      { { "material", 0, BRDF_HE_PRESETS - 1, 0, 1,
          "preset: 0 rough aluminium, 1 polished aluminium, 2 gold, 3 plastic" } }, "he",
      "rho_sp + rho_dd + rho_ud of He, Torrance, Sillion, Greenberg 1991 (lambda, sigma0, tau, n + ik)", NULL,
      "He et al. 1991 (Kirchhoff diffraction; the directional-diffuse sum truncated at float resolution)", 0 },
};

_Static_assert(sizeof registry / sizeof registry[0] == BRDF_MODEL_COUNT - 1,
               "every model id except BRDF_USER has a registry entry");

int models_count(void) { return (int)(sizeof registry / sizeof registry[0]); }

const struct model_info *models_at(int i)
{
    return (i >= 0 && i < models_count()) ? &registry[i] : NULL;
}

static struct {
    const struct model_info *info;
    const struct model_runtime *rt;
} user_models[MODELS_MAX_USER];
static int user_model_count;

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
        if (strcmp(user_models[i].info->id, id) == 0)
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
    return spec->info->kernel_id == BRDF_PHONGPOW || models_runtime(spec->info) != NULL;
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
