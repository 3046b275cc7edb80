/* shaderlang_error.c - the shader-language translator (shaderlang.c): failures (a message with its line and column, longjmp to the entry point) and the arena. */
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

void sl_vformat_at(char *err, size_t errlen, const char *origin, int line, int col, const char *fmt, va_list ap)
{
    char msg[400];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (line > 0 && col >= 0)
        snprintf(err, errlen, "%s:%d:%d: %s", origin, line, col, msg);
    else if (line > 0)
        snprintf(err, errlen, "%s:%d: %s", origin, line, msg);
    else
        snprintf(err, errlen, "%s: %s", origin, msg);
}

void sl_fail_at(struct sl *S, int line, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sl_vformat_at(S->err, S->errlen, S->origin, line, col, fmt, ap);
    va_end(ap);
    longjmp(S->fail, 1);
}

void *sl_arena_alloc(struct sl *S, size_t n)
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

const char *sl_sfmt(struct sl *S, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = sl_arena_alloc(S, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

const char *sl_tok_str(struct sl *S, const struct tok *t) { return sl_sfmt(S, "%.*s", t->len, t->p); }

int sl_tok_is(const struct tok *t, const char *s)
{
    return (t->k == K_ID || t->k == K_OP) && (int)strlen(s) == t->len && strncmp(t->p, s, (size_t)t->len) == 0;
}
