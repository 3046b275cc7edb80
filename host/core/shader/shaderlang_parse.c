/* shaderlang_parse.c - the shader-language translator (shaderlang.c): the parser. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "shaderlang_internal.h"
#include "exitcodes.h"
#include "mdbuf.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the parser ------------------------------------------------------------------------- */

const struct tok *sl_peek(struct sl *S) { return &S->toks.v[S->pos]; }
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
    if (sl_tok_is(sl_peek(S), s)) {
        next(S);
        return 1;
    }
    return 0;
}
static const char *tok_desc(struct sl *S, const struct tok *t)
{
    return t->k == K_EOF ? "the end of the text" : sl_sfmt(S, "'%.*s'", t->len > 40 ? 40 : t->len, t->p);
}
static const struct tok *expect(struct sl *S, const char *s)
{
    const struct tok *t = sl_peek(S);
    if (!sl_tok_is(t, s))
        FAIL(S, t, "expected '%s', found %s", s, tok_desc(S, t));
    return next(S);
}

/* A type name: float, half, vec2..4, float2..4, half2..4, int, uint, bool, void. 1 when t is one. */
int sl_type_of_name(const struct tok *t, struct type *ty, int *shader_only)
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
        *ty = (struct type){ .b = B_FLOAT, .n = 1, .half = w[0] != 'f' };
        return 1;
    }
    if (strcmp(w, "int") == 0 || strcmp(w, "uint") == 0) {
        *ty = (struct type){ .b = B_INT, .n = 1 };
        return 1;
    }
    if (strcmp(w, "bool") == 0) {
        *ty = (struct type){ .b = B_BOOL, .n = 1 };
        return 1;
    }
    if (strcmp(w, "void") == 0) {
        *ty = (struct type){ .b = B_VOID, .n = 1 };
        return 1;
    }
    int mn, rows;
    if (sl_matrix_of_name(w, &mn, &rows)) {
        *ty = (struct type){ .b = B_STRUCT, .n = 1, .st = sl_matrix_def(mn, rows) };
        *shader_only = 1;
        return 1;
    }
    size_t l = strlen(w);
    char last = w[l - 1];
    if (last >= '2' && last <= '4') {
        w[l - 1] = '\0';
        if (strcmp(w, "vec") == 0 || strcmp(w, "float") == 0 || strcmp(w, "half") == 0 ||
            strcmp(w, "min16float") == 0) {
            *ty = (struct type){ .b = B_FLOAT, .n = last - '0', .half = w[0] == 'h' || w[0] == 'm' };
            *shader_only = 1;
            return 1;
        }
    }
    return 0;
}

const struct sdef *sl_find_struct(struct sl *S, const struct tok *t)
{
    if (t->k != K_ID)
        return NULL;
    for (const struct sdef *d = S->structs; d; d = d->next)
        if (d->name->len == t->len && strncmp(d->name->p, t->p, (size_t)t->len) == 0)
            return d;
    return NULL;
}

static int is_qualifier(const struct tok *t)
{
    static const char *q[] = { "highp", "mediump", "lowp", "precise", "in", "inline", NULL };
    for (int i = 0; q[i]; ++i)
        if (sl_tok_is(t, q[i]))
            return 1;
    return 0;
}

static void check_unsupported_word(struct sl *S, const struct tok *t)
{
    static const struct { const char *w, *why; } words[] = {
        { "discard", "discard is not supported" },
        { "uniform", "uniforms are not supported: declare the model's parameters in the header "
                     "('param: NAME MIN MAX DEFAULT') and take them as the function's arguments after c and n" },
        { "double", "double is not supported (write float: the reference is double anyway)" },
        /* what a shader cannot do, and a model may not either */
        { "asm", "inline assembly is not accepted in a model" },
        { "__asm__", "inline assembly is not accepted in a model" },
        { "volatile", "volatile is not accepted in a model (a model has no memory but its own values)" },
        { "sizeof", "sizeof is not accepted in a model (a model has no memory but its own values)" },
        { "goto", "goto is not accepted in a model" },
        { NULL, NULL } };
    for (int i = 0; words[i].w; ++i)
        if (sl_tok_is(t, words[i].w)) {
            /* what no model may do is refused for good: not left to the OpenCL C reading of a
               --model expression */
            if (strstr(words[i].why, "not accepted in a model"))
                S->shader_only = 1;
            FAIL(S, t, "%s", words[i].why);
        }
}

