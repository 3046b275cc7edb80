/* shaderlang_lex.c - the shader-language translator (shaderlang.c): the lexer. */
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

/* ---- the lexer ------------------------------------------------------------------------ */

void sl_tokv_push(struct sl *S, struct tokv *v, struct tok t)
{
    if (v->n == v->cap) {
        int cap = v->cap ? 2 * v->cap : 256;
        struct tok *nv = sl_arena_alloc(S, sizeof *nv * (size_t)cap);
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
        sl_tokv_push(S, &S->toks, t);
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

/* Past a block comment that starts at *p, counting lines and columns. */
static void skip_block_comment(struct sl *S, const char **pp, const char *end, int *line, int *col)
{
    const char *p = *pp;
    int l0 = *line, c0 = *col;
    p += 2;
    *col += 2;
    while (p < end && !(p[0] == '*' && p + 1 < end && p[1] == '/')) {
        if (*p == '\n') {
            ++*line;
            *col = 1;
        } else {
            ++*col;
        }
        ++p;
    }
    if (p >= end)
        sl_fail_at(S, l0, c0, "unterminated comment");
    p += 2;
    *col += 2;
    *pp = p;
}

/* A preprocessor line at p (its '#'): #define NAME VALUE becomes a macro, #version, #extension
 * and #pragma are skipped. Returns the end of the line. */
static const char *lex_directive(struct sl *S, const char *p, const char *end, int line, int col)
{
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
    } else if (wl == 4 && strncmp(w, "line", 4) == 0 && S->pp_active) {
        /* passed through by the preprocessor: the next line is line N */
        long n = strtol(q, NULL, 10);
        if (n > 0 && n < 100000000)
            S->line_delta = (int)n - (line + 1);
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
        struct macro *m = sl_arena_alloc(S, sizeof *m);
        m->name = nm;
        m->len = (int)(q - nm);
        sl_lex_span(S, q, eol, line, col + (int)(q - p), &m->body);
        m->next = S->macros;
        S->macros = m;
    } else {
        sl_fail_at(S, line, col, "preprocessor directive '#%.*s' is not supported (#define NAME VALUE, "
                   "#version, #extension and #pragma are)", wl, w);
    }
    return eol;
}

/* A number at p: its kind (K_INT or K_FLT) and length into t. */
static void lex_number(struct sl *S, const char *p, const char *end, struct tok *t)
{
    int line = t->line, col = t->col;
    const char *q = p;
    int is_float = 0;
    if (*p == '0' && q + 1 < end && (q[1] == 'x' || q[1] == 'X'))
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
    t->k = is_float ? K_FLT : K_INT;
    t->len = (int)(q - p);
}

/* An operator at p: its length into t (K_OP). */
static void lex_operator(struct sl *S, const char *p, const char *end, struct tok *t)
{
    unsigned char ch = (unsigned char)*p;
    t->k = K_OP;
    for (int i = 0; ops2[i]; ++i)
        if (p + 1 < end && p[0] == ops2[i][0] && p[1] == ops2[i][1])
            t->len = 2;
    if (!t->len && strchr(ops1, ch) && ch)
        t->len = 1;
    if (!t->len) {
        if (ch == '&') {
            /* after a value it is a bitwise and (an OpenCL C expression may have one); anywhere
               else it takes an address, refused for good */
            const struct tok *prev = S->toks.n > 0 ? &S->toks.v[S->toks.n - 1] : NULL;
            int after_value = prev && (prev->k == K_ID || prev->k == K_INT || prev->k == K_FLT ||
                                       sl_tok_is(prev, ")") || sl_tok_is(prev, "]"));
            if (!after_value)
                S->shader_only = 1;
            sl_fail_at(S, t->line, t->col, "'&' takes an address (or is a bitwise and): pointers and bit "
                       "operations are not accepted in a model");
        }
        if (ch == '"' || ch == '\'')
            sl_fail_at(S, t->line, t->col, "a string or character literal: a model has none (and calls only the "
                       "math built-ins and its own functions)");
        if (ch < 0x20 || ch > 0x7e)
            sl_fail_at(S, t->line, t->col, "character 0x%02x is not allowed in a model", ch);
        sl_fail_at(S, t->line, t->col, "'%c' is not an operator of a model (+ - * / %% comparisons && || ! ?: "
                   "= and the compound assignments are)", ch);
    }
}

/* Tokens of [p, end): into the program (macros expanded), or into a macro's body. */
void sl_lex_span(struct sl *S, const char *p, const char *end, int line, int col, struct tokv *into)
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
            skip_block_comment(S, &p, end, &line, &col);
            continue;
        }
        if (ch == '#') {
            if (!at_line_start || into)
                sl_fail_at(S, line, col, "'#' is only allowed at the start of a line (a preprocessor directive)");
            const char *eol = lex_directive(S, p, end, line, col);
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
            /* before its operand's string is read as one */
            if ((t.len == 3 && strncmp(p, "asm", 3) == 0) || (t.len == 5 && strncmp(p, "__asm", 5) == 0) ||
                (t.len == 7 && strncmp(p, "__asm__", 7) == 0))
                sl_fail_at(S, line, S->pp_active ? sl_pp_column(S, &t, line) : col,
                           "inline assembly is not accepted in a model");
        } else if (isdigit(ch) || (ch == '.' && p + 1 < end && isdigit((unsigned char)p[1]))) {
            lex_number(S, p, end, &t);
        } else {
            lex_operator(S, p, end, &t);
        }
        if (S->pp_active && !into) {
            /* the preprocessor's output: the user's column and line (#line as written) */
            t.col = sl_pp_column(S, &t, line);
            t.line = line + S->line_delta;
        }
        if (into)
            sl_tokv_push(S, into, t);
        else
            push_expanded(S, t, 0);
        p += t.len;
        col += t.len;
    }
}
