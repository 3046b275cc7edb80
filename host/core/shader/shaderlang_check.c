/* shaderlang_check.c - the shader-language translator (shaderlang.c): type checks, values and temporaries, the built-in functions. */
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

/* ---- checking and emitting ---------------------------------------------------------------- */


const char *sl_type_name(struct sl *S, struct type t)
{
    switch (t.b) {
    case B_VOID: return "void";
    case B_BOOL: return "bool";
    case B_INT: return "int";
    case B_STRUCT: return sl_sfmt(S, "%.*s", t.st->name->len, t.st->name->p);
    default: return t.n == 1 ? "float" : sl_sfmt(S, "vec%d", t.n);
    }
}

int sl_same_type(struct type a, struct type b)
{
    return a.b == b.b && a.n == b.n && (a.b != B_STRUCT || a.st == b.st);
}

/* Output lines carry the user's line: a #line directive wherever the next line's number differs. */
void sl_out_line(struct sl *S, const char *fmt, ...)
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
        char *big = sl_arena_alloc(S, (size_t)n + 1);
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
    if (S->out.len > SL_MAX_OUTPUT)
        sl_fail_at(S, S->stmt_line, -1, "the translation is larger than %zu MiB (loops unrolled and helper functions "
                   "inlined): write the loop with fewer iterations or fewer statements", SL_MAX_OUTPUT >> 20);
    if ((S->line_next & 1023) == 0)
        sl_check_deadline(S);
}

