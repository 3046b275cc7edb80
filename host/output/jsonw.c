/* jsonw.c - streaming JSON writer (see jsonw.h). */
#include "jsonw.h"
#include "outdir.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void jw_init(struct jw *w) { memset(w, 0, sizeof *w); }

void jw_free(struct jw *w)
{
    md_free(&w->out);
    memset(w, 0, sizeof *w);
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
        md_append(&w->out, plain && w->is_array[d] ? ", " : ",", plain && w->is_array[d] ? 2 : 1);
    if (d > 0 && !(plain && w->is_array[d])) {
        w->broken[d] = 1;
        md_append(&w->out, "\n", 1);
        for (int i = 0; i < d; ++i)
            md_append(&w->out, "  ", 2);
    }
}

static void jw_sep(struct jw *w) { jw_sep_kind(w, 1); }

static void jw_open(struct jw *w, char c)
{
    jw_sep_kind(w, 0);
    md_append(&w->out, &c, 1);
    if (w->depth + 1 < JW_MAX_DEPTH) {
        ++w->depth;
        w->count[w->depth] = 0;
        w->is_array[w->depth] = c == '[';
        w->broken[w->depth] = 0;
    } else {
        w->malformed = 1;   /* deeper than the writer tracks: its closings would not match */
    }
}

static void jw_close(struct jw *w, char c)
{
    int had_lines = w->broken[w->depth];
    if (w->depth > 0 && w->is_array[w->depth] == (c == ']'))
        --w->depth;
    else
        w->malformed = 1;   /* a closing with nothing open, or of the other kind */
    if (had_lines) {
        md_append(&w->out, "\n", 1);
        for (int i = 0; i < w->depth; ++i)
            md_append(&w->out, "  ", 2);
    }
    md_append(&w->out, &c, 1);
}

void jw_obj_begin(struct jw *w) { jw_open(w, '{'); }
void jw_obj_end(struct jw *w) { jw_close(w, '}'); }
void jw_arr_begin(struct jw *w) { jw_open(w, '['); }
void jw_arr_end(struct jw *w) { jw_close(w, ']'); }

static void jw_quoted(struct jw *w, const char *s)
{
    md_append(&w->out, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
        switch (*p) {
        case '"': md_append(&w->out, "\\\"", 2); break;
        case '\\': md_append(&w->out, "\\\\", 2); break;
        case '\n': md_append(&w->out, "\\n", 2); break;
        case '\r': md_append(&w->out, "\\r", 2); break;
        case '\t': md_append(&w->out, "\\t", 2); break;
        default:
            if (*p < 0x20)
                md_printf(&w->out, "\\u%04x", *p);
            else
                md_append(&w->out, (const char *)p, 1);
        }
    }
    md_append(&w->out, "\"", 1);
}

void jw_key(struct jw *w, const char *key)
{
    jw_sep_kind(w, 0);
    jw_quoted(w, key);
    md_append(&w->out, ": ", 2);
    w->after_key = 1;
}

void jw_str(struct jw *w, const char *s)
{
    jw_sep(w);
    if (s)
        jw_quoted(w, s);
    else
        md_append(&w->out, "null", 4);
}

void jw_numf(struct jw *w, double v, int sig)
{
    jw_sep(w);
    if (!isfinite(v))
        md_append(&w->out, "null", 4);
    else
        md_printf(&w->out, "%.*g", sig, v);
}

void jw_num(struct jw *w, double v) { jw_numf(w, v, 17); }

void jw_int(struct jw *w, long long v)
{
    jw_sep(w);
    md_printf(&w->out, "%lld", v);
}

void jw_bool(struct jw *w, int v)
{
    jw_sep(w);
    md_append(&w->out, v ? "true" : "false", v ? 4 : 5);
}

void jw_null(struct jw *w)
{
    jw_sep(w);
    md_append(&w->out, "null", 4);
}

void jw_kv_str(struct jw *w, const char *key, const char *s) { jw_key(w, key); jw_str(w, s); }
void jw_kv_num(struct jw *w, const char *key, double v) { jw_key(w, key); jw_num(w, v); }
void jw_kv_int(struct jw *w, const char *key, long long v) { jw_key(w, key); jw_int(w, v); }
void jw_kv_bool(struct jw *w, const char *key, int v) { jw_key(w, key); jw_bool(w, v); }
void jw_kv_obj(struct jw *w, const char *key) { jw_key(w, key); jw_obj_begin(w); }
void jw_kv_arr(struct jw *w, const char *key) { jw_key(w, key); jw_arr_begin(w); }

