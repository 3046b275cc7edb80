/* shaderlang_emit.c - the shader-language translator (shaderlang.c): constructors, calls, expressions and statements, emitted as C. */
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

/* ---- constructors, casts and calls --------------------------------------------------------- */

static int const_int(struct sl *S, struct expr *e, long *out);
static struct val val_float(void);

static int field_index(const struct sdef *d, const struct tok *f)
{
    for (int i = 0; i < d->nfields; ++i)
        if (d->fname[i]->len == f->len && strncmp(d->fname[i]->p, f->p, (size_t)f->len) == 0)
            return i;
    return -1;
}

/* The declarations of s's C names, set from v (of s's type). */
static void store_val(struct sl *S, struct sym *s, struct val v)
{
    if (s->t.b == B_STRUCT) {
        for (int i = 0; i < s->t.st->nfields; ++i)
            store_val(S, s->fields[i], v.f[i]);
    } else if (s->t.b == B_INT) {
        sl_out_line(S, "int %s = %s;", s->c[0], v.c[0]);
    } else if (s->t.b == B_BOOL) {
        sl_out_line(S, "REAL %s = (%s) ? RSPLAT(1.0) : RSPLAT(0.0);", s->c[0], v.c[0]);
    } else {
        for (int i = 0; i < s->t.n; ++i)
            sl_out_line(S, "REAL %s = %s;", s->c[i], v.c[i]);
    }
}

/* A value of type t that is zero in every component. */
static struct val zero_val(struct sl *S, struct type t)
{
    struct val v = { t, { NULL }, 1, NULL };
    if (t.b == B_STRUCT) {
        v.f = sl_arena_alloc(S, sizeof *v.f * (size_t)t.st->nfields);
        for (int i = 0; i < t.st->nfields; ++i)
            v.f[i] = zero_val(S, t.st->fty[i]);
        return v;
    }
    for (int i = 0; i < t.n; ++i)
        v.c[i] = t.b == B_INT || t.b == B_BOOL ? "0" : "RSPLAT(0.0)";
    return v;
}

static void assign_sym(struct sl *S, struct sym *s, const int *comp, int ncomp, struct val v, const char *pred,
                       const struct tok *where);

/* A whole struct assigned field by field (under pred). */
static void assign_struct(struct sl *S, struct sym *s, struct val v, const char *pred, const struct tok *where)
{
    static const int all[4] = { 0, 1, 2, 3 };
    for (int i = 0; i < s->t.st->nfields; ++i) {
        struct sym *f = s->fields[i];
        if (f->t.b == B_STRUCT)
            assign_struct(S, f, v.f[i], pred, where);
        else
            assign_sym(S, f, all, f->t.n, v.f[i], pred, where);
    }
}

/* What the left of an assignment (or an out argument) names: a variable, a struct's field (to
 * any depth), then maybe a swizzle: the sym and its components. */
static struct sym *lvalue(struct sl *S, struct expr *l, int *comp, int *ncomp, int *swizzled)
{
    *swizzled = 0;
    if (l->k == E_VAR) {
        struct sym *s = sl_lookup(S, l->t);
        if (!s)
            FAIL(S, l->t, "use of undeclared identifier '%.*s'", l->t->len, l->t->p);
        *ncomp = s->t.n;
        for (int i = 0; i < 4; ++i)
            comp[i] = i;
        return s;
    }
    if (l->k != E_SWZ)
        FAIL(S, l->t, "the left of an assignment must be a variable, its components, a field or an element");
    int inner;
    struct sym *b = lvalue(S, l->a, comp, ncomp, &inner);
    if (b->t.b == B_STRUCT && !inner) {
        int k = field_index(b->t.st, l->field);
        if (k < 0)
            FAIL(S, l->field, "%s has no field '%.*s'", sl_type_name(S, b->t), l->field->len, l->field->p);
        struct sym *f = b->fields[k];
        f->is_const = b->is_const;
        *ncomp = f->t.n;
        for (int i = 0; i < 4; ++i)
            comp[i] = i;
        return f;
    }
    if (inner)
        FAIL(S, l->t, "a swizzle of a swizzle on the left of an assignment");
    if (b->t.b != B_FLOAT || l->nswz == 0)
        FAIL(S, l->t, "a swizzle of a %s", sl_type_name(S, b->t));
    *ncomp = l->nswz;
    for (int i = 0; i < l->nswz; ++i) {
        comp[i] = l->swz[i];
        if (comp[i] >= b->t.n)
            FAIL(S, l->t, "component %c of a %s", "xyzw"[comp[i]], sl_type_name(S, b->t));
        for (int j = 0; j < i; ++j)
            if (comp[j] == comp[i])
                FAIL(S, l->t, "component %c is written twice", "xyzw"[comp[i]]);
    }
    *swizzled = 1;
    return b;
}

/* The variable an expression ends in (through fields and swizzles), or NULL. */
static const struct tok *root_name(struct expr *l)
{
    while (l->k == E_SWZ)
        l = l->a;
    return l->k == E_VAR ? l->t : NULL;
}

static const char *effective(struct sl *S, const char *pred);

/* The variable (and its components) an out or inout argument names. */
static struct sym *out_target(struct sl *S, struct expr *a, int *comp, int *ncomp)
{
    if (!root_name(a))
        FAIL(S, a->t, "an out or inout argument must be a variable or its components");
    int swz;
    struct sym *s = lvalue(S, a, comp, ncomp, &swz);
    if (s->is_const)
        FAIL(S, root_name(a), "'%.*s' is const: it cannot take an out or inout argument", root_name(a)->len,
             root_name(a)->p);
    return s;
}

/* How far an argument of type a is from a parameter of type p: 0 the same, 1 an int to a float,
 * 2 more for a scalar made a vector (HLSL's promotion), -1 not at all. */
static int conversion_cost(struct type a, struct type p, int mode)
{
    if (sl_same_type(a, p))
        return 0;
    if (mode != PM_IN || a.b == B_STRUCT || p.b == B_STRUCT)
        return -1;
    if (p.b == B_FLOAT && (a.b == B_INT || a.b == B_FLOAT) && (a.n == p.n || a.n == 1))
        return (a.b == B_INT) + 2 * (a.n != p.n);
    return -1;
}

/* A call of a function of the text: the overload whose parameters take the arguments with
 * the fewest conversions (a tie is an ambiguous call), inlined. */
