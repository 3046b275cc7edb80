/* shaderlang_brdf.c - the shader-language translator (shaderlang.c): BRDF Explorer .brdf files. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "shaderlang_internal.h"
#include "exitcodes.h"
#include "mdbuf.h"
#include "models.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- BRDF Explorer .brdf files ------------------------------------------------------------ */

#define BRDF_MAX_FILE_PARAMS 32

struct brdf_param {
    int type;                  /* 'f' float, 'b' bool, 'c' color */
    char name[SL_NAME_MAX + 1];
    double v[3];               /* float: min max default; bool: value; color: r g b */
    int line;
};

static int brdf_fail(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int brdf_fail(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sl_vformat_at(err, errlen, path, line, -1, fmt, ap);
    va_end(ap);
    return EXIT_USAGE;
}

static int parse_finite(const char *t, double *v)
{
    char *end = NULL;
    *v = strtod(t, &end);
    return end != t && *end == '\0' && *v == *v && *v - *v == 0;
}

/* A BRDF Explorer file: "::begin parameters" (float NAME MIN MAX DEFAULT, bool NAME 0|1,
 * color NAME R G B) and "::begin shader" with vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y),
 * as a full BRDF reduced to a lobe of one cosine c (docs/user-models.md, "BRDF Explorer files"). */

/* How the lobe's n reaches a parameter of the file: the first float parameter named in this
   table takes it, converted as the engines convert their roughness axes (docs/user-models.md,
   "Roughness, alpha, m and n"); a file with none of these names is evaluated at its defaults
   and its lobe does not depend on n. */
enum brdf_conv { CONV_N, CONV_ALPHA, CONV_ROUGHNESS, CONV_F0 };
static const struct {
    const char *name;
    enum brdf_conv conv;
    int alone;   /* taken only when it is the file's one float parameter (a Fresnel term's) */
} brdf_lobe_params[] = {
    { "n", CONV_N, 0 },                 /* a Phong / Blinn-Phong exponent */
    { "alpha", CONV_ALPHA, 0 },         /* alpha = sqrt(2 / (n + 2)), the microfacet built-ins' width */
    { "alphaG", CONV_ALPHA, 0 },        /* Walter et al.'s GGX width */
    { "m", CONV_ALPHA, 0 },             /* Beckmann's rms slope m = alpha */
    { "roughness", CONV_ROUGHNESS, 0 }, /* the engines' roughness: alpha = roughness^2 */
    /* a Fresnel term's index of refraction, the axis of the built-in fresnel, and the reflectance
       at normal incidence of that index, ((n - 1) / (n + 1))^2; beside other floats (a full
       BRDF's F0) they keep their defaults */
    { "ior", CONV_N, 1 },
    { "f0", CONV_F0, 1 },
    { "F0", CONV_F0, 1 },
};

/* Where L and V lie for the lobe's cosine c (the header's lobe: key). */
enum brdf_geom {
    GEOM_THETA_H,   /* L = N, V at 2 theta_h from N: N.H = c (a D term, a full BRDF's highlight) */
    GEOM_PSI,       /* L = N, V at psi from R = N: N.V = R.V = c (a Phong lobe) */
    GEOM_THETA_D    /* L and V mirrored about N at theta = acos c: H = N, N.L = N.V = L.H = c (F, G and
                       diffuse terms, which L = N hides) */
};

/* The statement that opens a .brdf file's functions: the lobe parameter from n and the model
 * parameters from their arguments. */
static void brdf_set_params(struct md_buf *epi, int lobe_param, enum brdf_conv conv, const struct brdf_param *prm,
                            const int *model_params, int nmp)
{
    if (lobe_param >= 0) {
        const char *v = prm[lobe_param].name;
        switch (conv) {
        case CONV_N:
            md_printf(epi, "%s = brdfbench_n; ", v);
            break;
        case CONV_ALPHA:
            md_printf(epi, "%s = sqrt(2.0 / (brdfbench_n + 2.0)); ", v);
            break;
        case CONV_ROUGHNESS:
            md_printf(epi, "%s = sqrt(sqrt(2.0 / (brdfbench_n + 2.0))); ", v);
            break;
        case CONV_F0:
            md_printf(epi, "%s = ((brdfbench_n - 1.0) / (brdfbench_n + 1.0)) * ((brdfbench_n - 1.0) / "
                           "(brdfbench_n + 1.0)); ", v);
            break;
        }
    }
    for (int i = 0; i < nmp; ++i)
        md_printf(epi, prm[model_params[i]].type == 'b' ? "%s = brdfbench_p%d != 0.0; " : "%s = brdfbench_p%d; ",
                  prm[model_params[i]].name, i);
}

/* What a .brdf file declares: its parameters, where its shader block lies, which parameters take
   the lobe's n and the model's parameters, and the lobe's geometry. */
struct brdf_doc {
    struct brdf_param prm[BRDF_MAX_FILE_PARAMS];
    int nprm, shader_line;
    size_t shader_start, shader_end;
    int lobe_param, model_params[SL_MAX_PARAMS], nmp;
    enum brdf_conv conv;
    enum brdf_geom geom;
};

/* One line of the parameters block (t, trimmed, split in place): a float, bool or color. */
static int brdf_param_line(char *t, int line, struct brdf_doc *D, const char *path, char *err, size_t errlen)
{
    struct brdf_param *prm = D->prm;
    char *save = NULL, *w[6];
    int nw = 0;
    for (char *x = strtok_r(t, " \t", &save); x && nw < 6; x = strtok_r(NULL, " \t", &save))
        w[nw++] = x;
    if (D->nprm == BRDF_MAX_FILE_PARAMS)
        return brdf_fail(err, errlen, path, line, "more than %d parameters", BRDF_MAX_FILE_PARAMS);
    struct brdf_param *q = &prm[D->nprm];
    memset(q, 0, sizeof *q);
    q->line = line;
    int want = 0;
    if (strcmp(w[0], "float") == 0) {
        q->type = 'f';
        want = 5;
    } else if (strcmp(w[0], "bool") == 0) {
        q->type = 'b';
        want = 3;
    } else if (strcmp(w[0], "color") == 0) {
        q->type = 'c';
        want = 5;
    } else {
        return brdf_fail(err, errlen, path, line, "unknown parameter type '%.40s' (accepted: float NAME MIN "
                         "MAX DEFAULT, bool NAME 0|1, color NAME R G B)", w[0]);
    }
    if (nw != want)
        return brdf_fail(err, errlen, path, line, "%s takes %d values after its type (%s), found %d",
                         w[0], want - 1, q->type == 'f' ? "NAME MIN MAX DEFAULT" : q->type == 'b' ? "NAME 0|1" :
                         "NAME R G B", nw - 1);
    if (!sl_valid_identifier(w[1]) || strncmp(w[1], "brdfbench_", 10) == 0 || strncmp(w[1], "u__", 3) == 0 ||
        strncmp(w[1], "sl_", 3) == 0)
        return brdf_fail(err, errlen, path, line, "parameter name '%.60s' is not an identifier of 1 to %d "
                         "characters or is reserved (brdfbench_*, sl_*, u__*)", w[1], SL_NAME_MAX);
    for (int k = 0; k < D->nprm; ++k)
        if (strcmp(prm[k].name, w[1]) == 0)
            return brdf_fail(err, errlen, path, line, "parameter '%s' is declared twice", w[1]);
    snprintf(q->name, sizeof q->name, "%s", w[1]);
    for (int k = 2; k < nw; ++k)
        if (!parse_finite(w[k], &q->v[k - 2]))
            return brdf_fail(err, errlen, path, line, "parameter '%s': '%.40s' is not a finite number",
                             q->name, w[k]);
    if (q->type == 'f' && !(q->v[0] < q->v[1] && q->v[2] >= q->v[0] && q->v[2] <= q->v[1]))
        return brdf_fail(err, errlen, path, line, "parameter '%s': MIN < MAX and MIN <= DEFAULT <= MAX "
                         "expected (found %g %g %g)", q->name, q->v[0], q->v[1], q->v[2]);
    if (q->type == 'b' && q->v[0] != 0 && q->v[0] != 1)
        return brdf_fail(err, errlen, path, line, "bool '%s' is 0 or 1, not %g", q->name, q->v[0]);
    ++D->nprm;
    return 0;
}

/* The file line by line: the ::begin/::end blocks, the parameters, and where the shader
   block lies. */
static int brdf_blocks(const char *text, size_t len, const char *path, struct brdf_doc *D, char *err,
                       size_t errlen)
{
    int in_params = 0, in_shader = 0, seen_params = 0, line = 0;
    const char *p = text, *end = text + len;
    while (p < end) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        if (!eol)
            eol = end;
        ++line;
        char buf[512];
        size_t n = (size_t)(eol - p);
        if (n >= sizeof buf)
            n = sizeof buf - 1;
        memcpy(buf, p, n);
        buf[n] = '\0';
        char *t = buf;
        while (*t == ' ' || *t == '\t' || *t == '\r')
            ++t;
        size_t tl = strlen(t);
        while (tl > 0 && (t[tl - 1] == ' ' || t[tl - 1] == '\t' || t[tl - 1] == '\r'))
            t[--tl] = '\0';
        if (in_shader) {
            if (strcmp(t, "::end shader") == 0) {
                in_shader = 2;
                D->shader_end = (size_t)(p - text);
            }
        } else if (strncmp(t, "::", 2) == 0) {
            if (strcmp(t, "::begin parameters") == 0) {
                if (in_params || seen_params)
                    return brdf_fail(err, errlen, path, line, "a second ::begin parameters");
                in_params = seen_params = 1;
            } else if (strcmp(t, "::end parameters") == 0) {
                if (!in_params)
                    return brdf_fail(err, errlen, path, line, "::end parameters without ::begin parameters");
                in_params = 0;
            } else if (strcmp(t, "::begin shader") == 0) {
                if (in_params)
                    return brdf_fail(err, errlen, path, line, "::begin shader inside the parameters (no ::end parameters)");
                if (D->shader_line)
                    return brdf_fail(err, errlen, path, line, "a second ::begin shader");
                in_shader = 1;
                D->shader_line = line + 1;
                D->shader_start = (size_t)(eol - text) + (eol < end);
            } else {
                return brdf_fail(err, errlen, path, line, "unknown block line '%.60s' (accepted: ::begin/::end "
                                 "parameters, ::begin/::end shader)", t);
            }
        } else if (in_params && *t && *t != '#' && strncmp(t, "//", 2) != 0) {
            int rc = brdf_param_line(t, line, D, path, err, errlen);
            if (rc)
                return rc;
        }
        p = eol + (eol < end);
    }
    if (in_params)
        return brdf_fail(err, errlen, path, 0, "::begin parameters is not closed by ::end parameters");
    if (!D->shader_line)
        return brdf_fail(err, errlen, path, 0, "no ::begin shader block (a BRDF Explorer file holds vec3 BRDF(vec3 L, "
                         "vec3 V, vec3 N, vec3 X, vec3 Y) there)");
    if (in_shader != 2)
        return brdf_fail(err, errlen, path, D->shader_line - 1, "::begin shader is not closed by ::end shader");
    return 0;
}