void jw_kv_nums(struct jw *w, const char *key, const double *v, size_t count)
{
    jw_kv_arr(w, key);
    for (size_t i = 0; i < count; ++i)
        jw_num(w, v[i]);
    jw_arr_end(w);
}

void jw_kv_texts(struct jw *w, const char *key, const char *const rows[][2], size_t count)
{
    jw_kv_obj(w, key);
    for (size_t i = 0; i < count; ++i)
        jw_kv_str(w, rows[i][0], rows[i][1]);
    jw_obj_end(w);
}

/* Appends the closing newline and checks the document: 0, or -1 with a message naming `name`
 * (the newline taken off again). */
static int jw_finish(struct jw *w, const char *name, char *err, size_t errlen)
{
    md_append(&w->out, "\n", 1);
    /* Checked after the newline: its own append may be the one that runs out of memory. */
    if (w->out.failed) {
        snprintf(err, errlen, "%s: out of memory while formatting JSON", name);
        return -1;
    }
    /* a writer's bug never reaches the disk as a truncated or mismatched document */
    if (w->malformed || w->depth != 0 || w->after_key) {
        w->out.len--;
        w->out.s[w->out.len] = '\0';
        snprintf(err, errlen, "%s: not written: the JSON document is unbalanced (%d containers left open%s)", name,
                 w->depth, w->malformed ? ", a container closed that was not open" : "");
        return -1;
    }
    return 0;
}

int jw_write_file(struct jw *w, const char *path, char *err, size_t errlen)
{
    if (jw_finish(w, path, err, errlen)) return -1;
    int rc = write_file_atomic(path, w->out.s, w->out.len, err, errlen);
    w->out.len--; /* the newline is not part of the document */
    w->out.s[w->out.len] = '\0';
    return rc;
}

int jw_write_stream(struct jw *w, FILE *f, const char *name, char *err, size_t errlen)
{
    if (jw_finish(w, name, err, errlen)) return -1;
    int rc = 0;
    if (fwrite(w->out.s, 1, w->out.len, f) != w->out.len || fflush(f) != 0) {
        snprintf(err, errlen, "%s: writing failed: %s", name, strerror(errno));
        rc = -1;
    }
    w->out.len--;
    w->out.s[w->out.len] = '\0';
    return rc;
}

int jw_write_file_free(struct jw *w, const char *path, char *err, size_t errlen)
{
    int rc = jw_write_file(w, path, err, errlen);
    jw_free(w);
    return rc;
}

void jw_kv_fields(struct jw *w, const void *record, const struct jw_field *fields, size_t count)
{
    const char *base = record;
    for (size_t i = 0; i < count; i++) {
        const struct jw_field *f = &fields[i];
        const char *at = base + f->offset;
        switch (f->kind) {
        case JWF_TEXT: jw_kv_str(w, f->key, at); break;
        case JWF_TEXTP: jw_kv_str(w, f->key, *(const char *const *)(const void *)at); break;
        case JWF_NUM: jw_kv_num(w, f->key, *(const double *)(const void *)at); break;
        case JWF_INT: jw_kv_int(w, f->key, *(const int *)(const void *)at); break;
        case JWF_UINT: jw_kv_int(w, f->key, *(const unsigned *)(const void *)at); break;
        case JWF_LONG: jw_kv_int(w, f->key, *(const long *)(const void *)at); break;
        case JWF_LLONG: jw_kv_int(w, f->key, *(const long long *)(const void *)at); break;
        case JWF_BOOL: jw_kv_bool(w, f->key, *(const int *)(const void *)at); break;
        }
    }
}

void jw_kv_records(struct jw *w, const char *key, const void *records, size_t count, size_t stride,
                   const struct jw_field *fields, size_t nfields)
{
    jw_kv_arr(w, key);
    for (size_t i = 0; i < count; i++) {
        jw_obj_begin(w);
        jw_kv_fields(w, (const char *)records + i * stride, fields, nfields);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}