static struct val call_user(struct sl *S, struct func *first, struct expr *e)
{
    struct val args[SL_MAX_ARGS];
    struct sym *arrs[SL_MAX_ARGS]; /* an argument naming an array (for an array parameter) */
    for (int i = 0; i < e->nargs; ++i) {
        struct sym *as = e->args[i]->k == E_VAR ? sl_lookup(S, e->args[i]->t) : NULL;
        arrs[i] = as && as->arr_n ? as : NULL;
        if (arrs[i]) {
            args[i] = val_float();
            args[i].t = as->t;
        } else {
            args[i] = sl_ev(S, e->args[i]);
        }
    }
    struct func *f = NULL;
    int best = -1, tie = 0, candidates = 0;
    for (struct func *g = first; g; g = g->next) {
        if (!(g->name->len == first->name->len && strncmp(g->name->p, first->name->p, (size_t)g->name->len) == 0))
            continue;
        ++candidates;
        if (g->nparams != e->nargs)
            continue;
        int cost = 0;
        for (int i = 0; i < e->nargs && cost >= 0; ++i) {
            int c = !arrs[i] != !g->parr[i] ? -1
                    : arrs[i] ? (sl_same_type(args[i].t, g->pty[i]) ? 0 : -1)
                              : conversion_cost(args[i].t, g->pty[i], g->pmode[i]);
            cost = c < 0 ? -1 : cost + c;
        }
        if (cost < 0)
            continue;
        if (best < 0 || cost < best) {
            best = cost;
            f = g;
            tie = 0;
        } else if (cost == best) {
            tie = 1;
        }
    }
    if (!f && candidates == 1)
        f = first; /* its own message: the count, or the argument that does not convert */
    if (!f) {
        const char *types = "";
        for (int i = 0; i < e->nargs; ++i)
            types = sl_sfmt(S, "%s%s%s", types, i ? ", " : "", sl_type_name(S, args[i].t));
        FAIL(S, e->t, "no function %.*s takes (%s)", first->name->len, first->name->p, types);
    }
    if (tie)
        FAIL(S, e->t, "the call of %.*s is ambiguous: two of its overloads take these arguments equally well",
             f->name->len, f->name->p);
    if (e->nargs != f->nparams)
        FAIL(S, e->t, "%.*s takes %d argument%s, not %d", f->name->len, f->name->p, f->nparams,
             f->nparams == 1 ? "" : "s", e->nargs);
    for (int i = 0; i < S->ninline; ++i)
        if (S->inlining[i] == f)
            FAIL(S, e->t, "%.*s calls itself: recursion is not supported", f->name->len, f->name->p);
    if (S->ninline >= SL_MAX_INLINE)
        FAIL(S, e->t, "calls nested more than %d deep", SL_MAX_INLINE);
    if (f->ret.b == B_BOOL)
        FAIL(S, f->name, "a helper function must return a number or a vector (this one returns %s)",
             sl_type_name(S, f->ret));
    if (f->ret.b != B_VOID && !sl_stmt_returns(f->body))
        FAIL(S, f->close, "%.*s can reach its end without returning a value", f->name->len, f->name->p);
    long alen[SL_MAX_ARGS] = { 0 };
    for (int i = 0; i < e->nargs; ++i) {
        if (f->parr[i] || arrs[i]) {
            /* an array passed by value: the same element type and length */
            if (!f->parr[i])
                FAIL(S, e->args[i]->t, "argument %d of %.*s is an array: it takes a %s", i + 1, f->name->len,
                     f->name->p, sl_type_name(S, f->pty[i]));
            if (f->pmode[i] != PM_IN)
                FAIL(S, f->pname[i], "an %s array parameter: array parameters are passed in only",
                     f->pmode[i] == PM_OUT ? "out" : "inout");
            if (!const_int(S, f->parr[i], &alen[i]) || alen[i] < 1 || alen[i] > SL_MAX_ARRAY)
                FAIL(S, f->parr[i]->t, "an array parameter's length is a constant integer from 1 to %d", SL_MAX_ARRAY);
            if (!arrs[i] || !sl_same_type(args[i].t, f->pty[i]) || arrs[i]->arr_n != alen[i])
                FAIL(S, e->args[i]->t, "argument %d of %.*s takes a %s[%ld]: pass an array of that type and length",
                     i + 1, f->name->len, f->name->p, sl_type_name(S, f->pty[i]), alen[i]);
            continue;
        }
        if (f->pmode[i] != PM_IN) {
            int comp[4], ncomp;
            out_target(S, e->args[i], comp, &ncomp);
            if (!sl_same_type(args[i].t, f->pty[i]))
                FAIL(S, e->args[i]->t, "argument %d of %.*s is %s: it takes a %s exactly", i + 1, f->name->len,
                     f->name->p, f->pmode[i] == PM_OUT ? "out" : "inout", sl_type_name(S, f->pty[i]));
            /* a copy in: the callee's writes must not be read through the caller's name */
            if (args[i].t.b != B_STRUCT)
                args[i] = sl_temp_val(S, args[i]);
        } else {
            args[i] = sl_convert(S, args[i], f->pty[i], e->args[i]->t,
                                 sl_sfmt(S, "argument %d of %.*s", i + 1, f->name->len, f->name->p));
        }
    }
    int saved_line = S->stmt_line;
    struct scope *saved_scope = S->scope;
    struct fnctx *saved_fn = S->fn;
    struct fnctx fc = { .ret = f->ret };
    int k = ++S->ntemp;
    if (f->ret.b == B_VOID) {
        /* nothing returned */
    } else if (f->ret.b == B_STRUCT) {
        static const struct tok ret_tok = { K_ID, 0, 0, "ret", 3 };
        fc.ret_sym = sl_declare(S, S->scope, &ret_tok, f->ret);
        store_val(S, fc.ret_sym, zero_val(S, f->ret));
    } else if (f->ret.b == B_INT) {
        fc.ret_c[0] = sl_sfmt(S, "sl_r%d", k);
        sl_out_line(S, "int %s = 0;", fc.ret_c[0]);
    } else {
        for (int i = 0; i < f->ret.n; ++i) {
            fc.ret_c[i] = f->ret.n == 1 ? sl_sfmt(S, "sl_r%d", k) : sl_sfmt(S, "sl_r%d_%c", k, "xyzw"[i]);
            sl_out_line(S, "REAL %s = RSPLAT(0.0);", fc.ret_c[i]);
        }
    }
    S->scope = S->globals;
    sl_push_scope(S, 1);
    S->stmt_line = f->name->line;
    struct sym *psym[SL_MAX_ARGS];
    for (int i = 0; i < f->nparams; ++i) {
        if (f->parr[i]) {
            /* a copy of each element, so the callee's writes stay its own */
            struct sym *p = sl_declare_array(S, S->scope, f->pname[i], f->pty[i], (int)alen[i]);
            psym[i] = p;
            for (long k = 0; k < alen[i]; ++k)
                for (int c = 0; c < f->pty[i].n; ++c)
                    sl_out_line(S, "REAL %s = %s;", p->elem[k]->c[c], arrs[i]->elem[k]->c[c]);
            continue;
        }
        struct sym *p = sl_declare(S, S->scope, f->pname[i], f->pty[i]);
        psym[i] = p;
        if (f->pty[i].b == B_STRUCT) {
            store_val(S, p, f->pmode[i] == PM_OUT ? zero_val(S, f->pty[i]) : args[i]);
            continue;
        }
        for (int c = 0; c < f->pty[i].n; ++c) {
            const char *init = f->pmode[i] == PM_OUT ? (f->pty[i].b == B_INT ? "0" : "RSPLAT(0.0)")
                               : f->pty[i].b == B_BOOL ? sl_sfmt(S, "(%s) ? RSPLAT(1.0) : RSPLAT(0.0)", args[i].c[c])
                                                       : args[i].c[c];
            sl_out_line(S, "%s %s = %s;", f->pty[i].b == B_INT ? "int" : "REAL", p->c[c], init);
        }
    }
    const char *saved_pred = S->cur_pred;
    S->cur_pred = NULL;
    S->inlining[S->ninline++] = f;
    S->fn = &fc;
    /* the function's statements are its own: no loop of the caller's to break out of */
    struct loopctx *saved_loops = S->loops;
    S->loops = NULL;
    sl_emit_block(S, f->body, NULL, 0);
    S->loops = saved_loops;
    S->fn = saved_fn;
    --S->ninline;
    S->scope = saved_scope;
    S->stmt_line = saved_line;
    S->cur_pred = saved_pred;
    /* out and inout: the values written back, under the calling statement's condition */
    for (int i = 0; i < f->nparams; ++i)
        if (f->pmode[i] != PM_IN) {
            int comp[4], ncomp;
            struct sym *dst = out_target(S, e->args[i], comp, &ncomp);
            struct val v = sl_sym_val(psym[i]);
            if (dst->t.b == B_STRUCT) {
                assign_struct(S, dst, v, S->cur_pred, e->args[i]->t);
                continue;
            }
            if (psym[i]->t.b == B_BOOL)
                v.c[0] = sl_sfmt(S, "(%s != RSPLAT(0.0))", psym[i]->c[0]);
            assign_sym(S, dst, comp, ncomp, v, S->cur_pred, e->args[i]->t);
        }
    if (f->ret.b == B_STRUCT)
        return sl_sym_val(fc.ret_sym);
    struct val r = { f->ret, { NULL }, f->ret.b == B_INT, NULL };
    for (int i = 0; i < f->ret.n && f->ret.b != B_VOID; ++i)
        r.c[i] = fc.ret_c[i];
    return r;
}

