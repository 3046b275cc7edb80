/* jsonw.c - streaming JSON writer (see jsonw.h). */
#include "jsonw.h"
#include "outdir.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void jw_init(struct jw *w) { memset(w, 0, sizeof *w); }

void jw_free(struct jw *w)
{
    free(w->buf);
    memset(w, 0, sizeof *w);
}

static void jw_raw(struct jw *w, const char *s, size_t n)
{
    if (w->failed)
        return;
    if (w->len + n + 1 > w->cap) {
        size_t cap = w->cap ? w->cap : 4096;
        while (cap < w->len + n + 1)
            cap *= 2;
        char *nb = realloc(w->buf, cap);
        if (!nb) {
            w->failed = 1;
            return;
        }
        w->buf = nb;
        w->cap = cap;
    }
    memcpy(w->buf + w->len, s, n);
    w->len += n;
    w->buf[w->len] = '\0';
}

static void jw_rawf(struct jw *w, const char *fmt, ...)
{
    char tmp[64];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0)
        jw_raw(w, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

/* Comma and indentation before a value or key. A plain value inside an array stays on the
 * array's line; keys and containers start a new, indented line. */
static void jw_sep_kind(struct jw *w, int plain)
{
    if (w->after_key) {
        w->after_key = 0;
        return;
    }
    int d = w->depth;
    if (d > 0 && w->count[d]++ > 0)
        jw_raw(w, plain && w->is_array[d] ? ", " : ",", plain && w->is_array[d] ? 2 : 1);
    if (d > 0 && !(plain && w->is_array[d])) {
        w->broken[d] = 1;
        jw_raw(w, "\n", 1);
        for (int i = 0; i < d; ++i)
            jw_raw(w, "  ", 2);
    }
}

static void jw_sep(struct jw *w) { jw_sep_kind(w, 1); }

static void jw_open(struct jw *w, char c)
{
    jw_sep_kind(w, 0);
    jw_raw(w, &c, 1);
    if (w->depth + 1 < JW_MAX_DEPTH) {
        ++w->depth;
        w->count[w->depth] = 0;
        w->is_array[w->depth] = c == '[';
        w->broken[w->depth] = 0;
    }
}

static void jw_close(struct jw *w, char c)
{
    int had_lines = w->broken[w->depth];
    if (w->depth > 0)
        --w->depth;
    if (had_lines) {
        jw_raw(w, "\n", 1);
        for (int i = 0; i < w->depth; ++i)
            jw_raw(w, "  ", 2);
    }
    jw_raw(w, &c, 1);
}

void jw_obj_begin(struct jw *w) { jw_open(w, '{'); }
void jw_obj_end(struct jw *w) { jw_close(w, '}'); }
void jw_arr_begin(struct jw *w) { jw_open(w, '['); }
void jw_arr_end(struct jw *w) { jw_close(w, ']'); }

static void jw_quoted(struct jw *w, const char *s)
{
    jw_raw(w, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
        switch (*p) {
        case '"': jw_raw(w, "\\\"", 2); break;
        case '\\': jw_raw(w, "\\\\", 2); break;
        case '\n': jw_raw(w, "\\n", 2); break;
        case '\r': jw_raw(w, "\\r", 2); break;
        case '\t': jw_raw(w, "\\t", 2); break;
        default:
            if (*p < 0x20)
                jw_rawf(w, "\\u%04x", *p);
            else
                jw_raw(w, (const char *)p, 1);
        }
    }
    jw_raw(w, "\"", 1);
}

void jw_key(struct jw *w, const char *key)
{
    jw_sep_kind(w, 0);
    jw_quoted(w, key);
    jw_raw(w, ": ", 2);
    w->after_key = 1;
}

void jw_str(struct jw *w, const char *s)
{
    jw_sep(w);
    if (s)
        jw_quoted(w, s);
    else
        jw_raw(w, "null", 4);
}

void jw_numf(struct jw *w, double v, int sig)
{
    jw_sep(w);
    if (!isfinite(v))
        jw_raw(w, "null", 4);
    else
        jw_rawf(w, "%.*g", sig, v);
}

void jw_num(struct jw *w, double v) { jw_numf(w, v, 17); }

void jw_int(struct jw *w, long long v)
{
    jw_sep(w);
    jw_rawf(w, "%lld", v);
}

void jw_bool(struct jw *w, int v)
{
    jw_sep(w);
    jw_raw(w, v ? "true" : "false", v ? 4 : 5);
}

void jw_null(struct jw *w)
{
    jw_sep(w);
    jw_raw(w, "null", 4);
}

void jw_kv_str(struct jw *w, const char *key, const char *s) { jw_key(w, key); jw_str(w, s); }
void jw_kv_num(struct jw *w, const char *key, double v) { jw_key(w, key); jw_num(w, v); }
void jw_kv_int(struct jw *w, const char *key, long long v) { jw_key(w, key); jw_int(w, v); }
void jw_kv_bool(struct jw *w, const char *key, int v) { jw_key(w, key); jw_bool(w, v); }

int jw_write_file(struct jw *w, const char *path, char *err, size_t errlen)
{
    if (w->failed) {
        snprintf(err, errlen, "%s: out of memory while formatting JSON", path);
        return -1;
    }
    jw_raw(w, "\n", 1);
    int rc = write_file_atomic(path, w->buf, w->len, err, errlen);
    w->len--; /* the newline is not part of the document */
    w->buf[w->len] = '\0';
    return rc;
}
