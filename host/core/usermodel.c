/* usermodel.c - parsing, registering, building and evaluating user-defined models
 * (see usermodel.h and docs/user-models.md). */
#define _POSIX_C_SOURCE 200809L
#include "usermodel.h"
#include "exitcodes.h"
#include "infile.h"
#include "mdbuf.h"
#include "outdir.h"
#include "shaderlang.h"
#include "usermodel_check.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The model ids (BRDF_USER); the header's functions are not used here. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

/* The registered user models are the model registry's (models.c: models_user_at), one table for
   both: a user model's info is its first member. */
static struct user_model *registry_at(int i) { return (struct user_model *)usermodel_at(i); }

/* ---- small text helpers ------------------------------------------------------------- */

static int is_ident_start(int c) { return isalpha(c) || c == '_'; }
static int is_ident_char(int c) { return isalnum(c) || c == '_'; }

/* 1 when s is a C identifier of 1 to max characters. */
static int is_identifier(const char *s, size_t max)
{
    size_t n = strlen(s);
    if (n == 0 || n > max || !is_ident_start((unsigned char)s[0]))
        return 0;
    for (size_t i = 1; i < n; ++i)
        if (!is_ident_char((unsigned char)s[i]))
            return 0;
    return 1;
}

/* Names the user's text may not take: the evaluation's own variables and words of the
 * generated code, so that a name never shadows them. */
static int is_reserved_name(const char *s)
{
    static const char *words[] = { "c", "n", "p0", "p1", "REAL", "RSCALAR", "RC", "RSPLAT", "all",
                                   "brdf_eval", "brdf_user_eval", "float", "double", "int", "return",
                                   "if", "else", "for", "while", "do", "switch", "case", "static",
                                   "inline", "const", "void", "kernel", "__kernel", NULL };
    for (int i = 0; words[i]; ++i)
        if (strcmp(s, words[i]) == 0)
            return 1;
    return strncmp(s, "brdf_", 5) == 0 || strncmp(s, "BRDF_", 5) == 0;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r')
        ++s;
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r'))
        s[--n] = '\0';
    return s;
}

