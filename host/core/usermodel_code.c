/* usermodel_code.c - what OpenCL C a user model may contain: no pointer, no memory access
 * beyond its own scalar and vector variables, no call but a math built-in or its own
 * function (usermodel_check.h, usermodel_check_code).
 *
 * Why: a model's text is compiled into the device's kernels (PoCL runs them inside this
 * process) and, as C, into the host reference (hostjit.c). A dereference of a made-up
 * address there writes where it likes: `*(float*)8` kills the run, `((long*)&c)[2] = X`
 * overwrote the host reference's return address. A BRDF lobe needs none of that, so the
 * text is refused at parse, before any compiler sees it, with its file:line:column.
 *
 * The check works on tokens (comments skipped, line continuations joined) and decides
 * whether '*' and '&' are binary (multiplication, bitwise and) from the token before them:
 * an operand (a variable, a number, ')' that does not close a cast, or a non-type macro)
 * makes them binary; anything else (an operator, '(', a type name, a cast) makes them a
 * dereference, an address-of or a pointer declarator, which are refused. Macros are checked
 * where they are defined (a replacement starts in operator position, so `#define D *` is
 * refused) and where they are used (an argument made only of type names is refused, so a
 * parameter never stands for a type). */
#define _POSIX_C_SOURCE 200809L
#include "usermodel_check.h"
#include "exitcodes.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum tok_kind { T_IDENT, T_NUMBER, T_PUNCT, T_STRING, T_DIRECTIVE_END };

struct tok {
    enum tok_kind kind;
    size_t at, len;          /* in the joined text */
    int directive;           /* 1: the token belongs to a preprocessor line */
    int first_of_line;
};

static int word_in(const char *s, size_t n, const char *const *list)
{
    for (int i = 0; list[i]; ++i)
        if (strlen(list[i]) == n && memcmp(list[i], s, n) == 0)
            return 1;
    return 0;
}

static const char *const scalar_types[] = { "char", "uchar", "short", "ushort", "int", "uint", "long", "ulong",
                                            "float", "double", "half", NULL };

/* A type name of OpenCL C (scalar, vector, qualifier) or of kernels/brdf_models.h. */
static int is_builtin_type(const char *s, size_t n)
{
    static const char *const others[] = { "void", "bool", "_Bool", "size_t", "ptrdiff_t", "intptr_t", "uintptr_t",
                                          "unsigned", "signed", "const", "REAL", "RSCALAR", "static", "inline",
                                          "register", "auto", NULL };
    if (word_in(s, n, scalar_types) || word_in(s, n, others))
        return 1;
    /* vector types: float4, uchar16, ... */
    size_t k = n;
    while (k > 0 && isdigit((unsigned char)s[k - 1]))
        --k;
    if (k == n || k == 0)
        return 0;
    static const char *const widths[] = { "2", "3", "4", "8", "16", NULL };
    return word_in(s, k, scalar_types) && word_in(s + k, n - k, widths);
}

/* Words that have no place in a lobe's formula: the ways to a pointer, to memory beyond the
   model's variables, to code the check cannot see, or to the compiler's own extensions. */
