/* jsonr.c - the strict JSON reader of jsonr.h: recursive descent over the whole text,
 * one tree of jr_value, every error with file:line:col. */
#include "jsonr.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define JR_MAX_DEPTH 64
#define JR_MAX_FILE (256L * 1024 * 1024)

struct parser {
    const char *s;
    size_t len, pos;
    int line, col;
    const char *name;
    char *err;
    size_t errlen;
    int depth;
};

static int perr(struct parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int perr(struct parser *p, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(p->err, p->errlen, "%s:%d:%d: %s", p->name, p->line, p->col, msg);
    return 2;
}

static int peek(const struct parser *p) { return p->pos < p->len ? (unsigned char)p->s[p->pos] : -1; }

static void advance(struct parser *p)
{
    if (p->pos >= p->len) return;
    if (p->s[p->pos] == '\n') {
        p->line++;
        p->col = 1;
    } else {
        p->col++;
    }
    p->pos++;
}

static void skip_ws(struct parser *p)
{
    for (;;) {
        int c = peek(p);
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') advance(p);
        else break;
    }
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

static int expect_word(struct parser *p, const char *word)
{
    size_t n = strlen(word);
    if (p->len - p->pos < n || memcmp(p->s + p->pos, word, n) != 0) return perr(p, "unexpected character '%c'", peek(p) > 31 && peek(p) < 127 ? peek(p) : '?');
    for (size_t i = 0; i < n; i++) advance(p);
    int c = peek(p);
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))
        return perr(p, "unexpected character '%c' after %s", c, word);
    return 0;
}