/* A strict number: the whole token, finite, no ERANGE. */
static int parse_number(const char *t, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(t, &end);
    if (*t == '\0' || end == t || *end != '\0' || errno == ERANGE || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

/* A file name as the string of a #line directive: quotes and backslashes escaped. */
static void line_directive(struct md_buf *b, int line, const char *name)
{
    md_printf(b, "\n#line %d \"", line);
    for (const char *p = name; *p; ++p) {
        if (*p == '"' || *p == '\\')
            md_append(b, "\\", 1);
        md_append(b, p, 1);
    }
    md_append(b, "\"\n", 2);
}

/* ---- the model_info of a user model --------------------------------------------------- */

static struct user_model *usermodel_new(void)
{
    struct user_model *um = calloc(1, sizeof *um);
    if (!um)
        return NULL;
    snprintf(um->reference, sizeof um->reference, "phong");
    return um;
}

/* Points the embedded model_info at the model's own strings. */
static void usermodel_fill_info(struct user_model *um)
{
    struct model_info *in = &um->info;
    in->id = um->name;
    in->kernel_id = BRDF_USER;
    in->family = MODEL_FAMILY_USER;
    in->reference_id = um->reference;
    in->formula = um->formula;
    in->root = NULL;
    in->description = um->description;
    in->in_default_set = 0;
    for (int p = 0; p < in->nparams; ++p) {
        in->params[p].name = um->param_names[p];
        in->params[p].meaning = "declared by the model file";
    }
}

/* The host reference's sandbox (hostjit.h) lost its process: the model's code crashed it.
   Its values are gone, so the run ends as at a runaway kernel: one line, the unfinished
   outputs removed, exit 3. */
static _Noreturn void host_reference_died(const struct user_model *um, double c, double n)
{
    fprintf(stderr, "brdfbench: the host reference of %s failed near c = %.9g, n = %.9g: %s; the run is "
            "stopped and its unfinished outputs removed\n", um->what, c, n,
            hostjit_failure(um->host) ? hostjit_failure(um->host) : "its sandbox failed");
    outdir_remove_own();
    fflush(NULL);
    _exit(EXIT_RUNTIME);
}

/* ---- the runtime that the registry sees ----------------------------------------------- */

#define UM_OF_RUNTIME(rt) ((struct user_model *)((char *)(rt) - offsetof(struct user_model, runtime)))

static double runtime_eval(const struct model_runtime *rt, const struct model_spec *spec, double c, double n)
{
    (void)rt;
    return usermodel_eval_host(spec, c, n);
}

static int runtime_open(const struct model_runtime *rt, struct cl_session *s)
{
    struct user_model *um = UM_OF_RUNTIME(rt);
    if (usermodel_host_ready(um))
        return 0;
    return usermodel_reference_open(um, s);
}

static void runtime_close(const struct model_runtime *rt, struct cl_session *s)
{
    struct user_model *um = UM_OF_RUNTIME(rt);
    if (um->ref_session == s)
        usermodel_reference_close(um);
}

static const char *runtime_note(const struct model_runtime *rt) { return usermodel_reference_note(UM_OF_RUNTIME(rt)); }

static int runtime_on_device(const struct model_runtime *rt) { return !usermodel_host_ready(UM_OF_RUNTIME(rt)); }

static double runtime_eval_full(const struct model_runtime *rt, const struct model_spec *spec, const double L[3],
                                const double V[3], const double N[3], double n)
{
    const struct user_model *um = UM_OF_RUNTIME(rt);
    if (!usermodel_host_ready(um) || !hostjit_full_function(um->host))
        return NAN;
    usermodel_watch_begin(um, NAN, n);   /* the host reference's deadline (usermodel_check.h) */
    double a[12] = { L[0], L[1], L[2], V[0], V[1], V[2], N[0], N[1], N[2], n, spec->params[0], spec->params[1] };
    double v = NAN;
    if (hostjit_eval_full(um->host, a, &v) != 0)
        host_reference_died(um, NAN, n);
    usermodel_watch_end();
    return v;
}

/* Called once the model's text (device_source) and origin are known. */
static void usermodel_fill_runtime(struct user_model *um)
{
    snprintf(um->what, sizeof um->what, "user model '%s' (%s)", um->name, um->origin);
    um->runtime.device_source = um->device_source;
    um->runtime.device_options = um->full ? USERMODEL_FLOAT_OPTIONS USERMODEL_FULL_OPTION : USERMODEL_FLOAT_OPTIONS;
    um->runtime.what = um->what;
    um->runtime.eval_host = runtime_eval;
    um->runtime.open_host = runtime_open;
    um->runtime.close_host = runtime_close;
    um->runtime.note = runtime_note;
    um->runtime.eval_on_device = runtime_on_device;
    um->runtime.eval_full_host = um->full ? runtime_eval_full : NULL;
    um->runtime.isolated = usermodel_isolated;
    um->runtime.lobe_declared = um->lobe_declared;
    um->runtime.fp16 = strstr(um->device_source, "RHALF(") != NULL;
}

int usermodel_host_ready(const struct user_model *cum)
{
    /* Every user model is allocated by this file: its host state may change. */
    struct user_model *um = (struct user_model *)cum;
    if (!um->host_tried) {
        um->host_tried = 1;
        char *header = clsession_kernel_source("brdf_models.h", NULL);
        if (!header) {
            snprintf(um->host_error, sizeof um->host_error, "kernel header brdf_models.h not found");
            return 0;
        }
        um->host = hostjit_compile(header, um->device_source, um->host_error, sizeof um->host_error);
        free(header);
    }
    return um->host != NULL;
}

void usermodel_free(struct user_model *um)
{
    if (!um)
        return;
    usermodel_reference_close(um);
    hostjit_free(um->host);
    free(um->device_source);
    free(um);
}

/* ---- model files ---------------------------------------------------------------------- */

static int file_fail(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int file_fail(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(err, errlen, "%s:%d: %s", path, line, msg);
    else
        snprintf(err, errlen, "%s: %s", path, msg);
    return EXIT_USAGE;
}

/* One "param: NAME MIN MAX DEFAULT [integer]" line. generated: the header was written by the
   translator (shaderlang.h) for a .brdf file, whose parameter names it checked; there NAME only
   labels the value (the code takes it as p0 or p1), so c and n are names like others (BRDF
   Explorer's c). */
static int parse_param_line(struct user_model *um, char *value, const char *path, int line, char *err,
                            size_t errlen, int generated)
{
    static const char *form = "expected 'param: NAME MIN MAX DEFAULT [integer]'";
    char *tok[6];
    int count = 0;
    char *save = NULL;
    for (char *t = strtok_r(value, " \t", &save); t; t = strtok_r(NULL, " \t", &save)) {
        if (count == 5)
            return file_fail(err, errlen, path, line, "too many words in a parameter declaration; %s", form);
        tok[count++] = t;
    }
    if (count < 4)
        return file_fail(err, errlen, path, line, "too few words in a parameter declaration; %s", form);
    if (um->info.nparams >= MODEL_MAX_PARAMS)
        return file_fail(err, errlen, path, line, "more than %d parameters (accepted: 0 to %d)",
                         MODEL_MAX_PARAMS, MODEL_MAX_PARAMS);
    if (!is_identifier(tok[0], USERMODEL_NAME_MAX) || (!generated && is_reserved_name(tok[0])))
        return file_fail(err, errlen, path, line,
                         "parameter name '%.60s' is not an identifier of 1 to %d characters or is reserved "
                         "(c, n, p0, p1, brdf_*)", tok[0], USERMODEL_NAME_MAX);
    for (int p = 0; p < um->info.nparams; ++p)
        if (strcmp(um->param_names[p], tok[0]) == 0)
            return file_fail(err, errlen, path, line, "parameter '%s' is declared twice", tok[0]);
    double v[3];
    static const char *what[3] = { "MIN", "MAX", "DEFAULT" };
    for (int k = 0; k < 3; ++k)
        if (parse_number(tok[1 + k], &v[k]))
            return file_fail(err, errlen, path, line, "parameter '%s': %s '%.40s' is not a finite number",
                             tok[0], what[k], tok[1 + k]);
    int integer = 0;
    if (count == 5) {
        if (strcmp(tok[4], "integer") != 0)
            return file_fail(err, errlen, path, line, "parameter '%s': unknown word '%.40s'; %s", tok[0], tok[4],
                             form);
        integer = 1;
    }
    if (!(v[0] < v[1]))
        return file_fail(err, errlen, path, line, "parameter '%s': MIN %g must be below MAX %g", tok[0], v[0], v[1]);
    if (v[2] < v[0] || v[2] > v[1] || (integer && v[2] != floor(v[2])))
        return file_fail(err, errlen, path, line, "parameter '%s': DEFAULT %g is not %s in [%g, %g]", tok[0],
                         v[2], integer ? "an integer" : "a number", v[0], v[1]);
    int p = um->info.nparams++;
    snprintf(um->param_names[p], sizeof um->param_names[p], "%s", tok[0]);
    um->info.params[p].min = v[0];
    um->info.params[p].max = v[1];
    um->info.params[p].def = v[2];
    um->info.params[p].integer = integer;
    return 0;
}

/* 1 when text holds `name` as a whole identifier followed (after blanks) by '('. */
static int has_call_or_definition(const char *text, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = strstr(text, name); p; p = strstr(p + 1, name)) {
        if (p > text && is_ident_char((unsigned char)p[-1]))
            continue;
        const char *q = p + n;
        if (is_ident_char((unsigned char)*q))
            continue;
        while (*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r')
            ++q;
        if (*q == '(')
            return 1;
    }
    return 0;
}

/* A full BRDF's wrappers: brdf_user_full for the kernels, brdfbench_host_full for the host's
 * double build (hostjit.h). */
static void full_wrapper(struct md_buf *b, const struct user_model *um)
{
    const char *pp = um->info.nparams > 1 ? ", p0, p1" : um->info.nparams > 0 ? ", p0" : "";
    md_printf(b, "BRDF_FN REAL brdf_user_full(REAL lx, REAL ly, REAL lz, REAL vx, REAL vy, REAL vz, REAL nx, "
                 "REAL ny, REAL nz, REAL n, RSCALAR p0, RSCALAR p1)\n{\n    (void)p0;\n    (void)p1;\n"
                 "    return " SHADERLANG_FULL_FUNCTION "(lx, ly, lz, vx, vy, vz, nx, ny, nz, n%s);\n}\n", pp);
    md_printf(b, "#ifdef BRDF_HOST_JIT\ndouble brdfbench_host_full(double lx, double ly, double lz, double vx, "
                 "double vy, double vz, double nx, double ny, double nz, double n, double p0, double p1)\n{\n"
                 "    return brdf_user_full(lx, ly, lz, vx, vy, vz, nx, ny, nz, n, p0, p1);\n}\n#endif\n");
}

/* The text appended to a kernel file for a model file: its whole text from line 1 (so the
 * compiler's line numbers are the file's own), then the wrapper that brdf_eval calls. */
static int make_file_source(struct user_model *um, const char *text, size_t len)
{
    struct md_buf b;
    md_init(&b);
    line_directive(&b, 1, um->origin);
    md_append(&b, text, len);
    char wrapper_name[600];
    snprintf(wrapper_name, sizeof wrapper_name, "brdfbench wrapper of %s", um->origin);
    line_directive(&b, 1, wrapper_name);
    md_printf(&b, "BRDF_FN REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n{\n");
    md_printf(&b, "    (void)p0;\n    (void)p1;\n    return %s(c, n%s%s);\n}\n", um->function,
              um->info.nparams > 0 ? ", p0" : "", um->info.nparams > 1 ? ", p1" : "");
    static const char full_def[] = "\nREAL " SHADERLANG_FULL_FUNCTION "(";
    um->full = 0;
    for (size_t i = 0; i + sizeof full_def - 1 <= len && !um->full; ++i)
        um->full = memcmp(text + i, full_def, sizeof full_def - 1) == 0;
    if (um->full)
        full_wrapper(&b, um);
    if (b.failed) {
        md_free(&b);
        return -1;
    }
    um->device_source = b.s;
    usermodel_fill_runtime(um);
    return 0;
}

/* The keys a model file's header has declared so far. */
struct header_seen {
    int name, reference, description, function, lobe;
    int generated;   /* the header is the translator's (parse_param_line) */
};

/* One "key: value" line of a model file's header (s, trimmed, split in place). */
static int header_line(struct user_model *um, char *s, struct header_seen *h, const char *path, int line,
                       char *err, size_t errlen)
{
    char *colon = strchr(s, ':');
    if (!colon)
        return file_fail(err, errlen, path, line, "expected 'key: value' (keys: name, param, reference, "
                                                  "lobe, function, description), found '%.40s'", s);
    *colon = '\0';
    char *key = trim(s), *value = trim(colon + 1);
    if (strcmp(key, "name") == 0) {
        if (h->name++)
            return file_fail(err, errlen, path, line, "'name' is declared twice");
        if (!is_identifier(value, USERMODEL_NAME_MAX) || is_reserved_name(value))
            return file_fail(err, errlen, path, line,
                             "name '%.60s' is not an identifier of 1 to %d characters (letters, digits, _) "
                             "or is reserved", value, USERMODEL_NAME_MAX);
        snprintf(um->name, sizeof um->name, "%s", value);
    } else if (strcmp(key, "function") == 0) {
        if (h->function++)
            return file_fail(err, errlen, path, line, "'function' is declared twice");
        if (!is_identifier(value, USERMODEL_NAME_MAX) || is_reserved_name(value))
            return file_fail(err, errlen, path, line, "function '%.60s' is not an identifier of 1 to %d "
                             "characters or is reserved", value, USERMODEL_NAME_MAX);
        snprintf(um->function, sizeof um->function, "%s", value);
    } else if (strcmp(key, "reference") == 0) {
        const struct model_info *ref = models_find(value);
        if (h->reference++ || !ref || ref->kernel_id == BRDF_USER)
            return file_fail(err, errlen, path, line, h->reference > 1 ? "'reference' is declared twice"
                             : "reference '%.40s' is not a built-in model (see brdfbench list)", value);
        snprintf(um->reference, sizeof um->reference, "%s", ref->id);
    } else if (strcmp(key, "lobe") == 0) {
        if (h->lobe++ || (strcmp(value, "psi") != 0 && strcmp(value, "theta_h") != 0))
            return file_fail(err, errlen, path, line, h->lobe > 1 ? "'lobe' is declared twice"
                             : "lobe '%.40s' is unknown (accepted: psi, theta_h)", value);
        um->info.lobe = strcmp(value, "psi") == 0 ? LOBE_PSI : LOBE_THETA_H;
        um->lobe_declared = 1;
    } else if (strcmp(key, "description") == 0) {
        if (h->description++)
            return file_fail(err, errlen, path, line, "'description' is declared twice");
        /* one line of text: an escape sequence would drive the terminal of whoever lists it */
        for (const char *c = value; *c; ++c)
            if (((unsigned char)*c < 0x20 && *c != '\t') || *c == 0x7f)
                return file_fail(err, errlen, path, line, "'description' holds a control character (accepted: "
                                 "one line of printable text)");
        snprintf(um->description, sizeof um->description, "%s", value);
    } else if (strcmp(key, "param") == 0) {
        return parse_param_line(um, value, path, line, err, errlen, h->generated);
    } else {
        return file_fail(err, errlen, path, line, "unknown key '%.40s' (accepted: name, param, reference, "
                         "lobe, function, description)", key);
    }
    return 0;
}

/* The header: the first thing in the file (text, cut in place), a block comment opening with
   brdfbench-model, then its keys line by line; *close at the comment's closing. */
static int parse_header(struct user_model *um, char *text, char **close, struct header_seen *h, const char *path,
                        char *err, size_t errlen)
{
    char *p = text;
    int line = 1;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') {
        if (*p == '\n')
            ++line;
        ++p;
    }
    if (strncmp(p, "/*", 2) != 0 || !(*close = strstr(p + 2, "*/")))
        return file_fail(err, errlen, path, line,
                         "a model file begins with a header comment '/* brdfbench-model ... */' "
                         "(see docs/user-models.md)");
    **close = '\0';
    p += 2;
    for (int first = 1;; first = 0) {
        char *eol = strchr(p, '\n');
        if (eol)
            *eol = '\0';
        char *s = trim(p);
        if (!first && *s == '*')
            s = trim(s + 1);
        if (first) {
            if (strcmp(s, "brdfbench-model") != 0)
                return file_fail(err, errlen, path, line,
                                 "the header comment must open with 'brdfbench-model' on its first line (found "
                                 "'%.40s')", s);
        } else if (*s) {
            int rc = header_line(um, s, h, path, line, err, errlen);
            if (rc)
                return rc;
        }
        if (!eol)
            break;
        p = eol + 1;
        ++line;
    }
    return 0;
}

/* A .brdf file's NAME@FILE.brdf (usermodel.h, qualified), when it fits a model name and the
   --models list can name it (no ',', ':', '=' or blank in the file's name). */
static void brdf_qualified_name(struct user_model *um, const char *path)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t bl = strlen(base);
    um->qualified[0] = '\0';
    if (bl < 6 || strcmp(base + bl - 5, ".brdf") != 0 || strcspn(base, ",:= \t\r\n@") != bl)
        return;
    size_t nl = strlen(um->name);
    if (nl + 1 + bl > USERMODEL_NAME_MAX)
        return;
    memcpy(um->qualified, um->name, nl);
    um->qualified[nl] = '@';
    memcpy(um->qualified + nl + 1, base, bl + 1);
}

/* usermodel_parse_file_text; translating_expression: the text is the translation of a --model
   expression, machine-made text whose own brdfbench_* names are not the user's (the expression
   itself was checked). */
static int parse_file_text(const char *text, size_t len, const char *path, int translating_expression,
                           struct user_model **out, char *err, size_t errlen)
{
    *out = NULL;
    if (len == 0)
        return file_fail(err, errlen, path, 0, "empty model file (see docs/user-models.md)");
    if (len > USERMODEL_MAX_FILE)
        return file_fail(err, errlen, path, 0, "larger than %d bytes", USERMODEL_MAX_FILE);
    if (memchr(text, '\0', len))
        return file_fail(err, errlen, path, 0, "NUL byte in a model file (a text file is expected)");
    /* A GLSL/HLSL-style file is read as its translation (shaderlang.h). The reserved names are
       looked for in what the user wrote: the translation names its own brdfbench_* values. */
    char *translated = NULL;
    const char *own = text;
    size_t own_len = len;
    int sl = shaderlang_file(text, len, path, &translated, &len, err, errlen);
    if (sl == EXIT_USAGE)
        return sl;
    int generated = translating_expression;
    if (sl == 0) {
        /* The user's names are the user's: the translation renames every one (u__NAME) and calls
           only the file's own functions and the math built-ins, so BRDF_GGX or brdf in a shader
           never meets brdfbench's code, and the reserved-name check is for OpenCL C texts. */
        (void)own;
        (void)own_len;
        text = translated;
        generated = 1;
    }
    char *copy = malloc(len + 1);
    struct user_model *um = usermodel_new();
    if (!copy || !um) {
        free(copy);
        free(um);
        free(translated);
        return file_fail(err, errlen, path, 0, "out of memory");
    }
    memcpy(copy, text, len);
    copy[len] = '\0';
    snprintf(um->origin, sizeof um->origin, "%s", path);
    um->from_file = 1;
    int rc = 0;

    char *close = NULL;
    struct header_seen seen = {0};
    /* a .brdf file's parameters come from its ::begin parameters block, checked by the translator */
    size_t pl = strlen(path);
    seen.generated = sl == 0 && pl > 5 && strcmp(path + pl - 5, ".brdf") == 0;
    if ((rc = parse_header(um, copy, &close, &seen, path, err, errlen)) != 0)
        goto done;
    if (!seen.name) {
        rc = file_fail(err, errlen, path, 0, "the header declares no 'name: NAME'");
        goto done;
    }
    if (!seen.function)
        snprintf(um->function, sizeof um->function, "%s", um->name);
    for (int k = 0; k < um->info.nparams; ++k)
        if (strcmp(um->param_names[k], um->name) == 0 || strcmp(um->param_names[k], um->function) == 0) {
            rc = file_fail(err, errlen, path, 0, "parameter '%s' has the model's or its function's name",
                           um->param_names[k]);
            goto done;
        }
    /* The body (after the header) must define the function; the compiler checks the rest. */
    memcpy(copy, text, len);
    copy[len] = '\0';
    if (!has_call_or_definition(copy + (close - copy) + 2, um->function)) {
        rc = file_fail(err, errlen, path, 0,
                       "no function '%s' after the header (expected REAL %s(REAL c, REAL n%s%s) { ... })",
                       um->function, um->function, um->info.nparams > 0 ? ", RSCALAR ..." : "",
                       um->info.nparams > 1 ? ", RSCALAR ..." : "");
        goto done;
    }
    /* The text may not name brdfbench's own functions (the wrapper, the dispatchers); the
       header is a comment, which the scan skips. */
    if (!generated && (rc = usermodel_check_text(text, len, path, 1, err, errlen)) != 0)
        goto done;
    /* No pointer, no memory but the model's own variables (usermodel_code.c). */
    if (!generated && (rc = usermodel_check_code(text, len, path, 1, err, errlen)) != 0)
        goto done;
    if (!seen.description)
        snprintf(um->description, sizeof um->description, "user model from %.200s", path);
    snprintf(um->formula, sizeof um->formula, "%s(c, n%s) in %.200s", um->function,
             um->info.nparams ? ", ..." : "", path);
    if (sl == 0)
        brdf_qualified_name(um, path);
    usermodel_fill_info(um);
    if (make_file_source(um, text, len)) {
        rc = file_fail(err, errlen, path, 0, "out of memory");
        goto done;
    }
done:
    free(copy);
    free(translated);
    if (rc)
        usermodel_free(um);
    else
        *out = um;
    return rc;
}

/* ---- expressions ---------------------------------------------------------------------- */

int usermodel_parse_expression(const char *arg, struct user_model **out, char *err, size_t errlen)
{
    *out = NULL;
    const char *eq = arg ? strchr(arg, '=') : NULL;
    if (!eq) {
        snprintf(err, errlen, "--model: '%.60s' is not NAME=EXPR (e.g. --model 'sq=c*c')", arg ? arg : "");
        return EXIT_USAGE;
    }
    char name[USERMODEL_NAME_MAX + 1];
    size_t nlen = (size_t)(eq - arg);
    if (nlen == 0 || nlen > USERMODEL_NAME_MAX) {
        snprintf(err, errlen, "--model: the name before '=' must have 1 to %d characters", USERMODEL_NAME_MAX);
        return EXIT_USAGE;
    }
    memcpy(name, arg, nlen);
    name[nlen] = '\0';
    if (!is_identifier(name, USERMODEL_NAME_MAX) || is_reserved_name(name)) {
        snprintf(err, errlen, "--model: name '%s' is not an identifier (letters, digits, _) or is reserved", name);
        return EXIT_USAGE;
    }
    const char *expr = eq + 1;
    size_t elen = strlen(expr);
    if (elen == 0 || elen > USERMODEL_MAX_EXPR) {
        snprintf(err, errlen, "--model %s: the expression must have 1 to %d characters", name, USERMODEL_MAX_EXPR);
        return EXIT_USAGE;
    }
    {
        /* GLSL/HLSL-style text (shaderlang.h): read as the model file it translates to. */
        char origin[USERMODEL_NAME_MAX + 16], *text = NULL;
        size_t tlen = 0;
        snprintf(origin, sizeof origin, "--model %s", name);
        int sl = shaderlang_expression(name, expr, origin, &text, &tlen, err, errlen);
        /* the user's own text may not name brdfbench's code; its translation does */
        if (sl == 0 && (sl = usermodel_check_text(expr, elen, origin, 0, err, errlen)) != 0) {
            free(text);
            text = NULL;
        }
        if (sl == 0) {
            sl = parse_file_text(text, tlen, origin, 1, out, err, errlen);
            free(text);
            if (sl == 0) {
                (*out)->from_file = 0;
                snprintf((*out)->formula, sizeof (*out)->formula, "%s", expr);
                snprintf((*out)->description, sizeof (*out)->description, "user expression %.200s", expr);
            }
        }
        if (sl != SHADERLANG_NOT_SHADER)
            return sl;
    }
    int blank = 1;
    for (size_t i = 0; i < elen; ++i) {
        unsigned char ch = (unsigned char)expr[i];
        if (ch < 0x20 || ch > 0x7e || strchr(";{}#\\\"'", ch) ||
            (ch == '/' && (expr[i + 1] == '/' || expr[i + 1] == '*')) || (ch == '*' && expr[i + 1] == '/')) {
            snprintf(err, errlen, "--model %s: character %zu of the expression is not allowed (an expression "
                     "of c and n: numbers, operators, parentheses, OpenCL math functions; no ; { } # quotes, "
                     "comments or control characters)", name, i + 1);
            return EXIT_USAGE;
        }
        if (ch != ' ')
            blank = 0;
    }
    if (blank) {
        snprintf(err, errlen, "--model %s: the expression is blank", name);
        return EXIT_USAGE;
    }
    {
        char what[USERMODEL_NAME_MAX + 16];
        snprintf(what, sizeof what, "--model %s", name);
        int r = usermodel_check_text(expr, elen, what, 0, err, errlen);
        if (!r)
            r = usermodel_check_code(expr, elen, what, 0, err, errlen);
        if (r)
            return r;
    }
    struct user_model *um = usermodel_new();
    if (!um) {
        snprintf(err, errlen, "--model: out of memory");
        return EXIT_RUNTIME;
    }
    snprintf(um->name, sizeof um->name, "%s", name);
    snprintf(um->function, sizeof um->function, "%s", name);
    snprintf(um->origin, sizeof um->origin, "--model %s", name);
    snprintf(um->formula, sizeof um->formula, "%s", expr);
    snprintf(um->description, sizeof um->description, "user expression %.200s", expr);
    usermodel_fill_info(um);

    /* The expression stands alone on line 1 of its own #line name, so the compiler's
       line:column point into the expression as the user typed it. */
    struct md_buf b;
    md_init(&b);
    char wrapper_name[600];
    snprintf(wrapper_name, sizeof wrapper_name, "brdfbench wrapper of %s", um->origin);
    line_directive(&b, 1, wrapper_name);
    md_printf(&b, "BRDF_FN REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n{\n"
                  "    (void)p0;\n    (void)p1;\n    return RSPLAT(0.0) + (");
    line_directive(&b, 1, um->origin);
    md_append(&b, expr, elen);
    line_directive(&b, 6, wrapper_name);
    md_printf(&b, "    );\n}\n");
    if (b.failed) {
        md_free(&b);
        usermodel_free(um);
        snprintf(err, errlen, "--model: out of memory");
        return EXIT_RUNTIME;
    }
    um->device_source = b.s;
    usermodel_fill_runtime(um);
    *out = um;
    return 0;
}

int usermodel_parse_file_text(const char *text, size_t len, const char *path, struct user_model **out,
                              char *err, size_t errlen)
{
    return parse_file_text(text, len, path, 0, out, err, errlen);
}

/* ---- the registry ---------------------------------------------------------------------- */

int usermodel_register(struct user_model *um, char *err, size_t errlen)
{
    const struct model_info *taken = models_find(um->name);
    /* A .brdf file's model whose name is taken lives in its file's namespace: phong.brdf's phong
       is phong@phong.brdf beside the built-in phong. */
    if (taken && um->qualified[0]) {
        taken = models_find(um->qualified);   /* NULL, or another file of the same name */
        snprintf(um->name, sizeof um->name, "%s", um->qualified);
        um->qualified[0] = '\0';
        snprintf(um->what, sizeof um->what, "user model '%s' (%s)", um->name, um->origin);
    }
    if (um->qualified[0] && models_find(um->qualified))
        um->qualified[0] = '\0';   /* that name is another model's: the model keeps its own alone */
    um->runtime.alias = um->qualified[0] ? um->qualified : NULL;
    if (taken) {
        if (usermodel_of_info(taken))
            snprintf(err, errlen, "%s: user model '%s' is already defined by %s", um->origin, um->name,
                     usermodel_of_info(taken)->origin);
        else
            snprintf(err, errlen, "%s: '%s' is the name of a built-in model (choose another name)", um->origin,
                     um->name);
        usermodel_free(um);
        return EXIT_USAGE;
    }
    char clash[512];
    if (usermodel_check_file_names(um->name, clash, sizeof clash)) {
        snprintf(err, errlen, "%s: %s", um->origin, clash);
        usermodel_free(um);
        return EXIT_USAGE;
    }
    if (usermodel_count() >= USERMODEL_MAX || models_register(&um->info, &um->runtime) != 0) {
        snprintf(err, errlen, "%s: at most %d user models per run", um->origin, USERMODEL_MAX);
        usermodel_free(um);
        return EXIT_USAGE;
    }
    return 0;
}

void usermodel_clear_all(void)
{
    for (int i = usermodel_count() - 1; i >= 0; --i)
        usermodel_free(registry_at(i));
    models_unregister_all();
}

int usermodel_count(void) { return models_user_count(); }

const struct user_model *usermodel_at(int i) { return usermodel_of_info(models_user_at(i)); }

const char *usermodel_names(void)
{
    static char names[USERMODEL_MAX * (USERMODEL_NAME_MAX + 1) + 1];
    size_t used = 0;
    names[0] = '\0';
    for (int i = 0; i < usermodel_count(); ++i)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? "," : "", registry_at(i)->name);
    return names;
}

