/* jsonr.c - the strict JSON reader of jsonr.h on Debian's libjansson: jansson parses, and a
 * pass over the accepted text gives every value its line and column; every error names
 * file:line:col. */
#include "jsonr.h"
#include "infile.h"

#include <jansson.h>

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define JR_MAX_DEPTH 64
#define JR_MAX_FILE (256L * 1024 * 1024)

/* Jansson parses and decodes (strictly: RFC 8259, duplicate keys refused, UTF-8 checked); it
 * keeps no positions, so a second pass over the text, which jansson has accepted and which is
 * therefore well-formed, gives each value its line and column. Jansson keeps an object's
 * members in the order of the text, so the two walks meet member by member. */
struct walk {
    const char *s;
    size_t len, pos;
    int line, col;
};

static void walk_advance(struct walk *w)
{
    if (w->pos >= w->len)
        return;
    if (w->s[w->pos] == '\n') {
        w->line++;
        w->col = 1;
    } else {
        w->col++;
    }
    w->pos++;
}

static void walk_ws(struct walk *w)
{
    while (w->pos < w->len && strchr(" \t\r\n", w->s[w->pos]) && w->s[w->pos])
        walk_advance(w);
}

/* Past a string (at its opening quote), a number or a literal. */
static void walk_scalar(struct walk *w)
{
    if (w->pos < w->len && w->s[w->pos] == '"') {
        walk_advance(w);
        while (w->pos < w->len && w->s[w->pos] != '"') {
            if (w->s[w->pos] == '\\')
                walk_advance(w);
            walk_advance(w);
        }
        walk_advance(w);
        return;
    }
    while (w->pos < w->len && !strchr(" \t\r\n,]}", w->s[w->pos]))
        walk_advance(w);
}

static void free_value(struct jr_value *v)
{
    if (v->type == JR_STR) free(v->str);
    if (v->type == JR_ARR || v->type == JR_OBJ) {
        for (size_t i = 0; i < v->count; i++) {
            free_value(&v->items[i]);
            if (v->keys) free(v->keys[i]);
        }
        free(v->items);
        free(v->keys);
    }
    memset(v, 0, sizeof *v);
}

/* Copies jansson's value j into v, with the position of its text. Returns 0 or -1 (memory). */
static int build_value(struct walk *w, json_t *j, struct jr_value *v)
{
    walk_ws(w);
    v->line = w->line;
    v->col = w->col;
    switch (json_typeof(j)) {
    case JSON_OBJECT:
    case JSON_ARRAY: {
        int object = json_is_object(j);
        size_t n = object ? json_object_size(j) : json_array_size(j);
        v->type = object ? JR_OBJ : JR_ARR;
        walk_advance(w); /* { or [ */
        if (n) {
            v->items = calloc(n, sizeof *v->items);
            if (!v->items || (object && !(v->keys = calloc(n, sizeof *v->keys))))
                return -1;
        }
        void *it = object ? json_object_iter(j) : NULL;
        for (size_t i = 0; i < n; ++i) {
            json_t *item;
            walk_ws(w);
            if (object) {
                walk_scalar(w); /* the member's name */
                walk_ws(w);
                walk_advance(w); /* : */
                const char *key = json_object_iter_key(it);
                size_t klen = json_object_iter_key_len(it);
                item = json_object_iter_value(it);
                it = json_object_iter_next(j, it);
                if (!(v->keys[i] = malloc(klen + 1)))
                    return -1;
                memcpy(v->keys[i], key, klen + 1);
            } else {
                item = json_array_get(j, i);
            }
            v->count = i + 1;
            if (build_value(w, item, &v->items[i]))
                return -1;
            walk_ws(w);
            walk_advance(w); /* , or the closing bracket */
        }
        if (!n) {
            walk_ws(w);
            walk_advance(w);
        }
        return 0;
    }
    case JSON_STRING: {
        size_t n = json_string_length(j);
        v->type = JR_STR;
        walk_scalar(w);
        if (!(v->str = malloc(n + 1)))
            return -1;
        memcpy(v->str, json_string_value(j), n + 1);
        return 0;
    }
    case JSON_INTEGER:
    case JSON_REAL:
        v->type = JR_NUM;
        v->num = json_number_value(j);
        walk_scalar(w);
        return 0;
    case JSON_TRUE:
    case JSON_FALSE:
        v->type = JR_BOOL;
        v->num = json_is_true(j);
        walk_scalar(w);
        return 0;
    case JSON_NULL:
    default:
        v->type = JR_NULL;
        walk_scalar(w);
        return 0;
    }
}