static unsigned name_hash(const char *s)
{
    unsigned h = 2166136261u; /* FNV-1a */
    for (; *s; ++s)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

/* The slot of s in the table: its own, or the empty one where it would go. */
static struct name_slot *name_slot(struct name_table *tb, const char *s, unsigned h)
{
    size_t i = h & (tb->cap - 1);
    while (tb->v[i].s && (tb->v[i].hash != h || strcmp(tb->v[i].s, s) != 0))
        i = (i + 1) & (tb->cap - 1);
    return &tb->v[i];
}

/* The slot of s, added (with next_suffix 2) if it was not there. */
static struct name_slot *name_intern(struct sl *S, struct name_table *tb, const char *s)
{
    if (2 * (tb->n + 1) > tb->cap) {
        struct name_table grown = { NULL, tb->n, tb->cap ? 2 * tb->cap : 64 };
        grown.v = sl_arena_alloc(S, sizeof *grown.v * grown.cap);
        for (size_t i = 0; i < tb->cap; ++i)
            if (tb->v[i].s)
                *name_slot(&grown, tb->v[i].s, tb->v[i].hash) = tb->v[i];
        *tb = grown;
    }
    unsigned h = name_hash(s);
    struct name_slot *slot = name_slot(tb, s, h);
    if (!slot->s) {
        slot->s = s;
        slot->hash = h;
        slot->next_suffix = 2;
        tb->n++;
    }
    return slot;
}

static int name_taken(struct name_table *tb, const char *s)
{
    return tb->cap && name_slot(tb, s, name_hash(s))->s != NULL;
}

/* A C name for a user variable, unique in the output: u__NAME, then u__NAME_2, u__NAME_3, ...
 * Each base remembers where its suffixes stopped, so a name declared in every iteration of an
 * unrolled loop costs the same each time. */
static int vec_names_taken(struct sl *S, const char *root, int n)
{
    if (name_taken(&S->used, root))
        return 1;
    for (int i = 0; i < n && n > 1; ++i)
        if (name_taken(&S->used, sl_sfmt(S, "%s_%c", root, "xyzw"[i])))
            return 1;
    return 0;
}

/* n > 1: a vector's root, whose components ROOT_x .. are free and given out too (a float
 * called v_x and a vec3 called v must not meet). */
static const char *c_name_n(struct sl *S, const char *base, int n)
{
    struct name_slot *b = name_intern(S, &S->bases, base);
    const char *s = sl_sfmt(S, "u__%s", base);
    while (vec_names_taken(S, s, n))
        s = sl_sfmt(S, "u__%s_%d", base, b->next_suffix++);
    name_intern(S, &S->used, s);
    for (int i = 0; i < n && n > 1; ++i)
        name_intern(S, &S->used, sl_sfmt(S, "%s_%c", s, "xyzw"[i]));
    return s;
}

static const char *c_name(struct sl *S, const char *base) { return c_name_n(S, base, 1); }

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

const char *sl_temp_real(struct sl *S, const char *expr)
{
    if (is_simple(expr))
        return expr;
    const char *t = sl_sfmt(S, "sl_t%d", ++S->ntemp);
    sl_out_line(S, "REAL %s = %s;", t, expr);
    return t;
}

/* A condition kept for later: an int where it is uniform, else a REAL mask. */
const char *sl_temp_cond(struct sl *S, const char *cond, int uniform)
{
    if (is_simple(cond))
        return cond;
    if (uniform) {
        const char *t = sl_sfmt(S, "sl_b%d", ++S->ntemp);
        sl_out_line(S, "int %s = %s;", t, cond);
        return t;
    }
    int k = ++S->ntemp;
    sl_out_line(S, "REAL sl_m%d = (%s) ? RSPLAT(1.0) : RSPLAT(0.0);", k, cond);
    return sl_sfmt(S, "(sl_m%d != RSPLAT(0.0))", k);
}

struct val sl_temp_val(struct sl *S, struct val v)
{
    if (v.t.b == B_STRUCT) {
        struct val *f = sl_arena_alloc(S, sizeof *f * (size_t)v.t.st->nfields);
        for (int i = 0; i < v.t.st->nfields; ++i)
            f[i] = sl_temp_val(S, v.f[i]);
        v.f = f;
        return v;
    }
    if (v.t.b == B_FLOAT)
        for (int i = 0; i < v.t.n; ++i)
            v.c[i] = sl_temp_real(S, v.c[i]);
    else if (v.t.b == B_BOOL)
        v.c[0] = sl_temp_cond(S, v.c[0], v.uniform);
    else if (!is_simple(v.c[0])) {
        const char *t = sl_sfmt(S, "sl_i%d", ++S->ntemp);
        sl_out_line(S, "int %s = %s;", t, v.c[0]);
        v.c[0] = t;
    }
    return v;
}

/* A number as written, without its suffix, as a C floating literal. */
const char *sl_float_literal(struct sl *S, const struct tok *t)
{
    int len = t->len;
    while (len > 0 && (t->p[len - 1] == 'f' || t->p[len - 1] == 'F' || t->p[len - 1] == 'h' ||
                       t->p[len - 1] == 'H' || t->p[len - 1] == 'l' || t->p[len - 1] == 'L' ||
                       t->p[len - 1] == 'u' || t->p[len - 1] == 'U'))
        --len;
    const char *s = sl_sfmt(S, "%.*s", len, t->p);
    int has_point = strchr(s, '.') || strchr(s, 'e') || strchr(s, 'E');
    if (!has_point)
        s = sl_sfmt(S, "%s.0", s);
    if (s[0] == '.')
        s = sl_sfmt(S, "0%s", s);
    size_t l = strlen(s);
    if (s[l - 1] == '.')
        s = sl_sfmt(S, "%s0", s);
    return s;
}

struct val sl_to_float(struct sl *S, struct val v, const struct tok *where)
{
    if (v.t.b == B_FLOAT)
        return v;
    if (v.t.b == B_INT) {
        const char *s = v.c[0];
        int digits = *s != '\0';
        for (const char *p = s; *p; ++p)
            if (!isdigit((unsigned char)*p))
                digits = 0;
        v.c[0] = digits ? sl_sfmt(S, "RSPLAT(%s.0)", s) : sl_sfmt(S, "RSPLAT((RSCALAR)(%s))", s);
        v.t = (struct type){ .b = B_FLOAT, .n = 1, .half = 2 }; /* an int takes the other operand's precision */
        return v;
    }
    FAIL(S, where, "a %s where a number is expected", sl_type_name(S, v.t));
}

/* Converts v to type t where the languages do it implicitly: int to float, a scalar to a vector
 * (HLSL's float3 v = 0). */
struct val sl_convert(struct sl *S, struct val v, struct type t, const struct tok *where, const char *what)
{
    /* into a binary16 variable, parameter or result: the value stored is rounded */
    if (t.b == B_FLOAT && t.half == 1 && (v.t.b == B_INT || (v.t.b == B_FLOAT && v.t.half != 1))) {
        struct type full = t;
        full.half = 0;
        return sl_round_half(S, sl_convert(S, v, full, where, what));
    }
    if (sl_same_type(t, v.t))
        return v;
    if (t.b == B_STRUCT || v.t.b == B_STRUCT)
        FAIL(S, where, "%s: a %s cannot become a %s", what, sl_type_name(S, v.t), sl_type_name(S, t));
    if (t.b == B_FLOAT && (v.t.b == B_INT || v.t.b == B_FLOAT)) {
        v = sl_to_float(S, v, where);
        if (v.t.n == t.n)
            return v;
        if (v.t.n == 1) {
            const char *s = sl_temp_real(S, v.c[0]);
            for (int i = 0; i < t.n; ++i)
                v.c[i] = s;
            v.t = t;
            return v;
        }
    }
    FAIL(S, where, "%s: a %s cannot become a %s", what, sl_type_name(S, v.t), sl_type_name(S, t));
}

struct sym *sl_lookup(struct sl *S, const struct tok *t)
{
    for (struct scope *sc = S->scope; sc; sc = sc->up)
        for (struct sym *s = sc->syms; s; s = s->next)
            if (s->len == t->len && strncmp(s->name, t->p, (size_t)t->len) == 0)
                return s;
    return NULL;
}

void sl_push_scope(struct sl *S, int function_level)
{
    struct scope *sc = sl_arena_alloc(S, sizeof *sc);
    sc->up = S->scope;
    sc->function_level = function_level;
    S->scope = sc;
}

/* The C names of s (of type s->t) from base: its components', or its fields' syms. */
static void sym_names(struct sl *S, struct sym *s, const char *base)
{
    struct type t = s->t;
    if (t.b == B_STRUCT) {
        s->fields = sl_arena_alloc(S, sizeof *s->fields * (size_t)t.st->nfields);
        s->fvals = sl_arena_alloc(S, sizeof *s->fvals * (size_t)t.st->nfields);
        for (int i = 0; i < t.st->nfields; ++i) {
            struct sym *f = sl_arena_alloc(S, sizeof *f);
            f->name = t.st->fname[i]->p;
            f->len = t.st->fname[i]->len;
            f->t = t.st->fty[i];
            sym_names(S, f, sl_sfmt(S, "%s__%.*s", base, f->len, f->name));
            s->fields[i] = f;
        }
    } else if (t.b == B_FLOAT && t.n > 1) {
        const char *root = c_name_n(S, base, t.n);
        for (int i = 0; i < t.n; ++i)
            s->c[i] = sl_sfmt(S, "%s_%c", root, "xyzw"[i]);
    } else {
        s->c[0] = c_name(S, base);
    }
}

struct sym *sl_declare(struct sl *S, struct scope *sc, const struct tok *name, struct type t)
{
    for (struct sym *s = sc->syms; s; s = s->next)
        if (s->len == name->len && strncmp(s->name, name->p, (size_t)name->len) == 0)
            FAIL(S, name, "'%.*s' is declared twice in this scope", name->len, name->p);
    if (name->len > SL_NAME_MAX)
        FAIL(S, name, "a name of more than %d characters", SL_NAME_MAX);
    struct sym *s = sl_arena_alloc(S, sizeof *s);
    s->name = name->p;
    s->len = name->len;
    s->t = t;
    sym_names(S, s, sl_tok_str(S, name));
    s->next = sc->syms;
    sc->syms = s;
    return s;
}

/* An array NAME[n] of t in scope sc: a sym with n element syms, each with C names of its own. */
struct sym *sl_declare_array(struct sl *S, struct scope *sc, const struct tok *name, struct type t, int n)
{
    struct sym *s = sl_declare(S, sc, name, t);
    s->arr_n = n;
    s->elem = sl_arena_alloc(S, sizeof *s->elem * (size_t)n);
    const char *base = sl_tok_str(S, name);
    for (int k = 0; k < n; ++k) {
        struct sym *e = sl_arena_alloc(S, sizeof *e);
        *e = *s;
        e->arr_n = 0;
        e->elem = NULL;
        e->next = NULL;
        const char *root = c_name_n(S, sl_sfmt(S, "%s__%d", base, k), t.n);
        for (int i = 0; i < t.n; ++i)
            e->c[i] = t.n > 1 ? sl_sfmt(S, "%s_%c", root, "xyzw"[i]) : root;
        s->elem[k] = e;
    }
    return s;
}

/* The value of a variable. */
struct val sl_sym_val(struct sym *s)
{
    struct val v = { s->t, { NULL, NULL, NULL, NULL }, 0, NULL };
    if (s->t.b == B_STRUCT) {
        /* the fields' values are their syms' names, kept with the sym (sym_names) */
        v.f = s->fvals;
        for (int i = 0; i < s->t.st->nfields; ++i)
            s->fvals[i] = sl_sym_val(s->fields[i]);
        return v;
    }
    if (s->t.b == B_BOOL) {
        return (struct val){ .t = s->t, .c = { s->c[0] } }; /* replaced by the caller */
    }
    for (int i = 0; i < s->t.n; ++i)
        v.c[i] = s->c[i];
    v.uniform = s->t.b == B_INT;
    return v;
}


const char *sl_op_text(int op)
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

int sl_half_of(int a, int b)
{
    if (a == 0 || b == 0)
        return 0;
    return a == 1 || b == 1 ? 1 : 2;
}

struct val sl_round_half(struct sl *S, struct val v)
{
    if (v.t.b != B_FLOAT)
        return v;
    for (int i = 0; i < v.t.n; ++i)
        v.c[i] = sl_sfmt(S, "RHALF(%s)", v.c[i]);
    v.t.half = 1;
    return v;
}

/* a OP b for the arithmetic operators, with int promotion and scalar broadcast. An operation
 * in binary16 (sl_half_of) rounds its literal operand as a half constant and its result. */
struct val sl_arith(struct sl *S, int op, struct val a, struct val b, const struct tok *where)
{
    if ((sl_is_matrix(a.t) && (b.t.b == B_FLOAT || b.t.b == B_INT || sl_is_matrix(b.t))) ||
        (sl_is_matrix(b.t) && (a.t.b == B_FLOAT || a.t.b == B_INT)))
        return sl_matrix_arith(S, op, a, b, where);
    if (a.t.b == B_BOOL || b.t.b == B_BOOL || a.t.b == B_VOID || b.t.b == B_VOID || a.t.b == B_STRUCT ||
        b.t.b == B_STRUCT)
        FAIL(S, where, "'%s' needs numbers, not %s and %s", sl_op_text(op), sl_type_name(S, a.t), sl_type_name(S, b.t));
    struct val r = { .t = { .b = B_INT, .n = 1 }, .uniform = a.uniform && b.uniform };
    if (a.t.b == B_INT && b.t.b == B_INT) {
        r.c[0] = sl_sfmt(S, "(%s %s %s)", a.c[0], sl_op_text(op), b.c[0]);
        return r;
    }
    a = sl_to_float(S, a, where);
    b = sl_to_float(S, b, where);
    if (a.t.n != b.t.n && a.t.n != 1 && b.t.n != 1)
        FAIL(S, where, "'%s' of a %s and a %s", sl_op_text(op), sl_type_name(S, a.t), sl_type_name(S, b.t));
    int n = a.t.n > b.t.n ? a.t.n : b.t.n;
    int h = sl_half_of(a.t.half, b.t.half);
    if (h == 1) {
        if (a.t.half != 1)
            a = sl_round_half(S, a);
        if (b.t.half != 1)
            b = sl_round_half(S, b);
    }
    if (n > 1) {
        if (a.t.n == 1)
            a.c[0] = sl_temp_real(S, a.c[0]);
        if (b.t.n == 1)
            b.c[0] = sl_temp_real(S, b.c[0]);
    }
    r.t = (struct type){ .b = B_FLOAT, .n = n, .half = h };
    for (int i = 0; i < n; ++i) {
        const char *x = a.c[a.t.n == 1 ? 0 : i], *y = b.c[b.t.n == 1 ? 0 : i];
        r.c[i] = op == '%' ? sl_sfmt(S, "fmod(%s, %s)", x, y) : sl_sfmt(S, "(%s %s %s)", x, sl_op_text(op), y);
    }
    if (h == 1)
        r = sl_round_half(S, r);
    return n > 1 ? sl_temp_val(S, r) : r;
}

/* ---- built-in functions ------------------------------------------------------------------ */

enum builtin_kind { BK_CW, BK_DOT, BK_LENGTH, BK_DISTANCE, BK_NORMALIZE, BK_REFLECT, BK_CROSS, BK_ATAN, BK_FACEFORWARD };
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
    { "faceforward", 3, BK_FACEFORWARD, NULL, 1 },
    { NULL, 0, 0, NULL, 0 } };