/* The lobe parameter (brdf_lobe_params: the first name of the table the file declares as a
   float), then up to two other floats as the model's parameters, then bools while there is room
   (an integer parameter in [0, 1], so that a user can switch a file's option, e.g. blinnphong's
   divide_by_NdotL); the rest, and the colours, keep their defaults. A file without a lobe parameter is accepted: its lobe is the
   BRDF at its defaults, whatever n. */
static void brdf_choose_params(struct brdf_doc *D)
{
    const struct brdf_param *prm = D->prm;
    int nfloat = 0;
    for (int k = 0; k < D->nprm; ++k)
        nfloat += prm[k].type == 'f';
    D->lobe_param = -1;
    D->nmp = 0;
    for (size_t t = 0; t < sizeof brdf_lobe_params / sizeof brdf_lobe_params[0] && D->lobe_param < 0; ++t)
        for (int k = 0; k < D->nprm && (!brdf_lobe_params[t].alone || nfloat == 1); ++k)
            if (prm[k].type == 'f' && strcmp(prm[k].name, brdf_lobe_params[t].name) == 0) {
                D->lobe_param = k;
                D->conv = brdf_lobe_params[t].conv;
                break;
            }
    for (int k = 0; k < D->nprm; ++k) {
        if (prm[k].type != 'f' || k == D->lobe_param)
            continue;
        if (D->nmp < SL_MAX_PARAMS)
            D->model_params[D->nmp++] = k;
    }
    for (int k = 0; k < D->nprm && D->nmp < SL_MAX_PARAMS; ++k)
        if (prm[k].type == 'b')
            D->model_params[D->nmp++] = k;
}