static struct val construct(struct sl *S, struct type t, struct expr *e)
{
    struct val r = { t, { NULL }, 1, NULL };
    if (sl_is_matrix(t)) {
        struct val parts[SL_MAX_ARGS];
        if (e->nargs == 0)
            FAIL(S, e->t, "%s() needs its values", sl_type_name(S, t));
        for (int i = 0; i < e->nargs; ++i)
            parts[i] = sl_ev(S, e->args[i]);
        return sl_matrix_construct(S, t, parts, e->nargs, e->t);
    }
    if (t.b == B_STRUCT) {
        /* NAME(a, b, ...) or { a, b, ... }: one value per field, in order */
        const struct sdef *d = t.st;
        if (e->nargs != d->nfields)
            FAIL(S, e->t, "%.*s has %d field%s, %d value%s given", d->name->len, d->name->p, d->nfields,
                 d->nfields == 1 ? "" : "s", e->nargs, e->nargs == 1 ? "" : "s");
        r.f = sl_arena_alloc(S, sizeof *r.f * (size_t)d->nfields);
        for (int i = 0; i < d->nfields; ++i)
            r.f[i] = sl_temp_val(S, sl_convert(S, sl_ev(S, e->args[i]), d->fty[i], e->args[i]->t,
                                               sl_sfmt(S, "field '%.*s'", d->fname[i]->len, d->fname[i]->p)));
        return r;
    }
    if (t.b == B_VOID)
        FAIL(S, e->t, "void is not a value");
    if (t.b == B_BOOL)
        FAIL(S, e->t, "bool(...) is not supported (compare with != 0.0)");
    if (t.b == B_INT) {
        if (e->nargs != 1)
            FAIL(S, e->t, "int(...) takes one value");
        struct expr *x = e->args[0];
        if (x->k == E_FLT) {
            r.c[0] = sl_sfmt(S, "(int)(%s)", sl_float_literal(S, x->t));
            return r;
        }
        struct val v = sl_ev(S, x);
        if (v.t.b == B_INT)
            return v;
        if (v.t.b == B_FLOAT && v.t.n == 1) {
            /* a value that may differ between lanes: its integer part, kept as a float (an int
               of C is the same in every lane) */
            r.t = (struct type){ .b = B_FLOAT, .n = 1 };
            r.uniform = 0;
            r.c[0] = sl_sfmt(S, "trunc(%s)", v.c[0]);
            return r;
        }
        FAIL(S, x->t, "int of a %s: a number is expected", sl_type_name(S, v.t));
    }
    struct val parts[SL_MAX_ARGS];
    int total = 0;
    for (int i = 0; i < e->nargs; ++i) {
        parts[i] = sl_ev(S, e->args[i]);
        if (parts[i].t.b == B_BOOL) {
            parts[i] = (struct val){ .t = { .b = B_FLOAT, .n = 1 },
                                     .c = { sl_sfmt(S, "((%s) ? RSPLAT(1.0) : RSPLAT(0.0))", parts[i].c[0]) },
                                     .uniform = parts[i].uniform };
        }
        parts[i] = sl_to_float(S, parts[i], e->args[i]->t);
        /* half3(x): each value becomes binary16; vec3(x), float3(x): the values' precision */
        if (t.half == 1 && parts[i].t.half != 1)
            parts[i] = sl_round_half(S, parts[i]);
        if (t.half != 1)
            r.t.half = i == 0 ? parts[i].t.half : sl_half_of(r.t.half, parts[i].t.half);
        total += parts[i].t.n;
    }
    r.uniform = 0;
    if (e->nargs == 1 && parts[0].t.n == 1) {
        const char *s = t.n > 1 ? sl_temp_real(S, parts[0].c[0]) : parts[0].c[0];
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
        FAIL(S, e->t, "%s(...) needs %d component%s, these give %d", sl_type_name(S, t), t.n, t.n == 1 ? "" : "s", total);
    int k = 0;
    for (int i = 0; i < e->nargs; ++i)
        for (int j = 0; j < parts[i].t.n; ++j)
            r.c[k++] = parts[i].c[j];
    return r;
}

struct func *sl_find_func(struct sl *S, const struct tok *t)
{
    for (struct func *f = S->funcs; f; f = f->next)
        if (f->name->len == t->len && strncmp(f->name->p, t->p, (size_t)t->len) == 0)
            return f;
    return NULL;
}

static __attribute__((noreturn)) void fail_unknown(struct sl *S, const struct tok *t, const char *what)
{
    S->unknown_name = 1;
    FAIL(S, t, "use of undeclared %s '%.*s'", what, t->len, t->p);
}

/* ---- expressions -------------------------------------------------------------------------- */

/* A value of a float kind with no components yet (what each kind of expression starts from). */
static struct val val_float(void)
{
    struct val r = { .t = { .b = B_FLOAT, .n = 1 }, .uniform = 1 };
    return r;
}

static struct val ev_int(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    r.t = (struct type){ .b = B_INT, .n = 1 };
    if (e->op == 1) {
        r.c[0] = "1";
        return r;
    }
    int len = e->t->len;
    while (len > 0 && (e->t->p[len - 1] == 'u' || e->t->p[len - 1] == 'U'))
        --len;
    if (len > 9)
        FAIL(S, e->t, "the integer %.*s is too large (write it with a decimal point)", e->t->len, e->t->p);
    r.c[0] = sl_sfmt(S, "%ld", strtol(sl_sfmt(S, "%.*s", len, e->t->p), NULL, 10));
    return r;
}

static struct val ev_var(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    struct sym *s = sl_lookup(S, e->t);
    if (!s)
        fail_unknown(S, e->t, "identifier");
    if (s->arr_n)
        FAIL(S, e->t, "'%.*s' is an array: take one of its elements (%.*s[0])", e->t->len, e->t->p, e->t->len, e->t->p);
    if (s->t.b == B_BOOL) {
        r.t = s->t;
        r.c[0] = sl_sfmt(S, "(%s != RSPLAT(0.0))", s->c[0]);
        r.uniform = 0;
        return r;
    }
    if (s->has_value) {
        r.t = s->t;
        r.c[0] = sl_sfmt(S, "%ld", s->value);
        return r;
    }
    return sl_sym_val(s);
}

static struct val ev_swizzle(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    struct val v = sl_ev(S, e->a);
    if (v.t.b == B_STRUCT) {
        int k = field_index(v.t.st, e->field);
        if (k < 0)
            FAIL(S, e->field, "%s has no field '%.*s'", sl_type_name(S, v.t), e->field->len, e->field->p);
        return v.f[k];
    }
    if (v.t.b != B_FLOAT)
        FAIL(S, e->t, "a swizzle of a %s", sl_type_name(S, v.t));
    if (e->nswz == 0)
        FAIL(S, e->field, "'%.*s' is not a swizzle (1 to 4 of x y z w, r g b a or s t p q)", e->field->len,
             e->field->p);
    for (int i = 0; i < e->nswz; ++i)
        if (e->swz[i] >= v.t.n)
            FAIL(S, e->t, "component %c of a %s", "xyzw"[e->swz[i]], sl_type_name(S, v.t));
    r.t = (struct type){ .b = B_FLOAT, .n = e->nswz, .half = v.t.half };
    r.uniform = v.uniform;
    for (int i = 0; i < e->nswz; ++i)
        r.c[i] = v.c[e->swz[i]];
    return r;
}

static struct val ev_unary(struct sl *S, struct expr *e)
{
    struct val v = sl_ev(S, e->a);
    if (e->op == '!') {
        if (v.t.b != B_BOOL)
            FAIL(S, e->t, "'!' of a %s (a condition is expected)", sl_type_name(S, v.t));
        v.c[0] = sl_sfmt(S, "(!%s)", v.c[0]);
        return v;
    }
    if (v.t.b != B_FLOAT && v.t.b != B_INT)
        FAIL(S, e->t, "'%c' of a %s", e->op == 'u' ? '-' : '+', sl_type_name(S, v.t));
    if (e->op == 'p')
        return v;
    for (int i = 0; i < v.t.n; ++i)
        v.c[i] = sl_sfmt(S, "(-%s)", v.c[i]);
    return v;
}

static struct val ev_binary(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    struct val a = sl_ev(S, e->a), b = sl_ev(S, e->b);
    int op = e->op;
    if (op == 'A' || op == 'O') {
        if (a.t.b != B_BOOL || b.t.b != B_BOOL)
            FAIL(S, e->t, "'%s' needs conditions, not %s and %s", sl_op_text(op), sl_type_name(S, a.t), sl_type_name(S, b.t));
        r.t = a.t;
        r.uniform = a.uniform && b.uniform;
        r.c[0] = sl_sfmt(S, "(%s %s %s)", a.c[0], sl_op_text(op), b.c[0]);
        return r;
    }
    if (strchr("<>LGEN", op)) {
        if (a.t.b == B_BOOL || b.t.b == B_BOOL)
            FAIL(S, e->t, "'%s' of conditions: combine them with && || !", sl_op_text(op));
        if (a.t.n > 1 || b.t.n > 1)
            FAIL(S, e->t, "'%s' of vectors: compare their components", sl_op_text(op));
        if (a.t.b != b.t.b) {
            a = sl_to_float(S, a, e->t);
            b = sl_to_float(S, b, e->t);
        }
        r.t = (struct type){ .b = B_BOOL, .n = 1 };
        r.uniform = a.uniform && b.uniform;
        r.c[0] = sl_sfmt(S, "(%s %s %s)", a.c[0], sl_op_text(op), b.c[0]);
        return r;
    }
    return sl_arith(S, op, a, b, e->t);
}

static struct val ev_ternary(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    struct val c = sl_ev(S, e->a);
    if (c.t.b != B_BOOL || c.t.n != 1)
        FAIL(S, e->a->t, "the condition of ?: is a %s, not a comparison", sl_type_name(S, c.t));
    struct val a = sl_ev(S, e->b), b = sl_ev(S, e->c);
    if (a.t.b == B_BOOL || b.t.b == B_BOOL)
        FAIL(S, e->t, "?: of conditions: combine them with && || !");
    if (a.t.b == B_INT && b.t.b == B_INT && c.uniform) {
        r.t = a.t;
        r.c[0] = sl_sfmt(S, "(%s ? %s : %s)", c.c[0], a.c[0], b.c[0]);
        return r;
    }
    a = sl_to_float(S, a, e->b->t);
    b = sl_to_float(S, b, e->c->t);
    int n = a.t.n > b.t.n ? a.t.n : b.t.n;
    if (a.t.n != b.t.n && a.t.n != 1 && b.t.n != 1)
        FAIL(S, e->t, "?: between a %s and a %s", sl_type_name(S, a.t), sl_type_name(S, b.t));
    int h = sl_half_of(a.t.half, b.t.half);
    if (h == 1) {
        a = a.t.half == 1 ? a : sl_round_half(S, a);
        b = b.t.half == 1 ? b : sl_round_half(S, b);
    }
    if (n > 1)
        c.c[0] = sl_temp_cond(S, c.c[0], c.uniform);
    r.t = (struct type){ .b = B_FLOAT, .n = n, .half = h };
    r.uniform = 0;
    for (int i = 0; i < n; ++i)
        r.c[i] = sl_sfmt(S, "(%s ? %s : %s)", c.c[0], a.c[a.t.n == 1 ? 0 : i], b.c[b.t.n == 1 ? 0 : i]);
    return n > 1 ? sl_temp_val(S, r) : r;
}

/* ---- arrays and indexing ---------------------------------------------------------------- */

/* An index: constant (*k, returns 1; checked against count) or an int of C (*idx). */
static int index_of(struct sl *S, struct expr *x, int count, const char *what, long *k, const char **idx)
{
    if (const_int(S, x, k)) {
        if (*k < 0 || *k >= count)
            FAIL(S, x->t, "index %ld is out of range: %s has %d element%s (0 to %d)", *k, what, count,
                 count == 1 ? "" : "s", count - 1);
        return 1;
    }
    struct val v = sl_ev(S, x);
    if (v.t.b != B_INT)
        FAIL(S, x->t, "an index is an int, not a %s", sl_type_name(S, v.t));
    *idx = sl_temp_val(S, v).c[0];
    return 0;
}

/* "I == 0 ? e0 : I == 1 ? e1 : ... : NaN": an element chosen by an int that is known only when
 * the model runs (the same in every lane); out of range, NaN, which the accuracy figures show. */
static const char *select_by(struct sl *S, const char *idx, const char **elems, int count)
{
    const char *r = "(RSPLAT(0.0) / RSPLAT(0.0))";
    for (int j = count - 1; j >= 0; --j)
        r = sl_sfmt(S, "((%s == %d) ? %s : %s)", idx, j, elems[j], r);
    return r;
}

static struct val ev_index(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    r.uniform = 0;
    struct sym *s = e->a->k == E_VAR ? sl_lookup(S, e->a->t) : NULL;
    long k = 0;
    const char *idx = NULL;
    if (s && s->arr_n) {
        const char *what = sl_sfmt(S, "'%.*s'", e->a->t->len, e->a->t->p);
        if (index_of(S, e->b, s->arr_n, what, &k, &idx))
            return sl_sym_val(s->elem[k]);
        r.t = s->t;
        for (int i = 0; i < s->t.n; ++i) {
            const char **col = sl_arena_alloc(S, sizeof *col * (size_t)s->arr_n);
            for (int j = 0; j < s->arr_n; ++j)
                col[j] = s->elem[j]->c[i];
            r.c[i] = select_by(S, idx, col, s->arr_n);
        }
        return r.t.n > 1 ? sl_temp_val(S, r) : r;
    }
    struct val v = sl_ev(S, e->a);
    if (sl_is_matrix(v.t)) {
        /* a column (GLSL) or a row (HLSL) */
        int n = v.t.st->nfields;
        if (index_of(S, e->b, n, sl_sfmt(S, "a %s", sl_type_name(S, v.t)), &k, &idx))
            return v.f[k];
        v = sl_temp_val(S, v);
        r.t = (struct type){ .b = B_FLOAT, .n = n };
        for (int i = 0; i < n; ++i) {
            const char *col[4];
            for (int j = 0; j < n; ++j)
                col[j] = v.f[j].c[i];
            r.c[i] = select_by(S, idx, col, n);
        }
        return sl_temp_val(S, r);
    }
    if (v.t.b != B_FLOAT || v.t.n < 2)
        FAIL(S, e->t, "indexing a %s (a vector or an array is indexed)", sl_type_name(S, v.t));
    r.t.half = v.t.half;
    if (index_of(S, e->b, v.t.n, sl_sfmt(S, "a %s", sl_type_name(S, v.t)), &k, &idx)) {
        r.c[0] = v.c[k];
        return r;
    }
    v = sl_temp_val(S, v);
    r.c[0] = select_by(S, idx, v.c, v.t.n);
    return r;
}

/* A call: a constructor or cast, a function of the text, or a built-in. */
static struct val ev_call(struct sl *S, struct expr *e)
{
    struct type t;
    int so;
    if (e->has_ctor)
        return construct(S, e->ctor, e);
    if (sl_type_of_name(e->t, &t, &so))
        return construct(S, t, e);
    const struct sdef *sd = sl_find_struct(S, e->t);
    if (sd)
        return construct(S, (struct type){ .b = B_STRUCT, .n = 1, .st = sd }, e);
    struct func *f = sl_find_func(S, e->t);
    if (f)
        return call_user(S, f, e);
    if (sl_tok_is(e->t, "mul") || sl_tok_is(e->t, "transpose")) {
        int two = sl_tok_is(e->t, "mul");
        if (e->nargs != (two ? 2 : 1))
            FAIL(S, e->t, "%s takes %d argument%s, not %d", two ? "mul" : "transpose", two ? 2 : 1, two ? "s" : "",
                 e->nargs);
        struct val a = sl_ev(S, e->args[0]);
        if (!two)
            return sl_matrix_transpose(S, a, e->t);
        struct val b = sl_ev(S, e->args[1]);
        if (sl_is_matrix(a.t) || sl_is_matrix(b.t))
            return sl_matrix_mul(S, a, b, e->t);
        /* HLSL's mul of vectors is their dot product; of numbers, the product */
        if (a.t.b == B_FLOAT && b.t.b == B_FLOAT && a.t.n > 1 && a.t.n == b.t.n) {
            a = sl_temp_val(S, a);
            b = sl_temp_val(S, b);
            const char *d = sl_sfmt(S, "%s * %s", a.c[0], b.c[0]);
            for (int i = 1; i < a.t.n; ++i)
                d = sl_sfmt(S, "%s + %s * %s", d, a.c[i], b.c[i]);
            struct val r = val_float();
            r.uniform = 0;
            r.c[0] = sl_sfmt(S, "(%s)", d);
            return r;
        }
        return sl_arith(S, '*', a, b, e->t);
    }
    const struct builtin *bi = sl_find_builtin(e->t);
    if (bi)
        return sl_call_builtin(S, bi, e);
    S->unknown_name = 1;
    FAIL(S, e->t, "use of undeclared function '%.*s' (a model calls only its own functions and the math "
         "built-ins of docs/user-models.md)", e->t->len, e->t->p);
}

struct val sl_ev(struct sl *S, struct expr *e)
{
    struct val r = val_float();
    switch (e->k) {
    case E_FLT:
        r.c[0] = sl_sfmt(S, "RSPLAT(%s)", sl_float_literal(S, e->t));
        r.t.half = 2; /* a literal takes the precision of what it meets */
        if (e->t->p[e->t->len - 1] == 'h' || e->t->p[e->t->len - 1] == 'H')
            r = sl_round_half(S, r); /* HLSL's 0.1h is a half constant, even where it meets a float */
        return r;
    case E_INT:
        return ev_int(S, e);
    case E_BOOL:
        r.t = (struct type){ .b = B_BOOL, .n = 1 };
        r.c[0] = sl_tok_is(e->t, "true") ? "1" : "0";
        return r;
    case E_VAR:
        return ev_var(S, e);
    case E_SWZ:
        return ev_swizzle(S, e);
    case E_UN:
        return ev_unary(S, e);
    case E_BIN:
        return ev_binary(S, e);
    case E_TER:
        return ev_ternary(S, e);
    case E_CALL:
        return ev_call(S, e);
    case E_IDX:
        return ev_index(S, e);
    case E_ARR:
        FAIL(S, e->t, "a list of values is an array's initialiser (TYPE NAME[N] = ...;), not a value");
    }
    FAIL(S, e->t, "internal: unknown expression");
}

/* ---- statements -------------------------------------------------------------------------- */

/* A break or continue that leaves s's enclosing switch (not one of a loop or switch inside s). */
static int leaves_switch(const struct stmt *s)
{
    if (!s)
        return 0;
    switch (s->k) {
    case S_BREAK:
    case S_CONTINUE: return 1;
    case S_BLOCK:
        for (int i = 0; i < s->n; ++i)
            if (leaves_switch(s->items[i]))
                return 1;
        return 0;
    case S_IF: return leaves_switch(s->s1) || leaves_switch(s->s2);
    default: return 0;
    }
}

int sl_stmt_returns(const struct stmt *s)
{
    if (!s)
        return 0;
    switch (s->k) {
    case S_RET: return 1;
    case S_SWITCH: {
        /* every way in ends in a return: a default label, nothing that leaves the switch, and a
           last statement that returns (the sections fall through to it) */
        const struct stmt *b = s->s1;
        int has_default = 0;
        for (int i = 0; i < b->n; ++i)
            has_default |= b->items[i]->k == S_CASE && !b->items[i]->e;
        return has_default && b->n > 0 && !leaves_switch(b) && sl_stmt_returns(b->items[b->n - 1]);
    }
    case S_BLOCK:
        for (int i = 0; i < s->n; ++i)
            if (sl_stmt_returns(s->items[i]))
                return 1;
        return 0;
    case S_IF: return s->s2 && sl_stmt_returns(s->s1) && sl_stmt_returns(s->s2);
    default: return 0;
    }
}

/* The flag of a break or continue as a condition: an int as it is, a REAL mask compared. */
static const char *flag_cond(struct sl *S, const char *var, int is_int)
{
    return is_int ? var : sl_sfmt(S, "(%s != RSPLAT(0.0))", var);
}

/* "pred and the lane still runs" (has not returned, broken out of or continued past any loop or
 * switch it is in), or NULL for every lane. */
static const char *effective(struct sl *S, const char *pred)
{
    const char *live = S->fn->live;
    const char *r = pred;
    if (live)
        r = r ? sl_sfmt(S, "(%s && %s)", r, live) : live;
    for (const struct loopctx *L = S->loops; L; L = L->up) {
        const char *f[4] = { L->brk_int, L->cont_int, L->brk_real, L->cont_real };
        for (int i = 0; i < 4; ++i)
            if (f[i]) {
                const char *c = flag_cond(S, f[i], i < 2);
                r = r ? sl_sfmt(S, "(%s && %s)", r, c) : c;
            }
    }
    return r;
}

/* break (is_continue 0) or continue under pred: the lanes where it runs leave the innermost
 * loop or switch (continue: the rest of the innermost loop's iteration). Its flag is made
 * where it is first needed (the translated code is one straight block, so it is seen after). */
static void emit_break(struct sl *S, struct stmt *st, const char *pred, int is_continue)
{
    struct loopctx *L = S->loops;
    while (is_continue && L && L->is_switch)
        L = L->up;
    if (!L)
        FAIL(S, st->t, "'%s' outside a %s", is_continue ? "continue" : "break", is_continue ? "loop" : "loop or switch");
    const char *E = effective(S, pred);
    int uniform = !E || !strstr(E, "RSPLAT");
    const char **flag = is_continue ? (uniform ? &L->cont_int : &L->cont_real) : (uniform ? &L->brk_int : &L->brk_real);
    if (!*flag) {
        *flag = sl_sfmt(S, uniform ? "sl_bk%d" : "sl_k%d", ++S->ntemp);
        sl_out_line(S, uniform ? "int %s = 1;" : "REAL %s = RSPLAT(1.0);", *flag);
    }
    const char *off = uniform ? "0" : "RSPLAT(0.0)";
    if (E)
        sl_out_line(S, "%s = (%s) ? %s : %s;", *flag, E, off, *flag);
    else
        sl_out_line(S, "%s = %s;", *flag, off);
}

/* A new iteration of loop L: no lane has continued past it yet. */
static void loop_iteration(struct sl *S, const struct loopctx *L)
{
    if (L->cont_int)
        sl_out_line(S, "%s = 1;", L->cont_int);
    if (L->cont_real)
        sl_out_line(S, "%s = RSPLAT(1.0);", L->cont_real);
}

static const char *and_cond(struct sl *S, const char *a, const char *b)
{
    if (!a)
        return b;
    return sl_sfmt(S, "(%s && %s)", a, b);
}

/* A float variable a while/do loop writes (emit_while makes it NaN where the loop did not end). */
static void loop_note(struct sl *S, struct sym *s)
{
    for (int i = 0; i < S->nloop_syms; ++i)
        if (S->loop_syms[i] == s)
            return;
    if (S->nloop_syms == S->loop_syms_cap) {
        int cap = S->loop_syms_cap ? 2 * S->loop_syms_cap : 16;
        struct sym **v = sl_arena_alloc(S, sizeof *v * (size_t)cap);
        if (S->nloop_syms)
            memcpy(v, S->loop_syms, sizeof *v * (size_t)S->nloop_syms);
        S->loop_syms = v;
        S->loop_syms_cap = cap;
    }
    S->loop_syms[S->nloop_syms++] = s;
}

static void assign_sym(struct sl *S, struct sym *s, const int *comp, int ncomp, struct val v, const char *pred,
                       const struct tok *where)
{
    const char *E = effective(S, pred);
    if (S->loop_syms && s->t.b == B_FLOAT)
        loop_note(S, s);
    if (s->t.b == B_INT) {
        if (E && !strstr(E, "RSPLAT")) {
            /* a condition the same in every lane (ints only): the int may follow it */
            sl_out_line(S, "%s = (%s) ? %s : %s;", s->c[0], E, v.c[0], s->c[0]);
            return;
        }
        if (E)
            FAIL(S, where, "the int '%s' is assigned under a condition: make it a float", sl_sfmt(S, "%.*s", s->len, s->name));
        sl_out_line(S, "%s = %s;", s->c[0], v.c[0]);
        return;
    }
    if (s->t.b == B_BOOL) {
        const char *m = sl_sfmt(S, "((%s) ? RSPLAT(1.0) : RSPLAT(0.0))", v.c[0]);
        if (E)
            sl_out_line(S, "%s = (%s) ? %s : %s;", s->c[0], E, m, s->c[0]);
        else
            sl_out_line(S, "%s = %s;", s->c[0], m);
        return;
    }
    /* A component read on the right may be written on the left: read them all first. */
    if (ncomp > 1)
        for (int i = 0; i < ncomp; ++i)
            for (int j = 0; j < s->t.n; ++j)
                if (strstr(v.c[i], s->c[j]))
                    v.c[i] = sl_temp_real(S, sl_sfmt(S, "(%s)", v.c[i]));
    if (E && ncomp > 1)
        E = sl_temp_cond(S, E, 0);
    for (int i = 0; i < ncomp; ++i) {
        const char *dst = s->c[comp[i]];
        if (E)
            sl_out_line(S, "%s = %s ? %s : %s;", dst, E, v.c[i], dst);
        else
            sl_out_line(S, "%s = %s;", dst, v.c[i]);
    }
}

static void emit_array_decl(struct sl *S, struct stmt *d)
{
    struct type t = d->ty;
    if (t.b != B_FLOAT)
        FAIL(S, d->name, "an array of %s: arrays hold floats or vectors", sl_type_name(S, t));
    long n = -1, m;
    if (d->arr_len) {
        if (!const_int(S, d->arr_len, &n))
            FAIL(S, d->arr_len->t, "an array's length is a constant integer");
        if (n < 1 || n > SL_MAX_ARRAY)
            FAIL(S, d->arr_len->t, "an array of %ld elements (1 to %d are accepted)", n, SL_MAX_ARRAY);
    }
    struct expr *init = d->e;
    if (init && init->k != E_ARR)
        FAIL(S, init->t, "an array is set from a list of values ({ a, b } or %s[N](a, b))", sl_type_name(S, t));
    if (init && init->has_ctor && (init->ctor.b != t.b || init->ctor.n != t.n))
        FAIL(S, init->t, "an array of %s set from values of %s[]", sl_type_name(S, t), sl_type_name(S, init->ctor));
    if (init && init->a && (!const_int(S, init->a, &m) || m != init->nargs))
        FAIL(S, init->a->t, "the constructor's length is not the count of its values (%d)", init->nargs);
    if (n < 0) {
        if (!init)
            FAIL(S, d->name, "an array without a length needs its values");
        n = init->nargs;
    }
    if (init && init->nargs != n)
        FAIL(S, init->t, "%d value%s for an array of %ld", init->nargs, init->nargs == 1 ? "" : "s", n);
    struct val *v = sl_arena_alloc(S, sizeof *v * (size_t)n);
    for (long k = 0; k < n; ++k) {
        if (init) {
            v[k] = sl_convert(S, sl_ev(S, init->args[k]), t, init->args[k]->t,
                              sl_sfmt(S, "element %ld of '%.*s'", k, d->name->len, d->name->p));
        } else {
            v[k].t = t;
            for (int i = 0; i < t.n; ++i)
                v[k].c[i] = "RSPLAT(0.0)";
        }
    }
    struct sym *s = sl_declare_array(S, S->scope, d->name, t, (int)n);
    s->is_const = d->is_const;
    for (long k = 0; k < n; ++k) {
        s->elem[k]->is_const = d->is_const;
        for (int i = 0; i < t.n; ++i)
            sl_out_line(S, "REAL %s = %s;", s->elem[k]->c[i], v[k].c[i]);
    }
}

/* An assignment to an element of an array or a component of a vector by index (a[i] = v,
 * a[i].x += v, v[2] = x): with an index known only when the model runs, every element is
 * assigned where the index is its own. */
static void emit_assign_indexed(struct sl *S, struct stmt *st, const char *pred)
{
    struct expr *l = st->lhs;
    struct expr *ix = l->k == E_IDX ? l : l->a;
    if (ix->a->k != E_VAR)
        FAIL(S, ix->t, "the left of an assignment must be a variable, its components or an element");
    struct sym *s = sl_lookup(S, ix->a->t);
    if (!s)
        fail_unknown(S, ix->a->t, "identifier");
    if (s->is_const)
        FAIL(S, ix->a->t, "'%.*s' is const", ix->a->t->len, ix->a->t->p);
    struct sym **els = s->arr_n ? s->elem : sl_is_matrix(s->t) ? s->fields : NULL;
    int nels = s->arr_n ? s->arr_n : sl_is_matrix(s->t) ? s->t.st->nfields : 0;
    if (!els && (s->t.b != B_FLOAT || s->t.n < 2))
        FAIL(S, ix->t, "indexing a %s (a vector or an array is indexed)", sl_type_name(S, s->t));
    if (!els && l->k == E_SWZ)
        FAIL(S, l->t, "a swizzle of one component");
    struct val rhs = sl_ev(S, st->e);
    int count = els ? nels : s->t.n;
    long k = 0;
    const char *idx = NULL;
    int fixed = index_of(S, ix->b, count, sl_sfmt(S, "'%.*s'", ix->a->t->len, ix->a->t->p), &k, &idx);
    if (!fixed)
        rhs = sl_temp_val(S, rhs);
    for (int j = fixed ? (int)k : 0; j < (fixed ? (int)k + 1 : count); ++j) {
        struct sym *ts = els ? els[j] : s;
        int comp[4] = { 0, 1, 2, 3 }, ncomp = els ? ts->t.n : 1;
        if (!els)
            comp[0] = j;
        if (l->k == E_SWZ) {
            ncomp = l->nswz;
            for (int i = 0; i < ncomp; ++i) {
                comp[i] = l->swz[i];
                if (comp[i] >= ts->t.n)
                    FAIL(S, l->t, "component %c of a %s", "xyzw"[comp[i]], sl_type_name(S, ts->t));
            }
        }
        struct type target = { .b = B_FLOAT, .n = ncomp };
        struct val v = rhs;
        if (st->op != '=') {
            struct val cur = sl_sym_val(ts), part = cur;
            part.t = target;
            for (int i = 0; i < ncomp; ++i)
                part.c[i] = cur.c[comp[i]];
            v = sl_arith(S, st->op, part, rhs, st->t);
        }
        v = sl_convert(S, v, target, st->e->t, sl_sfmt(S, "'%.*s[%d]'", ix->a->t->len, ix->a->t->p, j));
        const char *p = fixed ? pred : and_cond(S, pred, sl_sfmt(S, "(%s == %d)", idx, j));
        assign_sym(S, ts, comp, ncomp, v, p, st->t);
    }
}

static void emit_decl(struct sl *S, struct stmt *d)
{
    struct type t = d->ty;
    struct val v;
    if (d->is_array) {
        emit_array_decl(S, d);
        return;
    }
    if (t.b == B_STRUCT) {
        struct val sv = d->e ? sl_convert(S, sl_ev(S, d->e), t, d->e->t, sl_sfmt(S, "'%.*s'", d->name->len, d->name->p))
                             : zero_val(S, t);
        struct sym *ss = sl_declare(S, S->scope, d->name, t);
        ss->is_const = d->is_const;
        store_val(S, ss, sv);
        return;
    }
    if (d->e) {
        v = sl_ev(S, d->e);
        if (t.b == B_BOOL) {
            if (v.t.b != B_BOOL)
                FAIL(S, d->e->t, "a bool is set from a %s", sl_type_name(S, v.t));
        } else {
            v = sl_convert(S, v, t, d->e->t, sl_sfmt(S, "'%.*s'", d->name->len, d->name->p));
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
    struct sym *s = sl_declare(S, S->scope, d->name, t);
    s->is_const = d->is_const;
    if (constant) {
        s->has_value = 1;
        s->value = value;
        return;
    }
    if (t.b == B_INT) {
        sl_out_line(S, "int %s = %s;", s->c[0], v.c[0]);
    } else if (t.b == B_BOOL) {
        sl_out_line(S, "REAL %s = (%s) ? RSPLAT(1.0) : RSPLAT(0.0);", s->c[0], v.c[0]);
    } else {
        for (int i = 0; i < t.n; ++i)
            sl_out_line(S, "REAL %s = %s;", s->c[i], v.c[i]);
    }
}

static void emit_assign(struct sl *S, struct stmt *st, const char *pred)
{
    struct expr *l = st->lhs;
    if (l->k == E_IDX || (l->k == E_SWZ && l->a->k == E_IDX)) {
        emit_assign_indexed(S, st, pred);
        return;
    }
    const struct tok *rn = root_name(l);
    struct sym *root = rn ? sl_lookup(S, rn) : NULL;
    if (root && root->t.b == B_STRUCT) {
        /* a struct, a field (to any depth), a field's components */
        int comp[4], ncomp, swz;
        struct sym *s = lvalue(S, l, comp, &ncomp, &swz);
        if (root->is_const)
            FAIL(S, rn, "'%.*s' is const", rn->len, rn->p);
        struct val v = sl_ev(S, st->e);
        if (s->t.b == B_STRUCT) {
            if (st->op != '=')
                FAIL(S, st->t, "a compound assignment to a struct");
            assign_struct(S, s, sl_convert(S, v, s->t, st->e->t, "the struct assigned"), pred, st->t);
            return;
        }
        struct type target = s->t.b == B_FLOAT ? (struct type){ .b = B_FLOAT, .n = ncomp } : s->t;
        if (st->op != '=') {
            struct val cur = sl_sym_val(s), part = cur;
            part.t = target;
            for (int i = 0; i < ncomp; ++i)
                part.c[i] = cur.c[comp[i]];
            v = sl_arith(S, st->op, part, v, st->t);
        }
        v = sl_convert(S, v, target, st->e->t, sl_sfmt(S, "'%.*s'", s->len, s->name));
        assign_sym(S, s, comp, ncomp, v, pred, st->t);
        return;
    }
    const struct tok *nt = l->k == E_SWZ ? l->a->t : l->t;
    if (!(l->k == E_VAR || (l->k == E_SWZ && l->a->k == E_VAR)))
        FAIL(S, l->t, "the left of an assignment must be a variable or its components");
    struct sym *s = sl_lookup(S, nt);
    struct val v = sl_ev(S, st->e);
    if (!s) {
        if (!(S->allow_implicit && st->op == '=' && l->k == E_VAR))
            fail_unknown(S, nt, "identifier");
        /* the body form: the first assignment declares it, at the function's level */
        struct scope *sc = S->scope;
        while (!sc->function_level)
            sc = sc->up;
        struct type t = v.t.b == B_INT ? (struct type){ .b = B_FLOAT, .n = 1 } : v.t;
        if (t.b == B_VOID)
            FAIL(S, st->e->t, "a void value");
        s = sl_declare(S, sc, nt, t);
        if (t.b == B_FLOAT)
            for (int i = 0; i < t.n; ++i)
                sl_out_line(S, "REAL %s = RSPLAT(0.0);", s->c[i]);
        else
            sl_out_line(S, "REAL %s = RSPLAT(0.0);", s->c[0]);
    }
    if (s->is_const)
        FAIL(S, nt, "'%.*s' is const", nt->len, nt->p);
    if (s->arr_n)
        FAIL(S, nt, "'%.*s' is an array: assign its elements (%.*s[0] = ...)", nt->len, nt->p, nt->len, nt->p);
    int comp[4] = { 0, 1, 2, 3 }, ncomp = s->t.n;
    struct type target = s->t;
    if (l->k == E_SWZ) {
        if (s->t.b != B_FLOAT)
            FAIL(S, l->t, "a swizzle of a %s", sl_type_name(S, s->t));
        ncomp = l->nswz;
        for (int i = 0; i < ncomp; ++i) {
            comp[i] = l->swz[i];
            if (comp[i] >= s->t.n)
                FAIL(S, l->t, "component %c of a %s", "xyzw"[comp[i]], sl_type_name(S, s->t));
            for (int j = 0; j < i; ++j)
                if (comp[j] == comp[i])
                    FAIL(S, l->t, "component %c is written twice", "xyzw"[comp[i]]);
        }
        target = (struct type){ .b = B_FLOAT, .n = ncomp };
    }
    if (st->op != '=') {
        if (s->t.b == B_BOOL)
            FAIL(S, st->t, "a compound assignment to a bool");
        struct val cur = sl_sym_val(s);
        struct val part = cur;
        part.t = target;
        for (int i = 0; i < ncomp; ++i)
            part.c[i] = cur.c[comp[i]];
        v = sl_arith(S, st->op, part, v, st->t);
    }
    if (s->t.b == B_BOOL) {
        if (v.t.b != B_BOOL)
            FAIL(S, st->e->t, "a bool is set from a %s", sl_type_name(S, v.t));
    } else {
        v = sl_convert(S, v, target, st->e->t, sl_sfmt(S, "'%.*s'", nt->len, nt->p));
    }
    assign_sym(S, s, comp, ncomp, v, pred, st->t);
}

static void emit_return(struct sl *S, struct stmt *st, const char *pred)
{
    struct fnctx *fc = S->fn;
    const char *E = effective(S, pred);
    if (fc->ret.b == B_VOID || !st->e) {
        if (fc->ret.b != B_VOID)
            FAIL(S, st->t, "return needs a value");
        if (st->e)
            FAIL(S, st->e->t, "a void function returns no value");
        if (!E)
            return; /* every lane returns: what follows is never reached (sl_emit_block stops there) */
        if (!fc->live_var) {
            fc->live_var = sl_sfmt(S, "sl_live%d", ++S->ntemp);
            sl_out_line(S, "REAL %s = RSPLAT(1.0);", fc->live_var);
            fc->live = sl_sfmt(S, "(%s != RSPLAT(0.0))", fc->live_var);
        }
        sl_out_line(S, "%s = %s ? RSPLAT(0.0) : %s;", fc->live_var, E, fc->live_var);
        return;
    }
    struct val v = sl_ev(S, st->e);
    v = sl_convert(S, v, fc->ret, st->e->t, "the returned value");
    if (fc->ret.b == B_STRUCT) {
        assign_struct(S, fc->ret_sym, v, E, st->t);
        if (E) {
            if (!fc->live_var) {
                fc->live_var = sl_sfmt(S, "sl_live%d", ++S->ntemp);
                sl_out_line(S, "REAL %s = RSPLAT(1.0);", fc->live_var);
                fc->live = sl_sfmt(S, "(%s != RSPLAT(0.0))", fc->live_var);
            }
            sl_out_line(S, "%s = %s ? RSPLAT(0.0) : %s;", fc->live_var, E, fc->live_var);
        }
        return;
    }
    if (!E && fc->is_model && !fc->ret_c[0]) {
        sl_out_line(S, "return %s;", v.c[0]);
        fc->returned = 1;
        return;
    }
    if (fc->is_model && !fc->ret_c[0]) {
        fc->ret_c[0] = "sl_ret";
        sl_out_line(S, "REAL sl_ret = RSPLAT(0.0);");
    }
    if (E && fc->ret.n > 1)
        E = sl_temp_cond(S, E, 0);
    for (int i = 0; i < fc->ret.n; ++i) {
        if (E)
            sl_out_line(S, "%s = %s ? %s : %s;", fc->ret_c[i], E, v.c[i], fc->ret_c[i]);
        else
            sl_out_line(S, "%s = %s;", fc->ret_c[i], v.c[i]);
    }
    if (E) {
        if (!fc->live_var) {
            fc->live_var = sl_sfmt(S, "sl_live%d", ++S->ntemp);
            sl_out_line(S, "REAL %s = RSPLAT(1.0);", fc->live_var);
            fc->live = sl_sfmt(S, "(%s != RSPLAT(0.0))", fc->live_var);
        }
        sl_out_line(S, "%s = %s ? RSPLAT(0.0) : %s;", fc->live_var, E, fc->live_var);
    }
}

static int const_int(struct sl *S, struct expr *e, long *out)
{
    switch (e->k) {
    case E_INT: {
        struct val v = sl_ev(S, e);
        *out = strtol(v.c[0], NULL, 10);
        return 1;
    }
    case E_VAR: {
        struct sym *s = sl_lookup(S, e->t);
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

/* while (COND) BODY and do BODY while (COND): unrolled SL_MAX_WHILE times, lane by lane. A
 * lane runs the body while it has not left the loop (its mask); a condition the same in every
 * lane (ints) keeps the mask an int, so an int counter may step. A lane still in the loop after
 * the last copy has not finished: what the loop wrote is NaN there, which the figures show. */
static void emit_while(struct sl *S, struct stmt *st, const char *pred, int is_do)
{
    if (sl_stmt_returns(st->s3))
        FAIL(S, st->t, "a return inside a %s loop is not supported", is_do ? "do" : "while");
    int k = ++S->ntemp;
    /* the condition's kind, from its first evaluation: uniform (an int mask) or not (a REAL one) */
    int uniform = -1;
    const char *w = NULL, *wc = NULL;
    struct sym **saved = S->loop_syms;
    int saved_n = S->nloop_syms, saved_cap = S->loop_syms_cap;
    S->loop_syms = sl_arena_alloc(S, sizeof *S->loop_syms * 16);
    S->nloop_syms = 0;
    S->loop_syms_cap = 16;
    struct loopctx L = { .up = S->loops };
    S->loops = &L;
    for (int it = 0; it <= SL_MAX_WHILE; ++it) {
        if (++S->unrolled > SL_MAX_UNROLL_TOTAL)
            FAIL(S, st->t, "the loops unroll to more than %d iterations in all (nested loops multiply; "
                 "a while or do loop is unrolled %d times)", SL_MAX_UNROLL_TOTAL, SL_MAX_WHILE);
        S->stmt_line = st->t->line;
        loop_iteration(S, &L);
        if (!is_do || it > 0) {
            struct val c = sl_ev(S, st->e);
            if (c.t.b != B_BOOL)
                FAIL(S, st->e->t, "the condition of %s is a %s, not a comparison", is_do ? "do ... while" : "while",
                     sl_type_name(S, c.t));
            if (uniform < 0) {
                const char *outer = effective(S, NULL);
                uniform = c.uniform && (!pred || !strstr(pred, "RSPLAT")) && !S->fn->live &&
                          (!outer || !strstr(outer, "RSPLAT"));
                w = sl_sfmt(S, uniform ? "sl_bw%d" : "sl_w%d", k);
                sl_out_line(S, uniform ? "int %s = 1;" : "REAL %s = RSPLAT(1.0);", w);
                wc = uniform ? w : sl_sfmt(S, "(%s != RSPLAT(0.0))", w);
            }
            if (uniform)
                sl_out_line(S, "%s = %s && %s;", w, w, c.c[0]);
            else
                sl_out_line(S, "%s = (%s && %s) ? RSPLAT(1.0) : RSPLAT(0.0);", w, wc, c.c[0]);
        }
        if (it == SL_MAX_WHILE)
            break; /* the last evaluation: lanes still in the loop */
        const char *bp = pred;
        if (wc)
            bp = sl_temp_cond(S, and_cond(S, pred, wc), uniform > 0);
        sl_emit_block(S, st->s3, bp, 1);
    }
    /* lanes that did not finish (nor break out): what the loop wrote becomes NaN */
    loop_iteration(S, &L);
    const char *E = effective(S, and_cond(S, pred, wc));
    S->loops = L.up;
    for (int i = 0; i < S->nloop_syms; ++i) {
        struct sym *s = S->loop_syms[i];
        for (int c = 0; c < s->t.n; ++c)
            sl_out_line(S, "%s = %s ? (RSPLAT(0.0) / RSPLAT(0.0)) : %s;", s->c[c], E, s->c[c]);
    }
    struct sym **inner = S->loop_syms;
    int ninner = S->nloop_syms;
    S->loop_syms = saved;
    S->nloop_syms = saved_n;
    S->loop_syms_cap = saved_cap;
    /* an enclosing loop also wrote what this one wrote */
    for (int i = 0; saved && i < ninner; ++i)
        loop_note(S, inner[i]);
}

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
    struct loopctx L = { .up = S->loops };
    S->loops = &L;
    for (long i = i0;; i += step) {
        int go = c->op == '<' ? i < bound : c->op == 'L' ? i <= bound : c->op == '>' ? i > bound : i >= bound;
        if (!go)
            break;
        if (++count > SL_MAX_UNROLL)
            FAIL(S, st->t, "a for loop of more than %d iterations", SL_MAX_UNROLL);
        /* nested loops multiply: the bodies emitted in all are bounded too */
        if (++S->unrolled > SL_MAX_UNROLL_TOTAL)
            FAIL(S, st->t, "the loops unroll to more than %d iterations in all (nested loops multiply; "
                 "one loop may have %d)", SL_MAX_UNROLL_TOTAL, SL_MAX_UNROLL);
        loop_iteration(S, &L);
        sl_push_scope(S, 0);
        struct sym *s = sl_declare(S, S->scope, d->name, d->ty);
        s->is_const = 1;
        s->has_value = 1;
        s->value = i;
        emit_stmt(S, st->s3, pred);
        S->scope = S->scope->up;
        if (sl_stmt_returns(st->s3))
            FAIL(S, st->t, "a return inside a for loop is not supported");
    }
    S->loops = L.up;
}

/* switch (SEL) { case K: ... default: ... }: SEL an int (the same in every lane), each label a
 * constant. An int flag says "fallen into a section" (a case that matches, or default when none
 * does, at the label's place; then on through the sections that follow, as C falls through);
 * the statements run under it, and break leaves the switch (emit_break). */
static void emit_switch(struct sl *S, struct stmt *st, const char *pred)
{
    struct val sel = sl_ev(S, st->e);
    if (sel.t.b != B_INT)
        FAIL(S, st->e->t, "switch on a %s: the selector is an int", sl_type_name(S, sel.t));
    sel = sl_temp_val(S, sel);
    struct stmt *b = st->s1;
    const char *any = NULL; /* "one of the cases matches" */
    int ndefault = 0;
    long *seen = sl_arena_alloc(S, sizeof *seen * (size_t)(b->n + 1));
    int nseen = 0;
    for (int i = 0; i < b->n; ++i) {
        struct stmt *c = b->items[i];
        if (c->k != S_CASE)
            continue;
        if (!c->e) {
            if (ndefault++)
                FAIL(S, c->t, "a second default label in one switch");
            continue;
        }
        long k;
        if (!const_int(S, c->e, &k))
            FAIL(S, c->e->t, "a case label is a constant integer");
        for (int j = 0; j < nseen; ++j)
            if (seen[j] == k)
                FAIL(S, c->t, "case %ld appears twice in one switch", k);
        seen[nseen++] = k;
        const char *m = sl_sfmt(S, "(%s == %ld)", sel.c[0], k);
        any = any ? sl_sfmt(S, "%s | %s", any, m) : m; /* | of 0/1: no warning where both are constant */
    }
    int pred_uniform = !pred || !strstr(pred, "RSPLAT");
    const char *in = sl_sfmt(S, "sl_bs%d", ++S->ntemp);
    sl_out_line(S, "int %s = 0;", in);
    struct loopctx L = { .up = S->loops, .is_switch = 1 };
    S->loops = &L;
    sl_push_scope(S, 0);
    const char *bp = NULL;
    for (int i = 0; i < b->n; ++i) {
        struct stmt *c = b->items[i];
        S->stmt_line = c->t->line;
        if (c->k == S_CASE) {
            long k = 0;
            if (c->e)
                const_int(S, c->e, &k);
            const char *m = c->e ? sl_sfmt(S, "(%s == %ld)", sel.c[0], k) : any ? sl_sfmt(S, "!(%s)", any) : "1";
            sl_out_line(S, "%s = %s | %s;", in, in, m);
            bp = sl_temp_cond(S, and_cond(S, pred, in), pred_uniform);
            continue;
        }
        if (!bp)
            continue; /* before the first label: never run */
        emit_stmt(S, c, bp);
    }
    S->scope = S->scope->up;
    S->loops = L.up;
}

static void emit_stmt_inner(struct sl *S, struct stmt *st, const char *pred);
static void emit_stmt(struct sl *S, struct stmt *st, const char *pred)
{
    const char *saved = S->cur_pred;
    S->cur_pred = pred;
    emit_stmt_inner(S, st, pred);
    S->cur_pred = saved;
}

static void emit_stmt_inner(struct sl *S, struct stmt *st, const char *pred)
{
    S->stmt_line = st->t->line;
    switch (st->k) {
    case S_EMPTY:
        return;
    case S_CALL:
        (void)sl_ev(S, st->e);
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
        sl_emit_block(S, st, pred, st->op != 1);
        return;
    case S_FOR:
        emit_for(S, st, pred);
        return;
    case S_WHILE:
    case S_DO:
        emit_while(S, st, pred, st->k == S_DO);
        return;
    case S_BREAK:
    case S_CONTINUE:
        emit_break(S, st, pred, st->k == S_CONTINUE);
        return;
    case S_SWITCH:
        emit_switch(S, st, pred);
        return;
    case S_CASE:
        FAIL(S, st->t, "a case label outside a switch");
    case S_IF: {
        struct val c = sl_ev(S, st->e);
        if (c.t.b != B_BOOL)
            FAIL(S, st->e->t, "the condition of if is a %s, not a comparison", sl_type_name(S, c.t));
        S->stmt_line = st->t->line;
        const char *cm = sl_temp_cond(S, c.c[0], c.uniform);
        int uniform = c.uniform && (!pred || strncmp(pred, "sl_b", 4) == 0);
        const char *tp = sl_temp_cond(S, and_cond(S, pred, cm), uniform);
        sl_emit_block(S, st->s1, tp, 1);
        if (st->s2) {
            S->stmt_line = st->t->line;
            const char *ep = sl_temp_cond(S, and_cond(S, pred, sl_sfmt(S, "(!%s)", cm)), uniform);
            sl_emit_block(S, st->s2, ep, 1);
        }
        return;
    }
    }
}

void sl_emit_block(struct sl *S, struct stmt *b, const char *pred, int new_scope)
{
    if (new_scope)
        sl_push_scope(S, 0);
    if (b->k != S_BLOCK) {
        emit_stmt(S, b, pred);
    } else {
        for (int i = 0; i < b->n; ++i) {
            emit_stmt(S, b->items[i], pred);
            if (sl_stmt_returns(b->items[i]))
                break; /* what follows is never reached */
        }
    }
    if (new_scope)
        S->scope = S->scope->up;
}
