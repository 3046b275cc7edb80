/* jsonw.h - a small streaming JSON writer into a growable buffer.
 * Non-finite numbers are written as null (docs/architecture.md, habit 6): callers add a status and a
 * reason beside such a value. Arrays of plain values are written on one line, so large
 * numeric arrays stay compact; objects and nested containers get a line per item. */
#ifndef BRDF_JSONW_H
#define BRDF_JSONW_H

#include <stddef.h>
#include <stdio.h>

#include "mdbuf.h"

#define JW_MAX_DEPTH 32

struct jw {
    struct md_buf out;        /* the document so far; out.failed: out of memory */
    int depth;
    int count[JW_MAX_DEPTH];  /* items written at each depth, for commas */
    char is_array[JW_MAX_DEPTH];   /* the container at each depth is an array */
    char broken[JW_MAX_DEPTH];     /* it holds a line break (an object, or a nested container) */
    int after_key;
    int malformed;            /* a closing that matched no opening, or nesting past JW_MAX_DEPTH */
};

void jw_init(struct jw *w);
void jw_free(struct jw *w);
void jw_obj_begin(struct jw *w);
void jw_obj_end(struct jw *w);
void jw_arr_begin(struct jw *w);
void jw_arr_end(struct jw *w);
void jw_key(struct jw *w, const char *key);
void jw_str(struct jw *w, const char *s);
void jw_num(struct jw *w, double v);       /* %.17g, or null when not finite */
void jw_numf(struct jw *w, double v, int sig); /* with `sig` significant digits */
void jw_int(struct jw *w, long long v);
void jw_bool(struct jw *w, int v);
void jw_null(struct jw *w);
/* Convenience: "key": value pairs. */
void jw_kv_str(struct jw *w, const char *key, const char *s);
void jw_kv_num(struct jw *w, const char *key, double v);
void jw_kv_int(struct jw *w, const char *key, long long v);
void jw_kv_bool(struct jw *w, const char *key, int v);
/* "key": { and "key": [ , closed by jw_obj_end and jw_arr_end. */
void jw_kv_obj(struct jw *w, const char *key);
void jw_kv_arr(struct jw *w, const char *key);
/* "key": [v[0], ..., v[count-1]] with jw_num. */
void jw_kv_nums(struct jw *w, const char *key, const double *v, size_t count);
/* "key": { "name": "text", ... } from rows of { name, text }: a document's definitions, kept
 * as one table of prose beside the writer. */
void jw_kv_texts(struct jw *w, const char *key, const char *const rows[][2], size_t count);
#define JW_TEXTS(TABLE) (TABLE), (sizeof(TABLE) / sizeof((TABLE)[0]))
/* A record's members written from a table: each row names the key, the member's C type and
 * its offset, so a writer lists what a document holds instead of one call per member, and
 * the keys come out in the table's order. */
enum jw_field_kind {
    JWF_TEXT,     /* char array member */
    JWF_TEXTP,    /* const char * member (NULL: null) */
    JWF_NUM,      /* double (null when not finite) */
    JWF_INT,      /* int */
    JWF_UINT,     /* unsigned int */
    JWF_LONG,     /* long */
    JWF_LLONG,    /* long long */
    JWF_BOOL      /* int, 0 or not */
};
struct jw_field {
    const char *key;
    enum jw_field_kind kind;
    size_t offset;
};
#define JW_FIELD(KIND, TYPE, MEMBER, KEY) { (KEY), (KIND), offsetof(TYPE, MEMBER) }
#define JW_FIELDS(TABLE) (TABLE), (sizeof(TABLE) / sizeof((TABLE)[0]))
void jw_kv_fields(struct jw *w, const void *record, const struct jw_field *fields, size_t count);
/* "key": [ {fields of record 0}, {fields of record 1}, ... ] for count records stride bytes
 * apart starting at records. */
void jw_kv_records(struct jw *w, const char *key, const void *records, size_t count, size_t stride,
                   const struct jw_field *fields, size_t nfields);

/* Writes the buffer (plus a newline) atomically to path. Returns 0, or -1 with a message when out
 * of memory, when the write fails, or when the document is unbalanced (a container left open or
 * closed twice: a writer's bug, which never reaches the disk). */
int jw_write_file(struct jw *w, const char *path, char *err, size_t errlen);
/* The same checks, the document (plus a newline) written to f and flushed; name is what a
 * message calls it ("--json -"). Returns 0 or -1 with a message. */
int jw_write_stream(struct jw *w, FILE *f, const char *name, char *err, size_t errlen);
/* jw_write_file, then jw_free: the end of every writer that builds one document. */
int jw_write_file_free(struct jw *w, const char *path, char *err, size_t errlen);

#endif