static const char *refused_word(const char *s, size_t n)
{
    static const struct { const char *word, *why; } words[] = {
        { "asm", "inline assembly" }, { "__asm", "inline assembly" }, { "__asm__", "inline assembly" },
        { "volatile", "volatile (memory outside the model's variables)" },
        { "__volatile__", "volatile (memory outside the model's variables)" },
        { "sizeof", "sizeof (the layout of memory)" }, { "_Alignof", "_Alignof (the layout of memory)" },
        { "__alignof__", "__alignof__ (the layout of memory)" }, { "alignof", "alignof (the layout of memory)" },
        { "vec_step", "vec_step (the layout of memory)" },
        { "typeof", "typeof" }, { "__typeof__", "typeof" }, { "__typeof", "typeof" }, { "_Generic", "_Generic" },
        { "__attribute__", "__attribute__" }, { "__attribute", "__attribute__" },
        { "__global", "an address space (pointers)" }, { "global", "an address space (pointers)" },
        { "__local", "an address space (pointers)" }, { "local", "an address space (pointers)" },
        { "__private", "an address space (pointers)" }, { "private", "an address space (pointers)" },
        { "__constant", "an address space (pointers)" }, { "constant", "an address space (pointers)" },
        { "__generic", "an address space (pointers)" }, { "generic", "an address space (pointers)" },
        { "restrict", "restrict (pointers)" }, { "__restrict", "restrict (pointers)" },
        { "__restrict__", "restrict (pointers)" },
        { "extern", "extern (a name of the program around the model)" },
        { "_Thread_local", "thread storage" }, { "__thread", "thread storage" }, { "_Atomic", "_Atomic" },
        { "__kernel", "a kernel" }, { "kernel", "a kernel" },
        { "typedef", "typedef (a model uses the types of OpenCL C)" },
        { "struct", "struct (a model uses scalars and vectors)" }, { "union", "union (a model uses scalars and vectors)" },
        { "enum", "enum (a model uses scalars and vectors)" },
        { "_Pragma", "_Pragma" }, { "__pragma", "_Pragma" }, { "goto", "goto" },
    };
    for (size_t i = 0; i < sizeof words / sizeof words[0]; ++i)
        if (strlen(words[i].word) == n && memcmp(words[i].word, s, n) == 0)
            return words[i].why;
    if (n >= 10 && memcmp(s, "__builtin_", 10) == 0)
        return "a compiler built-in";
    if (n >= 6 && memcmp(s, "__sync", 6) == 0)
        return "a compiler built-in";
    if (n >= 8 && memcmp(s, "__atomic", 8) == 0)
        return "a compiler built-in";
    return NULL;
}

/* OpenCL C's built-in functions that take and return values only (none that takes a pointer:
   fract, frexp, modf, remquo, sincos, lgamma_r, vload*, vstore* are refused), the helpers of
   kernels/brdf_models.h a model may call, and its macros RC and RSPLAT. */
static int is_allowed_builtin(const char *s, size_t n)
{
    static const char *const fns[] = {
        "acos", "acosh", "acospi", "asin", "asinh", "asinpi", "atan", "atan2", "atanh", "atanpi", "atan2pi",
        "cbrt", "ceil", "copysign", "cos", "cosh", "cospi", "erfc", "erf", "exp", "exp2", "exp10", "expm1",
        "fabs", "fdim", "floor", "fma", "fmax", "fmin", "fmod", "hypot", "ilogb", "ldexp", "lgamma", "log",
        "log2", "log10", "log1p", "logb", "mad", "maxmag", "minmag", "nan", "nextafter", "pow", "pown", "powr",
        "remainder", "rint", "rootn", "round", "rsqrt", "sin", "sinh", "sinpi", "sqrt", "tan", "tanh", "tanpi",
        "tgamma", "trunc",
        "clamp", "degrees", "max", "min", "mix", "radians", "step", "smoothstep", "sign",
        "cross", "dot", "distance", "length", "normalize", "fast_distance", "fast_length", "fast_normalize",
        "isequal", "isnotequal", "isgreater", "isgreaterequal", "isless", "islessequal", "islessgreater",
        "isfinite", "isinf", "isnan", "isnormal", "isordered", "isunordered", "signbit", "any", "all",
        "bitselect", "select",
        "abs", "abs_diff", "add_sat", "hadd", "rhadd", "clz", "ctz", "mad_hi", "mad_sat", "mul_hi", "rotate",
        "sub_sat", "upsample", "popcount", "mad24", "mul24",
        "brdf_quadratic", "brdf_pow_lobe", "brdf_sin2", "brdf_alpha_from_n", "brdf_d_beckmann", "brdf_d_ggx",
        "brdf_phong_norm", "brdf_blinn_norm", "RC", "RSPLAT", "RHALF",
        NULL };
    if (word_in(s, n, fns))
        return 1;
    if (n > 7 && (memcmp(s, "native_", 7) == 0))
        return is_allowed_builtin(s + 7, n - 7) || (n == 13 && memcmp(s + 7, "divide", 6) == 0) ||
               (n == 12 && memcmp(s + 7, "recip", 5) == 0);
    if (n > 5 && memcmp(s, "half_", 5) == 0)
        return is_allowed_builtin(s + 5, n - 5) || (n == 11 && memcmp(s + 5, "divide", 6) == 0) ||
               (n == 10 && memcmp(s + 5, "recip", 5) == 0);
    /* convert_TYPE[_sat][_rte|_rtz|_rtp|_rtn] and as_TYPE */
    const char *rest = NULL;
    size_t rn = 0;
    if (n > 8 && memcmp(s, "convert_", 8) == 0)
        rest = s + 8, rn = n - 8;
    else if (n > 3 && memcmp(s, "as_", 3) == 0)
        rest = s + 3, rn = n - 3;
    if (rest) {
        size_t t = 0;
        while (t < rn && rest[t] != '_')
            ++t;
        if (!is_builtin_type(rest, t) || (t == 4 && memcmp(rest, "void", 4) == 0))
            return 0;
        if (rest == s + 3)
            return t == rn;
        static const char *const suffixes[] = { "", "_sat", "_rte", "_rtz", "_rtp", "_rtn", "_sat_rte", "_sat_rtz",
                                                "_sat_rtp", "_sat_rtn", NULL };
        return word_in(rest + t, rn - t, suffixes);
    }
    return 0;
}