static struct expr *new_expr(struct sl *S, int k, const struct tok *t)
{
    struct expr *e = sl_arena_alloc(S, sizeof *e);
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
                FAIL(S, sl_peek(S), "more than %d arguments", SL_MAX_ARGS);
            args[n++] = parse_expr(S);
            if (accept(S, ")"))
                break;
            expect(S, ",");
        }
    }
    e->args = sl_arena_alloc(S, sizeof *e->args * (size_t)(n ? n : 1));
    memcpy(e->args, args, sizeof *args * (size_t)n);
    e->nargs = n;
    return e;
}

static struct expr *parse_unary(struct sl *S);

/* Values up to `close` (after the opening), a trailing comma allowed: an E_ARR at t. */
static struct expr *parse_value_list(struct sl *S, const struct tok *t, const char *close, int max)
{
    struct expr *e = new_expr(S, E_ARR, t);
    int cap = 8;
    e->args = sl_arena_alloc(S, sizeof *e->args * (size_t)cap);
    if (!sl_tok_is(sl_peek(S), close))
        for (;;) {
            if (e->nargs == max)
                FAIL(S, sl_peek(S), "more than %d values", max);
            if (e->nargs == cap) {
                struct expr **v = sl_arena_alloc(S, sizeof *v * (size_t)(2 * cap));
                memcpy(v, e->args, sizeof *v * (size_t)cap);
                e->args = v;
                cap *= 2;
            }
            e->args[e->nargs++] = parse_expr(S);
            if (!accept(S, ","))
                break;
            if (sl_tok_is(sl_peek(S), close))
                break; /* a trailing comma */
        }
    expect(S, close);
    if (e->nargs == 0)
        FAIL(S, t, "an empty list of values");
    return e;
}