const struct builtin *sl_find_builtin(const struct tok *t)
{
    for (int i = 0; builtins[i].name; ++i)
        if (sl_tok_is(t, builtins[i].name))
            return &builtins[i];
    return NULL;
}

/* Writes fmt with %1..%3 replaced; an argument used twice is kept in a temporary first. */
static const char *apply_fmt(struct sl *S, const char *fmt, const char **args, int nargs)
{
    int uses[3] = { 0, 0, 0 };
    for (const char *p = fmt; *p; ++p)
        if (p[0] == '%' && p[1] >= '1' && p[1] <= '3')
            uses[p[1] - '1']++;
    const char *a[3];
    for (int i = 0; i < nargs; ++i)
        a[i] = uses[i] > 1 ? sl_temp_real(S, args[i]) : args[i];
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
    const char *s = sl_sfmt(S, "%s", b.s ? b.s : "");
    int failed = b.failed;
    md_free(&b);
    if (failed)
        sl_fail_at(S, 0, 0, "out of memory");
    return s;
}

static const char *dot_of(struct sl *S, struct val a, struct val b)
{
    const char *s = sl_sfmt(S, "%s * %s", a.c[0], b.c[0]);
    for (int i = 1; i < a.t.n; ++i)
        s = sl_sfmt(S, "%s + %s * %s", s, a.c[i], b.c[i]);
    return sl_sfmt(S, "(%s)", s);
}