/* Nesting is bounded before jansson (whose own bound is 2048) sees the text, so that the
 * walk above stays shallow. Returns the offset of the first bracket too deep, or -1. */
static long too_deep(const char *s, size_t len)
{
    int depth = 0, in_string = 0;
    for (size_t i = 0; i < len; ++i) {
        char c = s[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = 0;
        } else if (c == '"') {
            in_string = 1;
        } else if (c == '[' || c == '{') {
            if (++depth > JR_MAX_DEPTH)
                return (long)i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return -1;
}

static int where_fail(char *err, size_t errlen, const char *name, const char *text, size_t upto, const char *fmt,
                      const char *what)
{
    int line = 1, col = 1;
    for (size_t i = 0; i < upto; ++i) {
        if (text[i] == '\n') {
            line++;
            col = 1;
        } else {
            col++;
        }
    }
    snprintf(err, errlen, "%s:%d:%d: ", name, line, col);
    size_t used = strlen(err);
    snprintf(err + used, errlen - used, fmt, what);
    return 2;
}

int jr_parse_text(const char *text, size_t len, const char *name, struct jr_doc *doc, char *err, size_t errlen)
{
    memset(doc, 0, sizeof *doc);
    snprintf(doc->name, sizeof doc->name, "%s", name ? name : "(json)");
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        return where_fail(err, errlen, doc->name, text, 0, "%s", "byte order mark is not allowed");
    const char *nul = memchr(text, 0, len);
    if (nul)
        return where_fail(err, errlen, doc->name, text, (size_t)(nul - text), "%s", "NUL byte in the text");
    long deep = too_deep(text, len);
    if (deep >= 0) {
        char what[64];
        snprintf(what, sizeof what, "nesting deeper than %d", JR_MAX_DEPTH);
        return where_fail(err, errlen, doc->name, text, (size_t)deep, "%s", what);
    }
    json_error_t je;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY | JSON_DECODE_INT_AS_REAL, &je);
    if (!root) {
        /* Jansson's position is the end of the token it stopped at. A closing bracket right
         * after a comma is the commonest slip: name it. */
        size_t at = je.position > 0 ? (size_t)je.position - 1 : 0;
        int trailing = 0;
        if (at < len && (text[at] == '}' || text[at] == ']')) {
            size_t k = at;
            while (k > 0 && strchr(" \t\r\n", text[k - 1]))
                --k;
            trailing = k > 0 && text[k - 1] == ',';
        }
        /* The column of the token's start, as for every other message: jansson names the
         * token it stopped at ("... near 'NaN'") and counts the column at its end. */
        int col = je.column;
        const char *near = strstr(je.text, " near '");
        size_t tlen = near ? strlen(near + 7) : 0;
        if (tlen > 0 && near[7 + tlen - 1] == '\'' && col - (int)(tlen - 1) + 1 >= 1)
            col -= (int)(tlen - 1) - 1;
        else if (strstr(je.text, "near end of file"))
            col += 1;   /* the end itself, one past the last character read */
        /* ... and a text cut short (a truncated file) too. */
        int cut = !trailing && strncmp(je.text, "unexpected", 10) != 0 &&
                  (strstr(je.text, "near end of file") || strstr(je.text, "premature end of input"));
        snprintf(err, errlen, "%s:%d:%d: %s%s", doc->name, je.line > 0 ? je.line : 1, col > 0 ? col : 1,
                 trailing ? "trailing comma: " : cut ? "unexpected end of file: " : "", je.text);
        return 2;
    }
    struct walk w = { text, len, 0, 1, 1 };
    int bad = build_value(&w, root, &doc->root);
    json_decref(root);
    if (bad) {
        free_value(&doc->root);
        snprintf(err, errlen, "%s: out of memory", doc->name);
        return 2;
    }
    return 0;
}

int jr_parse_file(const char *path, struct jr_doc *doc, char *err, size_t errlen)
{
    return jr_parse_file_max(path, (size_t)JR_MAX_FILE, doc, err, errlen);
}

int jr_parse_file_max(const char *path, size_t max, struct jr_doc *doc, char *err, size_t errlen)
{
    memset(doc, 0, sizeof *doc);
    char *buf = NULL, why[256];
    size_t len = 0;
    /* A result file is a regular file: a FIFO or device in its place is refused, not waited on. */
    int r = infile_read(path, 0, max, &buf, &len, why, sizeof why);
    if (r == -2) {
        snprintf(err, errlen, "%s: out of memory", path);
        return 2;
    }
    if (r == -3) {
        snprintf(err, errlen, "%s: read error: %s", path, why);
        return 2;
    }
    if (r != 0) {
        int cannot_open = strncmp(why, "is ", 3) != 0;
        snprintf(err, errlen, "%s: %s%s", path, cannot_open ? "cannot open: " : "", why);
        return 2;
    }
    if (len == 0) {
        free(buf);
        snprintf(err, errlen, "%s: empty file", path);
        return 2;
    }
    int rc = jr_parse_text(buf, len, path, doc, err, errlen);
    free(buf);
    return rc;
}

void jr_free(struct jr_doc *doc)
{
    if (doc) free_value(&doc->root);
}

const struct jr_value *jr_get(const struct jr_value *obj, const char *key)
{
    if (!obj || obj->type != JR_OBJ) return NULL;
    for (size_t i = 0; i < obj->count; i++)
        if (strcmp(obj->keys[i], key) == 0) return &obj->items[i];
    return NULL;
}

const char *jr_str_or(const struct jr_value *obj, const char *key, const char *dflt)
{
    const struct jr_value *v = jr_get(obj, key);
    return v && v->type == JR_STR ? v->str : dflt;
}

double jr_num_or_nan(const struct jr_value *obj, const char *key)
{
    const struct jr_value *v = jr_get(obj, key);
    return v && v->type == JR_NUM ? v->num : NAN;
}

int jr_fail(const struct jr_doc *d, const struct jr_value *v, char *err, size_t errlen, const char *fmt, ...)
{
    char msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s:%d:%d: %s", d ? d->name : "(json)", v ? v->line : 0, v ? v->col : 0, msg);
    return 2;
}

static const char *type_name(enum jr_type t)
{
    static const char *names[] = {"null", "a boolean", "a number", "a string", "an array", "an object"};
    return names[t];
}

int jr_need(const struct jr_doc *d, const struct jr_value *obj, const char *key, enum jr_type type,
            const struct jr_value **out, char *err, size_t errlen)
{
    if (!obj || obj->type != JR_OBJ) return jr_fail(d, obj, err, errlen, "an object expected (looking for \"%s\")", key);
    const struct jr_value *v = jr_get(obj, key);
    if (!v) return jr_fail(d, obj, err, errlen, "member \"%s\" is missing", key);
    if (v->type != type && !(type == JR_NUM && v->type == JR_NULL))
        return jr_fail(d, v, err, errlen, "member \"%s\" is %s, %s expected", key, type_name(v->type), type_name(type));
    *out = v;
    return 0;
}

int jr_need_num(const struct jr_doc *d, const struct jr_value *obj, const char *key, double *out, char *err,
                size_t errlen)
{
    const struct jr_value *v;
    if (jr_need(d, obj, key, JR_NUM, &v, err, errlen)) return 2;
    *out = v->type == JR_NULL ? NAN : v->num;
    return 0;
}

int jr_need_str(const struct jr_doc *d, const struct jr_value *obj, const char *key, const char **out, char *err,
                size_t errlen)
{
    const struct jr_value *v;
    if (jr_need(d, obj, key, JR_STR, &v, err, errlen)) return 2;
    *out = v->str;
    return 0;
}

int jr_need_num_array(const struct jr_doc *d, const struct jr_value *obj, const char *key, double **out,
                      size_t *count, char *err, size_t errlen)
{
    const struct jr_value *v;
    if (jr_need(d, obj, key, JR_ARR, &v, err, errlen)) return 2;
    double *a = malloc((v->count ? v->count : 1) * sizeof *a);
    if (!a) return jr_fail(d, v, err, errlen, "out of memory");
    for (size_t i = 0; i < v->count; i++) {
        const struct jr_value *it = &v->items[i];
        if (it->type == JR_NUM) a[i] = it->num;
        else if (it->type == JR_NULL) a[i] = NAN;
        else {
            free(a);
            return jr_fail(d, it, err, errlen, "item %zu of \"%s\" is %s, a number expected", i, key, type_name(it->type));
        }
    }
    *out = a;
    *count = v->count;
    return 0;
}