/* The keys a .brdf file's header comment (the brdfbench-model comment that opens its shader
   block) may hold: its parameters are those of the ::begin parameters block and its function is
   BRDF, so param and function are not among them. */
#define BRDF_HEADER_KEYS "name, reference, lobe, description"

/* Checks the header comment at the start of the shader block, if it is one, key by key (the
   reader of headers, sl_read_header, skips what it does not know), and reads its lobe. line is
   the file's line of the shader block's first line. */
static int brdf_check_header(const char *text, size_t len, int line, const char *path, struct brdf_doc *D,
                             char *err, size_t errlen)
{
    D->geom = GEOM_THETA_H;
    size_t i = 0;
    while (i < len && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
        if (text[i++] == '\n')
            ++line;
    if (i + 2 > len || text[i] != '/' || text[i + 1] != '*')
        return 0;
    const char *p = text + i + 2, *end = text + len;
    const char *close = NULL;
    for (const char *q = p; q + 1 < end && !close; ++q)
        if (q[0] == '*' && q[1] == '/')
            close = q;
    if (!close)
        return 0;
    int seen[4] = { 0, 0, 0, 0 };
    static const char *keys[4] = { "name", "reference", "lobe", "description" };
    for (int first = 1; p < close; first = 0, ++line) {
        const char *eol = memchr(p, '\n', (size_t)(close - p));
        if (!eol)
            eol = close;
        char buf[256];
        size_t n = (size_t)(eol - p) < sizeof buf - 1 ? (size_t)(eol - p) : sizeof buf - 1;
        memcpy(buf, p, n);
        buf[n] = '\0';
        p = eol + 1;
        char *a = buf;
        while (*a == ' ' || *a == '\t' || *a == '\r')
            ++a;
        if (!first && *a == '*')
            ++a;
        while (*a == ' ' || *a == '\t')
            ++a;
        size_t al = strlen(a);
        while (al > 0 && (a[al - 1] == ' ' || a[al - 1] == '\t' || a[al - 1] == '\r'))
            a[--al] = '\0';
        if (first) {
            if (strcmp(a, "brdfbench-model") != 0)
                return 0; /* an ordinary comment */
            continue;
        }
        if (!*a)
            continue;
        char *colon = strchr(a, ':');
        if (!colon)
            return brdf_fail(err, errlen, path, line, "expected 'key: value' in the brdfbench-model header "
                             "(keys of a .brdf file: " BRDF_HEADER_KEYS "), found '%.40s'", a);
        char *ke = colon;
        while (ke > a && (ke[-1] == ' ' || ke[-1] == '\t'))
            --ke;
        *ke = '\0';
        char *v = colon + 1;
        while (*v == ' ' || *v == '\t')
            ++v;
        int k = 0;
        while (k < 4 && strcmp(a, keys[k]) != 0)
            ++k;
        if (k == 4)
            return brdf_fail(err, errlen, path, line, "unknown header key '%.40s' (accepted in a .brdf file: "
                             BRDF_HEADER_KEYS "; its parameters are those of ::begin parameters)", a);
        if (seen[k]++)
            return brdf_fail(err, errlen, path, line, "'%s' is declared twice", keys[k]);
        /* the rule of a model file's reference (usermodel.c), said here at the file's own line:
           the translation's header has lines of its own */
        const struct model_info *ref = k == 1 ? models_find(v) : NULL;
        if (k == 1 && (!ref || !model_is_builtin(ref)))
            return brdf_fail(err, errlen, path, line, "reference '%.40s' is not a built-in model (see brdfbench "
                             "list)", v);
        if (k == 2) {
            if (strcmp(v, "theta_h") == 0)
                D->geom = GEOM_THETA_H;
            else if (strcmp(v, "psi") == 0)
                D->geom = GEOM_PSI;
            else if (strcmp(v, "theta_d") == 0)
                D->geom = GEOM_THETA_D;
            else
                return brdf_fail(err, errlen, path, line, "lobe '%.40s' is unknown (accepted in a .brdf file: "
                                 "theta_h, psi, theta_d)", v);
        }
    }
    return 0;
}

/* The model's header comment: name, description, reference and its parameters. */
static void brdf_header_text(struct md_buf *hb, const struct header *sh, const char *name, const struct brdf_doc *D)
{
    static const char *geom_text[] = { "L = N, theta_h = acos(c)", "L = N, psi = acos(N.V) = acos(c)",
                                       "L and V mirrored about N at acos(c)" };
    md_printf(hb, "/* brdfbench-model\n * name: %s\n * function: brdfbench_lobe\n", sh->name[0] ? sh->name : name);
    if (sh->description[0]) {
        md_printf(hb, " * description: %s\n", sh->description);
    } else {
        md_printf(hb, " * description: BRDF Explorer file: luminance of BRDF at %s", geom_text[D->geom]);
        if (D->lobe_param >= 0) {
            static const char *conv_text[] = { "n", "sqrt(2/(n+2))", "(2/(n+2))^(1/4)", "((n-1)/(n+1))^2" };
            md_printf(hb, ", %s = %s", D->prm[D->lobe_param].name, conv_text[D->conv]);
        } else {
            md_printf(hb, ", at its defaults (no parameter takes n)");
        }
        md_printf(hb, "\n");
    }
    /* psi is the lobe variable of a Phong lobe, whose reference is phong; the others are theta_h
       for the registry (a full BRDF is shaded from its vectors) */
    md_printf(hb, " * reference: %s\n * lobe: %s\n",
              sh->reference[0] ? sh->reference : D->geom == GEOM_PSI ? "phong" : "blinn",
              D->geom == GEOM_PSI ? "psi" : "theta_h");
    for (int i = 0; i < D->nmp; ++i) {
        const struct brdf_param *q = &D->prm[D->model_params[i]];
        if (q->type == 'b')
            md_printf(hb, " * param: %s 0 1 %d integer\n", q->name, q->v[0] != 0);
        else
            md_printf(hb, " * param: %s %.17g %.17g %.17g\n", q->name, q->v[0], q->v[1], q->v[2]);
    }
    md_printf(hb, " */\n");
}

/* The parameters as globals; the lobe function sets those it takes, the rest are constants. */
static void brdf_prelude(struct md_buf *pre, const struct brdf_doc *D)
{
    for (int k = 0; k < D->nprm; ++k) {
        const struct brdf_param *q = &D->prm[k];
        int taken = k == D->lobe_param;
        for (int i = 0; i < D->nmp; ++i)
            taken |= D->model_params[i] == k;
        if (taken)
            md_printf(pre, "%s %s; ", q->type == 'b' ? "bool" : "float", q->name);
        else if (q->type == 'f')
            md_printf(pre, "const float %s = %.17g; ", q->name, q->v[2]);
        else if (q->type == 'b')
            md_printf(pre, "const bool %s = %s; ", q->name, q->v[0] != 0 ? "true" : "false");
        else
            md_printf(pre, "const vec3 %s = vec3(%.17g, %.17g, %.17g); ", q->name, q->v[0], q->v[1], q->v[2]);
    }
}

/* The lobe function (BRDF's luminance at the geometry of D->geom) and the full function after
   the shader. */
static void brdf_epilogue(struct md_buf *epi, const struct brdf_doc *D)
{
    int nmp = D->nmp;
    md_printf(epi, "float brdfbench_lobe(float brdfbench_c, float brdfbench_n");
    for (int i = 0; i < nmp; ++i)
        md_printf(epi, ", float brdfbench_p%d", i);
    md_printf(epi, ") { ");
    brdf_set_params(epi, D->lobe_param, D->conv, D->prm, D->model_params, nmp);
    md_printf(epi, "vec3 brdfbench_N = vec3(0.0, 0.0, 1.0); "
                   "float brdfbench_sn = sqrt(max((1.0 - brdfbench_c) * (1.0 + brdfbench_c), 0.0)); ");
    switch (D->geom) {
    case GEOM_THETA_H:
        /* L = N, V at 2 theta_h from N in the XZ plane: N.V = 2c^2 - 1, N.H = V.H = c */
        md_printf(epi, "float brdfbench_nv = 2.0 * brdfbench_c * brdfbench_c - 1.0; "
                       "vec3 brdfbench_L = brdfbench_N; "
                       "vec3 brdfbench_V = vec3(2.0 * brdfbench_c * brdfbench_sn, 0.0, brdfbench_nv); ");
        break;
    case GEOM_PSI:
        /* L = N, so R = N and V at psi from it: N.V = c */
        md_printf(epi, "float brdfbench_nv = brdfbench_c; "
                       "vec3 brdfbench_L = brdfbench_N; "
                       "vec3 brdfbench_V = vec3(brdfbench_sn, 0.0, brdfbench_c); ");
        break;
    case GEOM_THETA_D:
        /* L and V mirrored about N in the XZ plane: H = N, N.L = N.V = L.H = c */
        md_printf(epi, "float brdfbench_nv = brdfbench_c; "
                       "vec3 brdfbench_L = vec3(-brdfbench_sn, 0.0, brdfbench_c); "
                       "vec3 brdfbench_V = vec3(brdfbench_sn, 0.0, brdfbench_c); ");
        break;
    }
    /* V on or below the horizon is outside the BRDF's domain: the lobe is 0 there */
    md_printf(epi, "vec3 brdfbench_rgb = BRDF(brdfbench_L, brdfbench_V, brdfbench_N, vec3(1.0, 0.0, 0.0), "
                   "vec3(0.0, 1.0, 0.0)); "
                   "float brdfbench_y = dot(brdfbench_rgb, vec3(0.2126, 0.7152, 0.0722)); "
                   "return brdfbench_nv > 0.0 ? brdfbench_y : 0.0; }");
    sl_full_function_open(epi, nmp);
    brdf_set_params(epi, D->lobe_param, D->conv, D->prm, D->model_params, nmp);
    md_printf(epi, "return dot(BRDF(brdfbench_L, brdfbench_V, brdfbench_N, brdfbench_X, brdfbench_Y), "
                   "vec3(0.2126, 0.7152, 0.0722)); }");
}

static int brdf_file(const char *text, size_t len, const char *path, const char *name, char **out, size_t *outlen,
                     char *err, size_t errlen)
{
    struct brdf_doc D;
    memset(&D, 0, sizeof D);
    int rc = brdf_blocks(text, len, path, &D, err, errlen);
    if (rc)
        return rc;
    brdf_choose_params(&D);
    if ((rc = brdf_check_header(text + D.shader_start, D.shader_end - D.shader_start, D.shader_line, path, &D, err,
                                errlen)) != 0)
        return rc;
    struct header sh;
    sl_read_header(text + D.shader_start, D.shader_end - D.shader_start, &sh);
    struct md_buf hb, pre, epi;
    md_init(&hb);
    md_init(&pre);
    md_init(&epi);
    brdf_header_text(&hb, &sh, name, &D);
    brdf_prelude(&pre, &D);
    brdf_epilogue(&epi, &D);
    if (hb.failed || pre.failed || epi.failed) {
        rc = brdf_fail(err, errlen, path, 0, "out of memory");
    } else {
        struct header h;
        memset(&h, 0, sizeof h);
        h.present = 1;
        snprintf(h.function, sizeof h.function, "brdfbench_lobe");
        h.nparams = D.nmp;
        for (int i = 0; i < D.nmp; ++i) {
            snprintf(h.params[i], sizeof h.params[i], "%s", D.prm[D.model_params[i]].name);
            h.integer[i] = D.prm[D.model_params[i]].type == 'b';
        }
        h.header_text = hb.s;
        h.prelude = pre.s ? pre.s : "";
        h.epilogue = epi.s;
        h.first_line = D.shader_line;
        struct sl S;
        memset(&S, 0, sizeof S);
        S.err = err;
        S.errlen = errlen;
        S.origin = path;
        rc = sl_translate(&S, text + D.shader_start, D.shader_end - D.shader_start, &h, sh.name[0] ? sh.name : name,
                          out, outlen);
        sl_free(&S);
    }
    md_free(&hb);
    md_free(&pre);
    md_free(&epi);
    return rc;
}

int shaderlang_file(const char *text, size_t len, const char *path, char **out, size_t *outlen, char *err,
                    size_t errlen)
{
    *out = NULL;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *ext = strrchr(base, '.');
    static const char *shader_ext[] = { ".glsl", ".hlsl", ".frag", ".fx", ".fxh", ".hlsli", ".brdf", NULL };
    int shader = 0, is_brdf = ext && strcmp(ext, ".brdf") == 0;
    for (int i = 0; ext && shader_ext[i]; ++i)
        if (strcmp(ext, shader_ext[i]) == 0)
            shader = 1;
    if (!shader) {
        if (ext && strcmp(ext, ".cl") == 0)
            return SHADERLANG_NOT_SHADER;
        if (sl_uses_word(text, len, "REAL") || sl_uses_word(text, len, "RSCALAR"))
            return SHADERLANG_NOT_SHADER;
    }
    struct header h;
    if (is_brdf)
        memset(&h, 0, sizeof h); /* its header, if any, is in the shader block */
    else
        sl_read_header(text, len, &h);
    char name[SL_NAME_MAX + 1] = "";
    if (h.present && h.name[0]) {
        snprintf(name, sizeof name, "%s", h.name);
    } else if (!h.present) {
        size_t n = strcspn(base, ".");
        if (n == 0 || n > SL_NAME_MAX) {
            snprintf(err, errlen, "%s: the model needs a name: the file's name up to its first dot has %zu "
                     "characters (1 to %d accepted), or begin the file with /* brdfbench-model name: NAME */",
                     path, n, SL_NAME_MAX);
            return EXIT_USAGE;
        }
        snprintf(name, sizeof name, "%.*s", (int)n, base);
        if (!sl_valid_identifier(name)) {
            snprintf(err, errlen, "%s: the model is named after its file, and '%s' is not an identifier (letters, "
                     "digits, _): rename the file or begin it with /* brdfbench-model name: NAME */", path, name);
            return EXIT_USAGE;
        }
    } else {
        /* a header without a name: usermodel.c reports it */
        snprintf(name, sizeof name, "unnamed");
    }
    if (is_brdf)
        return brdf_file(text, len, path, name, out, outlen, err, errlen);
    struct sl S;
    memset(&S, 0, sizeof S);
    S.err = err;
    S.errlen = errlen;
    S.origin = path;
    int rc = sl_translate(&S, text, len, &h, name, out, outlen);
    sl_free(&S);
    return rc;
}

int shaderlang_expression(const char *name, const char *expr, const char *origin, char **out, size_t *outlen,
                          char *err, size_t errlen)
{
    *out = NULL;
    struct header h;
    memset(&h, 0, sizeof h);
    struct sl S;
    memset(&S, 0, sizeof S);
    S.err = err;
    S.errlen = errlen;
    S.origin = origin;
    size_t len = strlen(expr);
    int rc = sl_translate(&S, expr, len, &h, name, out, outlen);
    if (rc && !S.statement_form && !S.shader_only && !memchr(expr, ';', len) && !memchr(expr, '{', len))
        rc = SHADERLANG_NOT_SHADER; /* OpenCL C as before: its compiler has the last word */
    sl_free(&S);
    return rc;
}