static struct val builtin_value(struct sl *S, const struct builtin *bi, struct expr *e, struct val *a, int n,
                                int width);

struct val sl_call_builtin(struct sl *S, const struct builtin *bi, struct expr *e)
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
    int h = 2;   /* the call's precision: its arguments' (sl_half_of) */
    for (int i = 0; i < n; ++i) {
        a[i] = sl_ev(S, e->args[i]);
        if (a[i].t.b != B_FLOAT && a[i].t.b != B_INT)
            FAIL(S, e->args[i]->t, "argument %d of %s is a %s, not a number", i + 1, bi->name, sl_type_name(S, a[i].t));
        a[i] = sl_to_float(S, a[i], e->args[i]->t);
        if (a[i].t.n > 1) {
            if (width > 1 && a[i].t.n != width)
                FAIL(S, e->args[i]->t, "%s of vectors of different sizes", bi->name);
            width = a[i].t.n;
        }
        h = sl_half_of(h, a[i].t.half);
    }
    /* In binary16 a literal argument is a half constant; the result is rounded once (a dot
       product, length or normalize too: as one fused operation, docs/user-models.md). */
    if (h == 1)
        for (int i = 0; i < n; ++i)
            if (a[i].t.half != 1)
                a[i] = sl_round_half(S, a[i]);
    struct val r = builtin_value(S, bi, e, a, n, width);
    if (h == 1)
        r = sl_round_half(S, r);
    else
        r.t.half = h;
    return r.t.n > 1 ? sl_temp_val(S, r) : r;
}