int usermodel_append_all(struct model_spec *models, int *count, int max, char *err, size_t errlen)
{
    for (int i = 0; i < usermodel_count(); ++i) {
        if (*count >= max) {
            snprintf(err, errlen, "at most %d models per run (with the user models)", max);
            return EXIT_USAGE;
        }
        model_spec_default(&registry_at(i)->info, &models[(*count)++]);
    }
    return 0;
}

const struct user_model *usermodel_of_info(const struct model_info *info)
{
    return (info && info->kernel_id == BRDF_USER) ? (const struct user_model *)info : NULL;
}

const struct user_model *usermodel_of(const struct model_spec *m) { return m ? usermodel_of_info(m->info) : NULL; }

int usermodel_load_file(const char *path, const struct user_model **out, char *err, size_t errlen)
{
    if (out)
        *out = NULL;
    /* The same file again, however it is reached (the same path, a link, a hard link): the
       model it defined. */
    struct stat st_new, st_old;
    int have_new = stat(path, &st_new) == 0;
    for (int i = 0; i < usermodel_count(); ++i)
        if (registry_at(i)->from_file &&
            (strcmp(registry_at(i)->origin, path) == 0 ||
             (have_new && stat(registry_at(i)->origin, &st_old) == 0 && st_old.st_dev == st_new.st_dev &&
              st_old.st_ino == st_new.st_ino))) {
            if (out)
                *out = registry_at(i);
            return 0;
        }
    /* A regular file, its size checked before it is read (no FIFO or device: infile.h). */
    char *buf = NULL, why[256];
    size_t len = 0;
    int r = infile_read(path, 0, USERMODEL_MAX_FILE, &buf, &len, why, sizeof why);
    if (r == -2) {
        snprintf(err, errlen, "--model-file: out of memory");
        return EXIT_RUNTIME;
    }
    if (r == -1 && strncmp(why, "is larger", 9) == 0)
        return file_fail(err, errlen, path, 0, "larger than %d bytes", USERMODEL_MAX_FILE);
    if (r != 0) {
        if (strncmp(why, "is a folder", 11) == 0)
            snprintf(why, sizeof why, "%s", strerror(EISDIR));
        snprintf(err, errlen, "--model-file: cannot read %s: %s", path, why);
        return EXIT_USAGE;
    }
    struct user_model *um = NULL;
    int rc = usermodel_parse_file_text(buf, len, path, &um, err, errlen);
    free(buf);
    if (rc)
        return rc;
    rc = usermodel_register(um, err, errlen);
    if (rc)
        return rc;
    if (out)
        *out = um;
    return 0;
}