static int is_statement_word(const char *s, size_t n)
{
    static const char *const words[] = { "if", "else", "while", "for", "do", "switch", "case", "default",
                                         "return", "break", "continue", "defined", NULL };
    return word_in(s, n, words);
}

/* ---- the text as tokens --------------------------------------------------------------- */

struct code {
    const char *t;           /* joined text (line continuations removed) */
    size_t len;
    const int *line_of;      /* line of each character of t */
    const char *what;
    int is_file;
    struct tok *tok;
    size_t ntok;
    /* names the file gives meaning to */
    char (*fn)[64];          /* functions defined or declared at file scope */
    int nfn;
    struct macro { char name[64]; int function_like, type_like, nparams; char params[8][64]; const char *alias; size_t alias_len; } *mac;
    int nmac;
};

static int fail_at(const struct code *c, size_t at, char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int fail_at(const struct code *c, size_t at, char *err, size_t errlen, const char *fmt, ...)
{
    char msg[700];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    size_t col = 1;
    for (size_t k = at; k > 0 && c->t[k - 1] != '\n'; --k)
        ++col;
    if (c->is_file)
        snprintf(err, errlen, "%s:%d:%zu: %s", c->what, c->line_of[at], col, msg);
    else
        snprintf(err, errlen, "%s:%zu: %s", c->what, col, msg);
    return EXIT_USAGE;
}

static const char *const puncts3[] = { "<<=", ">>=", "...", NULL };
static const char *const puncts2[] = { "->", "++", "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||", "*=",
                                       "/=", "%=", "+=", "-=", "&=", "^=", "|=", "##", NULL };

static int push_tok(struct code *c, size_t *cap, enum tok_kind kind, size_t at, size_t len, int directive, int first)
{
    if (c->ntok == *cap) {
        size_t ncap = *cap ? *cap * 2 : 256;
        struct tok *nt = realloc(c->tok, ncap * sizeof *nt);
        if (!nt)
            return -1;
        c->tok = nt;
        *cap = ncap;
    }
    c->tok[c->ntok++] = (struct tok){ kind, at, len, directive, first };
    return 0;
}

/* Splits the text into tokens; a directive's line ends with a T_DIRECTIVE_END token. */
static int tokenize(struct code *c, char *err, size_t errlen)
{
    size_t cap = 0;
    int bol = 1, in_directive = 0;
    const char *t = c->t;
    for (size_t i = 0; i < c->len;) {
        char ch = t[i];
        if (ch == '\n') {
            if (in_directive && push_tok(c, &cap, T_DIRECTIVE_END, i, 0, 1, 0))
                goto oom;
            in_directive = 0;
            bol = 1;
            ++i;
            continue;
        }
        if (isspace((unsigned char)ch)) {
            ++i;
            continue;
        }
        if (ch == '/' && i + 1 < c->len && t[i + 1] == '*') {
            size_t k = i + 2;
            while (k + 1 < c->len && !(t[k] == '*' && t[k + 1] == '/'))
                ++k;
            i = k + 1 < c->len ? k + 2 : c->len;
            continue;
        }
        if (ch == '/' && i + 1 < c->len && t[i + 1] == '/') {
            while (i < c->len && t[i] != '\n')
                ++i;
            continue;
        }
        int first = bol;
        bol = 0;
        if (first && ch == '#')
            in_directive = 1;
        size_t k = i;
        enum tok_kind kind = T_PUNCT;
        if (isalpha((unsigned char)ch) || ch == '_') {
            while (k < c->len && (isalnum((unsigned char)t[k]) || t[k] == '_'))
                ++k;
            kind = T_IDENT;
        } else if (isdigit((unsigned char)ch) || (ch == '.' && i + 1 < c->len && isdigit((unsigned char)t[i + 1]))) {
            for (++k; k < c->len; ++k) {
                unsigned char u = (unsigned char)t[k];
                if (isalnum(u) || u == '_' || u == '.')
                    continue;
                if ((u == '+' || u == '-') && strchr("eEpP", t[k - 1]))
                    continue;
                break;
            }
            kind = T_NUMBER;
        } else if (ch == '"' || ch == '\'') {
            for (++k; k < c->len && t[k] != ch && t[k] != '\n'; ++k)
                if (t[k] == '\\')
                    ++k;
            if (k < c->len && t[k] == ch)
                ++k;
            kind = T_STRING;
        } else {
            k = i + 1;
            for (int w = 3; w >= 2; --w) {
                const char *const *list = w == 3 ? puncts3 : puncts2;
                if (i + (size_t)w <= c->len)
                    for (int p = 0; list[p]; ++p)
                        if (memcmp(t + i, list[p], (size_t)w) == 0) {
                            k = i + (size_t)w;
                            goto punct_done;
                        }
            }
        punct_done:;
        }
        if (push_tok(c, &cap, kind, i, k - i, in_directive, first))
            goto oom;
        i = k;
    }
    if (in_directive && push_tok(c, &cap, T_DIRECTIVE_END, c->len, 0, 1, 0))
        goto oom;
    return 0;
oom:
    snprintf(err, errlen, "%s: out of memory", c->what);
    return EXIT_RUNTIME;
}

static int tok_is(const struct code *c, size_t i, const char *s)
{
    return i < c->ntok && c->tok[i].len == strlen(s) && memcmp(c->t + c->tok[i].at, s, c->tok[i].len) == 0;
}

static const struct macro *find_macro(const struct code *c, const char *s, size_t n)
{
    for (int i = c->nmac - 1; i >= 0; --i)
        if (strlen(c->mac[i].name) == n && memcmp(c->mac[i].name, s, n) == 0)
            return &c->mac[i];
    return NULL;
}

static int is_function_of_file(const struct code *c, const char *s, size_t n)
{
    for (int i = 0; i < c->nfn; ++i)
        if (strlen(c->fn[i]) == n && memcmp(c->fn[i], s, n) == 0)
            return 1;
    return 0;
}

static int is_type_word(const struct code *c, const char *s, size_t n)
{
    if (is_builtin_type(s, n))
        return 1;
    const struct macro *m = find_macro(c, s, n);
    return m && !m->function_like && m->type_like;
}

/* The names a file defines: its functions (a type, then a name followed by '(', at file
   scope and outside parentheses) and its macros (with whether a replacement ends in a type name). */
static int collect_names(struct code *c, char *err, size_t errlen)
{
    int depth = 0, paren = 0;
    c->fn = calloc(c->ntok + 1, sizeof *c->fn);
    c->mac = calloc(c->ntok + 1, sizeof *c->mac);
    if (!c->fn || !c->mac) {
        snprintf(err, errlen, "%s: out of memory", c->what);
        return EXIT_RUNTIME;
    }
    for (size_t i = 0; i < c->ntok; ++i) {
        const struct tok *k = &c->tok[i];
        if (k->directive) {
            if (k->first_of_line && tok_is(c, i + 1, "define") && i + 2 < c->ntok && c->tok[i + 2].kind == T_IDENT) {
                struct macro *m = &c->mac[c->nmac++];
                const struct tok *nt = &c->tok[i + 2];
                snprintf(m->name, sizeof m->name, "%.*s", (int)(nt->len < 63 ? nt->len : 63), c->t + nt->at);
                size_t j = i + 3;
                /* function-like: '(' right after the name, no space */
                if (tok_is(c, j, "(") && c->tok[j].at == nt->at + nt->len) {
                    m->function_like = 1;
                    for (++j; j < c->ntok && !tok_is(c, j, ")") && c->tok[j].kind != T_DIRECTIVE_END; ++j)
                        if (c->tok[j].kind == T_IDENT && m->nparams < 8)
                            snprintf(m->params[m->nparams++], sizeof m->params[0], "%.*s",
                                     (int)(c->tok[j].len < 63 ? c->tok[j].len : 63), c->t + c->tok[j].at);
                    ++j;
                }
                size_t first = j, last = j;
                while (last < c->ntok && c->tok[last].kind != T_DIRECTIVE_END)
                    ++last;
                if (last > first) {
                    const struct tok *lt = &c->tok[last - 1];
                    m->type_like = lt->kind == T_IDENT && is_type_word(c, c->t + lt->at, lt->len);
                    if (!m->function_like && last - first == 1 && c->tok[first].kind == T_IDENT) {
                        m->alias = c->t + c->tok[first].at;
                        m->alias_len = c->tok[first].len;
                    }
                }
                i = last;
            }
            continue;
        }
        if (tok_is(c, i, "{"))
            ++depth;
        else if (tok_is(c, i, "}"))
            depth -= depth > 0;
        else if (tok_is(c, i, "("))
            ++paren;
        else if (tok_is(c, i, ")"))
            paren -= paren > 0;
        else if (c->is_file && k->kind == T_IDENT && depth == 0 && paren == 0 && tok_is(c, i + 1, "(") && i > 0 &&
                 c->tok[i - 1].kind == T_IDENT && is_type_word(c, c->t + c->tok[i - 1].at, c->tok[i - 1].len) &&
                 !is_builtin_type(c->t + k->at, k->len) && k->len < 64)
            snprintf(c->fn[c->nfn++], sizeof c->fn[0], "%.*s", (int)k->len, c->t + k->at);
    }
    return 0;
}

/* May NAME be called? A built-in, a function or function-like macro of the file, or an
   object-like macro that names one of those. */
static int is_callable(const struct code *c, const char *s, size_t n, int depth)
{
    if (is_allowed_builtin(s, n) || is_function_of_file(c, s, n))
        return 1;
    const struct macro *m = find_macro(c, s, n);
    if (!m)
        return 0;
    if (m->function_like)
        return 1;
    return m->alias && depth < 8 && is_callable(c, m->alias, m->alias_len, depth + 1);
}

enum prev { P_NONE, P_OPERAND, P_TYPE, P_CAST };

/* The checks of a run of tokens [from, to): the file's code, or one macro's replacement.
   params: the macro's parameters (a parameter followed by '(' would call what the user of
   the macro passes). */
static int check_run(const struct code *c, size_t from, size_t to, const struct macro *params, char *err,
                     size_t errlen)
{
    enum prev prev = P_NONE;
    /* per open parenthesis: the contents so far are only type names; it follows a macro */
    struct paren { int only_types, any, macro_call, arg_only_types, arg_any; size_t at; const struct macro *m; };
    struct paren stack[256];
    int sp = 0;
    for (size_t i = from; i < to; ++i) {
        const struct tok *k = &c->tok[i];
        const char *s = c->t + k->at;
        size_t n = k->len;
        if (k->kind == T_STRING)
            return fail_at(c, k->at, err, errlen, "a string or character literal is not accepted in a model (a "
                           "lobe is a formula of numbers)");
        if (k->kind == T_IDENT) {
            const char *why = refused_word(s, n);
            if (why)
                return fail_at(c, k->at, err, errlen, "'%.*s' is not accepted in a model: %s (a model is a formula "
                               "of scalars and vectors: no pointers, no memory beyond its own variables; "
                               "docs/user-models.md)", (int)(n > 40 ? 40 : n), s, why);
            int is_param = 0;
            if (params)
                for (int p = 0; p < params->nparams; ++p)
                    if (strlen(params->params[p]) == n && memcmp(params->params[p], s, n) == 0)
                        is_param = 1;
            if (tok_is(c, i + 1, "(") && !is_statement_word(s, n) && !is_builtin_type(s, n)) {
                if (is_param)
                    return fail_at(c, k->at, err, errlen, "macro parameter '%.*s' is called: a macro may not call "
                                   "what its user passes it", (int)(n > 40 ? 40 : n), s);
                if (!is_callable(c, s, n, 0))
                    return fail_at(c, k->at, err, errlen, "'%.*s' is called, which is neither an OpenCL C math "
                                   "built-in (that takes no pointer) nor a function or macro of the model",
                                   (int)(n > 40 ? 40 : n), s);
            }
            if (sp > 0) {
                if (!is_type_word(c, s, n))
                    stack[sp - 1].only_types = 0;
                stack[sp - 1].any = 1;
                if (!is_type_word(c, s, n))
                    stack[sp - 1].arg_only_types = 0;
                stack[sp - 1].arg_any = 1;
            }
            prev = is_type_word(c, s, n) ? P_TYPE : is_statement_word(s, n) ? P_NONE : P_OPERAND;
            continue;
        }
        if (sp > 0 && !(k->kind == T_PUNCT && (tok_is(c, i, ")") || tok_is(c, i, ",")))) {
            stack[sp - 1].only_types = 0;
            stack[sp - 1].any = 1;
            stack[sp - 1].arg_only_types = 0;
            stack[sp - 1].arg_any = 1;
        }
        if (k->kind == T_NUMBER) {
            prev = P_OPERAND;
            continue;
        }
        if (n == 2 && memcmp(s, "->", 2) == 0)
            return fail_at(c, k->at, err, errlen, "'->' is not accepted in a model (no pointers, no structs)");
        if (n == 1 && (s[0] == '[' || s[0] == ']'))
            return fail_at(c, k->at, err, errlen, "'%c' is not accepted in a model: no arrays or subscripts (an "
                           "index past the end writes outside the model's variables)", s[0]);
        if ((n == 1 && (s[0] == '*' || s[0] == '&')) || (n == 2 && memcmp(s, "&&", 2) == 0)) {
            if (prev != P_OPERAND)
                return fail_at(c, k->at, err, errlen, "'%.*s' %s is not accepted in a model (no pointers: '*' "
                               "and '&' only multiply and mask, between two operands)", (int)n, s,
                               s[0] == '*' ? (prev == P_TYPE || prev == P_CAST ? "after a type (a pointer)"
                                                                              : "as a dereference")
                                           : "as an address-of");
            prev = P_NONE;
            continue;
        }
        if (n == 1 && s[0] == '(') {
            if (prev == P_OPERAND && i > from && tok_is(c, i - 1, ")"))
                return fail_at(c, k->at, err, errlen, "a call of a parenthesised expression is not accepted in a "
                               "model (only named functions are called)");
            if (sp >= (int)(sizeof stack / sizeof stack[0]))
                return fail_at(c, k->at, err, errlen, "parentheses nested more than %d deep",
                               (int)(sizeof stack / sizeof stack[0]));
            const struct macro *m = NULL;
            if (i > from && c->tok[i - 1].kind == T_IDENT)
                m = find_macro(c, c->t + c->tok[i - 1].at, c->tok[i - 1].len);
            stack[sp++] = (struct paren){ 1, 0, m && m->function_like, 1, 0, k->at, m };
            prev = P_NONE;
            continue;
        }
        if (n == 1 && (s[0] == ')' || s[0] == ',') && sp > 0) {
            struct paren *p = &stack[sp - 1];
            if (p->macro_call && p->arg_any && p->arg_only_types)
                return fail_at(c, k->at, err, errlen, "a type name as the argument of macro '%s' is not accepted "
                               "in a model (a macro's parameter stands for a value)", p->m->name);
            p->arg_only_types = 1;
            p->arg_any = 0;
            if (s[0] == ',') {
                p->only_types = 0;
                prev = P_NONE;
                continue;
            }
            int cast = p->any && p->only_types;
            --sp;
            if (sp > 0)
                stack[sp - 1].only_types = 0, stack[sp - 1].any = 1, stack[sp - 1].arg_only_types = 0,
                stack[sp - 1].arg_any = 1;
            prev = cast ? P_CAST : P_OPERAND;
            continue;
        }
        if (n == 1 && s[0] == ')') {
            prev = P_OPERAND;
            continue;
        }
        prev = (n == 2 && (memcmp(s, "++", 2) == 0 || memcmp(s, "--", 2) == 0) && prev == P_OPERAND) ? P_OPERAND
                                                                                                      : P_NONE;
    }
    return 0;
}

static int check_tokens(struct code *c, char *err, size_t errlen)
{
    int rc = collect_names(c, err, errlen);
    if (rc)
        return rc;
    size_t code_from = 0;
    for (size_t i = 0; i < c->ntok; ++i) {
        const struct tok *k = &c->tok[i];
        if (!k->directive)
            continue;
        /* the code before this directive */
        if ((rc = check_run(c, code_from, i, NULL, err, errlen)) != 0)
            return rc;
        size_t end = i;
        while (end < c->ntok && c->tok[end].kind != T_DIRECTIVE_END)
            ++end;
        if (!c->is_file)
            return fail_at(c, k->at, err, errlen, "'#' is not accepted in an expression");
        const struct tok *d = i + 1 < end ? &c->tok[i + 1] : NULL;
        static const char *const fine[] = { "if", "ifdef", "ifndef", "elif", "else", "endif", "undef", "pragma",
                                            "error", "warning", NULL };
        if (d && tok_is(c, i + 1, "define")) {
            const struct macro *m = i + 2 < end ? find_macro(c, c->t + c->tok[i + 2].at, c->tok[i + 2].len) : NULL;
            size_t j = i + 3;
            if (m && m->function_like) {
                while (j < end && !tok_is(c, j, ")"))
                    ++j;
                ++j;
                if (m->type_like)
                    return fail_at(c, c->tok[i + 2].at, err, errlen, "function-like macro '%s' ends in a type "
                                   "name: not accepted in a model (it could declare a pointer)", m->name);
            }
            if (j < end && (rc = check_run(c, j, end, m && m->function_like ? m : NULL, err, errlen)) != 0)
                return rc;
        } else if (!d || d->kind != T_IDENT || !word_in(c->t + d->at, d->len, fine)) {
            return fail_at(c, k->at, err, errlen, "directive '#%.*s' is not accepted in a model (accepted: #define, "
                           "#undef, #if, #ifdef, #ifndef, #elif, #else, #endif, #pragma, #error, #warning)",
                           d ? (int)(d->len > 20 ? 20 : d->len) : 0, d ? c->t + d->at : "");
        } else if (tok_is(c, i + 1, "if") || tok_is(c, i + 1, "elif")) {
            if ((rc = check_run(c, i + 2, end, NULL, err, errlen)) != 0)
                return rc;
        }
        i = end;
        code_from = end + 1;
    }
    return check_run(c, code_from < c->ntok ? code_from : c->ntok, c->ntok, NULL, err, errlen);
}

int usermodel_check_code(const char *text, size_t len, const char *what, int is_file, char *err, size_t errlen)
{
    /* A test of the host reference's isolation (tests/test_hostile.sh) needs a model that
       reaches it unchecked; nothing else sets this. */
    const char *skip = getenv("BRDFBENCH_TEST_UNCHECKED_MODEL_CODE");
    if (skip && strcmp(skip, "1") == 0)
        return 0;
    struct code c = { 0 };
    char *t = malloc(len + 1);
    int *line_of = malloc((len + 1) * sizeof *line_of);
    int rc = 0;
    if (!t || !line_of) {
        snprintf(err, errlen, "%s: out of memory", what);
        rc = EXIT_RUNTIME;
        goto done;
    }
    size_t n = 0;
    int line = 1;
    for (size_t i = 0; i < len; ++i) {
        if (text[i] == '\\' && i + 1 < len &&
            (text[i + 1] == '\n' || (text[i + 1] == '\r' && i + 2 < len && text[i + 2] == '\n'))) {
            i += text[i + 1] == '\r' ? 2 : 1;
            ++line;
            continue;
        }
        line_of[n] = line;
        t[n++] = text[i];
        if (text[i] == '\n')
            ++line;
    }
    t[n] = '\0';
    line_of[n] = line;
    c.t = t;
    c.len = n;
    c.line_of = line_of;
    c.what = what;
    c.is_file = is_file;
    if ((rc = tokenize(&c, err, errlen)) == 0)
        rc = check_tokens(&c, err, errlen);
done:
    free(c.tok);
    free(c.fn);
    free(c.mac);
    free(t);
    free(line_of);
    return rc;
}