static struct val builtin_value(struct sl *S, const struct builtin *bi, struct expr *e, struct val *a, int n,
                                int width)
{
    struct val r = { .t = { .b = B_FLOAT, .n = 1 } };
    switch (bi->kind) {
    case BK_CW:
    case BK_ATAN: {
        const char *fmt = bi->fmt ? bi->fmt : n == 1 ? "atan(%1)" : "atan2(%1, %2)";
        for (int i = 0; i < n; ++i)
            if (a[i].t.n == 1 && width > 1)
                a[i].c[0] = sl_temp_real(S, a[i].c[0]);
        r.t.n = width;
        for (int k = 0; k < width; ++k) {
            const char *args[3];
            for (int i = 0; i < n; ++i)
                args[i] = a[i].c[a[i].t.n == 1 ? 0 : k];
            r.c[k] = apply_fmt(S, fmt, args, n);
        }
        return width > 1 ? sl_temp_val(S, r) : r;
    }
    case BK_FACEFORWARD:
        if (a[0].t.n != a[1].t.n || a[0].t.n != a[2].t.n)
            FAIL(S, e->t, "faceforward of vectors of different sizes");
        break;
    case BK_DOT:
    case BK_DISTANCE:
    case BK_REFLECT:
    case BK_CROSS:
        if (a[0].t.n != a[1].t.n)
            FAIL(S, e->t, "%s of a %s and a %s", bi->name, sl_type_name(S, a[0].t), sl_type_name(S, a[1].t));
        break;
    default:
        break;
    }
    struct val x = sl_temp_val(S, a[0]);
    switch (bi->kind) {
    case BK_DOT:
        r.c[0] = dot_of(S, x, sl_temp_val(S, a[1]));
        return r;
    case BK_LENGTH:
        r.c[0] = x.t.n == 1 ? sl_sfmt(S, "fabs(%s)", x.c[0]) : sl_sfmt(S, "sqrt(%s)", dot_of(S, x, x));
        return r;
    case BK_DISTANCE: {
        struct val d = sl_arith(S, '-', x, a[1], e->t);
        d = sl_temp_val(S, d);
        r.c[0] = d.t.n == 1 ? sl_sfmt(S, "fabs(%s)", d.c[0]) : sl_sfmt(S, "sqrt(%s)", dot_of(S, d, d));
        return r;
    }
    case BK_NORMALIZE: {
        const char *len = sl_temp_real(S, x.t.n == 1 ? sl_sfmt(S, "fabs(%s)", x.c[0]) : sl_sfmt(S, "sqrt(%s)", dot_of(S, x, x)));
        r.t.n = x.t.n;
        for (int i = 0; i < x.t.n; ++i)
            r.c[i] = sl_sfmt(S, "(%s / %s)", x.c[i], len);
        return sl_temp_val(S, r);
    }
    case BK_REFLECT: {
        /* I - 2 dot(N, I) N */
        struct val nn = sl_temp_val(S, a[1]);
        const char *d = sl_temp_real(S, dot_of(S, nn, x));
        r.t.n = x.t.n;
        for (int i = 0; i < x.t.n; ++i)
            r.c[i] = sl_sfmt(S, "(%s - RSPLAT(2.0) * %s * %s)", x.c[i], d, nn.c[i]);
        return sl_temp_val(S, r);
    }
    case BK_FACEFORWARD: {
        /* N where dot(Nref, I) < 0, else -N (GLSL's definition) */
        const char *d = sl_temp_cond(S, sl_sfmt(S, "(%s < RSPLAT(0.0))", dot_of(S, sl_temp_val(S, a[2]),
                                                                                sl_temp_val(S, a[1]))), 0);
        r.t.n = x.t.n;
        for (int i = 0; i < x.t.n; ++i)
            r.c[i] = sl_sfmt(S, "(%s ? %s : -%s)", d, x.c[i], x.c[i]);
        return sl_temp_val(S, r);
    }
    case BK_CROSS: {
        if (x.t.n != 3)
            FAIL(S, e->t, "cross takes two vec3");
        struct val y = sl_temp_val(S, a[1]);
        r.t.n = 3;
        for (int i = 0; i < 3; ++i) {
            int j = (i + 1) % 3, k = (i + 2) % 3;
            r.c[i] = sl_sfmt(S, "(%s * %s - %s * %s)", x.c[j], y.c[k], x.c[k], y.c[j]);
        }
        return sl_temp_val(S, r);
    }
    default:
        FAIL(S, e->t, "internal: unknown built-in kind");
    }
}