static struct expr *parse_primary(struct sl *S)
{
    const struct tok *t = sl_peek(S);
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
        if (sl_tok_is(t, "true") || sl_tok_is(t, "false")) {
            next(S);
            S->shader_only = 1;
            return new_expr(S, E_BOOL, t);
        }
        next(S);
        if (sl_type_of_name(t, &ty, &so) && sl_tok_is(sl_peek(S), "[")) {
            /* GLSL's array constructor float[3](a, b, c) (or float[](...)) */
            next(S);
            struct expr *len = sl_tok_is(sl_peek(S), "]") ? NULL : parse_expr(S);
            expect(S, "]");
            const struct tok *open = expect(S, "(");
            struct expr *e = parse_value_list(S, open, ")", SL_MAX_ARRAY);
            e->ctor = ty;
            e->has_ctor = 1;
            e->a = len;
            return e;
        }
        if (sl_tok_is(sl_peek(S), "(")) {
            if (sl_type_of_name(t, &ty, &so))
                S->shader_only = 1;
            return parse_call_args(S, new_expr(S, E_CALL, t));
        }
        if (sl_type_of_name(t, &ty, &so))
            FAIL(S, t, "a type name here: a constructor takes its components in parentheses, e.g. %.*s(...)",
                 t->len, t->p);
        return new_expr(S, E_VAR, t);
    }
    if (sl_tok_is(t, "*")) {
        S->shader_only = 1; /* refused for good, not left to OpenCL C */
        FAIL(S, t, "'*' before a value reads through a pointer: pointers are not accepted in a model");
    }
    if (sl_tok_is(t, "(")) {
        const struct tok *t1 = peek_at(S, 1);
        if (sl_type_of_name(t1, &ty, &so) && sl_tok_is(peek_at(S, 2), "*")) {
            S->shader_only = 1;
            FAIL(S, peek_at(S, 2), "a cast to a pointer type: pointers are not accepted in a model");
        }
        if (sl_type_of_name(t1, &ty, &so) && sl_tok_is(peek_at(S, 2), ")")) {
            /* a cast: (float)x, (int)x, (float3)x */
            next(S);
            next(S);
            next(S);
            S->shader_only = 1;
            struct expr *e = new_expr(S, E_CALL, t1);
            e->is_cast = 1;
            e->args = sl_arena_alloc(S, sizeof *e->args);
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
    while (sl_tok_is(sl_peek(S), ".") || sl_tok_is(sl_peek(S), "[")) {
        if (sl_tok_is(sl_peek(S), "[")) {
            const struct tok *open = next(S);
            struct expr *x = new_expr(S, E_IDX, open);
            x->a = e;
            x->b = parse_expr(S);
            expect(S, "]");
            S->shader_only = 1;
            e = x;
            continue;
        }
        const struct tok *dot = next(S);
        const struct tok *f = sl_peek(S);
        if (f->k != K_ID)
            FAIL(S, f, "expected a swizzle (.x, .xy, .rgb, ...) after '.'");
        next(S);
        struct expr *s = new_expr(S, E_SWZ, dot);
        s->a = e;
        s->field = f;
        /* a swizzle, or (no swizzle's letters) a struct's field: which one, the value's type says */
        s->nswz = f->len <= 4 ? f->len : 0;
        for (int i = 0; i < s->nswz; ++i) {
            int k = swizzle_index(f->p[i]);
            if (k < 0) {
                s->nswz = 0;
                break;
            }
            s->swz[i] = k;
        }
        S->shader_only = 1;
        e = s;
    }
    return e;
}

static struct expr *parse_unary_inner(struct sl *S);
static struct expr *parse_unary(struct sl *S)
{
    if (++S->depth > SL_MAX_NESTING)
        FAIL(S, sl_peek(S), "nested more than %d levels deep", SL_MAX_NESTING);
    struct expr *e = parse_unary_inner(S);
    --S->depth;
    return e;
}

static struct expr *parse_unary_inner(struct sl *S)
{
    const struct tok *t = sl_peek(S);
    if (sl_tok_is(t, "-") || sl_tok_is(t, "+") || sl_tok_is(t, "!")) {
        next(S);
        struct expr *e = new_expr(S, E_UN, t);
        e->op = t->p[0] == '-' ? 'u' : t->p[0] == '+' ? 'p' : '!';
        e->a = parse_unary(S);
        return e;
    }
    if (sl_tok_is(t, "++") || sl_tok_is(t, "--"))
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
        if (ops[i].level == level && sl_tok_is(t, ops[i].s))
            return ops[i].code;
    return 0;
}

static struct expr *parse_binary(struct sl *S, int level)
{
    if (level > 5)
        return parse_unary(S);
    struct expr *e = parse_binary(S, level + 1);
    for (;;) {
        const struct tok *t = sl_peek(S);
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
    if (sl_tok_is(sl_peek(S), "?")) {
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

struct stmt *sl_new_stmt(struct sl *S, int k, const struct tok *t)
{
    struct stmt *s = sl_arena_alloc(S, sizeof *s);
    s->k = k;
    s->t = t;
    return s;
}

static void block_add(struct sl *S, struct stmt *b, struct stmt *s)
{
    if (b->n == b->cap) {
        int cap = b->cap ? 2 * b->cap : 8;
        struct stmt **v = sl_arena_alloc(S, sizeof *v * (size_t)cap);
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
    int prec = -1; /* a precision qualifier: 1 mediump or lowp (binary16), 0 highp */
    for (;;) {
        const struct tok *t = sl_peek(S);
        if (sl_tok_is(t, "const")) {
            *is_const = 1;
            next(S);
        } else if (sl_tok_is(t, "static") || is_qualifier(t)) {
            if (sl_tok_is(t, "mediump") || sl_tok_is(t, "lowp"))
                prec = 1;
            else if (sl_tok_is(t, "highp"))
                prec = 0;
            next(S);
        } else {
            break;
        }
    }
    int so;
    const struct tok *t = sl_peek(S);
    check_unsupported_word(S, t);
    if (sl_type_of_name(t, ty, &so) && !sl_tok_is(peek_at(S, 1), "(")) {
        if (so)
            S->shader_only = 1;
        /* float and vecN take the qualifier, else the default of `precision mediump float;` */
        if (ty->b == B_FLOAT && ty->half == 0 && (prec == 1 || (prec == -1 && S->default_half)))
            ty->half = 1;
        next(S);
        return 1;
    }
    const struct sdef *st = sl_find_struct(S, t);
    if (st && !sl_tok_is(peek_at(S, 1), "(")) {
        *ty = (struct type){ .b = B_STRUCT, .n = 1, .st = st };
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
    struct stmt *list = sl_new_stmt(S, S_BLOCK, start);
    list->op = 1; /* no scope */
    for (;;) {
        const struct tok *name = sl_peek(S);
        if (sl_tok_is(name, "*"))
            FAIL(S, name, "a pointer declaration: pointers are not accepted in a model");
        if (name->k != K_ID)
            FAIL(S, name, "expected a variable name, found %s", tok_desc(S, name));
        check_unsupported_word(S, name);
        next(S);
        struct stmt *d = sl_new_stmt(S, S_DECL, name);
        d->ty = ty;
        d->is_const = is_const;
        d->name = name;
        if (accept(S, "[")) {
            d->is_array = 1;
            d->arr_len = sl_tok_is(sl_peek(S), "]") ? NULL : parse_expr(S);
            expect(S, "]");
        }
        if (accept(S, "=")) {
            const struct tok *brace = sl_peek(S);
            if (d->is_array) {
                if (accept(S, "{"))
                    d->e = parse_value_list(S, brace, "}", SL_MAX_ARRAY);
                else
                    d->e = parse_expr(S);
            } else if (accept(S, "{")) {
                /* HLSL's float3 v = { 1, 2, 3 }: the type's constructor of the listed values */
                struct expr *e = new_expr(S, E_CALL, brace);
                struct expr *args[SL_MAX_ARGS];
                int n = 0;
                if (!sl_tok_is(sl_peek(S), "}"))
                    for (;;) {
                        if (n == SL_MAX_ARGS)
                            FAIL(S, sl_peek(S), "more than %d values in braces", SL_MAX_ARGS);
                        args[n++] = parse_expr(S);
                        if (!accept(S, ","))
                            break;
                        if (sl_tok_is(sl_peek(S), "}"))
                            break; /* a trailing comma */
                    }
                expect(S, "}");
                if (n == 0)
                    FAIL(S, brace, "empty braces: an initialiser lists the values");
                e->args = sl_arena_alloc(S, sizeof *e->args * (size_t)n);
                memcpy(e->args, args, sizeof *args * (size_t)n);
                e->nargs = n;
                e->has_ctor = 1;
                e->ctor = ty;
                d->e = e;
            } else {
                d->e = parse_expr(S);
            }
        } else if (is_const)
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
    struct stmt *b = sl_new_stmt(S, S_BLOCK, open);
    while (!sl_tok_is(sl_peek(S), "}")) {
        if (sl_peek(S)->k == K_EOF)
            FAIL(S, open, "this '{' is not closed");
        block_add(S, b, parse_statement(S, 0));
    }
    next(S);
    return b;
}

static struct stmt *parse_simple(struct sl *S, int top_body, int need_semicolon)
{
    const struct tok *t = sl_peek(S);
    struct type ty;
    int is_const;
    if (parse_decl_type(S, &ty, &is_const)) {
        if (ty.b == B_VOID)
            FAIL(S, t, "a variable cannot be void");
        return parse_declaration(S, ty, is_const, t);
    }
    if (sl_tok_is(t, "++") || sl_tok_is(t, "--")) {
        next(S);
        struct stmt *s = sl_new_stmt(S, S_ASSIGN, t);
        s->lhs = parse_unary(S);
        s->op = t->p[0];
        s->e = new_expr(S, E_INT, t);
        s->e->op = 1; /* the literal 1 */
        if (need_semicolon)
            expect(S, ";");
        return s;
    }
    struct expr *e = parse_expr(S);
    const struct tok *a = sl_peek(S);
    struct stmt *s = sl_new_stmt(S, S_ASSIGN, a);
    s->lhs = e;
    if (sl_tok_is(a, "=") || sl_tok_is(a, "+=") || sl_tok_is(a, "-=") || sl_tok_is(a, "*=") || sl_tok_is(a, "/=") ||
        sl_tok_is(a, "%=")) {
        next(S);
        s->op = a->len == 1 ? '=' : a->p[0];
        s->e = parse_expr(S);
    } else if (sl_tok_is(a, "++") || sl_tok_is(a, "--")) {
        next(S);
        s->op = a->p[0];
        s->e = new_expr(S, E_INT, a);
        s->e->op = 1;
    } else if (top_body && a->k == K_EOF) {
        /* the body form's last expression, without return: its value */
        struct stmt *r = sl_new_stmt(S, S_RET, e->t);
        r->e = e;
        return r;
    } else if (e->k == E_CALL && !e->is_cast && sl_tok_is(a, ";")) {
        /* a call on its own: a function with out parameters, or of void */
        s->k = S_CALL;
        s->e = e;
        s->t = e->t;
    } else {
        if (sl_tok_is(a, ";"))
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
        FAIL(S, sl_peek(S), "nested more than %d levels deep", SL_MAX_NESTING);
    struct stmt *st = parse_statement_inner(S, top_body);
    --S->depth;
    return st;
}

static struct stmt *parse_statement_inner(struct sl *S, int top_body)
{
    /* HLSL's attributes before a statement ([unroll], [loop], [branch], [flatten], [unroll(4)]):
       hints to a compiler, nothing to a lobe's value (loops are unrolled here anyway) */
    while (sl_tok_is(sl_peek(S), "[") && peek_at(S, 1)->k == K_ID &&
           (sl_tok_is(peek_at(S, 2), "]") || sl_tok_is(peek_at(S, 2), "("))) {
        next(S);
        next(S);
        if (accept(S, "(")) {
            while (!sl_tok_is(sl_peek(S), ")") && sl_peek(S)->k != K_EOF)
                next(S);
            expect(S, ")");
        }
        expect(S, "]");
    }
    const struct tok *t = sl_peek(S);
    check_unsupported_word(S, t);
    if (sl_tok_is(t, "{"))
        return parse_block(S);
    if (accept(S, ";"))
        return sl_new_stmt(S, S_EMPTY, t);
    if (sl_tok_is(t, "if")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, S_IF, t);
        expect(S, "(");
        s->e = parse_expr(S);
        expect(S, ")");
        s->s1 = parse_statement(S, 0);
        if (accept(S, "else"))
            s->s2 = parse_statement(S, 0);
        return s;
    }
    if (sl_tok_is(t, "else"))
        FAIL(S, t, "'else' without an 'if'");
    if (sl_tok_is(t, "return")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, S_RET, t);
        if (accept(S, ";"))
            return s; /* of a void function; a value is asked for where one is due */
        s->e = parse_expr(S);
        if (!(top_body && sl_peek(S)->k == K_EOF))
            expect(S, ";");
        return s;
    }
    if (sl_tok_is(t, "while") || sl_tok_is(t, "do")) {
        /* while (COND) BODY; do BODY while (COND); */
        int is_do = sl_tok_is(t, "do");
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, is_do ? S_DO : S_WHILE, t);
        if (is_do) {
            s->s3 = parse_statement(S, 0);
            expect(S, "while");
        }
        expect(S, "(");
        s->e = parse_expr(S);
        expect(S, ")");
        if (is_do)
            expect(S, ";");
        else
            s->s3 = parse_statement(S, 0);
        return s;
    }
    if (sl_tok_is(t, "break") || sl_tok_is(t, "continue")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, sl_tok_is(t, "break") ? S_BREAK : S_CONTINUE, t);
        expect(S, ";");
        return s;
    }
    if (sl_tok_is(t, "case") || sl_tok_is(t, "default"))
        FAIL(S, t, "'%.*s' outside a switch", t->len, t->p);
    if (sl_tok_is(t, "switch")) {
        /* switch (EXPR) { case K: ... default: ... }: the labels are S_CASE items of its block
           (e: the constant, NULL for default) among its statements */
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, S_SWITCH, t);
        expect(S, "(");
        s->e = parse_expr(S);
        expect(S, ")");
        const struct tok *open = sl_peek(S);
        expect(S, "{");
        s->s1 = sl_new_stmt(S, S_BLOCK, open);
        while (!accept(S, "}")) {
            const struct tok *l = sl_peek(S);
            if (l->k == K_EOF)
                FAIL(S, open, "the switch's '{' is not closed");
            struct stmt *item;
            if (sl_tok_is(l, "case") || sl_tok_is(l, "default")) {
                next(S);
                item = sl_new_stmt(S, S_CASE, l);
                if (sl_tok_is(l, "case"))
                    item->e = parse_expr(S);
                expect(S, ":");
            } else {
                item = parse_statement(S, 0);
            }
            block_add(S, s->s1, item);
        }
        return s;
    }
    if (sl_tok_is(t, "for")) {
        next(S);
        S->statement_form = 1;
        struct stmt *s = sl_new_stmt(S, S_FOR, t);
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



/* struct NAME { TYPE field[, field]; ... }; (fields of numbers, vectors and structs). */
static void parse_struct(struct sl *S)
{
    next(S);
    const struct tok *name = sl_peek(S);
    if (name->k != K_ID)
        FAIL(S, name, "expected the struct's name, found %s", tok_desc(S, name));
    struct type dummy;
    int so;
    if (sl_type_of_name(name, &dummy, &so) || sl_find_struct(S, name))
        FAIL(S, name, "'%.*s' is already a type", name->len, name->p);
    next(S);
    struct sdef *d = sl_arena_alloc(S, sizeof *d);
    d->name = name;
    expect(S, "{");
    while (!accept(S, "}")) {
        struct type ft;
        int fc;
        const struct tok *t0 = sl_peek(S);
        if (!parse_decl_type(S, &ft, &fc))
            FAIL(S, t0, "expected a field's type, found %s", tok_desc(S, t0));
        if (ft.b == B_VOID || ft.b == B_BOOL)
            FAIL(S, t0, "a struct's field is a number, a vector or a struct, not %s", ft.b == B_VOID ? "void" : "bool");
        for (;;) {
            const struct tok *fn = sl_peek(S);
            if (fn->k != K_ID)
                FAIL(S, fn, "expected a field's name, found %s", tok_desc(S, fn));
            next(S);
            if (sl_tok_is(sl_peek(S), "[") || sl_tok_is(sl_peek(S), ":"))
                FAIL(S, sl_peek(S), "a struct's field is one value (no arrays, no semantics)");
            for (int i = 0; i < d->nfields; ++i)
                if (d->fname[i]->len == fn->len && strncmp(d->fname[i]->p, fn->p, (size_t)fn->len) == 0)
                    FAIL(S, fn, "field '%.*s' is declared twice", fn->len, fn->p);
            if (d->nfields == SL_MAX_FIELDS)
                FAIL(S, fn, "a struct of more than %d fields", SL_MAX_FIELDS);
            d->fname[d->nfields] = fn;
            d->fty[d->nfields++] = ft;
            if (accept(S, ";"))
                break;
            expect(S, ",");
        }
    }
    if (d->nfields == 0)
        FAIL(S, name, "struct '%.*s' has no fields", name->len, name->p);
    expect(S, ";");
    d->next = S->structs;
    S->structs = d;
}

/* The function form: somewhere outside braces and parentheses a type, a name and '('. */
static int is_function_start(struct sl *S)
{
    int depth = 0;
    for (int i = S->pos; i + 2 < S->toks.n; ++i) {
        const struct tok *t = &S->toks.v[i];
        if (sl_tok_is(t, "{") || sl_tok_is(t, "("))
            ++depth;
        else if (sl_tok_is(t, "}") || sl_tok_is(t, ")"))
            --depth;
        struct type ty;
        int so;
        if (depth == 0 && sl_type_of_name(t, &ty, &so) && t[1].k == K_ID && sl_tok_is(&t[2], "("))
            return 1;
    }
    return 0;
}

/* A file: function definitions and global declarations, or (no function) a body. */
struct stmt *sl_parse_program(struct sl *S, struct stmt *globals)
{
    if (!is_function_start(S)) {
        struct stmt *body = sl_new_stmt(S, S_BLOCK, sl_peek(S));
        while (sl_peek(S)->k != K_EOF)
            block_add(S, body, parse_statement(S, 1));
        return body;
    }
    struct func **tail = &S->funcs;
    while (*tail)
        tail = &(*tail)->next;
    while (sl_peek(S)->k != K_EOF) {
        const struct tok *start = sl_peek(S);
        if (accept(S, ";"))
            continue;
        if (sl_tok_is(start, "struct")) {
            parse_struct(S);
            continue;
        }
        if (sl_tok_is(start, "precision")) {
            /* precision mediump float; makes float binary16 in what follows (highp: float) */
            next(S);
            const struct tok *q = sl_peek(S);
            if (sl_tok_is(peek_at(S, 1), "float"))
                S->default_half = sl_tok_is(q, "mediump") || sl_tok_is(q, "lowp");
            while (sl_peek(S)->k != K_EOF && !accept(S, ";"))
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
        const struct tok *name = sl_peek(S);
        if (name->k != K_ID)
            FAIL(S, name, "expected a name, found %s", tok_desc(S, name));
        if (!sl_tok_is(peek_at(S, 1), "(")) {
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
        struct func *f = sl_arena_alloc(S, sizeof *f);
        f->name = name;
        f->ret = t;
        if (accept(S, "void")) {
            expect(S, ")");
        } else if (!accept(S, ")")) {
            for (;;) {
                struct type pt;
                int pc, mode = PM_IN;
                for (;;) {
                    /* in, out, inout (const and the precision are parse_decl_type's) */
                    if (accept(S, "out"))
                        mode = PM_OUT;
                    else if (accept(S, "inout"))
                        mode = PM_INOUT;
                    else if (!accept(S, "in"))
                        break;
                }
                const struct tok *pt0 = sl_peek(S);
                if (!parse_decl_type(S, &pt, &pc))
                    FAIL(S, pt0, "expected a parameter type, found %s", tok_desc(S, pt0));
                if (pt.b == B_VOID)
                    FAIL(S, pt0, "a parameter cannot be void");
                const struct tok *pn = sl_peek(S);
                if (sl_tok_is(pn, "*"))
                    FAIL(S, pn, "a pointer parameter: pointers are not accepted in a model");
                if (pn->k != K_ID)
                    FAIL(S, pn, "expected a parameter name, found %s", tok_desc(S, pn));
                next(S);
                struct expr *alen = NULL;
                if (accept(S, "[")) {
                    /* an array parameter (GLSL's const in vec3 v[4]): passed by value, its length a constant */
                    if (sl_tok_is(sl_peek(S), "]"))
                        FAIL(S, sl_peek(S), "an array parameter needs its length (%.*s[N])", pn->len, pn->p);
                    alen = parse_expr(S);
                    expect(S, "]");
                }
                if (sl_tok_is(sl_peek(S), ":"))
                    FAIL(S, sl_peek(S), "HLSL semantics (': NAME') are not supported on a model's parameters");
                if (f->nparams == SL_MAX_ARGS)
                    FAIL(S, pn, "more than %d parameters", SL_MAX_ARGS);
                f->parr[f->nparams] = alen;
                if (mode != PM_IN && pc)
                    FAIL(S, pt0, "an %s parameter cannot be const", mode == PM_OUT ? "out" : "inout");
                f->pty[f->nparams] = pt;
                f->pmode[f->nparams] = mode;
                f->pname[f->nparams++] = pn;
                if (accept(S, ")"))
                    break;
                expect(S, ",");
            }
        }
        if (accept(S, ";"))
            continue; /* a prototype */
        /* overloads differ in their parameters' types */
        for (struct func *g = S->funcs; g; g = g->next) {
            int same = g->name->len == name->len && strncmp(g->name->p, name->p, (size_t)name->len) == 0 &&
                       g->nparams == f->nparams;
            for (int i = 0; same && i < f->nparams; ++i)
                same = g->pty[i].b == f->pty[i].b && g->pty[i].n == f->pty[i].n && !g->parr[i] == !f->parr[i];
            if (same)
                FAIL(S, name, "function '%.*s' is defined twice with the same parameter types (line %d)", name->len,
                     name->p, g->name->line);
        }
        f->body = parse_block(S);
        f->close = &S->toks.v[S->pos - 1];
        *tail = f;
        tail = &f->next;
    }
    return NULL;
}
