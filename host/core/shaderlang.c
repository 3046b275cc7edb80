/* shaderlang.c - GLSL/HLSL-style model texts translated into the OpenCL C user-model form
 * (see shaderlang.h and docs/user-models.md, "Shader-language models").
 *
 * Three stages: a lexer (comments, object-like #define, numbers with their suffixes), a
 * recursive-descent parser to a small syntax tree, and an emitter that checks types while it
 * writes the C. The emitter writes straight-line code: every float value is REAL, a vector is
 * one REAL per component, a value that is used more than once is kept in a temporary, and
 * control flow becomes selection: an assignment under `if` is `x = mask ? new : x`, a return
 * under `if` sets the result and clears a "still running" mask. Integers and booleans that
 * depend only on literals and integers stay C ints (the same in every lane); a boolean that may
 * differ between lanes is kept as a REAL mask of 0 and 1, so that its type is REAL's in every
 * build. A failure anywhere longjmps to the entry point with its message. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "exitcodes.h"
#include "mdbuf.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SL_NAME_MAX 48       /* as USERMODEL_NAME_MAX */
#define SL_MAX_PARAMS 2      /* as MODEL_MAX_PARAMS */
#define SL_MAX_ARGS 8
#define SL_MAX_UNROLL 256    /* iterations of one unrolled for loop */
#define SL_MAX_INLINE 16     /* nested calls of helper functions */
#define SL_MAX_MACRO_DEPTH 16
#define SL_MAX_NESTING 200   /* parentheses, operators and statements inside each other */

/* ---- memory: one arena per translation ------------------------------------------------ */

struct arena_block {
    struct arena_block *next;
    size_t used, cap;
    max_align_t data[];
};

enum tok_kind { K_EOF, K_ID, K_INT, K_FLT, K_OP };

struct tok {
    int k;
    int line, col;
    const char *p;
    int len;
};

struct tokv {
    struct tok *v;
    int n, cap;
};

struct macro {
    const char *name;
    int len;
    struct tokv body;
    int active;
    struct macro *next;
};

enum base { B_VOID, B_BOOL, B_INT, B_FLOAT };
struct type {
    int b;
    int n; /* components: 1 to 4 (vectors of float only) */
};

enum expr_kind { E_FLT, E_INT, E_BOOL, E_VAR, E_UN, E_BIN, E_TER, E_CALL, E_SWZ };
struct expr {
    int k;
    const struct tok *t;   /* where it is, for messages; the name of a variable or a call */
    int op;
    struct expr *a, *b, *c;
    struct expr **args;
    int nargs;
    int swz[4], nswz;
    int is_cast;
};

enum stmt_kind { S_DECL, S_ASSIGN, S_IF, S_BLOCK, S_RET, S_FOR, S_EMPTY };
struct stmt {
    int k;
    const struct tok *t;
    struct type ty;        /* S_DECL */
    int is_const;
    const struct tok *name;
    struct expr *e;        /* init, rhs, condition, returned value */
    struct expr *lhs;
    int op;
    struct stmt *s1, *s2, *s3; /* then/else; for: init, step, body */
    struct stmt **items;   /* S_BLOCK */
    int n, cap;
};

struct func {
    const struct tok *name;
    struct type ret;
    int nparams;
    struct type pty[SL_MAX_ARGS];
    const struct tok *pname[SL_MAX_ARGS];
    struct stmt *body;
    const struct tok *close;
    struct func *next;
};

struct sym {
    const char *name;
    int len;
    struct type t;
    const char *c[4];     /* the C names of its components */
    int is_const;
    int has_value;        /* a constant int: its value */
    long value;
    struct sym *next;
};

struct scope {
    struct sym *syms;
    struct scope *up;
    int function_level;   /* implicit declarations go here */
};

struct fnctx {
    struct type ret;
    const char *ret_c[4];  /* NULL until needed (the model function), else declared */
    const char *live;      /* condition "this lane has not returned yet", NULL before any early return */
    const char *live_var;
    int is_model;
    int returned;          /* the model function has returned (a plain return was written) */
};

struct used_name {
    const char *s;
    struct used_name *next;
};

struct sl {
    jmp_buf fail;
    char *err;
    size_t errlen;
    const char *origin;
    const char *src;           /* the text being translated */
    struct arena_block *arena;
    struct tokv toks;
    int pos;
    struct macro *macros;
    int allow_implicit;        /* the body form: assigning an undeclared name declares it */
    int shader_only;           /* the text used something OpenCL C has not */
    int unknown_name;          /* the failure was an unknown name */
    int statement_form;
    struct md_buf out;
    int line_next;             /* the line number the next output line has */
    int stmt_line;
    int ntemp;
    struct used_name *used;
    struct scope *scope, *globals;
    struct func *funcs;
    const struct func *inlining[SL_MAX_INLINE];
    int ninline;
    struct fnctx *fn;
    int depth;                 /* of the parser's recursion */
};

static void *arena_alloc(struct sl *S, size_t n);

static void sl_fail_at(struct sl *S, int line, int col, const char *fmt, ...) __attribute__((format(printf, 4, 5), noreturn));
static void sl_fail_at(struct sl *S, int line, int col, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(S->err, S->errlen, "%s:%d:%d: %s", S->origin, line, col, msg);
    else
        snprintf(S->err, S->errlen, "%s: %s", S->origin, msg);
    longjmp(S->fail, 1);
}

#define FAIL(S, t, ...) sl_fail_at((S), (t) ? (t)->line : 0, (t) ? (t)->col : 0, __VA_ARGS__)

static void *arena_alloc(struct sl *S, size_t n)
{
    n = (n + sizeof(max_align_t) - 1) / sizeof(max_align_t) * sizeof(max_align_t);
    struct arena_block *b = S->arena;
    if (!b || b->cap - b->used < n) {
        size_t cap = n > 65536 ? n : 65536;
        b = malloc(sizeof *b + cap);
        if (!b)
            sl_fail_at(S, 0, 0, "out of memory");
        b->cap = cap;
        b->used = 0;
        b->next = S->arena;
        S->arena = b;
    }
    void *p = (char *)b->data + b->used;
    b->used += n;
    memset(p, 0, n);
    return p;
}