/* ---- a phase in the sandbox ------------------------------------------------------------- */

static void isolated_tick(void *tctx, double c, double n) { usermodel_watch_begin(tctx, c, n); }

int usermodel_isolated(const struct model_spec *m, void (*fn)(void *ctx, void *out), void *ctx, void *out,
                       size_t outlen)
{
    struct user_model *um = (struct user_model *)usermodel_of(m);
    const char *off = getenv("BRDFBENCH_TEST_PHASE_IN_PROCESS");
    if (!um || !usermodel_host_ready(um) || (off && strcmp(off, "1") == 0)) {
        fn(ctx, out);
        return 0;
    }
    /* one value first, in the per-value sandbox: the deadline's watcher thread starts here,
       not in the child, which may start no thread */
    (void)usermodel_eval_host(m, 1.0, 1.0);
    char why[256];
    usermodel_watch_begin(um, NAN, NAN);
    int rc = hostjit_isolated(fn, ctx, out, outlen, isolated_tick, um, why, sizeof why);
    usermodel_watch_end();
    if (rc) {
        fprintf(stderr, "brdfbench: the host reference of %s failed: %s; the run is stopped and its unfinished "
                "outputs removed\n", um->what, why);
        outdir_remove_own();
        fflush(NULL);
        _exit(EXIT_RUNTIME);
    }
    return 0;
}