static int hex4(struct parser *p, unsigned *out)
{
    unsigned v = 0;
    for (int i = 0; i < 4; i++) {
        int c = peek(p);
        unsigned d;
        if (c >= '0' && c <= '9') d = (unsigned)(c - '0');
        else if (c >= 'a' && c <= 'f') d = (unsigned)(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F') d = (unsigned)(c - 'A' + 10);
        else return perr(p, "bad \\u escape: four hex digits expected");
        v = v * 16 + d;
        advance(p);
    }
    *out = v;
    return 0;
}

static void put_utf8(char *buf, size_t *n, unsigned cp)
{
    if (cp < 0x80) buf[(*n)++] = (char)cp;
    else if (cp < 0x800) {
        buf[(*n)++] = (char)(0xC0 | (cp >> 6));
        buf[(*n)++] = (char)(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        buf[(*n)++] = (char)(0xE0 | (cp >> 12));
        buf[(*n)++] = (char)(0x80 | ((cp >> 6) & 0x3F));
        buf[(*n)++] = (char)(0x80 | (cp & 0x3F));
    } else {
        buf[(*n)++] = (char)(0xF0 | (cp >> 18));
        buf[(*n)++] = (char)(0x80 | ((cp >> 12) & 0x3F));
        buf[(*n)++] = (char)(0x80 | ((cp >> 6) & 0x3F));
        buf[(*n)++] = (char)(0x80 | (cp & 0x3F));
    }
}

/* A string at the opening quote; the result is malloc'd. Escapes never make the text
 * longer than its source, so the source length bounds the buffer. */
static int parse_string(struct parser *p, char **out)
{
    int line = p->line, col = p->col; /* an unterminated string is reported where it opens */
    advance(p); /* opening quote */
    size_t start = p->pos, end = start;
    while (end < p->len && p->s[end] != '"') end += (p->s[end] == '\\') ? 2 : 1;
    char *buf = malloc(end - start + 1);
    if (!buf) return perr(p, "out of memory");
    size_t n = 0;
    for (;;) {
        int c = peek(p);
        if (c < 0) {
            free(buf);
            p->line = line, p->col = col;
            return perr(p, "unterminated string");
        }
        if (c == '"') {
            advance(p);
            break;
        }
        if (c < 0x20) {
            free(buf);
            return perr(p, "control character in a string");
        }
        if (c != '\\') {
            buf[n++] = (char)c;
            advance(p);
            continue;
        }
        advance(p);
        int e = peek(p);
        const char *simple = "\"\\/bfnrt", *value = "\"\\/\b\f\n\r\t";
        const char *k = e > 0 ? strchr(simple, e) : NULL;
        if (k && *k) {
            buf[n++] = value[k - simple];
            advance(p);
            continue;
        }
        if (e != 'u') {
            free(buf);
            return perr(p, "bad escape in a string");
        }
        advance(p);
        unsigned cp;
        if (hex4(p, &cp)) {
            free(buf);
            return 2;
        }
        if (cp >= 0xD800 && cp <= 0xDBFF) { /* a surrogate pair */
            unsigned lo;
            if (peek(p) != '\\') {
                free(buf);
                return perr(p, "lone high surrogate in a \\u escape");
            }
            advance(p);
            if (peek(p) != 'u') {
                free(buf);
                return perr(p, "lone high surrogate in a \\u escape");
            }
            advance(p);
            if (hex4(p, &lo)) {
                free(buf);
                return 2;
            }
            if (lo < 0xDC00 || lo > 0xDFFF) {
                free(buf);
                return perr(p, "bad low surrogate in a \\u escape");
            }
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
        } else if (cp >= 0xDC00 && cp <= 0xDFFF) {
            free(buf);
            return perr(p, "lone low surrogate in a \\u escape");
        }
        if (cp == 0) {
            free(buf);
            return perr(p, "\\u0000 in a string is not supported");
        }
        put_utf8(buf, &n, cp);
    }
    buf[n] = 0;
    *out = buf;
    return 0;
}

static int parse_number(struct parser *p, double *out)
{
    size_t start = p->pos;
    int line = p->line, col = p->col;
    if (peek(p) == '-') advance(p);
    if (peek(p) == '0') {
        advance(p);
        if (peek(p) >= '0' && peek(p) <= '9') return perr(p, "leading zero in a number");
    } else if (peek(p) >= '1' && peek(p) <= '9') {
        while (peek(p) >= '0' && peek(p) <= '9') advance(p);
    } else {
        return perr(p, "digit expected");
    }
    if (peek(p) == '.') {
        advance(p);
        if (!(peek(p) >= '0' && peek(p) <= '9')) return perr(p, "digit expected after '.'");
        while (peek(p) >= '0' && peek(p) <= '9') advance(p);
    }
    if (peek(p) == 'e' || peek(p) == 'E') {
        advance(p);
        if (peek(p) == '+' || peek(p) == '-') advance(p);
        if (!(peek(p) >= '0' && peek(p) <= '9')) return perr(p, "digit expected in the exponent");
        while (peek(p) >= '0' && peek(p) <= '9') advance(p);
    }
    char tmp[64];
    size_t n = p->pos - start;
    if (n >= sizeof tmp) {
        p->line = line, p->col = col;
        return perr(p, "number too long");
    }
    memcpy(tmp, p->s + start, n);
    tmp[n] = 0;
    errno = 0;
    char *end;
    double v = strtod(tmp, &end);
    if (*end || !isfinite(v) || (errno == ERANGE && fabs(v) > 1.0)) {
        p->line = line, p->col = col;
        return perr(p, "number %s out of range", tmp);
    }
    *out = v;
    return 0;
}

static int parse_value(struct parser *p, struct jr_value *v);

/* Appends an item to a container, growing it geometrically. */
static struct jr_value *push_item(struct parser *p, struct jr_value *v, size_t *cap, int with_key)
{
    if (v->count == *cap) {
        size_t nc = *cap ? *cap * 2 : 8;
        struct jr_value *items = realloc(v->items, nc * sizeof *items);
        if (!items) return NULL;
        v->items = items;
        if (with_key) {
            char **keys = realloc(v->keys, nc * sizeof *keys);
            if (!keys) return NULL;
            v->keys = keys;
        }
        *cap = nc;
    }
    (void)p;
    struct jr_value *it = &v->items[v->count];
    memset(it, 0, sizeof *it);
    return it;
}

static int parse_container(struct parser *p, struct jr_value *v, int object)
{
    char close = object ? '}' : ']';
    v->type = object ? JR_OBJ : JR_ARR;
    if (++p->depth > JR_MAX_DEPTH) return perr(p, "nesting deeper than %d", JR_MAX_DEPTH);
    advance(p);
    skip_ws(p);
    size_t cap = 0;
    if (peek(p) == close) {
        advance(p);
        p->depth--;
        return 0;
    }
    for (;;) {
        skip_ws(p);
        char *key = NULL;
        if (object) {
            if (peek(p) != '"') return perr(p, "member name (a string) expected");
            int kl = p->line, kc = p->col;
            if (parse_string(p, &key)) return 2;
            for (size_t i = 0; i < v->count; i++)
                if (strcmp(v->keys[i], key) == 0) {
                    p->line = kl, p->col = kc;
                    int rc = perr(p, "duplicate member \"%s\"", key);
                    free(key);
                    return rc;
                }
            skip_ws(p);
            if (peek(p) != ':') {
                free(key);
                return perr(p, "':' expected after a member name");
            }
            advance(p);
            skip_ws(p);
        }
        struct jr_value *it = push_item(p, v, &cap, object);
        if (!it) {
            free(key);
            return perr(p, "out of memory");
        }
        if (object) v->keys[v->count] = key;
        v->count++;
        if (parse_value(p, it)) return 2;
        skip_ws(p);
        int c = peek(p);
        if (c == ',') {
            advance(p);
            skip_ws(p);
            if (peek(p) == close) return perr(p, "trailing comma");
            continue;
        }
        if (c == close) {
            advance(p);
            break;
        }
        return perr(p, object ? "',' or '}' expected" : "',' or ']' expected");
    }
    p->depth--;
    return 0;
}

static int parse_value(struct parser *p, struct jr_value *v)
{
    skip_ws(p);
    v->line = p->line;
    v->col = p->col;
    int c = peek(p);
    switch (c) {
    case -1: return perr(p, "unexpected end of file");
    case '{': return parse_container(p, v, 1);
    case '[': return parse_container(p, v, 0);
    case '"': v->type = JR_STR; return parse_string(p, &v->str);
    case 't': v->type = JR_BOOL; v->num = 1; return expect_word(p, "true");
    case 'f': v->type = JR_BOOL; v->num = 0; return expect_word(p, "false");
    case 'n': v->type = JR_NULL; return expect_word(p, "null");
    default:
        if (c == '-' || (c >= '0' && c <= '9')) {
            v->type = JR_NUM;
            return parse_number(p, &v->num);
        }
        return perr(p, "unexpected character '%c'", c > 31 && c < 127 ? c : '?');
    }
}

int jr_parse_text(const char *text, size_t len, const char *name, struct jr_doc *doc, char *err, size_t errlen)
{
    memset(doc, 0, sizeof *doc);
    snprintf(doc->name, sizeof doc->name, "%s", name ? name : "(json)");
    struct parser p = {text, len, 0, 1, 1, doc->name, err, errlen, 0};
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) return perr(&p, "byte order mark is not allowed");
    if (memchr(text, 0, len)) return perr(&p, "NUL byte in the text");
    if (parse_value(&p, &doc->root)) {
        free_value(&doc->root);
        return 2;
    }
    skip_ws(&p);
    if (p.pos != p.len) {
        free_value(&doc->root);
        return perr(&p, "text after the JSON value");
    }
    return 0;
}

int jr_parse_file(const char *path, struct jr_doc *doc, char *err, size_t errlen)
{
    memset(doc, 0, sizeof *doc);
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return 2;
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len == cap) {
            cap = cap ? cap * 2 : 65536;
            if ((long)cap > JR_MAX_FILE + 1) {
                fclose(f);
                free(buf);
                snprintf(err, errlen, "%s: larger than %ld bytes", path, JR_MAX_FILE);
                return 2;
            }
            char *nb = realloc(buf, cap);
            if (!nb) {
                fclose(f);
                free(buf);
                snprintf(err, errlen, "%s: out of memory", path);
                return 2;
            }
            buf = nb;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        snprintf(err, errlen, "%s: read error", path);
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