static const char *sfmt(struct sl *S, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static const char *sfmt(struct sl *S, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = arena_alloc(S, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

static const char *tok_str(struct sl *S, const struct tok *t) { return sfmt(S, "%.*s", t->len, t->p); }

static int tok_is(const struct tok *t, const char *s)
{
    return (t->k == K_ID || t->k == K_OP) && (int)strlen(s) == t->len && strncmp(t->p, s, (size_t)t->len) == 0;
}

/* ---- the lexer ------------------------------------------------------------------------ */

static void tokv_push(struct sl *S, struct tokv *v, struct tok t)
{
    if (v->n == v->cap) {
        int cap = v->cap ? 2 * v->cap : 256;
        struct tok *nv = arena_alloc(S, sizeof *nv * (size_t)cap);
        if (v->n)
            memcpy(nv, v->v, sizeof *nv * (size_t)v->n);
        v->v = nv;
        v->cap = cap;
    }
    v->v[v->n++] = t;
}

static struct macro *find_macro(struct sl *S, const struct tok *t)
{
    for (struct macro *m = S->macros; m; m = m->next)
        if (m->len == t->len && strncmp(m->name, t->p, (size_t)t->len) == 0)
            return m;
    return NULL;
}

/* Appends a token to the program, expanding object-like macros. */
static void push_expanded(struct sl *S, struct tok t, int depth)
{
    struct macro *m = t.k == K_ID ? find_macro(S, &t) : NULL;
    if (!m || m->active) {
        tokv_push(S, &S->toks, t);
        return;
    }
    if (depth >= SL_MAX_MACRO_DEPTH)
        sl_fail_at(S, t.line, t.col, "macro '%.*s' expands more than %d levels deep", t.len, t.p, SL_MAX_MACRO_DEPTH);
    m->active = 1;
    for (int i = 0; i < m->body.n; ++i)
        push_expanded(S, m->body.v[i], depth + 1);
    m->active = 0;
}

static const char *const ops2[] = { "+=", "-=", "*=", "/=", "%=", "++", "--", "==", "!=", "<=", ">=", "&&", "||", NULL };
static const char ops1[] = "+-*/%(){}[],;?:=<>!.";

/* Tokens of [p, end): into the program (macros expanded), or into a macro's body. */
static void lex_span(struct sl *S, const char *p, const char *end, int line, int col, struct tokv *into)
{
    int at_line_start = 1;
    while (p < end) {
        unsigned char ch = (unsigned char)*p;
        if (ch == '\n') {
            ++line;
            col = 1;
            ++p;
            at_line_start = 1;
            continue;
        }
        if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') {
            ++p;
            ++col;
            continue;
        }
        if (ch == '/' && p + 1 < end && p[1] == '/') {
            while (p < end && *p != '\n')
                ++p;
            continue;
        }
        if (ch == '/' && p + 1 < end && p[1] == '*') {
            int l0 = line, c0 = col;
            p += 2;
            col += 2;
            while (p < end && !(p[0] == '*' && p + 1 < end && p[1] == '/')) {
                if (*p == '\n') {
                    ++line;
                    col = 1;
                } else {
                    ++col;
                }
                ++p;
            }
            if (p >= end)
                sl_fail_at(S, l0, c0, "unterminated comment");
            p += 2;
            col += 2;
            continue;
        }
        if (ch == '#') {
            if (!at_line_start || into)
                sl_fail_at(S, line, col, "'#' is only allowed at the start of a line (a preprocessor directive)");
            S->shader_only = 1;
            const char *eol = memchr(p, '\n', (size_t)(end - p));
            if (!eol)
                eol = end;
            const char *q = p + 1;
            while (q < eol && (*q == ' ' || *q == '\t'))
                ++q;
            const char *w = q;
            while (q < eol && isalpha((unsigned char)*q))
                ++q;
            int wl = (int)(q - w);
            if ((wl == 7 && strncmp(w, "version", 7) == 0) || (wl == 9 && strncmp(w, "extension", 9) == 0) ||
                (wl == 6 && strncmp(w, "pragma", 6) == 0)) {
                /* nothing for a lobe: skipped */
            } else if (wl == 6 && strncmp(w, "define", 6) == 0) {
                while (q < eol && (*q == ' ' || *q == '\t'))
                    ++q;
                const char *nm = q;
                while (q < eol && (isalnum((unsigned char)*q) || *q == '_'))
                    ++q;
                if (q == nm || isdigit((unsigned char)*nm))
                    sl_fail_at(S, line, col + (int)(nm - p), "#define needs a name");
                if (q < eol && *q == '(')
                    sl_fail_at(S, line, col + (int)(q - p),
                               "function-like macros are not supported (write a function instead)");
                struct macro *m = arena_alloc(S, sizeof *m);
                m->name = nm;
                m->len = (int)(q - nm);
                lex_span(S, q, eol, line, col + (int)(q - p), &m->body);
                m->next = S->macros;
                S->macros = m;
            } else {
                sl_fail_at(S, line, col, "preprocessor directive '#%.*s' is not supported (#define NAME VALUE, "
                           "#version, #extension and #pragma are)", wl, w);
            }
            col += (int)(eol - p);
            p = eol;
            continue;
        }
        at_line_start = 0;
        struct tok t = { K_EOF, line, col, p, 0 };
        if (isalpha(ch) || ch == '_') {
            const char *q = p;
            while (q < end && (isalnum((unsigned char)*q) || *q == '_'))
                ++q;
            t.k = K_ID;
            t.len = (int)(q - p);
        } else if (isdigit(ch) || (ch == '.' && p + 1 < end && isdigit((unsigned char)p[1]))) {
            const char *q = p;
            int is_float = 0;
            if (ch == '0' && q + 1 < end && (q[1] == 'x' || q[1] == 'X'))
                sl_fail_at(S, line, col, "hexadecimal numbers are not supported");
            while (q < end && isdigit((unsigned char)*q))
                ++q;
            if (q < end && *q == '.') {
                is_float = 1;
                ++q;
                while (q < end && isdigit((unsigned char)*q))
                    ++q;
            }
            if (q < end && (*q == 'e' || *q == 'E')) {
                const char *r = q + 1;
                if (r < end && (*r == '+' || *r == '-'))
                    ++r;
                if (r >= end || !isdigit((unsigned char)*r))
                    sl_fail_at(S, line, col, "malformed exponent in the number '%.*s'", (int)(r - p), p);
                while (r < end && isdigit((unsigned char)*r))
                    ++r;
                q = r;
                is_float = 1;
            }
            /* Suffixes: f F h H lf LF (float), u U (int). */
            if (q < end && (*q == 'f' || *q == 'F' || *q == 'h' || *q == 'H')) {
                if (*q == 'h' || *q == 'H')
                    S->shader_only = 1;
                ++q;
                is_float = 1;
            } else if (q + 1 < end && (q[0] == 'l' || q[0] == 'L') && (q[1] == 'f' || q[1] == 'F')) {
                q += 2;
                is_float = 1;
                S->shader_only = 1;
            } else if (!is_float && q < end && (*q == 'u' || *q == 'U')) {
                ++q;
            }
            if (q < end && (isalnum((unsigned char)*q) || *q == '_' || *q == '.'))
                sl_fail_at(S, line, col, "malformed number '%.*s'", (int)(q - p) + 1, p);
            t.k = is_float ? K_FLT : K_INT;
            t.len = (int)(q - p);
        } else {
            t.k = K_OP;
            for (int i = 0; ops2[i]; ++i)
                if (p + 1 < end && p[0] == ops2[i][0] && p[1] == ops2[i][1])
                    t.len = 2;
            if (!t.len && strchr(ops1, ch) && ch)
                t.len = 1;
            if (!t.len) {
                if (ch < 0x20 || ch > 0x7e)
                    sl_fail_at(S, line, col, "character 0x%02x is not allowed in a model", ch);
                sl_fail_at(S, line, col, "'%c' is not an operator of a model (+ - * / %% comparisons && || ! ?: "
                           "= and the compound assignments are)", ch);
            }
        }
        if (into)
            tokv_push(S, into, t);
        else
            push_expanded(S, t, 0);
        p += t.len;
        col += t.len;
    }
}

/* ---- the parser ------------------------------------------------------------------------- */

static const struct tok *peek(struct sl *S) { return &S->toks.v[S->pos]; }
static const struct tok *peek_at(struct sl *S, int k)
{
    int i = S->pos + k;
    return &S->toks.v[i < S->toks.n ? i : S->toks.n - 1];
}
static const struct tok *next(struct sl *S)
{
    const struct tok *t = &S->toks.v[S->pos];
    if (t->k != K_EOF)
        ++S->pos;
    return t;
}
static int accept(struct sl *S, const char *s)
{
    if (tok_is(peek(S), s)) {
        next(S);
        return 1;
    }
    return 0;
}
static const char *tok_desc(struct sl *S, const struct tok *t)
{
    return t->k == K_EOF ? "the end of the text" : sfmt(S, "'%.*s'", t->len > 40 ? 40 : t->len, t->p);
}
static const struct tok *expect(struct sl *S, const char *s)
{
    const struct tok *t = peek(S);
    if (!tok_is(t, s))
        FAIL(S, t, "expected '%s', found %s", s, tok_desc(S, t));
    return next(S);
}

/* A type name: float, half, vec2..4, float2..4, half2..4, int, uint, bool, void. 1 when t is one. */
static int type_of_name(const struct tok *t, struct type *ty, int *shader_only)
{
    if (t->k != K_ID)
        return 0;
    char w[16];
    if (t->len >= (int)sizeof w)
        return 0;
    memcpy(w, t->p, (size_t)t->len);
    w[t->len] = '\0';
    *shader_only = 0;
    if (strcmp(w, "float") == 0 || strcmp(w, "half") == 0 || strcmp(w, "min16float") == 0) {
        *ty = (struct type){ B_FLOAT, 1 };
        return 1;
    }
    if (strcmp(w, "int") == 0 || strcmp(w, "uint") == 0) {
        *ty = (struct type){ B_INT, 1 };
        return 1;
    }
    if (strcmp(w, "bool") == 0) {
        *ty = (struct type){ B_BOOL, 1 };
        return 1;
    }
    if (strcmp(w, "void") == 0) {
        *ty = (struct type){ B_VOID, 1 };
        return 1;
    }
    size_t l = strlen(w);
    char last = w[l - 1];
    if (last >= '2' && last <= '4') {
        w[l - 1] = '\0';
        if (strcmp(w, "vec") == 0 || strcmp(w, "float") == 0 || strcmp(w, "half") == 0) {
            *ty = (struct type){ B_FLOAT, last - '0' };
            *shader_only = 1;
            return 1;
        }
    }
    return 0;
}

static int is_qualifier(const struct tok *t)
{
    static const char *q[] = { "highp", "mediump", "lowp", "precise", "in", NULL };
    for (int i = 0; q[i]; ++i)
        if (tok_is(t, q[i]))
            return 1;
    return 0;
}

static void check_unsupported_word(struct sl *S, const struct tok *t)
{
    static const struct { const char *w, *why; } words[] = {
        { "while", "while loops are not supported (a for loop with constant bounds is)" },
        { "do", "do loops are not supported (a for loop with constant bounds is)" },
        { "switch", "switch is not supported (use if/else)" },
        { "break", "break is not supported" },
        { "continue", "continue is not supported" },
        { "discard", "discard is not supported" },
        { "struct", "structs are not supported" },
        { "uniform", "uniforms are not supported: declare the model's parameters in the header "
                     "('param: NAME MIN MAX DEFAULT') and take them as the function's arguments after c and n" },
        { "out", "out parameters are not supported" },
        { "inout", "inout parameters are not supported" },
        { "double", "double is not supported (write float: the reference is double anyway)" },
        { "mat2", "matrices are not supported" }, { "mat3", "matrices are not supported" },
        { "mat4", "matrices are not supported" }, { "float3x3", "matrices are not supported" },
        { "float4x4", "matrices are not supported" },
        { NULL, NULL } };
    for (int i = 0; words[i].w; ++i)
        if (tok_is(t, words[i].w))
            FAIL(S, t, "%s", words[i].why);
}

static struct expr *new_expr(struct sl *S, int k, const struct tok *t)
{
    struct expr *e = arena_alloc(S, sizeof *e);
    e->k = k;
    e->t = t;
    return e;
}

static struct expr *parse_expr(struct sl *S);

static int swizzle_index(char ch)
{
    const char *sets[] = { "xyzw", "rgba", "stpq" };
    for (int s = 0; s < 3; ++s)
        for (int i = 0; i < 4; ++i)
            if (sets[s][i] == ch)
                return i;
    return -1;
}

static struct expr *parse_call_args(struct sl *S, struct expr *e)
{
    expect(S, "(");
    struct expr *args[SL_MAX_ARGS];
    int n = 0;
    if (!accept(S, ")")) {
        for (;;) {
            if (n == SL_MAX_ARGS)
                FAIL(S, peek(S), "more than %d arguments", SL_MAX_ARGS);
            args[n++] = parse_expr(S);
            if (accept(S, ")"))
                break;
            expect(S, ",");
        }
    }
    e->args = arena_alloc(S, sizeof *e->args * (size_t)(n ? n : 1));
    memcpy(e->args, args, sizeof *args * (size_t)n);
    e->nargs = n;
    return e;
}

static struct expr *parse_unary(struct sl *S);

static struct expr *parse_primary(struct sl *S)
{
    const struct tok *t = peek(S);
    struct type ty;
    int so;
    if (t->k == K_FLT) {
        next(S);
        return new_expr(S, E_FLT, t);
    }
    if (t->k == K_INT) {
        next(S);
        return new_expr(S, E_INT, t);
    }
    if (t->k == K_ID) {
        check_unsupported_word(S, t);
        if (tok_is(t, "true") || tok_is(t, "false")) {
            next(S);
            S->shader_only = 1;
            return new_expr(S, E_BOOL, t);
        }
        next(S);
        if (tok_is(peek(S), "(")) {
            if (type_of_name(t, &ty, &so))
                S->shader_only = 1;
            return parse_call_args(S, new_expr(S, E_CALL, t));
        }
        if (type_of_name(t, &ty, &so))
            FAIL(S, t, "a type name here: a constructor takes its components in parentheses, e.g. %.*s(...)",
                 t->len, t->p);
        return new_expr(S, E_VAR, t);
    }
    if (tok_is(t, "(")) {
        const struct tok *t1 = peek_at(S, 1);
        if (type_of_name(t1, &ty, &so) && tok_is(peek_at(S, 2), ")")) {
            /* a cast: (float)x, (int)x, (float3)x */
            next(S);
            next(S);
            next(S);
            S->shader_only = 1;
            struct expr *e = new_expr(S, E_CALL, t1);
            e->is_cast = 1;
            e->args = arena_alloc(S, sizeof *e->args);
            e->args[0] = parse_unary(S);
            e->nargs = 1;
            return e;
        }
        next(S);
        struct expr *e = parse_expr(S);
        expect(S, ")");
        return e;
    }
    FAIL(S, t, "expected a value, found %s", tok_desc(S, t));
}

static struct expr *parse_postfix(struct sl *S)
{
    struct expr *e = parse_primary(S);
    while (tok_is(peek(S), ".")) {
        const struct tok *dot = next(S);
        const struct tok *f = peek(S);
        if (f->k != K_ID)
            FAIL(S, f, "expected a swizzle (.x, .xy, .rgb, ...) after '.'");
        next(S);
        struct expr *s = new_expr(S, E_SWZ, dot);
        s->a = e;
        if (f->len > 4)
            FAIL(S, f, "a swizzle has 1 to 4 components, '%.*s' has %d", f->len, f->p, f->len);
        for (int i = 0; i < f->len; ++i) {
            int k = swizzle_index(f->p[i]);
            if (k < 0)
                FAIL(S, f, "'%c' is not a component (x y z w, r g b a or s t p q)", f->p[i]);
            s->swz[i] = k;
        }
        s->nswz = f->len;
        S->shader_only = 1;
        e = s;
    }
    if (tok_is(peek(S), "["))
        FAIL(S, peek(S), "indexing with [] is not supported (use .x, .y, ...)");
    return e;
}

static struct expr *parse_unary_inner(struct sl *S);
static struct expr *parse_unary(struct sl *S)
{
    if (++S->depth > SL_MAX_NESTING)
        FAIL(S, peek(S), "nested more than %d levels deep", SL_MAX_NESTING);
    struct expr *e = parse_unary_inner(S);
    --S->depth;
    return e;
}

static struct expr *parse_unary_inner(struct sl *S)
{
    const struct tok *t = peek(S);
    if (tok_is(t, "-") || tok_is(t, "+") || tok_is(t, "!")) {
        next(S);
        struct expr *e = new_expr(S, E_UN, t);
        e->op = t->p[0] == '-' ? 'u' : t->p[0] == '+' ? 'p' : '!';
        e->a = parse_unary(S);
        return e;
    }
    if (tok_is(t, "++") || tok_is(t, "--"))
        FAIL(S, t, "'%.*s' is a statement here: write it on its own (++x;)", t->len, t->p);
    return parse_postfix(S);
}

/* Binary operators by precedence level (lowest first). */
static int binop_code(const struct tok *t, int level)
{
    if (t->k != K_OP)
        return 0;
    static const struct { const char *s; int code, level; } ops[] = {
        { "||", 'O', 0 }, { "&&", 'A', 1 }, { "==", 'E', 2 }, { "!=", 'N', 2 }, { "<", '<', 3 },
        { ">", '>', 3 },  { "<=", 'L', 3 }, { ">=", 'G', 3 }, { "+", '+', 4 },  { "-", '-', 4 },
        { "*", '*', 5 },  { "/", '/', 5 },  { "%", '%', 5 },  { NULL, 0, 0 } };
    for (int i = 0; ops[i].s; ++i)
        if (ops[i].level == level && tok_is(t, ops[i].s))
            return ops[i].code;
    return 0;
}

static struct expr *parse_binary(struct sl *S, int level)
{
    if (level > 5)
        return parse_unary(S);
    struct expr *e = parse_binary(S, level + 1);
    for (;;) {
        const struct tok *t = peek(S);
        int code = binop_code(t, level);
        if (!code)
            return e;
        next(S);
        struct expr *b = new_expr(S, E_BIN, t);
        b->op = code;
        b->a = e;
        b->b = parse_binary(S, level + 1);
        e = b;
    }
}

static struct expr *parse_expr(struct sl *S)
{
    struct expr *c = parse_binary(S, 0);
    if (tok_is(peek(S), "?")) {
        const struct tok *q = next(S);
        struct expr *e = new_expr(S, E_TER, q);
        e->a = c;
        e->b = parse_expr(S);
        expect(S, ":");
        e->c = parse_expr(S);
        return e;
    }
    return c;
}

static struct stmt *new_stmt(struct sl *S, int k, const struct tok *t)
{
    struct stmt *s = arena_alloc(S, sizeof *s);
    s->k = k;
    s->t = t;
    return s;
}

static void block_add(struct sl *S, struct stmt *b, struct stmt *s)
{
    if (b->n == b->cap) {
        int cap = b->cap ? 2 * b->cap : 8;
        struct stmt **v = arena_alloc(S, sizeof *v * (size_t)cap);
        if (b->n)
            memcpy(v, b->items, sizeof *v * (size_t)b->n);
        b->items = v;
        b->cap = cap;
    }
    b->items[b->n++] = s;
}

/* Qualifiers and a type, if the next tokens are one. */
static int parse_decl_type(struct sl *S, struct type *ty, int *is_const)
{
    int save = S->pos;
    *is_const = 0;
    for (;;) {
        const struct tok *t = peek(S);
        if (tok_is(t, "const")) {
            *is_const = 1;
            next(S);
        } else if (tok_is(t, "static") || is_qualifier(t)) {
            next(S);
        } else {
            break;
        }
    }
    int so;
    const struct tok *t = peek(S);
    check_unsupported_word(S, t);
    if (type_of_name(t, ty, &so) && !tok_is(peek_at(S, 1), "(")) {
        if (so)
            S->shader_only = 1;
        next(S);
        return 1;
    }
    S->pos = save;
    return 0;
}

static struct stmt *parse_statement(struct sl *S, int top_body);

/* Declarations of one type: `float a = 1.0, b;` as a block of S_DECL (no scope of its own). */
static struct stmt *parse_declaration(struct sl *S, struct type ty, int is_const, const struct tok *start)
{
    struct stmt *list = new_stmt(S, S_BLOCK, start);
    list->op = 1; /* no scope */
    for (;;) {
        const struct tok *name = peek(S);
        if (name->k != K_ID)
            FAIL(S, name, "expected a variable name, found %s", tok_desc(S, name));
        check_unsupported_word(S, name);
        next(S);
        struct stmt *d = new_stmt(S, S_DECL, name);
        d->ty = ty;
        d->is_const = is_const;
        d->name = name;
        if (tok_is(peek(S), "["))
            FAIL(S, peek(S), "arrays are not supported");
        if (accept(S, "="))
            d->e = parse_expr(S);
        else if (is_const)
            FAIL(S, name, "const '%.*s' needs a value", name->len, name->p);
        block_add(S, list, d);
        if (accept(S, ";"))
            return list;
        expect(S, ",");
    }
}

static struct stmt *parse_block(struct sl *S)
{
    const struct tok *open = expect(S, "{");
    struct stmt *b = new_stmt(S, S_BLOCK, open);
    while (!tok_is(peek(S), "}")) {
        if (peek(S)->k == K_EOF)
            FAIL(S, open, "this '{' is not closed");
        block_add(S, b, parse_statement(S, 0));
    }
    next(S);
    return b;
}

static struct stmt *parse_simple(struct sl *S, int top_body, int need_semicolon)
{
    const struct tok *t = peek(S);
    struct type ty;
    int is_const;
    if (parse_decl_type(S, &ty, &is_const)) {
        if (ty.b == B_VOID)
            FAIL(S, t, "a variable cannot be void");
        return parse_declaration(S, ty, is_const, t);
    }
    if (tok_is(t, "++") || tok_is(t, "--")) {
        next(S);
        struct stmt *s = new_stmt(S, S_ASSIGN, t);
        s->lhs = parse_unary(S);
        s->op = t->p[0];
        s->e = new_expr(S, E_INT, t);
        s->e->op = 1; /* the literal 1 */
        if (need_semicolon)
            expect(S, ";");
        return s;
    }
    struct expr *e = parse_expr(S);
    const struct tok *a = peek(S);
    struct stmt *s = new_stmt(S, S_ASSIGN, a);
    s->lhs = e;
    if (tok_is(a, "=") || tok_is(a, "+=") || tok_is(a, "-=") || tok_is(a, "*=") || tok_is(a, "/=") ||
        tok_is(a, "%=")) {
        next(S);
        s->op = a->len == 1 ? '=' : a->p[0];
        s->e = parse_expr(S);
    } else if (tok_is(a, "++") || tok_is(a, "--")) {
        next(S);
        s->op = a->p[0];
        s->e = new_expr(S, E_INT, a);
        s->e->op = 1;
    } else if (top_body && a->k == K_EOF) {
        /* the body form's last expression, without return: its value */
        struct stmt *r = new_stmt(S, S_RET, e->t);
        r->e = e;
        return r;
    } else {
        if (tok_is(a, ";"))
            FAIL(S, e->t, "this expression is computed and then dropped (assign it, or return it)");
        FAIL(S, a, "expected ';' or an assignment, found %s", tok_desc(S, a));
    }
    if (need_semicolon)
        expect(S, ";");
    return s;
}

static struct stmt *parse_statement_inner(struct sl *S, int top_body);
static struct stmt *parse_statement(struct sl *S, int top_body)
{
    if (++S->depth > SL_MAX_NESTING)
        FAIL(S, peek(S), "nested more than %d levels deep", SL_MAX_NESTING);
    struct stmt *st = parse_statement_inner(S, top_body);
    --S->depth;
    return st;
}

static struct stmt *parse_statement_inner(struct sl *S, int top_body)
{
    const struct tok *t = peek(S);
    check_unsupported_word(S, t);
    if (tok_is(t, "{"))
        return parse_block(S);
    if (accept(S, ";"))
        return new_stmt(S, S_EMPTY, t);
    if (tok_is(t, "if")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = new_stmt(S, S_IF, t);
        expect(S, "(");
        s->e = parse_expr(S);
        expect(S, ")");
        s->s1 = parse_statement(S, 0);
        if (accept(S, "else"))
            s->s2 = parse_statement(S, 0);
        return s;
    }
    if (tok_is(t, "else"))
        FAIL(S, t, "'else' without an 'if'");
    if (tok_is(t, "return")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = new_stmt(S, S_RET, t);
        if (tok_is(peek(S), ";"))
            FAIL(S, peek(S), "return needs a value");
        s->e = parse_expr(S);
        if (!(top_body && peek(S)->k == K_EOF))
            expect(S, ";");
        return s;
    }
    if (tok_is(t, "for")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = new_stmt(S, S_FOR, t);
        expect(S, "(");
        s->s1 = parse_simple(S, 0, 0);
        if (s->s1->k == S_BLOCK && s->s1->op == 1) {
            /* parse_declaration consumed the ';' */
        } else {
            expect(S, ";");
        }
        s->e = parse_expr(S);
        expect(S, ";");
        s->s2 = parse_simple(S, 0, 0);
        expect(S, ")");
        s->s3 = parse_statement(S, 0);
        return s;
    }
    return parse_simple(S, top_body, 1);
}

/* ---- checking and emitting ---------------------------------------------------------------- */

struct val {
    struct type t;
    const char *c[4];
    int uniform;   /* the same in every lane (literals, ints, uniform booleans) */
};

static const char *type_name(struct sl *S, struct type t)
{
    switch (t.b) {
    case B_VOID: return "void";
    case B_BOOL: return "bool";
    case B_INT: return "int";
    default: return t.n == 1 ? "float" : sfmt(S, "vec%d", t.n);
    }
}

/* Output lines carry the user's line: a #line directive wherever the next line's number differs. */
static void out_line(struct sl *S, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void out_line(struct sl *S, const char *fmt, ...)
{
    int cont = S->stmt_line > 0 && S->line_next == S->stmt_line + 1 && S->out.len > 0 &&
               S->out.s[S->out.len - 1] == '\n';
    if (!cont && S->stmt_line > 0 && S->line_next != S->stmt_line) {
        md_printf(&S->out, "#line %d \"", S->stmt_line);
        for (const char *p = S->origin; *p; ++p) {
            if (*p == '"' || *p == '\\')
                md_append(&S->out, "\\", 1);
            md_append(&S->out, p, 1);
        }
        md_append(&S->out, "\"\n", 2);
        S->line_next = S->stmt_line;
    }
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (cont) {
        /* the same user line as the previous output line: continue it */
        S->out.s[--S->out.len] = '\0';
        md_append(&S->out, " ", 1);
        --S->line_next;
    } else {
        md_append(&S->out, "    ", 4);
    }
    if (n >= (int)sizeof buf) {
        char *big = arena_alloc(S, (size_t)n + 1);
        va_start(ap, fmt);
        vsnprintf(big, (size_t)n + 1, fmt, ap);
        va_end(ap);
        md_append(&S->out, big, (size_t)n);
    } else {
        md_append(&S->out, buf, (size_t)n);
    }
    md_append(&S->out, "\n", 1);
    ++S->line_next;
    if (S->out.failed)
        sl_fail_at(S, 0, 0, "out of memory");
}

/* A C name for a user variable, unique in the output. */
static const char *c_name(struct sl *S, const char *base)
{
    const char *s = sfmt(S, "u__%s", base);
    for (int k = 2;; ++k) {
        int taken = 0;
        for (struct used_name *u = S->used; u; u = u->next)
            if (strcmp(u->s, s) == 0)
                taken = 1;
        if (!taken)
            break;
        s = sfmt(S, "u__%s_%d", base, k);
    }
    struct used_name *u = arena_alloc(S, sizeof *u);
    u->s = s;
    u->next = S->used;
    S->used = u;
    return s;
}

static int is_simple(const char *s)
{
    int ident = 1;
    for (const char *p = s; *p; ++p)
        if (!isalnum((unsigned char)*p) && *p != '_')
            ident = 0;
    if (ident)
        return 1;
    if (strncmp(s, "RSPLAT(", 7) == 0 && !strchr(s + 7, '(') && !strchr(s, ' '))
        return 1;
    /* a mask read: (sl_mN != RSPLAT(0.0)) */
    if (strncmp(s, "(sl_m", 5) == 0) {
        const char *p = s + 5;
        while (isdigit((unsigned char)*p))
            ++p;
        return strcmp(p, " != RSPLAT(0.0))") == 0;
    }
    return 0;
}

static const char *temp_real(struct sl *S, const char *expr)
{
    if (is_simple(expr))
        return expr;
    const char *t = sfmt(S, "sl_t%d", ++S->ntemp);
    out_line(S, "REAL %s = %s;", t, expr);
    return t;
}

/* A condition kept for later: an int where it is uniform, else a REAL mask. */
static const char *temp_cond(struct sl *S, const char *cond, int uniform)
{
    if (is_simple(cond))
        return cond;
    if (uniform) {
        const char *t = sfmt(S, "sl_b%d", ++S->ntemp);
        out_line(S, "int %s = %s;", t, cond);
        return t;
    }
    int k = ++S->ntemp;
    out_line(S, "REAL sl_m%d = (%s) ? RSPLAT(1.0) : RSPLAT(0.0);", k, cond);
    return sfmt(S, "(sl_m%d != RSPLAT(0.0))", k);
}

static struct val temp_val(struct sl *S, struct val v)
{
    if (v.t.b == B_FLOAT)
        for (int i = 0; i < v.t.n; ++i)
            v.c[i] = temp_real(S, v.c[i]);
    else if (v.t.b == B_BOOL)
        v.c[0] = temp_cond(S, v.c[0], v.uniform);
    else if (!is_simple(v.c[0])) {
        const char *t = sfmt(S, "sl_i%d", ++S->ntemp);
        out_line(S, "int %s = %s;", t, v.c[0]);
        v.c[0] = t;
    }
    return v;
}

/* A number as written, without its suffix, as a C floating literal. */
static const char *float_literal(struct sl *S, const struct tok *t)
{
    int len = t->len;
    while (len > 0 && (t->p[len - 1] == 'f' || t->p[len - 1] == 'F' || t->p[len - 1] == 'h' ||
                       t->p[len - 1] == 'H' || t->p[len - 1] == 'l' || t->p[len - 1] == 'L' ||
                       t->p[len - 1] == 'u' || t->p[len - 1] == 'U'))
        --len;
    const char *s = sfmt(S, "%.*s", len, t->p);
    int has_point = strchr(s, '.') || strchr(s, 'e') || strchr(s, 'E');
    if (!has_point)
        s = sfmt(S, "%s.0", s);
    if (s[0] == '.')
        s = sfmt(S, "0%s", s);
    size_t l = strlen(s);
    if (s[l - 1] == '.')
        s = sfmt(S, "%s0", s);
    return s;
}

static struct val to_float(struct sl *S, struct val v, const struct tok *where)
{
    if (v.t.b == B_FLOAT)
        return v;
    if (v.t.b == B_INT) {
        const char *s = v.c[0];
        int digits = *s != '\0';
        for (const char *p = s; *p; ++p)
            if (!isdigit((unsigned char)*p))
                digits = 0;
        v.c[0] = digits ? sfmt(S, "RSPLAT(%s.0)", s) : sfmt(S, "RSPLAT((RSCALAR)(%s))", s);
        v.t = (struct type){ B_FLOAT, 1 };
        return v;
    }
    FAIL(S, where, "a %s where a number is expected", type_name(S, v.t));
}

/* Converts v to type t where the languages do it implicitly: int to float, a scalar to a vector
 * (HLSL's float3 v = 0). */
static struct val convert(struct sl *S, struct val v, struct type t, const struct tok *where, const char *what)
{
    if (t.b == v.t.b && t.n == v.t.n)
        return v;
    if (t.b == B_FLOAT && (v.t.b == B_INT || v.t.b == B_FLOAT)) {
        v = to_float(S, v, where);
        if (v.t.n == t.n)
            return v;
        if (v.t.n == 1) {
            const char *s = temp_real(S, v.c[0]);
            for (int i = 0; i < t.n; ++i)
                v.c[i] = s;
            v.t = t;
            return v;
        }
    }
    FAIL(S, where, "%s: a %s cannot become a %s", what, type_name(S, v.t), type_name(S, t));
}

static struct sym *lookup(struct sl *S, const struct tok *t)
{
    for (struct scope *sc = S->scope; sc; sc = sc->up)
        for (struct sym *s = sc->syms; s; s = s->next)
            if (s->len == t->len && strncmp(s->name, t->p, (size_t)t->len) == 0)
                return s;
    return NULL;
}

static void push_scope(struct sl *S, int function_level)
{
    struct scope *sc = arena_alloc(S, sizeof *sc);
    sc->up = S->scope;
    sc->function_level = function_level;
    S->scope = sc;
}

static struct sym *declare(struct sl *S, struct scope *sc, const struct tok *name, struct type t)
{
    for (struct sym *s = sc->syms; s; s = s->next)
        if (s->len == name->len && strncmp(s->name, name->p, (size_t)name->len) == 0)
            FAIL(S, name, "'%.*s' is declared twice in this scope", name->len, name->p);
    if (name->len > SL_NAME_MAX)
        FAIL(S, name, "a name of more than %d characters", SL_NAME_MAX);
    struct sym *s = arena_alloc(S, sizeof *s);
    s->name = name->p;
    s->len = name->len;
    s->t = t;
    const char *base = tok_str(S, name);
    if (t.b == B_FLOAT && t.n > 1) {
        const char *root = c_name(S, base);
        for (int i = 0; i < t.n; ++i)
            s->c[i] = sfmt(S, "%s_%c", root, "xyzw"[i]);
    } else {
        s->c[0] = c_name(S, base);
    }
    s->next = sc->syms;
    sc->syms = s;
    return s;
}

/* The value of a variable. */
static struct val sym_val(struct sym *s)
{
    struct val v = { s->t, { NULL, NULL, NULL, NULL }, 0 };
    if (s->t.b == B_BOOL) {
        return (struct val){ s->t, { s->c[0] }, 0 }; /* replaced by the caller */
    }
    for (int i = 0; i < s->t.n; ++i)
        v.c[i] = s->c[i];
    v.uniform = s->t.b == B_INT;
    return v;
}

static struct val ev(struct sl *S, struct expr *e);

static const char *op_text(int op)
{
    switch (op) {
    case 'L': return "<=";
    case 'G': return ">=";
    case 'E': return "==";
    case 'N': return "!=";
    case 'A': return "&&";
    case 'O': return "||";
    case '<': return "<";
    case '>': return ">";
    case '+': return "+";
    case '-': return "-";
    case '*': return "*";
    case '/': return "/";
    default: return "%";
    }
}

/* a OP b for the arithmetic operators, with int promotion and scalar broadcast. */
static struct val arith(struct sl *S, int op, struct val a, struct val b, const struct tok *where)
{
    if (a.t.b == B_BOOL || b.t.b == B_BOOL || a.t.b == B_VOID || b.t.b == B_VOID)
        FAIL(S, where, "'%s' needs numbers, not %s and %s", op_text(op), type_name(S, a.t), type_name(S, b.t));
    struct val r = { { B_INT, 1 }, { NULL }, a.uniform && b.uniform };
    if (a.t.b == B_INT && b.t.b == B_INT) {
        r.c[0] = sfmt(S, "(%s %s %s)", a.c[0], op_text(op), b.c[0]);
        return r;
    }
    a = to_float(S, a, where);
    b = to_float(S, b, where);
    if (a.t.n != b.t.n && a.t.n != 1 && b.t.n != 1)
        FAIL(S, where, "'%s' of a %s and a %s", op_text(op), type_name(S, a.t), type_name(S, b.t));
    int n = a.t.n > b.t.n ? a.t.n : b.t.n;
    if (n > 1) {
        if (a.t.n == 1)
            a.c[0] = temp_real(S, a.c[0]);
        if (b.t.n == 1)
            b.c[0] = temp_real(S, b.c[0]);
    }
    r.t = (struct type){ B_FLOAT, n };
    for (int i = 0; i < n; ++i) {
        const char *x = a.c[a.t.n == 1 ? 0 : i], *y = b.c[b.t.n == 1 ? 0 : i];
        r.c[i] = op == '%' ? sfmt(S, "fmod(%s, %s)", x, y) : sfmt(S, "(%s %s %s)", x, op_text(op), y);
    }
    return n > 1 ? temp_val(S, r) : r;
}

/* ---- built-in functions ------------------------------------------------------------------ */

enum builtin_kind { BK_CW, BK_DOT, BK_LENGTH, BK_DISTANCE, BK_NORMALIZE, BK_REFLECT, BK_CROSS, BK_ATAN };
struct builtin {
    const char *name;
    int nargs;
    int kind;
    const char *fmt;   /* component-wise: %1 %2 %3 are the arguments */
    int shader_only;
};

static const struct builtin builtins[] = {
    { "abs", 1, BK_CW, "fabs(%1)", 0 },          { "fabs", 1, BK_CW, "fabs(%1)", 0 },
    { "sign", 1, BK_CW, "sign(%1)", 0 },         { "floor", 1, BK_CW, "floor(%1)", 0 },
    { "ceil", 1, BK_CW, "ceil(%1)", 0 },         { "trunc", 1, BK_CW, "trunc(%1)", 0 },
    { "round", 1, BK_CW, "round(%1)", 0 },       { "fract", 1, BK_CW, "(%1 - floor(%1))", 1 },
    { "frac", 1, BK_CW, "(%1 - floor(%1))", 1 }, { "sqrt", 1, BK_CW, "sqrt(%1)", 0 },
    { "inversesqrt", 1, BK_CW, "rsqrt(%1)", 1 }, { "rsqrt", 1, BK_CW, "rsqrt(%1)", 0 },
    { "rcp", 1, BK_CW, "(RSPLAT(1.0) / %1)", 1 }, { "exp", 1, BK_CW, "exp(%1)", 0 },
    { "exp2", 1, BK_CW, "exp2(%1)", 0 },         { "log", 1, BK_CW, "log(%1)", 0 },
    { "log2", 1, BK_CW, "log2(%1)", 0 },         { "log10", 1, BK_CW, "log10(%1)", 0 },
    { "expm1", 1, BK_CW, "expm1(%1)", 0 },       { "log1p", 1, BK_CW, "log1p(%1)", 0 },
    { "sin", 1, BK_CW, "sin(%1)", 0 },           { "cos", 1, BK_CW, "cos(%1)", 0 },
    { "tan", 1, BK_CW, "tan(%1)", 0 },           { "asin", 1, BK_CW, "asin(%1)", 0 },
    { "acos", 1, BK_CW, "acos(%1)", 0 },         { "sinh", 1, BK_CW, "sinh(%1)", 0 },
    { "cosh", 1, BK_CW, "cosh(%1)", 0 },         { "tanh", 1, BK_CW, "tanh(%1)", 0 },
    { "radians", 1, BK_CW, "radians(%1)", 0 },   { "degrees", 1, BK_CW, "degrees(%1)", 0 },
    { "saturate", 1, BK_CW, "clamp(%1, RSPLAT(0.0), RSPLAT(1.0))", 1 },
    { "pow", 2, BK_CW, "pow(%1, %2)", 0 },       { "min", 2, BK_CW, "fmin(%1, %2)", 0 },
    { "max", 2, BK_CW, "fmax(%1, %2)", 0 },      { "fmin", 2, BK_CW, "fmin(%1, %2)", 0 },
    { "fmax", 2, BK_CW, "fmax(%1, %2)", 0 },     { "mod", 2, BK_CW, "(%1 - %2 * floor(%1 / %2))", 1 },
    { "fmod", 2, BK_CW, "fmod(%1, %2)", 0 },     { "atan2", 2, BK_CW, "atan2(%1, %2)", 0 },
    { "step", 2, BK_CW, "step(%1, %2)", 0 },     { "clamp", 3, BK_CW, "clamp(%1, %2, %3)", 0 },
    { "mix", 3, BK_CW, "(%1 + (%2 - %1) * %3)", 0 }, { "lerp", 3, BK_CW, "(%1 + (%2 - %1) * %3)", 1 },
    { "smoothstep", 3, BK_CW, "smoothstep(%1, %2, %3)", 0 }, { "mad", 3, BK_CW, "(%1 * %2 + %3)", 0 },
    { "fma", 3, BK_CW, "fma(%1, %2, %3)", 0 },   { "atan", -1, BK_ATAN, NULL, 0 },
    { "dot", 2, BK_DOT, NULL, 1 },               { "length", 1, BK_LENGTH, NULL, 1 },
    { "distance", 2, BK_DISTANCE, NULL, 1 },     { "normalize", 1, BK_NORMALIZE, NULL, 1 },
    { "reflect", 2, BK_REFLECT, NULL, 1 },       { "cross", 2, BK_CROSS, NULL, 1 },
    { NULL, 0, 0, NULL, 0 } };

/* Writes fmt with %1..%3 replaced; an argument used twice is kept in a temporary first. */
static const char *apply_fmt(struct sl *S, const char *fmt, const char **args, int nargs)
{
    int uses[3] = { 0, 0, 0 };
    for (const char *p = fmt; *p; ++p)
        if (p[0] == '%' && p[1] >= '1' && p[1] <= '3')
            uses[p[1] - '1']++;
    const char *a[3];
    for (int i = 0; i < nargs; ++i)
        a[i] = uses[i] > 1 ? temp_real(S, args[i]) : args[i];
    struct md_buf b;
    md_init(&b);
    for (const char *p = fmt; *p; ++p) {
        if (p[0] == '%' && p[1] >= '1' && p[1] <= '3') {
            md_printf(&b, "%s", a[p[1] - '1']);
            ++p;
        } else {
            md_append(&b, p, 1);
        }
    }
    const char *s = sfmt(S, "%s", b.s ? b.s : "");
    int failed = b.failed;
    md_free(&b);
    if (failed)
        sl_fail_at(S, 0, 0, "out of memory");
    return s;
}

static const char *dot_of(struct sl *S, struct val a, struct val b)
{
    const char *s = sfmt(S, "%s * %s", a.c[0], b.c[0]);
    for (int i = 1; i < a.t.n; ++i)
        s = sfmt(S, "%s + %s * %s", s, a.c[i], b.c[i]);
    return sfmt(S, "(%s)", s);
}

static struct val call_builtin(struct sl *S, const struct builtin *bi, struct expr *e)
{
    struct val a[SL_MAX_ARGS];
    int n = e->nargs;
    if (bi->kind == BK_ATAN) {
        if (n != 1 && n != 2)
            FAIL(S, e->t, "atan takes 1 or 2 arguments, not %d", n);
    } else if (n != bi->nargs) {
        FAIL(S, e->t, "%s takes %d argument%s, not %d", bi->name, bi->nargs, bi->nargs == 1 ? "" : "s", n);
    }
    if (bi->shader_only)
        S->shader_only = 1;
    int width = 1;
    for (int i = 0; i < n; ++i) {
        a[i] = ev(S, e->args[i]);
        if (a[i].t.b != B_FLOAT && a[i].t.b != B_INT)
            FAIL(S, e->args[i]->t, "argument %d of %s is a %s, not a number", i + 1, bi->name, type_name(S, a[i].t));
        a[i] = to_float(S, a[i], e->args[i]->t);
        if (a[i].t.n > 1) {
            if (width > 1 && a[i].t.n != width)
                FAIL(S, e->args[i]->t, "%s of vectors of different sizes", bi->name);
            width = a[i].t.n;
        }
    }
    struct val r = { { B_FLOAT, 1 }, { NULL }, 0 };
    switch (bi->kind) {
    case BK_CW:
    case BK_ATAN: {
        const char *fmt = bi->fmt ? bi->fmt : n == 1 ? "atan(%1)" : "atan2(%1, %2)";
        for (int i = 0; i < n; ++i)
            if (a[i].t.n == 1 && width > 1)
                a[i].c[0] = temp_real(S, a[i].c[0]);
        r.t.n = width;
        for (int k = 0; k < width; ++k) {
            const char *args[3];
            for (int i = 0; i < n; ++i)
                args[i] = a[i].c[a[i].t.n == 1 ? 0 : k];
            r.c[k] = apply_fmt(S, fmt, args, n);
        }
        return width > 1 ? temp_val(S, r) : r;
    }
    case BK_DOT:
    case BK_DISTANCE:
    case BK_REFLECT:
    case BK_CROSS:
        if (a[0].t.n != a[1].t.n)
            FAIL(S, e->t, "%s of a %s and a %s", bi->name, type_name(S, a[0].t), type_name(S, a[1].t));
        break;
    default:
        break;
    }
    struct val x = temp_val(S, a[0]);
    switch (bi->kind) {
    case BK_DOT:
        r.c[0] = dot_of(S, x, temp_val(S, a[1]));
        return r;
    case BK_LENGTH:
        r.c[0] = x.t.n == 1 ? sfmt(S, "fabs(%s)", x.c[0]) : sfmt(S, "sqrt(%s)", dot_of(S, x, x));
        return r;
    case BK_DISTANCE: {
        struct val d = arith(S, '-', x, a[1], e->t);
        d = temp_val(S, d);
        r.c[0] = d.t.n == 1 ? sfmt(S, "fabs(%s)", d.c[0]) : sfmt(S, "sqrt(%s)", dot_of(S, d, d));
        return r;
    }
    case BK_NORMALIZE: {
        const char *len = temp_real(S, x.t.n == 1 ? sfmt(S, "fabs(%s)", x.c[0]) : sfmt(S, "sqrt(%s)", dot_of(S, x, x)));
        r.t.n = x.t.n;
        for (int i = 0; i < x.t.n; ++i)
            r.c[i] = sfmt(S, "(%s / %s)", x.c[i], len);
        return temp_val(S, r);
    }
    case BK_REFLECT: {
        /* I - 2 dot(N, I) N */
        struct val nn = temp_val(S, a[1]);
        const char *d = temp_real(S, dot_of(S, nn, x));
        r.t.n = x.t.n;
        for (int i = 0; i < x.t.n; ++i)
            r.c[i] = sfmt(S, "(%s - RSPLAT(2.0) * %s * %s)", x.c[i], d, nn.c[i]);
        return temp_val(S, r);
    }
    case BK_CROSS: {
        if (x.t.n != 3)
            FAIL(S, e->t, "cross takes two vec3");
        struct val y = temp_val(S, a[1]);
        r.t.n = 3;
        for (int i = 0; i < 3; ++i) {
            int j = (i + 1) % 3, k = (i + 2) % 3;
            r.c[i] = sfmt(S, "(%s * %s - %s * %s)", x.c[j], y.c[k], x.c[k], y.c[j]);
        }
        return temp_val(S, r);
    }
    default:
        FAIL(S, e->t, "internal: unknown built-in kind");
    }
}

/* ---- constructors, casts and calls --------------------------------------------------------- */

static void emit_block(struct sl *S, struct stmt *b, const char *pred, int new_scope);
static int stmt_returns(const struct stmt *s);
static int const_int(struct sl *S, struct expr *e, long *out);

static struct val call_user(struct sl *S, struct func *f, struct expr *e)
{
    if (e->nargs != f->nparams)
        FAIL(S, e->t, "%.*s takes %d argument%s, not %d", f->name->len, f->name->p, f->nparams,
             f->nparams == 1 ? "" : "s", e->nargs);
    for (int i = 0; i < S->ninline; ++i)
        if (S->inlining[i] == f)
            FAIL(S, e->t, "%.*s calls itself: recursion is not supported", f->name->len, f->name->p);
    if (S->ninline >= SL_MAX_INLINE)
        FAIL(S, e->t, "calls nested more than %d deep", SL_MAX_INLINE);
    if (f->ret.b == B_VOID || f->ret.b == B_BOOL)
        FAIL(S, f->name, "a helper function must return a number or a vector (this one returns %s)",
             type_name(S, f->ret));
    if (!stmt_returns(f->body))
        FAIL(S, f->close, "%.*s can reach its end without returning a value", f->name->len, f->name->p);
    struct val args[SL_MAX_ARGS];
    for (int i = 0; i < e->nargs; ++i)
        args[i] = convert(S, ev(S, e->args[i]), f->pty[i], e->args[i]->t,
                          sfmt(S, "argument %d of %.*s", i + 1, f->name->len, f->name->p));
    int saved_line = S->stmt_line;
    struct scope *saved_scope = S->scope;
    struct fnctx *saved_fn = S->fn;
    struct fnctx fc = { f->ret, { NULL }, NULL, NULL, 0, 0 };
    int k = ++S->ntemp;
    if (f->ret.b == B_INT) {
        fc.ret_c[0] = sfmt(S, "sl_r%d", k);
        out_line(S, "int %s = 0;", fc.ret_c[0]);
    } else {
        for (int i = 0; i < f->ret.n; ++i) {
            fc.ret_c[i] = f->ret.n == 1 ? sfmt(S, "sl_r%d", k) : sfmt(S, "sl_r%d_%c", k, "xyzw"[i]);
            out_line(S, "REAL %s = RSPLAT(0.0);", fc.ret_c[i]);
        }
    }
    S->scope = S->globals;
    push_scope(S, 1);
    S->stmt_line = f->name->line;
    for (int i = 0; i < f->nparams; ++i) {
        struct sym *p = declare(S, S->scope, f->pname[i], f->pty[i]);
        for (int c = 0; c < f->pty[i].n; ++c)
            out_line(S, "%s %s = %s;", f->pty[i].b == B_INT ? "int" : f->pty[i].b == B_BOOL ? "REAL" : "REAL",
                     p->c[c], f->pty[i].b == B_BOOL ? sfmt(S, "(%s) ? RSPLAT(1.0) : RSPLAT(0.0)", args[i].c[c])
                                                      : args[i].c[c]);
    }
    S->inlining[S->ninline++] = f;
    S->fn = &fc;
    emit_block(S, f->body, NULL, 0);
    S->fn = saved_fn;
    --S->ninline;
    S->scope = saved_scope;
    S->stmt_line = saved_line;
    struct val r = { f->ret, { NULL }, f->ret.b == B_INT };
    for (int i = 0; i < f->ret.n; ++i)
        r.c[i] = fc.ret_c[i];
    return r;
}

static struct val construct(struct sl *S, struct type t, struct expr *e)
{
    struct val r = { t, { NULL }, 1 };
    if (t.b == B_VOID)
        FAIL(S, e->t, "void is not a value");
    if (t.b == B_BOOL)
        FAIL(S, e->t, "bool(...) is not supported (compare with != 0.0)");
    if (t.b == B_INT) {
        if (e->nargs != 1)
            FAIL(S, e->t, "int(...) takes one value");
        struct expr *x = e->args[0];
        if (x->k == E_FLT) {
            r.c[0] = sfmt(S, "(int)(%s)", float_literal(S, x->t));
            return r;
        }
        struct val v = ev(S, x);
        if (v.t.b == B_INT)
            return v;
        FAIL(S, x->t, "int of a %s: only an int or a literal number becomes an int (an int is the same in "
                      "every lane of a sweep; keep the value a float)", type_name(S, v.t));
    }
    struct val parts[SL_MAX_ARGS];
    int total = 0;
    for (int i = 0; i < e->nargs; ++i) {
        parts[i] = ev(S, e->args[i]);
        if (parts[i].t.b == B_BOOL) {
            parts[i] = (struct val){ { B_FLOAT, 1 },
                                     { sfmt(S, "((%s) ? RSPLAT(1.0) : RSPLAT(0.0))", parts[i].c[0]) }, parts[i].uniform };
        }
        parts[i] = to_float(S, parts[i], e->args[i]->t);
        total += parts[i].t.n;
    }
    r.uniform = 0;
    if (e->nargs == 1 && parts[0].t.n == 1) {
        const char *s = t.n > 1 ? temp_real(S, parts[0].c[0]) : parts[0].c[0];
        for (int i = 0; i < t.n; ++i)
            r.c[i] = s;
        return r;
    }
    if (e->nargs == 1 && parts[0].t.n >= t.n && e->is_cast) {
        /* HLSL's (float3)v4 keeps the first components */
        for (int i = 0; i < t.n; ++i)
            r.c[i] = parts[0].c[i];
        return r;
    }
    if (total != t.n)
        FAIL(S, e->t, "%s(...) needs %d component%s, these give %d", type_name(S, t), t.n, t.n == 1 ? "" : "s", total);
    int k = 0;
    for (int i = 0; i < e->nargs; ++i)
        for (int j = 0; j < parts[i].t.n; ++j)
            r.c[k++] = parts[i].c[j];
    return r;
}

static struct func *find_func(struct sl *S, const struct tok *t)
{
    for (struct func *f = S->funcs; f; f = f->next)
        if (f->name->len == t->len && strncmp(f->name->p, t->p, (size_t)t->len) == 0)
            return f;
    return NULL;
}

static void fail_unknown(struct sl *S, const struct tok *t, const char *what)
{
    S->unknown_name = 1;
    FAIL(S, t, "use of undeclared %s '%.*s'", what, t->len, t->p);
}

/* ---- expressions -------------------------------------------------------------------------- */

static struct val ev(struct sl *S, struct expr *e)
{
    struct val r = { { B_FLOAT, 1 }, { NULL }, 1 };
    switch (e->k) {
    case E_FLT:
        r.c[0] = sfmt(S, "RSPLAT(%s)", float_literal(S, e->t));
        return r;
    case E_INT:
        if (e->op == 1) {
            r.t = (struct type){ B_INT, 1 };
            r.c[0] = "1";
            return r;
        }
        {
            int len = e->t->len;
            while (len > 0 && (e->t->p[len - 1] == 'u' || e->t->p[len - 1] == 'U'))
                --len;
            if (len > 9)
                FAIL(S, e->t, "the integer %.*s is too large (write it with a decimal point)", e->t->len, e->t->p);
            r.t = (struct type){ B_INT, 1 };
            r.c[0] = sfmt(S, "%ld", strtol(sfmt(S, "%.*s", len, e->t->p), NULL, 10));
        }
        return r;
    case E_BOOL:
        r.t = (struct type){ B_BOOL, 1 };
        r.c[0] = tok_is(e->t, "true") ? "1" : "0";
        return r;
    case E_VAR: {
        struct sym *s = lookup(S, e->t);
        if (!s)
            fail_unknown(S, e->t, "identifier");
        if (s->t.b == B_BOOL) {
            r.t = s->t;
            r.c[0] = sfmt(S, "(%s != RSPLAT(0.0))", s->c[0]);
            r.uniform = 0;
            return r;
        }
        if (s->has_value) {
            r.t = s->t;
            r.c[0] = sfmt(S, "%ld", s->value);
            return r;
        }
        return sym_val(s);
    }
    case E_SWZ: {
        struct val v = ev(S, e->a);
        if (v.t.b != B_FLOAT)
            FAIL(S, e->t, "a swizzle of a %s", type_name(S, v.t));
        for (int i = 0; i < e->nswz; ++i)
            if (e->swz[i] >= v.t.n)
                FAIL(S, e->t, "component %c of a %s", "xyzw"[e->swz[i]], type_name(S, v.t));
        r.t = (struct type){ B_FLOAT, e->nswz };
        r.uniform = v.uniform;
        for (int i = 0; i < e->nswz; ++i)
            r.c[i] = v.c[e->swz[i]];
        return r;
    }
    case E_UN: {
        struct val v = ev(S, e->a);
        if (e->op == '!') {
            if (v.t.b != B_BOOL)
                FAIL(S, e->t, "'!' of a %s (a condition is expected)", type_name(S, v.t));
            v.c[0] = sfmt(S, "(!%s)", v.c[0]);
            return v;
        }
        if (v.t.b != B_FLOAT && v.t.b != B_INT)
            FAIL(S, e->t, "'%c' of a %s", e->op == 'u' ? '-' : '+', type_name(S, v.t));
        if (e->op == 'p')
            return v;
        for (int i = 0; i < v.t.n; ++i)
            v.c[i] = sfmt(S, "(-%s)", v.c[i]);
        return v;
    }
    case E_BIN: {
        struct val a = ev(S, e->a), b = ev(S, e->b);
        int op = e->op;
        if (op == 'A' || op == 'O') {
            if (a.t.b != B_BOOL || b.t.b != B_BOOL)
                FAIL(S, e->t, "'%s' needs conditions, not %s and %s", op_text(op), type_name(S, a.t), type_name(S, b.t));
            r.t = a.t;
            r.uniform = a.uniform && b.uniform;
            r.c[0] = sfmt(S, "(%s %s %s)", a.c[0], op_text(op), b.c[0]);
            return r;
        }
        if (strchr("<>LGEN", op)) {
            if (a.t.b == B_BOOL || b.t.b == B_BOOL)
                FAIL(S, e->t, "'%s' of conditions: combine them with && || !", op_text(op));
            if (a.t.n > 1 || b.t.n > 1)
                FAIL(S, e->t, "'%s' of vectors: compare their components", op_text(op));
            if (a.t.b != b.t.b) {
                a = to_float(S, a, e->t);
                b = to_float(S, b, e->t);
            }
            r.t = (struct type){ B_BOOL, 1 };
            r.uniform = a.uniform && b.uniform;
            r.c[0] = sfmt(S, "(%s %s %s)", a.c[0], op_text(op), b.c[0]);
            return r;
        }
        return arith(S, op, a, b, e->t);
    }
    case E_TER: {
        struct val c = ev(S, e->a);
        if (c.t.b != B_BOOL || c.t.n != 1)
            FAIL(S, e->a->t, "the condition of ?: is a %s, not a comparison", type_name(S, c.t));
        struct val a = ev(S, e->b), b = ev(S, e->c);
        if (a.t.b == B_BOOL || b.t.b == B_BOOL)
            FAIL(S, e->t, "?: of conditions: combine them with && || !");
        if (a.t.b == B_INT && b.t.b == B_INT && c.uniform) {
            r.t = a.t;
            r.c[0] = sfmt(S, "(%s ? %s : %s)", c.c[0], a.c[0], b.c[0]);
            return r;
        }
        a = to_float(S, a, e->b->t);
        b = to_float(S, b, e->c->t);
        int n = a.t.n > b.t.n ? a.t.n : b.t.n;
        if (a.t.n != b.t.n && a.t.n != 1 && b.t.n != 1)
            FAIL(S, e->t, "?: between a %s and a %s", type_name(S, a.t), type_name(S, b.t));
        if (n > 1)
            c.c[0] = temp_cond(S, c.c[0], c.uniform);
        r.t = (struct type){ B_FLOAT, n };
        r.uniform = 0;
        for (int i = 0; i < n; ++i)
            r.c[i] = sfmt(S, "(%s ? %s : %s)", c.c[0], a.c[a.t.n == 1 ? 0 : i], b.c[b.t.n == 1 ? 0 : i]);
        return n > 1 ? temp_val(S, r) : r;
    }
    case E_CALL: {
        struct type t;
        int so;
        if (type_of_name(e->t, &t, &so))
            return construct(S, t, e);
        struct func *f = find_func(S, e->t);
        if (f)
            return call_user(S, f, e);
        for (int i = 0; builtins[i].name; ++i)
            if (tok_is(e->t, builtins[i].name))
                return call_builtin(S, &builtins[i], e);
        fail_unknown(S, e->t, "function");
    }
    }
    FAIL(S, e->t, "internal: unknown expression");
}

/* ---- statements -------------------------------------------------------------------------- */

static int stmt_returns(const struct stmt *s)
{
    if (!s)
        return 0;
    switch (s->k) {
    case S_RET: return 1;
    case S_BLOCK:
        for (int i = 0; i < s->n; ++i)
            if (stmt_returns(s->items[i]))
                return 1;
        return 0;
    case S_IF: return s->s2 && stmt_returns(s->s1) && stmt_returns(s->s2);
    default: return 0;
    }
}

/* "pred and the lane still runs", or NULL for every lane. */
static const char *effective(struct sl *S, const char *pred)
{
    const char *live = S->fn->live;
    if (!pred)
        return live;
    if (!live)
        return pred;
    return sfmt(S, "(%s && %s)", pred, live);
}

static const char *and_cond(struct sl *S, const char *a, const char *b)
{
    if (!a)
        return b;
    return sfmt(S, "(%s && %s)", a, b);
}

static void assign_sym(struct sl *S, struct sym *s, const int *comp, int ncomp, struct val v, const char *pred,
                       const struct tok *where)
{
    const char *E = effective(S, pred);
    if (s->t.b == B_INT) {
        if (E)
            FAIL(S, where, "the int '%s' is assigned under a condition: make it a float", sfmt(S, "%.*s", s->len, s->name));
        out_line(S, "%s = %s;", s->c[0], v.c[0]);
        return;
    }
    if (s->t.b == B_BOOL) {
        const char *m = sfmt(S, "((%s) ? RSPLAT(1.0) : RSPLAT(0.0))", v.c[0]);
        if (E)
            out_line(S, "%s = (%s) ? %s : %s;", s->c[0], E, m, s->c[0]);
        else
            out_line(S, "%s = %s;", s->c[0], m);
        return;
    }
    /* A component read on the right may be written on the left: read them all first. */
    if (ncomp > 1)
        for (int i = 0; i < ncomp; ++i)
            for (int j = 0; j < s->t.n; ++j)
                if (strstr(v.c[i], s->c[j]))
                    v.c[i] = temp_real(S, sfmt(S, "(%s)", v.c[i]));
    if (E && ncomp > 1)
        E = temp_cond(S, E, 0);
    for (int i = 0; i < ncomp; ++i) {
        const char *dst = s->c[comp[i]];
        if (E)
            out_line(S, "%s = %s ? %s : %s;", dst, E, v.c[i], dst);
        else
            out_line(S, "%s = %s;", dst, v.c[i]);
    }
}

static void emit_decl(struct sl *S, struct stmt *d)
{
    struct type t = d->ty;
    struct val v;
    if (d->e) {
        v = ev(S, d->e);
        if (t.b == B_BOOL) {
            if (v.t.b != B_BOOL)
                FAIL(S, d->e->t, "a bool is set from a %s", type_name(S, v.t));
        } else {
            v = convert(S, v, t, d->e->t, sfmt(S, "'%.*s'", d->name->len, d->name->p));
        }
    } else {
        v.t = t;
        v.uniform = 1;
        for (int i = 0; i < t.n; ++i)
            v.c[i] = t.b == B_INT ? "0" : "RSPLAT(0.0)";
        if (t.b == B_BOOL)
            v.c[0] = "0";
    }
    /* a const int of a constant value is substituted where it is used (for loop bounds) */
    long value = 0;
    int constant = t.b == B_INT && d->is_const && d->e && const_int(S, d->e, &value);
    struct sym *s = declare(S, S->scope, d->name, t);
    s->is_const = d->is_const;
    if (constant) {
        s->has_value = 1;
        s->value = value;
        return;
    }
    if (t.b == B_INT) {
        out_line(S, "int %s = %s;", s->c[0], v.c[0]);
    } else if (t.b == B_BOOL) {
        out_line(S, "REAL %s = (%s) ? RSPLAT(1.0) : RSPLAT(0.0);", s->c[0], v.c[0]);
    } else {
        for (int i = 0; i < t.n; ++i)
            out_line(S, "REAL %s = %s;", s->c[i], v.c[i]);
    }
}

static void emit_assign(struct sl *S, struct stmt *st, const char *pred)
{
    struct expr *l = st->lhs;
    const struct tok *nt = l->k == E_SWZ ? l->a->t : l->t;
    if (!(l->k == E_VAR || (l->k == E_SWZ && l->a->k == E_VAR)))
        FAIL(S, l->t, "the left of an assignment must be a variable or its components");
    struct sym *s = lookup(S, nt);
    struct val v = ev(S, st->e);
    if (!s) {
        if (!(S->allow_implicit && st->op == '=' && l->k == E_VAR))
            fail_unknown(S, nt, "identifier");
        /* the body form: the first assignment declares it, at the function's level */
        struct scope *sc = S->scope;
        while (!sc->function_level)
            sc = sc->up;
        struct type t = v.t.b == B_INT ? (struct type){ B_FLOAT, 1 } : v.t;
        if (t.b == B_VOID)
            FAIL(S, st->e->t, "a void value");
        s = declare(S, sc, nt, t);
        if (t.b == B_FLOAT)
            for (int i = 0; i < t.n; ++i)
                out_line(S, "REAL %s = RSPLAT(0.0);", s->c[i]);
        else
            out_line(S, "REAL %s = RSPLAT(0.0);", s->c[0]);
    }
    if (s->is_const)
        FAIL(S, nt, "'%.*s' is const", nt->len, nt->p);
    int comp[4] = { 0, 1, 2, 3 }, ncomp = s->t.n;
    struct type target = s->t;
    if (l->k == E_SWZ) {
        if (s->t.b != B_FLOAT)
            FAIL(S, l->t, "a swizzle of a %s", type_name(S, s->t));
        ncomp = l->nswz;
        for (int i = 0; i < ncomp; ++i) {
            comp[i] = l->swz[i];
            if (comp[i] >= s->t.n)
                FAIL(S, l->t, "component %c of a %s", "xyzw"[comp[i]], type_name(S, s->t));
            for (int j = 0; j < i; ++j)
                if (comp[j] == comp[i])
                    FAIL(S, l->t, "component %c is written twice", "xyzw"[comp[i]]);
        }
        target = (struct type){ B_FLOAT, ncomp };
    }
    if (st->op != '=') {
        if (s->t.b == B_BOOL)
            FAIL(S, st->t, "a compound assignment to a bool");
        struct val cur = sym_val(s);
        struct val part = cur;
        part.t = target;
        for (int i = 0; i < ncomp; ++i)
            part.c[i] = cur.c[comp[i]];
        v = arith(S, st->op, part, v, st->t);
    }
    if (s->t.b == B_BOOL) {
        if (v.t.b != B_BOOL)
            FAIL(S, st->e->t, "a bool is set from a %s", type_name(S, v.t));
    } else {
        v = convert(S, v, target, st->e->t, sfmt(S, "'%.*s'", nt->len, nt->p));
    }
    assign_sym(S, s, comp, ncomp, v, pred, st->t);
}

static void emit_return(struct sl *S, struct stmt *st, const char *pred)
{
    struct fnctx *fc = S->fn;
    struct val v = ev(S, st->e);
    v = convert(S, v, fc->ret, st->e->t, "the returned value");
    const char *E = effective(S, pred);
    if (!E && fc->is_model && !fc->ret_c[0]) {
        out_line(S, "return %s;", v.c[0]);
        fc->returned = 1;
        return;
    }
    if (fc->is_model && !fc->ret_c[0]) {
        fc->ret_c[0] = "sl_ret";
        out_line(S, "REAL sl_ret = RSPLAT(0.0);");
    }
    if (E && fc->ret.n > 1)
        E = temp_cond(S, E, 0);
    for (int i = 0; i < fc->ret.n; ++i) {
        if (E)
            out_line(S, "%s = %s ? %s : %s;", fc->ret_c[i], E, v.c[i], fc->ret_c[i]);
        else
            out_line(S, "%s = %s;", fc->ret_c[i], v.c[i]);
    }
    if (E) {
        if (!fc->live_var) {
            fc->live_var = sfmt(S, "sl_live%d", ++S->ntemp);
            out_line(S, "REAL %s = RSPLAT(1.0);", fc->live_var);
            fc->live = sfmt(S, "(%s != RSPLAT(0.0))", fc->live_var);
        }
        out_line(S, "%s = %s ? RSPLAT(0.0) : %s;", fc->live_var, E, fc->live_var);
    }
}

static int const_int(struct sl *S, struct expr *e, long *out)
{
    switch (e->k) {
    case E_INT: {
        struct val v = ev(S, e);
        *out = strtol(v.c[0], NULL, 10);
        return 1;
    }
    case E_VAR: {
        struct sym *s = lookup(S, e->t);
        if (s && s->has_value) {
            *out = s->value;
            return 1;
        }
        return 0;
    }
    case E_UN: {
        long a;
        if (e->op == 'u' && const_int(S, e->a, &a)) {
            *out = -a;
            return 1;
        }
        return 0;
    }
    case E_BIN: {
        long a, b;
        if (!const_int(S, e->a, &a) || !const_int(S, e->b, &b))
            return 0;
        switch (e->op) {
        case '+': *out = a + b; return 1;
        case '-': *out = a - b; return 1;
        case '*': *out = a * b; return 1;
        case '/': if (b == 0) return 0; *out = a / b; return 1;
        default: return 0;
        }
    }
    default:
        return 0;
    }
}

static void emit_stmt(struct sl *S, struct stmt *st, const char *pred);

/* for (int i = A; i < B; i++) with constant A and B: unrolled. */
static void emit_for(struct sl *S, struct stmt *st, const char *pred)
{
    static const char *form = "a for loop must read for (int i = A; i < B; i++) (or <=, >, >=, --, += K, -= K) "
                              "with A, B and K constant integers";
    struct stmt *init = st->s1;
    if (!(init->k == S_BLOCK && init->n == 1 && init->items[0]->k == S_DECL && init->items[0]->ty.b == B_INT &&
          init->items[0]->e))
        FAIL(S, st->t, "%s", form);
    struct stmt *d = init->items[0];
    long i0, bound, step;
    if (!const_int(S, d->e, &i0))
        FAIL(S, d->e->t, "the loop's start is not a constant integer; %s", form);
    struct expr *c = st->e;
    if (!(c->k == E_BIN && strchr("<>LG", c->op) && c->a->k == E_VAR && c->a->t->len == d->name->len &&
          strncmp(c->a->t->p, d->name->p, (size_t)d->name->len) == 0 && const_int(S, c->b, &bound)))
        FAIL(S, c->t, "%s", form);
    struct stmt *inc = st->s2;
    if (!(inc->k == S_ASSIGN && inc->lhs->k == E_VAR && inc->lhs->t->len == d->name->len &&
          strncmp(inc->lhs->t->p, d->name->p, (size_t)d->name->len) == 0 && (inc->op == '+' || inc->op == '-') &&
          const_int(S, inc->e, &step) && step > 0))
        FAIL(S, inc->t, "%s", form);
    if (inc->op == '-')
        step = -step;
    int count = 0;
    for (long i = i0;; i += step) {
        int go = c->op == '<' ? i < bound : c->op == 'L' ? i <= bound : c->op == '>' ? i > bound : i >= bound;
        if (!go)
            break;
        if (++count > SL_MAX_UNROLL)
            FAIL(S, st->t, "a for loop of more than %d iterations", SL_MAX_UNROLL);
        push_scope(S, 0);
        struct sym *s = declare(S, S->scope, d->name, d->ty);
        s->is_const = 1;
        s->has_value = 1;
        s->value = i;
        emit_stmt(S, st->s3, pred);
        S->scope = S->scope->up;
        if (stmt_returns(st->s3))
            FAIL(S, st->t, "a return inside a for loop is not supported");
    }
}

static void emit_stmt(struct sl *S, struct stmt *st, const char *pred)
{
    S->stmt_line = st->t->line;
    switch (st->k) {
    case S_EMPTY:
        return;
    case S_DECL:
        emit_decl(S, st);
        return;
    case S_ASSIGN:
        emit_assign(S, st, pred);
        return;
    case S_RET:
        emit_return(S, st, pred);
        return;
    case S_BLOCK:
        emit_block(S, st, pred, st->op != 1);
        return;
    case S_FOR:
        emit_for(S, st, pred);
        return;
    case S_IF: {
        struct val c = ev(S, st->e);
        if (c.t.b != B_BOOL)
            FAIL(S, st->e->t, "the condition of if is a %s, not a comparison", type_name(S, c.t));
        S->stmt_line = st->t->line;
        const char *cm = temp_cond(S, c.c[0], c.uniform);
        int uniform = c.uniform && (!pred || strncmp(pred, "sl_b", 4) == 0);
        const char *tp = temp_cond(S, and_cond(S, pred, cm), uniform);
        emit_block(S, st->s1, tp, 1);
        if (st->s2) {
            S->stmt_line = st->t->line;
            const char *ep = temp_cond(S, and_cond(S, pred, sfmt(S, "(!%s)", cm)), uniform);
            emit_block(S, st->s2, ep, 1);
        }
        return;
    }
    }
}

static void emit_block(struct sl *S, struct stmt *b, const char *pred, int new_scope)
{
    if (new_scope)
        push_scope(S, 0);
    if (b->k != S_BLOCK) {
        emit_stmt(S, b, pred);
    } else {
        for (int i = 0; i < b->n; ++i) {
            emit_stmt(S, b->items[i], pred);
            if (stmt_returns(b->items[i]))
                break; /* what follows is never reached */
        }
    }
    if (new_scope)
        S->scope = S->scope->up;
}

/* ---- the program ------------------------------------------------------------------------- */

struct header {
    int present;
    size_t end;                 /* bytes of the text the header comment takes */
    char name[SL_NAME_MAX + 1];
    char function[SL_NAME_MAX + 1];
    int nparams;
    char params[SL_MAX_PARAMS][SL_NAME_MAX + 1];
    int integer[SL_MAX_PARAMS];
    char reference[SL_NAME_MAX + 1];
    char lobe[16];
    char description[200];
    /* A .brdf file: the header written for it, code lexed before and after the user's text
       (no position of their own), and the line the user's text starts on. */
    const char *header_text, *prelude, *epilogue;
    int first_line;
};

/* Reads what the translation needs from a brdfbench-model header; usermodel.c checks it all. */
static void read_header(const char *text, size_t len, struct header *h)
{
    memset(h, 0, sizeof *h);
    size_t i = 0;
    while (i < len && isspace((unsigned char)text[i]))
        ++i;
    if (i + 2 > len || text[i] != '/' || text[i + 1] != '*')
        return;
    const char *start = text + i + 2;
    const char *close = NULL;
    for (const char *p = start; p + 1 < text + len; ++p)
        if (p[0] == '*' && p[1] == '/') {
            close = p;
            break;
        }
    if (!close)
        return;
    const char *p = start;
    int first = 1;
    while (p < close) {
        const char *eol = memchr(p, '\n', (size_t)(close - p));
        if (!eol)
            eol = close;
        const char *a = p, *b = eol;
        while (a < b && isspace((unsigned char)*a))
            ++a;
        if (!first && a < b && *a == '*')
            ++a;
        while (a < b && isspace((unsigned char)*a))
            ++a;
        while (b > a && isspace((unsigned char)b[-1]))
            --b;
        if (first) {
            if ((size_t)(b - a) != 15 || strncmp(a, "brdfbench-model", 15) != 0)
                return;
            first = 0;
        } else {
            const char *colon = memchr(a, ':', (size_t)(b - a));
            if (colon) {
                const char *k = a, *ke = colon;
                while (ke > k && isspace((unsigned char)ke[-1]))
                    --ke;
                const char *v = colon + 1;
                while (v < b && isspace((unsigned char)*v))
                    ++v;
                const char *ve = v;
                while (ve < b && !isspace((unsigned char)*ve))
                    ++ve;
                size_t kl = (size_t)(ke - k), vl = (size_t)(ve - v);
                if (vl > SL_NAME_MAX)
                    vl = SL_NAME_MAX;
                if (kl == 4 && strncmp(k, "name", 4) == 0)
                    snprintf(h->name, sizeof h->name, "%.*s", (int)vl, v);
                else if (kl == 8 && strncmp(k, "function", 8) == 0)
                    snprintf(h->function, sizeof h->function, "%.*s", (int)vl, v);
                else if (kl == 9 && strncmp(k, "reference", 9) == 0)
                    snprintf(h->reference, sizeof h->reference, "%.*s", (int)vl, v);
                else if (kl == 4 && strncmp(k, "lobe", 4) == 0)
                    snprintf(h->lobe, sizeof h->lobe, "%.*s", (int)(vl < 15 ? vl : 15), v);
                else if (kl == 11 && strncmp(k, "description", 11) == 0)
                    snprintf(h->description, sizeof h->description, "%.*s", (int)(b - v), v);
                else if (kl == 5 && strncmp(k, "param", 5) == 0 && h->nparams < SL_MAX_PARAMS) {
                    snprintf(h->params[h->nparams], sizeof h->params[0], "%.*s", (int)vl, v);
                    const char *rest = ve;
                    h->integer[h->nparams] = 0;
                    for (const char *q = rest; q + 7 <= b; ++q)
                        if (strncmp(q, "integer", 7) == 0)
                            h->integer[h->nparams] = 1;
                    h->nparams++;
                }
            }
        }
        p = eol + 1;
    }
    h->present = 1;
    h->end = (size_t)(close + 2 - text);
}

/* The function form: somewhere outside braces and parentheses a type, a name and '('. */
static int is_function_start(struct sl *S)
{
    int depth = 0;
    for (int i = S->pos; i + 2 < S->toks.n; ++i) {
        const struct tok *t = &S->toks.v[i];
        if (tok_is(t, "{") || tok_is(t, "("))
            ++depth;
        else if (tok_is(t, "}") || tok_is(t, ")"))
            --depth;
        struct type ty;
        int so;
        if (depth == 0 && type_of_name(t, &ty, &so) && t[1].k == K_ID && tok_is(&t[2], "("))
            return 1;
    }
    return 0;
}

/* A file: function definitions and global declarations, or (no function) a body. */
static struct stmt *parse_program(struct sl *S, struct stmt *globals)
{
    if (!is_function_start(S)) {
        struct stmt *body = new_stmt(S, S_BLOCK, peek(S));
        while (peek(S)->k != K_EOF)
            block_add(S, body, parse_statement(S, 1));
        return body;
    }
    struct func **tail = &S->funcs;
    while (*tail)
        tail = &(*tail)->next;
    while (peek(S)->k != K_EOF) {
        const struct tok *start = peek(S);
        if (accept(S, ";"))
            continue;
        if (tok_is(start, "precision")) {
            while (peek(S)->k != K_EOF && !accept(S, ";"))
                next(S);
            continue;
        }
        struct type t;
        int is_const;
        int save = S->pos;
        if (!parse_decl_type(S, &t, &is_const)) {
            check_unsupported_word(S, start);
            FAIL(S, start, "expected a function or a declaration, found %s", tok_desc(S, start));
        }
        const struct tok *name = peek(S);
        if (name->k != K_ID)
            FAIL(S, name, "expected a name, found %s", tok_desc(S, name));
        if (!tok_is(peek_at(S, 1), "(")) {
            S->pos = save;
            parse_decl_type(S, &t, &is_const);
            if (t.b == B_VOID)
                FAIL(S, start, "a variable cannot be void");
            struct stmt *d = parse_declaration(S, t, is_const, start);
            block_add(S, globals, d);
            continue;
        }
        next(S);
        expect(S, "(");
        struct func *f = arena_alloc(S, sizeof *f);
        f->name = name;
        f->ret = t;
        if (find_func(S, name))
            FAIL(S, name, "function '%.*s' is defined twice (overloads are not supported)", name->len, name->p);
        if (accept(S, "void")) {
            expect(S, ")");
        } else if (!accept(S, ")")) {
            for (;;) {
                struct type pt;
                int pc;
                const struct tok *pt0 = peek(S);
                if (!parse_decl_type(S, &pt, &pc))
                    FAIL(S, pt0, "expected a parameter type, found %s", tok_desc(S, pt0));
                if (pt.b == B_VOID)
                    FAIL(S, pt0, "a parameter cannot be void");
                const struct tok *pn = peek(S);
                if (pn->k != K_ID)
                    FAIL(S, pn, "expected a parameter name, found %s", tok_desc(S, pn));
                next(S);
                if (tok_is(peek(S), ":"))
                    FAIL(S, peek(S), "HLSL semantics (': NAME') are not supported on a model's parameters");
                if (f->nparams == SL_MAX_ARGS)
                    FAIL(S, pn, "more than %d parameters", SL_MAX_ARGS);
                f->pty[f->nparams] = pt;
                f->pname[f->nparams++] = pn;
                if (accept(S, ")"))
                    break;
                expect(S, ",");
            }
        }
        if (accept(S, ";"))
            continue; /* a prototype */
        f->body = parse_block(S);
        f->close = &S->toks.v[S->pos - 1];
        *tail = f;
        tail = &f->next;
    }
    return NULL;
}

static int valid_identifier(const char *s)
{
    if (!*s || !(isalpha((unsigned char)*s) || *s == '_') || strlen(s) > SL_NAME_MAX)
        return 0;
    for (const char *p = s; *p; ++p)
        if (!isalnum((unsigned char)*p) && *p != '_')
            return 0;
    return 1;
}

/* Translates text (the whole file or expression), whose model is called name. */
/* The luminance of a colour and the geometry of the lobe of a full BRDF: L = N, V at 2 theta_h
 * from N in the XZ plane (N.V = 2c^2 - 1, N.H = V.H = c), 0 where V is below the horizon, as the
 * built-in physical models (kernels/brdf_models.h, brdf_pb_lobe). */
#define SL_LOBE_GEOMETRY                                                                               \
    "vec3 brdfbench_N = vec3(0.0, 0.0, 1.0); "                                                         \
    "float brdfbench_nv = 2.0 * brdfbench_c * brdfbench_c - 1.0; "                                     \
    "vec3 brdfbench_V = vec3(2.0 * brdfbench_c * sqrt(max((1.0 - brdfbench_c) * (1.0 + brdfbench_c), 0.0)), " \
    "0.0, brdfbench_nv); "
#define SL_LUMINANCE "vec3(0.2126, 0.7152, 0.0722)"
/* The tangents X, Y a full BRDF of (L, V, N, X, Y) gets at a normal N of the scene: the
 * branch-free orthonormal basis of Duff et al. 2017 ("Building an orthonormal basis, revisited");
 * an isotropic BRDF does not depend on them. */
#define SL_TANGENT_FRAME                                                                               \
    "float brdfbench_s = brdfbench_N.z >= 0.0 ? 1.0 : -1.0; "                                          \
    "float brdfbench_a = -1.0 / (brdfbench_s + brdfbench_N.z); "                                       \
    "float brdfbench_b = brdfbench_N.x * brdfbench_N.y * brdfbench_a; "                                \
    "vec3 brdfbench_X = vec3(1.0 + brdfbench_s * brdfbench_N.x * brdfbench_N.x * brdfbench_a, "        \
    "brdfbench_s * brdfbench_b, -brdfbench_s * brdfbench_N.x); "                                       \
    "vec3 brdfbench_Y = vec3(brdfbench_b, brdfbench_s + brdfbench_N.y * brdfbench_N.y * brdfbench_a, " \
    "-brdfbench_N.y); "

/* The opening of the full-vector function of a full BRDF (SHADERLANG_FULL_FUNCTION), with nparams
 * model parameters, up to its first statement. */
static void full_function_open(struct md_buf *w, int nparams)
{
    md_printf(w, " float brdfbench_full(vec3 brdfbench_L, vec3 brdfbench_V, vec3 brdfbench_N, float brdfbench_n");
    for (int i = 0; i < nparams; ++i)
        md_printf(w, ", float brdfbench_p%d", i);
    md_printf(w, ") { " SL_TANGENT_FRAME);
}

/* A model function of vectors, float|vec3 f(vec3 L, vec3 V, vec3 N[, vec3 X, vec3 Y], float n
 * [, float p0[, float p1]]): a full BRDF. Appends and parses the lobe function that calls it
 * and returns that function. */
static struct func *full_brdf_lobe(struct sl *S, struct func *f, const struct header *h, struct stmt *globals)
{
    int nvec = 0;
    while (nvec < f->nparams && f->pty[nvec].b == B_FLOAT && f->pty[nvec].n == 3)
        ++nvec;
    static const char *form = "a full BRDF takes (vec3 L, vec3 V, vec3 N[, vec3 X, vec3 Y], float n[, float p0"
                              "[, float p1]]) and returns float or vec3";
    if (nvec != 3 && nvec != 5)
        FAIL(S, f->name, "%s (this one takes %d vectors first)", form, nvec);
    if (f->nparams <= nvec || f->pty[nvec].b != B_FLOAT || f->pty[nvec].n != 1)
        FAIL(S, f->name, "%s: the shininess n after the vectors is missing", form);
    for (int i = nvec + 1; i < f->nparams; ++i)
        if (f->pty[i].b != B_FLOAT || f->pty[i].n != 1)
            FAIL(S, f->pname[i], "%s", form);
    if (f->nparams - nvec - 1 != h->nparams)
        FAIL(S, f->name, "the full BRDF takes %d parameter%s after n, the header declares %d", f->nparams - nvec - 1,
             f->nparams - nvec - 1 == 1 ? "" : "s", h->nparams);
    if (!(f->ret.b == B_FLOAT && (f->ret.n == 1 || f->ret.n == 3)))
        FAIL(S, f->name, "%s (this one returns %s)", form, type_name(S, f->ret));
    if (h->present && strcmp(h->lobe, "theta_h") != 0)
        FAIL(S, f->name, "a full BRDF is measured over theta_h: its header says 'lobe: theta_h'");
    struct md_buf w;
    md_init(&w);
    md_printf(&w, "float brdfbench_lobe(float brdfbench_c, float brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", float brdfbench_p%d", i);
    md_printf(&w, ") { " SL_LOBE_GEOMETRY "%s brdfbench_r = %.*s(brdfbench_N, brdfbench_V, brdfbench_N, ",
              f->ret.n == 3 ? "vec3" : "float", f->name->len, f->name->p);
    if (nvec == 5)
        md_printf(&w, "vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), ");
    md_printf(&w, "brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", brdfbench_p%d", i);
    md_printf(&w, "); float brdfbench_y = %s; return brdfbench_nv > 0.0 ? brdfbench_y : 0.0; }",
              f->ret.n == 3 ? "dot(brdfbench_r, " SL_LUMINANCE ")" : "brdfbench_r");
    /* the same function at the vectors of a scene (render, the physical-cost table) */
    full_function_open(&w, h->nparams);
    md_printf(&w, "%s brdfbench_r = %.*s(brdfbench_L, brdfbench_V, brdfbench_N, ", f->ret.n == 3 ? "vec3" : "float",
              f->name->len, f->name->p);
    if (nvec == 5)
        md_printf(&w, "brdfbench_X, brdfbench_Y, ");
    md_printf(&w, "brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", brdfbench_p%d", i);
    md_printf(&w, "); return %s; }", f->ret.n == 3 ? "dot(brdfbench_r, " SL_LUMINANCE ")" : "brdfbench_r");
    if (w.failed) {
        md_free(&w);
        sl_fail_at(S, 0, 0, "out of memory");
    }
    /* the tokens go before the end of the text; the text is kept until the translation ends */
    char *kept = arena_alloc(S, w.len + 1);
    memcpy(kept, w.s, w.len + 1);
    md_free(&w);
    struct tok eof = S->toks.v[--S->toks.n];
    S->pos = S->toks.n;
    lex_span(S, kept, kept + strlen(kept), 0, 0, NULL);
    tokv_push(S, &S->toks, eof);
    parse_program(S, globals);
    for (struct func *g = S->funcs; g; g = g->next)
        if (tok_is(g->name, "brdfbench_lobe"))
            return g;
    sl_fail_at(S, 0, 0, "internal: the lobe function of the full BRDF is missing");
}

/* Emits the function emit_name: the model's (c, n[, p...]), or with full set the full-vector
 * function of a full BRDF (REAL L, V, N components, n[, p...]). */
static void emit_function(struct sl *S, struct func *model, struct stmt *body, struct stmt *globals,
                          const struct header *h, const char *emit_name, int first_line, int full)
{
    S->line_next = -1;
    int fline = model && model->name->line > 0 ? model->name->line : first_line;
    S->stmt_line = fline;
    md_printf(&S->out, "#line %d \"", fline);
    for (const char *p = S->origin; *p; ++p) {
        if (*p == '"' || *p == '\\')
            md_append(&S->out, "\\", 1);
        md_append(&S->out, p, 1);
    }
    if (full)
        md_printf(&S->out, "\"\nREAL %s(REAL sl_a0_x, REAL sl_a0_y, REAL sl_a0_z, REAL sl_a1_x, REAL sl_a1_y, "
                  "REAL sl_a1_z, REAL sl_a2_x, REAL sl_a2_y, REAL sl_a2_z, REAL sl_n", emit_name);
    else
        md_printf(&S->out, "\"\nREAL %s(REAL sl_c, REAL sl_n", emit_name);
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&S->out, ", RSCALAR sl_p%d", i);
    md_printf(&S->out, ")\n{\n");
    S->line_next = fline + 2;
    push_scope(S, 1);
    S->globals = S->scope;
    struct fnctx fc = { { B_FLOAT, 1 }, { NULL }, NULL, NULL, 1, 0 };
    S->fn = &fc;
    /* The arguments: in the function form in a scope of their own under the globals (a helper
       sees the globals, not the model's arguments); in the body form among the globals. */
    struct scope *args = S->globals;
    if (model) {
        push_scope(S, 1);
        args = S->scope;
    }
    static const struct tok cn[2] = { { K_ID, 0, 0, "c", 1 }, { K_ID, 0, 0, "n", 1 } };
    struct tok pt[SL_MAX_PARAMS];
    if (full) {
        /* L, V, N, n, then the parameters */
        for (int i = 0; i < model->nparams; ++i) {
            struct sym *s = declare(S, args, model->pname[i], model->pty[i]);
            for (int k = 0; k < model->pty[i].n && i < 3; ++k)
                out_line(S, "REAL %s = sl_a%d_%c;", s->c[k], i, "xyz"[k]);
            if (i == 3)
                out_line(S, "REAL %s = sl_n;", s->c[0]);
            else if (i > 3)
                out_line(S, "REAL %s = RSPLAT(sl_p%d);", s->c[0], i - 4);
        }
    }
    for (int i = 0; i < 2 + h->nparams && !full; ++i) {
        const struct tok *pn;
        struct type ty = { B_FLOAT, 1 };
        if (model) {
            pn = model->pname[i];
            ty = model->pty[i];
        } else if (i < 2) {
            pn = &cn[i];
        } else {
            pt[i - 2] = (struct tok){ K_ID, 0, 0, h->params[i - 2], (int)strlen(h->params[i - 2]) };
            pn = &pt[i - 2];
            ty.b = h->integer[i - 2] ? B_INT : B_FLOAT;
        }
        struct sym *s = declare(S, args, pn, ty);
        if (i < 2)
            out_line(S, "REAL %s = sl_%c;", s->c[0], i == 0 ? 'c' : 'n');
        else if (ty.b == B_INT)
            out_line(S, "int %s = (int)sl_p%d;", s->c[0], i - 2);
        else
            out_line(S, "REAL %s = RSPLAT(sl_p%d);", s->c[0], i - 2);
    }
    if (model) {
        S->scope = S->globals;
        emit_block(S, globals, NULL, 0);
        S->scope = args;
        S->inlining[S->ninline++] = model;
        emit_block(S, model->body, NULL, 0);
    } else {
        S->allow_implicit = 1;
        emit_block(S, body, NULL, 0);
    }
    if (!fc.returned)
        out_line(S, "return sl_ret;");
    md_printf(&S->out, "}\n");
}

static __attribute__((noinline)) void translate_text(struct sl *S, const char *text, size_t len, const struct header *h, const char *name)
{
    S->src = text;
    int first_line = h->first_line > 0 ? h->first_line : 1;
    if (h->prelude)
        lex_span(S, h->prelude, h->prelude + strlen(h->prelude), 0, 0, NULL);
    lex_span(S, text, text + len, first_line, 1, NULL);
    if (h->epilogue)
        lex_span(S, h->epilogue, h->epilogue + strlen(h->epilogue), 0, 0, NULL);
    tokv_push(S, &S->toks, (struct tok){ K_EOF, 0, 0, text + len, 0 });
    {
        /* the end-of-text token points after the last character */
        int line = first_line, col = 1;
        for (size_t i = 0; i < len; ++i) {
            if (text[i] == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
        }
        S->toks.v[S->toks.n - 1].line = line;
        S->toks.v[S->toks.n - 1].col = col;
    }
    if (S->toks.n == 1)
        sl_fail_at(S, 0, 0, "the model has no code (a function of c and n, or statements ending in return)");
    struct stmt *globals = new_stmt(S, S_BLOCK, peek(S));
    globals->op = 1;
    struct stmt *body = parse_program(S, globals);

    const char *fname = h->function[0] ? h->function : name;
    struct func *model = NULL;
    int full_brdf = 0;
    if (!body) {
        for (struct func *f = S->funcs; f; f = f->next)
            if ((int)strlen(fname) == f->name->len && strncmp(f->name->p, fname, (size_t)f->name->len) == 0)
                model = f;
        if (!model && h->function[0])
            sl_fail_at(S, 0, 0, "the header names the function '%s', which the text does not define", fname);
        if (!model)
            for (struct func *f = S->funcs; f; f = f->next)
                model = f; /* the last one */
        if (!model)
            sl_fail_at(S, 0, 0, "no function defined");
        if (model->nparams > 0 && model->pty[0].b == B_FLOAT && model->pty[0].n == 3) {
            model = full_brdf_lobe(S, model, h, globals);
            full_brdf = 1;
        }
        if (model->ret.b != B_FLOAT || model->ret.n != 1)
            FAIL(S, model->name, "the model's function must return float (a lobe value), not %s", type_name(S, model->ret));
        if (model->nparams < 2)
            FAIL(S, model->name, "the model's function takes the cosine c and the shininess n first: "
                                 "float %.*s(float c, float n%s)", model->name->len, model->name->p,
                 h->nparams ? ", float ..." : "");
        for (int i = 0; i < model->nparams; ++i) {
            int want_int = i >= 2 && h->integer[i - 2];
            if (!(model->pty[i].b == B_FLOAT && model->pty[i].n == 1) && !(want_int && model->pty[i].b == B_INT))
                FAIL(S, model->pname[i], "parameter %d of the model's function is a %s; it takes floats "
                     "(c, n, then the header's parameters)", i + 1, type_name(S, model->pty[i]));
        }
        if (model->nparams - 2 != h->nparams) {
            if (!h->present)
                FAIL(S, model->pname[2], "the model's parameter '%.*s' needs a range: begin the file with a header "
                     "/* brdfbench-model  name: %s  param: %.*s MIN MAX DEFAULT */ (docs/user-models.md)",
                     model->pname[2]->len, model->pname[2]->p, name, model->pname[2]->len, model->pname[2]->p);
            FAIL(S, model->name, "the model's function takes %d parameter%s after c and n, the header declares %d",
                 model->nparams - 2, model->nparams - 2 == 1 ? "" : "s", h->nparams);
        }
        if (!stmt_returns(model->body))
            FAIL(S, model->close, "the function can reach its end without returning a value");
    } else if (!stmt_returns(body)) {
        sl_fail_at(S, S->toks.v[S->toks.n - 1].line, S->toks.v[S->toks.n - 1].col,
                   "the model ends without returning a value (end it with return EXPR; or with an expression)");
    }
    if (h->function[0] && (strncmp(fname, "u__", 3) == 0 || strncmp(fname, "sl_", 3) == 0))
        sl_fail_at(S, 0, 0, "names beginning with u__ or sl_ are reserved in a shader-language model");

    /* The model function, in the form usermodel.c wraps. Unless the header names it, it is
       called sl_NAME (NAME: the shader's function, or "model"), so that a model's name never
       meets a word of OpenCL C (a model called half, or mix). */
    const char *emit_name = h->function[0] ? h->function
                            : model ? sfmt(S, "sl_%.*s", model->name->len, model->name->p) : "sl_model";
    if (h->header_text) {
        md_printf(&S->out, "%s", h->header_text);
    } else if (h->present) {
        size_t close = h->end - 2, line_start = close;
        while (line_start > 0 && text[line_start - 1] != '\n')
            --line_start;
        int bare = line_start > 0;
        for (size_t i = line_start; i < close; ++i)
            if (!isspace((unsigned char)text[i]) && text[i] != '*')
                bare = 0;
        if (h->function[0]) {
            md_append(&S->out, text, h->end);
        } else if (bare) {
            /* "function: ..." on the closing line, so the header keeps its lines */
            md_append(&S->out, text, line_start);
            md_printf(&S->out, " * function: %s */", emit_name);
        } else {
            md_append(&S->out, text, h->end);
            emit_name = name;
        }
        md_append(&S->out, "\n", 1);
    } else {
        md_printf(&S->out, "/* brdfbench-model\n * name: %s\n * function: %s\n%s */\n", name, emit_name,
                  full_brdf ? " * lobe: theta_h\n * reference: blinn\n * description: a full BRDF: luminance of "
                              "f(L = N, V) with theta_h = acos(c)\n" : "");
    }
    emit_function(S, model, body, globals, h, emit_name, first_line, 0);
    /* a full BRDF: its function of the vectors too */
    if (full_brdf || h->header_text)
        for (struct func *g = S->funcs; g; g = g->next)
            if (tok_is(g->name, "brdfbench_full")) {
                S->scope = NULL;
                S->ninline = 0;
                emit_function(S, g, NULL, globals, h, SHADERLANG_FULL_FUNCTION, first_line, 1);
            }
    if (S->out.failed)
        sl_fail_at(S, 0, 0, "out of memory");
}

static int translate(struct sl *S, const char *text, size_t len, const struct header *h, const char *name,
                     char **out, size_t *outlen)
{
    md_init(&S->out);
    if (setjmp(S->fail)) {
        md_free(&S->out);
        return EXIT_USAGE;
    }
    translate_text(S, text, len, h, name);
    *out = S->out.s;
    *outlen = S->out.len;
    return 0;
}

static void sl_free(struct sl *S)
{
    while (S->arena) {
        struct arena_block *b = S->arena;
        S->arena = b->next;
        free(b);
    }
}

static int uses_word(const char *text, size_t len, const char *w)
{
    size_t wl = strlen(w);
    for (size_t i = 0; i + wl <= len; ++i)
        if (strncmp(text + i, w, wl) == 0 && (i == 0 || !(isalnum((unsigned char)text[i - 1]) || text[i - 1] == '_')) &&
            (i + wl == len || !(isalnum((unsigned char)text[i + wl]) || text[i + wl] == '_')))
            return 1;
    return 0;
}

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
    char msg[400];
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

static int parse_finite(const char *t, double *v)
{
    char *end = NULL;
    *v = strtod(t, &end);
    return end != t && *end == '\0' && *v == *v && *v - *v == 0;
}

/* A BRDF Explorer file: "::begin parameters" (float NAME MIN MAX DEFAULT, bool NAME 0|1,
 * color NAME R G B) and "::begin shader" with vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y),
 * as a full BRDF reduced to a lobe (docs/user-models.md, "BRDF Explorer files"). */
/* The statements that open a .brdf file's functions: the shininess to n (or alpha) and the model
 * parameters to their globals. */
static void brdf_set_params(struct md_buf *epi, int has_n, const struct brdf_param *prm, const int *model_params,
                            int nmp)
{
    if (has_n)
        md_printf(epi, "n = brdfbench_n; ");
    else
        md_printf(epi, "alpha = sqrt(2.0 / (brdfbench_n + 2.0)); ");
    for (int i = 0; i < nmp; ++i)
        md_printf(epi, "%s = brdfbench_p%d; ", prm[model_params[i]].name, i);
}

static int brdf_file(const char *text, size_t len, const char *path, const char *name, char **out, size_t *outlen,
                     char *err, size_t errlen)
{
    struct brdf_param prm[BRDF_MAX_FILE_PARAMS];
    int nprm = 0, in_params = 0, in_shader = 0, shader_line = 0, seen_params = 0, line = 0;
    size_t shader_start = 0, shader_end = 0;
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
                shader_end = (size_t)(p - text);
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
                if (shader_line)
                    return brdf_fail(err, errlen, path, line, "a second ::begin shader");
                in_shader = 1;
                shader_line = line + 1;
                shader_start = (size_t)(eol - text) + (eol < end);
            } else {
                return brdf_fail(err, errlen, path, line, "unknown block line '%.60s' (accepted: ::begin/::end "
                                 "parameters, ::begin/::end shader)", t);
            }
        } else if (in_params && *t && *t != '#' && strncmp(t, "//", 2) != 0) {
            char *save = NULL, *w[6];
            int nw = 0;
            for (char *x = strtok_r(t, " \t", &save); x && nw < 6; x = strtok_r(NULL, " \t", &save))
                w[nw++] = x;
            if (nprm == BRDF_MAX_FILE_PARAMS)
                return brdf_fail(err, errlen, path, line, "more than %d parameters", BRDF_MAX_FILE_PARAMS);
            struct brdf_param *q = &prm[nprm];
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
            if (!valid_identifier(w[1]) || strncmp(w[1], "brdfbench_", 10) == 0 || strncmp(w[1], "u__", 3) == 0 ||
                strncmp(w[1], "sl_", 3) == 0)
                return brdf_fail(err, errlen, path, line, "parameter name '%.60s' is not an identifier of 1 to %d "
                                 "characters or is reserved (brdfbench_*, sl_*, u__*)", w[1], SL_NAME_MAX);
            for (int k = 0; k < nprm; ++k)
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
            ++nprm;
        }
        p = eol + (eol < end);
    }
    if (in_params)
        return brdf_fail(err, errlen, path, 0, "::begin parameters is not closed by ::end parameters");
    if (!shader_line)
        return brdf_fail(err, errlen, path, 0, "no ::begin shader block (a BRDF Explorer file holds vec3 BRDF(vec3 L, "
                         "vec3 V, vec3 N, vec3 X, vec3 Y) there)");
    if (in_shader != 2)
        return brdf_fail(err, errlen, path, shader_line - 1, "::begin shader is not closed by ::end shader");

    /* The shininess: a float parameter n takes the sweep's n; else one called alpha takes
       sqrt(2 / (n + 2)), the microfacet built-ins' roughness. Up to two other floats become the
       model's parameters; the rest, the bools and the colours keep their defaults. */
    int shin = -1, alpha = -1, model_params[SL_MAX_PARAMS], nmp = 0;
    for (int k = 0; k < nprm; ++k)
        if (prm[k].type == 'f' && strcmp(prm[k].name, "n") == 0)
            shin = k;
    for (int k = 0; k < nprm && shin < 0; ++k)
        if (prm[k].type == 'f' && strcmp(prm[k].name, "alpha") == 0)
            alpha = k;
    if (shin < 0 && alpha < 0)
        return brdf_fail(err, errlen, path, 0, "no float parameter n or alpha: the sweep's shininess n goes to n, or "
                         "to alpha as sqrt(2/(n+2)) (docs/user-models.md)");
    for (int k = 0; k < nprm; ++k) {
        if (prm[k].type != 'f' || k == shin || k == alpha)
            continue;
        if (nmp < SL_MAX_PARAMS)
            model_params[nmp++] = k;
    }
    struct header sh;
    read_header(text + shader_start, shader_end - shader_start, &sh);
    struct md_buf hb, pre, epi;
    md_init(&hb);
    md_init(&pre);
    md_init(&epi);
    md_printf(&hb, "/* brdfbench-model\n * name: %s\n * function: brdfbench_lobe\n", sh.name[0] ? sh.name : name);
    md_printf(&hb, " * description: %s\n", sh.description[0] ? sh.description
               : "BRDF Explorer file: luminance of BRDF(L = N, V) with theta_h = acos(c)");
    md_printf(&hb, " * reference: %s\n * lobe: theta_h\n", sh.reference[0] ? sh.reference : "blinn");
    for (int i = 0; i < nmp; ++i) {
        const struct brdf_param *q = &prm[model_params[i]];
        md_printf(&hb, " * param: %s %.17g %.17g %.17g\n", q->name, q->v[0], q->v[1], q->v[2]);
    }
    md_printf(&hb, " */\n");
    /* the parameters as globals; the lobe function sets those it takes */
    for (int k = 0; k < nprm; ++k) {
        const struct brdf_param *q = &prm[k];
        int taken = k == shin || k == alpha;
        for (int i = 0; i < nmp; ++i)
            taken |= model_params[i] == k;
        if (taken)
            md_printf(&pre, "float %s; ", q->name);
        else if (q->type == 'f')
            md_printf(&pre, "const float %s = %.17g; ", q->name, q->v[2]);
        else if (q->type == 'b')
            md_printf(&pre, "const bool %s = %s; ", q->name, q->v[0] != 0 ? "true" : "false");
        else
            md_printf(&pre, "const vec3 %s = vec3(%.17g, %.17g, %.17g); ", q->name, q->v[0], q->v[1], q->v[2]);
    }
    md_printf(&epi, "float brdfbench_lobe(float brdfbench_c, float brdfbench_n");
    for (int i = 0; i < nmp; ++i)
        md_printf(&epi, ", float brdfbench_p%d", i);
    md_printf(&epi, ") { ");
    brdf_set_params(&epi, shin >= 0, prm, model_params, nmp);
    /* L = N, V at 2 theta_h from N in the XZ plane: N.V = 2c^2 - 1, N.H = V.H = c */
    md_printf(&epi, "vec3 brdfbench_N = vec3(0.0, 0.0, 1.0); "
                    "float brdfbench_nv = 2.0 * brdfbench_c * brdfbench_c - 1.0; "
                    "vec3 brdfbench_V = vec3(2.0 * brdfbench_c * sqrt(max((1.0 - brdfbench_c) * (1.0 + brdfbench_c), 0.0)), "
                    "0.0, brdfbench_nv); "
                    "vec3 brdfbench_rgb = BRDF(brdfbench_N, brdfbench_V, brdfbench_N, vec3(1.0, 0.0, 0.0), "
                    "vec3(0.0, 1.0, 0.0)); "
                    "float brdfbench_y = dot(brdfbench_rgb, vec3(0.2126, 0.7152, 0.0722)); "
                    "return brdfbench_nv > 0.0 ? brdfbench_y : 0.0; }");
    full_function_open(&epi, nmp);
    brdf_set_params(&epi, shin >= 0, prm, model_params, nmp);
    md_printf(&epi, "return dot(BRDF(brdfbench_L, brdfbench_V, brdfbench_N, brdfbench_X, brdfbench_Y), "
                    "vec3(0.2126, 0.7152, 0.0722)); }");
    int rc;
    if (hb.failed || pre.failed || epi.failed) {
        rc = brdf_fail(err, errlen, path, 0, "out of memory");
    } else {
        struct header h;
        memset(&h, 0, sizeof h);
        h.present = 1;
        snprintf(h.function, sizeof h.function, "brdfbench_lobe");
        h.nparams = nmp;
        for (int i = 0; i < nmp; ++i)
            snprintf(h.params[i], sizeof h.params[i], "%s", prm[model_params[i]].name);
        h.header_text = hb.s;
        h.prelude = pre.s ? pre.s : "";
        h.epilogue = epi.s;
        h.first_line = shader_line;
        struct sl S;
        memset(&S, 0, sizeof S);
        S.err = err;
        S.errlen = errlen;
        S.origin = path;
        rc = translate(&S, text + shader_start, shader_end - shader_start, &h, sh.name[0] ? sh.name : name, out,
                       outlen);
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
        if (uses_word(text, len, "REAL") || uses_word(text, len, "RSCALAR"))
            return SHADERLANG_NOT_SHADER;
    }
    struct header h;
    if (is_brdf)
        memset(&h, 0, sizeof h); /* its header, if any, is in the shader block */
    else
        read_header(text, len, &h);
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
        if (!valid_identifier(name)) {
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
    int rc = translate(&S, text, len, &h, name, out, outlen);
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
    int rc = translate(&S, expr, len, &h, name, out, outlen);
    if (rc && !S.statement_form && !S.shader_only && !memchr(expr, ';', len) && !memchr(expr, '{', len))
        rc = SHADERLANG_NOT_SHADER; /* OpenCL C as before: its compiler has the last word */
    sl_free(&S);
    return rc;
}