/* ---- the reference on the device (fallback) -------------------------------------------- */

int usermodel_reference_open(const struct user_model *cum, struct cl_session *s)
{
    /* Every user model is allocated by this file: its device state may change. */
    struct user_model *um = (struct user_model *)cum;
    if (um->ref_point && um->ref_session == s)
        return 0;
    usermodel_reference_close(um);
    const char *no_fp64 = getenv("BRDFBENCH_NO_FP64");
    int use_double = s->has_fp64 && !(no_fp64 && strcmp(no_fp64, "1") == 0);
    const char *opts = use_double ? "-DBRDF_HAVE_USER_MODEL -DUSERMODEL_REF_DOUBLE" : USERMODEL_FLOAT_OPTIONS;
    int rc = clsession_build_user(s, "usermodel_ref.cl", um->device_source, opts, &um->ref_program, 0);
    if (rc) {
        if (rc == EXIT_USAGE)
            fprintf(stderr, "brdfbench: user model '%s' (%s) does not compile for its %s reference; the build "
                            "log above names the lines of %s\n", um->name, um->origin,
                    use_double ? "double" : "float", um->from_file ? um->origin : "the expression");
        um->ref_program = NULL;
        return rc;
    }
    cl_int e;
    um->ref_point = clCreateKernel(um->ref_program, "usermodel_ref_point", &e);
    if (e != CL_SUCCESS) {
        cl_report("clCreateKernel(usermodel_ref_point)", e, __FILE__, __LINE__);
        clReleaseProgram(um->ref_program);
        um->ref_program = NULL;
        um->ref_point = NULL;
        return EXIT_RUNTIME;
    }
    um->ref_out = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, sizeof(double), NULL, &e);
    if (e != CL_SUCCESS) {
        cl_report("clCreateBuffer(user model reference)", e, __FILE__, __LINE__);
        usermodel_reference_close(um);
        return EXIT_RUNTIME;
    }
    um->ref_session = s;
    um->ref_is_double = use_double;
    um->ref_warned = 0;
    if (!um->ref_noted++)
        fprintf(stderr, "brdfbench: note: %s is not C (%s), so its double reference runs on the device, one "
                        "launch per value: expect the accuracy sweep to take minutes (docs/user-models.md)\n",
                um->what, um->host_error);
    return 0;
}

void usermodel_reference_close(const struct user_model *cum)
{
    /* Called from usermodel_free too, before the model is in the registry. */
    struct user_model *um = (struct user_model *)cum;
    if (um->ref_out)
        clReleaseMemObject(um->ref_out);
    if (um->ref_point)
        clReleaseKernel(um->ref_point);
    if (um->ref_program)
        clReleaseProgram(um->ref_program);
    um->ref_out = NULL;
    um->ref_point = NULL;
    um->ref_program = NULL;
    um->ref_session = NULL;
}

const char *usermodel_reference_note(const struct user_model *um)
{
    if (!um || !um->ref_point || um->ref_is_double)
        return NULL;
    return "the device has no cl_khr_fp64: this user model's reference is evaluated in float on the device, "
           "so its float-vs-double check does not hold";
}

double usermodel_eval_host(const struct model_spec *m, double c, double n)
{
    struct user_model *um = (struct user_model *)usermodel_of(m);
    if (!um)
        return NAN;
    if (usermodel_host_ready(um)) {
        /* The sandbox's round trip costs more than the formula: the value of a point asked
           for again (a search asks for its best point twice, an error for the model's value
           after its validity check) comes from a small cache of the last points. */
        double key[4] = { c, n, m->params[0], m->params[1] };
        uint64_t h = 1469598103934665603ull;
        for (int k = 0; k < 4; ++k) {
            uint64_t bits;
            memcpy(&bits, &key[k], sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        struct usermodel_cached *e = &um->cache[(h >> 17) % USERMODEL_CACHE];
        if (e->valid && memcmp(e->key, key, sizeof key) == 0) {
            um->cache_hits++;
            return e->value;
        }
        usermodel_watch_begin(um, c, n);   /* the host reference's deadline (usermodel_check.h) */
        double v = NAN;
        if (hostjit_eval(um->host, c, n, m->params[0], m->params[1], &v) != 0)
            host_reference_died(um, c, n);
        usermodel_watch_end();
        memcpy(e->key, key, sizeof key);
        e->value = v;
        e->valid = 1;
        um->cache_misses++;
        return v;
    }
    if (!um->ref_point)
        return NAN;
    struct cl_session *s = um->ref_session;
    cl_int e = CL_SUCCESS;
    double result = NAN;
    cl_mem out = um->ref_out;
    char why[256] = "";   /* which argument failed, when one did */
    /* One point per launch: the accuracy sweep's refinement asks for points one at a time. */
    if (um->ref_is_double) {
        double args[4] = { m->params[0], m->params[1], c, n };
        e = CL_SET_ARGS_WHY(um->ref_point, 0, why, sizeof why, CL_ARG(args[0]), CL_ARG(args[1]), CL_ARG(args[2]),
                            CL_ARG(args[3]), CL_ARG(out));
    } else {
        float args[4] = { (float)m->params[0], (float)m->params[1], (float)c, (float)n };
        e = CL_SET_ARGS_WHY(um->ref_point, 0, why, sizeof why, CL_ARG(args[0]), CL_ARG(args[1]), CL_ARG(args[2]),
                            CL_ARG(args[3]), CL_ARG(out));
    }
    size_t one = 1;
    if (e == CL_SUCCESS)
        e = clEnqueueNDRangeKernel(s->queue, um->ref_point, 1, NULL, &one, NULL, 0, NULL, NULL);
    if (e == CL_SUCCESS)
        e = clsession_finish(s, um->ref_point, um->name);
    if (e == CL_SUCCESS) {
        if (um->ref_is_double) {
            e = clEnqueueReadBuffer(s->queue, out, CL_TRUE, 0, sizeof(double), &result, 0, NULL, NULL);
        } else {
            float v = NAN;
            e = clEnqueueReadBuffer(s->queue, out, CL_TRUE, 0, sizeof(float), &v, 0, NULL, NULL);
            result = v;
        }
    }
    if (e != CL_SUCCESS)
        goto fail;
    um->ref_calls++;
    return result;
fail:
    if (!um->ref_warned) {
        um->ref_warned = 1;
        if (why[0])
            fprintf(stderr, "brdfbench: evaluating the reference of user model '%s': %s\n", um->name, why);
        else
            fprintf(stderr, "brdfbench: evaluating the reference of user model '%s' failed with %s\n", um->name,
                    cl_error_name(e));
    }
    return NAN;
}
